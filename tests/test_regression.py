"""Regression tests: every engine against the analytic model and the closed forms, with
the limits of validate/core/tolerances.py, and against the golden metrics in tests/golden/.

Regenerate the goldens (only after checking that a change of numbers is intended):

    python -m pytest tests/test_regression.py -k golden --regenerate-golden          # every engine
    python -m pytest tests/test_regression.py -k "golden and mujoco" --regenerate-golden
"""
from __future__ import annotations

import functools
import importlib.metadata
import json
import math
from pathlib import Path

import pytest

from isorock.analytic.coefficients import beta as beta_closed
from isorock.validate.core.compare import compare, exact_first_impact_time, first_tilt
from isorock.validate.core.engines import CONTACT_ENGINES, ENGINE_NAMES, REFERENCE, get_engine
from isorock.validate.io.output import write_json
from isorock.validate.tools.report_run import effective_beta
from isorock.validate.core.scenarios import ROBUST_SINE, golden_scenarios
from isorock.validate.core.tolerances import (GOLDEN_TOLERANCES, TOLERANCES, GoldenTolerance, golden_tolerances,
                                         tolerance)

GOLDEN_DIR = Path(__file__).resolve().parent / "golden"


def _why_not_importable(name):
    try:
        get_engine(name)
    except ImportError as e:
        return f"engine {name!r} not importable: {type(e).__name__}: {e}"
    return None


SKIP = {name: _why_not_importable(name) for name in ENGINE_NAMES}


def engine_param(name):
    return pytest.param(name, id=name, marks=pytest.mark.skipif(SKIP[name] is not None, reason=SKIP[name] or ""))


ALL = [engine_param(n) for n in ENGINE_NAMES]
CONTACT = [engine_param(n) for n in CONTACT_ENGINES]
SCENARIOS = {sc.name: sc for sc in golden_scenarios()}


@functools.lru_cache(maxsize=None)
def run(engine: str, scenario: str):
    """Each (engine, scenario) is simulated once per session: the runs are a few seconds
    of simulated time each, shared by the tolerance tests and the golden test."""
    sc = SCENARIOS[scenario]
    return get_engine(engine).simulate(sc.system, sc.ground_motion(), duration=sc.duration, theta0=sc.theta0)


def within(engine, metric, value, context=""):
    tol = tolerance(engine, metric)
    assert value is not None and math.isfinite(value), f"{engine} {metric} {context}: not measured ({value})"
    assert value <= tol.limit, (f"{engine} {metric} {context}: {value:.4g} exceeds the tolerance "
                                f"{tol.limit:g} ({tol.reason})")


# --- closed forms ---------------------------------------------------------------------

@pytest.mark.parametrize("engine", ALL)
@pytest.mark.parametrize("scenario", ["free_isolated", "free_fixed"])
def test_free_rocking_beta(engine, scenario):
    eb = effective_beta(run(engine, scenario))
    assert eb["impacts_used"] >= 2, f"{engine} {scenario}: only {eb['impacts_used']} impacts above 0.1α"
    within(engine, "beta_rel_error", eb["beta_rel_error"],
           f"{scenario} (β {eb['beta']:.5f} against {eb['beta_closed']:.5f})")
    if scenario == "free_isolated":
        within(engine, "beta2_abs_error", eb["beta2_abs_error"],
               f"{scenario} (β₂/h {eb['beta2_over_h']:.5f} against {eb['beta2_over_h_closed']:.5f})")


@pytest.mark.parametrize("engine", ALL)
def test_time_to_first_impact(engine):
    sc = SCENARIOS["free_fixed"]
    t1 = exact_first_impact_time(sc.system, sc.theta0)
    tr = run(engine, "free_fixed")
    assert tr.counted_impacts, f"{engine}: no impact in free rocking"
    t = tr.counted_impacts[0].t
    within(engine, "first_impact_time_rel_error", abs(t / t1 - 1), f"(t₁ {t:.6f} s, exact {t1:.6f} s)")


def test_exact_first_impact_time_matches_model_md():
    sc = SCENARIOS["free_fixed"]
    assert exact_first_impact_time(sc.system, sc.theta0) == pytest.approx(0.5014170, abs=5e-8)


@pytest.mark.parametrize("scenario", list(SCENARIOS))
def test_analytic_every_impact_is_the_closed_form(scenario):
    tr = run(REFERENCE, scenario)
    ref = beta_closed(tr.system.slenderness, tr.system.mu)
    continued = [i for i in tr.impacts if i.continued]
    assert continued, f"{scenario}: no impact"
    worst = max(abs(i.beta / ref - 1) for i in continued)
    within(REFERENCE, "beta_rel_error", worst, f"{scenario}, every impact")
    within(REFERENCE, "energy_residual", tr.energy.relative_residual, scenario)


# --- contact engines against the analytic model ------------------------------------------

@pytest.mark.parametrize("engine", CONTACT)
@pytest.mark.parametrize("scenario", ["pulse_isolated", "pulse_fixed"])
def test_pulse_agrees_with_analytic(engine, scenario):
    c = compare(run(engine, scenario), run(REFERENCE, scenario))
    within(engine, "theta_max_diff", abs(c.theta_max_diff),
           f"{scenario} (θmax/α {c.theta_max_over_alpha:.4f} against {c.theta_max_over_alpha_ref:.4f})")
    assert c.overturn_agree, f"{engine} {scenario}: overturned {c.overturned}, analytic {c.overturned_ref}"
    assert c.first_uplift_diff is not None, f"{engine} {scenario}: uplift {c.first_uplift}, analytic {c.first_uplift_ref}"
    within(engine, "first_uplift_diff", abs(c.first_uplift_diff), scenario)
    if scenario == "pulse_isolated":
        within(engine, "u_max_rel_error", abs(c.u_max_rel_error),
               f"{scenario} (max|u| {c.u_max:.5f} m against {c.u_max_ref:.5f} m)")


@pytest.mark.parametrize("engine", CONTACT)
def test_deterministic(engine):
    sc = SCENARIOS["pulse_fixed"]
    again = get_engine(engine).simulate(sc.system, sc.ground_motion(), duration=sc.duration)
    first = run(engine, "pulse_fixed")
    assert (again.theta == first.theta).all() and (again.u == first.u).all(), f"{engine}: two runs differ"


# --- golden metrics -----------------------------------------------------------------------

def golden_metrics(engine: str) -> dict:
    """The numbers tests/golden/<engine>.json holds, from this session's runs."""
    out = {}
    for name, sc in SCENARIOS.items():
        tr = run(engine, name)
        m = {"theta_max_over_alpha": tr.theta_max_over_alpha, "impacts": tr.impact_count,
             "overturned": tr.overturned, "u_max": tr.u_max}
        if sc.theta0_over_alpha:
            eb = effective_beta(tr)
            m["beta_effective"] = eb["beta"]
            m["first_impact_time"] = eb["first_impact_time"]
        else:
            m["first_uplift"] = first_tilt(tr)
        out[name] = m
    return out


def _versions() -> dict:
    out = {}
    for dist in ("isorock", "numpy", "scipy", "mujoco", "pybullet", "numba"):
        try:
            out[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
            out[dist] = "not installed"
    return out


def golden_mismatches(actual: dict, golden: dict, tolerances: dict[str, GoldenTolerance]) -> list[str]:
    """One line per key that differs beyond its tolerance, with both values and the
    difference (keys without a tolerance must be equal)."""
    out = []
    for scenario in sorted(set(golden) | set(actual)):
        g, a = golden.get(scenario), actual.get(scenario)
        if g is None or a is None:
            out.append(f"{scenario}: {'missing from the golden file' if g is None else 'not computed'}")
            continue
        for key in sorted(set(g) | set(a)):
            gv, av = g.get(key), a.get(key)
            tol = tolerances.get(key)
            if isinstance(gv, (int, float)) and not isinstance(gv, bool) and isinstance(av, (int, float)) \
                    and not isinstance(av, bool) and tol is not None:
                diff = av - gv
                allowed = tol.atol + tol.rtol * abs(gv)
                if not abs(diff) <= allowed:
                    out.append(f"{scenario}.{key}: {av!r} against golden {gv!r}, difference {diff:+.3g} "
                               f"(allowed ±{allowed:.3g}: {tol.reason})")
            elif gv != av:
                out.append(f"{scenario}.{key}: {av!r} against golden {gv!r} (must be equal)")
    return out


REGENERATE = "python -m pytest tests/test_regression.py -k 'golden and {engine}' --regenerate-golden"


@pytest.mark.parametrize("engine", ALL)
def test_golden(engine, request):
    path = GOLDEN_DIR / f"{engine}.json"
    actual = json.loads(json.dumps(golden_metrics(engine)))
    if request.config.getoption("--regenerate-golden"):
        write_json(path, {"engine": engine, "versions": _versions(), "motion": ROBUST_SINE,
                          "regenerate": REGENERATE.format(engine=engine), "metrics": actual})
        pytest.skip(f"regenerated {path}")
    assert path.is_file(), f"{path} missing: run `{REGENERATE.format(engine=engine)}`"
    golden = json.loads(path.read_text())["metrics"]
    problems = golden_mismatches(actual, golden, golden_tolerances(engine))
    assert not problems, (f"{engine} differs from {path.name} (if intended, regenerate with "
                          f"`{REGENERATE.format(engine=engine)}`):\n  " + "\n  ".join(problems))


def test_golden_comparison_can_fail():
    golden = {"s": {"theta_max_over_alpha": 0.5, "impacts": 7, "overturned": False}}
    same = {"s": {"theta_max_over_alpha": 0.5 + 1e-9, "impacts": 7, "overturned": False}}
    off = {"s": {"theta_max_over_alpha": 0.51, "impacts": 9, "overturned": True}}
    assert golden_mismatches(same, golden, golden_tolerances("mujoco")) == []
    problems = golden_mismatches(off, golden, golden_tolerances("mujoco"))
    assert len(problems) == 3
    assert "0.51 against golden 0.5, difference +0.01" in problems[1] or any(
        "difference +0.01" in p for p in problems), problems


def test_every_tolerance_has_a_reason():
    for key, tol in TOLERANCES.items():
        assert tol.reason.strip() and tol.kind in ("max", "min", "equal"), key
    for key, tol in GOLDEN_TOLERANCES.items():
        assert tol.reason.strip() and tol.rtol >= 0 and tol.atol >= 0, key
    for engine in ENGINE_NAMES:  # every golden key of every engine has its own tolerance
        assert set(golden_tolerances(engine)) >= {"theta_max_over_alpha", "u_max", "impacts"}, engine
