"""Drake on the friction pendulum and the ball in a bowl (its held puck, drake_models/scene.py
_pendulum_puck) against the exact model (engine "analytic"): the base's peak |u|, its history
max |Δu|/u_max, where it ends, and θmax/α and the counted impacts where the block rocks; CPU
seconds of Drake's run (time.process_time: other load on the machine does not count). The
cases of docs/drake.md, "Pendulum isolators: a held puck" (docs/scripts/pendulum_cases.py).

    python docs/scripts/drake_pendulum.py [--stiction V] [--accuracy A] [--stiffness K] [--height H] [CASE ...]

--height: every case's block H m tall (width 0.35·H, the 2 m block's slenderness), the stiction
tolerance and the contact following it (Settings.for_system).
"""
from __future__ import annotations

import argparse

from pendulum_cases import CASES, HEADER, HEIGHT, measure, row

from isorock.drake_models import Settings


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", help=f"of {', '.join(CASES)} (default: every case)")
    ap.add_argument("--stiction", type=float, default=None, help="isolator_stiction_tolerance (m/s)")
    ap.add_argument("--accuracy", type=float, default=None)
    ap.add_argument("--stiffness", type=float, default=None, help="the point contact's (N/m on the paper's block)")
    ap.add_argument("--height", type=float, default=2.0, help="the block's height (m)")
    a = ap.parse_args()
    HEIGHT[0] = a.height
    unknown = [c for c in a.cases if c not in CASES]
    if unknown:
        ap.error(f"unknown case {', '.join(unknown)}: one of {', '.join(CASES)}")
    kw = {k: v for k, v in (("isolator_stiction_tolerance", a.stiction), ("accuracy", a.accuracy),
                            ("stiffness", a.stiffness)) if v}
    print(HEADER)
    for name in a.cases or CASES:
        print(row(measure(name, "drake", Settings(**kw))))


if __name__ == "__main__":
    main()
