"""The rest phase every contact engine may skip (docs/mujoco.md "Phased stepping",
docs/bullet.md "Phased stepping"): while the block sits on its base and the base's
absolute acceleration |a| = |ü + ẍg| stays well below the uplift threshold g·tanα,
nothing about contact happens. On a fixed base the block rides the ground (its state is
constant); on an isolated one block and base move as one body, the 1-DOF oscillator
M ü + c u̇ + k u = −M ẍg (M = m + m_b), which each engine writes out as its own step
would integrate it (a linear map per step, `linear_steps`).

The rules, shared by the engines so that a phased run means the same everywhere: the
contact scene takes over LEAD_TIME before |a| first reaches F_HIGH·g·tanα, and hands
over again once the block has rested SETTLE_TIME with |a| < F_LOW·g·tanα. "At rest" is
dimensionless in the block's own scales (REST_TILT, REST_RATE, REST_SPEED), so the rule
holds at any size.
"""
from __future__ import annotations

import numpy as np
from scipy.signal import lfilter

from .slide_physics import needs_contact_model
from .system import LINEAR

#: The contact scene takes over LEAD_TIME (s) before the base's absolute acceleration first
#: reaches F_HIGH of the uplift threshold: the block's compliant rest tilts by a contact
#: time constant's worth before it lifts, and a record's acceleration can jump within a
#: step, so the margin is both a fraction of the threshold and a time (0.05 s: 25 contact
#: time constants, 10 samples of a 0.005 s record). Against full stepping F_HIGH 0.8
#: moved MuJoCo's fixed-base Ricker θmax/α by 1.9e-3, 0.7 by ≤ 2.5e-4 on the Rickers and
#: 1.3e-3 on Kobe (the limit is 0.02; docs/mujoco.md).
F_HIGH = 0.7
LEAD_TIME = 0.05
#: Back to the rest phase after the block has rested SETTLE_TIME (s) with
#: |a| < F_LOW·g·tanα at the last of those rows.
F_LOW = 0.5
SETTLE_TIME = 0.1
#: "At rest": |θ| below REST_TILT·α, |θ̇| below REST_RATE·α·p, and the block's sliding
#: and vertical speeds relative to the base below REST_SPEED·g/p. The speed bound allows
#: a soft friction contact's elastic creep (2e-5·g/p measured in MuJoCo on Kobe after
#: rocking); true sliding needs |a| > μg, far above F_LOW·g·tanα.
REST_TILT = 1e-4
REST_RATE = 1e-4
REST_SPEED = 1e-4


def stepped_throughout(system, motion) -> str | None:
    """Why a contact engine's run takes no rest phase (and MuJoCo no coarse step away from
    impacts), whatever its Settings.phased asks, in the words its extras["stepping"] says it
    with; None: it may. A non-linear isolator: the rest phase's map is the linear isolator's (and
    a coarse step would soften MuJoCo's dry friction, whose time constant is 2 timesteps). A
    statue that may slide, or a vertical motion: the rest phase holds the block on its base until
    the base nears the horizontal uplift threshold g·tanα, while friction lets it slide below
    that (at μ·g) and the heave moves it at any acceleration; the coarse steps were measured on
    a block that cannot slide (docs/mujoco.md)."""
    if system.isolator_kind != LINEAR:
        return "non-linear isolator"
    if needs_contact_model(system, motion):
        return "a statue that may slide" if motion.vertical is None else "a vertical motion"
    return None


def takeover(acceleration, threshold: float, lead: int, start: int = 0) -> int | None:
    """Index into `acceleration` (|a| after each step of a rest phase, from index `start`)
    of the last step before the contact scene takes over: `lead` steps before |a| first
    reaches F_HIGH·threshold (at least `start`), or None if it never does.
    `acceleration` is an array or anything sliced like one (it is read BLOCK steps at a
    time, so a record evaluated as it is read is evaluated only as far as needed)."""
    for block in range(start, acceleration.size, BLOCK):
        hot = first_hot(acceleration[block:min(block + BLOCK, acceleration.size)], threshold)
        if hot is not None:
            return max(start, block + hot - lead)
    return None


def first_hot(acceleration: np.ndarray, threshold: float) -> int | None:
    """Index of the first |a| at or above F_HIGH·threshold, or None."""
    hot = np.flatnonzero(np.abs(acceleration) >= F_HIGH * threshold)
    return None if hot.size == 0 else int(hot[0])


#: Steps a rest phase's states are computed in at a time: a rest phase usually ends long
#: before the record does, and each block is cheap (a few ms), so the states past the end
#: of the phase are not computed for the whole record.
BLOCK = 1 << 15


def rest_states(a, b, x0, f, acceleration) -> tuple[np.ndarray | None, int | None]:
    """The states after each step of x' = A x + B f (`linear_steps`), block by block
    (BLOCK steps) until one is hot: `acceleration(states)` gives |a| of each state over
    the uplift threshold (states: a row per state variable). Returns (states, index of the first hot state or None): the
    states of every block computed, up to and including the one where it was found; None
    for states where the map has a repeated mode (the caller steps it itself)."""
    f = np.asarray(f, dtype=float)
    x, parts, done = np.asarray(x0, dtype=float), [], 0
    while done < f.size:
        part = linear_steps(a, b, x, f[done:done + BLOCK])
        if part is None:
            return None, None
        parts.append(part)
        hot = first_hot(acceleration(part), 1.0)
        if hot is not None:
            return np.concatenate(parts, axis=1), done + hot
        done += part.shape[1]
        x = part[:, -1]
    return (np.concatenate(parts, axis=1) if parts else np.zeros((len(x), 0))), None


def linear_steps(a: np.ndarray, b: np.ndarray, x0: np.ndarray, f: np.ndarray) -> np.ndarray | None:
    """The states after each step of x' = A x + B f (a column per entry of f, a row per
    state variable), run mode by mode through scipy's lfilter (C speed: a Python loop
    costs ~2 µs a step, as much as an engine's contact step): with A = V Λ V⁻¹, each mode
    z = (V⁻¹x)_i is a first-order filter; a complex pair is run once (the conjugate adds
    the conjugate). Modes, not the direct-form recursion of one state alone, whose poles
    so near 1 lose ~1e-10 of u over a record (measured). Returns None where V is
    ill-conditioned (a repeated mode: the caller steps the map itself)."""
    a, b, x0 = np.asarray(a, dtype=float), np.asarray(b, dtype=float), np.asarray(x0, dtype=float)
    lam, vec = np.linalg.eig(a)
    if np.linalg.cond(vec) > 1e6:
        return None
    inv = np.linalg.inv(vec)
    z0, g = inv @ x0.astype(complex), inv @ b
    f = np.asarray(f, dtype=float)
    out = np.zeros((a.shape[0], f.size))
    fc = None
    for i, li in enumerate(lam):
        if li.imag < 0 and np.any(np.isclose(lam, np.conj(li), rtol=0, atol=1e-14) & (lam.imag > 0)):
            continue  # the conjugate of a mode already run
        if li.imag != 0:
            fc = f.astype(complex) if fc is None else fc
            mode = lfilter([g[i]], [1.0, -li], fc, zi=[li * z0[i]])[0]
            re, im = mode.real, mode.imag
            for j in range(a.shape[0]):  # 2·Re(v_j · mode), without a complex (d, n) array
                out[j] += 2 * vec[j, i].real * re - 2 * vec[j, i].imag * im
        else:
            mode = lfilter([g[i].real], [1.0, -li.real], f, zi=[(li * z0[i]).real])[0]
            for j in range(a.shape[0]):
                out[j] += vec[j, i].real * mode
    return out


__all__ = ["F_HIGH", "LEAD_TIME", "F_LOW", "SETTLE_TIME", "REST_TILT", "REST_RATE", "REST_SPEED", "stepped_throughout",
           "takeover", "first_hot", "rest_states", "linear_steps", "BLOCK"]
