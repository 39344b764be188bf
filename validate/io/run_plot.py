"""The figure of `isorock run --plot`: one system and motion, one or several engines
overlaid. Panels: the ground motion ẍg/g, θ/α with the counted impacts marked (its axis
follows the data: rocking of 0.1α fills it, and ±α is drawn where the data come near), θ̇,
the base displacement u (not on a fixed base, where u ≡ 0); with several engines, the difference of each engine from the first
(the reference) in θ/α and u on a common time grid, where engines part is visible.
"""
from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ...analytic.system import STANDARD_GRAVITY
from ..core.compare import COMPARE_DT
from .figures import DPI, style
from .naming import describe_motion, describe_system


def _style(name: str, index: int) -> dict:
    """The engine's figure style; the same engine asked for twice (two presets) gets a
    thinner line the second time so both stay visible."""
    st = dict(style(name))
    st["lw"] = 1.2 if index == 0 else 1.0
    return st


def _name(label: str, traj) -> str:
    """The engine's display name, or the label when it names a preset ("mujoco:fast")."""
    return style(traj.engine)["label"] if label == traj.engine else label


#: θ/α axis: ±1 (α) is drawn, and the axis reaches it, once the data come within this
#: fraction of it; below, the axis follows the data (rocking of 0.1α would be a flat line
#: on a ±1 axis)
ALPHA_LINE_FROM = 0.5


def plot_runs(runs: dict, motion, path, *, format: str | None = None) -> None:
    """`runs`: label → Trajectory (first = reference), all on one system and motion;
    `format` the image format (default: from the path's suffix)."""
    fig = runs_figure(runs, motion)
    fig.savefig(path, dpi=DPI, format=format)


def runs_figure(runs: dict, motion) -> Figure:
    """The figure plot_runs writes."""
    labels = list(runs)
    several = len(labels) > 1
    ref = runs[labels[0]]
    has_u = not ref.system.fixed_base  # on a fixed base u ≡ 0 for every engine: no panel
    show_du = several and has_u
    n_panels = 3 + has_u + several + show_du
    fig = Figure(figsize=(10, 2.0 * n_panels + 1.0))
    axes = list(fig.subplots(n_panels, 1, sharex=True))
    t_end = max(float(tr.t[-1]) for tr in runs.values() if tr.t.size)
    tg = np.linspace(0.0, t_end, max(2, int(t_end / 0.005) + 1))
    ax_g, ax_th, ax_thd = axes[:3]
    ax_u = axes[3] if has_u else None
    diff = axes[3 + has_u:]
    ax_g.plot(tg, motion(tg) / STANDARD_GRAVITY, color="gray", lw=0.8)
    ax_g.set_ylabel("ẍg / g")
    for i, label in enumerate(labels):
        tr = runs[label]
        st = _style(tr.engine, i)
        kw = dict(color=st["color"], ls=st["linestyle"], lw=st["lw"])
        name = _name(label, tr)
        ax_th.plot(tr.t, tr.theta / tr.alpha, label=name, **kw)
        impacts = [imp.t for imp in tr.counted_impacts]
        if impacts:
            ax_th.plot(impacts, np.zeros(len(impacts)), ls="none", marker=st["marker"], ms=4, mfc="none",
                       mec=st["color"], label=f"{name}: {len(impacts)} counted impacts")
        ax_thd.plot(tr.t, tr.theta_dot, **kw)
        if has_u:
            ax_u.plot(tr.t, tr.u * 100, **kw)
        if several and i > 0:
            a, b = tr.resample(COMPARE_DT), ref.resample(COMPARE_DT)
            n = min(a.t.size, b.t.size)
            diff[0].plot(a.t[:n], (a.theta[:n] - b.theta[:n]) / ref.alpha, label=name, **kw)
            if show_du:
                diff[1].plot(a.t[:n], (a.u[:n] - b.u[:n]) * 100, **kw)
    peak = max((float(np.max(np.abs(tr.theta))) / tr.alpha for tr in runs.values() if tr.theta.size), default=0.0)
    if peak >= ALPHA_LINE_FROM:
        for y in (1, -1):
            ax_th.axhline(y, color="k", lw=0.5)
    elif peak == 0.0:
        ax_th.set_ylim(-1, 1)
        ax_th.text(0.01, 0.85, "no uplift: θ ≡ 0", transform=ax_th.transAxes, fontsize=8)
    else:
        ax_th.text(0.01, 0.85, f"peak {peak:.2g}α (±α off this scale)", transform=ax_th.transAxes, fontsize=8)
    ax_th.set_ylabel("θ/α")
    ax_th.legend(fontsize=7, loc="upper right", ncol=2)
    ax_thd.set_ylabel("θ̇ (rad/s)")
    if has_u:
        ax_u.set_ylabel("base u (cm)")
    if several:
        ref_name = _name(labels[0], ref)
        diff[0].set_ylabel(f"Δθ/α\n(− {ref_name})")
        diff[0].axhline(0, color="k", lw=0.5)
        diff[0].legend(fontsize=7, loc="upper right")
    if show_du:
        diff[1].set_ylabel(f"Δu (cm)\n(− {ref_name})")
        diff[1].axhline(0, color="k", lw=0.5)
    axes[-1].set_xlabel("t (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    engines = ", ".join(_name(k, runs[k]) for k in labels)
    what = "rocking response" if not several else "rocking response of each engine and its difference"
    title = textwrap.fill(f"{describe_motion(motion, shown=t_end)}: {what} ({engines})", 110)
    fig.suptitle(f"{title}\n{textwrap.fill(describe_system(ref.system), 110)}", fontsize=10)
    FigureCanvasAgg(fig)
    fig.tight_layout()
    return fig
