"""The bench's machinery on a tiny configuration: errors measured against the tight
reference are small for the analytic engines, and the outputs are written whole."""
import json

from isorock.analytic import paper_system
from isorock.validate import bench
from isorock.validate.cli import main
from isorock.validate.scenarios import Scenario


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
