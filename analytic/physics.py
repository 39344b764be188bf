"""The physics of model.md, written once: equations of motion of both modes, the uplift
condition, both impact maps, the pivot forces (friction demand), the energy terms, the
overturning rule and the first uplift under a closed-form pulse or a record.

Every function here is plain Python on floats that numba can compile as it is: the
SciPy reference path (analytic/hybrid.py) calls them directly, the compiled kernel
(analytic/fast.py) wraps them with `numba.njit`. So the two paths cannot disagree on
physics, only on integration (and the kernel ports SciPy's integrator step by step).

A system and a motion are passed as packed parameter vectors (`system_params`,
`motion_params`), indexed by the names below; a tuple or a float64 array both work.
Energy and force functions use numpy's sin/cos so that they also take arrays.
"""
from __future__ import annotations

import math

import numpy as np

from .coefficients import beta, beta2, beta3, edge_impact
from .system import STANDARD_GRAVITY

# --- packed system parameters -------------------------------------------------------
(M_BLOCK, M_TOTAL, H, B_HALF, G, K, C_DAMP, FIXED, ALPHA, J, THR, BETA, BETA2, BETA3, REST,
 INV_M, INV_J, M_BASE, INERTIA, B_NEG, ALPHA_NEG, J_NEG, INV_J_NEG, THR_NEG, BETA_NEG, BETA2_NEG, N_SP) = range(27)
# The slots that differ between a statue's two tipping edges (System.body, issue 36) hold the
# forward edge's (s = +1: B_HALF, ALPHA, J, INV_J, THR, and the BETA, BETA2 of an impact that
# ends rocking about it) and, in their _NEG twins, the backward edge's (s = −1); `edge` reads the
# one of corner s. For the rectangle the twins are equal, and every result is as before to the bit.

# --- packed motion parameters -------------------------------------------------------
(KIND, DT, END, AMP, OMEGA, FREQ, PEND, SCALE, SHIFT, PIECE, PI, PA0, PA1, INV_DT, N_MP) = range(15)
# PIECE: how the current integration piece reads a record: 0 the general way,
# 1 within one sample interval (index PI, samples PA0, PA1), 2 after the last sample (PA0:
# the value at the last sample itself); see piece_acceleration and record_piece
SAMPLED, SINE, COSINE, RICKER = 0, 1, 2, 3
PULSE_KIND = {"sine": SINE, "cosine": COSINE, "ricker": RICKER}

# --- overturning rules ----------------------------------------------------------------
#: model.md's rule (default): overturned when |θ| reaches π/2, or when the run ends with |θ| > α
PAST_ALPHA = "past-alpha"
#: the conservative engineering rule: overturned once |θ| reaches α (the run stops there)
AT_ALPHA = "alpha"
OVERTURN_RULES = (PAST_ALPHA, AT_ALPHA)
SIDE_ANGLE = 0.5 * math.pi  # |θ| at which the block lies on its side


def system_params(system, rest_velocity: float) -> np.ndarray:
    """A System packed for the functions below (rest_velocity: the dimensionless floor
    of AnalyticSettings, stored as rest_velocity·p·α in rad/s)."""
    lam, mu, h = system.slenderness, system.mu, system.h
    sp = np.zeros(N_SP)
    sp[M_BLOCK] = system.mass
    sp[M_TOTAL] = system.total_mass
    sp[H] = h
    sp[G] = system.gravity
    sp[K] = 0.0 if system.fixed_base else system.stiffness
    sp[C_DAMP] = 0.0 if system.fixed_base else system.damping
    sp[FIXED] = 1.0 if system.fixed_base else 0.0
    sp[BETA3] = beta3(mu, h)
    sp[REST] = rest_velocity * system.p * system.alpha
    sp[INV_M] = 1.0 / system.total_mass
    sp[M_BASE] = 0.0 if system.fixed_base else system.base_mass
    sp[INERTIA] = system.inertia
    for side, (b, alpha, j, inv_j, thr, bt, bt2) in ((1, (B_HALF, ALPHA, J, INV_J, THR, BETA, BETA2)),
                                                     (-1, (B_NEG, ALPHA_NEG, J_NEG, INV_J_NEG, THR_NEG, BETA_NEG,
                                                           BETA2_NEG))):
        sp[b] = system.lever(side)
        sp[alpha] = system.edge_alpha(side)
        sp[j] = system.mass * system.edge_radius(side) ** 2 + system.inertia
        sp[inv_j] = 1.0 / sp[j]
        sp[thr] = system.gravity * sp[b] / h if system.asymmetric else system.uplift_acceleration
        if system.asymmetric:  # the impact onto the other edge, from this one (coefficients.edge_impact)
            sp[bt], sp[bt2] = edge_impact(system.mass, None if system.fixed_base else system.base_mass, h,
                                          system.inertia, system.lever(side), system.lever(-side))
        else:  # the paper's closed forms, as they always were
            sp[bt], sp[bt2] = beta(lam, mu), beta2(lam, mu, h)
    return sp


def edge(sp, s, forward, backward):
    """The slot of corner s's edge: sp[forward] for s = +1, sp[backward] for s = −1 (s a number
    or an array of ±1, as the energy functions take it). Exact for the rectangle, whose two are
    equal (½(x + x) + ½s·0 is x to the bit); within an ulp for two edges."""
    return 0.5 * (sp[forward] + sp[backward]) + 0.5 * s * (sp[forward] - sp[backward])


def motion_params(motion):
    """(parameters, samples) of a GroundMotion: pulses in closed form, records as samples."""
    mp = np.zeros(N_MP)
    if motion.pulse is not None:
        p = motion.pulse
        mp[KIND] = PULSE_KIND[p.kind]
        mp[AMP] = p.amp * STANDARD_GRAVITY
        mp[OMEGA] = 2 * math.pi * p.freq
        mp[FREQ] = p.freq
        mp[PEND] = p.end_time
        mp[SCALE] = motion.scale
        mp[SHIFT] = motion._pulse_shift
        mp[END] = motion.end_time
        return mp, np.zeros(1)
    mp[KIND] = SAMPLED
    mp[DT] = motion.dt
    mp[END] = motion.end_time
    mp[INV_DT] = 1.0 / motion.dt if motion.dt > 0 else 0.0
    return mp, np.asarray(motion.acceleration, dtype=np.float64)


# --- ground motion ----------------------------------------------------------------------

def pulse_acceleration(kind, amp, omega, freq, tt):
    """A closed-form pulse's ẍg (m/s², before scaling) at pulse time tt inside its span."""
    if kind == SINE:
        return amp * math.sin(omega * tt)
    if kind == COSINE:
        return amp * math.cos(omega * tt)
    tau = tt - 1.0 / freq
    x = (math.pi * freq * tau) ** 2
    return amp * (1.0 - 2.0 * x) * math.exp(-x)


def piece_acceleration(t, mp):
    """ẍg(t) in m/s² inside one integration piece, from the motion's parameters alone: a
    closed-form pulse, or a record's piece as `record_piece` set it up (its one sample
    interval, linear; or after the record's end, zero but at the end itself)."""
    if int(mp[KIND]) == SAMPLED:
        if mp[PIECE] == 2.0:
            return mp[PA0] if t <= mp[END] else 0.0
        f = t * mp[INV_DT] - mp[PI]
        return (1.0 - f) * mp[PA0] + f * mp[PA1]
    tt = t + mp[SHIFT]
    if tt < 0.0 or tt > mp[PEND]:
        return 0.0
    return mp[SCALE] * pulse_acceleration(int(mp[KIND]), mp[AMP], mp[OMEGA], mp[FREQ], tt)


def ground_acceleration(t, mp, acc):
    """ẍg(t) in m/s² (GroundMotion.at): records linearly interpolated, zero outside."""
    if int(mp[KIND]) == SAMPLED and mp[PIECE] == 0.0:
        if t < 0.0 or t > mp[END]:
            return 0.0
        n = acc.size
        if n == 1:
            return acc[0] if t == 0.0 else 0.0
        x = t / mp[DT]
        i = min(int(x), n - 2)
        f = x - i
        return (1.0 - f) * acc[i] + f * acc[i + 1]
    return piece_acceleration(t, mp)


def record_piece(mp, acc, t0, t1):
    """Set mp's piece slots (PIECE, PI, PA0, PA1) for an integration piece [t0, t1] of a
    record that lies within one sample interval or after the record's end (pieces restart
    at every sample), so that piece_acceleration reads it without the samples."""
    n = acc.size
    tm = 0.5 * (t0 + t1)
    if tm > mp[END] or n < 2:
        mp[PIECE] = 0.0
        mp[PA0] = ground_acceleration(mp[END], mp, acc)  # the value at the end itself
        mp[PIECE] = 2.0
    else:
        i = min(int(tm / mp[DT]), n - 2)
        mp[PIECE] = 1.0
        mp[PI] = i
        mp[PA0] = acc[i]
        mp[PA1] = acc[i + 1]


# --- equations of motion -----------------------------------------------------------------

def translation_acceleration(sp, u, u_dot, xg):
    """ü in pure translation, M ü + c u̇ + k u = −M ẍg (fixed base: 0)."""
    if sp[FIXED] != 0.0:
        return 0.0
    return -xg - (sp[C_DAMP] * u_dot + sp[K] * u) * sp[INV_M]


def rocking_accelerations(sp, s, theta, theta_dot, u, u_dot, xg):
    """(ü, θ̈, L1) in rocking about corner s = ±1 (model.md's 2-DOF equations),
    L1 = h cosθ + s b sinθ; fixed base: ü = 0 and θ̈ = −p²[sin(sα − θ) + (ẍg/g) cos(sα − θ)]."""
    return rocking_accelerations_with(sp, s, theta, theta_dot, u, u_dot, 0.0, xg)


def rocking_accelerations_with(sp, s, theta, theta_dot, u, u_dot, q, xg):
    """rocking_accelerations with a non-linear isolator's element force q (N) on the base
    besides the spring k·u and dashpot c·u̇ of sp (isolator_element_force: docs/isolators.md);
    q = 0 is the linear isolator, to the last bit (x − 0.0 is x)."""
    h, b, m, g = sp[H], edge(sp, s, B_HALF, B_NEG), sp[M_BLOCK], sp[G]
    st, ct = math.sin(theta), math.cos(theta)
    L1 = h * ct + s * b * st
    L2 = s * b * ct - h * st
    if sp[FIXED] != 0.0:
        return 0.0, (-m * L1 * xg - m * g * L2) * edge(sp, s, INV_J, INV_J_NEG), L1
    M, Jt = sp[M_TOTAL], edge(sp, s, J, J_NEG)
    f_u = -M * xg - m * L2 * theta_dot * theta_dot - sp[C_DAMP] * u_dot - sp[K] * u - q
    f_t = -m * L1 * xg - m * g * L2
    inv = 1.0 / (M * Jt - (m * L1) ** 2)
    return (Jt * f_u - m * L1 * f_t) * inv, (M * f_t - m * L1 * f_u) * inv, L1


def base_acceleration(sp, u, u_dot, xg):
    """Absolute base acceleration in pure translation, a = ü + ẍg = −(c u̇ + k u)/M
    (fixed base: ẍg), m/s²."""
    if sp[FIXED] != 0.0:
        return xg
    return -(sp[C_DAMP] * u_dot + sp[K] * u) * sp[INV_M]


def uplift_direction(sp, a):
    """+1 / −1 when an absolute base acceleration a lifts the block about O / O'
    (a < −g·tanα₊ lifts about O, a > g·tanα₋ about O'), else 0."""
    if a < -sp[THR]:
        return 1
    if a > sp[THR_NEG]:
        return -1
    return 0


def other_threshold(sp, thr):
    """The backward edge's uplift threshold (m/s²) for the forward edge's `thr`, raised alike
    (GRAZE_MARGIN, a rest scale): thr itself for the rectangle (to the bit), thr·tanα₋/tanα₊
    for a statue of two edges."""
    if sp[THR_NEG] == sp[THR]:
        return thr
    return thr * sp[THR_NEG] / sp[THR]


#: A block whose rocking phase ended while its base acceleration only grazed g·tanα
#: re-lifts when |a| exceeds g·tanα·(1 + GRAZE_MARGIN): far above rounding, far below physics.
GRAZE_MARGIN = 1e-8


def relift(sp, u, u_dot, xg):
    """The corner a block at rest at θ = 0 (rocking just ceased) lifts about at once, or 0.
    It lifts only when θ̈ points clearly away from the base (s·θ̈ above rounding): a base
    acceleration that only grazes g·tanα gives θ̈ ≈ 0 there, and lifting would start a
    rocking phase of zero length, landing and lifting again at the same instant without
    end (issue 9, defect 1). Such a block stays down until |a| rises clearly past."""
    s = uplift_direction(sp, base_acceleration(sp, u, u_dot, xg))
    if s == 0:
        return 0
    thdd = rocking_accelerations(sp, float(s), 0.0, 0.0, u, u_dot, xg)[1]
    return s if lifts_clearly(sp, s, thdd) else 0


def lifts_clearly(sp, s, thdd):
    """Whether θ̈ at θ = 0 points clearly away from the base about corner s (relift's rule)."""
    return s * thdd > 1e-10 * sp[THR] / sp[H]


def impact_function_order(sp, s, u, u_dot, theta_dot, xg):
    """(k, limit) for a rocking piece that starts at θ = 0: θ's first non-zero derivative
    there is of order k, and s·θ/(t − t0)^k tends to `limit`. The impact event divides by
    (t − t0)^k so that the trivial root at the piece's start is never found."""
    if theta_dot != 0.0:
        return 1, s * theta_dot
    return lift_order(sp, s, rocking_accelerations(sp, s, 0.0, 0.0, u, u_dot, xg)[1])


def hidden_crossing(direction, g_start, g_cut):
    """Whether an event function of `direction` (+1 rising through 0, −1 falling, 0 either)
    crossed 0 between a step's start (g_start) and the point where another event cut the piece
    inside the step (g_cut), though its sign at the step's end hid it (issue 39). Events fire by
    their signs at step ends (solve_ivp's find_active_events), and after the cut the step ran on
    a branch that never happened: on a non-linear isolator, past a landing, in the rocking
    equations of the corner that had landed, which carried a cone's ball back over the vertex it
    had crossed. Strict signs: a function at zero at either end is the event located there."""
    if direction >= 0 and g_start < 0.0 < g_cut:
        return True
    return direction <= 0 and g_start > 0.0 > g_cut


def lift_order(sp, s, thdd):
    """impact_function_order of a piece starting at θ = 0 with θ̇ = 0, from θ̈ there."""
    if s * thdd > 1e-9 * sp[THR]:
        return 2, 0.5 * s * thdd
    return 3, 1e-300  # at an uplift found as an event θ̈ is ~0 and θ grows as (t − t0)³


# --- non-linear isolators (docs/isolators.md) ---------------------------------------------
#
# Every isolator is a spring k·u and a dashpot c·u̇ (sp's K and C_DAMP) in parallel with an
# element of force q: none for the linear isolator (q = 0); for the bilinear bearing an
# elastic–perfectly-plastic spring, a spring k_e in series with a slider of slip force F_s
# (q = k_e·(u − u_p), u_p the slider's position, |q| ≤ F_s = k_e·u_y); for the friction
# pendulum a rigid slider (k_e = ∞): the base itself sticks, or slips with q = ±μ_f·M·g.
# `phase` is 0 while the slider sticks (the bilinear bearing elastic, the pendulum's base
# at rest on the ground) and ±1 while it slips that way (u̇_p = u̇, q = ±F_s); the slip work
# q·u̇_p = F_s·|u̇| is the hysteretic or friction loss. Phases change at events: a stuck
# slider slips when |q| (its demand, for the pendulum) reaches F_s; a slipping one sticks
# when u̇ crosses 0, and the pendulum's slips on the other way at once if its demand there
# exceeds F_s.

#
# Three more kinds share the rigid slider of the pendulum (the base pinned while its phase
# is 0) and add one piecewise-constant part, told apart by |phase| 1 or 2 while slipping σ
# (σ = sgn phase), so that every kind's state is (phase, u_p) and two event slots suffice:
# - ball in cone: the restoring force F_c·sgn(u) (I_FCONE), constant within a piece: |phase| 1
#   while the ball slips outward (sgn u = σ, or from u = 0), 2 while it returns towards the
#   vertex (sgn u = −σ); returning, it reaches u = 0 (an event) and goes on outward. At the
#   vertex itself the cone holds up to F_c more (rigid_demand). Rolling resistance = F_s.
# - ball in bowl: the friction pendulum itself (ISO_FRICTION, radius R_eff, μ_f = μ_r).
# - double concave pendulum, surfaces ordered by friction (lo, hi): the rigid slider μ_lo·W,
#   the parallel spring W/(R_lo + R_hi) and a Jenkins element of k_e = W·R_hi/(R_lo·(R_lo + R_hi)),
#   u_y = (μ_hi − μ_lo)·R_lo (I_UY): |phase| 1 while only the surface lo slides (the element
#   elastic, regime I), 2 while both slide (the element yielded that way, regime II). That
#   these are the two series surfaces is docs/isolators.md's derivation (u_p = u2·(R1+R2)/R_hi).

(I_KIND, I_KEL, I_FSLIP, I_FMAX, I_RATE, I_UY, I_FCONE, N_IP) = range(8)
ISO_LINEAR, ISO_BILINEAR, ISO_FRICTION, ISO_CONE, ISO_DOUBLE = 0, 1, 2, 3, 4
ISO_KIND = {"linear": ISO_LINEAR, "bilinear": ISO_BILINEAR, "friction-pendulum": ISO_FRICTION,
            "ball-in-bowl": ISO_FRICTION, "ball-in-cone": ISO_CONE, "double-friction-pendulum": ISO_DOUBLE}


def isolator_params(system, rest_velocity: float):
    """(sp, ip): system_params with K the isolator's parallel spring (the bilinear bearing's
    post-yield r·k0, the pendulum's M·g/R_fp, the double pendulum's W/(R1 + R2), the cone's 0)
    and the element's parameters ip (I_KIND, I_KEL: k_e in N/m, I_FSLIP: F_s in N, the slip
    force at rest; I_FMAX, I_RATE: a pendulum's velocity-dependent friction, slip_force;
    I_UY: the Jenkins element's u_y, m; I_FCONE: the cone's restoring force F_c, N)."""
    sp = system_params(system, rest_velocity)
    ip = np.zeros(N_IP)
    iso = None if system.fixed_base else system.isolator
    if iso is None:
        return sp, ip
    if iso.kind == "ball-in-bowl":  # the friction pendulum's equations, run as one
        iso = iso.as_pendulum
    ip[I_KIND] = ISO_KIND[iso.kind]
    W = system.total_mass * system.gravity
    if ip[I_KIND] == ISO_BILINEAR:
        sp[K] = iso.post_yield_ratio * iso.stiffness
        ip[I_KEL] = (1.0 - iso.post_yield_ratio) * iso.stiffness
        ip[I_FSLIP] = ip[I_KEL] * iso.yield_displacement
        ip[I_UY] = iso.yield_displacement
    elif ip[I_KIND] == ISO_CONE:
        sp[K] = 0.0
        ip[I_FSLIP] = iso.rolling_resistance * W
        ip[I_FCONE] = iso.slope * W
    elif ip[I_KIND] == ISO_DOUBLE:  # sp[K] = W/(R1 + R2), System.stiffness
        r_lo, mu_lo, r_hi, mu_hi = iso.series
        ip[I_FSLIP] = mu_lo * system.total_mass * system.gravity  # as the pendulum's, to the bit
        if mu_hi > mu_lo:  # equal frictions: no element, one pendulum of R1 + R2
            ip[I_KEL] = W * r_hi / (r_lo * (r_lo + r_hi))
            ip[I_UY] = (mu_hi - mu_lo) * r_lo
    else:  # the pendulum's normal force is M·g in both modes (docs/isolators.md)
        ip[I_FSLIP] = iso.friction_coefficient * system.total_mass * system.gravity
        if iso.friction_rate > 0.0:
            ip[I_FMAX] = iso.friction_max * system.total_mass * system.gravity
            ip[I_RATE] = iso.friction_rate
    return sp, ip


def rigid_slider(ip):
    """Whether the isolator's slider is rigid (the base itself sticks): every kind but the
    linear isolator and the bilinear bearing."""
    return ip[I_KIND] >= ISO_FRICTION


def base_pinned(ip, phase):
    """Whether the base is stuck to the ground: a rigid slider that sticks."""
    return ip[I_KIND] >= ISO_FRICTION and phase == 0


def slip_force(ip, u_dot):
    """The slider's force (N) while it slips at u̇: F_s, or with a velocity-dependent friction
    (I_RATE a > 0) F_max − (F_max − F_s)·exp(−a|u̇|), μ_f(v) = μ_max − (μ_max − μ_min)·exp(−a|v|)
    (F_s = μ_min·M·g, what holds a pinned slider)."""
    if ip[I_RATE] == 0.0:
        return ip[I_FSLIP]
    return ip[I_FMAX] - (ip[I_FMAX] - ip[I_FSLIP]) * math.exp(-ip[I_RATE] * abs(u_dot))


def isolator_element_force(ip, phase, u, u_dot, u_p):
    """q (N): the element's force on the base in a slipping or elastic phase (0 for the
    linear isolator; a stuck pendulum's is a constraint force, stick_demand)."""
    if phase != 0:
        kind = ip[I_KIND]
        if kind == ISO_CONE:  # rolling resistance, and the cone's force on the side sgn u
            sigma = 1.0 if phase > 0 else -1.0
            return sigma * ip[I_FSLIP] + (sigma if abs(phase) == 1 else -sigma) * ip[I_FCONE]
        if kind == ISO_DOUBLE:  # regime I: the element elastic; II: yielded, k_e·u_y more
            sigma = 1.0 if phase > 0 else -1.0
            if abs(phase) == 2:
                return sigma * (ip[I_FSLIP] + ip[I_KEL] * ip[I_UY])
            return sigma * ip[I_FSLIP] + ip[I_KEL] * (u - u_p)
        return phase * slip_force(ip, u_dot)
    if ip[I_KIND] == ISO_BILINEAR:
        return ip[I_KEL] * (u - u_p)
    return 0.0


def isolator_translation_acceleration(sp, ip, phase, u, u_dot, u_p, xg):
    """ü in pure translation, M ü + c u̇ + k u + q = −M ẍg (0 while the base is pinned)."""
    if base_pinned(ip, phase):
        return 0.0
    return -xg - (sp[C_DAMP] * u_dot + sp[K] * u + isolator_element_force(ip, phase, u, u_dot, u_p)) * sp[INV_M]


def isolator_rocking_accelerations(sp, ip, phase, s, theta, theta_dot, u, u_dot, u_p, xg):
    """(ü, θ̈, L1) rocking about corner s on the isolator: the 2-DOF equations with q, or,
    while the base is pinned, the block rocking on the moving ground (ü = 0)."""
    if base_pinned(ip, phase):
        return pinned_rocking_accelerations(sp, s, theta, xg)
    return rocking_accelerations_with(sp, s, theta, theta_dot, u, u_dot,
                                      isolator_element_force(ip, phase, u, u_dot, u_p), xg)


def pinned_rocking_accelerations(sp, s, theta, xg):
    """(0, θ̈, L1) of a block rocking about corner s on a base that moves with the ground."""
    h, b, m = sp[H], edge(sp, s, B_HALF, B_NEG), sp[M_BLOCK]
    st, ct = math.sin(theta), math.cos(theta)
    L1 = h * ct + s * b * st
    L2 = s * b * ct - h * st
    return 0.0, (-m * L1 * xg - m * sp[G] * L2) * edge(sp, s, INV_J, INV_J_NEG), L1


def isolator_base_acceleration(sp, ip, phase, u, u_dot, u_p, xg):
    """Absolute base acceleration in pure translation, a = ü + ẍg = −(c u̇ + k u + q)/M
    (ẍg while the base is pinned), m/s²: the uplift condition reads it."""
    if base_pinned(ip, phase):
        return xg
    return -(sp[C_DAMP] * u_dot + sp[K] * u + isolator_element_force(ip, phase, u, u_dot, u_p)) * sp[INV_M]


def stick_demand(sp, mode, theta, theta_dot, u, xg):
    """The force (N) a pinned pendulum's slider must exert on the base to hold it (u̇ = ü = 0):
    translation −M ẍg − k u; rocking about corner `mode` also −m L1 θ̈ − m L2 θ̇², θ̈ that of
    the block on the moving ground. It sticks while |demand| ≤ F_s; past it, it slips its way."""
    f = -sp[M_TOTAL] * xg - sp[K] * u
    if mode != 0:
        s = float(mode)
        thdd = pinned_rocking_accelerations(sp, s, theta, xg)[1]
        b = edge(sp, s, B_HALF, B_NEG)
        L2 = s * b * math.cos(theta) - sp[H] * math.sin(theta)
        L1 = sp[H] * math.cos(theta) + s * b * math.sin(theta)
        f = f - sp[M_BLOCK] * (L1 * thdd + L2 * theta_dot * theta_dot)
    return f


def rigid_demand(sp, ip, mode, theta, theta_dot, u, u_p, xg):
    """The force (N) the rigid slider itself must exert to hold a pinned base: stick_demand
    less what the isolator's other parts hold (element_hold)."""
    return element_hold(ip, stick_demand(sp, mode, theta, theta_dot, u, xg), u, u_p)


def element_hold(ip, f, u, u_p):
    """What is left for the rigid slider of a force f (N) needed to hold a pinned base, once
    the isolator's other parts hold their share: the cone's F_c·sgn(u) (at the vertex u = 0,
    anything within ±F_c: the demand's excess over F_c), the double pendulum's elastic
    element k_e·(u − u_p). The pendulum's is f itself."""
    kind = ip[I_KIND]
    if kind == ISO_CONE:
        if u > 0.0:
            return f - ip[I_FCONE]
        if u < 0.0:
            return f + ip[I_FCONE]
        if f > ip[I_FCONE]:
            return f - ip[I_FCONE]
        if f < -ip[I_FCONE]:
            return f + ip[I_FCONE]
        return 0.0
    if kind == ISO_DOUBLE:
        return f - ip[I_KEL] * (u - u_p)
    return f


def slip_phase(ip, sigma, u, u_p):
    """The phase of a rigid slider that starts to slip the way sigma (±1) at u (u_p: the
    element's slider): ±1, or ±2 for a cone's ball returning towards its vertex (sgn u = −σ)
    and for a double pendulum whose element is already at its yield that way."""
    kind = ip[I_KIND]
    if kind == ISO_CONE and sigma * u < 0.0:
        return 2.0 * sigma
    if kind == ISO_DOUBLE and ip[I_UY] > 0.0 and sigma * (u - u_p) >= ip[I_UY]:
        return 2.0 * sigma
    return sigma


def slider_position(ip, phase, u, u_p):
    """u_p as it is now: a yielded element's slider moves with the base at u − σ·u_y (the
    bilinear bearing's plastic phase, the double pendulum's regime II); else u_p."""
    kind = ip[I_KIND]
    if phase != 0 and (kind == ISO_BILINEAR or (kind == ISO_DOUBLE and abs(phase) == 2)):
        return u - (1.0 if phase > 0 else -1.0) * ip[I_UY]
    return u_p


def vertex_function(sigma, u, at_start):
    """The event function of a returning cone's ball (|phase| 2, rolling the way σ) reaching
    its vertex: σ·u, rising through 0. At the piece's start (at_start) it is at most 0: a ball
    found there at or past its vertex crossed it at the instant of the event that ended the last
    piece (a landing within the rounding of time, issue 39), and reaches it at once, instead of
    rolling on beyond it with a returning ball's force, away from the vertex, without end."""
    return min(sigma * u, 0.0) if at_start else sigma * u


def vertex_rest_speed(sp, ip):
    """|u̇| below which a cone's ball that reaches its vertex rests there (m/s): the speed that
    would climb VERTEX_REST_HEIGHT against g·(tanφ + μ_r). Below it the ball's returns form a
    Zeno sequence (each amplitude (tanφ − μ_r)/(tanφ + μ_r) of the last, its legs ∝ √amplitude,
    converging in finite time); the kinetic energy left is the rolling resistance's (S)."""
    return math.sqrt(2.0 * (ip[I_FCONE] + ip[I_FSLIP]) * sp[INV_M] * VERTEX_REST_HEIGHT)


#: climb (m) below which a cone's ball arriving at its vertex rests: numerical, like the
#: rocking's rest floor; far below any stroke (0.1 µm), far above the positions DOP853 resolves.
#: The returns below it change no state by more than their climb; at 1 nm instead the tests'
#: free decay held 53 events, not 39; their times are ill-conditioned at any floor (docs/isolators.md)
VERTEX_REST_HEIGHT = 1e-7


#: A pinned pendulum slips once its demand exceeds F_s by STICK_BAND·M·g: far below physics
#: (a delay of 1e-12·g/|dD/dt·1/M| s), far above rounding, so that a slip always starts with
#: an acceleration of its own sign and never flips back at once (a zero-length phase).
STICK_BAND = 1e-12


def stick_limit(sp, ip):
    """The demand (N) up to which a pinned pendulum's slider holds: F_s + STICK_BAND·M·g."""
    return ip[I_FSLIP] + STICK_BAND * sp[M_TOTAL] * sp[G]


def slip_power(ip, phase, u_dot):
    """The slip work's rate (W, ≥ 0): F_s·|u̇| (q·u̇_p; the cone's force is conservative, the
    double pendulum's yielded element adds k_e·u_y·|u̇|): the hysteretic or friction loss."""
    if phase == 0:
        return 0.0
    # σ·F·u̇, not F·|u̇|: smooth through the stop (u̇ = 0) that a step may straddle before the
    # event ends the piece; |u̇| put a kink there that DOP853 integrated 1e-9 of the energy off
    kind = ip[I_KIND]
    sigma = 1.0 if phase > 0 else -1.0
    if kind == ISO_CONE or (kind == ISO_DOUBLE and abs(phase) == 1):
        return sigma * ip[I_FSLIP] * u_dot
    if kind == ISO_DOUBLE:
        return sigma * (ip[I_FSLIP] + ip[I_KEL] * ip[I_UY]) * u_dot
    return phase * slip_force(ip, u_dot) * u_dot


def element_energy(ip, u, u_p):
    """Energy held in the element (J): its spring's ½ k_e (u − u_p)² (0 for the pendulum), and
    the cone's F_c·|u| (the ball's height above the vertex times M·g)."""
    e = 0.5 * ip[I_KEL] * (u - u_p) ** 2
    if ip[I_KIND] == ISO_CONE:
        return e + ip[I_FCONE] * np.abs(u)
    return e


def balance_energy(sp, ip, s, u, u_dot, theta, theta_dot, u_p):
    """E (J) of the energy balance on an isolator: kinetic and potential energy with the
    element's (EnergyLog.total on a non-linear isolator's run)."""
    return kinetic_energy(sp, s, u_dot, theta, theta_dot) + potential_energy(sp, s, u, theta) + element_energy(ip, u, u_p)


# --- impact at θ = 0 ----------------------------------------------------------------------

def landing_side(theta_dot_pre):
    """The corner a block rocked about as it lands with θ̇⁻ (θ returns to 0 from its side:
    θ̇⁻ < 0 on corner +1)."""
    return -1.0 if theta_dot_pre > 0.0 else 1.0


def impact_continues(sp, theta_dot_pre):
    """Rocking continues about the other corner unless |θ̇⁻| is below the rest floor
    (the Zeno tail) or the block is below the no-bounce slenderness (β ≤ 0)."""
    return abs(theta_dot_pre) >= sp[REST] and edge(sp, landing_side(theta_dot_pre), BETA, BETA_NEG) > 0.0


def impact_map(sp, theta_dot_pre, u_dot_pre, continued):
    """(θ̇⁺, u̇⁺): θ̇⁺ = β θ̇⁻, u̇⁺ = u̇⁻ + β₂ θ̇⁻ when rocking continues; θ̇⁺ = 0,
    u̇⁺ = u̇⁻ + β₃ θ̇⁻ when it ceases (fixed base: u̇ stays 0). β and β₂ of the edge it lands
    from (landing_side)."""
    if continued:
        s = landing_side(theta_dot_pre)
        thd = edge(sp, s, BETA, BETA_NEG) * theta_dot_pre
        ud = u_dot_pre + edge(sp, s, BETA2, BETA2_NEG) * theta_dot_pre
    else:
        thd, ud = 0.0, u_dot_pre + sp[BETA3] * theta_dot_pre
    if sp[FIXED] != 0.0:
        ud = 0.0
    return thd, ud


def impact_energy_loss(sp, u_dot_pre, theta_dot_pre, u_dot_post, theta_dot_post):
    """Kinetic energy lost in an impact at θ = 0 (J)."""
    s = landing_side(theta_dot_pre)
    return (kinetic_energy(sp, s, u_dot_pre, 0.0, theta_dot_pre)
            - kinetic_energy(sp, -s, u_dot_post, 0.0, theta_dot_post))


# --- energy and forces (scalars or arrays) ---------------------------------------------------

def kinetic_energy(sp, s, u_dot, theta, theta_dot):
    """T = ½ m_b u̇² + ½ m [(u̇ + ẋ)² + ż²] + ½ I θ̇² (J), velocities relative to the ground."""
    h, b, m = sp[H], edge(sp, s, B_HALF, B_NEG), sp[M_BLOCK]
    ct, st = np.cos(theta), np.sin(theta)
    xd = theta_dot * (h * ct + s * b * st)
    zd = theta_dot * (s * b * ct - h * st)
    return (0.5 * sp[M_BASE] * u_dot * u_dot + 0.5 * m * ((u_dot + xd) ** 2 + zd * zd)
            + 0.5 * sp[INERTIA] * theta_dot * theta_dot)


def potential_energy(sp, s, u, theta):
    """V = ½ k u² + m g (s b sinθ + h cosθ − h) (J); zero at rest."""
    h, b = sp[H], edge(sp, s, B_HALF, B_NEG)
    return 0.5 * sp[K] * u * u + sp[M_BLOCK] * sp[G] * (s * b * np.sin(theta) + h * np.cos(theta) - h)


def pivot_force_ratio(sp, mode, theta, theta_dot, u, u_dot, xg):
    """|F_x / F_z| of the base's force on the block at its pivot (in translation: the
    contact as a whole), the friction coefficient the no-sliding assumption needs.
    Newton on the block's centre of mass: F_x = m (ẍg + ü + θ̈ L1 + θ̇² L2),
    F_z = m (g + θ̈ L2 − θ̇² L1); F_z ≤ 0 (the block would leave the base) is infinite."""
    if mode == 0:
        return abs(base_acceleration(sp, u, u_dot, xg)) / sp[G]
    s = float(mode)
    udd, thdd, L1 = rocking_accelerations(sp, s, theta, theta_dot, u, u_dot, xg)
    return rocking_pivot_force_ratio(sp, s, theta, theta_dot, udd, thdd, xg)


def rocking_pivot_force_ratio(sp, s, theta, theta_dot, udd, thdd, xg):
    """pivot_force_ratio while rocking about corner s, given the accelerations ü and θ̈
    there (rocking_accelerations'); an integrator has them from its last stage."""
    st, ct = math.sin(theta), math.cos(theta)
    b = edge(sp, s, B_HALF, B_NEG)
    L1 = sp[H] * ct + s * b * st
    L2 = s * b * ct - sp[H] * st
    fx = xg + udd + thdd * L1 + theta_dot * theta_dot * L2
    fz = sp[G] + thdd * L2 - theta_dot * theta_dot * L1
    if fz <= 0.0:
        return math.inf
    return abs(fx) / fz


# --- overturning ------------------------------------------------------------------------

def overturn_code(rule_alpha, theta_end, alpha, reached_side):
    """model.md's verdict from how a run ended: 0 survived, 1 |θ| reached α (rule
    "alpha"), 2 |θ| reached π/2, 3 the run ended with |θ| > α. rule_alpha: the
    conservative rule, under which reaching α is enough."""
    if reached_side:
        return 2
    if abs(theta_end) > alpha:
        return 1 if rule_alpha else 3
    return 0


# --- first uplift on a fixed base, from the motion itself ------------------------------

def _bisect_ricker(r, lo, hi):
    """x in [lo, hi] with (1 − 2x)e^(−x) = r, f monotone on the bracket."""
    flo = (1.0 - 2.0 * lo) * math.exp(-lo) - r
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        fm = (1.0 - 2.0 * mid) * math.exp(-mid) - r
        if (fm < 0.0) == (flo < 0.0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _pulse_crossings(kind, omega, freq, r, out):
    """Pulse times (before any shift), within one period for sine/cosine or over the
    whole Ricker wavelet, where |pulse| = r·|amp| (0 < r < 1); returns how many."""
    n = 0
    if kind == SINE or kind == COSINE:
        a = math.asin(r)
        phases = (a, math.pi - a, math.pi + a, 2.0 * math.pi - a)
        for k in range(4):
            ph = phases[k] - (0.5 * math.pi if kind == COSINE else 0.0)
            if ph < 0.0:
                ph += 2.0 * math.pi
            out[n] = ph / omega
            n += 1
        return n
    # Ricker, x = (πFτ)²: f(x) = (1 − 2x)e^(−x) falls from 1 to −2e^(−3/2) at x = 3/2, then rises to 0
    scale = 1.0 / (math.pi * freq)
    xs = np.zeros(3)
    m = 0
    xs[m] = _bisect_ricker(r, 0.0, 0.5)
    m += 1
    fmin = -2.0 * math.exp(-1.5)
    if -r > fmin:
        xs[m] = _bisect_ricker(-r, 0.5, 1.5)
        m += 1
        hi = 1.5
        while (1.0 - 2.0 * hi) * math.exp(-hi) < -r:
            hi *= 2.0
        xs[m] = _bisect_ricker(-r, 1.5, hi)
        m += 1
    for k in range(m):
        tau = math.sqrt(xs[k]) * scale
        out[n] = 1.0 / freq - tau
        out[n + 1] = 1.0 / freq + tau
        n += 2
    return n


def first_uplift(sp, mp, acc, t0, t1, margin):
    """(t, s): the first time in [t0, t1] at which a fixed base's ground acceleration
    exceeds g·tanα in magnitude, and the corner it lifts about; (t1, 0) if none.
    Found from the motion itself (issue 9, defect 2): a closed-form pulse's crossings
    in closed form (Ricker's by bisection to rounding), a record's within every sample
    interval (the record is linear there), so no excursion is missed at any frequency.
    Already above the threshold at t0 lifts at t0. margin: the threshold is
    g·tanα·(1 + margin) (GRAZE_MARGIN after a grazing uplift stayed down)."""
    thr = sp[THR] * (1.0 + margin)
    thr_neg = other_threshold(sp, thr)  # a statue of two edges: each its own (thr for the rectangle)
    xg0 = ground_acceleration(t0, mp, acc)
    if xg0 < -thr:
        return t0, 1
    if xg0 > thr_neg:
        return t0, -1
    kind = int(mp[KIND])
    if kind == SAMPLED:
        n = acc.size
        if n < 2:
            return t1, 0
        dt = mp[DT]
        i = max(int(t0 / dt), 0)
        while i < n - 1:
            ta = i * dt
            if ta > t1:
                break
            a0, a1 = acc[i], acc[i + 1]
            for sgn in (1.0, -1.0):  # a > thr₋ lifts about O' (s = −1), a < −thr about O
                level = thr_neg if sgn > 0.0 else thr
                c0, c1 = sgn * a0 - level, sgn * a1 - level
                if c1 > 0.0 and c0 <= 0.0 or (c0 > 0.0 and c1 > 0.0):
                    f = 0.0 if c0 > 0.0 else c0 / (c0 - c1)
                    tc = ta + f * dt
                    if tc < t0:
                        tc = t0
                    if tc <= t1 and (tc > t0 or sgn * ground_acceleration(tc, mp, acc) > level):
                        return tc, (-1 if sgn > 0.0 else 1)
            i += 1
        return t1, 0
    amp = abs(mp[SCALE] * mp[AMP])
    shift, pend, omega, freq = mp[SHIFT], mp[PEND], mp[OMEGA], mp[FREQ]
    period = 2.0 * math.pi / omega if kind != RICKER else 0.0
    # candidate crossings of each edge's level (the rectangle's one level serves both ways): the
    # base ones plus whole periods, from the period holding t0; a rising crossing of |a| lifts the
    # block about the edge whose threshold the pulse passes just after it
    tt0 = t0 + shift
    k0 = math.floor(tt0 / period) if period > 0.0 else 0.0
    dtt = 1e-9 * (period if period > 0.0 else 1.0 / freq)
    base = np.zeros(6)
    best, side = math.inf, 0
    for k in range(1 if thr_neg == thr else 2):
        level = thr if k == 0 else thr_neg
        if amp <= level:
            continue
        nb = _pulse_crossings(kind, omega, freq, level / amp, base)
        for rep in range(3 if period > 0.0 else 1):
            for q in range(nb):
                tt = base[q] + (k0 + rep) * period
                if tt < max(tt0, 0.0) or tt > pend or tt >= best:
                    continue
                after = mp[SCALE] * pulse_acceleration(kind, mp[AMP], omega, freq, min(tt + dtt, pend))
                lifts = 1 if after < -thr else (-1 if after > thr_neg else 0)
                if lifts != 0:
                    best, side = tt, lifts
    if best == math.inf or best - shift > t1:
        return t1, 0
    return max(best - shift, t0), side


# --- pure translation of an isolated base, in closed form ----------------------------------
#
# In pure translation an isolated base is a linear oscillator, ü + 2ζω u̇ + ω² u = −ẍg, and a
# record is linear within each sample interval, ẍg = a0 + a1·τ (τ from the interval's start
# or any later instant in it). There the motion is exact in closed form (Nigam & Jennings
# 1969): u = z_u + P0 + P1·τ with the particular P1 = −a1/ω², P0 = −(a0 + 2ζω P1)/ω² and
# z = (z_u, z_v = u̇ − P1) a free vibration, z' = A z, A = [[0, 1], [−ω², −2ζω]]. The base's
# absolute acceleration is a = ẍg + ż_v = a0 + a1 τ + (A z)_v, so uplift (|a| > g·tanα) is
# a root of a damped sinusoid plus a line, which `translation_uplift` finds to rounding
# from the closed form itself: no crossing can hide between integrator steps.
#
# Bounds used to skip root searches: along a free vibration the energy norm
# ‖z‖ = √(z_v² + ω² z_u²) never grows (d/dτ of ½‖z‖² is −2ζω z_v² ≤ 0), and Aᵏz is a free
# vibration too, so |(Aᵏz(τ))_v| ≤ ‖Aᵏz(0)‖ over the whole interval.

def oscillator_constants(sp):
    """(ζω, ω², ω² − (ζω)²) of an isolated base in pure translation: ζω = c/(2M), ω² = k/M;
    the last is the damped frequency squared (negative when over-damped)."""
    a = 0.5 * sp[C_DAMP] * sp[INV_M]
    w2 = sp[K] * sp[INV_M]
    return a, w2, w2 - a * a


def free_vibration_change(sp, zu, zv, tau):
    """(Δz_u, Δz_v): how much the free oscillator z' = A z moves in τ ≥ 0 from (zu, zv).
    z(τ) = e^(−ζωτ) [C·z + S·(A + ζω I) z], C = cos qτ, S = sin(qτ)/q with q² = ω² − (ζω)²
    (cosh and sinh when over-damped, 1 and τ when critically damped); the change is formed
    as (e^(−ζωτ)C − 1)·z + e^(−ζωτ)S·(A + ζω I) z with expm1 and half angles, so that it is
    exact to rounding relative to itself however short τ is."""
    a, w2, q2 = oscillator_constants(sp)
    em1 = math.expm1(-a * tau)
    if q2 > 0.0:
        q = math.sqrt(q2)
        sh = math.sin(0.5 * q * tau)
        ch = math.cos(0.5 * q * tau)
        cm1 = -2.0 * sh * sh
        s = 2.0 * sh * ch / q
    elif q2 < 0.0:
        q = math.sqrt(-q2)
        sh = math.sinh(0.5 * q * tau)
        ch = math.cosh(0.5 * q * tau)
        cm1 = 2.0 * sh * sh
        s = 2.0 * sh * ch / q
    else:
        cm1 = 0.0
        s = tau
    ecm1 = em1 + cm1 + em1 * cm1  # e^(−ζωτ)·C − 1
    es = (1.0 + em1) * s
    return ecm1 * zu + es * (a * zu + zv), ecm1 * zv - es * (w2 * zu + a * zv)


def free_vibration(sp, zu, zv, tau):
    """(z_u, z_v) of the free oscillator z' = A z, A = [[0, 1], [−ω², −2ζω]], after τ ≥ 0
    from (zu, zv) (free_vibration_change)."""
    du, dv = free_vibration_change(sp, zu, zv, tau)
    return zu + du, zv + dv


def translation_start(sp, u0, v0, a0, a1):
    """(z_u, z_v, P0, P1) at the start of a closed-form interval from (u, u̇) and ẍg = a0 + a1·τ:
    the particular solution u_p = P0 + P1·τ and the free vibration z = (u − P0, u̇ − P1)."""
    a, w2, q2 = oscillator_constants(sp)
    p1 = -a1 / w2
    p0 = -(a0 + 2.0 * a * p1) / w2
    return u0 - p0, v0 - p1, p0, p1


def translation_state(sp, zu0, zv0, p1, u0, v0, a0, a1, tau):
    """(u, u̇, ΔW, ΔD) τ seconds into a closed-form interval that starts at (u0, u̇0) with
    translation_start's z and P1: u = u0 + Δz_u + P1·τ, u̇ = u̇0 + Δz_v; ΔW = −M ∫ ẍg u̇ dτ,
    the ground's work, and ΔD = c ∫ u̇² dτ, the dashpot's loss, both in closed form
    (∫z_u = −(2ζω Δz_u + Δz_v)/ω², and c ∫z_v² = −M·Δ(½z_v² + ½ω² z_u²), the free
    vibration's energy decay)."""
    a, w2, q2 = oscillator_constants(sp)
    dzu, dzv = free_vibration_change(sp, zu0, zv0, tau)
    du = dzu + p1 * tau
    u = u0 + du
    v = v0 + dzv
    # ∫ (u − u0) dτ = ∫ (z_u − z_u0) dτ + P1 τ²/2
    int_du = -(2.0 * a * dzu + dzv) / w2 - zu0 * tau + 0.5 * p1 * tau * tau
    dW = -sp[M_TOTAL] * (a0 * du + a1 * (tau * du - int_du))
    if sp[C_DAMP] == 0.0:
        dD = 0.0
    else:
        drop = -0.5 * dzv * (2.0 * zv0 + dzv) - 0.5 * w2 * dzu * (2.0 * zu0 + dzu)
        dD = sp[M_TOTAL] * drop + sp[C_DAMP] * p1 * (2.0 * dzu + p1 * tau)
    return u, v, dW, dD


def _energy_norm(w2, zu, zv):
    return math.sqrt(zv * zv + w2 * zu * zu)


def _times_a(a, w2, zu, zv):
    """A·(z_u, z_v), A = [[0, 1], [−ω², −2ζω]] (a = ζω): the rate of the free vibration there."""
    return zv, -w2 * zu - 2.0 * a * zv


def _second_rate_norm(sp, zu, zv):
    """‖A² z‖ at the start of an interval: the energy norm never grows along a free
    vibration, so it bounds |z_v''| = |(A² z(τ))_v| over the whole interval."""
    a, w2, q2 = oscillator_constants(sp)
    a1u, a1v = _times_a(a, w2, zu, zv)
    a2u, a2v = _times_a(a, w2, a1u, a1v)
    return _energy_norm(w2, a2u, a2v)


def _oscillator_line(sp, wu, wv, sigma, c0, c1, tau):
    """g(τ) = σ·(e^(Aτ) w)_v + c0 + c1·τ and g'(τ) = σ·(A e^(Aτ) w)_v + c1."""
    a, w2, q2 = oscillator_constants(sp)
    zu, zv = free_vibration(sp, wu, wv, tau)
    return sigma * zv + c0 + c1 * tau, sigma * _times_a(a, w2, zu, zv)[1] + c1


def _newton_bracket(sp, wu, wv, sigma, c0, c1, lo, hi, glo, ghi):
    """The zero of g (see _oscillator_line) in [lo, hi], where g is monotone and changes
    sign (glo·ghi ≤ 0): Newton's method kept inside a shrinking bracket (bisection when a
    step leaves it or stalls), to the spacing of floats."""
    if glo == 0.0:
        return lo
    if ghi == 0.0:
        return hi
    rising = ghi > 0.0
    x = lo - glo * (hi - lo) / (ghi - glo)  # secant start
    if not (lo < x < hi):
        x = 0.5 * (lo + hi)
    for _ in range(100):
        g, gp = _oscillator_line(sp, wu, wv, sigma, c0, c1, x)
        if g == 0.0:
            return x
        if (g > 0.0) == rising:
            hi = x
        else:
            lo = x
        if hi - lo <= 4.0 * 2.220446049250313e-16 * max(abs(lo), abs(hi)) or hi - lo < 5e-324 * 4:
            break
        nx = x - g / gp if gp != 0.0 else 0.5 * (lo + hi)
        if not (lo < nx < hi) or abs(nx - x) > 0.5 * (hi - lo):
            nx = 0.5 * (lo + hi)
        if nx == x:
            break
        x = nx
    return x


#: Intervals `_oscillator_zeros` examines at most before it splits none further (a search
#: that separates every zero takes tens; a degenerate one would take 2^78).
ZERO_VISITS = 10_000


def _oscillator_zeros(sp, wu, wv, sigma, c0, c1, bound, h, rising, out):
    """Zeros of g(τ) = σ·(e^(Aτ) w)_v + c0 + c1·τ in [0, h], in increasing order, up to
    out.size of them (rising: only the first at which g rises through 0, counting g(0) = 0
    rising). bound ≥ sup |g''| on [0, h]. Intervals are split until g is provably of one
    sign there (its chord ± bound·w²/8) or monotone (|g'| at the middle > bound·w/2), so
    every sign change is found, however briefly g crosses. Returns how many."""
    n = 0
    lo_s = np.empty(80)
    hi_s = np.empty(80)
    glo_s = np.empty(80)
    ghi_s = np.empty(80)
    g0 = _oscillator_line(sp, wu, wv, sigma, c0, c1, 0.0)[0]
    gh = _oscillator_line(sp, wu, wv, sigma, c0, c1, h)[0]
    lo_s[0], hi_s[0], glo_s[0], ghi_s[0] = 0.0, h, g0, gh
    top = 1
    last = -1.0
    visits = 0
    while top > 0:
        top -= 1
        visits += 1
        lo, hi, glo, ghi = lo_s[top], hi_s[top], glo_s[top], ghi_s[top]
        w = hi - lo
        dev = 0.125 * bound * w * w
        if max(glo, ghi) + dev < 0.0 or min(glo, ghi) - dev > 0.0:
            continue  # no zero here
        # dev = 0: g'' ≡ 0 (bound 0, the oscillator at rest), so g is the line c0 + c1·τ with
        # one sign change at most, none if it is zero throughout; splitting a zero function
        # would find nothing at every one of 2^78 leaves (the hang of a block at rest)
        mid = lo + 0.5 * w
        gm, gpm = glo, 0.0
        if dev != 0.0:
            gm, gpm = _oscillator_line(sp, wu, wv, sigma, c0, c1, mid)
        # past ZERO_VISITS intervals no interval is split again: near a double zero (a base at
        # rest under a record that starts at 0: u̇ = ü = 0 at τ = 0) with `bound` above |g''|,
        # neither test above decides, and both halves split down to depth 78 (2^78 leaves:
        # the compiled kernel hung on a stress case)
        if (dev == 0.0 or abs(gpm) > 0.5 * bound * w or top >= 78 or mid <= lo or mid >= hi
                or visits > ZERO_VISITS):
            # g is monotone here (or the interval cannot be split further)
            if glo * ghi > 0.0 or (glo == 0.0 and ghi == 0.0):
                continue
            if rising and not (ghi > glo):
                continue
            x = _newton_bracket(sp, wu, wv, sigma, c0, c1, lo, hi, glo, ghi)
            if x <= last:
                continue  # found already, at the end of the interval before
            out[n] = x
            n += 1
            last = x
            if rising or n == out.size:
                return n
            continue
        # split: the left half is examined first
        lo_s[top], hi_s[top], glo_s[top], ghi_s[top] = mid, hi, gm, ghi
        lo_s[top + 1], hi_s[top + 1], glo_s[top + 1], ghi_s[top + 1] = lo, mid, glo, gm
        top += 2
    return n


def translation_uplift(sp, zu0, zv0, a0, a1, h, thr, a_end):
    """(τ, s): the first τ in [0, h] at which the base's absolute acceleration a(τ) =
    a0 + a1·τ + (A z(τ))_v reaches −thr (s = 1, lifting about O) or +thr₋ (s = −1, about O';
    other_threshold: thr for the rectangle)
    from inside the band, in the closed form of a translation interval; (h, 0) if none.
    Already beyond the threshold at τ = 0 lifts at 0. a_end: a(h), as the caller has it
    from the end state (base_acceleration); it only lets the search be skipped when both
    ends lie clearly inside the band, by more than a's largest bow over the interval."""
    a, w2, q2 = oscillator_constants(sp)
    wu, wv = _times_a(a, w2, zu0, zv0)  # w = A z
    bound = _second_rate_norm(sp, wu, wv)  # ≥ |a''| on the interval
    bow = 0.125 * bound * h * h
    a_start = a0 + wv
    best, side = h, 0
    for k in range(2):
        sigma = -1.0 if k == 0 else 1.0  # k = 0: a < −thr lifts about O (s = 1)
        level = thr if k == 0 else other_threshold(sp, thr)  # a > thr₋ lifts about O'
        g0 = sigma * a_start - level
        if g0 > 0.0:
            return 0.0, (1 if k == 0 else -1)
        if max(g0, sigma * a_end - level) + bow < -1e-12 * level:
            continue  # the common case: far inside the band
        zs = np.empty(1)
        if (_oscillator_zeros(sp, wu, wv, sigma, sigma * a0 - level, sigma * a1, bound, h, True, zs)
                and zs[0] < best):
            best, side = zs[0], (1 if k == 0 else -1)
    return best, side


def translation_velocity_zeros(sp, zu0, zv0, p1, h, out):
    """Times τ in (0, h) at which u̇ = z_v(τ) + P1 vanishes (the extremes of u) in a
    closed-form translation interval, in order, up to out.size; returns how many."""
    m = _oscillator_zeros(sp, zu0, zv0, 1.0, p1, 0.0, _second_rate_norm(sp, zu0, zv0), h, False, out)
    n = 0
    for i in range(m):  # the ends are stored and measured anyway
        if 0.0 < out[i] < h:
            out[n] = out[i]
            n += 1
    return n


def translation_u_bound(sp, zu0, zv0, h):
    """A bound on how far |u| can exceed the chord of its end values over a closed-form
    interval of length h: |ü| ≤ ‖A² z(0)‖/ω, so the excess is at most that·h²/8."""
    return 0.125 * h * h * _second_rate_norm(sp, zu0, zv0) / math.sqrt(sp[K] * sp[INV_M])
