"""Stepping the PyBullet scene from Python, one control step (Settings.control_step) at
a time, and the states as a RawHistory (measured outside the engine, by the registry).

- ground motion as horizontal gravity, `setGravity(−ẍg, 0, −g)`: exact for a translating
  ground (model.md), held over a control step and so taken at its middle, as MuJoCo
  takes its forces (at its start it would lag by half a step); a vertical üv makes its z
  −(g + üv), the base riding the ground vertically (it moves on its x joint alone);
- a second horizontal component ÿg (GroundMotion.transverse) is gravity's y, −ÿg, the same way;
  on the linear isolator the plate's y joint (scene.build(transverse=True)) takes the isolator
  force by the x joint's rule; a pair is stepped throughout (the rest phase is planar);
- the isolator force is held by Bullet over the sub-steps, so it is evaluated at the
  sub-steps' mean time: −(k(u + l u̇) + c(u̇ + l ü)), l = (n − 1)/(2n)·dt, with ü the base
  acceleration of the last step (kept from the step before when θ changed sign over it:
  an impact's jump of u̇ is no acceleration);
- a run stops by the shared rules of `isorock.analytic.kinematics.first_stop`;
- a duration that is no multiple of the step ends with one shorter step.
Measurements behind each choice and each skipped cost: docs/bullet.md.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from ..analytic import hull_contact, kinematics
from ..analytic.motion import GroundMotion
from ..analytic.engine_protocol import run_inputs
from ..analytic.isolator_parts import CONTACT_ISOLATORS, PLANE_ISOLATORS, check_contact_isolator, isolator_parts
from ..analytic.rest_phase import stepped_throughout
from ..analytic.status import Status
from ..analytic.system import LINEAR, System
from ..analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, RawHistory

from .scene import build, connect, p, run_client
from .rest import Rest
from .settings import Settings

ENGINE = "bullet"
#: Whether PyBullet carries a statue of two edges (its own shape, statue.py): what
#: Capabilities.two_edges says, judged in docs/statues.md ("PyBullet on the statue's hull")
TWO_EDGES = True
#: Whether PyBullet carries two horizontal components (GroundMotion.transverse) on a fixed base
#: and the linear isolator: what Capabilities.transverse says, judged in docs/statues.md ("Two
#: horizontal components", PyBullet) by tests/test_two_components_bullet.py
TRANSVERSE = True
#: |θ| below this fraction of α counts as "down": no sign change of θ there is an impact
#: to keep out of the base-acceleration estimate.
REST_FRACTION = 1e-3


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """Simulate from rest at tilt `theta0` (rad; > 0 rests on corner O, centroid towards
    +x) for `duration` s (default: motion end + 5 s, or 10 s without motion).
    progress: callable(t, duration), called about once a second."""
    settings = (settings or Settings()).for_system(system)
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD, settings=settings,
                                  isolators=CONTACT_ISOLATORS, kinetic_friction=False, two_edges=TWO_EDGES,
                                  transverse=TRANSVERSE, transverse_isolators=PLANE_ISOLATORS)
    transverse = motion.transverse is not None
    if transverse:
        # stepped throughout, as MuJoCo's pair is: the rest phase carries the body on the base
        # along x alone (rest.py), so it would lose ÿg
        settings = replace(settings, phased=False)
    hull_contact.check_shape(system, "PyBullet")
    check_contact_isolator(system, ENGINE)
    settings.check_isolator(system)
    linear = system.isolator_kind == LINEAR  # a fixed base too

    dt = settings.control_step
    n_steps = int(math.floor(duration / dt + 1e-9))
    times = (np.arange(n_steps + 1) * dt).tolist()
    mids = (np.arange(n_steps) + 0.5) * dt
    last = duration - n_steps * dt  # a shorter last step, so the run ends at `duration`
    if last > 1e-6 * dt:
        times.append(duration)
        mids = np.append(mids, n_steps * dt + 0.5 * last)
        n_steps += 1
    else:
        last = 0.0
    xg = np.asarray(motion(mids), dtype=float).tolist()
    g = system.gravity
    # gravity's z at each control step's middle: −(g + üv) with a vertical motion, else −g throughout
    gz = [-g] * len(xg) if motion.vertical is None else (-(g + np.asarray(motion.vertical(mids)))).tolist()
    # the second horizontal component ÿg as gravity's y, as ẍg is its x (every body, the plate
    # too, feels −m·ÿg); 0.0 throughout without one, as before
    gy = (-np.asarray(motion.transverse_at(mids), dtype=float)).tolist() if transverse else [0.0] * len(xg)
    k, c_dash = system.stiffness, system.damping
    element = None if linear else Element(isolator_parts(system))
    if element is not None:
        k, c_dash = element.parts.stiffness, element.parts.damping  # the springs in parallel with it
    n = settings.substeps
    lead = (n - 1) / (2 * n) * dt  # the held isolator force acts at the sub-steps' mean time
    rocking = REST_FRACTION * system.alpha
    every = settings.output_every
    fixed = system.fixed_base
    # two components: the 'falling' rule reads θ, the tilt's projection on xz, and a statue leaning
    # on a diagonal past the x edge's α may still stand; it is planar, so it never stops a 3-D run
    # ('lying' holds), as in MuJoCo's (mujoco_models/state.stop_in)
    motion_end = math.inf if transverse else motion.end_time
    throttle = kinematics.Throttle(progress, duration)
    check_every = max(1, round(0.25 / dt))  # the stop rules look at the rows every 0.25 s

    with run_client() as client:
        scene = build(client, system, settings, theta0, transverse=transverse)
        c, block, base = client, scene.block, scene.base
        set_gravity, step = c.setGravity, c.stepSimulation
        joint_state, motor = c.getJointState, c.setJointMotorControl2
        pose, velocity = (lambda _body: scene.pose()), c.getBaseVelocity  # the statue's own frame
        torque = p.TORQUE_CONTROL
        rows = []  # (t, u, u̇, x, y, z, qx, qy, qz, qw, ω_y, ẋ), and u_y, u̇_y with two components
        slider = []  # a bearing's slider position u_p at each row
        status, message, stop_reason = Status.COMPLETED, "reached the end time", None
        u = ud = 0.0
        ud_prev = udd = 0.0  # base velocity one step back; base acceleration estimate
        side_prev = 0.0  # sin θ (≈ R₀₂) one step back
        uy = udy = udy_prev = uddy = side_y_prev = 0.0  # the same along y (two components)
        a_set, gy_set, gz_set = 0.0, 0.0, -g  # build() set gravity (0, 0, −g)
        checked = 0  # rows already looked at by the stop rules
        why = stepped_throughout(system, motion)
        rest = None if why is not None else _rest(system, settings, theta0, xg, dt, lead)
        puck = scene.puck_link  # a pendulum's friction under a pair: its puck's contact, not the joints' motors
        if element is not None and puck is None:
            element.start(c, base, settings.substeps)
        rest_end = n_steps - (1 if last else 0)  # the shorter last step is stepped by Bullet
        resumed = False  # the state of step i came from a rest phase (already in rows)
        start = time.perf_counter()
        i = 0
        while i <= n_steps:
            if not fixed and not resumed:
                # one read serves both the isolator force and the output
                u, ud = joint_state(base, 0)[:2]
                if transverse:
                    uy, udy = joint_state(base, 1)[:2]
            if (i % every == 0 or i == n_steps) and not resumed:
                pos, orn = pose(block)
                (vx, _, _), (_, wy, _) = velocity(block)
                rows.append((times[i], u, ud, *pos, *orn, wy, vx, uy, udy) if transverse else
                            (times[i], u, ud, *pos, *orn, wy, vx))
                if element is not None:
                    slider.append(element.u_p)
            resumed = False
            if i % check_every == 0 or i == n_steps:  # the stop rules, over the rows since the last look
                stop, reason = _stop_in(system, rows, checked, motion_end)
                if reason == "non-finite":
                    status, message = Status.FAILED, f"non-finite state at t = {rows[stop][0]:.6g} s"
                    del rows[stop:]  # the history ends at the last finite state
                    break
                if reason is not None:
                    del rows[stop + 1:]
                    stop_reason = reason
                    break
                checked = len(rows)
                if i:
                    throttle(times[i])
            if i == n_steps:
                break
            if rest is not None and i < rest_end and i % rest.check_every == 0 and rest.may_rest(rows, i):
                skipped, states = rest.phase(i, rest_end, u, ud, ud_prev)
                if skipped:
                    pos, orn = pose(block)
                    offset = pos[0] - u
                    for j in range(skipped):
                        k_row = i + 1 + j
                        if k_row % every == 0 or k_row == n_steps:
                            su, sud = states[j, 0], states[j, 1]
                            rows.append((times[k_row], su, sud, su + offset, pos[1], pos[2], *orn, 0.0, sud))
                    i += skipped
                    if not fixed:
                        u, ud, ud_prev = (float(x) for x in states[-1])
                        udd = (ud - ud_prev) / dt
                        c.resetJointState(base, 0, u, ud)
                    # Bullet's bodies where the rest phase left them: the block on the base, moving with it
                    scene.reset_pose([u + offset, pos[1], pos[2]], orn)
                    c.resetBaseVelocity(block, [ud, 0.0, 0.0], [0.0, 0.0, 0.0])
                    resumed = True
                    continue
            if last and i == n_steps - 1:  # the shorter last step, sub-steps no longer than before
                m = math.ceil(last / settings.timestep - 1e-9)
                c.setPhysicsEngineParameter(fixedTimeStep=last, numSubSteps=m)
                lead = (m - 1) / (2 * m) * last
                if element is not None and puck is None:
                    element.start(c, base, m)  # the friction's impulse per sub-step follows the step
            a, ay, az = xg[i], gy[i], gz[i]
            if a != a_set or ay != gy_set or az != gz_set:  # gravity persists in Bullet: set it only when it changes
                set_gravity(-a, ay, az)
                a_set, gy_set, gz_set = a, ay, az
            if not fixed:
                # ü from the last step, except over an impact (θ changed sign while rocking):
                # the jump of u̇ there is no acceleration to extrapolate, the last one is kept
                qx, qy, qz, qw = orn if i % every == 0 else pose(block)[1]
                side = 2 * (qx * qz + qw * qy)
                if i and ((side > 0) == (side_prev > 0) or max(abs(side), abs(side_prev)) < rocking):
                    udd = (ud - ud_prev) / dt
                ud_prev, side_prev = ud, side
                q = 0.0 if element is None else element.force(u + lead * ud)
                motor(base, 0, torque, force=-(k * (u + lead * ud) + c_dash * (ud + lead * udd) + q))
                if transverse:
                    # the isotropic isolator along y, by the same rule: ü_y from the last step except
                    # over an impact across y (the lean of the body's z axis towards y changed sign)
                    side_y = 2 * (qy * qz - qw * qx)
                    if i and ((side_y > 0) == (side_y_prev > 0) or max(abs(side_y), abs(side_y_prev)) < rocking):
                        uddy = (udy - udy_prev) / dt
                    udy_prev, side_y_prev = udy, side_y
                    motor(base, 1, torque, force=-(k * (uy + lead * udy) + c_dash * (udy + lead * uddy)))
                if puck is not None:  # held down, so that the floor pushes it up by W
                    motor(base, puck, torque, force=scene.puck_hold)
            step()
            i += 1
        runtime = time.perf_counter() - start
    raw = raw_history(system, motion, np.array(rows), runtime, status, message, stop_reason)
    # the numbers this run used (Settings.for_system may have made them finer than asked)
    raw.extras.update(timestep=float(settings.timestep), control_step=float(settings.control_step))
    if why is not None:
        raw.extras.update(stepping=f"throughout (no rest phase: {why})")
    if not linear:
        if element.parts.has_element:
            raw.extras.update(isolator_slider=np.array(slider[:len(rows)], dtype=float))
    return raw


class Element:
    """A non-linear isolator's parts besides its spring and dashpot (analytic/isolator_parts.py)
    in Bullet. A pendulum's rigid slider (the friction pendulum's, the ball in a bowl's, the
    double pendulum's μ_lo·W) is the base joint's own dry friction: Bullet's standard joint
    friction, a velocity motor with target 0 whose force is limited to F_b, solved with the
    contacts at every sub-step (it holds the base still exactly, or slides at F_b). A Jenkins
    element (the bilinear bearing's, the double pendulum's of μ1 ≠ μ2) is a state update at each
    control step, its return map: q = k_e (u − u_p), and where |q| > F_s the slider moves to
    u − sgn(q)·u_y and q = sgn(q)·F_s; the force is held over the control step like the
    spring's. The double pendulum has both."""

    def __init__(self, parts):
        self.parts = parts
        self.u_p = 0.0  # the element's slider, from its virgin state (docs/isolators.md)

    def start(self, client, base, substeps):
        """Switch the base's dry friction on (again after the sub-steps change).
        PyBullet turns a motor force into the impulse force × fixedTimeStep, the whole
        control step, but applies it at every one of its `substeps` sub-steps: the force
        is given divided by them, so that each sub-step's impulse is F_b × its own length."""
        if self.parts.base_friction > 0.0:
            client.setJointMotorControl2(base, 0, p.VELOCITY_CONTROL, targetVelocity=0.0,
                                         force=self.parts.base_friction / substeps)

    def force(self, u: float) -> float:
        """q (N) on the base at displacement u (m): the Jenkins element's; 0 without one (the
        base's friction is the motor's)."""
        if not self.parts.has_element:
            return 0.0
        k_e, f_s = self.parts.element_stiffness, self.parts.slip_force
        q = k_e * (u - self.u_p)
        if abs(q) > f_s:
            side = 1.0 if q > 0 else -1.0
            self.u_p = u - side * self.parts.yield_displacement
            q = side * f_s
        return q


def _rest(system, settings, theta0, xg, dt, lead):
    """The rest phases' rules for this run (rest.Rest), or None: asked for, starting at
    rest (free rocking starts tilted and is stepped throughout), a record that moves, and
    every control step stored (the rest test reads consecutive rows)."""
    xg = np.asarray(xg, dtype=float)
    if not (settings.phased and theta0 == 0.0 and settings.output_every == 1 and xg.size and np.any(xg != 0.0)):
        return None
    return Rest(system, dt, settings.substeps, lead, xg)


def _stop_in(system, rows, checked, motion_end):
    """kinematics.first_stop over rows[checked:]: (index into rows, reason) or (None, None)."""
    new = np.array(rows[checked:], dtype=float)
    if not new.size:
        return None, None
    qx, qy, qz, qw = new[:, 6:10].T
    theta = kinematics.tilts_from_quaternion(qw, qx, qy, qz)[0]
    finite = np.all(np.isfinite(new), axis=1)
    k, reason = kinematics.first_stop(new[:, 0], theta, new[:, 10], finite, system=system, motion_end=motion_end)
    return (None, None) if k is None else (checked + k, reason)


def step_cost(system: System, settings: Settings | None = None, *, steps: int = 24_000) -> float:
    """CPU seconds per physics step of the scene itself, the block resting on its base,
    Bullet stepping its sub-steps in C (one stepSimulation per control step, as
    `simulate` calls it, without the isolator force and the rows): the limit of any
    stepping of this scene, timestep / step_cost simulated s per CPU s."""
    settings = (settings or Settings()).for_system(system)
    client = connect()
    try:
        build(client, system, settings, 0.0)
        calls = max(1, steps // settings.substeps)
        for _ in range(10):
            client.stepSimulation()
        start = time.process_time()
        for _ in range(calls):
            client.stepSimulation()
        return (time.process_time() - start) / (calls * settings.substeps)
    finally:
        client.disconnect()


def raw_history(system, motion, rows, runtime, status, message, stop_reason) -> RawHistory:
    t, u, ud, x, y, z, qx, qy, qz, qw, wy, xd = rows.T[:12]
    theta, roll, yaw = kinematics.tilts_from_quaternion(qw, qx, qy, qz)
    extras = kinematics.contact_extras(
        system, x_centroid=x, z_centroid=z, theta=theta, u=u,
        out_of_plane=np.maximum.reduce([np.abs(y), np.abs(roll), np.abs(yaw)]))
    slide, slide_dot = kinematics.slide_history(system, motion, x_centroid=x, x_centroid_dot=xd, theta=theta,
                                                theta_dot=wy, u=u, u_dot=ud)
    if motion.transverse is not None:  # the 3-D history the two-component measures read (validate.core.biaxial)
        kinematics.pair_extras(extras, orientation=np.stack([qw, qx, qy, qz], axis=1), y_centroid=y, u_y=rows[:, 12])
    return RawHistory(engine=ENGINE, system=system, t=t, u=u, u_dot=ud, theta=theta, theta_dot=wy,
                      status=status, message=message, runtime_s=runtime, extras=extras, stop_reason=stop_reason,
                      slide=slide, slide_dot=slide_dot)
