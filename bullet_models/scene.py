"""The block on its base in PyBullet, behind the engine protocol of `validate.engines`.

Scene (built with `createMultiBody`, one private `p.DIRECT` client per run):

- block: a free box 2b × 2b × 2h (x, y, z) of mass m, a plain rigid body (maximal
  coordinates); Bullet's box inertia about y is m(b² + h²)/3, the model's I;
- isolated base: a plate on a prismatic joint along x under a massless, shapeless
  anchor; its default velocity motor is switched off (force 0) and the isolator force
  −(k u + c u̇) is applied as a joint force every step (Bullet clears it after each
  `stepSimulation`);
- fixed base: the same plate as a static body (mass 0), no joint;
- no ground plane: the base moves on its joint, so the only collision pair in the
  world is block–plate and no collision filtering is needed;
- ground motion as horizontal gravity, `setGravity(−ẍg, 0, −g)`: exact for a
  translating ground (model.md).

Conventions: θ is the block's rotation about the world y axis, θ > 0 when the centroid
moves to +x (rocking about corner O, the +x corner); Bullet's angular velocity is in
the world frame, so θ̇ = ω_y. Quaternions are (x, y, z, w). u is the joint position.
Out-of-plane drift (block y, rotations about x and z) and the pivot's slip relative to
the plate are recorded as extras.

Measured choices (free rocking from θ0 = α/2, λ 2.857 and 5, fixed base and μ = 1 with
T 1.5 s, ξ 0 and 0.2; effective β per impact against the closed form; Kobe JMA 40 s and
a sine pulse against the analytic model; tables, commands and speeds in docs/bullet.md):

- timestep (the Python step: ground motion, isolator force, output) 4 ms with 12 Bullet
  sub-steps of 1/3 ms: β within 0.38% on the first four impacts of all six cases, 1.45–1.55×
  the speed of the former 1 ms / 3 (CPU time). Sub-steps run in C and cost ~3–6 µs each;
  a Python step costs ~4–8 µs more, so longer Python steps pay while the sub-step sets the
  accuracy (1 ms sub-steps: β up to 0.97%; 1/3 ms: 0.38%; 0.2 ms: 0.14%).
- the block is a plain rigid body (useMaximalCoordinates), not a one-link multibody:
  the same β, 1.15–1.27× faster.
- the isolator force is held by Bullet over the sub-steps, so it is evaluated at the
  sub-steps' mean time: −(k(u + l u̇) + c(u̇ + l ü)), l = (n − 1)/(2n)·dt, with ü the base
  acceleration of the last step (kept from the step before when θ changed sign over it:
  an impact's jump of u̇ is no acceleration). Without the ü term the damper lags: the
  isolated Kobe run peaked 0.016α high at 1 ms / 3 and parted from the analytic history
  after 8 s with 4–10 ms steps. The ground motion held over a 4 ms step costs little
  (held over 10 ms: +0.002 in θmax/α on Kobe).
- contact processing threshold 0: Bullet otherwise keeps contact points up to 2 cm
  apart in the solver, so the lifted corner of a block rocking by under ~0.1α acts as a
  speculative contact and those impacts are off by up to 1.7%. It is a per-body
  setting; Bullet's contactBreakingThreshold does the same but is process-global and
  would leak into every later client.
- solver: 50 iterations at Bullet's residual threshold. 5 or 10 iterations, a residual
  threshold of 1e-6 to 1e-2 (up to ~30% off the sub-step), cone friction off, contact
  slop 0 or 1e-4 each put β errors at 1.5–2.1% with 1 ms sub-steps (0.97% as chosen),
  global CFM 1e-6 at 6%; the MLCP solver doubles the sub-step; split impulse, SAT,
  friction ERP, CCD penetration, restitution threshold and non-contact iterations change
  nothing measurable.
- collision: box–box. Four small spheres (a compound) or two capsules at the bottom
  edges cost as much or more per sub-step; a static plane under a fixed base costs 20–30%
  less per sub-step but lets the pivot slip 0.8 mm and the block tilt by 3e-4·α at
  0.99·g·tanα (box: 0.03 mm, 7.5e-6·α).
- linear/angular damping 0 (Bullet's 0.04 lowers β by ~0.3%), restitution 0,
  friction 1 (0.5 lets the pivot slide: 3.4%), contact ERP 0.08 (Bullet's default; 0.2
  similar, 0.8 bounces: up to 6%), sleeping off (a resting block otherwise sleeps through a ground motion
  that starts late: a change of gravity does not wake it).
- skipped, each worth 2–8% of the run time: setGravity only when ẍg changes (gravity
  persists in Bullet), one getJointState per step serving both the isolator force and
  the output, ẍg precomputed as a list, no ground plane (the base is on its joint) and
  so no collision filtering, no deterministicOverlappingPairs (one pair; runs are
  bit-identical without it). output_every stays 1 (every 4 ms).
- a duration that is no multiple of the step ends with one shorter step.
"""
from __future__ import annotations

import ctypes
import math
import os
import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, fields

import numpy as np


def _libc_fflush():
    try:
        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # no C library to ask: nothing was buffered by it
        pass


@contextmanager
def _c_output_silenced(fds=(1,)):
    """Point the process's file descriptors `fds` (stdout by default) at /dev/null,
    flushing C's buffers before they are restored. Bullet's C code prints "argv[0]=" on
    stdout when it connects, and the CLI prints its JSON there."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(fd) for fd in fds]
    try:
        with open(os.devnull, "wb") as null:
            for fd in fds:
                os.dup2(null.fileno(), fd)
            try:
                yield
            finally:
                _libc_fflush()
    finally:
        for fd, keep in zip(fds, saved):
            os.dup2(keep, fd)
            os.close(keep)


# the import prints a build-time banner, noise in every command's output
with _c_output_silenced(fds=(1, 2)):
    import pybullet as p
    from pybullet_utils.bullet_client import BulletClient

from isorock.analytic.errors import require, require_nonnegative_finite, require_positive_finite
from isorock.analytic.motion import GroundMotion
from isorock.analytic.protocol import run_inputs
from isorock.analytic.status import Status
from isorock.analytic.system import System
from isorock.analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, Trajectory
from isorock.validate.measure import CONTACT_WINDOW, REST_FRACTION, contact_trajectory

ENGINE = "bullet"
SCENE_SUFFIX = ".sdf"
PLATE_THICKNESS = 0.1  # m; the plate only translates, so its size changes nothing but where it ends
#: s; the step at which ground motion, isolator force and output are updated (Bullet
#: sub-steps fill it): the default, and the one `settings_for_timestep` keeps
PYTHON_STEP = 4e-3


@dataclass(frozen=True)
class Settings:
    """Numerical settings of the PyBullet scene (defaults chosen by measurement; see
    the module docstring).

    timestep: the step (s) at which the ground motion, the isolator force and the
        output are updated (the Python step). substeps: Bullet sub-steps inside each step (0 or 1: none);
        Bullet integrates at timestep/substeps. solver_iterations: constraint solver
        iterations. friction: block–plate lateral friction coefficient. restitution:
        block–plate restitution. contact_erp: error reduction of contacts (Bullet's
        contactERP; 0.8 makes the block bounce). contact_processing_threshold: contact
        points farther apart than this (m) are left out of the solver (Bullet's default
        keeps them up to 2 cm: the lifted corner of a block rocking by less than ~0.1α
        then acts as a speculative contact and small impacts are off by up to 1.7%).
        linear_damping, angular_damping: Bullet's velocity damping of every body (1/s);
        model.md's physics has none.
        output_every: store every n-th step. contact_window: how far (s) before and
        after a sign change of θ the states for the effective β are taken
        (validate.measure.CONTACT_WINDOW by default).
    """

    timestep: float = PYTHON_STEP
    substeps: int = 12
    solver_iterations: int = 50
    friction: float = 1.0
    restitution: float = 0.0
    contact_erp: float = 0.08
    contact_processing_threshold: float = 0.0
    linear_damping: float = 0.0
    angular_damping: float = 0.0
    output_every: int = 1
    contact_window: float = CONTACT_WINDOW

    def __post_init__(self):
        require_positive_finite("timestep", self.timestep)
        require(self.timestep <= 0.01, "timestep", self.timestep,
                "at most 0.01 s (contacts need steps far shorter than the rocking time scale)")
        for name, low in (("substeps", 0), ("solver_iterations", 1), ("output_every", 1)):
            value = getattr(self, name)
            require(isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= low,
                    name, value, f"an integer ≥ {low}")
        require_positive_finite("friction", self.friction)
        require(0 <= self.restitution <= 1, "restitution", self.restitution, "in [0, 1]")
        require(0 < self.contact_erp <= 1, "contact_erp", self.contact_erp, "in (0, 1]")
        for name in ("linear_damping", "angular_damping", "contact_processing_threshold"):
            require_nonnegative_finite(name, getattr(self, name))
        require_positive_finite("contact_window", self.contact_window)

    @property
    def internal_step(self) -> float:
        """The step Bullet integrates with (s)."""
        return self.timestep / max(self.substeps, 1)


def settings_for_timestep(dt: float) -> Settings:
    """Settings whose Bullet step is `dt` (s), for work-precision ladders (validate.bench):
    the Python step (ground motion, isolator force, output) stays near PYTHON_STEP (4 ms)
    and Bullet sub-steps fill it, sub-steps in C being cheaper than Python steps.
    dt = 1/3000 s gives the defaults."""
    dt = require_positive_finite("timestep", dt)
    n = max(1, round(PYTHON_STEP / dt))
    return Settings(timestep=n * dt, substeps=n)


# --- the scene -------------------------------------------------------------------

@dataclass(frozen=True)
class Scene:
    """Body ids of a built scene. `base` is the plate's body; on an isolated base the
    plate is link 0 of it (the joint), on a fixed base it is the static body itself."""

    client: BulletClient
    block: int
    base: int
    plate_link: int  # -1 on a fixed base (the static body), 0 on an isolated base


def _plate_half_extents(system: System):
    # wide enough that even an overturned block lands on it
    half = system.b + system.height
    return [half, half, 0.5 * PLATE_THICKNESS]


def _block_pose(system: System, theta0: float):
    """Position of the block's centroid and its orientation, resting on the corner
    s·b (s = sign θ0) of the plate's top face (z = 0) and tilted by θ0 about y."""
    s = 1.0 if theta0 >= 0 else -1.0
    b, h = system.b, system.h
    # rotation by θ about y: x' = x cosθ + z sinθ, z' = −x sinθ + z cosθ
    vx, vz = -s * b, h  # centroid relative to the pivot corner, upright
    x = s * b + vx * math.cos(theta0) + vz * math.sin(theta0)
    z = -vx * math.sin(theta0) + vz * math.cos(theta0)
    return [x, 0.0, z], p.getQuaternionFromEuler([0.0, theta0, 0.0])


def build(client: BulletClient, system: System, settings: Settings, theta0: float = 0.0) -> Scene:
    """Create the bodies in `client` (a fresh DIRECT client) and set the physics."""
    c = client
    c.setPhysicsEngineParameter(fixedTimeStep=settings.timestep, numSubSteps=settings.substeps,
                                numSolverIterations=settings.solver_iterations,
                                contactERP=settings.contact_erp)
    c.setGravity(0.0, 0.0, -system.gravity)
    plate = c.createCollisionShape(p.GEOM_BOX, halfExtents=_plate_half_extents(system))
    top = [0.0, 0.0, -0.5 * PLATE_THICKNESS]  # the plate's top face is z = 0
    if system.fixed_base:
        base = c.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=plate, basePosition=top)
        plate_link = -1
    else:
        base = c.createMultiBody(
            baseMass=0.0, baseCollisionShapeIndex=-1, basePosition=[0.0, 0.0, 0.0],
            linkMasses=[system.base_mass], linkCollisionShapeIndices=[plate], linkVisualShapeIndices=[-1],
            linkPositions=[top], linkOrientations=[[0, 0, 0, 1]], linkInertialFramePositions=[[0, 0, 0]],
            linkInertialFrameOrientations=[[0, 0, 0, 1]], linkParentIndices=[0],
            linkJointTypes=[p.JOINT_PRISMATIC], linkJointAxis=[[1, 0, 0]])
        plate_link = 0
        # the joint's default velocity motor would hold the base still
        c.setJointMotorControl2(base, 0, p.VELOCITY_CONTROL, targetVelocity=0.0, force=0.0)
    box = c.createCollisionShape(p.GEOM_BOX, halfExtents=[system.b, system.b, system.h])
    pos, orn = _block_pose(system, theta0)
    # a plain rigid body (maximal coordinates), not a one-link Featherstone multibody: the
    # same β to 0.01 points, ~10% less time per sub-step
    block = c.createMultiBody(baseMass=system.mass, baseCollisionShapeIndex=box, basePosition=pos,
                              baseOrientation=orn, useMaximalCoordinates=True)
    for body, link in ((block, -1), (base, plate_link)):
        c.changeDynamics(body, link, lateralFriction=settings.friction, restitution=settings.restitution,
                         linearDamping=settings.linear_damping, angularDamping=settings.angular_damping,
                         activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING,
                         contactProcessingThreshold=settings.contact_processing_threshold)
    return Scene(client=c, block=block, base=base, plate_link=plate_link)


def connect() -> BulletClient:
    """A private DIRECT client: runs in one process share no state."""
    with _c_output_silenced():
        return BulletClient(connection_mode=p.DIRECT)


# --- the scene as a file ----------------------------------------------------------

_SDF = """<?xml version="1.0"?>
<!-- isorock: block on {base_kind} base for PyBullet (p.loadSDF). Generated by bullet_models.scene;
     simulate() builds the same bodies with createMultiBody and then applies
     {settings}
     linear/angular damping, friction and restitution with changeDynamics on both bodies, sleeping off,
     {isolator} -->
<sdf version="1.6">
  <world name="isorock">
    <model name="base">
{base_links}
    </model>
    <model name="block">
      <pose>0 0 {h} 0 0 0</pose>
      <link name="block">
        <inertial><mass>{m}</mass>{inertia}</inertial>
        <collision name="block"><geometry><box><size>{B} {B} {H}</size></box></geometry></collision>
      </link>
    </model>
  </world>
</sdf>
"""
_PLATE = """      <link name="plate">
        <pose>0 0 {z} 0 0 0</pose>
        <inertial><mass>{mass}</mass>{inertia}</inertial>
        <collision name="plate"><geometry><box><size>{w} {w} {t}</size></box></geometry></collision>
      </link>"""
_ANCHOR = """      <link name="anchor">
        <inertial><mass>0</mass>{inertia}</inertial>
      </link>
{plate}
      <joint name="isolator" type="prismatic">
        <parent>anchor</parent><child>plate</child>
        <axis><xyz>1 0 0</xyz><limit><lower>-1e30</lower><upper>1e30</upper></limit></axis>
      </joint>"""
# PyBullet recomputes a box's inertia from its mass and size; the parser still wants the element
_NO_INERTIA = "<inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>"


def scene_text(system: System, settings: Settings | None = None) -> str:
    """The scene as an SDF world (block upright at rest), loadable with `p.loadSDF`.
    SDF rather than URDF because a URDF holds one tree and the block is a second, free
    body. The numerical settings do not live in SDF; the header comment lists them."""
    settings = settings or Settings()
    w = 2 * _plate_half_extents(system)[0]
    plate_mass = 0.0 if system.fixed_base else system.base_mass
    plate = _PLATE.format(z=-0.5 * PLATE_THICKNESS, mass=plate_mass, inertia=_NO_INERTIA, w=w, t=PLATE_THICKNESS)
    base_links = plate if system.fixed_base else _ANCHOR.format(inertia=_NO_INERTIA, plate=plate)
    isolator = ("no isolator: the plate is static" if system.fixed_base else
                f"isolator force -(k u + c u_dot) on the joint each step, k = {system.stiffness} N/m, "
                f"c = {system.damping} N s/m, joint motor off")
    listed = ", ".join(f"{f.name} = {getattr(settings, f.name)!r}" for f in fields(settings))
    return _SDF.format(base_kind="a fixed" if system.fixed_base else "an isolated", settings=listed,
                       isolator=isolator, base_links=base_links, h=system.h, m=system.mass,
                       inertia=_NO_INERTIA, B=system.width, H=system.height)


# --- simulate --------------------------------------------------------------------

def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0,
             impact_threshold: float = DEFAULT_IMPACT_THRESHOLD, progress=None) -> Trajectory:
    """Simulate from rest at tilt `theta0` (rad; > 0 rests on corner O, centroid towards
    +x) for `duration` s (default: motion end + 5 s, or 10 s without motion). Returns the
    shared Trajectory built by `validate.measure.contact_trajectory`; a run stops at the
    first stored sample where |θ| ≥ α (overturned). progress: callable(t, duration),
    called about once a second."""
    settings = settings or Settings()
    motion, duration = run_inputs(system, motion, duration, theta0, impact_threshold)

    dt = settings.timestep
    n_steps = int(math.floor(duration / dt + 1e-9))
    times = (np.arange(n_steps + 1) * dt).tolist()
    # ẍg held over each step, taken at its middle (at its start it would lag by dt/2)
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
    k, c_dash = system.stiffness, system.damping
    n = max(settings.substeps, 1)
    lead = (n - 1) / (2 * n) * dt  # the held isolator force acts at the sub-steps' mean time
    rocking = REST_FRACTION * system.alpha
    report_every = max(1, round(0.25 / dt))
    every = settings.output_every
    fixed = system.fixed_base

    client = connect()
    try:
        scene = build(client, system, settings, theta0)
        c, block, base = client, scene.block, scene.base
        set_gravity, step = c.setGravity, c.stepSimulation
        joint_state, motor = c.getJointState, c.setJointMotorControl2
        pose, velocity = c.getBasePositionAndOrientation, c.getBaseVelocity
        torque = p.TORQUE_CONTROL
        rows = []  # (t, u, u̇, x, y, z, qx, qy, qz, qw, ω_y)
        alpha = system.alpha
        status, message = Status.COMPLETED, "reached the end time"
        u = ud = 0.0
        ud_prev = udd = 0.0  # base velocity one step back; base acceleration estimate
        side_prev = 0.0  # sin θ (≈ R₀₂) one step back
        a_set = 0.0  # build() set gravity (0, 0, −g)
        start = last_report = time.perf_counter()
        for i in range(n_steps + 1):
            if not fixed:
                # one read serves both the isolator force and the output
                u, ud = joint_state(base, 0)[:2]
            if i % every == 0 or i == n_steps:
                pos, orn = pose(block)
                rows.append((times[i], u, ud, *pos, *orn, velocity(block)[1][1]))
                qx, qy, qz, qw = orn
                tilt = abs(math.atan2(2 * (qx * qz + qw * qy), 1 - 2 * (qx * qx + qy * qy)))
                if not math.isfinite(tilt + u):
                    rows.pop()  # the history ends at the last finite state
                    status, message = Status.FAILED, f"non-finite state at t = {times[i]:.6g} s"
                    break
                if tilt >= alpha:
                    break  # overturned: contact_trajectory reports it
            if i == n_steps:
                break
            if last and i == n_steps - 1:  # the shorter last step, sub-steps no longer than before
                m = math.ceil(last / settings.internal_step - 1e-9) if n > 1 else settings.substeps
                c.setPhysicsEngineParameter(fixedTimeStep=last, numSubSteps=m)
                lead = (m - 1) / (2 * m) * last if m > 1 else 0.0
            a = xg[i]
            if a != a_set:  # gravity persists in Bullet: set it only when ẍg changes
                set_gravity(-a, 0.0, -g)
                a_set = a
            if not fixed:
                # ü from the last step, except over an impact (θ changed sign while rocking):
                # the jump of u̇ there is no acceleration to extrapolate, the last one is kept
                qx, qy, qz, qw = orn if i % every == 0 else pose(block)[1]
                side = 2 * (qx * qz + qw * qy)
                if i and ((side > 0) == (side_prev > 0) or max(abs(side), abs(side_prev)) < rocking):
                    udd = (ud - ud_prev) / dt
                ud_prev, side_prev = ud, side
                motor(base, 0, torque, force=-(k * (u + lead * ud) + c_dash * (ud + lead * udd)))
            step()
            if progress is not None and i % report_every == report_every - 1:
                now = time.perf_counter()
                if now - last_report > 1.0:
                    progress(times[i + 1], duration)
                    last_report = now
        runtime = time.perf_counter() - start
    finally:
        client.disconnect()

    return _trajectory(system, motion, np.array(rows), settings, impact_threshold, runtime, status, message)


def _trajectory(system, motion, rows, settings, impact_threshold, runtime, status, message) -> Trajectory:
    t, u, ud, x, y, _z, qx, qy, qz, qw, wy = rows.T
    # rotation matrix entries of (x, y, z, w) quaternions
    r00 = 1 - 2 * (qy**2 + qz**2)
    r10 = 2 * (qx * qy + qw * qz)
    r02 = 2 * (qx * qz + qw * qy)
    r12 = 2 * (qy * qz - qw * qx)
    r22 = 1 - 2 * (qx**2 + qy**2)
    theta = np.arctan2(r02, r22)  # the body z axis leans to +x when θ > 0
    roll = np.arctan2(-r12, np.hypot(r02, r22))  # rotation about world x
    yaw = np.arctan2(r10, r00)  # rotation about world z
    # the pivot corner (s·b, ·, −h) in the body frame, relative to where it rests on the plate
    s = np.where(theta >= 0, 1.0, -1.0)
    b, h = system.b, system.h
    pivot_slip = x + r00 * s * b - r02 * h - u - s * b
    rocking = np.abs(theta) > REST_FRACTION * system.alpha
    extras = {
        "drift_y": y, "drift_roll": roll, "drift_yaw": yaw, "pivot_slip": pivot_slip,
        "drift_y_max": float(np.max(np.abs(y))),
        "drift_roll_max": float(np.max(np.abs(roll))),
        "drift_yaw_max": float(np.max(np.abs(yaw))),
        "pivot_slip_max": float(np.max(np.abs(pivot_slip[rocking]))) if rocking.any() else 0.0,
    }
    return contact_trajectory(ENGINE, system, motion, t=t, u=u, u_dot=ud, theta=theta, theta_dot=wy,
                              impact_threshold=impact_threshold, runtime_s=runtime, status=status,
                              message=message, extras=extras, window=settings.contact_window)
