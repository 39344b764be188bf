"""The hybrid integrator against closed forms, conservation laws and independent
computations (quadrature of the exact time to first impact, energy written out here
from model.md, momenta from positions and velocities)."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from isorock.analytic import AnalyticSettings, GroundMotion, InputError, System, beta, load_motion, paper_system, simulate
from isorock.analytic.trajectory import counted_sign_changes

FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)
ISOLATED_UNDAMPED = System.from_stiffness(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0,
                                          stiffness=7600 * (2 * math.pi / 1.5) ** 2, damping=0.0)
SLENDER = System.from_stiffness(height=3.0, width=0.5, mass=500.0, base_mass=2000.0, stiffness=2e4, damping=0.0)


def _energy(sys, u, ud, th, thd):
    """model.md's energy, written out independently of analytic.hybrid."""
    s = np.where(th >= 0, 1.0, -1.0)
    h, b, m = sys.h, sys.b, sys.mass
    xd = thd * (h * np.cos(th) + s * b * np.sin(th))
    zd = thd * (s * b * np.cos(th) - h * np.sin(th))
    mb = 0.0 if sys.fixed_base else sys.base_mass
    k = 0.0 if sys.fixed_base else sys.stiffness
    T = 0.5 * mb * ud**2 + 0.5 * m * ((ud + xd) ** 2 + zd**2) + 0.5 * m * (b * b + h * h) / 3 * thd**2
    V = 0.5 * k * u**2 + m * sys.gravity * (s * b * np.sin(th) + h * np.cos(th) - h)
    return T + V


@pytest.mark.parametrize("sys", [FIXED, ISOLATED_UNDAMPED, SLENDER, paper_system()], ids=["fixed", "iso", "slender", "paper"])
def test_free_rocking_each_impact_multiplies_by_beta(sys):
    tr = simulate(sys, None, theta0=0.5 * sys.alpha, duration=30.0)
    b = beta(sys.slenderness, sys.mu)
    continued = [i for i in tr.impacts if i.continued]
    assert len(continued) >= 6
    for imp in continued:
        assert imp.theta_dot_post / imp.theta_dot_pre == pytest.approx(b, abs=1e-10)
    # the Zeno tail ends at the rest floor, and the block then sits on its base
    floor = AnalyticSettings().rest_velocity * sys.p * sys.alpha
    assert tr.impacts[-1].continued is False and abs(tr.impacts[-1].theta_dot_pre) < floor
    assert all(abs(i.theta_dot_pre) >= floor for i in continued)
    assert tr.mode[-1] == 0 and tr.theta[-1] == 0


@pytest.mark.parametrize("sys", [FIXED, ISOLATED_UNDAMPED, SLENDER], ids=["fixed", "iso", "slender"])
def test_energy_constant_between_impacts(sys):
    tr = simulate(sys, None, theta0=0.6 * sys.alpha, duration=3.0, settings=AnalyticSettings(output_dt=1e-3))
    E = _energy(sys, tr.u, tr.u_dot, tr.theta, tr.theta_dot)
    edges = [0.0] + [i.t for i in tr.impacts] + [tr.t[-1] + 1]
    checked = 0
    for a, b in zip(edges[:-1], edges[1:]):
        inside = (tr.t > a) & (tr.t < b)
        if inside.sum() > 3:
            seg = E[inside]
            assert np.ptp(seg) <= 1e-9 * E[0], f"energy drifts by {np.ptp(seg) / E[0]:.2e} in ({a}, {b})"
            checked += 1
    assert checked >= 5
    # impacts only lose energy, and the log books what each one lost
    assert len(tr.energy.per_impact) == len(tr.impacts)
    for i, lost in zip(tr.impacts, tr.energy.per_impact):
        before = _energy(sys, 0.0, i.u_dot_pre, 0.0, i.theta_dot_pre)
        after = _energy(sys, 0.0, i.u_dot_post, 0.0, i.theta_dot_post)
        assert after <= before
        assert lost == pytest.approx(before - after, rel=1e-12, abs=1e-12 * E[0])
    assert tr.summary()["energy_lost_in_impacts"] == pytest.approx(sum(tr.energy.per_impact))


def test_momentum_conserved_across_logged_impacts():
    sys = paper_system()
    tr = simulate(sys, load_motion("sine:amp=0.6,freq=1,cycles=2"), duration=6.0)
    assert tr.impacts
    for i in tr.impacts:
        pre = sys.total_mass * i.u_dot_pre + sys.mass * sys.h * i.theta_dot_pre
        post = sys.total_mass * i.u_dot_post + sys.mass * sys.h * i.theta_dot_post
        assert post == pytest.approx(pre, rel=1e-12, abs=1e-12)


def _exact_first_impact(sys, theta0):
    """model.md: t₁ = ∫₀^θ0 dθ/θ̇(θ), with θ = θ0 − s² removing the end-point singularity."""
    c = 3 * sys.gravity / (2 * sys.R)
    a = sys.alpha

    def integrand(s):
        th = theta0 - s * s
        return 2 * s / math.sqrt(c * (math.cos(a - theta0) - math.cos(a - th)))
    value, _ = quad(integrand, 0, math.sqrt(theta0), epsabs=1e-14, epsrel=1e-13, limit=200)
    return value


@pytest.mark.parametrize("height,width", [(2.0, 0.7), (3.0, 0.3), (1.0, 0.6)])
def test_first_quarter_period_fixed_base(height, width):
    sys = System.fixed(height=height, width=width, mass=100.0)
    theta0 = 0.5 * sys.alpha
    tr = simulate(sys, None, theta0=theta0, duration=3.0)
    t1 = tr.impacts[0].t
    assert t1 == pytest.approx(_exact_first_impact(sys, theta0), rel=1e-9)
    # the small-angle formula is right to order α² only (model.md)
    linear = math.acosh(1 / (1 - theta0 / sys.alpha)) / sys.p
    assert t1 == pytest.approx(linear, rel=sys.alpha**2)


def test_model_md_quotes_first_impact():
    tr = simulate(FIXED, None, theta0=0.5 * FIXED.alpha, duration=1.0)
    assert tr.impacts[0].t == pytest.approx(0.5014170, abs=5e-8)


@pytest.mark.parametrize("sign", [1, -1])
def test_uplift_threshold_and_direction(sign):
    sys = System.fixed(height=2.0, width=0.7, mass=3800.0)
    thr = sys.uplift_acceleration
    below = GroundMotion.from_array(np.full(301, sign * 0.999 * thr), dt=0.01)
    tr = simulate(sys, below, duration=3.0)
    assert tr.uplifts == 0 and np.all(tr.theta == 0)
    above = GroundMotion.from_array(np.full(301, sign * 1.001 * thr), dt=0.01)
    tr = simulate(sys, above, duration=3.0)
    assert tr.uplifts >= 1 and tr.uplift_times[0] == 0.0
    # a > 0 lifts about O' (θ < 0), a < 0 about O (θ > 0)
    rocking = tr.theta[(tr.mode != 0) & (tr.theta != 0)]
    assert rocking.size and np.all(np.sign(rocking) == -sign)


def test_isolated_uplift_at_threshold_of_base_acceleration():
    sys = paper_system()
    tr = simulate(sys, load_motion("sine:amp=0.6,freq=1,cycles=2"), duration=6.0)
    assert tr.uplifts >= 1
    for t_up in tr.uplift_times:
        k = np.searchsorted(tr.t, t_up)
        a = -(sys.damping * tr.u_dot[k] + sys.stiffness * tr.u[k]) / sys.total_mass
        assert abs(a) == pytest.approx(sys.uplift_acceleration, rel=1e-7)


def test_overturning_is_located():
    """Rule "alpha" stops where |θ| reaches α; the default rule goes on past α, and a
    fixed base past α and falling after the motion stops early, overturned at the same
    (only) time it rose through α."""
    motion = load_motion("sine:amp=0.9,freq=0.8,cycles=1")
    at_alpha = simulate(FIXED, motion, duration=5.0, settings=AnalyticSettings(overturn="alpha"))
    assert at_alpha.overturned and at_alpha.status == "overturned"
    assert at_alpha.theta_max_over_alpha == pytest.approx(1.0, abs=1e-9)
    assert at_alpha.t[-1] == pytest.approx(at_alpha.overturn_time)
    assert at_alpha.summary()["overturn_rule"] == "alpha"
    past = simulate(FIXED, motion, duration=5.0)
    assert past.overturned and past.summary()["overturn_rule"] == "past-alpha"
    assert past.overturn_time == pytest.approx(at_alpha.overturn_time, abs=1e-9)
    assert past.theta_max_over_alpha > 1.0 and past.t[-1] >= motion.end_time
    assert past.theta[-1] * past.theta_dot[-1] > 0  # falling


def test_energy_balance_with_damping_and_ground_motion():
    sys = System.isolated(height=2.0, width=0.7, mass=3800, base_mass=3800, period=1.0, damping_ratio=0.1)
    tr = simulate(sys, load_motion("sine:amp=0.7,freq=1.2,cycles=3"), duration=8.0)
    assert len(tr.impacts) >= 3 and tr.energy.dashpot_loss[-1] > 0
    assert tr.energy.relative_residual < 1e-8
    # the energy log's total agrees with model.md's energy written out here
    E = _energy(sys, tr.u, tr.u_dot, tr.theta, tr.theta_dot)
    np.testing.assert_allclose(tr.energy.total, E, rtol=1e-12, atol=1e-9 * E.max())


def test_counting_rule_on_history_matches_event_log():
    sys = paper_system()
    tr = simulate(sys, load_motion("sine:amp=0.6,freq=1,cycles=2"), duration=6.0,
                  settings=AnalyticSettings(output_dt=1e-3))
    from_history = counted_sign_changes(tr.theta, sys.alpha, 0.01)
    assert tr.impact_count == len(from_history) > 0
    for (i, peak), imp in zip(from_history, tr.counted_impacts):
        assert tr.t[i] == pytest.approx(imp.t, abs=1e-3)
        assert peak == pytest.approx(imp.amplitude, rel=1e-6)


def test_tolerance_convergence_on_a_pulse():
    m = load_motion("ricker:amp=0.5,freq=1.5")
    loose = simulate(paper_system(), m, settings=AnalyticSettings(rtol=1e-7, atol=1e-9, max_step=0.05))
    tight = simulate(paper_system(), m, settings=AnalyticSettings(rtol=1e-11, atol=1e-13))
    assert loose.theta_max_over_alpha == pytest.approx(tight.theta_max_over_alpha, abs=1e-6)
    assert loose.impact_count == tight.impact_count


def test_resample_and_summary_fields():
    tr = simulate(FIXED, None, theta0=0.3 * FIXED.alpha, duration=2.0)
    r = tr.resample(0.01)
    assert r.t[1] == pytest.approx(0.01) and r.t[-1] == pytest.approx(2.0)
    assert np.interp(0.5, tr.t, tr.theta) == pytest.approx(r.theta[50])
    s = tr.summary()
    for key in ("engine", "alpha", "slenderness", "mass_ratio", "theta_max_over_alpha", "impacts",
                "uplifts", "overturned", "u_max", "runtime_s", "impact_log"):
        assert key in s
    assert s["theta_max_over_alpha"] == pytest.approx(0.3, abs=1e-12)


@pytest.mark.parametrize("kwargs,match", [
    (dict(duration=-1.0), "duration"),
    (dict(theta0=1.0), "theta0"),
    (dict(impact_threshold=2.0), "impact_threshold"),
])
def test_bad_arguments(kwargs, match):
    with pytest.raises(InputError, match=match):
        simulate(FIXED, None, **kwargs)


def test_kobe_isolated_against_model_md(kobe_at2):
    """model.md: with T 1.5 s, ξ 0.2 the isolated θmax/α is ≈ 0.57; the fixed base overturns."""
    m = load_motion(str(kobe_at2)).trimmed(0, 40)
    iso = simulate(paper_system(), m, duration=40.0)
    assert iso.theta_max_over_alpha == pytest.approx(0.57, abs=0.01) and not iso.overturned
    assert iso.energy.relative_residual < 1e-8
    fixed = simulate(paper_system(fixed_base=True), m, duration=40.0)
    assert fixed.overturned


def test_below_no_bounce_slenderness_rocking_ends_at_first_impact():
    # μ = 1: λ_nb = √(4/5) ≈ 0.894; a block with λ = 0.85 has β < 0
    sys = System.from_stiffness(height=1.7, width=2.0, mass=100.0, base_mass=100.0, stiffness=1e4, damping=0.0)
    assert beta(sys.slenderness, sys.mu) < 0
    tr = simulate(sys, None, theta0=0.5 * sys.alpha, duration=3.0)
    assert len(tr.impacts) == 1 and not tr.impacts[0].continued
    assert np.all(tr.theta[tr.t > tr.impacts[0].t] == 0)
    # momentum is kept by the cessation map
    i = tr.impacts[0]
    assert sys.total_mass * i.u_dot_post == pytest.approx(sys.total_mass * i.u_dot_pre + sys.mass * sys.h * i.theta_dot_pre)


def test_an_integrator_failure_is_a_status_not_a_traceback(monkeypatch):
    import isorock.analytic.integrators as integrators  # the driver's integrators: analytic.hybrid's

    def broken(*args, **kwargs):
        raise ValueError("f(a) and f(b) must have different signs")
    monkeypatch.setattr(integrators, "solve_ivp", broken)
    tr = simulate(FIXED, None, theta0=0.3 * FIXED.alpha, duration=1.0)
    assert tr.status == "failed" and "different signs" in tr.message
