"""The analytic model's two engines, declared in one place with the same settings and
presets: "analytic", the compiled kernel (analytic.fast), and "analytic-reference", the
same model on SciPy's DOP853 (analytic.hybrid), which the kernel is tested against."""
from .engine_protocol import Capabilities, EngineSpec, Preset
from .settings import AnalyticSettings as Settings
from .system import ISOLATOR_KINDS

PRESETS = {
    "default": Preset("the exact model at rtol 1e-10: the reference every engine is compared with", Settings),
    "conservative": Preset("overturned once |θ| reaches α (model.md's conservative rule), not only past it",
                           lambda: Settings(overturn="alpha")),
}


def ladder(quick: bool):
    """Work-precision ladder (label, Settings), cheapest first: tolerances, with
    max_step relaxed so the tolerance, not the step cap, sets the accuracy."""
    tols = (1e-4, 1e-7, 1e-10) if quick else (1e-4, 1e-6, 1e-8, 1e-10)
    return [(f"rtol={r:g}", Settings(rtol=r, atol=r * 1e-2, max_step=0.1)) for r in tols]


def simulate(system, motion=None, *, progress=None, **kwargs):
    """The compiled kernel: a whole run takes milliseconds, so there is no progress to report."""
    from .fast import simulate_fast
    return simulate_fast(system, motion, **kwargs)


def simulate_reference(system, motion=None, **kwargs):
    from .hybrid import simulate as reference
    return reference(system, motion, **kwargs)


ENGINE = EngineSpec(
    name="analytic", label="analytic", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=True, exact_impacts=True,
                              isolators=ISOLATOR_KINDS),
    presets=PRESETS, ladder=ladder)

REFERENCE_ENGINE = EngineSpec(
    name="analytic-reference", label="analytic (SciPy reference)", settings_type=Settings,
    simulate=simulate_reference,
    # a run takes a second where the compiled engine takes milliseconds: no grid engine
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=True,
                              campaigns=False, isolators=ISOLATOR_KINDS),
    presets=PRESETS, ladder=ladder)

__all__ = ["ENGINE", "REFERENCE_ENGINE", "Settings", "simulate", "simulate_reference", "ladder"]
