"""The block on its base in Drake (pydrake): the scene, its settings and its stepping.

Drake is the third, independent contact formulation: a continuous-time plant whose
point contact (Hunt–Crossley) is integrated with error control, beside MuJoCo's soft
constraints and Bullet's impulses. It is for free rocking, pulses and single records;
a step costs ~25× MuJoCo's and there is no batched rollout, so campaigns of thousands
of runs belong to MuJoCo or the analytic kernel (docs/drake.md).

The scene (`scene_text`: an SDFormat file Drake's Parser reads; `simulate` parses the
same text, so what a user opens is what ran):

- ground: a massless link welded to the world, turned −90° about x so that its x–y
  plane is the world's x–z plane (a `drake:joint` cannot name the world, and a planar
  joint moves in its parent frame's x–y plane);
- block: a homogeneous box (mass m, I = m(b² + h²)/3 about the rocking axis) on a
  `PlanarJoint` (drake:joint type "planar") from the ground; its link frame, at the
  centroid, is turned like the ground's, so the joint's (x, y, θ) are the centroid's
  world x, minus its world z, and the rotation about world +y: θ > 0 moves the centroid
  to +x (model.md). Contact geometry: a small sphere (radius `corner_radius`) inscribed
  in each bottom corner of the rocking plane — point contact, Hunt–Crossley;
  with `contact="hydroelastic"` the whole block is a compliant-hydroelastic box instead;
- base: a plate (top face z = 0) on a `PrismaticJoint` along x with a
  `PrismaticSpring` (k) and joint damping (c) — the isolator; welded to the world on a
  fixed base. A friction pendulum or a ball in a bowl (k = W/R, c: isolator_parts) adds its
  dry friction μ·W as a contact (_pendulum_puck): a light puck under the plate on its own
  vertical joint, held down by a constant force on that joint onto a floor welded to the world,
  its friction F_b/W, the same in every direction; its stiction tolerance
  `isolator_stiction_tolerance` (docs/drake.md, "Pendulum isolators: a held puck").
- ground motion: generalized forces −m ẍg on the block's x and −m_b ẍg on the base
  (exact for a translating ground), from a first-order-hold trajectory source into the
  plant's applied-generalized-force port; the stepping runs in C++ (Simulator.AdvanceTo
  over chunks of CHUNK s) and a VectorLogSink samples the state every `sample_interval`.
- two horizontal components (GroundMotion.transverse, issue 36; `scene_text(transverse=True)`):
  the second, ÿg along the world's y, is applied as the first: −m ÿg on the body's world y
  and, on the linear isolator, −m_b ÿg on a second prismatic joint of the base along y
  ("isolator_y", the same spring k and damping c: the isolator is isotropic; a pendulum's puck
  under the plate, its friction isotropic) under a massless carriage on the x joint. The
  block leaves its planar joint for a free body (its four bottom corner spheres; a statue's
  own shape is a free body already); a fixed base and the plate (square already) are as
  before. Without a second component the scene is the one-component scene, unchanged.

Outputs follow model.md: u (m) is the base's joint position, θ the planar joint's angle;
`simulate` returns a RawHistory, measured by the registry like every engine's. Extras, in
the vocabulary of every contact engine: `lift_off_max_after_impact` (m, the lowest
contact point's height above the base after the first counted impact), `penetration_max`
(m), `pivot_slip_max` (m, the pivot sphere's slip relative to rolling on the base). These
follow the corner spheres' own geometry (they roll), not the sharp corners of
`analytic.kinematics.contact_extras`.

A run stops by the shared rules of `analytic.kinematics.first_stop` (a non-finite state,
the block lying on its side, falling on a fixed base after the motion), and when Drake's
integrator gives up (status "failed"); it goes on past α (model.md, "Past α"). A run of two
components is never stopped as falling (that rule reads θ, the tilt's projection on xz, and a
body leaning on a diagonal past the x edge's α may still stand), as MuJoCo's and PyBullet's;
its extras add the 3-D history the two-component measures read (`kinematics.pair_extras`).

Presets (PRESETS; measured in docs/drake.md with docs/scripts/drake_presets.py; worst
β error over the first 4 impacts from θ0 = 0.3–0.8α, fixed / μ = 1 isolated):
"continuous" (the default): continuous plant, Radau3 at accuracy 1e-4, k 1e10 N/m,
d 100 s/m: 0.05% / 0.08% (at 1e-3, the feasibility study's: 0.11% / 0.16% and θmax/α
+0.0071 against +0.0014 on the report's robust isolated sine, for 1.2–1.4× less time); "sap":
discrete SAP, dt 2e-4 s, relaxation time 5 ms (τ < 2 ms makes the block hop): 0.19% /
0.44%, the slowest; "tamsi": discrete TAMSI, dt 2e-4 s: 0.13% / 0.33%, the fastest
(deprecated by Drake); "hydroelastic": the block a compliant box (1e10 Pa) on a rigid
plate, discrete SAP: 12% / 22% high, as at every modulus tried (the pressure field at
impact), shown for comparison only.

The corner spheres shrink the rocking half width to b − r and the block rolls on them:
`sphere_geometry_beta` and `sphere_geometry_first_impact_time` are this geometry's own
closed forms, against which the engine's convergence is judged.
"""
from __future__ import annotations

import math
import tempfile
import time
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np
from scipy.integrate import quad

try:
    import pydrake.all as pd
except ImportError as exc:  # an optional extra; the registry and the report skip an engine that cannot import
    raise ImportError(f"the drake engine needs pydrake ({exc}): pip install 'isorock[drake]'") from exc

from ..analytic import hull_contact, kinematics
from ..analytic.errors import InputError, require, require_positive_finite
from ..analytic.motion import GroundMotion
from ..analytic.engine_protocol import check_friction, contact_friction, run_inputs
from ..analytic.isolator_parts import (PLANE_ISOLATORS, PUCK_HALF, check_contact_isolator, isolator_parts,
                                             pendulum_puck)
from ..analytic.status import Status
from ..analytic.system import LINEAR, System, paper_system
from ..analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, RawHistory, counted_sign_changes

from . import statue

ENGINE = "drake"
SCENE_FORMAT = ("SDFormat", ".sdf")

INTEGRATORS = ("radau3", "radau1", "implicit_euler", "runge_kutta3")
CONTACTS = ("point", "hydroelastic")
DISCRETE_SOLVERS = ("sap", "tamsi", "lagged")
#: a statue's own shape (System.body.solid): spheres on its hull's vertices, or Drake's Convex (drake_models.statue)
HULLS = ("vertices", "convex")

#: Radius (m) of the corner spheres, inscribed in the block's bottom corners (centre r
#: inside both faces): small against b (0.06% of 0.35 m), large enough that the sphere
#: rolls rather than digs in.
CORNER_RADIUS = 2e-4
#: Block depth (y half-size) as a fraction of b: a square footprint (inertia only).
DEPTH_FRACTION = 1.0
#: Base plate thickness (m); its top face is z = 0.
PLATE_THICKNESS = 0.1
#: Simulated seconds per Simulator.AdvanceTo call: the stop rules and the progress
#: callback run between calls (each call's loop is Drake's, in C++).
CHUNK = 0.25
#: Largest knot spacing (s) of the ground-force trajectory (linear between knots): a
#: record's own samples are knots, so a record is reproduced exactly; a pulse's
#: curvature error at this spacing is below 1e-5 of its amplitude.
FORCE_KNOT = 5e-4
#: A statue with friction (System.friction): the continuous plant's stiction tolerance v_s (its
#: regularised Stribeck friction reaches μ_s at slip speed v_s and μ_k at 3·v_s, and a stuck
#: contact creeps below v_s) in units of the block's R·p (Settings.stiction_tolerance follows
#: it), so that every size meets the same friction law. Drake's own 1e-4 m/s, fixed in m/s, is
#: 5e-5·R·p on a 1 m block and 1.6e-5·R·p on a 10 m one: stiffer than Radau3 at accuracy 1e-4
#: follows, it parted from the exact model on 6 of 16 random cases at 10 m (slides 0.15–1.3·b
#: off, docs/sliding_engines.md) and cost 2–10× the time; 3e-4·R·p brought four of them within
#: 0.006·b, 2–10× faster, and its creep, below v_s/p = 3e-4·R per 1/p of sticking, is far below
#: the 0.01·b a slide is read from (1e-4·R·p did as well on the cases). Without friction the
#: plant keeps Drake's default, as before.
STICTION_SHARE = 3e-4
_PAPER = paper_system()
#: Whether Drake carries a statue of two edges (its own shape, drake_models.statue): what
#: Capabilities.two_edges says, judged in docs/statues.md
TWO_EDGES = True
#: Whether Drake carries two horizontal components (GroundMotion.transverse) on a fixed base
#: and the linear isolator: what Capabilities.transverse says, judged in docs/statues.md ("Two
#: horizontal components", Drake) by tests/test_two_components_drake.py
TRANSVERSE = True
#: The isolators Drake carries (Capabilities.isolators), on one component and under a pair
#: (Capabilities.transverse_isolators, the same three): the linear one, and the friction pendulum and
#: the ball in a bowl, whose dry friction is a held puck's contact (_pendulum_puck). Not the bilinear
#: bearing, the ball in a cone or the double pendulum (refused in one line): a Jenkins element's
#: slider, or a restoring force none of the plant's parts is
ISOLATORS = PLANE_ISOLATORS
#: The continuous plant's stiction tolerance v_s (m/s) on a pendulum (its puck's friction), on the
#: paper's block (∝ R·p with follow_system): a stuck base creeps at v_s·F/(μ·W)
ISOLATOR_STICTION = 3e-5
#: The pendulum's floor (m): a box of the plate's thickness, its top face 2·PUCK_HALF below the
#: plate's bottom, this wide (a half-space warns of deformable contact at every run), wider than any
#: pendulum's travel
FLOOR_WIDTH = 200.0


@dataclass(frozen=True)
class Settings:
    """Drake's numerical settings for this scene (defaults: the "continuous" preset).

    timestep: 0 for a continuous plant integrated with error control (`integrator`
        at `accuracy`), or the step (s) of a discrete plant solved by
        `discrete_solver` (sap, tamsi or lagged).
    integrator: continuous plants only: radau3, radau1, implicit_euler or
        runge_kutta3. accuracy: the integrator's relative accuracy.
    contact: "point" (corner spheres, Hunt–Crossley) or "hydroelastic" (the block a
        compliant-hydroelastic box of `hydroelastic_modulus` Pa on a rigid plate).
    stiffness: point-contact stiffness (N/m) between sphere and plate (each
        geometry carries 2·stiffness; Drake combines them in series).
    dissipation: Hunt–Crossley dissipation (s/m). relaxation_time: SAP's and
        Lagged's linear dissipation time scale (s; each geometry carries half, Drake adds them).
    friction: block–plate Coulomb friction (static = dynamic), where the statue has none of its
        own (System.friction and kinetic_friction, Drake's static and dynamic coefficients).
    corner_radius: radius (m) of the corner spheres, below b/10.
    sample_interval: the history's sample spacing (s); a multiple of timestep on a
        discrete plant.
    stiction_tolerance: the continuous plant's stiction tolerance (m/s: below it a stuck contact
        creeps, Stribeck's regularisation) for a statue with friction (System.friction); without
        friction the plant keeps Drake's default, as always (STICTION_SHARE).
    isolator_stiction_tolerance: the continuous plant's stiction tolerance (m/s) on a friction
        pendulum or a ball in a bowl (its puck's friction; the block's contact meets it too): a
        stuck base creeps at v_s·F/(μ·W); ISOLATOR_STICTION, measured in docs/drake.md.
    hull: a statue's own shape only (System.body.solid; drake_models.statue): "vertices", a
        sphere of corner_radius on each vertex of its hull, or "convex", the hull as Drake's
        Convex in point contact (one point per pair: for comparison only).
    follow_system: True: `for_system` puts every contact quantity in the block's own
        units (the values above are those measured on the paper's block); an explicit
        contact setting given to `settings_for` (every command's path) sets it False.
    """

    timestep: float = 0.0
    integrator: str = "radau3"
    accuracy: float = 1e-4
    discrete_solver: str = "sap"
    contact: str = "point"
    stiffness: float = 1e10
    dissipation: float = 100.0
    relaxation_time: float = 5e-3
    hydroelastic_modulus: float = 1e10
    friction: float = 1.0
    corner_radius: float = CORNER_RADIUS
    sample_interval: float = 1e-3
    #: m/s on the paper's block (∝ R·p with follow_system): STICTION_SHARE·R·p
    stiction_tolerance: float = STICTION_SHARE * _PAPER.R * _PAPER.p
    #: m/s on the paper's block (∝ R·p with follow_system): a pendulum isolator's puck (ISOLATOR_STICTION)
    isolator_stiction_tolerance: float = ISOLATOR_STICTION
    hull: str = "vertices"
    follow_system: bool = True

    def for_system(self, system: System, duration: float | None = None) -> "Settings":
        """These settings for `system`: with follow_system, the contact in the block's own
        units, as measured on the paper's block (docs/drake.md, "Every size"): lengths ∝ R
        (the corner spheres), forces ∝ the block's weight (stiffness ∝ m·g/R, the
        hydroelastic modulus ∝ m·g/R²), velocities ∝ R·p (Hunt–Crossley's dissipation, s/m,
        ∝ 1/(R·p); the stiction tolerance ∝ R·p), times ∝ 1/p (a discrete step, SAP's
        relaxation time, the sample spacing, at most 0.01 s). The result is final (follow_system False); `duration`
        is not needed (a continuous plant ends on it)."""
        if not self.follow_system:
            return self
        ref = paper_system()
        length, weight, slow = system.R / ref.R, system.mass / ref.mass, ref.p / system.p
        step = min(self.timestep * slow, 0.01)
        sample = min(self.sample_interval * slow, 0.01)
        if step > 0:
            sample = step * max(1, math.floor(sample / step + 1e-9))
        return replace(self, stiffness=self.stiffness * weight / length, dissipation=self.dissipation * slow / length,
                       corner_radius=self.corner_radius * length, timestep=step, sample_interval=sample,
                       relaxation_time=self.relaxation_time * slow,
                       stiction_tolerance=self.stiction_tolerance * length / slow,
                       isolator_stiction_tolerance=self.isolator_stiction_tolerance * length / slow,
                       hydroelastic_modulus=self.hydroelastic_modulus * weight / length ** 2, follow_system=False)

    def __post_init__(self):
        try:
            dt = float(self.timestep)
        except (TypeError, ValueError):
            raise InputError(f"timestep = {self.timestep!r}: must be 0 (continuous) or a positive step") from None
        require(math.isfinite(dt) and 0 <= dt <= 0.01, "timestep", self.timestep,
                "0 (continuous) or a step in (0, 0.01] s")
        object.__setattr__(self, "timestep", dt)
        require(self.integrator in INTEGRATORS, "integrator", self.integrator, f"one of {', '.join(INTEGRATORS)}")
        require(self.discrete_solver in DISCRETE_SOLVERS, "discrete_solver", self.discrete_solver,
                f"one of {', '.join(DISCRETE_SOLVERS)}")
        require(self.contact in CONTACTS, "contact", self.contact, f"one of {', '.join(CONTACTS)}")
        require(self.hull in HULLS, "hull", self.hull, f"one of {', '.join(HULLS)}")
        acc = require_positive_finite("accuracy", self.accuracy)
        require(acc < 1, "accuracy", self.accuracy, "below 1 (a relative accuracy)")
        for name in ("stiffness", "dissipation", "relaxation_time", "hydroelastic_modulus", "friction",
                     "stiction_tolerance", "isolator_stiction_tolerance", "corner_radius"):
            object.__setattr__(self, name, require_positive_finite(name, getattr(self, name)))
        object.__setattr__(self, "accuracy", acc)
        si = require_positive_finite("sample_interval", self.sample_interval)
        require(si <= 0.01, "sample_interval", self.sample_interval, "at most 0.01 s")
        if dt > 0:
            ratio = si / dt
            require(ratio >= 1 - 1e-9 and abs(ratio - round(ratio)) < 1e-6, "sample_interval",
                    self.sample_interval, f"a whole multiple of timestep = {dt:g} s")
        object.__setattr__(self, "sample_interval", si)
        require(isinstance(self.follow_system, bool), "follow_system", self.follow_system, "true or false")

    @property
    def continuous(self) -> bool:
        return self.timestep == 0


#: Named families of settings (issue 12). Measured β error and speed: docs/drake.md.
PRESETS: dict[str, Settings] = {
    "continuous": Settings(),
    "sap": Settings(timestep=2e-4, discrete_solver="sap", relaxation_time=5e-3),
    "tamsi": Settings(timestep=2e-4, discrete_solver="tamsi"),
    "hydroelastic": Settings(timestep=2e-4, discrete_solver="sap", contact="hydroelastic"),
}


#: The history's sample spacing (s) when a timestep is given alone: the multiple of the
#: step nearest to this.
SAMPLE_INTERVAL = 1e-3


def settings_for(**overrides) -> Settings:
    """Settings with `overrides`; a positive timestep given without sample_interval
    takes the whole multiple of it nearest to SAMPLE_INTERVAL (a discrete plant is
    sampled on its steps)."""
    if {"timestep", "stiffness", "dissipation", "relaxation_time", "hydroelastic_modulus", "corner_radius",
            "sample_interval"} & set(overrides):
        overrides.setdefault("follow_system", False)  # what a user sets, the run uses
    dt = overrides.get("timestep")
    if dt and "sample_interval" not in overrides:
        dt = require_positive_finite("timestep", dt)
        overrides["sample_interval"] = dt * max(1, round(SAMPLE_INTERVAL / dt))
    return Settings(**overrides)


def settings_for_timestep(timestep: float, **overrides) -> Settings:
    """The discrete family at this step (what a work-precision ladder steps through):
    SAP with the "sap" preset's relaxation time, sampled near every SAMPLE_INTERVAL."""
    base = {f.name: getattr(PRESETS["sap"], f.name) for f in fields(Settings)}
    base.pop("sample_interval")
    return settings_for(**{**base, "timestep": timestep, **overrides})


def preset(name: str, **overrides) -> Settings:
    """The settings of preset `name` (PRESETS) with `overrides` applied."""
    require(name in PRESETS, "preset", name, f"one of {', '.join(PRESETS)}")
    known = {f.name for f in fields(Settings)}
    unknown = sorted(k for k in overrides if k not in known)
    if unknown:
        raise InputError(f"{', '.join(unknown)}: not a setting of engine 'drake' (its settings: {', '.join(sorted(known))})")
    return replace(PRESETS[name], **overrides)


# --- the contact geometry's own closed forms -------------------------------------------

def _check_radius(system: System, radius: float) -> float:
    r = require_positive_finite("corner_radius", radius)
    require(r < 0.1 * system.b, "corner_radius", radius, f"below b/10 = {0.1 * system.b:.6g} m")
    return r


def sphere_geometry_beta(system: System, radius: float = CORNER_RADIUS) -> float:
    """β of a fixed-base block standing on spheres of radius r inscribed in its bottom
    corners. The impulse acts at the new sphere's contact point, at (b − r) from the
    centroid's vertical and h below it (the sphere's bottom is the block's bottom face),
    and the block leaves it rolling about that point; conserving angular momentum about
    it gives β = (I + m(h² − b'²)) / (I + m(h² + b'²)), b' = b − r, with the block's own
    I = m(b² + h²)/3. r = 0 is Housner's 1 − 1.5 sin²α."""
    require(system.fixed_base, "system", "isolated base", "a fixed base (this closed form is Housner's)")
    r = _check_radius(system, radius)
    m, h, bp = system.mass, system.h, system.b - r
    inertia = system.inertia
    return (inertia + m * (h * h - bp * bp)) / (inertia + m * (h * h + bp * bp))


def sphere_geometry_first_impact_time(system: System, theta0: float, radius: float = CORNER_RADIUS) -> float:
    """Time (s) from rest at tilt θ0 (rad) to the first impact of a fixed-base block on
    corner spheres of radius r, rolling without slip: the sphere's centre stays r above
    the plate, so the centroid's height is r + (h − r)cosθ + (b − r)sinθ, and the block
    turns about the contact point, with inertia I + m|G − C|² (G − C changes with θ).
    Energy gives θ̇(θ); t₁ = ∫ dθ/|θ̇| with θ = θ0 − s² (as model.md's exact t₁).
    r → 0 gives model.md's exact box integral."""
    require(system.fixed_base, "system", "isolated base", "a fixed base (free rocking on a fixed plate)")
    r = _check_radius(system, radius)
    th0 = abs(theta0)
    require(0 < th0 < system.alpha, "theta0", theta0, f"non-zero and smaller than α = {system.alpha:.6g} rad")
    m, g, inertia = system.mass, system.gravity, system.inertia
    hp, bp = system.h - r, system.b - r

    def height(th):
        return hp * math.cos(th) + bp * math.sin(th)

    def inertia_about_contact(th):
        gx = -bp * math.cos(th) + hp * math.sin(th)
        gz = bp * math.sin(th) + hp * math.cos(th) + r
        return inertia + m * (gx * gx + gz * gz)

    slope = bp * math.cos(th0) - hp * math.sin(th0)  # d(height)/dθ at θ0, > 0 below the tipping angle

    def integrand(s):
        if s == 0:
            return 2 / math.sqrt(2 * m * g * slope / inertia_about_contact(th0))
        th = th0 - s * s
        # height(θ0) − height(θ) written with sines of half-differences, to keep digits near θ0
        x = s * s
        drop = 2 * math.sin(x / 2) * (bp * math.cos(th0 - x / 2) - hp * math.sin(th0 - x / 2))
        return 2 * s / math.sqrt(2 * m * g * drop / inertia_about_contact(th))

    value, _ = quad(integrand, 0.0, math.sqrt(th0), epsabs=1e-14, epsrel=1e-13, limit=200)
    return value


# --- the scene -----------------------------------------------------------------------

_SDF = """<?xml version="1.0"?>
<!-- isorock: {what} on {base_kind} base for Drake (pydrake Parser, SDFormat with drake: extensions).
     Written by isorock.drake_models.scene for H = {H:g} m, B = {B:g} m, m = {m:g} kg, m_b = {base_mass:g} kg{plate}.
     Plant settings that SDFormat cannot hold (simulate() applies them):
       {plant}
     Ground motion: apply -m*xg''(t) to the {body_x} and -m_b*xg''(t) to the isolator joint
     (MultibodyPlant applied generalized force).{pair} {coords}
     Settings: {settings} -->
<sdf version="1.9" xmlns:drake="http://drake.mit.edu">
  <model name="isorock">
    <!-- its x-y plane is the world's x-z plane: the plane the planar joint moves in -->
    <link name="ground">
      <pose>0 0 0 {rot} 0 0</pose>
    </link>
    <joint name="ground_weld" type="fixed"><parent>world</parent><child>ground</child></joint>
    <link name="base">
      <pose>0 0 {plate_z} 0 0 0</pose>
      <inertial><mass>{mb}</mass>
        <inertia><ixx>{bixx}</ixx><iyy>{biyy}</iyy><izz>{bizz}</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
      <collision name="plate">
        <geometry><box><size>{W} {W} {T}</size></box></geometry>
        <drake:proximity_properties>
{plate_props}
        </drake:proximity_properties>
      </collision>
      <visual name="plate"><geometry><box><size>{W} {W} {T}</size></box></geometry></visual>
    </link>
{base_joint}
{body}
  </model>
</sdf>
"""
#: the header's account of the block's coordinates (planar joint)
_PLANAR_COORDS = """The planar joint's coordinates are
     (x, y, theta) = (centroid world x, minus centroid world z, rotation about world +y):
     tilt the block by theta0 about its corner sphere to start free rocking."""
_BLOCK = """    <!-- the link frame is the ground's orientation at the centroid: link x = world x,
         link y = world -z (up is -y), link z = world y (the rocking axis) -->
    <link name="block">
      <pose>0 0 {h} {rot} 0 0</pose>
      <inertial><mass>{m}</mass>
        <inertia><ixx>{ixx}</ixx><iyy>{iyy}</iyy><izz>{izz}</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
{block_collisions}
      <visual name="block"><geometry><box><size>{B} {H} {D}</size></box></geometry></visual>
    </link>
    <drake:joint name="rocking" type="planar">
      <drake:parent>ground</drake:parent>
      <drake:child>block</drake:child>
      <drake:damping>0 0 0</drake:damping>
    </drake:joint>"""
#: the block of two horizontal components: a free body (no joint), which may leave the plane
_FREE_BLOCK = """    <!-- two horizontal components: the block on no joint (Drake's quaternion floating joint), free to
         leave the plane; the link frame is the world's axes at the centroid (x along the first
         component, y along the second, z up) -->
    <link name="block">
      <pose>0 0 {h!r} 0 0 0</pose>
      <inertial><mass>{m}</mass>
        <inertia><ixx>{ixx}</ixx><iyy>{iyy}</iyy><izz>{izz}</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
{block_collisions}
      <visual name="block"><geometry><box><size>{B} {D} {H}</size></box></geometry></visual>
    </link>"""
#: the header's account of the free block's coordinates (two components)
_FREE_COORDS = """The block (link "block") has no joint: Drake's quaternion floating
     joint, its position the centroid's. Tilt it by theta0 about world +y about its corner spheres
     to start free rocking."""
_PRISMATIC = """    <joint name="{name}" type="prismatic">
      <parent>{parent}</parent><child>{child}</child>
      <axis><xyz>{axis}</xyz>
        <limit><lower>-1e30</lower><upper>1e30</upper><effort>1e30</effort></limit>
        <dynamics><damping>{c!r}</damping><spring_stiffness>{k!r}</spring_stiffness><spring_reference>0</spring_reference></dynamics>
      </axis>
    </joint>"""
#: the isolator of one component: the base on a prismatic joint along x
_ISOLATOR = _PRISMATIC.replace("{name}", "isolator").replace("{parent}", "world").replace(
    "{child}", "base").replace("{axis}", "1 0 0")
#: two components (GroundMotion.transverse): the base on a y joint on a massless carriage on the x
#: joint, the same k and c on both (the linear isolator is isotropic). The carriage carries no
#: mass, so the x joint's inertia is the plate's m_b, as the y joint's is: u and u_y are the two
#: joints' positions, each driven by −m_b·(its component), as the one joint is
_CARRIAGE = """    <!-- two horizontal components: the base rides a y joint on a massless carriage on the x joint -->
    <link name="carriage">
      <inertial><mass>0</mass>
        <inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
    </link>
"""
_WELD = """    <joint name="base_weld" type="fixed"><parent>world</parent><child>base</child></joint>"""
_SPHERE_AT = """      <collision name="{name}">
        <pose>{x!r} {y!r} {z!r} 0 0 0</pose>
        <geometry><sphere><radius>{r!r}</radius></sphere></geometry>
        <drake:proximity_properties>
{props}
        </drake:proximity_properties>
      </collision>"""
#: a corner sphere of the planar block, in its rocking plane (link z = 0)
_SPHERE = _SPHERE_AT.replace("{z!r}", "0")
_BOX = """      <collision name="block">
        <geometry><box><size>{B!r} {H!r} {D!r}</size></box></geometry>
        <drake:proximity_properties>
{props}
        </drake:proximity_properties>
      </collision>"""


#: a pendulum's dry friction (the friction pendulum's, the ball in a bowl's), the same in every
#: direction: a light puck under the plate on its own vertical joint, held down by a constant force
#: on that joint so that a floor welded to the world pushes it up by W (_pendulum_puck)
_PUCK = """    <!-- the pendulum's dry friction, the same in every direction: to reproduce a run, apply {hold!r} N
         to puck_z (applied generalized force) at all times, so that the floor pushes the puck up by
         W = {load!r} N; its friction {mu!r} (both sides) makes the limit mu*W = {limit!r} N -->
    <link name="isolator_puck">
      <pose>0 0 {z!r} 0 0 0</pose>
      <inertial><mass>{m!r}</mass>
        <inertia><ixx>{i!r}</ixx><iyy>{i!r}</iyy><izz>{i!r}</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
      </inertial>
      <collision name="puck">
        <geometry><sphere><radius>{r!r}</radius></sphere></geometry>
        <drake:proximity_properties>
{props}
        </drake:proximity_properties>
      </collision>
    </link>
{joint}
    <link name="isolator_floor">
      <collision name="floor">
        <pose>0 0 {floor_c!r} 0 0 0</pose>
        <geometry><box><size>{floor_w!r} {floor_w!r} {t!r}</size></box></geometry>
        <drake:proximity_properties>
{props}
        </drake:proximity_properties>
      </collision>
    </link>
    <joint name="floor_weld" type="fixed"><parent>world</parent><child>isolator_floor</child></joint>
    <!-- the floor meets the puck alone -->
    <drake:collision_filter_group name="isolator_floor_group">
      <drake:member>isolator_floor</drake:member>
      <drake:ignored_collision_filter_group>scene_group</drake:ignored_collision_filter_group>
    </drake:collision_filter_group>
    <drake:collision_filter_group name="scene_group">
      <drake:member>base</drake:member>
      <drake:member>block</drake:member>
      <drake:ignored_collision_filter_group>isolator_floor_group</drake:ignored_collision_filter_group>
    </drake:collision_filter_group>"""


def _pendulum_puck(system: System, settings: Settings, puck) -> str:
    """A pendulum's dry friction F_b = μ·W, the same in every direction (as MuJoCo's
    mujoco_models/scene._pair_pendulum and PyBullet's bullet_models/scene._pendulum_puck; its numbers
    analytic.isolator_parts.pendulum_puck): MultibodyPlant has no joint dry friction, so it is a
    contact: a sphere of radius PUCK_HALF (the puck, its mass taken from the base's) on its own
    vertical prismatic joint `puck_z` under the plate, held down by `hold` on that joint (a constant
    row of the ground-force source, _Built) onto a floor welded to the world (a box FLOOR_WIDTH
    wide), friction coefficient F_b/W on both (Drake combines two equal μ to themselves), the point contact's
    stiffness and dissipation the block's. On one component and on a pair alike."""
    t = PLATE_THICKNESS
    mu = (puck.friction, puck.friction)
    joint = _PRISMATIC.format(name="puck_z", parent="base", child="isolator_puck", axis="0 0 1", k=0.0, c=0.0)
    return _PUCK.format(hold=puck.hold, load=puck.load, mu=puck.friction, limit=puck.friction * puck.load,
                        z=-t - PUCK_HALF, m=puck.mass, i=0.4 * puck.mass * PUCK_HALF ** 2, r=PUCK_HALF,
                        props=_props(settings, mu), joint=joint, floor_c=-1.5 * t - 2 * PUCK_HALF, t=t,
                        floor_w=FLOOR_WIDTH)


def frictions(system: System, settings: Settings) -> tuple[float, float]:
    """(static, dynamic) friction of the block–base contact: the statue's μ_s and μ_k
    (System.friction, kinetic_friction) when it has them, else Settings.friction for both."""
    mu_s = contact_friction(system, settings.friction)
    return mu_s, mu_s if system.friction is None else system.kinetic_friction


def _props(settings: Settings, friction: tuple[float, float], *, hydro: str | None = None) -> str:
    """Proximity properties of one geometry. Drake combines a pair's point stiffnesses
    in series and adds their relaxation times, so each side carries 2·k and τ/2; equal
    dissipations and frictions combine to themselves (`friction`: (static, dynamic), the same
    on both sides)."""
    lines = [f"<drake:point_contact_stiffness>{2 * settings.stiffness!r}</drake:point_contact_stiffness>",
             f"<drake:hunt_crossley_dissipation>{settings.dissipation!r}</drake:hunt_crossley_dissipation>",
             f"<drake:relaxation_time>{settings.relaxation_time / 2!r}</drake:relaxation_time>",
             f"<drake:mu_dynamic>{friction[1]!r}</drake:mu_dynamic>",
             f"<drake:mu_static>{friction[0]!r}</drake:mu_static>"]
    if hydro == "rigid":
        lines.append("<drake:rigid_hydroelastic/>")
    elif hydro == "compliant":
        lines += ["<drake:compliant_hydroelastic/>",
                  f"<drake:hydroelastic_modulus>{settings.hydroelastic_modulus!r}</drake:hydroelastic_modulus>"]
    return "\n".join("          " + x for x in lines)


def _plant_description(settings: Settings) -> str:
    if settings.continuous:
        return (f"continuous plant (timestep 0), integrator {settings.integrator}, accuracy {settings.accuracy:g}, "
                f"contact model {settings.contact}")
    return (f"discrete plant, timestep {settings.timestep:g} s, contact approximation "
            f"{settings.discrete_solver}, contact model {settings.contact}")


def scene_text(system: System, settings: Settings | None = None, *, transverse: bool = False) -> str:
    """The SDFormat text of this system with these settings (what `simulate` parses),
    block upright at rest. `transverse`: the scene of two horizontal components
    (GroundMotion.transverse): the block a free body on four bottom corner spheres (a statue
    is one already), on an isolated base the base on a second prismatic joint along y under
    a massless carriage (the same k and c); without it the one-component scene, unchanged."""
    settings = (settings or Settings()).for_system(system)
    b, h, d = system.b, system.h, DEPTH_FRACTION * system.b
    m, mb = system.mass, system.base_mass
    r = _check_radius(system, settings.corner_radius)
    # wide enough that even an overturned block lands on it, and a statue that may slide walks on it
    w = 2 * (b + system.height + kinematics.slide_room(system))
    t = PLATE_THICKNESS
    hydro = settings.contact == "hydroelastic"
    mu = frictions(system, settings)
    statue_shape = hull_contact.has_solid(system)
    free_block = transverse and not statue_shape
    if transverse:
        require(system.fixed_base or system.isolator_kind in ISOLATORS, "isolator", system.isolator_kind,
                f"{' or '.join(ISOLATORS)} or a fixed base with two horizontal components")
        require(not hydro, "contact", settings.contact, "point with two horizontal components (the corner spheres)")
    if statue_shape:  # its own shape in the block's place, on a free body (drake_models.statue)
        require(not hydro, "contact", settings.contact, "point for a statue's own shape (its hull's vertices)")
        w = 2 * hull_contact.plate_half_width(system)
        collisions = ""
    elif free_block:  # the four bottom corners, each sphere inscribed (centre r inside all three faces)
        collisions = "\n".join(
            _SPHERE_AT.format(name=f"corner_{'pn'[sx < 0]}{'pn'[sy < 0]}", x=sx * (b - r), y=sy * (d - r),
                              z=-(h - r), r=r, props=_props(settings, mu))
            for sx in (1.0, -1.0) for sy in (1.0, -1.0))
    elif hydro:
        collisions = _BOX.format(B=2 * b, H=2 * h, D=2 * d, props=_props(settings, mu, hydro="compliant"))
    else:  # the two bottom corners of the rocking plane, in link coordinates (up is −y)
        collisions = "\n".join(_SPHERE.format(name=name, x=sx * (b - r), y=h - r, r=r, props=_props(settings, mu))
                               for name, sx in (("corner_pos", 1.0), ("corner_neg", -1.0)))
    # the isolator's spring and dashpot (a pendulum's k = W/R and c: isolator_parts), and a pendulum's
    # dry friction as a held puck on a floor (_pendulum_puck; None on the linear isolator)
    parts = None if system.fixed_base or system.isolator_kind == LINEAR else isolator_parts(system)
    k, c = (system.stiffness, system.damping) if parts is None else (parts.stiffness, parts.damping)
    puck = pendulum_puck(system)
    if system.fixed_base:
        base_joint = _WELD
    elif transverse:
        base_joint = _CARRIAGE + "\n".join(
            _PRISMATIC.format(name=name, parent=parent, child=child, axis=axis, k=k, c=c)
            for name, parent, child, axis in (("isolator", "world", "carriage", "1 0 0"),
                                              ("isolator_y", "carriage", "base", "0 1 0")))
    else:
        base_joint = _ISOLATOR.format(k=k, c=c)
    if puck is not None:
        mb = mb - puck.mass  # the puck's mass is taken from the base's: the joints still move m_b
        base_joint += "\n" + _pendulum_puck(system, settings, puck)
    listed = ", ".join(f"{f.name} = {getattr(settings, f.name)!r}" for f in fields(settings))
    if statue_shape:
        body = statue.link(system, settings, _props(settings, mu))
    elif free_block:  # link axes the world's: I about x, y, z of the box 2b × 2d × 2h
        body = _FREE_BLOCK.format(h=h, m=m, B=system.width, D=2 * d, H=system.height, ixx=m * (d * d + h * h) / 3,
                                  iyy=m * (b * b + h * h) / 3, izz=m * (b * b + d * d) / 3, block_collisions=collisions)
    else:  # link axes: x = world x, y = world −z, z = world y (the rocking axis)
        body = _BLOCK.format(
            h=h, rot=repr(-math.pi / 2), m=m, B=system.width, H=system.height, D=2 * d,
            ixx=m * (h * h + d * d) / 3, iyy=m * (b * b + d * d) / 3, izz=m * (b * b + h * h) / 3,
            block_collisions=collisions)
    return _SDF.format(
        base_kind="a fixed" if system.fixed_base else f"an isolated (k = {k:.6g} N/m, c = {c:.6g} N s/m)"
        if puck is None else f"a {system.isolator_kind} (k = {k:.6g} N/m, c = {c:.6g} N s/m, its dry friction "
        f"a puck held down on a floor: {puck.friction:.6g} x W = {puck.load:.6g} N)",
        H=system.height, B=system.width, D=2 * d, m=m, mb=mb, h=h, rot=repr(-math.pi / 2),
        base_mass=system.base_mass,
        plate="" if puck is None else f" (the plate {mb:g} kg, the puck {puck.mass:g} kg)",
        plant=_plant_description(settings), settings=listed,
        plate_z=-t / 2, W=w, T=t, bixx=mb * (w * w + t * t) / 12, biyy=mb * (w * w + t * t) / 12,
        bizz=mb * w * w / 6, plate_props=_props(settings, mu, hydro="rigid" if hydro else None),
        base_joint=base_joint, body=body,
        what="a statue's own shape (its hull's vertices)" if statue_shape else "block",
        body_x="statue's free-body world x (the centre of mass)" if statue_shape else
        "block's free-body world x (the centroid)" if free_block else "block's planar x",
        pair="\n     Second horizontal component: apply -m*yg''(t) to the body's world y and -m_b*yg''(t) to\n"
        "     isolator_y (the base's y joint)." if transverse else "",
        coords=statue.COORDS if statue_shape else _FREE_COORDS if free_block else _PLANAR_COORDS)


class _Built:
    """A built diagram and where the scene's quantities sit in the plant's state."""

    def __init__(self, system: System, motion: GroundMotion, settings: Settings, duration: float):
        #: two horizontal components: the pair's scene (scene_text(transverse=True))
        self.transverse = motion.transverse is not None
        builder = pd.DiagramBuilder()
        plant, _ = pd.AddMultibodyPlantSceneGraph(builder, settings.timestep)
        if not settings.continuous:
            plant.set_discrete_contact_approximation({
                "sap": pd.DiscreteContactApproximation.kSap,
                "tamsi": pd.DiscreteContactApproximation.kTamsi,
                "lagged": pd.DiscreteContactApproximation.kLagged}[settings.discrete_solver])
        plant.set_contact_model(pd.ContactModel.kHydroelastic if settings.contact == "hydroelastic"
                                else pd.ContactModel.kPoint)
        text = scene_text(system, settings, transverse=self.transverse)
        if hull_contact.has_solid(system) and settings.hull == "convex":
            # the hull's OBJ beside the SDF, which names it by a relative path
            with tempfile.TemporaryDirectory(prefix="isorock-drake-") as folder:
                Path(folder, statue.HULL_FILE).write_text(statue.hull_obj(system))
                Path(folder, "scene.sdf").write_text(text)
                pd.Parser(plant).AddModels(str(Path(folder, "scene.sdf")))
        else:
            pd.Parser(plant).AddModelsFromString(text, "sdf")
        plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, -system.gravity])
        #: a pendulum's friction puck (_pendulum_puck), or None
        self.puck = pendulum_puck(system)
        if settings.continuous and self.puck is not None:
            plant.set_stiction_tolerance(settings.isolator_stiction_tolerance)
        elif system.friction is not None and settings.continuous:
            plant.set_stiction_tolerance(settings.stiction_tolerance)
        plant.Finalize()
        self.plant = plant
        self.nq, self.nv = plant.num_positions(), plant.num_velocities()
        # the free body's indices: a statue's own shape, or the block of a pair (None: the planar block)
        self.statue = statue.Indices(plant) if hull_contact.has_solid(system) or self.transverse else None
        if self.statue is None:
            rocking = plant.GetJointByName("rocking")
            self.xq, self.yq, self.thq = (rocking.position_start() + i for i in range(3))
            self.xv, self.yv, self.thv = (rocking.velocity_start() + i for i in range(3))
        else:
            self.xv = self.statue.xv
        if system.fixed_base:
            self.uq = self.uv = None
        else:
            iso = plant.GetJointByName("isolator")
            self.uq, self.uv = iso.position_start(), iso.velocity_start()
        self.uyq = self.uyv = None  # the base's y joint (two components on an isolated base)
        if self.transverse and not system.fixed_base:
            iso_y = plant.GetJointByName("isolator_y")
            self.uyq, self.uyv = iso_y.position_start(), iso_y.velocity_start()
        self.puckq = self.puckv = None
        if self.puck is not None:
            held = plant.GetJointByName("puck_z")
            self.puckq, self.puckv = held.position_start(), held.velocity_start()

        # ground motion as generalized forces, linear between knots
        knots = _force_knots(motion, duration)
        xg = np.asarray(motion(knots), dtype=float)
        forces = np.zeros((self.nv, knots.size))
        forces[self.xv] = -system.mass * xg
        if self.uv is not None:
            forces[self.uv] = -system.base_mass * xg
        if self.transverse:
            # ÿg as ẍg: −m·ÿg on the free body's world y (at its centre of mass: no torque), −m_b·ÿg
            # on the base's y joint (zero rows on a fixed base, as before)
            yg = np.asarray(motion.transverse_at(knots), dtype=float)
            forces[self.statue.yv] = -system.mass * yg
            if self.uyv is not None:
                forces[self.uyv] = -system.base_mass * yg
        if motion.vertical is not None:
            # −m·üv on the block's world z, and the planar joint's y is −z: +m·üv on y (the base
            # rides the ground vertically, welded or on its x joint); a free body's z is the world's
            vertical = system.mass * np.asarray(motion.vertical(knots), dtype=float)
            if self.statue is None:
                forces[self.yv] = vertical
            else:
                forces[self.statue.zv] = -vertical
        if self.puckv is not None:  # the puck held down, so that the floor pushes it up by W
            forces[self.puckv] = self.puck.hold
        source = builder.AddSystem(pd.TrajectorySource(pd.PiecewisePolynomial.FirstOrderHold(knots, forces)))
        builder.Connect(source.get_output_port(), plant.get_applied_generalized_force_input_port())
        self.logger = pd.LogVectorOutput(plant.get_state_output_port(), builder, settings.sample_interval)
        self.diagram = builder.Build()

    def tilt(self, data) -> tuple[np.ndarray, np.ndarray]:
        """(θ, θ̇) of logged state columns."""
        if self.statue is not None:
            return statue.tilt(self.statue, self.nq, data)
        return data[self.thq], data[self.nq + self.thv]


def _force_knots(motion: GroundMotion, duration: float) -> np.ndarray:
    """Knots of the ground-force trajectory up to `duration`: spaced at most FORCE_KNOT,
    a record's samples among them (it is linear between them), and the end of a motion
    (a pulse stops there, possibly with a jump); a vertical or a second horizontal
    component's knots too."""
    if motion.is_zero:
        return np.array([0.0, duration])
    step = FORCE_KNOT if motion.pulse is not None else motion.dt / math.ceil(motion.dt / FORCE_KNOT - 1e-9)
    n = int(math.ceil(duration / step - 1e-9))
    knots = np.arange(n + 1) * step
    end = motion.end_time
    if 0 < end < duration:  # ẍg is zero after the end: add its last value and the zero beside it
        knots = np.union1d(knots, [end, min(end + 1e-9, duration)])
    for other in (motion.vertical, motion.transverse):  # another component's samples and end too
        if other is not None:
            knots = np.union1d(knots, _force_knots(other, duration))
    return knots


def _tilted_centroid(system: System, settings: Settings, theta0: float) -> tuple[float, float]:
    """(x, z) of the block's centroid tilted by θ0 about the corner sphere it rests on, the
    sphere touching the plate: centroid = sphere centre + R(θ)·(−s(b − r), h − r), the centre
    at (s(b − r) + rθ0, r), where rolling from upright puts it."""
    s = 1.0 if theta0 >= 0 else -1.0
    r = settings.corner_radius if settings.contact == "point" else 0.0
    bp, hp = system.b - r, system.h - r
    c, sn = math.cos(theta0), math.sin(theta0)
    return s * bp + r * theta0 - s * bp * c + hp * sn, r + s * bp * sn + hp * c


def _initial_positions(built: _Built, system: System, settings: Settings, theta0: float) -> np.ndarray:
    """The planar block tilted by θ0 about its corner sphere (_tilted_centroid)."""
    q = np.zeros(built.nq)
    x, z = _tilted_centroid(system, settings, theta0)
    q[built.xq], q[built.yq], q[built.thq] = x, -z, theta0
    return q


def _free_block_positions(built: _Built, system: System, settings: Settings, theta0: float) -> np.ndarray:
    """The block of a pair (a free body, its frame the world's axes) tilted by θ0 about world +y
    about its two corner spheres on that side: the planar block's pose (_tilted_centroid)."""
    q = np.zeros(built.nq)
    ix = built.statue
    x, z = _tilted_centroid(system, settings, theta0)
    q[ix.quat] = (math.cos(theta0 / 2), 0.0, math.sin(theta0 / 2), 0.0)
    q[ix.xq], q[ix.yq], q[ix.zq] = x, 0.0, z
    return q


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0, progress=None) -> RawHistory:
    """Simulate the scene from t = 0 to `duration` (s; default: the motion's end + 5 s,
    or 10 s without motion) from rest, tilted by `theta0` (rad) about its corner.
    progress: optional callable(t, duration), called between AdvanceTo chunks about once
    a second."""
    settings = (settings or Settings()).for_system(system)
    motion, duration = run_inputs(system, motion, duration, theta0, DEFAULT_IMPACT_THRESHOLD, settings=settings,
                                  two_edges=TWO_EDGES, transverse=TRANSVERSE, isolators=ISOLATORS,
                                  transverse_isolators=ISOLATORS)
    check_system(system, settings)
    # two components: the 'falling' rule reads θ, the tilt's projection on xz, and a body leaning
    # on a diagonal past the x edge's α may still stand; it is planar, so it never stops a 3-D run
    # ('lying' holds), as in MuJoCo's and PyBullet's
    motion_end = math.inf if motion.transverse is not None else motion.end_time
    start = time.perf_counter()
    built = _Built(system, motion, settings, duration)
    simulator = pd.Simulator(built.diagram)
    if settings.continuous:
        pd.ApplySimulatorConfig(pd.SimulatorConfig(integration_scheme=settings.integrator,
                                                   accuracy=settings.accuracy, use_error_control=True,
                                                   max_step_size=settings.sample_interval,
                                                   publish_every_time_step=False), simulator)
    context = simulator.get_mutable_context()
    plant_context = built.plant.GetMyMutableContextFromRoot(context)
    if built.statue is None:
        q0 = _initial_positions(built, system, settings, theta0)
    elif hull_contact.has_solid(system):
        q0 = statue.initial_positions(built.plant, built.statue, built.nq, system, settings, theta0)
    else:
        q0 = _free_block_positions(built, system, settings, theta0)
    if built.puckq is not None:  # the puck pressed into the floor by W/k: at rest from the start
        q0[built.puckq] = -built.puck.load / settings.stiffness
    built.plant.SetPositions(plant_context, q0)
    built.plant.SetVelocities(plant_context, np.zeros(built.nv))

    status, message, stop_reason = Status.COMPLETED, "reached the end time", None
    checked = 0
    last = None  # where the history ends, when a stop rule ends it early
    throttle = kinematics.Throttle(progress, duration)
    heard = []  # what the progress callback raised inside an advance (a run budget), re-raised after it

    def monitor(ctx):
        # progress (and a run budget through it) at every integrator step, not only between
        # chunks: one stiff chunk can take minutes (Throttle keeps the calls to ~1 a second)
        try:
            throttle(ctx.get_time())
        except Exception as exc:  # noqa: BLE001 — ends the advance, raised again below
            heard.append(exc)
            return pd.EventStatus.ReachedTermination(None, "stopped by its progress callback")
        return pd.EventStatus.Succeeded()
    simulator.set_monitor(monitor)
    t = 0.0
    simulator.Initialize()
    while t < duration - 1e-12:
        t = min(t + CHUNK, duration)
        try:
            simulator.AdvanceTo(t)
        except RuntimeError as exc:  # Drake's integrator or solver gave up
            status, message = Status.FAILED, f"Drake stopped near t = {context.get_time():.6g} s: {exc}"
            break
        if heard:
            raise heard[0]
        log = built.logger.FindLog(context)
        new, new_t = log.data()[:, checked:], log.sample_times()[checked:]
        k, reason = kinematics.first_stop(new_t, *built.tilt(new),
                                          np.all(np.isfinite(new), axis=0), system=system,
                                          motion_end=motion_end)
        if reason == "non-finite":
            status = Status.FAILED
            message = (f"the state stopped being finite near t = {new_t[k]:.6g} s; "
                       "try a smaller accuracy or timestep")
        if reason is not None:
            stop_reason = None if reason == "non-finite" else reason
            last = checked + k + (reason != "non-finite")  # a stopping sample is kept, a non-finite one not
            break
        checked = log.data().shape[1]
        throttle(t)
    runtime = time.perf_counter() - start
    log = built.logger.FindLog(context)
    return _raw_history(built, system, motion, settings, log.sample_times()[:last], log.data()[:, :last], runtime,
                        status, message, stop_reason)


def check_system(system: System, settings: Settings) -> None:
    """What this scene refuses before any work (EngineSpec.check_system): a friction pendulum of
    velocity-dependent friction (check_contact_isolator), corner spheres too large for the block,
    and a statue whose kinetic friction is below its static one on a
    discrete plant, whose contact solvers (SAP, TAMSI, Lagged) use the dynamic coefficient alone.
    The continuous plant's regularised Stribeck friction carries both (measured:
    docs/sliding_engines.md)."""
    settings = settings.for_system(system)
    check_contact_isolator(system, ENGINE)
    hull_contact.check_shape(system, "Drake")
    _check_radius(system, settings.corner_radius)
    check_friction(system, settings.continuous, "Drake's discrete plant (timestep > 0)")


def _raw_history(built: _Built, system, motion, settings, times, data, runtime, status, message,
                 stop_reason) -> RawHistory:
    """The raw history from the logged states (one column per sample), up to the last
    finite sample, with the extras of this geometry, and the slide where the run needs it
    (kinematics.slide_history: the box's sharp corners, as for every engine; the corner
    sphere's rolling, r·θ, stays below 2e-4·b, as the spheres are ∝ R)."""
    if built.statue is not None:  # a free body: a statue's own shape, or the block of a pair
        return statue.raw_history(built, system, motion, settings, times, data, runtime, status, message,
                                  stop_reason, ENGINE)
    times = np.asarray(times, dtype=float)
    data = np.asarray(data, dtype=float)
    finite = np.all(np.isfinite(data), axis=0)
    keep = int(np.argmin(finite)) if not finite.all() else data.shape[1]
    times, data = times[:keep], data[:, :keep]
    q, v = data[:built.nq], data[built.nq:]
    theta, theta_dot = q[built.thq], v[built.thv]
    if built.uq is None:
        u = u_dot = np.zeros(times.size)
    else:
        u, u_dot = q[built.uq], v[built.uv]
    x_c, z_c = q[built.xq], -q[built.yq]
    s = np.where(theta >= 0, 1.0, -1.0)
    h = system.h
    if settings.contact == "point":
        r = settings.corner_radius
        bp, hp = system.b - r, h - r
        # the pivot sphere's centre, relative to rolling from its rest place on the plate
        centre_x = x_c + s * bp * np.cos(theta) - hp * np.sin(theta)
        slip = centre_x - u - s * bp - r * theta
        # the lowest sphere's bottom above the plate's top face
        lowest = np.minimum(z_c + bp * np.sin(theta) - hp * np.cos(theta),
                            z_c - bp * np.sin(theta) - hp * np.cos(theta)) - r
    else:  # the box itself: sharp corners, the shared kinematics
        slip = kinematics.pivot_slip(system, x_c, theta, u)
        lowest = kinematics.lift_off(system, z_c, theta)
    counted = counted_sign_changes(theta, system.alpha, DEFAULT_IMPACT_THRESHOLD)
    after = lowest[counted[0][0]:] if counted else lowest[:0]
    extras = {
        "lift_off_max_after_impact": float(np.max(after)) if after.size else 0.0,
        "penetration_max": float(max(0.0, -np.min(lowest))) if lowest.size else 0.0,
        # while |θ| ≤ α, as for every engine (analytic.kinematics.contact_extras)
        "pivot_slip_max": float(np.max(np.abs(slip[np.abs(theta) <= system.alpha]), initial=0.0)),
    }
    slide, slide_dot = kinematics.slide_history(system, motion, x_centroid=x_c, x_centroid_dot=v[built.xv],
                                                theta=theta, theta_dot=theta_dot, u=u, u_dot=u_dot)
    return RawHistory(engine=ENGINE, system=system, t=times, u=u, u_dot=u_dot, theta=theta, theta_dot=theta_dot,
                      status=status, message=message, runtime_s=runtime, extras=extras, stop_reason=stop_reason,
                      slide=slide, slide_dot=slide_dot)


__all__ = ["Settings", "PRESETS", "preset", "simulate", "check_system", "scene_text", "SCENE_FORMAT",
           "sphere_geometry_beta", "sphere_geometry_first_impact_time"]
