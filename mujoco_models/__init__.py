"""The rocking block as a MuJoCo scene: `scene.xml` + `scene.py` (the model),
`settings.py` (numerical settings, measured), `stepping.py` (stepping with
`mujoco.rollout`), `event_resolved.py` (an opt-in second stepping scheme), `state.py`
(what both read from the state rows, and the history a run returns).
Measurements behind every default: docs/mujoco.md."""
import math
from dataclasses import replace

from ..analytic.engine_protocol import Capabilities, EngineSpec, Preset, Tuning
from ..analytic.isolator_parts import CONTACT_ISOLATORS, PLANE_ISOLATORS

from .scene import SCENE_FORMAT, build_model, check_representable, scene_text
from .settings import Settings, event_resolved_settings, settings_for, settings_for_timestep
from .stepping import run_model, simulate, simulate_many, step_cost
from .replay import replay_scene
from . import mesh_scene  # the rock's hull on a free joint, for measured shake-table tests


def ladder(quick: bool):
    """Work-precision ladder: timesteps with the contact parameters measured for each."""
    steps = (2e-3, 1e-3, 2.5e-4) if quick else (2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4)
    return [(f"dt={dt:.3g}", settings_for_timestep(dt)) for dt in steps]


def _contact(settings):
    """(log2 of the contact time constant in steps, damping ratio, solimp dmin) of the
    settings: solref (timeconst τ, dampratio ζ) as given, or from the direct form
    (−K, −D) by MuJoCo's own conversion K = 1/(τζ)², D = 2/τ."""
    a, b = settings.solref
    tau, zeta = (a, b) if a > 0 else (2.0 / -b, -b / (2.0 * math.sqrt(-a)))
    return [math.log2(tau / settings.timestep), zeta, settings.solimp[0]]


def _with_contact(settings, x):
    """The settings at those coordinates, in the direct form (not bound to τ ≥ 2 steps);
    the rest of solimp is kept."""
    tau, zeta = 2.0 ** x[0] * settings.timestep, float(x[1])
    return replace(settings, solref=(-1.0 / (tau * zeta) ** 2, -2.0 / tau),
                   solimp=(float(x[2]), *settings.solimp[1:]))


#: Calibration moves the contact's time constant in units of the step (log2: 1.5–12
#: steps; 1 step hops by metres, and the rungs measured best sit at 3.3–4), its damping
#: ratio (0.7–3: below 1 it rings, above 2 the impact lasts long enough to lose β) and
#: the impedance dmin (0.7–0.99; 0.99 lets the pivot contact flicker). Physical
#: coordinates tied to the step, not raw stiffness and damping, whose useful ratio moves
#: with both (docs/mujoco.md, "Calibration").
TUNING = Tuning(
    names=("log2 contact time constant / timestep", "damping ratio", "solimp dmin"),
    bounds=((math.log2(1.5), math.log2(12.0)), (0.7, 3.0), (0.7, 0.99)),
    start=_contact,
    apply=_with_contact)



def _replay_scene(system):
    return replay_scene(system)


def _simulate_body(vertices, com, inertia, mass, acceleration, dt, *, duration=None, friction=None, dampratio=None):
    solref = (mesh_scene.SOLREF[0], mesh_scene.SOLREF[1] if dampratio is None else dampratio)
    xml = mesh_scene.scene_xml(vertices, com, inertia, mass, solref=solref,
                               friction=mesh_scene.FRICTION if friction is None else friction)
    return mesh_scene.simulate(xml, acceleration, dt, duration=duration)


ENGINE = EngineSpec(
    name="mujoco", label="MuJoCo", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              isolators=CONTACT_ISOLATORS, kinetic_friction=False, two_edges=True,
                              transverse=True, transverse_isolators=PLANE_ISOLATORS),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT, replay_scene=_replay_scene,
    simulate_body=_simulate_body,
    presets={
        "default": Preset(
            "the measured default: step, contact time constant and impedance width follow the block (docs/mujoco.md, "
            "\"Every size\")", Settings),
        "absolute": Preset(
            "the former default: step 0.5 ms, contact time constant 2 ms and width 1 mm at every size, right on the "
            "paper's 2 m block, 80% off in β on a 0.2 m one (docs/atlas.md): kept to compare against",
            lambda: Settings(follow_system=False)),
        "full": Preset(
            "the contact scene stepped throughout at the timestep: no rest phase skipped, no coarse steps away "
            "from impacts (phases.py)",
            lambda: Settings(phased=False)),
        "newton": Preset(
            "Newton, MuJoCo's own solver and the default's: named so that it reads beside cg",
            lambda: Settings(solver="Newton")),
        "cg": Preset(
            "conjugate gradient, MuJoCo's other solver for soft contacts: cheaper iterations, more of them",
            lambda: Settings(solver="CG")),
        "elliptic": Preset(
            "the elliptic cone, the default's: named so that it reads beside pyramidal",
            lambda: Settings(cone="elliptic")),
        "pyramidal": Preset(
            "the pyramidal cone: cheaper per step, lets the pivot creep 2.3× as far (docs/mujoco.md)",
            lambda: Settings(cone="pyramidal")),
        "fast": Preset(
            "the cheapest step whose β stays within ~1% on the paper's block (docs/mujoco.md, bench ladder)",
            lambda: settings_for_timestep(2e-3)),
        "fine": Preset(
            "a step 5× finer than the default's at every size (1e-4 s, time constant 4e-4 s on the paper's "
            "block, scaled with the block)",
            lambda: settings_for_timestep(1e-4, follow_system=True)),
        "model-md": Preset(
            "model.md's feasibility recipe as written, in seconds: time constant at MuJoCo's floor 2·dt, impedance "
            "dmin 0.99 (the pivot contact flickers at it, docs/mujoco.md; kept to measure it over the atlas)",
            lambda: Settings(solref=(2 * Settings.timestep, 2.0), solimp=(0.99, 0.999, 0.001), follow_system=False)),
        "event-resolved": Preset(
            "coarse steps in flight, fine ones around each impact: long records, not free rocking",
            event_resolved_settings),
        "corners": Preset(
            "a small sphere in each bottom corner instead of box–box: cheaper collision, no better per cost",
            lambda: Settings(contact="corners")),
    },
    ladder=ladder, tuning=TUNING, simulate_many=simulate_many, step_cost=step_cost,
    check_system=lambda system, settings: check_representable(system))

__all__ = ["ENGINE", "Settings", "simulate", "simulate_many", "run_model", "scene_text", "build_model", "settings_for",
           "settings_for_timestep", "event_resolved_settings"]
