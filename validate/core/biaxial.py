"""Two horizontal ground-motion components (issue 36): what a 3-D history says, and the planar
exact model along each component beside it.

The data flow is the project's: an engine's run of the pair (MuJoCo's scene, the body on the
free joint, the base on two slide joints) leaves its orientation history in the Trajectory's
extras (`orientation`, quaternions w x y z per row); `measure_3d` reads tilt, twist and wobble
from it; `planar_runs` runs the exact model along each component alone (the statue's edges at
the azimuth and at azimuth + 90°); `compare_3d` puts them side by side in words. Nothing here
runs an engine's pair or changes a history.

Frames: the scene's x is the statue's --azimuth (the first component's direction), its y
azimuth + 90° (the second's). The body frame is the world frame at rest (the hull's vertices
are given about its centre of mass in the table frame), so the body's z axis is its vertical.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...analytic import shape
from ...analytic.kinematics import LYING, LYING_SLACK
from ...analytic.system import PlanarBody
from .engines import get_engine

#: The tilt direction is read only where the total tilt exceeds this fraction of the statue's
#: least α: below it the direction is set by the contact's micro-motion (a planar rock's
#: out-of-plane tilt stays ~1e-9 rad) and swings at random, and a planar rock passes through
#: zero tilt at every impact, where its direction flips by 180° without any wobble.
WOBBLE_FLOOR = 0.05
#: Directions over which α(direction) is tabulated (one a degree), read by interpolation: the
#: statue's tipping edge along the direction it leans at each sample.
ALPHA_DIRECTIONS = 360
#: The report says the twist and the wobble in words above these (degrees): below, a trace
#: (a hull symmetric to roundoff under one component turns by ~1e-3°, measured).
TWIST_SAID_DEG = 1.0
WOBBLE_SAID_DEG = 10.0


def tilt_twist(orientation: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(total tilt, tilt direction, twist), rad, of unit quaternions (rows w, x, y, z): the
    angle of the body's z axis from the vertical, the direction (from x towards y) its top
    leans, and the rotation about the body's own vertical (the swing–twist decomposition's
    twist 2·atan2(q_z, q_w), unwrapped over the history so that a turn past 180° counts)."""
    w, x, y, z = np.asarray(orientation, dtype=float).T
    zx, zy, zz = 2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)
    tilt = np.arctan2(np.hypot(zx, zy), zz)
    direction = np.arctan2(zy, zx)
    # the twist's half angle lives on (−π/2, π/2] for w ≥ 0: take the quaternion with w ≥ 0
    sign = np.where(w < 0, -1.0, 1.0)
    twist = np.unwrap(2 * np.arctan2(sign * z, sign * w))
    return tilt, direction, twist


def alpha_table(body: shape.RestingBody, azimuth: float):
    """α(ψ) of the forward tipping edge when the statue leans towards ψ (rad, in the scene's
    frame, whose x is `azimuth` on the statue): shape.tipping_edges at azimuth + ψ, on a grid
    of ALPHA_DIRECTIONS, returned as a function of ψ (periodic linear interpolation)."""
    grid = np.linspace(0.0, 2 * math.pi, ALPHA_DIRECTIONS, endpoint=False)
    alphas = np.array([shape.tipping_edges(body, azimuth + g)["forward"]["alpha"] for g in grid])

    def alpha(psi):
        return np.interp(np.mod(psi, 2 * math.pi), grid, alphas, period=2 * math.pi)
    return alpha, float(alphas.min())


def box_body(height: float, width: float, depth: float, mass: float) -> shape.RestingBody:
    """The block H × B × D as a resting body (its tipping edges along any direction, as a
    statue's): what MuJoCo's scene builds for it (scene.DEPTH_FRACTION)."""
    corners = np.array([(sx * width / 2, sy * depth / 2, z) for sx in (-1, 1) for sy in (-1, 1)
                        for z in (0.0, height)])
    vertices, faces = shape.hull_mesh(corners)
    return shape.standing(vertices, faces, mass=mass, name="the block")


@dataclass(frozen=True)
class Measures3D:
    """What the 3-D history says (angles in rad unless named _deg)."""

    tilt_max: float             #: the largest total tilt
    tilt_max_over_alpha: float  #: the largest of tilt / α(the direction it leans), each sample its own α
    direction_at_max_deg: float  #: where it leaned then, degrees from the scene's x (the --azimuth)
    alpha_at_max: float         #: α of the edge it leaned towards then
    overturned: bool            #: lying (tilt within LYING_SLACK of π/2), or past α at the end
    #: the largest |rotation about its vertical|, before it first passes α (while it rocks)
    twist_max_deg: float
    #: how far the tilt's axis swings from its axis at the largest tilt (0–90°), while it rocks
    wobble_deg: float
    base_y_max: float           #: the base's largest |displacement| along y (m; 0 on a fixed base)
    rocked: bool                #: whether it tilted past WOBBLE_FLOOR · least α at all

    def as_dict(self) -> dict:
        return {k: (bool(v) if isinstance(v, (bool, np.bool_)) else float(v)) for k, v in self.__dict__.items()}


def measure_3d(t: np.ndarray, orientation: np.ndarray, alpha, least_alpha: float, *, u_y=None) -> Measures3D:
    """The two-component measures of an orientation history (`alpha`: alpha_table's function)."""
    tilt, direction, twist = tilt_twist(orientation)
    ratio = tilt / alpha(direction)
    k = int(np.argmax(ratio))
    final = float(ratio[-1])
    lying = bool(np.max(tilt) >= LYING - LYING_SLACK)
    # twist and wobble while it stands or rocks: up to the first time it passes α (after that
    # it falls, or tumbles back, and turning as it lands is not a rocking statue's wobble)
    past = np.flatnonzero(ratio > 1.0)
    rocking = slice(0, past[0] if past.size else ratio.size)
    significant = np.zeros(ratio.size, dtype=bool)
    significant[rocking] = tilt[rocking] > WOBBLE_FLOOR * least_alpha
    if significant.any():
        # the tilt's axis (its direction modulo 180°: rocking back across the pivot is no wobble)
        # against the axis at the largest tilt while rocking, folded onto 0–90°
        j = int(np.argmax(np.where(significant, ratio, -np.inf)))
        off = np.mod(direction[significant] - direction[j] + 0.5 * math.pi, math.pi) - 0.5 * math.pi
        wobble = float(np.degrees(np.max(np.abs(off))))
    else:
        wobble = 0.0
    twist_max = float(np.degrees(np.max(np.abs(twist[rocking])))) if twist[rocking].size else 0.0
    return Measures3D(tilt_max=float(np.max(tilt)), tilt_max_over_alpha=float(ratio[k]),
                      direction_at_max_deg=float(np.degrees(direction[k]) % 360.0),
                      alpha_at_max=float(alpha(direction[k])), overturned=lying or final > 1.0,
                      twist_max_deg=twist_max, wobble_deg=wobble,
                      base_y_max=0.0 if u_y is None else float(np.max(np.abs(u_y))),
                      rocked=bool(significant.any()))


def planar_systems(system, body: shape.RestingBody | None, azimuth: float):
    """(System along the first component, System along the second) of the exact model: a
    statue's two edges at the azimuth and at azimuth + 90° (its System.body along each); the
    block (no `body`) is the same H × B both ways, its footprint square (scene.DEPTH_FRACTION)."""
    if body is None:
        return system, system
    across = PlanarBody.from_resting(body.along(azimuth + 0.5 * math.pi))
    return system, replace(system, body=across, **across.box)


def planar_runs(system, motion, body: shape.RestingBody | None, azimuth: float, *, duration: float,
                engine: str = "analytic") -> dict:
    """The exact model along each component alone: {'x': Trajectory, 'y': Trajectory}."""
    exact = get_engine(engine)
    along_x, along_y = planar_systems(system, body, azimuth)
    return {"x": exact.simulate(along_x, motion.with_transverse(None), duration=duration),
            "y": exact.simulate(along_y, motion.transverse, duration=duration)}


def planar_numbers(tr) -> dict:
    return {"theta_max_over_alpha": float(tr.theta_max_over_alpha), "overturned": bool(tr.overturned),
            "alpha": float(tr.system.alpha), "status": str(tr.status)}


CANNOT_CAPTURE = ("The planar exact model rocks the statue in one vertical plane about one of two edges: it cannot "
                  "capture the twist about the vertical, the wobble of the tilt's direction (rocking on a corner, "
                  "or rolling on a rim), nor the coupling between the two directions (the rocking about one edge "
                  "changes the statue's response to the other component; each planar run sees one component alone).")


def compare_3d(three: Measures3D, planar: dict) -> dict:
    """The verdict first, then the numbers, and in words where the 3-D run parts from both
    planar runs (`planar`: planar_numbers of the run along x and along y)."""
    px, py = planar["x"], planar["y"]
    worst = max(px["theta_max_over_alpha"], py["theta_max_over_alpha"])
    planar_over = bool(px["overturned"] or py["overturned"])
    verdict = (f"Overturned (two components, 3-D): its total tilt reached {three.tilt_max:.3g} rad"
               if three.overturned else
               f"Stands (two components, 3-D): total tilt at most {three.tilt_max_over_alpha:.3g} α "
               f"(leaning towards {three.direction_at_max_deg:.0f}° from the first component)")
    parts = []
    if three.overturned != planar_over:
        which = " and ".join(k for k, p in (("x", px), ("y", py)) if p["overturned"])
        parts.append(f"the 3-D run {'overturns' if three.overturned else 'stands'} where "
                     + (f"the planar run along {which} overturns" if planar_over else "both planar runs stand"))
    elif three.overturned:
        parts.append("all three overturn (a fallen statue's tilt/α is no measure of how near it came)")
    elif max(three.tilt_max_over_alpha, worst) < WOBBLE_FLOOR:
        # a relative difference of two traces means nothing: both are the contact's micro-motion
        parts.append(f"none of the three rocks past {WOBBLE_FLOOR:g} α (3-D {three.tilt_max_over_alpha:.2g}, planar "
                     f"{worst:.2g})")
    elif worst < WOBBLE_FLOOR:
        parts.append(f"its peak tilt/α is {three.tilt_max_over_alpha:.3g} where neither planar run passes "
                     f"{WOBBLE_FLOOR:g} α")
    else:
        rel = (three.tilt_max_over_alpha - worst) / worst
        parts.append(f"its peak tilt/α is {three.tilt_max_over_alpha:.3g} against the larger planar "
                     f"{worst:.3g} ({100 * rel:+.1f}%)")
    # what neither planar run has at all, said when it is more than a trace
    if three.twist_max_deg > TWIST_SAID_DEG:
        parts.append(f"it turned {three.twist_max_deg:.3g}° about its vertical (before it first passed α), which "
                     "neither planar run has")
    if three.wobble_deg > WOBBLE_SAID_DEG:
        parts.append(f"its tilt's axis swung {three.wobble_deg:.3g}° while it rocked (it rocked on a corner or rolled, "
                     "not about one edge), which neither planar run has")
    return {"verdict": verdict, "three_d": three.as_dict(), "planar": {"x": px, "y": py},
            "cannot_capture": CANNOT_CAPTURE,
            "where_it_parts": "Against both planar runs: " + "; ".join(parts) + ".",
            "planar_overturned": planar_over}


def two_components(runs: dict, system, motion, body: shape.RestingBody, azimuth: float, duration: float, *,
                   planar: dict | None = None) -> dict:
    """label → compare_3d of each engine's run of the pair (`runs`: label → Trajectory whose
    extras hold its orientation), against the exact model along each component alone (run
    once for all of them; `planar`: planar_runs' where the caller has them). `body`: the statue at
    rest (or box_body's block); `azimuth` (rad): the statue's direction along the first component."""
    alpha, least = alpha_table(body, azimuth)
    if planar is None:
        planar = planar_runs(system, motion, body if system.body is not None else None, azimuth, duration=duration)
    planar = {k: planar_numbers(tr) for k, tr in planar.items()}
    out = {}
    for label, tr in runs.items():
        three = measure_3d(tr.t, tr.extras["orientation"], alpha, least, u_y=tr.extras.get("u_y"))
        out[label] = dict(compare_3d(three, planar), azimuth_deg=math.degrees(azimuth) % 360.0,
                          transverse=motion.transverse.name)
    return out


def render(report: dict, label: str) -> str:
    """The report in words: verdict, the 3-D numbers, the two planar runs, what the planar
    model cannot capture and where the 3-D run parts from both."""
    d, px, py = report["three_d"], report["planar"]["x"], report["planar"]["y"]
    az = report["azimuth_deg"]
    return "\n".join([
        report["verdict"],
        f"{label}, 3-D (both components): total tilt max {d['tilt_max']:.4g} rad = {d['tilt_max_over_alpha']:.3f} α "
        f"(α {d['alpha_at_max']:.3f} rad of the edge it leaned towards, {d['direction_at_max_deg']:.0f}° from x), "
        f"overturned {'yes' if d['overturned'] else 'no'}, twist max {d['twist_max_deg']:.3g}°, wobble (the tilt "
        f"axis's swing) {d['wobble_deg']:.3g}°, base y max {100 * d['base_y_max']:.3g} cm",
        f"exact planar model, first component alone along x ({az:.0f}° on the statue): θmax/α "
        f"{px['theta_max_over_alpha']:.3f}, overturned {'yes' if px['overturned'] else 'no'} (α {px['alpha']:.3f})",
        f"exact planar model, second component alone along y ({(az + 90) % 360:.0f}° on the statue): θmax/α "
        f"{py['theta_max_over_alpha']:.3f}, overturned {'yes' if py['overturned'] else 'no'} (α {py['alpha']:.3f})",
        report["cannot_capture"],
        report["where_it_parts"]])
