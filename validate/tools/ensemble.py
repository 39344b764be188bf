"""Ensembles: one motion scaled over a range of its PGA, every engine on every scale.

Single histories near overturning are chaotic (model.md), so engines are judged
on how often they overturn as the analytic model does, and on the median |Δ θmax/α|
over the ensemble, not on one history.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...analytic.errors import InputError, require
from ...analytic.system import System
from ..core.cases import Case
from ..core.chunks import run_cases
from ..core.engines import REFERENCE, choose as engine_setting

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
        rocking = self.rocking_mask(engine)
        dr = np.abs(t - ref_t)[rocking]
        return {
            "overturn_agreement": float(np.mean(o[ok] == ref_o[ok])) if ok.any() else math.nan,
            "median_theta_max_diff": float(np.median(d)) if d.size else math.nan,
            "max_theta_max_diff": float(np.max(d)) if d.size else math.nan,
            "cases": int(ok.sum()),
            "rocking_cases": int(rocking.sum()),
            "median_theta_max_diff_rocking": float(np.median(dr)) if dr.size else math.nan,
        }

    def rocking_mask(self, engine: str) -> np.ndarray:
        """The cases where the reference rocks and neither overturns (the median over all
        cases is mostly zeros: no uplift at small scales, both overturned at large), and,
        where measured, where the reference is robust (a chaotic peak tests no engine)."""
        ref_t, ref_o = self.theta_max[REFERENCE], self.overturned[REFERENCE]
        t, o = self.theta_max[engine], self.overturned[engine]
        rocking = np.isfinite(t) & np.isfinite(ref_t) & (np.nan_to_num(ref_t) > ROCKING) & ~o & ~ref_o
        return rocking & self.robust if self.robust is not None else rocking

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


def run_ensembles(specs, engines, *, overrides_for=None, overturn_rule: str | None = None, client=None,
                  executor=None, threads: int | None = None, progress=None) -> list[Ensemble]:
    """One Ensemble per spec (system, motion, label, duration, scales): every engine
    ("ENGINE" or "ENGINE:PRESET", the analytic reference among them) on the motion scaled
    by each factor. The runs are campaign cases (`isorock.validate.tools.campaign.run_cases`): the
    analytic model's in batches of its compiled kernel in this process, the contact
    engines' in chunks on the `executor` (core.executor.Executor: validate's worker
    processes) or the Dask `client`'s workers, or here when there is neither (in `threads`
    threads). overrides_for(name): the settings that differ for that engine
    (those it lacks are ignored). A run that raised gets NaN and its message in `failed`;
    one that failed inside the engine (a blow-up) keeps what it measured, as a single
    run reports it. progress: an object with update(n, work), called as runs finish."""
    names = list(engines)
    if REFERENCE not in names:
        raise InputError(f"engines = {names}: an ensemble needs the {REFERENCE!r} reference")
    specs = list(specs)
    for system, motion, label, duration, scales in specs:
        if motion.pga <= 0:
            raise InputError(f"motion = {motion.name!r}: an ensemble scales the PGA, which is zero here")
    settings = {name: engine_setting(name, (overrides_for or (lambda _n: {}))(name)) for name in names}
    column = {(s.engine, s.label): name for name, s in settings.items()}
    cases, where = [], []
    for i, (system, motion, _label, duration, scales) in enumerate(specs):
        for k, f in enumerate(np.asarray(scales, dtype=float)):
            where.append((i, k, float(f)))
            cases.append(Case(len(cases), system, motion.scaled(float(f)), duration))
    table = run_cases(cases, list(settings.values()), client=client, executor=executor, threads=threads,
                      progress=progress, overturn_rule=overturn_rule, batch_here=True).to_pydict()
    out = [Ensemble(system=system, motion=label, pga_g=motion.pga_g, duration=duration,
                    scales=np.asarray(scales, dtype=float))
           for system, motion, label, duration, scales in specs]
    for ens in out:
        for name in names:
            ens.theta_max[name] = np.full(ens.scales.size, math.nan)
            ens.overturned[name] = np.zeros(ens.scales.size, dtype=bool)
    for row in range(len(table["case"])):
        i, k, f = where[table["case"][row]]
        name, ens = column[(table["engine"][row], table["setting"][row])], out[i]
        tmax = table["theta_max_over_alpha"][row]
        if tmax is None or math.isnan(tmax):  # the run raised: its row holds the message
            ens.failed.setdefault(name, []).append((f, table["message"][row]))
            continue
        ens.theta_max[name][k], ens.overturned[name][k] = tmax, table["overturned"][row]
    for ens in out:  # in scale order, as the runs were listed
        for name in ens.failed:
            ens.failed[name].sort()
    return out
