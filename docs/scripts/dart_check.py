"""DART (the engine "dart", dart_models/) against the exact model, as quoted in docs/dart.md:
free rocking from 0.5α on a fixed base and on the paper's isolator at H 0.2, 2 and 10 m (λ 2.86,
μ 1): the worst |β/β_closed − 1| over the first 4 counted impacts and the first impact time
against its closed form (fixed base); and two of the paper's pulses against the analytic
engine: counted impacts, θmax/α, overturning, the first uplift. Every number comes from
tests/test_dart.py's measuring functions, which assert them against validate/core/tolerances.py.

    python docs/scripts/dart_check.py
"""
import importlib.util
import time
from pathlib import Path

path = Path(__file__).resolve().parents[2] / "tests" / "test_dart.py"
spec = importlib.util.spec_from_file_location("test_dart", path)
T = importlib.util.module_from_spec(spec)
spec.loader.exec_module(T)

print("| case | DART | limit |\n|---|---|---|")
for height in T.HEIGHTS:
    for fixed in (True, False):
        start = time.process_time()
        got = T.measure_free_rocking(height, fixed)
        cpu = time.process_time() - start
        print(f"| free rocking, H {height:g} m, {'fixed base' if fixed else 'isolated'} | "
              + ", ".join(f"{k} {v:.2e}" for k, v in got.items()) + f" ({cpu:.1f} s CPU) | "
              + ", ".join(f"{k} ≤ {T.limit(k):g}" for k in got) + " |")
for name, (system, pulse) in T.PULSES.items():
    got = T.measure_pulse(system, pulse)
    print(f"| {name}: {pulse} | " + ", ".join(f"{k} {v:.3g}" for k, v in got.items()) + " | "
          + ", ".join(f"{k} ≤ {T.limit(k):g}" for k in got) + " |")
