"""The specimens: the shake-table data's meshes, URDF inertial data and placements, read into
analytic.shape's resting body (the pose on a flat table, its footprint, the centre of mass
and inertia from the mesh at uniform density, checked against the data's own, and the
equivalent planar block in the shaking plane: analytic/shape.py, the one home of shapes).
"""
from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path
import xml.etree.ElementTree as ET

import numpy as np

from ....analytic import shape
from ....analytic.errors import InputError
from ....analytic.shape import RestingBody, mass_properties

#: The specimens' files and the data's placement (the data folder's README: the original
#: repository's config files). Orientation quaternion (x, y, z, w) applied to the mesh.
SPECIMEN_FILES = {
    1: ("models/SP1_PBRmodel/final_sp1_pca.obj", "models/SP1_PBRmodel/sp1.urdf",
        (0.8676640240119536, 0.06594471044608025, 0.4791004506761131, 0.11520935188391664)),
    2: ("models/SP2_PBRmodel/final_sp2_1.obj", "models/SP2_PBRmodel/sp2.urdf", (0.0, 0.0, 0.0, 1.0)),
}


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


def quat_matrix(q) -> np.ndarray:
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


@dataclass
class Specimen(RestingBody):
    """A specimen at rest on the table (analytic.shape.RestingBody), with its number."""
    number: int = 0

    def describe(self) -> dict:
        return dict(specimen=self.number, **super().describe())


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
    """The specimen at rest (analytic.shape.resting), numbered."""
    body = shape.resting(vertices, faces, mass, placement, name=f"specimen {number}")
    return Specimen(**{f.name: getattr(body, f.name) for f in fields(RestingBody)}, number=number)


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
