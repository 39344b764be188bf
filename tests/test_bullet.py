"""The PyBullet scene: structure, closed-form β, the uplift threshold, determinism,
finiteness, overturning against the analytic model, and the client's lifetime.

Tolerances (at the default Settings: physics step 1/3000 s, 12 per 4 ms control step)
come from the one table, validate/core/tolerances.py, each with its reason and measured value
there: β per impact, staying down at 0.99·g·tanα, pivot slip, out-of-plane drift.
"""
import math
from dataclasses import replace

import threading

import numpy as np
import pybullet as p
import pytest

from isorock.analytic.coefficients import beta
from isorock.analytic.errors import InputError
from isorock.analytic.hybrid import simulate as analytic_simulate
from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.system import System
from isorock.bullet_models import scene, stepping
from isorock.bullet_models.scene import SCENE_FORMAT, build, connect
from isorock.bullet_models.settings import Settings, settings_for_timestep
from isorock.analytic import kinematics
from isorock.validate.core.engines import get_engine
from isorock.validate.core.tolerances import tolerance

#: This engine at its default settings, measured: simulate returns the shared Trajectory.
simulate = get_engine("bullet").simulate
BETA_RTOL = tolerance("bullet", "beta_rel_error_per_impact").limit
STAY_DOWN = tolerance("bullet", "rest_tilt").limit  # × α
PIVOT_SLIP = tolerance("bullet", "pivot_slip").limit  # m
OUT_OF_PLANE = tolerance("bullet", "out_of_plane").limit

FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)
ISOLATED = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.0)
CASES = {
    "fixed-2.857": FIXED,
    "fixed-5": System.fixed(height=2.0, width=0.4, mass=3800.0),
    "mu1-2.857": ISOLATED,
    "mu1-5": System.isolated(height=2.0, width=0.4, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.0),
    "mu1-2.857-xi0.2": System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5,
                                       damping_ratio=0.2),
}


def _scene(system):
    client = connect()
    return client, build(client, system, Settings(), 0.3 * system.alpha)


def _shapes(client):
    """(body, link) of every collision shape in the world."""
    out = []
    for i in range(client.getNumBodies()):
        body = client.getBodyUniqueId(i)
        for link in range(-1, client.getNumJoints(body)):
            try:
                has_shape = bool(client.getCollisionShapeData(body, link))
            except p.error:  # PyBullet gives no shape data for a maximal-coordinates body (the block)
                low, high = client.getAABB(body, link)
                has_shape = all(h > lo for lo, h in zip(low, high))
            if has_shape:
                out.append((body, link))
    return out


def _block_size(system):
    """Extents of the block's collision box, from its AABB when built upright (the contact
    processing threshold 0 adds no margin)."""
    client = connect()
    try:
        s = build(client, system, Settings(), 0.0)
        low, high = client.getAABB(s.block, -1)
        return [h - lo for lo, h in zip(low, high)]
    finally:
        client.disconnect()


# --- structure ------------------------------------------------------------------

def test_isolated_scene_is_a_free_block_on_a_prismatic_base():
    client, s = _scene(ISOLATED)
    try:
        assert client.getNumBodies() == 2
        assert client.getNumJoints(s.block) == 0
        assert client.getNumJoints(s.base) == 1
        info = client.getJointInfo(s.base, 0)
        assert info[2] == p.JOINT_PRISMATIC
        assert info[13] == (1.0, 0.0, 0.0)  # along x
        assert client.getDynamicsInfo(s.base, 0)[0] == pytest.approx(ISOLATED.base_mass)
        assert client.getDynamicsInfo(s.block, -1)[0] == pytest.approx(ISOLATED.mass)
        # the block's inertia about y is the model's m(b² + h²)/3
        assert client.getDynamicsInfo(s.block, -1)[2][1] == pytest.approx(ISOLATED.inertia, rel=1e-6)
        # two collision shapes in the world (plate, block): the only possible pair
        assert sorted(_shapes(client)) == sorted([(s.base, 0), (s.block, -1)])
        assert _block_size(ISOLATED) == pytest.approx([ISOLATED.width, ISOLATED.width, ISOLATED.height])
        # the joint's velocity motor is off: a base launched at 0.1 m/s keeps 0.090 m/s
        # after 10 ms (friction drags the block along); a 10 kN motor leaves 0.050
        client.resetJointState(s.base, 0, 0.0, 0.1)
        for _ in range(10):
            client.stepSimulation()
        assert client.getJointState(s.base, 0)[1] > 0.08
        pairs = {(c[1], c[2], c[3], c[4]) for c in client.getContactPoints()}
        assert pairs and pairs <= {(s.block, s.base, -1, 0), (s.base, s.block, 0, -1)}
    finally:
        client.disconnect()


def test_fixed_scene_has_a_static_base_and_no_joint():
    client, s = _scene(FIXED)
    try:
        assert client.getNumBodies() == 2
        assert client.getNumJoints(s.base) == 0 and client.getNumJoints(s.block) == 0
        assert client.getDynamicsInfo(s.base, -1)[0] == 0.0  # static
        assert sorted(_shapes(client)) == sorted([(s.base, -1), (s.block, -1)])
    finally:
        client.disconnect()


@pytest.mark.parametrize("system", [ISOLATED, FIXED], ids=["isolated", "fixed"])
def test_scene_text_loads_as_the_same_bodies(system, tmp_path):
    path = tmp_path / f"scene{SCENE_FORMAT[1]}"
    path.write_text(scene.scene_text(system, Settings()))
    built, s = _scene(system)
    loaded = connect()
    try:
        base, block = loaded.loadSDF(str(path))
        assert loaded.getNumBodies() == 2
        assert loaded.getNumJoints(base) == built.getNumJoints(s.base)
        if not system.fixed_base:
            assert loaded.getJointInfo(base, 0)[2] == p.JOINT_PRISMATIC
            assert loaded.getJointInfo(base, 0)[13] == (1.0, 0.0, 0.0)
        for (lb, ll), (bb, bl) in (((block, -1), (s.block, -1)), ((base, -1 if system.fixed_base else 0),
                                                                   (s.base, s.plate_link))):
            mass, _, inertia = loaded.getDynamicsInfo(lb, ll)[:3]
            assert mass == pytest.approx(built.getDynamicsInfo(bb, bl)[0])
            assert inertia == pytest.approx(built.getDynamicsInfo(bb, bl)[2])
            size = loaded.getCollisionShapeData(lb, ll)[0][3]
            # the built block is a maximal-coordinates body: PyBullet has no shape data for it
            expected = _block_size(system) if bb == s.block else built.getCollisionShapeData(bb, bl)[0][3]
            assert size == pytest.approx(expected)
    finally:
        loaded.disconnect()
        built.disconnect()


@pytest.mark.parametrize("field, value", [
    ("timestep", 0.0), ("timestep", 0.1), ("substeps", 0), ("substeps", 1.5), ("solver_iterations", 0),
    ("friction", 0.0), ("restitution", 2.0), ("contact_erp", 0.0), ("linear_damping", -1.0),
    ("output_every", 0),
])
def test_settings_reject_bad_values_naming_field_and_value(field, value):
    with pytest.raises(InputError, match=f"{field} = {value!r}"):
        Settings(**{field: value})


@pytest.mark.parametrize("dt, control_step, substeps", [(1 / 500, 4e-3, 2), (1 / 1000, 4e-3, 4),
                                                         (1 / 3000, 4e-3, 12), (1 / 10000, 4e-3, 40),
                                                         (1 / 150, 1 / 150, 1)])
def test_a_timestep_is_the_physics_step_and_the_control_step_stays_near_4ms(dt, control_step, substeps):
    for s in (settings_for_timestep(dt), get_engine("bullet").settings(timestep=dt)):
        assert s.timestep == pytest.approx(dt) and s.substeps == substeps
        assert s.control_step == pytest.approx(control_step)
    if dt == 1 / 3000:  # the defaults are one rung (a rung is its named step: it does not follow the system)
        assert settings_for_timestep(dt) == replace(Settings(), follow_system=False)
    # given with its sub-steps, a timestep stands as it is
    assert get_engine("bullet").settings(timestep=dt, substeps=1).control_step == pytest.approx(dt)


def test_a_duration_off_the_step_grid_ends_on_time():
    # 0.0503 s is 12 steps of 4 ms and a last one of 2.3 ms (7 sub-steps of 1/3000 s or less)
    traj = simulate(ISOLATED, duration=0.0503, theta0=0.5 * ISOLATED.alpha)
    assert traj.t[-1] == pytest.approx(0.0503) and np.all(np.diff(traj.t) > 0)
    longer = simulate(ISOLATED, duration=0.06, theta0=0.5 * ISOLATED.alpha)
    assert traj.theta[-1] == pytest.approx(np.interp(0.0503, longer.t, longer.theta), rel=1e-3)


# --- physics against closed forms and the analytic model -----------------------------

@pytest.mark.parametrize("name", list(CASES))
def test_free_rocking_beta_per_impact(name):
    system = CASES[name]
    traj = simulate(system, duration=3.0, theta0=0.5 * system.alpha)
    ref = beta(system.slenderness, system.mu)
    impacts = traj.counted_impacts[:4]
    assert len(impacts) == 4, f"{len(traj.counted_impacts)} counted impacts"
    errors = [i.beta / ref - 1 for i in impacts]
    assert max(abs(e) for e in errors) < BETA_RTOL, f"β errors {errors}"
    assert traj.extras["pivot_slip_max"] < PIVOT_SLIP
    assert traj.extras["out_of_plane_max"] < OUT_OF_PLANE
    assert traj.extras["lift_off_max_after_impact"] < tolerance("bullet", "lift_off_after_impact").limit


def test_tilt_sign_matches_the_analytic_convention():
    # θ0 > 0 rests on corner O (+x): the block falls back with θ decreasing through 0
    traj = simulate(FIXED, duration=0.3, theta0=0.5 * FIXED.alpha)
    assert traj.theta[0] == pytest.approx(0.5 * FIXED.alpha, rel=1e-9)
    assert np.all(np.diff(traj.theta) <= 1e-12) and traj.theta_dot[-1] < 0


@pytest.mark.parametrize("fraction, lifts", [(0.99, False), (-0.99, False), (1.01, True)])
def test_uplift_threshold_on_a_fixed_base(fraction, lifts):
    # a constant ground acceleration a: the block lifts (θ < 0 for a > 0) only when |a| > g·tanα
    a = fraction * FIXED.uplift_acceleration
    motion = GroundMotion.from_array(np.full(3, a), dt=1.0)
    traj = simulate(FIXED, motion, duration=2.0)
    peak = np.max(np.abs(traj.theta)) / FIXED.alpha
    if lifts:
        assert peak > 0.1 and np.sign(traj.theta[np.argmax(np.abs(traj.theta))]) == -np.sign(a)
    else:
        assert peak < STAY_DOWN, f"max |θ| = {peak:.3g}·α"


def test_a_ground_motion_that_starts_late_still_moves_the_block():
    # Bullet puts resting bodies to sleep and a change of gravity does not wake them
    acc = np.zeros(351)
    acc[250:] = -0.5 * 9.81  # 0.5 g from t = 2.5 s, above g·tanα = 0.35 g
    traj = simulate(FIXED, GroundMotion.from_array(acc, dt=0.01), duration=3.5)
    assert traj.theta_max_over_alpha > 0.1


@pytest.mark.parametrize("amp, freq", [(0.8, 1.0), (0.8, 2.0)])
def test_overturning_agrees_with_the_analytic_model(amp, freq):
    motion = GroundMotion.from_pulse(Pulse("sine", amp, freq))
    duration = motion.end_time + 2.0
    oracle = analytic_simulate(FIXED, motion, duration=duration)
    # the cases sit far from the boundary: overturned, or a peak well below α
    assert oracle.overturned or oracle.theta_max_over_alpha < 0.7
    traj = simulate(FIXED, motion, duration=duration)
    assert traj.overturned == oracle.overturned
    assert traj.status == ("overturned" if oracle.overturned else "completed")


def test_isolated_pulse_is_deterministic_and_finite():
    system = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
    motion = GroundMotion.from_pulse(Pulse("sine", 0.6, 1.5))
    a = simulate(system, motion, duration=2.0)
    b = simulate(system, motion, duration=2.0)
    for key in ("t", "u", "u_dot", "theta", "theta_dot"):
        x, y = getattr(a, key), getattr(b, key)
        assert np.all(np.isfinite(x)), key
        assert np.array_equal(x, y), key
    assert a.extras == b.extras
    assert a.uplifts > 0 and np.max(np.abs(a.u)) > 0.01  # the pulse did rock it and move the base
    assert a.t[-1] == pytest.approx(2.0)


def test_runs_share_no_state():
    # a run with other contact settings in between leaves a run unchanged (no Bullet globals set)
    other = Settings(contact_processing_threshold=0.02, contact_erp=0.5, timestep=4e-3, substeps=1)
    first = simulate(ISOLATED, duration=1.5, theta0=0.5 * ISOLATED.alpha)
    simulate(ISOLATED, settings=other, duration=1.5, theta0=0.5 * ISOLATED.alpha)
    again = simulate(ISOLATED, duration=1.5, theta0=0.5 * ISOLATED.alpha)
    assert np.array_equal(first.theta, again.theta) and np.array_equal(first.u, again.u)


def test_default_duration_follows_the_analytic_engine():
    motion = GroundMotion.from_pulse(Pulse("sine", 0.1, 4.0))  # below uplift, ends at 0.25 s
    traj = simulate(FIXED, motion, settings=Settings(output_every=50))
    assert traj.t[-1] == pytest.approx(motion.end_time + 5.0)


def test_bad_arguments_raise_input_error():
    with pytest.raises(InputError, match="theta0"):
        simulate(FIXED, theta0=FIXED.alpha)
    with pytest.raises(InputError, match="duration"):
        simulate(FIXED, duration=-1.0)


# --- the client's lifetime ---------------------------------------------------------

def test_a_thread_keeps_its_client_and_a_failure_disconnects_it(monkeypatch):
    """A thread's runs share one client, emptied before each (two runs of one case give the
    same history bit for bit, and a run after another case equals it too); a run that
    raises disconnects its client, and the next run connects a new one."""
    from isorock.bullet_models import scene as bullet_scene
    ids = []

    def tracking_connect(fail_at=None):
        client = connect()
        ids.append(client._client)
        if fail_at is not None:
            step, calls = client.stepSimulation, [0]

            def failing_step():
                calls[0] += 1
                if calls[0] == fail_at:
                    raise RuntimeError("stepping failed")
                step()
            client.stepSimulation = failing_step
        return client

    monkeypatch.setattr(bullet_scene, "_local", threading.local())  # this test's own thread state
    monkeypatch.setattr(bullet_scene, "connect", tracking_connect)
    first = simulate(FIXED, duration=0.3, theta0=0.5 * FIXED.alpha)
    simulate(ISOLATED, duration=0.3, theta0=0.5 * ISOLATED.alpha)
    again = simulate(FIXED, duration=0.3, theta0=0.5 * FIXED.alpha)
    assert len(ids) == 1 and p.isConnected(physicsClientId=ids[0])
    assert np.array_equal(first.theta, again.theta) and np.array_equal(first.t, again.t)
    bullet_scene._local.client = None
    monkeypatch.setattr(bullet_scene, "connect", lambda: tracking_connect(fail_at=10))
    with pytest.raises(RuntimeError, match="stepping failed"):
        simulate(FIXED, duration=0.1)
    assert len(ids) == 2 and not p.isConnected(physicsClientId=ids[1])
    monkeypatch.setattr(bullet_scene, "connect", tracking_connect)
    simulate(FIXED, duration=0.05)
    assert len(ids) == 3 and p.isConnected(physicsClientId=ids[2])


def test_progress_is_called_with_the_duration(monkeypatch):
    seen = []
    ticks = iter(np.arange(0.0, 1000.0, 0.6))  # a clock that moves 0.6 s per reading
    monkeypatch.setattr(kinematics.time, "perf_counter", lambda: next(ticks))
    simulate(FIXED, duration=3.0, progress=lambda t, total: seen.append((t, total)))
    assert seen and all(total == 3.0 and 0 < t <= 3.0 for t, total in seen)


def test_an_isolator_too_stiff_for_the_control_step_is_refused():
    stiff = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=0.01, damping_ratio=0.2)
    with pytest.raises(InputError, match=r"period = 0\.01: must be at least 0\.126 s"):  # ω·dt ≤ 0.2 at 4 ms
        simulate(stiff, GroundMotion.from_pulse(Pulse("sine", 0.6, 1.3)), settings=Settings(follow_system=False),
                 duration=1.0)
    # the default follows the block: its control step, 12 physics steps of 0.0003/p_eff, names its own bound
    control = 12 * 0.0003 / stiff.rocking_rate
    with pytest.raises(InputError, match=rf"period = 0\.01: must be at least {2 * math.pi * control / 0.2:.3g} s"):
        simulate(stiff, GroundMotion.from_pulse(Pulse("sine", 0.6, 1.3)), duration=1.0)
    # a shorter control step carries it
    fine = Settings(timestep=1e-4, substeps=1)
    fine.check_isolator(System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=0.01,
                                        damping_ratio=0.2))


def test_a_squat_block_that_slides_says_so():
    squat = System.fixed(height=0.5, width=0.56, mass=100.0)
    traj = simulate(squat, GroundMotion.from_pulse(Pulse("sine", 1.5, 1.0, 2)), duration=3.0)
    assert traj.status == "slid" and traj.extras["pivot_slip_max"] > 0.01 * squat.b


def test_scene_file_carries_friction_and_the_isolator(tmp_path):
    """The SDF holds the friction (SDF's surface/ode mu) and the isolator: c as the joint's
    damping, which loadSDF applies, and k as spring_stiffness, which it does not (the
    header says so and names both values)."""
    import xml.etree.ElementTree as ET
    system = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
    settings = Settings(friction=0.8)
    text = scene.scene_text(system, settings)
    root = ET.fromstring(text.encode())
    mus = [float(e.text) for e in root.iter("mu")]
    assert mus == [0.8, 0.8]  # plate and block
    dyn = root.find(".//joint/axis/dynamics")
    assert float(dyn.find("damping").text) == pytest.approx(system.damping)
    assert float(dyn.find("spring_stiffness").text) == pytest.approx(system.stiffness)
    header = text.split("-->")[0]
    assert f"k = {system.stiffness}" in header and f"c = {system.damping}" in header
    assert "ignores" in header and "lateralFriction=0.8" in header
    path = tmp_path / "scene.sdf"
    path.write_text(text)
    loaded = connect()
    try:
        base, _ = loaded.loadSDF(str(path))
        assert loaded.getJointInfo(base, 0)[6] == pytest.approx(system.damping)  # jointDamping as loaded
    finally:
        loaded.disconnect()
    fixed = scene.scene_text(FIXED, settings)
    assert "<joint" not in fixed and "Isolator: none" in fixed
