"""The physical system: a rigid block (statue) on a base plate tied to the ground
by an isolator (by default a linear spring and dashpot; or a bilinear hysteretic bearing,
or a friction pendulum: docs/isolators.md), or on a fixed base.

Units are SI throughout (m, kg, s, N/m, N·s/m). Sign conventions follow
`shared/docs/model.md`: u is the base displacement relative to the ground,
θ > 0 is rocking about corner O (the centroid moves towards +x).
"""
from __future__ import annotations

import math
from types import MappingProxyType
from dataclasses import dataclass, replace

from .errors import InputError, require, require_nonnegative_finite, require_positive_finite

STANDARD_GRAVITY = 9.81  # m/s², the value the paper's β and thresholds are quoted with

#: isolator kinds, as a System's `isolator_kind`, the CLI's --isolator and the engines'
#: Capabilities.isolators name them
LINEAR, BILINEAR, FRICTION_PENDULUM = "linear", "bilinear", "friction-pendulum"
BALL_IN_CONE, BALL_IN_BOWL, DOUBLE_PENDULUM = "ball-in-cone", "ball-in-bowl", "double-friction-pendulum"
ISOLATOR_KINDS = (LINEAR, BILINEAR, FRICTION_PENDULUM, BALL_IN_CONE, BALL_IN_BOWL, DOUBLE_PENDULUM)


@dataclass(frozen=True)
class Solid:
    """A statue's own shape, for the contact engines that carry it (issue 36; docs/statues.md,
    "The contact engines on the base and isolator"): the vertices of its convex hull relative
    to its centre of mass (m; x the shaking direction, z up, the plinth at z = −h), and its
    inertia tensor about the centre of mass in the same frame (kg·m²). The hull is exact for
    contact with a flat plinth: nothing inside it can touch one. The exact model reads none
    of it (its PlanarBody's edges are the hull's, in that direction); a scene builds it."""

    vertices: tuple  # ((x, y, z), ...)
    inertia: tuple  # ((Ixx, Ixy, Ixz), (Ixy, Iyy, Iyz), (Ixz, Iyz, Izz))

    def __post_init__(self):
        rows = tuple(tuple(float(c) for c in v) for v in self.vertices)
        require(len(rows) >= 4 and all(len(v) == 3 and all(math.isfinite(c) for c in v) for v in rows),
                "vertices", f"{len(rows)} rows", "at least 4 finite (x, y, z) points (a solid's hull)")
        inertia = tuple(tuple(float(c) for c in r) for r in self.inertia)
        require(len(inertia) == 3 and all(len(r) == 3 and all(math.isfinite(c) for c in r) for r in inertia)
                and all(inertia[i][i] > 0 for i in range(3)), "inertia", inertia,
                "a 3×3 tensor with positive finite diagonal (kg·m²)")
        object.__setattr__(self, "vertices", rows)
        object.__setattr__(self, "inertia", inertia)

    @classmethod
    def of_resting(cls, body) -> "Solid":
        """The solid of a statue's mesh at rest (analytic.shape.RestingBody, turned onto its
        shaking direction): its hull's vertices about the centre of mass, and its inertia."""
        return cls(vertices=tuple(map(tuple, (body.vertices - body.com).tolist())),
                   inertia=tuple(map(tuple, body.inertia.tolist())))


@dataclass(frozen=True)
class PlanarBody:
    """A statue that is not a symmetric rectangle, as the planar model sees it in one shaking
    direction (issue 36; docs/statues.md): its centre of mass `centre_height` h above the
    plinth, `lever_forward` b₊ and `lever_backward` b₋ the horizontal distances from it to the
    two tipping edges (b₊ to the edge about which θ > 0 rocks, the body turning towards +x,
    lifted by a ground acceleration below −g·b₊/h), and `inertia` I_c (kg·m²) about the centre of
    mass, about the axis of rocking. Each edge s has its own α_s = atan(b_s/h), R_s = √(b_s² + h²)
    and I_s = I_c + m R_s²; an impact onto the other edge conserves the angular momentum about
    it (model.md's map, re-derived for two edges: physics.system_params). The rectangle is
    b₊ = b₋ = b, h = H/2, I_c = m(b² + h²)/3."""

    centre_height: float
    lever_forward: float
    lever_backward: float
    inertia: float
    #: its own shape (a Solid), where it came from a mesh: what a contact engine carries on a
    #: free joint; None: a planar body of two edges only (a scene makes it a box on its edges)
    solid: Solid | None = None

    def __post_init__(self):
        for name in ("centre_height", "lever_forward", "lever_backward", "inertia"):
            object.__setattr__(self, name, require_positive_finite(name, getattr(self, name)))

    def lever(self, side: int) -> float:
        """b_s (m) of the edge on `side` (+1 forward, −1 backward)."""
        return self.lever_forward if side > 0 else self.lever_backward

    def alpha(self, side: int) -> float:
        return math.atan2(self.lever(side), self.centre_height)

    def radius(self, side: int) -> float:
        return math.hypot(self.lever(side), self.centre_height)

    @property
    def weaker_side(self) -> int:
        """The edge it tips about first (the smaller α; forward on a tie)."""
        return 1 if self.lever_forward <= self.lever_backward else -1

    @classmethod
    def rectangle(cls, height: float, width: float, mass: float) -> "PlanarBody":
        """The symmetric block H × B of mass m as a PlanarBody (the model's special case)."""
        h, b = 0.5 * height, 0.5 * width
        return cls(centre_height=h, lever_forward=b, lever_backward=b, inertia=mass * (b * b + h * h) / 3)

    @classmethod
    def from_resting(cls, body) -> "PlanarBody":
        """The planar body of a statue's mesh at rest, shaken along its x (analytic.shape.RestingBody,
        turned with .along(azimuth)): b± from the centre of mass to the footprint's extremes."""
        fw, bw = body.direction(1), body.direction(-1)
        return cls(centre_height=fw["h"], lever_forward=fw["b"], lever_backward=bw["b"],
                   inertia=float(body.inertia[1, 1]), solid=Solid.of_resting(body))

    @property
    def box(self) -> dict:
        """height 2h and width b₊ + b₋ of the block whose place it takes in a System: what the
        System's own checks and a report read (its physics reads the body's edges)."""
        return dict(height=2.0 * self.centre_height, width=self.lever_forward + self.lever_backward)

    def describe(self) -> dict:
        return {"centre_height": self.centre_height, "lever_forward": self.lever_forward,
                "lever_backward": self.lever_backward, "centroidal_inertia": self.inertia,
                "alpha_forward": self.alpha(1), "alpha_backward": self.alpha(-1)}


@dataclass(frozen=True)
class LinearIsolator:
    """The seed paper's isolator: a linear spring `stiffness` k (N/m) and dashpot `damping`
    c (N·s/m). A System holds it as its own `stiffness` and `damping` (its default)."""

    stiffness: float
    damping: float = 0.0
    kind = LINEAR

    def __post_init__(self):
        object.__setattr__(self, "stiffness", require_positive_finite("stiffness", self.stiffness))
        object.__setattr__(self, "damping", require_nonnegative_finite("damping", self.damping))

    def describe(self, total_mass: float, gravity: float) -> dict:
        return {"isolator": LINEAR}


@dataclass(frozen=True)
class BilinearIsolator:
    """A hysteretic bearing (Roussis & Odysseos 2017): an elastic–perfectly-plastic spring of
    stiffness (1 − r)·k0 yielding at `yield_displacement` u_y, in parallel with the
    post-yield spring r·k0 and a dashpot `damping` c. `stiffness`: the initial stiffness
    k0 (N/m); `post_yield_ratio`: r in [0, 1) (0: elastic–perfectly-plastic). The yield
    force is k0·u_y (`yield_force`)."""

    stiffness: float
    post_yield_ratio: float
    yield_displacement: float
    damping: float = 0.0
    kind = BILINEAR

    def __post_init__(self):
        object.__setattr__(self, "stiffness", require_positive_finite("stiffness", self.stiffness))
        r = require_nonnegative_finite("post_yield_ratio", self.post_yield_ratio)
        require(r < 1, "post_yield_ratio", self.post_yield_ratio,
                "in [0, 1) (post-yield over initial stiffness; 1 is the linear isolator)")
        object.__setattr__(self, "post_yield_ratio", r)
        object.__setattr__(self, "yield_displacement",
                           require_positive_finite("yield_displacement", self.yield_displacement))
        object.__setattr__(self, "damping", require_nonnegative_finite("damping", self.damping))

    @property
    def yield_force(self) -> float:
        """k0·u_y (N): the force at which the bearing first yields."""
        return self.stiffness * self.yield_displacement

    def describe(self, total_mass: float, gravity: float) -> dict:
        return {"isolator": BILINEAR, "post_yield_ratio": self.post_yield_ratio,
                "yield_displacement": self.yield_displacement, "yield_force": self.yield_force}


#: largest statue–base friction coefficient (System.friction): stone on stone, wood or metal
#: lies at 0.2–0.8; beyond 10 a coefficient means "it cannot slip", which None says exactly
MAX_STATUE_FRICTION = 10.0

#: largest friction coefficient a friction pendulum may be given: measured sliders lie far
#: below it (0.01–0.2); above it a "friction" pendulum is a fixed base with extra steps
MAX_FRICTION_COEFFICIENT = 1.0


@dataclass(frozen=True)
class FrictionPendulum:
    """A single concave friction pendulum: the base slides on a spherical surface of
    `radius` R_fp (m) with Coulomb friction coefficient `friction_coefficient` μ_f. Its
    restoring force is (M·g/R_fp)·u and its friction μ_f·M·g (docs/isolators.md: the
    normal force is taken as M·g in both modes, and why). A double concave slider is not
    modelled yet.

    Velocity-dependent friction (optional): with `friction_rate` a > 0 (s/m) the friction
    coefficient while slipping at speed v is μ_f(v) = μ_max − (μ_max − μ_f)·exp(−a|v|),
    μ_max = `friction_max`; `friction_coefficient` is then μ_min, the value at rest, which
    is what holds a stuck slider. a = 0 (the default) is Coulomb friction μ_f."""

    radius: float
    friction_coefficient: float
    friction_max: float | None = None
    friction_rate: float = 0.0
    kind = FRICTION_PENDULUM

    def __post_init__(self):
        object.__setattr__(self, "radius", require_positive_finite("radius", self.radius))
        mu = require_nonnegative_finite("friction_coefficient", self.friction_coefficient)
        require(mu <= MAX_FRICTION_COEFFICIENT, "friction_coefficient", self.friction_coefficient,
                f"a friction coefficient in [0, {MAX_FRICTION_COEFFICIENT:g}]")
        object.__setattr__(self, "friction_coefficient", mu)
        rate = require_nonnegative_finite("friction_rate", self.friction_rate)
        object.__setattr__(self, "friction_rate", rate)
        if self.friction_max is None:
            require(rate == 0.0, "friction_rate", self.friction_rate, "0 unless friction_max (μ_max) is given")
            object.__setattr__(self, "friction_max", mu)
        top = require_nonnegative_finite("friction_max", self.friction_max)
        require(mu <= top <= MAX_FRICTION_COEFFICIENT, "friction_max", self.friction_max,
                f"a friction coefficient in [friction_coefficient = {mu:g}, {MAX_FRICTION_COEFFICIENT:g}]")
        object.__setattr__(self, "friction_max", top)

    def describe(self, total_mass: float, gravity: float) -> dict:
        d = {"isolator": FRICTION_PENDULUM, "radius": self.radius,
             "friction_coefficient": self.friction_coefficient,
             "friction_force": self.friction_coefficient * total_mass * gravity}
        if self.friction_rate > 0.0:  # μ_f(v): friction_coefficient is μ_min
            d.update(friction_max=self.friction_max, friction_rate=self.friction_rate)
        return d


def _friction(name, value):
    """A friction (or rolling-resistance) coefficient in [0, MAX_FRICTION_COEFFICIENT]."""
    mu = require_nonnegative_finite(name, value)
    require(mu <= MAX_FRICTION_COEFFICIENT, name, value,
            f"a friction coefficient in [0, {MAX_FRICTION_COEFFICIENT:g}]")
    return mu


#: steepest cone a ball-in-cone isolator may be given (tanφ): above it the "isolator"
#: transmits more than g, no isolation at all
MAX_CONE_SLOPE = 1.0


@dataclass(frozen=True)
class BallInCone:
    """A rolling isolator, ball in a conical dish: a constant restoring force
    M·g·tanφ·sgn(u) (`slope` = tanφ, the cone's rise over run) and a rolling resistance
    `rolling_resistance` μ_r that acts as Coulomb friction μ_r·M·g (the base holds while its
    demand is within it; at the cone's vertex, u = 0, within M·g·(tanφ + μ_r)). The force
    switches sign at u = 0, an event. No linear stiffness: its free period
    4√(2u₀/(g·tanφ)) grows with the amplitude u₀ (System.period is inf)."""

    slope: float
    rolling_resistance: float = 0.0
    kind = BALL_IN_CONE

    def __post_init__(self):
        tan_phi = require_positive_finite("slope", self.slope)
        require(tan_phi <= MAX_CONE_SLOPE, "slope", self.slope,
                f"tanφ in (0, {MAX_CONE_SLOPE:g}] (the cone's rise over run)")
        object.__setattr__(self, "slope", tan_phi)
        object.__setattr__(self, "rolling_resistance", _friction("rolling_resistance", self.rolling_resistance))

    def describe(self, total_mass: float, gravity: float) -> dict:
        return {"isolator": BALL_IN_CONE, "slope": self.slope, "rolling_resistance": self.rolling_resistance,
                "restoring_force": self.slope * total_mass * gravity,
                "friction_force": self.rolling_resistance * total_mass * gravity}


@dataclass(frozen=True)
class BallInBowl:
    """A rolling isolator, ball in a spherical bowl of effective radius `radius` R_eff (m):
    restoring force M·g·u/R_eff and rolling resistance μ_r·M·g. Its equations are the
    friction pendulum's with μ_f = μ_r (`as_pendulum`), and it runs as one."""

    radius: float
    rolling_resistance: float = 0.0
    kind = BALL_IN_BOWL

    def __post_init__(self):
        object.__setattr__(self, "radius", require_positive_finite("radius", self.radius))
        object.__setattr__(self, "rolling_resistance", _friction("rolling_resistance", self.rolling_resistance))

    @property
    def as_pendulum(self) -> FrictionPendulum:
        """The friction pendulum of the same equations (radius R_eff, μ_f = μ_r)."""
        return FrictionPendulum(self.radius, self.rolling_resistance)

    def describe(self, total_mass: float, gravity: float) -> dict:
        return {"isolator": BALL_IN_BOWL, "radius": self.radius, "rolling_resistance": self.rolling_resistance,
                "friction_force": self.rolling_resistance * total_mass * gravity}


@dataclass(frozen=True)
class DoubleFrictionPendulum:
    """A double concave friction pendulum (Fenz & Constantinou 2008): two spherical surfaces
    of radii `radius_1`, `radius_2` (m) and friction `friction_1`, `friction_2`, in series
    through an articulated slider: F = W·u1/R1 + μ1·W·sgn(u̇1) = W·u2/R2 + μ2·W·sgn(u̇2),
    u = u1 + u2, W = M·g. Equal frictions: one pendulum of radius R1 + R2. Otherwise the
    surface of lower friction slides alone (stiffness W/R_lo) until the force reaches the
    other's μ·W, then both (stiffness W/(R1 + R2)); docs/isolators.md gives the equivalent
    the model runs: a rigid slider μ_lo·W, a spring W/(R1 + R2) and a Jenkins element."""

    radius_1: float
    friction_1: float
    radius_2: float
    friction_2: float
    kind = DOUBLE_PENDULUM

    def __post_init__(self):
        for name in ("radius_1", "radius_2"):
            object.__setattr__(self, name, require_positive_finite(name, getattr(self, name)))
        for name in ("friction_1", "friction_2"):
            object.__setattr__(self, name, _friction(name, getattr(self, name)))

    @property
    def series(self) -> tuple[float, float, float, float]:
        """(R_lo, μ_lo, R_hi, μ_hi): the surfaces ordered by friction (the series is symmetric)."""
        if self.friction_1 <= self.friction_2:
            return self.radius_1, self.friction_1, self.radius_2, self.friction_2
        return self.radius_2, self.friction_2, self.radius_1, self.friction_1

    @property
    def transition_displacement(self) -> float:
        """2(μ_hi − μ_lo)·R_lo (m): the stroke of the lower-friction surface alone, after a
        reversal, before the other starts to slide (the loop's kink)."""
        r_lo, mu_lo, _, mu_hi = self.series
        return 2.0 * (mu_hi - mu_lo) * r_lo

    def describe(self, total_mass: float, gravity: float) -> dict:
        return {"isolator": DOUBLE_PENDULUM, "radius_1": self.radius_1, "friction_1": self.friction_1,
                "radius_2": self.radius_2, "friction_2": self.friction_2}


NONLINEAR_ISOLATORS = (BilinearIsolator, FrictionPendulum, BallInCone, BallInBowl, DoubleFrictionPendulum)


@dataclass(frozen=True)
class System:
    """Block of height `height` = 2h and width `width` = 2b, mass `mass`, on a base of
    mass `base_mass` with isolator stiffness `stiffness` (N/m) and dashpot `damping`
    (N·s/m). `fixed_base=True` means the base is welded to the ground (μ = 0).

    `friction`: the Coulomb coefficient μ_s between the statue and its base (the static one:
    what holds a statue at rest or a corner while it rocks); None (the default) is the seed
    paper's no-slip assumption, and every result is then the no-slip model's to the last
    digit. `kinetic_friction`: μ_k while it slips (None: μ_s; at most μ_s). A statue with
    friction slides, rocks or slides and rocks (docs/sliding.md).

    `isolator`: None (the default) is the linear spring–dashpot of `stiffness` and
    `damping`; a BilinearIsolator or a FrictionPendulum replaces it, and then `stiffness`
    and `damping` are derived from it (its initial stiffness k0 and dashpot; the
    pendulum's M·g/R_fp and 0), so that the period and every reader of them stay
    meaningful. A LinearIsolator given here is stored as `stiffness` and `damping`.

    Build it with `System.isolated(...)` (period and damping ratio),
    `System.from_stiffness(...)`, `System.with_isolator(...)` or `System.fixed(...)`;
    the constructor validates.
    """

    height: float
    width: float
    mass: float
    base_mass: float
    stiffness: float = 0.0
    damping: float = 0.0
    fixed_base: bool = False
    gravity: float = STANDARD_GRAVITY
    isolator: (LinearIsolator | BilinearIsolator | FrictionPendulum | BallInCone | BallInBowl
               | DoubleFrictionPendulum | None) = None
    friction: float | None = None
    kinetic_friction: float | None = None
    body: PlanarBody | None = None

    def __post_init__(self):
        for name in ("height", "width", "mass", "base_mass", "gravity"):
            object.__setattr__(self, name, require_positive_finite(name, getattr(self, name)))
        self._check_friction()
        if self.body is not None:
            require(isinstance(self.body, PlanarBody), "body", self.body, "a PlanarBody (or None: the rectangle)")
            require(self.friction is None, "friction", self.friction,
                    "absent for a statue of two different edges (body): the sliding model takes the rectangle")
        iso = self.isolator
        if iso is not None:
            require(isinstance(iso, (LinearIsolator,) + NONLINEAR_ISOLATORS), "isolator", iso,
                    "a LinearIsolator, BilinearIsolator, FrictionPendulum, BallInCone, BallInBowl or "
                    "DoubleFrictionPendulum")
            require(not self.fixed_base, "isolator", iso.kind, "absent on a fixed base")
            if isinstance(iso, LinearIsolator):  # the default, held as stiffness and damping
                object.__setattr__(self, "stiffness", iso.stiffness)
                object.__setattr__(self, "damping", iso.damping)
                object.__setattr__(self, "isolator", None)
            elif isinstance(iso, BilinearIsolator):
                object.__setattr__(self, "stiffness", iso.stiffness)
                object.__setattr__(self, "damping", iso.damping)
            elif iso.kind == BALL_IN_CONE:  # a constant restoring force: no stiffness, no period
                object.__setattr__(self, "stiffness", 0.0)
                object.__setattr__(self, "damping", 0.0)
            else:  # a pendulum's (or bowl's) restoring stiffness M·g/R, no dashpot
                radius = iso.radius_1 + iso.radius_2 if iso.kind == DOUBLE_PENDULUM else iso.radius
                object.__setattr__(self, "stiffness", (self.mass + self.base_mass) * self.gravity / radius)
                object.__setattr__(self, "damping", 0.0)
        for name in ("stiffness", "damping"):
            object.__setattr__(self, name, require_nonnegative_finite(name, getattr(self, name)))
        if not self.fixed_base and self.isolator_kind != BALL_IN_CONE:
            require(self.stiffness > 0, "stiffness", self.stiffness,
                    "positive for an isolated base (use System.fixed for a fixed base)")

    def _check_friction(self):
        if self.friction is None:
            require(self.kinetic_friction is None, "kinetic_friction", self.kinetic_friction,
                    "absent unless friction (μ_s, the static coefficient) is given")
            return
        mu_s = require_positive_finite("friction", self.friction)
        require(mu_s <= MAX_STATUE_FRICTION, "friction", self.friction,
                f"a friction coefficient in (0, {MAX_STATUE_FRICTION:g}] (None: no slip)")
        mu_k = mu_s if self.kinetic_friction is None else require_positive_finite(
            "kinetic_friction", self.kinetic_friction)
        require(mu_k <= mu_s, "kinetic_friction", self.kinetic_friction,
                f"a kinetic coefficient in (0, μ_s = {mu_s:g}] (μ_k ≤ μ_s)")
        object.__setattr__(self, "friction", mu_s)
        object.__setattr__(self, "kinetic_friction", mu_k)

    @property
    def slides(self) -> bool:
        """Whether the statue may slip on its base (a finite friction μ_s)."""
        return self.friction is not None

    def with_friction(self, friction: float | None, kinetic_friction: float | None = None) -> "System":
        """The same system with statue–base friction μ_s (and μ_k; None: μ_s), or none (no slip)."""
        return replace(self, friction=friction, kinetic_friction=kinetic_friction)

    # --- constructors -----------------------------------------------------------
    @classmethod
    def isolated(cls, *, height, width, mass, base_mass, period, damping_ratio,
                 gravity=STANDARD_GRAVITY) -> "System":
        """Isolated base from the isolation period T = 2π√(M/k) (s) and damping
        ratio ξ = c / (2Mω)."""
        T = require_positive_finite("period", period)
        xi = require_nonnegative_finite("damping_ratio", damping_ratio)
        M = require_positive_finite("mass", mass) + require_positive_finite("base_mass", base_mass)
        omega = 2 * math.pi / T
        return cls(height=height, width=width, mass=mass, base_mass=base_mass,
                   stiffness=M * omega**2, damping=2 * xi * M * omega, gravity=gravity)

    @classmethod
    def from_stiffness(cls, *, height, width, mass, base_mass, stiffness, damping,
                       gravity=STANDARD_GRAVITY) -> "System":
        return cls(height=height, width=width, mass=mass, base_mass=base_mass,
                   stiffness=stiffness, damping=damping, gravity=gravity)

    @classmethod
    def with_isolator(cls, *, height, width, mass, base_mass, isolator,
                      gravity=STANDARD_GRAVITY) -> "System":
        """Isolated base on `isolator` (a LinearIsolator, BilinearIsolator or FrictionPendulum)."""
        return cls(height=height, width=width, mass=mass, base_mass=base_mass, isolator=isolator,
                   gravity=gravity)

    @classmethod
    def fixed(cls, *, height, width, mass, base_mass=None, gravity=STANDARD_GRAVITY) -> "System":
        """Fixed (non-isolated) base: m_b → ∞, μ = 0. base_mass is kept only for
        building contact scenes (their plate needs a mass); it does not enter the physics."""
        return cls(height=height, width=width, mass=mass,
                   base_mass=mass if base_mass is None else base_mass,
                   fixed_base=True, gravity=gravity)

    @classmethod
    def of_body(cls, body: PlanarBody, *, mass, gravity=STANDARD_GRAVITY) -> "System":
        """A statue of two edges (`body`, mass kg) on a fixed base."""
        return replace(cls.fixed(**body.box, mass=mass, gravity=gravity), body=body)

    def on_fixed_base(self) -> "System":
        """The same block (and its friction) on a fixed base (its base mass kept for a scene's plate)."""
        return replace(System.fixed(height=self.height, width=self.width, mass=self.mass, base_mass=self.base_mass,
                                    gravity=self.gravity), body=self.body).with_friction(self.friction,
                                                                                        self.kinetic_friction)

    def on_isolator(self, period: float, damping_ratio: float) -> "System":
        """The same block (and its friction) and base mass on an isolator of period T (s) and damping ratio ξ."""
        return replace(System.isolated(height=self.height, width=self.width, mass=self.mass, base_mass=self.base_mass,
                                       period=period, damping_ratio=damping_ratio, gravity=self.gravity),
                       body=self.body).with_friction(self.friction, self.kinetic_friction)

    # --- geometry ---------------------------------------------------------------
    # A System with a `body` (two different edges) answers these for the edge it tips about
    # first (PlanarBody.weaker_side): the smaller α, its R, p, λ and threshold; `lever(s)`,
    # `edge_alpha(s)` and `edge_radius(s)` give either edge. Without one, the rectangle's.
    @property
    def asymmetric(self) -> bool:
        """Whether the statue has two different edges (a `body`), not the rectangle H × B."""
        return self.body is not None

    def lever(self, side: int) -> float:
        """b_s (m): the horizontal distance from the centre of mass to the edge on `side` (±1)."""
        return self.b if self.body is None else self.body.lever(side)

    def edge_alpha(self, side: int) -> float:
        """α_s = atan(b_s/h) of the edge on `side` (rad)."""
        return self.alpha if self.body is None else self.body.alpha(side)

    def edge_radius(self, side: int) -> float:
        """R_s = √(b_s² + h²) of the edge on `side` (m)."""
        return self.R if self.body is None else self.body.radius(side)

    def edge_inertia(self, side: int) -> float:
        """I_s = I_c + m R_s² about the edge on `side` (kg·m²)."""
        return self.mass * self.edge_radius(side) ** 2 + self.inertia

    @property
    def subject(self) -> str:
        """How a report names what rocks: "the statue" for a statue's own shape (body), else
        "the block"."""
        return "the block" if self.body is None else "the statue"

    @property
    def h(self) -> float:
        """Half height (m): centroid height above the base (a body's centre of mass height)."""
        return 0.5 * self.height if self.body is None else self.body.centre_height

    @property
    def b(self) -> float:
        """Half width (m); a body's lever of the edge it tips about first."""
        return 0.5 * self.width if self.body is None else self.body.lever(self.body.weaker_side)

    @property
    def R(self) -> float:
        """Centroid-to-corner distance √(b² + h²) (m)."""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Critical angle atan(b/h) (rad)."""
        return math.atan2(self.b, self.h)

    @property
    def slenderness(self) -> float:
        """λ = h/b."""
        return self.h / self.b

    @property
    def p(self) -> float:
        """Frequency parameter √(3g / 4R) (rad/s); a body's √(m g R/I_O) of its weaker edge."""
        if self.body is not None:
            return math.sqrt(self.mass * self.gravity * self.R / (self.mass * self.R ** 2 + self.inertia))
        return math.sqrt(3 * self.gravity / (4 * self.R))

    @property
    def inertia(self) -> float:
        """Centroidal moment of inertia m(b² + h²)/3 (kg·m²); a body's own I_c."""
        return self.mass * (self.b**2 + self.h**2) / 3 if self.body is None else self.body.inertia

    # --- base ---------------------------------------------------------------------
    @property
    def mu(self) -> float:
        """Mass ratio m / m_b; 0 on a fixed base."""
        return 0.0 if self.fixed_base else self.mass / self.base_mass

    @property
    def total_mass(self) -> float:
        """M = m + m_b (kg)."""
        return self.mass + self.base_mass

    @property
    def omega(self) -> float:
        """Isolation circular frequency √(k/M) (rad/s); inf on a fixed base."""
        return math.inf if self.fixed_base else math.sqrt(self.stiffness / self.total_mass)  # 0: the cone

    @property
    def period(self) -> float:
        """Isolation period 2π√(M/k) (s); 0 on a fixed base; inf on a ball-in-cone isolator
        (no stiffness: its period depends on the amplitude)."""
        if self.fixed_base:
            return 0.0
        return math.inf if self.stiffness == 0.0 else 2 * math.pi / self.omega

    @property
    def damping_ratio(self) -> float:
        """ξ = c / (2Mω); 0 on a fixed base."""
        return 0.0 if self.fixed_base or self.stiffness == 0.0 else self.damping / (2 * self.total_mass * self.omega)

    @property
    def rocking_rate(self) -> float:
        """p_eff (rad/s): the block's small-angle rocking rate with its base's recoil. A free
        base takes m·h²·μ/(1+μ) of the block's inertia about its pivot, I_O = (4/3)·m·R², so
        p_eff = p/√(1 − ¾·cos²α·μ/(1+μ)); p on a fixed base; a statue's, of its weaker edge's
        own I_O = I_c + m·R²: p_eff = p/√(1 − m·h²/I_O·μ/(1+μ)). Contact engines scale their
        steps with it (docs/mujoco.md, "A rule that follows the system")."""
        share = 0.0 if self.fixed_base else self.mu / (1 + self.mu)
        if self.body is None:  # the block: m·h²/I_O = ¾·cos²α, its closed form (kept digit for digit)
            return self.p / math.sqrt(1 - 0.75 * math.cos(self.alpha) ** 2 * share)
        # a statue: its own inertia about its weaker edge, I_O = I_c + m·R², not the block's 4/3·m·R²
        # (a bust's I_c is smaller: its base's recoil takes a larger share, it rocks faster)
        return self.p / math.sqrt(1 - self.mass * self.h ** 2 / (self.inertia + self.mass * self.R ** 2) * share)

    @property
    def isolator_kind(self) -> str:
        """One of ISOLATOR_KINDS ("linear" on a fixed base too: no isolator to refuse)."""
        return LINEAR if self.isolator is None else self.isolator.kind

    @property
    def isolator_model(self):
        """The isolator as its own type (a LinearIsolator for the default), None on a fixed base."""
        if self.fixed_base:
            return None
        return self.isolator if self.isolator is not None else LinearIsolator(self.stiffness, self.damping)

    @property
    def uplift_acceleration(self) -> float:
        """|a| above which rocking starts: g·tanα = g b/h (m/s²)."""
        return self.gravity * self.b / self.h

    def describe(self) -> dict:
        """Plain numbers for reports and JSON."""
        return {
            "height": self.height, "width": self.width, "mass": self.mass,
            "base_mass": self.base_mass, "fixed_base": self.fixed_base,
            "stiffness": self.stiffness, "damping": self.damping,
            "period": self.period, "damping_ratio": self.damping_ratio,
            "alpha": self.alpha, "slenderness": self.slenderness, "mass_ratio": self.mu,
            "R": self.R, "p": self.p, "gravity": self.gravity,
            **({} if self.isolator is None else self.isolator.describe(self.total_mass, self.gravity)),
            # only where the statue may slip: a no-slip system's description is as before
            **({} if self.friction is None else {"friction": self.friction,
                                                 "kinetic_friction": self.kinetic_friction}),
            # only for a statue of two edges: a rectangle's description is as before
            **({} if self.body is None else {"body": self.body.describe()}),
        }


#: The paper's isolator as we read it (model.md): period T (s) and damping ratio ξ. The
#: paper's digits are unreadable in our copy ("T = ?.5 s", "ξ = ?"); these fit its Figure 5.
PAPER_PERIOD, PAPER_DAMPING_RATIO = 1.5, 0.2
#: The paper's Figure 5 block: height and width (m), the block's mass and the base's (kg).
PAPER_BLOCK = MappingProxyType(dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0))
#: The paper's system in words, for help texts and reports.
PAPER_TEXT = (f"H {PAPER_BLOCK['height']:.1f} m, B {PAPER_BLOCK['width']:g} m, m = m_b = {PAPER_BLOCK['mass']:g} kg, "
              f"T {PAPER_PERIOD:g} s, ξ {PAPER_DAMPING_RATIO:g}")


def paper_system(*, fixed_base: bool = False, period: float = PAPER_PERIOD,
                 damping_ratio: float = PAPER_DAMPING_RATIO) -> System:
    """The paper's Figure 5 block: H 2.0 m, B 0.7 m, m = m_b = 3800 kg; the period and
    damping that fit the paper's figure are T = 1.5 s, ξ = 0.2 (model.md)."""
    if fixed_base:
        return System.fixed(**PAPER_BLOCK)
    return System.isolated(**PAPER_BLOCK, period=period, damping_ratio=damping_ratio)


__all__ = ["System", "PlanarBody", "InputError", "LinearIsolator", "BilinearIsolator", "FrictionPendulum", "BallInCone",
           "BallInBowl", "DoubleFrictionPendulum", "ISOLATOR_KINDS", "BALL_IN_CONE", "BALL_IN_BOWL",
           "DOUBLE_PENDULUM", "LINEAR", "BILINEAR", "FRICTION_PENDULUM", "paper_system", "STANDARD_GRAVITY", "PAPER_PERIOD",
           "PAPER_DAMPING_RATIO", "PAPER_BLOCK", "PAPER_TEXT"]
