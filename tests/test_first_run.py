"""A first run that starts at once (issue 34): while the compiled kernel a run needs is not
built, `isorock run` takes the SciPy reference (the same model) instead of waiting minutes
for the build, says so, and gives what the kernel gives. The oracle is the other path: the
kernel and the reference are two integrators of the same equations (tests/test_fast.py)."""
import json

import numba
import pytest

from isorock.analytic import engines, kernel_cache
from isorock.analytic.motion import load_motion
from isorock.analytic.system import FrictionPendulum, System, paper_system
from isorock.validate.cli.main import main

PENDULUM = ["--height", "1.2", "--width", "0.3", "--mass", "250", "--base-mass", "500", "--isolator",
            "friction-pendulum", "--radius", "1.0", "--friction-coefficient", "0.3",
            "--motion", "ricker:amp=0.5,freq=2.0", "--duration", "4.5", "--quiet"]
#: the same pendulum as a System
PENDULUM_SYSTEM = System.with_isolator(height=1.2, width=0.3, mass=250, base_mass=500,
                                       isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.3))


def _run_json(tmp_path, capsys, name, args):
    out = tmp_path / f"{name}.json"
    code = main(["run", *args, "--json", str(out)])
    err = capsys.readouterr().err
    assert code == 0, err
    return json.loads(out.read_text()), err


def test_a_first_run_takes_the_reference_says_so_and_agrees_with_the_kernel(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("ISOROCK_FIRST_RUN", "kernel")
    kernel, err = _run_json(tmp_path, capsys, "kernel", PENDULUM)
    assert kernel["engine"] == "analytic" and "not built yet" not in err
    monkeypatch.setenv("ISOROCK_FIRST_RUN", "reference")
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: False)  # a new install
    first, err = _run_json(tmp_path, capsys, "first", PENDULUM)
    assert first["engine"] == "analytic-reference"
    assert "the non-linear isolators' compiled kernel is not built yet" in err and "analytic-reference" in err
    assert first["status"] == kernel["status"] and first["impacts"] == kernel["impacts"] >= 10
    assert first["theta_max_over_alpha"] == pytest.approx(kernel["theta_max_over_alpha"], rel=1e-8)
    assert first["u_max"] == pytest.approx(kernel["u_max"], rel=1e-8)


@pytest.mark.parametrize("args, kernel_named", [
    (["--fixed-base", "--motion", "sine:amp=0.6,freq=1.3,cycles=1", "--duration", "3"], "fixed base"),
    (["--fixed-base", "--statue-friction", "0.3", "--motion", "sine:amp=0.6,freq=1.3,cycles=1",
      "--duration", "3"], "sliding statue"),
])
def test_each_kernel_is_named_by_what_it_serves(args, kernel_named, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("ISOROCK_FIRST_RUN", "reference")
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: False)
    d, err = _run_json(tmp_path, capsys, "run", [*args, "--quiet"])
    assert d["engine"] == "analytic-reference" and kernel_named in err


def test_a_built_kernel_a_long_run_and_a_contact_engine_keep_their_engine(monkeypatch):
    monkeypatch.setenv("ISOROCK_FIRST_RUN", "reference")
    system, motion = paper_system(), load_motion("sine:amp=0.6,freq=1.3,cycles=1")
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: True)
    assert engines.first_run_reference(system, motion, 10.0) is None  # built: the kernel serves
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: False)
    assert engines.first_run_reference(system, motion, engines.FIRST_RUN_REFERENCE_S) is not None
    # longer than the reference's bound: the build pays off, and is announced where it runs
    assert engines.first_run_reference(system, motion, engines.FIRST_RUN_REFERENCE_S * 1.01) is None
    assert engines.first_run_reference(system, motion, float("nan")) is None
    monkeypatch.setenv("ISOROCK_FIRST_RUN", "kernel")
    assert engines.first_run_reference(system, motion, 10.0) is None


def test_the_kernel_each_run_needs(monkeypatch):
    from isorock.analytic import fast, slide_fast
    asked = []
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: asked.append(dispatcher) or True)
    pendulum = PENDULUM_SYSTEM
    for system, motion in ((paper_system(), None), (paper_system(fixed_base=True), None), (pendulum, None),
                           (paper_system().with_friction(0.4), None),
                           (paper_system(), load_motion("sine:amp=0.6,freq=1.3,cycles=1"))):
        assert engines.kernel_ready(system, motion)
    assert asked == [fast._integrate, fast._integrate, fast._integrate_iso, slide_fast._run, fast._integrate]


def test_is_ready_before_and_after_a_compilation():
    @numba.njit
    def plus_one(x):
        return x + 1.0
    assert not kernel_cache.is_ready(plus_one)  # never compiled, no disk cache
    assert kernel_cache.call_kernel(plus_one, 1.0) == 2.0
    assert kernel_cache.is_ready(plus_one)


def test_an_ahead_of_time_kernel_is_ready_only_once_built(monkeypatch):
    from isorock.analytic import fast
    kernel = fast._integrate_iso
    monkeypatch.delenv("ISOROCK_KERNEL", raising=False)
    # as in a new process: nothing loaded or compiled here
    monkeypatch.setattr(kernel_cache, "_ready", set())
    monkeypatch.setattr(kernel_cache, "_aot_loaded", {})
    monkeypatch.setattr(kernel, "overloads", {})
    real = kernel_cache._module_name(kernel)
    monkeypatch.setattr(kernel_cache, "_module_name", lambda d: real + "_not_built")
    assert not kernel_cache.is_ready(kernel)
    monkeypatch.setattr(kernel_cache, "_module_name", lambda d: real)
    assert kernel_cache.is_ready(kernel) == kernel_cache.is_built(kernel)


def test_a_long_command_names_the_builds_it_will_wait_for(monkeypatch):
    pendulum = PENDULUM_SYSTEM
    fixed, linear = paper_system(fixed_base=True), paper_system()
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: True)
    assert engines.unbuilt_kernels([fixed, pendulum]) == []
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: False)
    assert engines.unbuilt_kernels([fixed, linear]) == [
        f"the fixed base's and the linear isolator's kernel ({kernel_cache.BUILD_ESTIMATE['_integrate']})"]
    got = engines.unbuilt_kernels([fixed, pendulum, fixed.with_friction(0.4)])
    assert len(got) == 3 and "non-linear isolators'" in got[1] and "sliding statue's" in got[2]


def test_design_states_the_build_before_its_work(records_dir, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(kernel_cache, "is_ready", lambda dispatcher: False)
    code = main(["design", "--records", str(records_dir), "--pga", "0.4", "--periods", "2", "--damping-ratios", "0.1",
                 "--height", "0.6", "--width", "0.2", "--mass", "80", "--base-mass", "150", "--out", str(tmp_path / "d")])
    err = capsys.readouterr().err
    assert code == 0
    assert "before it, once per install, it builds the fixed base's and the linear isolator's kernel" in err


def test_a_kernel_is_called_with_one_flavour_of_array():
    """A record's samples are a read-only array, a pulse's a writable one: numba compiles a
    signature per flavour (the sliding kernel's cache held four, 33 s each), and a cache holding
    only read-only flavours would read as ready for a call that compiles. call_kernel passes
    every array writable, and is_ready asks for that signature."""
    import numpy as np

    @numba.njit
    def total(a):
        return a.sum()
    frozen = np.arange(4.0)
    frozen.flags.writeable = False
    assert kernel_cache.call_kernel(total, frozen) == 6.0
    assert kernel_cache.call_kernel(total, np.arange(4.0)) == 6.0
    assert len(total.signatures) == 1 and all(t.mutable for t in total.signatures[0])
