"""Run every hostile input of tests/adversarial_cases.py as a real `isorock` process and
print the table for issues 13, 24 and 34's closing notes (rounds one to four:
tests/adversarial_cases.py, adversarial_round_two.py, _three.py, _four.py): per class, how many cases, how many ended
with exit 2 and one line, how many gave the correct result, how many anything else
(traceback, hang, wrong result, a file touched outside the command's own outputs).

    python scripts/adversarial_table.py [--jobs 2] [--markdown] [--classes campaign-files,cache]

Each case runs in a fresh temporary folder; the folder it is started from, /dev/null
and /dev/full are checked unchanged afterwards. Exit code 1 when any case is "other".
"""
from __future__ import annotations

import argparse
import os
import stat
import sys
import tempfile
from collections import Counter, defaultdict
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from adversarial_cases import cases, run_as_process, snapshot  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--jobs", type=int, default=2, help="cases run at once (default 2)")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--classes", help="only these classes, comma-separated (default: all)")
    ap.add_argument("--match", help="only cases whose name contains this")
    a = ap.parse_args()
    here = Path.cwd()
    before = snapshot(here)
    devices = {p: os.stat(p).st_mode for p in ("/dev/null", "/dev/full")}
    all_cases = [c for c in cases() if (not a.classes or c.cls in a.classes.split(","))
                 and (not a.match or a.match in c.name)]

    # the compiled kernels built here, before any case's clock starts (tests/test_adversarial.py
    # does the same): on a fresh clone a case would spend its time limit building one
    from test_adversarial import _build_kernels
    _build_kernels()

    def one(case):
        with tempfile.TemporaryDirectory(prefix="isorock-adversarial-") as d:
            outcome = run_as_process(case, Path(d), sys.executable)
            return case, outcome, outcome.verdict(case, Path(d))

    with ThreadPoolExecutor(a.jobs) as pool:
        results = list(pool.map(one, all_cases))
    rows = defaultdict(Counter)
    others = []
    for case, outcome, verdict in results:
        r = rows[case.cls]
        r["count"] += 1
        r[verdict if not verdict.startswith("other") else "other"] += 1
        r["tracebacks"] += outcome.traceback
        r["hangs"] += outcome.hung
        r["touched"] += bool(outcome.touched)
        if verdict.startswith("other"):
            others.append(f"{case.cls}: {case.name}: {verdict}")
    outside = sorted(k for k in before.keys() | snapshot(here).keys() if before.get(k) != snapshot(here).get(k))
    devices_ok = all(os.stat(p).st_mode == m and stat.S_ISCHR(m) for p, m in devices.items())

    cols = ("count", "exit 2", "correct result", "other", "tracebacks", "hangs", "touched")
    total = Counter()
    lines = []
    for cls, r in rows.items():
        total.update(r)
        lines.append((cls, *[r[c] for c in cols]))
    lines.append(("total", *[total[c] for c in cols]))
    if a.markdown:
        print("| class | " + " | ".join(cols) + " |")
        print("|---|" + "---:|" * len(cols))
        for ln in lines:
            print("| " + " | ".join(str(x) for x in ln) + " |")
    else:
        print(f"{'class':16s}" + "".join(f"{c:>16s}" for c in cols))
        for ln in lines:
            print(f"{ln[0]:16s}" + "".join(f"{x:>16d}" for x in ln[1:]))
    print(f"\nfiles changed in the starting folder: {len(outside)}; /dev/null and /dev/full still devices: "
          f"{'yes' if devices_ok else 'NO'}")
    for o in others:
        print("  " + o)
    return 1 if others or outside or not devices_ok else 0


if __name__ == "__main__":
    sys.exit(main())
