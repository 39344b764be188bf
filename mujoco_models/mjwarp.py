"""The engine "mjwarp" (issue 37): the MuJoCo scene stepped by MuJoCo Warp, MuJoCo's port to NVIDIA
Warp: the same MJCF, the same settings and the same forces as the MuJoCo engine (`batch.py`, shared
with MJX), stepped throughout at the timestep by `mujoco_warp.step`, many runs of one scene at once
as Warp's worlds (`nworld`, simulate_batch). On Warp's CPU device here, on a CUDA device where Warp
finds one (never required).

MuJoCo Warp computes in float32 (its arrays are Warp's `float`, no float64 build): the scene's
positions and contact depth are rounded to ~6e-8 of their size, which MJX in float64 does not do
(docs/mjwarp.md measures what that does to β). A step is ~100 kernel launches; GRAPH_STEPS steps
are recorded once per call (`wp.ScopedCapture`: a CUDA graph on a GPU, Warp's API capture on a CPU)
and replayed, which on this CPU made a step ~100× cheaper than launching its kernels from Python. What it cannot carry is refused before any work, as MJX refuses it: a non-linear isolator,
MuJoCo's phased or event-resolved stepping. An optional engine: `pip install 'isorock[mjwarp]'`
(mujoco-warp, with warp-lang). Measured against MuJoCo's C engine and the exact model: docs/mjwarp.md."""
# no `from __future__ import annotations`: Warp reads the kernels' annotations (wp.array…) as objects
import contextlib
import functools
import importlib.util
import io
import time

import mujoco
import numpy as np

from ..analytic.engine_protocol import Capabilities, EngineSpec, Preset
from ..analytic.errors import import_extra
from ..analytic.motion import GroundMotion
from ..analytic.system import System
from ..analytic.trajectory import RawHistory

from . import batch, ladder  # ladder: MuJoCo's work-precision ladder, the same scene, the same timesteps
from .batch import ISOLATORS
from .scene import SCENE_FORMAT, check_representable, scene_text
from .settings import Settings, settings_for

# Registered, but where the extra is not installed the engine cannot be loaded (an ImportError, as
# Drake's where pydrake is absent): every loop over the engines skips it with this reason, and a
# command that names it says it in one line. find_spec: Warp itself is imported on the first run only.
for _package in ("warp", "mujoco_warp"):
    if importlib.util.find_spec(_package) is None:
        raise ModuleNotFoundError(f"MuJoCo Warp cannot run here without the package {_package!r}: "
                                  "pip install 'isorock[mjwarp]'", name=_package)

#: steps recorded in one capture, replayed as often as a run needs: recording costs ~20 ms a step
#: on this CPU (once per call: the capture holds that call's arrays), a replayed step ~0.08 ms
GRAPH_STEPS = 50
#: steps between two reads of the stepped rows back into numpy (a multiple of GRAPH_STEPS)
CHUNK_STEPS = 2000


def _warp():
    """(warp, mujoco_warp), Warp initialised quietly: its banner and its line per module loaded go to
    standard output, where they would land in `--json -`'s output (its warnings go to standard error)."""
    wp = import_extra("warp", "mjwarp", "the MuJoCo Warp engine")
    mjw = import_extra("mujoco_warp", "mjwarp", "the MuJoCo Warp engine")
    wp.config.quiet = True
    if hasattr(wp, "LOG_WARNING"):  # warp-lang 1.19 prints its module loads at its log level INFO
        wp.config.log_level = wp.LOG_WARNING
    with contextlib.redirect_stdout(io.StringIO()), batch.without_native_line(NO_DRIVER):
        wp.init()
    return wp, mjw


#: what Warp's native library prints on standard error on a machine without an NVIDIA driver, each
#: time it starts: isorock runs Warp on its CPU device there, which the engine's status says
NO_DRIVER = b"Warp CUDA warning: Could not find or load the NVIDIA CUDA driver"



@functools.cache
def _kernels():
    """The three kernels around each step: load the step's qfrc_applied from the chunk's forces,
    store qpos and qvel after it, and advance the step counter (on the device, so a recorded
    capture replays the next steps, not the same one)."""
    wp, _ = _warp()

    @wp.kernel
    def load(forces: wp.array3d(dtype=wp.float32), k: wp.array(dtype=wp.int32),
             qfrc_applied: wp.array2d(dtype=wp.float32)):
        world, dof = wp.tid()
        qfrc_applied[world, dof] = forces[world, k[0], dof]

    @wp.kernel
    def store(qpos: wp.array2d(dtype=wp.float32), qvel: wp.array2d(dtype=wp.float32), k: wp.array(dtype=wp.int32),
              nq: int, nv: int, qpos_out: wp.array3d(dtype=wp.float32), qvel_out: wp.array3d(dtype=wp.float32)):
        world = wp.tid()
        for i in range(nq):
            qpos_out[world, k[0], i] = qpos[world, i]
        for i in range(nv):
            qvel_out[world, k[0], i] = qvel[world, i]

    @wp.kernel
    def advance(k: wp.array(dtype=wp.int32)):
        k[0] = k[0] + 1
    return load, store, advance


def _model(model):
    """The scene as MuJoCo Warp takes it: MuJoCo C's auto-reset (off in the scene, so that a run
    that blows up fails instead of restarting) is not a flag Warp has, nor a thing it does."""
    model.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_AUTORESET)
    return model


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """The scene from t = 0 to `duration` (default: the motion's end + 5 s, or 10 s without
    motion), from rest tilted by θ0 (rad) about its corner, stepped by mujoco_warp.step."""
    return simulate_batch(system, [motion], settings=settings, duration=duration, theta0=[theta0],
                          progress=progress)[0]


def simulate_batch(system: System, motions, *, settings: Settings | None = None, duration: float | None = None,
                   theta0=None, progress=None, device: str | None = None) -> list[RawHistory]:
    """Runs of one system, one per motion (and θ0), stepped together as MuJoCo Warp's worlds of one
    scene. Each history is the run's own, as `simulate` makes it alone. `device`: Warp's ("cpu",
    "cuda:0"; default Warp's preferred one, a GPU where there is one)."""
    start = time.perf_counter()
    b = batch.prepare(system, motions, settings, duration, theta0, "MuJoCo Warp")  # refuses before any Warp work
    wp, mjw = _warp()
    model, nworld, nstep = _model(b.model), len(b.motions), b.nstep
    load, store, advance = _kernels()
    with wp.ScopedDevice(device or wp.get_preferred_device()):
        m = mjw.put_model(model)
        d = mjw.put_data(model, b.starts[0], nworld=nworld)
        # each world from its own start: its tilt, and the solver's warm start there
        for name in ("qpos", "qvel", "qacc_warmstart"):
            getattr(d, name).assign(np.stack([getattr(s, name) for s in b.starts]).astype(np.float32))
        forces = wp.zeros((nworld, CHUNK_STEPS, model.nv), dtype=wp.float32)
        qpos_out = wp.zeros((nworld, CHUNK_STEPS, model.nq), dtype=wp.float32)
        qvel_out = wp.zeros((nworld, CHUNK_STEPS, model.nv), dtype=wp.float32)
        k = wp.zeros(1, dtype=wp.int32)

        def steps(n):
            for _ in range(n):
                wp.launch(load, dim=(nworld, model.nv), inputs=[forces, k, d.qfrc_applied])
                mjw.step(m, d)
                wp.launch(store, dim=nworld, inputs=[d.qpos, d.qvel, k, model.nq, model.nv, qpos_out, qvel_out])
                wp.launch(advance, dim=1, inputs=[k])

        graph = None
        qpos, qvel = np.zeros((nworld, nstep, model.nq)), np.zeros((nworld, nstep, model.nv))
        for c0 in range(0, nstep, CHUNK_STEPS):
            n = min(CHUNK_STEPS, nstep - c0)
            chunk = np.zeros((nworld, CHUNK_STEPS, model.nv), dtype=np.float32)
            chunk[:, :n] = b.forces[:, c0:c0 + n]
            forces.assign(chunk)
            k.zero_()
            whole = n - n % GRAPH_STEPS
            if whole and graph is None:
                # recorded once, replayed: the recording itself steps nothing
                with wp.ScopedCapture(force_module_load=False) as capture:
                    steps(GRAPH_STEPS)
                graph = capture.graph
            for _ in range(whole // GRAPH_STEPS):
                wp.capture_launch(graph)
            steps(n - whole)
            qpos[:, c0:c0 + n] = qpos_out.numpy()[:, :n]
            qvel[:, c0:c0 + n] = qvel_out.numpy()[:, :n]
            if progress is not None:
                progress(min(b.duration, (c0 + n) * b.dt), b.duration)
    runtime = (time.perf_counter() - start) / nworld
    return batch.histories(b, qpos, qvel, runtime, "mjwarp", "MuJoCo Warp",
                           "throughout at the timestep, by mujoco_warp.step in float32")


ENGINE = EngineSpec(
    name="mjwarp", label="MuJoCo Warp", settings_type=Settings, simulate=simulate,
    # a run on this CPU costs several times MuJoCo C's, and a scene's first run compiles Warp's
    # kernels (~40 s, cached on disk after): no campaigns (bench, stress and sweep run it only when named)
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              campaigns=False, isolators=ISOLATORS, kinetic_friction=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={"default": Preset("MuJoCo's default scene and settings, stepped throughout by mujoco_warp.step in "
                               "float32 (MuJoCo's rest phase and coarse steps are its C engine's, not Warp's)",
                               Settings)},
    ladder=ladder, check_system=lambda system, settings: check_representable(system))
