"""A campaign's work is bounded when its file is read (issue 24, items 8-9): the
bounds of analytic/limits.py that `run` applies (duration, steps, isolator periods)
name the key the user wrote, and the grid's size is the product of its lengths,
known before any grid is built."""
from __future__ import annotations

import subprocess
import sys

import pytest

from isorock.analytic.errors import InputError
from isorock.validate.tools.campaign import load_spec
from isorock.validate.tools.campaign.spec import MAX_RUNS

from test_campaign import write_spec

MUJOCO_FINE = '\n[[engines]]\nname = "mujoco"\nsettings = [{timestep = 1e-12}]\n'


@pytest.mark.parametrize("edit, key, bound", [
    (lambda s: s.replace("tail = 1.0", "end = 1e9"), "duration.end", "MAX_DURATION"),
    (lambda s: s.replace("tail = 1.0", "tail = 3600"), "duration.tail", "MAX_DURATION"),
    (lambda s: s.replace("period = 1.5", "period = 1e-9"), "systems.period", "MAX_ISOLATOR_CYCLES"),
    (lambda s: s.replace('name = "analytic"', 'name = "analytic"\nsettings = [{max_step = 1e-12}]'),
     "engines[0].settings[0]", "MAX_STEPS"),
    (lambda s: s + MUJOCO_FINE, "engines[1].settings[0]", "MAX_STEPS"),
])
def test_unbounded_work_is_refused_when_the_file_is_read(tmp_path, edit, key, bound):
    spec = write_spec(tmp_path, more="")
    spec.write_text(edit(spec.read_text()))
    with pytest.raises(InputError) as e:
        load_spec(spec)
    assert key in str(e.value) and bound in str(e.value), str(e.value)


@pytest.mark.parametrize("edits", [
    {"size = 1.0": "size = {from = 0.5, to = 2, num = 1000000}",
     "mass = 1000.0": "mass = {from = 10, to = 2000, num = 1000000}"},
    {"size = 1.0": "size = {from = 0.5, to = 2, num = 1000}", "period = 1.5": "period = {from = 1, to = 3, num = 1000}",
     "mass_ratio = 1.0": "mass_ratio = {from = 0.1, to = 3, num = 1000}"},
])
def test_a_huge_grid_is_refused_from_its_lengths_before_it_is_built(tmp_path, edits):
    spec = write_spec(tmp_path, more="")
    text = spec.read_text()
    for old, new in edits.items():
        text = text.replace(old, new)
    spec.write_text(text)
    # in a child process, bounded: the grid built first took minutes or a MemoryError
    code = ("import sys\nfrom isorock.validate.tools.campaign import load_spec\nfrom isorock.analytic.errors import InputError\n"
            f"try:\n    load_spec({str(spec)!r})\nexcept InputError as e:\n    print(e)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and "campaign size" in out.stdout and str(MAX_RUNS) in out.stdout, out


def test_no_grid_is_built_for_a_campaign_its_lengths_already_refuse(tmp_path, monkeypatch):
    """The table found two 1e6-point ranges taking 15-30 s to refuse on a loaded machine:
    each range was built (2e6 values) before the product was checked. The lengths are
    multiplied first, so no range is spaced at all."""
    from isorock.validate.tools.campaign import spec as spec_module
    spec = write_spec(tmp_path, more="")
    spec.write_text(spec.read_text().replace("size = 1.0", "size = {from = 0.5, to = 2, num = 1000000}")
                    .replace("mass = 1000.0", "mass = {from = 10, to = 2000, num = 1000000}"))

    def spaced(*a, **k):
        raise AssertionError("a range was built before the campaign's size was known")
    monkeypatch.setattr(spec_module.np, "linspace", spaced)
    monkeypatch.setattr(spec_module.np, "geomspace", spaced)
    with pytest.raises(InputError) as e:
        load_spec(spec)
    assert "campaign size" in str(e.value) and str(MAX_RUNS) in str(e.value)


def test_steps_are_counted_at_the_step_each_system_derives(tmp_path):
    """MuJoCo's default step follows the block (Settings.for_system: dt·p_eff fixed): a
    campaign's work bound counts the steps its fastest-rocking block takes, not those of
    the step written in seconds. A 5 mm block (p_eff ≈ 48 rad/s: a step of ~7 µs) over
    500 s is ~7e7 steps, past MAX_STEPS (2e7), though 500 s at the default's own 0.5 ms
    would be 1e6."""
    from isorock.analytic.limits import MAX_STEPS
    spec = write_spec(tmp_path, more='\n[[engines]]\nname = "mujoco"\n')
    spec.write_text(spec.read_text().replace("size = 1.0", "size = 0.005").replace("tail = 1.0", "tail = 500"))
    with pytest.raises(InputError) as e:
        load_spec(spec)
    assert "engines[1]" in str(e.value) and "MAX_STEPS" in str(e.value), str(e.value)
    assert 500 / 5e-4 < MAX_STEPS  # the step in seconds alone would have passed


@pytest.mark.parametrize("edit, engine, field", [
    # a statue lighter than MuJoCo's mjMINVAL: 9 rows of errors and exit 0 before
    (lambda s: s.replace("mass = 1000.0", "mass = 1e-30"), "mujoco", "mass"),
    # a base lighter than 1/1000 of the block: PyBullet's own bound (bullet_models/settings.py)
    (lambda s: s.replace("mass_ratio = 1.0", "mass_ratio = [1.0, 5000.0]"), "bullet", "mass_ratio"),
])
def test_an_engine_refusing_a_system_of_the_grid_is_refused_when_the_file_is_read(tmp_path, edit, engine, field):
    """Each engine's own bounds on a System (EngineSpec.check_system) hold for every
    system of the grid before anything runs, as `run` and `validate` refuse them."""
    spec = write_spec(tmp_path, more=f'\n[[engines]]\nname = "{engine}"\n')
    spec.write_text(edit(spec.read_text()))
    with pytest.raises(InputError) as e:
        load_spec(spec)
    assert f"engines[1]" in str(e.value) and f"{field} =" in str(e.value), str(e.value)


@pytest.mark.parametrize("route", ["file", "value"])
def test_a_long_value_is_named_in_a_short_line(tmp_path, route):
    """A bad value in a grid of 100,001 numbers (a file within the read bound, or the campaign as a
    value from Python) is one short line naming the key and what is allowed, not an echo of the
    whole list (it was a 7.9 MB line for a million numbers)."""
    import isorock
    heights = list(range(100_001))  # 0 is the bad one: a height must be positive
    text = (f"[systems]\nheight = {heights}\nwidth = 0.2\nmass = 80.0\nbase = [\"fixed\"]\n"
            "[motions]\ntype = \"pulse\"\n[engines]\nnames = [\"analytic\"]\n")
    path = tmp_path / "long.toml"
    path.write_text(text)
    with pytest.raises(InputError) as e:
        if route == "file":
            load_spec(path)
        else:
            import tomllib
            isorock.sweep(tomllib.loads(text), products=False)
    line = str(e.value)
    assert "\n" not in line and len(line) < 400, (len(line), line[:300])
    assert line.startswith("systems.height") and "positive" in line
