"""`validate --config`: every value the file gives is what the user meant, or one line
naming the key, the value and what is allowed, before any run (issue 24, items 11, 14,
15). Each case: exit 2, one line on stderr naming the key, no report folder."""
from __future__ import annotations

import pytest

from isorock.validate.cli.main import main

PAPER = "[system]\nheight = 2.0\nwidth = 0.7\nmass = 3800\nbase_mass = 3800\nperiod = 1.5\ndamping_ratio = 0.2\n"


@pytest.mark.parametrize("text, key", [
    (PAPER.replace("damping_ratio = 0.2", "damping_ratio = 1e6"), "system.damping_ratio"),   # item 11: hung
    (PAPER.replace("mass = 3800\n", "mass = " + "9" * 400 + "\n", 1), "system.mass"),       # 400 digits
    ('duration = "10"\n', "duration"),
    ("motions = [5]\n", "motions"),
    ("[settings]\nanalytic = 5\n", "settings.analytic"),
    ("settings = 5\n", "settings"),
    ("system = 5\n", "system"),
    ('[system]\nheight = 2.0\nwidth = 0.7\nmass = 3800\nfixed_base = "no"\n', "system.fixed_base"),
    (PAPER.replace("height = 2.0", "height = true"), "system.height"),
    ('quick = "no"\n', "quick"),
    ("duration = true\n", "duration"),
    ("[settings.analytic]\nrtoll = 1e-8\n", "rtoll"),
    ("[settings.warp]\ntimestep = 1e-3\n", "settings.warp"),
    ("engines = []\n", "engines"),
    ("motions = []\n", "motions"),
    ('engines = "analytic"\n', "engines"),
    ('motions = "sine:amp=0.5,freq=1"\n', "motions"),
    ("[settings.analytic]\nrtol = true\n", "rtol"),
    ('[settings."mujoco:finest"]\ntimestep = 1e-3\n', "mujoco:finest"),   # ran the report, table ignored
    (PAPER + "[settings.mujoco]\ntimestep = 1e-9\n", "timestep"),          # a worker's logged traceback
])
def test_a_bad_config_value_is_one_line_naming_the_key(tmp_path, capsys, text, key):
    cfg = tmp_path / "c.toml"
    cfg.write_text(text)
    out = tmp_path / "rep"
    assert main(["validate", "--config", str(cfg), "--quick", "--quiet", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and key in err and "Traceback" not in err, err
    assert not out.exists()


def test_invalid_utf8_is_one_line(tmp_path, capsys):
    cfg = tmp_path / "c.toml"
    cfg.write_bytes(b"[system]\nheight = 2.0 # \xff\xfe\n")
    assert main(["validate", "--config", str(cfg), "--out", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "UTF-8" in err


def test_a_good_config_reads_back_as_written(tmp_path):
    from isorock.validate.io.config_file import read_config
    cfg = tmp_path / "c.toml"
    cfg.write_bytes(("\ufeff" + 'engines = ["analytic", "mujoco:fast"]\nquick = true\nduration = 3\n' + PAPER
                     + "[settings.mujoco]\ntimestep = 1e-3\n").encode())
    c = read_config(cfg)
    assert c["system"]["height"] == 2.0 and c["system"]["mass"] == 3800.0
    assert c["engines"] == ["analytic", "mujoco:fast"] and c["quick"] is True and c["duration"] == 3.0
    assert c["settings"] == {"mujoco": {"timestep": 1e-3}} and "motions" not in c


def test_damping_ratio_on_the_command_line_is_capped_too(tmp_path, capsys):
    assert main(["validate", "--quick", "--quiet", "--engines", "analytic", "--height", "2", "--width", "0.7",
                 "--mass", "3800", "--base-mass", "3800", "--period", "1.5", "--damping-ratio", "1e6",
                 "--out", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "damping" in err
