"""Closed forms of the impact model (Roussis et al. 2008; model.md).

All take the slenderness λ = h/b and the mass ratio μ = m/m_b (μ = 0: fixed base).
β is dimensionless; β₂ and β₃ multiply θ̇ (rad/s) to give a velocity (m/s) and so
carry the half height h (m).
"""
from __future__ import annotations

import math

from .errors import require, require_nonnegative_finite, require_positive_finite


#: The largest slenderness and mass ratio the closed forms take: λ²(μ + 4) must stay a
#: double (λ = 1e300 overflowed λ², a traceback from `isorock beta`). No statue or base
#: comes within many orders of magnitude of it; past it every form has reached its limit
#: (β → 1, β₂ → 0 as λ → ∞) to the last digit.
MAX_CLOSED_FORM = 1e100


def _check(slenderness, mass_ratio):
    lam = require_positive_finite("slenderness", slenderness)
    mu = require_nonnegative_finite("mass_ratio", mass_ratio)
    require(lam <= MAX_CLOSED_FORM, "slenderness", slenderness, f"at most {MAX_CLOSED_FORM:g}")
    require(mu <= MAX_CLOSED_FORM, "mass_ratio", mass_ratio, f"at most {MAX_CLOSED_FORM:g}")
    return lam, mu


def _denominator(lam, mu):
    return lam**2 * (mu + 4) + 4 * (mu + 1)


def beta(slenderness: float, mass_ratio: float) -> float:
    """θ̇⁺ = β θ̇⁻ when rocking continues about the other corner."""
    lam, mu = _check(slenderness, mass_ratio)
    return (lam**2 * (mu + 4) - 2 * (mu + 1)) / _denominator(lam, mu)


def beta2(slenderness: float, mass_ratio: float, half_height: float) -> float:
    """u̇⁺ = u̇⁻ + β₂ θ̇⁻ when rocking continues (m/rad)."""
    lam, mu = _check(slenderness, mass_ratio)
    h = require_positive_finite("half_height", half_height)
    return 6 * mu * h / _denominator(lam, mu)


def beta3(mass_ratio: float, half_height: float) -> float:
    """u̇⁺ = u̇⁻ + β₃ θ̇⁻ when rocking ceases (m/rad)."""
    mu = require_nonnegative_finite("mass_ratio", mass_ratio)
    h = require_positive_finite("half_height", half_height)
    return mu * h / (1 + mu)


def beta_housner(slenderness: float) -> float:
    """Housner's fixed-base coefficient 1 − 1.5 sin²α, α = atan(1/λ)."""
    lam = require_positive_finite("slenderness", slenderness)
    return 1 - 1.5 * math.sin(math.atan(1 / lam)) ** 2


def no_bounce_slenderness(mass_ratio: float) -> float:
    """β > 0 exactly when λ exceeds √(2(μ+1)/(μ+4))."""
    mu = require_nonnegative_finite("mass_ratio", mass_ratio)
    return math.sqrt(2 * (mu + 1) / (mu + 4))


def edge_impact(mass: float, base_mass: float | None, centre_height: float, inertia: float,
                lever_from: float, lever_to: float) -> tuple[float, float]:
    """(β, β₂) of an impact that ends rocking about the edge at lever_from (m, the horizontal
    distance from the centre of mass) and starts it about the edge at lever_to, on a base of
    base_mass (None: a fixed base, β₂ = 0): a statue of two different edges (System.body).

    At θ = 0 the block's centre of mass moves at (u̇ + h θ̇, s·b_s·θ̇) about edge s. The impact's
    impulses act at the new edge and between base and ground only through bounded forces, so it
    conserves the block's angular momentum about the new edge,
        (I_c + m h² − m b_from b_to) θ̇⁻ + m h u̇⁻ = (I_c + m h² + m b_to²) θ̇⁺ + m h u̇⁺,
    and the system's horizontal momentum, M u̇ + m h θ̇. With c = m²h²/M (0 on a fixed base):
        β = (I_c + m h² − m b_from b_to − c) / (I_c + m h² + m b_to² − c),   β₂ = (m h/M)(1 − β).
    For the rectangle (b_from = b_to = b, I_c = m(b² + h²)/3) these are beta and beta2 above."""
    m = require_positive_finite("mass", mass)
    h = require_positive_finite("centre_height", centre_height)
    i_c = require_positive_finite("inertia", inertia)
    b_from = require_positive_finite("lever_from", lever_from)
    b_to = require_positive_finite("lever_to", lever_to)
    if base_mass is None:
        share, c = 0.0, 0.0
    else:
        big_m = m + require_positive_finite("base_mass", base_mass)
        share = m * h / big_m
        c = m * h * share
    beta_ = (i_c + m * h * h - m * b_from * b_to - c) / (i_c + m * h * h + m * b_to * b_to - c)
    return beta_, share * (1.0 - beta_)
