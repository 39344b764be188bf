"""analytic/kernel_cache.py: a damaged numba cache is rebuilt with one line on stderr, a
missing writable cache folder falls back instead of crashing, and the kernel's cache is
stamped with physics.py too. Exercised on a tiny jitted function of its own (the real
kernel takes a minute to compile), in a temporary folder."""
import importlib.util
import os
from pathlib import Path
import sys

import pytest

pytest.importorskip("numba")
from isorock.analytic import kernel_cache  # noqa: E402

TINY = "from numba import njit\n\n@njit(cache=True)\ndef twice(x):\n    return 2.0 * x\n"


def load_tiny(folder, name, text=TINY):
    path = folder / f"{name}.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("damage", ["random-index", "empty-index", "random-data"])
def test_damaged_cache_is_rebuilt_with_one_line(tmp_path, capsys, damage):
    name = f"tiny_{damage.replace('-', '_')}"
    assert kernel_cache.call_kernel(load_tiny(tmp_path, name).twice, 1.5) == 3.0  # compiles, caches
    cache = tmp_path / "__pycache__"
    index = next(cache.glob(f"{name}.twice-*.nbi"))
    data = next(cache.glob(f"{name}.twice-*.nbc"))
    if damage == "random-index":
        # random bytes, but never a valid pickle opening: numba reads some valid openings as
        # "another version's cache" and recompiles silently, which would make this test flaky
        index.write_bytes(b"\xff" + os.urandom(299))
    elif damage == "empty-index":
        index.write_bytes(b"")
    else:
        data.write_bytes(os.urandom(300))
    capsys.readouterr()
    fresh = load_tiny(tmp_path, name)  # a new process's view: nothing loaded yet
    assert kernel_cache.call_kernel(fresh.twice, 2.0) == 4.0
    err = capsys.readouterr().err
    assert ("damaged" in err or damage == "random-data" and "compil" in err), err
    assert "Traceback" not in err
    # and the rebuilt cache loads silently in the next "process"
    again = load_tiny(tmp_path, name)
    assert kernel_cache.call_kernel(again.twice, 3.0) == 6.0
    assert "damaged" not in capsys.readouterr().err


def test_no_writable_cache_folder_compiles_uncached(monkeypatch, capsys):
    from numba.core.caching import CacheImpl
    monkeypatch.setattr(CacheImpl, "_locator_classes", [])  # numba: "cannot cache function"

    def third(x):
        return x / 3.0
    jitted = kernel_cache.cached_jit()(third)
    assert jitted(3.0) == 1.0
    assert "no writable cache folder" in capsys.readouterr().err


def test_kernel_cache_falls_back_to_a_writable_folder(monkeypatch, tmp_path):
    """A read-only install (package __pycache__ not writable) caches in the next folder."""
    monkeypatch.setenv("ISOROCK_CACHE_DIR", str(tmp_path / "cache"))
    first = kernel_cache.cache_dirs()[0]
    monkeypatch.setattr(kernel_cache, "_writable", lambda p: p != first and os.access(os.path.dirname(p) or ".", os.W_OK)
                        or p == str(tmp_path / "cache"))
    locator_cls = kernel_cache._locator_class()

    def f():
        pass
    loc = locator_cls.from_function(f, kernel_cache.KERNEL_SOURCES[0])
    assert loc is not None and loc.get_cache_path() == str(tmp_path / "cache")
    assert locator_cls.from_function(f, __file__) is None  # other files: numba's own locators
    # the stamp covers physics.py and dop853.py: the kernel inlines the one, and freezes the other's tableau
    assert len(loc.get_source_stamp()) == len(kernel_cache.KERNEL_SOURCES) == 3
    assert any(p.endswith("physics.py") for p in kernel_cache.KERNEL_SOURCES)


def test_first_compilation_is_announced(tmp_path, capsys):
    tiny = load_tiny(tmp_path, "tiny_announce")
    kernel_cache.call_kernel(tiny.twice, 1.0)
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("isorock: compiling") and err[-1].startswith("isorock: compiled")
    assert len(err) == 2
    sys.modules.pop("tiny_announce", None)


# --- the kernel built ahead of time (numba.pycc) ----------------------------------------

TINY_AOT = ("from numba import njit\n\n@njit\ndef halve(x, a):\n"
            "    a[0] = x / 2.0\n    return a[0] + a.size\n")


@pytest.fixture
def aot_cache(tmp_path, monkeypatch):
    """The ahead-of-time registry and cache folder of a test of its own."""
    folder = tmp_path / "cache"
    folder.mkdir()
    monkeypatch.setattr(kernel_cache, "cache_dirs", lambda: [str(folder)])
    monkeypatch.setattr(kernel_cache, "_aot_exports", {})
    monkeypatch.setattr(kernel_cache, "_aot_loaded", {})
    monkeypatch.delenv("ISOROCK_KERNEL", raising=False)
    return folder


def tiny_aot(tmp_path, name):
    from numba import types as nt
    module = load_tiny(tmp_path, name, TINY_AOT)
    return kernel_cache.ahead_of_time(nt.float64(nt.float64, nt.float64[::1]))(module.halve)


def in_new_process(tmp_path, folder, name, x):
    """call_kernel(halve, x, zeros(3)) in a new Python process using `folder` as its cache:
    (printed result, stderr). A new process because Python keeps an extension module it
    has loaded: a damaged file is only seen by the next process."""
    import subprocess
    code = (
        "import importlib.util, sys\nimport numpy as np\nfrom numba import types as nt\n"
        "from isorock.analytic import kernel_cache as kc\n"
        f"kc.cache_dirs = lambda: [{str(folder)!r}]\n"
        f"spec = importlib.util.spec_from_file_location({name!r}, {str(tmp_path / (name + '.py'))!r})\n"
        "m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)\n"
        "f = kc.ahead_of_time(nt.float64(nt.float64, nt.float64[::1]))(m.halve)\n"
        f"print(kc.call_kernel(f, {x!r}, np.zeros(3)))\n")
    env = {k: v for k, v in os.environ.items() if k != "ISOROCK_KERNEL"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout.strip(), out.stderr


def test_ahead_of_time_build_is_announced_cached_and_rebuilt_when_damaged(tmp_path, aot_cache, capsys):
    import numpy as np
    halve = tiny_aot(tmp_path, "tiny_aot")
    a = np.zeros(3)
    assert kernel_cache.call_kernel(halve, 5.0, a) == 2.5 + 3 and a[0] == 2.5  # built, then run
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and "ahead of time" in err[0] and err[1].startswith("isorock: compiled"), err
    built = list(aot_cache.glob("isorock_halve_*"))
    assert len(built) == 1 and not list(aot_cache.glob(".build-*"))  # whole, no leftovers
    # a read-only, non-contiguous array is passed as a contiguous copy, never misread
    ro = np.arange(6.0)[::2]
    ro.flags.writeable = False
    assert kernel_cache.call_kernel(halve, 1.0, ro) == 0.5 + 3 and ro[0] == 0.0
    # a new process loads the module, silently, instead of building it again
    assert in_new_process(tmp_path, aot_cache, "tiny_aot", 1.0) == ("3.5", "")
    # a damaged module is said in one line and rebuilt (a new file, as another process
    # would leave it: overwriting the one this process has mapped would crash this one)
    damaged = tmp_path / "damaged"
    damaged.write_bytes(os.urandom(500))
    os.replace(damaged, built[0])
    result, err = in_new_process(tmp_path, aot_cache, "tiny_aot", 4.0)
    assert result == "5.0" and "does not load" in err and "Traceback" not in err, err
    assert len(list(aot_cache.glob("isorock_halve_*"))) == 1
    assert in_new_process(tmp_path, aot_cache, "tiny_aot", 2.0) == ("4.0", "")


def test_a_failed_ahead_of_time_build_falls_back_to_the_jit_kernel(tmp_path, aot_cache, monkeypatch, capsys):
    import numpy as np
    halve = tiny_aot(tmp_path, "tiny_aot_fallback")

    def no_compiler(dispatcher, name):
        raise OSError("no C compiler")
    monkeypatch.setattr(kernel_cache, "_build_module", no_compiler)
    assert kernel_cache.call_kernel(halve, 3.0, np.zeros(2)) == 1.5 + 2
    err = capsys.readouterr().err
    assert "cannot compile the analytic kernel ahead of time (OSError: no C compiler)" in err
    assert "JIT" in err and "Traceback" not in err
    # nothing half-built left behind (the empty lock file of the build stays: removing it
    # while another process opens it would let a third build beside that one)
    assert [p.name for p in aot_cache.iterdir()] == [f".{kernel_cache._module_name(halve)}.lock"]


def test_a_numba_without_pycc_falls_back_to_the_jit_kernel(tmp_path, aot_cache, monkeypatch, capsys):
    """numba has marked numba.pycc for deprecation: the day a numba comes without it, the
    build's import fails and the cached JIT kernel runs instead, with the same result and
    one line on stderr (no traceback, nothing left in the cache folder)."""
    import numpy as np
    halve = tiny_aot(tmp_path, "tiny_aot_no_pycc")
    monkeypatch.setitem(sys.modules, "numba.pycc", None)  # `from numba.pycc import ...` raises ImportError
    a = np.zeros(2)
    assert kernel_cache.call_kernel(halve, 7.0, a) == 3.5 + 2 and a[0] == 3.5
    err = capsys.readouterr().err
    assert err.startswith("isorock: cannot compile the analytic kernel ahead of time (") and "numba.pycc" in err, err
    assert "JIT" in err and "first use, cached in" not in err  # no build was announced
    assert "Traceback" not in err
    assert not list(aot_cache.glob("isorock_halve_*")) and not list(aot_cache.glob(".build-*"))


def test_numba_pycc_is_used_in_one_function_only():
    """The deprecated numba.pycc stays behind one function (kernel_cache._pycc), so
    replacing it is one change: no other module or function of the product imports it."""
    import ast
    root = Path(__file__).resolve().parents[1]
    users = []
    for folder in ("analytic", "mujoco_models", "bullet_models", "drake_models", "validate", "campaign",
                   "experiments"):
        for path in sorted((root / folder).rglob("*.py")):
            tree = ast.parse(path.read_text())
            enclosing = {id(n): f.name for f in ast.walk(tree) if isinstance(f, ast.FunctionDef)
                         for n in ast.walk(f)}  # innermost last: ast.walk visits outer functions first
            for node in ast.walk(tree):
                names = ([node.module or ""] if isinstance(node, ast.ImportFrom) else
                         [a.name for a in node.names] if isinstance(node, ast.Import) else [])
                if any(n == "numba.pycc" or n.startswith("numba.pycc.") for n in names):
                    users.append((path.relative_to(root).as_posix(), enclosing.get(id(node), "module level")))
    assert users and set(users) == {("analytic/kernel_cache.py", "_pycc")}, users


def test_a_new_process_runs_the_kernel_without_initialising_numba(tmp_path):
    """The point of the ahead-of-time module: a new process's first run does not pay
    numba's ~1 s target initialisation (which imports numba.np.arraymath and scipy.linalg).
    Structural, not timed: that module is never imported."""
    import subprocess
    from isorock.analytic import fast
    if kernel_cache._aot_function(fast._integrate) is None:
        pytest.skip("the kernel cannot be built ahead of time here (see the stderr line above)")
    code = ("import sys\nfrom isorock.analytic.fast import simulate_fast\n"
            "from isorock.analytic.motion import load_motion\nfrom isorock.analytic.system import paper_system\n"
            "t = simulate_fast(paper_system(fixed_base=True), load_motion('sine:amp=0.6,freq=1.3,cycles=1'), "
            "duration=3.0)\nprint(t.status != 'failed', len(t.impacts) > 0, 'numba.np.arraymath' in sys.modules)\n")
    env = {k: v for k, v in os.environ.items() if k != "ISOROCK_KERNEL"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["True", "True", "False"], (out.stdout, out.stderr)
    assert "compiling" not in out.stderr


def test_a_build_leaves_no_temporary_files_outside_its_own_folder(tmp_path, aot_cache, monkeypatch, capsys):
    """Issue 24 item 16: numba.pycc writes its C and object files into the system's temporary
    folder (a `pycc-build-*` folder it removes only on success, and a `temp.c` per compiler
    check that it never removes); every build, and every killed or failed one, left them
    there. They belong in the build's own `.build-PID-*` folder, which is always cleared."""
    import tempfile

    import numpy as np
    from numba.pycc import platform
    system_tmp = tmp_path / "system-tmp"
    system_tmp.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(system_tmp))
    platform.external_compiler_works.cache_clear()  # its compiler check writes temp.c: make it run here
    halve = tiny_aot(tmp_path, "tiny_aot_tmp")
    assert kernel_cache.call_kernel(halve, 5.0, np.zeros(3)) == 2.5 + 3
    assert list(system_tmp.iterdir()) == []
    # a build that fails half-way (the link step) leaves nothing either
    monkeypatch.setattr(kernel_cache, "_aot_loaded", {})
    for built in aot_cache.glob("isorock_halve_*"):
        built.unlink()

    def no_linker(*a, **k):
        raise OSError("the linker was killed")
    monkeypatch.setattr(platform.Toolchain, "link_shared", no_linker)
    halve = tiny_aot(tmp_path, "tiny_aot_tmp2")
    assert kernel_cache.call_kernel(halve, 3.0, np.zeros(2)) == 1.5 + 2  # the JIT kernel
    assert "linker was killed" in capsys.readouterr().err
    assert list(system_tmp.iterdir()) == [] and not list(aot_cache.glob(".build-*"))


def test_two_processes_that_need_the_same_kernel_build_it_once(tmp_path, aot_cache):
    """A campaign's worker processes (and the test session's background build) all ask for
    the kernel on a fresh install: one builds it, the others wait for it and load what it
    built, instead of each spending the same minutes. The builder is held midway by its
    stdin, so the order is fixed without any clock."""
    import subprocess
    load_tiny(tmp_path, "tiny_aot_once", TINY_AOT)
    env = {k: v for k, v in os.environ.items() if k != "ISOROCK_KERNEL"}
    setup = (
        "import importlib.util, sys\nimport numpy as np\nfrom numba import types as nt\n"
        "from isorock.analytic import kernel_cache as kc\n"
        f"kc.cache_dirs = lambda: [{str(aot_cache)!r}]\n"
        f"spec = importlib.util.spec_from_file_location('tiny_aot_once', {str(tmp_path / 'tiny_aot_once.py')!r})\n"
        "m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)\n"
        "f = kc.ahead_of_time(nt.float64(nt.float64, nt.float64[::1]))(m.halve)\n")
    held = (setup + "build = kc._build_module\n"
            "def held(*a):\n    print('building', flush=True)\n    sys.stdin.readline()\n    return build(*a)\n"
            "kc._build_module = held\nprint(kc.call_kernel(f, 3.0, np.zeros(3)), flush=True)\n")
    first = subprocess.Popen([sys.executable, "-c", held], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=env)
    second = None
    try:
        assert first.stdout.readline().strip() == "building"  # it holds the build
        second = subprocess.Popen([sys.executable, "-c", setup + "print(kc.call_kernel(f, 1.0, np.zeros(3)))\n"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        waiting = second.stderr.readline()
        assert "waiting for another process" in waiting, waiting
        first.stdin.write("\n")
        first.stdin.flush()
        out1, err1 = first.communicate(timeout=300)
        out2, err2 = second.communicate(timeout=300)
    finally:
        for p in (first, second):
            if p is not None and p.poll() is None:
                p.kill()
    assert first.returncode == 0 and out1.strip() == "4.5", err1
    assert second.returncode == 0 and out2.strip() == "3.5", err2
    assert "compiled" in err1 and "compil" not in err2, (err1, err2)  # built once, loaded once
    assert len(list(aot_cache.glob("isorock_halve_*"))) == 1


def test_a_build_held_past_the_wait_bound_is_built_here_too(tmp_path, aot_cache, monkeypatch, capsys):
    """Waiting for another process's build is bounded (BUILD_WAIT_S): a build that hangs,
    here one holding the lock until told, does not hang this process; it says so and
    builds its own copy."""
    import subprocess

    import numpy as np
    halve = tiny_aot(tmp_path, "tiny_aot_bound")
    name = kernel_cache._module_name(halve)
    holder = subprocess.Popen(
        [sys.executable, "-c", "import fcntl, sys\n"
         f"f = open({str(aot_cache / ('.' + name + '.lock'))!r}, 'a')\nfcntl.flock(f, fcntl.LOCK_EX)\n"
         "print('held', flush=True)\nsys.stdin.readline()\n"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        monkeypatch.setattr(kernel_cache, "BUILD_WAIT_S", 0.0)
        assert kernel_cache.call_kernel(halve, 5.0, np.zeros(3)) == 2.5 + 3
    finally:
        holder.communicate("\n", timeout=60)
    err = capsys.readouterr().err
    assert "waiting for another process" in err and "building it here" in err and "compiled" in err, err
    assert len(list(aot_cache.glob("isorock_halve_*"))) == 1


def test_every_cached_kernel_is_stamped_with_the_sources_it_compiles_in():
    """A kernel inlines analytic.physics's functions: its cache must be stamped with physics.py, or
    a change there runs the old compiled physics. design's rest pass (analytic/rest_scales.py) was
    stamped by numba with its own file only: after the two-edge physics landed, a checkout that
    had compiled it before kept the symmetric uplift test, and settled as standing a bust that
    lifts on its backward edge (design --check mujoco: 1 of 3 outcomes agreed)."""
    import inspect
    import pathlib
    here = pathlib.Path(kernel_cache.__file__).parent
    users = sorted(p for p in here.glob("*.py") if p.name != "kernel_cache.py" and "@cached_jit" in p.read_text())
    assert {p.name for p in users} >= {"fast.py", "slide_fast.py", "rest_scales.py"}
    for path in users:
        sources = kernel_cache.KERNEL_FILES.get(str(path.resolve()))
        assert sources is not None, f"{path.name}: its kernels' caches are stamped by numba with their own file only"
        assert {pathlib.Path(s).name for s in sources} >= {path.name, "physics.py"}, path.name
    from isorock.analytic import rest_scales
    locator_cls = kernel_cache._locator_class()
    f = rest_scales._rest_pass.py_func
    loc = locator_cls.from_function(f, inspect.getfile(f))
    assert loc is not None and len(loc.get_source_stamp()) >= 3  # rest_scales.py, fast.py, physics.py
