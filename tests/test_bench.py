"""The bench's machinery on a tiny configuration: errors measured against the tight
reference are small for the analytic engines, and the outputs are written whole."""
import json
import math

import pytest

from isorock.analytic import paper_system
from isorock.validate.tools import bench
from isorock.validate.cli.main import main
from isorock.validate.core.scenarios import Scenario


def test_quick_analytic_bench_writes_tables(tmp_path, capsys, monkeypatch):
    # one short scenario keeps this a test of the machinery, not a timing
    sc = Scenario("free-rocking", paper_system(fixed_base=True), "none", 2.0, 0.5)
    monkeypatch.setattr(bench, "bench_scenarios", lambda quick: [sc])
    out = tmp_path / "b"
    assert main(["bench", "--quick", "--engines", "analytic", "--out", str(out)]) == 0
    data = json.loads((out / "bench.json").read_text())
    rows = data["rows"]
    assert [r["setting"] for r in rows] == ["rtol=0.0001", "rtol=1e-07", "rtol=1e-10"]
    for r in rows:
        # every impact of the analytic model is the closed-form map, whatever the tolerance
        assert r["beta_error_max"] < 1e-12 and r["impacts"] == r["impacts_ref"]
        assert r["history_rms"] < 1e-6 and not r["parted"]
    for name in ("bench.md", "bench.csv", "bench.png"):
        assert (out / name).stat().st_size > 0
    assert "Fastest setting" in (out / "bench.md").read_text()


def test_unknown_engine_is_bad_input(tmp_path, capsys):
    assert main(["bench", "--engines", "ode45", "--out", str(tmp_path / "x")]) == 2
    assert not (tmp_path / "x").exists()


def test_presets_are_rows_of_their_own(tmp_path, monkeypatch):
    sc = Scenario("free-rocking", paper_system(fixed_base=True), "none", 1.0, 0.5)
    monkeypatch.setattr(bench, "bench_scenarios", lambda quick: [sc])
    out = tmp_path / "b"
    assert main(["bench", "--quick", "--engines", "analytic:default", "analytic:conservative", "--out", str(out)]) == 0
    rows = json.loads((out / "bench.json").read_text())["rows"]
    assert [(r["engine"], r["setting"]) for r in rows] == [("analytic:default", "default"),
                                                          ("analytic:conservative", "conservative")]
    md = (out / "bench.md").read_text()
    assert "| analytic:default | default |" in md and "| analytic:conservative | conservative |" in md


@pytest.mark.parametrize("engines, named", [(["mujoco:warp"], "'warp'"), (["mujoco:fast,ode45"], "'ode45'")])
def test_an_unknown_engine_or_preset_is_one_line_and_exit_2(tmp_path, capsys, engines, named):
    assert main(["bench", "--engines", *engines, "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and named in err and ("its presets: default" in err or "must be one of" in err)
    assert not (tmp_path / "x").exists()


def test_an_engine_and_its_former_name_are_one_series():
    """`analytic-fast` is the former name of `analytic` (the same spec in the registry):
    bench runs it once, by default and when both are named."""
    from isorock.validate.core.engines import ALIASES, campaign_engines, get_engine
    for alias, name in ALIASES.items():
        assert get_engine(alias).spec is get_engine(name).spec  # the oracle: the registry's own objects
    assert not set(ALIASES) & set(campaign_engines())
    default = bench.bench_engines()
    assert len({get_engine(e.partition(":")[0]).spec.name for e in default}) == len(default)
    assert bench.bench_engines(["analytic", "analytic-fast", "analytic-fast:conservative"]) == \
        ["analytic", "analytic:conservative"]


def test_a_setting_past_the_run_budget_is_a_row_that_says_so(monkeypatch):
    """Issue 24 item 13: bench's runs had no budget (a slow rung of a ladder held the
    command without an end). Past RUN_BUDGET_S the rung is a row saying it was stopped,
    with no speed or error claimed for it, and the bench goes on."""
    from isorock.analytic import limits
    from isorock.analytic.system import paper_system
    from isorock.validate.core.engines import get_engine
    from isorock.validate.core.scenarios import Scenario
    from isorock.validate.tools.bench import fastest, markdown, measure
    monkeypatch.setattr(limits, "RUN_BUDGET_S", 0.5)
    sc = Scenario("free-rocking", paper_system(fixed_base=True), "none", 600.0, theta0_over_alpha=0.3)
    ref = get_engine("analytic").simulate(sc.system, None, duration=5.0, theta0=sc.theta0)
    row = measure("bullet", "default", get_engine("bullet").settings(), sc, ref, 3)
    assert "budget of 0.5 s" in row["stopped"]
    assert row["beta_error_max"] is None and math.isnan(row["sim_per_wall"])
    assert fastest([row], "bullet", 1.0) is None
    assert "stopped" in markdown([row], {})
