"""The compiled kernel of the sliding model (analytic.slide_fast, engine "analytic") against its
reference path (analytic.slide_hybrid, SciPy's DOP853, engine "analytic-reference") on random
cases that slide on every base (tests/sliding_cases.py; docs/scripts/sliding_kernel_agreement.py
runs 1,000): the same status, events and impacts, and every number within 1e-9 of the block's
own scale (α for angles, b for lengths)."""
import sys
from pathlib import Path

import numpy as np
import pytest

from isorock.analytic import hybrid
from isorock.analytic.fast import compare_on_grid, simulate_batch, simulate_fast

sys.path.insert(0, str(Path(__file__).parent))
from sliding_cases import case  # noqa: E402

TOL = 1e-9
N_CASES = 150


def _differences(a, b):
    """The largest difference of two runs' results, each in the block's own scale."""
    sa, sb = a.summary(), b.summary()
    system = a.system
    d = [abs(sa["theta_max_over_alpha"] - sb["theta_max_over_alpha"]),
         abs(sa["slide_max"] - sb["slide_max"]) / system.b, abs(sa["slide_final"] - sb["slide_final"]) / system.b,
         abs(sa["u_max"] - sb["u_max"]) / system.b, compare_on_grid(a, b) / system.alpha]
    for (ta, _), (tb, _) in zip(a.extras["slip_events"], b.extras["slip_events"]):
        d.append(abs(ta - tb) * system.p)
    for ia, ib in zip(a.impacts, b.impacts):
        d.append(abs(ia.t - ib.t) * system.p)
        d.append(abs(ia.theta_dot_post - ib.theta_dot_post) / (system.p * system.alpha))
    return max(d)


def test_kernel_is_the_reference_on_random_sliding_cases():
    slid, worst = 0, 0.0
    for i in range(N_CASES):
        system, motion, duration = case(i)
        ref = hybrid.simulate(system, motion, duration=duration)
        fast = simulate_fast(system, motion, duration=duration)
        assert fast.engine == "analytic" and ref.engine == "analytic-reference"
        assert fast.status == ref.status and fast.message == ref.message, i
        assert [s for _, s in fast.extras["slip_events"]] == [s for _, s in ref.extras["slip_events"]], i
        assert fast.impact_count == ref.impact_count and len(fast.impacts) == len(ref.impacts), i
        assert np.allclose(fast.uplift_times, ref.uplift_times, rtol=0, atol=TOL / system.p), i
        d = _differences(ref, fast)
        assert d < TOL, (i, d)
        worst = max(worst, d)
        slid += ref.summary()["slide_max"] > 1e-6 * system.b
        assert ref.energy.relative_residual < 1e-8 and fast.energy.relative_residual < 1e-8, i
    assert slid >= 80  # most of them slide (the rest rock, rest or slide-rock below 1e-6·b)


def test_batch_rows_are_single_runs():
    cases = [case(i) for i in range(21)]
    rows = simulate_batch([c[0] for c in cases], [c[1] for c in cases], duration=[c[2] for c in cases])
    for (system, motion, duration), row in zip(cases, rows):
        single = simulate_fast(system, motion, duration=duration).summary()
        assert row["status"] == single["status"]
        for key in ("theta_max_over_alpha", "impacts", "uplifts", "overturned"):
            assert row[key] == pytest.approx(single[key], rel=1e-12, abs=1e-12), key
        assert row["slide_max"] == pytest.approx(single["slide_max"], rel=1e-12, abs=1e-15)
        assert row["u_max"] == pytest.approx(single["u_max"], rel=1e-9, abs=1e-15)
