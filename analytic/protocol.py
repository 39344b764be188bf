"""What every engine's `simulate(system, motion, *, settings, duration, theta0,
impact_threshold, progress)` takes, checked in one place so all engines accept and
refuse the same inputs with the same messages."""
from __future__ import annotations

import math

from .errors import InputError, require, require_positive_finite
from .limits import check_duration, check_isolator, check_settings
from .motion import GroundMotion
from .system import System

#: seconds simulated after the motion ends, and without any motion (free rocking)
TAIL_AFTER_MOTION = 5.0
FREE_DURATION = 10.0


def run_inputs(system: System, motion: GroundMotion | None, duration: float | None, theta0: float,
               impact_threshold: float, *, theta_dot0: float = 0.0, u0: float = 0.0,
               u_dot0: float = 0.0, settings=None) -> tuple[GroundMotion, float]:
    """(motion, duration) after the shared checks: `none` motion is zero ground
    acceleration; the default duration is the motion's end + 5 s, or 10 s without motion;
    θ0 (rad) must be a finite tilt below α; the counting threshold in [0, 1). The work
    bounds of analytic.limits: the duration, the isolator periods it spans and, when the
    engine's `settings` are given, the steps they imply."""
    require(isinstance(system, System), "system", system, "a System")
    motion = motion or GroundMotion.zero()
    given = duration is not None
    if not given:
        duration = FREE_DURATION if motion.is_zero else motion.end_time + TAIL_AFTER_MOTION
    duration = require_positive_finite("duration", duration)
    check_duration("duration", duration, "" if given else f" (the motion's end + {TAIL_AFTER_MOTION:g} s)")
    check_isolator(system, duration)
    check_settings(settings, duration)
    require(math.isfinite(theta0) and abs(theta0) < system.alpha, "theta0", theta0,
            f"a finite tilt smaller than α = {system.alpha:.6g} rad in magnitude")
    for name, v in (("theta_dot0", theta_dot0), ("u0", u0), ("u_dot0", u_dot0)):
        require(math.isfinite(v), name, v, "a finite number")
    if system.fixed_base:
        require(u0 == 0 and u_dot0 == 0, "u0/u_dot0", (u0, u_dot0), "zero on a fixed base")
    require(0 <= impact_threshold < 1, "impact_threshold", impact_threshold, "in [0, 1)")
    # a stepping engine samples the ground motion once per (control) step: a pulse that
    # ends within two of them is lost, or reduced to one sample, without a word
    step = getattr(settings, "control_step", None) or getattr(settings, "timestep", None)
    if step and motion.pulse is not None and not motion.is_zero and motion.end_time < 2 * step:
        raise InputError(f"motion = {motion.name or 'pulse'}: lasts {motion.end_time:.3g} s, less than two of this "
                         f"engine's steps ({step:g} s): it would be lost; a longer pulse or a shorter --timestep")
    return motion, duration
