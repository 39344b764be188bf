"""The rocking block as a PyBullet scene: `scene.py` (the bodies, and the same scene as
an SDF file), `settings.py` (numerical settings, measured), `stepping.py` (stepping).
Measurements behind every default: docs/bullet.md."""
import math
from dataclasses import replace

from isorock.analytic.engine_protocol import Capabilities, EngineSpec, Tuning

from .scene import SCENE_FORMAT, build, connect, scene_text
from .settings import Settings, settings_for, settings_for_timestep
from .stepping import simulate, step_cost


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


ENGINE = EngineSpec(
    name="bullet", label="PyBullet", settings_type=Settings, simulate=simulate,
    capabilities=Capabilities(isolated_base=True, past_alpha=True, batch=False, exact_impacts=False),
    settings_for=settings_for, scene_text=scene_text, scene_format=SCENE_FORMAT,
    presets={
        "default": Settings,
        # the former default: physics step 1/3000 s and ERP 0.08 at every size, right on the paper's
        # 2 m block, 1.6% off in β on small and squat ones (docs/bullet.md): kept to compare against
        "absolute": lambda: Settings(follow_system=False, contact_erp=0.08),
        # 1 ms physics steps: β within ~1% on the paper's block at three times the speed (docs/bullet.md)
        "fast": lambda: settings_for_timestep(1e-3, follow_system=True),
        # 0.1 ms physics steps: β within ~0.1% on the paper's block
        "fine": lambda: settings_for_timestep(1e-4, follow_system=True),
        # contact ERP a quarter of Bullet's 0.08: a sunk corner is pushed out more slowly, with less kick
        "erp-low": lambda: Settings(contact_erp=0.02),
        # contact ERP 0.2, the value most engines default to: faster correction, and a bounce (0.8 bounces)
        "erp-high": lambda: Settings(contact_erp=0.2),
        # 10 solver iterations instead of 50: a cheaper solve, unconverged at impacts (docs/bullet.md)
        "iterations-10": lambda: Settings(solver_iterations=10),
        # 200 solver iterations: whether the default's 50 leaves the impact unconverged
        "iterations-200": lambda: Settings(solver_iterations=200),
        # the isolator force and ground motion updated every 3 physics steps (1 ms), not 12 (4 ms)
        "substeps-3": lambda: Settings(substeps=3),
        # every 30 physics steps (10 ms): fewer Python steps, the force held longer
        "substeps-30": lambda: Settings(substeps=30),
    },
    ladder=ladder, tuning=TUNING, step_cost=step_cost)

__all__ = ["ENGINE", "Settings", "simulate", "scene_text", "build", "connect", "settings_for",
           "settings_for_timestep"]
