"""The amphora's round foot, measured (docs/statues.md, "The amphora's round foot, measured"):
why MuJoCo's hull of the example amphora parts from the exact planar model of its two edges.

The amphora (analytic.shape.example_statue, 2,600 kg/m³) stands on a round foot of radius
r_f = 5 cm, a 96-gon (trimesh's revolve). Four questions, each a table:

1. closed form: the planar model's α, R and I_O against the revolved profile by hand (h and I_c
   integrated slice by slice: a regular N-gon of circumradius r(z) has area (N/2)·r²·sin(2π/N)
   and second moment about a diameter A·r²·(1 + 2cos²(π/N))/12; the edge at r_f·cos(π/N)
   from the axis at an edge's middle, r_f at a vertex);
2. free rocking (no ground motion) from θ0 = 0.3·α on a fixed base, 3 s (12 impacts of the exact
   model): the engine's θ at 1 s, its worst β error against each impact's own edge (the closed
   form) and its largest wobble out of the plane, for scene variants built here from
   MuJoCo's own scene (mujoco_models.scene_text, run by mujoco_models.run_model, measured by the
   registry's measure): the hull on the free joint (the project's scene); the same hull on
   planar joints (slide x, slide z, hinge y: no motion out of the plane); the hull's
   footprint vertices as spheres of radius 0.2 mm (scene.CORNER_RADIUS) on the free joint, in
   place of the mesh-box pair, each sphere's bottom on its vertex (a contact set mirror-symmetric
   about the shaking plane); the foot with 384 and 1024 sections; the azimuth at a vertex of
   the 96-gon; the contact 4× stiffer (time constant, step and impedance width ÷ 4); the centre of mass 0.1 mm or 1 mm
   off the axis (an imperfection); the bust and the obelisk (straight edges) with the same
   imperfection; the box of the amphora's two edges (no mesh) on planar joints; with --drake,
   Drake's statue (a sphere at every hull vertex on a free body), as built and 0.1 mm off axis;
3. the pulse of docs/scripts/statue_engines.py (exact θmax/α 0.05, validate.tools.statue_check)
   at 0.5×, 1× and 3× on the three bases, for the hull on the free joint, on planar joints, and
   the footprint's spheres on the free joint at each --stiff factor (1 and 4: 75 s; 16 alone: 215 s).

    python docs/scripts/amphora.py [--parts closed,free,pulse] [--stiff 1,4] [--target 0.05] [--drake]
"""
from __future__ import annotations

import argparse
import math
import os
import time
import xml.etree.ElementTree as ET
from dataclasses import replace

import mujoco
import numpy as np

from isorock.analytic import shape
from isorock.analytic.motion import GroundMotion
from isorock.analytic.system import FrictionPendulum, PlanarBody, Solid, System
from isorock.analytic.trajectory import DEFAULT_IMPACT_THRESHOLD
from isorock.mujoco_models import Settings, run_model, scene_text
from isorock.mujoco_models.scene import CORNER_RADIUS, _fmt
from isorock.validate.core.engines import REFERENCE, get_engine
from isorock.validate.core.measure import beta_errors, measure
from isorock.validate.tools import statue_check as sc

#: the example amphora's profile (analytic.shape.example_statue("amphora")): (radius, z), m
PROFILE = shape.AMPHORA_PROFILE
FOOT_RADIUS = 0.05
QUIET = GroundMotion.from_array(np.zeros(11), dt=1e-3, units="m/s2", name="none")


def amphora(sections: int = 96, scale: float = 1.0, base: str = "fixed", where: str = "edge",
            off_axis: float = 0.0):
    """(resting body, System) of the amphora revolved with `sections`, shaken across the middle
    of an edge of its foot (`where` "edge", what weakest_direction picks) or through a vertex
    ("vertex"), on statue_check's `base`; `off_axis` (m): its centre of mass moved that far
    across the shaking plane (the hull's vertices moved by −off_axis in y; the planar model,
    which reads x and z only, is the same)."""
    v, f = shape._revolved(PROFILE, sections)
    body = shape.standing(v * scale, f, density=sc.DENSITY, name="amphora")
    body = body.along(math.pi / sections if where == "edge" else 0.0)
    return body, placed(System.of_body(PlanarBody.from_resting(body), mass=body.mass), body.mass, base, off_axis)


def placed(system: System, mass: float, base: str, off_axis: float = 0.0) -> System:
    """statue_check.example's bases, and the centre of mass off the axis."""
    system = replace(system, base_mass=mass)
    if base == "linear":
        system = system.on_isolator(2.0, 0.1)
    elif base == "friction-pendulum":
        system = replace(system.on_isolator(2.0, 0.1), isolator=FrictionPendulum(radius=1.5, friction_coefficient=0.05))
    if off_axis:
        solid = system.body.solid
        moved = Solid(vertices=tuple((x, y - off_axis, z) for x, y, z in solid.vertices), inertia=solid.inertia)
        system = replace(system, body=replace(system.body, solid=moved))
    return system


def settings_for(system: System, duration: float, joint: str, stiff: float) -> Settings:
    """MuJoCo's settings for the statue (the contact that follows it), `stiff` times stiffer
    (time constant, step and impedance width divided by it), on `joint`; stepped throughout."""
    s = Settings().for_system(system, duration)
    if stiff != 1:
        s = replace(s, timestep=s.timestep / stiff, solref=(s.solref[0] / stiff, s.solref[1]),
                    solimp=(*s.solimp[:2], s.solimp[2] / stiff, *s.solimp[3:]))
    return replace(s, joint=joint, phased=False)


def variant_xml(system: System, settings: Settings, contact: str) -> str:
    """MuJoCo's statue scene (the hull on the free joint), changed: planar joints (settings.joint)
    instead of the free joint; `contact` "spheres": a sphere in each footprint vertex instead of
    the hull-plate pair; the box of the two edges where the body has no solid."""
    root = ET.fromstring(scene_text(system, replace(settings, joint="free")))
    block = root.find(".//body[@name='block']")
    if settings.joint == "planar":
        block.remove(block.find("freejoint"))
        for k, (name, kind, axis) in enumerate((("block_x", "slide", "1 0 0"), ("block_z", "slide", "0 0 1"),
                                                 ("block_theta", "hinge", "0 1 0"))):
            block.insert(k, ET.Element("joint", name=name, type=kind, axis=axis))
    if system.body.solid is None:  # planar joints read I_y only: an isotropic tensor passes MuJoCo's check
        i = system.body.inertia
        block.find("inertial").set("diaginertia", _fmt(i, i, i))
    if contact == "spheres":
        contact_el = root.find("contact")
        pair = contact_el.find("pair")
        h, r = system.body.centre_height, CORNER_RADIUS
        feet = [v for v in system.body.solid.vertices if abs(v[2] + h) < 1e-9]
        for k, (x, y, z) in enumerate(feet):  # its bottom on the vertex (Drake's statue): the levers kept
            ET.SubElement(block, "geom", name=f"foot{k}", type="sphere", size=repr(r), mass="0",
                          pos=_fmt(x, y, z + r))
            p = ET.SubElement(contact_el, "pair", dict(pair.attrib))
            p.set("name", f"foot{k}")
            p.set("geom1", f"foot{k}")
        contact_el.remove(pair)
    return ET.tostring(root, encoding="unicode")


def run(system: System, motion: GroundMotion, duration: float, *, joint="free", contact="hull", stiff=1.0,
        theta0=0.0):
    """The variant's Trajectory, measured as the registry measures MuJoCo's."""
    settings = settings_for(system, duration, joint, stiff)
    model = mujoco.MjModel.from_xml_string(variant_xml(system, settings, contact))
    raw = run_model(model, system, motion, settings=settings, duration=duration, theta0=theta0)
    return measure(raw, motion, impact_threshold=DEFAULT_IMPACT_THRESHOLD)


def worst_beta(tr) -> float:
    errors = [abs(e) for e in beta_errors(tr) if math.isfinite(e)]
    return max(errors) if errors else math.nan


def oop(tr) -> str:
    x = tr.extras.get("out_of_plane_max", math.nan)
    return "—" if not math.isfinite(x) else f"{x:.0e}"


# --- 1. closed form ------------------------------------------------------------------------

def closed_form(sections: int, where: str) -> dict:
    """α, R, h, I_O of the revolved profile by hand (slices: exact Gauss-Legendre on each
    linear piece of r(z))."""
    area = 0.5 * sections * math.sin(2 * math.pi / sections)  # × r²
    second = area * (1 + 2 * math.cos(math.pi / sections) ** 2) / 12  # × r⁴, about a diameter
    xg, wg = np.polynomial.legendre.leggauss(4)
    vol = mz = mzz = ixx = 0.0
    for (r0, z0), (r1, z1) in zip(PROFILE, PROFILE[1:]):
        if z1 <= z0:
            continue
        z = 0.5 * (z0 + z1) + 0.5 * (z1 - z0) * xg
        r = r0 + (r1 - r0) * (z - z0) / (z1 - z0)
        w = 0.5 * (z1 - z0) * wg
        vol += np.sum(w * area * r ** 2)
        mz += np.sum(w * area * r ** 2 * z)
        mzz += np.sum(w * area * r ** 2 * z ** 2)
        ixx += np.sum(w * second * r ** 4)
    m = sc.DENSITY * vol
    h = mz / vol
    i_c = sc.DENSITY * (ixx + mzz - vol * h ** 2)  # about the horizontal axis through the centre of mass
    b = FOOT_RADIUS * (math.cos(math.pi / sections) if where == "edge" else 1.0)
    R = math.hypot(b, h)
    return dict(mass=m, h=h, b=b, alpha=math.atan2(b, h), R=R, I_O=i_c + m * R * R)


def part_closed() -> None:
    print("\n1. The planar model's edge against the closed form (forward edge; the backward is its mirror)")
    print("| sections | azimuth | α (closed form) | α (shape.tipping_edges) | R (m) | I_O (kg·m²) | worst relative difference |")
    print("|---:|---|---:|---:|---:|---:|---:|")
    for n in (96, 1024):
        for where in ("edge", "vertex"):
            v, f = shape._revolved(PROFILE, n)
            body = shape.standing(v, f, density=sc.DENSITY)
            edge = shape.tipping_edges(body, math.pi / n if where == "edge" else 0.0)["forward"]
            c = closed_form(n, where)
            worst = max(abs(edge[k] / c[k] - 1) for k in ("alpha", "R", "h", "b", "I_O"))
            print(f"| {n} | {where} | {c['alpha']:.6f} | {edge['alpha']:.6f} | {edge['R']:.5f} | {edge['I_O']:.4f} | "
                  f"{worst:.1e} |", flush=True)


# --- 2. free rocking -----------------------------------------------------------------------

def part_free(stiffs, drake: bool = False) -> None:
    print("\n2. Free rocking from θ0 = 0.3·α, fixed base, 1×, 3 s (exact model: 12 impacts)")
    print("| statue | scene | θ(1 s)/α engine / exact | worst β error | impacts exact / engine | out of plane (rad, m) |")
    print("|---|---|---:|---:|---|---:|")
    cases = [("amphora 96, edge", amphora(), "free", "hull", 1),
             ("amphora 96, edge", amphora(), "planar", "hull", 1),
             ("amphora 96, edge", amphora(), "free", "spheres", 1)]
    cases += [("amphora 96, edge", amphora(), "free", "spheres", s) for s in stiffs if s != 1]
    cases += [("amphora 96, edge", amphora(), "free", "hull", s) for s in stiffs if s != 1]
    cases += [("amphora 96, vertex", amphora(where="vertex"), "free", "hull", 1),
              ("amphora 384, edge", amphora(384), "free", "hull", 1),
              ("amphora 1024, edge", amphora(1024), "free", "hull", 1),
              ("amphora 1024, edge", amphora(1024), "free", "spheres", 1),
              ("amphora 96, c.o.m. 0.1 mm off axis", amphora(off_axis=1e-4), "free", "spheres", 1),
              ("amphora 96, c.o.m. 1 mm off axis", amphora(off_axis=1e-3), "free", "spheres", 1),
              ("amphora 96, c.o.m. 0.1 mm off axis", amphora(off_axis=1e-4), "free", "hull", 1)]
    body, system = amphora()
    cases.append(("amphora's two edges as a box (no mesh)", (body, replace(system, body=replace(system.body, solid=None))),
                  "planar", "box", 1))
    for name in ("bust", "obelisk"):
        b, s = sc.example(name, 1.0, "fixed")
        cases.append((f"{name}, c.o.m. 0.1 mm off axis", (b, placed(s, b.mass, "fixed", 1e-4)), "free", "hull", 1))
    scene = {("free", "hull"): "hull, free joint (the project's)", ("planar", "hull"): "hull, planar joints",
             ("free", "spheres"): "footprint spheres, free joint", ("planar", "box"): "box, planar joints"}
    reference = get_engine(REFERENCE).simulate
    if drake:  # Drake's statue: a sphere at every hull vertex (drake_models/statue.py), a free body
        cases += [("amphora 96, edge", amphora(), "drake", "spheres", 1),
                  ("amphora 96, c.o.m. 0.1 mm off axis", amphora(off_axis=1e-4), "drake", "spheres", 1)]
        scene["drake", "spheres"] = "Drake: a sphere at every hull vertex, free body"
    for label, (_, system), joint, contact, stiff in cases:
        a = system.alpha
        ex = reference(system, QUIET, duration=3.0, theta0=0.3 * a)
        if joint == "drake":
            tr = get_engine("drake").simulate(system, QUIET, duration=3.0, theta0=0.3 * a)
        else:
            tr = run(system, QUIET, 3.0, joint=joint, contact=contact, stiff=stiff, theta0=0.3 * a)
        at = lambda t: float(np.interp(1.0, t.t, t.theta)) / a  # noqa: E731
        print(f"| {label} | {scene[joint, contact]}{'' if stiff == 1 else f', {stiff:g}× stiffer'} | "
              f"{at(tr):+.4f} / {at(ex):+.4f} | {worst_beta(tr):.2%} | {ex.impact_count} / {tr.impact_count} | "
              f"{oop(tr)} |", flush=True)


# --- 3. the pulse ----------------------------------------------------------------------------

def part_pulse(stiffs, target: float = 0.05) -> None:
    print(f"\n3. The pulse of statue_engines.py (exact θmax/α {target:g}): θmax error (|Δ θmax/α|), worst β error, "
          "impacts exact / engine, out of plane")
    variants = [("hull, free", "free", "hull", 1), ("hull, planar", "planar", "hull", 1)]
    variants += [(f"spheres, free{'' if s == 1 else f' ×{s:g}'}", "free", "spheres", s) for s in stiffs]
    print("| size | base | spread under ±1% | " + " | ".join(v[0] for v in variants) + " |")
    print("|---:|---|---:|" + "---:|" * len(variants))
    for size in (0.5, 1.0, 3.0):
        for base in sc.BASES:
            _, system = amphora(scale=size, base=base)
            motion = sc.pulse(system, sc.amplitude_for(system, target))
            steady, spread = sc.robust(system, motion)
            duration = motion.end_time + sc.AFTER
            ex = sc.exact(system, motion)
            cells = []
            for _, joint, contact, stiff in variants:
                tr = run(system, motion, duration, joint=joint, contact=contact, stiff=stiff)
                rel = float(np.max(np.abs(tr.theta))) / float(np.max(np.abs(ex.theta))) - 1
                cells.append(f"{rel:+.0%} ({abs(tr.theta_max_over_alpha - ex.theta_max_over_alpha):.3f}), "
                             f"{worst_beta(tr):.1%}, {ex.impact_count}/{tr.impact_count}, {oop(tr)}"
                             + (", overturns" if tr.overturned else ""))
            print(f"| {size:g}× | {base} | {spread:.3f}{'' if steady else ' (chaotic)'} | " + " | ".join(cells) + " |",
                  flush=True)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--parts", default="closed,free,pulse")
    p.add_argument("--drake", action="store_true", help="part 2 with Drake's statue too (two runs, ~10 s each)")
    p.add_argument("--target", type=float, default=0.05, help="the pulse's exact θmax/α (statue_engines.py's: 0.05)")
    p.add_argument("--stiff", default="1,4", help="contact stiffness factors (1: the contact that follows the statue)")
    a = p.parse_args()
    stiffs = [float(x) for x in a.stiff.split(",")]
    start = time.perf_counter()
    print(f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores, MuJoCo {mujoco.__version__}")
    parts = a.parts.split(",")
    if "closed" in parts:
        part_closed()
    if "free" in parts:
        part_free(stiffs, a.drake)
    if "pulse" in parts:
        part_pulse(stiffs, a.target)
    print(f"\n{time.perf_counter() - start:.0f} s in all, load {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
