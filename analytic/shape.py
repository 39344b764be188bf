"""A statue's shape, from its mesh: its mass properties, the pose it rests in on a flat
plinth, its footprint, and for a shaking direction (azimuth) the two tipping edges the planar
rocking model needs (α, R, the inertia about each edge), and where it first tips (issue 36).
One home: `isorock statue`, `--statue FILE` and the shake-table study (experiments.specimen)
all read shapes here.

The resting pose is found, not assumed: a rigid body on a flat table rests on a face of its
convex hull (the table touches nothing inside the hull), and it can rest on a face only when
the centre of mass projects, along the face's normal, inside that face. Of the stable faces,
the pose taken is the one whose outward normal is nearest the table's downward normal after
the given placement (a rotation of the mesh; a statue's own file stands it up: z up).

Rocking about the footprint's forward (+x) or backward (−x) extreme edge, the planar
equation of motion of any rigid body depends on α (the angle from the vertical of the line
from the edge to the centre of mass), and p² = m g R / I_O (I_O its moment of inertia about
the edge). A rectangular block with the same α and p (so R_eq = 3g/(4p²), h = R_eq cos α,
b = R_eq sin α) rocks by the same equation between impacts; its impact law (Housner's, from
the rectangle's geometry) is the model's assumption, not the statue's.

Meshes are read by trimesh (STL, OBJ, PLY, …; the `statue` extra), in the length unit the
caller names (a mesh file states none that this reader trusts: never guessed); a mesh that is
not closed and consistently wound (no volume to weigh) is refused in one line.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.spatial import ConvexHull

from .errors import InputError, import_extra, python_number
from .fast import simulate_batch
from .system import PlanarBody, STANDARD_GRAVITY, System

#: Hull faces whose planes agree to this (unit normal, and offset in m) are one face.
FACE_TOLERANCE = 1e-6
#: a mesh's length unit → metres (what `unit` may name)
UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}


def mass_properties(v: np.ndarray, f: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """(volume, centroid, inertia tensor about the centroid per unit density) of a closed,
    consistently oriented triangle mesh, by signed tetrahedra from the origin (exact for a
    polyhedron)."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol6 = np.einsum("ij,ij->i", a, np.cross(b, c))
    volume = vol6.sum() / 6.0
    if volume < 0:  # inward-oriented mesh
        vol6, volume = -vol6, -volume
    com = (vol6[:, None] * (a + b + c)).sum(0) / (24.0 * volume)
    # second moments ∫ x_i x_j dV of each tetrahedron (0, a, b, c): vol/20 (Σ p_i p_j + (Σp)_i (Σp)_j)
    s = a + b + c
    second = (np.einsum("k,ki,kj->ij", vol6, a, a) + np.einsum("k,ki,kj->ij", vol6, b, b)
              + np.einsum("k,ki,kj->ij", vol6, c, c) + np.einsum("k,ki,kj->ij", vol6, s, s)) / 120.0
    second -= volume * np.outer(com, com)
    inertia = np.trace(second) * np.eye(3) - second
    return float(volume), com, inertia


def rotation_between(u, v) -> np.ndarray:
    """The smallest rotation taking unit vector u to unit vector v (Rodrigues)."""
    u, v = np.asarray(u, float), np.asarray(v, float)
    axis = np.cross(u, v)
    s, c = np.linalg.norm(axis), float(np.dot(u, v))
    if s < 1e-12:
        if c > 0:
            return np.eye(3)
        perp = np.cross(u, [1.0, 0, 0] if abs(u[0]) < 0.9 else [0, 1.0, 0])
        perp /= np.linalg.norm(perp)
        return 2 * np.outer(perp, perp) - np.eye(3)
    k = axis / s
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * K + (1 - c) * K @ K


def hull_faces(points: np.ndarray) -> list[tuple[np.ndarray, float, np.ndarray]]:
    """The convex hull's faces, coplanar triangles merged: (outward unit normal n, offset d
    with n·x + d = 0 on the face, indices of the face's points)."""
    hull = ConvexHull(points)
    # one key per plane, at FACE_TOLERANCE: coplanar triangles share it
    keys = np.round(hull.equations / FACE_TOLERANCE).astype(np.int64)
    _, group = np.unique(keys, axis=0, return_inverse=True)
    out = []
    for g in range(group.max() + 1):
        rows = np.flatnonzero(group.ravel() == g)
        eq = hull.equations[rows[0]]
        out.append((eq[:3], float(eq[3]), np.unique(hull.simplices[rows])))
    return out


def _inside_polygon(point2: np.ndarray, poly2: np.ndarray) -> float:
    """Signed distance of a 2-D point inside the convex hull of poly2 (> 0 inside)."""
    h = ConvexHull(poly2)
    return float(-(h.equations[:, :2] @ point2 + h.equations[:, 2]).max())


def _plane_basis(n):
    e1 = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(n, e1)


def stable_faces(points: np.ndarray, com: np.ndarray) -> list[dict]:
    """Every hull face the body can rest on: the centre of mass projects inside it. Each
    with its outward normal, the margin (distance of the projection from the face's border,
    m) and the height of the centre of mass above it."""
    out = []
    for n, d, idx in hull_faces(points):
        if idx.size < 3:
            continue
        e1, e2 = _plane_basis(n)
        p = points[idx]
        poly = np.column_stack((p @ e1, p @ e2))
        try:
            margin = _inside_polygon(np.array([com @ e1, com @ e2]), poly)
        except Exception:  # noqa: BLE001 — a degenerate (sliver) face: no area to stand on
            continue
        if margin > 0:
            out.append(dict(normal=n, offset=d, indices=idx, margin=margin, height=-(n @ com + d)))
    return out


@dataclass
class RestingBody:
    """A rigid body at rest on a flat table: its hull vertices in the table frame (z up, the
    table at z = 0, shaking along x), mass, centre of mass and inertia about it (table frame)."""
    mass: float
    vertices: np.ndarray  # hull vertices, table frame, m
    com: np.ndarray
    inertia: np.ndarray
    footprint: np.ndarray  # the resting face's vertices, table frame (z = 0)
    checks: dict = field(default_factory=dict)

    def along(self, azimuth: float) -> "RestingBody":
        """The same body with the shaking direction at `azimuth` (rad, from the table's x
        towards y) turned onto x: its vertices, footprint, centre of mass and inertia
        rotated by −azimuth about the vertical."""
        c, s = math.cos(azimuth), math.sin(azimuth)
        R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
        return replace(self, vertices=self.vertices @ R.T, footprint=self.footprint @ R.T, com=R @ self.com,
                       inertia=R @ self.inertia @ R.T)

    def direction(self, sign: int) -> dict:
        """Rocking about the footprint's extreme edge towards +x (sign 1) or −x (sign −1):
        the edge's half-base b, the height h of the centre of mass, α, R, p and the
        equivalent block's R_eq (same α and p)."""
        x = self.footprint[:, 0]
        b = (x.max() - self.com[0]) if sign > 0 else (self.com[0] - x.min())
        h = float(self.com[2])
        R = math.hypot(b, h)
        I_O = self.inertia[1, 1] + self.mass * R ** 2
        p2 = self.mass * STANDARD_GRAVITY * R / I_O
        alpha = math.atan2(b, h)
        R_eq = 3 * STANDARD_GRAVITY / (4 * p2)
        return dict(b=float(b), h=h, R=R, alpha=alpha, p=math.sqrt(p2), I_O=I_O, R_eq=R_eq,
                    block_height=2 * R_eq * math.cos(alpha), block_width=2 * R_eq * math.sin(alpha))

    def lift_off(self, sign: int) -> dict:
        """Where the rock first tips under a table acceleration along x (turning towards +x for
        sign 1, −x for −1): the resultant of gravity and the inertial force leaves the
        footprint where the ray from the centre of mass's projection along sign·x crosses the
        footprint's boundary, b_x from it, so the rock lifts off at |a| = g·b_x/h, turning
        about the boundary edge it crosses (d: the edge's distance from the projection; cos ψ:
        its outward normal's cosine with x; α_edge = atan(d/h); p_edge² = m g R / I about the
        edge, R = √(d² + h²): turning about that edge is planar rocking with these, driven by
        the acceleration's component a·cos ψ across the edge). For a rectangle b_x = d = the
        direction's b; for a footprint whose extreme point lies off the x axis through the
        centre of mass (these rocks stand on triangles) b_x is smaller than b."""
        pts = self.footprint[:, :2] - self.com[:2]
        ring = pts[ConvexHull(pts).vertices]  # counter-clockwise
        h = float(self.com[2])
        for A, B in zip(ring, np.roll(ring, -1, axis=0)):
            if (A[1] > 0) == (B[1] > 0):
                continue
            x = A[0] + A[1] / (A[1] - B[1]) * (B[0] - A[0])
            if x * sign > 0:
                e = (B - A) / np.linalg.norm(B - A)
                d = abs(A[0] * e[1] - A[1] * e[0])
                R = math.hypot(d, h)
                e3 = np.array([e[0], e[1], 0.0])
                I_edge = float(e3 @ self.inertia @ e3) + self.mass * R * R
                return dict(b_x=float(abs(x)), accel_g=float(abs(x)) / h, edge_distance=float(d),
                            cos_psi=float(abs(e[1])), alpha_edge=math.atan2(d, h),
                            p_edge=math.sqrt(self.mass * STANDARD_GRAVITY * R / I_edge))
        raise ValueError("the centre of mass does not project inside the footprint")

    def describe(self) -> dict:
        fw, bw = self.direction(1), self.direction(-1)
        fw, bw = dict(fw, lift_off=self.lift_off(1)), dict(bw, lift_off=self.lift_off(-1))
        return dict(mass=self.mass, com_height=float(self.com[2]),
                    footprint_x=[float(self.footprint[:, 0].min() - self.com[0]),
                                 float(self.footprint[:, 0].max() - self.com[0])],
                    footprint_y=[float(self.footprint[:, 1].min() - self.com[1]),
                                 float(self.footprint[:, 1].max() - self.com[1])],
                    forward=fw, backward=bw, alpha_ratio=max(fw["alpha"], bw["alpha"]) / min(fw["alpha"], bw["alpha"]),
                    checks=self.checks)


def resting(vertices: np.ndarray, faces: np.ndarray, mass: float, placement: np.ndarray,
            name: str = "the body", properties=None) -> RestingBody:
    """The body at rest: `vertices` (mesh frame) placed by the rotation `placement`,
    settled on the stable hull face nearest the table's downward normal, then in the table
    frame (that face at z = 0, normal −z). `properties`: the mesh's mass_properties, where the
    caller has them already."""
    volume, com0, inertia_unit = mass_properties(vertices, faces) if properties is None else properties
    density = mass / volume
    v = vertices @ placement.T
    com = placement @ com0
    hull_v = v[ConvexHull(v).vertices]
    stable = stable_faces(hull_v, com)
    if not stable:
        raise InputError(f"{name}: no hull face under its centre of mass (mesh not closed?)")
    face = max(stable, key=lambda s: -s["normal"][2])  # the outward normal nearest −z
    R = rotation_between(face["normal"], np.array([0.0, 0.0, -1.0]))
    hv = hull_v @ R.T
    c = R @ com
    z0 = (hv[face["indices"]] @ np.array([0, 0, 1.0])).mean()
    hv[:, 2] -= z0
    c[2] -= z0
    # the plane's points: the hull's vertices on it (the face's indices index hull_v)
    foot = hv[np.abs(hv[:, 2]) < 1e-6]
    I = R @ placement @ (density * inertia_unit) @ placement.T @ R.T
    tilt = math.degrees(math.acos(min(1.0, -face["normal"][2])))
    return RestingBody(mass=mass, vertices=hv, com=c, inertia=I, footprint=foot,
                    checks=dict(volume_m3=volume, density_kg_m3=density, stable_faces=len(stable),
                                settle_tilt_deg=tilt, margin_m=face["margin"]))


def read_mesh(path, unit: str, key: str = "statue") -> tuple[np.ndarray, np.ndarray]:
    """(vertices n×3 in m, triangles m×3) of the mesh file at `path` (whatever trimesh reads:
    STL, OBJ, PLY, OFF, GLB), its lengths in `unit` (one of UNITS; required: an STL states
    none). Refused in one line: an unreadable file, no triangles, a mesh that is not closed
    or not consistently wound (it has no volume to weigh), a non-finite vertex, each naming the
    file as `key` (how the caller spells it: --statue, systems.statue.mesh)."""
    if unit not in UNITS:
        raise InputError(f"unit = {unit!r}: must be the mesh file's length unit, one of {', '.join(UNITS)}")
    trimesh = import_extra("trimesh", "statue", "reading a statue's mesh")
    try:
        mesh = trimesh.load_mesh(str(path))
    except Exception as e:  # noqa: BLE001 - every reader's failure is the file's: one line
        why = getattr(e, "strerror", None) or f"{type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}"
        raise InputError(f"{key} = {str(path)!r}: cannot be read as a mesh ({why})") from None
    if isinstance(mesh, trimesh.Scene):  # a file of several bodies (OBJ groups, GLB): one statue
        mesh = mesh.to_geometry() if hasattr(mesh, "to_geometry") else mesh.dump(concatenate=True)
    faces = np.asarray(getattr(mesh, "faces", np.empty((0, 3))), dtype=np.int64)
    vertices = np.asarray(getattr(mesh, "vertices", np.empty((0, 3))), dtype=float)
    if faces.ndim != 2 or faces.shape[0] < 4:
        raise InputError(f"{key} = {str(path)!r}: has {faces.shape[0] if faces.ndim == 2 else 0} triangles; a "
                         "statue's mesh is a closed surface (at least 4)")
    if not np.all(np.isfinite(vertices)):
        raise InputError(f"{key} = {str(path)!r}: a vertex is not a finite number")
    if not mesh.is_watertight:
        raise InputError(f"{key} = {str(path)!r}: the mesh is not closed (holes or edges shared by more than two "
                         "triangles): it has no volume to weigh; close it (e.g. trimesh's fill_holes) first")
    if not mesh.is_winding_consistent:
        raise InputError(f"{key} = {str(path)!r}: its triangles are not wound consistently (inside and outside "
                         "mixed): it has no volume to weigh")
    return vertices * UNITS[unit], faces


#: the least footprint margin (m) a statue's resting pose must have: its centre of mass
#: projects at least this far inside the face it stands on (less, and it stands on an edge)
MIN_MARGIN = 1e-6


def standing(vertices: np.ndarray, faces: np.ndarray, *, mass: float | None = None, density: float | None = None,
             name: str = "statue") -> RestingBody:
    """The statue as its mesh stands (z up, settled on the stable hull face nearest its
    bottom), weighing `mass` kg, or `density` kg/m³ times its volume (one of the two)."""
    properties = mass_properties(vertices, faces)
    volume = properties[0]
    if not volume > 0:
        raise InputError(f"{name}: its mesh encloses no volume")
    if (mass is None) == (density is None):
        raise InputError(f"{name}: give its mass (kg) or its density (kg/m³), one of the two")
    value, what = (mass, "mass") if mass is not None else (density, "density")
    allowed = f"a positive finite number ({'kg' if what == 'mass' else 'kg/m³'})"
    x = python_number(what, value, allowed)
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"{what} = {value!r}: must be {allowed}")
    body = resting(vertices, faces, x if mass is not None else x * volume, np.eye(3), name=name, properties=properties)
    if not body.checks["margin_m"] > MIN_MARGIN:
        raise InputError(f"{name}: its centre of mass is {body.checks['margin_m']:.3g} m inside the face it stands "
                         "on: it stands on an edge")
    return body


def tipping_edges(body: RestingBody, azimuth: float) -> dict:
    """The two tipping edges for shaking along `azimuth` (rad, from the table's x towards y):
    forward (turning towards the azimuth) and backward, each with its half-base b (m), the
    centre of mass's height h (m), α, R, the inertia I_O about the edge (kg m²), p, and the
    static uplift acceleration across it (g: the table's acceleration at which the statue
    first tips, b_x/h, the resultant leaving the footprint along the azimuth)."""
    turned = body.along(azimuth)
    out = {}
    for key, sign in (("forward", 1), ("backward", -1)):
        d = turned.direction(sign)
        out[key] = dict(b=d["b"], h=d["h"], alpha=d["alpha"], R=d["R"], I_O=d["I_O"], p=d["p"],
                        uplift_g=turned.lift_off(sign)["accel_g"])
    return out


def weakest_direction(body: RestingBody) -> tuple[float, float]:
    """(azimuth in rad, uplift acceleration in g) of the direction the statue tips first: the
    resultant of gravity and the inertial force leaves the footprint soonest across the edge
    nearest the centre of mass's projection, along that edge's outward normal (the least,
    over the footprint's edges, of their distance d from it: uplift at d/h)."""
    pts = body.footprint[:, :2] - body.com[:2]
    hull = ConvexHull(pts)
    # equations: n·x + c ≤ 0 inside, n the outward unit normal; the origin's distance to each edge is −c
    k = int(np.argmax(hull.equations[:, 2]))
    n, c = hull.equations[k, :2], hull.equations[k, 2]
    return float(math.atan2(n[1], n[0]) % (2 * math.pi)), float(-c / body.com[2])


def along_directions(body: RestingBody, azimuths) -> list:
    """The exact model's System of the statue's two edges along each shaking direction (rad), on
    a fixed base (System.of_body)."""
    return [System.of_body(PlanarBody.from_resting(body.along(a)), mass=body.mass) for a in azimuths]


#: the PGA levels (g) of the direction sweep: 2^(k/8) from 0.05 g to 3.2 g (9% apart), fixed
#: before any run, as the shake-table study's overturning scale is
SWEEP_LEVELS = tuple(0.05 * 2.0 ** (k / 8) for k in range(49))
#: directions of the sweep, one every 10°
SWEEP_AZIMUTHS = 36


def overturning_by_azimuth(body: RestingBody, motion, *, azimuths: int = SWEEP_AZIMUTHS,
                           levels=SWEEP_LEVELS, tail: float = 5.0, workers=None) -> dict:
    """The direction it falls (issue 36): for each of `azimuths` shaking directions, the exact
    model of the statue's two edges along it (System.body) on a fixed base under `motion`
    scaled to each PGA of `levels` (ascending), and the lowest level at which it overturns
    (None: none up to the last). Rocking is not monotone in amplitude: the lowest level that
    overturns, not a boundary above which all do. One batch of the compiled kernel
    (fast.simulate_batch). {azimuth_deg, overturning_pga_g, worst: (azimuth_deg, pga_g)}."""
    angles = [2.0 * math.pi * k / azimuths for k in range(azimuths)]
    systems = along_directions(body, angles)
    motions = [motion.scaled_to_pga(level) for level in levels]
    rows = simulate_batch(systems, motions, duration=motion.end_time + tail, product=True, workers=workers)
    first = []
    for i in range(len(systems)):
        over = [r["overturned"] for r in rows[i * len(levels):(i + 1) * len(levels)]]
        first.append(next((float(levels[j]) for j, o in enumerate(over) if o), None))
    falls = [(p, math.degrees(a)) for p, a in zip(first, angles) if p is not None]
    worst = min(falls) if falls else None
    return dict(azimuth_deg=[math.degrees(a) for a in angles], overturning_pga_g=first,
                worst=None if worst is None else dict(azimuth_deg=worst[1], pga_g=worst[0]),
                levels_g=[float(x) for x in levels], motion=motion.name)


def _revolved(profile, sections: int = 96):
    """(vertices, faces) of a profile [(radius, z), …] from the axis at the bottom to the axis
    at the top, revolved about z (trimesh.creation.revolve)."""
    trimesh = import_extra("trimesh", "statue", "making an example statue")
    mesh = trimesh.creation.revolve(np.asarray(profile, float), sections=sections)
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)


def hull_mesh(points):
    """(vertices, faces) of the convex hull of `points`, wound outward (trimesh.convex)."""
    trimesh = import_extra("trimesh", "statue", "making an example statue")
    mesh = trimesh.convex.convex_hull(np.asarray(points, float))
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)


def _stacked(*parts):
    """One mesh of closed parts that touch without overlapping (a bust on its plinth): the
    volumes and moments add, and the hull is the whole's."""
    verts, faces, n = [], [], 0
    for v, f in parts:
        verts.append(v)
        faces.append(f + n)
        n += len(v)
    return np.vstack(verts), np.vstack(faces)


#: the example amphora's profile, (radius, z) in m from the axis at the bottom to the axis at the
#: top: a round foot of radius 5 cm, 2 cm high, under a jar 0.6 m tall
AMPHORA_PROFILE = ((0.0, 0.0), (0.05, 0.0), (0.05, 0.02), (0.03, 0.06), (0.16, 0.25), (0.17, 0.33), (0.10, 0.48),
                   (0.06, 0.52), (0.08, 0.60), (0.0, 0.60))


def example_statue(name: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices in m, faces) of an example statue made by code, standing on z = 0: "bust" (a
    revolved head and shoulders, 0.45 m, on a square plinth block 0.24 m wide and 0.15 m high,
    4 cm forward of its centre: two different tipping edges),
    "amphora" (a revolved jar 0.6 m tall on a narrow foot), "obelisk" (a tapered square shaft
    2 m tall with a pyramidion)."""
    if name == "bust":
        plinth = hull_mesh([[x, y, z] for x in (-0.12, 0.12) for y in (-0.12, 0.12) for z in (0.0, 0.15)])
        profile = [(0.0, 0.15), (0.10, 0.15), (0.17, 0.20), (0.18, 0.27), (0.07, 0.34), (0.05, 0.38), (0.08, 0.42),
                   (0.09, 0.50), (0.07, 0.57), (0.0, 0.60)]
        head_v, head_f = _revolved(profile)
        return _stacked(plinth, (head_v + [0.04, 0.0, 0.0], head_f))  # it leans forward, as busts do
    if name == "amphora":
        return _revolved(AMPHORA_PROFILE)
    if name == "obelisk":
        return hull_mesh([[x, y, 0.0] for x in (-0.2, 0.2) for y in (-0.2, 0.2)]
                          + [[x, y, 1.8] for x in (-0.13, 0.13) for y in (-0.13, 0.13)] + [[0.0, 0.0, 2.0]])
    raise InputError(f"example = {name!r}: must be one of {', '.join(EXAMPLES)}")


EXAMPLES = ("bust", "amphora", "obelisk")


# --- a statue named by its inputs (one home for every surface that takes one) ----------------

#: how each input of `load_statue` is named in messages by default (a campaign file's keys);
#: a caller passes its own spelling (the command line's --statue, --unit, …)
STATUE_NAMES = {"mesh": "mesh", "example": "example", "unit": "unit", "mass": "mass", "density": "density",
                "azimuth": "azimuth", "source": "its mesh (mesh = FILE) or an example (example = NAME)"}


def _one_source(mesh, example, n) -> None:
    if (mesh is None) == (example is None):
        raise InputError(f"statue: give {n['source']}, one of the two")


def statue_mesh(*, mesh=None, example: str | None = None, unit: str | None = None,
                names: dict | None = None) -> tuple[np.ndarray, np.ndarray, str]:
    """(vertices n×3 in m, triangles, a label) of a statue's mesh file (`unit`: the file's length
    unit, required: never guessed) or of an example made by code (`example`, in metres): the one
    reader every surface that takes a statue uses (the command line's --statue, a config
    file's [statue], a campaign's [systems.statue]). `names`: how the caller spells each input
    in its one-line errors (STATUE_NAMES' keys)."""
    n = {**STATUE_NAMES, **(names or {})}
    _one_source(mesh, example, n)
    if unit is not None and unit not in UNITS:
        raise InputError(f"{n['unit']} = {unit!r}: one of {', '.join(UNITS)}")
    if example is not None:
        if example not in EXAMPLES:
            raise InputError(f"{n['example']} = {example!r}: one of {', '.join(EXAMPLES)}")
        if unit not in (None, "m"):
            raise InputError(f"{n['unit']} = {unit!r}: an example statue is made in metres; leave {n['unit']} out")
        vertices, faces = example_statue(example)
        return vertices, faces, f"the example {example}"
    if unit is None:
        raise InputError(f"{n['unit']}: {str(mesh)!r} needs {n['unit']}, its length unit ({', '.join(UNITS)}): a "
                         "mesh file states none this reader trusts, so it is never guessed")
    if unit not in UNITS:
        raise InputError(f"{n['unit']} = {unit!r}: one of {', '.join(UNITS)}")
    vertices, faces = read_mesh(mesh, unit, key=n["mesh"])
    return vertices, faces, str(mesh)


def load_statue(*, mesh=None, example: str | None = None, unit: str | None = None, mass=None, density=None,
                names: dict | None = None) -> RestingBody:
    """The statue standing on a flat plinth (statue_mesh's mesh), weighing `mass` kg or
    `density` kg/m³ (one of the two), its errors naming the inputs as `names` spells them."""
    n = {**STATUE_NAMES, **(names or {})}
    _one_source(mesh, example, n)
    if (mass is None) == (density is None):
        raise InputError(f"statue: give its {n['mass']} (kg) or its {n['density']} (kg/m³), one of the two")
    vertices, faces, label = statue_mesh(mesh=mesh, example=example, unit=unit, names=names)
    try:
        return standing(vertices, faces, mass=mass, density=density, name=label)
    except InputError as e:  # mass or density, named as the caller names it
        text = str(e)
        for key in ("mass", "density"):
            if text.startswith(f"{key} = "):
                raise InputError(n[key] + text[len(key):]) from None
        raise


def shaking_direction(body: RestingBody, azimuth_deg=None, *, names: dict | None = None) -> float:
    """The azimuth (rad) a statue is shaken along: `azimuth_deg` (degrees, from the table's x
    towards y), or where none is given the direction it tips first (weakest_direction)."""
    if azimuth_deg is None:
        return weakest_direction(body)[0]
    n = {**STATUE_NAMES, **(names or {})}
    x = python_number(n["azimuth"], azimuth_deg, "a finite number of degrees")
    if not math.isfinite(x):
        raise InputError(f"{n['azimuth']} = {azimuth_deg!r}: must be a finite number of degrees")
    return math.radians(x)
