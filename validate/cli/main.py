"""The `isorock` command line.

    isorock beta     closed-form impact coefficients
    isorock run      one simulation with one engine (analytic, mujoco, bullet)
    isorock scene    the model file a contact engine runs (open it in its viewer)
    isorock validate the validation report (all engines side by side)
    isorock bench    work-precision benchmarks
    isorock stress   the stability stress grid
    isorock view     replay a run in MuJoCo's viewer (or as a GIF without a display)
    isorock calibrate  fit a contact engine's contact parameters to the closed-form β
    isorock presets  every engine's presets (ENGINE:PRESET), with their reasons and settings
    isorock atlas    the contact-model atlas: every preset's β and t₁ error over λ × μ × size, and its cost
    isorock sweep    campaigns: spectra, fragility curves, agreement maps (Dask)
    isorock design   which isolator keeps a statue standing at a site: P(overturn) and stroke per isolator
    isorock experiments  the engines scored against measured shake-table tests of two rocks
    isorock scorecard  every engine and preset on the same rows, written to docs/engines.md

Bad input exits with code 2 and one line on stderr, and leaves no output file.
Outputs go through validate.io.output: checked before the work, written all or none.
SIGTERM, SIGHUP or SIGINT end a command cleanly wherever they arrive: one line, nothing staged
is left, exit 128 + signal.
"""
from __future__ import annotations

import argparse
import importlib
import json
import logging
import os
import signal
import sys

from ...analytic import coefficients as co
from ...analytic.engine_protocol import DEFAULT_IMPACT_THRESHOLD
from ...analytic.errors import InputError
from ...analytic.system import PAPER_BLOCK, PAPER_TEXT
from ..core.registry import ALL_ENGINES
from ..io.output import Terminated, signal_received, signals_end_cleanly
from .options import (OneLineParser, add_budget_option, add_engine_options, add_isolator_options,
                      add_motion_options, add_statue_options, add_system_options, add_transverse_options, number)

#: Subcommands that live in their own modules (each has add_parser(subparsers)), with
#: their one-line help. Only the module of the command being run is imported, so a
#: light command never loads what a heavy one needs.
EXTRA_COMMANDS = {
    "validate": ("isorock.validate.cli.report", "the validation report: all engines side by side with the "
                                                 "analytic model"),
    "bench": ("isorock.validate.cli.bench", "work-precision benchmarks of every engine"),
    "stress": ("isorock.validate.cli.stress", "the stability stress grid (exits non-zero on any failure)"),
    "calibrate": ("isorock.validate.cli.calibrate", "fit a contact engine's contact parameters to the closed-form β"),
    "atlas": ("isorock.validate.cli.atlas", "the contact-model atlas: every preset's β and t₁ error over slenderness "
                                        "× mass ratio × size, with its cost"),
    "view": ("isorock.validate.cli.view", "replay a run in MuJoCo's viewer, or write it as a GIF where there is no "
                                      "display"),
    "presets": ("isorock.validate.cli.presets", "every engine's presets, with their reasons and settings"),
    "sweep": ("isorock.validate.cli.sweep", "run a campaign (TOML): overturning spectra, fragility curves, agreement maps"),
    "design": ("isorock.validate.cli.design", "which isolator keeps my statue standing at my site: P(overturn) and "
                                              "stroke per isolator over a record suite, the chart, the recommended region"),
    "statue": ("isorock.validate.cli.statue", "a statue's mesh: the direction it tips first, and its two tipping "
                                              "edges"),
    "experiments": ("isorock.validate.cli.experiments", "score the rigid model and the contact engines against measured "
                                                        "shake-table tests"),
    "scorecard": ("isorock.validate.cli.scorecard", "every engine and preset on the same rows (atlas, validate, stress, "
                                                    "speed, shake table), written to docs/engines.md"),
}


def _command(module: str, name: str):
    """The function `name` of `module`, imported when the command runs: the dispatch, the one place
    where imports wait, so that building the parser stays light (`isorock beta` loads no NumPy)
    while each command's module has its imports at its top."""
    def command(args):
        return getattr(importlib.import_module(module), name)(args)
    return command


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of `command`: the other extra commands are listed with their one-line
    help, their modules not imported, so `isorock --help` and light commands stay fast."""
    parser = OneLineParser(prog="isorock", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("beta", help="closed-form impact coefficients β, β₂, β₃ (JSON)")
    p.add_argument("--slenderness", type=number, required=True, help="λ = h/b = H/B")
    p.add_argument("--mass-ratio", type=number, required=True, help="μ = m/m_b (0: fixed base)")
    p.add_argument("--height", type=number, default=2.0, help="block height H, m; β₂, β₃ use h = H/2 (default 2.0)")
    p.set_defaults(func=cmd_beta)

    p = sub.add_parser("run", help="simulate one system with one engine",
                       description="Simulate one block on its base with one engine and print its metrics. Without "
                                   f"block options it is the paper's block (H {PAPER_BLOCK['height']:g} m, B "
                                   f"{PAPER_BLOCK['width']:g} m, m = m_b = {PAPER_BLOCK['mass']:g} kg), as "
                                   "validate and design take it; its base is yours to choose: fixed, on a linear "
                                   "isolator, or on another isolator.")
    p.add_argument("--engine", default=None, metavar="ENGINE[:PRESET][,…]",
                   help=f"one of {', '.join(_registered())}, optionally ENGINE:PRESET (e.g. mujoco:fast); "
                        "several, comma-separated, run on the same system and motion and are compared with "
                        "the first (default: analytic, the compiled kernel, which carries every --isolator)")
    add_system_options(p, defaults=PAPER_BLOCK)
    add_statue_options(p)
    add_isolator_options(p)
    add_motion_options(p)
    add_transverse_options(p)
    p.add_argument("--duration", type=number,
                   help="end time from t = 0, s (default: motion end + 5 s, or 10 s without motion)")
    p.add_argument("--theta0-over-alpha", "--theta0", dest="theta0_over_alpha", type=number, default=0.0,
                   help="initial tilt as a fraction of α (default 0; --theta0 is an alias)")
    p.add_argument("--impact-threshold", type=number, default=DEFAULT_IMPACT_THRESHOLD,
                   help="an impact counts when its half-cycle's peak |θ| exceeds this × α (default 0.01)")
    p.add_argument("--json", metavar="FILE", help="write the metrics and impact log as JSON ('-': standard output)")
    p.add_argument("--csv", metavar="FILE", help="write the history t,u,u_dot,theta,theta_dot (s, m, m/s, rad, rad/s; "
                                                 "'-': standard output); several engines: one file each, "
                                                 "FILE.ENGINE.csv")
    p.add_argument("--csv-dt", type=number, help="resample the CSV history at this interval, s")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw ẍg, θ/α with the counted impacts, θ̇ and u (several engines: overlaid, with each "
                        "engine's difference from the first); the format follows the suffix")
    p.add_argument("--quiet", action="store_true",
                   help="print nothing but errors (the summary, with the motion's PGA, is on standard output "
                        "otherwise, unless --json or --csv is '-')")
    add_engine_options(p)
    add_budget_option(p)
    p.set_defaults(func=_command("isorock.validate.cli.run", "cmd_run"))

    p = sub.add_parser("scene", help="write the model file a contact engine runs (MuJoCo: MJCF, PyBullet and "
                                     "Drake: SDFormat)",
                       description="Write the model file a contact engine runs. Without system options it is "
                                   f"the paper's block ({PAPER_TEXT}).")
    p.add_argument("--engine", required=True, help="a contact engine: mujoco, bullet or drake")
    add_system_options(p, defaults=PAPER_BLOCK)
    p.add_argument("--out", required=True, metavar="FILE", help="where to write the model file ('-': standard output)")
    add_engine_options(p)
    p.set_defaults(func=_command("isorock.validate.cli.scene", "cmd_scene"))

    for name, (module, help_) in EXTRA_COMMANDS.items():
        if command != name:  # listed (top-level help, another command), its module not imported
            sub.add_parser(name, help=help_)
            continue
        try:
            mod = importlib.import_module(module)
        except ModuleNotFoundError as e:
            if e.name != module:
                raise
            continue
        mod.add_parser(sub)
    return parser


def cmd_beta(a) -> int:
    h = a.height / 2 if a.height is not None and a.height > 0 else a.height
    if h is None or not h > 0:
        raise InputError(f"height = {a.height!r}: must be a positive finite number")
    out = {
        "slenderness": a.slenderness, "mass_ratio": a.mass_ratio, "height": a.height,
        "beta": co.beta(a.slenderness, a.mass_ratio),
        "beta2": co.beta2(a.slenderness, a.mass_ratio, h),
        "beta3": co.beta3(a.mass_ratio, h),
        "beta_housner": co.beta_housner(a.slenderness),
        "no_bounce_slenderness": co.no_bounce_slenderness(a.mass_ratio),
    }
    print(json.dumps(out, indent=2))  # plain floats: no NumPy needed, so `beta` stays light
    return 0


def _registered():
    return ALL_ENGINES


def _stopped(code: int, *, as_process: bool) -> int:
    """A command stopped by a signal, its cleanup done: as a process, exit now, so that a
    worker thread still inside a compiled kernel (it hears no signal) cannot hold the
    exit (the interpreter joins its threads at exit: a stopped sweep went on for hours)."""
    if as_process:
        sys.stdout.flush()
        sys.stderr.flush()
        _end_children()
        os._exit(code)
    return code


def _end_children() -> None:
    """SIGTERM to this process's children: a child left running (glfw's library probe,
    started while MuJoCo is imported; a worker) would write after the stopped command's one
    line (its BrokenPipeError traceback, on the stderr it shares) or outlive it. Linux's
    /proc; elsewhere nothing is done."""
    me = os.getpid()
    try:
        entries = [e for e in os.listdir("/proc") if e.isdigit()]
    except OSError:
        return
    for entry in entries:
        try:
            with open(f"/proc/{entry}/stat") as f:
                ppid = int(f.read().rsplit(")", 1)[1].split()[1])
            if ppid == me:
                os.kill(int(entry), signal.SIGTERM)
        except (OSError, ValueError, IndexError):
            continue  # gone meanwhile, or not ours to signal


def _signalled(name: str, signum: int, error: BaseException | None) -> str:
    """The one line of a command a signal ended, with what it left (an `outcome` a command
    attached to the exception on its way up, or one it wraps)."""
    outcome = None
    while error is not None and outcome is None:
        outcome = getattr(error, "outcome", None)
        error = error.__cause__ or error.__context__
    outcome = outcome or "no output written"
    if signum == signal.SIGINT:
        return f"isorock {name}: interrupted; {outcome}"
    return f"isorock {name}: terminated by {signal.Signals(signum).name}; {outcome}"


def main(argv=None) -> int:
    argv_given = argv
    argv = sys.argv[1:] if argv is None else list(argv)
    command = next((x for x in argv if not x.startswith("-")), None)
    name = command or ""
    with signals_end_cleanly() as settle:
        # a signal may arrive at any point once it is heard, parsing and imports included, and
        # the exception its handler raised may come back as another (a C import re-wraps it) or
        # not at all (swallowed): once a signal was received, whatever ends the command is it
        error, code = None, 0
        try:
            try:
                parser = build_parser(command)  # imports the command's module: heard from here on
                try:
                    args = parser.parse_args(argv)
                except SystemExit as e:  # argparse: --help (0) or one error line (2)
                    code = e.code if isinstance(e.code, int) else 2
                else:
                    name = args.command
                    code = int(args.func(args) or 0)
            finally:
                settle()  # a signal from here on is recorded, never raised past the except below
        except BaseException as e:  # noqa: BLE001 — sorted below; what is not ours is raised again
            error = e
        signum = signal_received()
        if signum is None and isinstance(error, Terminated):
            signum = error.signum
        if signum is None and isinstance(error, KeyboardInterrupt):
            signum = signal.SIGINT  # raised without our handler (a thread, an embedding caller)
        if signum is not None:
            if argv_given is None:
                # a stopped command's one line is its last: what libraries log while their
                # loops and clusters are torn down (Dask's "Task exception was never
                # retrieved", a nanny that failed to start) is not for the user (issue 34)
                logging.disable(logging.CRITICAL)
            print(_signalled(name, signum, error), file=sys.stderr)
            return _stopped(128 + signum, as_process=argv_given is None)
        if isinstance(error, InputError):
            print(f"isorock {name}: error: {error}", file=sys.stderr)
            return 2
        if isinstance(error, BrokenPipeError):
            return 141
        if error is not None:
            raise error
        return code


if __name__ == "__main__":
    sys.exit(main())
