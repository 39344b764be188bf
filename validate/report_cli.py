"""`isorock validate`: the validation report (validate/report.py) from the command line.

Exit code 0 when every check passes, 1 when some check fails (the last line says
which), 2 for bad input (nothing is written).
"""
from __future__ import annotations

import argparse
import sys

from isorock.analytic.errors import InputError
from isorock.validate.engines import ENGINE_NAMES

DEFAULT_OUT = "isorock-report"
#: ensemble bounds: steps each run every engine on every motion; a factor of 100 turns
#: the paper's 0.83 g Kobe record into 83 g, far past overturning
MAX_SCALE_STEPS = 200
MAX_SCALE = 100.0


def add_parser(subparsers) -> argparse.ArgumentParser:
    from isorock.validate.report import DEFAULT_MOTIONS, RECORD_WINDOW
    p = subparsers.add_parser(
        "validate", help="the validation report: all engines side by side with the analytic model",
        description="Run the paper's block (isolated T 1.5 s ξ 0.2, and on a fixed base) on each motion "
                    "with every engine, compare with the analytic model, check against the tolerance table "
                    "and write DIR/report.md, DIR/report.html, the figures and DIR/metrics.json.")
    p.add_argument("--motion", action="append", metavar="SPEC",
                   help="a record file or a pulse 'sine:amp=A,freq=F,cycles=N', 'cosine:…', "
                        "'ricker:amp=A,freq=F' (A in g, F in Hz); repeat for several "
                        f"(default: {' and '.join(DEFAULT_MOTIONS)})")
    p.add_argument("--format", choices=("at2", "jma", "csv"),
                   help="record format; guessed from the file when omitted")
    from isorock.validate.cli import add_units_option, number
    add_units_option(p)
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR",
                   help="report folder: a new or empty folder, or one an earlier isorock run wrote (replaced "
                        "whole when the report is done); any other folder is refused (default: %(default)s)")
    p.add_argument("--engines", nargs="+", default=list(ENGINE_NAMES), metavar="ENGINE",
                   help=f"engines to run, space- or comma-separated; must include analytic "
                        f"(default: {' '.join(ENGINE_NAMES)})")
    p.add_argument("--quick", action="store_true",
                   help="fewer ensemble steps (6), shorter tails after pulses, Figure 4 at μ = 1 only")
    p.add_argument("--duration", type=number,
                   help=f"end time of every run, s (default: pulse end + 4 s, 2 s with --quick; "
                        f"records: the first {RECORD_WINDOW:g} s)")
    p.add_argument("--scales", metavar="FIRST,LAST,STEPS",
                   help="ensemble scale factors of the PGA (default: 0.25,1.5,21; 6 steps with --quick)")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=run)
    return p


def _scales(text):
    if text is None:
        return None
    parts = text.split(",")
    try:
        if len(parts) != 3:
            raise ValueError
        first, last, steps = float(parts[0]), float(parts[1]), float(parts[2])
    except ValueError:
        raise InputError(f"scales = {text!r}: must be FIRST,LAST,STEPS, e.g. 0.25,1.5,21") from None
    if steps != int(steps) or not 1 <= steps <= MAX_SCALE_STEPS:
        raise InputError(f"scales = {text!r}: STEPS must be a whole number from 1 to {MAX_SCALE_STEPS} "
                         "(MAX_SCALE_STEPS: each step runs every engine on every motion)")
    for name, x in (("FIRST", first), ("LAST", last)):
        if not 0 < x <= MAX_SCALE:
            raise InputError(f"scales = {text!r}: {name} = {x:g} must be a positive factor of the PGA, "
                             f"at most {MAX_SCALE:g} (MAX_SCALE)")
    return first, last, int(steps)


def run(args) -> int:
    from isorock.validate.output import check_folder
    from isorock.validate.report import DEFAULT_MOTIONS, ReportConfig, build, verdict, write_report
    check_folder(args.out)  # a folder we may not write is refused before the runs, not after
    engines = tuple(e for item in args.engines for e in item.split(",") if e)
    config = ReportConfig(motions=tuple(args.motion or DEFAULT_MOTIONS), engines=engines, quick=args.quick,
                          duration=args.duration, scales=_scales(args.scales), format=args.format,
                          units=args.units)
    log = (lambda line: None) if args.quiet else (lambda line: print(line, file=sys.stderr, flush=True))
    results = build(config, log=log)
    for motion in {id(sc.motion): sc.motion for sc in results.scenarios}.values():
        log(f"motion {motion.name}: PGA {motion.pga_g:.4g} g (read in {motion.units})")
    write_report(results, args.out)
    log(f"wrote {args.out}/report.md, report.html, metrics.json ({results.wall_s:.0f} s)")
    print(verdict(results))
    return 1 if results.failed else 0
