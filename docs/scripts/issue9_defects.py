"""The three issue-9 defect cases (and the high-frequency one at 10 Hz), on either path:

    python docs/scripts/issue9_defects.py fast|ref [case ...]

cases: grazing (isolated, h 1 m, α 0.25, T 1.5 s, ξ 0.2, one sine ω_p = 8.5p at 4.3·g·tanα),
hf50 / hf10 (the paper's block on a fixed base, 50 Hz at 1.5·g·tanα / 10 Hz at 1.01·g·tanα),
past_alpha (fixed base, α 0.25, ω_p = 6p, a_p = 9·g·tanα)."""
import math, sys, time
from isorock.analytic import GroundMotion, Pulse, System
from isorock.analytic.hybrid import simulate as ref
engine = sys.argv[1]
if engine == "fast":
    from isorock.analytic.fast import simulate_fast as sim
else:
    sim = ref
a = 0.25
iso = System.isolated(height=2.0, width=2 * math.tan(a), mass=1000.0, base_mass=1000.0, period=1.5, damping_ratio=0.2)
paper_fixed = System.fixed(height=2.0, width=0.7, mass=3800.0)
fixed = System.fixed(height=2.0, width=2 * math.tan(a), mass=1000.0)
cases = {
 "grazing": (iso, Pulse("sine", 4.3 * math.tan(a), 8.5 * iso.p / (2 * math.pi))),
 "hf50": (paper_fixed, Pulse("sine", 1.5 * 0.35, 50.0)),
 "hf10": (paper_fixed, Pulse("sine", 1.01 * 0.35, 10.0)),
 "past_alpha": (fixed, Pulse("sine", 9 * math.tan(a), 6 * fixed.p / (2 * math.pi))),
}
for name in sys.argv[2:] or cases:
    s, p = cases[name]
    t0 = time.perf_counter()
    tr = sim(s, GroundMotion.from_pulse(p))
    print(f"{engine} {name}: status={tr.status} impacts={tr.impact_count} (all {len(tr.impacts)}) uplifts={tr.uplifts} "
          f"theta_max/alpha={tr.theta_max_over_alpha:.4f} overturn_time={tr.overturn_time} "
          f"wall={time.perf_counter()-t0:.3f}s {tr.message}", flush=True)
