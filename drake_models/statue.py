"""A statue's own shape in Drake's block scene (issue 36; docs/statues.md, "The contact engines
on the base and isolator"): the counterpart of mujoco_models.scene._statue.

A `PlanarBody` read from a mesh keeps its `Solid` (analytic.system.Solid: the convex hull's
vertices about the centre of mass and the inertia tensor). Here it takes the block's place on
the same plate, isolator joint and ground forces as the block (scene.py), as a free body (a
link with no joint: Drake gives it a quaternion floating joint), so that it may rock, wobble,
twist and slide in 3-D. The planar joint cannot carry it: a hull of two different edges need
not stay in one plane.

Contact (Settings.hull):
- "vertices" (the default): a small sphere of radius `corner_radius` at every vertex of the
  hull, its bottom on the vertex (centre r above it in the body frame). A convex polyhedron
  meets a flat plate at its vertices first, so these are exactly the points that can touch;
  each is one Hunt–Crossley point contact, as the block's corner spheres are (the same
  stiffness, dissipation and friction, scaled with the statue by Settings.for_system). Unlike
  the block's inscribed spheres they do not shrink the levers: the sphere's bottom is the
  vertex itself at rest.
- "convex": the hull as Drake's Convex shape (an OBJ written beside the scene) in point contact
  with the plate's box. Drake's point contact reports ONE point per pair of geometries (the
  deepest penetration), so a hull standing on a face is carried on a single wandering point:
  kept to show that (docs/statues.md), not to be used.

What it returns is the block scene's history: θ the lean of the body's z axis towards +x
(kinematics.tilts_from_quaternion, as MuJoCo's free joint), θ̇ the world angular velocity about
+y, and the extras of every contact engine (kinematics.contact_extras) with the wobble out of
the plane (|y|, roll, yaw). The block of a run of two horizontal components is a free body too
(scene.py, its frame the world's axes at the centroid): `Indices`, `tilt` and `raw_history` read
it as they read a statue, and a pair's history adds what the two-component measures read
(kinematics.pair_extras).
"""
from __future__ import annotations

import math

import numpy as np

from ..analytic import hull_contact, kinematics
from ..analytic.system import System
from ..analytic.trajectory import RawHistory

from .mesh_scene import _hull_obj  # the shake-table scene's writer: one for both

#: the OBJ the "convex" hull's SDF names, written beside it by `simulate`
HULL_FILE = "statue_hull.obj"
#: the SDF header's account of the statue's coordinates (scene._SDF)
COORDS = """The statue (link "block") has no joint: Drake's quaternion floating
     joint, its position the centre of mass's; H and B above are the box of its two edges.
     Tilt it by theta0 about world +y about the edge it rests on to start free rocking."""


def hull_obj(system: System) -> str:
    """The hull as OBJ text (faces wound outwards), for Drake's Convex."""
    return _hull_obj(np.asarray(system.body.solid.vertices, dtype=float))


def link(system: System, settings, props: str) -> str:
    """The SDFormat <link> of the statue: at rest its centre of mass h above the plate's top, the
    link frame the world's (x the shaking direction, z up), its mass and full inertia tensor, its
    contact geometry by Settings.hull."""
    I = system.body.solid.inertia
    r = settings.corner_radius
    if settings.hull == "convex":
        collisions = (f'      <collision name="hull">\n        <geometry><mesh><uri>{HULL_FILE}</uri>'
                      f"<drake:declare_convex/></mesh></geometry>\n        <drake:proximity_properties>\n{props}\n"
                      "        </drake:proximity_properties>\n      </collision>")
    else:
        collisions = "\n".join(
            f'      <collision name="vertex_{i}">\n        <pose>{x!r} {y!r} {z!r} 0 0 0</pose>\n'
            f"        <geometry><sphere><radius>{r!r}</radius></sphere></geometry>\n"
            f"        <drake:proximity_properties>\n{props}\n        </drake:proximity_properties>\n      </collision>"
            for i, (x, y, z) in enumerate(hull_contact.vertex_sphere_centres(system, r).tolist()))
    return f"""    <!-- the statue's own shape: its convex hull's {len(system.body.solid.vertices)} vertices, contact "{settings.hull}";
         no joint: a free body (Drake's quaternion floating joint). Link frame = world axes at the
         centre of mass; to start tilted, turn it by theta0 about world +y about the edge it rests on -->
    <link name="block">
      <pose>0 0 {system.h!r} 0 0 0</pose>
      <inertial><mass>{system.mass!r}</mass>
        <inertia><ixx>{I[0][0]!r}</ixx><iyy>{I[1][1]!r}</iyy><izz>{I[2][2]!r}</izz><ixy>{I[0][1]!r}</ixy><ixz>{I[0][2]!r}</ixz><iyz>{I[1][2]!r}</iyz></inertia>
      </inertial>
{collisions}
    </link>"""


class Indices:
    """Where the free body's quantities sit in the plant's state: positions (w, x, y, z) of the
    quaternion then the centre of mass's world position; velocities ω then v, both in the world."""

    def __init__(self, plant):
        body = plant.GetBodyByName("block")
        q0, v0 = body.floating_positions_start(), body.floating_velocities_start_in_v()
        self.quat = slice(q0, q0 + 4)
        self.xq, self.yq, self.zq = q0 + 4, q0 + 5, q0 + 6
        self.wy = v0 + 1  # ω about world +y; these index v (the state's rows nq + i)
        self.xv, self.yv, self.zv = v0 + 3, v0 + 4, v0 + 5


def tilt(ix: Indices, nq: int, data) -> tuple[np.ndarray, np.ndarray]:
    """(θ, θ̇) of logged state columns: the lean towards +x, and ω_y."""
    w, x, y, z = np.asarray(data[ix.quat])
    n = np.sqrt(w * w + x * x + y * y + z * z)
    n = np.where(n > 0, n, 1.0)
    theta, _, _ = kinematics.tilts_from_quaternion(w / n, x / n, y / n, z / n)
    return theta, np.asarray(data[nq + ix.wy])


def initial_positions(plant, ix: Indices, nq: int, system: System, settings, theta0: float) -> np.ndarray:
    """At rest tilted by θ0 about the edge it rests on (kinematics.tilted_centroid), lifted by
    r(1 − cos θ0) so that the pivot's sphere, turned with the body, still just touches the plate."""
    q = np.zeros(nq)
    q[ix.quat] = (math.cos(theta0 / 2), 0.0, math.sin(theta0 / 2), 0.0)
    x, z = hull_contact.tilted_start(system, theta0, settings.corner_radius)
    q[ix.xq], q[ix.yq], q[ix.zq] = x, 0.0, z
    return q


def raw_history(built, system, motion, settings, times, data, runtime, status, message, stop_reason,
                engine: str) -> RawHistory:
    """The raw history of the logged states, up to the last finite sample, in the block scene's
    vocabulary (kinematics.contact_extras, with the wobble out of the plane); with two horizontal
    components the 3-D history too (kinematics.pair_extras: u_y the base's y joint, zeros on a
    fixed base)."""
    ix = built.statue
    times = np.asarray(times, dtype=float)
    data = np.asarray(data, dtype=float)
    finite = np.all(np.isfinite(data), axis=0)
    keep = int(np.argmin(finite)) if not finite.all() else data.shape[1]
    times, data = times[:keep], data[:, :keep]
    theta, theta_dot = tilt(ix, built.nq, data)
    w, x, y, z = data[ix.quat] / np.linalg.norm(data[ix.quat], axis=0)
    _, roll, yaw = kinematics.tilts_from_quaternion(w, x, y, z)
    v = data[built.nq:]
    if built.uq is None:
        u = u_dot = np.zeros(times.size)
    else:
        u, u_dot = data[built.uq], v[built.uv]
    x_c, z_c = data[ix.xq], data[ix.zq]
    extras = kinematics.contact_extras(system, x_centroid=x_c, z_centroid=z_c, theta=theta, u=u,
                                       out_of_plane=np.maximum.reduce([np.abs(data[ix.yq]), np.abs(roll), np.abs(yaw)]))
    if motion.transverse is not None:  # the 3-D history the two-component measures read (validate.core.biaxial)
        u_y = np.zeros(times.size) if built.uyq is None else data[built.uyq]
        kinematics.pair_extras(extras, orientation=np.stack([w, x, y, z], axis=1), y_centroid=data[ix.yq], u_y=u_y)
    slide, slide_dot = kinematics.slide_history(system, motion, x_centroid=x_c, x_centroid_dot=v[ix.xv],
                                                theta=theta, theta_dot=theta_dot, u=u, u_dot=u_dot)
    return RawHistory(engine=engine, system=system, t=times, u=u, u_dot=u_dot, theta=theta, theta_dot=theta_dot,
                      status=status, message=message, runtime_s=runtime, extras=extras, stop_reason=stop_reason,
                      slide=slide, slide_dot=slide_dot)
