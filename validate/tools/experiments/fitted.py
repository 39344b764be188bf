"""A fit carried to new tests (issue 38): every choice made on one set of shake-table tests
frozen into a model file, and applied to another set without refitting anything.

What is chosen, and how:
- the candidates (CANDIDATES): each a predictor of "specimen s overturned in test k" from the
  rigid planar models' runs and the record's intensity: a threshold on a model's continuous
  score (θmax/α of the forward or backward equivalent block, or of the rock's own two edges
  with the record along +x or −x; the forward block's overturning scale), a logistic boundary
  on the overturning scale and the record's PGV/PGA, and the intensity alone (a PGA threshold,
  a logistic on log PGA and log PGV/PGA: the controls). The processing is the command's
  (--steps, --lowpass-hz), frozen with the rest;
- the choice among them is nested inside the folds: the outer folds and the inner ones are
  grouped by ground-motion record and stratified by outcome (scores.grouped_folds), and in each
  outer training part the candidate of the best inner held-out accuracy is chosen, refitted on
  that whole part, and scored on the outer fold it never saw. That held-out score is the honest
  one for the whole procedure; the report says how many candidates were compared;
- the model file holds, per specimen, the candidate chosen the same way on every fit test and
  its parameters fitted on all of them (a threshold, or a logistic's standardization and
  weights), the processing, the fit tests and records, and the provenance.

`predict` runs only what the chosen candidates need on the new tests, applies the frozen
parameters, and scores them against the measured outcomes with intervals over tests and over
records, the tests that no scale up to 2 overturns (the forward block's) apart from the rest:
every predictor gets those right for free, so the hard tests show.
"""
from __future__ import annotations

import json
import math

import numpy as np

from ....analytic.errors import InputError

from . import data, processing, scores, study

#: the model file's format; a file of another format is refused, not guessed at
FORMAT = "isorock-experiments-model"
VERSION = 1
INNER_FOLDS = 4

#: name → (kind, the run setting it reads, or None for the record's intensity alone)
CANDIDATES = {
    "analytic:forward θmax/α threshold": ("threshold", "analytic:forward"),
    "analytic:backward θmax/α threshold": ("threshold", "analytic:backward"),
    "asymmetric:+x θmax/α threshold": ("threshold", "asymmetric:+x"),
    "asymmetric:-x θmax/α threshold": ("threshold", "asymmetric:-x"),
    "overturning scale threshold": ("threshold", study.SCALE_SETTING),
    "overturning scale × PGV/PGA logistic": ("scale-logistic", study.SCALE_SETTING),
    "pga threshold": ("pga-threshold", None),
    "pga × PGV/PGA logistic (no model)": ("intensity-logistic", None),
}


def features(kind: str, score, pga, period) -> np.ndarray:
    """The candidate's input, one row per test: its score alone (a threshold), or the logistic's
    columns (the overturning scale's never-overturns floor as study.NEVER_OVERTURNS)."""
    if kind == "threshold":
        return np.asarray(score, float)[:, None]
    if kind == "pga-threshold":
        return np.asarray(pga, float)[:, None]
    if kind == "scale-logistic":
        return np.column_stack((np.log(np.maximum(score, study.NEVER_OVERTURNS)), np.log(period)))
    return np.column_stack((np.log(pga), np.log(period)))


def fit_candidate(kind: str, y, X) -> dict:
    if kind.endswith("logistic"):
        return scores.fit_logistic(y, X)
    return {"threshold": scores.best_threshold(y, X[:, 0])}


def apply_candidate(kind: str, params: dict, X) -> np.ndarray:
    if kind.endswith("logistic"):
        return scores.logistic_probability(params, X) > 0.5
    return X[:, 0] >= params["threshold"]


def choose(y, groups, inputs: dict, k: int = INNER_FOLDS) -> str:
    """The candidate of the best held-out accuracy over folds grouped by record within these
    tests (ties: the first in CANDIDATES' order). inputs: name → (kind, X)."""
    f = scores.grouped_folds(groups, y, k)
    best, best_acc = None, -1.0
    for name, (kind, X) in inputs.items():
        pred = np.zeros(y.size, bool)
        for j in np.unique(f):
            tr = f != j
            pred[f == j] = apply_candidate(kind, fit_candidate(kind, y[tr], X[tr]), X[f == j])
        acc = float((pred == y).mean())
        if acc > best_acc:
            best, best_acc = name, acc
    return best


def nested(y, groups, inputs: dict, k: int = scores.FOLDS) -> tuple[np.ndarray, list[str]]:
    """Held-out predictions of the whole choice: in each outer fold (grouped by record,
    stratified) the candidate chosen on the training part alone (choose), refitted on it."""
    f = scores.grouped_folds(groups, y, k)
    pred = np.zeros(y.size, bool)
    chosen = []
    for j in np.unique(f):
        tr = f != j
        name = choose(y[tr], groups[tr], {n: (kind, X[tr]) for n, (kind, X) in inputs.items()})
        kind, X = inputs[name]
        pred[f == j] = apply_candidate(kind, fit_candidate(kind, y[tr], X[tr]), X[f == j])
        chosen.append(name)
    return pred, chosen


def record_interval(y, pred, groups, n: int = scores.BOOTSTRAP, level: float = scores.LEVEL,
                    seed: int = scores.SEED) -> list[float]:
    """The accuracy's percentile interval over resampled records (each drawn with all its tests):
    the tests of one record are not independent draws."""
    y, pred, groups = np.asarray(y, bool), np.asarray(pred, bool), np.asarray(groups)
    names = np.unique(groups)
    right = np.array([int((pred[groups == g] == y[groups == g]).sum()) for g in names])
    count = np.array([int((groups == g).sum()) for g in names])
    idx = np.random.default_rng(seed).integers(0, names.size, (n, names.size))
    acc = right[idx].sum(1) / count[idx].sum(1)
    return [float(np.quantile(acc, (1 - level) / 2)), float(np.quantile(acc, (1 + level) / 2))]


def _runs(settings, spec, accel, dts) -> dict:
    """The run settings asked for, of one specimen: {setting: {test: (verdict, score, wall)}}."""
    runs: dict = {}
    directions = tuple(name.split(":")[1] for name in settings if name.startswith("analytic:")
                       and name != study.SCALE_SETTING)
    if directions:
        runs.update(study.run_analytic(spec, accel, dts, directions))
    if any(name.startswith("asymmetric:") for name in settings):
        runs.update(study.run_asymmetric(spec, accel, dts))
    if study.SCALE_SETTING in settings:
        runs.update(study.run_overturning_scale(spec, accel, dts))
    return runs


def _inputs(names, runs, testlist, pga, period) -> dict:
    out = {}
    for name in names:
        kind, setting = CANDIDATES[name]
        score = None if setting is None else np.array([runs[setting][t][1] for t in testlist])
        out[name] = (kind, features(kind, score, pga, period))
    return out


def _intensity(outcomes, testlist):
    return (np.array([outcomes[t].scaled_pga_g for t in testlist]),
            np.array([outcomes[t].pgv_over_pga_s for t in testlist]),
            np.array([outcomes[t].ground_motion for t in testlist]))


def fit(folder, *, tests=None, steps=processing.DEFAULT_STEPS, lowpass_hz=processing.LOWPASS_HZ) -> dict:
    """The model file's content: per specimen the candidate chosen on these tests (nested,
    grouped by record) and fitted on all of them, with the nested held-out score of the choice."""
    outcomes, testlist, _, accel, dts, specimens, _ = study.read(folder, tests, steps, lowpass_hz)
    pga, period, groups = _intensity(outcomes, testlist)
    settings = {s for _, s in CANDIDATES.values() if s is not None}
    out = {"format": FORMAT, "version": VERSION, "processing": {"steps": list(steps), "lowpass_hz": lowpass_hz},
           "fit": {"tests": testlist, "records": int(np.unique(groups).size), "candidates": list(CANDIDATES),
                   "outer_folds": scores.FOLDS, "inner_folds": INNER_FOLDS}, "specimens": {}}
    for s, spec in specimens.items():
        y = np.array([outcomes[t].measured[s] for t in testlist], bool)
        runs = _runs(settings, spec, accel, dts)
        inputs = _inputs(CANDIDATES, runs, testlist, pga, period)
        held, chosen = nested(y, groups, inputs)
        name = choose(y, groups, inputs)
        kind, X = inputs[name]
        out["specimens"][str(s)] = {
            "predictor": name, "kind": kind, "setting": CANDIDATES[name][1],
            "params": fit_candidate(kind, y, X),
            "nested": {"accuracy": float((held == y).mean()), "accuracy_records_ci": record_interval(y, held, groups),
                       "chosen_per_fold": chosen,
                       "own_verdict_accuracy": float((np.array([runs["analytic:forward"][t][0] for t in testlist])
                                                      == y).mean())}}
    return out


def load_model(path) -> dict:
    """A model file written by fit, checked: one line naming what is wrong otherwise."""
    try:
        with open(path, encoding="utf-8") as f:
            model = json.load(f)
    except FileNotFoundError:
        raise InputError(f"model = {str(path)!r}: no such file") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as e:
        raise InputError(f"model = {str(path)!r}: not a readable JSON model file ({type(e).__name__})") from None
    if not isinstance(model, dict) or model.get("format") != FORMAT or model.get("version") != VERSION:
        raise InputError(f"model = {str(path)!r}: not an isorock experiments model of version {VERSION} "
                         "(write one with `isorock experiments --fit DIR --out MODEL`)")
    try:
        steps = processing.parse_steps(",".join(model["processing"]["steps"]))
        lowpass = float(model["processing"]["lowpass_hz"])
        processing.check_lowpass(lowpass)
        for s in data.SPECIMENS:
            entry = model["specimens"][str(s)]
            kind, setting = CANDIDATES[entry["predictor"]]
            if entry["kind"] != kind or entry["setting"] != setting:
                raise KeyError("kind")
            params = entry["params"]
            values = ([params["threshold"]] if "threshold" in params
                      else [*params["mean"], *params["scale"], *params["weights"]])
            if not values or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                                     for v in values):
                raise KeyError("params")
            if not kind.endswith("logistic") and "threshold" not in params:
                raise KeyError("threshold")
            if kind.endswith("logistic") and not (len(params["mean"]) == len(params["scale"]) == 2
                                                  and len(params["weights"]) == 3):
                raise KeyError("weights")
    except (KeyError, TypeError, ValueError, AttributeError) as e:
        raise InputError(f"model = {str(path)!r}: its entry {e} is missing or not what fit writes") from None
    model["processing"] = {"steps": list(steps), "lowpass_hz": lowpass}
    return model


def predict(folder, model: dict, *, tests=None) -> dict:
    """The frozen model applied to the tests of `folder`: per specimen its predictions and
    scores (intervals over tests and over records), the tests that no scale up to 2 overturns
    apart, and which of these tests the fit had seen (none, for an honest score)."""
    proc = model["processing"]
    outcomes, testlist, _, accel, dts, specimens, _ = study.read(folder, tests, proc["steps"], proc["lowpass_hz"])
    pga, period, groups = _intensity(outcomes, testlist)
    seen = sorted(set(testlist) & set(model["fit"]["tests"]))
    out = {"tests": testlist, "records": int(np.unique(groups).size), "seen_in_fit": seen, "specimens": {}}
    for s, spec in specimens.items():
        entry = model["specimens"][str(s)]
        y = np.array([outcomes[t].measured[s] for t in testlist], bool)
        # the scale splits the easy tests from the hard ones, whatever the predictor reads
        runs = _runs({entry["setting"], study.SCALE_SETTING} - {None}, spec, accel, dts)
        kind, X = _inputs([entry["predictor"]], runs, testlist, pga, period)[entry["predictor"]]
        pred = apply_candidate(kind, entry["params"], X)
        hard = np.array([runs[study.SCALE_SETTING][t][1] > 0.0 for t in testlist])
        row = {"predictor": entry["predictor"], "scores": scores.bootstrap(y, pred),
               "accuracy_records_ci": record_interval(y, pred, groups),
               "hard_tests": int(hard.sum()), "never_overturned_tests": int((~hard).sum()),
               "hard": scores.metrics(y[hard], pred[hard]) if hard.any() else None,
               "never_overturned": scores.metrics(y[~hard], pred[~hard]) if (~hard).any() else None,
               "predictions": {int(t): bool(p) for t, p in zip(testlist, pred)}}
        out["specimens"][str(s)] = row
    return out
