"""The notebook API (issue 25): isorock.run / isorock.report / isorock.sweep with keyword
arguments, the command line's validation and results, DataFrames; a campaign from code
without a __main__ guard runs (notebook) or says in one line what to do (script)."""
from __future__ import annotations

import io
import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import isorock
from isorock.analytic.errors import InputError
from isorock.validate.cli.main import main

PAPER = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
SINE = "sine:amp=0.6,freq=1.3,cycles=2"


def _cli_args(options: dict) -> list[str]:
    return [x for k, v in options.items() for x in (f"--{k.replace('_', '-')}", str(v))]


def test_the_top_package_names_its_entry_points_and_keeps_its_subpackages():
    import isorock.validate.core.engines  # noqa: F401 — the subpackage isorock.validate stays one
    assert callable(isorock.run) and callable(isorock.report) and callable(isorock.sweep)
    assert callable(isorock.simulate) and callable(isorock.design) and isorock.System.__name__ == "System"
    assert isorock.validate.__name__ == "isorock.validate"
    with pytest.raises(AttributeError):
        isorock.no_such_entry_point  # noqa: B018


def test_run_is_the_command_line_run(tmp_path):
    """The same keywords as options: the summary the command writes (--json) is the one
    the returned Trajectory gives, the motion scaled to pga in both."""
    options = dict(PAPER, motion=SINE, pga=0.5)
    tr = isorock.run(engine="analytic", **options)
    path = tmp_path / "r.json"
    assert main(["run", "--engine", "analytic", *_cli_args(options), "--json", str(path), "--quiet"]) == 0
    cli = json.loads(path.read_text())
    mine = tr.summary()
    for key in ("theta_max_over_alpha", "impacts", "uplifts", "overturned", "u_max"):
        assert mine[key] == pytest.approx(cli[key], rel=1e-12), key
    assert cli["motion"]["pga_g"] == pytest.approx(0.5)


def test_several_engines_are_a_dict_in_the_order_given():
    runs = isorock.run(engine="analytic,analytic:conservative", motion=SINE, **PAPER)
    assert list(runs) == ["analytic", "analytic:conservative"]


@pytest.mark.parametrize("options, cli", [
    (dict(PAPER, duration=-1.0), ["--duration", "-1.0"]),
    (dict(PAPER, motion="sine:amp=0.5"), ["--motion", "sine:amp=0.5"]),
    (dict(PAPER, engine="mujoco:nope"), ["--engine", "mujoco:nope"]),
    (dict(PAPER, theta0_over_alpha=1.5), ["--theta0-over-alpha", "1.5"]),
])
def test_bad_input_is_the_command_lines_one_line(options, cli, capsys):
    """The same refusal as the command's (its stderr line, options spelt as keywords)."""
    base = {k: v for k, v in PAPER.items()}
    assert main(["run", *_cli_args(base), *cli]) == 2
    line = capsys.readouterr().err.strip().split(": error: ", 1)[1]
    with pytest.raises(InputError) as e:
        isorock.run(**options)
    assert str(e.value) == line.replace("--theta0-over-alpha", "theta0_over_alpha").replace(
        " (see isorock run --help)", "")


def test_an_unknown_keyword_or_an_output_option_is_named():
    with pytest.raises(InputError, match=r"^heigth: not an option of isorock.run \(its options: .*height"):
        isorock.run(heigth=2.0)
    with pytest.raises(InputError, match=r"^json: an output of the command"):
        isorock.run(json="x.json", **PAPER)
    with pytest.raises(InputError, match=r"fixed_base = 'yes': must be True or False"):
        isorock.run(fixed_base="yes", height=2.0, width=0.7, mass=1.0)


def test_a_trajectory_as_a_dataframe_is_its_csv(tmp_path):
    tr = isorock.run(engine="analytic", motion=SINE, **PAPER)
    frame = tr.to_dataframe()
    buf = io.StringIO()
    tr.to_csv(buf)
    csv = np.loadtxt(io.StringIO(buf.getvalue()), delimiter=",", skiprows=1)
    assert list(frame.columns[:5]) == ["t", "u", "u_dot", "theta", "theta_dot"]
    # the CSV's 10 significant digits against the frame's floats
    np.testing.assert_allclose(frame[["t", "u", "u_dot", "theta", "theta_dot"]].to_numpy(), csv, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(frame["theta_over_alpha"], frame["theta"] / tr.system.alpha, rtol=1e-15)
    assert frame["t"].is_monotonic_increasing and frame["t"].is_unique
    assert frame.attrs["summary"]["theta_max_over_alpha"] == tr.theta_max_over_alpha


def test_report_is_validates_report(tmp_path, capsys):
    options = ["--quick", "--engines", "analytic", "--motion", SINE, "--pga", "0.5"]
    assert main(["validate", *options, "--quiet", "--out", str(tmp_path / "cli")]) == 0
    cli_verdict = capsys.readouterr().out.strip().splitlines()[-1]
    got = isorock.report(quick=True, engines=["analytic"], motion=SINE, pga=0.5, out=str(tmp_path / "api"))
    assert got.verdict == cli_verdict and got.passed
    metrics = json.loads((tmp_path / "api" / "metrics.json").read_text())
    assert metrics["verdict"] == got.verdict
    checks = got.checks()
    assert len(checks) == len(metrics["checks"]) and "metric" in checks.columns


def test_report_refuses_as_validate_does():
    with pytest.raises(InputError, match=r"^pga = -0.5"):
        isorock.report(quick=True, engines=["analytic"], motion=SINE, pga=-0.5)


def test_a_campaign_as_a_dataframe(tmp_path):
    from test_campaign import write_spec
    from isorock.validate.core.summary import COLUMNS
    spec = write_spec(tmp_path, more="")
    result = isorock.sweep(spec, out=tmp_path / "out", products=False)
    frame = result.to_dataframe()
    assert list(frame.columns) == list(COLUMNS) and len(frame) == result.table.num_rows == 18
    assert set(frame["base"]) == {"fixed", "isolated"}
    with pytest.raises(InputError, match="workers"):
        isorock.sweep(spec, workers=-1)


def test_a_campaign_given_as_a_value_is_the_files_campaign(tmp_path, monkeypatch):
    """The campaign as a value (issue 35): the file's tables as tomllib reads them give the file's
    table, row for row (the oracle: the file's own run); a bad key is the file's one line."""
    import tomllib
    from test_campaign import write_spec
    spec = write_spec(tmp_path, more="")
    monkeypatch.chdir(spec.parent)  # the value's relative paths are the current folder's, as the file's are its own
    tables = tomllib.loads(spec.read_text())
    from test_campaign import assert_same_rows
    from_file, from_value = isorock.sweep(spec, products=False), isorock.sweep(tables, products=False)
    assert from_file.table.num_rows == 18
    assert_same_rows(from_value.table, from_file.table)  # all but the wall time, NaN where the file's is NaN
    with pytest.raises(InputError, match=r"^colour: unknown key") as e:
        isorock.sweep(dict(tables, colour="red"))
    assert "\n" not in str(e.value)


SCRIPT = """
import isorock
r = isorock.sweep({spec!r}, out={out!r}, workers=2, products=False)
print("rows", r.table.num_rows)
"""


@pytest.mark.slow
def test_a_script_without_a_main_guard_is_told_what_to_do_and_code_without_a_file_runs(tmp_path):
    """Dask's worker processes start by "spawn", which runs a script again: without
    `if __name__ == "__main__":` it says so in one line (one traceback, the script's own),
    not Dask's wall. Code without a file (a notebook, `python -c`) is not run again: it runs."""
    from test_campaign import write_spec
    spec = write_spec(tmp_path, more="")
    script = tmp_path / "no_guard.py"
    script.write_text(textwrap.dedent(SCRIPT.format(spec=str(spec), out=str(tmp_path / "a"))))
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode != 0
    assert r.stderr.count("Traceback") == 1, r.stderr[-3000:]
    last = r.stderr.strip().splitlines()[-1]
    assert 'if __name__ == "__main__":' in last and "workers=0" in last
    code = SCRIPT.format(spec=str(spec), out=str(tmp_path / "b"))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0 and "rows 18" in r.stdout, r.stderr[-3000:]


REPORT_SCRIPT = """
import isorock
r = isorock.report(quick=True, engines=["analytic", "mujoco"], motion={motion!r}, pga=0.5)
print("passed", r.passed)
"""


@pytest.mark.slow
def test_a_report_from_a_script_without_a_main_guard_is_told_what_to_do(tmp_path):
    """The README's notebook example run as a script (found running it so): isorock.report
    starts worker processes for the contact engines by "spawn", which runs the script again
    in each; without `if __name__ == "__main__":` that was a wall of Python's bootstrapping
    tracebacks and a BrokenPipeError. Now one line says what to do, as isorock.sweep does;
    with workers=1 (one process) or from code without a file it runs."""
    script = tmp_path / "no_guard_report.py"
    script.write_text(textwrap.dedent(REPORT_SCRIPT.format(motion=SINE)))
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode != 0
    assert r.stderr.count("Traceback") == 1, r.stderr[-3000:]
    last = r.stderr.strip().splitlines()[-1]
    assert 'if __name__ == "__main__":' in last and "workers=1" in last, last
    code = REPORT_SCRIPT.format(motion=SINE)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0 and "passed" in r.stdout, r.stderr[-3000:]


@pytest.mark.slow
def test_a_report_from_code_on_standard_input_is_told_what_to_do(tmp_path):
    """`python - < script.py`: Python cannot run standard input again in a spawned worker
    (FileNotFoundError: '<stdin>'), so the workers die before their first task, and the
    report ended in a BrokenPipeError. Any worker that dies before its first task is said
    in one line, with what to do."""
    r = subprocess.run([sys.executable, "-"], input=REPORT_SCRIPT.format(motion=SINE), capture_output=True, text=True,
                       cwd=tmp_path, timeout=300)
    assert r.returncode != 0
    last = r.stderr.strip().splitlines()[-1]
    assert "InputError" in last and "could not start" in last and "workers=1" in last, r.stderr[-3000:]
    assert "BrokenPipeError" not in r.stderr
    # no worker is started to fail: each printed its FileNotFoundError first (issue 34, item 12)
    assert "FileNotFoundError" not in r.stderr and r.stderr.count("Traceback") == 1, r.stderr  # the script's own


@pytest.mark.slow
def test_a_sweep_on_workers_from_code_on_standard_input_is_told_what_to_do(tmp_path):
    """The same for isorock.sweep's Dask workers (spawned, they too run the program again)."""
    (tmp_path / "c.toml").write_text('[systems]\nalpha = 0.25\nsize = 1.0\n\n[motions]\ntype = "pulse"\n'
                                     'pulse = "sine"\nfrequency_ratio = 2.0\namplitude_ratio = 2.0\n\n'
                                     '[[engines]]\nname = "mujoco"\n')
    r = subprocess.run([sys.executable, "-"], input="import isorock\nisorock.sweep('c.toml', workers=2)\n",
                       capture_output=True, text=True, cwd=tmp_path, timeout=300)
    last = r.stderr.strip().splitlines()[-1]
    assert r.returncode != 0 and "InputError" in last and "could not start" in last, r.stderr[-3000:]
    assert "FileNotFoundError" not in r.stderr, r.stderr[-3000:]


def test_simulate_takes_python_values_and_its_runs_are_the_engines_own():
    """(issue 35) isorock.simulate(system, motion, engine=, settings=): no command line in
    between. Oracles: free rocking's first impact time against model.md's exact integral (the
    analytic engine), and MuJoCo with a settings dict exactly as the engine run with those
    settings; bad values are one-line InputErrors naming the keyword."""
    import isorock
    from isorock.analytic.errors import InputError
    from isorock.validate.core.compare import exact_first_impact_time
    from isorock.validate.core.engines import get_engine
    block = isorock.System.fixed(height=2.0, width=0.7, mass=3800.0)
    tr = isorock.simulate(block, None, theta0=0.5 * block.alpha, duration=2.0)
    assert abs(tr.impacts[0].t / exact_first_impact_time(block, 0.5 * block.alpha) - 1) < 1e-8
    motion = isorock.load_motion("sine:amp=0.6,freq=1.3,cycles=1")
    got = isorock.simulate(block, motion, engine="mujoco", settings={"timestep": 2e-4}, duration=3.0)
    mj = get_engine("mujoco")
    want = mj.simulate(block, motion, settings=mj.settings(timestep=2e-4), duration=3.0)
    assert np.array_equal(got.theta, want.theta) and got.status == want.status
    for kwargs, field in [(dict(system="block"), "system"), (dict(motion=[0.1]), "motion"),
                          (dict(engine="nope"), "engine"), (dict(settings={"no_such": 1}), "no_such"),
                          (dict(engine="analytic", settings=mj.settings()), "settings")]:
        with pytest.raises(InputError) as e:
            isorock.simulate(**{"system": block, "motion": motion, **kwargs})
        assert field in str(e.value) and "\n" not in str(e.value), (kwargs, str(e.value))


# --- the typed options (issue 35): the keyword route and the command line's build one value ------

from isorock.validate.io.options import RunOptions, ValidateOptions  # noqa: E402


def _subparser(command):
    """The command's own argparse parser (the oracle: what the command line reads)."""
    import argparse
    from isorock.validate.cli.main import build_parser
    top = build_parser(command)
    return next(a for a in top._actions if isinstance(a, argparse._SubParsersAction)).choices[command]


def _types(options):
    return {k: type(v) for k, v in options}


def test_the_api_module_reads_no_command_line():
    """isorock.run/report/sweep build typed options from keywords and call the floors below the
    command line: api.py imports neither argparse nor any module of the command line (validate/cli:
    its parser, its options, its commands), at any depth (every import, by Python's ast; issue 35).
    It stands on that floor itself, for the tools it calls (the campaign's, which only it imports)."""
    from pathlib import Path
    from test_architecture import ROOT, imports
    path = Path(ROOT / "validate/cli/api.py")
    modules = [m for _, m in imports(path, "validate.cli")]
    assert modules and not [m for m in modules if m == "argparse" or m.startswith("argparse.")
                            or m == "isorock.validate.cli" or m.startswith("isorock.validate.cli.")], modules
    # the readers isorock.report calls are below the command line
    assert {"isorock.validate.tools.report_config.report_config", "isorock.validate.tools.pair_report",
            "isorock.validate.io.inputs.plan_runs"} <= set(modules), modules


@pytest.mark.parametrize("model, command, keywords, argv", [
    (RunOptions, "run", dict(height=np.float64(0.6), width=0.2, mass=80, base_mass=np.int64(150), period=2,
                             damping_ratio=0.15, motion=SINE, pga=np.float64(0.5)),
     ["--height", "0.6", "--width", "0.2", "--mass", "80", "--base-mass", "150", "--period", "2",
      "--damping-ratio", "0.15", "--motion", SINE, "--pga", "0.5"]),
    (RunOptions, "run", dict(engine="mujoco", fixed_base=True, solref=(0.02, 1), solimp=[0.9, 0.95, 0.001],
                             noslip=np.int64(3), integrator="RK4", quiet=True),
     ["--engine", "mujoco", "--fixed-base", "--solref", "0.02,1", "--solimp", "0.9,0.95,0.001", "--noslip", "3",
      "--integrator", "RK4", "--quiet"]),
    (RunOptions, "run", dict(set_settings=["mujoco.integrator=RK4", "timestep=1e-4"], isolator="bilinear",
                             stiffness=1e5, post_yield_ratio=0.1, yield_displacement=0.01, theta0_over_alpha=-0.2),
     ["--set", "mujoco.integrator=RK4", "--set", "timestep=1e-4", "--isolator", "bilinear", "--stiffness", "1e5",
      "--post-yield-ratio", "0.1", "--yield-displacement", "0.01", "--theta0", "-0.2"]),
    (RunOptions, "run", dict(), []),
    (ValidateOptions, "validate", dict(quick=True, engines=["analytic", "mujoco:fast"], motion=[SINE, "ricker:amp=0.3,freq=2"],
                                       pga=np.float64(0.5), workers=np.int64(2), overturn="alpha"),
     ["--quick", "--engines", "analytic", "mujoco:fast", "--motion", SINE, "--motion", "ricker:amp=0.3,freq=2",
      "--pga", "0.5", "--workers", "2", "--overturn", "alpha"]),
    (ValidateOptions, "validate", dict(motion=SINE, engines="analytic", height=2.0, width=0.7, mass=10,
                                       fixed_base=True, scales="1,2,3"),
     ["--motion", SINE, "--engines", "analytic", "--height", "2", "--width", "0.7", "--mass", "10", "--fixed-base",
      "--scales", "1,2,3"]),
])
def test_keywords_and_the_command_line_give_one_typed_value(model, command, keywords, argv):
    """The oracle: the argv through the command's real parser, read into the typed value as the
    command reads it; the keywords (NumPy numbers, a pair, a triple, flags, lists) give the same
    value, field by field, a default (the paper's block: io.keys.Default) kept a default."""
    want = model.from_namespace(_subparser(command).parse_args(argv))
    got = model.from_keywords(command, keywords)
    assert got == want
    assert _types(got) == _types(want)


def test_the_typed_values_fields_are_the_commands_options_with_their_defaults():
    """Declared twice (the parser for --help, the typed value for both routes), held equal."""
    for model, command in ((RunOptions, "run"), (ValidateOptions, "validate")):
        actions = {a.dest: a for a in _subparser(command)._actions if a.dest != "help"}
        assert set(actions) == set(model.model_fields), command
        for dest, action in actions.items():
            default = model.model_fields[dest].default
            assert default == action.default and type(default) is type(action.default), (command, dest)


@pytest.mark.parametrize("call, keywords, line", [
    ("run", dict(height="2.0"), "height = '2.0': must be a number, not a string"),
    ("run", dict(fixed_base="yes"), "fixed_base = 'yes': must be True or False"),
    ("run", dict(pga=True), "pga = True: must be a number (a boolean is not a number)"),
    ("run", dict(solref="0.02,1"), "solref = '0.02,1': must be a sequence of 2–2 numbers, e.g. (0.02, 1)"),
    ("run", dict(solimp=(0.9,)), "solimp = (0.9,): must have 3–5 numbers"),
    ("run", dict(noslip=2.5), "noslip = 2.5: must be a whole number"),
    ("run", dict(cone="round"), "cone = 'round': must be one of pyramidal, elliptic"),
    ("run", dict(motion=""), "motion = '': an empty value; give one, or leave it out for its default"),
    ("report", dict(quick="yes"), "quick = 'yes': must be True or False"),
    ("report", dict(engines=[]), "engines = []: must give one or more (leave it out for the defaults)"),
    ("report", dict(workers="2"), "workers = '2': must be a whole number"),
])
def test_a_bad_keyword_type_is_one_line_naming_the_keyword(call, keywords, line):
    with pytest.raises(InputError) as e:
        getattr(isorock, call)(**keywords)
    assert str(e.value) == line


def test_the_command_line_hands_the_typed_value_on(monkeypatch):
    """`isorock run` reads its namespace into RunOptions and hands that to the readers isorock.run
    calls (plan_runs), not the namespace."""
    from isorock.validate.cli import run as run_module
    seen = []

    def plan_runs(a, specs):
        seen.append(a)
        raise InputError("stop")
    monkeypatch.setattr(run_module, "plan_runs", plan_runs)
    assert main(["run", "--fixed-base", "--solref", "0.02,1", "--quiet"]) == 2
    assert seen == [RunOptions.from_keywords("run", dict(fixed_base=True, solref=(0.02, 1), quiet=True))]
