"""DART on the friction pendulum and the ball in a bowl (dart_models._Pendulum: the spring W/R a joint
force, the slider the base joint's Coulomb friction) against the exact model (engine "analytic"): the
base's peak |u|, its history max |Δu|/u_max, where it ends, and θmax/α and the counted impacts where
the block rocks; CPU seconds of DART's run. The cases of docs/dart.md, "Pendulum isolators"
(docs/scripts/pendulum_cases.py, Drake's too), then with no CASE given "pulse-rest" under a 0.2 m and
a 10 m block (width 0.35·H; DART's step and time unit follow the block, Settings.for_system).

    python docs/scripts/dart_pendulum.py [--timestep S] [--height H] [CASE ...]
"""
from __future__ import annotations

import argparse

from pendulum_cases import CASES, HEADER, HEIGHT, measure, row

from isorock.dart_models import Settings, settings_for


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", help=f"of {', '.join(CASES)} (default: every case, and the heights)")
    ap.add_argument("--timestep", type=float, default=None, help="DART's step in seconds (default: following the body)")
    ap.add_argument("--height", type=float, default=2.0, help="the block's height (m)")
    a = ap.parse_args()
    unknown = [c for c in a.cases if c not in CASES]
    if unknown:
        ap.error(f"unknown case {', '.join(unknown)}: one of {', '.join(CASES)}")
    settings = settings_for(timestep=a.timestep) if a.timestep else Settings()
    print(HEADER)
    HEIGHT[0] = a.height
    for name in a.cases or CASES:
        print(row(measure(name, "dart", settings)))
    if not a.cases:
        for h in (0.2, 10.0):
            HEIGHT[0] = h
            r = measure("pulse-rest", "dart", settings)
            print(row(dict(r, case=f"pulse-rest, H {h:g} m")))


if __name__ == "__main__":
    main()
