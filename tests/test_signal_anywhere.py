"""A signal that arrives anywhere ends the command the same way: one line, exit
128 + signal (130 for SIGINT), nothing left behind. Found on a loaded machine: SIGTERM
arrived while the command lazily imported NumPy, whose C import turned the handler's
Terminated into `ImportError: PyCapsule_Import could not import module "datetime"`, and
main printed a traceback and exited 1. The commands here stand in for such code,
deterministically: they signal themselves inside code that re-wraps or swallows what the
signal raised."""
from __future__ import annotations

import os
import signal

import pytest

from isorock.validate.cli import main as cli
from isorock.validate.io.output import Outputs

BETA = ["beta", "--slenderness", "3", "--mass-ratio", "1"]


def _rewrapped(sig):
    def command(a):
        try:
            os.kill(os.getpid(), sig)
        except BaseException as e:  # what NumPy's C import did: the signal's exception re-wrapped
            raise ImportError('PyCapsule_Import could not import module "datetime"') from e
        return 0
    return command


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGHUP, 129), (signal.SIGINT, 130)])
def test_a_signal_rewrapped_by_an_import_is_still_that_signal(monkeypatch, capsys, sig, code):
    monkeypatch.setattr(cli, "cmd_beta", _rewrapped(sig))
    assert cli.main(BETA) == code
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert (sig.name if sig != signal.SIGINT else "interrupted") in err
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # handlers restored


def test_a_signal_swallowed_by_the_command_still_ends_it_with_nothing_written(monkeypatch, capsys, tmp_path):
    """Code that swallows the signal's exception (a fallback on ImportError) and goes on:
    its outputs are not committed, and the command still ends as signalled."""
    target = tmp_path / "x.json"

    def command(a):
        with Outputs() as out:
            j = out.file("json", target)
            try:
                os.kill(os.getpid(), signal.SIGTERM)
            except BaseException:  # swallowed, as `except ImportError: continue` would
                pass
            j.write_text("{}")
            out.commit()
        return 0
    monkeypatch.setattr(cli, "cmd_beta", command)
    assert cli.main(BETA) == 143
    err = capsys.readouterr().err
    assert "SIGTERM" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert list(tmp_path.iterdir()) == []


def test_an_error_without_a_signal_is_not_taken_for_one(monkeypatch, capsys):
    """The record of a signal belongs to one command: a later command's own error is its
    own (a traceback for a bug, as before), not the earlier command's signal."""
    monkeypatch.setattr(cli, "cmd_beta", _rewrapped(signal.SIGTERM))
    assert cli.main(BETA) == 143
    capsys.readouterr()
    monkeypatch.undo()
    assert cli.main(BETA) == 0


CHILD_OUTLIVES = """
import os, signal, subprocess, sys
from isorock.validate.cli import main as cli
PID_FILE = sys.argv[1]  # read before sys.argv becomes the command's (it wrote a file named 'beta' here)

def command(a):
    # as glfw's library probe (imported with MuJoCo): a child that answers on a pipe once
    # its input ends; its stderr is the command's own
    child = subprocess.Popen([sys.executable, "-c", "import sys; sys.stdin.read(); print('x' * 65536)"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    open(PID_FILE, "w").write(str(child.pid))
    os.kill(os.getpid(), signal.SIGTERM)
    child.communicate()
    return 0

cli.cmd_beta = command
sys.argv = ["isorock", "beta", "--slenderness", "3", "--mass-ratio", "1"]
sys.exit(cli.main())
"""


def test_a_child_of_a_stopped_command_does_not_write_after_it(tmp_path):
    """Found by signalling `run` at random points: glfw's probe (a child process, started
    while MuJoCo is imported) wrote its answer after the stopped command had exited, and
    its BrokenPipeError traceback followed the command's one line. A command a signal
    ends ends its own children first. The state waited for is the child's end (stderr
    closes when every process holding it has exited), not a clock."""
    import subprocess
    import sys
    pid_file = tmp_path / "child"
    p = subprocess.run([sys.executable, "-c", CHILD_OUTLIVES, str(pid_file)], capture_output=True, text=True,
                       timeout=120, cwd=tmp_path)  # and nothing written outside its own folder
    assert sorted(x.name for x in tmp_path.iterdir()) == ["child"]
    assert p.returncode == 143, p.stderr
    assert "Traceback" not in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr
