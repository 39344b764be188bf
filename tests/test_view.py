"""`isorock view`: the replay's kinematics, the GIF where an offscreen renderer exists,
and one line (exit 1) where none does."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from isorock.analytic.system import System
from isorock.validate.tools import view
from isorock.validate.cli.main import main

ISOLATED = System.isolated(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)


@pytest.mark.parametrize("system", [ISOLATED, FIXED], ids=["isolated", "fixed"])
@pytest.mark.parametrize("theta", [0.12, -0.2])
def test_replayed_block_pivots_on_its_corner_riding_the_base(system, theta):
    """Rigid rocking: the pivot corner (s·b, 0, −h in the block's frame) stays on the
    plate's top face at x = u + s·b, whatever θ and u."""
    import mujoco
    model, pose = view.replay_scene(system)
    data = mujoco.MjData(model)
    u = 0.0 if system.fixed_base else 0.07
    data.qpos[:] = pose(u, theta)
    mujoco.mj_kinematics(model, data)
    block = model.body("block").id
    s = math.copysign(1.0, theta)
    corner = data.xpos[block] + data.xmat[block].reshape(3, 3) @ np.array([s * system.b, 0.0, -system.h])
    assert corner == pytest.approx([u + s * system.b, 0.0, 0.0], abs=1e-12)
    if not system.fixed_base:
        assert data.xpos[model.body("base").id][0] == pytest.approx(u)


def test_no_display_and_no_renderer_says_so_in_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(view, "has_display", lambda: False)
    monkeypatch.setattr(view, "offscreen_backend", lambda: None)
    out = tmp_path / "v.gif"
    rc = main(["view", "--duration", "0.5", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 1
    assert len(err.strip().splitlines()) == 1 and "no display and no offscreen" in err
    assert not out.exists()


@pytest.mark.parametrize("args, needle", [(["--out", "v.mp4"], "out = "), (["--size", "big"], "size = "),
                                          (["--fps", "0"], "fps = "), (["--engine", "analytic,mujoco"], "one engine")])
def test_bad_view_options_exit_2(args, needle, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc = main(["view", *args])
    assert rc == 2 and needle in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_gif_of_free_rocking_where_an_offscreen_renderer_exists(tmp_path):
    backend = view.offscreen_backend()
    if backend is None:
        pytest.skip("no offscreen OpenGL renderer here (MUJOCO_GL=egl needs libegl1, osmesa needs libosmesa6)")
    out = tmp_path / "rock.gif"
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env["MUJOCO_GL"] = backend
    r = subprocess.run([sys.executable, "-m", "isorock.validate.cli.main", "view", "--engine", "analytic",
                        "--fixed-base", "--motion", "none", "--theta0", "0.5", "--duration", "1", "--fps", "5",
                        "--size", "160x120", "--out", str(out)], env=env, capture_output=True, text=True,
                       timeout=240)
    assert r.returncode == 0, r.stderr
    from PIL import Image, ImageChops
    with Image.open(out) as im:
        assert im.format == "GIF" and im.size == (160, 120)
        assert im.n_frames == 6  # t = 0, 0.2, …, 1.0 s
        im.seek(0)
        first = im.convert("RGB")
        im.seek(3)  # t = 0.6 s: past the first impact (0.50 s), tilted the other way
        later = im.convert("RGB")
    assert ImageChops.difference(first, later).getbbox() is not None


def test_the_viewer_replays_a_run_in_its_frames(monkeypatch):
    """replay_in_viewer (a display): one frame per 1/60 s of the window, `speed` times as
    much of the run, bounded before the window opens. A stand-in viewer (mujoco.viewer
    needs a display) counts the frames shown and closes after the run's last one; the
    function once referred to an `fps` it does not have (NameError on every display)."""
    import contextlib
    import time

    import mujoco
    import mujoco.viewer
    from isorock.analytic import load_motion
    from isorock.validate.core.engines import get_engine
    traj = get_engine("analytic").simulate(FIXED, load_motion("sine:amp=0.6,freq=1.3,cycles=2"), duration=1.0)
    expected = len(view.frames(traj, 2.0 / 60))  # the run at twice real time, 60 frames a second
    shown = []

    class Viewer:
        def is_running(self):
            return len(shown) < expected  # closed by its user after the last frame

        def sync(self):
            shown.append(1)

    monkeypatch.setattr(mujoco.viewer, "launch_passive", lambda model, data: contextlib.nullcontext(Viewer()))
    monkeypatch.setattr(time, "sleep", lambda seconds: None)  # no waiting on a clock
    assert view.replay_in_viewer(traj, speed=2.0) == 0
    assert len(shown) == expected > 1
    with pytest.raises(view.InputError, match="frames"):  # bounded before the window opens
        view.replay_in_viewer(traj, speed=1e-9)


def test_the_view_command_imports_mujoco_only_after_choosing_its_renderer():
    """mujoco reads MUJOCO_GL when it is first imported, and `isorock view` sets it to the offscreen
    backend it found before rendering: loading the command (its module and its tool's) must not
    import mujoco first, or the backend it chose is ignored. The oracle: a new process's modules."""
    code = ("import sys\nimport isorock.validate.cli.view, isorock.validate.tools.view\n"
            "print('mujoco' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "False"
