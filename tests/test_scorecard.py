"""`isorock scorecard`: every engine and preset on the same rows, each from its tool; a budget
said first and kept; what does not fit or cannot run says 'not run' and why; outputs whole or
absent; and the committed docs/engines.md and the README's table are the command's output.

The oracles are the tools themselves, called here directly on the same grid (atlas.build), and
the committed JSON re-rendered (nobody edits docs/engines.md or the README's table by hand).
About 45 s on 2 cores (40 s with -n auto), most of it the one quick run of analytic, MuJoCo and PyBullet."""
from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from isorock.validate.cli import scorecard as sc
from isorock.validate.cli.main import main
from isorock.validate.tools.atlas import Grid, build

ROOT = Path(__file__).resolve().parents[1]
#: the quick run's budget (s); CI's whole suite must stay under ~5 minutes on 2 cores
BUDGET = 45.0
QUICK_ENGINES = ("analytic:default", "mujoco:default", "bullet:default")


def _readme_copy(tmp_path) -> Path:
    readme = tmp_path / "README.md"
    readme.write_text("# mine\n\nbefore\n\n" + sc.README_BEGIN + "\nold table\n" + sc.README_END + "\n\nafter\n",
                      encoding="utf-8")
    return readme


class EstimateClock(sc.Clock):
    """The budget spent as the plan's estimates, not as the machine's seconds: what the plan
    admits, and what it leaves out, is then the same on a quiet machine and a loaded one (the
    wall clock's own cut is tested with a budget of 1 s, below). The real wall time of a run is a
    measurement, said by the command (docs/engines.md), not asserted here."""

    def __init__(self, budget: float):
        super().__init__(budget)
        self.spent = 0.0

    @property
    def elapsed(self) -> float:
        return self.spent

    def charge(self, estimate: float) -> None:
        self.spent += estimate


def _quick_run(tmp, monkeypatch):
    """One quick scorecard of the fast engines' defaults, as CI runs it: (data, stderr, wall s, paths)."""
    import contextlib
    import io
    monkeypatch.setattr(sc, "Clock", EstimateClock)
    atlases = []  # what the atlas tool itself returned to the scorecard: the rows its cells are checked against

    def atlas_build(*args, **kwargs):
        atlases.append(dict(build(*args, **kwargs), grid=args[1]))
        return atlases[-1]
    monkeypatch.setattr(sc, "atlas_build", atlas_build)
    readme = _readme_copy(tmp)
    md, js = tmp / "engines.md", tmp / "engines.json"
    err = io.StringIO()
    start = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["scorecard", "--quick", "--engines", *QUICK_ENGINES, "--budget", f"{BUDGET:g}",
                     "--out", str(md), "--json", str(js), "--readme", str(readme)])
    wall = time.perf_counter() - start
    assert code == 0, err.getvalue()[-2000:]
    return json.loads(js.read_text()), err.getvalue(), wall, {"md": md, "json": js, "readme": readme,
                                                              "atlases": atlases}


def check_the_budget_is_said_before_the_work_and_kept(quick):
    data, err, wall, _ = quick
    lines = [x for x in err.splitlines() if x.startswith("scorecard:")]
    assert lines[0].startswith(f"scorecard: budget {BUDGET:g} s (quick); planned")
    assert "estimated" in lines[0]
    # the estimates of what ran fit the budget (the wall seconds are the machine's, not asserted)
    assert data["budget_s"] == BUDGET and 0 < data["wall_s"] <= BUDGET
    assert data["effort"] == "quick" and data["cells"] == len(sc.QUICK.heights) * len(sc.QUICK.mass_ratios) * len(
        sc.QUICK.slenderness)


def check_every_cell_is_measured_or_says_why_not(quick):
    data, _, _, _ = quick
    assert [r["label"] for r in data["rows"]] == list(QUICK_ENGINES)
    for r in data["rows"]:
        for m in sc.MEASURES:
            cell = r[m]
            assert isinstance(cell, dict) and cell, (r["label"], m)
            if "not_run" in cell:
                assert cell["not_run"].startswith("not run: ") and len(cell["not_run"]) > len("not run: ") + 10
            else:
                assert not any(v is None for k, v in cell.items() if k in ("worst_beta_error", "verdict", "runs")), cell
    # the fast engines' atlas and the analytic model's every measure fit a 45 s budget
    assert all("not_run" not in r["atlas"] for r in data["rows"])
    assert all("not_run" not in data["rows"][0][m] for m in sc.MEASURES)
    md = (quick[3]["md"]).read_text()
    assert "| — |" not in md.replace("| — (", "")  # never a bare blank in a cell


def check_the_atlas_cells_are_the_atlas_tools_worst_values_on_the_same_grid(quick):
    data, _, _, paths = quick
    grid = Grid(tuple(data["grid"]["slenderness"]), tuple(data["grid"]["mass_ratios"]),
                tuple(data["grid"]["heights_m"]))
    assert grid.cells() and len(grid.cells()) == data["cells"]
    assert paths["atlases"] and all(atlas["grid"] == grid for atlas in paths["atlases"])  # the grid it says it ran
    # the atlas tool's own rows (its output, caught on the way to the scorecard): the worst values
    # are recomputed from them here, not read from the scorecard's aggregation
    rows = [r for atlas in paths["atlases"] for r in atlas["rows"]]
    presets = [s for atlas in paths["atlases"] for s in atlas["presets"]]
    assert {s["engine"] for s in presets} == {r["label"] for r in data["rows"]}
    for s in presets:
        row = next(r for r in data["rows"] if r["label"] == s["engine"])["atlas"]
        # the worst over the grid, recomputed here from the tool's own rows: the oracle
        judged = [r for r in rows if r["engine"] == s["engine"] and r["status"] == "ok"]
        assert len(judged) == len(grid.cells())
        assert row["worst_beta_error"] == pytest.approx(max(abs(r["beta_error"]) for r in judged), rel=1e-12)
        assert row["worst_t1_error"] == pytest.approx(max(abs(r["t1_error"]) for r in judged), rel=1e-12)
        assert row["impacts_lost"] == sum(r["impacts_lost"] for r in judged)
        assert row["judged"] == len(judged) and row["complete"]


def check_the_files_agree_with_each_other_and_the_readme_keeps_the_rest(quick):
    data, _, _, paths = quick
    assert paths["md"].read_text(encoding="utf-8") == sc.markdown(data)
    text = paths["readme"].read_text(encoding="utf-8")
    assert text.startswith("# mine\n\nbefore\n\n") and text.endswith("\n\nafter\n") and "old table" not in text
    assert sc.readme_block(text) == sc.readme_table(data)
    assert data["command"].startswith("isorock scorecard --quick --engines analytic:default")
    assert "## Summary" in paths["md"].read_text() and "## How this file was made" in paths["md"].read_text()


def test_a_quick_scorecard_of_the_fast_engines(tmp_path, monkeypatch):
    """One run (CI's: the fast engines' defaults, --quick, a 45 s budget), checked four ways; one
    test, so that pytest-xdist never runs it twice on the two cores."""
    quick = _quick_run(tmp_path, monkeypatch)
    check_the_budget_is_said_before_the_work_and_kept(quick)
    check_every_cell_is_measured_or_says_why_not(quick)
    check_the_atlas_cells_are_the_atlas_tools_worst_values_on_the_same_grid(quick)
    check_the_files_agree_with_each_other_and_the_readme_keeps_the_rest(quick)


def test_the_committed_scorecard_and_readme_table_are_the_commands_output():
    """docs/engines.md and the README's table are re-rendered from docs/engines.json, which the
    same command wrote: an edit by hand to either fails here."""
    data = json.loads((ROOT / "docs" / "engines.json").read_text(encoding="utf-8"))
    assert data["command"].startswith("isorock scorecard") and "--readme README.md" in data["command"]
    assert (ROOT / "docs" / "engines.md").read_text(encoding="utf-8") == sc.markdown(data)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert sc.readme_block(readme) == sc.readme_table(data)
    # every engine's defaults have a row in the README's table, measured or with the reason
    names = {r["engine"] for r in data["rows"]}
    assert {"analytic", "mujoco", "bullet", "dart", "mjx"} <= names


def test_an_engine_that_cannot_be_loaded_is_not_run_with_the_reason(monkeypatch):
    from isorock.validate.core import engines
    real = engines.get_engine

    def get_engine(name):
        if name == "dart":
            raise ImportError("No module named 'dartpy' (the test's)")
        return real(name)
    monkeypatch.setattr(engines, "get_engine", get_engine)
    from isorock.validate.cli import atlas
    for caller in (sc, atlas):  # as the scorecard and the atlas's label expansion call it
        monkeypatch.setattr(caller, "get_engine", get_engine)
    labels = sc.labels_of(["analytic:default", "dart"])
    assert labels == ["analytic:default", "dart"]
    data = sc.build(labels, sc.QUICK, budget=1.0)
    dart = next(r for r in data["rows"] if r["engine"] == "dart")
    for m in sc.MEASURES:
        assert "cannot be loaded here" in dart[m]["not_run"] and "dartpy" in dart[m]["not_run"]
    table = "\n".join(sc.table_lines(json.loads(json.dumps(data))))
    assert "dartpy" in table


def test_work_over_the_budget_is_not_run_with_its_estimate_and_the_file_is_whole(tmp_path, capsys):
    out, js = tmp_path / "engines.md", tmp_path / "engines.json"
    assert main(["scorecard", "--quick", "--engines", "mujoco:default", "--budget", "1", "--out", str(out),
                 "--json", str(js)]) == 0
    err = capsys.readouterr().err
    assert "scorecard: budget 1 s (quick); planned 0 measurements" in err
    data = json.loads(js.read_text())
    (row,) = data["rows"]
    for m in ("atlas", "speed", "validate", "stress"):
        assert row[m]["not_run"].startswith("not run: estimated ") and "over the --budget of 1 s" in row[m]["not_run"]
    assert out.read_text() == sc.markdown(data)


@pytest.mark.parametrize("args, named", [
    (["--budget", "0"], "budget = 0.0"),
    (["--budget", "nan"], "budget = nan"),
    (["--budget", "1e9"], "budget = 1000000000.0"),
    (["--budget", "soon"], "--budget"),
    (["--engines", "mujoco:warp"], "'warp'"),
    (["--engines", "ode45"], "'ode45'"),
    (["--workers", "0"], "workers"),
])
def test_bad_flags_exit_2_with_one_line_and_write_nothing(tmp_path, capsys, args, named):
    out, js = tmp_path / "engines.md", tmp_path / "engines.json"
    assert main(["scorecard", "--quick", *args, "--out", str(out), "--json", str(js)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and named in err, err
    assert not out.exists() and not js.exists()


def test_a_readme_without_the_markers_is_refused_before_any_work(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_text("# mine\n\nno markers\n")
    out = tmp_path / "engines.md"
    start = time.perf_counter()
    assert main(["scorecard", "--quick", "--budget", "600", "--out", str(out), "--readme", str(readme)]) == 2
    assert time.perf_counter() - start < 10  # refused before the work, not after it
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "readme = " in err and "marker" in err
    assert readme.read_text() == "# mine\n\nno markers\n" and not out.exists()


def test_a_refused_output_leaves_the_earlier_scorecard_whole(tmp_path, capsys):
    out = tmp_path / "engines.md"
    out.write_text("an earlier scorecard\n")
    folder = tmp_path / "a-folder"
    folder.mkdir()
    assert main(["scorecard", "--quick", "--budget", "1", "--out", str(out), "--json", str(folder)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "json = " in err and "folder" in err
    assert out.read_text() == "an earlier scorecard\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-folder", "engines.md"]  # nothing staged left


# --- --check: the committed scorecard made again and compared (what CI runs) -------------------

def _committed() -> dict:
    return json.loads((ROOT / "docs" / "engines.json").read_text(encoding="utf-8"))


def _measured_row(data: dict, measure: str) -> dict:
    return next(r for r in data["rows"] if r["engine"] != "analytic" and "not_run" not in r[measure])


def test_drift_names_each_cell_a_reader_would_see_change_and_nothing_else():
    """The oracle is the edit made here by hand to a copy of the committed scorecard: each changed
    cell is named once, a change below the 3 significant digits the scorecard shows and a speed are
    not, and a measure made in one of the two only, for the budget or an engine not installed in
    both places, is listed apart, not drift."""
    import copy
    old = _committed()
    assert sc.drift(old, copy.deepcopy(old)) == ([], [], len(old["rows"]) * len(sc.CHECKED_COLUMNS))

    new = copy.deepcopy(old)
    atlas_row = _measured_row(new, "atlas")
    atlas_row["atlas"]["worst_beta_error"] *= 1.1  # seen: the scorecard shows 3 significant digits
    speed_row = _measured_row(new, "speed")
    speed_row["speed"]["alone_isolated"] *= 3.0  # the machine's, never compared
    validate_row = _measured_row(new, "validate")
    validate_row["validate"]["failed"] += 1
    drifted, unmeasured, _ = sc.drift(old, new)
    assert len(drifted) == 2 and not unmeasured, drifted
    assert drifted[0].startswith(f"{atlas_row['label']}, atlas: worst β") or drifted[1].startswith(
        f"{atlas_row['label']}, atlas: worst β")
    assert any(d.startswith(f"{validate_row['label']}, validate") for d in drifted)

    new = copy.deepcopy(old)
    _measured_row(new, "atlas")["atlas"]["worst_beta_error"] *= 1 + 1e-6  # below what is shown
    assert sc.drift(old, new)[0] == []

    new = copy.deepcopy(old)
    row = _measured_row(new, "stress")
    row["stress"] = {"not_run": "not run: the stress tool failed (RuntimeError: the test's)"}
    assert sc.drift(old, new)[0] and not sc.drift(old, new)[1]  # a measure that failed: drift
    row["stress"] = {"not_run": "not run: estimated 46 s, 12 s of the --budget of 1200 s left when its turn came"}
    assert not sc.drift(old, new)[0] and len(sc.drift(old, new)[1]) == 1  # the clock, on a busier machine
    row["stress"] = {"not_run": "not run: estimated 46 s, over the --budget of 1200 s with the work before it"}
    drifted, one_only, compared = sc.drift(old, new)
    assert not drifted and len(one_only) == 1 and row["label"] in one_only[0]
    assert compared == len(old["rows"]) * len(sc.CHECKED_COLUMNS) - 1
    assert sc.drift(new, old)[:2] == ([], one_only)  # measured now, over the budget in the file: the same
    row["stress"] = {"not_run": "not run: the engine cannot be loaded here (No module named 'warp')"}
    assert sc.drift(old, new)[0] == [] and len(sc.drift(old, new)[1]) == 1  # an optional engine not installed

    new = copy.deepcopy(old)  # not made in either, for another reason in each: apart where one is the engine's absence
    row = next(r for r in new["rows"] if "no model of the rock" in r["experiments"].get("not_run", ""))
    row["experiments"] = {"not_run": "not run: the engine cannot be loaded here (No module named 'warp')"}
    drifted, one_only, _ = sc.drift(old, new)
    assert not drifted and len(one_only) == 1 and row["label"] in one_only[0]
    row["experiments"] = {"not_run": "not run: the experiments tool failed (ValueError: the test's)"}
    assert len(sc.drift(old, new)[0]) == 1  # any other new reason is drift

    new = copy.deepcopy(old)  # the similarity column is the atlas's: apart with it
    row = _measured_row(new, "atlas")
    row["atlas"] = {"not_run": "not run: estimated 42 s, over the --budget of 1200 s with the work before it"}
    drifted, one_only, _ = sc.drift(old, new)
    assert not drifted and [x.split(",")[1].split(":")[0].strip() for x in one_only] == ["atlas", "similarity"]

    new = copy.deepcopy(old)  # the numbers of a 'not run' reason (an estimate) are not the engine's
    not_run = next(r for r in new["rows"] if "estimated" in r["atlas"].get("not_run", ""))
    not_run["atlas"]["not_run"] = not_run["atlas"]["not_run"].replace("1", "2")
    assert sc.drift(old, new)[0] == []
    new["rows"].pop()
    assert sc.drift(old, new)[0] == [f"{old['rows'][-1]['label']}: a row only in the file"]


def test_check_makes_the_files_scorecard_again_and_exits_1_on_drift(tmp_path, monkeypatch, capsys):
    """--check takes its engines, effort and budget from the file, writes nothing unless asked,
    and exits 1 naming the cell that drifted (the build is the file itself here, or a copy with one
    cell changed: what the engines make is the committed scorecard's own test above)."""
    import copy
    old = _committed()
    path = tmp_path / "engines.json"
    path.write_text(json.dumps(old), encoding="utf-8")
    calls = []

    def build(labels, effort, *, budget, workers, quiet, command):
        calls.append((labels, effort.name, budget, command))
        return made
    monkeypatch.setattr(sc, "build", build)
    monkeypatch.chdir(tmp_path)  # the default --out (docs/engines.md) would be here: it must not be written
    made = copy.deepcopy(old)
    assert main(["scorecard", "--check", str(path), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert calls == [([r["label"] for r in old["rows"]], old["effort"], old["budget_s"], old["command"])]
    assert "0 drifted" in out and "wrote nothing" in out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["engines.json"]

    made = copy.deepcopy(old)
    row = _measured_row(made, "atlas")
    row["atlas"]["impacts_lost"] += 1
    md = tmp_path / "again.md"
    assert main(["scorecard", "--check", str(path), "--quiet", "--out", str(md)]) == 1
    out = capsys.readouterr().out
    assert f"drifted: {row['label']}, atlas" in out and "1 drifted" in out
    assert md.read_text(encoding="utf-8") == sc.markdown(made)  # what was named is written, whole
    assert json.loads(path.read_text(encoding="utf-8")) == old  # the file checked is never touched


@pytest.mark.parametrize("args, named", [
    (["--quick"], "--quick = True"),
    (["--budget", "600"], "--budget = 600.0"),
    (["--engines", "mujoco"], "--engines = ['mujoco']"),
])
def test_check_refuses_what_the_file_decides_in_one_line(tmp_path, capsys, args, named):
    assert main(["scorecard", "--check", str(ROOT / "docs" / "engines.json"), *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and named in err, err
