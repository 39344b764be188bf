"""An isorock engine in a package of its own: the rocking block (and its linear isolator)
stepped by classical fixed-step Runge–Kutta (RK4), with an impact located inside the step
where θ changes sign and the rigid impact map applied there. It is what a researcher's own
simulator looks like to isorock (docs/plugins.md): one `ENGINE = EngineSpec(...)`, found
through the entry point `isorock.engines` of this package's pyproject.toml.

The equations of motion are isorock's (isorock.analytic.physics, model.md); the integrator,
its step, its event location and its preset are this package's own. It returns a RawHistory
(t, u, u̇, θ, θ̇ per row): isorock measures it like any contact engine's, and judges it by the
limits it declares below, each with its reason.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from isorock.analytic import physics
from isorock.analytic.engine_protocol import Capabilities, EngineSpec, Preset, run_inputs
from isorock.analytic.errors import InputError
from isorock.analytic.status import Status
from isorock.analytic.trajectory import RawHistory
from isorock.validate.core.tolerances import Tolerance


@dataclass(frozen=True)
class RK4Settings:
    """timestep: the fixed step, s."""

    timestep: float = 2e-4

    def __post_init__(self):
        if not (isinstance(self.timestep, (int, float)) and 1e-6 <= self.timestep <= 1e-2):
            raise InputError(f"timestep = {self.timestep!r}: must be a step from 1e-6 to 0.01 s")


def _step(f, y, t, h):
    k1 = f(t, y)
    k2 = f(t + h / 2, y + h / 2 * k1)
    k3 = f(t + h / 2, y + h / 2 * k2)
    k4 = f(t + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def simulate(system, motion=None, *, settings=None, duration=None, theta0=0.0, progress=None) -> RawHistory:
    settings = settings or RK4Settings()
    motion, duration = run_inputs(system, motion, duration, theta0, 0.01, settings=settings)
    # what it does not carry (Capabilities below) isorock refuses before calling it; said again here
    # for a caller that calls this function directly
    if system.friction is not None or motion.vertical is not None:
        raise InputError("system: engine 'rk4' carries a statue that cannot slip, on level ground")
    sp = physics.system_params(system, 1e-8)
    h, start = settings.timestep, time.perf_counter()

    def rocking(s):
        def f(t, y):
            udd, thdd, _ = physics.rocking_accelerations(sp, s, y[2], y[3], y[0], y[1], motion.at(t))
            return np.array([y[1], udd, y[3], thdd])
        return f

    def translation(t, y):
        return np.array([y[1], physics.translation_acceleration(sp, y[0], y[1], motion.at(t)), 0.0, 0.0])
    y = np.array([0.0, 0.0, float(theta0), 0.0])
    s = 0 if theta0 == 0 else (1 if theta0 > 0 else -1)
    n = int(math.ceil(duration / h))
    rows = np.empty((n + 1, 5))
    rows[0] = (0.0, *y)
    status, message, t = Status.COMPLETED, "reached the end time", 0.0
    for i in range(1, n + 1):
        t_next = min(i * h, duration)
        if s == 0:
            y = _step(translation, y, t, t_next - t)
            s = physics.relift(sp, y[0], y[1], motion.at(t_next))
        else:
            new = _step(rocking(s), y, t, t_next - t)
            if s * new[2] < 0:  # θ passed 0 inside the step: the impact, located on the step's cubic
                a = _crossing(y[2], y[3], new[2], new[3], t_next - t)
                y = _step(rocking(s), y, t, a)
                thd, ud = physics.impact_map(sp, y[3], y[1], physics.impact_continues(sp, y[3]))
                y = np.array([y[0], ud, 0.0, thd])
                s = -s if thd != 0 else 0
                f = rocking(s) if s else translation
                new = _step(f, y, t + a, t_next - t - a)
                if s == 0:
                    new[2] = new[3] = 0.0
            y = new
            if abs(y[2]) >= math.pi / 2:
                rows[i] = (t_next, *y)
                rows = rows[:i + 1]
                status, message = Status.OVERTURNED, f"overturned at t = {t_next:.4g} s"
                break
        t = t_next
        rows[i] = (t, *y)
        if progress is not None and i % 5000 == 0:
            progress(t, duration)
    return RawHistory(engine="rk4", system=system, t=rows[:, 0], u=rows[:, 1], u_dot=rows[:, 2], theta=rows[:, 3],
                      theta_dot=rows[:, 4], status=status, message=message, runtime_s=time.perf_counter() - start)


def _crossing(th0, thd0, th1, thd1, h) -> float:
    """Where θ's cubic Hermite interpolant over the step (values and slopes at both ends)
    crosses 0, by bisection: the impact time inside the step, to the step's own order."""
    def theta(x):
        u = x / h
        return ((2 * u**3 - 3 * u**2 + 1) * th0 + (u**3 - 2 * u**2 + u) * h * thd0
                + (-2 * u**3 + 3 * u**2) * th1 + (u**3 - u**2) * h * thd1)
    lo, hi = 0.0, h
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if theta(mid) * th0 > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


ENGINE = EngineSpec(
    name="rk4", label="RK4 (plugin)", settings_type=RK4Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, campaigns=False, isolators=("linear",),
                              statue_friction=False, vertical=False),
    presets={"coarse": Preset("a 2 ms step: ten times the default, to see the step's error in β and t₁",
                              lambda: RK4Settings(timestep=2e-3))},
    tolerances={
        "beta_rel_error": Tolerance(1e-3, "the closed-form impact map applied at the crossing located on the "
                                          "step's cubic: θ̇⁻ to the step's order, far below 0.1%"),
        "first_impact_time_rel_error": Tolerance(1e-3, "the crossing on the step's cubic, a 0.2 ms step"),
        "beta2_abs_error": Tolerance(1e-3, "the closed-form map: the base's jump to the step's order"),
        "theta_max_diff": Tolerance(0.02, "as the contact engines' (a history's peak, in units of α)"),
        "impacts_diff": Tolerance(1, "as the contact engines': one impact near the counting threshold"),
        "first_uplift_diff": Tolerance(0.005, "uplift read on a 0.2 ms step"),
        "overturn_agree": Tolerance(1, "the same outcome", "equal"),
        "u_max_rel_error": Tolerance(0.01, "the isolator's peak, to the step's order"),
        "ensemble_theta_max_diff": Tolerance(0.02, "as the contact engines': the median θmax/α over an ensemble"),
        "ensemble_overturn_median": Tolerance(0.10, "as the contact engines': the fragility's median scale"),
        "ensemble_overturn_dispersion": Tolerance(0.15, "as the contact engines': the fragility's dispersion"),
    })
