"""Verdicts that are statistics (issue 20): an engine agrees or disagrees with the analytic
model over an ensemble only when a confidence interval says so, never by a bare fraction
that flips with the number of runs drawn.

The rule, for a difference D between a contact engine and the analytic model (of a
fragility median, a dispersion, a quantile of θmax/α) with limit L from the tolerance
table and a bootstrap interval [lo, hi] at the table's confidence:

    disagrees      the whole interval lies beyond ±L   (lo > L or hi < −L)
    agrees         the whole interval lies within ±L   (−L ≤ lo and hi ≤ L)
    inconclusive   otherwise, with the ensemble size that would decide it: the
                   interval's half-width shrinks as 1/√n, so n·(half-width / |L − |D||)²

More cases only narrow the interval, so a larger ensemble may turn "inconclusive" into
a decision but (up to the bootstrap's own noise) never one decision into the other: the
quick run may be inconclusive where the full run decides, not the opposite.

The bootstrap resamples the ensemble's cases (its motions: one motion at each scale, or
the records of a suite), the engine's and the model's outcomes of a case together
(paired), with a fixed seed: the same table gives the same verdict.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from scipy import stats

from .fragility import fit_counts

AGREES, DISAGREES, INCONCLUSIVE = "agrees", "disagrees", "inconclusive"
#: resamples per interval (as the campaigns' fragility bands): each is a maximum-likelihood
#: fit, a few ms; the 2.5% and 97.5% quantiles of 200 move by a few % of the width
BOOTSTRAP = 200


@dataclass(frozen=True)
class Verdict:
    """One statistical decision: `estimate` of a difference, its interval at `confidence`
    against ±`limit`, over `n` cases."""

    quantity: str
    estimate: float
    interval: tuple[float, float]
    limit: float
    confidence: float
    n: int
    word: str
    n_needed: int | None = None  # the ensemble size that would decide (inconclusive only)
    note: str = ""
    #: how the interval is held against the limit: "±" (a difference, either sign) or "≤" (a
    #: rate, never negative)
    bound: str = "±"

    def describe(self) -> str:
        lo, hi = self.interval
        s = (f"{self.quantity} {self.estimate:+.3g}, {self.confidence:.0%} interval [{lo:+.3g}, {hi:+.3g}] "
             f"against {self.bound}{self.limit:g} over {self.n} cases: {self.word}")
        if self.word == INCONCLUSIVE:
            s += (f" (about {self.n_needed} cases would decide)" if self.n_needed
                  else " (the interval is open: a median beyond the intensities tried; a wider range would decide)"
                  if not (math.isfinite(lo) and math.isfinite(hi)) else " (the estimate sits on the limit)")
        return s + (f"; {self.note}" if self.note else "")

    def cell(self) -> str:
        """The verdict as one table cell: 'estimate [lo, hi] / ±limit: word'."""
        lo, hi = self.interval
        return f"{self.estimate:+.3g} [{lo:+.3g}, {hi:+.3g}] / {self.bound}{self.limit:g}: {self.word}" + (
            f" ({self.n_needed} would decide)" if self.n_needed else "")

    def as_dict(self) -> dict:
        return asdict(self)


def decide(estimate: float, lo: float, hi: float, limit: float, n: int, widen: float = 0.0) -> tuple[str, int | None]:
    """The three-way rule on an interval [lo, hi] against ±limit, and for an
    inconclusive one the ensemble size m whose interval (centred on the estimate) would
    clear the limit on the estimate's side: its bootstrap half-width shrinks as 1/√m,
    the part `widen` added for the grid's step (over the same range) as 1/m."""
    if lo > limit or hi < -limit:
        return DISAGREES, None
    if lo >= -limit and hi <= limit:
        return AGREES, None
    half, room = (hi - lo) / 2 - widen, abs(limit - abs(estimate))
    if not (math.isfinite(half) and math.isfinite(room)) or room <= 0 or n <= 0:
        return INCONCLUSIVE, None
    # half·s + widen·s² = room, s = √(n/m)
    s = room / half if widen <= 0 else (-half + math.sqrt(half * half + 4 * widen * room)) / (2 * widen)
    return INCONCLUSIVE, max(n + 1, math.ceil(n / s ** 2))


def interval(samples, confidence: float) -> tuple[float, float]:
    """The percentile interval of bootstrap samples (±inf allowed: a censored side)."""
    s = np.asarray(samples, dtype=float)
    s = s[~np.isnan(s)]
    if s.size == 0:
        return math.nan, math.nan
    a = (1 - confidence) / 2
    # inverted_cdf: no interpolation, so an infinite sample never makes a NaN bound
    lo, hi = np.quantile(s, [a, 1 - a], method="inverted_cdf")
    return float(lo), float(hi)


def bootstrap(statistic, n: int, *, resamples: int = BOOTSTRAP, seed: int = 0) -> np.ndarray:
    """statistic(indices) over `resamples` resamples with replacement of n cases."""
    rng = np.random.default_rng(seed)
    return np.array([statistic(rng.integers(0, n, n)) for _ in range(resamples)], dtype=float)


#: The note of a verdict over fewer cases than its rule's minimum (an inconclusive one that no
#: interval decides): the report tells it apart from one whose interval straddles its limit.
TOO_FEW_CASES = "cases: no interval"


def _judge(quantity, estimate, samples, limit, confidence, n, min_cases, note="", widen=0.0) -> Verdict:
    lo, hi = interval(samples, confidence)
    lo, hi = lo - widen, hi + widen
    if math.isnan(estimate) or math.isnan(lo):
        return Verdict(quantity, estimate, (lo, hi), limit, confidence, n, INCONCLUSIVE, None,
                       note or "the data bound no estimate")
    if n < min_cases:  # a percentile bootstrap over a handful of cases has no width to speak of
        return Verdict(quantity, float(estimate), (lo, hi), limit, confidence, n, INCONCLUSIVE,
                       int(min_cases), f"fewer than {min_cases} {TOO_FEW_CASES}")
    word, need = decide(estimate, lo, hi, limit, n, widen)
    dropped = int(np.isnan(samples).sum())
    if dropped:
        note = "; ".join(filter(None, [note, f"{dropped} of {len(samples)} resamples bound no difference"]))
    return Verdict(quantity, float(estimate), (lo, hi), limit, confidence, n, word, need, note)


def _fit(x, overturned) -> tuple[float, float]:
    """(ln θ, β) of the lognormal fit to one outcome per case; ln θ censored at +inf
    where no case overturned (the median lies above every intensity tried) and −inf
    where every case did; β then NaN (nothing bounds it)."""
    k = np.asarray(overturned, dtype=float)
    if k.sum() == 0:
        return math.inf, math.nan
    if k.sum() == k.size:
        return -math.inf, math.nan
    theta, beta = fit_counts(x, np.ones_like(k), k)
    return math.log(theta), beta


def _differences(a: tuple, b: tuple) -> tuple[float, float]:
    """(Δ ln θ, Δ β); Δ ln θ NaN where both are censored on the same side (no difference
    is bound)."""
    dm = math.nan if (math.isinf(a[0]) and a[0] == b[0]) else a[0] - b[0]
    return dm, a[1] - b[1]


def overturn_verdicts(intensity, engine, reference, *, median_limit: float, dispersion_limit: float,
                      confidence: float, min_cases: int, resamples: int = BOOTSTRAP, seed: int = 0,
                      groups=None) -> tuple[Verdict, Verdict] | None:
    """The engine's lognormal fragility P(overturn | intensity) against the reference's:
    (ln of the ratio of medians, difference of dispersions β), each judged by `decide`
    on a paired bootstrap over the cases (one fit per side per resample). None where
    neither overturns in any case or both in every case (the ensemble says nothing
    about overturning).

    `groups` (one label per case; None: every case its own): the units the bootstrap
    resamples, and the n of the verdict. A record suite scaled to several intensities is
    a sample of records, not of runs: a record's outcomes at every level are drawn
    together (as core.fragility's band), so n is the number of records.

    The median's interval is widened on each side by the largest step of ln(intensity)
    between the cases: outcomes at discrete intensities place each median only within the
    step where its outcomes change, so two engines that overturn from the same step may
    still differ by up to a step; the bootstrap, resampling those same steps, cannot see it."""
    x = np.asarray(intensity, dtype=float)
    e, r = np.asarray(engine, dtype=bool), np.asarray(reference, dtype=bool)
    if (not e.any() and not r.any()) or (e.all() and r.all()):
        return None
    members = ([np.array([i]) for i in range(x.size)] if groups is None else
               [np.flatnonzero(np.asarray(groups) == g) for g in dict.fromkeys(np.asarray(groups).tolist())])
    n = len(members)
    rng = np.random.default_rng(seed)
    fits: dict = {}

    def fit(xs, ks):
        # the likelihood depends only on the multiset of (intensity, outcome) pairs: resamples
        # repeat them (and an engine that overturns as the model does repeats the model's), so
        # each distinct one is fitted once: the same numbers, several times faster
        key = tuple(sorted(zip(xs.tolist(), ks.tolist())))
        if key not in fits:
            fits[key] = _fit(xs, ks)
        return fits[key]

    samples = np.array([_differences(fit(x[i], e[i]), fit(x[i], r[i]))
                        for i in (np.concatenate([members[j] for j in rng.integers(0, n, n)])
                                  for _ in range(resamples))], dtype=float)
    dm, db = _differences(fit(x, e), fit(x, r))
    levels = np.unique(x[x > 0])
    step = float(np.max(np.diff(np.log(levels)))) if levels.size > 1 else math.inf
    return (_judge("ln(median ratio)", dm, samples[:, 0], median_limit, confidence, n, min_cases, widen=step,
                   note=f"interval widened by ±{step:.3g}, the ensemble's largest step of ln(scale)"),
            _judge("Δ dispersion β", db, samples[:, 1], dispersion_limit, confidence, n, min_cases, widen=step,
                   note=f"interval widened by ±{step:.3g}: a dispersion below the step is not resolved"))


def quantile_verdict(engine, reference, *, limit: float, confidence: float, min_cases: int, q: float = 0.5,
                     resamples: int = BOOTSTRAP, seed: int = 0, quantity: str = "") -> Verdict:
    """The difference of the q-quantile of a quantity over the ensemble (θmax/α, say)
    between the engine and the reference, on a paired bootstrap over the cases."""
    e, r = np.asarray(engine, dtype=float), np.asarray(reference, dtype=float)
    n = e.size

    def diff(i):
        return float(np.quantile(e[i], q) - np.quantile(r[i], q))

    if n == 0:
        return Verdict(quantity or f"Δ q{q:g}", math.nan, (math.nan, math.nan), limit, confidence, 0,
                       INCONCLUSIVE, None, "no case")
    return _judge(quantity or f"Δ q{q:g}", diff(np.arange(n)), bootstrap(diff, n, resamples=resamples, seed=seed),
                  limit, confidence, n, min_cases)


def rate_interval(k: float, n: int, confidence: float) -> tuple[float, float]:
    """The exact (Clopper–Pearson) interval of a rate from k of n: what a count of
    disagreements over a grid of cases says about the engine's rate, not only the count.
    k may lie between whole numbers (the beta quantiles take any k): `rate_verdict` asks
    what a larger ensemble at the same rate would say."""
    if n <= 0:
        return math.nan, math.nan
    a = 1 - confidence
    lo = 0.0 if k <= 0 else float(stats.beta.ppf(a / 2, k, n - k + 1))
    hi = 1.0 if k >= n else float(stats.beta.ppf(1 - a / 2, k + 1, n - k))
    return lo, hi


def rate_verdict(k: int, n: int, *, limit: float, confidence: float, min_cases: int,
                 quantity: str = "disagreement rate") -> Verdict:
    """A count judged by the same rule: k of n cases in which an engine parts from the
    model (stress's robust comparisons, the atlas's cells, a campaign's map), the rate's
    exact interval (`rate_interval`) against `limit`: disagrees when even its lower bound
    exceeds the limit, agrees when its upper bound is within it, else inconclusive, with
    the number of cases at the same rate whose exact interval would decide (the bound of
    0 of n falls as 1/n, not 1/√n: found by search, not by the bootstrap's scaling)."""
    if n <= 0:
        return Verdict(quantity, math.nan, (math.nan, math.nan), limit, confidence, 0, INCONCLUSIVE, None, "no case",
                       bound="≤")
    rate = k / n
    lo, hi = rate_interval(k, n, confidence)
    if n < min_cases:
        return Verdict(quantity, rate, (lo, hi), limit, confidence, n, INCONCLUSIVE, int(min_cases),
                       f"{k} of {n}; fewer than {min_cases} {TOO_FEW_CASES}", bound="≤")
    word, _ = decide(rate, lo, hi, limit, n)
    need = None
    if word == INCONCLUSIVE and rate != limit:
        need = _cases_to_decide(rate, n, limit, confidence)
    return Verdict(quantity, rate, (lo, hi), limit, confidence, n, word, need, f"{k} of {n}", bound="≤")


def _cases_to_decide(rate: float, n: int, limit: float, confidence: float, most: int = 10 ** 7) -> int | None:
    """The least m > n whose exact interval at `rate` (k = rate·m) clears `limit` on the
    rate's side; None beyond `most`."""
    def decides(m):
        lo, hi = rate_interval(rate * m, m, confidence)
        return hi <= limit if rate < limit else lo > limit
    lo_m, hi_m = n, n + 1
    while not decides(hi_m):
        lo_m, hi_m = hi_m, 2 * hi_m
        if hi_m > most:
            return None
    while hi_m - lo_m > 1:
        mid = (lo_m + hi_m) // 2
        lo_m, hi_m = (lo_m, mid) if decides(mid) else (mid, hi_m)
    return hi_m

