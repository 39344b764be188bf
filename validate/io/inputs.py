"""What the options of `isorock run` and `isorock validate` describe, read from their typed
value (io/options.py: RunOptions, ValidateOptions) or any object with those attributes (the
parser's namespace): the System, the ground motion, the engines and their settings, and the
run's Plan (core.plan.make_plan). Below the command line (issue 35): `isorock run` and
`isorock.run` both call these, with the value each built; cli/options.py and cli/run.py keep
their names importable.

Errors name the options as the command line spells them (--base-mass); the notebook API says
them as its keywords (base_mass).

A record pair (--pair SUITE:ID) is read by the campaign's records (validate/tools/campaign), a
floor above: the caller hands its reader in (`read_pair`); the command line's is
cli.readers.read_pair.
"""
from __future__ import annotations

import sys
from dataclasses import fields, replace
from types import SimpleNamespace

from ...analytic import shape
from ...analytic.errors import InputError
from ...analytic.limits import check_period
from ...analytic.motion import load_motion
from ...analytic.system import (BALL_IN_BOWL, BALL_IN_CONE, BILINEAR, LINEAR, BallInBowl, BallInCone,
                                BilinearIsolator, DOUBLE_PENDULUM, DoubleFrictionPendulum, FRICTION_PENDULUM,
                                FrictionPendulum, ISOLATOR_KINDS, PlanarBody, System)
from ..core.biaxial import box_body
from ..core.engines import choose, describe_settings, get_engine, resolve, table_overrides
from ..core.plan import EngineRun, make_plan, run_plan
from . import keys
from .keys import ISOLATOR_KEYS, given  # noqa: F401 — ISOLATOR_KEYS: importable from here as before


#: Engine options: CLI dest → the field of the engine's Settings it sets.
ENGINE_OPTIONS = ("timestep", "solref", "solimp", "cone", "integrator", "friction", "noslip",
                  "solver_iterations", "substeps", "rtol", "atol", "rest_velocity", "max_step")


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


def transverse_asked(a) -> bool:
    return getattr(a, "motion_transverse", None) is not None or getattr(a, "pair", None) is not None


def _with_transverse(a, m, read_pair=None):
    """`m` with the second horizontal component the options name (--motion-transverse or the
    --pair's second), or `m` as it is without them."""
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
        if read_pair is None:
            raise InputError(f"--pair = {pair!r}: no reader of record pairs was given here")
        first, second = read_pair(pair)
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


def motion_from_args(a, *, read_pair=None):
    """The motion the options describe: read, then scaled by --scale, or to --pga / --pgv.
    read_pair(SUITE:ID) → (along x, along y): the reader of --pair (the caller's: a floor above)."""
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
    m = _with_transverse(a, m, read_pair)
    if targets:
        key, value = targets[0]
        if m.is_zero:  # 'none', or a record of zeros: named as given
            raise InputError(f"--{key} = {value:g}: the motion {a.motion!r} is zero throughout; it has no peak to "
                             "scale")
        return m.scaled_to_pga(value) if key == "pga" else m.scaled_to_pgv(value)
    return m if a.scale == 1.0 else m.scaled(a.scale)


def run_budget(a) -> float:
    """The --budget given, checked: a positive finite number of seconds."""
    if not (a.budget > 0 and a.budget < float("inf")):
        raise InputError(f"budget = {a.budget!r}: must be a positive finite number of seconds")
    return a.budget


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


def parse_engines(text: str) -> list[tuple[str, str | None]]:
    """'analytic,mujoco:fast' → [('analytic', None), ('mujoco', 'fast')]; names are
    checked by the registry when the engine is loaded."""
    out = []
    for item in (s.strip() for s in str(text).split(",")):
        if not item:
            raise InputError(f"engine = {text!r}: must be comma-separated engine names (ENGINE or ENGINE:PRESET)")
        name, _, preset = item.partition(":")
        out.append((name.strip(), preset.strip() or None))
    if len(set(out)) != len(out):
        raise InputError(f"engine = {text!r}: must name each engine (and preset) once")
    return out


def spec_label(name: str, preset: str | None) -> str:
    return name if preset is None else f"{name}:{preset}"


def engine_labels(items) -> list[str]:
    """`--engines` as bench and atlas take it (each item ENGINE or ENGINE:PRESET, space- or
    comma-separated, as validate takes it) → labels, each checked before any work: an
    unknown engine or preset is an InputError naming it and what is allowed. An engine
    that cannot be imported here is kept; the command reports it as not run."""
    # "analytic, mujoco" arrives as the items "analytic," and "mujoco": an item's own
    # leading or trailing comma separates, it does not name an empty engine
    specs = parse_engines(",".join(str(item).strip().strip(",") for item in items))
    for name, preset in specs:
        try:
            resolve(spec_label(name, preset))
        except ImportError:
            pass
    return [spec_label(name, preset) for name, preset in specs]


def load_engines(specs, a) -> list[tuple[str, object, object]]:
    """(label, Engine, Settings) for each spec, through the registry's one engine choice
    (core.engines.choose): the preset or the defaults, with the engine options given that
    the engine has. An engine option that none of the engines has is an error (it would
    silently do nothing); a bad value is named as its option."""
    tables = engine_tables(a)
    engines = [(spec_label(n, p), get_engine(n)) for n, p in specs]
    check_tables_run(tables, [label for label, _ in engines])
    unused = sorted(set(tables["*"]) - {f.name for _, e in engines for f in fields(e.Settings)})
    if unused:
        names = ", ".join("--" + k.replace("_", "-") for k in unused)
        raise InputError(f"{names}: not a setting of engine {', '.join(label for label, _ in engines)}")
    out = []
    for label, engine in engines:
        try:
            out.append((label, engine, choose(label, table_overrides(tables, label)).settings()))
        except InputError as e:
            raise InputError(str(e).replace("_", "-")) from None
    return out


def _progress(quiet):
    if quiet or not sys.stderr.isatty():
        return None

    def report(t, total):
        print(f"\r  t = {t:8.2f} / {total:.2f} s", end="", file=sys.stderr, flush=True)
    return report


def engine_asked(a) -> str:
    """--engine as given, or the default: the compiled kernel, which carries every isolator
    the model has (docs/isolators.md); with two horizontal components, MuJoCo, the engine
    that carries them."""
    if a.engine is not None:
        return a.engine
    return "mujoco" if transverse_asked(a) else "analytic"


def plan_runs(a, specs, *, read_pair=None):
    """The run options `a` (RunOptions, or the parser's namespace) read into Python values, and the one Plan
    of them (core.plan.make_plan: every check made there once, before any work). read_pair:
    motion_from_args's."""
    runs = [EngineRun(label, engine, settings) for label, engine, settings in load_engines(specs, a)]
    statue = statue_body(a)  # a statue's mesh read once: the System's two edges, and the 3-D measures' body
    system, motion = system_from_args(a, statue=statue), motion_from_args(a, read_pair=read_pair)
    # two components: the body shaken and its direction for the 3-D measures, its isolator checked
    # first; an engine that runs one component named as the option names it
    for r in runs:
        if motion.transverse is not None:
            check_pair_engine(r, system)
    shaken = None if motion.transverse is None else shaken_body(a, system, statue)
    if not (abs(a.theta0_over_alpha) < 1):
        raise InputError(f"theta0_over_alpha = {a.theta0_over_alpha!r}: must be a fraction of α between -1 and 1")
    # a fraction of the α of the edge it tilts onto (a statue's two edges differ)
    theta0 = a.theta0_over_alpha * system.edge_alpha(1 if a.theta0_over_alpha >= 0 else -1)
    plan = make_plan(system, motion, runs, duration=a.duration, theta0=theta0, impact_threshold=a.impact_threshold,
                     overturn_rule=a.overturn, first_run=True)
    return plan, shaken


def check_pair_engine(r, system) -> None:
    """One line, before any work, for an engine that does not run two horizontal components, or
    not on this isolator (Capabilities.transverse_isolators: the linear one, and in MuJoCo,
    PyBullet, Drake and DART the pendulums, whose friction in the plane their scenes make isotropic)."""
    caps = r.engine.capabilities
    if not getattr(caps, "transverse", False):
        raise InputError(f"--engine = {r.label!r}: runs one horizontal component only; with two "
                         "(--motion-transverse, --pair) the engine is mujoco, bullet, drake or dart")
    kinds = getattr(caps, "transverse_isolators", (LINEAR,))
    if not system.fixed_base and system.isolator_kind not in kinds:
        raise InputError(f"--isolator = {system.isolator_kind!r}: with two horizontal components (--motion-transverse, "
                         f"--pair) engine {r.label!r} carries {' or '.join(kinds)} (the same k and c along x and y"
                         f"{'' if kinds == (LINEAR,) else '; a pendulum with its friction the same in every direction'}"
                         "), or give --fixed-base")


def shaken_body(a, system, statue, names: dict = STATUE_OPTIONS) -> tuple:
    """(the body at rest, the azimuth in rad) of a run with two components: the statue's mesh
    (`statue`, statue_body's (resting, body), along --azimuth or the direction it tips first), or
    the block H × B × D of MuJoCo's scene along 0. `names`: how a statue's inputs are spelled in
    errors (statue_body's)."""
    # the contact scenes' block stands on a square footprint (MuJoCo's and Drake's DEPTH_FRACTION 1, PyBullet's
    # 2b × 2b box, DART's DEPTH_RATIO 1)
    if system.body is None:
        return box_body(system.height, system.width, system.width, system.mass), 0.0
    standing = statue[0]
    return standing, statue_azimuth(a, standing, names)


def simulate_plan(plan, a, *, announce: bool = False, budget: float | None = None) -> tuple[dict, dict]:
    """(label → Trajectory, label → Settings used), in the order the engines were given;
    each run within `budget` s (core.plan.run_plan)."""
    runs = run_plan(plan, progress=_progress(getattr(a, "quiet", True)), budget_s=budget,
                    on_start=(lambda label: print(f"\r{label} …", file=sys.stderr)) if announce else None)
    return runs, {r.label: r.settings for r in plan.runs}
