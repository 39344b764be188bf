"""The specimens: mesh + inertial data → the resting pose on a flat table, its footprint, the
centre of mass and inertia (from the mesh at uniform density, checked against the data's own),
and the equivalent planar block of the rigid rocking model in the shaking plane (x–z).

The resting pose is found, not assumed: a rigid body on a flat table rests on a face of its
convex hull (the table touches nothing inside the hull), and it can rest on a face only when
the centre of mass projects, along the face's normal, inside that face. Of the stable faces,
the pose taken is the one whose outward normal is nearest the table's downward normal after
the data's own placement (its orientation quaternion): the test set-up placed it there, and
the pose it settles to is the stable face that placement is nearest.

The equivalent block: rocking about the footprint's forward (+x) or backward (−x) extreme
edge, the planar equation of motion of any rigid body depends on α (the angle from the
vertical of the line from the edge to the centre of mass), and p² = m g R / I_O (I_O its
moment of inertia about the edge). A rectangular block with the same α and p (so
R_eq = 3g/(4p²), h = R_eq cos α, b = R_eq sin α) rocks by the same equation between impacts;
its impact law (Housner's, from the rectangle's geometry) is the model's assumption, not
the rock's.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
import xml.etree.ElementTree as ET

import numpy as np
from scipy.spatial import ConvexHull

from isorock.analytic.errors import InputError
from isorock.analytic.system import STANDARD_GRAVITY

#: The specimens' files and the data's placement (the data folder's README: the original
#: repository's config files). Orientation quaternion (x, y, z, w) applied to the mesh.
SPECIMEN_FILES = {
    1: ("models/SP1_PBRmodel/final_sp1_pca.obj", "models/SP1_PBRmodel/sp1.urdf",
        (0.8676640240119536, 0.06594471044608025, 0.4791004506761131, 0.11520935188391664)),
    2: ("models/SP2_PBRmodel/final_sp2_1.obj", "models/SP2_PBRmodel/sp2.urdf", (0.0, 0.0, 0.0, 1.0)),
}
#: Hull faces whose planes agree to this (unit normal, and offset in m) are one face.
FACE_TOLERANCE = 1e-6


def read_obj(path) -> tuple[np.ndarray, np.ndarray]:
    """(vertices n×3 in the file's units, triangles m×3 indices); polygons fanned."""
    verts, faces = [], []
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            for lineno, line in enumerate(f, 1):
                if line.startswith("v "):
                    try:
                        verts.append([float(x) for x in line.split()[1:4]])
                    except ValueError:
                        raise InputError(f"{path}:{lineno}: vertex {line.strip()[:50]!r}: expected 3 numbers") from None
                elif line.startswith("f "):
                    idx = [int(tok.split("/")[0]) for tok in line.split()[1:]]
                    idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                    faces += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    except OSError as e:
        raise InputError(f"{path}: cannot be read ({e.strerror})") from None
    v, fc = np.asarray(verts, float), np.asarray(faces, int)
    if v.shape[0] < 4 or fc.shape[0] < 4 or fc.max() >= v.shape[0] or fc.min() < 0:
        raise InputError(f"{path}: not a closed triangle mesh (vertices {v.shape[0]}, faces {fc.shape[0]})")
    return v, fc


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


def quat_matrix(q) -> np.ndarray:
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


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
class Specimen:
    """A specimen at rest on the table: its hull vertices in the table frame (z up, the
    table at z = 0, shaking along x), mass, centre of mass and inertia about it (table frame)."""
    number: int
    mass: float
    vertices: np.ndarray  # hull vertices, table frame, m
    com: np.ndarray
    inertia: np.ndarray
    footprint: np.ndarray  # the resting face's vertices, table frame (z = 0)
    checks: dict = field(default_factory=dict)

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
        return dict(specimen=self.number, mass=self.mass, com_height=float(self.com[2]),
                    footprint_x=[float(self.footprint[:, 0].min() - self.com[0]),
                                 float(self.footprint[:, 0].max() - self.com[0])],
                    footprint_y=[float(self.footprint[:, 1].min() - self.com[1]),
                                 float(self.footprint[:, 1].max() - self.com[1])],
                    forward=fw, backward=bw, alpha_ratio=max(fw["alpha"], bw["alpha"]) / min(fw["alpha"], bw["alpha"]),
                    checks=self.checks)


def read_urdf_inertial(path) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, inertia tensor, the collision mesh's origin offset xyz) of a one-link URDF."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise InputError(f"{path}: cannot be read as URDF ({e})") from None
    inertial = root.find(".//inertial")
    if inertial is None or inertial.find("mass") is None or inertial.find("inertia") is None:
        raise InputError(f"{path}: no <inertial> with <mass> and <inertia>")
    m = float(inertial.find("mass").get("value"))
    a = {k: float(v) for k, v in inertial.find("inertia").attrib.items()}
    I = np.array([[a["ixx"], a["ixy"], a["ixz"]], [a["ixy"], a["iyy"], a["iyz"]], [a["ixz"], a["iyz"], a["izz"]]])
    origin = root.find(".//collision/origin")
    xyz = np.array([float(x) for x in origin.get("xyz").split()]) if origin is not None else np.zeros(3)
    return m, I, xyz


def resting(vertices: np.ndarray, faces: np.ndarray, mass: float, placement: np.ndarray,
            number: int = 0) -> Specimen:
    """The specimen at rest: `vertices` (mesh frame) placed by the rotation `placement`,
    settled on the stable hull face nearest the table's downward normal, then in the table
    frame (that face at z = 0, normal −z)."""
    volume, com0, inertia_unit = mass_properties(vertices, faces)
    density = mass / volume
    v = vertices @ placement.T
    com = placement @ com0
    hull_v = v[ConvexHull(v).vertices]
    stable = stable_faces(hull_v, com)
    if not stable:
        raise InputError(f"specimen {number}: no hull face under its centre of mass (mesh not closed?)")
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
    return Specimen(number=number, mass=mass, vertices=hv, com=c, inertia=I, footprint=foot,
                    checks=dict(volume_m3=volume, density_kg_m3=density, stable_faces=len(stable),
                                settle_tilt_deg=tilt, margin_m=face["margin"]))


def load_specimen(folder, number: int) -> Specimen:
    """Specimen `number` (1 or 2) of the data folder, at rest, with its checks: the mesh's
    centre of mass and inertia (uniform density, the data's mass) beside the URDF's."""
    if number not in SPECIMEN_FILES:
        raise InputError(f"specimen = {number!r}: must be one of {', '.join(map(str, SPECIMEN_FILES))}")
    obj, urdf, quat = SPECIMEN_FILES[number]
    folder = Path(folder)
    for p in (folder / obj, folder / urdf):
        if not p.is_file():
            raise InputError(f"data = {str(folder)!r}: {p.relative_to(folder)} missing (the specimen's mesh and URDF)")
    verts, faces = read_obj(folder / obj)
    mass, I_urdf, origin = read_urdf_inertial(folder / urdf)
    volume, com0, I_unit = mass_properties(verts, faces)
    spec = resting(verts, faces, mass, quat_matrix(quat), number)
    I_mesh = mass / volume * I_unit
    spec.checks.update(
        urdf_mass=mass, mesh_com=com0.tolist(), urdf_mesh_origin=origin.tolist(),
        # the URDF's link frame is its centre of mass; its collision origin is where the mesh's
        # frame sits in it, so the mesh's centre of mass should sit at −origin
        com_offset_m=float(np.linalg.norm(com0 + origin)),
        inertia_mesh=np.linalg.eigvalsh(I_mesh).tolist(), inertia_urdf=np.linalg.eigvalsh(I_urdf).tolist(),
        inertia_rel_diff=float(np.abs(np.linalg.eigvalsh(I_mesh) - np.linalg.eigvalsh(I_urdf)).max()
                               / np.linalg.eigvalsh(I_urdf).max()))
    return spec
