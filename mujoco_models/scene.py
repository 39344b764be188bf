"""The block on its base as a MuJoCo scene: uplift, rocking and impact come from
contact, not from the analytic model's rules.

The scene (`scene.xml`, filled in by `scene_text`): a box block on a box base plate,
one explicit contact pair between them and no other collision; the base slides on a
joint with `stiffness = k`, `damping = c` (no joint on a fixed base); the block moves
on planar joints (slide x, slide z, hinge y) or, with `Settings(joint="free")`, on a
free joint. The ground motion is applied exactly as generalized forces in the
(translating) ground frame: −m ẍg(t) on the block's x dof and −m_b ẍg(t) on the
base's, with ẍg sampled at the step times; `mujoco.rollout` runs the stepping loop
in C.

Outputs follow model.md's conventions: u (m) is the base displacement relative to the
ground, θ (rad) is the hinge angle about +y (θ > 0 rocks about corner O at x = +b,
the centroid moving towards +x). Impacts and effective β are measured by
`validate.measure.contact_trajectory`, the same way for every engine. Extras:
`lift_off` (m, per stored point: every step), the height of the block's lowest corner above the
base's top face (negative: penetration); `lift_off_max_after_impact` (m), its largest
value after the first counted impact (a hop shows here); `penetration_max` (m); with
the free joint `out_of_plane_max` (m and rad, the largest of |y|, and the tilts about
x and z).

A run stops when |θ| reaches α (the block overturns; the history ends there, as the
analytic model's does) or when the state stops being finite (status "failed";
MuJoCo's auto-reset is off so a blow-up cannot pass silently).

Defaults, chosen by measurement (docs/mujoco.md): dt 5e-4 s, implicitfast, elliptic
cone, solref (0.002, 2), solimp (0.9, 0.999, 0.001), friction 1: effective β within
0.66% of the closed form on each of the first 4 impacts of free rocking (λ 2.857 and 5,
fixed and μ = 1, θ0 = 0.3–0.8 α), no hop after impacts. dmin 0.9 rather than 0.99:
at 0.99 the pivot's contact drops out for single steps while rocking and comes back
with a kick, which makes β jump by up to 2.5%. Of the features the scene does not
use, only island discovery costs anything (disabled: +10% speed, identical
histories); the others are skipped by MuJoCo already when absent.

`settings_for_timestep(dt)` (the bench ladder) ties solref = (4·dt, 2) below 1e-3 and
uses MuJoCo's direct form (−0.05/dt², −0.6/dt), solimp (0.9, 0.9, 0.001), from 1e-3
up: at 2e-3 β rms 0.88% against 2.3% for the tie. A step costs 3.3–3.9 µs whatever
the contact parameters (half of it the contact), so ~1000 simulated s per CPU s
needs dt ≈ 4e-3, where β errors are several percent: the landing corner sinks up to
v·dt in the step it lands, and pushing it out does work comparable to 1–2% of the
rocking energy. `Settings(contact="corners")` (a sphere in each bottom corner)
steps 15% faster but is less accurate by as much: not the default.
`event_resolved_settings()` (Settings.impact_timestep) takes coarse 3e-3 s steps and
fine 2.5e-4 s steps around impacts: β 0.47% at θ0 = α/2, 4× faster on a 40 s record,
but θmax/α 0.035 low and a softer rest: opt-in.
"""
from __future__ import annotations

import math
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
from mujoco import rollout

from isorock.analytic.errors import InputError, require, require_positive_finite
from isorock.analytic.motion import GroundMotion
from isorock.analytic.protocol import run_inputs
from isorock.analytic.status import Status
from isorock.analytic.system import System
from isorock.analytic.trajectory import DEFAULT_IMPACT_THRESHOLD, Trajectory, counted_sign_changes
from isorock.validate.measure import CONTACT_WINDOW, contact_trajectory

TEMPLATE = Path(__file__).with_name("scene.xml")
SCENE_SUFFIX = ".xml"
ENGINE = "mujoco"

INTEGRATORS = ("Euler", "implicit", "implicitfast", "RK4")
CONES = ("pyramidal", "elliptic")
JOINTS = ("planar", "free")
CONTACTS = ("box", "corners")

#: Steps per call of mujoco.rollout: the progress callback and the overturning /
#: blow-up checks run between calls. The warm start is carried across calls, so the
#: split does not change the result (tested).
CHUNK_STEPS = 20_000
#: Wall seconds between calls of the progress callback.
PROGRESS_INTERVAL = 1.0

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


@dataclass(frozen=True)
class Settings:
    """MuJoCo's numerical settings for this scene.

    timestep: s. integrator: one of Euler, implicit, implicitfast, RK4. cone:
    pyramidal or elliptic friction cone. solref: contact (timeconst s, dampratio),
    both positive, with timeconst ≥ 2·timestep (MuJoCo would silently raise it), or
    MuJoCo's direct form (−stiffness, −damping). solimp: (dmin, dmax, width[, mid,
    power]). friction: block–base sliding friction coefficient. noslip: noslip
    solver iterations (0: off). impact_timestep: None (one timestep throughout), or a
    divisor of `timestep` (s) used from just before each impact until IMPACT_SETTLE
    after it ("event-resolved" stepping, docs/mujoco.md; needs the direct solref form:
    the fine model keeps the stiffness and scales the damping by timestep /
    impact_timestep). joint: "planar" (slide x, slide z, hinge y) or
    "free". contact: "box" (box–box, the default) or "corners" (a small sphere in
    each bottom corner of the block against the base box, CORNER_RADIUS: cheaper
    collision, no better per unit of cost, docs/mujoco.md). contact_window: s, how far outside a θ sign change the states mapped to
    θ = 0 are taken (validate.measure; several contact time constants).
    """

    timestep: float = 5e-4
    integrator: str = "implicitfast"
    cone: str = "elliptic"
    solref: tuple = (0.002, 2.0)
    solimp: tuple = (0.9, 0.999, 0.001)
    friction: float = 1.0
    noslip: int = 0
    joint: str = "planar"
    contact_window: float = CONTACT_WINDOW
    contact: str = "box"
    impact_timestep: float | None = None

    def __post_init__(self):
        dt = require_positive_finite("timestep", self.timestep)
        require(dt <= 0.01, "timestep", self.timestep, "at most 0.01 s (rocking needs far finer steps)")
        require(self.integrator in INTEGRATORS, "integrator", self.integrator, f"one of {', '.join(INTEGRATORS)}")
        require(self.cone in CONES, "cone", self.cone, f"one of {', '.join(CONES)}")
        require(self.joint in JOINTS, "joint", self.joint, f"one of {', '.join(JOINTS)}")
        require(self.contact in CONTACTS, "contact", self.contact, f"one of {', '.join(CONTACTS)}")
        if self.impact_timestep is not None:
            fine = require_positive_finite("impact_timestep", self.impact_timestep)
            ratio = dt / fine
            require(fine < dt and abs(ratio - round(ratio)) < 1e-6, "impact_timestep", self.impact_timestep,
                    f"the timestep {dt:g} s divided by a whole number of at least 2")
            require(all(x < 0 for x in _float_tuple("solref", self.solref, 2, 2)), "solref", self.solref,
                    "the direct form (−stiffness, −damping) with impact_timestep (both models share the stiffness)")
            object.__setattr__(self, "impact_timestep", fine)
        solref = _float_tuple("solref", self.solref, 2, 2)
        positive = all(x > 0 for x in solref)
        require(positive or all(x < 0 for x in solref), "solref", self.solref,
                "(timeconst, dampratio) both positive, or (−stiffness, −damping) both negative")
        require(not positive or solref[0] >= 2 * dt * (1 - 1e-9), "solref", self.solref,
                f"a timeconst of at least 2·timestep = {2 * dt:g} s (MuJoCo raises a shorter one to that)")
        solimp = _float_tuple("solimp", self.solimp, 3, 5)
        require(0 < solimp[0] < 1 and 0 < solimp[1] < 1, "solimp", self.solimp,
                "(dmin, dmax, width[, mid, power]) with dmin and dmax in (0, 1)")
        require(solimp[2] > 0, "solimp", self.solimp, "a positive width (third value)")
        if len(solimp) > 3:
            require(0 < solimp[3] < 1, "solimp", self.solimp, "a midpoint (fourth value) in (0, 1)")
        if len(solimp) > 4:
            require(solimp[4] >= 1, "solimp", self.solimp, "a power (fifth value) of at least 1")
        object.__setattr__(self, "timestep", dt)
        object.__setattr__(self, "solref", solref)
        object.__setattr__(self, "solimp", solimp)
        object.__setattr__(self, "friction", require_positive_finite("friction", self.friction))
        require(isinstance(self.noslip, (int, np.integer)) and not isinstance(self.noslip, bool)
                and self.noslip >= 0, "noslip", self.noslip, "a non-negative whole number of iterations")
        object.__setattr__(self, "noslip", int(self.noslip))
        object.__setattr__(self, "contact_window", require_positive_finite("contact_window", self.contact_window))


#: The default contact time constant in steps: solref = (SOLREF_STEPS · timestep, 2).
SOLREF_STEPS = 4
#: Event-resolved stepping (Settings.impact_timestep): fine steps start when the block
#: would reach θ = 0 within IMPACT_ZONE coarse steps at its present θ̇ (and |θ̇| is above
#: IMPACT_MIN_RATE, rad/s: a block at rest stays on coarse steps) and end IMPACT_SETTLE
#: seconds after the last sign change of θ. A coarse rollout call runs about as far as
#: the next θ = 0 while rocking (|θ/θ̇|, at least 4 steps), COARSE_CHUNK·8 steps at
#: most (at rest); steps past the start of a fine zone are recomputed.
IMPACT_ZONE = 2.0
IMPACT_MIN_RATE = 1e-3
IMPACT_SETTLE = 0.01
COARSE_CHUNK = 64

#: From this timestep up, `settings_for_timestep` uses MuJoCo's direct contact
#: parameters: solref = (−DIRECT_STIFFNESS / dt², −DIRECT_DAMPING / dt) (stiffness and
#: damping of the reference acceleration, mass-normalised) with solimp DIRECT_SOLIMP.
#: A time constant of 4 steps makes the impact last 16 ms or more at dt ≥ 2e-3, about
#: half the measuring window, and β errors reach 8%; the direct form is not bound to
#: timeconst ≥ 2·dt and measured rms 0.88% against 2.3% at 2e-3, 0.54% against 0.57%
#: at 1e-3, and worse than the default at 5e-4 (docs/mujoco.md).
DIRECT_FROM = 1e-3
DIRECT_STIFFNESS = 0.05
DIRECT_DAMPING = 0.6
DIRECT_SOLIMP = (0.9, 0.9, 0.001)


def settings_for(**overrides) -> Settings:
    """Settings with `overrides`; a timestep given without solref and solimp takes the
    contact parameters measured for it (settings_for_timestep), since the default
    contact time constant is only right for the default step."""
    if "timestep" in overrides and not {"solref", "solimp"} & set(overrides):
        return settings_for_timestep(overrides.pop("timestep"), **overrides)
    return Settings(**overrides)


def settings_for_timestep(timestep: float, **overrides) -> Settings:
    """The contact parameters measured best at this timestep (what `isorock bench`
    ladders): below DIRECT_FROM the defaults with the contact time constant kept at
    SOLREF_STEPS steps (the default is this at 5e-4 s); from DIRECT_FROM up the
    direct form, stiffness DIRECT_STIFFNESS/dt² and damping DIRECT_DAMPING/dt."""
    dt = require_positive_finite("timestep", timestep)
    if dt >= DIRECT_FROM * (1 - 1e-9):
        base = dict(timestep=dt, solref=(-DIRECT_STIFFNESS / dt**2, -DIRECT_DAMPING / dt), solimp=DIRECT_SOLIMP)
    else:
        base = dict(timestep=dt, solref=(SOLREF_STEPS * dt, Settings.solref[1]))
    return Settings(**{**base, **overrides})


#: Event-resolved stepping as measured (docs/mujoco.md): coarse contact stiffness
#: EVENT_STIFFNESS/dt² (static pivot sink ≈ 0.02 mm at dt 3e-3), damping 0.6/dt.
EVENT_STIFFNESS = 0.5


def event_resolved_settings(timestep: float = 3e-3, impact_timestep: float = 2.5e-4, **overrides) -> Settings:
    """Coarse steps of `timestep` with fine steps of `impact_timestep` around impacts
    (Settings.impact_timestep), direct contact parameters tied to the coarse step.
    Measured at the defaults of this function: β within 0.47% of the closed form at
    θ0 = α/2 (1.3% worst over θ0 = 0.3–0.7α), Kobe 40 s 4× faster than the defaults but
    θmax/α 0.035 low (the defaults: 0.007)."""
    dt = require_positive_finite("timestep", timestep)
    base = dict(timestep=dt, impact_timestep=impact_timestep, solref=(-EVENT_STIFFNESS / dt**2, -DIRECT_DAMPING / dt),
                solimp=DIRECT_SOLIMP)
    return Settings(**{**base, **overrides})


def _float_tuple(name, value, n_min, n_max) -> tuple:
    try:
        out = tuple(float(x) for x in value)
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r}: must be {n_min}–{n_max} numbers") from None
    require(n_min <= len(out) <= n_max and all(math.isfinite(x) for x in out), name, value,
            f"{n_min} finite numbers" if n_min == n_max else f"{n_min}–{n_max} finite numbers")
    return out


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

    opt = root.find("option")
    opt.set("timestep", repr(settings.timestep))
    opt.set("integrator", settings.integrator)
    opt.set("cone", settings.cone)
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
        " written by mujoco_models.scene for H = {height:g} m, B = {width:g} m, m = {mass:g} kg, "
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


def build_model(system: System, settings: Settings | None = None) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(scene_text(system, settings or Settings()))


# --- simulation ----------------------------------------------------------------------

class _Layout:
    """Where the scene's quantities sit in qpos / qvel and in rollout's state rows."""

    def __init__(self, model: mujoco.MjModel, system: System, joint: str):
        self.nq, self.nv = model.nq, model.nv
        self.nstate = mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS)
        self.free = joint == "free"
        self.base_v = None if system.fixed_base else model.jnt_dofadr[model.joint("base_slide").id]
        self.base_q = None if system.fixed_base else model.jnt_qposadr[model.joint("base_slide").id]
        if self.free:
            jid = model.joint("block_free").id
            self.bq, self.bv = model.jnt_qposadr[jid], model.jnt_dofadr[jid]
            self.x_v = self.bv  # free joint: linear velocity first, in the world frame
        else:
            self.xq, self.zq, self.thq = (model.jnt_qposadr[model.joint(n).id]
                                           for n in ("block_x", "block_z", "block_theta"))
            self.x_v, self.thv = (model.jnt_dofadr[model.joint(n).id] for n in ("block_x", "block_theta"))


def _initial_qpos(model, lay: _Layout, system: System, theta0: float) -> np.ndarray:
    """Tilted by θ0 about the corner it rocks on (x_c = s b + h sinθ − s b cosθ,
    z_c = h cosθ + s b sinθ relative to that corner's rest position), corner on the base."""
    qpos = model.qpos0.copy()
    s = 1.0 if theta0 >= 0 else -1.0
    h, b = system.h, system.b
    dx = s * b + h * math.sin(theta0) - s * b * math.cos(theta0)
    dz = h * math.cos(theta0) + s * b * math.sin(theta0) - h
    if lay.free:
        qpos[lay.bq:lay.bq + 3] = (dx, 0.0, h + dz)
        qpos[lay.bq + 3:lay.bq + 7] = (math.cos(theta0 / 2), 0.0, math.sin(theta0 / 2), 0.0)
    else:
        qpos[lay.xq], qpos[lay.zq], qpos[lay.thq] = dx, dz, theta0
    return qpos


def _histories(lay: _Layout, system: System, states: np.ndarray) -> dict:
    """t, u, u̇, θ, θ̇ and the block's lowest-corner height from rollout state rows."""
    t = states[:, 0]
    qpos = states[:, 1:1 + lay.nq]
    qvel = states[:, 1 + lay.nq:1 + lay.nq + lay.nv]
    n = t.size
    if lay.base_q is None:
        u, u_dot = np.zeros(n), np.zeros(n)
    else:
        u, u_dot = qpos[:, lay.base_q].copy(), qvel[:, lay.base_v].copy()
    out = {"t": t.copy(), "u": u, "u_dot": u_dot}
    if lay.free:
        q = qpos[:, lay.bq + 3:lay.bq + 7]
        w, x, y, z = q.T
        # body z axis in the world is (sinθ, ·, cosθ) for a rotation about y
        r02 = 2 * (x * z + w * y)
        r22 = 1 - 2 * (x * x + y * y)
        out["theta"] = np.arctan2(r02, r22)
        out["theta_dot"] = qvel[:, lay.bv + 4].copy()  # angular velocity about the body y axis
        zc = qpos[:, lay.bq + 2]
        # out-of-plane motion: |y|, and the tilts about x and z (small-angle, rad)
        r12 = 2 * (y * z - w * x)
        r10 = 2 * (x * y + w * z)
        out["out_of_plane"] = np.maximum.reduce([np.abs(qpos[:, lay.bq + 1]), np.abs(r12), np.abs(r10)])
    else:
        out["theta"] = qpos[:, lay.thq].copy()
        out["theta_dot"] = qvel[:, lay.thv].copy()
        zc = system.h + qpos[:, lay.zq]
    th = out["theta"]
    out["lift_off"] = zc - system.h * np.cos(th) - system.b * np.abs(np.sin(th))
    return out


def simulate(system: System, motion: GroundMotion | None = None, *, settings: Settings | None = None,
             duration: float | None = None, theta0: float = 0.0,
             impact_threshold: float = DEFAULT_IMPACT_THRESHOLD, progress=None) -> Trajectory:
    """Simulate the scene from t = 0 to `duration` (s; default: the motion's end + 5 s,
    or 10 s without motion) from rest, tilted by `theta0` (rad) about its corner.
    progress: optional callable(t, duration), called between rollout chunks about
    once a second. Returns the shared Trajectory (validate.measure.contact_trajectory)."""
    settings = settings or Settings()
    motion, duration = run_inputs(system, motion, duration, theta0, impact_threshold)

    model = build_model(system, settings)
    return run_model(model, system, motion, settings=settings, duration=duration, theta0=theta0,
                     impact_threshold=impact_threshold, progress=progress)


def run_model(model: mujoco.MjModel, system: System, motion: GroundMotion, *, settings: Settings,
              duration: float, theta0: float = 0.0, impact_threshold: float = DEFAULT_IMPACT_THRESHOLD,
              progress=None, chunk_steps: int | None = None) -> Trajectory:
    """`simulate` on an already compiled scene (for measuring variants of the model)."""
    start = time.perf_counter()
    chunk_steps = chunk_steps or CHUNK_STEPS
    data = mujoco.MjData(model)
    lay = _Layout(model, system, settings.joint)
    dt = model.opt.timestep
    nstep = int(math.floor(duration / dt + 1e-9))
    if settings.impact_timestep is not None:
        return _run_event_resolved(model, system, motion, settings, lay, nstep, theta0, impact_threshold,
                                   progress, start, duration)

    # Ground motion as applied forces, one row per step, taken at the step's start time.
    xg = motion.sampled(dt, nstep * dt)[:nstep]
    forces = np.zeros((nstep, lay.nv))
    forces[:, lay.x_v] = -system.mass * xg
    if lay.base_v is not None:
        forces[:, lay.base_v] = -system.base_mass * xg

    state0 = np.zeros(lay.nstate)
    state0[1:1 + lay.nq] = _initial_qpos(model, lay, system, theta0)
    warm = np.zeros(lay.nv)
    rows = [state0[None, :]]
    status, message = Status.COMPLETED, "reached the end time"
    alpha = system.alpha
    last_report = start
    done = 0
    thq = None if lay.free else 1 + lay.thq
    while done < nstep:
        n = min(chunk_steps, nstep - done)
        state, _ = rollout.rollout(model, data, state0, forces[done:done + n][None],
                                   control_spec=mujoco.mjtState.mjSTATE_QFRC_APPLIED,
                                   initial_warmstart=warm)
        chunk = state[0]
        done += n
        bad = ~np.all(np.isfinite(chunk), axis=1)
        if bad.any():
            k = int(np.argmax(bad))
            rows.append(chunk[:k])
            status = Status.FAILED
            message = (f"the state stopped being finite at t = {(done - n + k + 1) * dt:.6g} s; "
                       "try a smaller timestep or a longer solref timeconst")
            break
        theta = (chunk[:, thq] if thq is not None else
                 _histories(lay, system, chunk)["theta"])
        over = np.nonzero(np.abs(theta) >= alpha)[0]
        if over.size:
            rows.append(chunk[:over[0] + 1])  # contact_trajectory reports the overturning
            break
        rows.append(chunk)
        state0 = chunk[-1]
        warm = data.qacc_warmstart.copy()
        if progress is not None and time.perf_counter() - last_report >= PROGRESS_INTERVAL:
            progress(float(state0[0]), duration)
            last_report = time.perf_counter()
    runtime = time.perf_counter() - start
    hist = _histories(lay, system, np.concatenate(rows))
    return _trajectory(lay, system, motion, settings, hist, dt, impact_threshold, runtime, status, message)


def _trajectory(lay, system, motion, settings, hist, dt, impact_threshold, runtime, status, message):
    hist["t"] = np.arange(hist["t"].size) * dt  # MuJoCo's time sums dt and drifts by round-off
    extras = {"lift_off": hist["lift_off"]}
    counted = counted_sign_changes(hist["theta"], system.alpha, impact_threshold)
    after = hist["lift_off"][counted[0][0]:] if counted else hist["lift_off"][:0]
    extras["lift_off_max_after_impact"] = float(np.max(after)) if after.size else 0.0
    extras["penetration_max"] = float(max(0.0, -np.min(hist["lift_off"])))
    if lay.free:
        extras["out_of_plane_max"] = float(np.max(hist["out_of_plane"]))
    return contact_trajectory(ENGINE, system, motion, t=hist["t"], u=hist["u"], u_dot=hist["u_dot"],
                              theta=hist["theta"], theta_dot=hist["theta_dot"],
                              impact_threshold=impact_threshold, runtime_s=runtime, status=status,
                              message=message, extras=extras, window=settings.contact_window)


def _run_event_resolved(model, system, motion, settings, lay, nstep, theta0, impact_threshold, progress,
                        start, duration) -> Trajectory:
    """Coarse steps (settings.timestep) in flight and at rest, fine steps
    (settings.impact_timestep) around impacts; the history keeps the coarse grid.

    Semi-implicit Euler carries the velocity of the half step behind the position, so
    a coarse state's velocity is converted (± a·dt/2) where the step size changes, and
    the history reports a coarse row's velocity as the mean of its half steps (the
    leapfrog velocity, second order); fine rows are reported as they are."""
    dt, dtf = settings.timestep, settings.impact_timestep
    n_per = int(round(dt / dtf))
    k_stiff, damping = settings.solref
    fine_model = mujoco.MjModel.from_xml_string(scene_text(system, Settings(**{
        **{f: getattr(settings, f) for f in settings.__dataclass_fields__},
        "timestep": dtf, "solref": (k_stiff, damping * n_per), "impact_timestep": None})))
    data_c, data_f = mujoco.MjData(model), mujoco.MjData(fine_model)
    spec = mujoco.mjtState.mjSTATE_QFRC_APPLIED
    v0 = 1 + lay.nq
    vel = slice(v0, v0 + lay.nv)

    def forces(t0, h, n):
        xg = np.asarray(motion(t0 + np.arange(n) * h), dtype=float)
        f = np.zeros((n, lay.nv))
        f[:, lay.x_v] = -system.mass * xg
        if lay.base_v is not None:
            f[:, lay.base_v] = -system.base_mass * xg
        return f

    def theta_rate(states):
        h = _histories(lay, system, states)
        return h["theta"], h["theta_dot"]

    state = np.zeros(lay.nstate)
    state[1:1 + lay.nq] = _initial_qpos(model, lay, system, theta0)
    rows, coarse = [state.copy()], [False]
    warm = np.zeros(lay.nv)
    k = 0
    last_cross = -math.inf
    status, message = Status.COMPLETED, "reached the end time"
    last_report = start
    while k < nstep:
        th, thd = theta_rate(state[None, :])
        t_k = k * dt
        fine = (t_k - last_cross < IMPACT_SETTLE
                or (abs(thd[0]) > IMPACT_MIN_RATE and abs(th[0]) < IMPACT_ZONE * abs(thd[0]) * dt))
        start_state = state.copy()
        if coarse[-1] != (not fine) and len(rows) >= 2:
            acc = (rows[-1][vel] - rows[-2][vel]) / dt
            start_state[vel] += acc * dt / 2 if fine else -acc * dt / 2
        if fine:
            m = min(int(math.ceil(IMPACT_ZONE + IMPACT_SETTLE / dt)) + 1, nstep - k)
            out, _ = rollout.rollout(fine_model, data_f, start_state, forces(t_k, dtf, m * n_per)[None],
                                     control_spec=spec, initial_warmstart=warm)
            seg = out[0]
            warm = data_f.qacc_warmstart.copy()
            th_f, thd_f = theta_rate(seg)
            prev = np.concatenate(([th[0]], th_f))
            flips = np.nonzero((np.sign(prev[1:]) * np.sign(prev[:-1]) < 0) & (np.abs(thd_f) > IMPACT_MIN_RATE))[0]
            if flips.size:
                last_cross = t_k + (flips[-1] + 1) * dtf
            chunk = seg[n_per - 1::n_per]
            chunk_coarse = [False] * len(chunk)
        else:
            if abs(thd[0]) > IMPACT_MIN_RATE:  # rocking: about as far as the next θ = 0
                ahead = abs(th[0] / thd[0]) / dt * (0.7 if th[0] * thd[0] < 0 else 1.0)
                m = int(min(max(ahead, 4), 8 * COARSE_CHUNK))
            else:
                m = 8 * COARSE_CHUNK
            m = min(m, nstep - k)
            out, _ = rollout.rollout(model, data_c, start_state, forces(t_k, dt, m)[None],
                                     control_spec=spec, initial_warmstart=warm)
            chunk = out[0]
            warm = data_c.qacc_warmstart.copy()
            th_c, thd_c = theta_rate(chunk)
            zone = (np.abs(thd_c) > IMPACT_MIN_RATE) & (np.abs(th_c) < IMPACT_ZONE * np.abs(thd_c) * dt)
            prev = np.concatenate(([th[0]], th_c))
            flipped = (np.sign(prev[1:]) * np.sign(prev[:-1]) < 0) & (np.abs(thd_c) > IMPACT_MIN_RATE)
            stop = np.nonzero(zone | flipped)[0]
            if stop.size:  # keep the chunk up to the first state inside the zone
                chunk = chunk[:stop[0] + 1]
                if flipped[stop[0]]:
                    last_cross = t_k + (stop[0] + 1) * dt
            chunk_coarse = [True] * len(chunk)
        bad = ~np.all(np.isfinite(chunk), axis=1)
        if bad.any():
            j = int(np.argmax(bad))
            rows.extend(chunk[:j])
            coarse.extend(chunk_coarse[:j])
            status = Status.FAILED
            message = (f"the state stopped being finite near t = {t_k + (j + 1) * dt:.6g} s; "
                       "try a smaller timestep")
            break
        th_chunk, _ = theta_rate(chunk)
        over = np.nonzero(np.abs(th_chunk) >= system.alpha)[0]
        if over.size:
            rows.extend(chunk[:over[0] + 1])
            coarse.extend(chunk_coarse[:over[0] + 1])
            break
        rows.extend(chunk)
        coarse.extend(chunk_coarse)
        k += len(chunk)
        state = chunk[-1].copy()
        if progress is not None and time.perf_counter() - last_report >= PROGRESS_INTERVAL:
            progress(k * dt, duration)
            last_report = time.perf_counter()
    runtime = time.perf_counter() - start

    states = np.array(rows)
    coarse = np.array(coarse)
    v = states[:, vel]
    rep = v.copy()
    n = len(states)
    both = coarse[1:n - 1] & coarse[2:n]  # this row and the next from coarse steps: leapfrog mean
    idx = np.nonzero(both)[0] + 1
    rep[idx] = 0.5 * (v[idx] + v[idx + 1])
    tail = np.nonzero(coarse[1:] & ~np.concatenate((both, [False])) & coarse[:-1])[0] + 1
    rep[tail] = 1.5 * v[tail] - 0.5 * v[tail - 1]  # coarse row followed by a fine one (or the end)
    states = states.copy()
    states[:, vel] = rep
    hist = _histories(lay, system, states)
    return _trajectory(lay, system, motion, settings, hist, dt, impact_threshold, runtime, status, message)


__all__ = ["Settings", "simulate", "scene_text", "build_model", "settings_for_timestep",
           "event_resolved_settings", "SCENE_SUFFIX"]
