"""The report's figures (PNG), drawn with matplotlib's object API on the Agg canvas so
no global pyplot state or display is involved.

    beta_slenderness   β and β₂/h against λ, closed form and engines (the paper's Figure 4)
    history            one motion on one base: ẍg, θ/α, engine − analytic, a zoom on the
                       rocking window, u or θ̇ with its difference
    beta_per_impact    effective β error of each engine per impact index, with tolerances
    ensemble           θmax/α against the PGA scale factor, and each engine − analytic
    turned_pair        a record pair: each engine's total tilt as given and turned with the statue,
                       their difference against its limit, and the planar model along each component
"""
from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ...analytic.coefficients import beta, beta2, beta_housner
from ...analytic.system import STANDARD_GRAVITY
from ..core import biaxial
from ..core.compare import COMPARE_DT
from ..core.engines import ALL_ENGINES, REFERENCE, engine_label

#: The reference is drawn black and solid; the other engines take these in registry order.
PALETTE = (("tab:blue", "--", "s"), ("tab:red", ":", "^"), ("tab:green", "-.", "v"), ("tab:purple", "--", "D"),
           ("tab:brown", ":", "P"))
MU_COLORS = {0.5: "tab:green", 1.0: "tab:blue", 1.5: "tab:orange", 2.0: "tab:purple"}
DPI = 110


#: A preset of an engine (ENGINE:PRESET) keeps the engine's colour and takes these.
PRESET_STYLES = ((":", "x"), ("-.", "+"), ((0, (1, 1)), "1"))


def style(engine: str) -> dict:
    """Line and marker style of an engine (or ENGINE:PRESET), the same in every figure."""
    name, _, preset = engine.partition(":")
    if name == REFERENCE and not preset:
        return dict(color="black", linestyle="-", marker="o", label=engine_label(name))
    others = [e for e in ALL_ENGINES if e != REFERENCE]
    i = others.index(name) if name in others else len(others)
    color, linestyle, marker = ("black", "-", "o") if name == REFERENCE else PALETTE[i % len(PALETTE)]
    label = engine_label(name)
    if preset:
        linestyle, marker = PRESET_STYLES[sum(map(ord, preset)) % len(PRESET_STYLES)]
        label = f"{label} ({preset})"
    return dict(color=color, linestyle=linestyle, marker=marker, label=label)


def _save(fig: Figure, path) -> None:
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=DPI)


def beta_slenderness(points, path, *, mass_ratios=(0.5, 1.0, 1.5, 2.0)) -> None:
    """Figure 4. `points`: dicts with engine, mass_ratio, slenderness, beta, beta2_over_h
    (effective values measured from free rocking)."""
    fig = Figure(figsize=(10, 4.2))
    ax_b, ax_b2 = fig.subplots(1, 2)
    lam = np.linspace(1.0, 10.0, 400)
    for mu in mass_ratios:
        c = MU_COLORS.get(mu, None)
        ax_b.plot(lam, [beta(x, mu) for x in lam], color=c, lw=1.2, label=f"μ = {mu:g}")
        ax_b2.plot(lam, [beta2(x, mu, 1.0) for x in lam], color=c, lw=1.2, label=f"μ = {mu:g}")
    ax_b.plot(lam, [beta_housner(x) for x in lam], color="gray", lw=1, ls="--", label="fixed base (Housner)")
    seen = set()
    for p in points:
        st = style(p["engine"])
        label = st["label"] if p["engine"] not in seen else None
        seen.add(p["engine"])
        kw = dict(marker=st["marker"], mfc="none", mec=MU_COLORS.get(p["mass_ratio"], "gray"), ms=8, ls="none")
        ax_b.plot(p["slenderness"], p["beta"], label=label, **kw)
        if p.get("beta2_over_h") is not None:
            ax_b2.plot(p["slenderness"], p["beta2_over_h"], **kw)
    ax_b.set(xlabel="slenderness λ = h/b", ylabel="β = θ̇⁺/θ̇⁻", xlim=(1, 10), ylim=(0, 1),
             title="Coefficient of restitution β")
    ax_b2.set(xlabel="slenderness λ = h/b", ylabel="β₂/h", xlim=(1, 10), ylim=(0, None),
              title="Base velocity jump β₂/h")
    ax_b.legend(fontsize=8, loc="lower right")
    ax_b2.legend(fontsize=8, loc="upper right")
    for ax in (ax_b, ax_b2):
        ax.grid(alpha=0.3)
    fig.suptitle("β and β₂/h against slenderness: closed form (lines), contact engines' effective values (markers)",
                 fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def _on_grid(tr, grid):
    """θ/α, u and θ̇ of a Trajectory on a common time grid (NaN past its end)."""
    r = tr.resample(COMPARE_DT)
    out = []
    for y in (r.theta / tr.alpha, r.u, r.theta_dot):
        out.append(np.interp(grid, r.t, y, right=np.nan))
    return out


def rocking_window(runs: dict, *, before: float = 0.2, length: float = 4.0):
    """(t0, t1): from a little before the first time any engine leaves |θ| ≤ 1% α, for
    at most `length` s while some engine still rocks; None when none rocked."""
    starts, ends = [], []
    for tr in runs.values():
        moving = np.flatnonzero(np.abs(tr.theta) > 0.01 * tr.alpha)
        if moving.size:
            starts.append(tr.t[moving[0]])
            ends.append(tr.t[moving[-1]])
    if not starts:
        return None
    t0 = max(0.0, min(starts) - before)
    return t0, min(max(ends) + before, t0 + length)


def history(motion, runs: dict, path, *, title: str, reference: str = REFERENCE) -> None:
    """One motion on one base, every engine: the ground acceleration, θ/α, each engine −
    the reference (θ/α), a zoom on the rocking window, and the base displacement with its
    difference (isolated base) or θ̇ with its difference (fixed base)."""
    fig = Figure(figsize=(11, 9.5))
    axes = fig.subplots(3, 2)
    t_end = max([tr.t[-1] for tr in runs.values()] + [1e-3])
    grid = np.arange(0.0, t_end + COMPARE_DT / 2, COMPARE_DT)
    fixed = next(iter(runs.values())).system.fixed_base if runs else True
    on_grid = {e: _on_grid(tr, grid) for e, tr in runs.items()}
    ref = on_grid.get(reference)
    ax = axes[0, 0]
    ax.plot(grid, motion(grid) / STANDARD_GRAVITY, color="gray", lw=0.8)
    ax.set(ylabel="ẍg / g", title="ground acceleration")
    for engine, (th, u, thd) in on_grid.items():
        st = style(engine)
        kw = dict(color=st["color"], ls=st["linestyle"], lw=1, label=st["label"])
        axes[0, 1].plot(grid, th, **kw)
        axes[2, 0].plot(grid, u * 100 if not fixed else thd, **kw)
        if ref is not None and engine != reference:
            axes[1, 0].plot(grid, th - ref[0], **kw)
            axes[2, 1].plot(grid, (u - ref[1]) * 1000 if not fixed else thd - ref[2], **kw)
    for y in (-1, 1):
        axes[0, 1].axhline(y, color="k", lw=0.5)
    axes[0, 1].set(ylabel="θ/α", title="rotation (±1: the critical angle α)")
    axes[1, 0].set(ylabel="Δθ/α", title=f"each engine − {style(reference)['label']}: rotation")
    window = rocking_window(runs)
    zoom = axes[1, 1]
    if window is None:
        zoom.text(0.5, 0.5, "no engine lifted the block", ha="center", va="center", transform=zoom.transAxes)
    else:
        for engine, (th, _, _) in on_grid.items():
            st = style(engine)
            keep = (grid >= window[0]) & (grid <= window[1])
            zoom.plot(grid[keep], th[keep], color=st["color"], ls=st["linestyle"], lw=1.2, label=st["label"])
        zoom.set_xlim(*window)
    zoom.set(ylabel="θ/α", title="zoom: the rocking window")
    if fixed:
        axes[2, 0].set(ylabel="θ̇ (rad/s)", title="angular velocity (fixed base: the base does not move)")
        axes[2, 1].set(ylabel="Δθ̇ (rad/s)", title=f"each engine − {style(reference)['label']}: angular velocity")
    else:
        axes[2, 0].set(ylabel="u (cm)", title="base displacement")
        axes[2, 1].set(ylabel="Δu (mm)", title=f"each engine − {style(reference)['label']}: base displacement")
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    for ax in axes[2]:
        ax.set_xlabel("t (s)")
    axes[0, 1].legend(fontsize=8, loc="upper right")
    if ref is not None and len(runs) > 1:
        axes[1, 0].legend(fontsize=8, loc="upper right")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    _save(fig, path)


def beta_per_impact(panels, path, *, bands: dict | None = None) -> None:
    """beta_per_impact_figure, written to `path`."""
    _save(beta_per_impact_figure(panels, bands=bands), path)


def beta_per_impact_figure(panels, *, bands: dict | None = None) -> Figure:
    """`panels`: (title, series) or (title, series, note) with series = (label, engine,
    list of β_eff/β − 1), one marker colour per engine and one fill per label; points are
    spread a little along x so that engines at the same impact index stay visible.
    `bands`: engine → its tolerance (a fraction), drawn as ± lines in the engine's colour
    on the panels that are judged; a panel with a `note` is not judged (the note says why,
    under its title, and no tolerance is drawn there: a point beyond one would read as a
    failure)."""
    panels = [p if len(p) == 3 else (*p, "") for p in panels] or [("", [], "")]
    fig = Figure(figsize=(6 * len(panels), 6))
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    fills = ["full", "none", "left", "bottom", "right", "top"]
    for ax, (title, series, note) in zip(axes, panels):
        labels = sorted({label for label, _, _ in series})
        engines = sorted({engine for _, engine, _ in series})
        for label, engine, errors in series:
            st = style(engine)
            e = np.asarray(errors, dtype=float) * 100
            x = np.arange(1, e.size + 1) + 0.08 * (engines.index(engine) - (len(engines) - 1) / 2)
            ax.plot(x, e, marker=st["marker"], color=st["color"], ls="none",
                    fillstyle=fills[labels.index(label) % len(fills)], label=f"{st['label']}, {label}")
        ax.axhline(0, color="k", lw=0.5)
        for engine, limit in ({} if note else bands or {}).items():
            if any(e == engine for _, e, _ in series):
                st = style(engine)
                for sign in (-1, 1):
                    ax.axhline(sign * limit * 100, color=st["color"], lw=1, ls="--", alpha=0.7,
                               label=f"{st['label']} tolerance ±{limit * 100:g}%" if sign > 0 else None)
        ax.set(xlabel="counted impact", ylabel="β_eff / β − 1 (%)")
        ax.set_title(title + (f"\n{textwrap.fill(note, 70)}" if note else ""), fontsize=10 if not note else 9)
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.grid(alpha=0.3)
        if series:  # below the axes: the points fill the whole panel
            ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=1)
    fig.suptitle("Effective β of every counted impact against the closed form, with each engine's tolerance",
                 fontsize=10)
    FigureCanvasAgg(fig)
    fig.tight_layout()
    return fig


def ensemble(ensembles, path, *, bands: dict | None = None, reference: str = REFERENCE) -> None:
    """Per Ensemble a column: θmax/α against the scale factor, one curve per engine
    (overturned drawn at 1 with a cross), and below it each engine − the reference, with
    `bands` (engine → tolerance of the median difference) as ± lines."""
    _save(ensemble_figure(ensembles, bands=bands, reference=reference), path)


def scale_axis_label(pga_g: float) -> str:
    """The ensembles' x axis: the factor multiplies the whole motion, whose own PGA is
    given at factor 1 (a label that put the factor beside the PGA read as a PGA in g)."""
    return f"scale factor of the motion (its PGA at 1: {pga_g:.2f} g)"


def ensemble_figure(ensembles, *, bands: dict | None = None, reference: str = REFERENCE) -> Figure:
    """The figure `ensemble` writes; titles wrapped to their panel's width (long record
    names ran into the neighbouring panel's title)."""
    n = max(1, len(ensembles))
    cols = min(n, 2)  # isolated and fixed side by side, one pair of rows per motion
    rows = -(-n // cols)
    # constrained: room for the figure's title above the wrapped panel titles (tight_layout leaves none)
    fig = Figure(figsize=(5.8 * cols, 6.2 * rows), layout="constrained")
    axes = np.atleast_2d(fig.subplots(2 * rows, cols, squeeze=False, gridspec_kw={"height_ratios": [2, 1] * rows}))
    for k in range(rows * cols):
        top, bottom = axes[2 * (k // cols), k % cols], axes[2 * (k // cols) + 1, k % cols]
        if k >= len(ensembles):
            top.set_visible(False)
            bottom.set_visible(False)
            continue
        ens = ensembles[k]
        capped = {e: np.where(ens.overturned[e], 1.0, np.minimum(t, 1.0)) for e, t in ens.theta_max.items()}
        for engine, y in capped.items():
            st = style(engine)
            over = ens.overturned[engine]
            top.plot(ens.scales, y, color=st["color"], ls=st["linestyle"], marker=st["marker"], ms=3, lw=1,
                     label=st["label"])
            top.plot(ens.scales[over], np.full(over.sum(), 1.0), "x", color=st["color"], ms=9)
            if engine != reference and reference in capped:
                bottom.plot(ens.scales, y - capped[reference], color=st["color"], ls=st["linestyle"],
                            marker=st["marker"], ms=3, lw=1, label=st["label"])
                limit = (bands or {}).get(engine)
                if limit is not None:
                    for sign in (-1, 1):
                        bottom.axhline(sign * limit, color=st["color"], lw=0.8, ls="--", alpha=0.7)
        top.axhline(1, color="k", lw=0.5)
        bottom.axhline(0, color="k", lw=0.5)
        base = "fixed base" if ens.system.fixed_base else "isolated base"
        top.set(ylabel="θmax/α (× = overturned)", ylim=(0, 1.1))
        top.set_title(textwrap.fill(f"{ens.motion}, {base}: {ens.rocking_count()} of {ens.scales.size} cases rock",
                                    60, break_long_words=True), fontsize=10)
        bottom.set(xlabel=scale_axis_label(ens.pga_g), ylabel=f"Δ θmax/α (vs {style(reference)['label']})")
        for ax in (top, bottom):
            ax.grid(alpha=0.3)
        top.legend(fontsize=8)
    fig.suptitle("Peak rotation over the motion scaled in amplitude: where engines part from the analytic model",
                 fontsize=10)
    FigureCanvasAgg(fig)
    return fig


def turned_pair(motion, runs: dict, planar: dict, limits: dict, least_alpha: float, path, *, title: str) -> None:
    """A record pair judged by turning it with the statue (core/turned_pair.py), every engine:
    the two ground components; each engine's total tilt over the statue's least α as given (solid)
    and turned (dashed), with the exact planar model along each component alone (grey, unjudged);
    the turned run's difference |Δ tilt| over the peak against the engine's limit (its row of the
    table, dashed), log scale, where the engines part; and the base's travel √(u² + u_y²), or on a
    fixed base the direction each leans. `runs`: label → TurnedRuns; `planar`: 'x'/'y' → Trajectory;
    `limits`: label → the history row's limit; `least_alpha`: the statue's least α (rad)."""
    fig = Figure(figsize=(11, 8))
    axes = fig.subplots(2, 2)
    t_end = max([r.first.t[-1] for r in runs.values()] + [1e-3])
    grid = np.linspace(0.0, t_end, 2000)
    ax = axes[0, 0]
    ax.plot(grid, motion(grid) / STANDARD_GRAVITY, color="tab:gray", lw=0.8, label="ẍg (along x)")
    ax.plot(grid, motion.transverse(grid) / STANDARD_GRAVITY, color="tab:olive", lw=0.8, label="ÿg (along y)")
    ax.set(ylabel="g", title="the two ground components")
    ax.legend(fontsize=8, loc="upper right")
    fixed = next(iter(runs.values())).first.system.fixed_base if runs else True
    for label, r in runs.items():
        st = style(label)
        tilts = []
        for tr, ls, which in ((r.first, "-", "as given"), (r.turned, "--", f"turned {r.turn_deg:g}°")):
            tilt, direction, _ = biaxial.tilt_twist(tr.extras["orientation"])
            tilts.append(tilt)
            axes[0, 1].plot(tr.t, tilt / least_alpha, color=st["color"], ls=ls, lw=1, label=f"{st['label']}, {which}")
            if fixed:
                axes[1, 1].plot(tr.t, np.degrees(direction) % 360, color=st["color"], ls="none", marker=".",
                                ms=1, label=f"{st['label']}, {which}")
            else:
                axes[1, 1].plot(tr.t, 100 * np.hypot(tr.u, tr.extras["u_y"]), color=st["color"], ls=ls, lw=1,
                                label=f"{st['label']}, {which}")
        n = min(t.size for t in tilts)
        diff = np.abs(tilts[0][:n] - tilts[1][:n]) / max(float(np.max(tilts[0][:n])), 1e-300)
        axes[1, 0].semilogy(r.first.t[:n], np.maximum(diff, 1e-16), color=st["color"], lw=1, label=st["label"])
        if label in limits:
            axes[1, 0].axhline(limits[label], color=st["color"], ls="--", lw=1,
                               label=f"{st['label']} limit {limits[label]:g}")
    for key, ls in (("x", "-"), ("y", ":")):
        tr = planar.get(key)
        if tr is not None:
            axes[0, 1].plot(tr.t, np.abs(tr.theta) / tr.system.alpha, color="0.45", ls=ls, lw=0.9,
                            label=f"exact planar, {key} alone (|θ|/α of its edge)")
    axes[0, 1].set(ylabel="total tilt / least α", title="total tilt: as given (solid) and turned (dashed)")
    axes[0, 1].legend(fontsize=7, loc="upper right")
    axes[1, 0].set(ylabel="|Δ tilt| / peak tilt", title="the turned run's difference, and each engine's limit")
    axes[1, 0].legend(fontsize=7, loc="lower right")
    if fixed:
        axes[1, 1].set(ylabel="lean direction (° from x)", title="where it leans (the turned run's: φ less)")
    else:
        axes[1, 1].set(ylabel="√(u² + u_y²) (cm)", title="the base's travel")
    for ax in axes.ravel():
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("t (s)")
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    _save(fig, path)
