"""A statue's own shape in PyBullet (issue 36; docs/statues.md, "PyBullet on the statue's hull"): the
hull's vertices as small spheres on a free body with the statue's inertia tensor, in the block scene
(plate, isolator, ground forcing), against the exact model of the statue's two edges, judged by the
rows MuJoCo's statues are judged by; free rocking against each edge's closed-form t₁ and β; and the
one-line refusal of a PlanarBody without its shape."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from isorock.analytic.errors import InputError
from isorock.bullet_models import ENGINE, Settings
from isorock.bullet_models import statue
from isorock.bullet_models.scene import build, connect
from isorock.validate.core.engines import get_engine
from isorock.validate.tools import statue_check as sc
from statue_judging import SHAPELESS, judge_free_rocking, judge_hull, judge_refused


def test_bullet_says_it_carries_a_statue():
    assert ENGINE.capabilities.two_edges


def test_the_statue_is_a_free_body_with_its_inertia_and_a_sphere_on_each_hull_vertex():
    _, system = sc.example("bust", 1.0, "linear")
    client = connect()
    try:
        scene = build(client, system, Settings().for_system(system))
        info = client.getDynamicsInfo(scene.block, -1)
        assert info[0] == pytest.approx(system.mass, rel=1e-12)
        # the principal moments in the inertial frame, turned back: the Solid's full tensor
        moments, axes = np.array(info[2]), statue.hull_contact.principal_axes(system)[1]
        assert axes @ np.diag(moments) @ axes.T == pytest.approx(np.array(system.body.solid.inertia), abs=1e-9)
        # at rest the statue's own frame is the world's and its centre of mass h above the plate's top
        pos, orn = scene.pose()
        assert np.allclose(pos, [0.0, 0.0, system.h], atol=1e-12)
        assert abs(abs(orn[3]) - 1.0) < 1e-12
        # a sphere on each hull vertex, its bottom on the vertex: those of the plinth's face touch the
        # plate's top (z = 0) at rest, at no depth (Bullet reports those at a distance ≤ 0: of the
        # bust's 4 face vertices, 2 sit at −1e-17 and 2 at +1e-17 m, measured)
        v = np.asarray(system.body.solid.vertices)
        on_face = int(np.sum(v[:, 2] - np.min(v[:, 2]) < 1e-12))
        client.performCollisionDetection()
        points = client.getContactPoints(scene.block)
        assert 2 <= len(points) <= on_face
        assert max(abs(pt[8]) for pt in points) < 1e-9 * system.h
    finally:
        client.disconnect()


#: robust references at θmax/α 0.05 (docs/scripts/statue_engines.py): the two-edge bust on a fixed
#: base (β 0.64 and 0.73, alternating) and on the friction pendulum (1.82% off in β before
#: STATUE_STEP_FACTOR), and the obelisk on the linear isolator
CASES = [("bust", 1.0, "fixed"), ("bust", 1.0, "friction-pendulum"), ("obelisk", 3.0, "linear")]


@pytest.mark.parametrize("name,scale,base", CASES)
def test_bullet_hull_rocks_as_the_exact_model_of_its_two_edges(name, scale, base):
    judge_hull("bullet", name, scale, base)


@pytest.mark.parametrize("side", [1, -1])
def test_free_rocking_on_each_edge_meets_its_closed_forms(side):
    """Free rocking from 0.4·α of each of the bust's edges, by PyBullet's block rows."""
    judge_free_rocking("bullet", side)


def test_bullet_refuses_a_body_without_its_shape_in_one_line():
    judge_refused("bullet", SHAPELESS, "body: PyBullet carries a statue's own shape")


def test_run_a_statue_on_bullet_from_the_command_line(tmp_path):
    """`isorock run --engine bullet --statue-example …` on a fixed base runs (it was refused in one line
    before PyBullet carried a statue)."""
    base = [sys.executable, "-m", "isorock.validate.cli", "run", "--engine", "bullet", "--statue-example", "bust",
            "--mass", "80", "--fixed-base", "--motion", "sine:amp=0.5,freq=2,cycles=1", "--duration", "1.0"]
    r = subprocess.run(base, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert r.returncode == 0, r.stderr


def test_pybullets_model_file_refuses_a_statue_rather_than_write_the_block():
    """PyBullet's SDF holds the block; asked for a statue's it says so in one line instead of
    writing a file of another body."""
    _, system = sc.example("bust", 1.0, "fixed")
    with pytest.raises(InputError, match="model file holds the block") as e:
        get_engine("bullet").scene_text(system)
    assert "\n" not in str(e.value)
