"""PyBullet's phased stepping (Settings.phased, bullet_models/rest.py) against stepping
Bullet throughout, on the paper's block (isolated and fixed): the report's robust sine
and Ricker, and Kobe 40 s. θmax/α, counted impacts and the first uplift against the
analytic model's, and simulated s per CPU s of each whole call (measuring included).

    nice -n 5 python docs/scripts/phased_bullet.py
"""
from __future__ import annotations

import time

from isorock.analytic import paper_system
from isorock.analytic.motion import load_motion
from isorock.bullet_models import Settings
from isorock.validate.core.compare import first_tilt
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import KOBE, REPORT_MOTIONS, ROBUST_SINE


def main():
    bullet, analytic = get_engine("bullet"), get_engine("analytic")
    print("| motion | base | exact θmax/α, impacts, first uplift s | stepping | θmax/α | impacts | first uplift s "
          "| sim s / CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    cases = [("robust sine", ROBUST_SINE, None), ("Ricker", REPORT_MOTIONS[1], None)]
    if KOBE.is_file():
        cases.append(("Kobe 40 s", str(KOBE), 40.0))
    for fixed in (False, True):
        system = paper_system(fixed_base=fixed)
        for name, spec, duration in cases:
            motion = load_motion(spec)
            duration = duration or motion.end_time + 2.0
            ref = analytic.simulate(system, motion, duration=duration)
            exact = f"{ref.theta_max_over_alpha:.4f}, {ref.impact_count}, {first_tilt(ref):.4f}"
            for label, settings in (("throughout", Settings(phased=False)), ("phased", Settings())):
                start = time.process_time()
                traj = bullet.simulate(system, motion, settings=settings, duration=duration)
                cpu = time.process_time() - start
                print(f"| {name} | {'fixed' if fixed else 'isolated'} | {exact} | {label} | "
                      f"{traj.theta_max_over_alpha:.4f} | {traj.impact_count} | {first_tilt(traj):.4f} | "
                      f"{traj.t[-1] / cpu:.0f} |", flush=True)


if __name__ == "__main__":
    main()
