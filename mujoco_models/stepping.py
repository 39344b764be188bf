"""Stepping the MuJoCo scene: `mujoco.rollout` runs the loop in C, chunk by chunk, and
the states become a RawHistory (measured outside the engine, by the registry).

The ground motion is applied exactly as generalized forces in the (translating) ground
frame: −m ẍg on the block's x dof and −m_b ẍg on the base's. A force is held over a
step, so ẍg is taken at the step's middle: the impulse it gives is then right to
second order (taken at the step's start it lags by dt/2). PyBullet does the same.

Outputs follow model.md: u (m) is the base displacement relative to the ground, θ (rad)
the rotation about +y (θ > 0 rocks about corner O at x = +b). A run stops by the shared
rules of `isorock.analytic.kinematics.first_stop` (a non-finite state, the block lying on
its side, or falling on a fixed base after the motion); MuJoCo's auto-reset is off, so a
blow-up cannot pass silently.

`simulate_many` runs many cases (a campaign's chunk, an ensemble) exactly as `simulate`
runs each: one compiled scene per distinct system, and runs stepped side by side by
Python threads, since `mujoco.rollout` releases the GIL while it steps.
"""
from __future__ import annotations

import math
import re
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager

import mujoco
import numpy as np
from mujoco import rollout

from isorock.analytic import kinematics
from isorock.analytic.motion import GroundMotion
from isorock.analytic.protocol import run_inputs
from isorock.analytic.status import Status
from isorock.analytic.system import System
from isorock.analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, RawHistory, counted_sign_changes

from .scene import build_model
from .settings import Settings

ENGINE = "mujoco"
#: Steps per call of mujoco.rollout: the progress callback and the stop rules run
#: between calls. The warm start is carried across calls, so the split does not change
#: the result (tested).
CHUNK_STEPS = 20_000


class Layout:
    """Where the scene's quantities sit in qpos / qvel and in rollout's state rows."""

    def __init__(self, model: mujoco.MjModel, system: System, joint: str):
        self.nq, self.nv = model.nq, model.nv
        self.nstate = mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS)
        self.free = joint == "free"
        self.base_v = None if system.fixed_base else model.jnt_dofadr[model.joint("base_slide").id]
        self.base_q = None if system.fixed_base else model.jnt_qposadr[model.joint("base_slide").id]
        if self.free:
            jid = model.joint("block_free").id
            self.bq, self.bv = model.jnt_qposadr[jid], model.jnt_dofadr[jid]
            self.x_v = self.bv  # free joint: linear velocity first, in the world frame
        else:
            self.xq, self.zq, self.thq = (model.jnt_qposadr[model.joint(n).id]
                                           for n in ("block_x", "block_z", "block_theta"))
            self.x_v, self.thv = (model.jnt_dofadr[model.joint(n).id] for n in ("block_x", "block_theta"))

    def initial_state(self, model, system: System, theta0: float) -> np.ndarray:
        """A rollout state row at t = 0: at rest, tilted by θ0 about the corner it rocks on."""
        qpos = model.qpos0.copy()
        x, z = kinematics.tilted_centroid(system, theta0)
        if self.free:
            qpos[self.bq:self.bq + 3] = (x, 0.0, z)
            qpos[self.bq + 3:self.bq + 7] = (math.cos(theta0 / 2), 0.0, math.sin(theta0 / 2), 0.0)
        else:
            qpos[self.xq], qpos[self.zq], qpos[self.thq] = x, z - system.h, theta0
        state = np.zeros(self.nstate)
        state[1:1 + self.nq] = qpos
        return state

    def forces(self, system: System, xg: np.ndarray) -> np.ndarray:
        """qfrc_applied rows for the ground accelerations ẍg (one per step)."""
        f = np.zeros((xg.size, self.nv))
        f[:, self.x_v] = -system.mass * xg
        if self.base_v is not None:
            f[:, self.base_v] = -system.base_mass * xg
        return f

    def histories(self, system: System, states: np.ndarray) -> dict:
        """t, u, u̇, θ, θ̇ and the centroid's x and z (and out-of-plane tilt with the free
        joint) from rollout state rows."""
        t = states[:, 0]
        qpos = states[:, 1:1 + self.nq]
        qvel = states[:, 1 + self.nq:1 + self.nq + self.nv]
        n = t.size
        if self.base_q is None:
            u, u_dot = np.zeros(n), np.zeros(n)
        else:
            u, u_dot = qpos[:, self.base_q].copy(), qvel[:, self.base_v].copy()
        out = {"t": t.copy(), "u": u, "u_dot": u_dot}
        if self.free:
            w, x, y, z = qpos[:, self.bq + 3:self.bq + 7].T
            theta, roll, yaw = kinematics.tilts_from_quaternion(w, x, y, z)
            out["theta"] = theta
            out["theta_dot"] = qvel[:, self.bv + 4].copy()  # angular velocity about the body y axis
            out["x"], out["z"] = qpos[:, self.bq].copy(), qpos[:, self.bq + 2].copy()
            out["out_of_plane"] = np.maximum.reduce([np.abs(qpos[:, self.bq + 1]), np.abs(roll), np.abs(yaw)])
        else:
            out["theta"] = qpos[:, self.thq].copy()
            out["theta_dot"] = qvel[:, self.thv].copy()
            out["x"], out["z"] = qpos[:, self.xq].copy(), system.h + qpos[:, self.zq]
        return out


@contextmanager
def warnings_as_status():
    """MuJoCo's warnings (a blown-up state, "Nan, Inf or huge value in QACC", a full
    contact buffer) collected as messages while the body runs, instead of being printed
    and written to MUJOCO_LOG.TXT in the user's working directory; the run reports the
    first one as its failure. The handler is process-wide, so the previous one is restored."""
    messages: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(messages.append)
    try:
        yield messages
    finally:
        mujoco.set_mju_user_warning(previous)


def warning_failure(messages: list[str], data: mujoco.MjData) -> tuple[str, float] | None:
    """(message, time) of the first MuJoCo warning of a run, or None: any warning means the
    history after it is not the physics (MuJoCo's auto-reset is off, so the bad state stays)."""
    if not messages and not any(w.number for w in data.warning):
        return None
    text = messages[0] if messages else "MuJoCo raised a warning"
    found = re.search(r"Time = ([0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?)", text)
    return text, float(found.group(1)) if found else math.nan


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """Simulate the scene from t = 0 to `duration` (s; default: the motion's end + 5 s,
    or 10 s without motion) from rest, tilted by `theta0` (rad) about its corner.
    progress: optional callable(t, duration), called between rollout chunks about
    once a second."""
    settings = settings or Settings()
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD, settings=settings)
    model = build_model(system, settings)
    return run_model(model, system, motion, settings=settings, duration=duration, theta0=theta0,
                     progress=progress)


def run_model(model: mujoco.MjModel, system: System, motion: GroundMotion, *, settings: Settings,
              duration: float, theta0: float = 0.0, progress=None, chunk_steps: int | None = None) -> RawHistory:
    """`simulate` on an already compiled scene (for measuring variants of the model)."""
    with warnings_as_status() as warnings:
        return _run(model, system, motion, settings, duration, theta0, progress, chunk_steps, warnings)


def _run(model, system, motion, settings, duration, theta0, progress, chunk_steps, warnings) -> RawHistory:
    """One run; MuJoCo's warnings arrive in the list `warnings` (the caller's handler)."""
    start = time.perf_counter()
    lay = Layout(model, system, settings.joint)
    dt = model.opt.timestep
    nstep = int(math.floor(duration / dt + 1e-9))
    if settings.impact_timestep is not None:
        from .event_resolved import run_event_resolved
        return run_event_resolved(model, system, motion, settings, lay, nstep, theta0, progress, start,
                                  duration, warnings)

    chunk_steps = chunk_steps or CHUNK_STEPS
    data = mujoco.MjData(model)
    forces = lay.forces(system, np.asarray(motion((np.arange(nstep) + 0.5) * dt), dtype=float))
    state0 = lay.initial_state(model, system, theta0)
    warm = np.zeros(lay.nv)
    rows = [state0[None, :]]
    throttle = kinematics.Throttle(progress, duration)
    rows, status, message, stop_reason = _roll(model, data, lay, system, motion, forces, state0, warm, rows,
                                               nstep, chunk_steps, dt, throttle, warnings)
    runtime = time.perf_counter() - start
    return raw_history(lay, system, np.concatenate(rows), dt, runtime, status, message, stop_reason)


def simulate_many(runs, *, settings: Settings | None = None, threads: int = 1) -> list:
    """Many runs, each exactly as `simulate` makes it: `runs` is a sequence of (system,
    motion, duration, theta0), as `simulate` takes them; returns, per run, its RawHistory
    or the exception it raised (one bad case is that case's result, not a lost batch).

    A scene is compiled once per distinct system (a chunk of a campaign shares one or
    two), and `threads` runs step side by side, each with its own MjData: rollout
    releases the GIL while it steps, so a process uses that many cores. Each run's steps,
    forces, warm starts and stop rules are those of `simulate`, so each history is
    identical to a run made alone (tested). MuJoCo reports warnings through one
    process-wide handler, which cannot say which thread's run raised one: if any run
    raised one, every run of the batch is made again alone, so that each run's failure
    is its own, as `simulate` reports it."""
    settings = settings or Settings()
    runs = list(runs)
    models: dict = {}

    def prepare(run):
        system, motion, duration, theta0 = run
        motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD,
                                      settings=settings)
        if system not in models:
            models[system] = build_model(system, settings)
        return models[system], system, motion, duration, theta0

    prepared = []
    for run in runs:
        try:
            prepared.append(prepare(run))
        except Exception as e:  # noqa: BLE001 — returned as this run's result
            prepared.append(e)

    def one(item, warnings):
        if isinstance(item, Exception):
            return item
        model, system, motion, duration, theta0 = item
        try:
            return _run(model, system, motion, settings, duration, theta0, None, None, warnings)
        except Exception as e:  # noqa: BLE001
            return e

    def alone(item):
        with warnings_as_status() as own:
            return one(item, own)

    if threads <= 1 or len(prepared) <= 1:
        return [alone(item) for item in prepared]
    with warnings_as_status() as warnings:
        with ThreadPoolExecutor(max_workers=min(threads, len(prepared))) as pool:
            out = list(pool.map(lambda item: one(item, warnings), prepared))
        warned = bool(warnings)
    return [alone(item) for item in prepared] if warned else out


def _roll(model, data, lay, system, motion, forces, state0, warm, rows, nstep, chunk_steps, dt, throttle, warnings):
    status, message, stop_reason = Status.COMPLETED, "reached the end time", None
    done = 0
    while done < nstep:
        n = min(chunk_steps, nstep - done)
        state, _ = rollout.rollout(model, data, state0, forces[done:done + n][None],
                                   control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED,
                                   initial_warmstart=warm)
        chunk = state[0]
        t0 = done * dt
        done += n
        failure = warning_failure(warnings, data)
        if failure is not None:
            text, at = failure
            keep = int(np.searchsorted(t0 + dt * np.arange(1, n + 1), at)) if math.isfinite(at) else 0
            rows.append(chunk[:keep])
            status, message = Status.FAILED, f"MuJoCo: {text} (try a smaller timestep)"
            break
        k, reason = stop_in(lay, system, chunk, t0 + dt * np.arange(1, n + 1), motion)
        if reason == "non-finite":
            rows.append(chunk[:k])
            status = Status.FAILED
            message = (f"the state stopped being finite at t = {t0 + (k + 1) * dt:.6g} s; "
                       "try a smaller timestep or a longer solref timeconst")
            break
        if reason is not None:
            rows.append(chunk[:k + 1])
            stop_reason = reason
            break
        rows.append(chunk)
        state0 = chunk[-1]
        warm = data.qacc_warmstart.copy()
        throttle(done * dt)
    return rows, status, message, stop_reason


def stop_in(lay: Layout, system: System, chunk: np.ndarray, t: np.ndarray, motion: GroundMotion):
    """kinematics.first_stop over a chunk of rollout state rows (at times t)."""
    finite = np.all(np.isfinite(chunk), axis=1)
    h = lay.histories(system, np.where(finite[:, None], chunk, 0.0))
    return kinematics.first_stop(t, h["theta"], h["theta_dot"], finite, system=system,
                                 motion_end=motion.end_time)


def raw_history(lay, system, states, dt, runtime, status, message, stop_reason) -> RawHistory:
    hist = lay.histories(system, states)
    t = np.arange(hist["t"].size) * dt  # MuJoCo's time sums dt and drifts by round-off
    counted = counted_sign_changes(hist["theta"], system.alpha, DEFAULT_IMPACT_THRESHOLD)
    extras = kinematics.contact_extras(
        system, x_centroid=hist["x"], z_centroid=hist["z"], theta=hist["theta"], u=hist["u"],
        counted_from=counted[0][0] if counted else None, out_of_plane=hist.get("out_of_plane"))
    return RawHistory(engine=ENGINE, system=system, t=t, u=hist["u"], u_dot=hist["u_dot"], theta=hist["theta"],
                      theta_dot=hist["theta_dot"], status=status, message=message, runtime_s=runtime,
                      extras=extras, stop_reason=stop_reason)
