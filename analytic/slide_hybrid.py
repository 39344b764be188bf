"""The reference path of a statue that may slip on its base, or of a ground motion with a
vertical component (docs/sliding.md): the hybrid model's driver (analytic.integrators) with the
four contact modes of analytic.slide_physics, on the fixed base and on every isolator.

A run's mode is the rocking corner (0 flat, ±1) as in the no-slip model, and the contact's
slip σ (0 sticking, ±1 slipping that way); both change at events located like the others:

- resting flat: the base's force reaches the tipping limit F_z·tanα ("tip") or μ_s·F_z
  ("slip"), and the consistent mode is chosen (slide_physics.flat_mode);
- rocking with its corner stuck: |F_x| reaches μ_s·F_z ("slip");
- slipping, flat or rocking: ẋ falls through 0 ("stop"), and the contact sticks or slips back;
- any mode: the normal force or g + üv falls to 0 ("fly"), or the slide-rock equations lose
  their solution ("painleve"): the model stops there with status `failed`, saying so
  (it carries no free flight);
- impacts at θ = 0 with a friction-limited impulse (slide_physics.impact).

The state carries the block's slide x, ẋ and the contact's friction loss beside the no-slip
model's, so that the energy balance closes with the friction's work: it is the test oracle.
"""
from __future__ import annotations

import math

import numpy as np

from . import physics
from . import slide_physics as sl
from .integrators import D, S_LOSS, TH, THD, U, UD, W, StopRun, _event, _IsolatorIntegrator
from .status import Status
from .trajectory import EnergyLog, Impact, Trajectory, cumulative_impact_loss

# the state beyond the isolator integrator's (u, u̇, θ, θ̇, W, D, S): the slide and its loss
X, XD, FL = 7, 8, 9
N_STATE = 10


def stop(why: int, t: float, what: str = "") -> StopRun:
    return StopRun(Status.OUTSIDE_MODEL, f"the model stops at t = {t:.6g} s{what}: {sl.STOP_WHY[why]}", t)


class SlidingIntegrator(_IsolatorIntegrator):
    """The hybrid model with a contact that may slip and a vertical ground motion."""

    def __init__(self, system, motion, settings, duration, progress, impact_threshold):
        super().__init__(system, motion, settings, duration, progress, impact_threshold)
        vertical = motion.vertical is not None and not motion.vertical.is_zero
        self.cp = tuple(sl.contact_params(system, vertical).tolist())
        mpv, self.accv = physics.motion_params(motion.vertical) if vertical else (np.zeros(physics.N_MP), np.zeros(1))
        self.mpv = tuple(mpv.tolist())
        self.vertical = vertical
        self.motion_end = motion.last_time
        self.linear = self.kind == physics.ISO_LINEAR  # no element: no slider events
        self.slips = math.isfinite(self.cp[sl.C_MUS])
        self.sigma = 0
        self.chosen = False  # whether the run's first mode has its slip yet (uplift_mode, begin)
        self.slip_start = (0.0, 1, 0.0)  # (t0, k, limit) of a slip that started from ẋ = 0
        self.out_sigma = []
        self.slip_log = []  # (t, σ after) at every change of the contact's slip
        self.graze_mode = 0

    # the ground ---------------------------------------------------------------------------
    def av(self, t):
        return physics.ground_acceleration(t, self.mpv, self.accv) if self.vertical else 0.0

    def ge(self, t):
        return sl.effective_gravity(self.sp, self.cp, self.av(t))

    def forces(self, t, y, mode, sigma=None):
        """slide_physics.accelerations at (t, y) in `mode` with slip σ (default: the run's)."""
        sigma = self.sigma if sigma is None else sigma
        return sl.accelerations(self.sp, self.ip, self.cp, float(mode), float(sigma), self.phase, self.u_p,
                                y[TH], y[THD], y[U], y[UD], self.xg(t), self.ge(t))

    # the state and the modes ---------------------------------------------------------------
    def initial_state(self, u0, u_dot0, theta0, theta_dot0):
        y = super().initial_state(u0, u_dot0, theta0, theta_dot0)
        return np.concatenate([y, np.zeros(N_STATE - y.size)])

    def rests_still(self):
        return False  # a block that may slip, or a heaving ground, is integrated at rest too

    def uplift_mode(self, t, y):
        s, sigma, why = sl.flat_mode(self.sp, self.ip, self.cp, self.phase, self.u_p, y[U], y[UD], 0.0,
                                     self.xg(t), self.ge(t), False, False, False)
        if s == sl.NO_MODE:
            raise stop(why, t, " (at the start)")
        self.set_sigma(t, y, sigma, mode=int(s))
        self.chosen = True
        if s != 0 and self.friction and y[UD] == 0.0:
            # a rigid slider at rest takes its phase from the lifting block's demand, not from a
            # block at rest's (initial_state): _IsolatorIntegrator.uplift_mode's rule (issue 39)
            self.phase = self.stick_or_slip(t, y, int(s))
        return int(s)

    def begin(self, t, y, mode):
        if not self.chosen:  # an initial tilt or spin: its corner sticks if it can
            sigma, why = sl.rock_mode(self.sp, self.ip, self.cp, float(mode), self.phase, self.u_p, y[TH], y[THD],
                                      y[U], y[UD], self.xg(t), self.ge(t), True)
            if sigma == sl.NO_MODE:
                raise stop(why, t, " (at the start)")
            self.set_sigma(t, y, sigma, mode=mode)
        return mode

    def kinetic(self, s, u_dot, y):
        return sl.kinetic_energy(self.sp, s, u_dot, y[XD], y[TH], y[THD])

    def set_sigma(self, t, y, sigma, mode):
        """The contact slips the way σ (0: sticks) from t on."""
        sigma = int(sigma)
        if sigma != 0 and y[XD] == 0.0:
            xdd = self.forces(t, y, mode, sigma)[1]
            k, limit = sl.slip_start_order(float(sigma), xdd)
            self.slip_start = (t, k, limit)
        if sigma == 0:
            y[XD] = 0.0  # the contact sticks exactly
        if sigma != self.sigma:
            self.slip_log.append((float(t), sigma))
        self.sigma = sigma

    # right-hand sides -----------------------------------------------------------------------
    def rhs(self, s):
        sp, ip, cp, ph, up, sigma = self.sp, self.ip, self.cp, self.phase, self.u_p, float(self.sigma)
        s = float(s)
        se = s if s != 0.0 else 1.0  # the lever arms' corner: θ = θ̇ = 0 while flat

        def f(t, y):
            xg, av = self.xg(t), self.av(t)
            udd, xdd, thdd, fx, fz = sl.accelerations(sp, ip, cp, s, sigma, ph, up, y[TH], y[THD], y[U], y[UD], xg,
                                                      sl.effective_gravity(sp, cp, av))
            return (y[UD], udd, y[THD], thdd, sl.ground_power(sp, se, xg, av, y[UD], y[XD], y[TH], y[THD]),
                    sp[physics.C_DAMP] * y[UD] ** 2, physics.slip_power(ip, ph, y[UD]), y[XD], xdd,
                    sl.friction_power(cp, sigma, fz, y[XD]))
        return f

    def rhs_translation(self, t, y):
        return self.rhs(0)(t, y)

    def rhs_rocking(self, s):
        return self.rhs(s)

    # events ------------------------------------------------------------------------------------
    def contact_events(self, mode, t0):
        """The contact's own events in `mode` with the run's slip (see the module's doc)."""
        evs = []
        sigma, tan = self.sigma, self.cp[sl.C_TAN]
        mus = self.cp[sl.C_MUS] + sl.SLIP_BAND
        if mode == 0 and sigma == 0:
            thr = tan * (1.0 + (physics.GRAZE_MARGIN if self.graze else 0.0))

            def a_over_ge(t, y):  # the base's acceleration over g_e: F_x/F_z at rest
                r = self.forces(t, y, 0)
                return r[3] / r[4]
            evs += [_event(lambda t, y: -a_over_ge(t, y) - thr, "tip", +1, side=1),
                    _event(lambda t, y: a_over_ge(t, y) - thr, "tip", +1, side=-1)]
            if self.slips:
                evs += [_event(lambda t, y: -a_over_ge(t, y) - mus, "slip", +1, side=1),
                        _event(lambda t, y: a_over_ge(t, y) - mus, "slip", +1, side=-1)]
        elif sigma == 0:  # rocking, its corner stuck
            if self.slips:
                def ratio(t, y):
                    r = self.forces(t, y, mode)
                    return r[3] / r[4] if r[4] > 0.0 else math.copysign(math.inf, r[3])
                evs += [_event(lambda t, y: -ratio(t, y) - mus, "slip", +1, side=1),
                        _event(lambda t, y: ratio(t, y) - mus, "slip", +1, side=-1)]
        else:  # slipping: it stops when ẋ falls through 0
            t_start, k, limit = self.slip_start
            if t_start == t0 and k:
                evs.append(_event(lambda t, y: sigma * y[XD] / (t - t0) ** k if t > t0 else limit, "stop", -1))
            else:
                evs.append(_event(lambda t, y: sigma * y[XD], "stop", -1))
            if mode != 0:
                evs.append(_event(lambda t, y: sl.slide_rock_denominator(self.sp, self.cp, float(mode), float(sigma),
                                                                         y[TH]), "painleve", -1))
        if mode != 0:
            evs.append(_event(lambda t, y: self.forces(t, y, mode)[4], "fly", -1))
        elif self.vertical:
            evs.append(_event(lambda t, y: self.ge(t), "fly", -1))
        return evs

    def slider_events(self, mode, t0, y0, fun):
        if self.linear:
            return []
        if self.phase == 0 and self.friction:  # a pinned base: its demand with the block's mode
            f_s = physics.stick_limit(self.sp, self.ip)
            return [_event(lambda t, y: self.demand(t, y, mode) - f_s, "isolator", +1, side=1),
                    _event(lambda t, y: -self.demand(t, y, mode) - f_s, "isolator", +1, side=-1)]
        return super().slider_events(mode, t0, y0, fun)

    def demand(self, t, y, mode):
        u_p = physics.slider_position(self.ip, self.phase, y[U], self.u_p)
        return sl.held_demand(self.sp, self.ip, self.cp, float(mode), float(self.sigma), y[TH], y[THD], y[U], u_p,
                              self.xg(t), self.ge(t))

    def translation_events(self, t0, y0):
        return self.contact_events(0, t0) + self.slider_events(0, t0, y0, self.rhs(0))

    def rocking_events(self, s, t0, y0):
        return super().rocking_events(s, t0, y0) + self.contact_events(s, t0)

    def function_order(self, s, t0, y0):
        if y0[THD] != 0.0:
            return 1, s * y0[THD]
        return physics.lift_order(self.sp, s, self.forces(t0, y0, s)[2])

    # the isolator's slider, with the block's mode ---------------------------------------------------
    def stick_or_slip(self, t, y, mode):
        if abs(self.demand(t, y, mode)) <= physics.stick_limit(self.sp, self.ip):
            return 0
        return self.slip_phase(1 if self.demand(t, y, mode) > 0 else -1, y[U])

    def isolator_event(self, t, y, mode, ev):
        mode, y = super().isolator_event(t, y, mode, ev)
        if self.sigma == 0 and mode != 0:  # the base's force jumped (a slider stuck): the corner may slip
            sigma, why = sl.rock_mode(self.sp, self.ip, self.cp, float(mode), self.phase, self.u_p, y[TH], y[THD],
                                      y[U], y[UD], self.xg(t), self.ge(t), True)
            if sigma == sl.NO_MODE:
                raise stop(why, t)
            self.set_sigma(t, y, sigma, mode)
        return mode, y

    def relift(self, t, y):
        """The block's mode at rest after its base's force jumped (an isolator's slider stuck, or
        the block landed): flat_mode, the slip set here; returns the corner it lifts about, or 0."""
        s, sigma, why = sl.flat_mode(self.sp, self.ip, self.cp, self.phase, self.u_p, y[U], y[UD], y[XD],
                                     self.xg(t), self.ge(t), self.graze, False, False)
        if s == sl.NO_MODE:
            raise stop(why, t)
        self.set_sigma(t, y, sigma, int(s))
        return int(s)

    # transitions ---------------------------------------------------------------------------------
    def transition(self, t, y, mode, ev):
        kind, sp, ip, cp = ev.kind, self.sp, self.ip, self.cp
        xg, ge = self.xg(t), self.ge(t)
        if kind in ("fly", "painleve"):
            raise stop(sl.FLIGHT if kind == "fly" else sl.PAINLEVE, t)
        if kind == "stop":
            old = self.sigma
            y[XD] = 0.0
            if mode == 0:
                s, sigma, why = sl.flat_mode(sp, ip, cp, self.phase, self.u_p, y[U], y[UD], 0.0, xg, ge, self.graze,
                                             False, False)
            else:
                s, (sigma, why) = mode, sl.rock_mode(sp, ip, cp, float(mode), self.phase, self.u_p, y[TH], y[THD],
                                                     y[U], y[UD], xg, ge, True)
            if s == sl.NO_MODE or sigma == sl.NO_MODE:
                raise stop(why, t)
            if sigma == old and s == mode:
                sigma = 0  # ẋ fell through 0, so slipping on the same way is rounding: it sticks
            self.set_sigma(t, y, sigma, int(s))
            return (self.lift(t, int(s)) if s != mode else mode), y
        if mode == 0:  # "tip" or "slip" from rest
            s, sigma, why = sl.flat_mode(sp, ip, cp, self.phase, self.u_p, y[U], y[UD], 0.0, xg, ge, self.graze,
                                         kind == "tip", kind == "slip")
            if s == sl.NO_MODE:
                raise stop(why, t)
            self.set_sigma(t, y, sigma, int(s))
            if s != 0:
                return self.lift(t, int(s)), y
            if sigma == 0:  # a grazing tip stays down: it re-lifts only clearly above the limit
                self.graze = True
            return 0, y
        # "slip" of a rocking block's corner
        sigma = ev.side
        if sl.slide_rock_denominator(sp, cp, float(mode), float(sigma), y[TH]) <= 0.0:
            raise stop(sl.PAINLEVE, t)
        self.set_sigma(t, y, sigma, mode)
        return mode, y

    def impact(self, t, y, mode):
        sp = self.sp
        s = float(mode)
        y[TH] = 0.0
        thd_pre, xd_pre, ud_pre = float(y[THD]), float(y[XD]), float(y[UD])
        continued = physics.impact_continues(sp, thd_pre)
        thd, xd, ud, px, pz, ok = sl.impact(sp, self.cp, s, thd_pre, xd_pre, ud_pre, continued)
        if not ok:
            raise StopRun(Status.OUTSIDE_MODEL, f"the model stops at t = {t:.6g} s: the landing would need a negative "
                                         f"normal impulse (P_z = {pz:.3g} N·s; docs/sliding.md, \"Impact\")", t)
        loss = (sl.kinetic_energy(sp, s, ud_pre, xd_pre, 0.0, thd_pre)
                - sl.kinetic_energy(sp, -s, ud, xd, 0.0, thd))
        continued = thd != 0.0
        self.impact_loss += loss
        self.losses.append(loss)
        self.impacts.append(Impact(t=t, theta_dot_pre=thd_pre, theta_dot_post=thd, u_dot_pre=ud_pre, u_dot_post=ud,
                                   continued=continued, amplitude=self.peak,
                                   counted=self.peak > self.impact_threshold * self.sys.alpha))
        self.peak = 0.0
        y[THD], y[XD], y[UD] = thd, xd, ud
        new = -mode if continued else 0
        self.after_impact(t, y, new)  # the isolator's slider, after the base's jump
        if continued:
            if xd != 0.0:
                self.set_sigma(t, y, 1 if xd > 0.0 else -1, new)
            else:
                sigma, why = sl.rock_mode(sp, self.ip, self.cp, float(new), self.phase, self.u_p, 0.0, thd, y[U],
                                          y[UD], self.xg(t), self.ge(t), True)
                if sigma == sl.NO_MODE:
                    raise stop(why, t)
                self.set_sigma(t, y, sigma, new)
            return new, y
        side = self.relift(t, y)
        if side:
            return self.lift(t, side), y
        if self.sigma == 0:
            self.graze = True
        return 0, y

    def after_impact(self, t, y, mode):
        if not self.linear:
            super().after_impact(t, y, mode)

    # the result ------------------------------------------------------------------------------------
    def store(self, sol, t0, t1, mode):
        super().store(sol, t0, t1, mode)
        self.out_sigma.append(np.full(self.out_t[-1].size, self.sigma, dtype=np.int8))

    def trajectory(self, status, message, overturn_time, runtime):
        sys, sp, ip = self.sys, self.sp, self.ip
        t = np.concatenate(self.out_t) if self.out_t else np.zeros(1)
        y = np.concatenate(self.out_y, axis=1) if self.out_y else np.zeros((N_STATE, 1))
        mode = np.concatenate(self.out_mode) if self.out_mode else np.zeros(1, np.int8)
        sigma = np.concatenate(self.out_sigma) if self.out_sigma else np.zeros(1, np.int8)
        u_p = np.concatenate(self.out_up) if self.out_up else np.zeros(t.size)
        s = np.where(mode == 0, 1.0, mode)
        kin = sl.kinetic_energy(sp, s, y[UD], y[XD], y[TH], y[THD])
        pot = physics.potential_energy(sp, s, y[U], y[TH]) + physics.element_energy(ip, y[U], u_p)
        cum = cumulative_impact_loss(t, [i.t for i in self.impacts], self.losses)
        log = EnergyLog(kinetic=kin, potential=pot, ground_work=y[W], dashpot_loss=y[D], impact_loss=cum,
                        per_impact=tuple(self.losses), isolator_loss=None if self.linear else y[S_LOSS],
                        slip_loss=y[FL] if self.slips else None)
        onset = next((te for te, sg in self.slip_log if sg != 0), None)
        extras = {"overturn_rule": self.cfg.overturn, "slip_mode": sigma, "slip_events": tuple(self.slip_log),
                  "slip_onset": onset}
        if not self.linear:
            extras.update(isolator=sys.isolator_kind, isolator_phase=np.concatenate(self.out_phase),
                          isolator_slider=u_p, isolator_events=tuple(self.isolator_log))
        failure = log.failure(t) if status.ended_normally else None
        if failure:  # a history that took a branch the physics did not is no answer (limits.py)
            status, message, overturn_time = Status.FAILED, failure, None
        return Trajectory(
            engine="analytic-reference", system=sys, t=t, u=y[U], u_dot=y[UD], theta=y[TH], theta_dot=y[THD],
            mode=mode, impacts=tuple(self.impacts), uplift_times=tuple(self.uplifts),
            overturned=status == Status.OVERTURNED, overturn_time=overturn_time,
            impact_threshold=self.impact_threshold, runtime_s=runtime, status=status, message=message,
            energy=log, extras=extras, slide=y[X], slide_dot=y[XD])


def simulate(system, motion, settings, duration, progress, impact_threshold, theta0, theta_dot0, u0, u_dot0):
    """hybrid.simulate's run of a statue that may slip, or under a vertical motion (inputs checked there)."""
    return SlidingIntegrator(system, motion, settings, duration, progress, impact_threshold).run(
        theta0, theta_dot0, u0, u_dot0)
