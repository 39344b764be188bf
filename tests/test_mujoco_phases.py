"""MuJoCo's phased stepping (mujoco_models/phases.py) against full stepping and against
independent solutions of the isolator: the rest phase is the 1-DOF oscillator, the full
scene takes over before the uplift threshold, free rocking is untouched."""
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from isorock.analytic.motion import load_motion
from isorock.analytic.system import paper_system
from isorock.mujoco_models import Settings, phases, simulate
from isorock.validate.core.compare import first_tilt
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import REPORT_MOTIONS, ROBUST_SINE
from isorock.validate.core.tolerances import tolerance

PHASED, FULL = replace(Settings(), phased=True), replace(Settings(), phased=False)
MUJOCO = get_engine("mujoco")


def test_isolator_steps_are_mujocos_step_of_the_reduced_scene():
    """The written-out step against MuJoCo stepping the one-body scene (the oracle)."""
    s = paper_system()
    f = np.random.default_rng(3).normal(size=4000) * s.total_mass * 2.0
    for integrator in phases.MATCHED:
        u, v = phases.isolator_steps(s.total_mass, s.stiffness, s.damping, 5e-4, 0.01, -0.02, f)
        ur, vr = phases.reduced_steps(s.total_mass, s.stiffness, s.damping, 5e-4, integrator, 0.01, -0.02, f)
        assert np.abs(u - ur).max() <= 1e-11 * np.abs(ur).max()
        assert np.abs(v - vr).max() <= 1e-11 * np.abs(vr).max()


def test_a_weak_record_gives_the_exact_isolator_response():
    """A sine at a tenth of the uplift threshold: the block never rocks, and u is the
    1-DOF oscillator's response (solve_ivp at rtol 1e-10, an independent integration),
    within semi-implicit Euler's first-order error ω·dt at the default step."""
    s = paper_system()
    amp_g = 0.1 * s.uplift_acceleration / 9.80665
    motion = load_motion(f"sine:amp={amp_g!r},freq=1,cycles=3")
    raw = simulate(s, motion, settings=PHASED, duration=6.0)

    def rhs(t, y):
        return [y[1], -(s.stiffness * y[0] + s.damping * y[1]) / s.total_mass - float(motion(np.array([t]))[0])]

    exact = solve_ivp(rhs, (0, 6.0), [0.0, 0.0], t_eval=raw.t, rtol=1e-10, atol=1e-13, max_step=1e-3)
    scale = np.abs(exact.y[0]).max()
    assert np.abs(raw.u - exact.y[0]).max() <= s.omega * Settings.timestep * scale  # measured 0.5·ω·dt
    assert np.abs(raw.theta).max() <= 1e-4 * s.alpha


def test_free_rocking_is_stepped_in_full():
    s = paper_system()
    a = simulate(s, None, settings=FULL, duration=2.0, theta0=0.5 * s.alpha)
    b = simulate(s, None, settings=PHASED, duration=2.0, theta0=0.5 * s.alpha)
    assert np.array_equal(a.theta, b.theta) and np.array_equal(a.u, b.u)


@pytest.mark.parametrize("fixed", [False, True])
def test_a_lifting_pulse_agrees_with_full_stepping(fixed):
    """The robust sine lifts the block on both bases: θmax/α, counted impacts and the
    first uplift of the phased run are those of the full run (measured: Δθmax/α ≤ 2e-4,
    same impacts, first uplift within 0.03 ms), within a tenth of the tolerance table's
    limits for MuJoCo against the exact model."""
    s = paper_system(fixed_base=fixed)
    motion = load_motion(ROBUST_SINE)
    full = MUJOCO.simulate(s, motion, settings=FULL, duration=motion.end_time + 2.0)
    phased = MUJOCO.simulate(s, motion, settings=PHASED, duration=motion.end_time + 2.0)
    assert full.impact_count >= 3 and phased.impact_count == full.impact_count
    assert (abs(phased.theta_max_over_alpha - full.theta_max_over_alpha)
            <= 0.1 * tolerance("mujoco", "theta_max_diff").limit)
    assert abs(first_tilt(phased) - first_tilt(full)) <= 0.1 * tolerance("mujoco", "first_uplift_diff").limit


@pytest.mark.parametrize("fixed", [False, True])
def test_the_full_scene_takes_over_before_the_threshold(fixed, monkeypatch):
    """Every rest phase ends at least LEAD_TIME before the base's absolute acceleration
    first reaches F_HIGH·g·tanα, and before the block first lifts."""
    s = paper_system(fixed_base=fixed)
    motion = load_motion(REPORT_MOTIONS[1])  # a Ricker: the block rests first, then lifts
    spans, rest = [], phases.Phases.rest

    def recording(self, row, k, nstep):
        out = rest(self, row, k, nstep)
        spans.append((k, out[1]))
        return out

    monkeypatch.setattr(phases.Phases, "rest", recording)
    raw = simulate(s, motion, settings=PHASED, duration=motion.end_time + 2.0)
    dt = PHASED.for_system(s).timestep  # the step the run took (it follows the system)
    steps = np.rint(raw.t / dt).astype(int)  # rows sit at whole steps, coarse ones every few
    a = (np.abs(motion((steps + 0.5) * dt)) if fixed else
         np.abs(s.stiffness * raw.u + s.damping * raw.u_dot) / s.total_mass)
    lead = int(round(phases.LEAD_TIME / dt))
    uplift = int(steps[np.argmax(np.abs(raw.theta) > 1e-3 * s.alpha)])
    assert spans and uplift > 0
    for k, end in spans:
        if end < steps[-1]:
            assert np.all(a[(steps >= k) & (steps < end + lead)] < phases.F_HIGH * s.uplift_acceleration)
    assert any(end < uplift - lead for _, end in spans)
    assert not any(k < uplift <= end for k, end in spans)


@pytest.mark.parametrize("bad", ["yes", 1, None])
def test_phased_must_be_a_boolean(bad):
    from isorock.analytic.errors import InputError
    with pytest.raises(InputError, match="phased"):
        Settings(phased=bad)


COARSE_OFF = replace(Settings(), coarse=1)


@pytest.mark.parametrize("fixed", [False, True])
def test_coarse_steps_away_from_impacts_keep_the_run(fixed):
    """Phased runs step coarse (Settings.coarse timesteps) away from impacts: against the same
    run stepped fine throughout the contact phases, the counted impacts are the same and
    θmax/α and the first uplift stay within a quarter of the tolerance table's limits for
    MuJoCo against the exact model (measured on the report's sine: Δθmax/α −2.0e-3
    isolated, −3e-4 fixed); against the exact model itself, within the limit."""
    s = paper_system(fixed_base=fixed)
    motion = load_motion(ROBUST_SINE)
    duration = motion.end_time + 2.0
    fine = MUJOCO.simulate(s, motion, settings=COARSE_OFF, duration=duration)
    coarse = MUJOCO.simulate(s, motion, settings=PHASED, duration=duration)
    exact = get_engine("analytic").simulate(s, motion, duration=duration)
    limit = tolerance("mujoco", "theta_max_diff").limit
    assert fine.impact_count >= 3 and coarse.impact_count == fine.impact_count
    assert abs(coarse.theta_max_over_alpha - fine.theta_max_over_alpha) <= 0.25 * limit
    assert abs(coarse.theta_max_over_alpha - exact.theta_max_over_alpha) <= limit
    assert abs(first_tilt(coarse) - first_tilt(fine)) <= 0.25 * tolerance("mujoco", "first_uplift_diff").limit
    # it did step coarse: fewer rows than steps
    dt = PHASED.for_system(s, duration).timestep
    assert coarse.t.size < 0.7 * fine.t.size and np.all(np.diff(coarse.t) > 0.5 * dt)


def test_every_impact_is_stepped_fine():
    """Each sign change of θ (an impact) lies between two rows one timestep apart: the
    coarse steps stop IMPACT_ZONE coarse steps before θ = 0 and resume SETTLE_TAUS
    contact time constants after."""
    s = paper_system()
    motion = load_motion(ROBUST_SINE)
    duration = motion.end_time + 2.0
    raw = simulate(s, motion, settings=PHASED, duration=duration)
    dt = PHASED.for_system(s, duration).timestep
    cross = np.nonzero(np.sign(raw.theta[1:]) * np.sign(raw.theta[:-1]) < 0)[0] + 1
    assert cross.size >= 3
    np.testing.assert_allclose(raw.t[cross] - raw.t[cross - 1], dt, rtol=1e-6)
    gaps = np.diff(raw.t)
    assert gaps.max() == pytest.approx(Settings.coarse * dt, rel=1e-6)  # and coarse steps elsewhere


def test_the_coarse_step_keeps_mujocos_floor():
    """The coarse step is at most half the contact time constant (MuJoCo raises a shorter
    timeconst to 2·step, which would change the contact), and 1 where the contact's
    parameters are tied to the step."""
    from isorock.mujoco_models import settings_for_timestep
    assert phases.coarse_multiple(Settings().for_system(paper_system())) == 3  # τ = 6 steps
    assert phases.coarse_multiple(settings_for_timestep(1e-4)) == 2             # τ = 4 steps
    assert phases.coarse_multiple(settings_for_timestep(2e-3)) == 1             # direct form
    assert phases.coarse_multiple(replace(Settings(), coarse=1)) == 1


@pytest.mark.parametrize("bad", [0, -1, 1.5, True])
def test_coarse_must_be_a_whole_number(bad):
    from isorock.analytic.errors import InputError
    with pytest.raises(InputError, match="coarse"):
        Settings(coarse=bad)
