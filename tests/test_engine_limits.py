"""What an engine cannot carry is refused, not reported as an answer (issue 24, item 6).

PyBullet on a base 10⁶ times lighter than the block reported "completed" with
θmax/α = 2.4e-7 where the block rocks and falls (analytic 4.67): measured with the paper's
block (2 × 0.7 m, 3800 kg, T = 2 s, ξ = 0.1) under a 0.5 g, 1 Hz sine, PyBullet agrees
with the closed form up to μ = m/m_b = 1000, reports a slide from 3000, loses the
rocking at 1e5 and says nothing at 1e6 (scripts in docs/bullet.md)."""
from __future__ import annotations

import pytest

from isorock.analytic.errors import InputError
from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.system import System
from isorock.bullet_models.settings import MAX_MASS_RATIO
from isorock.validate.cli.main import main
from isorock.validate.core.engines import get_engine

SINE = GroundMotion.from_pulse(Pulse("sine", amp=0.5, freq=1.0, cycles=1))


def _system(mu):
    return System.isolated(height=2, width=0.7, mass=3800, base_mass=3800 / mu, period=2, damping_ratio=0.1)


def test_bullet_refuses_a_base_lighter_than_it_can_carry():
    with pytest.raises(InputError, match="mass_ratio"):
        get_engine("bullet").simulate(_system(1e6), SINE, duration=4.0)


def test_bullet_at_its_limit_still_agrees_with_the_closed_form():
    tr = get_engine("bullet").simulate(_system(MAX_MASS_RATIO), SINE, duration=4.0)
    ref = get_engine("analytic").simulate(_system(MAX_MASS_RATIO), SINE, duration=4.0)
    assert tr.overturned and ref.overturned
    assert tr.impact_count == ref.impact_count


def test_run_with_bullet_on_a_featherweight_base_is_one_line_exit_2(tmp_path, capsys):
    js = tmp_path / "r.json"
    rc = main(["run", "--engine", "bullet", "--height", "2", "--width", "0.7", "--mass", "3800",
               "--base-mass", "3.8e-3", "--period", "2", "--damping-ratio", "0.1",
               "--motion", "sine:amp=0.5,freq=1,cycles=1", "--json", str(js)])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "mass_ratio" in err and "1000" in err, err
    assert not js.exists()


@pytest.mark.parametrize("engine", ["mujoco", "bullet"])
def test_a_pulse_shorter_than_two_steps_is_refused_not_lost(engine):
    """A 1e4 Hz one-cycle sine lasts 1e-4 s, less than MuJoCo's 5e-4 s step and
    PyBullet's 4 ms control step: it was sampled to nothing (issue 24, item 16)."""
    short = GroundMotion.from_pulse(Pulse("sine", amp=5.0, freq=1e4, cycles=1))
    with pytest.raises(InputError, match="lasts 0.0001 s"):
        get_engine(engine).simulate(_system(1.0), short, duration=0.5)
    # the analytic model integrates the pulse itself: it keeps it
    get_engine("analytic").simulate(_system(1.0), short, duration=0.5)
