"""The atlas's figures (PNG), drawn like the report's (validate.figures: matplotlib's object
API on the Agg canvas, each engine in its colour of every figure).

    error_map   one preset: signed β error (top row) and t₁ error (bottom row) of every
                cell, λ across and H up, one panel per mass ratio; cells that were not
                judged are grey with their status written in
    pareto      cost (wall s per simulated s) against worst β error over the grid, every
                preset of every engine, each engine's Pareto front joined
"""
from __future__ import annotations

import math

import matplotlib
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import SymLogNorm
from matplotlib.figure import Figure
from matplotlib.text import Text

from ..io.figures import _save, style

#: Both maps share one colour scale, in %, so that two presets' maps compare by eye: a
#: diverging map, white at 0, linear within ±LINEAR_PCT, saturating at ±SATURATE_PCT
#: (the number in the cell is the measured one).
LINEAR_PCT, SATURATE_PCT = 0.1, 10.0
#: Short words for the statuses of cells that were not judged, written in the grey cell.
SHORT = {"missing impacts": "missing", "too slow": "slow", "unmeasured": "unmeas."}


def error_map(rows: list[dict], grid, summary: dict, path) -> None:
    lams, heights = grid.slenderness, grid.heights
    # one panel per mass ratio, and per statue friction where the grid has that axis
    mus = [(mu, f) for f in grid.frictions for mu in grid.mass_ratios]
    fig = Figure(figsize=(2.0 + 2.3 * len(mus) + 0.4 * len(lams), 1.6 + 1.05 * len(heights) * 2))
    # laid out by hand: a layout engine costs as much as drawing the figure, once per preset
    fig.subplots_adjust(left=0.07, right=0.82, bottom=0.08, top=0.88, wspace=0.25, hspace=0.35)
    axes = np.atleast_2d(fig.subplots(2, len(mus), squeeze=False))
    norm = SymLogNorm(linthresh=LINEAR_PCT, vmin=-SATURATE_PCT, vmax=SATURATE_PCT, base=10)
    cmap = _cmap()
    by_cell = {(r["slenderness"], (r["mass_ratio"], r.get("friction")), r["height"]): r for r in rows}
    image = None
    for k, (metric, what) in enumerate((("beta_error", "β error"), ("t1_error", "t₁ error"))):
        for j, mu in enumerate(mus):
            ax = axes[k, j]
            values = np.full((len(heights), len(lams)), np.nan)
            for i, h in enumerate(heights):
                for n, lam in enumerate(lams):
                    r = by_cell.get((lam, mu, h))
                    v = None if r is None else r[metric]
                    if v is not None and math.isfinite(v):
                        values[i, n] = 100 * v
                    word = "—" if r is None else (f"{100 * v:+.2g}" if v is not None and math.isfinite(v) else
                                                   SHORT.get(r["status"], r["status"]) if r["status"] != "ok" else "—")
                    ax.text(n, i, word, ha="center", va="center", fontsize=7,
                            color="black" if v is None or abs(100 * v) < 3 else "white")
            image = ax.imshow(values, origin="lower", cmap=cmap, norm=norm, aspect="auto")
            ax.set_xticks(range(len(lams)), [f"{x:g}" for x in lams], fontsize=8)
            ax.set_yticks(range(len(heights)), [f"{x:g}" for x in heights], fontsize=8)
            base = ("fixed base" if mu[0] == 0 else f"μ = {mu[0]:g}") + ("" if mu[1] is None else f", μ_s {mu[1]:g}")
            ax.set_title(f"{what}, {base}", fontsize=9)
            if k == 1:
                ax.set_xlabel("λ = H/B", fontsize=8)
            if j == 0:
                ax.set_ylabel("H (m)", fontsize=8)
    bar = fig.colorbar(image, cax=fig.add_axes((0.85, 0.12, 0.018, 0.72)))
    bar.set_label("error, % (signed; saturates at ±10%)", fontsize=8)
    worst = summary["worst_beta_error"]
    fig.suptitle(f"{summary['engine']}: worst |β error| "
                 f"{'—' if worst is None else f'{100 * worst:.3g}%'} over {summary['judged']}/{summary['cells']} "
                 f"judged cells, {_speed(summary['sim_per_wall'])} sim s / wall s", fontsize=10)
    _save(fig, path)


def pareto(summaries: list[dict], path, levels) -> None:
    """Cost against worst β error; a preset that was not judged on every cell (failed,
    slid, overturned, missed impacts, too slow) is drawn in the band above the plot with
    an ×, never at a small error."""
    _save(pareto_figure(summaries, levels), path)


#: Where a point's label may go, tried in order (offsets in points, horizontal alignment):
#: beside it, above and below, then further out, so that presets that crowd (two at the
#: same cost and error: newton is the default) each keep a readable label.
LABEL_SPOTS = [(dx * r ** 0.5, dy, ha) for r in range(1, 9)
               for dx, dy, ha in ((4, 8 * r - 6, "left"), (4, -8 * r - 1, "left"), (-4, 8 * r - 6, "right"),
                                  (-4, -8 * r - 1, "right"), (0, 8 * r + 2, "center"), (0, -8 * r - 9, "center"))]


def _place_labels(fig, ax, items, taken) -> None:
    """Annotate each (text, x, y, colour, fontsize) at the first LABEL_SPOTS offset whose
    rendered box overlaps no box already taken (labels placed, legend, titles); the last
    spot where none is free."""
    renderer = fig.canvas.get_renderer()
    for text, x, y, color, size in items:
        for k, (dx, dy, ha) in enumerate(LABEL_SPOTS):
            # a label beyond the first ring is tied to its point by a thin line
            leader = dict(arrowprops=dict(arrowstyle="-", lw=0.5, color=color, alpha=0.6)) if k >= 6 else {}
            note = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy), ha=ha,
                               fontsize=size, color=color, **leader)
            note.update_positions(renderer)
            box = Text.get_window_extent(note, renderer).expanded(1.04, 1.1)  # the text, not its leader line
            inside = (ax.bbox.x0 <= box.x0 and box.x1 <= ax.bbox.x1 and ax.bbox.y0 <= box.y0 and box.y1 <= ax.bbox.y1)
            if inside and not any(box.overlaps(other) for other in taken):
                break
            note.remove()
        else:  # nowhere free: the first spot (a test of the figure would say so)
            dx, dy, ha = LABEL_SPOTS[0]
            note = ax.annotate(text, (x, y), textcoords="offset points", xytext=(dx, dy), ha=ha, fontsize=size,
                               color=color)
            box = Text.get_window_extent(note, renderer)
        taken.append(box)


def pareto_figure(summaries: list[dict], levels) -> Figure:
    """The figure `pareto` writes; labels placed where they overlap nothing (_place_labels)."""
    fig = Figure(figsize=(9.5, 6.0))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    judged = [s for s in summaries if s["complete"] and s["worst_beta_error"] is not None and s["sim_per_wall"]]
    errors = [100 * s["worst_beta_error"] for s in judged] + [100 * lv for lv in levels]
    low, high = min(errors) / 2, max(errors) * 2
    ceiling = high * 2  # the band of presets not judged on every cell, above the line at `high`
    costs = [1 / s["sim_per_wall"] for s in summaries if s["sim_per_wall"]] or [1.0]
    labels = []
    for name in dict.fromkeys(s["engine_name"] for s in summaries):
        st = style(name)
        mine = sorted((s for s in judged if s["engine_name"] == name), key=lambda s: 1 / s["sim_per_wall"])
        xs = [1 / s["sim_per_wall"] for s in mine]
        ys = [100 * s["worst_beta_error"] for s in mine]
        ax.scatter(xs, ys, color=st["color"], marker=st["marker"], s=36, zorder=3, label=st["label"])
        front, best = [], math.inf
        for x, y in zip(xs, ys):  # cheapest first: a preset is on the front when nothing cheaper is as accurate
            if y < best:
                front.append((x, y))
                best = y
        if front:
            fx, fy = zip(*front)
            ax.step(fx, fy, where="post", color=st["color"], lw=1.2, alpha=0.8)
        labels += [(s["preset"], x, y, st["color"], 7) for s, x, y in zip(mine, xs, ys)]
        failed = sorted((s for s in summaries if s["engine_name"] == name and s not in judged and s["sim_per_wall"]),
                        key=lambda s: s["sim_per_wall"])
        for k, s in enumerate(failed):  # in the band, at staggered heights so that their notes can be read
            x, y = 1 / s["sim_per_wall"], ceiling * 1.45 ** (k % 3)
            ax.scatter([x], [y], color=st["color"], marker="x", s=36, zorder=3)
            why = ", ".join(f"{k} {v}" for k, v in sorted(s["failures"].items()))
            labels.append((f"{s['preset']}: {why}", x, y, st["color"], 6))
    level_texts = []
    for level in levels:
        ax.axhline(100 * level, color="0.5", lw=0.8, ls="--")
        level_texts.append(ax.text(1.0, 100 * level, f" {100 * level:g}%", transform=ax.get_yaxis_transform(),
                                   va="center", fontsize=8, color="0.4"))
    ax.axhline(high, color="0.7", lw=0.6)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(low, ceiling * 4)
    ax.set_xlim(min(costs) / 2, max(costs) * 3)
    ax.set_xlabel("cost: wall s per simulated s (engine's stepping, summed over the grid)")
    ax.set_ylabel("worst |β error| over the grid, %")
    ax.set_title("Contact presets: cost against worst effective-β error (× above the line: not judged on every "
                 "cell)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    legend = ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.canvas.draw()  # the layout fixed: the boxes measured now are the ones saved
    renderer = fig.canvas.get_renderer()
    _place_labels(fig, ax, labels, [legend.get_window_extent(renderer),
                                    *(t.get_window_extent(renderer) for t in level_texts)])
    return fig


def _cmap():
    return matplotlib.colormaps["RdBu_r"].with_extremes(bad="0.82")


def _speed(x) -> str:
    return "—" if x is None else f"{x:.3g}"


__all__ = ["error_map", "pareto", "pareto_figure"]
