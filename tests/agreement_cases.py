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


# --- non-linear isolators (docs/isolators.md): the isolator kernel against the reference ---

def isolator_cases(seed: int, n: int, kind: str) -> list[tuple[System, GroundMotion]]:
    """n cases on a bilinear bearing, a single concave friction pendulum, a rolling ball in a
    cone or a bowl, or a double concave pendulum (kind: System's isolator_kind, or
    "velocity-friction": a pendulum with μ_f(v)): blocks of slenderness 2–8 and height 0.5–4 m, μ = m/m_b 0.2–5; a pendulum
    of R_fp 0.5–4 m and μ_f 0–0.15, or a bearing of initial period 0.3–2 s, post-yield ratio
    0–0.5, u_y 1–20 mm and ξ 0–0.2 on its initial stiffness; a sine, cosine or Ricker pulse of
    ω_p/p 0.5–12 and 0.8–12 × g·tanα (so that many lift, slip and stick, some overturn)."""
    from isorock.analytic.system import (BallInBowl, BallInCone, BilinearIsolator, DoubleFrictionPendulum,
                                         FrictionPendulum)
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(n):
        lam, H, mu = rng.uniform(2, 8), rng.uniform(0.5, 4), rng.uniform(0.2, 5)
        m, m_b = 1000.0, 1000.0 / mu
        if kind == "friction-pendulum":
            iso = FrictionPendulum(radius=rng.uniform(0.5, 4), friction_coefficient=rng.uniform(0, 0.15))
        elif kind == "velocity-friction":  # μ_f(v): μ_min 0–0.1, μ_max μ_min + 0–0.1, a 5–200 s/m
            mu_min = rng.uniform(0, 0.1)
            iso = FrictionPendulum(radius=rng.uniform(0.5, 4), friction_coefficient=mu_min,
                                   friction_max=mu_min + rng.uniform(0, 0.1), friction_rate=rng.uniform(5, 200))
        elif kind == "ball-in-cone":  # tanφ 0.02–0.3, μ_r 0–0.1 (some balls never move)
            iso = BallInCone(slope=rng.uniform(0.02, 0.3), rolling_resistance=rng.uniform(0, 0.1))
        elif kind == "ball-in-bowl":
            iso = BallInBowl(radius=rng.uniform(0.5, 4), rolling_resistance=rng.uniform(0, 0.1))
        elif kind == "double-friction-pendulum":  # R1, R2 0.3–3 m, μ1, μ2 0–0.15
            iso = DoubleFrictionPendulum(radius_1=rng.uniform(0.3, 3), friction_1=rng.uniform(0, 0.15),
                                         radius_2=rng.uniform(0.3, 3), friction_2=rng.uniform(0, 0.15))
        else:
            w0 = 2 * math.pi / rng.uniform(0.3, 2)
            k0 = (m + m_b) * w0 ** 2
            iso = BilinearIsolator(stiffness=k0, post_yield_ratio=rng.uniform(0, 0.5),
                                   yield_displacement=rng.uniform(0.001, 0.02),
                                   damping=2 * rng.uniform(0, 0.2) * (m + m_b) * w0)
        system = System.with_isolator(height=H, width=H / lam, mass=m, base_mass=m_b, isolator=iso)
        pulse = str(rng.choice(["sine", "cosine", "ricker"]))
        amp = rng.uniform(0.8, 12) / lam
        freq = rng.uniform(0.5, 12) * system.p / (2 * math.pi)
        cases.append((system, GroundMotion.from_pulse(Pulse(kind=pulse, amp=amp, freq=freq))))
    return cases


def _on_grid(a, b, x, y, dt):
    """max |x − y| over the output-grid times k·dt both histories store (first of each)."""
    def grid(t, v):
        k = np.round(t / dt)
        on = np.abs(t - k * dt) <= 1e-12 * max(1.0, float(np.max(np.abs(t))))
        kk, first = np.unique(k[on], return_index=True)
        return kk, v[on][first]
    ka, xa = grid(a.t, x)
    kb, xb = grid(b.t, y)
    common, ia, ib = np.intersect1d(ka, kb, return_indices=True)
    return float(np.max(np.abs(xa[ia] - xb[ib]))) if common.size else math.nan


def _times_diff(ta, tb):
    """max |Δt| of two event-time lists of the same length (nan if the counts differ)."""
    if len(ta) != len(tb):
        return math.nan
    return float(np.max(np.abs(np.subtract(ta, tb)))) if len(ta) else 0.0


def compare_isolator_paths(cases, settings: AnalyticSettings | None = None) -> dict:
    """Every case on both paths: θ and u on the shared output grid (rad, m), impact, uplift and
    stick–slip/yield times (s, matched in order), the slider's loss at the end (J, relative to
    the energy involved), counts and statuses; per-case rows and the worst of each."""
    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.hybrid import simulate
    settings = settings or AnalyticSettings()
    rows = []
    for k, (system, motion) in enumerate(cases):
        ref = simulate(system, motion, settings=settings)
        ker = simulate_fast(system, motion, settings=settings)
        dt = settings.output_dt
        ev_k, ev_r = ker.extras["isolator_events"], ref.extras["isolator_events"]
        e = ref.energy
        involved = max(float(np.max(np.abs(e.ground_work))), float(np.max(e.kinetic + e.potential)), 1e-300)
        rows.append({
            "case": k, "isolator": system.isolator_kind, "motion": motion.name, "status": str(ker.status),
            "reference_status": str(ref.status),
            "theta": _on_grid(ker, ref, ker.theta, ref.theta, dt), "u": _on_grid(ker, ref, ker.u, ref.u, dt),
            "impacts": len(ker.impacts), "reference_impacts": len(ref.impacts),
            "impact_times": _times_diff([i.t for i in ker.impacts], [i.t for i in ref.impacts]),
            "uplifts": len(ker.uplift_times), "reference_uplifts": len(ref.uplift_times),
            "uplift_times": _times_diff(ker.uplift_times, ref.uplift_times),
            "slider_events": len(ev_k), "reference_slider_events": len(ev_r),
            "slider_event_times": _times_diff([x[0] for x in ev_k], [x[0] for x in ev_r]),
            "slider_phases_equal": [x[1] for x in ev_k] == [x[1] for x in ev_r],
            "slider_loss": abs(float(ker.energy.isolator_loss[-1] - e.isolator_loss[-1])) / involved,
            "theta_max_over_alpha": abs(ker.theta_max_over_alpha - ref.theta_max_over_alpha),
        })

    def worst(key):
        values = [r[key] for r in rows if not math.isnan(r[key])]
        return max(values) if values else 0.0
    return {
        "cases": len(rows),
        "rocking_cases": sum(r["reference_uplifts"] > 0 for r in rows),
        "overturned_cases": sum(r["reference_status"] == "overturned" for r in rows),
        "slider_events_total": sum(r["reference_slider_events"] for r in rows),
        "impacts_total": sum(r["reference_impacts"] for r in rows),
        **{f"max_{key}": worst(key) for key in ("theta", "u", "impact_times", "uplift_times", "slider_event_times",
                                                "slider_loss", "theta_max_over_alpha")},
        "count_mismatches": sum(r["impacts"] != r["reference_impacts"] or r["uplifts"] != r["reference_uplifts"]
                                or r["slider_events"] != r["reference_slider_events"]
                                or not r["slider_phases_equal"] for r in rows),
        "status_mismatches": sum(r["status"] != r["reference_status"] for r in rows),
        "rows": rows,
    }
