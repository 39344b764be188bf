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


def _option_help(help_text: str, option: str) -> str:
    """The help of one option: its line and the indented lines that continue it."""
    lines = help_text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip().startswith(option))
    out = [lines[start]]
    for line in lines[start + 1:]:
        if line.strip().startswith("-") or not line.startswith(" " * 10):
            break
        out.append(line)
    return " ".join(x.strip() for x in out)


@pytest.mark.parametrize("option, unit", [
    ("--height", ", m"), ("--width", ", m"), ("--mass", "kg"), ("--base-mass", "kg"), ("--period", ", s"),
    ("--stiffness", "N/m"), ("--dashpot", "N·s/m"), ("--damping-ratio", "dimensionless"),
    ("--theta0-over-alpha", "fraction of α"), ("--duration", ", s"), ("--motion", "in g"),
])
def test_every_physical_option_names_its_unit(option, unit, capsys):
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    assert unit in _option_help(capsys.readouterr().out, option)


def test_old_option_names_stay_as_aliases(capsys):
    """--damping and --theta0 are a contract: they keep working beside the clearer names."""
    base = ["run", *PAPER, "--duration", "1", "--quiet"]
    assert main(base + ["--period", "1.5", "--damping", "0.2", "--theta0", "0.3"]) == 0
    assert main(base + ["--period", "1.5", "--damping-ratio", "0.2", "--theta0-over-alpha", "0.3"]) == 0


def test_beta_loads_no_heavy_module():
    code = ("import sys; from isorock.validate.cli import main; "
            "main(['beta', '--slenderness', '3', '--mass-ratio', '1']); "
            "heavy = {'numpy', 'scipy', 'matplotlib', 'mujoco', 'pybullet', 'numba'}; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"
