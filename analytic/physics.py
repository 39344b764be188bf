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

# --- packed system parameters -------------------------------------------------------
(M_BLOCK, M_TOTAL, H, B_HALF, G, K, C_DAMP, FIXED, ALPHA, J, THR, BETA, BETA2, BETA3, REST,
 INV_M, INV_J, M_BASE, INERTIA, N_SP) = range(20)

# --- packed motion parameters -------------------------------------------------------
(KIND, DT, END, AMP, OMEGA, FREQ, PEND, SCALE, SHIFT, PIECE, PI, PA0, PA1, INV_DT, N_MP) = range(15)
# PIECE: how the current integration piece reads a record: 0 the general way,
# 1 within one sample interval (index PI, samples PA0, PA1), 2 after the last sample
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
    from .coefficients import beta, beta2, beta3
    lam, mu, h = system.slenderness, system.mu, system.h
    sp = np.zeros(N_SP)
    sp[M_BLOCK] = system.mass
    sp[M_TOTAL] = system.total_mass
    sp[H] = h
    sp[B_HALF] = system.b
    sp[G] = system.gravity
    sp[K] = 0.0 if system.fixed_base else system.stiffness
    sp[C_DAMP] = 0.0 if system.fixed_base else system.damping
    sp[FIXED] = 1.0 if system.fixed_base else 0.0
    sp[ALPHA] = system.alpha
    sp[J] = system.mass * system.R**2 + system.inertia
    sp[THR] = system.uplift_acceleration
    sp[BETA] = beta(lam, mu)
    sp[BETA2] = beta2(lam, mu, h)
    sp[BETA3] = beta3(mu, h)
    sp[REST] = rest_velocity * system.p * system.alpha
    sp[INV_M] = 1.0 / system.total_mass
    sp[INV_J] = 1.0 / sp[J]
    sp[M_BASE] = 0.0 if system.fixed_base else system.base_mass
    sp[INERTIA] = system.inertia
    return sp


def motion_params(motion):
    """(parameters, samples) of a GroundMotion: pulses in closed form, records as samples."""
    from .system import STANDARD_GRAVITY
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


def ground_acceleration(t, mp, acc):
    """ẍg(t) in m/s² (GroundMotion.at): records linearly interpolated, zero outside."""
    if int(mp[KIND]) == SAMPLED:
        piece = mp[PIECE]
        if piece == 1.0:  # a piece lies within one sample interval: no search
            f = t * mp[INV_DT] - mp[PI]
            return (1.0 - f) * mp[PA0] + f * mp[PA1]
        if t < 0.0 or t > mp[END]:
            return 0.0
        n = acc.size
        if n == 1:
            return acc[0] if t == 0.0 else 0.0
        x = t / mp[DT]
        i = min(int(x), n - 2)
        f = x - i
        return (1.0 - f) * acc[i] + f * acc[i + 1]
    tt = t + mp[SHIFT]
    if tt < 0.0 or tt > mp[PEND]:
        return 0.0
    return mp[SCALE] * pulse_acceleration(int(mp[KIND]), mp[AMP], mp[OMEGA], mp[FREQ], tt)


# --- equations of motion -----------------------------------------------------------------

def translation_acceleration(sp, u, u_dot, xg):
    """ü in pure translation, M ü + c u̇ + k u = −M ẍg (fixed base: 0)."""
    if sp[FIXED] != 0.0:
        return 0.0
    return -xg - (sp[C_DAMP] * u_dot + sp[K] * u) * sp[INV_M]


def rocking_accelerations(sp, s, theta, theta_dot, u, u_dot, xg):
    """(ü, θ̈, L1) in rocking about corner s = ±1 (model.md's 2-DOF equations),
    L1 = h cosθ + s b sinθ; fixed base: ü = 0 and θ̈ = −p²[sin(sα − θ) + (ẍg/g) cos(sα − θ)]."""
    h, b, m, g = sp[H], sp[B_HALF], sp[M_BLOCK], sp[G]
    st, ct = math.sin(theta), math.cos(theta)
    L1 = h * ct + s * b * st
    L2 = s * b * ct - h * st
    if sp[FIXED] != 0.0:
        return 0.0, (-m * L1 * xg - m * g * L2) * sp[INV_J], L1
    M, Jt = sp[M_TOTAL], sp[J]
    f_u = -M * xg - m * L2 * theta_dot * theta_dot - sp[C_DAMP] * u_dot - sp[K] * u
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
    (|a| > g·tanα; a < 0 lifts about O), else 0."""
    thr = sp[THR]
    if a < -thr:
        return 1
    if a > thr:
        return -1
    return 0


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
    return s if s * thdd > 1e-10 * sp[THR] / sp[H] else 0


def impact_function_order(sp, s, u, u_dot, theta_dot, xg):
    """(k, limit) for a rocking piece that starts at θ = 0: θ's first non-zero derivative
    there is of order k, and s·θ/(t − t0)^k tends to `limit`. The impact event divides by
    (t − t0)^k so that the trivial root at the piece's start is never found."""
    if theta_dot != 0.0:
        return 1, s * theta_dot
    thdd = rocking_accelerations(sp, s, 0.0, 0.0, u, u_dot, xg)[1]
    if s * thdd > 1e-9 * sp[THR]:
        return 2, 0.5 * s * thdd
    return 3, 1e-300  # at an uplift found as an event θ̈ is ~0 and θ grows as (t − t0)³


# --- impact at θ = 0 ----------------------------------------------------------------------

def impact_continues(sp, theta_dot_pre):
    """Rocking continues about the other corner unless |θ̇⁻| is below the rest floor
    (the Zeno tail) or the block is below the no-bounce slenderness (β ≤ 0)."""
    return abs(theta_dot_pre) >= sp[REST] and sp[BETA] > 0.0


def impact_map(sp, theta_dot_pre, u_dot_pre, continued):
    """(θ̇⁺, u̇⁺): θ̇⁺ = β θ̇⁻, u̇⁺ = u̇⁻ + β₂ θ̇⁻ when rocking continues; θ̇⁺ = 0,
    u̇⁺ = u̇⁻ + β₃ θ̇⁻ when it ceases (fixed base: u̇ stays 0)."""
    if continued:
        thd, ud = sp[BETA] * theta_dot_pre, u_dot_pre + sp[BETA2] * theta_dot_pre
    else:
        thd, ud = 0.0, u_dot_pre + sp[BETA3] * theta_dot_pre
    if sp[FIXED] != 0.0:
        ud = 0.0
    return thd, ud


def impact_energy_loss(sp, u_dot_pre, theta_dot_pre, u_dot_post, theta_dot_post):
    """Kinetic energy lost in an impact at θ = 0 (J)."""
    return (kinetic_energy(sp, 1.0, u_dot_pre, 0.0, theta_dot_pre)
            - kinetic_energy(sp, -1.0, u_dot_post, 0.0, theta_dot_post))


# --- energy and forces (scalars or arrays) ---------------------------------------------------

def kinetic_energy(sp, s, u_dot, theta, theta_dot):
    """T = ½ m_b u̇² + ½ m [(u̇ + ẋ)² + ż²] + ½ I θ̇² (J), velocities relative to the ground."""
    h, b, m = sp[H], sp[B_HALF], sp[M_BLOCK]
    ct, st = np.cos(theta), np.sin(theta)
    xd = theta_dot * (h * ct + s * b * st)
    zd = theta_dot * (s * b * ct - h * st)
    return (0.5 * sp[M_BASE] * u_dot * u_dot + 0.5 * m * ((u_dot + xd) ** 2 + zd * zd)
            + 0.5 * sp[INERTIA] * theta_dot * theta_dot)


def potential_energy(sp, s, u, theta):
    """V = ½ k u² + m g (s b sinθ + h cosθ − h) (J); zero at rest."""
    h, b = sp[H], sp[B_HALF]
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
    L2 = s * sp[B_HALF] * math.cos(theta) - sp[H] * math.sin(theta)
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
    xg0 = ground_acceleration(t0, mp, acc)
    if abs(xg0) > thr:
        return t0, (1 if xg0 < 0.0 else -1)
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
            for sgn in (1.0, -1.0):  # a > thr lifts about O' (s = −1), a < −thr about O
                c0, c1 = sgn * a0 - thr, sgn * a1 - thr
                if c1 > 0.0 and c0 <= 0.0 or (c0 > 0.0 and c1 > 0.0):
                    f = 0.0 if c0 > 0.0 else c0 / (c0 - c1)
                    tc = ta + f * dt
                    if tc < t0:
                        tc = t0
                    if tc <= t1 and (tc > t0 or abs(ground_acceleration(tc, mp, acc)) > thr):
                        return tc, (-1 if sgn > 0.0 else 1)
            i += 1
        return t1, 0
    amp = abs(mp[SCALE] * mp[AMP])
    if amp <= thr:
        return t1, 0
    r = thr / amp
    shift, pend, omega = mp[SHIFT], mp[PEND], mp[OMEGA]
    base = np.zeros(6)
    nb = _pulse_crossings(kind, omega, mp[FREQ], r, base)
    period = 2.0 * math.pi / omega if kind != RICKER else 0.0
    # candidate crossings: the base ones plus whole periods, from the period holding t0
    tt0 = t0 + shift
    k0 = math.floor(tt0 / period) if period > 0.0 else 0.0
    best = math.inf
    for rep in range(3 if period > 0.0 else 1):
        for q in range(nb):
            tt = base[q] + (k0 + rep) * period
            if tt < max(tt0, 0.0) or tt > pend:
                continue
            # a rising crossing of |a|: just after it |a| exceeds the threshold
            dtt = 1e-9 * (period if period > 0.0 else 1.0 / mp[FREQ])
            after = abs(pulse_acceleration(kind, amp, omega, mp[FREQ], min(tt + dtt, pend)))
            if after > thr and tt < best:
                best = tt
    if best == math.inf:
        return t1, 0
    tc = best - shift
    if tc > t1:
        return t1, 0
    a = mp[SCALE] * pulse_acceleration(kind, mp[AMP], omega, mp[FREQ], min(best + 1e-12 / mp[FREQ], pend))
    return max(tc, t0), (1 if a < 0.0 else -1)
