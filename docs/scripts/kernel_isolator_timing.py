"""The isolator kernel against the SciPy reference in CPU time (process_time medians), one
process, warm (the kernel compiled once before):

    python docs/scripts/kernel_isolator_timing.py

Kobe JMA N-S on the paper's block on a pendulum and on a bearing, and 40 seeded random pulse
cases per isolator type (tests/agreement_cases.py), single runs and simulate_batch's summaries.
The machine's load matters: quote it."""
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from agreement_cases import isolator_cases  # noqa: E402
from isorock.analytic.fast import simulate_batch, simulate_fast  # noqa: E402
from isorock.analytic.hybrid import simulate  # noqa: E402
from isorock.analytic.motion import read_at2  # noqa: E402
from isorock.analytic.system import BilinearIsolator, FrictionPendulum, System  # noqa: E402
from isorock.validate.core.scenarios import KOBE  # noqa: E402  (the records folder, found as the commands find it)

kobe = read_at2(KOBE)
blk = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)
fp = System.with_isolator(**blk, isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.06))
bl = System.with_isolator(**blk, isolator=BilinearIsolator(stiffness=3e6, post_yield_ratio=0.1, yield_displacement=0.002, damping=1000.0))
def med(fn, n):
    ts = []
    for _ in range(n):
        t = time.process_time(); fn(); ts.append(time.process_time() - t)
    return statistics.median(ts)
print("load", os.getloadavg()[0])
for name, s in (("pendulum R 1 m mu 0.06", fp), ("bilinear 3e6/0.1/2mm/c1000", bl)):
    simulate_fast(s, kobe)
    k = med(lambda: simulate_fast(s, kobe), 7); r = med(lambda: simulate(s, kobe), 1)
    print(f"Kobe JMA (record + 5 s tail), {name}: kernel {k*1e3:.1f} ms, reference {r:.2f} s, ratio {r/k:.0f}x")
for kind in ("friction-pendulum", "bilinear"):
    cs = isolator_cases(22, 40, kind)
    k = med(lambda: [simulate_fast(s, m) for s, m in cs], 5); r = med(lambda: [simulate(s, m) for s, m in cs], 1)
    b = med(lambda: simulate_batch([c[0] for c in cs], [c[1] for c in cs], duration=6.0, workers=1), 5)
    print(f"40 random {kind} pulse cases: kernel {k*1e3:.1f} ms (batch summaries, 6 s each: {b*1e3:.1f} ms), reference {r:.2f} s, ratio {r/k:.0f}x")
print("load", os.getloadavg()[0])
