"""A statue's own shape in DART's block scene (issue 36; docs/statues.md, "DART on the statue's
hull"): the counterpart of drake_models/statue.py and bullet_models/statue.py, on the same
engine-neutral geometry (analytic.hull_contact).

The statue takes the block's place on the same plate, isolator joint and ground forcing as the
block (dart_models/__init__.py), on a free joint (it may rock, wobble, twist and slide in 3-D). Its
body frame sits on the centre of mass with the statue's own axes (x the shaking direction, z up at
rest), so the block scene's θ (the lean of z towards +x) is read from it unchanged; DART takes the
full inertia tensor about the centre of mass in that frame (BodyNode.setMomentOfInertia with the
products), so no principal frame is needed, as it is in Bullet.

Contact: a small sphere (radius hull_contact.VERTEX_RADIUS_SHARE·R, as PyBullet's) on every vertex of the hull, its bottom on
the vertex at rest, each its own shape node: a convex polyhedron meets a flat plate at its
vertices first, and a sphere against the plate's box is one exact contact point in DART's
collision (FCL), where a mesh's contact reports a few wandering points (Drake's and Bullet's did:
docs/statues.md). The block scene's step, restitution 0 and friction apply unchanged.
"""
from __future__ import annotations

import math

import numpy as np

from ..analytic import hull_contact, kinematics
from ..analytic.system import System

def plate_size(system: System) -> float:
    """Side (m) of the square plate: past the hull and where an overturned statue lands."""
    return 2.0 * hull_contact.plate_half_width(system)


def build(dart, body, free, system: System, theta0: float, friction: float) -> None:
    """Give the free body `body` (on joint `free`) the statue: its mass and inertia tensor, a
    sphere on each hull vertex, tilted by θ0 about the edge it rests on."""
    r = hull_contact.vertex_radius(system)
    m = float(system.mass)
    body.setMass(m)
    inertia = np.asarray(system.body.solid.inertia, dtype=float)  # about the centre of mass, the statue's axes
    # DART's Inertia takes the tensor's own entries (Ixy = I[0, 1], not its negative): checked in
    # tests/test_statue_dart.py against body.getInertia().getMoment()
    body.setMomentOfInertia(inertia[0, 0], inertia[1, 1], inertia[2, 2], inertia[0, 1], inertia[0, 2], inertia[1, 2])
    for centre in hull_contact.vertex_sphere_centres(system, r):
        node = body.createShapeNode(dart.dynamics.SphereShape(r))
        node.setRelativeTranslation(np.asarray(centre, dtype=float))
        node.createCollisionAspect()
        dynamics = node.createDynamicsAspect()
        dynamics.setRestitutionCoeff(0.0)
        dynamics.setFrictionCoeff(float(friction))
    x, z = hull_contact.tilted_start(system, float(theta0), r)
    c, s = math.cos(theta0), math.sin(theta0)
    pose = dart.math.Isometry3()
    pose.set_rotation(np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]))  # about y: z leans towards +x
    pose.set_translation([x, 0.0, z])
    free.setPositions(dart.dynamics.FreeJoint.convertToPositions(pose))


def row(body) -> tuple[float, float, float, float, float]:
    """(x, y, z of the centre of mass, roll, yaw) of the body's world pose: the wobble out of the
    plane, as kinematics.tilts_from_quaternion reads it (roll about x, yaw about z)."""
    tf = body.getWorldTransform()
    R, p = tf.rotation(), tf.translation()
    roll = math.atan2(-R[1, 2], math.hypot(R[0, 2], R[2, 2]))
    yaw = math.atan2(R[1, 0], R[0, 0])
    return float(p[0]), float(p[1]), float(p[2]), roll, yaw


def extras(system: System, theta, u, more: np.ndarray) -> dict:
    """Every contact engine's extras (kinematics.contact_extras) with the wobble out of the plane
    (|y| in m, roll and yaw in rad), from the rows of `row`."""
    return kinematics.contact_extras(system, x_centroid=more[:, 0], z_centroid=more[:, 2], theta=theta, u=u,
                                     out_of_plane=np.max(np.abs(more[:, [1, 3, 4]]), axis=1))
