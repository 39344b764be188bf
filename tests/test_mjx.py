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


# --- the compiled chunk kept on disk (JAX's persistent compilation cache) ----------------------

_CACHED = """
import json, sys, warnings
import jax, jax.numpy as jnp, numpy as np  # np.asarray: the values read without a second computation
from isorock.mujoco_models import mjx as engine
engine.writable_cache_dir = lambda: sys.argv[1]     # the test's folder, not the checkout's
engine.KEEP_COMPILED_FROM_S = 0.0                   # keep even this small computation
hits = []
jax.monitoring.register_event_listener(lambda event, **kw: hits.append(event))
engine._jax()
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    y = jax.jit(lambda x: jnp.cumsum(x * 2.0 + 1.0))(jnp.arange(4.0))
engine._mend_damaged_cache(caught)
print(json.dumps({"y": np.asarray(y).tolist(), "hits": hits.count("/jax/compilation_cache/cache_hits"),
                  "folder": jax.config.jax_compilation_cache_dir}))
"""


def _cached_run(folder):
    import json
    import subprocess
    import sys
    done = subprocess.run([sys.executable, "-c", _CACHED, str(folder)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1]), done.stderr


def test_a_compiled_chunk_is_kept_for_the_next_process_and_a_damaged_one_is_replaced(tmp_path):
    """The oracles: JAX's own cache-hit event in a second process (it compiled nothing), the
    computation's values by hand (cumsum of 2x + 1 over 0..3), and the entry on disk."""
    first, _ = _cached_run(tmp_path)
    assert first["folder"] == str(tmp_path / "mjx") and first["hits"] == 0
    assert first["y"] == [1.0, 4.0, 9.0, 16.0]
    entries = [e for e in (tmp_path / "mjx").iterdir() if e.name.endswith("-cache")]
    assert entries, "nothing kept"
    assert (tmp_path / "mjx" / ".lockfile").exists()  # bounded, so JAX locks its reads and writes
    second, _ = _cached_run(tmp_path)
    assert second["hits"] >= 1 and second["y"] == first["y"]
    for entry in entries:  # damaged: JAX would warn and compile again on every run, the entry left as it is
        entry.write_bytes(b"not a compiled computation")
    third, err = _cached_run(tmp_path)
    assert third["y"] == first["y"] and third["hits"] == 0
    lines = [x for x in err.splitlines() if x.strip()]
    assert len(lines) == 1 and "MJX compilation cache" in lines[0] and "damaged" in lines[0], err
    # emptied: the next process compiles afresh and keeps a sound entry, as the first did
    assert not any(e.read_bytes() == b"not a compiled computation" for e in (tmp_path / "mjx").iterdir())


def test_a_cache_folder_the_user_gave_jax_is_kept(tmp_path):
    import os
    import subprocess
    import sys
    mine = tmp_path / "my-jax-cache"
    code = ("import jax\nfrom isorock.mujoco_models import mjx as engine\nengine._jax()\n"
            "print(jax.config.jax_compilation_cache_dir, engine._OWN_CACHE)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "JAX_COMPILATION_CACHE_DIR": str(mine)})
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split() == [str(mine), "None"]
