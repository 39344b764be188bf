"""The rigid rocking model of a shake-table specimen's own two edges: the exact model
(isorock.analytic, System.body: docs/statues.md) of the rock's forward and backward tipping edges
in the shaking direction, on the table (a fixed base), under its measured acceleration. A caller,
not an integrator of its own (issue 36): the RK4 this study ran before is kept in the tests as the
exact model's oracle (tests/asymmetric_rk4.py).

What the planar model leaves out (the 3-D hull in MuJoCo has it): rocking about a footprint
vertex rather than an edge, twist about the vertical, sliding, bouncing, and a real contact's
energy loss (the impact law is the rigid one).
"""
from __future__ import annotations

import numpy as np

from ....analytic.motion import GroundMotion
from ....analytic.system import PlanarBody, System
from ...core.engines import get_engine


def system(spec) -> System:
    """The specimen (a specimen.Specimen, table frame) as the exact model's System: its mass and
    its two edges along the table's x on a fixed base."""
    return System.of_body(PlanarBody.from_resting(spec), mass=float(spec.mass))


def simulate(rock: System, acceleration, dt: float, pad: float = 5.0) -> tuple[bool, float, int]:
    """(overturned, peak φ/α of either edge against its own α, impacts) of the exact model's run
    under the table acceleration (m/s², step dt, linear between samples) and `pad` s of stillness
    after it (the registry's analytic engine: the compiled kernel)."""
    a = np.asarray(acceleration, dtype=float)
    motion = GroundMotion.from_array(a, dt=dt, units="m/s2", name="table")
    tr = get_engine("analytic").simulate(rock, motion, duration=(a.size - 1) * dt + pad)
    if tr.status.is_failure:
        raise RuntimeError(f"asymmetric model: the exact model's run failed: {tr.message}")
    return bool(tr.overturned), tr.edge_tilt_max, len(tr.impacts)
