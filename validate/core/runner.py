"""Runs whose whole history a command reads (the report's histories and free rocking):
each a task naming its engine as "ENGINE" or "ENGINE:PRESET" plus setting overrides, so
it is small and can be sent to another process; an engine that raises on one task gets
the message in that task's result, never a lost batch.

Where and how tasks run is the one executor's (core.executor.execute: serially, or on a
Dask cluster with the analytic model's runs kept in this process); runs read only as
summaries (ensembles) are cases run into rows (core.executor.run_cases).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from isorock.analytic.errors import InputError


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
    from .engines import resolve
    try:
        engine, settings = resolve(task.engine, task.overrides)
        from isorock.analytic.limits import RUN_BUDGET_S
        traj = engine.simulate(task.system, task.motion, settings=settings, duration=task.duration,
                               theta0=task.theta0, overturn_rule=task.overturn_rule, budget_s=RUN_BUDGET_S)
        return task.key, traj, None
    except InputError:
        raise
    except Exception as e:  # one engine's failure on one case is that case's result
        return task.key, None, f"{type(e).__name__}: {e}"


def run_tasks(tasks: list[Task], *, client=None, workers: int = 1, on_result=None,
              work=None) -> dict:
    """Run every task; key → (result or None, error or None). client: a Dask client
    (core.executor.local_client) for the contact engines' tasks, the analytic model's
    staying here; None: with workers > 1 a local cluster of that many processes is started
    for them and closed after, otherwise all run here. `on_result(key)`
    is called as each result arrives. `work(task)` runs one task and returns (key, result,
    error) (default: run_task, a Trajectory); one that measures its result where it ran (a
    row instead of a history) must be picklable, a module-level function or a
    functools.partial of one."""
    from functools import partial

    from .executor import close_client, execute, local_client
    out = {}
    own = None
    if client is None and workers > 1 and not all(_light(t) for t in tasks):
        own = client = local_client(workers)

    def done(_task, result):
        key, traj, err = result
        out[key] = (traj, err)
        if on_result:
            on_result(key)
    try:
        execute(tasks, client=client, on_done=done, run=partial(_one, work or run_task), here=_light,
                weight=lambda _t: 1)
    finally:
        if own is not None:
            close_client(own)
    return out


def _one(work, task: Task, threads: int | None = None):
    """work(task), called as the executor calls a task's runner (threads means
    nothing to one run)."""
    return work(task)


def _light(task: Task) -> bool:
    from .engines import runs_here
    return runs_here(task.engine)


__all__ = ["Task", "run_task", "run_tasks"]
