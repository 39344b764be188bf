"""The bilinear bearing's steady state under harmonic input against the independent oracle
(tests/bilinear_oracle.py): the measured errors of docs/isolators.md, "Bilinear steady state
under harmonic input", for both analytic engines, with the same cases and helpers as
tests/test_bilinear_steady_state.py.

    python docs/scripts/bilinear_steady_state.py                     # the table
    python docs/scripts/bilinear_steady_state.py --perturb-u-y 1e-6  # the oracle's u_y × (1 + 1e-6):
                                                                     # the errors must leap past 1e-9
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
import test_bilinear_steady_state as t  # noqa: E402
from bilinear_oracle import Bearing, linear_steady_state  # noqa: E402


def steady_errors(run, amp, freq, oracle_u_y):
    s = Bearing(t.M, t.C, t.K0, t.R, oracle_u_y, amp * t.G, 2 * math.pi * freq).steady_state()
    T, U = s.case.period, s.U
    tr = t.run_on_orbit(run, s, amp, freq, 3)  # the engines' bearing is the test's, whatever the oracle's u_y
    ev = [e for e in tr.extras["isolator_events"] if e[0] < 3 * T - 1e-6]
    peaks = [abs(ti - (k // 2 + 1) * 0.5 * T) for k, (ti, _, _) in enumerate(ev) if k % 2]
    yields = [abs(ti - (s.t_yield + k // 2 * 0.5 * T)) for k, (ti, _, _) in enumerate(ev) if k % 2 == 0]
    yield_u = [abs(abs(u) - (U - 2 * oracle_u_y)) / U for k, (_, _, u) in enumerate(ev) if k % 2 == 0]
    e = tr.energy
    loop = max(abs(t.per_cycle(tr, e.isolator_loss, k, T) / s.loop_area - 1) for k in range(3))
    work = max(abs((t.per_cycle(tr, e.ground_work, k, T) - t.per_cycle(tr, e.dashpot_loss, k, T)) / s.loop_area - 1)
               for k in range(3))
    w_in, visc = s.work_per_cycle()
    return dict(U=U, tau=s.tau, t_yield=s.t_yield, loop=s.loop_area, uplifts=tr.uplifts, events=len(ev),
                amplitude=abs(tr.u_max / U - 1), peaks=max(peaks), yields=max(yields), yield_u=max(yield_u),
                history=float(np.max(np.abs(tr.u - t.oracle_u(s, tr.t))) / U), loop_err=loop, work_err=work,
                oracle_balance=abs((w_in - visc) / s.loop_area - 1), a_max=s.max_abs_acceleration())


def linear_errors(run, limit):
    amp, freq = (0.005, 0.8) if limit == "elastic" else (0.1, 0.8)
    r = t.R if limit == "elastic" else 1 - 1e-12
    k = t.K0 if limit == "elastic" else r * t.K0
    w = 2 * math.pi * freq
    X, phi = linear_steady_state(t.M, t.C, k, amp * t.G, w)
    T = 2 * math.pi / w
    tr = run(t.system(r=r), t.sine(amp, freq, 0.0, 3 * T), duration=3 * T, u0=X * math.sin(phi),
             u_dot0=-X * w * math.cos(phi))
    X_run, phi_run = t.fitted(tr, w)
    return dict(X=X, phi=phi, amplitude=abs(X_run / X - 1), phase=abs(phi_run - phi), u_max=abs(tr.u_max / X - 1),
                history=float(np.max(np.abs(tr.u + X * np.sin(w * tr.t - phi)))) / X,
                events=len(tr.extras["isolator_events"]))


def uplift_errors(run):
    a_star, thr = t.boundary()
    below = t.orbit(0.99 * a_star, 0.8)
    above = t.orbit(1.01 * a_star, 0.8)
    n_below = t.run_on_orbit(run, below, 0.99 * a_star, 0.8, 2, block=t.SLENDER).uplifts
    tr = t.run_on_orbit(run, above, 1.01 * a_star, 0.8, 1, block=t.SLENDER)
    t_lift = above.first_time_above(thr) - above.tau
    return dict(a_star=a_star, below=n_below, above=tr.uplifts, t_lift=t_lift,
                lift_err=abs(tr.uplift_times[0] - t_lift) if tr.uplifts else math.nan,
                a_below=below.max_abs_acceleration() / thr, a_above=above.max_abs_acceleration() / thr)


def settle_errors(amp, freq, periods):
    """The kernel from rest: the last two cycles' peaks against the orbit's ±U at τ + kT/2."""
    s, T = t.orbit(amp, freq), 1.0 / freq
    tr = t.simulate_fast(t.system(), t.sine(amp, freq, 0.0, periods * T), duration=periods * T)
    peaks = [(ti, u) for ti, phase, u in tr.extras["isolator_events"] if phase == 0][-4:]
    return (max(abs(abs(u) / s.U - 1) for _, u in peaks),
            max(abs(((ti - s.tau) + 0.25 * T) % (0.5 * T) - 0.25 * T) for ti, _ in peaks))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--perturb-u-y", type=float, default=0.0,
                    help="relative change of the oracle's u_y (not the engines'): shows the checks can fail")
    args = ap.parse_args()
    runs = [("reference", t.simulate)] + ([("kernel", t.simulate_fast)] if t.simulate_fast else [])
    oracle_u_y = t.U_Y * (1 + args.perturb_u_y)
    print(f"limit ('analytic', 'bilinear_steady_state') = {t.LIMIT:g}; bearing k0 {t.K0:g} N/m, r {t.R}, "
          f"u_y {t.U_Y} m, c {t.C:.1f} N·s/m (5% of critical on k0), M {t.M:g} kg; oracle u_y {oracle_u_y!r}")
    for amp, freq in t.CASES:
        for name, run in runs:
            d = steady_errors(run, amp, freq, oracle_u_y)
            print(f"{amp} g, {freq} Hz, {name}: U {d['U']:.10g} m, τ {d['tau']:.10g} s, t_yield {d['t_yield']:.10g} s,"
                  f" loop {d['loop']:.10g} J, max|a| {d['a_max']:.4g} m/s², uplifts {d['uplifts']}, events "
                  f"{d['events']}\n    amplitude {d['amplitude']:.2g}; peak (unload) times {d['peaks']:.2g} s; "
                  f"yield times {d['yields']:.2g} s; yield u {d['yield_u']:.2g}·U; history {d['history']:.2g}·U; "
                  f"loop area/cycle {d['loop_err']:.2g}; (input − viscous)/cycle {d['work_err']:.2g}; "
                  f"oracle's own balance {d['oracle_balance']:.2g}")
    for limit in ("elastic", "r-to-1"):
        for name, run in runs:
            d = linear_errors(run, limit)
            print(f"{limit}, {name}: X {d['X']:.10g} m, φ {d['phi']:.10g} rad, slider events {d['events']}\n"
                  f"    amplitude {d['amplitude']:.2g}; phase {d['phase']:.2g} rad; u_max {d['u_max']:.2g}; "
                  f"history {d['history']:.2g}·X")
    if t.simulate_fast:
        for amp, freq in t.CASES:
            for periods in (20, 40):
                du, dt = settle_errors(amp, freq, periods)
                print(f"from rest, kernel, {amp} g, {freq} Hz, {periods} periods: last peaks {du:.2g}·U, "
                      f"their times {dt:.2g} s off τ + kT/2")
    for name, run in runs:
        d = uplift_errors(run)
        print(f"uplift boundary, {name}: A* {d['a_star']:.10g} g (tanα 0.1, 0.8 Hz); max|a|/g·tanα "
              f"{d['a_below']:.6f} at 0.99 A*, {d['a_above']:.6f} at 1.01 A*\n    uplifts at 0.99 A*: {d['below']}; "
              f"at 1.01 A*: {d['above']}, first at {d['t_lift']:.10g} s, error {d['lift_err']:.2g} s")


if __name__ == "__main__":
    main()
