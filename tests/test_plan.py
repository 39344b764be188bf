"""One run, planned (issue 35, core.plan): every input checked once before any work, in one
frozen Plan that `isorock.simulate`, `isorock run` and `isorock.run` share.

Oracles: the engine called on its own (a plan adds nothing to a run), a counter of the runs
started (a refusal comes before any), a counter of the registry's checks (once per engine)."""
import dataclasses

import numpy as np
import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.motion import load_motion
from isorock.analytic.system import System
from isorock.validate.core import engines as registry
from isorock.validate.core.plan import engine_run, make_plan, run_plan, simulate

SYSTEM = System.isolated(height=1.2, width=0.3, mass=250.0, base_mass=500.0, period=2.0, damping_ratio=0.1)
MOTION = load_motion("sine:amp=0.4,freq=2,cycles=1")


def test_a_planned_run_is_the_engine_run_on_its_own():
    """simulate() through its Plan gives the engine's own run, bit for bit: the plan checks and
    resolves (the duration: the motion's end + 5 s), it changes nothing."""
    planned = simulate(SYSTEM, MOTION, engine="analytic-reference")
    alone = registry.get_engine("analytic-reference").simulate(SYSTEM, MOTION, duration=MOTION.end_time + 5.0)
    assert np.array_equal(planned.theta, alone.theta) and np.array_equal(planned.t, alone.t)
    assert planned.t[-1] == pytest.approx(MOTION.end_time + 5.0)


def test_a_plan_is_frozen_and_resolved():
    plan = make_plan(SYSTEM, MOTION, [engine_run("analytic-reference"), ("analytic-reference", {"rtol": 1e-9})])
    assert [r.label for r in plan.runs] == ["analytic-reference", "analytic-reference"]
    assert plan.runs[1].settings.rtol == 1e-9 and plan.duration == pytest.approx(MOTION.end_time + 5.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        plan.duration = 1.0


def test_a_refusal_comes_before_any_run(monkeypatch):
    """Two engines, the second of which does not carry the isolator (MuJoCo refuses the ball in
    a cone): the plan refuses in one line and the first engine never starts."""
    pytest.importorskip("mujoco")
    from isorock.analytic.system import BallInCone
    started = []
    real = registry.Engine.simulate
    monkeypatch.setattr(registry.Engine, "simulate",
                        lambda self, *a, **k: started.append(self.name) or real(self, *a, **k))
    cone = System.with_isolator(height=1.2, width=0.3, mass=250.0, base_mass=500.0,
                                isolator=BallInCone(slope=0.1, rolling_resistance=0.01))
    with pytest.raises(InputError, match="mujoco") as e:
        make_plan(cone, MOTION, [engine_run("analytic-reference"), engine_run("mujoco")])
    assert "\n" not in str(e.value) and started == []


def test_each_engine_is_checked_once(monkeypatch):
    """The registry's check that an engine carries the system and motion (Engine.check_run) is
    made once per engine of the plan, by the plan; the runs trust it."""
    calls = []
    real = registry.Engine.check_run
    monkeypatch.setattr(registry.Engine, "check_run", lambda self, *a: calls.append(self.name) or real(self, *a))
    plan = make_plan(SYSTEM, MOTION, [engine_run("analytic-reference"), engine_run("analytic-reference")],
                     duration=2.0)
    run_plan(plan)
    assert calls == ["analytic-reference", "analytic-reference"]


@pytest.mark.parametrize("kwargs, says", [
    (dict(system="block"), "system = str: must be an isorock System"),
    (dict(motion=[0.1, 0.2]), "motion = list: must be a GroundMotion"),
    (dict(duration=-1.0), "duration = -1.0: must be a positive number of seconds"),
    (dict(theta0=1.0), "theta0 = 1.0: must be a finite tilt smaller than α"),
    (dict(runs=[]), "engine: give one or more"),
    (dict(runs=[("nosuch", None)]), "nosuch"),
    (dict(runs=[("analytic-reference", {"timestep": 1e-3})]), "timestep"),
])
def test_bad_values_are_one_line(kwargs, says):
    args = dict(system=SYSTEM, motion=MOTION, runs=[engine_run("analytic-reference")])
    args.update(kwargs)
    system, motion, runs = args.pop("system"), args.pop("motion"), args.pop("runs")
    with pytest.raises(InputError) as e:
        make_plan(system, motion, runs, **args)
    assert says in str(e.value) and "\n" not in str(e.value)


def test_the_command_lines_plan_is_the_same_plan():
    """`isorock.run(...)` reads its keywords into the same Plan simulate() makes: the same
    history from the same values."""
    import isorock
    tr = isorock.run(engine="analytic-reference", height=1.2, width=0.3, mass=250, base_mass=500, period=2.0,
                     damping_ratio=0.1, motion="sine:amp=0.4,freq=2,cycles=1")
    assert np.array_equal(tr.theta, simulate(SYSTEM, MOTION, engine="analytic-reference").theta)
