"""The block on its base as a MuJoCo model: `scene.xml` (the MJCF template, beside this
file) filled in for one System and Settings.

A box block on a box base plate, one explicit contact pair between them and no other
collision; the base slides on a joint with `stiffness = k`, `damping = c` (no joint on
a fixed base); the block moves on planar joints (slide x, slide z, hinge y) or, with
`Settings(joint="free")`, on a free joint. Why each choice: docs/mujoco.md.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco

from ..analytic import kinematics
from ..analytic.engine_protocol import contact_friction
from ..analytic.errors import require
from ..analytic.isolator_parts import PLANE_ISOLATORS, PUCK_HALF, isolator_parts, pendulum_puck
from ..analytic.system import LINEAR, System

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


def scene_text(system: System, settings: Settings | None = None, *, transverse: bool = False) -> str:
    """The MJCF of this system with these settings (what `simulate` compiles). `transverse`:
    the scene of two horizontal components (GroundMotion.transverse): the base on a second
    slide joint along y with the same stiffness and damping (the linear isolator is isotropic;
    a pendulum's friction made isotropic too, _pair_pendulum), the body on the free joint;
    without it the scene is the one-component scene, unchanged."""
    settings = settings or Settings()
    if transverse:
        require(settings.joint == "free", "joint", settings.joint,
                "free with two horizontal components (the body must be free to leave the plane)")
        require(system.fixed_base or system.isolator_kind in PLANE_ISOLATORS, "isolator", system.isolator_kind,
                f"{', '.join(PLANE_ISOLATORS)} or a fixed base with two horizontal components")
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

    # Base: its top face is z = 0 and it reaches past where an overturned block lands, and where
    # a statue that may slide can walk (kinematics.slide_room).
    named["base"].set("pos", _fmt(0, 0, -BASE_HALF_THICKNESS))
    named["base_geom"].set("size", _fmt(b + 2 * h + 0.1 + kinematics.slide_room(system), d + 0.1,
                                        BASE_HALF_THICKNESS))
    named["base"].find("inertial").set("mass", repr(mb))
    slide = named["base_slide"]
    if system.fixed_base:
        named["base"].remove(slide)  # a body without joints is welded to the ground
    elif system.isolator_kind == LINEAR:
        slide.set("stiffness", repr(system.stiffness))
        slide.set("damping", repr(system.damping))
        if transverse:  # the isotropic isolator's y: the same spring and dashpot, after x in qpos
            named["base"].insert(list(named["base"]).index(slide) + 1, ET.Element(
                "joint", name="base_slide_y", type="slide", axis="0 1 0", stiffness=repr(system.stiffness),
                damping=repr(system.damping)))
    elif transverse:
        _pair_pendulum(root, named, system, settings)
    else:
        _isolator_element(root, named, system, settings)

    # Block: a homogeneous box, centroid h above the base top; I_y = m(b² + h²)/3.
    block = named["block"]
    block.set("pos", _fmt(0, 0, h))
    named["block_geom"].set("size", _fmt(b, d, h))
    block.find("inertial").set("mass", repr(m))
    block.find("inertial").set("diaginertia", _fmt(m * (d**2 + h**2) / 3, m * (b**2 + h**2) / 3,
                                                    m * (b**2 + d**2) / 3))
    if system.body is not None:
        _statue(root, named, system.body, settings)
    if transverse:  # a body may fall along y as along x: the plate as wide as it is long
        sx, _, sz = (float(v) for v in named["base_geom"].get("size").split())
        named["base_geom"].set("size", _fmt(sx, sx, sz))
    if settings.joint == "free":
        for name in ("block_x", "block_z", "block_theta"):
            block.remove(named[name])
        free = ET.Element("freejoint", name="block_free")
        block.insert(0, free)

    pair = root.find("contact/pair")
    mu = contact_friction(system, settings.friction)  # the statue's, when it has one
    pair.set("friction", _fmt(mu, mu, 0.005, 0.0001, 0.0001))
    pair.set("solref", _fmt(*settings.solref))
    pair.set("solimp", _fmt(*settings.solimp))
    if settings.contact == "corners":
        body = system.body
        levers = (b, b) if body is None else (body.lever_forward, body.lever_backward)
        _corner_pairs(root, block, pair, levers, h, d, settings.joint == "free")
    sd = system.describe()
    root.insert(0, ET.Comment(
        " written by isorock.mujoco_models for H = {height:g} m, B = {width:g} m, m = {mass:g} kg, "
        "m_b = {base_mass:g} kg, {base}; to reproduce a run, tilt the block by θ0 about its corner "
        "and apply −m ẍg(t) to block_x and −m_b ẍg(t) to base_slide (qfrc_applied) ".format(
            base="fixed base" if system.fixed_base else
            f"k = {system.stiffness:.6g} N/m, c = {system.damping:.6g} N·s/m" if system.isolator_kind == LINEAR else
            _isolator_words(system), **sd)))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


#: Dry friction (MuJoCo's joint `frictionloss`) is a soft constraint: a stuck joint under a
#: load below its limit creeps at v = a0·(1 − d)/d·dmax·τ/2 (a0 the acceleration the load
#: would give, d = solimpfriction's dmin, τ solreffriction's time constant). At MuJoCo's
#: floor τ = 2·timestep and d = 0.9999 that is ~1e-8 m/s at a0 = 1 m/s², 0.5 ms: the stick
#: holds to microns over a record (MuJoCo's default, τ 0.02 s and d 0.9, creeps at ~1 mm/s).
#: Measured in docs/mujoco.md, "Non-linear isolators".
FRICTION_TIMECONST_STEPS = 2
FRICTION_SOLIMP = (0.9999, 0.9999, 0.001)
#: The bilinear bearing's slider is a body (a joint needs inertia): light, its own period
#: against the element spring k_e SLIDER_PERIOD_STEPS timesteps (MuJoCo steps a spring
#: explicitly: ω_s·dt = 0.13, far from the semi-implicit step's limit of 2), damped by the
#: tendon at SLIDER_DAMPING of critical so that it does not ring once it slips. Both cost
#: something: the dry friction's creep before a yield grows as ω_s² (frictionloss holds a
#: light body by the acceleration it would get: 20 steps crept 18 µm, yielding 62 ms early;
#: 50 steps 3 µm), and the tendon's dashpot 2·SLIDER_DAMPING·k_e/ω_s damps the elastic bearing
#: (at 0.5 of critical it doubled the dashpot of a stiff bearing, k0 3e6 N/m, c 1000 N·s/m:
#: its base history 1.9% off the analytic model's, 0.6% at 0.1). Measured in docs/isolators.md,
#: "The contact engines" (docs/scripts/isolator_engines.py).
SLIDER_PERIOD_STEPS = 50
SLIDER_DAMPING = 0.1


def _isolator_words(system) -> str:
    """The header's account of a non-linear isolator (what _isolator_element built)."""
    parts = isolator_parts(system)
    words = [f"{system.isolator_kind} isolator: base_slide stiffness {parts.stiffness:.6g} N/m, damping "
             f"{parts.damping:.6g} N·s/m"]
    if parts.base_friction > 0.0:
        words.append(f"frictionloss {parts.base_friction:.6g} N")
    if parts.has_element:
        words.append(f"in parallel with the tendon isolator_element (k_e {parts.element_stiffness:.6g} N/m) to "
                     f"the slider slider_slide (frictionloss {parts.slip_force:.6g} N)")
    return ", ".join(words)


def _isolator_element(root, named, system, settings):
    """A non-linear isolator from MuJoCo's own parts (docs/isolators.md; the parts derived
    once, analytic/isolator_parts.py): the base joint's stiffness and damping are the
    parallel spring k and dashpot c; a pendulum's rigid slider (the friction pendulum's, the
    ball in a bowl's, the double pendulum's μ_lo·W) is the base joint's own dry friction
    `frictionloss` (the model keeps the normal force at M·g, so a constant one is the same
    model); a Jenkins element (the bilinear bearing's, the double pendulum's of μ1 ≠ μ2) is a
    light slider body on its own slide joint with frictionloss F_s, tied to the base by a fixed
    tendon (base joint − slider joint) of stiffness k_e. The double pendulum has both."""
    parts = isolator_parts(system)
    slide = named["base_slide"]
    slide.set("stiffness", repr(parts.stiffness))
    slide.set("damping", repr(parts.damping))

    def friction(force):
        return dict(frictionloss=repr(force), solreffriction=_fmt(FRICTION_TIMECONST_STEPS * settings.timestep, 1.0),
                    solimpfriction=_fmt(*FRICTION_SOLIMP))
    if parts.base_friction > 0.0:  # a pendulum's rigid slider: the base itself sticks
        for key, value in friction(parts.base_friction).items():
            slide.set(key, value)
    if not parts.has_element:
        return
    k_e = parts.element_stiffness
    omega = 2 * math.pi / (SLIDER_PERIOD_STEPS * settings.timestep)
    mass = k_e / omega**2
    world = root.find("worldbody")
    slider = ET.SubElement(world, "body", name="isolator_slider", pos=_fmt(0, 0, -2 * BASE_HALF_THICKNESS))
    ET.SubElement(slider, "joint", name="slider_slide", type="slide", axis="1 0 0", **friction(parts.slip_force))
    ET.SubElement(slider, "inertial", pos="0 0 0", mass=repr(mass), diaginertia=_fmt(mass, mass, mass))
    tendon = root.find("tendon")
    if tendon is None:
        tendon = ET.SubElement(root, "tendon")
    fixed = ET.SubElement(tendon, "fixed", name="isolator_element", stiffness=repr(k_e),
                          damping=repr(2 * SLIDER_DAMPING * k_e / omega), springlength="0")
    ET.SubElement(fixed, "joint", joint="base_slide", coef="1")
    ET.SubElement(fixed, "joint", joint="slider_slide", coef="-1")


def _pair_pendulum(root, named, system, settings) -> None:
    """A pendulum isolator under two horizontal components (issue 36): its restoring spring
    k = W/R and dashpot along x and along y (base_slide, base_slide_y), and its dry friction
    μ·W in the plane, isotropic: |F| ≤ μ·W whichever way the base slides. A joint's
    `frictionloss` holds each axis apart (a square: √2·μ·W along a diagonal), so the friction is
    a contact instead: a light puck under the base (a child body on its own vertical slide
    joint `puck_z`, moving with the base in x and y) pressed by a held force onto a floor with
    friction coefficient F_b/W on MuJoCo's elliptic cone (Settings.cone), so that its normal
    force is the model's W = M·g (state.Layout.forces holds it) and the friction's limit F_b =
    μ·W in every direction (analytic.isolator_parts.pendulum_puck). Its time constants are the joint friction's (FRICTION_TIMECONST_STEPS,
    FRICTION_SOLIMP), so that it sticks as tightly."""
    require(settings.cone == "elliptic", "cone", settings.cone,
            "elliptic with two horizontal components on a pendulum isolator (a pyramid's friction is not isotropic)")
    parts = isolator_parts(system)
    base, slide = named["base"], named["base_slide"]
    slide.set("stiffness", repr(parts.stiffness))
    slide.set("damping", repr(parts.damping))
    base.insert(list(base).index(slide) + 1, ET.Element(
        "joint", name="base_slide_y", type="slide", axis="0 1 0", stiffness=repr(parts.stiffness),
        damping=repr(parts.damping)))
    held = pendulum_puck(system)
    if held is None:
        return
    base.find("inertial").set("mass", repr(system.base_mass - held.mass))
    puck = ET.SubElement(base, "body", name="isolator_puck", pos=_fmt(0, 0, -BASE_HALF_THICKNESS - PUCK_HALF))
    puck.append(ET.Comment(f" the pendulum's dry friction, the same in every direction: to reproduce a run, hold "
                           f"this puck down by applying {held.hold:.6g} N to puck_z "
                           f"(qfrc_applied) at every step, so that the floor pushes it up by W = {held.load:.6g} N "))
    ET.SubElement(puck, "joint", name="puck_z", type="slide", axis="0 0 1")
    ET.SubElement(puck, "inertial", pos="0 0 0", mass=repr(held.mass), diaginertia=_fmt(*(held.mass * PUCK_HALF**2,) * 3))
    ET.SubElement(puck, "geom", name="puck_geom", type="box", size=_fmt(PUCK_HALF, PUCK_HALF, PUCK_HALF),
                  rgba="0.3 0.3 0.35 1")
    floor_z = -2 * BASE_HALF_THICKNESS - 2 * PUCK_HALF
    ET.SubElement(root.find("worldbody"), "geom", name="isolator_floor", type="plane", size="0 0 1",
                  pos=_fmt(0, 0, floor_z), rgba="0.4 0.4 0.4 1")
    mu = held.friction
    tau = FRICTION_TIMECONST_STEPS * settings.timestep
    ET.SubElement(root.find("contact"), "pair", name="isolator_friction", geom1="puck_geom", geom2="isolator_floor",
                  condim="3", friction=_fmt(mu, mu, 0, 0, 0), solref=_fmt(tau, 1.0), solreffriction=_fmt(tau, 1.0),
                  solimp=_fmt(*FRICTION_SOLIMP))


def _statue(root, named, body, settings) -> None:
    """A statue of two edges (System.body) in the block's place, centre of mass h above the
    base top: with its own shape (body.solid), its convex hull as a mesh with its inertia
    tensor, on the free joint (Settings.for_system asks for it: a hull rocks, wobbles and
    twists in 3-D); without one, the box spanning its two edges (x from −b₋ to +b₊ about
    the centre of mass) with I_y = I_c, on the planar joints. Contact, as the block's, is the
    one pair between it and the base plate."""
    geom = named["block_geom"]
    inertial = named["block"].find("inertial")
    if body.solid is None:
        b_f, b_b, h = body.lever_forward, body.lever_backward, body.centre_height
        half = 0.5 * (b_f + b_b)
        geom.set("pos", _fmt(0.5 * (b_f - b_b), 0, 0))
        geom.set("size", _fmt(half, DEPTH_FRACTION * half, h))
        i_x, _, i_z = (float(v) for v in inertial.get("diaginertia").split())
        inertial.set("diaginertia", _fmt(i_x, body.inertia, i_z))  # only I_y acts on planar joints
        return
    require(settings.joint == "free", "joint", settings.joint, "free for a statue's own shape (its hull rocks in 3-D)")
    require(settings.contact == "box", "contact", settings.contact, "box for a statue's own shape (its hull is the geom)")
    vertices = body.solid.vertices
    asset = root.find("asset")
    if asset is None:
        asset = ET.Element("asset")
        root.insert(list(root).index(root.find("worldbody")), asset)
    ET.SubElement(asset, "mesh", name="statue_hull", vertex=" ".join(_fmt(*v) for v in vertices))
    for key in ("size", "pos"):
        geom.attrib.pop(key, None)
    geom.set("type", "mesh")
    geom.set("mesh", "statue_hull")
    I = body.solid.inertia
    inertial.attrib.pop("diaginertia", None)
    inertial.set("fullinertia", _fmt(I[0][0], I[1][1], I[2][2], I[0][1], I[0][2], I[1][2]))
    # the plate reaches past the hull across the shaking direction too
    base = named["base_geom"]
    sx, sy, sz = (float(v) for v in base.get("size").split())
    base.set("size", _fmt(sx, max(sy, max(abs(v[1]) for v in vertices) + 0.1), sz))


def _corner_pairs(root, block, pair, levers, h, d, free):
    """Replace the box–box pair by one pair per bottom corner: a sphere of radius
    CORNER_RADIUS inscribed in the corner against the base box (`levers`: the corners'
    distances b₊, b₋ from the centre of mass, b and b for the block). Planar joints need
    the two corners of the rocking plane (y = 0); the free joint all four."""
    r = CORNER_RADIUS
    contact = root.find("contact")
    contact.remove(pair)
    ys = (-(d - r), d - r) if free else (0.0,)
    for sx, xname, b in ((1, "pos", levers[0]), (-1, "neg", levers[1])):
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


def build_model(system: System, settings: Settings | None = None, *, transverse: bool = False) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(scene_text(system, settings or Settings(), transverse=transverse))


