"""The contact engines where the statue slides and the ground heaves (issue 33, deliverable 5;
docs/sliding_engines.md), each against an oracle that is not the engine:

- pure sliding under a rectangular pulse on a fixed base: the rigid-plastic block's slip in
  closed form (written here, piecewise polynomials over the record's linear samples), its
  final slide and its onset; Drake's static and kinetic coefficients too;
- a block that rocks and slides (slide-rock), fixed and isolated: the exact model's θmax/α,
  slide and overturning;
- a constant vertical acceleration is a rescaled gravity: the engine's block under g + a_v
  against the same engine's block on a System whose gravity is g + a_v;
- an engine with one friction coefficient refuses μ_k < μ_s with one line;
- the slide is the engines' shared kinematics row by row, its rate integrates to it, and a
  run without friction or vertical motion carries none (its histories are the golden files').
Tolerances come from validate/core/tolerances.py, where each is justified by measurement."""
import importlib.util
import math
from dataclasses import replace

import numpy as np
import pytest

from isorock.analytic import kinematics
from isorock.analytic.errors import InputError
from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.status import Status
from isorock.analytic.system import System
from isorock.analytic.trajectory import SLIDING_FRACTION, RawHistory, first_passage
from isorock.validate.core import measure
from isorock.validate.core.engines import get_engine, settings_used
from isorock.validate.core.tolerances import tolerance

G = 9.81
needs_drake = pytest.mark.skipif(importlib.util.find_spec("pydrake") is None,
                                 reason="pydrake (Drake) is not installed: pip install 'isorock[drake]'")
ENGINES = ["mujoco", "bullet", pytest.param("drake", marks=needs_drake)]
ONE_COEFFICIENT = ["mujoco", "bullet"]


# --- the rigid-plastic block under a rectangular pulse, in closed form ---------------------

def rectangular_record(a0, start, length, dt=0.01):
    """ẍg: 0 until `start`, a0 for `length` s, then 0 again; linear between its samples (so it
    ramps up over the sample before `start` and down over the one after `start + length`)."""
    k, n = int(round(start / dt)), int(round(length / dt))
    return GroundMotion.from_array(np.r_[np.zeros(k), np.full(n + 1, a0), 0.0], dt=dt), (k - 1) * dt, dt


def rigid_plastic_slide(a0, t_up, dt, length, mu_s, mu_k, g=G):
    """The slide x(t) of a rigid-plastic block on a fixed base under rectangular_record (a0 > 0,
    a0 > μ_s·g): it sticks until ẍg passes μ_s·g on the ramp up, then slides backwards (x < 0)
    under ẍ = −ẍg + μ_k·g, the ground's ramp down and its rest after, until ẋ = 0. Each piece of
    ẍg is linear, c0 + c1·τ, so ẋ and x are polynomials in τ. Returns (x(t), t_slip, t_stop)."""
    t_slip = t_up + dt * mu_s * g / a0
    t_flat, t_down = t_up + dt, t_up + dt + length
    pieces = [(t_slip, mu_s * g, a0 / dt), (t_flat, a0, 0.0), (t_down, a0, -a0 / dt), (t_down + dt, 0.0, 0.0)]
    states, x, v = [], 0.0, 0.0
    for (t0, c0, c1), t1 in zip(pieces, [p[0] for p in pieces[1:]] + [math.inf]):
        if t1 == math.inf:  # the ground at rest: friction stops the block
            assert v < 0, "still sliding when the ground stops"
            t1 = t0 - v / (mu_k * g)
        states.append((t0, t1, x, v, c0, c1))
        tau = t1 - t0
        x, v = (x + v * tau + (mu_k * g - c0) * tau**2 / 2 - c1 * tau**3 / 6,
                v + (mu_k * g - c0) * tau - c1 * tau**2 / 2)

    def at(t):
        if t <= t_slip:
            return 0.0
        for t0, t1, x0, v0, c0, c1 in states:
            if t <= t1:
                tau = t - t0
                return x0 + v0 * tau + (mu_k * g - c0) * tau**2 / 2 - c1 * tau**3 / 6
        return x
    return at, t_slip, states[-1][1]


def closed_form_onset(at, t_slip, t_stop, level):
    """When the closed form's |x| first passes `level` (it decreases monotonically)."""
    from scipy.optimize import brentq
    return brentq(lambda t: -at(t) - level, t_slip, t_stop, xtol=1e-12)


#: (a0/g, μ, T s): a long push that slides the block 1.4·b, and a short hard one (0.24·b)
PUSHES = [(0.5, 0.2, 0.3), (1.2, 0.3, 0.05)]


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("a0_g, mu, length", PUSHES)
def test_sliding_under_a_rectangular_pulse_is_the_closed_form(engine, a0_g, mu, length):
    """A block whose tanα (1) is far above μ slides without rocking; the pulse starts after
    0.2 s, once the contact has settled under the block's weight (an engine's block starts just
    touching its base, without the normal force the model has from t = 0)."""
    system = System.fixed(height=0.5, width=0.5, mass=50.0).with_friction(mu)
    motion, t_up, dt = rectangular_record(a0_g * G, 0.2, length)
    at, t_slip, t_stop = rigid_plastic_slide(a0_g * G, t_up, dt, length, mu, mu)
    tr = get_engine(engine).simulate(system, motion, duration=t_stop + 0.3)
    s = tr.summary()
    assert tr.status == Status.COMPLETED, tr.message  # sliding is the model's: not flagged
    assert abs(s["slide_final"] / at(t_stop) - 1) <= tolerance(engine, "slide_closed_form").limit
    level = SLIDING_FRACTION * system.b
    onset = first_passage(tr.t, tr.slide, level)
    assert abs(onset - closed_form_onset(at, t_slip, t_stop, level)) * system.p <= tolerance(engine, "slide_onset").limit
    assert tr.theta_max_over_alpha < 0.01


@needs_drake
@pytest.mark.parametrize("a0_over_mu_s", [0.95, 1.2])
def test_drake_carries_static_and_kinetic_friction(a0_over_mu_s):
    """μ_s 0.3, μ_k 0.2: below μ_s·g the block holds (the model does not slide at all; Drake's
    regularised stiction creeps), above it slides as the closed form with μ_s to start and μ_k
    to slide."""
    mu_s, mu_k = 0.3, 0.2
    system = System.fixed(height=0.5, width=0.5, mass=50.0).with_friction(mu_s, mu_k)
    a0 = a0_over_mu_s * mu_s * G
    motion, t_up, dt = rectangular_record(a0, 0.2, 0.3)
    tr = get_engine("drake").simulate(system, motion, duration=1.2)
    s = tr.summary()
    if a0_over_mu_s < 1:
        assert s["slide_max"] <= tolerance("drake", "slide_max").limit * system.b
        return
    at, _, t_stop = rigid_plastic_slide(a0, t_up, dt, 0.3, mu_s, mu_k)
    assert t_stop < 1.2
    assert abs(s["slide_final"] / at(t_stop) - 1) <= tolerance("drake", "slide_closed_form").limit


# --- slide-rock against the exact model ----------------------------------------------------

def slide_rock_case(base):
    """A squat block (λ 2) whose friction (1.2 and 1.5 × tanα) lets it rock, and whose corner
    slips on each impact and in slide-rock: the exact model's θmax/α 0.83 and 0.55, slide 0.39·b
    and 0.21·b, robust under ±1% of the motion, standing."""
    if base == "fixed":
        system = System.fixed(height=1.0, width=0.5, mass=100.0).with_friction(0.6)
        motion = GroundMotion.from_pulse(Pulse("sine", 2.0, 4 * system.p / (2 * math.pi), 1))
        return system, motion, motion.end_time + 6 / system.p
    system = System.isolated(height=1.0, width=0.5, mass=100.0, base_mass=100.0, period=0.5,
                             damping_ratio=0.1).with_friction(0.75)
    motion = GroundMotion.from_pulse(Pulse("sine", 1.0, 2.0, 1))
    return system, motion, motion.end_time + 2.0


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("base", ["fixed", "isolated"])
def test_slide_rock_is_the_exact_models(engine, base):
    system, motion, duration = slide_rock_case(base)
    exact = get_engine("analytic").simulate(system, motion, duration=duration)
    got = get_engine(engine).simulate(system, motion, duration=duration)
    e, g = exact.summary(), got.summary()
    assert 0.5 < exact.theta_max_over_alpha < 0.9 and e["slide_max"] > 0.2 * system.b  # it rocks and slides
    assert got.overturned == exact.overturned
    assert (abs(got.theta_max_over_alpha - exact.theta_max_over_alpha)
            <= tolerance(engine, "slide_theta_max_diff").limit)
    assert abs(g["slide_max"] - e["slide_max"]) <= tolerance(engine, "slide_max").limit * system.b
    assert abs(g["slide_final"] - e["slide_final"]) <= tolerance(engine, "slide_final").limit * system.b


# --- a constant vertical acceleration is a heavier gravity ---------------------------------

#: the rescaled-gravity twins agree to rounding in MuJoCo and Bullet (the vertical force and the
#: heavier gravity are the same sum); Drake's error control steps the two differently
VERTICAL_TOL = {"mujoco": 1e-9, "bullet": 1e-9, "drake": 1e-3}


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("mu", [None, 0.4])
def test_constant_vertical_acceleration_is_a_heavier_gravity(engine, mu):
    """The paper's block on a fixed base under a sine that rocks it to 0.4α (and slides it with
    μ 0.4), heaved up at a_v = 3 m/s² throughout, against the same block on a System whose
    gravity is g + a_v, both stepped alike (the heavier block's settings, throughout)."""
    av = 3.0
    engine_ = get_engine(engine)
    duration = 1.0 if engine == "drake" else 4.0

    def block(g):
        return System.fixed(height=2.0, width=0.7, mass=3800.0, gravity=g).with_friction(mu)
    heavier = block(G + av)
    settings = settings_used(engine_.settings(), heavier, duration)
    if hasattr(settings, "phased"):  # the heavier block without friction would rest in phases
        settings = replace(settings, phased=False)
    pulse = GroundMotion.from_pulse(Pulse("sine", 1.5, 3.0, 1))
    heaved = engine_.simulate(block(G), pulse.with_vertical(GroundMotion.from_array(np.full(13, av), dt=0.5)),
                              settings=settings, duration=duration)
    heavy = engine_.simulate(heavier, pulse, settings=settings, duration=duration)
    assert heavy.theta_max_over_alpha > 0.3  # it rocks
    n = min(heaved.t.size, heavy.t.size)
    assert np.max(np.abs(heaved.theta[:n] - heavy.theta[:n])) <= VERTICAL_TOL[engine] * heavier.alpha
    if mu is not None:
        assert np.max(np.abs(heaved.slide[:n] - heavy.slide[:n])) <= VERTICAL_TOL[engine] * heavier.b
    # and the heave matters: under g alone (its own settings) the same block rocks otherwise, far beyond that limit
    light = engine_.simulate(block(G), pulse, duration=duration)
    m = min(light.t.size, heavy.t.size)
    assert np.max(np.abs(light.theta[:m] - heavy.theta[:m])) > 0.05 * heavier.alpha


# --- what an engine with one friction coefficient refuses -----------------------------------

@pytest.mark.parametrize("engine", ONE_COEFFICIENT)
def test_one_coefficient_engines_refuse_kinetic_below_static_with_one_line(engine):
    system = System.fixed(height=1.0, width=0.5, mass=10.0).with_friction(0.5, 0.4)
    e = get_engine(engine)
    assert not e.capabilities.kinetic_friction
    motion = GroundMotion.from_pulse(Pulse("sine", 0.3, 1.0, 1))
    for ask in (lambda: e.simulate(system, motion), lambda: e.spec.simulate(system, motion),
                lambda: e.check_system(system)):
        with pytest.raises(InputError) as err:
            ask()
        text = str(err.value)
        assert "\n" not in text and text.startswith("kinetic_friction = 0.4") and "friction = 0.5" in text
    e.check_system(system.with_friction(0.5))  # one coefficient: carried


@needs_drake
def test_drake_refuses_kinetic_below_static_on_a_discrete_plant_only():
    system = System.fixed(height=1.0, width=0.5, mass=10.0).with_friction(0.5, 0.4)
    drake = get_engine("drake")
    assert drake.capabilities.kinetic_friction
    drake.check_system(system)  # the continuous plant carries both
    with pytest.raises(InputError, match="^kinetic_friction = 0.4: Drake's discrete plant"):
        drake.check_system(system, drake.preset("sap"))
    with pytest.raises(InputError, match="^kinetic_friction = 0.4: Drake's discrete plant"):
        drake.simulate(system, None, settings=drake.preset("tamsi"), duration=0.1)


# --- the slide's history ----------------------------------------------------------------------

@pytest.mark.parametrize("engine", ENGINES)
def test_slide_is_the_pivot_slip_and_its_rate_integrates_to_it(engine):
    """The slide-rock case (fixed base for MuJoCo and PyBullet, isolated for Drake): x is
    kinematics.pivot_slip row by row (its definition, analytic.slide_physics), and ẋ, read from
    the body's velocities, integrates (trapezoidal rule) to x within 1% of the slide."""
    system, motion, duration = slide_rock_case("isolated" if engine == "drake" else "fixed")
    raw = get_engine(engine).spec.simulate(system, motion, duration=duration)
    assert raw.slide is not None and raw.slide_dot is not None
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (raw.slide_dot[1:] + raw.slide_dot[:-1]) * np.diff(raw.t))])
    assert np.max(np.abs(integral - (raw.slide - raw.slide[0]))) <= 0.01 * np.max(np.abs(raw.slide))
    # where the block has not slid, x is a contact's compliance
    assert abs(raw.slide[0]) < 1e-3 * system.b
    assert "stepping" in raw.extras or engine == "drake"


@pytest.mark.parametrize("engine", ["mujoco", "bullet"])
def test_without_friction_or_vertical_nothing_new(engine):
    """No friction, no vertical motion: no slide in the history, stepping by phases as before,
    and a block that slid is flagged as before (the golden files keep the numbers)."""
    system = System.fixed(height=1.0, width=0.7, mass=10.0)
    motion = GroundMotion.from_pulse(Pulse("sine", 0.3, 1.5, 1))
    raw = get_engine(engine).spec.simulate(system, motion)
    assert raw.slide is None and raw.slide_dot is None and "stepping" not in raw.extras
    tr = get_engine(engine).simulate(system, motion)
    assert tr.slide is None and "slide_max" not in tr.summary()


def test_measure_flags_a_slid_block_only_where_the_model_assumes_no_slip():
    """measure: pivot slip past SLIDING_FRACTION·b is the status SLID without friction, and the
    model's own sliding, compared and not flagged, with it."""
    system = System.fixed(height=1.0, width=0.5, mass=10.0)
    t = np.linspace(0.0, 1.0, 11)
    zeros = np.zeros_like(t)

    def raw_of(s):
        return RawHistory(engine="mujoco", system=s, t=t, u=zeros, u_dot=zeros, theta=zeros, theta_dot=zeros,
                          extras={"pivot_slip_max": 0.5 * s.b}, slide=-0.05 * t, slide_dot=-0.05 + zeros)
    motion = GroundMotion.zero()
    assert measure.measure(raw_of(system), motion).status == Status.SLID
    with_friction = measure.measure(raw_of(system.with_friction(0.3)), motion)
    assert with_friction.status == Status.COMPLETED
    assert with_friction.summary()["slide_final"] == pytest.approx(-0.05)
    assert with_friction.summary()["slide_onset"] == pytest.approx(SLIDING_FRACTION * system.b / 0.05)


def test_slide_room_only_for_a_statue_that_may_slide():
    system = System.fixed(height=1.0, width=0.5, mass=10.0)
    assert kinematics.slide_room(system) == 0.0
    assert kinematics.slide_room(system.with_friction(0.3)) == kinematics.SLIDE_ROOM * system.R
