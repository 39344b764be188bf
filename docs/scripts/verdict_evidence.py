"""Issue 20's evidence from `isorock validate` report folders (their metrics.json): the
statistical verdicts of quick and full runs side by side, the agreement horizons against
the model's own, and the recorded outcomes the tests judge quick against full on.

    # the runs (docs/validation.md, "Verdicts over the paper's motions"), then:
    python docs/scripts/verdict_evidence.py tables  QUICK_DIR FULL_DIR [QUICK_DIR FULL_DIR ...]
    python docs/scripts/verdict_evidence.py record  tests/data/ensemble_outcomes.json QUICK_DIR FULL_DIR ...

`tables` prints Markdown: one row per ensemble (motion × base) and engine, per judged
quantity the quick run's word, interval and cases (and the cases that would decide) → the
full run's, and whether quick contradicts full (it never may); then the horizons of every history of the full runs. `record` keeps
each ensemble's per-case outcomes (scales, θmax/α, overturned, robustness) of every engine
and the report's own statuses, for tests/test_verdict.py.
"""
import json
import math
import sys
from pathlib import Path

OWN = "model under ±0.5% of the motion"
QUANTITIES = {"ensemble_overturn_median": "ln(median ratio)", "ensemble_overturn_dispersion": "Δ dispersion β",
              "ensemble_theta_max_diff": "Δ median θmax/α"}
LABELS = {"mujoco": "MuJoCo", "bullet": "PyBullet"}


def load(folder) -> dict:
    return json.loads((Path(folder) / "metrics.json").read_text())


def statistical(m: dict) -> dict:
    """(ensemble scenario, engine, metric) → check, for the checks a verdict judged (or
    that were not exercised / skipped in a statistical family)."""
    return {(c["scenario"], c["engine"], c["metric"]): c for c in m["checks"] if c["metric"] in QUANTITIES}


def cell(c) -> str:
    if c is None:
        return "–"
    word = {"pass": "agrees", "fail": "DISAGREES"}.get(c["status"], c["status"])
    if c["interval"] is None:
        return word
    lo, hi = c["interval"]  # JSON keeps ±inf as null: an open side
    lo_s = "−∞" if lo is None else f"{lo:+.3f}"
    hi_s = "+∞" if hi is None else f"{hi:+.3f}"
    cases = c.get("cases") or _cases_from_note(c["note"])
    need = c.get("n_needed") or _need_from_note(c["note"])
    return f"{word} [{lo_s}, {hi_s}] n {cases}" + (f" (~{need})" if need else "")


def _cases_from_note(note: str):
    # reports made before Check carried `cases`: "… over 21 cases: …"
    after = note.split(" over ", 1)
    return after[1].split(" cases", 1)[0] if len(after) > 1 else "?"


def _need_from_note(note: str):
    if "cases would decide" not in note:
        return None
    return note.split("(about ", 1)[1].split(" cases", 1)[0]


def contradicts(q, f) -> bool:
    """Quick decided, and otherwise than full did."""
    if q is None or f is None:
        return False
    decided = ("pass", "fail")
    return q["status"] in decided and f["status"] in decided and q["status"] != f["status"]


def verdict_table(pairs) -> list[str]:
    """One row per ensemble (motion × base) and engine; per judged quantity the quick run's
    verdict → the full run's, and whether any quick verdict contradicts the full one."""
    head = " | ".join(f"{q}: quick → full" for q in QUANTITIES.values())
    lines = [f"| motion | base | engine | {head} | quick contradicts full |", "|---|---|---|" + "---|" * 4]
    for quick, full in pairs:
        q_checks, f_checks = statistical(quick), statistical(full)
        rows = dict.fromkeys((s, e) for s, e, _ in f_checks)
        for scenario, engine in sorted(rows, key=lambda k: (k[0], k[1] != "mujoco")):
            motion, _, base = scenario[len("ensemble "):].rpartition(", ")
            cells, bad = [], False
            for metric in QUANTITIES:
                q, f = q_checks.get((scenario, engine, metric)), f_checks.get((scenario, engine, metric))
                cells.append(f"{cell(q)} → {cell(f)}")
                bad |= contradicts(q, f)
            lines.append(f"| {motion} | {base} | {LABELS.get(engine, engine)} | {' | '.join(cells)} | "
                         f"{'YES' if bad else 'no'} |")
    return lines


def horizon_table(fulls) -> list[str]:
    lines = ["| history | MuJoCo: s, × 1/p, impacts | PyBullet: s, × 1/p, impacts | model's own (±0.5%) | "
             "reaches the model's own? |", "|---|---|---|---|---|"]

    def h(x):
        return (f"{x['s']:.2f} s, {x['p_units']:.1f}, {x['impacts']}"
                + ("" if x["parted"] else " (whole run)")) if x else "–"
    for m in fulls:
        for sc in m["scenarios"]:
            hz = sc["agreement_horizons"]
            own = hz.get(OWN)
            reach = ", ".join(f"{LABELS.get(e, e)} {'yes' if hz[e]['s'] >= own['s'] - 1e-9 else 'no'}"
                              for e in ("mujoco", "bullet") if e in hz) if own else "–"
            lines.append(f"| {sc['name']} | {h(hz.get('mujoco'))} | {h(hz.get('bullet'))} | {h(own)} | {reach} |")
    return lines


def record(out, pairs) -> None:
    """Each ensemble's per-case outcomes and the report's statuses, quick and full."""
    data = {"made_by": "docs/scripts/verdict_evidence.py record", "ensembles": []}
    for quick, full in pairs:
        for kind, m in (("quick", quick), ("full", full)):
            checks = statistical(m)
            for e in m["ensembles"]:
                base = "fixed base" if e["fixed_base"] else "isolated base"
                scenario = f"ensemble {e['motion']}, {base}"
                data["ensembles"].append({
                    "run": kind, "motion": e["motion"], "base": base, "scales": e["scales"],
                    "theta_max_over_alpha": e["theta_max_over_alpha"], "overturned": e["overturned"],
                    "robust": e["robust"],
                    "statuses": {f"{eng} {met}": c["status"] for (s, eng, met), c in checks.items() if s == scenario}})
    Path(out).write_text(json.dumps(data, indent=1, allow_nan=False) + "\n", encoding="utf-8")


def main(argv):
    if len(argv) < 2 or argv[0] not in ("tables", "record"):
        sys.exit(__doc__)
    if argv[0] == "record":
        out, folders = argv[1], argv[2:]
    else:
        out, folders = None, argv[1:]
    if len(folders) % 2:
        sys.exit("folders come in pairs: QUICK_DIR FULL_DIR")
    pairs = [(load(folders[i]), load(folders[i + 1])) for i in range(0, len(folders), 2)]
    if out:
        record(out, pairs)
        return
    print("\n".join(verdict_table(pairs)))
    print()
    print("\n".join(horizon_table([f for _, f in pairs])))


if __name__ == "__main__":
    main(sys.argv[1:])
