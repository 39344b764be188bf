"""`isorock run`: one engine, or several (`--engine analytic,mujoco:fast,bullet`) on the same
system and motion, the first the reference every other is compared with (core.compare).
One path for both: every output (--json, --csv, --plot) is checked before the runs and
written all or none through one `Outputs` (io.output). One engine prints and writes its
metrics; several print and write the comparison and draw the engines overlaid.

ENGINE:PRESET asks for one of the engine's named presets (`EngineSpec.presets`); engine
options given on the command line (--timestep, --friction, …) are applied on top, to
every engine that has that setting.

--csv with several engines writes one file per engine, the engine (and preset) added
before the suffix: `--csv h.csv` → h.analytic.csv, h.mujoco-fast.csv. The single-engine
output (its JSON fields, its CSV) is unchanged.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from ...analytic.errors import InputError
from ...analytic.limits import BudgetExceeded, check_resample
from ..io.provenance import provenance
from .options import budget_stopped
from .readers import read_pair
from ..core.biaxial import render, two_components
from ..core.compare import compare
from ..core.estimate import announce_cost
from ..io import inputs
# the options read into a Plan, below the command line (io/inputs.py)
from ..io.inputs import engine_asked, parse_engines, run_budget, settings_dict, simulate_plan, spec_label
from ..io.naming import cell, describe_motion
from ..io.options import RunOptions
from ..io.output import Outputs, to_json


def plan_runs(a, specs):
    """The run options' Plan (io.inputs.plan_runs, --pair read by the command line's read_pair)."""
    return inputs.plan_runs(a, specs, read_pair=read_pair)


def _file_suffix(path, label: str) -> Path:
    path = Path(path)
    return path.with_name(f"{path.stem}.{label.replace(':', '-')}{path.suffix}")


def plot_format(path) -> str:
    """The image format of --plot FILE, from its suffix (one matplotlib can write)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # lazy: matplotlib only with --plot
    supported = FigureCanvasAgg.get_supported_filetypes()
    fmt = Path(path).suffix.lower().lstrip(".")
    if fmt not in supported:
        raise InputError(f"plot = {str(path)!r}: must end in one of {', '.join('.' + s for s in sorted(supported))}")
    return fmt


def comparison_table(runs: dict, comparisons: dict) -> str:
    """Each engine's metrics, then each engine against the reference (the first)."""

    ref_label = next(iter(runs))
    width = max(18, 2 + max(len(label) for label in runs))
    slides = any(tr.slide is not None for tr in runs.values())  # the statue may slip: its walk beside
    head = (f"{'engine':<{width}}{'status':<12}{'θmax/α':>8}{'impacts':>9}{'overturned':>12}{'u_max cm':>10}"
            + (f"{'slide cm':>10}{'final cm':>10}" if slides else "") + f"{'wall s':>8}")
    lines = [head]
    for label, tr in runs.items():
        walk = ""
        if slides:
            x = None if tr.slide is None else tr.slide - tr.slide[0]
            walk = (f"{cell(None if x is None else 100 * np.max(np.abs(x)), '{:.3g}'):>10}"
                    f"{cell(None if x is None else 100 * x[-1], '{:.3g}'):>10}")
        lines.append(f"{label:<{width}}{str(tr.status):<12}{tr.theta_max_over_alpha:>8.3f}{tr.impact_count:>9d}"
                     f"{'yes' if tr.overturned else 'no':>12}{tr.u_max * 100:>10.3g}{walk}{tr.runtime_s:>8.2f}")
    if comparisons:
        lines.append("")
        lines.append(f"against {ref_label}:")
        lines.append(f"{'engine':<{width}}{'Δθmax/α':>9}{'horizon s':>11}{'parted':>8}{'|β err| median %':>18}"
                     f"{'Δuplift s':>11}{'overturn agree':>16}"
                     + (f"{'Δslide %':>10}{'Δslide onset s':>16}  modes" if slides else ""))
        for label, c in comparisons.items():
            beta = None if c.beta_error_median is None else 100 * c.beta_error_median
            walk = ""
            if slides:
                rel = None if c.slide_rel_error is None else 100 * c.slide_rel_error
                walk = (f"{cell(rel, '{:+.3g}'):>10}{cell(c.slide_onset_diff, '{:+.3g}'):>16}  "
                        f"{' → '.join(c.modes or ()) or 'rest'}"
                        + ("" if c.modes == c.modes_ref else f" (reference: {' → '.join(c.modes_ref or ()) or 'rest'})"))
            lines.append(f"{label:<{width}}{c.theta_max_diff:>+9.3f}{c.horizon:>11.3f}{'yes' if c.parted else 'no':>8}"
                         f"{cell(beta, '{:.3g}'):>18}{cell(c.first_uplift_diff, '{:+.3g}'):>11}"
                         f"{'yes' if c.overturn_agree else 'NO':>16}{walk}")
    return "\n".join(lines)


def cmd_run(a) -> int:
    """One or several engines on one system and motion; exit 1 when any run failed. `a`: the
    parser's namespace, read into the typed RunOptions that isorock.run builds from keywords."""
    a = RunOptions.from_namespace(a)
    specs = parse_engines(engine_asked(a))
    several = len(specs) > 1
    with Outputs() as outputs:
        # every output path is checked before the runs, so a bad one costs nothing
        json_out = outputs.file("json", a.json) if a.json is not None else None
        csv_outs = {}
        if a.csv is not None:
            for name, preset in specs:  # several engines: FILE.ENGINE.csv each
                label = spec_label(name, preset)
                csv_outs[label] = outputs.file("csv", _file_suffix(a.csv, label) if several else a.csv)
        plot_out = outputs.file("plot", a.plot) if a.plot is not None else None
        plot_kind = plot_format(a.plot) if a.plot is not None else None
        plan, shaken = plan_runs(a, specs)
        system, motion, duration = plan.system, plan.motion, plan.duration
        if a.csv_dt is not None:
            if not (a.csv_dt > 0 and a.csv_dt < float("inf")):
                raise InputError(f"csv-dt = {a.csv_dt!r}: must be a positive number of seconds")
            check_resample("csv-dt", a.csv_dt, duration)
        # every run has a budget, and a long command says what it will cost before it starts
        budget = run_budget(a)
        announce_cost("run", {r.label: duration for r in plan.runs}, budget, quiet=a.quiet)
        try:
            runs, used = simulate_plan(plan, a, announce=several and not a.quiet and sys.stderr.isatty(), budget=budget)
        except BudgetExceeded as e:
            return budget_stopped("run", e.label, e)
        ref_label, ref = next(iter(runs.items()))
        comparisons = {label: compare(tr, ref) for label, tr in runs.items() if label != ref_label}
        two = None
        if shaken is not None:  # two components: the 3-D measures, the planar runs beside (issue 36)
            two = two_components(runs, system, motion, *shaken, duration)
        if several:
            report = {
                "reference": ref_label, "system": system.describe(),
                "motion": dict(motion.describe(), description=describe_motion(motion)),
                "engines": {label: dict(tr.summary(), settings=settings_dict(used[label], system, duration))
                            for label, tr in runs.items()},
                "comparisons": {label: c.as_dict() for label, c in comparisons.items()},
            }
        else:
            summary = ref.summary()
            report = dict(summary, system=system.describe(), motion=motion.describe(),
                          settings=settings_dict(used[ref_label], system, duration))
        if two is not None:  # first: its verdict is the run's (the fields above are the planar projection on x)
            report = dict(two_components=two[ref_label] if not several else two, **report)
        if json_out:
            json_out.write_text(to_json(dict(report, provenance=provenance(record_paths=[a.motion]))) + "\n")
        for label, out in csv_outs.items():
            tr = runs[label]
            out.write((tr.resample(a.csv_dt) if a.csv_dt else tr).to_csv)
        if plot_out:
            from ..io.run_plot import plot_runs  # lazy: matplotlib only with --plot
            plot_out.write(lambda tmp: plot_runs(runs, motion, tmp, format=plot_kind))
        outputs.commit()
    if not a.quiet and "-" not in (a.json, a.csv):
        if two is not None:
            for label, one in two.items():
                print(render(one, label))
        if several:
            print(comparison_table(runs, comparisons))
            for out in [*csv_outs.values(), *([plot_out] if plot_out else [])]:
                print(f"wrote {out.given}")
        else:
            brief = {k: v for k, v in summary.items() if k != "impact_log"}
            brief["motion"] = {k: report["motion"][k] for k in ("name", "pga_g", "units_read")}
            print(to_json(brief))
    return 1 if any(tr.status.is_failure for tr in runs.values()) else 0
