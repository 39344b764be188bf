"""The block on its base in DART (dartpy, the optional `dart` extra; issue 37): a fourth contact
engine, DART's own collision (FCL box–box) and its constraint solver (an LCP of the contacts,
restitution 0, Coulomb friction), at a fixed step.

The scene: the block a box H × D × B on a free joint (it may rock, slide, twist and lift off in
3-D), resting on a base plate: welded to the world on a fixed base, or on a prismatic joint along
x with the isolator's spring k and dashpot c (DART's joint spring and damping). The ground motion
enters as the uniform inertial field of the base's translating frame: the gravity is set to
(−ẍg(t), 0, −g) before each step (exact for a translating frame: the bullet_models hull scene
does the same), so u is the base's joint position relative to the ground.

What it carries: the linear isolator, a statue that cannot slip on its base (its friction is
DART's high default, Settings.friction), horizontal ground motion, a statue's own shape in the
block's place (statue.py; Capabilities below: anything else is refused in one line). Measured in docs/dart.md; its limits in validate/core/tolerances.py.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isorock.analytic import hull_contact
from isorock.analytic.engine_protocol import DEFAULT_IMPACT_THRESHOLD, Capabilities, EngineSpec, Preset, run_inputs
from isorock.analytic.errors import InputError, import_extra
from isorock.analytic.status import Status
from isorock.analytic.trajectory import RawHistory

from . import statue

#: the block's depth (m) over its width: out of the rocking plane, only its stability matters
DEPTH_RATIO = 1.0
#: the base plate's size against the block's width, and its thickness (m)
PLATE_WIDTH_RATIO, PLATE_THICKNESS = 6.0, 0.1
#: a row of the history every this many seconds (at most), as the other contact engines store
SAMPLE_DT = 1e-3
#: a statue's own shape (statue.py) is carried: Capabilities.two_edges says so, judged in
#: docs/statues.md ("DART on the statue's hull": the bust and the obelisk within MuJoCo's statue rows)
TWO_EDGES = True


@dataclass(frozen=True)
class Settings:
    """timestep (s): DART's fixed step; friction: the block's Coulomb coefficient on the plate
    (high: the model assumes no sliding)."""

    timestep: float = 1e-4
    friction: float = 1.0

    def __post_init__(self):
        if not (isinstance(self.timestep, (int, float)) and 1e-6 <= self.timestep <= 1e-2):
            raise InputError(f"timestep = {self.timestep!r}: must be a step from 1e-6 to 0.01 s")
        if not (isinstance(self.friction, (int, float)) and 0 < self.friction <= 10 and math.isfinite(self.friction)):
            raise InputError(f"friction = {self.friction!r}: must be a friction coefficient in (0, 10]")


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


def simulate(system, motion=None, *, settings=None, duration=None, theta0=0.0, progress=None) -> RawHistory:
    dart = import_extra("dartpy", "dart", "the engine 'dart'")
    settings = settings or Settings()
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD, settings=settings,
                                  two_edges=TWO_EDGES)  # a statue without its shape: hull_contact.check_shape, below
    if system.friction is not None or motion.vertical is not None:  # said again for a direct caller
        raise InputError("system: engine 'dart' carries a statue that cannot slip, on level ground")
    hull_contact.check_shape(system, "DART")
    hull = hull_contact.has_solid(system)
    h, b = system.h, system.b
    dt = float(settings.timestep)
    world = dart.simulation.World()
    world.setTimeStep(dt)
    world.setGravity([0.0, 0.0, -system.gravity])

    base = dart.dynamics.Skeleton("base")
    if system.fixed_base:
        joint, plate = base.createWeldJointAndBodyNodePair()
    else:
        joint, plate = base.createPrismaticJointAndBodyNodePair()
        joint.setAxis([1.0, 0.0, 0.0])
        joint.setSpringStiffness(0, float(system.stiffness))
        joint.setDampingCoefficient(0, float(system.damping))
        plate.setMass(float(system.base_mass))
    below = dart.math.Isometry3()
    below.set_translation([0.0, 0.0, -0.5 * PLATE_THICKNESS])
    joint.setTransformFromParentBodyNode(below)  # the plate's top at z = 0
    # a statue's plate is square, past its hull and where it lands overturned (hull_contact)
    side = statue.plate_size(system) if hull else None
    # the plate's friction is the body's: DART takes the smaller of the two shapes' coefficients,
    # so the plate's default 1 held Settings.friction to 1 at most (the default, 1, is unchanged)
    _box(plate, (side, side, PLATE_THICKNESS) if hull else
         (PLATE_WIDTH_RATIO * system.width, DEPTH_RATIO * system.width * 2, PLATE_THICKNESS),
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

    every = max(1, int(round(SAMPLE_DT / dt)))
    n = int(math.ceil(duration / dt))
    rows = np.empty((n // every + 2, 5))
    # a statue's wobble out of the plane and its centre of mass, for the contact engines' extras
    more = np.empty((rows.shape[0], 5)) if hull else None
    k = 0
    status, message, start = Status.COMPLETED, "reached the end time", time.perf_counter()

    def row(t):
        Rw = body.getWorldTransform().rotation()
        theta = math.atan2(Rw[0, 2], Rw[2, 2])
        omega = np.asarray(body.getAngularVelocity())  # world frame: its y is θ̇
        u, ud = (0.0, 0.0) if system.fixed_base else (float(joint.getPosition(0)), float(joint.getVelocity(0)))
        return t, u, ud, theta, float(omega[1])

    rows[k] = row(0.0)
    if hull:
        more[k] = statue.row(body)
    k += 1
    for i in range(1, n + 1):
        t = i * dt
        world.setGravity([-float(motion.at(t - dt)), 0.0, -system.gravity])
        world.step()
        if i % every == 0 or i == n:
            rows[k] = row(min(t, duration))
            if hull:
                more[k] = statue.row(body)
            if not np.all(np.isfinite(rows[k])):
                status, message = Status.FAILED, f"non-finite state at t = {t:.4g} s"
                break
            k += 1
            if abs(rows[k - 1, 3]) >= 0.5 * math.pi:
                break  # on its side: measure() judges the fall from the history
        if progress is not None and i % 20000 == 0:
            progress(t, duration)
    rows = rows[:k]
    extras = statue.extras(system, rows[:, 3], rows[:, 1], more[:k]) if hull else {}
    return RawHistory(engine="dart", system=system, t=rows[:, 0], u=rows[:, 1], u_dot=rows[:, 2], theta=rows[:, 3],
                      theta_dot=rows[:, 4], status=status, message=message, runtime_s=time.perf_counter() - start,
                      extras=extras)


def ladder(quick: bool):
    """Work-precision ladder (label, Settings), cheapest first: DART's fixed step."""
    steps = (1e-3, 3e-4, 1e-4) if quick else (1e-3, 3e-4, 1e-4, 3e-5)
    return [(f"dt={h:g}", Settings(timestep=h)) for h in steps]


ENGINE = EngineSpec(
    name="dart", label="DART", settings_type=Settings, simulate=simulate, ladder=ladder,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False, campaigns=False,
                              isolators=("linear",), kinetic_friction=False, statue_friction=False, vertical=False,
                              two_edges=TWO_EDGES),
    presets={"default": Preset("a 0.1 ms step, restitution 0, friction 1 (docs/dart.md)", Settings),
             "coarse": Preset("a 1 ms step: what DART's step costs in β (docs/dart.md)",
                              lambda: Settings(timestep=1e-3))})

__all__ = ["ENGINE", "Settings", "simulate", "ladder"]
