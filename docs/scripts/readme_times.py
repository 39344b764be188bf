"""Every time the README states beside a command, measured: each `isorock …` line of the
README's bash blocks that carries a time in its comment (`# ~15 s`, `(~30 s)` on the line
above, `~7 min`) is run as written, from the repository's root, with its outputs sent to a
temporary folder (`--out`, appended: the last one given wins), and timed whole as a process:

    python docs/scripts/readme_times.py [--repeats N] [--skip drake] [--tests]

Prints one row per command: the time the README states, the measured median wall time, their
ratio, the CPU seconds of the command and the machine's load average (1 min) before and after,
then the verdict: every stated time reproduced within 1.5× (issue 39's rule) or the rows that
are not. --tests times the README's test command too (`python -m pytest -q`, minutes).
Exit 0 when every row holds, 1 otherwise. The load matters: quote it with the numbers."""
from __future__ import annotations

import argparse
import math
import os
import re
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: a stated time: "~15 s", "≈ 4 min", "~7 min", "(~30 s)"
STATED = re.compile(r"[~≈]\s*(\d+(?:\.\d+)?)\s*(s|min)\b")
ALLOWED = 1.5
#: stated in the README's prose, not beside a command: the main job ("under a minute on 2 cores once installed"),
#: and the paper's block over the FEMA P695 set in the command table ("75 s wall at load 7–10")
PROSE = [("isorock validate", 60.0), ("isorock design", 75.0)]


def readme_commands(text: str) -> list[tuple[str, float]]:
    """(command, stated seconds) for every `isorock` line of a bash block with a stated time in
    its own comment or in the comment lines just above it; continuation lines joined."""
    lines, in_bash = [], False
    for line in text.splitlines():
        if line.startswith("```"):
            in_bash = line.strip() == "```bash"
            lines.append("")  # a block's end parts its comments from the next block's
        elif in_bash:
            if lines and lines[-1].rstrip().endswith("\\"):
                lines[-1] = lines[-1].rstrip()[:-1].rstrip() + " " + line.strip()
            else:
                lines.append(line.strip())
    out, comments = [], []
    for line in lines:
        if line.startswith("#"):
            comments.append(line)
            continue
        if line.startswith("isorock "):
            command, _, own = line.partition("#")
            m = STATED.search(own) or STATED.search(" ".join(comments))
            if m is not None:
                out.append((command.strip(), float(m.group(1)) * (60 if m.group(2) == "min" else 1)))
        comments = []
    return out


def run_timed(argv: list[str], cwd: Path) -> tuple[float, float, int]:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    rc = subprocess.run(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, rc


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--skip", action="append", default=[], help="skip commands containing this text")
    p.add_argument("--tests", action="store_true", help="time the README's test command too")
    a = p.parse_args()
    rows = []
    commands = PROSE + readme_commands((ROOT / "README.md").read_text(encoding="utf-8"))
    isorock = str(Path(sys.executable).with_name("isorock"))
    with tempfile.TemporaryDirectory() as tmp:
        for i, (command, stated) in enumerate(commands):
            if any(s in command for s in a.skip):
                continue
            argv = [isorock, *shlex.split(command)[1:]]
            walls, cpus, rcs, loads = [], [], [], [os.getloadavg()[0]]
            for r in range(a.repeats):
                wall, cpu, rc = run_timed([*argv, "--out", f"{tmp}/out-{i}-{r}"], ROOT)
                walls.append(wall), cpus.append(cpu), rcs.append(rc)
                loads.append(os.getloadavg()[0])
            rows.append((command, stated, statistics.median(walls), statistics.median(cpus), sorted(set(rcs)),
                         min(loads), max(loads)))
            print(f"{statistics.median(walls):7.1f} s (stated {stated:g} s) {command}", file=sys.stderr, flush=True)
        if a.tests:
            loads = [os.getloadavg()[0]]
            wall, cpu, rc = run_timed([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"], ROOT)
            loads.append(os.getloadavg()[0])
            rows.append(("python -m pytest -q", math.nan, wall, cpu, [rc], min(loads), max(loads)))
    print("| command | stated | measured (median wall) | ratio | CPU s | exit | load (1 min) |")
    print("|---|---:|---:|---:|---:|---|---|")
    bad = []
    for command, stated, wall, cpu, rcs, lo, hi in rows:
        ratio = wall / stated if stated == stated else float("nan")
        if ratio > ALLOWED:
            bad.append(command)
        print(f"| `{command}` | {stated:g} s | {wall:.0f} s | {ratio:.2f} | {cpu:.0f} | {','.join(map(str, rcs))} | "
              f"{lo:.1f}–{hi:.1f} |")
    print()
    print(f"{len(rows) - len(bad)} of {len(rows)} stated times hold within {ALLOWED}×"
          + (": " + "; ".join(bad) + " do not" if bad else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
