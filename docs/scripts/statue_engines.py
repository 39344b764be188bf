"""The contact engines on a statue's own shape, on every base, against the exact model of its
two edges (issue 36; docs/statues.md, "The contact engines on the base and isolator").

Each example statue (bust, amphora, obelisk; 2,600 kg/m³) at 0.5×, 1× and 3× its size, on a
fixed base, a linear isolator (T 2 s, ξ 0.1) and a friction pendulum (R 1.5 m, μ 0.05), its
base as heavy as the statue, under one sine cycle that follows the statue, its amplitude set
per case so that the exact model's θmax/α is 0.05 (--target; validate.tools.statue_check). MuJoCo runs
the statue's convex hull on a free joint in its own block scene (the contact following the
statue, as for the block); Drake the hull's vertices as point-contact spheres on a free body in
its block scene (drake_models/statue.py), on the fixed base and the linear isolator (it refuses
the friction pendulum: the row says so in one line). Printed per case: the exact model's θmax/α spread under ±1% of the
amplitude (chaotic where the report's rule says so: one history cannot judge), the engine's
|Δ θmax/α| and θmax's relative error, its history's largest |Δθ|/α, impacts (exact / engine),
the worst β error against each impact's own edge, the largest wobble out of the plane (|y| in
m, roll and yaw in rad) and the wall time.

    python docs/scripts/statue_engines.py [--engines mujoco,drake] [--statues bust,amphora,obelisk]
"""
from __future__ import annotations

import argparse
import os
import time

from isorock.analytic.errors import InputError
from isorock.validate.tools import statue_check as sc


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--engines", default="mujoco")
    p.add_argument("--statues", default="bust,amphora,obelisk")
    p.add_argument("--sizes", default="0.5,1,3")
    p.add_argument("--bases", default=",".join(sc.BASES))
    p.add_argument("--target", type=float, default=0.05)
    p.add_argument("--base-mass-ratio", type=float, default=1.0,
                   help="the base's mass over the statue's (default 1; below 1: a light plinth)")
    a = p.parse_args()
    start = time.perf_counter()
    print(f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print("| statue | size | base | α₊ / α₋ (rad) | θmax/α spread under ±1% | engine | |Δ θmax/α| (θmax error) "
          "| history |Δθ|/α | impacts | worst β error | out of plane | wall (s) |")
    print("|---|---:|---|---|---:|---|---:|---:|---|---:|---:|---:|")
    for name in a.statues.split(","):
        for size in (float(x) for x in a.sizes.split(",")):
            for base in a.bases.split(","):
                _, system = sc.example(name, size, base, base_mass_ratio=a.base_mass_ratio)
                k = sc.amplitude_for(system, a.target)
                motion = sc.pulse(system, k)
                steady, spread = sc.robust(system, motion)
                for engine in a.engines.split(","):
                    head = (f"| {name} | {size:g}× | {base} | {system.body.alpha(1):.3f} / {system.body.alpha(-1):.3f} | "
                            f"{spread:.3f}{'' if steady else ' (chaotic)'} | {engine} | ")
                    try:
                        r = sc.compare(system, motion, engine)
                    except InputError as exc:  # an engine that does not carry this base: its one line
                        print(f"{head}refused: {str(exc).splitlines()[0]} |||||", flush=True)
                        continue
                    print(f"{head}"
                          f"{r['theta_max_diff']:.4f} ({r['theta_max_rel_error']:+.2%}) | {r['history_error']:.4f} | "
                          f"{r['exact_impacts']} / {r['impacts']} | {r['beta_rel_error']:.2%} | {r['out_of_plane']:.1e} | "
                          f"{r['wall_s']:.1f} |",
                          flush=True)
    print(f"{time.perf_counter() - start:.0f} s in all, load {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
