"""Every run has a wall-clock budget (issue 24, item 13): past it the run stops with that
reason, in `run`-like single runs, in validate's histories (runner.run_task) and in the
one-by-one runs of a campaign or an ensemble (Engine.simulate_many). The oracle is the
run's own message: it stopped short of its simulated end."""
from __future__ import annotations

import re

import pytest

from isorock.analytic import limits
from isorock.analytic.limits import BudgetExceeded
from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.system import paper_system
from isorock.validate.core.engines import get_engine

LONG = 600.0  # simulated s: PyBullet stepped throughout takes minutes for it, far past a 0.5 s budget
MOTION = GroundMotion.from_pulse(Pulse("sine", amp=0.2, freq=1.0, cycles=1))
#: bullet:full steps Bullet throughout: the default skips the rest phase, and the block
#: rests for all but the sine's second, so its 600 s take well under the budget
FULL = {"phased": False}


def _stopped_at(message: str) -> float:
    m = re.search(r"at t = ([0-9.e+-]+) s of ([0-9.e+-]+) s simulated", message)
    assert m, message
    return float(m.group(1))


def test_a_run_past_its_budget_stops_with_that_reason():
    with pytest.raises(BudgetExceeded) as e:
        get_engine("bullet").simulate(paper_system(), MOTION, settings=get_engine("bullet").settings(**FULL),
                                      duration=LONG, budget_s=0.5)
    assert "budget of 0.5 s" in str(e.value) and _stopped_at(str(e.value)) < LONG


def test_validate_histories_and_campaign_runs_have_the_budget(monkeypatch):
    from isorock.validate.core.runner import Task, run_task
    monkeypatch.setattr(limits, "RUN_BUDGET_S", 0.5)
    key, traj, error = run_task(Task("k", "bullet:full", paper_system(), MOTION, LONG))
    assert traj is None and "budget" in error and _stopped_at(error) < LONG
    out = get_engine("bullet").simulate_many([(paper_system(), MOTION, LONG, 0.0)], budget_s=0.5,
                                             settings=get_engine("bullet").settings(**FULL))
    assert isinstance(out[0], BudgetExceeded)


def test_the_estimate_of_a_long_report_is_announced():
    from isorock.validate.core.estimate import estimate_line
    line = estimate_line({"analytic": 1000.0, "drake": 3600.0})
    assert line is not None and "drake" in line and "min" in line
    assert estimate_line({"analytic": 1000.0}) is None  # seconds: nothing to announce


def test_mujocos_batch_path_gives_each_run_the_budget():
    """MuJoCo runs a batch side by side (its own simulate_many); each run still stops at its
    budget: a long run that steps throughout (mujoco:full) against half a second."""
    from isorock.validate.core.engines import choose
    settings = choose("mujoco:full").settings()
    runs = [(paper_system(), MOTION, LONG, 0.0)] * 2
    out = get_engine("mujoco").simulate_many(runs, settings=settings, threads=2, budget_s=0.5)
    assert all(isinstance(r, BudgetExceeded) and _stopped_at(str(r)) < LONG for r in out), out


# --- the commands a user runs one simulation with: run and view ---------------------------

FIXED = ["--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base"]
SINE = ["--motion", "sine:amp=0.2,freq=1,cycles=1"]


def test_run_announces_its_cost_and_stops_at_its_budget_writing_nothing(tmp_path, capsys):
    """`run` had no budget at all: `run --engine bullet --duration 1800` (minutes) or Drake
    (hours) ran without an estimate or an end. The estimate comes first (SPEEDS), then the
    run stops at --budget with one line, exit 1, and no output is written."""
    from isorock.validate.cli.main import main
    out = tmp_path / "x.json"
    code = main(["run", "--engine", "bullet:full", *FIXED, *SINE, "--duration", "1800", "--budget", "0.5",
                 "--json", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1, err
    assert len(err) == 2 and err[0].startswith("run: about 1800 simulated s") and "min" in err[0], err
    assert "bullet" in err[1] and "budget of 0.5 s" in err[1] and "--budget" in err[1], err
    assert _stopped_at(err[1]) < 1800
    assert list(tmp_path.iterdir()) == []


def test_a_short_run_is_not_announced_and_finishes_within_the_default_budget(tmp_path, capsys):
    from isorock.validate.cli.main import main
    code = main(["run", "--engine", "analytic", *FIXED, *SINE, "--duration", "4", "--quiet"])
    assert code == 0 and capsys.readouterr().err == ""


@pytest.mark.parametrize("value", ["0", "-1", "inf", "nan"])
def test_a_budget_that_is_not_a_positive_number_of_seconds_is_refused(tmp_path, capsys, value):
    from isorock.validate.cli.main import main
    code = main(["run", "--engine", "analytic", *FIXED, *SINE, "--budget", value])
    err = capsys.readouterr().err
    assert code == 2 and "budget = " in err and len(err.strip().splitlines()) == 1


def test_view_stops_at_its_budget_before_drawing(tmp_path, capsys, monkeypatch):
    from isorock.validate.cli.main import main
    from isorock.validate.tools import view
    monkeypatch.setattr(view, "has_display", lambda: False)
    monkeypatch.setattr(view, "offscreen_backend", lambda: "egl")
    monkeypatch.setenv("MUJOCO_GL", "egl")  # view sets it for its renderer; restored after the test
    out = tmp_path / "v.gif"
    code = main(["view", "--engine", "bullet", *FIXED, *SINE, "--duration", "1800", "--budget", "0.5",
                 "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1 and "budget of 0.5 s" in err[-1] and err[0].startswith("view: about"), err
    assert not out.exists()


def test_sweep_announces_its_cost_before_its_first_chunk(tmp_path, capsys, monkeypatch):
    """A campaign lasts hours: its estimate (core.estimate, each engine's simulated seconds
    over the workers) comes before any chunk runs. ANNOUNCE_AFTER at 0 so that a small
    campaign is announced too: the order on stderr is the check."""
    from test_campaign import write_spec

    from isorock.validate.cli.main import main
    from isorock.validate.core import estimate
    monkeypatch.setattr(estimate, "ANNOUNCE_AFTER", 0.0)
    spec = write_spec(tmp_path, more="")
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0", "--no-products"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err[0].startswith("sweep: about ") and "analytic" in err[0] and "budget of 300 s" in err[0], err


def test_a_run_whose_derived_steps_exceed_the_bound_is_refused_before_any_work(tmp_path, capsys):
    """The work bound counts the steps the run will take: PyBullet's step follows the block
    (0.114 ms on the paper's fixed block), so an hour is 3.2e7 steps, over MAX_STEPS; refused
    before the estimate and the run (with the former 1/3000 s it passed the check and was
    refused only inside the engine)."""
    from isorock.validate.cli.main import main
    code = main(["run", "--engine", "bullet", *FIXED, *SINE, "--duration", "3600", "--json", str(tmp_path / "x.json")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "MAX_STEPS" in err[0] and "timestep" in err[0], err
    assert list(tmp_path.iterdir()) == []
