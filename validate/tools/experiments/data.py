"""Readers of the shake-table data: the tests' table acceleration and results.csv.

The layout read is the shared folder's (README of the data folder): `results.csv` (UTF-8, a
byte-order mark allowed) and `Shake_Table_Response/TestNNN.txt.gz` or `TestNNN.txt`, whose
first two columns are time and acceleration (more columns are ignored). The units are read
from the header line ("Time [s]  Acceleration [g]"), never guessed: a header that states
other or no units is refused. A clone of the original repository is not this layout (its
test files say "Amplitude - Plot 0", no units; its outcomes are spreadsheets) and is refused
saying so. Anything malformed is an InputError (exit 2, one line) naming the file and line.
"""
from __future__ import annotations

import csv
import gzip
import io
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ....analytic.errors import InputError
from ....analytic.limits import check_acceleration
from ....analytic.system import STANDARD_GRAVITY

#: Units of the table acceleration this reader knows, as a header states them → m/s².
ACCEL_UNITS = {"g": STANDARD_GRAVITY, "m/s2": 1.0, "m/s^2": 1.0, "gal": 0.01, "cm/s2": 0.01}
TIME_UNITS = {"s": 1.0}
#: A sample's time may sit off its uniform grid point by this fraction of the step (the
#: file's rounding of the printed time is < 0.05 of a step; a lost sample is a whole step).
STEP_TOLERANCE = 0.25
SPECIMENS = (1, 2)
#: fewest tests a study can score: each test's threshold is fitted on the others
MIN_TESTS = 2


@dataclass(frozen=True)
class TableMotion:
    """One test's measured table acceleration: uniform samples (m/s²) from t = 0."""
    test: int
    dt: float
    acceleration: np.ndarray  # m/s²
    source: str
    units: str  # as the header stated them

    @property
    def duration(self) -> float:
        return (self.acceleration.size - 1) * self.dt


@dataclass(frozen=True)
class Outcome:
    """One row of results.csv: measured overturning of each specimen (1 overturned), the
    discrete-element baseline's predictions per setting, the record and its scaling."""
    test: int
    measured: dict  # specimen → 0/1
    baseline: dict  # specimen → {setting: 0/1}
    ground_motion: str
    pgv_over_pga_s: float
    scaled_pga_g: float


def _units(label: str, known: dict, path, lineno: int, column: str) -> str:
    m = re.search(r"\[([^\]]+)\]", label)
    if m is None:
        raise InputError(f"{path}:{lineno}: {column} column {label!r} states no units in [..]; "
                         f"allowed: {', '.join(known)}")
    unit = m.group(1).strip().lower().replace(" ", "")
    if unit not in known:
        raise InputError(f"{path}:{lineno}: {column} units [{m.group(1)}] are not one of {', '.join(known)}")
    return unit


def test_files(folder) -> dict[int, Path]:
    """test number → its file under `folder`/Shake_Table_Response (compressed or not)."""
    sub = Path(folder) / "Shake_Table_Response"
    found: dict[int, Path] = {}
    if sub.is_dir():
        for p in sorted(sub.iterdir()):
            m = re.fullmatch(r"Test(\d+)\.txt(\.gz)?", p.name)
            if m:
                found.setdefault(int(m.group(1)), p)
    return found


def read_test(path, test: int | None = None) -> TableMotion:
    """The table acceleration of one test file (either layout); columns past the second
    are ignored (a clone's other direction and displacement)."""
    path = Path(path)
    if test is None:
        m = re.search(r"(\d+)", path.name)
        test = int(m.group(1)) if m else -1
    opener = gzip.open if path.suffix == ".gz" else open
    try:
        with opener(path, "rt", encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except (OSError, EOFError) as e:
        raise InputError(f"{path}: cannot be read ({e})") from None
    if not lines:
        raise InputError(f"{path}: empty file; expected a header 'Time [s]<TAB>Acceleration [g]' and samples")
    header = [c.strip() for c in re.split(r"\t|,|\s{2,}", lines[0].strip()) if c.strip()]
    if len(header) < 2:
        raise InputError(f"{path}:1: header {lines[0]!r}: expected at least two columns, time [s] and "
                         "acceleration [units]")
    t_unit = _units(header[0], TIME_UNITS, path, 1, "time")
    a_unit = _units(header[1], ACCEL_UNITS, path, 1, "acceleration")
    rows = []
    for i, line in enumerate(lines[1:], start=2):
        tok = line.replace(",", " ").split()
        if not tok:
            continue
        try:
            rows.append((float(tok[0]), float(tok[1])))
        except (ValueError, IndexError):
            raise InputError(f"{path}:{i}: {line.strip()[:60]!r}: expected two numbers (time, acceleration)") from None
    if len(rows) < 3:
        raise InputError(f"{path}: {len(rows)} samples; a test needs at least 3")
    arr = np.asarray(rows)
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        raise InputError(f"{path}:{int(np.argmax(bad)) + 2}: a sample is not a finite number")
    peak = np.abs(arr[:, 1]) * ACCEL_UNITS[a_unit] / STANDARD_GRAVITY
    k = int(np.argmax(peak))
    try:
        check_acceleration("acceleration", float(peak[k]))  # no table moves so; the kernel spun on such
    except InputError as e:
        raise InputError(f"{path}:{k + 2}: {e}") from None
    t = arr[:, 0] * TIME_UNITS[t_unit]
    # the file prints times to 6 significant digits (16.0312 for 16.03125): the step is the
    # fit over the whole test, and each time may sit off its grid point by that rounding
    # only; a missing, repeated or out-of-order sample is off by a whole step
    dt = float((t[-1] - t[0]) / (t.size - 1))
    off = np.abs(t - (t[0] + dt * np.arange(t.size)))
    steps = np.diff(t)
    off = np.maximum(off, np.concatenate(([0.0], np.abs(steps - dt))))  # a lost sample: a step of 2dt
    if not dt > 0 or off.max() > STEP_TOLERANCE * dt:
        i = int(np.argmax(off)) + 2
        raise InputError(f"{path}:{i}: time {t[i - 2]!r} s is off the uniform grid of step {dt:.6g} s; "
                         "samples must be uniform and increasing")
    return TableMotion(test=test, dt=dt, acceleration=arr[:, 1] * ACCEL_UNITS[a_unit], source=str(path),
                       units=a_unit)


_MEASURED = "Experimental Results for response-Specimen {}"
_BASELINE = re.compile(r"Specimen (\d)-Numerical (.+)")


def _flag(path, lineno, column, text) -> int:
    if text.strip() not in ("0", "1"):
        raise InputError(f"{path}:{lineno}: {column} = {text!r}: must be 0 or 1")
    return int(text)


def _positive(path, lineno, column, text) -> float:
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (v > 0 and np.isfinite(v)):
        raise InputError(f"{path}:{lineno}: {column} = {text!r}: must be a positive number")
    return v


def read_results(path) -> dict[int, Outcome]:
    """results.csv → test number → Outcome. UTF-8, with or without the byte-order mark a
    spreadsheet saves (it was read as part of the first column's name)."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise InputError(f"{path}: cannot be read ({e.strerror})") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        line = raw.count(b"\n", 0, e.start) + 1
        raise InputError(f"{path}:{line}: not UTF-8 text (byte {e.start}: {raw[e.start:e.start + 1]!r}); save it "
                         "as UTF-8") from None
    try:
        reader = csv.reader(io.StringIO(text, newline=""))
        header = next(reader, None)
        body = list(reader)
    except csv.Error as e:
        raise InputError(f"{path}:{reader.line_num}: not a CSV row ({e})") from None
    need = ["test", _MEASURED.format(1), _MEASURED.format(2), "ground_motion", "pgv_over_pga_s", "scaled_pga_g"]
    if header is None:
        raise InputError(f"{path}: empty; expected a header with {', '.join(need)}")
    missing = [c for c in need if c not in header]
    if missing:
        raise InputError(f"{path}:1: column {missing[0]!r} missing; needed: {', '.join(need)}")
    col = {name: i for i, name in enumerate(header)}
    base_cols = [(int(m.group(1)), m.group(2), i) for i, name in enumerate(header) if (m := _BASELINE.fullmatch(name))]
    out: dict[int, Outcome] = {}
    for lineno, row in enumerate(body, start=2):
        if not any(c.strip() for c in row):
            continue
        if len(row) != len(header):
            raise InputError(f"{path}:{lineno}: {len(row)} fields; the header has {len(header)}")
        try:
            test = int(row[col["test"]])
        except ValueError:
            raise InputError(f"{path}:{lineno}: test = {row[col['test']]!r}: must be a whole number") from None
        if test in out:
            raise InputError(f"{path}:{lineno}: test = {test}: appears twice")
        measured = {s: _flag(path, lineno, _MEASURED.format(s), row[col[_MEASURED.format(s)]]) for s in SPECIMENS}
        baseline: dict = {s: {} for s in SPECIMENS}
        for s, setting, i in base_cols:
            baseline[s][setting] = _flag(path, lineno, header[i], row[i])
        out[test] = Outcome(test=test, measured=measured, baseline=baseline,
                            ground_motion=row[col["ground_motion"]].strip("' ").removesuffix(".xlsx"),
                            pgv_over_pga_s=_positive(path, lineno, "pgv_over_pga_s", row[col["pgv_over_pga_s"]]),
                            scaled_pga_g=_positive(path, lineno, "scaled_pga_g", row[col["scaled_pga_g"]]))
    if not out:
        raise InputError(f"{path}: no test rows")
    return out


def results_path(folder) -> Path:
    folder = Path(folder)
    for p in (folder / "results.csv",):
        if p.is_file():
            return p
    raise InputError(f"data = {str(folder)!r}: no results.csv there (the outcomes; see the data folder's README)")


def load(folder, tests=None):
    """(outcomes, files): the tests that have both an outcome row and a motion file (those
    of `tests` if given). A folder without either is an InputError."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(f"data = {str(folder)!r}: not a folder (expected the shake-table data folder)")
    if not (folder / "results.csv").is_file() and (folder / "data" / "Shake_Table_Response").is_dir():
        raise InputError(f"data = {str(folder)!r}: a clone of the original repository is not read as it is: its "
                         "test files state no units ('Amplitude - Plot 0') and its outcomes are spreadsheets; give "
                         "the shared data folder made from it (its README says how: results.csv and "
                         "Shake_Table_Response/TestNNN.txt[.gz] with 'Time [s]  Acceleration [g]')")
    outcomes = read_results(results_path(folder))
    files = test_files(folder)
    if not files:
        raise InputError(f"data = {str(folder)!r}: no Shake_Table_Response/TestNNN.txt[.gz] files there")
    common = sorted(set(outcomes) & set(files))
    if len(common) < MIN_TESTS:  # each test is scored by a threshold fitted on the others
        raise InputError(f"data = {str(folder)!r}: {len(common)} test(s) with both a motion file and an outcome; "
                         f"the study needs at least {MIN_TESTS} (each is scored by a threshold fitted on the others)")
    if tests is not None:
        unknown = [t for t in tests if t not in common]
        if unknown:
            raise InputError(f"tests = {unknown[0]}: not among the {len(common)} tests with both a file and an outcome")
        common = sorted(tests)
    return {t: outcomes[t] for t in common}, {t: files[t] for t in common}
