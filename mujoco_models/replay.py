"""A scene to replay any engine's history in: the same block and base on planar joints,
so that a frame is set by u and θ alone (the block pivoting on its corner, riding on the
base). `isorock view` reaches it through the registry (its replay_scene facet, validate/tools/view.py)."""
from __future__ import annotations

from ..analytic import kinematics
from ..analytic.system import System

from .scene import build_model
from .settings import Settings
from .state import Layout


def replay_scene(system: System):
    """(model, pose): MuJoCo's scene of the system with the planar block joints, and
    pose(u, θ) → the joint positions of the rigid model at base displacement u (m) and
    tilt θ (rad)."""
    model = build_model(system, Settings(joint="planar"))
    layout = Layout(model, system, "planar")

    def pose(u: float, theta: float):
        qpos = model.qpos0.copy()
        x, z = kinematics.tilted_centroid(system, theta)
        qpos[layout.xq], qpos[layout.zq], qpos[layout.thq] = u + x, z - system.h, theta
        if layout.base_q is not None:
            qpos[layout.base_q] = u
        return qpos
    return model, pose
