"""DART (dart_models/, the optional `dart` extra; issue 37) against the exact model's closed
forms and runs: β of free rocking from 0.5α against model.md's closed form at H 0.2, 2 and 10 m
on a fixed base and the paper's isolator, the first impact time against its closed form, and two
of the paper's pulses against the analytic engine. docs/scripts/dart_check.py prints these
numbers for docs/dart.md."""
from __future__ import annotations

import math

import pytest

from isorock.analytic.coefficients import beta
from isorock.analytic.errors import InputError
from isorock.analytic.motion import load_motion
from isorock.analytic.system import FrictionPendulum, System, paper_system
from isorock.validate.core.compare import compare, exact_first_impact_time
from isorock.validate.core.engines import get_engine
from isorock.validate.core.tolerances import tolerance

pytest.importorskip("dartpy")

HEIGHTS = (0.2, 2.0, 10.0)
PULSES = {"isolated": (paper_system(), "sine:amp=0.6,freq=1.3,cycles=2"),
          "fixed": (paper_system(fixed_base=True), "sine:amp=0.5,freq=1.5,cycles=2")}


def limit(metric):
    return tolerance("dart", metric).limit


def block(height, fixed):
    width, mass = 0.35 * height, 100.0 * height
    if fixed:
        return System.fixed(height=height, width=width, mass=mass)
    return System.isolated(height=height, width=width, mass=mass, base_mass=mass, period=1.5, damping_ratio=0.2)


def measure_free_rocking(height, fixed) -> dict:
    system = block(height, fixed)
    theta0 = 0.5 * system.alpha
    tr = get_engine("dart").simulate(system, None, duration=3.0 * math.sqrt(height / 2) + 1.0, theta0=theta0)
    assert tr.status == "completed" and len(tr.counted_impacts) >= 4
    b = beta(system.slenderness, system.mu)
    out = {"beta_rel_error": max(abs(i.beta / b - 1) for i in tr.counted_impacts[:4])}
    if fixed:
        out["first_impact_time_rel_error"] = abs(tr.impacts[0].t / exact_first_impact_time(system, theta0) - 1)
    return out


def measure_pulse(system, pulse) -> dict:
    motion = load_motion(pulse)
    ref = get_engine("analytic").simulate(system, motion)
    c = compare(get_engine("dart").simulate(system, motion), ref)
    assert ref.impact_count >= 5 and c.overturn_agree and c.first_uplift_diff is not None
    return {"impacts_diff": abs(c.impacts - c.impacts_ref), "theta_max_diff": abs(c.theta_max_diff),
            "first_uplift_diff": abs(c.first_uplift_diff)}


@pytest.mark.parametrize("height", HEIGHTS)
@pytest.mark.parametrize("fixed", [True, False], ids=["fixed", "isolated"])
def test_free_rocking_keeps_the_closed_form_beta_at_every_size(height, fixed):
    for metric, value in measure_free_rocking(height, fixed).items():
        assert value <= limit(metric), (metric, value)


@pytest.mark.parametrize("name", PULSES)
def test_the_papers_pulses_as_the_analytic_engine(name):
    for metric, value in measure_pulse(*PULSES[name]).items():
        assert value <= limit(metric), (metric, value)


def test_registered_and_what_it_refuses_in_one_line():
    from isorock.dart_models import Settings
    engine = get_engine("dart")
    assert engine.name == "dart" and engine.capabilities.isolators == ("linear",)
    pendulum = System.with_isolator(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0,
                                    isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.1))
    for system, says in ((pendulum, "friction-pendulum"), (paper_system().with_friction(0.5), "friction")):
        with pytest.raises(InputError, match=says) as e:
            engine.simulate(system, None, duration=1.0)
        assert "\n" not in str(e.value)
    for field, value in (("timestep", 0.0), ("timestep", 1.0), ("friction", -1.0), ("friction", float("nan"))):
        with pytest.raises(InputError, match=field):
            Settings(**{field: value})
