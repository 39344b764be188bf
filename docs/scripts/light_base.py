"""Why does MuJoCo's default err more on a light base than on a fixed base at the same
size? (docs/mujoco.md, "Why the light base errs more".) One small slender cell
(H 0.2 m, λ 10, free rocking from 0.5α) at several mass ratios and with one setting
changed at a time: the worst |β error| over the atlas's judged impacts, the first impact
time error, and the largest pivot slip (`pivot_slip_max`, m).

    python docs/scripts/light_base.py            # the one-change-at-a-time table
    python docs/scripts/light_base.py --sweep    # the time-constant sweep, with the rigid
                                                 # model's amplitude and θ̇ at each judged impact
"""
import sys
from types import SimpleNamespace

from isorock.validate.tools import atlas

DT, TIMECONST = 5e-4, 0.002  # the defaults (mujoco_models/settings.py)

VARIANTS = {
    "default": {},
    "noslip 20 (stiff friction)": {"noslip": 20},
    "step ÷2, same timeconst": {"timestep": DT / 2, "solref": (TIMECONST, 2.0)},
    "timeconst ÷2, step ÷2": {"timestep": DT / 2, "solref": (TIMECONST / 2, 2.0)},
    "pyramidal cone": {"cone": "pyramidal"},
}


def sweep():
    """Contact time constant τ (4 steps each, as by default) on three cells; for each judged
    impact the per-impact β error and the rigid model's amplitude/α, |θ̇| before it and
    the ratio |θ̇|·τ/amplitude (how far the block turns while the contact acts, as a
    fraction of the half-cycle's swing)."""
    from isorock.validate.core.engines import REFERENCE, get_engine
    print("| H (m) | μ | τ (s) | τ·p | per judged impact: β error (|θ̇|·τ/amplitude) |")
    print("|---|---|---|---|---|")
    for h, mu in ((0.2, 0.0), (0.2, 4.0), (1.0, 4.0)):
        cell = atlas.Cell(10.0, mu, h)
        ref = atlas.reference(cell)
        system = ref["system"]
        rigid = get_engine(REFERENCE).simulate(system, None, duration=ref["duration"], theta0=ref["theta0"])
        judged = [rigid.counted_impacts[k] for k in ref["judged_impacts"]]
        for tc in (0.004, 0.002, 0.001, 0.0005):
            task = SimpleNamespace(engine="mujoco", overrides={"timestep": tc / 4, "solref": (tc, 2.0)}, system=system,
                                   motion=None, duration=ref["duration"], theta0=ref["theta0"], key=tc)
            m = atlas.run_cell(task)
            errors = atlas.judged_errors(m, ref) or [None] * len(judged)
            cells = [(f"{100 * e:+.2f}%" if e is not None else "lost") + f" ({abs(i.theta_dot_pre) * tc / i.amplitude:.3f})"
                     for e, i in zip(errors, judged)]
            print(f"| {h:g} | {mu:g} | {tc:g} | {tc * system.p:.4f} | {'; '.join(cells)} |", flush=True)
    print("\nrigid model, judged impacts: amplitude/α, |θ̇| before (rad/s), half-cycle before (s)")
    for h, mu in ((0.2, 0.0), (0.2, 4.0), (1.0, 4.0), (5.0, 4.0)):
        cell = atlas.Cell(10.0, mu, h)
        ref = atlas.reference(cell)
        system = ref["system"]
        rigid = get_engine(REFERENCE).simulate(system, None, duration=ref["duration"], theta0=ref["theta0"])
        imp = rigid.counted_impacts
        rows = [f"{imp[k].amplitude / system.alpha:.3f}, {abs(imp[k].theta_dot_pre):.3f}, "
                f"{imp[k].t - (imp[k - 1].t if k else 0.0):.4f}" for k in ref["judged_impacts"]]
        print(f"H {h:g} μ {mu:g} (1/p {1 / system.p:.4f} s): " + " | ".join(rows))


def main():
    if sys.argv[1:] == ["--sweep"]:
        return sweep()
    mus = [float(x) for x in sys.argv[1:]] or [0.0, 0.25, 1.0, 4.0]
    print("| μ | setting | status | worst β error | t₁ error | impacts | pivot slip (mm) |")
    print("|---|---|---|---|---|---|---|")
    for mu in mus:
        cell = atlas.Cell(10.0, mu, 0.2)
        ref = atlas.reference(cell)
        for name, overrides in VARIANTS.items():
            if mu not in (0.0, 4.0) and name != "default":
                continue
            task = SimpleNamespace(engine="mujoco", overrides=overrides, system=ref["system"], motion=None,
                                   duration=ref["duration"], theta0=ref["theta0"], key=(cell.key, name))
            m = atlas.run_cell(task)
            status = atlas.judge(m, ref)[0]
            errors = atlas.judged_errors(m, ref) if status == atlas.OK else None
            worst = f"{100 * max(errors, key=abs):+.2f}%" if errors else "—"
            t1 = m.get("first_impact_time")
            t1e = f"{100 * (t1 / ref['t1_reference'] - 1):+.3f}%" if t1 else "—"
            slip = m.get("pivot_slip")
            print(f"| {mu:g} | {name} | {status} | {worst} | {t1e} | {m.get('impacts_counted')}/"
                  f"{ref['impacts_expected']} | {1e3 * slip if slip is not None else float('nan'):.3f} |", flush=True)


if __name__ == "__main__":
    main()
