"""The asymmetric model's RK4 integrator against the exact model on every measured record
(issue 21; since issue 36 the RK4 is the exact model's oracle, tests/asymmetric_rk4.py, and the
study runs the exact model's two edges): the RK4 run as the *symmetric* forward-edge block of each
specimen (α, R, I of the forward edge on both sides, Housner's impact ratio) must give the
exact model's verdict (isorock.analytic, event-driven DOP853 at rtol 1e-10) and its θmax/α.

A record on which the rocking is chaotic has no single right answer at rounding level: the
exact model's own verdict or θmax/α changes when the record is scaled by 1 ± 1e-10
(PERTURBATION). Such tests are counted apart ("sensitive"); the agreement that the
integrator must reach is on the others, and the tolerance on θmax/α is
validate/core/tolerances.py's ("asymmetric", "theta_max_diff").

    nice -n 10 python docs/scripts/asymmetric_agreement.py [DATA] [--substeps 4,8,16]

Exit 1 when a robust test parts (verdict, or θmax/α past the tolerance) at any of the
sub-step counts asked; 2 on bad input. About 45 s of CPU with three sub-step counts.
"""
from __future__ import annotations

import argparse
import importlib.util
import math
import sys
import time
from pathlib import Path

import numpy as np

from isorock.analytic.motion import GroundMotion
from isorock.analytic.system import System
from isorock.validate.tools.experiments import data, processing, specimen, study
from isorock.validate.core.engines import get_engine
from isorock.validate.core.tolerances import tolerance

_ORACLE = Path(__file__).resolve().parents[2] / "tests" / "asymmetric_rk4.py"
_spec = importlib.util.spec_from_file_location("asymmetric_rk4", _ORACLE)
asymmetric = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(asymmetric)

#: the record's relative scaling that tells a chaotic test: far above the exact model's
#: rtol-level error on an impact time (~1e-12 relative), far below any physical change
PERTURBATION = 1e-10


def symmetric_forward(spec) -> dict:
    """asymmetric.parameters of the specimen with both edges its forward one."""
    d = spec.direction(1)
    return dict(asymmetric.parameters(spec), alpha=np.full(2, d["alpha"]), R=np.full(2, d["R"]),
                I=np.full(2, d["I_O"]), ratio=np.full(2, 1 - 1.5 * math.sin(d["alpha"]) ** 2))


def exact_runs(spec, accel: dict, dts: dict, scale: float = 1.0) -> dict:
    d = spec.direction(1)
    system = System.fixed(height=d["block_height"], width=d["block_width"], mass=spec.mass)
    engine = get_engine("analytic")
    out = {}
    for t, a in accel.items():
        m = GroundMotion.from_array(a * scale, dt=dts[t], units="m/s2")
        tr = engine.simulate(system, m, duration=m.end_time + study.PAD)
        out[t] = (bool(tr.overturned), float(tr.theta_max_over_alpha))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data", nargs="?", default=str(study.default_data()))
    ap.add_argument("--substeps", default=str(asymmetric.SUBSTEPS))
    args = ap.parse_args(argv)
    try:
        substeps = [int(x) for x in args.substeps.split(",")]
        outcomes, files = data.load(args.data, None)
    except (ValueError, OSError) as e:  # bad input (InputError is a ValueError): one line, exit 2
        print(f"asymmetric_agreement: {e}", file=sys.stderr)
        return 2
    tol = tolerance("asymmetric", "theta_max_diff").limit
    failed = False
    accel, dts = {}, {}
    for t in sorted(outcomes):
        m = data.read_test(files[t], t)
        accel[t], dts[t] = processing.process(m.acceleration, m.dt), m.dt
    for s in data.SPECIMENS:
        spec = specimen.load_specimen(args.data, s)
        exact = exact_runs(spec, accel, dts)
        sens = {t for k in (1 + PERTURBATION, 1 - PERTURBATION)
                for t, r in exact_runs(spec, accel, dts, k).items()
                if r[0] != exact[t][0] or abs(r[1] - exact[t][1]) > tol}
        p = symmetric_forward(spec)
        for n in substeps:
            start = time.process_time()
            runs = {t: asymmetric.simulate(p, a, dts[t], pad=study.PAD, substeps=n) for t, a in accel.items()}
            cpu = time.process_time() - start
            robust = [t for t in accel if t not in sens]
            if n == substeps[0]:
                print(f"SP{s} sensitive tests: {sorted(sens)}")
            bad = [t for t in robust if runs[t][0] != exact[t][0]]
            bad_s = [t for t in sens if runs[t][0] != exact[t][0]]
            dev = [abs(runs[t][1] - exact[t][1]) for t in robust if not exact[t][0] and not runs[t][0]]
            far = [t for t in robust if not exact[t][0] and abs(runs[t][1] - exact[t][1]) > tol]
            print(f"SP{s} substeps {n}: verdicts differ on {len(bad)} of {len(robust)} robust tests {bad}"
                  f" and {len(bad_s)} of {len(sens)} sensitive ones {sorted(bad_s)}; |Δθmax/α| on robust standing"
                  f" tests max {max(dev):.1e}, median {np.median(dev):.0e}, {len(far)} past {tol:g} {far};"
                  f" {cpu:.1f} s CPU for {len(accel)} runs", flush=True)
            failed |= bool(bad or far)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
