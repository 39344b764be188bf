"""The pendulum isolator cases a contact engine is measured on against the exact model (engine
"analytic"), shared by docs/scripts/drake_pendulum.py and docs/scripts/dart_pendulum.py (docs/drake.md,
"Pendulum isolators: a held puck"; docs/dart.md, "Pendulum isolators"):

- "pulse-rest": the 2 m block (m = m_b = 1000 kg) on R 1 m, μ 0.05 under
  sine:amp=0.4,freq=1,cycles=2 for 4 s (the pair tests' case, tests/test_two_components.py);
- "kobe-rest": the paper's block (3800 kg) on R 2 m, μ 0.05 under the first 12 s of Kobe
  (../shared/data/records/RSN1106_KOBE_KJM000.AT2, PGA 0.83 g) and 5 s of tail;
- "sine-rocking": the paper's block on R 0.5 m, μ 0.2 under sine:amp=0.6,freq=1.3,cycles=2, 5 s;
- "kobe-threshold": the paper's block on R 0.5 m, μ 0.2 under the same Kobe window;
- "bowl-rest": the 2 m block on a ball in a bowl R 1.5 m, μ_r 0.03, the pulse, 4 s.

HEIGHT[0]: every case's block that tall (width 0.35·H, the 2 m block's slenderness).
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from isorock.analytic.motion import GroundMotion, load_motion
from isorock.analytic.system import BallInBowl, FrictionPendulum, System
from isorock.validate.core.engines import get_engine

KOBE = Path(__file__).resolve().parents[3] / "shared" / "data" / "records" / "RSN1106_KOBE_KJM000.AT2"
PULSE = "sine:amp=0.4,freq=1.0,cycles=2"


def _kobe(seconds: float = 12.0) -> GroundMotion:
    m = load_motion(str(KOBE))
    return GroundMotion.from_array(np.asarray(m.acceleration)[:int(round(seconds / m.dt))], dt=m.dt, name="kobe-12s")


HEIGHT = [2.0]


def _block(mass, isolator):
    h = HEIGHT[0]
    return System.with_isolator(height=h, width=0.35 * h, mass=mass, base_mass=mass, isolator=isolator)


CASES = {
    "pulse-rest": lambda: (_block(1000.0, FrictionPendulum(1.0, 0.05)), load_motion(PULSE), 4.0),
    "kobe-rest": lambda: (_block(3800.0, FrictionPendulum(2.0, 0.05)), _kobe(), None),
    "sine-rocking": lambda: (_block(3800.0, FrictionPendulum(0.5, 0.2)),
                             load_motion("sine:amp=0.6,freq=1.3,cycles=2"), 5.0),
    "kobe-threshold": lambda: (_block(3800.0, FrictionPendulum(0.5, 0.2)), _kobe(), None),
    "bowl-rest": lambda: (_block(1000.0, BallInBowl(1.5, 0.03)), load_motion(PULSE), 4.0),
}

HEADER = ("| case | u_max rel err | max |Δu|/u_max | u end (exact) m | θmax/α (exact) | impacts (exact) | CPU s |\n"
          "|---|---|---|---|---|---|---|")


def measure(name: str, engine: str, settings) -> dict:
    """Case `name` on `engine` with `settings` against the exact model; CPU seconds of the engine's
    run (time.process_time: other load on the machine does not count)."""
    system, motion, duration = CASES[name]()
    exact = get_engine("analytic").simulate(system, motion, duration=duration)
    start = time.process_time()
    run = get_engine(engine).simulate(system, motion, duration=duration, settings=settings)
    cpu = time.process_time() - start
    u = np.interp(run.t, exact.t, exact.u)
    return dict(case=name, status=str(run.status), cpu_s=cpu, u_max=run.u_max, u_max_exact=exact.u_max,
                u_max_rel=run.u_max / exact.u_max - 1, u_history=float(np.max(np.abs(run.u - u)) / exact.u_max),
                u_end=float(run.u[-1]), u_end_exact=float(exact.u[-1]), theta=run.theta_max_over_alpha,
                theta_exact=exact.theta_max_over_alpha, impacts=run.impact_count, impacts_exact=exact.impact_count)


def row(r: dict) -> str:
    """One markdown row of `measure`'s result."""
    return (f"| {r['case']} | {r['u_max_rel']:+.2e} | {r['u_history']:.2e} | {r['u_end']:.5f} ({r['u_end_exact']:.5f}) "
            f"| {r['theta']:.4f} ({r['theta_exact']:.4f}) | {r['impacts']} ({r['impacts_exact']}) | {r['cpu_s']:.1f} |")
