"""The compiled kernel against the SciPy reference on seeded random cases: θmax/α, counted
impacts and the overturning verdict, past-α cases included. `tests/test_agreement.py`
runs a few cases; `docs/scripts/kernel_agreement.py` a few hundred."""
from __future__ import annotations

import math

import numpy as np

from isorock.analytic.motion import GroundMotion, Pulse
from isorock.analytic.settings import AnalyticSettings
from isorock.analytic.system import System


def random_cases(seed: int, n: int) -> list[tuple[System, GroundMotion]]:
    """n cases: blocks of slenderness 2–8 and height 0.5–4 m; 40% on a fixed base, the
    rest isolated (μ 0.2–5, T 0.5–4 s, ξ 0–0.3); a sine, cosine or Ricker pulse with
    ω_p/p in 0.5–12 and amplitude 0.8–12 × g·tanα (so many rock past α)."""
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        lam, H = rng.uniform(2, 8), rng.uniform(0.5, 4)
        if rng.random() < 0.4:
            system = System.fixed(height=H, width=H / lam, mass=1000.0)
        else:
            mu = rng.uniform(0.2, 5)
            system = System.isolated(height=H, width=H / lam, mass=1000.0, base_mass=1000.0 / mu,
                                     period=rng.uniform(0.5, 4), damping_ratio=rng.uniform(0, 0.3))
        kind = str(rng.choice(["sine", "cosine", "ricker"]))
        amp = rng.uniform(0.8, 12) / lam  # in g: tanα = 1/λ
        freq = rng.uniform(0.5, 12) * system.p / (2 * math.pi)
        cases.append((system, GroundMotion.from_pulse(Pulse(kind=kind, amp=amp, freq=freq))))
    return cases


def safe_band_cases(seed: int, n: int) -> list[tuple[System, GroundMotion]]:
    """n one-sine cases on a fixed base (α = 0.25 rad) near the safe region of the
    overturning spectrum (docs/images/overturning_spectrum_fixed.png), where blocks lean
    past α and return: ω_p/p in 4–9, a_p/(g·tanα) = 1.55·ω_p/p − 0.5 ± 0.8."""
    rng = np.random.default_rng(seed)
    block = System.fixed(height=2.0, width=2 * math.tan(0.25), mass=1000.0)
    cases = []
    for _ in range(n):
        w = rng.uniform(4, 9)
        a = 1.55 * w - 0.5 + rng.uniform(-0.8, 0.8)
        cases.append((block, GroundMotion.from_pulse(Pulse("sine", a * math.tan(0.25), w * block.p / (2 * math.pi)))))
    return cases


def compare_paths(cases, settings: AnalyticSettings | None = None) -> dict:
    """Run every case on both paths; the per-case rows and the worst disagreements."""
    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.hybrid import simulate
    settings = settings or AnalyticSettings()
    rows = []
    for k, (system, motion) in enumerate(cases):
        ref = simulate(system, motion, settings=settings)
        ker = simulate_fast(system, motion, settings=settings)
        rows.append({
            "case": k, "fixed_base": system.fixed_base, "motion": motion.name,
            "status": str(ker.status), "reference_status": str(ref.status),
            "theta_max_over_alpha": ker.theta_max_over_alpha,
            "reference_theta_max_over_alpha": ref.theta_max_over_alpha,
            "impacts": ker.impact_count, "reference_impacts": ref.impact_count,
            "overturned": ker.overturned, "reference_overturned": ref.overturned,
            "past_alpha": max(ker.theta_max_over_alpha, ref.theta_max_over_alpha) > 1.0,
        })
    d = [abs(r["theta_max_over_alpha"] - r["reference_theta_max_over_alpha"]) for r in rows]
    return {
        "cases": len(rows),
        "past_alpha_cases": sum(r["past_alpha"] for r in rows),
        "overturned_cases": sum(r["reference_overturned"] for r in rows),
        "max_abs_dtheta_max_over_alpha": max(d) if d else 0.0,
        "impact_count_mismatches": sum(r["impacts"] != r["reference_impacts"] for r in rows),
        "overturn_mismatches": sum(r["overturned"] != r["reference_overturned"] for r in rows),
        "status_mismatches": sum(r["status"] != r["reference_status"] for r in rows),
        "rows": rows,
    }
