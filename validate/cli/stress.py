"""The `isorock stress` command: options, then the stress grid's tables written as one folder."""
from __future__ import annotations

import csv
import io
import time
from pathlib import Path

from ...analytic.errors import InputError
from ...analytic.limits import check_workers
from ..core.engines import get_engine
from ..io.output import check_folder, to_json, write_folder_atomic
from ..io.progress import Progress
from ..tools import stress as tool
from ..tools.stress import (COLUMNS, DRAWN_FULL, DRAWN_QUICK, failed, failures, markdown, run_stress,
                            stress_verdict)


def add_parser(sub) -> None:
    p = sub.add_parser("stress", help="the stability stress grid (exits non-zero on any failure)",
                       description=tool.__doc__.split("\n\n")[1])
    p.add_argument("--quick", action="store_true", help="the quick subset (under 2 minutes)")
    p.add_argument("--drawn", type=int, metavar="N",
                   help=f"property-based cases to draw (default {DRAWN_FULL}, {DRAWN_QUICK} with --quick)")
    p.add_argument("--workers", type=int, default=2, help="runs at a time (default: %(default)s)")
    p.add_argument("--out", default="isorock-stress", metavar="DIR",
                   help="folder for stress.md, stress.csv, stress.json: new, empty or an earlier isorock "
                        "output (default: %(default)s)")
    p.add_argument("--engines", nargs="+", metavar="ENGINE",
                   help="engines to stress (default: every engine fast enough for grids; Drake by name)")
    p.add_argument("--time-limit", type=float, help="wall-time limit per case, s (default 30 quick, 120 full)")
    p.set_defaults(func=cmd_stress)


def cmd_stress(a) -> int:
    for e in a.engines or []:
        get_engine(e)  # an unknown name is an InputError before anything runs
    if a.time_limit is not None and not a.time_limit > 0:
        raise InputError(f"time-limit = {a.time_limit!r}: must be a positive number of seconds")
    check_folder(a.out)  # a folder we may not write is refused before the grid runs
    start = time.perf_counter()
    if a.drawn is not None and not 0 <= a.drawn <= 100_000:
        raise InputError(f"drawn = {a.drawn!r}: must be a number of cases from 0 to 100000")
    check_workers("workers", a.workers)
    results = run_stress(quick=a.quick, engines=a.engines, time_limit=a.time_limit, drawn=a.drawn,
                         workers=a.workers, progress=lambda total: Progress(total, "stress"))

    def fill(tmp: Path):
        (tmp / "stress.md").write_text(markdown(results))
        (tmp / "stress.json").write_text(to_json(results) + "\n")
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(results)
        (tmp / "stress.csv").write_text(buf.getvalue())
    write_folder_atomic(a.out, fill)
    fails = failures(results)
    for r in fails:
        print(f"  {r['verdict'] if r['verdict'] != 'pass' else r['cross']} {r['engine']} {r['case']}: "
              f"{r['status']} {r.get('error', '')}")
    print(f"report in {a.out}/stress.md ({time.perf_counter() - start:.0f} s)")
    print(stress_verdict(results))
    return 1 if failed(results) else 0
