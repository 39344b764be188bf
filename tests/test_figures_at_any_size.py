"""Figures that read at any size (issue 25): each figure drawn with many panels and long
names; its size stays within a screen's reach in both directions and no two of its texts
overlap (tests/figure_checks.py measures the rendered text boxes)."""
from __future__ import annotations

import numpy as np
import pytest

from figure_checks import overlapping_texts, size_px, texts_outside

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

#: the largest side a figure may have at its dpi (a 4K screen's width, and a bit)
MAX_SIDE_PX = 4200


def _check(fig, dpi):
    w, h = size_px(fig, dpi)
    try:
        assert max(w, h) <= MAX_SIDE_PX and max(w, h) / min(w, h) <= 5, (w, h)  # one row of 16 was 20:1
        assert not overlapping_texts(fig), overlapping_texts(fig)[:5]
        assert not texts_outside(fig), texts_outside(fig)[:5]
    finally:
        plt.close(fig)
    return w, h


def _fits(n_systems: int, pairs: list[tuple[str, str]]):
    from isorock.validate.core.fragility import fit_fragility
    rng = np.random.default_rng(1)
    levels = np.linspace(0.1, 1.5, 15)
    out = []
    for i in range(n_systems):
        system = (f"isolated T {1 + 0.1 * i:g} s, ξ 0.2, μ {0.25 * (i + 1):g}, H {2 + i:g} m, B 0.7 m"
                  if i % 2 else f"fixed base, H {2 + i:g} m, B 0.7 m")
        for engine, setting in pairs:
            o = (rng.random((44, levels.size)) < 1 / (1 + np.exp(-(levels - 0.6) * 8))).astype(float)
            out.append({"system": system, "engine": engine, "setting": setting, "scale_by": "pga",
                        "levels": levels, "fraction": o.mean(axis=0), "records": 44,
                        "fit": fit_fragility(levels, o, bootstrap=0)})
    return out


@pytest.mark.parametrize("n_systems", [1, 3, 16])
def test_fragility_lays_out_many_systems_as_a_grid(n_systems):
    from isorock.validate.tools.campaign.products import FRAGILITY_COLUMNS, fragility_plot
    pairs = [("analytic", "default"), ("mujoco", "preset=fast,timestep=0.002"), ("bullet", "default")]
    fig = fragility_plot(_fits(n_systems, pairs))
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == n_systems
    rows = {round(ax.get_position().y0, 3) for ax in visible}
    assert len(rows) == -(-n_systems // FRAGILITY_COLUMNS)  # ⌈n / columns⌉ rows
    w, h = _check(fig, 130)
    if n_systems == 16:
        assert w < 3000 and h < 3000  # it was 10,816 × 546 px in one row


# --- isorock run --plot ----------------------------------------------------------------------

PAPER = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)


def _theta_axis(fig):
    return next(ax for ax in fig.axes if ax.get_ylabel() == "θ/α")


def test_run_plot_theta_axis_follows_small_rocking_and_a_fixed_base_has_no_u_panel():
    """Free rocking from 0.1α (the oracle: the initial tilt is the peak, energy only being
    lost): the θ/α axis spans about ±0.1, not ±1; on a fixed base no panel of u ≡ 0."""
    import isorock
    from isorock.validate.io.run_plot import runs_figure
    from isorock.analytic.motion import GroundMotion
    tr = isorock.run(engine="analytic", fixed_base=True, height=2.0, width=0.7, mass=3800.0, base_mass=3800.0,
                     theta0_over_alpha=0.1, duration=3.0)
    fig = runs_figure({"analytic": tr}, GroundMotion.zero())
    lo, hi = _theta_axis(fig).get_ylim()
    assert 0.1 <= hi < 0.2 and -0.2 < lo < -0.05, (lo, hi)  # after an impact the swing is β times smaller
    assert "base u (cm)" not in [ax.get_ylabel() for ax in fig.axes]
    _check(fig, 100)


def test_run_plot_draws_alpha_where_the_block_comes_near_it():
    import isorock
    from isorock.validate.io.run_plot import runs_figure
    from isorock.analytic.motion import GroundMotion
    tr = isorock.run(engine="analytic", theta0_over_alpha=0.8, duration=2.0, **PAPER)
    fig = runs_figure({"analytic": tr}, GroundMotion.zero())
    lo, hi = _theta_axis(fig).get_ylim()
    assert hi >= 1 and lo <= -1
    assert "base u (cm)" in [ax.get_ylabel() for ax in fig.axes]
    plt.close(fig)


def test_run_plot_with_many_engines_and_long_names_keeps_its_texts_apart():
    import isorock
    from isorock.analytic.motion import load_motion
    from isorock.validate.io.run_plot import runs_figure
    motion = "sine:amp=0.6,freq=1.3,cycles=2"
    runs = isorock.run(engine="analytic,analytic:conservative,analytic-reference,mujoco:fast,bullet:fast",
                       motion=motion, duration=4.0, **PAPER)
    fig = runs_figure(runs, load_motion(motion))
    assert len(fig.axes) == 6
    _check(fig, 100)


# --- the validation report's ensembles ---------------------------------------------------------

def _ensemble(motion: str, fixed: bool):
    from types import SimpleNamespace
    scales = np.linspace(0.4, 1.6, 21)
    rng = np.random.default_rng(2)
    ref = np.clip(scales - 0.3, 0, None)
    theta = {"analytic": ref, "mujoco": ref + rng.normal(0, 0.01, ref.size), "bullet": ref + rng.normal(0, 0.01, ref.size)}
    system = SimpleNamespace(fixed_base=fixed)
    return SimpleNamespace(system=system, motion=motion, pga_g=0.28, scales=scales, theta_max=theta,
                           overturned={k: v > 1 for k, v in theta.items()},
                           rocking_count=lambda: int(np.sum(ref > 0.01)))


def test_the_ensemble_figure_keeps_long_record_names_apart_and_says_what_the_scale_is():
    from isorock.validate.io.figures import ensemble_figure, scale_axis_label
    names = ["RSN1106_KOBE_KJM000.AT2 (Kobe 1995, KJMA, first 40 s)",
             "RSN6_IMPVALL.I_I-ELC180_with_a_very_long_processing_suffix.AT2",
             "RSN766_LOMAP_G02000.AT2 scaled to 0.5 g", "KOBE_NS"]
    ensembles = [_ensemble(n, fixed) for n in names for fixed in (False, True)]
    fig = ensemble_figure(ensembles, bands={"mujoco": 0.05, "bullet": 0.05})
    label = scale_axis_label(0.28)
    assert "× PGA" not in label and "0.28 g" in label and "scale factor" in label
    assert label in [ax.get_xlabel() for ax in fig.axes]
    _check(fig, 130)


# --- campaign agreement maps ---------------------------------------------------------------------

def _map(engine: str, setting: str):
    xs, ys = np.array([1.0, 2.0, 3.0, 4.0]), np.array([0.5, 1.0, 2.0])
    verdict = np.array([[0.0, 0.0, 0.2, np.nan], [0.0, 0.5, np.nan, 1.0], [0.0, 0.1, 0.3, 0.0]])
    return {"engine": engine, "setting": setting, "x": "frequency_ratio", "y": "amplitude_ratio", "xs": xs, "ys": ys,
            "verdict": verdict, "theta": verdict[::-1].copy(), "tolerance": 0.02}


def _cell_rgb(fig, ax, x, y):
    """The rendered colour at data point (x, y) of the axes (the oracle: pixels)."""
    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(float)
    px, py = ax.transData.transform((x, y))
    h = image.shape[0]
    return image[int(round(h - py)), int(round(px))]


def test_an_agreement_maps_zero_and_not_applicable_look_apart_and_many_maps_keep_their_texts_apart():
    from isorock.validate.tools.campaign.products import agreement_plot
    maps = [_map("mujoco", "default"), _map("mujoco", "preset=event-resolved,timestep=0.0005,friction=0.8"),
            _map("bullet", "preset=substeps-30"), _map("drake", "preset=hydroelastic")]
    fig = agreement_plot(maps)
    ax = fig.axes[0]  # mujoco default, verdict: (x 1, y 0.5) is 0, (x 4, y 0.5) not applicable
    zero, na = _cell_rgb(fig, ax, 1.0, 0.5), _cell_rgb(fig, ax, 4.0, 0.5)
    assert np.abs(zero - na).max() > 40, (zero, na)  # 0 is near white; n/a is grey (or its hatch)
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert any("not applicable" in t for t in texts)
    _check(fig, 130)


# --- the atlas's Pareto plot ---------------------------------------------------------------------

def _summaries():
    """Presets as the atlas finds them: several at the same cost and error (a preset named
    for the default's own setting), others close by, some not judged on every cell."""
    out = []
    mujoco = {"default": (110, 0.004), "newton": (110, 0.004), "elliptic": (110, 0.004), "full": (95, 0.004),
              "cg": (120, 0.0041), "pyramidal": (130, 0.006), "fast": (400, 0.009), "fine": (12, 0.0009),
              "model-md": (105, 0.005), "event-resolved": (300, 0.02), "corners": (140, 0.0045)}
    bullet = {"default": (50, 0.0038), "fast": (150, 0.009), "fine": (6, 0.0011), "erp-low": (50, 0.0039),
              "erp-high": (52, 0.05), "iterations-10": (70, 0.0045), "iterations-200": (30, 0.0038),
              "substeps-3": (45, 0.0038), "substeps-30": (60, 0.0052)}
    for engine, presets in (("mujoco", mujoco), ("bullet", bullet)):
        for preset, (speed, error) in presets.items():
            out.append({"engine_name": engine, "preset": f"{engine}:{preset}", "complete": True,
                        "worst_beta_error": error, "sim_per_wall": speed, "failures": {}})
    for preset, speed in (("drake:hydroelastic", 0.5), ("drake:tamsi", 2.0), ("drake:sap", 1.0)):
        out.append({"engine_name": "drake", "preset": preset, "complete": False, "worst_beta_error": 0.2,
                    "sim_per_wall": speed, "failures": {"too slow": 12, "missing impacts": 3}})
    return out


def test_the_pareto_plots_labels_do_not_overlap():
    from isorock.validate.tools.atlas_figures import pareto_figure
    fig = pareto_figure(_summaries(), (0.005, 0.001))
    labels = [t.get_text() for t in fig.axes[0].texts]
    assert all(s["preset"] in " ".join(labels) for s in _summaries())
    _check(fig, 100)


def test_a_fragility_fit_says_what_it_does_not_know():
    """A median beyond the levels tried is an extrapolation; a band over 2 records means
    little (issue 25): said in the table's note and in the figure's legend."""
    from isorock.validate.tools.campaign.products import fragility_caveats, fragility_plot
    from isorock.validate.core.fragility import fit_fragility
    levels = np.array([0.1, 0.2, 0.3])
    few = np.array([[0, 0, 1], [0, 0, 0]], dtype=float)  # 2 records, 1 of 6 runs overturned, at the top level
    fit = fit_fragility(levels, few, bootstrap=0)
    assert fit.median > levels.max()  # the oracle: fewer than half overturn at the highest level
    f = {"system": "fixed base, H 2 m, B 0.7 m", "engine": "analytic", "setting": "default", "scale_by": "pga",
         "levels": levels, "fraction": few.mean(axis=0), "records": 2, "fit": fit}
    caveats = fragility_caveats(f)
    assert any("extrapolation" in c for c in caveats) and any("2 records" in c for c in caveats)
    fig = fragility_plot([f])
    legend = " ".join(t.get_text() for t in fig.axes[0].get_legend().get_texts())
    assert "(extrapolated)" in legend
    plt.close(fig)
    many = np.tile([[0, 1, 1], [0, 0, 1], [0, 1, 1], [1, 1, 1], [0, 0, 1], [0, 1, 1]], (2, 1)).astype(float)
    inside = fit_fragility(levels, many, bootstrap=0)
    assert levels.min() <= inside.median <= levels.max()
    assert fragility_caveats(dict(f, fit=inside, records=12)) == []


def test_the_beta_figure_judges_free_rocking_and_says_why_forced_impacts_are_not():
    from isorock.validate.io.figures import beta_per_impact_figure
    from isorock.validate.tools.report_render import FORCED_BETA_NOTE
    rng = np.random.default_rng(3)
    free = [(label, engine, list(rng.normal(0, 0.002, 4))) for label in ("isolated", "fixed")
            for engine in ("mujoco", "bullet", "mujoco:fast")]
    forced = [(name, engine, list(rng.normal(0, 0.03, 12)))
              for name in ("RSN1106_KOBE_KJM000.AT2 isolated", "RSN1106_KOBE_KJM000.AT2 fixed base", "KOBE_NS")
              for engine in ("mujoco", "bullet")]
    fig = beta_per_impact_figure([("free rocking from 0.5α", free), ("forced histories", forced, FORCED_BETA_NOTE)],
                                 bands={"mujoco": 0.005, "bullet": 0.005, "mujoco:fast": 0.01})
    free_ax, forced_ax = fig.axes[:2]

    def dashed(ax):
        return [line for line in ax.get_lines() if line.get_linestyle() == "--"]
    assert dashed(free_ax) and not dashed(forced_ax)  # a tolerance only where the points are judged
    assert "not judged" in forced_ax.get_title()
    _check(fig, 100)
