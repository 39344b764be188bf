"""A candidate for MuJoCo's system-following default (issue 19), measured before it is
wired in: contact time constant τ = C / p_eff and step τ/4 (dampratio 2, as by default),
never coarser than today's default (τ 2 ms, step 0.5 ms). p_eff is the rocking rate with
the base's recoil, p / √(1 − ¾·cos²α·μ/(1+μ)) (the inertia about the pivot less what the
free base takes, docs/mujoco.md "Why the light base errs more"). Free rocking from 0.5α
on atlas cells; worst signed β error over the judged impacts, t₁ error, counted/judged.

    python docs/scripts/contact_rule.py [C]
"""
import math
import sys
from types import SimpleNamespace

from isorock.validate.tools import atlas

DT, TIMECONST = 5e-4, 0.002  # today's defaults (mujoco_models/settings.py)


def p_eff(system) -> float:
    share = 0.0 if system.fixed_base else system.mu / (1 + system.mu)
    return system.p / math.sqrt(1 - 0.75 * math.cos(system.alpha) ** 2 * share)


def main():
    c = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0035
    print(f"C = {c:g}\n\n| H (m) | λ | μ | τ (ms) | step (ms) | status | worst β error | t₁ error | impacts |")
    print("|---|---|---|---|---|---|---|---|---|")
    for h in (0.1, 0.2, 1.0, 5.0):
        for lam, mu in ((10.0, 0.0), (10.0, 4.0), (4.0, 1.0)):
            cell = atlas.Cell(lam, mu, h)
            ref = atlas.reference(cell)
            system = ref["system"]
            tau = min(TIMECONST, c / p_eff(system))
            task = SimpleNamespace(engine="mujoco", overrides={"timestep": tau / 4, "solref": (tau, 2.0)},
                                   system=system, motion=None, duration=ref["duration"], theta0=ref["theta0"], key=1)
            m = atlas.run_cell(task)
            status = atlas.judge(m, ref)[0]
            errors = atlas.judged_errors(m, ref) if status == atlas.OK else None
            t1 = m.get("first_impact_time")
            worst = f"{100 * max(errors, key=abs):+.2f}%" if errors else "—"
            t1e = f"{100 * (t1 / ref['t1_reference'] - 1):+.3f}%" if t1 else "—"
            print(f"| {h:g} | {lam:g} | {mu:g} | {1e3 * tau:.3f} | {250 * tau:.4f} | {status} | "
                  f"{worst} | {t1e} | "
                  f"{m.get('impacts_counted')}/{ref['impacts_expected']} |", flush=True)


if __name__ == "__main__":
    main()
