"""analytic/kernel_cache.py: a damaged numba cache is rebuilt with one line on stderr, a
missing writable cache folder falls back instead of crashing, and the kernel's cache is
stamped with physics.py too. Exercised on a tiny jitted function of its own (the real
kernel takes a minute to compile), in a temporary folder."""
import importlib.util
import os
import sys

import pytest

pytest.importorskip("numba")
from isorock.analytic import kernel_cache  # noqa: E402

TINY = "from numba import njit\n\n@njit(cache=True)\ndef twice(x):\n    return 2.0 * x\n"


def load_tiny(folder, name):
    path = folder / f"{name}.py"
    path.write_text(TINY)
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
    # the stamp covers physics.py: the kernel inlines it
    assert len(loc.get_source_stamp()) == len(kernel_cache.KERNEL_SOURCES) == 2
    assert any(p.endswith("physics.py") for p in kernel_cache.KERNEL_SOURCES)


def test_first_compilation_is_announced(tmp_path, capsys):
    tiny = load_tiny(tmp_path, "tiny_announce")
    kernel_cache.call_kernel(tiny.twice, 1.0)
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("isorock: compiling") and err[-1].startswith("isorock: compiled")
    assert len(err) == 2
    sys.modules.pop("tiny_announce", None)
