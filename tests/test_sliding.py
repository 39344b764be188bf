"""A statue that may slip on its base, and vertical ground motion (docs/sliding.md), against
oracles that do not come from the code under test:

- the regime boundaries from rest under a constant acceleration (Shenton 1996): rest–slide at
  a = μg, rest–rock at a = g·tanα, rock–slide-rock where a pivot's friction demand, solved
  here from Newton–Euler as a linear system, reaches μ (and Shenton's closed form beside it);
- pure sliding under a rectangular pulse and under harmonic motion: the rigid-plastic block's
  slip in closed form, its stops located here by root finding on that closed form;
- constant vertical acceleration as a rescaled gravity (similarity: a block R·g/g' with the
  pulse scaled by g/g' has the same θ(t) as block R under g' = g + a_v);
- the impact map: ample friction gives model.md's closed-form β and β₂; a slipping impact
  keeps the block's angular momentum about its landing corner and carries P_x = μ·P_z;
- the energy balance with friction's work, and no slip as μ_s → ∞ (the no-slip model).
"""
import math
import zlib

import numpy as np
import pytest
from scipy.optimize import brentq

from isorock.analytic import hybrid
from isorock.analytic.coefficients import beta, beta2
from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.settings import AnalyticSettings
from isorock.analytic.system import (BallInCone, BilinearIsolator, DoubleFrictionPendulum, FrictionPendulum, System)

G = 9.81


def reference(system, motion, **kw):
    return hybrid.simulate(system, motion, **kw)


def kernel(system, motion, **kw):
    from isorock.analytic.fast import simulate_fast
    return simulate_fast(system, motion, **kw)


PATHS = {"reference": reference, "kernel": kernel}


def constant(a, duration=1.0, dt=0.5):
    return GroundMotion.from_array(np.full(int(round(duration / dt)) + 1, float(a)), dt=dt)


def first_mode(tr):
    """The mode a run starts in at t = 0, read off what it logged."""
    rocks = bool(tr.uplift_times) and tr.uplift_times[0] == 0.0
    slips = any(t == 0.0 and s != 0 for t, s in tr.extras["slip_events"])
    return {(False, False): "rest", (False, True): "slide", (True, False): "rock", (True, True): "slide-rock"}[
        (rocks, slips)]


def boundary(mode_at, lo, hi, rel=1e-12):
    """The acceleration where mode_at(a) changes, by bisection to `rel`."""
    below = mode_at(lo)
    assert mode_at(hi) != below
    while hi - lo > rel * hi:
        mid = 0.5 * (lo + hi)
        if mode_at(mid) == below:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def pivot_friction_ratio(a, b, h, ge):
    """|F_x|/F_z at a pivot that sticks, the block at rest at θ = 0 on a base accelerating at −a:
    Newton–Euler for (θ̈, F_x, F_z) solved as a linear system (m = 1, I = (b² + h²)/3)."""
    inertia = (b * b + h * h) / 3.0
    # F_x − h·θ̈ = −a;  F_z − b·θ̈ = g_e;  I·θ̈ + h·F_x + b·F_z = 0   (corner O at (+b, 0))
    A = np.array([[1.0, 0.0, -h], [0.0, 1.0, -b], [h, b, inertia]])
    fx, fz, _ = np.linalg.solve(A, [-a, ge, 0.0])
    return abs(fx) / fz


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("b_over_h, mu, av", [(0.35, 0.2, 0.0), (0.2, 0.15, 0.0), (0.35, 0.2, 2.5),
                                               (0.5, 0.3, -3.0)])
def test_rest_slide_boundary_is_mu_g(path, b_over_h, mu, av):
    """μ < tanα: a block at rest slides once the base's acceleration passes μ·g_e (Shenton)."""
    h = 1.0
    system = System.fixed(height=2 * h, width=2 * h * b_over_h, mass=100.0).with_friction(mu)
    vert = constant(av) if av else None

    def mode_at(a):
        return first_mode(PATHS[path](system, constant(a).with_vertical(vert), duration=1e-3))
    a_star = boundary(mode_at, 0.5 * mu * (G + av), 1.5 * mu * (G + av))
    assert a_star == pytest.approx(mu * (G + av), rel=1e-9)
    assert mode_at(1.01 * a_star) == "slide"


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("b_over_h, mu, av", [(0.35, 0.6, 0.0), (0.2, 0.5, 0.0), (0.35, 0.6, 3.0)])
def test_rest_rock_and_rock_slide_rock_boundaries(path, b_over_h, mu, av):
    """μ > tanα: a block at rest rocks once |a| passes g_e·tanα, and rocks with its corner
    slipping once the pivot's friction demand (Newton–Euler, solved here) passes μ."""
    h = 1.0
    b = h * b_over_h
    ge = G + av
    system = System.fixed(height=2 * h, width=2 * b, mass=100.0).with_friction(mu)
    vert = constant(av) if av else None

    def mode_at(a):
        return first_mode(PATHS[path](system, constant(-a).with_vertical(vert), duration=1e-3))
    rock = boundary(mode_at, 0.5 * ge * b_over_h, 1.5 * ge * b_over_h)
    assert rock == pytest.approx(ge * b_over_h, rel=1e-9)
    # the rock–slide-rock boundary: where the pivot's demand reaches μ, found on the oracle
    a_sr = brentq(lambda a: pivot_friction_ratio(a, b, h, ge) - mu, ge * b_over_h * 1.0001, 50 * ge)
    # Shenton (1996)'s closed form agrees with that linear system
    tau = b_over_h
    assert a_sr / ge == pytest.approx((mu * (4 + tau**2) - 3 * tau) / (1 + 4 * tau**2 - 3 * mu * tau), rel=1e-12)
    found = boundary(mode_at, 0.5 * (rock + a_sr), 2 * a_sr)
    assert found == pytest.approx(a_sr, rel=1e-9)
    assert mode_at(0.99 * a_sr) == "rock" and mode_at(1.01 * a_sr) == "slide-rock"


def _rectangular_slide(a0, mu, T, dt):
    """Closed form: a rigid-plastic block slides from t = 0 under a0 for T, the record ramping
    to 0 over one sample dt after (it is linear between samples), then stops by friction.
    Returns (final slide, time it stops)."""
    c = a0 - mu * G  # ẍ = −(a0 − μg) while the ground pushes
    v1, x1 = -c * T, -0.5 * c * T * T
    # the ramp, a(τ) = a0·(1 − τ/dt): ẍ = −a0 + μg + a0·τ/dt
    v2 = v1 - c * dt + 0.5 * a0 * dt
    x2 = x1 + v1 * dt - 0.5 * c * dt * dt + a0 * dt * dt / 6.0
    assert v2 < 0  # still sliding when the ground stops
    t_stop = T + dt - v2 / (mu * G)
    return x2 - v2 * v2 / (2 * mu * G), t_stop


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("a0_g, mu, T", [(0.5, 0.2, 0.3), (1.2, 0.3, 0.05)])
def test_sliding_under_a_rectangular_pulse(path, a0_g, mu, T):
    dt = 0.01
    n = int(round(T / dt))
    rec = GroundMotion.from_array(np.r_[np.full(n + 1, a0_g * G), 0.0], dt=dt)
    system = System.fixed(height=1.0, width=1.0, mass=50.0).with_friction(mu)  # tanα 1 > μ: it slides
    tr = PATHS[path](system, rec, duration=T + 3.0)
    x_final, t_stop = _rectangular_slide(a0_g * G, mu, n * dt, dt)
    assert tr.summary()["slide_final"] == pytest.approx(x_final, rel=1e-9)
    assert tr.extras["slip_events"][0] == (0.0, -1)
    assert tr.extras["slip_events"][-1][1] == 0
    assert tr.extras["slip_events"][-1][0] == pytest.approx(t_stop, rel=1e-9)
    assert tr.theta_max_over_alpha == 0.0


def _harmonic_slides(A, f, cycles, mu, t_end):
    """The rigid-plastic block under ẍg = A·g·sin(ωt) for `cycles` cycles (then still), in closed
    form: each slip's start where |ẍg| first passes μg (or at once, when a stop cannot hold),
    its velocity ẋ = (Ag/ω)(cos ωt − cos ωt0) − σμg(t − t0) + … and its stop found here by
    root finding on that form. Returns (events [(t, σ)], final slide)."""
    w = 2 * math.pi * f
    end = cycles / f

    def acc(t):
        return A * G * math.sin(w * t) if t <= end else 0.0

    def vel(t, t0, v0, sigma):  # ẋ during a slip from (t0, v0), for t within the pulse or after it
        def prim(s):  # ∫ −ẍg ds
            return (A * G / w) * math.cos(w * min(s, end)) - (0.0 if s <= end else 0.0)
        return v0 + prim(t) - prim(t0) - sigma * mu * G * (t - t0)

    def pos(t, t0, x0, v0, sigma):
        def iprim(s):  # ∫∫: the pulse's part ∫ (Ag/ω) cos(ω s) ds, held after its end
            se = min(s, end)
            return (A * G / w**2) * math.sin(w * se) + (A * G / w) * math.cos(w * end) * max(0.0, s - end)
        return (x0 + iprim(t) - iprim(t0) - ((A * G / w) * math.cos(w * min(t0, end))) * (t - t0) + v0 * (t - t0)
                - 0.5 * sigma * mu * G * (t - t0) ** 2)

    events, x, t = [], 0.0, 0.0
    while t < t_end:
        # sticking: the next time |ẍg| passes μg
        if abs(acc(t)) > mu * G:
            t0 = t
        else:
            grid = np.linspace(t, min(end, t_end), 2001)
            over = [i for i in range(1, grid.size) if abs(acc(grid[i])) > mu * G]
            if not over or grid[over[0]] > end:
                break
            i = over[0]
            t0 = brentq(lambda s: abs(acc(s)) - mu * G, grid[i - 1], grid[i], xtol=1e-15, rtol=1e-15)
        sigma = -1 if acc(t0 + 1e-12) > 0 else 1
        events.append((t0, sigma))
        # slipping: ẋ from 0 at t0 until σ·ẋ falls through 0
        grid = t0 + np.linspace(0.0, 5.0, 50001)[1:]
        v = np.array([vel(s, t0, 0.0, sigma) for s in grid])
        k = next(i for i in range(1, v.size) if sigma * v[i] <= 0)
        ts = brentq(lambda s: vel(s, t0, 0.0, sigma), grid[k - 1], grid[k], xtol=1e-15, rtol=1e-15)
        x = pos(ts, t0, x, 0.0, sigma)
        events.append((ts, 0))
        t = ts
    return events, x


@pytest.mark.parametrize("path", PATHS)
def test_sliding_under_harmonic_motion(path):
    A, f, cycles, mu = 0.4, 2.0, 2, 0.25
    motion = GroundMotion.from_pulse(Pulse("sine", A, f, cycles))
    system = System.fixed(height=1.0, width=1.2, mass=10.0).with_friction(mu)  # tanα 1.2: it never rocks
    tr = PATHS[path](system, motion, duration=2.0)
    events, x = _harmonic_slides(A, f, cycles, mu, 2.0)
    got = [(t, s) for t, s in tr.extras["slip_events"]]
    assert [s for _, s in got] == [s for _, s in events]
    for (tg, _), (te, _) in zip(got, events):
        assert tg == pytest.approx(te, rel=1e-9, abs=1e-12)
    assert tr.summary()["slide_final"] == pytest.approx(x, rel=1e-9)


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("base", ["fixed", "isolated"])
@pytest.mark.parametrize("mu", [None, 0.4])
def test_constant_vertical_acceleration_is_a_rescaled_gravity(path, base, mu):
    """Similarity: block R under g + a_v (a_v constant) moves as block R·g/(g + a_v) under g with
    the horizontal motion scaled by g/(g + a_v): the same p, α, θ(t), and u, x scaled alike."""
    av = 3.0
    r = G / (G + av)
    H, B = 2.0, 0.7
    # each rocks, and with μ 0.4 slides too (the isolated block past α, and back)
    pulse = GroundMotion.from_pulse(Pulse("sine", 1.5, 3.0, 1) if base == "fixed" else Pulse("sine", 0.7, 0.8, 1))

    def make(height, width):
        if base == "fixed":
            s = System.fixed(height=height, width=width, mass=3800.0)
        else:
            s = System.isolated(height=height, width=width, mass=3800.0, base_mass=3800.0, period=1.5,
                                damping_ratio=0.1)
        return s.with_friction(mu)
    heaving = PATHS[path](make(H, B), pulse.with_vertical(constant(av, 6.0)), duration=4.0,
                          settings=AnalyticSettings(output_dt=0.01))
    scaled = hybrid.simulate(make(H * r, B * r), pulse.scaled(r), duration=4.0,
                             settings=AnalyticSettings(output_dt=0.01))
    assert heaving.theta_max_over_alpha > 0.3  # it rocks
    grid = np.arange(401) * 0.01  # both store their states exactly there (output_dt)
    th_a = np.interp(grid, heaving.t, heaving.theta)
    th_b = np.interp(grid, scaled.t, scaled.theta)
    assert np.max(np.abs(th_a - th_b)) < 1e-9 * heaving.system.alpha
    assert heaving.theta_max_over_alpha == pytest.approx(scaled.theta_max_over_alpha, rel=1e-9)
    assert heaving.u_max * r == pytest.approx(scaled.u_max, rel=1e-8, abs=1e-12)
    if mu is not None:
        assert abs(heaving.summary()["slide_max"] * r - scaled.summary()["slide_max"]) < 1e-9 * H


def _corner_angular_momentum(m, b, h, s_land, vx, vz, thd):
    """The block's angular momentum about the landing corner (−s·b, 0) at θ = 0: I·θ̇ + r × m·v."""
    inertia = m * (b * b + h * h) / 3.0
    rx, rz = s_land * b, h  # the centre of mass relative to that corner
    return inertia * thd + m * (rz * vx - rx * vz)


@pytest.mark.parametrize("lam, mu_ratio", [(2.857, 1.0), (5.0, 0.3), (1.5, 4.0), (3.0, 0.0)])
def test_impact_with_ample_friction_is_model_mds_map(lam, mu_ratio):
    from isorock.analytic import physics, slide_physics as sl
    b = 0.35
    h = lam * b
    if mu_ratio == 0.0:
        system = System.fixed(height=2 * h, width=2 * b, mass=100.0).with_friction(10.0)
    else:
        system = System.isolated(height=2 * h, width=2 * b, mass=100.0, base_mass=100.0 / mu_ratio, period=2.0,
                                 damping_ratio=0.1).with_friction(10.0)
    sp, _ = physics.isolator_params(system, 1e-5)
    cp = sl.contact_params(system, False)
    for s in (1.0, -1.0):
        thd_pre = -s * 0.4
        thd, xd, ud, px, pz, ok = sl.impact(sp, cp, s, thd_pre, 0.0, 0.05, True)
        assert ok and xd == 0.0
        assert thd / thd_pre == pytest.approx(beta(lam, system.mu), abs=1e-14)
        assert (ud - 0.05) / thd_pre == pytest.approx(beta2(lam, system.mu, h), abs=1e-14)


@pytest.mark.parametrize("mu, xd_pre", [(0.1, 0.0), (0.05, 1.0), (0.05, -0.2)])
def test_slipping_impact_keeps_corner_momentum_and_carries_mu(mu, xd_pre):
    """On a fixed base the impulse acts at the landing corner: the block's angular momentum
    about that corner is kept, and a slipping impulse has |P_x| = μ·P_z (both from momenta)."""
    from isorock.analytic import physics, slide_physics as sl
    m, b, h = 100.0, 0.3, 1.0
    system = System.fixed(height=2 * h, width=2 * b, mass=m).with_friction(mu)
    sp, _ = physics.isolator_params(system, 1e-5)
    cp = sl.contact_params(system, False)
    s = 1.0
    thd_pre = -0.8
    thd, xd, ud, px, pz, ok = sl.impact(sp, cp, s, thd_pre, xd_pre, 0.0, True)
    assert ok and xd != 0.0
    # the centre's velocity before (about corner s) and after (about −s, slipping at ẋ⁺)
    vx0, vz0 = xd_pre + h * thd_pre, s * b * thd_pre
    vx1, vz1 = xd + h * thd, -s * b * thd
    assert _corner_angular_momentum(m, b, h, s, vx0, vz0, thd_pre) == pytest.approx(
        _corner_angular_momentum(m, b, h, s, vx1, vz1, thd), rel=1e-12)
    P_x, P_z = m * (vx1 - vx0), m * (vz1 - vz0)
    assert P_z > 0 and abs(P_x) == pytest.approx(mu * P_z, rel=1e-12)
    assert P_x * xd < 0 or xd_pre * P_x < 0  # friction opposes the slip


ISOLATORS = {
    "fixed": lambda **k: System.fixed(**k),
    "linear": lambda **k: System.isolated(**k, base_mass=200.0, period=2.0, damping_ratio=0.1),
    "bilinear": lambda **k: System.with_isolator(**k, base_mass=200.0, isolator=BilinearIsolator(4000.0, 0.1, 0.01,
                                                                                                 50.0)),
    "friction-pendulum": lambda **k: System.with_isolator(**k, base_mass=200.0, isolator=FrictionPendulum(1.0, 0.05)),
    "ball-in-cone": lambda **k: System.with_isolator(**k, base_mass=200.0, isolator=BallInCone(0.1, 0.03)),
    "double-friction-pendulum": lambda **k: System.with_isolator(
        **k, base_mass=200.0, isolator=DoubleFrictionPendulum(1.0, 0.03, 1.5, 0.08)),
}


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("kind", ISOLATORS)
def test_energy_balance_with_friction_work(path, kind):
    # a seed of the kind's name, the same in every process: hash() of a str is salted per process
    # (PYTHONHASHSEED), so the draws changed from run to run, and one CI run drew a block thrown
    # off its pivot (free flight: outside the model, no energy balance to check)
    rng = np.random.default_rng(zlib.crc32(kind.encode()))
    for _ in range(4):
        lam = rng.uniform(1.2, 4.0)
        b = rng.uniform(0.1, 0.4)
        mu = rng.uniform(0.15, 0.9)
        system = ISOLATORS[kind](height=2 * lam * b, width=2 * b, mass=100.0).with_friction(mu, mu * rng.uniform(0.7, 1))
        motion = GroundMotion.from_pulse(Pulse("sine", rng.uniform(0.3, 1.0), rng.uniform(1.0, 4.0), 2))
        if rng.uniform() < 0.5:
            motion = motion.with_vertical(GroundMotion.from_pulse(Pulse("sine", rng.uniform(0.1, 0.4),
                                                                        rng.uniform(2.0, 6.0), 3)))
        tr = PATHS[path](system, motion, duration=3.0)
        assert tr.status in ("completed", "overturned"), tr.message
        assert tr.energy.relative_residual < 1e-8, (kind, lam, b, mu, tr.energy.relative_residual)


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("base", ["fixed", "isolated"])
def test_no_slip_as_friction_grows(path, base):
    """μ_s large enough that the pivot never slips: the no-slip model's run, to its tolerance."""
    if base == "fixed":
        system = System.fixed(height=2.0, width=0.7, mass=3800.0)
    else:
        system = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
    motion = GroundMotion.from_pulse(Pulse("sine", 0.5 if base == "fixed" else 0.7, 1.5, 2))
    no_slip = hybrid.simulate(system, motion, duration=5.0)
    slipping = PATHS[path](system.with_friction(10.0), motion, duration=5.0)
    assert no_slip.impact_count >= 3
    assert slipping.summary()["slide_max"] < 1e-9
    assert slipping.impact_count == no_slip.impact_count
    assert slipping.theta_max_over_alpha == pytest.approx(no_slip.theta_max_over_alpha, rel=1e-8)
    for a, b in zip(slipping.counted_impacts, no_slip.counted_impacts):
        assert a.t == pytest.approx(b.t, abs=1e-8)
