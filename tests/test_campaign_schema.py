"""The campaign file means what it says, or is one line naming the key (issue 24, items
14-15): `isorock sweep` exits 2 with one line on stderr naming the key the user wrote,
writes no folder, and never shows a traceback."""
from __future__ import annotations

import numpy as np
import pytest

from isorock.validate.cli.main import main

from test_campaign import write_spec


def _sub(old, new):
    return lambda s: s.replace(old, new, 1)


@pytest.mark.parametrize("edit, key", [
    (_sub("mass = 1000.0", "mass = " + "9" * 400), "systems.mass"),                  # 400-digit integer
    (_sub("mass = 1000.0", "mass = true"), "systems.mass"),
    (_sub("period = 1.5", 'period = "1.5"'), "systems.period"),
    (_sub('base = ["fixed", "isolated"]', 'base = ["isolated", "isolated"]'), "systems.base"),   # ran twice
    (_sub('pulse = "sine"', 'pulse = ["sine", "sine"]'), "motions.pulse"),
    (_sub("[2.0, 4.0, 8.0]", "[2.0, 2.0, 8.0]"), "motions.frequency_ratio"),
    (_sub('base = ["fixed", "isolated"]\n', ""), "base"),                             # isolator without base
    (_sub("period = 1.5", "period = [1.5, -1.5]"), "systems.period"),
    (_sub("mass_ratio = 1.0", "mass_ratio = 1e-300"), "mass_ratio"),                  # not "stiffness = inf"
    (_sub("timestep = 2e-3", 'timestep = "2e-3"'), "timestep"),
    (lambda s: s + '\n[[engines]]\nname = "analytic"\nsettings = [{rtol = "1e-8"}]\n', "rtol"),
    (_sub("tail = 1.0", "tail = true"), "duration.tail"),
    (_sub("analytic_chunk = 7", "analytic_chunk = 7.5"), "campaign.analytic_chunk"),
    (_sub("amplitude_ratio = [0.9, 3.0, 8.0]", "amplitude_ratio = []"), "motions.amplitude_ratio"),
    (_sub("[systems]", "systems = 5\n[not_systems]"), "systems"),
    (_sub('type = "pulse"', 'type = "pulse"\nfolder = "x"'), "motions"),
])
def test_a_bad_campaign_value_is_one_line_naming_the_key(tmp_path, capsys, edit, key):
    spec = write_spec(tmp_path)
    spec.write_text(edit(spec.read_text()))
    out = tmp_path / "out"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and key in err and "Traceback" not in err, err
    assert not out.exists()


RECORDS = """
[systems]
alpha = 0.25
size = 1.0
base = "fixed"

[motions]
type = "records"
{motions}

[duration]
end = 1.0

[[engines]]
name = "analytic"
"""


def _records(tmp_path, motions, files):
    suite = tmp_path / "suite"
    suite.mkdir()
    for name, text in files.items():
        (suite / name).write_text(text)
    spec = tmp_path / "r.toml"
    spec.write_text(RECORDS.format(motions=motions))
    return spec


QUIET = "# units: g\n" + "".join(f"{t:.2f} 0\n" for t in np.arange(0, 1, 0.01))
LOUD = "# units: g\n" + "".join(f"{t:.2f} {0.3 * np.sin(6 * t):.6f}\n" for t in np.arange(0, 1, 0.01))


@pytest.mark.parametrize("motions, files, key", [
    ('folder = "suite"\nlevels = [0.3]', {"quiet.txt": QUIET}, "PGA of 0"),                  # ZeroDivisionError
    ('folder = "suite"\nscale_by = "pgv"\nlevels = [0.3]', {"quiet.txt": QUIET}, "PGV of 0"),
    ('folder = "suite"\nscale_by = ["pga"]\nlevels = [0.3]', {"a.txt": LOUD}, "motions.scale_by"),
    ('folder = "suite"\nunits = ["g"]\nlevels = [0.3]', {"a.txt": LOUD}, "motions.units"),
    ('folder = ""\nlevels = [0.3]', {"a.txt": LOUD}, "motions.folder"),
    ('folder = "suite"\nlevels = [0.3]', {"a.txt": LOUD.replace("0.00 0.000000", "0.00 1_000")}, "1_000"),
    ('folder = "suite"\nlevels = [0.3]', {"a.txt": "# units: g\n# units: gal\n" + LOUD}, "units"),
])
def test_records_campaign_faults_are_one_line(tmp_path, capsys, motions, files, key):
    spec = _records(tmp_path, motions, files)
    out = tmp_path / "out"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and key in err and "Traceback" not in err, err


def test_a_byte_order_mark_is_utf8(tmp_path):
    from isorock.validate.tools.campaign import load_spec
    spec = write_spec(tmp_path, more="")
    spec.write_bytes(b"\xef\xbb\xbf" + spec.read_bytes())
    assert load_spec(spec).n_cases == 18


def test_a_failed_analytic_row_says_why(monkeypatch):
    """A case the kernel could not run carries the kernel's message, not an empty one."""
    from isorock.analytic import fast
    from isorock.analytic.motion import GroundMotion, Pulse
    from isorock.analytic.system import System
    from isorock.validate.tools.campaign import Case, run_cases
    real = fast.simulate_batch

    def failing(*a, **k):
        rows = real(*a, **k)
        return [{**r, "status": "failed", "message": "the compiled kernel failed: test"} for r in rows]
    monkeypatch.setattr(fast, "simulate_batch", failing)
    s = System.fixed(height=2.0, width=0.7, mass=3800.0)
    t = run_cases([Case(0, s, GroundMotion.from_pulse(Pulse("sine", amp=0.2, freq=1.0)), 2.0)], ["analytic"])
    assert t["message"].to_pylist() == ["the compiled kernel failed: test"]


def test_a_read_only_out_is_one_line(tmp_path, capsys, monkeypatch):
    import errno
    from pathlib import Path
    real = Path.mkdir

    def read_only(self, *a, **k):
        if self.name == "parts":
            raise OSError(errno.EROFS, "Read-only file system")
        return real(self, *a, **k)
    monkeypatch.setattr(Path, "mkdir", read_only)
    spec = write_spec(tmp_path, more="")
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0", "--no-products"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--out" in err and "Read-only" in err, err


def test_a_full_disk_while_drawing_is_one_line_and_the_table_is_whole(tmp_path, capsys, monkeypatch):
    import errno

    import pyarrow.parquet as pq

    from isorock.validate.tools.campaign import products

    def full(*a, **k):
        raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr(products, "write_products", full)
    spec = write_spec(tmp_path, more="")
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert "No space left" in err and "results.parquet is complete" in err, err
    assert pq.read_table(tmp_path / "out" / "results.parquet").num_rows == 18


# --- the base's mass instead of the mass ratio (issue 25) -------------------------------

def _with_base_mass(text: str, value: str) -> str:
    return text.replace("mass_ratio = 1.0", f"base_mass = {value}", 1)


def test_base_mass_runs_the_systems_of_the_mass_ratios_it_means(tmp_path):
    """base_mass = [500, 2000] kg under a 1000 kg block is μ = 2 and 0.5: the same rows as
    the file that says mass_ratio = [2.0, 0.5], and the base built at the mass given."""
    from isorock.validate.tools.campaign import load_spec, run_campaign
    from test_campaign import assert_same_rows
    by_ratio = write_spec(tmp_path, more="", name="ratio.toml")
    by_ratio.write_text(by_ratio.read_text().replace("mass_ratio = 1.0", "mass_ratio = [2.0, 0.5]"))
    by_mass = write_spec(tmp_path, more="", name="mass.toml")
    by_mass.write_text(_with_base_mass(by_mass.read_text(), "[500.0, 2000.0]"))
    spec = load_spec(by_mass)
    assert spec.n_systems() == len(spec.system_grid()) == 3  # fixed, and two isolated
    isolated = [c.system for c in spec.cases() if not c.system.fixed_base]
    assert sorted({s.base_mass for s in isolated}) == [500.0, 2000.0]
    a = run_campaign(by_ratio, tmp_path / "a", workers=0, progress=False).table
    b = run_campaign(by_mass, tmp_path / "b", workers=0, progress=False).table
    assert sorted(set(b.column("mass_ratio").to_pylist()) - {0.0}) == [0.5, 2.0]
    assert_same_rows(a, b)


@pytest.mark.parametrize("value, named", [
    ("-500.0", "systems.base_mass"),
    ("true", "systems.base_mass"),
    ("1e-4", "systems.base_mass"),  # μ = 1e7: beyond the mass ratios a campaign may ask for
])
def test_a_bad_base_mass_is_one_line_naming_it(tmp_path, capsys, value, named):
    spec = write_spec(tmp_path, more="")
    spec.write_text(_with_base_mass(spec.read_text(), value))
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and named in err and "Traceback" not in err, err
    assert not (tmp_path / "out").exists()


def test_base_mass_and_mass_ratio_together_are_refused_in_one_line(tmp_path, capsys):
    spec = write_spec(tmp_path, more="")
    spec.write_text(spec.read_text().replace("mass_ratio = 1.0", "mass_ratio = 1.0\nbase_mass = 1000.0"))
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "mass_ratio" in err and "base_mass" in err and "not both" in err, err
    assert not (tmp_path / "out").exists()
