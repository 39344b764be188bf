"""`isorock calibrate`: find a contact engine's contact parameters that reproduce the
impact law of one system, and check them on cases they were not fitted on.

The objective is the worst |β_eff/β − 1| over the first impacts of free rocking of the
system from FITTED tilts, and of the block on its other base; each engine says what may move (its `EngineSpec.tuning`: MuJoCo
the direct contact stiffness, damping and impedance; PyBullet the contact ERP and solver
iterations; Drake the point contact's stiffness and dissipation). SciPy's bounded
Nelder–Mead searches them, from the engine's settings at the user's timestep. The result
is held against other tilts on both bases (HELD_OUT); only a result that holds there is
written, as a TOML file whose [settings.ENGINE] table `isorock validate --config` takes
(exit 1 when it does not hold).
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import asdict, dataclass, fields

import numpy as np

from isorock.analytic.errors import InputError

#: Free-rocking tilts (fractions of α) the parameters are fitted on, and held out on.
FITTED = (0.3, 0.45, 0.6, 0.8)
HELD_OUT = (0.35, 0.5, 0.7)
#: Impacts per run whose β counts (the first ones: the later, smaller ones measure the
#: contact's own scale more than the impact law).
IMPACTS = 4
#: The objective of a run that gives fewer impacts or an unmeasurable β: worse than any real error.
PENALTY = 1.0


@dataclass(frozen=True)
class Case:
    label: str
    system: object
    theta0_over_alpha: float


def cases(system) -> tuple[list[Case], list[Case]]:
    """(fitted, held out): the system and the block on its other base (a fixed base for an
    isolated one; the paper's isolator, T 1.5 s ξ 0.2, for a fixed one) from the FITTED
    tilts (one base, or few tilts, over-fit the step-to-step noise of β); held out, both
    from the HELD_OUT tilts."""
    from isorock.analytic.system import System
    if system.fixed_base:
        other = System.isolated(height=system.height, width=system.width, mass=system.mass,
                                base_mass=system.base_mass, period=1.5, damping_ratio=0.2)
        where = ("fixed base", "isolated base (T 1.5 s, ξ 0.2)")
    else:
        other = System.fixed(height=system.height, width=system.width, mass=system.mass, base_mass=system.base_mass)
        where = ("isolated base", "fixed base")
    fitted = [Case(f"θ0 = {f}α, {b}", sys_, f) for f in FITTED for b, sys_ in zip(where, (system, other))]
    held = [Case(f"θ0 = {f}α, {b}", sys_, f) for f in HELD_OUT for b, sys_ in zip(where, (system, other))]
    return fitted, held


def worst_beta_error(engine, settings, case_list, duration: float) -> tuple[float, list[float]]:
    """(worst |β error| over every case's first IMPACTS counted impacts, per case)."""
    from isorock.validate.measure import beta_errors
    per = []
    for c in case_list:
        try:
            tr = engine.simulate(c.system, None, settings=settings, duration=duration,
                                 theta0=c.theta0_over_alpha * c.system.alpha)
            errs = [abs(e) for e in beta_errors(tr, IMPACTS)]
        except InputError:
            raise
        except Exception:  # a setting that breaks the engine is a bad point, not a crash
            errs = []
        ok = len(errs) == IMPACTS and all(math.isfinite(e) for e in errs)
        per.append(max(errs) if ok else PENALTY)
    return max(per), per


def calibrate(engine_name: str, system, *, settings=None, duration: float = 4.0, max_evals: int = 80,
              progress=None) -> dict:
    """Fit the engine's tuning to `system`; returns the settings before and after and the
    worst β errors on the fitted and held-out cases."""
    from scipy.optimize import minimize

    from isorock.validate.engines import get_engine
    engine = get_engine(engine_name)
    tuning = engine.spec.tuning
    if tuning is None:
        raise InputError(f"engine = {engine_name!r}: has no contact parameters to calibrate")
    start_settings = settings or engine.settings()
    fitted, held = cases(system)
    lo = np.array([b[0] for b in tuning.bounds])
    hi = np.array([b[1] for b in tuning.bounds])
    x0 = np.clip(np.asarray(tuning.start(start_settings), dtype=float), lo, hi)
    seen = {}

    def objective(x):
        x = np.clip(x, lo, hi)
        key = tuple(np.round(x, 12))
        if key not in seen:
            try:
                s = tuning.apply(start_settings, x)
            except InputError:  # outside what the engine accepts: a bad point
                seen[key] = PENALTY
            else:
                seen[key] = worst_beta_error(engine, s, fitted, duration)[0]
            if progress:
                progress(len(seen), max_evals, seen[key])
        return seen[key]

    t0 = time.perf_counter()
    before_fit, before_fit_cases = worst_beta_error(engine, start_settings, fitted, duration)
    before_held, before_held_cases = worst_beta_error(engine, start_settings, held, duration)
    result = minimize(objective, x0, method="Nelder-Mead", bounds=list(zip(lo, hi)),
                      options={"maxfev": max_evals, "xatol": 1e-3, "fatol": 1e-5,
                               "initial_simplex": _simplex(x0, lo, hi)})
    best_x = np.clip(result.x, lo, hi)
    best = tuning.apply(start_settings, best_x)
    after_fit, after_fit_cases = worst_beta_error(engine, best, fitted, duration)
    if after_fit > before_fit:  # the search found nothing better than where it started
        best, best_x, after_fit, after_fit_cases = start_settings, x0, before_fit, before_fit_cases
    after_held, after_held_cases = worst_beta_error(engine, best, held, duration)
    return {
        "engine": engine_name, "parameters": dict(zip(tuning.names, map(float, best_x))),
        "settings_before": start_settings, "settings_after": best,
        "fitted": {"cases": [c.label for c in fitted], "before": before_fit, "after": after_fit,
                   "before_per_case": before_fit_cases, "after_per_case": after_fit_cases},
        "held_out": {"cases": [c.label for c in held], "before": before_held, "after": after_held,
                     "before_per_case": before_held_cases, "after_per_case": after_held_cases},
        "evaluations": len(seen), "wall_s": time.perf_counter() - t0,
    }


def _simplex(x0, lo, hi):
    """A starting simplex a fifth of each range wide, inside the bounds."""
    pts = [x0]
    for i in range(x0.size):
        p = x0.copy()
        step = 0.2 * (hi[i] - lo[i])
        p[i] = p[i] + step if p[i] + step <= hi[i] else p[i] - step
        pts.append(p)
    return np.array(pts)


def settings_toml(engine_name: str, settings, header_lines) -> str:
    """A TOML preset file: the header as comments, then [settings.ENGINE]."""
    lines = [f"# {line}" for line in header_lines] + ["", f"[settings.{engine_name}]"]
    for f in fields(settings):
        v = getattr(settings, f.name)
        if v is None:
            continue
        if isinstance(v, bool):
            lines.append(f"{f.name} = {'true' if v else 'false'}")
        elif isinstance(v, (int, float)):
            lines.append(f"{f.name} = {v!r}")
        elif isinstance(v, str):
            lines.append(f'{f.name} = "{v}"')
        elif isinstance(v, (tuple, list)):
            lines.append(f"{f.name} = [{', '.join(repr(float(x)) for x in v)}]")
    return "\n".join(lines) + "\n"


# --- command line ----------------------------------------------------------------------------

def add_parser(sub) -> None:
    from isorock.validate.cli import add_engine_options, add_system_options
    p = sub.add_parser("calibrate", help="fit a contact engine's contact parameters to the closed-form β",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("--engine", required=True, help="mujoco, bullet or drake")
    add_system_options(p, required=False)
    add_engine_options(p)
    p.add_argument("--max-evals", type=int, default=80,
                   help="simulations of the fitted cases the search may spend (default: %(default)s)")
    p.add_argument("--out", metavar="FILE.toml",
                   help="write the calibrated settings as a preset file (`isorock validate --config FILE`)")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    p.set_defaults(func=cmd_calibrate)


def cmd_calibrate(a) -> int:
    from isorock.analytic.system import paper_system
    from isorock.validate.cli import engine_settings_from_args, system_from_options
    from isorock.validate.engines import get_engine
    from isorock.validate.output import write_text
    engine = get_engine(a.engine)
    if engine.spec.tuning is None:
        raise InputError(f"engine = {a.engine!r}: has no contact parameters to calibrate")
    if not 5 <= a.max_evals <= 2000:
        raise InputError(f"max-evals = {a.max_evals!r}: must be a whole number from 5 to 2000")
    system = system_from_options(a) or paper_system(fixed_base=True)
    if a.out:
        from pathlib import Path
        if Path(a.out).exists():
            raise InputError(f"out = {a.out!r}: exists; give a new file (isorock does not replace files it "
                             "did not write)")
    settings = engine_settings_from_args(engine, a)

    def progress(k, total, value):
        if not a.quiet and sys.stderr.isatty():
            print(f"\r  calibrate: {k}/{total} evaluations, worst β error {100 * value:.3f}%", end="",
                  file=sys.stderr, flush=True)
    r = calibrate(a.engine, system, settings=settings, max_evals=a.max_evals, progress=progress)
    if not a.quiet and sys.stderr.isatty():
        print(file=sys.stderr)
    before, after = asdict(r["settings_before"]), asdict(r["settings_after"])
    changed = {k: (before[k], after[k]) for k in after if before[k] != after[k]}
    lines = [f"isorock calibrate --engine {a.engine}: {system.describe()['height']:g} × "
             f"{system.describe()['width']:g} m block, {'fixed' if system.fixed_base else 'isolated'} base",
             f"worst β error over the first {IMPACTS} impacts, {len(r['fitted']['cases'])} fitted cases (free rocking "
             f"from {', '.join(map(str, FITTED))}·α on both bases): "
             f"{100 * r['fitted']['before']:.3f}% → {100 * r['fitted']['after']:.3f}%",
             f"{len(r['held_out']['cases'])} held-out cases (from {', '.join(map(str, HELD_OUT))}·α on both bases): "
             f"{100 * r['held_out']['before']:.3f}% → {100 * r['held_out']['after']:.3f}%",
             f"{r['evaluations']} evaluations in {r['wall_s']:.0f} s"]
    for k, (b, v) in changed.items():
        lines.append(f"{k}: {b} → {v}")
    holds = r["held_out"]["after"] <= r["held_out"]["before"]
    lines.append("the calibrated settings hold on the held-out cases" if holds else
                 "the calibrated settings do NOT hold on the held-out cases (worse than where the search started): "
                 "at this step β's error is set by the step, not by these contact parameters; keep the defaults")
    print("\n".join(lines))
    if a.out and holds:
        write_text(a.out, settings_toml(a.engine, r["settings_after"], lines))
        print(f"wrote {a.out} (use it with: isorock validate --config {a.out} --engines analytic {a.engine})")
    elif a.out:
        print(f"{a.out} not written: a preset that does not hold on cases it was not fitted on is no preset")
    return 0 if holds else 1
