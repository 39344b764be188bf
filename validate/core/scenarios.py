"""Named runs (`Scenario`: the one case type, core.cases.Case, made by name) and the named
families the report, bench, stress grid, golden metrics and campaigns draw from; where the
shared data folders lie.
"""
from __future__ import annotations

import os
from pathlib import Path

from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD, System, paper_system

from .cases import Case, _load, block_system, synthetic_record



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


#: A named run is the one case type (core.cases.Case), made from its name, system, motion
#: spec, duration and tilt as a fraction of α: Scenario(name, system, motion, duration,
#: theta0_over_alpha, window=…, format=…, units=…), as before the two types were one.
Scenario = Case.named


# --- families --------------------------------------------------------------------------

def paper_bases() -> tuple[tuple[str, System], ...]:
    """The paper's block (H 2.0 m, B 0.7 m, m = m_b = 3800 kg) on its isolated base
    (T 1.5 s, ξ 0.2) and on a fixed base, with their labels, in that order."""
    return (("isolated base", paper_system()), ("fixed base", paper_system(fixed_base=True)))


def block(height=2.0, slenderness=2.857, mass_ratio=1.0, period=PAPER_PERIOD, damping_ratio=PAPER_DAMPING_RATIO,
          fixed=False, mass=3800.0, friction=None) -> System:
    """A block of the paper's kind varied in one or more of its numbers (cases.block_system)."""
    return block_system(height=height, slenderness=slenderness, mass=mass, mass_ratio=0.0 if fixed else mass_ratio,
                        period=period, damping_ratio=damping_ratio, friction=friction)


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
