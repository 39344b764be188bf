"""Drake beside MuJoCo and PyBullet on the report's history scenarios (docs/drake.md).

The report's default pulses (validate.tools.report_run.DEFAULT_MOTIONS: one-sine 0.6 g 1.3 Hz two
cycles, Ricker 0.5 g 1 Hz) on the paper's block, isolated (T 1.5 s, ξ 0.2, μ = 1) and
fixed, each for the pulse + the full report's tail (4 s); every engine through the
registry (validate.engines) at its default settings. Per engine: θmax/α and its
difference from the analytic model's, the worst |effective β error| over the counted
impacts whose half-cycle peaked above BETA_MIN_AMPLITUDE·α (as the report takes them),
the number of counted impacts, how long the θ histories agree (validate.compare's
agreement horizon), and the CPU time of the call (time.process_time: the machine is
shared, so wall time would measure the other jobs too). Robust: the analytic
θmax/α moves less than ROBUST_SPREAD under ±1% PGA (single-history agreement means
something only there, model.md).

    python docs/scripts/drake_scenarios.py [ENGINE ...]    (default: analytic mujoco bullet drake)

An ENGINE may be `drake:PRESET` (drake_models.scene.PRESETS) or `drake:accuracy=A` (the
default at another accuracy); the analytic reference always runs.
"""
from __future__ import annotations

import math
import sys
import time

from isorock.analytic.motion import load_motion
from isorock.validate.core.compare import compare
from isorock.validate.core.probes import reference_sensitivity
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import paper_bases
from isorock.validate.tools.report_run import BETA_MIN_AMPLITUDE, DEFAULT_MOTIONS, FULL
from isorock.validate.core.tolerances import ROBUST_SPREAD

ENGINES = ("analytic", "mujoco", "bullet", "drake")


def runner(spec: str):
    """(label, simulate) for an engine name or a drake variant."""
    name, _, variant = spec.partition(":")
    engine = get_engine(name)
    if not variant:
        return spec, engine.simulate
    from isorock.drake_models import scene
    key, _, value = variant.partition("=")
    settings = scene.preset("continuous", **{key: float(value)}) if value else scene.preset(key)
    return spec, lambda system, motion, **kw: engine.simulate(system, motion, settings=settings, **kw)


def beta_error_max(traj, ref_cmp) -> float:
    """Worst |β error| over the counted impacts above BETA_MIN_AMPLITUDE·α."""
    big = [e for i, e in zip(traj.counted_impacts, ref_cmp.beta_errors)
           if i.amplitude > BETA_MIN_AMPLITUDE * traj.alpha and math.isfinite(e)]
    return max((abs(e) for e in big), default=math.nan)


def main(engines):
    specs = list(engines or ENGINES)
    runners = [runner(n) for n in (specs if "analytic" in specs else ["analytic", *specs])]
    print("| scenario | robust | engine | θmax/α | Δ vs analytic | worst β err (peaks > 0.1α) | "
          "impacts (analytic) | agrees until (s) | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for spec in DEFAULT_MOTIONS:
        motion = load_motion(spec)
        duration = motion.end_time + FULL.tail
        for base, system in paper_bases():
            sens = reference_sensitivity(system, motion, duration=duration)
            robust = sens["spread"] < ROBUST_SPREAD and not sens["overturn_flips"]
            runs = {}
            for label, simulate in runners:
                start = time.process_time()
                runs[label] = (simulate(system, motion, duration=duration), time.process_time() - start)
            ref = runs["analytic"][0] if "analytic" in runs else None
            for name, (tr, cpu) in runs.items():
                if ref is not None and name != "analytic":
                    c = compare(tr, ref)
                    diff, berr = f"{c.theta_max_diff:+.4f}", beta_error_max(tr, c)
                    berr = "—" if math.isnan(berr) else f"{100 * berr:.2f}%"
                    horizon = f"{c.horizon:.2f}" + (" (parted)" if c.parted else "")
                else:
                    diff, berr, horizon = "—", "—", "—"
                note = f" ({tr.status})" if tr.status != "completed" else ""
                print(f"| {spec}, {base} | {'yes' if robust else 'no'} | {name} | "
                      f"{tr.theta_max_over_alpha:.4f}{note} | {diff} | {berr} | {tr.impact_count}"
                      f"{'' if ref is None else f' ({ref.impact_count})'} | {horizon} | {cpu:.2f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
