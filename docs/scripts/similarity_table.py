"""The similarity case of tests/test_similarity.py (λ 4, μ 1, T·p 12, ξ 0.1, θ0 0.6α, free
rocking for 15/p) at H 0.1, 1 and 10 m, each engine at its defaults against the analytic
model: the first impact's t·p error, the largest half-cycle peak difference (θ/α), the
worst per-impact β error of the first 4 counted impacts, and the counted impacts.

    python docs/scripts/similarity_table.py [--engines analytic,mujoco,bullet,mujoco:absolute,bullet:absolute]
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from test_similarity import HEIGHTS, SPAN, THETA0, _case  # noqa: E402  (the test's own case)

from isorock.validate.core.engines import resolve  # noqa: E402
from isorock.validate.core.measure import beta_errors  # noqa: E402


def row(label: str, height: float, fixed: bool) -> str:
    engine, settings = resolve(label)
    system = _case(height, fixed)
    run = dict(duration=SPAN / system.p, theta0=THETA0 * system.alpha)
    tr = engine.simulate(system, None, settings=settings, **run)
    ref = resolve("analytic")[0].simulate(system, None, **run)
    tp, tp_ref = (np.array([i.t * system.p for i in x.counted_impacts]) for x in (tr, ref))
    amp, amp_ref = (np.array([i.amplitude / system.alpha for i in x.counted_impacts]) for x in (tr, ref))
    n = min(len(tp), len(tp_ref))
    errors = [abs(e) for e in beta_errors(tr, 4) if np.isfinite(e)]
    return (f"| {label} | {'fixed' if fixed else 'isolated'} | {height:g} | {100 * (tp[0] / tp_ref[0] - 1):+.4f}% | "
            f"{np.max(np.abs(amp[:n] - amp_ref[:n])):.2e} | {100 * max(errors):.3f}% | {len(tp)}/{len(tp_ref)} |")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--engines", default="mujoco,bullet,mujoco:absolute,bullet:absolute")
    a = ap.parse_args()
    print("| engine | base | H (m) | t₁·p error | peaks /α | worst β error (4 impacts) | impacts (analytic) |")
    print("|---|---|---|---|---|---|---|")
    for label in a.engines.split(","):
        for fixed in (True, False):
            for h in HEIGHTS:
                print(row(label, h, fixed), flush=True)
