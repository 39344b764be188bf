"""Stepping the MuJoCo scene: `mujoco.rollout` runs the loop in C, chunk by chunk, and
the states become a RawHistory (measured outside the engine, by the registry).

The ground motion is applied exactly as generalized forces in the (translating) ground
frame: −m ẍg on the block's x dof and −m_b ẍg on the base's, and a vertical üv as −m üv on
the block's z dof (the base rides the ground vertically). A force is held over a
step, so ẍg is taken at the step's middle: the impulse it gives is then right to
second order (taken at the step's start it lags by dt/2). PyBullet does the same.

Outputs follow model.md: u (m) is the base displacement relative to the ground, θ (rad)
the rotation about +y (θ > 0 rocks about corner O at x = +b). A run stops by the shared
rules of `isorock.analytic.kinematics.first_stop` (a non-finite state, the block lying on
its side, or falling on a fixed base after the motion); MuJoCo's auto-reset is off, so a
blow-up cannot pass silently.

`simulate_many` runs many cases (a campaign's chunk, an ensemble) exactly as `simulate`
runs each: one compiled scene per distinct system, and runs stepped side by side by
Python threads, since `mujoco.rollout` releases the GIL while it steps.
"""
from __future__ import annotations

import functools
import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import mujoco
import numpy as np
from mujoco import rollout

from ..analytic import kinematics
from ..analytic.motion import GroundMotion
from ..analytic.engine_protocol import run_inputs
from ..analytic.errors import require
from ..analytic.isolator_parts import CONTACT_ISOLATORS, PLANE_ISOLATORS, check_contact_isolator
from ..analytic.limits import RunBudget
from ..analytic.rest_phase import stepped_throughout
from ..analytic.status import Status
from ..analytic.system import LINEAR, System
from ..analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, RawHistory

from .event_resolved import run_event_resolved
from .scene import build_model
from . import phases
from .settings import Settings
from .state import (Layout, StepRecord, fresh_data, raw_history, stop_in, vertical_at, vertical_record,
                    warning_failure, warnings_as_status)
#: Steps per call of mujoco.rollout: the progress callback and the stop rules run
#: between calls. The warm start is carried across calls, so the split does not change
#: the result (tested).
CHUNK_STEPS = 20_000


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """Simulate the scene from t = 0 to `duration` (s; default: the motion's end + 5 s,
    or 10 s without motion) from rest, tilted by `theta0` (rad) about its corner.
    progress: optional callable(t, duration), called between rollout chunks about
    once a second."""
    motion, duration, settings = _inputs(settings or Settings(), system, motion, duration, theta0)
    model = _scene(system, settings, motion.transverse is not None)
    return run_model(model, system, motion, settings=settings, duration=duration, theta0=theta0,
                     progress=progress)


def run_model(model: mujoco.MjModel, system: System, motion: GroundMotion, *, settings: Settings,
              duration: float, theta0: float = 0.0, progress=None, chunk_steps: int | None = None) -> RawHistory:
    """`simulate` on an already compiled scene (for measuring variants of the model)."""
    with warnings_as_status() as warnings:
        return _run(model, system, motion, settings, duration, theta0, progress, chunk_steps, warnings)


def _run(model, system, motion, settings, duration, theta0, progress, chunk_steps, warnings) -> RawHistory:
    """One run; MuJoCo's warnings arrive in the list `warnings` (the caller's handler)."""
    start = time.perf_counter()
    if settings.phased and stepped_throughout(system, motion) is not None:  # why: there
        settings = replace(settings, phased=False)
    lay = Layout(model, system, settings.joint, transverse=motion.transverse is not None)
    # a scene of one component (no y joint for the base, or the block on planar joints) or the
    # event-resolved scheme (its forces are ẍg's alone) would lose ÿg, unsaid
    require(not lay.transverse or (lay.free and settings.impact_timestep is None
                                   and (system.fixed_base or lay.base_yv is not None)), "model", "this scene",
            "built with build_model(..., transverse=True), on the free joint, stepped at one timestep, for a motion "
            "of two horizontal components")
    dt = model.opt.timestep
    nstep = int(math.floor(duration / dt + 1e-9))
    if settings.impact_timestep is not None:
        return run_event_resolved(model, system, motion, settings, lay, nstep, theta0, progress, start,
                                  duration, warnings)

    chunk_steps = chunk_steps or CHUNK_STEPS
    data = fresh_data(model)
    xg, zg = StepRecord(motion, dt, nstep), vertical_record(motion, dt, nstep)
    yg = None if motion.transverse is None else StepRecord(motion.transverse, dt, nstep)
    state0 = lay.initial_state(model, system, theta0)
    warm = np.zeros(lay.nv)
    rows = [state0[None, :]]
    throttle = kinematics.Throttle(progress, duration)
    # coarse steps away from impacts, in every run whose stepping follows its phase
    flight = phases.Flight(model, lay, system, settings, dt) if phases.coarse_applies(settings) else None
    if phases.applies(settings, theta0, motion, nstep):
        rows, status, message, stop_reason = _phased(model, data, lay, system, motion, settings, xg,
                                                     state0, rows, nstep, dt, throttle, warnings, flight)
    else:
        rows, status, message, stop_reason, _, _ = _roll(model, data, lay, system, motion, xg, state0, warm,
                                                         rows, nstep, chunk_steps, dt, throttle, warnings,
                                                         flight=flight, zg=zg, yg=yg)
    runtime = time.perf_counter() - start
    states = np.concatenate(rows)
    raw = raw_history(lay, system, motion, states, dt, runtime, status, message, stop_reason, t=states[:, 0])
    # the numbers this run used (Settings.for_system may have made them finer than asked)
    raw.extras.update(timestep=float(dt), solref_0=float(settings.solref[0]), solref_1=float(settings.solref[1]))
    why = stepped_throughout(system, motion)
    if why is not None:  # how the run was stepped, when not as Settings.phased asks
        raw.extras.update(stepping=f"throughout at the timestep (no rest phase, no coarse steps: {why})")
    if lay.slider_q is not None:  # the bearing's slider position u_p per row, as the analytic run's
        raw.extras.update(isolator_slider=states[:, 1 + lay.slider_q].copy())
    return raw


def step_cost(system: System, settings: Settings | None = None, *, steps: int = 20_000) -> float:
    """CPU seconds per step of the contact scene itself, the block resting on its base (the
    paper's scene: two bodies, four box–box contacts), stepped by `mujoco.rollout` in C
    with no Python between steps: the limit of any stepping scheme over this scene,
    timestep / step_cost simulated s per CPU s (`isorock bench` reports each run's speed
    as a fraction of it)."""
    settings = (settings or Settings()).for_system(system)
    model = build_model(system, settings)
    data = mujoco.MjData(model)
    lay = Layout(model, system, settings.joint)
    state0, forces = lay.initial_state(model, system, 0.0), lay.forces(system, np.zeros(steps))[None]
    rollout.rollout(model, data, state0, forces[:, :100], control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED)
    start = time.process_time()
    rollout.rollout(model, data, state0, forces, control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED)
    return (time.process_time() - start) / steps


@functools.lru_cache(maxsize=64)
def _scene(system: System, settings: Settings, transverse: bool = False) -> mujoco.MjModel:
    """The compiled scene of a (system, settings), kept for the runs that follow (compiling
    costs ~9 ms, a tenth of a 40 s record's run): private to this module, which never
    changes a model it steps (the coarse step is stepped on a copy, phases.Flight)."""
    return build_model(system, settings, transverse=transverse)


def _inputs(given: Settings, system: System, motion, duration, theta0):
    """(motion, duration, settings) of one run: the shared checks (run_inputs) with the steps
    the run will take, then the settings derived for the system and that duration (the
    step a whole divisor of it, so the run ends on it)."""
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD,
                                  settings=given.for_system(system), isolators=CONTACT_ISOLATORS,
                                  kinetic_friction=False, two_edges=True, transverse=True,
                                  transverse_isolators=PLANE_ISOLATORS)
    check_contact_isolator(system, "mujoco")
    if motion.transverse is not None:
        # two components: the body on the free joint (the block's planar joints cannot leave
        # the plane), stepped throughout (the rest phase and the coarse steps are planar)
        require(given.impact_timestep is None, "impact_timestep", given.impact_timestep,
                "None with two horizontal components (event-resolved stepping is planar)")
        given = replace(given, joint="free", phased=False)
    derived = given.for_system(system, duration)
    if system.isolator_kind != LINEAR:
        require(derived.impact_timestep is None, "impact_timestep", derived.impact_timestep,
                "None with a non-linear isolator (its dry friction's time constant follows the one timestep)")
    return motion, duration, derived


def simulate_many(runs, *, settings: Settings | None = None, threads: int = 1, budget_s: float | None = None) -> list:
    """Many runs, each exactly as `simulate` makes it: `runs` is a sequence of (system,
    motion, duration, theta0), as `simulate` takes them; returns, per run, its RawHistory
    or the exception it raised (one bad case is that case's result, not a lost batch).

    A scene is compiled once per distinct system (`_scene` keeps the last 64; a chunk
    of a campaign shares one or two), and `threads` runs step side by side, each with its own MjData: rollout
    releases the GIL while it steps, so a process uses that many cores. Each run's steps,
    forces, warm starts and stop rules are those of `simulate`, so each history is
    identical to a run made alone (tested). MuJoCo reports warnings through one
    process-wide handler, which cannot say which thread's run raised one: if any run
    raised one, every run of the batch is made again alone, so that each run's failure
    is its own, as `simulate` reports it."""
    settings = settings or Settings()
    runs = list(runs)

    def prepare(run):
        system, motion, duration, theta0 = run
        motion, duration, derived = _inputs(settings, system, motion, duration, theta0)  # per system
        return _scene(system, derived, motion.transverse is not None), derived, system, motion, duration, theta0

    prepared = []
    for run in runs:
        try:
            prepared.append(prepare(run))
        except Exception as e:  # noqa: BLE001 — returned as this run's result
            prepared.append(e)

    def one(item, warnings):
        if isinstance(item, Exception):
            return item
        model, derived, system, motion, duration, theta0 = item
        try:
            # each run its own wall-clock budget (analytic.limits.RunBudget), as `simulate` gives one
            progress = None if budget_s is None else RunBudget(budget_s)
            return _run(model, system, motion, derived, duration, theta0, progress, None, warnings)
        except Exception as e:  # noqa: BLE001
            return e

    def alone(item):
        with warnings_as_status() as own:
            return one(item, own)

    if threads <= 1 or len(prepared) <= 1:
        return [alone(item) for item in prepared]
    with warnings_as_status() as warnings:
        with ThreadPoolExecutor(max_workers=min(threads, len(prepared))) as pool:
            out = list(pool.map(lambda item: one(item, warnings), prepared))
        warned = bool(warnings)
    return [alone(item) for item in prepared] if warned else out


def _phased(model, data, lay, system, motion, settings, xg, state0, rows, nstep, dt, throttle, warnings, flight):
    """Full-scene stepping only where contact can happen (phases.py): full phases until
    the block has settled (coarse away from impacts with `flight`), rest phases (no
    contact scene) until the base's acceleration nears the uplift threshold."""
    ph = phases.Phases(model, lay, system, settings, xg, dt)
    k, state, warm = 0, state0, np.zeros(lay.nv)
    while True:
        rows, status, message, stop_reason, k, _ = _roll(model, data, lay, system, motion, xg, state, warm,
                                                         rows, nstep, phases.FULL_CHUNK, dt, throttle, warnings,
                                                         start=k, until=ph.rest_finder(), flight=flight)
        if status is not Status.COMPLETED or stop_reason is not None or k >= nstep:
            return rows, status, message, stop_reason
        rest, k, warm = ph.rest(rows[-1][-1], k, nstep)
        if rest.shape[0]:
            rows.append(rest)
            state = rest[-1]
        else:
            state = rows[-1][-1]
        throttle(k * dt)
        if k >= nstep:
            return rows, status, message, stop_reason


def _roll(model, data, lay, system, motion, xg, state0, warm, rows, nstep, chunk_steps, dt, throttle, warnings,
          start=0, until=None, flight=None, zg=None, yg=None):
    """Contact-scene rollout from step `start` to `nstep`, or, with `until(chunk, steps)`, to
    the row it names (the phased run's rest); with `flight` (phases.Flight), coarse steps
    away from impacts; `zg`: üv at each step's middle (state.vertical_record), or None. Each row's column 0 is its time, step index × dt (MuJoCo's own
    time sums the step and drifts). Returns (rows, status, message, stop_reason, steps
    done, warm start)."""
    status, message, stop_reason = Status.COMPLETED, "reached the end time", None
    done = start
    tilt = _tilt(lay.histories(system, state0[None, :]), 0)  # (θ, θ̇) of state0
    while done < nstep:
        if flight is None:
            multiple, n = 1, min(chunk_steps, nstep - done)
        else:
            multiple, n = flight.plan(*tilt, done, nstep)
        if multiple == 1:
            # ẍg at each step's middle (xg), as forces on the block's and the base's x dofs
            step_model, step_data = model, data
            f = lay.forces(system, xg[done:done + n], None if zg is None else zg[done:done + n],
                           None if yg is None else yg[done:done + n])
        else:
            step_model, step_data = flight.model, flight.data
            mids = (done + multiple * (np.arange(n) + 0.5)) * dt
            f = lay.forces(system, np.asarray(motion(mids), dtype=float), vertical_at(motion, mids),
                           None if motion.transverse is None else motion.transverse_at(mids))
        state, _ = rollout.rollout(step_model, step_data, state0, f[None],
                                   control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED,
                                   initial_warmstart=warm)
        chunk = state[0]
        steps = done + multiple * np.arange(1, n + 1)
        chunk[:, 0] = steps * dt
        failure = warning_failure(warnings, step_data)
        if failure is not None:
            text, at = failure
            keep = int(np.searchsorted(chunk[:, 0], at)) if math.isfinite(at) else 0
            rows.append(chunk[:keep])
            status, message = Status.FAILED, f"MuJoCo: {text} (try a smaller timestep)"
            break
        # the chunk's θ, u, … once: every rule below reads them
        hist = lay.histories(system, chunk)
        if flight is not None:
            kept = flight.keep(hist["theta"], hist["theta_dot"], steps, multiple)
            if kept == 0:
                continue
            if kept < chunk.shape[0]:
                chunk, steps = chunk[:kept], steps[:kept]
                hist = {name: column[:kept] for name, column in hist.items()}
        t = chunk[:, 0]
        k, reason = stop_in(lay, system, chunk, t, motion, hist)
        if reason == "non-finite":
            rows.append(chunk[:k])
            status = Status.FAILED
            message = (f"the state stopped being finite at t = {t[k]:.6g} s; "
                       "try a smaller timestep or a longer solref timeconst")
            break
        if reason is not None:
            rows.append(chunk[:k + 1])
            stop_reason = reason
            break
        settled = until(chunk, steps, hist) if until is not None else None
        if settled is not None:
            rows.append(chunk[:settled + 1])
            done = int(steps[settled])
            break
        rows.append(chunk)
        done = int(steps[-1])
        state0, tilt = chunk[-1], _tilt(hist, -1)
        warm = step_data.qacc_warmstart.copy()
        throttle(done * dt)
    return rows, status, message, stop_reason, done, warm


def _tilt(hist: dict, i: int) -> tuple[float, float]:
    """(θ, θ̇) of row i of a chunk's histories."""
    return float(hist["theta"][i]), float(hist["theta_dot"][i])
