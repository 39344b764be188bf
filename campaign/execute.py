"""Running cases: in chunks, serially or on a Dask cluster, each finished chunk stored
at once so that nothing is lost and nothing is redone.

- A *task* is one chunk of cases for one (engine, setting). The analytic engine runs a
  chunk (hundreds of cases) in one call of the compiled kernel
  (`analytic.fast.simulate_batch`); a contact engine runs its chunk case by case in the
  worker process.
- A chunk's id is a hash of the engine, its settings and its cases' inputs, so it
  depends on what is computed and on nothing else (not on workers, order or time).
- The caller's process writes each finished chunk as `parts/<id>.parquet`, atomically
  (temporary file, then rename): a killed run leaves whole parts or none. A run skips
  the chunks whose part exists, so a finished campaign run again does no work.
- Rows are independent of how they were computed: the kernel and the engines are
  deterministic, so serial, local-cluster and remote-cluster tables are identical
  except `runtime_s` (wall time, and for analytic chunks the chunk's time shared
  equally among its cases).
"""
from __future__ import annotations

import hashlib
import json
import math
import socket
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from isorock.analytic import limits
from isorock.analytic.limits import available_cores

from .spec import Case, EngineSetting

def runs_as_batch(engine: str) -> bool:
    """Does the engine run many cases in one call (its capabilities say so: the compiled
    analytic kernel's `simulate_batch`)? The registry answers; no engine is named here."""
    from isorock.validate.engines import get_engine
    return get_engine(engine).capabilities.batch

# The table's schema: one home. Inputs first (what defines a case), then results.
INPUT_COLUMNS = {
    "case": "int64", "engine": "string", "setting": "string",
    "base": "string", "height": "float64", "width": "float64", "slenderness": "float64",
    "alpha": "float64", "size": "float64", "p": "float64", "mass": "float64",
    "mass_ratio": "float64", "period": "float64", "damping_ratio": "float64",
    "motion": "string", "cycles": "float64", "frequency_ratio": "float64",
    "amplitude_ratio": "float64", "pulse_amp_g": "float64", "pulse_freq_hz": "float64",
    "scale_by": "string", "intensity": "float64", "scale_factor": "float64",
    "duration": "float64", "theta0": "float64",
}
RESULT_COLUMNS = {
    "status": "string", "message": "string", "theta_max_over_alpha": "float64",
    "overturned": "bool", "overturn_mode": "string", "overturn_time": "float64",
    "impacts": "int64", "uplift": "bool", "uplifts": "int64", "u_max": "float64",
    "runtime_s": "float64",
}
COLUMNS = {**INPUT_COLUMNS, **RESULT_COLUMNS}
#: The one column allowed to differ between two runs of the same campaign.
NONDETERMINISTIC_COLUMNS = ("runtime_s",)
SORT_KEYS = ("case", "engine", "setting")

NOT_OVERTURNED, WITHOUT_IMPACT, AFTER_IMPACTS = "none", "without impact", "after impacts"


@dataclass(frozen=True)
class Task:
    id: str
    setting: EngineSetting
    cases: tuple[Case, ...]
    #: model.md's overturning rule for every engine (None: each engine's default, past α)
    overturn_rule: str | None = None


def _schema():
    import pyarrow as pa
    types = {"int64": pa.int64(), "float64": pa.float64(), "string": pa.string(), "bool": pa.bool_()}
    return pa.schema([(k, types[v]) for k, v in COLUMNS.items()])


def _case_inputs(case: Case) -> dict:
    """The table's input columns for a case: the system's from the System itself (so an
    in-memory case needs nothing else), the motion's from `inputs` where given."""
    s = case.system
    row = {k: (math.nan if t == "float64" else "") for k, t in INPUT_COLUMNS.items() if t != "int64"}
    row.update(base="fixed" if s.fixed_base else "isolated", height=s.height, width=s.width,
               slenderness=s.slenderness, alpha=s.alpha, size=s.R, p=s.p, mass=s.mass,
               mass_ratio=s.mu, period=math.nan if s.fixed_base else s.period,
               damping_ratio=math.nan if s.fixed_base else s.damping_ratio,
               motion=getattr(case.motion, "name", ""), duration=case.duration, theta0=case.theta0)
    row.update({k: v for k, v in case.inputs.items() if k in INPUT_COLUMNS})
    row["case"] = case.case
    return row


def chunk_id(setting: EngineSetting, cases, overturn_rule: str | None = None) -> str:
    head = [setting.engine, [list(o) for o in setting.overrides]]
    # a preset and a rule join the hash only when given, so that the ids (and parts) of
    # campaigns made before they existed stay valid
    if setting.preset:
        head.append(["preset", setting.preset])
    if overturn_rule is not None:
        head.append(["overturn_rule", overturn_rule])
    # a record's content joins its case's inputs (a pulse's inputs define it whole, so its
    # ids stay as they were)
    from .build import record_digest
    inputs = []
    for c in cases:
        row, digest = _case_inputs(c), record_digest(c)
        if digest is not None:
            row["record_sha256"] = digest
        inputs.append(row)
    body = json.dumps([*head, inputs], sort_keys=True, default=str)
    return hashlib.sha256(body.encode()).hexdigest()[:20]


def make_tasks(cases: list[Case], settings, *, analytic_chunk: int, contact_chunk: int,
               overturn_rule: str | None = None) -> list[Task]:
    tasks = []
    for setting in settings:
        size = analytic_chunk if runs_as_batch(setting.engine) else contact_chunk
        for lo in range(0, len(cases), size):
            chunk = tuple(cases[lo:lo + size])
            tasks.append(Task(chunk_id(setting, chunk, overturn_rule), setting, chunk, overturn_rule))
    return tasks


# --- running one task (in a worker, or here) --------------------------------------------

def _overturn_mode(overturned: bool, impacts_before: int) -> str:
    if not overturned:
        return NOT_OVERTURNED
    return WITHOUT_IMPACT if impacts_before == 0 else AFTER_IMPACTS


def run_task(task: Task, threads: int | None = 1) -> list[dict]:
    """The rows of one chunk. threads: the analytic kernel's threads, or a contact
    engine's runs side by side (1 in a Dask worker, which is one core; None: all cores,
    for the serial path)."""
    if runs_as_batch(task.setting.engine):
        return _run_batch(task, threads)
    return _run_contact(task, threads)


def _run_batch(task: Task, threads) -> list[dict]:
    from dataclasses import replace

    from isorock.analytic.fast import simulate_batch

    from .build import motion_of
    settings = task.setting.settings()
    if task.overturn_rule is not None:
        settings = replace(settings, overturn=task.overturn_rule)
    cases = task.cases
    start = time.perf_counter()
    out = simulate_batch([c.system for c in cases], [motion_of(c) for c in cases],
                         duration=np.array([c.duration for c in cases]),
                         theta0=np.array([c.theta0 for c in cases]), settings=settings,
                         workers=threads)
    per_case = (time.perf_counter() - start) / len(cases)
    rows = []
    for case, r in zip(cases, out):
        overturned = bool(r["overturned"])
        rows.append({**_case_inputs(case), "engine": task.setting.engine, "setting": task.setting.label,
                     # a failed case says why (the kernel's message); others need no words
                     "status": str(r["status"]), "message": str(r.get("message", "")),
                     "theta_max_over_alpha": float(r["theta_max_over_alpha"]), "overturned": overturned,
                     # a batch run stops when the block falls, so its impacts all precede it
                     "overturn_mode": _overturn_mode(overturned, int(r["impacts"])),
                     "overturn_time": math.nan if r["overturn_time"] is None else float(r["overturn_time"]),
                     "impacts": int(r["impacts"]), "uplift": int(r["uplifts"]) > 0,
                     "uplifts": int(r["uplifts"]), "u_max": float(r["u_max"]), "runtime_s": per_case})
    return rows


def _run_contact(task: Task, threads: int | None) -> list[dict]:
    """A contact engine's chunk: its batch path (MuJoCo's: one scene per system, `threads`
    runs side by side) or one run after another; each row what the run alone gives.
    Impacts are counted, not mapped to effective β: no column reads it."""
    from isorock.validate.engines import get_engine

    from .build import motion_of
    engine = get_engine(task.setting.engine)
    start = time.perf_counter()
    results = engine.simulate_many([(c.system, motion_of(c), c.duration, c.theta0) for c in task.cases],
                                   settings=task.setting.settings(), overturn_rule=task.overturn_rule,
                                   effective_beta=False, budget_s=limits.RUN_BUDGET_S,
                                   threads=available_cores() if threads is None else threads)
    # runs overlap in threads, so a run's own wall time says little: each row gets the
    # chunk's time shared equally, as an analytic chunk's rows do
    share = (time.perf_counter() - start) / max(len(task.cases), 1)
    rows = []
    for case, tr in zip(task.cases, results):
        base = {**_case_inputs(case), "engine": task.setting.engine, "setting": task.setting.label}
        if isinstance(tr, Exception):  # one failed case is a row saying so, not a lost chunk
            rows.append({**base, "status": "failed", "message": f"{type(tr).__name__}: {tr}",
                         "theta_max_over_alpha": math.nan, "overturned": False,
                         "overturn_mode": NOT_OVERTURNED, "overturn_time": math.nan, "impacts": 0,
                         "uplift": False, "uplifts": 0, "u_max": math.nan, "runtime_s": share})
            continue
        t_fall = tr.overturn_time if tr.overturned and tr.overturn_time is not None else math.inf
        before = sum(1 for i in tr.counted_impacts if i.t <= t_fall)
        rows.append({**base, "status": str(tr.status), "message": tr.message,
                     "theta_max_over_alpha": tr.theta_max_over_alpha, "overturned": bool(tr.overturned),
                     "overturn_mode": _overturn_mode(tr.overturned, before),
                     "overturn_time": math.nan if tr.overturn_time is None else float(tr.overturn_time),
                     "impacts": tr.impact_count, "uplift": tr.uplifts > 0, "uplifts": tr.uplifts,
                     "u_max": tr.u_max, "runtime_s": share})
    return rows


# --- tables -----------------------------------------------------------------------------

def rows_to_table(rows: list[dict]):
    import pyarrow as pa
    schema = _schema()
    return pa.Table.from_pylist([{k: r.get(k) for k in COLUMNS} for r in rows], schema=schema)


def sort_table(table):
    return table.sort_by([(k, "ascending") for k in SORT_KEYS])


def write_part(path: Path, rows: list[dict]) -> None:
    import pyarrow.parquet as pq
    from isorock.validate.output import write_atomic
    write_atomic(path, lambda tmp: pq.write_table(rows_to_table(rows), tmp))


def part_problem(path: Path, task: Task) -> str | None:
    """Why the part at `path` cannot stand for `task`'s rows (None: it can): unreadable,
    another schema, or not exactly one row per case of the chunk under its engine and
    setting. A part copied over another, damaged or from another version of the table
    is run again instead of being trusted by its name."""
    import pyarrow.parquet as pq
    try:
        table = pq.read_table(path)
    except FileNotFoundError:
        return "missing"
    except Exception as e:  # noqa: BLE001 - any unreadable file is a part to run again
        return f"unreadable ({type(e).__name__})"
    if table.schema.remove_metadata() != _schema():
        return "another schema"
    want = sorted(c.case for c in task.cases)
    if sorted(table["case"].to_pylist()) != want:
        return f"{table.num_rows} rows whose cases are not the chunk's {len(want)}"
    if set(table["engine"].to_pylist()) != {task.setting.engine} or \
            set(table["setting"].to_pylist()) != {task.setting.label}:
        return "rows of another engine or setting"
    return None


def read_parts(paths) -> "pyarrow.Table":
    import pyarrow as pa
    import pyarrow.parquet as pq
    tables = [pq.read_table(p, schema=_schema()) for p in paths]
    return sort_table(pa.concat_tables(tables) if tables else _schema().empty_table())


# --- progress ---------------------------------------------------------------------------

#: what a batch engine's simulated second costs against a contact engine's, for the ETA
#: alone: the compiled analytic kernel makes ~1,000 runs of 40 s per second on 2 cores, a
#: contact engine 1–10 simulated seconds per wall second (docs/campaigns.md, Throughput)
BATCH_COST = 1e-4
#: the share of a campaign's expected work done before its progress bar gives an ETA
ETA_AFTER = 1e-3


def expected_cost(task: Task) -> float:
    """A task's expected cost, in contact-engine simulated seconds: what the progress
    bar's ETA is measured in (the run count alone made a campaign's analytic third, done
    in seconds, promise the contact runs in seconds too)."""
    simulated = sum(c.duration for c in task.cases)
    return simulated * (BATCH_COST if runs_as_batch(task.setting.engine) else 1.0)


class Progress:
    """One progress bar with an ETA on stderr: redrawn in place on a terminal, else a
    line at most every `every` seconds (logs stay short). It counts runs; the ETA follows
    `work` (the tasks' expected cost, `update`'s second argument) where given, else the
    run count."""

    def __init__(self, total: int, *, work: float | None = None, stream=None, every: float = 10.0,
                 label: str = "runs"):
        self.total, self.done, self.label = total, 0, label
        self.work, self.work_done = work, 0.0
        self.stream = stream if stream is not None else sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.every, self.start, self.last = every, time.monotonic(), -math.inf

    def update(self, n: int, work: float = 0.0) -> None:
        self.done += n
        self.work_done += work
        now = time.monotonic()
        if self.tty or now - self.last >= self.every or self.done >= self.total:
            self.last = now
            self._draw(now)

    def _draw(self, now):
        elapsed = now - self.start
        frac = self.done / self.total if self.total else 1.0
        ahead = min(1.0, self.work_done / self.work) if self.work else frac
        # below a thousandth of the work done (a campaign's analytic batches, say, whose
        # seconds are mostly the cluster's start) the rate says nothing yet: "?"
        eta = elapsed * (1 - ahead) / ahead if ahead >= ETA_AFTER else math.nan
        eta_s = f"{eta:5.0f} s" if math.isfinite(eta) else "    ? s"
        if self.tty:
            bar = "#" * int(30 * frac)
            self.stream.write(f"\r[{bar:<30}] {self.done}/{self.total} {self.label} "
                              f"{elapsed:5.0f} s, ETA {eta_s}")
            if self.done >= self.total:
                self.stream.write("\n")
        else:
            self.stream.write(f"{self.done}/{self.total} {self.label} ({100 * frac:.0f}%), "
                              f"{elapsed:.0f} s, ETA {eta_s}\n")
        self.stream.flush()


# --- executing a list of tasks ----------------------------------------------------------

def execute(tasks: list, *, client=None, threads: int | None = None, on_done, progress=None, here=None,
            run=None, weight=None, cost=None) -> int:
    """Run `tasks`, calling on_done(task, result) here as each one finishes (in the order
    they finish). client: a dask.distributed Client, or None to run serially in this
    process. run(task, threads): a task's result (default: `run_task`, a chunk's rows;
    `isorock validate` runs its histories through here too). here(task): tasks that run
    in this process even with a client (e.g. the analytic model's, loaded here already and
    done in milliseconds), while the cluster works on the others. progress.update(n) after
    each task, n = weight(task) (default: its number of cases), with the work it was,
    cost(task) (the ETA's measure, `expected_cost`; 0 without `cost`). Returns the number
    of tasks run."""
    run = run or run_task
    weight = weight or (lambda task: len(task.cases))
    local = [t for t in tasks if client is None or (here is not None and here(t))]
    remote = [t for t in tasks if client is not None and not (here is not None and here(t))]

    def finished(task, result):
        on_done(task, result)
        if progress:
            progress.update(weight(task), cost(task) if cost else 0.0)

    by_key, futures = {}, []
    for task in remote:  # submitted first, so that the cluster works while this process does its part
        fut = client.submit(run, task, 1, pure=False)
        by_key[fut.key] = task
        futures.append(fut)
    try:
        for task in local:
            finished(task, run(task, threads))
        if futures:
            from dask.distributed import as_completed
            for fut in as_completed(futures):
                task = by_key[fut.key]
                finished(task, fut.result())
                fut.release()
    except BaseException:
        if futures:
            client.cancel(futures)
        raise
    return len(tasks)


#: Dask's housekeeping, slowed down for a cluster without a dashboard: its defaults (an
#: event-loop tick every 20 ms, a system monitor every 0.5 s, a memory monitor every 0.1 s,
#: a statistical profiler sampling the workers every 10 ms) keep an idle 2-worker cluster
#: at 0.13–0.14 of a core, measured; these at 0.02. On 2 cores that is 7% of the machine,
#: taken from the runs for as long as a campaign lasts.
QUIET_CLUSTER = {"distributed.admin.tick.interval": "1s", "distributed.admin.system-monitor.interval": "5s",
                 "distributed.worker.memory.monitor-interval": "1s", "distributed.worker.profile.enabled": False}


def local_client(workers: int):
    """A LocalCluster of `workers` single-threaded worker processes (the analytic kernel
    and the contact engines each use one core per process), with QUIET_CLUSTER's
    housekeeping (the workers take the configuration they are started with)."""
    import logging

    import dask
    from dask.distributed import Client, LocalCluster
    # Dask's nanny starts workers with MALLOC_TRIM_THRESHOLD_=65536, so that freed memory
    # goes back to the system at once: for PyBullet's stepping loop (many small Python
    # objects per step) that is 30% more CPU, in system calls (measured: 32 runs, 2.35 s
    # → 3.05 s). A campaign's workers hold little memory; glibc's own threshold serves.
    environ = {k: v for k, v in dask.config.get("distributed.nanny.pre-spawn-environ", {}).items()
               if k != "MALLOC_TRIM_THRESHOLD_"}
    with dask.config.set({**QUIET_CLUSTER, "distributed.nanny.pre-spawn-environ": environ}):
        # the scheduler serves HTTP routes even without a dashboard, on port 8787 unless
        # told otherwise: with another cluster on this machine that printed "Port 8787 is
        # already in use" on stderr. Any free port on this host alone will do.
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
                               silence_logs=logging.ERROR)
        return Client(cluster)


#: how long a scheduler has to greet a probe (s): a Dask scheduler writes its handshake
#: as soon as it accepts a connection, within milliseconds on a network
GREETING_TIMEOUT = 10.0
#: a Dask handshake's first 8 bytes are its length (little-endian uint64): a few hundred
#: bytes; "HTTP/1.1" read so is 3.5e18 (the "Unable to allocate 3.07 EiB" a 403 gave)
MAX_GREETING = 1 << 20


def check_scheduler(address: str, timeout: float = GREETING_TIMEOUT) -> None:
    """Refuse (InputError) an address that is not one, or a TCP server that does not
    greet as a Dask scheduler does, within `timeout` s. Dask's own connect bounds the TCP
    connect alone: an HTTP server, which waits for a request, held it for ever."""
    from urllib.parse import urlsplit

    from isorock.analytic.errors import InputError

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


def close_client(client) -> None:
    """Close a client opened here, and its LocalCluster if it started one."""
    cluster = getattr(client, "cluster", None)
    client.close()
    if cluster is not None:
        cluster.close()
