"""The analytic model's engine (registry name "analytic"): the compiled kernel
(analytic.fast), with the settings and Trajectory of the reference path ("analytic-reference")."""
from .engine import ladder
from .engine_protocol import Capabilities, EngineSpec
from .fast import simulate_fast
from .settings import AnalyticSettings as Settings


def simulate(system, motion=None, *, progress=None, **kwargs):
    # a whole run takes milliseconds, so there is no progress to report
    return simulate_fast(system, motion, **kwargs)


ENGINE = EngineSpec(
    name="analytic", label="analytic", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=True, exact_impacts=True),
    presets={"default": Settings, "conservative": lambda: Settings(overturn="alpha")}, ladder=ladder)

__all__ = ["ENGINE", "Settings", "simulate", "ladder"]
