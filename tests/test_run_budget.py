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

LONG = 600.0  # simulated s: PyBullet takes minutes for it, far past a 0.5 s budget
MOTION = GroundMotion.from_pulse(Pulse("sine", amp=0.2, freq=1.0, cycles=1))


def _stopped_at(message: str) -> float:
    m = re.search(r"at t = ([0-9.e+-]+) s of ([0-9.e+-]+) s simulated", message)
    assert m, message
    return float(m.group(1))


def test_a_run_past_its_budget_stops_with_that_reason():
    with pytest.raises(BudgetExceeded) as e:
        get_engine("bullet").simulate(paper_system(), MOTION, duration=LONG, budget_s=0.5)
    assert "budget of 0.5 s" in str(e.value) and _stopped_at(str(e.value)) < LONG


def test_validate_histories_and_campaign_runs_have_the_budget(monkeypatch):
    from isorock.validate.core.runner import Task, run_task
    monkeypatch.setattr(limits, "RUN_BUDGET_S", 0.5)
    key, traj, error = run_task(Task("k", "bullet", paper_system(), MOTION, LONG))
    assert traj is None and "budget" in error and _stopped_at(error) < LONG
    out = get_engine("bullet").simulate_many([(paper_system(), MOTION, LONG, 0.0)], budget_s=0.5)
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
