"""The contact engines on a statue's real shape against the exact model of its two edges
(issue 36; docs/statues.md, "The contact engines on the hull"): each example statue (bust,
amphora, obelisk: analytic.shape.example_statue, 2,600 kg/m³) at 0.5×, 1× and 3× its size, as
its convex hull on a free joint on a fixed table (the simulate_body facet: the scenes the
shake-table study runs), under one sine cycle along the direction it tips first, against the
exact model of its two edges along that direction (System.body, engine "analytic").

The pulse follows the statue (a similarity law of the exact model): frequency 2·√(g/R₊)/2π
and amplitude k·g·tanα of its weaker edge, k found once per statue (at 1×) so that the exact
model's θmax/α is TARGET; the exact model then gives the same θmax/α at every size, and so
should an engine.

    python docs/scripts/hull_two_edges.py [--engines mujoco,bullet] [--target 0.3]
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np

from isorock.analytic import shape
from isorock.analytic.motion import GroundMotion
from isorock.analytic.system import PlanarBody, System
from isorock.validate.core.engines import get_engine
from isorock.validate.tools.experiments.study import SIMULATE_BODY

G = 9.81
STATUES = ("bust", "amphora", "obelisk")
SIZES = (0.5, 1.0, 3.0)
TARGET = 0.3
DENSITY = 2600.0


def statue(name: str, scale: float):
    """(the statue at rest turned onto the direction it tips first, its System of two edges)."""
    vertices, faces = shape.example_statue(name)
    body = shape.standing(vertices * scale, faces, density=DENSITY, name=name)
    body = body.along(shape.weakest_direction(body)[0])
    return body, System.of_body(PlanarBody.from_resting(body), mass=body.mass)


def pulse(system: System, k: float, dt: float = 1e-3):
    """One sine cycle: amplitude k·g·tanα (the weaker edge), frequency 2·√(g/R₊)/2π (m/s², dt)."""
    edges = system.body
    thr = min(edges.lever_forward, edges.lever_backward) / edges.centre_height
    freq = 2.0 * math.sqrt(G / edges.radius(1)) / (2.0 * math.pi)
    t = np.arange(0.0, 1.0 / freq + 1e-12, dt)
    return k * thr * G * np.sin(2.0 * np.pi * freq * t), dt


def exact(system: System, a, dt):
    motion = GroundMotion.from_array(a, dt=dt, units="m/s2", name="sine")
    return get_engine("analytic").simulate(system, motion, duration=a.size * dt + 3.0)


def amplitude_for(system: System, target: float) -> float:
    """k at which the exact model's θmax/α is `target` (bisection; θmax/α rises with k here)."""
    lo, hi = 1.0, 4.0
    for _ in range(40):
        k = 0.5 * (lo + hi)
        tr = exact(system, *pulse(system, k))
        if tr.overturned or tr.theta_max_over_alpha > target:
            hi = k
        else:
            lo = k
    return lo


def rows(engines, target=TARGET):
    for name in STATUES:
        k = amplitude_for(statue(name, 1.0)[1], target)
        for scale in SIZES:
            body, system = statue(name, scale)
            a, dt = pulse(system, k)
            tr = exact(system, a, dt)
            theta = float(np.max(np.abs(tr.theta)))
            for engine in engines:
                start = time.perf_counter()
                got = SIMULATE_BODY.of(get_engine(engine).spec)(body.vertices, body.com, body.inertia, body.mass, a, dt,
                                                            duration=a.size * dt + 3.0)
                yield dict(statue=name, scale=scale, k=k, mass=body.mass, engine=engine,
                           alpha_forward=system.body.alpha(1), alpha_backward=system.body.alpha(-1),
                           exact_theta_max=theta, exact_over_alpha=tr.theta_max_over_alpha, exact_impacts=tr.impact_count,
                           engine_tilt_max=float(got["tilt_max"]), overturned=(tr.overturned, bool(got["overturned"])),
                           rel_error=float(got["tilt_max"]) / theta - 1.0, wall_s=time.perf_counter() - start)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--engines", default="mujoco,bullet")
    p.add_argument("--target", type=float, default=TARGET)
    a = p.parse_args()
    print("| statue | size | mass (kg) | α₊ / α₋ (rad) | exact θmax/α (impacts) | engine | engine θmax / exact θmax − 1 |")
    print("|---|---:|---:|---|---|---|---:|")
    for r in rows([e for e in a.engines.split(",") if e], a.target):
        over = "overturned" if r["overturned"][1] else ""
        print(f"| {r['statue']} | {r['scale']:g}× | {r['mass']:.4g} | {r['alpha_forward']:.3f} / {r['alpha_backward']:.3f} | "
              f"{r['exact_over_alpha']:.3f} ({r['exact_impacts']}) | {r['engine']} | {r['rel_error']:+.3f} {over} |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
