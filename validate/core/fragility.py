"""Lognormal fragility curves by maximum likelihood (Baker 2015, "Efficient analytical
fragility function fitting using dynamic structural analysis"):

    P(overturn | IM = x) = Φ(ln(x / θ) / β)

fitted to the count overturned k_j of n_j runs at each intensity x_j by maximising the
binomial likelihood Σ k ln Φ(z_j) + (n_j − k_j) ln Φ(−z_j). The confidence band is a
bootstrap over records (the records are the random sample: each resampled suite keeps
a record's outcomes at every level together)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special, stats

#: Dispersions are searched in [BETA_MIN, BETA_MAX]: a suite that separates perfectly
#: (every record overturns above one level, none below) drives the MLE to β → 0.
BETA_MIN, BETA_MAX = 0.01, 5.0
BOOTSTRAP = 200
BAND = (0.05, 0.95)


@dataclass(frozen=True)
class LognormalFit:
    median: float  # θ, in the intensity's units
    dispersion: float  # β
    median_band: tuple[float, float]  # bootstrap 5–95 % of θ
    note: str = ""
    samples: tuple = ()  # bootstrap (θ, β) pairs

    def band(self, x) -> tuple[np.ndarray, np.ndarray]:
        """The bootstrap 5–95 % band of P(overturn) at intensities x."""
        x = np.asarray(x, dtype=float)
        if not self.samples:
            return np.full(x.shape, np.nan), np.full(x.shape, np.nan)
        s = np.asarray(self.samples)
        curves = stats.norm.cdf(np.log(x[None, :] / s[:, :1]) / s[:, 1:])
        return np.quantile(curves, BAND[0], axis=0), np.quantile(curves, BAND[1], axis=0)

    def probability(self, x):
        x = np.asarray(x, dtype=float)
        if not math.isfinite(self.median):
            return np.full(x.shape, np.nan)
        return stats.norm.cdf(np.log(x / self.median) / self.dispersion)


def _neg_log_likelihood(params, log_x, k, survived):
    """−ln L in (ln θ, ln β) of k overturned and `survived` (n − k) standing at ln x; log Φ by
    scipy.special.log_ndtr (exact in the tails). A fit calls it a few hundred times: the array's
    own sum and n − k taken once (the same numbers as np.sum of n − k each call, 25% sooner)."""
    log_theta, log_beta = params
    z = (log_x - log_theta) / math.exp(log_beta)
    return -float((k * special.log_ndtr(z) + survived * special.log_ndtr(-z)).sum())


def fit_counts(x, n, k) -> tuple[float, float]:
    """(θ, β) maximising the binomial likelihood of k overturned of n at intensities x.
    (nan, nan) where no run or every run overturned: the data bound no median."""
    x, n, k = (np.asarray(a, dtype=float) for a in (x, n, k))
    keep = n > 0
    x, n, k = x[keep], n[keep], k[keep]
    if k.sum() == 0 or k.sum() == n.sum():
        return math.nan, math.nan
    log_x = np.log(x)
    frac = k / n
    # start at the level where the observed fraction first reaches one half
    above = np.flatnonzero(frac >= 0.5)
    start = log_x[above[0]] if above.size else log_x[-1] + 0.5
    lo, hi = math.log(BETA_MIN), math.log(BETA_MAX)
    survived = n - k

    def objective(params):
        # the dispersion is held inside [BETA_MIN, BETA_MAX] (perfect separation → β → 0)
        return _neg_log_likelihood((params[0], min(max(params[1], lo), hi)), log_x, k, survived)

    # Nelder–Mead in two dimensions: a few hundred cheap evaluations, no gradient or
    # bound handling needed (L-BFGS-B costs ~100× more per fit here)
    best = None
    for b0 in (0.2, 0.6):
        r = optimize.minimize(objective, x0=[start, math.log(b0)], method="Nelder-Mead",
                              options={"xatol": 1e-7, "fatol": 1e-10, "maxiter": 2000})
        if best is None or r.fun < best.fun:
            best = r
    best.x[1] = min(max(best.x[1], lo), hi)
    return float(math.exp(best.x[0])), float(math.exp(best.x[1]))


def fit_fragility(levels, outcomes, *, bootstrap: int = BOOTSTRAP, seed: int = 0) -> LognormalFit:
    """levels: (L,) intensities; outcomes: (R, L) overturned or not, record by level
    (nan where a run is missing). Median and dispersion by MLE, the median's band by
    a bootstrap over records with a fixed seed (the same table gives the same band)."""
    levels = np.asarray(levels, dtype=float)
    o = np.asarray(outcomes, dtype=float)
    valid = ~np.isnan(o)
    n, k = valid.sum(axis=0), np.where(valid, o, 0).sum(axis=0)
    theta, beta = fit_counts(levels, n, k)
    if not math.isfinite(theta):
        note = "no run overturned" if k.sum() == 0 else "every run overturned"
        return LognormalFit(math.nan, math.nan, (math.nan, math.nan), note)
    rng = np.random.default_rng(seed)
    samples = []
    for _ in range(bootstrap):
        pick = rng.integers(0, o.shape[0], o.shape[0])
        ob, vb = o[pick], valid[pick]
        t, b = fit_counts(levels, vb.sum(axis=0), np.where(vb, ob, 0).sum(axis=0))
        if math.isfinite(t):
            samples.append((t, b))
    medians = [t for t, _ in samples]
    band = tuple(float(q) for q in np.quantile(medians, BAND)) if medians else (math.nan, math.nan)
    return LognormalFit(theta, beta, band, samples=tuple(samples))
