"""Ensembles: one motion scaled over a range of its PGA, every engine on every scale.

Single histories near overturning are chaotic (model.md), so engines are judged
on how often they overturn as the analytic model does, and on the median |Δ θmax/α|
over the ensemble, not on one history.
"""
from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from isorock.analytic.errors import InputError, require
from isorock.analytic.motion import GroundMotion
from isorock.analytic.system import System
from isorock.validate.engines import REFERENCE

DEFAULT_SCALES = (0.25, 1.5, 21)  # first, last factor of the motion's PGA, number of steps
#: θmax/α above which a case counts as rocking (model.md's impact threshold).
ROCKING = 0.01


def scale_factors(first: float = DEFAULT_SCALES[0], last: float = DEFAULT_SCALES[1],
                  steps: int = DEFAULT_SCALES[2]) -> np.ndarray:
    require(math.isfinite(first) and first > 0, "scales", first, "a positive first factor")
    require(math.isfinite(last) and last >= first, "scales", last, f"a last factor ≥ the first ({first})")
    require(int(steps) == steps and steps >= 1, "scales", steps, "a whole number of steps ≥ 1")
    return np.linspace(first, last, int(steps)) if steps > 1 else np.array([first])


@dataclass(frozen=True, eq=False)
class Ensemble:
    """θmax/α and overturning per engine (keys) per scale factor (rows of `scales`)."""

    system: System
    motion: str
    pga_g: float
    duration: float
    scales: np.ndarray
    theta_max: dict = field(default_factory=dict)   # engine → array of θmax/α
    overturned: dict = field(default_factory=dict)  # engine → bool array
    failed: dict = field(default_factory=dict)      # engine → list of (scale, message)
    #: per scale: does the reference's θmax/α hold (spread < ROBUST_SPREAD, no overturning
    #: flip) under ±1% of the motion? None: not measured, every case counts
    robust: np.ndarray | None = None

    def agreement(self, engine: str) -> dict:
        """Fraction of scales where `engine` overturns as the analytic model does, and
        the median and max |Δ θmax/α| against it."""
        ref_t, ref_o = self.theta_max[REFERENCE], self.overturned[REFERENCE]
        t, o = self.theta_max[engine], self.overturned[engine]
        ok = np.isfinite(t) & np.isfinite(ref_t)
        d = np.abs(np.minimum(t, 1.0) - np.minimum(ref_t, 1.0))[ok]
        # cases where the reference rocks and neither overturns: the median over all
        # cases is mostly zeros (no uplift at small scales, both overturned at large); and,
        # where measured, where the reference is robust (a chaotic peak tests no engine)
        rocking = (ok & (ref_t > ROCKING) & ~o & ~ref_o)
        if self.robust is not None:
            rocking &= self.robust
        dr = np.abs(t - ref_t)[rocking]
        return {
            "overturn_agreement": float(np.mean(o[ok] == ref_o[ok])) if ok.any() else math.nan,
            "median_theta_max_diff": float(np.median(d)) if d.size else math.nan,
            "max_theta_max_diff": float(np.max(d)) if d.size else math.nan,
            "cases": int(ok.sum()),
            "rocking_cases": int(rocking.sum()),
            "median_theta_max_diff_rocking": float(np.median(dr)) if dr.size else math.nan,
        }

    def rocking_count(self) -> int:
        """How many cases the reference rocks in (θmax/α above ROCKING)."""
        ref = self.theta_max.get(REFERENCE)
        return int(np.sum(np.nan_to_num(ref) > ROCKING)) if ref is not None else 0

    def as_dict(self) -> dict:
        out = {"motion": self.motion, "pga_g": self.pga_g, "duration": self.duration,
               "fixed_base": self.system.fixed_base, "scales": self.scales.tolist(),
               "theta_max_over_alpha": {k: v.tolist() for k, v in self.theta_max.items()},
               "overturned": {k: v.tolist() for k, v in self.overturned.items()},
               "failed": {k: [list(x) for x in v] for k, v in self.failed.items()},
               "rocking_cases": self.rocking_count(),
               "robust": None if self.robust is None else self.robust.tolist()}
        out["agreement"] = {e: self.agreement(e) for e in self.theta_max if e != REFERENCE}
        return out


def run_ensemble(engines, system: System, motion: GroundMotion, *, scales=None, duration: float,
                 settings: dict | None = None, label: str = "", progress=None) -> Ensemble:
    """Run every engine (validate.engines.Engine, the analytic one first) on `motion`
    scaled by each factor. `settings`: engine name → Settings (default: the engine's).
    `progress`: callable(line) called once per case; default prints to stderr.
    An engine that raises on one case gets NaN there and the message in `failed`."""
    scales = scale_factors() if scales is None else np.asarray(scales, dtype=float)
    names = [e.name for e in engines]
    if REFERENCE not in names:
        raise InputError(f"engines = {names}: an ensemble needs the {REFERENCE!r} reference")
    if motion.pga <= 0:
        raise InputError(f"motion = {motion.name!r}: an ensemble scales the PGA, which is zero here")
    progress = progress or _stderr
    settings = settings or {}
    result = Ensemble(system=system, motion=motion.name, pga_g=motion.pga_g, duration=duration, scales=scales)
    total, done = len(engines) * scales.size, 0
    for engine in engines:
        tmax = np.full(scales.size, math.nan)
        over = np.zeros(scales.size, dtype=bool)
        for i, f in enumerate(scales):
            start = time.perf_counter()
            try:
                tr = engine.simulate(system, motion.scaled(float(f)), settings=settings.get(engine.name),
                                     duration=duration)
                tmax[i], over[i] = tr.theta_max_over_alpha, tr.overturned
                note = f"θmax/α {tr.theta_max_over_alpha:.3f}{' overturned' if tr.overturned else ''}"
            except InputError:
                raise
            except Exception as e:  # an engine's failure on one case is a result, not a crash
                result.failed.setdefault(engine.name, []).append((float(f), f"{type(e).__name__}: {e}"))
                note = f"failed: {type(e).__name__}: {e}"
            done += 1
            progress(f"ensemble {label} [{done}/{total}] {engine.name} ×{f:.3f} PGA: {note} "
                     f"({time.perf_counter() - start:.1f} s)")
        result.theta_max[engine.name] = tmax
        result.overturned[engine.name] = over
    return result


def _stderr(line):
    print(line, file=sys.stderr, flush=True)
