"""The analytic model (the SciPy reference path, `hybrid.py`) as an engine
(`isorock.analytic.engine_protocol`)."""
from .engine_protocol import Capabilities, EngineSpec
from .hybrid import AnalyticSettings as Settings
from .hybrid import simulate


def ladder(quick: bool):
    """Work-precision ladder (label, Settings), cheapest first: tolerances, with
    max_step relaxed so the tolerance, not the step cap, sets the accuracy."""
    tols = (1e-4, 1e-7, 1e-10) if quick else (1e-4, 1e-6, 1e-8, 1e-10)
    return [(f"rtol={r:g}", Settings(rtol=r, atol=r * 1e-2, max_step=0.1)) for r in tols]


ENGINE = EngineSpec(
    name="analytic", label="analytic", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=False, batch=False, exact_impacts=True),
    presets={"default": Settings}, ladder=ladder)

__all__ = ["ENGINE", "Settings", "simulate", "ladder"]
