"""A measured rock on a shake table as a MuJoCo model (issue 21, `isorock experiments`):
the rock's convex hull on a free joint (it may rock, twist, slide and lift off in 3D) on a
flat table, driven by the table's measured acceleration.

The simulation runs in the table's frame: a rigid table translating with acceleration
a(t) along x is, for the rock, gravity plus the uniform inertial force −m·a(t) x̂ at its
centre of mass (exact for a translating frame; no table body, no prescribed-motion
joint whose tracking error would enter the result). The convex hull is exact for contact
with a flat table (the table touches nothing inside it). The rock's inertia is the one
given (the mesh's at uniform density), not MuJoCo's from the hull.

Contact: the data's own simulation used friction 0.3–0.5 (its README): FRICTION 0.5; a
soft contact of time constant SOLREF[0] (4 ms: MuJoCo asks for ≥ 2 timesteps; critically damped).
"""
from __future__ import annotations

import math
import time

import mujoco
import numpy as np

FRICTION = 0.5
TIMESTEP = 1e-3
SOLREF = (0.004, 1.0)
SOLIMP = (0.9, 0.95, 0.001)
from ..analytic.engine_protocol import BODY_OVERTURN_TILT as OVERTURN_TILT  # every hull scene's rule


def _fmt(v) -> str:
    return " ".join(repr(float(x)) for x in np.ravel(v))


def scene_xml(vertices, com, inertia, mass, *, friction=FRICTION, timestep=TIMESTEP,
              solref=SOLREF, solimp=SOLIMP) -> str:
    """MJCF of the rock at rest: `vertices` (its hull, table frame, table at z = 0, m),
    centre of mass `com`, inertia tensor `inertia` about it (kg m²), `mass` (kg)."""
    vertices = np.asarray(vertices, float) - np.asarray(com, float)  # body frame at the centre of mass
    I = np.asarray(inertia, float)
    full = (I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2])
    return f"""<mujoco model="rock">
  <option timestep="{timestep!r}" integrator="implicitfast" cone="elliptic"/>
  <asset><mesh name="hull" vertex="{_fmt(vertices)}"/></asset>
  <worldbody>
    <geom name="table" type="plane" size="5 5 0.1" friction="{friction!r} 0.005 0.0001"
          solref="{_fmt(solref)}" solimp="{_fmt(solimp)}"/>
    <body name="rock" pos="{_fmt(com)}">
      <freejoint/>
      <inertial pos="0 0 0" mass="{mass!r}" fullinertia="{_fmt(full)}"/>
      <geom type="mesh" mesh="hull" friction="{friction!r} 0.005 0.0001" solref="{_fmt(solref)}"
            solimp="{_fmt(solimp)}" contype="1" conaffinity="1"/>
    </body>
  </worldbody>
</mujoco>"""


def simulate(xml: str, acceleration, dt: float, *, duration=None, settle: float = 0.5) -> dict:
    """Run the rock under the table acceleration `acceleration` (m/s², samples at dt, linear
    between them, zero after): first `settle` s at rest (the soft contact finds its
    equilibrium), then the record. Returns the peak tilt (rad, angle of the rock's z axis
    from its resting direction), the final tilt, overturned (tilt passed OVERTURN_TILT),
    the peak slide (m) and the wall time."""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    a = np.asarray(acceleration, float)
    h = model.opt.timestep
    n_settle = int(round(settle / h))
    end = (a.size - 1) * dt if duration is None else duration
    n = int(math.ceil(end / h))
    t_samples = dt * np.arange(a.size)
    drive = np.interp(h * np.arange(n), t_samples, a, right=0.0)
    m = float(model.body_mass[1])
    start = time.perf_counter()
    for _ in range(n_settle):
        mujoco.mj_step(model, data)
    q_rest = data.qpos[3:7].copy()
    R_rest = np.zeros(9)
    mujoco.mju_quat2Mat(R_rest, q_rest)
    z_rest = R_rest.reshape(3, 3)[:, 2].copy()
    x_rest = data.qpos[:2].copy()
    tilt_max, slide_max, overturned = 0.0, 0.0, False
    R = np.zeros(9)
    force = data.xfrc_applied[1]
    for i in range(n):
        force[0] = -m * drive[i]
        mujoco.mj_step(model, data)
        if i % 4 == 0:  # every 4 ms: far finer than rocking's time scale
            mujoco.mju_quat2Mat(R, data.qpos[3:7])
            tilt = math.acos(max(-1.0, min(1.0, float(R.reshape(3, 3)[:, 2] @ z_rest))))
            if tilt > tilt_max:
                tilt_max = tilt
            slide_max = max(slide_max, float(np.hypot(*(data.qpos[:2] - x_rest))))
            if tilt > OVERTURN_TILT:
                overturned = True
                break  # what follows a fall does not change the outcome
    mujoco.mju_quat2Mat(R, data.qpos[3:7])
    final = math.acos(max(-1.0, min(1.0, float(R.reshape(3, 3)[:, 2] @ z_rest))))
    return dict(tilt_max=tilt_max, tilt_final=final, overturned=overturned, slide_max=slide_max,
                wall_s=time.perf_counter() - start, steps=n_settle + n)
