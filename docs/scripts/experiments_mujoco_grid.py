"""Issue 21: a finer MuJoCo contact grid on the shake-table tests (docs/experiments.md,
"Attempts at 0.92"), held out. The rock's hull in MuJoCo (the `isorock experiments` scene),
the record along +x (the sign the earlier variant used), the command's default processing,
every test; the grid is fixed here before any run:

    friction ∈ FRICTIONS × contact dampratio ∈ DAMPRATIOS  (the default: 0.5, 1.0)

Each point's own verdict and its held-out threshold (5-fold), and the grid point chosen with
its threshold on 4 of 5 folds by training accuracy and scored on the fifth, afresh in each
fold (study.select_cv: nested), with 95% bootstrap intervals over tests. Runs go to
OUT/<point>-SP<s>.json as they finish (a rerun resumes); two processes.

    nice -n 10 python docs/scripts/experiments_mujoco_grid.py OUT [DATA [TESTS]]   (TESTS: 11,33,… a smoke run)
"""
from __future__ import annotations

import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from isorock.validate.tools.experiments import data, scores, specimen, study

FRICTIONS = (0.5, 0.8)
DAMPRATIOS = (1.0, 0.5, 0.25)


def _name(friction, dampratio):
    return f"mu{friction:g}-zeta{dampratio:g}"


def _run(job):
    folder, out, friction, dampratio, s, tests = job
    path = Path(out) / f"{_name(friction, dampratio)}-SP{s}.json"
    if path.is_file():
        return str(path)
    outcomes, files = data.load(folder, tests)
    sp = specimen.load_specimen(folder, s)
    accel, dts = {}, {}
    for t in sorted(outcomes):
        tm = data.read_test(files[t], t)
        accel[t], dts[t] = study._motion(tm, study.processing.DEFAULT_STEPS, study.processing.LOWPASS_HZ), tm.dt
    start = time.perf_counter()
    runs = study.run_body("mujoco", sp, accel, dts, signs=study.SIGNS[:1], friction=friction, dampratio=dampratio)
    rows = {t: [overturned, score] for t, (overturned, score, _) in runs["mujoco:+x"].items()}
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(dict(rows=rows, wall_s=time.perf_counter() - start)))
    tmp.replace(path)
    return str(path)


def fmt(m):
    lo, hi = m["accuracy_ci"]
    return f"{m['accuracy']:.3f} [{lo:.3f}, {hi:.3f}]"


def main(out, folder=None, tests=None):
    folder = str(folder or study.default_data())
    tests = None if tests is None else [int(t) for t in tests.split(",")]  # a smoke run on a few
    Path(out).mkdir(parents=True, exist_ok=True)
    jobs = [(folder, out, f, z, s, tests) for f in FRICTIONS for z in DAMPRATIOS for s in data.SPECIMENS]
    with ProcessPoolExecutor(2) as pool:
        for done in pool.map(_run, jobs):
            print(f"done {done}", file=sys.stderr, flush=True)
    outcomes, _ = data.load(folder, tests)
    tests = sorted(outcomes)
    print("| MuJoCo +x setting | SP1 own | SP1 held-out threshold | SP2 own | SP2 held-out threshold | wall s (SP1, SP2) |")
    print("|---|---|---|---|---|---|")
    cands = {s: {} for s in data.SPECIMENS}
    walls = {}
    cells = {}
    for f in FRICTIONS:
        for z in DAMPRATIOS:
            row = []
            for s in data.SPECIMENS:
                saved = json.loads((Path(out) / f"{_name(f, z)}-SP{s}.json").read_text())
                y = np.array([outcomes[t].measured[s] for t in tests], bool)
                pred = np.array([saved["rows"][str(t)][0] for t in tests])
                score = np.array([saved["rows"][str(t)][1] for t in tests])
                cands[s][_name(f, z)] = (pred, score)
                m = study.score_engine(y, pred, score)
                row += [fmt(m["own"]), fmt(m["cv"])]
                walls.setdefault(_name(f, z), []).append(saved["wall_s"])
            cells[_name(f, z)] = row
            print(f"| friction {f:g}, dampratio {z:g} | " + " | ".join(row)
                  + f" | {walls[_name(f, z)][0]:.0f}, {walls[_name(f, z)][1]:.0f} |")
    line = []
    for s in data.SPECIMENS:
        y = np.array([outcomes[t].measured[s] for t in tests], bool)
        held, chosen = study.select_cv(y, cands[s])
        line.append(f"SP{s} {fmt(scores.bootstrap(y, held))} (chosen: {', '.join(c[0] for c in chosen)})")
    print("\nnested (setting and threshold chosen on the training folds): " + "; ".join(line))


if __name__ == "__main__":
    main(*sys.argv[1:])
