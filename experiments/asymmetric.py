"""The rigid rocking model of an asymmetric body on a fixed base (issue 21's stretch): a
planar rigid body that rocks about a forward edge (+x) with (α_f, R_f, I_f) and a backward
edge (−x) with (α_b, R_b, I_b), I about each edge, under the table's acceleration a(t).

Rocking about the forward edge by φ ≥ 0 (the body turns towards +x), in the table's frame
(gravity, and the inertial force −m·a at the centre of mass):

    I_f φ̈ = −m g R_f sin(α_f − φ) − m a R_f cos(α_f − φ)

and about the backward edge (turning towards −x) the same with b, and +m a. At rest it
lifts off forward when a < −g tan α_f, backward when a > g tan α_b.

Impact (φ back to 0, the other edge strikes; no bounce, no slide): angular momentum about
the striking edge is conserved. With the centre of mass at height h above the table and
b_f, b_b the horizontal distances from it to the two edges, the body's angular velocity
goes from ω to

    ω' = ω · (I_c + m (h² − b_f b_b)) / I_new,          I_new = I_c + m R_new²

(I_c about the centre of mass). For a symmetric rectangle (b_f = b_b = b, I_c = m R²/3) it
is Housner's 1 − 3/2 sin²α. The motion is integrated by classical RK4 at the record's step
with each impact located by linear interpolation of φ within the step; an impact that
leaves |ω'| below REST_RATE ends the rocking.

What it still leaves out (the 3-D hull in MuJoCo has it): rocking about a footprint vertex
rather than an edge, twist about the vertical, sliding, bouncing, and the impact's energy
loss of a real contact (the law above is the rigid one).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

REST_RATE = 1e-5  # rad/s
#: RK4 steps per sample: an impact is located within one step and the rest of that step
#: is lost, so the step must be short against the rocking (1.25 ms / 8 here: θmax/α within 0.2% of the exact model on the tests of tests/test_experiments.py).
SUBSTEPS = 8
OVERTURN_ANGLE = 0.5 * math.pi


def impact_ratio(I_c: float, m: float, h: float, b_from: float, b_to: float, R_to: float) -> float:
    """ω'/ω at an impact onto the edge at b_to (the body was on the edge at b_from)."""
    return (I_c + m * (h * h - b_from * b_to)) / (I_c + m * R_to * R_to)


@njit(cache=True)
def _rhs(phi, rate, a, side, alpha, R, I, m, g):
    # side 0: forward edge; 1: backward edge (the table's acceleration enters with opposite sign)
    sgn = -1.0 if side == 0 else 1.0
    return rate, (-m * g * R[side] * math.sin(alpha[side] - phi)
                  + sgn * m * a * R[side] * math.cos(alpha[side] - phi)) / I[side]


@njit(cache=True)
def _run(acc, dt, n_pad, alpha, R, I, ratio, m, g):
    """(overturned, peak φ/α of the edge it rocked on, impacts)."""
    n = acc.size + n_pad
    side, phi, rate = -1, 0.0, 0.0  # side −1: at rest
    peak, impacts = 0.0, 0
    tan_f, tan_b = math.tan(alpha[0]), math.tan(alpha[1])
    for i in range(n - 1):
        a0 = acc[i] if i < acc.size else 0.0
        a1 = acc[i + 1] if i + 1 < acc.size else 0.0
        if side < 0:
            if a0 < -g * tan_f:
                side = 0
            elif a0 > g * tan_b:
                side = 1
            else:
                continue
        am = 0.5 * (a0 + a1)
        k1p, k1r = _rhs(phi, rate, a0, side, alpha, R, I, m, g)
        k2p, k2r = _rhs(phi + 0.5 * dt * k1p, rate + 0.5 * dt * k1r, am, side, alpha, R, I, m, g)
        k3p, k3r = _rhs(phi + 0.5 * dt * k2p, rate + 0.5 * dt * k2r, am, side, alpha, R, I, m, g)
        k4p, k4r = _rhs(phi + dt * k3p, rate + dt * k3r, a1, side, alpha, R, I, m, g)
        new_phi = phi + dt / 6.0 * (k1p + 2 * k2p + 2 * k3p + k4p)
        new_rate = rate + dt / 6.0 * (k1r + 2 * k2r + 2 * k3r + k4r)
        if new_phi < 0.0:
            # an impact inside the step: the rate at the crossing, by linear interpolation
            f = phi / (phi - new_phi) if phi > new_phi else 1.0
            hit_rate = rate + f * (new_rate - rate)
            impacts += 1
            w = -hit_rate * ratio[side]  # now on the other edge, turning away from it
            side = 1 - side
            if w < REST_RATE:
                side, phi, rate = -1, 0.0, 0.0
            else:
                phi, rate = 0.0, w
            continue
        phi, rate = new_phi, new_rate
        if phi / alpha[side] > peak:
            peak = phi / alpha[side]
        if phi >= OVERTURN_ANGLE:
            return True, peak, impacts
    return bool(side >= 0 and phi > alpha[side]), peak, impacts


def parameters(spec) -> dict:
    """The model's parameters from a specimen.Specimen (table frame)."""
    fw, bw = spec.direction(1), spec.direction(-1)
    I_c = float(spec.inertia[1, 1])
    h = fw["h"]
    return dict(alpha=np.array([fw["alpha"], bw["alpha"]]), R=np.array([fw["R"], bw["R"]]),
                I=np.array([fw["I_O"], bw["I_O"]]), m=float(spec.mass), g=9.81,
                ratio=np.array([impact_ratio(I_c, spec.mass, h, fw["b"], bw["b"], bw["R"]),
                                impact_ratio(I_c, spec.mass, h, bw["b"], fw["b"], fw["R"])]))


def simulate(params: dict, acceleration, dt: float, pad: float = 5.0,
             substeps: int = SUBSTEPS) -> tuple[bool, float, int]:
    """(overturned, peak φ/α, impacts) under the table acceleration (m/s², step dt, linear
    between samples), integrated at dt/substeps."""
    p = params
    a = np.asarray(acceleration, dtype=float)
    if substeps > 1:
        a = np.interp(np.arange((a.size - 1) * substeps + 1) / substeps, np.arange(a.size), a)
        dt = dt / substeps
    return _run(np.ascontiguousarray(a), float(dt), int(round(pad / dt)),
                p["alpha"], p["R"], p["I"], p["ratio"], p["m"], p["g"])
