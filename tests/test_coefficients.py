"""Closed forms against independent oracles: Housner's limit, momentum and angular
momentum computed from positions and velocities, the no-bounce boundary."""
import math

import numpy as np
import pytest

from isorock.analytic import System, beta, beta2, beta3, beta_housner, no_bounce_slenderness, InputError
from isorock.analytic.hybrid import impact_map


@pytest.mark.parametrize("lam", [1.5, 2.857, 4.0, 10.0])
def test_mu_to_zero_gives_housner(lam):
    # Housner's form is written with α = atan(1/λ), a different expression
    assert beta(lam, 0.0) == pytest.approx(beta_housner(lam), abs=1e-14)
    assert beta(lam, 1e-9) == pytest.approx(1 - 1.5 * math.sin(math.atan(1 / lam)) ** 2, abs=1e-8)


def test_paper_example():
    # model.md: λ = 2.857, μ = 1 gives β = 0.75418 (with λ = 2/0.7)
    assert beta(2.0 / 0.7, 1.0) == pytest.approx(0.75418, abs=5e-6)


@pytest.mark.parametrize("mu", [0.0, 0.3, 1.0, 2.0, 50.0])
def test_beta_positive_exactly_above_no_bounce(mu):
    lam0 = no_bounce_slenderness(mu)
    assert beta(lam0, mu) == pytest.approx(0.0, abs=1e-14)
    assert beta(lam0 * (1 + 1e-9), mu) > 0
    assert beta(lam0 * (1 - 1e-9), mu) < 0


def _system(lam, mu, h=1.0):
    return System.from_stiffness(height=2 * h, width=2 * h / lam, mass=1000.0, base_mass=1000.0 / mu,
                                 stiffness=5e4, damping=0.0)


def _horizontal_momentum(sys, u_dot, theta_dot):
    # base + block; at θ = 0 the centroid's horizontal velocity is u̇ + h θ̇
    return sys.base_mass * u_dot + sys.mass * (u_dot + sys.h * theta_dot)


def _angular_momentum_about(sys, corner_x, s, u_dot, theta_dot):
    """Block's angular momentum about a corner at height 0, from positions and
    velocities: I θ̇ + m (r_z v_x − r_x v_z), r = centroid − corner, θ positive clockwise
    (x right, z up), the block rocking about corner s at θ = 0."""
    r_x, r_z = 0.0 - corner_x, sys.h  # centroid at x = 0
    pivot_x = s * sys.b  # rocking about O (s = +1) pivots on the corner at +b
    # rigid rotation about the pivot: v = u̇ e_x + θ̇ ω × (centroid − pivot), clockwise
    d_x, d_z = 0.0 - pivot_x, sys.h
    v_x = u_dot + theta_dot * d_z
    v_z = -theta_dot * d_x
    return sys.inertia * theta_dot + sys.mass * (r_z * v_x - r_x * v_z)


@pytest.mark.parametrize("lam,mu", [(2.857, 1.0), (5.0, 0.5), (3.0, 4.0), (8.0, 0.05)])
@pytest.mark.parametrize("s", [1, -1])
def test_impact_map_conserves_momenta(lam, mu, s):
    sys = _system(lam, mu)
    rng = np.random.default_rng(7)
    for _ in range(5):
        u_dot = rng.normal()
        theta_dot = -s * abs(rng.normal())  # landing from rocking about s
        thd_post, ud_post = impact_map(sys, theta_dot, u_dot, continued=True)
        assert _horizontal_momentum(sys, ud_post, thd_post) == pytest.approx(
            _horizontal_momentum(sys, u_dot, theta_dot), rel=1e-13, abs=1e-12)
        impacting = -s * sys.b  # the corner that lands is the other one
        assert _angular_momentum_about(sys, impacting, -s, ud_post, thd_post) == pytest.approx(
            _angular_momentum_about(sys, impacting, s, u_dot, theta_dot), rel=1e-12, abs=1e-12)
        # cessation keeps the horizontal momentum with the block at rest on the base
        thd_c, ud_c = impact_map(sys, theta_dot, u_dot, continued=False)
        assert thd_c == 0.0
        assert _horizontal_momentum(sys, ud_c, 0.0) == pytest.approx(
            _horizontal_momentum(sys, u_dot, theta_dot), rel=1e-13, abs=1e-12)


def test_beta2_beta3_units_scale_with_height():
    assert beta2(3.0, 1.0, 2.0) == pytest.approx(2 * beta2(3.0, 1.0, 1.0), rel=1e-15)
    assert beta3(1.0, 1.0) == pytest.approx(0.5)
    assert beta2(3.0, 0.0, 1.0) == 0.0 and beta3(0.0, 1.0) == 0.0


@pytest.mark.parametrize("call,field", [
    (lambda: beta(-1.0, 1.0), "slenderness"),
    (lambda: beta(2.0, -0.1), "mass_ratio"),
    (lambda: beta(float("nan"), 1.0), "slenderness"),
    (lambda: beta2(2.0, 1.0, 0.0), "half_height"),
    (lambda: no_bounce_slenderness(float("inf")), "mass_ratio"),
])
def test_bad_arguments_name_the_field(call, field):
    with pytest.raises(InputError, match=field):
        call()


@pytest.mark.parametrize("field,args", [("slenderness", (1e300, 1.0)), ("mass_ratio", (4.0, 1e300))])
def test_closed_forms_refuse_values_past_double_precision(field, args):
    """λ² of λ = 1e300 overflows a double (Python's float power raised OverflowError, a
    traceback from `isorock beta`): such a value is refused by name, not computed."""
    with pytest.raises(InputError, match=field):
        beta(*args)


def test_closed_forms_near_the_bound_reach_their_limits():
    # λ → ∞: β → 1 and β₂ → 0 (the block no longer rotates relative to the base's slide);
    # the oracle is the limit of the written-out expressions, not the code's value
    assert beta(1e99, 1.0) == pytest.approx(1.0, abs=1e-15)
    assert beta2(1e99, 1.0, 1.0) == pytest.approx(0.0, abs=1e-150)
    # μ → ∞ (a weightless base): β → (λ² − 2)/(λ² + 4)
    assert beta(4.0, 1e99) == pytest.approx((16 - 2) / (16 + 4), rel=1e-12)
