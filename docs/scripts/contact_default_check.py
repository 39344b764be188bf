"""The derived MuJoCo default (Settings.for_system) on seven atlas cells, free rocking from
0.5α: worst signed β error over the judged impacts, t₁ error, counted/judged impacts, loop s.

    python docs/scripts/contact_default_check.py
"""
from types import SimpleNamespace
from isorock.validate.tools import atlas
print("| H (m) | λ | μ | status | worst β error | t₁ error | impacts | loop s |")
print("|---|---|---|---|---|---|---|---|")
for h, lam, mu in ((0.1, 10, 4), (0.2, 10, 4), (0.2, 10, 0), (1, 10, 4), (5, 10, 4), (10, 10, 4), (10, 10, 0)):
    cell = atlas.Cell(float(lam), float(mu), float(h)); ref = atlas.reference(cell)
    task = SimpleNamespace(engine="mujoco", overrides={}, system=ref["system"], motion=None, duration=ref["duration"], theta0=ref["theta0"], key=1)
    m = atlas.run_cell(task)
    st = atlas.judge(m, ref)[0]; e = atlas.judged_errors(m, ref) if st == atlas.OK else None
    t1 = m.get("first_impact_time")
    print(f"| {h:g} | {lam} | {mu} | {st} | {f'{100*max(e, key=abs):+.2f}%' if e else '—'} | {100*(t1/ref['t1_reference']-1) if t1 else float('nan'):+.3f}% | {m.get('impacts_counted')}/{ref['impacts_expected']} | {m['loop_s']:.2f} |", flush=True)
