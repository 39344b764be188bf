"""MJX, MuJoCo's JAX port (issue 37), on MuJoCo's own scene: against MuJoCo's C engine stepping
the same scene the same way (an independent implementation of the same equations), against the
closed-form β, a batch against its runs alone, and what it refuses."""
import math

import numpy as np
import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.motion import load_motion
from isorock.analytic.system import BilinearIsolator, System, paper_system
from isorock.validate.core.engines import get_engine
from isorock.validate.core.measure import beta_errors
from isorock.validate.core.tolerances import tolerance

pytest.importorskip("jax")
pytest.importorskip("mujoco.mjx")

from isorock.mujoco_models.mjx import simulate_batch  # noqa: E402
from isorock.mujoco_models import Settings  # noqa: E402

FULL = Settings(phased=False)  # MuJoCo C stepping the scene throughout at the timestep, as MJX does


@pytest.mark.parametrize("system, motion", [
    (paper_system(fixed_base=True), None),
    (paper_system(), None),
    (paper_system(fixed_base=True), load_motion("sine:amp=0.5,freq=1.5,cycles=1")),
], ids=["fixed, free rocking", "isolated, free rocking", "fixed, under a sine"])
def test_mjx_steps_the_scene_as_mujoco_c_does(system, motion):
    kw = dict(settings=FULL, duration=2.0, theta0=0.0 if motion is not None else 0.5 * system.alpha)
    c = get_engine("mujoco").simulate(system, motion, **kw)
    x = get_engine("mjx").simulate(system, motion, **kw)
    assert x.status == c.status == "completed" and x.impact_count == c.impact_count >= 2
    assert np.allclose(x.t, c.t, rtol=0, atol=1e-12)
    # the two implementations of one scene agree to the contact solver's tolerance
    limit = tolerance("mjx", "history_vs_mujoco").limit
    assert float(np.max(np.abs(x.theta - c.theta))) / system.alpha <= limit
    assert float(np.max(np.abs(x.u - c.u))) <= limit * c.u_max + 1e-12


def test_mjx_beta_is_the_closed_form_within_mujocos_limit():
    system = paper_system(fixed_base=True)
    tr = get_engine("mjx").simulate(system, None, duration=2.0, theta0=0.5 * system.alpha)
    errors = [abs(e) for e in beta_errors(tr, 3) if math.isfinite(e)]
    assert len(errors) >= 2 and max(errors) <= tolerance("mjx", "beta_rel_error").limit


def test_a_batch_is_its_runs_alone():
    system = paper_system(fixed_base=True)
    theta0 = [0.3 * system.alpha, 0.6 * system.alpha]
    batch = simulate_batch(system, [None, None], settings=FULL, duration=1.0, theta0=theta0)
    for raw, th in zip(batch, theta0):
        alone = simulate_batch(system, [None], settings=FULL, duration=1.0, theta0=[th])[0]
        assert float(np.max(np.abs(raw.theta - alone.theta))) <= 1e-12


def test_what_mjx_cannot_carry_is_refused_in_one_line():
    bearing = System.with_isolator(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0,
                                   isolator=BilinearIsolator(stiffness=3e5, post_yield_ratio=0.5,
                                                             yield_displacement=0.005))
    with pytest.raises(InputError) as e:
        get_engine("mjx").simulate(bearing, None, duration=0.5)
    assert "\n" not in str(e.value) and "bilinear" in str(e.value)
    with pytest.raises(InputError, match="impact_timestep"):
        get_engine("mjx").simulate(paper_system(), None, duration=0.5,
                                   settings=Settings(impact_timestep=2.5e-4, timestep=3e-3))
