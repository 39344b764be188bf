"""An oracle: a separate integrator of the rigid rocking model of an asymmetric body on a fixed
base, written from its equations apart from isorock.analytic (issue 21's stretch; since issue 36
the shake-table study runs the exact model's two edges, experiments/asymmetric.py, and this RK4
checks it: tests/test_two_edges.py, tests/test_experiments.py). A
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
is Housner's 1 − 3/2 sin²α.

The motion is integrated by classical RK4 at a fixed fraction of the record's step, the
table's acceleration linear between samples and zero after the record (as the exact model
reads it), with every event located where it happens rather than at a step's end: lift-off
from rest where the linear acceleration passes g·tanα of an edge, and each impact at the
crossing φ = 0 of the step's own RK4 map (bisection to rounding), after which the rest of
the step is integrated on the other edge. An impact whose incoming |ω| is below the exact
model's rest floor (rest_floor) ends the rocking. With α, R, I and the ratio the same on
both edges it is the symmetric block, and it gives the exact model's verdict on every
measured record (docs/scripts/asymmetric_agreement.py). An earlier version dropped the rest
of the step after each impact and ended the rocking on a fixed rate floor: a time error of
up to a step per impact, which hundreds of impacts turned into wrong verdicts on 13–14 of
305 records, still 6–8 at 128 steps per sample.

What it still leaves out (the 3-D hull in MuJoCo has it): rocking about a footprint vertex
rather than an edge, twist about the vertical, sliding, bouncing, and the impact's energy
loss of a real contact (the law above is the rigid one).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from isorock.analytic.system import STANDARD_GRAVITY

#: RK4 steps per sample of the record. Each impact is located within its step (the crossing
#: φ = 0 of the step's own RK4 map, by bisection to rounding) and the rest of the step is
#: integrated after it, so the steps only set the smooth flight's error, O(h⁴). At 8 the
#: symmetric block gives the exact model's verdict on all 305 records of each specimen, θmax/α
#: within 5e-6 on the non-chaotic ones (at 4, two chaotic SP2 records part; 8 costs ~1.5 s
#: of CPU per 305 runs; docs/scripts/asymmetric_agreement.py).
SUBSTEPS = 8
OVERTURN_ANGLE = 0.5 * math.pi
#: a run with more impacts than this stops (a guard against an endless chatter; the exact
#: model's AnalyticSettings.max_events is the same idea)
MAX_IMPACTS = 200_000


def impact_ratio(I_c: float, m: float, h: float, b_from: float, b_to: float, R_to: float) -> float:
    """ω'/ω at an impact onto the edge at b_to (the body was on the edge at b_from)."""
    return (I_c + m * (h * h - b_from * b_to)) / (I_c + m * R_to * R_to)


@njit(cache=True)
def _rhs(phi, a, side, alpha, R, I, m, g):
    # φ̈; side 0: forward edge; 1: backward edge (the table's acceleration enters with opposite sign)
    sgn = -1.0 if side == 0 else 1.0
    return (-m * g * R[side] * math.sin(alpha[side] - phi)
            + sgn * m * a * R[side] * math.cos(alpha[side] - phi)) / I[side]


@njit(cache=True)
def _rk4(phi, rate, tau, h, a0, slope, side, alpha, R, I, m, g):
    """One RK4 step of length h from local time τ, the table's acceleration a0 + slope·τ
    (linear within a sample interval, as the exact model reads a record)."""
    am, a1 = a0 + slope * (tau + 0.5 * h), a0 + slope * (tau + h)
    k1r = _rhs(phi, a0 + slope * tau, side, alpha, R, I, m, g)
    k2p = rate + 0.5 * h * k1r
    k2r = _rhs(phi + 0.5 * h * rate, am, side, alpha, R, I, m, g)
    k3p = rate + 0.5 * h * k2r
    k3r = _rhs(phi + 0.5 * h * k2p, am, side, alpha, R, I, m, g)
    k4p = rate + h * k3r
    k4r = _rhs(phi + h * k3p, a1, side, alpha, R, I, m, g)
    return (phi + h / 6.0 * (rate + 2 * k2p + 2 * k3p + k4p),
            rate + h / 6.0 * (k1r + 2 * k2r + 2 * k3r + k4r))


@njit(cache=True)
def _first_zero(phi, rate, tau, hi, which, a0, slope, side, alpha, R, I, m, g):
    """The step length s in (0, hi] at which the step's RK4 map crosses zero in φ (which 0)
    or in φ̇ (which 1), by bisection: the sign at s → 0⁺ is taken from the start (φ ≥ 0 at a
    step's start, also at a rocking phase's start at φ = 0, so the trivial root s = 0 is never
    returned), the end's is opposite. Bisection to rounding: ~50 halvings of a fraction of a ms."""
    lo = 0.0
    pos = (rate > 0.0) if which == 1 else True
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        p, r = _rk4(phi, rate, tau, mid, a0, slope, side, alpha, R, I, m, g)
        v = r if which == 1 else p
        if (v > 0.0) == pos and v != 0.0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 4e-16 * hi:
            break
    return hi


@njit(cache=True)
def _run(acc, dt, substeps, n_pad, alpha, R, I, ratio, rest, m, g, side, phi):
    """(overturned, peak φ/α of the edge it rocked on, impacts). acc: the record (m/s²) at
    step dt, linear between samples and zero after its end (the exact model's reading); n_pad
    sample intervals of stillness after it; released from rest at φ on edge `side` (−1: at
    rest on the table)."""
    rate = 0.0
    peak, impacts = (phi / alpha[side] if side >= 0 else 0.0), 0
    thr_f, thr_b = g * math.tan(alpha[0]), g * math.tan(alpha[1])
    h = dt / substeps
    for i in range(acc.size - 1 + n_pad):
        if i < acc.size - 1:
            a0, slope = acc[i], (acc[i + 1] - acc[i]) / dt
        else:
            a0, slope = 0.0, 0.0
        tau = 0.0
        for k in range(substeps):
            t_end = dt if k == substeps - 1 else (k + 1) * h
            while tau < t_end:
                if side < 0:
                    # at rest: lift off where the (linear) acceleration first passes g·tanα of an edge
                    a_now, a_end = a0 + slope * tau, a0 + slope * t_end
                    if a_now < -thr_f:
                        side = 0
                    elif a_now > thr_b:
                        side = 1
                    elif a_end < -thr_f:
                        side, tau = 0, (-thr_f - a0) / slope
                    elif a_end > thr_b:
                        side, tau = 1, (thr_b - a0) / slope
                    else:
                        tau = t_end
                        continue
                    phi, rate = 0.0, 0.0
                    if tau >= t_end:
                        continue
                s = t_end - tau
                new_phi, new_rate = _rk4(phi, rate, tau, s, a0, slope, side, alpha, R, I, m, g)
                hit = new_phi < 0.0
                if not hit and rate < 0.0 and new_rate > 0.0:
                    # φ turned back up inside the step: an impact at its minimum would be missed
                    sm = _first_zero(phi, rate, tau, s, 1, a0, slope, side, alpha, R, I, m, g)
                    if _rk4(phi, rate, tau, sm, a0, slope, side, alpha, R, I, m, g)[0] < 0.0:
                        hit, s = True, sm
                if hit:
                    # the impact: at the step's own crossing of φ = 0, then the rest of the step
                    s = _first_zero(phi, rate, tau, s, 0, a0, slope, side, alpha, R, I, m, g)
                    w_pre = _rk4(phi, rate, tau, s, a0, slope, side, alpha, R, I, m, g)[1]
                    tau += s
                    impacts += 1
                    if impacts > MAX_IMPACTS:
                        return False, peak, impacts  # simulate refuses it
                    if abs(w_pre) < rest[side]:
                        side = -1  # the Zeno tail ends at the exact model's rest floor
                    else:
                        rate = -w_pre * ratio[side]  # now on the other edge, turning away from it
                        side = 1 - side
                    phi = 0.0
                    if side < 0:
                        rate = 0.0
                    continue
                phi, rate, tau = new_phi, new_rate, t_end
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
                I=np.array([fw["I_O"], bw["I_O"]]), m=float(spec.mass), g=STANDARD_GRAVITY,
                ratio=np.array([impact_ratio(I_c, spec.mass, h, fw["b"], bw["b"], bw["R"]),
                                impact_ratio(I_c, spec.mass, h, bw["b"], fw["b"], fw["R"])]))


def rest_floor(params: dict) -> np.ndarray:
    """The rate (rad/s) below which an impact ends the rocking, per edge: the exact model's
    floor (AnalyticSettings.rest_velocity·p·α, analytic/settings.py) on that edge's α and p,
    so the symmetric case ends its Zeno tail where the exact model does."""
    from isorock.analytic.settings import AnalyticSettings
    p = params
    freq = np.sqrt(p["m"] * p["g"] * p["R"] / p["I"])
    return AnalyticSettings().rest_velocity * freq * p["alpha"]


def simulate(params: dict, acceleration, dt: float, pad: float = 5.0,
             substeps: int = SUBSTEPS, phi0: float = 0.0) -> tuple[bool, float, int]:
    """(overturned, peak φ/α, impacts) under the table acceleration (m/s², step dt, linear
    between samples, zero after the record), RK4 at dt/substeps between impacts located
    within their step; `pad` s of stillness after the record. phi0 (rad): released from rest
    tilted onto the forward edge (> 0) or the backward edge (< 0), for free rocking."""
    p = params
    a = np.ascontiguousarray(np.asarray(acceleration, dtype=float))
    side = -1 if phi0 == 0.0 else (0 if phi0 > 0.0 else 1)
    out = _run(a, float(dt), int(substeps), int(round(pad / dt)), p["alpha"], p["R"], p["I"],
               p["ratio"], rest_floor(p), p["m"], p["g"], side, abs(float(phi0)))
    if out[2] > MAX_IMPACTS:
        raise RuntimeError(f"asymmetric model: more than {MAX_IMPACTS} impacts (an endless chatter)")
    return out
