"""Writing the validation report: report.md, report.html (figures embedded), the PNGs and
metrics.json, from the Results of `isorock.validate.tools.report_run.build`.

The report opens with its verdict: one line per engine (agrees / agrees with caveats /
disagrees) and a scorecard of the worst value of each family of checks against its
tolerance; the evidence follows (figures where engines part, tables), and the full
check table last, folded. It is a list of blocks (headings, paragraphs, tables, images,
folded sections), rendered once to Markdown and once to HTML.
"""
from __future__ import annotations

import base64
import html
import math
from dataclasses import fields
from pathlib import Path

from ...analytic.system import PAPER_BLOCK, PAPER_DAMPING_RATIO, PAPER_PERIOD
from ..core.engines import REFERENCE, describe_settings
from ..core.measure import mode_sequence, slide_onset
from ..core.tolerances import has_tolerance, limit, tolerance
from ..core.verdict import TOO_FEW_CASES
from ..io import figures
from ..io.naming import describe_motion, markdown_cell
from ..io.output import write_folder_atomic, write_json
from ..io.provenance import provenance
from .paper import PAPER_FIGURE5, is_kobe, paper_blocks
from .report_run import OWN, PAPER_SLENDERNESS, Results

#: The families of checks the scorecard shows, in order: (title, metrics).
FAMILIES = (
    ("β per impact", ("beta_rel_error", "beta2_abs_error")),
    ("first impact time", ("first_impact_time_rel_error",)),
    ("θmax/α", ("theta_max_diff",)),
    ("impacts", ("impacts_diff",)),
    ("uplift time", ("first_uplift_diff",)),
    ("overturning", ("overturn_agree",)),
    ("base displacement", ("u_max_rel_error",)),
    ("ensemble θmax/α", ("ensemble_theta_max_diff",)),
    ("ensemble overturning (fragility)", ("ensemble_overturn_median", "ensemble_overturn_dispersion")),
    ("energy balance", ("energy_residual",)),
    # a statue that slides (docs/sliding.md): its largest and final slide (×b), when it began (×1/p)
    ("slide", ("slide_max", "slide_final", "slide_onset")),
    ("θmax/α where the statue may slide", ("slide_theta_max_diff",)),
)
NOT_EXERCISED = "not exercised"
INCONCLUSIVE = "inconclusive"
AGREES, CAVEATS, DISAGREES, UNTESTED = "agrees", "agrees with caveats", "disagrees", "was not tested"


def _f(x, fmt=".3f"):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    if isinstance(x, bool):
        return "yes" if x else "no"
    return format(x, fmt)


def sliding_rows(results) -> list[list[str]]:
    """One row per sliding scenario and engine: how far the statue walked, when, and its modes."""
    rows = []
    for sc in results.sliding:
        for name, tr in sc.runs.items():
            x = None if tr.slide is None else tr.slide - tr.slide[0]
            rows.append([sc.name, _label(name), str(tr.status),
                         _f(None if x is None else 100 * float(abs(x).max()), ".3g"),
                         _f(None if x is None else 100 * float(x[-1]), ".3g"), _f(slide_onset(tr), ".3f"),
                         _f(tr.theta_max_over_alpha), " → ".join(mode_sequence(tr)) or "rest"])
        for name, err in sc.errors.items():
            rows.append([sc.name, _label(name), "error: " + err] + ["–"] * 5)
    return rows


def family_of(metric: str) -> str:
    return next((title for title, metrics in FAMILIES if metric in metrics), metric)


def _margin(c) -> float | None:
    """How far a checked value is inside its tolerance, as a fraction of the limit
    (negative: outside); None for a check without a value."""
    if c.kind == "within" and c.interval is not None:  # a statistical verdict: the interval's far end
        far = max(abs(c.interval[0]), abs(c.interval[1]))
        return (c.limit - far) / (abs(c.limit) or 1.0) if math.isfinite(far) else -math.inf
    if c.value is None or not math.isfinite(c.value):
        return None
    if c.kind == "equal":
        return 0.0 if c.value == c.limit else -1.0
    scale = abs(c.limit) or 1.0
    return (c.limit - c.value) / scale if c.kind == "max" else (c.value - c.limit) / scale


def _label(name: str) -> str:
    return figures.style(name)["label"]


# --- the verdict ------------------------------------------------------------------------

def engine_verdicts(results: Results) -> dict:
    """engine → (verdict word, reasons): disagrees when a check fails; agrees with
    caveats when checks were skipped, scenarios not exercised, or a run slid or failed;
    was not tested when no check of it passed."""
    out = {}
    for name in results.engines:
        mine = [c for c in results.checks if c.engine == name]
        fails = [c for c in mine if c.status == "fail"]
        passes = [c for c in mine if c.status == "pass"]
        skips = [c for c in mine if c.status == "skip"]
        idle = [c for c in mine if c.status == NOT_EXERCISED]
        open_ = [c for c in mine if c.status == INCONCLUSIVE]
        odd = sorted({f"{sc.name}: {sc.runs[name].status}" for sc in results.scenarios
                      if name in sc.runs and str(sc.runs[name].status) in ("slid", "failed", "event-limit")})
        reasons = []
        if fails:
            reasons.append(f"{len(fails)} failed ({', '.join(sorted({family_of(c.metric) for c in fails}))})")
        if skips:
            reasons.append(f"{len(skips)} skipped (chaotic references are judged by their ensembles)")
        if idle:
            where = _where_never_lifted(results, name)
            reasons.append(f"{len(idle)} not exercised (no engine lifted {_subject(results)} there"
                           + (f": {where}; nothing about contact was tested there" if where else "") + ")")
        if open_:
            few = [c for c in open_ if _too_few(c)]
            why = "; ".join(filter(None, [
                f"{len(few)} with too few cases for an interval (n = {_span_of(c.cases for c in few)})" if few else "",
                (f"{len(open_) - len(few)} whose interval straddles its limit" if len(few) < len(open_) else "")]))
            reasons.append(f"{len(open_)} inconclusive at {_confidence():.0%} ({why}: {_tally(open_, words=False)}"
                           f"{_would_decide(open_)})")
        reasons += odd
        word = (DISAGREES if fails else UNTESTED if not passes else
                CAVEATS if (skips or idle or odd or open_) else AGREES)
        out[name] = (word, reasons)
    return out


def _where_never_lifted(results: Results, name: str) -> str:
    """Where an engine's single histories were not exercised, in words: "the block never
    lifted on the isolated base, under any motion" when a whole base was (a museum's bust on
    its isolator stays still at the site's PGA: its contact was not tested there, issue 39),
    else how many of the histories."""
    idle_by_base, all_by_base = {}, {}
    for sc in results.scenarios:
        base = "fixed base" if sc.system.fixed_base else "isolated base"
        mine = [c for c in results.checks if c.engine == name and c.scenario == sc.name]
        if mine:
            all_by_base[base] = all_by_base.get(base, 0) + 1
            idle_by_base[base] = idle_by_base.get(base, 0) + all(c.status == NOT_EXERCISED for c in mine)
    whole = [b for b in all_by_base if idle_by_base[b] == all_by_base[b]]
    if whole:
        return " and ".join(f"{_subject(results)} never lifted on the {b} under any motion" for b in whole)
    idle = sum(idle_by_base.values())
    return f"{_subject(results)} never lifted in {idle} of {sum(all_by_base.values())} histories" if idle else ""


def _subject(results: Results) -> str:
    """"the statue" or "the block": what the report's system is (System.subject)."""
    return results.scenarios[0].system.subject if results.scenarios else "the block"


def _how_many_not_judged(results: Results, name: str) -> str:
    """" (12 of 30 checks not exercised, 2 skipped)": how much of an engine's 'agrees with
    caveats' was not judged, in the verdict line itself (issue 25)."""
    mine = [c for c in results.checks if c.engine == name]
    said = [f"{n} {word}" for n, word in
            ((sum(c.status == st for c in mine), word) for st, word in
             ((NOT_EXERCISED, "not exercised"), ("skip", "skipped"), (INCONCLUSIVE, "inconclusive"))) if n]
    if not said:
        return ""
    where = _where_never_lifted(results, name) if said[0].endswith("not exercised") else ""
    count, word = said[0].split(" ", 1)
    rest = ", ".join(said[1:])
    return (f" ({count} of {len(mine)} checks {word}" + (f": {where}" + (f"; {rest}" if rest else "") if where
                                                          else "".join(", " + x for x in said[1:])) + ")")


def verdict(results: Results) -> str:
    """The one-line verdict: the report's first line, the terminal's last, metrics.json's `verdict`."""
    checks = results.checks
    n_pass = sum(c.status == "pass" for c in checks)
    n_skip = sum(c.status == "skip" for c in checks)
    n_idle = sum(c.status == NOT_EXERCISED for c in checks)
    stats = [c for c in checks if c.interval is not None]
    failed = results.failed
    engines = "; ".join(f"{_label(n)} {word}{_how_many_not_judged(results, n) if word == CAVEATS else ''}"
                        for n, (word, _) in engine_verdicts(results).items() if n != REFERENCE)
    skipped_engines = f" Engines skipped: {', '.join(results.skipped)}." if results.skipped else ""
    n_open = sum(c.status == INCONCLUSIVE for c in checks)
    # every check not made is in the count, by why (issue 39: the inconclusive ones were missing)
    n_else = len(checks) - n_pass - len(failed) - n_skip - n_idle - n_open
    tail = (f"({n_skip} skipped, {n_idle} not exercised, {n_open} inconclusive"
            + (f", {n_else} without a value" if n_else else "") + ")")
    if stats:  # what the ensembles decided, per engine and quantity, and with what confidence
        per_engine = "; ".join(f"{_label(n)} {_tally([c for c in stats if c.engine == n])}"
                               for n in dict.fromkeys(c.engine for c in stats))
        open_ = [c for c in stats if c.status == INCONCLUSIVE]
        tail += (f"; ensembles judged at {_confidence():.0%} confidence, the interval against the limit: "
                 f"{per_engine}{_would_decide(open_)}")
    if failed:
        worst = ", ".join(sorted({f"{c.engine} {c.metric}" for c in failed}))
        head = f"Result: FAILED — {len(failed)} of {len(checks)} checks failed ({worst}) {tail}"
    elif n_pass == 0:
        head = f"Result: nothing was tested — no check could be made {tail}"
    elif n_pass < len(checks):  # the checks not made are as many as the line says, not hidden by "all"
        head = f"Result: all {n_pass} checks made passed, {len(checks) - n_pass} of {len(checks)} not made {tail}"
    else:
        head = f"Result: all {n_pass} checks passed {tail}"
    return f"{head}. {engines}.{skipped_engines}" if engines else f"{head}.{skipped_engines}"


#: What each statistical check decides, in the verdict line's words.
DECIDES = {"ensemble_overturn_median": "overturning median", "ensemble_overturn_dispersion": "overturning dispersion",
           "ensemble_theta_max_diff": "median θmax/α"}
_WORDS = {"pass": "agrees", "fail": "DISAGREES", INCONCLUSIVE: "inconclusive"}


def _tally(checks, words: bool = True) -> str:
    """Statistical checks counted per quantity and outcome: 'overturning median 2 agrees,
    median θmax/α 1 inconclusive' (words=False: the quantities only, with their counts)."""
    out = []
    for metric in dict.fromkeys(c.metric for c in checks):
        mine = [c for c in checks if c.metric == metric]
        name = DECIDES.get(metric, metric)
        if not words:
            out.append(f"{name} ×{len(mine)}" if len(mine) > 1 else name)
            continue
        counts = {w: sum(_WORDS.get(c.status, c.status) == w for c in mine) for w in dict.fromkeys(
            _WORDS.get(c.status, c.status) for c in mine)}
        out.append(f"{name} " + ", ".join(f"{k} {w}" for w, k in counts.items()))
    return ", ".join(out)


def _would_decide(open_) -> str:
    """The ensemble sizes the inconclusive checks name, as a range against the cases run."""
    need = sorted({c.n_needed for c in open_ if c.n_needed})
    if not need:
        return ""
    return (f" (about {_span_of(need)} cases would decide the inconclusive; this run judged "
            f"{_span_of(c.cases for c in open_ if c.cases)})")


def scorecard(results: Results) -> tuple[list, list]:
    """One row per family of checks, one column per engine: PASS/FAIL, how many passed,
    the worst value against its tolerance with the margin left, and how many were not
    judged (skipped: a chaotic reference; not exercised: nothing lifted the block)."""
    header = ["checks"] + [_label(n) for n in results.engines]
    rows = []
    for title, metrics in FAMILIES:
        row = [title]
        for name in results.engines:
            mine = [c for c in results.checks if c.engine == name and c.metric in metrics]
            row.append(_score(mine) if mine else "")
        if any(row[1:]):
            rows.append(row)
    return header, rows


def _score(checks) -> str:
    judged = [c for c in checks if c.status in ("pass", "fail")]
    n_fail = sum(c.status == "fail" for c in judged)
    with_margin = [(m, c) for c in judged if (m := _margin(c)) is not None]
    parts = []
    if judged:
        parts.append(f"{'FAIL' if n_fail else 'PASS'} {len(judged) - n_fail}/{len(judged)}")
        if with_margin:
            worst = min(with_margin, key=lambda x: x[0])[1]
            if worst.interval is not None:
                lo, hi = worst.interval
                where = "within" if worst.status == "pass" else "beyond"
                parts.append(f"worst [{lo:+.3g}, {hi:+.3g}] {where} ±{worst.limit:g} at {_confidence():.0%}")
            else:
                sign = {"max": "≤", "min": "≥", "equal": "="}[worst.kind]
                parts.append(f"worst {_f(worst.value, '.3g')} {sign} {worst.limit:g} ({_margin_text(worst)})")
        elif n_fail:
            parts.append("not measured")
    else:
        parts.append("SKIP")
    n_skip = sum(c.status == "skip" for c in checks)
    n_idle = sum(c.status == NOT_EXERCISED for c in checks)
    for c in checks:
        if c.status == INCONCLUSIVE:
            lo, hi = c.interval
            parts.append(f"inconclusive [{lo:+.3g}, {hi:+.3g}] against ±{c.limit:g}"
                         + (f" (n = {c.cases}: too few cases for an interval)" if _too_few(c) else ""))
    if n_skip:
        parts.append(f"{n_skip} skipped")
    if n_idle:
        parts.append(f"{n_idle} not exercised")
    return " · ".join(parts)


def _too_few(c) -> bool:
    """An inconclusive check whose ensemble had too few cases for any interval (core.verdict's
    min_cases): its 'interval' may lie wholly inside the limit and still decide nothing (issue 39)."""
    return c.status == INCONCLUSIVE and TOO_FEW_CASES in (c.note or "")


def _span_of(values) -> str:
    """'5' or '5–12': the smallest and largest of whole numbers (None left out)."""
    v = sorted({x for x in values if x is not None})
    return "?" if not v else f"{v[0]}" if len(v) == 1 else f"{v[0]}–{v[-1]}"


def _interval_cell(c) -> str:
    """A statistical check as 'estimate [lo, hi] / ±limit: word'."""
    if c is None:
        return "–"
    if c.interval is None:
        return c.status
    word = {"pass": "agrees", "fail": "disagrees"}.get(c.status, c.status)
    return f"{c.value:+.3f} [{c.interval[0]:+.3f}, {c.interval[1]:+.3f}] / ±{c.limit:g}: {word}"


def _confidence() -> float:
    return limit("verdict_confidence")


def _margin_text(c) -> str:
    m = _margin(c)
    if c.kind == "equal":
        return "holds" if m == 0 else "broken"
    return f"margin {m * 100:.0f}%"


# --- the report's blocks -------------------------------------------------------------------

def summary_rows(results: Results):
    """The evidence table: one row per scenario and engine."""
    rows = []
    for sc in results.scenarios:
        for name in results.engines:
            tr, c = sc.runs.get(name), sc.comparisons.get(name)
            if tr is None:
                rows.append([sc.name, _label(name), "error: " + sc.errors.get(name, "?")] + ["–"] * 8)
                continue
            rows.append([sc.name, _label(name), str(tr.status), _f(tr.theta_max_over_alpha),
                         _f(c.theta_max_diff, "+.3f") if c else "(reference)",
                         str(tr.impact_count), _f(tr.overturned),
                         _f(c.horizon, ".2f") + ("" if c.parted else " (whole run)") if c else "–",
                         _f(tr.u_max * 100, ".2f"),
                         _f(c.beta_error_median * 100 if c and c.beta_error_median is not None else None, ".2f"),
                         _f(tr.runtime_s, ".2f")])
    header = ["scenario", "engine", "status", "θmax/α", "Δθmax/α", "impacts", "overturned", "horizon (s)",
              "max |u| (cm)", "median |β err| (%)", "runtime (s)"]
    return header, rows


def describe_system(results: Results) -> str:
    cfg = results.config
    if not cfg.own_system:
        return (f"the paper's block (H {PAPER_BLOCK['height']:.1f} m, B {PAPER_BLOCK['width']:g} m, "
                f"m = m_b = {PAPER_BLOCK['mass']:g} kg), isolated with T {PAPER_PERIOD:g} s, ξ {PAPER_DAMPING_RATIO:g} "
                "(the reading "
                "of the paper that fits its figure: the paper's own values are unreadable in our copy), and on a fixed base")
    s = cfg.system
    noun = s.subject.removeprefix("the ")
    if s.fixed_base:
        base = "a fixed base"
    elif s.isolator is None:
        base = (f"an isolated base (m_b {s.base_mass:g} kg, T {s.period:.3g} s, ξ {s.damping_ratio:.3g}), and the "
                f"same {noun} on a fixed base")
    else:  # a non-linear isolator: its kind and its own parameters, not a linear T and ξ it does not have
        params = {k: v for k, v in s.isolator.describe(s.total_mass, s.gravity).items()
                  if k != "isolator" and isinstance(v, (int, float)) and not isinstance(v, bool)}
        words = ", ".join(f"{k.replace('_', ' ')} {v:.3g}" for k, v in params.items())
        base = (f"a base of m_b {s.base_mass:g} kg on a {s.isolator_kind} isolator ({words}), and the same {noun} on "
                "a fixed base")
    if s.body is not None:  # a statue's mesh: its two edges along the shaking direction
        e = s.body
        return (f"your statue (m {s.mass:g} kg; centre of mass {e.centre_height:.3g} m up, edges b₊ "
                f"{e.lever_forward:.3g} m and b₋ {e.lever_backward:.3g} m from it, α₊ {e.alpha(1):.4g} and α₋ "
                f"{e.alpha(-1):.4g} rad) on {base}")
    return (f"your block (H {s.height:g} m, B {s.width:g} m, m {s.mass:g} kg; λ {s.slenderness:.3g}, "
            f"α {s.alpha:.4g} rad) on {base}")


def _blocks(results: Results, images: dict) -> list:
    cfg = results.config
    verdicts = engine_verdicts(results)
    B = [("h1", "Do the contact engines agree with the exact rocking model?"),
         ("verdict", verdict(results), [(_label(n), word, "; ".join(reasons)) for n, (word, reasons) in verdicts.items()
                                        if n != REFERENCE]),
         ("p", f"System: {describe_system(results)}. Motions: {'; '.join(describe_motion(sc.motion) for sc in results.scenarios[::len(cfg.bases())])}. "
               f"Reference: the analytic hybrid model (exact impacts, closed-form β). Generated {results.started} in "
               f"{results.wall_s:.0f} s ({'quick' if cfg.quick else 'full'} run).")]
    header, rows = scorecard(results)
    B.append(("h2", "Scorecard: the worst of each family of checks"))
    B.append(("table", header, rows))
    B.append(("p", "Each cell: checks passed, the worst value against its tolerance and the margin left (how far "
                   "inside the limit, as a share of it; negative: outside). Skipped: the analytic history is "
                   "chaotic there (θmax/α moves a lot under ±1% of PGA), so the ensemble judges it. Not exercised: "
                   f"no engine lifted {_subject(results)}, so nothing about contact was tested; counted apart, never passed. "
                   "Every tolerance and its reason is in the folded table at the end (and in isorock's validate/core/tolerances.py)."))
    B.append(("h2", "Where the engines part from the analytic model"))
    for sc, key in zip(results.scenarios, images["histories"]):
        B.append(("img", key, f"{sc.name}: ground acceleration, θ/α of every engine, each engine − analytic, "
                              f"a zoom on the rocking window, and the base displacement (or θ̇ on a fixed base) "
                              f"with its difference."
                              + (" The paper's Figure 5 shows this record." if is_kobe(sc.motion) else "")))
        if not sc.exercised:
            B.append(("p", f"{sc.name}: {sc.why_not_exercised()}."))
    B.append(("img", images["ensemble"], "θmax/α over the motion scaled in amplitude (from just above the scale "
                                         f"at which {_subject(results)} first lifts), and each engine − analytic with its "
                                         "tolerance on the median; × marks overturning."))
    B.append(("img", images["beta_per_impact"], "Effective β of every counted impact against the closed form, "
                                                "free rocking, judged against each engine's tolerance (dashed), "
                                                "and the forced histories, shown but not judged (the closed form "
                                                "is free rocking's)."))
    B.append(("h2", "Evidence"))
    header, rows = summary_rows(results)
    B.append(("table", header, rows))
    B.append(("p", "Δ is engine − analytic. The horizon is the first time |Δθ| > 0.1α (histories on a 1 ms grid). "
                   "β errors are per counted impact, effective β (states 30 ms outside the contact mapped to θ = 0 "
                   "with the rigid equations) against the closed form."))
    for sc in results.scenarios:
        s = sc.sensitivity
        B.append(("p", f"{sc.name}: analytic θmax/α {', '.join(f'{v:.3f}' for v in s['theta_max_over_alpha'])} "
                       f"at ×0.99, ×1, ×1.01 PGA — "
                       f"{'robust, single-history checks apply' if sc.robust else 'sensitive, so single-history checks are skipped and the ensemble decides'}."))
    if results.sliding:
        B.append(("h2", "Where the statue slides"))
        B.append(("p", "The paper's block on a fixed base with a statue friction below its tanα: it slides under the "
                       "report's motions and never lifts (docs/sliding.md). Judged by the slide rows of the tolerance "
                       "table: the largest and final slide in units of b, the slide's onset (the first time it has "
                       "slid 0.01·b) in units of 1/p, and the modes each run went through in order. Nearer tanα (μ_s/tanα 0.6–1) MuJoCo's soft contact tilts "
                       "a fast-sliding block and parts from the exact model; PyBullet and Drake do not "
                       "(docs/sliding_engines.md)."))
        B.append(("table", ["scenario", "engine", "status", "slide max (cm)", "final (cm)", "onset (s)", "θmax/α",
                            "modes"], sliding_rows(results)))
    kobe = [sc for sc in results.scenarios if is_kobe(sc.motion)]
    if kobe and not cfg.own_system:
        B += paper_blocks(results, kobe, _f)
    B.append(("h2", "Free rocking: effective β" + ("" if cfg.own_system else " (the paper's Figure 4)")))
    if "beta_slenderness" in images:
        B.append(("img", images["beta_slenderness"], "β and β₂/h against slenderness: closed form (lines), "
                                                      "contact engines' effective values (markers); the paper's "
                                                      "Figure 4."))
    B.append(("table", ["engine", "case", "β closed", "β effective", "|β err| max (%)", "β₂/h closed",
                        "β₂/h effective", "first impact (s)", "impacts used"],
              [[_label(r["engine"]), r["scenario"], _f(r.get("beta_closed"), ".4f"), _f(r.get("beta"), ".4f"),
                _f(r.get("beta_rel_error", math.nan) * 100 if r.get("beta_rel_error") is not None else None, ".3f"),
                _f(r.get("beta2_over_h_closed"), ".4f") if not r["fixed_base"] else "–",
                _f(r.get("beta2_over_h"), ".4f"), _f(r.get("first_impact_time"), ".4f"),
                str(r.get("impacts_used", "–")) if not r["error"] else "error: " + r["error"]]
               for r in results.free]))
    B.append(("h2", "Agreement horizons"))
    B.append(("table", ["history", "engine", "horizon (s)", "× 1/p", "impacts before it", "parted"],
              [[sc.name, name if name == OWN else _label(name), _f(h["s"], ".2f"), _f(h["p_units"], ".1f"),
                str(h["impacts"]), _f(h["parted"])]
               for sc in results.scenarios for name, h in sc.horizons.items()]))
    B.append(("p", "How long each engine's θ stays within 0.1·α of the analytic model's before they part, in "
                   "seconds, in units of 1/p (p = √(3g/4R)) and in the model's counted impacts; and the analytic "
                   f"model's own horizon with the motion scaled by ±0.5% ('{OWN}'). An engine whose horizon "
                   "reaches the model's own has done all that physics allows: beyond it, histories part by chaos."))
    B.append(("h2", "Ensembles"))
    ens_rows = []
    for sc, ens in zip(results.scenarios, results.ensembles):
        for name, a in ens.as_dict()["agreement"].items():
            by = {c.metric: c for c in results.checks if c.engine == name and c.scenario == f"ensemble {sc.name}"}
            ens_rows.append([f"{ens.motion}, {'fixed' if ens.system.fixed_base else 'isolated'} base", _label(name),
                             f"{ens.rocking_count()} of {a['cases']}",
                             *(_interval_cell(by.get(m)) for m in ("ensemble_overturn_median",
                                                                   "ensemble_overturn_dispersion",
                                                                   "ensemble_theta_max_diff")),
                             _f(a["overturn_agreement"] * 100, ".0f") + " %",
                             f"{_f(a['median_theta_max_diff_rocking'])} ({a['rocking_cases']})"])
    B.append(("table", ["ensemble", "engine", "cases that rock",
                        f"ln(median ratio) of the overturning fragility, {_confidence():.0%} interval",
                        "Δ dispersion β", "Δ median θmax/α, robust rocking cases",
                        "overturning as the model (not judged)", "median |Δθmax/α|, robust rocking cases (n)"],
              ens_rows))
    B.append(("p", f"Each ensemble is judged as statistics (core/verdict.py): a contact engine disagrees only "
                   f"when the {_confidence():.0%} bootstrap interval (over the ensemble's cases, engine and model "
                   "paired) of its difference from the model lies wholly beyond the tolerance table's limit, agrees "
                   "when it lies wholly within, and is otherwise inconclusive, with the ensemble size that would "
                   "decide (the interval narrows as 1/√n). The fraction of cases overturning as the model is shown "
                   "for reference only: it flips with the sample."))
    B.append(("p", "θmax/α is capped at 1 (overturned) before differencing. Robust rocking cases: the analytic "
                   "block rocks (θmax/α > 0.01), neither overturns, and the analytic θmax/α moves by less than "
                   "0.05 under ±1% of the motion (a chaotic peak tests no engine)."))
    B.append(("h2", "Engines and settings"))
    B.append(("table", ["engine", "status", "settings"],
              [[_label(n), "ok", ", ".join(f"{k}={v}" for k, v in engine_settings(results)[n].items())]
               for n in results.engines] + [[n, "SKIPPED", why] for n, why in results.skipped.items()]))
    B.append(("details", f"All {len(results.checks)} checks, by family (the reason for each tolerance once per family)",
              _check_blocks(results)))
    B.append(("h2", "Versions"))
    B.append(("table", ["package", "version"], [[k, v] for k, v in results.versions.items()]))
    B.append(("p", verdict(results)))
    return B


def _check_blocks(results: Results) -> list:
    out = []
    for title, metrics in FAMILIES + (("other", ()),):
        mine = [c for c in results.checks if family_of(c.metric) == title or (title == "other" and
                                                                                family_of(c.metric) == c.metric)]
        if not mine:
            continue
        out.append(("h3", title))
        for reason_key in dict.fromkeys((c.engine, c.metric) for c in mine):
            c0 = next(c for c in mine if (c.engine, c.metric) == reason_key)
            out.append(("p", f"{_label(c0.engine)}, {c0.metric} "
                             f"({ {'max': '≤', 'min': '≥', 'equal': '=', 'within': '±'}[c0.kind]} {c0.limit:g}): {c0.reason}"))
        out.append(("table", ["result", "engine", "metric", "scenario", "value", "note"],
                    [[c.status.upper(), _label(c.engine), c.metric, c.scenario, _f(c.value, ".4g"), c.note]
                     for c in mine]))
    return out


def engine_settings(results: Results) -> dict:
    """Each engine's Settings as given, derived settings included (per system: each
    scenario's `settings` in metrics.json)."""
    return {name: describe_settings(s) for name, s in results.settings.items()}


# --- rendering -----------------------------------------------------------------------------

def render_markdown(blocks) -> str:
    out = []
    for b in blocks:
        kind = b[0]
        if kind in ("h1", "h2", "h3"):
            out.append(f"{'#' * int(kind[1])} {b[1]}\n")
        elif kind == "p":
            out.append(f"{b[1]}\n")
        elif kind == "verdict":
            out.append(f"**{b[1]}**\n")
            out += [f"- **{label} {word}**" + (f" — {why}" if why else "") for label, word, why in b[2]]
            out.append("")
        elif kind == "img":
            out.append(f"![{b[2]}]({b[1]})\n\n*{b[2]}*\n")
        elif kind == "table":
            header, rows = b[1], b[2]
            out.append("| " + " | ".join(map(markdown_cell, header)) + " |")
            out.append("|" + "---|" * len(header))
            out += ["| " + " | ".join(map(markdown_cell, r)) + " |" for r in rows]
            out.append("")
        elif kind == "details":
            out.append(f"<details><summary>{b[1]}</summary>\n")
            out.append(render_markdown(b[2]))
            out.append("</details>\n")
    return "\n".join(out) + "\n"


def _html_body(blocks, folder: Path) -> list:
    e = html.escape
    body = []
    for b in blocks:
        kind = b[0]
        if kind in ("h1", "h2", "h3"):
            body.append(f"<{kind}>{e(b[1])}</{kind}>")
        elif kind == "p":
            body.append(f"<p>{e(b[1])}</p>")
        elif kind == "verdict":
            cls = "fail" if b[1].startswith("Result: FAILED") else "pass" if "checks passed" in b[1] else "skip"
            lines = "".join(f'<li class="{_word_css(word)}"><b>{e(label)} {e(word)}</b>'
                            + (f" — {e(why)}" if why else "") + "</li>" for label, word, why in b[2])
            body.append(f'<div class="verdict {cls}"><p><b>{e(b[1])}</b></p><ul>{lines}</ul></div>')
        elif kind == "img":
            data = base64.b64encode((folder / b[1]).read_bytes()).decode("ascii")
            body.append(f'<figure><img src="data:image/png;base64,{data}" alt="{e(b[2])}">'
                        f"<figcaption>{e(b[2])}</figcaption></figure>")
        elif kind == "table":
            head = "".join(f"<th>{e(str(h))}</th>" for h in b[1])
            rows = "".join("<tr>" + "".join(f'<td class="{_css(c)}">{e(str(c))}</td>' for c in r) + "</tr>"
                           for r in b[2])
            body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>")
        elif kind == "details":
            body.append(f"<details><summary>{e(b[1])}</summary>" + "\n".join(_html_body(b[2], folder))
                        + "</details>")
    return body


def render_html(blocks, folder: Path) -> str:
    css = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4;padding:0 1em}"
           "h1{font-size:1.6em;margin-bottom:0.3em}"
           ".verdict{border-radius:6px;padding:0.4em 1em;margin:0.8em 0}.verdict ul{margin:0.3em 0}"
           ".verdict.pass{background:#e8f6e8;border:1px solid #7c7}.verdict.fail{background:#fbe5e5;border:1px solid #d77}"
           ".verdict.skip{background:#f1f1f1;border:1px solid #bbb}"
           "li.agrees{color:#185c18}li.caveats{color:#7a5a00}li.disagrees{color:#a01010}li.untested{color:#555}"
           "table{border-collapse:collapse;font-size:0.85em;margin:1em 0}"
           "td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}"
           "td.fail{background:#fdd;font-weight:bold}td.pass{background:#dfd}td.skip{background:#eee}"
           "img{max-width:100%}figcaption{font-size:0.85em;color:#444}"
           "details{margin:1em 0}summary{cursor:pointer;font-weight:bold}")
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>isorock validation report</title>"
            f"<style>{css}</style></head><body>\n" + "\n".join(_html_body(blocks, folder)) + "\n</body></html>\n")


def _css(cell) -> str:
    text = str(cell)
    for word, cls in (("PASS", "pass"), ("FAIL", "fail"), ("SKIP", "skip"), (NOT_EXERCISED.upper(), "skip"),
                      (INCONCLUSIVE.upper(), "skip")):
        if text == word or text.startswith(word + " "):
            return cls
    return ""


def _word_css(word: str) -> str:
    return {AGREES: "agrees", CAVEATS: "caveats", DISAGREES: "disagrees", UNTESTED: "untested"}[word]


# --- machine-readable -----------------------------------------------------------------------

def metrics(results: Results) -> dict:
    """metrics.json: everything the tables show, machine-readable."""
    def cfg(c):
        out = {}
        for f in fields(c):
            v = getattr(c, f.name)
            out[f.name] = (list(v) if isinstance(v, tuple) else v.describe() if hasattr(v, "describe") else v)
        return out
    out = {
        "verdict": verdict(results),
        "engine_verdicts": {n: {"verdict": w, "reasons": r} for n, (w, r) in engine_verdicts(results).items()},
        "passed": not results.failed,
        "provenance": provenance(record_paths=list(results.record_paths)),
        "config": cfg(results.config),
        "started": results.started, "wall_s": results.wall_s, "versions": results.versions,
        "engines": {**{n: "ok" for n in results.engines}, **{n: f"skipped: {w}" for n, w in results.skipped.items()}},
        "engine_settings": engine_settings(results),
        "free_rocking": results.free,
        "scenarios": [{
            "name": sc.name, "motion": sc.motion.describe(), "system": sc.system.describe(),
            "duration": sc.duration, "sensitivity": sc.sensitivity, "robust": sc.robust,
            "exercised": sc.exercised, "base_acceleration_peak": sc.base_acceleration_peak,
            "runs": {n: tr.summary() for n, tr in sc.runs.items()}, "errors": sc.errors,
            # the numbers each engine used on this system (MuJoCo's and PyBullet's follow it)
            "settings": {n: describe_settings(results.settings[n], sc.system, sc.duration)
                         for n in sc.runs if n in results.settings},
            "comparisons": {n: c.as_dict() for n, c in sc.comparisons.items()},
            "agreement_horizons": sc.horizons,
        } for sc in results.scenarios],
        "ensembles": [e.as_dict() for e in results.ensembles],
        "checks": [c.as_dict() for c in results.checks],
    }
    if results.sliding:
        out["sliding"] = [{"name": sc.name, "motion": sc.motion.describe(), "system": sc.system.describe(),
                           "duration": sc.duration, "exercised": sc.exercised,
                           "runs": {n: tr.summary() for n, tr in sc.runs.items()}, "errors": sc.errors,
                           "comparisons": {n: c.as_dict() for n, c in sc.comparisons.items()}}
                          for sc in results.sliding]
    kobe = [sc for sc in results.scenarios if is_kobe(sc.motion)]
    if kobe and not results.config.own_system:
        out["paper_figure5"] = {
            ("fixed base" if sc.system.fixed_base else "isolated base"): {
                "paper_theta_max_over_alpha": PAPER_FIGURE5["fixed base" if sc.system.fixed_base else "isolated base"],
                **{n: tr.theta_max_over_alpha for n, tr in sc.runs.items()}} for sc in kobe}
    return out


def beta_series(results: Results):
    """Figure panels of per-impact β errors: free rocking (the paper's block, or the
    user's), and every impact of the forced histories."""
    own = results.config.own_system
    free = [(r["scenario"] if own else ("isolated" if not r["fixed_base"] else "fixed"), r["engine"],
             r["beta_errors_all"])
            for r in results.free if r["engine"] != REFERENCE and not r["error"]
            and (own or (abs(r["slenderness"] - PAPER_SLENDERNESS) < 1e-9 and r["mass_ratio"] in (0.0, 1.0)))]
    forced = [(sc.name, name, list(c.beta_errors)) for sc in results.scenarios
              for name, c in sc.comparisons.items()]
    return [("free rocking from 0.5α", free),
            ("forced histories", forced, FORCED_BETA_NOTE)]


#: Why the forced histories' β is drawn but not judged (no dashed tolerance on that panel):
#: the closed form is the impact of a block rocking freely; under ground motion the state
#: 30 ms either side of the impact also moves with the ground, so β_eff there measures more
#: than the impact (model.md, "effective β").
FORCED_BETA_NOTE = ("not judged: the closed-form β is free rocking's; under ground motion the states "
                    "either side of an impact move with the ground too")


def _bands(results: Results, metric: str) -> dict:
    return {n: tolerance(n.partition(":")[0], metric).limit for n in results.engines
            if n != REFERENCE and has_tolerance(n.partition(":")[0], metric)}


def write_report(results: Results, out_dir) -> None:
    """report.md, report.html (figures embedded), the PNGs and metrics.json, written
    into a temporary folder that replaces out_dir only when all of it is done."""
    def fill(tmp: Path):
        images = {"beta_per_impact": "beta_per_impact.png", "ensemble": "ensemble.png", "histories": []}
        if not results.config.own_system:
            images["beta_slenderness"] = "fig4_beta_slenderness.png"
            figures.beta_slenderness([r for r in results.free if r["engine"] != REFERENCE and not r["error"]
                                      and not r["fixed_base"]], tmp / images["beta_slenderness"])
        figures.beta_per_impact(beta_series(results), tmp / images["beta_per_impact"],
                                bands=_bands(results, "beta_rel_error"))
        figures.ensemble(results.ensembles, tmp / images["ensemble"],
                         bands=_bands(results, "ensemble_theta_max_diff"))
        for k, sc in enumerate(results.scenarios, 1):
            name = f"history_{k}.png"
            figures.history(sc.motion, sc.runs, tmp / name,
                            title=f"Every engine against the analytic model: {sc.name}")
            images["histories"].append(name)
        blocks = _blocks(results, images)
        (tmp / "report.md").write_text(render_markdown(blocks), encoding="utf-8")
        (tmp / "report.html").write_text(render_html(blocks, tmp), encoding="utf-8")
        write_json(tmp / "metrics.json", metrics(results))
    write_folder_atomic(out_dir, fill)
