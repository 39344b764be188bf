"""Issue 21: is one predictor's held-out accuracy above another's, test by test?

Reads the study.json of `isorock experiments` and, per specimen, compares the held-out
predictions of one row (default: the overturning scale × PGV/PGA row of
`--overturning-scale`) with every other row that has held-out predictions: the difference of
their accuracies with its 95% paired bootstrap interval (the same resamples of the tests for
both, scores.BOOTSTRAP of them, scores.SEED), and the tests only one of them gets right.
Paired, because both predict the same tests: far narrower than comparing two intervals.

Usage: python docs/scripts/experiments_paired.py STUDY_JSON [ROW]
"""
from __future__ import annotations

import json
import sys

import numpy as np

from isorock.validate.tools.experiments import scores, study


def main(path, row=study.SCALE_BY_PERIOD):
    with open(path) as f:
        result = json.load(f)
    tests = result["tests"]
    print(f"| specimen | {row} against | accuracy difference [95% paired CI] | only it right | only the other right |")
    print("|---|---|---|---|---|")
    for s, rows in result["scores"].items():
        y = np.array([result["outcomes"][str(t)]["measured"][s] for t in tests], bool)
        mine = np.array(rows[row]["held"], bool) == y
        idx = np.random.default_rng(scores.SEED).integers(0, y.size, (scores.BOOTSTRAP, y.size))
        for other, r in rows.items():
            if other == row or "held" not in r:
                continue
            theirs = np.array(r["held"], bool) == y
            d = mine[idx].mean(1) - theirs[idx].mean(1)
            lo, hi = np.quantile(d, [(1 - scores.LEVEL) / 2, (1 + scores.LEVEL) / 2])
            print(f"| SP{s} | {other} | {mine.mean() - theirs.mean():+.3f} [{lo:+.3f}, {hi:+.3f}] | "
                  f"{int((mine & ~theirs).sum())} | {int((~mine & theirs).sum())} |")


if __name__ == "__main__":
    main(*sys.argv[1:3])
