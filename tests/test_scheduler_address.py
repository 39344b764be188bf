"""--scheduler at something that is not a Dask scheduler is one bounded line (issue 24,
item 12): an HTTP server that waits for a request (the handshake hung for ever), a
service that greets with "HTTP/1.1 403" (its bytes read as a frame length: "Unable to
allocate 3.07 EiB"), an address that is not one (a traceback). The oracle is a real
server in this process: what it sends is known."""
from __future__ import annotations

import socket
import subprocess
import sys
import threading

import pytest

from test_campaign import write_spec


def _server(greeting: bytes | None):
    """A TCP server on a free port that accepts and sends `greeting` (None: nothing),
    then holds the connection open."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held = []

    def serve():
        while True:
            try:
                conn, _ = srv.accept()
            except OSError:
                return
            held.append(conn)
            if greeting:
                conn.sendall(greeting)
    threading.Thread(target=serve, daemon=True).start()
    return srv


def test_a_server_that_is_not_dask_is_refused_in_bounded_time(tmp_path):
    """A service that greets with "HTTP/1.1 403", run as a user runs the command (a process of
    its own, bounded by a hang guard): one line, exit 2, nothing written."""
    srv = _server(b"HTTP/1.1 403 Forbidden\r\nContent-Length: 0\r\n\r\n")
    try:
        spec = write_spec(tmp_path, more="")
        address = "tcp://127.0.0.1:%d" % srv.getsockname()[1]
        out = subprocess.run([sys.executable, "-m", "isorock.validate.cli.main", "sweep", str(spec), "--out",
                              str(tmp_path / "out"), "--scheduler", address],
                             capture_output=True, text=True, timeout=120)  # a hang guard, not a measurement
    finally:
        srv.close()
    assert out.returncode == 2, out.stderr
    assert out.stderr.count("\n") == 1 and "--scheduler" in out.stderr and "Dask scheduler" in out.stderr, out.stderr
    assert "answered b'HTTP/1.1'" in out.stderr, out.stderr
    assert not (tmp_path / "out").exists()


def test_a_server_that_says_nothing_is_refused_when_its_greeting_time_is_up(tmp_path, capsys, monkeypatch):
    """An HTTP server waits for a request and says nothing: refused when GREETING_TIMEOUT is up
    (10 s; here 0.3 s, so that the suite does not wait out the real one), in one line naming it."""
    from isorock.validate.cli.main import main
    from isorock.validate.core import executor
    monkeypatch.setattr(executor, "GREETING_TIMEOUT", 0.3)
    srv = _server(None)
    try:
        spec = write_spec(tmp_path, more="")
        code = main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--scheduler",
                     "tcp://127.0.0.1:%d" % srv.getsockname()[1]])
    finally:
        srv.close()
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "no Dask handshake within 0.3 s" in err, err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("address", ["not a url", "tcp://", "tcp://127.0.0.1:notaport", "http://[::1"])
def test_an_address_that_is_not_one_is_one_line(tmp_path, capsys, address):
    from isorock.validate.cli.main import main
    spec = write_spec(tmp_path, more="")
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--scheduler", address]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--scheduler" in err, err
