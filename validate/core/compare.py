"""One engine's Trajectory against the analytic one, on the same System and GroundMotion.

Rocking near overturning is chaotic, so histories are compared only up to the
agreement horizon (the first time |Δθ| exceeds AGREEMENT_FRACTION·α); the summary
metrics (θmax/α, impacts, uplift, overturning, base displacement, effective β) are
compared over the whole run. Angles are reported as fractions of α, times in s,
displacements in m.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from scipy.integrate import quad

from ...analytic.system import System
from ...analytic.trajectory import Trajectory
from .measure import REST_FRACTION, beta_errors, mode_sequence, slide_onset
from .tolerances import limit

#: Histories have parted once |Δθ| exceeds this fraction of α (the tolerance table's, with its reason).
AGREEMENT_FRACTION = limit("horizon_parting")
#: Common grid (s) both histories are resampled onto before differencing.
COMPARE_DT = 1e-3


@dataclass(frozen=True)
class Comparison:
    """`engine` against `reference` (the analytic model). Differences are engine − reference."""

    engine: str
    reference: str
    duration: float
    horizon: float                 # s; the whole common duration when `parted` is False
    parted: bool
    theta_rms_error: float         # RMS |Δθ|/α on [0, horizon]
    theta_max_error: float         # max |Δθ|/α on [0, horizon]
    theta_max_over_alpha: float
    theta_max_over_alpha_ref: float
    theta_max_diff: float
    impacts: int
    impacts_ref: int
    first_uplift: float | None       # first |θ| > REST_FRACTION·α (s), see first_tilt
    first_uplift_ref: float | None
    first_uplift_diff: float | None  # None unless both uplifted
    uplift_agree: bool               # both rocked, or neither did
    overturned: bool
    overturned_ref: bool
    overturn_agree: bool
    u_max: float
    u_max_ref: float
    u_max_rel_error: float | None    # None on a fixed base (u ≡ 0)
    beta_errors: tuple[float, ...]   # effective β / closed form − 1, per counted impact
    runtime_s: float
    # where the statue may slip (docs/sliding.md; None where the reference carries no slide):
    # its largest and final slide (m), when it started to slide (s, measure.slide_onset), and
    # the modes each run reached in order (measure.mode_sequence)
    slide_max: float | None = None
    slide_max_ref: float | None = None
    slide_final: float | None = None
    slide_final_ref: float | None = None
    slide_onset: float | None = None
    slide_onset_ref: float | None = None
    slide_onset_diff: float | None = None  # None unless both slid
    modes: tuple[str, ...] | None = None
    modes_ref: tuple[str, ...] | None = None

    @property
    def slide_rel_error(self) -> float | None:
        """The largest slide's relative error (None without a slide to compare, or where the
        reference barely slides: below SLIDE_ONSET_FRACTION·b both read as "did not slide")."""
        if self.slide_max is None or self.slide_max_ref is None:
            return None
        return None if self.slide_max_ref == 0 else self.slide_max / self.slide_max_ref - 1

    @property
    def beta_error_median(self) -> float | None:
        finite = [abs(e) for e in self.beta_errors if math.isfinite(e)]
        return float(np.median(finite)) if finite else None

    def as_dict(self) -> dict:
        out = dict(asdict(self), beta_errors=list(self.beta_errors), beta_error_median=self.beta_error_median)
        if self.slide_max_ref is None:  # a run that cannot slip: its comparison is as before
            for key in ("slide_max", "slide_max_ref", "slide_final", "slide_final_ref", "slide_onset",
                        "slide_onset_ref", "slide_onset_diff", "modes", "modes_ref"):
                out.pop(key)
        else:
            out.update(modes=list(self.modes or ()), modes_ref=list(self.modes_ref or ()),
                       slide_rel_error=self.slide_rel_error)
        return out


def agreement(traj: Trajectory, ref: Trajectory, *, dt: float = COMPARE_DT,
              fraction: float = AGREEMENT_FRACTION) -> tuple[float, bool, float, float]:
    """(horizon, parted, RMS |Δθ|/α, max |Δθ|/α) on a common grid of step dt."""
    a, b = traj.resample(dt), ref.resample(dt)
    n = min(a.t.size, b.t.size)
    alpha = ref.alpha
    d = np.abs(a.theta[:n] - b.theta[:n]) / alpha
    out = np.nonzero(d > fraction)[0]
    parted = out.size > 0
    k = int(out[0]) if parted else n
    window = d[:max(k, 1)]
    horizon = float(a.t[k]) if parted else float(a.t[n - 1])
    return horizon, parted, float(np.sqrt(np.mean(window**2))), float(np.max(window))


def compare(traj: Trajectory, ref: Trajectory, *, dt: float = COMPARE_DT) -> Comparison:
    """All of the comparison metrics of `traj` against the analytic `ref`."""
    horizon, parted, rms, worst = agreement(traj, ref, dt=dt)
    up, up_ref = first_tilt(traj), first_tilt(ref)
    fixed = ref.system.fixed_base
    return Comparison(
        engine=traj.engine, reference=ref.engine,
        duration=float(min(traj.t[-1], ref.t[-1])),
        horizon=horizon, parted=parted, theta_rms_error=rms, theta_max_error=worst,
        theta_max_over_alpha=traj.theta_max_over_alpha,
        theta_max_over_alpha_ref=ref.theta_max_over_alpha,
        theta_max_diff=_peak(traj, ref) - _peak(ref, traj),
        impacts=traj.impact_count, impacts_ref=ref.impact_count,
        first_uplift=up, first_uplift_ref=up_ref,
        first_uplift_diff=None if up is None or up_ref is None else up - up_ref,
        uplift_agree=(up is None) == (up_ref is None),
        overturned=traj.overturned, overturned_ref=ref.overturned,
        overturn_agree=traj.overturned == ref.overturned,
        u_max=traj.u_max, u_max_ref=ref.u_max,
        u_max_rel_error=None if fixed or ref.u_max == 0 else traj.u_max / ref.u_max - 1,
        beta_errors=tuple(beta_errors(traj)), runtime_s=traj.runtime_s,
        **_slides(traj, ref),
    )


def _slides(traj: Trajectory, ref: Trajectory) -> dict:
    """The slide's fields of a Comparison (empty where the reference carries no slide)."""
    if ref.slide is None:
        return {}
    on, on_ref = slide_onset(traj), slide_onset(ref)

    def largest(tr):
        return None if tr.slide is None else float(np.max(np.abs(tr.slide - tr.slide[0])))
    return dict(slide_max=largest(traj), slide_max_ref=largest(ref),
                slide_final=None if traj.slide is None else float(traj.slide[-1] - traj.slide[0]),
                slide_final_ref=float(ref.slide[-1] - ref.slide[0]), slide_onset=on, slide_onset_ref=on_ref,
                slide_onset_diff=None if on is None or on_ref is None else on - on_ref,
                modes=mode_sequence(traj), modes_ref=mode_sequence(ref))


def _peak(traj: Trajectory, other: Trajectory) -> float:
    """θmax/α for differencing: capped at 1 when either run overturned, since past α an
    overturning block's peak is its fall onto its side (π/2 in the rigid model, a little
    short of it through a compliant contact), not its rocking; overturning itself is
    compared on its own (overturn_agree)."""
    if traj.overturned or other.overturned:
        return min(traj.theta_max_over_alpha, 1.0)
    return traj.theta_max_over_alpha


def first_tilt(traj: Trajectory, fraction: float = REST_FRACTION) -> float | None:
    """First time (s) |θ| exceeds fraction·α, interpolated between samples; None if never.
    Read off every engine's history the same way: the analytic uplift event is exact,
    but a contact engine's can only be seen once θ leaves its rest band, and θ grows as
    (t − t₀)³ after a smooth uplift, so comparing the event with the reading would
    measure the band, not the engines."""
    level = fraction * traj.alpha
    a = np.abs(traj.theta)
    above = np.nonzero(a > level)[0]
    if not above.size:
        return None
    i = int(above[0])
    if i == 0:
        return float(traj.t[0])
    t0, t1, a0, a1 = traj.t[i - 1], traj.t[i], a[i - 1], a[i]
    return float(t0 + (t1 - t0) * (level - a0) / (a1 - a0))


# --- oracles and sensitivity -----------------------------------------------------------

def exact_first_impact_time(system: System, theta0: float) -> float:
    """model.md's exact time (s) from rest at tilt θ0 (rad) to the first impact, fixed
    base: t₁ = ∫₀^θ0 dθ/θ̇, θ̇² = K[cos(α − θ0) − cos(α − θ)] with K = 2·m·g·R/I_O (3g/2R for
    the block), with θ = θ0 − s² to remove the end-point singularity. A statue of two edges
    rocks on the edge s = sign θ0: its own α_s, R_s and I_s."""
    if not system.fixed_base:
        raise ValueError("exact_first_impact_time: the closed form holds on a fixed base only")
    th0 = abs(theta0)
    side = 1 if theta0 > 0 else -1
    alpha = system.edge_alpha(side)
    if not 0 < th0 < alpha:
        raise ValueError(f"theta0 = {theta0!r}: must be non-zero and smaller than α in magnitude")
    if system.asymmetric:
        K = 2 * system.mass * system.gravity * system.edge_radius(side) / system.edge_inertia(side)
    else:
        K = 3 * system.gravity / (2 * system.R)

    def integrand(s):
        if s == 0:
            return 2 / math.sqrt(K * math.sin(alpha - th0))
        # cos(a) − cos(a + x) written as 2 sin(a + x/2) sin(x/2) to keep digits for small x
        x = s * s
        diff = 2 * math.sin(alpha - th0 + x / 2) * math.sin(x / 2)
        return 2 * s / math.sqrt(K * diff)

    value, _ = quad(integrand, 0.0, math.sqrt(th0), epsabs=1e-14, epsrel=1e-13, limit=200)
    return value


def horizon_units(horizon: float, ref: Trajectory, system: System) -> dict:
    """A horizon (s) in the units of the physics: times 1/p (p = √(3g/4R), the block's
    frequency parameter) and in the reference's counted impacts before it."""
    return {"s": float(horizon), "p_units": float(horizon * system.p),
            "impacts": int(sum(1 for i in ref.counted_impacts if i.t < horizon))}


def base_history_error(traj: Trajectory, ref: Trajectory, until: float | None = None, *, dt: float = 0.002) -> float:
    """max |Δu| over the reference's u_max, on a `dt` grid from 0 to `until` (default: the
    shorter run). A base history is held to the model's up to the model's own horizon
    (own_horizon) only: a stiff bearing under a long pulse (17 impacts) disagrees with itself
    after 7 of them under 0.5% of the motion, and there the contact engines' histories part
    too (max |Δu|/u_max 0.04–0.08, against ≤ 0.006 before it), while their θmax/α stays inside
    the model's ensemble (reference_sensitivity), which judges them past it
    (docs/isolators.md, "Where a single base history is a test")."""
    end = min(traj.t[-1], ref.t[-1]) if until is None else min(until, traj.t[-1], ref.t[-1])
    grid = np.linspace(0.0, end, max(2, int(round(end / dt)) + 1))
    return float(np.max(np.abs(np.interp(grid, traj.t, traj.u) - np.interp(grid, ref.t, ref.u)))) / ref.u_max
