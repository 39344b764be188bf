"""`isorock view`: watch a run. The engine named simulates (through the registry, so any
engine, the analytic model included); the run is then replayed in MuJoCo's scene of the
same system by setting each frame's joint positions from the measured history (base at
u, block tilted by θ about its corner; the rigid kinematics, so a contact engine's
sub-millimetre pivot slip is not shown).

- a display (DISPLAY or WAYLAND_DISPLAY) and no --out: MuJoCo's interactive viewer
  (mujoco.viewer), in real time × --speed, until the window is closed;
- otherwise, where an offscreen OpenGL renderer works (MUJOCO_GL if set, else EGL, then
  OSMesa; each is probed in a child process, since MuJoCo fixes its backend on import):
  a GIF (Pillow, already installed with matplotlib) of --fps frames per simulated second
  × --speed, with the time and θ/α written on each frame;
- where neither exists: one line on stderr and exit 1 (the environment, not the input, is
  at fault; exit 2 stays for bad input).
"""
from __future__ import annotations

import os
import subprocess
import sys
import time

import numpy as np
from PIL import Image, ImageDraw

from ...analytic.engine_protocol import declare_facet
from ...analytic.errors import InputError
from ...analytic.system import PAPER_BLOCK
from ..core.engines import get_engine
from ..core.scenarios import ROBUST_SINE
from ..io.output import write_atomic

#: Tried in this order when MUJOCO_GL is not set.
OFFSCREEN_BACKENDS = ("egl", "osmesa")
PROBE_TIMEOUT_S = 60
_PROBE = ("import mujoco\n"
          "m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><geom size=\"1\"/></worldbody></mujoco>')\n"
          "r = mujoco.Renderer(m, 16, 16); d = mujoco.MjData(m); r.update_scene(d); r.render(); r.close()\n")
DEFAULT_OUT = "isorock-view.gif"
#: Paper block for a first look (as `isorock scene`, analytic.system.PAPER_BLOCK with the
#: paper's isolator), under a pulse that makes it rock clearly (θmax ≈ 0.46 α): the report's
#: robust sine
PAPER = PAPER_BLOCK
DEFAULT_MOTION = ROBUST_SINE


def has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def probe(backend: str) -> bool:
    """Whether MuJoCo can render offscreen with MUJOCO_GL=backend (in a child process)."""
    try:
        r = subprocess.run([sys.executable, "-c", _PROBE], env=dict(os.environ, MUJOCO_GL=backend),
                           capture_output=True, timeout=PROBE_TIMEOUT_S, check=False)
    except (OSError, subprocess.SubprocessError):
        return False
    return r.returncode == 0


def offscreen_backend() -> str | None:
    """The first offscreen backend that works: MUJOCO_GL when the user set it, else EGL,
    then OSMesa; None when none does."""
    requested = os.environ.get("MUJOCO_GL")
    for backend in ((requested,) if requested else OFFSCREEN_BACKENDS):
        if probe(backend):
            return backend
    return None


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise InputError(f"size = {text!r}: must be WIDTHxHEIGHT in pixels, e.g. 480x360") from None
    if not (16 <= w <= 4096 and 16 <= h <= 4096):
        raise InputError(f"size = {text!r}: must be 16–4096 pixels each way")
    return w, h


# --- replay ---------------------------------------------------------------------------

#: an engine's scene in which any engine's history can be replayed (MuJoCo's)
REPLAY_SCENE = declare_facet("replay_scene", "isorock view", "(system) → (model, pose(u, θ) → joint positions): a "
                             "scene of the engine's viewer in which any engine's history can be replayed")

def replay_scene(system):
    """(model, pose(u, θ) → qpos): MuJoCo's replay scene, through the registry."""
    return REPLAY_SCENE.of(get_engine("mujoco").spec)(system)


#: most frames one GIF or replay may have (a 40 s run at 20 fps is 800): `--speed 1e-6`
#: asked for 8e8 and ran out of memory after 27 s
MAX_FRAMES = 20_000


def check_frames(traj, dt: float) -> None:
    """At most MAX_FRAMES frames of `dt` s of run each: bad input before any rendering."""
    n = (float(traj.t[-1]) if traj.t.size else 0.0) / dt
    if n > MAX_FRAMES:
        raise InputError(f"speed = the run's {traj.t[-1]:.3g} s at {dt:.3g} s of run per frame make {n:.3g} frames; "
                         f"must be at most {MAX_FRAMES} (MAX_FRAMES): a larger --speed or a smaller --fps")


def frames(traj, dt: float):
    """(t, u, θ) at t = 0, dt, 2dt, … of the run (at most MAX_FRAMES)."""
    check_frames(traj, dt)
    r = traj.resample(dt)
    return list(zip(r.t.tolist(), r.u.tolist(), r.theta.tolist()))


def _camera(system):
    import mujoco  # lazy: mujoco reads MUJOCO_GL when first imported, set by the command first
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = (0.0, 0.0, system.h)
    cam.distance = 2.2 * system.height + 2 * system.width
    cam.azimuth, cam.elevation = 90.0, -8.0  # looking along +y: x to the right, rocking in the image plane
    return cam


#: Software OpenGL (Mesa's EGL or OSMesa) spends ~3/4 of a frame on shadows (measured:
#: 0.27 → 0.076 s per 480×360 frame): a line drawing needs neither shadows nor reflections.
_OFF = ("mjRND_SHADOW", "mjRND_REFLECTION")


def _prepare(scene, system) -> None:
    """Shadows and reflections off; the ground drawn under the plate, with a mark at
    x = 0, so the base's motion relative to the ground is seen (the scene's world frame
    is the ground, which the MuJoCo scene does not draw)."""
    import mujoco  # lazy: mujoco reads MUJOCO_GL when first imported, set by the command first
    for name in _OFF:
        scene.flags[getattr(mujoco.mjtRndFlag, name)] = 0
    half = system.b + system.height
    top = -0.12  # just below the plate (0.1 m thick, top face at z = 0)
    depth = system.b + 0.5  # deeper than the plate, so the mark stands in front of it
    for size, pos, rgba in (((1.5 * half, depth, 0.02), (0.0, 0.0, top - 0.02), (0.6, 0.55, 0.45, 1.0)),
                            ((0.012, 0.012, 0.1), (0.0, -depth, top + 0.1), (0.9, 0.1, 0.1, 1.0))):
        if scene.ngeom >= scene.maxgeom:
            return
        mujoco.mjv_initGeom(scene.geoms[scene.ngeom], mujoco.mjtGeom.mjGEOM_BOX, np.array(size, dtype=float),
                            np.array(pos, dtype=float), np.eye(3).ravel(), np.array(rgba, dtype=np.float32))
        scene.ngeom += 1


def write_gif(traj, path, *, fps: float, speed: float, size: tuple[int, int], title: str) -> None:
    import mujoco  # lazy: mujoco reads MUJOCO_GL when first imported, set by the command first
    system = traj.system
    shots = frames(traj, speed / fps)  # too many frames is bad input, refused before any rendering
    model, pose = replay_scene(system)
    data = mujoco.MjData(model)
    width, height = size
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)
    model.vis.global_.offheight = max(model.vis.global_.offheight, height)
    renderer = mujoco.Renderer(model, height, width)
    cam = _camera(system)
    images = []
    try:
        for t, u, theta in shots:
            data.qpos[:] = pose(u, theta)
            mujoco.mj_forward(model, data)
            renderer.update_scene(data, camera=cam)
            _prepare(renderer.scene, system)
            img = Image.fromarray(renderer.render())
            ImageDraw.Draw(img).text((8, 8), f"{title}   t = {t:5.2f} s   theta/alpha = {theta / system.alpha:+.2f}   "
                                             f"u = {100 * u:+.1f} cm", fill=(255, 255, 255))
            images.append(img.convert("P", palette=Image.Palette.ADAPTIVE))
    finally:
        renderer.close()
    first, rest = images[0], images[1:]
    write_atomic(path, lambda tmp: first.save(tmp, format="GIF", save_all=True, append_images=rest,
                                              duration=max(20, round(1000 / fps)), loop=0))


def replay_in_viewer(traj, *, speed: float) -> int:
    """The run in MuJoCo's interactive viewer, in real time × speed; the window stays
    open on the last frame until it is closed."""
    import mujoco  # lazy: as in write_gif, after the command has set MUJOCO_GL
    import mujoco.viewer
    system = traj.system
    dt = 1 / 60  # the window's frame interval, s
    shots = frames(traj, dt * speed)  # too many frames is bad input, refused before the window opens
    model, pose = replay_scene(system)
    data = mujoco.MjData(model)
    with mujoco.viewer.launch_passive(model, data) as viewer:
        start = time.perf_counter()
        for t, u, theta in shots:
            if not viewer.is_running():
                break
            data.qpos[:] = pose(u, theta)
            mujoco.mj_forward(model, data)
            viewer.sync()
            time.sleep(max(0.0, start + t / speed - time.perf_counter()))
        while viewer.is_running():
            time.sleep(0.05)
    return 0
