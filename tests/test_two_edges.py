"""Issue 36: the exact model of a statue with two different tipping edges (System.body, a
PlanarBody: its centre of mass h, levers b₊ and b₋ to the two edges, inertia I_c).

Independent oracles:
- the impact map (coefficients.edge_impact, from momentum conservation) against a Newton–Euler
  impulse solve written here from the geometry (numpy.linalg.solve), on a fixed base and a free one;
- the rectangle as a PlanarBody: the paper's closed forms to 1e-12, and the same runs;
- the mirror law: the body (b₊, b₋) under ẍg(t) is the body (b₋, b₊) under −ẍg(t) with θ → −θ;
- free rocking on a fixed base: the time to the first impact by quadrature of the energy
  integral, and the peak on the other edge from the energy after the impact;
- a separate integrator written from the same equations (tests/asymmetric_rk4.py: RK4 with its
  impacts located in the step) on a record: the peak φ/α per edge, impacts and the verdict;
- the energy balance on an isolated base.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import quad

from isorock.analytic.coefficients import beta, beta2, edge_impact
from isorock.analytic.errors import InputError
from isorock.analytic.hybrid import simulate
from isorock.analytic.motion import GroundMotion, load_motion
from isorock.analytic.system import FrictionPendulum, PlanarBody, System
from isorock.validate.tools.experiments.study import SIMULATE_BODY

G = 9.81
M = 3800.0
#: a statue whose centre of mass sits off the middle of its footprint: α₊ 0.245, α₋ 0.423 rad
BODY = PlanarBody(centre_height=1.0, lever_forward=0.25, lever_backward=0.45, inertia=M * (0.35**2 + 1.0) / 3)
MIRROR = PlanarBody(centre_height=1.0, lever_forward=0.45, lever_backward=0.25, inertia=BODY.inertia)
#: a stockier one for the isolated base (α₊ 0.291, α₋ 0.398 rad), which BODY's forward edge would
#: overturn at once under what rocks it there
STOCKY = PlanarBody(centre_height=1.0, lever_forward=0.3, lever_backward=0.42, inertia=BODY.inertia)
STOCKY_MIRROR = PlanarBody(centre_height=1.0, lever_forward=0.42, lever_backward=0.3, inertia=BODY.inertia)


def fixed(body):
    return dataclasses.replace(System.fixed(height=2.0, width=0.7, mass=M), body=body)


def isolated(body, isolator=None):
    if isolator is not None:
        return dataclasses.replace(System.with_isolator(height=2.0, width=0.7, mass=M, base_mass=M,
                                                        isolator=isolator), body=body)
    return dataclasses.replace(System.isolated(height=2.0, width=0.7, mass=M, base_mass=M, period=1.5,
                                               damping_ratio=0.2), body=body)


def impulse_solve(m, m_b, h, i_c, b_from, b_to, theta_dot_pre, u_dot_pre):
    """(θ̇⁺, u̇⁺) by Newton–Euler impulses. Frame: x right, z up, the centre of mass's foot at the
    origin, corner s at x = s·b_s, θ > 0 clockwise about corner +1 (so Ω = −θ̇, CCW positive).
    Unknowns v_x, v_z, Ω, u̇ (after) and the new edge's impulse P_x, P_z on the block: the block's
    momentum and angular momentum about its centre of mass change by P and r × P, the base's by
    −P_x (m_b None: a fixed base, u̇ stays 0), and afterwards the new edge moves with the base."""
    s = 1.0  # the block lands from corner +1 onto corner −1
    v_pre = np.array([u_dot_pre + h * theta_dot_pre, s * b_from * theta_dot_pre])
    omega_pre = -theta_dot_pre
    rx, rz = -s * b_to, -h  # the new edge from the centre of mass
    # rows: m(v − v⁻) − P = 0 (2); I_c(Ω − Ω⁻) − (r_x P_z − r_z P_x) = 0; base; edge velocity (2)
    A = np.zeros((6, 6))
    rhs = np.zeros(6)
    A[0, [0, 4]] = m, -1.0
    rhs[0] = m * v_pre[0]
    A[1, [1, 5]] = m, -1.0
    rhs[1] = m * v_pre[1]
    A[2, 2], A[2, 4], A[2, 5] = i_c, rz, -rx
    rhs[2] = i_c * omega_pre
    if m_b is None:
        A[3, 3] = 1.0  # u̇⁺ = u̇⁻ = 0
        rhs[3] = u_dot_pre
    else:
        A[3, 3], A[3, 4] = m_b, 1.0
        rhs[3] = m_b * u_dot_pre
    A[4, [0, 2, 3]] = 1.0, -rz, -1.0  # v_x + Ω(−r_z) = u̇
    A[5, [1, 2]] = 1.0, rx  # v_z + Ω r_x = 0
    vx, vz, omega, ud, px, pz = np.linalg.solve(A, rhs)
    return -omega, ud


@pytest.mark.parametrize("base_mass", [None, 380.0, 3800.0, 38000.0])
@pytest.mark.parametrize("levers", [(0.25, 0.45), (0.45, 0.25), (0.3, 0.3), (0.05, 0.6)])
def test_the_two_edge_impact_map_is_the_impulse_solution(base_mass, levers):
    b_from, b_to = levers
    h, i_c = 1.0, 900.0
    b, b2 = edge_impact(M, base_mass, h, i_c, b_from, b_to)
    thd, ud = -0.7, 0.13  # landing from corner +1 (θ̇⁻ < 0)
    want_thd, want_ud = impulse_solve(M, base_mass, h, i_c, b_from, b_to, thd, 0.0 if base_mass is None else ud)
    assert b * thd == pytest.approx(want_thd, rel=1e-12, abs=1e-15)
    if base_mass is not None:
        assert ud + b2 * thd == pytest.approx(want_ud, rel=1e-12, abs=1e-15)
    else:
        assert b2 == 0.0


@pytest.mark.parametrize("lam", [1.5, 2.857, 8.0])
@pytest.mark.parametrize("mu", [0.0, 0.2, 1.0, 5.0])
def test_the_rectangle_is_the_special_case_of_the_two_edge_map(lam, mu):
    b, m = 0.35, M
    h = lam * b
    body = PlanarBody.rectangle(2 * h, 2 * b, m)
    got = edge_impact(m, None if mu == 0 else m / mu, h, body.inertia, b, b)
    assert got[0] == pytest.approx(beta(lam, mu), rel=1e-12, abs=1e-14)
    assert got[1] == pytest.approx(beta2(lam, mu, h), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("make", [fixed, isolated], ids=["fixed", "isolated"])
def test_the_rectangle_given_as_a_body_runs_as_the_rectangle(make):
    rect = make(None)
    as_body = make(PlanarBody.rectangle(2.0, 0.7, M))
    motion = load_motion("sine:amp=0.5,freq=1.5,cycles=2" if make is fixed else "sine:amp=1.0,freq=1.5,cycles=2")
    a, b = simulate(rect, motion, duration=6.0), simulate(as_body, motion, duration=6.0)
    assert a.impact_count == b.impact_count >= 5
    assert np.max(np.abs(a.theta - np.interp(a.t, b.t, b.theta))) < 1e-12
    assert b.theta_max_over_alpha == pytest.approx(a.theta_max_over_alpha, rel=1e-12)


def _record_samples(sign=1.0, seed=7, amp=3.5, duration=6.0, dt=0.005):
    """A seeded record (m/s²): four sines of random phase and weight under a sin² envelope."""
    rng = np.random.default_rng(seed)
    t = np.arange(0, duration, dt)
    a = sum(rng.normal() * np.sin(2 * np.pi * f * t + rng.uniform(0, 6)) for f in (0.8, 1.3, 2.1, 3.4))
    return sign * amp * a / np.max(np.abs(a)) * np.sin(np.pi * t / duration) ** 2


def _record(sign=1.0, seed=7, amp=6.0, duration=6.0, dt=0.005):
    return GroundMotion.from_array(_record_samples(sign, seed, amp, duration, dt), dt=dt, units="m/s2",
                                   name="synthetic")


def _sine(sign=1.0, amp_g=0.8, freq=1.5, cycles=2, dt=0.002):
    """Two cycles of a sine (a stored record, so that its sign can be turned)."""
    t = np.arange(0.0, cycles / freq + 1e-12, dt)
    return GroundMotion.from_array(sign * amp_g * G * np.sin(2 * np.pi * freq * t), dt=dt, units="m/s2", name="sine")


PENDULUM = FrictionPendulum(radius=1.0, friction_coefficient=0.08)


@pytest.mark.parametrize("make, body, mirror, motion", [
    (fixed, BODY, MIRROR, _record),
    (isolated, STOCKY, STOCKY_MIRROR, _sine),
    (lambda b: isolated(b, PENDULUM), STOCKY, STOCKY_MIRROR, _sine),
], ids=["fixed", "isolated", "pendulum"])
def test_the_mirror_law(make, body, mirror, motion):
    """A body under ẍg(t) is its mirror image under −ẍg(t), θ → −θ, u → −u."""
    a = simulate(make(body), motion(1.0), duration=8.0)
    b = simulate(make(mirror), motion(-1.0), duration=8.0)
    assert a.impact_count == b.impact_count >= 3 and not a.overturned
    assert np.max(a.theta) > 0.05 and np.min(a.theta) < -0.005  # it rocks about both edges
    assert np.max(np.abs(a.theta + np.interp(a.t, b.t, b.theta))) < 1e-9 * np.max(np.abs(a.theta))
    assert np.max(np.abs(a.u + np.interp(a.t, b.t, b.u))) < 1e-9 * max(np.max(np.abs(a.u)), 1e-12)
    assert [i.t for i in a.counted_impacts] == pytest.approx([i.t for i in b.counted_impacts], abs=1e-9)


@pytest.mark.parametrize("start_side", [1, -1])
def test_free_rocking_first_impact_and_next_peak_from_energy(start_side):
    """Released at rest at 40% of the smaller α, on a fixed base: the landing time is the energy
    integral ∫ dθ / θ̇(θ), ½ I_s θ̇² = m g R_s (cos(α_s − θ0) − cos(α_s − θ)); after the impact
    (θ̇⁺ = β θ̇⁻) the block rises on the other edge to the peak where its kinetic energy is spent."""
    system = fixed(BODY)
    s = start_side
    a_s, r_s, i_s = system.edge_alpha(s), system.edge_radius(s), system.edge_inertia(s)
    theta0 = 0.4 * min(BODY.alpha(1), BODY.alpha(-1))  # (at 0.6 the impact throws it over the forward edge)

    def rate(th):
        return math.sqrt(max(2 * M * G * r_s * (math.cos(a_s - theta0) - math.cos(a_s - th)) / i_s, 0.0))
    # θ = θ0 − x²: the integrand 2x/θ̇ stays finite at the release (θ̇ ∝ x there)
    t_land = quad(lambda x: 2 * x / rate(theta0 - x * x), 0.0, math.sqrt(theta0), limit=200, epsabs=0,
                  epsrel=1e-12)[0]
    thd_pre = rate(0.0)
    b_coef = edge_impact(M, None, BODY.centre_height, BODY.inertia, BODY.lever(s), BODY.lever(-s))[0]
    kinetic = 0.5 * system.edge_inertia(-s) * (b_coef * thd_pre) ** 2
    a_o, r_o = system.edge_alpha(-s), system.edge_radius(-s)
    peak = a_o - math.acos(math.cos(a_o) + kinetic / (M * G * r_o))  # m g R(cos(α − θp) − cos α) = T

    tr = simulate(system, None, duration=6 * t_land, theta0=s * theta0)
    first = tr.impacts[0]
    assert first.t == pytest.approx(t_land, rel=1e-7)
    assert abs(first.theta_dot_pre) == pytest.approx(thd_pre, rel=1e-7)
    assert first.theta_dot_post / first.theta_dot_pre == pytest.approx(b_coef, rel=1e-10)
    other = -s * tr.theta[(tr.t > first.t) & (tr.t < tr.impacts[1].t)]
    assert np.max(other) == pytest.approx(peak, rel=1e-6)


def test_the_separate_integrator_on_a_record():
    """tests/asymmetric_rk4.py integrates the same body by RK4, its impacts located inside the
    step (written from the equations apart from analytic/): the same verdict, the peak φ/α per
    edge to its O(h⁴) step error (measured 2e-7), and as many impacts."""
    import asymmetric_rk4 as asymmetric
    record = _record(1.0, seed=11, amp=5.0)
    tr = simulate(fixed(BODY), record, duration=record.end_time + 3.0)
    i_c, h = BODY.inertia, BODY.centre_height
    edges = (1, -1)
    params = dict(alpha=np.array([BODY.alpha(s) for s in edges]), R=np.array([BODY.radius(s) for s in edges]),
                  I=np.array([i_c + M * BODY.radius(s) ** 2 for s in edges]), m=M, g=G,
                  ratio=np.array([asymmetric.impact_ratio(i_c, M, h, BODY.lever(s), BODY.lever(-s), BODY.radius(-s))
                                  for s in edges]))
    over, peak, impacts = asymmetric.simulate(params, _record_samples(1.0, seed=11, amp=5.0), 0.005, pad=3.0)
    assert over == tr.overturned and not over and tr.impact_count >= 10
    # every impact, the Zeno tails' too: those end at a rest floor the oracle sets per edge and the
    # model once per body (rest_velocity·p·α of the weaker edge), a few impacts apart in 60-odd
    assert abs(impacts - len(tr.impacts)) <= 0.1 * len(tr.impacts)
    per_edge = max(max(np.max(tr.theta), 0.0) / BODY.alpha(1), max(-np.min(tr.theta), 0.0) / BODY.alpha(-1))
    assert peak == pytest.approx(per_edge, rel=1e-5)
    assert tr.theta_max_over_alpha == pytest.approx(per_edge * BODY.alpha(1) / fixed(BODY).alpha, rel=1e-12)


@pytest.mark.parametrize("make, body, motion", [
    (fixed, BODY, lambda sign: _record(sign)),
    (fixed, BODY, lambda sign: load_motion("sine:amp=0.3,freq=1.5,cycles=3")),
    # the Ricker's peak (0.6 g) lifts it about the backward edge (0.45 g), its lobes (0.27 g)
    # about the forward one (0.25 g)
    (fixed, BODY, lambda sign: load_motion("ricker:amp=0.6,freq=2")),
    (isolated, STOCKY, _sine),
    (isolated, STOCKY, lambda sign: _record(sign, amp=20.0)),
    (lambda b: isolated(b, PENDULUM), STOCKY, _sine),
], ids=["fixed-record", "fixed-sine", "fixed-ricker", "isolated-sine", "isolated-record", "pendulum"])
def test_the_compiled_kernel_runs_two_edges_as_the_reference_does(make, body, motion):
    """Both paths of the exact model on a statue of two edges: the compiled kernel's closed forms at
    rest (a fixed base's first uplift from the motion itself, each edge its own threshold:
    physics.first_uplift, a pulse's crossings of each edge's level; an isolated base's closed-form translation,
    physics.translation_uplift) and its events against SciPy's DOP853 with event location: the same
    impacts and uplifts, the impacts' times to 1e-9 s, θ on the output grid both store to 1e-8 rad
    (test_fast.py's limits for the rectangle)."""
    from isorock.analytic.fast import compare_on_grid, simulate_fast
    system, m = make(body), motion(1.0)
    ref = simulate(system, m, duration=8.0)
    fast = simulate_fast(system, m, duration=8.0)
    assert ref.impact_count == fast.impact_count >= 2
    assert len(ref.uplift_times) == len(fast.uplift_times) >= 1
    assert np.allclose(ref.uplift_times, fast.uplift_times, atol=1e-9)
    assert np.allclose([i.t for i in ref.impacts], [i.t for i in fast.impacts], atol=1e-9)
    assert compare_on_grid(ref, fast) < 1e-8
    assert fast.overturned == ref.overturned
    assert fast.theta_max_over_alpha == pytest.approx(ref.theta_max_over_alpha, rel=1e-7)


def test_the_energy_balance_on_an_isolated_base():
    tr = simulate(isolated(STOCKY), _sine(), duration=8.0)
    assert tr.impact_count >= 3 and not tr.overturned
    e = tr.energy
    balance = e.kinetic + e.potential - e.ground_work + e.dashpot_loss + e.impact_loss
    scale = np.max(np.abs(e.ground_work))
    assert np.max(np.abs(balance - balance[0])) < 1e-7 * scale


def test_contact_engines_refuse_a_body_in_one_line():
    """The engines that build the box H × B only refuse two edges (MJX); those that carry a statue's
    mesh on a free body refuse two edges given by their numbers alone, with no mesh (PyBullet, DART;
    MuJoCo builds that body as the box on its edges: tests/test_statue_engines.py)."""
    from isorock.validate.core.engines import get_engine
    for engine, says in (("mjx", "two different edges"), ("bullet", "given by its numbers alone"),
                         ("dart", "given by its numbers alone is not built for DART")):
        try:
            spec = get_engine(engine)
        except ImportError:  # an optional engine not installed here
            continue
        with pytest.raises(InputError, match=says) as e:
            spec.simulate(fixed(BODY), None, duration=1.0)
        assert "\n" not in str(e.value)
    tr = get_engine("analytic").simulate(fixed(BODY), None, duration=1.0, theta0=0.1)
    assert tr.engine == "analytic" and tr.impact_count >= 1


def test_a_body_and_the_options_it_does_not_take():
    with pytest.raises(InputError, match="lever_backward"):
        PlanarBody(centre_height=1.0, lever_forward=0.3, lever_backward=-0.1, inertia=1.0)
    with pytest.raises(InputError, match="friction"):
        dataclasses.replace(fixed(BODY), friction=0.5)
    with pytest.raises(InputError, match="theta0"):  # past the forward edge's α, within the backward's
        simulate(fixed(BODY), None, duration=1.0, theta0=0.3)
    assert simulate(fixed(BODY), None, duration=0.5, theta0=-0.3).impact_count >= 0


def _hull_script():
    import importlib.util
    from pathlib import Path
    path = Path(__file__).resolve().parents[1] / "docs" / "scripts" / "hull_two_edges.py"
    spec = importlib.util.spec_from_file_location("hull_two_edges", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name, scale", [("bust", 1.0), ("bust", 3.0), ("obelisk", 0.5), ("obelisk", 1.0),
                                         ("obelisk", 3.0)])
def test_mujocos_hull_of_a_statue_rocks_as_the_exact_model_of_its_two_edges(name, scale):
    """Issue 36: the statue's convex hull on a free joint in MuJoCo (the shake-table scene) against
    the exact model of its two edges, one sine cycle along the direction it tips first, scaled
    with the statue (its θmax/α 0.3 at every size: the exact model's similarity law, checked here
    too, to the pulse's sampling). Where the scene does not hold (the 0.5× bust, the amphora's round foot) is said in
    docs/statues.md and the tolerance's reason, not tested as agreement."""
    pytest.importorskip("trimesh")
    from isorock.validate.core.tolerances import tolerance
    hull = _hull_script()
    k = hull.amplitude_for(hull.statue(name, 1.0)[1], hull.TARGET)
    body, system = hull.statue(name, scale)
    a, dt = hull.pulse(system, k)
    tr = hull.exact(system, a, dt)
    # the same θmax/α at every size, but for the pulse's samples (1 ms at every size: 1e-4 apart)
    assert tr.theta_max_over_alpha == pytest.approx(hull.TARGET, rel=1e-3) and not tr.overturned
    from isorock.validate.core.engines import get_engine
    got = SIMULATE_BODY.of(get_engine("mujoco").spec)(body.vertices, body.com, body.inertia, body.mass, a, dt,
                                                  duration=a.size * dt + 3.0)
    assert not got["overturned"]
    error = got["tilt_max"] / float(np.max(np.abs(tr.theta))) - 1.0
    assert abs(error) <= tolerance("mujoco", "hull_theta_max_rel_error").limit, error


def test_the_batch_gives_each_runs_summary_on_two_edges():
    """fast.simulate_batch (design's and the sweeps' path) on statues of two edges: each case's
    θmax/α (each way against its own edge, read by the kernel without a history), impacts and
    verdict are those of the run's own Trajectory."""
    from isorock.analytic.fast import simulate_batch, simulate_fast
    systems = [fixed(BODY), fixed(MIRROR), isolated(STOCKY), isolated(STOCKY, PENDULUM)]
    motions = [_record(1.0), _record(-1.0), _sine(), _sine()]
    rows = simulate_batch(systems, motions, duration=8.0, workers=1)
    for system, motion, row in zip(systems, motions, rows):
        tr = simulate_fast(system, motion, duration=8.0)
        assert row["impacts"] == tr.impact_count >= 3 and row["overturned"] == tr.overturned
        assert row["theta_max_over_alpha"] == pytest.approx(tr.theta_max_over_alpha, rel=1e-9)
        per_edge = max(-np.min(tr.theta) / system.edge_alpha(-1), np.max(tr.theta) / system.edge_alpha(1))
        assert per_edge == pytest.approx(tr.theta_max_over_alpha, rel=1e-12)


@pytest.mark.parametrize("body", [BODY, MIRROR], ids=["weaker-forward", "weaker-backward"])
def test_the_rest_pass_never_settles_a_statue_that_lifts_on_either_edge(body):
    """design's rest pass (analytic.rest_scales) answers without the kernel the runs whose block
    never lifts: it must see a statue lift on either edge, the weaker backward one too (a bust
    shaken along 180°). A rest pass compiled before the two-edge physics, kept by a cache stamped
    with rest_scales.py alone, did not (tests/test_kernel_cache.py; found by `design --check
    mujoco`). Oracle: the exact model's own first uplift."""
    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.rest_scales import rest_phases
    system = dataclasses.replace(System.isolated(**body.box, mass=M, base_mass=M, period=0.3, damping_ratio=0.1),
                                 body=body)
    t = np.arange(0.0, 6.0, 0.005)
    # a stiff isolator (T 0.3 s) passes a 0.5 Hz motion nearly whole: the base peaks between the two
    # edges' thresholds (0.25 and 0.45 g), so the statue lifts on its weaker edge only
    record = GroundMotion.from_array(0.36 * 9.80665 * np.sin(2 * np.pi * 0.5 * t) * np.minimum(1, t / 2), dt=0.005,
                                     units="m/s2", name="ramped sine")
    tr = simulate_fast(system, record, duration=6.0)
    assert tr.uplifts, "the case must lift for the test to mean anything"
    uplift, _ = rest_phases([system], [record], [[1.0]], [6.0])
    assert uplift[0, 0, 0] <= tr.uplift_times[0] + 1e-9
