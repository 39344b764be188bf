"""An independent oracle for the bilinear bearing's steady state under harmonic input
(issue 22, docs/isolators.md "Bilinear steady state under harmonic input").

The base in pure translation under ẍg(t) = A·sin(ωt):

    M ü + c u̇ + r·k0·u + q = −M·A·sin(ωt),

q the elastic–perfectly-plastic element of stiffness k_e = (1 − r)·k0 yielding at u_y
(F_s = k_e·u_y). Between switches the equation is linear with constant coefficients, so each
segment has a closed form (a constant + the harmonic particular solution + a damped free
vibration fitted to the segment's initial state):

- elastic, slider fixed at u_p: K = k0, constant force k_e·u_p;
- plastic in direction σ (slider moving with the base): K = r·k0, constant force −σ·F_s.

Switches: an elastic segment yields when u − u_p reaches ±u_y; a plastic one unloads when u̇
reaches 0. Their times are the first roots of those closed forms, bracketed on a fine grid and
polished by Brent's method. The symmetric periodic orbit (the state at t + T/2 is minus the
state at t) is found by shooting on the half-cycle map from a positive peak (u = U, u̇ = 0 at
t = τ, slider at U − u_y): elastic until u = U − 2u_y, plastic (σ = −1) until u̇ = 0, which
must happen at τ + T/2 with u = −U. Two unknowns (U, τ), two equations, solved by
scipy.optimize.root from a guess that the same closed-form segments give when run from rest.

Deliberately independent of the code under test: numpy, scipy and the segment closed forms
only; nothing from isorock.analytic's integrators or physics is imported here (the tests
build the System and run the engines; this module only knows numbers).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq, root

GRID = 4000  # grid points per forcing period used to bracket the first root of a switch
XTOL = 1e-15  # Brent's absolute tolerance on switch times (s); its rtol is 4 eps


@dataclass(frozen=True)
class Segment:
    """u(t) of M ü + c u̇ + K u = F0 − M·A·sin(ωt) from u(t0) = u0, u̇(t0) = v0, K > 0 and
    underdamped (ζ < 1, checked)."""

    M: float
    c: float
    K: float
    F0: float
    A: float
    w: float
    t0: float
    u0: float
    v0: float

    def __post_init__(self):
        M, c, K, w = self.M, self.c, self.K, self.w
        d, e = K - M * w * w, c * w
        det = d * d + e * e
        xs, xc = -M * self.A * d / det, M * self.A * e / det  # particular: F0/K + xs sin ωt + xc cos ωt
        wn = math.sqrt(K / M)
        z = c / (2.0 * math.sqrt(K * M))
        if not z < 1.0:
            raise ValueError(f"segment with ζ = {z:.3g} ≥ 1: the oracle only has the underdamped closed form")
        s, wd = z * wn, wn * math.sqrt(1.0 - z * z)
        h0 = self.u0 - (self.F0 / K + xs * math.sin(w * self.t0) + xc * math.cos(w * self.t0))
        hd0 = self.v0 - (xs * w * math.cos(w * self.t0) - xc * w * math.sin(w * self.t0))
        for name, value in (("xs", xs), ("xc", xc), ("s", s), ("wd", wd), ("c1", h0), ("c2", (hd0 + s * h0) / wd)):
            object.__setattr__(self, name, value)

    def u(self, t):
        t = np.asarray(t, dtype=float)
        x = t - self.t0
        part = self.F0 / self.K + self.xs * np.sin(self.w * t) + self.xc * np.cos(self.w * t)
        return part + np.exp(-self.s * x) * (self.c1 * np.cos(self.wd * x) + self.c2 * np.sin(self.wd * x))

    def v(self, t):
        t = np.asarray(t, dtype=float)
        x = t - self.t0
        w, s, wd = self.w, self.s, self.wd
        part = w * (self.xs * np.cos(w * t) - self.xc * np.sin(w * t))
        ex = np.exp(-s * x)
        return part + ex * ((self.c2 * wd - s * self.c1) * np.cos(wd * x)
                            - (self.c1 * wd + s * self.c2) * np.sin(wd * x))

    def acc(self, t):
        """ü from the equation itself."""
        t = np.asarray(t, dtype=float)
        return (self.F0 - self.M * self.A * np.sin(self.w * t) - self.c * self.v(t) - self.K * self.u(t)) / self.M


def first_root(f, t0, span, grid):
    """The first t in (t0, t0 + span] where f changes sign (f(t0) is taken as its sign just
    after t0), bracketed on `grid` points and polished by Brent; None if there is none."""
    ts = t0 + np.linspace(0.0, span, grid + 1)
    fs = f(ts)
    fs[0] = fs[1]  # a segment starts on its own switch (|u − u_p| = u_y, u̇ = 0) up to rounding
    change = np.nonzero(np.sign(fs[1:]) != np.sign(fs[:-1]))[0]
    if change.size == 0:
        return None
    i = int(change[0])
    if fs[i + 1] == 0.0:
        return float(ts[i + 1])
    return brentq(lambda t: float(f(t)), ts[i], ts[i + 1], xtol=XTOL, rtol=4 * np.finfo(float).eps)


@dataclass(frozen=True)
class Bearing:
    """The case: total mass M (kg, block + base), dashpot c, initial stiffness k0, post-yield
    ratio r (0 < r < 1), yield displacement u_y (m), ground acceleration A (m/s²) at ω (rad/s)."""

    M: float
    c: float
    k0: float
    r: float
    u_y: float
    A: float
    w: float

    @property
    def k_p(self):
        return self.r * self.k0

    @property
    def k_e(self):
        return (1.0 - self.r) * self.k0

    @property
    def f_s(self):
        return self.k_e * self.u_y

    @property
    def period(self):
        return 2.0 * math.pi / self.w

    def elastic(self, t0, u0, v0, u_p):
        return Segment(self.M, self.c, self.k0, self.k_e * u_p, self.A, self.w, t0, u0, v0)

    def plastic(self, t0, u0, v0, sigma):
        return Segment(self.M, self.c, self.k_p, -sigma * self.f_s, self.A, self.w, t0, u0, v0)

    # --- the half-cycle map from a positive peak ----------------------------------------------
    def half_cycle(self, U, tau):
        """From the peak u = U, u̇ = 0 at τ (slider at U − u_y, elastic): the yield time t1 (u
        reaches U − 2u_y), the next peak's time t2 (u̇ = 0 in the plastic segment, σ = −1) and
        u(t2), with the two segments. Raises if the orbit is not of this type (re-yield the same
        way, or no yield within a period)."""
        u_p = U - self.u_y
        el = self.elastic(tau, U, 0.0, u_p)
        span, grid = self.period, GRID
        t1 = first_root(lambda t: np.abs(el.u(t) - u_p) - self.u_y, tau, span, grid)
        if t1 is None:
            raise ValueError("no yield within a period after the peak: not a yielding orbit")
        if el.u(t1) - u_p > 0:
            raise ValueError("re-yields the same way after the peak: not the two-segment orbit")
        pl = self.plastic(t1, float(el.u(t1)), float(el.v(t1)), -1)
        if not pl.v0 < 0:
            raise ValueError("yields while moving the wrong way")
        t2 = first_root(pl.v, t1, span, grid)
        if t2 is None:
            raise ValueError("the plastic segment does not stop within a period")
        return t1, t2, float(pl.u(t2)), el, pl

    def steady_state(self, guess=None):
        """The symmetric periodic orbit: a SteadyState."""
        U, tau = guess if guess is not None else self.settle()
        T = self.period

        def residual(x):
            t1, t2, u2, _, _ = self.half_cycle(x[0], x[1])
            return [(u2 + x[0]) / self.u_y, (t2 - x[1] - 0.5 * T) / T]

        sol = root(residual, [U, tau], method="hybr", options={"xtol": 1e-15})
        U, tau = float(sol.x[0]), float(sol.x[1]) % T  # the segments below start at the τ stored
        res = residual([U, tau])
        if max(abs(res[0]) * self.u_y / U, abs(res[1])) > 1e-13:
            raise ValueError(f"the shooting did not converge: {res}, {sol.message}")
        t1, t2, _, el, pl = self.half_cycle(U, tau)
        return SteadyState(self, U, tau, t1 - tau, el, pl, t1, t2)

    def settle(self, cycles=60):
        """(U, τ) of the last positive peak after `cycles` periods from rest: the closed-form
        segments stepped from switch to switch (the shooting's starting guess)."""
        t, u, v, phase, u_p = 0.0, 0.0, 0.0, 0, 0.0
        peak = None
        t_end = cycles * self.period
        while t < t_end:
            if phase == 0:
                seg = self.elastic(t, u, v, u_p)
                t_next = first_root(lambda s: np.abs(seg.u(s) - u_p) - self.u_y, t, self.period, GRID)
                if t_next is None:  # no yield within this period: go on elastic from its end
                    t, u, v = t + self.period, float(seg.u(t + self.period)), float(seg.v(t + self.period))
                    continue
                u, v = float(seg.u(t_next)), float(seg.v(t_next))
                phase = 1 if u - u_p > 0 else -1
            else:
                seg = self.plastic(t, u, v, phase)
                t_next = first_root(seg.v, t, self.period, GRID)
                if t_next is None:
                    raise ValueError("a plastic segment does not stop within a period")
                u, v = float(seg.u(t_next)), 0.0
                if phase == 1:
                    peak = (u, t_next)
                u_p, phase = u - phase * self.u_y, 0
            t = t_next
        return peak[0], peak[1] % self.period


@dataclass(frozen=True)
class SteadyState:
    """The symmetric periodic orbit of a Bearing: amplitude U (m), the phase τ (s, in [0, T)) of
    the positive peak, the time from a peak to the next yield t_yield (s), and the two segments
    of the half cycle [τ, τ + T/2] (elastic on [τ, t1], plastic σ = −1 on [t1, t2])."""

    case: Bearing
    U: float
    tau: float
    t_yield: float
    elastic: Segment
    plastic: Segment
    t1: float
    t2: float

    @property
    def loop_area(self):
        """Hysteretic energy per cycle: F_s × the slider's travel, 2·(2U − 2u_y) a cycle."""
        return self.case.f_s * 4.0 * (self.U - self.case.u_y)

    def work_per_cycle(self):
        """(input work ∫ −M ẍg u̇ dt, viscous loss ∫ c u̇² dt) over one cycle, by quadrature of
        the closed forms (twice the half cycle, by symmetry): the loop area's independent check."""
        b = self.case
        win = dis = 0.0
        for seg, a, z in ((self.elastic, self.tau, self.t1), (self.plastic, self.t1, self.t2)):
            win += quad(lambda t: -b.M * b.A * math.sin(b.w * t) * float(seg.v(t)), a, z,
                        epsabs=0.0, epsrel=1e-13, limit=200)[0]
            dis += quad(lambda t: b.c * float(seg.v(t)) ** 2, a, z, epsabs=0.0, epsrel=1e-13, limit=200)[0]
        return 2.0 * win, 2.0 * dis

    def base_acceleration(self, t):
        """Absolute base acceleration a = ü + ẍg = −(c u̇ + r k0 u + q)/M on the half cycle."""
        b = self.case
        t = np.asarray(t, dtype=float)
        u_p = self.U - b.u_y
        el, pl = self.elastic, self.plastic
        q = np.where(t <= self.t1, b.k_e * (el.u(t) - u_p), -b.f_s)  # σ = −1 on the plastic segment
        u = np.where(t <= self.t1, el.u(t), pl.u(t))
        v = np.where(t <= self.t1, el.v(t), pl.v(t))
        return -(b.c * v + b.k_p * u + q) / b.M

    def max_abs_acceleration(self):
        """max |a| over the orbit (the half cycle suffices, by symmetry): each segment's grid
        maximum, polished by Brent on the slope of |a| (a is smooth within a segment; its ends,
        where the slope jumps at the yield, are candidates too)."""
        h = 1e-7 * self.case.period
        best = 0.0
        for a, z in ((self.tau, self.t1), (self.t1, self.t2)):
            ts = np.linspace(a, z, GRID + 1)
            f = np.abs(self.base_acceleration(ts))
            best = max(best, float(f[0]), float(f[-1]))
            i = int(np.argmax(f))
            if 0 < i < GRID:

                def slope(t):
                    return float(np.abs(self.base_acceleration(t + h)) - np.abs(self.base_acceleration(t - h)))
                if slope(ts[i - 1]) > 0 > slope(ts[i + 1]):
                    best = max(best, float(np.abs(self.base_acceleration(brentq(slope, ts[i - 1], ts[i + 1],
                                                                                      xtol=1e-14)))))
                else:
                    best = max(best, float(f[i]))
        return best

    def first_time_above(self, threshold):
        """The first time after the peak τ where |a| reaches `threshold` (on the half cycle), or None."""
        for a, z in ((self.tau, self.t1), (self.t1, self.t2)):
            t = first_root(lambda s: np.abs(self.base_acceleration(s)) - threshold, a, z - a, GRID)
            if t is not None:
                return t
        return None


def linear_steady_state(M, c, k, A, w):
    """The classical steady state of M ü + c u̇ + k u = −M A sin ωt (a textbook closed form):
    u = −X sin(ωt − φ), X = M A / √((k − M ω²)² + (c ω)²), φ = atan2(c ω, k − M ω²); (X, φ)."""
    X = M * A / math.hypot(k - M * w * w, c * w)
    return X, math.atan2(c * w, k - M * w * w)


def uplift_amplitude(case: Bearing, threshold: float, lo: float, hi: float, rtol: float = 1e-10):
    """The ground amplitude A* (m/s²) in [lo, hi] at which the steady state's largest |a| is
    `threshold` (g·tanα: the block resting on the base lifts where |a| exceeds it): below A*
    the steady state never lifts the block, above it it does. Brent on A, each steady state
    shot from the last one (the orbit moves continuously with A)."""
    guess = [None]

    def excess(A):
        b = Bearing(case.M, case.c, case.k0, case.r, case.u_y, A, case.w)
        s = b.steady_state(guess[0])
        guess[0] = (s.U, s.tau)
        return s.max_abs_acceleration() - threshold
    return brentq(excess, lo, hi, rtol=rtol)
