"""The compiled analytic kernel (analytic.fast) as an engine: same settings as the
reference path, same Trajectory."""
from .engine import ladder
from .engine_protocol import Capabilities, EngineSpec
from .fast import simulate_fast
from .hybrid import AnalyticSettings as Settings


def simulate(system, motion=None, *, progress=None, **kwargs):
    # a whole run takes milliseconds, so there is no progress to report
    return simulate_fast(system, motion, **kwargs)


ENGINE = EngineSpec(
    name="analytic-fast", label="analytic (compiled)", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=False, batch=True, exact_impacts=True),
    presets={"default": Settings}, ladder=ladder)

__all__ = ["ENGINE", "Settings", "simulate", "ladder"]
