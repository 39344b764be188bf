"""The rolling isolators' and the double concave pendulum's closed-form errors, on both analytic
paths, as quoted in docs/isolators.md (tests/test_rolling_and_double_isolators.py asserts the
same closed forms to 1e-9; the oracles are that file's, imported, not copied).

    python docs/scripts/rolling_double_closed_forms.py
"""
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from agreement_cases import _on_grid  # noqa: E402
from test_rolling_and_double_isolators import (G, M, cone, cone_decay, cone_without_friction,  # noqa: E402
                                               double, series_free_vibration)

from isorock.analytic import load_motion, physics  # noqa: E402
from isorock.analytic.fast import compare_on_grid, simulate_fast  # noqa: E402
from isorock.analytic.hybrid import simulate  # noqa: E402
from isorock.analytic.system import (PAPER_BLOCK, BallInBowl, DoubleFrictionPendulum,  # noqa: E402
                                     FrictionPendulum, System)

PATHS = (("reference", simulate), ("kernel", simulate_fast))


def row(name, **errors):
    print(f"{name}: " + ", ".join(f"{k} {v:.2g}" for k, v in errors.items()), flush=True)


for label, run in PATHS:
    print(f"--- {label}")
    slope = 0.1
    for u0 in (0.02, 0.08):  # μ_r = 0: parabolas, period 4√(2u0/(g tanφ))
        tq = math.sqrt(2 * u0 / (G * slope))
        tr = run(cone(slope, 0.0), None, duration=8 * tq + 0.01, u0=u0)
        ev = tr.extras["isolator_events"]
        row(f"cone tanφ 0.1 μ_r 0 u0 {u0}: period {4 * tq:.4f} s",
            u_rel=np.max(np.abs(tr.u - cone_without_friction(tr.t, u0, G * slope))) / u0,
            t_events=max(abs(t - k * tq) for k, (t, _, _) in enumerate(ev, 1)),
            energy=tr.energy.relative_residual)
    slope, mu_r, u0 = 0.15, 0.05, 0.1
    tr = run(cone(slope, mu_r), None, duration=4.0, u0=u0)
    ev = tr.extras["isolator_events"]
    exp = cone_decay(u0, slope, mu_r, 20)
    rho = (slope - mu_r) / (slope + mu_r)
    down, up = G * (slope - mu_r), G * (slope + mu_r)
    t_inf = (math.sqrt(2 * u0 / down) + math.sqrt(2 * rho * u0 / up)) / (1 - math.sqrt(rho))
    row(f"cone tanφ 0.15 μ_r 0.05 u0 0.1: {len(ev)} events, rest at {ev[-1][0]:.6f} s (T∞ {t_inf:.6f})",
        t_events=max(abs(a[0] - b[0]) for a, b in zip(ev, exp)),
        u_rel=max(abs(a[2] - b[1]) for a, b in zip(ev, exp)) / u0,
        T_inf_minus_rest=t_inf - ev[-1][0],
        loss_rel=abs(tr.energy.isolator_loss[-1] / (slope * M * G * u0) - 1),
        energy=tr.energy.relative_residual)
    kobe = load_motion(str(Path(__file__).resolve().parents[2].parent / "shared" / "data" / "records" / "KOBE_NS"))
    system = cone(0.15, 0.05)
    sp, ip = physics.isolator_params(system, 1e-5)
    start = time.perf_counter()
    tr = run(system, kobe)
    wall = time.perf_counter() - start
    a = np.array([physics.isolator_base_acceleration(sp, ip, int(p), u, ud, 0.0, kobe.at(t))
                  for p, u, ud, t in zip(tr.extras["isolator_phase"], tr.u, tr.u_dot, tr.t)])
    row(f"cone tanφ 0.15 μ_r 0.05 Kobe JMA: uplifts {tr.uplifts}, u_max {tr.u_max:.4f} m, "
        f"{len(tr.extras['isolator_events'])} events, wall {wall:.2f} s",
        max_a_over_bound=np.max(np.abs(a)) / (0.2 * G) - 1, energy=tr.energy.relative_residual)
    motion = load_motion("sine:amp=0.6,freq=1.5,cycles=2")
    a = run(System.with_isolator(**PAPER_BLOCK, isolator=BallInBowl(0.5, 0.05)), motion)
    b = run(System.with_isolator(**PAPER_BLOCK, isolator=FrictionPendulum(0.5, 0.05)), motion)
    row("bowl R 0.5 μ_r 0.05 = pendulum R 0.5 μ_f 0.05 (sine 0.6 g 1.5 Hz)",
        u=float(np.max(np.abs(a.u - b.u))), theta=float(np.max(np.abs(a.theta - b.theta))))
    a = run(double(0.3, 0.05, 0.2, 0.05), motion)
    b = run(System.with_isolator(**PAPER_BLOCK, isolator=FrictionPendulum(0.5, 0.05)), motion)
    ea, eb = np.array(a.extras["isolator_events"]), np.array(b.extras["isolator_events"])
    row(f"double 0.3/0.05 + 0.2/0.05 = pendulum 0.5/0.05 (sine): {a.uplifts} uplifts, {len(a.impacts)} impacts",
        theta=compare_on_grid(a, b), u=_on_grid(a, b, a.u, b.u, 0.005), events=float(np.max(np.abs(ea - eb))))
    R, mu, u0 = 1.5, 0.005, 0.1
    tr = run(double(1.0, mu, 0.5, mu), None, duration=12.0, u0=u0)
    w, amp, et, eu = math.sqrt(G / R), u0, [], []
    for k, (t, _, u) in enumerate(tr.extras["isolator_events"], 1):
        amp -= 2 * mu * R
        et.append(abs(t - k * math.pi / w))
        eu.append(abs(u - (-1) ** k * amp))
    row(f"double 1.0 + 0.5, μ 0.005, Coulomb decay: {len(et)} events", t_events=max(et), u_rel=max(eu) / u0)
    for surfaces in ((1.0, 0.005, 2.0, 0.015), (2.0, 0.015, 1.0, 0.005), (0.5, 0.004, 3.0, 0.01)):
        iso = DoubleFrictionPendulum(*surfaces)
        r_lo, mu_lo, r_hi, mu_hi = iso.series
        exp = series_free_vibration(r_lo, mu_lo, r_hi, mu_hi, 0.3, 100)
        tr = run(System.with_isolator(**PAPER_BLOCK, isolator=iso), None, duration=exp[-1][0] + 1.0, u0=0.3)
        ev = tr.extras["isolator_events"]
        trans = [abs(abs(u1 - x0) - 2 * (mu_hi - mu_lo) * r_lo) for (_, p0, x0), (_, p1, u1) in zip(ev[1:], ev[2:])
                 if abs(p0) == 1 and abs(p1) == 2]
        row(f"double {surfaces} u0 0.3: {len(ev)} events ({len(exp)} expected), transition "
            f"2(μ_hi − μ_lo)R_lo = {2 * (mu_hi - mu_lo) * r_lo:g} m",
            t_events=max(abs(a[0] - b[0]) for a, b in zip(ev, exp)),
            u_rel=max(abs(a[2] - b[2]) for a, b in zip(ev, exp)) / 0.3, transition=max(trans),
            energy=tr.energy.relative_residual)
    for name, system, m in (("cone 0.3/0.1 sine 0.6 g 1.5 Hz", cone(0.3, 0.1), "sine:amp=0.6,freq=1.5,cycles=2"),
                            ("cone 0.4/0.1 Ricker 0.9 g 2 Hz", cone(0.4, 0.1), "ricker:amp=0.9,freq=2.0"),
                            ("double 0.4/0.05 + 1.0/0.12 sine 0.6 g 1 Hz", double(0.4, 0.05, 1.0, 0.12),
                             "sine:amp=0.6,freq=1.0,cycles=3"),
                            ("double 1.0/0.25 + 0.5/0.4 sine 0.9 g 2 Hz", double(1.0, 0.25, 0.5, 0.4),
                             "sine:amp=0.9,freq=2.0,cycles=3")):
        tr = run(system, load_motion(m))
        row(f"{name}: {tr.uplifts} uplifts, {len(tr.impacts)} impacts, "
            f"{len(tr.extras['isolator_events'])} events", energy=tr.energy.relative_residual)
