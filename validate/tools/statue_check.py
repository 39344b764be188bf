"""A contact engine on a statue's own shape against the exact model of its two edges (issue 36;
docs/statues.md, "The contact engines on the base and isolator"): the example statues at any
size, on any base, under one sine cycle that follows the statue, judged history by history.

The pulse follows the statue (a similarity law of the exact model): frequency 2·√(g/R₊)/2π and
amplitude k·g·tanα of its weaker edge. `amplitude_for` finds the k at which the exact model's
θmax/α is a target, so that a case rocks clearly without overturning. A case is judged history
by history only where the exact model's own history is robust, by the report's rule
(core.probes.reference_sensitivity: θmax/α moves by less than ROBUST_SPREAD under ±1% of the
amplitude, overturning unflipped): a single pulse's peak climbs steeply towards overturning,
so a target near it makes a chaotic reference that tests no engine (model.md).

    from isorock.validate.tools import statue_check as sc
    body, system = sc.example("bust", 1.0, "linear")
    row = sc.compare(system, sc.pulse(system, sc.amplitude_for(system, 0.3)), "mujoco")
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from ...analytic import shape
from ...analytic.motion import GroundMotion
from ...analytic.errors import require
from ...analytic.system import BallInBowl, FrictionPendulum, PlanarBody, System
from ..core.probes import reference_sensitivity
from ..core.engines import REFERENCE, get_engine
from ..core.measure import beta_errors
from ..core.tolerances import ROBUST_SPREAD

#: the example statues' stone, kg/m³ (granite and marble: 2,600–2,800)
DENSITY = 2600.0
#: s the runs go on after the pulse: the free rocking that follows it, with its impacts
AFTER = 3.0


#: the bases `example` puts a statue on: fixed; a linear isolator of T 2 s, ξ 0.1; a friction
#: pendulum of radius 1.5 m (T 2.5 s) and μ 0.05
BASES = ("fixed", "linear", "friction-pendulum")
#: bases `example` builds beyond the script's default table: the ball in a bowl (R 1.5 m, μ_r 0.05),
#: the same equations as the friction pendulum (BallInBowl.as_pendulum), judged in the hull engines' tests
MORE_BASES = ("ball-in-bowl",)


def example(name: str, scale: float, base: str = "fixed", *, base_mass_ratio: float = 1.0,
            density: float = DENSITY):
    """(the statue at rest turned onto the direction it tips first, its System of two edges):
    the example statue `name` (analytic.shape.example_statue) scaled by `scale`, on `base` (one
    of BASES), its base weighing base_mass_ratio times the statue."""
    vertices, faces = shape.example_statue(name)
    body = shape.standing(vertices * scale, faces, density=density, name=name)
    body = body.along(shape.weakest_direction(body)[0])
    system = replace(System.of_body(PlanarBody.from_resting(body), mass=body.mass),
                     base_mass=base_mass_ratio * body.mass)
    if base == "linear":
        system = system.on_isolator(2.0, 0.1)
    elif base == "friction-pendulum":
        system = replace(system.on_isolator(2.0, 0.1), isolator=FrictionPendulum(radius=1.5, friction_coefficient=0.05))
    elif base == "ball-in-bowl":
        system = replace(system.on_isolator(2.0, 0.1), isolator=BallInBowl(radius=1.5, rolling_resistance=0.05))
    else:
        require(base == "fixed", "base", base, f"one of {', '.join(BASES + MORE_BASES)}")
    return body, system


def pulse(system: System, k: float, dt: float = 1e-3) -> GroundMotion:
    """One sine cycle: amplitude k·g·tanα of the weaker edge, frequency 2·√(g/R₊)/2π."""
    edges = system.body
    tan_alpha = min(edges.lever_forward, edges.lever_backward) / edges.centre_height
    freq = 2.0 * math.sqrt(system.gravity / edges.radius(1)) / (2.0 * math.pi)
    t = np.arange(0.0, 1.0 / freq + 1e-12, dt)
    a = k * tan_alpha * system.gravity * np.sin(2.0 * np.pi * freq * t)
    return GroundMotion.from_array(a, dt=dt, units="m/s2", name=f"sine k={k:.4g}")


def exact(system: System, motion: GroundMotion):
    return get_engine(REFERENCE).simulate(system, motion, duration=motion.end_time + AFTER)


def amplitude_for(system: System, target: float, *, low: float = 0.5, high: float = 20.0) -> float:
    """k at which the exact model's θmax/α reaches `target` without overturning (bisection)."""
    for _ in range(30):
        k = 0.5 * (low + high)
        tr = exact(system, pulse(system, k))
        if tr.overturned or tr.theta_max_over_alpha > target:
            high = k
        else:
            low = k
    return low


def robust(system: System, motion: GroundMotion) -> tuple[bool, float]:
    """(whether the exact model's history under `motion` is robust, its θmax/α spread under ±1%)."""
    s = reference_sensitivity(system, motion, duration=motion.end_time + AFTER)
    return bool(s["spread"] < ROBUST_SPREAD and not s["overturn_flips"]), float(s["spread"])


def compare(system: System, motion: GroundMotion, engine: str, *, settings=None) -> dict:
    """One engine's run of `system` under `motion` against the exact model's, in the tolerance
    table's terms: |Δ θmax/α| (theta_max_diff), the impacts of each (impacts_diff), the worst
    |β error| against each impact's own edge (beta_rel_error, measure.beta_errors); besides,
    θmax's relative error, the history's largest |Δθ|/α, overturning, the statue's wobble out
    of the plane (a free body's), the wall time."""
    tr = exact(system, motion)
    start = time.perf_counter()
    # the registry's engine hands back a measured Trajectory, whatever the engine returns
    got = get_engine(engine).simulate(system, motion, duration=motion.end_time + AFTER,
                                      **({} if settings is None else {"settings": settings}))
    wall = time.perf_counter() - start
    peak = float(np.max(np.abs(tr.theta)))
    errors = [abs(e) for e in beta_errors(got) if math.isfinite(e)]
    return dict(engine=engine, status=str(got.status), theta_max_rel_error=float(np.max(np.abs(got.theta))) / peak - 1.0,
                theta_max_diff=abs(float(got.theta_max_over_alpha) - float(tr.theta_max_over_alpha)),
                history_error=float(np.max(np.abs(got.theta - np.interp(got.t, tr.t, tr.theta)))) / system.alpha,
                exact_impacts=tr.impact_count, impacts=got.impact_count,
                beta_rel_error=max(errors) if errors else math.nan,
                overturned=(bool(tr.overturned), bool(got.overturned)), wall_s=wall,
                # the wobble and twist of a statue's own shape, which the planar model does not describe
                out_of_plane=float(got.extras.get("out_of_plane_max", math.nan)),
                exact_theta_max_over_alpha=float(tr.theta_max_over_alpha))
