"""A record pair and the statue turned together by one angle (issue 36): the one exact oracle a
contact engine meets under two horizontal components.

Turning the pair's two components by φ (GroundMotion.rotated) and the statue's shaking direction
by the same φ is the same ground acceleration in the statue's own frame: the total tilt's history,
its peak over α, the direction it leans (turned by φ) and, on an isotropic isolator, the base's
travel √(u² + u_y²) are the same. An engine whose contact or friction is not rotation-invariant
(a friction pyramid along the world's axes, a square of joint frictions) parts there, whatever
the exact planar model says. Each engine is judged by its own rows of the one table
(core/tolerances.py: pair_turned_*), its runs at the settings of the first (the same steps).

The statue's mesh turns with the pair; the block has no mesh its scenes can turn (they build it
along the world's axes), so it is turned by a quarter turn, under which its square footprint is
the same (QUARTER_TURN): that still swaps the two components between the base's x and y joints.

Judged where it tests something (judge): the statue rocked, and its rocking is not chaotic at the
scale of roundoff (the pair PROBE_SCALE stronger moves its history less than the limit): a third run.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...analytic.errors import InputError
from ...analytic.limits import BudgetExceeded
from ...analytic.motion import GroundMotion
from ...analytic.system import PlanarBody
from . import biaxial
from .engines import settings_used
from .plan import EngineRun, Plan, make_plan, run_plan
from .tolerances import Check, check, has_tolerance, not_exercised, skipped, tolerance

#: φ (degrees) a statue's pair is turned by: not a multiple of 90°, so that a contact or friction
#: built along the world's axes shows
TURN_DEG = 30.0
#: the block's turn (degrees): its scenes build it along the world's axes
QUARTER_TURN = 90.0
METRICS = ("pair_turned_tilt_history", "pair_turned_tilt_max_diff", "pair_turned_direction_deg", "pair_turned_travel")
HISTORY = METRICS[0]


def as_record(motion: GroundMotion) -> GroundMotion:
    """A pair whose components are records (GroundMotion.rotated turns records): a pulse sampled
    at its own dt, as a record of it is; a record as it is."""
    def record(m):
        return m if m.pulse is None else GroundMotion.from_array(m.acceleration, dt=m.dt, name=m.name)
    return record(motion).with_transverse(record(motion.transverse))


def turned_system(system, body, azimuth: float, turn: float):
    """The System of the statue turned by `turn` (rad) with its pair: its two edges along azimuth +
    turn (PlanarBody.from_resting); the block's (no mesh) unchanged."""
    if system.body is None:
        return system
    turned = PlanarBody.from_resting(body.along(azimuth + turn))
    return replace(system, body=turned, **turned.box)


#: the probe's change of the motion: the two runs of a symmetry differ by the scenes' roundoff (1e-12 on
#: a quarter turn), so the question is not how the rocking moves under the report's ±1% of PGA (a bust
#: rocking on a corner moves by 0.1 α there, and yet turns to 1e-6) but whether a change far below any
#: engine's own differences and far above roundoff grows past the limit through the impacts
PROBE_SCALE = 1.0 + 1e-9


@dataclass(frozen=True)
class TurnedRuns:
    """One engine's runs (`first`: the pair as a record, `turned`: it and the statue turned by
    `turn_deg`, `probe`: the pair PROBE_SCALE stronger) and what they say."""

    label: str
    turn_deg: float
    first: object
    turned: object
    probe: object
    measures: tuple  # biaxial.Measures3D of the first and the turned run, α read at each run's own azimuth
    checks: tuple[Check, ...]


def plans(plan: Plan, body, azimuth: float, turn_deg: float) -> tuple[Plan, Plan, Plan]:
    """(the plan of the pair as records, the plan turned by `turn_deg`, the pair PROBE_SCALE stronger), every
    engine at the settings the first system derives (so that every run takes the same steps)."""
    motion = as_record(plan.motion)
    runs = tuple(EngineRun(r.label, r.engine, settings_used(r.settings, plan.system, plan.duration)) for r in plan.runs)
    keep = dict(duration=plan.duration, theta0=plan.theta0, impact_threshold=plan.impact_threshold,
                overturn_rule=plan.overturn_rule)
    turn = math.radians(turn_deg)
    return (make_plan(plan.system, motion, runs, **keep),
            make_plan(turned_system(plan.system, body, azimuth, turn), motion.rotated(turn), runs, **keep),
            make_plan(plan.system, motion.scaled(PROBE_SCALE), runs, **keep))


def judge(label: str, first, turned, probe, body, azimuth: float, turn_deg: float) -> TurnedRuns:
    """The runs of one engine judged by its pair_turned_* rows. The tilt's three are judged where
    they test something: the statue rocked (past biaxial.WOBBLE_FLOOR of its least α: below it the
    tilt is the contact's micro-motion), and the pair PROBE_SCALE stronger moved its history by less
    than the history's limit (otherwise it is chaotic there: a difference of roundoff between the
    scenes would grow as large, and the turned run could not tell the engine's own)."""
    turn = math.radians(turn_deg)
    # α(direction) at each run's own azimuth, each tabulated once (a tipping-edge search a degree)
    tables = (biaxial.alpha_table(body, azimuth), biaxial.alpha_table(body, azimuth + turn))
    three = tuple(biaxial.measure_3d(tr.t, tr.extras["orientation"], *table, u_y=tr.extras.get("u_y"))
                  for tr, table in zip((first, turned), tables))
    (tilt, direction, _), *others = (biaxial.tilt_twist(tr.extras["orientation"]) for tr in (first, turned, probe))
    tilts = [tilt, *(angles[0] for angles in others)]
    scenario = f"pair turned {turn_deg:g}°"
    n = min(t.size for t in tilts)
    if three[0].overturned:  # the histories while it rocks: up to its first passing α (a fall is no rocking)
        n = min(n, int(np.argmax(tilt / tables[0][0](direction) > 1.0)) or n)
    peak = float(np.max(tilts[0][:n]))
    grown = float(np.max(np.abs(tilts[0][:n] - tilts[2][:n]))) / peak if peak > 0 else 0.0
    lean = (three[1].direction_at_max_deg - three[0].direction_at_max_deg + turn_deg) % 360.0
    values = {"pair_turned_tilt_history": float(np.max(np.abs(tilts[0][:n] - tilts[1][:n]))) / peak,
              "pair_turned_tilt_max_diff": abs(three[1].tilt_max_over_alpha - three[0].tilt_max_over_alpha),
              # the scene's x is the pair's first component: the pair seen in axes turned by φ leans at its
              # peak φ less, in the scene's frame, than the first run does
              "pair_turned_direction_deg": min(lean, 360.0 - lean)}
    if not three[0].rocked:
        why = (f"the statue did not rock past {biaxial.WOBBLE_FLOOR:g} of its least α (peak tilt/α "
               f"{three[0].tilt_max_over_alpha:.3g}): its tilt is the contact's micro-motion")
        checks = [not_exercised(label, m, scenario, why) for m in values]
    elif grown >= (tolerance(label, HISTORY).limit if has_tolerance(label, HISTORY) else math.inf):
        why = (f"chaotic here: the pair {PROBE_SCALE - 1:.0e} stronger moves the tilt's history by {grown:.3g} of its "
               "peak, past the limit, so any difference of roundoff between the two scenes grows as large")
        checks = [skipped(label, m, scenario, why) for m in values]
    elif three[0].overturned and three[1].overturned:
        why = "both runs overturned: a fallen statue's peak tilt/α and lean are no measure (its history judged until it fell)"
        checks = [check(label, "pair_turned_tilt_history", scenario, values["pair_turned_tilt_history"])]
        checks += [not_exercised(label, m, scenario, why) for m in values if m != "pair_turned_tilt_history"]
    else:  # one overturned and not the other: its peak tilt/α parts by more than 1 − its own
        checks = [check(label, m, scenario, v) for m, v in values.items()]
    if not first.system.fixed_base:
        travel = [np.hypot(tr.u[:n], tr.extras["u_y"][:n]) for tr in (first, turned)]
        top = float(np.max(travel[0]))
        checks.append(check(label, "pair_turned_travel", scenario,
                            float(np.max(np.abs(travel[0] - travel[1]))) / top if top > 0 else math.nan))
    return TurnedRuns(label, turn_deg, first, turned, probe, three, tuple(checks))


def turned_runs(plan: Plan, body, azimuth: float, turn_deg: float, *, progress=None, budget_s=None,
                on_start=None) -> dict:
    """label → TurnedRuns of each of the plan's engines; or, for an engine that did not run all
    three, the BudgetExceeded of a run past `budget_s` s, or the InputError of an engine that refused
    the pair when it ran (its one line): the other engines still run."""
    planned = plans(plan, body, azimuth, turn_deg)
    out = {}
    for k, one in enumerate(planned[0].runs):
        try:
            first, turned, probe = (run_plan(replace(p, runs=(p.runs[k],)), progress=progress, budget_s=budget_s,
                                             on_start=on_start)[one.label] for p in planned)
            out[one.label] = judge(one.label, first, turned, probe, body, azimuth, turn_deg)
        except (BudgetExceeded, InputError) as e:
            out[one.label] = e
    return out
