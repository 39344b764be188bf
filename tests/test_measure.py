"""Measuring a contact engine's raw history (validate/measure.py) on synthetic histories
whose impacts, β and overturning are known independently: closed-form β, hand-made
θ(t) with known half-cycle peaks, and model.md's overturning rules."""
import math

import numpy as np
import pytest

from isorock.analytic import AnalyticSettings, GroundMotion, System, simulate
from isorock.analytic.coefficients import beta
from isorock.analytic.status import Status
from isorock.analytic.trajectory import RawHistory
from isorock.validate.core.measure import CONTACT_WINDOW, measure

FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)
ISOLATED = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
ZERO = GroundMotion.zero()
FINE = AnalyticSettings(output_dt=1e-3)  # stored points every 1 ms, like a contact engine's


def raw(system, t, theta, theta_dot=None, u=None, u_dot=None, **kw):
    n = len(t)
    theta = np.asarray(theta, dtype=float)
    return RawHistory(engine="synthetic", system=system, t=np.asarray(t, dtype=float),
                      u=np.zeros(n) if u is None else np.asarray(u), u_dot=np.zeros(n) if u_dot is None else u_dot,
                      theta=theta, theta_dot=np.gradient(theta, t) if theta_dot is None else theta_dot, **kw)


@pytest.mark.parametrize("system", [FIXED, ISOLATED], ids=["fixed", "isolated"])
def test_rigid_history_sampled_like_a_contact_engine_gives_the_closed_form_beta(system):
    # the rigid model's own states, stored every 1 ms: impacts are instantaneous, so the
    # states outside the window map to θ = 0 exactly and β_eff is the closed form
    s = exact = simulate(system, None, duration=2.0, theta0=0.5 * system.alpha, settings=FINE)
    tr = measure(raw(system, s.t, s.theta, s.theta_dot, s.u, s.u_dot), ZERO)
    ref = beta(system.slenderness, system.mu)
    counted = tr.counted_impacts
    assert len(counted) >= 3
    for got, want in zip(counted, exact.counted_impacts):
        assert got.t == pytest.approx(want.t, abs=1e-3)  # the crossing, read between two samples
        assert got.beta == pytest.approx(ref, rel=1e-6)
    assert tr.status == Status.COMPLETED and not tr.overturned


def test_every_sign_change_is_an_impact_and_the_rule_counts_some():
    # half-cycles of known peaks: 0.5α, 0.005α (below the 1% threshold), 0.3α
    a = FIXED.alpha
    peaks = [0.5, 0.005, 0.3]
    t, theta, sign = [], [], 1.0
    for k, p in enumerate(peaks):
        tt = np.linspace(k, k + 1, 201)[:-1]
        t.append(tt)
        theta.append(sign * p * a * np.sin(np.pi * (tt - k)))
        sign = -sign
    t = np.concatenate(t + [np.array([3.0, 3.1])])
    theta = np.concatenate(theta + [sign * np.array([0.01 * a, 0.02 * a])])  # a last half-cycle begins
    tr = measure(raw(FIXED, t, theta), ZERO)
    assert [round(i.amplitude / a, 6) for i in tr.impacts] == [0.5, 0.005, 0.3]
    assert [i.counted for i in tr.impacts] == [True, False, True]
    assert tr.impact_count == 2 and tr.summary()["impacts_total"] == 3
    assert math.isnan(tr.impacts[1].beta)  # not counted: no β measured for chatter


def test_uplift_is_read_where_theta_leaves_the_rest_band():
    t = np.linspace(0, 2, 2001)
    theta = np.where(t > 0.5, 0.2 * FIXED.alpha * np.sin(np.pi * (t - 0.5)), 0.0)
    tr = measure(raw(FIXED, t, theta), ZERO)
    assert len(tr.uplift_times) == 1 and tr.uplift_times[0] == pytest.approx(0.5, abs=0.01)


def _lean(peak, end):
    """θ/α rising to `peak` at t = 1 s and ending at `end` at t = 3 s (piecewise linear)."""
    t = np.linspace(0, 3, 3001)
    return t, np.interp(t, [0, 1, 3], [0.0, peak, end]) * FIXED.alpha


def test_overturning_past_alpha_follows_model_md():
    t, th = _lean(1.3, 0.2)  # leaned past α and came back: survives by the past-α rule
    assert not measure(raw(FIXED, t, th), ZERO).overturned
    conservative = measure(raw(FIXED, t, th), ZERO, overturn_rule="alpha")  # the conservative rule
    assert conservative.overturned and conservative.overturn_time == pytest.approx(1 / 1.3, abs=2e-3)
    assert conservative.summary()["overturn_rule"] == "alpha"
    t, th = _lean(0.8, 1.2)  # ends beyond α: overturned, at the last time it passed α
    over = measure(raw(FIXED, t, th), ZERO)
    assert over.overturned and over.overturn_time == pytest.approx(1 + 2 * 0.2 / 0.4, abs=2e-3)
    assert over.summary()["overturn_rule"] == "past-alpha"


def test_measure_reports_overturning_in_the_status_and_keeps_failures():
    t, th = _lean(0.8, 1.2)
    tr = measure(raw(FIXED, t, th), ZERO)
    assert tr.overturned and tr.status == Status.OVERTURNED and "> α" in tr.message
    failed = measure(raw(FIXED, t, th, status=Status.FAILED, message="blew up"), ZERO)
    assert failed.status == Status.FAILED and failed.message == "blew up"  # a failure is never renamed


def test_contact_window_is_a_measuring_parameter():
    s = simulate(FIXED, None, duration=1.2, theta0=0.5 * FIXED.alpha, settings=FINE)
    history = raw(FIXED, s.t, s.theta, s.theta_dot)
    for window in (0.5 * CONTACT_WINDOW, CONTACT_WINDOW):
        tr = measure(history, ZERO, window=window)
        assert tr.counted_impacts[0].beta == pytest.approx(beta(FIXED.slenderness, 0.0), rel=1e-6)


def test_a_block_that_slides_says_so_in_its_status():
    t = np.linspace(0, 1, 101)
    theta = 0.2 * FIXED.alpha * np.sin(np.pi * t)
    slid = measure(raw(FIXED, t, theta, extras={"pivot_slip_max": 0.05 * FIXED.b}), ZERO)
    assert slid.status == Status.SLID and "assumes no sliding" in slid.message
    held = measure(raw(FIXED, t, theta, extras={"pivot_slip_max": 1e-5}), ZERO)
    assert held.status == Status.COMPLETED


# --- issue 34: β measured where the base moves as the model says it moves ---------------------------

PAPER_BLOCK = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)


def _isolated_on(isolator, height=1.2, width=0.3, mass=250.0, base_mass=500.0):
    return System.with_isolator(height=height, width=width, mass=mass, base_mass=base_mass, isolator=isolator)


def _measured_against_the_models_own_impacts(system, pulse, duration, theta0=0.0):
    """The exact model's own history, stored every 1 ms as a contact engine's is, measured as a
    contact engine's: each counted impact's β against the model's own θ̇⁺/θ̇⁻ (an impact is
    instantaneous in the model, so the states a window away map onto it exactly)."""
    from isorock.analytic.motion import load_motion
    motion = ZERO if pulse is None else load_motion(pulse)
    exact = simulate(system, motion, duration=duration, settings=FINE, theta0=theta0 * system.alpha)
    extras = {k: v for k, v in exact.extras.items() if k == "isolator_slider"}
    tr = measure(raw(system, exact.t, exact.theta, exact.theta_dot, exact.u, exact.u_dot, extras=extras), motion)
    pairs = [(got.beta, want.theta_dot_post / want.theta_dot_pre)
             for got, want in zip(tr.counted_impacts, exact.counted_impacts)]
    assert len(tr.counted_impacts) == len(exact.counted_impacts) >= 3
    assert all(abs(g.t - w.t) < 1e-3 for g, w in zip(tr.counted_impacts, exact.counted_impacts))
    return pairs


@pytest.mark.parametrize("isolator, pulse", [
    # issue 34's case: μ_f 0.3 > tanα 0.25 sticks between impacts, and each impact kicks it loose
    # for a few ms (the model's u̇⁺ = 0.010 m/s): β read 3% high, as if the base were pinned
    ("friction-pendulum", "ricker:amp=0.5,freq=2.0"),
    ("ball-in-bowl", "ricker:amp=0.6,freq=1.5"),
    # double pendulums on the paper's block (tests/test_isolator_engines.py's): the windows hold
    # every phase (regime II, regime I, pinned then slipping, a reversal), and the element's
    # slider is read off the rows as an engine's (extras["isolator_slider"]); no β before
    ("double-friction-pendulum", "sine:amp=0.5,freq=1.5,cycles=1"),
    ("double-friction-pendulum-pinned", "ricker:amp=0.8,freq=2"),
], ids=["pendulum-sticking", "bowl", "double", "double-pinned"])
def test_beta_on_a_base_the_impact_kicks_loose_is_the_models(isolator, pulse):
    from isorock.analytic.system import BallInBowl, DoubleFrictionPendulum, FrictionPendulum
    if isolator.startswith("double"):
        series = (0.15, 0.03, 0.3, 0.2) if isolator == "double-friction-pendulum" else (0.2, 0.1, 0.3, 0.4)
        system = System.with_isolator(**PAPER_BLOCK, isolator=DoubleFrictionPendulum(*series))
    else:
        system = _isolated_on(FrictionPendulum(radius=1.0, friction_coefficient=0.3) if isolator == "friction-pendulum"
                              else BallInBowl(radius=0.5, rolling_resistance=0.05))
    pairs = _measured_against_the_models_own_impacts(system, pulse, 4.5)
    assert all(math.isfinite(got) for got, _ in pairs), pairs  # every impact measured
    assert max(abs(got / want - 1) for got, want in pairs) < 1e-6, pairs


@pytest.mark.parametrize("kind", ["fixed", "linear", "pendulum-sliding", "bearing"])
def test_beta_measured_on_every_isolator_kind_is_the_models_where_it_is_measured(kind):
    """Every kind the measure maps: where β is measured, it is the model's own to 1e-6 (a kind
    whose element changes phase inside the window gives no β, never a wrong one)."""
    from isorock.analytic.system import BilinearIsolator, FrictionPendulum
    system, pulse, theta0 = {
        "fixed": (System.fixed(height=1.2, width=0.3, mass=250.0), "ricker:amp=0.5,freq=2.0", 0.0),
        "linear": (ISOLATED, None, 0.5),  # free rocking: the base moves through every impact
        "pendulum-sliding": (System.with_isolator(**PAPER_BLOCK, isolator=FrictionPendulum(
            radius=0.3, friction_coefficient=0.1)), "sine:amp=0.5,freq=1.5,cycles=1", 0.0),
        "bearing": (System.with_isolator(**PAPER_BLOCK, isolator=BilinearIsolator(
            stiffness=3e6, post_yield_ratio=0.1, yield_displacement=0.002, damping=1000.0)),
            "ricker:amp=0.8,freq=2", 0.0)}[kind]
    pairs = _measured_against_the_models_own_impacts(system, pulse, 4.5, theta0)
    measured = [(g, w) for g, w in pairs if math.isfinite(g)]
    assert len(measured) >= (1 if kind == "bearing" else 3), pairs
    assert max(abs(g / w - 1) for g, w in measured) < 1e-6, pairs
