"""One schema for the system (issue 35): `validate`'s options and a --config file's [system] table
name the same keys, every isolator kind among them (before, validate and its config file could
describe only the linear isolator), and each surface makes the same System. The oracles: the
System built directly from the model's own classes, and the other surfaces' Systems."""
from __future__ import annotations

import json

import pytest

from isorock.analytic.system import FrictionPendulum, BilinearIsolator, System
from isorock.validate.cli.config_file import SystemTable, read_config
from isorock.validate.cli.main import build_parser, main
from isorock.validate.cli.options import SYSTEM_KEYS, system_from_args, system_from_options

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
    from isorock.validate.cli.config_file import ConfigFile
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
