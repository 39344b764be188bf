"""The rocking block as a MuJoCo scene: `scene.xml` + `scene.py` (the model),
`settings.py` (numerical settings, measured), `stepping.py` (stepping with
`mujoco.rollout`), `event_resolved.py` (an opt-in second stepping scheme).
Measurements behind every default: docs/mujoco.md."""
from isorock.analytic.engine_protocol import Capabilities, EngineSpec

from .scene import SCENE_FORMAT, build_model, scene_text
from .settings import Settings, event_resolved_settings, settings_for, settings_for_timestep
from .stepping import run_model, simulate


def ladder(quick: bool):
    """Work-precision ladder: timesteps with the contact parameters measured for each."""
    steps = (2e-3, 1e-3, 2.5e-4) if quick else (2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4)
    return [(f"dt={dt:.3g}", settings_for_timestep(dt)) for dt in steps]


ENGINE = EngineSpec(
    name="mujoco", label="MuJoCo", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={
        "default": Settings,
        # the cheapest step whose β stays within ~1% (docs/mujoco.md, bench ladder)
        "fast": lambda: settings_for_timestep(2e-3),
        "event-resolved": event_resolved_settings,
        "corners": lambda: Settings(contact="corners"),
        "pyramidal": lambda: Settings(cone="pyramidal"),
    },
    ladder=ladder)

__all__ = ["ENGINE", "Settings", "simulate", "run_model", "scene_text", "build_model", "settings_for",
           "settings_for_timestep", "event_resolved_settings"]
