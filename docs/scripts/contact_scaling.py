"""Does scaling MuJoCo's contact with the block fix its size-dependent β error?
(docs/mujoco.md, "Contact parameters and the block's size"; the atlas found the default's
worst error growing as the block shrinks, docs/atlas.md.)

Free rocking from 0.5 α on five atlas cells (`validate.atlas.Cell`: λ = H/B, μ = m/m_b,
0 = fixed base), the worst |β error| over the atlas's judged impacts, for four settings:
the default; the solimp width scaled with the half-width b (length ratio b / b_paper);
the contact time constant and the step scaled with the rocking time 1/p (ratio
p_paper / p, so 4 steps per time constant as by default); and both.

    python docs/scripts/contact_scaling.py
"""
from types import SimpleNamespace

from isorock.analytic.system import paper_system
from isorock.validate.tools import atlas

P_PAPER = paper_system(fixed_base=True).p
B_PAPER = paper_system().b
CELLS = [atlas.Cell(10.0, 0.0, 0.2), atlas.Cell(4.0, 0.0, 0.2), atlas.Cell(10.0, 4.0, 0.2),
         atlas.Cell(10.0, 4.0, 1.0), atlas.Cell(10.0, 4.0, 5.0)]
DT, TIMECONST, WIDTH = 5e-4, 0.002, 0.001  # the defaults (mujoco_models/settings.py)


def variants(system):
    time_ratio, length_ratio = P_PAPER / system.p, system.b / B_PAPER
    yield "default", {}
    yield "width ∝ b", {"solimp": (0.9, 0.999, WIDTH * length_ratio)}
    yield "time ∝ 1/p", {"timestep": DT * time_ratio, "solref": (TIMECONST * time_ratio, 2.0)}
    yield "both", {"timestep": DT * time_ratio, "solref": (TIMECONST * time_ratio, 2.0),
                   "solimp": (0.9, 0.999, WIDTH * length_ratio)}


def main():
    print("| H (m) | λ | μ | setting | status | worst β error | timestep (s) |")
    print("|---|---|---|---|---|---|---|")
    for cell in CELLS:
        ref = atlas.reference(cell)
        system = ref["system"]
        for name, overrides in variants(system):
            task = SimpleNamespace(engine="mujoco", overrides=overrides, system=system, motion=None,
                                   duration=ref["duration"], theta0=ref["theta0"], key=(cell.key, name))
            measured = atlas.run_cell(task)
            errors = atlas.judged_errors(measured, ref)
            status = atlas.judge(measured, ref)[0]
            worst = f"{100 * max(abs(e) for e in errors):.2f}%" if errors else "—"
            print(f"| {cell.height:g} | {cell.slenderness:g} | {cell.mass_ratio:g} | {name} | {status} | {worst} "
                  f"| {overrides.get('timestep', DT):.2e} |", flush=True)


if __name__ == "__main__":
    main()
