"""The `isorock bench` command: options, then the work-precision table written as one folder."""
from __future__ import annotations

import csv
import io
import time
from pathlib import Path

from ..io.inputs import engine_labels
from ..core.engines import ALL_ENGINES
from ..io.output import check_folder, to_json, write_folder_atomic
from ..tools import bench as tool
from ..tools.bench import COLUMNS, markdown, plot, run_bench


def _engine_names():
    return ALL_ENGINES


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="work-precision benchmarks of every engine",
                       description=tool.__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="fewer settings, one repeat (a few minutes)")
    p.add_argument("--out", default="isorock-bench", metavar="DIR",
                   help="folder for bench.csv, bench.md, bench.png, bench.json: new, empty or an earlier "
                        "isorock output (default: %(default)s)")
    p.add_argument("--engines", nargs="+", metavar="ENGINE[:PRESET]",
                   help="engines to bench, space- or comma-separated: ENGINE runs its ladder of settings, "
                        "ENGINE:PRESET that preset alone, as rows of its own (e.g. mujoco:default mujoco:fast "
                        "drake:sap; default: the engines fast enough for grids; others, e.g. drake, by name; "
                        "registered: %s)" % ", ".join(_engine_names()))
    p.set_defaults(func=cmd_bench)


def cmd_bench(a) -> int:
    # an unknown engine or preset is an InputError before anything runs
    engines = engine_labels(a.engines) if a.engines else None
    check_folder(a.out)  # so is a folder we may not write
    start = time.perf_counter()
    rows, extra = run_bench(quick=a.quick, engines=engines)

    def fill(tmp: Path):
        (tmp / "bench.md").write_text(markdown(rows, extra))
        (tmp / "bench.json").write_text(to_json({"rows": rows, **extra}) + "\n")
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=COLUMNS + ("wall_per_sim", "parted", "overturn_agree", "stopped"),
                           extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
        (tmp / "bench.csv").write_text(buf.getvalue())
        plot(rows, tmp / "bench.png")
    write_folder_atomic(a.out, fill)
    # the tables on standard output (as every command's result); each row's progress was on stderr
    print(markdown(rows, extra))
    print(f"bench: {len(rows)} runs in {time.perf_counter() - start:.0f} s; table in {a.out}/bench.md")
    return 0
