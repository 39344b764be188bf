"""Running many simulations for a command: the engines whose runs take milliseconds (the
analytic model) in this process, the contact engines in worker processes, every result
keyed by its task, so the outcome does not depend on the order in which they finish.

A task names its engine as "ENGINE" or "ENGINE:PRESET" plus setting overrides, so it is
small and can be sent to another process; an engine that raises on one task gets the
message in that task's result, never a lost batch.
"""
from __future__ import annotations

import multiprocessing as mp
import os
from concurrent.futures import ProcessPoolExecutor, as_completed
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


def resolve(engine: str, overrides: dict | None = None):
    """(Engine, Settings) of "ENGINE" or "ENGINE:PRESET" with `overrides` applied to the
    settings that the engine has (others are ignored: a friction given for every engine
    means nothing to the analytic model)."""
    from dataclasses import fields, replace

    from isorock.validate.engines import get_engine
    name, _, preset = engine.partition(":")
    e = get_engine(name)
    settings = e.preset(preset) if preset else e.settings()
    mine = {k: v for k, v in (overrides or {}).items() if k in {f.name for f in fields(settings)}}
    if mine:
        settings = replace(settings, **mine) if preset else e.settings(**mine)
    return e, settings


def run_task(task: Task):
    """(key, Trajectory or None, error message or None)."""
    try:
        engine, settings = resolve(task.engine, task.overrides)
        traj = engine.simulate(task.system, task.motion, settings=settings, duration=task.duration,
                               theta0=task.theta0, overturn_rule=task.overturn_rule)
        return task.key, traj, None
    except InputError:
        raise
    except Exception as e:  # one engine's failure on one case is that case's result
        return task.key, None, f"{type(e).__name__}: {e}"


def default_workers() -> int:
    return max(1, min(2, os.cpu_count() or 1))


def run_tasks(tasks: list[Task], *, workers: int | None = None, in_process=None, on_result=None,
              work=run_task) -> dict:
    """Run every task; key → (Trajectory or None, error or None). `in_process(task)` says
    which tasks run here (default: those of engines that run as batches, i.e. the compiled
    analytic model, and any task when workers ≤ 1); the rest go to `workers` processes
    (spawned: a forked copy of a process that loaded numba's threads is not safe).
    `on_result(key)` is called as each result arrives (a progress bar). `work(task)` runs
    one task and returns (key, result, error) (default: run_task, a Trajectory); one that
    measures its result where it ran (a row instead of a history) must be picklable, a
    module-level function or a functools.partial of one."""
    workers = default_workers() if workers is None else workers
    in_process = in_process or _light
    out = {}
    local = [t for t in tasks if workers <= 1 or in_process(t)]
    remote = [t for t in tasks if not (workers <= 1 or in_process(t))]
    pool = None
    try:
        if remote:
            pool = ProcessPoolExecutor(max_workers=min(workers, len(remote)), mp_context=mp.get_context("spawn"))
            futures = [pool.submit(work, t) for t in remote]
        for t in local:
            key, traj, err = work(t)
            out[key] = (traj, err)
            if on_result:
                on_result(key)
        if remote:
            for f in as_completed(futures):
                key, traj, err = f.result()
                out[key] = (traj, err)
                if on_result:
                    on_result(key)
    finally:
        if pool is not None:
            pool.shutdown(wait=True, cancel_futures=True)
    return out


def _light(task: Task) -> bool:
    from isorock.validate.engines import get_engine
    try:
        return get_engine(task.engine.partition(":")[0]).capabilities.exact_impacts
    except ImportError:
        return True  # reported by run_task in this process


__all__ = ["Task", "resolve", "run_task", "run_tasks", "default_workers"]
