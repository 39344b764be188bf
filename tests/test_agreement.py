"""The compiled kernel ("analytic") against the SciPy reference ("analytic-reference") on
seeded random pulse cases plus model.md's block that leans past α and returns
(tests/agreement_cases.py; the few-hundred-case version is docs/scripts/kernel_agreement.py).
Same integrator steps and the same physics module: θmax/α agrees to rounding, impacts
and overturning exactly."""
import math

import pytest

pytest.importorskip("isorock.analytic.fast", reason="numba is not installed")
from isorock.analytic import GroundMotion, Pulse, System  # noqa: E402
from agreement_cases import compare_paths, random_cases  # noqa: E402


def test_kernel_agrees_with_reference_on_random_cases():
    block = System.fixed(height=2.0, width=2 * math.tan(0.25), mass=1000.0)
    leans = GroundMotion.from_pulse(Pulse("sine", 9 * math.tan(0.25), 6 * block.p / (2 * math.pi)))
    out = compare_paths(random_cases(seed=7, n=6) + [(block, leans)])
    survivors_past_alpha = sum(r["past_alpha"] and not r["reference_overturned"] for r in out["rows"])
    assert survivors_past_alpha >= 1 and out["overturned_cases"] >= 1, out  # the draw covers both
    assert out["max_abs_dtheta_max_over_alpha"] < 1e-6, out
    assert out["impact_count_mismatches"] == 0 and out["overturn_mismatches"] == 0, out
    assert out["status_mismatches"] == 0, out
