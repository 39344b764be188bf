"""An engine in a package of its own (issue 37): the example plugin of examples/
isorock-engine-example, installed by pip into a folder of its own (never into this
environment), is found through its entry point and runs through `run`, `validate`, `atlas`
and `presets` with no change to isorock; judged by the limits it declares. Oracles: the
exact model (the plugin's β and θmax/α against the analytic engine's closed forms), and the
registry's refusals of a plugin that names a built-in engine or hands over something else."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "isorock-engine-example"
ISOROCK = [sys.executable, "-m", "isorock.validate.cli.main"]


@pytest.fixture(scope="module")
def plugin_path(tmp_path_factory) -> Path:
    """The example installed as a user installs it (pip, from its pyproject.toml), into a folder
    put on PYTHONPATH for the commands below: its entry point is read from its dist-info."""
    target = tmp_path_factory.mktemp("plugin")
    done = subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--target", str(target),
                           str(EXAMPLE)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    assert list(target.glob("isorock_engine_example-*.dist-info/entry_points.txt"))
    return target


def isorock(plugin_path, *args, cwd=None):
    env = {**os.environ, "PYTHONPATH": str(plugin_path)}
    return subprocess.run([*ISOROCK, *args], capture_output=True, text=True, env=env, cwd=cwd, timeout=600)


def test_run_finds_the_plugin_and_it_agrees_with_the_exact_model(plugin_path):
    done = isorock(plugin_path, "run", "--engine", "analytic,rk4,rk4:coarse", "--fixed-base", "--height", "2",
                   "--width", "0.7", "--mass", "3800", "--motion", "ricker:amp=0.5,freq=2", "--duration", "4",
                   "--json", "-", "--quiet")
    assert done.returncode == 0, done.stderr
    doc = json.loads(done.stdout)
    ref = doc["engines"]["analytic"]
    assert ref["impacts"] >= 3  # it rocks: the comparison means something
    for label in ("rk4", "rk4:coarse"):
        got, c = doc["engines"][label], doc["comparisons"][label]
        assert got["impacts"] == ref["impacts"] and got["overturned"] == ref["overturned"]
        assert abs(got["theta_max_over_alpha"] - ref["theta_max_over_alpha"]) < 0.02
        assert c["beta_error_median"] is not None and abs(c["beta_error_median"]) < 1e-6


def test_validate_judges_the_plugin_by_its_own_limits_and_skips_what_it_cannot_carry(plugin_path, tmp_path):
    out = tmp_path / "report"
    done = isorock(plugin_path, "validate", "--quick", "--motion", "ricker:amp=0.5,freq=1", "--scales", "0.8,1.0,2",
                   "--duration", "3", "--quiet", "--engines", "analytic", "rk4", "--workers", "1", "--out", str(out))
    assert done.returncode == 0, done.stderr
    m = json.loads((out / "metrics.json").read_text())
    mine = [c for c in m["checks"] if c["engine"] == "rk4"]
    judged = [c for c in mine if c["status"] == "pass"]
    assert len(judged) >= 10 and {"beta_rel_error", "theta_max_diff", "overturn_agree"} <= {c["metric"] for c in judged}
    beta = [c for c in judged if c["metric"] == "beta_rel_error"]
    assert all(c["limit"] == 1e-3 and "cubic" in c["reason"] for c in beta)  # the plugin's limit and its reason
    slides = [c for c in mine if "slides" in c["scenario"]]
    assert slides and all(c["status"] == "skip" for c in slides)
    assert any("cannot slip" in c["note"] for c in slides)
    assert "RK4 (plugin) agrees" in m["verdict"]


def test_atlas_and_presets_list_and_run_the_plugin(plugin_path, tmp_path):
    done = isorock(plugin_path, "presets")
    assert done.returncode == 0 and "rk4" in done.stdout and "coarse" in done.stdout, done.stdout[-2000:]
    out = tmp_path / "atlas"
    done = isorock(plugin_path, "atlas", "--engines", "rk4", "--quick", "--slenderness", "2.5", "--mass-ratios", "0,1",
                   "--heights", "1", "--workers", "1", "--out", str(out), "--quiet")
    assert done.returncode == 0, done.stderr
    presets = [r for r in json.loads((out / "atlas.json").read_text())["presets"] if r["engine_name"] == "rk4"]
    assert presets and all(r["complete"] and r["judged"] == 2 and r["worst_beta_error"] < 1e-6 for r in presets)


def _entry_points(monkeypatch, *points):
    from importlib.metadata import EntryPoint
    eps = [EntryPoint(name, value, "isorock.engines") for name, value in points]
    monkeypatch.setattr("importlib.metadata.entry_points", lambda group=None: eps if group == "isorock.engines" else [])


def test_a_plugin_that_names_a_built_in_engine_is_refused_and_said(monkeypatch):
    from isorock.validate.core import engines
    _entry_points(monkeypatch, ("mujoco", "somewhere:ENGINE"), ("toy", "somewhere:ENGINE"), ("a:b", "x:ENGINE"))
    found, refused = engines._plugins()
    assert found == {"toy": "somewhere:ENGINE"}
    assert "built-in engine 'mujoco'" in refused["mujoco"] and "no ':'" in refused["a:b"]


def test_a_plugin_that_hands_over_something_else_is_one_line(monkeypatch):
    from isorock.analytic.errors import InputError
    from isorock.validate.core import engines
    monkeypatch.setitem(engines.ENGINE_MODULES, "fake", "isorock.mujoco_models:ENGINE")
    monkeypatch.setitem(engines.PLUGINS, "fake", "isorock.mujoco_models:ENGINE")
    with pytest.raises(InputError) as e:
        engines.get_engine("fake")
    assert "must be an EngineSpec named 'fake'" in str(e.value) and "named 'mujoco'" in str(e.value)


def test_sweep_runs_the_plugin_and_stress_says_what_it_could_not_carry(plugin_path, tmp_path):
    """A campaign file names it like any engine; stress's grid (every case a statue that may slide)
    is refused by an engine that declares no statue friction: counted 'not carried', never a pass,
    and with nothing else run the verdict is NOTHING TESTED (exit 1)."""
    spec = tmp_path / "rk4.toml"
    spec.write_text("""
[campaign]
name = "rk4 plugin"
[systems]
alpha = 0.25
size = 1.0
mass = 3800.0
base = ["fixed"]
[motions]
type = "pulse"
pulse = "sine"
cycles = 1
frequency_ratio = {from = 2.0, to = 4.0, num = 2}
amplitude_ratio = {from = 1.5, to = 3.0, num = 2}
[duration]
tail = 2.0
[[engines]]
name = "analytic"
[[engines]]
name = "rk4"
""")
    done = isorock(plugin_path, "sweep", str(spec), "--out", str(tmp_path / "sweep"), cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    import pyarrow.parquet as pq
    table = pq.read_table(tmp_path / "sweep" / "results.parquet").to_pandas()
    rk4 = table[table["engine"] == "rk4"]
    ref = table[table["engine"] == "analytic"]
    assert len(rk4) == len(ref) == 4 and set(rk4["status"]) <= {"completed", "overturned"}
    assert list(rk4.sort_values("case")["overturned"]) == list(ref.sort_values("case")["overturned"])
    done = isorock(plugin_path, "stress", "--quick", "--engines", "rk4", "--out", str(tmp_path / "stress"))
    assert done.returncode == 1 and "stress: NOTHING TESTED" in done.stdout + done.stderr
    assert "not carried by their engine" in done.stdout + done.stderr
