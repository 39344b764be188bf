"""Writing the validation report: report.md, report.html (figures embedded), the PNGs and
metrics.json, from the Results of `isorock.validate.report_run.build`.

The report is a list of blocks (headings, paragraphs, tables, images), rendered once to
Markdown and once to HTML.
"""
from __future__ import annotations

import base64
import html
import math
from dataclasses import asdict
from pathlib import Path

from isorock.validate import figures
from isorock.validate.engines import ENGINE_MODULES, REFERENCE
from isorock.validate.output import write_folder_atomic, write_json
from isorock.validate.paper import PAPER_FIGURE5, is_kobe, paper_blocks
from isorock.validate.report_run import PAPER_SLENDERNESS, Results

def _f(x, fmt=".3f"):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, bool):
        return "yes" if x else "no"
    return format(x, fmt)


def summary_rows(results: Results):
    """The report's summary table: one row per scenario and engine."""
    rows = []
    for sc in results.scenarios:
        for name in results.engines:
            tr, c = sc.runs.get(name), sc.comparisons.get(name)
            if tr is None:
                rows.append([sc.name, name, "error: " + sc.errors.get(name, "?")] + ["–"] * 7)
                continue
            rows.append([sc.name, name, _f(tr.theta_max_over_alpha),
                         _f(c.theta_max_diff, "+.3f") if c else "(reference)",
                         str(tr.impact_count), _f(tr.overturned),
                         _f(c.horizon, ".2f") + ("" if c.parted else " (whole run)") if c else "–",
                         _f(tr.u_max * 100, ".2f"),
                         _f(c.beta_error_median * 100 if c and c.beta_error_median is not None else None, ".2f"),
                         _f(tr.runtime_s, ".2f")])
    header = ["scenario", "engine", "θmax/α", "Δθmax/α", "impacts", "overturned", "horizon (s)",
              "max |u| (cm)", "median |β err| (%)", "runtime (s)"]
    return header, rows


def _blocks(results: Results, images: dict) -> list:
    """The report as a list of blocks, rendered once to Markdown and once to HTML."""
    cfg = results.config
    B = [("h1", "isorock validation report")]
    B.append(("p", f"Generated {results.started} in {results.wall_s:.0f} s "
                   f"({'quick' if cfg.quick else 'full'} run). Reference: the analytic hybrid model; "
                   f"contact engines are compared with it on the same System and GroundMotion. "
                   f"System: the paper's block (H 2.0 m, B 0.7 m, m = m_b = 3800 kg), isolated with "
                   f"T 1.5 s, ξ 0.2 (the reading of the paper that fits its figure, model.md), and on a fixed base."))
    settings = engine_settings(results)
    eng_rows = [[n, "ok", ENGINE_MODULES[n], ", ".join(f"{k}={v}" for k, v in settings[n].items())]
                for n in results.engines] + \
               [[n, "SKIPPED", why, "–"] for n, why in results.skipped.items()]
    B.append(("h2", "Engines"))
    B.append(("table", ["engine", "status", "module / reason", "settings (defaults)"], eng_rows))
    B.append(("h2", "Summary"))
    header, rows = summary_rows(results)
    B.append(("table", header, rows))
    B.append(("p", "Δ is engine − analytic. The horizon is the first time |Δθ| > 0.1α (histories on a 1 ms grid). "
                   "β errors are per counted impact, effective β (states 30 ms outside the contact mapped to θ = 0 "
                   "with the rigid equations) against the closed form."))
    kobe = [sc for sc in results.scenarios if is_kobe(sc.motion)]
    if kobe:
        B += paper_blocks(results, kobe, _f)
    B.append(("h2", "Free rocking: effective β (the paper's Figure 4)"))
    B.append(("img", images["beta_slenderness"], "β and β₂/h against slenderness: closed form (lines), "
                                                  "contact engines' effective values (markers)."))
    B.append(("table", ["engine", "case", "β closed", "β effective", "|β err| max (%)", "β₂/h closed",
                        "β₂/h effective", "first impact (s)", "impacts used"],
              [[r["engine"], r["scenario"], _f(r.get("beta_closed"), ".4f"), _f(r.get("beta"), ".4f"),
                _f(r.get("beta_rel_error", math.nan) * 100 if r.get("beta_rel_error") is not None else None, ".3f"),
                _f(r.get("beta2_over_h_closed"), ".4f") if not r["fixed_base"] else "–",
                _f(r.get("beta2_over_h"), ".4f"), _f(r.get("first_impact_time"), ".4f"),
                str(r.get("impacts_used", "–")) if not r["error"] else "error: " + r["error"]]
               for r in results.free]))
    B.append(("img", images["beta_per_impact"], "Effective β per counted impact against the closed form: free "
                                                "rocking of the paper's block, and every impact of the forced "
                                                "histories (small half-cycles and impacts where the block comes to "
                                                "rest between pulses measure the contact more than β)."))
    B.append(("h2", "Histories (the paper's Figure 5 layout)"))
    for sc_iso, sc_fix, key in _history_pairs(results):
        B.append(("img", images[key], f"{sc_iso.motion.name}: ground acceleration, θ/α on the isolated and the "
                                      f"fixed base, base displacement and angular velocity (isolated)."))
    for sc in results.scenarios:
        s = sc.sensitivity
        B.append(("p", f"{sc.name}: analytic θmax/α {', '.join(f'{v:.3f}' for v in s['theta_max_over_alpha'])} "
                       f"at ×0.99, ×1, ×1.01 PGA — "
                       f"{'robust, single-history checks apply' if sc.robust else 'sensitive, so single-history checks are skipped and the ensemble decides'}."))
    B.append(("h2", "Ensembles (PGA scaled)"))
    B.append(("img", images["ensemble"], "θmax/α against the scale factor of the PGA; × marks overturning."))
    ens_rows = []
    for ens in results.ensembles:
        for name, a in ens.as_dict()["agreement"].items():
            ens_rows.append([f"{ens.motion}, {'fixed' if ens.system.fixed_base else 'isolated'} base", name,
                             str(a["cases"]), _f(a["overturn_agreement"] * 100, ".0f") + " %",
                             _f(a["median_theta_max_diff"]), _f(a["max_theta_max_diff"]),
                             f"{_f(a['median_theta_max_diff_rocking'])} ({a['rocking_cases']})"])
    B.append(("table", ["ensemble", "engine", "cases", "overturning agrees", "median |Δθmax/α|",
                        "max |Δθmax/α|", "median |Δθmax/α|, rocking cases (n)"], ens_rows))
    B.append(("p", "θmax/α is capped at 1 (overturned) before differencing. Rocking cases: the analytic "
                   "block rocks (θmax/α > 0.01) and neither overturns."))
    B.append(("h2", "Checks"))
    B.append(("table", ["result", "engine", "metric", "scenario", "value", "tolerance", "reason", "note"],
              [[c.status.upper(), c.engine, c.metric, c.scenario, _f(c.value, ".4g"),
                {"max": "≤ ", "min": "≥ ", "equal": "= "}[c.kind] + format(c.limit, "g"), c.reason, c.note]
               for c in results.checks]))
    B.append(("h2", "Versions"))
    B.append(("table", ["package", "version"], [[k, v] for k, v in results.versions.items()]))
    B.append(("p", verdict(results)))
    return B


def engine_settings(results: Results) -> dict:
    """Each loaded engine's default Settings as plain values (every run uses the defaults)."""
    out = {}
    for name, engine in results.engines.items():
        try:
            out[name] = asdict(engine.Settings())
        except TypeError:  # a Settings that is not a dataclass
            out[name] = {}
    return out


def _history_pairs(results):
    """(isolated, fixed, image key) per motion, in order."""
    out = []
    for k in range(0, len(results.scenarios), 2):
        out.append((results.scenarios[k], results.scenarios[k + 1], f"histories_{k // 2 + 1}"))
    return out


def verdict(results: Results) -> str:
    n = len(results.checks)
    n_skip = sum(c.status == "skip" for c in results.checks)
    failed = results.failed
    skipped_engines = (f" Engines skipped: {', '.join(results.skipped)}." if results.skipped else "")
    if failed:
        worst = ", ".join(sorted({f"{c.engine} {c.metric}" for c in failed}))
        return f"Result: FAILED — {len(failed)} of {n} checks failed ({worst}).{skipped_engines}"
    return f"Result: all {n - n_skip} checks passed ({n_skip} skipped).{skipped_engines}"


def _md_cell(x) -> str:
    return str(x).replace("|", "\\|").replace("\n", " ")


def render_markdown(blocks) -> str:
    out = []
    for b in blocks:
        kind = b[0]
        if kind == "h1":
            out.append(f"# {b[1]}\n")
        elif kind == "h2":
            out.append(f"## {b[1]}\n")
        elif kind == "p":
            out.append(f"{b[1]}\n")
        elif kind == "img":
            out.append(f"![{b[2]}]({b[1]})\n\n*{b[2]}*\n")
        elif kind == "table":
            header, rows = b[1], b[2]
            out.append("| " + " | ".join(map(_md_cell, header)) + " |")
            out.append("|" + "---|" * len(header))
            out += ["| " + " | ".join(map(_md_cell, r)) + " |" for r in rows]
            out.append("")
    return "\n".join(out) + "\n"


def render_html(blocks, folder: Path) -> str:
    e = html.escape
    body = []
    for b in blocks:
        kind = b[0]
        if kind in ("h1", "h2"):
            body.append(f"<{kind}>{e(b[1])}</{kind}>")
        elif kind == "p":
            body.append(f"<p>{e(b[1])}</p>")
        elif kind == "img":
            data = base64.b64encode((folder / b[1]).read_bytes()).decode("ascii")
            body.append(f'<figure><img src="data:image/png;base64,{data}" alt="{e(b[2])}">'
                        f"<figcaption>{e(b[2])}</figcaption></figure>")
        elif kind == "table":
            head = "".join(f"<th>{e(str(h))}</th>" for h in b[1])
            rows = "".join("<tr>" + "".join(f'<td class="{_css(c)}">{e(str(c))}</td>' for c in r) + "</tr>"
                           for r in b[2])
            body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>")
    css = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}"
           "table{border-collapse:collapse;font-size:0.85em;margin:1em 0}"
           "td,th{border:1px solid #ccc;padding:3px 6px;text-align:left}"
           "td.fail{background:#fdd;font-weight:bold}td.pass{background:#dfd}td.skip{background:#eee}"
           "img{max-width:100%}figcaption{font-size:0.85em;color:#444}")
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>isorock validation report</title>"
            f"<style>{css}</style></head><body>\n" + "\n".join(body) + "\n</body></html>\n")


def _css(cell) -> str:
    return {"PASS": "pass", "FAIL": "fail", "SKIP": "skip"}.get(str(cell), "")


def metrics(results: Results) -> dict:
    """metrics.json: everything the tables show, machine-readable."""
    def cfg(c):
        return {k: list(v) if isinstance(v, tuple) else v for k, v in asdict(c).items()}
    out = {
        "config": cfg(results.config),
        "started": results.started, "wall_s": results.wall_s, "versions": results.versions,
        "engines": {**{n: "ok" for n in results.engines}, **{n: f"skipped: {w}" for n, w in results.skipped.items()}},
        "engine_settings": engine_settings(results),
        "free_rocking": results.free,
        "scenarios": [{
            "name": sc.name, "motion": sc.motion.describe(), "system": sc.system.describe(),
            "duration": sc.duration, "sensitivity": sc.sensitivity, "robust": sc.robust,
            "runs": {n: tr.summary() for n, tr in sc.runs.items()}, "errors": sc.errors,
            "comparisons": {n: c.as_dict() for n, c in sc.comparisons.items()},
        } for sc in results.scenarios],
        "ensembles": [e.as_dict() for e in results.ensembles],
        "checks": [c.as_dict() for c in results.checks],
        "passed": not results.failed,
        "verdict": verdict(results),
    }
    kobe = [sc for sc in results.scenarios if is_kobe(sc.motion)]
    if kobe:
        out["paper_figure5"] = {
            ("fixed base" if sc.system.fixed_base else "isolated base"): {
                "paper_theta_max_over_alpha": PAPER_FIGURE5["fixed base" if sc.system.fixed_base else "isolated base"],
                **{n: tr.theta_max_over_alpha for n, tr in sc.runs.items()}} for sc in kobe}
    return out


def beta_series(results: Results):
    """Figure panels of per-impact β errors: free rocking of the paper's block (isolated
    μ = 1 and fixed), and every impact of the forced histories."""
    free = [("isolated" if not r["fixed_base"] else "fixed", r["engine"], r["beta_errors_all"])
            for r in results.free if r["engine"] != REFERENCE and not r["error"]
            and abs(r["slenderness"] - PAPER_SLENDERNESS) < 1e-9 and r["mass_ratio"] in (0.0, 1.0)]
    forced = [(sc.name, name, list(c.beta_errors)) for sc in results.scenarios
              for name, c in sc.comparisons.items()]
    return [("free rocking from 0.5α, the paper's block", free), ("forced histories", forced)]


def write_report(results: Results, out_dir) -> None:
    """report.md, report.html (figures embedded), the PNGs and metrics.json, written
    into a temporary folder that replaces out_dir only when all of it is done."""
    def fill(tmp: Path):
        images = {"beta_slenderness": "fig4_beta_slenderness.png", "beta_per_impact": "beta_per_impact.png",
                  "ensemble": "ensemble.png"}
        figures.beta_slenderness([r for r in results.free if r["engine"] != REFERENCE and not r["error"]
                                  and not r["fixed_base"]], tmp / images["beta_slenderness"])
        figures.beta_per_impact(beta_series(results), tmp / images["beta_per_impact"])
        figures.ensemble(results.ensembles, tmp / images["ensemble"])
        for iso, fix, key in _history_pairs(results):
            images[key] = f"fig5_{key}.png"
            figures.histories(iso.motion, iso.runs, fix.runs, tmp / images[key],
                              title=f"Figure 5 layout: {iso.motion.name}")
        blocks = _blocks(results, images)
        (tmp / "report.md").write_text(render_markdown(blocks), encoding="utf-8")
        (tmp / "report.html").write_text(render_html(blocks, tmp), encoding="utf-8")
        write_json(tmp / "metrics.json", metrics(results))
    write_folder_atomic(out_dir, fill)
