"""The study: every engine on every test and specimen, scored; and `isorock experiments`.

Engines (each a predictor of "specimen s overturned in test k"):
- analytic:forward / analytic:backward — the rigid rocking model (isorock.analytic, fixed
  base) on the specimen's equivalent symmetric block of its forward (smaller α) or backward
  (larger α) rocking edge: the planar symmetric model cannot have both (see docs).
- asymmetric:+x / asymmetric:-x — the exact model of the rock's own two edges (α, R, I of
  each, the impact law re-derived for two edges: System.body, asymmetric.py), the record along
  +x or −x of the rest pose.
- mujoco:±x, bullet:±x, drake:±x — the rock's convex hull on a free joint
  (mujoco_models.mesh_scene, bullet_models.mesh_scene, drake_models.mesh_scene), the measured acceleration along +x
  or −x of the rest pose (the data do not state which
  way the record's positive sign points in the rock's frame; the sign is fitted like any
  other parameter, on training folds only).
- dem:KN=.. — the data's own discrete-element predictions (the baseline), as given.
- pga — the null model: overturned when the test's scaled PGA passes a threshold; and its
  second row, a logistic boundary on (log PGA, log PGV/PGA): the record's intensity alone.
- with overturning_scale: the forward block scored by the record scale at which it first
  overturns (run_overturning_scale), and that score's threshold made to follow the record's
  PGV/PGA (a logistic boundary, the row beside the intensity-only one: what the model adds).

Scores per engine and specimen: the engine's own verdict (nothing fitted), and the held-out
verdict of a threshold on its continuous score (θmax/α, or the peak tilt over the smaller
α) fitted by 5-fold cross-validation, each with a 95% bootstrap interval over tests; the
"selected" rows choose, in each training fold, the setting (and threshold) with the best
training accuracy, and are scored on the held-out fold only.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ....analytic.engine_protocol import declare_facet
from ....analytic.errors import InputError
from ....analytic.fast import simulate_batch
from ....analytic.motion import GroundMotion
from ....analytic.system import System
from ...core.engines import get_engine
from ...core.scenarios import shared_folder
from . import asymmetric, data, processing, scores, specimen

#: the shake-table tests (shared/data/vsr, or $ISOROCK_VSR): found as the records are, not
#: computed from this file's location (which, in a wheel, is site-packages)
DEFAULT_DATA = shared_folder("vsr", "ISOROCK_VSR")
ENGINES = ("analytic", "asymmetric", "mujoco", "bullet", "drake")
#: A run past this θmax/α counts as overturned in the continuous score (an overturned run's
#: θmax/α is not a measure of how far it was from overturning: it is "beyond").
OVERTURNED_SCORE = 100.0
PAD = 5.0  # s simulated after the record: a rock still rocking at its end may yet fall


def default_data() -> Path:
    return DEFAULT_DATA


def _motion(tm: data.TableMotion, steps, lowpass_hz):
    try:
        return processing.process(tm.acceleration, tm.dt, steps, lowpass_hz=lowpass_hz)
    except InputError as e:  # a test too short, a corner past its Nyquist frequency: named
        raise InputError(f"{tm.source}: {e}") from None


def equivalent_block(spec: specimen.Specimen, sign: int):
    """The exact model's System of the specimen's equivalent block forward (sign 1) or
    backward (−1) on a fixed base."""
    d = spec.direction(sign)
    return System.fixed(height=d["block_height"], width=d["block_width"], mass=spec.mass)


def run_block(system, accel: dict, dt: dict) -> dict:
    """{test: (overturned, θmax/α, wall s)} of the exact rigid model (the registry's analytic
    engine) of `system` under each record."""
    engine = get_engine("analytic")
    rows = {}
    for test, a in accel.items():
        motion = GroundMotion.from_array(a, dt=dt[test], units="m/s2", name=f"Test{test:03d}")
        start = time.perf_counter()
        tr = engine.simulate(system, motion, duration=motion.end_time + PAD)
        wall = time.perf_counter() - start
        if tr.status.is_failure:
            raise RuntimeError(f"analytic run failed on test {test}: {tr.message}")
        score = OVERTURNED_SCORE if tr.overturned else float(tr.theta_max_over_alpha)
        rows[test] = (bool(tr.overturned), score, wall)
    return rows


def run_analytic(spec: specimen.Specimen, accel: dict, dt: dict, directions=("forward", "backward")) -> dict:
    """{setting: {test: (overturned, θmax/α, wall s)}} of the rigid model on the specimen's
    forward and backward equivalent blocks (those of `directions`)."""
    return {f"analytic:{name}": run_block(equivalent_block(spec, sign), accel, dt)
            for name, sign in (("forward", 1), ("backward", -1)) if name in directions}


#: the record scales of the overturning-scale score: 2^(k/n), k = −n..n (0.5 to 2, 9% apart at
#: n = 8). Fixed before any run (docs/scripts/experiments_scale.py also ran 32 per octave: the
#: ROC AUC moved by < 0.01, the accuracy by up to 0.03 either way: the thresholds' noise)
SCALES_PER_OCTAVE = 8
SCALE_SETTING = "analytic:forward, overturning scale"
#: the row whose threshold on the overturning scale follows the record's PGV/PGA
SCALE_BY_PERIOD = "analytic:forward, overturning scale × PGV/PGA (logistic)"
#: the null model's second row: a logistic boundary on the record's intensity alone
INTENSITY_ONLY = "pga × PGV/PGA (logistic, no model)"
#: where a test that no scale up to 2 overturns sits on the score's log axis: the next octave
NEVER_OVERTURNS = 0.25


def overturning_scales(per_octave: int = SCALES_PER_OCTAVE) -> np.ndarray:
    """The scales tried, ascending: 2^(k/n), k = −n..n."""
    return 2.0 ** (np.arange(-per_octave, per_octave + 1) / per_octave)


def run_overturning_scale(spec: specimen.Specimen, accel: dict, dt: dict,
                          per_octave: int = SCALES_PER_OCTAVE) -> dict:
    """{SCALE_SETTING: {test: (overturned at scale 1, 1 / the smallest scale that overturns
    the forward block or 0 when none of overturning_scales() does, wall s)}}: the issue's
    "scale at which the engine first overturns", the engineer's question of how much stronger
    the record would have to be. Rocking is not monotone in amplitude (a block that stands at
    1 may fall at 1.05 and stand at 1.1), so every scale is run in ascending order until the
    first that overturns; θmax/α says only how far one run came from falling. Each scale's
    runs go through the exact model's batch path (fast.simulate_batch: the same kernel and
    verdicts as run_analytic's, without the histories only a verdict does not need, on all
    cores); a test's wall time is its share of each batch it was in."""
    system = equivalent_block(spec, 1)
    first: dict = {t: None for t in accel}
    at_one, wall = {}, dict.fromkeys(accel, 0.0)
    for scale in overturning_scales(per_octave):
        todo = [t for t in accel if first[t] is None or scale == 1.0]
        motions = [GroundMotion.from_array(scale * accel[t], dt=dt[t], units="m/s2", name=f"Test{t:03d}")
                   for t in todo]
        start = time.perf_counter()
        runs = simulate_batch(system, motions, duration=[m.end_time + PAD for m in motions])
        share = (time.perf_counter() - start) / len(todo)
        for t, r in zip(todo, runs):
            if r["status"].is_failure:
                raise RuntimeError(f"analytic run failed on test {t} at scale {scale:.4g}: "
                                   f"{r.get('message', r['status'])}")
            wall[t] += share
            if scale == 1.0:
                at_one[t] = bool(r["overturned"])
            if r["overturned"] and first[t] is None:
                first[t] = float(scale)
    return {SCALE_SETTING: {t: (at_one[t], 0.0 if first[t] is None else 1.0 / first[t], wall[t]) for t in accel}}


#: the record's two signs in the rock's frame (the data do not state which it is)
SIGNS = (("+x", 1.0), ("-x", -1.0))


def run_asymmetric(spec: specimen.Specimen, accel: dict, dt: dict) -> dict:
    """The exact model of the rock's own two edges (asymmetric.py: System.body), the acceleration
    along +x and along −x of the rest pose."""
    rock = asymmetric.system(spec)
    out = {}
    for name, sign in SIGNS:
        rows = {}
        for test, a in accel.items():
            start = time.perf_counter()
            over, peak, _ = asymmetric.simulate(rock, sign * a, dt[test], pad=PAD)
            rows[test] = (bool(over), OVERTURNED_SCORE if over else float(peak), time.perf_counter() - start)
        out[f"asymmetric:{name}"] = rows
    return out


#: the engines with a rigid body of the rock's hull on a table (their SIMULATE_BODY facet)
HULL_ENGINES = ("mujoco", "bullet", "drake")
SIMULATE_BODY = declare_facet(
    "simulate_body", "isorock experiments (the shake-table study), scorecard",
    "(vertices, com, inertia, mass, acceleration, dt, *, duration, friction, **contact) → a dict with "
    "overturned, tilt_max (rad) and wall_s: a free rigid body of that convex hull on a flat table moved by a "
    "horizontal acceleration history (m/s², step dt s); friction and the engine's own contact keywords (MuJoCo: "
    "dampratio; PyBullet: restitution) None for its defaults")
#: simulated s per wall s of one hull run on one core, for the estimate said before the runs
#: (core.estimate): rounded down from the cost measured here (docs/experiments.md, "Cost"):
#: MuJoCo 1220 runs of ≈ 43 s in 381 s wall (113); PyBullet 1432 s wall at load 6–8 (36);
#: Drake a run's median 11.2 s wall on SP2, loaded (3.8). Loaded: a bound on an idle machine.
HULL_SPEEDS = {"mujoco": 40.0, "bullet": 25.0, "drake": 3.0}


def hull_seconds(accel: dict, dt: dict, engines) -> dict:
    """Simulated seconds each hull engine of `engines` will run: every test, both specimens,
    both signs (the rigid models' runs take under a minute in all: not counted)."""
    per_engine = sum((a.size - 1) * dt[t] + PAD for t, a in accel.items()) * len(data.SPECIMENS) * len(SIGNS)
    return {e: per_engine for e in engines if e in HULL_ENGINES}


def run_body(engine: str, spec: specimen.Specimen, accel: dict, dt: dict, progress=None, signs=SIGNS,
             **contact) -> dict:
    """The engine's rigid body (the rock's hull on a free joint, its SIMULATE_BODY facet),
    through the registry, the acceleration along each of `signs` of the rest pose (both,
    by default); `contact`: the engine's contact keywords (friction, and MuJoCo's dampratio
    or PyBullet's restitution), absent for its own defaults. The continuous score: the peak
    tilt over the smaller α."""
    simulate_body = SIMULATE_BODY.of(get_engine(engine).spec)
    alpha = min(spec.direction(1)["alpha"], spec.direction(-1)["alpha"])
    out = {}
    for name, sign in signs:
        rows = {}
        for test, a in accel.items():
            r = simulate_body(spec.vertices, spec.com, spec.inertia, spec.mass, sign * a, dt[test],
                              duration=(a.size - 1) * dt[test] + PAD, **contact)
            score = OVERTURNED_SCORE if r["overturned"] else r["tilt_max"] / alpha
            rows[test] = (bool(r["overturned"]), score, r["wall_s"])
            if progress:
                progress()
        out[f"{engine}:{name}"] = rows
    return out


def score_engine(y, pred, score, k=scores.FOLDS) -> dict:
    """The engine's own verdict and its cross-validated threshold, both with intervals."""
    own = scores.bootstrap(y, pred, score)
    held, thresholds = scores.cross_validated(y, score, k)
    cv = scores.bootstrap(y, held, score)
    return dict(own=own, cv=cv, thresholds=thresholds)


def select_cv(y, candidates: dict, k=scores.FOLDS, threshold=True) -> tuple[np.ndarray, list]:
    """Held-out predictions of the setting (and threshold on its score) that does best on the
    training folds, chosen afresh in each fold. candidates: name → (pred, score)."""
    y = np.asarray(y, bool)
    f = scores.folds(y.size, k)
    out = np.zeros(y.size, bool)
    chosen = []
    for j in range(k):
        tr = f != j
        best = None
        for name, (pred, score) in candidates.items():
            if threshold and score is not None:
                t = scores.best_threshold(y[tr], score[tr])
                p_tr, p_te = score[tr] >= t, score[f == j] >= t
            else:
                t, p_tr, p_te = None, pred[tr], pred[f == j]
            acc = (p_tr == y[tr]).mean()
            if best is None or acc > best[0]:
                best = (acc, name, t, p_te)
        out[f == j] = best[3]
        chosen.append((best[1], best[2]))
    return out, chosen


def read(folder, tests, steps, lowpass_hz):
    """The tests of `folder` (`tests`: those; None: all) read and processed, and the specimens:
    (outcomes, the tests sorted, their table motions, processed accelerations, sample steps,
    specimens, the seconds reading the motions took)."""
    outcomes, files = data.load(folder, tests)
    t0 = time.perf_counter()
    motions = {t: data.read_test(files[t], t) for t in outcomes}
    read_s = time.perf_counter() - t0
    specimens = {s: specimen.load_specimen(folder, s) for s in data.SPECIMENS}
    testlist = sorted(outcomes)
    dts = {t: motions[t].dt for t in testlist}
    accel = {t: _motion(motions[t], steps, lowpass_hz) for t in testlist}
    return outcomes, testlist, motions, accel, dts, specimens, read_s


def build(folder, *, engines=ENGINES, steps=processing.DEFAULT_STEPS, lowpass_hz=processing.LOWPASS_HZ,
          tests=None, sensitivity=False, progress=None, contact=None, overturning_scale=False,
          announce=None) -> dict:
    """contact: engine → its hull scene's contact keywords ({'mujoco': {'friction': μ,
    'dampratio': ζ}, 'bullet': {'friction': μ, 'restitution': e}}; absent: the scene's own).
    overturning_scale: also the forward block scored by the record scale at which it first
    overturns (run_overturning_scale: 17 runs of a standing test instead of one). announce:
    called with the hull engines' simulated seconds (hull_seconds) once the tests are read,
    before any run, to say the cost."""
    outcomes, testlist, motions, accel, dts, specimens, read_s = read(folder, tests, steps, lowpass_hz)
    result = dict(tests=testlist, steps=list(steps), lowpass_hz=lowpass_hz, read_s=read_s,
                  specimens={s: sp.describe() for s, sp in specimens.items()}, runs={}, scores={}, cost={},
                  outcomes={t: dict(measured=outcomes[t].measured, pga=outcomes[t].scaled_pga_g,
                                    pgv_over_pga=outcomes[t].pgv_over_pga_s) for t in testlist})
    if announce is not None:
        announce(hull_seconds(accel, dts, engines))
    for s, sp in specimens.items():
        y = np.array([outcomes[t].measured[s] for t in testlist], bool)
        runs = {}
        for eng in engines:
            start = time.perf_counter()
            if eng == "analytic":
                runs.update(run_analytic(sp, accel, dts))
                if overturning_scale:
                    runs.update(run_overturning_scale(sp, accel, dts))
            elif eng == "asymmetric":
                runs.update(run_asymmetric(sp, accel, dts))
            elif eng in HULL_ENGINES:
                runs.update(run_body(eng, sp, accel, dts, progress, **(contact or {}).get(eng, {})))
            result["cost"][f"{eng} SP{s}"] = time.perf_counter() - start
        rows = {}
        by_engine: dict = {}
        for name, r in runs.items():
            pred = np.array([r[t][0] for t in testlist])
            score = np.array([r[t][1] for t in testlist])
            rows[name] = score_engine(y, pred, score)
            by_engine.setdefault(name.split(":")[0], {})[name] = (pred, score)
            result["runs"].setdefault(s, {})[name] = {t: list(r[t]) for t in testlist}
        for eng, cands in by_engine.items():
            held, chosen = select_cv(y, cands)
            rows[f"{eng} (CV-selected)"] = dict(cv=scores.bootstrap(y, held), chosen=chosen, held=held.tolist())
        # the baseline: each DEM setting as given, and the setting chosen on training folds
        dem = {f"dem:{k}": (np.array([outcomes[t].baseline[s][k] for t in testlist], bool), None)
               for k in outcomes[testlist[0]].baseline[s]}
        for name, (pred, _) in dem.items():
            rows[name] = dict(own=scores.bootstrap(y, pred))
        held, chosen = select_cv(y, dem, threshold=False)
        rows["dem (CV-selected)"] = dict(cv=scores.bootstrap(y, held), chosen=chosen, held=held.tolist())
        period = np.array([outcomes[t].pgv_over_pga_s for t in testlist])
        if SCALE_SETTING in runs:
            # the rigid model misses overturns under long-period shaking and raises false
            # alarms under short-period shaking at any one threshold (docs/experiments.md):
            # the threshold on its overturning scale made to follow the record's PGV/PGA, a
            # logistic boundary in (log score, log PGV/PGA) fitted on the training folds only
            score = np.array([runs[SCALE_SETTING][t][1] for t in testlist])
            held, prob = scores.logistic_cv(y, [np.log(np.maximum(score, NEVER_OVERTURNS)), np.log(period)])
            rows[SCALE_BY_PERIOD] = dict(cv=scores.bootstrap(y, held, prob), held=held.tolist())
        pga = np.array([outcomes[t].scaled_pga_g for t in testlist])
        held, thr = scores.cross_validated(y, pga)
        rows["pga threshold"] = dict(cv=scores.bootstrap(y, held, pga), thresholds=thr, held=held.tolist())
        # the control of the SCALE_BY_PERIOD row: the same logistic boundary on the record's
        # intensity alone (log PGA, log PGV/PGA), no model of the rock: what the model adds
        held, prob = scores.logistic_cv(y, [np.log(pga), np.log(period)])
        rows[INTENSITY_ONLY] = dict(cv=scores.bootstrap(y, held, prob), held=held.tolist())
        result["scores"][s] = rows
    if sensitivity:
        rigid = tuple(e for e in SENSITIVITY_ENGINES if e == "analytic" or e in engines)
        result["sensitivity"], candidates = processing_sensitivity(outcomes, motions, specimens, steps, lowpass_hz,
                                                                   rigid)
        # the processing is a fitted choice too: chosen with the setting and the threshold on
        # the training folds only, scored on the held-out fold
        for eng, by_specimen in candidates.items():
            for s, cands in by_specimen.items():
                y = np.array([outcomes[t].measured[s] for t in testlist], bool)
                held, chosen = select_cv(y, cands)
                result["scores"][s][f"{eng} (CV-selected processing)"] = dict(
                    cv=scores.bootstrap(y, held), chosen=chosen, held=held.tolist())
    return result


#: the engines re-run under each processing variant (cheap enough: the rigid planar models);
#: analytic always, asymmetric when the study runs it
SENSITIVITY_ENGINES = ("analytic", "asymmetric")


def processing_sensitivity(outcomes, motions, specimens, steps, lowpass_hz,
                           engines=("analytic",)) -> tuple[list[dict], dict]:
    """The rigid engines' accuracy (own verdict, and held-out threshold) with all the
    chosen steps, each one left out, and none (the raw record); and every (setting,
    processing) pair's predictions per engine, for the cross-validated choice among them."""
    variants = [("all: " + ",".join(steps), tuple(steps))]
    variants += [(f"without {s}", tuple(x for x in steps if x != s)) for s in steps]
    variants += [("none (raw)", ())]
    if "highpass" not in steps:
        variants.append(("drift → highpass", tuple("highpass" if x == "drift" else x for x in steps)))
    testlist = sorted(outcomes)
    dts = {t: motions[t].dt for t in testlist}
    out = []
    candidates: dict = {eng: {s: {} for s in specimens} for eng in engines}
    runners = dict(analytic=run_analytic, asymmetric=run_asymmetric)
    for label, st in variants:
        accel = {t: _motion(motions[t], st, lowpass_hz) for t in testlist}
        row = dict(variant=label)
        for s, sp in specimens.items():
            y = np.array([outcomes[t].measured[s] for t in testlist], bool)
            runs = {}
            for eng in engines:
                runs.update(runners[eng](sp, accel, dts))
            for name, r in runs.items():
                pred = np.array([r[t][0] for t in testlist])
                score = np.array([r[t][1] for t in testlist])
                held, _ = scores.cross_validated(y, score)
                candidates[name.split(":")[0]][s][f"{name} | {label}"] = (pred, score)
                row[f"{name} SP{s} own"] = float((pred == y).mean())
                row[f"{name} SP{s} cv"] = float((held == y).mean())
        out.append(row)
    return out, candidates
