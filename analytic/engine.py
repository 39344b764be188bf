"""The analytic model's SciPy reference path (registry name "analytic-reference"), which
the compiled engine "analytic" is tested against."""
from .engine_protocol import Capabilities, EngineSpec
from .hybrid import simulate
from .settings import AnalyticSettings as Settings


def ladder(quick: bool):
    """Work-precision ladder (label, Settings), cheapest first: tolerances, with
    max_step relaxed so the tolerance, not the step cap, sets the accuracy."""
    tols = (1e-4, 1e-7, 1e-10) if quick else (1e-4, 1e-6, 1e-8, 1e-10)
    return [(f"rtol={r:g}", Settings(rtol=r, atol=r * 1e-2, max_step=0.1)) for r in tols]


ENGINE = EngineSpec(
    name="analytic-reference", label="analytic (SciPy reference)", settings_type=Settings, simulate=simulate,
    # a run takes a second where the compiled engine takes milliseconds: no grid engine
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=True,
                              campaigns=False),
    presets={"default": Settings, "conservative": lambda: Settings(overturn="alpha")}, ladder=ladder)

__all__ = ["ENGINE", "Settings", "simulate", "ladder"]
