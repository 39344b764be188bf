"""Cases into rows, engine by engine: every table of runs (a campaign's, design's, an
ensemble's, `run_cases`) is cut into chunks here and each chunk run by its engine, on the
generic executor (core.executor), which runs callables and knows no engine.

- A `Chunk` is a list of cases for one engine choice: the analytic engine runs a
  chunk (hundreds of cases) in one call of the compiled kernel
  (`analytic.fast.simulate_batch`); a contact engine runs its chunk case by case. Its rows
  are summary rows (core.summary). `run_cases` runs in-memory cases into a table.
- A chunk's id is a hash of the engine, its settings and its cases' inputs, so it depends
  on what is computed and on nothing else (not on workers, order or time): campaigns
  store each finished chunk under it (campaign.parts) and never redo one.
- Rows are independent of how they were computed: the kernel and the engines are
  deterministic, so serial, local-cluster and remote-cluster tables are identical except
  `runtime_s`.
- `worker_pool(n)`: the executor's worker processes, with the compiled kernel made ready
  in this process first (`ready_kernel`).
"""
from __future__ import annotations

import hashlib
import json
import time
from dataclasses import dataclass, replace

import numpy as np

from ...analytic import fast, limits
from ...analytic.limits import available_cores
from ...analytic.system import paper_system

from .cases import Case, motion_of, record_digest
from .engines import EngineChoice, choose, get_engine, runs_here
from .executor import Executor, Pool, borrowed, execute
from .summary import case_inputs, row_of_batch, row_of_failure, row_of_trajectory, rows_to_table, sort_table


#: Default cases per chunk: the analytic kernel runs a whole chunk in one call.
ANALYTIC_CHUNK = 500
CONTACT_CHUNK = 4


def runs_as_batch(engine: str) -> bool:
    """Does the engine run many cases in one call (its capabilities say so: the compiled
    analytic kernel's `simulate_batch`)? The registry answers; no engine is named here."""
    return get_engine(engine).capabilities.batch


@dataclass(frozen=True)
class Chunk:
    """Cases run together under one engine choice: the unit of work sent to a worker and
    stored as one part (campaign.parts), named by `id` (chunk_id)."""

    id: str
    setting: EngineChoice
    cases: tuple[Case, ...]
    #: model.md's overturning rule for every engine (None: each engine's default, past α)
    overturn_rule: str | None = None


def chunk_id(setting: EngineChoice, cases, overturn_rule: str | None = None) -> str:
    head = [setting.engine, [list(o) for o in setting.overrides]]
    # a preset and a rule join the hash only when given, so that the ids (and parts) of
    # campaigns made before they existed stay valid
    if setting.preset:
        head.append(["preset", setting.preset])
    if overturn_rule is not None:
        head.append(["overturn_rule", overturn_rule])
    # a record's content joins its case's inputs (a pulse's inputs define it whole, so its
    # ids stay as they were)
    inputs = []
    for c in cases:
        row, digest = case_inputs(c), record_digest(c)
        if c.system.friction is None:  # a statue that cannot slip hashes as before friction was a column
            row.pop("friction")
        if not row["statue"]:  # the block H × B hashes as before a statue's mesh was a column
            row.pop("statue"), row.pop("azimuth")
        elif c.inputs.get("statue_sha256"):  # a mesh file's content, not only its name
            row["statue_sha256"] = c.inputs["statue_sha256"]
        if digest is not None:
            row["record_sha256"] = digest
        inputs.append(row)
    body = json.dumps([*head, inputs], sort_keys=True, default=str)
    return hashlib.sha256(body.encode()).hexdigest()[:20]


def make_tasks(cases: list[Case], settings, *, analytic_chunk: int, contact_chunk: int,
               overturn_rule: str | None = None) -> list[Chunk]:
    tasks = []
    for setting in settings:
        size = analytic_chunk if runs_as_batch(setting.engine) else contact_chunk
        for lo in range(0, len(cases), size):
            chunk = tuple(cases[lo:lo + size])
            tasks.append(Chunk(chunk_id(setting, chunk, overturn_rule), setting, chunk, overturn_rule))
    return tasks


# --- running one chunk (in a worker, or here) -------------------------------------------

def run_chunk(task: Chunk, threads: int | None = 1) -> list[dict]:
    """The rows of one chunk. threads: the analytic kernel's threads, or a contact
    engine's runs side by side (1 in a Dask worker, which is one core; None: all cores,
    for the serial path)."""
    if runs_as_batch(task.setting.engine):
        return _run_batch(task, threads)
    return _run_contact(task, threads)


def _run_batch(task: Chunk, threads) -> list[dict]:
    settings = task.setting.settings()
    if task.overturn_rule is not None:
        settings = replace(settings, overturn=task.overturn_rule)
    cases = task.cases
    start = time.perf_counter()
    out = fast.simulate_batch([c.system for c in cases], [motion_of(c) for c in cases],
                              duration=np.array([c.duration for c in cases]),
                              theta0=np.array([c.theta0 for c in cases]), settings=settings,
                              workers=threads)
    per_case = (time.perf_counter() - start) / len(cases)
    return [{**case_inputs(case), "engine": task.setting.engine, "setting": task.setting.label,
             **row_of_batch(case, r), "runtime_s": per_case} for case, r in zip(cases, out)]


def _run_contact(task: Chunk, threads: int | None) -> list[dict]:
    """A contact engine's chunk: its batch path (MuJoCo's: one scene per system, `threads`
    runs side by side) or one run after another; each row what the run alone gives.
    Impacts are counted, not mapped to effective β: no column reads it."""
    engine = get_engine(task.setting.engine)
    start = time.perf_counter()
    results = engine.simulate_many([(c.system, motion_of(c), c.duration, c.theta0) for c in task.cases],
                                   settings=task.setting.settings(), overturn_rule=task.overturn_rule,
                                   effective_beta=False, budget_s=limits.RUN_BUDGET_S,
                                   threads=available_cores() if threads is None else threads)
    # runs overlap in threads, so a run's own wall time says little: each row gets the
    # chunk's time shared equally, as an analytic chunk's rows do
    share = (time.perf_counter() - start) / max(len(task.cases), 1)
    return [{**case_inputs(case), "engine": task.setting.engine, "setting": task.setting.label,
             **(row_of_failure(tr) if isinstance(tr, Exception) else row_of_trajectory(tr)), "runtime_s": share}
            for case, tr in zip(task.cases, results)]


# --- progress ---------------------------------------------------------------------------

#: what a batch engine's simulated second costs against a contact engine's, for the ETA
#: alone: the compiled analytic kernel makes ~1,000 runs of 40 s per second on 2 cores, a
#: contact engine 1–10 simulated seconds per wall second (docs/campaigns.md, Throughput)
BATCH_COST = 1e-4


def chunk_weight(task: Chunk) -> int:
    """A chunk's share of a progress bar's count: its number of runs."""
    return len(task.cases)


def expected_cost(task: Chunk) -> float:
    """A task's expected cost, in contact-engine simulated seconds: what the progress
    bar's ETA is measured in (the run count alone made a campaign's analytic third, done
    in seconds, promise the contact runs in seconds too)."""
    simulated = sum(c.duration for c in task.cases)
    return simulated * (BATCH_COST if runs_as_batch(task.setting.engine) else 1.0)


def run_cases(cases, engines, *, client=None, workers: int = 0, executor: "Executor | None" = None,
              analytic_chunk: int = ANALYTIC_CHUNK, contact_chunk: int = CONTACT_CHUNK, progress=None,
              overturn_rule: str | None = None, threads: int | None = None, batch_here: bool = False):
    """Rows for in-memory `cases` (core.cases.Case: system, motion, duration, theta0,
    optional inputs) under `engines`: labels ("ENGINE" or "ENGINE:PRESET"), (label,
    {setting: value}) pairs, or EngineChoices. Nothing is written. Returns a pyarrow.Table
    sorted by case, engine, setting.

    overturn_rule: model.md's rule for every engine (None: past α). threads: the serial
    path's threads (None: every core). executor: where they run (an Executor the caller
    keeps; else client or workers, see client_for). batch_here: with a cluster or worker
    processes, the analytic chunks (engines.runs_here) still run in this process (where
    the kernel is loaded; they take milliseconds) while they run the contact engines'.
    progress: an object with update(n, work) (io.progress.Progress), or None."""
    choices = []
    for e in engines:
        choice = e if isinstance(e, EngineChoice) else choose(*((e, {}) if isinstance(e, str) else e), strict=True)
        choice.settings()  # an unknown engine, preset or setting fails here
        choices.append(choice)
    tasks = make_tasks(list(cases), choices, analytic_chunk=analytic_chunk, contact_chunk=contact_chunk,
                       overturn_rule=overturn_rule)
    rows = []
    here = (lambda task: runs_here(task.setting.engine)) if batch_here else None
    with (Executor.on(client, workers) if executor is None else borrowed(executor)) as where:
        execute(tasks, executor=where, threads=threads, on_done=lambda t, r: rows.extend(r), progress=progress,
                here=here, run=run_chunk, weight=chunk_weight, cost=expected_cost)
    return sort_table(rows_to_table(rows))


def ready_kernel() -> None:
    """Make the compiled analytic kernel ready in this process before an executor's worker
    processes start. A worker loads it from its cache in milliseconds, but on first use (a fresh
    install, changed sources) it is built, 1–2 minutes: built inside a worker, the build
    counts against the task's budget, a budget shorter than the build kills the worker
    mid-build, and the next worker starts it again (a fresh install's `isorock stress
    --quick` timed out on every analytic case). One tiny run here builds it once, said on
    stderr; with the cache in place it costs milliseconds."""
    try:
        engine = get_engine("analytic")
    except ImportError:  # no compiled kernel here (numba missing): nothing to ready
        return
    system = paper_system(fixed_base=True)
    engine.simulate(system, None, duration=0.05, theta0=0.1 * system.alpha)


def worker_pool(processes: int) -> Executor:
    """An executor of `processes` (≥ 1) worker processes that can be killed, with the compiled
    analytic kernel built here first (ready_kernel), not inside a task's budget in each
    worker: validate's histories, atlas, stress and calibrate run on it."""
    return Pool(processes, prepare=ready_kernel)
