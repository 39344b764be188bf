"""A contact engine's rocking state on a non-linear isolator carried to θ = 0 along the rigid
model's equations (model.md, "Counting impacts, and effective β"): what hybrid.map_to_impact
does for the linear isolator, with the isolator's element (physics.py, "non-linear isolators")
in its phase at that state.

The phase is read off the engine's history and held over the map: a friction pendulum slips
its way while |u̇| exceeds SLIP_SPEED, else its base is pinned (and must hold: its demand
within F_s); a bilinear bearing is plastic while its slider follows the base (it moved by more
than half the base's travel over the last row, the same way), else elastic with the slider
where the engine has it. Where the phase would change before θ = 0 (a slip stops, a pinned
base breaks loose, an elastic bearing yields, a plastic one unloads) the map is not the rigid
model's image of that state alone, and it gives None: that impact's β is not measured.
"""
from __future__ import annotations

import math

from scipy.integrate import solve_ivp

from . import physics
from .errors import require
from .system import BALL_IN_BOWL, BILINEAR, FRICTION_PENDULUM

#: the kinds whose phase a contact engine's row tells (the ball in a bowl is the friction
#: pendulum's equations: physics.isolator_params runs it as one). Not the double pendulum: its
#: three phases (pinned, one surface sliding, both) are not read off the rows yet, so a contact
#: engine's impacts on it carry no effective β (NaN: not measured)
PENDULUMS = (FRICTION_PENDULUM, BALL_IN_BOWL)
MAPPED = (BILINEAR, *PENDULUMS)

#: m/s; a pendulum's base slower than this is taken as pinned: above the engines' creep of a
#: stuck base (MuJoCo ~1e-8, PyBullet ~5e-5 while the block settles), far below a slip's speed
SLIP_SPEED = 1e-3


def phase_at(system, u_dot: float, slider_step: float | None, base_step: float | None) -> int:
    """The element's phase (0 stuck or elastic, ±1 slipping that way) of a contact engine's row:
    from the base's speed (pendulum), or from how the slider moved against the base over the
    last row (bearing: `slider_step`, `base_step`, m)."""
    if system.isolator_kind in PENDULUMS:
        return 0 if abs(u_dot) <= SLIP_SPEED else (1 if u_dot > 0 else -1)
    if slider_step is None or base_step is None or base_step == 0.0:
        return 0
    follows = slider_step * base_step > 0 and abs(slider_step) > 0.5 * abs(base_step)
    return (1 if base_step > 0 else -1) if follows else 0


def map_to_impact(system, motion, t: float, state, *, phase: int, u_p: float, backward: bool,
                  rtol: float = 1e-10, atol: float = 1e-12, horizon: float = 1.0):
    """(t0, θ̇, u̇) at θ = 0 of the rocking state (u, u̇, θ, θ̇) at time t with the element in
    `phase` (slider at u_p, m), forward to the landing or backward to the lift-off; None when θ
    = 0 is not reached within `horizon` s, or the phase would change first."""
    kind = system.isolator_kind
    require(kind in MAPPED, "isolator", kind, " or ".join(MAPPED))
    sp, ip = physics.isolator_params(system, 0.0)
    u, ud, th, thd = (float(x) for x in state)
    if th == 0:
        return t, thd, ud
    s = 1.0 if th > 0 else -1.0
    u_y = ip[physics.I_FSLIP] / ip[physics.I_KEL] if kind == BILINEAR else 0.0
    pinned = kind in PENDULUMS and phase == 0
    if pinned:
        ud = 0.0
        demand = physics.stick_demand(sp, s, th, thd, u, motion.at(t))
        if abs(demand) > physics.stick_limit(sp, ip):
            return None  # the base breaks loose at once: no single phase to map in

    def slider(y):
        return y[0] - phase * u_y if kind == BILINEAR and phase != 0 else u_p

    def rhs(tt, y):
        udd, thdd, _ = physics.isolator_rocking_accelerations(sp, ip, phase, s, y[2], y[3], y[0], y[1],
                                                              slider(y), motion.at(tt))
        return [y[1], udd, y[3], thdd]

    def land(tt, y):
        return s * y[2]
    land.terminal, land.direction = True, 0

    if pinned:
        def change(tt, y):  # the demand reaching the slider's limit
            return physics.stick_limit(sp, ip) - abs(physics.stick_demand(sp, s, y[2], y[3], y[0], motion.at(tt)))
    elif phase != 0:
        def change(tt, y):  # a slip stops, a plastic bearing unloads
            return phase * y[1]
    elif kind == BILINEAR:
        def change(tt, y):  # an elastic bearing yields
            return u_y - abs(y[0] - u_p)
    change.terminal, change.direction = True, 0

    t_end = t - horizon if backward else t + horizon
    sol = solve_ivp(rhs, (t, t_end), [u, ud, th, thd], method="DOP853", rtol=rtol, atol=atol,
                    events=[land, change])
    if not len(sol.t_events[0]):
        return None
    t0 = float(sol.t_events[0][0])
    if len(sol.t_events[1]) and abs(float(sol.t_events[1][0]) - t) < abs(t0 - t):
        return None
    ye = sol.y_events[0][0]
    return t0, float(ye[3]), float(ye[1])


def base_velocity_after(system, u_dot_pre: float, theta_dot_pre: float, theta_dot_post: float) -> float:
    """u̇⁺ at an impact whose θ̇ jumps from θ̇⁻ to θ̇⁺: the system's horizontal momentum,
    M u̇ + m h θ̇ at θ = 0, which no bounded force (spring, dashpot, friction) changes in an
    instant (the model's β₂ is this relation at θ̇⁺ = β θ̇⁻)."""
    sp, _ = physics.isolator_params(system, 0.0)
    return u_dot_pre + sp[physics.M_BLOCK] * sp[physics.H] / sp[physics.M_TOTAL] * (theta_dot_pre - theta_dot_post)


#: phase changes a forward run of a pendulum may make within a window before it is given up
MAX_PHASES = 16


def pendulum_forward(system, motion, t0: float, state, t1: float, *, phase: int | None = None,
                     to_landing: bool = False, rtol: float = 1e-10, atol: float = 1e-12):
    """The rigid model's state (u, u̇, θ, θ̇) at t1 of a pendulum's rocking from `state` at t0,
    its slider's phases taken as the model takes them (hybrid._IsolatorIntegrator): slipping its
    way while u̇ ≠ 0; where a slip stops, pinned if the demand is within the slider's limit, else
    slipping the demand's way; pinned until the demand passes the limit. `phase`: the slider's
    at t0 (default: from u̇ as the model reads it). None when θ returns to 0 first (another
    impact) or the phases change more than MAX_PHASES times. to_landing: run to θ = 0 instead,
    and return (t, state) there (None if it is not reached by t1)."""
    sp, ip = physics.isolator_params(system, 0.0)
    y = [float(x) for x in state]
    s = 1.0 if (y[2] > 0 or (y[2] == 0 and y[3] > 0)) else -1.0
    if to_landing and y[2] == 0:
        return t0, tuple(y)

    def demand(tt, y):
        return physics.rigid_demand(sp, ip, s, y[2], y[3], y[0], 0.0, motion.at(tt))

    def stick_or_slip(tt, y):
        d = demand(tt, y)
        return 0 if abs(d) <= physics.stick_limit(sp, ip) else (1 if d > 0 else -1)
    if phase is None:
        phase = (1 if y[1] > 0 else -1) if y[1] != 0 else stick_or_slip(t0, y)
    elif phase == 0:  # a pinned base whose demand is past its limit already slips
        phase = stick_or_slip(t0, y)
    t = t0
    for _ in range(MAX_PHASES):
        if phase == 0:
            y[1] = 0.0

        def rhs(tt, yy, phase=phase):
            udd, thdd, _ = physics.isolator_rocking_accelerations(sp, ip, phase, s, yy[2], yy[3], yy[0], yy[1], 0.0,
                                                                  motion.at(tt))
            return [yy[1], udd, yy[3], thdd]

        def land(tt, yy):  # θ back to 0 (it starts there, moving away: only a return counts)
            return s * yy[2]
        land.terminal, land.direction = True, -1

        def change(tt, yy, phase=phase):  # a slip stops; a pinned base's demand reaches the limit
            return phase * yy[1] if phase != 0 else physics.stick_limit(sp, ip) - abs(demand(tt, yy))
        change.terminal, change.direction = True, -1
        sol = solve_ivp(rhs, (t, t1), y, method="DOP853", rtol=rtol, atol=atol, events=[land, change])
        if sol.status == 0:
            return None if to_landing else tuple(float(v) for v in sol.y[:, -1])
        if len(sol.t_events[0]):
            return (float(sol.t_events[0][0]), tuple(float(v) for v in sol.y_events[0][0])) if to_landing else None
        t, y = float(sol.t_events[1][0]), [float(v) for v in sol.y_events[1][0]]
        if phase != 0:  # the slip stopped: it sticks, or slips on the other way
            y[1] = 0.0
            new = stick_or_slip(t, y)
            phase = 0 if new * phase > 0 else new  # on the same way is rounding (hybrid.isolator_event)
        else:
            phase = 1 if demand(t, y) > 0 else -1
    return None


def image_after_impact(system, motion, t_cross: float, u_cross: float, u_dot_pre: float, theta_dot_pre: float,
                       t_k: float, theta_dot_k: float, *, rtol: float = 1e-10, atol: float = 1e-12):
    """(θ̇⁺, u̇⁺) just after an impact at t_cross on a pendulum: the θ̇⁺ whose forward run of the
    rigid model (pendulum_forward, the base's u̇⁺ from the momentum, base_velocity_after) has
    the engine's θ̇ at t_k. The impact kicks a pinned base loose and it may stick again within
    the window: a backward map holding the phase of row k cannot see that, and read β 3% high
    on a sticking friction pendulum (issue 34); forward, the base moves as the model says it
    moves. None where no θ̇⁺ from 0.2 to 1.2 θ̇⁻ reaches θ̇_k (or none is found where the
    forward run returns to θ = 0 first: the θ̇⁺ so small that the block falls back)."""
    from scipy.optimize import brentq

    def miss(theta_dot_post):
        state = (u_cross, base_velocity_after(system, u_dot_pre, theta_dot_pre, theta_dot_post), 0.0,
                 theta_dot_post)
        end = pendulum_forward(system, motion, t_cross, state, t_k, rtol=rtol, atol=atol)
        return math.nan if end is None else end[3] - theta_dot_k
    # from β = 1.2 down in steps of 0.1 to the first change of sign (a small θ̇⁺ may fall back to
    # θ = 0 before t_k: no value there), then Brent's method inside that step
    hi, f_hi = 1.2 * theta_dot_pre, miss(1.2 * theta_dot_pre)
    for beta in (1.1, 1.0, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2):
        lo, f_lo = beta * theta_dot_pre, miss(beta * theta_dot_pre)
        if math.isfinite(f_lo) and math.isfinite(f_hi) and f_lo * f_hi <= 0:
            post = brentq(miss, lo, hi, xtol=1e-14 * abs(theta_dot_pre), rtol=1e-13)
            return post, base_velocity_after(system, u_dot_pre, theta_dot_pre, post)
        hi, f_hi = lo, f_lo
    return None


__all__ = ["MAPPED", "PENDULUMS", "SLIP_SPEED", "phase_at", "map_to_impact", "base_velocity_after",
           "pendulum_forward", "image_after_impact"]
