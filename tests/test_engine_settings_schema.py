"""One schema for an engine's settings (issue 35): a --config file's [settings.ENGINE] tables, a
campaign's [[engines]] settings and the command line's --set [ENGINE.]KEY=VALUE are checked by
core.engines.check_settings_table, and --set reaches every setting of every engine, not only the
shorthand options listed by hand. The oracles: each engine's own Settings (its fields and their
defaults), and the same bad value refused in the same words by all three surfaces."""
from __future__ import annotations

import argparse
import math
from dataclasses import MISSING, fields

import pytest

from isorock.validate.tools.campaign.schema import check_campaign
from isorock.analytic.errors import InputError
from isorock.validate.io.config_file import read_config
from isorock.validate.cli.main import build_parser, main
from isorock.validate.cli.options import setting_assignment
from isorock.validate.io.inputs import engine_tables
from isorock.validate.core.engines import ALL_ENGINES, choose, get_engine, table_overrides


def _installed():
    out = []
    for name in ALL_ENGINES:
        try:
            out.append((name, get_engine(name)))
        except ImportError:
            pass
    return out


def _typed(value) -> str:
    """A setting's value as a user types it after --set."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, tuple):
        return "[" + ", ".join(repr(float(x)) for x in value) + "]"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def test_every_setting_of_every_engine_is_reachable_with_its_own_default():
    """--set ENGINE.KEY=DEFAULT, for every field of every installed engine's Settings that has a
    value by default, reads back as that default and makes the engine's default Settings: the
    schema refuses none of the engine's own values, and names no setting the engine lacks."""
    checked = 0
    for name, engine in _installed():
        defaults = engine.settings()
        for f in fields(engine.Settings):
            if f.default is MISSING or f.default is None or isinstance(f.default, float) and not math.isfinite(f.default):
                continue
            table, key, value = setting_assignment(f"{name}.{f.name}={_typed(f.default)}")
            assert (table, key) == (name, f.name)
            assert (tuple(value) if isinstance(value, list) else value) == f.default, (name, f.name, value)
            made = choose(name, {key: value}, strict=True).settings()
            assert getattr(made, f.name) == getattr(defaults, f.name), (name, f.name)
            checked += 1
    assert checked >= 40  # analytic, MuJoCo and PyBullet alone have more than 40 settings


@pytest.mark.parametrize("text, words", [
    ("analytic.rtol=true", "rtol = True: must be a number"),
    ("analytic.rtol=\"1e-8\"", "rtol = '1e-8': must be a number"),
    ("mujoco.integrator=4", "integrator = 4: must be a word"),
    ("mujoco.solref=0.02", "solref = 0.02: must be a list of numbers"),
    ("analytic.rtoll=1e-8", "rtoll: not a setting of analytic"),
    ("rtoll=1e-8", "rtoll: not a setting of any engine"),
    ("warp.timestep=1e-3", "warp: not an engine"),
    ("analytic.rtol=inf", "rtol = inf: must be a finite number"),
    ("analytic.rtol", "must be KEY=VALUE"),
    ("=1", "must be KEY=VALUE"),
])
def test_a_bad_set_is_one_line_naming_it(text, words):
    with pytest.raises(argparse.ArgumentTypeError) as e:
        setting_assignment(text)
    assert words in str(e.value) and "\n" not in str(e.value)


def test_the_three_surfaces_refuse_a_bad_value_in_the_same_words(tmp_path, capsys):
    """rtol = true: the config file, a campaign file and --set each say 'rtol = True: must be a
    number', from the one check."""
    words = "rtol = True: must be a number"
    cfg = tmp_path / "c.toml"
    cfg.write_text("[settings.analytic]\nrtol = true\n")
    with pytest.raises(InputError, match=words):
        read_config(cfg)
    campaign = {"systems": {"slenderness": 4.0, "size": 1.0}, "motions": {"type": "pulse", "pulse": "sine",
                "frequency_ratio": 2.0, "amplitude_ratio": 2.0},
                "engines": [{"name": "analytic", "settings": {"rtol": True}}]}
    with pytest.raises(InputError, match=words):
        check_campaign(campaign)
    assert main(["run", "--engine", "analytic", "--fixed-base", "--set", "analytic.rtol=true"]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


def test_set_reaches_the_engine_it_names_and_only_it():
    a = build_parser("run").parse_args(["run", "--engine", "analytic,mujoco", "--fixed-base", "--timestep", "2e-4",
                                        "--set", "mujoco.integrator=RK4", "--set", "rtol=1e-9",
                                        "--set", "mujoco.solref=[0.01, 1]"])
    tables = engine_tables(a)
    assert tables == {"*": {"timestep": 2e-4, "rtol": 1e-9}, "mujoco": {"integrator": "RK4", "solref": (0.01, 1)}}
    from isorock.validate.io.inputs import load_engines
    got = {label: settings for label, _, settings in load_engines([("analytic", None), ("mujoco", None)], a)}
    assert got["mujoco"].integrator == "RK4" and got["mujoco"].solref == (0.01, 1) and got["mujoco"].timestep == 2e-4
    assert got["analytic"].rtol == 1e-9
    assert get_engine("mujoco").settings().integrator != "RK4"  # the default is not what was asked


def test_set_over_the_config_file_table_by_table(tmp_path):
    """validate: the file's [settings.mujoco] timestep, and --set mujoco.timestep over it."""
    from isorock.validate.tools.report_config import report_config
    cfg = tmp_path / "c.toml"
    cfg.write_text("[settings.mujoco]\ntimestep = 1e-3\nintegrator = \"RK4\"\n")
    a = build_parser("validate").parse_args(["validate", "--config", str(cfg), "--engines", "analytic", "mujoco",
                                             "--set", "mujoco.timestep=5e-4"])
    report = report_config(a)
    assert report.overrides_for("mujoco") == {"timestep": 5e-4, "integrator": "RK4"}
    assert table_overrides(report.overrides, "analytic") == {}


def test_a_set_for_an_engine_not_run_is_refused(capsys):
    assert main(["run", "--engine", "analytic", "--fixed-base", "--set", "mujoco.timestep=1e-3"]) == 2
    err = capsys.readouterr().err
    assert "mujoco" in err and "not run" in err and err.count("\n") == 1
