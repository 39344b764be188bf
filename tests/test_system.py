import math

import pytest

from isorock.analytic import InputError, System, paper_system


def test_derived_quantities():
    s = System.isolated(height=2.0, width=0.7, mass=3800, base_mass=1900, period=1.5, damping_ratio=0.2)
    assert s.h == 1.0 and s.b == 0.35
    assert s.alpha == pytest.approx(math.atan(0.35))
    assert s.slenderness == pytest.approx(1 / 0.35)
    assert s.mu == pytest.approx(2.0)
    assert s.R == pytest.approx(math.sqrt(1 + 0.35**2))
    assert s.p == pytest.approx(math.sqrt(3 * 9.81 / (4 * s.R)))
    assert s.total_mass == 5700
    # T = 2π√(M/k), ξ = c/(2Mω) recovered from k and c
    assert 2 * math.pi * math.sqrt(s.total_mass / s.stiffness) == pytest.approx(1.5)
    assert s.damping / (2 * s.total_mass * (2 * math.pi / 1.5)) == pytest.approx(0.2)
    assert s.period == pytest.approx(1.5) and s.damping_ratio == pytest.approx(0.2)
    assert s.uplift_acceleration == pytest.approx(9.81 * 0.35)


def test_fixed_base_has_zero_mass_ratio():
    s = System.fixed(height=2.0, width=0.7, mass=3800)
    assert s.mu == 0.0 and s.fixed_base


def test_frozen():
    s = paper_system()
    with pytest.raises(Exception):
        s.height = 3.0


@pytest.mark.parametrize("kwargs,field", [
    (dict(height=-2.0), "height"),
    (dict(width=0.0), "width"),
    (dict(mass=float("nan")), "mass"),
    (dict(base_mass=float("inf")), "base_mass"),
    (dict(period=0.0), "period"),
    (dict(period=-1.0), "period"),
    (dict(damping_ratio=-0.1), "damping_ratio"),
    (dict(height="tall"), "height"),
])
def test_bad_input_names_field_value_and_rule(kwargs, field):
    args = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0, period=1.5, damping_ratio=0.2)
    args.update(kwargs)
    with pytest.raises(InputError) as e:
        System.isolated(**args)
    msg = str(e.value)
    assert msg.startswith(field) and "must be" in msg and repr(kwargs[field]) in msg


def test_isolated_needs_a_spring():
    with pytest.raises(InputError, match="stiffness"):
        System.from_stiffness(height=2, width=0.7, mass=1, base_mass=1, stiffness=0, damping=0)


def test_the_same_block_on_the_other_base():
    """on_fixed_base / on_isolator keep the block, its base mass and gravity; the isolator
    is the one asked for (T = 2π√(M/k), ξ = c/(2Mω) read back)."""
    import math
    iso = System.isolated(height=1.3, width=0.4, mass=900.0, base_mass=450.0, period=2.0, damping_ratio=0.1,
                          gravity=9.7)
    fixed = iso.on_fixed_base()
    assert fixed.fixed_base and (fixed.height, fixed.width, fixed.mass, fixed.base_mass, fixed.gravity) == (
        1.3, 0.4, 900.0, 450.0, 9.7)
    back = fixed.on_isolator(2.0, 0.1)
    assert back == iso
    M = iso.mass + iso.base_mass
    assert 2 * math.pi * math.sqrt(M / back.stiffness) == pytest.approx(2.0, rel=1e-14)
    assert back.damping / (2 * M * 2 * math.pi / 2.0) == pytest.approx(0.1, rel=1e-14)


def test_the_rocking_rate_is_the_exact_models_own_with_its_base_recoil():
    """System.rocking_rate (p_eff: what the contact engines scale their step and contact with) is
    √(θ̈/θ-slope) of the exact model's own equations: at θ → 0 on its weaker edge, with no ground
    motion and no spring, the free base's θ̈ over the fixed base's is (p_eff/p)² (the base's
    recoil lightens the inertia about the pivot). Oracle: analytic.physics's 2-DOF equations, which
    the rate's formula does not use; for the block, the ¾cos²α closed form, and for a statue its own
    I_O = I_c + m·R² (a bust's I_c is not the block's m·R²/3)."""
    from dataclasses import replace

    from isorock.analytic import physics, shape
    from isorock.analytic.system import PlanarBody
    bust = PlanarBody.from_resting(shape.load_statue(example="bust", mass=80.0).along(0.0))
    for mu in (0.2, 1.0, 5.0):
        block = System.isolated(height=1.2, width=0.3, mass=250.0, base_mass=250.0 / mu, period=1e6,
                                damping_ratio=0.0)
        statue = replace(System.isolated(**bust.box, mass=80.0, base_mass=80.0 / mu, period=1e6, damping_ratio=0.0),
                         body=bust)
        for system in (block, statue):
            side = 1 if system.body is None else system.body.weaker_side
            free = physics.system_params(system, 0.0)
            fixed = physics.system_params(system.on_fixed_base(), 0.0)
            free[physics.K] = 0.0  # no spring: the base only recoils
            _, free_acc, _ = physics.rocking_accelerations(free, side, 1e-9 * side, 0.0, 0.0, 0.0, 0.0)
            _, fixed_acc, _ = physics.rocking_accelerations(fixed, side, 1e-9 * side, 0.0, 0.0, 0.0, 0.0)
            assert (system.rocking_rate / system.p) ** 2 == pytest.approx(free_acc / fixed_acc, rel=1e-9), (mu, system.body)
