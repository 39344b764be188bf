"""The event-driven hybrid model (Roussis et al. 2008; model.md): pure translation
(1 DOF) and rocking about either corner (2 DOF), with uplift, perfectly inelastic
impact at θ = 0, end of rocking and overturning located as events.

This is the reference path: SciPy's `solve_ivp` (DOP853 by default) between events,
restarted at every event and at every kink of the ground motion (record samples,
pulse ends), so each piece is smooth and the result is exact to the integrator
tolerance. The state carries two quadratures, the work of the ground motion and the
energy lost in the dashpot, for the energy balance.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from . import physics
from .motion import GroundMotion
from .engine_protocol import run_inputs
from .errors import require
from .settings import AnalyticSettings
from .slide_physics import needs_contact_model
from .system import ISOLATOR_KINDS, System
from .trajectory import DEFAULT_IMPACT_THRESHOLD, Trajectory
from .integrators import TH, THD, UD, _event, _Integrator, _IsolatorIntegrator
from .slide_hybrid import simulate as simulate_sliding


# --- the physics, for callers holding a System (analytic.physics has it all) -----------

def _params(sys: System) -> tuple:
    return tuple(physics.system_params(sys, AnalyticSettings.rest_velocity).tolist())


def rocking_accelerations(sys: System, s: int, theta, theta_dot, u, u_dot, xg_dd):
    """(ü, θ̈) in rocking mode s = ±1 (physics.rocking_accelerations); fixed base: ü = 0."""
    return physics.rocking_accelerations(_params(sys), s, theta, theta_dot, u, u_dot, xg_dd)[:2]


def energy(sys: System, s, u, u_dot, theta, theta_dot):
    """(kinetic, potential) in J, velocities relative to the ground (model.md); s None:
    the corner of θ's sign."""
    sp = _params(sys)
    s = np.where(np.asarray(theta) >= 0, 1.0, -1.0) if s is None else s
    return physics.kinetic_energy(sp, s, u_dot, theta, theta_dot), physics.potential_energy(sp, s, u, theta)


def impact_map(sys: System, theta_dot_pre: float, u_dot_pre: float, *, continued: bool):
    """Post-impact (θ̇⁺, u̇⁺) at θ = 0 (perfectly inelastic, no bounce, no slide)."""
    return physics.impact_map(_params(sys), theta_dot_pre, u_dot_pre, continued)


# --- the driver -------------------------------------------------------------------

def simulate(system: System, motion: GroundMotion | None = None, *, settings: AnalyticSettings | None = None,
             duration: float | None = None, theta0: float = 0.0, theta_dot0: float = 0.0,
             u0: float = 0.0, u_dot0: float = 0.0, impact_threshold: float = DEFAULT_IMPACT_THRESHOLD,
             progress=None) -> Trajectory:
    """Integrate the hybrid model from t = 0 to `duration` (s).

    theta0: initial tilt in rad (sign picks the corner); free rocking when the
    motion is zero. impact_threshold: model.md's counting rule, as a fraction of α.
    progress: optional callable(t, duration) called about once a second. Returns a Trajectory whose `impacts` are every impact the model
    made (`counted` marks those model.md's rule counts) and whose `energy` holds the
    balance. Overturning follows settings.overturn (model.md, "Past α"): by default the
    run goes on past α and stops when |θ| reaches π/2 (or, on a fixed base after the
    motion, once the block is past α and falling); under "alpha" it stops at α.
    """
    settings = settings or AnalyticSettings()
    motion, duration = run_inputs(system, motion, duration, theta0, impact_threshold,
                                  theta_dot0=theta_dot0, u0=u0, u_dot0=u_dot0, isolators=ISOLATOR_KINDS,
                                  two_edges=True)
    if needs_contact_model(system, motion):  # the statue may slip, or the ground heaves: docs/sliding.md
        return simulate_sliding(system, motion, settings, duration, progress, impact_threshold, theta0, theta_dot0,
                                u0, u_dot0)
    integrator = _Integrator if system.fixed_base or system.isolator is None else _IsolatorIntegrator
    return integrator(system, motion, settings, duration, progress, impact_threshold).run(
        theta0, theta_dot0, u0, u_dot0)



def map_to_impact(system: System, motion: GroundMotion, t: float, state, *, backward: bool,
                  rtol: float = 1e-10, atol: float = 1e-12, horizon: float = 1.0):
    """Carry a rocking state (u, u̇, θ, θ̇) at time t along the rigid rocking equations
    (ground motion included) to θ = 0: forward to the next landing, or backward
    (`backward=True`) to the last lift-off from θ = 0. Returns (t0, θ̇, u̇) at θ = 0,
    or None when θ = 0 is not reached within `horizon` seconds. This is how a contact
    engine's states outside the contact transient become θ̇⁻ and θ̇⁺ (model.md)."""
    require(system.fixed_base or system.isolator is None, "isolator", system.isolator_kind,
            "linear to map a contact engine's states to θ = 0 (no contact engine carries another yet)")
    u, ud, th, thd = (float(x) for x in state)
    if th == 0:
        return t, thd, ud
    s = 1 if th > 0 else -1
    integ = _Integrator(system, motion, AnalyticSettings(rtol=rtol, atol=atol), t + horizon, None,
                        DEFAULT_IMPACT_THRESHOLD)
    fun = integ.rhs_rocking(s)
    land = _event(lambda tt, y: s * y[TH], "impact", 0)
    t_end = t - horizon if backward else t + horizon
    sol = solve_ivp(fun, (t, t_end), [u, ud, th, thd, 0.0, 0.0], method="DOP853", rtol=rtol, atol=atol,
                    events=[land])
    if not len(sol.t_events[0]):
        return None
    ye = sol.y_events[0][0]
    return float(sol.t_events[0][0]), float(ye[THD]), float(ye[UD])
