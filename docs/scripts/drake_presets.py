"""Effective β error and speed of each Drake preset (docs/drake.md).

Free rocking of the paper's block (H 2.0 m, B 0.7 m, m = m_b = 3800 kg) from θ0 = 0.3,
0.5 and 0.8 α, on a fixed base and on the μ = 1 isolator (T 1.5 s, ξ 0.2); the first
four counted impacts of each run. β errors are against the closed forms: the box's
(model.md) and, on the fixed base, the corner-sphere geometry's own
(drake_models.scene.sphere_geometry_beta: the spheres the point-contact presets stand on).
Speed is simulated seconds per CPU second of the process (time.process_time, so other
load on the machine does not count) and per wall second.

    python docs/scripts/drake_presets.py [PRESET ...]     (default: every preset)
"""
from __future__ import annotations

import sys
import time

from isorock.analytic.coefficients import beta
from isorock.analytic.system import paper_system
from isorock.drake_models import scene

THETA0 = (0.3, 0.5, 0.8)
#: long enough for four counted impacts from every θ0 (the fixed base's come slower)
DURATION = {"fixed": 3.5, "isolated": 2.0}
N_IMPACTS = 4
#: extra rows: the default at a tighter accuracy (the converged reference of the study)
VARIANTS = {"continuous, accuracy 1e-4": scene.preset("continuous", accuracy=1e-4)}


def measure(settings: scene.Settings) -> dict:
    out = {"box_fixed": 0.0, "sphere_fixed": 0.0, "box_isolated": 0.0, "sim": 0.0, "cpu": 0.0, "wall": 0.0,
           "impacts": [], "hop": 0.0}
    for base, system in (("fixed", paper_system(fixed_base=True)), ("isolated", paper_system())):
        box = beta(system.slenderness, system.mu)
        sphere = scene.sphere_geometry_beta(system, settings.corner_radius) if system.fixed_base else None
        for f in THETA0:
            cpu, wall = time.process_time(), time.perf_counter()
            tr = scene.simulate(system, None, settings=settings, duration=DURATION[base], theta0=f * system.alpha)
            out["cpu"] += time.process_time() - cpu
            out["wall"] += time.perf_counter() - wall
            out["sim"] += DURATION[base]
            betas = [i.beta for i in tr.counted_impacts[:N_IMPACTS]]
            out["impacts"].append(len(betas))
            out["hop"] = max(out["hop"], tr.extras["lift_off_max_after_impact"])
            out[f"box_{base}"] = max(out[f"box_{base}"], max(abs(b / box - 1) for b in betas))
            if sphere is not None:
                out["sphere_fixed"] = max(out["sphere_fixed"], max(abs(b / sphere - 1) for b in betas))
    return out


def main(names):
    rows = [(n, scene.PRESETS[n]) for n in names] if names else [*scene.PRESETS.items(), *VARIANTS.items()]
    print("| preset | worst β err fixed (sphere geometry) | fixed (box) | isolated μ = 1 (box) | "
          "sim s / CPU s | sim s / wall s | largest hop after impact (mm) | impacts per run |")
    print("|---|---|---|---|---|---|---|---|")
    for name, settings in rows:
        r = measure(settings)
        print(f"| {name} | {100 * r['sphere_fixed']:.3f}% | {100 * r['box_fixed']:.3f}% | "
              f"{100 * r['box_isolated']:.3f}% | {r['sim'] / r['cpu']:.2f} | {r['sim'] / r['wall']:.2f} | "
              f"{1e3 * r['hop']:.4f} | {min(r['impacts'])}–{max(r['impacts'])} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
