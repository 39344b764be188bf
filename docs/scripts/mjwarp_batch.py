"""MuJoCo Warp's batch against MuJoCo's C engine on the same scene, as docs/mjwarp.md quotes it (issue
37): B runs of the paper's block rocking freely from θ0 between 0.3α and 0.7α for 3 s, on the fixed
base, by MuJoCo Warp as B worlds of one call (`mujoco_models.mjwarp.simulate_batch`, on Warp's
preferred device: its CPU here; its kernels compiled and the step recorded before the clock starts)
and by MuJoCo C one after another (the `full` preset: the same scene stepped throughout, as Warp
steps it), in this one process; wall seconds per run, and the largest |Δθ|/α between the two
engines' histories of the same run.

    python docs/scripts/mjwarp_batch.py [B ...]     # default 1 8 64 512
"""
import sys
import time

import numpy as np

from isorock.analytic.system import System
from isorock.mujoco_models.mjwarp import simulate_batch
from isorock.mujoco_models import Settings, simulate

system = System.fixed(height=2.0, width=0.7, mass=3800.0)
full = Settings(phased=False)
sizes = [int(b) for b in sys.argv[1:]] or [1, 8, 64, 512]
simulate_batch(system, [None], settings=full, duration=0.1, theta0=[0.5 * system.alpha])  # compiles the kernels
for b in sizes:
    theta0 = list(np.linspace(0.3, 0.7, b) * system.alpha)
    start = time.perf_counter()
    batch = simulate_batch(system, [None] * b, settings=full, duration=3.0, theta0=theta0)
    warp_s = (time.perf_counter() - start) / b
    start = time.perf_counter()
    alone = [simulate(system, None, settings=full, duration=3.0, theta0=th) for th in theta0]
    c_s = (time.perf_counter() - start) / b
    diff = max(float(np.max(np.abs(np.interp(a.t, m.t, m.theta) - a.theta))) for a, m in zip(alone, batch))
    print(f"B {b:4d}: MuJoCo Warp {warp_s * 1e3:8.1f} ms per run, MuJoCo C {c_s * 1e3:7.1f} ms per run "
          f"(Warp/C {warp_s / c_s:6.2f}×); max |Δθ|/α between them {diff / system.alpha:.2e}", flush=True)
