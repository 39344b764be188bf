"""The block on its base as a MuJoCo model: `scene.xml` (the MJCF template, beside this
file) filled in for one System and Settings.

A box block on a box base plate, one explicit contact pair between them and no other
collision; the base slides on a joint with `stiffness = k`, `damping = c` (no joint on
a fixed base); the block moves on planar joints (slide x, slide z, hinge y) or, with
`Settings(joint="free")`, on a free joint. Why each choice: docs/mujoco.md.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco

from isorock.analytic.errors import require
from isorock.analytic.system import System

from .settings import Settings

TEMPLATE = Path(__file__).with_name("scene.xml")
SCENE_FORMAT = ("MJCF", ".xml")

#: Block depth (y half-size) as a fraction of its half width b: a square footprint.
#: Only the free joint can feel it (through the inertia about x and z).
DEPTH_FRACTION = 1.0
#: Base plate half thickness (m); the plate's top face is z = 0.
BASE_HALF_THICKNESS = 0.05
#: Radius (m) of the corner spheres of `Settings(contact="corners")`, inscribed in the
#: block's bottom corners (centre r inside both faces): the rocking half width
#: becomes b − r at θ = 0, a relative change r/b of 0.06% (B 0.7 m) to 0.1% (B 0.4 m)
#: (β moves by about 0.02%).
CORNER_RADIUS = 2e-4

# --- the scene -----------------------------------------------------------------------

def _fmt(*values) -> str:
    return " ".join(repr(float(v)) for v in values)


def scene_text(system: System, settings: Settings | None = None) -> str:
    """The MJCF of this system with these settings (what `simulate` compiles)."""
    settings = settings or Settings()
    # keep the template's comments: they explain the scene to whoever opens the file
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    root = ET.parse(TEMPLATE, parser=parser).getroot()
    named = {el.get("name"): el for el in root.iter() if el.get("name")}
    h, b, d = system.h, system.b, DEPTH_FRACTION * system.b
    m, mb = system.mass, system.base_mass
    check_representable(system)

    opt = root.find("option")
    opt.set("timestep", repr(settings.timestep))
    opt.set("integrator", settings.integrator)
    opt.set("cone", settings.cone)
    opt.set("solver", settings.solver)
    opt.set("gravity", _fmt(0, 0, -system.gravity))
    opt.set("noslip_iterations", str(settings.noslip))

    # Base: its top face is z = 0 and it reaches past where an overturned block lands.
    named["base"].set("pos", _fmt(0, 0, -BASE_HALF_THICKNESS))
    named["base_geom"].set("size", _fmt(b + 2 * h + 0.1, d + 0.1, BASE_HALF_THICKNESS))
    named["base"].find("inertial").set("mass", repr(mb))
    slide = named["base_slide"]
    if system.fixed_base:
        named["base"].remove(slide)  # a body without joints is welded to the ground
    else:
        slide.set("stiffness", repr(system.stiffness))
        slide.set("damping", repr(system.damping))

    # Block: a homogeneous box, centroid h above the base top; I_y = m(b² + h²)/3.
    block = named["block"]
    block.set("pos", _fmt(0, 0, h))
    named["block_geom"].set("size", _fmt(b, d, h))
    block.find("inertial").set("mass", repr(m))
    block.find("inertial").set("diaginertia", _fmt(m * (d**2 + h**2) / 3, m * (b**2 + h**2) / 3,
                                                    m * (b**2 + d**2) / 3))
    if settings.joint == "free":
        for name in ("block_x", "block_z", "block_theta"):
            block.remove(named[name])
        free = ET.Element("freejoint", name="block_free")
        block.insert(0, free)

    pair = root.find("contact/pair")
    mu = settings.friction
    pair.set("friction", _fmt(mu, mu, 0.005, 0.0001, 0.0001))
    pair.set("solref", _fmt(*settings.solref))
    pair.set("solimp", _fmt(*settings.solimp))
    if settings.contact == "corners":
        _corner_pairs(root, block, pair, b, h, d, settings.joint == "free")
    sd = system.describe()
    root.insert(0, ET.Comment(
        " written by isorock.mujoco_models for H = {height:g} m, B = {width:g} m, m = {mass:g} kg, "
        "m_b = {base_mass:g} kg, {base}; to reproduce a run, tilt the block by θ0 about its corner "
        "and apply −m ẍg(t) to block_x and −m_b ẍg(t) to base_slide (qfrc_applied) ".format(
            base="fixed base" if system.fixed_base else
            f"k = {system.stiffness:.6g} N/m, c = {system.damping:.6g} N·s/m", **sd)))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def _corner_pairs(root, block, pair, b, h, d, free):
    """Replace the box–box pair by one pair per bottom corner: a sphere of radius
    CORNER_RADIUS inscribed in the corner against the base box. Planar joints need
    the two corners of the rocking plane (y = 0); the free joint all four."""
    r = CORNER_RADIUS
    contact = root.find("contact")
    contact.remove(pair)
    ys = (-(d - r), d - r) if free else (0.0,)
    for sx, xname in ((1, "pos"), (-1, "neg")):
        for k, y in enumerate(ys):
            name = f"corner_{xname}" + (f"_{k}" if free else "")
            # no mass: the block's <inertial> is explicit, the box geom stays for display
            ET.SubElement(block, "geom", name=name, type="sphere", size=repr(r), mass="0",
                          pos=_fmt(sx * (b - r), y, -h + r), rgba="0.8 0.3 0.3 1")
            corner = ET.SubElement(contact, "pair", dict(pair.attrib))
            corner.set("name", name)
            corner.set("geom1", name)


def check_representable(system: System) -> None:
    """MuJoCo refuses a moving body whose mass or any principal inertia is below mjMINVAL
    (1e-15): its compiler raised a ValueError from deep inside a run (a 1e-30 kg statue).
    Such a system is bad input for this engine, named by its field."""
    h, b, d = system.h, system.b, DEPTH_FRACTION * system.b
    least = mujoco.mjMINVAL
    inertia = system.mass * min(d**2 + h**2, b**2 + h**2, b**2 + d**2) / 3
    require(system.mass > least and inertia > least, "mass", system.mass,
            f"heavier for MuJoCo: its mass and least inertia ({inertia:.3g} kg·m²) must exceed mjMINVAL = {least:g}")
    if not system.fixed_base:
        require(system.base_mass > least, "base_mass", system.base_mass,
                f"more than MuJoCo's mjMINVAL = {least:g} kg")


def build_model(system: System, settings: Settings | None = None) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(scene_text(system, settings or Settings()))


