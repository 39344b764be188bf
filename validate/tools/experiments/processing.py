"""Processing of the measured (unfiltered) table acceleration into the ground motion the
engines run: explicit steps, each one switchable (`isorock experiments --steps ...`), applied
in this order:

- offset:   remove the constant offset of the accelerometer: the mean of the leading quiet
            window (OFFSET_WINDOW s, before the table moves), else of the whole test.
- drift:    remove the drift a small remaining error integrates into: fit a polynomial of
            degree DRIFT_DEGREE to the velocity (the integral of the acceleration) and
            subtract its derivative, so that the table's velocity starts and ends at rest.
- highpass: (off by default, an alternative to drift) zero-phase Butterworth high-pass.
- lowpass:  zero-phase Butterworth low-pass (LOWPASS_HZ): sensor noise and the table's
            high-frequency chatter above what moves a 1 m rock.
- trim:     cut the quiet ends (|a| below TRIM_FRACTION of the peak), keeping TRIM_PAD s.

Zero-phase filters (forward-backward) shift no peak in time. Each step maps an array of
samples (m/s²) at step dt to another; `process` applies the chosen ones and says which.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import signal

from ....analytic.errors import InputError

STEPS = ("offset", "drift", "highpass", "lowpass", "trim")
DEFAULT_STEPS = ("offset", "drift", "lowpass", "trim")
OFFSET_WINDOW = 0.5  # s: the table has not started in the first 0.5 s of every test here
DRIFT_DEGREE = 3
HIGHPASS_HZ = 0.1
LOWPASS_HZ = 20.0
FILTER_ORDER = 4
TRIM_FRACTION = 0.05
TRIM_PAD = 1.0  # s
#: fewest samples a test may have: more than the zero-phase filter pads each end with
#: (scipy's sosfiltfilt: 3·(2·sections + 1), 15 for FILTER_ORDER 4), or it cannot run
MIN_SAMPLES = 3 * (2 * ((FILTER_ORDER + 1) // 2) + 1) + 1
#: lowest low-pass corner (Hz): below the high-pass corner a low-pass removes the shaking
#: itself (and at 1e-6 Hz its filter's initial conditions are a singular system)
MIN_LOWPASS_HZ = HIGHPASS_HZ


def remove_offset(a: np.ndarray, dt: float, window: float = OFFSET_WINDOW) -> np.ndarray:
    n = int(round(window / dt))
    lead = a[:n] if 0 < n < a.size else a
    return a - lead.mean()


def remove_drift(a: np.ndarray, dt: float, degree: int = DRIFT_DEGREE) -> np.ndarray:
    """Subtract d/dt of the least-squares polynomial fit of the velocity v(t) = ∫a."""
    t = dt * np.arange(a.size)
    v = np.concatenate(([0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)))
    coef = np.polynomial.polynomial.polyfit(t, v, degree)
    return a - np.polynomial.polynomial.polyval(t, np.polynomial.polynomial.polyder(coef))


def _butter(a, dt, hz, kind):
    nyquist = 0.5 / dt
    if not 0 < hz < nyquist:
        raise InputError(f"{kind} = {hz!r} Hz: must be between 0 and the Nyquist frequency {nyquist:g} Hz")
    sos = signal.butter(FILTER_ORDER, hz, btype=kind, fs=1.0 / dt, output="sos")
    return signal.sosfiltfilt(sos, a)


def check_lowpass(hz: float) -> float:
    """The low-pass corner, from MIN_LOWPASS_HZ (its upper bound, each test's Nyquist
    frequency, is asked of the test's step)."""
    if not (hz >= MIN_LOWPASS_HZ and math.isfinite(hz)):
        raise InputError(f"lowpass-hz = {hz!r}: must be a finite number of Hz from {MIN_LOWPASS_HZ:g} (MIN_LOWPASS_HZ: "
                         "a lower corner removes the shaking itself) to the Nyquist frequency")
    return hz


def highpass(a, dt, hz: float = HIGHPASS_HZ):
    return _butter(a, dt, hz, "highpass")


def lowpass(a, dt, hz: float = LOWPASS_HZ):
    return _butter(a, dt, check_lowpass(hz), "lowpass")


def trim(a, dt, fraction: float = TRIM_FRACTION, pad: float = TRIM_PAD):
    """(samples, start index): the part from TRIM_PAD s before the first to TRIM_PAD s after
    the last sample above `fraction` of the peak."""
    loud = np.flatnonzero(np.abs(a) >= fraction * np.abs(a).max())
    if loud.size == 0:
        return a, 0
    k = int(round(pad / dt))
    i0, i1 = max(loud[0] - k, 0), min(loud[-1] + k + 1, a.size)
    return a[i0:i1], i0


def parse_steps(text: str) -> tuple[str, ...]:
    """'offset,drift,lowpass' → the steps; 'none' → no step."""
    if text.strip().lower() == "none":
        return ()
    steps = tuple(s.strip() for s in text.split(",") if s.strip())
    for s in steps:
        if s not in STEPS:
            raise InputError(f"steps = {text!r}: {s!r} is not a step; allowed: {', '.join(STEPS)} or none")
    return steps


def process(a: np.ndarray, dt: float, steps=DEFAULT_STEPS, *, lowpass_hz: float = LOWPASS_HZ) -> np.ndarray:
    """The steps named in `steps`, in STEPS order (not the order given: trimming before the
    offset would take the offset window from the shaking)."""
    out = np.asarray(a, dtype=float)
    if out.size < MIN_SAMPLES:
        raise InputError(f"{out.size} samples: a test must have at least {MIN_SAMPLES} (MIN_SAMPLES: more than the "
                         "zero-phase filter pads each end with)")
    if "offset" in steps:
        out = remove_offset(out, dt)
    if "drift" in steps:
        out = remove_drift(out, dt)
    if "highpass" in steps:
        out = highpass(out, dt)
    if "lowpass" in steps:
        out = lowpass(out, dt, lowpass_hz)
    if "trim" in steps:
        out, _ = trim(out, dt)
    return out
