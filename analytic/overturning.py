"""When a block has overturned: model.md's rule ("Past α"), one judge for every engine.

Rules (`physics.OVERTURN_RULES`):
- "past-alpha" (default): the motion goes on past |θ| = α (the ground can still pull the
  block back); the block has overturned when |θ| reaches π/2 (it lies on its side), or
  when the run ends with |θ| > α (there is no rest state beyond α).
- "alpha": the conservative engineering rule, overturned once |θ| reaches α.

The overturning time is when |θ| last rose through α (under "alpha": when it first
reached α), so both rules give the same time to a block that falls straight over.

`judge_overturning` judges a sampled history (any engine's t, θ); the analytic engines
locate the same crossings as events and describe their verdict with `describe`, so
every engine says the same thing the same way.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import require
from .physics import AT_ALPHA, OVERTURN_RULES, PAST_ALPHA, SIDE_ANGLE

__all__ = ["Overturning", "judge_overturning", "describe", "REASONS", "OVERTURN_RULES", "PAST_ALPHA",
           "AT_ALPHA", "SIDE_ANGLE", "THETA_MAX_DEFINITION", "theta_max_over_alpha"]

#: physics.overturn_code's verdicts, as words
REASONS = {0: "survived", 1: "reached-alpha", 2: "reached-side", 3: "ended-past-alpha"}


@dataclass(frozen=True)
class Overturning:
    """The verdict: overturned or not, when (s; None if it survived), why (a REASONS word)
    and a one-line message."""

    overturned: bool
    time: float | None
    reason: str
    message: str


def describe(code: int, t: float, t_alpha: float | None, theta_end_over_alpha: float) -> str:
    """The message for verdict `code` (physics.overturn_code) at time t (s), the block
    having last risen through α at t_alpha (s)."""
    since = f" (past α since t = {t_alpha:.6g} s)" if t_alpha is not None else ""
    if code == 0:
        return "reached the end time"
    if code == 1:
        return f"|θ| reached α at t = {t:.6g} s (overturning rule 'alpha')"
    if code == 2:
        return f"|θ| reached π/2 at t = {t:.6g} s{since}"
    return f"|θ| = {abs(theta_end_over_alpha):.4g}·α > α at t = {t:.6g} s, falling{since}"


#: What θmax/α means, stated in every run's JSON (one definition for every motion and
#: engine: where a run stops once the block's fate is known must not change it).
THETA_MAX_DEFINITION = {
    PAST_ALPHA: "the largest |θ|/α reached; for an overturned block π/(2α): it ends on its side "
                "(π/2), however early the run stopped once the fall was certain",
    AT_ALPHA: "the largest |θ|/α reached; for an overturned block 1: the conservative rule stops "
              "at α",
}


def theta_max_over_alpha(theta_max: float, alpha: float, overturned: bool, rule: str = PAST_ALPHA) -> float:
    """θmax/α by THETA_MAX_DEFINITION: an overturned block's is its end, π/2 (rule
    'past-alpha') or α (rule 'alpha'), not the angle where its run happened to stop (a
    fixed base past α after the motion stops early, a record's quiet tail runs on to π/2,
    a contact engine's block rests a little short of π/2)."""
    if overturned and math.isfinite(theta_max):
        return 1.0 if rule == AT_ALPHA else SIDE_ANGLE / alpha
    return theta_max / alpha


def _crossing(t, a, i, level):
    """Time at which |θ| = level between samples i − 1 and i (linear interpolation)."""
    if i == 0 or a[i] == a[i - 1]:
        return float(t[i])
    f = (level - a[i - 1]) / (a[i] - a[i - 1])
    return float(t[i - 1] + min(max(f, 0.0), 1.0) * (t[i] - t[i - 1]))


def judge_overturning(t, theta, alpha: float, *, motion_end: float | None = None, rule: str = PAST_ALPHA,
                      side_angle: float = SIDE_ANGLE) -> Overturning:
    """Has the block of a sampled history (t in s, θ in rad) overturned, by `rule`?

    alpha: the block's α (rad). motion_end: when the ground motion ended (s), to say in
    the message whether the block was still moving after it. side_angle: |θ| at which
    the block lies on its side (π/2; a contact engine whose block rests on its side a
    little short of it, by penetration or rounding, may pass a slightly smaller angle).
    Times are interpolated linearly between samples. A sample within a relative 1e-9
    of α (or of side_angle) has reached it: an engine that stops at α, located as an
    event, stores it to rounding, either side.
    """
    require(rule in OVERTURN_RULES, "overturn", rule, f"one of {', '.join(OVERTURN_RULES)}")
    require(math.isfinite(alpha) and 0 < alpha < side_angle, "alpha", alpha, f"in (0, {side_angle:.6g}) rad")
    t = np.asarray(t, dtype=float)
    a = np.abs(np.asarray(theta, dtype=float))
    require(t.shape == a.shape and t.ndim == 1, "t/theta", (t.shape, a.shape), "1-D arrays of one length")
    if t.size == 0:
        return Overturning(False, None, REASONS[0], "no history")
    reach = alpha * (1 - 1e-9)
    over = np.nonzero(a >= reach)[0]
    if rule == AT_ALPHA:
        if over.size == 0:
            return Overturning(False, None, REASONS[0], describe(0, float(t[-1]), None, a[-1] / alpha))
        i = int(over[0])
        when = _crossing(t, a, i, alpha)
        return Overturning(True, when, REASONS[1], describe(1, when, when, a[i] / alpha))
    side = np.nonzero(a >= side_angle * (1 - 1e-9))[0]
    end = int(side[0]) if side.size else t.size - 1
    rises = np.nonzero((a[1:end + 1] >= alpha) & (a[:end] < alpha))[0] + 1
    last_rise = _crossing(t, a, int(rises[-1]), alpha) if rises.size else (float(t[0]) if a[0] >= alpha else None)
    if side.size:
        code = 2
    elif a[-1] > alpha:
        code = 3
    else:
        return Overturning(False, None, REASONS[0], describe(0, float(t[-1]), None, a[-1] / alpha))
    message = describe(code, float(t[end]), last_rise, a[end] / alpha)
    if motion_end is not None and last_rise is not None and last_rise > motion_end:
        message += " after the motion ended"
    return Overturning(True, last_rise, REASONS[code], message)
