"""The narrow engine protocol (issue 35): an EngineSpec is what every command relies on (name,
label, Settings, simulate, capabilities, presets, the settings that follow the system, what it
refuses, its limits); what a single tool uses is a facet that tool declares (engine_protocol.
declare_facet), and an engine offers it under that name. The oracle: the tools' own
declarations, imported here, against every built-in engine's facets."""
import dataclasses
import importlib

import pytest

from isorock.analytic.engine_protocol import FACETS, Capabilities, EngineSpec, declare_facet
from isorock.validate.core.engines import ENGINE_NAMES, get_engine

#: the modules that declare the facets they use
TOOLS = ("isorock.validate.core.engines", "isorock.validate.tools.bench", "isorock.validate.tools.calibrate",
         "isorock.validate.tools.view", "isorock.validate.tools.experiments.study")
PROTOCOL = ("name", "label", "settings_type", "simulate", "capabilities", "presets", "settings_for", "check_system",
            "tolerances", "facets")


def _declared():
    for module in TOOLS:
        importlib.import_module(module)
    return dict(FACETS)


def test_the_protocol_is_narrow_and_the_tools_parts_are_facets():
    assert tuple(f.name for f in dataclasses.fields(EngineSpec)) == PROTOCOL
    spec = EngineSpec("x", "X", int, lambda *a, **k: None, ladder=lambda quick: [], step_cost=None,
                      facets={"tuning": "t"})
    assert dict(spec.facets) == {"ladder": spec.facets["ladder"], "tuning": "t"}  # None: not offered
    assert not hasattr(spec, "ladder") and not hasattr(spec, "tuning")
    with pytest.raises(TypeError):
        spec.facets["scene_text"] = None  # read-only, as the spec is frozen
    assert dataclasses.replace(spec, label="Y").facets == spec.facets


@pytest.mark.parametrize("name", [n for n in ENGINE_NAMES if n != "analytic-fast"])
def test_every_engine_offers_only_facets_a_tool_declared(name):
    try:
        spec = get_engine(name).spec
    except Exception as e:  # an optional engine not installed here
        pytest.skip(f"{name}: {e}")
    declared = _declared()
    assert set(spec.facets) <= set(declared), set(spec.facets) - set(declared)
    assert isinstance(spec.capabilities, Capabilities)


def test_every_declared_facet_is_offered_by_some_engine_and_named_in_the_plugin_guide():
    declared = _declared()
    offered = set()
    for name in ENGINE_NAMES:
        try:
            offered |= set(get_engine(name).spec.facets)
        except Exception:  # noqa: BLE001 - an optional engine not installed here
            continue
    assert set(declared) <= offered, set(declared) - offered
    import os
    guide = open(os.path.join(os.path.dirname(__file__), "..", "docs", "plugins.md"), encoding="utf-8").read()
    for facet in declared:
        assert f"`{facet}`" in guide, facet


def test_a_facet_declared_twice_with_another_meaning_is_refused():
    first = declare_facet("test_only_facet", "this test", "a value")
    assert declare_facet("test_only_facet", "this test", "a value") is first
    with pytest.raises(ValueError, match="declared twice"):
        declare_facet("test_only_facet", "another tool", "a value")
    del FACETS["test_only_facet"]
