"""The one executor's Pool (core.executor): tasks run in worker processes, in order; a task
that never ends is stopped at its budget (wall or CPU time) and its worker replaced; a
worker that dies is a crashed task, not a lost run; bad input is the caller's. The tasks
that must be stopped never end by themselves, so no test depends on the machine's speed."""
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


def test_a_pool_readies_the_analytic_kernel_before_its_workers_start(monkeypatch):
    """Workers load the compiled analytic kernel from its cache; on first use (a fresh
    install) it is built, 1–2 minutes. Built inside a worker, the build counts against the
    task's budget, and a budget shorter than it kills every worker mid-build (a fresh
    install's `isorock stress --quick` timed out on all its analytic cases): the Pool makes
    it ready in the parent, once, before the first worker starts."""
    from isorock.validate.core import executor
    order = []
    monkeypatch.setattr(executor, "ready_kernel", lambda: order.append("kernel"))
    real = executor._Worker.__init__

    def worker(self, *args, **kwargs):
        order.append("worker")
        real(self, *args, **kwargs)

    monkeypatch.setattr(executor._Worker, "__init__", worker)
    with executor.Pool(2):
        pass
    assert order == ["kernel", "worker", "worker"]
