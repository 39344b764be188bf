"""How fast could a contact run be, given the steps it must take? (docs/mujoco.md and
docs/bullet.md, "Where the speed goals stand"; issue 19's speed goals.)

Kobe 40 s on the paper's block, isolated and fixed, at each engine's default: the steps
the engine itself takes (MuJoCo: the timesteps `mujoco.rollout` steps, fine and coarse;
PyBullet: the control steps Bullet is stepped and their sub-steps) and the CPU time spent
inside the engine's stepping calls alone, against the whole run's. The engine's time is
what no Python outside it can remove: the simulated time over it is the speed of a run
with nothing but those steps, and, for a batch, the same over the machine's cores.
Best of `REPEATS` runs (the machine is shared: take the quietest).

    python docs/scripts/speed_floor.py
"""
import contextlib
import time

from mujoco import rollout as mj_rollout

from isorock.analytic import paper_system
from isorock.analytic.motion import load_motion
from isorock.bullet_models import stepping as bullet_stepping
from isorock.mujoco_models import stepping as mujoco_stepping
from isorock.validate.core.engines import get_engine
from isorock.validate.core.scenarios import KOBE

REPEATS = 7
BATCH_RUNS, CORES = 16, 2


class Inside:
    """CPU time and calls inside a wrapped function."""

    def __init__(self):
        self.cpu, self.calls, self.steps = 0.0, 0, 0

    def wrap(self, f, steps_of):
        def wrapped(*args, **kwargs):
            start = time.thread_time()
            out = f(*args, **kwargs)
            self.cpu += time.thread_time() - start
            self.calls += 1
            self.steps += steps_of(args, kwargs)
            return out
        return wrapped


def measure(engine: str, system, motion) -> dict:
    best = None
    for _ in range(REPEATS):
        inside = Inside()
        if engine == "mujoco":
            patch = contextlib.ExitStack()
            original = mj_rollout.rollout
            mujoco_stepping.rollout.rollout = inside.wrap(original, lambda a, k: a[3].shape[1])
            patch.callback(setattr, mujoco_stepping.rollout, "rollout", original)
        else:
            patch = contextlib.ExitStack()
            original = bullet_stepping.run_client

            @contextlib.contextmanager
            def counted():
                with original() as client:
                    client.stepSimulation = inside.wrap(client.stepSimulation, lambda a, k: 1)
                    yield client
            bullet_stepping.run_client = counted
            patch.callback(setattr, bullet_stepping, "run_client", original)
        with patch:
            start = time.thread_time()
            traj = get_engine(engine).simulate(system, motion, duration=40.0, effective_beta=False)
            whole = time.thread_time() - start
        if best is None or whole < best["whole_cpu_s"]:
            best = {"whole_cpu_s": whole, "engine_cpu_s": inside.cpu, "calls": inside.calls,
                    "steps": inside.steps, "simulated_s": float(traj.t[-1])}
    return best


def main():
    motion = load_motion(str(KOBE))
    print("| engine | base | simulated s | engine calls | steps | CPU s, whole run | CPU s inside the engine "
          "| sim s per CPU s: whole run | engine alone |")
    print("|---|---|---|---|---|---|---|---|---|")
    pairs = {}
    for engine in ("mujoco", "bullet"):
        for base, system in (("isolated", paper_system()), ("fixed", paper_system(fixed_base=True))):
            r = measure(engine, system, motion)
            pairs.setdefault(engine, []).append(r)
            print(f"| {engine} | {base} | {r['simulated_s']:.2f} | {r['calls']} | {r['steps']} | "
                  f"{r['whole_cpu_s']:.4f} | {r['engine_cpu_s']:.4f} | {r['simulated_s'] / r['whole_cpu_s']:.0f} | "
                  f"{r['simulated_s'] / r['engine_cpu_s']:.0f} |")
    for engine, (iso, fixed) in pairs.items():
        simulated = BATCH_RUNS // 2 * (iso["simulated_s"] + fixed["simulated_s"])
        for label, key in (("whole runs", "whole_cpu_s"), ("engine alone", "engine_cpu_s")):
            cpu = BATCH_RUNS // 2 * (iso[key] + fixed[key])
            print(f"{engine}: a batch of {BATCH_RUNS} (half isolated) on {CORES} cores, perfectly shared, "
                  f"{label}: {simulated / (cpu / CORES):.0f} sim s per wall s at most")


if __name__ == "__main__":
    main()
