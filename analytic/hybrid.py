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

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from .coefficients import beta, beta2, beta3
from .errors import require, require_positive_finite
from .motion import GroundMotion
from .protocol import run_inputs
from .status import Status
from .system import System
from .trajectory import DEFAULT_IMPACT_THRESHOLD, EnergyLog, Impact, Trajectory, cumulative_impact_loss

# state vector: u, u̇, θ, θ̇, ground work W, dashpot loss D
U, UD, TH, THD, W, D = range(6)


@dataclass(frozen=True)
class AnalyticSettings:
    """How to integrate the analytic model.

    rtol, atol: solve_ivp tolerances (atol applies to u in m and θ in rad alike).
    rest_velocity: rocking ends at an impact whose |θ̇⁻| is below rest_velocity·p·α
        (dimensionless). Free rocking with inelastic impacts is a Zeno sequence;
        this floor is a numerical setting, not physics (model.md). Rocking also ends
        at every impact of a block below the no-bounce slenderness (β ≤ 0).
    output_dt: stored points are at most this far apart (s), for plotting.
    max_step: largest integrator step (s); bounds how long a threshold crossing of
        the base acceleration can hide inside one step.
    max_events: a run with more events than this stops with status 'event-limit'.
    """

    rtol: float = 1e-10
    atol: float = 1e-12
    method: str = "DOP853"
    rest_velocity: float = 1e-5
    output_dt: float = 0.005
    max_step: float = 0.01
    max_events: int = 200_000

    def __post_init__(self):
        for name in ("rtol", "atol", "rest_velocity", "output_dt", "max_step"):
            require_positive_finite(name, getattr(self, name))
        require(self.method in ("DOP853", "RK45", "Radau", "LSODA", "BDF", "RK23"),
                "method", self.method, "a solve_ivp method name")


# --- the equations of motion ------------------------------------------------------

def rocking_accelerations(sys: System, s: int, theta, theta_dot, u, u_dot, xg_dd):
    """(ü, θ̈) in rocking mode s = ±1 (model.md's 2-DOF equations); fixed base: ü = 0."""
    h, b, m, g = sys.h, sys.b, sys.mass, sys.gravity
    L1 = h * math.cos(theta) + s * b * math.sin(theta)
    L2 = s * b * math.cos(theta) - h * math.sin(theta)
    J = m * sys.R**2 + sys.inertia
    if sys.fixed_base:
        return 0.0, (-m * L1 * xg_dd - m * g * L2) / J
    M = sys.total_mass
    f_u = -M * xg_dd - m * L2 * theta_dot**2 - sys.damping * u_dot - sys.stiffness * u
    f_t = -m * L1 * xg_dd - m * g * L2
    det = M * J - (m * L1) ** 2
    return (J * f_u - m * L1 * f_t) / det, (M * f_t - m * L1 * f_u) / det


def base_acceleration(sys: System, u, u_dot, xg_dd):
    """Absolute base acceleration in pure translation, a = ü + ẍg (m/s²)."""
    if sys.fixed_base:
        return xg_dd
    return -(sys.damping * u_dot + sys.stiffness * u) / sys.total_mass


def uplift_direction(sys: System, a: float) -> int:
    """+1 / −1 if an absolute base acceleration a lifts the block about O / O', else 0."""
    thr = sys.uplift_acceleration
    return 1 if a < -thr else (-1 if a > thr else 0)


def energy(sys: System, s, u, u_dot, theta, theta_dot):
    """(kinetic, potential) in J, velocities relative to the ground (model.md)."""
    h, b, m = sys.h, sys.b, sys.mass
    s = np.where(np.asarray(theta) >= 0, 1.0, -1.0) if s is None else s
    xd = theta_dot * (h * np.cos(theta) + s * b * np.sin(theta))
    zd = theta_dot * (s * b * np.cos(theta) - h * np.sin(theta))
    mb = 0.0 if sys.fixed_base else sys.base_mass
    kin = 0.5 * mb * u_dot**2 + 0.5 * m * ((u_dot + xd) ** 2 + zd**2) + 0.5 * sys.inertia * theta_dot**2
    pot = 0.5 * sys.stiffness * u**2 * (not sys.fixed_base) + m * sys.gravity * (
        s * b * np.sin(theta) + h * np.cos(theta) - h)
    return kin, pot


def impact_map(sys: System, theta_dot_pre: float, u_dot_pre: float, *, continued: bool):
    """Post-impact (θ̇⁺, u̇⁺) at θ = 0 (perfectly inelastic, no bounce, no slide)."""
    lam, mu, h = sys.slenderness, sys.mu, sys.h
    if continued:
        return beta(lam, mu) * theta_dot_pre, u_dot_pre + beta2(lam, mu, h) * theta_dot_pre
    return 0.0, u_dot_pre + beta3(mu, h) * theta_dot_pre


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
    balance. A run that overturns stops at the overturning time.
    """
    settings = settings or AnalyticSettings()
    motion, duration = run_inputs(system, motion, duration, theta0, impact_threshold,
                                  theta_dot0=theta_dot0, u0=u0, u_dot0=u_dot0)
    return _Integrator(system, motion, settings, duration, progress, impact_threshold).run(
        theta0, theta_dot0, u0, u_dot0)


class _Integrator:
    def __init__(self, system, motion, settings, duration, progress, impact_threshold):
        self.impact_threshold = impact_threshold
        self.sys, self.motion, self.cfg, self.T = system, motion, settings, duration
        self.progress = progress
        self.breaks = list(motion.breakpoints(duration)) + [duration]
        self.rest = settings.rest_velocity * system.p * system.alpha
        self.beta = beta(system.slenderness, system.mu)
        self.out_t, self.out_y, self.out_mode = [], [], []
        self.impacts, self.uplifts = [], []
        self.impact_loss = 0.0
        self.losses = []  # energy lost in each impact (J), in the order of self.impacts
        self.peak = 0.0  # largest |θ| of the current half-cycle
        # located only so that max |u| is exact, not read off stored points
        self.base_peak = _event(lambda t, y: y[UD], "base-peak", 0)
        self.base_peak.terminal = False

    # right-hand sides ---------------------------------------------------------------
    def rhs_translation(self, t, y):
        sys = self.sys
        xg = self.motion.at(t)
        if sys.fixed_base:
            return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        M = sys.total_mass
        udd = -xg - (sys.damping * y[UD] + sys.stiffness * y[U]) / M
        return (y[UD], udd, 0.0, 0.0, -xg * M * y[UD], sys.damping * y[UD] ** 2)

    def rhs_rocking(self, s):
        sys = self.sys
        m, h, b = sys.mass, sys.h, sys.b
        M = 0.0 if sys.fixed_base else sys.total_mass

        def f(t, y):
            xg = self.motion.at(t)
            udd, thdd = rocking_accelerations(sys, s, y[TH], y[THD], y[U], y[UD], xg)
            L1 = h * math.cos(y[TH]) + s * b * math.sin(y[TH])
            return (y[UD], udd, y[THD], thdd, -xg * (M * y[UD] + m * L1 * y[THD]),
                    sys.damping * y[UD] ** 2)
        return f

    # one smooth piece -----------------------------------------------------------------
    def solve(self, fun, t0, t1, y0, events):
        try:
            return solve_ivp(fun, (t0, t1), y0, method=self.cfg.method, rtol=self.cfg.rtol,
                             atol=self.cfg.atol, events=events, dense_output=True,
                             max_step=self.cfg.max_step)
        except ValueError as e:
            # solve_ivp checks an event's sign change on the step ends, brentq re-evaluates
            # it on the dense output: in rounding's worst case they disagree and brentq
            # raises. A failed run is a status, not a traceback.
            return _Failed(str(e))

    def store(self, sol, t0, t1, mode):
        dt = self.cfg.output_dt
        grid = np.arange(math.ceil(t0 / dt - 1e-9), math.floor(t1 / dt + 1e-9) + 1) * dt
        extra = [te for te, ev in zip(sol.t_events or [], self._evs) if not ev.terminal]
        extra = np.concatenate(extra) if extra else np.empty(0)
        inside = np.concatenate([sol.t, extra, grid])
        ts = np.unique(inside[(inside > t0) & (inside < t1)])
        ts = np.union1d(ts, [t0, t1])
        ys = sol.sol(ts) if sol.sol is not None else np.repeat(sol.y[:, :1], ts.size, axis=1)
        if mode == 0:
            ys[TH] = 0.0
            ys[THD] = 0.0
        self.out_t.append(ts)
        self.out_y.append(ys)
        self.out_mode.append(np.full(ts.size, mode, dtype=np.int8))
        if mode != 0:
            self.peak = max(self.peak, float(np.max(np.abs(ys[TH]))))

    def run(self, theta0, theta_dot0, u0, u_dot0):
        sys, cfg = self.sys, self.cfg
        start = time.perf_counter()
        t = 0.0
        y = np.array([u0, u_dot0, theta0, theta_dot0, 0.0, 0.0])
        if theta0 != 0:
            mode = 1 if theta0 > 0 else -1
        elif theta_dot0 != 0:
            mode = 1 if theta_dot0 > 0 else -1
        else:
            mode = self.uplift_mode(t, y)
            if mode:
                self.uplifts.append(0.0)
        status, message = Status.COMPLETED, "reached the end time"
        overturn_time = None
        events = 0
        ibreak = 1
        last_report = start
        while t < self.T:
            while ibreak < len(self.breaks) and self.breaks[ibreak] <= t + 1e-12:
                ibreak += 1
            t_end = self.breaks[ibreak] if ibreak < len(self.breaks) else self.T
            if mode == 0:
                fun, evs = self.rhs_translation, self.uplift_events()
            else:
                fun, evs = self.rhs_rocking(mode), self.rocking_events(mode, t, y)
            if not sys.fixed_base:
                evs = evs + [self.base_peak]
            self._evs = evs
            sol = self.solve(fun, t, t_end, y, evs)
            if sol.status == -1:
                status, message = Status.FAILED, f"integration failed at t = {t:.6g} s: {sol.message}"
                break
            hit = self.first_terminal(sol, evs)
            if hit is None:
                self.store(sol, t, sol.t[-1], mode)
                t, y = float(sol.t[-1]), sol.y[:, -1].copy()
                continue
            k, te, ye = hit
            self.store(sol, t, te, mode)
            if mode:
                self.peak = max(self.peak, abs(float(ye[TH])))
            t, y = te, ye.copy()
            events += 1
            if events > cfg.max_events:
                status, message = Status.EVENT_LIMIT, (
                    f"stopped after {cfg.max_events} events at t = {t:.6g} s (max_events)")
                break
            kind = evs[k].kind
            if kind == "overturn":
                status, message = Status.OVERTURNED, f"|θ| reached α at t = {t:.6g} s"
                overturn_time = t
                break
            if kind == "impact":
                mode, y = self.impact(t, y, mode)
            else:  # uplift
                mode = evs[k].side
                self.uplifts.append(t)
                self.peak = 0.0
            if self.progress and time.perf_counter() - last_report > 1.0:
                self.progress(t, self.T)
                last_report = time.perf_counter()
        return self.trajectory(status, message, overturn_time, time.perf_counter() - start)

    def uplift_mode(self, t, y):
        return uplift_direction(self.sys, base_acceleration(self.sys, y[U], y[UD], self.motion.at(t)))

    def impact(self, t, y, mode):
        sys = self.sys
        y[TH] = 0.0
        thd_pre, ud_pre = float(y[THD]), float(y[UD])
        # Below the no-bounce slenderness β ≤ 0: the model has no rocking continuation
        # (the block would bounce back), so such an impact ends rocking (model.md).
        continued = abs(thd_pre) >= self.rest and self.beta > 0
        thd_post, ud_post = impact_map(sys, thd_pre, ud_pre, continued=continued)
        if sys.fixed_base:
            ud_post = 0.0
        k_pre = sum(energy(sys, mode, 0.0, ud_pre, 0.0, thd_pre))
        k_post = sum(energy(sys, -mode, 0.0, ud_post, 0.0, thd_post))
        self.impact_loss += float(k_pre - k_post)
        self.losses.append(float(k_pre - k_post))
        self.impacts.append(Impact(
            t=t, theta_dot_pre=thd_pre, theta_dot_post=thd_post, u_dot_pre=ud_pre,
            u_dot_post=ud_post, continued=continued, amplitude=self.peak,
            counted=self.peak > self.impact_threshold * sys.alpha))
        self.peak = 0.0
        y[THD], y[UD] = thd_post, ud_post
        if continued:
            return -mode, y
        y[THD] = 0.0
        new = self.uplift_mode(t, y)  # a base still accelerating past g·tanα re-lifts at once
        if new:
            self.uplifts.append(t)
        return new, y

    # events ---------------------------------------------------------------------------
    def uplift_events(self):
        sys, thr = self.sys, self.sys.uplift_acceleration

        def a(t, y):
            return base_acceleration(sys, y[U], y[UD], self.motion.at(t))
        # a < −thr lifts about O (θ > 0); a > thr about O' (θ < 0)
        e_pos = _event(lambda t, y: -a(t, y) - thr, "uplift", +1, side=1)
        e_neg = _event(lambda t, y: a(t, y) - thr, "uplift", +1, side=-1)
        return [e_pos, e_neg]

    def rocking_events(self, s, t0, y0):
        alpha = self.sys.alpha
        peak = _event(lambda t, y: y[THD], "peak", 0)
        peak.terminal = False  # located only so θmax is exact, not read off samples
        return [
            _event(self.impact_function(s, t0, y0), "impact", -1),
            _event(lambda t, y: s * y[TH] - alpha, "overturn", +1),
            peak,
        ]

    def impact_function(self, s, t0, y0):
        """s·θ, divided by (t − t0)^k when a piece starts at θ = 0 (after an impact or
        an uplift), k being the order of θ's first non-zero derivative there. Plain s·θ
        is zero at t0, and when a whole half-cycle of the Zeno tail fits in the first
        step the root finder returns that trivial root; divided, the function starts
        at its positive limit and vanishes only when the block really lands."""
        if y0[TH] != 0:
            return lambda t, y: s * y[TH]
        if y0[THD] != 0:
            k, limit = 1, s * y0[THD]
        else:
            _, thdd = rocking_accelerations(self.sys, s, 0.0, 0.0, y0[U], y0[UD], self.motion.at(t0))
            # at an uplift found as an event θ̈ is ~0 and θ grows as (t − t0)³
            k, limit = (2, 0.5 * s * thdd) if s * thdd > 1e-9 * self.sys.uplift_acceleration else (3, 1e-300)

        def g(t, y):
            dt = t - t0
            return s * y[TH] / dt**k if dt > 0 else limit
        return g

    @staticmethod
    def first_terminal(sol, evs):
        best = None
        for k, (te, ye) in enumerate(zip(sol.t_events, sol.y_events)):
            if len(te) and evs[k].terminal and (best is None or te[0] < best[1]):
                best = (k, float(te[0]), ye[0])
        return best

    # result ---------------------------------------------------------------------------
    def trajectory(self, status, message, overturn_time, runtime):
        sys = self.sys
        t = np.concatenate(self.out_t) if self.out_t else np.zeros(1)
        y = np.concatenate(self.out_y, axis=1) if self.out_y else np.zeros((6, 1))
        mode = np.concatenate(self.out_mode) if self.out_mode else np.zeros(1, np.int8)
        kin, pot = energy(sys, np.where(mode == 0, 1, mode), y[U], y[UD], y[TH], y[THD])
        cum = cumulative_impact_loss(t, [i.t for i in self.impacts], self.losses)
        log = EnergyLog(kinetic=kin, potential=pot, ground_work=y[W], dashpot_loss=y[D], impact_loss=cum,
                        per_impact=tuple(self.losses))
        return Trajectory(
            engine="analytic", system=sys, t=t, u=y[U], u_dot=y[UD], theta=y[TH], theta_dot=y[THD],
            mode=mode, impacts=tuple(self.impacts), uplift_times=tuple(self.uplifts),
            overturned=status == Status.OVERTURNED, overturn_time=overturn_time,
            impact_threshold=self.impact_threshold, runtime_s=runtime, status=status,
            message=message, energy=log)


class _Failed:
    status = -1

    def __init__(self, message):
        self.message = message


def _event(fun, kind, direction, side=0):
    fun.terminal = True
    fun.direction = direction
    fun.kind = kind
    fun.side = side
    return fun


def map_to_impact(system: System, motion: GroundMotion, t: float, state, *, backward: bool,
                  rtol: float = 1e-10, atol: float = 1e-12, horizon: float = 1.0):
    """Carry a rocking state (u, u̇, θ, θ̇) at time t along the rigid rocking equations
    (ground motion included) to θ = 0: forward to the next landing, or backward
    (`backward=True`) to the last lift-off from θ = 0. Returns (t0, θ̇, u̇) at θ = 0,
    or None when θ = 0 is not reached within `horizon` seconds. This is how a contact
    engine's states outside the contact transient become θ̇⁻ and θ̇⁺ (model.md)."""
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
