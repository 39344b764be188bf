"""The physics of a statue that may slip on its base and of vertical ground motion
(docs/sliding.md, where every equation is derived): the four contact modes (rest, slide,
rock, slide-rock), their forces, which mode is consistent at a transition, and the impact
at θ = 0 with a friction-limited impulse.

Like analytic/physics.py, every function is plain Python on floats that numba compiles as
it is: the SciPy reference path (analytic/slide_hybrid.py) calls them directly and the
compiled kernel (analytic/slide_fast.py) compiles them, so the two paths cannot disagree on
physics, only on integration.

Coordinates (model.md's, and one more): u the base relative to the ground, θ the block's
rotation (θ > 0 about corner O at +b), and x the block's slide on its base: the horizontal
position, relative to the base, of the middle of its bottom face when θ = 0, carried through
rocking as x = x_c − s·b (x_c the pivot corner's position, s = sgn θ), so that x is
continuous through an impact, where the pivot changes. The block's centre of mass is then at
x + s·b·(1 − cosθ) + h·sinθ on the base, and at height z = s·b·sinθ + h·cosθ.

A contact mode is (s, σ): s = 0 the block flat on its base, ±1 rocking about corner s; σ = 0
the contact sticks, ±1 it slips that way (ẋ has sign σ). F_x, F_z are the base's force on
the block (at its pivot when rocking), g_e = g + üv the effective gravity (the base carries
the vertical motion rigidly).
"""
from __future__ import annotations

import math

import numpy as np

from .physics import (B_HALF, C_DAMP, FIXED, G, GRAZE_MARGIN, H, INERTIA, INV_J, INV_M, J, K, M_BASE, M_BLOCK,
                      M_TOTAL, REST, base_pinned, element_hold, isolator_element_force, lifts_clearly)

# --- packed contact parameters ------------------------------------------------------------
(C_MUS, C_MUK, C_VERT, C_TAN, N_CP) = range(5)

#: A contact sticks while |F_x| ≤ (μ_s + SLIP_BAND)·F_z, and a slip that stops sticks again
#: within the same band: far below physics, far above rounding (the demand's excess over
#: μ_s·F_z at a located event is ~1e-14·F_z), so that a slip starts with an acceleration of
#: its own sign and never flips back at once (a zero-length phase), as physics.STICK_BAND
#: does for the isolator's slider.
SLIP_BAND = 1e-12

#: how a transition's choice of mode can fail (choose_* return it as s = NO_MODE)
NO_MODE = 9
#: why no mode was consistent: the base pulls away from the block (g_e or F_z ≤ 0: free
#: flight, which the model does not carry), or Coulomb friction admits no solution (a
#: Painlevé paradox: the slide-rock equations' denominator is not positive)
FLIGHT, PAINLEVE = 1, 2
#: the stop message's reason for each
STOP_WHY = {FLIGHT: "free flight (the base's normal force on the block fell to zero: g + üv ≤ 0, or the block "
                    "is thrown off its pivot), which the model does not carry",
            PAINLEVE: "Coulomb friction admits no consistent contact mode here (a Painlevé paradox: the slide-rock "
                      "equations' effective inertia is not positive)"}


def needs_contact_model(system, motion) -> bool:
    """Whether a run needs the model of a contact that may slip: a statue with friction, or a
    motion with a vertical component. Otherwise the no-slip model runs, as it always has, to
    the last digit (both analytic paths dispatch on this)."""
    return system.friction is not None or motion.vertical is not None


def contact_params(system, vertical: bool) -> np.ndarray:
    """The contact's parameters: μ_s and μ_k (inf without friction: it never slips), whether
    the motion has a vertical component, and tanα = b/h."""
    cp = np.zeros(N_CP)
    cp[C_MUS] = math.inf if system.friction is None else system.friction
    cp[C_MUK] = math.inf if system.friction is None else system.kinetic_friction
    cp[C_VERT] = 1.0 if vertical else 0.0
    cp[C_TAN] = system.b / system.h
    return cp


def levers(sp, s, theta):
    """(L1, L2) of the centre of mass about corner s: ẋ_G = L1·θ̇ and ż_G = L2·θ̇ relative to
    the pivot, L1 = h cosθ + s b sinθ, L2 = s b cosθ − h sinθ (model.md)."""
    st, ct = math.sin(theta), math.cos(theta)
    return sp[H] * ct + s * sp[B_HALF] * st, s * sp[B_HALF] * ct - sp[H] * st


def base_held(sp, ip, phase):
    """Whether the base cannot move: a fixed base, or an isolator's rigid slider that sticks."""
    return sp[FIXED] != 0.0 or base_pinned(ip, phase)


def isolator_force(sp, ip, phase, u, u_dot, u_p):
    """c·u̇ + k·u + q (N): the isolator's force on the base, opposing its motion."""
    return sp[C_DAMP] * u_dot + sp[K] * u + isolator_element_force(ip, phase, u, u_dot, u_p)


def slide_rock_denominator(sp, cp, s, sigma, theta):
    """I + m·L2² − σ·μ_k·m·L1·L2: the effective inertia of slide-rock about corner s slipping
    the way σ. Not positive: Coulomb friction admits no slide-rock solution (Painlevé)."""
    L1, L2 = levers(sp, s, theta)
    m = sp[M_BLOCK]
    return sp[INERTIA] + m * L2 * L2 - sigma * cp[C_MUK] * m * L1 * L2


def accelerations(sp, ip, cp, s, sigma, phase, u_p, theta, theta_dot, u, u_dot, xg, ge):
    """(ü, ẍ, θ̈, F_x, F_z) in contact mode (s, σ) at ground accelerations ẍg (horizontal)
    and g_e = g + üv (docs/sliding.md, "Equations of motion"):

    - rest (0, 0): the block moves with its base, M·ü + c·u̇ + k·u + q = −M·ẍg;
    - rock (s, 0): model.md's 2-DOF equations with g_e for g;
    - slide (0, σ) and slide-rock (s, σ): F_x = −σ·μ_k·F_z, and the block's rotation and
      normal force follow from its own equations alone,
      θ̈ = m·(σμ_k·L1 − L2)·(g_e − L1·θ̇²) / (I + m·L2² − σμ_k·m·L1·L2), F_z = m·(g_e + L2·θ̈ − L1·θ̇²);
      the base then moves under −F_x and its isolator, m_b·(ẍg + ü) = −F_x − c·u̇ − k·u − q.
    A held base (fixed, or its rigid slider stuck) has ü = 0."""
    m = sp[M_BLOCK]
    held = base_held(sp, ip, phase)
    if sigma == 0.0:
        if s == 0.0:
            udd = 0.0 if held else -xg - isolator_force(sp, ip, phase, u, u_dot, u_p) * sp[INV_M]
            return udd, 0.0, 0.0, m * (xg + udd), m * ge
        L1, L2 = levers(sp, s, theta)
        w2 = theta_dot * theta_dot
        f_t = -m * L1 * xg - m * ge * L2
        if held:
            udd = 0.0
            thdd = f_t * sp[INV_J]
        else:
            M, Jt = sp[M_TOTAL], sp[J]
            f_u = -M * xg - m * L2 * w2 - isolator_force(sp, ip, phase, u, u_dot, u_p)
            inv = 1.0 / (M * Jt - (m * L1) ** 2)
            udd = (Jt * f_u - m * L1 * f_t) * inv
            thdd = (M * f_t - m * L1 * f_u) * inv
        return udd, 0.0, thdd, m * (xg + udd + L1 * thdd + L2 * w2), m * (ge + L2 * thdd - L1 * w2)
    mu = cp[C_MUK]
    if s == 0.0:
        L1, L2, thdd, w2 = 0.0, 0.0, 0.0, 0.0
        fz = m * ge
    else:
        L1, L2 = levers(sp, s, theta)
        w2 = theta_dot * theta_dot
        thdd = m * (sigma * mu * L1 - L2) * (ge - L1 * w2) / slide_rock_denominator(sp, cp, s, sigma, theta)
        fz = m * (ge + L2 * thdd - L1 * w2)
    fx = -sigma * mu * fz
    udd = 0.0 if held else -xg - (fx + isolator_force(sp, ip, phase, u, u_dot, u_p)) / sp[M_BASE]
    xdd = fx / m - xg - udd - L1 * thdd - L2 * w2
    return udd, xdd, thdd, fx, fz


def held_block_force(sp, cp, s, sigma, theta, theta_dot, xg, ge):
    """F_x (N) of the block's contact in mode (s, σ) were its base held (ü = 0)."""
    m = sp[M_BLOCK]
    if sigma != 0.0:
        if s == 0.0:
            return -sigma * cp[C_MUK] * m * ge
        L1, L2 = levers(sp, s, theta)
        w2 = theta_dot * theta_dot
        thdd = m * (sigma * cp[C_MUK] * L1 - L2) * (ge - L1 * w2) / slide_rock_denominator(sp, cp, s, sigma, theta)
        return -sigma * cp[C_MUK] * m * (ge + L2 * thdd - L1 * w2)
    if s == 0.0:
        return m * xg
    L1, L2 = levers(sp, s, theta)
    thdd = (-m * L1 * xg - m * ge * L2) * sp[INV_J]
    return m * (xg + L1 * thdd + L2 * theta_dot * theta_dot)


def held_demand(sp, ip, cp, s, sigma, theta, theta_dot, u, u_p, xg, ge):
    """The force (N) an isolator's rigid slider must exert to hold its base still (u̇ = ü = 0)
    with the block in mode (s, σ): −m_b·ẍg − F_x − k·u, less what the isolator's other
    parts hold (physics.element_hold). It sticks while |demand| ≤ its slip force."""
    f = -sp[M_BASE] * xg - held_block_force(sp, cp, s, sigma, theta, theta_dot, xg, ge) - sp[K] * u
    return element_hold(ip, f, u, u_p)


# --- energy (scalars or arrays) ----------------------------------------------------------------

def kinetic_energy(sp, s, u_dot, x_dot, theta, theta_dot):
    """T = ½ m_b u̇² + ½ m [(u̇ + ẋ + L1 θ̇)² + (L2 θ̇)²] + ½ I θ̇² (J), velocities relative to the ground."""
    h, b, m = sp[H], sp[B_HALF], sp[M_BLOCK]
    ct, st = np.cos(theta), np.sin(theta)
    vx = u_dot + x_dot + theta_dot * (h * ct + s * b * st)
    vz = theta_dot * (s * b * ct - h * st)
    return 0.5 * sp[M_BASE] * u_dot * u_dot + 0.5 * m * (vx * vx + vz * vz) + 0.5 * sp[INERTIA] * theta_dot * theta_dot


def ground_power(sp, s, xg, av, u_dot, x_dot, theta, theta_dot):
    """The ground's power (W) in its own translating frame: the horizontal inertial force −ẍg on
    every mass, −ẍg·(M·u̇ + m·ẋ + m·L1·θ̇), and the vertical −m·üv on the block, −m·üv·L2·θ̇
    (the base moves with the ground vertically). Fixed base: u̇ = 0."""
    L1, L2 = levers(sp, s, theta)
    m = sp[M_BLOCK]
    return -xg * (sp[M_TOTAL] * u_dot + m * x_dot + m * L1 * theta_dot) - av * m * L2 * theta_dot


def friction_power(cp, sigma, fz, x_dot):
    """The contact's friction loss (W, ≥ 0) while it slips: μ_k·F_z·|ẋ| as σ·μ_k·F_z·ẋ, smooth
    through the stop that a step may straddle (as physics.slip_power)."""
    if sigma == 0.0:
        return 0.0
    return sigma * cp[C_MUK] * fz * x_dot


# --- which mode is consistent (docs/sliding.md, "Transitions") ------------------------------

def sticks(cp, fx, fz):
    """Whether a contact carrying F_x with normal force F_z sticks (Coulomb, with SLIP_BAND)."""
    return abs(fx) <= (cp[C_MUS] + SLIP_BAND) * fz


def slip_way(fx):
    """The way a contact that cannot carry F_x slips: against it (σ = −sgn F_x)."""
    return -1.0 if fx > 0.0 else 1.0


def rock_mode(sp, ip, cp, s, phase, u_p, theta, theta_dot, u, u_dot, xg, ge, stick_ok):
    """(σ, why) of a block rocking about corner s whose contact does not slip now (ẋ = 0): 0 if
    it sticks (stick_ok and |F_x| within μ_s·F_z), else the slip against F_x, or (NO_MODE, why)."""
    r = accelerations(sp, ip, cp, s, 0.0, phase, u_p, theta, theta_dot, u, u_dot, xg, ge)
    if r[4] <= 0.0:
        return NO_MODE, FLIGHT
    if stick_ok and sticks(cp, r[3], r[4]):
        return 0.0, 0
    sigma = slip_way(r[3])
    if slide_rock_denominator(sp, cp, s, sigma, theta) <= 0.0:
        return NO_MODE, PAINLEVE
    return sigma, 0


def flat_mode(sp, ip, cp, phase, u_p, u, u_dot, x_dot, xg, ge, graze, tip, slip):
    """(s, σ, why) of a block flat on its base (θ = θ̇ = 0) sliding at x_dot: the first
    consistent of rest, rock, slide-rock and slide (Shenton 1996's modes; docs/sliding.md):

    - sliding (x_dot ≠ 0): it slides on, unless friction's moment tips it (μ_k > tanα), then
      it slide-rocks about its leading corner;
    - at rest: it rests while the base's force is within both μ_s·F_z and the tipping limit
      F_z·tanα; past the tipping limit it rocks (its corner sticking) or slide-rocks; past
      μ_s only, it slides against the force. `tip` and `slip` say that an event found a limit
      crossed (the choice trusts it, as rounding may put the demand a hair inside, and a block
      tipped by an event lifts as the no-slip model's does); otherwise a rocking phase starts
      only where θ̈ points clearly away from the base (physics.lifts_clearly),
      and `graze` adds GRAZE_MARGIN to the tipping limit after a grazing uplift stayed down.
    why: FLIGHT (g_e ≤ 0) or PAINLEVE when no mode is consistent (s = NO_MODE)."""
    if ge <= 0.0:
        return NO_MODE, 0.0, FLIGHT
    mu_k, tan = cp[C_MUK], cp[C_TAN]
    if x_dot != 0.0:
        sigma = 1.0 if x_dot > 0.0 else -1.0
        if mu_k > tan:  # friction at the bottom face tips the sliding block over its leading corner
            r = accelerations(sp, ip, cp, sigma, sigma, phase, u_p, 0.0, 0.0, u, u_dot, xg, ge)
            if slide_rock_denominator(sp, cp, sigma, sigma, 0.0) > 0.0 and lifts_clearly(sp, sigma, r[2]):
                return sigma, sigma, 0
        return 0.0, sigma, 0
    r = accelerations(sp, ip, cp, 0.0, 0.0, phase, u_p, 0.0, 0.0, u, u_dot, xg, ge)
    fx, fz = r[3], r[4]
    a = fx / sp[M_BLOCK]  # the base's absolute acceleration
    tips = tip or abs(a) > ge * tan * (1.0 + (GRAZE_MARGIN if graze else 0.0))
    holds = not slip and sticks(cp, fx, fz)
    if holds and not tips:
        return 0.0, 0.0, 0
    if tips:
        s = 1.0 if a < 0.0 else -1.0
        rs = accelerations(sp, ip, cp, s, 0.0, phase, u_p, 0.0, 0.0, u, u_dot, xg, ge)
        if tip or lifts_clearly(sp, s, rs[2]):
            if rs[4] > 0.0 and sticks(cp, rs[3], rs[4]):
                return s, 0.0, 0
            sigma = slip_way(rs[3])
            if slide_rock_denominator(sp, cp, s, sigma, 0.0) > 0.0:
                rr = accelerations(sp, ip, cp, s, sigma, phase, u_p, 0.0, 0.0, u, u_dot, xg, ge)
                if (tip or lifts_clearly(sp, s, rr[2])) and sigma * rr[1] > 0.0 and rr[4] > 0.0:
                    return s, sigma, 0
    if not holds and mu_k <= tan:
        sigma = slip_way(fx)
        rr = accelerations(sp, ip, cp, 0.0, sigma, phase, u_p, 0.0, 0.0, u, u_dot, xg, ge)
        if sigma * rr[1] > 0.0 or slip:  # an event found the slip: trusted, as `tip`
            return 0.0, sigma, 0
    if holds or sticks(cp, fx, fz):
        return 0.0, 0.0, 0  # tipped only by a graze, or slipped only by rounding: it stays down
    return NO_MODE, 0.0, PAINLEVE


def slip_start_order(sigma, xdd):
    """(k, limit) of a slip that starts from ẋ = 0: σ·ẋ/(t − t0)^k tends to `limit` > 0 (the
    stop event divides by it, so that the start is never taken for the stop)."""
    if sigma * xdd > 0.0:
        return 1, sigma * xdd
    return 2, 1e-300  # started by a trusted event with ẍ ~ 0: ẋ grows as (t − t0)²


# --- the impact at θ = 0 with a friction-limited impulse (docs/sliding.md, "Impact") -----------

def impact(sp, cp, s, theta_dot_pre, x_dot_pre, u_dot_pre, continued):
    """(θ̇⁺, ẋ⁺, u̇⁺, P_x, P_z, ok) of a block rocking about corner s that lands at θ = 0 with
    θ̇⁻, sliding at ẋ⁻ on a base moving at u̇⁻, perfectly inelastic at the other corner −s
    (continued: it rocks on about −s) or on its whole face (rocking ceases). P_x, P_z: the
    impulse on the block (N·s). The impulse sticks the landing corner (ẋ⁺ = 0) when
    |P_x| ≤ μ_s·P_z; otherwise it slips through the impact with P_x = ±μ_k·P_z, the way the
    sticking impulse would have pushed (no reversal of the slip within the impact: the
    assumption of docs/sliding.md). The base takes −P_x (free, as model.md's β₂ and β₃ have
    it: the isolator's finite forces give no impulse); a fixed base takes it all. Without
    slip this is model.md's map: θ̇⁺ = β θ̇⁻, u̇⁺ = u̇⁻ + β₂ θ̇⁻ (or β₃). ok is False when the
    landing would need a negative normal impulse (the model stops there: docs/sliding.md)."""
    m, h, b, inertia = sp[M_BLOCK], sp[H], sp[B_HALF], sp[INERTIA]
    inv_mb = 0.0 if sp[FIXED] != 0.0 else 1.0 / sp[M_BASE]
    if continued:
        A = 1.0 / m + inv_mb + h * h / inertia
        Bc = s * b * h / inertia
        C = 1.0 / m + b * b / inertia
        vz = 2.0 * s * b * theta_dot_pre  # the landing corner's downward speed, −2·s·b·θ̇⁻ > 0 down
        det = A * C - Bc * Bc
        px = (-x_dot_pre * C - Bc * vz) / det
        pz = (-A * vz - Bc * x_dot_pre) / det
        xd = 0.0
        if not sticks(cp, px, pz):
            kappa = 1.0 if px > 0.0 else -1.0
            pz = -vz / (C - kappa * cp[C_MUK] * Bc)
            px = kappa * cp[C_MUK] * pz
            xd = x_dot_pre + A * px - Bc * pz
        thd = theta_dot_pre + (-h * px + s * b * pz) / inertia
        if pz <= 0.0:
            return thd, xd, u_dot_pre - inv_mb * px, px, pz, False
        if -s * thd > 0.0:
            return thd, xd, u_dot_pre - inv_mb * px, px, pz, True
        # the impulse leaves no rotation about −s: the block lands on its face instead
    if s * theta_dot_pre > 0.0:
        theta_dot_pre = 0.0  # a landing found where θ̇ ≈ 0 (a graze), rounding's sign: at rest
    pz = -m * s * b * theta_dot_pre
    px = -(x_dot_pre + h * theta_dot_pre) / (1.0 / m + inv_mb)
    xd = 0.0
    if not sticks(cp, px, pz):
        kappa = 1.0 if px > 0.0 else -1.0
        px = kappa * cp[C_MUK] * pz
        xd = x_dot_pre + h * theta_dot_pre + px * (1.0 / m + inv_mb)
        if abs(xd) < sp[REST] * h:
            # the rocking's rest floor as a speed (θ̇ at the floor times h): below it the block
            # lands and stays (its kinetic energy is the impact's loss). Above μ_k > tanα a flat
            # block that slides tips over its leading corner, lands, slides and tips again: a
            # Zeno sequence of ever smaller slips that this floor ends, as it ends rocking's
            xd = 0.0
    return 0.0, xd, u_dot_pre - inv_mb * px, px, pz, pz >= 0.0  # P_z = 0: it lands at rest


def effective_gravity(sp, cp, av):
    """g_e = g + üv (m/s²): what the block feels of gravity on a base that heaves with the ground."""
    return sp[G] + av if cp[C_VERT] != 0.0 else sp[G]
