"""The paper's Figure 5 (Roussis et al. 2008: Kobe JMA N-S, first 40 s) beside ours: its
numbers and the prose that explains where and why they differ (model.md, "The paper's
numerical example"). Only the report reads it.
"""
from __future__ import annotations

from ...analytic.motion import GroundMotion
from ..core.engines import REFERENCE

#: The paper's θmax/α for the Kobe JMA N-S record (Figure 5).
PAPER_FIGURE5 = {"fixed base": 0.95, "isolated base": 0.64}


def is_kobe(motion: GroundMotion) -> bool:
    return "KOBE" in motion.name.upper()


def paper_blocks(results, kobe, fmt):
    """Report blocks (see report_render) comparing the Kobe runs with the paper's figure;
    `fmt(value, format)` formats a number or a missing value."""
    B = [("h2", "The paper's Figure 5 (Kobe JMA N-S, first 40 s)")]
    rows = []
    for sc in kobe:
        base = "fixed base" if sc.system.fixed_base else "isolated base"
        for name in results.engines:
            tr = sc.runs.get(name)
            rows.append([base, name, fmt(PAPER_FIGURE5[base], ".2f"),
                         ("≥ 1 (overturned: " + fmt(tr.theta_max_over_alpha, ".2f") + " as it falls on its side)")
                         if tr and tr.overturned else fmt(tr.theta_max_over_alpha) if tr else "error",
                         fmt(tr.overturned) if tr else "–", str(tr.impact_count) if tr else "–"])
    B.append(("table", ["base", "engine", "paper θmax/α", "ours θmax/α", "overturned", "impacts"], rows))
    ours = {("fixed" if sc.system.fixed_base else "isolated"): sc.runs.get(REFERENCE) for sc in kobe}
    iso, fix = ours.get("isolated"), ours.get("fixed")
    iso_text = f"{iso.theta_max_over_alpha:.2f}" if iso else "not run"
    fix_text = ("overturns at t = " + format(fix.overturn_time, ".2f") + " s" if fix and fix.overturned
                else f"reaches {fix.theta_max_over_alpha:.2f}" if fix else "not run")
    diffs = [abs(c.theta_max_diff) for sc in kobe for c in sc.comparisons.values()]
    agree = [c.overturn_agree for sc in kobe for c in sc.comparisons.values()]
    if not diffs:
        engines_text = "No contact engine ran."
    elif max(diffs) < 0.05 and all(agree):
        engines_text = (f"The contact engines follow the analytic model (|Δθmax/α| ≤ {max(diffs):.3f}, same "
                        "overturning), so the differences from the paper lie in the inputs and the chaos, "
                        "not in the engines.")
    else:
        engines_text = (f"The contact engines differ from the analytic model here (|Δθmax/α| up to "
                        f"{max(diffs):.3f}{'' if all(agree) else ', overturning differs'}); see the ensemble "
                        "below for whether that is chaos or the engine.")
    B.append(("p", f"Analytic model here: isolated θmax/α {iso_text} against the paper's 0.64; fixed base "
                   f"{fix_text} against the paper's 0.95. {engines_text}"))
    B.append(("p", "Where and why our numbers differ from the paper's: (1) the isolation period and damping are "
                   "unreadable in our copy of the paper (\"T = ?.5 s\", \"ξ = ?\"); T 1.5 s, ξ 0.2 is the reading "
                   "that fits its figure (T 2.5 s gives no uplift at all), and the analytic peak for it is "
                   f"{iso_text}, not 0.64. (2) The response is chaotic near overturning: a 0.5% change of PGA or block width moves "
                   "the isolated θmax/α by ±10% (the sensitivity line below shows it for this run). (3) On the fixed "
                   "base the block is 'on the verge of overturning' in the paper (0.95); a careful reference "
                   "integration overturns it, so 'overturned' (θmax/α = 1) against 0.95 is a difference of one "
                   "chaotic outcome, not of the model. The qualitative finding stands: isolation keeps the block "
                   "well away from overturning with far fewer impacts."))
    return B
