"""The one home for writing a command's outputs: nothing lost, nothing half-written.

Every output of one command is declared before the work starts (`Outputs.file`,
`Outputs.folder`: bad paths are refused at once, with exit code 2, before minutes of
simulation), staged beside its target while the command writes it, and committed
together at the end; an error or a signal before the commit leaves nothing behind.

What a command may write to:
- a file path: a new file, or an existing regular file (replaced whole; a symbolic link
  is written through, never replaced); `-` is standard output; an existing character
  device or pipe (/dev/null, a FIFO, /proc/self/fd/1) is written to as a stream; a
  folder, a block device, a socket, a path under a file, an unwritable folder or ''
  are refused.
- a folder path (`--out DIR`): a new folder, an existing empty folder (filled in place),
  or a folder this module wrote itself, recognised by its marker file MARKER listing the
  entries written; a folder holding anything else, a file, or '' is refused.
  Files and folders get the user's normal permissions (0666/0777 less the umask).
"""
from __future__ import annotations

import json
import math
import os
import shutil
import signal
import stat
import sys
import tempfile
import threading
import time
from contextlib import contextmanager
from pathlib import Path


from ...analytic.errors import InputError

#: the file inside every folder isorock writes: it marks the folder as replaceable
MARKER = ".isorock-output"
#: prefix of staging files and folders (hidden, removed on any failure)
STAGING_PREFIX = ".isorock-staging-"
#: signals that end a command: it cleans up and exits 128 + the signal number
TERMINATING_SIGNALS = (signal.SIGTERM, signal.SIGHUP)


def _clean(obj):
    """JSON-safe: NumPy scalars to Python, NaN/inf to None (JSON has neither)."""
    import numpy as np  # lazy: every command loads this module, `beta` needs no NumPy

    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return [_clean(v) for v in obj.tolist()]
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def to_json(data) -> str:
    return json.dumps(_clean(data), indent=2, allow_nan=False)


# --- signals ------------------------------------------------------------------------------

class Terminated(BaseException):
    """SIGTERM/SIGHUP arrived: unwinds like KeyboardInterrupt so staged outputs are removed."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum

    @property
    def name(self) -> str:
        return signal.Signals(self.signum).name


#: the signal this command received while signals_end_cleanly was active, if any: the
#: record outlives the exception its handler raised, which code on the way up may re-wrap
#: (NumPy's C import turned Terminated into an ImportError) or swallow
_received: list[int] = []


def signal_received() -> int | None:
    """The signal that is ending this command, or None: any exception raised after it,
    whatever its type, is that signal's doing, and no output may be committed."""
    return _received[0] if _received else None


def raise_for_signal(signum: int):
    """The exception a received signal raises: KeyboardInterrupt for SIGINT, Terminated
    for the others."""
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)


#: how often a signal whose exception was swallowed is sent again until it is raised (s)
RESEND_EVERY = 0.001


@contextmanager
def signals_end_cleanly():
    """While active, SIGTERM and SIGHUP raise Terminated and SIGINT KeyboardInterrupt in
    this process (so every `finally` and staging cleanup runs), and each is recorded
    (signal_received) so that it still ends the command if the exception is lost on the
    way. A process forked from it (stress runs cases in children) dies of the signal as
    usual (SIGINT: KeyboardInterrupt, as Python's default) instead of unwinding its
    parent's stack. It yields `settle`: called, signals are recorded and no longer raise.

    Raised where Python can only print it and swallow it ("Exception ignored in", with a
    traceback: inside a garbage-collector callback, as Dask's scheduler installs one, or a
    finalizer), the signal's exception is not printed (the unraisable hook below) and the
    signal is sent again to the main thread until its handler raises where it can end the
    command (issue 34)."""
    owner = os.getpid()
    pending: list[int] = []  # a signal whose exception was swallowed, to be raised again

    def handler(signum, frame):
        if os.getpid() != owner:
            if signum == signal.SIGINT:
                signal.default_int_handler(signum, frame)
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)
            return
        if not _received:
            _received.append(signum)
        if settled or _within(frame, unraisable.__code__):
            return  # recorded; raised inside the hook it would be printed (it is sent again)
        pending.clear()
        raise_for_signal(signum)

    settled = False

    def settle():
        """From here on a signal is only recorded: the command's end is being decided,
        and an exception raised there would escape as a traceback."""
        nonlocal settled
        settled = True

    def resend():
        main = threading.main_thread().ident
        while pending and not settled:
            time.sleep(RESEND_EVERY)
            if pending and not settled:
                signal.pthread_kill(main, pending[0])  # to the main thread: its blocking wait ends too

    def unraisable(report):
        if isinstance(report.exc_value, (Terminated, KeyboardInterrupt)) and _received and os.getpid() == owner:
            if not settled and not pending:
                pending.append(_received[0])
                threading.Thread(target=resend, daemon=True, name="isorock-resend-signal").start()
            return
        hook(report)

    _received.clear()  # a record belongs to one command
    previous = {}
    hook, sys.unraisablehook = sys.unraisablehook, unraisable
    try:
        for s in (*TERMINATING_SIGNALS, signal.SIGINT):
            previous[s] = signal.signal(s, handler)
    except ValueError:  # not the main thread: signals cannot be caught here
        pass
    try:
        yield settle
    finally:
        for s, h in previous.items():
            signal.signal(s, h)
        sys.unraisablehook = hook
        pending.clear()


def _within(frame, code) -> bool:
    """Is `frame`, or any frame that called it, running `code`?"""
    while frame is not None:
        if frame.f_code is code:
            return True
        frame = frame.f_back
    return False


@contextmanager
def _signals_held():
    """No signal may interrupt a commit half-way: held until it is done."""
    held = set(TERMINATING_SIGNALS) | {signal.SIGINT}
    try:
        old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    except (AttributeError, ValueError):
        old = None
    try:
        yield
    finally:
        if old is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


# --- permissions --------------------------------------------------------------------------

def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _file_mode() -> int:
    return 0o666 & ~_umask()


def _folder_mode() -> int:
    return 0o777 & ~_umask()


def _refuse(field: str, path, allowed: str):
    raise InputError(f"{field} = {str(path)!r}: {allowed}")


def _os_failure(field: str, path, e: OSError):
    return InputError(f"{field} = {str(path)!r}: cannot be written ({e.strerror or e})")


def _missing_parents(field: str, path: Path) -> list[Path]:
    """The folders to create for `path` (outermost first); the nearest existing ancestor
    must be a writable folder."""
    missing = []
    parent = path.parent
    while not parent.exists():
        if parent.is_symlink():
            _refuse(field, path, f"its folder {str(parent)!r} is a symbolic link to nothing")
        missing.append(parent)
        parent = parent.parent
    if not parent.is_dir():
        _refuse(field, path, f"{str(parent)!r} is a file, not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        _refuse(field, path, f"the folder {str(parent)!r} is not writable")
    return missing[::-1]


def _make_parents(folders: list[Path], created: list[Path]) -> None:
    for d in folders:
        if not d.exists():
            d.mkdir(mode=_folder_mode())
            created.append(d)


def _remove_folders(created: list[Path]) -> None:
    """Remove the folders a discarded output made, innermost first (left where not empty)."""
    for d in reversed(created):
        try:
            d.rmdir()
        except OSError:
            pass


# --- staging names: the writer's process id, so a killed writer's leftovers can be known ---

def _staging_prefix(name: str) -> str:
    return f"{STAGING_PREFIX}{os.getpid()}-{name}."


def clear_stale_staging(folder: Path) -> None:
    """Remove the staging files and folders of writers that no longer run (killed with
    SIGKILL before they could clean up): `.isorock-staging-PID-…` whose PID is gone."""
    try:
        entries = list(Path(folder).iterdir())
    except OSError:
        return
    for e in entries:
        rest = e.name[len(STAGING_PREFIX):] if e.name.startswith(STAGING_PREFIX) else ""
        pid = rest.split("-", 1)[0]
        if not pid.isdigit() or "-" not in rest:
            continue  # another shape: not ours to judge
        try:
            os.kill(int(pid), 0)
            continue  # its writer still runs
        except ProcessLookupError:
            pass
        except OSError:
            continue
        try:
            shutil.rmtree(e) if e.is_dir() and not e.is_symlink() else e.unlink()
        except OSError:
            pass


# --- targets ------------------------------------------------------------------------------

class FileOutput:
    """One output file of a command: stage it with write_text/write(callable), then the
    command's Outputs commits it."""

    def __init__(self, field: str, path: str, exclusive: bool = False):
        self.field, self.given = field, path
        self.staged: str | None = None
        self._created: list[Path] = []
        #: a new file only: refused if it exists now, and created exclusively at commit,
        #: so a file that appears there meanwhile (another run's, a user's) is kept
        self.exclusive = exclusive
        if path is None or str(path) == "":
            _refuse(field, path, "must be a file path, or - for standard output")
        path = str(path)
        if path == "-":
            self.kind, self.target, self.identity = "stdout", None, ("stdout",)
            return
        if path.endswith(("/", os.sep)):  # `--out newdir/` wrote a file named newdir
            _refuse(field, path, "ends in a folder separator; give a file path (e.g. newdir/scene.xml)")
        p = Path(path)
        if exclusive and os.path.lexists(p):
            _refuse(field, path, "exists; give a new file (isorock does not replace files it did not write)")
        if os.path.lexists(p):
            try:
                st = os.stat(p)
            except OSError:
                _refuse(field, path, "is a symbolic link to nothing; give a file path")
            if stat.S_ISDIR(st.st_mode):
                _refuse(field, path, "is a folder; give a file path")
            self.identity = (st.st_dev, st.st_ino)
            if stat.S_ISCHR(st.st_mode) or stat.S_ISFIFO(st.st_mode):
                if not os.access(p, os.W_OK):
                    _refuse(field, path, "is a device or pipe that is not writable")
                self.kind, self.target = "stream", p
                return
            if not stat.S_ISREG(st.st_mode):
                _refuse(field, path, "is not a regular file, a character device or a pipe")
            # through a symbolic link to the file it points at: the link stays a link
            self.kind, self.target = "file", Path(os.path.realpath(p))
            self._mode = stat.S_IMODE(st.st_mode)
            if not os.access(self.target.parent, os.W_OK | os.X_OK):
                _refuse(field, path, f"the folder {str(self.target.parent)!r} is not writable")
            self._parents = []
            return
        self.kind, self.target = "file", Path(os.path.abspath(p))
        self.identity = ("new", str(self.target))
        self._mode = None
        missing = _missing_parents(field, self.target)
        if missing:  # a typo in a folder name is not a folder to make without a word
            _refuse(field, path, f"its folder {str(missing[-1])!r} does not exist; create it first")
        self._parents = []

    # staging ---------------------------------------------------------------------------
    def write(self, writer) -> None:
        """writer(path) writes the whole output to `path` (a staging file)."""
        self.discard()
        try:
            if self.kind == "file":
                _make_parents(self._parents, self._created)
                clear_stale_staging(self.target.parent)
                fd, tmp = tempfile.mkstemp(prefix=_staging_prefix(self.target.name), dir=self.target.parent)
            else:  # streams are written at commit, from a private staging copy
                fd, tmp = tempfile.mkstemp(prefix=STAGING_PREFIX)
            os.close(fd)
            self.staged = tmp
            writer(tmp)
        except OSError as e:
            self.discard()
            raise _os_failure(self.field, self.given, e) from None
        except BaseException:
            self.discard()
            raise

    def write_text(self, text: str) -> None:
        self.write(lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))

    def commit(self) -> None:
        if self.staged is None:
            return
        try:
            if self.kind == "file":
                os.chmod(self.staged, self._mode if self._mode is not None else _file_mode())
                if self.exclusive:  # claim the name first: O_EXCL fails if anything holds it
                    try:
                        os.close(os.open(self.target, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600))
                    except FileExistsError:
                        _refuse(self.field, self.given, "was created by something else while this command ran; "
                                                        "not replacing it (nothing written)")
                os.replace(self.staged, self.target)
                self.staged = None
                self._created = []
            else:
                with open(self.staged, "rb") as src:
                    if self.kind == "stdout":
                        sys.stdout.flush()
                        shutil.copyfileobj(src, sys.stdout.buffer)
                        sys.stdout.buffer.flush()
                    else:
                        with open(self.target, "wb") as dst:
                            shutil.copyfileobj(src, dst)
                self.discard()
        except OSError as e:
            raise _os_failure(self.field, self.given, e) from None

    def discard(self) -> None:
        if self.staged is not None:
            try:
                os.unlink(self.staged)
            except FileNotFoundError:
                pass
            self.staged = None
        _remove_folders(self._created)
        self._created = []


class FolderOutput:
    """One output folder (`--out DIR`): `staging()` is the folder to fill; the commit
    puts its entries in place with the marker, replacing only what isorock wrote."""

    def __init__(self, field: str, path: str):
        self.field, self.given = field, path
        self._staging: Path | None = None
        self._created: list[Path] = []
        if path is None or str(path) == "":
            _refuse(field, path, "must be a folder path ('.' for the working folder)")
        p = Path(os.path.abspath(str(path)))
        if os.path.lexists(p):
            if not p.exists():
                _refuse(field, path, "is a symbolic link to nothing; give a folder path")
            p = Path(os.path.realpath(p))
            if not p.is_dir():
                _refuse(field, path, "is not a folder; give a new, empty or earlier isorock output folder")
            foreign = _foreign_entries(p)
            if foreign:
                shown = ", ".join(sorted(foreign)[:3]) + (", …" if len(foreign) > 3 else "")
                _refuse(field, path, f"holds files isorock did not write ({shown}); give a new or empty "
                                     "folder, or one an earlier isorock run wrote")
            if not os.access(p, os.W_OK | os.X_OK):
                _refuse(field, path, "is not writable")
            self.exists, self._parents = True, []
        else:
            self.exists, self._parents = False, _missing_parents(field, p)
        self.target = p
        self.identity = ("folder", str(p))

    def staging(self) -> Path:
        """A fresh, empty folder to write the outputs into."""
        self.discard()
        try:
            if self.exists:  # staged inside: the folder itself stays (its inode, its permissions)
                self._staging = Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=self.target))
            else:
                _make_parents(self._parents, self._created)
                clear_stale_staging(self.target.parent)
                self._staging = Path(tempfile.mkdtemp(prefix=_staging_prefix(self.target.name),
                                                      dir=self.target.parent))
        except OSError as e:
            self.discard()
            raise _os_failure(self.field, self.given, e) from None
        return self._staging

    def write(self, fill) -> None:
        try:
            fill(self.staging())
        except OSError as e:
            self.discard()
            raise _os_failure(self.field, self.given, e) from None
        except BaseException:
            self.discard()
            raise

    def commit(self) -> None:
        if self._staging is None:
            return
        staging = self._staging
        try:
            names = sorted(e.name for e in staging.iterdir())
            (staging / MARKER).write_text(json.dumps({"written_by": "isorock", "entries": names}) + "\n")
            for d in [staging, *staging.rglob("*")]:
                if d.is_dir():
                    os.chmod(d, _folder_mode())
            if not self.exists:
                os.replace(staging, self.target)
                self._staging, self._created = None, []
                return
            self._replace_in_place(staging, names)
        except OSError as e:
            raise _os_failure(self.field, self.given, e) from None

    def _replace_in_place(self, staging: Path, names: list[str]) -> None:
        # re-checked now: a file the user put there during the run must not be lost
        foreign = _foreign_entries(self.target)
        if foreign:
            _refuse(self.field, self.given, f"now holds files isorock did not write ({', '.join(sorted(foreign))})")
        old = Path(tempfile.mkdtemp(prefix=STAGING_PREFIX, dir=self.target))
        moved_out, moved_in = [], []
        try:
            # the old marker first: an interruption leaves no marker claiming new files
            previous = sorted((e for e in self.target.iterdir() if e.name not in (staging.name, old.name)),
                              key=lambda e: e.name != MARKER)
            for e in previous:
                os.replace(e, old / e.name)
                moved_out.append(e.name)
            for name in names + [MARKER]:
                os.replace(staging / name, self.target / name)
                moved_in.append(name)
        except BaseException:
            for name in reversed(moved_in):
                os.replace(self.target / name, staging / name)
            for name in reversed(moved_out):
                os.replace(old / name, self.target / name)
            shutil.rmtree(old, ignore_errors=True)
            raise
        shutil.rmtree(old, ignore_errors=True)
        shutil.rmtree(staging, ignore_errors=True)
        self._staging = None

    def discard(self) -> None:
        if self._staging is not None:
            shutil.rmtree(self._staging, ignore_errors=True)
            self._staging = None
        _remove_folders(self._created)
        self._created = []


def _foreign_entries(folder: Path) -> set[str]:
    """Entries of `folder` that its marker does not list (all of them without a marker).
    Staging entries are ours: a run killed by SIGKILL may leave one behind."""
    entries = {e.name for e in folder.iterdir() if not e.name.startswith(STAGING_PREFIX)}
    if not entries:
        return set()
    marker = folder / MARKER
    try:
        listed = set(json.loads(marker.read_text())["entries"]) if marker.is_file() else None
    except (OSError, ValueError, KeyError, TypeError):
        listed = None
    if listed is None:
        return entries
    return entries - listed - {MARKER}


class Outputs:
    """All outputs of one command, written all or none:

        with Outputs() as out:
            j = out.file("json", args.json)      # refused here when the path is bad
            ... the command's work ...
            j.write_text(text)
            out.commit()

    Leaving the block without commit (an error, a signal) removes everything staged."""

    def __init__(self):
        self.targets: list[FileOutput | FolderOutput] = []

    def file(self, field: str, path, *, exclusive: bool = False) -> FileOutput:
        return self._add(FileOutput(field, path, exclusive))

    def folder(self, field: str, path) -> FolderOutput:
        return self._add(FolderOutput(field, path))

    def _add(self, target):
        for other in self.targets:
            if other.identity == target.identity:
                raise InputError(f"{target.field} = {str(target.given)!r}: is also given as {other.field}; "
                                 "each output needs a path of its own")
        self.targets.append(target)
        return target

    def commit(self) -> None:
        committed = False
        try:
            with _signals_held():
                try:
                    signum = signal_received()
                    if signum is not None:  # its exception was swallowed on the way: still nothing lands
                        raise_for_signal(signum)
                    # streams first: a full device or a closed pipe fails before any file is replaced;
                    # exclusive files next: the one commit that may be refused, before anything is replaced
                    for t in sorted(self.targets, key=lambda t: (getattr(t, "kind", None) not in ("stdout", "stream"),
                                                                 not getattr(t, "exclusive", False))):
                        t.commit()
                    committed = True
                except BaseException:
                    self.discard()
                    raise
        except (Terminated, KeyboardInterrupt) as e:
            if committed:  # a signal held during the commit lands once it is done: say what was written
                e.outcome = "its outputs were written before it stopped: " + ", ".join(
                    str(t.given) for t in self.targets)
            raise

    def discard(self) -> None:
        for t in self.targets:
            t.discard()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.discard()
        return False


# --- one-output conveniences ------------------------------------------------------------

def write_atomic(path, write, *, field: str = "output") -> None:
    """write(tmp_path) writes the whole file; it replaces `path` only when done."""
    with Outputs() as out:
        out.file(field, path).write(write)
        out.commit()


def write_text(path, text: str, *, field: str = "output") -> None:
    write_atomic(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"), field=field)


def write_json(path, data, *, field: str = "output") -> None:
    write_text(path, to_json(data) + "\n", field=field)


def check_folder(path, *, field: str = "out") -> None:
    """Refuse a bad output folder before the work starts (InputError, exit 2)."""
    FolderOutput(field, path)


def write_folder_atomic(out_dir, fill, *, field: str = "out") -> None:
    """fill(tmp_dir) writes a whole output folder; it lands in out_dir only when done,
    and only if out_dir is new, empty or an earlier isorock output (see the module)."""
    with Outputs() as out:
        out.folder(field, out_dir).write(fill)
        out.commit()
