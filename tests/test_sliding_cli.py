"""The sliding model on the command line (docs/sliding.md): --statue-friction, --kinetic-friction
and --vertical in `isorock run`, what the JSON and the table say, and one-line refusals."""
import json

import numpy as np
import pytest

from isorock.validate.cli.main import main

G = 9.81
BLOCK = ["--height", "1.0", "--width", "1.0", "--mass", "50", "--base-mass", "50", "--fixed-base"]


def run_cli(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_run_slides_as_the_rigid_plastic_closed_form(tmp_path, capsys):
    """A rectangular push of 0.5 g for 0.3 s on a block with μ 0.2 (tanα 1: it slides, never
    tips): the final slide in closed form, −(a0 − μg)·T·(T + (a0 − μg)·T/(μg))/2, with the
    record's last sample ramping to zero over its step (tests/test_sliding.py derives it)."""
    rec = tmp_path / "push.csv"
    a = np.r_[np.full(31, 0.5), 0.0]
    rec.write_text("t [s], a [g]\n" + "\n".join(f"{i * 0.01:.2f}, {v}" for i, v in enumerate(a)) + "\n")
    j = tmp_path / "run.json"
    code, _, err = run_cli(["run", "--engine", "analytic", *BLOCK, "--statue-friction", "0.2", "--motion", str(rec),
                            "--duration", "3", "--json", str(j)], capsys)
    assert code == 0, err
    d = json.loads(j.read_text())
    a0, mu, T, dt = 0.5 * G, 0.2, 0.3, 0.01
    c = a0 - mu * G
    v1, x1 = -c * T, -0.5 * c * T * T
    v2 = v1 - c * dt + 0.5 * a0 * dt
    x2 = x1 + v1 * dt - 0.5 * c * dt * dt + a0 * dt * dt / 6.0
    assert d["slide_final"] == pytest.approx(x2 - v2 * v2 / (2 * mu * G), rel=1e-9)
    assert d["slip_onset"] == 0.0 and 0 < d["slide_onset"] < 0.1 and d["energy_lost_in_slip"] > 0
    assert d["system"]["friction"] == 0.2 and d["system"]["kinetic_friction"] == 0.2
    assert d["energy_balance_residual"] < 1e-9


def test_run_without_friction_says_nothing_of_a_slide(tmp_path, capsys):
    j = tmp_path / "run.json"
    code, _, _ = run_cli(["run", "--engine", "analytic", *BLOCK, "--motion", "sine:amp=0.5,freq=2,cycles=1",
                          "--json", str(j)], capsys)
    assert code == 0
    d = json.loads(j.read_text())
    assert "slide_max" not in d and "friction" not in d["system"] and "vertical" not in d["motion"]


def test_run_compares_slides_and_modes(capsys):
    code, out, err = run_cli(["run", "--engine", "analytic,analytic-reference", *BLOCK, "--statue-friction", "0.3",
                              "--motion", "sine:amp=0.6,freq=2,cycles=2", "--vertical",
                              "sine:amp=0.2,freq=5,cycles=3", "--duration", "3"], capsys)
    assert code == 0, err
    assert "slide cm" in out and "Δslide onset s" in out
    assert out.strip().splitlines()[-1].endswith("slide")  # the two agree: one mode sequence, no reference note


@pytest.mark.parametrize("args, says", [
    (["--kinetic-friction", "0.3"], "--kinetic-friction = 0.3: needs --statue-friction"),
    (["--statue-friction", "0.3", "--kinetic-friction", "0.5"], "--kinetic-friction = 0.5"),
    (["--statue-friction", "0"], "--statue-friction = 0"),
    (["--statue-friction", "nan"], "--statue-friction = nan"),
    (["--statue-friction", "11"], "--statue-friction = 11"),
    (["--vertical", ""], "--vertical"),
    (["--vertical", "none"], "--vertical = 'none'"),
    (["--vertical", "no-such-file"], "no-such-file"),
])
def test_bad_friction_or_vertical_is_one_line(args, says, capsys):
    code, out, err = run_cli(["run", "--engine", "analytic", *BLOCK, "--motion", "sine:amp=0.5,freq=2", *args],
                             capsys)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and says in err, err


def test_vertical_record_needs_its_units(tmp_path, capsys):
    rec = tmp_path / "up.csv"
    rec.write_text("0, 0.1\n0.01, 0.2\n0.02, 0.0\n")
    code, _, err = run_cli(["run", "--engine", "analytic", *BLOCK, "--motion", "sine:amp=0.5,freq=2", "--vertical",
                            str(rec)], capsys)
    assert code == 2 and "units" in err and len(err.strip().splitlines()) == 1
    code, _, err = run_cli(["run", "--engine", "analytic", *BLOCK, "--motion", "sine:amp=0.5,freq=2", "--vertical",
                            str(rec), "--vertical-units", "g"], capsys)
    assert code == 0, err
