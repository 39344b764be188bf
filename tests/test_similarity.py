"""Similarity law (Dimitrakopoulos & DeJong 2012): the rigid model is self-similar, so the
same dimensionless case — λ, μ, T·p, ξ, θ0/α — at any size gives the same θ/α against
t·p. The oracle is the law itself: three sizes two decades apart must agree with each
other. The integrator's own settings are in seconds, so they are scaled with 1/p here
(otherwise each size would be integrated to a different accuracy)."""
import math

import numpy as np
import pytest

from isorock.analytic.settings import AnalyticSettings
from isorock.analytic.system import System
from isorock.validate.core.engines import get_engine

HEIGHTS = (0.1, 1.0, 10.0)  # m
SLENDERNESS, MASS_RATIO, PERIOD_P, DAMPING, THETA0 = 4.0, 1.0, 12.0, 0.1, 0.6  # λ, μ, T·p, ξ, θ0/α
SPAN = 15.0  # run length in units of 1/p: several impacts on the light isolated base


def _case(height: float, fixed: bool) -> System:
    width = height / SLENDERNESS
    mass = 2400.0 * height * width * width  # the density only sets a scale of force, not θ(t)
    probe = System.fixed(height=height, width=width, mass=mass)
    if fixed:
        return probe
    return System.isolated(height=height, width=width, mass=mass, base_mass=mass / MASS_RATIO,
                           period=PERIOD_P / probe.p, damping_ratio=DAMPING)


def _dimensionless(system: System):
    s = AnalyticSettings(output_dt=0.02 / system.p, max_step=0.05 / system.p)
    traj = get_engine("analytic").simulate(system, None, settings=s, duration=SPAN / system.p,
                                           theta0=THETA0 * system.alpha)
    impacts = traj.counted_impacts
    return (np.asarray(traj.t) * system.p, np.asarray(traj.theta) / system.alpha,
            np.array([i.t * system.p for i in impacts]),
            np.array([i.theta_dot_post / (system.p * system.alpha) for i in impacts]))


@pytest.mark.parametrize("fixed", [True, False], ids=["fixed base", "isolated base"])
def test_analytic_model_is_self_similar(fixed):
    runs = [_dimensionless(_case(h, fixed)) for h in HEIGHTS]
    tp, theta, impact_tp, rate = runs[1]
    assert len(impact_tp) >= 3  # the case must reach impacts for the law to say anything
    for other_h, (tp_o, theta_o, impact_tp_o, rate_o) in zip((HEIGHTS[0], HEIGHTS[2]), (runs[0], runs[2])):
        assert len(impact_tp_o) == len(impact_tp), other_h
        np.testing.assert_allclose(impact_tp_o, impact_tp, rtol=0, atol=1e-9, err_msg=f"t·p of impacts, H {other_h}")
        np.testing.assert_allclose(rate_o, rate, rtol=0, atol=1e-9, err_msg=f"θ̇⁺/(pα), H {other_h}")
        # θ/α on the common dimensionless grid (the output grid is in units of 1/p)
        common = np.intersect1d(np.round(tp, 9), np.round(tp_o, 9))
        assert len(common) > 100
        a = np.interp(common, tp, theta)
        b = np.interp(common, tp_o, theta_o)
        assert np.max(np.abs(a - b)) < 1e-9, f"θ/α against t·p, H {other_h}: {np.max(np.abs(a - b)):.3g}"


# --- the contact engines at their defaults ------------------------------------------------
# The analytic model being self-similar (above), a contact engine whose defaults treat every
# size alike stays within its tolerance of the analytic model's dimensionless history at
# every size. PyBullet's default is fixed in seconds (its 1/3000 s step and 4 ms control
# step): at H 0.1 m the contact lasts a larger share of a half-cycle and it leaves its
# tolerance on the isolated base (issue 19, docs/bullet.md), which the strict xfail records
# until its default follows the system as MuJoCo's does.
KEPT = 4  # impacts judged, as the tolerance table's per-impact β error


def _contact_case(engine: str, height: float, fixed: bool):
    from isorock.validate.core.measure import beta_errors
    system = _case(height, fixed)
    traj = get_engine(engine).simulate(system, None, duration=SPAN / system.p, theta0=THETA0 * system.alpha)
    impacts = traj.counted_impacts
    return (np.array([i.t * system.p for i in impacts]), np.array([i.amplitude / system.alpha for i in impacts]),
            beta_errors(traj, KEPT))


def _rigid_case(height: float, fixed: bool):
    system = _case(height, fixed)
    traj = get_engine("analytic").simulate(system, None, duration=SPAN / system.p, theta0=THETA0 * system.alpha)
    impacts = traj.counted_impacts
    return np.array([i.t * system.p for i in impacts]), np.array([i.amplitude / system.alpha for i in impacts])


#: the cases measured outside tolerance at the former defaults, fixed in seconds: PyBullet
#: at H 0.1 m on the isolated base (10 of 12 impacts, β 2.2%), MuJoCo at H 0.1 m on both
#: bases (t₁ 0.21–0.25%; isolated: 9 of 12 impacts, β 2.3%). None since their step and
#: contact follow the system (Settings.for_system, issue 19).
_KNOWN_DEFECT: set = set()
_CASES = [pytest.param(e, f, h, id=f"{e}-{'fixed' if f else 'isolated'}-H{h:g}",
                       marks=[pytest.mark.xfail(strict=True, reason="issue 19: defaults fixed in seconds")]
                       if (e, f, h) in _KNOWN_DEFECT else [])
          for e in ("mujoco", "bullet") for f in (True, False) for h in HEIGHTS]


@pytest.mark.parametrize("engine, fixed, height", _CASES)
def test_contact_engine_defaults_follow_the_similarity_law(engine, fixed, height):
    from isorock.validate.core.tolerances import tolerance
    pytest.importorskip({"mujoco": "mujoco", "bullet": "pybullet"}[engine])
    tp, amplitude, errors = _contact_case(engine, height, fixed)
    tp_ref, amplitude_ref = _rigid_case(height, fixed)
    assert abs(len(tp) - len(tp_ref)) <= tolerance(engine, "impacts_diff").limit
    n = min(len(tp), len(tp_ref))
    assert abs(tp[0] / tp_ref[0] - 1) <= tolerance(engine, "first_impact_time_rel_error").limit
    # half-cycle peaks θ/α against t·p's impacts: the dimensionless history at its extremes
    assert np.max(np.abs(amplitude[:n] - amplitude_ref[:n])) <= tolerance(engine, "theta_max_diff").limit
    assert max(map(abs, errors)) <= tolerance(engine, "beta_rel_error_per_impact").limit


def test_mujocos_contact_is_in_the_blocks_own_units():
    """MuJoCo's default puts every contact time and length in the block's units (step and
    time constant ∝ 1/p_eff, impedance width ∝ R), and gravity is the same at every size,
    so its scene is the same dimensionless system at 0.1, 1 and 10 m: up to the first
    impact (before the measuring window, the one thing still in seconds) the history in
    units of 1/p is the same to rounding, not only within the engine's tolerance."""
    pytest.importorskip("mujoco")
    for fixed in (True, False):
        tp = [_contact_case("mujoco", h, fixed)[0][0] for h in HEIGHTS]
        assert max(tp) - min(tp) <= 1e-6 * tp[0], (fixed, tp)


@pytest.mark.parametrize("engine, share", [("mujoco", 0.002 / 6), ("bullet", 0.0003)])
def test_run_json_lists_the_step_derived_for_the_block(engine, share, tmp_path):
    """`isorock run --json` names the numbers the run used: a 0.2 m block on a light base
    steps at share/p_eff, p_eff the rocking rate with the base's recoil written out here
    from the closed form (p = √(3g/4R), the pivot inertia (4/3)mR² less m h²·μ/(1+μ))."""
    import json
    from isorock.validate.cli.main import main
    pytest.importorskip({"mujoco": "mujoco", "bullet": "pybullet"}[engine])
    h, b, mu = 0.1, 0.025, 4.0
    R = math.hypot(h, b)
    p = math.sqrt(3 * 9.81 / (4 * R))
    p_eff = p / math.sqrt(1 - (h * h / R / R) * (3 / 4) * mu / (1 + mu))
    out = tmp_path / "run.json"
    assert main(["run", "--engine", engine, "--height", "0.2", "--width", "0.05", "--mass", "2",
                 "--base-mass", "0.5", "--period", "0.5", "--damping-ratio", "0.1", "--theta0", "0.5",
                 "--duration", "0.3", "--json", str(out)]) == 0
    settings = json.loads(out.read_text())["settings"]
    dt = settings["timestep"]
    if engine == "mujoco":  # the step is made a whole divisor of the run's 0.3 s: at most a step finer
        assert 0.3 / dt == pytest.approx(round(0.3 / dt), abs=1e-6)
        assert share * (1 - dt / 0.3) <= dt * p_eff <= share * (1 + 1e-9)
        assert settings["solref"][0] * p_eff == pytest.approx(6 * share, rel=1e-9)  # τ·p_eff = 0.002
    else:
        assert dt * p_eff == pytest.approx(share, rel=1e-9)
    assert settings["follow_system"] is False  # final: what the run used
