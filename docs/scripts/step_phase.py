"""How much an atlas cell's β error moves with the phase of its impacts within a step
(docs/mujoco.md, "Every size"): MuJoCo at the contact time constant its default derives
for the cell, with the step τ/RATIO changed by 0.01–10%.

    python docs/scripts/step_phase.py 1.5 4 1 --ratio 6       # λ, μ, H (m)
"""
import argparse

from isorock.mujoco_models.settings import Settings
from isorock.validate.tools.atlas import Cell, Grid, build

CHANGES = (0.0, 1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1)

if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("slenderness", type=float)
    ap.add_argument("mass_ratio", type=float)
    ap.add_argument("height", type=float)
    ap.add_argument("--ratio", type=float, default=6.0, help="steps per contact time constant")
    ap.add_argument("--tau-scale", type=float, default=1.0, help="the derived time constant times this")
    a = ap.parse_args()
    cell = Cell(a.slenderness, a.mass_ratio, a.height)
    derived = Settings().for_system(cell.system())
    tau = derived.solref[0] * a.tau_scale
    errors = []
    for change in CHANGES:
        overrides = dict(timestep=tau / a.ratio * (1 - change), solref=(tau, derived.solref[1]),
                         solimp=derived.solimp, follow_system=False)
        row = build(["mujoco:default"], Grid((a.slenderness,), (a.mass_ratio,), (a.height,)), workers=1,
                    overrides=overrides)["rows"][0]
        errors.append(row["beta_error"])
        shown = "—" if row["beta_error"] is None else f"{100 * row['beta_error']:+.3f}%"
        print(f"step −{100 * change:g}%: {row['status']}, β error {shown}", flush=True)
    judged = [e for e in errors if e is not None]
    print(f"range: {100 * min(judged):+.3f}% … {100 * max(judged):+.3f}%")
