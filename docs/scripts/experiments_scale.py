"""Issue 21, task: the issue's other continuous score, "the scale at which the engine first
overturns", for the exact rigid model on the forward-edge block.

θmax/α of a standing run says how far one run came from falling; rocking is not monotone in
the record's amplitude, so a run that stands at scale 1 may fall at 1.05 and stand again at
1.1. The score here asks the engineer's question instead: how much stronger would this
record have to be to topple the rock? Each record is run at the scales `study.overturning_scales()` (fixed
here before any run: 2^(k/8), k = −8..8, i.e. 0.5 to 2 in steps of 9%), and the score is
1 / (the smallest scale that overturns it), 0 when none does. The verdict: a threshold on it,
fitted on the training folds (5-fold, the folds of every other row), scored on the held-out
fold; and, as a second row fixed beforehand, that threshold chosen together with the
low-pass corner ∈ LOWPASS (the grid of experiments_levers.py), nested the same way.

Added after the first run showed why one threshold cannot do better (the model misses
overturns under long-period records and raises false alarms under short-period ones, at
every threshold): the command's `× PGV/PGA (logistic)` row, a logistic boundary in (log
score, log PGV/PGA) fitted on the training folds, at every corner and resolution.

Usage: nice -n 10 python docs/scripts/experiments_scale.py [DATA] [--per-octave N] [--save JSON | --load JSON]
       (8 per octave: about 6 min of CPU; 32: about 4 times that)
"""
from __future__ import annotations

import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from isorock.validate.tools.experiments import data, processing, scores, specimen, study

#: scales per octave (study.overturning_scales): 8 fixed before the first run; 32 (2.2% steps)
#: run after it, to converge the first overturning scale the 9% grid rounds (the threshold can
#: only fall on grid points)
PER_OCTAVE = study.SCALES_PER_OCTAVE
LOWPASS = (10.0, 20.0, 50.0, None)
STEPS = ("offset", "drift", "trim")  # + lowpass where a corner is given


def first_overturning_scale(folder, s, hz, per_octave):
    """{test: (overturned at scale 1, 1 / the smallest overturning scale or 0)} of specimen s
    (study.run_overturning_scale, the command's own with --overturning-scale)."""
    outcomes, files = data.load(folder)
    spec = specimen.load_specimen(folder, s)
    steps = STEPS + (("lowpass",) if hz else ())
    accel, dts = {}, {}
    for t in sorted(outcomes):
        m = data.read_test(files[t], t)
        accel[t], dts[t] = processing.process(m.acceleration, m.dt, steps, lowpass_hz=hz or 20.0), m.dt
    r = study.run_overturning_scale(spec, accel, dts, per_octave)[study.SCALE_SETTING]
    return {t: v[:2] for t, v in r.items()}


def fmt(m):
    lo, hi = m["accuracy_ci"]
    return f"{m['accuracy']:.3f} [{lo:.3f}, {hi:.3f}]"


def main(folder, per_octave=PER_OCTAVE, save=None, load=None):
    start = time.perf_counter()
    outcomes, _ = data.load(folder)
    tests = sorted(outcomes)
    jobs = [(s, hz) for s in data.SPECIMENS for hz in LOWPASS]
    import json
    if load:  # the raw scores of an earlier run (--save), scored again without rerunning
        with open(load) as f:
            raw = json.load(f)
        results = {(s, hz): {t: raw[f"{s} {hz}"][str(t)] for t in tests} for s, hz in jobs}
    else:
        with ProcessPoolExecutor(2) as pool:
            results = dict(zip(jobs, pool.map(first_overturning_scale, [folder] * len(jobs), *zip(*jobs),
                                              [per_octave] * len(jobs))))
    if save:
        with open(save, "w") as f:
            json.dump({f"{s} {hz}": {str(t): v for t, v in r.items()} for (s, hz), r in results.items()}, f)
    print("| forward block, score 1 / first overturning scale | SP1 accuracy | SP1 ROC AUC | SP2 accuracy | SP2 ROC AUC |")
    print("|---|---|---|---|---|")
    rows = {}
    ratio = np.log(np.array([outcomes[t].pgv_over_pga_s for t in tests]))
    for s in data.SPECIMENS:
        y = np.array([outcomes[t].measured[s] for t in tests], bool)
        cands = {}
        for hz in LOWPASS:
            r = results[s, hz]
            pred = np.array([r[t][0] for t in tests], bool)
            score = np.array([r[t][1] for t in tests], float)
            cands[hz] = (pred, score)
            held, thr = scores.cross_validated(y, score)
            rows.setdefault(f"low-pass {hz or 'none'}, threshold fitted", {})[s] = (
                scores.bootstrap(y, held, score), thr)
            # the command's "× PGV/PGA (logistic)" row: the threshold following the record's period
            held, prob = scores.logistic_cv(y, [np.log(np.maximum(score, study.NEVER_OVERTURNS)), ratio])
            rows.setdefault(f"low-pass {hz or 'none'}, logistic on (log score, log PGV/PGA)", {})[s] = (
                scores.bootstrap(y, held, prob), None)
        held, chosen = study.select_cv(y, cands)
        rows.setdefault("low-pass corner and threshold fitted (nested)", {})[s] = (
            scores.bootstrap(y, held), chosen)
    for name, r in rows.items():
        auc = [f"{r[s][0]['auc']:.3f}" if "auc" in r[s][0] else "—" for s in data.SPECIMENS]
        print(f"| {name} | {fmt(r[1][0])} | {auc[0]} | {fmt(r[2][0])} | {auc[1]} |")
    for name, r in rows.items():
        print(name, "; ".join(f"SP{s}: {r[s][1]}" for s in data.SPECIMENS))
    print(f"\n{time.perf_counter() - start:.0f} s wall")


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser()
    ap.add_argument("data", nargs="?", default=study.default_data())
    ap.add_argument("--per-octave", type=int, default=PER_OCTAVE)
    ap.add_argument("--save", help="write the raw scores to this JSON")
    ap.add_argument("--load", help="score the raw scores of an earlier --save instead of running")
    a = ap.parse_args()
    main(a.data, a.per_octave, a.save, a.load)
