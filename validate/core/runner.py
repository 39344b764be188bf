"""Runs whose whole history a command reads (the report's histories and free rocking):
each a task naming its engine as "ENGINE" or "ENGINE:PRESET" plus setting overrides, so
it is small and can be sent to another process; an engine that raises on one task gets
the message in that task's result, never a lost batch.

Where and how tasks run is the one executor's (core.executor.Executor: serially, in worker
processes that can be killed, or on a Dask cluster, with the analytic model's runs kept in
this process); runs read only as summaries (ensembles) are cases run into rows
(core.chunks.run_cases) on the same executor.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial
from typing import Any

from ...analytic import limits
from ...analytic.errors import InputError
from .chunks import worker_pool
from .engines import resolve, runs_here
from .executor import STUCK_AFTER_S, Executor


@dataclass(frozen=True)
class Task:
    key: Any                      # how the caller finds the result
    engine: str                   # "ENGINE" or "ENGINE:PRESET"
    system: Any                   # System
    motion: Any                   # GroundMotion
    duration: float
    theta0: float = 0.0           # rad
    overrides: dict = field(default_factory=dict)  # settings of the engine that differ
    overturn_rule: str | None = None  # model.md's rule, the same for every engine (None: the default)


def run_task(task: Task, threads: int | None = None):
    """(key, Trajectory or None, error message or None). `threads` is the executor's
    (core.executor) and means nothing to one run."""
    try:
        engine, settings = resolve(task.engine, task.overrides)
        traj = engine.simulate(task.system, task.motion, settings=settings, duration=task.duration,
                               theta0=task.theta0, overturn_rule=task.overturn_rule, budget_s=limits.RUN_BUDGET_S)
        return task.key, traj, None
    except InputError:
        raise
    except Exception as e:  # one engine's failure on one case is that case's result
        return task.key, None, f"{type(e).__name__}: {e}"


def run_tasks(tasks: list[Task], *, client=None, workers: int = 1, executor=None, on_result=None,
              work=None, stuck_after: float | None = None) -> dict:
    """Run every task; key → (result or None, error or None). executor: where the contact
    engines' tasks run (core.executor.Executor), the analytic model's staying here; else
    client, a Dask client; else with workers > 1 that many worker processes are started
    for them and stopped after, otherwise all run here. In a worker process a run still
    going `stuck_after` s after it started (default STUCK_AFTER_S: it did not hear its
    own budget) is killed, and its result is None with the reason. `on_result(key)` is
    called as each result arrives. `work(task)` runs one task and returns (key, result,
    error) (default: run_task, a Trajectory); one that measures its result where it ran
    (a row instead of a history) must be picklable, a module-level function or a
    functools.partial of one."""
    out = {}
    own = None
    if executor is None:
        if client is not None:
            executor = Executor(client=client)
        elif workers > 1 and not all(_light(t) for t in tasks):
            own = executor = worker_pool(workers)
        else:
            executor = Executor()

    def arrived(i, outcome):
        if outcome.done:
            key, traj, err = outcome.value
        else:  # killed past STUCK_AFTER_S, its worker died, or the work itself raised
            key, traj, err = tasks[i].key, None, _lost(outcome)
        out[key] = (traj, err)
        if on_result:
            on_result(key)
    try:
        executor.map(partial(_one, work or run_task), [(t,) for t in tasks], here=lambda args: _light(args[0]),
                     budget=STUCK_AFTER_S if stuck_after is None else stuck_after, on_result=arrived)
    finally:
        if own is not None:
            own.close()
    return out


def _lost(outcome) -> str:
    """Why a task has no result, in words."""
    if outcome.status == "timeout":
        return (f"StuckRun: no result {outcome.seconds:.3g} s after it started, past the run's budget "
                f"(RUN_BUDGET_S, heard at the engine's progress calls): its worker process was killed")
    if outcome.status == "crashed":
        return f"WorkerDied: its worker process ended with exit code {outcome.value}"
    return str(outcome.value)


def _one(work, task: Task, threads: int | None = None):
    """work(task), called as the executor calls a task's runner (threads means
    nothing to one run)."""
    return work(task)


def _light(task: Task) -> bool:
    return runs_here(task.engine)


__all__ = ["Task", "run_task", "run_tasks"]
