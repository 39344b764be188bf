"""The analytic model's two engines, declared in one place with the same settings and
presets: "analytic", the compiled kernel (analytic.fast), and "analytic-reference", the
same model on SciPy's DOP853 (analytic.hybrid), which the kernel is tested against."""
import numbers
import os

from . import fast, hybrid, kernel_cache, slide_fast
from .engine_protocol import Capabilities, EngineSpec, Preset
from .motion import GroundMotion
from .settings import AnalyticSettings as Settings
from .slide_physics import needs_contact_model
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
    return fast.simulate_fast(system, motion, **kwargs)


def simulate_reference(system, motion=None, **kwargs):
    return hybrid.simulate(system, motion, **kwargs)


def _kernel_of(system, motion):
    """The compiled kernel a run of `system` under `motion` calls: the sliding model's, the
    linear one (fixed base, linear isolator) or the non-linear isolators'."""
    if needs_contact_model(system, motion):
        return slide_fast._run
    return fast._integrate if system.fixed_base or system.isolator is None else fast._integrate_iso


#: what each kernel serves, by its name (kernel_cache.BUILD_ESTIMATE's keys)
_KERNEL_SERVES = {"_integrate": "the fixed base's and the linear isolator's", "_integrate_iso":
                  "the non-linear isolators'", "_run": "the sliding statue's and vertical shaking's"}


def kernel_ready(system, motion=None) -> bool:
    """Whether the compiled kernel a run of `system` under `motion` needs runs without being
    compiled first (kernel_cache.is_ready)."""
    return kernel_cache.is_ready(_kernel_of(system, GroundMotion.zero() if motion is None else motion))


def unbuilt_kernels(systems) -> list[str]:
    """What building the compiled kernels that runs of `systems` (horizontal motion) need, and
    are not built yet, will cost, one phrase per kernel: a long command's estimate adds it."""
    kernels = dict.fromkeys(_kernel_of(system, GroundMotion.zero()) for system in systems)
    return [f"{_KERNEL_SERVES[k.__name__]} kernel ({kernel_cache.BUILD_ESTIMATE[k.__name__]})" for k in kernels
            if not kernel_cache.is_ready(k)]


#: the longest run (simulated s) that a first run takes on the reference while the kernel it
#: needs is not built. A new checkout of the shared 2 cores ran the 155 s of Kobe JMA N-S (the
#: record and 5 s after it) in 1.5 s wall on the fixed base, 6.6 s on the linear isolator,
#: 9.6–11.3 s on the pendulums, the bowl and the cone, 13.0 s with the statue sliding, all under
#: 200 MB, and the reference runs 150 s of a block rocking throughout (900 impacts) in 4–7 s;
#: the kernels' builds take 35–110 s and up to 1.9 GB there (kernel_cache.BUILD_ESTIMATE)
FIRST_RUN_REFERENCE_S = 200.0


def first_run_reference(system, motion, duration: float) -> str | None:
    """Why one run of the compiled engine should take the SciPy reference instead (the
    same model, tested against the kernel to ~1e-10 rad), or None: its kernel is not
    built yet and the run is short enough that the reference ends before the build would
    (issue 34: a first run that starts at once). ISOROCK_FIRST_RUN=kernel builds it instead."""
    # only a run of a positive duration within the bound: anything else (None, text, a negative
    # or NaN duration) is no reason to swap engines, and the run's own checks refuse it
    if (os.environ.get("ISOROCK_FIRST_RUN", "reference") == "kernel" or isinstance(duration, bool)
            or not isinstance(duration, numbers.Real) or not 0 < duration <= FIRST_RUN_REFERENCE_S):
        return None
    kernel = _kernel_of(system, GroundMotion.zero() if motion is None else motion)
    if kernel_cache.is_ready(kernel):
        return None
    name = kernel.__name__
    return (f"{_KERNEL_SERVES[name]} compiled kernel is not built yet (once per install, {kernel_cache.BUILD_ESTIMATE[name]}): "
            "this run takes the same model on SciPy (analytic-reference), which needs no build; design, sweep "
            "and validate build the kernel, and ISOROCK_FIRST_RUN=kernel builds it now")


ENGINE = EngineSpec(
    name="analytic", label="analytic", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=True, exact_impacts=True,
                              isolators=ISOLATOR_KINDS, two_edges=True),
    presets=PRESETS, ladder=ladder)

REFERENCE_ENGINE = EngineSpec(
    name="analytic-reference", label="analytic (SciPy reference)", settings_type=Settings,
    simulate=simulate_reference,
    # a run takes a second where the compiled engine takes milliseconds: no grid engine
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=True,
                              campaigns=False, isolators=ISOLATOR_KINDS, two_edges=True),
    presets=PRESETS, ladder=ladder)

__all__ = ["ENGINE", "REFERENCE_ENGINE", "Settings", "simulate", "simulate_reference", "ladder", "kernel_ready",
           "first_run_reference", "FIRST_RUN_REFERENCE_S", "unbuilt_kernels"]
