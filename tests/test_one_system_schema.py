"""One schema for the system (issue 35): `validate`'s options and a --config file's [system] table
name the same keys, every isolator kind among them (before, validate and its config file could
describe only the linear isolator), and each surface makes the same System. The oracles: the
System built directly from the model's own classes, and the other surfaces' Systems."""
from __future__ import annotations

import json

import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.system import (PAPER_BLOCK, BallInBowl, BallInCone, BilinearIsolator, DoubleFrictionPendulum,
                                     FrictionPendulum, System)
from isorock.validate.io.config_file import SystemTable, read_config
from isorock.validate.cli.main import build_parser, main
from isorock.validate.io.inputs import SYSTEM_KEYS, system_from_args, system_from_options

BLOCK = dict(height=1.2, width=0.3, mass=250.0, base_mass=500.0)
FP_FILE = ("[system]\nheight = 1.2\nwidth = 0.3\nmass = 250\nbase_mass = 500\nisolator = \"friction-pendulum\"\n"
           "radius = 1.0\nfriction_coefficient = 0.05\n")
FP_OPTIONS = ["--height", "1.2", "--width", "0.3", "--mass", "250", "--base-mass", "500",
              "--isolator", "friction-pendulum", "--radius", "1.0", "--friction-coefficient", "0.05"]


def test_the_file_and_the_options_name_the_same_keys():
    """Every key of the [system] table is a validate option and every system option is a key:
    a key added to one and not the other fails here."""
    options = set(vars(build_parser("validate").parse_args(["validate"])))
    assert set(SystemTable.model_fields) == set(SYSTEM_KEYS)
    assert set(SYSTEM_KEYS) <= options


def test_the_files_other_keys_are_validate_options_too():
    """The motion and run keys of a --config file (motions, their units and format, the scaling, the
    duration, quick) are validate's options by the same names (`motions` lists what --motion gives
    one at a time), and its tables are the system, the statue and the engines' settings (--set): a key
    added to the file and not to the options, or the reverse, fails here."""
    from isorock.validate.io.config_file import ConfigFile
    options = set(vars(build_parser("validate").parse_args(["validate"])))
    tables = {"system": "height", "statue": "statue", "settings": "set_settings", "motions": "motion"}
    for key in ConfigFile.model_fields:
        assert tables.get(key, key) in options, key
    assert {"motion", "units", "format", "pga", "pgv", "duration"} <= {tables.get(k, k) for k in ConfigFile.model_fields}


def test_a_friction_pendulum_is_the_same_system_from_the_file_the_options_and_run(tmp_path):
    direct = System.with_isolator(**BLOCK, isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.05))
    cfg = tmp_path / "fp.toml"
    cfg.write_text(FP_FILE)
    empty = build_parser("validate").parse_args(["validate"])
    from_file = system_from_options(empty, read_config(cfg)["system"])
    from_options = system_from_options(build_parser("validate").parse_args(["validate", *FP_OPTIONS]))
    from_run = system_from_args(build_parser("run").parse_args(["run", *FP_OPTIONS]))
    assert from_file == direct and from_options == direct and from_run == direct


def test_an_option_wins_over_the_file_key_by_key(tmp_path):
    """--friction-coefficient over the file's, the file's isolator and radius kept."""
    cfg = tmp_path / "fp.toml"
    cfg.write_text(FP_FILE)
    a = build_parser("validate").parse_args(["validate", "--friction-coefficient", "0.08"])
    s = system_from_options(a, read_config(cfg)["system"])
    assert s == System.with_isolator(**BLOCK, isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.08))


def test_a_bilinear_bearing_from_the_file_takes_its_stiffness_from_the_period(tmp_path):
    cfg = tmp_path / "b.toml"
    cfg.write_text("[system]\nheight = 1.2\nwidth = 0.3\nmass = 250\nbase_mass = 500\nisolator = \"bilinear\"\n"
                   "period = 2.0\ndamping_ratio = 0.1\npost_yield_ratio = 0.2\nyield_displacement = 0.01\n")
    s = system_from_options(build_parser("validate").parse_args(["validate"]), read_config(cfg)["system"])
    linear = System.isolated(**BLOCK, period=2.0, damping_ratio=0.1)
    assert s.isolator == BilinearIsolator(stiffness=linear.stiffness, damping=linear.damping, post_yield_ratio=0.2,
                                          yield_displacement=0.01)


@pytest.mark.parametrize("text, key", [
    (FP_FILE.replace("radius = 1.0\n", ""), "radius"),                           # a key its kind needs
    (FP_FILE + "slope = 0.1\n", "slope"),                                        # a key of another kind
    (FP_FILE.replace('"friction-pendulum"', '"pendulum"'), "system.isolator"),    # not a kind
    (FP_FILE.replace("radius = 1.0", "radius = -1.0"), "system.radius"),
    (FP_FILE + "period = 2.0\ndamping_ratio = 0.1\n", "period"),                 # its period is its radius's
])
def test_a_bad_isolator_in_the_file_is_one_line_naming_the_key(tmp_path, capsys, text, key):
    cfg = tmp_path / "c.toml"
    cfg.write_text(text)
    out = tmp_path / "rep"
    assert main(["validate", "--config", str(cfg), "--quick", "--quiet", "--engines", "analytic",
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and key in err and "Traceback" not in err, err
    assert not out.exists()


def test_validate_judges_on_the_friction_pendulum_the_file_describes(tmp_path):
    cfg = tmp_path / "fp.toml"
    cfg.write_text(FP_FILE)
    out = tmp_path / "rep"
    assert main(["validate", "--config", str(cfg), "--quick", "--quiet", "--engines", "analytic",
                 "--out", str(out)]) == 0
    report = (out / "report.md").read_text()
    assert "friction-pendulum isolator (radius 1, friction coefficient 0.05" in report
    assert "T 2.01 s" not in report  # no linear period it does not have
    metrics = json.loads((out / "metrics.json").read_text())
    assert "friction-pendulum" in json.dumps(metrics)


def test_an_engines_contact_friction_is_not_the_statues_sliding_friction(capsys):
    """`run --friction` is MuJoCo's and PyBullet's block–base contact coefficient (an engine
    setting), which a statue's hull takes as the block does; only --statue-friction (the sliding
    model's μ_s, which takes the block alone) is refused with a statue. `design --friction` is
    the statue's own μ_s there, and is refused with a mesh."""
    assert main(["run", "--engine", "mujoco", "--statue-example", "bust", "--mass", "80", "--fixed-base",
                 "--motion", "sine:amp=0.5,freq=2", "--friction", "0.9", "--duration", "0.5", "--json", "-"]) == 0
    out = capsys.readouterr().out
    assert json.loads(out)["settings"]["friction"] == 0.9  # one engine: its run's JSON
    assert main(["run", "--engine", "analytic", "--statue-example", "bust", "--mass", "80", "--fixed-base",
                 "--statue-friction", "0.5"]) == 2
    assert "--statue-friction" in capsys.readouterr().err
    assert main(["design", "--statue-example", "bust", "--mass", "80", "--friction", "0.5", "--quiet"]) == 2
    assert "--friction" in capsys.readouterr().err


# --- one declaration (validate/io/keys.py): each key's surfaces made from it ------------------------------------

_BLOCK_WORDS = ["--height", "1.2", "--width", "0.3", "--mass", "250", "--base-mass", "500"]
_LINEAR = System.isolated(**BLOCK, period=2.0, damping_ratio=0.1)

#: (the options, written out here, not from the declaration; the System the model's own classes build)
_CASES = {
    "period": (["--period", "2", "--damping-ratio", "0.1"], _LINEAR),
    "stiffness": (["--stiffness", "3000", "--dashpot", "150"],
                  System.from_stiffness(**BLOCK, stiffness=3000.0, damping=150.0)),
    "fixed": (["--fixed-base"], System.fixed(**BLOCK)),
    "sliding": (["--period", "2", "--damping-ratio", "0.1", "--statue-friction", "0.6", "--kinetic-friction", "0.5"],
                _LINEAR.with_friction(0.6, 0.5)),
    "friction-pendulum": (["--isolator", "friction-pendulum", "--radius", "1.5", "--friction-coefficient", "0.04",
                           "--friction-max", "0.08", "--friction-rate", "20"],
                          System.with_isolator(**BLOCK, isolator=FrictionPendulum(
                              radius=1.5, friction_coefficient=0.04, friction_max=0.08, friction_rate=20.0))),
    "bilinear": (["--isolator", "bilinear", "--stiffness", "3000", "--dashpot", "150", "--post-yield-ratio", "0.2",
                  "--yield-displacement", "0.01"],
                 System.with_isolator(**BLOCK, isolator=BilinearIsolator(
                     stiffness=3000.0, damping=150.0, post_yield_ratio=0.2, yield_displacement=0.01))),
    "ball-in-cone": (["--isolator", "ball-in-cone", "--slope", "0.05", "--rolling-resistance", "0.01"],
                     System.with_isolator(**BLOCK, isolator=BallInCone(slope=0.05, rolling_resistance=0.01))),
    "ball-in-bowl": (["--isolator", "ball-in-bowl", "--radius", "2", "--rolling-resistance", "0.02"],
                     System.with_isolator(**BLOCK, isolator=BallInBowl(radius=2.0, rolling_resistance=0.02))),
    "double-friction-pendulum": (["--isolator", "double-friction-pendulum", "--radius", "1", "--friction-coefficient",
                                  "0.03", "--radius-2", "2", "--friction-coefficient-2", "0.06"],
                                 System.with_isolator(**BLOCK, isolator=DoubleFrictionPendulum(
                                     radius_1=1.0, friction_1=0.03, radius_2=2.0, friction_2=0.06))),
}


def _as_toml(words: list[str]) -> str:
    """The [system] table the options spell: --base-mass 500 → base_mass = 500, --fixed-base → true."""
    lines, i = ["[system]"], 0
    while i < len(words):
        key = words[i].removeprefix("--").replace("-", "_")
        if i + 1 == len(words) or words[i + 1].startswith("--"):
            lines.append(f"{key} = true")
            i += 1
            continue
        value = words[i + 1]
        lines.append(f"{key} = {value if value[0].isdigit() else json.dumps(value)}")  # a number, or a string
        i += 2
    return "\n".join(lines) + "\n"


def test_every_declared_key_is_exercised_below():
    """A key added to the declaration (io/keys.py) is an option and a [system] key at once; it
    fails here until a case below shows it making the System the model's own classes make."""
    used = {w.removeprefix("--").replace("-", "_") for words, _ in _CASES.values() for w in [*_BLOCK_WORDS, *words]
            if w.startswith("--")}
    assert used == set(SYSTEM_KEYS) == set(SystemTable.model_fields)


@pytest.mark.parametrize("case", list(_CASES))
def test_each_key_from_an_option_and_from_the_file_makes_the_models_system(tmp_path, case):
    """The oracle: the System built directly with analytic.system's classes. Each key's option
    (run's and validate's parsers) and its [system] key in a --config file make that System."""
    words, direct = _CASES[case]
    assert system_from_args(build_parser("run").parse_args(["run", *_BLOCK_WORDS, *words])) == direct
    a = build_parser("validate").parse_args(["validate", *_BLOCK_WORDS, *words])
    assert system_from_options(a) == direct
    cfg = tmp_path / "system.toml"
    cfg.write_text(_as_toml([*_BLOCK_WORDS, *words]))
    assert system_from_options(build_parser("validate").parse_args(["validate"]), read_config(cfg)["system"]) == direct


#: a key whose least value is another key's, not 0: μ_max is at least μ_f (the model says so, naming both)
_BOUNDED_BY_ANOTHER = {"friction_max"}


@pytest.mark.parametrize("case", list(_CASES))
def test_a_file_takes_a_zero_where_the_model_does(tmp_path, case):
    """The oracle: the model's own checks, reached through the options (which take any number). A
    [system] key declared positive refuses 0 in the file, one declared non-negative takes it, as the
    System itself does: a kind declared wrong in io/keys.py fails here."""
    words = [*_BLOCK_WORDS, *_CASES[case][0]]
    for i, word in enumerate(words[:-1]):
        if not (word.startswith("--") and words[i + 1][0].isdigit()):
            continue
        zeroed = [*words[:i + 1], "0", *words[i + 2:]]
        try:
            system_from_args(build_parser("run").parse_args(["run", *zeroed]))
            model_takes = True
        except InputError:
            model_takes = False
        cfg = tmp_path / "zero.toml"
        cfg.write_text(_as_toml(zeroed))
        try:
            read_config(cfg)
            file_takes = True
        except InputError:
            file_takes = False
        key = word.removeprefix("--").replace("-", "_")
        assert file_takes == model_takes or (key in _BOUNDED_BY_ANOTHER and file_takes), (key, file_takes)


def test_damping_is_damping_ratio_and_a_units_help_states_it():
    from isorock.validate.io import keys
    a = build_parser("run").parse_args(["run", "--period", "2", "--damping", "0.1"])
    assert system_from_args(a) == System.isolated(**PAPER_BLOCK, period=2.0, damping_ratio=0.1)
    run = build_parser("run")._subparsers._group_actions[0].choices["run"]
    assert "--damping-ratio DAMPING_RATIO, --damping DAMPING_RATIO" in run.format_help()  # named, not an abbreviation
    for key in [*keys.SYSTEM.values(), *keys.ISOLATOR.values(), *keys.MOTION.values()]:
        assert key.unit is None or f", {key.unit}" in key.help, key.name


def test_a_records_units_and_formats_are_the_models_on_every_surface(tmp_path):
    """The oracle: analytic.motion's own tables of units and formats. Each is taken by the options
    (run, validate), a --config file and a campaign file; a word that is none of them by none."""
    from isorock.analytic.motion import FORMATS, UNITS
    from isorock.validate.tools.campaign.schema import check_campaign

    def campaign(units):
        check_campaign({"systems": {"height": 1.0}, "engines": [{"name": "analytic"}],
                        "motions": {"type": "records", "units": units}})

    def config(**keys):
        cfg = tmp_path / "m.toml"
        cfg.write_text("".join(f'{k} = "{v}"\n' for k, v in keys.items()))
        return read_config(cfg)

    for units in UNITS:
        for command in ("run", "validate"):
            assert build_parser(command).parse_args([command, "--units", units]).units == units
        assert config(units=units)["units"] == units
        campaign(units)
    for fmt in FORMATS:
        for command in ("run", "validate"):
            assert build_parser(command).parse_args([command, "--format", fmt]).format == fmt
        assert config(format=fmt)["format"] == fmt
    with pytest.raises(SystemExit):
        build_parser("run").parse_args(["run", "--units", "furlong/s2"])
    with pytest.raises(InputError, match="config key units = 'furlong/s2'"):
        config(units="furlong/s2")
    with pytest.raises(InputError, match="motions.units = 'furlong/s2'"):
        campaign("furlong/s2")


_ADDED_KEY = r"""
import dataclasses, json, sys
from isorock.validate.io import keys
# a key declared once, before any surface is made from the declaration
keys.SYSTEM["plinth_height"] = keys.Key("plinth_height", keys.POSITIVE, "the plinth's height, m", unit="m")
# and an existing key's kind changed: the campaign's axis of it follows
keys.SYSTEM["mass"] = dataclasses.replace(keys.SYSTEM["mass"], kind=keys.NON_NEGATIVE)
from pydantic import ValidationError
from isorock.validate.io.config_file import ConfigFile, SystemTable, describe
from isorock.validate.cli.main import build_parser
from isorock.validate.io.inputs import SYSTEM_KEYS
from isorock.validate.tools.campaign.schema import check_campaign
out = {"keys": list(SYSTEM_KEYS), "fields": list(SystemTable.model_fields)}
parser = build_parser("validate")
out["option"] = parser.parse_args(["validate", "--plinth-height", "0.4"]).plinth_height
out["help"] = next(a.help for a in parser._subparsers._group_actions[0].choices["validate"]._actions
                   if "--plinth-height" in a.option_strings)
try:
    ConfigFile.model_validate({"system": {"plinth_height": -1}})
except ValidationError as e:
    out["file"] = str(describe(e))
check_campaign({"systems": {"mass": 0}, "engines": [{"name": "analytic"}], "motions": {"type": "records"}})
out["campaign"] = "mass = 0 taken"
json.dump(out, sys.stdout)
"""


def test_a_key_added_to_the_declaration_appears_on_every_surface():
    """A new key in io/keys.py is an option (its flag, help, a number), a [system] key checked as
    its kind, and one of SYSTEM_KEYS; a kind changed there changes the campaign's axis of the key
    (the campaign spans its own axes, slenderness, mass_ratio…, and takes the kinds of those that
    are System keys). Run in a fresh process: the surfaces are made when their modules load."""
    import subprocess
    import sys
    done = subprocess.run([sys.executable, "-c", _ADDED_KEY], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert "plinth_height" in out["keys"] and "plinth_height" in out["fields"]
    assert out["option"] == 0.4 and out["help"] == "the plinth's height, m"
    assert out["file"] == "config key system.plinth_height = -1: must be a positive number"
    assert out["campaign"] == "mass = 0 taken"
