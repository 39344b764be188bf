"""The `isorock` command line: contract field names, exit codes, no partial files."""
import csv
import json
import subprocess
import sys

import pytest

from isorock.analytic import beta, beta2, beta3, beta_housner, no_bounce_slenderness
from isorock.validate.cli import main

PAPER = ["--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]


def run_cli(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_beta_prints_closed_forms(capsys):
    code, out, _ = run_cli(["beta", "--slenderness", "4", "--mass-ratio", "0.5", "--height", "3"], capsys)
    assert code == 0
    d = json.loads(out)
    assert d["beta"] == pytest.approx(beta(4, 0.5), rel=1e-15)
    assert d["beta2"] == pytest.approx(beta2(4, 0.5, 1.5), rel=1e-15)
    assert d["beta3"] == pytest.approx(beta3(0.5, 1.5), rel=1e-15)
    assert d["beta_housner"] == pytest.approx(beta_housner(4), rel=1e-15)
    assert d["no_bounce_slenderness"] == pytest.approx(no_bounce_slenderness(0.5), rel=1e-15)
    # height defaults to 2.0 m
    _, out, _ = run_cli(["beta", "--slenderness", "4", "--mass-ratio", "0.5"], capsys)
    assert json.loads(out)["beta2"] == pytest.approx(beta2(4, 0.5, 1.0))


def test_run_writes_json_and_csv(tmp_path, capsys):
    j, c = tmp_path / "out.json", tmp_path / "out.csv"
    code, out, _ = run_cli(["run", "--engine", "analytic", *PAPER, "--period", "1.5", "--damping", "0.2",
                            "--motion", "sine:amp=0.6,freq=1,cycles=2", "--duration", "6",
                            "--json", str(j), "--csv", str(c)], capsys)
    assert code == 0
    d = json.loads(j.read_text())
    for key in ("engine", "alpha", "slenderness", "mass_ratio", "theta_max_over_alpha", "impacts",
                "uplifts", "overturned", "u_max", "runtime_s", "impact_log"):
        assert key in d
    assert d["engine"] == "analytic" and d["mass_ratio"] == pytest.approx(1.0)
    assert d["impacts"] == len(d["impact_log"]) > 0
    for entry in d["impact_log"]:
        assert {"t", "theta_dot_pre", "theta_dot_post", "u_dot_pre", "u_dot_post"} <= set(entry)
    rows = list(csv.reader(c.open()))
    assert rows[0] == ["t", "u", "u_dot", "theta", "theta_dot"]
    theta = [float(r[3]) for r in rows[1:]]
    assert max(abs(x) for x in theta) / d["alpha"] == pytest.approx(d["theta_max_over_alpha"], rel=1e-3)


def test_run_free_rocking_theta0_fraction_of_alpha(capsys):
    code, out, _ = run_cli(["run", *PAPER, "--fixed-base", "--theta0", "0.5", "--duration", "2"], capsys)
    assert code == 0
    d = json.loads(out)
    assert d["theta_max_over_alpha"] == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("args,field", [
    (["--height", "-2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base"], "height"),
    ([*PAPER, "--period", "1.5"], "isolator"),
    ([*PAPER, "--period", "0", "--damping", "0.2"], "period"),
    ([*PAPER, "--period", "1.5", "--damping", "-1"], "damping_ratio"),
    ([*PAPER, "--fixed-base", "--motion", "sine:amp=1"], "freq"),
    ([*PAPER, "--fixed-base", "--motion", "nope.AT2"], "not a file"),
    ([*PAPER, "--fixed-base", "--theta0", "1.5"], "theta0"),
    ([*PAPER, "--fixed-base", "--duration", "-3"], "duration"),
    ([*PAPER, "--fixed-base", "--engine", "ode45"], "engine"),
    ([*PAPER, "--fixed-base", "--solref", "0.01,1"], "solref"),
    ([*PAPER, "--fixed-base", "--max-step", "0"], "max-step"),
])
def test_bad_input_exit_2_one_line_no_file(tmp_path, capsys, args, field):
    j = tmp_path / "out.json"
    code, out, err = run_cli(["run", *args, "--json", str(j)], capsys)
    assert code == 2
    assert field in err and err.count("\n") == 1 and "Traceback" not in err
    assert not j.exists() and list(tmp_path.iterdir()) == []


def test_help_names_units():
    out = subprocess.run([sys.executable, "-m", "isorock.validate.cli", "run", "--help"], capture_output=True,
                         text=True, check=True).stdout
    for needle in ("--height", "m", "kg", "--period", "s", "--theta0", "fraction of α", "--motion", "in g"):
        assert needle in out
