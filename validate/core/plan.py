"""One run, planned (issue 35): every input checked once, before any work, into one frozen
`Plan` that its runs then follow, from Python values, with no command line in between.

    plan = make_plan(system, motion, [engine_run("analytic"), engine_run("mujoco", {"timestep": 2e-4})])
    runs = run_plan(plan)                      # label → Trajectory, in the order given

`isorock.simulate` is one engine's plan; `isorock run` (and `isorock.run`) read their options
into these values and make the same plan, so the three refuse the same inputs with the same
messages. What is checked once here: the system is a System and the motion a GroundMotion; each
engine carries the system and the motion (Engine.check_run: its isolator, a statue's two edges,
its friction, a vertical component); the work bounds of analytic.limits for each engine's steps
as its settings derive them for this system (engine_protocol.run_inputs, which also gives the
duration: the motion's end + 5 s where none is given). An engine's own `simulate` keeps its
own checks: it is public too, and a plugin's is not ours to trust.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass

from ...analytic.engine_protocol import DEFAULT_IMPACT_THRESHOLD, run_inputs
from ...analytic.engines import first_run_reference
from ...analytic.errors import InputError, python_number
from ...analytic.limits import BudgetExceeded
from ...analytic.motion import GroundMotion
from ...analytic.system import System

from .engines import REFERENCE, Engine, canonical, choose, get_engine, settings_used


@dataclass(frozen=True)
class EngineRun:
    """One engine of a plan: its label as asked ("ENGINE" or "ENGINE:PRESET"), the Engine and
    the Settings it runs with (the preset's or the defaults, with the overrides given; an
    engine whose settings follow the system derives the rest when it runs)."""

    label: str
    engine: Engine
    settings: object


def engine_run(engine: str = REFERENCE, settings=None) -> EngineRun:
    """An EngineRun from Python values: `engine` "ENGINE" or "ENGINE:PRESET" (`isorock presets`
    lists them); `settings` None (the engine's or the preset's), a dict of overrides checked
    against the engine's settings (an unknown one is an InputError naming it), or the engine's
    own Settings."""
    if not isinstance(engine, str):
        raise InputError(f"engine = {engine!r}: must be a name, ENGINE or ENGINE:PRESET")
    if settings is None or isinstance(settings, dict):
        choice = choose(engine, settings or {}, strict=True)
        return EngineRun(engine, get_engine(choice.engine), choice.settings())
    choice = choose(canonical(engine))  # the engine and its preset checked, as a dict's are
    own = get_engine(choice.engine).Settings
    if not isinstance(settings, own):
        raise InputError(f"settings = {type(settings).__name__}: must be a dict of overrides or engine "
                         f"{choice.engine!r}'s {own.__name__}")
    if choice.preset:  # the preset's settings or these: one of them would be dropped unsaid
        raise InputError(f"engine = {engine!r} with settings = {own.__name__}(…): give the preset or the "
                         "Settings, not both (a dict of overrides goes on top of a preset)")
    return EngineRun(engine, get_engine(choice.engine), settings)


@dataclass(frozen=True)
class Plan:
    """What a run will simulate, every input checked: the engines with their settings, the
    system, the motion (cut to the work bounds), the duration (s), the initial tilt θ0 (rad),
    model.md's impact-counting threshold (a fraction of α) and overturning rule (None: past α)."""

    runs: tuple[EngineRun, ...]
    system: object
    motion: object
    duration: float
    theta0: float
    impact_threshold: float = DEFAULT_IMPACT_THRESHOLD
    overturn_rule: str | None = None


def make_plan(system, motion, runs, *, duration: float | None = None, theta0: float = 0.0,
              impact_threshold: float = DEFAULT_IMPACT_THRESHOLD, overturn_rule: str | None = None,
              first_run: bool = False) -> Plan:
    """The Plan of `runs` (EngineRuns, or (engine, settings) pairs as engine_run takes them) on
    `system` under `motion` (None: none, free rocking from theta0), every check made here once.
    first_run: the compiled engine takes the SciPy reference where its kernel is not built yet
    and the run is short (analytic.engines.first_run_reference, said on stderr): what `isorock
    run` asks, so that a first run starts at once."""
    if not isinstance(system, System):
        raise InputError(f"system = {type(system).__name__}: must be an isorock System (System.fixed, "
                         "System.isolated, System.with_isolator)")
    if motion is not None and not isinstance(motion, GroundMotion):
        raise InputError(f"motion = {type(motion).__name__}: must be a GroundMotion (isorock.load_motion reads a "
                         "pulse or a record) or None")
    if duration is not None and not python_number("duration", duration, "a positive number of seconds") > 0:
        raise InputError(f"duration = {duration!r}: must be a positive number of seconds")
    runs = [r if isinstance(r, EngineRun) else engine_run(*r) for r in runs]
    if not runs:
        raise InputError("engine: give one or more")
    # the work bounds (duration, isolator, every engine's steps) before any work
    cut, length = motion, duration
    for r in runs:
        r.engine.check_run(system, motion)
        cut, length = run_inputs(system, cut, duration, theta0, impact_threshold,
                                 settings=settings_used(r.settings, system),
                                 isolators=r.engine.capabilities.isolators,
                                 two_edges=getattr(r.engine.capabilities, "two_edges", False),
                                 transverse=getattr(r.engine.capabilities, "transverse", False),
                                 transverse_isolators=getattr(r.engine.capabilities, "transverse_isolators",
                                                              ("linear",)))
    if first_run:
        runs = [_first_run(r, system, cut, length) for r in runs]
    return Plan(tuple(runs), system, cut, length, theta0, impact_threshold, overturn_rule)


def _first_run(r: EngineRun, system, motion, duration) -> EngineRun:
    why = first_run_reference(system, motion, duration) if r.engine.name == REFERENCE else None
    if not why:
        return r
    print(f"isorock: {r.label}: {why}", file=sys.stderr, flush=True)
    return EngineRun(r.label, get_engine("analytic-reference"), r.settings)


def run_plan(plan: Plan, *, progress=None, budget_s: float | None = None, on_start=None) -> dict:
    """label → Trajectory of each of the plan's runs, in its order; each within `budget_s` s
    (analytic.limits.RunBudget): past it, the BudgetExceeded raised carries the run's `label`.
    progress(t, total): each run's; on_start(label): before each run."""
    out = {}
    for r in plan.runs:
        if on_start is not None:
            on_start(r.label)
        try:
            out[r.label] = r.engine.simulate(plan.system, plan.motion, settings=r.settings, duration=plan.duration,
                                             theta0=plan.theta0, impact_threshold=plan.impact_threshold,
                                             overturn_rule=plan.overturn_rule, progress=progress, budget_s=budget_s,
                                             checked=True)
        except BudgetExceeded as e:
            e.label = r.label
            raise
    return out


def simulate(system, motion=None, *, engine: str = REFERENCE, settings=None, duration: float | None = None,
             theta0: float = 0.0, overturn_rule: str | None = None, budget_s: float | None = None):
    """One run of any engine, from Python values (`isorock.simulate`): one engine's Plan.

    system: an isorock.analytic.System; motion: a GroundMotion (None: no motion, free rocking
    from theta0, rad); engine: "ENGINE" or "ENGINE:PRESET" (`isorock presets` lists them);
    settings: None (the engine's or the preset's), a dict of overrides checked against the
    engine's settings (an unknown one is an InputError naming it), or the engine's own Settings;
    duration (s; None: the motion's end + 5 s). Returns the measured Trajectory every engine's
    run becomes (a contact engine's history measured as the commands measure it)."""
    plan = make_plan(system, motion, [engine_run(engine, settings)], duration=duration, theta0=theta0,
                     overturn_rule=overturn_rule)
    return next(iter(run_plan(plan, budget_s=budget_s).values()))
