"""A measured rock on a shake table in Drake (issue 21, `isorock experiments`): the rock's
convex hull as a free body on a table (a wide box), driven by the table's measured
acceleration — the counterpart of mujoco_models.mesh_scene and bullet_models.mesh_scene.

In the table's frame: the inertial force −m·a(t) x̂ at the centre of mass (the body frame's
origin, so no torque) is the free body's generalized force, linear between the record's
samples (a first-order-hold trajectory source into the plant's applied-generalized-force
port). The plant is discrete (1 ms, SAP), point contact (the hull against the table's
box), friction 0.5 as the other hull scenes; Drake's Convex shape reads a mesh file,
so the hull is written to a temporary OBJ. The run advances in chunks of CHUNK s and stops
at the first chunk whose end finds the tilt past OVERTURN_TILT (one rule for every hull
scene); between chunk ends the tilt is sampled every 4 ms by a logger.
"""
from __future__ import annotations

import math
import os
import tempfile
import time

import numpy as np
import pydrake.all as pd

from ..analytic.engine_protocol import BODY_OVERTURN_TILT as OVERTURN_TILT  # every hull scene's rule

FRICTION = 0.5
TIMESTEP = 1e-3
SAMPLE = 4e-3  # s: the tilt's sampling, as the other hull scenes
CHUNK = 1.0  # s advanced between overturn checks
GRAVITY = 9.81
TABLE = (20.0, 20.0, 1.0)  # m: wide enough for any slide or fall here


def _hull_obj(vertices) -> str:
    """An OBJ text of the convex hull of `vertices` (faces outward)."""
    from scipy.spatial import ConvexHull  # lazy: scipy.spatial, for a hull scene only
    v = np.asarray(vertices, float)
    hull = ConvexHull(v)
    c = v[hull.vertices].mean(0)
    lines = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in v]
    for tri in hull.simplices:
        a, b, d = v[tri]
        if np.cross(b - a, d - a) @ (a - c) < 0:
            tri = tri[[0, 2, 1]]
        lines.append("f " + " ".join(str(i + 1) for i in tri))
    return "\n".join(lines) + "\n"


def simulate(vertices, com, inertia, mass, acceleration, dt: float, *, duration=None, settle: float = 0.5,
             friction=FRICTION, timestep=TIMESTEP) -> dict:
    """The same returns as mujoco_models.mesh_scene.simulate."""
    a = np.asarray(acceleration, float)
    end = (a.size - 1) * dt if duration is None else duration
    com = np.asarray(com, float)
    local = np.asarray(vertices, float) - com
    fd, path = tempfile.mkstemp(suffix=".obj", prefix="isorock-hull-")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(_hull_obj(local))
        builder = pd.DiagramBuilder()
        plant, scene_graph = pd.AddMultibodyPlantSceneGraph(builder, timestep)
        plant.set_discrete_contact_approximation(pd.DiscreteContactApproximation.kSap)
        plant.set_contact_model(pd.ContactModel.kPoint)
        I = np.asarray(inertia, float)
        rock = plant.AddRigidBody("rock", pd.SpatialInertia(
            mass, np.zeros(3), pd.UnitInertia(*(np.array([I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]])
                                                / mass))))
        props = pd.CoulombFriction(friction, friction)
        plant.RegisterCollisionGeometry(rock, pd.RigidTransform(), pd.Convex(path), "hull", props)
        # the table: a box with its top at z = 0, not a HalfSpace (Drake warns on every run that a
        # rigid half space takes no deformable contact: noise on the command's stderr)
        plant.RegisterCollisionGeometry(plant.world_body(), pd.RigidTransform([0.0, 0.0, -0.5 * TABLE[2]]),
                                        pd.Box(*TABLE), "table", props)
        plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, -GRAVITY])
        plant.Finalize()
        nv = plant.num_velocities()
        # the free body's generalized velocities are (ω, v) in the world: the force is entry 3 + x
        settle_n = int(round(settle / dt))
        knots = dt * np.arange(settle_n + a.size + 1)
        drive = np.concatenate((np.zeros(settle_n), a, [0.0]))
        forces = np.zeros((nv, knots.size))
        forces[3] = -mass * drive
        source = builder.AddSystem(pd.TrajectorySource(pd.PiecewisePolynomial.FirstOrderHold(knots, forces)))
        builder.Connect(source.get_output_port(), plant.get_applied_generalized_force_input_port())
        logger = pd.LogVectorOutput(plant.get_state_output_port(), builder, SAMPLE)
        diagram = builder.Build()
        simulator = pd.Simulator(diagram)
        context = simulator.get_mutable_context()
        pc = plant.GetMyMutableContextFromRoot(context)
        plant.SetFreeBodyPose(pc, rock, pd.RigidTransform(com))
        start = time.perf_counter()
        simulator.AdvanceTo(settle)
        rest = plant.EvalBodyPoseInWorld(pc, rock)
        z_rest = rest.rotation().matrix()[:, 2].copy()
        x_rest = rest.translation()[:2].copy()
        t, overturned = settle, False
        total = settle + end
        while t < total - 1e-12 and not overturned:
            t = min(t + CHUNK, total)
            simulator.AdvanceTo(t)
            R = plant.EvalBodyPoseInWorld(pc, rock).rotation().matrix()
            overturned = math.acos(max(-1.0, min(1.0, float(R[:, 2] @ z_rest)))) > OVERTURN_TILT
        wall = time.perf_counter() - start
        log = logger.FindLog(context)
        times, q = log.sample_times(), log.data()
        keep = times >= settle
        quat, pos = q[:4, keep], q[4:7, keep]  # the free body's positions: quaternion (w, x, y, z), then xyz
        w, x, y, z = quat / np.linalg.norm(quat, axis=0)
        body_z = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
        tilts = np.arccos(np.clip(z_rest @ body_z, -1.0, 1.0))
        slide = np.hypot(pos[0] - x_rest[0], pos[1] - x_rest[1])
        return dict(tilt_max=float(tilts.max(initial=0.0)), tilt_final=float(tilts[-1]) if tilts.size else 0.0,
                    overturned=bool(overturned or tilts.max(initial=0.0) > OVERTURN_TILT),
                    slide_max=float(slide.max(initial=0.0)), wall_s=wall, steps=int(round(t / timestep)))
    finally:
        os.unlink(path)
