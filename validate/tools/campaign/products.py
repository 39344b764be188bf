"""What a campaign's table is drawn as: overturning spectra, fragility curves and
agreement maps (PNG), and a Markdown summary that shows them with their numbers.

Each product is made when the table holds what it needs (pulse cases for a spectrum,
record cases for fragility, a contact engine beside the analytic one for agreement).
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ...core.chunks import runs_as_batch
from ...core.fragility import fit_fragility
from ...core.tolerances import has_tolerance, limit, tolerance
from ...core.verdict import overturn_verdicts, quantile_verdict, rate_verdict
from ...io.naming import cell
from ...io.output import write_text
from .spec import AXES

#: θmax/α departure for an agreement map when the tolerance table has no entry for the
#: engine: the table's single-history limit for MuJoCo and PyBullet is 0.02 (β within
#: 1% per impact over ~10 impacts); a new engine is held to the same.
DEFAULT_THETA_TOLERANCE = 0.02

REGIONS = ("no uplift", "rocks and survives", "safe region", "overturns after impacts",
           "overturns without impact")
REGION_COLORS = ("#f2f2f2", "#9ecae1", "#a1d99b", "#fdae6b", "#de2d26")
SYSTEM_KEYS = ("base", "height", "width", "mass_ratio", "period", "damping_ratio", "statue", "azimuth")


def _columns(table) -> dict:
    d = table.to_pydict()
    return {k: np.asarray(v) for k, v in d.items()}


def _select(cols, mask):
    return {k: v[mask] for k, v in cols.items()}


def _system_label(cols, i) -> str:
    geo = f"H {cols['height'][i]:g} m, B {cols['width'][i]:g} m"
    if "statue" in cols and cols["statue"][i]:  # a statue's mesh along one direction (docs/statues.md)
        geo = f"{cols['statue'][i]} at {cols['azimuth'][i]:g}°"
    if cols["base"][i] == "fixed":
        return f"fixed base, {geo}"
    return (f"isolated T {cols['period'][i]:g} s, ξ {cols['damping_ratio'][i]:g}, "
            f"μ {cols['mass_ratio'][i]:g}, {geo}")


def _groups(cols, keys):
    """Indices of rows grouped by the values of `keys` (NaN-safe), in first-seen order."""
    out = {}
    keys = [k for k in keys if k in cols]  # a table made before a key was a column (statue, azimuth)
    for i in range(len(cols["case"])):
        key = tuple("nan" if isinstance(cols[k][i], float) and math.isnan(cols[k][i]) else cols[k][i]
                    for k in keys)
        out.setdefault(key, []).append(i)
    return [np.array(v) for v in out.values()]


def _engine_settings(cols):
    pairs = sorted(set(zip(cols["engine"].tolist(), cols["setting"].tolist())))
    reference = next((p for p in pairs if runs_as_batch(p[0])), None)
    return reference, [p for p in pairs if not runs_as_batch(p[0])]


def _is(cols, pair):
    return (cols["engine"] == pair[0]) & (cols["setting"] == pair[1])


def theta_tolerance(engine: str) -> float:
    return tolerance(engine, "theta_max_diff").limit if has_tolerance(engine, "theta_max_diff") \
        else DEFAULT_THETA_TOLERANCE


# --- 1. overturning spectrum --------------------------------------------------------------

def region_codes(cols) -> np.ndarray:
    """The region of each pulse case (index into REGIONS) from its analytic row.
    'safe region': survives above the lowest overturning amplitude of its frequency."""
    code = np.where(~cols["uplift"], 0, 1)
    code = np.where(cols["overturned"] & (cols["overturn_mode"] == "after impacts"), 3, code)
    code = np.where(cols["overturned"] & (cols["overturn_mode"] == "without impact"), 4, code)
    lowest = lowest_overturning(cols)
    for i in range(code.size):
        if code[i] == 1 and cols["amplitude_ratio"][i] > lowest.get(cols["frequency_ratio"][i], math.inf):
            code[i] = 2
    return code


def lowest_overturning(cols) -> dict:
    """frequency ratio → lowest amplitude ratio that overturns (absent: none does)."""
    out = {}
    for f, a, o in zip(cols["frequency_ratio"], cols["amplitude_ratio"], cols["overturned"]):
        if o and a < out.get(f, math.inf):
            out[f] = a
    return out


def spectrum_figure(cols, path: Path) -> list[dict]:
    """Region map of the analytic model, one panel per base (fixed and isolated side by
    side), every contact engine's lowest-overturning-amplitude line drawn over it."""
    import matplotlib  # lazy: matplotlib, for the figures only
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: matplotlib, for the figures only
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    reference, contacts = _engine_settings(cols)
    if reference is None:
        return []
    ref = _select(cols, _is(cols, reference))
    panels = _groups(ref, SYSTEM_KEYS)
    fig, axes = plt.subplots(1, len(panels), figsize=(5.6 * max(len(panels), 2), 4.6 + 0.25 * len(contacts)),
                             squeeze=False, sharey=True, layout="constrained")
    cmap = ListedColormap(REGION_COLORS)
    norm = BoundaryNorm(np.arange(-0.5, len(REGIONS)), cmap.N)
    stats_rows = []
    styles = ["-o", "--s", "-.^", ":v", "-D", "--x"]
    for ax, idx in zip(axes[0], panels):
        p = _select(ref, idx)
        code = region_codes(p)
        fr, ar = np.unique(p["frequency_ratio"]), np.unique(p["amplitude_ratio"])
        grid = np.full((ar.size, fr.size), np.nan)
        grid[np.searchsorted(ar, p["amplitude_ratio"]), np.searchsorted(fr, p["frequency_ratio"])] = code
        ax.pcolormesh(_edges(fr), _edges(ar), np.ma.masked_invalid(grid), cmap=cmap, norm=norm)
        label = _system_label(p, 0)
        ax.set_title(label.split(", H")[0], fontsize=9)
        ax.set_xlabel("ω_p / p")
        counts = {r: int(np.sum(code == k)) for k, r in enumerate(REGIONS)}
        stats_rows.append({"panel": label, "engine": f"{reference[0]} ({reference[1]})", **counts})
        low = lowest_overturning(p)
        ax.plot(fr, [low.get(x, np.nan) for x in fr], "k-", lw=0.8, label=f"{reference[0]}: lowest overturning")
        # contact engines: their lowest overturning amplitude per frequency, on the same systems
        for j, pair in enumerate(contacts):
            m = _is(cols, pair)
            for k in SYSTEM_KEYS:
                v = p[k][0]
                m &= (cols[k] == v) if not (isinstance(v, float) and math.isnan(v)) else np.isnan(cols[k])
            c = _select(cols, m)
            if not c["case"].size:
                continue
            low = lowest_overturning(c)
            xs = np.unique(c["frequency_ratio"])
            ys = np.array([low.get(x, np.nan) for x in xs])
            ax.plot(xs, ys, styles[j % len(styles)], ms=5 - j, lw=1.2, color=f"C{j}", mfc="none",
                    label=f"{pair[0]} {pair[1]}: lowest overturning")
            stats_rows.append({"panel": label, "engine": f"{pair[0]} ({pair[1]})",
                               "overturns": int(c["overturned"].sum()), "runs": int(c["case"].size)})
    axes[0][0].set_ylabel("a_p / (g·tanα)")
    handles = [Patch(color=c, label=r) for c, r in zip(REGION_COLORS, REGIONS)]
    line_handles, _ = axes[0][-1].get_legend_handles_labels()
    fig.legend(handles=handles + line_handles, loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return stats_rows


def _edges(v):
    v = np.asarray(v, dtype=float)
    if v.size == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5])
    mid = (v[1:] + v[:-1]) / 2
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


# --- 2. fragility -------------------------------------------------------------------------

def fragility_fits(cols) -> list[dict]:
    """One lognormal fit per (system, engine, setting) over the record cases."""
    out = []
    for idx in _groups(cols, SYSTEM_KEYS + ("engine", "setting")):
        g = _select(cols, idx)
        levels = np.unique(g["intensity"])
        records = sorted(set(g["motion"].tolist()))
        o = np.full((len(records), levels.size), np.nan)
        r_index = {r: i for i, r in enumerate(records)}
        for m, x, ov, status in zip(g["motion"], g["intensity"], g["overturned"], g["status"]):
            # a run that failed (its energy balance, say) or stopped at its event limit is missing
            o[r_index[m], np.searchsorted(levels, x)] = float(ov) if status in ("completed", "overturned") else np.nan
        fit = fit_fragility(levels, o)
        out.append({"system": _system_label(g, 0), "engine": g["engine"][0], "setting": g["setting"][0],
                    "scale_by": g["scale_by"][0], "levels": levels, "fraction": np.nanmean(o, axis=0),
                    "records": len(records), "fit": fit})
    return out


def _limit(engine: str, metric: str, fallback: float) -> float:
    return tolerance(engine, metric).limit if has_tolerance(engine, metric) else fallback


def _judging():
    """The confidence and the fewest cases of every statistical verdict (the tolerance table)."""
    return dict(confidence=limit("verdict_confidence"), min_cases=int(limit("verdict_min_cases")))


def fragility_comparisons(cols) -> list[dict]:
    """Each contact (engine, setting)'s fragility against the analytic model's on the same
    system and records, judged as validate's ensembles are (core.verdict.overturn_verdicts):
    ln of the ratio of medians and Δ dispersion β, each with its interval from a paired
    bootstrap over the records (a record's outcomes at every level drawn together) against
    the tolerance table's limits: agrees, disagrees or inconclusive with the records that
    would decide. A record at a level one engine lacks is left out of both."""
    reference, contacts = _engine_settings(cols)
    if reference is None:
        return []
    out = []
    for idx in _groups(cols, SYSTEM_KEYS):
        g = _select(cols, idx)
        ref = {(m, x): bool(o) for m, x, o in zip(*(_select(g, _is(g, reference))[k]
                                                    for k in ("motion", "intensity", "overturned")))}
        for pair in contacts:
            c = _select(g, _is(g, pair))
            rows = [(m, x, bool(o), ref[(m, x)]) for m, x, o in zip(c["motion"], c["intensity"], c["overturned"])
                    if (m, x) in ref]
            if not rows:
                continue
            motion, x, e, r = (np.array(v) for v in zip(*rows))
            v = overturn_verdicts(x.astype(float), e, r, groups=motion, **_judging(),
                                  median_limit=_limit(pair[0], "ensemble_overturn_median", math.nan),
                                  dispersion_limit=_limit(pair[0], "ensemble_overturn_dispersion", math.nan))
            out.append({"system": _system_label(g, 0), "engine": pair[0], "setting": pair[1],
                        "records": len(set(motion.tolist())), "verdicts": v})
    return out


def fragility_caveats(f) -> list[str]:
    """What a fragility fit does not know, said beside it: a median outside the levels
    tried is an extrapolation of the lognormal, and a bootstrap band over fewer records
    than a statistical verdict needs (tolerances: verdict_min_cases) means little."""
    fit, levels, out = f["fit"], np.asarray(f["levels"], dtype=float), []
    if math.isfinite(fit.median) and fit.median > levels.max():
        out.append(f"median beyond the highest level tried ({levels.max():g}): an extrapolation")
    elif math.isfinite(fit.median) and fit.median < levels.min():
        out.append(f"median below the lowest level tried ({levels.min():g}): an extrapolation")
    least = limit("verdict_min_cases")
    if math.isfinite(fit.median) and f["records"] < least:
        out.append(f"band over {f['records']} records: too few to mean much (fewer than {least:g})")
    return out


#: Fragility panels per row: 16 systems in one row made a 10,816 × 546 px strip (issue 25)
FRAGILITY_COLUMNS = 4


def _wrap(text: str, width: int) -> str:
    """`text` in lines of at most `width` characters, broken after a space or a comma (a
    setting's label "preset=fast,timestep=0.002" has no spaces), never inside a word."""
    lines = [""]
    for token in re.split(r"(?<=[,\s])", text):
        if lines[-1] and len(lines[-1] + token.rstrip()) > width:
            lines.append("")
        lines[-1] += token
    return "\n".join(line.rstrip() for line in lines)


def fragility_plot(fits):
    """The fragility figure: one panel per system, FRAGILITY_COLUMNS to a row (so that
    any number of systems reads at the same size), each curve labelled in its panel's
    legend; titles wrapped to the panel's width."""
    import matplotlib  # lazy: matplotlib, for the figures only
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: matplotlib, for the figures only
    systems = list(dict.fromkeys(f["system"] for f in fits))
    pairs = list(dict.fromkeys((f["engine"], f["setting"]) for f in fits))
    ncols = min(FRAGILITY_COLUMNS, len(systems))
    nrows = math.ceil(len(systems) / ncols)
    # room under each panel for its legend, one line per engine and setting
    legend_h = 0.2 * len(pairs) + 0.3
    fig, axes = plt.subplots(nrows, ncols, figsize=(5.2 * ncols, (3.6 + legend_h) * nrows), squeeze=False,
                             sharey=True, layout="constrained")
    unit = "g" if fits[0]["scale_by"] == "pga" else "m/s"
    for ax in axes.flat[len(systems):]:
        ax.set_visible(False)
    for ax, system in zip(axes.flat, systems):
        for f in (f for f in fits if f["system"] == system):
            j = pairs.index((f["engine"], f["setting"]))
            color = "k" if runs_as_batch(f["engine"]) else f"C{j}"
            # curves that coincide (engines agreeing run for run) stay visible: each pair
            # its own dash pattern, later ones thinner
            style = ("-", "--", "-.", ":")[j % 4]
            width = max(2.6 - 0.5 * j, 0.8)
            x = f["levels"]
            ax.plot(x, f["fraction"], "o", color=color, ms=max(6 - j, 2), mfc="none" if j else color)
            fit = f["fit"]
            name = _wrap(f"{f['engine']} {f['setting']}", 40)
            if math.isfinite(fit.median):
                xx = np.geomspace(x[0], x[-1], 200)
                lo, hi = fit.band(xx)
                ax.fill_between(xx, lo, hi, color=color, alpha=0.10, lw=0)
                beyond = " (extrapolated)" if any("extrapolation" in c for c in fragility_caveats(f)) else ""
                ax.plot(xx, fit.probability(xx), style, color=color, lw=width,
                        label=f"{name}: θ = {fit.median:.3g}{beyond}, β = {fit.dispersion:.2f}")
            else:
                ax.plot([], [], "o", color=color, label=f"{name}: {_wrap(fit.note, 50)}")
        ax.set_xlabel(f"{fits[0]['scale_by'].upper()} ({unit})")
        ax.set_title(_wrap(system, 55), fontsize=9)
        ax.set_ylim(-0.02, 1.02)
        # under the panel, not over its curves
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)
    for row in axes:
        row[0].set_ylabel("P(overturn)")
    return fig


def fragility_figure(fits, path: Path) -> None:
    import matplotlib.pyplot as plt  # lazy: matplotlib, for the figures only
    fig = fragility_plot(fits)
    fig.savefig(path, dpi=130)
    plt.close(fig)


# --- 3. agreement maps ----------------------------------------------------------------------

def _auto_axes(cols) -> tuple[str, str] | None:
    counts = sorted(((np.unique(cols[k][~_nan(cols[k])]).size, k) for k in AXES), reverse=True)
    chosen = [k for n, k in counts if n > 1][:2]
    return (chosen[0], chosen[1]) if len(chosen) == 2 else None


def _nan(v):
    return np.isnan(v) if v.dtype.kind == "f" else np.zeros(v.shape, bool)


def _ended(cols) -> np.ndarray:
    """Rows whose run ended as the model's can: it completed or overturned."""
    return np.isin(cols["status"], ["completed", "overturned"])


def agreement(cols, x: str, y: str) -> list[dict]:
    """Per contact (engine, setting): for each (x, y) cell, the fraction of cases whose
    verdict differs from the analytic one, and of those both survive, the fraction
    whose θmax/α departs by more than the engine's tolerance; and each engine's whole map
    judged by core.verdict's rule (`overturn_verdict`, `theta_verdict`)."""
    reference, contacts = _engine_settings(cols)
    if reference is None:
        return []
    ref = _select(cols, _is(cols, reference))
    by_case = {c: i for i, c in enumerate(ref["case"].tolist())}
    out = []
    for pair in contacts:
        c = _select(cols, _is(cols, pair))
        keep = np.array([k in by_case for k in c["case"].tolist()], dtype=bool)
        c = _select(c, keep)
        r = _select(ref, np.array([by_case[k] for k in c["case"].tolist()], dtype=int))
        # only runs that both ended as the model can end are compared: a contact run that slid (the
        # model assumes no slip), left the model (a statue that rolled off its plane), or failed is
        # counted apart by its status, never as agreement or disagreement
        judged = _ended(c) & _ended(r)
        apart = {str(k): int(v) for k, v in zip(*np.unique(c["status"][~_ended(c)], return_counts=True))}
        cases = int(c["case"].size)
        c, r = _select(c, judged), _select(r, judged)
        tol = theta_tolerance(pair[0])
        verdict = c["overturned"] != r["overturned"]
        both_survive = ~c["overturned"] & ~r["overturned"]
        theta = both_survive & (np.abs(c["theta_max_over_alpha"] - r["theta_max_over_alpha"]) > tol)
        xs, ys = np.unique(c[x]), np.unique(c[y])
        ix, iy = np.searchsorted(xs, c[x]), np.searchsorted(ys, c[y])
        shape = (ys.size, xs.size)
        n = np.zeros(shape)
        np.add.at(n, (iy, ix), 1)
        nv = np.zeros(shape)
        np.add.at(nv, (iy, ix), verdict)
        ns = np.zeros(shape)
        np.add.at(ns, (iy, ix), both_survive)
        nt = np.zeros(shape)
        np.add.at(nt, (iy, ix), theta)
        # the map's counts judged as every count and ensemble is (core.verdict): overturning
        # as the share of cases that differ, θmax/α as the median difference where both survive
        overturn = rate_verdict(int(verdict.sum()), int(verdict.size), limit=limit("verdict_disagreement_rate"),
                                quantity="share of cases whose overturning differs", **_judging())
        d_theta = quantile_verdict(c["theta_max_over_alpha"][both_survive], r["theta_max_over_alpha"][both_survive],
                                   limit=_limit(pair[0], "ensemble_theta_max_diff", tol),
                                   quantity="Δ median θmax/α (both survive)", **_judging())
        with np.errstate(invalid="ignore", divide="ignore"):
            out.append({"engine": pair[0], "setting": pair[1], "x": x, "y": y, "xs": xs, "ys": ys,
                        "overturn_verdict": overturn, "theta_verdict": d_theta,
                        "verdict": np.where(n > 0, nv / n, np.nan), "theta": np.where(ns > 0, nt / ns, np.nan),
                        "tolerance": tol, "cases": cases, "judged": int(c["case"].size),
                        "not judged": ", ".join(f"{n} {k}" for k, n in sorted(apart.items())) or "none",
                        "verdict_differs": int(verdict.sum()),
                        "both_survive": int(both_survive.sum()), "theta_departs": int(theta.sum())})
    return out


#: An agreement map's cells where nothing is judged (no case there, or for θmax/α none in
#: which both survive): hatched grey, never the colour of 0 (which is judged and agrees)
NOT_APPLICABLE = {"facecolor": "#bdbdbd", "hatch": "///", "edgecolor": "#737373"}


def agreement_plot(maps):
    """The agreement maps: per contact engine and setting a column, the fraction of cases
    whose overturning verdict differs (top) and whose θmax/α departs (bottom); cells with
    nothing to judge hatched grey (NOT_APPLICABLE), apart from 0."""
    import matplotlib  # lazy: matplotlib, for the figures only
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above
    from matplotlib.patches import Patch, Rectangle
    fig, axes = plt.subplots(2, len(maps), figsize=(4.6 * len(maps), 8.0), squeeze=False, layout="constrained")
    for j, m in enumerate(maps):
        for i, (key, title) in enumerate((("verdict", "overturned or not differs"),
                                           ("theta", f"|Δ θmax/α| > {m['tolerance']:g} (both survive)"))):
            ax = axes[i][j]
            xe, ye = _edges(m["xs"]), _edges(m["ys"])
            ax.add_patch(Rectangle((xe[0], ye[0]), xe[-1] - xe[0], ye[-1] - ye[0], lw=0, zorder=0, **NOT_APPLICABLE))
            im = ax.pcolormesh(xe, ye, np.ma.masked_invalid(m[key]), cmap="Reds", vmin=0, vmax=1, zorder=1)
            ax.set_title(_wrap(f"{m['engine']} {m['setting']}", 36) + f"\n{title}", fontsize=8)
            ax.set_xlabel(m["x"])
            ax.set_ylabel(m["y"])
        fig.colorbar(im, ax=axes[:, j].tolist(), shrink=0.6, label="fraction of cases")
    fig.legend(handles=[Patch(label="not applicable: no case to judge", **NOT_APPLICABLE)], loc="outside lower center",
               fontsize=8, frameon=False)
    return fig


def agreement_figure(maps, path: Path) -> None:
    import matplotlib.pyplot as plt  # lazy: matplotlib, for the figures only
    fig = agreement_plot(maps)
    fig.savefig(path, dpi=130)
    plt.close(fig)


# --- the summary ------------------------------------------------------------------------------

def _md_table(rows: list[dict]) -> list[str]:
    if not rows:
        return []
    keys = list(dict.fromkeys(k for r in rows for k in r))
    out = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    for r in rows:
        out.append("| " + " | ".join(cell(r.get(k, "")) for k in keys) + " |")
    return out




def write_products(table, out: Path, spec=None) -> list[Path]:
    cols = _columns(table)
    made, lines = [], [f"# Campaign: {spec.name if spec else 'cases'}", ""]
    if not cols["case"].size:
        write_text(out / "summary.md", "\n".join(lines + ["No rows."]) + "\n")
        return [out / "summary.md"]
    lines += [f"{np.unique(cols['case']).size} cases, {cols['case'].size} runs. "
              "Overturned: |θ| reached π/2, or the run ended with |θ| > α (model.md, “Past α”).", "",
              "## Runs per engine", ""]
    per = []
    for idx in _groups(cols, ("engine", "setting")):
        g = _select(cols, idx)
        per.append({"engine": g["engine"][0], "setting": g["setting"][0], "runs": idx.size,
                    "overturned": int(g["overturned"].sum()),
                    "not completed/overturned": int(np.sum(~np.isin(g["status"], ["completed", "overturned"]))),
                    "mean runtime s": float(np.mean(g["runtime_s"]))})
    lines += _md_table(per) + [""]
    pulses = cols["frequency_ratio"].astype(float)
    pulse_rows = ~np.isnan(pulses)
    if pulse_rows.any() and (spec is None or spec.products.get("spectrum", True)):
        for idx in _groups(_select(cols, pulse_rows), ("motion",)):
            p = _select(_select(cols, pulse_rows), idx)
            name = f"spectrum-{p['motion'][0]}.png"
            rows = spectrum_figure(p, out / name)
            if rows:
                made.append(out / name)
                lines += [f"## Overturning spectrum: one-{p['motion'][0]} pulse", "", f"![spectrum]({name})", ""]
                lines += _md_table(rows) + [""]
    record_rows = ~np.isnan(cols["intensity"].astype(float))
    if record_rows.any() and (spec is None or spec.products.get("fragility", True)):
        fits = fragility_fits(_select(cols, record_rows))
        fragility_figure(fits, out / "fragility.png")
        made.append(out / "fragility.png")
        unit = "g" if fits[0]["scale_by"] == "pga" else "m/s"
        lines += ["## Fragility", "", "![fragility](fragility.png)", "",
                  f"Lognormal fit by maximum likelihood (binomial); median θ in {unit} of "
                  f"{fits[0]['scale_by'].upper()}, with its bootstrap 5–95% band over records.", ""]
        lines += _md_table([{"system": f["system"], "engine": f["engine"], "setting": f["setting"],
                             "records": f["records"], "median θ": f["fit"].median,
                             "θ 5%": f["fit"].median_band[0], "θ 95%": f["fit"].median_band[1],
                             "dispersion β": f["fit"].dispersion,
                             "note": "; ".join(filter(None, [f["fit"].note, *fragility_caveats(f)]))}
                            for f in fits]) + [""]
        compared = fragility_comparisons(_select(cols, record_rows))
        if compared:
            lines += [f"Each contact engine against the analytic model, judged as `isorock validate` judges its "
                      f"ensembles (core/verdict.py): the difference's {_judging()['confidence']:.0%} interval from a "
                      "paired bootstrap over the records, against the tolerance table's limit: agrees when wholly "
                      "within, disagrees when wholly beyond, else inconclusive (with the records that would "
                      "decide). The median's interval is widened by the largest step of ln(intensity) between "
                      "levels.", ""]
            lines += _md_table([{"system": f["system"], "engine": f["engine"], "setting": f["setting"],
                                 "records": f["records"],
                                 **({"ln(median ratio)": f["verdicts"][0].cell(), "Δ dispersion β": f["verdicts"][1].cell()}
                                    if f["verdicts"] else {"ln(median ratio)": "neither overturns, or both always",
                                                           "Δ dispersion β": "–"})} for f in compared]) + [""]
    axes = None
    if spec is not None and "agreement" in spec.products:
        a = spec.products["agreement"]
        axes = (a.get("x"), a.get("y")) if a.get("x") and a.get("y") else None
    axes = axes or _auto_axes(cols)
    if axes:
        maps = agreement(cols, *axes)
        if maps:
            agreement_figure(maps, out / "agreement.png")
            made.append(out / "agreement.png")
            lines += ["## Agreement with the analytic model", "", "![agreement](agreement.png)", "",
                      "θmax/α tolerance: the tolerance table's `theta_max_diff` for the engine "
                      f"(else {DEFAULT_THETA_TOLERANCE}).", ""]
            lines += _md_table([{**{k: m[k] for k in ("engine", "setting", "cases", "judged", "not judged",
                                                      "verdict_differs",
                                                      "both_survive", "theta_departs", "tolerance")},
                                 "overturning differs (share)": m["overturn_verdict"].cell(),
                                 "Δ median θmax/α": m["theta_verdict"].cell()}
                                for m in maps]) + [""]
            lines += [f"Judged as every count and ensemble is (core/verdict.py), at "
                      f"{_judging()['confidence']:.0%} confidence: the share of cases whose overturning differs "
                      "by its exact interval against the tolerance table's verdict_disagreement_rate, the median "
                      "θmax/α difference where both survive by its bootstrap interval against the engine's "
                      "ensemble_theta_max_diff; only the cases both engines ended as the model can (completed or "
                      "overturned) are judged, the others counted apart by their status.", ""]
    write_text(out / "summary.md", "\n".join(lines) + "\n")
    return [out / "summary.md", *made]
