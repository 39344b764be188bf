"""The non-linear isolators in MuJoCo and PyBullet against their closed forms and the analytic
model, as quoted in docs/isolators.md ("The contact engines"): every number comes from the
measuring functions of tests/test_isolator_engines.py (which assert them against
validate/core/tolerances.py), so the table and the tests cannot drift apart.

    python docs/scripts/isolator_engines.py
"""
import importlib.util
import time
from pathlib import Path

from isorock.validate.core.tolerances import tolerance

path = Path(__file__).resolve().parents[2] / "tests" / "test_isolator_engines.py"
spec = importlib.util.spec_from_file_location("test_isolator_engines", path)
T = importlib.util.module_from_spec(spec)
spec.loader.exec_module(T)

checks = [("pendulum free swing (R 1.5 m, μ_f 0.01)", T.measure_pendulum_free),
          ("stick–slip onset (A 0.3, 1 Hz, μ_f 0.05)", T.measure_onset),
          ("bearing yield time (k0 3e5, r 0.5, u_y 5 mm, step 0.05 g)", T.measure_yield),
          ("bearing peaks and loops (same, after a 0.1 g sine)", T.measure_loops)]
checks += [(f"{device} {params} under {pulse}", lambda e, d=device, p=params, q=pulse: T.measure_rocking(e, d, p, q))
           for device, params, pulse, _ in T.ROCKING]
for engine in T.ENGINES:
    print(f"== {engine}")
    for name, fn in checks:
        start = time.process_time()
        got = fn(engine)
        cpu = time.process_time() - start
        cells = ", ".join(f"{m} {v:.3g} (≤ {tolerance(engine, m).limit:g})" for m, v in got.items())
        print(f"{name}: {cells}  [{cpu:.2f} s CPU]")
