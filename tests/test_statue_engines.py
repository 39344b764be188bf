"""A statue's own shape in the contact engines, on every base (issue 36; docs/statues.md, "The
contact engines on the base and isolator"): MuJoCo's hull on a free joint against the exact model
of the statue's two edges, judged by the tolerance table's rows for the block; each impact's β
against its own edge's closed form; the closed forms themselves against the exact model; and
`validate --statue` with an engine that cannot carry a statue."""
from __future__ import annotations

import math
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest

from isorock.analytic.coefficients import edge_impact
from isorock.analytic.errors import InputError
from isorock.analytic.system import PlanarBody, Solid, System
from isorock.validate.core.compare import exact_first_impact_time
from isorock.validate.core.engines import get_engine
from isorock.validate.core.measure import beta_errors, impact_closed_forms
from isorock.validate.core.tolerances import tolerance
from isorock.validate.tools import statue_check as sc
from statue_judging import judge_hull
from isorock.validate.tools.report_run import effective_beta

#: robust cases (the exact model's θmax/α moves < 0.05 under ±1% of the pulse) of the two statues
#: the planar model describes, at the amplitude where its θmax/α is 0.05 (docs/scripts/statue_engines.py)
CASES = [("bust", 1.0, "fixed"), ("bust", 1.0, "friction-pendulum"), ("bust", 3.0, "linear"),
         ("obelisk", 0.5, "linear"), ("obelisk", 3.0, "friction-pendulum")]


def _case(name, scale, base, target=0.05):
    _, system = sc.example(name, scale, base)
    return system, sc.pulse(system, sc.amplitude_for(system, target))


@pytest.mark.parametrize("name,scale,base", CASES)
def test_mujoco_hull_rocks_as_the_exact_model_of_its_two_edges(name, scale, base):
    judge_hull("mujoco", name, scale, base)


def test_the_statue_is_its_hull_on_a_free_joint_and_the_plate_reaches_past_it():
    import mujoco
    from isorock.mujoco_models.scene import scene_text
    from isorock.mujoco_models.settings import Settings
    _, system = sc.example("bust", 1.0, "linear")
    settings = Settings().for_system(system)
    assert (settings.joint, settings.contact) == ("free", "box")  # asked for by the statue's solid
    model = mujoco.MjModel.from_xml_string(scene_text(system, settings))
    hull = model.geom("block_geom")
    assert hull.type[0] == mujoco.mjtGeom.mjGEOM_MESH
    assert model.body("block").mass[0] == pytest.approx(system.mass, rel=1e-12)
    # the explicit inertia tensor, not one computed from the hull's geometry
    inertia = np.linalg.eigvalsh(np.array(system.body.solid.inertia))
    assert np.sort(model.body("block").inertia) == pytest.approx(inertia, rel=1e-9)
    y_reach = max(abs(v[1]) for v in system.body.solid.vertices)
    assert model.geom("base_geom").size[1] > y_reach
    with pytest.raises(InputError, match="joint"):
        scene_text(system, replace(settings, joint="planar"))


def test_a_planar_body_without_its_shape_is_the_box_on_its_two_edges():
    """No mesh (a PlanarBody given by its numbers): MuJoCo builds the box spanning its edges on the
    planar joints; its impacts keep each edge's β."""
    body = PlanarBody(centre_height=1.0, lever_forward=0.25, lever_backward=0.45, inertia=800 * (0.35**2 + 1.0) / 3)
    system = System.of_body(body, mass=800.0)
    tr = get_engine("mujoco").simulate(system, None, duration=4.0, theta0=0.15)
    errors = beta_errors(tr)
    assert len(errors) >= 3 and max(abs(e) for e in errors) <= tolerance("mujoco", "beta_rel_error").limit
    # impacts alternate edges: each its own β (0.81 onto the backward edge, 0.69 onto the forward one)
    betas = {round(impact_closed_forms(system, i)[0], 6) for i in tr.counted_impacts}
    assert len(betas) == 2


@pytest.mark.parametrize("base", ["fixed", "linear"])
def test_each_impact_of_the_exact_model_has_its_own_edges_closed_forms(base):
    """The closed forms (coefficients.edge_impact) against the exact model's impact states, β and
    β₂ of every impact, alternating edges: independent of the integrator that made them."""
    _, system = sc.example("bust", 1.0, base)
    tr = get_engine("analytic").simulate(system, None, duration=3.0, theta0=0.5 * system.alpha)
    assert len(tr.counted_impacts) >= 3
    assert max(abs(e) for e in beta_errors(tr)) < 1e-9
    sides = {1 if i.theta_dot_pre > 0 else -1 for i in tr.counted_impacts}
    assert sides == {1, -1}
    b = effective_beta(tr)
    assert b["beta_rel_error"] < 1e-9
    if base == "linear":
        assert b["beta2_abs_error"] < 1e-9
    # the forward edge's impact onto the backward one, by hand from the momentum balance
    m, h, ic = system.mass, system.h, system.inertia
    bf, bb = system.lever(1), system.lever(-1)
    fixed = System.of_body(system.body, mass=m)
    by_hand = (ic + m * h * h - m * bf * bb) / (ic + m * h * h + m * bb * bb)
    assert edge_impact(m, None, h, ic, bf, bb)[0] == pytest.approx(by_hand, rel=1e-14)
    assert impact_closed_forms(fixed)[0] == pytest.approx(by_hand, rel=1e-14)  # it tips forward first


@pytest.mark.parametrize("side", [1, -1])
def test_first_impact_time_of_each_edge(side):
    """model.md's quadrature for t₁ with each edge's own α, R and I against the exact model."""
    _, system = sc.example("bust", 1.0, "fixed")
    theta0 = side * 0.4 * system.edge_alpha(side)
    tr = get_engine("analytic").simulate(system, None, duration=2.0, theta0=theta0)
    assert tr.counted_impacts[0].t == pytest.approx(exact_first_impact_time(system, theta0), rel=1e-8)
    other = exact_first_impact_time(system, -theta0 * system.edge_alpha(-side) / system.edge_alpha(side))
    assert not math.isclose(other, tr.counted_impacts[0].t, rel_tol=1e-3)  # the two edges differ


def test_a_solid_is_checked_where_it_is_made():
    with pytest.raises(InputError, match="vertices"):
        Solid(vertices=((0, 0, 0), (1, 0, 0), (0, 1, 0)), inertia=((1, 0, 0), (0, 1, 0), (0, 0, 1)))
    with pytest.raises(InputError, match="inertia"):
        Solid(vertices=((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)), inertia=((1, 0, 0), (0, -1, 0), (0, 0, 1)))
    with pytest.raises(InputError, match="vertices"):
        Solid(vertices=((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, math.nan)), inertia=((1, 0, 0), (0, 1, 0), (0, 0, 1)))


def _isorock(*args, cwd):
    return subprocess.run([sys.executable, "-m", "isorock.validate.cli", *args], capture_output=True, text=True,
                          cwd=cwd, timeout=600)


def test_validate_a_statue_skips_the_engine_that_cannot_carry_it(tmp_path):
    # MJX builds the box H × B only (PyBullet and DART carry a statue since docs/statues.md, "PyBullet
    # on the statue's hull" and "DART on the statue's hull"); the refusal needs no jax
    out = tmp_path / "report"
    r = _isorock("validate", "--statue-example", "bust", "--mass", "80", "--base-mass", "150", "--period", "2",
                 "--damping-ratio", "0.15", "--quick", "--engines", "analytic", "mjx", "--out", str(out),
                 "--quiet", cwd=tmp_path)
    assert r.returncode in (0, 1), r.stderr
    text = (out / "report.md").read_text()
    assert "| mjx | SKIPPED | cannot carry this system: body:" in text
    assert "Engines skipped: mjx" in r.stdout.strip().splitlines()[-1]


def test_a_config_files_statue_table(tmp_path):
    """[statue] as --statue and its options: a mesh beside the file, whatever the folder it is run
    from; a key it does not know, or the block's height beside it, is one line and exit 2."""
    import trimesh
    box = trimesh.creation.box(extents=(300.0, 300.0, 1200.0))  # mm, standing on z = 0
    box.apply_translation((0, 0, 600.0))
    (tmp_path / "meshes").mkdir()
    box.export(tmp_path / "meshes" / "block.stl")
    config = tmp_path / "meshes" / "statue.toml"
    config.write_text('engines = ["analytic"]\nquick = true\nmotions = ["sine:amp=0.4,freq=2,cycles=1"]\n'
                      '[system]\nmass = 270.0\nfixed_base = true\n[statue]\nmesh = "block.stl"\nunit = "mm"\n')
    r = _isorock("validate", "--config", str(config), "--out", str(tmp_path / "r"), "--quiet", cwd=tmp_path)
    assert r.returncode in (0, 1), r.stderr
    import json
    body = json.loads((tmp_path / "r" / "metrics.json").read_text())["config"]["system"]["body"]
    # the box 0.3 × 0.3 × 1.2 m: its centre of mass 0.6 m up, 0.15 m from each edge
    assert body["centre_height"] == pytest.approx(0.6, rel=1e-9)
    assert body["lever_forward"] == pytest.approx(0.15, rel=1e-9) and body["lever_backward"] == pytest.approx(0.15, rel=1e-9)
    assert body["centroidal_inertia"] == pytest.approx(270.0 * (0.3**2 + 1.2**2) / 12, rel=1e-9)
    bad = tmp_path / "bad.toml"
    bad.write_text('[statue]\nmesh = "block.stl"\nunits = "mm"\n[system]\nmass = 3.0\nfixed_base = true\n')
    r = _isorock("validate", "--config", str(bad), "--out", str(tmp_path / "r2"), cwd=tmp_path)
    assert r.returncode == 2 and "statue.units: not known" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    r = _isorock("validate", "--config", str(config), "--height", "2", "--out", str(tmp_path / "r3"), cwd=tmp_path)
    assert r.returncode == 2 and "--height" in r.stderr and not (tmp_path / "r3").exists()


@pytest.mark.parametrize("table, says", [
    ('example = "bust"\nazimuth = nan\n', "statue.azimuth = nan: must be a finite number of degrees"),
    ('example = "bust"\nunit = "mm"\n', "statue.unit = 'mm': an example statue is made in metres; leave statue.unit out"),
    ('example = "bost"\n', "statue.example = 'bost': one of bust"),
    ('mesh = "missing.stl"\n', "statue.unit: "),
], ids=["azimuth", "unit-of-an-example", "example", "unit-missing"])
def test_a_config_files_statue_errors_name_its_keys(tmp_path, table, says):
    """An error in a config file's [statue] names the file's key (statue.azimuth), not the
    command-line option the user never typed (--azimuth)."""
    config = tmp_path / "statue.toml"
    config.write_text('[system]\nmass = 80.0\nfixed_base = true\n[statue]\n' + table)
    r = _isorock("validate", "--config", str(config), "--quick", "--engines", "analytic", "--out",
                 str(tmp_path / "r"), cwd=tmp_path)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert says in r.stderr and "--" not in r.stderr.split("error:", 1)[1], r.stderr


def test_a_statues_report_names_the_statue(tmp_path):
    """The report of a statue's mesh says what it is: "your statue" with its two edges, "the
    statue never lifted", not the block's words (oracle: the edges printed are the mesh's own,
    analytic.shape; the bust at 0.01 g lifts on neither base)."""
    from isorock.analytic import shape
    from isorock.analytic.system import PlanarBody
    config = tmp_path / "bust.toml"
    config.write_text('engines = ["analytic", "mujoco"]\nmotions = ["sine:amp=0.3,freq=2,cycles=2"]\nquick = true\n'
                      'pga = 0.01\n[system]\nmass = 80.0\nbase_mass = 150.0\nperiod = 2.0\ndamping_ratio = 0.15\n'
                      '[statue]\nexample = "bust"\nazimuth = 0\n')
    r = _isorock("validate", "--config", str(config), "--out", str(tmp_path / "r"), "--quiet", cwd=tmp_path)
    assert r.returncode in (0, 1), r.stderr
    text = (tmp_path / "r" / "report.md").read_text()
    body = PlanarBody.from_resting(shape.load_statue(example="bust", mass=80.0).along(0.0))
    assert f"your statue (m 80 kg; centre of mass {body.centre_height:.3g} m up" in text
    assert f"α₊ {body.alpha(1):.4g} and α₋ {body.alpha(-1):.4g} rad" in text
    assert "the statue never lifted on the fixed base" in text and "the same statue on a fixed base" in text
    assert "the block never lifted" not in text and "no engine lifted the block" not in text
    assert "the statue never lifted" in r.stdout.strip().splitlines()[-1]


def test_a_statue_that_leaves_its_plane_is_outside_the_model_not_slid():
    """The bust shaken along its square plinth's diagonal rocks on a corner and rolls off the
    plane the model of two edges rocks in (roll and yaw of its hull, a free body, measured while
    it rocks): its run says so ('outside-model', not judged), where the planar pivot slip read
    the roll as a slide. Shaken across an edge (0°: its plane of symmetry) it stays in its plane
    (oracle: the mirror symmetry; MuJoCo's out-of-plane motion there is roundoff)."""
    import math
    from dataclasses import replace

    from isorock.analytic import shape
    from isorock.analytic.motion import GroundMotion
    from isorock.analytic.system import PlanarBody, System
    from isorock.validate.core.cases import pulse_for
    from isorock.validate.core.measure import PLANE_LEFT
    from isorock.validate.core.plan import simulate
    resting = shape.load_statue(example="bust", mass=80.0)
    out = {}
    for azimuth in (0.0, 45.0):
        body = PlanarBody.from_resting(resting.along(math.radians(azimuth)))
        system = replace(System.fixed(**body.box, mass=80.0), body=body)
        motion = GroundMotion.from_pulse(pulse_for(system, "sine", 1.0, 2.0, 1.0))
        out[azimuth] = simulate(system, motion, engine="mujoco")
    assert out[0.0].extras["out_of_plane_max"] < 1e-6 and str(out[0.0].status) != "outside-model"
    diagonal = out[45.0]
    assert diagonal.extras["out_of_plane_max"] > PLANE_LEFT
    assert str(diagonal.status) == "outside-model" and "left its plane" in diagonal.message
