"""The validation report's runs: every engine on the paper's block (or the user's own
system) under each motion, side by side with the analytic model, each check against the
tolerance table. `build(config)` runs everything and returns a Results;
`isorock.validate.tools.report_render` writes it.

Every run goes through the campaign machinery (`isorock.validate.tools.campaign`): the histories and
free rocking as `isorock.validate.core.runner` tasks (whole Trajectories), the ensembles as
campaign cases (`validate.ensemble.run_ensembles`: the analytic model in batches of its
compiled kernel); the analytic model's runs in this process, the contact engines' on the
one executor's `--workers` worker processes (core.executor: a run stuck past its budget is
killed there). A
scenario in which no engine lifts the block tests nothing about contact: it is "not
exercised" and counted apart, never passed.
"""
from __future__ import annotations

import importlib.metadata
import math
import platform
import sys
import time
from dataclasses import dataclass, field, replace
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ...analytic.errors import InputError, require
from ...analytic.limits import check_settings
from ...analytic.motion import GroundMotion, load_motion
from ...analytic.system import System, paper_system
from ...analytic.trajectory import SLIDING_FRACTION
from ..core.chunks import worker_pool
from ..core.compare import Comparison, compare, exact_first_impact_time, horizon_units
from ..core.estimate import estimate_line
from ..core.probes import own_horizon, reference_sensitivity
from ..core.engines import (ENGINE_MODULES, ENGINE_NAMES, REFERENCE, get_engine, resolve, runs_here,
                            settings_used, table_overrides)
from ..core.executor import Executor, default_workers
from ..core.measure import beta_errors, impact_closed_forms
from ..core.runner import Task, run_tasks
from ..core.scenarios import (FREE_THETA0_OVER_ALPHA, RECORD_WINDOW, REPORT_MOTIONS, Scenario,
                              free_rocking_grid, paper_bases)
from ..core.tolerances import (ROBUST_SPREAD, Check, check, has_tolerance, judged, limit, not_exercised,
                               skipped, tolerance, unjudged)
from ..core.verdict import overturn_verdicts, quantile_verdict
from ..io.naming import describe_motion
from ..io.progress import bar_of
from .ensemble import ROCKING, Ensemble, run_ensembles, scale_factors

#: Built-in pulses of the default report, chosen with the analytic model so that the
#: paper's block rocks on both bases without overturning, and (the sine) robustly:
#: θmax/α moves < 0.05 under ±1% PGA there. The Ricker's isolated case is sensitive
#: (uplift barely exceeds the threshold) and is judged by its ensemble instead.
DEFAULT_MOTIONS = REPORT_MOTIONS
#: Effective β is the mean over the first impacts whose half-cycle peaked above this
#: fraction of α (smaller ones are dominated by the contact's own scale), at most BETA_IMPACTS.
BETA_MIN_AMPLITUDE = 0.1
BETA_IMPACTS = 3
#: The paper's block (H 2 m, B 0.7 m, m = m_b = 3800 kg) and its isolator (T 1.5 s, ξ 0.2).
PAPER_SLENDERNESS = paper_system().slenderness
#: An ensemble scales the motion from above the scale at which the block first lifts
#: (ENSEMBLE_FIRST × that scale: just above it the block lifts only a little) to
#: ENSEMBLE_LAST × it, so that most cases rock and the largest overturn: a range fixed in
#: PGA would waste cases below uplift on a user's record.
ENSEMBLE_FIRST, ENSEMBLE_LAST = 1.2, 2.5
#: The scale factors' range when the motion never lifts the block in the linear estimate.
FALLBACK_SCALES = (0.25, 1.5)


@dataclass(frozen=True)
class Effort:
    """How much to run: the full report, or --quick."""

    scale_steps: int
    tail: float                      # s simulated after a pulse ends
    free_duration: float             # s of free rocking
    mass_ratios: tuple[float, ...]   # Figure 4's markers
    slenderness: tuple[float, ...]


FULL = Effort(scale_steps=21, tail=4.0, free_duration=3.0, mass_ratios=(0.5, 1.0, 1.5, 2.0),
              slenderness=(1.5, PAPER_SLENDERNESS, 4.0, 6.0, 8.0))
QUICK = Effort(scale_steps=6, tail=2.0, free_duration=2.0, mass_ratios=(1.0,),
               slenderness=(PAPER_SLENDERNESS, 6.0))


@dataclass(frozen=True)
class ReportConfig:
    """What to validate. `engines`: names, or ENGINE:PRESET (reported as separate
    columns); `system`: the user's block and base (None: the paper's block, isolated and
    on a fixed base); `overrides`: engine name → settings that differ from the defaults
    (a name of "*" applies to every engine that has the setting, e.g. friction);
    `workers`: processes for the contact engines (1: all in this one)."""

    motions: tuple[str, ...] = DEFAULT_MOTIONS
    engines: tuple[str, ...] = ENGINE_NAMES
    quick: bool = False
    duration: float | None = None        # s; default: pulse end + tail, records RECORD_WINDOW
    scales: tuple[float, float, int] | None = None
    format: str | None = None
    units: str | None = None
    system: System | None = None
    overrides: dict = field(default_factory=dict)
    workers: int | None = None
    overturn_rule: str | None = None
    pga: float | None = None             # g: every motion scaled to this peak ground acceleration
    pgv: float | None = None             # m/s: … or to this peak ground velocity

    def __post_init__(self):
        require(len(self.motions) > 0, "motion", self.motions, "at least one motion")
        require(self.pga is None or self.pgv is None, "pga/pgv", (self.pga, self.pgv), "one of the two, not both")
        for name in self.engines:
            base, _, preset = name.partition(":")
            require(base in ENGINE_MODULES, "engines", name, f"one of {', '.join(ENGINE_MODULES)} "
                                                              "(optionally ENGINE:PRESET)")
        require(REFERENCE in self.engines, "engines", ",".join(self.engines),
                f"a list that includes the {REFERENCE!r} reference")
        require(len(set(self.engines)) == len(self.engines), "engines", ",".join(self.engines),
                "a list without repeats")
        if self.duration is not None:
            require(math.isfinite(self.duration) and self.duration > 0, "duration", self.duration,
                    "a positive number of seconds")

    @property
    def effort(self) -> Effort:
        return QUICK if self.quick else FULL

    @property
    def own_system(self) -> bool:
        return self.system is not None

    def bases(self) -> tuple[tuple[str, System], ...]:
        """(label, System) of every base the histories and ensembles run on."""
        if self.system is None:
            return paper_bases()
        noun = self.system.subject.removeprefix("the ")  # block, or statue (a statue's mesh)
        if self.system.fixed_base:
            return ((f"your {noun} on a fixed base", self.system),)
        return (("your isolated base", self.system), (f"the same {noun} on a fixed base", self.system.on_fixed_base()))

    def overrides_for(self, name: str) -> dict:
        return table_overrides(self.overrides, name)


@dataclass
class HistoryRuns:
    """One motion on one base, every engine."""

    name: str
    motion: GroundMotion
    system: System
    duration: float
    runs: dict = field(default_factory=dict)         # engine → Trajectory
    errors: dict = field(default_factory=dict)       # engine → message
    not_carried: dict = field(default_factory=dict)  # engine → why it was not run (it cannot carry the system)
    comparisons: dict = field(default_factory=dict)  # engine → Comparison
    sensitivity: dict | None = None
    #: agreement horizons: engine → {s, p_units, impacts, parted}; "model under ±0.5%" the model's own
    horizons: dict = field(default_factory=dict)
    base_acceleration_peak: float | None = None      # m/s², the base's largest |absolute acceleration|

    @property
    def robust(self) -> bool:
        s = self.sensitivity
        return s is not None and s["spread"] < ROBUST_SPREAD and not s["overturn_flips"]

    @property
    def exercised(self) -> bool:
        """True when some engine lifted the block, or slid it (a statue with friction): otherwise
        nothing about contact was tested."""
        return any(tr.theta_max_over_alpha > ROCKING or _slid(tr) for tr in self.runs.values())

    def why_not_exercised(self) -> str:
        need = self.system.uplift_acceleration / self.system.gravity
        if self.system.slides:
            need = min(need, self.system.friction)
        reach = (self.base_acceleration_peak or 0.0) / self.system.gravity
        what = "uplift or a slide" if self.system.slides else "uplift"
        return f"not exercised: {what} needs ≈ {need:.3g} g, the base reaches {reach:.3g} g"


def _slid(tr) -> bool:
    """Whether a run's statue slid more than SLIDING_FRACTION·b (a statue with friction)."""
    return (tr.slide is not None and tr.slide.size > 0
            and float(np.max(np.abs(tr.slide - tr.slide[0]))) > SLIDING_FRACTION * tr.system.b)


#: The default report's statue that slides (issue 33): the paper's block on a fixed base with a
#: statue friction μ_s 0.2 (a polished plinth), below its tanα 0.35, so that the report's motions
#: slide it and it never lifts; judged by its histories alone (the slide rows of the tolerance
#: table). Nearer tanα (μ_s/tanα 0.6–1) MuJoCo's soft contact tilts a fast-sliding block and parts
#: from the exact model (at μ_s 0.3 it rocks, slides 4.9 cm to the exact 0.56: docs/sliding_engines.md)
SLIDING_FRICTION = 0.2


def sliding_bases(config) -> tuple[tuple[str, System], ...]:
    """(label, System) of the histories where the statue slides: the paper's block with
    SLIDING_FRICTION on a fixed base in the default report; none for a user's own system (its
    own bases slide where the user gave its friction)."""
    if config.system is not None:
        return ()
    return ((f"fixed base, statue friction μ_s {SLIDING_FRICTION:g} (it slides)",
             paper_system(fixed_base=True).with_friction(SLIDING_FRICTION)),)


@dataclass
class Results:
    config: ReportConfig
    engines: dict                 # name → Engine, those that could be loaded
    skipped: dict                 # name → why not
    free: list                    # dicts: engine, system label, effective β, errors
    scenarios: list               # HistoryRuns
    ensembles: list               # Ensemble
    checks: list                  # Check
    versions: dict
    started: str
    wall_s: float = 0.0
    settings: dict = field(default_factory=dict)  # engine → its Settings
    record_paths: tuple = ()
    sliding: list = field(default_factory=list)   # HistoryRuns of a statue that slides (histories only)

    @property
    def failed(self) -> list:
        return [c for c in self.checks if c.status == "fail"]


# --- what to run ---------------------------------------------------------------------------

def load_engines(names):
    """(name → Engine, name → reason) for the requested names (ENGINE or ENGINE:PRESET);
    a module that cannot be imported is skipped with the reason, not a crash."""
    ok, skipped_ = {}, {}
    for name in names:
        base = name.partition(":")[0]
        try:
            ok[name] = get_engine(base)
        except ImportError as e:
            skipped_[name] = f"module {ENGINE_MODULES[base]} not importable ({type(e).__name__}: {e})"
    return ok, skipped_


def beta_impacts(traj) -> list:
    """The impacts whose effective β a free-rocking run is judged by: the first
    BETA_IMPACTS counted impacts that peaked above BETA_MIN_AMPLITUDE·α."""
    return [i for i in traj.counted_impacts if i.amplitude >= BETA_MIN_AMPLITUDE * traj.system.alpha][:BETA_IMPACTS]


def effective_beta(traj) -> dict:
    """Effective β and β₂/h of a free-rocking run: means over its `beta_impacts`, with
    the largest errors against the closed forms among them."""
    sys_ = traj.system
    used = beta_impacts(traj)
    # each impact's own closed forms (a statue's two edges differ; the block's are one pair)
    refs = np.array([impact_closed_forms(sys_, i) for i in used]).reshape(-1, 2)
    b_refs, b2_refs = refs[:, 0], refs[:, 1] / sys_.h
    b_ref = float(np.mean(b_refs)) if used else impact_closed_forms(sys_)[0]
    b2_ref = float(np.mean(b2_refs)) if used else impact_closed_forms(sys_)[1] / sys_.h
    betas = np.array([i.beta for i in used])
    b2 = np.array([(i.u_dot_post - i.u_dot_pre) / i.theta_dot_pre / sys_.h for i in used])
    first = traj.counted_impacts[0].t if traj.counted_impacts else None
    return {
        "impacts_used": len(used), "beta_closed": b_ref, "beta2_over_h_closed": b2_ref,
        "beta": float(np.mean(betas)) if used else math.nan,
        "beta2_over_h": float(np.mean(b2)) if used and not sys_.fixed_base else None,
        "beta_rel_error": float(np.max(np.abs(betas / b_refs - 1))) if used else math.nan,
        "beta2_abs_error": float(np.max(np.abs(b2 - b2_refs))) if used and not sys_.fixed_base else None,
        "beta_errors": [float(b / r - 1) for b, r in zip(betas, b_refs)],
        "beta_errors_all": beta_errors(traj),
        "first_impact_time": first,
    }


def free_scenarios(config: ReportConfig) -> list[Scenario]:
    """The paper's Figure 4 grid (isolated bases of each μ, H fixed, B = H/λ) and the
    paper's block on a fixed base; or, for the user's system, its block free rocking on
    each of its bases; from FREE_THETA0_OVER_ALPHA·α."""
    effort = config.effort
    if not config.own_system:
        return free_rocking_grid(effort.mass_ratios, effort.slenderness, duration=effort.free_duration)
    return [Scenario(f"free rocking, {label}", system, "none", effort.free_duration, FREE_THETA0_OVER_ALPHA)
            for label, system in config.bases()]


def scenario_duration(motion: GroundMotion, config: ReportConfig) -> float:
    if config.duration is not None:
        return config.duration
    if motion.pulse is not None:
        return motion.end_time + config.effort.tail
    return min(motion.end_time, RECORD_WINDOW)


def load_motions(config: ReportConfig):
    """(GroundMotion, path or None) of every motion."""
    motions = []
    for spec in config.motions:
        kwargs = {"format": config.format}
        if config.units is not None:
            kwargs["units"] = config.units
        m = load_motion(spec, **kwargs)
        if m.is_zero:
            raise InputError(f"motion = {spec!r}: the report needs a ground motion ('none' has none)")
        if m.pulse is None and m.end_time > RECORD_WINDOW and config.duration is None:
            m = m.trimmed(0.0, RECORD_WINDOW)
        if config.pga is not None:  # scaled to the target on the window the report runs
            m = m.scaled_to_pga(config.pga)
        elif config.pgv is not None:
            m = m.scaled_to_pgv(config.pgv)
        motions.append((m, spec if m.pulse is None and Path(spec).is_file() else None))
    return motions


def base_acceleration_peak(system: System, motion: GroundMotion, duration: float) -> float:
    """The largest |absolute base acceleration| (m/s²) while the block stays down: the
    ground's on a fixed base; on an isolated base the linear isolator's response, read
    from the analytic model under the motion scaled far below uplift (it is linear there)."""
    if system.fixed_base:
        return motion.pga
    small = 1e-3 * system.uplift_acceleration / max(motion.pga, 1e-300)
    tr = get_engine(REFERENCE).simulate(system, motion.scaled(small), duration=duration)
    a = (system.damping * tr.u_dot + system.stiffness * tr.u) / system.total_mass
    return float(np.max(np.abs(a))) / small


def ensemble_scales(config: ReportConfig, system: System, motion: GroundMotion, peak: float) -> np.ndarray:
    """The user's --scales, or a range from just above the uplift scale: the motion scaled
    by f lifts the block once f·peak exceeds g·tanα."""
    if config.scales is not None:
        return scale_factors(*config.scales)
    steps = config.effort.scale_steps
    if peak <= 0:
        return scale_factors(*FALLBACK_SCALES, steps)
    lift = system.uplift_acceleration / peak
    return scale_factors(ENSEMBLE_FIRST * lift, ENSEMBLE_LAST * lift, steps)


# --- running -------------------------------------------------------------------------------

def build(config: ReportConfig, *, progress=None) -> Results:
    """Run every part of the report. Bad input raises InputError before anything runs.
    `progress(total)`: makes the progress object (io.progress.Progress, or anything with
    update(n, work)) once the number of runs is known; None shows none."""
    start = time.perf_counter()
    motions = load_motions(config)          # bad input fails here, before any simulation
    if config.scales is not None:
        scale_factors(*config.scales)
    engines, skipped_ = load_engines(config.engines)
    for name in list(engines):  # an engine that cannot carry the system (a statue's two edges, an isolator)
        for _, system in config.bases():  # is skipped with its reason before any run, never a failure
            try:
                engines[name].check_isolator(system)
            except InputError as e:
                skipped_[name] = f"cannot carry this system: {e}"
                del engines[name]
                break
    settings = {name: resolve(name, config.overrides_for(name))[1] for name in engines}
    started = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")

    free = free_scenarios(config)
    histories = []
    for motion, _ in motions:
        duration = scenario_duration(motion, config)
        for base, system in config.bases():
            sc = HistoryRuns(f"{describe_motion(motion)}, {base}", motion, system, duration)
            sc.base_acceleration_peak = base_acceleration_peak(system, motion, duration)
            histories.append(sc)
    scales = [ensemble_scales(config, sc.system, sc.motion, sc.base_acceleration_peak) for sc in histories]
    sliding = []
    for motion, _ in motions:
        for base, system in sliding_bases(config):
            sc = HistoryRuns(f"{describe_motion(motion)}, {base}", motion, system, scenario_duration(motion, config))
            sc.base_acceleration_peak = base_acceleration_peak(system, motion, sc.duration)
            sliding.append(sc)

    rule = config.overturn_rule
    tasks = []
    for name in engines:
        o = config.overrides_for(name)
        tasks += [Task(("free", i, name), name, sc.system, GroundMotion.zero(), sc.duration, sc.theta0, o, rule)
                  for i, sc in enumerate(free)]
        tasks += [Task(("history", i, name), name, sc.system, sc.motion, sc.duration, 0.0, o, rule)
                  for i, sc in enumerate(histories)]
        tasks += [Task(("slide", i, name), name, sc.system, sc.motion, sc.duration, 0.0, o, rule)
                  for i, sc in enumerate(sliding) if engines[name].capabilities.statue_friction]
    total = len(tasks) + len(engines) * sum(len(s) for s in scales)
    for t in tasks:  # the work bounds before any run (the steps each run will take): in a worker they were a traceback
        check_settings(settings_used(settings[t.engine], t.system, t.duration), t.duration)
    if progress is not None:  # a long report says so before it starts (core.estimate)
        simulated = {name: sum(t.duration for t in tasks if t.engine == name)
                     + sum(len(s) * sc.duration for s, sc in zip(scales, histories)) for name in engines}
        line = estimate_line(simulated, workers=config.workers or 2)
        if line:
            print(line, file=sys.stderr)
    bar = bar_of(progress, total)
    # one executor for every run: worker processes when a contact engine runs on several
    # (they start once; a run stuck past its budget is killed), this process otherwise
    executor = _executor(config, engines)
    try:
        results = run_tasks(tasks, executor=executor, on_result=lambda _key: bar.update(1))
        specs = [(sc.system, sc.motion, describe_motion(sc.motion), sc.duration, scales[i])
                 for i, sc in enumerate(histories)]
        ensembles = run_ensembles(specs, list(engines), overrides_for=config.overrides_for, overturn_rule=rule,
                                  executor=executor, threads=1 if config.workers == 1 else None, progress=bar)
    finally:
        executor.close()

    free_rows, checks = _free_rocking(engines, free, results)
    for key, sc in [(("history", i), sc) for i, sc in enumerate(histories)] + [(("slide", i), sc)
                                                                             for i, sc in enumerate(sliding)]:
        for name in engines:
            if (*key, name) not in results:  # an engine that carries no statue friction (a plugin's)
                sc.not_carried[name] = (f"not run: engine {name!r} carries a statue that cannot slip only "
                                        "(Capabilities.statue_friction)")
                continue
            tr, err = results[(*key, name)]
            if tr is None:
                sc.errors[name] = err
            else:
                sc.runs[name] = tr
        sc.sensitivity = reference_sensitivity(sc.system, sc.motion, duration=sc.duration)
        ref = sc.runs.get(REFERENCE)
        if ref is not None:
            sc.comparisons = {name: compare(tr, ref) for name, tr in sc.runs.items() if name != REFERENCE}
            sc.horizons = {name: dict(horizon_units(c.horizon, ref, sc.system), parted=c.parted)
                           for name, c in sc.comparisons.items()}
            sc.horizons[OWN] = own_horizon(sc.system, sc.motion, ref, duration=sc.duration)
        checks += _history_checks(sc, engines)
    for i, sc in enumerate(histories):
        ensembles[i] = _with_robustness(ensembles[i], sc)
        checks += _ensemble_checks(ensembles[i], sc.name, engines)
    return Results(config=config, engines=engines, skipped=skipped_, free=free_rows, scenarios=histories,
                   ensembles=ensembles, checks=checks, versions=versions(), started=started,
                   wall_s=time.perf_counter() - start, settings=settings,
                   record_paths=tuple(p for _, p in motions if p), sliding=sliding)


#: The key of the analytic model's own horizon (under ±0.5% of the motion) in HistoryRuns.horizons.
OWN = "model under ±0.5% of the motion"


def _free_rocking(engines, scenarios, results):
    rows, checks = [], []
    for name in engines:
        for i, sc in enumerate(scenarios):
            label, s = sc.name, sc.system
            tr, err = results[("free", i, name)]
            row = {"engine": name, "scenario": label, "slenderness": s.slenderness,
                   "mass_ratio": s.mu, "fixed_base": s.fixed_base, "error": err}
            if tr is not None:
                row.update(effective_beta(tr))
                row["runtime_s"] = tr.runtime_s
                row["status"] = str(tr.status)
            rows.append(row)
            checks.append(check(name, "beta_rel_error", label, row.get("beta_rel_error"), note=err or ""))
            if not s.fixed_base:
                checks.append(check(name, "beta2_abs_error", label, row.get("beta2_abs_error"), note=err or ""))
            else:
                t1 = exact_first_impact_time(s, sc.theta0)
                row["first_impact_time_exact"] = t1
                t = row.get("first_impact_time")
                checks.append(check(name, "first_impact_time_rel_error", label,
                                    None if t is None else abs(t / t1 - 1), note=err or ""))
    return rows, checks


def _history_checks(sc: HistoryRuns, engines) -> list[Check]:
    out = []
    ref = sc.runs.get(REFERENCE)
    if ref is not None and ref.energy is not None:
        out.append(check(REFERENCE, "energy_residual", sc.name, ref.energy.relative_residual))
    s = sc.sensitivity
    why_not = (f"reference not robust: analytic θmax/α {', '.join(f'{v:.3f}' for v in s['theta_max_over_alpha'])} "
               f"at ×{', '.join(f'{f:g}' for f in s['scales'])} PGA"
               f"{' (overturning flips)' if s['overturn_flips'] else ''}; judged by the ensemble")
    for name in engines:
        if name == REFERENCE:
            continue
        c: Comparison | None = sc.comparisons.get(name)
        err = sc.errors.get(name) or ("" if c else "no analytic reference")
        if sc.system.slides:  # a statue that may slide: its slide, and θ by the slide rows (docs/sliding.md)
            b, p = sc.system.b, sc.system.p
            stand = c is not None and not c.overturned and not c.overturned_ref
            metrics = {"slide_theta_max_diff": None if c is None else abs(c.theta_max_diff),
                       "overturn_agree": None if c is None else c.overturn_agree,
                       "slide_max": None if not stand or c.slide_max is None else abs(c.slide_max - c.slide_max_ref) / b,
                       "slide_final": (None if not stand or c.slide_final is None
                                       else abs(c.slide_final - c.slide_final_ref) / b)}
            if c is None or c.slide_onset_ref is not None or c.slide_onset is not None:
                metrics["slide_onset"] = None if c is None or c.slide_onset_diff is None else abs(c.slide_onset_diff) * p
        else:
            metrics = {"theta_max_diff": None if c is None else abs(c.theta_max_diff),
                       "impacts_diff": None if c is None else abs(c.impacts - c.impacts_ref),
                       "overturn_agree": None if c is None else c.overturn_agree}
        if not sc.system.fixed_base:
            metrics["u_max_rel_error"] = None if c is None or c.u_max_rel_error is None else abs(c.u_max_rel_error)
        # a sliding statue's soft contact tilts it a little (MuJoCo's by 0.005α at μ_s 0.2): it lifted where
        # the exact model did, or its θmax/α says how far it rocked (slide_theta_max_diff)
        lifted = c is None or c.first_uplift_ref is not None or (c.first_uplift is not None and not sc.system.slides)
        if lifted:
            metrics["first_uplift_diff"] = (None if c is None or c.first_uplift_diff is None
                                            else abs(c.first_uplift_diff))
        slid = sc.runs.get(name) is not None and str(sc.runs[name].status) == "slid"
        for metric, value in metrics.items():
            if not has_tolerance(name, metric):
                # counted as not made, with the reason (issue 39: Drake's θmax/α, impacts, uplift,
                # overturning and stroke were silently never judged beside its 'agrees with caveats')
                out.append(unjudged(name, metric, sc.name, None))
                continue
            if name in sc.not_carried:
                out.append(skipped(name, metric, sc.name, sc.not_carried[name]))
                continue
            if not sc.exercised and not err:
                out.append(not_exercised(name, metric, sc.name, sc.why_not_exercised()))
            elif not sc.robust:
                out.append(skipped(name, metric, sc.name, why_not))
            else:
                note = err or ("uplifted in one engine only" if metric == "first_uplift_diff" and value is None
                               else "slid in one engine only" if metric == "slide_onset" and value is None
                               else f"{sc.system.subject} slid on its base" if slid else "")
                out.append(check(name, metric, sc.name, value, note=note))
    return out


def _with_robustness(ens: Ensemble, sc: HistoryRuns) -> Ensemble:
    """The ensemble with, per scale, whether the reference's θmax/α is robust there.
    Robustness matters only where the reference rocks without overturning (the cases the
    median is taken over): elsewhere the two extra runs are not made."""
    ref_t, ref_o = ens.theta_max.get(REFERENCE), ens.overturned.get(REFERENCE)
    if ref_t is None:
        return ens
    rocks = (np.nan_to_num(ref_t) > ROCKING) & ~ref_o
    return replace(ens, robust=np.array([bool(r) and _robust(sc, f) for r, f in zip(rocks, ens.scales)]))


def _executor(config: ReportConfig, engines):
    """The one executor (core.executor) on config.workers worker processes (default:
    executor.default_workers) when a contact engine runs, else serial (the analytic
    model runs here in milliseconds)."""
    workers = default_workers() if config.workers is None else config.workers
    if workers <= 1 or all(runs_here(name) for name in engines):
        return Executor()
    return worker_pool(workers)


def _robust(sc: HistoryRuns, scale: float) -> bool:
    """Is the reference's θmax/α at this scale robust (as a history's, probes.reference_sensitivity)?
    The compiled reference makes the two extra runs per case cheap."""
    s = reference_sensitivity(sc.system, sc.motion.scaled(float(scale)), duration=sc.duration)
    return bool(s["spread"] < ROBUST_SPREAD and not s["overturn_flips"])


def _ensemble_checks(ens: Ensemble, label: str, engines) -> list[Check]:
    """Statistical verdicts over the ensemble (core.verdict): each engine's overturning
    fragility (median and dispersion against the scale) and its median θmax/α over the
    robust rocking cases, against the model's, at the table's confidence."""
    checks = []
    scenario = f"ensemble {label}"
    rocked = ens.rocking_count()
    confidence, min_cases = limit("verdict_confidence"), int(limit("verdict_min_cases"))
    for name in engines:
        if name == REFERENCE:
            continue
        note = "; ".join(f"×{f:.3g}: {m}" for f, m in ens.failed.get(name, []))
        if rocked == 0:
            why = f"not exercised: {ens.system.subject} rocks in none of the {ens.scales.size} cases"
            for metric in ("ensemble_overturn_median", "ensemble_overturn_dispersion", "ensemble_theta_max_diff"):
                checks.append(not_exercised(name, metric, scenario, why))
            continue
        ok = np.isfinite(ens.theta_max[name]) & np.isfinite(ens.theta_max[REFERENCE])
        limits = ("ensemble_overturn_median", "ensemble_overturn_dispersion")
        if not all(has_tolerance(name, m) for m in limits):
            checks += [skipped(name, m, scenario, f"no limit for {name} in the tolerance table") for m in limits]
            fits = False
        else:
            fits = overturn_verdicts(ens.scales[ok], ens.overturned[name][ok], ens.overturned[REFERENCE][ok],
                                     median_limit=tolerance(name, "ensemble_overturn_median").limit,
                                     dispersion_limit=tolerance(name, "ensemble_overturn_dispersion").limit,
                                     confidence=confidence, min_cases=min_cases)
        if fits is False:
            pass  # skipped above
        elif fits is None:
            why = ("neither overturns in any case" if not ens.overturned[REFERENCE][ok].any()
                   else "both overturn in every case")
            for metric in ("ensemble_overturn_median", "ensemble_overturn_dispersion"):
                checks.append(not_exercised(name, metric, scenario, f"{why} of {int(ok.sum())}"))
        else:
            checks.append(judged(name, "ensemble_overturn_median", scenario, fits[0], note=note))
            checks.append(judged(name, "ensemble_overturn_dispersion", scenario, fits[1], note=note))
        a = ens.agreement(name)
        if not has_tolerance(name, "ensemble_theta_max_diff"):  # no limit for this engine: skipped, saying why
            checks.append(skipped(name, "ensemble_theta_max_diff", scenario,
                                  f"no limit for {name} in the tolerance table"))
        elif a["rocking_cases"]:
            rocking = ens.rocking_mask(name)
            v = quantile_verdict(ens.theta_max[name][rocking], ens.theta_max[REFERENCE][rocking],
                                 limit=tolerance(name, "ensemble_theta_max_diff").limit, confidence=confidence,
                                 min_cases=min_cases, quantity="Δ median θmax/α")
            checks.append(judged(name, "ensemble_theta_max_diff", scenario, v, note=note))
        else:
            checks.append(skipped(name, "ensemble_theta_max_diff", scenario,
                                  "the reference rocks robustly without overturning in no case"))
    return checks


def versions() -> dict:
    out = {"python": platform.python_version()}
    for dist in ("isorock", "numpy", "scipy", "matplotlib", "mujoco", "pybullet", "numba"):
        try:
            out[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            out[dist] = "not installed"
    return out
