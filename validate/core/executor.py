"""The one executor: every command's runs (validate, sweep, atlas, stress, calibrate) go
through `Executor.map`, serially in this process, in worker processes that can be killed,
or on a Dask cluster (a local one or a scheduler's), each result reported as it arrives
and the one progress bar (io.progress) updated with the work done. It runs callables and
knows no engine: what a task is (a chunk of cases, core.chunks; a validate history,
core.runner) is its caller's.

- `Executor(processes=n | client=…, prepare=…)`: where the runs go; `map(fn, tasks,
  budget=…, clock="wall" | "cpu")`: an `Outcome` per task; a run past its budget in a
  worker process is killed ("timeout"), a worker that dies is "crashed", an exception is
  that task's "error"; `here(args)` keeps some in this process while the workers or a
  cluster work on the others (the analytic model's, done in milliseconds). `Pool(n)` is an
  executor of n processes. Worker processes: validate (its histories, core.runner, and
  ensembles), atlas, stress, calibrate; Dask or serial: sweep.
- `execute(tasks, run=…, executor=… | client=…, on_done=…)`: `map` for tasks that fail
  loudly (the first exception is raised): every table of runs (core.chunks.run_cases,
  campaigns).
"""
from __future__ import annotations

import logging
import multiprocessing
import os
import socket
import sys
import time
from dataclasses import dataclass, field
from multiprocessing import resource_tracker
from multiprocessing.connection import wait
from urllib.parse import urlsplit

from ...analytic.errors import InputError
from ...analytic import limits
from ...analytic.limits import available_cores

def default_workers() -> int:
    """Processes for a command's contact runs (validate's, atlas's and calibrate's worker
    processes): two, or fewer where this process may use fewer cores (available_cores)."""
    return max(1, min(2, available_cores()))


def execute(tasks: list, *, run, client=None, executor: "Executor | None" = None, threads: int | None = None, on_done,
            progress=None, here=None, weight=None, cost=None) -> int:
    """`Executor.map` for tasks that fail loudly (a chunk of a table, a history of
    validate's): on_done(task, result) here as each one finishes (in the order they
    finish); the first task that raises stops the others and its exception is raised
    here. executor: where they run (an Executor); else client: a dask.distributed Client,
    or None to run serially in this process.
    run(task, threads): a task's result (e.g. a chunk's rows, core.chunks);
    `threads` is what a task run here may use, 1 on a cluster's worker (one core each).
    here(task): tasks that run in this process even with a client (e.g. the analytic
    model's, loaded here already and done in milliseconds), while the cluster works on
    the others. progress.update(n, work) after each task, n = weight(task) (default: 1),
    work = cost(task) (the ETA's measure, e.g. core.chunks.expected_cost; 0 without `cost`). Returns the number of tasks run."""
    weight = weight or (lambda task: 1)

    executor = executor if executor is not None else Executor(client=client)

    def local(task) -> bool:
        return executor.where == "serial" or (here is not None and here(task))
    outcomes = executor.map(
        run, [(t, threads if local(t) else 1) for t in tasks], here=lambda args: local(args[0]),
        on_result=lambda i, o: on_done(tasks[i], o.value) if o.done else None,
        stop=lambda o: not o.done, progress=progress, weight=lambda args: weight(args[0]),
        cost=(lambda args: cost(args[0])) if cost else None)
    for outcome in outcomes:
        if outcome is not None and not outcome.done:
            raise outcome.error if outcome.error is not None else RuntimeError(str(outcome.value))
    return len(tasks)


#: Dask's housekeeping, slowed down for a cluster without a dashboard: its defaults (an
#: event-loop tick every 20 ms, a system monitor every 0.5 s, a memory monitor every 0.1 s,
#: a statistical profiler sampling the workers every 10 ms) keep an idle 2-worker cluster
#: at 0.13–0.14 of a core, measured; these at 0.02. On 2 cores that is 7% of the machine,
#: taken from the runs for as long as a campaign lasts.
QUIET_CLUSTER = {"distributed.admin.tick.interval": "1s", "distributed.admin.system-monitor.interval": "5s",
                 "distributed.worker.memory.monitor-interval": "1s", "distributed.worker.profile.enabled": False}


def quiet_resource_tracker() -> None:
    """Start multiprocessing's resource tracker (the process that unlinks the semaphores
    its workers leave) with its stderr on the null device, before any worker process
    starts: a command stopped by a signal ends its workers at once, and the tracker, which
    outlives it, printed 'There appear to be N leaked semaphore objects' after the command's
    one line (issue 34). It still unlinks them; only its warning goes unsaid."""
    try:
        saved = os.dup(2)
    except OSError:  # no standard error to keep quiet
        resource_tracker.ensure_running()
        return
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        sys.stderr.flush()
        os.dup2(null, 2)
        resource_tracker.ensure_running()  # started once per process; its stderr is the fd 2 of now
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        os.close(null)


def local_client(workers: int):
    """A LocalCluster of `workers` single-threaded worker processes (the analytic kernel
    and the contact engines each use one core per process), with QUIET_CLUSTER's
    housekeeping (the workers take the configuration they are started with)."""
    import dask  # lazy: Dask (~1 s) only for a cluster
    from dask.distributed import Client, LocalCluster
    # Dask's nanny starts workers with MALLOC_TRIM_THRESHOLD_=65536, so that freed memory
    # goes back to the system at once: for PyBullet's stepping loop (many small Python
    # objects per step) that is 30% more CPU, in system calls (measured: 32 runs, 2.35 s
    # → 3.05 s). A campaign's workers hold little memory; glibc's own threshold serves.
    environ = {k: v for k, v in dask.config.get("distributed.nanny.pre-spawn-environ", {}).items()
               if k != "MALLOC_TRIM_THRESHOLD_"}
    refuse_unrepeatable_main()  # its workers are spawned too
    quiet_resource_tracker()
    with dask.config.set({**QUIET_CLUSTER, "distributed.nanny.pre-spawn-environ": environ}):
        # the scheduler serves HTTP routes even without a dashboard, on port 8787 unless
        # told otherwise: with another cluster on this machine that printed "Port 8787 is
        # already in use" on stderr. Any free port on this host alone will do.
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                               # what its workers would log is for no user: a failed task comes back
                               # as the task's error, and a worker outliving a stopped command
                               # (its heartbeat to a scheduler gone) printed its traceback after
                               # the command's one line (issue 34)
                               silence_logs=logging.CRITICAL)
        return Client(cluster)


#: how long a scheduler has to greet a probe (s): a Dask scheduler writes its handshake
#: as soon as it accepts a connection, within milliseconds on a network
GREETING_TIMEOUT = 10.0
#: a Dask handshake's first 8 bytes are its length (little-endian uint64): a few hundred
#: bytes; "HTTP/1.1" read so is 3.5e18 (the "Unable to allocate 3.07 EiB" a 403 gave)
MAX_GREETING = 1 << 20


def check_scheduler(address: str, timeout: float | None = None) -> None:
    """Refuse (InputError) an address that is not one, or a TCP server that does not
    greet as a Dask scheduler does, within `timeout` s (None: GREETING_TIMEOUT, read at the
    call). Dask's own connect bounds the TCP connect alone: an HTTP server, which waits for
    a request, held it for ever."""
    timeout = GREETING_TIMEOUT if timeout is None else timeout
    def refuse(why):
        return InputError(f"--scheduler = {address!r}: must be a running Dask scheduler, e.g. "
                          f"tcp://host:8786 ({why})")
    text = address if "://" in address else f"tcp://{address}"
    try:
        parts = urlsplit(text)
        host, port = parts.hostname, parts.port
    except ValueError as e:
        raise refuse(f"not an address: {e}") from None
    if parts.scheme not in ("tcp", "tls", "inproc", "ucx", "ws", "wss") or not host or " " in address:
        raise refuse("not an address")
    if parts.scheme != "tcp":
        return  # TLS and the others greet inside their own protocol: Dask's connect judges them
    if port is None:
        raise refuse("no port")
    try:
        with socket.create_connection((host, port), timeout=timeout) as sock:
            sock.settimeout(timeout)
            head = b""
            while len(head) < 8:
                chunk = sock.recv(8 - len(head))
                if not chunk:
                    raise refuse("it closed the connection without a Dask handshake")
                head += chunk
    except TimeoutError:
        raise refuse(f"no Dask handshake within {timeout:g} s") from None
    except OSError as e:
        raise refuse(e.strerror or str(e)) from None
    if not 0 < int.from_bytes(head, "little") <= MAX_GREETING:
        raise refuse(f"it answered {head!r}, not a Dask handshake")


#: how long closing a cluster on the way out of a stopped command may take (s): its workers
#: are told to stop, then killed by their nannies
CLOSE_TIMEOUT = 5.0


def close_client(client, *, stopping: bool = False) -> None:
    """Close a client opened here, and its LocalCluster if it started one. `stopping`: the
    command is ending on a signal or an error; Dask's and tornado's shutdown chatter (a
    worker's heartbeat to a scheduler already gone, a callback of a loop being torn down,
    each with its traceback) is not for the user, whose one line follows (issue 34)."""
    cluster = getattr(client, "cluster", None)
    level = logging.root.manager.disable
    if stopping:
        logging.disable(logging.CRITICAL)
    try:
        client.close(timeout=CLOSE_TIMEOUT)
        if cluster is not None:
            cluster.close(timeout=CLOSE_TIMEOUT)
    finally:
        logging.disable(level)


def client_for(client=None, workers: int = 0, scheduler: str | None = None):
    """(client, close): an explicit client; one connected to `scheduler`; a LocalCluster
    of `workers` processes; or none (serial, workers = 0)."""
    if client is not None:
        return client, False
    if scheduler:
        from dask.distributed import Client  # lazy: Dask only for a cluster
        check_scheduler(scheduler)
        try:
            return Client(scheduler, timeout="10s"), True
        except (OSError, TimeoutError) as e:
            raise InputError(f"--scheduler = {scheduler!r}: must be a reachable Dask scheduler ({e})") from None
    if workers and workers > 0:
        return local_client(workers), True
    return None, False


# --- the executor: where a command's runs go, each stopped at its budget ----------------

@dataclass(frozen=True)
class Outcome:
    """What became of one task: `status` "done" (its `value`), "error" (it raised: `value`
    is "Type: message", `error` the exception itself where it was raised here or on a
    Dask worker), "timeout" (past its budget: its worker process was killed) or
    "crashed" (its worker process died: `value` is the exit code); `seconds` of wall
    time (on a Dask cluster, since the task was submitted)."""

    status: str
    value: object = None
    seconds: float = 0.0
    error: BaseException | None = field(default=None, compare=False, repr=False)

    @property
    def done(self) -> bool:
        return self.status == "done"


def _error(e: BaseException, seconds: float) -> Outcome:
    return Outcome("error", f"{type(e).__name__}: {e}", seconds, e)


def _serve(conn) -> None:
    """A worker process's loop: run each (function, args) it is sent, until None or its
    pipe closes. An InputError is the caller's (bad input); any other exception the task's.
    Asked to stop, it leaves at once (_leave)."""
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError, KeyboardInterrupt):
            return
        if task is None:
            _leave(conn)
        fn, args = task
        # loaded (the function's module imported, the arguments unpickled): the run's
        # budget counts from here, not from a fresh worker's imports
        conn.send(("started", None))
        try:
            conn.send(("done", fn(*args)))
        except InputError as e:
            conn.send(("input", str(e)))
        except Exception as e:  # noqa: BLE001 — one task's failure is that task's outcome
            conn.send(("error", f"{type(e).__name__}: {e}"))


def _leave(conn) -> None:
    """End a worker asked to stop, without the interpreter's teardown: every result is sent
    and nothing of a task outlives it (each writes its files whole inside the task), while
    tearing down the engines a worker loaded (MuJoCo, Bullet, Drake, JAX) took ~1.3 s per
    worker on the shared 2 cores, paid at every pool's close."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
    conn.close()
    os._exit(0)


class _Worker:
    """One worker process serving _serve over a pipe; `restart` kills it and starts another
    (a run stuck inside an engine cannot be stopped from outside in any other way)."""

    def __init__(self, context):
        self.context = context
        self._start()

    def _start(self):
        self.conn, child = self.context.Pipe()
        self.process = self.context.Process(target=_serve, args=(child,), daemon=True)
        self.process.start()
        child.close()
        self._cpu = None
        #: whether it has taken a task (a worker that dies before could not start at all)
        self.started = False

    def cpu_seconds(self) -> float:
        """CPU time the worker process has used (user + system), s."""
        import psutil  # lazy: only where a worker's CPU time is read
        if self._cpu is None:
            self._cpu = psutil.Process(self.process.pid)
        t = self._cpu.cpu_times()
        return t.user + t.system

    def restart(self):
        self.stop(kill=True)
        self._start()

    def stop(self, kill: bool = False):
        try:
            if not kill:
                self.conn.send(None)
        except (OSError, ValueError):
            pass
        self.process.join(0 if kill else 2.0)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
        self.conn.close()


#: The exit code of a worker process that found itself running a script's unguarded
#: top level (exit_if_bootstrapping).
BOOTSTRAP_EXIT = 3


def exit_if_bootstrapping() -> None:
    """A script that starts worker processes at its top level, without the `__main__`
    guard, is run again in each worker as it starts ("spawn"), which would start workers in
    each, and Python answers with a wall of tracebacks. Such a worker stops here at once,
    quietly (BOOTSTRAP_EXIT); the process that started it then says what to do in one line
    (_refuse_if_never_started; isorock.sweep for its Dask workers). A notebook's code, or
    `python -c`, is not run again in a worker: there is nothing to guard."""
    # a process started by "spawn" runs the parent's script again as the module __mp_main__
    if multiprocessing.current_process().name != "MainProcess" and "__mp_main__" in sys.modules:
        os._exit(BOOTSTRAP_EXIT)


#: what a worker started by "spawn" could not start, said in one line (both where a worker
#: dies before its first task and before any is started)
UNREPEATABLE_MAIN = ("the worker processes for the contact engines could not start{why}: Python could not run this "
                     "program again in them, as for code read from standard input; run it from a file, or in one "
                     "process (workers=1, --workers 1; isorock.sweep: workers=0)")


def refuse_unrepeatable_main() -> None:
    """Before any worker is spawned: a worker runs the parent's program again ("spawn"),
    from its file; a program read from standard input (`python - < script.py`) has none
    ('<stdin>'), and each worker died printing its FileNotFoundError before the one line
    said so (issue 34). Code without a file (`python -c`, a notebook) is not run again."""
    if multiprocessing.current_process().name != "MainProcess":
        return
    main = sys.modules.get("__main__")
    spec = getattr(main, "__spec__", None)
    path = getattr(main, "__file__", None)
    if (spec is None or not spec.name) and path is not None and not os.path.isfile(path):
        raise InputError(UNREPEATABLE_MAIN.format(why=f" (the program, {path!r}, is not a file)"))


def _refuse_if_never_started(worker: "_Worker") -> None:
    """Raise one line for a worker that died before it took its first task: it could not
    start (it stopped at exit_if_bootstrapping, or Python could not run the program again
    in it, as for code read from standard input), so no run would ever go to it."""
    worker.process.join(1.0)
    if worker.started:
        return
    code = worker.process.exitcode
    if code == BOOTSTRAP_EXIT:
        raise InputError("the worker processes for the contact engines could not start: this script starts "
                         "them at its top level, and each runs it again; call isorock under "
                         "`if __name__ == \"__main__\":`, or run in one process (workers=1, --workers 1)") from None
    raise InputError(UNREPEATABLE_MAIN.format(why=f" (exit code {code}: or they could not load their task)")) from None


#: How often (s) the executor reads its worker processes' CPU clocks under a CPU budget.
CPU_POLL = 0.25
CLOCKS = ("wall", "cpu")


class Executor:
    """The one executor of every command (validate, sweep, atlas, stress, calibrate): where
    its runs go, chosen once, and one `map` whatever the choice.

    - serial (the default): one after another in this process;
    - `processes=n`: n worker processes, spawned, not forked (a fork of a process whose
      numba threads have started is not safe), so a task's function must be importable
      at module level; a task past its budget, counted from when its worker has loaded it
      (a fresh worker's imports do not count), is stopped by killing its worker, which is
      replaced (a run stuck inside an engine cannot be stopped in any other way);
    - `client=`: a Dask client (a local cluster or a scheduler's, `client_for`), its
      workers one core each; `close=True` closes it (and its LocalCluster) with the
      executor.

    A run's budget is wall seconds (clock "wall": how long a user waits) or its process's
    CPU seconds (clock "cpu": others' load on a shared machine does not count against
    it). Only worker processes can be killed: in this process and on Dask the budget is
    the engines' own (analytic.limits.RUN_BUDGET_S, heard at each progress call of a
    run). `prepare()` runs here once before worker processes start (core.chunks.worker_pool:
    the compiled kernel they would each build). Use as a context manager (worker processes
    and an owned client stop on leaving it)."""

    def __init__(self, *, processes: int = 0, client=None, close: bool = False, prepare=None):
        if processes and client is not None:
            raise ValueError("an Executor runs on worker processes or on a Dask client, not both")
        if processes < 0:
            raise InputError(f"workers = {processes!r}: must be a whole number of processes ≥ 0")
        self.client, self._close_client = client, close
        self.workers: list[_Worker] = []
        if processes:
            exit_if_bootstrapping()
            refuse_unrepeatable_main()
            context = multiprocessing.get_context("spawn")
            quiet_resource_tracker()
            if prepare is not None:  # e.g. a compiled kernel built here once, not inside each worker's task budget
                prepare()
            self.workers = [_Worker(context) for _ in range(processes)]

    @classmethod
    def on(cls, client=None, workers: int = 0, scheduler: str | None = None) -> "Executor":
        """An executor on `client`; on a client connected to `scheduler`; on a LocalCluster
        of `workers` Dask processes; or serial (client_for), closing what it opened."""
        live, close = client_for(client, workers, scheduler)
        return cls(client=live, close=close)

    @property
    def where(self) -> str:
        return "processes" if self.workers else "dask" if self.client is not None else "serial"

    def map(self, fn, tasks, *, budget: float | None = None, clock: str = "wall", here=None, on_result=None,
            stop=None, progress=None, weight=None, cost=None, note=None) -> list[Outcome | None]:
        """fn(*args) for each args of `tasks`: an Outcome per task, in the order of
        `tasks`. on_result(index, outcome) here as each arrives (in the order they
        finish); then progress.update(weight(args) or 1, cost(args) or 0, note(args) or
        "") (io.progress's bar: its ETA follows `cost`). stop(outcome) true: start no
        further task (those not started stay None; on Dask they are cancelled).
        here(args) true: that task runs in this process whatever the executor (with Dask,
        while the cluster works on the others). An InputError raised by fn is raised here
        (bad input is the caller's); any other exception is that task's outcome."""
        if clock not in CLOCKS:
            raise InputError(f"clock = {clock!r}: must be 'wall' or 'cpu'")
        tasks = [tuple(t) for t in tasks]
        results: list[Outcome | None] = [None] * len(tasks)
        state = {"stopped": False}

        def arrived(i: int, outcome: Outcome) -> None:
            results[i] = outcome
            if on_result:
                on_result(i, outcome)
            if progress is not None:
                args = tasks[i]
                progress.update(weight(args) if weight else 1, cost(args) if cost else 0.0,
                                note(args) if note else "")
            state["stopped"] = state["stopped"] or bool(stop and stop(outcome))

        mine = [i for i in range(len(tasks)) if self.where == "serial" or (here is not None and here(tasks[i]))]
        others = [i for i in range(len(tasks)) if not (self.where == "serial" or (here is not None and here(tasks[i])))]
        if self.where == "dask":
            self._on_dask(fn, tasks, mine, others, arrived, state)
        elif self.where == "processes":
            self._in_processes(fn, tasks, others, mine, arrived, state, budget, clock)
        else:
            self._here(fn, tasks, mine, arrived, state)
        return results

    @staticmethod
    def _here(fn, tasks, indices, arrived, state) -> None:
        for i in indices:
            if state["stopped"]:
                return
            start = time.perf_counter()
            try:
                value = fn(*tasks[i])
            except InputError:
                raise
            except Exception as e:  # noqa: BLE001 — one task's failure is that task's outcome
                arrived(i, _error(e, time.perf_counter() - start))
            else:
                arrived(i, Outcome("done", value, time.perf_counter() - start))

    def _on_dask(self, fn, tasks, mine, others, arrived, state) -> None:
        by_key, futures, submitted = {}, [], time.perf_counter()
        for i in others:  # submitted first, so that the cluster works while this process does its part
            fut = self.client.submit(fn, *tasks[i], pure=False)
            by_key[fut.key] = i
            futures.append(fut)
        try:
            self._here(fn, tasks, mine, arrived, state)
            if futures and not state["stopped"]:
                from dask.distributed import as_completed  # lazy: Dask only for a cluster
                for fut in as_completed(futures):
                    i = by_key[fut.key]
                    try:
                        value = fut.result()
                    except InputError:
                        raise
                    except Exception as e:  # noqa: BLE001 — that task's outcome
                        arrived(i, _error(e, time.perf_counter() - submitted))
                    else:
                        arrived(i, Outcome("done", value, time.perf_counter() - submitted))
                    fut.release()
                    if state["stopped"]:
                        break
            if state["stopped"] and futures:
                self.client.cancel(futures)
        except BaseException:
            if futures:
                self.client.cancel(futures)
            raise

    def _in_processes(self, fn, tasks, indices, mine, arrived, state, budget, clock) -> None:
        """The workers run `indices`; this process runs `mine` (here(args)) one at a time
        while they work, reading their results and clocks between its own."""
        pending, busy, local = list(indices)[::-1], {}, list(mine)[::-1]
        while busy or ((pending or local) and not state["stopped"]):
            for w in self.workers:
                if w not in busy and pending and not state["stopped"]:
                    i = pending.pop()
                    try:
                        w.conn.send((fn, tasks[i]))
                    except OSError:  # it died before reading a task (a broken pipe)
                        _refuse_if_never_started(w)
                        raise
                    busy[w] = (i, time.perf_counter(), None, 0.0)  # (task, sent, started, CPU s then)
            if local and not state["stopped"]:
                self._here(fn, tasks, [local.pop()], arrived, state)
                timeout = 0.0  # read what the workers finished meanwhile, then the next one here
            elif budget is None:
                timeout = None
            elif clock == "wall":
                started = [start for _, _, start, _ in busy.values() if start is not None]
                timeout = max(0.0, min(started) + budget - time.perf_counter()) if started else None
            else:
                timeout = CPU_POLL
            ready = set(wait([w.conn for w in busy], timeout=timeout))
            for w in list(busy):
                i, sent, start, cpu0 = busy[w]
                elapsed = time.perf_counter() - sent
                if w.conn in ready:
                    try:
                        kind, value = w.conn.recv()
                    except (EOFError, OSError):
                        _refuse_if_never_started(w)
                        code = w.process.exitcode
                        w.restart()
                        outcome = Outcome("crashed", code, elapsed)
                    else:
                        if kind == "input":
                            raise InputError(value)
                        if kind == "started":
                            w.started = True
                            busy[w] = (i, sent, time.perf_counter(), w.cpu_seconds() if clock == "cpu" else 0.0)
                            continue
                        outcome = Outcome(kind, value, elapsed)
                elif (budget is not None and start is not None
                      and (time.perf_counter() - start if clock == "wall" else w.cpu_seconds() - cpu0) >= budget):
                    w.restart()  # stuck inside the engine: the run has failed
                    outcome = Outcome("timeout", None, elapsed)
                else:
                    continue
                del busy[w]
                arrived(i, outcome)

    def close(self) -> None:
        for w in self.workers:
            w.stop()
        if self._close_client and self.client is not None:
            close_client(self.client)
            self.client = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class borrowed:
    """An executor the caller keeps, used in a `with` without being closed by it."""

    def __init__(self, executor: Executor):
        self.executor = executor

    def __enter__(self) -> Executor:
        return self.executor

    def __exit__(self, *exc):
        return False


#: Wall seconds after which a run in a worker process counts as stuck and its worker is
#: killed: twice the budget every run hears (analytic.limits.RUN_BUDGET_S, at the engine's
#: progress calls), so that only a run stuck where it cannot hear it (inside one call of an
#: engine's own code) is killed, and a run that stops itself says why in its own words.
STUCK_AFTER_S = 2 * limits.RUN_BUDGET_S


def Pool(workers: int, prepare=None) -> Executor:
    """An executor of `workers` worker processes that can be killed (core.chunks.worker_pool:
    with the compiled kernel made ready first)."""
    if workers < 1:
        raise InputError(f"workers = {workers!r}: must be a whole number of processes ≥ 1")
    return Executor(processes=workers, prepare=prepare)
