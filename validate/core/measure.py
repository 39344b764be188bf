"""Measuring, the same way for every engine (model.md): a contact engine's raw history
(`RawHistory`) becomes the shared `Trajectory` here, never inside the engine.

- impacts: every sign change of θ is an impact; it is counted when the largest |θ| of
  the half-cycle ending in it exceeds `impact_threshold`·α;
- effective β per counted impact: the states `window` seconds outside the crossing
  mapped to θ = 0 with the rigid equations (finite differences across a soft contact
  are biased by about 1%); impacts that are not counted (contact chatter) carry NaN
  velocities, since their β measures the contact more than the block;
- uplifts: where |θ| leaves the band REST_FRACTION·α after resting;
- overturning: judged from the history by the run's rule, with the judge every engine
  shares (`isorock.analytic.overturning.judge_overturning`);
- sliding: a statue with friction (System.friction) slides as part of the model, and its
  slide (RawHistory.slide) is handed on to be compared; without friction the model assumes
  no slip, and a block that slid more than SLIDING_FRACTION·b is flagged (Status.SLID), as is
  a statue that walked off the engine's plate (kinematics.plate_edge).
"""
from __future__ import annotations

import math

import numpy as np

from ...analytic import isolator_map
from ...analytic.coefficients import beta as beta_closed_form, beta2 as beta2_closed_form, edge_impact
from ...analytic.hybrid import map_to_impact
from ...analytic.isolator_map import (MAPPED, PENDULUMS, image_after_impact, pendulum_forward, phase_at,
                                           reads_slider)
from ...analytic.kinematics import LYING, LYING_SLACK, plate_edge
from ...analytic.overturning import OVERTURN_RULES, PAST_ALPHA, judge_overturning
from ...analytic.motion import GroundMotion
from ...analytic.status import Status
from ...analytic.system import LINEAR, System
from ...analytic.trajectory import (DEFAULT_IMPACT_THRESHOLD, SLIDING_FRACTION, Impact, RawHistory, Trajectory,
                                        first_passage, half_cycles)

#: How far (s) before and after a sign change the states are taken: well outside the
#: contact transient of the default scenes (time constants of a few ms), and capped at
#: half the neighbouring half-cycles so a state never belongs to another half-cycle.
CONTACT_WINDOW = 0.03
#: The window in units of the block's 1/p: a contact engine whose contact time follows the
#: block (its time constant ∝ 1/p, docs/mujoco.md) leaves a transient ∝ 1/p too, so a
#: large, slow block needs a longer window than 30 ms (at H 10 m, λ 1.5 the 30 ms left
#: β 0.3 points off, measured). 0.079/p is 30 ms on the paper's block (p 2.64/s).
CONTACT_WINDOW_P = 0.079


def contact_window(system: System) -> float:
    """The window (s) for `system`: CONTACT_WINDOW_P/p, never shorter than CONTACT_WINDOW
    (engines whose contact time is fixed in seconds need that much at every size)."""
    return max(CONTACT_WINDOW, CONTACT_WINDOW_P / system.p)
#: The share of the window each side of a crossing that is the contact's transient (5 ms of
#: 30 ms: the default scenes' time constants are 0.6–1 ms): a non-linear isolator's element
#: must keep its phase from there to the mapped state (_mapped).
TRANSIENT_SHARE = 1 / 6
#: |θ| below this fraction of α counts as "down" when deriving the mode of a contact engine.
REST_FRACTION = 1e-3
#: The corner the block stands or rocks on moving along the base by more than SLIDING_FRACTION
#: of the half width b (analytic.trajectory: the same level a slide's onset is read at) is
#: sliding, not a contact's compliance (measured up to 4e-4·b at the defaults of both engines
#: under the report's pulses; a squat λ 0.89 block with friction 1 slides 0.6–0.7·b): a run of
#: a statue without friction then breaks the analytic model's no-sliding assumption and says
#: so in its status.
#: A statue's hull (a free body) that rolls, turns or drifts sideways while it rocks (before it
#: passes α) by more than this (rad of roll or yaw, or m across its plane) has left the plane the
#: model of its two edges rocks in: rocking on a corner of its footprint (shaken along a diagonal),
#: or turned by a centre of mass off the shaking plane. Its run is then outside the model, said in
#: its status, not judged, and its planar pivot slip no measure (it read such a roll as a slide).
#: Statues shaken across an edge stay within 4e-9 (docs/statues.md); the bust along its plinth's
#: diagonal rolls 0.17–1.5 rad.
PLANE_LEFT = 0.01


def measure(raw: RawHistory, motion: GroundMotion, *, impact_threshold: float = DEFAULT_IMPACT_THRESHOLD,
            window: float | None = None, overturn_rule: str = PAST_ALPHA,
            effective_beta: bool = True) -> Trajectory:
    """The shared Trajectory of a contact engine's raw history: modes from |θ|, every
    impact with model.md's `counted` flag, effective β of the counted ones, uplifts,
    and overturning by `overturn_rule`. effective_beta=False leaves every impact's
    velocities NaN: mapping them is a fifth of a short run's cost, and a summary
    (θmax/α, counted impacts, overturning, a campaign's row) reads none of them."""
    t, u, u_dot, theta, theta_dot = (np.asarray(x, dtype=float)
                                     for x in (raw.t, raw.u, raw.u_dot, raw.theta, raw.theta_dot))
    system = raw.system
    window = contact_window(system) if window is None else window
    rest = REST_FRACTION * system.alpha
    mode = np.where(theta > rest, 1, np.where(theta < -rest, -1, 0)).astype(np.int8)
    # a contact engine's block rests on its side through a compliant contact, a little short of π/2
    verdict = judge_overturning(t, theta, system.alpha, motion_end=motion.end_time, rule=overturn_rule,
                                side_angle=LYING - LYING_SLACK)
    overturned, overturn_time = verdict.overturned, verdict.time
    status, message = raw.status, raw.message
    if overturned and status == Status.COMPLETED:
        status, message = Status.OVERTURNED, verdict.message
    plane = raw.extras.get("out_of_plane_max")
    if (system.body is not None and motion.transverse is None and plane is not None and plane > PLANE_LEFT
            and not status.is_failure):
        status = Status.OUTSIDE_MODEL
        message = (f"the statue left its plane while it rocked (roll, yaw or sideways drift up to {plane:.3g}, more "
                   f"than {PLANE_LEFT:g}): it rocked on a corner or turned, which the planar model of its two edges "
                   "does not describe" + (f"; it also {message}" if overturned else ""))
    slip = raw.extras.get("pivot_slip_max")
    # with friction set, sliding is the model's too: compared (Trajectory.slide), not flagged
    if (system.friction is None and slip is not None and slip > SLIDING_FRACTION * system.b
            and not status.is_failure):
        status = Status.SLID
        message = (f"the block slid {slip * 1000:.3g} mm at its pivot (more than {SLIDING_FRACTION:g}·b): the "
                   f"analytic model assumes no sliding (friction above b/h = {1 / system.slenderness:.3g} is needed)"
                   + (f"; it also {message}" if overturned else ""))
    walked = float(np.max(np.abs(raw.slide))) if raw.slide is not None and raw.slide.size else 0.0
    if walked > plate_edge(system) and not status.is_failure:  # the model's base has no edge
        status = Status.SLID
        message = (f"the statue slid {walked:.3g} m, off the engine's plate (its edge {plate_edge(system):.3g} m "
                   "from the middle): the model's base has no edge, and the history past it is not the model's")
    # a non-linear isolator's map to θ = 0 starts in its element's phase, read from the row (a
    # bearing's and a double pendulum's from the element's slider, extras["isolator_slider"]:
    # without it, no β); a kind whose phase the rows do not tell (a ball in a cone) gets no β
    slider = raw.extras.get("isolator_slider")
    kind = system.isolator_kind  # LINEAR on a fixed base too
    mapped = effective_beta and (kind == LINEAR or (kind in MAPPED and (slider is not None
                                                                        or not reads_slider(system))))
    impacts = effective_impacts(system, motion, t, u, u_dot, theta, theta_dot,
                                impact_threshold=impact_threshold, window=window, mapped=mapped, slider=slider)
    return Trajectory(engine=raw.engine, system=system, t=t, u=u, u_dot=u_dot, theta=theta, theta_dot=theta_dot,
                      mode=mode, impacts=impacts, uplift_times=_uplifts(t, mode, window), overturned=overturned,
                      overturn_time=overturn_time, impact_threshold=impact_threshold, runtime_s=raw.runtime_s,
                      status=status, message=message, extras={**raw.extras, "overturn_rule": overturn_rule},
                      slide=raw.slide, slide_dot=raw.slide_dot)


def _uplifts(t, mode, rest_time):
    """Times the block leaves the rest band. Every impact passes through the band, so
    leaving it the other way after less than `rest_time` is rocking, not an uplift;
    leaving it the same way, or after resting longer, is."""
    out = []
    last_sign, left_at = 0, None  # sign before the band, and when the block entered it
    prev = 0
    for i in np.nonzero(np.diff(mode.astype(np.int64), prepend=0) != 0)[0]:
        m = int(mode[i])
        if m == 0:
            last_sign, left_at = prev, t[i]
        elif prev == 0:
            rested = left_at is None or t[i] - left_at >= rest_time
            if last_sign == 0 or last_sign == m or rested:
                out.append(float(t[i]))
        prev = m
    return tuple(out)


def effective_impacts(system, motion, t, u, u_dot, theta, theta_dot, *, impact_threshold=DEFAULT_IMPACT_THRESHOLD,
                      window=CONTACT_WINDOW, mapped: bool = True, slider=None) -> tuple[Impact, ...]:
    """One Impact per sign change of θ. Counted ones (model.md's rule) carry the
    rigid-model images at θ = 0 of the states `window` seconds before and after the
    crossing (mapped=False: they too carry NaN); the others NaN velocities. `slider`: a
    bilinear bearing's slider position per row (its phase is read from it)."""
    changes = half_cycles(theta)
    out = []
    for n, (i, peak) in enumerate(changes):
        t_cross = _crossing_time(t, theta, i)
        counted = peak > impact_threshold * system.alpha
        thd_pre = ud_pre = thd_post = ud_post = math.nan
        if counted and mapped:
            t_prev = t[changes[n - 1][0]] if n > 0 else t[0]
            t_next = t[changes[n + 1][0]] if n + 1 < len(changes) else t[-1]
            t_before = t_cross - min(window, 0.5 * (t_cross - t_prev))
            if system.isolator_kind in PENDULUMS:  # its base may break loose or stick before the impact
                pre = _pendulum_pre(system, motion, t, u, u_dot, theta, theta_dot, t_before, t_cross, window, slider)
            else:
                pre = _mapped(system, motion, t, u, u_dot, theta, theta_dot, t_before, backward=False, window=window,
                              slider=slider, t_cross=t_cross)
            t_after = t_cross + min(window, 0.5 * (t_next - t_cross))
            if system.isolator_kind in PENDULUMS:  # the impact kicks the base loose: forward, as the model moves it
                post = _pendulum_post(system, motion, t, u, theta_dot, i, t_cross, t_after, pre, slider)
            else:
                post = _mapped(system, motion, t, u, u_dot, theta, theta_dot, t_after, backward=True, window=window,
                               slider=slider, t_cross=t_cross)
            if pre:
                thd_pre, ud_pre = pre
            if post:
                thd_post, ud_post = post
        out.append(Impact(t=float(t_cross), theta_dot_pre=thd_pre, theta_dot_post=thd_post,
                          u_dot_pre=ud_pre, u_dot_post=ud_post, continued=True, amplitude=float(peak),
                          counted=counted))
    return tuple(out)


def _crossing_time(t, theta, i):
    """Linear interpolation of the zero of θ between samples i−1 and i."""
    a, b = theta[i - 1], theta[i]
    if a == b:
        return float(t[i])
    return float(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b))


def _pendulum_pre(system, motion, t, u, u_dot, theta, theta_dot, t_before, t_cross, window, slider=None):
    """(θ̇⁻, u̇⁻, phase, u_p) of a rigid slider's impact: the engine's state at the row a window
    before the crossing, its slider's phase read off the row (isolator_map.phase_at; a double
    pendulum's element slider from `slider`), run forward by the rigid model, whose slider sticks
    and slips as the model's does, to θ = 0; it must land near the engine's crossing (None
    otherwise: not this impact)."""
    k = int(np.clip(np.searchsorted(t, t_before), 0, t.size - 1))
    if theta[k] == 0 or t[k] >= t_cross:
        return None
    u_p = 0.0 if slider is None else float(slider[k])
    phase = phase_at(system, float(u_dot[k]), u=float(u[k]), u_p=u_p)
    state = (float(u[k]), 0.0 if phase == 0 else float(u_dot[k]), float(theta[k]), float(theta_dot[k]))
    landed = pendulum_forward(system, motion, float(t[k]), state, float(t[k]) + 5 * window + 0.05, phase=phase,
                              u_p=u_p, to_landing=True)
    if landed is None or abs(landed[0] - t_cross) > window:
        return None
    return landed[1][3], landed[1][1]


def _pendulum_post(system, motion, t, u, theta_dot, i, t_cross, t_after, pre, slider=None):
    """(θ̇⁺, u̇⁺) of a rigid slider's impact: the rigid model run forward from the crossing
    (isolator_map.image_after_impact) to the engine's row a window after it, from the
    pre-impact image `pre` (none without it), the base's position at the crossing and, on a
    double pendulum, its element's slider and regime there (from `slider`)."""
    if not pre:
        return None
    k = int(np.clip(np.searchsorted(t, t_after), 0, t.size - 1))
    if t[k] <= t_cross:
        return None

    def at_cross(x):
        return float(x[i - 1] + (x[i] - x[i - 1]) * (t_cross - t[i - 1]) / (t[i] - t[i - 1]))
    u_cross = at_cross(u)
    thd_pre, ud_pre = pre
    u_p = 0.0 if slider is None else at_cross(slider)
    phase = phase_at(system, ud_pre, u=u_cross, u_p=u_p)
    return image_after_impact(system, motion, t_cross, u_cross, ud_pre, thd_pre, float(t[k]), float(theta_dot[k]),
                              phase_pre=phase, u_p=u_p)


def _mapped(system, motion, t, u, u_dot, theta, theta_dot, t_at, *, backward, window, slider=None, t_cross=None):
    k = int(np.clip(np.searchsorted(t, t_at), 0, t.size - 1))
    if theta[k] == 0:
        return None
    # the rigid image lands close to the contact engine's crossing, `window` away: a few
    # windows bound the search (an image that does not land there is not this impact)
    state, horizon = (u[k], u_dot[k], theta[k], theta_dot[k]), 5 * window + 0.05
    if system.isolator_kind == LINEAR:  # a fixed base too
        r = map_to_impact(system, motion, float(t[k]), state, backward=backward, horizon=horizon)
    else:
        def phase(i):
            j = max(i - 1, 0)
            step = None if slider is None else float(slider[i] - slider[j])
            return isolator_map.phase_at(system, float(u_dot[i]), step, float(u[i] - u[j]))
        # the map holds the phase of row k: it must be the phase of every row between k and the
        # impact in the engine's own history, outside the contact's transient (TRANSIENT_SHARE of
        # the window each side of the crossing, where the impact itself kicks the base): a pinned
        # base kicked loose by the impact and stuck again by k is no single phase to map in
        edge = TRANSIENT_SHARE * window
        if t_cross is None:
            rows = range(k, k + 1)
        elif t[k] < t_cross:
            rows = range(k, max(k + 1, int(np.searchsorted(t, t_cross - edge))))
        else:
            rows = range(min(k, int(np.searchsorted(t, t_cross + edge, side="right"))), k + 1)
        held = phase(k)
        if any(phase(i) != held for i in rows):
            return None
        r = isolator_map.map_to_impact(system, motion, float(t[k]), state, phase=held,
                                       u_p=0.0 if slider is None else float(slider[k]), backward=backward,
                                       horizon=horizon)
    return None if r is None else (r[1], r[2])


#: A statue has started to slide once it has moved this fraction of its half width b on its
#: base: read off every engine's history alike (the analytic slip event is exact, a contact
#: engine's soft friction creeps before it slips; measured up to 4e-4·b at the no-slip
#: defaults, SLIDING_FRACTION's note).
SLIDE_ONSET_FRACTION = SLIDING_FRACTION
#: The modes a run passes through are read with the rest band of θ (REST_FRACTION·α) and a
#: slide speed of SLIDE_SPEED_FRACTION·b·p (p the block's frequency parameter: at that speed
#: the block moves 1% of b in its own time unit 1/p), and a mode counts once it has lasted
#: MODE_HOLD/p: shorter ones are a contact's transients (an impact's few time constants).
SLIDE_SPEED_FRACTION = 0.01
MODE_HOLD = 0.05


def slide_onset(traj: Trajectory, fraction: float = SLIDE_ONSET_FRACTION) -> float | None:
    """First time (s) the statue has slid `fraction`·b from where it stood (trajectory.first_passage);
    None if never (or where the run carries no slide)."""
    if traj.slide is None:
        return None
    return first_passage(traj.t, np.asarray(traj.slide) - traj.slide[0], fraction * traj.system.b)


def mode_sequence(traj: Trajectory) -> tuple[str, ...]:
    """The contact modes a run reached, in the order it first reached each ("slide", "rock",
    "slide-rock"; resting is where every run starts): each read at every sample from the
    tilt (beyond REST_FRACTION·α) and the slide's speed (beyond SLIDE_SPEED_FRACTION·b·p), and
    counted once held for MODE_HOLD/p. The same reading for every engine (docs/sliding.md)."""
    system = traj.system
    t = np.asarray(traj.t, dtype=float)
    rocks = np.abs(traj.theta) > REST_FRACTION * system.alpha
    if traj.slide_dot is None:
        slides = np.zeros(t.size, dtype=bool)
    else:
        slides = np.abs(traj.slide_dot) > SLIDE_SPEED_FRACTION * system.b * system.p
    code = rocks.astype(int) * 2 + slides.astype(int)  # 0 rest, 1 slide, 2 rock, 3 slide-rock
    names = {1: "slide", 2: "rock", 3: "slide-rock"}
    hold = MODE_HOLD / system.p
    seen: list[str] = []
    starts = np.flatnonzero(np.diff(code, prepend=-1) != 0)
    ends = np.append(starts[1:], t.size)
    for a, b in zip(starts, ends):
        c = int(code[a])
        if c and names[c] not in seen and t[b - 1] - t[a] >= hold:
            seen.append(names[c])
    return tuple(seen)


def impact_closed_forms(system, impact=None) -> tuple[float, float]:
    """(β, β₂) of the closed forms for one impact: the paper's for the block; for a statue of
    two edges (System.body), those of the edge it rocked on (the side opposite to θ̇⁻; with no
    impact, the edge it tips about first) onto the other (coefficients.edge_impact). β₂ in m
    (u̇⁺ = u̇⁻ + β₂ θ̇⁻, model.md); 0 on a fixed base."""
    if system.asymmetric:
        s = system.body.weaker_side if impact is None else (-1 if impact.theta_dot_pre > 0 else 1)
        return edge_impact(system.mass, None if system.fixed_base else system.base_mass, system.h, system.inertia,
                           system.lever(s), system.lever(-s))
    b2 = 0.0 if system.fixed_base else beta2_closed_form(system.slenderness, system.mu, system.h)
    return beta_closed_form(system.slenderness, system.mu), b2


def beta_errors(traj: Trajectory, n: int | None = None) -> list[float]:
    """Relative error of each counted impact's effective β against its closed form
    (impact_closed_forms: each edge its own for a statue of two)."""
    errs = [i.beta / impact_closed_forms(traj.system, i)[0] - 1 for i in traj.counted_impacts]
    return errs[:n] if n is not None else errs


__all__ = ["measure", "effective_impacts", "beta_errors", "impact_closed_forms", "slide_onset", "mode_sequence", "CONTACT_WINDOW", "contact_window", "REST_FRACTION", "OVERTURN_RULES"]
