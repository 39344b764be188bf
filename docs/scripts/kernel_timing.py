"""Cold-process and warm timings of `isorock run` on the first 40 s of Kobe, the compiled
engine ("analytic") against the SciPy reference ("analytic-reference"), in one run:

    python docs/scripts/kernel_timing.py [REPEATS]

Per engine, REPEATS new processes (`isorock run ... --json -`), each reporting runtime_s
(from the call to the result: for "analytic" the loading of the compiled kernel included)
and timed whole from outside; then warm calls in one process. Prints medians. The kernel
must have been compiled once before (any earlier run). Machine load matters: quote it."""
import json
import os
import statistics
import subprocess
import sys
import time

from isorock.validate.core.scenarios import KOBE  # the records folder, found as the commands find it
PAPER = ["--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass", "3800",
         "--period", "1.5", "--damping-ratio", "0.2"]


def cold(engine, repeats):
    isorock = [sys.executable, "-m", "isorock.validate.cli.main"]
    walls, runtimes = [], []
    for _ in range(repeats):
        t = time.perf_counter()
        out = subprocess.run([*isorock, "run", "--engine", engine, *PAPER, "--motion", str(KOBE),
                              "--duration", "40", "--json", "-", "--quiet"],
                             capture_output=True, text=True, check=True)
        walls.append(time.perf_counter() - t)
        runtimes.append(json.loads(out.stdout)["runtime_s"])
    return statistics.median(walls), statistics.median(runtimes)


def warm(engine, repeats):
    from isorock.analytic.motion import read_at2
    from isorock.analytic.system import paper_system
    from isorock.validate.core.engines import get_engine
    e, system, kobe = get_engine(engine), paper_system(), read_at2(KOBE)
    e.simulate(system, kobe, duration=40.0)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        e.simulate(system, kobe, duration=40.0)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; medians of {repeats}")
    rows = {}
    for engine in ("analytic", "analytic-reference"):
        wall, runtime = cold(engine, repeats)
        rows[engine] = (wall, runtime, warm(engine, repeats if engine == "analytic" else 2))
        print(f"{engine:20s} new process: whole command {wall:.3f} s, runtime_s {runtime:.3f} s; "
              f"warm call {rows[engine][2]:.4f} s", flush=True)
    a, r = rows["analytic"], rows["analytic-reference"]
    print(f"reference / analytic: new process runtime_s {r[1] / a[1]:.0f}x, warm {r[2] / a[2]:.0f}x")


if __name__ == "__main__":
    main()
