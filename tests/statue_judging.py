"""What every contact engine's statue tests judge, in one place (tests/test_statue_engines.py
for MuJoCo, test_statue_bullet.py, test_statue_drake.py, test_statue_dart.py): an engine's hull
against the exact model of the statue's two edges, by the rows MuJoCo's statues are judged by, and
free rocking from rest on one edge against that edge's closed forms, by the engine's own block rows.
Oracles: the exact model (its SciPy reference), model.md's quadrature t₁ and each edge's β."""
import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.system import PlanarBody, System
from isorock.validate.core.compare import exact_first_impact_time
from isorock.validate.core.engines import get_engine
from isorock.validate.core.measure import beta_errors
from isorock.validate.core.tolerances import tolerance
from isorock.validate.tools import statue_check as sc


def judge_hull(engine: str, name: str, scale: float, base: str, *, target: float = 0.05) -> dict:
    """The example statue `name` at `scale` on `base` under one sine cycle that rocks the exact model
    to θmax/α = target: the engine within the statue rows (θmax/α, impacts, each impact's β against
    its own edge), standing, its history within 0.01 α. The compare() row, for more checks."""
    _, system = sc.example(name, scale, base)
    motion = sc.pulse(system, sc.amplitude_for(system, target))
    steady, spread = sc.robust(system, motion)
    assert steady, f"the reference is no longer robust (spread {spread:.3f}): pick another case"
    r = sc.compare(system, motion, engine)
    assert r["status"] == "completed", r
    assert r["theta_max_diff"] <= tolerance("mujoco", "theta_max_diff").limit, r
    assert abs(r["impacts"] - r["exact_impacts"]) <= tolerance("mujoco", "impacts_diff").limit, r
    assert r["impacts"] >= 1 and r["beta_rel_error"] <= tolerance("mujoco", "beta_rel_error").limit, r
    assert r["overturned"] == (False, False)
    assert r["history_error"] < 0.01, r  # |Δθ|/α over the whole run, beside the peak
    return r


def judge_free_rocking(engine: str, side: int, *, min_impacts: int = 4):
    """From rest at 0.4·α of the bust's edge `side`: the first impact at model.md's t₁ of that edge
    (quadrature, independent of any integrator), then impacts alternating edges, each with its own
    edge's β (measure.impact_closed_forms), by the engine's block rows. The Trajectory."""
    _, system = sc.example("bust", 1.0, "fixed")
    theta0 = side * 0.4 * system.edge_alpha(side)
    tr = get_engine(engine).simulate(system, None, duration=1.2, theta0=theta0)
    assert tr.status == "completed"
    t1 = exact_first_impact_time(system, theta0)
    assert tr.counted_impacts[0].t == pytest.approx(t1, rel=tolerance(engine, "first_impact_time_rel_error").limit)
    errors = beta_errors(tr)
    assert len(errors) >= min_impacts and max(abs(e) for e in errors) <= tolerance(engine, "beta_rel_error").limit, errors
    assert {1 if i.theta_dot_pre > 0 else -1 for i in tr.counted_impacts[:2]} == {1, -1}
    return tr


#: a statue given by its numbers alone (two edges, no mesh): what a hull engine cannot build
SHAPELESS = System.of_body(PlanarBody(centre_height=1.0, lever_forward=0.25, lever_backward=0.45,
                                      inertia=800 * (0.35**2 + 1.0) / 3), mass=800.0)


def judge_refused(engine: str, system, match: str) -> None:
    """The engine refuses `system` before any work, in one line saying `match`."""
    with pytest.raises(InputError, match=match) as exc:
        get_engine(engine).simulate(system, None, duration=1.0, theta0=0.1)
    assert len(str(exc.value).splitlines()) == 1
