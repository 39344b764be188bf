"""The MuJoCo scene's state and what a run's history is made of, shared by both stepping
schemes (`stepping.py`, `event_resolved.py`): where θ, u and the block's centroid sit in
rollout's state rows (`Layout`), MuJoCo's warnings as a run's failure, the shared stop
rules over a chunk of rows, and the RawHistory a run returns."""
from __future__ import annotations

import math
import re
import threading
from contextlib import contextmanager

import mujoco
import numpy as np

from ..analytic import kinematics
from ..analytic.motion import GroundMotion
from ..analytic.isolator_parts import pendulum_puck
from ..analytic.rest_phase import BLOCK
from ..analytic.system import System
from ..analytic.trajectory import RawHistory

ENGINE = "mujoco"


class Layout:
    """Where the scene's quantities sit in qpos / qvel and in rollout's state rows."""

    def __init__(self, model: mujoco.MjModel, system: System, joint: str, transverse: bool = False):
        self.nq, self.nv = model.nq, model.nv
        # two horizontal components (scene_text(transverse=True)): the body's y dof and the base's y joint
        self.transverse = transverse
        y_joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "base_slide_y")
        self.base_yv = None if y_joint < 0 else model.jnt_dofadr[y_joint]
        self.base_yq = None if y_joint < 0 else model.jnt_qposadr[y_joint]
        self.nstate = mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS)
        self.free = joint == "free"
        self.base_v = None if system.fixed_base else model.jnt_dofadr[model.joint("base_slide").id]
        self.base_q = None if system.fixed_base else model.jnt_qposadr[model.joint("base_slide").id]
        # a bilinear bearing's slider body (scene._isolator_element): it moves in the ground's
        # frame too, so it takes its own −m_s ẍg
        slider = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "slider_slide")
        self.slider_v = None if slider < 0 else model.jnt_dofadr[slider]
        self.slider_q = None if slider < 0 else model.jnt_qposadr[slider]
        self.slider_mass = 0.0 if slider < 0 else float(model.body_mass[model.jnt_bodyid[slider]])
        # a pendulum's friction puck under a pair (scene._pair_pendulum): held down so that the
        # floor pushes it up by the model's W = M·g, its own weight included
        puck = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "puck_z")
        self.puck_v = None if puck < 0 else model.jnt_dofadr[puck]
        self.puck_hold = 0.0 if puck < 0 else pendulum_puck(system).hold
        if self.free:
            jid = model.joint("block_free").id
            self.bq, self.bv = model.jnt_qposadr[jid], model.jnt_dofadr[jid]
            self.x_v, self.z_v = self.bv, self.bv + 2  # free joint: linear velocity first, in the world frame
        else:
            self.xq, self.zq, self.thq = (model.jnt_qposadr[model.joint(n).id]
                                           for n in ("block_x", "block_z", "block_theta"))
            self.x_v, self.z_v, self.thv = (model.jnt_dofadr[model.joint(n).id]
                                            for n in ("block_x", "block_z", "block_theta"))

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

    def forces(self, system: System, xg: np.ndarray, zg: np.ndarray | None = None,
               yg: np.ndarray | None = None) -> np.ndarray:
        """qfrc_applied rows for the ground accelerations ẍg (one per step) and, with a vertical
        motion, üv (`zg`): the block alone feels −m·üv, on its z dof (the base is carried
        rigidly up and down with the ground, so its reaction goes to the ground). With a second
        horizontal component ÿg (`yg`), the same as ẍg along y: −m·ÿg on the body's y dof (the
        free joint's second linear dof, world frame) and −m_b·ÿg on the base's y joint."""
        f = np.zeros((xg.size, self.nv))
        f[:, self.x_v] = -system.mass * xg
        if yg is not None:
            f[:, self.x_v + 1] = -system.mass * yg
            if self.base_yv is not None:
                f[:, self.base_yv] = -system.base_mass * yg
        if zg is not None:
            f[:, self.z_v] = -system.mass * zg
        if self.base_v is not None:
            f[:, self.base_v] = -system.base_mass * xg
        if self.slider_v is not None:
            f[:, self.slider_v] = -self.slider_mass * xg
        if self.puck_v is not None:
            f[:, self.puck_v] = self.puck_hold
        return f

    def histories(self, system: System, states: np.ndarray) -> dict:
        """t, u, u̇, θ, θ̇ and the centroid's x, ẋ and z (and out-of-plane tilt with the free
        joint) from rollout state rows."""
        t = states[:, 0]
        qpos = states[:, 1:1 + self.nq]
        qvel = states[:, 1 + self.nq:1 + self.nq + self.nv]
        n = t.size
        if self.base_q is None:
            u, u_dot = np.zeros(n), np.zeros(n)
        else:
            u, u_dot = qpos[:, self.base_q].copy(), qvel[:, self.base_v].copy()
        out = {"t": t.copy(), "u": u, "u_dot": u_dot, "x_dot": qvel[:, self.x_v].copy()}
        if self.free:
            w, x, y, z = qpos[:, self.bq + 3:self.bq + 7].T
            theta, roll, yaw = kinematics.tilts_from_quaternion(w, x, y, z)
            out["theta"] = theta
            out["theta_dot"] = qvel[:, self.bv + 4].copy()  # angular velocity about the body y axis
            out["x"], out["z"] = qpos[:, self.bq].copy(), qpos[:, self.bq + 2].copy()
            out["out_of_plane"] = np.maximum.reduce([np.abs(qpos[:, self.bq + 1]), np.abs(roll), np.abs(yaw)])
            if self.transverse:  # the 3-D history the two-component measures read (validate.core.biaxial)
                out["orientation"] = qpos[:, self.bq + 3:self.bq + 7].copy()
                out["y"] = qpos[:, self.bq + 1].copy()
                out["u_y"] = (np.zeros(n) if self.base_yq is None else qpos[:, self.base_yq].copy())
        else:
            out["theta"] = qpos[:, self.thq].copy()
            out["theta_dot"] = qvel[:, self.thv].copy()
            out["x"], out["z"] = qpos[:, self.xq].copy(), system.h + qpos[:, self.zq]
        return out


_local = threading.local()
#: Scenes whose MjData a thread keeps (a campaign's chunk uses one or two systems)
KEPT_DATA = 8


def fresh_data(model: mujoco.MjModel) -> mujoco.MjData:
    """An MjData of `model` as MjData(model) makes it, for this thread's next run: kept per
    thread and reset (creating one costs ~0.35 ms, a hundredth of a run; resetting 3 µs).
    Reset clears the warning counters too, so a run never sees an earlier run's warning."""
    kept = getattr(_local, "data", None)
    if kept is None:
        kept = _local.data = {}
    entry = kept.get(id(model))
    if entry is None or entry[0] is not model:  # the id of a model since freed
        if len(kept) >= KEPT_DATA:
            kept.clear()
        entry = kept[id(model)] = (model, mujoco.MjData(model))
    mujoco.mj_resetData(model, entry[1])
    return entry[1]


class StepRecord:
    """ẍg at the middle of each of a run's `nstep` steps of `dt` (a held force's impulse is
    then right to second order), evaluated block by block as the run reaches it: a run
    that overturns, or rests through a fixed base's record, never needs the rest of it.
    Indexed like the array it stands for (`xg[a:b]`, `xg[steps]`). The vertical üv is a
    StepRecord of `motion.vertical` (`vertical_record`)."""

    def __init__(self, motion: GroundMotion, dt: float, nstep: int):
        self.motion, self.dt, self.size = motion, dt, nstep
        self._values = np.empty(nstep)
        self._filled = 0

    def _fill(self, end: int) -> None:
        end = min(self.size, end)
        if end > self._filled:
            end = min(self.size, max(end, self._filled + BLOCK))
            i = np.arange(self._filled, end)
            self._values[self._filled:end] = self.motion((i + 0.5) * self.dt)
            self._filled = end

    def __getitem__(self, index):
        if isinstance(index, slice):
            self._fill(self.size if index.stop is None else index.stop)
        else:
            self._fill(int(np.max(index)) + 1 if np.size(index) else 0)
        return self._values[index]


def vertical_record(motion: GroundMotion, dt: float, nstep: int) -> StepRecord | None:
    """üv at the middle of each step (StepRecord), or None for a motion without a vertical
    component (its forces, and every history, as before)."""
    return None if motion.vertical is None else StepRecord(motion.vertical, dt, nstep)


def vertical_at(motion: GroundMotion, t) -> np.ndarray | None:
    """üv at times t (s), or None without a vertical component."""
    return None if motion.vertical is None else np.asarray(motion.vertical(t), dtype=float)


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
    if not messages and not data.warning.number.any():
        return None
    text = messages[0] if messages else "MuJoCo raised a warning"
    found = re.search(r"Time = ([0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?)", text)
    return text, float(found.group(1)) if found else math.nan


def stop_in(lay: Layout, system: System, chunk: np.ndarray, t: np.ndarray, motion: GroundMotion,
            hist: dict | None = None):
    """kinematics.first_stop over a chunk of rollout state rows (at times t); `hist`: the
    chunk's `Layout.histories`, when the caller has them already."""
    finite = np.all(np.isfinite(chunk), axis=1)
    h = hist if hist is not None and finite.all() else lay.histories(system, np.where(finite[:, None], chunk, 0.0))
    # two components: θ is the tilt's projection on the xz plane, and past α of the x edge a
    # statue leaning on a diagonal may still stand (the corner's α is larger): the 'falling' rule
    # (motion_end) is planar, so a 3-D run is never stopped by it; 'lying' holds (the total tilt
    # is at least the projection's)
    return kinematics.first_stop(t, h["theta"], h["theta_dot"], finite, system=system,
                                 motion_end=math.inf if lay.transverse else motion.end_time)


def raw_history(lay, system, motion, states, dt, runtime, status, message, stop_reason, t=None) -> RawHistory:
    """The history of state rows: at times `t`, or every `dt` from 0 (MuJoCo's own time
    sums dt and drifts by round-off); the slide where `motion` and `system` need it
    (kinematics.slide_history)."""
    hist = lay.histories(system, states)
    t = np.arange(hist["t"].size) * dt if t is None else np.array(t, dtype=float)
    extras = kinematics.contact_extras(
        system, x_centroid=hist["x"], z_centroid=hist["z"], theta=hist["theta"], u=hist["u"],
        out_of_plane=hist.get("out_of_plane"))
    slide, slide_dot = kinematics.slide_history(
        system, motion, x_centroid=hist["x"], x_centroid_dot=hist["x_dot"], theta=hist["theta"],
        theta_dot=hist["theta_dot"], u=hist["u"], u_dot=hist["u_dot"])
    if lay.transverse:  # histories, not scalars: read by the two-component measures only
        kinematics.pair_extras(extras, orientation=hist["orientation"], y_centroid=hist["y"], u_y=hist["u_y"])
    return RawHistory(engine=ENGINE, system=system, t=t, u=hist["u"], u_dot=hist["u_dot"], theta=hist["theta"],
                      theta_dot=hist["theta_dot"], status=status, message=message, runtime_s=runtime,
                      extras=extras, stop_reason=stop_reason, slide=slide, slide_dot=slide_dot)
