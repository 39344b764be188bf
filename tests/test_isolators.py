"""Non-linear isolators (issue 22, docs/isolators.md): the types, their closed forms on the
reference path (analytic-reference), the energy balance with the slip work, and every engine
that does not carry them refusing them with one line.

Oracles: the friction pendulum's period 2π√(R/g) and its Coulomb free decay (2μR per half
cycle, half periods apart); the stick–slip onset under a sine from rest, asin(μ/A)/ω; the
transmitted-acceleration bound g(μ + D/R) (a block with μ + D_max/R < tanα cannot lift); the
bilinear bearing's yield time (an offset cosine) and its peaks and loop areas from the energy
of its springs and F_s times the plastic travel; the energy balance.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from isorock.analytic import load_motion, physics
from isorock.analytic.errors import InputError
from isorock.analytic.fast import simulate_batch, simulate_fast
from isorock.analytic.hybrid import simulate
from isorock.analytic.system import (BilinearIsolator, FrictionPendulum, LinearIsolator, System, paper_system)
from isorock.validate.cli.main import main
from isorock.validate.core.tolerances import tolerance

CLOSED = tolerance("analytic", "isolator_closed_form").limit
ENERGY = tolerance("analytic", "isolator_energy_residual").limit
BLOCK = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)  # the paper's block, M = 7600 kg
G = 9.81


def pendulum(radius, mu, **block):
    return System.with_isolator(**(block or BLOCK), isolator=FrictionPendulum(radius=radius, friction_coefficient=mu))


def bearing(k0=3e5, r=0.1, u_y=0.01, c=0.0):
    return System.with_isolator(**BLOCK, isolator=BilinearIsolator(
        stiffness=k0, post_yield_ratio=r, yield_displacement=u_y, damping=c))


# --- the types ------------------------------------------------------------------------------

@pytest.mark.parametrize("make, field", [
    (lambda: FrictionPendulum(radius=0.0, friction_coefficient=0.05), "radius"),
    (lambda: FrictionPendulum(radius=math.inf, friction_coefficient=0.05), "radius"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=-0.01), "friction_coefficient"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=1.5), "friction_coefficient"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient="a"), "friction_coefficient"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=0.05, friction_max=0.01, friction_rate=10.0),
     "friction_max"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=0.05, friction_max=1.5, friction_rate=10.0),
     "friction_max"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=0.05, friction_max=0.1, friction_rate=-1.0),
     "friction_rate"),
    (lambda: FrictionPendulum(radius=1.0, friction_coefficient=0.05, friction_rate=10.0), "friction_rate"),
    (lambda: BilinearIsolator(stiffness=-1.0, post_yield_ratio=0.1, yield_displacement=0.01), "stiffness"),
    (lambda: BilinearIsolator(stiffness=1e5, post_yield_ratio=1.0, yield_displacement=0.01), "post_yield_ratio"),
    (lambda: BilinearIsolator(stiffness=1e5, post_yield_ratio=-0.1, yield_displacement=0.01), "post_yield_ratio"),
    (lambda: BilinearIsolator(stiffness=1e5, post_yield_ratio=0.1, yield_displacement=0.0), "yield_displacement"),
    (lambda: BilinearIsolator(stiffness=1e5, post_yield_ratio=0.1, yield_displacement=0.01, damping=-1.0),
     "damping"),
    (lambda: LinearIsolator(stiffness=0.0), "stiffness"),
    (lambda: System(**BLOCK, fixed_base=True, isolator=FrictionPendulum(radius=1.0, friction_coefficient=0.1)),
     "isolator"),
    (lambda: System(**BLOCK, isolator="friction"), "isolator"),
])
def test_bad_isolator_names_its_field(make, field):
    with pytest.raises(InputError) as e:
        make()
    assert str(e.value).startswith(f"{field} = ")


def test_linear_isolator_is_the_default_system():
    """A LinearIsolator is stored as the System's own stiffness and damping: the same System
    (equal, same hash), the same history bit for bit."""
    a = System.from_stiffness(**BLOCK, stiffness=1.3e5, damping=2.0e3)
    b = System.with_isolator(**BLOCK, isolator=LinearIsolator(stiffness=1.3e5, damping=2.0e3))
    assert a == b and hash(a) == hash(b) and b.isolator is None and b.isolator_kind == "linear"
    assert b.describe() == a.describe()
    motion = load_motion("sine:amp=0.6,freq=1.3,cycles=2")
    ta, tb = simulate(a, motion), simulate(b, motion)
    for key in ("t", "u", "u_dot", "theta", "theta_dot"):
        assert np.array_equal(getattr(ta, key), getattr(tb, key))
    assert ta.energy.isolator_loss is None and "energy_lost_in_isolator" not in ta.summary()


def test_pendulum_and_bearing_derive_stiffness():
    """The pendulum's stiffness is M·g/R (so its period is 2π√(R/g)) and it has no dashpot;
    the bearing's is its initial stiffness. Changing the masses keeps them consistent."""
    s = pendulum(1.5, 0.05)
    assert s.stiffness == pytest.approx(7600 * G / 1.5, rel=1e-15) and s.damping == 0.0
    assert s.period == pytest.approx(2 * math.pi * math.sqrt(1.5 / G), rel=1e-14)
    assert s.describe()["friction_force"] == pytest.approx(0.05 * 7600 * G, rel=1e-15)
    b = bearing(k0=2e5, c=300.0)
    assert (b.stiffness, b.damping) == (2e5, 300.0)
    assert b.isolator.yield_force == pytest.approx(2e5 * 0.01, rel=1e-15)


# --- friction pendulum: closed forms --------------------------------------------------------

def test_pendulum_period_without_friction():
    """μ = 0, no rocking: u = u0·cos(√(g/R)·t) exactly (the restoring force is linear in u),
    and every reversal (u̇ = 0, located) falls on a half period π√(R/g)."""
    R, u0 = 1.5, 0.05
    tr = simulate(pendulum(R, 0.0), None, duration=6.0, u0=u0)
    w = math.sqrt(G / R)
    assert tr.uplifts == 0
    assert np.max(np.abs(tr.u - u0 * np.cos(w * tr.t))) <= CLOSED * u0
    times = [t for t, _, _ in tr.extras["isolator_events"]]
    assert len(times) == int(6.0 / (math.pi / w))
    for k, t in enumerate(times, start=1):
        assert abs(t - k * math.pi / w) <= CLOSED


def test_pendulum_free_decay():
    """Coulomb free decay: each half cycle (π√(R/g) long) loses 2μ·R of amplitude (4μR a
    cycle); the base sticks at the first peak within μR of the centre. The friction work is
    μ·M·g times the travel, and equals the loss of spring energy."""
    R, mu, u0 = 1.5, 0.005, 0.1
    tr = simulate(pendulum(R, mu), None, duration=12.0, u0=u0)
    w = math.sqrt(G / R)
    events = tr.extras["isolator_events"]
    amplitude, k = u0, 0
    while amplitude > mu * R:
        k += 1
        amplitude -= 2 * mu * R
        t, phase, u = events[k - 1]
        assert abs(t - k * math.pi / w) <= CLOSED
        assert abs(u - (-1) ** k * amplitude) <= CLOSED * u0
        assert phase == ((-1) ** (k + 1) if amplitude > mu * R else 0)  # slips back, or sticks
    assert len(events) == k
    assert abs(tr.u[-1] - (-1) ** k * amplitude) <= CLOSED * u0 and tr.u_dot[-1] == 0.0
    travel = u0 + 2 * sum(u0 - 2 * mu * R * j for j in range(1, k)) + amplitude
    friction_work = mu * 7600 * G * travel
    assert abs(tr.energy.isolator_loss[-1] / friction_work - 1) <= CLOSED
    spring = 0.5 * (7600 * G / R) * (u0**2 - amplitude**2)
    assert abs(friction_work / spring - 1) <= CLOSED


def test_pendulum_slips_when_the_ground_pulls_past_friction():
    """From rest under ẍg = A·g·sin ωt the base holds (it moves with the ground) until
    M·A·g·sin ωt = μ·M·g: the first slip at asin(μ/A)/ω, away from the pull (u̇ < 0)."""
    A, f, mu = 0.3, 1.0, 0.05
    tr = simulate(pendulum(1.0, mu), load_motion(f"sine:amp={A},freq={f},cycles=1"), duration=1.5)
    t, phase, u = tr.extras["isolator_events"][0]
    assert phase == -1 and u == 0.0
    assert abs(t - math.asin(mu / A) / (2 * math.pi * f)) <= CLOSED
    before = tr.t <= t
    assert np.all(tr.u[before] == 0.0) and np.all(tr.u_dot[before] == 0.0)
    assert tr.uplifts == 0  # |a| = |ẍg| ≤ μ·g while it holds, then ≤ g(μ + |u|/R)


def test_pendulum_cannot_lift_a_block_with_friction_and_stroke_below_tan_alpha(kobe_jma):
    """The transmitted acceleration is bounded by g(μ + D/R) (sticking: |ẍg| ≤ g(μ + |u|/R), or
    it would slip; slipping: (M g/R)|u| + μ M g over M), so a block with μ + D_max/R < tanα
    cannot lift, whatever the motion. Kobe JMA N-S (0.83 g) lifts the paper's block on a
    fixed base; on a pendulum of R = 1 m, μ = 0.06 it does not: no simulation reference."""
    motion = load_motion(str(kobe_jma))
    assert simulate_fast(paper_system(fixed_base=True), motion, duration=15.0).uplifts > 0
    system = pendulum(1.0, 0.06)
    tr = simulate(system, motion)
    tan_alpha = system.width / system.height
    assert 0.06 + tr.u_max / 1.0 < tan_alpha  # the theorem's premise, from the run itself
    assert tr.uplifts == 0 and np.all(tr.mode == 0) and np.all(tr.theta == 0.0)
    sp, ip = physics.isolator_params(system, 1e-5)
    phase = tr.extras["isolator_phase"]
    a = np.array([physics.isolator_base_acceleration(sp, ip, int(p), u, ud, 0.0, motion.at(t))
                  for p, u, ud, t in zip(phase, tr.u, tr.u_dot, tr.t)])
    # a pinned base slips only past F_s + STICK_BAND·M·g (physics.STICK_BAND, 1e-12)
    # (and the event that ends a stick is located to rounding of the demand: 1e-12 more)
    assert np.all(np.abs(a) <= G * (0.06 + np.abs(tr.u) / 1.0 + physics.STICK_BAND) * (1 + 1e-12))
    assert np.max(np.abs(a)) > 0.9 * 0.06 * G  # the bound is approached, not idle


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_pendulum_no_uplift_under_random_pulses(seed):
    """Seeded strong pulses (1–3 g·tanα): wherever the run's own μ + D_max/R stays below tanα,
    the block never lifts; the pulses are strong enough to lift it on a fixed base."""
    rng = np.random.default_rng(seed)
    kind = ("sine", "cosine", "ricker")[seed % 3]
    amp = 0.35 * rng.uniform(1.0, 3.0)
    freq = rng.uniform(0.5, 3.0)
    motion = load_motion(f"{kind}:amp={amp:.6f},freq={freq:.6f}" + (",cycles=2" if kind != "ricker" else ""))
    assert simulate_fast(paper_system(fixed_base=True), motion).uplifts > 0
    R = rng.uniform(2.0, 4.0)
    tr = simulate(pendulum(R, 0.03), motion)
    if 0.03 + tr.u_max / R < 0.35:
        assert tr.uplifts == 0
    else:
        pytest.skip(f"μ + D/R = {0.03 + tr.u_max / R:.3f} ≥ tanα: the bound does not apply")


# --- bilinear bearing: closed forms ---------------------------------------------------------

def test_bearing_yields_on_time_and_decays_by_its_loop():
    """Free vibration of the bearing pushed to a = 0.1 m (slider at a − u_y), c = 0, no rocking.
    Yield: elastic from rest about u_c = k_e·u_p/k0, so u = u_c + (a − u_c)·cos ω0 t reaches
    u_p − u_y at acos(…)/ω0. Peaks: from x to the next peak −x' (x' > 0 on the other side) the
    springs lose ½ r k0 (x² − x'²) and the slider works F_s·(x + x' − 2 u_y), the loop's area:
    x' is the root of ½ r k0 x'² + F_s x' − (½ r k0 x² − F_s x + 2 F_s u_y) = 0. Each half
    cycle's hysteretic loss in EnergyLog.isolator_loss equals that area."""
    k0, r, u_y, a = 3e5, 0.5, 0.005, 0.1
    system = bearing(k0, r, u_y)
    tr = simulate(system, None, duration=6.0, u0=a)
    k_e, k_p = (1 - r) * k0, r * k0
    f_s = k_e * u_y
    events = tr.extras["isolator_events"]
    u_p = a - u_y
    u_c = k_e * u_p / k0
    t_yield = math.acos((u_p - u_y - u_c) / (a - u_c)) / math.sqrt(k0 / 7600)
    assert events[0][1] == -1 and abs(events[0][0] - t_yield) <= CLOSED
    assert abs(events[0][2] - (u_p - u_y)) <= CLOSED * a
    peaks = [(t, u) for t, phase, u in events if phase == 0]
    assert len(peaks) >= 3
    x, t_prev, checked = a, 0.0, 0
    for k, (t, u) in enumerate(peaks, start=1):
        c = 0.5 * k_p * x * x - f_s * x + 2 * f_s * u_y
        nxt = (-f_s + math.sqrt(f_s * f_s + 2 * k_p * c)) / k_p
        if x + nxt <= 2 * u_y:
            break  # this half cycle did not yield: the closed form no longer applies
        assert abs(u - (-1) ** k * nxt) <= CLOSED * a
        loss = np.interp(t, tr.t, tr.energy.isolator_loss) - np.interp(t_prev, tr.t, tr.energy.isolator_loss)
        assert abs(loss / (f_s * (x + nxt - 2 * u_y)) - 1) <= CLOSED
        x, t_prev, checked = nxt, t, checked + 1
    assert checked >= 5
    assert tr.energy.relative_residual <= ENERGY


# --- energy, rocking included ----------------------------------------------------------------

@pytest.mark.parametrize("system, motion", [
    (pendulum(0.5, 0.05), "sine:amp=0.6,freq=1.5,cycles=2"),
    (pendulum(0.5, 0.05), "ricker:amp=0.6,freq=1.5"),
    (pendulum(1.0, 0.25), "sine:amp=0.9,freq=2.0,cycles=3"),
    (bearing(3e6, 0.1, 0.002, 1000.0), "sine:amp=0.45,freq=2,cycles=3"),
    (bearing(3e6, 0.1, 0.002, 1000.0), "ricker:amp=0.6,freq=1.5"),
], ids=["pendulum", "pendulum-ricker", "pendulum-pinned", "bearing", "bearing-ricker"])
@pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])
def test_energy_balance_closes_with_the_slip_work(system, motion, run):
    """E(t) − E(0) = ground work − dashpot − impacts − slip work, to 1e-10 of the energy involved,
    through uplifts, impacts and stick–slip in both modes, on both analytic paths."""
    tr = run(system, load_motion(motion))
    assert tr.uplifts > 0 and tr.impacts
    assert tr.energy.isolator_loss[-1] > 0
    assert tr.energy.relative_residual <= ENERGY
    assert tr.summary()["energy_lost_in_isolator"] == tr.energy.isolator_loss[-1]


@pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])
def test_pinned_pendulum_rocks_on_the_moving_ground(run):
    """With high friction the base holds while the block rocks: the block rocks as on a fixed
    base (u and u̇ unchanged), and an impact's momentum (β₂θ̇⁻, no impulsive friction) sets
    the base sliding."""
    tr = run(pendulum(1.0, 0.25), load_motion("sine:amp=0.9,freq=2.0,cycles=3"))
    phase = tr.extras["isolator_phase"]
    pinned_rocking = (tr.mode != 0) & (phase == 0)
    assert pinned_rocking.any()
    assert np.all(tr.u_dot[pinned_rocking] == 0.0)
    after_impact = [i for i in tr.impacts if i.u_dot_pre == 0.0]
    assert after_impact and all(i.u_dot_post != 0.0 for i in after_impact)


# --- who carries them ---------------------------------------------------------------------------

@pytest.mark.parametrize("engine", ["drake"])  # MuJoCo and PyBullet carry both: tests/test_isolator_engines.py
def test_registry_refuses_what_an_engine_does_not_carry(engine):
    from isorock.validate.core.engines import get_engine
    try:
        e = get_engine(engine)
    except ImportError:
        pytest.skip(f"{engine} is not installed")
    with pytest.raises(InputError) as err:  # Drake carries the pendulums (tests/test_isolator_drake.py)
        e.simulate(bearing(), None, duration=1.0)
    assert f"'{engine}'" in str(err.value) and "bilinear" in str(err.value)
    with pytest.raises(InputError):
        e.simulate_many([(bearing(), None, 1.0, 0.0)])
    if e.has_scene:  # nor is its model file written with a linear spring in the device's place
        with pytest.raises(InputError, match="isolator = bilinear"):
            e.scene_text(bearing())


def test_shared_engine_checks_refuse_by_default():
    """run_inputs, which every engine's simulate calls, refuses a non-linear isolator unless the
    engine says it carries it: an engine called directly cannot run it as linear either."""
    from isorock.analytic.engine_protocol import run_inputs
    with pytest.raises(InputError, match="isolator = bilinear"):
        run_inputs(bearing(), None, 1.0, 0.0, 0.01)
    run_inputs(bearing(), None, 1.0, 0.0, 0.01, isolators=("linear", "bilinear"))


# --- the command line --------------------------------------------------------------------------

PAPER = ["--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]


@pytest.mark.parametrize("engine", [[], ["--engine", "analytic-reference"]], ids=["kernel", "reference"])
def test_run_takes_a_pendulum_on_either_analytic_path(engine, capsys):
    code = main(["run", *PAPER, "--isolator", "friction-pendulum", "--radius", "1.0",
                 "--friction-coefficient", "0.06", "--motion", "sine:amp=0.3,freq=1.0,cycles=1", "--quiet",
                 "--json", "-", *engine])
    out = capsys.readouterr().out
    assert code == 0
    d = json.loads(out)
    assert d["engine"] == ("analytic-reference" if engine else "analytic")  # the kernel by default
    assert d["system"]["isolator"] == "friction-pendulum" and d["system"]["radius"] == 1.0
    assert d["energy_lost_in_isolator"] > 0


@pytest.mark.parametrize("args, first", [
    (["--isolator", "friction-pendulum", "--radius", "-1", "--friction-coefficient", "0.05"], "radius = "),
    (["--isolator", "friction-pendulum", "--radius", "1", "--friction-coefficient", "2"], "friction_coefficient = "),
    (["--isolator", "friction-pendulum", "--radius", "1"], "--friction-coefficient"),
    (["--isolator", "friction-pendulum", "--radius", "1", "--friction-coefficient", "0.1", "--period", "2"],
     "--period"),
    (["--radius", "1", "--period", "2", "--damping-ratio", "0.1"], "--radius"),
    (["--isolator", "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "1", "--yield-displacement", "0.01"],
     "post_yield_ratio = "),
    (["--isolator", "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "0.1"], "--yield-displacement"),
    (["--isolator", "friction-pendulum", "--radius", "1", "--friction-coefficient", "0.02", "--friction-max", "0.1"],
     "--friction-rate"),
    (["--isolator", "friction-pendulum", "--radius", "1", "--friction-coefficient", "0.02", "--friction-max", "0.01",
      "--friction-rate", "30"], "friction_max = "),
    (["--isolator", "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "0.1", "--yield-displacement", "0.01",
      "--friction-rate", "30"], "--friction-rate"),
    (["--isolator", "bilinear", "--stiffness", "1e5", "--post-yield-ratio", "0.1", "--yield-displacement", "0.01",
      "--engine", "drake"], "isolator = bilinear"),
])
def test_run_refuses_bad_isolator_options_in_one_line(args, first, capsys):
    code = main(["run", *PAPER, *args])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and first in err


# --- velocity-dependent friction μ_f(v) = μ_max − (μ_max − μ_min)·exp(−a|v|) -----------------------

def pendulum_v(radius, mu_min, mu_max, rate):
    return System.with_isolator(**BLOCK, isolator=FrictionPendulum(
        radius=radius, friction_coefficient=mu_min, friction_max=mu_max, friction_rate=rate))


@pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])
def test_velocity_dependent_friction_tends_to_coulomb_at_its_maximum(run):
    """a → ∞: μ_f(v) is μ_max at every speed above 1/a, so the free decay is Coulomb's at μ_max:
    2μ_max·R lost per half cycle of π√(R/g) (the friction at rest, μ_min, only lets each slip
    start). At a = 1e12 s/m the low-friction window lasts ~1e-12 m/s of speed: the peaks move by
    ~1e-12 m."""
    R, mu_min, mu_max, u0 = 1.5, 0.002, 0.006, 0.1
    tr = run(pendulum_v(R, mu_min, mu_max, 1e12), None, duration=3 * math.pi * math.sqrt(R / G) + 0.1, u0=u0)
    w = math.sqrt(G / R)
    events = tr.extras["isolator_events"]
    # peaks: the slip's stops (phase changes at u̇ = 0) while the amplitude is above μ_max·R
    amplitude = u0
    for k in range(1, 4):
        amplitude -= 2 * mu_max * R
        t, phase, u = events[k - 1]
        assert abs(t - k * math.pi / w) <= CLOSED
        assert abs(u - (-1) ** k * amplitude) <= CLOSED * u0
        assert phase == (-1) ** (k + 1)


@pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])
def test_velocity_dependent_friction_at_equal_bounds_is_coulomb(run):
    """μ_max = μ_min: the same pendulum as Coulomb's μ_f, the same history to the last bit."""
    motion = load_motion("sine:amp=0.6,freq=1.5,cycles=2")
    a, b = run(pendulum_v(0.5, 0.05, 0.05, 40.0), motion), run(pendulum(0.5, 0.05), motion)
    assert np.array_equal(a.t, b.t) and np.array_equal(a.theta, b.theta) and np.array_equal(a.u, b.u)


@pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])
def test_velocity_dependent_friction_closes_the_energy_balance(run):
    """E(t) − E(0) = ground work − impacts − the slip work ∫ μ_f(|u̇|)·M·g·|u̇| dt, to 1e-10 of the
    energy involved, through uplift, impacts and stick–slip; more friction work than at μ_min."""
    motion = load_motion("sine:amp=0.6,freq=1.5,cycles=2")
    tr = run(pendulum_v(0.5, 0.03, 0.09, 20.0), motion)
    assert tr.uplifts > 0 and tr.impacts and len(tr.extras["isolator_events"]) > 2
    assert tr.energy.relative_residual <= ENERGY
    assert tr.energy.isolator_loss[-1] > run(pendulum(0.5, 0.03), motion).energy.isolator_loss[-1]
