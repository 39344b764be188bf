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

from isorock.validate.tools.campaign.run import PARTS

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


DASK_SPEC = """[campaign]
name = "dask-signal"
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


@pytest.mark.parametrize("sig, code, line", [(signal.SIGTERM, 143, "terminated by SIGTERM;"),
                                             (signal.SIGINT, 130, "interrupted;"),
                                             (signal.SIGHUP, 129, "terminated by SIGHUP;")])
def test_a_signal_to_a_dask_sweep_is_one_line_and_a_clean_exit(tmp_path, sig, code, line):
    """A sweep on a local Dask cluster (the default with workers), signalled once it has
    finished a chunk: its one line, exit 128 + signal, nothing after it. It printed Dask's and
    asyncio's tracebacks (a worker's heartbeat to a scheduler gone, a loop's callback torn
    down: up to 50 lines) and multiprocessing's 'leaked semaphore' warnings (issue 34)."""
    pytest.importorskip("pybullet")
    spec, out = tmp_path / "c.toml", tmp_path / "out"
    spec.write_text(DASK_SPEC)
    proc = subprocess.Popen([sys.executable, "-m", "isorock.validate.cli.main", "sweep", str(spec), "--out", str(out),
                             "--workers", "2", "--no-products"], stderr=subprocess.PIPE, text=True)
    while not list((out / PARTS).glob("*.parquet")) and proc.poll() is None:  # a state: a chunk is done
        time.sleep(0.05)
    assert proc.poll() is None, proc.stderr.read()
    proc.send_signal(sig)
    try:
        # a guard against a hang, not a measurement; the pipe closes when the last process
        # holding it (the workers, the resource tracker) has ended: all they print is here
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail(f"the sweep did not end on {sig.name}")
    lines = [ln for ln in err.replace("\r", "\n").splitlines() if ln.strip() and "%|" not in ln
             and not ln.startswith("sweep: about")]  # the progress bar's and the estimate's lines
    assert proc.returncode == code, err
    assert len(lines) == 1 and lines[0].startswith(f"isorock sweep: {line}"), err
