"""Where the compiled kernel (analytic/fast.py) is cached on disk, and how it is loaded.

numba's own cache has three failure modes users met (issue 13): a read-only install with
no writable home gives "cannot cache function" at import; a damaged cache file (random
bytes, a zero-length index) raises UnpicklingError/EOFError on every later run; and a
change to analytic/physics.py (which the kernel inlines) is not noticed, because numba
stamps a cache with the source file of the jitted function only. Here:

- `CacheLocator` stamps the kernel's cache with both fast.py and physics.py, and puts it
  in the first writable of: the package's `__pycache__`, `$ISOROCK_CACHE_DIR`,
  `$XDG_CACHE_HOME/isorock` (or `~/.cache/isorock`), a per-user temporary folder. With
  none writable `cached_jit` compiles without a cache (and says so once);
- `call_kernel` checks the cache before the first call: a damaged one is emptied with one
  line on stderr and rebuilt; the first compilation says on stderr what it is doing and
  how long it took (instead of a silent half minute).
"""
from __future__ import annotations

import os
import pickle
import sys
import tempfile
import time

_HERE = os.path.dirname(os.path.abspath(__file__))
#: the sources compiled into the kernel: a change to any of them invalidates the cache
KERNEL_SOURCES = tuple(os.path.join(_HERE, f) for f in ("fast.py", "physics.py"))


def _say(message: str) -> None:
    print(f"isorock: {message}", file=sys.stderr, flush=True)


def cache_dirs() -> list[str]:
    """Candidate cache folders, most preferred first."""
    dirs = [os.path.join(_HERE, "__pycache__")]
    if os.environ.get("ISOROCK_CACHE_DIR"):
        dirs.append(os.environ["ISOROCK_CACHE_DIR"])
    xdg = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    dirs.append(os.path.join(xdg, "isorock", "numba"))
    uid = os.getuid() if hasattr(os, "getuid") else "user"
    dirs.append(os.path.join(tempfile.gettempdir(), f"isorock-numba-{uid}"))
    return dirs


def _writable(path: str) -> bool:
    try:
        os.makedirs(path, exist_ok=True)
        tempfile.TemporaryFile(dir=path).close()
        return True
    except OSError:
        return False


def _locator_class():
    from numba.core.caching import _CacheLocator, _hash_source_file

    class CacheLocator(_CacheLocator):
        """numba cache locator for the kernel's functions only (see the module's doc)."""

        def __init__(self, py_func, py_file, path):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = path

        def ensure_cache_path(self):
            os.makedirs(self._cache_path, exist_ok=True)
            tempfile.TemporaryFile(dir=self._cache_path).close()

        def get_cache_path(self):
            return self._cache_path

        def get_source_stamp(self):
            stamps = []
            for path in KERNEL_SOURCES:
                st = os.stat(path)
                stamps.append(_hash_source_file(path, st.st_mtime, st.st_size))
            return tuple(stamps)

        def get_disambiguator(self):
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func, py_file):
            if os.path.abspath(py_file) not in KERNEL_SOURCES:
                return None  # not ours: numba's own locators decide
            for path in cache_dirs():
                if _writable(path):
                    return cls(py_func, py_file, path)
            return None

    return CacheLocator


_installed = False


def install_locator() -> None:
    """Put CacheLocator first in numba's list (it declines every file but the kernel's)."""
    global _installed
    if _installed:
        return
    from numba.core.caching import CacheImpl
    CacheImpl._locator_classes = [_locator_class(), *CacheImpl._locator_classes]
    _installed = True


def cached_jit(**options):
    """numba.njit(cache=True, **options), or without a cache (said once on stderr) when no
    cache folder is writable."""
    from numba import njit
    install_locator()

    def wrap(func):
        try:
            return njit(cache=True, **options)(func)
        except RuntimeError as e:  # numba: "cannot cache function ...: no locator available"
            _say(f"no writable cache folder ({e}); the kernel is compiled in every new process")
            return njit(**options)(func)
    return wrap


_ready: set = set()
_DAMAGED = (pickle.UnpicklingError, EOFError, ValueError, TypeError, AttributeError, IndexError, KeyError,
            ImportError, OSError)


def _cache_file(dispatcher):
    cache = getattr(dispatcher, "_cache", None)
    return getattr(cache, "_cache_file", None)


def _empty(dispatcher, error) -> None:
    cf = _cache_file(dispatcher)
    _say(f"the compiled-kernel cache {cf._index_path} is damaged ({type(error).__name__}: {error}); "
         "rebuilding it")
    folder, base = os.path.split(cf._index_path)
    stem = base[:-len(".nbi")]
    for name in os.listdir(folder):
        if name == base or (name.startswith(stem + ".") and name.endswith(".nbc")):
            try:
                os.remove(os.path.join(folder, name))
            except OSError:
                pass


def call_kernel(dispatcher, *args):
    """dispatcher(*args), after making sure its cache is loadable: a damaged cache is
    emptied and rebuilt; a compilation (first use, or sources changed) is announced on
    stderr with its duration."""
    if dispatcher in _ready:
        return dispatcher(*args)
    cf = _cache_file(dispatcher)
    compiling = not dispatcher.overloads
    if cf is not None and compiling:
        try:
            compiling = not cf._load_index()
        except _DAMAGED as e:
            _empty(dispatcher, e)
            compiling = True
    if compiling:
        where = f", cached in {cf._cache_path}" if cf is not None else ", not cached"
        _say(f"compiling the analytic kernel {dispatcher.__name__} (first use{where}; about a minute)...")
    start = time.perf_counter()
    try:
        out = dispatcher(*args)
    except _DAMAGED as e:
        if cf is None or dispatcher.overloads:
            raise
        _empty(dispatcher, e)  # the data file behind a readable index
        compiling = True
        _say(f"compiling the analytic kernel {dispatcher.__name__}...")
        out = dispatcher(*args)
    if compiling:
        _say(f"compiled {dispatcher.__name__} in {time.perf_counter() - start:.1f} s")
    _ready.add(dispatcher)
    return out
