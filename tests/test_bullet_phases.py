"""PyBullet's phased stepping (bullet_models/rest.py, the shared rules of
analytic/rest_phase.py) against stepping Bullet throughout and against independent
solutions: the rest phase is the 1-DOF oscillator, Bullet takes over before the uplift
threshold, free rocking is untouched."""
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

pytest.importorskip("pybullet")

from isorock.analytic import rest_phase  # noqa: E402
from isorock.analytic.motion import load_motion  # noqa: E402
from isorock.analytic.system import paper_system  # noqa: E402
from isorock.bullet_models import Settings, rest, simulate  # noqa: E402
from isorock.validate.core.compare import first_tilt  # noqa: E402
from isorock.validate.core.engines import get_engine  # noqa: E402
from isorock.validate.core.scenarios import REPORT_MOTIONS, ROBUST_SINE  # noqa: E402
from isorock.validate.core.tolerances import tolerance  # noqa: E402

PHASED, FULL = Settings(), replace(Settings(), phased=False)
BULLET = get_engine("bullet")


def test_linear_steps_is_the_map_stepped_one_by_one():
    """The mode-by-mode filter against x' = A x + B f stepped in a Python loop (the
    oracle), for an underdamped (complex pair), an overdamped (real modes) and a
    three-state map (PyBullet's control step)."""
    rng = np.random.default_rng(5)
    f = rng.normal(size=3000)
    maps = [(np.array([[0.999, 1e-3], [-0.5, 0.998]]), np.array([1e-6, 1e-3])),
            (np.array([[0.99, 0.0], [0.01, 0.95]]), np.array([1.0, 0.5])),
            (np.array([[0.9995, 1.1e-3, 1e-7], [-0.9, 0.997, 1e-4], [0.0, 1.0, 0.0]]), np.array([-6e-7, -1.1e-3, 0.0]))]
    for a, b in maps:
        x0 = rng.normal(size=a.shape[0])
        got = rest_phase.linear_steps(a, b, x0, f).T  # a column per step
        x, want = x0.copy(), []
        for fk in f:
            x = a @ x + b * fk
            want.append(x)
        want = np.array(want)
        assert np.abs(got - want).max() <= 1e-10 * np.abs(want).max()


def test_a_weak_record_gives_the_exact_isolator_response():
    """A sine at a tenth of the uplift threshold: the block never rocks, Bullet is
    stepped only for the first SETTLE_TIME, and u is the 1-DOF oscillator's response
    (solve_ivp at rtol 1e-10, independent) within the control step's first-order error."""
    s = paper_system()
    amp_g = 0.1 * s.uplift_acceleration / 9.80665
    motion = load_motion(f"sine:amp={amp_g!r},freq=1,cycles=3")
    raw = simulate(s, motion, settings=PHASED, duration=6.0)

    def rhs(t, y):
        return [y[1], -(s.stiffness * y[0] + s.damping * y[1]) / s.total_mass - float(motion(np.array([t]))[0])]

    exact = solve_ivp(rhs, (0, 6.0), [0.0, 0.0], t_eval=raw.t, rtol=1e-10, atol=1e-13, max_step=1e-3)
    scale = np.abs(exact.y[0]).max()
    control = PHASED.for_system(s).control_step
    assert np.abs(raw.u - exact.y[0]).max() <= s.omega * control * scale
    assert np.abs(raw.theta).max() <= 1e-4 * s.alpha


def test_free_rocking_is_stepped_throughout():
    s = paper_system()
    a = simulate(s, None, settings=FULL, duration=1.5, theta0=0.5 * s.alpha)
    b = simulate(s, None, settings=PHASED, duration=1.5, theta0=0.5 * s.alpha)
    assert np.array_equal(a.theta, b.theta) and np.array_equal(a.u, b.u)


@pytest.mark.parametrize("fixed", [False, True])
def test_a_lifting_pulse_agrees_with_stepping_throughout(fixed):
    """The robust sine lifts the block on both bases: θmax/α, counted impacts and the
    first uplift of the phased run are those of the full run within a tenth of the
    tolerance table's limits for PyBullet against the exact model."""
    s = paper_system(fixed_base=fixed)
    motion = load_motion(ROBUST_SINE)
    full = BULLET.simulate(s, motion, settings=FULL, duration=motion.end_time + 2.0)
    phased = BULLET.simulate(s, motion, settings=PHASED, duration=motion.end_time + 2.0)
    assert full.impact_count >= 3 and phased.impact_count == full.impact_count
    assert (abs(phased.theta_max_over_alpha - full.theta_max_over_alpha)
            <= 0.1 * tolerance("bullet", "theta_max_diff").limit)
    assert abs(first_tilt(phased) - first_tilt(full)) <= 0.1 * tolerance("bullet", "first_uplift_diff").limit


@pytest.mark.parametrize("fixed", [False, True])
def test_bullet_takes_over_before_the_threshold(fixed, monkeypatch):
    """Every rest phase ends at least LEAD_TIME before the base's absolute acceleration
    first reaches F_HIGH·g·tanα, and before the block first lifts; and there are rest
    phases (the run did skip Bullet's steps)."""
    s = paper_system(fixed_base=fixed)
    motion = load_motion(REPORT_MOTIONS[1])  # a Ricker: the block rests first, then lifts
    spans, phase = [], rest.Rest.phase

    def recording(self, i, end, *state):
        skipped, states = phase(self, i, end, *state)
        spans.append((i, i + skipped))
        return skipped, states

    monkeypatch.setattr(rest.Rest, "phase", recording)
    raw = simulate(s, motion, settings=PHASED, duration=motion.end_time + 2.0)
    dt = PHASED.for_system(s).control_step
    steps = np.rint(raw.t / dt).astype(int)
    a = (np.abs(motion((steps + 0.5) * dt)) if fixed else
         np.abs(s.stiffness * raw.u + s.damping * raw.u_dot) / s.total_mass)
    lead = int(round(rest_phase.LEAD_TIME / dt))
    uplift = int(steps[np.argmax(np.abs(raw.theta) > 1e-3 * s.alpha)])
    spans = [(i, e) for i, e in spans if e > i]
    assert spans and uplift > 0
    for i, end in spans:
        if end < steps[-1]:
            assert np.all(a[(steps >= i) & (steps < end + lead)] < rest_phase.F_HIGH * s.uplift_acceleration)
    assert not any(i < uplift <= end for i, end in spans)


@pytest.mark.parametrize("bad", [1, "yes", None])
def test_phased_must_be_a_boolean(bad):
    from isorock.analytic.errors import InputError
    with pytest.raises(InputError, match="phased"):
        Settings(phased=bad)
