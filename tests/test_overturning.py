"""analytic/overturning.py: model.md's overturning rule judged from a sampled history (the
judge the contact engines use), on histories written out here, and against the
analytic engines' own verdicts (located as events) on their histories."""
import math

import numpy as np
import pytest

from isorock.analytic import AnalyticSettings, GroundMotion, InputError, Pulse, System
from isorock.analytic.hybrid import simulate as reference
from isorock.analytic.overturning import judge_overturning

A = 0.25


def history(*points, n=101):
    """Piecewise-linear |θ| through (t, θ) points, sampled n times per segment."""
    t, th = [], []
    for (t0, a0), (t1, a1) in zip(points[:-1], points[1:]):
        t.append(np.linspace(t0, t1, n)[:-1])
        th.append(np.linspace(a0, a1, n)[:-1])
    t.append([points[-1][0]])
    th.append([points[-1][1]])
    return np.concatenate(t), np.concatenate(th)


def test_survivor_that_leaned_past_alpha():
    t, th = history((0, 0), (1, 1.3 * A), (2, 0), (3, -0.5 * A), (4, 0.1 * A))
    v = judge_overturning(t, th, A)
    assert not v.overturned and v.time is None and v.reason == "survived"
    at_alpha = judge_overturning(t, th, A, rule="alpha")
    assert at_alpha.overturned and at_alpha.reason == "reached-alpha"
    assert at_alpha.time == pytest.approx(1 / 1.3, abs=1e-12)  # linear ramp reaches α at t = 1/1.3


def test_block_on_its_side_overturned_when_it_last_rose_past_alpha():
    t, th = history((0, 0), (1, -1.2 * A), (2, -0.5 * A), (3, -2 * A), (4, -math.pi / 2), (5, -math.pi / 2))
    v = judge_overturning(t, th, A, motion_end=1.5)
    assert v.overturned and v.reason == "reached-side"
    # second rise through α on the ramp from −0.5α (t = 2) to −2α (t = 3)
    assert v.time == pytest.approx(2 + 0.5 / 1.5, abs=1e-12)
    assert "after the motion ended" in v.message


def test_run_ending_past_alpha_overturned():
    t, th = history((0, 0), (1, 0.9 * A), (2, 0.2 * A), (3, 1.1 * A))
    v = judge_overturning(t, th, A)
    assert v.overturned and v.reason == "ended-past-alpha"
    assert v.time == pytest.approx(2 + 0.8 / 0.9, abs=1e-12)


def test_bad_rule_is_an_input_error():
    with pytest.raises(InputError, match="overturn"):
        judge_overturning([0, 1], [0, 0], A, rule="pi")
    with pytest.raises(InputError, match="overturn"):
        AnalyticSettings(overturn="sometimes")


FIXED = System.fixed(height=2.0, width=2 * math.tan(A), mass=1000.0)


def sine(omega_over_p, amp_over_threshold, cycles=1.0):
    return GroundMotion.from_pulse(Pulse("sine", amp_over_threshold * math.tan(A),
                                         omega_over_p * FIXED.p / (2 * math.pi), cycles))


@pytest.mark.parametrize("motion", [sine(6.0, 9.0), sine(1.0, 3.0, 3), sine(2.0, 2.5), sine(4.0, 12.0)],
                         ids=["returns", "side", "falls-after", "strong"])
@pytest.mark.parametrize("rule", ["past-alpha", "alpha"])
def test_engine_verdict_equals_judge_on_its_history(motion, rule):
    tr = reference(FIXED, motion, settings=AnalyticSettings(overturn=rule))
    v = judge_overturning(tr.t, tr.theta, FIXED.alpha, motion_end=motion.end_time, rule=rule)
    assert v.overturned == tr.overturned
    if v.overturned:
        assert v.time == pytest.approx(tr.overturn_time, abs=5e-3)  # stored points are ≤ 5 ms apart
