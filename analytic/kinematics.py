"""Rigid-block kinematics every contact scene needs, written once: the pose of a block
tilted about its corner, the rocking angle and out-of-plane tilts from a rotation,
where the pivot corner and the lowest corner are, and the rules that stop a run.

Conventions (model.md): x horizontal, z up, the base's top face at z = 0 when u = 0;
θ is a rotation about +y, θ > 0 when the centroid moves to +x (rocking about corner
O at x = +b). Positions are absolute, in the ground's (translating) frame; u is the
base displacement relative to the ground.
"""
from __future__ import annotations

import math
import time

import numpy as np

from .slide_physics import needs_contact_model
from .system import System
from .trajectory import DEFAULT_IMPACT_THRESHOLD, counted_sign_changes


# --- pose -----------------------------------------------------------------------------

def tilted_centroid(system: System, theta: float) -> tuple[float, float]:
    """(x, z) of the centroid of a block resting on its corner s·b (s = sign θ; b_s for a
    statue of two edges) of the base's top face and tilted by θ about it: the corner stays
    where it rests upright."""
    s = 1.0 if theta >= 0 else -1.0
    h, b = system.h, system.lever(s)
    return (s * b + h * math.sin(theta) - s * b * math.cos(theta),
            h * math.cos(theta) + s * b * math.sin(theta))


#: How far (in units of the block's R) a statue that may slide (System.friction) can walk on
#: its base before it reaches the edge of a contact engine's plate, beyond the room every
#: plate leaves for a block that falls: the exact model's base has no edge. Random pulses
#: slid up to 32·b (the 95th percentile 10·b, docs/sliding_engines.md), but the full stress grid's
#: squat blocks under 6 g of record-like noise up to 282·b (drawn-0553: 313 m on a soft isolator,
#: PyBullet within 1e-5 of the exact slide on this plate, off a plate of 100·R); 1000·R is at
#: least 1400·b (R ≥ √2·b for λ ≥ 1). A statue that walks farther is flagged (validate.core.measure).
SLIDE_ROOM = 1000.0


def slide_room(system: System) -> float:
    """Half-width (m) a contact engine's plate adds for a statue that may slide: SLIDE_ROOM·R
    with friction, 0 without (that plate, and every history on it, as before)."""
    return 0.0 if system.friction is None else SLIDE_ROOM * system.R


def plate_edge(system: System) -> float:
    """How far (m) a statue's slide x may go before its footprint passes the edge of a contact
    engine's plate: every engine's plate reaches b + H + slide_room from its middle (MuJoCo's
    0.1 m more), and the footprint b beyond x."""
    return system.height + slide_room(system)


# --- rotations ------------------------------------------------------------------------

def tilts_from_quaternion(w, x, y, z):
    """(θ, roll, yaw) of unit quaternions (arrays or scalars, scalar part w first): θ the
    lean of the body's z axis towards +x (rotation about y), roll about the world x axis,
    yaw about the world z axis. For a block that stays in its plane roll = yaw = 0."""
    r00 = 1 - 2 * (y * y + z * z)
    r10 = 2 * (x * y + w * z)
    r02 = 2 * (x * z + w * y)
    r12 = 2 * (y * z - w * x)
    r22 = 1 - 2 * (x * x + y * y)
    theta = np.arctan2(r02, r22)
    roll = np.arctan2(-r12, np.hypot(r02, r22))
    yaw = np.arctan2(r10, r00)
    return theta, roll, yaw


# --- corners --------------------------------------------------------------------------

def _per_side(s, value):
    """value(side) for each of s (an array of ±1): a statue of two edges (System.body) has its own
    lever and α on each side; the block's two are one (System.lever, System.edge_alpha)."""
    return np.where(s > 0, value(1), value(-1))


def pivot_slip(system: System, x_centroid, theta, u):
    """How far (m) the corner the block rocks on has moved along x relative to the point
    of the base it rests on (s·b + u): zero for pure rocking, non-zero when it slides.
    The corner (s·b, −h) of the body frame is at x_c + s·b·cosθ − h·sinθ."""
    theta = np.asarray(theta, dtype=float)
    s = np.where(theta >= 0, 1.0, -1.0)
    b, h = _per_side(s, system.lever), system.h
    return np.asarray(x_centroid) + s * b * np.cos(theta) - h * np.sin(theta) - np.asarray(u) - s * b


def pivot_slip_rate(system: System, x_centroid_dot, theta, theta_dot, u_dot):
    """d/dt of pivot_slip (m/s) from the body's velocities: the pivot corner's horizontal
    velocity relative to the base, ẋ_c − θ̇·(s·b·sinθ + h·cosθ) − u̇. Continuous through θ = 0,
    where both bottom corners move alike."""
    theta = np.asarray(theta, dtype=float)
    s = np.where(theta >= 0, 1.0, -1.0)
    b, h = _per_side(s, system.lever), system.h
    return (np.asarray(x_centroid_dot) - np.asarray(theta_dot) * (s * b * np.sin(theta) + h * np.cos(theta))
            - np.asarray(u_dot))


def slide_history(system: System, motion, *, x_centroid, x_centroid_dot, theta, theta_dot, u, u_dot):
    """(slide, slide_dot) of a contact engine's history: the block's slide x on its base (m) of
    analytic.slide_physics (the middle of its bottom face at θ = 0, carried through rocking as
    x = x_c − s·b: pivot_slip, row by row) and its rate (m/s, pivot_slip_rate, from the body's
    velocities), where the run needs the model of a contact that may slip
    (slide_physics.needs_contact_model: a statue with friction, or a vertical motion);
    (None, None) otherwise, so that a history of the no-slip model carries nothing new."""
    if not needs_contact_model(system, motion):
        return None, None
    return (pivot_slip(system, x_centroid, theta, u),
            pivot_slip_rate(system, x_centroid_dot, theta, theta_dot, u_dot))


def lift_off(system: System, z_centroid, theta):
    """Height (m) of the block's lowest bottom corner above the base's top face
    (negative: penetration), for an in-plane rotation θ."""
    theta = np.asarray(theta, dtype=float)
    b = _per_side(np.where(theta >= 0, 1.0, -1.0), system.lever)
    return np.asarray(z_centroid) - system.h * np.cos(theta) - b * np.abs(np.sin(theta))


def contact_extras(system: System, *, x_centroid, z_centroid, theta, u, out_of_plane=None) -> dict:
    """The contact engines' extras, one vocabulary for all of them (each a scalar):
    pivot_slip_max (m: how far the corner the block stands or rocks on moved along the
    base, at rest too, while |θ| ≤ α: beyond, a falling block pivots on its edge and lands
    on its side, and "the pivot" means nothing), lift_off_max_after_impact (m, after the first
    counted impact: a hop shows here), penetration_max (m) and, where the block can
    leave its plane, out_of_plane_max (largest of |y| in m and the roll and yaw tilts in
    rad, while |θ| ≤ α as the slip). The first counted impact is model.md's (counted_sign_changes
    at the default threshold), found here for every engine."""
    counted = counted_sign_changes(np.asarray(theta, dtype=float), system.alpha, DEFAULT_IMPACT_THRESHOLD)
    counted_from = counted[0][0] if counted else None
    theta = np.asarray(theta, dtype=float)
    upright = np.abs(theta) <= _per_side(np.where(theta >= 0, 1.0, -1.0), system.edge_alpha)
    slip = pivot_slip(system, x_centroid, theta, u)[upright]
    low = lift_off(system, z_centroid, theta)
    after = low[counted_from:] if counted_from is not None else low[:0]
    out = {
        "pivot_slip_max": float(np.max(np.abs(slip))) if slip.size else 0.0,
        "lift_off_max_after_impact": float(np.max(after)) if after.size else 0.0,
        "penetration_max": float(max(0.0, -np.min(low))) if low.size else 0.0,
    }
    if out_of_plane is not None:  # while it rocks, as the slip: a fallen body lies anyhow
        rocking = np.asarray(out_of_plane)[upright]
        out["out_of_plane_max"] = float(np.max(rocking)) if rocking.size else 0.0
    return out



def pair_extras(extras: dict, *, orientation, y_centroid, u_y) -> dict:
    """A contact engine's extras of a run of two horizontal components (GroundMotion.transverse),
    one vocabulary for every engine that carries them: the histories (not scalars) the
    two-component measures read (validate.core.biaxial): `orientation` (the body's own frame,
    quaternions w x y z per row), `y_centroid` (m), `u_y` (the base along y, m; zeros on a fixed
    base). The planar pivot's slip is dropped: it reads the corner on x and θ about y, so a
    statue leaning along y or a diagonal would read as sliding (its 3-D slip is not measured yet)."""
    extras.pop("pivot_slip_max", None)
    extras.update(orientation=np.asarray(orientation, dtype=float), y_centroid=np.asarray(y_centroid, dtype=float),
                  u_y=np.asarray(u_y, dtype=float))
    return extras


# --- when a run stops -------------------------------------------------------------------

#: |θ| at which the block lies on its side: the rocking equations end there (model.md).
LYING = 0.5 * math.pi
#: A contact engine's block lands on its side face through a compliant contact and comes
#: to rest a little short of π/2 (MuJoCo and PyBullet rest 0.003–0.035 rad short, measured on
#: the Kobe ensembles): within this (rad) it is lying, and the run stops there.
LYING_SLACK = 0.05


def first_stop(t, theta, theta_dot, finite, *, system: System, motion_end: float) -> tuple[int | None, str | None]:
    """(index, reason) of the first sample at which a contact engine's run stops, by the
    rules of model.md ("Past α"), or (None, None) while it goes on:
    - 'non-finite': the state stopped being finite (the history ends before it);
    - 'lying': |θ| reached π/2 (within LYING_SLACK), the block lies on its side (the
      history ends with it);
    - 'falling': on a fixed base after the motion has ended, |θ| > α and growing: nothing
      can bring the block back (on an isolated base the base still swings, so never).
    Overturning itself is judged from the history afterwards, the same way for every
    engine (`isorock.validate.core.measure`)."""
    t = np.asarray(t, dtype=float)
    theta = np.asarray(theta, dtype=float)
    theta_dot = np.asarray(theta_dot, dtype=float)
    finite = np.asarray(finite, dtype=bool)
    th = np.where(finite, theta, 0.0)
    thd = np.where(finite, theta_dot, 0.0)
    candidates = []
    bad = np.flatnonzero(~finite)
    if bad.size:
        candidates.append((int(bad[0]), "non-finite"))
    lying = np.flatnonzero(np.abs(th) >= LYING - LYING_SLACK)
    if lying.size:
        candidates.append((int(lying[0]), "lying"))
    if system.fixed_base:
        falling = np.flatnonzero((t > motion_end) & (np.abs(th) > system.alpha) & (th * thd > 0))
        if falling.size:
            candidates.append((int(falling[0]), "falling"))
    return min(candidates) if candidates else (None, None)


#: Wall seconds between two progress reports of an engine.
PROGRESS_INTERVAL = 1.0


class Throttle:
    """Calls `report(t, duration)` at most once per `interval` wall seconds (default
    PROGRESS_INTERVAL): engines report progress between chunks of work without paying
    for it at every step."""

    def __init__(self, report, duration: float, interval: float | None = None):
        self.report, self.duration = report, duration
        self.interval = PROGRESS_INTERVAL if interval is None else interval
        self.last = time.perf_counter()

    def __call__(self, t: float) -> None:
        if self.report is None:
            return
        now = time.perf_counter()
        if now - self.last >= self.interval:
            self.report(float(t), self.duration)
            self.last = now


__all__ = ["tilted_centroid", "tilts_from_quaternion", "pivot_slip", "pivot_slip_rate", "slide_history",
           "slide_room", "plate_edge", "lift_off", "contact_extras", "first_stop", "Throttle", "LYING"]
