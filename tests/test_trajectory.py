import numpy as np
import pytest

from isorock.analytic import AnalyticSettings, System, simulate
from isorock.analytic.trajectory import counted_sign_changes, half_cycles, hermite


def test_hermite_is_exact_for_cubics_and_fourth_order_for_sine():
    t = np.linspace(0, 1, 11)
    tn = np.linspace(0, 1, 97)
    y, dy = 2 * t**3 - t**2 + 3 * t - 1, 6 * t**2 - 2 * t + 3
    np.testing.assert_allclose(hermite(t, y, dy, tn), 2 * tn**3 - tn**2 + 3 * tn - 1, atol=1e-13)
    errs = []
    for n in (21, 41):
        t = np.linspace(0, 2, n)
        errs.append(np.max(np.abs(hermite(t, np.sin(3 * t), 3 * np.cos(3 * t), tn * 2) - np.sin(3 * tn * 2))))
    assert errs[0] / errs[1] == pytest.approx(16, rel=0.25)  # halving the step divides the error by 2⁴


def test_hermite_respects_repeated_times():
    # a kink at t = 1 stored twice, as the integrator stores an impact
    t = np.array([0.0, 1.0, 1.0, 2.0])
    y = np.array([0.0, 1.0, 1.0, 0.0])
    dy = np.array([1.0, 1.0, -1.0, -1.0])
    np.testing.assert_allclose(hermite(t, y, dy, np.array([0.5, 1.5])), [0.5, 0.5], atol=1e-15)


def test_resample_matches_a_dense_run():
    sys = System.fixed(height=2.0, width=0.7, mass=1.0)
    coarse = simulate(sys, None, theta0=0.5 * sys.alpha, duration=2.0)
    dense = simulate(sys, None, theta0=0.5 * sys.alpha, duration=2.0, settings=AnalyticSettings(output_dt=1e-5))
    r = coarse.resample(1e-3)
    assert np.max(np.abs(r.theta - np.interp(r.t, dense.t, dense.theta))) < 1e-8 * sys.alpha


def test_counting_rule_on_a_decaying_sine():
    t = np.linspace(0, 10, 100001)
    alpha = 0.3
    theta = alpha * 0.5 * np.exp(-0.5 * t) * np.sin(2 * np.pi * t)
    changes = half_cycles(theta)
    # sign changes every half period; peak of the half-cycle ending at k/2 is ≈ 0.5α·e^{-0.5(k/2-0.25)}
    assert len(changes) == 19
    counted = counted_sign_changes(theta, alpha, 0.01)
    expected = sum(1 for k in range(1, 20) if 0.5 * np.exp(-0.5 * (k / 2 - 0.25)) > 0.0101)
    assert len(counted) == expected
    # zeros carry no sign: landing, resting and lifting the same way is not an impact
    assert half_cycles(np.array([0.1, 0.0, 0.0, 0.2])) == []
    assert half_cycles(np.array([0.1, 0.0, 0.0, -0.2])) == [(3, 0.1)]
