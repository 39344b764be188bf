"""`isorock bench`: work-precision for every engine on the same scenarios.

For each engine a ladder of settings (analytic: tolerances 1e-4 to 1e-10, reference
path and compiled kernel; MuJoCo: timesteps 2e-3 to 1e-4 with contact parameters
tied to the timestep; PyBullet: 1/500 to 1/10000 s), or for ENGINE:PRESET that preset
alone (rows of their own, labelled ENGINE:PRESET), runs on each scenario (free
rocking; a pulse; Kobe, first 40 s, when the shared records are there). Errors are
taken against a tight analytic reference (rtol 1e-12): effective β error per impact
against the closed form, θmax/α error, and the θ/α history error up to the agreement
horizon. Wall times are medians of repeats measured in this one run.
"""
from __future__ import annotations

import math
import statistics
import sys
import time

import numpy as np

from ...analytic import limits, paper_system
from ...analytic.engine_protocol import declare_facet
from ...analytic.errors import InputError
from ...analytic.fast import compare_on_grid, simulate_fast
from ...analytic.hybrid import AnalyticSettings, simulate as reference_simulate
from ...analytic.motion import load_motion
from ..core.compare import compare
from ..core.engines import campaign_engines, canonical, get_engine, resolve, settings_used
from ..core.scenarios import KOBE, Scenario, bench_scenarios
from ..core.tolerances import has_tolerance, limit, tolerance

#: the reference path's settings the bench measures errors against (tighter than the
#: engine's defaults); core.engines.REFERENCE is the reference engine's name
REFERENCE_SETTINGS = AnalyticSettings(rtol=1e-12, atol=1e-14)
N_BETA = 4  # impacts whose effective β error is reported
#: The speed goals (issue 19), judged on Kobe 40 s (the paper's block, isolated and fixed):
#: engine → (one run alone, a batch of BATCH_RUNS on BATCH_THREADS threads or None), sim s
#: per wall s; and the β error on free rocking at which the speed counts.
SPEED_GOALS = {"mujoco": (limit("bench_mujoco_speed_alone"), limit("bench_mujoco_speed")),
               "bullet": (limit("bench_bullet_speed"), None)}
BATCH_RUNS, BATCH_THREADS = 16, 2
#: The preset each goal engine keeps its former default under (fixed in seconds), run beside it.
FORMER = "absolute"
#: Runs shorter than this (s) are repeated FAST_REPEATS times: their medians need more samples.
FAST_RUN = 0.1
FAST_REPEATS = 5

#: the parts of an engine bench uses (engine_protocol.Facet)
LADDER = declare_facet("ladder", "isorock bench", "(quick) → [(label, Settings)], cheapest first: "
                       "the engine's work-precision ladder")
STEP_COST = declare_facet("step_cost", "isorock bench, scorecard", "(system, settings) → the CPU time (s) of one "
                          "physics step of the engine's scene, the block at rest, no Python between steps: the "
                          "limit of its speed")


def ladder(engine: str, quick: bool) -> list[tuple[str, object]]:
    """(label, settings) from cheapest to most accurate: the engine's own ladder; for
    ENGINE:PRESET the preset alone (a row of its own, labelled by it)."""
    name, _, preset = engine.partition(":")
    if preset:
        return [(preset, resolve(engine)[1])]
    spec = get_engine(name).spec
    own = LADDER.of(spec)
    return own(quick) if own else [("default", spec.settings())]


def measure(engine, label, settings, sc: Scenario, ref, repeats: int) -> dict:
    """One (engine or ENGINE:PRESET, setting) on one scenario; the row's engine is the label."""
    run = get_engine(engine.partition(":")[0]).simulate
    motion = sc.ground_motion()
    kwargs = dict(settings=settings, duration=sc.duration, theta0=sc.theta0, budget_s=limits.RUN_BUDGET_S)
    walls, loops, traj = [], [], None
    k = 0
    while k < repeats or (k < FAST_REPEATS and statistics.median(walls) < FAST_RUN):
        start = time.perf_counter()
        try:
            traj = run(sc.system, motion, **kwargs)
        except limits.BudgetExceeded as e:  # a rung too slow to finish: a row that says so, no figures
            return _stopped_row(engine, label, sc, str(e))
        walls.append(time.perf_counter() - start)
        loops.append(traj.runtime_s)
        k += 1
    wall = statistics.median(walls)
    loop = statistics.median(loops)
    c = compare(traj, ref)
    berr = [abs(e) for e in c.beta_errors[:N_BETA] if math.isfinite(e)]
    # whole call (building the scene, measuring impacts) and the engine's own loop
    # (Trajectory.runtime_s): fixed costs weigh on short runs, so both are reported
    return dict(engine=engine, setting=label, scenario=sc.name, wall_s=wall, loop_s=loop,
                sim_per_wall=sc.duration / wall if wall > 0 else math.inf,
                sim_per_loop=sc.duration / loop if loop > 0 else math.inf,
                wall_per_sim=wall / sc.duration,
                beta_error_max=max(berr) if berr else None,
                beta_error_median=float(np.median(berr)) if berr else None,
                theta_max_error=abs(c.theta_max_diff), history_rms=c.theta_rms_error,
                horizon=c.horizon, parted=c.parted, impacts=c.impacts, impacts_ref=c.impacts_ref,
                overturn_agree=c.overturn_agree)


def bench_engines(engines=None) -> list[str]:
    """The series to bench, each once: those asked for (default: the engines fast enough
    for grids) that can be imported here, an engine asked for under its former name too
    (analytic-fast) one series with it."""
    engines = list(dict.fromkeys(canonical(e) for e in (engines or campaign_engines())))
    return [e for e in engines if _importable(e.partition(":")[0])]


def _stopped_row(engine, label, sc: Scenario, why: str) -> dict:
    """A setting stopped at its run budget: neither its speed nor its errors are known."""
    nan = math.nan
    return dict(engine=engine, setting=label, scenario=sc.name, wall_s=nan, loop_s=nan, sim_per_wall=nan,
                sim_per_loop=nan, wall_per_sim=nan, beta_error_max=None, beta_error_median=None,
                theta_max_error=nan, history_rms=nan, horizon=nan, parted=None, impacts=None, impacts_ref=None,
                overturn_agree=None, stopped=why)


def run_bench(*, quick=False, engines=None, progress=True) -> tuple[list[dict], dict]:
    engines = bench_engines(engines)
    rows = []
    for sc in bench_scenarios(quick):
        motion = sc.ground_motion()
        ref = reference_simulate(sc.system, motion, settings=REFERENCE_SETTINGS, duration=sc.duration, theta0=sc.theta0)
        for engine in engines:
            # once outside the timing: a compiled kernel loads (or compiles) on its first call
            get_engine(engine.partition(":")[0]).simulate(sc.system, motion, duration=min(sc.duration, 1.0), theta0=sc.theta0)
            for label, settings in ladder(engine, quick):
                row = measure(engine, label, settings, sc, ref, 1 if quick else 3)
                rows.append(row)
                if progress and row.get("stopped"):
                    print(f"  {sc.name:13s} {engine:22s} {label:14s} {row['stopped']}", file=sys.stderr, flush=True)
                elif progress:
                    print(f"  {sc.name:13s} {engine:22s} {label:14s} {row['sim_per_wall']:10.3g} sim s/wall s "
                          f"({row['sim_per_loop']:.3g} in the loop)  "
                          f"β err {_pct(row['beta_error_max']):>8s}  θmax err {row['theta_max_error']:.2e}",
                          file=sys.stderr, flush=True)
    extra = {"solve_ivp_ratio": speed_ratio(quick)} if _fast_available() else {}
    extra["speed_goals"] = speed_goals(engines, repeats=1 if quick else 3, progress=progress)
    return rows, extra


def speed_goals(engines=None, *, repeats: int = 3, progress=True, labels=None) -> list[dict]:
    """Issue 19's speed goals, measured side by side in this run: for each goal engine asked
    for (SPEED_GOALS), its default and its former default (preset FORMER) on Kobe 40 s, the
    paper's block, isolated and fixed: one run alone (medians of `repeats` of the wall and
    CPU time of the whole call), θmax/α against the analytic model's with the validation
    tolerance, a batch of BATCH_RUNS (half isolated, half fixed) through the registry's
    simulate_many on BATCH_THREADS threads, and the engine's step cost (its STEP_COST facet:
    one physics step of the scene in C, the block at rest) as the limit each speed is a
    fraction of. Rows: one per (label, base), the batch on the isolated row.

    `labels`: measure exactly these ENGINE:PRESET labels instead, of any engine (the
    scorecard's rows): the batch where the engine has a batch path (its simulate_many facet;
    None otherwise, as it would only run them one by one), the step's limit where it has a
    step cost, θ judged where the table has its theta_max_diff tolerance (None otherwise)."""
    if not KOBE.is_file():
        return []
    if labels is None:
        names = [n for n in SPEED_GOALS if _importable(n)
                 and (engines is None or any(e.partition(":")[0] == n for e in engines))]
        chosen = [f"{n}:{p}" for n in names for p in ("default", FORMER) if p in get_engine(n).spec.presets]
    else:
        chosen = list(labels)
    motion = load_motion(str(KOBE))
    bases = {"isolated": paper_system(), "fixed": paper_system(fixed_base=True)}
    ref = {b: get_engine("analytic").simulate(s, motion, duration=40.0).theta_max_over_alpha for b, s in bases.items()}
    rows = []
    for label in chosen:
        name = label.partition(":")[0]
        engine = get_engine(name)
        settings = resolve(label)[1]
        engine.simulate(bases["fixed"], motion, settings=settings, duration=1.0)  # loaded outside the clock
        batch = None
        if (SPEED_GOALS[name][1] is not None if labels is None
                else engine.has_batch):
            runs = [(bases[b], motion, 40.0, 0.0) for b in ("isolated", "fixed") for _ in range(BATCH_RUNS // 2)]
            start = time.perf_counter()
            out = engine.simulate_many(runs, settings=settings, threads=BATCH_THREADS, effective_beta=False,
                                       budget_s=limits.RUN_BUDGET_S)
            wall = time.perf_counter() - start
            # simulated seconds as run: a block that overturned and lies on its side stops early
            batch = (None if any(isinstance(x, Exception) for x in out)
                     else sum(float(x.t[-1]) for x in out) / wall)
        for base, system in bases.items():
            walls, cpus, mapped, traj = [], [], [], None
            try:
                for _ in range(repeats):
                    # the run as a campaign's row makes it (impacts counted, not mapped to β) ...
                    w, c = time.perf_counter(), time.process_time()
                    traj = engine.simulate(system, motion, settings=settings, duration=40.0,
                                           budget_s=limits.RUN_BUDGET_S, effective_beta=False)
                    walls.append(time.perf_counter() - w)
                    cpus.append(time.process_time() - c)
                    # ... and with every counted impact mapped to its effective β (a report's run)
                    w = time.perf_counter()
                    traj = engine.simulate(system, motion, settings=settings, duration=40.0,
                                           budget_s=limits.RUN_BUDGET_S)
                    mapped.append(time.perf_counter() - w)
            except limits.BudgetExceeded as e:  # as a ladder's rung: said, no speed claimed, the bench goes on
                if progress:
                    print(f"  kobe-40s {base:8s} {label:16s} {e}", file=sys.stderr, flush=True)
                continue
            used = settings_used(settings, system, 40.0)
            step_cost = STEP_COST.of(engine.spec)
            cost = step_cost(system, settings) if step_cost else None
            timestep = getattr(used, "timestep", None)  # an event-driven engine (analytic) has none
            limit_cpu = timestep / cost if cost and timestep else None
            simulated = float(traj.t[-1])  # a run that overturned and lies on its side stops early
            sim_cpu = simulated / statistics.median(cpus)
            diff = traj.theta_max_over_alpha - ref[base]
            rows.append(dict(
                engine=label, base=base, timestep=timestep, simulated_s=simulated,
                sim_per_wall=simulated / statistics.median(walls),
                sim_per_wall_mapped=simulated / statistics.median(mapped),
                sim_per_cpu=sim_cpu, theta_max_over_alpha=traj.theta_max_over_alpha,
                reference_theta_max_over_alpha=ref[base], theta_max_diff=diff,
                theta_ok=(abs(diff) <= tolerance(name, "theta_max_diff").limit or (traj.overturned and ref[base] > 1))
                if has_tolerance(name, "theta_max_diff") else None,
                overturned=traj.overturned, step_us=None if cost is None else cost * 1e6,
                limit_sim_per_cpu=limit_cpu, fraction_of_limit=None if not limit_cpu else sim_cpu / limit_cpu,
                batch_sim_per_wall=batch if base == "isolated" else None))
            if progress:
                r = rows[-1]
                print(f"  kobe-40s {base:8s} {label:16s} {r['sim_per_wall']:8.3g} sim s/wall s alone, "
                      f"{r['sim_per_cpu']:.3g} per CPU s ({_times(r['fraction_of_limit'])} the step's limit)"
                      + (f", batch of {BATCH_RUNS}: {batch:.3g}" if batch and base == "isolated" else ""),
                      file=sys.stderr, flush=True)
    return rows


def goal_lines(goal_rows: list[dict]) -> list[str]:
    """The speed goals' table and verdicts (bench.md)."""
    if not goal_rows:
        return []
    lines = ["## Speed goals (issue 19): Kobe 40 s, the paper's block", "",
             "One run alone: medians of the whole call's wall and CPU time, the run as a campaign makes it "
             "(impacts located and counted, not mapped to effective β), and beside it with every counted "
             "impact mapped (`validate.core.measure.effective_impacts`, the same for every engine); batch: "
             f"{BATCH_RUNS} runs (half isolated, half fixed) on {BATCH_THREADS} threads; the step's limit: "
             "one physics step of the scene in C with the block at rest (its step_cost facet), "
             "timestep / its CPU time, and each run's speed per CPU s as a multiple of it (above 1×: phased "
             "stepping skips the scene where the block rests). Simulated s: as run (a block that overturned "
             "and lies on its side stops early). θmax/α against the analytic model's, within the validation "
             "tolerance (or both overturned).", "",
             "| engine | base | step (ms) | sim s / wall s, alone | per CPU s | alone, β mapped | step's cost (µs) | step's limit (sim s / CPU s) "
             "| speed per CPU s / the limit | batch, sim s / wall s | θmax/α (analytic) | θ within tolerance |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    def num(x, fmt=".3g"):
        return "—" if x is None else format(x, fmt)
    for r in goal_rows:
        lines.append(f"| {r['engine']} | {r['base']} | {num(None if r['timestep'] is None else 1000 * r['timestep'])} | {num(r['sim_per_wall'])} | "
                     f"{num(r['sim_per_cpu'])} | {num(r.get('sim_per_wall_mapped'))} | {num(r['step_us'], '.2f')} | {num(r['limit_sim_per_cpu'])} | "
                     f"{_times(r['fraction_of_limit'])} | {num(r['batch_sim_per_wall'])} | "
                     f"{r['theta_max_over_alpha']:.4g} ({r['reference_theta_max_over_alpha']:.4g}) | "
                     f"{'yes' if r['theta_ok'] else 'no'} |")
    lines.append("")
    for name, (alone, batch) in SPEED_GOALS.items():
        mine = [r for r in goal_rows if r["engine"] == f"{name}:default"]
        if not mine:
            continue
        worst = min(r["sim_per_wall"] for r in mine)
        ok = all(r["theta_ok"] for r in mine)
        text = f"- {name}: one run alone ≥ {alone:g} sim s / wall s on both bases: " + (
            "met" if worst >= alone and ok else f"not met ({worst:.3g}{'' if ok else '; θmax/α outside tolerance'})")
        if batch is not None:
            got = next((r["batch_sim_per_wall"] for r in mine if r["batch_sim_per_wall"] is not None), None)
            text += f"; a batch of {BATCH_RUNS} ≥ {batch:g}: " + (
                "not run" if got is None else "met" if got >= batch else f"not met ({got:.3g})")
        lines.append(text)
    return lines


def _importable(engine: str) -> bool:
    try:
        get_engine(engine)
        return True
    except ImportError:
        return False


def _fast_available() -> bool:
    return _importable("analytic")


def speed_ratio(quick: bool) -> dict | None:
    """The compiled kernel against solve_ivp (DOP853 with events) at the same tolerance,
    side by side in this run, on the Kobe scenario."""
    kobe = next((sc for sc in bench_scenarios(quick) if sc.name == "kobe-40s"), None)
    if kobe is None:
        return None
    return against_solve_ivp(kobe.system, kobe.ground_motion(), duration=kobe.duration, repeats=5 if quick else 20)


def against_solve_ivp(system, motion, *, duration: float = 40.0, repeats: int = 21, reference_repeats: int = 3,
                      settings=None) -> dict:
    """Time the compiled engine (`analytic.fast.simulate_fast`) and the reference
    (`analytic.hybrid.simulate`: SciPy solve_ivp, DOP853 with events, the same rtol/atol/
    max_step) on one case, side by side in this process, on one core.

    Returns a dict of seconds (medians after a warm-up call): fast_s (the whole run,
    Trajectory included), reference_s, ratio = reference_s / fast_s, first_call_s (this
    process's first call: loading the compiled kernel), max_abs_dtheta (rad, over the
    common output grid) and both runs' θmax/α and impact counts."""
    settings = settings or AnalyticSettings()
    if not (isinstance(repeats, int) and repeats >= 1 and isinstance(reference_repeats, int) and reference_repeats >= 1):
        raise InputError(f"repeats = {(repeats, reference_repeats)!r}: must be positive whole numbers")

    def timed(run, n):
        out, seconds = None, []
        for _ in range(n):
            start = time.perf_counter()
            out = run()
            seconds.append(time.perf_counter() - start)
        return out, seconds
    _, first = timed(lambda: simulate_fast(system, motion, settings=settings, duration=duration), 1)
    fast, fast_t = timed(lambda: simulate_fast(system, motion, settings=settings, duration=duration), repeats)
    ref, ref_t = timed(lambda: reference_simulate(system, motion, settings=settings, duration=duration),
                       reference_repeats)
    fast_s, ref_s = statistics.median(fast_t), statistics.median(ref_t)
    return {
        "case": f"{motion.name if motion else 'none'}, duration {duration:g} s",
        "repeats": repeats, "reference_repeats": reference_repeats,
        "first_call_s": first[0], "fast_s": fast_s, "fast_min_s": min(fast_t), "reference_s": ref_s,
        "ratio": ref_s / fast_s, "max_abs_dtheta": compare_on_grid(fast, ref, settings.output_dt),
        "theta_max_over_alpha": fast.theta_max_over_alpha,
        "reference_theta_max_over_alpha": ref.theta_max_over_alpha,
        "impacts": fast.impact_count, "reference_impacts": ref.impact_count,
    }


def fastest(rows, engine, level) -> dict | None:
    """The fastest setting of an engine whose β error on the free-rocking scenario stays
    within `level` (and whose other scenarios use the same setting)."""
    ok = [r for r in rows if r["engine"] == engine and r["scenario"] == "free-rocking"
          and r["beta_error_max"] is not None and r["beta_error_max"] <= level]
    return max(ok, key=lambda r: r["sim_per_wall"]) if ok else None


def _pct(x):
    return "—" if x is None else f"{100 * x:.3f}%"


def _times(x):
    """A speed as a multiple of a limit, to 3 figures (11.6×, not 1157.663%)."""
    return "—" if x is None else f"{x:.3g}×"


COLUMNS = ("engine", "setting", "scenario", "sim_per_wall", "sim_per_loop", "wall_s", "loop_s", "beta_error_max", "beta_error_median",
           "theta_max_error", "history_rms", "horizon", "impacts", "impacts_ref")


def markdown(rows, extra) -> str:
    lines = ["# isorock bench: work-precision", "",
             "Errors against a tight analytic reference (solve_ivp DOP853, rtol 1e-12). β errors: largest "
             f"|β_eff/β − 1| over the first {N_BETA} counted impacts. θmax error: |Δ θmax/α|. History: RMS "
             "|Δθ|/α up to the agreement horizon (|Δθ| > 0.1α). Wall times: medians of repeats in this run.", "",
             "Speed: simulated s per wall s of the whole call (scene built, impacts measured), and of the "
             "engine's own stepping loop (`Trajectory.runtime_s`).", "",
             "| engine | setting | scenario | sim s / wall s | in the loop | β err (max) | θmax/α err | history RMS | horizon s | impacts (ref) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r.get("stopped"):
            lines.append(f"| {r['engine']} | {r['setting']} | {r['scenario']} | stopped: {r['stopped']} | | | | | | |")
            continue
        lines.append(f"| {r['engine']} | {r['setting']} | {r['scenario']} | {r['sim_per_wall']:.1f} | {r['sim_per_loop']:.1f} | "
                     f"{_pct(r['beta_error_max'])} | {r['theta_max_error']:.2e} | {r['history_rms']:.2e} | "
                     f"{r['horizon']:.2f} | {r['impacts']} ({r['impacts_ref']}) |")
    lines += ["", "## Fastest setting reaching a β error (free rocking)", "",
              "| engine | ≤ 1% | sim s / wall s | ≤ 0.1% | sim s / wall s |", "|---|---|---|---|---|"]
    for engine in dict.fromkeys(r["engine"] for r in rows):
        a, b = fastest(rows, engine, 0.01), fastest(rows, engine, 0.001)
        lines.append(f"| {engine} | {a['setting'] if a else 'none'} | {a['sim_per_wall']:.3g} |" if a else
                     f"| {engine} | none | — |")
        lines[-1] += (f" {b['setting']} | {b['sim_per_wall']:.3g} |" if b else " none | — |")
    if not KOBE.is_file():
        lines += ["", f"The Kobe scenario was not run: {KOBE} not found (the shared records sit beside the "
                      "repository)."]
    goals = goal_lines(extra.get("speed_goals") or [])
    if goals:
        lines += [""] + goals
    ratio = extra.get("solve_ivp_ratio")
    if ratio:
        lines += ["", "## Compiled analytic kernel against solve_ivp (Kobe 40 s isolated, same tolerance)", ""]
        lines += [f"- {k}: {v:.6g}" if isinstance(v, float) else f"- {k}: {v}" for k, v in ratio.items()]
    return "\n".join(lines) + "\n"


def plot(rows, path) -> None:
    import matplotlib  # lazy: matplotlib only for the plot
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above
    floor = 1e-16  # exact agreement cannot sit on a log axis: drawn at the floor
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for (metric, ax, title) in (("beta_error_max", axes[0], "effective β error (free rocking)"),
                                ("theta_max_error", axes[1], "|Δ θmax/α| (pulse)")):
        scen = "free-rocking" if metric == "beta_error_max" else "pulse"
        for engine in dict.fromkeys(r["engine"] for r in rows):
            # in ladder order (coarse to fine), so each line is one engine's settings
            pts = [(r["wall_per_sim"], max(r[metric], floor)) for r in rows
                   if r["engine"] == engine and r["scenario"] == scen and r[metric] is not None]
            if pts:
                x, y = zip(*pts)
                ax.loglog(x, y, "o-", label=engine)
        ax.axhline(floor, color="0.7", lw=0.8, ls=":")
        ax.set_xlabel("wall s per simulated s")
        ax.set_ylabel("error")
        ax.set_title(title + f", exact at {floor:g}")
        ax.grid(True, which="both", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend()
        else:
            ax.text(0.5, 0.5, f"no {scen} runs", ha="center", transform=ax.transAxes)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
