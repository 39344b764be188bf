"""The reference path's integrators (analytic.hybrid's driver): SciPy's `solve_ivp` between
events, restarted at every event and every kink of the ground motion, on a fixed base or a
linear isolator (_Integrator) and on a non-linear isolator (_IsolatorIntegrator); the sliding
model's (analytic.slide_hybrid) builds on the latter.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from . import physics
from .overturning import describe
from .status import Status
from .trajectory import EnergyLog, Impact, Trajectory, cumulative_impact_loss

# state vector: u, u̇, θ, θ̇, ground work W, dashpot loss D
U, UD, TH, THD, W, D = range(6)
EPS = np.finfo(float).eps  # solve_ivp's event location: Brent's method to 4·eps


class StopRun(Exception):
    """Raised by a model's event handling when it cannot go on: the run ends at t with
    `status` and `message` (the state stored so far stands)."""

    def __init__(self, status, message, t):
        super().__init__(message)
        self.status, self.message, self.t = status, message, t


class _Integrator:
    def __init__(self, system, motion, settings, duration, progress, impact_threshold):
        self.impact_threshold = impact_threshold
        self.sys, self.motion, self.cfg, self.T = system, motion, settings, duration
        self.progress = progress
        self.breaks = list(motion.breakpoints(duration)) + [duration]
        # the physics takes packed parameters (analytic.physics); plain floats here
        self.sp = tuple(physics.system_params(system, settings.rest_velocity).tolist())
        mp, self.acc = physics.motion_params(motion)
        self.mp = tuple(mp.tolist())  # Python floats: numpy scalars would slow every right-hand side
        self.motion_end = motion.end_time
        self.out_t, self.out_y, self.out_mode = [], [], []
        self.impacts, self.uplifts = [], []
        self.impact_loss = 0.0
        self.losses = []  # energy lost in each impact (J), in the order of self.impacts
        self.peak = 0.0  # largest |θ| of the current half-cycle
        self.graze = False  # a grazing uplift stayed down: re-lift only clearly above g·tanα
        self.last_past_alpha = None  # when |θ| last rose through α
        # located only so that max |u| is exact, not read off stored points
        self.base_peak = _event(lambda t, y: y[UD], "base-peak", 0)
        self.base_peak.terminal = False

    def xg(self, t):
        return physics.ground_acceleration(t, self.mp, self.acc)

    # right-hand sides ---------------------------------------------------------------
    def rhs_translation(self, t, y):
        sp = self.sp
        xg = self.xg(t)
        udd = physics.translation_acceleration(sp, y[U], y[UD], xg)
        return (y[UD], udd, 0.0, 0.0, -xg * sp[physics.M_TOTAL] * y[UD], sp[physics.C_DAMP] * y[UD] ** 2)

    def rhs_rocking(self, s):
        sp = self.sp
        m = sp[physics.M_BLOCK]
        M = 0.0 if self.sys.fixed_base else sp[physics.M_TOTAL]
        c = sp[physics.C_DAMP]

        def f(t, y):
            xg = self.xg(t)
            udd, thdd, L1 = physics.rocking_accelerations(sp, s, y[TH], y[THD], y[U], y[UD], xg)
            return (y[UD], udd, y[THD], thdd, -xg * (M * y[UD] + m * L1 * y[THD]), c * y[UD] ** 2)
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

    def store_at_rest(self, t0, t1, y):
        """A fixed base in translation does not move: its state is stored on the grid."""
        dt = self.cfg.output_dt
        grid = np.arange(math.ceil(t0 / dt - 1e-9), math.floor(t1 / dt + 1e-9) + 1) * dt
        ts = np.union1d(grid[(grid > t0) & (grid < t1)], [t0, t1])
        self.out_t.append(ts)
        self.out_y.append(np.repeat(y[:, None], ts.size, axis=1))
        self.out_mode.append(np.zeros(ts.size, dtype=np.int8))

    def run(self, theta0, theta_dot0, u0, u_dot0):
        sys, cfg = self.sys, self.cfg
        start = time.perf_counter()
        t = 0.0
        y = self.initial_state(u0, u_dot0, theta0, theta_dot0)
        status, message = Status.COMPLETED, "reached the end time"
        past_alpha_rule = cfg.overturn == physics.PAST_ALPHA
        verdict = 0
        try:
            if theta0 != 0:
                mode = 1 if theta0 > 0 else -1
            elif theta_dot0 != 0:
                mode = 1 if theta_dot0 > 0 else -1
            else:
                mode = self.uplift_mode(t, y)
                if mode:
                    self.uplifts.append(0.0)
            mode = self.begin(t, y, mode)
            verdict, t, y, status, message = self.integrate(t, y, mode, status, message, past_alpha_rule, start)
        except StopRun as stop:  # the model cannot go on (a sliding block's free flight, say)
            status, message, t = stop.status, stop.message, stop.t
            y = self.out_y[-1][:, -1] if self.out_y else y
        if status == Status.COMPLETED and verdict == 0:
            verdict = physics.overturn_code(not past_alpha_rule, float(y[TH]),
                                            sys.edge_alpha(1 if y[TH] >= 0 else -1), False)
        overturn_time = None
        if verdict:
            status, overturn_time = Status.OVERTURNED, self.last_past_alpha
            message = describe(verdict, t, overturn_time, float(y[TH]) / sys.edge_alpha(1 if y[TH] >= 0 else -1))
        return self.trajectory(status, message, overturn_time, time.perf_counter() - start)

    def integrate(self, t, y, mode, status, message, past_alpha_rule, start):
        """The event loop from (t, y) in `mode`: (verdict, t, y, status, message) where it ended."""
        sys, cfg = self.sys, self.cfg
        verdict = 0
        events = 0
        ibreak = 1
        last_report = start
        while t < self.T:
            while ibreak < len(self.breaks) and self.breaks[ibreak] <= t + 1e-12:
                ibreak += 1
            t_end = self.breaks[ibreak] if ibreak < len(self.breaks) else self.T
            if mode == 0 and self.rests_still():
                # the state cannot change: the first uplift is found from the motion itself
                margin = physics.GRAZE_MARGIN if self.graze else 0.0
                t_up, side = physics.first_uplift(self.sp, self.mp, self.acc, t, t_end, margin)
                self.store_at_rest(t, t_up, y)
                t = t_up
                if side:
                    events += 1
                    if events > cfg.max_events:
                        status, message = Status.EVENT_LIMIT, (
                            f"stopped after {cfg.max_events} events at t = {t:.6g} s (max_events)")
                        break
                    mode = self.lift(t, side)
                continue
            if (mode and past_alpha_rule and sys.fixed_base and t >= self.motion_end
                    and mode * y[TH] > sys.edge_alpha(mode) and mode * y[THD] > 0):
                verdict = 3  # past α and falling, nothing left to pull it back
                break
            if mode == 0:
                fun, evs = self.rhs_translation, self.translation_events(t, y)
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
            t_cut = sol.t[-1] if hit is None else hit[1]
            for te, ev in zip(sol.t_events, evs):
                if ev.kind == "alpha" and len(te) and te[te <= t_cut].size:
                    self.last_past_alpha = float(te[te <= t_cut][-1])
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
            if kind == "alpha":
                self.last_past_alpha = t
                verdict = 1 if not past_alpha_rule else 3
                break
            if kind == "side":
                verdict = 2
                break
            if kind == "impact":
                mode, y = self.impact(t, y, mode)
            elif kind == "isolator":  # a non-linear isolator's slider sticks or slips
                mode, y = self.isolator_event(t, y, mode, evs[k])
            elif kind == "uplift":
                mode = self.lift(t, evs[k].side)
            else:  # a model's own event (a sliding block's: slide_hybrid)
                mode, y = self.transition(t, y, mode, evs[k])
            if self.progress and time.perf_counter() - last_report > 1.0:
                self.progress(t, self.T)
                last_report = time.perf_counter()
        return verdict, t, y, status, message

    def rests_still(self):
        """Whether the state cannot change while the block rests (a fixed base): the run then
        finds the first uplift from the motion itself (physics.first_uplift)."""
        return self.sys.fixed_base

    def begin(self, t, y, mode):
        """The mode the run starts in (a model that tells more than the corner refines it)."""
        return mode

    def transition(self, t, y, mode, ev):
        raise NotImplementedError(ev.kind)

    def initial_state(self, u0, u_dot0, theta0, theta_dot0):
        return np.array([u0, u_dot0, theta0, theta_dot0, 0.0, 0.0])

    def kinetic(self, s, u_dot, y):
        """The kinetic energy (J) of state y with the base's velocity u_dot (physics.kinetic_energy)."""
        return physics.kinetic_energy(self.sp, s, u_dot, y[TH], y[THD])

    def lift(self, t, side):
        self.uplifts.append(t)
        self.peak = 0.0
        self.graze = False
        return side

    def uplift_mode(self, t, y):
        return physics.uplift_direction(
            self.sp, physics.base_acceleration(self.sp, y[U], y[UD], self.xg(t)))

    def impact(self, t, y, mode):
        sp = self.sp
        y[TH] = 0.0
        thd_pre, ud_pre = float(y[THD]), float(y[UD])
        # Below the no-bounce slenderness β ≤ 0: the model has no rocking continuation
        # (the block would bounce back), so such an impact ends rocking (model.md).
        continued = physics.impact_continues(sp, thd_pre)
        thd_post, ud_post = physics.impact_map(sp, thd_pre, ud_pre, continued)
        loss = physics.impact_energy_loss(sp, ud_pre, thd_pre, ud_post, thd_post)
        self.impact_loss += loss
        self.losses.append(loss)
        self.impacts.append(Impact(
            t=t, theta_dot_pre=thd_pre, theta_dot_post=thd_post, u_dot_pre=ud_pre,
            u_dot_post=ud_post, continued=continued, amplitude=self.peak,
            counted=self.peak > self.impact_threshold * self.sys.edge_alpha(physics.landing_side(thd_pre))))
        self.peak = 0.0
        y[THD], y[UD] = thd_post, ud_post
        if continued:
            self.after_impact(t, y, -mode)
            return -mode, y
        y[THD] = 0.0
        self.after_impact(t, y, 0)
        # a base still accelerating past g·tanα re-lifts at once, if it lifts clearly;
        # a grazing one stays down (no rocking phases of zero length)
        new = self.relift(t, y)
        if new:
            return self.lift(t, new), y
        self.graze = True
        return 0, y

    def translation_events(self, t0, y0):
        return self.uplift_events()

    def after_impact(self, t, y, mode):
        """An impact changed u̇ (a non-linear isolator's slider may stick or slip anew)."""

    def relift(self, t, y):
        return physics.relift(self.sp, y[U], y[UD], self.xg(t))

    # events ---------------------------------------------------------------------------
    def uplift_events(self):
        sp = self.sp
        thr_pos, thr_neg = self.uplift_thresholds()

        def a(t, y):
            return physics.base_acceleration(sp, y[U], y[UD], self.xg(t))
        # a < −thr₊ lifts about O (θ > 0); a > thr₋ about O' (θ < 0)
        e_pos = _event(lambda t, y: -a(t, y) - thr_pos, "uplift", +1, side=1)
        e_neg = _event(lambda t, y: a(t, y) - thr_neg, "uplift", +1, side=-1)
        return [e_pos, e_neg]

    def uplift_thresholds(self):
        """(g·tanα₊, g·tanα₋), raised by GRAZE_MARGIN after a grazing landing (physics.relift)."""
        thr = self.sp[physics.THR] * (1.0 + (physics.GRAZE_MARGIN if self.graze else 0.0))
        return thr, physics.other_threshold(self.sp, thr)

    def rocking_events(self, s, t0, y0):
        alpha = self.sys.edge_alpha(s)
        peak = _event(lambda t, y: y[THD], "peak", 0)
        peak.terminal = False  # located only so θmax is exact, not read off samples
        # |θ| rising through α: the end of the run under the rule "alpha", and on a fixed
        # base after the motion (nothing can pull the block back); otherwise only noted
        past = _event(lambda t, y: s * y[TH] - alpha, "alpha", +1)
        past.terminal = (self.cfg.overturn == physics.AT_ALPHA
                         or (self.sys.fixed_base and t0 >= self.motion_end))
        evs = [_event(self.impact_function(s, t0, y0), "impact", -1), past, peak]
        if self.cfg.overturn == physics.PAST_ALPHA:
            evs.append(_event(lambda t, y: s * y[TH] - physics.SIDE_ANGLE, "side", +1))
        return evs

    def impact_function(self, s, t0, y0):
        """s·θ, divided by (t − t0)^k when a piece starts at θ = 0 (after an impact or
        an uplift), k being the order of θ's first non-zero derivative there. Plain s·θ
        is zero at t0, and when a whole half-cycle of the Zeno tail fits in the first
        step the root finder returns that trivial root; divided, the function starts
        at its positive limit and vanishes only when the block really lands."""
        if y0[TH] != 0:
            return lambda t, y: s * y[TH]
        kpow, limit = self.function_order(s, t0, y0)

        def g(t, y):
            dt = t - t0
            return s * y[TH] / dt**kpow if dt > 0 else limit
        return g

    def function_order(self, s, t0, y0):
        return physics.impact_function_order(self.sp, s, y0[U], y0[UD], y0[THD], self.xg(t0))

    def friction_demand(self, t, y, mode):
        """The largest |F_x/F_z| at the block's pivot over the stored states (physics.pivot_force_ratio)."""
        sp = self.sp
        return max((physics.pivot_force_ratio(sp, int(mode[i]), y[TH, i], y[THD, i], y[U, i], y[UD, i],
                                              self.xg(t[i])) for i in range(t.size)), default=0.0)

    @staticmethod
    def first_terminal(sol, evs):
        best = None
        for k, (te, ye) in enumerate(zip(sol.t_events, sol.y_events)):
            if len(te) and evs[k].terminal and (best is None or te[0] < best[1]):
                best = (k, float(te[0]), ye[0])
        return best

    # result ---------------------------------------------------------------------------
    def trajectory(self, status, message, overturn_time, runtime):
        sys, sp = self.sys, self.sp
        t = np.concatenate(self.out_t) if self.out_t else np.zeros(1)
        y = np.concatenate(self.out_y, axis=1) if self.out_y else np.zeros((6, 1))
        mode = np.concatenate(self.out_mode) if self.out_mode else np.zeros(1, np.int8)
        s = np.where(mode == 0, 1.0, mode)
        kin = physics.kinetic_energy(sp, s, y[UD], y[TH], y[THD])
        pot = physics.potential_energy(sp, s, y[U], y[TH])
        demand = self.friction_demand(t, y, mode)
        cum = cumulative_impact_loss(t, [i.t for i in self.impacts], self.losses)
        log = EnergyLog(kinetic=kin, potential=pot, ground_work=y[W], dashpot_loss=y[D], impact_loss=cum,
                        per_impact=tuple(self.losses))
        return Trajectory(
            engine="analytic-reference", system=sys, t=t, u=y[U], u_dot=y[UD], theta=y[TH], theta_dot=y[THD],
            mode=mode, impacts=tuple(self.impacts), uplift_times=tuple(self.uplifts),
            overturned=status == Status.OVERTURNED, overturn_time=overturn_time,
            impact_threshold=self.impact_threshold, runtime_s=runtime, status=status,
            message=message, energy=log,
            extras={"overturn_rule": self.cfg.overturn, "friction_demand": float(demand)})


# state vector of a non-linear isolator's run: the linear's and the slider's loss S
S_LOSS = 6


class _IsolatorIntegrator(_Integrator):
    """The hybrid model on a non-linear isolator (docs/isolators.md): the linear path's modes,
    events and impacts, with the isolator's element force q in the base's equation and its
    slider's phase (stuck 0, slipping ±1, or ±2: physics) changed at events located like the
    others: stick when u̇ crosses 0 with the demand within F_s, slip when the demand (a rigid
    slider's) or the elastic force (the bearing's) reaches F_s; a cone's ball returning to its
    vertex, a double pendulum's second surface starting to slide. The state carries the slip
    loss S (hysteretic, friction or rolling work) beside the dashpot's D."""

    def __init__(self, system, motion, settings, duration, progress, impact_threshold):
        super().__init__(system, motion, settings, duration, progress, impact_threshold)
        sp, ip = physics.isolator_params(system, settings.rest_velocity)
        self.sp, self.ip = tuple(sp.tolist()), tuple(ip.tolist())
        self.kind = ip[physics.I_KIND]
        self.friction = physics.rigid_slider(ip)  # the base itself sticks (a pendulum, a ball)
        self.u_y = self.ip[physics.I_UY]
        self.phase, self.u_p = 0, 0.0
        self.out_phase, self.out_up = [], []
        self.isolator_log = []  # (t, phase after, u) at every change of the slider's phase
        # u̇ ≡ 0 while the pendulum's base is pinned: its extremes are the pinned states
        # themselves, and an event function that is zero throughout fires at every step
        self.base_peak = _event(lambda t, y: 1.0 if self.friction and self.phase == 0 else y[UD], "base-peak", 0)
        self.base_peak.terminal = False

    # the slider's state --------------------------------------------------------------
    def initial_state(self, u0, u_dot0, theta0, theta_dot0):
        """A bilinear bearing displaced to u0 was pushed there from its virgin state, so
        its slider sits at u0 − clip(u0, ±u_y); a pendulum moving slips its way, at rest
        it sticks unless its demand exceeds F_s."""
        y = np.array([u0, u_dot0, theta0, theta_dot0, 0.0, 0.0, 0.0])
        # a double pendulum's element, like the bearing, was pushed to u0 from its virgin state
        self.u_p = u0 - min(max(u0, -self.u_y), self.u_y) if self.u_y > 0.0 else 0.0
        if self.friction:
            mode = 0 if theta0 == 0 else (1 if theta0 > 0 else -1)
            self.phase = (self.slip_phase(1 if u_dot0 > 0 else -1, u0) if u_dot0 != 0
                          else self.stick_or_slip(0.0, y, mode))
        return y

    def slip_phase(self, sigma, u):
        """physics.slip_phase with the element's slider where it is now."""
        u_p = physics.slider_position(self.ip, self.phase, u, self.u_p)
        return int(physics.slip_phase(self.ip, float(sigma), float(u), u_p))

    def stick_or_slip(self, t, y, mode):
        """A rigid slider's phase at rest (u̇ = 0): 0 if its demand is within F_s, else a slip its way."""
        u_p = physics.slider_position(self.ip, self.phase, y[U], self.u_p)
        demand = physics.rigid_demand(self.sp, self.ip, mode, y[TH], y[THD], y[U], u_p, self.xg(t))
        if abs(demand) <= physics.stick_limit(self.sp, self.ip):
            return 0
        return self.slip_phase(1 if demand > 0 else -1, y[U])

    def set_phase(self, t, y, phase):
        if phase == self.phase:
            return
        # a yielded element's slider (the bearing's, the double pendulum's) stops where it is
        self.u_p = float(physics.slider_position(self.ip, self.phase, float(y[U]), self.u_p))
        if phase == 0 and self.friction:
            y[UD] = 0.0  # the base rests on the ground exactly
        self.phase = phase
        self.isolator_log.append((float(t), phase, float(y[U])))

    def slider_after_velocity(self, t, y, mode):
        """The phase that a new base velocity u̇ (after an impact) leaves the slider in."""
        ud = y[UD]
        if self.friction:
            if ud == 0:
                return self.stick_or_slip(t, y, mode)
            sigma = 1 if ud > 0 else -1
            # on its way still: the same phase (a cone's side, a double pendulum's regime)
            return self.phase if self.phase * sigma > 0 else self.slip_phase(sigma, y[U])
        if self.phase != 0 and self.phase * ud <= 0:
            return 0  # the bearing unloads elastically
        return self.phase

    def after_impact(self, t, y, mode):
        self.set_phase(t, y, self.slider_after_velocity(t, y, mode))

    def isolator_event(self, t, y, mode, ev):
        if ev.side == 0:  # a slipping slider's u̇ crossed 0: located to rounding, made exact
            y[UD] = 0.0
            new = self.stick_or_slip(t, y, mode) if self.friction else 0
            if new * self.phase > 0:
                # u̇ fell through 0, so σ·demand ≤ F_s: slipping on the same way is rounding
                # (it would start and end at once, without end); the slider holds
                new = 0
        elif self.phase == 0 and self.friction:  # a pinned slider slips
            new = self.slip_phase(ev.side, y[U])
        elif self.kind == physics.ISO_CONE:  # the returning ball reaches the vertex: made exact
            y[U] = 0.0
            new = ev.side
            if abs(y[UD]) < physics.vertex_rest_speed(self.sp, self.ip):
                # the Zeno tail of returns (physics.vertex_rest_speed): the ball rests at the
                # vertex, its kinetic energy left to the rolling resistance
                s = 1.0 if mode >= 0 else -1.0
                y[S_LOSS] += self.kinetic(s, y[UD], y) - self.kinetic(s, 0.0, y)
                y[UD] = 0.0
                self.set_phase(t, y, 0)
                new = self.stick_or_slip(t, y, mode)
        else:  # the bearing yields; the double pendulum's second surface starts to slide
            new = ev.side
        self.set_phase(t, y, new)
        if mode == 0:  # the base's acceleration may have jumped (the pendulum sticking)
            side = self.relift(t, y)
            if side:
                return self.lift(t, side), y
        return mode, y

    # the physics ---------------------------------------------------------------------
    def relift(self, t, y):
        sp, xg = self.sp, self.xg(t)
        side = physics.uplift_direction(sp, physics.isolator_base_acceleration(
            sp, self.ip, self.phase, y[U], y[UD], self.u_p, xg))
        if side == 0:
            return 0
        thdd = physics.isolator_rocking_accelerations(sp, self.ip, self.phase, float(side), 0.0, 0.0, y[U], y[UD],
                                                      self.u_p, xg)[1]
        return side if physics.lifts_clearly(sp, side, thdd) else 0

    def uplift_mode(self, t, y):
        """The corner the block lifts about at t = 0 (0: none). A rigid slider at rest then took
        its phase from the demand of a block at rest (initial_state); one that lifts at once
        takes it from the rocking block's (a motion that starts with a jump: the demand in
        translation drove a cone's ball one way and the block's reaction the base the other,
        the slip never stopped and ran away, issue 39)."""
        side = physics.uplift_direction(self.sp, physics.isolator_base_acceleration(
            self.sp, self.ip, self.phase, y[U], y[UD], self.u_p, self.xg(t)))
        if side and self.friction and y[UD] == 0.0:
            self.phase = self.stick_or_slip(t, y, side)
        return side

    def function_order(self, s, t0, y0):
        if y0[THD] != 0.0:
            return 1, s * y0[THD]
        thdd = physics.isolator_rocking_accelerations(self.sp, self.ip, self.phase, s, 0.0, 0.0, y0[U], y0[UD],
                                                      self.u_p, self.xg(t0))[1]
        return physics.lift_order(self.sp, s, thdd)

    def rhs_translation(self, t, y):
        sp, ip, ph, up = self.sp, self.ip, self.phase, self.u_p
        xg = self.xg(t)
        udd = physics.isolator_translation_acceleration(sp, ip, ph, y[U], y[UD], up, xg)
        return (y[UD], udd, 0.0, 0.0, -xg * sp[physics.M_TOTAL] * y[UD], sp[physics.C_DAMP] * y[UD] ** 2,
                physics.slip_power(ip, ph, y[UD]))

    def rhs_rocking(self, s):
        sp, ip, ph, up = self.sp, self.ip, self.phase, self.u_p
        m, M, c = sp[physics.M_BLOCK], sp[physics.M_TOTAL], sp[physics.C_DAMP]

        def f(t, y):
            xg = self.xg(t)
            udd, thdd, L1 = physics.isolator_rocking_accelerations(sp, ip, ph, s, y[TH], y[THD], y[U], y[UD], up, xg)
            return (y[UD], udd, y[THD], thdd, -xg * (M * y[UD] + m * L1 * y[THD]), c * y[UD] ** 2,
                    physics.slip_power(ip, ph, y[UD]))
        return f

    # events ----------------------------------------------------------------------------
    def solve(self, fun, t0, t1, y0, events):
        self._fun = fun  # hidden_stop reads the piece's accelerations
        return super().solve(fun, t0, t1, y0, events)

    def first_terminal(self, sol, evs):
        """The first terminal event, a slip's stop that dipped within one step (hidden_stop), or
        one that either hid (physics.hidden_crossing): a terminal event whose function changed
        sign, its way, between the step's start and the cut, located there on the step's dense
        output as solve_ivp locates any (Brent, 4·eps), ends the piece instead; checked again
        from the earlier cut until none is left. On a linear isolator the only terminal events
        are the landing, α and π/2 (the run is unchanged)."""
        hit = self.hidden_stop(sol, evs, super().first_terminal(sol, evs))
        dense = None
        if hit is not None and sol.sol is not None:  # the step that holds the cut
            dense = next(d for d in sol.sol.interpolants if d.t_old <= hit[1] <= d.t)
        while dense is not None and hit[1] > dense.t_old:
            k, te, ye = hit
            t_old = dense.t_old
            hidden = None
            for j, ev in enumerate(evs):
                if j == k or not ev.terminal:
                    continue
                if physics.hidden_crossing(ev.direction, ev(t_old, dense.y_old), ev(te, ye)):
                    r = brentq(lambda t: ev(t, dense(t)), t_old, te, xtol=4 * EPS, rtol=4 * EPS)
                    if r < te and (hidden is None or r < hidden[1]):
                        hidden = (j, r)
            if hidden is None:
                break
            hit = (hidden[0], hidden[1], dense(hidden[1]))
        return hit

    def hidden_stop(self, sol, evs, hit):
        """A slip whose phase·u̇ dips through 0 and back within one step (both ends positive, so
        solve_ivp never sees its stop): on a cone in translation under a record u̇ is quadratic in
        a sample interval, DOP853 integrates it exactly and steps across the whole dip, the slip
        then pushed along by its own friction (issue 39). Where phase·ü rises through 0 within a
        step (its least, by Brent on the dense output) phase·u̇ is below 0, the stop is the first
        zero before it, and ends the piece if before the hit (the kernel: its dip)."""
        ph = self.phase
        stop = next((k for k, ev in enumerate(evs) if ev.kind == "isolator" and ev.side == 0 and ph != 0), None)
        if stop is None or sol.sol is None:
            return hit
        ev, fun = evs[stop], self._fun
        for i, dense in enumerate(sol.sol.interpolants):
            t_old, t_new = dense.t_old, dense.t
            if hit is not None and t_old >= hit[1]:
                break
            y_old = dense.y_old
            y_new = sol.y[:, i + 1] if i + 1 < sol.t.size and sol.t[i + 1] == t_new else dense(t_new)
            if not (ev(t_old, y_old) > 0.0 and ev(t_new, y_new) > 0.0
                    and ph * fun(t_old, y_old)[UD] < 0.0 < ph * fun(t_new, y_new)[UD]):
                continue

            def rate(t, dense=dense):
                return ph * fun(t, dense(t))[UD]
            if not rate(t_old) < 0.0 < rate(t_new):
                continue
            t_m = brentq(rate, t_old, t_new, xtol=4 * EPS, rtol=4 * EPS)
            if ph * dense(t_m)[UD] < 0.0:
                r = brentq(lambda t: ev(t, dense(t)), t_old, t_m, xtol=4 * EPS, rtol=4 * EPS)
                if hit is None or r < hit[1]:
                    hit = (stop, r, dense(r))
                break
        return hit

    def slider_events(self, mode, t0, y0, fun):
        """The slider's phase changes: a slipping one stops (u̇ crosses 0, side 0); a stuck
        one slips (side ±1) when the pendulum's demand, or the bearing's elastic force,
        reaches F_s that way. A slip that starts from u̇ = 0 (the pendulum's, from rest or
        reversing) is watched as σ·u̇/(t − t0), which starts at σ·ü(t0) > 0 (STICK_BAND),
        so that the start itself is never taken for its end."""
        ph = self.phase
        if ph != 0:
            if y0[UD] != 0.0:
                evs = [_event(lambda t, y: ph * y[UD], "isolator", -1, side=0)]
            else:
                start = ph * fun(t0, y0)[1]
                evs = [_event(lambda t, y: ph * y[UD] / (t - t0) if t > t0 else start, "isolator", -1, side=0)]
            sigma = 1 if ph > 0 else -1
            if self.kind == physics.ISO_CONE and abs(ph) == 2:  # the returning ball reaches the vertex
                evs.append(_event(lambda t, y: physics.vertex_function(sigma, y[U], t <= t0), "isolator", +1,
                                  side=sigma))
            elif self.kind == physics.ISO_DOUBLE and abs(ph) == 1 and self.u_y > 0.0:  # both surfaces slide
                up, uy = self.u_p, self.u_y
                evs.append(_event(lambda t, y: sigma * (y[U] - up) - uy, "isolator", +1, side=2 * sigma))
            return evs
        if self.friction:
            sp, ip, f_s, up = self.sp, self.ip, physics.stick_limit(self.sp, self.ip), self.u_p

            def demand(t, y):
                return physics.rigid_demand(sp, ip, mode, y[TH], y[THD], y[U], up, self.xg(t))
            return [_event(lambda t, y: demand(t, y) - f_s, "isolator", +1, side=1),
                    _event(lambda t, y: -demand(t, y) - f_s, "isolator", +1, side=-1)]
        up, uy = self.u_p, self.u_y
        return [_event(lambda t, y: y[U] - up - uy, "isolator", +1, side=1),
                _event(lambda t, y: up - y[U] - uy, "isolator", +1, side=-1)]

    def uplift_events(self):
        sp, ip, ph, up = self.sp, self.ip, self.phase, self.u_p
        thr_pos, thr_neg = self.uplift_thresholds()

        def a(t, y):
            return physics.isolator_base_acceleration(sp, ip, ph, y[U], y[UD], up, self.xg(t))
        return [_event(lambda t, y: -a(t, y) - thr_pos, "uplift", +1, side=1),
                _event(lambda t, y: a(t, y) - thr_neg, "uplift", +1, side=-1)]

    def translation_events(self, t0, y0):
        return self.uplift_events() + self.slider_events(0, t0, y0, self.rhs_translation)

    def rocking_events(self, s, t0, y0):
        return super().rocking_events(s, t0, y0) + self.slider_events(s, t0, y0, self.rhs_rocking(s))

    # result ------------------------------------------------------------------------------
    def store(self, sol, t0, t1, mode):
        super().store(sol, t0, t1, mode)
        ts, ys = self.out_t[-1], self.out_y[-1]
        self.out_phase.append(np.full(ts.size, self.phase, dtype=np.int8))
        if self.phase != 0 and (self.kind == physics.ISO_BILINEAR
                                or (self.kind == physics.ISO_DOUBLE and abs(self.phase) == 2)):
            self.out_up.append(ys[U] - np.sign(self.phase) * self.u_y)  # the slider moves with the base
        else:
            self.out_up.append(np.full(ts.size, self.u_p))

    def trajectory(self, status, message, overturn_time, runtime):
        tr = super().trajectory(status, message, overturn_time, runtime)
        ip = self.ip
        y = np.concatenate(self.out_y, axis=1) if self.out_y else np.zeros((7, 1))
        phase = np.concatenate(self.out_phase) if self.out_phase else np.zeros(1, np.int8)
        u_p = np.concatenate(self.out_up) if self.out_up else np.zeros(1)
        e = tr.energy
        log = EnergyLog(kinetic=e.kinetic, potential=e.potential + physics.element_energy(ip, y[U], u_p),
                        ground_work=e.ground_work, dashpot_loss=e.dashpot_loss, impact_loss=e.impact_loss,
                        per_impact=e.per_impact, isolator_loss=y[S_LOSS])
        extras = dict(tr.extras)
        extras["isolator"] = self.sys.isolator_kind
        extras["isolator_phase"] = phase
        extras["isolator_slider"] = u_p
        extras["isolator_events"] = tuple(self.isolator_log)
        failure = log.failure(tr.t) if tr.status.ended_normally else None
        if failure:  # a history that took a branch the physics did not is no answer (limits.py)
            return replace(tr, energy=log, extras=extras, status=Status.FAILED, message=failure, overturned=False,
                           overturn_time=None)
        return replace(tr, energy=log, extras=extras)

    def friction_demand(self, t, y, mode):
        phase = np.concatenate(self.out_phase) if self.out_phase else np.zeros(1, np.int8)
        u_p = np.concatenate(self.out_up) if self.out_up else np.zeros(1)
        return max((self.pivot_ratio(int(mode[i]), int(phase[i]), y[:, i], u_p[i], float(t[i]))
                    for i in range(t.size)), default=0.0)

    def pivot_ratio(self, mode, phase, y, u_p, t):
        """physics.pivot_force_ratio on the isolator: the friction the block needs on the base."""
        sp, xg = self.sp, self.xg(t)
        if mode == 0:
            return abs(physics.isolator_base_acceleration(sp, self.ip, phase, y[U], y[UD], u_p, xg)) / sp[physics.G]
        udd, thdd, _ = physics.isolator_rocking_accelerations(sp, self.ip, phase, float(mode), y[TH], y[THD], y[U],
                                                              y[UD], u_p, xg)
        return physics.rocking_pivot_force_ratio(sp, float(mode), y[TH], y[THD], udd, thdd, xg)


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
