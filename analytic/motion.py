"""Ground motion: horizontal ground acceleration ẍg(t) in m/s².

A `GroundMotion` is either a uniformly sampled record (linear between samples,
zero after the last sample) or one of model.md's closed-form pulses (evaluated
exactly). Every engine asks the same object for ẍg(t), so all three see the same
input.

Readers: PEER NGA AT2 (the units its header states: g, cm/s² or m/s²; a velocity or
displacement series is refused), the JMA text format (gal, `dt` on the third line),
two-column text (t, a) whose units must be given (`units=`, the CLI's `--units`) or
stated in the file (see `read_two_column`). Units given for a file that states its
own must agree with it. Malformed files raise `InputError` naming the file, the line
and what was expected. Sizes are bounded by analytic.limits (record samples, pulse
length).
"""
from __future__ import annotations

import functools

import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .errors import InputError, require, require_nonnegative_finite, require_positive_finite
from .limits import MAX_DURATION, MAX_SAMPLES, check_record_samples
from .system import STANDARD_GRAVITY

UNITS = {"m/s2": 1.0, "g": STANDARD_GRAVITY, "gal": 0.01, "cm/s2": 0.01}
FORMATS = ("at2", "jma", "csv")
PULSES = ("sine", "cosine", "ricker")


@dataclass(frozen=True)
class Pulse:
    """Closed-form pulse (model.md): amplitude `amp` in g, frequency `freq` in Hz."""

    kind: str
    amp: float
    freq: float
    cycles: float = 1.0

    def __post_init__(self):
        require(self.kind in PULSES, "pulse", self.kind, f"one of {', '.join(PULSES)}")
        object.__setattr__(self, "amp", _finite("amp", self.amp))
        object.__setattr__(self, "freq", require_positive_finite("freq", self.freq))
        object.__setattr__(self, "cycles", require_positive_finite("cycles", self.cycles))
        if self.end_time > MAX_DURATION:
            length = "3/freq" if self.kind == "ricker" else "cycles/freq"
            raise InputError(f"{self.spec()}: lasts {length} = {self.end_time:.3g} s; a pulse must end within "
                             f"{MAX_DURATION:g} s (MAX_DURATION): raise freq or lower cycles")

    @property
    def end_time(self) -> float:
        # A Ricker wavelet centred at 1/F is below 1e-15 of its peak beyond 3/F.
        return 3.0 / self.freq if self.kind == "ricker" else self.cycles / self.freq

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        A = self.amp * STANDARD_GRAVITY
        w = 2 * math.pi * self.freq
        if self.kind == "sine":
            a = A * np.sin(w * t)
        elif self.kind == "cosine":
            a = A * np.cos(w * t)
        else:
            tau = t - 1.0 / self.freq
            x = (math.pi * self.freq * tau) ** 2
            a = A * (1 - 2 * x) * np.exp(-x)
        return np.where((t >= 0) & (t <= self.end_time), a, 0.0)

    def spec(self) -> str:
        if self.kind == "ricker":
            return f"ricker:amp={self.amp:g},freq={self.freq:g}"
        return f"{self.kind}:amp={self.amp:g},freq={self.freq:g},cycles={self.cycles:g}"


def _finite(name, value) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r}: must be a finite number") from None
    require(math.isfinite(x), name, value, "a finite number")
    return x


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """ẍg(t) in m/s² for t ≥ 0.

    Records: `acceleration[i]` at t = i·dt, linear between samples, zero after the
    last one. Pulses: `pulse` is evaluated exactly and `acceleration` holds it
    sampled at `dt` for engines that want samples. Use `from_array`, the readers,
    `pulse(...)`, `zero()` or `load_motion(spec)`.
    """

    dt: float
    acceleration: np.ndarray
    name: str = ""
    pulse: Pulse | None = None
    scale: float = 1.0
    _pulse_shift: float = field(default=0.0, repr=False)  # time trimmed off a pulse's start
    units: str = "m/s2"  # the units the source was read in (its samples are always m/s²)
    #: the vertical component üv(t) (m/s², positive up) as a motion of its own, or None: a
    #: paired record or a pulse; the base carries it rigidly (docs/sliding.md, "Vertical")
    vertical: "GroundMotion | None" = None
    #: the second horizontal component ÿg(t) (m/s², along the ground's +y, 90° from this one's
    #: +x) as a motion of its own, or None: a record pair's other component (issue 36). Only an
    #: engine whose Capabilities.transverse is True carries it; the others refuse it (run_inputs)
    transverse: "GroundMotion | None" = None

    def __post_init__(self):
        require_positive_finite("dt", self.dt)
        a = np.asarray(self.acceleration, dtype=float)
        require(a.ndim == 1, "acceleration", f"array of shape {a.shape}", "one-dimensional")
        if a.size == 0:
            raise InputError(f"{self.name or 'acceleration'}: no samples (the motion is empty)")
        bad = ~np.isfinite(a)
        if bad.any():
            i = int(np.argmax(bad))
            raise InputError(f"{self.name or 'acceleration'}: sample {i} is {a[i]}: "
                             "every sample must be a finite number")
        if self.pulse is None:
            check_record_samples(self.name or "acceleration", a.size)
            if (a.size - 1) * self.dt > MAX_DURATION:
                raise InputError(f"{self.name or 'acceleration'}: lasts {(a.size - 1) * self.dt:.3g} s; a record "
                                 f"must end within {MAX_DURATION:g} s (MAX_DURATION)")
        a.setflags(write=False)
        object.__setattr__(self, "acceleration", a)
        if self.vertical is not None:
            require(isinstance(self.vertical, GroundMotion) and self.vertical.vertical is None, "vertical",
                    self.vertical, "a GroundMotion of one component (the vertical üv, m/s², up positive)")
        if self.transverse is not None:
            t = self.transverse
            require(isinstance(t, GroundMotion) and t.vertical is None and t.transverse is None, "transverse",
                    t, "a GroundMotion of one component (the second horizontal ÿg, m/s², along +y)")

    # --- construction -------------------------------------------------------------
    @classmethod
    def from_array(cls, acceleration, *, dt=None, t=None, units="m/s2", name="array") -> "GroundMotion":
        """From samples at a uniform step `dt` (s), or at times `t` (s) that must be
        uniform and increasing. `units`: one of m/s2, g, gal, cm/s2."""
        require(units in UNITS, "units", units, f"one of {', '.join(UNITS)}")
        try:
            a = np.asarray(acceleration, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"{name}: acceleration values must be numbers") from None
        if (dt is None) == (t is None):
            raise InputError(f"{name}: give exactly one of dt or t")
        if t is not None:
            dt = _uniform_step(np.asarray(t, dtype=float), a.size, name)
        return cls(dt=require_positive_finite("dt", dt), acceleration=a * UNITS[units], name=name, units=units)

    @classmethod
    def from_pulse(cls, pulse: Pulse, *, dt: float | None = None) -> "GroundMotion":
        dt = dt or min(1e-3, 1 / (200 * pulse.freq))
        n = math.floor(pulse.end_time / dt + 1e-9) + 1
        if n > MAX_SAMPLES:
            raise InputError(f"{pulse.spec()}: sampled every {dt:.3g} s it takes {n:.3g} samples; must be at most "
                             f"{MAX_SAMPLES:.0e} (MAX_SAMPLES): fewer cycles")
        return cls(dt=dt, acceleration=pulse(np.arange(n) * dt), name=pulse.spec(), pulse=pulse, units="g")

    @classmethod
    def zero(cls) -> "GroundMotion":
        return cls(dt=1.0, acceleration=np.zeros(1), name="none")

    # --- evaluation ---------------------------------------------------------------
    @property
    def n(self) -> int:
        return self.acceleration.size

    @property
    def end_time(self) -> float:
        """Time of the last sample (s); ẍg is zero after it."""
        if self.pulse is not None:
            return self.pulse.end_time - self._pulse_shift
        return (self.n - 1) * self.dt

    @property
    def is_zero(self) -> bool:
        """No horizontal and no vertical motion."""
        return (self.pulse is None and not np.any(self.acceleration)
                and (self.vertical is None or self.vertical.is_zero)
                and (self.transverse is None or self.transverse.is_zero))

    @property
    def last_time(self) -> float:
        """When the last component ends (s): the horizontal's end_time, or the vertical's if later."""
        return max([self.end_time] + [c.end_time for c in (self.vertical, self.transverse) if c is not None])

    def with_vertical(self, vertical: "GroundMotion | None") -> "GroundMotion":
        """This horizontal motion paired with a vertical one (None: without)."""
        return replace(self, vertical=vertical)

    def with_transverse(self, transverse: "GroundMotion | None") -> "GroundMotion":
        """This motion with a second horizontal component along +y (None: without)."""
        return replace(self, transverse=transverse)

    def transverse_at(self, t):
        """ÿg at time(s) t, m/s² (zeros without a second horizontal component)."""
        return np.zeros(np.shape(t)) if self.transverse is None else np.asarray(self.transverse(t), dtype=float)

    def vertical_at(self, t: float) -> float:
        """Scalar üv(t), m/s² (0 without a vertical component)."""
        return 0.0 if self.vertical is None else self.vertical.at(t)

    @functools.cached_property
    def times(self) -> np.ndarray:
        """The samples' times (s), kept: every evaluation interpolates over them."""
        return np.arange(self.n) * self.dt

    def __call__(self, t):
        """ẍg at time(s) t (s), in m/s²."""
        if self.pulse is not None:
            return self.scale * self.pulse(np.asarray(t, dtype=float) + self._pulse_shift)
        t = np.asarray(t, dtype=float)
        a = np.interp(t, self.times, self.acceleration, left=0.0, right=0.0)
        return np.where((t >= 0) & (t <= self.end_time), a, 0.0)

    def at(self, t: float) -> float:
        """Scalar ẍg(t), cheaper than __call__ inside integrators."""
        if self.pulse is not None:
            return float(self(t))
        if t < 0 or t > self.end_time:
            return 0.0
        x = t / self.dt
        i = min(int(x), self.n - 2) if self.n > 1 else 0
        if self.n == 1:
            return float(self.acceleration[0]) if t == 0 else 0.0
        f = x - i
        return float((1 - f) * self.acceleration[i] + f * self.acceleration[i + 1])

    def breakpoints(self, t_end: float) -> np.ndarray:
        """Times in [0, t_end] where ẍg or its slope may jump: integrators restart there."""
        if self.pulse is not None:
            pts = [0.0, self.end_time]
        elif self.n > 1:
            pts = list(self.times[self.times <= t_end])
            pts.append(self.end_time)
        else:
            pts = [0.0]
        for other in (self.vertical, self.transverse):  # the other components' kinks too
            if other is not None:
                pts.extend(other.breakpoints(t_end))
        return np.unique(np.clip(np.array(pts), 0.0, t_end))

    @property
    def pga(self) -> float:
        """Peak |ẍg| (m/s²) of the samples, which carry any scale applied (a pulse's too)."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def pgv(self) -> float:
        """Peak |ẋg| (m/s): the samples integrated by the trapezoidal rule from rest (no
        baseline correction: a record of a suite is processed already)."""
        a = np.asarray(self.acceleration, dtype=float)
        v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * self.dt)])
        return float(np.max(np.abs(v)))

    @property
    def pga_g(self) -> float:
        return self.pga / STANDARD_GRAVITY

    def sampled(self, dt: float, t_end: float) -> np.ndarray:
        """ẍg at 0, dt, 2dt, … up to t_end (for engines that step at dt)."""
        n = int(math.floor(t_end / dt + 1e-9)) + 1
        return np.asarray(self(np.arange(n) * dt), dtype=float)

    # --- transformations ----------------------------------------------------------
    def scaled(self, factor: float) -> "GroundMotion":
        """Every component scaled by `factor` (a record scaled to a PGA keeps its V/H ratio, and a
        pair the ratio of its two horizontal components)."""
        f = _finite("scale", factor)
        vertical = None if self.vertical is None else self.vertical.scaled(f)
        transverse = None if self.transverse is None else self.transverse.scaled(f)
        if self.pulse is not None:
            return GroundMotion(dt=self.dt, acceleration=self.acceleration * f, name=self.name,
                                pulse=self.pulse, scale=self.scale * f, _pulse_shift=self._pulse_shift,
                                units=self.units, vertical=vertical, transverse=transverse)
        return GroundMotion(dt=self.dt, acceleration=self.acceleration * f, name=self.name, units=self.units,
                            vertical=vertical, transverse=transverse)

    def scaled_to_pga(self, pga_g: float) -> "GroundMotion":
        target = require_positive_finite("pga", pga_g)
        require(self.pga > 0, "motion", self.name, "non-zero to scale to a PGA")
        return self.scaled(target / self.pga_g)

    def scaled_to_pgv(self, pgv: float) -> "GroundMotion":
        """The motion scaled to a peak ground velocity of `pgv` m/s (GroundMotion.pgv)."""
        target = require_positive_finite("pgv", pgv)
        require(self.pgv > 0, "motion", self.name, "non-zero to scale to a PGV")
        return self.scaled(target / self.pgv)

    def trimmed(self, start: float = 0.0, end: float | None = None) -> "GroundMotion":
        """The part between `start` and `end` (s), re-based to start at t = 0."""
        start = require_nonnegative_finite("start", start)
        end = self.end_time if end is None else require_positive_finite("end", end)
        require(end > start, "end", end, f"greater than start = {start}")
        for key in ("transverse", "vertical"):  # the same window of every component
            other = getattr(self, key)
            if other is not None:
                part = other.trimmed(start, end) if other.end_time > start else None
                return replace(replace(self, **{key: None}).trimmed(start, end), **{key: part})
        if self.pulse is not None:
            shift = self._pulse_shift + start
            return GroundMotion(dt=self.dt, acceleration=self.acceleration, name=self.name,
                                pulse=self.pulse, scale=self.scale, _pulse_shift=shift,
                                units=self.units)._clip(end - start)
        i0 = int(math.ceil(start / self.dt - 1e-9))
        i1 = int(math.floor(end / self.dt + 1e-9))
        require(i1 >= i0, "end", end, "at least one sample after start")
        return GroundMotion(dt=self.dt, acceleration=self.acceleration[i0:i1 + 1], name=self.name, units=self.units)

    def rotated(self, angle: float) -> "GroundMotion":
        """A record pair (this component along x, `transverse` along y) as seen in axes turned
        by `angle` (rad, from x towards y): the same ground acceleration vector, its components
        cos·ẍ + sin·ÿ and −sin·ẍ + cos·ÿ. Both components must be records sampled at one dt
        (a pair is); the shorter is zero past its end, as a motion is."""
        require(self.transverse is not None, "motion", self.name, "a pair (with a transverse component) to rotate")
        a, b = self, self.transverse
        require(a.pulse is None and b.pulse is None and a.dt == b.dt and a.vertical is None, "motion", self.name,
                "a pair of records sampled at one dt, without a vertical component, to rotate")
        n = max(a.n, b.n)
        x, y = (np.pad(m.acceleration, (0, n - m.n)) for m in (a, b))
        c, s = math.cos(_finite("angle", angle)), math.sin(angle)
        turned = f" turned {math.degrees(angle):g}°"
        return GroundMotion(dt=a.dt, acceleration=c * x + s * y, name=a.name + turned, units=a.units,
                            transverse=GroundMotion(dt=a.dt, acceleration=-s * x + c * y, name=b.name + turned,
                                                    units=b.units))

    def _clip(self, length):
        # a trimmed pulse keeps its closed form; samples are refreshed for engines
        t = np.arange(int(math.floor(length / self.dt + 1e-9)) + 1) * self.dt
        return GroundMotion(dt=self.dt, acceleration=self(t), name=self.name, pulse=self.pulse,
                            scale=self.scale, _pulse_shift=self._pulse_shift, units=self.units)

    def describe(self) -> dict:
        out = {"name": self.name, "dt": self.dt, "points": self.n,
               "end_time": self.end_time, "pga_g": self.pga_g, "units_read": self.units}
        if self.vertical is not None:  # only then: a horizontal motion's description is as before
            out["vertical"] = self.vertical.describe()
        if self.transverse is not None:  # likewise: a one-component motion's description is as before
            out["transverse"] = self.transverse.describe()
        return out


# --- readers ----------------------------------------------------------------------

def _uniform_step(t: np.ndarray, n: int, name: str) -> float:
    require(t.ndim == 1 and t.size == n, f"{name}: t", f"{t.size} times", f"one per sample ({n})")
    if n < 2:
        raise InputError(f"{name}: at least two samples are needed to tell the time step")
    if not np.all(np.isfinite(t)):
        raise InputError(f"{name}: time values must be finite numbers")
    d = np.diff(t)
    if np.any(d <= 0):
        i = int(np.argmax(d <= 0))
        raise InputError(f"{name}: time must increase; t[{i + 1}] = {t[i + 1]} follows t[{i}] = {t[i]}")
    dt = (t[-1] - t[0]) / (n - 1)
    if np.max(np.abs(d - dt)) > 1e-6 * dt + 1e-9:
        i = int(np.argmax(np.abs(d - dt)))
        raise InputError(f"{name}: time must be uniformly spaced; step {i} is {d[i]} s, the mean is {dt} s")
    if abs(t[0]) > 1e-9 * dt:
        raise InputError(f"{name}: time must start at 0, it starts at {t[0]}")
    return float(dt)


def _numbers(tokens, path, lineno):
    out = []
    for tok in tokens:
        if "_" in tok:  # Python reads 1_000 as 1000; no record format writes digit separators
            raise InputError(f"{path}:{lineno}: {tok!r} is not a number (digit separators '_' are not read)")
        try:
            x = float(tok.replace("D", "E").replace("d", "e"))
        except ValueError:
            raise InputError(f"{path}:{lineno}: {tok!r} is not a number") from None
        if not math.isfinite(x):
            raise InputError(f"{path}:{lineno}: {tok!r} is not a finite number")
        out.append(x)
    return out


def _read_lines(path) -> list[str]:
    p = Path(path)
    if not p.is_file():
        raise InputError(f"motion file {str(path)!r}: no such file")
    try:
        # utf-8-sig: a byte-order mark is not part of the first value
        return p.read_text(encoding="utf-8-sig", errors="replace").splitlines()
    except OSError as e:
        raise InputError(f"motion file {str(path)!r}: cannot be read ({e.strerror})") from None


_AT2_HEADER = re.compile(r"NPTS\s*=\s*([0-9]+)\s*,\s*DT\s*=\s*([^\s,]+)", re.IGNORECASE)
# "UNITS OF G", "IN UNITS OF CM/SEC/SEC", "UNITS: m/s2", "(UNITS = GAL)"
_UNITS_STATED = re.compile(r"\bUNITS?\s*(?:OF|IN|:|=)?\s*([A-Za-z][A-Za-z0-9/*^.²]*(?:\s*/\s*[A-Za-z0-9*^²]+)*)",
                           re.IGNORECASE)
_NOT_ACCELERATION = re.compile(r"\b(VELOCITY|DISPLACEMENT)\b", re.IGNORECASE)


def units_from_text(text: str) -> str | None:
    """One of UNITS for an acceleration unit as records write it (G, GAL, CM/SEC/SEC,
    CM/S2, CM/S^2, CM/S**2, M/S/S, …), None for anything else (not an acceleration,
    or unknown)."""
    s = re.sub(r"\s+", "", text).upper().rstrip(".").replace("²", "2")
    if s in ("G", "GS", "G'S"):
        return "g"
    if s in ("GAL", "GALS"):
        return "gal"
    m = re.fullmatch(r"(CM|M)/(?:S|SEC)(?:/(?:S|SEC)|\^?2|\*\*2)", s)
    if m:
        return "cm/s2" if m.group(1) == "CM" else "m/s2"
    return None


def _same_units(a: str, b: str) -> bool:
    return UNITS[a] == UNITS[b]


def _stated_units(path, stated_text: str | None, where: str, given: str | None, default: str | None) -> str:
    """The units to read a file in: those it states (which `given` must agree with),
    else `given`, else `default`; a file with none of these is refused."""
    if stated_text is not None:
        stated = units_from_text(stated_text)
        if stated is None:
            raise InputError(f"{path}: {where} states units {stated_text!r}: not an acceleration in known units "
                             f"(accepted: g, gal or cm/s², m/s²)")
        if given is not None and not _same_units(stated, given):
            raise InputError(f"units = {given!r}: contradicts {path}, whose {where} states {stated_text!r}")
        return stated
    if given is not None:
        require(given in UNITS, "units", given, f"one of {', '.join(UNITS)}")
        return given
    if default is not None:
        return default
    raise InputError(f"{path}: its units are not stated: give --units ({', '.join(UNITS)}) "
                     "or a line '# units: g' in the file")


def read_at2(path, units: str | None = None) -> GroundMotion:
    """PEER NGA AT2: 3 text lines (the third says what the series is and its units,
    e.g. `ACCELERATION TIME SERIES IN UNITS OF G`), then `NPTS = n, DT = dt SEC`,
    then the values. The header's units are read (g, cm/s², m/s²); a velocity or
    displacement series, or a header without units and without `units`, is refused."""
    lines = _read_lines(path)
    if len(lines) < 4:
        raise InputError(f"{path}: an AT2 file has 4 header lines; this one has {len(lines)} lines")
    header = " ".join(lines[:3])
    kind = _NOT_ACCELERATION.search(header)
    if kind:
        raise InputError(f"{path}: the header says it is a {kind.group(1).lower()} series; "
                         "a ground motion must be an acceleration series")
    m = _AT2_HEADER.search(lines[3])
    if not m:
        raise InputError(f"{path}:4: expected 'NPTS = n, DT = dt SEC', found {lines[3].strip()!r}")
    stated = _UNITS_STATED.search(header)
    units = _stated_units(path, stated.group(1) if stated else None, "header", units, None)
    npts = int(m.group(1))
    check_record_samples(f"{path}:4: NPTS = {npts}", npts)  # before reading millions of values
    try:
        dt = float(m.group(2))
    except ValueError:
        dt = None
    if dt is None or not (math.isfinite(dt) and dt > 0):
        raise InputError(f"{path}:4: DT = {m.group(2)!r}: must be a positive number of seconds")
    values = []
    for k, line in enumerate(lines[4:], start=5):
        values.extend(_numbers(line.split(), path, k))
    if len(values) != npts:
        raise InputError(f"{path}: header says NPTS = {npts} but the file has {len(values)} values")
    return GroundMotion.from_array(values, dt=dt, units=units, name=Path(path).name)


def read_jma(path, units: str | None = None) -> GroundMotion:
    """JMA text as in shared/data/records/KOBE_NS: `;` comment lines, a line
    `dt x` (the second number is unused), then values in gal (cm/s², the format's
    units: `units`, when given, must agree)."""
    if units is not None:
        _stated_units(path, "gal", "format (JMA)", units, None)
    lines = [(k, ln) for k, ln in enumerate(_read_lines(path), start=1)
             if ln.strip() and not ln.lstrip().startswith(";")]
    if not lines:
        raise InputError(f"{path}: no data (expected a line 'dt x' and then values in gal)")
    k0, head = lines[0]
    head_numbers = _numbers(head.split(), path, k0)
    if not head_numbers:
        raise InputError(f"{path}:{k0}: expected the time step on the first data line")
    dt = head_numbers[0]
    values = []
    for k, line in lines[1:]:
        values.extend(_numbers(line.split(), path, k))
    return GroundMotion.from_array(values, dt=dt, units="gal", name=Path(path).name)


_COMMENT_UNITS = re.compile(r"^\s*#\s*units?\s*[:=]\s*(\S+)\s*$", re.IGNORECASE)
_COLUMN_UNITS = re.compile(r"[\[(]\s*([^\])]+?)\s*[\])]\s*$")


def read_two_column(path, units: str | None = None) -> GroundMotion:
    """Two columns t (s), a separated by commas, spaces or tabs; `#` comments and one
    non-numeric header line are allowed. The units of a must be known: `units`, or
    stated in the file by a comment line `# units: g` (g, gal, cm/s2, m/s2, or as
    records write them, CM/SEC/SEC …) or by the header's second column name ending in
    brackets or parentheses, `t [s], a [g]` or `time (s), acc (cm/s2)`; both given
    must agree. A file without units is refused: read as m/s², a file in g would be
    981 times too weak and look like a plausible quiet record."""
    t, a = [], []
    stated, where = None, ""
    lines = _read_lines(path)
    for k, line in enumerate(lines, start=1):
        c = _COMMENT_UNITS.match(line)
        if c and stated is None:
            stated, where = c.group(1), f"line {k}"
        elif c and units_from_text(c.group(1)) != units_from_text(stated):
            raise InputError(f"{path}:{k}: states units {c.group(1)!r}, contradicting {where} ({stated!r}); "
                             "state them once")
        s = line.split("#", 1)[0].strip()
        if not s:
            continue
        parts = [p for p in re.split(r"[,\s;]+", s) if p]
        if not t and not a and parts and not _looks_numeric(parts[0]):
            columns = [col.strip() for col in re.split(r"[,;\t]", s) if col.strip()]
            named = _COLUMN_UNITS.search(columns[-1]) if len(columns) == 2 else None
            if named and stated is None:
                stated, where = named.group(1), f"header (line {k})"
            continue  # header line
        if len(parts) != 2:
            raise InputError(f"{path}:{k}: expected two columns (t, a), found {len(parts)}")
        x, y = _numbers(parts, path, k)
        t.append(x)
        a.append(y)
    if not a:
        raise InputError(f"{path}: no data rows (expected two columns t, a)")
    units = _stated_units(path, stated, where, units, None)
    return GroundMotion.from_array(a, t=t, units=units, name=Path(path).name)


def _looks_numeric(tok):
    try:
        float(tok)
        return True
    except ValueError:
        return False


def parse_pulse(spec: str) -> Pulse:
    """`sine:amp=A,freq=F,cycles=N`, `cosine:…`, `ricker:amp=A,freq=F` (A in g, F in Hz)."""
    kind, _, rest = spec.partition(":")
    kind = kind.strip().lower()
    require(kind in PULSES, "motion", spec, f"a file, 'none' or a pulse {', '.join(PULSES)}")
    allowed = {"amp", "freq"} | ({"cycles"} if kind != "ricker" else set())
    params = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, value = item.partition("=")
        key = key.strip()
        if not eq or key not in allowed:
            raise InputError(f"motion = {spec!r}: parameter {item!r} unknown; "
                             f"{kind} takes {', '.join(sorted(allowed))} as key=value")
        if key in params:
            raise InputError(f"motion = {spec!r}: {key} is given twice; give each of "
                             f"{', '.join(sorted(allowed))} once")
        params[key] = _finite(f"{kind} {key}", value)
    for key in ("amp", "freq"):
        if key not in params:
            raise InputError(f"motion = {spec!r}: {kind} needs {key}=… ({'in g' if key == 'amp' else 'in Hz'})")
    return Pulse(kind=kind, **params)


def load_motion(spec: str | None, *, format: str | None = None, units: str | None = None) -> GroundMotion:
    """A motion from a command-line SPEC: `none`, a pulse, or a file path (format
    from --format, or guessed: .AT2 → at2, otherwise JMA if it starts like one,
    else two columns). `units`: the file's units when it does not state them; a file
    that states them must agree (pulses are in g by definition)."""
    if units is not None:
        require(units in UNITS, "units", units, f"one of {', '.join(UNITS)}")
    if spec is None or spec.strip().lower() in ("", "none"):
        return GroundMotion.zero()
    if format is not None:
        require(format in FORMATS, "format", format, f"one of {', '.join(FORMATS)}")
    head = spec.split(":", 1)[0].lower()
    if head in PULSES and not Path(spec).exists():
        return GroundMotion.from_pulse(parse_pulse(spec))
    path = Path(spec)
    if format is None:
        if not path.is_file():
            raise InputError(f"motion = {spec!r}: not a file, 'none' or a pulse "
                             f"({', '.join(p + ':amp=…,freq=…' for p in PULSES)})")
        if path.suffix.lower() == ".at2":
            format = "at2"
        else:
            first = next((ln for ln in _read_lines(path) if ln.strip()), "")
            format = "jma" if first.lstrip().startswith(";") else "csv"
    if format == "at2":
        return read_at2(path, units=units)
    if format == "jma":
        return read_jma(path, units=units)
    return read_two_column(path, units=units)
