"""The analytic model at its edges (issue 9): a grazing uplift on an isolated base, uplift
under high-frequency motion on a fixed base, motion past α, and a free vibration that
decays into denormals (issue 13). Each case runs on both paths, the SciPy reference and
the compiled kernel; oracles are closed forms (the pulse's own threshold crossings) or
counts that the physics fixes (no zero-length rocking phases)."""
import math

import numpy as np
import pytest

from isorock.analytic import AnalyticSettings, GroundMotion, Pulse, System
from isorock.analytic.hybrid import simulate as reference

fast = pytest.importorskip("isorock.analytic.fast", reason="numba is not installed")
PATHS = [pytest.param(reference, id="reference"), pytest.param(fast.simulate_fast, id="kernel")]

ALPHA = 0.25
ISOLATED = System.isolated(height=2.0, width=2 * math.tan(ALPHA), mass=1000.0, base_mass=1000.0, period=1.5,
                           damping_ratio=0.2)
FIXED = System.fixed(height=2.0, width=2 * math.tan(ALPHA), mass=1000.0)
PAPER_FIXED = System.fixed(height=2.0, width=0.7, mass=3800.0)


def sine(system, omega_over_p, amp_over_threshold, cycles=1.0):
    """One-sine pulse ω_p = ratio·p, a_p = ratio·g·tanα."""
    return GroundMotion.from_pulse(Pulse("sine", amp_over_threshold * system.b / system.h,
                                         omega_over_p * system.p / (2 * math.pi), cycles))


def most_events_at_one_instant(tr, tol=1e-12):
    times = np.sort(np.concatenate([[i.t for i in tr.impacts], tr.uplift_times]))
    if times.size == 0:
        return 0
    groups = np.split(times, np.nonzero(np.diff(times) > tol)[0] + 1)
    return max(g.size for g in groups)


# --- defect 1: a grazing uplift loops -----------------------------------------------------

@pytest.mark.parametrize("sim", PATHS)
def test_grazing_uplift_rocks_or_stays_down(sim):
    """The external check's case: before, uplift → impact (θ̇⁻ ≈ 1e-31) → uplift at one
    instant until the event limit. A grazing uplift rocks for real or stays down."""
    tr = sim(ISOLATED, sine(ISOLATED, 8.5, 4.3), settings=AnalyticSettings(max_events=1000))
    assert tr.status == "completed", tr.message
    assert most_events_at_one_instant(tr) <= 3
    assert len(tr.impacts) + tr.uplifts < 20


# --- defect 2: uplift missed at high frequency on a fixed base -----------------------------

@pytest.mark.parametrize("sim", PATHS)
@pytest.mark.parametrize("freq, ratio", [(50.0, 1.5), (10.0, 1.01), (3.0, 1.0001)])
def test_fixed_base_uplift_at_the_pulse_crossing(sim, freq, ratio):
    """ẍg = A sin(ωt) first exceeds g·tanα at t = asin(1/ratio)/ω (the block lifts about
    O', θ < 0, while ẍg > 0), whatever the frequency."""
    motion = GroundMotion.from_pulse(Pulse("sine", ratio * PAPER_FIXED.b / PAPER_FIXED.h, freq))
    tr = sim(PAPER_FIXED, motion, duration=1.0)
    assert tr.uplifts >= 1
    assert tr.uplift_times[0] == pytest.approx(math.asin(1 / ratio) / (2 * math.pi * freq), abs=1e-12)
    assert np.min(tr.theta) < 0


@pytest.mark.parametrize("sim", PATHS)
def test_fixed_base_uplift_inside_a_record_sample_interval(sim):
    """A record is linear between samples: one sample at 2·g·tanα between zeros crosses
    the threshold half-way up its rising ramp, whatever the step."""
    thr = PAPER_FIXED.uplift_acceleration
    acc = np.zeros(11)
    acc[5] = -2 * thr  # lifts about O (θ > 0)
    motion = GroundMotion.from_array(acc, dt=0.02)
    tr = sim(PAPER_FIXED, motion, duration=1.0)
    assert tr.uplift_times[0] == pytest.approx(4 * 0.02 + 0.5 * 0.02, abs=1e-12)
    assert np.max(tr.theta) > 0


# --- defect 3: motion past α -----------------------------------------------------------------

@pytest.mark.parametrize("sim", PATHS)
def test_block_leans_past_alpha_and_returns(sim):
    """model.md: ω_p = 6p, a_p = 9·g·tanα on a fixed base, α = 0.25: the block leans to
    about 1.25α and returns; it has not overturned."""
    tr = sim(FIXED, sine(FIXED, 6.0, 9.0))
    assert tr.status == "completed" and not tr.overturned, tr.message
    assert 1.2 < tr.theta_max_over_alpha < 1.3
    assert abs(tr.theta[-1]) < FIXED.alpha


@pytest.mark.parametrize("sim", PATHS)
def test_rule_alpha_stops_at_alpha(sim):
    tr = sim(FIXED, sine(FIXED, 6.0, 9.0), settings=AnalyticSettings(overturn="alpha"))
    assert tr.status == "overturned" and tr.summary()["overturn_rule"] == "alpha"
    assert tr.theta_max_over_alpha == pytest.approx(1.0, abs=1e-9)
    assert tr.t[-1] == pytest.approx(tr.overturn_time)


@pytest.mark.parametrize("sim", PATHS)
def test_block_reaching_its_side_has_overturned(sim):
    """A long strong pulse lays the block on its side while the ground still moves:
    |θ| reaches π/2 exactly (the event), and the overturning time is when it rose through α."""
    tr = sim(FIXED, sine(FIXED, 1.0, 3.0, cycles=3))
    assert tr.status == "overturned" and tr.summary()["overturn_rule"] == "past-alpha"
    assert np.max(np.abs(tr.theta)) == pytest.approx(math.pi / 2, abs=1e-9)
    crossing = np.interp(FIXED.alpha, np.abs(tr.theta), tr.t)  # |θ| grows monotonically to the side
    assert tr.overturn_time == pytest.approx(crossing, abs=1e-3)
    assert "π/2" in tr.message


@pytest.mark.parametrize("sim", PATHS)
def test_run_ending_past_alpha_has_overturned(sim):
    """A run that ends while the block leans past α has overturned (no rest state there),
    at the time it rose through α; the full run shows it returns, so only the end decides."""
    full = sim(FIXED, sine(FIXED, 6.0, 9.0))
    k = int(np.argmax(np.abs(full.theta)))
    rise = float(np.interp(FIXED.alpha, np.abs(full.theta[:k + 1]), full.t[:k + 1]))
    cut = sim(FIXED, sine(FIXED, 6.0, 9.0), duration=float(full.t[k]))
    assert cut.status == "overturned" and cut.overturned
    assert cut.overturn_time == pytest.approx(rise, abs=2e-3)


# --- issue 13: a free vibration decaying into denormals ------------------------------------

def test_kobe_600_s_does_not_raise(kobe_at2):
    """Before: ZeroDivisionError ~250 s after the record ended (event values in denormals)."""
    from isorock.analytic import paper_system
    from isorock.analytic.motion import read_at2
    tr = fast.simulate_fast(paper_system(), read_at2(kobe_at2), duration=600.0)
    assert tr.status == "completed" and tr.t[-1] == pytest.approx(600.0)
