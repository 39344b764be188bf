"""Phased stepping, the same for every contact engine that has it (the shared rules of
analytic/rest_phase.py; MuJoCo: mujoco_models/phases.py, PyBullet: bullet_models/rest.py),
against stepping the scene throughout and against independent solutions: the rest phase
is the 1-DOF oscillator, the scene takes over before the uplift threshold, free rocking
is untouched. (MuJoCo's coarse steps away from impacts have their own tests in
test_mujoco_phases.py: here MuJoCo's contact phases step at the timestep.)"""
from dataclasses import dataclass, replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from isorock.analytic import rest_phase
from isorock.analytic.motion import load_motion
from isorock.analytic.system import paper_system
from isorock.validate.core.compare import first_tilt
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import REPORT_MOTIONS, ROBUST_SINE
from isorock.validate.core.tolerances import tolerance


@dataclass(frozen=True)
class Phased:
    """An engine's phased and full settings, its stepping's step (s) for a system, and
    how to hear the spans (first step, step the scene takes over) of its rest phases."""
    name: str
    phased: object
    full: object
    step: object
    record_spans: object


def _mujoco():
    from isorock.mujoco_models import Settings, phases

    def record(monkeypatch, spans):
        rest = phases.Phases.rest

        def recording(self, row, k, nstep):
            out = rest(self, row, k, nstep)
            spans.append((k, out[1]))
            return out
        monkeypatch.setattr(phases.Phases, "rest", recording)
    return Phased("mujoco", replace(Settings(), coarse=1), replace(Settings(), phased=False, coarse=1),
                  lambda s, d=None: Settings().for_system(s, d).timestep, record)


def _bullet():
    pytest.importorskip("pybullet")
    from isorock.bullet_models import Settings, rest

    def record(monkeypatch, spans):
        phase = rest.Rest.phase

        def recording(self, i, end, *state):
            skipped, states = phase(self, i, end, *state)
            spans.append((i, i + skipped))
            return skipped, states
        monkeypatch.setattr(rest.Rest, "phase", recording)
    return Phased("bullet", Settings(), replace(Settings(), phased=False),
                  lambda s, d=None: Settings().for_system(s).control_step, record)


ENGINES = {"mujoco": _mujoco, "bullet": _bullet}


@pytest.mark.parametrize("name", ENGINES)
def test_a_weak_record_gives_the_exact_isolator_response(name):
    """A sine at a tenth of the uplift threshold: the block never rocks, and u is the
    1-DOF oscillator's response (solve_ivp at rtol 1e-10, an independent integration),
    within the engine step's first-order error ω·dt (measured: MuJoCo 0.5·ω·dt)."""
    e = ENGINES[name]()
    s = paper_system()
    amp_g = 0.1 * s.uplift_acceleration / 9.80665
    motion = load_motion(f"sine:amp={amp_g!r},freq=1,cycles=3")
    raw = get_engine(name).spec.simulate(s, motion, settings=e.phased, duration=6.0)

    def rhs(t, y):
        return [y[1], -(s.stiffness * y[0] + s.damping * y[1]) / s.total_mass - float(motion(np.array([t]))[0])]

    exact = solve_ivp(rhs, (0, 6.0), [0.0, 0.0], t_eval=raw.t, rtol=1e-10, atol=1e-13, max_step=1e-3)
    scale = np.abs(exact.y[0]).max()
    assert np.abs(raw.u - exact.y[0]).max() <= s.omega * max(e.step(s), 5e-4) * scale
    assert np.abs(raw.theta).max() <= 1e-4 * s.alpha


@pytest.mark.parametrize("name", ENGINES)
def test_free_rocking_is_stepped_throughout(name):
    e = ENGINES[name]()
    s = paper_system()
    run = get_engine(name).spec.simulate
    a = run(s, None, settings=e.full, duration=1.5, theta0=0.5 * s.alpha)
    b = run(s, None, settings=e.phased, duration=1.5, theta0=0.5 * s.alpha)
    assert np.array_equal(a.theta, b.theta) and np.array_equal(a.u, b.u)


@pytest.mark.parametrize("fixed", [False, True])
@pytest.mark.parametrize("name", ENGINES)
def test_a_lifting_pulse_agrees_with_stepping_throughout(name, fixed):
    """The robust sine lifts the block on both bases: θmax/α, counted impacts and the
    first uplift of the phased run are those of the full run (measured: Δθmax/α ≤ 2e-4,
    same impacts, first uplift within 0.03 ms), within a tenth of the tolerance table's
    limits for the engine against the exact model."""
    e = ENGINES[name]()
    s = paper_system(fixed_base=fixed)
    motion = load_motion(ROBUST_SINE)
    engine = get_engine(name)
    full = engine.simulate(s, motion, settings=e.full, duration=motion.end_time + 2.0)
    phased = engine.simulate(s, motion, settings=e.phased, duration=motion.end_time + 2.0)
    assert full.impact_count >= 3 and phased.impact_count == full.impact_count
    assert (abs(phased.theta_max_over_alpha - full.theta_max_over_alpha)
            <= 0.1 * tolerance(name, "theta_max_diff").limit)
    assert abs(first_tilt(phased) - first_tilt(full)) <= 0.1 * tolerance(name, "first_uplift_diff").limit


@pytest.mark.parametrize("fixed", [False, True])
@pytest.mark.parametrize("name", ENGINES)
def test_the_scene_takes_over_before_the_threshold(name, fixed, monkeypatch):
    """Every rest phase ends at least LEAD_TIME before the base's absolute acceleration
    first reaches F_HIGH·g·tanα, and before the block first lifts; and there are rest
    phases (the run did skip the scene)."""
    e = ENGINES[name]()
    s = paper_system(fixed_base=fixed)
    motion = load_motion(REPORT_MOTIONS[1])  # a Ricker: the block rests first, then lifts
    spans = []
    e.record_spans(monkeypatch, spans)
    duration = motion.end_time + 2.0
    raw = get_engine(name).spec.simulate(s, motion, settings=e.phased, duration=duration)
    dt = e.step(s, duration)  # the step the run took (it follows the system)
    steps = np.rint(raw.t / dt).astype(int)  # rows sit at whole steps (coarse ones every few)
    a = (np.abs(motion((steps + 0.5) * dt)) if fixed else
         np.abs(s.stiffness * raw.u + s.damping * raw.u_dot) / s.total_mass)
    lead = int(round(rest_phase.LEAD_TIME / dt))
    uplift = int(steps[np.argmax(np.abs(raw.theta) > 1e-3 * s.alpha)])
    spans = [(k, end) for k, end in spans if end > k]
    assert spans and uplift > 0
    for k, end in spans:
        if end < steps[-1]:
            assert np.all(a[(steps >= k) & (steps < end + lead)] < rest_phase.F_HIGH * s.uplift_acceleration)
    assert any(end < uplift - lead for _, end in spans)
    assert not any(k < uplift <= end for k, end in spans)


@pytest.mark.parametrize("bad", [1, "yes", None])
@pytest.mark.parametrize("name", ENGINES)
def test_phased_must_be_a_boolean(name, bad):
    from isorock.analytic.errors import InputError
    settings_type = type(ENGINES[name]().phased)
    with pytest.raises(InputError, match="phased"):
        settings_type(phased=bad)


def test_linear_steps_is_the_map_stepped_one_by_one():
    """The mode-by-mode filter against x' = A x + B f stepped in a Python loop (the
    oracle), for an underdamped (complex pair), an overdamped (real modes) and a
    three-state map (PyBullet's control step)."""
    rng = np.random.default_rng(5)
    f = rng.normal(size=3000)
    maps = [(np.array([[0.999, 1e-3], [-0.5, 0.998]]), np.array([1e-6, 1e-3])),
            (np.array([[0.99, 0.0], [0.01, 0.95]]), np.array([1.0, 0.5])),
            (np.array([[0.9995, 1.1e-3, 1e-7], [-0.9, 0.997, 1e-4], [0.0, 1.0, 0.0]]), np.array([-6e-7, -1.1e-3, 0.0]))]
    for a, b in maps:
        x0 = rng.normal(size=a.shape[0])
        got = rest_phase.linear_steps(a, b, x0, f).T  # a column per step
        x, want = x0.copy(), []
        for fk in f:
            x = a @ x + b * fk
            want.append(x)
        want = np.array(want)
        assert np.abs(got - want).max() <= 1e-10 * np.abs(want).max()


def test_takeover_is_lead_steps_before_the_first_hot_step_from_start():
    """takeover read block by block from `start` against the rule written out over the
    whole array (the first |a| ≥ F_HIGH·threshold, `lead` steps earlier, not before start),
    with the hot step in the first block, past it, within `lead` of start, and never."""
    n, threshold, lead = 3 * rest_phase.BLOCK + 11, 2.0, 40
    hot_at = rest_phase.F_HIGH * threshold
    for first_hot, start in ((100, 0), (rest_phase.BLOCK + 7, 5), (2 * rest_phase.BLOCK + 3, 2 * rest_phase.BLOCK),
                             (60, 30), (None, 17)):
        a = np.full(n, 0.5 * hot_at)
        if first_hot is not None:
            a[first_hot] = hot_at
            a[first_hot + 5:] = 3 * hot_at
        want = None if first_hot is None else max(start, first_hot - lead)
        assert rest_phase.takeover(a, threshold, lead, start=start) == want
