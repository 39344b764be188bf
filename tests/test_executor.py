"""The one executor (core.executor): tasks run serially here or in worker processes, in
order; a task that never ends is stopped at its budget (wall or CPU time) and its worker
replaced; a worker that dies is a crashed task, not a lost run; bad input is the caller's;
where a task ran does not change its outcome. The tasks that must be stopped never end by
themselves, so no test depends on the machine's speed."""
from __future__ import annotations

import os
import time

import pytest

from isorock.analytic.errors import InputError
from isorock.validate.core.executor import Pool


def square(x):
    return x * x


def sleep_forever(_):
    while True:
        time.sleep(60)


def spin_forever(_):
    while True:
        pass


def die(code):
    os._exit(code)


def refuse(value):
    raise InputError(f"value = {value!r}: must be positive")


def fail(_):
    raise ValueError("broken")


def test_results_come_back_in_the_order_of_the_tasks():
    with Pool(2) as pool:
        out = pool.map(square, [(k,) for k in range(7)])
    assert [o.status for o in out] == ["done"] * 7
    assert [o.value for o in out] == [k * k for k in range(7)]


@pytest.mark.parametrize("fn,clock", [(sleep_forever, "wall"), (spin_forever, "cpu")])
def test_a_task_past_its_budget_is_stopped_and_its_worker_replaced(fn, clock):
    with Pool(1) as pool:
        out = pool.map(fn, [(0,)], budget=0.3, clock=clock)
        assert out[0].status == "timeout"
        # the same pool goes on: its worker was replaced
        assert [o.value for o in pool.map(square, [(3,)])] == [9]


def test_a_dead_worker_is_a_crashed_task_and_the_rest_still_run():
    with Pool(1) as pool:
        out = pool.map(die, [(7,)])
        assert out[0].status == "crashed" and out[0].value == 7
        assert pool.map(square, [(4,)])[0].value == 16


def test_an_exception_is_that_tasks_outcome_and_bad_input_is_the_callers():
    with Pool(1) as pool:
        out = pool.map(fail, [(0,)])
        assert out[0].status == "error" and out[0].value == "ValueError: broken"
        with pytest.raises(InputError, match="must be positive"):
            pool.map(refuse, [(-1,)])


def test_stop_starts_no_further_task():
    with Pool(1) as pool:
        out = pool.map(fail, [(0,), (1,), (2,)], stop=lambda o: o.status == "error")
    assert out[0].status == "error" and out[1:] == [None, None]


def test_bad_pool_arguments_are_named():
    with pytest.raises(InputError, match="workers = 0"):
        Pool(0)
    with Pool(1) as pool, pytest.raises(InputError, match="clock = 'gpu'"):
        pool.map(square, [(1,)], clock="gpu")


class Bar:
    """A progress bar that records its updates (io.progress's shape)."""

    def __init__(self):
        self.updates = []

    def update(self, n=1, work=0.0, note=""):
        self.updates.append((n, work, note))


def test_serial_and_worker_processes_give_the_same_outcomes():
    from isorock.validate.core.executor import Executor
    tasks = [(k,) for k in range(5)]
    with Executor() as here, Executor(processes=2) as there:
        assert here.where == "serial" and there.where == "processes"
        a, b = here.map(square, tasks), there.map(square, tasks)
        assert [o.value for o in a] == [o.value for o in b] == [k * k for k, in tasks]
        assert here.map(fail, [(0,)])[0].value == there.map(fail, [(0,)])[0].value == "ValueError: broken"


def test_progress_is_updated_once_per_task_with_its_weight_cost_and_note():
    from isorock.validate.core.executor import Executor
    bar = Bar()
    Executor().map(square, [(2,), (3,)], progress=bar, weight=lambda a: a[0], cost=lambda a: 10.0 * a[0],
                   note=lambda a: f"x{a[0]}")
    assert bar.updates == [(2, 20.0, "x2"), (3, 30.0, "x3")]


def test_serial_stop_and_bad_input():
    from isorock.validate.core.executor import Executor
    out = Executor().map(fail, [(0,), (1,)], stop=lambda o: o.status == "error")
    assert out[0].status == "error" and isinstance(out[0].error, ValueError) and out[1] is None
    with pytest.raises(InputError, match="must be positive"):
        Executor().map(refuse, [(-1,)])


def _run_square(task, threads):
    if task < 0:
        raise ValueError(f"task {task}")
    return task * task


def test_execute_raises_the_first_failure_and_runs_nothing_after_it():
    from isorock.validate.core.executor import execute
    done = []
    with pytest.raises(ValueError, match="task -1"):
        execute([2, -1, 3], on_done=lambda t, r: done.append((t, r)), run=_run_square, weight=lambda t: 1)
    assert done == [(2, 4)]


def stuck_or_square(task):
    """A validate task's work (core.runner): stuck for ever inside one call (as an engine
    that never calls its progress callback), or its key squared."""
    if task.key < 0:
        sleep_forever(0)
    return task.key, task.key ** 2, None


def test_validates_runs_in_worker_processes_a_stuck_one_killed_the_others_kept():
    """validate's histories (core.runner.run_tasks) run on the executor's worker
    processes: a run that never returns is killed at its budget and reported, not waited
    on, and the runs beside it keep their results."""
    from isorock.validate.core.executor import Executor
    from isorock.validate.core.runner import Task, run_tasks
    tasks = [Task(key=k, engine="mujoco", system=None, motion=None, duration=1.0) for k in (2, -1, 3)]
    with Executor(processes=1) as executor:
        out = run_tasks(tasks, executor=executor, work=stuck_or_square, stuck_after=0.3)
    assert out[2] == (4, None) and out[3] == (9, None)
    assert out[-1][0] is None and out[-1][1].startswith("StuckRun:") and "killed" in out[-1][1]


def test_worker_processes_find_the_analytic_kernel_ready(monkeypatch):
    """Workers load the compiled analytic kernel from its cache; on first use (a fresh
    install) it is built, 1–2 minutes. Built inside a worker, the build counts against the
    task's budget, and a budget shorter than it kills every worker mid-build (a fresh
    install's `isorock stress --quick` timed out on all its analytic cases): the worker pool
    (core.chunks.worker_pool) makes it ready in the parent, once, before the first worker starts."""
    from isorock.validate.core import chunks, executor
    order = []
    monkeypatch.setattr(chunks, "ready_kernel", lambda: order.append("kernel"))
    real = executor._Worker.__init__

    def worker(self, *args, **kwargs):
        order.append("worker")
        real(self, *args, **kwargs)

    monkeypatch.setattr(executor._Worker, "__init__", worker)
    with chunks.worker_pool(2):
        pass
    assert order == ["kernel", "worker", "worker"]


def test_the_executor_knows_no_engine():
    """Issue 35: the executor runs callables; what a task is (a chunk of cases and the engine
    that runs it) lives in core.chunks. Oracle: the executor's own import statements, read
    with ast: none names the registry, a case, a summary row or an engine package."""
    import ast
    from pathlib import Path
    source = Path(executor_module_file()).read_text()
    named = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            named.add(("." * node.level) + (node.module or ""))
        elif isinstance(node, ast.Import):
            named.update(alias.name for alias in node.names)
    engine_facing = {".engines", ".cases", ".summary", ".chunks", "isorock.validate.core.engines",
                     "isorock.analytic.fast", "isorock.analytic.system"}
    assert not named & engine_facing, named & engine_facing
    assert not any(name.split(".")[1:2] in (["mujoco_models"], ["bullet_models"], ["drake_models"], ["dart_models"])
                   for name in named if name.startswith("isorock."))
    for word in ("get_engine", "simulate", "Chunk", "run_chunk"):
        assert word not in source, word


def executor_module_file():
    from isorock.validate.core import executor
    return executor.__file__
