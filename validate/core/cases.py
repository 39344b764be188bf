"""Cases: one system under one motion for one duration (`Case`, the one case type: a table
row's inputs or a named run), the motion specs a named run holds (`synthetic_record`), and
the one place a System is built from the numbers people vary (`block_system`: height,
slenderness, mass ratio, isolator) or from a table's columns (`build_system`), and a
pulse from its dimensionless form (`pulse_for`). A case's inputs are the table's
columns, so they are the whole definition of a case."""
from __future__ import annotations

import functools
import hashlib
import math
import weakref
from dataclasses import dataclass, field, replace

import numpy as np

from ...analytic.errors import InputError
from ...analytic.limits import check_acceleration
from ...analytic.motion import GroundMotion, Pulse, load_motion
from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD, STANDARD_GRAVITY, System


@dataclass(frozen=True)
class Case:
    """The one case type: one system under one motion for one duration from one initial
    tilt (`theta0`, rad). A table's row (campaigns, ensembles: `case` its number, `inputs`
    the table's columns that define it, everything needed to rebuild it) or a named run
    (`named`: the report's, bench's, stress grid's, calibration's, golden files'; `name`).

    `motion` is a GroundMotion, one made only when a run needs it (a campaign's pulses
    and scaled records), or a spec: a pulse, a record path, "none", or a synthetic record
    "noise:dt=…,pga=…,seconds=…,seed=…", so that a named case is small, frozen and cheap
    to send to another process; `window` (s), if given, keeps only a record's first
    seconds; `format` and `units` are how to read a record file. `ground_motion()` is the
    motion, loaded once per process."""

    case: int
    system: object  # analytic.system.System
    motion: object  # analytic.motion.GroundMotion, a lazy one, or a spec (str)
    duration: float
    inputs: dict = field(default_factory=dict, compare=False)
    theta0: float = 0.0
    name: str = ""
    window: float | None = None
    format: str | None = None
    units: str | None = None

    @classmethod
    def named(cls, name: str, system: System, motion: str, duration: float, theta0_over_alpha: float = 0.0,
              window: float | None = None, format: str | None = None, units: str | None = None, **more) -> "Case":
        """A named run from its tilt as a fraction of α (what `Scenario(...)` made)."""
        return cls(0, system, motion, duration, theta0=theta0_over_alpha * system.alpha, name=name, window=window,
                   format=format, units=units, **more)

    @property
    def theta0_over_alpha(self) -> float:
        return self.theta0 / self.system.alpha

    def ground_motion(self) -> GroundMotion:
        m = self.motion
        if isinstance(m, str):
            return _load(m, self.window, self.format, self.units)
        return m.motion() if isinstance(m, (_LazyPulse, _LazyScaled)) else m

    def with_system(self, system: System, name: str | None = None) -> "Case":
        """The same case on another system, its tilt the same fraction of the new α."""
        return replace(self, system=system, theta0=self.theta0_over_alpha * system.alpha, name=name or self.name)


#: A spec's vertical component follows this separator: "HORIZONTAL + vertical VERTICAL", each
#: a spec of its own (a pulse, a record, a synthetic record): a two-component motion that a
#: named case can carry as a string (docs/sliding.md)
VERTICAL_SEPARATOR = " + vertical "


def with_vertical_spec(spec: str, vertical: str | None) -> str:
    """The spec of `spec`'s motion with the vertical component `vertical` (a spec; None: none)."""
    return spec if vertical is None else f"{spec}{VERTICAL_SEPARATOR}{vertical}"


@functools.lru_cache(maxsize=64)
def _load(spec, window, format, units) -> GroundMotion:
    if VERTICAL_SEPARATOR in spec:
        horizontal, vertical = spec.split(VERTICAL_SEPARATOR, 1)
        return _load(horizontal, window, format, units).with_vertical(_load(vertical, window, format, units))
    if spec.startswith("noise:"):
        p = dict(kv.split("=") for kv in spec[len("noise:"):].split(","))
        m = synthetic_record(float(p["dt"]), float(p["pga"]), float(p["seconds"]), int(p["seed"]))
    else:
        kwargs = {"format": format} if format else {}
        if units:
            kwargs["units"] = units
        m = load_motion(spec, **kwargs)
    return m.trimmed(0.0, window) if window is not None and m.end_time > window else m


def synthetic_record(dt: float, pga_g: float, seconds: float, seed: int) -> GroundMotion:
    """Band-limited noise (0.2–10 Hz, or Nyquist) with a build-up and decay envelope,
    scaled to `pga_g`: a record-like input at any sample step."""
    rng = np.random.default_rng(seed)
    n = int(round(seconds / dt)) + 1
    spectrum = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    spectrum[(f < 0.2) | (f > min(10.0, 0.45 / dt))] = 0
    a = np.fft.irfft(spectrum, n)
    t = np.arange(n) * dt
    a *= np.minimum(1.0, t / (0.2 * seconds)) * np.exp(-np.maximum(0.0, t - 0.5 * seconds) / (0.2 * seconds))
    return GroundMotion.from_array(a / np.max(np.abs(a)) * pga_g, dt=dt, units="g",
                                   name=f"noise dt={dt:g} pga={pga_g:g}g")


def block_system(*, height: float, slenderness: float, mass: float, mass_ratio: float,
                 period: float = PAPER_PERIOD, damping_ratio: float = PAPER_DAMPING_RATIO,
                 friction: float | None = None) -> System:
    """A block of height H (m) and slenderness λ = H/B of mass m (kg), on a base of mass
    m/μ tied by the isolator (T s, ξ; the paper's by default), or on a fixed base when
    μ = 0, with the statue–base friction μ_s (None: it cannot slip): the one place a
    System is built from the numbers that are varied."""
    width = height / slenderness
    if mass_ratio == 0:
        return System.fixed(height=height, width=width, mass=mass).with_friction(friction)
    return System.isolated(height=height, width=width, mass=mass, base_mass=mass / mass_ratio, period=period,
                           damping_ratio=damping_ratio).with_friction(friction)


def build_system(inputs: dict) -> System:
    """The System of a table row's inputs; `body` (a PlanarBody: a statue's mesh along its
    shaking direction, docs/statues.md) takes the block's place where the row has one."""
    body = inputs.get("body")
    geo = dict(body.box if body is not None else dict(height=inputs["height"], width=inputs["width"]),
               mass=inputs["mass"])
    friction = inputs.get("friction")  # the statue's (docs/sliding.md), None or NaN: it cannot slip
    friction = None if friction is None or math.isnan(friction) else friction
    if inputs["base"] == "fixed":
        system = System.fixed(**geo)
    else:
        # the base's mass as the user gave it, where they did (a campaign's base_mass), not
        # recomputed from the ratio (80/(80/150) is not 150 in floating point)
        base_mass = inputs.get("base_mass") or inputs["mass"] / inputs["mass_ratio"]
        system = System.isolated(**geo, base_mass=base_mass, period=inputs["period"],
                                 damping_ratio=inputs["damping_ratio"])
    if body is not None:
        system = replace(system, body=body)
    return system.with_friction(friction)


def pulse_for(system: System, kind: str, frequency_ratio: float, amplitude_ratio: float,
              cycles: float) -> Pulse:
    """The pulse in dimensionless form: ω_p = frequency_ratio·p, a_p = amplitude_ratio·g·tanα
    (the block's p and α; on an isolated base too, so spectra of both bases share axes)."""
    freq = frequency_ratio * system.p / (2 * math.pi)
    amp_g = amplitude_ratio * math.tan(system.alpha) * system.gravity / STANDARD_GRAVITY
    return Pulse(kind=kind, amp=amp_g, freq=freq, cycles=cycles)


def peak_ground_velocity(motion: GroundMotion) -> float:
    """max |v| (m/s) of the record (GroundMotion.pgv: the one home of the rule)."""
    return motion.pgv


def record_factor(record: GroundMotion, scale_by: str, level: float) -> float:
    """The factor that scales the record to PGA = level (g) or PGV = level (m/s)."""
    peak = record.pga_g if scale_by == "pga" else peak_ground_velocity(record)
    if not peak > 0:
        raise InputError(f"motions.scale_by = {scale_by!r}: record {record.name!r} has a "
                         f"{'PGA' if scale_by == 'pga' else 'PGV'} of 0 and cannot be scaled to a level")
    factor = level / peak
    # a level past any earthquake, or a PGV level that scales a record's PGA past it, before
    # the compiled kernel sees it (issue 34: it spun on such accelerations)
    check_acceleration(f"level {level:g} ({scale_by})", record.pga_g * factor, f" (record {record.name!r} "
                                                                                 "scaled to it)")
    return factor


def build_case(case_id: int, inputs: dict, duration_rule: dict, records: dict | None = None) -> Case:
    system = build_system(inputs)
    inputs = dict(inputs)
    inputs.update(alpha=system.alpha, slenderness=system.slenderness, size=system.R, p=system.p)
    if inputs["scale_by"]:
        record = records[inputs["motion"]]
        factor = record_factor(record, inputs["scale_by"], inputs["intensity"])
        motion = _LazyScaled(record, factor)
        inputs.update(scale_factor=factor, pulse_amp_g=math.nan, pulse_freq_hz=math.nan)
    else:
        pulse = pulse_for(system, inputs["motion"], inputs["frequency_ratio"], inputs["amplitude_ratio"],
                          inputs["cycles"])
        motion = _LazyPulse(pulse)
        inputs.update(scale_factor=math.nan, pulse_amp_g=pulse.amp, pulse_freq_hz=pulse.freq)
    end = motion.end_time
    duration = duration_rule["end"] if "end" in duration_rule else end + duration_rule["tail"]
    inputs["duration"] = duration
    return Case(case_id, system, motion, duration, inputs)


class _LazyPulse:
    """A pulse whose GroundMotion (with its samples) is made only when a run needs it:
    a 4,000-cell spectrum would otherwise hold and ship 4,000 sampled copies."""

    __slots__ = ("pulse",)

    def __init__(self, pulse: Pulse):
        self.pulse = pulse

    @property
    def end_time(self) -> float:
        return self.pulse.end_time

    def motion(self) -> GroundMotion:
        return GroundMotion.from_pulse(self.pulse)


class _LazyScaled:
    """A record and its scale factor, scaled only when a run needs it: the cases of one
    record at several levels then share one record, which a task ships once (pickle keeps
    one copy of an object however often it is referred to), not once per level. The
    FEMA far-field set at 5 levels made a 22 MiB task graph with the copies."""

    __slots__ = ("record", "factor")

    def __init__(self, record: GroundMotion, factor: float):
        self.record, self.factor = record, factor

    @property
    def end_time(self) -> float:
        return self.record.end_time

    def motion(self) -> GroundMotion:
        return self.record.scaled(self.factor)


#: a record's content digest, computed once per loaded record (a suite's cases share it)
_DIGESTS: "weakref.WeakKeyDictionary[GroundMotion, str]" = weakref.WeakKeyDictionary()


def record_digest(case: Case) -> str | None:
    """SHA-256 of the samples and step of the record a case runs (after its units were
    read, before its scale factor): None for a pulse, which its inputs define whole. A
    record's name, level and scale do not define it: a file replaced by another of the
    same name, PGA and length must not pass for the old one (a resumed sweep kept the
    old rows)."""
    m = case.motion
    record = m.record if isinstance(m, _LazyScaled) else m
    if isinstance(m, _LazyPulse) or not isinstance(record, GroundMotion) or record.pulse is not None:
        return None
    digest = _DIGESTS.get(record)
    if digest is None:
        h = hashlib.sha256(np.float64(record.dt).tobytes())
        h.update(np.ascontiguousarray(record.acceleration, dtype="<f8").tobytes())
        digest = _DIGESTS[record] = h.hexdigest()
    return digest


def motion_of(case: Case) -> GroundMotion:
    """The case's GroundMotion (Case.ground_motion)."""
    return case.ground_motion()
