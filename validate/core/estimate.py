"""The cost of a long command, announced before it starts (issue 24, item 13).

    estimate_line({"analytic": 1200.0, "drake": 3600.0})  # simulated seconds per engine
    → "validate: about 230 runs' worth ... ≈ 30 min (drake ≈ 0.27 simulated s per wall s)"

Each engine's speed is its measured simulated seconds per wall second on a rocking block
(the slow case: impacts); see SPEEDS. An estimate under ANNOUNCE_AFTER is not announced.
"""
from __future__ import annotations

import sys

from ...analytic import limits

#: simulated seconds per wall second of one run on one core, with the block rocking
#: (impacts are what is slow), rounded down: free rocking of the paper's block for 10 s from
#: 0.5α at the defaults (MuJoCo 56–68 and PyBullet 20–40 simulated s per CPU s, load 4; a
#: record, where the block mostly rests and the rest phase is skipped, runs 3–5× faster:
#: `isorock bench`'s speed goals, README), and docs/drake.md's free-rocking table for Drake
#: (continuous preset: 0.27). An engine not listed counts as the slowest.
SPEEDS = {"analytic": 1000.0, "analytic-fast": 1000.0, "analytic-reference": 20.0, "mujoco": 40.0,
          "bullet": 10.0, "drake": 0.27,
          # DART at its default step (0.1 ms on the paper's block, following the body's size): 8.6 on the
          # atlas's 18 cells, 9.0 on its 100, 5 on Kobe 40 s (docs/dart.md); MJX on a CPU,
          # stepped throughout: 0.15 on the atlas grid (docs/mjx.md); MuJoCo Warp on a CPU, stepped
          # throughout: 1.5 on the atlas grid (0.08–7.7 a cell: each run records its steps first, ~1 s),
          # 2.9 on validate --quick (docs/mjwarp.md)
          "dart": 5.0, "mjx": 0.15, "mjwarp": 1.5}
#: wall seconds from which the estimate is announced
ANNOUNCE_AFTER = 120.0


def estimate_s(simulated: dict[str, float], workers: int = 1, speeds: dict | None = None) -> float:
    """Wall seconds for `simulated` seconds per engine label (ENGINE or ENGINE:PRESET),
    the contact engines' runs spread over `workers` processes; `speeds`: simulated s per wall
    s per engine for work other than a rocking block (SPEEDS by default)."""
    speeds = speeds or SPEEDS
    slowest = min(speeds.values())
    total = 0.0
    for label, seconds in simulated.items():
        engine = label.partition(":")[0]
        share = 1 if engine.startswith("analytic") else max(1, workers)
        total += seconds / speeds.get(engine, slowest) / share
    return total


def estimate_line(simulated: dict[str, float], workers: int = 1, command: str = "validate",
                  budget_s: float | None = None, speeds: dict | None = None, basis: str | None = None
                  ) -> str | None:
    """One line for stderr, or None when the work is short; `budget_s`: each run's budget
    (None: limits.RUN_BUDGET_S; 0: its runs have none); `speeds`: as estimate_s takes them,
    and `basis` what they were measured on (default: SPEEDS', a block rocking throughout)."""
    budget_s = limits.RUN_BUDGET_S if budget_s is None else budget_s
    speeds = speeds or SPEEDS
    basis = basis or ("with the block rocking throughout; a block that mostly rests runs several times faster, and "
                      "the progress line's ETA follows the runs")
    wall = estimate_s(simulated, workers, speeds)
    if wall < ANNOUNCE_AFTER:
        return None
    slowest = max(simulated, key=lambda k: simulated[k] / speeds.get(k.partition(":")[0], min(speeds.values())))
    speed = speeds.get(slowest.partition(":")[0], min(speeds.values()))
    # a bound, said as one: SPEEDS are a block that rocks throughout, and most records leave
    # it resting most of the time (docs/campaigns/fragility-contact.toml: ≈ 23 min said, 92 s
    # taken), so the progress bar's ETA, which follows the runs, is the better guide
    return (f"{command}: about {sum(simulated.values()):.0f} simulated s in all; at most ≈ {wall / 60:.0f} min "
            f"on {workers} worker{'s' if workers != 1 else ''} (mostly {slowest}, ≈ {speed:g} simulated s per wall s "
            f"{basis})" + (f"; each run stops at its budget of {budget_s:g} s wall time" if budget_s else ""))


def announce_cost(command: str, simulated: dict[str, float], budget_s: float | None = None, quiet: bool = False, *,
                  workers: int = 1, speeds: dict | None = None, basis: str | None = None) -> None:
    """The cost estimate of a long command on stderr, before its work (estimate_line): the
    commands' and the tools' that run under them (validate under a record pair)."""
    line = estimate_line(simulated, workers=workers, command=command, budget_s=budget_s, speeds=speeds, basis=basis)
    if line and not quiet:
        print(line, file=sys.stderr, flush=True)
