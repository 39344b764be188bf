"""examples/statue.toml (issue 25): the shipped `validate --config` file parses, runs, and
documents every key the file format has (the oracle: the schema's own fields)."""
from __future__ import annotations

import json
import re
from pathlib import Path

from isorock.validate.io.config_file import ConfigFile, StatueTable, SystemTable, read_config
from isorock.validate.cli.main import main

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "statue.toml"


def test_it_parses_as_the_bust_it_describes():
    cfg = read_config(EXAMPLE)
    s = cfg["system"]
    assert (s["mass"], s["base_mass"]) == (80.0, 150.0)
    assert abs(s["height"] / s["width"] - 3.0) < 1e-12  # the comment's slenderness
    assert cfg["pga"] == 0.5 and "pgv" not in cfg


def test_every_key_of_the_format_is_in_it_and_each_commented_one_is_valid(tmp_path):
    text = EXAMPLE.read_text()
    written = set(re.findall(r"^#?\s*\[?([a-z_0-9]+)\s*=", text, re.M)) | set(re.findall(r"^#?\s*\[([a-z_0-9]+)", text, re.M))
    for key in set(ConfigFile.model_fields) | set(SystemTable.model_fields) | set(StatueTable.model_fields):
        assert key in written, f"examples/statue.toml does not document {key}"
    # the [statue] table, uncommented with its lines, is a valid file (its keys read as written)
    block = [line[1:] for line in text.splitlines() if re.match(r"^#\[statue\]|^#[a-z_0-9]+ =", line)]
    path = tmp_path / "statue.toml"
    path.write_text("\n".join(block) + "\n")
    assert set(read_config(path)["statue"]) == set(StatueTable.model_fields)
    # each commented-out key, uncommented alone into the file, is a valid file too
    head, _, tail = text.partition("\n# [settings")
    lines = head.splitlines()
    for i, line in enumerate(lines):
        m = re.match(r"^# ([a-z_0-9]+ = .*?)(\s+#.*)?$", line)
        if not m or m.group(1).startswith(("motions", "fixed_base")):
            continue  # the records are the user's own files; fixed_base with the isolator is refused (below)
        trial = lines[:i] + [m.group(1)] + lines[i + 1:]
        if m.group(1).startswith("pgv"):
            trial = [x for x in trial if not x.startswith("pga")]
        if m.group(1).startswith(("stiffness", "dashpot")):
            trial = [x for x in trial if not x.startswith(("period", "damping_ratio"))]
        path = tmp_path / f"t{i}.toml"
        path.write_text("\n".join(trial) + "\n")
        read_config(path)  # raises on a key or value the format does not take
    # the settings tables, uncommented together
    settings = re.sub(r"^# ", "", "# [settings" + tail, flags=re.M)
    path = tmp_path / "settings.toml"
    path.write_text(head + "\n" + settings)
    assert set(read_config(path)["settings"]) == {"mujoco", "*"}


def test_it_runs_quick(tmp_path, capsys):
    out = tmp_path / "bust"
    # the file's motions, system and target; the analytic engine alone (the command line wins)
    code = main(["validate", "--config", str(EXAMPLE), "--quick", "--quiet", "--engines", "analytic",
                 "--out", str(out)])
    assert code == 0, capsys.readouterr()
    metrics = json.loads((out / "metrics.json").read_text())
    text = json.dumps(metrics)
    assert "sine:amp=0.3,freq=2,cycles=2" in text and "ricker:amp=0.3,freq=1.5" in text
    assert (out / "report.md").is_file()
    # the file's pga = 0.5 scaled both pulses (0.3 g as written) to 0.5 g
    assert [sc["motion"]["pga_g"] for sc in metrics["scenarios"]] == [0.5] * len(metrics["scenarios"])


def test_pga_and_pgv_in_one_file_are_refused_in_one_line(tmp_path, capsys):
    path = tmp_path / "c.toml"
    path.write_text(EXAMPLE.read_text().replace("\npga = 0.5\n", "\npga = 0.5\npgv = 0.4\n"))
    assert main(["validate", "--config", str(path), "--quick", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "pgv" in err[0] and "not both" in err[0], err
    assert not (tmp_path / "o").exists()


def test_the_bust_stays_still_on_its_isolator_and_rocks_on_a_fixed_base_as_the_file_says():
    """(issue 39) The file's comment: at 0.5 g the isolated plinth (with the bust on it, one
    body until uplift) never reaches the bust's uplift acceleration g·tanα; on a fixed base the
    ground's 0.5 g does. Oracle: the isolator's own linear oscillator integrated here by SciPy
    (M ü + c u̇ + k u = −M ü_g, M = m + m_b), its absolute acceleration against g·tanα, and the
    exact model agreeing (θmax 0 isolated, lifted on the fixed base)."""
    import numpy as np
    from scipy.integrate import solve_ivp

    import isorock
    from isorock.analytic.motion import GroundMotion, parse_pulse
    from isorock.analytic.system import System
    bust = System.isolated(height=0.6, width=0.2, mass=80.0, base_mass=150.0, period=2.0, damping_ratio=0.15)
    lift = 9.81 * np.tan(bust.alpha)
    for spec in ("sine:amp=0.3,freq=2,cycles=2", "ricker:amp=0.3,freq=1.5"):
        ground = GroundMotion.from_pulse(parse_pulse(spec)).scaled_to_pga(0.5)
        w, xi = 2 * np.pi / 2.0, 0.15

        def rhs(t, y):
            return [y[1], -ground.at(t) - 2 * xi * w * y[1] - w * w * y[0]]
        t = np.linspace(0.0, ground.end_time + 4.0, 20001)
        sol = solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-10, atol=1e-12, max_step=0.002)
        absolute = -(2 * xi * w * sol.y[1] + w * w * sol.y[0])  # ü_g + ü
        assert np.abs(absolute).max() < 0.6 * lift, spec  # the plinth stays well below uplift
        kw = dict(engine="analytic", motion=spec, pga=0.5, height=0.6, width=0.2, mass=80)
        assert isorock.run(base_mass=150, period=2.0, damping_ratio=0.15, **kw).theta_max_over_alpha == 0.0
        assert isorock.run(fixed_base=True, **kw).theta_max_over_alpha > 0.3  # 0.5 g > g·tanα = 0.333 g
