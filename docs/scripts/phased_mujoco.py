"""MuJoCo's phased stepping (Settings.phased, mujoco_models/phases.py) against full
stepping, side by side on the golden scenarios, Kobe 40 s (isolated and fixed base), the
report's Ricker pulse and free rocking: θmax/α, counted impacts, first uplift, worst β
error against the analytic model, and the median wall time of REPEATS runs each.

    nice -n 5 python docs/scripts/phased_mujoco.py [--repeats 5]
"""
from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import replace

from isorock.analytic.hybrid import AnalyticSettings
from isorock.analytic.system import paper_system
from isorock.mujoco_models import Settings
from isorock.validate.core.compare import compare
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import KOBE, REPORT_MOTIONS, Scenario, golden_scenarios


def scenarios():
    out = list(golden_scenarios())
    for fixed in (False, True):
        out.append(Scenario("ricker" + ("_fixed" if fixed else "_isolated"), paper_system(fixed_base=fixed),
                            REPORT_MOTIONS[1], 8.0))
        if KOBE.is_file():
            out.append(Scenario("kobe40" + ("_fixed" if fixed else "_isolated"), paper_system(fixed_base=fixed),
                                str(KOBE), 40.0))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    ref_settings = AnalyticSettings(rtol=1e-12, atol=1e-14)
    print("| scenario | stepping | θmax/α | Δθmax/α vs full | impacts (analytic) | first uplift s (Δ vs full) "
          "| worst β err (4) | wall s (median) | sim s / wall s |")
    print("|---|---|---|---|---|---|---|---|---|")
    run = get_engine("mujoco").simulate
    for sc in scenarios():
        motion = sc.ground_motion()
        ref = get_engine("analytic").simulate(sc.system, motion, settings=ref_settings,
                                              duration=sc.duration, theta0=sc.theta0)
        full = None
        for label, settings in (("full", Settings()), ("phased", replace(Settings(), phased=True))):
            walls = []
            for _ in range(args.repeats):
                t = time.perf_counter()
                traj = run(sc.system, motion, settings=settings, duration=sc.duration, theta0=sc.theta0)
                walls.append(time.perf_counter() - t)
            c = compare(traj, ref)
            berr = [abs(e) for e in c.beta_errors[:4]]
            wall = statistics.median(walls)
            if full is None:
                full = c
            dtheta = c.theta_max_over_alpha - full.theta_max_over_alpha
            dup = (c.first_uplift - full.first_uplift) if (c.first_uplift is not None and full.first_uplift is not None) else None
            print(f"| {sc.name} | {label} | {c.theta_max_over_alpha:.4f} | {dtheta:+.1e} | {c.impacts} ({c.impacts_ref}) "
                  f"| {c.first_uplift if c.first_uplift is None else round(c.first_uplift, 4)}"
                  f" ({'–' if dup is None else f'{dup * 1e3:+.2f} ms'}) "
                  f"| {max(berr) * 100 if berr else float('nan'):.3f}% | {wall:.3f} | {sc.duration / wall:.0f} |", flush=True)


if __name__ == "__main__":
    main()
