"""Event-resolved stepping of the MuJoCo scene (opt-in: `Settings.impact_timestep`,
`settings.event_resolved_settings`): coarse steps in flight and at rest, fine steps
around impacts. Measured in docs/mujoco.md: β 0.47% at θ0 = α/2 and 4× faster on a
40 s record, but θmax/α 0.035 low and a softer rest, so it is not the default.
"""
from __future__ import annotations

import math
import time

import mujoco
import numpy as np
from mujoco import rollout

from ..analytic import kinematics
from ..analytic.status import Status
from ..analytic.trajectory import RawHistory

from .scene import scene_text
from .settings import Settings
from .state import raw_history, stop_in, vertical_at, warning_failure

#: Fine steps start when the block would reach θ = 0 within IMPACT_ZONE coarse steps at
#: its present θ̇ (and |θ̇| is above IMPACT_MIN_RATE, rad/s: a block at rest stays on
#: coarse steps) and end IMPACT_SETTLE seconds after the last sign change of θ. A coarse
#: rollout call runs about as far as the next θ = 0 while rocking (|θ/θ̇|, at least 4
#: steps), COARSE_CHUNK·8 steps at most (at rest); steps past the start of a fine zone
#: are recomputed.
IMPACT_ZONE = 2.0
IMPACT_MIN_RATE = 1e-3
IMPACT_SETTLE = 0.01
COARSE_CHUNK = 64


def run_event_resolved(model, system, motion, settings, lay, nstep, theta0, progress, start,
                       duration, warnings) -> RawHistory:
    """Coarse steps (settings.timestep) in flight and at rest, fine steps
    (settings.impact_timestep) around impacts; the history keeps the coarse grid.

    Semi-implicit Euler carries the velocity of the half step behind the position, so
    a coarse state's velocity is converted (± a·dt/2) where the step size changes, and
    the history reports a coarse row's velocity as the mean of its half steps (the
    leapfrog velocity, second order); fine rows are reported as they are."""
    dt, dtf = settings.timestep, settings.impact_timestep
    n_per = int(round(dt / dtf))
    k_stiff, damping = settings.solref
    fine_model = mujoco.MjModel.from_xml_string(scene_text(system, Settings(**{
        **{f: getattr(settings, f) for f in settings.__dataclass_fields__},
        "timestep": dtf, "solref": (k_stiff, damping * n_per), "impact_timestep": None})))
    data_c, data_f = mujoco.MjData(model), mujoco.MjData(fine_model)
    spec = mujoco.mjtState.mjSTATE_QFRC_APPLIED
    v0 = 1 + lay.nq
    vel = slice(v0, v0 + lay.nv)

    def forces(t0, h, n):  # ẍg (and üv) at each step's middle, as in stepping.run_model
        mids = t0 + (np.arange(n) + 0.5) * h
        return lay.forces(system, np.asarray(motion(mids), dtype=float), vertical_at(motion, mids))

    def theta_rate(states):
        h = lay.histories(system, states)
        return h["theta"], h["theta_dot"]

    state = lay.initial_state(model, system, theta0)
    rows, coarse = [state.copy()], [False]
    warm = np.zeros(lay.nv)
    k = 0
    last_cross = -math.inf
    status, message, stop_reason = Status.COMPLETED, "reached the end time", None
    throttle = kinematics.Throttle(progress, duration)
    while k < nstep:
        th, thd = theta_rate(state[None, :])
        t_k = k * dt
        fine = (t_k - last_cross < IMPACT_SETTLE
                or (abs(thd[0]) > IMPACT_MIN_RATE and abs(th[0]) < IMPACT_ZONE * abs(thd[0]) * dt))
        start_state = state.copy()
        if coarse[-1] != (not fine) and len(rows) >= 2:
            acc = (rows[-1][vel] - rows[-2][vel]) / dt
            start_state[vel] += acc * dt / 2 if fine else -acc * dt / 2
        if fine:
            m = min(int(math.ceil(IMPACT_ZONE + IMPACT_SETTLE / dt)) + 1, nstep - k)
            out, _ = rollout.rollout(fine_model, data_f, start_state, forces(t_k, dtf, m * n_per)[None],
                                     control_spec=spec, initial_warmstart=warm)
            seg = out[0]
            warm = data_f.qacc_warmstart.copy()
            th_f, thd_f = theta_rate(seg)
            prev = np.concatenate(([th[0]], th_f))
            flips = np.nonzero((np.sign(prev[1:]) * np.sign(prev[:-1]) < 0) & (np.abs(thd_f) > IMPACT_MIN_RATE))[0]
            if flips.size:
                last_cross = t_k + (flips[-1] + 1) * dtf
            chunk = seg[n_per - 1::n_per]
            chunk_coarse = [False] * len(chunk)
        else:
            if abs(thd[0]) > IMPACT_MIN_RATE:  # rocking: about as far as the next θ = 0
                ahead = abs(th[0] / thd[0]) / dt * (0.7 if th[0] * thd[0] < 0 else 1.0)
                m = int(min(max(ahead, 4), 8 * COARSE_CHUNK))
            else:
                m = 8 * COARSE_CHUNK
            m = min(m, nstep - k)
            out, _ = rollout.rollout(model, data_c, start_state, forces(t_k, dt, m)[None],
                                     control_spec=spec, initial_warmstart=warm)
            chunk = out[0]
            warm = data_c.qacc_warmstart.copy()
            th_c, thd_c = theta_rate(chunk)
            zone = (np.abs(thd_c) > IMPACT_MIN_RATE) & (np.abs(th_c) < IMPACT_ZONE * np.abs(thd_c) * dt)
            prev = np.concatenate(([th[0]], th_c))
            flipped = (np.sign(prev[1:]) * np.sign(prev[:-1]) < 0) & (np.abs(thd_c) > IMPACT_MIN_RATE)
            stop = np.nonzero(zone | flipped)[0]
            if stop.size:  # keep the chunk up to the first state inside the zone
                chunk = chunk[:stop[0] + 1]
                if flipped[stop[0]]:
                    last_cross = t_k + (stop[0] + 1) * dt
            chunk_coarse = [True] * len(chunk)
        failure = warning_failure(warnings, data_f if fine else data_c)
        if failure is not None:
            status, message = Status.FAILED, f"MuJoCo: {failure[0]} (try a smaller timestep)"
            break
        k_stop, reason = stop_in(lay, system, chunk, t_k + dt * np.arange(1, len(chunk) + 1), motion)
        if reason == "non-finite":
            rows.extend(chunk[:k_stop])
            coarse.extend(chunk_coarse[:k_stop])
            status = Status.FAILED
            message = (f"the state stopped being finite near t = {t_k + (k_stop + 1) * dt:.6g} s; "
                       "try a smaller timestep")
            break
        if reason is not None:
            rows.extend(chunk[:k_stop + 1])
            coarse.extend(chunk_coarse[:k_stop + 1])
            stop_reason = reason
            break
        rows.extend(chunk)
        coarse.extend(chunk_coarse)
        k += len(chunk)
        state = chunk[-1].copy()
        throttle(k * dt)
    runtime = time.perf_counter() - start

    states = np.array(rows)
    coarse = np.array(coarse)
    v = states[:, vel]
    rep = v.copy()
    n = len(states)
    both = coarse[1:n - 1] & coarse[2:n]  # this row and the next from coarse steps: leapfrog mean
    idx = np.nonzero(both)[0] + 1
    rep[idx] = 0.5 * (v[idx] + v[idx + 1])
    tail = np.nonzero(coarse[1:] & ~np.concatenate((both, [False])) & coarse[:-1])[0] + 1
    rep[tail] = 1.5 * v[tail] - 0.5 * v[tail - 1]  # coarse row followed by a fine one (or the end)
    states = states.copy()
    states[:, vel] = rep
    return raw_history(lay, system, motion, states, dt, runtime, status, message, stop_reason)
