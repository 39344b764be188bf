"""`isorock run --engine A,B` compares engines on one system and motion; `--plot` draws
the run. Short runs: free rocking on a fixed base from 0.5α for 1 s (first impact at
t₁ = 0.5014 s, model.md's exact oracle)."""
import json

import pytest

from isorock.validate.cli.main import main

SYSTEM = ["--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base",
          "--theta0", "0.5", "--duration", "1.0"]
T1 = 0.5014170  # model.md: first impact from rest at α/2, H 2.0, B 0.7


def _run(args, capsys):
    rc = main(["run", *args])
    out, err = capsys.readouterr()
    return rc, out, err


def test_two_engines_json_has_summaries_and_comparison(tmp_path, capsys):
    j, c, png = tmp_path / "r.json", tmp_path / "h.csv", tmp_path / "r.png"
    rc, out, err = _run([*SYSTEM, "--engine", "analytic,mujoco:fast", "--json", str(j), "--csv", str(c),
                         "--plot", str(png)], capsys)
    assert rc == 0, err
    data = json.loads(j.read_text())
    assert data["reference"] == "analytic"
    assert set(data["engines"]) == {"analytic", "mujoco:fast"}
    assert set(data["comparisons"]) == {"mujoco:fast"}
    cmp = data["comparisons"]["mujoco:fast"]
    # both engines see the first impact near the closed-form time; before it the histories agree
    for name in data["engines"]:
        first = data["engines"][name]["impact_log"][0]["t"]
        assert abs(first - T1) < 0.01, (name, first)
    assert cmp["horizon"] > T1 and cmp["overturn_agree"] is True
    assert data["engines"]["mujoco:fast"]["settings"]["timestep"] == pytest.approx(2e-3)  # the preset's step
    assert "provenance" in data
    assert (tmp_path / "h.analytic.csv").is_file() and (tmp_path / "h.mujoco-fast.csv").is_file()
    assert not c.exists()  # one file per engine, never the bare name
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "against analytic" in out and "mujoco:fast" in out


def test_single_engine_output_is_unchanged_and_plot_is_written(tmp_path, capsys):
    png = tmp_path / "one.png"
    rc, out, _ = _run([*SYSTEM, "--plot", str(png)], capsys)
    assert rc == 0
    brief = json.loads(out)  # still the JSON brief on stdout
    assert brief["engine"] == "analytic" and brief["impacts"] >= 1
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize("args, needle", [
    (["--engine", "analytic,nosuch"], "engine = 'nosuch'"),
    (["--engine", "analytic,analytic"], "each engine"),
    (["--engine", "mujoco:nosuch"], "preset = 'nosuch'"),
    (["--engine", "analytic,bullet", "--solref", "0.004,1"], "--solref"),
    (["--plot", "x.nosuchformat"], "plot = "),
])
def test_bad_engine_lists_exit_2_with_one_line(args, needle, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run([*SYSTEM, *args], capsys)
    assert rc == 2
    assert needle in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []
