"""Hostile inputs to the `isorock` command line, as an adversarial user would try them
(issue 13), shared by tests/test_adversarial.py (in-process, every case) and
scripts/adversarial_table.py (the real command in a subprocess, the closing table).

Each case runs in a fresh working folder that `setup` fills; it must end with the
expected outcome ("exit2": one line on stderr, exit code 2; "ok": exit 0 and `check`
holds), never a traceback or a hang, and may change nothing in the folder but the
paths in `outputs`.
"""
from __future__ import annotations

import json
import os
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

BLOCK = ["--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]
FIXED = ["run", "--engine", "analytic", *BLOCK, "--fixed-base"]
ISOLATED = ["run", "--engine", "analytic", *BLOCK, "--period", "1.5", "--damping", "0.2"]
SHORT = ["--duration", "0.5"]
G = 9.80665


@dataclass
class Case:
    cls: str
    name: str
    argv: list[str]
    expect: str = "exit2"                       # "exit2" or "ok"
    setup: Callable[[Path], None] | None = None
    outputs: tuple[str, ...] = ()               # paths the command may create or change
    check: Callable[[Path, str], bool] | None = None  # (folder, stdout) -> the result is right
    in_process: bool = True                     # False: only as a real process (it uses fd 1)
    env: dict = field(default_factory=dict)     # environment variables for the process
    code: str | None = None                     # Python to run instead of a command (the notebook API)
    says: str = ""                              # exit 2: what its one line must name
    needs: tuple[str, ...] = ()                 # "vsr": the shared shake-table folder (skipped without it)


def _files(**contents) -> Callable[[Path], None]:
    def setup(d: Path):
        for name, text in contents.items():
            p = d / name.replace("__", ".")
            p.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(text, bytes):
                p.write_bytes(text)
            else:
                p.write_text(text)
    return setup


def _project(d: Path):
    (d / "src").mkdir()
    (d / "src" / "main.py").write_text("print('mine')\n")
    (d / "NOTES.md").write_text("my notes\n")
    (d / "results").mkdir()
    (d / "results" / "important.csv").write_text("1,2,3\n")


def _device(name: str) -> Callable[[Path], None]:
    """A character device node `dev-<name>` in the folder (as root), so no case can
    harm the machine's own /dev/null or /dev/full; other users get a symlink to it."""
    numbers = {"null": (1, 3), "full": (1, 7)}

    def setup(d: Path):
        node = d / f"dev-{name}"
        if os.geteuid() == 0:
            os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(*numbers[name]))
        else:
            os.symlink(f"/dev/{name}", node)
    return setup


def _symlink(name, target) -> Callable[[Path], None]:
    def setup(d: Path):
        os.symlink(target, d / name)
    return setup


def _both(*setups):
    def setup(d: Path):
        for s in setups:
            s(d)
    return setup


def _json_out(key, value, rel=1e-3) -> Callable[[Path, str], bool]:
    def check(d: Path, out: str) -> bool:
        got = json.loads(out)
        for k in key.split("."):
            got = got[k]
        return abs(got - value) <= rel * abs(value) + 1e-12
    return check


def _file_json(path, key, value, rel=1e-3):
    def check(d: Path, out: str) -> bool:
        return _json_out(key, value, rel)(d, (d / path).read_text())
    return check


def _file_starts(path, prefix):
    return lambda d, out: (d / path).read_text().startswith(prefix)


AT2 = "PEER NGA\nrecord\n{line3}\nNPTS=    5, DT=   {dt} SEC\n  .1 .2 -.3 .1 .0\n"
FREE = ["--theta0", "0.5", "--duration", "1"]
free_rocks = _json_out("theta_max_over_alpha", 0.5, rel=1e-9)


def cases() -> list[Case]:
    c: list[Case] = []
    add = c.append

    # --- output folders: never empty or replace what isorock did not write -----------------
    for cmd in (["validate", "--quick", "--quiet", "--engines", "analytic"], ["bench", "--engines", "analytic"],
                ["stress", "--engines", "analytic"]):
        n = cmd[0]
        add(Case("out-folder", f"{n} --out . (project)", [*cmd, "--out", "."], setup=_project))
        add(Case("out-folder", f"{n} --out ''", [*cmd, "--out", ""], setup=_project))
        add(Case("out-folder", f"{n} --out results/", [*cmd, "--out", "results"], setup=_project))
        add(Case("out-folder", f"{n} --out an existing file", [*cmd, "--out", "NOTES.md"], setup=_project))
        add(Case("out-folder", f"{n} --out link to a user folder", [*cmd, "--out", "link"],
                 setup=_both(_project, _symlink("link", "src"))))
        add(Case("out-folder", f"{n} --out dangling link", [*cmd, "--out", "nowhere"],
                 setup=_symlink("nowhere", "missing/dir")))
        add(Case("out-folder", f"{n} --out under a file", [*cmd, "--out", "NOTES.md/rep"], setup=_project))

    # --- output files: --json, --csv, scene --out -----------------------------------------------
    add(Case("out-file", "--json ''", [*FIXED, *SHORT, "--json", ""]))
    add(Case("out-file", "--json at a folder", [*FIXED, *SHORT, "--json", "src"], setup=_project))
    add(Case("out-file", "--csv at a folder", [*FIXED, *SHORT, "--csv", "src"], setup=_project))
    add(Case("out-file", "--json under a file", [*FIXED, *SHORT, "--json", "NOTES.md/x.json"], setup=_project))
    add(Case("out-file", "--json X --csv X", [*FIXED, *SHORT, "--json", "x", "--csv", "x"]))
    add(Case("out-file", "--json X --csv ./X", [*FIXED, *SHORT, "--json", "x", "--csv", "./x"]))
    add(Case("out-file", "--json - --csv -", [*FIXED, *SHORT, "--json", "-", "--csv", "-"]))
    add(Case("out-file", "--json dangling link", [*FIXED, *SHORT, "--json", "l.json"],
             setup=_symlink("l.json", "missing/x.json")))
    add(Case("out-file", "--json full device", [*FIXED, *SHORT, "--json", "dev-full"], setup=_device("full")))
    add(Case("out-file", "--json ok, --csv full device (all or none)",
             [*FIXED, *SHORT, "--json", "x.json", "--csv", "dev-full"], setup=_device("full")))
    add(Case("out-file", "scene --out a folder", ["scene", "--engine", "mujoco", "--out", "src"], setup=_project))
    add(Case("out-file", "scene --out ''", ["scene", "--engine", "mujoco", "--out", ""]))
    add(Case("out-file", "scene --out a block device", ["scene", "--engine", "mujoco", "--out", "/dev/loop0"]))
    add(Case("out-file", "--json - is standard output", [*FIXED, *FREE, "--json", "-"], "ok", check=free_rocks))
    add(Case("out-file", "--json null device", [*FIXED, *FREE, "--json", "dev-null", "--quiet"], "ok",
             setup=_device("null"), outputs=("dev-null",),
             check=lambda d, out: out == "" and stat.S_ISCHR(os.stat(d / "dev-null").st_mode)))
    add(Case("out-file", "--json through a symlink", [*FIXED, *FREE, "--json", "link.json"], "ok",
             setup=_both(_files(**{"real__json": "old"}), _symlink("link.json", "real.json")),
             outputs=("real.json",),
             check=lambda d, out: (d / "link.json").is_symlink()
             and json.loads((d / "real.json").read_text())["theta_max_over_alpha"] > 0.49))
    # a missing folder is refused, not made without a word (issue 24, item 5)
    add(Case("out-file", "--json into a new sub-folder", [*FIXED, *FREE, "--json", "new/sub/x.json"]))
    add(Case("out-file", "--json replaces an existing file", [*FIXED, *FREE, "--json", "x.json"], "ok",
             setup=_files(**{"x__json": "old"}), outputs=("x.json",),
             check=_file_json("x.json", "theta_max_over_alpha", 0.5, rel=1e-9)))
    add(Case("out-file", "--json link to /proc/self/fd/1", [*FIXED, *FREE, "--json", "fd1.json", "--quiet"], "ok",
             setup=_symlink("fd1.json", "/proc/self/fd/1"), check=free_rocks, in_process=False))
    add(Case("out-file", "scene --out - is standard output", ["scene", "--engine", "mujoco", "--out", "-"], "ok",
             check=lambda d, out: out.lstrip().startswith("<mujoco")))
    add(Case("out-file", "scene --out file", ["scene", "--engine", "bullet", "--out", "b.urdf"], "ok",
             outputs=("b.urdf",), check=_file_starts("b.urdf", "<?xml")))

    # --- argument errors: one line, not the usage block -------------------------------------
    add(Case("arguments", "--height abc", ["run", *BLOCK, "--fixed-base", "--height", "abc"]))
    add(Case("arguments", "missing options (the base)", ["run"]))
    add(Case("arguments", "--duration -inf", [*FIXED, "--duration", "-inf"]))
    add(Case("arguments", "--duration nan", [*FIXED, "--duration", "nan"]))
    add(Case("arguments", "--duration 0", [*FIXED, "--duration", "0"]))
    add(Case("arguments", "--scales -1,2,3", ["validate", "--engines", "analytic", "--scales", "-1,2,3"]))
    add(Case("arguments", "--scales 1,2", ["validate", "--engines", "analytic", "--scales", "1,2"]))
    add(Case("arguments", "--substeps 1.5", [*FIXED, "--substeps", "1.5"]))
    add(Case("arguments", "--theta0 nan", [*FIXED, "--theta0", "nan"]))
    add(Case("arguments", "--theta0 -1e0", [*FIXED, "--theta0", "-1e0"]))
    for value in ("0", "-1", "nan", "inf"):  # every run's budget (issue 24 item 13)
        add(Case("arguments", f"--budget {value}", [*FIXED, "--budget", value]))
    add(Case("arguments", "view --budget 0", ["view", "--budget", "0", "--out", "v.gif"]))
    add(Case("arguments", "unknown option", [*FIXED, "--bogus", "1"]))
    add(Case("arguments", "option without its value", [*FIXED, "--engine"]))
    add(Case("arguments", "no command", []))
    add(Case("arguments", "unknown command", ["frobnicate"]))
    add(Case("arguments", "--units furlongs", [*FIXED, "--units", "furlongs"]))
    add(Case("arguments", "--solref 1", [*FIXED, "--solref", "1"]))
    add(Case("arguments", "beta --slenderness -2", ["beta", "--slenderness", "-2", "--mass-ratio", "1"]))
    add(Case("arguments", "--theta0 -0.5 (a negative value)", [*FIXED, "--theta0", "-0.5", "--duration", "1"],
             "ok", check=_json_out("theta_max_over_alpha", 0.5, rel=1e-9)))

    # --- records: read in the units they state, or refused --------------------------------------
    add(Case("records", "AT2 DT = .", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF G", dt="."))))
    add(Case("records", "AT2 DT = 1.2.3", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF G", dt="1.2.3"))))
    add(Case("records", "AT2 velocity series", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="VELOCITY TIME SERIES IN UNITS OF CM/S", dt=".01"))))
    add(Case("records", "AT2 units CM/SEC (not acceleration)", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF CM/SEC", dt=".01"))))
    add(Case("records", "AT2 without units", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES", dt=".01"))))
    add(Case("records", "AT2 --units contradicting its header", [*FIXED, *SHORT, "--motion", "r.AT2", "--units", "m/s2"],
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF G", dt=".01"))))
    add(Case("records", "AT2 in CM/SEC/SEC", [*FIXED, *SHORT, "--motion", "r.AT2"], "ok",
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF CM/SEC/SEC", dt=".01")),
             check=_json_out("motion.pga_g", 0.003 / G)))
    add(Case("records", "AT2 in G", [*FIXED, *SHORT, "--motion", "r.AT2"], "ok",
             setup=_files(r__AT2=AT2.format(line3="ACCELERATION TIME SERIES IN UNITS OF G", dt=".01")),
             check=_json_out("motion.pga_g", 0.3)))
    add(Case("records", "AT2 NPTS mismatch", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=AT2.format(line3="UNITS OF G", dt=".01").replace("NPTS=    5", "NPTS=    9"))))
    add(Case("records", "AT2 of random bytes", [*FIXED, *SHORT, "--motion", "r.AT2"],
             setup=_files(r__AT2=bytes(range(256)) * 8)))
    add(Case("records", "two columns without units", [*FIXED, *SHORT, "--motion", "r.csv"],
             setup=_files(r__csv="0,0\n0.01,0.3\n0.02,-0.3\n")))
    add(Case("records", "two columns with --units g", [*FIXED, *SHORT, "--motion", "r.csv", "--units", "g"], "ok",
             setup=_files(r__csv="0,0\n0.01,0.3\n0.02,-0.3\n"), check=_json_out("motion.pga_g", 0.3)))
    add(Case("records", "two columns, '# units: g'", [*FIXED, *SHORT, "--motion", "r.csv"], "ok",
             setup=_files(r__csv="# units: g\n0,0\n0.01,0.3\n0.02,-0.3\n"), check=_json_out("motion.pga_g", 0.3)))
    add(Case("records", "two columns, header 't [s], a [cm/s2]'", [*FIXED, *SHORT, "--motion", "r.csv"], "ok",
             setup=_files(r__csv="t [s], a [cm/s2]\n0,0\n0.01,300\n0.02,-300\n"),
             check=_json_out("motion.pga_g", 3.0 / G)))
    add(Case("records", "UTF-8 BOM, headerless", [*FIXED, *SHORT, "--motion", "r.csv", "--units", "g"], "ok",
             setup=_files(r__csv="\ufeff0,0.4\n0.01,0.1\n0.02,0\n".encode("utf-8")),
             check=_json_out("motion.pga_g", 0.4)))
    add(Case("records", "two columns, uneven time", [*FIXED, *SHORT, "--motion", "r.csv", "--units", "g"],
             setup=_files(r__csv="0,0\n0.01,0.3\n0.05,-0.3\n")))
    add(Case("records", "JMA --units g", [*FIXED, *SHORT, "--motion", "j.txt", "--units", "g"],
             setup=_files(j__txt=";c\n0.01 0.5\n 100. -200. 50.\n")))
    add(Case("records", "a folder as the record", [*FIXED, *SHORT, "--motion", "src"], setup=_project))
    add(Case("records", "empty file", [*FIXED, *SHORT, "--motion", "e.csv", "--units", "g"], setup=_files(e__csv="")))

    # --- pulses ----------------------------------------------------------------------------------
    for spec in ("sine:amp=0.1,amp=5,freq=1", "sine:amp=0.5", "sine:amp=inf,freq=1", "sine:amp=nan,freq=1",
                 "sine:amp=0.5,freq=0", "ricker:amp=1,freq=1,cycles=2", "sine:", "sine:amp=0.5,freq=1,bogus=3"):
        add(Case("pulses", spec, [*FIXED, *SHORT, "--motion", spec]))
    add(Case("pulses", "sine:amp=0.05,freq=2", [*FIXED, *SHORT, "--motion", "sine:amp=0.05,freq=2"], "ok",
             check=_json_out("motion.pga_g", 0.05)))

    # --- work bounds: refused at once, naming the bound ---------------------------------------
    add(Case("work", "--duration 1e9", [*FIXED, "--duration", "1e9"]))
    add(Case("work", "--duration inf", [*FIXED, "--duration", "inf"]))
    add(Case("work", "cycles=1e9", [*FIXED, "--motion", "sine:amp=0.5,freq=1,cycles=1e9"]))
    add(Case("work", "freq=1e-6", [*FIXED, "--motion", "sine:amp=0.5,freq=1e-6"]))
    add(Case("work", "freq=1e6, cycles=1e5 (samples)", [*FIXED, "--motion", "sine:amp=0.5,freq=1e6,cycles=1e5"]))
    add(Case("work", "--max-step 1e-9", [*FIXED, "--max-step", "1e-9"]))
    add(Case("work", "--timestep 1e-7 (mujoco)", [*FIXED, "--engine", "mujoco", "--timestep", "1e-7",
                                                   "--duration", "100"]))
    add(Case("work", "--substeps 1000000 (bullet)", [*FIXED, "--engine", "bullet", "--substeps", "1000000"]))
    add(Case("work", "--csv-dt 1e-9", [*FIXED, "--csv-dt", "1e-9", "--json", "x.json", "--csv", "x.csv"]))
    add(Case("work", "--rest-velocity 1e-300", [*FIXED, "--rest-velocity", "1e-300"]))
    add(Case("work", "--period 1e-9", [*ISOLATED[:-4], "--period", "1e-9", "--damping", "0.1"]))
    add(Case("work", "--stiffness 1e30", [*ISOLATED[:-4], "--stiffness", "1e30"]))
    add(Case("work", "validate --scales 0.1,1,1e9", ["validate", "--engines", "analytic", "--scales", "0.1,1,1e9"]))
    add(Case("work", "validate --scales 0.1,1e9,3", ["validate", "--engines", "analytic", "--scales", "0.1,1e9,3"]))
    for extra in (["--engine", "mujoco", "--timestep", "0"], ["--engine", "bullet", "--substeps", "-5"],
                  ["--rtol", "0"], ["--max-step", "inf"], ["--scale", "nan"], ["--impact-threshold", "2"],
                  ["--engine", "mujoco", "--friction", "nan"]):
        add(Case("work", " ".join(extra), [*FIXED, *SHORT, *extra]))
    add(Case("work", "isolated, 2 s of a pulse", [*ISOLATED, "--motion", "sine:amp=0.5,freq=2", "--duration", "2"],
             "ok", check=lambda d, out: json.loads(out)["status"] in ("completed", "overturned")))
    from adversarial_round_two import round_two  # issue 24: campaigns, config files, calibration, cache
    c += round_two(Case)
    from adversarial_round_three import round_three  # issue 34: design, file bounds, experiments' data, the API
    c += round_three(Case)
    from adversarial_round_four import round_four  # issue 34's goal: the typed API, first runs, plugins, sliding
    c += round_four(Case)
    return c


# --- running a case and judging it ------------------------------------------------------------

TIME_LIMIT = 30.0  # s per case: far beyond any case's work, so reaching it means a hang


def snapshot(d: Path) -> dict:
    """Every path under d with what a change would alter (type, size, mtime, mode)."""
    out = {}
    for root, dirs, files in os.walk(d):
        for name in dirs + files:
            p = Path(root) / name
            st = os.lstat(p)
            rel = str(p.relative_to(d))
            out[rel] = (stat.S_IFMT(st.st_mode), st.st_size if not stat.S_ISDIR(st.st_mode) else 0,
                        st.st_mtime_ns if not stat.S_ISDIR(st.st_mode) else 0, st.st_mode)
    return out


@dataclass
class Outcome:
    code: int | None           # None: it hung (time limit) or raised
    out: str
    err: str
    touched: list[str] = field(default_factory=list)
    traceback: bool = False
    hung: bool = False

    def verdict(self, case: Case, d: Path) -> str:
        """'exit 2' or 'correct result' when the case ended as it should, else what went wrong."""
        if self.hung:
            return "other: hang"
        if self.traceback:
            return "other: traceback"
        if self.touched:
            return f"other: touched {', '.join(self.touched)}"
        if case.expect == "exit2":
            if self.code != 2:
                return f"other: exit {self.code}, expected 2"
            if self.err.count("\n") != 1 or "error" not in self.err:
                return "other: not one error line"
            if case.says not in self.err:
                return f"other: the line does not name {case.says!r}"
            return "exit 2"
        if self.code != 0:
            return f"other: exit {self.code}: {self.err.strip()[-200:]}"
        try:
            ok = case.check is None or case.check(d, self.out)
        except Exception as e:  # a wrong or missing result
            return f"other: result unreadable ({type(e).__name__}: {e})"
        return "correct result" if ok else "other: wrong result"


def _touched(before: dict, after: dict, allowed) -> list[str]:
    """Changed paths not among `allowed` (an entry ending in '/' allows that folder and
    everything under it: a sweep's output folder)."""
    changed = {k for k in before.keys() | after.keys() if before.get(k) != after.get(k)}
    folders = tuple(a for a in allowed if a.endswith("/"))
    return sorted(k for k in changed - set(allowed)
                  if not any(k == f[:-1] or k.startswith(f) for f in folders))


def run_in_process(case: Case, d: Path) -> Outcome:
    """The case through validate.cli.main in this process, in folder d, with a SIGALRM watchdog."""
    import contextlib
    import io
    import signal
    import traceback

    from isorock.validate.cli.main import main

    class Hang(BaseException):
        pass

    def alarm(*_):
        raise Hang()

    if case.setup:
        case.setup(d)
    before = snapshot(d)
    out_b, err = io.BytesIO(), io.StringIO()
    out = io.TextIOWrapper(out_b, encoding="utf-8", write_through=True)
    cwd = os.getcwd()
    env = {k: os.environ.get(k) for k in case.env}  # the process's environment, as run_as_process gives it
    os.environ.update(case.env)
    old = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, TIME_LIMIT)
    code, tb, hung = None, False, False
    try:
        os.chdir(d)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(case.argv) if case.code is None else _run_code(case.code)
    except Hang:
        hung = True
    except BaseException:
        tb = True
        err.write(traceback.format_exc())
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
        os.chdir(cwd)
        for k, v in env.items():
            os.environ.pop(k, None) if v is None else os.environ.__setitem__(k, v)
    out.flush()
    return Outcome(code, out_b.getvalue().decode("utf-8", "replace"), err.getvalue(),
                   _touched(before, snapshot(d), case.outputs), tb or "Traceback" in err.getvalue(), hung)


def _run_code(code: str) -> int:
    """A notebook-API case: its InputError is the command's exit 2 and one line; code that
    drives the command line (validate.cli.main) sets EXIT to its exit code."""
    import sys

    from isorock.analytic.errors import InputError
    scope = {"__name__": "__main__"}
    try:
        exec(compile(code, "<case>", "exec"), scope)
    except InputError as e:
        print(f"isorock: error: {e}", file=sys.stderr)
        return 2
    return int(scope.get("EXIT", 0))


def run_as_process(case: Case, d: Path, python: str) -> Outcome:
    """The case as a real `python -m isorock.validate.cli.main` process in folder d (a
    notebook-API case: its code in `python -c`, judged as _run_code judges it)."""
    import subprocess
    if case.setup:
        case.setup(d)
    before = snapshot(d)
    argv = ["-m", "isorock.validate.cli.main", *case.argv]
    if case.code is not None:
        argv = ["-c", f"import sys\nsys.path.insert(0, {str(Path(__file__).parent)!r})\n"
                      f"from adversarial_cases import _run_code\nsys.exit(_run_code({case.code!r}))"]
    try:
        p = subprocess.run([python, *argv], cwd=d, capture_output=True,
                           text=True, timeout=TIME_LIMIT, env={**os.environ, **case.env} if case.env else None)
    except subprocess.TimeoutExpired as e:
        return Outcome(None, "", str(e), _touched(before, snapshot(d), case.outputs), False, True)
    return Outcome(p.returncode, p.stdout, p.stderr, _touched(before, snapshot(d), case.outputs),
                   "Traceback" in p.stderr, False)
