"""Rolling isolators (ball in cone, ball in bowl) and the double concave friction pendulum
(issue 22, docs/isolators.md) against closed forms, on the reference path and the kernel.

Oracles, none of them a value of the code under test:
- ball in cone, μ_r = 0: constant deceleration g·tanφ on every leg, so u is a chain of
  parabolas, vertex crossings every √(2u0/(g tanφ)) and a period 4√(2u0/(g tanφ)) that grows
  with the amplitude;
- ball in cone, μ_r > 0: legs of constant acceleration g(tanφ − μ_r) (returning) and
  deceleration g(tanφ + μ_r) (climbing): each amplitude (tanφ − μ_r)/(tanφ + μ_r) of the last,
  leg times √(2A/(g(tanφ ∓ μ_r))), the ball resting at the vertex at the geometric series' sum
  (less the tail below the numerical floor, bounded in closed form) with all of F_c·u0 lost to
  the rolling resistance; with tanφ ≤ μ_r it never moves;
- the transmitted acceleration is at most g(tanφ + μ_r) (the record need not be simulated on a
  fixed base to know the block cannot lift when that is below tanα);
- ball in bowl: the friction pendulum with μ_f = μ_r, bit for bit;
- double pendulum: with μ1 = μ2 one pendulum of R1 + R2 (the existing FrictionPendulum run, and
  its Coulomb decay of 2μ(R1 + R2) per half period π√((R1 + R2)/g)); with μ1 ≠ μ2 the free
  vibration regime by regime from the series model itself (Fenz & Constantinou: regime I the
  surface of lower friction alone, stiffness W/R_lo, until F − W·u_hi/R_hi reaches μ_hi·W;
  regime II both, F = W(u + σ(μ_lo R_lo + μ_hi R_hi))/(R1 + R2)), its transition displacement
  2(μ_hi − μ_lo)·R_lo;
- the energy balance with the rolling resistance's or the sliders' work, rocking included.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from isorock.analytic import load_motion, physics
from isorock.analytic.errors import InputError
from isorock.analytic.fast import compare_on_grid, simulate_fast
from isorock.analytic.hybrid import simulate
from isorock.analytic.system import (BallInBowl, BallInCone, DoubleFrictionPendulum, FrictionPendulum, System)
from isorock.validate.cli.main import main
from isorock.validate.core.tolerances import tolerance
from agreement_cases import _on_grid

CLOSED = tolerance("analytic", "isolator_closed_form").limit
ENERGY = tolerance("analytic", "isolator_energy_residual").limit
BLOCK = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)  # the paper's block, M = 7600 kg
M, G = 7600.0, 9.81
PATHS = pytest.mark.parametrize("run", [simulate, simulate_fast], ids=["reference", "kernel"])


def cone(slope, mu_r):
    return System.with_isolator(**BLOCK, isolator=BallInCone(slope=slope, rolling_resistance=mu_r))


def double(r1, mu1, r2, mu2):
    return System.with_isolator(**BLOCK, isolator=DoubleFrictionPendulum(r1, mu1, r2, mu2))


# --- the types ------------------------------------------------------------------------------

@pytest.mark.parametrize("make, field", [
    (lambda: BallInCone(slope=0.0), "slope"),
    (lambda: BallInCone(slope=1.5), "slope"),
    (lambda: BallInCone(slope=0.1, rolling_resistance=-0.01), "rolling_resistance"),
    (lambda: BallInBowl(radius=-1.0), "radius"),
    (lambda: BallInBowl(radius=1.0, rolling_resistance=2.0), "rolling_resistance"),
    (lambda: DoubleFrictionPendulum(0.0, 0.02, 1.0, 0.05), "radius_1"),
    (lambda: DoubleFrictionPendulum(1.0, 0.02, math.nan, 0.05), "radius_2"),
    (lambda: DoubleFrictionPendulum(1.0, -0.02, 1.0, 0.05), "friction_1"),
    (lambda: DoubleFrictionPendulum(1.0, 0.02, 1.0, 1.05), "friction_2"),
    (lambda: System(**BLOCK, fixed_base=True, isolator=BallInCone(slope=0.1)), "isolator"),
])
def test_bad_isolator_names_its_field(make, field):
    with pytest.raises(InputError) as e:
        make()
    assert str(e.value).startswith(f"{field} = ")


def test_derived_stiffness_and_period():
    """The cone has no stiffness (its period depends on the amplitude); the bowl's and the
    double pendulum's (both surfaces sliding) are M·g/R_eff and M·g/(R1 + R2)."""
    c = cone(0.1, 0.02)
    assert c.stiffness == 0.0 and c.period == math.inf and c.damping_ratio == 0.0
    assert c.isolator_kind == "ball-in-cone" and c.describe()["restoring_force"] == pytest.approx(0.1 * M * G)
    b = System.with_isolator(**BLOCK, isolator=BallInBowl(radius=2.0, rolling_resistance=0.01))
    assert b.stiffness == M * G / 2.0 and abs(b.period - 2 * math.pi * math.sqrt(2.0 / G)) <= CLOSED
    d = double(1.0, 0.02, 1.5, 0.05)
    assert d.stiffness == M * G / 2.5
    assert DoubleFrictionPendulum(1.5, 0.05, 1.0, 0.02).transition_displacement == 2 * (0.05 - 0.02) * 1.0


# --- ball in cone -----------------------------------------------------------------------------

def cone_without_friction(t, u0, a):
    """u(t) from rest at u0 > 0 under the constant restoring acceleration a·sgn(u): parabolas,
    the quarter period √(2u0/a), u(t + half period) = −u(t)."""
    tq = math.sqrt(2 * u0 / a)
    k, tau = np.divmod(t, 2 * tq)
    u = np.where(tau <= tq, u0 - 0.5 * a * tau**2, -u0 + 0.5 * a * (2 * tq - tau) ** 2)
    return np.where(k % 2 == 0, u, -u)


@PATHS
def test_cone_period_grows_with_amplitude(run):
    """μ_r = 0: u is the chain of parabolas at every stored point, the vertex is crossed at
    odd multiples and the ball turns at even multiples of √(2u0/(g tanφ)); four times the
    amplitude, twice the period. The energy M·g·tanφ·|u| + kinetic is conserved."""
    slope = 0.1
    for u0 in (0.02, 0.08):
        tq = math.sqrt(2 * u0 / (G * slope))
        tr = run(cone(slope, 0.0), None, duration=8 * tq + 0.01, u0=u0)
        assert tr.uplifts == 0
        assert np.max(np.abs(tr.u - cone_without_friction(tr.t, u0, G * slope))) <= CLOSED * u0
        events = tr.extras["isolator_events"]
        assert len(events) == 8
        for k, (t, phase, u) in enumerate(events, start=1):
            assert abs(t - k * tq) <= CLOSED
            if k % 2:  # the vertex: climbing on the other side
                assert u == 0.0 and abs(phase) == 1
            else:  # a turn at the amplitude, returning
                assert abs(abs(u) - u0) <= CLOSED * u0 and abs(phase) == 2
        assert tr.energy.relative_residual <= ENERGY


def cone_decay(u0, slope, mu_r, n_legs):
    """(t, u) of the first n_legs events of the free decay from rest at u0 > 0: each return of
    amplitude A takes √(2A/(g(tanφ − μ_r))) to the vertex, each climb reaches ρ·A,
    ρ = (tanφ − μ_r)/(tanφ + μ_r), in √(2ρA/(g(tanφ + μ_r)))."""
    down, up = G * (slope - mu_r), G * (slope + mu_r)
    rho = (slope - mu_r) / (slope + mu_r)
    out, t, A, side = [], 0.0, u0, 1.0
    while len(out) < n_legs:
        t += math.sqrt(2 * A / down)
        out.append((t, 0.0))
        A *= rho
        side = -side
        t += math.sqrt(2 * A / up)
        out.append((t, side * A))
    return out[:n_legs]


@PATHS
def test_cone_rolling_resistance_decays_geometrically_and_rests_at_the_vertex(run):
    """μ_r < tanφ: the ball never stops away from the vertex (its demand there, M·g·tanφ, exceeds
    μ_r·M·g), its amplitudes fall geometrically and their legs shorten as √A: it rests at the
    vertex at the series' sum T∞, all of its potential M·g·tanφ·u0 lost to rolling resistance.
    The run stops the tail when a return would climb below VERTEX_REST_HEIGHT, which bounds how
    early it rests (the tail from a vertex speed v: (v/(g(tanφ + μ_r)) + √(2h/(g(tanφ − μ_r))))
    /(1 − √ρ), h = v²/(2g(tanφ + μ_r)))."""
    slope, mu_r, u0 = 0.15, 0.05, 0.1
    tr = run(cone(slope, mu_r), None, duration=4.0, u0=u0)
    events = tr.extras["isolator_events"]
    expected = cone_decay(u0, slope, mu_r, 20)
    for (t, phase, u), (te, ue) in zip(events, expected):
        assert abs(t - te) <= CLOSED and abs(u - ue) <= CLOSED * u0
    rho = (slope - mu_r) / (slope + mu_r)
    down, up = G * (slope - mu_r), G * (slope + mu_r)
    t_inf = (math.sqrt(2 * u0 / down) + math.sqrt(2 * rho * u0 / up)) / (1 - math.sqrt(rho))
    t_rest, phase, u = events[-1]
    assert phase == 0 and u == 0.0 and tr.u[-1] == 0.0 and tr.u_dot[-1] == 0.0
    v = math.sqrt(2 * up * physics.VERTEX_REST_HEIGHT)  # the floor's vertex speed
    tail = (v / up + math.sqrt(2 * (v * v / (2 * up)) / down)) / (1 - math.sqrt(rho))
    assert 0.0 <= t_inf - t_rest <= tail + CLOSED
    assert abs(tr.energy.isolator_loss[-1] / (slope * M * G * u0) - 1) <= CLOSED
    assert tr.energy.relative_residual <= ENERGY


@PATHS
def test_cone_ball_held_by_rolling_resistance_never_moves(run):
    """tanφ ≤ μ_r: the demand at rest, M·g·tanφ, is within the rolling resistance: u stays u0."""
    tr = run(cone(0.04, 0.05), None, duration=2.0, u0=0.05)
    assert np.all(tr.u == 0.05) and np.all(tr.u_dot == 0.0) and not tr.extras["isolator_events"]


def test_cone_transmits_at_most_its_slope_and_resistance(kobe_jma):
    """The base's absolute acceleration is at most g(tanφ + μ_r) (rolling: (F_c + F_s)/M; held:
    |ẍg| ≤ g(μ_r + tanφ), or at the vertex g(tanφ + μ_r), or it would roll), so a block with
    tanφ + μ_r < tanα never lifts, whatever the motion: Kobe JMA N-S (0.83 g) on tanφ 0.15,
    μ_r 0.05 (0.2 < 0.35). The bound is checked at every stored state of both paths."""
    motion = load_motion(str(kobe_jma))
    system = cone(0.15, 0.05)
    sp, ip = physics.isolator_params(system, 1e-5)
    for tr in (simulate_fast(system, motion), simulate(system, motion, duration=20.0)):
        assert tr.uplifts == 0 and np.all(tr.mode == 0) and np.all(tr.theta == 0.0)
        phase = tr.extras["isolator_phase"]
        a = np.array([physics.isolator_base_acceleration(sp, ip, int(p), u, ud, 0.0, motion.at(t))
                      for p, u, ud, t in zip(phase, tr.u, tr.u_dot, tr.t)])
        assert np.all(np.abs(a) <= G * (0.2 + physics.STICK_BAND) * (1 + 1e-12))
        assert np.max(np.abs(a)) > 0.99 * 0.2 * G  # the bound is reached, not idle


# --- ball in bowl ---------------------------------------------------------------------------------

@PATHS
def test_bowl_is_the_friction_pendulum(run):
    """The bowl's equations are the pendulum's with μ_f = μ_r: the same history, bit for bit."""
    motion = load_motion("sine:amp=0.6,freq=1.5,cycles=2")
    a = run(System.with_isolator(**BLOCK, isolator=BallInBowl(radius=0.5, rolling_resistance=0.05)), motion)
    b = run(System.with_isolator(**BLOCK, isolator=FrictionPendulum(radius=0.5, friction_coefficient=0.05)), motion)
    assert a.uplifts > 0 and a.impacts
    for name in ("t", "u", "u_dot", "theta", "theta_dot"):
        assert np.array_equal(getattr(a, name), getattr(b, name))
    assert a.extras["isolator_events"] == b.extras["isolator_events"]
    assert a.extras["isolator"] == "ball-in-bowl"


# --- double concave friction pendulum ------------------------------------------------------------

@PATHS
def test_double_pendulum_with_equal_friction_is_one_pendulum(run):
    """μ1 = μ2: one pendulum of radius R1 + R2 and friction μ, under a pulse that rocks the block
    (the FrictionPendulum run, to 1e-9), and in free decay 2μ(R1 + R2) lower each half period
    π√((R1 + R2)/g) (Coulomb's closed form)."""
    motion = load_motion("sine:amp=0.6,freq=1.5,cycles=2")
    a = run(double(0.3, 0.05, 0.2, 0.05), motion)
    b = run(System.with_isolator(**BLOCK, isolator=FrictionPendulum(radius=0.5, friction_coefficient=0.05)), motion)
    assert a.uplifts > 0 and a.impacts and a.uplifts == b.uplifts and len(a.impacts) == len(b.impacts)
    assert compare_on_grid(a, b) <= CLOSED and _on_grid(a, b, a.u, b.u, 0.005) <= CLOSED
    ea, eb = np.array(a.extras["isolator_events"]), np.array(b.extras["isolator_events"])
    assert ea.shape == eb.shape and np.max(np.abs(ea - eb)) <= CLOSED
    R, mu, u0 = 1.5, 0.005, 0.1
    tr = run(double(1.0, mu, 0.5, mu), None, duration=12.0, u0=u0)
    w, amplitude = math.sqrt(G / R), u0
    for k, (t, phase, u) in enumerate(tr.extras["isolator_events"], start=1):
        amplitude -= 2 * mu * R
        assert abs(t - k * math.pi / w) <= CLOSED and abs(u - (-1) ** k * amplitude) <= CLOSED * u0


def series_free_vibration(r_lo, mu_lo, r_hi, mu_hi, u0, n_half):
    """The events of the two surfaces in series, free vibration from u0 > 0 reached by a slow push
    (both slid that way), per Fenz & Constantinou, in closed form: [(t, kind, u)], kind "both"
    (the second surface starts to slide) or "stop" (the base stops). Regime I (only lo, hi stuck
    at u_hi): M ü = −W(u − u_hi)/R_lo − σ μ_lo W, until F − W u_hi/R_hi = σ μ_hi W; regime II:
    M ü = −W(u + σ(μ_lo R_lo + μ_hi R_hi))/(R_lo + R_hi), until u̇ = 0, where u_hi = R_hi(F/W − σμ_hi)."""
    R = r_lo + r_hi
    w1, w2 = math.sqrt(G / r_lo), math.sqrt(G / R)
    sigma = 1.0
    u_hi = r_hi * ((u0 + mu_lo * r_lo + mu_hi * r_hi) / R - mu_hi)  # after the push
    t, x, out = 0.0, u0, []
    for _ in range(n_half):
        sigma = -sigma
        if abs((x - u_hi) / r_lo) <= mu_lo:  # F = 0 at rest: lo holds (and hi, whose margin is larger)
            break
        c = u_hi - sigma * mu_lo * r_lo  # regime I's centre
        u_t = u_hi + r_lo * (u_hi / r_hi + sigma * (mu_hi - mu_lo))  # where hi starts to slide
        if sigma * (u_t - (2 * c - x)) >= 0:  # regime I turns before: a half cycle of ω1
            t, x = t + math.pi / w1, 2 * c - x
            out.append((t, "stop", x))
            continue
        t1 = math.acos((u_t - c) / (x - c)) / w1
        v1 = -(x - c) * w1 * math.sin(w1 * t1)
        out.append((t + t1, "both", u_t))
        c2 = -sigma * (mu_lo * r_lo + mu_hi * r_hi)
        A = math.hypot(u_t - c2, v1 / w2)
        phi0 = math.atan2(-v1 / w2, u_t - c2)  # u − c2 = A cos(w2 τ + phi0)
        tau = ((math.pi if sigma < 0 else 2 * math.pi) - phi0) % (2 * math.pi) / w2
        t, x = t + t1 + tau, c2 + (-A if sigma < 0 else A)
        F = G * (x + sigma * (mu_lo * r_lo + mu_hi * r_hi)) / R  # per unit mass, = W(…)/(R M)
        u_hi = r_hi * (F / G - sigma * mu_hi)
        out.append((t, "stop", x))
    return out


@PATHS
@pytest.mark.parametrize("surfaces", [(1.0, 0.005, 2.0, 0.015), (2.0, 0.015, 1.0, 0.005), (0.5, 0.004, 3.0, 0.01)],
                         ids=["lo-first", "hi-first", "small-R-lo"])
def test_double_pendulum_regimes_against_the_series_model(run, surfaces):
    """μ1 ≠ μ2, free vibration from a push to u0: every event of the run (the second surface
    starting to slide, the base stopping) at the series model's time and place; after each
    reversal regime I lasts 2(μ_hi − μ_lo)·R_lo of travel (the loop's transition displacement).
    Which surface is given first does not matter (the series is symmetric)."""
    iso = DoubleFrictionPendulum(*surfaces)
    r_lo, mu_lo, r_hi, mu_hi = iso.series
    u0 = 0.3
    expected = series_free_vibration(r_lo, mu_lo, r_hi, mu_hi, u0, 100)  # to the stop that holds
    tr = run(System.with_isolator(**BLOCK, isolator=iso), None, duration=expected[-1][0] + 1.0, u0=u0)
    events = tr.extras["isolator_events"]
    assert len(expected) >= 6 and any(kind == "both" for _, kind, _ in expected[2:])
    got = [(t, "both" if abs(phase) == 2 else "stop", u) for t, phase, u in events]
    assert len(got) == len(expected)
    for (t, kind, u), (te, ke, ue) in zip(got, expected):
        assert kind == ke and abs(t - te) <= CLOSED and abs(u - ue) <= CLOSED * u0
    for (_, k0, x), (_, k1, u) in zip(got[1:], got[2:]):
        if k0 == "stop" and k1 == "both":
            assert abs(abs(u - x) - 2 * (mu_hi - mu_lo) * r_lo) <= CLOSED * u0
    assert tr.energy.relative_residual <= ENERGY


# --- energy, rocking included ----------------------------------------------------------------

@pytest.mark.parametrize("system, motion", [
    (cone(0.3, 0.1), "sine:amp=0.6,freq=1.5,cycles=2"),
    (cone(0.4, 0.1), "ricker:amp=0.9,freq=2.0"),
    (double(0.4, 0.05, 1.0, 0.12), "sine:amp=0.6,freq=1.0,cycles=3"),
    (double(1.0, 0.25, 0.5, 0.4), "sine:amp=0.9,freq=2.0,cycles=3"),
], ids=["cone", "cone-ricker", "double", "double-pinned"])
@PATHS
def test_energy_balance_closes_with_the_rolling_and_sliding_work(system, motion, run):
    """E(t) − E(0) = ground work − impacts − the isolator's slip work (E with F_c·|u| and the
    element's spring), to 1e-10 of the energy involved, through uplifts, impacts and stick–slip."""
    tr = run(system, load_motion(motion))
    assert tr.uplifts > 0 and tr.impacts and tr.energy.isolator_loss[-1] > 0
    assert tr.energy.relative_residual <= ENERGY


# --- the command line --------------------------------------------------------------------------

PAPER = ["--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]


@pytest.mark.parametrize("args, kind", [
    (["--isolator", "ball-in-cone", "--slope", "0.15", "--rolling-resistance", "0.05"], "ball-in-cone"),
    (["--isolator", "ball-in-bowl", "--radius", "1.0", "--rolling-resistance", "0.02"], "ball-in-bowl"),
    (["--isolator", "double-friction-pendulum", "--radius", "1.0", "--friction-coefficient", "0.02",
      "--radius-2", "2.0", "--friction-coefficient-2", "0.06"], "double-friction-pendulum"),
])
@pytest.mark.parametrize("engine", [[], ["--engine", "analytic-reference"]], ids=["kernel", "reference"])
def test_run_takes_the_new_isolators(args, kind, engine, capsys):
    code = main(["run", *PAPER, *args, "--motion", "sine:amp=0.3,freq=1.0,cycles=1", "--quiet", "--json", "-",
                 *engine])
    assert code == 0
    d = json.loads(capsys.readouterr().out)
    assert d["system"]["isolator"] == kind and d["energy_lost_in_isolator"] > 0


@pytest.mark.parametrize("args, first", [
    (["--isolator", "ball-in-cone", "--slope", "2", "--rolling-resistance", "0.05"], "slope = 2"),
    (["--isolator", "ball-in-cone", "--slope", "0.1", "--rolling-resistance", "-1"], "rolling_resistance = -1"),
    (["--isolator", "ball-in-cone", "--rolling-resistance", "0.05"], "--slope"),
    (["--isolator", "ball-in-cone", "--slope", "0.1", "--radius", "1"], "--radius"),
    (["--isolator", "ball-in-cone", "--slope", "0.1", "--period", "2"], "--period"),
    (["--isolator", "ball-in-bowl", "--radius", "0", "--rolling-resistance", "0.05"], "radius = 0"),
    (["--isolator", "ball-in-bowl", "--radius", "1", "--friction-coefficient", "0.05"], "--friction-coefficient"),
    (["--isolator", "double-friction-pendulum", "--radius", "1", "--friction-coefficient", "0.02",
      "--radius-2", "1"], "--friction-coefficient-2"),
    (["--isolator", "double-friction-pendulum", "--radius", "1", "--friction-coefficient", "0.02",
      "--radius-2", "-1", "--friction-coefficient-2", "0.05"], "radius_2 = -1"),
    (["--slope", "0.1", "--period", "2", "--damping-ratio", "0.1"], "--slope"),
    (["--isolator", "ball-in-cone", "--slope", "0.1", "--engine", "mujoco"], "isolator = ball-in-cone"),
])
def test_run_refuses_bad_options_in_one_line(args, first, capsys):
    code = main(["run", *PAPER, *args])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and first in err, err
