"""`isorock statue` (issue 36): the direction a statue tips first, and its edges, checked against
trimesh's own mass properties (an integrator of its own) and the closed form of a footprint."""
import json
import math

import pytest

from isorock.analytic import shape
from isorock.validate.cli.main import main

trimesh = pytest.importorskip("trimesh")


def _json(capsys, *args):
    code = main(["statue", *args, "--json", "-"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out), out.err


def test_the_bust_tips_first_forward_where_trimeshs_centre_of_mass_says(capsys):
    d, err = _json(capsys, "--example", "bust", "--mass", "80")
    mesh = trimesh.Trimesh(*shape.example_statue("bust"), process=False)
    com = mesh.center_mass  # trimesh's own integrals of the same surface
    assert d["tips_first"]["azimuth_deg"] == pytest.approx(0.0, abs=1e-9)
    assert d["tips_first"]["uplift_g"] == pytest.approx((0.12 - com[0]) / com[2], rel=1e-9)
    back = d["edges"]["backward"]
    assert back["uplift_g"] == pytest.approx((0.12 + com[0]) / com[2], rel=1e-9)
    assert back["alpha"] == pytest.approx(math.atan2(0.12 + com[0], com[2]), rel=1e-9)
    assert d["volume"] == pytest.approx(mesh.volume, rel=1e-9)
    assert "tips first when the table accelerates at" in err and "two edges differ" in err


def test_the_polar_table_is_the_footprint_seen_from_the_centre_of_mass(capsys):
    d, _ = _json(capsys, "--example", "obelisk", "--density", "2600")
    grid = d["uplift_by_azimuth"]
    h = d["com_height"]
    for deg, g in zip(grid["azimuth_deg"], grid["uplift_g"]):
        a = math.radians(deg)
        reach = min(0.2 / abs(math.cos(a)) if abs(math.cos(a)) > 1e-12 else math.inf,
                    0.2 / abs(math.sin(a)) if abs(math.sin(a)) > 1e-12 else math.inf)
        assert g == pytest.approx(reach / h, rel=1e-9)
    assert d["tips_first"]["uplift_g"] == pytest.approx(min(grid["uplift_g"]), rel=1e-12)


def test_a_file_is_read_in_its_unit_and_every_output_is_written(tmp_path, capsys):
    mesh = trimesh.Trimesh(*shape.example_statue("amphora"), process=False)
    mm = tmp_path / "amphora-mm.stl"
    mesh.copy().apply_scale(1000.0).export(mm)
    in_m, _ = _json(capsys, "--example", "amphora", "--mass", "60")
    code = main(["statue", str(mm), "--unit", "mm", "--mass", "60", "--json", str(tmp_path / "a.json"),
                 "--plot", str(tmp_path / "a.png"), "--write-mesh", str(tmp_path / "a.stl")])
    capsys.readouterr()
    assert code == 0
    in_mm = json.loads((tmp_path / "a.json").read_text())
    # an STL holds its vertices as 32-bit floats (a relative 6e-8 each)
    assert in_mm["tips_first"]["uplift_g"] == pytest.approx(in_m["tips_first"]["uplift_g"], rel=1e-6)
    assert in_mm["edges"]["forward"]["I_O"] == pytest.approx(in_m["edges"]["forward"]["I_O"], rel=1e-6)
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert trimesh.load_mesh(tmp_path / "a.stl").volume == pytest.approx(mesh.volume, rel=1e-6)


@pytest.mark.parametrize("args, says", [
    (["--mass", "80"], "give its mesh FILE or --example"),
    (["--example", "bust"], "mass (kg) or its density"),
    (["--example", "bust", "--mass", "80", "--unit", "mm"], "made in metres"),
    (["--example", "bust", "--mass", "80", "--azimuth", "nan"], "azimuth"),
    (["FILE.stl", "--mass", "80"], "needs --unit"),
    (["FILE.stl", "--example", "bust", "--mass", "80"], "one of the two"),
    (["missing.stl", "--unit", "m", "--mass", "80"], "cannot be read"),
    (["--example", "bust", "--mass", "80", "--motion", "none"], "zero throughout"),
    (["--example", "bust", "--mass", "80", "--units", "g"], "needs --motion"),
    (["--example", "bust", "--mass", "80", "--motion", "missing.at2"], "missing.at2"),
])
def test_bad_input_is_one_line_and_exit_2(args, says, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    trimesh.creation.box(extents=(1, 1, 2)).export(tmp_path / "FILE.stl")
    code = main(["statue", *args])
    err = capsys.readouterr().err
    assert code == 2 and says in err and err.count("\n") == 1


# --- issue 36: `isorock run --statue`: the exact model of the statue's own two edges ---------------

def _run_json(capsys, *args):
    code = main(["run", *args, "--json", "-", "--quiet"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out), out.err


def test_run_takes_the_bust_on_its_two_edges_and_lifts_it_where_its_centre_of_mass_says(capsys):
    """The bust along 0° (its weaker direction): b± = 0.12 ∓ x_c and h = z_c from trimesh's own
    centre of mass; under a sine of 0.5 g, between the forward edge's g·b₊/h (0.416 g) and the
    backward's (0.656 g), it first lifts about the forward edge where −A sin ωt reaches g·b₊/h:
    t = (π + asin(b₊/(h·A)))/ω, and only ever that way (θ ≥ 0)."""
    d, err = _run_json(capsys, "--statue-example", "bust", "--mass", "80", "--fixed-base",
                       "--motion", "sine:amp=0.5,freq=2,cycles=1")
    com = trimesh.Trimesh(*shape.example_statue("bust"), process=False).center_mass
    body = d["body"]
    assert body["lever_forward"] == pytest.approx(0.12 - com[0], rel=1e-9)
    assert body["lever_backward"] == pytest.approx(0.12 + com[0], rel=1e-9)
    assert body["centre_height"] == pytest.approx(com[2], rel=1e-9)
    omega = 2 * math.pi * 2.0
    ratio = body["lever_forward"] / (body["centre_height"] * 0.5)
    assert d["engine"] in ("analytic", "analytic-reference")  # the reference on a first run (issue 34)
    assert d["uplift_times"][0] == pytest.approx((math.pi + math.asin(ratio)) / omega, abs=1e-9)
    assert d["uplifts"] >= 1 and not d["overturned"]


def test_run_help_names_every_example_and_unit(capsys):
    """The run parser names them in its help without loading analytic.shape (and NumPy)."""
    assert main(["run", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert all(name in text for name in shape.EXAMPLES) and all(unit in text for unit in shape.UNITS)


@pytest.mark.parametrize("args, says", [
    (["--statue-example", "bust", "--mass", "80", "--height", "2"], "--height"),
    (["--statue-example", "bost", "--mass", "80"], "one of bust"),
    (["--statue-example", "bust", "--mass", "80", "--unit", "furlong"], "one of m"),
    (["--statue-example", "bust", "--mass", "80", "--density", "2600"], "one of the two"),
    (["--statue-example", "bust"], "one of the two"),  # neither (the block's default mass is not the statue's)
    (["--statue", "bust.stl", "--mass", "80"], "--unit"),
    (["--unit", "mm"], "describes a statue's mesh"),
    (["--statue-example", "bust", "--mass", "80", "--engine", "mjx"], "two different edges"),
    (["--statue-example", "bust", "--mass", "80", "--statue-friction", "0.5"], "--statue-friction"),
], ids=["height", "unknown-example", "unknown-unit", "mass-and-density", "no-mass", "no-unit", "unit-alone", "contact-engine", "friction"])
def test_run_with_a_statue_refuses_in_one_line(args, says, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = main(["run", *args, "--fixed-base", "--motion", "sine:amp=0.5,freq=2,cycles=1"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and says in err and len(err.splitlines()) == 1, err


def test_the_direction_sweep_of_a_box_is_the_rectangles_own_overturning_pga(tmp_path, capsys):
    """`isorock statue BOX --motion SPEC`: a 0.35 × 0.5 × 1.2 m box shaken along its x (0°) is the
    exact model's rectangle H 1.2 m, B 0.35 m, and along 90° the rectangle of B 0.5 m: the lowest
    PGA of the sweep's levels that overturns each, found here by running those rectangles directly
    (System(height, width) on a fixed base, never built from the mesh)."""
    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.motion import load_motion
    from isorock.analytic.system import System
    box = trimesh.creation.box(extents=(0.35, 0.5, 1.2))
    box.apply_translation((0.0, 0.0, 0.6))
    path = tmp_path / "box.stl"
    box.export(path)
    spec = "ricker:amp=1,freq=1.5"
    code = main(["statue", str(path), "--unit", "m", "--density", "2000", "--motion", spec, "--json", "-"])
    out = capsys.readouterr()
    assert code == 0, out.err
    d = json.loads(out.out)["overturning_by_azimuth"]
    motion = load_motion(spec)
    for azimuth, width in ((0.0, 0.35), (90.0, 0.5), (180.0, 0.35)):
        k = d["azimuth_deg"].index(azimuth)
        block = System.fixed(height=1.2, width=width, mass=0.35 * 0.5 * 1.2 * 2000)
        want = next((lv for lv in d["levels_g"] if simulate_fast(block, motion.scaled_to_pga(lv),
                                                                 duration=motion.end_time + 5.0).overturned), None)
        assert want is not None and d["overturning_pga_g"][k] == pytest.approx(want, rel=1e-12), (azimuth, want)
    assert d["worst"]["pga_g"] == min(p for p in d["overturning_pga_g"] if p is not None)
    assert "first overturns at" in out.err and "1,764 runs" in out.err
