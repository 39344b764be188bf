"""`isorock validate`: the validation report (report_run.py runs it, report_render.py
writes it) from the command line.

Exit code 0 when every check passes, 1 when some check fails (the last line says
which), 2 for bad input (nothing is written).
"""
from __future__ import annotations

import argparse
import sys

from ...analytic.errors import InputError
from ...analytic.limits import check_workers
from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD
from ..io.config_file import check_damping_ratio, read_config
from . import pair_report
from .options import (add_engine_options, add_isolator_options, add_key_option, add_statue_options,
                      add_system_options, add_transverse_options, add_units_option, check_tables_run, engine_tables,
                      number, statue_body, system_from_args, system_from_options, system_options, transverse_asked)
from .run import engine_labels, shaken_body
from ..core.engines import ENGINE_NAMES, resolve
from ..core.scenarios import RECORD_WINDOW, REPORT_MOTIONS as DEFAULT_MOTIONS
from ..io import keys
from ..io.options import DEFAULT_OUT, ValidateOptions
from ..io.output import check_folder
from ..io.progress import Progress
from ..tools.report_run import ReportConfig, build

#: ensemble bounds: steps each run every engine on every motion; a factor of 100 turns
#: the paper's 0.83 g Kobe record into 83 g, far past overturning
MAX_SCALE_STEPS = 200
MAX_SCALE = 100.0


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


def _read_config(path) -> dict:
    return read_config(path)


def engine_overrides(args, config: dict, engines) -> dict:
    """table → settings of the engines: the --config file's [settings.ENGINE] tables, and over them
    table by table the command line's (--set and the engine options)."""
    overrides = {str(k): dict(v) for k, v in config.get("settings", {}).items()}
    given = engine_tables(args)
    check_tables_run(given, engines)
    for table, values in given.items():
        if values:  # "*": a setting on the command line applies to every engine that has it
            overrides[table] = {**overrides.get(table, {}), **values}
    return overrides


def _pair_report(args) -> int:
    """validate under a record pair (pair_report.py)."""
    check_folder(args.out)  # a folder we may not write is refused before the runs
    return pair_report.run(args, **pair_inputs(args))


def pair_inputs(args) -> dict:
    """The options of validate under a record pair read as report_config reads them (the engines
    without the analytic reference: the exact model is planar, beside each engine, unjudged)."""
    config = _read_config(args.config) if args.config else {}
    engines = tuple(engine_labels(args.engines)) if args.engines else pair_report.DEFAULT_PAIR_ENGINES
    overrides = engine_overrides(args, config, engines)
    system = shaken = None
    given = system_options(args, config.get("system"), config.get("statue"))
    if given is not None:
        # a statue's mesh read once: the System's two edges, and the body the 3-D measures read
        options, names = given
        statue = statue_body(options, names)
        system = system_from_args(options, statue_names=names, statue=statue)
        check_damping_ratio(system)
        shaken = shaken_body(options, system, statue, names)
    duration = args.duration if args.duration is not None else config.get("duration")
    return dict(config=config, engines=engines, overrides=overrides, system=system, shaken=shaken, duration=duration)


def report_config(args):
    """The validate options `args` (the parser's namespace) and the --config file they name,
    checked and merged into the report's ReportConfig, before any run."""
    config = _read_config(args.config) if args.config else {}
    engines = tuple(engine_labels(args.engines or config.get("engines") or ENGINE_NAMES))
    overrides = engine_overrides(args, config, engines)
    if args.workers is not None:
        check_workers("workers", args.workers)
    report = ReportConfig(motions=tuple(args.motion or config.get("motions") or DEFAULT_MOTIONS), engines=engines,
                          quick=args.quick or bool(config.get("quick")),
                          duration=args.duration if args.duration is not None else config.get("duration"),
                          scales=_scales(args.scales), format=args.format or config.get("format"),
                          units=args.units or config.get("units"), system=system_from_options(args, config.get("system"), config.get("statue")),
                          overrides=overrides, workers=args.workers, overturn_rule=args.overturn,
                          # a target on the command line wins over the file's, whichever it names
                          **({"pga": args.pga, "pgv": args.pgv} if args.pga is not None or args.pgv is not None
                             else {"pga": config.get("pga"), "pgv": config.get("pgv")}))
    check_damping_ratio(report.system)
    for name in report.engines:  # an unknown setting or preset is bad input before anything runs
        try:
            resolve(name, report.overrides_for(name))
        except ImportError:
            pass  # reported as a skipped engine
    return report


def run(args) -> int:
    """`isorock validate`: the parser's namespace read into the typed ValidateOptions that
    isorock.report builds from keywords, then the report."""
    from ..tools.report_render import verdict, write_report  # lazy: matplotlib, once the runs are done
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
