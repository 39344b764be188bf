"""The isolator as the parts a contact engine builds it from (docs/isolators.md, "The
equations"): a parallel spring k and dashpot c on the base, and a Jenkins element — a spring
k_e in series with a Coulomb slider of slip force F_s (k_e infinite for the friction
pendulum: the base itself sticks). Derived once, from the same `physics.isolator_params` the
analytic model integrates, so MuJoCo's scene and PyBullet's force law cannot read the
isolator differently from the model they are judged against.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import InputError
from .system import BILINEAR, FRICTION_PENDULUM, LINEAR

#: the isolator kinds a contact engine can build from its own parts (a joint spring, a
#: dashpot, a dry-friction joint, a fixed tendon or a held force): every kind the model has
CONTACT_ISOLATORS = (LINEAR, BILINEAR, FRICTION_PENDULUM)


@dataclass(frozen=True)
class IsolatorParts:
    """kind: System.isolator_kind; stiffness k and damping c: the spring and dashpot in
    parallel with the element (N/m, N·s/m); element_stiffness k_e (N/m; inf for the
    pendulum's rigid slider, 0 without an element); slip_force F_s (N; 0 without one)."""

    kind: str
    stiffness: float
    damping: float
    element_stiffness: float
    slip_force: float

    @property
    def has_element(self) -> bool:
        return self.kind != LINEAR

    @property
    def yield_displacement(self) -> float:
        """u_y = F_s/k_e (m): the element's stretch at which its slider slips (0 for a rigid one)."""
        return self.slip_force / self.element_stiffness if 0 < self.element_stiffness < math.inf else 0.0


def isolator_parts(system) -> IsolatorParts:
    """The parts of `system`'s isolator (an isolated base: a fixed base has none)."""
    from .physics import C_DAMP, I_FSLIP, I_KEL, K, isolator_params
    sp, ip = isolator_params(system, 0.0)
    kind = system.isolator_kind
    k_e = math.inf if kind == FRICTION_PENDULUM else float(ip[I_KEL])
    return IsolatorParts(kind=kind, stiffness=float(sp[K]), damping=float(sp[C_DAMP]), element_stiffness=k_e,
                         slip_force=float(ip[I_FSLIP]))


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


__all__ = ["CONTACT_ISOLATORS", "IsolatorParts", "isolator_parts", "check_contact_isolator"]
