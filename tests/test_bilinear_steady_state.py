"""The bilinear bearing's steady state under a harmonic ground acceleration, and the uplift
boundary it sets, against an independent oracle (issue 22, docs/isolators.md "Bilinear steady
state under harmonic input").

The block rests (pure translation): M ü + c u̇ + r·k0·u + q = −M·A·sin ωt, q the
elastic–perfectly-plastic element. tests/bilinear_oracle.py finds the symmetric periodic orbit
from the closed forms of the linear segments (no code of the engines). Both analytic engines
are started on the orbit (at a positive peak, where the bearing's slider is where a virgin
bearing pushed there would have it: u − u_y) under the sine shifted to the orbit's phase, so
no transient has to decay, and must stay on it: the same peaks (amplitude and phase), yields,
history, loop area and work per cycle to 1e-9. Limits: r → 1 and an amplitude too small to
yield, both the textbook damped oscillator. The uplift boundary: the largest A whose steady
state keeps |ü + ẍg| below g·tanα; the engines lift just above it, where the oracle says, and
not just below.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from bilinear_oracle import Bearing, linear_steady_state, uplift_amplitude
from isorock.analytic import load_motion
from isorock.analytic.hybrid import simulate
from isorock.analytic.system import STANDARD_GRAVITY, BilinearIsolator, System
from isorock.validate.core.tolerances import tolerance

pytestmark = pytest.mark.isolator_kernel

try:
    from isorock.analytic.fast import simulate_fast
except ImportError:  # numba missing: the reference path alone
    simulate_fast = None

LIMIT = tolerance("analytic", "bilinear_steady_state").limit
G = STANDARD_GRAVITY  # a pulse's amp is in g: A = amp·G, the product the engines take
PAPER = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)  # tanα 0.35: rests in every case below
SLENDER = dict(height=2.0, width=0.2, mass=3800.0, base_mass=3800.0)  # tanα 0.1: the uplift boundary
M = 7600.0
K0, R, U_Y = 3e5, 0.1, 0.01  # initial period 1.0 s, post-yield 3.2 s, F_s = 2700 N
C = 2 * 0.05 * math.sqrt(K0 * M)  # 5% of critical on k0 (16% on r·k0): underdamped in both segments
RUNS = [pytest.param(simulate, id="reference"),
        pytest.param(simulate_fast, id="kernel",
                     marks=pytest.mark.skipif(simulate_fast is None, reason="numba is not installed"))]
CASES = [(0.1, 0.8), (0.2, 0.6)]  # (amp in g, freq in Hz): post-yield resonance side, yielding every half cycle


def system(block=PAPER, r=R, u_y=U_Y):
    return System.with_isolator(**block, isolator=BilinearIsolator(
        stiffness=K0, post_yield_ratio=r, yield_displacement=u_y, damping=C))


def sine(amp, freq, shift, duration):
    """ẍg(t) = amp·g·sin(ω(t + shift)) on [0, duration]: the pulse's closed form, trimmed."""
    cycles = math.ceil((duration + shift) * freq) + 1
    return load_motion(f"sine:amp={amp!r},freq={freq!r},cycles={cycles}").trimmed(shift)


@functools.lru_cache(maxsize=None)
def orbit(amp, freq, r=R, u_y=U_Y):
    return Bearing(M, C, K0, r, u_y, amp * G, 2 * math.pi * freq).steady_state()


def run_on_orbit(run, s, amp, freq, periods, block=PAPER):
    """The engine started at the orbit's positive peak (u = U, u̇ = 0, t = τ of the input), on
    the bearing built here (not from the oracle's numbers: a wrong oracle must show)."""
    T = 1.0 / freq
    return run(system(block), sine(amp, freq, s.tau, periods * T), duration=periods * T, u0=s.U, u_dot0=0.0)


def oracle_u(s, t):
    """The orbit's u at run time t (the run starts at the peak τ): half cycles alternate sign."""
    T2 = 0.5 * s.case.period
    k = np.floor(t / T2)
    ta = s.tau + (t - k * T2)
    return np.where(ta <= s.t1, s.elastic.u(ta), s.plastic.u(ta)) * (-1.0) ** k


def per_cycle(tr, log, k, T):
    """The increase of an energy log over the k-th period [kT, (k+1)T] (both ends are peaks, stored)."""
    return float(np.interp((k + 1) * T, tr.t, log) - np.interp(k * T, tr.t, log))


# --- the oracle's own checks ------------------------------------------------------------------

@pytest.mark.parametrize("amp, freq", CASES)
def test_oracle_loop_area_is_the_work_balance(amp, freq):
    """Over a period the springs and the mass return to their state, so the loop area F_s × the
    slider's travel (4 F_s (U − u_y)) is the input work minus the viscous loss, both integrated
    by quadrature of the closed forms; and the orbit found is a symmetric periodic one."""
    s = orbit(amp, freq)
    w_in, viscous = s.work_per_cycle()
    assert abs((w_in - viscous) / s.loop_area - 1) <= 1e-12
    t1, t2, u2, _, _ = s.case.half_cycle(s.U, s.tau)
    assert abs(u2 + s.U) <= 1e-13 * s.U and abs(t2 - s.tau - 0.5 * s.case.period) <= 1e-13
    assert s.U > U_Y and s.max_abs_acceleration() < G * PAPER["width"] / PAPER["height"]  # yields; rests


def test_oracle_tends_to_the_linear_oscillator():
    """r → 1: the element (k_e = (1 − r)k0, F_s ≤ 3e-9 N here) vanishes; the orbit is the textbook
    steady state of M ü + c u̇ + r k0 u = −M A sin ωt (amplitude and the peak's phase)."""
    r = 1 - 1e-12
    s = orbit(0.1, 0.8, r=r)
    X, phi = linear_steady_state(M, C, r * K0, 0.1 * G, 2 * math.pi * 0.8)
    T = s.case.period
    assert abs(s.U / X - 1) <= 1e-12
    peak = ((phi - 0.5 * math.pi) / s.case.w) % T  # u = −X sin(ωt − φ) is +X where ωt − φ = −π/2
    assert abs((s.tau - peak + 0.5 * T) % T - 0.5 * T) <= 1e-12


# --- the engines on the orbit -----------------------------------------------------------------

@pytest.mark.parametrize("amp, freq", CASES)
@pytest.mark.parametrize("run", RUNS)
def test_engines_hold_the_steady_state(run, amp, freq):
    """Started on the orbit, 3 periods: the block never lifts; every yield (u = ±(U − 2u_y), at
    τ + t_yield + kT/2) and every unload (a peak ±U at τ + kT/2: the amplitude and the phase)
    where the oracle has it; u at every stored point; per period the hysteretic loss equals the
    loop area and so does the input work minus the viscous loss."""
    s = orbit(amp, freq)
    T, U = s.case.period, s.U
    tr = run_on_orbit(run, s, amp, freq, 3)
    assert tr.uplifts == 0 and np.all(tr.mode == 0)
    assert s.max_abs_acceleration() < tr.system.uplift_acceleration  # why: the oracle's orbit rests
    events = [e for e in tr.extras["isolator_events"] if e[0] < 3 * T - 1e-6]
    assert len(events) == 11  # 6 yields, 5 unloads before the end
    for k, (t, phase, u) in enumerate(events):
        half, sign = k // 2, (-1) ** (k // 2)
        if k % 2 == 0:  # yield in the half cycle's direction −sign
            assert phase == -sign
            assert abs(t - (s.t_yield + half * 0.5 * T)) <= LIMIT
            assert abs(u - sign * (U - 2 * U_Y)) <= LIMIT * U
        else:  # unload at the next peak
            assert phase == 0
            assert abs(t - (half + 1) * 0.5 * T) <= LIMIT
            assert abs(u + sign * U) <= LIMIT * U
    assert abs(tr.u_max / U - 1) <= LIMIT
    assert np.max(np.abs(tr.u - oracle_u(s, tr.t))) <= LIMIT * U
    e = tr.energy
    for k in range(3):
        assert abs(per_cycle(tr, e.isolator_loss, k, T) / s.loop_area - 1) <= LIMIT
        work = per_cycle(tr, e.ground_work, k, T) - per_cycle(tr, e.dashpot_loss, k, T)
        assert abs(work / s.loop_area - 1) <= LIMIT


@pytest.mark.parametrize("amp, freq", CASES)
@pytest.mark.skipif(simulate_fast is None, reason="numba is not installed")
def test_kernel_settles_from_rest_onto_the_orbit(amp, freq):
    """From rest (virgin bearing) under the unshifted sine the transient decays onto the oracle's
    orbit, the attractor: after 40 periods the last two cycles' peaks are ±U at τ + kT/2 to 1e-9
    (the transient left is 1.3e-9 and 3.6e-7 of U after 20 periods, ≤ 2e-13 after 40: measured).
    The kernel only: 40 periods cost it 0.02 s, the reference 3 s."""
    s = orbit(amp, freq)
    T = 1.0 / freq
    tr = simulate_fast(system(), sine(amp, freq, 0.0, 40 * T), duration=40 * T)
    peaks = [(t, u) for t, phase, u in tr.extras["isolator_events"] if phase == 0][-4:]
    assert len(peaks) == 4 and tr.uplifts == 0
    for t, u in peaks:
        assert abs(abs(u) / s.U - 1) <= LIMIT
        assert abs(((t - s.tau) + 0.25 * T) % (0.5 * T) - 0.25 * T) <= LIMIT  # on τ + kT/2
        assert (u > 0) == (round((t - s.tau) / (0.5 * T)) % 2 == 0)  # +U at τ + kT, −U half a period on


def fitted(tr, w):
    """Amplitude X and phase φ of u ≈ −X sin(ωt − φ), by least squares on the stored points."""
    basis = np.column_stack([np.sin(w * tr.t), np.cos(w * tr.t)])
    (a, b), *_ = np.linalg.lstsq(basis, tr.u, rcond=None)  # u = a sin ωt + b cos ωt
    return math.hypot(a, b), math.atan2(b, -a)  # −X sin(ωt − φ) = −X cos φ sin ωt + X sin φ cos ωt


@pytest.mark.parametrize("limit", ["elastic", "r-to-1"])
@pytest.mark.parametrize("run", RUNS)
def test_engines_tend_to_the_linear_oscillator(run, limit):
    """Two limits, started on the textbook steady state u = −X sin(ωt − φ) of M ü + c u̇ + k u =
    −M A sin ωt: an amplitude so small that the bearing never yields (k = k0: X = 3.4 mm < u_y)
    and r → 1 (k = r k0; the element's force is at most F_s = 3e-9 N). The run's amplitude and
    phase (fitted over 3 periods) and u at every stored point are the textbook's."""
    amp, freq = (0.005, 0.8) if limit == "elastic" else (0.1, 0.8)
    r = R if limit == "elastic" else 1 - 1e-12
    k = K0 if limit == "elastic" else r * K0
    w = 2 * math.pi * freq
    X, phi = linear_steady_state(M, C, k, amp * G, w)
    T = 2 * math.pi / w
    tr = run(system(r=r), sine(amp, freq, 0.0, 3 * T), duration=3 * T,
             u0=X * math.sin(phi), u_dot0=-X * w * math.cos(phi))
    if limit == "elastic":
        assert X < U_Y and tr.extras["isolator_events"] == () and tr.energy.isolator_loss[-1] == 0.0
    assert tr.uplifts == 0
    assert np.max(np.abs(tr.u + X * np.sin(w * tr.t - phi))) <= LIMIT * X
    X_run, phi_run = fitted(tr, w)
    assert abs(X_run / X - 1) <= LIMIT and abs(phi_run - phi) <= LIMIT
    assert abs(tr.u_max / X - 1) <= LIMIT


# --- the uplift boundary ---------------------------------------------------------------------

@functools.lru_cache(maxsize=None)
def boundary():
    """A* for the slender block (tanα 0.1) at 0.8 Hz: the steady state's max |ü + ẍg| = g·tanα."""
    thr = system(SLENDER).uplift_acceleration
    return uplift_amplitude(Bearing(M, C, K0, R, U_Y, 0.1 * G, 2 * math.pi * 0.8), thr, 0.1 * G, 0.4 * G) / G, thr


@pytest.mark.parametrize("run", RUNS)
def test_engines_lift_just_above_the_uplift_boundary(run):
    """The block rests on the base while |ü + ẍg| < g·tanα (model.md), so the largest steady
    amplitude that never lifts it is A* (the oracle's max |a| over its orbit equal to g·tanα:
    0.2636 g here). On the orbit at 0.99 A* the engines keep it down for 2 periods; at 1.01 A* it
    lifts at the first instant the orbit's |a| reaches g·tanα, to 1e-9 s."""
    a_star, thr = boundary()
    freq = 0.8
    below = orbit(0.99 * a_star, freq)
    assert below.max_abs_acceleration() < thr
    tr = run_on_orbit(run, below, 0.99 * a_star, freq, 2, block=SLENDER)
    assert tr.uplifts == 0 and np.all(tr.theta == 0.0)
    above = orbit(1.01 * a_star, freq)
    t_lift = above.first_time_above(thr) - above.tau
    tr = run_on_orbit(run, above, 1.01 * a_star, freq, 1, block=SLENDER)
    assert tr.uplifts >= 1 and abs(tr.uplift_times[0] - t_lift) <= LIMIT
