"""The compiled kernels built at install (issue 34: a first run, design or sweep that waits for no
build): pip's editable install runs build_backend/isorock_backend.py, which builds every kernel
through analytic.kernel_build in pip's build environment, the checkout imported as the install
maps it. The oracle is a new process: after the build it compiles nothing, whatever it runs."""
import importlib.util
import os
import subprocess
import sys
import tomllib

import pytest

from isorock.analytic import kernel_build

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _backend():
    spec = importlib.util.spec_from_file_location("isorock_backend_under_test",
                                                  os.path.join(ROOT, "build_backend", "isorock_backend.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_pyproject_builds_with_the_backend_and_it_offers_every_setuptools_hook():
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        system = tomllib.load(f)["build-system"]
    assert system["build-backend"] == "isorock_backend" and system["backend-path"] == ["build_backend"]
    # what the kernels are built with: the project's own bounds, so pip resolves what the install gets
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        runtime = tomllib.load(f)["project"]["dependencies"]
    for package in ("numba", "numpy", "scipy"):
        bound = next(r for r in runtime if r.startswith(package + ">="))
        assert bound in system["requires"]
    from setuptools import build_meta
    backend = _backend()
    for hook in build_meta.__all__:
        assert callable(getattr(backend, hook)) or hook == "__legacy__", hook
    assert backend.build_editable is not build_meta.build_editable  # the one hook it extends


def test_the_preamble_imports_the_checkout_under_the_names_the_install_gives(tmp_path):
    """The kernels' caches are named after their modules: built under other names, an install
    would not find them. A process with only the preamble (no installed isorock on its path)
    sees the same kernels built, and none missing, as this one."""
    backend = _backend()
    code = (backend.PREAMBLE + "import isorock.analytic.fast as f, isorock.analytic.kernel_build as k\n"
            "print(f._integrate.py_func.__module__, f.__file__, sorted(k.unbuilt()))\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = subprocess.run([sys.executable, "-S", "-c", f"import sys; sys.path[:0] = {sys.path[1:]!r}\n" + code],
                         capture_output=True, text=True, cwd=tmp_path, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    module, path, missing = out.stdout.split(" ", 2)
    assert module == "isorock.analytic.fast" and path == os.path.join(ROOT, "analytic", "fast.py")
    assert missing.strip() == str(sorted(kernel_build.unbuilt()))


def test_a_failed_build_is_one_line_and_never_fails_the_install(capsys):
    assert kernel_build.build(preamble="raise SystemExit('no compiler here')") is False
    err = capsys.readouterr().err
    assert err.count("a kernel build failed (no compiler here); a first run builds it instead") == 2


def test_a_build_past_its_budget_is_stopped_and_said(capsys):
    assert kernel_build.build(preamble="import time\ntime.sleep(60)", budget_s=1.0) is False
    assert "passed its budget of 1 s and was stopped" in capsys.readouterr().err


def test_the_install_skips_the_build_when_asked_and_survives_a_broken_one(monkeypatch, capsys):
    backend = _backend()
    before = {name: module for name, module in sys.modules.items() if name.startswith("isorock")}
    monkeypatch.setattr(backend, "PREAMBLE", "raise ImportError('numba missing')")
    for skip in ("0", "no", "False", " off "):
        monkeypatch.setenv("ISOROCK_BUILD_KERNELS", skip)
        assert backend.build_kernels() is False
        assert capsys.readouterr().err == ""  # skipped before anything ran
    monkeypatch.setenv("ISOROCK_BUILD_KERNELS", "1")
    assert backend.build_kernels() is False
    assert "were not built at install (ImportError: numba missing); a first run builds them" in capsys.readouterr().err
    # this process's own package is left as it was
    assert {name: module for name, module in sys.modules.items() if name.startswith("isorock")} == before


@pytest.mark.isolator_kernel
def test_after_the_build_a_new_process_compiles_nothing_whatever_it_runs(tmp_path):
    """Every kernel a command can need (a run of each kind, a sliding statue, design's rest pass)
    is built by kernel_build; a new process then announces no compilation. On a fresh install the
    build ran at install and this takes seconds; after the kernels' sources changed, minutes."""
    subprocess.run([sys.executable, "-m", "isorock.analytic.kernel_build"], check=True, timeout=900,
                   capture_output=True)
    code = ("from isorock.analytic import kernel_build as k\n"
            "assert k.unbuilt() == [], k.unbuilt()\n"
            "for name in k.KERNELS:\n    k._warm(name)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert "compiling" not in out.stderr and "compiled" not in out.stderr, out.stderr
