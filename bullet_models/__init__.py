"""The rocking block as a PyBullet scene: `scene.py` (the bodies, and the same scene as
an SDF file), `settings.py` (numerical settings, measured), `stepping.py` (stepping),
`rest.py` (the rest phases a run skips).
Measurements behind every default: docs/bullet.md."""
import math
from dataclasses import replace

from ..analytic.engine_protocol import Capabilities, EngineSpec, Preset, Tuning
from ..analytic.isolator_parts import CONTACT_ISOLATORS, PLANE_ISOLATORS

from .scene import SCENE_FORMAT, build, connect, scene_text
from .settings import Settings, settings_for, settings_for_timestep
from .stepping import TRANSVERSE, TWO_EDGES, simulate, step_cost
from . import mesh_scene  # the rock's hull as a free body, for measured shake-table tests


def ladder(quick: bool):
    """Work-precision ladder: physics steps, the control step kept near 4 ms."""
    steps = (1 / 500, 1 / 1000, 1 / 4000) if quick else (1 / 500, 1 / 1000, 1 / 2000, 1 / 5000, 1 / 10000)
    return [(f"dt={dt:.3g}", settings_for_timestep(dt)) for dt in steps]


#: Calibration moves the contact error reduction (ERP, log10: 0.01–0.25; 0.3 and more
#: make the block bounce), the fraction of a contact's penetration Bullet removes per
#: physics step. The physics step (--timestep) stays the user's. Solver iterations are
#: left out: they are a convergence setting, not a contact law (50 and 100 give identical
#: runs, 20 differs by noise alone), and a whole number Nelder–Mead can only round.
TUNING = Tuning(
    names=("log10 contact ERP",),
    bounds=((-2.0, math.log10(0.25)),),
    start=lambda s: [math.log10(s.contact_erp)],
    apply=lambda s, x: replace(s, contact_erp=float(10 ** x[0])))


def _simulate_body(vertices, com, inertia, mass, acceleration, dt, *, duration=None, friction=None, restitution=None):
    contact = {k: v for k, v in (("friction", friction), ("restitution", restitution)) if v is not None}
    return mesh_scene.simulate(vertices, com, inertia, mass, acceleration, dt, duration=duration, **contact)


ENGINE = EngineSpec(
    name="bullet", label="PyBullet", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False,
                              isolators=CONTACT_ISOLATORS, kinetic_friction=False,
                              two_edges=TWO_EDGES, transverse=TRANSVERSE,
                              transverse_isolators=PLANE_ISOLATORS),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT, simulate_body=_simulate_body,
    presets={
        "default": Preset("the measured default, its step following the block (docs/bullet.md, \"Settings that follow "
                          "the block's size\")", Settings),
        "absolute": Preset(
            "the former default: physics step 1/3000 s and ERP 0.08 at every size, right on the paper's 2 m block, "
            "4% off in β on small ones (docs/atlas.md): kept to compare against",
            lambda: Settings(follow_system=False, contact_erp=0.08)),
        "full": Preset(
            "Bullet stepped throughout, also while the block rests on its base (rest.py: the default skips it)",
            lambda: Settings(phased=False)),
        "fast": Preset(
            "1 ms physics steps on the paper's block (scaled with the block): β within ~1% there at three times "
            "the former default's speed (docs/bullet.md)",
            lambda: settings_for_timestep(1e-3, follow_system=True)),
        "fine": Preset(
            "0.1 ms physics steps on the paper's block (scaled with the block): β within ~0.1% there",
            lambda: settings_for_timestep(1e-4, follow_system=True)),
        "erp-low": Preset(
            "contact ERP 0.02, half the default's 0.04: a sunk corner is pushed out more slowly, with less kick",
            lambda: Settings(contact_erp=0.02)),
        "erp-high": Preset(
            "contact ERP 0.2, the value most engines default to: faster correction, and a bounce (0.8 bounces)",
            lambda: Settings(contact_erp=0.2)),
        "iterations-10": Preset(
            "10 solver iterations instead of 50: a cheaper solve, unconverged at impacts (docs/bullet.md)",
            lambda: Settings(solver_iterations=10)),
        "iterations-200": Preset(
            "200 solver iterations: whether the default's 50 leaves the impact unconverged",
            lambda: Settings(solver_iterations=200)),
        "substeps-3": Preset(
            "the isolator force and ground motion updated every 3 physics steps, not 12",
            lambda: Settings(substeps=3)),
        "substeps-30": Preset(
            "every 30 physics steps: fewer Python steps, the force held longer",
            lambda: Settings(substeps=30)),
    },
    ladder=ladder, tuning=TUNING, step_cost=step_cost,
    # the base light enough, the isolator slow enough for Bullet (Settings.check_isolator)
    check_system=lambda system, settings: settings.check_isolator(system))

__all__ = ["ENGINE", "Settings", "simulate", "scene_text", "build", "connect", "settings_for",
           "settings_for_timestep"]
