"""The engine registry's names: which engines there are (built in, and those installed packages
register), their former names, the reference. Light (the standard library only), so that the
command line's parser lists the engines without loading one (`isorock beta`, `isorock --help`);
the engines themselves are loaded by validate.core.engines (get_engine).
"""
from __future__ import annotations

import importlib.metadata


ENGINE_MODULES = {
    # the analytic model, compiled (analytic.fast); its SciPy reference path, which the
    # compiled kernel is tested against, is "analytic-reference"
    "analytic": "isorock.analytic.engines:ENGINE",
    "analytic-reference": "isorock.analytic.engines:REFERENCE_ENGINE",
    "mujoco": "isorock.mujoco_models",
    "bullet": "isorock.bullet_models",
    # Drake's point contact: an independent, slower formulation, asked for by name (docs/drake.md)
    "drake": "isorock.drake_models",
    # MuJoCo's JAX port on MuJoCo's own scene (optional: the mjx extra; docs/mjx.md)
    "mjx": "isorock.mujoco_models.mjx:ENGINE",
    # MuJoCo Warp, MuJoCo's port to NVIDIA Warp, on MuJoCo's own scene (optional: the mjwarp extra; docs/mjwarp.md)
    "mjwarp": "isorock.mujoco_models.mjwarp:ENGINE",
    # DART's contact and constraint solver (optional: the dart extra; docs/dart.md)
    "dart": "isorock.dart_models:ENGINE",
    # the former name of the compiled engine, kept so that nothing breaks
    "analytic-fast": "isorock.analytic.engines:ENGINE",
}
#: The entry-point group an installed package registers an engine under (issue 37): in its
#: pyproject.toml, `[project.entry-points."isorock.engines"] NAME = "package.module:ENGINE"`,
#: ENGINE an EngineSpec whose `name` is NAME (docs/plugins.md; examples/isorock-engine-example).
PLUGIN_GROUP = "isorock.engines"


def _plugins() -> tuple[dict, dict]:
    """(name → "module:ATTRIBUTE", name → why it is not registered) of the engines installed
    packages declare. A name a built-in engine has is never taken (said, not silently)."""
    found, refused = {}, {}
    for ep in importlib.metadata.entry_points(group=PLUGIN_GROUP):
        if ep.name in ENGINE_MODULES:
            refused[ep.name] = (f"{ep.value} (from {ep.dist.name if ep.dist else 'a package'}) names the built-in "
                                f"engine {ep.name!r}: not registered")
        elif ep.name in found:
            refused[ep.name] = f"declared twice ({found[ep.name]}, {ep.value}): not registered"
        elif not ep.name or ":" in ep.name or "," in ep.name or " " in ep.name:
            refused[ep.name] = f"{ep.value}: an engine's name has no ':', ',' or space: not registered"
        else:
            found[ep.name] = ep.value
    for name in refused:
        found.pop(name, None)
    return found, refused


#: the engines installed packages register (PLUGIN_GROUP), and those refused with the reason
PLUGINS, PLUGINS_REFUSED = _plugins()
ENGINE_MODULES.update(PLUGINS)
#: The engine every other is compared with.
REFERENCE = "analytic"
#: The engines every report and comparison loops over: the reference and the contact engines.
ENGINE_NAMES = ("analytic", "mujoco", "bullet")
CONTACT_ENGINES = tuple(n for n in ENGINE_NAMES if n != REFERENCE)
#: Every engine that can be asked for by name, former names included.
ALL_ENGINES = tuple(ENGINE_MODULES)
#: Former names: each runs the engine it names, so no tool runs it as an engine of its own.
ALIASES = {"analytic-fast": "analytic"}
#: Every engine once (bench and stress run them all; `isorock presets` lists them).
DISTINCT_ENGINES = tuple(n for n in ENGINE_MODULES if n not in ALIASES)


def canonical(label: str) -> str:
    """ENGINE[:PRESET] with a former engine name replaced by the engine's own."""
    name, sep, preset = str(label).partition(":")
    return ALIASES.get(name, name) + sep + preset
