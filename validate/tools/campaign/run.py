"""The Python API: run a campaign file into a folder, or a list of cases in memory.

    run_campaign(spec, out=None, client=None, workers=0) -> CampaignResult
    run_cases(cases, engines, client=None, workers=0) -> pyarrow.Table   (core.executor's)

A campaign is cases (core.cases) run by the one executor (core.executor) into summary
rows (core.summary), stored as parts (campaign.parts) and drawn as products.
"""
from __future__ import annotations

import json
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from ....analytic.errors import InputError, import_extra
from ...core.chunks import chunk_weight, expected_cost, make_tasks, run_cases, run_chunk
from ...core.estimate import estimate_line
from ...core.executor import client_for, close_client, execute
from ...core.summary import rows_to_table, sort_table
from ...io.output import write_atomic, write_text
from ...io.progress import bar_of, logged
from . import products as products_module  # `products` is run_campaign's flag
from .parts import part_problem, read_parts, write_part
from .records import load_suite
from .spec import CampaignSpec, check_limits, load_spec

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

    def to_dataframe(self):
        """The results table as a pandas DataFrame (one row per case, engine and setting;
        columns as docs/campaigns.md lists them). Needs pandas (`isorock[notebook]`)."""
        import_extra("pandas", "notebook", "CampaignResult.to_dataframe")
        return self.table.to_pandas()


def run_campaign(spec, out=None, *, client=None, workers: int = 0, scheduler: str | None = None,
                 progress=True, products: bool = True) -> CampaignResult:
    """Run a campaign (a CampaignSpec or the path of its TOML file).

    out: the folder for parts, the table and products (None: nothing is written and
    nothing is resumed). client / scheduler / workers: where to run (see core.executor.client_for).
    progress: as every tool takes it, a factory (total, work=…) → bar (io.progress.bar_of),
    with the estimate before the first chunk and a line while the figures are drawn;
    True (the default): io.progress.logged, a bar that also writes a line every 10 s to a
    log; False or None: nothing shown."""
    if progress is True:
        progress = logged
    progress = progress or None
    if not isinstance(spec, CampaignSpec):
        spec = load_spec(spec)
    records = None
    if spec.motions["type"] == "records":
        records = load_suite(spec.motions)
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
    live, close = client_for(client, workers, scheduler) if todo else (None, False)
    bar = None
    try:
        if out is not None:
            try:
                parts_dir.mkdir(parents=True, exist_ok=True)
            except OSError as e:  # a read-only or full file system: one line, not a traceback
                raise InputError(f"--out = {str(out)!r}: cannot be written ({e.strerror or e})") from None
            write_text(out / MARKER, json.dumps({"tool": "isorock sweep", "campaign": spec.name,
                                                 "fingerprint": spec.fingerprint()}) + "\n")
        if progress and todo:  # a campaign lasts hours: its cost is said before its first chunk,
            # once every input is checked (a refusal is one line, not a line after an estimate)
            simulated: dict[str, float] = {}
            for t in todo:
                simulated[t.setting.engine] = simulated.get(t.setting.engine, 0.0) + sum(c.duration for c in t.cases)
            line = estimate_line(simulated, workers=max(1, workers), command="sweep")
            if line:
                print(line, file=sys.stderr, flush=True)
        bar = bar_of(progress if todo else None, sum(len(t.cases) for t in todo), work=sum(map(expected_cost, todo)))
        ran = execute(todo, run=run_chunk, client=live, threads=None, on_done=on_done, progress=bar, weight=chunk_weight,
                      cost=expected_cost)
    finally:
        if bar is not None:
            bar.close()
        if close:
            close_client(live, stopping=sys.exc_info()[0] is not None)
    if parts_dir is None:
        return CampaignResult(sort_table(rows_to_table(memory)), None, len(tasks), ran)
    # only this campaign's parts: a folder may hold parts of an earlier version of the file
    table = read_parts([parts_dir / f"{t.id}.parquet" for t in tasks])
    import pyarrow.parquet as pq  # lazy: pyarrow, once the parts are read
    write_atomic(out / RESULTS, lambda tmp: pq.write_table(table, tmp))
    if spec.source and Path(spec.source).is_file():
        write_text(out / "campaign.toml", Path(spec.source).read_text(encoding="utf-8"))
    made = []
    if products:
        # drawing takes its own while after the bar reached 100%: a line of its own, so that
        # a finished bar and a silent terminal do not read as a hang
        if progress:
            start = time.perf_counter()
            print(f"isorock sweep: drawing the figures and summary of {table.num_rows} rows…", file=sys.stderr,
                  flush=True)
        try:
            made = products_module.write_products(table, out, spec)
            if progress:
                print(f"isorock sweep: drew {len(made)} products in {time.perf_counter() - start:.0f} s",
                      file=sys.stderr, flush=True)
        except OSError as e:  # a full disk while drawing: the table is whole, the figures are not
            raise InputError(f"--out = {str(out)!r}: the figures and summary could not be written "
                             f"({e.strerror or e}); {RESULTS} is complete: rerun with room to write them") from None
    return CampaignResult(table, out, len(tasks), ran, made)
