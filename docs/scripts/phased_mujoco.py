"""MuJoCo's phased stepping (Settings.phased, mujoco_models/phases.py) against full
stepping (and phased with fine steps throughout its contact phases), side by side on the golden scenarios, Kobe 40 s (isolated and fixed base), the
report's Ricker pulse and free rocking: θmax/α, counted impacts, first uplift, worst β
error against the analytic model, and the median wall time of REPEATS runs each.
With --speed: Kobe 40 s alone and as a batch of 16 (the record scaled 0.6–1.35×,
Engine.simulate_many, threads=2), full against phased, medians of REPEATS; and the raw
cost of one step of the contact scene (mujoco.rollout of the block at rest, no Python).

    nice -n 5 python docs/scripts/phased_mujoco.py [--repeats 5] [--speed]
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


#: full stepping (the contact scene at every timestep), phased with every contact step the
#: timestep, and phased with coarse steps away from impacts (the default, phases.Flight)
STEPPINGS = (("full", replace(Settings(), phased=False, coarse=1)), ("phased, fine", replace(Settings(), coarse=1)),
             ("phased", Settings()))


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
    ap.add_argument("--speed", action="store_true")
    args = ap.parse_args()
    from isorock.mujoco_models import phases
    print(f"phases: F_HIGH {phases.F_HIGH}, LEAD_TIME {phases.LEAD_TIME} s, F_LOW {phases.F_LOW}, "
          f"SETTLE_TIME {phases.SETTLE_TIME} s; coarse {Settings.coarse} steps, IMPACT_ZONE {phases.IMPACT_ZONE}, "
          f"SETTLE_TAUS {phases.SETTLE_TAUS}; repeats {args.repeats}\n")
    if args.speed:
        return speed(args.repeats)
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
        for label, settings in STEPPINGS:
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


def speed(repeats):
    import mujoco
    import numpy as np
    from mujoco import rollout

    from isorock.mujoco_models import build_model
    from isorock.mujoco_models.state import Layout
    eng = get_engine("mujoco")
    print("| base | stepping | one run: sim s / wall s | one run: sim s / CPU s | stepping loop alone (runtime_s): sim s / wall s "
          "| batch of 16, threads=2: sim s / wall s |")
    print("|---|---|---|---|---|---|")
    for fixed in (False, True):
        system = paper_system(fixed_base=fixed)
        motion = Scenario("k", system, str(KOBE), 40.0).ground_motion()
        batch = [(system, motion.scaled(0.6 + 0.05 * i), 40.0, 0.0) for i in range(16)]
        for label, settings in STEPPINGS:
            one, cpu, loop, many = [], [], [], []
            for _ in range(repeats):
                t, c = time.perf_counter(), time.process_time()
                traj = eng.simulate(system, motion, settings=settings, duration=40.0)
                one.append(time.perf_counter() - t)
                cpu.append(time.process_time() - c)
                loop.append(traj.runtime_s)
                t = time.perf_counter()
                out = eng.simulate_many(batch, settings=settings, threads=2)
                many.append(time.perf_counter() - t)
                assert not any(isinstance(o, Exception) for o in out), out
            sim = traj.t[-1]  # a run that overturns stops early
            print(f"| {'fixed' if fixed else 'isolated'} | {label} | {sim / statistics.median(one):.0f} "
                  f"| {sim / statistics.median(cpu):.0f} | {sim / statistics.median(loop):.0f} "
                  f"| {sum(o.t[-1] for o in out) / statistics.median(many):.0f} |", flush=True)
    for fixed in (False, True):  # the floor: rollout's cost per step of the contact scene, nothing else
        system = paper_system(fixed_base=fixed)
        model = build_model(system, Settings())
        lay = Layout(model, system, "planar")
        state = lay.initial_state(model, system, 0.0)
        n = 80_000
        f = np.zeros((1, n, lay.nv))
        per = []
        for _ in range(repeats):
            t = time.perf_counter()
            rollout.rollout(model, mujoco.MjData(model), state, f, control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED)
            per.append((time.perf_counter() - t) / n)
        print(f"raw step, {'fixed' if fixed else 'isolated'} base: {statistics.median(per) * 1e6:.2f} µs "
              f"({5e-4 / statistics.median(per):.0f} sim s / wall s at 5e-4 s)")


if __name__ == "__main__":
    main()
