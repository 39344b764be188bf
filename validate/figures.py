"""The report's figures (PNG), drawn with matplotlib's object API on the Agg canvas so
no global pyplot state or display is involved.

    beta_slenderness   the paper's Figure 4: β and β₂/h against λ, closed form and engines
    histories          the paper's Figure 5: ẍg, θ/α isolated and fixed, u, θ̇, engines overlaid
    beta_per_impact    effective β error of each engine per impact index
    ensemble           θmax/α against the PGA scale factor, one curve per engine
"""
from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from isorock.analytic.coefficients import beta, beta2, beta_housner
from isorock.analytic.system import STANDARD_GRAVITY
from isorock.validate.engines import ALL_ENGINES, REFERENCE, engine_label

#: The reference is drawn black and solid; the other engines take these in registry order.
PALETTE = (("tab:blue", "--", "s"), ("tab:red", ":", "^"), ("tab:green", "-.", "v"), ("tab:purple", "--", "D"),
           ("tab:brown", ":", "P"))
MU_COLORS = {0.5: "tab:green", 1.0: "tab:blue", 1.5: "tab:orange", 2.0: "tab:purple"}
DPI = 110


def style(engine: str) -> dict:
    """Line and marker style of an engine, the same in every figure."""
    if engine == REFERENCE:
        return dict(color="black", linestyle="-", marker="o", label=engine_label(engine))
    others = [e for e in ALL_ENGINES if e != REFERENCE]
    i = others.index(engine) if engine in others else len(others)
    color, linestyle, marker = PALETTE[i % len(PALETTE)]
    return dict(color=color, linestyle=linestyle, marker=marker, label=engine_label(engine))


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
    fig.suptitle("Figure 4: closed form (lines) and effective values of the contact engines (markers)", fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def histories(motion, isolated: dict, fixed: dict, path, *, title: str = "") -> None:
    """Figure 5. `isolated`, `fixed`: engine → Trajectory on the same motion."""
    fig = Figure(figsize=(10, 11))
    axes = fig.subplots(5, 1, sharex=True)
    t_end = max([tr.t[-1] for tr in (*isolated.values(), *fixed.values())] + [0.0])
    tg = np.linspace(0.0, t_end, max(2, int(t_end / 0.005) + 1))
    axes[0].plot(tg, motion(tg) / STANDARD_GRAVITY, color="gray", lw=0.8)
    axes[0].set_ylabel("ẍg / g")
    for ax, runs, name in ((axes[1], isolated, "isolated base"), (axes[2], fixed, "fixed base")):
        for engine, tr in runs.items():
            st = style(engine)
            ax.plot(tr.t, tr.theta / tr.alpha, color=st["color"], ls=st["linestyle"], lw=1, label=st["label"])
        ax.axhline(1, color="k", lw=0.5)
        ax.axhline(-1, color="k", lw=0.5)
        ax.set_ylabel(f"θ/α, {name}")
        ax.set_ylim(-1.1, 1.1)
        ax.legend(fontsize=8, loc="upper right")
    for engine, tr in isolated.items():
        st = style(engine)
        axes[3].plot(tr.t, tr.u * 100, color=st["color"], ls=st["linestyle"], lw=1, label=st["label"])
        axes[4].plot(tr.t, tr.theta_dot, color=st["color"], ls=st["linestyle"], lw=1, label=st["label"])
    axes[3].set_ylabel("base u (cm), isolated")
    axes[4].set_ylabel("θ̇ (rad/s), isolated")
    axes[4].set_xlabel("t (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(title or f"Figure 5: {motion.name}", fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def beta_per_impact(panels, path) -> None:
    """`panels`: (title, series) with series = (label, engine, list of β_eff/β − 1), one
    marker colour per engine and one fill per label; points are spread a little along x
    so that engines at the same impact index stay visible."""
    panels = list(panels) or [("", [])]
    fig = Figure(figsize=(6 * len(panels), 6))
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    fills = ["full", "none", "left", "bottom", "right", "top"]
    for ax, (title, series) in zip(axes, panels):
        labels = sorted({label for label, _, _ in series})
        engines = sorted({engine for _, engine, _ in series})
        for label, engine, errors in series:
            st = style(engine)
            e = np.asarray(errors, dtype=float) * 100
            x = np.arange(1, e.size + 1) + 0.08 * (engines.index(engine) - (len(engines) - 1) / 2)
            ax.plot(x, e, marker=st["marker"], color=st["color"], ls="none",
                    fillstyle=fills[labels.index(label) % len(fills)], label=f"{st['label']}, {label}")
        ax.axhline(0, color="k", lw=0.5)
        ax.set(xlabel="counted impact", ylabel="β_eff / β − 1 (%)", title=title)
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.grid(alpha=0.3)
        if series:  # below the axes: the points fill the whole panel
            ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=1)
    fig.suptitle("Effective β per impact against the closed form", fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def ensemble(ensembles, path) -> None:
    """θmax/α against the scale factor, one panel per Ensemble, one curve per engine;
    overturned cases are drawn at 1 with a cross."""
    n = max(1, len(ensembles))
    cols = min(n, 2)  # isolated and fixed side by side, one row per motion
    rows = -(-n // cols)
    fig = Figure(figsize=(5.5 * cols, 4 * rows))
    axes = np.atleast_1d(fig.subplots(rows, cols, squeeze=False)).ravel()
    for ax in axes[n:]:
        ax.set_visible(False)
    for ax, ens in zip(axes, ensembles):
        for engine, tmax in ens.theta_max.items():
            st = style(engine)
            over = ens.overturned[engine]
            y = np.where(over, 1.0, np.minimum(tmax, 1.0))
            ax.plot(ens.scales, y, color=st["color"], ls=st["linestyle"], marker=st["marker"], ms=3,
                    lw=1, label=st["label"])
            ax.plot(ens.scales[over], np.full(over.sum(), 1.0), "x", color=st["color"], ms=9)
        ax.axhline(1, color="k", lw=0.5)
        base = "fixed base" if ens.system.fixed_base else "isolated base"
        ax.set(xlabel=f"scale factor × PGA ({ens.pga_g:.2f} g)", ylabel="θmax/α (× = overturned)",
               ylim=(0, 1.1), title=f"{ens.motion}, {base}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, path)
