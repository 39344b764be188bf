"""The block on its base in Drake (pydrake): the third contact engine, an independent
point-contact formulation for free rocking, pulses and single records, not campaigns of
thousands of runs (a run costs ~100× MuJoCo's). It carries the linear isolator, the friction
pendulum and the ball in a bowl (a held puck's contact: docs/drake.md), on one component and
under a pair. `scene.py` holds the SDFormat scene,
the settings and presets, and the stepping; `statue.py` a statue's own shape (its hull's
vertices on a free body) in the block's place; measurements in docs/drake.md and docs/statues.md."""
import math
from dataclasses import replace

from ..analytic.engine_protocol import Capabilities, EngineSpec, Preset, Tuning

from .scene import (ISOLATORS, PRESETS, SCENE_FORMAT, TRANSVERSE, TWO_EDGES, Settings, check_system, preset, scene_text,
                    settings_for, settings_for_timestep, simulate, sphere_geometry_beta,
                    sphere_geometry_first_impact_time)
from . import mesh_scene  # the rock's hull as a free body; after .scene, whose import says how to install pydrake


def ladder(quick: bool):
    """Work-precision ladder: the continuous plant's accuracy, then the discrete SAP steps."""
    accuracies = (1e-2, 1e-3) if quick else (1e-2, 1e-3, 1e-4)
    return [(f"accuracy={a:g}", Settings(accuracy=a)) for a in accuracies]


#: Calibration moves the point contact's stiffness (3e8–5e10 N/m: the paper block's pivot
#: sinks 0.06 mm to 0.4 µm; stiffer runs cost more and more of Radau's steps) and its
#: Hunt–Crossley dissipation (30–2000 s/m: the force is k·x·(1 + d·ẋ), so d·v ≫ 1 is an
#: inelastic impact, and the late impacts land at v ≈ 0.1 m/s; the study saw hops at
#: d ≤ 10, and such runs cost minutes each in the calibration's coarse design).
TUNING = Tuning(
    names=("log10 stiffness (N/m)", "log10 dissipation (s/m)"),
    bounds=((8.5, 10.7), (1.5, 3.3)),
    start=lambda s: [math.log10(s.stiffness), math.log10(s.dissipation)],
    apply=lambda s, x: replace(s, stiffness=10 ** x[0], dissipation=10 ** x[1]))


#: Why each preset is there (measured in docs/drake.md with docs/scripts/drake_presets.py;
#: worst β error over the first 4 impacts, fixed / μ = 1 isolated): what `isorock presets` shows.
PRESET_REASONS = {
    "continuous": "the default: continuous plant, Radau3 at accuracy 1e-4; β within 0.05% / 0.08%",
    "sap": "discrete SAP, dt 2e-4 s, relaxation time 5 ms (shorter makes the block hop); 0.19% / 0.44%, the slowest",
    "tamsi": "discrete TAMSI, dt 2e-4 s: 0.13% / 0.33%, the fastest (deprecated by Drake)",
    "hydroelastic": "the block a compliant box on a rigid plate (discrete SAP): β 12% / 22% high, for comparison only",
}


def _simulate_body(vertices, com, inertia, mass, acceleration, dt, *, duration=None, friction=None):
    contact = {} if friction is None else {"friction": friction}
    return mesh_scene.simulate(vertices, com, inertia, mass, acceleration, dt, duration=duration, **contact)


ENGINE = EngineSpec(
    name="drake", label="Drake", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              campaigns=False, two_edges=TWO_EDGES, transverse=TRANSVERSE,
                              isolators=ISOLATORS, transverse_isolators=ISOLATORS),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT, simulate_body=_simulate_body,
    presets={"default": Preset("the continuous plant's, as \"continuous\"", Settings),
             **{name: Preset(PRESET_REASONS[name], lambda s=s: s) for name, s in PRESETS.items()}},
    ladder=ladder, tuning=TUNING,
    # corner spheres the block can hold, and μ_k < μ_s on the continuous plant only
    check_system=check_system)

__all__ = ["ENGINE", "Settings", "PRESETS", "preset", "simulate", "scene_text", "settings_for",
           "settings_for_timestep", "sphere_geometry_beta", "sphere_geometry_first_impact_time"]
