"""The `isorock view` command: options, then a replay in MuJoCo's viewer or a GIF."""
from __future__ import annotations

import os
import sys
from pathlib import Path

from ...analytic.engine_protocol import DEFAULT_IMPACT_THRESHOLD, run_inputs
from ...analytic.errors import InputError
from ...analytic.limits import BudgetExceeded
from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD
from ..core.estimate import announce_cost
from .options import (add_budget_option, add_engine_options, add_motion_options, add_system_options,
                      budget_stopped)
from .readers import motion_from_args
from ..io.inputs import load_engines, parse_engines, run_budget, system_from_args
from ..core.engines import settings_used
from ..tools import view as tool
from ..tools.view import (DEFAULT_MOTION, DEFAULT_OUT, OFFSCREEN_BACKENDS, PAPER, _size,
                          replay_in_viewer, write_gif)


def add_parser(sub) -> None:
    p = sub.add_parser("view", help="replay a run in MuJoCo's viewer, or write it as a GIF where there is no display",
                       description=tool.__doc__.split("\n\n")[0] + "\n\nWithout options: the paper's block "
                       f"(T {PAPER_PERIOD:g} s, ξ {PAPER_DAMPING_RATIO:g}) under " + DEFAULT_MOTION + ".")
    p.add_argument("--engine", default="mujoco", metavar="ENGINE[:PRESET]",
                   help="the engine that simulates (default: %(default)s); the replay is drawn in MuJoCo's scene")
    add_system_options(p, defaults=PAPER)
    add_motion_options(p, default=DEFAULT_MOTION)
    p.add_argument("--duration", type=float,
                   help="end time from t = 0, s (default: motion end + 5 s, or 10 s without motion)")
    p.add_argument("--theta0-over-alpha", "--theta0", dest="theta0_over_alpha", type=float, default=0.0,
                   help="initial tilt as a fraction of α (default 0)")
    p.add_argument("--out", metavar="FILE.gif",
                   help=f"write a GIF here instead of opening the viewer (default without a display: {DEFAULT_OUT}, "
                        "never replacing an existing file of that name)")
    p.add_argument("--fps", type=float, default=20.0, help="GIF frames per second of playback (default: %(default)s)")
    p.add_argument("--speed", type=float, default=1.0,
                   help="simulated seconds per second of playback (default: %(default)s)")
    p.add_argument("--size", default="480x360", metavar="WxH", help="GIF frame size in pixels (default: %(default)s)")
    add_engine_options(p)
    add_budget_option(p)
    p.set_defaults(func=run)


def _check(a) -> None:
    for name in ("fps", "speed"):
        value = getattr(a, name)
        if not (value > 0 and value < 1e4):
            raise InputError(f"{name} = {value!r}: must be a positive number below 10000")
    if a.out is not None and Path(a.out).suffix.lower() != ".gif":
        raise InputError(f"out = {a.out!r}: must end in .gif")
    if not abs(a.theta0_over_alpha) < 1:
        raise InputError(f"theta0_over_alpha = {a.theta0_over_alpha!r}: must be a fraction of α between -1 and 1")
    if a.duration is not None and not a.duration > 0:
        raise InputError(f"duration = {a.duration!r}: must be a positive number of seconds")
    run_budget(a)  # before any display or renderer is looked for


def run(a) -> int:
    _check(a)
    size = _size(a.size)
    specs = parse_engines(a.engine)
    if len(specs) != 1:
        raise InputError(f"engine = {a.engine!r}: view replays one engine")
    system = system_from_args(a, default_isolator=(PAPER_PERIOD, PAPER_DAMPING_RATIO))
    motion = motion_from_args(a)
    interactive = tool.has_display() and a.out is None
    out = a.out or DEFAULT_OUT
    if not interactive:
        if a.out is None and Path(out).exists():
            raise InputError(f"out = {out!r}: exists; give --out FILE.gif to write elsewhere or replace it")
        backend = tool.offscreen_backend()
        if backend is None:
            tried = os.environ.get("MUJOCO_GL") or " and ".join(OFFSCREEN_BACKENDS)
            print(f"isorock view: no display and no offscreen OpenGL renderer ({tried} tried; install EGL "
                  f"(libegl1) or OSMesa (libosmesa6), or run where there is a display)", file=sys.stderr)
            return 1
        os.environ["MUJOCO_GL"] = backend  # read when mujoco is first imported, which is below
    label, engine, settings = load_engines(specs, a)[0]
    # the run's budget, and its cost said first when it is long (as `run`)
    budget = run_budget(a)
    theta0 = a.theta0_over_alpha * system.alpha
    _, duration = run_inputs(system, motion, a.duration, theta0, DEFAULT_IMPACT_THRESHOLD,
                             settings=settings_used(settings, system))  # the steps the run will take
    announce_cost("view", {label: duration}, budget)
    try:
        traj = engine.simulate(system, motion, settings=settings, duration=a.duration,
                               overturn_rule=getattr(a, "overturn", None), theta0=theta0, budget_s=budget)
    except BudgetExceeded as e:
        return budget_stopped("view", label, e)
    if interactive:
        return replay_in_viewer(traj, speed=a.speed)
    try:
        write_gif(traj, out, fps=a.fps, speed=a.speed, size=size, title=label)
    except InputError:
        raise  # bad input (too many frames) is one line and exit 2, not a rendering failure
    except Exception as e:  # noqa: BLE001 — MuJoCo's GL errors have no common type
        print(f"isorock view: offscreen rendering failed with MUJOCO_GL={os.environ.get('MUJOCO_GL')}: "
              f"{type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}", file=sys.stderr)
        return 1
    print(out)
    return 0
