"""The block on its base in DART (dartpy, the optional `dart` extra; issue 37): a fourth contact
engine, DART's own collision (FCL box–box) and its constraint solver (an LCP of the contacts,
restitution 0, Coulomb friction), at a fixed step that follows the body's size (Settings.for_system:
the same share of its rocking time 1/p_eff at every size, 0.1 ms on the paper's block), in a time
unit of its own that puts the body's speed scale R·p_eff at SCENE_SPEED (Settings.time_stretch: DART's
contact keeps a constant in m/s), so that one dimensionless case meets its contact alike at every size.

The scene: the block a box H × D × B on a free joint (it may rock, slide, twist and lift off in
3-D), resting on a base plate: welded to the world on a fixed base, or on a prismatic joint along
x with the isolator's spring k and dashpot c (DART's joint spring and damping). The ground motion
enters as the uniform inertial field of the base's translating frame: the gravity is set to
(−ẍg(t), 0, −g) before each step (exact for a translating frame: the bullet_models hull scene
does the same), so u is the base's joint position relative to the ground.

Two horizontal components (GroundMotion.transverse, issue 36): ÿg is the gravity's y as ẍg is its
x, (−ẍg, −ÿg, −g), so every body, the plate too, feels −m·ÿg; on the linear isolator the plate is on
one joint of two translations (x and y, DART's TranslationalJoint2D) with the same k and c on each
(the isolator is isotropic); a fixed base is the same weld. A pair runs at a friction of
PAIR_FRICTION or more (the preset `pair`; below it the statue slips). Without a second component
the scene is the one above, unchanged.

A friction pendulum or a ball in a bowl (isolator_parts: k = W/R, c, F_b = μ·W) is built on the
same base joint: the spring a joint force set before each step, the slider the joint's Coulomb
friction, under a pair bounded along the base's velocity or load (_Pendulum; docs/dart.md,
"Pendulum isolators").

What it carries: the linear isolator, the friction pendulum and the ball in a bowl (ISOLATORS, on
one component and under a pair), a statue that cannot slip on its base (its friction is
DART's high default, Settings.friction), horizontal ground motion (one component or a pair), a
statue's own shape in the block's place (statue.py; Capabilities below: anything else is refused
in one line). Measured in docs/dart.md; its limits in validate/core/tolerances.py.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

from ..analytic import hull_contact, kinematics
from ..analytic.engine_protocol import (DEFAULT_IMPACT_THRESHOLD, Capabilities, EngineSpec, Preset, contact_scale,
                                             run_inputs)
from ..analytic.errors import InputError, import_extra
from ..analytic.isolator_parts import PLANE_ISOLATORS, check_contact_isolator, isolator_parts
from ..analytic.status import Status
from ..analytic.system import LINEAR, paper_system
from ..analytic.trajectory import RawHistory

from . import statue

#: the block's depth (m) over its width: out of the rocking plane, only its stability matters
DEPTH_RATIO = 1.0
#: the base plate's size against the block's width, and its thickness (m)
PLATE_WIDTH_RATIO, PLATE_THICKNESS = 6.0, 0.1
#: s; a row of the history every this many seconds (at most), as the other contact engines store,
#: on the paper's isolated block (Settings.sample_interval: it follows the body's size as the step does)
SAMPLE_DT = 1e-3
#: a statue's own shape (statue.py) is carried: Capabilities.two_edges says so, judged in
#: docs/statues.md ("DART on the statue's hull": the bust and the obelisk within MuJoCo's statue rows)
TWO_EDGES = True
#: two horizontal components on a fixed base, the linear isolator and the pendulums (ISOLATORS): what
#: Capabilities.transverse says, judged in docs/statues.md ("Two horizontal components", DART) by
#: tests/test_two_components_dart.py, the pendulums by tests/test_isolator_dart.py
TRANSVERSE = True
#: the least Settings.friction a pair runs at: the statue's hull (its vertex spheres) slips under two
#: components below it, and its tilt then turns on μ and on the pair's direction against the world's
#: axes, the friction pyramid's; measured on the bust's test pairs (tests/test_two_components_dart.py):
#: peak tilt 0.465 α at μ 1, 0.1955 α at μ 3 to 10 on a fixed base; 0.154 α at μ 1, 0.188 at μ 2–3,
#: 0.1813 at μ 5 to 10 on the linear isolator (docs/statues.md, "Two horizontal components", DART).
#: The block (a box on its four corners) held at μ 1 (its peak under a pair the same as at μ 3 to
#: 4e-12): one rule for both keeps what a pair's settings mean the same whatever the body
PAIR_FRICTION = 5.0
#: The isolators DART carries (Capabilities.isolators), on one component and under a pair
#: (Capabilities.transverse_isolators, the same three): the linear one, and the friction pendulum and
#: the ball in a bowl (isolator_parts.PLANE_ISOLATORS): the pendulum's spring k = W/R and dashpot c on
#: the base joint, its rigid slider μ·W the joint's own Coulomb friction (DART's
#: JointCoulombFrictionConstraint, a stick solved in the same LCP as the contacts; _Pendulum).
#: Not the bilinear bearing, the ball in a cone or the double pendulum: refused in one line.
ISOLATORS = PLANE_ISOLATORS
#: m/s (the system's): a base slower than this is taken as stuck by a pair's friction direction
#: (_Pendulum), which then follows the load on the base instead of its velocity
STUCK_SPEED = 1e-9


#: s; DART's step on the paper's isolated block (p_eff 3.23/s), measured there (docs/dart.md)
DEFAULT_TIMESTEP = 1e-4
#: The step in units of the body's rocking time 1/p_eff (System.rocking_rate): follow_system makes
#: timestep·p_eff = STEP_SHARE at every size, the default's on the paper's isolated block (so that
#: block steps 0.1 ms and keeps a row every 1 ms, as before). A fixed 0.1 ms was
#: 1.06e-3 of the bust's 1/p_eff at 0.25× (0.11 m tall) and put its β 1.32% off on a fixed base; at
#: this share the bust and the obelisk from 0.25× to 3× keep β within 0.53% (docs/statues.md,
#: "Smaller, and lighter-based, in every hull engine"), and the atlas's blocks, 0.1 m to 10 m, meet
#: one step in their own time units (docs/dart.md, "Every size").
STEP_SHARE = DEFAULT_TIMESTEP * paper_system().rocking_rate
#: m/s; the body's speed scale R·p_eff as DART's world sees it (Settings.time_stretch). DART's contact
#: keeps constants in m/s that dartpy does not expose (its ContactConstraint pushes a penetration
#: out at ERP·depth/dt, 1% per step, but at 1e-3 m/s at most), so at a fixed share of 1/p_eff its β
#: still turned on the body's size: the squat block on a light base (λ 1.5, μ 4) erred 0.17% at 0.1 m
#: (R·p_eff 0.87 m/s), 0.60% at 1 m and 0.85% at 10 m (8.7 m/s), and the same 0.1 m block under 100 g
#: as the 10 m one (0.83%): a speed, not a length or a mass. The scene runs in a time unit stretched
#: by R·p_eff/SCENE_SPEED (exact: its step, gravity, ground motion, spring and dashpot rescaled, the
#: history's velocities scaled back), so every body meets those constants at this one speed, below
#: where the cap binds: that block then errs 0.14–0.16% at every size, the atlas's 100 cells ≤ 0.17%
#: (docs/dart.md, "Every size").
SCENE_SPEED = 0.3


@dataclass(frozen=True)
class Settings:
    """timestep (s): DART's fixed step; friction: the block's Coulomb coefficient on the plate
    (high: the model assumes no sliding); sample_interval (s): a row of the history at most this
    far apart (at whole steps); follow_system: True: `for_system` scales the step and the sample
    interval with the body's rocking time, by contact_scale(system, DEFAULT_TIMESTEP, STEP_SHARE)
    as MuJoCo's and PyBullet's steps (1 on the paper's isolated block; a preset ten times coarser
    stays ten times coarser). A timestep or sample interval given to `settings_for` (every
    command's path: --timestep, a campaign's or a table's) sets it False, as does `for_system`
    once applied: what a user sets, the run uses."""

    timestep: float = DEFAULT_TIMESTEP
    friction: float = 1.0
    sample_interval: float = SAMPLE_DT
    follow_system: bool = True
    #: DART's time units per second of the system (1: its world in seconds, its contact's
    #: constants in m/s then meeting each body at its own speed); None: R·p_eff/SCENE_SPEED, the
    #: system's own (fixed by for_system, or at the run)
    stretch: float | None = None

    def for_system(self, system, duration: float | None = None) -> "Settings":
        """These settings for `system`: with follow_system, the step and the sample interval
        times contact_scale(system, DEFAULT_TIMESTEP, STEP_SHARE) (0.30 on the bust at 0.25× on a fixed base, 0.22
        on a squat 0.1 m block on a light base, 2.2 on a 10 m one), so that a run steps and samples
        alike in units of its own 1/p_eff at every size; final (follow_system False). Without
        follow_system, the step as given, the time unit fixed for the system all the same (what a
        run uses, and what its report shows). `duration` is not needed: the last step's row is
        stamped at the duration, as with a step given in seconds."""
        if not self.follow_system:
            return self if self.stretch is not None else replace(self, stretch=self.time_stretch(system))
        k = contact_scale(system, DEFAULT_TIMESTEP, STEP_SHARE)
        return replace(self, timestep=self.timestep * k, sample_interval=self.sample_interval * k,
                       stretch=self.time_stretch(system), follow_system=False)

    def __post_init__(self):
        if not (isinstance(self.timestep, (int, float)) and 1e-6 <= self.timestep <= 1e-2):
            raise InputError(f"timestep = {self.timestep!r}: must be a step from 1e-6 to 0.01 s")
        if not (isinstance(self.friction, (int, float)) and 0 < self.friction <= 10 and math.isfinite(self.friction)):
            raise InputError(f"friction = {self.friction!r}: must be a friction coefficient in (0, 10]")
        if not (isinstance(self.sample_interval, (int, float)) and 0 < self.sample_interval <= 1.0):
            raise InputError(f"sample_interval = {self.sample_interval!r}: must be a time in (0, 1] s")
        if not isinstance(self.follow_system, bool):
            raise InputError(f"follow_system = {self.follow_system!r}: must be true or false")
        if self.stretch is not None and not (isinstance(self.stretch, (int, float)) and not isinstance(self.stretch, bool)
                                             and 1e-3 <= self.stretch <= 1e4):
            raise InputError(f"stretch = {self.stretch!r}: must be from 0.001 to 10000 (DART's time units per "
                             "second; 1: seconds), or none (the system's own, SCENE_SPEED)")

    def time_stretch(self, system) -> float:
        """How many of DART's time units a second of `system` lasts: `stretch`, or without it
        R·p_eff/SCENE_SPEED, so that the body's speed scale R·p_eff is SCENE_SPEED in DART's world.
        Every speed DART sees is the body's divided by it."""
        return float(self.stretch) if self.stretch is not None else system.R * system.rocking_rate / SCENE_SPEED


def settings_for(**overrides) -> Settings:
    """Settings with `overrides`; a timestep or sample interval given is what the run takes
    (follow_system False unless told), as for PyBullet and MuJoCo."""
    if {"timestep", "sample_interval"} & set(overrides):
        overrides.setdefault("follow_system", False)
    return Settings(**overrides)


def _box(skeleton_node, size, *, friction=None):
    dart = import_extra("dartpy", "dart", "the engine 'dart'")
    node = skeleton_node.createShapeNode(dart.dynamics.BoxShape(list(size)))
    node.createVisualAspect()
    node.createCollisionAspect()
    dynamics = node.createDynamicsAspect()
    dynamics.setRestitutionCoeff(0.0)
    if friction is not None:
        dynamics.setFrictionCoeff(float(friction))
    return node


def _pose(tilt: float, b: float, h: float, z0: float):
    """(rotation, position) of the block's centre tilted by `tilt` about its corner on that side."""
    s = 1.0 if tilt >= 0 else -1.0
    c, si = math.cos(tilt), math.sin(tilt)
    R = np.array([[c, 0.0, si], [0.0, 1.0, 0.0], [-si, 0.0, c]])  # about y: z leans towards +x for tilt > 0
    pivot = np.array([s * b, 0.0, z0])
    return R, pivot + R @ np.array([-s * b, 0.0, h])


class _Pendulum:
    """A pendulum isolator's parts (isolator_parts: its spring k = W/R, dashpot c and rigid slider
    F_b = μ·W) on the base joint, in DART's units (forces 1/stretch² of a newton).

    The spring is a joint force −k·u set before each step, not DART's joint spring: DART steps a
    joint spring implicitly, which damps a swing by ω·dt/2 of its amplitude per radian (the free
    pendulum's Coulomb decay 2μ_f·R per half cycle measured 2.1e-3 too large at R 1.5 m, μ 0.01, 0.1 ms,
    and 5.4e-4 at a quarter of the step), where the explicit force, DART's semi-implicit Euler, leaves
    5e-6 (docs/dart.md, "Pendulum isolators"). The dashpot c stays the joint's damping (0 on these).

    The slider is DART's joint Coulomb friction (JointCoulombFrictionConstraint: a stick solved in the
    same LCP as the block's contacts). One component: F_b on the prismatic joint, set once: the
    model's constant slip force. A pair (TranslationalJoint2D): DART bounds each dof's friction apart
    (a square: √2·F_b along a diagonal, as MuJoCo's frictionloss on two joints; DART's contact
    friction is a pyramid of two directions alike, and dartpy sets no contact's friction direction,
    so a held puck, MuJoCo's and Drake's pair construction, would be no rounder here). So before each
    step the bounds are F_b·|ê_x| and F_b·|ê_y| along a unit direction ê: the base's velocity while it
    slides (faster than STUCK_SPEED), so that the friction is F_b against it, the model's isotropic
    Coulomb force (ê a step behind); while it is stuck, the load that would move it with the block
    riding on it, −(m + m_b)·a_g − k·u, so that it holds up to F_b along that load and slips there.
    Along one fixed direction (a pulse turned by any angle) the bounds are exactly F_b along it."""

    def __init__(self, system, joint, stretch: float):
        parts = isolator_parts(system)
        self.joint, self.stretch = joint, stretch
        self.k, self.total = parts.stiffness, system.mass + system.base_mass
        self.friction = parts.base_friction / stretch**2
        self.dofs = joint.getNumDofs()
        self.last = (1.0, 0.0)
        for dof in range(self.dofs):
            joint.setSpringStiffness(dof, 0.0)
            joint.setDampingCoefficient(dof, parts.damping / stretch)
        if self.dofs == 1 and self.friction > 0.0:
            joint.setCoulombFriction(0, self.friction)

    def direction(self, ax: float, ay: float):
        """ê before a step whose ground acceleration is (ax, ay) (m/s²)."""
        j, s = self.joint, self.stretch
        vx, vy = j.getVelocity(0) * s, j.getVelocity(1) * s
        v = math.hypot(vx, vy)
        if v > STUCK_SPEED:
            return vx / v, vy / v
        lx, ly = -self.total * ax - self.k * j.getPosition(0), -self.total * ay - self.k * j.getPosition(1)
        load = math.hypot(lx, ly)
        return (lx / load, ly / load) if load > 0.0 else self.last

    def before_step(self, ax: float, ay: float) -> None:
        """The spring's force at the step's start; under a pair, the friction's bounds along ê."""
        for dof in range(self.dofs):
            self.joint.setForce(dof, -self.k * self.joint.getPosition(dof) / self.stretch**2)
        if self.dofs == 2 and self.friction > 0.0:
            self.last = ex, ey = self.direction(ax, ay)
            self.joint.setCoulombFriction(0, self.friction * abs(ex))
            self.joint.setCoulombFriction(1, self.friction * abs(ey))


def simulate(system, motion=None, *, settings=None, duration=None, theta0=0.0, progress=None) -> RawHistory:
    dart = import_extra("dartpy", "dart", "the engine 'dart'")
    # the step this system takes (Settings.for_system): the bounds below judge that one
    settings = (settings or Settings()).for_system(system)
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD, settings=settings,
                                  two_edges=TWO_EDGES,  # a statue without its shape: hull_contact.check_shape, below
                                  transverse=TRANSVERSE, isolators=ISOLATORS, transverse_isolators=ISOLATORS)
    check_contact_isolator(system, "dart")  # μ_f(v): refused in one line
    if system.friction is not None or motion.vertical is not None:  # said again for a direct caller
        raise InputError("system: engine 'dart' carries a statue that cannot slip, on level ground")
    hull_contact.check_shape(system, "DART")
    hull = hull_contact.has_solid(system)
    transverse = motion.transverse is not None
    if transverse and settings.friction < PAIR_FRICTION:  # refused, never run slipping in its place
        raise InputError(f"friction = {settings.friction:g}: engine 'dart' runs two horizontal components with a "
                         f"friction of {PAIR_FRICTION:g} or more (below it its statue slips, the tilt turning on the "
                         f"pair's direction: docs/statues.md); the preset dart:pair, or Settings(friction={PAIR_FRICTION:g}) "
                         "up to 10")
    h, b = system.h, system.b
    dt = float(settings.timestep)
    world = dart.simulation.World()
    # DART's own time unit (Settings.time_stretch, SCENE_SPEED): a second of the system lasts `stretch`
    # of them, so its step is stretch·dt, every acceleration (gravity, the ground's) and the spring
    # 1/stretch² (its period stretch·T), the dashpot 1/stretch, and each speed DART reports is
    # stretch times too slow (scaled back in the history's rows; positions and angles are unchanged)
    stretch = settings.time_stretch(system)
    world.setTimeStep(dt * stretch)
    # DART puts a body slower than 0.01 m/s and 0.05 rad/s for 0.5 s to sleep: absolute speeds and
    # a time again, and the exact model has no sleep
    sleep = world.getDeactivationOptions()
    sleep.mEnabled = False
    world.setDeactivationOptions(sleep)
    world.setGravity([0.0, 0.0, -system.gravity / stretch**2])

    base = dart.dynamics.Skeleton("base")
    if system.fixed_base:
        joint, plate = base.createWeldJointAndBodyNodePair()
    else:
        if transverse:
            # one joint of two translations, x then y (its default plane): the plate's one mass
            # moves along both, u and u_y its two positions
            joint, plate = base.createTranslationalJoint2DAndBodyNodePair()
        else:
            joint, plate = base.createPrismaticJointAndBodyNodePair()
            joint.setAxis([1.0, 0.0, 0.0])
        for dof in range(joint.getNumDofs()):  # the isotropic isolator: the same k and c along each
            joint.setSpringStiffness(dof, float(system.stiffness) / stretch**2)
            joint.setDampingCoefficient(dof, float(system.damping) / stretch)
        plate.setMass(float(system.base_mass))
    # a pendulum's spring, dashpot and slider on the base joint (_Pendulum; None on the linear isolator)
    pendulum = None if system.fixed_base or system.isolator_kind == LINEAR else _Pendulum(system, joint, stretch)
    below = dart.math.Isometry3()
    below.set_translation([0.0, 0.0, -0.5 * PLATE_THICKNESS])
    joint.setTransformFromParentBodyNode(below)  # the plate's top at z = 0
    # a statue's plate is square, past its hull and where it lands overturned (hull_contact); the
    # block's is square too under a pair, as it may fall along y as along x
    side = statue.plate_size(system) if hull else None
    # the plate's friction is the body's: DART takes the smaller of the two shapes' coefficients,
    # so the plate's default 1 held Settings.friction to 1 at most (the default, 1, is unchanged)
    _box(plate, (side, side, PLATE_THICKNESS) if hull else
         (PLATE_WIDTH_RATIO * system.width,
          PLATE_WIDTH_RATIO * system.width if transverse else DEPTH_RATIO * system.width * 2, PLATE_THICKNESS),
         friction=settings.friction)
    world.addSkeleton(base)

    block = dart.dynamics.Skeleton("block")
    free, body = block.createFreeJointAndBodyNodePair()
    if hull:  # its own shape in the block's place (statue.py)
        statue.build(dart, body, free, system, float(theta0), settings.friction)
    else:
        depth = DEPTH_RATIO * system.width
        _box(body, (system.width, depth, system.height), friction=settings.friction)
        m = float(system.mass)
        body.setMass(m)
        body.setMomentOfInertia(m * (depth**2 + system.height**2) / 12, system.inertia,
                                m * (system.width**2 + depth**2) / 12, 0.0, 0.0, 0.0)
        R, centre = _pose(float(theta0), b, h, 0.0)
        pose = dart.math.Isometry3()
        pose.set_rotation(R)
        pose.set_translation(centre)
        free.setPositions(dart.dynamics.FreeJoint.convertToPositions(pose))
    world.addSkeleton(block)

    every = max(1, int(round(settings.sample_interval / dt)))
    n = int(math.ceil(duration / dt))
    rows = np.empty((n // every + 2, 5))
    # a statue's wobble out of the plane and its centre of mass, for the contact engines' extras
    more = np.empty((rows.shape[0], 5)) if hull else None
    # a pair's 3-D history (kinematics.pair_extras): the body's rotation matrix (9), its centre's y, u_y
    pair = np.empty((rows.shape[0], 11)) if transverse else None
    k = 0
    status, message, start = Status.COMPLETED, "reached the end time", time.perf_counter()

    def row(t):
        Rw = body.getWorldTransform().rotation()
        theta = math.atan2(Rw[0, 2], Rw[2, 2])
        omega = np.asarray(body.getAngularVelocity())  # world frame: its y is θ̇
        u, ud = (0.0, 0.0) if system.fixed_base else (float(joint.getPosition(0)), float(joint.getVelocity(0)))
        return t, u, ud * stretch, theta, float(omega[1]) * stretch

    def pair_row():
        tf = body.getWorldTransform()
        u_y = 0.0 if system.fixed_base else float(joint.getPosition(1))
        return (*np.asarray(tf.rotation(), dtype=float).ravel(), float(tf.translation()[1]), u_y)

    rows[k] = row(0.0)
    if hull:
        more[k] = statue.row(body)
    if transverse:
        pair[k] = pair_row()
    k += 1
    # ÿg at each step's start, as ẍg; 0.0 throughout without a second component, as before
    y_at = motion.transverse.at if transverse else (lambda _t: 0.0)
    for i in range(1, n + 1):
        t = i * dt
        ax, ay = float(motion.at(t - dt)), float(y_at(t - dt))
        if pendulum is not None:
            pendulum.before_step(ax, ay)
        world.setGravity([-ax / stretch**2, -ay / stretch**2, -system.gravity / stretch**2])
        world.step()
        if i % every == 0 or i == n:
            rows[k] = row(min(t, duration))
            if hull:
                more[k] = statue.row(body)
            if transverse:
                pair[k] = pair_row()
            if not np.all(np.isfinite(rows[k])):
                status, message = Status.FAILED, f"non-finite state at t = {t:.4g} s"
                break
            k += 1
            # on its side: measure() judges the fall from the history. |atan2(R02, R22)| ≥ π/2 is
            # R22 ≤ 0, the total tilt past π/2 whichever way it leans: a pair's rule too
            if abs(rows[k - 1, 3]) >= 0.5 * math.pi:
                break
        if progress is not None and i % 20000 == 0:
            progress(t, duration)
    rows = rows[:k]
    extras = statue.extras(system, rows[:, 3], rows[:, 1], more[:k]) if hull else {}
    if transverse:  # the 3-D history the two-component measures read (validate.core.biaxial)
        pair = pair[:k]
        x, y, z, w = Rotation.from_matrix(pair[:, :9].reshape(-1, 3, 3)).as_quat().T  # scipy: scalar last
        kinematics.pair_extras(extras, orientation=np.stack([w, x, y, z], axis=1), y_centroid=pair[:, 9],
                               u_y=pair[:, 10])
    return RawHistory(engine="dart", system=system, t=rows[:, 0], u=rows[:, 1], u_dot=rows[:, 2], theta=rows[:, 3],
                      theta_dot=rows[:, 4], status=status, message=message, runtime_s=time.perf_counter() - start,
                      extras=extras)


def ladder(quick: bool):
    """Work-precision ladder (label, Settings), cheapest first: DART's step, as named (a rung is
    the step it says, whatever the system: follow_system False)."""
    steps = (1e-3, 3e-4, 1e-4) if quick else (1e-3, 3e-4, 1e-4, 3e-5)
    return [(f"dt={h:g}", settings_for(timestep=h)) for h in steps]


ENGINE = EngineSpec(
    name="dart", label="DART", settings_type=Settings, simulate=simulate, ladder=ladder, settings_for=settings_for,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False, campaigns=False,
                              isolators=ISOLATORS, kinetic_friction=False, statue_friction=False, vertical=False,
                              two_edges=TWO_EDGES, transverse=TRANSVERSE, transverse_isolators=ISOLATORS),
    presets={"default": Preset("a step of STEP_SHARE/p_eff (0.1 ms on the paper's block, following the body's size), "
                               "restitution 0, friction 1 (docs/dart.md)", Settings),
             "coarse": Preset("ten times the default's step (1 ms on the paper's block, following the body's size): "
                              "what DART's step costs in β (docs/dart.md)", lambda: Settings(timestep=1e-3)),
             "pair": Preset(f"friction {PAIR_FRICTION:g}: the least two horizontal components run at (below it the "
                            "statue slips under a pair; docs/statues.md)", lambda: Settings(friction=PAIR_FRICTION))})

__all__ = ["ENGINE", "Settings", "simulate", "ladder", "settings_for"]
