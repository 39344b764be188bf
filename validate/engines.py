"""The engine registry: every command, report and test loops over these names.

An engine is a module exposing
    simulate(system, motion, *, settings=None, duration=None, theta0=0.0,
             impact_threshold=0.01, progress=None) -> Trajectory
    Settings            a frozen dataclass of its own numerical settings
and optionally `scene_text(system, settings) -> str` (the model file a user can open)
with `SCENE_SUFFIX`, and `settings_for(**overrides) -> Settings` where some settings
must follow others (MuJoCo's contact time constant follows its timestep). Modules are imported lazily so `isorock beta` never loads a
physics engine.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass, fields, replace
from types import ModuleType

from isorock.analytic.errors import InputError

ENGINE_MODULES = {
    # the analytic model, compiled (analytic.fast); its SciPy reference path, which the
    # compiled kernel is tested against, is "analytic-reference"
    "analytic": "isorock.analytic.fast_engine",
    "analytic-reference": "isorock.analytic.engine",
    "mujoco": "isorock.mujoco_models.scene",
    "bullet": "isorock.bullet_models.scene",
    # the former name of the compiled engine, kept so that nothing breaks
    "analytic-fast": "isorock.analytic.fast_engine",
}
#: The engines every report and comparison loops over: the reference and the contact engines.
ENGINE_NAMES = ("analytic", "mujoco", "bullet")
CONTACT_ENGINES = ("mujoco", "bullet")
#: Every engine that can be asked for by name (bench and stress run them all).
ALL_ENGINES = tuple(ENGINE_MODULES)


@dataclass(frozen=True)
class Engine:
    name: str
    module: ModuleType

    @property
    def Settings(self):
        return self.module.Settings

    def simulate(self, system, motion, **kwargs):
        return self.module.simulate(system, motion, **kwargs)

    def settings(self, **overrides):
        """The engine's default settings with `overrides` applied; an override the
        engine does not have is an InputError naming it."""
        known = {f.name for f in fields(self.Settings)}
        unknown = sorted(k for k in overrides if k not in known)
        if unknown:
            raise InputError(f"{', '.join(unknown)}: not a setting of engine {self.name!r} "
                             f"(its settings: {', '.join(sorted(known))})")
        tie = getattr(self.module, "settings_for", None)
        return tie(**overrides) if tie else replace(self.Settings(), **overrides)

    @property
    def has_scene(self) -> bool:
        return hasattr(self.module, "scene_text")


def get_engine(name: str) -> Engine:
    if name not in ENGINE_MODULES:
        raise InputError(f"engine = {name!r}: must be one of {', '.join(ALL_ENGINES)}")
    return Engine(name, importlib.import_module(ENGINE_MODULES[name]))
