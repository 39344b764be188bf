"""The block on its base in MJX, MuJoCo's JAX port (issue 37): the MuJoCo engine's own scene
and settings (mujoco_models), stepped by `mjx.step` in float64 (stepping.py), one run or a
batch of runs of one scene at once (`simulate_batch`, jax.vmap). An optional engine:
`pip install 'isorock[mjx]'` (mujoco-mjx, with JAX); on a CPU here, on a GPU where JAX finds
one (never required). Measured against MuJoCo's C engine and the exact model: docs/mjx.md."""
from isorock.analytic.engine_protocol import Capabilities, EngineSpec, Preset
from isorock.mujoco_models.scene import SCENE_FORMAT, check_representable, scene_text
from isorock.mujoco_models.settings import Settings, settings_for

from .stepping import ISOLATORS, simulate, simulate_batch

ENGINE = EngineSpec(
    name="mjx", label="MJX (MuJoCo on JAX)", settings_type=Settings, simulate=simulate,
    # a compiled chunk costs seconds per scene layout, and a single run on a CPU ~17× MuJoCo C's:
    # no campaigns (bench, stress and sweep run it only when named)
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              campaigns=False, isolators=ISOLATORS, kinetic_friction=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={"default": Preset("MuJoCo's default scene and settings, stepped throughout by mjx.step in float64 "
                               "(MuJoCo's rest phase and coarse steps are its C engine's, not MJX's)", Settings)},
    check_system=lambda system, settings: check_representable(system))

__all__ = ["ENGINE", "Settings", "simulate", "simulate_batch"]
