"""The MuJoCo scene against the closed forms and the analytic model (model.md).

Runs are short (a few simulated seconds at the default settings) so the whole file
stays fast; the analytic model is the oracle for overturning.
"""
import dataclasses
import math
import xml.etree.ElementTree as ET

import mujoco
import numpy as np
import pytest

from isorock.analytic import hybrid
from isorock.analytic.coefficients import beta
from isorock.analytic.errors import InputError
from isorock.analytic.motion import GroundMotion, load_motion
from isorock.analytic.system import System
from isorock import mujoco_models as scene
from isorock.analytic import kinematics
from isorock.mujoco_models import stepping
from isorock.mujoco_models.scene import CORNER_RADIUS, SCENE_FORMAT
from isorock.mujoco_models.settings import JOINTS
from isorock.validate.core.compare import exact_first_impact_time
from isorock.validate.core.engines import get_engine
from isorock.validate.core.measure import beta_errors
from isorock.validate.core.tolerances import tolerance

#: This engine at its default settings, measured: simulate returns the shared Trajectory.
MUJOCO = get_engine("mujoco")
#: Limits from the one tolerance table (validate/core/tolerances.py), each with its reason there.
TOL = {
    "beta": tolerance("mujoco", "beta_rel_error_per_impact").limit,
    "lift_off": tolerance("mujoco", "lift_off_after_impact").limit,
    "rest_tilt": tolerance("mujoco", "rest_tilt").limit,
    "first_impact": tolerance("mujoco", "first_impact_time_rel_error").limit,
    "pivot_slip": tolerance("mujoco", "pivot_slip").limit,
}

H, B07, B04, M = 2.0, 0.7, 0.4, 3800.0


def fixed(width=B07):
    return System.fixed(height=H, width=width, mass=M, base_mass=M)


def isolated(width=B07):
    return System.isolated(height=H, width=width, mass=M, base_mass=M, period=1.5, damping_ratio=0.2)


def stiff():
    """An isolator of 1 ms: MuJoCo's 0.5 ms step goes unstable on it (a run that blows up
    within every input bound; a 1e10 g pulse did before accelerations were bounded)."""
    return System.isolated(height=H, width=B07, mass=M, base_mass=M, period=0.001, damping_ratio=0.0)


def free_rocking(system, settings=None, duration=2.5):
    return MUJOCO.simulate(system, None, settings=settings, duration=duration, theta0=0.5 * system.alpha)


# --- the scene -----------------------------------------------------------------------

def _names(model, objtype, n):
    return {mujoco.mj_id2name(model, objtype, i) for i in range(n)}


def test_scene_isolated_structure():
    system = isolated()
    text = scene.scene_text(system, scene.Settings())
    root = ET.fromstring(text)
    assert len(root.findall("contact/pair")) == 1
    model = mujoco.MjModel.from_xml_string(text)
    assert _names(model, mujoco.mjtObj.mjOBJ_BODY, model.nbody) == {"world", "base", "block"}
    assert model.njnt == 4
    kinds = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j): int(model.jnt_type[j])
             for j in range(model.njnt)}
    slide, hinge = int(mujoco.mjtJoint.mjJNT_SLIDE), int(mujoco.mjtJoint.mjJNT_HINGE)
    assert kinds == {"base_slide": slide, "block_x": slide, "block_z": slide, "block_theta": hinge}
    base = model.joint("base_slide")
    assert base.stiffness[0] == pytest.approx(system.stiffness, rel=1e-12)
    assert model.dof_damping[base.dofadr[0]] == pytest.approx(system.damping, rel=1e-12)
    np.testing.assert_array_equal(model.jnt_axis[model.joint("block_theta").id], [0, 1, 0])
    # exactly one contact pair, block–base; nothing collides by contype/conaffinity
    assert model.npair == 1
    assert {int(model.pair_geom1[0]), int(model.pair_geom2[0])} == {model.geom("block_geom").id,
                                                                    model.geom("base_geom").id}
    assert not model.geom_contype.any() and not model.geom_conaffinity.any()
    # masses and the block's inertia about y, m(b² + h²)/3
    assert model.body("block").mass[0] == pytest.approx(M)
    assert model.body("base").mass[0] == pytest.approx(M)
    assert model.body("block").inertia[1] == pytest.approx(system.inertia, rel=1e-12)
    np.testing.assert_allclose(model.geom("block_geom").size[[0, 2]], [system.b, system.h])


def test_scene_fixed_base_and_free_joint():
    model = scene.build_model(fixed(), scene.Settings(joint="free"))
    assert model.njnt == 1 and model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    assert model.body("base").jntnum[0] == 0  # welded to the ground
    assert model.npair == 1


def test_scene_carries_settings():
    s = scene.Settings(timestep=2e-4, solref=(0.001, 1.0), solimp=(0.95, 0.99, 0.002), cone="pyramidal",
                       integrator="RK4", friction=2.0, noslip=3, solver="CG")
    model = scene.build_model(isolated(), s)
    assert model.opt.solver == mujoco.mjtSolver.mjSOL_CG
    assert model.opt.timestep == 2e-4
    assert model.opt.integrator == mujoco.mjtIntegrator.mjINT_RK4
    assert model.opt.cone == mujoco.mjtCone.mjCONE_PYRAMIDAL
    assert model.opt.noslip_iterations == 3
    np.testing.assert_allclose(model.pair_solref[0], [0.001, 1.0])
    np.testing.assert_allclose(model.pair_solimp[0][:3], [0.95, 0.99, 0.002])
    assert model.pair_friction[0][0] == 2.0


def test_settings_for_timestep_ties_solref_to_the_step():
    # the defaults are one rung (a rung is its named step: it does not follow the system)
    assert scene.settings_for_timestep(5e-4) == dataclasses.replace(scene.Settings(), follow_system=False)
    s = scene.settings_for_timestep(2.5e-4, friction=2.0)
    assert s.timestep == 2.5e-4 and s.solref == (1e-3, 2.0) and s.friction == 2.0
    # from 1e-3 up: the direct form, stiffness 0.05/dt² and damping 0.6/dt
    s = scene.settings_for_timestep(2e-3)
    assert s.solref == pytest.approx((-0.05 / 2e-3**2, -0.6 / 2e-3)) and s.solimp == (0.9, 0.9, 0.001)
    assert scene.settings_for_timestep(1e-3).solref[0] < 0 > scene.settings_for_timestep(1e-3).solref[1]


def test_coarse_rung_rocks_without_hopping():
    """The bench's coarsest rung (2e-3 s, direct solref): measured worst β error 1.7% at
    θ0 = α/2 (2.6% over θ0 = 0.3–0.8 α; 8% with the time constant tied to 4 steps)."""
    system, duration = FREE_CASES["lambda 2.857 mu 1"]
    traj = free_rocking(system, scene.settings_for_timestep(2e-3), duration=duration)
    errors = beta_errors(traj, 4)
    assert len(errors) == 4 and max(abs(e) for e in errors) < 0.03, errors
    assert traj.extras["lift_off_max_after_impact"] < TOL["lift_off"]


@pytest.mark.parametrize("field, value", [
    ("timestep", 0.0), ("timestep", 0.1), ("integrator", "rk4"), ("cone", "round"), ("solver", "newton"),
    ("solref", (0.002,)), ("solref", (0.002, -1.0)), ("solref", (0.0005, 1.0)),
    ("solimp", (0.9, 0.99)), ("solimp", (1.5, 0.99, 0.001)), ("friction", 0.0),
    ("noslip", -1), ("noslip", 1.5), ("joint", "ball"),
    ("contact", "spheres"),
])
def test_settings_reject_bad_values(field, value):
    with pytest.raises(InputError, match=field):
        scene.Settings(**{field: value})


def test_simulate_rejects_bad_input():
    with pytest.raises(InputError, match="theta0"):
        scene.simulate(fixed(), None, theta0=0.4, duration=0.1)
    with pytest.raises(InputError, match="duration"):
        scene.simulate(fixed(), None, duration=-1.0)


# --- free rocking against the closed form ---------------------------------------------

# (system, duration that holds 4 counted impacts and the window after the 4th)
FREE_CASES = {
    "lambda 2.857 fixed": (fixed(), 2.4),
    "lambda 2.857 mu 1": (isolated(), 1.4),
    "lambda 5 fixed": (fixed(B04), 3.6),
    "lambda 5 mu 1": (isolated(B04), 2.2),
}


@pytest.mark.parametrize("case", FREE_CASES)
def test_free_rocking_beta_per_impact(case):
    system, duration = FREE_CASES[case]
    traj = free_rocking(system, duration=duration)
    errors = beta_errors(traj, 4)
    assert len(errors) == 4, f"{traj.impact_count} counted impacts in {duration} s"
    worst = max(abs(e) for e in errors)
    assert worst < TOL["beta"], (f"effective β vs {beta(system.slenderness, system.mu):.6f}: "
                                 f"errors {[f'{100 * e:+.3f}%' for e in errors]}")
    assert traj.extras["lift_off_max_after_impact"] < TOL["lift_off"]
    assert traj.extras["pivot_slip_max"] < TOL["pivot_slip"]


@pytest.mark.parametrize("joint, n_corners", [("planar", 2), ("free", 4)])
def test_corner_contact_scene(joint, n_corners):
    """contact="corners": one block-corner sphere–base pair per corner the motion can
    use (2 in the plane, 4 with the free joint) instead of the one box–box pair, so the
    scene holds several pairs, all of them block–base; mass and inertia unchanged."""
    system = isolated()
    model = scene.build_model(system, scene.Settings(contact="corners", joint=joint))
    corners = {model.geom(f"corner_{x}" + (f"_{k}" if joint == "free" else "")).id
               for x in ("pos", "neg") for k in range(n_corners // 2)}
    assert model.npair == n_corners
    pairs = {frozenset((int(model.pair_geom1[i]), int(model.pair_geom2[i]))) for i in range(model.npair)}
    assert pairs == {frozenset((g, model.geom("base_geom").id)) for g in corners}
    assert not model.geom_contype.any() and not model.geom_conaffinity.any()
    assert model.body("block").mass[0] == pytest.approx(M)
    assert model.body("block").inertia[1] == pytest.approx(system.inertia, rel=1e-12)
    np.testing.assert_allclose(model.geom_size[list(corners), 0], CORNER_RADIUS)


@pytest.mark.parametrize("case", FREE_CASES)
def test_corner_contact_beta_per_impact(case):
    # measured worst 0.67% at θ0 = α/2 (1.1% over θ0 = 0.3–0.8 α): docs/mujoco.md
    system, duration = FREE_CASES[case]
    traj = free_rocking(system, scene.Settings(contact="corners"), duration=duration)
    errors = beta_errors(traj, 4)
    assert len(errors) == 4 and max(abs(e) for e in errors) < TOL["beta"], errors
    assert traj.extras["lift_off_max_after_impact"] < TOL["lift_off"]


@pytest.mark.parametrize("case", FREE_CASES)
def test_event_resolved_beta_per_impact(case):
    # coarse 3e-3 s steps, fine 2.5e-4 s around impacts: measured worst 0.47% at θ0 = α/2
    system, duration = FREE_CASES[case]
    traj = free_rocking(system, scene.event_resolved_settings(), duration=duration)
    errors = beta_errors(traj, 4)
    assert len(errors) == 4 and max(abs(e) for e in errors) < TOL["beta"], errors
    assert traj.extras["lift_off_max_after_impact"] < TOL["lift_off"]
    np.testing.assert_allclose(np.diff(traj.t), 3e-3)  # the history keeps the coarse grid


def test_event_resolved_rest_and_uplift():
    system = fixed()
    s = scene.event_resolved_settings()
    # the coarse contact is soft (solimp 0.9): held at 0.99 of the threshold the block
    # tilts by 6.5e-3 α and comes back (the defaults: 2.9e-5 α; docs/mujoco.md)
    held = MUJOCO.simulate(system, _constant(0.99 * system.uplift_acceleration, 1.0), settings=s, duration=1.0)
    assert np.max(np.abs(held.theta)) < 1e-2 * system.alpha and held.impact_count == 0
    lifted = MUJOCO.simulate(system, _constant(1.05 * system.uplift_acceleration, 1.0), settings=s, duration=1.0)
    assert lifted.theta.min() < -0.1 * system.alpha


def test_event_resolved_settings_are_checked():
    with pytest.raises(InputError, match="impact_timestep"):
        scene.Settings(timestep=3e-3, impact_timestep=7e-4, solref=(-1e4, -200.0))
    with pytest.raises(InputError, match="solref"):
        scene.Settings(timestep=3e-3, impact_timestep=2.5e-4)  # the positive form


def test_free_joint_matches_closed_form_and_stays_in_plane():
    system = fixed()
    traj = free_rocking(system, scene.Settings(joint="free"), duration=2.4)
    errors = beta_errors(traj, 4)
    assert len(errors) == 4 and max(abs(e) for e in errors) < TOL["beta"], errors
    assert traj.extras["out_of_plane_max"] < tolerance("mujoco", "out_of_plane").limit


def test_time_to_first_impact():
    traj = free_rocking(fixed(), duration=0.7)
    exact = exact_first_impact_time(fixed(), 0.5 * fixed().alpha)  # model.md: 0.5014170 s
    assert traj.counted_impacts[0].t == pytest.approx(exact, rel=TOL["first_impact"])


# --- uplift threshold, overturning -----------------------------------------------------

def _constant(value, duration):
    return GroundMotion.from_array(np.full(2, value), dt=duration, name="constant")


@pytest.mark.parametrize("sign", [1, -1])
def test_stays_down_below_uplift_threshold(sign):
    system = fixed()
    traj = MUJOCO.simulate(system, _constant(sign * 0.99 * system.uplift_acceleration, 1.0), duration=1.0)
    assert np.max(np.abs(traj.theta)) < TOL["rest_tilt"] * system.alpha
    assert traj.impact_count == 0


def test_lifts_above_uplift_threshold():
    # the same test's other side, so the one above can fail; a > 0 lifts about O' (θ < 0)
    system = fixed()
    traj = MUJOCO.simulate(system, _constant(1.05 * system.uplift_acceleration, 1.0), duration=1.0)
    assert traj.theta.min() < -0.1 * system.alpha and traj.theta.max() <= 0.0


@pytest.mark.parametrize("amp, overturns", [(0.8, True), (0.44, False)])
def test_overturning_agrees_with_analytic(amp, overturns):
    # 1.5 Hz one-cycle sine on the fixed paper block: the analytic boundary is between
    # 0.55 g (θmax 0.66 α) and 0.6 g; 0.8 g and 0.44 g (θmax 0.17 α) are well away from it
    system = fixed()
    motion = load_motion(f"sine:amp={amp},freq=1.5,cycles=1")
    duration = motion.end_time + 2.0
    oracle = hybrid.simulate(system, motion, duration=duration)
    assert oracle.overturned is overturns
    traj = MUJOCO.simulate(system, motion, duration=duration)
    assert traj.overturned is overturns
    assert traj.status == ("overturned" if overturns else "completed")
    if overturns:  # past α the run goes on until the block falls (fixed base, motion over) or lies
        assert abs(traj.theta[-1]) > system.alpha and traj.t[-1] > motion.end_time


# --- determinism, finiteness, the stepping loop ------------------------------------------

#: Pulses that rock each base well short of overturning (analytic θmax 0.27 α and 0.16 α in 2 s).
PULSES = {"fixed": "ricker:amp=0.8,freq=1.5", "isolated": "ricker:amp=0.5,freq=1"}
PULSE = PULSES["isolated"]


def test_deterministic():
    system, motion = isolated(), load_motion(PULSE)
    a = MUJOCO.simulate(system, motion, duration=2.0)
    b = MUJOCO.simulate(system, motion, duration=2.0)
    for name in ("t", "u", "u_dot", "theta", "theta_dot"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert a.extras == b.extras


@pytest.mark.parametrize("joint", JOINTS)
@pytest.mark.parametrize("make", [fixed, isolated])
def test_finite(joint, make):
    motion = load_motion(PULSES[make.__name__])
    traj = MUJOCO.simulate(make(), motion, settings=scene.Settings(joint=joint), duration=2.0)
    assert traj.status == "completed" and traj.theta_max_over_alpha > 0.05  # it rocked
    for name in ("t", "u", "u_dot", "theta", "theta_dot"):
        assert np.all(np.isfinite(getattr(traj, name))), name
    assert traj.extras and all(np.isfinite(v) for v in traj.extras.values() if not isinstance(v, str))
    assert all(np.isfinite(v) for v in traj.summary().values() if isinstance(v, float))


def test_chunked_rollout_is_one_rollout():
    """The warm start is carried between rollout calls, so the chunk size is invisible."""
    system, motion = isolated(), load_motion(PULSE)
    s = scene.Settings()
    model = scene.build_model(system, s)
    a = scene.run_model(model, system, motion, settings=s, duration=1.5)
    b = scene.run_model(model, system, motion, settings=s, duration=1.5, chunk_steps=271)
    np.testing.assert_array_equal(a.theta, b.theta)
    np.testing.assert_array_equal(a.u, b.u)


def test_simulate_many_gives_each_run_as_alone(monkeypatch):
    """The batch path (a campaign's chunk: scenes shared, runs in threads) against runs
    made one at a time: identical histories, stop points, statuses, and each failure its
    own — a run that blows up (a warning through the process-wide handler, which makes
    the batch run again alone) and bad input (an exception as that run's result)."""
    monkeypatch.setattr(stepping, "CHUNK_STEPS", 701)  # several rollout calls per run, stops mid-run
    runs = [(fixed(), load_motion("sine:amp=0.5,freq=1,cycles=1"), 3.0, 0.0),      # falls after the motion
            (isolated(), load_motion("sine:amp=0.8,freq=1,cycles=2"), 3.0, 0.0),   # lies on its side
            (fixed(), load_motion(PULSE), 2.0, 0.0),                              # rocks and survives
            (fixed(), None, 1.5, 0.3 * fixed().alpha),                            # free rocking
            (stiff(), load_motion("sine:amp=0.5,freq=5,cycles=1"), 1.0, 0.0),     # MuJoCo warns: failed
            (fixed(), None, 1.0, 1.0)]                                            # θ0 > α: bad input
    for threads in (1, 2):
        batch = stepping.simulate_many(runs, settings=scene.Settings(), threads=threads)
        assert len(batch) == len(runs)
        for (system, motion, duration, theta0), got in zip(runs, batch):
            try:
                alone = stepping.simulate(system, motion, duration=duration, theta0=theta0)
            except InputError as e:
                assert isinstance(got, InputError) and str(got) == str(e)
                continue
            assert (got.status, got.message, got.stop_reason) == (alone.status, alone.message, alone.stop_reason)
            for name in ("t", "u", "u_dot", "theta", "theta_dot"):
                np.testing.assert_array_equal(getattr(got, name), getattr(alone, name), err_msg=name)
    assert [r.stop_reason for r in batch[:3]] == ["falling", "lying", None] and batch[4].status == "failed"


def test_rollout_matches_python_loop():
    """The C loop against a plain mj_step loop that sets qfrc_applied each step (the
    contact scene stepped throughout: phased stepping has its own tests)."""
    system, motion = isolated(), load_motion(PULSE)
    s = scene.Settings(phased=False).for_system(system)  # what simulate steps with, in full
    duration = 1.2
    traj = MUJOCO.simulate(system, motion, settings=s, duration=duration)
    model = scene.build_model(system, s)
    data = mujoco.MjData(model)
    dt = model.opt.timestep
    xg = motion((np.arange(traj.t.size) + 0.5) * dt)  # each step's middle
    theta = [0.0]
    u = [0.0]
    x_dof, base_dof = model.joint("block_x").dofadr[0], model.joint("base_slide").dofadr[0]
    for k in range(traj.t.size - 1):
        data.qfrc_applied[x_dof] = -system.mass * xg[k]
        data.qfrc_applied[base_dof] = -system.base_mass * xg[k]
        mujoco.mj_step(model, data)
        theta.append(data.qpos[model.joint("block_theta").qposadr[0]])
        u.append(data.qpos[model.joint("base_slide").qposadr[0]])
    np.testing.assert_allclose(traj.theta, theta, rtol=0, atol=1e-12)
    np.testing.assert_allclose(traj.u, u, rtol=0, atol=1e-12)


def test_progress_reports_simulated_time(monkeypatch):
    monkeypatch.setattr(stepping, "CHUNK_STEPS", 500)
    monkeypatch.setattr(kinematics, "PROGRESS_INTERVAL", 0.0)  # report after every chunk
    calls = []
    # the default's own 5e-4 s step (not the system's finer one), stepped throughout (no
    # coarse steps, whose calls end where impacts come): 500 steps are 0.25 s
    scene.simulate(isolated(), None, settings=scene.Settings(follow_system=False, phased=False), duration=1.0,
                   progress=lambda t, total: calls.append((t, total)))
    assert [round(t, 9) for t, _ in calls] == [0.25, 0.5, 0.75, 1.0]
    assert all(total == 1.0 for _, total in calls)
    # with coarse steps away from impacts, the reports still climb to the end
    calls.clear()
    scene.simulate(isolated(), None, settings=scene.Settings(follow_system=False), duration=1.0,
                   progress=lambda t, total: calls.append((t, total)))
    times = [t for t, _ in calls]
    assert len(times) >= 2 and times == sorted(times) and times[-1] == pytest.approx(1.0)


def test_scene_text_compiles_and_cli_writes_it(tmp_path):
    from isorock.validate.cli.main import main
    out = tmp_path / "scene.xml"
    assert main(["scene", "--engine", "mujoco", "--fixed-base", "--out", str(out)]) == 0
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.npair == 1 and model.njnt == 3
    assert SCENE_FORMAT == ("MJCF", ".xml")


def test_a_timestep_alone_takes_the_contact_parameters_measured_for_it():
    from isorock.validate.core.engines import get_engine
    engine = get_engine("mujoco")
    tied = engine.settings(timestep=2e-3)
    assert tied == scene.settings_for_timestep(2e-3)
    # solref given with it: the user's values stand
    assert engine.settings(timestep=2e-3, solref=(0.004, 1.0)).solref == (0.004, 1.0)
    assert engine.settings(friction=2.0).timestep == scene.Settings().timestep


def test_a_blown_up_state_is_a_failure_and_leaves_no_log_file(tmp_path, monkeypatch):
    """T 0.001 s is far too stiff for dt 5e-4: MuJoCo warns of a huge QACC. The run must
    say 'failed' (not 'completed' with a 600 m base displacement) and write nothing into
    the working directory (MuJoCo's MUJOCO_LOG.TXT)."""
    monkeypatch.chdir(tmp_path)
    stiff = System.isolated(height=H, width=B07, mass=M, base_mass=M, period=0.001, damping_ratio=0.2)
    traj = MUJOCO.simulate(stiff, load_motion("sine:amp=0.6,freq=1.3,cycles=2"),
                           settings=scene.Settings(follow_system=False), duration=2.0)  # dt 5e-4 as said
    assert traj.status == "failed" and "QACC" in traj.message
    assert list(tmp_path.iterdir()) == []


def test_a_squat_block_that_slides_says_so():
    # λ 0.89 with friction 1 < b/h: the block slides instead of rocking (model.md assumes it cannot)
    squat = System.fixed(height=0.5, width=0.56, mass=100.0)
    traj = MUJOCO.simulate(squat, load_motion("sine:amp=1.5,freq=1,cycles=2"), duration=3.0,
                           settings=MUJOCO.settings(friction=1.0))
    assert traj.status == "slid" and traj.extras["pivot_slip_max"] > 0.01 * squat.b
