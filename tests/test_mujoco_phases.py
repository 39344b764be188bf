"""MuJoCo's phased stepping (mujoco_models/phases.py) against full stepping and against
independent solutions of the isolator: the rest phase is the 1-DOF oscillator, the full
scene takes over before the uplift threshold, free rocking is untouched."""
from dataclasses import replace

import numpy as np
import pytest

from isorock.analytic.motion import load_motion
from isorock.analytic.system import paper_system
from isorock.mujoco_models import Settings, phases, simulate
from isorock.validate.core.compare import first_tilt
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import ROBUST_SINE
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


@pytest.mark.parametrize("fixed", [False, True])
def test_free_rocking_steps_coarse_between_impacts_within_tolerance(fixed):
    """Free rocking from 0.5α on the paper's block steps coarse between impacts: every
    counted impact of the fine run is there, each impact's effective β stays within the
    tolerance table's per-impact limit of the closed form, and the first impact's time
    within a quarter of its limit of the fine run's (the atlas, 100 cells: worst β error
    0.509% against 0.527% fine, t₁ 0.040% against 0.017%)."""
    from isorock.analytic.coefficients import beta as beta_closed_form
    s = paper_system(fixed_base=fixed)
    fine = MUJOCO.simulate(s, None, settings=COARSE_OFF, duration=2.0, theta0=0.5 * s.alpha)
    coarse = MUJOCO.simulate(s, None, settings=PHASED, duration=2.0, theta0=0.5 * s.alpha)
    assert coarse.t.size < 0.6 * fine.t.size  # it did step coarse
    assert len(fine.counted_impacts) >= 3 and len(coarse.counted_impacts) == len(fine.counted_impacts)
    beta = beta_closed_form(s.slenderness, s.mu)
    limit = tolerance("mujoco", "beta_rel_error_per_impact").limit
    assert all(abs(i.beta / beta - 1) <= limit for i in coarse.counted_impacts[:4])
    t1 = tolerance("mujoco", "first_impact_time_rel_error").limit
    assert abs(coarse.counted_impacts[0].t / fine.counted_impacts[0].t - 1) <= 0.25 * t1


def test_step_record_is_the_motion_at_each_steps_middle():
    """StepRecord (evaluated block by block as a run reads it) against the motion evaluated
    at every step's middle at once, read in the orders a run reads it."""
    from isorock.analytic.rest_phase import BLOCK
    from isorock.mujoco_models.state import StepRecord
    motion = load_motion("sine:amp=2.0,freq=1.3,cycles=3")
    dt, nstep = 1e-4, 3 * BLOCK + 17
    whole = motion((np.arange(nstep) + 0.5) * dt)
    xg = StepRecord(motion, dt, nstep)
    assert np.array_equal(xg[10:20], whole[10:20])
    steps = np.array([5, BLOCK + 3, 2 * BLOCK + 1])
    assert np.array_equal(xg[steps], whole[steps])
    assert np.array_equal(xg[BLOCK - 5:], whole[BLOCK - 5:])
    assert xg.size == nstep and np.array_equal(xg[:], whole)


def test_a_kept_mjdata_starts_each_run_as_a_new_one():
    """A thread's MjData is kept between runs and reset: an earlier run's warning counters
    and warm start are gone (a warning left over would fail the next run), and two runs of
    one case, the second on the kept data, give the same history bit for bit."""
    import mujoco
    from isorock.mujoco_models.state import fresh_data
    from isorock.mujoco_models.stepping import _scene
    s = paper_system()
    model = _scene(s, Settings().for_system(s, 2.0))
    data = fresh_data(model)
    data.warning[int(mujoco.mjtWarning.mjWARN_BADQACC)].number = 3
    data.qacc_warmstart[:] = 1.0
    again = fresh_data(model)
    assert again is data
    assert not again.warning.number.any() and not again.qacc_warmstart.any()
    motion = load_motion(ROBUST_SINE)
    first, second = (simulate(s, motion, duration=4.0) for _ in range(2))
    assert np.array_equal(first.theta, second.theta) and np.array_equal(first.u, second.u)
