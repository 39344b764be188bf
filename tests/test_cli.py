"""The `isorock` command line: contract field names, exit codes, no partial files."""
import csv
import json
import os
import stat
import subprocess
import sys

import pytest

from isorock.analytic import beta, beta2, beta3, beta_housner, no_bounce_slenderness
from isorock.validate.cli.main import main

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
    assert main(["run", "--help"]) == 0
    assert unit in _option_help(capsys.readouterr().out, option)


def test_old_option_names_stay_as_aliases(capsys):
    """--damping and --theta0 are a contract: they keep working beside the clearer names."""
    base = ["run", *PAPER, "--duration", "1", "--quiet"]
    assert main(base + ["--period", "1.5", "--damping", "0.2", "--theta0", "0.3"]) == 0
    assert main(base + ["--period", "1.5", "--damping-ratio", "0.2", "--theta0-over-alpha", "0.3"]) == 0


def test_beta_loads_no_heavy_module():
    code = ("import sys; from isorock.validate.cli.main import main; "
            "main(['beta', '--slenderness', '3', '--mass-ratio', '1']); "
            "heavy = {'numpy', 'scipy', 'matplotlib', 'mujoco', 'pybullet', 'numba'}; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]"


# --- issue 13: outputs, one-line errors, input read honestly, bounded work ------------------

FIXED = [*PAPER, "--fixed-base"]


def _one_line_error(code, err, *needles):
    assert code == 2, err
    assert err.count("\n") == 1 and "Traceback" not in err and "usage:" not in err, err
    for n in needles:
        assert n in err, (n, err)


@pytest.mark.parametrize("args,needles", [
    (["run", *PAPER, "--height", "abc", "--fixed-base"], ["--height", "'abc'", "number"]),
    (["run"], ["isolator", "--fixed-base"]),  # the block defaults to the paper's (issue 39); its base does not
    (["run", *FIXED, "--duration", "-inf"], ["duration", "-inf", "positive"]),
    (["run", *FIXED, "--substeps", "1.5"], ["--substeps", "whole number"]),
    (["validate", "--scales", "-1,2,3", "--engines", "analytic"], ["scales", "-1,2,3", "positive"]),
    (["beta", "--slenderness", "x", "--mass-ratio", "1"], ["--slenderness", "'x'"]),
])
def test_argument_errors_are_one_line(tmp_path, monkeypatch, capsys, args, needles):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(args, capsys)
    _one_line_error(code, err, *needles)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args,needles", [
    (["--duration", "1e9"], ["duration", "3600"]),
    (["--motion", "sine:amp=0.5,freq=1,cycles=1e9"], ["cycles/freq", "3600"]),
    (["--motion", "sine:amp=0.5,freq=1e-6"], ["cycles/freq", "3600"]),
    (["--max-step", "1e-9"], ["max-step", "MAX_STEPS"]),
    (["--rest-velocity", "1e-300"], ["rest-velocity", "MIN_REST_VELOCITY"]),
    (["--engine", "mujoco", "--timestep", "1e-7", "--duration", "200"], ["timestep", "MAX_STEPS"]),
    (["--engine", "bullet", "--substeps", "1000000"], ["substeps", "control step"]),
    (["--csv-dt", "1e-9", "--csv", "x.csv", "--json", "x.json"], ["csv-dt", "MAX_SAMPLES"]),
    (["--motion", "sine:amp=0.1,amp=5,freq=1"], ["amp", "twice"]),
    (["--json", ""], ["--json", "an empty value"]),
    (["--json", "same", "--csv", "same"], ["csv", "also given as json"]),
])
def test_run_bad_input_is_refused_before_any_work(tmp_path, monkeypatch, capsys, args, needles):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(["run", *FIXED, *args], capsys)
    _one_line_error(code, err, *needles)
    assert list(tmp_path.iterdir()) == []


def test_stiff_isolator_period_is_bounded(tmp_path, capsys):
    code, _, err = run_cli(["run", *PAPER, "--period", "1e-5", "--damping", "0.1"], capsys)
    _one_line_error(code, err, "period", "MAX_ISOLATOR_CYCLES")


def test_outputs_at_bad_paths_exit_2_and_write_nothing(tmp_path, capsys, char_device):
    full = char_device("full")
    (tmp_path / "afile").write_text("keep")
    (tmp_path / "adir").mkdir()
    for flag, path in (("--json", tmp_path / "afile" / "x.json"), ("--json", tmp_path / "adir"),
                       ("--csv", tmp_path / "adir"), ("--json", full)):
        code, _, err = run_cli(["run", *FIXED, "--duration", "0.5", flag, str(path)], capsys)
        _one_line_error(code, err, flag[2:])
    code, _, err = run_cli(["scene", "--engine", "mujoco", "--out", str(tmp_path / "adir")], capsys)
    _one_line_error(code, err, "out", "folder")
    assert sorted(p.name for p in tmp_path.iterdir() if p != full) == ["adir", "afile"]
    assert list((tmp_path / "adir").iterdir()) == [] and (tmp_path / "afile").read_text() == "keep"
    assert stat.S_ISCHR(os.stat(full).st_mode)


def test_json_written_only_if_csv_is_too(tmp_path, capsys, char_device):
    full = char_device("full")
    j = tmp_path / "x.json"
    code, _, err = run_cli(["run", *FIXED, "--duration", "0.5", "--json", str(j), "--csv", str(full)], capsys)
    _one_line_error(code, err, "csv")
    assert not j.exists()


def test_dash_is_stdout_and_devices_stay_devices(tmp_path, monkeypatch, capsys, char_device):
    null = char_device("null")
    monkeypatch.chdir(tmp_path)
    code, out, _ = run_cli(["run", *FIXED, "--theta0", "0.5", "--duration", "1", "--json", "-"], capsys)
    assert code == 0 and json.loads(out)["theta_max_over_alpha"] == pytest.approx(0.5, abs=1e-12)
    code, out, _ = run_cli(["run", *FIXED, "--duration", "0.5", "--json", str(null), "--quiet"], capsys)
    assert code == 0 and out == ""
    assert stat.S_ISCHR(os.stat(null).st_mode)
    code, out, _ = run_cli(["scene", "--engine", "mujoco", "--out", "-"], capsys)
    assert code == 0 and out.lstrip().startswith("<mujoco")
    expected = [null.name] if null.parent == tmp_path else []
    assert [p.name for p in tmp_path.iterdir()] == expected  # no file named '-', nothing else


def test_run_prints_the_pga_it_used(tmp_path, capsys):
    code, out, _ = run_cli(["run", *FIXED, "--motion", "sine:amp=0.05,freq=2", "--duration", "1"], capsys)
    assert code == 0
    assert json.loads(out)["motion"]["pga_g"] == pytest.approx(0.05, rel=1e-3)


def test_two_column_record_needs_units(tmp_path, capsys):
    rec = tmp_path / "rec.csv"
    rec.write_text("0,0\n0.01,0.3\n0.02,-0.3\n0.03,0\n")
    code, _, err = run_cli(["run", *FIXED, "--motion", str(rec), "--duration", "0.5"], capsys)
    _one_line_error(code, err, "units")
    code, out, _ = run_cli(["run", *FIXED, "--motion", str(rec), "--units", "g", "--duration", "0.5"], capsys)
    assert code == 0 and json.loads(out)["motion"]["pga_g"] == pytest.approx(0.3)


def test_at2_units_option_contradicting_the_header_is_an_error(tmp_path, capsys):
    rec = tmp_path / "x.AT2"
    rec.write_text("PEER\nrec\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   3, DT=  .0100 SEC\n .1 .2 .0\n")
    code, _, err = run_cli(["run", *FIXED, "--motion", str(rec), "--units", "m/s2", "--duration", "0.5"], capsys)
    _one_line_error(code, err, "units", "contradicts")


def test_validate_refuses_a_foreign_out_folder_before_running(tmp_path, monkeypatch, capsys):
    (tmp_path / "src").mkdir()
    (tmp_path / "NOTES.md").write_text("mine")
    monkeypatch.chdir(tmp_path)
    for out in (".", ""):
        code, _, err = run_cli(["validate", "--quick", "--quiet", "--engines", "analytic", "--out", out], capsys)
        _one_line_error(code, err, "out")
    for cmd in (["bench", "--engines", "analytic"], ["stress", "--engines", "analytic"]):
        code, _, err = run_cli([*cmd, "--out", "NOTES.md"], capsys)
        _one_line_error(code, err, "NOTES.md")
        code, _, err = run_cli([*cmd, "--out", "."], capsys)
        _one_line_error(code, err, "did not write")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["NOTES.md", "src"]
    assert (tmp_path / "NOTES.md").read_text() == "mine"


def test_sigterm_mid_run_exits_cleanly_and_leaves_nothing(tmp_path):
    import signal
    import time
    # a run that cannot end on its own before it is signalled (an hour of MuJoCo steps,
    # which hand control back to Python between chunks; mujoco:full, since the default
    # skips a block that never lifts), so the test waits for a state (the command catches
    # SIGTERM), never for a clock: a command that finished first made it fail 3 times in
    # 4 on a loaded machine (issue 24, item 17)
    args = [sys.executable, "-m", "isorock.validate.cli.main", "run", *FIXED, "--engine", "mujoco:full",
            "--motion", "sine:amp=0.3,freq=2,cycles=400", "--duration", "3600", "--json", "x.json", "--csv", "x.csv"]
    proc = subprocess.Popen(args, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # wait until the command catches SIGTERM (the kernel's SigCgt mask)
    def catches_sigterm():
        for line in open(f"/proc/{proc.pid}/status"):
            if line.startswith("SigCgt:"):
                return bool(int(line.split()[1], 16) & (1 << (signal.SIGTERM - 1)))
        return False
    deadline = time.monotonic() + 60
    while not catches_sigterm() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert proc.poll() is None
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM, err
    assert "Traceback" not in err and "SIGTERM" in err
    assert list(tmp_path.iterdir()) == []


def test_several_engines_write_all_outputs_or_none_and_create_no_folder(tmp_path, monkeypatch, capsys):
    """Issue 24 item 5: `run` with several engines, a good --json and a --csv in a folder
    that does not exist: exit 2 before any run, no multi.json left behind, no folder made."""
    monkeypatch.chdir(tmp_path)
    code = main(["run", "--engine", "analytic,analytic:conservative", "--height", "2", "--width", "0.7",
                 "--mass", "3800", "--base-mass", "1", "--fixed-base", "--motion", "sine:amp=0.6,freq=1.3,cycles=1",
                 "--json", "multi.json", "--csv", "afile/x.csv"])
    assert code == 2
    err = capsys.readouterr().err
    assert "csv" in err and "afile" in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_one_engine_refuses_an_output_in_a_missing_folder(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    code = main(["run", "--engine", "analytic", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "1",
                 "--fixed-base", "--json", "new/deeper/out.json"])
    assert code == 2 and "does not exist" in capsys.readouterr().err
    assert not (tmp_path / "new").exists()


def test_scene_refuses_to_replace_a_users_file_as_calibrate_does(tmp_path, capsys):
    """Issue 24 item 16: `scene --out` replaced a user's file where `calibrate --out` refuses
    to; both write a file a user keeps and edits, so both refuse one that exists."""
    mine = tmp_path / "my-scene.xml"
    mine.write_text("my own edits")
    code, _, err = run_cli(["scene", "--engine", "mujoco", "--out", str(mine)], capsys)
    assert code == 2 and "exists" in err and err.count("\n") == 1
    assert mine.read_text() == "my own edits"
    fresh = tmp_path / "new.xml"
    assert run_cli(["scene", "--engine", "mujoco", "--out", str(fresh)], capsys)[0] == 0 and fresh.stat().st_size > 0


@pytest.mark.parametrize("option, value, field", [("--pga", "0.3", "pga_g"), ("--pgv", "0.25", None)])
def test_run_scales_a_record_to_a_target_pga_or_pgv(tmp_path, capsys, option, value, field):
    """`--pga G` / `--pgv V` scale the motion to that peak (issue 25): the JSON's motion says
    so, checked against the motion's own peaks computed here."""
    import json

    from isorock.analytic.motion import load_motion
    out = tmp_path / "r.json"
    code, _, err = run_cli(["run", *FIXED, "--motion", "sine:amp=0.6,freq=1.3,cycles=1", option, value,
                            "--duration", "1", "--json", str(out), "--quiet"], capsys)
    assert code == 0, err
    motion = json.loads(out.read_text())["motion"]
    base = load_motion("sine:amp=0.6,freq=1.3,cycles=1")
    factor = float(value) / (base.pga_g if option == "--pga" else base.pgv)
    assert motion["pga_g"] == pytest.approx(base.pga_g * factor, rel=1e-9)


def test_pga_with_scale_is_refused(tmp_path, capsys):
    code, _, err = run_cli(["run", *FIXED, "--motion", "sine:amp=0.6,freq=1.3,cycles=1", "--pga", "0.3",
                            "--scale", "2"], capsys)
    assert code == 2 and "pga" in err and err.count("\n") == 1


def test_beta_with_a_slenderness_past_double_precision_is_one_line(capsys):
    """λ = 1e300 gave a traceback (OverflowError from λ²): now exit 2 naming the field."""
    code, _, err = run_cli(["beta", "--slenderness", "1e300", "--mass-ratio", "1"], capsys)
    assert code == 2 and "slenderness" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_mujoco_refuses_a_body_lighter_than_it_can_represent(capsys):
    """A 1e-30 kg statue: MuJoCo's compiler raised ValueError (mass and inertia of moving
    bodies must exceed mjMINVAL), a traceback; now exit 2 naming the field."""
    code, _, err = run_cli(["run", "--engine", "mujoco", "--height", "1", "--width", "0.3", "--mass", "1e-30",
                            "--base-mass", "200", "--period", "2", "--damping-ratio", "0.1",
                            "--motion", "ricker:amp=0.5,freq=2"], capsys)
    assert code == 2 and "mass" in err and "Traceback" not in err
    code, _, err = run_cli(["run", "--engine", "mujoco", "--height", "1", "--width", "0.3", "--mass", "100",
                            "--base-mass", "1e-30", "--period", "2", "--damping-ratio", "0.1",
                            "--motion", "ricker:amp=0.5,freq=2"], capsys)
    assert code == 2 and "base_mass" in err and "Traceback" not in err
