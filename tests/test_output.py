"""validate.io.output: a command writes only its own outputs, whole or not at all, with
the user's normal permissions; bad paths are refused before any work (issue 13)."""
import json
import os
import signal
import stat

import pytest

from isorock.analytic.errors import InputError
from isorock.validate.io.output import (MARKER, Outputs, Terminated, check_folder, signals_end_cleanly, write_folder_atomic,
                                     write_text)


def _fill(tmp):
    (tmp / "a.txt").write_text("new")


def _umask():
    m = os.umask(0o022)
    os.umask(m)
    return m


# --- folders (--out DIR) ------------------------------------------------------------

def test_folder_refuses_a_foreign_nonempty_folder_and_keeps_it(tmp_path):
    (tmp_path / "src").mkdir()
    (tmp_path / "NOTES.md").write_text("mine")
    with pytest.raises(InputError, match="did not write"):
        write_folder_atomic(tmp_path, _fill)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["NOTES.md", "src"]
    assert (tmp_path / "NOTES.md").read_text() == "mine"


def test_folder_refuses_a_file_and_the_empty_path(tmp_path):
    f = tmp_path / "important.csv"
    f.write_text("keep")
    with pytest.raises(InputError, match="not a folder"):
        write_folder_atomic(f, _fill)
    assert f.read_text() == "keep" and sorted(p.name for p in tmp_path.iterdir()) == ["important.csv"]
    with pytest.raises(InputError, match="folder path"):
        check_folder("")


def test_folder_new_empty_and_own_are_written_with_normal_permissions(tmp_path):
    new = tmp_path / "new"
    write_folder_atomic(new, _fill)
    assert (new / "a.txt").read_text() == "new" and (new / MARKER).is_file()
    assert stat.S_IMODE(new.stat().st_mode) == 0o777 & ~_umask()
    assert stat.S_IMODE((new / "a.txt").stat().st_mode) == 0o666 & ~_umask()
    # an empty folder is filled in place (same folder, its own permissions kept)
    empty = tmp_path / "empty"
    empty.mkdir(mode=0o750)
    ino = empty.stat().st_ino
    write_folder_atomic(empty, _fill)
    assert empty.stat().st_ino == ino and (empty / "a.txt").is_file()
    # isorock's own folder is replaced: old entries go, new ones come
    write_folder_atomic(new, lambda tmp: (tmp / "b.txt").write_text("b"))
    assert sorted(p.name for p in new.iterdir()) == sorted([MARKER, "b.txt"])
    assert json.loads((new / MARKER).read_text())["entries"] == ["b.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty", "new"]


def test_own_folder_with_a_user_file_added_is_refused(tmp_path):
    out = tmp_path / "rep"
    write_folder_atomic(out, _fill)
    (out / "my-notes.txt").write_text("mine")
    with pytest.raises(InputError, match="my-notes.txt"):
        write_folder_atomic(out, _fill)
    assert (out / "my-notes.txt").read_text() == "mine"


def test_failed_fill_leaves_nothing(tmp_path):
    def boom(tmp):
        (tmp / "half").write_text("x")
        raise RuntimeError("fail")
    with pytest.raises(RuntimeError):
        write_folder_atomic(tmp_path / "new" / "deeper", boom)
    assert list(tmp_path.iterdir()) == []
    own = tmp_path / "own"
    write_folder_atomic(own, _fill)
    with pytest.raises(RuntimeError):
        write_folder_atomic(own, boom)
    assert sorted(p.name for p in own.iterdir()) == sorted([MARKER, "a.txt"])


# --- files (--json, --csv, scene --out) ----------------------------------------------

def test_file_refusals_name_the_field(tmp_path):
    (tmp_path / "f").write_text("x")
    for path, why in ((tmp_path / "f" / "x.json", "is a file, not a folder"), (tmp_path, "is a folder"),
                      ("", "file path"), (tmp_path / "dangling", "symbolic link to nothing")):
        if "dangling" in str(path):
            os.symlink(tmp_path / "nowhere", path)
        with pytest.raises(InputError, match=why) as e:
            Outputs().file("json", path)
        assert str(e.value).startswith("json = ")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["dangling", "f"]


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes anywhere")
def test_read_only_folder_is_refused(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir(mode=0o555)
    with pytest.raises(InputError, match="not writable"):
        Outputs().file("json", ro / "x.json")


def test_symlink_is_written_through_not_replaced(tmp_path):
    target = tmp_path / "real.json"
    target.write_text("old")
    os.chmod(target, 0o640)
    link = tmp_path / "link.json"
    os.symlink(target, link)
    write_text(link, "new")
    assert link.is_symlink() and target.read_text() == "new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # an existing file keeps its mode


def test_new_file_has_normal_permissions_not_0600(tmp_path):
    write_text(tmp_path / "x.json", "{}")
    assert stat.S_IMODE((tmp_path / "x.json").stat().st_mode) == 0o666 & ~_umask()


def test_character_device_is_written_not_replaced(char_device):
    null = char_device("null")
    write_text(null, "x")
    assert stat.S_ISCHR(os.stat(null).st_mode)


def test_full_device_is_an_input_error(char_device):
    full = char_device("full")
    with pytest.raises(InputError, match="cannot be written"):
        write_text(full, "x" * 100000)
    assert stat.S_ISCHR(os.stat(full).st_mode)


def test_fifo_is_written_as_a_stream(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    r = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    try:
        write_text(fifo, "hello")
        assert os.read(r, 100) == b"hello"
    finally:
        os.close(r)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_stdout_dash(capfdbinary):
    write_text("-", "to stdout\n")
    assert capfdbinary.readouterr().out == b"to stdout\n"


def test_same_path_twice_is_refused(tmp_path):
    out = Outputs()
    out.file("json", tmp_path / "x")
    with pytest.raises(InputError, match="also given as json"):
        out.file("csv", str(tmp_path / "." / "x"))
    out = Outputs()
    out.file("json", "-")
    with pytest.raises(InputError, match="also given"):
        out.file("csv", "-")


def test_all_or_none_when_the_second_output_fails(tmp_path, char_device):
    full = char_device("full")
    j = tmp_path / "x.json"
    with pytest.raises(InputError):
        with Outputs() as out:
            a, b = out.file("json", j), out.file("csv", full)
            a.write_text("{}")
            b.write_text("x" * 100000)
            out.commit()
    assert not j.exists() and stat.S_ISCHR(os.stat(full).st_mode)


def test_sigterm_while_staging_removes_everything(tmp_path):
    def killed(tmp):
        (tmp / "half").write_text("x")
        os.kill(os.getpid(), signal.SIGTERM)
    with signals_end_cleanly():
        with pytest.raises(Terminated) as e:
            with Outputs() as out:
                j = out.file("json", tmp_path / "x.json")
                f = out.folder("out", tmp_path / "rep")
                j.write_text("{}")
                f.write(killed)
                out.commit()
    assert e.value.signum == signal.SIGTERM
    assert list(tmp_path.iterdir()) == []
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # handlers restored
