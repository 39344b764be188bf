"""A statue's own shape in PyBullet's block scene (issue 36; docs/statues.md, "PyBullet on the
statue's hull"): the counterpart of drake_models/statue.py, on the same engine-neutral geometry
(analytic.hull_contact).

The statue takes the block's place on the same plate, isolator joint and ground forcing as the
block (scene.py, stepping.py), as a free rigid body (maximal coordinates, as the block), so that
it may rock, wobble, twist and slide in 3-D. Its mass and full inertia tensor are the Solid's:
Bullet takes a diagonal inertia in the body's inertial frame, so that frame is put on the
tensor's principal axes (hull_contact.principal_axes) and its moments are set with
changeDynamics(localInertiaDiagonal=…) (Bullet would otherwise take the compound shape's
bounding-box inertia).

Contact: a small sphere (radius hull_contact.VERTEX_RADIUS_SHARE·R) on every vertex of the hull, its bottom on
the vertex at rest, as one compound collision shape. A sphere against the plate's box is Bullet's
own sphere–box algorithm, one exact contact point each; the statue's hull as a convex mesh slid
(docs/statues.md: Bullet's convex–box manifold keeps up to four wandering points and the pivot
did not hold, β 12–31% off). The block scene's ERP, friction, restitution and steps apply
unchanged (Settings.for_system scales the step with the statue's rocking rate).

Bullet reports and resets a body's pose by its inertial (centre-of-mass) frame, here turned onto
the principal axes: `link_orientation` turns that back to the statue's own frame (x the shaking
direction, z up at rest), in which the block scene's θ (the lean of z towards +x) is read.
"""
from __future__ import annotations

import numpy as np

from ..analytic import hull_contact
from ..analytic.system import System

def _quaternion(rotation: np.ndarray) -> list[float]:
    """(x, y, z, w) of a proper rotation matrix."""
    m = rotation
    w = 0.5 * np.sqrt(max(0.0, 1.0 + m[0, 0] + m[1, 1] + m[2, 2]))
    x = 0.5 * np.sqrt(max(0.0, 1.0 + m[0, 0] - m[1, 1] - m[2, 2]))
    y = 0.5 * np.sqrt(max(0.0, 1.0 - m[0, 0] + m[1, 1] - m[2, 2]))
    z = 0.5 * np.sqrt(max(0.0, 1.0 - m[0, 0] - m[1, 1] + m[2, 2]))
    x = np.copysign(x, m[2, 1] - m[1, 2])
    y = np.copysign(y, m[0, 2] - m[2, 0])
    z = np.copysign(z, m[1, 0] - m[0, 1])
    return [float(x), float(y), float(z), float(w)]


def multiply(a, b):
    """Quaternion product a ⊗ b, (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def build(client, p, system: System, theta0: float):
    """Create the statue in `client` tilted by θ0 about the edge it rests on: (body id, the
    inertial frame's orientation in the statue's frame, (x, y, z, w))."""
    r = hull_contact.vertex_radius(system)
    moments, axes = hull_contact.principal_axes(system)
    frame = _quaternion(axes)
    centres = hull_contact.vertex_sphere_centres(system, r)
    n = len(centres)
    shape = client.createCollisionShapeArray([p.GEOM_SPHERE] * n, radii=[r] * n,
                                             collisionFramePositions=centres.tolist())
    x, z = hull_contact.tilted_start(system, theta0, r)
    orn = client.getQuaternionFromEuler([0.0, theta0, 0.0])
    body = client.createMultiBody(baseMass=system.mass, baseCollisionShapeIndex=shape, basePosition=[x, 0.0, z],
                                  baseOrientation=orn, baseInertialFramePosition=[0.0, 0.0, 0.0],
                                  baseInertialFrameOrientation=frame, useMaximalCoordinates=True)
    # the mass given again: PyBullet's changeDynamics on a maximal-coordinates body sets the mass
    # props together, and without it the body was left with mass 0 (measured)
    client.changeDynamics(body, -1, mass=system.mass, localInertiaDiagonal=[float(v) for v in moments])
    return body, tuple(frame)


def link_orientation(orn, frame):
    """The statue's own orientation from Bullet's inertial-frame one: orn ⊗ frame⁻¹."""
    fx, fy, fz, fw = frame
    return multiply(orn, (-fx, -fy, -fz, fw))


def inertial_orientation(orn, frame):
    """Bullet's inertial-frame orientation from the statue's own: orn ⊗ frame."""
    return multiply(orn, frame)
