"""Scores of an overturn prediction against the measured outcomes: the confusion matrix,
accuracy, precision, recall, F1, ROC AUC of a continuous score, bootstrap intervals over
tests, and the held-out (k-fold cross-validated) scores of a threshold fitted on the
continuous score.

Conventions: outcome 1 = overturned (the positive class). Precision with no positive
prediction, recall with no positive outcome and F1 with neither are NaN (undefined), not 0.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize
from scipy.stats import rankdata

BOOTSTRAP = 2000  # resamples of the tests
LEVEL = 0.95
FOLDS = 5
SEED = 20260621  # fixed: the same folds and resamples every run (the first test day)


def confusion(y, pred) -> dict:
    y, pred = np.asarray(y, bool), np.asarray(pred, bool)
    return dict(tp=int((y & pred).sum()), fp=int((~y & pred).sum()), fn=int((y & ~pred).sum()),
                tn=int((~y & ~pred).sum()))


def _ratio(a, b):
    return a / b if b else math.nan


def metrics(y, pred) -> dict:
    c = confusion(y, pred)
    n = sum(c.values())
    precision, recall = _ratio(c["tp"], c["tp"] + c["fp"]), _ratio(c["tp"], c["tp"] + c["fn"])
    f1 = _ratio(2 * c["tp"], 2 * c["tp"] + c["fp"] + c["fn"])
    return dict(accuracy=_ratio(c["tp"] + c["tn"], n), precision=precision, recall=recall, f1=f1, **c)


def roc_auc(y, score) -> float:
    """P(score of an overturned test > score of a standing one), ties counting one half
    (the Mann–Whitney statistic); NaN without both classes."""
    y, s = np.asarray(y, bool), np.asarray(score, float)
    pos, neg = s[y], s[~y]
    if pos.size == 0 or neg.size == 0:
        return math.nan
    r = rankdata(np.concatenate((pos, neg)))
    return float((r[:pos.size].sum() - pos.size * (pos.size + 1) / 2) / (pos.size * neg.size))


def scored(y, pred, score=None) -> dict:
    out = metrics(y, pred)
    if score is not None:
        out["auc"] = roc_auc(y, score)
    return out


def bootstrap(y, pred, score=None, *, n=BOOTSTRAP, level=LEVEL, seed=SEED) -> dict:
    """Each metric with its percentile interval over `n` resamples of the tests (all
    resamples at once: one array of n × tests)."""
    y, pred = np.asarray(y, bool), np.asarray(pred, bool)
    score = None if score is None else np.asarray(score, float)
    out = scored(y, pred, score)
    idx = np.random.default_rng(seed).integers(0, y.size, (n, y.size))
    yy, pp = y[idx], pred[idx]
    tp, fp = (yy & pp).sum(1), (~yy & pp).sum(1)
    fn, tn = (yy & ~pp).sum(1), (~yy & ~pp).sum(1)
    with np.errstate(invalid="ignore", divide="ignore"):
        draws = dict(accuracy=(tp + tn) / y.size, precision=tp / (tp + fp), recall=tp / (tp + fn),
                     f1=2 * tp / (2 * tp + fp + fn))
        if score is not None:
            ss = score[idx]
            ranks = rankdata(ss, axis=1)
            npos, nneg = yy.sum(1), (~yy).sum(1)
            draws["auc"] = ((ranks * yy).sum(1) - npos * (npos + 1) / 2) / (npos * nneg)
    lo, hi = (1 - level) / 2, (1 + level) / 2
    for k, d in draws.items():
        d = d[np.isfinite(d)]
        out[k + "_ci"] = [float(np.quantile(d, lo)), float(np.quantile(d, hi))] if d.size else [math.nan, math.nan]
    return out


def best_threshold(y, score) -> float:
    """The threshold t (predict overturned when score ≥ t) of the highest accuracy on (y,
    score), the midpoint between neighbouring scores; ties go to the smallest t."""
    y, s = np.asarray(y, bool), np.asarray(score, float)
    cand = np.unique(s)
    mids = np.concatenate(([cand[0] - 1.0], (cand[1:] + cand[:-1]) / 2, [cand[-1] + 1.0]))
    mids = np.where(np.isfinite(mids), mids, np.where(mids > 0, 1e300, -1e300))
    acc = [((s >= t) == y).mean() for t in mids]
    return float(mids[int(np.argmax(acc))])


def folds(n: int, k: int = FOLDS, seed: int = SEED) -> np.ndarray:
    """The fold (0..k-1) of each of n tests: a fixed random partition."""
    rng = np.random.default_rng(seed)
    return rng.permutation(np.arange(n) % k)


def cross_validated(y, score, k: int = FOLDS, seed: int = SEED) -> tuple[np.ndarray, list[float]]:
    """Held-out predictions of the fitted threshold: each test predicted by the threshold
    fitted on the other k−1 folds only. (predictions, the k thresholds)."""
    y, s = np.asarray(y, bool), np.asarray(score, float)
    f = folds(y.size, k, seed)
    pred = np.zeros(y.size, bool)
    thresholds = []
    for j in range(k):
        t = best_threshold(y[f != j], s[f != j])
        thresholds.append(t)
        pred[f == j] = s[f == j] >= t
    return pred, thresholds


#: the logistic regression's ridge penalty on its standardized weights: only to keep a
#: separable training fold's weights finite (it moves nothing else measurably)
RIDGE = 1e-3


def grouped_folds(groups, y, k: int = FOLDS, seed: int = SEED) -> np.ndarray:
    """The fold (0..k-1) of each test, every test of one group (a ground-motion record) in one
    fold, and the folds stratified by outcome: the groups, shuffled (seeded), then taken most
    overturns first, each to the fold with the fewest overturns so far (ties: the fewest tests).
    A test fold then holds records its training folds never saw (the random folds put 97% of a
    test fold's records in its training folds, issue 38). k is lowered to the number of groups."""
    groups = np.asarray(groups)
    y = np.asarray(y, bool)
    names = np.unique(groups)
    k = max(1, min(k, names.size))
    rng = np.random.default_rng(seed)
    names = names[rng.permutation(names.size)]
    pos = np.array([int(y[groups == g].sum()) for g in names])
    size = np.array([int((groups == g).sum()) for g in names])
    order = np.lexsort((-size, -pos))  # most overturns first, then the largest
    fold_pos, fold_size = np.zeros(k, int), np.zeros(k, int)
    out = np.zeros(y.size, int)
    for i in order:
        j = int(np.lexsort((fold_size, fold_pos))[0]) if pos[i] else int(np.argmin(fold_size))
        out[groups == names[i]] = j
        fold_pos[j] += pos[i]
        fold_size[j] += size[i]
    return out


def fit_logistic(y, X) -> dict:
    """A logistic regression of the outcome on the columns of X, standardized on these rows:
    {"mean", "scale", "weights"} (intercept first), what logistic_probability applies."""
    y = np.asarray(y, bool)
    X = np.asarray(X, float)
    mu, sd = X.mean(0), X.std(0)
    sd = np.where(sd > 0, sd, 1.0)
    Z = np.column_stack((np.ones(y.size), (X - mu) / sd))

    def nll(w):
        z = Z @ w
        return float(np.sum(np.logaddexp(0, z) - y * z) + RIDGE * w @ w)
    w = minimize(nll, np.zeros(Z.shape[1]), method="BFGS").x
    return {"mean": mu.tolist(), "scale": sd.tolist(), "weights": w.tolist()}


def logistic_probability(fit: dict, X) -> np.ndarray:
    """P(overturned) of each row of X under a fit_logistic result."""
    X = np.asarray(X, float)
    Z = np.column_stack((np.ones(X.shape[0]), (X - np.asarray(fit["mean"])) / np.asarray(fit["scale"])))
    return 1.0 / (1.0 + np.exp(-(Z @ np.asarray(fit["weights"]))))


def logistic_cv(y, features, k: int = FOLDS, seed: int = SEED) -> tuple[np.ndarray, np.ndarray]:
    """Held-out (predictions, probabilities) of a logistic regression of the outcome on
    `features` (columns), each test predicted by the regression fitted on the other k−1 folds
    only, its features standardized on those folds."""
    y = np.asarray(y, bool)
    X = np.column_stack(features).astype(float)
    f = folds(y.size, k, seed)
    prob = np.zeros(y.size)
    for j in range(k):
        prob[f == j] = logistic_probability(fit_logistic(y[f != j], X[f != j]), X[f == j])
    return prob > 0.5, prob
