"""`isorock run` with several engines (`--engine analytic,mujoco:fast,bullet`) and the
`--plot` figure: each engine runs the same system and motion, the first is the
reference every other is compared with (validate.compare), and the comparison is
printed, written with --json, and drawn with --plot (engines overlaid, plus each
engine's difference from the reference).

ENGINE:PRESET asks for one of the engine's named presets (`EngineSpec.presets`); engine
options given on the command line (--timestep, --friction, …) are applied on top, to
every engine that has that setting.

--csv with several engines writes one file per engine, the engine (and preset) added
before the suffix: `--csv h.csv` → h.analytic.csv, h.mujoco-fast.csv. The single-engine
output (its JSON fields, its CSV) is unchanged.
"""
from __future__ import annotations

import sys
from dataclasses import fields
from pathlib import Path

from isorock.analytic.errors import InputError
from isorock.validate.cli.main import ENGINE_OPTIONS, _settings_dict


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
    from isorock.validate.core.engines import resolve
    # "analytic, mujoco" arrives as the items "analytic," and "mujoco": an item's own
    # leading or trailing comma separates, it does not name an empty engine
    specs = parse_engines(",".join(str(item).strip().strip(",") for item in items))
    for name, preset in specs:
        try:
            resolve(spec_label(name, preset))
        except ImportError:
            pass
    return [spec_label(name, preset) for name, preset in specs]


def _overrides(a) -> dict:
    return {k: getattr(a, k) for k in ENGINE_OPTIONS if getattr(a, k, None) is not None}


def settings_for(engine, preset: str | None, overrides: dict):
    """The engine's settings: its default (or the preset) with the overrides it has
    (runner.engine_setting, as validate and the campaigns make them); a bad value is
    named as its option."""
    from isorock.validate.core.engines import choose as engine_setting
    try:
        return engine_setting(spec_label(engine.name, preset), overrides).settings()
    except InputError as e:
        raise InputError(str(e).replace("_", "-")) from None


def load_engines(specs, a) -> list[tuple[str, object, object]]:
    """(label, Engine, Settings) for each spec. An engine option that none of the engines
    has is an error (it would silently do nothing)."""
    from isorock.validate.core.engines import get_engine
    overrides = _overrides(a)
    engines = [(spec_label(n, p), get_engine(n), p) for n, p in specs]
    unused = sorted(set(overrides) - {f.name for _, e, _ in engines for f in fields(e.Settings)})
    if unused:
        names = ", ".join("--" + k.replace("_", "-") for k in unused)
        raise InputError(f"{names}: not a setting of engine {', '.join(l for l, _, _ in engines)}")
    return [(label, e, settings_for(e, p, overrides)) for label, e, p in engines]


def _file_suffix(path, label: str) -> Path:
    path = Path(path)
    return path.with_name(f"{path.stem}.{label.replace(':', '-')}{path.suffix}")


def plot_format(path) -> str:
    """The image format of --plot FILE, from its suffix (one matplotlib can write)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    supported = FigureCanvasAgg.get_supported_filetypes()
    fmt = Path(path).suffix.lower().lstrip(".")
    if fmt not in supported:
        raise InputError(f"plot = {str(path)!r}: must end in one of {', '.join('.' + s for s in sorted(supported))}")
    return fmt


def write_plot(path, runs: dict, motion) -> None:
    from isorock.validate.io.output import write_atomic
    from isorock.validate.io.run_plot import plot_runs
    fmt = plot_format(path)
    write_atomic(path, lambda tmp: plot_runs(runs, motion, tmp, format=fmt))


def _fmt(x, spec="{:.3g}"):
    return "–" if x is None else spec.format(x)


def comparison_table(runs: dict, comparisons: dict) -> str:
    """Each engine's metrics, then each engine against the reference (the first)."""
    ref_label = next(iter(runs))
    head = f"{'engine':<18}{'status':<12}{'θmax/α':>8}{'impacts':>9}{'overturned':>12}{'u_max cm':>10}{'wall s':>8}"
    lines = [head]
    for label, tr in runs.items():
        lines.append(f"{label:<18}{str(tr.status):<12}{tr.theta_max_over_alpha:>8.3f}{tr.impact_count:>9d}"
                     f"{'yes' if tr.overturned else 'no':>12}{tr.u_max * 100:>10.3g}{tr.runtime_s:>8.2f}")
    if comparisons:
        lines.append("")
        lines.append(f"against {ref_label}:")
        lines.append(f"{'engine':<18}{'Δθmax/α':>9}{'horizon s':>11}{'parted':>8}{'|β err| median %':>18}"
                     f"{'Δuplift s':>11}{'overturn agree':>16}")
        for label, c in comparisons.items():
            beta = None if c.beta_error_median is None else 100 * c.beta_error_median
            lines.append(f"{label:<18}{c.theta_max_diff:>+9.3f}{c.horizon:>11.3f}{'yes' if c.parted else 'no':>8}"
                         f"{_fmt(beta):>18}{_fmt(c.first_uplift_diff, '{:+.3g}'):>11}"
                         f"{'yes' if c.overturn_agree else 'NO':>16}")
    return "\n".join(lines)


def run_engines(a, specs, system, motion, *, progress=None) -> int:
    """Several engines on one system and motion; exit 1 when any run failed."""
    from isorock.validate.core.compare import compare
    from isorock.validate.io.output import write_atomic, write_json
    from isorock.validate.io.provenance import provenance
    if a.plot:
        plot_format(a.plot)  # a bad --plot name fails before minutes of simulation
    loaded = load_engines(specs, a)
    runs, used = {}, {}
    for label, engine, settings in loaded:
        if not a.quiet and sys.stderr.isatty():
            print(f"\r{label} …", file=sys.stderr)
        runs[label] = engine.simulate(system, motion, settings=settings, duration=a.duration,
                                      overturn_rule=getattr(a, "overturn", None),
                                      theta0=a.theta0_over_alpha * system.alpha,
                                      impact_threshold=a.impact_threshold, progress=progress)
        used[label] = settings
    ref_label, ref = next(iter(runs.items()))
    comparisons = {label: compare(tr, ref) for label, tr in runs.items() if label != ref_label}
    if a.json:
        from isorock.validate.io.naming import describe_motion
        report = {
            "reference": ref_label,
            "system": system.describe(),
            "motion": dict(motion.describe(), description=describe_motion(motion)),
            "engines": {label: dict(tr.summary(), settings=_settings_dict(used[label]))
                        for label, tr in runs.items()},
            "comparisons": {label: c.as_dict() for label, c in comparisons.items()},
            "provenance": provenance(record_paths=[a.motion]),
        }
        write_json(a.json, report)
    written = []
    if a.csv:
        for label, tr in runs.items():
            path = _file_suffix(a.csv, label)
            hist = tr.resample(a.csv_dt) if a.csv_dt else tr
            write_atomic(path, hist.to_csv)
            written.append(str(path))
    if a.plot:
        write_plot(a.plot, runs, motion)
        written.append(str(a.plot))
    if not a.quiet:
        print(comparison_table(runs, comparisons))
        for path in written:
            print(f"wrote {path}")
    return 1 if any(tr.status.is_failure for tr in runs.values()) else 0
