"""How to integrate the analytic model: one settings object for both of its paths, the
compiled kernel (engine "analytic") and the SciPy reference (engine "analytic-reference")."""
from __future__ import annotations

from dataclasses import dataclass

from . import physics
from .errors import require, require_positive_finite


@dataclass(frozen=True)
class AnalyticSettings:
    """How to integrate the analytic model.

    rtol, atol: solve_ivp tolerances (atol applies to u in m and θ in rad alike).
    rest_velocity: rocking ends at an impact whose |θ̇⁻| is below rest_velocity·p·α
        (dimensionless). Free rocking with inelastic impacts is a Zeno sequence;
        this floor is a numerical setting, not physics (model.md). Rocking also ends
        at every impact of a block below the no-bounce slenderness (β ≤ 0).
    output_dt: stored points are at most this far apart (s), for plotting.
    max_step: largest integrator step (s); bounds how long a threshold crossing of
        the base acceleration can hide inside one step.
    max_events: a run with more events than this stops with status 'event-limit'.
    overturn: the overturning rule (model.md, "Past α"). "past-alpha" (default): the
        motion continues past α; overturned when |θ| reaches π/2 or the run ends with
        |θ| > α (a fixed base past α and falling after the motion may stop early).
        "alpha": the conservative rule, overturned (and stopped) once |θ| reaches α.
    """

    rtol: float = 1e-10
    atol: float = 1e-12
    method: str = "DOP853"
    rest_velocity: float = 1e-5
    output_dt: float = 0.005
    max_step: float = 0.01
    max_events: int = 200_000
    overturn: str = physics.PAST_ALPHA

    def __post_init__(self):
        for name in ("rtol", "atol", "rest_velocity", "output_dt", "max_step"):
            require_positive_finite(name, getattr(self, name))
        require(self.method in ("DOP853", "RK45", "Radau", "LSODA", "BDF", "RK23"),
                "method", self.method, "a solve_ivp method name")
        require(self.overturn in physics.OVERTURN_RULES, "overturn", self.overturn,
                f"one of {', '.join(physics.OVERTURN_RULES)}")
