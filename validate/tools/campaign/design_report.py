"""What `isorock design` writes: the chart (design.png), the answer in words and tables
(design.md, verdict first), every number (design.json, design.csv) and every run
(runs.parquet, the executor's summary rows)."""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from ...io.output import to_json
from ...io.provenance import provenance
from .design import ANSWERED, Design, _pct, hazard_text, target_judgement, verdict

#: P(overturn) bands of the chart's colours: the decisions an engineer makes sit at 1–10 %
P_BANDS = (0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0)


def chart(d: Design, target: float, max_stroke: float | None, path) -> None:
    """Left: P(overturn) over the hazard on the family's two axes (filled contours),
    the 84th-percentile stroke at the highest level as labelled contour lines, the
    recommended region outlined and hatched, the named isolator starred, the fixed base's
    P in the title. Right (several levels): P(overturn) against PGA for the fixed base,
    the named isolator and the grid's corners."""
    import matplotlib as mpl  # lazy: matplotlib, for the chart only
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import BoundaryNorm
    from matplotlib.figure import Figure

    fam, h = d.family, d.hazard
    x, y = np.asarray(fam.x_values), np.asarray(fam.y_values)
    p = d.grid(d.p_hazard())
    stroke = d.grid(d.stroke(0.84)[:, -1])
    ok = d.recommended(target, max_stroke)
    iy, ix = d.best(target, max_stroke)
    levels = len(h.levels) > 1
    fig = Figure(figsize=(12.5 if levels else 7.0, 5.4), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2, width_ratios=(1.35, 1)) if levels else [fig.subplots(1, 1)]
    ax = axes[0]
    cmap = mpl.colormaps["RdYlGn_r"]
    norm = BoundaryNorm(P_BANDS, cmap.N)
    contours = x.size > 1 and y.size > 1
    if contours:
        filled = ax.contourf(x, y, np.clip(p, 0, 1), levels=P_BANDS, cmap=cmap, norm=norm, extend="neither")
        if np.nanmax(stroke) > np.nanmin(stroke):
            lines = ax.contour(x, y, stroke, levels=_nice_levels(stroke), colors="k", linewidths=0.8)
            ax.clabel(lines, fmt=lambda v: f"{v:.2g} m", fontsize=7)
        if ok.any() and not ok.all():
            with mpl.rc_context({"hatch.color": "tab:blue", "hatch.linewidth": 0.6}):
                ax.contourf(x, y, ok.astype(float), levels=[0.5, 1.5], colors="none", hatches=["/"])
            ax.contour(x, y, ok.astype(float), levels=[0.5], colors="tab:blue", linewidths=2.2)
        ax.plot(x[None, :].repeat(y.size, 0), y[:, None].repeat(x.size, 1), ".", color="0.35", ms=1.2)
    else:  # one row or one column: cells, not contours
        filled = ax.pcolormesh(_edges(x), _edges(y), p, cmap=cmap, norm=norm)
        for (j, i) in zip(*np.nonzero(ok)):
            ax.text(x[i], y[j], "✓", ha="center", va="center", color="tab:blue")
    ax.plot(x[ix], y[iy], marker="*", ms=16, color="tab:blue", mec="white", mew=1.2, ls="none",
            label="named isolator", clip_on=False, zorder=5)
    cbar = fig.colorbar(filled, ax=ax, ticks=P_BANDS)
    cbar.set_label("P(overturn) over the hazard")
    cbar.ax.set_yticklabels([f"{100 * v:g}%" for v in P_BANDS])
    ax.set_xlabel(fam.x_label)
    ax.set_ylabel(fam.y_label)
    shape = (f"{d.statue.name or 'statue'} (α₊ {d.statue.body.alpha(1):.3g}, α₋ {d.statue.body.alpha(-1):.3g} rad)"
             if d.statue.body is not None else f"{d.statue.height:g} × {d.statue.width:g} m statue")
    ax.set_title(f"{shape}, μ = {d.statue.mass / d.statue.base_mass:.3g}: "
                 f"fixed base P = {_pct(d.p_hazard()[0])}\nblue: recommended (P ≤ {_pct(target)}"
                 + (f", stroke ≤ {max_stroke:g} m" if max_stroke is not None else "")
                 + f"); lines: 84th-pct stroke at {h.levels[-1]:g} g", fontsize=9)
    ax.legend(loc="lower right", fontsize=8)
    if levels:
        ax2 = axes[1]
        pl = d.p_level()
        lv = np.asarray(h.levels)
        ax2.plot(lv, pl[0], "k-o", lw=2.2, label="fixed base")
        corners = {(0, 0), (0, x.size - 1), (y.size - 1, 0), (y.size - 1, x.size - 1)} - {(iy, ix)}
        for n, (j, i) in enumerate(sorted(corners)):
            k = 1 + j * x.size + i
            ax2.plot(lv, pl[k], "--", color=f"C{n + 1}", lw=1.0,
                     label=f"{fam.x_values[i]:.3g} {fam.x_unit}, {fam.y_values[j]:.3g}".replace(" ,", ","))
        k = 1 + iy * x.size + ix
        ax2.plot(lv, pl[k], "-*", color="tab:blue", lw=2.2, ms=10,
                 label=f"named: {fam.x_values[ix]:.3g} {fam.x_unit}, {fam.y_values[iy]:.3g}".replace(" ,", ","))
        ax2.set_xlabel("PGA (g)")
        ax2.set_ylabel("P(overturn): fraction of records")
        ax2.set_ylim(-0.02, 1.02)
        ax2.set_title(f"per level ({len(h.records)} records; isolators as {fam.x_name.replace('_', ' ')}, "
                      f"{fam.y_name.replace('_', ' ')})", fontsize=9)
        ax2.legend(fontsize=7, loc="upper left")
        ax2.grid(alpha=0.3)
    fig.savefig(path, dpi=110)


def _nice_levels(v) -> list[float]:
    lo, hi = float(np.nanmin(v)), float(np.nanmax(v))
    step = 10 ** math.floor(math.log10((hi - lo) / 6)) if hi > lo else 1.0
    for m in (1, 2, 2.5, 5, 10):
        if (hi - lo) / (m * step) <= 8:
            step *= m
            break
    return [float(t) for t in np.arange(math.ceil(lo / step) * step, hi, step)] or [lo]


def _edges(v):
    v = np.asarray(v, dtype=float)
    if v.size == 1:
        return np.array([v[0] * 0.9, v[0] * 1.1])
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


def isolator_rows(d: Design, target: float, max_stroke: float | None) -> list[dict]:
    """One row per isolator (y outer, x inner), the fixed base first."""
    fam, h = d.family, d.hazard
    p_h, p_l = d.p_hazard(), d.p_level()
    p_ci, n_rec, locked = d.p_interval(), d.records_answered(), d.locked()
    s50, s84 = d.stroke(0.5), d.stroke(0.84)
    ok = np.concatenate([[False], d.recommended(target, max_stroke).ravel()])
    rows = []
    for k in range(p_h.size):
        if k == 0:
            x = y = math.nan
        else:
            iy, ix = divmod(k - 1, len(fam.x_values))
            x, y = fam.x_values[ix], fam.y_values[iy]
        rows.append({"base": "fixed" if k == 0 else "isolated", fam.x_name: x, fam.y_name: y,
                     "p_hazard": float(p_h[k]), "p_hazard_interval": [float(v) for v in p_ci[k]],
                     "records": int(n_rec[k]), "target": target_judgement(p_h[k], *p_ci[k], target),
                     "p_levels": [float(v) for v in p_l[k]],
                     "stroke_median": [float(v) for v in s50[k]], "stroke_84": [float(v) for v in s84[k]],
                     "recommended": bool(ok[k]), "locked": bool(locked[k])})
    return rows


def _grid_table(d: Design, values, fmt) -> str:
    fam = d.family
    head = f"| {fam.y_name} \\ {fam.x_name} | " + " | ".join(f"{x:.3g}" for x in fam.x_values) + " |"
    sep = "|---|" + "---:|" * len(fam.x_values)
    body = [f"| {y:.3g} | " + " | ".join(fmt(values[iy, ix]) for ix in range(len(fam.x_values))) + " |"
            for iy, y in enumerate(fam.y_values)]
    return "\n".join([head, sep, *body])


def markdown(d: Design, target: float, max_stroke: float | None, v: dict) -> str:
    fam, h = d.family, d.hazard
    n_runs = d.overturned.size
    lines = ["# Which isolator keeps the statue standing?", "", f"**{v['headline']}**", ""]
    for c in d.checks or ():  # each contact engine's agreement is part of the answer
        lines += [f"Checked: {c['text']} (details below).", ""]
    lines += ["![design chart](design.png)", "",
             f"- statue: {d.statue.label}",
             f"- hazard: {hazard_text(h)}",
             f"- isolators: {fam.kind}, {fam.x_name.replace('_', ' ')} "
             f"{fam.x_values[0]:.3g}–{fam.x_values[-1]:.3g} {fam.x_unit} ({len(fam.x_values)}) × "
             f"{fam.y_name.replace('_', ' ')} {fam.y_values[0]:.3g}–{fam.y_values[-1]:.3g} ({len(fam.y_values)})",
             f"- rule: recommended when {v['rule']}; overturned as model.md says (|θ| reaches π/2, or past α "
             "when the run ends)",
             f"- runs: {n_runs:,} with the analytic model (compiled kernel) in {d.wall_s:.0f} s wall"
             + (f"; {d.failed} failed or stopped at their event limit, left out of every fraction" if d.failed
                else "; none failed"),
             f"- not monotone in the level: {d.non_monotone()} (system, record) pairs survive a level above "
             "one that overturned them (every level is run; nothing is inferred from another)", ""]
    for c in d.checks or ():
        lines += [f"## Checked by {c['engine']}", "", c["text"] + ".", "",
                  f"| system | record | PGA (g) | analytic overturned | {c['engine']} overturned | analytic u_max (m) "
                  f"| {c['engine']} u_max (m) | Δ stroke |", "|---|---|---:|---|---|---:|---:|---:|"]
        for r in c["runs"]:
            rel, status = r["u_max_rel_diff"], r[c["engine"] + "_status"]
            last = status if status not in ANSWERED else "" if not math.isfinite(rel) else f"{100 * rel:.2g}%"
            lines.append(f"| {r['system']} | {r['record']} | {r['pga']:g} | {r['analytic_overturned']} | "
                         f"{r[c['engine'] + '_overturned']} | {r['analytic_u_max']:.4g} | "
                         f"{r[c['engine'] + '_u_max']:.4g} | {last} |")
        lines.append("")
    if v["region_edges"]:
        lines += ["## The recommended region, row by row", "",
                  f"| {fam.y_name} | {fam.x_name} from | to |", "|---:|---:|---:|"]
        lines += [f"| {e[fam.y_name]:.3g} | {e[fam.x_name + '_from']:.3g} | {e[fam.x_name + '_to']:.3g} |"
                  for e in v["region_edges"]]
        lines.append("")
    p = d.grid(d.p_hazard())
    s84 = d.grid(d.stroke(0.84)[:, -1])
    lines += ["## P(overturn) over the hazard", "", _grid_table(d, p, lambda x: _pct(x)), "",
              f"Each P is a fraction of {int(d.records_answered().min())}–{int(d.records_answered().max())} records; "
              f"its {100 * v['confidence']:g}% interval (Clopper–Pearson) is in design.json and design.csv. With none "
              f"overturning, {v['records_needed']} records are needed to show P ≤ {_pct(target)} at that confidence.",
              "",
              f"## Stroke: 84th percentile of the peak base displacement at {h.levels[-1]:g} g (m)", "",
              _grid_table(d, s84, lambda x: f"{x:.3g}"), "",
              "## Fixed base, per level", "", "| PGA (g) | P(overturn) |", "|---:|---:|"]
    lines += [f"| {lv:g} | {_pct(pv)} |" for lv, pv in zip(h.levels, d.p_level()[0])]
    fb, named = v["fixed_base"]["fragility_median_pga"], v["best"]["fragility_median_pga"]
    lines += ["", f"PGA at which half the records overturn the block (lognormal fit): fixed base "
              f"{_median_words(fb, h.levels)}, the named isolator {_median_words(named, h.levels)}.", "",
              "design.json holds every isolator's P per level and its stroke (median and 84th percentile) per level; "
              "runs.parquet every run.", ""]
    return "\n".join(lines)


def _median_words(m: float, levels) -> str:
    if not math.isfinite(m):
        return "not bounded by the runs (none or all overturned)"
    beyond = " (beyond the levels run: an extrapolation)" if not levels[0] <= m <= levels[-1] else ""
    return f"{m:.3g} g{beyond}"


def csv_text(rows: list[dict], fam, levels) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    top = levels[-1]
    w.writerow(["base", fam.x_name, fam.y_name, "p_hazard", f"p_at_{top:g}g", f"stroke_median_at_{top:g}g_m",
                f"stroke_84_at_{top:g}g_m", "recommended", "p_hazard_low", "p_hazard_high", "records", "target",
                "locked"])
    for r in rows:
        lo, hi = r["p_hazard_interval"]
        w.writerow([r["base"], r[fam.x_name], r[fam.y_name], f"{r['p_hazard']:.6g}", f"{r['p_levels'][-1]:.6g}",
                    f"{r['stroke_median'][-1]:.6g}", f"{r['stroke_84'][-1]:.6g}", r["recommended"], f"{lo:.6g}",
                    f"{hi:.6g}", r["records"], r["target"], r["locked"]])
    return buf.getvalue()


def write_design(d: Design, target: float, max_stroke: float | None, folder: Path, record_paths=()) -> dict:
    """Fill `folder` (a staging folder of validate.io.output): every output of a design."""
    import pyarrow.parquet as pq  # lazy: pyarrow, for the written table only

    v = verdict(d, target, max_stroke)
    rows = isolator_rows(d, target, max_stroke)
    fam, h = d.family, d.hazard
    chart(d, target, max_stroke, folder / "design.png")
    (folder / "design.md").write_text(markdown(d, target, max_stroke, v), encoding="utf-8")
    (folder / "design.csv").write_text(csv_text(rows, fam, h.levels), encoding="utf-8")
    doc = {"verdict": v["headline"], "answer": v,
           "statue": {"height": d.statue.height, "width": d.statue.width, "mass": d.statue.mass,
                      "base_mass": d.statue.base_mass,
                      # the statue that may slip, as designed for (without them the file read as one that cannot)
                      **({} if d.statue.friction is None else {"friction": d.statue.friction}),
                      **({} if d.statue.plinth_margin is None else {"plinth_margin": d.statue.plinth_margin}),
                      # a statue's mesh: its two edges along the direction designed for
                      **({} if d.statue.body is None else {"name": d.statue.name, "body": d.statue.body.describe()})},
           "hazard": {"records": h.names, "source": h.source, "pga_levels": list(h.levels),
                      "level_weights": list(h.weights)},
           "family": {"isolator": fam.kind, "x": fam.x_name, "x_values": list(fam.x_values), "y": fam.y_name,
                      "y_values": list(fam.y_values)},
           "rule": {"target": target, "max_stroke": max_stroke, "overturn_rule": "past-alpha"},
           "runs": int(d.overturned.size), "failed": d.failed, "non_monotone": d.non_monotone(),
           # `check`: the first engine's (the field as it was with one); `checks`: each engine's
           "wall_s": d.wall_s, "isolators": rows, "check": d.check, "checks": d.checks or [],
           "provenance": provenance(record_paths)}
    (folder / "design.json").write_text(to_json(doc) + "\n", encoding="utf-8")
    if d.table is not None:
        pq.write_table(d.table, folder / "runs.parquet")
    return v
