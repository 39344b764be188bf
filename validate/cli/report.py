"""`isorock validate`: the validation report (report_run.py runs it, report_render.py
writes it) from the command line.

Exit code 0 when every check passes, 1 when some check fails (the last line says
which), 2 for bad input (nothing is written).
"""
from __future__ import annotations

import argparse
import sys

from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD
from . import pair_report
from .options import (add_engine_options, add_isolator_options, add_key_option, add_statue_options,
                      add_system_options, add_transverse_options, add_units_option, number)
from ..io.inputs import transverse_asked
from ..core.engines import ENGINE_NAMES
from ..core.scenarios import RECORD_WINDOW, REPORT_MOTIONS as DEFAULT_MOTIONS
from ..io import keys
from ..io.options import DEFAULT_OUT, ValidateOptions
from ..io.output import check_folder
from ..io.progress import Progress
# the options read into what the report runs, below the command line, as isorock.report reads them
from ..tools.pair_report import pair_inputs
from ..tools.report_config import report_config
from ..tools.report_render import verdict, write_report
from ..tools.report_run import build


def add_parser(subparsers) -> argparse.ArgumentParser:
    p = subparsers.add_parser(
        "validate", help="the validation report: all engines side by side with the analytic model",
        description=f"Run a block on its base (the paper's by default: isolated T {PAPER_PERIOD:g} s "
                    f"ξ {PAPER_DAMPING_RATIO:g}, and on a fixed base; "
                    "or yours, given by the system options or --config) under each motion with every engine, "
                    "compare with the analytic model, check against the tolerance table and write DIR/report.md, "
                    "DIR/report.html, the figures and DIR/metrics.json. The last line on stdout is the verdict.")
    p.add_argument("--config", metavar="FILE.toml",
                   help="a TOML file with [system] (the system options, underscored), engines = [...], "
                        "motions = [...], pga or pgv, and [settings.ENGINE] tables of engine settings; options "
                        "given on the command line win (a commented example: examples/statue.toml)")
    p.add_argument("--motion", action="append", metavar="SPEC",
                   help="a record file or a pulse 'sine:amp=A,freq=F,cycles=N', 'cosine:…', "
                        "'ricker:amp=A,freq=F' (A in g, F in Hz); repeat for several "
                        f"(default: {' and '.join(DEFAULT_MOTIONS)})")
    # the motion keys a --config file gives too (io/keys.MOTION), said of every motion
    add_key_option(p, keys.MOTION["format"], help="record format; guessed from the file when omitted")
    add_units_option(p)
    add_key_option(p, keys.MOTION["pga"], help="scale every motion to this peak ground acceleration, g (the "
                   "ensembles scale from there)")
    add_key_option(p, keys.MOTION["pgv"], help="scale every motion to this peak ground velocity, m/s (instead of "
                   "--pga)")
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR",
                   help="report folder: a new or empty folder, or one an earlier isorock run wrote (replaced "
                        "whole when the report is done); any other folder is refused (default: %(default)s)")
    p.add_argument("--engines", nargs="+", metavar="ENGINE",
                   help=f"engines to run, space- or comma-separated, each ENGINE or ENGINE:PRESET (a preset "
                        f"is its own column); must include analytic (default: {' '.join(ENGINE_NAMES)})")
    p.add_argument("--quick", action="store_true",
                   help="fewer ensemble steps (6), shorter tails after pulses, Figure 4 at μ = 1 only")
    p.add_argument("--duration", type=number,
                   help=f"end time of every run, s (default: pulse end + 4 s, 2 s with --quick; "
                        f"records: the first {RECORD_WINDOW:g} s)")
    p.add_argument("--scales", metavar="FIRST,LAST,STEPS",
                   help="ensemble scale factors of the motion (default: from 1.2 to 2.5 times the scale at which "
                        "the block first lifts, 21 steps, 6 with --quick)")
    p.add_argument("--workers", type=int,
                   help="processes for the contact engines (default: 2, or the cores there are; 1: one process)")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    add_system_options(p, required=False)
    add_isolator_options(p, in_file=True)  # every isolator kind, as `run` takes it (docs/isolators.md)
    add_statue_options(p)  # its mesh instead of H × B: the engines that carry it judged on it (docs/statues.md)
    add_engine_options(p)
    add_transverse_options(p)  # a record pair: each engine that runs it judged on turning it (pair_report.py)
    p.set_defaults(func=run)
    return p


def _pair_report(args) -> int:
    """validate under a record pair (tools/pair_report.py; cli/pair_report.py prints)."""
    check_folder(args.out)  # a folder we may not write is refused before the runs
    return pair_report.run(args, **pair_inputs(args))


def run(args) -> int:
    """`isorock validate`: the parser's namespace read into the typed ValidateOptions that
    isorock.report builds from keywords, then the report."""
    args = ValidateOptions.from_namespace(args)
    if transverse_asked(args):  # a record pair: its own report (pair_report.py)
        return _pair_report(args)
    check_folder(args.out)  # a folder we may not write is refused before the runs, not after
    report = report_config(args)
    bars = []  # made by the report once it knows how many runs it makes

    def progress(total):
        bars.append(Progress(total, "validate", enabled=False if args.quiet else None))
        return bars[-1]
    results = build(report, progress=progress)
    for bar in bars:
        bar.close()
    if not args.quiet:
        for motion in {id(sc.motion): sc.motion for sc in results.scenarios}.values():
            print(f"motion {motion.name}: PGA {motion.pga_g:.4g} g (read in {motion.units})", file=sys.stderr)
    write_report(results, args.out)
    print(f"wrote {args.out}/report.md, report.html, metrics.json in {results.wall_s:.0f} s")
    print(verdict(results))
    return 1 if results.failed else 0
