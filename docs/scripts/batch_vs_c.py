"""A batched MuJoCo engine's batch against MuJoCo's C engine on the same scene, as docs/mjx.md and
docs/mjwarp.md quote it (issue 37): B runs of the paper's block rocking freely from θ0 between 0.3α
and 0.7α for 3 s, on the fixed base, by the batched engine in one call (MJX: one vmapped batch,
`mujoco_models.mjx.simulate_batch`; MuJoCo Warp: B worlds of one call on Warp's preferred device,
its CPU here, `mujoco_models.mjwarp.simulate_batch`), compiled before the clock starts, and by
MuJoCo C one after another (the `full` preset: the same scene stepped throughout, as the batched
engines step it), in this one process; wall seconds per run, and the largest |Δθ|/α between the two
engines' histories of the same run.

    python docs/scripts/batch_vs_c.py mjx [B ...]      # default 1 8 64
    python docs/scripts/batch_vs_c.py mjwarp [B ...]   # default 1 8 64 512
"""
import importlib
import sys
import time

import numpy as np

from isorock.analytic.system import System
from isorock.mujoco_models import Settings, simulate

#: per engine: its label, the default batch sizes, the duration of the run that compiles it
ENGINES = {"mjx": ("MJX", [1, 8, 64], 3.0), "mjwarp": ("MuJoCo Warp", [1, 8, 64, 512], 0.1)}


def main() -> int:
    engine = sys.argv[1] if len(sys.argv) > 1 else ""
    if engine not in ENGINES:
        print(f"engine = {engine!r}: one of {', '.join(ENGINES)}", file=sys.stderr)
        return 2
    label, default_sizes, warm_up = ENGINES[engine]
    simulate_batch = importlib.import_module(f"isorock.mujoco_models.{engine}").simulate_batch
    system = System.fixed(height=2.0, width=0.7, mass=3800.0)
    full = Settings(phased=False)
    sizes = [int(b) for b in sys.argv[2:]] or default_sizes
    simulate_batch(system, [None], settings=full, duration=warm_up, theta0=[0.5 * system.alpha])  # compiles it
    for b in sizes:
        theta0 = list(np.linspace(0.3, 0.7, b) * system.alpha)
        start = time.perf_counter()
        batch = simulate_batch(system, [None] * b, settings=full, duration=3.0, theta0=theta0)
        batched_s = (time.perf_counter() - start) / b
        start = time.perf_counter()
        alone = [simulate(system, None, settings=full, duration=3.0, theta0=th) for th in theta0]
        c_s = (time.perf_counter() - start) / b
        diff = max(float(np.max(np.abs(np.interp(a.t, m.t, m.theta) - a.theta))) for a, m in zip(alone, batch))
        print(f"B {b:4d}: {label} {batched_s * 1e3:8.1f} ms per run, MuJoCo C {c_s * 1e3:7.1f} ms per run "
              f"({label}/C {batched_s / c_s:6.2f}×); max |Δθ|/α between them {diff / system.alpha:.2e}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
