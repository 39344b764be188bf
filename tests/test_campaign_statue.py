"""A statue's own mesh in a campaign file (issue 36): [systems] statue = {mesh, unit | example,
density} and azimuth, the statue's two edges along each direction in every case.

Oracles: the block H × B (a box's mesh is that block: the same rows, to 1e-12), the exact
model run on its own (analytic.shape and System, not the campaign), and the file's
content (a changed mesh is new work)."""
import math

import pyarrow.parquet as pq
import pytest

from isorock.analytic.errors import InputError
from isorock.validate.tools.campaign.run import run_campaign
from isorock.validate.tools.campaign.spec import load_spec

trimesh = pytest.importorskip("trimesh")

PULSES = ('[motions]\ntype = "pulse"\npulse = "sine"\ncycles = 1\nfrequency_ratio = [1.0, 3.0]\n'
          'amplitude_ratio = [1.5, 3.0, 6.0]\n[[engines]]\nname = "analytic"\n')
ISOLATED = 'base = ["fixed", "isolated"]\nbase_mass = 300.0\nperiod = 2.0\ndamping_ratio = 0.1\n'


def _box(path, extents_mm):
    box = trimesh.creation.box(extents=extents_mm)
    box.apply_translation((0, 0, extents_mm[2] / 2))
    box.export(path)


def _rows(spec_path, out):
    run_campaign(load_spec(spec_path), out, products=False)
    return pq.read_table(out / "results.parquet").to_pylist()


def test_a_box_mesh_runs_as_the_block_it_is(tmp_path):
    """A box 0.3 × 0.5 × 1.2 m read from its STL (mm), shaken along x and along y, is the block
    H 1.2 × B 0.3 and the block H 1.2 × B 0.5: every row's verdict and θmax/α the same."""
    _box(tmp_path / "box.stl", (300.0, 500.0, 1200.0))
    (tmp_path / "statue.toml").write_text('[systems]\nstatue = { mesh = "box.stl", unit = "mm" }\n'
                                          'azimuth = [0, 90]\nmass = 270.0\n' + ISOLATED + PULSES)
    (tmp_path / "block.toml").write_text('[systems]\nheight = 1.2\nwidth = [0.3, 0.5]\nmass = 270.0\n'
                                         + ISOLATED + PULSES)
    statue = _rows(tmp_path / "statue.toml", tmp_path / "s")
    block = _rows(tmp_path / "block.toml", tmp_path / "b")
    assert len(statue) == len(block) == 2 * 2 * 6
    by_width = {}
    for r in block:
        by_width.setdefault(round(r["width"], 9), []).append(r)
    for azimuth, width in ((0.0, 0.3), (90.0, 0.5)):
        mine = [r for r in statue if r["azimuth"] == azimuth]
        theirs = by_width[width]
        assert all(r["statue"] == "box.stl" for r in mine)
        for a, b in zip(mine, theirs):
            assert a["base"] == b["base"] and a["overturned"] == b["overturned"]
            assert a["theta_max_over_alpha"] == pytest.approx(b["theta_max_over_alpha"], rel=1e-9, abs=1e-12)
            assert a["width"] == pytest.approx(width, rel=1e-12)


def test_each_direction_is_the_statues_own_two_edges(tmp_path):
    """The bust along 0° and 180°: its two edges swap (b₊ at 0° is b₋ at 180°); each row is the
    exact model run on its own on that System (analytic.shape → PlanarBody → System.body)."""
    from dataclasses import replace

    from isorock.analytic import shape
    from isorock.analytic.motion import GroundMotion
    from isorock.analytic.system import PlanarBody, System
    from isorock.validate.core.cases import pulse_for
    from isorock.validate.core.plan import simulate
    (tmp_path / "bust.toml").write_text('[systems]\nstatue = { example = "bust" }\nazimuth = [0, 180]\nmass = 80.0\n'
                                        'base = "fixed"\n' + PULSES)
    rows = _rows(tmp_path / "bust.toml", tmp_path / "o")
    resting = shape.load_statue(example="bust", mass=80.0)
    at0 = PlanarBody.from_resting(resting.along(0.0))
    at180 = PlanarBody.from_resting(resting.along(math.pi))
    assert at0.lever_forward == pytest.approx(at180.lever_backward, rel=1e-9)
    assert at0.lever_forward != pytest.approx(at0.lever_backward, rel=1e-3)  # the bust's edges differ
    for row in rows:
        body = at0 if row["azimuth"] == 0.0 else at180
        system = replace(System.fixed(**body.box, mass=80.0), body=body)
        pulse = pulse_for(system, "sine", row["frequency_ratio"], row["amplitude_ratio"], 1.0)
        tr = simulate(system, GroundMotion.from_pulse(pulse), engine="analytic", duration=row["duration"])
        assert row["overturned"] == tr.overturned
        assert row["theta_max_over_alpha"] == pytest.approx(tr.summary()["theta_max_over_alpha"], rel=1e-9)
    overturned = {a: sum(r["overturned"] for r in rows if r["azimuth"] == a) for a in (0.0, 180.0)}
    assert overturned[0.0] != overturned[180.0] or any(  # the direction matters somewhere
        a["theta_max_over_alpha"] != pytest.approx(b["theta_max_over_alpha"], rel=1e-6)
        for a, b in zip([r for r in rows if r["azimuth"] == 0.0], [r for r in rows if r["azimuth"] == 180.0]))


def test_a_changed_mesh_is_new_work_and_the_block_keeps_its_ids(tmp_path):
    """Chunks are named by what is computed: the same file name with other content is other
    work; a block campaign's chunk ids are what they were before statues were columns."""
    from isorock.validate.core.chunks import make_tasks
    spec_text = '[systems]\nstatue = { mesh = "box.stl", unit = "mm" }\nmass = 270.0\nbase = "fixed"\n' + PULSES
    (tmp_path / "s.toml").write_text(spec_text)
    ids = []
    for extents in ((300.0, 500.0, 1200.0), (300.0, 500.0, 1300.0)):
        _box(tmp_path / "box.stl", extents)
        spec = load_spec(tmp_path / "s.toml")
        ids.append({t.id for t in make_tasks(spec.cases(), spec.engines, analytic_chunk=500, contact_chunk=4)})
        assert spec.systems["azimuth"] == (0.0,) or spec.systems["azimuth"] == (180.0,)  # it tips first across x
    assert ids[0].isdisjoint(ids[1])


@pytest.mark.parametrize("systems, says", [
    ('statue = { example = "bust" }\nheight = 2.0\n', "height: the statue's mesh gives its shape"),
    ('height = 1.0\nwidth = 0.3\nazimuth = 30\n', "azimuth: the direction a statue's mesh is shaken along"),
    ('statue = { example = "bust" }\nazimuth = [0, 400]\n', "systems.azimuth = 400.0: must be degrees"),
    ('statue = { example = "bust", density = 2000 }\nmass = 80\n', "mass: the statue's statue.density"),
    ('statue = { mesh = "none.stl" }\n', "systems.statue.unit: "),
    ('statue = { mesh = "none.stl", unit = "mm" }\n', "systems.statue.mesh = "),
    ('statue = { example = "bust", unit = "mm" }\n', "systems.statue.unit = 'mm': an example statue is made in metres"),
    ('statue = { example = "bust", shape = "x" }\n', "systems.statue.shape: unknown key"),
    ('statue = { example = "bust" }\nfriction = 0.5\n', "friction: the sliding model takes the block"),
    ('statue = { mesh = "", unit = "mm" }\n', "systems.statue.mesh = '': must be a mesh file's path"),
], ids=["height", "azimuth-alone", "azimuth-range", "density-and-mass", "unit-missing", "no-file", "unit-of-example",
        "unknown-key", "friction", "empty-path"])
def test_a_bad_statue_table_is_one_line(tmp_path, systems, says):
    (tmp_path / "c.toml").write_text("[systems]\n" + systems + PULSES)
    with pytest.raises(InputError) as e:
        load_spec(tmp_path / "c.toml")
    assert says in str(e.value) and "\n" not in str(e.value)


def test_an_engine_that_cannot_carry_the_statue_is_refused_before_any_run(tmp_path):
    # MJX builds the symmetric box only (every other contact engine carries a statue on a campaign's
    # fixed and linear bases since DART does: docs/statues.md); the check needs no jax
    (tmp_path / "c.toml").write_text('[systems]\nstatue = { example = "bust" }\nmass = 80.0\n'
                                     + PULSES.replace('name = "analytic"', 'name = "mjx"'))
    with pytest.raises(InputError, match="two different edges"):
        load_spec(tmp_path / "c.toml")
