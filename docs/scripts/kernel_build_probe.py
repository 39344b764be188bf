"""What shortens the first build of the analytic kernel, and what it costs at run time (issue 34,
"a first run that starts at once"; docs/install.md, "The first build").

Compiles `_integrate` (the linear kernel) and `_integrate_iso` (the non-linear isolators') afresh,
with no cache, as numba's JIT does, in one of four ways, and runs the paper's block under Kobe on
each (CPU time, medians, the shipped kernel and the probe's interleaved) checking the histories
are identical to the bit:

- `full`: as shipped (analytic.physics's small functions and the kernel's own inlined in numba's IR);
- `physics`: physics's inlined, the kernel's own functions called;
- `hot`: physics's inlined only into the functions every step calls, none into the driver;
- `none`: nothing inlined by numba (LLVM still inlines what it finds worth it).

    python docs/scripts/kernel_build_probe.py none     # one mode per process: a fresh compile
Set NUMBA_OPT=0..3 to see LLVM's share (numba's default 3).
"""
from __future__ import annotations

import os
import resource
import statistics
import sys
import time
import types

import numpy as np
from numba import njit
from numba.core.registry import CPUDispatcher

import isorock.analytic.fast as fast
import isorock.analytic.physics as physics
from isorock.analytic.motion import read_at2
from isorock.analytic.system import FrictionPendulum, System

HOT = {"_rhs", "_eval_rhs", "_slider_event", "_event", "_dense_all", "_event_dense", "_brentq", "_initial_step",
       "_stage", "_set_row", "_rk_step", "_error_norm", "_dense_coeffs", "_store", "_base_acc_of", "_pivot_ratio",
       "_stick_or_slip", "_phase_after_velocity", "_iso_relift"}
PHYSICS = set(vars(physics))


def _hot_only(expr, caller_ir, callee_ir):
    return caller_ir.func_id.func_name in HOT or caller_ir.func_id.func_name in PHYSICS


def build(which: str, mode: str):
    """`which` kernel compiled afresh with `mode`'s inlining (the module's functions rebuilt over
    copies of their globals, as fast._isolator_kernel does)."""
    ptab, newp = dict(vars(physics)), {}
    for name, d in fast._P.items():
        if isinstance(d, CPUDispatcher) and name in vars(physics):
            shipped = d.targetoptions.get("inline", "never")
            inline = {"full": shipped, "physics": shipped, "none": "never",
                      "hot": _hot_only if shipped == "always" else "never"}[mode]
            f = d.py_func
            newp[name] = njit(inline=inline)(types.FunctionType(f.__code__, ptab, f.__name__, f.__defaults__,
                                                                f.__closure__))
    ptab.update(newp)
    table, by_id = dict(vars(fast)), {id(d): n for n, d in fast._P.items()}
    for k, v in list(table.items()):
        if id(v) in by_id and by_id[id(v)] in newp:
            table[k] = newp[by_id[id(v)]]
    if which == "_integrate_iso":
        table.update(_ISO=True, _NY=7, _N_EV=fast._ISO_N_EV, _DIRECTION=fast._ISO_DIRECTION)
    for name in fast._KERNEL_FUNCTIONS:
        d = getattr(fast, name)
        inline = d.targetoptions.get("inline", "never") if mode == "full" else "never"
        f = d.py_func
        table[name] = njit(inline=inline)(types.FunctionType(f.__code__, table, f.__name__, f.__defaults__,
                                                             f.__closure__))
    f = fast._integrate.py_func
    kernel = njit(nogil=True)(types.FunctionType(f.__code__, table, which, f.__defaults__, f.__closure__))
    kernel.compile(fast._integrate_signature())
    return kernel


def main() -> int:
    mode = sys.argv[1] if len(sys.argv) > 1 else "none"
    records = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data", "records")
    kobe = read_at2(os.path.join(records, "RSN1106_KOBE_KJM000.AT2"))
    paper = dict(height=2.0, width=0.7, mass=3800, base_mass=3800)
    cases = {"linear isolator": System.isolated(**paper, period=1.5, damping_ratio=0.2),
             "fixed base": System.fixed(**paper),
             "friction pendulum": System.with_isolator(**paper, isolator=FrictionPendulum(radius=2.0,
                                                                                          friction_coefficient=0.05))}
    shipped = (fast._integrate, fast._integrate_iso)
    for s in cases.values():
        fast.simulate_fast(s, kobe)  # the shipped kernels loaded (built if need be) before the clock
    print(f"load {os.getloadavg()[0]:.1f}; mode {mode}; NUMBA_OPT {os.environ.get('NUMBA_OPT', '3 (default)')}")
    start = time.perf_counter()
    linear = build("_integrate", mode)
    mid = time.perf_counter()
    iso = build("_integrate_iso", mode)
    end = time.perf_counter()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"compiled: linear {mid - start:.1f} s, isolators' {end - mid:.1f} s; peak memory {peak:.0f} MB")
    for name, system in cases.items():
        old, new = [], []
        for _ in range(15):
            for kernels, times in ((shipped, old), ((linear, iso), new)):
                fast._integrate, fast._integrate_iso = kernels
                t = time.process_time()
                tr = fast.simulate_fast(system, kobe)
                times.append(time.process_time() - t)
                if kernels is shipped:
                    ref = tr
        same = np.array_equal(ref.theta, tr.theta) and np.array_equal(ref.t, tr.t)
        print(f"{name}: shipped {statistics.median(old) * 1e3:.2f} ms CPU, {mode} {statistics.median(new) * 1e3:.2f} "
              f"ms, ratio {statistics.median(new) / statistics.median(old):.2f}, identical to the bit: {same}")
    fast._integrate, fast._integrate_iso = shipped
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
