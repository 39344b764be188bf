"""The isolator as the parts a contact engine builds it from (docs/isolators.md, "The
equations"): a parallel spring k and dashpot c on the base, the base's own dry friction (the
pendulum's rigid slider: the base itself sticks), and a Jenkins element — a spring k_e in
series with a Coulomb slider of slip force F_s. The friction pendulum and the ball in a bowl
(the same equations, `BallInBowl.as_pendulum`) have the base's friction alone, the bilinear
bearing the element alone, and the double concave pendulum both at once. Derived once, from
the same `physics.isolator_params` the analytic model integrates, so MuJoCo's scene and
PyBullet's force law cannot read the isolator differently from the model they are judged
against.
"""
from __future__ import annotations

from dataclasses import dataclass

from .errors import InputError
from .physics import C_DAMP, I_FSLIP, I_KEL, I_UY, K, isolator_params, rigid_slider
from .system import BALL_IN_BOWL, BILINEAR, DOUBLE_PENDULUM, FRICTION_PENDULUM, LINEAR

#: the isolator kinds a contact engine can build from its own parts (a joint spring, a
#: dashpot, a dry-friction joint, a fixed tendon or a held force). Not the ball in a cone: its
#: restoring force M·g·tanφ·sgn(u) is none of these (docs/isolators.md, "Who carries what")
CONTACT_ISOLATORS = (LINEAR, BILINEAR, FRICTION_PENDULUM, BALL_IN_BOWL, DOUBLE_PENDULUM)
#: the isolators a contact engine builds in both horizontal directions (two components): the
#: linear one (the same k and c along x and y) and the pendulums whose only friction is the
#: base's own (the friction pendulum, the ball in a bowl), its limit μ·W the same in every
#: direction as a contact of a puck held down by W (MuJoCo's, PyBullet's and Drake's scenes; Drake
#: builds the puck on one component too, having no joint dry friction; DART, whose contact friction
#: is a pyramid, bounds its joint's Coulomb friction along the base's velocity or load instead,
#: dart_models._Pendulum); not a
#: Jenkins element's yielding (the bearing, a double pendulum)
PLANE_ISOLATORS = (LINEAR, FRICTION_PENDULUM, BALL_IN_BOWL)
#: that puck: its mass as a share of the base's (taken from the base, which still moves m_b)
#: and its half size (m)
PUCK_MASS_SHARE = 1e-3
PUCK_HALF = 0.02


@dataclass(frozen=True)
class PendulumPuck:
    """A pendulum's dry friction under two horizontal components, the same in every direction
    (MuJoCo's mujoco_models/scene._pair_pendulum, PyBullet's bullet_models/scene._pendulum_puck,
    Drake's drake_models/scene._pendulum_puck, on one component too):
    a light puck under the base, on its own vertical joint, held down by `hold` (N, on that
    joint, negative: down) so that a floor pushes it up by `load` W = M·g, its own weight
    included; the contact's friction coefficient `friction` = F_b/W, so that its limit is the
    model's F_b = μ·W whichever way the base slides. Its `mass` (kg) is taken from the base's."""

    mass: float
    load: float
    friction: float
    hold: float


def pendulum_puck(system) -> PendulumPuck | None:
    """The puck of `system`'s pendulum under a pair; None where the base has no dry friction of
    its own to build (a linear isolator, a pendulum without friction, a fixed base)."""
    if system.fixed_base or system.isolator_kind not in PLANE_ISOLATORS or system.isolator_kind == LINEAR:
        return None
    parts = isolator_parts(system)
    if parts.base_friction <= 0.0:
        return None
    load = (system.mass + system.base_mass) * system.gravity
    mass = PUCK_MASS_SHARE * system.base_mass
    return PendulumPuck(mass=mass, load=load, friction=parts.base_friction / load,
                        hold=-(load - mass * system.gravity))


@dataclass(frozen=True)
class IsolatorParts:
    """kind: System.isolator_kind; stiffness k and damping c: the spring and dashpot in
    parallel with the rest (N/m, N·s/m); base_friction F_b (N): the base's own dry friction,
    a rigid slider that holds the base still within it (0 without one); element_stiffness k_e
    (N/m) and slip_force F_s (N): the Jenkins element's spring and slider (both 0 without
    one)."""

    kind: str
    stiffness: float
    damping: float
    base_friction: float
    element_stiffness: float
    slip_force: float

    @property
    def has_element(self) -> bool:
        """Whether there is a Jenkins element (the bearing, a double pendulum of μ1 ≠ μ2)."""
        return self.element_stiffness > 0.0

    @property
    def yield_displacement(self) -> float:
        """u_y = F_s/k_e (m): the element's stretch at which its slider slips (0 without one)."""
        return self.slip_force / self.element_stiffness if self.has_element else 0.0

    @property
    def initial_stiffness(self) -> float:
        """k + k_e (N/m): the stiffness while the element is elastic and the base slides (the
        bearing's k0, the double pendulum's regime I W/R_lo): what an explicit step must follow."""
        return self.stiffness + self.element_stiffness


def isolator_parts(system) -> IsolatorParts:
    """The parts of `system`'s isolator (an isolated base: a fixed base has none)."""
    kind = system.isolator_kind
    if kind not in CONTACT_ISOLATORS:
        raise InputError(f"isolator = {kind}: no contact-engine parts (docs/isolators.md, 'Who carries what')")
    sp, ip = isolator_params(system, 0.0)
    rigid = kind != LINEAR and bool(rigid_slider(ip))
    # the element's slip force k_e·u_y: for the bearing the same product as ip[I_FSLIP] (bit for
    # bit); for the double pendulum ip[I_FSLIP] is the base's μ_lo·W and the element's is k_e·u_y
    k_e = float(ip[I_KEL])
    return IsolatorParts(kind=kind, stiffness=float(sp[K]), damping=float(sp[C_DAMP]),
                         base_friction=float(ip[I_FSLIP]) if rigid else 0.0, element_stiffness=k_e,
                         slip_force=float(ip[I_KEL] * ip[I_UY]) if k_e > 0.0 else 0.0)


def check_contact_isolator(system, engine: str) -> None:
    """One line refusing what a contact engine cannot build honestly from its parts: a
    friction pendulum with velocity-dependent friction μ_f(v). The engines' dry friction is a
    constant slip force (MuJoCo's joint frictionloss, Bullet's motor force limit), set
    before the step; a force that follows |u̇| within the step would need a new
    constraint, and one lagging a step behind would creep where the model sticks."""
    iso = getattr(system, "isolator", None)
    if iso is not None and iso.kind == FRICTION_PENDULUM and iso.friction_rate > 0.0:
        raise InputError(f"friction_rate = {iso.friction_rate!r}: engine {engine!r} carries a friction pendulum "
                         "with constant (Coulomb) friction only, friction_rate 0 (μ_f(v) runs on 'analytic' "
                         "and 'analytic-reference'; docs/isolators.md)")


__all__ = ["CONTACT_ISOLATORS", "PLANE_ISOLATORS", "PUCK_MASS_SHARE", "PUCK_HALF", "PendulumPuck", "pendulum_puck", "IsolatorParts", "isolator_parts", "check_contact_isolator"]
