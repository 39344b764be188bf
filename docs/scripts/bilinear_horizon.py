"""Where a contact engine's base history can be held to the analytic model's on a stiff bilinear
bearing (issue 34), as quoted in docs/isolators.md ("Where a single history is a test").

For each case: the exact model's own horizon (core.probes.own_horizon: how long it agrees with
itself under a 0.5% change of the motion's amplitude, with the counted impacts before it), then
each engine's max |Δu|/u_max against the model up to that horizon and over the whole run, and
its θmax/α beside the model's ensemble (the motion scaled by 1 ± 1%, core.probes.reference_sensitivity): the verdict that
still means something once single histories have parted.

    python docs/scripts/bilinear_horizon.py [--engines mujoco,bullet]
"""
import argparse
import time
from pathlib import Path

from isorock.analytic.motion import load_motion
from isorock.analytic.system import BilinearIsolator, System
from isorock.validate.core.compare import base_history_error, compare
from isorock.validate.core.probes import own_horizon, reference_sensitivity
from isorock.validate.core.engines import get_engine
from isorock.validate.core.tolerances import tolerance

BLOCK = dict(height=2.0, width=0.7, mass=3800.0, base_mass=3800.0)
STIFF = (3e6, 0.1, 0.002, 1000.0)  # the bearing of tests/test_isolator_engines.py's rocking pulses
CASES = [
    (STIFF, "ricker:amp=0.6,freq=1.5"),
    (STIFF, "ricker:amp=0.8,freq=2"),
    (STIFF, "sine:amp=0.5,freq=1.5,cycles=3"),
    (STIFF, "sine:amp=0.45,freq=1.2,cycles=4"),
    (STIFF, "sine:amp=0.6,freq=2,cycles=6"),
    (STIFF, "sine:amp=0.45,freq=1.5,cycles=6"),
    (STIFF, "sine:amp=0.55,freq=1.5,cycles=8"),
    (STIFF, "kobe@0.4"),
    (STIFF, "kobe@0.5"),
    ((3e5, 0.5, 0.005, 1000.0), "sine:amp=0.5,freq=1.5,cycles=3"),
]
KOBE = Path(__file__).resolve().parents[3] / "shared" / "data" / "records" / "RSN1106_KOBE_KJM000.AT2"


def bearing(k0, r, u_y, c):
    return System.with_isolator(**BLOCK, isolator=BilinearIsolator(stiffness=k0, post_yield_ratio=r,
                                                                   yield_displacement=u_y, damping=c))


def motion_of(spec):
    """A pulse spec, or kobe@PGA: the Kobe record (read from ../shared, never copied) scaled to PGA g."""
    if spec.startswith("kobe@"):
        kobe = load_motion(str(KOBE))
        return kobe.scaled(float(spec[5:]) * 9.80665 / kobe.pga)
    return load_motion(spec)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--engines", default="mujoco,bullet")
    engines = p.parse_args().engines.split(",")
    reference = get_engine("analytic-reference")
    for params, pulse in CASES:
        system, motion = bearing(*params), motion_of(pulse)
        duration = motion.end_time + 2.0
        ref = reference.simulate(system, motion, duration=duration)
        own = own_horizon(system, motion, ref, duration=duration)
        ensemble = reference_sensitivity(system, motion, duration=duration)["theta_max_over_alpha"]
        lo, hi = min(ensemble), max(ensemble)
        print(f"== bearing {params} under {pulse}: {ref.impact_count} impacts, θmax/α {ref.theta_max_over_alpha:.3f}, "
              f"u_max {ref.u_max * 100:.2f} cm; the model's own horizon {own['s']:.2f} s "
              f"({own['impacts']} impacts{', parted' if own['parted'] else ', never parted'}); "
              f"its ensemble θmax/α {lo:.3f}–{hi:.3f}")
        for name in engines:
            start = time.process_time()
            tr = get_engine(name).simulate(system, motion, duration=duration)
            c = compare(tr, ref)
            limit = tolerance(name, "isolator_u_history").limit
            within = base_history_error(tr, ref, own["s"])
            whole = base_history_error(tr, ref)
            th = tolerance(name, "theta_max_diff").limit
            inside = lo - th <= tr.theta_max_over_alpha <= hi + th
            print(f"  {name}: max|Δu|/u_max {within:.4f} to the model's horizon, {whole:.4f} over the run "
                  f"(limit {limit:g}); its own horizon {c.horizon:.2f} s{' (parted)' if c.parted else ''}; "
                  f"impacts {tr.impact_count}; θmax/α {tr.theta_max_over_alpha:.3f} "
                  f"{'inside' if inside else 'OUTSIDE'} the ensemble ± {th:g}  [{time.process_time() - start:.1f} s CPU]")


if __name__ == "__main__":
    main()
