"""The rocking block as a MuJoCo scene: `scene.xml` + `scene.py` (the model),
`settings.py` (numerical settings, measured), `stepping.py` (stepping with
`mujoco.rollout`), `event_resolved.py` (an opt-in second stepping scheme).
Measurements behind every default: docs/mujoco.md."""
import math
from dataclasses import replace

from isorock.analytic.engine_protocol import Capabilities, EngineSpec, Tuning

from .scene import SCENE_FORMAT, build_model, scene_text
from .settings import Settings, event_resolved_settings, settings_for, settings_for_timestep
from .stepping import run_model, simulate, simulate_many


def ladder(quick: bool):
    """Work-precision ladder: timesteps with the contact parameters measured for each."""
    steps = (2e-3, 1e-3, 2.5e-4) if quick else (2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4)
    return [(f"dt={dt:.3g}", settings_for_timestep(dt)) for dt in steps]


def _direct(settings):
    """(log10 K, log10 D, dmin) of the direct contact form solref = (−K/dt², −D/dt),
    solimp (dmin, dmin, 0.001); positive solref is converted at its critical damping."""
    dt = settings.timestep
    a, b = settings.solref
    if a > 0:  # (timeconst, dampratio): stiffness 1/(tc²·dr²), damping 2/tc
        a, b = -1.0 / (a * a * b * b), -2.0 / a
    return [math.log10(-a * dt * dt), math.log10(-b * dt), settings.solimp[0]]


#: Calibration moves the direct form's stiffness and damping (in units of the step) and
#: the constraint impedance dmin (docs/mujoco.md: the direct form measured best from 1 ms up).
TUNING = Tuning(
    names=("log10 stiffness·dt²", "log10 damping·dt", "solimp dmin"),
    bounds=((-3.0, 0.5), (-2.0, 1.0), (0.5, 0.99)),
    start=_direct,
    apply=lambda s, x: replace(s, solref=(-(10 ** x[0]) / s.timestep ** 2, -(10 ** x[1]) / s.timestep),
                               solimp=(x[2], x[2], 0.001)))


ENGINE = EngineSpec(
    name="mujoco", label="MuJoCo", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={
        "default": Settings,
        # Newton, MuJoCo's own solver and the default's: named so that it reads beside cg
        "newton": lambda: Settings(solver="Newton"),
        # conjugate gradient, MuJoCo's other solver for soft contacts: cheaper iterations, more of them
        "cg": lambda: Settings(solver="CG"),
        # the elliptic cone, the default's: named so that it reads beside pyramidal
        "elliptic": lambda: Settings(cone="elliptic"),
        # the pyramidal cone: cheaper per step, lets the pivot creep 2.3× as far (docs/mujoco.md)
        "pyramidal": lambda: Settings(cone="pyramidal"),
        # the cheapest step whose β stays within ~1% on the paper's block (docs/mujoco.md, bench ladder)
        "fast": lambda: settings_for_timestep(2e-3),
        # soft contact tied to the step, time constant 4·dt, at 1e-4 s: the ladder's most accurate rung
        "fine": lambda: settings_for_timestep(1e-4),
        # model.md's feasibility recipe: time constant at MuJoCo's floor 2·dt, impedance dmin 0.99
        # (the pivot contact flickers at it, docs/mujoco.md; kept to measure it over the atlas)
        "model-md": lambda: Settings(solref=(2 * Settings.timestep, 2.0), solimp=(0.99, 0.999, 0.001)),
        # coarse steps in flight, fine ones around each impact: long records, not free rocking
        "event-resolved": event_resolved_settings,
        # a small sphere in each bottom corner instead of box–box: cheaper collision, no better per cost
        "corners": lambda: Settings(contact="corners"),
    },
    ladder=ladder, tuning=TUNING, simulate_many=simulate_many)

__all__ = ["ENGINE", "Settings", "simulate", "simulate_many", "run_model", "scene_text", "build_model", "settings_for",
           "settings_for_timestep", "event_resolved_settings"]
