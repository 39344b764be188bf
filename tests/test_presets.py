"""`isorock presets [ENGINE] [--json]` (issue 25): every engine's presets with their
one-line reasons and settings, read from the engine packages themselves."""
from __future__ import annotations

import json
from dataclasses import asdict

import pytest

from isorock.analytic.engine_protocol import Preset
from isorock.validate.cli.main import main
from isorock.validate.core.engines import DISTINCT_ENGINES, get_engine


def _loadable():
    out = []
    for name in DISTINCT_ENGINES:
        try:
            out.append(get_engine(name))
        except ImportError:
            continue
    return out


@pytest.mark.parametrize("engine", _loadable(), ids=lambda e: e.name)
def test_every_preset_carries_a_one_line_reason(engine):
    assert "default" in engine.spec.presets
    for name, preset in engine.spec.presets.items():
        assert isinstance(preset, Preset), f"{engine.name}:{name} has no reason (use Preset(reason, make))"
        assert preset.reason.strip() and "\n" not in preset.reason, f"{engine.name}:{name}"
        assert isinstance(preset(), engine.Settings)


def test_json_lists_every_preset_with_the_settings_the_engine_runs(capsys):
    assert main(["presets", "--json"]) == 0
    table = json.loads(capsys.readouterr().out)
    for engine in _loadable():
        listed = table[engine.name]
        assert list(listed) == list(engine.spec.presets)
        for name, entry in listed.items():
            # the oracle: the settings the registry hands a run of ENGINE:PRESET
            assert entry["settings"] == json.loads(json.dumps(asdict(engine.preset(name))))
            assert entry["reason"] == engine.spec.presets[name].reason
    assert "analytic-fast" not in table  # a former name is not an engine of its own
    # what differs from the default: known by construction of these presets
    assert table["analytic"]["conservative"]["differs"] == ["overturn"]
    assert table["analytic"]["conservative"]["settings"]["overturn"] == "alpha"
    assert table["mujoco"]["pyramidal"]["differs"] == ["cone"]
    assert table["bullet"]["substeps-30"]["differs"] == ["substeps"]
    assert table["mujoco"]["default"]["differs"] == []


def test_text_names_each_preset_its_reason_and_what_differs(capsys):
    assert main(["presets", "mujoco"]) == 0
    out = capsys.readouterr().out
    engine = get_engine("mujoco")
    for name, preset in engine.spec.presets.items():
        assert f"  {name} " in out and preset.reason in out
    assert "as default, but cone=pyramidal" in out
    assert "bullet" not in out.split("\n")[0]


def test_a_former_name_lists_the_engine_it_names(capsys):
    assert main(["presets", "analytic-fast", "--json"]) == 0
    assert list(json.loads(capsys.readouterr().out)) == ["analytic"]


def test_an_unknown_engine_is_one_line_and_exit_2(capsys):
    assert main(["presets", "havok"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "havok" in err[0] and "mujoco" in err[0]
