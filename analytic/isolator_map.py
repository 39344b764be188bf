"""A contact engine's rocking state on a non-linear isolator carried to θ = 0 along the rigid
model's equations (model.md, "Counting impacts, and effective β"): what hybrid.map_to_impact
does for the linear isolator, with the isolator's element (physics.py, "non-linear isolators")
in its phase at that state.

The phase is read off the engine's history: a rigid slider (a friction pendulum, a ball in a
bowl, a double pendulum) slips its way while |u̇| exceeds SLIP_SPEED, else its base is pinned; a
double pendulum's second surface slides too (its element yielded, physics.slip_phase) once the
element's stretch u − u_p, read off the engine's element slider, reaches u_y. A bilinear bearing
is plastic while its slider follows the base (it moved by more than half the base's travel over
the last row, the same way), else elastic with the slider where the engine has it.

Backward from a row after the impact (map_to_impact: the bearing) the phase is held, and where
it would change before θ = 0 the map gives None. Forward (pendulum_forward: every rigid slider)
the phases change as the model changes them, so a base that the impact kicks loose and that
sticks again within the window is followed as the model moves it (issue 34).
"""
from __future__ import annotations

import math

from scipy.integrate import solve_ivp

from . import physics
from .errors import require
from .system import BALL_IN_BOWL, BILINEAR, DOUBLE_PENDULUM, FRICTION_PENDULUM

#: the kinds whose base itself sticks (a rigid slider): mapped forward, their phases changing as
#: the model's do (the ball in a bowl is the friction pendulum's equations: physics.isolator_params
#: runs it as one; a double pendulum adds a Jenkins element, whose slider the engine reports)
PENDULUMS = (FRICTION_PENDULUM, BALL_IN_BOWL, DOUBLE_PENDULUM)
#: the kinds whose phase a contact engine's row tells
MAPPED = (BILINEAR, *PENDULUMS)

#: m/s; a pendulum's base slower than this is taken as pinned: above the engines' creep of a
#: stuck base (MuJoCo ~1e-8, PyBullet ~5e-5 while the block settles), far below a slip's speed
SLIP_SPEED = 1e-3


def reads_slider(system) -> bool:
    """Whether a contact engine's rows must carry the element's slider (extras["isolator_slider"])
    for the phase to be read: a bilinear bearing, a double pendulum of two frictions."""
    _, ip = physics.isolator_params(system, 0.0)
    return system.isolator_kind in MAPPED and ip[physics.I_KEL] > 0.0


def phase_at(system, u_dot: float, slider_step: float | None = None, base_step: float | None = None, *,
             u: float = 0.0, u_p: float = 0.0) -> int:
    """The element's phase (0 stuck or elastic, ±1 slipping that way, ±2 a double pendulum's
    second surface sliding too) of a contact engine's row: from the base's speed u̇ (a rigid
    slider; a double pendulum's regime from its element's stretch u − u_p, m, as physics.slip_phase
    reads it), or from how the slider moved against the base over the last row (the bearing:
    `slider_step`, `base_step`, m)."""
    if system.isolator_kind in PENDULUMS:
        if abs(u_dot) <= SLIP_SPEED:
            return 0
        _, ip = physics.isolator_params(system, 0.0)
        return int(physics.slip_phase(ip, 1.0 if u_dot > 0 else -1.0, u, u_p))
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
    held = (BILINEAR, FRICTION_PENDULUM, BALL_IN_BOWL)  # a double pendulum is mapped forward only
    require(kind in held, "isolator", kind, " or ".join(held))
    sp, ip = physics.isolator_params(system, 0.0)
    u, ud, th, thd = (float(x) for x in state)
    if th == 0:
        return t, thd, ud
    s = 1.0 if th > 0 else -1.0
    u_y = ip[physics.I_FSLIP] / ip[physics.I_KEL] if kind == BILINEAR else 0.0
    pinned = kind != BILINEAR and phase == 0
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


def pendulum_forward(system, motion, t0: float, state, t1: float, *, phase: int | None = None, u_p: float = 0.0,
                     to_landing: bool = False, rtol: float = 1e-10, atol: float = 1e-12):
    """The rigid model's state (u, u̇, θ, θ̇) at t1 of a rigid slider's rocking from `state` at t0,
    its phases taken as the model takes them (hybrid._IsolatorIntegrator): slipping its way while
    u̇ ≠ 0; where a slip stops, pinned if the demand is within the slider's limit, else slipping
    the demand's way; pinned until the demand passes the limit; a double pendulum's element
    yielding where its stretch reaches u_y (physics.slip_phase, slider_position). `phase`: the
    slider's at t0 (default: from u̇ as the model reads it); `u_p`: the element's slider there (m).
    None when θ returns to 0 first (another impact) or the phases change more than MAX_PHASES
    times. to_landing: run to θ = 0 instead, and return (t, state) there (None if it is not
    reached by t1)."""
    sp, ip = physics.isolator_params(system, 0.0)
    u_y = ip[physics.I_UY]
    limit = physics.stick_limit(sp, ip)
    y = [float(x) for x in state]
    s = 1.0 if (y[2] > 0 or (y[2] == 0 and y[3] > 0)) else -1.0
    if to_landing and y[2] == 0:
        return t0, tuple(y)

    def demand(tt, y):
        return physics.rigid_demand(sp, ip, s, y[2], y[3], y[0], u_p, motion.at(tt))

    def slip(sigma, y):
        return int(physics.slip_phase(ip, float(sigma), y[0], u_p))

    def stick_or_slip(tt, y):
        d = demand(tt, y)
        return 0 if abs(d) <= limit else slip(1 if d > 0 else -1, y)
    if phase is None:
        phase = slip(1 if y[1] > 0 else -1, y) if y[1] != 0 else stick_or_slip(t0, y)
    elif phase == 0:  # a pinned base whose demand is past its limit already slips
        phase = stick_or_slip(t0, y)
    t = t0
    for _ in range(MAX_PHASES):
        if phase == 0:
            y[1] = 0.0
        sigma = 1 if phase > 0 else -1
        yielding = abs(phase) == 1 and u_y > 0.0  # a double pendulum's element, elastic

        def rhs(tt, yy, phase=phase):
            udd, thdd, _ = physics.isolator_rocking_accelerations(
                sp, ip, phase, s, yy[2], yy[3], yy[0], yy[1], physics.slider_position(ip, phase, yy[0], u_p),
                motion.at(tt))
            return [yy[1], udd, yy[3], thdd]

        def land(tt, yy):  # θ back to 0 (it starts there, moving away: only a return counts)
            return s * yy[2]
        land.terminal, land.direction = True, -1

        def change(tt, yy, phase=phase):  # a slip stops; a pinned base's demand reaches the limit
            return phase * yy[1] if phase != 0 else limit - abs(demand(tt, yy))
        change.terminal, change.direction = True, -1

        def yields(tt, yy):  # the element's stretch reaches u_y: the second surface slides
            return u_y - sigma * (yy[0] - u_p)
        yields.terminal, yields.direction = True, -1
        events = [land, change, yields] if yielding else [land, change]
        sol = solve_ivp(rhs, (t, t1), y, method="DOP853", rtol=rtol, atol=atol, events=events)
        if sol.status == 0:
            return None if to_landing else tuple(float(v) for v in sol.y[:, -1])
        if len(sol.t_events[0]):
            return (float(sol.t_events[0][0]), tuple(float(v) for v in sol.y_events[0][0])) if to_landing else None
        hit = 1 if len(sol.t_events[1]) else 2
        t, y = float(sol.t_events[hit][0]), [float(v) for v in sol.y_events[hit][0]]
        if hit == 2:  # regime II: the element's slider moves with the base (slider_position)
            phase = 2 * sigma
        elif phase != 0:  # the slip stopped: a yielded element's slider stays where it is, and
            # it sticks, or slips on the other way
            u_p = float(physics.slider_position(ip, phase, y[0], u_p))
            y[1] = 0.0
            new = stick_or_slip(t, y)
            phase = 0 if new * phase > 0 else new  # on the same way is rounding (hybrid.isolator_event)
        else:
            phase = slip(1 if demand(t, y) > 0 else -1, y)
    return None


def image_after_impact(system, motion, t_cross: float, u_cross: float, u_dot_pre: float, theta_dot_pre: float,
                       t_k: float, theta_dot_k: float, *, phase_pre: int = 0, u_p: float = 0.0,
                       rtol: float = 1e-10, atol: float = 1e-12):
    """(θ̇⁺, u̇⁺) just after an impact at t_cross on a pendulum: the θ̇⁺ whose forward run of the
    rigid model (pendulum_forward, the base's u̇⁺ from the momentum, base_velocity_after) has
    the engine's θ̇ at t_k. The impact kicks a pinned base loose and it may stick again within
    the window: a backward map holding the phase of row k cannot see that, and read β 3% high
    on a sticking friction pendulum (issue 34); forward, the base moves as the model says it
    moves. None where no θ̇⁺ from 0.2 to 1.2 θ̇⁻ reaches θ̇_k (or none is found where the
    forward run returns to θ = 0 first: the θ̇⁺ so small that the block falls back). `phase_pre`,
    `u_p`: the slider's phase before the impact and the element's slider at it: a base that goes
    on its way keeps its phase (a double pendulum's regime), as hybrid's slider_after_velocity."""
    from scipy.optimize import brentq  # lazy: scipy.optimize only for an impact on a moving slider

    def miss(theta_dot_post):
        u_dot_post = base_velocity_after(system, u_dot_pre, theta_dot_pre, theta_dot_post)
        state = (u_cross, u_dot_post, 0.0, theta_dot_post)
        phase = phase_pre if phase_pre * u_dot_post > 0 else None
        end = pendulum_forward(system, motion, t_cross, state, t_k, phase=phase, u_p=u_p, rtol=rtol, atol=atol)
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


__all__ = ["MAPPED", "PENDULUMS", "SLIP_SPEED", "reads_slider", "phase_at", "map_to_impact", "base_velocity_after",
           "pendulum_forward", "image_after_impact"]
