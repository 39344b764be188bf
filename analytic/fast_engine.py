"""The analytic model's engine (registry name "analytic"): the compiled kernel
(analytic.fast), with the settings and Trajectory of the reference path ("analytic-reference")."""
from .fast import simulate_fast
from .settings import AnalyticSettings as Settings


def simulate(system, motion=None, *, progress=None, **kwargs):
    # a whole run takes milliseconds, so there is no progress to report
    return simulate_fast(system, motion, **kwargs)


__all__ = ["Settings", "simulate"]
