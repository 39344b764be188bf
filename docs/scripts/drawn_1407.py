"""Why the contact engines part from the exact model on the stress grid's drawn-1407
(H 2.64 m, λ 10, fixed base, noise:dt=0.01,pga=0.213764,seconds=8,seed=8048, 11 s):
docs/robustness.md, "The fourth round". Prints, in order:

1. the compiled kernel against the SciPy reference (θmax/α, impact times);
2. every impact 1.55–3 s of each engine with its effective β (model.md's mapping, the
   uncounted small ones too) against β = 1 − 1.5 sin²α;
3. the exact model with β scaled to each engine's measured β of its 1.60 s impact, against
   that engine: impact times 1.9–3 s and the time |Δθ| first exceeds 0.02α and 0.1α;
4. the record resampled to 0.5 ms (the same piecewise-linear motion): outcomes and impacts;
5. (--scan) every engine at 41 scales of the motion 0.95–1.05, step 0.25%.

    python docs/scripts/drawn_1407.py [--scan]      (about 30 s; 90 s more with --scan)
"""
import sys

import numpy as np

import isorock.analytic.fast as fast
import isorock.analytic.physics as ph
from isorock.analytic.motion import GroundMotion
from isorock.validate.core.engines import get_engine
from isorock.validate.core.measure import contact_window, effective_impacts
from isorock.validate.tools.stress import drawn_cases

SC = drawn_cases(1407)[1406].scenario
SYSTEM, MOTION, DURATION = SC.system, SC.ground_motion(), SC.duration
ALPHA = SYSTEM.alpha
ENGINES = (("mujoco", None), ("mujoco", "fine"), ("bullet", None))
GRID = np.arange(0, DURATION, 0.001)


def run(name, preset=None, motion=MOTION, beta_scale=1.0, **kw):
    engine = get_engine(name)
    settings = engine.preset(preset) if preset else None
    original = fast._system_params

    def scaled(system, s):
        sp = original(system, s).copy()
        sp[ph.BETA] *= beta_scale
        return sp
    fast._system_params = scaled
    try:
        return engine.simulate(SYSTEM, motion, settings=settings, duration=DURATION, **kw)
    finally:
        fast._system_params = original


def label(name, preset):
    return name + (f":{preset}" if preset else "")


def impacts(tr, t0, t1):
    return " ".join(f"{i.t:.4f}" for i in tr.impacts if t0 < i.t < t1)


def parting(a, b, threshold):
    d = np.abs(np.interp(GRID, a.t, a.theta) - np.interp(GRID, b.t, b.theta)) / ALPHA
    i = int(np.argmax(d > threshold))
    return f"{GRID[i]:.2f} s" if d[i] > threshold else "never"


def peak(tr):
    return float(np.max(np.abs(tr.theta)) / ALPHA)


def main():
    beta = fast._system_params(SYSTEM, get_engine("analytic").settings())[ph.BETA]
    exact, ref = run("analytic"), run("analytic-reference")
    print(f"1. analytic θmax/α {peak(exact):.6f}, impacts {impacts(exact, 0, 11)}\n"
          f"   reference θmax/α {peak(ref):.6f}, impacts {impacts(ref, 0, 11)}")
    print(f"2. β = {beta:.5f}; exact impacts 1.55–3 s: {impacts(exact, 1.55, 3)}")
    trs = {}
    for name, preset in ENGINES:
        tr = trs[label(name, preset)] = run(name, preset)
        imps = effective_impacts(SYSTEM, MOTION, tr.t, tr.u, tr.u_dot, tr.theta, tr.theta_dot,
                                 impact_threshold=1e-4, window=contact_window(SYSTEM))
        print(f"   {label(name, preset)}: " + " ".join(
            f"{i.t:.4f} ({i.amplitude / ALPHA:.4f}α, β {100 * (i.beta / beta - 1):+.2f}%)"
            for i in imps if 1.55 < i.t < 3.0))
    print("3. the exact model with the engine's β (of its 1.60 s impact) against the engine")
    for key, tr in trs.items():
        first = next(i for i in tr.impacts if i.counted and 1.55 < i.t < 1.65)
        scale = first.beta / beta
        rigid = run("analytic", beta_scale=scale)
        print(f"   {key}: engine {impacts(tr, 1.9, 3)} | exact, β×{scale:.5f}: {impacts(rigid, 1.9, 3)}\n"
              f"      |Δθ| > 0.02α / 0.1α at {parting(tr, exact, 0.02)} / {parting(tr, exact, 0.1)} against β, "
              f"{parting(tr, rigid, 0.02)} / {parting(tr, rigid, 0.1)} against β×{scale:.5f} "
              f"(which overturns: {rigid.overturned})")
    for f in (0.99, 0.995, 0.997, 0.998, 0.999, 0.9995, 1.0005, 1.001, 1.002, 1.003, 1.005):
        rigid = run("analytic", beta_scale=f)
        print(f"   exact, β×{f:g}: overturned {rigid.overturned}, θmax/α {peak(rigid):.3f}, impacts {impacts(rigid, 1.9, 2.4)}")
    tt = np.arange(0, MOTION.end_time + 1e-9, 0.0005)
    fine = GroundMotion.from_array(np.asarray(MOTION(tt)), dt=0.0005, name="resampled")
    print("4. record resampled to 0.5 ms")
    for name, preset in (("analytic", None),) + ENGINES[::2]:
        for what, m in (("dt 0.01", MOTION), ("0.5 ms", fine)):
            tr = run(name, preset, motion=m)
            print(f"   {label(name, preset)} {what}: overturned {tr.overturned}, impacts 1.9–2.4 {impacts(tr, 1.9, 2.4)}")
    if "--scan" in sys.argv:
        scales = np.round(np.arange(0.95, 1.05001, 0.0025), 4)
        print("5. overturned (X) at 41 scales 0.95–1.05")
        for name, preset in (("analytic", None), ("analytic-reference", None)) + ENGINES:
            out = [run(name, preset, motion=MOTION.scaled(float(s)), effective_beta=False).overturned for s in scales]
            print(f"   {label(name, preset):18s} {sum(out):2d} of 41: "
                  + " ".join(f"{s:.4f}" for s, o in zip(scales, out) if o))


if __name__ == "__main__":
    main()
