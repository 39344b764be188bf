"""A stuck sweep hears SIGTERM, SIGINT and SIGHUP, and says what it keeps (issue 24,
item 10). "Stuck": the compiled kernel of the third chunk never returns (a stand-in for
a run that takes hours: its threads ignore signals). The sweep must end at once, exit
128 + signal (130 for SIGINT), keep the two chunks it finished as parts and say so,
not "no output written"."""
from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

from isorock.campaign.run import PARTS

from test_campaign import write_spec

STUCK = """
import sys, threading
from pathlib import Path
from isorock.analytic import fast
state = Path(sys.argv[1])
calls = []
original_batch, original_cases = fast.simulate_batch, fast._run_cases
def counting(*a, **k):
    calls.append(1)
    return original_batch(*a, **k)
def stuck(args, lo, hi, failures):
    if len(calls) < 3:
        return original_cases(args, lo, hi, failures)
    state.write_text("stuck")
    threading.Event().wait()  # never returns, as a kernel of hours
fast.simulate_batch, fast._run_cases = counting, stuck
import isorock.validate.core.executor  # noqa: the sweep imports simulate_batch from fast at call time
from isorock.validate.cli.main import main
sys.argv = ["isorock", "sweep", sys.argv[2], "--out", sys.argv[3], "--workers", "0", "--no-products"]
sys.exit(main())
"""


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130), (signal.SIGHUP, 129)])
def test_a_stuck_sweep_ends_on_a_signal_and_says_what_it_keeps(tmp_path, sig, code):
    spec = write_spec(tmp_path, more="")  # analytic only: 18 cases in chunks of 7 → 3 chunks
    state, out = tmp_path / "state", tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-c", STUCK, str(state), str(spec), str(out)],
                            stderr=subprocess.PIPE, text=True)
    while not state.exists() and proc.poll() is None:  # wait for the state: the third chunk is stuck
        time.sleep(0.01)
    assert proc.poll() is None, proc.stderr.read()
    proc.send_signal(sig)
    try:
        _, err = proc.communicate(timeout=60)  # a guard against a hang, not a measurement
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail(f"the sweep did not end on {sig.name}")
    assert proc.returncode == code, err
    assert "Traceback" not in err, err
    last = err.strip().splitlines()[-1]  # the lines before it are the progress bar's
    parts = sorted((out / PARTS).glob("*.parquet"))
    assert len(parts) == 2
    assert "no output written" not in last and "2 finished chunks kept" in last and "resume" in last, err
    assert not list(out.glob(".isorock-staging*")) and not list((out / PARTS).glob(".isorock-staging*"))
