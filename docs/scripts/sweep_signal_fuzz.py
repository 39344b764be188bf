"""A signal at random points of a real `isorock sweep` on a local Dask cluster: how each ends
(docs/robustness.md, round three).

    python docs/scripts/sweep_signal_fuzz.py [N] [MAX_DELAY_S]

Each run is a campaign of 48 PyBullet runs on 2 worker processes (the default with
workers: Dask), sent SIGTERM, SIGINT or SIGHUP (in turn) a random 0–MAX_DELAY_S seconds after
the process catches SIGTERM. A run is counted by how it ended: exit 128 + signal with its one
line and nothing else on stderr (the progress bar's and the estimate's lines aside), or
anything else, printed. Everything the workers and multiprocessing's resource tracker print
is read too: the pipe closes when the last of them has ended.
"""
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

SPEC = """[campaign]
name = "fuzz"
contact_chunk = 1

[systems]
alpha = 0.25
size = 1.0
base = "fixed"

[motions]
type = "pulse"
pulse = "sine"
frequency_ratio = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0]
amplitude_ratio = [0.9, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0]

[duration]
tail = 15.0

[[engines]]
name = "bullet"
"""
SIGNALS = (signal.SIGTERM, signal.SIGINT, signal.SIGHUP)

n = int(sys.argv[1]) if len(sys.argv) > 1 else 12
max_delay = float(sys.argv[2]) if len(sys.argv) > 2 else 15.0
ends = Counter()
for i in range(n):
    d = Path(tempfile.mkdtemp())
    (d / "c.toml").write_text(SPEC)
    sig = SIGNALS[i % len(SIGNALS)]
    p = subprocess.Popen([sys.executable, "-m", "isorock.validate.cli.main", "sweep", "c.toml", "--out", "out",
                          "--workers", "2", "--no-products"], cwd=d, stderr=subprocess.PIPE, text=True)

    def catches():
        for line in open(f"/proc/{p.pid}/status"):
            if line.startswith("SigCgt:"):
                return bool(int(line.split()[1], 16) & (1 << (signal.SIGTERM - 1)))
        return False
    while p.poll() is None and not catches():
        time.sleep(0.0005)
    delay = random.uniform(0, max_delay)
    time.sleep(delay)
    p.send_signal(sig)
    _, err = p.communicate(timeout=120)
    lines = [ln for ln in err.replace("\r", "\n").splitlines()
             if ln.strip() and "%|" not in ln and not ln.startswith("sweep: about")]
    shutil.rmtree(d)
    if p.returncode == 128 + sig and len(lines) == 1 and lines[0].startswith("isorock sweep: "):
        ends[f"exit {128 + sig}, one line"] += 1
    elif p.returncode == 0 and len(lines) == 1 and lines[0].startswith("out: "):
        ends["finished before the signal"] += 1
    else:
        ends["other"] += 1
        print(i, sig.name, f"{delay:.1f} s", p.returncode, repr("\n".join(lines)[-1500:]), flush=True)
for k, v in sorted(ends.items()):
    print(f"{v:4d}  {k}")
