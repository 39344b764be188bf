"""A measured rock on a shake table as a PyBullet scene (issue 21, `isorock experiments`):
the rock's convex hull as a free rigid body (it may rock, twist, slide and lift off in 3D)
on a static plane, driven by the table's measured acceleration — the counterpart of
mujoco_models.mesh_scene, so that the two engines differ in their contact alone.

The simulation runs in the table's frame: a rigid table translating with acceleration
a(t) along x is, for the rock, gravity plus the uniform inertial field −a(t) x̂. Bullet
applies its gravity at the centre of mass of every body, so the field is set as the
gravity (−a(t), 0, −g) before each step: exact for a translating frame, no table body,
no force whose point of application must follow the rock. The convex hull is exact for
contact with a flat table. The rock's inertia is the one given (the mesh's at uniform
density): the body frame is put on its principal axes (Bullet takes a diagonal inertia),
not Bullet's estimate from the hull's bounding box.

Settings: those of the data's own PyBullet simulation (the data folder's README): step
1 ms, 150 solver iterations, split impulse, restitution 0.3; friction 0.5 (the top of its
0.3–0.5), as MuJoCo's hull scene. Overturned: the tilt passes OVERTURN_TILT (the same as
MuJoCo's hull scene, one home).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..analytic.engine_protocol import BODY_OVERTURN_TILT as OVERTURN_TILT  # every hull scene's rule

from .scene import connect, p

FRICTION = 0.5
RESTITUTION = 0.3
TIMESTEP = 1e-3
SOLVER_ITERATIONS = 150
GRAVITY = 9.81
#: the tilt is read every this many steps (4 ms: far finer than rocking's time scale), as MuJoCo's
READ_EVERY = 4


def principal_frame(inertia) -> tuple[np.ndarray, np.ndarray]:
    """(principal moments, rotation Q whose columns are the principal axes, det +1):
    inertia = Q diag(moments) Qᵀ."""
    moments, Q = np.linalg.eigh(np.asarray(inertia, float))
    if np.linalg.det(Q) < 0:
        Q[:, 2] = -Q[:, 2]
    return moments, Q


def _quat(Q) -> list[float]:
    """(x, y, z, w) of the rotation matrix Q."""
    from scipy.spatial.transform import Rotation  # lazy: scipy.spatial, for a hull scene only
    return Rotation.from_matrix(Q).as_quat().tolist()


def build(client, vertices, com, inertia, mass, *, friction=FRICTION, restitution=RESTITUTION,
          timestep=TIMESTEP, solver_iterations=SOLVER_ITERATIONS) -> int:
    """The rock (hull `vertices` in the table frame, table at z = 0, m; centre of mass
    `com`; inertia tensor about it, kg m²; mass kg) at rest on a static plane in `client`;
    returns the rock's body id."""
    c = client
    c.setPhysicsEngineParameter(fixedTimeStep=timestep, numSubSteps=1, numSolverIterations=solver_iterations,
                                useSplitImpulse=1)
    c.setGravity(0.0, 0.0, -GRAVITY)
    plane = c.createCollisionShape(p.GEOM_PLANE)
    table = c.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=plane)
    moments, Q = principal_frame(inertia)
    local = (np.asarray(vertices, float) - np.asarray(com, float)) @ Q  # body frame: principal axes at the COM
    hull = c.createCollisionShape(p.GEOM_MESH, vertices=local.tolist())
    rock = c.createMultiBody(baseMass=float(mass), baseCollisionShapeIndex=hull,
                             basePosition=np.asarray(com, float).tolist(), baseOrientation=_quat(Q))
    c.changeDynamics(rock, -1, localInertiaDiagonal=moments.tolist())
    # Bullet combines two bodies' friction and restitution as their product: the table's are
    # 1, so the contact's are the rock's (0.5 on both would be 0.25: measured, a box slid
    # under 0.22 g)
    for body, mu, e in ((table, 1.0, 1.0), (rock, float(friction), float(restitution))):
        c.changeDynamics(body, -1, lateralFriction=mu, restitution=e, activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING)
    return rock


def _tilt(c, rock, z_rest) -> float:
    _, q = c.getBasePositionAndOrientation(rock)
    z = np.asarray(c.getMatrixFromQuaternion(q)).reshape(3, 3)[:, 2]
    return math.acos(max(-1.0, min(1.0, float(z @ z_rest))))


def simulate(vertices, com, inertia, mass, acceleration, dt: float, *, duration=None, settle: float = 0.5,
             **settings) -> dict:
    """Run the rock under the table acceleration (m/s², samples at dt, linear between
    them, zero after): first `settle` s at rest, then the record. The same returns as
    mujoco_models.mesh_scene.simulate: peak and final tilt (rad), overturned, peak slide
    (m), wall time, steps."""
    a = np.asarray(acceleration, float)
    h = settings.get("timestep", TIMESTEP)
    n_settle = int(round(settle / h))
    end = (a.size - 1) * dt if duration is None else duration
    n = int(math.ceil(end / h))
    drive = np.interp(h * np.arange(n), dt * np.arange(a.size), a, right=0.0)
    c = connect()
    try:
        rock = build(c, vertices, com, inertia, mass, **settings)
        start = time.perf_counter()
        for _ in range(n_settle):
            c.stepSimulation()
        pos, q = c.getBasePositionAndOrientation(rock)
        z_rest = np.asarray(c.getMatrixFromQuaternion(q)).reshape(3, 3)[:, 2].copy()
        x_rest = np.asarray(pos[:2])
        tilt_max, slide_max, overturned = 0.0, 0.0, False
        for i in range(n):
            c.setGravity(-float(drive[i]), 0.0, -GRAVITY)
            c.stepSimulation()
            if i % READ_EVERY == 0:
                tilt = _tilt(c, rock, z_rest)
                tilt_max = max(tilt_max, tilt)
                pos, _ = c.getBasePositionAndOrientation(rock)
                slide_max = max(slide_max, float(np.hypot(*(np.asarray(pos[:2]) - x_rest))))
                if tilt > OVERTURN_TILT:
                    overturned = True
                    break  # what follows a fall does not change the outcome
        final = _tilt(c, rock, z_rest)
        wall = time.perf_counter() - start
    finally:
        c.disconnect()
    return dict(tilt_max=tilt_max, tilt_final=final, overturned=overturned, slide_max=slide_max,
                wall_s=wall, steps=n_settle + n)
