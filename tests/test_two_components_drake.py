"""Two horizontal ground-motion components in Drake (issue 36; docs/statues.md, "Two horizontal
components", Drake): the oracles Capabilities.transverse rests on, as MuJoCo's and PyBullet's
(tests/test_two_components.py, whose helpers these reuse): a zero second component is the run of
one, the block along y alone is the exact planar model along y, free rocking of the pair's free
block meets its corner spheres' closed forms, turning the pair and the statue together changes the
total tilt by no more than the integrator's error grows to, and the command reports the 3-D
measures. Drake's runs cost seconds each: the cases are few and short (the rocking's tail cut)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

pd = pytest.importorskip("pydrake.all", reason="pydrake is not installed (the drake extra)")
pytest.importorskip("mujoco")  # the helpers' module needs it
pytest.importorskip("trimesh")

from test_two_components import (ALONG_Y, _leans, _statue_system, bust,  # noqa: E402,F401 (bust: a fixture)
                                 check_along_y, check_turned, check_zero_component, run_reports_3d,
                                 turned_pair_runs)

from isorock.analytic import shape  # noqa: E402
from isorock.analytic.errors import InputError  # noqa: E402
from isorock.analytic.motion import GroundMotion, load_motion  # noqa: E402
from isorock.analytic.system import System  # noqa: E402
from isorock.drake_models import Settings  # noqa: E402
from isorock.drake_models.scene import (DEPTH_FRACTION, scene_text, sphere_geometry_beta,  # noqa: E402
                                        sphere_geometry_first_impact_time)
from isorock.validate.cli.main import main  # noqa: E402
from isorock.validate.core.engines import get_engine  # noqa: E402
from isorock.validate.core.tolerances import tolerance  # noqa: E402

DRAKE, EXACT = get_engine("drake"), get_engine("analytic")
#: the linear isolator of ALONG_Y's second case (T 1 s, ξ 0.2), the block on it
ISOLATED = ALONG_Y[1].values[0]


def test_the_capability_is_said():
    assert DRAKE.capabilities.transverse


def test_the_pairs_scene_is_a_free_block_and_a_base_on_two_joints_of_the_same_spring_and_dashpot():
    """The scene of two components: the block a free body on its four bottom corner spheres, the
    base on x then y prismatic joints (a massless carriage between), each with the isolator's k and
    c; the carriage is massless, so each joint moves the plate's m_b alone (the mass matrix's base
    block is m_b·I: the free block is not carried by the joints)."""
    plant = pd.MultibodyPlant(0.0)
    pd.Parser(plant).AddModelsFromString(scene_text(ISOLATED, Settings(), transverse=True), "sdf")
    plant.Finalize()
    assert plant.GetBodyByName("block").is_floating_base_body()
    assert plant.num_positions() == 7 + 2 and plant.num_velocities() == 6 + 2
    joints = [plant.GetJointByName(n) for n in ("isolator", "isolator_y")]
    assert [list(j.translation_axis()) for j in joints] == [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    assert [j.default_damping() for j in joints] == [ISOLATED.damping] * 2
    springs = [plant.get_force_element(pd.ForceElementIndex(i)) for i in range(plant.num_force_elements())]
    stiffness = sorted(s.stiffness() for s in springs if isinstance(s, pd.PrismaticSpring))
    assert stiffness == [ISOLATED.stiffness] * 2
    context = plant.CreateDefaultContext()
    mass = plant.CalcMassMatrix(context)
    base = [j.velocity_start() for j in joints]
    assert mass[np.ix_(base, base)] == pytest.approx(ISOLATED.base_mass * np.eye(2), rel=1e-12)
    # one component: the scene as it was (the planar joint, one isolator joint)
    assert "isolator_y" not in scene_text(ISOLATED, Settings()) and 'type="planar"' in scene_text(ISOLATED, Settings())


# --- (a) a zero second component is today's run ------------------------------------------

def test_a_zero_second_component_on_a_fixed_base_is_the_run_of_one_bit_for_bit(bust):
    """The statue is a free body in both scenes and a fixed base has no joint, so the pair's scene is
    the same plant; ÿg = 0 adds −0.0 to the body's y force, which changes no sum. Bit for bit, every
    history and every summary metric bar the wall time and the planar pivot's slip (dropped from a
    3-D run). 1.2 s: the bust's 5 impacts end at 1.15 s (the tail, resting, costs Drake the most)."""
    system = _statue_system(bust, shape.weakest_direction(bust)[0], False)
    motion = load_motion("sine:amp=0.7,freq=2,cycles=1")
    today = DRAKE.simulate(system, motion, duration=1.2)
    zero = DRAKE.simulate(system, motion.with_transverse(motion.scaled(0.0)), duration=1.2)
    check_zero_component(today, zero)
    assert today.impact_count >= 3


def test_a_zero_second_component_on_the_linear_isolator_is_the_run_of_one_to_the_integrators_error(bust):
    """On the isolator the pair's scene has two more states (the base's y joint), so Radau3's error
    control picks other steps: the two runs differ by the integrator's own error. At the default
    accuracy 1e-4 that is θ within 1.2% of its peak, u within 1e-3, θmax/α within 0.001 (each run
    within 0.0006 of a run at 1e-5), so the test runs at 1e-5, where it falls 10,000-fold: measured θ
    within 8.6e-7 of its peak, u within 5.3e-8, θmax/α within 4.2e-9, u_y 5e-12 m (the bust's hull,
    symmetric across its plane to roundoff, barely pushes the base along y), the same 3 impacts.
    Limits 1e-5 of the peak for θ and u, 1e-7 in θmax/α, 1e-10 m of u_y. 1.2 s: the impacts end at
    1.14 s."""
    system = _statue_system(bust, shape.weakest_direction(bust)[0], True)
    motion = load_motion("sine:amp=0.9,freq=2.5,cycles=1")
    settings = Settings(accuracy=1e-5)
    today = DRAKE.simulate(system, motion, duration=1.2, settings=settings)
    zero = DRAKE.simulate(system, motion.with_transverse(motion.scaled(0.0)), duration=1.2, settings=settings)
    check_zero_component(today, zero, within=1e-5, names=("theta", "u"), theta_max=1e-7, u_y=1e-10)


# --- (b) the block shaken along y alone is the exact planar model along y -----------------

@pytest.mark.parametrize("system, spec", ALONG_Y)
def test_the_block_shaken_along_y_alone_rocks_as_the_exact_model_along_y(system, spec):
    """Nothing along x, the pulse along y. Drake's block of a pair is a free body 2b × 2b × 2h on its
    four bottom corner spheres (DEPTH_FRACTION 1: a square footprint), so along y it is the same
    H × B. Judged by the rows every engine's statue is judged by (MuJoCo's: θmax/α, impacts, u_max;
    tests/statue_judging.py), its lean along x by Drake's out_of_plane row. Measured: θmax/α 0.4341
    against 0.4323, 11 / 11 impacts, lean along x 4.7e-9 rad (fixed); 0.2178 against 0.2181, 5 / 5,
    u_y 3.4e-4 from the exact u_max, the x joint 1.3e-9 m (linear)."""
    assert DEPTH_FRACTION == 1.0  # the square footprint this test and `run`'s box_body read
    motion = load_motion(spec)
    run = DRAKE.simulate(system, GroundMotion.zero().with_transverse(motion), duration=6.0)
    exact = EXACT.simulate(system, motion, duration=6.0)
    assert run.status == "completed"
    check_along_y(run, exact, system, rows="mujoco", plane="drake", direction_deg=1e-3, wobble_deg=1e-3)
    if not system.fixed_base:
        assert np.max(np.abs(run.u)) <= 1e-6 * exact.u_max  # the x joint barely moves


def test_the_pairs_free_block_rocks_freely_as_its_corner_spheres_closed_forms():
    """The pair's block (a free body, not the planar joint) from rest at 0.5·α about world +y under
    a pair of zero components: the first impact at the corner spheres' own t₁ and β
    (sphere_geometry_first_impact_time, sphere_geometry_beta: quadrature and momentum, apart from
    any integrator), by Drake's block rows; it stays in its plane (Drake's out_of_plane row). Measured:
    t₁ within 1.2e-5, β within 5e-5 over the 2 impacts of 1.6 s, its lean along y 0 (the planar
    block's scene, from the same start: 1.2e-4 and 2.2e-4)."""
    system = System.fixed(height=2.0, width=0.7, mass=3800.0)
    theta0 = 0.5 * system.alpha
    still = GroundMotion.zero().with_transverse(GroundMotion.zero())
    run = DRAKE.simulate(system, still, duration=1.6, theta0=theta0)
    r = Settings().for_system(system).corner_radius
    assert run.counted_impacts[0].t == pytest.approx(sphere_geometry_first_impact_time(system, theta0, r),
                                                     rel=tolerance("drake", "first_impact_time_rel_error").limit)
    errors = [i.beta / sphere_geometry_beta(system, r) - 1 for i in run.counted_impacts]
    assert len(errors) >= 2 and max(abs(e) for e in errors) <= tolerance("drake", "beta_rel_error").limit, errors
    lean_x, lean_y = _leans(run.extras["orientation"])
    assert np.max(np.abs(lean_y)) <= tolerance("drake", "out_of_plane").limit
    assert np.max(np.abs(lean_x - run.theta)) <= 1e-12  # θ is the lean towards x, as for a statue


# --- (c) turning the pair and the statue together -----------------------------------------

def test_turning_the_pair_and_the_statue_by_one_angle_gives_the_same_tilt_on_the_isolator(bust):
    """As MuJoCo's and PyBullet's test, on the linear isolator at 30° (the base's two joints and the
    body's y force at once), over 1.2 s (the bust rocks from 0.57 to 1.1 s). The hull meets the
    axis-aligned plate in a turned frame, and Radau3's error control (accuracy 1e-4) picks other
    steps there, so the runs differ by the integrator's error grown through the impacts: measured the
    total tilt's history within 1.04e-2 of its peak, its peak tilt/α within 0.0011, the base's travel
    √(u² + u_y²) within 3.7e-4 of its own, the direction at the peak turned by φ to 0.02°. Limits 2e-2,
    0.005 α (a quarter of the 0.02 α row peaks are judged by), 1e-3, 1°. That it is the integrator's:
    on the fixed base at 200° the history parts by 0.19 of its peak at 1e-4 late in the rocking (a
    small, twisting phase after 0.85 s; the peaks agree within 0.0002 α) and by 5.4e-3 at 1e-5."""
    turned = turned_pair_runs(DRAKE, bust, True, 30.0, lambda first: Settings().for_system(first), duration=1.2)
    check_turned(turned, 30.0, "drake")


# --- the command ------------------------------------------------------------------------------

def test_run_reports_the_3d_numbers_for_drake(tmp_path, capsys):
    """The block (its free body) on a fixed base under a pair, from the command line: the report's
    two-component part, and its planar run along y the exact model's run along y. 1.2 s: past the
    peak (0.35 α, measured) and before the block's late rocking on a corner, which costs Drake 6 s."""
    report = run_reports_3d(["--engine", "drake", "--height", "2", "--width", "0.7", "--mass", "3800", "--fixed-base",
                             "--motion", "sine:amp=0.5,freq=2,cycles=1", "--motion-transverse",
                             "sine:amp=0.5,freq=1.5,cycles=1", "--duration", "1.2"], tmp_path, capsys, "drake")
    two = report["two_components"]
    assert two["three_d"]["tilt_max_over_alpha"] > 0.1  # it rocks
    along_y = EXACT.simulate(System.fixed(height=2.0, width=0.7, mass=3800.0),
                             load_motion("sine:amp=0.5,freq=1.5,cycles=1"), duration=1.2)
    assert two["planar"]["y"]["theta_max_over_alpha"] == pytest.approx(along_y.theta_max_over_alpha, rel=1e-12)


def test_a_statue_on_a_friction_pendulum_under_an_equal_pair_slides_along_the_diagonal(tmp_path, capsys):
    """The bust on a friction pendulum under the same sine along x and y: it stays down, and the base
    slides along 45° as far as the exact model's base under that sine times √2 along one axis, each
    axis 1/√2 of it (the pendulum's friction is the same in every direction). Measured: +7.6e-4 along
    x, −7.4e-4 along y (MuJoCo 1.6e-6), against Drake's isolator_u_max_rel_error row."""
    common = ["--statue-example", "bust", "--mass", "80", "--isolator", "friction-pendulum", "--radius", "1",
              "--friction-coefficient", "0.05", "--base-mass", "150", "--duration", "1.5"]
    pair, along = tmp_path / "pair.json", tmp_path / "along.json"
    assert main(["run", "--engine", "drake", *common, "--motion", "sine:amp=0.5,freq=2",
                 "--motion-transverse", "sine:amp=0.5,freq=2", "--json", str(pair)]) == 0
    assert main(["run", "--engine", "analytic", *common, "--motion", f"sine:amp={0.5 * math.sqrt(2)!r},freq=2",
                 "--json", str(along)]) == 0
    capsys.readouterr()
    run, exact = json.loads(pair.read_text()), json.loads(along.read_text())
    assert exact["theta_max_over_alpha"] == 0.0 and run["two_components"]["three_d"]["tilt_max_over_alpha"] < 1e-4
    per_axis = exact["u_max"] / math.sqrt(2)
    for travel in (run["u_max"], run["two_components"]["three_d"]["base_y_max"]):
        assert abs(travel / per_axis - 1) <= tolerance("drake", "isolator_u_max_rel_error").limit


def test_a_pair_on_the_bilinear_bearing_is_one_line_and_exit_2(capsys):
    """Drake does not build the bilinear bearing, under a pair or not."""
    code = main(["run", "--engine", "drake", "--height", "2", "--width", "0.7", "--mass", "3800", "--isolator",
                 "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "0.1", "--yield-displacement", "0.01",
                 "--motion", "sine:amp=0.5,freq=2", "--motion-transverse", "sine:amp=0.5,freq=2"])
    err = capsys.readouterr().err
    assert code == 2 and "--isolator = 'bilinear'" in err and err.count("\n") == 1, err


def test_a_pair_on_the_hydroelastic_box_is_one_line():
    """The pair's block stands on corner spheres: the hydroelastic box (for comparison only,
    docs/drake.md) is not built for it, and says so before it steps."""
    motion = load_motion("sine:amp=0.5,freq=2,cycles=1")
    with pytest.raises(InputError, match="contact = 'hydroelastic'") as exc:
        DRAKE.simulate(System.fixed(height=2.0, width=0.7, mass=3800.0), motion.with_transverse(motion),
                       duration=1.0, settings=Settings(contact="hydroelastic"))
    assert len(str(exc.value).splitlines()) == 1
