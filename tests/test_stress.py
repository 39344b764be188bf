"""The stress grid's quick subset: every case finite, in time, and (analytic) with
its energy balance closed to 1e-6 of the input energy."""

import pytest

from isorock.analytic import System
from isorock.validate.core.scenarios import Scenario
from isorock.validate.tools.stress import (ENERGY_TOLERANCE, OUTSIDE, StressCase, compare_engines, drawn_cases,
                                           edge_cases, run_case, run_stress, stress_verdict, verdict)


def test_quick_edges_and_draws_pass_on_every_grid_engine():
    # Drake's continuous plant runs ~1–2 simulated s per CPU s here: it is no grid engine
    # (tests/test_drake.py covers it); the draws compare the report's engines
    from isorock.validate.core.engines import ENGINE_NAMES, campaign_engines
    engines = campaign_engines()
    assert "drake" not in engines
    results = run_stress(quick=True, time_limit=60, drawn=4)
    edges, draws = edge_cases(quick=True), drawn_cases(4)
    assert len(results) == len(edges) * len(engines) + len(draws) * len([e for e in engines if e in ENGINE_NAMES])
    bad = [(r["engine"], r["case"], r["status"], r.get("error"), r.get("energy_residual"))
           for r in results if r["verdict"] not in ("pass", OUTSIDE)]
    assert not bad
    # the exact model may stop where its assumptions break (drawn-0001: a squat block under 6.9 g
    # thrown off its pivot), saying so; then no engine is judged on that case
    outside = {r["case"] for r in results if r["verdict"] == OUTSIDE}
    for r in results:
        if r["case"] in outside:
            assert r["engine"].startswith("analytic") or r["cross"] == ""
            if r["verdict"] == OUTSIDE:
                assert r["status"] == "outside-model" and ("free flight" in r["message"] or "Painlevé" in r["message"])
    assert len(outside) <= 1
    assert {r["cross"] for r in results if r["case"] in {c.name for c in draws} and r["engine"] != "analytic"} <= {
        "agree", "chaotic", ""}
    for r in results:
        if r["engine"].startswith("analytic") and r["verdict"] == "pass":
            assert r["energy_residual"] < ENERGY_TOLERANCE
    # the grid does exercise rocking, impacts and overturning
    assert any(r["overturned"] for r in results) and any(r["impacts"] > 3 and not r["overturned"] for r in results)


def test_a_hang_is_reported_as_timeout():
    # 300 s of 1 ms record on the reference path cannot finish in 0.5 s
    case = StressCase(Scenario("slow", System.fixed(height=2, width=0.5, mass=1),
                               "noise:dt=0.001,pga=0.3,seconds=300,seed=0", 300.0), "forced time-out")
    r = run_case("analytic-reference", case, time_limit=0.5)
    assert r["status"] == "timeout" and r["verdict"] == "FAIL"


def test_verdict_rules():
    ok = dict(status="completed", finite=True, energy_residual=1e-12, sim_end=5.0, duration=5.0, overturned=False)
    assert verdict(ok) == "pass"
    assert verdict(dict(ok, finite=False)) == "FAIL"
    assert verdict(dict(ok, energy_residual=2e-6)) == "FAIL"
    assert verdict(dict(ok, sim_end=4.0)) == "FAIL"
    assert verdict(dict(ok, sim_end=4.0, status="overturned", overturned=True)) == "pass"
    assert verdict(dict(ok, sim_end=4.0, status="slid", overturned=True)) == "pass"  # slid, then overturned
    assert verdict(dict(ok, status="event-limit")) == "FAIL"
    alpha = 0.96  # a squat block: 4.3α is well past lying on its side (π/2)
    assert verdict(dict(ok, alpha=alpha, theta_peak_over_alpha=4.3, status="overturned", overturned=True)) == "FAIL"
    assert verdict(dict(ok, alpha=alpha, theta_peak_over_alpha=1.2, theta_end_over_alpha=0.1)) == "pass"  # leaned, came back
    assert verdict(dict(ok, alpha=alpha, theta_peak_over_alpha=1.2, theta_end_over_alpha=1.1)) == "FAIL"  # ended past α
    assert verdict(dict(ok, alpha=alpha, theta_peak_over_alpha=1.01, status="overturned", overturned=True)) == "pass"


def test_a_drawn_case_is_the_same_case_whatever_the_number_drawn():
    """A failing case is found again by its name: drawn-0008 of `stress --quick` (12 draws)
    was another system and record than drawn-0008 of the full grid (2000) or of
    --drawn 40, since Hypothesis's draws depend on how many it makes (the full run's two
    kernel timeouts could not be rerun by name). The first n of any number drawn up to
    the full grid's are the same cases, system and motion."""
    from isorock.validate.tools.stress import DRAWN_FULL, DRAWN_QUICK
    full = drawn_cases(DRAWN_FULL)
    for n in (DRAWN_QUICK, 40):
        for a, b in zip(drawn_cases(n), full):
            assert (a.name, a.scenario.system, a.scenario.motion, a.scenario.duration) == (
                b.name, b.scenario.system, b.scenario.motion, b.scenario.duration)


def test_drawn_cases_are_the_same_every_time_and_span_the_classes():
    a, b = drawn_cases(40), drawn_cases(40)
    assert [c.name for c in a] == [c.name for c in b] and len({c.name for c in a}) == 40
    kinds = {c.scenario.motion.split(":")[0] for c in a}
    assert {"noise", "sine"} <= kinds and any(c.scenario.system.fixed_base for c in a)
    assert any(not c.scenario.system.fixed_base for c in a)


def test_engines_are_compared_on_robust_overturning():
    base = dict(verdict="pass", status="completed")
    results = [dict(base, engine="analytic", case="c", overturned=True, robust=True),
               dict(base, engine="mujoco", case="c", overturned=False),
               dict(base, engine="bullet", case="c", overturned=True),
               dict(base, engine="analytic", case="d", overturned=True, robust=False),
               dict(base, engine="mujoco", case="d", overturned=False),
               dict(base, engine="bullet", case="d", overturned=False, status="slid")]
    compare_engines(results)
    assert [r["cross"] for r in results] == ["", "DISAGREE", "agree", "", "chaotic", "slid"]


def test_each_engines_agreement_count_is_judged_as_the_ensembles_are():
    """Issue 20: the count of robust comparisons is judged by core.verdict's rule on its
    exact interval, per engine. 0 of 30: the upper bound 1 − 0.025^(1/30) = 11.6% is above
    the 5% limit, inconclusive until 72 (0.025^(1/72) ≥ 0.95); 5 of 15 disagrees (the lower
    bound 11.8% is above it); chaotic and slid cases are not counted."""
    from isorock.validate.tools.stress import engine_agreement
    from isorock.validate.core.verdict import AGREES, DISAGREES, INCONCLUSIVE
    base = dict(verdict="pass", status="completed")
    results = ([dict(base, engine="mujoco", case=f"m{i}", cross="agree") for i in range(30)]
               + [dict(base, engine="mujoco", case="c", cross="chaotic"), dict(base, engine="mujoco", case="s", cross="slid")]
               + [dict(base, engine="bullet", case=f"b{i}", cross="agree" if i >= 5 else "DISAGREE") for i in range(15)]
)
    counts = engine_agreement(results)
    m, b = counts["mujoco"], counts["bullet"]
    assert m.word == INCONCLUSIVE and m.n == 30 and m.n_needed == 72
    assert m.interval[1] == pytest.approx(1 - 0.025 ** (1 / 30), rel=1e-9)
    assert b.word == DISAGREES and b.n == 15 and b.interval[0] > 0.05
    line = stress_verdict(results)
    assert "mujoco 0 of 30" in line and "inconclusive (72 comparisons would decide)" in line
    assert "bullet 5 of 15" in line and "disagrees" in line
    assert engine_agreement([dict(base, engine="mujoco", case=f"m{i}", cross="agree") for i in range(80)])[
        "mujoco"].word == AGREES


def test_a_disagreement_is_robust_only_if_the_engines_outcome_is_too():
    """The quick grid's former drawn-0008 (H 2 m, λ 7.77, fixed base, record-like noise at
    2.87·g·tanα), written out: the exact model overturns at 0.97, 1.00 and 1.03 × the motion; MuJoCo's
    default survives at exactly 1.00 after leaning to ~1.25α and overturns at 0.97 and 1.03
    (measured, docs/mujoco.md). Run for real: the engine's own ±3% runs decide that its
    survival is a knife edge, not a robust disagreement."""
    pytest.importorskip("mujoco")
    from isorock.validate.tools.stress import recheck_disagreements, run_cases
    system = System.fixed(height=1.9981007834466686, width=0.25703358563743334, mass=3800.0)
    case = StressCase(Scenario("drawn-0008 H2 λ7.77 fixed", system, "noise:dt=0.02,pga=0.369327,seconds=8,seed=4509",
                               11.0), "record-like noise at 2.87·g·tanα", quick=True, engines=None)
    ref, mine = run_cases([("analytic", case), ("mujoco", case)], 60.0)
    assert ref["overturned"]
    if mine["overturned"]:  # the knife edge fell the other way on this machine: nothing to recheck
        pytest.skip("MuJoCo overturns at 1.00 here too: no disagreement to recheck")
    ref["robust"] = True
    results = [ref, mine]
    compare_engines(results)
    assert mine["cross"] == "DISAGREE"
    recheck_disagreements(results, {case.name: case}, 60.0)
    # the exact model's own outcome flips first, at 1.015 × (it overturns at 0.97–1.0125 ×): the
    # disagreement is chaotic on that side before the engine's reruns are asked
    assert mine["cross"] == "chaotic" and ("1.015" in mine["note"] or "0.97" in mine["note"])


def test_a_disagreement_the_engine_holds_under_scaling_stays_a_disagreement(monkeypatch):
    """The rule's other side, with the reruns' outcomes given: an engine that keeps its
    outcome at 0.97 and 1.03 × the motion disagrees robustly."""
    from isorock.validate.tools import stress
    case = StressCase(Scenario("c", System.fixed(height=2, width=0.5, mass=1), "none", 1.0), "rule")
    ref = dict(engine="analytic", case="c", verdict="pass", overturned=True, robust=True, status="overturned")
    mine = dict(engine="mujoco", case="c", verdict="pass", overturned=False, status="completed")
    results = [ref, mine]
    compare_engines(results)
    # the reference's own reruns keep its outcome (overturned); the engine's keep its own
    monkeypatch.setattr(stress, "run_cases", lambda todo, *a, **k: [dict(verdict="pass", overturned=item[0] == "analytic")
                                                                    for item in todo])
    stress.recheck_disagreements(results, {"c": case}, 10.0)
    assert mine["cross"] == "DISAGREE" and mine["engine_robust"] is True


def test_a_run_is_the_one_summary_row_with_the_grids_own_checks_beside_it():
    """An overturned block: the row's θmax/α is its end on its side, π/(2α) (every table's
    definition, analytic.overturning), while the grid's lying check reads the peak reached,
    which for a block stopped once its fall is certain lies between 1 and π/(2α)."""
    import math

    from isorock.validate.core.summary import RESULT_COLUMNS
    from isorock.validate.tools.stress import edge_cases, run_one, verdict
    case = next(c for c in edge_cases() if c.name == "pga-3g-fixed")
    r = run_one("analytic", case)
    assert set(RESULT_COLUMNS) - {"runtime_s"} <= set(r)
    assert r["overturned"] and r["theta_max_over_alpha"] == math.pi / 2 / r["alpha"]
    assert 1 < r["theta_peak_over_alpha"] <= math.pi / 2 / r["alpha"]
    assert verdict(dict(r, duration=case.scenario.duration)) == "pass"


def test_a_reference_whose_outcome_flips_near_the_motion_is_chaotic_not_a_disagreement(monkeypatch):
    """drawn-1407 (H 2.64 m, λ 10, fixed base, record-like noise at 2.14·g·tanα): the exact model
    stands at 0.97, 1.00 and 1.03 × the motion, so its ±3% check called it robust, and MuJoCo,
    which overturns at all three, DISAGREEd. Yet the exact model overturns at 0.9975 × (and at
    9 of 41 scales 0.95–1.05 in steps of 0.25%, as MuJoCo does at 9 and PyBullet at 8:
    docs/robustness.md). A disagreement now reruns the reference on that finer step, nearest
    first, and one flip makes it chaotic; the engine's runs (stubbed here) are not needed."""
    from dataclasses import replace

    from isorock.validate.tools import stress
    case = drawn_cases(1407)[1406]
    # as it was drawn before the statue's friction joined the draws (issue 33): no slip
    case = replace(case, scenario=case.scenario.with_system(case.scenario.system.with_friction(None)))
    ref = dict(engine="analytic", case=case.name, verdict="pass", overturned=False, robust=True, status="completed")
    mine = dict(engine="mujoco", case=case.name, verdict="pass", overturned=True, status="overturned")
    results = [ref, mine]
    compare_engines(results)
    assert mine["cross"] == "DISAGREE"
    real = stress.run_cases
    engine_runs = []

    def runs(todo, *a, **k):
        engine_runs.extend(item for item in todo if item[0] != "analytic")
        return [dict(verdict="pass", overturned=True)] * len(todo) if todo[0][0] != "analytic" else real(todo, *a, **k)
    monkeypatch.setattr(stress, "run_cases", runs)
    stress.recheck_disagreements(results, {case.name: case}, 60.0)
    assert mine["cross"] == "chaotic" and "0.9975" in mine["note"] and "reference" in mine["note"]


def test_a_standing_statues_slide_is_judged_against_the_exact_models():
    """Issue 33: where both stand, an engine whose largest slide parts from the exact model's by more
    than its slide_max tolerance (×b) disagrees, if the exact slide holds under ±3% of the motion,
    and is chaotic otherwise; within it, it agrees; a statue that cannot slip is judged as before."""
    from isorock.validate.core.tolerances import tolerance
    tol = tolerance("mujoco", "slide_max").limit
    ref = dict(engine="analytic", case="c", verdict="pass", overturned=False, robust=True, status="completed",
               slide_over_b=1.0, slide_robust=True)

    def judged(slide, robust=True):
        mine = dict(engine="mujoco", case="c", verdict="pass", overturned=False, status="completed",
                    slide_over_b=slide)
        compare_engines([dict(ref, slide_robust=robust), mine])
        return mine["cross"]
    assert judged(1.0 + 0.5 * tol) == "agree"
    assert judged(1.0 + 2 * tol) == "DISAGREE"
    assert judged(1.0 + 2 * tol, robust=False) == "chaotic"
    assert judged(None) == "agree"  # no slide to compare: overturning alone, as before
