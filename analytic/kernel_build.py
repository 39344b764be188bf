"""Every compiled kernel built before a command needs it (issue 34: a first run that starts at once).

`pip install -e .` runs this (build_backend/isorock_backend.py), so that on a new install the
first run of any isolator kind, the first `design` and the first `sweep` wait for no build;
`python -m isorock.analytic.kernel_build` does the same for an install that skipped it (a
wheel, ISOROCK_BUILD_KERNELS=0) or after the kernels' sources changed.

Each kernel is built by the call a command makes, through the same path (kernel_cache's
ahead-of-time module, or numba's disk cache for the JIT kernels), so what is built is what a
run loads: a short run of each kind, and one rest pass. A numba build is one core's work, and
the non-linear isolators' kernel takes longer than the other three together
(kernel_cache.BUILD_ESTIMATE), so `build` gives it a process of its own beside one for the rest.
"""
from __future__ import annotations

import subprocess
import sys
import time

import numpy as np

from . import kernel_cache
from .motion import GroundMotion, load_motion
from .system import FrictionPendulum, System, paper_system

#: the kernels, by the name kernel_cache and its estimates use, in the two groups `build` runs side by side
GROUPS = (("_integrate_iso",), ("_integrate", "_run", "_rest_pass"))
KERNELS = tuple(name for group in GROUPS for name in group)
#: the longest a whole build may take before it is stopped (a first run then builds what is missing,
#: as before): the four took 80–120 s on the shared 2 cores (docs/install.md)
BUDGET_S = 900.0


def dispatcher(name: str):
    """The compiled function named `name` (one of KERNELS)."""
    from . import fast, rest_scales, slide_fast  # lazy: numba and the kernels, in the build processes only
    return {"_integrate": fast._integrate, "_integrate_iso": fast._integrate_iso, "_run": slide_fast._run,
            "_rest_pass": rest_scales._rest_pass}[name]


def _warm(name: str) -> None:
    """Make one call that needs kernel `name`, as a command makes it (it builds the kernel)."""
    from .fast import simulate_fast  # lazy: numba and the kernels, loaded in the build processes only
    record = GroundMotion.from_array(np.array([0.0, 0.5, -0.5, 0.0]), dt=0.02, units="g")
    if name == "_rest_pass":
        from .rest_scales import rest_phases  # lazy: as simulate_fast above
        rest_phases([paper_system()], [record], [[1.0]], [0.1], workers=1)
        return
    system = {"_integrate": paper_system(),
              "_integrate_iso": System.with_isolator(height=2.0, width=0.7, mass=3800, base_mass=3800,
                                                     isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.1)),
              "_run": paper_system(fixed_base=True).with_friction(0.4)}[name]
    simulate_fast(system, load_motion("sine:amp=0.6,freq=1.3,cycles=1"), duration=0.5)


def unbuilt(names=KERNELS) -> list[str]:
    """The kernels of `names` that a run in a new process would have to build first."""
    return [name for name in names if not kernel_cache.is_ready(dispatcher(name))]


def build_here(names=KERNELS) -> dict[str, float]:
    """Build, in this process, each kernel of `names` not built yet; {name: seconds it took}."""
    took = {}
    for name in unbuilt(names):
        start = time.perf_counter()
        _warm(name)
        took[name] = time.perf_counter() - start
    return took


def _say(message: str) -> None:
    print(f"isorock: {message}", file=sys.stderr, flush=True)


def build(preamble: str = "", python: str = sys.executable, budget_s: float = BUDGET_S) -> bool:
    """Build every kernel not built yet, GROUPS side by side in processes of `python` (each
    running `preamble` first: the build backend's, which makes the source tree importable);
    said on stderr. True where every process ended well; a failure or the budget passed is
    said in one line and leaves the rest to a first run (never raises)."""
    start = time.perf_counter()
    _say(f"building the compiled analytic kernels in {len(GROUPS)} processes "
         f"(once per install, 1-3 minutes on 2 cores; ISOROCK_BUILD_KERNELS=0 skips it)...")
    procs = []
    for group in GROUPS:
        code = f"{preamble}\nfrom isorock.analytic.kernel_build import build_here\nbuild_here({group!r})\n"
        procs.append(subprocess.Popen([python, "-c", code], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                      text=True))
    ok = True
    for proc in procs:
        try:
            _, err = proc.communicate(timeout=max(1.0, budget_s - (time.perf_counter() - start)))
        except subprocess.TimeoutExpired:
            for p in procs:
                p.kill()
            _say(f"the kernels' build passed its budget of {budget_s:.0f} s and was stopped; "
                 "a first run builds what is missing")
            return False
        if proc.returncode != 0:
            ok = False
            last = (err.strip().splitlines() or ["no message"])[-1]
            _say(f"a kernel build failed ({last}); a first run builds it instead")
    if ok:
        _say(f"built the compiled analytic kernels in {time.perf_counter() - start:.0f} s")
    return ok


def main() -> int:
    missing = unbuilt()
    if not missing:
        _say("every compiled analytic kernel is built already")
        return 0
    return 0 if build() else 1


if __name__ == "__main__":
    sys.exit(main())
