"""MuJoCo Warp (issue 37), on MuJoCo's own scene: against MuJoCo's C engine stepping the same scene
the same way (an independent implementation of the same equations), against the closed-form β and
the exact model's t₁, a batch against its runs alone, and what it refuses (docs/mjwarp.md). Warp's
kernels compile on the first run in a process (~40 s, cached on disk after): the runs here are
short and shared through a module fixture."""
import importlib.util
import math
import sys

import numpy as np
import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.system import BilinearIsolator, System, paper_system
from isorock.mujoco_models import Settings
from isorock.validate.cli.main import main
from isorock.validate.core.engines import ALL_ENGINES, get_engine, presets_of
from isorock.validate.core.measure import beta_errors
from isorock.validate.core.tolerances import tolerance

installed = pytest.mark.skipif(importlib.util.find_spec("mujoco_warp") is None
                               or importlib.util.find_spec("warp") is None,
                               reason="MuJoCo Warp not installed: pip install -e '.[mjwarp]'")
FULL = Settings(phased=False)  # MuJoCo C stepping the scene throughout at the timestep, as Warp does
DURATION = 1.5


@pytest.fixture(scope="module")
def runs():
    """system label → (system, MuJoCo Warp's run, MuJoCo C's run): free rocking from 0.5α."""
    out = {}
    for label, system in (("fixed", paper_system(fixed_base=True)), ("isolated", paper_system())):
        kw = dict(settings=FULL, duration=DURATION, theta0=0.5 * system.alpha)
        out[label] = (system, get_engine("mjwarp").simulate(system, None, **kw),
                      get_engine("mujoco").simulate(system, None, **kw))
    return out


@installed
@pytest.mark.parametrize("label", ["fixed", "isolated"])
def test_mjwarp_steps_the_scene_as_mujoco_c_does(runs, label):
    system, w, c = runs[label]
    assert w.status == c.status == "completed" and w.impact_count == c.impact_count >= 2
    assert np.allclose(w.t, c.t, rtol=0, atol=1e-12)
    # two implementations of one scene (and float32 against float64) agree to the contact solver's tolerance
    limit = tolerance("mjwarp", "history_vs_mujoco").limit
    assert float(np.max(np.abs(w.theta - c.theta))) / system.alpha <= limit
    assert float(np.max(np.abs(w.u - c.u))) <= limit * c.u_max + 1e-12


@installed
def test_mjwarp_beta_is_the_closed_form_within_mujocos_limit(runs):
    _, w, _ = runs["fixed"]
    errors = [abs(e) for e in beta_errors(w, 3) if math.isfinite(e)]
    assert len(errors) >= 2 and max(errors) <= tolerance("mjwarp", "beta_rel_error").limit


@installed
def test_mjwarp_first_impact_is_the_exact_models(runs):
    system, w, _ = runs["isolated"]
    exact = get_engine("analytic").simulate(system, None, duration=DURATION, theta0=0.5 * system.alpha)
    t1, t1_exact = w.counted_impacts[0].t, exact.counted_impacts[0].t
    assert abs(t1 - t1_exact) / t1_exact <= tolerance("mjwarp", "first_impact_time_rel_error").limit


@installed
def test_a_batch_is_its_runs_alone():
    from isorock.mujoco_models.mjwarp import simulate_batch
    system = paper_system(fixed_base=True)
    theta0 = [0.3 * system.alpha, 0.6 * system.alpha]
    batch = simulate_batch(system, [None, None], settings=FULL, duration=0.5, theta0=theta0)
    for raw, th in zip(batch, theta0):
        alone = simulate_batch(system, [None], settings=FULL, duration=0.5, theta0=[th])[0]
        assert float(np.max(np.abs(raw.theta - alone.theta))) <= tolerance("mjwarp", "batch_vs_alone").limit


@installed
def test_what_mjwarp_cannot_carry_is_refused_in_one_line():
    """Before any Warp work."""
    bearing = System.with_isolator(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0,
                                   isolator=BilinearIsolator(stiffness=3e5, post_yield_ratio=0.5,
                                                             yield_displacement=0.005))
    with pytest.raises(InputError) as e:
        get_engine("mjwarp").simulate(bearing, None, duration=0.5)
    assert "\n" not in str(e.value) and "bilinear" in str(e.value)
    with pytest.raises(InputError, match="impact_timestep"):
        get_engine("mjwarp").simulate(paper_system(), None, duration=0.5,
                                      settings=Settings(impact_timestep=2.5e-4, timestep=3e-3))


def test_without_the_extra_mjwarp_is_registered_and_cannot_run_here(monkeypatch, capsys):
    """Where mujoco-warp or warp-lang is absent (installed or not here): the engine is a name of the
    registry that cannot be loaded, skipped by every loop over the engines, and named, one line
    saying what to install."""
    for name in ("warp", "mujoco_warp"):
        monkeypatch.setitem(sys.modules, name, None)  # found nowhere, as where it is not installed
    monkeypatch.delitem(sys.modules, "isorock.mujoco_models.mjwarp", raising=False)
    assert "mjwarp" in ALL_ENGINES
    with pytest.raises(ImportError, match=r"cannot run here without the package 'warp': pip install 'isorock\[mjwarp\]'"):
        get_engine("mjwarp")
    with pytest.raises(InputError) as e:
        presets_of("mjwarp")
    assert "\n" not in str(e.value) and "cannot run here" in str(e.value) and "isorock[mjwarp]" in str(e.value)
    assert main(["run", "--engine", "mjwarp", "--fixed-base", "--theta0", "0.5", "--duration", "0.5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot run here" in err and "isorock[mjwarp]" in err


@installed
def test_mjwarp_keeps_standard_output_clean(capfd):
    """Warp prints its banner and each module it loads on standard output: `--json -` writes there."""
    system = paper_system(fixed_base=True)
    get_engine("mjwarp").simulate(system, None, settings=FULL, duration=0.05, theta0=0.3 * system.alpha)
    assert capfd.readouterr().out == ""


def test_warps_no_driver_line_is_dropped_and_the_rest_of_its_stderr_kept():
    """Warp's native library prints a CUDA warning with fprintf on a machine without an NVIDIA
    driver, each time it starts; isorock drops that one line (its runs say they are on Warp's CPU)
    and passes on everything else. Oracle: a child process writing to file descriptor 2 as a C
    library does; no Warp needed."""
    import subprocess
    # batch.py imports without Warp (mjwarp.py refuses to load where Warp is absent: CI's extra)
    code = ("import os\nfrom isorock.mujoco_models.batch import without_native_line\n"
            "NO_DRIVER = b'Warp CUDA warning: Could not find or load the NVIDIA CUDA driver'\n"
            "with without_native_line(NO_DRIVER):\n"
            "    os.write(2, NO_DRIVER + b'. GPU execution will not be available.\\n')\n"
            "    os.write(2, b'Warp error: something else\\n')\n"
            "os.write(2, b'after\\n')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stderr == b"Warp error: something else\nafter\n"
