"""`isorock sweep SPEC.toml [--out DIR] [--scheduler ADDRESS] [--workers N]`: run a
campaign file (docs/campaigns.md) into a folder of Parquet parts, a results table,
figures and a Markdown summary; rerun to resume."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ...analytic.limits import available_cores, check_workers
from ..io.output import Terminated, signal_received
from ..tools.campaign.run import run_campaign
from ..tools.campaign.spec import load_spec


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "sweep", help="run a campaign (spectra, fragility, agreement maps) serially or on Dask",
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", help="campaign file (TOML), see docs/campaigns.md")
    p.add_argument("--out", help="output folder (default: ./sweep-<file stem>); "
                                 "a rerun into it resumes and skips finished chunks")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--workers", type=int, default=None,
                       help="worker processes of a local Dask cluster (default: this machine's cores; "
                            "0: run serially in this process)")
    p.add_argument("--no-products", action="store_true", help="write the table only (no figures, no summary)")
    p.set_defaults(func=run)


def run(a) -> int:
    if a.workers is not None:
        check_workers("--workers", a.workers, serial=True)
    spec = load_spec(a.spec)
    out = Path(a.out) if a.out else Path(f"sweep-{Path(a.spec).stem}")
    workers = available_cores() if a.workers is None else a.workers
    try:
        result = run_campaign(spec, out, workers=workers, scheduler=a.scheduler, products=not a.no_products)
    except BaseException as e:
        if not (signal_received() or isinstance(e, (Terminated, KeyboardInterrupt))):
            raise
        # what a stopped sweep leaves is its finished chunks, on purpose: say so (the signal's
        # exception may arrive re-wrapped, by an import for one)
        kept = len(list((out / "parts").glob("*.parquet"))) if (out / "parts").is_dir() else 0
        e.outcome = (f"{kept} finished chunks kept in {out / 'parts'}; rerun the same command to resume"
                     if kept else "no output written")
        raise
    print(f"{result.out}: {result.table.num_rows} rows; {result.tasks_run} of {result.tasks_total} chunks "
          f"run now, {result.tasks_skipped} already done", file=sys.stderr)
    return 0
