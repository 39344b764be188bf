"""The compiled kernel ("analytic") against the SciPy reference ("analytic-reference") on
seeded random pulse cases, past-α cases included (analytic/agreement.py; the few-hundred
case version is docs/scripts/kernel_agreement.py). Same integrator steps and the same
physics module: θmax/α agrees to rounding, impacts and overturning exactly."""
import pytest

pytest.importorskip("isorock.analytic.fast", reason="numba is not installed")
from isorock.analytic.agreement import compare_paths, random_cases  # noqa: E402


def test_kernel_agrees_with_reference_on_random_cases():
    out = compare_paths(random_cases(seed=13, n=12))
    assert out["past_alpha_cases"] >= 2 and out["overturned_cases"] >= 1, out  # the draw covers both
    assert out["max_abs_dtheta_max_over_alpha"] < 1e-6, out
    assert out["impact_count_mismatches"] == 0 and out["overturn_mismatches"] == 0, out
    assert out["status_mismatches"] == 0, out
