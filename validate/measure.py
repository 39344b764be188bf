"""Measuring, the same way for every engine (model.md): impacts counted from a θ
history, and effective β per counted impact from states outside the contact
transient mapped to θ = 0 with the rigid equations.

Contact engines hand their raw histories to `contact_trajectory`, which returns the
shared `Trajectory`; no engine measures anything itself.
"""
from __future__ import annotations

import math

import numpy as np

from isorock.analytic.coefficients import beta as beta_closed_form
from isorock.analytic.hybrid import map_to_impact
from isorock.analytic.motion import GroundMotion
from isorock.analytic.status import Status
from isorock.analytic.system import System
from isorock.analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, Impact, Trajectory, half_cycles

#: How far (s) before and after a sign change the states are taken: well outside the
#: contact transient of the default scenes (time constants of a few ms), and capped at
#: half the neighbouring half-cycles so a state never belongs to another half-cycle.
CONTACT_WINDOW = 0.03
#: |θ| below this fraction of α counts as "down" when deriving the mode of a contact engine.
REST_FRACTION = 1e-3


def contact_trajectory(engine: str, system: System, motion: GroundMotion, *, t, u, u_dot, theta, theta_dot,
                       impact_threshold: float = DEFAULT_IMPACT_THRESHOLD, runtime_s: float = 0.0,
                       status: Status = Status.COMPLETED, message: str = "", extras: dict | None = None,
                       window: float = CONTACT_WINDOW) -> Trajectory:
    """The shared Trajectory of a contact engine: modes from |θ|, impacts counted by
    model.md's rule, effective β mapped to θ = 0, uplifts where |θ| leaves the rest
    band, overturning where |θ| ≥ α."""
    t, u, u_dot, theta, theta_dot = (np.asarray(x, dtype=float) for x in (t, u, u_dot, theta, theta_dot))
    alpha = system.alpha
    rest = REST_FRACTION * alpha
    mode = np.where(theta > rest, 1, np.where(theta < -rest, -1, 0)).astype(np.int8)
    over = np.nonzero(np.abs(theta) >= alpha)[0]
    overturn_time = float(t[over[0]]) if over.size else None
    if over.size:
        status, message = Status.OVERTURNED, f"|θ| reached α at t = {overturn_time:.6g} s"
    impacts = effective_impacts(system, motion, t, u, u_dot, theta, theta_dot,
                                impact_threshold=impact_threshold, window=window)
    uplift_times = _uplifts(t, mode, window)
    return Trajectory(engine=engine, system=system, t=t, u=u, u_dot=u_dot, theta=theta, theta_dot=theta_dot,
                      mode=mode, impacts=impacts, uplift_times=uplift_times, overturned=over.size > 0,
                      overturn_time=overturn_time, impact_threshold=impact_threshold, runtime_s=runtime_s,
                      status=status, message=message, extras=dict(extras or {}))


def _uplifts(t, mode, rest_time):
    """Times the block leaves the rest band. Every impact passes through the band, so
    leaving it the other way after less than `rest_time` is rocking, not an uplift;
    leaving it the same way, or after resting longer, is."""
    out = []
    last_sign, left_at = 0, None  # sign before the band, and when the block entered it
    prev = 0
    for i in np.nonzero(np.diff(mode.astype(np.int64), prepend=0) != 0)[0]:
        m = int(mode[i])
        if m == 0:
            last_sign, left_at = prev, t[i]
        elif prev == 0:
            rested = left_at is None or t[i] - left_at >= rest_time
            if last_sign == 0 or last_sign == m or rested:
                out.append(float(t[i]))
        prev = m
    return tuple(out)


def effective_impacts(system, motion, t, u, u_dot, theta, theta_dot, *, impact_threshold=DEFAULT_IMPACT_THRESHOLD,
                      window=CONTACT_WINDOW) -> tuple[Impact, ...]:
    """One Impact per counted sign change of θ, its velocities the rigid-model images
    at θ = 0 of the states `window` seconds before and after the crossing."""
    changes = half_cycles(theta)
    counted = {i for i, peak in changes if peak > impact_threshold * system.alpha}
    out = []
    for n, (i, peak) in enumerate(changes):
        if i not in counted:
            continue
        t_cross = _crossing_time(t, theta, i)
        t_prev = t[changes[n - 1][0]] if n > 0 else t[0]
        t_next = t[changes[n + 1][0]] if n + 1 < len(changes) else t[-1]
        pre = _mapped(system, motion, t, u, u_dot, theta, theta_dot,
                      t_cross - min(window, 0.5 * (t_cross - t_prev)), backward=False, window=window)
        post = _mapped(system, motion, t, u, u_dot, theta, theta_dot,
                       t_cross + min(window, 0.5 * (t_next - t_cross)), backward=True, window=window)
        thd_pre, ud_pre = pre if pre else (math.nan, math.nan)
        thd_post, ud_post = post if post else (math.nan, math.nan)
        out.append(Impact(t=float(t_cross), theta_dot_pre=thd_pre, theta_dot_post=thd_post,
                          u_dot_pre=ud_pre, u_dot_post=ud_post, continued=True, amplitude=float(peak),
                          counted=True))
    return tuple(out)


def _crossing_time(t, theta, i):
    """Linear interpolation of the zero of θ between samples i−1 and i."""
    a, b = theta[i - 1], theta[i]
    if a == b:
        return float(t[i])
    return float(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b))


def _mapped(system, motion, t, u, u_dot, theta, theta_dot, t_at, *, backward, window):
    k = int(np.clip(np.searchsorted(t, t_at), 0, t.size - 1))
    if theta[k] == 0:
        return None
    # the rigid image lands close to the contact engine's crossing, `window` away: a few
    # windows bound the search (an image that does not land there is not this impact)
    r = map_to_impact(system, motion, float(t[k]), (u[k], u_dot[k], theta[k], theta_dot[k]),
                      backward=backward, horizon=5 * window + 0.05)
    return None if r is None else (r[1], r[2])


def beta_errors(traj: Trajectory, n: int | None = None) -> list[float]:
    """Relative error of each counted impact's effective β against the closed form."""
    ref = beta_closed_form(traj.system.slenderness, traj.system.mu)
    errs = [i.beta / ref - 1 for i in traj.counted_impacts]
    return errs[:n] if n is not None else errs
