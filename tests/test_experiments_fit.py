"""Issue 38: a fit frozen on one set of shake-table tests and carried to another
(experiments.fitted, `isorock experiments --fit DIR --out MODEL`, `--predict DIR --model MODEL`).

Oracles: the folds' properties counted directly (every record in one fold, the overturns spread);
nesting as a property (a held-out fold's own labels cannot move its predictions); an interval
over records that is a point where every record scores alike; a prediction's accuracy recounted
from results.csv with the csv module; hostile model files refused with one line."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from isorock.validate.tools.experiments import fitted, scores
from isorock.validate.cli.main import main

VSR = Path(__file__).resolve().parents[2] / "shared" / "data" / "vsr"
needs_data = pytest.mark.skipif(not (VSR / "results.csv").exists(), reason="../shared/data/vsr is not beside the "
                                                                          "repository")


def _synthetic(n_records=23, seed=3):
    rng = np.random.default_rng(seed)
    groups, y = [], []
    for r in range(n_records):
        size = int(rng.integers(2, 12))
        groups += [f"RSN{r}"] * size
        y += list(rng.random(size) < (0.15 + 0.7 * (r % 3 == 0)))
    return np.array(groups), np.array(y, bool)


def test_grouped_folds_keep_each_record_in_one_fold_and_spread_the_overturns():
    groups, y = _synthetic()
    f = scores.grouped_folds(groups, y, 5)
    for g in np.unique(groups):
        assert np.unique(f[groups == g]).size == 1, g  # a record never on both sides of a split
    per_fold = [int(y[f == j].sum()) for j in range(5)]
    largest = max(int(y[groups == g].sum()) for g in np.unique(groups))
    assert max(per_fold) - min(per_fold) <= largest  # greedy: within one record's overturns
    assert np.array_equal(f, scores.grouped_folds(groups, y, 5))  # seeded: the same every run
    assert np.unique(scores.grouped_folds(groups[:5], y[:5], 5)).size == 1  # one record: one fold


def _inputs(y, seed=5):
    rng = np.random.default_rng(seed)
    signal = y + rng.normal(0, 0.6, y.size)
    noise = rng.normal(0, 1, y.size)
    pga = np.exp(rng.normal(-1, 0.5, y.size)) * (1 + 0.5 * y)
    period = np.exp(rng.normal(-2, 0.3, y.size))
    return {"analytic:forward θmax/α threshold": ("threshold", signal[:, None]),
            "analytic:backward θmax/α threshold": ("threshold", noise[:, None]),
            "pga × PGV/PGA logistic (no model)": ("intensity-logistic",
                                                   fitted.features("intensity-logistic", None, pga, period))}


def test_the_nested_choice_never_sees_the_labels_of_the_fold_it_predicts():
    """Each outer fold's predictions come from a choice and a fit on the other folds only: flipping
    every label inside one outer fold leaves that fold's predictions as they were."""
    groups, y = _synthetic()
    inputs = _inputs(y)
    pred, chosen = fitted.nested(y, groups, inputs)
    assert len(chosen) == 5 and set(chosen) <= set(inputs)
    f = scores.grouped_folds(groups, y, scores.FOLDS)
    for j in range(5):
        flipped = y.copy()
        flipped[f == j] = ~flipped[f == j]
        # the folds are drawn from the labels too (stratified): hold them, and ask nested again
        again, _ = _nested_with_folds(flipped, groups, inputs, f)
        assert np.array_equal(again[f == j], pred[f == j]), j


def _nested_with_folds(y, groups, inputs, f):
    """fitted.nested with the outer folds given (the folds themselves are not under test here)."""
    original = scores.grouped_folds
    calls = []

    def outer_first(g, yy, k=scores.FOLDS, seed=scores.SEED):
        calls.append(1)
        return f if len(calls) == 1 else original(g, yy, k, seed)
    scores.grouped_folds = outer_first
    try:
        return fitted.nested(y, groups, inputs)
    finally:
        scores.grouped_folds = original


def test_the_record_interval_is_a_point_where_every_record_scores_alike():
    groups = np.repeat(np.arange(10), 4)
    y = np.tile([True, True, False, False], 10)
    pred = np.tile([True, False, False, False], 10)  # 3 of 4 right in every record
    assert fitted.record_interval(y, pred, groups) == [0.75, 0.75]


@pytest.mark.parametrize("content, says", [
    ("not json", "not a readable JSON"),
    ("[]", "not an isorock experiments model"),
    (json.dumps({"format": fitted.FORMAT, "version": 99}), "version 1"),
    (json.dumps({"format": fitted.FORMAT, "version": 1, "processing": {"steps": ["offset"], "lowpass_hz": 25.0},
                 "specimens": {"1": {"predictor": "analytic:forward θmax/α threshold", "kind": "threshold",
                                     "setting": "analytic:forward", "params": {"threshold": float("nan")}}}})
     , "missing or not what fit writes"),
    (json.dumps({"format": fitted.FORMAT, "version": 1, "processing": {"steps": [], "lowpass_hz": 25.0},
                 "specimens": {"1": {"predictor": "made up", "kind": "threshold", "setting": None,
                                     "params": {"threshold": 1.0}}}}), "missing or not what fit writes"),
], ids=["text", "list", "version", "nan-threshold", "unknown-predictor"])
def test_a_hostile_model_file_is_refused_in_one_line(tmp_path, capsys, content, says):
    model = tmp_path / "model.json"
    model.write_text(content)
    code = main(["experiments", "--predict", str(tmp_path), "--model", str(model), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip()
    assert code == 2 and says in err and len(err.splitlines()) == 1, err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("argv, says", [
    (["--fit", "DIR", "--predict", "DIR"], "give one of them"),
    (["--fit", "DIR", "--engines", "analytic,mujoco"], "not taken with --fit"),
    (["--fit", "DIR", "--model", "m.json"], "is read by --predict"),
    (["--predict", "DIR"], "needs the model file"),
    (["--model", "m.json"], "is read by --predict"),
], ids=["both", "engines", "model-with-fit", "no-model", "model-alone"])
def test_fit_and_predict_options_refuse_what_they_do_not_take(tmp_path, capsys, argv, says):
    argv = [str(tmp_path) if x == "DIR" else x for x in argv]
    code = main(["experiments", *argv, "--out", str(tmp_path / "o.json")])
    err = capsys.readouterr().err.strip()
    assert code == 2 and says in err and len(err.splitlines()) == 1, err


def _tests_of_records(parity):
    with open(VSR / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    records = sorted({r["ground_motion"] for r in rows})
    chosen = set(records[parity::8])  # an eighth each: 33 tests fitted, 32 predicted
    return [int(r["test"]) for r in rows if r["ground_motion"] in chosen], {int(r["test"]): r for r in rows}


@needs_data
def test_a_model_fitted_on_some_records_predicts_the_tests_of_others_without_refitting(tmp_path, capsys):
    """Fit on an eighth of the records' tests, predict another eighth's: none was in the fit, the
    model file is not touched, and the accuracy is recounted from results.csv's outcomes."""
    fit_tests, rows = _tests_of_records(0)
    new_tests, _ = _tests_of_records(1)
    assert fit_tests and new_tests and not set(fit_tests) & set(new_tests)
    model = tmp_path / "model.json"
    assert main(["experiments", "--fit", str(VSR), "--tests", ",".join(map(str, fit_tests)),
                 "--out", str(model)]) == 0
    frozen = json.loads(model.read_text())
    assert frozen["fit"]["tests"] == sorted(fit_tests) and frozen["fit"]["candidates"] == list(fitted.CANDIDATES)
    before = model.read_bytes()
    out = tmp_path / "pred"
    assert main(["experiments", "--predict", str(VSR), "--tests", ",".join(map(str, new_tests)),
                 "--model", str(model), "--out", str(out)]) == 0
    assert model.read_bytes() == before
    result = json.loads((out / "prediction.json").read_text())
    assert result["seen_in_fit"] == [] and result["tests"] == sorted(new_tests)
    column = {"1": "Experimental Results for response-Specimen 1", "2": "Experimental Results for response-Specimen 2"}
    for s, r in result["specimens"].items():
        assert r["predictor"] == frozen["specimens"][s]["predictor"]
        right = [int(rows[t][column[s]]) == int(p) for t, p in ((int(k), v) for k, v in r["predictions"].items())]
        assert r["scores"]["accuracy"] == pytest.approx(sum(right) / len(right), abs=1e-12)
        assert r["hard_tests"] + r["never_overturned_tests"] == len(new_tests)
    # refitting to the same file is refused: the model is a new file, never replaced
    capsys.readouterr()
    assert main(["experiments", "--fit", str(VSR), "--tests", ",".join(map(str, fit_tests)),
                 "--out", str(model)]) == 2
    assert "exists" in capsys.readouterr().err and model.read_bytes() == before
