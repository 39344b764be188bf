"""Provenance: version, commit, command line, library versions, record hashes; never fails."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isorock.validate.io import provenance as prov
from isorock.validate.cli.main import main

ABC_SHA256 = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"  # FIPS 180-2 test vector


def test_record_hash_is_sha256_and_non_files_are_left_out(tmp_path):
    f = tmp_path / "rec.txt"
    f.write_bytes(b"abc")
    out = prov.provenance(record_paths=[str(f), "sine:amp=0.3,freq=1", str(tmp_path / "missing.at2")])
    assert [r["sha256"] for r in out["records"]] == [ABC_SHA256]
    assert out["records"][0]["bytes"] == 3


def test_versions_command_line_and_platform():
    import numpy
    out = prov.provenance()
    assert out["libraries"]["numpy"] == numpy.__version__
    assert out["command_line"] == sys.argv
    assert out["python"] == ".".join(map(str, sys.version_info[:3]))
    assert out["isorock_version"]
    assert set(prov.LIBRARIES.values()) <= set(out["libraries"])


def test_commit_is_the_checkouts_head():
    root = prov.PACKAGE_ROOT
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("isorock is not running from a git checkout")
    assert prov.provenance()["git_commit"] == head


def test_never_fails_outside_a_checkout(tmp_path, monkeypatch):
    monkeypatch.setattr(prov, "PACKAGE_ROOT", tmp_path)  # not a git work tree
    out = prov.provenance(record_paths=[tmp_path])  # a folder is not a record file
    assert out["git_commit"] is None and out["git_dirty"] is None
    assert out["records"] == []


def test_run_json_has_provenance_with_the_record_hash(tmp_path, capsys):
    t = np.arange(0, 1.0, 0.01)
    record = tmp_path / "pulse.csv"
    record.write_text("".join(f"{x:.2f},{0.4 * np.sin(2 * np.pi * 2 * x):.6f}\n" for x in t))
    out = tmp_path / "run.json"
    rc = main(["run", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base",
               "--motion", str(record), "--units", "g", "--duration", "1.0", "--quiet", "--json", str(out)])
    assert rc == 0
    data = json.loads(out.read_text())
    # the existing fields stay (a contract); provenance is one new field
    for key in ("engine", "status", "theta_max_over_alpha", "impacts", "system", "motion", "settings"):
        assert key in data
    import hashlib
    assert data["provenance"]["records"][0]["sha256"] == hashlib.sha256(record.read_bytes()).hexdigest()
    assert Path(data["provenance"]["records"][0]["resolved"]) == record.resolve()
