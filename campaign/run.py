"""The Python API: run a campaign file into a folder, or a list of cases in memory.

    run_campaign(spec, out=None, client=None, workers=0) -> CampaignResult
    run_cases(cases, engines, client=None, workers=0) -> pyarrow.Table

`isorock validate`'s ensembles can hand their cases to `run_cases` (compiled analytic
in batches, contact engines in worker processes) and read the rows back.
"""
from __future__ import annotations

import json
import sys
from dataclasses import dataclass, field
from pathlib import Path

from isorock.analytic.errors import InputError

from .execute import (Progress, close_client, execute, expected_cost, local_client, make_tasks, part_problem,
                      read_parts, rows_to_table, runs_as_batch, sort_table, write_part)
from .spec import ANALYTIC_CHUNK, CONTACT_CHUNK, CampaignSpec, EngineSetting, load_spec

#: The file that marks a folder as written by `isorock sweep`: a sweep fills a new or
#: empty folder, or one holding this marker, and refuses any other.
MARKER = ".isorock-sweep"
RESULTS = "results.parquet"
PARTS = "parts"


def check_output_folder(out: Path) -> None:
    """Refuse a folder this command did not write. (A small local check: it should move
    to the shared helper of validate/output.py once that exists.)"""
    if out.exists() and not out.is_dir():
        raise InputError(f"--out = {str(out)!r}: must be a folder (a file of that name exists)")
    if out.is_dir() and any(out.iterdir()) and not (out / MARKER).is_file():
        raise InputError(f"--out = {str(out)!r}: must be a new or empty folder, or one written by "
                         f"isorock sweep (no {MARKER} marker there); not overwriting it")


@dataclass
class CampaignResult:
    table: object  # pyarrow.Table, sorted by case, engine, setting
    out: Path | None
    tasks_total: int
    tasks_run: int
    products: list = field(default_factory=list)

    @property
    def tasks_skipped(self) -> int:
        return self.tasks_total - self.tasks_run


def _client_for(client, workers, scheduler):
    """(client, close): an explicit client; one connected to `scheduler`; a LocalCluster
    of `workers` processes; or none (serial, workers = 0)."""
    if client is not None:
        return client, False
    if scheduler:
        from dask.distributed import Client

        from .execute import check_scheduler
        check_scheduler(scheduler)
        try:
            return Client(scheduler, timeout="10s"), True
        except (OSError, TimeoutError) as e:
            raise InputError(f"--scheduler = {scheduler!r}: must be a reachable Dask scheduler ({e})") from None
    if workers and workers > 0:
        return local_client(workers), True
    return None, False


def run_campaign(spec, out=None, *, client=None, workers: int = 0, scheduler: str | None = None,
                 progress: bool = True, products: bool = True) -> CampaignResult:
    """Run a campaign (a CampaignSpec or the path of its TOML file).

    out: the folder for parts, the table and products (None: nothing is written and
    nothing is resumed). client / scheduler / workers: where to run (see _client_for)."""
    if not isinstance(spec, CampaignSpec):
        spec = load_spec(spec)
    records = None
    if spec.motions["type"] == "records":
        from .records import load_suite
        records = load_suite(spec.motions)
        from .spec import check_limits
        check_limits(spec, max((r.end_time for r in records.values()), default=0.0))
    cases = spec.cases(records)
    tasks = make_tasks(cases, spec.engines, analytic_chunk=spec.analytic_chunk,
                       contact_chunk=spec.contact_chunk)
    out = Path(out) if out is not None else None
    parts_dir = out / PARTS if out is not None else None
    memory = []
    if out is not None:
        check_output_folder(out)
        todo = []
        for t in tasks:
            path = parts_dir / f"{t.id}.parquet"
            problem = part_problem(path, t) if path.exists() else "missing"
            if problem is not None and problem != "missing":
                print(f"isorock sweep: {PARTS}/{path.name}: {problem}; running its chunk again", file=sys.stderr)
            if problem is not None:
                todo.append(t)
    else:
        todo = tasks

    def on_done(task, rows):
        if parts_dir is not None:
            write_part(parts_dir / f"{task.id}.parquet", rows)
        else:
            memory.extend(rows)

    # connect before writing anything: an unreachable scheduler leaves no folder behind
    live, close = _client_for(client, workers, scheduler) if todo else (None, False)
    try:
        if out is not None:
            from isorock.validate.output import write_text
            try:
                parts_dir.mkdir(parents=True, exist_ok=True)
            except OSError as e:  # a read-only or full file system: one line, not a traceback
                raise InputError(f"--out = {str(out)!r}: cannot be written ({e.strerror or e})") from None
            write_text(out / MARKER, json.dumps({"tool": "isorock sweep", "campaign": spec.name,
                                                 "fingerprint": spec.fingerprint()}) + "\n")
        bar = (Progress(sum(len(t.cases) for t in todo), work=sum(map(expected_cost, todo)))
               if progress and todo else None)
        ran = execute(todo, client=live, threads=None, on_done=on_done, progress=bar, cost=expected_cost)
    finally:
        if close:
            close_client(live)
    if parts_dir is None:
        return CampaignResult(sort_table(rows_to_table(memory)), None, len(tasks), ran)
    # only this campaign's parts: a folder may hold parts of an earlier version of the file
    table = read_parts([parts_dir / f"{t.id}.parquet" for t in tasks])
    import pyarrow.parquet as pq
    from isorock.validate.output import write_atomic, write_text
    write_atomic(out / RESULTS, lambda tmp: pq.write_table(table, tmp))
    if spec.source and Path(spec.source).is_file():
        write_text(out / "campaign.toml", Path(spec.source).read_text(encoding="utf-8"))
    made = []
    if products:
        from .products import write_products
        try:
            made = write_products(table, out, spec)
        except OSError as e:  # a full disk while drawing: the table is whole, the figures are not
            raise InputError(f"--out = {str(out)!r}: the figures and summary could not be written "
                             f"({e.strerror or e}); {RESULTS} is complete: rerun with room to write them") from None
    return CampaignResult(table, out, len(tasks), ran, made)


def run_cases(cases, engines, *, client=None, workers: int = 0, analytic_chunk: int = ANALYTIC_CHUNK,
              contact_chunk: int = CONTACT_CHUNK, progress=False, overturn_rule: str | None = None,
              threads: int | None = None, batch_here: bool = False):
    """Rows for in-memory `cases` (campaign.spec.Case: system, motion, duration, theta0,
    optional inputs) under `engines`: names ("ENGINE" or "ENGINE:PRESET"), (name,
    {setting: value}) pairs, or EngineSettings. Nothing is written. Returns a
    pyarrow.Table sorted by case, engine, setting.

    overturn_rule: model.md's rule for every engine (None: past α). threads: the serial
    path's threads (None: every core). batch_here: with a cluster, the analytic chunks
    still run in this process (where the kernel is loaded; they take milliseconds) while
    the cluster runs the contact engines'. progress: True for a bar on stderr, or an
    object with update(n, work) (Progress.update)."""
    from isorock.validate.engines import get_engine
    settings = []
    for e in engines:
        if isinstance(e, EngineSetting):
            setting = e
        else:
            name, overrides = (e, {}) if isinstance(e, str) else e
            base, _, preset = name.partition(":")
            setting = EngineSetting(base, tuple(sorted(overrides.items())), preset)
        get_engine(setting.engine)
        setting.settings()  # an unknown engine, preset or setting fails here
        settings.append(setting)
    tasks = make_tasks(list(cases), settings, analytic_chunk=analytic_chunk, contact_chunk=contact_chunk,
                       overturn_rule=overturn_rule)
    rows = []
    live, close = _client_for(client, workers, None)
    bar = (Progress(sum(len(t.cases) for t in tasks), work=sum(map(expected_cost, tasks)))
           if progress is True else (progress or None))
    here = (lambda task: runs_as_batch(task.setting.engine)) if batch_here else None
    try:
        execute(tasks, client=live, threads=threads, on_done=lambda t, r: rows.extend(r), progress=bar, here=here,
                cost=expected_cost)
    finally:
        if close:
            close_client(live)
    return sort_table(rows_to_table(rows))
