"""Two levers on MuJoCo's speed, measured (docs/mujoco.md, "Where the speed goals stand"):
the constraint solver and friction cone (step cost, whole-run CPU and θmax/α on Kobe 40 s,
the paper's block, both bases), and the rest phase's margins (analytic.rest_phase's F_HIGH,
LEAD_TIME, F_LOW, SETTLE_TIME) against full stepping on the pulse, the Ricker and Kobe
scaled 0.6–1.2, both bases: θmax/α, impacts, first uplift and CPU per run (best of 3).

    python docs/scripts/speed_levers.py [--solvers] [--margins]
"""
from __future__ import annotations

import argparse
import itertools
import time
from dataclasses import replace

from isorock.analytic import rest_phase
from isorock.analytic.hybrid import AnalyticSettings
from isorock.analytic.motion import load_motion
from isorock.analytic.system import paper_system
from isorock.mujoco_models import Settings, phases, stepping
from isorock.validate.core.compare import compare
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import KOBE, REPORT_MOTIONS, Scenario, golden_scenarios

#: (F_HIGH, LEAD_TIME s, F_LOW, SETTLE_TIME s); the first is the default
MARGINS = ((0.7, 0.05, 0.5, 0.1), (0.8, 0.05, 0.5, 0.1), (0.7, 0.02, 0.5, 0.1), (0.7, 0.05, 0.7, 0.05),
           (0.8, 0.02, 0.7, 0.05), (0.85, 0.02, 0.8, 0.03))


def best_cpu(run, repeats=3):
    times, out = [], None
    for _ in range(repeats):
        start = time.process_time()
        out = run()
        times.append(time.process_time() - start)
    return min(times), out


def solvers():
    motion = load_motion(str(KOBE))
    for solver, cone in itertools.product(("Newton", "CG", "PGS"), ("elliptic", "pyramidal")):
        s = Settings(solver=solver, cone=cone)
        step = min(stepping.step_cost(paper_system(), s) for _ in range(5))
        cells = []
        for fixed in (False, True):
            system = paper_system(fixed_base=fixed)
            cpu, raw = best_cpu(lambda: stepping.simulate(system, motion, settings=s, duration=40.0))
            theta = abs(raw.theta).max() / system.alpha
            cells.append(f"{'fixed' if fixed else 'isolated'} {cpu * 1e3:.1f} ms, θmax/α {theta:.4f}")
        print(f"{solver}/{cone}: step {step * 1e6:.2f} µs; " + "; ".join(cells), flush=True)


def set_margins(m):
    rest_phase.F_HIGH, phases.LEAD_TIME, phases.F_LOW, phases.SETTLE_TIME = m


def margins():
    cases = [(g, 1.0) for g in golden_scenarios() if g.theta0 == 0]
    for fixed in (False, True):
        cases.append((Scenario("ricker" + ("_fixed" if fixed else "_isolated"), paper_system(fixed_base=fixed),
                               REPORT_MOTIONS[1], 8.0), 1.0))
        cases += [(Scenario("kobe" + ("_fixed" if fixed else "_isolated"), paper_system(fixed_base=fixed),
                            str(KOBE), 40.0), s) for s in (0.6, 0.8, 1.0, 1.2)]
    mj, an = get_engine("mujoco"), get_engine("analytic")
    for sc, scale in cases:
        motion = sc.ground_motion().scaled(scale)
        ref = an.simulate(sc.system, motion, settings=AnalyticSettings(rtol=1e-12, atol=1e-14),
                          duration=sc.duration, theta0=sc.theta0)
        full = compare(mj.simulate(sc.system, motion, settings=replace(Settings(), phased=False),
                                   duration=sc.duration, theta0=sc.theta0), ref)
        print(f"{sc.name} × {scale}: full stepping θmax/α {full.theta_max_over_alpha:.4f}, impacts "
              f"{full.impacts} ({full.impacts_ref})", flush=True)
        for m in MARGINS:
            set_margins(m)
            cpu, traj = best_cpu(lambda: mj.simulate(sc.system, motion, settings=Settings(), duration=sc.duration,
                                                     theta0=sc.theta0))
            c = compare(traj, ref)
            up = ("–" if c.first_uplift is None or full.first_uplift is None
                  else f"{(c.first_uplift - full.first_uplift) * 1e3:+.2f} ms")
            print(f"  {m}: θmax/α {c.theta_max_over_alpha:.4f} "
                  f"({c.theta_max_over_alpha - full.theta_max_over_alpha:+.1e}), impacts {c.impacts}, "
                  f"first uplift {up}, CPU {cpu * 1e3:.0f} ms", flush=True)
        set_margins(MARGINS[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--solvers", action="store_true")
    ap.add_argument("--margins", action="store_true")
    a = ap.parse_args()
    if a.solvers or not a.margins:
        solvers()
    if a.margins or not a.solvers:
        margins()


if __name__ == "__main__":
    main()
