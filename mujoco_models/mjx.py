"""The engine "mjx" (issue 37): the MuJoCo scene stepped by MJX, MuJoCo's JAX port: the same MJCF,
the same settings and the same forces as the MuJoCo engine, stepped throughout at the timestep by
`mjx.step` in float64, in chunks of CHUNK_STEPS compiled once per scene layout (a jitted
`lax.scan`), many runs of one scene at once with `jax.vmap` (simulate_batch). What MJX cannot
carry is refused before any work: a non-linear isolator (its dry friction is a Python-side
element in MuJoCo's scene), MuJoCo's phased or event-resolved stepping (MJX steps throughout).
An optional engine: `pip install 'isorock[mjx]'` (mujoco-mjx, with JAX); on a CPU here, on a GPU
where JAX finds one (never required). Measured against MuJoCo's C engine and the exact model:
docs/mjx.md."""
from __future__ import annotations

import contextlib
import functools
import importlib.util
import io
import os
import sys
import time
import warnings

import numpy as np

from ..analytic.errors import import_extra
from ..analytic.kernel_cache import writable_cache_dir
from ..analytic.motion import GroundMotion
from ..analytic.system import System
from ..analytic.trajectory import RawHistory
from ..analytic.engine_protocol import Capabilities, EngineSpec, Preset

from . import batch, ladder  # ladder: MuJoCo's work-precision ladder, the same scene, the same timesteps
from .batch import ISOLATORS
from .scene import SCENE_FORMAT, check_representable, scene_text
from .settings import Settings, settings_for

#: a compilation shorter than this (s) is not kept on disk (JAX's persistent cache; _keep_compiled)
KEEP_COMPILED_FROM_S = 1.0
#: the most that cache holds (bytes; a chunk is ~0.5 MB): JAX evicts the least recently used
#: past it, and with a bound it locks each read and write (filelock), so that processes
#: compiling one scene at once never read each other's half-written entry
KEEP_COMPILED_BYTES = 256 << 20

#: steps per compiled chunk: one compilation serves every run of a scene layout whatever its
#: duration (the chunk's length is static to XLA), and a run ends within a chunk of its end
CHUNK_STEPS = 2000


def _jax():
    """(jax, mjx), float64 on: MJX's default float32 puts the pivot's contact force, and so β, off
    by its rounding (the scene's contact depth is ~1e-6 of the block)."""
    jax = import_extra("jax", "mjx", "the MJX engine")
    jax.config.update("jax_enable_x64", True)
    # mujoco.mjx prints "Failed to import warp" on standard output where MuJoCo Warp (its other
    # backend, not used here) is absent: it would land in `--json -`'s output
    with contextlib.redirect_stdout(io.StringIO()):
        mjx = import_extra("mujoco.mjx", "mjx", "the MJX engine")
    _keep_compiled(jax)
    return jax, mjx


def _keep_compiled(jax) -> None:
    """XLA's compiled chunk kept on disk by JAX's persistent compilation cache, in the project's
    cache folder (analytic.kernel_cache.writable_cache_dir, as the analytic kernels'), at most
    KEEP_COMPILED_BYTES, so that a later process does not compile a scene layout again: a first run of a 3 s pulse on the
    paper's system took 11.7 s, 5.8 s with the cache (docs/mjx.md). JAX keys each entry by the
    computation, its versions and the machine, and recompiles where an entry cannot be read. A
    cache folder the user gave JAX (JAX_COMPILATION_CACHE_DIR) is kept; none writable: no cache."""
    global _OWN_CACHE
    if jax.config.jax_compilation_cache_dir:
        return
    folder = writable_cache_dir()
    if folder is None:
        return
    _OWN_CACHE = os.path.join(folder, "mjx")
    jax.config.update("jax_compilation_cache_dir", _OWN_CACHE)
    jax.config.update("jax_persistent_cache_min_compile_time_secs", KEEP_COMPILED_FROM_S)
    if importlib.util.find_spec("filelock") is not None:  # the mjx extra's; JAX refuses a bound without it
        jax.config.update("jax_compilation_cache_max_size", KEEP_COMPILED_BYTES)


#: the cache folder _keep_compiled gave JAX (None: none, or the user's own)
_OWN_CACHE: str | None = None
#: what JAX warns where an entry of its cache cannot be read (it compiles again, and would on every run)
_DAMAGED = "Error reading persistent compilation cache entry"


def _mend_damaged_cache(caught) -> None:
    """A damaged entry of our cache folder (JAX compiled again, and would warn and compile on every
    later run, since it does not replace the entry): the folder is emptied, with one line, so that
    the next run keeps a sound one. Every other warning is passed on as it came."""
    damaged = False
    for w in caught:
        if _DAMAGED in str(w.message) and _OWN_CACHE is not None:
            damaged = True
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if damaged:  # its entries, not the folder (JAX goes on writing into it) nor the lock file
        for entry in os.scandir(_OWN_CACHE):
            if entry.name != ".lockfile":
                with contextlib.suppress(OSError):
                    os.remove(entry.path)
        print(f"isorock: the MJX compilation cache {_OWN_CACHE} was damaged: emptied, and compiled again",
              file=sys.stderr, flush=True)


@functools.cache
def _chunk():
    """The jitted chunk of CHUNK_STEPS steps: (mjx model, mjx data, forces (CHUNK_STEPS × nv))
    → (data, qpos rows, qvel rows). JAX compiles it once per scene layout (the shapes of its
    arguments), on its first call with one (seconds)."""
    jax, mjx = _jax()

    def step(carry, force):
        model, data = carry
        new = mjx.step(model, data.replace(qfrc_applied=force))
        # float64 on, a step returns the contact indices as int64 where put_data made int32:
        # the scan's carry keeps its types
        new = jax.tree_util.tree_map(lambda a, b: a.astype(b.dtype), new, data)
        return (model, new), (new.qpos, new.qvel)

    @jax.jit
    def chunk(model, data, forces):
        (_, data), (qpos, qvel) = jax.lax.scan(step, (model, data), forces)
        return data, qpos, qvel
    return chunk


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """The scene from t = 0 to `duration` (default: the motion's end + 5 s, or 10 s without
    motion), from rest tilted by θ0 (rad) about its corner, stepped by mjx.step."""
    return simulate_batch(system, [motion], settings=settings, duration=duration, theta0=[theta0],
                          progress=progress)[0]


def simulate_batch(system: System, motions, *, settings: Settings | None = None, duration: float | None = None,
                   theta0=None, progress=None) -> list[RawHistory]:
    """Runs of one system, one per motion (and θ0), stepped together by jax.vmap: one scene, so
    one compiled chunk. Each history is the run's own, as `simulate` makes it alone."""
    jax, mjx = _jax()
    import jax.numpy as jnp  # lazy: an optional extra
    start = time.perf_counter()
    b = batch.prepare(system, motions, settings, duration, theta0, "MJX")
    model, duration, dt, nstep = b.model, b.duration, b.dt, b.nstep
    n_chunks = -(-nstep // CHUNK_STEPS)
    forces = np.zeros((len(b.motions), n_chunks * CHUNK_STEPS, model.nv))
    forces[:, :nstep] = b.forces
    mx = mjx.put_model(model)
    starts = [mjx.put_data(model, data) for data in b.starts]
    chunk = _chunk()
    if len(starts) == 1:
        # one run is stepped as it is: under vmap every branch of a step (each collision
        # function's, the solver's) is taken by every run, which made one run 15× slower
        data = starts[0]

        def step(d, f):
            d, qp, qv = chunk(mx, d, f[0])
            return d, qp[None], qv[None]
    else:
        data = jax.tree_util.tree_map(lambda *xs: jnp.stack(xs), *starts)
        batched = jax.vmap(chunk, in_axes=(None, 0, 0))

        def step(d, f):
            return batched(mx, d, f)
    qpos, qvel = [], []
    with warnings.catch_warnings(record=True) as caught:  # the first chunk compiles, or reads the cache
        warnings.simplefilter("always")
        for c in range(n_chunks):
            data, qp, qv = step(data, jnp.asarray(forces[:, c * CHUNK_STEPS:(c + 1) * CHUNK_STEPS]))
            qpos.append(np.asarray(qp))
            qvel.append(np.asarray(qv))
            if progress is not None:
                progress(min(duration, (c + 1) * CHUNK_STEPS * dt), duration)
    _mend_damaged_cache(caught)
    qpos = np.concatenate(qpos, axis=1)[:, :nstep]
    qvel = np.concatenate(qvel, axis=1)[:, :nstep]
    runtime = (time.perf_counter() - start) / len(b.motions)
    return batch.histories(b, qpos, qvel, runtime, "mjx", "MJX", "throughout at the timestep, by mjx.step in float64")


ENGINE = EngineSpec(
    name="mjx", label="MJX (MuJoCo on JAX)", settings_type=Settings, simulate=simulate,
    # a compiled chunk costs seconds per scene, and a run on a CPU 12–37× MuJoCo C's: no campaigns
    # (bench, stress and sweep run it only when named)
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              campaigns=False, isolators=ISOLATORS, kinetic_friction=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={"default": Preset("MuJoCo's default scene and settings, stepped throughout by mjx.step in float64 "
                               "(MuJoCo's rest phase and coarse steps are its C engine's, not MJX's)", Settings)},
    ladder=ladder, check_system=lambda system, settings: check_representable(system))
