"""Issue 21, task: can a held-out calibration of the rigid model reach 0.92 on both specimens?
Every attempt below is scored the same way: its parameters (the grid's point, and the
threshold on θmax/α) chosen on 4 of 5 folds by training accuracy, scored on the fifth
(nested: the choice is made afresh in each fold, study.select_cv), with the bootstrap
interval over tests of the held-out predictions. The grids are fixed here before any run;
none is narrowed after seeing a score.

Attempts (the exact rigid model, isorock.analytic's compiled kernel, on the forward-edge
equivalent block of docs/experiments.md; its impact coefficient, the angular-velocity ratio
β, is set through the kernel's packed parameters, as `with_beta` says):

- restitution: β ∈ RESTITUTION instead of Housner's 1 − 3/2 sin²α (a real granite impact
  loses energy differently from the rigid law), the default processing (20 Hz low-pass);
- lowpass: the low-pass corner ∈ LOWPASS (Hz; None: no low-pass), Housner's β;
- both: restitution × lowpass;
- shared: one β (and low-pass) for both specimens, chosen on the training folds of both
  (the same granite, table and tests), each specimen's threshold its own;
- logistic: a logistic regression of the outcome on (log θmax/α of the forward block, log
  PGV/PGA), fitted on the training folds (a statistical correction on top of the physics,
  not an engine: reported as such);
- ensemble (with RUNS, a study.json of `isorock experiments` with a hull engine on all
  tests): a logistic regression on (log θmax/α of the forward block, log of each of the
  hull engine's two signs' scores), fitted on the training folds: the rigid model errs
  towards falling where the contact engines err towards standing.

- asymmetric (`--asymmetric`, run alone): the planar model of the rock's own two edges
  (experiments/asymmetric.py, its impact map unchanged), the record's sign × the low-pass
  corner ∈ LOWPASS fitted with the threshold: the same grid as the forward block's corner.

(An earlier version of this script ran the asymmetric model's first integrator, which
dropped the rest of a step after each impact and was not converged on these records; its
numbers were void. The `--asymmetric` attempt runs the event-located one.)

Usage: nice -n 10 python docs/scripts/experiments_levers.py [DATA [RUNS]]   (about 5 min of CPU)
       nice -n 10 python docs/scripts/experiments_levers.py [DATA] --asymmetric   (about 25 s)
"""
from __future__ import annotations

import sys
import time
from contextlib import contextmanager

import numpy as np

from isorock.validate.tools.experiments import data, processing, scores, specimen, study

#: the impact's angular-velocity ratio β of the forward block: fixed values, and "housner"
#: (1 − 3/2 sin²α ≈ 0.98 here, the exact model's: the baseline). Not above it: β = 1 loses
#: nothing and a rock rocking on chatters until the kernel's event limit (test 13 failed)
RESTITUTION = (0.8, 0.85, 0.9, 0.95, "housner")

LOWPASS = (10.0, 20.0, 50.0, None)
STEPS = ("offset", "drift", "trim")  # + lowpass where a corner is given


@contextmanager
def with_beta(beta):
    """The compiled kernel run with the impact coefficient β (None: Housner's, the model's):
    its packed system parameters (analytic.physics.system_params) with β replaced."""
    from isorock.analytic import fast, physics
    original = fast._system_params
    if beta is not None:
        def patched(system, settings):
            sp = original(system, settings)
            sp[physics.BETA] = beta
            return sp
        fast._system_params = patched
    try:
        yield
    finally:
        fast._system_params = original


def run(spec, beta, accel, dts, tests):
    """(predictions, θmax/α scores) of the forward block with impact coefficient β."""
    with with_beta(None if beta == "housner" else beta):
        r = study.run_analytic(spec, accel, dts, directions=("forward",))["analytic:forward"]
    return np.array([r[t][0] for t in tests], bool), np.array([r[t][1] for t in tests], float)


def select_shared(ys: dict, candidates: dict, k=scores.FOLDS):
    """As study.select_cv, but one grid point for both specimens (the same granite, table and
    tests): in each fold the point whose training accuracy summed over the specimens is
    best, each specimen with its own threshold fitted on the training folds. ys: specimen →
    outcomes; candidates: specimen → {point: (pred, score)}. Held-out predictions per specimen."""
    first = next(iter(ys.values()))
    f = scores.folds(first.size, k)
    out = {s: np.zeros(first.size, bool) for s in ys}
    chosen = []
    for j in range(k):
        tr, te = f != j, f == j
        best = None
        for point in candidates[next(iter(ys))]:
            total, preds = 0.0, {}
            for s, y in ys.items():
                score = candidates[s][point][1]
                t = scores.best_threshold(y[tr], score[tr])
                total += ((score[tr] >= t) == y[tr]).mean()
                preds[s] = score[te] >= t
            if best is None or total > best[0]:
                best = (total, point, preds)
        for s in ys:
            out[s][te] = best[2][s]
        chosen.append(best[1])
    return out, chosen


def held_out(y, candidates):
    held, chosen = study.select_cv(y, candidates)
    m = scores.bootstrap(y, held)
    return m, chosen


def fmt(m):
    lo, hi = m["accuracy_ci"]
    return f"{m['accuracy']:.3f} [{lo:.3f}, {hi:.3f}]"


def main(folder, runs_json=None):
    start = time.perf_counter()
    outcomes, files = data.load(folder)
    tests = sorted(outcomes)
    motions = {t: data.read_test(files[t], t) for t in tests}
    dts = {t: motions[t].dt for t in tests}
    accel = {}
    for hz in LOWPASS:
        steps = STEPS + (("lowpass",) if hz else ())
        accel[hz] = {t: processing.process(motions[t].acceleration, dts[t], steps, lowpass_hz=hz or 20.0)
                     for t in tests}
    ratio = np.log(np.array([outcomes[t].pgv_over_pga_s for t in tests]))
    rows = {}
    ys, shared = {}, {}
    for s in data.SPECIMENS:
        spec = specimen.load_specimen(folder, s)
        y = np.array([outcomes[t].measured[s] for t in tests], bool)
        fwd = {(r, hz): run(spec, r, accel[hz], dts, tests) for r in RESTITUTION for hz in LOWPASS}
        attempts = {
            "forward block, Housner, default processing (20 Hz): threshold only": {("housner", 20.0): fwd["housner", 20.0]},
            "forward block, β fitted (20 Hz)": {k: v for k, v in fwd.items() if k[1] == 20.0},
            "forward block, low-pass corner fitted (Housner)": {k: v for k, v in fwd.items() if k[0] == "housner"},
            "forward block, β × low-pass fitted": fwd,
        }
        ys[s], shared[s] = y, fwd
        for name, cands in attempts.items():
            m, chosen = held_out(y, cands)
            rows.setdefault(name, {})[s] = (m, chosen)
        # the statistical correction: fitted on the training folds' forward-block score at 20 Hz and none
        for hz in (20.0, None):
            sc = np.log(np.minimum(fwd["housner", hz][1], study.OVERTURNED_SCORE) + 1e-3)
            held = scores.logistic_cv(y, [sc, ratio])[0]
            rows.setdefault(f"logistic on (log θmax/α forward block at {hz or 'no'} low-pass, log PGV/PGA)",
                            {})[s] = (scores.bootstrap(y, held), None)
        if runs_json:
            import json
            with open(runs_json) as f:
                runs = json.load(f)["runs"][str(s)]
            engines = sorted({n.split(":")[0] for n in runs})
            base = np.log(np.minimum(fwd["housner", 20.0][1], study.OVERTURNED_SCORE) + 1e-3)
            for eng in engines:
                feats = [base] + [np.log(np.array([runs[n][str(t)][1] for t in tests]) + 1e-3)
                                  for n in sorted(runs) if n.split(":")[0] == eng]
                held = scores.logistic_cv(y, feats)[0]
                rows.setdefault(f"ensemble: logistic on (log θmax/α forward block, log {eng} ±x scores)",
                                {})[s] = (scores.bootstrap(y, held), None)
    for name, keep in (("forward block, one β × low-pass for both specimens", lambda k: True),
                       ("forward block, one β for both specimens (20 Hz)", lambda k: k[1] == 20.0)):
        held, chosen = select_shared(ys, {s: {k: v for k, v in c.items() if keep(k)} for s, c in shared.items()})
        for s in data.SPECIMENS:
            rows.setdefault(name, {})[s] = (scores.bootstrap(ys[s], held[s]), [(c,) for c in chosen])
    print("| attempt (held-out, 5-fold, nested) | SP1 accuracy | SP2 accuracy | chosen per fold (SP1; SP2) |")
    print("|---|---|---|---|")
    for name, r in rows.items():
        ch = "; ".join(", ".join(str(c[0]) for c in r[s][1]) if r[s][1] else "—" for s in data.SPECIMENS)
        print(f"| {name} | {fmt(r[1][0])} | {fmt(r[2][0])} | {ch} |")
    print(f"\n{time.perf_counter() - start:.0f} s wall")


def asymmetric_attempt(folder):
    """The asymmetric model: sign × low-pass corner × threshold chosen on the training folds."""
    start = time.perf_counter()
    outcomes, files = data.load(folder)
    tests = sorted(outcomes)
    motions = {t: data.read_test(files[t], t) for t in tests}
    dts = {t: motions[t].dt for t in tests}
    cands = {s: {} for s in data.SPECIMENS}
    for hz in LOWPASS:
        steps = STEPS + (("lowpass",) if hz else ())
        accel = {t: processing.process(motions[t].acceleration, dts[t], steps, lowpass_hz=hz or 20.0) for t in tests}
        for s in data.SPECIMENS:
            for name, r in study.run_asymmetric(specimen.load_specimen(folder, s), accel, dts).items():
                cands[s][(name, hz)] = (np.array([r[t][0] for t in tests], bool),
                                        np.array([r[t][1] for t in tests], float))
    res = {}
    for s in data.SPECIMENS:
        y = np.array([outcomes[t].measured[s] for t in tests], bool)
        res[s] = held_out(y, cands[s])
    ch = "; ".join(", ".join(f"{c[0][0].split(':')[1]} {c[0][1] or 'none'}" for c in res[s][1]) for s in data.SPECIMENS)
    print(f"| asymmetric, sign × low-pass corner fitted | {fmt(res[1][0])} | {fmt(res[2][0])} | {ch} |")
    print(f"\n{time.perf_counter() - start:.0f} s wall")


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--asymmetric"]
    folder = args[0] if args else study.default_data()
    if "--asymmetric" in sys.argv[1:]:
        asymmetric_attempt(folder)
    else:
        main(folder, args[1] if len(args) > 1 else None)
