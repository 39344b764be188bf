"""`isorock validate` under a record pair (issue 36; validate/tools/pair_report.py): each engine that
runs two horizontal components judged on turning the pair and the statue together, an exact
symmetry of the physics (the same ground acceleration in the statue's own frame), by its own
pair_turned_* rows of the one table. The oracle is that symmetry: a wrong turn (the statue left
unturned while its pair turns) must fail; the differences are computed again here from the runs
the report names, apart from validate/core/turned_pair.py."""
from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("mujoco")
pytest.importorskip("trimesh")

from isorock.validate.cli.main import main  # noqa: E402
from isorock.validate.core import turned_pair  # noqa: E402
from isorock.validate.core.tolerances import tolerance  # noqa: E402

#: the bust on a fixed base under the tests' sine pair (tests/test_two_components.py: it rocks to 0.18 α)
BUST_PAIR = ["--statue-example", "bust", "--mass", "80", "--fixed-base", "--motion", "sine:amp=0.7,freq=2,cycles=1",
             "--motion-transverse", "sine:amp=0.63,freq=1.6,cycles=1", "--quiet"]


def _validate(tmp_path, capsys, *more):
    code = main(["validate", *BUST_PAIR, "--out", str(tmp_path / "rep"), *more])
    out = capsys.readouterr().out.strip().splitlines()
    metrics = json.loads((tmp_path / "rep" / "metrics.json").read_text()) if (tmp_path / "rep").exists() else None
    return code, out, metrics


def test_mujoco_passes_the_turned_pair_and_the_report_says_what_was_not_run(tmp_path, capsys):
    """Every check made, each by MuJoCo's own row of the table; the analytic engine is named as not
    run, with why (the planar exact model, beside each engine, unjudged); the verdict is the last line
    and the report's first, the planar runs along each component beside."""
    code, out, m = _validate(tmp_path, capsys, "--engines", "analytic", "mujoco")
    assert code == 0 and out[-1] == m["verdict"] and out[-1].startswith("Result: all 3 checks passed"), out
    assert "analytic" in m["not_run"] and "planar" in m["not_run"]["analytic"]
    for c in m["checks"]:
        assert c["engine"] == "mujoco" and c["status"] == "pass" and c["limit"] == tolerance("mujoco", c["metric"]).limit
    assert {c["metric"] for c in m["checks"]} == set(turned_pair.METRICS) - {"pair_turned_travel"}  # a fixed base
    report = (tmp_path / "rep" / "report.md").read_text()
    assert m["verdict"] in report.splitlines()[2] and "exact planar model, second component alone along y" in report
    assert "](pair.png)" in report and (tmp_path / "rep" / "pair.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert m["two_components"]["mujoco"]["cannot_capture"] in report


def test_the_differences_are_the_runs_own(bust_runs):
    """turned_pair's history number recomputed from its two runs with plain NumPy: the total tilt from
    each quaternion's z axis, its history's largest difference over the peak."""
    runs = bust_runs
    tilts = []
    for tr in (runs.first, runs.turned):
        w, x, y, z = np.asarray(tr.extras["orientation"]).T
        # the body z axis (the rotation matrix's third column) and its angle from the vertical
        zx, zy, zz = 2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)
        tilts.append(np.arctan2(np.sqrt(zx * zx + zy * zy), zz))
    n = min(t.size for t in tilts)
    mine = np.max(np.abs(tilts[0][:n] - tilts[1][:n])) / np.max(tilts[0][:n])
    theirs = next(c.value for c in runs.checks if c.metric == "pair_turned_tilt_history")
    assert theirs == pytest.approx(mine, rel=1e-9)
    assert np.max(tilts[0]) > 0.15 * 0.39  # it rocked (its least α 0.394): the check tested something


@pytest.fixture(scope="module")
def bust_runs():
    """turned_pair's runs of MuJoCo on the bust's pair, from Python values (its module's API)."""
    from test_two_components import _statue_system

    from isorock.analytic import shape
    from isorock.analytic.motion import load_motion
    from isorock.validate.core.plan import make_plan
    standing = shape.standing(*shape.example_statue("bust"), mass=80.0)
    azimuth = shape.weakest_direction(standing)[0]
    system = _statue_system(standing, azimuth, False)
    pair = load_motion("sine:amp=0.7,freq=2,cycles=1").with_transverse(load_motion("sine:amp=0.63,freq=1.6,cycles=1"))
    plan = make_plan(system, pair, [("mujoco", None)], duration=2.0)
    return turned_pair.turned_runs(plan, standing, azimuth, turned_pair.TURN_DEG)["mujoco"]


def test_a_statue_left_unturned_while_its_pair_turns_fails(tmp_path, capsys, monkeypatch):
    """The counterfactual: the pair turned by 30° and the statue not (a wrong turn) is another
    problem, and the checks say so: exit 1, the verdict names the failed rows."""
    monkeypatch.setattr(turned_pair, "turned_system", lambda system, body, azimuth, turn: system)
    code, out, m = _validate(tmp_path, capsys, "--engines", "mujoco")
    failed = {c["metric"] for c in m["checks"] if c["status"] == "fail"}
    assert code == 1 and out[-1].startswith("Result: FAILED") and failed, out
    assert "pair_turned_tilt_history" in failed or "pair_turned_direction_deg" in failed


def test_a_pair_that_rocks_nothing_tests_nothing_and_says_so(tmp_path, capsys):
    """A pair too weak to lift the bust: the tilt's checks are 'not exercised', never passed."""
    code = main(["validate", "--statue-example", "bust", "--mass", "80", "--fixed-base", "--motion",
                 "sine:amp=0.05,freq=2,cycles=1", "--motion-transverse", "sine:amp=0.05,freq=1.6,cycles=1", "--quiet",
                 "--engines", "mujoco", "--out", str(tmp_path / "rep")])
    out = capsys.readouterr().out.strip().splitlines()
    m = json.loads((tmp_path / "rep" / "metrics.json").read_text())
    assert code == 0 and out[-1].startswith("Result: nothing was tested"), out
    assert {c["status"] for c in m["checks"]} == {"not exercised"}


@pytest.mark.parametrize("args, says", [
    (["--pair", "fema-p695:FF01", "--motion", "sine:amp=0.5,freq=2"], "--pair = 'fema-p695:FF01'"),
    (["--motion", "sine:amp=0.5,freq=2", "--motion", "sine:amp=0.4,freq=2", "--motion-transverse",
      "sine:amp=0.5,freq=2"], "--motion = ["),
    (["--motion", "sine:amp=0.5,freq=2", "--motion-transverse", "sine:amp=0.5,freq=2", "--engines", "analytic"],
     "--engines = analytic: none runs this pair"),
    (["--motion", "sine:amp=0.5,freq=2", "--motion-transverse", "sine:amp=0.5,freq=2", "--scales", "1,2,3"],
     "--scales: validate with a record pair runs no ensemble"),
    (["--motion", "sine:amp=0.5,freq=2", "--motion-transverse", "sine:amp=0.5,freq=2", "--quick"], "--quick:"),
])
def test_bad_pair_input_is_one_line_and_exit_2(tmp_path, capsys, args, says):
    code = main(["validate", "--statue-example", "bust", "--mass", "80", "--fixed-base", *args,
                 "--out", str(tmp_path / "rep")])
    err = capsys.readouterr().err
    assert code == 2 and says in err and err.count("\n") == 1, err
    assert not (tmp_path / "rep").exists()


def test_a_pair_without_a_system_is_one_line(tmp_path, capsys):
    code = main(["validate", "--motion", "sine:amp=0.5,freq=2", "--motion-transverse", "sine:amp=0.5,freq=2",
                 "--out", str(tmp_path / "rep")])
    err = capsys.readouterr().err
    assert code == 2 and "system:" in err and err.count("\n") == 1, err


def test_isorock_report_takes_a_pair_as_the_command_does(tmp_path):
    """The notebook API: the same pair's validation returned (and written where `out` is given),
    never the one-component report with the second component dropped."""
    import isorock
    v = isorock.report(statue_example="bust", mass=80, fixed_base=True, motion="sine:amp=0.7,freq=2,cycles=1",
                       motion_transverse="sine:amp=0.63,freq=1.6,cycles=1", engines=["mujoco"],
                       out=str(tmp_path / "rep"))
    assert v.passed and v.verdict.startswith("Result: all 3 checks passed") and "pair turned 30°" in v.checks()["scenario"][0]
    assert json.loads((tmp_path / "rep" / "metrics.json").read_text())["verdict"] == v.verdict
    assert set(v.results) == {"mujoco"} and v.results["mujoco"].turn_deg == turned_pair.TURN_DEG


def test_an_engine_without_rows_is_reported_unjudged_not_refused(bust_runs):
    """A plugin engine that runs a pair but brings no pair_turned_* rows: its numbers are reported and
    skipped with the reason (tolerances.unjudged), never an error after its runs, never a pass."""
    from isorock.analytic import shape
    standing = shape.standing(*shape.example_statue("bust"), mass=80.0)
    runs = turned_pair.judge("someones-engine", bust_runs.first, bust_runs.turned, bust_runs.probe, standing,
                             shape.weakest_direction(standing)[0], turned_pair.TURN_DEG)
    assert {c.status for c in runs.checks} == {"skip"} and all("no tolerance" in c.note for c in runs.checks)
    assert [c.value for c in runs.checks] == [c.value for c in bust_runs.checks]
