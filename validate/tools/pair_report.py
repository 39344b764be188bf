"""`isorock validate` under a record pair (--pair SUITE:ID, or --motion with --motion-transverse;
issue 36): every engine that runs two horizontal components judged on the one exact oracle they
meet there, turning the pair and the statue together (core/turned_pair.py), with the 3-D measures
of each and the exact planar model along each component beside them, unjudged (what it cannot
capture said in words). DIR/report.md, its figure DIR/pair.png and DIR/metrics.json, whole or
absent; the verdict is the last line on stdout; exit 1 when a check failed.

Below the command line (issue 35): `pair_inputs` reads the options, `build` runs and judges,
`write` writes; `isorock validate` (cli/pair_report.py prints) and `isorock.report` call them
alike. A --pair SUITE:ID is read by the reader the caller hands in (`read_pair`: the campaign's
records, which only the command line's floor imports).
"""
from __future__ import annotations

import argparse
import math
import sys

from ...analytic.errors import InputError
from ...analytic.limits import RUN_BUDGET_S
from ..core import biaxial, turned_pair
from ..core.engines import get_engine, table_overrides
from ..core.estimate import announce_cost
from ..core.plan import engine_run, make_plan
from ..core.tolerances import has_tolerance, tolerance
from ..io import figures
from ..io.config_file import check_damping_ratio
from ..io.inputs import (engine_labels, motion_from_args, shaken_body, statue_body, system_from_args,
                         system_options)
from ..io.output import to_json, write_folder_atomic
from .report_config import config_of, engine_overrides

#: the report's figure (figures.turned_pair): what the report shows before its tables
FIGURE = "pair.png"
#: the engines judged when --engines is not given: validate's defaults that run a pair
DEFAULT_PAIR_ENGINES = ("mujoco", "bullet")
#: s simulated after the pair ends (--duration otherwise): the runs part in the first impacts (measured: every
#: turned check the same at 2 s as at 4 s on the tests' pulses, which end by 0.45 s), and each engine runs three
#: times (turned_pair.turned_runs)
TAIL = 2.0


def pair_motion(args, config: dict, read_pair=None):
    """The pair the options name: --pair (read by read_pair), or one --motion (the first component)
    with --motion-transverse; scaled to --pga or --pgv as validate scales its motions."""
    motions = list(args.motion or config.get("motions") or [])
    if args.pair is None and len(motions) != 1:
        raise InputError(f"--motion = {motions!r}: with --motion-transverse, give one --motion (the first component, "
                         "along x)")
    one = argparse.Namespace(motion=motions[0] if motions else "none", format=args.format or config.get("format"),
                             units=args.units or config.get("units"), scale=1.0, pga=args.pga, pgv=args.pgv,
                             motion_transverse=args.motion_transverse, transverse_units=args.transverse_units,
                             pair=args.pair, vertical=None)
    if args.pga is None and args.pgv is None:
        one.pga, one.pgv = config.get("pga"), config.get("pgv")
    return motion_from_args(one, read_pair=read_pair)


def pair_inputs(args) -> dict:
    """The options of validate under a record pair read as report_config reads them (the engines
    without the analytic reference: the exact model is planar, beside each engine, unjudged):
    build's keywords."""
    config = config_of(args)
    engines = tuple(engine_labels(args.engines)) if args.engines else DEFAULT_PAIR_ENGINES
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


def _settled(labels, system, motion, overrides_for, duration, overturn_rule=None):
    """(the plan of the engines that run this pair, label → the one line why each other does not)."""
    runs, skipped = [], {}
    for label in labels:
        try:
            engine = get_engine(label.partition(":")[0])
        except ImportError as e:
            skipped[label] = f"not installed here ({type(e).__name__}: {e})"
            continue
        if not engine.capabilities.transverse:
            skipped[label] = ("the exact planar model: beside each engine along each component, not judged here"
                              if engine.capabilities.exact_impacts else "runs one horizontal component only")
            continue
        try:
            run = engine_run(label, overrides_for(label))
            make_plan(system, motion, [run], duration=duration, overturn_rule=overturn_rule)
        except InputError as e:  # its own one line (DART below its pair friction, an isolator it does not carry)
            skipped[label] = str(e)
            continue
        runs.append(run)
    if not runs:
        raise InputError(f"--engines = {', '.join(labels)}: none runs this pair ("
                         + "; ".join(f"{k}: {v}" for k, v in skipped.items())
                         + "); engines 'mujoco', 'bullet', 'drake' and 'dart:pair' run two horizontal components")
    return make_plan(system, motion, runs, duration=duration, overturn_rule=overturn_rule), skipped


def build(args, config: dict, *, engines, overrides: dict, system, shaken, duration,
          read_pair=None) -> tuple[dict, dict]:
    """(what metrics.json holds, label → turned_pair.TurnedRuns or the error of an engine that did
    not run) of the pair's validation: `engines` the labels asked, `overrides` table → settings
    (validate's --set, engine options and [settings.ENGINE] tables), `system` the System the options
    give, `shaken` its body at rest and azimuth (io.inputs.shaken_body), as pair_inputs reads them;
    `read_pair` the reader of --pair SUITE:ID. The command writes the first; isorock.report returns
    both."""
    for option, given in (("--quick", args.quick or bool(config.get("quick"))), ("--scales", args.scales is not None),
                          ("--workers", args.workers is not None)):
        if given:  # they shape the one-component report's ensembles and pool: said, never dropped unsaid
            raise InputError(f"{option}: validate with a record pair runs no ensemble and no worker pool (each engine's "
                             "three runs, here); leave it out")
    motion = pair_motion(args, config, read_pair)
    if system is None:
        raise InputError("system: with a record pair, give the statue (--statue or --statue-example) or the block "
                         "(--height, --width, --mass) and its base; validate's paper block is for one component")
    body, azimuth = shaken
    duration = duration if duration is not None else motion.last_time + TAIL
    plan, skipped = _settled(engines, system, motion, lambda label: table_overrides(overrides, label), duration,
                             args.overturn)
    turn = turned_pair.TURN_DEG if system.body is not None else turned_pair.QUARTER_TURN
    # each engine runs three times (as given, turned, the probe); each run stops at the run budget
    # (limits.RUN_BUDGET_S), said before
    announce_cost("validate", {r.label: 3 * plan.duration for r in plan.runs}, RUN_BUDGET_S, quiet=args.quiet)
    results = turned_pair.turned_runs(
        plan, body, azimuth, turn, budget_s=RUN_BUDGET_S,
        on_start=None if args.quiet else (lambda label: print(f"{label} …", file=sys.stderr, flush=True)))
    ran = {k: r for k, r in results.items() if isinstance(r, turned_pair.TurnedRuns)}
    # an engine that refused the pair as it ran, or ran past its budget: not run, its one line said
    skipped.update({k: str(r).splitlines()[0] for k, r in results.items() if k not in ran})
    # the exact model along each component alone: beside each engine in words, and in the figure
    planar = biaxial.planar_runs(system, motion, body if system.body is not None else None, azimuth,
                                 duration=plan.duration)
    three = biaxial.two_components({k: r.first for k, r in ran.items()}, system, motion, body, azimuth, plan.duration,
                                   planar=planar)
    checks = [c for r in ran.values() for c in r.checks]
    judged = list(ran)
    verdict = pair_verdict(checks, turn, judged, skipped)
    metrics = {"verdict": verdict, "motion": motion.describe(), "system": system.describe(), "turn_deg": turn,
               "azimuth_deg": math.degrees(azimuth) % 360.0,
               "checks": [c.as_dict() for c in checks], "not_run": skipped, "two_components": three}
    least = biaxial.alpha_table(body, azimuth)[1]
    limits = {label: tolerance(label, turned_pair.HISTORY).limit for label in ran  # an engine without the row: none drawn
              if has_tolerance(label, turned_pair.HISTORY)}

    def draw(path):
        figures.turned_pair(motion, ran, planar, limits, least, path,
                            title=f"{motion.name}: each engine as given and turned {turn:g}° with the statue")
    return dict(metrics, figure=draw), results


def write(metrics: dict, out) -> None:
    """report.md, its figure pair.png and metrics.json into `out`, whole or absent
    (write_folder_atomic); `metrics` as build returns it (its `figure` draws the PNG)."""
    data = {k: v for k, v in metrics.items() if k != "figure"}

    def fill(tmp):
        metrics["figure"](tmp / FIGURE)
        (tmp / "report.md").write_text(render(data), encoding="utf-8")
        (tmp / "metrics.json").write_text(to_json(data) + "\n", encoding="utf-8")
    write_folder_atomic(out, fill)


def pair_verdict(checks, turn: float, judged, skipped: dict) -> str:
    """The one line, in the words of validate's own verdict (report_render.verdict): what failed,
    or how many passed and how many were not made, and why."""
    failed = [c for c in checks if c.status == "fail"]
    n_pass = sum(c.status == "pass" for c in checks)
    n_skip = sum(c.status == "skip" for c in checks)
    n_idle = sum(c.status == "not exercised" for c in checks)
    tail = f"({n_skip} skipped, {n_idle} not exercised: the report says why)"
    if failed:
        worst = ", ".join(sorted({f"{c.engine} {c.metric}" for c in failed}))
        head = f"Result: FAILED — {len(failed)} of {len(checks)} checks failed ({worst}) {tail}"
    elif n_pass == 0:
        head = f"Result: nothing was tested — no check could be made {tail}"
    elif n_pass < len(checks):
        head = f"Result: all {n_pass} checks made passed, {len(checks) - n_pass} of {len(checks)} not made {tail}"
    else:
        head = f"Result: all {n_pass} checks passed"
    what = f"the pair and the statue turned together by {turn:g}°, on {', '.join(judged) or 'no engine'}"
    return f"{head}; {what}." + (f" Not run: {', '.join(skipped)}." if skipped else "")


def render(m: dict) -> str:
    """The report in words: the verdict, each engine's checks, its 3-D measures and the planar runs
    beside them, and what the planar model cannot capture."""
    lines = ["# isorock validate: a record pair", "", f"**{m['verdict']}**", "",
             f"Motion: {m['motion'].get('name')} (its second component along y, 90° from x); the statue's "
             f"direction along x {m['azimuth_deg']:.0f}°. Each engine ran the pair twice: as given, and with the pair "
             f"and the statue turned together by {m['turn_deg']:g}°, the same ground acceleration in the statue's own "
             "frame (an exact symmetry of the physics). Each difference is judged by the engine's own row of the one "
             "tolerance table.", "", f"![each engine as given and turned, their difference against its limit]({FIGURE})",
             "", "| engine | check | value | limit | status | why this limit |", "|---|---|---:|---:|---|---|"]
    for c in m["checks"]:
        value = "—" if c["value"] is None else f"{c['value']:.3g}"
        lines.append(f"| {c['engine']} | {c['metric']} | {value} | {c['limit']:g} | {c['status']} | {c['reason']} |")
    for label, why in m["not_run"].items():
        lines.append(f"| {label} | — | — | — | not run | {why} |")
    lines += ["", "## What each engine's run of the pair says, and the exact planar model beside it", ""]
    for label, one in m["two_components"].items():
        lines += [f"### {label}", "", biaxial.render(one, label).replace("\n", "\n\n"), ""]
    return "\n".join(lines) + "\n"
