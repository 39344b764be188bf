"""Every non-linear isolator coupled with rocking against the energy balance (issue 39): seeded
random systems × pulses (tests/agreement_cases.isolator_cases, the kernel agreement's draw) on
the compiled kernel, and optionally the first few rocking cases of each kind on the reference.

    python docs/scripts/isolator_energy_grid.py [--cases 500] [--seed 39] [--reference 0] [--kinds A,B]

Prints, per isolator kind, the runs, how many rock (lift at least once), the statuses, the
relative energy residual's distribution over the rocking runs (EnergyLog.relative_residual:
the largest |E(t) − E(0) − ground work + losses| over the largest energy involved), how many
exceed limits.ENERGY_BALANCE_LIMIT, and the count that matters: runs whose balance fails but
that say `completed` or `overturned` (the goal: 0), and, beside, the runs (not failed) whose isolator
loss fell somewhere: a slip pushed along by its own friction, which the balance cannot see. Exit
1 when the first count is not 0.
"""
import argparse
import sys
import time
from pathlib import Path

import numpy as np

# the cases are test code, kept beside the tests (not in the product)
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from agreement_cases import isolator_cases  # noqa: E402

from isorock.analytic.fast import simulate_fast  # noqa: E402
from isorock.analytic.hybrid import simulate  # noqa: E402
from isorock.analytic.limits import ENERGY_BALANCE_LIMIT  # noqa: E402

KINDS = ("bilinear", "friction-pendulum", "velocity-friction", "ball-in-cone", "ball-in-bowl",
         "double-friction-pendulum")


def gaining(tr):
    """Whether the isolator's loss fell between two instants (by more than 1e-9 of the energy
    involved): a slip pushed along by its own friction, which the balance itself cannot see (the
    work it books is the force it applied). At an instant it may fall: a cone's ball resting at
    its vertex under a rocking block leaves its kinetic energy's change, of either sign, to it."""
    s, t = tr.energy.isolator_loss, tr.t
    return bool(np.any((np.diff(s) < -1e-9 * tr.energy.input_energy) & (np.diff(t) > 0)))


def measure(run, cases):
    """(rocking runs' relative residuals, statuses of every run, the failures' rows, the runs
    whose isolator loss fell)."""
    residuals, statuses, bad, gains = [], {}, [], 0
    for i, (system, motion) in enumerate(cases):
        tr = run(system, motion)
        statuses[str(tr.status)] = statuses.get(str(tr.status), 0) + 1
        rel = tr.energy.relative_residual
        gains += gaining(tr) and str(tr.status) != "failed"
        if tr.uplifts:
            residuals.append(rel)
        if rel > ENERGY_BALANCE_LIMIT or str(tr.status) == "failed":
            bad.append((i, str(tr.status), rel, tr.message, system.isolator, motion.pulse))
    return np.array(residuals), statuses, bad, gains


def report(kind, path, n, residuals, statuses, bad, gains, wall):
    hidden = sum(1 for _, status, rel, *_ in bad if rel > ENERGY_BALANCE_LIMIT and status != "failed")
    q = (np.quantile(residuals, [0.5, 0.99]).tolist() + [residuals.max()]) if residuals.size else [np.nan] * 3
    print(f"{kind:26s} {path:9s} runs {n:5d}  rocking {residuals.size:5d}  statuses {statuses}  residual (rocking) "
          f"median {q[0]:.1e}  p99 {q[1]:.1e}  max {q[2]:.1e}  over {ENERGY_BALANCE_LIMIT:g}: "
          f"{int(np.sum(residuals > ENERGY_BALANCE_LIMIT))}  failed balance reported as an answer: {hidden}  "
          f"isolator loss falling: {gains}  ({wall:.1f} s)", flush=True)
    for i, status, rel, message, iso, pulse in bad:
        print(f"    case {i}: {status}, residual {rel:.2e}: {iso}, {pulse}; {message}")
    return hidden


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=500, help="cases per kind")
    p.add_argument("--seed", type=int, default=39)
    p.add_argument("--reference", type=int, default=0, help="rocking cases per kind run on the reference too")
    p.add_argument("--kinds", default=",".join(KINDS), help="isolator kinds, comma-separated")
    a = p.parse_args(argv)
    hidden = runs = rocking = 0
    for kind in a.kinds.split(","):
        cases = isolator_cases(a.seed, a.cases, kind)
        start = time.perf_counter()
        residuals, statuses, bad, gains = measure(simulate_fast, cases)
        hidden += report(kind, "kernel", len(cases), residuals, statuses, bad, gains, time.perf_counter() - start)
        runs += len(cases)
        rocking += residuals.size
        if a.reference:
            rocks = [c for c in cases if simulate_fast(*c).uplifts][:a.reference]
            start = time.perf_counter()
            residuals, statuses, bad, gains = measure(simulate, rocks)
            hidden += report(kind, "reference", len(rocks), residuals, statuses, bad, gains,
                             time.perf_counter() - start)
    print(f"total: {runs} runs, {rocking} rocking; runs whose energy balance fails reported as completed or "
          f"overturned: {hidden}")
    return 1 if hidden else 0


if __name__ == "__main__":
    sys.exit(main())
