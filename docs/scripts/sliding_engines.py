"""The contact engines against the exact model where the statue slides and the ground heaves
(issue 33, docs/sliding_engines.md): random cases of tests/sliding_cases.py on the bases every
contact engine carries (the fixed base and the linear isolator), each rescaled to a block of
height 0.1, 1 and 10 m by the similarity law (lengths × k, times × √k, accelerations kept), so
that the exact model's dimensionless answer is the same at every size and only the engines'
errors may move. Each engine runs at its default settings; MuJoCo and PyBullet have one
friction coefficient, so a case whose μ_k < μ_s runs there with μ_k = μ_s (the exact model too).

Per engine and size, over the cases (and over the robust ones: the exact model's θmax/α moves
by less than ROBUST_SPREAD, its overturning does not flip and its slide_max moves by less than
5% (or 0.01·b) under ±1% of the motion): overturning's agreement, and where the exact model's
block stands (a block that falls slides as it falls, and lies where it lands), the errors of
slide_max and of the final slide, in units of b and relative to the exact slide (where it is
at least 0.1·b), of the slide's onset (the first time |x| > 0.01·b,
analytic.trajectory.SLIDING_FRACTION) in units of 1/p, and of θmax/α; medians, 95th
percentiles and the worst case.

    python docs/scripts/sliding_engines.py                       # MuJoCo and PyBullet, 60 cases × 3 sizes
    python docs/scripts/sliding_engines.py --engines drake --cases 8 --standing --budget 120
    python docs/scripts/sliding_engines.py --engines mujoco --cases 20 --rows   # every case's row too
    python docs/scripts/sliding_engines.py --tilt                # a sustained slide's tilt, MuJoCo and PyBullet
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from sliding_cases import BASES, case  # noqa: E402

from isorock.analytic.motion import GroundMotion, Pulse  # noqa: E402
from isorock.analytic.system import System  # noqa: E402
from isorock.analytic.trajectory import SLIDING_FRACTION, first_passage  # noqa: E402
from isorock.validate.core.engines import get_engine  # noqa: E402
from isorock.validate.core.tolerances import ROBUST_SPREAD, tolerance  # noqa: E402

SIZES = (0.1, 1.0, 10.0)
#: the bases every contact engine carries (analytic.isolator_parts.CONTACT_ISOLATORS ∩ Drake's)
CARRIED = ("fixed", "linear")
#: wall seconds a run may take before it is counted as failed (Drake is slow on a lying block)
BUDGET_S = 300.0
G = 9.81


def rescaled(system: System, motion: GroundMotion, duration: float, height: float):
    """The same dimensionless case for a block of `height`: lengths × k, times × √k (the
    pulses' frequencies ÷ √k, the isolator's period × √k), accelerations and μ kept."""
    k = height / system.height
    r = math.sqrt(k)

    def pulse(m):
        q = m.pulse
        return GroundMotion.from_pulse(Pulse(q.kind, q.amp, q.freq / r, q.cycles))
    moved = pulse(motion)
    if motion.vertical is not None:
        moved = moved.with_vertical(pulse(motion.vertical))
    if system.fixed_base:
        scaled = System.fixed(height=system.height * k, width=system.width * k, mass=system.mass)
    else:
        scaled = System.isolated(height=system.height * k, width=system.width * k, mass=system.mass,
                                 base_mass=system.base_mass, period=system.period * r,
                                 damping_ratio=system.damping_ratio)
    return scaled.with_friction(system.friction, system.kinetic_friction), moved, duration * r


def cases(n: int, standing: bool = False):
    """The first n cases of tests/sliding_cases.py on a base every contact engine carries (with
    `standing`, of those whose block the exact model does not overturn: a contact engine's block
    lying on its side costs Drake minutes of tiny steps)."""
    analytic = get_engine("analytic")
    i, out = 0, []
    while len(out) < n:
        if BASES[i % len(BASES)] in CARRIED:
            system, motion, duration = case(i)
            if not standing or not analytic.simulate(system, motion, duration=duration).overturned:
                out.append((i, system, motion, duration))
        i += 1
    return out


def metrics(tr, system) -> dict:
    """slide_max and slide_final in units of b, the onset (read off the history the same way for
    every engine: the exact model's summary gives its first slip event instead) in units of
    1/p, θmax/α, overturned, status."""
    s = tr.summary()
    b = system.b
    onset = first_passage(tr.t, tr.slide, SLIDING_FRACTION * b)
    return {"slide_max": s["slide_max"] / b, "slide_final": s["slide_final"] / b,
            "onset": None if onset is None else onset * system.p,
            "speed": float(np.max(np.abs(tr.slide_dot))) / math.sqrt(system.gravity * system.R),
            "theta": tr.theta_max_over_alpha, "over": bool(tr.overturned), "status": str(tr.status)}


def robust(analytic, system, motion, duration, ref) -> bool:
    """Whether the exact model's outcome holds under ±1% of the motion (not chaos)."""
    for f in (0.99, 1.01):
        m = metrics(analytic.simulate(system, motion.scaled(f), duration=duration), system)
        if (m["over"] != ref["over"] or abs(m["theta"] - ref["theta"]) > ROBUST_SPREAD
                or abs(m["slide_max"] - ref["slide_max"]) > max(SLIDING_FRACTION, 0.05 * ref["slide_max"])):
            return False
    return True


def onset_error(a, e):
    """|Δ onset|·p, 0 when neither slid past 0.01·b, inf when only one did."""
    if a is None and e is None:
        return 0.0
    if a is None or e is None:
        return math.inf
    return abs(a - e)


def rows_for(engine_name: str, n: int, show_rows: bool, standing: bool = False, budget: float = BUDGET_S):
    analytic, engine = get_engine("analytic"), get_engine(engine_name)
    carries_mu_k = engine.capabilities.kinetic_friction
    out = []
    for i, system0, motion0, duration0 in cases(n, standing):
        if not carries_mu_k:  # one coefficient: the case as μ_k = μ_s, for the exact model too
            system0 = system0.with_friction(system0.friction)
        for size in SIZES:
            system, motion, duration = rescaled(system0, motion0, duration0, size)
            ref_tr = analytic.simulate(system, motion, duration=duration)
            ref = metrics(ref_tr, system)
            steady = robust(analytic, system, motion, duration, ref)
            start = time.perf_counter()
            try:
                got = metrics(engine.simulate(system, motion, duration=duration, effective_beta=False,
                                              budget_s=budget), system)
            except Exception as exc:  # noqa: BLE001 — a failed run is a row of its own
                got = {"slide_max": math.nan, "slide_final": math.nan, "onset": None, "speed": math.nan,
                       "theta": math.nan, "over": None, "status": f"raised {type(exc).__name__}: {exc}"}
            wall = time.perf_counter() - start
            row = dict(case=i, base=BASES[i % len(BASES)], size=size, vertical=motion.vertical is not None,
                       robust=steady, ref=ref, got=got, wall=wall, mu_tan=system.friction * system.h / system.b,
                       d_max=abs(got["slide_max"] - ref["slide_max"]),
                       d_final=abs(got["slide_final"] - ref["slide_final"]),
                       d_onset=onset_error(ref["onset"], got["onset"]),
                       d_theta=abs(got["theta"] - ref["theta"]),
                       agree=got["over"] == ref["over"])
            row["r_max"] = row["d_max"] / ref["slide_max"] if ref["slide_max"] >= 0.1 else None
            row["r_final"] = row["d_final"] / abs(ref["slide_final"]) if abs(ref["slide_final"]) >= 0.1 else None
            out.append(row)
            if show_rows:
                print(f"  case {i:3d} {row['base']:6s} H {size:4g} {'v' if row['vertical'] else ' '} "
                      f"{'robust ' if steady else 'chaotic'} μ/tanα {row['mu_tan']:.2f} "
                      f"slip speed {ref['speed']:.2f}·√(gR) exact slide_max {ref['slide_max']:.3f}b "
                      f"final {ref['slide_final']:+.3f}b onset {rounded(ref['onset'])} "
                      f"θ {ref['theta']:.3f} over {ref['over']} | {engine_name} {got['slide_max']:.3f}b "
                      f"{got['slide_final']:+.3f}b onset {rounded(got['onset'])} "
                      f"θ {got['theta']:.3f} over {got['over']} {got['status']} [{wall:.1f} s]", flush=True)
    return out


def rounded(x):
    return x if x is None else round(x, 3)


def stats(values) -> str:
    v = np.array([x for x in values if x is not None], dtype=float)
    if not v.size:
        return "—"
    finite = v[np.isfinite(v)]
    worst = "inf" if np.any(~np.isfinite(v)) else f"{np.max(v):.3g}"
    if not finite.size:
        return f"n {v.size}: all inf"
    return (f"median {np.median(finite):.3g}, p95 {np.percentile(v[np.isfinite(v)], 95):.3g}"
            f"{'' if finite.size == v.size else f' (+{v.size - finite.size} inf)'}, worst {worst} (n {v.size})")


def within(engine_name: str, row: dict) -> bool:
    """Whether a run is within the engine's tolerances (validate/core/tolerances.py): overturning
    as the exact model's, and where its block stands, slide_max, slide_final, slide_onset and
    θmax/α."""
    if row["got"]["over"] != row["ref"]["over"]:
        return False
    if row["ref"]["over"]:
        return True
    return all(row[key] <= tolerance(engine_name, metric).limit for key, metric in
               (("d_max", "slide_max"), ("d_final", "slide_final"), ("d_onset", "slide_onset"),
                ("d_theta", "slide_theta_max_diff")))


def report(engine_name: str, rows: list) -> None:
    for size in SIZES:
        steady = [r for r in rows if r["size"] == size and r["robust"]]
        passed = [r for r in steady if within(engine_name, r)]
        print(f"{engine_name} H {size:g} m: within the tolerance table in {len(passed)} of {len(steady)} robust cases "
              f"({100 * len(passed) / max(1, len(steady)):.0f}%)")
        for r in steady:
            if r not in passed:
                print(f"    outside: case {r['case']} ({r['base']}{', vertical' if r['vertical'] else ''}), "
                      f"μ/tanα {r['mu_tan']:.2f}, exact slip speed {r['ref']['speed']:.2f}·√(gR), slide "
                      f"{r['ref']['slide_max']:.3g}·b: Δslide_max {r['d_max']:.3g}·b, Δfinal {r['d_final']:.3g}·b, "
                      f"Δθmax/α {r['d_theta']:.3g}, overturned {r['ref']['over']} / {r['got']['over']}")
        for label, keep in (("all", lambda r: True), ("robust", lambda r: r["robust"])):
            sel = [r for r in rows if r["size"] == size and keep(r)]
            if not sel:
                continue
            agree = sum(r["agree"] for r in sel)
            walls = sum(r["wall"] for r in sel)
            print(f"{engine_name} H {size:g} m, {label} ({len(sel)} cases, {walls:.0f} s wall): "
                  f"overturning agrees in {agree} of {len(sel)}")
            sel = [r for r in sel if not r["ref"]["over"]]
            print(f"  where the exact model's block stands ({len(sel)} cases, "
                  f"{sum(r['ref']['slide_max'] >= SLIDING_FRACTION for r in sel)} slide past 0.01·b, "
                  f"{sum(r['ref']['theta'] > 0 for r in sel)} rock):")
            print(f"    slide_max   |Δ|/b   {stats(r['d_max'] for r in sel)}")
            print(f"    slide_max   |Δ|/x   {stats(r['r_max'] for r in sel)}")
            print(f"    slide_final |Δ|/b   {stats(r['d_final'] for r in sel)}")
            print(f"    slide_final |Δ|/x   {stats(r['r_final'] for r in sel)}")
            print(f"    onset       |Δ|·p   {stats(r['d_onset'] for r in sel)}")
            print(f"    θmax/α      |Δ|     {stats(r['d_theta'] for r in sel)}")
            worst = max(sel, key=lambda r: (r["d_max"] if math.isfinite(r["d_max"]) else math.inf))
            vertical = ", vertical" if worst["vertical"] else ""
            print(f"    worst slide_max: case {worst['case']} ({worst['base']}{vertical}): "
                  f"exact {worst['ref']['slide_max']:.4g}b, {engine_name} {worst['got']['slide_max']:.4g}b, "
                  f"θmax/α {worst['ref']['theta']:.3g} / {worst['got']['theta']:.3g}")


def tilt(engines) -> None:
    """How far a block tilts while it slides without rocking in the exact model (μ < tanα: the
    model's block never tips while it slides): a fixed base, λ 2 (H 1 m), pushed at μ·g + 0.5·g
    for as long as it takes its slip to reach v (in units of √(g·R)), then left to stop."""
    system0 = System.fixed(height=1.0, width=0.5, mass=10.0)
    tan = system0.b / system0.h
    print("| engine | μ/tanα | peak slip v/√(gR) | θmax/α | status |")
    print("|---|---|---|---|---|")
    for name in engines:
        engine = get_engine(name)
        for ratio in (0.3, 0.5, 0.7, 0.9):
            system = system0.with_friction(ratio * tan)
            for v in (0.5, 1.0, 2.0, 4.0):
                length = v * math.sqrt(G * system.R) / (0.5 * G)
                n = int(round(length / 0.01))
                push = GroundMotion.from_array(np.r_[np.zeros(10), np.full(n + 1, (system.friction + 0.5) * G), 0.0],
                                               dt=0.01)
                stop = v * math.sqrt(system.R / G) / system.friction  # the slip's time to stop at μ·g
                tr = engine.simulate(system, push, duration=0.1 + length + 2 * stop)
                print(f"| {name} | {ratio:g} | {v:g} | {tr.theta_max_over_alpha:.3g} | {tr.status} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--engines", nargs="+", default=["mujoco", "bullet"])
    parser.add_argument("--cases", type=int, default=60, help="cases on the fixed base and the linear isolator")
    parser.add_argument("--rows", action="store_true", help="print every case's row")
    parser.add_argument("--tilt", action="store_true", help="a sustained slide's tilt instead of the cases")
    parser.add_argument("--standing", action="store_true", help="only cases whose block the exact model leaves standing")
    parser.add_argument("--budget", type=float, default=BUDGET_S, help="wall seconds per run (past it: a failed row)")
    a = parser.parse_args()
    if a.tilt:
        tilt(a.engines)
        return
    for name in a.engines:
        start = time.perf_counter()
        rows = rows_for(name, a.cases, a.rows, a.standing, a.budget)
        report(name, rows)
        print(f"{name}: {len(rows)} runs in {time.perf_counter() - start:.0f} s wall", flush=True)


if __name__ == "__main__":
    main()
