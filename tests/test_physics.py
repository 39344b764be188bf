"""analytic/physics.py, the one home of the model's physics, function by function against
model.md's closed forms (or the equations written out here independently)."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isorock.analytic import GroundMotion, Pulse, System, paper_system
from isorock.analytic import physics as P

FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)
ISO = paper_system()
G = 9.81


def sp(system, rest_velocity=1e-5):
    return P.system_params(system, rest_velocity)


@pytest.mark.parametrize("s", [1, -1])
@pytest.mark.parametrize("theta_frac, xg", [(0.0, 0.0), (0.3, -2.0), (-0.5, 3.5), (0.9, 1.0)])
def test_fixed_base_rocking_is_housners_equation(s, theta_frac, xg):
    th = s * abs(theta_frac) * FIXED.alpha
    p, a = FIXED.p, FIXED.alpha
    udd, thdd, _ = P.rocking_accelerations(sp(FIXED), float(s), th, 0.3, 0.0, 0.0, xg)
    assert udd == 0.0
    assert thdd == pytest.approx(-p**2 * (math.sin(s * a - th) + xg / G * math.cos(s * a - th)), rel=1e-12)


@pytest.mark.parametrize("s", [1, -1])
def test_isolated_rocking_solves_model_md_two_dof_equations(s):
    """M ü + m L1 θ̈ + m L2 θ̇² + c u̇ + k u = −M ẍg; (mR² + I) θ̈ + m L1 ü + m g L2 = −m L1 ẍg."""
    m, M, h, b = ISO.mass, ISO.total_mass, ISO.h, ISO.b
    th, thd, u, ud, xg = s * 0.1, 0.7, 0.02, -0.3, 1.7
    L1 = h * math.cos(th) + s * b * math.sin(th)
    L2 = s * b * math.cos(th) - h * math.sin(th)
    A = np.array([[M, m * L1], [m * L1, m * ISO.R**2 + ISO.inertia]])
    rhs = np.array([-M * xg - m * L2 * thd**2 - ISO.damping * ud - ISO.stiffness * u, -m * L1 * xg - m * G * L2])
    want = np.linalg.solve(A, rhs)
    got = P.rocking_accelerations(sp(ISO), float(s), th, thd, u, ud, xg)
    assert got[0] == pytest.approx(want[0], rel=1e-12) and got[1] == pytest.approx(want[1], rel=1e-12)
    assert got[2] == pytest.approx(L1)


def test_translation_and_base_acceleration():
    u, ud, xg = 0.05, -0.2, 2.0
    M, k, c = ISO.total_mass, ISO.stiffness, ISO.damping
    assert P.translation_acceleration(sp(ISO), u, ud, xg) == pytest.approx((-M * xg - c * ud - k * u) / M, rel=1e-13)
    assert P.base_acceleration(sp(ISO), u, ud, xg) == pytest.approx(-(c * ud + k * u) / M, rel=1e-13)
    assert P.translation_acceleration(sp(FIXED), u, ud, xg) == 0.0
    assert P.base_acceleration(sp(FIXED), 0.0, 0.0, xg) == xg


def test_uplift_direction_and_clear_relift():
    thr = G * FIXED.b / FIXED.h
    q = sp(FIXED)
    assert P.uplift_direction(q, -1.001 * thr) == 1 and P.uplift_direction(q, 1.001 * thr) == -1
    assert P.uplift_direction(q, 0.999 * thr) == 0 and P.uplift_direction(q, -thr) == 0
    assert P.relift(q, 0.0, 0.0, -1.01 * thr) == 1
    # θ̈ at θ = 0 is ~1e-16 of the threshold's scale: a grazing base stays down
    assert P.relift(q, 0.0, 0.0, -thr * (1 + 1e-15)) == 0


@pytest.mark.parametrize("lam, mu", [(2 / 0.7, 1.0), (3.5, 0.0), (5.0, 3.0)])
def test_impact_map_is_model_md(lam, mu):
    h = 1.0
    sys = System.isolated(height=2 * h, width=2 * h / lam, mass=1000.0, base_mass=1000.0 / mu, period=1.5,
                          damping_ratio=0.0) if mu else System.fixed(height=2 * h, width=2 * h / lam, mass=1000.0)
    q = sp(sys)
    den = lam**2 * (mu + 4) + 4 * (mu + 1)
    thd, ud = -0.8, 0.3
    c_thd, c_ud = P.impact_map(q, thd, ud, True)
    assert c_thd == pytest.approx((lam**2 * (mu + 4) - 2 * (mu + 1)) / den * thd, rel=1e-13)
    e_thd, e_ud = P.impact_map(q, thd, ud, False)
    assert e_thd == 0.0
    if mu:
        assert c_ud == pytest.approx(ud + 6 * mu * h / den * thd, rel=1e-13)
        assert e_ud == pytest.approx(ud + mu * h / (1 + mu) * thd, rel=1e-13)
        M, m = sys.total_mass, sys.mass
        for post in ((c_thd, c_ud), (e_thd, e_ud)):  # horizontal momentum M u̇ + m h θ̇
            assert M * post[1] + m * h * post[0] == pytest.approx(M * ud + m * h * thd, rel=1e-12)
    else:
        assert c_thd / thd == pytest.approx(1 - 1.5 * math.sin(math.atan(1 / lam)) ** 2, rel=1e-13)
        assert c_ud == 0.0 and e_ud == 0.0
    if (lam, mu) == (2 / 0.7, 1.0):  # the paper's example, λ = 2.857
        assert c_thd / thd == pytest.approx(0.75418, abs=5e-6)


def test_impact_continues_above_the_rest_floor_and_beta_positive():
    q = sp(FIXED, rest_velocity=1e-3)
    floor = 1e-3 * FIXED.p * FIXED.alpha
    assert P.impact_continues(q, 1.01 * floor) and P.impact_continues(q, -1.01 * floor)
    assert not P.impact_continues(q, 0.99 * floor)
    squat = System.fixed(height=1.0, width=1.5, mass=1.0)  # λ < no-bounce slenderness: β < 0
    assert not P.impact_continues(sp(squat), 10.0)


def test_energy_terms():
    """V(α) = m g (R − h) (the centroid above the pivot); T of pure rotation about the
    corner on a fixed base = ½ (4/3) m R² θ̇²; the base's spring and mass on an isolated one."""
    q = sp(FIXED)
    m, R, h = FIXED.mass, FIXED.R, FIXED.h
    assert P.potential_energy(q, 1.0, 0.0, FIXED.alpha) == pytest.approx(m * G * (R - h), rel=1e-12)
    assert P.potential_energy(q, -1.0, 0.0, -FIXED.alpha) == pytest.approx(m * G * (R - h), rel=1e-12)
    for th in (0.0, 0.2, -0.3):
        s = 1.0 if th >= 0 else -1.0
        assert P.kinetic_energy(q, s, 0.0, th, 1.3) == pytest.approx(0.5 * 4 / 3 * m * R**2 * 1.3**2, rel=1e-12)
    qi = sp(ISO)
    assert P.potential_energy(qi, 1.0, 0.1, 0.0) == pytest.approx(0.5 * ISO.stiffness * 0.01, rel=1e-12)
    assert P.kinetic_energy(qi, 1.0, 0.4, 0.0, 0.0) == pytest.approx(0.5 * ISO.total_mass * 0.16, rel=1e-12)
    # vectorised over arrays too (the stored histories)
    th = np.array([0.0, 0.1, -0.1])
    assert P.kinetic_energy(q, np.sign(th) + (th == 0), 0.0, th, np.ones(3)).shape == (3,)


def test_impact_energy_loss_fixed_base():
    """(1 − β²)·½ J_O θ̇⁻², J_O = (4/3) m R²."""
    q = sp(FIXED)
    thd = -0.9
    beta = q[P.BETA]
    post = P.impact_map(q, thd, 0.0, True)
    loss = P.impact_energy_loss(q, 0.0, thd, post[1], post[0])
    assert loss == pytest.approx((1 - beta**2) * 0.5 * 4 / 3 * FIXED.mass * FIXED.R**2 * thd**2, rel=1e-12)


def test_pivot_force_ratio():
    q = sp(FIXED)
    thr = G * FIXED.b / FIXED.h
    # in translation the friction needed is |a|/g; at the uplift threshold it is tanα
    assert P.pivot_force_ratio(q, 0, 0.0, 0.0, 0.0, 0.0, -thr) == pytest.approx(FIXED.b / FIXED.h, rel=1e-13)
    assert P.pivot_force_ratio(q, 1, 0.0, 0.0, 0.0, 0.0, -thr) == pytest.approx(FIXED.b / FIXED.h, rel=1e-9)
    # free rocking from rest at θ: Newton on the centroid, x = −b cosθ + h sinθ... written out
    th, s = 0.2, 1.0
    p2 = FIXED.p**2
    thdd = -p2 * math.sin(FIXED.alpha - th)
    L1 = FIXED.h * math.cos(th) + s * FIXED.b * math.sin(th)
    L2 = s * FIXED.b * math.cos(th) - FIXED.h * math.sin(th)
    want = abs(thdd * L1) / (G + thdd * L2)
    assert P.pivot_force_ratio(q, 1, th, 0.0, 0.0, 0.0, 0.0) == pytest.approx(want, rel=1e-12)
    # spinning fast enough, the centripetal pull lifts the block off the base
    assert P.pivot_force_ratio(q, 1, 0.0, 50.0, 0.0, 0.0, 0.0) == math.inf


def test_overturn_code():
    a = 0.25
    assert P.overturn_code(False, 0.2, a, False) == 0
    assert P.overturn_code(False, -0.3, a, False) == 3
    assert P.overturn_code(True, 0.3, a, False) == 1
    assert P.overturn_code(False, 1.5707963, a, True) == 2


def _params(motion):
    mp, acc = P.motion_params(motion)
    return mp, acc


@pytest.mark.parametrize("spec", ["sine:amp=0.3,freq=2.5,cycles=2", "cosine:amp=-0.4,freq=1.1,cycles=1.5",
                                  "ricker:amp=0.6,freq=3"])
def test_ground_acceleration_is_the_motion(spec):
    from isorock.analytic import load_motion
    motion = load_motion(spec)
    mp, acc = _params(motion)
    for t in np.linspace(-0.1, motion.end_time + 0.2, 37):
        assert P.ground_acceleration(t, mp, acc) == pytest.approx(motion.at(t), abs=1e-12)
    rec = GroundMotion.from_array(np.sin(np.arange(50) * 0.3), dt=0.01)
    mp, acc = _params(rec)
    for t in np.linspace(0.0, 0.6, 41):
        assert P.ground_acceleration(t, mp, acc) == pytest.approx(rec.at(t), abs=1e-14)


@pytest.mark.parametrize("kind", ["sine", "cosine", "ricker"])
@pytest.mark.parametrize("ratio", [1.3, 2.2])
def test_first_uplift_is_the_pulses_first_crossing(kind, ratio):
    """The first t with |ẍg| > g·tanα, found independently by a fine scan and brentq."""
    thr_g = FIXED.b / FIXED.h
    pulse = Pulse(kind, ratio * thr_g, 2.0)
    motion = GroundMotion.from_pulse(pulse)
    mp, acc = _params(motion)
    f = lambda t: abs(float(motion.at(t))) - thr_g * G  # noqa: E731
    grid = np.linspace(0.0, pulse.end_time, 20001)
    k = int(np.argmax(np.abs(motion(grid)) - thr_g * G > 0))
    want = 0.0 if k == 0 else brentq(f, grid[k - 1], grid[k], xtol=1e-15)
    t, s = P.first_uplift(sp(FIXED), mp, acc, 0.0, pulse.end_time, 0.0)
    assert t == pytest.approx(want, abs=1e-11)
    assert s == (1 if motion.at(t + 1e-6) < 0 else -1)
    # and the next crossing after it, from a later start inside the excursion's end
    t2, _ = P.first_uplift(sp(FIXED), mp, acc, 0.0, 0.5 * want, 0.0) if want > 0 else (0.5 * want, 0)
    assert t2 == pytest.approx(0.5 * want)  # none before: the window's end


def test_first_uplift_with_a_margin_needs_a_clear_excess():
    thr_g = FIXED.b / FIXED.h
    motion = GroundMotion.from_pulse(Pulse("sine", thr_g * (1 + 1e-9), 5.0))
    mp, acc = _params(motion)
    t, s = P.first_uplift(sp(FIXED), mp, acc, 0.0, 1.0, 0.0)
    assert s == -1 and 0.04 < t < 0.06
    assert P.first_uplift(sp(FIXED), mp, acc, 0.0, 1.0, P.GRAZE_MARGIN) == (1.0, 0)


# --- an isolated base in pure translation, in closed form ---------------------------------

OSCILLATORS = [ISO] + [System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=1900.0, period=T,
                                       damping_ratio=z) for T, z in ((0.8, 0.0), (2.0, 1.0), (1.2, 1.6))]
OSC_IDS = ["paper", "undamped", "critical", "overdamped"]


def _ramp_system(system):
    """The translation equation with the ramp ẍg = a0 + a1·τ as two more states (u, u̇, ẍg, a1):
    a linear system, solved independently by the matrix exponential."""
    M, c, k = system.total_mass, system.damping, system.stiffness
    return np.array([[0, 1, 0, 0], [-k / M, -c / M, -1, 0], [0, 0, 0, 1], [0, 0, 0, 0]], dtype=float)


def _exact(system, x0, tau):
    from scipy.linalg import expm
    return expm(_ramp_system(system) * tau) @ np.asarray(x0, dtype=float)


@pytest.mark.parametrize("system", OSCILLATORS, ids=OSC_IDS)
def test_translation_closed_form_is_the_oscillators_solution(system):
    """u, u̇ against the matrix exponential; the ground's work W = −M∫ẍg u̇ and the dashpot's
    loss D = c∫u̇² against the equations integrated as quadratures (DOP853 at rtol 1e-13)."""
    from scipy.integrate import solve_ivp
    q = sp(system)
    M, c, k = system.total_mass, system.damping, system.stiffness
    u0, v0, a0, a1 = 0.05, -0.3, 2.5, -150.0
    x0 = (u0, v0, a0, a1)

    def f(t, y):
        xg = a0 + a1 * t
        return [y[1], -xg - (c * y[1] + k * y[0]) / M, -M * xg * y[1], c * y[1] ** 2]
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, a0, a1)
    for tau in (1e-7, 0.004, 0.02, 0.3):
        u, v, dW, dD = P.translation_state(q, zu, zv, p1, u0, v0, a0, a1, tau)
        want = _exact(system, x0, tau)
        assert u == pytest.approx(want[0], rel=1e-12, abs=1e-15)
        assert v == pytest.approx(want[1], rel=1e-12, abs=1e-15)
        ref = solve_ivp(f, (0, tau), [u0, v0, 0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-20).y[:, -1]
        scale_e = M * (abs(a0) + abs(a1) * tau) * abs(v0) * tau  # |W| for a short τ
        assert dW == pytest.approx(ref[2], rel=1e-10, abs=1e-12 * scale_e)
        assert dD == pytest.approx(ref[3], rel=1e-10, abs=1e-12 * scale_e)
        if c == 0:
            assert dD == 0.0


@pytest.mark.parametrize("system", OSCILLATORS, ids=OSC_IDS)
def test_translation_energy_balance_in_closed_form(system):
    """Over a whole record interval: Δ(½Mu̇² + ½ku²) = W − D to rounding."""
    q = sp(system)
    u0, v0, a0, a1 = -0.12, 0.4, -3.0, 80.0
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, a0, a1)
    u, v, dW, dD = P.translation_state(q, zu, zv, p1, u0, v0, a0, a1, 0.02)
    M, k = system.total_mass, system.stiffness
    dE = 0.5 * M * (v * v - v0 * v0) + 0.5 * k * (u * u - u0 * u0)
    assert dE == pytest.approx(dW - dD, rel=1e-12, abs=1e-12 * (abs(dW) + abs(dD)))


def _brief_excursion(system, delta, t_peak=0.0071, sign=-1.0):
    """A free vibration (no ground motion) whose base acceleration a = −(c u̇ + k u)/M peaks at
    t_peak with a = sign·(1 + delta)·g·tanα: built at the peak (a' = 0 there) and carried back
    by the matrix exponential. Returns (u0, u̇0, a(τ) as a function)."""
    M, c, k = system.total_mass, system.damping, system.stiffness
    thr = system.uplift_acceleration
    # a = −(k u + c v)/M, a' = −(k v + c v')/M with v' = −(k u + c v)/M: solve for (u, v) at the peak
    A = np.array([[-k / M, -c / M], [c * k / M**2, -k / M + c * c / M**2]])
    up, vp = np.linalg.solve(A, [sign * (1 + delta) * thr, 0.0])
    x0 = _exact(system, (up, vp, 0.0, 0.0), -t_peak)

    def acc(tau):
        x = _exact(system, (x0[0], x0[1], 0.0, 0.0), tau)
        return -(c * x[1] + k * x[0]) / M
    return x0[0], x0[1], acc


@pytest.mark.parametrize("system", [OSCILLATORS[0], OSCILLATORS[2]], ids=["paper", "critical"])
@pytest.mark.parametrize("sign", [-1.0, 1.0])
def test_translation_uplift_finds_a_brief_excursion_inside_one_interval(system, sign):
    """|a| exceeds g·tanα by 1e-7 for a few µs in the middle of a 0.02 s interval, both ends
    well inside the band: a sign test at the ends would miss it; the closed form lifts at the
    crossing (found independently by brentq on the matrix exponential)."""
    q = sp(system)
    thr = system.uplift_acceleration
    u0, v0, acc = _brief_excursion(system, 1e-7, sign=sign)
    assert abs(acc(0.0)) < thr * (1 - 1e-5) and abs(acc(0.02)) < thr * (1 - 1e-5)
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, 0.0, 0.0)
    a_end = P.base_acceleration(q, *P.translation_state(q, zu, zv, p1, u0, v0, 0.0, 0.0, 0.02)[:2], 0.0)
    tau, side = P.translation_uplift(q, zu, zv, 0.0, 0.0, 0.02, thr, a_end)
    want = brentq(lambda s: sign * acc(s) - thr, 0.0, 0.0071, xtol=1e-16, rtol=1e-15)
    assert side == (1 if sign < 0 else -1)
    assert tau == pytest.approx(want, abs=1e-12)
    # just below the threshold at its peak: it stays down
    u0, v0, acc = _brief_excursion(system, -1e-7, sign=sign)
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, 0.0, 0.0)
    a_end = P.base_acceleration(q, *P.translation_state(q, zu, zv, p1, u0, v0, 0.0, 0.0, 0.02)[:2], 0.0)
    assert P.translation_uplift(q, zu, zv, 0.0, 0.0, 0.02, thr, a_end) == (0.02, 0)


def test_translation_uplift_under_a_ramp_and_at_the_start():
    q = sp(ISO)
    thr = ISO.uplift_acceleration
    u0, v0, a0, a1 = -0.165, -0.3, 0.5, 100.0  # moving away from the spring: a rises through g·tanα
    x0 = (u0, v0, a0, a1)
    acc = lambda s: (lambda x: -(ISO.damping * x[1] + ISO.stiffness * x[0]) / ISO.total_mass)(_exact(ISO, x0, s))  # noqa: E731
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, a0, a1)
    a_end = P.base_acceleration(q, *P.translation_state(q, zu, zv, p1, u0, v0, a0, a1, 0.05)[:2], 0.0)
    assert acc(0.0) < thr < acc(0.05)
    tau, side = P.translation_uplift(q, zu, zv, a0, a1, 0.05, thr, a_end)
    assert side == -1 and tau == pytest.approx(brentq(lambda s: acc(s) - thr, 0, 0.05, xtol=1e-16), abs=1e-13)
    # already beyond the threshold where the interval starts: it lifts there
    assert P.translation_uplift(q, zu, zv, a0, a1, 0.05, 0.5 * abs(acc(0.0)), a_end) == (0.0, -1 if acc(0) > 0 else 1)


@pytest.mark.parametrize("system", OSCILLATORS, ids=OSC_IDS)
def test_translation_velocity_zeros_are_the_extremes_of_u(system):
    q = sp(system)
    u0, v0, a0, a1 = 0.1, 0.02, -1.0, 30.0
    x0 = (u0, v0, a0, a1)
    h = 0.25
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, a0, a1)
    out = np.empty(4)
    n = P.translation_velocity_zeros(q, zu, zv, p1, h, out)
    from scipy.linalg import expm
    grid = np.linspace(0, h, 1001)
    step = expm(_ramp_system(system) * (grid[1] - grid[0]))
    xs = [np.asarray(x0, dtype=float)]
    for _ in grid[1:]:
        xs.append(step @ xs[-1])
    xs = np.array(xs)
    vel = xs[:, 1]
    flips = np.nonzero(np.sign(vel[1:]) != np.sign(vel[:-1]))[0]
    want = [brentq(lambda s: _exact(system, x0, s)[1], grid[i], grid[i + 1], xtol=1e-16) for i in flips]
    assert n == len(want) >= 1
    np.testing.assert_allclose(out[:n], want, atol=1e-12)
    bound = P.translation_u_bound(q, zu, zv, h)
    u = xs[:, 0]
    chord = u[0] + (u[-1] - u[0]) * grid / h
    assert np.max(np.abs(u - chord)) <= bound


class _TooManyEvaluations(Exception):
    pass


@pytest.mark.parametrize("u0, v0, a0, a1", [(0.0, 0.0, 0.0, 0.0),  # at rest, no motion (stress's zero-motion)
                                             (0.0, 0.0, 0.5, 0.0)])  # constant push from rest: u̇ grows, no extreme
def test_translation_zero_search_ends_on_a_function_that_is_zero_or_constant(monkeypatch, u0, v0, a0, a1):
    """A block at rest on an isolated base with no ground motion made the kernel hang: u̇ ≡ 0
    over the interval, so the interval search split every half again until 78 levels deep
    (2^78 intervals). An identically zero or linear function has no sign change to look for:
    the search must end after a handful of evaluations and report no extreme and no uplift."""
    q = sp(ISO)
    calls = [0]
    line = P._oscillator_line

    def counted(*a):
        calls[0] += 1
        if calls[0] > 10_000:
            raise _TooManyEvaluations
        return line(*a)
    monkeypatch.setattr(P, "_oscillator_line", counted)
    zu, zv, p0, p1 = P.translation_start(q, u0, v0, a0, a1)
    out = np.empty(4)
    h = 0.02
    n = P.translation_velocity_zeros(q, zu, zv, p1, h, out)
    u, v = P.translation_state(q, zu, zv, p1, u0, v0, a0, a1, h)[:2]
    # independent: at rest with no motion nothing moves; under a constant push from rest
    # u̇ = −a0·τ + O(τ²) keeps its sign over a short interval, so u has no extreme inside
    assert n == 0
    if a0 == 0.0:
        assert u == 0.0 and v == 0.0
    else:
        assert v == pytest.approx(-a0 * h, rel=0.05)
    a_end = P.base_acceleration(q, u, v, 0.0)
    tau, side = P.translation_uplift(q, zu, zv, a0, a1, h, ISO.uplift_acceleration, a_end)
    assert (tau, side) == (h, 0)
    assert calls[0] < 1000
