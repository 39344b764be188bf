"""The `isorock calibrate` command: options, the fit, and the preset file written only when it holds."""
from __future__ import annotations

import sys

from ...analytic.errors import InputError
from ...analytic.limits import check_workers
from ...analytic.system import paper_system
from ..core.estimate import announce_cost
from .options import add_engine_options, add_system_options, whole_number
from ..io.inputs import ENGINE_OPTIONS, SYSTEM_KEYS, engine_settings_from_args, system_from_options
from ..core.engines import get_engine
from ..core.executor import default_workers
from ..io.output import Outputs, to_json
from ..io.progress import Progress
from ..tools import calibrate as tool
from ..tools.calibrate import (DEFAULT_TILTS, TILT_RANGE, TUNING, preset_worthy, report_lines,
                               result_json, settings_toml)


def _options(a, keys) -> list[str]:
    """The options among `keys` that were given, as they would be typed."""
    words = []
    for k in keys:
        v = getattr(a, k, None)
        if v is True:
            words.append(f"--{k.replace('_', '-')}")
        elif v not in (None, False):
            v = ",".join(f"{x:g}" for x in v) if isinstance(v, tuple) else (f"{v:g}" if isinstance(v, float) else v)
            words.append(f"--{k.replace('_', '-')} {v}")
    return words


def _toml_value(value) -> str:
    """A --set value as it is typed again: a word bare, a number or a list as TOML writes it."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return "[" + ",".join(f"{x:g}" for x in value) + "]"
    return f"{value:g}"


def _command(a) -> str:
    """The command line that gives this result again (the options that were given)."""
    words = ["isorock calibrate", f"--engine {a.engine}", *_options(a, SYSTEM_KEYS), *_options(a, ENGINE_OPTIONS),
             *(f"--set {'' if table == '*' else table + '.'}{key}={_toml_value(value)}"
               for table, key, value in a.set_settings or ())]
    if a.tilts != DEFAULT_TILTS:
        words.append(f"--tilts {a.tilts}")
    words.append(f"--max-evals {a.max_evals}")
    return " ".join(words)


#: what the exit code says (help, docs/mujoco.md): "keep the current settings" is a result
EXIT_CODES = ("exit codes: 0, the calibration ran and its verdict is said (better settings, written with --out; or "
              "keep the current settings: the fit did not hold on the held-out runs beyond the noise); 1, --out was "
              "given and no preset written (the file asked for is not there: a script that goes on to use it must "
              "not); 2, bad input, one line")


def add_parser(sub) -> None:
    p = sub.add_parser("calibrate", help="fit a contact engine's contact parameters to the closed-form β",
                       description=tool.__doc__.split("\n\n")[0], epilog=EXIT_CODES)
    p.add_argument("--engine", required=True, help="mujoco, bullet or drake")
    add_system_options(p, required=False)
    add_engine_options(p)
    p.add_argument("--max-evals", type=whole_number, default=48,
                   help="evaluations of the fitted runs the search may spend (default: %(default)s)")
    p.add_argument("--tilts", type=whole_number, default=DEFAULT_TILTS,
                   help=f"fitted tilts per base, evenly over {TILT_RANGE[0]:g}–{TILT_RANGE[1]:g}·α; the held-out "
                        "runs are the tilts halfway between them (default: %(default)s)")
    p.add_argument("--workers", type=whole_number,
                   help="worker processes for the runs, each run stopped at its time limit (default: 2, or the "
                        "cores there are)")
    p.add_argument("--out", metavar="FILE.toml",
                   help="write the calibrated settings as a preset file (`isorock validate --config FILE`), "
                        "when they hold on the held-out runs")
    p.add_argument("--json", metavar="FILE", help="write the whole result (every run's β errors) as JSON")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    p.set_defaults(func=cmd_calibrate)


def cmd_calibrate(a) -> int:
    engine = get_engine(a.engine)
    if TUNING.of(engine.spec) is None:
        raise InputError(f"engine = {a.engine!r}: has no contact parameters to calibrate")
    if not 5 <= a.max_evals <= 2000:
        raise InputError(f"max-evals = {a.max_evals!r}: must be a whole number from 5 to 2000")
    if not 2 <= a.tilts <= 101:
        raise InputError(f"tilts = {a.tilts!r}: must be a whole number from 2 to 101")
    workers = default_workers() if a.workers is None else check_workers("workers", a.workers)
    system = system_from_options(a) or paper_system(fixed_base=True)
    settings = engine_settings_from_args(engine, a)
    # the cost before the runs (issue 34): every search point runs the fitted cases, and the
    # result runs the held-out ones twice (before and after), as tool.calibrate does; on one
    # worker, a bound: the search's points run one after another, each waiting for its slowest
    # run (the paper's block, MuJoCo: 57 s said, 52 s taken on 2 workers at load 2–3)
    fitted, held = tool.cases(system, a.tilts)
    announce_cost("calibrate", {a.engine: a.max_evals * sum(c.duration for c in fitted)
                                + 2 * sum(c.duration for c in held)}, quiet=a.quiet)
    with Outputs() as outputs:  # bad paths are refused before minutes of simulation
        # `is not None`: an empty path is refused as bad input, not read as "no output" (it ran for minutes)
        preset = outputs.file("out", a.out, exclusive=True) if a.out is not None else None
        report = outputs.file("json", a.json) if a.json is not None else None
        bars = []  # made at the first run, when the search's budget of runs is known

        def progress(total):
            bars.append(Progress(total, "calibrate", enabled=None if not a.quiet else False))
            return bars[-1]
        r = tool.calibrate(a.engine, system, settings=settings, n_tilts=a.tilts, max_evals=a.max_evals,
                           workers=workers, progress=progress)
        for bar in bars:
            bar.update(bar.total - bar.done)  # Nelder–Mead may converge before the budget is spent
            bar.close()
        lines = report_lines(r, system, _command(a))
        ok = preset_worthy(r)
        if preset is not None:
            if ok:
                preset.write_text(settings_toml(a.engine, r["settings_after"], lines))
                lines.append(f"wrote {a.out} (use it with: isorock validate --config {a.out} --engines analytic "
                             f"{' '.join([a.engine, *_options(a, SYSTEM_KEYS)])})")
            else:
                lines.append(f"{a.out} not written: the calibrated settings do not meet the preset's criterion above")
        if report is not None:
            report.write_text(to_json(result_json(r)) + "\n")
        # the JSON on standard output stays parseable: the text goes to stderr then
        print("\n".join(lines), file=sys.stderr if a.json == "-" else sys.stdout)
        outputs.commit()
    # keeping the current settings is a verdict, not a failure; only a preset asked for and
    # not written is (EXIT_CODES)
    return 0 if ok or a.out is None else 1
