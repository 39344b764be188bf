"""PyBullet's numerical settings for the rocking scene. Every default was chosen by
measurement (docs/bullet.md).

`timestep` is Bullet's own (physics) step, as for every engine; the ground motion, the
isolator force and the output are updated every `substeps` physics steps (the control
step, timestep × substeps), because a Python step costs more than Bullet's sub-steps in C.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..analytic.engine_protocol import contact_scale
from ..analytic.errors import require, require_nonnegative_finite, require_positive_finite
from ..analytic.isolator_parts import isolator_parts
from ..analytic.system import LINEAR

#: s; the control step (ground motion, isolator force, output) a timestep given alone keeps:
#: the physics step is what sets the accuracy, and sub-steps in C are cheaper than Python steps.
CONTROL_STEP = 4e-3
#: The longest control step: the isolator force and the ground motion are held over it.
MAX_CONTROL_STEP = 0.01
#: The isolator force is applied explicitly, once per control step: with ω·dt above this
#: (ω = 2π/T) it lags the spring enough to pump energy into the base, and at ω·dt ≈ 2 it
#: diverges (T 0.01 s at 4 ms overturned a block the analytic model rocks). 0.2 keeps
#: the held force within a few per cent of the spring's (T ≥ 0.126 s at 4 ms).
MAX_ISOLATOR_PHASE = 0.2


#: s; the default physics step, right on the paper's block (docs/bullet.md).
DEFAULT_TIMESTEP = CONTROL_STEP / 12
#: The physics step in units of the block's rocking time 1/p_eff (System.rocking_rate):
#: follow_system makes timestep·p_eff = STEP_SHARE. Measured over the atlas's λ 1.5–10 ×
#: μ 0–4 × H 0.1–10 m (docs/bullet.md, "Settings that follow the block's size"): the former
#: 1/3000 s is 0.00108 on the paper's isolated block (p_eff 3.23) and left small, squat
#: blocks 1.2% off; 0.0003 gives 0.093 ms there.
STEP_SHARE = 0.0003
#: A statue's own shape (System.body.solid, statue.py) steps this much finer than the block:
#: the bust (I_c small against m·R²) on the friction pendulum at 1× erred 1.82% in β at STEP_SHARE,
#: 0.15% at a third of it (docs/statues.md, "PyBullet on the statue's hull"); the block's
#: default, measured over the atlas's blocks, is left as it was.
STATUE_STEP_FACTOR = 1.0 / 3.0


@dataclass(frozen=True)
class Settings:
    """Numerical settings of the PyBullet scene.

    timestep: Bullet's physics step (s). substeps: physics steps per control step, at
        which the ground motion, the isolator force and the output are updated (the
        control step is timestep × substeps, at most MAX_CONTROL_STEP).
    solver_iterations: constraint solver iterations. friction: block–plate lateral
        friction coefficient. restitution: block–plate restitution. contact_erp: error
        reduction of contacts (Bullet's contactERP; 0.8 makes the block bounce).
        contact_processing_threshold: contact points farther apart than this (m) are left
        out of the solver (Bullet's default keeps them up to 2 cm: the lifted corner of a
        block rocking by less than ~0.1α then acts as a speculative contact and small
        impacts are off by up to 1.7%). linear_damping, angular_damping: Bullet's velocity
        damping of every body (1/s); model.md's physics has none. output_every: store
        every n-th control step. phased: while the block rests on its base and the base's
        acceleration stays below the uplift threshold, Bullet is not stepped (rest.py). follow_system: True: `for_system` divides the physics
        step by contact_scale(system, 1/3000 s, STEP_SHARE), the sub-steps kept, so the
        control step follows (on a block rocking faster than the paper's, the isolator
        force and ground motion held over 4 ms would lag: docs/bullet.md). An
        explicit timestep or substeps given to `settings_for` (every command's path) sets
        it False, as does `for_system` once applied.
    """

    timestep: float = DEFAULT_TIMESTEP
    substeps: int = 12
    solver_iterations: int = 50
    friction: float = 1.0
    restitution: float = 0.0
    #: 0.04: half Bullet's 0.08, which kicks heavy squat blocks off the base after an impact
    #: (hops of 0.6–1.4 mm, β up to 8% off at H 5 m, λ 1.5; docs/bullet.md)
    contact_erp: float = 0.04
    contact_processing_threshold: float = 0.0
    linear_damping: float = 0.0
    angular_damping: float = 0.0
    output_every: int = 1
    follow_system: bool = True
    #: skip Bullet's steps while the block rests on its base (rest.py, docs/bullet.md)
    phased: bool = True

    def for_system(self, system, duration: float | None = None) -> "Settings":
        """These settings for `system`: with follow_system, the physics step scaled by
        contact_scale(system, 1/3000 s, STEP_SHARE), so that timestep·p_eff = STEP_SHARE at
        every size (a preset twice as fine stays twice as fine), the sub-steps kept; the
        result is final (follow_system False). `duration` is not needed: a run whose
        duration the control step does not divide ends with a shorter step."""
        if not self.follow_system:
            return self
        finer = STATUE_STEP_FACTOR if getattr(system.body, "solid", None) is not None else 1.0
        return replace(self, timestep=self.timestep * finer * contact_scale(system, DEFAULT_TIMESTEP, STEP_SHARE),
                       follow_system=False)

    def __post_init__(self):
        require_positive_finite("timestep", self.timestep)
        for name, low in (("substeps", 1), ("solver_iterations", 1), ("output_every", 1)):
            value = getattr(self, name)
            require(isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= low,
                    name, value, f"an integer ≥ {low}")
        require(self.control_step <= MAX_CONTROL_STEP * (1 + 1e-9), "timestep", self.timestep,
                f"a step whose control step timestep × substeps ({self.substeps}) is at most "
                f"{MAX_CONTROL_STEP:g} s (contacts need steps far shorter than the rocking time scale)")
        require_positive_finite("friction", self.friction)
        require(0 <= self.restitution <= 1, "restitution", self.restitution, "in [0, 1]")
        require(0 < self.contact_erp <= 1, "contact_erp", self.contact_erp, "in (0, 1]")
        for name in ("linear_damping", "angular_damping", "contact_processing_threshold"):
            require_nonnegative_finite(name, getattr(self, name))
        require(isinstance(self.follow_system, bool), "follow_system", self.follow_system, "true or false")
        require(isinstance(self.phased, bool), "phased", self.phased, "true or false")

    @property
    def control_step(self) -> float:
        """The step (s) at which ground motion, isolator force and output are updated."""
        return self.timestep * self.substeps

    def check_isolator(self, system) -> None:
        """An isolator too stiff for the explicit force of this control step, or a base
        too light for Bullet's contact solver to carry the block (MAX_MASS_RATIO), is bad
        input: it would blow up or give a wrong history, not an answer."""
        if system.fixed_base:
            return
        require(system.mu <= MAX_MASS_RATIO, "mass_ratio", f"{system.mu:.3g}",
                f"at most {MAX_MASS_RATIO:g} for PyBullet (m/m_b: a base lighter than 1/{MAX_MASS_RATIO:g} of the "
                "block loses the rocking in Bullet's contact solver; measured, docs/bullet.md)")
        shortest = 2 * math.pi * self.control_step / MAX_ISOLATOR_PHASE
        period = system.period
        if system.isolator_kind != LINEAR:
            # the explicit step follows the stiffest branch: k + k_e while the element is elastic
            # (the bearing's k0; the double pendulum's regime I, W/R_lo, stiffer than its W/(R1 + R2))
            period = 2 * math.pi * math.sqrt(system.total_mass / isolator_parts(system).initial_stiffness)
        require(period >= shortest, "period", round(period, 6),
                f"at least {shortest:.3g} s for PyBullet with a control step of {self.control_step:g} s "
                f"(ω·dt ≤ {MAX_ISOLATOR_PHASE:g}: the isolator force is applied explicitly once per control step); "
                "give fewer --substeps or a shorter --timestep")


#: The largest block-to-base mass ratio μ = m/m_b PyBullet carries (measured: the
#: paper's block under a 0.5 g, 1 Hz sine on T = 2 s, ξ = 0.1 overturns after the
#: analytic model's impacts up to μ = 1000; from 3000 it slides at its pivot, at 1e5 it
#: no longer rocks, and at 1e6 it reported "completed" with θmax/α = 2.4e-7 where the
#: closed form gives 4.67 — docs/bullet.md, "Light bases").
MAX_MASS_RATIO = 1000.0


def settings_for(**overrides) -> Settings:
    """Settings with `overrides`; a timestep given without substeps keeps the control
    step near CONTROL_STEP (settings_for_timestep)."""
    if {"timestep", "substeps"} & set(overrides):
        overrides.setdefault("follow_system", False)  # what a user sets, the run uses
    if "timestep" in overrides and "substeps" not in overrides:
        return settings_for_timestep(overrides.pop("timestep"), **overrides)
    return Settings(**overrides)


def settings_for_timestep(dt: float, **overrides) -> Settings:
    """Settings whose physics step is `dt` (s), for work-precision ladders: the control
    step (ground motion, isolator force, output) stays near CONTROL_STEP and Bullet's
    sub-steps fill it. dt = 1/3000 s gives the defaults."""
    dt = require_positive_finite("timestep", dt)
    n = max(1, round(CONTROL_STEP / dt))
    # a ladder's rung is the step it names (a preset built on it passes follow_system=True)
    return Settings(**{"timestep": dt, "substeps": n, "follow_system": False, **overrides})
