"""Where a result came from: isorock's version and git commit, the command line, the
engine and library versions, the platform, and a SHA-256 of every record file read.
Every `--json` and the report's metrics.json carry it, so a number can be traced to the
code and the input that produced it.

`provenance(record_paths=[...])` never fails: what cannot be told is None. Library
versions are read from the installed distributions' metadata, without importing the
libraries (importing MuJoCo or PyBullet to ask their version would cost seconds).
"""
from __future__ import annotations

import hashlib
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path

#: Distribution name → the key it is reported under (the engines and numerical libraries
#: whose version can change a result).
LIBRARIES = {"mujoco": "mujoco", "pybullet": "pybullet", "drake": "drake", "numba": "numba",
             "numpy": "numpy", "scipy": "scipy", "matplotlib": "matplotlib"}
#: The folder holding the isorock packages: in a checkout (editable install) it is the
#: repository's work tree.
PACKAGE_ROOT = Path(__file__).resolve().parents[2]
GIT_TIMEOUT_S = 5.0
_CHUNK = 1 << 20


def _version(distribution: str) -> str | None:
    try:
        return metadata.version(distribution)
    except (metadata.PackageNotFoundError, ValueError):
        return None


def _git(*args: str) -> str | None:
    try:
        out = subprocess.run(["git", "-C", str(PACKAGE_ROOT), *args], capture_output=True, text=True,
                             timeout=GIT_TIMEOUT_S, check=False)
    except (OSError, subprocess.SubprocessError):  # no git, or it hung
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def git_state() -> dict:
    """The commit of the checkout isorock runs from and whether its tracked files differ
    from it (None for both when it is not a git checkout, e.g. a wheel install)."""
    commit = _git("rev-parse", "HEAD")
    if commit is None:
        return {"commit": None, "dirty": None}
    status = _git("status", "--porcelain", "--untracked-files=no")
    return {"commit": commit, "dirty": None if status is None else bool(status)}


def sha256_of(path) -> str | None:
    """The file's SHA-256 (hex), or None when it cannot be read."""
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(_CHUNK), b""):
                digest.update(chunk)
    except OSError:
        return None
    return digest.hexdigest()


def record_files(paths) -> list[dict]:
    """Path (as given and resolved), size and SHA-256 of each record file; a path that
    is not a file (a pulse spec, 'none') is left out."""
    out = []
    for given in paths or ():
        path = Path(given)
        if not path.is_file():
            continue
        out.append({"path": str(given), "resolved": str(path.resolve()), "bytes": path.stat().st_size,
                    "sha256": sha256_of(path)})
    return out


def provenance(record_paths=()) -> dict:
    """Everything needed to trace a result to its code and inputs (JSON-ready)."""
    try:
        argv = [str(a) for a in sys.argv]
    except Exception:  # sys.argv can be absent in an embedded interpreter
        argv = None
    return {
        "isorock_version": _version("isorock"),
        **{f"git_{k}": v for k, v in git_state().items()},
        "command_line": argv,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "machine": platform.machine(),
        "libraries": {key: _version(dist) for dist, key in LIBRARIES.items()},
        "records": record_files(record_paths),
    }
