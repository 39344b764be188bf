"""Campaign throughput, measured (not a test): `python docs/scripts/campaign_throughput.py WHAT`.

    spectrum   the 4,000-cell one-sine spectrum (fixed base, α = 0.25, ω_p/p 0.5–12 ×
               a_p/(g·tanα) 1–20), analytic, serial path (kernel threads on every core)
               and a LocalCluster (start-up included and excluded)
    kobe       analytic runs of 40 s of the Kobe record per second (the batch kernel)
    contact    MuJoCo and PyBullet: one run at a time against a campaign on a LocalCluster
               and the serial campaign path (wall and CPU seconds, with the load)
    overhead   a tiny campaign: a plain loop against run_cases serially and on Dask

Prints one JSON object per measurement. Numbers depend on the machine's load: say
which machine and how loaded when quoting them.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np


def _spectrum_spec(n_freq=80, n_amp=50, engines=({"name": "analytic"},), base="fixed"):
    from isorock.validate.tools.campaign.spec import parse_spec
    return parse_spec({
        "campaign": {"name": "bench spectrum", "analytic_chunk": 500, "contact_chunk": 2},
        "systems": {"alpha": 0.25, "size": 1.0, "mass": 1000.0, "base": base},
        "motions": {"type": "pulse", "pulse": "sine", "frequency_ratio": {"from": 0.5, "to": 12.0, "num": n_freq},
                    "amplitude_ratio": {"from": 1.0, "to": 20.0, "num": n_amp}},
        "duration": {"tail": 5.0}, "engines": list(engines)})


def _emit(**kw):
    print(json.dumps(kw), flush=True)


def bench_spectrum(workers):
    from isorock.validate.core.executor import close_client, local_client
    from isorock.validate.tools.campaign.run import run_campaign
    spec = _spectrum_spec()
    run_campaign(_spectrum_spec(2, 2), None, workers=0, progress=False)  # load the kernel first
    t = time.perf_counter()
    r = run_campaign(spec, None, workers=0, progress=False)
    _emit(what="spectrum 4000 cells, serial path (kernel threads)", cells=r.table.num_rows,
          seconds=round(time.perf_counter() - t, 2), cores=os.cpu_count())
    t = time.perf_counter()
    client = local_client(workers)
    started = time.perf_counter()
    r = run_campaign(spec, None, client=client, progress=False)
    done = time.perf_counter()
    close_client(client)
    _emit(what=f"spectrum 4000 cells, LocalCluster of {workers} processes", cells=r.table.num_rows,
          seconds_with_startup=round(done - t, 2), seconds_after_startup=round(done - started, 2))


def _kobe():
    from isorock.analytic.motion import read_at2
    from isorock.validate.core.scenarios import KOBE as path  # the records folder found, not computed from here
    if not path.is_file():
        sys.exit(f"benchmark kobe: {path} not found")
    return read_at2(path)


def bench_kobe(n, repeats=5):
    """Runs per second of the batch kernel over n runs (n/2 scalings of Kobe per base),
    `repeats` times in this process: the median and the range."""
    from isorock.analytic.fast import simulate_batch
    from isorock.analytic.system import paper_system
    kobe = _kobe()
    systems = [paper_system(), paper_system(fixed_base=True)]
    motions = [kobe.scaled(f) for f in np.linspace(0.5, 1.0, n // 2)]
    simulate_batch(systems[0], motions[0], duration=1.0)  # load the kernel
    for label, sys_ in (("isolated T 1.5 s ξ 0.2", systems[0]), ("fixed", systems[1])):
        rates, load = [], round(os.getloadavg()[0], 2)
        for _ in range(repeats):
            t = time.perf_counter()
            rows = simulate_batch(sys_, motions, duration=40.0)
            rates.append(len(rows) / (time.perf_counter() - t))
        _emit(what=f"analytic batch, Kobe 40 s, paper block {label}", runs=len(rows), repeats=repeats,
              runs_per_second_median=round(float(np.median(rates)), 1),
              runs_per_second_range=[round(min(rates), 1), round(max(rates), 1)],
              overturned=sum(r["overturned"] for r in rows), load_1min=[load, round(os.getloadavg()[0], 2)])


def _contact_cases(n):
    from isorock.analytic.motion import GroundMotion, Pulse
    from isorock.analytic.system import paper_system
    from isorock.validate.tools.campaign.spec import Case
    system = paper_system(fixed_base=True)
    # one-sine pulses around uplift (3 s runs): rocking with impacts, some overturning
    return [Case(i, system, GroundMotion.from_pulse(Pulse("sine", amp=a, freq=1.0)), 3.0)
            for i, a in enumerate(np.linspace(0.4, 0.9, n))]


def _tree_cpu() -> float:
    """CPU seconds of this process and all its children (a LocalCluster's nannies and
    workers): the work a measurement cost, whatever else shares the machine."""
    import psutil
    me = psutil.Process()
    total = 0.0
    for p in [me, *me.children(recursive=True)]:
        try:
            c = p.cpu_times()
            total += c.user + c.system
        except psutil.Error:  # a process that ended in between
            continue
    return total


def _timed(fn):
    cpu, wall = _tree_cpu(), time.perf_counter()
    fn()
    return time.perf_counter() - wall, _tree_cpu() - cpu


def bench_contact(n, workers, repeats=5):
    """Wall and CPU time of three ways to make the same n runs: one at a time
    (Engine.simulate in a loop, what a script would do), a campaign on a LocalCluster of
    `workers` processes, and the serial campaign path (MuJoCo's runs side by side in
    threads). Interleaved `repeats` times: medians, with the fastest wall beside them
    (on a shared machine the others' load only ever adds time). CPU seconds (of every
    process involved) say what each way costs whatever the load."""
    from isorock.validate.core.engines import get_engine
    from isorock.validate.core.executor import close_client, local_client
    from isorock.validate.tools.campaign.run import run_cases
    cases = _contact_cases(n)
    client = local_client(workers)
    try:
        for name in ("mujoco", "bullet"):
            engine = get_engine(name)
            engine.simulate(cases[0].system, cases[0].motion, duration=0.5)  # import and warm up
            client.run(lambda: get_engine(name).simulate(cases[0].system, cases[0].motion, duration=0.5))
            run_cases(cases[:1], [name])  # pyarrow and the campaign modules, out of the timing

            def loop():
                for c in cases:
                    engine.simulate(c.system, c.motion, duration=c.duration)
            ways = {"one_at_a_time": loop,
                    "campaign_cluster": lambda: run_cases(cases, [name], client=client,
                                                          contact_chunk=max(1, n // (2 * workers))),
                    "campaign_serial_threads": lambda: run_cases(cases, [name])}
            times = {k: [] for k in ways}
            load = [round(os.getloadavg()[0], 2)]
            for _ in range(repeats):
                for k, fn in ways.items():
                    times[k].append(_timed(fn))
            load.append(round(os.getloadavg()[0], 2))
            # medians of the interleaved repeats (wall and CPU each), and the fastest wall
            med = {k: (float(np.median([w for w, _ in v])), float(np.median([c for _, c in v])))
                   for k, v in times.items()}
            one = med["one_at_a_time"][0]
            _emit(what=f"{name}: {n} runs of 3 s, median of {repeats}", workers=workers, load_1min=load,
                  **{f"{k}_s": round(w, 2) for k, (w, _) in med.items()},
                  **{f"{k}_fastest_s": round(min(w for w, _ in v), 2) for k, v in times.items()},
                  **{f"{k}_cpu_s": round(c, 2) for k, (_, c) in med.items()},
                  # cores each way had (CPU / wall): on 2 idle cores a cluster of 2 has 2,
                  # one run at a time 1; what the others' load left shows here
                  **{f"{k}_cores": round(c / w, 2) for k, (w, c) in med.items()},
                  speedup_cluster=round(one / med["campaign_cluster"][0], 2),
                  speedup_serial_threads=round(one / med["campaign_serial_threads"][0], 2))
    finally:
        close_client(client)


def bench_overhead(n, workers):
    from isorock.analytic.fast import simulate_fast
    from isorock.validate.core.executor import close_client, local_client
    from isorock.validate.tools.campaign.run import run_cases
    cases = _contact_cases(n)
    simulate_fast(cases[0].system, cases[0].motion, duration=1.0)
    run_cases(cases[:1], ["analytic"])  # imports (pyarrow, the registry) out of the timing
    t = time.perf_counter()
    for c in cases:
        simulate_fast(c.system, c.motion, duration=c.duration)
    loop = time.perf_counter() - t
    t = time.perf_counter()
    run_cases(cases, ["analytic"])
    serial = time.perf_counter() - t
    t = time.perf_counter()
    client = local_client(workers)
    started = time.perf_counter()
    run_cases(cases, ["analytic"], client=client)
    first = time.perf_counter()
    # a one-task campaign lands on one worker; every worker loads the kernel on its first task
    client.run(lambda: __import__("isorock.analytic.fast") and None)
    warm = []
    for _ in range(3):
        a = time.perf_counter()
        run_cases(cases, ["analytic"], client=client)
        warm.append(time.perf_counter() - a)
    close_client(client)
    _emit(what=f"tiny campaign: {n} analytic runs of 3 s", plain_loop_s=round(loop, 3),
          run_cases_serial_s=round(serial, 3), cluster_startup_s=round(started - t, 2),
          dask_first_call_s=round(first - started, 2), dask_warm_call_s=round(min(warm), 3))


def main(argv=None):
    p = argparse.ArgumentParser(prog="python docs/scripts/campaign_throughput.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("what", choices=("spectrum", "kobe", "contact", "overhead"))
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    p.add_argument("-n", type=int, default=None, help="number of runs (kobe 400, contact 16, overhead 20)")
    p.add_argument("--repeats", type=int, default=5, help="kobe, contact: measurements per way (medians)")
    a = p.parse_args(argv)
    if a.what == "spectrum":
        bench_spectrum(a.workers)
    elif a.what == "kobe":
        bench_kobe(a.n or 400, a.repeats)
    elif a.what == "contact":
        bench_contact(a.n or 16, a.workers, a.repeats)
    else:
        bench_overhead(a.n or 20, a.workers)


if __name__ == "__main__":
    main()
