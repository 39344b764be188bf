"""`isorock design`: for my statue and my site, which isolator keeps it standing? (issue 22)

Every isolator of a family (the linear isolator's period × damping ratio grid; any
family whose `system(statue, x, y)` the compiled kernel carries) and the fixed base are
run by the analytic kernel under every record of a hazard (a record suite scaled to one
or more PGA levels), through the one executor (core.chunks.run_cases, summary rows).
Per isolator: the probability of overturning at each level (the fraction of records
that overturn it, under model.md's rule, past α) and over the hazard (the levels
weighted: equally unless the caller gives weights, e.g. from a hazard curve), the
isolator's stroke (peak |u| over the run: median and 84th percentile over the records
at each level) and the PGA at which half the records overturn it (a lognormal fit,
core.fragility). Nothing here assumes that overturning grows with the level: rocking is
not monotone in the scale of a motion (model.md, "Past α"), so every level is run and
the (isolator, record) pairs that survive a level above one that overturned them are
counted (`non_monotone`).

An isolator is *recommended* when its P(overturn) over the hazard is at most the target
and, where a stroke limit is given, its 84th-percentile stroke at the highest level is
within it. `check_with` runs a few of the design's points again with a contact engine
and says how far it agrees.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ....analytic.errors import InputError, real_number
from ....analytic.fast import simulate_batch
from ....analytic.limits import check_acceleration, check_duration, check_isolator, check_period
from ....analytic.motion import GroundMotion
from ....analytic.rest_scales import rest_phases
from ....analytic.shape import along_directions, weakest_direction
from ....analytic.system import (BALL_IN_BOWL, BALL_IN_CONE, FRICTION_PENDULUM, LINEAR, BallInBowl, BallInCone,
                                     FrictionPendulum, PlanarBody, System)
from ...core.cases import Case, _LazyScaled, record_factor
from ...core.chunks import run_cases
from ...core.engines import ALL_ENGINES, check_carries, choose, get_engine
from ...core.fragility import fit_counts
from ...core.summary import case_inputs, row_of_batch, rows_to_table, sort_table
from ...core.tolerances import has_tolerance, tolerance
from ...core.verdict import rate_interval

#: The engine that answers the design question (the compiled kernel).
ENGINE = "analytic"
#: Default time after each record's end (s): model.md's tail, as campaigns use.
DEFAULT_TAIL = 5.0
#: Simulated seconds per CPU second over a design grid, for the estimate announced before
#: the work, per path (design_speed), rounded down (docs/design.md):
#: - REST_PHASE_SPEED, a linear isolator's, with the rest phase settling the runs that never lift:
#:   the paper's block, T 1–4 s × ξ 0.02–0.4 × FEMA P695 far field × PGA 0.1–1 g, 8.69e6 simulated
#:   s in 33.7–36.6 CPU s; the 0.5 m statue in 27.5;
#: - ISOLATOR_KERNEL_SPEED, the non-linear isolators' kernel, which runs every run throughout: the
#:   bust of 80 kg on friction pendulums under that hazard, 8.69e6 simulated s in 196 s wall on 2
#:   threads (~22,000 per CPU s); the paper's block on friction pendulums, ball-in-cone and
#:   ball-in-bowl isolators under 6 records, 26,000–31,000;
#: - SLIDING_SPEED, a statue that may slip (the sliding model's kernel): the paper's block at μ_s 0.5
#:   on linear isolators under 6 records, 969,217 simulated s in 447 CPU s (~2,200).
#: The last two were one speed of 40,000, which announced 109 s and 2 s for designs that took 196 s
#: and 226 s (load 1.0–1.9, 29 Nov 2026).
REST_PHASE_SPEED = 200_000.0
ISOLATOR_KERNEL_SPEED = 12_000.0
SLIDING_SPEED = 1_500.0
#: The statuses of a run that gave an answer (overturned or not); any other is counted apart.
ANSWERED = ("completed", "overturned")
#: Largest number of runs a design may ask for (the campaigns' bound: campaign.spec.MAX_RUNS).
MAX_DESIGN_RUNS = 2_000_000
#: The most values one axis of a family (or the PGA levels) may take.
MAX_AXIS = 200
#: The grids a design runs when none is given: (from, to, number) per axis, per isolator kind, and
#: the PGA levels (g). (`isorock design` shows them as FROM:TO:NUM.)
DEFAULT_GRIDS = {LINEAR: (("periods", (1.0, 4.0, 20)), ("damping_ratios", (0.02, 0.4, 20))),
                 FRICTION_PENDULUM: (("radii", (0.5, 4.0, 20)), ("friction_coefficients", (0.02, 0.2, 20))),
                 BALL_IN_CONE: (("slopes", (0.02, 0.3, 15)), ("rolling_resistances", (0.005, 0.1, 20))),
                 BALL_IN_BOWL: (("radii", (0.5, 4.0, 20)), ("rolling_resistances", (0.005, 0.1, 20)))}
DEFAULT_LEVELS = (0.1, 1.0, 10)
#: The confidence of every P(overturn)'s interval (issue 39): a P from 44 records, or 2, is a
#: sample's fraction, and the target is judged with its interval, not the fraction alone.
CONFIDENCE = 0.95
#: An isolator whose 84th-percentile stroke at the highest level stays below this (m) barely
#: moves: a friction pendulum or a cone that never breaks away, a fixed base in effect. It is
#: said, and named only where no isolator that moves meets the rule (a cone whose median stroke
#: was 4.7 µm was named as the better choice than the fixed base it is).
LOCKED_STROKE = 1e-3


# --- the values a design is given, checked once for the command and for Python ----------------

def even_grid(lo: float, hi: float, num: float) -> tuple[float, ...]:
    """FROM:TO:NUM: `num` values from `lo` to `hi`, both ends included, evenly spaced."""
    # NUM is read as a number first: inf or nan has no whole value to take (an OverflowError)
    if not (math.isfinite(num) and num == int(num) and 1 <= num <= MAX_AXIS):
        raise InputError(f"grid = {lo:g}:{hi:g}:{num:g}: NUM must be a whole number from 1 to {MAX_AXIS}")
    if not (math.isfinite(lo) and math.isfinite(hi) and hi >= lo):
        raise InputError(f"grid = {lo:g}:{hi:g}:{num:g}: must be a range FROM:TO:NUM with finite FROM ≤ TO")
    # rounded as Python floats: NumPy's round multiplies by 1e12 first, and 1e300 became inf
    return tuple(round(float(v), 12) for v in np.linspace(lo, hi, int(num))) if num > 1 else (float(lo),)


def numbers_of(name: str, values) -> tuple[float, ...]:
    """A keyword given a number or a sequence of numbers, as floats (any real number: NumPy's,
    a Fraction); text, a bool, a dict or nesting is one line naming `name` ('2' was the period
    2 s, True the period 1 s)."""
    allowed = "a number or a sequence of numbers"
    try:
        ndim = np.ndim(values)
    except (TypeError, ValueError):  # a ragged nesting
        ndim = 2
    if isinstance(values, (str, bytes, dict, set)) or ndim > 1:
        raise InputError(f"{name} = {values!r}: must be {allowed}")
    items = list(values) if ndim else [values]
    out = []
    for v in items:
        if isinstance(v, (str, bytes)):
            raise InputError(f"{name} = {values!r}: must be {allowed}")
        out.append(real_number(name, v, allowed))
    return tuple(out)


def check_axis(name: str, values, *, below_one: bool = False) -> tuple[float, ...]:
    """An axis of a family, or the PGA levels: positive, finite, increasing numbers, at most
    MAX_AXIS (below 1 for a damping ratio); one line naming `name` otherwise."""
    values = numbers_of(name, values)
    if not values or len(values) > MAX_AXIS:
        raise InputError(f"{name} = {values!r}: {len(values)} values; must be 1 to {MAX_AXIS}")
    for v in values:
        if not (v > 0 and math.isfinite(v)) or (below_one and v >= 1):
            raise InputError(f"{name} = {values!r}: {v!r} must be a positive finite number"
                             + (" below 1 (an underdamped isolator)" if below_one else ""))
    if list(values) != sorted(set(values)):
        raise InputError(f"{name} = {values!r}: must be increasing, each value once")
    return values


def check_decision(target, max_stroke, tail, check_runs, *, named=str) -> None:
    """The decision's own numbers, each one line naming it as the caller spells it (`named`:
    the keyword, or the command's option)."""
    if not (isinstance(target, (int, float)) and 0 <= target <= 1):
        raise InputError(f"{named('target')} = {target!r}: must be a probability from 0 to 1")
    if max_stroke is not None and not (isinstance(max_stroke, (int, float)) and max_stroke > 0
                                       and math.isfinite(max_stroke)):
        raise InputError(f"{named('max_stroke')} = {max_stroke!r}: must be a positive finite length, m")
    if not (isinstance(tail, (int, float)) and tail >= 0 and math.isfinite(tail)):
        raise InputError(f"{named('tail')} = {tail!r}: must be a non-negative finite number of seconds")
    if not (isinstance(check_runs, int) and 1 <= check_runs <= 200):
        raise InputError(f"{named('check_runs')} = {check_runs!r}: must be a whole number from 1 to 200")


# --- the statue ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Statue:
    """The block and its base plate's mass: what every isolator of a family carries."""

    height: float
    width: float
    mass: float
    base_mass: float
    #: the statue's friction on its plinth (μ_s; None: it cannot slip, docs/sliding.md), and how far
    #: it may walk on the plinth before it walks off (m; None: not asked)
    friction: float | None = None
    plinth_margin: float | None = None
    #: a statue of two different tipping edges (its mesh along the shaking direction:
    #: System.body, docs/statues.md); None: the block H × B
    body: PlanarBody | None = None
    #: what the statue is, for the report (its mesh's file, or an example's name)
    name: str | None = None

    def __post_init__(self):
        self.fixed()  # the block's own checks, its friction's too
        if not (self.base_mass > 0 and math.isfinite(self.base_mass)):
            raise InputError(f"base-mass = {self.base_mass!r}: must be a positive finite number (kg)")
        if self.plinth_margin is not None:
            if self.friction is None:
                raise InputError(f"plinth-margin = {self.plinth_margin!r}: needs the statue's --friction (without it "
                                 "the statue cannot slip)")
            if not (self.plinth_margin > 0 and math.isfinite(self.plinth_margin)):
                raise InputError(f"plinth-margin = {self.plinth_margin!r}: must be a positive finite length, m")

    def fixed(self) -> System:
        return self.carried(System.fixed(height=self.height, width=self.width, mass=self.mass))

    def carried(self, system: System) -> System:
        """`system` (its base, its isolator) carrying this statue: its friction, its two edges."""
        return replace(system, body=self.body).with_friction(self.friction)

    @property
    def label(self) -> str:
        s = self.fixed()
        if self.body is not None:
            e = self.body
            return (f"{self.name or 'a statue of two edges'}: centre of mass {e.centre_height:.3g} m up, edges "
                    f"{e.lever_forward:.3g} m and {e.lever_backward:.3g} m from it (α₊ {e.alpha(1):.3g}, α₋ "
                    f"{e.alpha(-1):.3g} rad), m {self.mass:.4g} kg on a {self.base_mass:.4g} kg base "
                    f"(μ = {self.mass / self.base_mass:.3g})")
        return (f"H {self.height:g} m, B {self.width:g} m (λ = H/B = {s.slenderness:.3g}, α = {s.alpha:.3g} rad), "
                f"m {self.mass:g} kg on a {self.base_mass:g} kg base (μ = {self.mass / self.base_mass:.3g})"
                + ("" if self.friction is None else f", statue friction μ_s {self.friction:g}"
                   + ("" if self.plinth_margin is None else f", {self.plinth_margin:g} m to the plinth's edge")))


# --- isolator families: two axes, and the System at each cell ----------------------------

@dataclass(frozen=True)
class Family:
    """A family of isolators on two axes (x_values × y_values); a kind names its axes and
    builds its isolator at each cell (`isolator`), or its System (`system`)."""

    x_values: tuple[float, ...]
    y_values: tuple[float, ...]

    def __post_init__(self):
        """Every cell's isolator built once, its parameters checked (a friction coefficient
        past 1 is one line, not a chunk of failed runs), and its period within
        ISOLATOR_PERIOD_RANGE: a friction pendulum of radius 1e308 m (a period of 2e154 s)
        drew a chart whose axis matplotlib could not tick (a traceback). A family's isolator
        does not depend on the statue: a stand-in carries it."""
        stand_in = Statue(2.0, 0.7, 1.0, 1.0)
        for x in self.x_values:
            for y in self.y_values:
                period = self.system(stand_in, x, y).period
                if math.isfinite(period):  # a ball in a cone has none (its force is constant)
                    try:
                        check_period("period", period)
                    except InputError as e:
                        raise InputError(f"{self.x_name} = {x:g}: {e}") from None

    def isolator(self, x: float, y: float):
        raise NotImplementedError

    def system(self, statue: Statue, x: float, y: float) -> System:
        return statue.carried(System.with_isolator(height=statue.height, width=statue.width, mass=statue.mass,
                                                   base_mass=statue.base_mass, isolator=self.isolator(x, y)))


@dataclass(frozen=True)
class LinearFamily(Family):
    """The seed paper's isolator: period T (s) × damping ratio ξ."""

    kind = LINEAR
    x_name, y_name = "period", "damping_ratio"
    x_label, y_label = "isolation period T (s)", "damping ratio ξ"
    x_unit, y_unit = "s", ""

    def __post_init__(self):
        for period in self.x_values:  # before a stiffness M·(2π/T)² is computed from it
            check_period("periods", period)
        super().__post_init__()

    def system(self, statue: Statue, x: float, y: float) -> System:
        # given by period and damping ratio, which the System derives k and c from
        return statue.carried(System.isolated(height=statue.height, width=statue.width, mass=statue.mass,
                                              base_mass=statue.base_mass, period=x, damping_ratio=y))


@dataclass(frozen=True)
class FrictionPendulumFamily(Family):
    """The friction pendulum: radius of curvature R_fp (m) × friction coefficient μ_f."""

    kind = FRICTION_PENDULUM
    x_name, y_name = "radius", "friction_coefficient"
    x_label, y_label = "radius of curvature R_fp (m)", "friction coefficient μ_f"
    x_unit, y_unit = "m", ""

    def isolator(self, x: float, y: float):
        return FrictionPendulum(radius=x, friction_coefficient=y)


@dataclass(frozen=True)
class BallInConeFamily(Family):
    """Rolling balls in cones: slope tanφ × rolling resistance μ_r (docs/isolators.md). A block
    with tanφ + μ_r < tanα cannot lift on it, whatever the hazard."""

    kind = BALL_IN_CONE
    x_name, y_name = "slope", "rolling_resistance"
    x_label, y_label = "cone slope tanφ", "rolling resistance μ_r"
    x_unit, y_unit = "", ""

    def isolator(self, x: float, y: float):
        return BallInCone(slope=x, rolling_resistance=y)


@dataclass(frozen=True)
class BallInBowlFamily(Family):
    """Rolling balls in spherical bowls: effective radius R_eff (m) × rolling resistance μ_r."""

    kind = BALL_IN_BOWL
    x_name, y_name = "radius", "rolling_resistance"
    x_label, y_label = "bowl radius R_eff (m)", "rolling resistance μ_r"
    x_unit, y_unit = "m", ""

    def isolator(self, x: float, y: float):
        return BallInBowl(radius=x, rolling_resistance=y)


#: isolator kind → its family (what `--isolator` names)
FAMILIES = {LINEAR: LinearFamily, FRICTION_PENDULUM: FrictionPendulumFamily, BALL_IN_CONE: BallInConeFamily,
            BALL_IN_BOWL: BallInBowlFamily}


def check_family_runs(family) -> None:
    """The kernel must carry the family's isolator: one line otherwise, before any work."""
    carried = get_engine(ENGINE).capabilities.isolators
    if family.kind not in carried:
        raise InputError(f"isolator = {family.kind}: the compiled kernel (engine '{ENGINE}') that answers a design "
                         f"carries the {', '.join(carried)} isolator only so far (docs/design.md)")


# --- the hazard ----------------------------------------------------------------------------

@dataclass(frozen=True)
class Hazard:
    """Records (name → unscaled GroundMotion) each scaled to every PGA level (g); the
    levels' weights in P(overturn) over the hazard (normalised; equal by default)."""

    records: dict
    levels: tuple[float, ...]
    weights: tuple[float, ...] = ()
    source: str = ""

    def __post_init__(self):
        if not self.records:
            raise InputError("records: the hazard has no record")
        if not self.levels:
            raise InputError("pga: give one or more levels (g)")
        for x in self.levels:
            if not (x > 0 and math.isfinite(x)):
                raise InputError(f"pga = {x!r}: must be a positive finite PGA (g)")
        if list(self.levels) != sorted(set(self.levels)):
            raise InputError(f"pga = {','.join(f'{x:g}' for x in self.levels)}: must be increasing, each level once")
        for x in self.levels:
            check_acceleration("pga", x)  # the kernel spun on accelerations far past it
        w = self.weights or (1.0,) * len(self.levels)
        if len(w) != len(self.levels):
            raise InputError(f"level-weights: {len(w)} given for {len(self.levels)} PGA levels; give one per level")
        if any(not (x >= 0 and math.isfinite(x)) for x in w) or max(w) <= 0:
            raise InputError(f"level-weights = {','.join(f'{x:g}' for x in w)}: must be non-negative finite numbers, "
                             "not all zero")
        # over the largest first: the sum of weights near a float's top overflowed (1e308 +
        # 1e308 = inf made every weight 0, and every P over the hazard 0)
        top = max(w)
        w = [float(x) / top for x in w]
        object.__setattr__(self, "weights", tuple(x / sum(w) for x in w))
        for name, r in self.records.items():
            if not r.pga_g > 0:
                raise InputError(f"records: {name!r} has a PGA of 0 and cannot be scaled to a level")

    @property
    def names(self) -> list[str]:
        return sorted(self.records)

    @property
    def equal_weights(self) -> bool:
        return len(set(self.weights)) == 1


# --- the cases, and running them ----------------------------------------------------------

@dataclass
class Design:
    """What a design run found. Arrays over systems (0: the fixed base, 1 + iy·nx + ix:
    the isolator at x_values[ix], y_values[iy]) × records (hazard.names) × levels."""

    statue: Statue
    family: object
    hazard: Hazard
    overturned: np.ndarray  # bool
    u_max: np.ndarray  # m
    theta_max: np.ndarray  # θmax/α
    status: np.ndarray  # str
    table: object = None  # the executor's pyarrow table, one row per run
    wall_s: float = math.nan
    tail: float = DEFAULT_TAIL  # s simulated after each record
    check: dict | None = field(default=None)  # the first contact engine's check (as design.json's `check`)
    checks: list | None = field(default=None)  # every contact engine's, in the order asked
    _memo: dict = field(default_factory=dict, repr=False)
    slide: np.ndarray | None = None  # m: how far the statue walked on its plinth (a statue with friction)

    # --- per system ---------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return len(self.family.y_values), len(self.family.x_values)

    def _valid(self):
        """Runs that gave an answer: a failed run (or one stopped at its event limit) is
        left out of every fraction and counted apart (`failed`)."""
        return np.isin(self.status, ANSWERED)

    @property
    def failed(self) -> int:
        return int((~self._valid()).sum())

    def p_level(self) -> np.ndarray:
        """(systems, levels) fraction of records that overturn."""
        v = self._valid()
        with np.errstate(invalid="ignore"):
            return (self.overturned & v).sum(axis=1) / v.sum(axis=1)

    def p_hazard(self) -> np.ndarray:
        """(systems,) P(overturn) over the hazard: the levels' fractions, weighted."""
        return self.p_level() @ np.asarray(self.hazard.weights)

    def records_answered(self) -> np.ndarray:
        """(systems,) how many records stand behind P over the hazard: the fewest answered
        at any level (a failed run is left out of its level's fraction)."""
        return self._valid().sum(axis=1).min(axis=1)

    def p_interval(self, confidence: float = CONFIDENCE) -> np.ndarray:
        """(systems, 2) the interval of P(overturn) over the hazard: Clopper–Pearson's for
        P·n of the n records answered (core.verdict.rate_interval, as stress and the atlas
        judge rates). P over the hazard is the mean over the records of each record's
        weighted outcome over the levels, a number in [0, 1]; at one level it is a 0/1
        outcome and the interval exact, over several a bounded mean, whose variance is at
        most P(1 − P): the binomial interval is then at least as wide as it needs to be."""
        key = ("p_interval", confidence)
        if key not in self._memo:  # asked by the verdict, each P in words and every row: computed once
            p, n = self.p_hazard(), self.records_answered()
            self._memo[key] = np.array([rate_interval(pi * ni, int(ni), confidence) if ni > 0 and math.isfinite(pi)
                                        else (math.nan, math.nan) for pi, ni in zip(p, n)])
        return self._memo[key]

    def locked(self) -> np.ndarray:
        """(systems,) an isolator that barely moves: its 84th-percentile stroke at the
        highest level below LOCKED_STROKE (the fixed base: False)."""
        out = np.nan_to_num(self.stroke(0.84)[:, -1], nan=np.inf) < LOCKED_STROKE
        out[0] = False
        return out

    def walk_off_level(self) -> np.ndarray | None:
        """(systems, levels) fraction of records under which the statue walks farther than the plinth
        margin (a statue that falls first counts by its fall, p_level); None without a margin."""
        if self.slide is None or self.statue.plinth_margin is None:
            return None
        v = self._valid()
        off = np.nan_to_num(self.slide, nan=0.0) > self.statue.plinth_margin
        with np.errstate(invalid="ignore"):
            return (off & v).sum(axis=1) / v.sum(axis=1)

    def walk_off_hazard(self) -> np.ndarray | None:
        """(systems,) P(walks off its plinth) over the hazard: the levels' fractions, weighted."""
        w = self.walk_off_level()
        return None if w is None else w @ np.asarray(self.hazard.weights)

    def walk(self, q: float) -> np.ndarray | None:
        """(systems, levels) the q-quantile over the records of how far the statue walked (m)."""
        if self.slide is None:
            return None
        x = np.where(self._valid(), self.slide, np.nan)
        with np.errstate(invalid="ignore"):
            return np.nanquantile(x, q, axis=1)

    def stroke(self, q: float) -> np.ndarray:
        """(systems, levels) the q-quantile over the records of the peak base displacement (m)."""
        key = ("stroke", q)
        if key not in self._memo:
            u = np.where(self._valid(), self.u_max, np.nan)
            self._memo[key] = (np.quantile(u, q, axis=1) if not np.isnan(u).any()  # nanquantile: 10× slower
                               else np.nanquantile(u, q, axis=1))
        return self._memo[key]

    def non_monotone(self) -> int:
        """(system, record) pairs that survive a level above one that overturned them."""
        o = self.overturned & self._valid()
        first = np.where(o.any(axis=2), o.argmax(axis=2), o.shape[2])
        above = np.arange(o.shape[2])[None, None, :] > first[:, :, None]
        return int((above & ~o & self._valid()).any(axis=2).sum())

    def fragility_median(self, system: int) -> float:
        """The PGA (g) at which half the records overturn `system` (lognormal MLE,
        core.fragility); nan where no run or every run overturned. (Per system on demand:
        a fit is ~10 ms, 400 of them were a chart's slowest step.)"""
        v = self._valid()[system]
        return fit_counts(self.hazard.levels, v.sum(axis=0), (self.overturned[system] & v).sum(axis=0))[0]

    def grid(self, values: np.ndarray) -> np.ndarray:
        """The isolators' values (systems 1…) as a (y, x) grid."""
        return np.asarray(values)[1:].reshape(self.shape)

    # --- the answer ---------------------------------------------------------------------
    def recommended(self, target: float, max_stroke: float | None) -> np.ndarray:
        """(y, x) bool: P over the hazard ≤ target and, with a stroke limit, the
        84th-percentile stroke at the highest level within it."""
        ok = self.grid(self.p_hazard()) <= target
        if max_stroke is not None:
            ok &= self.grid(self.stroke(0.84)[:, -1]) <= max_stroke
        off = self.walk_off_hazard()
        if off is not None:  # and the statue stays on its plinth as often (a plinth margin given)
            ok &= self.grid(off) <= target
        return ok

    def best(self, target: float, max_stroke: float | None) -> tuple[int, int]:
        """(iy, ix) of the isolator to name: the lowest P(overturn) over the hazard, then
        the smallest 84th-percentile stroke at the highest level, among the recommended
        (among all where none is): not the region's edge, where the smallest stroke
        alone would lead, a grid step from failing. Among them, an isolator that moves
        before a locked one (`locked`)."""
        p = self.grid(self.p_hazard()).ravel()
        s = self.grid(self.stroke(0.84)[:, -1]).ravel()
        ok = self.recommended(target, max_stroke).ravel()
        moves = ~self.grid(self.locked()).ravel()
        first, second = (np.nan_to_num(v, nan=np.inf) for v in (p, s))
        # an isolator that moves first: a locked one is the fixed base again (LOCKED_STROKE)
        pool = next(np.flatnonzero(m) for m in (ok & moves, ok, np.ones_like(ok)) if m.any())
        k = pool[np.lexsort((second[pool], first[pool]))[0]]
        iy, ix = np.unravel_index(k, self.shape)
        return int(iy), int(ix)


def build_cases(statue: Statue, family, hazard: Hazard, tail: float = DEFAULT_TAIL) -> list[Case]:
    """Every run: the fixed base first, then each isolator (y outer, x inner), each under
    every record (name order) at every level. A record is shared by its levels' cases
    (core.cases._LazyScaled), scaled only when run."""
    systems = [statue.fixed()] + [family.system(statue, x, y) for y in family.y_values for x in family.x_values]
    # a record's factors once, not once per system (each reads the record's peak)
    factors = {name: [record_factor(hazard.records[name], "pga", level) for level in hazard.levels]
               for name in hazard.names}
    cases = []
    for system in systems:
        for name in hazard.names:
            record = hazard.records[name]
            for level, factor in zip(hazard.levels, factors[name]):
                cases.append(Case(len(cases), system, _LazyScaled(record, factor), record.end_time + tail,
                                  {"motion": name, "scale_by": "pga", "intensity": level, "scale_factor": factor}))
    return cases


def simulated_seconds(hazard: Hazard, n_systems: int, tail: float = DEFAULT_TAIL) -> float:
    return n_systems * len(hazard.levels) * sum(r.end_time + tail for r in hazard.records.values())


def settles_at_rest(family, statue: Statue) -> bool:
    """Whether run_design settles the runs in which the block never lifts in closed form
    (analytic.rest_scales): a linear isolator's rest phase, under a statue that cannot slip."""
    return family.kind == LINEAR and statue.friction is None


def design_speed(family, statue: Statue) -> float:
    """Simulated seconds per CPU second of the path run_design takes for this family and statue."""
    if statue.friction is not None:
        return SLIDING_SPEED
    return REST_PHASE_SPEED if settles_at_rest(family, statue) else ISOLATOR_KERNEL_SPEED


def estimate_s(family, hazard: Hazard, tail: float, cores: int, statue: Statue) -> float:
    """Wall seconds a design should take on `cores` idle cores (load on a shared machine
    stretches it), at the speed of the path it takes (design_speed)."""
    simulated = simulated_seconds(hazard, 1 + len(family.x_values) * len(family.y_values), tail)
    return simulated / design_speed(family, statue) / max(cores, 1)


def check_size(family, hazard: Hazard, tail: float = DEFAULT_TAIL) -> int:
    """The number of runs, refused past MAX_DESIGN_RUNS; each run within analytic/limits.py."""
    n = (1 + len(family.x_values) * len(family.y_values)) * len(hazard.records) * len(hazard.levels)
    if n > MAX_DESIGN_RUNS:
        raise InputError(f"design size = {n} runs (isolators × records × levels): must be at most {MAX_DESIGN_RUNS}")
    longest = max(r.end_time for r in hazard.records.values()) + tail
    check_duration("records", longest, " (the longest record + tail)")
    # every family's isolators, not the linear one's only: a friction pendulum of radius
    # 1e-12 m (a period of 2 µs) ran as 'P n/a, stroke nan m' with exit 0
    # (a family's period follows its x axis alone: a period, a radius, a slope)
    for x in family.x_values:
        try:
            check_isolator(family.system(Statue(2.0, 0.7, 1.0, 1.0), x, family.y_values[0]), longest)
        except InputError as e:
            raise InputError(f"{family.x_name} = {x:g}: {e}") from None  # it names the period it spans
    return n


#: the message of a run the rest phase settled (analytic.rest_scales): the block never lifts
SETTLED_AT_REST = "the block never lifts: the rest phase in closed form settles the run (analytic.rest_scales)"


def run_design(statue: Statue, family, hazard: Hazard, *, tail: float = DEFAULT_TAIL, threads: int | None = None,
               progress=None, rest_phase: bool = True) -> Design:
    """Run every case through the one executor (the compiled kernel in batches) and
    gather the outcomes by system, record and level. rest_phase (linear isolators): the
    runs in which the block never lifts are settled first, all levels of a record in one
    pass (analytic.rest_scales), and only the others are run; the outcome is the same
    (tests/test_design.py). progress: None, or a factory (total, label, unit) → a bar
    (io.progress.Progress) for each phase, made when the phase's size is known, closed
    by the caller."""

    check_family_runs(family)
    check_size(family, hazard, tail)
    cases = build_cases(statue, family, hazard, tail)
    n_rec, n_lev = len(hazard.records), len(hazard.levels)
    shape = (1 + len(family.x_values) * len(family.y_values), n_rec, n_lev)
    start = time.perf_counter()
    settled = []
    # the rest phase in closed form holds a statue that cannot slip (a linear isolator's, analytic.rest_scales)
    if rest_phase and settles_at_rest(family, statue):
        bar = progress(shape[0] - 1, "rest phase", "isolators") if progress is not None else None
        settled = _settle_at_rest(cases, shape, hazard, tail, threads, bar)
    done = {row["case"] for row in settled}
    todo = [c for c in cases if c.case not in done]
    bar = progress(len(todo), "kernel", "runs") if progress is not None and todo else None
    table = run_cases(todo, [ENGINE], threads=threads, progress=bar) if todo else None
    if settled:
        import pyarrow as pa  # lazy: pyarrow only where runs were settled

        parts = [rows_to_table(settled)] + ([table] if table is not None else [])
        table = sort_table(pa.concat_tables(parts))
    wall = time.perf_counter() - start
    order = np.argsort(table.column("case").to_numpy())  # sorted by case already; said, not assumed

    def col(name):
        return table.column(name).to_numpy(zero_copy_only=False)[order].reshape(shape)
    return Design(statue, family, hazard, overturned=col("overturned").astype(bool), u_max=col("u_max"),
                  theta_max=col("theta_max_over_alpha"), status=col("status").astype(str), table=table, wall_s=wall,
                  tail=tail, slide=col("slide_max") if statue.friction is not None else None)


def _settle_at_rest(cases, shape, hazard: Hazard, tail: float, threads, bar=None) -> list[dict]:
    """The summary rows of the isolated runs in which the block never lifts, from one
    rest-phase pass per (isolator, record): stays down, completes, stroke factor·max|u₁|."""

    n_sys, n_rec, n_lev = shape
    start = time.perf_counter()
    records = [hazard.records[n] for n in hazard.names]
    factors = np.array([[record_factor(r, "pga", lv) for lv in hazard.levels] for r in records])
    systems = [cases[i * n_rec * n_lev].system for i in range(1, n_sys)]
    uplift, u1 = rest_phases(systems, records, factors, [r.end_time + tail for r in records], workers=threads,
                             on_system=(lambda: bar.update(1)) if bar is not None else None)
    never = ~np.isfinite(uplift)
    per_run = (time.perf_counter() - start) / max(int(never.sum()), 1)
    label = choose(ENGINE, {}, strict=True).label
    rows = []
    for i, r, k in zip(*np.nonzero(never)):
        case = cases[((i + 1) * n_rec + r) * n_lev + k]
        result = {"status": "completed", "message": SETTLED_AT_REST, "theta_max_over_alpha": 0.0, "impacts": 0,
                  "uplifts": 0, "overturned": False, "overturn_time": None, "u_max": float(factors[r, k] * u1[i, r])}
        rows.append({**case_inputs(case), "engine": ENGINE, "setting": label, **row_of_batch(case, result),
                     "runtime_s": per_run})
    return rows


# --- the verdict in words -------------------------------------------------------------------

def _fmt_value(v: float, unit: str) -> str:
    return f"{v:.3g} {unit}".strip()


def _span(values, unit) -> str:
    lo, hi = min(values), max(values)
    return _fmt_value(lo, unit) if lo == hi else f"{lo:.3g}–{_fmt_value(hi, unit)}"


def _pct(p: float) -> str:
    if not math.isfinite(p):
        return "n/a"
    return f"{100 * p:.1f}%" if p < 0.995 or p == 1 else f"{100 * p:.2f}%"


def hazard_text(h: Hazard) -> str:
    levels = (f"PGA {h.levels[0]:g} g" if len(h.levels) == 1
              else f"PGA {h.levels[0]:g}–{h.levels[-1]:g} g in {len(h.levels)} levels")
    weights = "" if len(h.levels) == 1 else (", levels weighted equally" if h.equal_weights else ", levels weighted as given")
    return f"{len(h.records)} records{' (' + h.source + ')' if h.source else ''}, {levels}{weights}"


def region_rows(d: Design, target: float, max_stroke: float | None) -> list[dict]:
    """Per y value (a damping ratio, a friction coefficient): the x values recommended."""
    ok = d.recommended(target, max_stroke)
    fam = d.family
    rows = []
    for iy, y in enumerate(fam.y_values):
        xs = [fam.x_values[ix] for ix in range(len(fam.x_values)) if ok[iy, ix]]
        rows.append({fam.y_name: y, f"{fam.x_name}_recommended": xs})
    return rows


def records_needed(target: float, confidence: float = CONFIDENCE) -> int:
    """The fewest records that can show P(overturn) ≤ target at `confidence` when none
    overturns: Clopper–Pearson's upper bound of 0 of n, 1 − ((1 − confidence)/2)^(1/n),
    at most the target."""
    if not 0 < target < 1:
        return 1
    return math.ceil(math.log((1 - confidence) / 2) / math.log(1 - target))


def target_judgement(p: float, lo: float, hi: float, target: float) -> str:
    """The target judged with P's interval: 'meets' when its upper bound is within it,
    'fails' when its lower bound is past it, 'cannot tell' otherwise (the records are too
    few to say, whichever side the fraction falls)."""
    if not math.isfinite(p):
        return "cannot tell"
    return "meets" if hi <= target else "fails" if lo > target else "cannot tell"


def _p_words(d: Design, k: int, target: float) -> str:
    """P over the hazard with its interval and sample size, and what it says of the target."""
    p, (lo, hi), n = d.p_hazard()[k], d.p_interval()[k], int(d.records_answered()[k])
    judged = target_judgement(p, lo, hi, target)
    text = f"P(overturn) {_pct(p)} [{_pct(lo)}–{_pct(hi)}, {100 * CONFIDENCE:g}%; {n} records] over the hazard"
    if judged == "meets":
        return text + f", within {_pct(target)} at {100 * CONFIDENCE:g}%"
    if judged == "fails":
        return text + f", past {_pct(target)} at {100 * CONFIDENCE:g}%"
    need = records_needed(target)
    return text + (f": {n} records cannot tell it from {_pct(target)} at {100 * CONFIDENCE:g}%"
                   + (f" (even with none overturning, that takes {need})" if n < need else ""))


def verdict(d: Design, target: float, max_stroke: float | None) -> dict:
    """The answer, verdict first: whether the fixed base already meets the target, the
    recommended region in words, the isolator to name, each P with its interval and the
    number of records behind it, the target judged with the interval, a locked isolator
    said."""
    fam, h = d.family, d.hazard
    p_h, p_l = d.p_hazard(), d.p_level()
    p_ci, n_rec, locked = d.p_interval(), d.records_answered(), d.locked()
    s84, s50 = d.stroke(0.84), d.stroke(0.5)
    ok = d.recommended(target, max_stroke)
    iy, ix = d.best(target, max_stroke)
    k = 1 + iy * len(fam.x_values) + ix
    top = h.levels[-1]
    off = d.walk_off_hazard()
    rule = f"P(overturn) ≤ {_pct(target)} over the hazard" + (
        f" and 84th-percentile stroke ≤ {max_stroke:g} m at {top:g} g" if max_stroke is not None else "") + (
        f" and P(walks off its plinth, {d.statue.plinth_margin:g} m) ≤ {_pct(target)}" if off is not None else "")
    walk50, walk84 = d.walk(0.5), d.walk(0.84)

    def walk(i):  # how far the statue walks on its plinth (a statue with friction)
        if walk50 is None:
            return ""
        return (f"; it walks {walk50[i, -1]:.3g} m median, {walk84[i, -1]:.3g} m 84th percentile at {top:g} g"
                + ("" if off is None else f", P(walks off its plinth) {_pct(off[i])} over the hazard"))

    def at_top(i):
        return f" ({_pct(p_l[i, -1])} at {top:g} g)" if len(h.levels) > 1 else ""
    fixed_meets = bool(p_h[0] <= target and (off is None or off[0] <= target))
    fixed = f"Fixed base: {_p_words(d, 0, target)}{at_top(0)}{walk(0)}."
    best = (f"{fam.x_name.replace('_', ' ')} {_fmt_value(fam.x_values[ix], fam.x_unit)}, "
            f"{fam.y_name.replace('_', ' ')} {fam.y_values[iy]:.3g}: {_p_words(d, k, target)}{at_top(k)}"
            + f", stroke {s50[k, -1]:.3g} m median, {s84[k, -1]:.3g} m 84th percentile at {top:g} g" + walk(k)
            + (f" (locked: it barely moves, 84th-percentile stroke under {LOCKED_STROKE * 1e3:g} mm; a fixed base "
               "in effect)" if locked[k] else ""))
    n_ok = int(ok.sum())
    edges = []
    for row in region_rows(d, target, max_stroke):
        got = row[f"{fam.x_name}_recommended"]
        if got:
            whole = len(got) == fam.x_values.index(max(got)) - fam.x_values.index(min(got)) + 1
            edges.append((row[fam.y_name], min(got), max(got), whole))
    x_words = fam.x_name.replace("_", " ")
    # the fixed base first where it already meets the rule: an isolator is then a choice, not a need
    lead = (f"The fixed base already meets {rule} in the fraction of records: no isolator is needed to keep the "
            "statue standing under this hazard. " if fixed_meets else "")
    n_locked = int(locked[1:].sum())
    locked_words = (f" {n_locked} of {ok.size} isolators are locked (84th-percentile stroke under "
                    f"{LOCKED_STROKE * 1e3:g} mm at {top:g} g): a fixed base in effect." if n_locked else "")
    if n_ok:
        headline = (f"{lead}Recommended: {fam.kind} isolators with {x_words} {_region_words(edges, fam)} "
                    f"({n_ok} of {ok.size} on the grid) keep {rule}. Named: {best}. {fixed}{locked_words}")
    else:
        headline = f"{lead}No {fam.kind} isolator on the grid meets {rule}. Lowest P: {best}. {fixed}{locked_words}"

    def judged(i):
        return target_judgement(p_h[i], *p_ci[i], target)
    return {"headline": headline, "rule": rule, "recommended": n_ok, "of": int(ok.size),
            "confidence": CONFIDENCE, "records_needed": records_needed(target),
            "fixed_base_suffices": fixed_meets, "locked": n_locked,
            "best": {fam.x_name: fam.x_values[ix], fam.y_name: fam.y_values[iy], "p_hazard": float(p_h[k]),
                     "p_hazard_interval": [float(v) for v in p_ci[k]], "records": int(n_rec[k]),
                     "target": judged(k), "locked": bool(locked[k]),
                     "p_top": float(p_l[k, -1]), "stroke_median_top": float(s50[k, -1]),
                     "stroke_84_top": float(s84[k, -1]), "fragility_median_pga": float(d.fragility_median(k))},
            "fixed_base": {"p_hazard": float(p_h[0]), "p_hazard_interval": [float(v) for v in p_ci[0]],
                           "records": int(n_rec[0]), "target": judged(0), "p_levels": p_l[0].tolist(),
                           "fragility_median_pga": float(d.fragility_median(0))},
            "region_edges": [{fam.y_name: y, f"{fam.x_name}_from": a, f"{fam.x_name}_to": b, "contiguous": w}
                             for y, a, b, w in edges],
            **({} if walk50 is None else {"walk": {
                "statue_friction": d.statue.friction, "plinth_margin": d.statue.plinth_margin,
                "best_median_top": float(walk50[k, -1]), "best_84_top": float(walk84[k, -1]),
                "fixed_base_median_top": float(walk50[0, -1]), "fixed_base_84_top": float(walk84[0, -1]),
                "best_p_walk_off": None if off is None else float(off[k]),
                "fixed_base_p_walk_off": None if off is None else float(off[0])}})}


def _region_words(edges, fam) -> str:
    """The recommended x values per y, rows with the same span merged: "≥ 2 s at damping
    ratio 0.05–0.13, ≥ 1.5 s at 0.22" (≥ where the span reaches the grid's largest x)."""
    top = max(fam.x_values)
    groups = []
    for y, a, b, whole in edges:
        span = (f"≥ {_fmt_value(a, fam.x_unit)}" if b == top and whole else
                f"{_span([a, b], fam.x_unit)}" + ("" if whole else " (not every value between)"))
        if groups and groups[-1][0] == span and groups[-1][2] == fam.y_values.index(y) - 1:
            groups[-1][1].append(y)
            groups[-1][2] += 1
        else:
            groups.append([span, [y], fam.y_values.index(y)])
    y_words = fam.y_name.replace("_", " ")
    parts = [f"{span} at {_span(ys, fam.y_unit)}" for span, ys, _ in groups]
    return parts[0].replace(" at ", f" at {y_words} ", 1) + "".join(f", {p}" for p in parts[1:])


# --- a few points checked by a contact engine --------------------------------------------------

def check_points(d: Design, target: float, max_stroke: float | None, runs: int) -> list[tuple[int, str, int]]:
    """(system, record, level index) to run again with a contact engine: the named
    isolator, the grid's worst and the fixed base, at the highest level, each under
    records the kernel says overturn and records it says survive (half and half where it
    can), in name order. `runs` in all."""
    fam = d.family
    iy, ix = d.best(target, max_stroke)
    p = d.p_hazard()
    systems = list(dict.fromkeys([1 + iy * len(fam.x_values) + ix, 1 + int(np.nanargmax(p[1:])), 0]))
    per = max(1, runs // len(systems))
    names = d.hazard.names
    level = len(d.hazard.levels) - 1
    picks = []
    for k in systems:
        o = d.overturned[k, :, level]
        fell = [r for r in range(len(names)) if o[r]]
        stood = [r for r in range(len(names)) if not o[r]]
        chosen = fell[:per // 2] + stood[:per - min(per // 2, len(fell))]
        chosen += [r for r in fell if r not in chosen][:per - len(chosen)]
        picks += [(k, names[r], level) for r in chosen[:per]]
    return picks[:max(runs, len(systems))]


def contact_engines(names, *, named=str) -> list[str]:
    """The contact engines a check names, each once, each installed; one line naming the first
    that is not (`named`: the keyword, or the command's option)."""
    contact = [e for e in ALL_ENGINES if not e.startswith("analytic")]
    names = list(names)
    for name in names:
        if name not in contact:
            raise InputError(f"{named('check')} = {name!r}: must be a contact engine, one of {', '.join(contact)}")
    if len(set(names)) != len(names):
        raise InputError(f"{named('check')} = {','.join(names)}: name each engine once")
    for name in names:
        choose(name, {}, strict=True).settings()  # not installed: one line naming the extra
    return names


def check_engines_carry(statue: Statue, family, hazard: Hazard, engines, tail: float = DEFAULT_TAIL, *,
                        named=lambda key: "--" + key) -> None:
    """Each contact engine of a check asked, before any work, whether it carries every run
    the check may pick (the fixed base and every isolator of the family, for the longest
    record): the isolator kind, the engine's own bounds, its steps (core.engines.check_carries,
    as a campaign asks of its grid). It was asked after the whole design, or never."""
    systems = [statue.fixed()] + [family.system(statue, x, y) for y in family.y_values for x in family.x_values]
    longest = max(r.end_time for r in hazard.records.values()) + tail
    for name in engines:
        try:
            check_carries(choose(name, {}, strict=True), systems, longest)
        except InputError as e:
            raise InputError(f"{named('check')} {name}: {e}") from None


def check_with(d: Design, engine: str, picks, *, progress=None) -> dict:
    """The picked runs with `engine` (through the one executor), against the kernel's
    rows: outcomes agreed (overturned or not), and the stroke's relative difference
    where neither overturned, judged by the engine's u_max tolerance (a single history's,
    core.tolerances); runs near overturning may part for reasons of chaos, not of the
    engine (model.md), so the outcome count is reported, not judged."""
    fam, h = d.family, d.hazard
    systems = [d.statue.fixed()] + [fam.system(d.statue, x, y) for y in fam.y_values for x in fam.x_values]
    cases = []
    for k, name, li in picks:
        record, level = h.records[name], h.levels[li]
        factor = record_factor(record, "pga", level)
        cases.append(Case(len(cases), systems[k], _LazyScaled(record, factor), record.end_time + d.tail,
                          {"motion": name, "scale_by": "pga", "intensity": level, "scale_factor": factor}))
    table = run_cases(cases, [engine], progress=progress)
    cols = {c: table.column(c).to_numpy(zero_copy_only=False) for c in ("case", "overturned", "u_max", "status",
                                                                         "theta_max_over_alpha")}
    names = h.names
    limit = tolerance(engine, "u_max_rel_error").limit if has_tolerance(engine, "u_max_rel_error") else math.nan
    rows, answered = [], []
    for i, (k, name, li) in enumerate(picks):
        j = int(np.flatnonzero(cols["case"] == i)[0])
        r = names.index(name)
        # a run either engine did not finish (failed, stopped at its budget or event limit)
        # says nothing of agreement: counted apart and said, never as agreeing (a 1e-30 kg
        # statue's failed MuJoCo runs read "overturning as the analytic model's in 2 of 2")
        answered.append(str(cols["status"][j]) in ANSWERED and str(d.status[k, r, li]) in ANSWERED)
        a_over, e_over = bool(d.overturned[k, r, li]), bool(cols["overturned"][j])
        a_u, e_u = float(d.u_max[k, r, li]), _number(cols["u_max"][j])
        both_stand = not a_over and not e_over and k != 0
        rel = abs(e_u - a_u) / a_u if both_stand and a_u > 0 and math.isfinite(e_u) else math.nan
        rows.append({"system": "fixed base" if k == 0 else _isolator_label(d, k), "record": name,
                     "pga": h.levels[li], "analytic_overturned": a_over, f"{engine}_overturned": e_over,
                     "analytic_u_max": a_u, f"{engine}_u_max": e_u, "u_max_rel_diff": rel,
                     "analytic_theta_max_over_alpha": float(d.theta_max[k, r, li]),
                     f"{engine}_theta_max_over_alpha": _number(cols["theta_max_over_alpha"][j]),
                     f"{engine}_status": str(cols["status"][j])})
    failed = [row for row, ok in zip(rows, answered) if not ok]
    answered = [row for row, ok in zip(rows, answered) if ok]
    agree = sum(row["analytic_overturned"] == row[f"{engine}_overturned"] for row in answered)
    rels = [row["u_max_rel_diff"] for row in answered if math.isfinite(row["u_max_rel_diff"])]
    within = sum(x <= limit for x in rels) if math.isfinite(limit) else None
    text = (f"{engine} on {len(rows)} of the design's runs: overturning as the analytic model's in {agree} of "
            f"{len(answered)}")
    if failed:
        statuses = sorted({row[f"{engine}_status"] for row in failed})
        text += f"; {len(failed)} failed ({', '.join(statuses)}), not counted"
    if rels:
        text += (f"; stroke where both stand: worst {100 * max(rels):.2g}% apart, median {100 * float(np.median(rels)):.2g}%"
                 + (f", {within} of {len(rels)} within its tolerance {100 * limit:.2g}%" if within is not None else ""))
    return {"engine": engine, "runs": rows, "outcomes_agree": agree, "outcomes_differ": len(answered) - agree,
            "failed": len(failed), "n": len(rows), "stroke_rel_diffs": rels, "stroke_tolerance": limit,
            "stroke_within": within, "text": text}


def _number(x) -> float:
    """A table cell as a float (a failed run's missing value: nan)."""
    return math.nan if x is None else float(x)


def _isolator_label(d: Design, k: int) -> str:
    fam = d.family
    iy, ix = divmod(k - 1, len(fam.x_values))
    return (f"{fam.x_name.replace('_', ' ')} {_fmt_value(fam.x_values[ix], fam.x_unit)}, "
            f"{fam.y_name.replace('_', ' ')} {fam.y_values[iy]:.3g}")


#: the shaking directions design weighs for a statue's mesh, one every 10° (analytic.shape's sweep's)
DIRECTIONS = 36


def worst_direction(resting, hazard: Hazard, tail: float, *, threads=None) -> dict:
    """The shaking direction in which the statue on a fixed base overturns most often under the
    hazard (issue 36: design on the worst direction by default): for each of DIRECTIONS
    directions, from the one it tips first (analytic.shape.weakest_direction), the exact model
    of its two edges along it under every record at every level (one batch), and P(overturn)
    over the hazard as the design weighs it (the levels' fractions, weighted). Ties go to the
    first, so a statue that overturns nowhere keeps the direction it tips first.
    {azimuth_deg, body, p_hazard, p_by_azimuth}."""
    start = weakest_direction(resting)[0]
    angles = [(start + 2.0 * math.pi * k / DIRECTIONS) % (2.0 * math.pi) for k in range(DIRECTIONS)]
    systems = along_directions(resting, angles)
    cases = [(name, level) for name in hazard.names for level in hazard.levels]
    motions = [unit_scaled(hazard.records[name], level) for name, level in cases]
    durations = [hazard.records[name].end_time + tail for name, _ in cases]
    rows = simulate_batch(systems, motions, duration=np.tile(durations, len(systems)), product=True,
                          workers=threads)
    over = np.array([r["overturned"] for r in rows], bool).reshape(len(systems), len(hazard.names),
                                                                   len(hazard.levels))
    p = over.mean(axis=1) @ np.asarray(hazard.weights)
    k = int(np.argmax(p))
    return dict(azimuth_deg=math.degrees(angles[k]), body=systems[k].body, p_hazard=float(p[k]),
                p_by_azimuth=dict(zip([round(math.degrees(a), 6) for a in angles], p.tolist())))


def unit_scaled(record: GroundMotion, level: float) -> GroundMotion:
    """The record as a design run sees it at `level` (g): what a direct run must be given
    to reproduce a chart cell."""
    return _LazyScaled(record, record_factor(record, "pga", level)).motion()
