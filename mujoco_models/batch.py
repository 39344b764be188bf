"""What MuJoCo's batched engines share (issue 37): MJX (`mjx.py`, on JAX) and MuJoCo Warp
(`mjwarp.py`, on NVIDIA Warp) step MuJoCo's own scene throughout at the timestep, many runs of
one scene at once. The runs' inputs checked as the MuJoCo engine checks its own, the scene built
once for the batch, the ground motion's forces per step, each run's start, and the histories
made from the stepped qpos / qvel rows are the same for both: here, once."""
from __future__ import annotations

import contextlib
import math
import os
import sys
import tempfile
from dataclasses import dataclass, replace

import mujoco
import numpy as np

from ..analytic.engine_protocol import run_inputs
from ..analytic.errors import require
from ..analytic.motion import GroundMotion
from ..analytic.status import Status
from ..analytic.system import System
from ..analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, RawHistory

from .scene import build_model
from .settings import Settings
from .state import Layout, StepRecord, raw_history, vertical_record

#: isolators the batched engines carry: the linear one (a spring and dashpot on the base's joint);
#: the non-linear ones' dry friction is a Python-side element in MuJoCo's scene
ISOLATORS = ("linear",)


def inputs(given: Settings, system: System, motion, duration, theta0, engine: str):
    """(motion, duration, settings) of one run, checked as the MuJoCo engine checks its own."""
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD,
                                  settings=given.for_system(system), isolators=ISOLATORS, kinetic_friction=False)
    derived = given.for_system(system, duration)
    require(derived.impact_timestep is None, "impact_timestep", derived.impact_timestep,
            f"None: {engine} steps the scene throughout at the timestep")
    return motion, duration, replace(derived, phased=False)


@dataclass
class Batch:
    """Runs of one system, checked, on one scene: `forces` (runs × nstep × nv) is each run's
    qfrc_applied per step; `starts` each run's MjData at t = 0 (at rest, tilted by its θ0 about
    the corner, after mj_forward)."""

    system: System
    motions: list
    theta0: list
    duration: float
    settings: Settings
    model: mujoco.MjModel
    lay: Layout
    dt: float
    nstep: int
    forces: np.ndarray
    starts: list


def prepare(system: System, motions, settings: Settings | None, duration: float | None, theta0,
            engine: str) -> Batch:
    """The batch of runs of `system`, one per motion (and θ0), checked before any work: one
    duration for all (a batch is stepped together)."""
    motions = [GroundMotion.zero() if m is None else m for m in motions]
    theta0 = [0.0] * len(motions) if theta0 is None else [float(t) for t in theta0]
    require(len(theta0) == len(motions), "theta0", len(theta0), f"one per motion ({len(motions)})")
    checked = [inputs(settings or Settings(), system, m, duration, th, engine) for m, th in zip(motions, theta0)]
    durations = {d for _, d, _ in checked}
    require(len(durations) == 1, "duration", sorted(durations), "one duration for a batch")
    duration, derived = checked[0][1], checked[0][2]
    model = build_model(system, derived)
    lay = Layout(model, system, derived.joint)
    dt = model.opt.timestep
    nstep = int(math.floor(duration / dt + 1e-9))
    forces = np.zeros((len(motions), nstep, model.nv))
    for k, (m, _, _) in enumerate(checked):
        xg, zg = StepRecord(m, dt, nstep), vertical_record(m, dt, nstep)
        forces[k] = lay.forces(system, xg[0:nstep], None if zg is None else zg[0:nstep])
    starts = []
    for th in theta0:
        data = mujoco.MjData(model)
        data.qpos[:] = lay.initial_state(model, system, th)[1:1 + model.nq]
        mujoco.mj_forward(model, data)
        starts.append(data)
    return Batch(system, [m for m, _, _ in checked], theta0, duration, derived, model, lay, dt, nstep, forces, starts)


def histories(batch: Batch, qpos: np.ndarray, qvel: np.ndarray, runtime: float, engine: str, label: str,
              stepping: str) -> list[RawHistory]:
    """Each run's RawHistory from its stepped rows (qpos: runs × nstep × nq, qvel: runs × nstep
    × nv, after each step), as the MuJoCo engine makes one: t = k·dt, the run cut where its state
    stops being finite (FAILED, saying when)."""
    model, lay, dt, system = batch.model, batch.lay, batch.dt, batch.system
    out = []
    for k, m in enumerate(batch.motions):
        states = np.zeros((batch.nstep + 1, lay.nstate))
        states[0] = lay.initial_state(model, system, batch.theta0[k])
        states[1:, 1:1 + model.nq] = qpos[k]
        states[1:, 1 + model.nq:1 + model.nq + model.nv] = qvel[k]
        states[:, 0] = np.arange(batch.nstep + 1) * dt
        finite = np.all(np.isfinite(states), axis=1)
        status, message, stop = Status.COMPLETED, "", None
        if not finite.all():
            bad = int(np.argmin(finite))
            states = states[:bad]
            status, message, stop = Status.FAILED, f"{label}'s state is not finite at t = {bad * dt:.6g} s", "non-finite"
        raw = raw_history(lay, system, m, states, dt, runtime, status, message, stop, t=states[:, 0])
        raw.extras.update(timestep=float(dt), solref_0=float(batch.settings.solref[0]),
                          solref_1=float(batch.settings.solref[1]), stepping=stepping)
        out.append(replace(raw, engine=engine))
    return out


@contextlib.contextmanager
def without_native_line(dropped: bytes):
    """Standard error at the file-descriptor level (where a C library's fprintf writes) held in a
    temporary file while the block runs, then written back without the lines starting with
    `dropped`: everything else a batched engine's native library says still reaches the user
    (mjwarp.NO_DRIVER: Warp's line on a machine without an NVIDIA driver)."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as held:
        os.dup2(held.fileno(), 2)
        try:
            yield
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            held.seek(0)
            kept = [line for line in held.read().splitlines(keepends=True) if not line.startswith(dropped)]
            if kept:
                os.write(2, b"".join(kept))
