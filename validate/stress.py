"""`isorock stress`: a grid built to break each engine.

Each case varies one thing far from the paper's block (slenderness 1–20 including
both sides of the no-bounce limit, μ 0.01–100, T 0.2–6 s, ξ 0–0.5, PGA up to 3 g,
durations up to 300 s, records with dt 0.001–0.05 s, zero motion, long Zeno tails,
10 cm and 10 m blocks). Every case runs in a forked process with a wall-time limit,
so a hang is reported as a time-out instead of stalling the grid. A case fails when
its histories are not finite, it times out, the engine reports a failure, or (analytic)
the energy balance residual exceeds 1e-6 of the input energy.
"""
from __future__ import annotations

import math
import multiprocessing as mp
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from isorock.analytic.coefficients import no_bounce_slenderness
from isorock.analytic.motion import GroundMotion, load_motion
from isorock.analytic.system import System

ENERGY_TOLERANCE = 1e-6  # analytic energy balance residual / input energy (issue 6)
#: |θ|/α a run may show without being overturned: contact engines sample a step past α
OVERTURN_SLACK = 0.05


@dataclass(frozen=True)
class StressCase:
    name: str
    what: str  # the edge this case probes
    system: System
    motion: str  # a motion spec, or "noise:dt=…,pga=…,seconds=…,seed=…" (synthetic record)
    duration: float
    theta0: float = 0.0  # fraction of α
    quick: bool = False
    engines: tuple[str, ...] | None = None  # None: every engine

    def ground_motion(self) -> GroundMotion:
        if self.motion.startswith("noise:"):
            p = dict(kv.split("=") for kv in self.motion[6:].split(","))
            return synthetic_record(float(p["dt"]), float(p["pga"]), float(p["seconds"]), int(p["seed"]))
        return load_motion(self.motion)


def synthetic_record(dt: float, pga_g: float, seconds: float, seed: int) -> GroundMotion:
    """Band-limited noise (0.2–10 Hz, or Nyquist) with a build-up and decay envelope,
    scaled to `pga_g`: a record-like input at any sample step."""
    rng = np.random.default_rng(seed)
    n = int(round(seconds / dt)) + 1
    spectrum = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    spectrum[(f < 0.2) | (f > min(10.0, 0.45 / dt))] = 0
    a = np.fft.irfft(spectrum, n)
    t = np.arange(n) * dt
    a *= np.minimum(1.0, t / (0.2 * seconds)) * np.exp(-np.maximum(0.0, t - 0.5 * seconds) / (0.2 * seconds))
    return GroundMotion.from_array(a / np.max(np.abs(a)) * pga_g, dt=dt, units="g",
                                   name=f"noise dt={dt:g} pga={pga_g:g}g")


def _block(h=2.0, lam=2.857, mu=1.0, T=1.5, xi=0.2, fixed=False, mass=3800.0):
    width = h / lam
    if fixed:
        return System.fixed(height=h, width=width, mass=mass)
    return System.isolated(height=h, width=width, mass=mass, base_mass=mass / mu, period=T, damping_ratio=xi)


def grid(quick: bool = False) -> list[StressCase]:
    """The stress grid; `quick` keeps the cases marked quick."""
    pulse = "sine:amp=0.6,freq=1,cycles=2"
    c = []

    def add(name, what, system, motion=pulse, duration=6.0, theta0=0.0, q=False, engines=None):
        c.append(StressCase(name, what, system, motion, duration, theta0, q, engines))

    nb = no_bounce_slenderness(1.0)
    add("lambda-1", "squat block λ = 1 (uplift needs 1 g)", _block(lam=1.0), "sine:amp=1.5,freq=1,cycles=2", q=True)
    add("lambda-below-no-bounce", f"λ = 0.99·λ_nb = {0.99 * nb:.3f}: β < 0, impacts end rocking",
        _block(lam=0.99 * nb), "sine:amp=2.5,freq=1,cycles=2", q=True)
    add("lambda-above-no-bounce", f"λ = 1.01·λ_nb = {1.01 * nb:.3f}: β just above 0",
        _block(lam=1.01 * nb), "sine:amp=2.5,freq=1,cycles=2", q=True)
    add("lambda-20", "very slender λ = 20", _block(lam=20.0), "sine:amp=0.2,freq=1,cycles=2", q=True)
    add("zeno-tail-lambda-20", "long Zeno tail: free rocking, λ = 20, β ≈ 0.99", _block(lam=20.0, fixed=True),
        "none", duration=30.0, theta0=0.8, q=True)
    add("mu-0.01", "heavy base μ = 0.01", _block(mu=0.01))
    add("mu-100", "light base μ = 100", _block(mu=100.0), q=True)
    add("T-0.2", "stiff isolator T = 0.2 s", _block(T=0.2), q=True)
    add("T-6", "soft isolator T = 6 s", _block(T=6.0), "sine:amp=1.0,freq=0.2,cycles=1", duration=12.0)
    add("xi-0", "undamped isolator ξ = 0", _block(xi=0.0), q=True)
    add("xi-0.5", "heavily damped ξ = 0.5", _block(xi=0.5))
    add("pga-3g-fixed", "PGA 3 g, fixed base (overturns)", _block(fixed=True), "sine:amp=3,freq=2,cycles=2", q=True)
    add("pga-3g-isolated", "PGA 3 g, isolated", _block(), "sine:amp=3,freq=2,cycles=2")
    add("zero-motion", "no ground motion, block at rest", _block(), "none", duration=5.0, q=True)
    add("tiny-block", "10 cm block, fixed base", _block(h=0.1, mass=1.0, fixed=True), "sine:amp=0.5,freq=5,cycles=2",
        duration=3.0, q=True)
    add("huge-block", "10 m block", _block(h=10.0, mass=1e6), "sine:amp=0.6,freq=0.5,cycles=2", duration=15.0, q=True)
    add("record-dt-0.001", "record sampled at 1 ms", _block(), "noise:dt=0.001,pga=1.0,seconds=10,seed=1",
        duration=12.0, q=True)
    add("record-dt-0.05", "record sampled at 50 ms", _block(lam=4.0), "noise:dt=0.05,pga=0.8,seconds=20,seed=2",
        duration=22.0, q=True)
    add("record-dt-0.01-fixed", "record, fixed base", _block(fixed=True, lam=4.0),
        "noise:dt=0.01,pga=0.5,seconds=20,seed=3", duration=22.0)
    add("duration-300", "300 s: long record then free vibration", _block(), "noise:dt=0.02,pga=1.0,seconds=120,seed=4",
        duration=300.0)
    add("duration-60-quick", "60 s of record rocking a fixed base many times", _block(lam=4.0, fixed=True),
        "noise:dt=0.02,pga=0.3,seconds=50,seed=5",
        duration=60.0, q=True)
    return [x for x in c if x.quick] if quick else c


# --- running -------------------------------------------------------------------------

def _run_in_child(conn, engine_name, case):
    try:
        from isorock.validate.engines import get_engine
        engine = get_engine(engine_name)
        system, motion = case.system, case.ground_motion()
        start = time.perf_counter()
        tr = engine.simulate(system, motion, duration=case.duration, theta0=case.theta0 * system.alpha)
        wall = time.perf_counter() - start
        arrays = (tr.t, tr.u, tr.u_dot, tr.theta, tr.theta_dot)
        finite = all(np.all(np.isfinite(a)) for a in arrays)
        out = dict(status=tr.status, finite=bool(finite), wall_s=wall, impacts=tr.impact_count,
                   uplifts=tr.uplifts, overturned=tr.overturned,
                   theta_max_over_alpha=float(np.nanmax(np.abs(tr.theta)) / system.alpha) if tr.theta.size else 0.0,
                   u_max=float(np.nanmax(np.abs(tr.u))) if tr.u.size else 0.0, sim_end=float(tr.t[-1]),
                   energy_residual=tr.energy.relative_residual if tr.energy is not None else None)
    except Exception as e:  # reported as the case's failure, never silently
        out = dict(status="error", error=f"{type(e).__name__}: {e}", trace=traceback.format_exc(limit=3))
    conn.send(out)
    conn.close()


def run_case(engine: str, case: StressCase, time_limit: float) -> dict:
    """One case in a forked process; killed and reported as 'timeout' past time_limit."""
    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_run_in_child, args=(child, engine, case), daemon=True)
    start = time.perf_counter()
    proc.start()
    child.close()
    result = None
    if parent.poll(time_limit):
        try:
            result = parent.recv()
        except EOFError:
            result = None
    proc.join(1.0)
    if proc.is_alive():
        proc.kill()
        proc.join()
    if result is None:
        timed_out = time.perf_counter() - start >= time_limit
        result = dict(status="timeout" if timed_out else "crashed",
                      error=f"no result within {time_limit:g} s" if timed_out else f"exit code {proc.exitcode}")
    result.update(engine=engine, case=case.name, what=case.what, duration=case.duration)
    result["verdict"] = verdict(result)
    return result


def verdict(r: dict) -> str:
    if r["status"] in ("timeout", "crashed", "error", "failed", "event-limit"):
        return "FAIL"
    if not r.get("finite", False):
        return "FAIL"
    res = r.get("energy_residual")
    if res is not None and not res < ENERGY_TOLERANCE:
        return "FAIL"
    if r["status"] != "overturned" and r.get("sim_end", 0) < r["duration"] * (1 - 1e-9):
        return "FAIL"  # stopped early without saying why
    if r["status"] != "overturned" and r.get("theta_max_over_alpha", 0) > 1 + OVERTURN_SLACK:
        return "FAIL"  # tilted past α without calling it overturning: not a physical answer
    return "pass"


def run_stress(*, quick=False, engines=None, time_limit=None, progress=True) -> list[dict]:
    from isorock.validate.engines import ALL_ENGINES
    engines = list(engines or ALL_ENGINES)
    time_limit = time_limit or (30.0 if quick else 120.0)
    cases = grid(quick)
    todo = [(e, c) for c in cases for e in engines if c.engines is None or e in c.engines]
    results = []
    for k, (e, c) in enumerate(todo, 1):
        r = run_case(e, c, time_limit)
        results.append(r)
        if progress:
            print(f"[{k}/{len(todo)}] {e:8s} {c.name:26s} {r['verdict']:4s} {r['status']:10s} "
                  f"{r.get('wall_s', float('nan')):7.2f} s", file=sys.stderr, flush=True)
    return results


# --- output ----------------------------------------------------------------------------

COLUMNS = ("engine", "case", "verdict", "status", "finite", "wall_s", "impacts", "uplifts", "overturned",
           "theta_max_over_alpha", "u_max", "energy_residual", "what", "error")


def _fmt(v):
    if isinstance(v, float):
        return f"{v:.4g}" if math.isfinite(v) else str(v)
    return "" if v is None else str(v)


def markdown(results) -> str:
    fails = [r for r in results if r["verdict"] != "pass"]
    lines = [f"# isorock stress: {len(results) - len(fails)} of {len(results)} cases pass", "",
             "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for r in results:
        lines.append("| " + " | ".join(_fmt(r.get(c)).replace("|", "/") for c in COLUMNS) + " |")
    lines += ["", f"Energy balance tolerance (analytic): {ENERGY_TOLERANCE:g} of the input energy."]
    return "\n".join(lines) + "\n"


def add_parser(sub) -> None:
    p = sub.add_parser("stress", help="the stability stress grid (exits non-zero on any failure)",
                       description=__doc__.split("\n\n")[1])
    p.add_argument("--quick", action="store_true", help="the quick subset (under 2 minutes)")
    p.add_argument("--out", default="isorock-stress", metavar="DIR",
                   help="folder for stress.md, stress.csv, stress.json: new, empty or an earlier isorock "
                        "output (default: %(default)s)")
    p.add_argument("--engines", nargs="+", metavar="ENGINE", help="engines to stress (default: all)")
    p.add_argument("--time-limit", type=float, help="wall-time limit per case, s (default 30 quick, 120 full)")
    p.set_defaults(func=cmd_stress)


def cmd_stress(a) -> int:
    import csv
    import io

    from isorock.analytic.errors import InputError
    from isorock.validate.engines import get_engine
    from isorock.validate.output import to_json, write_folder_atomic
    for e in a.engines or []:
        get_engine(e)  # an unknown name is an InputError before anything runs
    if a.time_limit is not None and not a.time_limit > 0:
        raise InputError(f"time-limit = {a.time_limit!r}: must be a positive number of seconds")
    from isorock.validate.output import check_folder
    check_folder(a.out)  # a folder we may not write is refused before the grid runs
    start = time.perf_counter()
    results = run_stress(quick=a.quick, engines=a.engines, time_limit=a.time_limit)

    def fill(tmp: Path):
        (tmp / "stress.md").write_text(markdown(results))
        (tmp / "stress.json").write_text(to_json(results) + "\n")
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(results)
        (tmp / "stress.csv").write_text(buf.getvalue())
    write_folder_atomic(a.out, fill)
    fails = [r for r in results if r["verdict"] != "pass"]
    print(f"stress: {len(results) - len(fails)} of {len(results)} cases pass in "
          f"{time.perf_counter() - start:.0f} s; report in {a.out}/stress.md")
    for r in fails:
        print(f"  FAIL {r['engine']} {r['case']}: {r['status']} {r.get('error', '')}")
    return 1 if fails else 0
