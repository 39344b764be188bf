"""The analytic model's robustness probes: runs of the reference under a slightly perturbed
motion, which tell how far a single history can judge an engine (model.md). They simulate, so
they are not in core.compare, which only compares trajectories it is given (issue 35).

- reference_sensitivity: θmax/α and overturning with the motion scaled by 1 ± SENSITIVITY_SCALE
  (a history whose θmax/α moves a lot there is chaotic, and no single-history test);
- own_horizon: how long the model agrees with itself under 1 ± OWN_HORIZON_SCALE, the most any
  engine can be asked to hold.
"""
from __future__ import annotations

from ...analytic.motion import GroundMotion
from ...analytic.system import System
from ...analytic.trajectory import Trajectory
from .compare import agreement, horizon_units
from .engines import REFERENCE, get_engine
from .tolerances import limit

#: Relative PGA perturbation used to tell whether a reference history is robust (the table's).
SENSITIVITY_SCALE = limit("robust_perturbation")


def reference_sensitivity(system: System, motion: GroundMotion, *, duration: float,
                          scale: float = SENSITIVITY_SCALE, settings=None) -> dict:
    """θmax/α and overturning of the analytic model with the motion scaled by 1 ± scale.
    A history whose θmax/α moves a lot under a 1% change of PGA is chaotic there, and
    single-history agreement with it is no test of an engine (model.md)."""
    simulate = get_engine(REFERENCE).simulate
    values, over = [], []
    for f in (1 - scale, 1.0, 1 + scale):
        tr = simulate(system, motion.scaled(f), duration=duration, settings=settings)
        values.append(tr.theta_max_over_alpha)
        over.append(tr.overturned)
    return {"scales": [1 - scale, 1.0, 1 + scale], "theta_max_over_alpha": values,
            "overturned": over, "spread": max(values) - min(values),
            "overturn_flips": len(set(over)) > 1}


#: The analytic model's own horizon (issue 20): the motion scaled by 1 ± this, a
#: record's accuracy (the tolerance table's, with its reason).
OWN_HORIZON_SCALE = limit("own_horizon_perturbation")


def own_horizon(system: System, motion: GroundMotion, ref: Trajectory, *, duration: float,
                scale: float = OWN_HORIZON_SCALE) -> dict:
    """How long the analytic model agrees with itself (|Δθ| ≤ AGREEMENT_FRACTION·α) when
    the motion is scaled by 1 ± scale (compare.AGREEMENT_FRACTION): the most any engine can be asked to hold. An
    engine whose horizon reaches this one has done all that physics allows."""
    simulate = get_engine(REFERENCE).simulate
    runs = [agreement(simulate(system, motion.scaled(f), duration=duration), ref)
            for f in (1 - scale, 1 + scale)]
    horizon = min(r[0] for r in runs)
    return dict(horizon_units(horizon, ref, system), parted=any(r[1] for r in runs), scale=scale)
