"""MuJoCo's numerical settings for the rocking scene, and the ones that follow a timestep.

Every default was chosen by measurement; the tables and commands are in docs/mujoco.md.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..analytic.engine_protocol import contact_scale
from ..analytic.errors import InputError, require, require_positive_finite
from ..analytic.system import paper_system

INTEGRATORS = ("Euler", "implicit", "implicitfast", "RK4")
CONES = ("pyramidal", "elliptic")
#: MuJoCo's constraint solvers; Newton (MuJoCo's own default) converges in 1–3 iterations
#: here, CG changes histories by ~3e-4 and PGS by 0.5 (docs/mujoco.md, "Speed").
SOLVERS = ("Newton", "CG", "PGS")
JOINTS = ("planar", "free")
CONTACTS = ("box", "corners")


#: Away from impacts (the block resting on the compliant contact, or pivoting on one corner
#: in flight) a phased run steps COARSE_STEPS × the timestep (phases.Flight): nothing there
#: is faster than the contact time constant τ = 6 steps, and τ/2 is MuJoCo's floor for a
#: step (a longer one and MuJoCo raises solref's timeconst to 2·step: a softer contact).
#: Impacts, where θ̇ jumps within a few τ, keep the timestep itself. Measured on the
#: paper's block (docs/mujoco.md, "Coarse steps away from impacts"): Kobe 40 s isolated
#: θmax/α −0.0088 against phased fine stepping (limit 0.02), the report's sine −0.002.
COARSE_STEPS = 3


@dataclass(frozen=True)
class Settings:
    """MuJoCo's numerical settings for this scene.

    timestep: s. integrator: one of Euler, implicit, implicitfast, RK4. cone:
    pyramidal or elliptic friction cone. solref: contact (timeconst s, dampratio),
    both positive, with timeconst ≥ 2·timestep (MuJoCo would silently raise it), or
    MuJoCo's direct form (−stiffness, −damping). solimp: (dmin, dmax, width[, mid,
    power]). friction: block–base sliding friction coefficient. noslip: noslip
    solver iterations (0: off). impact_timestep: None (one timestep throughout), or a
    divisor of `timestep` (s) used from just before each impact until shortly after
    it ("event-resolved" stepping, docs/mujoco.md; needs the direct solref form:
    the fine model keeps the stiffness and scales the damping by timestep /
    impact_timestep). joint: "planar" (slide x, slide z, hinge y) or
    "free". contact: "box" (box–box, the default) or "corners" (a small sphere in
    each bottom corner of the block against the base box, scene.CORNER_RADIUS:
    cheaper collision, no better per unit of cost, docs/mujoco.md). solver: the
    constraint solver, one of Newton (the default), CG, PGS (MJCF `<option solver>`).
    follow_system: True: `for_system` puts the step, the contact time constant and the
    impedance width in the block's own units (contact_scale; an explicit
    timestep, solref or solimp given to `settings_for`, the path every command takes,
    sets it False, as does `for_system` once applied; `Settings(...)` built directly in
    Python keeps True unless told: pass follow_system=False to step exactly as written).
    """

    timestep: float = 5e-4
    integrator: str = "implicitfast"
    cone: str = "elliptic"
    solref: tuple = (0.002, 2.0)
    solimp: tuple = (0.9, 0.999, 0.001)
    #: The rigid model assumes the block cannot slide (model.md), so the contact's friction
    #: must not limit it: MuJoCo's soft elliptic cone lets a loaded pivot creep as its
    #: friction demand nears the cone, and the squattest block on the lightest base (λ 1.5,
    #: μ 4) demands the most: friction 2 halves that creep (2.8e-4·b → 1.6e-4·b) and moves
    #: its β error from 0.51% to 0.34%; the other 95 cells of the atlas are unchanged to
    #: the printed digit (docs/mujoco.md, "Friction").
    friction: float = 2.0
    noslip: int = 0
    joint: str = "planar"
    contact: str = "box"
    impact_timestep: float | None = None
    solver: str = "Newton"
    #: step the contact scene only where contact can happen (phases.py, docs/mujoco.md)
    phased: bool = True
    #: away from impacts a phased run steps this many timesteps at once (phases.Flight;
    #: at most solref's timeconst / 2 steps; 1: every step the timestep)
    coarse: int = COARSE_STEPS
    follow_system: bool = True

    def for_system(self, system, duration: float | None = None) -> "Settings":
        """These settings for `system`: with follow_system, every contact length and time
        in the block's own units (docs/mujoco.md, "Every size"): the (timeconst, dampratio)
        time constant scaled by contact_scale(system, 2 ms, CONTACT_SHARE) and the step by
        contact_scale(system, 0.5 ms, STEP_SHARE), so that τ·p_eff = CONTACT_SHARE and
        dt·p_eff = STEP_SHARE at every size (a preset twice as fine as the default stays
        twice as fine), and the impedance width (solimp's third value, m) scaled with R,
        since a contact that acts
        over a time ∝ 1/p sinks by a depth ∝ R. The direct solref form and event-resolved
        stepping keep their step and time constant. With `duration` (s), the derived step is
        shortened (by less than a step in the run) to a whole divisor of it, so that the
        run ends on its duration, as a step given in seconds that divides it does. The
        result has follow_system False: it is final, and applying it again changes nothing."""
        if getattr(system.body, "solid", None) is not None and (self.joint, self.contact) != ("free", "box"):
            # a statue's own shape is its hull on the free joint (scene._statue): it rocks in 3-D
            return replace(self, joint="free", contact="box").for_system(system, duration)
        if not self.follow_system:
            return self
        width = self.solimp[2] * system.R / REFERENCE_R
        out = replace(self, solimp=(*self.solimp[:2], width, *self.solimp[3:]), follow_system=False)
        if self.solref[0] < 0 or self.impact_timestep is not None:
            return out
        k = contact_scale(system, Settings.solref[0], CONTACT_SHARE)
        step = self.timestep * contact_scale(system, Settings.timestep, STEP_SHARE)
        if duration is not None and duration > 0:
            step = duration / math.ceil(duration / step - 1e-9)
        return replace(out, timestep=step, solref=(self.solref[0] * k, self.solref[1]))

    def __post_init__(self):
        dt = require_positive_finite("timestep", self.timestep)
        require(dt <= 0.01, "timestep", self.timestep, "at most 0.01 s (rocking needs far finer steps)")
        require(self.integrator in INTEGRATORS, "integrator", self.integrator, f"one of {', '.join(INTEGRATORS)}")
        require(self.cone in CONES, "cone", self.cone, f"one of {', '.join(CONES)}")
        require(self.joint in JOINTS, "joint", self.joint, f"one of {', '.join(JOINTS)}")
        require(self.contact in CONTACTS, "contact", self.contact, f"one of {', '.join(CONTACTS)}")
        require(self.solver in SOLVERS, "solver", self.solver, f"one of {', '.join(SOLVERS)}")
        if self.impact_timestep is not None:
            fine = require_positive_finite("impact_timestep", self.impact_timestep)
            ratio = dt / fine
            require(fine < dt and abs(ratio - round(ratio)) < 1e-6, "impact_timestep", self.impact_timestep,
                    f"the timestep {dt:g} s divided by a whole number of at least 2")
            require(all(x < 0 for x in _float_tuple("solref", self.solref, 2, 2)), "solref", self.solref,
                    "the direct form (−stiffness, −damping) with impact_timestep (both models share the stiffness)")
            object.__setattr__(self, "impact_timestep", fine)
        solref = _float_tuple("solref", self.solref, 2, 2)
        positive = all(x > 0 for x in solref)
        require(positive or all(x < 0 for x in solref), "solref", self.solref,
                "(timeconst, dampratio) both positive, or (−stiffness, −damping) both negative")
        require(not positive or solref[0] >= 2 * dt * (1 - 1e-9), "solref", self.solref,
                f"a timeconst of at least 2·timestep = {2 * dt:g} s (MuJoCo raises a shorter one to that)")
        solimp = _float_tuple("solimp", self.solimp, 3, 5)
        require(0 < solimp[0] < 1 and 0 < solimp[1] < 1, "solimp", self.solimp,
                "(dmin, dmax, width[, mid, power]) with dmin and dmax in (0, 1)")
        require(solimp[2] > 0, "solimp", self.solimp, "a positive width (third value)")
        if len(solimp) > 3:
            require(0 < solimp[3] < 1, "solimp", self.solimp, "a midpoint (fourth value) in (0, 1)")
        if len(solimp) > 4:
            require(solimp[4] >= 1, "solimp", self.solimp, "a power (fifth value) of at least 1")
        object.__setattr__(self, "timestep", dt)
        object.__setattr__(self, "solref", solref)
        object.__setattr__(self, "solimp", solimp)
        object.__setattr__(self, "friction", require_positive_finite("friction", self.friction))
        require(isinstance(self.noslip, (int, np.integer)) and not isinstance(self.noslip, bool)
                and self.noslip >= 0, "noslip", self.noslip, "a non-negative whole number of iterations")
        object.__setattr__(self, "noslip", int(self.noslip))
        require(isinstance(self.phased, bool), "phased", self.phased, "true or false")
        require(isinstance(self.coarse, (int, np.integer)) and not isinstance(self.coarse, bool) and self.coarse >= 1,
                "coarse", self.coarse, "a whole number of timesteps, at least 1")
        object.__setattr__(self, "coarse", int(self.coarse))


#: The contact time constant in units of the block's rocking time: follow_system makes
#: τ·p_eff = CONTACT_SHARE (p_eff = System.rocking_rate). Measured over the atlas's
#: λ 1.5–10 × μ 0–4 × H 0.1–10 m (docs/mujoco.md, "Every size"): the
#: squat λ 1.5 block on a light base needs 0.002 (0.003 left it 0.9% off at 10 m). On the
#: paper's block it gives τ 0.62 ms isolated, 0.76 ms fixed (the former default: 2 ms).
CONTACT_SHARE = 0.002
#: The step in the same units: τ/6. At τ/4 (the ratio measured best on the paper's block at
#: 0.5 ms) the squat light-base block's β moved by −0.06…+0.68% with the phase of its impact
#: within a step (the step changed by 0.01–10%); at τ/6 by −0.04…+0.40% (docs/mujoco.md).
STEP_SHARE = CONTACT_SHARE / 6
#: m; the centroid-to-corner distance of the paper's block, at which the default impedance
#: width (solimp, 1 mm) was measured: follow_system scales the width by R / REFERENCE_R.
REFERENCE_R = paper_system().R



#: The default contact time constant in steps: solref = (SOLREF_STEPS · timestep, 2).
SOLREF_STEPS = 4

#: From this timestep up, `settings_for_timestep` uses MuJoCo's direct contact
#: parameters: solref = (−DIRECT_STIFFNESS / dt², −DIRECT_DAMPING / dt) (stiffness and
#: damping of the reference acceleration, mass-normalised) with solimp DIRECT_SOLIMP.
#: A time constant of 4 steps makes the impact last 16 ms or more at dt ≥ 2e-3, about
#: half the measuring window, and β errors reach 8%; the direct form is not bound to
#: timeconst ≥ 2·dt and measured rms 0.88% against 2.3% at 2e-3, 0.54% against 0.57%
#: at 1e-3, and worse than the default at 5e-4 (docs/mujoco.md).
DIRECT_FROM = 1e-3
DIRECT_STIFFNESS = 0.05
DIRECT_DAMPING = 0.6
DIRECT_SOLIMP = (0.9, 0.9, 0.001)


def settings_for(**overrides) -> Settings:
    """Settings with `overrides`; a timestep given without solref and solimp takes the
    contact parameters measured for it (settings_for_timestep), since the default
    contact time constant is only right for the default step."""
    if {"timestep", "solref", "solimp"} & set(overrides):
        overrides.setdefault("follow_system", False)  # what a user sets, the run uses
    if "timestep" in overrides and not {"solref", "solimp"} & set(overrides):
        return settings_for_timestep(overrides.pop("timestep"), **overrides)
    return Settings(**overrides)


def settings_for_timestep(timestep: float, **overrides) -> Settings:
    """The contact parameters measured best at this timestep (what `isorock bench`
    ladders): below DIRECT_FROM the defaults with the contact time constant kept at
    SOLREF_STEPS steps (the default is this at 5e-4 s); from DIRECT_FROM up the
    direct form, stiffness DIRECT_STIFFNESS/dt² and damping DIRECT_DAMPING/dt."""
    dt = require_positive_finite("timestep", timestep)
    if dt >= DIRECT_FROM * (1 - 1e-9):
        base = dict(timestep=dt, solref=(-DIRECT_STIFFNESS / dt**2, -DIRECT_DAMPING / dt), solimp=DIRECT_SOLIMP)
    else:
        base = dict(timestep=dt, solref=(SOLREF_STEPS * dt, Settings.solref[1]))
    # a ladder's rung is the step it names (a preset built on it passes follow_system=True)
    return Settings(**{**base, "follow_system": False, **overrides})


#: Event-resolved stepping as measured (docs/mujoco.md): coarse contact stiffness
#: EVENT_STIFFNESS/dt² (static pivot sink ≈ 0.02 mm at dt 3e-3), damping 0.6/dt.
EVENT_STIFFNESS = 0.5


def event_resolved_settings(timestep: float = 3e-3, impact_timestep: float = 2.5e-4, **overrides) -> Settings:
    """Coarse steps of `timestep` with fine steps of `impact_timestep` around impacts
    (Settings.impact_timestep), direct contact parameters tied to the coarse step.
    Measured at the defaults of this function: β within 0.47% of the closed form at
    θ0 = α/2 (1.3% worst over θ0 = 0.3–0.7α), Kobe 40 s 4× faster than the defaults but
    θmax/α 0.035 low (the defaults: 0.007)."""
    dt = require_positive_finite("timestep", timestep)
    base = dict(timestep=dt, impact_timestep=impact_timestep, solref=(-EVENT_STIFFNESS / dt**2, -DIRECT_DAMPING / dt),
                solimp=DIRECT_SOLIMP)
    return Settings(**{**base, **overrides})


def _float_tuple(name, value, n_min, n_max) -> tuple:
    try:
        out = tuple(float(x) for x in value)
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r}: must be {n_min}–{n_max} numbers") from None
    require(n_min <= len(out) <= n_max and all(math.isfinite(x) for x in out), name, value,
            f"{n_min} finite numbers" if n_min == n_max else f"{n_min}–{n_max} finite numbers")
    return out

