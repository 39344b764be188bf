"""A statue's shape from its mesh (analytic/shape.py, issue 36), against closed forms: the mass
properties of a box, a regular n-gon prism and pyramid (exact for polyhedra, so to rounding),
the tipping edges of a box (the rectangle the exact model takes: α, R, I_O = 4/3 m R², p), its
uplift accelerations along any azimuth, and the mesh reader's refusals."""
import math

import numpy as np
import pytest

from isorock.analytic import shape
from isorock.analytic.errors import InputError
from isorock.analytic.system import System

trimesh = pytest.importorskip("trimesh")


def _closed(points):
    """A closed, outward-wound triangle mesh of the convex hull of `points`."""
    mesh = trimesh.convex.convex_hull(np.asarray(points, float))
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)


def _ngon(n, r, z=0.0, scale=1.0):
    return [[scale * r * math.cos(2 * math.pi * k / n), scale * r * math.sin(2 * math.pi * k / n), z] for k in range(n)]


def test_a_regular_prism_and_pyramid_weigh_as_their_closed_forms():
    n, r, H = 7, 0.3, 1.1
    c = math.cos(2 * math.pi / n)
    area = n / 2 * r * r * math.sin(2 * math.pi / n)
    polar = r * r * (2 + c) / 6  # J/A of a regular n-gon of circumradius r
    v, f = _closed(_ngon(n, r) + _ngon(n, r, H))
    vol, com, I = shape.mass_properties(v, f)
    assert vol == pytest.approx(area * H, rel=1e-12)
    assert np.allclose(com, [0, 0, H / 2], atol=1e-12)
    assert I[2, 2] / vol == pytest.approx(polar, rel=1e-12)
    assert I[0, 0] / vol == pytest.approx(polar / 2 + H * H / 12, rel=1e-12)
    # the pyramid over it (the cone's polyhedron): V = A H/3, the centre at H/4, and its slices'
    # second moments averaged with the weight of their area (3/5)
    v, f = _closed(_ngon(n, r) + [[0, 0, H]])
    vol, com, I = shape.mass_properties(v, f)
    assert vol == pytest.approx(area * H / 3, rel=1e-12)
    assert np.allclose(com, [0, 0, H / 4], atol=1e-12)
    assert I[2, 2] / vol == pytest.approx(3 / 5 * polar, rel=1e-12)
    assert I[0, 0] / vol == pytest.approx(3 / 5 * polar / 2 + 3 * H * H / 80, rel=1e-12)
    # and the cylinder and the cone as n grows (closed forms m r²/2 and 3/10 m r²)
    v, f = _closed(_ngon(4096, r) + [[0, 0, H]])
    vol, _, I = shape.mass_properties(v, f)
    assert I[2, 2] / vol == pytest.approx(3 / 10 * r * r, rel=1e-6)


@pytest.mark.parametrize("width, depth, height, mass", [(0.7, 0.5, 2.0, 3800.0), (0.02, 0.03, 0.1, 0.4),
                                                        (2.0, 1.5, 10.0, 2e5)])
def test_a_box_is_the_exact_models_rectangle_along_either_axis(width, depth, height, mass):
    v, f = _closed([[x, y, z] for x in (-width / 2, width / 2) for y in (-depth / 2, depth / 2) for z in (0, height)])
    body = shape.standing(v, f, mass=mass)
    for azimuth, b in ((0.0, width / 2), (math.pi / 2, depth / 2), (math.pi, width / 2)):
        edges = shape.tipping_edges(body, azimuth)
        block = System.fixed(height=height, width=2 * b, mass=mass)
        for e in edges.values():
            R = math.hypot(b, height / 2)
            assert e["alpha"] == pytest.approx(block.alpha, rel=1e-12)
            assert e["R"] == pytest.approx(block.R, rel=1e-12)
            assert e["I_O"] == pytest.approx(4 / 3 * mass * R * R, rel=1e-12)
            assert e["p"] == pytest.approx(block.p, rel=1e-12)
            assert e["uplift_g"] == pytest.approx(b / (height / 2), rel=1e-12)


def test_a_box_shaken_at_an_angle_tips_where_the_resultant_leaves_its_footprint():
    width, depth, height = 0.6, 0.4, 1.5
    v, f = _closed([[x, y, z] for x in (-width / 2, width / 2) for y in (-depth / 2, depth / 2) for z in (0, height)])
    body = shape.standing(v, f, density=2700.0)
    assert body.mass == pytest.approx(2700.0 * width * depth * height, rel=1e-12)
    for deg in (10, 30, 45, 60, 80):
        a = math.radians(deg)
        edges = shape.tipping_edges(body, a)
        reach = min(width / 2 / math.cos(a), depth / 2 / math.sin(a))  # the ray from the centre to the border
        corner = width / 2 * math.cos(a) + depth / 2 * math.sin(a)  # the footprint's extreme along the azimuth
        for e in edges.values():
            assert e["uplift_g"] == pytest.approx(reach / (height / 2), rel=1e-12)
            assert e["b"] == pytest.approx(corner, rel=1e-12)


def test_a_regular_prism_is_the_same_after_a_turn_of_its_symmetry():
    n = 5
    v, f = _closed(_ngon(n, 0.2) + _ngon(n, 0.2, 0.9))
    body = shape.standing(v, f, mass=50.0)
    for azimuth in (0.1, 0.7):
        one, turned = shape.tipping_edges(body, azimuth), shape.tipping_edges(body, azimuth + 2 * math.pi / n)
        for side in ("forward", "backward"):
            for key in ("alpha", "R", "I_O", "p", "uplift_g"):
                assert turned[side][key] == pytest.approx(one[side][key], rel=1e-12)


def test_the_mesh_is_read_in_the_unit_named(tmp_path):
    box = trimesh.creation.box(extents=(700.0, 500.0, 2000.0))  # mm
    box.apply_translation((0, 0, 1000.0))
    path = tmp_path / "box.stl"
    box.export(path)
    v, f = shape.read_mesh(path, "mm")
    assert np.allclose(v.min(0), [-0.35, -0.25, 0.0]) and np.allclose(v.max(0), [0.35, 0.25, 2.0])
    edges = shape.tipping_edges(shape.standing(v, f, mass=3800.0), 0.0)
    assert edges["forward"]["alpha"] == pytest.approx(System.fixed(height=2.0, width=0.7, mass=3800.0).alpha, rel=1e-12)
    with pytest.raises(InputError, match="unit = 'furlong'"):
        shape.read_mesh(path, "furlong")


def test_a_broken_mesh_is_refused_in_one_line(tmp_path):
    box = trimesh.creation.box(extents=(1.0, 1.0, 2.0))
    open_box = trimesh.Trimesh(box.vertices, box.faces[:-1], process=False)
    cases = {"open.stl": open_box.export(file_type="stl"), "junk.stl": b"solid x\nnot a facet\n",
             "empty.obj": b"", "text.ply": b"ply\nformat ascii 1.0\nelement vertex 1\nend_header\n1 2\n"}
    for name, data in cases.items():
        path = tmp_path / name
        path.write_bytes(data)
        with pytest.raises(InputError) as e:
            shape.read_mesh(path, "m")
        assert "\n" not in str(e.value) and name in str(e.value)
    with pytest.raises(InputError, match="not closed"):
        shape.read_mesh(tmp_path / "open.stl", "m")
    with pytest.raises(InputError, match="cannot be read"):
        shape.read_mesh(tmp_path / "missing.stl", "m")


def test_mass_or_density_one_of_the_two():
    v, f = _closed([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 2)])
    for kw in ({}, {"mass": 1.0, "density": 1.0}, {"mass": -1.0}, {"density": float("nan")}, {"mass": "80"}):
        with pytest.raises(InputError):
            shape.standing(v, f, **kw)
    assert shape.standing(v, f, mass=2.0).mass == 2.0


def test_the_weakest_direction_is_across_the_nearest_edge():
    width, depth, height = 0.4, 0.9, 1.6
    v, f = _closed([[x, y, z] for x in (-width / 2, width / 2) for y in (-depth / 2, depth / 2) for z in (0, height)])
    azimuth, g = shape.weakest_direction(shape.standing(v, f, mass=100.0))
    assert g == pytest.approx(width / height, rel=1e-12)
    assert min(abs(azimuth), abs(azimuth - math.pi), abs(azimuth - 2 * math.pi)) < 1e-12
    # a right-triangle prism (legs 0.6 along x, 0.9 along y): the centroid is 0.2 and 0.3 from the
    # legs and 0.6·0.9/(3·√(0.6² + 0.9²)) from the hypotenuse, the nearest
    v, f = _closed([[x, y, z] for x, y in ((0, 0), (0.6, 0), (0, 0.9)) for z in (0, 1.0)])
    azimuth, g = shape.weakest_direction(shape.standing(v, f, mass=10.0))
    hyp = 0.6 * 0.9 / (3 * math.hypot(0.6, 0.9))
    assert g == pytest.approx(hyp / 0.5, rel=1e-12)
    assert azimuth == pytest.approx(math.atan2(0.6, 0.9), rel=1e-12)


def _revolved_closed_form(profile, n, density):
    """(mass, centre-of-mass height, centroidal inertia about a horizontal axis) of `profile`
    revolved as an n-gon, slice by slice: a regular n-gon of circumradius r has area
    (n/2)·r²·sin(2π/n) and second moment about a diameter area·r²·(1 + 2cos²(π/n))/12; r is
    linear in z on each piece, so each integral is a polynomial's, exact."""
    a = 0.5 * n * math.sin(2 * math.pi / n)
    j = a * (1 + 2 * math.cos(math.pi / n) ** 2) / 12
    v = mz = mzz = i4 = 0.0
    for (r0, z0), (r1, z1) in zip(profile, profile[1:]):
        if z1 <= z0:
            continue
        r = np.polynomial.Polynomial([r0 - (r1 - r0) / (z1 - z0) * z0, (r1 - r0) / (z1 - z0)])
        z = np.polynomial.Polynomial([0.0, 1.0])
        span = lambda p: p.integ()(z1) - p.integ()(z0)  # noqa: E731
        v, mz, mzz, i4 = v + a * span(r ** 2), mz + a * span(r ** 2 * z), mzz + a * span(r ** 2 * z * z), i4 + j * span(r ** 4)
    h = mz / v
    return density * v, h, density * (i4 + mzz - v * h * h)


@pytest.mark.parametrize("where", ["edge", "vertex"])
def test_the_amphoras_round_foot_has_the_edges_of_its_profile_by_hand(where):
    """The example amphora's two edges along the direction it tips first (across the middle of an
    edge of its 96-gon foot: b = r_f·cos(π/96)) and through a vertex (b = r_f), the foot's radius
    r_f 5 cm, against the revolved profile by hand (docs/statues.md, "The amphora's round foot,
    measured": the planar model's edges are not why the engines part from it)."""
    n, r_f, density = 96, 0.05, 2600.0
    body = shape.standing(*shape.example_statue("amphora"), density=density)
    mass, h, i_c = _revolved_closed_form(shape.AMPHORA_PROFILE, n, density)
    azimuth = shape.weakest_direction(body)[0] if where == "edge" else 0.0
    b = r_f * (math.cos(math.pi / n) if where == "edge" else 1.0)
    R = math.hypot(b, h)
    assert body.mass == pytest.approx(mass, rel=1e-12)
    for edge in shape.tipping_edges(body, azimuth).values():
        assert edge["b"] == pytest.approx(b, rel=1e-12) and edge["h"] == pytest.approx(h, rel=1e-12)
        assert edge["alpha"] == pytest.approx(math.atan2(b, h), rel=1e-12)
        assert edge["I_O"] == pytest.approx(i_c + mass * R * R, rel=1e-12)
