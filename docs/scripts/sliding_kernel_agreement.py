"""The sliding model's compiled kernel against its SciPy reference on N random cases over every
base (tests/sliding_cases.py): how many slide, and the largest difference of any result in
the block's own scale (θ in α, lengths in b, times in 1/p). Issue 33's goal: kernel =
reference to 1e-9 on at least 300 cases that slide.

    python docs/scripts/sliding_kernel_agreement.py [N]        (default 1000)
"""
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from sliding_cases import case  # noqa: E402
from test_sliding_kernel import _differences  # noqa: E402

from isorock.analytic import hybrid  # noqa: E402
from isorock.analytic.fast import simulate_fast  # noqa: E402


def main(n: int) -> int:
    slid, worst, mismatched, seconds = 0, 0.0, [], [0.0, 0.0]
    diffs = []
    by_base = {}
    for i in range(n):
        system, motion, duration = case(i)
        t0 = time.perf_counter()
        ref = hybrid.simulate(system, motion, duration=duration)
        t1 = time.perf_counter()
        fast = simulate_fast(system, motion, duration=duration)
        t2 = time.perf_counter()
        seconds[0] += t1 - t0
        seconds[1] += t2 - t1
        same = (fast.status == ref.status and fast.impact_count == ref.impact_count
                and [s for _, s in fast.extras["slip_events"]] == [s for _, s in ref.extras["slip_events"]])
        d = _differences(ref, fast)
        slides = ref.summary()["slide_max"] > 1e-6 * system.b
        slid += slides
        base = "fixed" if system.fixed_base else system.isolator_kind
        n_b, s_b = by_base.get(base, (0, 0))
        by_base[base] = (n_b + 1, s_b + slides)
        if not same or not d < 1e-9:
            mismatched.append((i, base, str(ref.status), str(fast.status), d))
        if slides:
            diffs.append(d)
            worst = max(worst, d)
    print(f"{n} cases, {slid} slide (|x| > 1e-6·b at some time): per base " +
          ", ".join(f"{b} {s}/{k}" for b, (k, s) in by_base.items()))
    print(f"largest difference over the sliding cases: {worst:.2e} (median {np.median(diffs):.2e}) "
          "in units of α, b, 1/p")
    print(f"cases that differ in status, impacts or slip events, or by 1e-9 or more: {len(mismatched)}")
    for m in mismatched[:20]:
        print("  case %d (%s): reference %s, kernel %s, difference %.2e" % m)
    print(f"wall time: reference {seconds[0]:.1f} s, kernel {seconds[1]:.1f} s (×{seconds[0] / seconds[1]:.0f})")
    return 0 if not mismatched and slid >= 300 else 1


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 1000))
