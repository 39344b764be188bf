"""The stress grid's quick subset: every case finite, in time, and (analytic) with
its energy balance closed to 1e-6 of the input energy."""

from isorock.validate.stress import ENERGY_TOLERANCE, StressCase, grid, run_case, run_stress, verdict
from isorock.analytic import System


def test_quick_subset_passes_on_every_engine():
    from isorock.validate.engines import ALL_ENGINES
    results = run_stress(quick=True, time_limit=60, progress=False)
    assert len(results) == len(grid(quick=True)) * len(ALL_ENGINES) and len(grid(quick=True)) >= 10
    bad = [(r["case"], r["status"], r.get("error"), r.get("energy_residual")) for r in results if r["verdict"] != "pass"]
    assert not bad
    for r in results:
        if r["engine"].startswith("analytic"):
            assert r["energy_residual"] < ENERGY_TOLERANCE
    # the grid does exercise rocking, impacts and overturning
    assert any(r["overturned"] for r in results) and any(r["impacts"] > 3 and not r["overturned"] for r in results)


def test_a_hang_is_reported_as_timeout():
    # 300 s of 1 ms record on the reference path cannot finish in 0.5 s
    case = StressCase("slow", "forced time-out", System.fixed(height=2, width=0.5, mass=1),
                      "noise:dt=0.001,pga=0.3,seconds=300,seed=0", 300.0)
    r = run_case("analytic-reference", case, time_limit=0.5)
    assert r["status"] == "timeout" and r["verdict"] == "FAIL"


def test_verdict_rules():
    ok = dict(status="completed", finite=True, energy_residual=1e-12, sim_end=5.0, duration=5.0)
    assert verdict(ok) == "pass"
    assert verdict(dict(ok, finite=False)) == "FAIL"
    assert verdict(dict(ok, energy_residual=2e-6)) == "FAIL"
    assert verdict(dict(ok, sim_end=4.0)) == "FAIL"
    assert verdict(dict(ok, sim_end=4.0, status="overturned")) == "pass"
    assert verdict(dict(ok, status="event-limit")) == "FAIL"
    assert verdict(dict(ok, theta_max_over_alpha=4.3)) == "FAIL"
    assert verdict(dict(ok, theta_max_over_alpha=1.01, status="overturned")) == "pass"
