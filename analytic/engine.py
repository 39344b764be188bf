"""The analytic model's SciPy reference path (registry name "analytic-reference"), which
the compiled engine "analytic" is tested against."""
from .hybrid import simulate
from .settings import AnalyticSettings as Settings

__all__ = ["Settings", "simulate"]
