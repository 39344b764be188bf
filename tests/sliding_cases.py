"""Random cases where the statue slips on its base (docs/sliding.md): case i is a function of i
alone (its own seeded generator), drawn over every base (fixed and each isolator kind), sizes
0.1–10 m, slenderness 1.2–5, friction around tanα (so that sliding, rocking and slide-rock all
occur), static above kinetic or equal, pulses scaled to the block's own thresholds, and in
one case of three a vertical component. Used by tests/test_sliding_kernel.py and
docs/scripts/sliding_kernel_agreement.py."""
from __future__ import annotations

import math

import numpy as np

from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.system import (BallInBowl, BallInCone, BilinearIsolator, DoubleFrictionPendulum,
                                     FrictionPendulum, System)

BASES = ("fixed", "linear", "bilinear", "friction-pendulum", "ball-in-bowl", "ball-in-cone",
         "double-friction-pendulum")
G = 9.81


def _system(base, height, width, mass, rng):
    if base == "fixed":
        return System.fixed(height=height, width=width, mass=mass)
    mb = mass * rng.uniform(0.5, 4.0)
    M = mass + mb
    if base == "linear":
        return System.isolated(height=height, width=width, mass=mass, base_mass=mb, period=rng.uniform(0.5, 3.0),
                               damping_ratio=rng.uniform(0.0, 0.3))
    if base == "bilinear":
        k0 = M * (2 * math.pi / rng.uniform(0.3, 1.0)) ** 2
        iso = BilinearIsolator(k0, rng.uniform(0.05, 0.3), rng.uniform(0.002, 0.02), rng.uniform(0.0, 0.1) * k0 / 50)
    elif base == "friction-pendulum":
        iso = FrictionPendulum(rng.uniform(0.5, 3.0), rng.uniform(0.02, 0.12))
    elif base == "ball-in-bowl":
        iso = BallInBowl(rng.uniform(0.5, 3.0), rng.uniform(0.005, 0.05))
    elif base == "ball-in-cone":
        iso = BallInCone(rng.uniform(0.05, 0.3), rng.uniform(0.005, 0.05))
    else:
        iso = DoubleFrictionPendulum(rng.uniform(0.5, 2.0), rng.uniform(0.01, 0.05), rng.uniform(0.5, 2.0),
                                     rng.uniform(0.05, 0.12))
    return System.with_isolator(height=height, width=width, mass=mass, base_mass=mb, isolator=iso)


def case(i: int):
    """(system, motion, duration) of case i."""
    rng = np.random.default_rng(1_000_003 + i)
    base = BASES[i % len(BASES)]
    height = 10 ** rng.uniform(-1, 1)
    lam = rng.uniform(1.2, 5.0)
    width = height / lam
    tan = 1 / lam
    # on a fixed base, friction around tanα and the pulse past what it takes to slide or tip;
    # an isolator transmits a fraction of the ground's push: lower friction, stronger pulses
    mu_s = tan * rng.uniform(0.4, 2.5) if base == "fixed" else rng.uniform(0.03, 0.35)
    mu_k = mu_s * (1.0 if rng.uniform() < 0.5 else rng.uniform(0.6, 1.0))
    system = _system(base, height, width, 10 ** rng.uniform(0, 3), rng).with_friction(mu_s, mu_k)
    p = system.p
    kind = ("sine", "cosine", "ricker")[int(rng.integers(3))]
    amp = min(mu_s, tan) * rng.uniform(1.1, 4.0) if base == "fixed" else rng.uniform(0.3, 1.5)
    freq = p / (2 * math.pi) * rng.uniform(0.5, 6.0)
    motion = GroundMotion.from_pulse(Pulse(kind, amp, freq, 1.0 if kind == "ricker" else float(rng.integers(1, 3))))
    if rng.uniform() < 1 / 3:
        motion = motion.with_vertical(GroundMotion.from_pulse(Pulse("sine", rng.uniform(0.05, 0.5),
                                                                    freq * rng.uniform(0.8, 3.0), 2.0)))
    duration = motion.last_time + 4.0 / p
    return system, motion, duration
