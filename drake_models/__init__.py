"""The block on its base in Drake (pydrake): the third contact engine, an independent
point-contact formulation for free rocking, pulses and single records, not campaigns of
thousands of runs (a run costs ~100× MuJoCo's). `scene.py` holds the SDFormat scene,
the settings and presets, and the stepping; measurements in docs/drake.md."""
import math
from dataclasses import replace

from isorock.analytic.engine_protocol import Capabilities, EngineSpec, Tuning

from .scene import (PRESETS, SCENE_FORMAT, Settings, preset, scene_text, settings_for, settings_for_timestep,
                    simulate, sphere_geometry_beta, sphere_geometry_first_impact_time)


def ladder(quick: bool):
    """Work-precision ladder: the continuous plant's accuracy, then the discrete SAP steps."""
    accuracies = (1e-2, 1e-3) if quick else (1e-2, 1e-3, 1e-4)
    return [(f"accuracy={a:g}", Settings(accuracy=a)) for a in accuracies]


#: Calibration moves the point contact's stiffness and Hunt–Crossley dissipation.
TUNING = Tuning(
    names=("log10 stiffness (N/m)", "log10 dissipation (s/m)"),
    bounds=((7.0, 11.0), (0.0, 3.0)),
    start=lambda s: [math.log10(s.stiffness), math.log10(s.dissipation)],
    apply=lambda s, x: replace(s, stiffness=10 ** x[0], dissipation=10 ** x[1]))


ENGINE = EngineSpec(
    name="drake", label="Drake", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              campaigns=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={"default": Settings, **{name: (lambda s=s: s) for name, s in PRESETS.items()}},
    ladder=ladder, tuning=TUNING)

__all__ = ["ENGINE", "Settings", "PRESETS", "preset", "simulate", "scene_text", "settings_for",
           "settings_for_timestep", "sphere_geometry_beta", "sphere_geometry_first_impact_time"]
