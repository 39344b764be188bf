"""SIGTERM at random points of a real `isorock run`: how each ends (docs/robustness.md).

    python docs/scripts/signal_fuzz.py [N] [MAX_DELAY_S] [--no-isolator]

Each run is signalled a random 0–MAX_DELAY_S seconds after the process catches SIGTERM
(its handler is installed: imports, parsing and the run itself follow). A run is counted
by how it ended: exit 143 with one line and nothing left; exit 2 (it had refused its input
before the signal: --no-isolator omits --fixed-base); killed by the signal after its end
was decided; anything else is printed.
"""
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter

n = int(sys.argv[1]) if len(sys.argv) > 1 else 40
max_delay = float(sys.argv[2]) if len(sys.argv) > 2 else 0.6
isolator = [] if "--no-isolator" in sys.argv else ["--fixed-base"]
ends = Counter()
for i in range(n):
    d = tempfile.mkdtemp()
    args = [sys.executable, "-m", "isorock.validate.cli.main", "run", "--height", "2", "--width", "0.7", "--mass", "3800",
            "--base-mass", "3800", *isolator, "--engine", "mujoco:full", "--motion", "sine:amp=0.3,freq=2,cycles=400",
            "--duration", "3600", "--json", "x.json", "--csv", "x.csv"]
    p = subprocess.Popen(args, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)

    def catches():
        for line in open(f"/proc/{p.pid}/status"):
            if line.startswith("SigCgt:"):
                return bool(int(line.split()[1], 16) & (1 << (signal.SIGTERM - 1)))
        return False
    while p.poll() is None and not catches():
        time.sleep(0.0005)
    time.sleep(random.uniform(0, max_delay))
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    one_line = len(err.strip().splitlines()) == 1 and "Traceback" not in err
    left = os.listdir(d)
    shutil.rmtree(d)
    if p.returncode == 143 and one_line and not left:
        ends["exit 143, one line, nothing left"] += 1
    elif p.returncode == 2 and one_line and not left:
        ends["exit 2 before the signal"] += 1
    elif p.returncode == -signal.SIGTERM and one_line and not left:
        ends["killed by SIGTERM after its end was decided, one line"] += 1
    else:
        ends["other"] += 1
        print(i, p.returncode, repr(err[-2000:]), left)
for k, v in ends.items():
    print(f"{v:4d}  {k}")
