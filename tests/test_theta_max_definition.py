"""θmax/α of an overturned block has one definition for every motion and engine
(issue 24, item 7): under model.md's default rule an overturned block ends on its side,
θmax = π/2, whether the run went on to π/2, stopped early because the fall was certain
(a fixed base after the motion), or ended past α. A built-in pulse stopped at the α
crossing (θmax/α 1.0) while the same pulse as a two-column file with a quiet tail ran on
to π/2. The JSON states the definition."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from isorock.analytic.motion import GroundMotion, Pulse, load_motion
from isorock.analytic.settings import AnalyticSettings
from isorock.analytic.system import System
from isorock.validate.cli.main import main
from isorock.validate.core.engines import get_engine

FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)
PULSE = Pulse("sine", amp=0.5, freq=1.0, cycles=1)


def _as_file(tmp_path, tail=2.0):
    t = np.arange(0, 1.0 + tail + 1e-9, 1e-3)
    a = np.where(t <= 1.0, PULSE.amp * np.sin(2 * math.pi * t), 0.0)
    path = tmp_path / "sine.txt"
    path.write_text("# units: g\n" + "".join(f"{x:.4f} {y:.12g}\n" for x, y in zip(t, a)))
    return path


@pytest.mark.parametrize("engine", ["analytic", "analytic-fast", "mujoco", "bullet"])
def test_an_overturned_block_has_the_same_theta_max_whatever_the_motions_form(engine, tmp_path):
    side = 0.5 * math.pi / FIXED.alpha
    e = get_engine(engine)
    for motion in (GroundMotion.from_pulse(PULSE), load_motion(str(_as_file(tmp_path)))):
        tr = e.simulate(FIXED, motion, duration=4.0)
        assert tr.overturned
        assert tr.theta_max_over_alpha == pytest.approx(side, rel=1e-12), (engine, motion.name)


def test_the_conservative_rule_keeps_alpha_and_the_json_says_which():
    e = get_engine("analytic")
    tr = e.simulate(FIXED, GroundMotion.from_pulse(PULSE), duration=4.0,
                    settings=AnalyticSettings(overturn="alpha"))
    assert tr.overturned and tr.theta_max_over_alpha == pytest.approx(1.0, abs=1e-9)
    assert "α" in tr.summary()["theta_max_over_alpha_definition"]


def test_campaign_rows_and_run_json_use_the_same_definition(tmp_path, capsys):
    from isorock.validate.tools.campaign import Case, run_cases
    side = 0.5 * math.pi / FIXED.alpha
    motion = GroundMotion.from_pulse(PULSE)
    t = run_cases([Case(0, FIXED, motion, 4.0)], ["analytic"]).to_pydict()
    assert t["overturned"] == [True] and t["theta_max_over_alpha"][0] == pytest.approx(side, rel=1e-12)
    assert main(["run", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "1", "--fixed-base",
                 "--motion", str(_as_file(tmp_path)), "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["theta_max_over_alpha"] == pytest.approx(side, rel=1e-12)
    assert "π/2" in d["theta_max_over_alpha_definition"]
