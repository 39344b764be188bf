"""A statue's own shape as a contact engine carries it, engine-neutral (issue 36;
docs/statues.md, "Drake on the statue's hull" and "PyBullet on the statue's hull").

A convex polyhedron meets a flat plate at its vertices first, so a small sphere on every vertex
of the hull (its bottom on the vertex at rest) carries the hull's contact with the base plate as
exactly as the engine's point contact allows, where an engine's own convex-mesh contact does not
(Drake's reports one point per pair, PyBullet's slid: docs/statues.md). What is neutral here is the
geometry: which systems carry a shape, where the spheres sit in the body frame (about the centre
of mass, the world's axes at rest), how wide the plate must be, where the centre of mass starts
when tilted onto its pivot's sphere, and the body's principal axes (for engines that take a
diagonal inertia in a frame of their own). Each engine builds its bodies from these
(drake_models/statue.py, bullet_models/statue.py).
"""
from __future__ import annotations

import math

import numpy as np

from . import kinematics
from .errors import InputError
from .system import System

#: radius of the sphere on each vertex, in units of the statue's R (of the edge it tips first), for
#: the engines whose own contact sets no radius (PyBullet, DART; Drake's is Settings.corner_radius):
#: small, so that the pivot, which rolls by r·θ on the sphere, stays the vertex (at θ = α of the
#: obelisk, 1e-3·R·0.25 = 2.5e-4·R); large enough for Bullet's sphere–box contact at 0.5× (0.1 mm)
VERTEX_RADIUS_SHARE = 1e-3


def has_solid(system: System) -> bool:
    """True where the system is a statue of its own shape (System.body.solid)."""
    return getattr(system.body, "solid", None) is not None


def check_shape(system: System, engine: str) -> None:
    """A statue an engine that builds hulls does not build, in one line: a PlanarBody given by its
    numbers alone (no mesh, no Solid). Its scene is the symmetric block's; MuJoCo builds that body
    as the box on its two edges."""
    if system.body is not None and not has_solid(system):
        raise InputError(f"body: {engine} carries a statue's own shape (a mesh's convex hull, Solid) on a free body; "
                         f"a PlanarBody given by its numbers alone is not built for {engine} (MuJoCo builds it)")


def vertex_radius(system: System) -> float:
    """The vertex spheres' radius (m): VERTEX_RADIUS_SHARE·R."""
    return VERTEX_RADIUS_SHARE * system.R


def vertex_sphere_centres(system: System, radius: float) -> np.ndarray:
    """Centres (body frame, about the centre of mass) of spheres of `radius` on the hull's
    vertices: r above each vertex, so that at rest the bottom of each sphere is the vertex and
    the levers b₊, b₋ and the height h are the hull's own (not shrunk as an inscribed sphere's)."""
    v = np.asarray(system.body.solid.vertices, dtype=float)
    return v + np.array([0.0, 0.0, radius])


def plate_half_width(system: System) -> float:
    """Half-width (m) of a square plate that reaches past the hull in x and y, and past where an
    overturned statue lands (its height), plus the room a statue that may slide walks in."""
    v = np.asarray(system.body.solid.vertices, dtype=float)
    return float(np.max(np.abs(v[:, :2]))) + system.height + kinematics.slide_room(system)


def tilted_start(system: System, theta0: float, radius: float) -> tuple[float, float]:
    """(x, z) of the centre of mass at rest tilted by θ0 about the edge it rests on
    (kinematics.tilted_centroid), lifted by r(1 − cos θ0) so that the pivot's sphere, turned with
    the body, still just touches the plate."""
    x, z = kinematics.tilted_centroid(system, theta0)
    return x, z + radius * (1.0 - math.cos(theta0))


def principal_axes(system: System) -> tuple[np.ndarray, np.ndarray]:
    """(principal moments, R): the inertia tensor I = R·diag(moments)·Rᵀ, R a proper rotation
    whose columns are the principal axes in the body frame."""
    moments, axes = np.linalg.eigh(np.asarray(system.body.solid.inertia, dtype=float))
    if np.linalg.det(axes) < 0:  # eigh may hand back a reflection: a quaternion needs a rotation
        axes[:, 2] = -axes[:, 2]
    return moments, axes
