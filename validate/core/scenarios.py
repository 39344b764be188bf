"""Scenarios: one system, one motion, one duration, one initial tilt; and the named
families the report, bench, stress grid, golden metrics and campaigns draw from.

A motion is kept as its spec (a pulse, a record path, "none", or a synthetic record
"noise:dt=…,pga=…,seconds=…,seed=…"), so a Scenario is small, frozen and cheap to send
to another process; `ground_motion()` loads it (once per process).
"""
from __future__ import annotations

import functools
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from isorock.analytic.motion import GroundMotion, load_motion
from isorock.analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD, System, paper_system

from .cases import block_system



def shared_folder(kind: str, variable: str) -> Path:
    """Where a shared data folder (`shared/data/KIND`, never copied into the project) lies:
    the folder named by $VARIABLE; else `shared/data/KIND` beside the checkout the package
    runs from (an editable install); else beside the working folder (`../shared/...`, a
    wheel installed elsewhere, run from the checkout). The first that exists; the
    checkout's when none does, so that a message names where it looked. The one home of
    this search: the records' ($ISOROCK_RECORDS) and the shake-table tests' ($ISOROCK_VSR)."""
    if os.environ.get(variable):
        return Path(os.environ[variable])
    beside = [Path(__file__).resolve().parents[3] / "shared" / "data" / kind,
              Path.cwd().resolve().parent / "shared" / "data" / kind]
    return next((p for p in beside if p.is_dir()), beside[0])


def records_folder() -> Path:
    """Where the shared real records lie: shared_folder("records", "ISOROCK_RECORDS")."""
    return shared_folder("records", "ISOROCK_RECORDS")


#: The shared records folder (records_folder()), read when the module loads.
RECORDS = records_folder()
KOBE = RECORDS / "RSN1106_KOBE_KJM000.AT2"
#: The robust pulse of the report, the golden metrics and the bench: the paper's block
#: rocks on both bases without overturning, and θmax/α moves < 0.05 under ±1% PGA.
ROBUST_SINE = "sine:amp=0.6,freq=1.3,cycles=2"
#: Free rocking starts from this tilt, as a fraction of α.
FREE_THETA0_OVER_ALPHA = 0.5
#: The default motions of the validation report: the robust sine, and a Ricker whose
#: isolated case is sensitive (uplift barely exceeds the threshold) and so is judged by
#: its ensemble.
REPORT_MOTIONS = (ROBUST_SINE, "ricker:amp=0.5,freq=1")
#: The paper's Figure 5 shows the first 40 s of the record; so does the report.
RECORD_WINDOW = 40.0


@dataclass(frozen=True)
class Scenario:
    """`motion` is a spec (see the module docstring); `window` (s), if given, keeps only
    the first seconds of a record; `format` and `units` are how to read a record file."""

    name: str
    system: System
    motion: str
    duration: float
    theta0_over_alpha: float = 0.0
    window: float | None = None
    format: str | None = None
    units: str | None = None

    def ground_motion(self) -> GroundMotion:
        return _load(self.motion, self.window, self.format, self.units)

    @property
    def theta0(self) -> float:
        """The initial tilt in rad."""
        return self.theta0_over_alpha * self.system.alpha

    def with_system(self, system: System, name: str | None = None) -> "Scenario":
        return replace(self, system=system, name=name or self.name)


@functools.lru_cache(maxsize=64)
def _load(spec, window, format, units) -> GroundMotion:
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


# --- families --------------------------------------------------------------------------

def paper_bases() -> tuple[tuple[str, System], ...]:
    """The paper's block (H 2.0 m, B 0.7 m, m = m_b = 3800 kg) on its isolated base
    (T 1.5 s, ξ 0.2) and on a fixed base, with their labels, in that order."""
    return (("isolated base", paper_system()), ("fixed base", paper_system(fixed_base=True)))


def block(height=2.0, slenderness=2.857, mass_ratio=1.0, period=PAPER_PERIOD, damping_ratio=PAPER_DAMPING_RATIO,
          fixed=False, mass=3800.0) -> System:
    """A block of the paper's kind varied in one or more of its numbers (cases.block_system)."""
    return block_system(height=height, slenderness=slenderness, mass=mass, mass_ratio=0.0 if fixed else mass_ratio,
                        period=period, damping_ratio=damping_ratio)


def free_rocking_grid(mass_ratios, slenderness, *, duration: float,
                      theta0_over_alpha: float = FREE_THETA0_OVER_ALPHA) -> list[Scenario]:
    """The paper's Figure 4 grid: the paper's block and isolator varied in λ (H kept,
    B = H/λ) and μ (m kept, m_b = m/μ), free rocking; then the paper's block on a fixed base."""
    paper = paper_system()
    out = [Scenario(f"free rocking λ={lam:.4g} μ={mu:g}",
                    block_system(height=paper.height, slenderness=lam, mass=paper.mass, mass_ratio=mu),
                    "none", duration, theta0_over_alpha)
           for mu in mass_ratios for lam in slenderness]
    out.append(Scenario("free rocking, fixed base", paper_system(fixed_base=True), "none", duration,
                        theta0_over_alpha))
    return out


def golden_scenarios() -> list[Scenario]:
    """Short runs of the paper's block, free and under the robust sine, on both bases:
    what tests/golden/ holds for every engine."""
    end = _load(ROBUST_SINE, None, None, None).end_time
    return [
        Scenario("free_isolated", paper_system(), "none", 3.0, FREE_THETA0_OVER_ALPHA),
        Scenario("free_fixed", paper_system(fixed_base=True), "none", 3.0, FREE_THETA0_OVER_ALPHA),
        Scenario("pulse_isolated", paper_system(), ROBUST_SINE, end + 2.0),
        Scenario("pulse_fixed", paper_system(fixed_base=True), ROBUST_SINE, end + 2.0),
    ]


def bench_scenarios(quick: bool) -> list[Scenario]:
    """Free rocking, a pulse on the isolated base (7 impacts, θmax/α 0.66) and, when the
    shared records are there, the first 40 s of Kobe."""
    out = [
        Scenario("free-rocking", paper_system(fixed_base=True), "none", 3.0 if quick else 5.0, 0.5),
        Scenario("pulse", paper_system(), "sine:amp=0.4,freq=1,cycles=2", 8.0),
    ]
    if KOBE.is_file():
        out.append(Scenario("kobe-40s", paper_system(), str(KOBE), 40.0, window=40.0))
    return out


__all__ = ["Scenario", "synthetic_record", "paper_bases", "block", "free_rocking_grid", "golden_scenarios",
           "bench_scenarios", "ROBUST_SINE", "FREE_THETA0_OVER_ALPHA", "RECORDS", "KOBE"]
