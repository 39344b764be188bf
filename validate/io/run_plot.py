"""The figure of `isorock run --plot`: one system and motion, one or several engines
overlaid. Panels: the ground motion ẍg/g, θ/α with the counted impacts marked, θ̇, the
base displacement u; with several engines, the difference of each engine from the first
(the reference) in θ/α and u on a common time grid, where engines part is visible.
"""
from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from isorock.analytic.system import STANDARD_GRAVITY
from isorock.validate.core.compare import COMPARE_DT
from isorock.validate.io.figures import DPI, style
from isorock.validate.io.naming import describe_motion, describe_system


def _style(name: str, index: int) -> dict:
    """The engine's figure style; the same engine asked for twice (two presets) gets a
    thinner line the second time so both stay visible."""
    st = dict(style(name))
    st["lw"] = 1.2 if index == 0 else 1.0
    return st


def _name(label: str, traj) -> str:
    """The engine's display name, or the label when it names a preset ("mujoco:fast")."""
    return style(traj.engine)["label"] if label == traj.engine else label


def plot_runs(runs: dict, motion, path, *, format: str | None = None) -> None:
    """`runs`: label → Trajectory (first = reference), all on one system and motion;
    `format` the image format (default: from the path's suffix)."""
    labels = list(runs)
    several = len(labels) > 1
    ref = runs[labels[0]]
    show_du = several and not ref.system.fixed_base  # on a fixed base u ≡ 0 for every engine
    n_panels = 4 + several + show_du
    fig = Figure(figsize=(10, 2.0 * n_panels + 1.0))
    axes = fig.subplots(n_panels, 1, sharex=True)
    t_end = max(float(tr.t[-1]) for tr in runs.values() if tr.t.size)
    tg = np.linspace(0.0, t_end, max(2, int(t_end / 0.005) + 1))
    ax_g, ax_th, ax_thd, ax_u = axes[:4]
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
        ax_u.plot(tr.t, tr.u * 100, **kw)
        if several and i > 0:
            a, b = tr.resample(COMPARE_DT), ref.resample(COMPARE_DT)
            n = min(a.t.size, b.t.size)
            axes[4].plot(a.t[:n], (a.theta[:n] - b.theta[:n]) / ref.alpha, label=name, **kw)
            if show_du:
                axes[5].plot(a.t[:n], (a.u[:n] - b.u[:n]) * 100, **kw)
    for y in (1, -1):
        ax_th.axhline(y, color="k", lw=0.5)
    ax_th.set_ylabel("θ/α")
    ax_th.legend(fontsize=7, loc="upper right", ncol=2)
    ax_thd.set_ylabel("θ̇ (rad/s)")
    ax_u.set_ylabel("base u (cm)")
    if ref.system.fixed_base:
        ax_u.text(0.01, 0.85, "fixed base: u ≡ 0", transform=ax_u.transAxes, fontsize=8)
    if several:
        ref_name = _name(labels[0], ref)
        axes[4].set_ylabel(f"Δθ/α (− {ref_name})")
        axes[4].axhline(0, color="k", lw=0.5)
        axes[4].legend(fontsize=7, loc="upper right")
    if show_du:
        axes[5].set_ylabel(f"Δu (cm) (− {ref_name})")
        axes[5].axhline(0, color="k", lw=0.5)
    axes[-1].set_xlabel("t (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    engines = ", ".join(_name(k, runs[k]) for k in labels)
    what = "rocking response" if not several else "rocking response of each engine and its difference"
    fig.suptitle(f"{describe_motion(motion)}: {what} ({engines})\n{describe_system(ref.system)}", fontsize=10)
    fig.tight_layout()
    FigureCanvasAgg(fig)
    fig.savefig(path, dpi=DPI, format=format)
