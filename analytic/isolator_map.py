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


__all__ = ["MAPPED", "PENDULUMS", "SLIP_SPEED", "phase_at", "map_to_impact"]
