"""calibrate --out is created exclusively when it is written (issue 24, item 3): a file
that appears at that path while the calibration runs (a user's, or a second
calibration's with the same --out) is never replaced."""
from __future__ import annotations

from isorock.validate.cli.main import main

from test_calibrate import Score, _fake_result

GOOD = Score(((0.01, 0.005), (0.005, -0.01), (0.015, 0.0)))  # halved errors: a preset is written


def test_a_file_created_during_the_calibration_is_not_replaced(tmp_path, monkeypatch, capsys):
    from isorock.validate.tools import calibrate as module
    out = tmp_path / "preset.toml"

    def meanwhile(*a, **k):  # the other writer finishes first
        out.write_text("the other calibration's preset\n")
        return _fake_result(GOOD)
    monkeypatch.setattr(module, "calibrate", meanwhile)
    rc = main(["calibrate", "--engine", "mujoco", "--quiet", "--out", str(out), "--json", str(tmp_path / "r.json")])
    err = capsys.readouterr().err
    assert rc == 2 and out.read_text() == "the other calibration's preset\n"
    assert len(err.strip().splitlines()) == 1 and "out" in err and str(out) in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["preset.toml"]  # all or nothing: no r.json
    # without the other writer the same command writes the preset
    monkeypatch.setattr(module, "calibrate", lambda *a, **k: _fake_result(GOOD))
    out.unlink()
    assert main(["calibrate", "--engine", "mujoco", "--quiet", "--out", str(out)]) == 0
    assert "[settings.mujoco]" in out.read_text()


def test_an_empty_out_path_is_refused_before_any_run(monkeypatch, capsys):
    from isorock.validate.tools import calibrate as module

    def must_not_run(*a, **k):
        raise AssertionError("calibrated although --out '' is bad input")
    monkeypatch.setattr(module, "calibrate", must_not_run)
    for option in ("--out", "--json"):
        assert main(["calibrate", "--engine", "mujoco", "--quiet", option, ""]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and option.lstrip("-") in err, err
