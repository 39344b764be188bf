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
  how long it took (instead of a silent half minute);
- a function marked `ahead_of_time(signature)` (the kernel's `_integrate`) is compiled by
  numba.pycc into an extension module in the same cache folder, and `call_kernel` runs
  that: a new process loads it in milliseconds, where numba's JIT needs ~1 s to start
  (see the section at the end of this file). The JIT kernel stays the fallback.
"""
from __future__ import annotations

import contextlib
import hashlib
import importlib.machinery
import importlib.util
import os
import pickle
import platform
import shutil
import sys
import tempfile
import threading
import time
import warnings

import numpy as np

_HERE = os.path.dirname(os.path.abspath(__file__))
#: the sources compiled into the kernel: a change to any of them invalidates the cache
KERNEL_SOURCES = tuple(os.path.join(_HERE, f) for f in ("fast.py", "physics.py", "dop853.py"))
#: every kernel file and the sources compiled into its kernels: the sliding model's kernel
#: (analytic/slide_fast.py) compiles slide_physics.py and physics.py, and dop853.py's tableau; design's
#: rest pass (analytic/rest_scales.py) fast.py's compiled physics. A file missing here is stamped by
#: numba with its own source only, and keeps running the physics it was first compiled with
#: (tests/test_kernel_cache.py holds every @cached_jit file to this table).
KERNEL_FILES = {KERNEL_SOURCES[0]: KERNEL_SOURCES,
                os.path.join(_HERE, "slide_fast.py"): tuple(os.path.join(_HERE, f) for f in
                                                            ("slide_fast.py", "slide_physics.py", "physics.py",
                                                             "dop853.py")),
                os.path.join(_HERE, "rest_scales.py"): tuple(os.path.join(_HERE, f) for f in
                                                             ("rest_scales.py", "fast.py", "physics.py"))}


#: What a first build announces, per kernel: its time measured on a fresh checkout of the shared
#: 2-core machine at load about 1 (issue 39: an estimate is a bound that holds), 1.5× and rounded up:
#: _integrate 38.5 s, _run 33.9 s, _integrate_iso 80–106 s with a peak of 1.7–1.9 GB since its
#: bookkeeping is compiled out of line (analytic/fast.py, before _store; 157.3 s and 2.9 GB before)
#: (`isorock run --isolator friction-pendulum …` in a new checkout, /usr/bin/time)
BUILD_ESTIMATE = {"_integrate": "up to a minute", "_run": "up to a minute",
                  "_integrate_iso": "up to 3 minutes and 2 GB of memory"}


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


def writable_cache_dir() -> str | None:
    """The first of cache_dirs() that can be written (made if need be), or None."""
    return next((d for d in cache_dirs() if _writable(d)), None)


def _locator_class():
    from numba.core.caching import _CacheLocator, _hash_source_file  # lazy: numba, for the JIT cache only

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
            for path in KERNEL_FILES[os.path.abspath(self._py_file)]:
                st = os.stat(path)
                stamps.append(_hash_source_file(path, st.st_mtime, st.st_size))
            return tuple(stamps)

        def get_disambiguator(self):
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func, py_file):
            if os.path.abspath(py_file) not in KERNEL_FILES:
                return None  # not ours: numba's own locators decide
            path = writable_cache_dir()
            return None if path is None else cls(py_func, py_file, path)

    return CacheLocator


_installed = False


def install_locator() -> None:
    """Put CacheLocator first in numba's list (it declines every file but the kernel's)."""
    global _installed
    if _installed:
        return
    from numba.core.caching import CacheImpl  # lazy: numba, where a kernel is compiled or its cache looked up
    CacheImpl._locator_classes = [_locator_class(), *CacheImpl._locator_classes]
    _installed = True


def cached_jit(**options):
    """numba.njit(cache=True, **options), or without a cache (said once on stderr) when no
    cache folder is writable."""
    from numba import njit  # lazy: numba, where a kernel is compiled
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
    stderr with its duration. A dispatcher built ahead of time (`ahead_of_time`) runs as
    that extension module's function where it can be built."""
    if dispatcher in _aot_exports:
        fn = _aot_function(dispatcher)
        if fn is not None:
            return fn(*[c_writable(a) for a in args])
    # every array writable and C-contiguous, as the ahead-of-time export takes them: numba
    # compiles a signature per array flavour, and a record's read-only array beside a pulse's
    # writable one compiled the sliding kernel once for each (33 s each; four in one cache)
    args = [c_writable(a) for a in args]
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


# --- the kernel compiled ahead of time: a new process loads it in milliseconds ------------
#
# Why: numba's first call in a process initialises its CPU target (its typing and lowering
# registries, numba.np.arraymath importing scipy.linalg to probe BLAS): ~1 s on this
# machine before the cached kernel is even looked at, for a 40 s Kobe run that takes
# ~0.07 s. The same kernel compiled by numba.pycc into a CPython extension module needs
# none of that: importing it takes milliseconds. It is built once (on first use, instead
# of the JIT compilation, said on stderr) into the same cache folder, named after a stamp
# of the kernel's sources and of the toolchain and CPU it was built for, so a change to
# any of them builds a new one. Its Python wrapper releases the GIL like the JIT kernel's
# (nogil), so threads over it run in parallel. Where it cannot be built (no C compiler, a
# numba without pycc) the JIT kernel is used, said once on stderr;
# ISOROCK_KERNEL=jit asks for the JIT kernel outright.

_aot_exports: dict = {}  # dispatcher -> numba signature of its ahead-of-time export
_aot_loaded: dict = {}  # dispatcher -> the extension's function, or None (use the JIT)


def ahead_of_time(signature):
    """Also build the decorated cached_jit function ahead of time, with this signature: a
    numba signature, or a tuple of argument types (numba infers the return type). Every
    array C-contiguous and writable; call_kernel makes them so."""
    def wrap(dispatcher):
        _aot_exports[dispatcher] = signature
        return dispatcher
    return wrap


def _stamp(dispatcher) -> str:
    import llvmlite.binding as llvm  # lazy: the cache stamp only; a cache check loads no numba
    import numba
    h = hashlib.sha256()
    for path in KERNEL_SOURCES:
        with open(path, "rb") as f:
            h.update(f.read())
    h.update(str(_aot_exports[dispatcher]).encode())
    for part in (numba.__version__, np.__version__, sys.version, platform.machine(),
                 llvm.get_host_cpu_name(), llvm.get_host_cpu_features().flatten()):
        h.update(part.encode())
    return h.hexdigest()[:16]


def _module_name(dispatcher) -> str:
    return f"isorock_{dispatcher.__name__.strip('_')}_{_stamp(dispatcher)}"


def _find_modules(name: str) -> list[str]:
    """Every cached copy of `name`'s module, most preferred folder first."""
    return [path for folder in cache_dirs() for suffix in importlib.machinery.EXTENSION_SUFFIXES
            if os.path.isfile(path := os.path.join(folder, name + suffix))]


def _find_module(name: str) -> str | None:
    found = _find_modules(name)
    return found[0] if found else None


def clear_leftovers(folder: str) -> None:
    """Remove the `.build-PID-*` folders of builds whose process is gone (killed midway):
    each held half a build (C sources, objects) that nothing else would remove."""
    try:
        entries = os.listdir(folder)
    except OSError:
        return
    for entry in entries:
        if not entry.startswith(".build-"):
            continue
        pid = entry.split("-")[1] if entry.count("-") >= 2 else ""
        if pid.isdigit() and _alive(int(pid)):
            continue
        shutil.rmtree(os.path.join(folder, entry), ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # another user's process
    return True


def _load_module(name: str, path: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _pycc():
    """(CC, numba.pycc.compiler): the one place numba.pycc is imported. numba marked it
    for deprecation (0.57) with its replacement "being developed"; numba 0.68 still ships
    it and no supported ahead-of-time compiler for numba code is released (docs/floors.md:
    the cold start with and without it, measured). A numba without it raises
    ImportError here, before any build is announced, and the JIT kernel serves."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numba.pycc's pending-deprecation notice
        from numba.pycc import CC  # lazy: numba.pycc, for an ahead-of-time build only
        from numba.pycc import compiler as pycc_compiler
    return CC, pycc_compiler


def _build_module(dispatcher, name: str) -> str:
    """Compile dispatcher's Python function with numba.pycc into `name`'s extension module,
    in a temporary folder renamed into the first writable cache folder: whole or absent,
    and two processes building at once each leave a whole file."""
    from numba.core import compiler as numba_compiler  # lazy: numba, for an ahead-of-time build only
    CC, pycc_compiler = _pycc()
    folder = writable_cache_dir()
    if folder is None:
        raise OSError("no writable cache folder")

    class NoGilFlags(numba_compiler.Flags):
        """pycc's flags with the GIL released around the call, as njit(nogil=True) does."""

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.release_gil = True

    clear_leftovers(folder)
    tmp = tempfile.mkdtemp(prefix=f".build-{os.getpid()}-", dir=folder)  # the pid: a killed build's is cleared
    # numba.pycc writes its C and object files into the system's temporary folder (its
    # compiler check, made when CC() is, a temp.c it never removes; the build's own folder
    # removed only on success): inside the build's folder they go with it, or with the next
    old_tmp = tempfile.tempdir
    tempfile.tempdir = tmp
    try:
        cc = CC(name)
        cc.output_dir = tmp
        cc.target_cpu = "host"  # the stamp names the CPU: a copy on another CPU is not loaded
        cc.verbose = False
        cc.export("run", _aot_exports[dispatcher])(dispatcher.py_func)
        old = pycc_compiler.Flags
        pycc_compiler.Flags = NoGilFlags
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cc.compile()
        finally:
            pycc_compiler.Flags = old
        built = [f for f in os.listdir(tmp) if f.startswith(name + ".") and f.endswith((".so", ".pyd"))]
        if not built:
            raise OSError(f"numba.pycc wrote no module in {tmp}")
        target = os.path.join(folder, built[0])
        os.replace(os.path.join(tmp, built[0]), target)
        return target
    finally:
        tempfile.tempdir = old_tmp
        shutil.rmtree(tmp, ignore_errors=True)


#: One build at a time in a process: threads of a batch (simulate_batch's workers) that
#: all call a kernel not yet built would each build it (measured: `isorock design
#: --isolator friction-pendulum` on a fresh checkout compiled _integrate_iso twice, 91 and
#: 120 s, side by side); the later ones wait for the first and load what it built.
_BUILD_LOCK = threading.Lock()


def prepare(dispatcher) -> bool:
    """Load, or build and load, dispatcher's ahead-of-time module without running it (a
    process that readies the cache for others, e.g. the test session's background build);
    True where that module serves, False where the JIT kernel will."""
    return _aot_function(dispatcher) is not None


def is_built(dispatcher) -> bool:
    """Whether dispatcher's ahead-of-time module is in a cache folder already."""
    return _find_module(_module_name(dispatcher)) is not None


def is_ready(dispatcher) -> bool:
    """Whether a call of dispatcher through call_kernel would run without compiling: it
    is loaded in this process, or its ahead-of-time module is built, or (the JIT kernel
    asked for, or a kernel with no ahead-of-time build) numba's disk cache holds it. A
    damaged cache counts as not ready (call_kernel rebuilds it)."""
    if dispatcher in _ready or _aot_loaded.get(dispatcher) is not None or dispatcher.overloads:
        return True
    if dispatcher in _aot_exports and dispatcher not in _aot_loaded and os.environ.get("ISOROCK_KERNEL", "aot") != "jit":
        return is_built(dispatcher)  # call_kernel builds it first, whatever numba's cache holds
    cf = _cache_file(dispatcher)
    try:
        index = cf._load_index() if cf is not None else {}
    except _DAMAGED:
        return False
    # the one signature call_kernel calls with: every array writable (an older cache may hold
    # read-only flavours only, which a call no longer matches)
    from numba.core.types import Array  # lazy: numba, where a cache index was read
    return any(all(t.mutable for t in key[0] if isinstance(t, Array)) for key in index)


def _aot_function(dispatcher):
    """The extension module's function for dispatcher, built first if needed; None where
    the JIT kernel is to be used instead (said once)."""
    if dispatcher in _aot_loaded:
        return _aot_loaded[dispatcher]
    with _BUILD_LOCK:
        if dispatcher in _aot_loaded:  # built (or refused) by another thread meanwhile
            return _aot_loaded[dispatcher]
        return _aot_function_locked(dispatcher)


def _aot_function_locked(dispatcher):
    fn = None
    if os.environ.get("ISOROCK_KERNEL", "aot") != "jit":
        try:
            name = _module_name(dispatcher)
            fn, why = _load_cached(name)
            if fn is None:
                _pycc()  # a numba without numba.pycc: said (below) before any build is announced
                folder = writable_cache_dir()
                with _build_lock(folder, name):
                    fn, again = _load_cached(name)  # built by another process while this one waited
                    why = why or again
                    if fn is None:  # the reason and the build in one line (and its end in another)
                        _say(f"{why + '; ' if why else ''}compiling the analytic kernel {dispatcher.__name__} "
                             f"ahead of time ({'again' if why else 'first use'}, cached in "
                             f"{folder or '?'}; {BUILD_ESTIMATE.get(dispatcher.__name__, 'a few minutes')})...")
                        start = time.perf_counter()
                        fn = _load_module(name, _build_module(dispatcher, name)).run
                        _say(f"compiled {dispatcher.__name__} in {time.perf_counter() - start:.1f} s")
        except Exception as e:  # noqa: BLE001 - any failure to build leaves the JIT kernel, which always works
            _say(f"cannot compile the analytic kernel ahead of time ({type(e).__name__}: {e}); "
                 "using numba's JIT kernel (its disk cache costs each new process ~0.2-0.4 s more)")
            fn = None
    _aot_loaded[dispatcher] = fn
    return fn


def _load_cached(name: str):
    """(the cached module's function or None, why a copy did not load or ""): damaged
    copies are removed, and a good copy further on still serves (said in one line)."""
    fn, damaged = None, []
    for path in _find_modules(name):  # a damaged copy must not hide a good one further on
        try:
            fn = _load_module(name, path).run
            break
        except (ImportError, OSError):
            damaged.append(path)
            try:
                os.remove(path)
            except OSError:
                pass  # an unwritable folder: the next copy, or a build elsewhere, serves
    why = (f"the compiled kernel {damaged[0]}{f' (and {len(damaged) - 1} more)' if len(damaged) > 1 else ''}"
           " does not load" if damaged else "")
    if damaged and fn is not None:
        _say(f"{why}; using another cached copy")
    return fn, why


@contextlib.contextmanager
def _build_lock(folder: str | None, name: str):
    """One build of `name` at a time over every process sharing `folder` (the worker
    processes of a campaign on a fresh install would otherwise each spend the same
    minutes): an advisory lock on a file beside the modules, released by the system if
    its holder dies. Where there is none (no fcntl, an unwritable folder) builds may run
    side by side, each leaving a whole file (_build_module)."""
    try:
        import fcntl  # lazy: POSIX only
        handle = open(os.path.join(folder, f".{name}.lock"), "a")  # noqa: SIM115 - held across the yield
    except (ImportError, OSError, TypeError):
        yield
        return
    with handle:
        held = _try_lock(fcntl, handle)
        if not held:
            _say(f"waiting for another process building the analytic kernel {name} "
                 f"(at most {BUILD_WAIT_S / 60:g} min)...")
            deadline = time.monotonic() + BUILD_WAIT_S
            while not held and time.monotonic() < deadline:
                time.sleep(0.2)
                held = _try_lock(fcntl, handle)
            if not held:  # a build that hangs must not hang this process too
                _say(f"the other build of {name} did not end within {BUILD_WAIT_S / 60:g} min; building it here")
        try:
            yield
        finally:
            if held:
                fcntl.flock(handle, fcntl.LOCK_UN)


#: the longest a process waits for another's build of the same kernel (builds take 1–2
#: min; past this one it builds its own copy, which replaces the file whole)
BUILD_WAIT_S = 600.0


def _try_lock(fcntl, handle) -> bool:
    try:
        fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return True
    except OSError:
        return False


def c_writable(a):
    """a, or a C-contiguous writable copy of an array that is not: the one flavour of array every
    kernel is compiled for."""
    if isinstance(a, np.ndarray):
        if a.flags.c_contiguous and a.flags.writeable:
            return a
        return np.array(a, order="C")
    return a
