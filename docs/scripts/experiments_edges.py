"""Issue 21: the rigid model on the edge the rock really tips about.

These rocks stand on triangles (three hull vertices), and the equivalent blocks of
docs/experiments.md take b from the footprint's extreme point along ±x. Under a table
acceleration along x the rock lifts off where the ray from its centre of mass's projection
along x leaves the footprint (specimen.Specimen.lift_off), and turns about the boundary edge
that ray crosses, which is not perpendicular to x. Turning about one edge is planar rocking
with that edge's α_edge and p_edge, driven by the acceleration across it, a·cos ψ. This
script runs the exact rigid model (isorock.analytic) on that block for each direction, the
default processing, all tests, and scores it as the command scores analytic:forward: own
verdict, held-out threshold on θmax/α, and the direction chosen on the training folds.

Usage: nice -n 10 python docs/scripts/experiments_edges.py [DATA]   (about 20 s of CPU)
"""
from __future__ import annotations

import math
import sys

import numpy as np

from isorock.analytic.system import STANDARD_GRAVITY, System
from isorock.validate.tools.experiments import data, processing, scores, specimen, study


def fmt(m):
    lo, hi = m["accuracy_ci"]
    return f"{m['accuracy']:.3f} [{lo:.3f}, {hi:.3f}]"


def main(folder):
    outcomes, files = data.load(folder)
    tests = sorted(outcomes)
    motions = {t: data.read_test(files[t], t) for t in tests}
    dts = {t: motions[t].dt for t in tests}
    accel = {t: processing.process(motions[t].acceleration, dts[t], processing.DEFAULT_STEPS) for t in tests}
    print("| specimen | edge | lift-off along x (g) | extreme point's g·b/h | α_edge | cos ψ | p_edge (1/s) "
          "| own | held-out threshold | ROC AUC |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for s in data.SPECIMENS:
        sp = specimen.load_specimen(folder, s)
        y = np.array([outcomes[t].measured[s] for t in tests], bool)
        cands = {}
        for sign, name in ((1, "forward"), (-1, "backward")):
            e, old = sp.lift_off(sign), sp.direction(sign)
            r_eq = 3 * STANDARD_GRAVITY / (4 * e["p_edge"] ** 2)  # the rectangle of the same α and p
            block = System.fixed(height=2 * r_eq * math.cos(e["alpha_edge"]),
                                 width=2 * r_eq * math.sin(e["alpha_edge"]), mass=sp.mass)
            runs = study.run_block(block, {t: e["cos_psi"] * a for t, a in accel.items()}, dts)
            pred = np.array([runs[t][0] for t in tests], bool)
            score = np.array([runs[t][1] for t in tests], float)
            cands[name] = (pred, score)
            own = scores.bootstrap(y, pred, score)
            held, _ = scores.cross_validated(y, score)
            print(f"| SP{s} | {name} | {e['accel_g']:.4f} | {old['b'] / old['h']:.4f} | {e['alpha_edge']:.4f} | "
                  f"{e['cos_psi']:.3f} | {e['p_edge']:.3f} | {fmt(own)} | {fmt(scores.bootstrap(y, held))} | "
                  f"{own['auc']:.3f} |")
        held, chosen = study.select_cv(y, cands)
        print(f"| SP{s} | chosen on the training folds ({', '.join(c[0] for c in chosen)}) | | | | | | | "
              f"{fmt(scores.bootstrap(y, held))} | |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else study.default_data())
