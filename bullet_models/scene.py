"""The block on its base as a PyBullet scene (a private `p.DIRECT` client per thread, emptied for each run),
and the same scene as an SDF file a user can open.

- block: a free box 2b × 2b × 2h (x, y, z) of mass m, a plain rigid body (maximal
  coordinates); Bullet's box inertia about y is m(b² + h²)/3, the model's I;
- isolated base: a plate on a prismatic joint along x under a massless, shapeless
  anchor; its default velocity motor is switched off (force 0) and the isolator force
  −(k u + c u̇) is applied as a joint force every control step (stepping.py);
- fixed base: the same plate as a static body (mass 0), no joint;
- no ground plane: the base moves on its joint, so the only collision pair in the
  world is block–plate and no collision filtering is needed.

Conventions: quaternions are (x, y, z, w); angular velocity is in the world frame.
Why each choice, with measurements: docs/bullet.md.
"""
from __future__ import annotations

import ctypes
import os
import sys
import threading
from contextlib import contextmanager
from dataclasses import dataclass, fields


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

from ..analytic.errors import InputError
from ..analytic import hull_contact, kinematics
from ..analytic.isolator_parts import PUCK_HALF, isolator_parts, pendulum_puck
from ..analytic.system import LINEAR, System

from . import statue
from .settings import Settings

SCENE_FORMAT = ("SDF", ".sdf")
PLATE_THICKNESS = 0.1  # m; the plate only translates, so its size changes nothing but where it ends


# --- the scene -------------------------------------------------------------------

@dataclass(frozen=True)
class Scene:
    """Body ids of a built scene. `base` is the plate's body; on an isolated base the
    plate is link 0 of it (the joint), on a fixed base it is the static body itself."""

    client: BulletClient
    block: int
    base: int
    plate_link: int  # -1 on a fixed base (the static body), 0 on an isolated base (1 with two components)
    #: a statue's own shape (statue.py): its inertial frame's orientation in its own frame, which
    #: Bullet's poses are of (statue.link_orientation turns them back); None for the block
    frame: tuple | None = None
    #: a pendulum's friction puck under a pair (_pendulum_puck): the base's link 2, on its own
    #: vertical joint, and the force (N, on that joint) that holds it down; None otherwise
    puck_link: int | None = None
    puck_hold: float = 0.0

    def pose(self):
        """(position, orientation) of the block's or statue's own frame (x, y, z, w)."""
        pos, orn = self.client.getBasePositionAndOrientation(self.block)
        return pos, (orn if self.frame is None else statue.link_orientation(orn, self.frame))

    def reset_pose(self, pos, orn) -> None:
        """Put the block or statue at `pos` with its own frame's orientation `orn`."""
        self.client.resetBasePositionAndOrientation(
            self.block, pos, orn if self.frame is None else statue.inertial_orientation(orn, self.frame))


def _plate_half_extents(system: System):
    # wide enough that even an overturned block lands on it, and a statue that may slide walks on it
    # (a statue's own shape: past its hull in x and y, hull_contact.plate_half_width)
    half = (hull_contact.plate_half_width(system) if hull_contact.has_solid(system) else
            system.b + system.height + kinematics.slide_room(system))
    return [half, half, 0.5 * PLATE_THICKNESS]


def lateral_frictions(system: System, settings: Settings) -> tuple[float, float]:
    """(block's, plate's) lateral friction. Bullet's contact takes the product of the two
    bodies' (measured: √μ on each slides as μ, to 1e-6 of the rigid-plastic closed form), so a
    statue's friction μ (System.friction) is the block's with the plate's 1. Without one, both
    carry Settings.friction, as always: the contact's coefficient is then its square (1 at the
    default 1.0)."""
    if system.friction is None:
        return settings.friction, settings.friction
    return system.friction, 1.0




def build(client: BulletClient, system: System, settings: Settings, theta0: float = 0.0, *,
          transverse: bool = False) -> Scene:
    """Create the bodies in `client` (a fresh DIRECT client) and set the physics. `transverse`:
    the scene of two horizontal components (GroundMotion.transverse): on an isolated base the
    plate rides a second prismatic joint along y (joint 1) under the x joint's massless carriage,
    the same k and c applied to both (the linear isolator is isotropic; stepping.py); without it
    the scene is the one-component scene, unchanged. A fixed base and the free body are the same
    in both (the plate is already as wide as it is long)."""
    c = client
    c.setPhysicsEngineParameter(fixedTimeStep=settings.control_step, numSubSteps=settings.substeps,
                                numSolverIterations=settings.solver_iterations,
                                contactERP=settings.contact_erp)
    c.setGravity(0.0, 0.0, -system.gravity)
    plate = c.createCollisionShape(p.GEOM_BOX, halfExtents=_plate_half_extents(system))
    top = [0.0, 0.0, -0.5 * PLATE_THICKNESS]  # the plate's top face is z = 0
    puck_link, puck_hold = None, 0.0
    if system.fixed_base:
        base = c.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=plate, basePosition=top)
        plate_link = -1
    elif not transverse:
        base = c.createMultiBody(
            baseMass=0.0, baseCollisionShapeIndex=-1, basePosition=[0.0, 0.0, 0.0],
            linkMasses=[system.base_mass], linkCollisionShapeIndices=[plate], linkVisualShapeIndices=[-1],
            linkPositions=[top], linkOrientations=[[0, 0, 0, 1]], linkInertialFramePositions=[[0, 0, 0]],
            linkInertialFrameOrientations=[[0, 0, 0, 1]], linkParentIndices=[0],
            linkJointTypes=[p.JOINT_PRISMATIC], linkJointAxis=[[1, 0, 0]])
        plate_link = 0
        # the joint's default velocity motor would hold the base still
        c.setJointMotorControl2(base, 0, p.VELOCITY_CONTROL, targetVelocity=0.0, force=0.0)
    else:
        # two joints in series: a massless, shapeless carriage on x (link 0), the plate on y on it
        # (link 1): the plate's mass m_b moves along both (the x joint's articulated inertia is the
        # plate's, carried by the carriage), and u, u_y are the two joints' positions; a pendulum's
        # friction puck on the plate (link 2) where it has one (_pendulum_puck)
        puck = _pendulum_puck(c, system)
        links = [dict(mass=0.0, shape=-1, pos=[0, 0, 0], axis=[1, 0, 0]),
                 dict(mass=system.base_mass - (puck["mass"] if puck else 0.0), shape=plate, pos=top, axis=[0, 1, 0])]
        if puck:
            links.append(dict(mass=puck["mass"], shape=puck["shape"], pos=puck["pos"], axis=[0, 0, 1]))
        base = c.createMultiBody(
            baseMass=0.0, baseCollisionShapeIndex=-1, basePosition=[0.0, 0.0, 0.0],
            linkMasses=[x["mass"] for x in links], linkCollisionShapeIndices=[x["shape"] for x in links],
            linkVisualShapeIndices=[-1] * len(links), linkPositions=[x["pos"] for x in links],
            linkOrientations=[[0, 0, 0, 1]] * len(links), linkInertialFramePositions=[[0, 0, 0]] * len(links),
            linkInertialFrameOrientations=[[0, 0, 0, 1]] * len(links), linkParentIndices=list(range(len(links))),
            linkJointTypes=[p.JOINT_PRISMATIC] * len(links), linkJointAxis=[x["axis"] for x in links])
        plate_link = 1
        for joint in range(len(links)):  # the joints' default velocity motors would hold the base still
            c.setJointMotorControl2(base, joint, p.VELOCITY_CONTROL, targetVelocity=0.0, force=0.0)
        if puck:
            floor = c.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=c.createCollisionShape(
                p.GEOM_PLANE, planeNormal=[0, 0, 1]), basePosition=[0.0, 0.0, puck["floor_z"]])
            # (no activationState in this call: with it PyBullet left the link's friction at its default;
            # the base's sleeping is switched off with its plate, below)
            c.changeDynamics(base, 2, lateralFriction=puck["mu"], restitution=0.0)
            c.changeDynamics(floor, -1, lateralFriction=1.0, restitution=0.0)  # Bullet takes the product
            for link in (-1, 0, 1):  # the floor meets the puck alone (the plate is 4 cm above it)
                c.setCollisionFilterPair(base, floor, link, -1, 0)
            puck_link, puck_hold = 2, puck["hold"]
    frame = None
    if hull_contact.has_solid(system):  # its own shape in the block's place (statue.py)
        block, frame = statue.build(c, p, system, theta0)
    else:
        box = c.createCollisionShape(p.GEOM_BOX, halfExtents=[system.b, system.b, system.h])
        x, z = kinematics.tilted_centroid(system, theta0)
        pos, orn = [x, 0.0, z], p.getQuaternionFromEuler([0.0, theta0, 0.0])
        # a plain rigid body (maximal coordinates), not a one-link Featherstone multibody: the
        # same β to 0.01 points, ~10% less time per sub-step
        block = c.createMultiBody(baseMass=system.mass, baseCollisionShapeIndex=box, basePosition=pos,
                                  baseOrientation=orn, useMaximalCoordinates=True)
    for (body, link), mu in zip(((block, -1), (base, plate_link)), lateral_frictions(system, settings)):
        c.changeDynamics(body, link, lateralFriction=mu, restitution=settings.restitution,
                         linearDamping=settings.linear_damping, angularDamping=settings.angular_damping,
                         activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING,
                         contactProcessingThreshold=settings.contact_processing_threshold)
    return Scene(client=c, block=block, base=base, plate_link=plate_link, frame=frame, puck_link=puck_link,
                 puck_hold=puck_hold)


def _pendulum_puck(c, system) -> dict | None:
    """A pendulum's dry friction under a pair, the same in every direction (as MuJoCo's,
    mujoco_models/scene._pair_pendulum; its numbers analytic.isolator_parts.pendulum_puck): the
    base's motors hold each axis apart (a square, √2·μ·W along a diagonal), so the friction is a
    contact, a light puck under the plate on its own vertical joint, held down (Scene.puck_hold,
    a force on that joint, stepping.py) so that a floor pushes it up by W, on Bullet's friction
    cone. None on another isolator, or a pendulum without friction."""
    held = pendulum_puck(system)
    if held is None:
        return None
    pos = [0.0, 0.0, -0.5 * PLATE_THICKNESS - PUCK_HALF]  # below the plate, in the plate's frame
    return dict(mass=held.mass, shape=c.createCollisionShape(p.GEOM_BOX, halfExtents=[PUCK_HALF] * 3), pos=pos,
                floor_z=-PLATE_THICKNESS - 2 * PUCK_HALF, mu=held.friction, hold=held.hold)


def connect() -> BulletClient:
    """A private DIRECT client: runs in one process share no state."""
    with _c_output_silenced():
        return BulletClient(connection_mode=p.DIRECT)


_local = threading.local()


@contextmanager
def run_client():
    """This thread's own DIRECT client, emptied for a run, kept for the thread's next run
    (`resetSimulation` removes every body and restores the engine's parameters, gravity
    included, except the time step and sub-steps (checked with getPhysicsEngineParameters),
    which `build` sets for each run):
    connecting costs ~12 ms, a tenth of a run, resetting ~1.5 ms. Runs side by side on
    threads each have their own client, so they share no state; a run that raises leaves
    its client disconnected (the next run connects afresh)."""
    client = getattr(_local, "client", None)
    if client is None or not client.isConnected():
        client = _local.client = connect()
    else:
        client.resetSimulation()
    try:
        yield client
    except BaseException:
        _local.client = None
        client.disconnect()
        raise


# --- the scene as a file ----------------------------------------------------------

_SDF = """<?xml version="1.0"?>
<!-- isorock: block on {base_kind} base for PyBullet (p.loadSDF). Generated by isorock.bullet_models;
     simulate() builds the same bodies with createMultiBody and then applies
     {settings}
     linear/angular damping, friction and restitution with changeDynamics on both bodies, sleeping off.
     Friction: each collision carries its mu in SDF's <surface><friction><ode> (Bullet's contact takes the
     product of the two), but PyBullet's loadSDF does not read it (it keeps its default 0.5): after loading,
     call changeDynamics(body, link, lateralFriction={mu}, restitution={restitution}) on the block and
     changeDynamics(body, link, lateralFriction={plate_mu}, restitution={restitution}) on the plate.
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
        <collision name="block"><geometry><box><size>{B} {B} {H}</size></box></geometry>{block_surface}</collision>
      </link>
    </model>
  </world>
</sdf>
"""
_SURFACE = "<surface><friction><ode><mu>{mu}</mu><mu2>{mu}</mu2></ode></friction></surface>"
_PLATE = """      <link name="plate">
        <pose>0 0 {z} 0 0 0</pose>
        <inertial><mass>{mass}</mass>{inertia}</inertial>
        <collision name="plate"><geometry><box><size>{w} {w} {t}</size></box></geometry>{surface}</collision>
      </link>"""
# <dynamics><damping> is read by loadSDF and acts as the dashpot c (measured: a free plate's
# velocity decays as exp(-c t / m_b)); <spring_stiffness> is SDF's place for k but loadSDF
# ignores it, so the file states what a user must add
_ANCHOR = """      <link name="anchor">
        <inertial><mass>0</mass>{inertia}</inertial>
      </link>
{plate}
      <joint name="isolator" type="prismatic">
        <parent>anchor</parent><child>plate</child>
        <axis><xyz>1 0 0</xyz><limit><lower>-1e30</lower><upper>1e30</upper></limit>
          <dynamics><damping>{c}</damping><friction>0</friction><spring_stiffness>{k}</spring_stiffness><spring_reference>0</spring_reference></dynamics>
        </axis>
      </joint>"""
# PyBullet recomputes a box's inertia from its mass and size; the parser still wants the element
_NO_INERTIA = "<inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>"


def _element_text(parts, k, c) -> str:
    """The header's account of a non-linear isolator: the file holds its parallel spring and
    dashpot like the linear one's; the element is what simulate() adds (stepping.Element)."""
    common = (f"spring k = {k} N/m and dashpot c = {c} N s/m on the prismatic joint, as for the linear isolator "
              "(c in <dynamics><damping>, which loadSDF applies; k in <spring_stiffness>, which it ignores: apply "
              "-k u yourself each step)")
    words = [f"Isolator: {parts.kind.replace('-', ' ')} (docs/isolators.md): {common}"]
    if parts.base_friction > 0.0:
        words.append(f"dry friction F_s = {parts.base_friction} N: simulate() keeps the joint's velocity motor on "
                     "with target 0 and force F_s / substeps (PyBullet's impulse is force x the control step, "
                     "applied at each sub-step)")
    if parts.has_element:
        words.append(f"a Jenkins element, spring k_e = {parts.element_stiffness} N/m in series with a slider of "
                     f"slip force F_s = {parts.slip_force} N, which simulate() applies as a joint force each control "
                     "step (q = k_e (u - u_p), the slider u_p moving to u - sgn(q) F_s/k_e where |q| > F_s)")
    return ", and ".join(words) + "."


def scene_text(system: System, settings: Settings | None = None) -> str:
    """The scene as an SDF world (block upright at rest), loadable with `p.loadSDF`.
    SDF rather than URDF because a URDF holds one tree and the block is a second, free
    body. The numerical settings do not live in SDF; the header comment lists them."""
    if system.body is not None:  # the file below holds the block: a statue's would be a different body, unsaid
        raise InputError("body: PyBullet's model file holds the block H × B; a statue's hull (its vertices' "
                         "spheres on a free body, bullet_models/statue.py) is built in memory only")
    settings = settings or Settings()
    w = 2 * _plate_half_extents(system)[0]
    plate_mass = 0.0 if system.fixed_base else system.base_mass
    mu_block, mu_plate = lateral_frictions(system, settings)
    plate = _PLATE.format(z=-0.5 * PLATE_THICKNESS, mass=plate_mass, inertia=_NO_INERTIA, w=w, t=PLATE_THICKNESS,
                          surface=_SURFACE.format(mu=mu_plate))
    linear = system.isolator_kind == LINEAR  # a fixed base too
    parts = None if linear else isolator_parts(system)
    k, c = (system.stiffness, system.damping) if linear else (parts.stiffness, parts.damping)
    base_links = plate if system.fixed_base else _ANCHOR.format(inertia=_NO_INERTIA, plate=plate, c=c, k=k)
    isolator = (_element_text(parts, k, c) if parts is not None else
                "Isolator: none, the plate is static (fixed base)." if system.fixed_base else
                f"Isolator: spring k = {system.stiffness} N/m and dashpot c = {system.damping} N s/m on the "
                "prismatic joint. simulate() switches the joint motor off (setJointMotorControl2 VELOCITY_CONTROL, "
                "force 0) and applies -(k u + c u_dot) as a joint force every control step. In this file c is the "
                "joint's <dynamics><damping>, which loadSDF applies; k is in <spring_stiffness>, which loadSDF "
                "ignores: after loading, switch the motor off and apply -k u yourself each step (not c u_dot too, "
                "or the damping counts twice).")
    listed = ", ".join(f"{f.name} = {getattr(settings, f.name)!r}" for f in fields(settings))
    return _SDF.format(base_kind="a fixed" if system.fixed_base else "an isolated", settings=listed,
                       isolator=isolator, base_links=base_links, h=system.h, m=system.mass,
                       inertia=_NO_INERTIA, B=system.width, H=system.height,
                       block_surface=_SURFACE.format(mu=mu_block), mu=mu_block, plate_mu=mu_plate,
                       restitution=settings.restitution)
