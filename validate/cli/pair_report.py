"""`isorock validate` under a record pair (--pair SUITE:ID, or --motion with --motion-transverse;
issue 36), the command: tools/pair_report.py reads the options, runs and judges the engines and
writes DIR/report.md, DIR/pair.png and DIR/metrics.json (whole or absent); this prints where, and
the verdict last on stdout; exit 1 when a check failed. A --pair is read by the command line's
reader (readers.read_pair: the campaign's records).
"""
from __future__ import annotations

from ..tools.pair_report import FIGURE, build, write
from .readers import read_pair


def run(args, **inputs) -> int:
    """The command: the report written (report.md, pair.png, metrics.json, whole or absent), the
    verdict last; `inputs` as tools.pair_report.pair_inputs reads them."""
    metrics, _ = build(args, **inputs, read_pair=read_pair)
    write(metrics, args.out)
    print(f"wrote {args.out}/report.md, {FIGURE}, metrics.json")
    print(metrics["verdict"])
    return 1 if any(c["status"] == "fail" for c in metrics["checks"]) else 0
