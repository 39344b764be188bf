"""The compiled kernel of a statue that may slip on its base, or of a ground motion with a
vertical component (docs/sliding.md): a port of analytic.slide_hybrid (engine
"analytic-reference") that engine "analytic" runs, as analytic.fast ports analytic.hybrid.

The physics is analytic/slide_physics.py and analytic/physics.py, compiled here from the same
source the reference calls. The integrator is SciPy's `solve_ivp(method="DOP853",
dense_output=True, events=...)` ported step by step (its initial step, step-size control,
dense output, `find_active_events` and Brent's method on the dense output, xtol = rtol =
4·eps), restarted where the reference restarts it (every event and every kink of a ground
motion), with the reference's events in the reference's order: so the two paths take the
same branch at every event the integrator's tolerance resolves, and agree to ~1e-12 where
no event is ill-conditioned (tests/test_sliding_kernel.py holds them to 1e-9 on 300 random
cases that slide).

Unlike analytic.fast, this kernel is written on arrays of any length (the state has 10
components: u, u̇, θ, θ̇, the ground's work W, the dashpot's loss D, an isolator's slip loss
S, the slide x, ẋ and the friction's loss), compiled once with numba's JIT and cached on
disk (analytic.kernel_cache), and it stores only what a result needs: the piece ends, the
output grid and the events located inside pieces (the extremes of θ and u), not SciPy's
every step.
"""
from __future__ import annotations

import math
import time
import types

import numpy as np
from numba import njit

from . import physics
from . import slide_physics as sl
from .kernel_cache import cached_jit, call_kernel
from .dop853 import _A, _B, _C, _D, _E3, _E5
from .limits import energy_balance_failure
from .overturning import describe, theta_max_over_alpha
from .status import Status
from .trajectory import EnergyLog, Impact, Trajectory, cumulative_impact_loss

# --- analytic.physics and analytic.slide_physics, compiled ----------------------------------

_PHYSICS = ("edge", "landing_side", "ground_acceleration", "piece_acceleration", "pulse_acceleration", "base_pinned",
            "isolator_element_force", "slip_force", "element_hold", "lifts_clearly", "lift_order",
            "impact_continues", "stick_limit", "slip_phase", "slider_position", "slip_power", "vertex_rest_speed",
            "potential_energy", "element_energy", "overturn_code", "hidden_crossing", "vertex_function")
_SLIDE = ("levers", "base_held", "isolator_force", "slide_rock_denominator", "accelerations", "held_block_force",
          "held_demand", "kinetic_energy", "ground_power", "friction_power", "sticks", "slip_way", "rock_mode",
          "flat_mode", "slip_start_order", "impact", "effective_gravity")


def _compile():
    """The physics functions compiled over one table of globals (numba calls compiled functions
    only): each rebuilt over it and wrapped with njit, as analytic.fast._compile_physics does."""
    table = dict(vars(physics))
    table.update(vars(sl))
    out = {}
    for module, names in ((physics, _PHYSICS), (sl, _SLIDE)):
        for name in names:
            f = getattr(module, name)
            rebuilt = types.FunctionType(f.__code__, table, f.__name__, f.__defaults__, f.__closure__)
            out[name] = table[name] = njit(rebuilt)
    return out


_P = _compile()
_xg = _P["ground_acceleration"]
_acc = _P["accelerations"]
_held_demand = _P["held_demand"]
_kinetic = _P["kinetic_energy"]
_ground_power = _P["ground_power"]
_friction_power = _P["friction_power"]
_slip_power = _P["slip_power"]
_flat_mode = _P["flat_mode"]
_rock_mode = _P["rock_mode"]
_slip_start_order = _P["slip_start_order"]
_impact_map = _P["impact"]
_ge = _P["effective_gravity"]
_denominator = _P["slide_rock_denominator"]
_lift_order = _P["lift_order"]
_impact_continues = _P["impact_continues"]
_stick_limit = _P["stick_limit"]
_slip_phase = _P["slip_phase"]
_slider_position = _P["slider_position"]
_vertex_rest_speed = _P["vertex_rest_speed"]
_base_pinned = _P["base_pinned"]
_overturn_code = _P["overturn_code"]
_hidden_crossing = _P["hidden_crossing"]
_vertex_function = _P["vertex_function"]
_potential = _P["potential_energy"]
_element_energy = _P["element_energy"]

_NY = 10
U, UD, TH, THD, W, D, S_LOSS, X, XD, FL = range(_NY)
_EPS = float(np.finfo(float).eps)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0  # scipy.integrate._ivp.rk
_N_STAGES = 12

# event kinds, in the reference's vocabulary (slide_hybrid.SlidingIntegrator's events)
(E_IMPACT, E_ALPHA, E_PEAK, E_SIDE, E_BASE_PEAK, E_TIP, E_SLIP_FLAT, E_SLIP_ROCK, E_STOP, E_PAINLEVE, E_FLY_FZ,
 E_FLY_GE, E_ISO_DEMAND, E_ISO_STOP, E_ISO_VERTEX, E_ISO_DYIELD, E_ISO_BYIELD, E_DIP) = range(18)
# E_DIP is no event of the piece: a slipping isolator slider's phase·ü, whose rise through 0 inside a
# step marks where its stop's function may have dipped through 0 and back (the reference's hidden_stop)
_MAX_EV = 16

# the piece's context: what the reference's closures capture when a piece starts
(PC_S, PC_SIGMA, PC_PHASE, PC_UP, PC_T0, PC_KPOW, PC_LIMIT, PC_SK, PC_SLIMIT, PC_SDIV, PC_IDIV, PC_ISTART,
 PC_GRAZE, PC_FS, PC_THR, N_PC) = range(16)

# the run's state between pieces (the reference's attributes)
(R_PHASE, R_UP, R_SIGMA, R_PEAK, R_GRAZE, R_ST0, R_SK, R_SLIM, R_TALPHA, R_E0, R_IMPLOSS, R_HELD, R_NREC,
 N_RS) = range(14)
#: rows of a run's record of its energy residual's growth (the reference reads its whole history)
_N_REC = 128

# statuses and why a run stopped (slide_hybrid's StopRun messages)
_COMPLETED, _OVERTURNED, _EVENT_LIMIT, _FAILED, _NO_ROOM = 0, 1, 2, 3, 4
STOP_NONE, STOP_FLIGHT, STOP_PAINLEVE, STOP_IMPULSE, STOP_INTEGRATION = 0, 1, 2, 3, 4


# --- the right-hand side and the events --------------------------------------------------------

@njit
def _rhs(t, y, out, sp, ip, cp, mp, acc, mpv, accv, pc):
    """slide_hybrid.SlidingIntegrator.rhs: the 10 rates in the piece's mode."""
    s, sigma, ph, up = pc[PC_S], pc[PC_SIGMA], pc[PC_PHASE], pc[PC_UP]
    xg = _xg(t, mp, acc)
    av = _xg(t, mpv, accv) if cp[sl.C_VERT] != 0.0 else 0.0
    udd, xdd, thdd, fx, fz = _acc(sp, ip, cp, s, sigma, ph, up, y[TH], y[THD], y[U], y[UD], xg, _ge(sp, cp, av))
    se = s if s != 0.0 else 1.0
    out[U] = y[UD]
    out[UD] = udd
    out[TH] = y[THD]
    out[THD] = thdd
    out[W] = _ground_power(sp, se, xg, av, y[UD], y[XD], y[TH], y[THD])
    out[D] = sp[physics.C_DAMP] * y[UD] ** 2
    out[S_LOSS] = _slip_power(ip, ph, y[UD])
    out[X] = y[XD]
    out[XD] = xdd
    out[FL] = _friction_power(cp, sigma, fz, y[XD])


@njit
def _forces(t, y, sp, ip, cp, mp, acc, mpv, accv, pc, s, sigma):
    xg = _xg(t, mp, acc)
    av = _xg(t, mpv, accv) if cp[sl.C_VERT] != 0.0 else 0.0
    return _acc(sp, ip, cp, s, sigma, pc[PC_PHASE], pc[PC_UP], y[TH], y[THD], y[U], y[UD], xg, _ge(sp, cp, av))


@njit
def _event_value(kind, side, t, y, sp, ip, cp, mp, acc, mpv, accv, pc):
    """The event functions of slide_hybrid.SlidingIntegrator (and of the hybrid drivers it
    extends), by kind; `side` is the event's side (±1), or its constant."""
    s = pc[PC_S]
    if kind == E_IMPACT:
        if pc[PC_KPOW] == 0.0:
            return s * y[TH]
        dt = t - pc[PC_T0]
        return s * y[TH] / dt ** pc[PC_KPOW] if dt > 0 else pc[PC_LIMIT]
    if kind == E_ALPHA:
        return s * y[TH] - sp[physics.ALPHA]
    if kind == E_PEAK:
        return y[THD]
    if kind == E_SIDE:
        return s * y[TH] - physics.SIDE_ANGLE
    if kind == E_BASE_PEAK:
        return 1.0 if ip[physics.I_KIND] >= physics.ISO_FRICTION and pc[PC_PHASE] == 0.0 else y[UD]
    if kind == E_TIP or kind == E_SLIP_FLAT:
        r = _forces(t, y, sp, ip, cp, mp, acc, mpv, accv, pc, 0.0, 0.0)
        limit = pc[PC_THR] if kind == E_TIP else cp[sl.C_MUS] + sl.SLIP_BAND
        return -side * r[3] / r[4] - limit
    if kind == E_SLIP_ROCK:
        r = _forces(t, y, sp, ip, cp, mp, acc, mpv, accv, pc, s, 0.0)
        ratio = r[3] / r[4] if r[4] > 0.0 else math.copysign(math.inf, r[3])
        return -side * ratio - (cp[sl.C_MUS] + sl.SLIP_BAND)
    if kind == E_STOP:
        v = pc[PC_SIGMA] * y[XD]
        if pc[PC_SDIV] != 0.0:
            dt = t - pc[PC_T0]
            return v / dt ** pc[PC_SK] if dt > 0 else pc[PC_SLIMIT]
        return v
    if kind == E_PAINLEVE:
        return _denominator(sp, cp, s, pc[PC_SIGMA], y[TH])
    if kind == E_FLY_FZ:
        return _forces(t, y, sp, ip, cp, mp, acc, mpv, accv, pc, s, pc[PC_SIGMA])[4]
    if kind == E_FLY_GE:
        return _ge(sp, cp, _xg(t, mpv, accv) if cp[sl.C_VERT] != 0.0 else 0.0)
    if kind == E_ISO_DEMAND:
        u_p = _slider_position(ip, pc[PC_PHASE], y[U], pc[PC_UP])
        xg = _xg(t, mp, acc)
        av = _xg(t, mpv, accv) if cp[sl.C_VERT] != 0.0 else 0.0
        d = _held_demand(sp, ip, cp, s, pc[PC_SIGMA], y[TH], y[THD], y[U], u_p, xg, _ge(sp, cp, av))
        return side * d - pc[PC_FS]
    if kind == E_ISO_STOP:
        v = pc[PC_PHASE] * y[UD]
        if pc[PC_IDIV] != 0.0:
            return v / (t - pc[PC_T0]) if t > pc[PC_T0] else pc[PC_ISTART]
        return v
    if kind == E_ISO_VERTEX:
        return _vertex_function(side, y[U], t <= pc[PC_T0])
    if kind == E_DIP:
        return pc[PC_PHASE] * _forces(t, y, sp, ip, cp, mp, acc, mpv, accv, pc, s, pc[PC_SIGMA])[0]
    if kind == E_ISO_DYIELD:
        sg = 1.0 if pc[PC_PHASE] > 0 else -1.0
        return sg * (y[U] - pc[PC_UP]) - ip[physics.I_UY]
    # E_ISO_BYIELD
    return side * (y[U] - pc[PC_UP]) - ip[physics.I_UY]


# --- DOP853 (scipy.integrate._ivp.rk.DOP853, solve_ivp's event handling) -------------------------

@njit
def _rms(v, scale):
    acc = 0.0
    for i in range(v.size):
        x = v[i] / scale[i]
        acc += x * x
    return math.sqrt(acc) / math.sqrt(v.size)


@njit
def _initial_step(t0, y0, f0, t_bound, max_step, rtol, atol, tmp, f1, sp, ip, cp, mp, acc, mpv, accv, pc):
    """scipy.integrate._ivp.common.select_initial_step, order 7."""
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    scale = np.empty(_NY)
    for i in range(_NY):
        scale[i] = atol + abs(y0[i]) * rtol
    d0 = _rms(y0, scale)
    d1 = _rms(f0, scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(_NY):
        tmp[i] = y0[i] + h0 * f0[i]
    _rhs(t0 + h0, tmp, f1, sp, ip, cp, mp, acc, mpv, accv, pc)
    for i in range(_NY):
        tmp[i] = f1[i] - f0[i]
    d2 = _rms(tmp, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, interval, max_step)


@njit
def _rk_step(t, y, f, h, K, y_new, tmp, sp, ip, cp, mp, acc, mpv, accv, pc):
    """rk.rk_step: the 12 stages into K[0..11], y_new, and f_new into K[12]."""
    for i in range(_NY):
        K[0, i] = f[i]
    for s in range(1, _N_STAGES):
        for i in range(_NY):
            dy = 0.0
            for j in range(s):
                dy += K[j, i] * _A[s, j]
            tmp[i] = y[i] + dy * h
        _rhs(t + _C[s] * h, tmp, K[s], sp, ip, cp, mp, acc, mpv, accv, pc)
    for i in range(_NY):
        acc_i = 0.0
        for j in range(_N_STAGES):
            acc_i += K[j, i] * _B[j]
        y_new[i] = y[i] + h * acc_i
    _rhs(t + h, y_new, K[_N_STAGES], sp, ip, cp, mp, acc, mpv, accv, pc)


@njit
def _error_norm(K, h, y, y_new, rtol, atol):
    """DOP853._estimate_error_norm with scale = atol + max(|y|, |y_new|)·rtol."""
    e5, e3 = 0.0, 0.0
    for i in range(_NY):
        sc = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        a5, a3 = 0.0, 0.0
        for j in range(_N_STAGES + 1):
            a5 += K[j, i] * _E5[j]
            a3 += K[j, i] * _E3[j]
        a5 /= sc
        a3 /= sc
        e5 += a5 * a5
        e3 += a3 * a3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * _NY)


@njit
def _dense(t_old, h, y_old, y_new, f_old, f_new, K, F, tmp, sp, ip, cp, mp, acc, mpv, accv, pc):
    """DOP853._dense_output_impl: the extra stages K[13..15] and the interpolant F (7 × n)."""
    for s in range(_N_STAGES + 1, 16):
        for i in range(_NY):
            dy = 0.0
            for j in range(s):
                dy += K[j, i] * _A[s, j]
            tmp[i] = y_old[i] + dy * h
        _rhs(t_old + _C[s] * h, tmp, K[s], sp, ip, cp, mp, acc, mpv, accv, pc)
    for i in range(_NY):
        dy = y_new[i] - y_old[i]
        F[0, i] = dy
        F[1, i] = h * f_old[i] - dy
        F[2, i] = 2.0 * dy - h * (f_new[i] + f_old[i])
        for r in range(4):
            v = 0.0
            for j in range(16):
                v += _D[r, j] * K[j, i]
            F[3 + r, i] = h * v


@njit
def _at(F, y_old, t_old, h, t, out):
    """Dop853DenseOutput at t."""
    x = (t - t_old) / h
    for i in range(_NY):
        v = 0.0
        v = (v + F[6, i]) * x
        v = (v + F[5, i]) * (1.0 - x)
        v = (v + F[4, i]) * x
        v = (v + F[3, i]) * (1.0 - x)
        v = (v + F[2, i]) * x
        v = (v + F[1, i]) * (1.0 - x)
        v = (v + F[0, i]) * x
        out[i] = v + y_old[i]


@njit
def _event_at(kind, side, t, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc):
    _at(F, y_old, t_old, h, t, buf)
    return _event_value(kind, side, t, buf, sp, ip, cp, mp, acc, mpv, accv, pc)


@njit
def _brentq(kind, side, xa, xb, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc):
    """scipy.optimize.brentq with xtol = rtol = 4·eps on the dense output (solve_event_equation)."""
    xtol = 4.0 * _EPS
    rtol = 4.0 * _EPS
    xpre, xcur = xa, xb
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    fpre = _event_at(kind, side, xpre, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
    fcur = _event_at(kind, side, xcur, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if (fpre < 0.0) == (fcur < 0.0):
        return xcur
    for _ in range(100):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre = xcur
            xcur = xblk
            xblk = xpre
            fpre = fcur
            fcur = fblk
            fblk = fpre
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                den = fcur - fpre
                stry = -fcur * (xcur - xpre) / den if den != 0.0 else math.inf
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                den = dblk * dpre * (fblk - fpre)
                stry = -fcur * (fblk * dblk - fpre * dpre) / den if den != 0.0 else math.inf
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = _event_at(kind, side, xcur, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
    return xcur


# --- the output ------------------------------------------------------------------------------------

@njit
def _keep(out_t, out_y, out_m, out_sg, out_ph, out_up, n, t, y, mode, rs, history):
    """Store one state (when keeping a history); returns the new count, -1 when full."""
    if not history:
        return n
    if n >= out_t.size:
        return -1
    out_t[n] = t
    for i in range(_NY):
        out_y[n, i] = y[i]
    if mode == 0:
        out_y[n, TH] = 0.0
        out_y[n, THD] = 0.0
    out_m[n] = mode
    out_sg[n] = rs[R_SIGMA]
    out_ph[n] = rs[R_PHASE]
    out_up[n] = rs[R_UP]
    return n + 1


@njit
def _energy(y, mode, rs, sp, ip):
    """E (J) of the energy balance: kinetic, potential and the isolator element's (EnergyLog.total)."""
    s = float(mode) if mode != 0 else 1.0
    u_p = _slider_position(ip, rs[R_PHASE], y[U], rs[R_UP])
    return (_kinetic(sp, s, y[UD], y[XD], y[TH], y[THD]) + _potential(sp, s, y[U], y[TH])
            + _element_energy(ip, y[U], u_p))


@njit
def _note(t, y, mode, extremes, rs, sp, ip, rec):
    """What a stored point tells a summary, also without a history: the largest |θ|, |u| and
    |x| met, and the energy balance's residual there (the reference reads it on its stored
    points): the largest energy involved (rs[R_HELD]), and in rec the rows (t, |residual|)
    where it first doubled, its largest in the last row (limits.energy_balance_failure)."""
    if mode != 0 and abs(y[TH]) > extremes[0]:
        extremes[0] = abs(y[TH])
    if abs(y[U]) > extremes[1]:
        extremes[1] = abs(y[U])
    if abs(y[X]) > extremes[2]:
        extremes[2] = abs(y[X])
    e = _energy(y, mode, rs, sp, ip)
    res = abs(e - rs[R_E0] - y[W] + y[D] + rs[R_IMPLOSS] + y[S_LOSS] + y[FL])
    rs[R_HELD] = max(rs[R_HELD], abs(y[W]), abs(e), rs[R_IMPLOSS], y[S_LOSS], y[FL])
    n = int(rs[R_NREC])
    if (n == 0 or res > 2.0 * rec[n - 1, 1]) and n < _N_REC - 1:
        rec[n, 0] = t
        rec[n, 1] = res
        rs[R_NREC] = n + 1
    if res > rec[_N_REC - 1, 1]:
        rec[_N_REC - 1, 0] = t
        rec[_N_REC - 1, 1] = res


# --- one piece: solve_ivp between two restarts ---------------------------------------------------

@njit
def _piece(t0, t1, y, mode, evk, evs, evd, evt, nev, rtol, atol, max_step, odt, sp, ip, cp, mp, acc, mpv, accv,
           pc, rs, extremes, history, out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, wk, rec):
    """solve_ivp(fun, (t0, t1), y, method="DOP853", events=...) as the reference calls it, and
    the reference's store(): t0, the output grid and the non-terminal events' roots, then
    the end. y becomes the end state (the terminal event's, located by Brent on the dense
    output). Returns (code, t_end, index of the terminal event or −1, n_out, the last root of
    an α event up to the end or −1): code 0 reached t1, 1 a terminal event, −1 the step
    size underflowed, −2 the history is full."""
    K, F, y_new, f, tmp, f1, buf, g, g_new = wk[0], wk[1], wk[2][0], wk[2][1], wk[2][2], wk[2][3], wk[2][4], \
        wk[3][0], wk[3][1]
    t = t0
    t_alpha = -1.0
    _rhs(t, y, f, sp, ip, cp, mp, acc, mpv, accv, pc)
    h_abs = _initial_step(t, y, f, t1, max_step, rtol, atol, tmp, f1, sp, ip, cp, mp, acc, mpv, accv, pc)
    for e in range(nev):
        g[e] = _event_value(evk[e], evs[e], t, y, sp, ip, cp, mp, acc, mpv, accv, pc)
    n_out = _keep(out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, t, y, mode, rs, history)
    if n_out < 0:
        return -2, t, -1, n_out, t_alpha
    _note(t, y, mode, extremes, rs, sp, ip, rec)
    if mode != 0 and abs(y[TH]) > rs[R_PEAK]:
        rs[R_PEAK] = abs(y[TH])
    kg = math.floor(t0 / odt + 1e-9) + 1.0  # the next grid point after t0
    roots = np.empty(_MAX_EV)
    order = np.empty(_MAX_EV, dtype=np.int64)
    y_old = wk[2][5]
    while True:
        if t == t1:
            return 0, t, -1, n_out, t_alpha
        # rk._step_impl
        min_step = 10.0 * abs(np.nextafter(t, math.inf) - t)
        if h_abs > max_step:
            h_abs = max_step
        elif h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if h_abs < min_step:
                return -1, t, -1, n_out, t_alpha
            t_new = t + h_abs
            if t_new - t1 > 0:
                t_new = t1
            h = t_new - t
            h_abs = abs(h)
            _rk_step(t, y, f, h, K, y_new, tmp, sp, ip, cp, mp, acc, mpv, accv, pc)
            err = _error_norm(K, h, y, y_new, rtol, atol)
            if err < 1.0:
                factor = _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err ** (-1.0 / 8.0))
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(_MIN_FACTOR, _SAFETY * err ** (-1.0 / 8.0))
            rejected = True
        t_old = t
        for i in range(_NY):
            y_old[i] = y[i]
        # events (solve_ivp: find_active_events, handle_events)
        dense = False
        n_act = 0
        for e in range(nev):
            g_new[e] = _event_value(evk[e], evs[e], t_new, y_new, sp, ip, cp, mp, acc, mpv, accv, pc)
            up = g[e] <= 0.0 and g_new[e] >= 0.0
            down = g[e] >= 0.0 and g_new[e] <= 0.0
            if (up and evd[e] > 0) or (down and evd[e] < 0) or ((up or down) and evd[e] == 0):
                if not dense:
                    _dense(t_old, h, y_old, y_new, f, K[_N_STAGES], K, F, tmp, sp, ip, cp, mp, acc, mpv, accv, pc)
                    dense = True
                roots[n_act] = _brentq(evk[e], evs[e], t_old, t_new, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc,
                                       mpv, accv, pc)
                order[n_act] = e
                n_act += 1
            elif (evk[e] == E_ISO_STOP and g[e] > 0.0 and g_new[e] > 0.0 and pc[PC_PHASE] * f[UD] < 0.0
                  and pc[PC_PHASE] * K[_N_STAGES, UD] > 0.0):
                # a slip whose phase·u̇ dips through 0 and back within the step stops at its first
                # zero, before phase·ü rises through 0 (hybrid._IsolatorIntegrator.hidden_stop)
                if not dense:
                    _dense(t_old, h, y_old, y_new, f, K[_N_STAGES], K, F, tmp, sp, ip, cp, mp, acc, mpv, accv, pc)
                    dense = True
                fa = _event_at(E_DIP, 0.0, t_old, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
                fb = _event_at(E_DIP, 0.0, t_new, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
                if fa < 0.0 < fb:
                    t_m = _brentq(E_DIP, 0.0, t_old, t_new, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
                    _at(F, y_old, t_old, h, t_m, buf)
                    if pc[PC_PHASE] * buf[UD] < 0.0:
                        roots[n_act] = _brentq(evk[e], evs[e], t_old, t_m, F, y_old, t_old, h, buf, sp, ip, cp, mp,
                                               acc, mpv, accv, pc)
                        order[n_act] = e
                        n_act += 1
        # sorted by root (a stable insertion sort: ties keep the events' order, as numpy's argsort)
        for a in range(1, n_act):
            r, o = roots[a], order[a]
            b = a - 1
            while b >= 0 and roots[b] > r:
                roots[b + 1] = roots[b]
                order[b + 1] = order[b]
                b -= 1
            roots[b + 1] = r
            order[b + 1] = o
        hit = -1
        t_cut = t_new
        n_keep = n_act
        for a in range(n_act):
            if evt[order[a]]:
                hit = order[a]
                t_cut = roots[a]
                n_keep = a + 1
                break
        # a terminal event whose function changed sign its way between the step's start and the
        # cut, its sign at the step's end hiding it, ends the piece instead: checked again from
        # the earlier cut (hybrid._IsolatorIntegrator.first_terminal, physics.hidden_crossing)
        while hit >= 0 and t_cut > t_old:
            hid = -1
            r_hid = t_cut
            for e in range(nev):
                if e == hit or not evt[e]:
                    continue
                g_cut = _event_at(evk[e], evs[e], t_cut, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv, pc)
                if _hidden_crossing(evd[e], g[e], g_cut):
                    r = _brentq(evk[e], evs[e], t_old, t_cut, F, y_old, t_old, h, buf, sp, ip, cp, mp, acc, mpv, accv,
                                pc)
                    if r < r_hid:
                        hid = e
                        r_hid = r
            if hid < 0:
                break
            hit = hid
            t_cut = r_hid
        # the stored points of this step: grid points and the non-terminal roots before t_cut
        if not dense and (n_keep > 0 or (history and kg * odt <= t_cut)):
            _dense(t_old, h, y_old, y_new, f, K[_N_STAGES], K, F, tmp, sp, ip, cp, mp, acc, mpv, accv, pc)
            dense = True
        a = 0
        while True:
            while a < n_keep and evt[order[a]]:
                a += 1
            r = roots[a] if a < n_keep else math.inf
            tg = kg * odt if history else math.inf  # a summary needs no grid: extremes are events
            tn = min(r, tg)
            # a grid point at a step's end is stored there (SciPy's step ends are stored points),
            # but not at the piece's end or a terminal event's, which are stored below
            if tn > t_cut or (tn == t_cut and (hit >= 0 or t_new == t1)):
                break
            if tg <= r:
                kg += 1.0
            if r <= tg:
                a += 1
            if tn <= t_old:
                continue
            _at(F, y_old, t_old, h, tn, buf)
            if mode == 0:
                buf[TH] = 0.0
                buf[THD] = 0.0
            _note(tn, buf, mode, extremes, rs, sp, ip, rec)
            if mode != 0 and abs(buf[TH]) > rs[R_PEAK]:
                rs[R_PEAK] = abs(buf[TH])
            n_out = _keep(out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, tn, buf, mode, rs, history)
            if n_out < 0:
                return -2, t, -1, n_out, t_alpha
        for a in range(n_keep):
            if evk[order[a]] == E_ALPHA and roots[a] <= t_cut:
                t_alpha = roots[a]
        if hit >= 0:
            _at(F, y_old, t_old, h, t_cut, y)
            if mode == 0:
                y[TH] = 0.0
                y[THD] = 0.0
            _note(t_cut, y, mode, extremes, rs, sp, ip, rec)
            n_out = _keep(out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, t_cut, y, mode, rs, history)
            return (1 if n_out >= 0 else -2), t_cut, hit, n_out, t_alpha
        for i in range(_NY):
            y[i] = y_new[i]
            f[i] = K[_N_STAGES, i]
        for e in range(nev):
            g[e] = g_new[e]
        t = t_new
        if t == t1:
            if mode == 0:
                y[TH] = 0.0
                y[THD] = 0.0
            _note(t, y, mode, extremes, rs, sp, ip, rec)
            if mode != 0 and abs(y[TH]) > rs[R_PEAK]:
                rs[R_PEAK] = abs(y[TH])
            n_out = _keep(out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, t, y, mode, rs, history)
            return (0 if n_out >= 0 else -2), t, -1, n_out, t_alpha


# --- the run's transitions (slide_hybrid.SlidingIntegrator's and the drivers' it extends) --------

@njit
def _gravity(t, sp, cp, mpv, accv):
    return _ge(sp, cp, _xg(t, mpv, accv) if cp[sl.C_VERT] != 0.0 else 0.0)


@njit
def _log(logbuf, n, a, b, c):
    if n >= logbuf.shape[0]:
        return -1
    logbuf[n, 0] = a
    logbuf[n, 1] = b
    logbuf[n, 2] = c
    return n + 1


@njit
def _set_sigma(t, y, sigma, mode, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog):
    """SlidingIntegrator.set_sigma; returns the slip log's new length (−1 when full)."""
    if sigma != 0.0 and y[XD] == 0.0:
        xdd = _acc(sp, ip, cp, float(mode), sigma, rs[R_PHASE], rs[R_UP], y[TH], y[THD], y[U], y[UD],
                   _xg(t, mp, acc), _gravity(t, sp, cp, mpv, accv))[1]
        k, limit = _slip_start_order(sigma, xdd)
        rs[R_ST0] = t
        rs[R_SK] = k
        rs[R_SLIM] = limit
    if sigma == 0.0:
        y[XD] = 0.0
    if sigma != rs[R_SIGMA]:
        n_slog = _log(slog, n_slog, t, sigma, 0.0)
    rs[R_SIGMA] = sigma
    return n_slog


@njit
def _set_phase(t, y, phase, rs, ip, ilog, n_ilog):
    """_IsolatorIntegrator.set_phase."""
    if phase == rs[R_PHASE]:
        return n_ilog
    rs[R_UP] = _slider_position(ip, rs[R_PHASE], y[U], rs[R_UP])
    if phase == 0.0 and ip[physics.I_KIND] >= physics.ISO_FRICTION:
        y[UD] = 0.0
    rs[R_PHASE] = phase
    return _log(ilog, n_ilog, t, phase, y[U])


@njit
def _stick_or_slip(t, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv):
    """SlidingIntegrator.stick_or_slip: a rigid slider's phase at rest with the block's mode."""
    u_p = _slider_position(ip, rs[R_PHASE], y[U], rs[R_UP])
    d = _held_demand(sp, ip, cp, float(mode), rs[R_SIGMA], y[TH], y[THD], y[U], u_p, _xg(t, mp, acc),
                     _gravity(t, sp, cp, mpv, accv))
    if abs(d) <= _stick_limit(sp, ip):
        return 0.0
    return _slip_phase(ip, 1.0 if d > 0.0 else -1.0, y[U], u_p)


@njit
def _after_velocity(t, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv):
    """_IsolatorIntegrator.slider_after_velocity."""
    ud = y[UD]
    if ip[physics.I_KIND] >= physics.ISO_FRICTION:
        if ud == 0.0:
            return _stick_or_slip(t, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv)
        sg = 1.0 if ud > 0.0 else -1.0
        if rs[R_PHASE] * sg > 0.0:
            return rs[R_PHASE]
        return _slip_phase(ip, sg, y[U], _slider_position(ip, rs[R_PHASE], y[U], rs[R_UP]))
    if rs[R_PHASE] != 0.0 and rs[R_PHASE] * ud <= 0.0:
        return 0.0
    return rs[R_PHASE]


@njit
def _lift(t, side, upl, n_upl, rs):
    """The block lifts about corner `side` at t (the reference's lift): (uplifts logged, the new mode)."""
    upl[n_upl] = t
    rs[R_PEAK] = 0.0
    rs[R_GRAZE] = 0.0
    return n_upl + 1, int(side)


@njit
def _relift(t, y, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog):
    """SlidingIntegrator.relift: (corner it lifts about or 0, why it stops or 0, slip log length)."""
    s, sigma, why = _flat_mode(sp, ip, cp, rs[R_PHASE], rs[R_UP], y[U], y[UD], y[XD], _xg(t, mp, acc),
                               _gravity(t, sp, cp, mpv, accv), rs[R_GRAZE] != 0.0, False, False)
    if s == sl.NO_MODE:
        return 0, why, n_slog
    n_slog = _set_sigma(t, y, sigma, int(s), rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
    return int(s), 0, n_slog


@njit
def _events(mode, t, y, rs, pc, evk, evs, evd, evt, sp, ip, cp, mp, acc, mpv, accv, rule_alpha, fixed, motion_end,
            f0):
    """The piece's events, in the reference's order (SlidingIntegrator.translation_events or
    rocking_events, then the base's extremes); sets the piece context pc. Returns how many."""
    sigma, phase = rs[R_SIGMA], rs[R_PHASE]
    kind = ip[physics.I_KIND]
    pc[PC_S] = mode
    pc[PC_SIGMA] = sigma
    pc[PC_PHASE] = phase
    pc[PC_UP] = rs[R_UP]
    pc[PC_T0] = t
    pc[PC_THR] = cp[sl.C_TAN] * (1.0 + (physics.GRAZE_MARGIN if rs[R_GRAZE] != 0.0 else 0.0))
    pc[PC_FS] = _stick_limit(sp, ip)
    pc[PC_SDIV] = 1.0 if sigma != 0.0 and rs[R_ST0] == t else 0.0
    pc[PC_SK] = rs[R_SK]
    pc[PC_SLIMIT] = rs[R_SLIM]
    pc[PC_KPOW] = 0.0
    pc[PC_IDIV] = 0.0
    slips = cp[sl.C_MUS] < math.inf
    n = 0
    if mode != 0:
        s = float(mode)
        if y[TH] == 0.0:  # divided by (t − t0)^k: the piece's start is never taken for a landing
            if y[THD] != 0.0:
                pc[PC_KPOW], pc[PC_LIMIT] = 1.0, s * y[THD]
            else:
                thdd = _acc(sp, ip, cp, s, sigma, phase, rs[R_UP], y[TH], y[THD], y[U], y[UD], _xg(t, mp, acc),
                            _gravity(t, sp, cp, mpv, accv))[2]
                k, limit = _lift_order(sp, s, thdd)
                pc[PC_KPOW], pc[PC_LIMIT] = float(k), limit
        n = _add(evk, evs, evd, evt, n, E_IMPACT, 0.0, -1, True)
        n = _add(evk, evs, evd, evt, n, E_ALPHA, 0.0, 1, rule_alpha or (fixed and t >= motion_end))
        n = _add(evk, evs, evd, evt, n, E_PEAK, 0.0, 0, False)
        if not rule_alpha:
            n = _add(evk, evs, evd, evt, n, E_SIDE, 0.0, 1, True)
    else:
        if sigma == 0.0:
            n = _add(evk, evs, evd, evt, n, E_TIP, 1.0, 1, True)
            n = _add(evk, evs, evd, evt, n, E_TIP, -1.0, 1, True)
            if slips:
                n = _add(evk, evs, evd, evt, n, E_SLIP_FLAT, 1.0, 1, True)
                n = _add(evk, evs, evd, evt, n, E_SLIP_FLAT, -1.0, 1, True)
        else:
            n = _add(evk, evs, evd, evt, n, E_STOP, 0.0, -1, True)
        if cp[sl.C_VERT] != 0.0:
            n = _add(evk, evs, evd, evt, n, E_FLY_GE, 0.0, -1, True)
    # the isolator's slider (SlidingIntegrator.slider_events)
    if kind != physics.ISO_LINEAR:
        if phase == 0.0 and kind >= physics.ISO_FRICTION:
            n = _add(evk, evs, evd, evt, n, E_ISO_DEMAND, 1.0, 1, True)
            n = _add(evk, evs, evd, evt, n, E_ISO_DEMAND, -1.0, 1, True)
        elif phase != 0.0:
            if y[UD] == 0.0:
                pc[PC_IDIV] = 1.0
                pc[PC_ISTART] = phase * f0[UD]
            n = _add(evk, evs, evd, evt, n, E_ISO_STOP, 0.0, -1, True)
            sg = 1.0 if phase > 0.0 else -1.0
            if kind == physics.ISO_CONE and abs(phase) == 2.0:
                n = _add(evk, evs, evd, evt, n, E_ISO_VERTEX, sg, 1, True)
            elif kind == physics.ISO_DOUBLE and abs(phase) == 1.0 and ip[physics.I_UY] > 0.0:
                n = _add(evk, evs, evd, evt, n, E_ISO_DYIELD, 2.0 * sg, 1, True)
        else:
            n = _add(evk, evs, evd, evt, n, E_ISO_BYIELD, 1.0, 1, True)
            n = _add(evk, evs, evd, evt, n, E_ISO_BYIELD, -1.0, 1, True)
    if mode != 0:
        if sigma == 0.0:
            if slips:
                n = _add(evk, evs, evd, evt, n, E_SLIP_ROCK, 1.0, 1, True)
                n = _add(evk, evs, evd, evt, n, E_SLIP_ROCK, -1.0, 1, True)
        else:
            n = _add(evk, evs, evd, evt, n, E_STOP, 0.0, -1, True)
            n = _add(evk, evs, evd, evt, n, E_PAINLEVE, 0.0, -1, True)
        n = _add(evk, evs, evd, evt, n, E_FLY_FZ, 0.0, -1, True)
    if not fixed:
        n = _add(evk, evs, evd, evt, n, E_BASE_PEAK, 0.0, 0, False)
    return n


@njit
def _add(evk, evs, evd, evt, n, kind, side, direction, terminal):
    evk[n] = kind
    evs[n] = side
    evd[n] = direction
    evt[n] = terminal
    return n + 1


@cached_jit(nogil=True)
def _run(sp, ip, cp, mp, acc, mpv, accv, breaks, T, y0, rtol, atol, max_step, max_events, odt, history, cap,
         rule_alpha, motion_end):
    """SlidingIntegrator.run from (u0, u̇0, θ0, θ̇0) = y0 to T. Returns (status, why it stopped,
    t, last time past α, verdict, P_z of a failed landing, θ at the end, events, n_out, t, y, mode, σ, phase, u_p,
    n_imp, impacts [t, θ̇⁻, θ̇⁺, u̇⁻, u̇⁺, continued, amplitude, loss], n_upl, uplifts, n_slog,
    slip log [t, σ, 0], n_ilog, isolator log [t, phase, u], extremes [|θ|, |u|, |x|])."""
    n_hist = cap if history else 1
    out_t = np.empty(n_hist)
    out_y = np.empty((n_hist, _NY))
    out_m = np.empty(n_hist, dtype=np.int8)
    out_sg = np.empty(n_hist, dtype=np.int8)
    out_ph = np.empty(n_hist, dtype=np.int8)
    out_up = np.empty(n_hist)
    imp = np.empty((cap, 8))
    upl = np.empty(cap)
    slog = np.empty((cap, 3))
    ilog = np.empty((cap, 3))
    extremes = np.zeros(3)
    wk = (np.empty((16, _NY)), np.empty((7, _NY)), np.empty((6, _NY)), np.empty((2, _MAX_EV)))
    evk = np.empty(_MAX_EV, dtype=np.int64)
    evs = np.empty(_MAX_EV)
    evd = np.empty(_MAX_EV, dtype=np.int64)
    evt = np.empty(_MAX_EV, dtype=np.bool_)
    pc = np.zeros(N_PC)
    rs = np.zeros(N_RS)
    rs[R_TALPHA] = -1.0
    f0 = np.empty(_NY)
    y = np.zeros(_NY)
    y[U], y[UD], y[TH], y[THD] = y0[0], y0[1], y0[2], y0[3]
    fixed = sp[physics.FIXED] != 0.0
    friction = ip[physics.I_KIND] >= physics.ISO_FRICTION
    linear = ip[physics.I_KIND] == physics.ISO_LINEAR
    alpha = sp[physics.ALPHA]
    u_y = ip[physics.I_UY]
    n_out, n_imp, n_upl, n_slog, n_ilog = 0, 0, 0, 0, 0
    status, why, verdict, pz_fail = _COMPLETED, STOP_NONE, 0, 0.0
    t = 0.0
    # _IsolatorIntegrator.initial_state
    rs[R_UP] = y[U] - min(max(y[U], -u_y), u_y) if u_y > 0.0 else 0.0
    if friction:
        mode0 = 0 if y[TH] == 0.0 else (1 if y[TH] > 0.0 else -1)
        if y[UD] != 0.0:
            rs[R_PHASE] = _slip_phase(ip, 1.0 if y[UD] > 0.0 else -1.0, y[U], rs[R_UP])
        else:
            rs[R_PHASE] = _stick_or_slip(0.0, y, mode0, rs, sp, ip, cp, mp, acc, mpv, accv)
    # the first mode (SlidingIntegrator.uplift_mode and begin)
    mode = 0
    if y[TH] != 0.0:
        mode = 1 if y[TH] > 0.0 else -1
    elif y[THD] != 0.0:
        mode = 1 if y[THD] > 0.0 else -1
    chosen = False
    if mode == 0:
        s, sigma, w = _flat_mode(sp, ip, cp, rs[R_PHASE], rs[R_UP], y[U], y[UD], 0.0, _xg(0.0, mp, acc),
                                 _gravity(0.0, sp, cp, mpv, accv), False, False, False)
        if s == sl.NO_MODE:
            why = w
        else:
            n_slog = _set_sigma(0.0, y, sigma, int(s), rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
            chosen = True
            mode = int(s)
            if mode != 0:
                upl[n_upl] = 0.0
                n_upl += 1
                if friction and y[UD] == 0.0:
                    # a rigid slider at rest takes its phase from the lifting block's demand (the reference's rule)
                    rs[R_PHASE] = _stick_or_slip(0.0, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv)
    if why == STOP_NONE and not chosen:
        sigma, w = _rock_mode(sp, ip, cp, float(mode), rs[R_PHASE], rs[R_UP], y[TH], y[THD], y[U], y[UD],
                              _xg(0.0, mp, acc), _gravity(0.0, sp, cp, mpv, accv), True)
        if sigma == sl.NO_MODE:
            why = w
        else:
            n_slog = _set_sigma(0.0, y, sigma, mode, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
    rec = np.zeros((_N_REC, 2))  # the energy balance's growth (_note)
    rs[R_E0] = _energy(y, mode, rs, sp, ip)
    events = 0
    ibreak = 1
    nb = breaks.size
    while why == STOP_NONE and t < T:
        if n_imp >= cap - 1 or n_upl >= cap - 1 or n_slog < 0 or n_ilog < 0:
            status = _NO_ROOM
            break
        while ibreak < nb and breaks[ibreak] <= t + 1e-12:
            ibreak += 1
        t_end = breaks[ibreak] if ibreak < nb else T
        if (mode != 0 and not rule_alpha and fixed and t >= motion_end and mode * y[TH] > alpha
                and mode * y[THD] > 0.0):
            verdict = 3
            break
        pc[PC_S] = mode
        pc[PC_SIGMA] = rs[R_SIGMA]
        pc[PC_PHASE] = rs[R_PHASE]
        pc[PC_UP] = rs[R_UP]
        _rhs(t, y, f0, sp, ip, cp, mp, acc, mpv, accv, pc)
        nev = _events(mode, t, y, rs, pc, evk, evs, evd, evt, sp, ip, cp, mp, acc, mpv, accv, rule_alpha, fixed,
                      motion_end, f0)
        code, t_new, hit, n_out, t_al = _piece(t, t_end, y, mode, evk, evs, evd, evt, nev, rtol, atol, max_step,
                                               odt, sp, ip, cp, mp, acc, mpv, accv, pc, rs, extremes, history,
                                               out_t, out_y, out_m, out_sg, out_ph, out_up, n_out, wk, rec)
        if code == -2:
            status = _NO_ROOM
            break
        if t_al >= 0.0:
            rs[R_TALPHA] = t_al
        if code == -1:
            t = t_new
            why = STOP_INTEGRATION
            break
        t = t_new
        if hit < 0:
            continue
        if mode != 0 and abs(y[TH]) > rs[R_PEAK]:
            rs[R_PEAK] = abs(y[TH])
        events += 1
        if events > max_events:
            status = _EVENT_LIMIT
            break
        kind, side = evk[hit], evs[hit]
        xg, ge = _xg(t, mp, acc), _gravity(t, sp, cp, mpv, accv)
        if kind == E_ALPHA:
            rs[R_TALPHA] = t
            verdict = 1 if rule_alpha else 3
            break
        if kind == E_SIDE:
            verdict = 2
            break
        if kind == E_IMPACT:
            s = float(mode)
            y[TH] = 0.0
            thd_pre, xd_pre, ud_pre = y[THD], y[XD], y[UD]
            cont = _impact_continues(sp, thd_pre)
            thd, xd, ud, px, pz, ok = _impact_map(sp, cp, s, thd_pre, xd_pre, ud_pre, cont)
            if not ok:
                why = STOP_IMPULSE
                pz_fail = pz
                break
            loss = _kinetic(sp, s, ud_pre, xd_pre, 0.0, thd_pre) - _kinetic(sp, -s, ud, xd, 0.0, thd)
            cont = thd != 0.0
            imp[n_imp, 0] = t
            imp[n_imp, 1] = thd_pre
            imp[n_imp, 2] = thd
            imp[n_imp, 3] = ud_pre
            imp[n_imp, 4] = ud
            imp[n_imp, 5] = 1.0 if cont else 0.0
            imp[n_imp, 6] = rs[R_PEAK]
            imp[n_imp, 7] = loss
            rs[R_IMPLOSS] += loss
            n_imp += 1
            rs[R_PEAK] = 0.0
            y[THD], y[XD], y[UD] = thd, xd, ud
            new = -mode if cont else 0
            if not linear:
                n_ilog = _set_phase(t, y, _after_velocity(t, y, new, rs, sp, ip, cp, mp, acc, mpv, accv), rs, ip,
                                    ilog, n_ilog)
            if cont:
                if xd != 0.0:
                    n_slog = _set_sigma(t, y, 1.0 if xd > 0.0 else -1.0, new, rs, sp, ip, cp, mp, acc, mpv, accv,
                                        slog, n_slog)
                else:
                    sg, w = _rock_mode(sp, ip, cp, float(new), rs[R_PHASE], rs[R_UP], 0.0, thd, y[U], y[UD],
                                       _xg(t, mp, acc), _gravity(t, sp, cp, mpv, accv), True)
                    if sg == sl.NO_MODE:
                        why = w
                        break
                    n_slog = _set_sigma(t, y, sg, new, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
                mode = new
                continue
            side2, w, n_slog = _relift(t, y, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
            if w != 0:
                why = w
                break
            if side2 != 0:
                n_upl, mode = _lift(t, side2, upl, n_upl, rs)
            else:
                if rs[R_SIGMA] == 0.0:
                    rs[R_GRAZE] = 1.0
                mode = 0
            continue
        if kind >= E_ISO_DEMAND:  # the isolator's slider (_IsolatorIntegrator.isolator_event)
            phase = rs[R_PHASE]
            if kind == E_ISO_STOP:
                y[UD] = 0.0
                new_ph = _stick_or_slip(t, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv) if friction else 0.0
                if new_ph * phase > 0.0:
                    new_ph = 0.0
            elif phase == 0.0 and friction:
                new_ph = _slip_phase(ip, side, y[U], _slider_position(ip, phase, y[U], rs[R_UP]))
            elif ip[physics.I_KIND] == physics.ISO_CONE:
                y[U] = 0.0
                new_ph = side
                if abs(y[UD]) < _vertex_rest_speed(sp, ip):
                    s = 1.0 if mode >= 0 else -1.0
                    y[S_LOSS] += (_kinetic(sp, s, y[UD], y[XD], y[TH], y[THD])
                                  - _kinetic(sp, s, 0.0, y[XD], y[TH], y[THD]))
                    y[UD] = 0.0
                    n_ilog = _set_phase(t, y, 0.0, rs, ip, ilog, n_ilog)
                    new_ph = _stick_or_slip(t, y, mode, rs, sp, ip, cp, mp, acc, mpv, accv)
            else:
                new_ph = side
            n_ilog = _set_phase(t, y, new_ph, rs, ip, ilog, n_ilog)
            if mode == 0:
                side2, w, n_slog = _relift(t, y, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
                if w != 0:
                    why = w
                    break
                if side2 != 0:
                    n_upl, mode = _lift(t, side2, upl, n_upl, rs)
            if rs[R_SIGMA] == 0.0 and mode != 0:
                sg, w = _rock_mode(sp, ip, cp, float(mode), rs[R_PHASE], rs[R_UP], y[TH], y[THD], y[U], y[UD], xg,
                                   ge, True)
                if sg == sl.NO_MODE:
                    why = w
                    break
                n_slog = _set_sigma(t, y, sg, mode, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
            continue
        # the contact's own events (SlidingIntegrator.transition)
        if kind == E_FLY_FZ or kind == E_FLY_GE:
            why = STOP_FLIGHT
            break
        if kind == E_PAINLEVE:
            why = STOP_PAINLEVE
            break
        if kind == E_STOP:
            old = rs[R_SIGMA]
            y[XD] = 0.0
            if mode == 0:
                s, sg, w = _flat_mode(sp, ip, cp, rs[R_PHASE], rs[R_UP], y[U], y[UD], 0.0, xg, ge,
                                      rs[R_GRAZE] != 0.0, False, False)
            else:
                s = float(mode)
                sg, w = _rock_mode(sp, ip, cp, s, rs[R_PHASE], rs[R_UP], y[TH], y[THD], y[U], y[UD], xg, ge, True)
            if s == sl.NO_MODE or sg == sl.NO_MODE:
                why = w
                break
            if sg == old and int(s) == mode:
                sg = 0.0
            n_slog = _set_sigma(t, y, sg, int(s), rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
            if int(s) != mode:
                n_upl, mode = _lift(t, int(s), upl, n_upl, rs)
            continue
        if mode == 0:  # tip or slip from rest
            s, sg, w = _flat_mode(sp, ip, cp, rs[R_PHASE], rs[R_UP], y[U], y[UD], 0.0, xg, ge, rs[R_GRAZE] != 0.0,
                                  kind == E_TIP, kind == E_SLIP_FLAT)
            if s == sl.NO_MODE:
                why = w
                break
            n_slog = _set_sigma(t, y, sg, int(s), rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
            if s != 0.0:
                n_upl, mode = _lift(t, int(s), upl, n_upl, rs)
            elif sg == 0.0:
                rs[R_GRAZE] = 1.0
            continue
        # a rocking corner slips
        if _denominator(sp, cp, float(mode), side, y[TH]) <= 0.0:
            why = STOP_PAINLEVE
            break
        n_slog = _set_sigma(t, y, side, mode, rs, sp, ip, cp, mp, acc, mpv, accv, slog, n_slog)
    if n_slog < 0 or n_ilog < 0:
        status = _NO_ROOM
    if why != STOP_NONE and status == _COMPLETED:
        status = _FAILED
    if status == _COMPLETED and verdict == 0:
        verdict = _overturn_code(rule_alpha, y[TH], alpha, False)
    if verdict != 0 and status == _COMPLETED:
        status = _OVERTURNED
    return (status, why, t, rs[R_TALPHA], verdict, pz_fail, y[TH], events, n_out, out_t, out_y, out_m, out_sg,
            out_ph, out_up, n_imp, imp, n_upl, upl, n_slog, slog, n_ilog, ilog, extremes, rs[R_HELD], int(rs[R_NREC]),
            rec)


# --- Python side ------------------------------------------------------------------------------------

#: room for histories and logs a run starts with; a run that fills it runs again with four times more
_ROOM = 4096


def _vertical_params(motion):
    v = motion.vertical
    if v is None or v.is_zero:
        return np.zeros(physics.N_MP), np.zeros(1)
    return physics.motion_params(v)


def prepare(system, motion, settings, duration):
    """The kernel's packed inputs of one run (everything _run takes before y0)."""
    sp, ip = physics.isolator_params(system, settings.rest_velocity)
    vertical = motion.vertical is not None and not motion.vertical.is_zero
    cp = sl.contact_params(system, vertical)
    mp, acc = physics.motion_params(motion)
    mpv, accv = _vertical_params(motion)
    breaks = np.append(motion.breakpoints(duration), duration).astype(np.float64)
    return sp, ip, cp, mp, np.ascontiguousarray(acc, dtype=np.float64), mpv, np.ascontiguousarray(accv, np.float64), \
        breaks


def run(system, motion, settings, duration, y0, history: bool):
    """_run on one System and GroundMotion (inputs checked by the caller), again with more room
    while it fills its outputs."""
    args = prepare(system, motion, settings, duration)
    cap = _ROOM
    while True:
        r = call_kernel(_run, *args, float(duration), np.asarray(y0, dtype=np.float64), settings.rtol,
                        settings.atol, settings.max_step, settings.max_events, settings.output_dt, history, cap,
                        settings.overturn == physics.AT_ALPHA, float(motion.last_time))
        if r[0] != _NO_ROOM:
            return r
        cap *= 4


def _balance_failure(r):
    """limits.energy_balance_failure of a run r (its energy balance read at its stored points), or None."""
    held, n_rec, rec = r[24:27]
    rows = np.concatenate([rec[:n_rec], rec[-1:]])
    return energy_balance_failure(rows[:, 0], rows[:, 1], held)


def _message(system, settings, r):
    """The reference's status and message for how the run ended (slide_hybrid's, hybrid's)."""
    status, message = _ending(system, settings, r)
    if status.ended_normally:  # a history that took a branch the physics did not is no answer (limits.py)
        failure = _balance_failure(r)
        if failure:
            return Status.FAILED, failure
    return status, message


def _ending(system, settings, r):
    status, why, t, t_alpha, verdict, pz, theta_end, events = r[:8]
    if why == STOP_INTEGRATION:
        return Status.FAILED, f"integration failed at t = {t:.6g} s: Required step size is less than spacing between numbers."
    if why == STOP_IMPULSE:
        return Status.OUTSIDE_MODEL, (f"the model stops at t = {t:.6g} s: the landing would need a negative normal impulse "
                               f"(P_z = {pz:.3g} N·s; docs/sliding.md, \"Impact\")")
    if why != STOP_NONE:
        where = " (at the start)" if events == 0 and t == 0.0 else ""
        return Status.OUTSIDE_MODEL, f"the model stops at t = {t:.6g} s{where}: {sl.STOP_WHY[why]}"
    if status == _EVENT_LIMIT:
        return Status.EVENT_LIMIT, f"stopped after {settings.max_events} events at t = {t:.6g} s (max_events)"
    if status == _OVERTURNED:
        return Status.OVERTURNED, describe(verdict, t, t_alpha if t_alpha >= 0 else None, theta_end / system.alpha)
    return Status.COMPLETED, "reached the end time"


def simulate(system, motion, settings, duration, theta0, theta_dot0, u0, u_dot0, impact_threshold, engine):
    """The Trajectory of analytic.slide_hybrid.simulate (inputs checked by the caller), compiled."""
    start = time.perf_counter()
    r = run(system, motion, settings, duration, [u0, u_dot0, theta0, theta_dot0], True)
    status, message = _message(system, settings, r)
    (n_out, out_t, out_y, out_m, out_sg, out_ph, out_up, n_imp, imp, n_upl, upl, n_slog, slog, n_ilog,
     ilog) = r[8:23]
    sp, ip = physics.isolator_params(system, settings.rest_velocity)
    cp = sl.contact_params(system, False)
    t, y = out_t[:n_out], out_y[:n_out].T
    mode, sigma, phase = out_m[:n_out], out_sg[:n_out], out_ph[:n_out]
    kind = ip[physics.I_KIND]
    u_p = out_up[:n_out].copy()
    plastic = (phase != 0) & ((kind == physics.ISO_BILINEAR) | ((kind == physics.ISO_DOUBLE) & (np.abs(phase) == 2)))
    u_p[plastic] = y[U][plastic] - np.sign(phase[plastic]) * ip[physics.I_UY]  # the slider moves with the base
    imp = imp[:n_imp]
    impacts = tuple(Impact(t=row[0], theta_dot_pre=row[1], theta_dot_post=row[2], u_dot_pre=row[3],
                           u_dot_post=row[4], continued=bool(row[5]), amplitude=row[6],
                           counted=row[6] > impact_threshold * system.alpha) for row in imp.tolist())
    s = np.where(mode == 0, 1.0, mode)
    linear = kind == physics.ISO_LINEAR
    log = EnergyLog(kinetic=sl.kinetic_energy(sp, s, y[UD], y[XD], y[TH], y[THD]),
                    potential=physics.potential_energy(sp, s, y[U], y[TH]) + physics.element_energy(ip, y[U], u_p),
                    ground_work=y[W], dashpot_loss=y[D],
                    impact_loss=cumulative_impact_loss(t, imp[:, 0], imp[:, 7]), per_impact=tuple(imp[:, 7].tolist()),
                    isolator_loss=None if linear else y[S_LOSS],
                    slip_loss=y[FL] if math.isfinite(cp[sl.C_MUS]) else None)
    slip_events = tuple((float(a), int(b)) for a, b, _ in slog[:n_slog].tolist())
    extras = {"overturn_rule": settings.overturn, "slip_mode": sigma.copy(), "slip_events": slip_events,
              "slip_onset": next((te for te, sg in slip_events if sg != 0), None)}
    if not linear:
        extras.update(isolator=system.isolator_kind, isolator_phase=phase.copy(), isolator_slider=u_p,
                      isolator_events=tuple((float(a), int(b), float(c)) for a, b, c in ilog[:n_ilog].tolist()))
    overturned = status == Status.OVERTURNED
    return Trajectory(
        engine=engine, system=system, t=t, u=y[U], u_dot=y[UD], theta=y[TH], theta_dot=y[THD], mode=mode.copy(),
        impacts=impacts, uplift_times=tuple(upl[:n_upl].tolist()), overturned=overturned,
        overturn_time=(r[3] if r[3] >= 0 else None) if overturned else None, impact_threshold=impact_threshold,
        runtime_s=time.perf_counter() - start, status=status, message=message, energy=log, extras=extras,
        slide=y[X], slide_dot=y[XD])


def summary(system, motion, settings, duration, theta0, impact_threshold) -> dict:
    """The batch row of one run (analytic.fast.simulate_batch's fields, and the slide's)."""
    r = run(system, motion, settings, duration, [0.0, 0.0, theta0, 0.0], False)
    status, message = _message(system, settings, r)
    n_imp, imp, n_upl = r[15], r[16], r[17]
    extremes = r[23]
    overturned = status == Status.OVERTURNED
    slog = r[20][:r[19]]
    onset = next((float(a) for a, b, _ in slog.tolist() if b != 0), None)
    return {"status": status, "message": message,
            "theta_max_over_alpha": float(theta_max_over_alpha(extremes[0], system.alpha, overturned,
                                                               settings.overturn)),
            "impacts": int(np.sum(imp[:n_imp, 6] > impact_threshold * system.alpha)), "impacts_all": int(n_imp),
            "uplifts": int(n_upl), "overturned": overturned,
            "overturn_time": (r[3] if r[3] >= 0 else None) if overturned else None,
            "u_max": float(extremes[1]), "duration": float(r[2]), "overturn_rule": settings.overturn,
            "friction_demand": math.nan, "slide_max": float(extremes[2]), "slip_onset": onset}
