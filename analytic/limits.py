"""Bounds on the amount of work one run may ask for, in one place.

Every input that sets how much a run computes or stores (its duration, a pulse's
length, a record's samples, an engine's step, the isolator's period against the
duration, the Zeno floor) is checked here before any work starts, so a typo such as
`--duration 1e9` or `--timestep 1e-7` is a one-line InputError naming the bound
instead of a run that never ends or dies hours later for lack of memory.

The bounds are generous for the physics: the longest strong-motion records last a
few minutes, and the free vibration after them decays in seconds to minutes.
"""
from __future__ import annotations

import math
import os
import time

from .errors import InputError, real_number

#: longest simulated time (s): an hour, ten times the longest earthquake records
MAX_DURATION = 3600.0
#: most integration steps one run may take (MuJoCo ~5 µs a step: under two minutes;
#: an hour at MuJoCo's default 0.5 ms step is 7.2e6)
MAX_STEPS = 20_000_000
#: most samples one run may hold or write (a record, a resampled CSV history, the stored
#: output): 1e7 points of five histories is 400 MB
MAX_SAMPLES = 10_000_000
#: most samples of a ground-motion record: an hour at 250 Hz. The reference integrator
#: restarts at every sample (about 5 ms each), so 1e6 samples is already over an hour
MAX_RECORD_SAMPLES = 1_000_000
#: most isolator periods one run may span: an integrator resolves each period with tens
#: of steps, so a period of 1e-9 s (k ≈ 3e22 N/m) over 10 s would need ~1e12 steps
MAX_ISOLATOR_CYCLES = 100_000
#: smallest Zeno floor (× p·α): below it the impact sequence is resolved beneath the
#: reference integrator's tolerance (rtol 1e-10 on θ ~ α) and never reaches the floor
MIN_REST_VELOCITY = 1e-9
#: largest peak ground acceleration a run may be given (g): twenty times the strongest ever
#: recorded (4.4 g, Iwate–Miyagi 2008). Far past it the compiled kernel's steps shrink to
#: nothing: one sample of 1e25 g ran 200,000 events, one of 1e40 g or 1e300 g on an isolated
#: base spun for ever, out of reach of any budget (issue 34). Up to 1e10 g every isolator
#: ends cleanly (tests/test_round_three.py), so the bound is physics, with a wide margin.
MAX_PGA_G = 100.0
#: most worker processes a command may start: each is a Python with NumPy and the engines
#: (~150 MB); past a few per core they only wait on each other (sweep --workers 1000000000
#: took 2.2 GB in 45 s before it was killed, issue 34)
MAX_WORKERS = 64
#: isolation periods a linear isolator may have (s): below a microsecond its stiffness
#: M·(2π/T)² leaves a float (an OverflowError at 1e-300 s); above a million seconds (11 days)
#: it is no spring at all, and its stiffness rounded to 0
ISOLATOR_PERIOD_RANGE = (1e-6, 1e6)


#: wall-clock seconds one run may take, in every command: a run past it fails with that
#: reason (its row or history says so) instead of holding a report or a campaign for
#: hours (validate with Drake had not finished after 46 minutes, issue 24). The longest
#: run of the README's examples takes ~40 s (Drake, 20 s of Kobe at 0.27 simulated s per
#: wall s, docs/drake.md).
RUN_BUDGET_S = 300.0


#: relative energy residual (the largest |E(t) − E(0) − ground work + losses| over the largest
#: energy that entered or was held, EnergyLog.relative_residual) above which a run on a
#: non-linear isolator fails, on both analytic paths: its history took a branch the physics did
#: not (issue 39: a cone's ball rolling on beyond its vertex with a returning ball's force ran
#: away by 3.5 km), and neither it nor its verdict may be counted. Sound runs close their balance
#: to DOP853's tolerance (rtol 1e-10): ≤ 3.9e-10 over the 2,397 rocking runs of
#: docs/scripts/isolator_energy_grid.py --cases 1000, 1e-13 on the issue's 95 s record; the wrong
#: branches seen left 2e-5 to 1.7 of it. 1e-6 lies between, with room for long records (the linear
#: model's own limit in the tolerance table, ("analytic", "energy_residual"), is 1e-6 for that).
#: Read on the reference's stored points, at the kernel's step ends.
ENERGY_BALANCE_LIMIT = 1e-6


def energy_balance_failure(times, residuals, scale: float) -> str | None:
    """The message of a run whose energy balance failed (ENERGY_BALANCE_LIMIT), or None:
    residuals (J) of the balance at times (s), in order, their largest among them (the
    compiled kernel passes where its residual first doubled, and its largest); scale (J), the
    largest energy involved. It says when the residual first exceeded the limit, and its
    largest, where."""
    r = [abs(x) for x in residuals]
    limit = ENERGY_BALANCE_LIMIT * scale
    if not (scale > 0.0 and r and max(r) > limit):
        return None
    first = next(k for k, x in enumerate(r) if x > limit)
    top = r.index(max(r))
    return (f"the energy balance failed at t = {float(times[first]):.6g} s: it is off by {r[top]:.3g} J of the "
            f"{scale:.3g} J involved ({r[top] / scale:.2g}, limit {ENERGY_BALANCE_LIMIT:g}: "
            f"ENERGY_BALANCE_LIMIT) at t = {float(times[top]):.6g} s; the history took a branch the physics "
            "did not and is not an answer")


class BudgetExceeded(RuntimeError):
    """A run took longer than its wall-clock budget (RUN_BUDGET_S)."""


def check_budget(seconds, field: str = "budget_s") -> float:
    """A run's wall-clock budget: a positive finite number of seconds (a negative, NaN or text
    budget was taken as given from Python, and stopped nothing or everything)."""
    x = real_number(field, seconds, "a positive finite number of seconds")
    if not (x > 0 and math.isfinite(x)):
        raise InputError(f"{field} = {seconds!r}: must be a positive finite number of seconds")
    return x


class RunBudget:
    """An engine's progress callback (t, duration) that stops the run once it has taken
    `seconds` of wall time since it was made (then `chained`, the caller's own callback).
    Engines call progress about once a second (kinematics.Throttle), so a run stops within
    about a second of its budget."""

    def __init__(self, seconds: float, chained=None):
        self.seconds, self.chained, self.start = check_budget(seconds), chained, time.monotonic()

    def __call__(self, t: float, duration: float) -> None:
        if self.chained is not None:
            self.chained(t, duration)
        if time.monotonic() - self.start > self.seconds:
            raise BudgetExceeded(f"stopped at its budget of {self.seconds:g} s wall time (RUN_BUDGET_S) at "
                                 f"t = {t:.3g} s of {duration:.3g} s simulated")


def _fmt(x: float) -> str:
    return f"{x:.3g}"


def check_duration(field: str, duration: float, what: str = "") -> float:
    """`duration` (s) must be at most MAX_DURATION."""
    if duration > MAX_DURATION:
        raise InputError(f"{field} = {_fmt(duration)} s{what}: must be at most {MAX_DURATION:g} s "
                         f"(MAX_DURATION, an hour of simulated time)")
    return duration


def check_count(field: str, value, count: float, limit: int, noun: str, how: str) -> None:
    """`count` (the work `value` of `field` implies, described by `how`) within `limit`."""
    if not count <= limit:
        raise InputError(f"{field} = {value!r}: the run would take {_fmt(count)} {noun} ({how}); "
                         f"must be at most {limit:.0e}")


def check_record_samples(name: str, n: int) -> None:
    if n > MAX_RECORD_SAMPLES:
        raise InputError(f"{name}: {n} samples: a record must have at most {MAX_RECORD_SAMPLES:.0e} "
                         "(MAX_RECORD_SAMPLES); resample or trim it")


def check_acceleration(field: str, pga_g: float, what: str = "") -> None:
    """A peak ground acceleration (g) within ±MAX_PGA_G."""
    if not abs(pga_g) <= MAX_PGA_G:
        raise InputError(f"{field} = {_fmt(pga_g)} g{what}: must be at most {MAX_PGA_G:g} g (MAX_PGA_G, twenty "
                         "times the strongest ground motion ever recorded)")


def check_period(field: str, period: float) -> None:
    """A linear isolator's period (s) within ISOLATOR_PERIOD_RANGE: asked before its System
    is built (a stiffness past a float's range cannot be)."""
    lo, hi = ISOLATOR_PERIOD_RANGE
    if not lo <= period <= hi:
        raise InputError(f"{field} = {period!r} s: must be from {lo:g} to {hi:g} s (ISOLATOR_PERIOD_RANGE: a "
                         "stiffness a float holds, and a spring at all)")


def check_workers(field: str, workers, *, serial: bool = False) -> int:
    """A number of worker processes: a whole number from 1 (from 0 where `serial`, this
    process alone) to MAX_WORKERS."""
    low = 0 if serial else 1
    if isinstance(workers, bool) or not isinstance(workers, int) or not low <= workers <= MAX_WORKERS:
        raise InputError(f"{field} = {workers!r}: must be a whole number of processes from {low} to {MAX_WORKERS} "
                         f"(MAX_WORKERS){' (0: serially, in this process)' if serial else ''}")
    return workers


def check_isolator(system, duration: float) -> None:
    """The isolator's period against the run's length: at most MAX_ISOLATOR_CYCLES periods."""
    if getattr(system, "fixed_base", True):
        return
    period = system.period
    cycles = duration / period if period > 0 else math.inf
    if not cycles <= MAX_ISOLATOR_CYCLES:
        raise InputError(f"period = {_fmt(period)} s (stiffness {_fmt(system.stiffness)} N/m): a run of "
                         f"{_fmt(duration)} s spans {_fmt(cycles)} isolator periods; must be at most "
                         f"{MAX_ISOLATOR_CYCLES:.0e} (MAX_ISOLATOR_CYCLES): a period of at least "
                         f"{_fmt(duration / MAX_ISOLATOR_CYCLES)} s, or a shorter duration")


def check_settings(settings, duration: float) -> None:
    """An engine's numerical settings against the run's duration: the steps they imply
    (the physics timestep of the contact engines, max_step and output_dt of the
    analytic model) and the Zeno floor. Any engine's Settings: fields it lacks are skipped."""
    if settings is None:
        return
    get = lambda name: getattr(settings, name, None)  # noqa: E731
    timestep = get("timestep")  # the physics step of every engine (PyBullet's sub-steps fill its control step)
    if timestep is not None and timestep > 0:
        check_count("timestep", timestep, duration / timestep, MAX_STEPS, "steps",
                    f"duration {_fmt(duration)} s / timestep, MAX_STEPS")
    max_step = get("max_step")
    if max_step is not None and max_step > 0:
        check_count("max-step", max_step, duration / max_step, MAX_STEPS, "steps at least",
                    f"duration {_fmt(duration)} s / max-step, MAX_STEPS")
    output_dt = get("output_dt")
    if output_dt is not None and output_dt > 0:
        check_count("output-dt", output_dt, duration / output_dt, MAX_SAMPLES, "stored points",
                    f"duration {_fmt(duration)} s / output-dt, MAX_SAMPLES")
    rest = get("rest_velocity")
    if rest is not None and rest < MIN_REST_VELOCITY:
        raise InputError(f"rest-velocity = {rest!r}: must be at least {MIN_REST_VELOCITY:g} (× p·α, "
                         "MIN_REST_VELOCITY): slower impacts are below what the integrator resolves")


def check_resample(field: str, dt: float, duration: float) -> None:
    """A history resampled at `dt` over `duration` holds at most MAX_SAMPLES rows."""
    check_count(field, dt, duration / dt, MAX_SAMPLES, "rows", f"duration {_fmt(duration)} s / {field}, MAX_SAMPLES")


def available_cores() -> int:
    """The cores this process may run on (its affinity: a container's or taskset's share,
    not every core of the machine): the default number of threads or worker processes."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
