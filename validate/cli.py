"""The `isorock` command line.

    isorock beta     closed-form impact coefficients
    isorock run      one simulation with one engine (analytic, mujoco, bullet)
    isorock scene    the model file a contact engine runs (open it in its viewer)
    isorock validate the validation report (all engines side by side)
    isorock bench    work-precision benchmarks
    isorock stress   the stability stress grid
    isorock view     replay a run in MuJoCo's viewer (or as a GIF without a display)
    isorock calibrate  fit a contact engine's contact parameters to the closed-form β
    isorock atlas    the contact-model atlas: every preset's β and t₁ error over λ × μ × size, and its cost
    isorock sweep    campaigns: spectra, fragility curves, agreement maps (Dask)
    isorock experiments  the engines scored against measured shake-table tests of two rocks

Bad input exits with code 2 and one line on stderr, and leaves no output file.
Outputs go through validate.output: checked before the work, written all or none.
SIGTERM or SIGHUP end a command cleanly: nothing staged is left, exit 128 + signal.
"""
from __future__ import annotations

import argparse
import importlib
import re
import sys

from isorock.analytic.errors import InputError

#: Subcommands that live in their own modules (each has add_parser(subparsers)), with
#: their one-line help. Only the module of the command being run is imported, so a
#: light command never loads what a heavy one needs.
EXTRA_COMMANDS = {
    "validate": ("isorock.validate.report_cli", "the validation report: all engines side by side with the "
                                                 "analytic model"),
    "bench": ("isorock.validate.bench", "work-precision benchmarks of every engine"),
    "stress": ("isorock.validate.stress", "the stability stress grid (exits non-zero on any failure)"),
    "calibrate": ("isorock.validate.calibrate", "fit a contact engine's contact parameters to the closed-form β"),
    "atlas": ("isorock.validate.atlas", "the contact-model atlas: every preset's β and t₁ error over slenderness "
                                        "× mass ratio × size, with its cost"),
    "view": ("isorock.validate.view", "replay a run in MuJoCo's viewer, or write it as a GIF where there is no "
                                      "display"),
    "sweep": ("isorock.campaign.cli", "run a campaign (TOML): overturning spectra, fragility curves, agreement maps"),
    "experiments": ("isorock.experiments.cli", "score the rigid model and the contact engines against measured "
                                               "shake-table tests"),
}

#: Engine options: CLI dest → the field of the engine's Settings it sets.
ENGINE_OPTIONS = ("timestep", "solref", "solimp", "cone", "integrator", "friction", "noslip",
                  "solver_iterations", "substeps", "rtol", "atol", "rest_velocity", "max_step")


class OneLineParser(argparse.ArgumentParser):
    """argparse with model.md's error convention: one line naming the option, the value
    and what is allowed, exit 2 (not the usage block). A value may start with '-'
    (`--duration -inf`, `--scales -1,2,3`): it is a value, checked like any other."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # argparse's own pattern takes only -12 and -1.5 as values; -1e3, -inf, -1,2,3 are
        # values too (no isorock option looks like a number)
        self._negative_number_matcher = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def number(text: str) -> float:
    """argparse type: a real number (finite or not; the checks that follow say what is allowed)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: must be a number") from None


def whole_number(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: must be a whole number") from None


def _floats(n_min, n_max, name):
    def parse(text):
        try:
            values = tuple(float(x) for x in text.split(","))
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be comma-separated numbers") from None
        if not n_min <= len(values) <= n_max:
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must have {n_min}–{n_max} numbers")
        return values
    return parse


def add_system_options(p: argparse.ArgumentParser, *, required=True, defaults=None) -> None:
    d = defaults or {}
    g = p.add_argument_group("system (SI units)")
    g.add_argument("--height", type=number, required=required and "height" not in d, default=d.get("height"),
                   help="block height H = 2h, m")
    g.add_argument("--width", type=number, required=required and "width" not in d, default=d.get("width"),
                   help="block width B = 2b, m")
    g.add_argument("--mass", type=number, required=required and "mass" not in d, default=d.get("mass"),
                   help="block mass m, kg")
    g.add_argument("--base-mass", type=number, required=required and "base_mass" not in d,
                   default=d.get("base_mass"), help="base plate mass m_b, kg (μ = m/m_b)")
    g.add_argument("--period", type=number, help="isolation period T = 2π√(M/k), s")
    g.add_argument("--damping-ratio", "--damping", dest="damping_ratio", type=number,
                   help="isolator damping ratio ξ = c/(2Mω), dimensionless (--damping is an alias)")
    g.add_argument("--stiffness", type=number, help="isolator stiffness k, N/m (instead of --period)")
    g.add_argument("--dashpot", type=number, help="isolator dashpot c, N·s/m (with --stiffness)")
    g.add_argument("--fixed-base", action="store_true", help="fixed (non-isolated) base: μ = 0")


def system_from_args(a, *, default_isolator=None):
    """The System the options describe; `default_isolator` (period, damping ratio)
    is used when no isolator option is given (the scene command's paper defaults)."""
    from isorock.analytic.system import System
    common = dict(height=a.height, width=a.width, mass=a.mass, base_mass=a.base_mass)
    isolation = [x is not None for x in (a.period, a.damping_ratio, a.stiffness, a.dashpot)]
    if a.fixed_base:
        if any(isolation):
            raise InputError("--fixed-base: cannot be combined with --period/--damping-ratio/--stiffness/--dashpot")
        return System.fixed(**common)
    if a.period is not None or a.damping_ratio is not None:
        if a.period is None or a.damping_ratio is None or a.stiffness is not None or a.dashpot is not None:
            raise InputError("isolator: give --period with --damping-ratio, or --stiffness with --dashpot, "
                             "or --fixed-base")
        return System.isolated(**common, period=a.period, damping_ratio=a.damping_ratio)
    if a.stiffness is not None:
        return System.from_stiffness(**common, stiffness=a.stiffness,
                                     damping=0.0 if a.dashpot is None else a.dashpot)
    if default_isolator is not None:
        return System.isolated(**common, period=default_isolator[0], damping_ratio=default_isolator[1])
    raise InputError("isolator: give --period T --damping-ratio XI, or --stiffness K --dashpot C, or --fixed-base")


#: The system options, as argparse names them (and a TOML [system] table does).
SYSTEM_KEYS = ("height", "width", "mass", "base_mass", "period", "damping_ratio", "stiffness", "dashpot",
               "fixed_base")


def system_from_options(a, defaults: dict | None = None):
    """The System of the system options given with optional ones (`add_system_options(p,
    required=False)`), over `defaults` (a TOML [system] table); None when none is given,
    for the command's own default system."""
    from types import SimpleNamespace
    values = {k: (defaults or {}).get(k) for k in SYSTEM_KEYS}
    for k in SYSTEM_KEYS:
        v = getattr(a, k, None)
        if v not in (None, False):
            values[k] = v
    if not any(v not in (None, False) for v in values.values()):
        return None
    missing = [k for k in ("height", "width", "mass") if values[k] is None]
    if missing:
        raise InputError(f"--{missing[0].replace('_', '-')}: give the block's height, width and mass "
                         "(and its base) for your own system")
    if values["base_mass"] is None and not values["fixed_base"]:
        raise InputError("--base-mass: give the base plate's mass for an isolated base (or --fixed-base)")
    return system_from_args(SimpleNamespace(**values))


def add_motion_options(p: argparse.ArgumentParser, *, default="none") -> None:
    g = p.add_argument_group("ground motion")
    g.add_argument("--motion", default=default, metavar="SPEC",
                   help="a record file, a pulse 'sine:amp=A,freq=F,cycles=N', 'cosine:…', "
                        "'ricker:amp=A,freq=F' (A in g, F in Hz), or 'none' (default: %(default)s)")
    g.add_argument("--format", choices=("at2", "jma", "csv"),
                   help="record format: at2 (PEER, g), jma (gal), csv (two columns t, a); "
                        "guessed from the file when omitted")
    add_units_option(g)
    g.add_argument("--scale", type=number, default=1.0, help="factor applied to the motion (default: 1)")


def add_units_option(g) -> None:
    g.add_argument("--units", choices=("m/s2", "g", "gal", "cm/s2"),
                   help="units of a record: required for a two-column (csv) file unless the file states them "
                        "('# units: g', or a header 't [s], a [g]'); for an AT2 or JMA file, which state "
                        "theirs, it must agree")


def motion_from_args(a):
    from isorock.analytic.motion import load_motion
    m = load_motion(a.motion, format=a.format, units=a.units)
    return m if a.scale == 1.0 else m.scaled(a.scale)


def add_engine_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("engine settings (defaults chosen by measurement; see each engine's docs)")
    g.add_argument("--timestep", type=number,
                   help="the physics step, s, for every contact engine. mujoco: its contact solref/solimp "
                        "follow it unless given; bullet: the ground motion and isolator force are updated every "
                        "--substeps physics steps, which follow it (keeping that control step near 4 ms) unless "
                        "given. The settings used, those that followed included, are in the --json output")
    g.add_argument("--solref", type=_floats(2, 2, "solref"), help="mujoco: contact solref 'timeconst,dampratio'")
    g.add_argument("--solimp", type=_floats(3, 5, "solimp"), help="mujoco: contact solimp 'dmin,dmax,width[,mid,power]'")
    g.add_argument("--cone", choices=("pyramidal", "elliptic"), help="mujoco: friction cone")
    g.add_argument("--integrator", choices=("Euler", "implicit", "implicitfast", "RK4"), help="mujoco: integrator")
    g.add_argument("--friction", type=number, help="mujoco, bullet: block–base friction coefficient")
    g.add_argument("--noslip", type=whole_number, dest="noslip", metavar="N", help="mujoco: noslip iterations")
    g.add_argument("--solver-iterations", type=whole_number, help="bullet: constraint solver iterations")
    g.add_argument("--substeps", type=whole_number,
                   help="bullet: physics steps per control step (ground motion and isolator force updated)")
    g.add_argument("--rtol", type=number, help="analytic: relative tolerance (default 1e-10)")
    g.add_argument("--atol", type=number, help="analytic: absolute tolerance, m and rad (default 1e-12)")
    g.add_argument("--max-step", type=number,
                   help="analytic: largest integrator step, s (default 0.01; bounds how long a threshold "
                        "crossing of the base acceleration can hide inside one step)")
    g.add_argument("--rest-velocity", type=number,
                   help="analytic: rocking ends at an impact with |θ̇| below this × p·α (default 1e-5)")
    g.add_argument("--overturn", choices=("past-alpha", "alpha"),
                   help="the overturning rule (model.md, 'Past α'), for every engine: past-alpha (default: the "
                        "block has overturned when |θ| reaches π/2 or the run ends with |θ| > α) or alpha "
                        "(conservative: once |θ| reaches α)")


def engine_settings_from_args(engine, a):
    overrides = {k: getattr(a, k) for k in ENGINE_OPTIONS if getattr(a, k, None) is not None}
    try:
        return engine.settings(**overrides)
    except InputError as e:
        raise InputError(str(e).replace("_", "-")) from None


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
                       description="Simulate one block on its base with one engine and print its metrics.")
    p.add_argument("--engine", default="analytic", metavar="ENGINE[:PRESET][,…]",
                   help=f"one of {', '.join(_registered())}, optionally ENGINE:PRESET (e.g. mujoco:fast); "
                        "several, comma-separated, run on the same system and motion and are compared with "
                        "the first (default: %(default)s)")
    add_system_options(p)
    add_motion_options(p)
    p.add_argument("--duration", type=number,
                   help="end time from t = 0, s (default: motion end + 5 s, or 10 s without motion)")
    p.add_argument("--theta0-over-alpha", "--theta0", dest="theta0_over_alpha", type=number, default=0.0,
                   help="initial tilt as a fraction of α (default 0; --theta0 is an alias)")
    p.add_argument("--impact-threshold", type=number, default=0.01,
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
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("scene", help="write the model file a contact engine runs (MuJoCo: MJCF, PyBullet and "
                                     "Drake: SDFormat)",
                       description="Write the model file a contact engine runs. Without system options it is "
                                   "the paper's block (H 2.0 m, B 0.7 m, m = m_b = 3800 kg, T 1.5 s, ξ 0.2).")
    p.add_argument("--engine", required=True, help="a contact engine: mujoco, bullet or drake")
    add_system_options(p, defaults=dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0))
    p.add_argument("--out", required=True, metavar="FILE", help="where to write the model file ('-': standard output)")
    add_engine_options(p)
    p.set_defaults(func=cmd_scene)

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
    import json

    from isorock.analytic import coefficients as co
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


def _progress(quiet):
    if quiet or not sys.stderr.isatty():
        return None
    def report(t, total):
        print(f"\r  t = {t:8.2f} / {total:.2f} s", end="", file=sys.stderr, flush=True)
    return report


def cmd_run(a) -> int:
    from isorock.analytic.limits import check_resample
    from isorock.analytic.protocol import run_inputs
    from isorock.validate import run_cli
    from isorock.validate.engines import get_engine
    from isorock.validate.output import Outputs, to_json
    specs = run_cli.parse_engines(a.engine)
    if len(specs) > 1:  # several engines on one system and motion, compared with the first
        system, motion = system_from_args(a), motion_from_args(a)
        if a.duration is not None and not a.duration > 0:
            raise InputError(f"duration = {a.duration!r}: must be a positive number of seconds")
        if not (abs(a.theta0_over_alpha) < 1):
            raise InputError(f"theta0_over_alpha = {a.theta0_over_alpha!r}: must be a fraction of α between -1 and 1")
        run_inputs(system, motion, a.duration, a.theta0_over_alpha * system.alpha, a.impact_threshold)
        return run_cli.run_engines(a, specs, system, motion, progress=_progress(a.quiet))
    with Outputs() as outputs:
        # every output path is checked before the run, so a bad one costs nothing
        json_out = outputs.file("json", a.json) if a.json is not None else None
        csv_out = outputs.file("csv", a.csv) if a.csv is not None else None
        plot_out = outputs.file("plot", a.plot) if a.plot is not None else None
        if a.plot is not None:
            plot_kind = run_cli.plot_format(a.plot)  # a bad --plot name fails before the simulation
        engine = get_engine(specs[0][0])
        system = system_from_args(a)
        motion = motion_from_args(a)
        if specs[0][1] is not None:  # ENGINE:PRESET, with the engine options on top
            settings = run_cli.load_engines(specs, a)[0][2]
        else:
            settings = engine_settings_from_args(engine, a)
        if a.duration is not None and not a.duration > 0:
            raise InputError(f"duration = {a.duration!r}: must be a positive number of seconds")
        if not (abs(a.theta0_over_alpha) < 1):
            raise InputError(f"theta0_over_alpha = {a.theta0_over_alpha!r}: must be a fraction of α between -1 and 1")
        theta0 = a.theta0_over_alpha * system.alpha
        # the work bounds (duration, isolator, engine steps) before any work
        motion, duration = run_inputs(system, motion, a.duration, theta0, a.impact_threshold, settings=settings)
        if a.csv_dt is not None:
            if not (a.csv_dt > 0 and a.csv_dt < float("inf")):
                raise InputError(f"csv-dt = {a.csv_dt!r}: must be a positive number of seconds")
            check_resample("csv-dt", a.csv_dt, duration)
        traj = engine.simulate(system, motion, settings=settings, duration=duration, theta0=theta0,
                               impact_threshold=a.impact_threshold, overturn_rule=a.overturn,
                               progress=_progress(a.quiet))
        summary = traj.summary()
        report = dict(summary, system=system.describe(), motion=motion.describe(), settings=_settings_dict(settings))
        if json_out:
            from isorock.validate.provenance import provenance
            json_out.write_text(to_json(dict(report, provenance=provenance(record_paths=[a.motion]))) + "\n")
        if csv_out:
            hist = traj.resample(a.csv_dt) if a.csv_dt else traj
            csv_out.write(hist.to_csv)
        if plot_out:
            from isorock.validate.run_plot import plot_runs
            plot_out.write(lambda tmp: plot_runs({a.engine: traj}, motion, tmp, format=plot_kind))
        outputs.commit()
    to_stdout = "-" in (a.json, a.csv)
    if not a.quiet and not to_stdout:
        brief = {k: v for k, v in summary.items() if k != "impact_log"}
        brief["motion"] = {k: report["motion"][k] for k in ("name", "pga_g", "units_read")}
        print(to_json(brief))
    return 1 if traj.status.is_failure else 0


def _settings_dict(settings):
    """Every setting the run used, with those derived from them (e.g. PyBullet's control
    step): a timestep given alone brings other settings along, and the JSON says which."""
    from dataclasses import asdict
    out = asdict(settings)
    for name in dir(type(settings)):
        if isinstance(getattr(type(settings), name), property):
            out[name] = getattr(settings, name)
    return out


def cmd_scene(a) -> int:
    from isorock.validate.engines import get_engine
    from isorock.validate.output import Outputs
    with Outputs() as outputs:
        out = outputs.file("out", a.out)
        engine = get_engine(a.engine)
        if not engine.has_scene:
            raise InputError(f"engine = {a.engine!r}: has no model file to write (those that do: "
                             f"{', '.join(_engines_with_scenes())})")
        system = system_from_args(a, default_isolator=(1.5, 0.2))
        settings = engine_settings_from_args(engine, a)
        out.write_text(engine.scene_text(system, settings))
        outputs.commit()
    if a.out == "-":
        return 0
    kind, suffix = engine.spec.scene_format
    if not str(a.out).lower().endswith(suffix):
        print(f"note: {a.engine} scenes are {kind} files ({suffix}); {a.out} holds {kind}", file=sys.stderr)
    print(a.out)
    return 0


def _registered():
    from isorock.validate.engines import ALL_ENGINES
    return ALL_ENGINES


def _engines_with_scenes():
    from isorock.validate.engines import ALL_ENGINES, get_engine
    out = []
    for name in ALL_ENGINES:
        try:
            if get_engine(name).has_scene:
                out.append(name)
        except ImportError:
            continue
    return out


def main(argv=None) -> int:
    from isorock.validate.output import Terminated, signals_end_cleanly
    argv = sys.argv[1:] if argv is None else list(argv)
    command = next((x for x in argv if not x.startswith("-")), None)
    parser = build_parser(command)
    with signals_end_cleanly():
        try:
            args = parser.parse_args(argv)
        except SystemExit as e:  # argparse: --help (0) or one error line (2)
            return e.code if isinstance(e.code, int) else 2
        try:
            return int(args.func(args) or 0)
        except InputError as e:
            print(f"isorock {args.command}: error: {e}", file=sys.stderr)
            return 2
        except KeyboardInterrupt:
            print(f"isorock {args.command}: interrupted; no output written", file=sys.stderr)
            return 130
        except Terminated as e:
            print(f"isorock {args.command}: terminated by {e.name}; no output written", file=sys.stderr)
            return 128 + e.signum
        except BrokenPipeError:
            return 141


if __name__ == "__main__":
    sys.exit(main())
