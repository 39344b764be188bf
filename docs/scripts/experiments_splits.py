"""Issue 38: the fit carried to tests it never saw, over many splits instead of one.

docs/experiments.md, "A fit carried to new tests", fits on half the records (A: even places of
the 55 records sorted by name) and scores the other half (B), and the other way round: one split,
two numbers (SP1 0.867 fitted on A, 0.938 fitted on B). How much of that spread is the split?
This script repeats exactly `isorock experiments --fit` on one half and `--predict` on the other
(experiments/fitted.py's own functions: the candidate chosen by grouped inner folds on the fit
half, refitted on it, applied frozen to the other half) over N random halvings of the records,
each half of the records drawn with numpy's seeded generator (seed i for split i), and prints the
distribution of the scored half's accuracy per specimen. The runs do not depend on the split (the
processing is fixed), so each test is run once.

    python docs/scripts/experiments_splits.py ../shared/data/vsr --splits 200

The first split printed is the documented one (A = even places), both ways, to check the script
against the command's numbers.
"""
from __future__ import annotations

import argparse
import collections
import time

import numpy as np

from isorock.validate.tools.experiments import fitted, processing, study


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("folder")
    p.add_argument("--splits", type=int, default=200)
    a = p.parse_args()
    t0 = time.perf_counter()
    outcomes, testlist, _, accel, dts, specimens, _ = study.read(a.folder, None, processing.DEFAULT_STEPS,
                                                                processing.LOWPASS_HZ)
    pga, period, groups = fitted._intensity(outcomes, testlist)
    settings = {s for _, s in fitted.CANDIDATES.values() if s is not None}
    data = {}
    for s, spec in specimens.items():
        runs = fitted._runs(settings, spec, accel, dts)
        y = np.array([outcomes[t].measured[s] for t in testlist], bool)
        data[s] = (y, fitted._inputs(fitted.CANDIDATES, runs, testlist, pga, period))
    print(f"runs of {len(testlist)} tests, both specimens: {time.perf_counter() - t0:.0f} s")
    records = np.array(sorted(set(groups)))
    documented = set(records[0::2])

    def carried(fit_records):
        """per specimen: (the candidate chosen on the fit half, its accuracy on the other half)"""
        fit_mask = np.isin(groups, list(fit_records))
        out = {}
        for s, (y, inputs) in data.items():
            on_fit = {n: (kind, X[fit_mask]) for n, (kind, X) in inputs.items()}
            name = fitted.choose(y[fit_mask], groups[fit_mask], on_fit)
            kind, X = inputs[name]
            params = fitted.fit_candidate(kind, y[fit_mask], X[fit_mask])
            pred = fitted.apply_candidate(kind, params, X[~fit_mask])
            out[s] = (name, float((pred == y[~fit_mask]).mean()))
        return out

    for label, fit_records in (("A (even places) → B", documented),
                               ("B (odd places) → A", set(records) - documented)):
        r = carried(fit_records)
        print(label, {s: (name, round(acc, 3)) for s, (name, acc) in r.items()})
    acc = collections.defaultdict(list)
    names = collections.defaultdict(collections.Counter)
    for i in range(a.splits):
        rng = np.random.default_rng(i)
        half = set(rng.permutation(records)[: records.size // 2 + rng.integers(0, 2)])
        for s, (name, value) in carried(half).items():
            acc[s].append(value)
            names[s][name] += 1
    print(f"{a.splits} random halvings of the {records.size} records (fit on one half, scored on the other):")
    for s in sorted(acc):
        v = np.array(acc[s])
        q = np.quantile(v, [0.05, 0.25, 0.5, 0.75, 0.95])
        print(f"  SP{s}: mean {v.mean():.3f}, median {q[2]:.3f}, quartiles [{q[1]:.3f}, {q[3]:.3f}], "
              f"5–95% [{q[0]:.3f}, {q[4]:.3f}], ≥ 0.92 in {np.mean(v >= 0.92):.0%} of splits")
        print("    chosen:", dict(names[s].most_common()))
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
