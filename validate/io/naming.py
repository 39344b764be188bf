"""Readable names of systems and motions for titles, tables and terminal output
("one-sine pulse 0.6 g, 1.3 Hz" rather than "sine:amp=0.6,freq=1.3,cycles=1").
One home, so that `isorock run --plot`, the report and its figures say the same thing.
Plain string formatting: loading this module loads nothing numerical.
"""
from __future__ import annotations

import math
import numbers

_PULSE_NAMES = {"sine": "sine", "cosine": "cosine"}


def _g(x: float) -> str:
    """A number as a person writes it: 3 significant digits, no trailing zeros."""
    return f"{x:.3g}"


def _cycles(n: float) -> str:
    return f"{_g(n)} cycle" if n == 1 else f"{_g(n)} cycles"


def describe_motion(motion, shown: float | None = None) -> str:
    """What a GroundMotion is, in words. Pulses: their kind, amplitude (in g, the scale
    applied), frequency and cycles ("one-sine pulse 0.6 g, 1.3 Hz" for one cycle,
    "sine pulse 0.6 g, 1.3 Hz, 2 cycles" for more); a Ricker wavelet has no cycles.
    Records: the name they were read under, their PGA and length, and, where a figure
    shows only its first `shown` seconds, that (a 150 s record run for 40 s was titled
    '150 s' above 40 s of data). No motion: free rocking."""
    if motion is None or motion.is_zero:
        return "no ground motion (free rocking)"
    pulse = motion.pulse
    if pulse is not None:
        amp = pulse.amp * motion.scale
        head = f"{_g(amp)} g, {_g(pulse.freq)} Hz"
        if pulse.kind == "ricker":
            return f"Ricker wavelet {head}"
        kind = _PULSE_NAMES[pulse.kind]
        if pulse.cycles == 1:
            return f"one-{kind} pulse {head}"
        return f"{kind} pulse {head}, {_cycles(pulse.cycles)}"
    name = motion.name or "record"
    cut = f"; its first {shown:.3g} s shown" if shown is not None and shown < motion.end_time else ""
    return f"{name} (PGA {motion.pga_g:.2f} g, {motion.end_time:.3g} s{cut})"


def describe_system(system) -> str:
    """The block and its base in one line: "block 2 × 0.7 m (λ 2.86), isolated base
    T 1.5 s, ξ 0.2, μ 1" or "block 2 × 0.7 m (λ 2.86), fixed base"."""
    block = (f"block {_g(system.height)} × {_g(system.width)} m (λ {system.slenderness:.3g})" if system.body is None
             else f"statue of edges α₊ {system.body.alpha(1):.3g}, α₋ {system.body.alpha(-1):.3g} rad, its centre "
                  f"{_g(system.body.centre_height)} m up")
    if system.fixed_base:
        return f"{block}, fixed base"
    if system.isolator_kind == "ball-in-cone":  # no period: a constant restoring force
        iso = system.isolator
        return (f"{block}, isolated base on a ball in a cone, tanφ {_g(iso.slope)}, μ_r {_g(iso.rolling_resistance)}, "
                f"μ {_g(system.mu)}")
    return (f"{block}, isolated base T {_g(system.period)} s, ξ {_g(system.damping_ratio)}, "
            f"μ {_g(system.mu)}")


def markdown_cell(text) -> str:
    """Text in one cell of a Markdown table (the report's, the scorecard's): its pipes escaped,
    so that they do not split the row, and on one line."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def cell(value, spec: str = "{:.4g}", missing: str = "–") -> str:
    """A value in a table of text (the run comparison, the stress grid, a campaign's
    summary): a real number by `spec` (±inf as "inf"); None or NaN, a value that is not
    there, as `missing` (each table keeps its own spelling: "–", or "" where most cells of
    a column are empty); anything else as str() (an integer, a flag, a word)."""
    if value is None:
        return missing
    if isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral):
        return missing if math.isnan(value) else spec.format(value)
    return str(value)
