"""Campaign results that can be trusted (issue 24, items 1-2): a chunk's id covers the
content of every input it depends on, and every part found in a folder is checked
(ids, schema, row count) before it is reused; what does not check out runs again.
The oracle throughout is a fresh run of the same campaign into an empty folder."""
from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from isorock.validate.tools.campaign import run_campaign
from isorock.validate.tools.campaign.run import PARTS

from test_campaign import assert_same_rows, write_spec

RECORDS_SPEC = """
[campaign]
name = "rec"
analytic_chunk = 2

[systems]
alpha = 0.25
size = 1.0
base = "fixed"

[motions]
type = "records"
folder = "suite"
scale_by = "pga"
levels = [0.3, 0.6, 0.9]

[duration]
tail = 2.0

[[engines]]
name = "analytic"
"""


def _write_record(path: Path, a: np.ndarray, dt=0.01):
    t = np.arange(a.size) * dt
    path.write_text("# units: g\n" + "".join(f"{x:.6f} {y:.9g}\n" for x, y in zip(t, a)))


def _one_sided_record():
    # a strong one-sided push then a weak tail: its time-reversed copy has the same PGA
    # and length but rocks the block differently
    t = np.arange(0, 3.0, 0.01)
    return np.where(t < 0.5, np.sin(2 * np.pi * t / 0.5), 0.05 * np.sin(2 * np.pi * 3 * t))


def test_resumed_sweep_reruns_chunks_of_a_changed_record(tmp_path):
    suite = tmp_path / "suite"
    suite.mkdir()
    a = _one_sided_record()
    _write_record(suite / "r.txt", a)
    spec = tmp_path / "rec.toml"
    spec.write_text(RECORDS_SPEC)
    first = run_campaign(spec, tmp_path / "out", workers=0, progress=False, products=False)
    assert first.tasks_run == first.tasks_total
    _write_record(suite / "r.txt", a[::-1].copy())  # same PGA, same length, other content
    resumed = run_campaign(spec, tmp_path / "out", workers=0, progress=False, products=False)
    fresh = run_campaign(spec, tmp_path / "fresh", workers=0, progress=False, products=False)
    assert resumed.tasks_run == resumed.tasks_total  # nothing of the old record reused
    assert_same_rows(fresh.table, resumed.table)
    # and the change mattered: the old rows differ from the new
    assert first.table["theta_max_over_alpha"].to_pylist() != fresh.table["theta_max_over_alpha"].to_pylist()


@pytest.fixture
def finished(tmp_path):
    spec = write_spec(tmp_path, more="")  # analytic only: 36 cases in chunks of 7 → 6 parts
    out = tmp_path / "out"
    whole = run_campaign(spec, out, workers=0, progress=False, products=False)
    parts = sorted((out / PARTS).glob("*.parquet"))
    assert len(parts) == whole.tasks_total >= 3
    return spec, out, whole, parts


def _damage_copy(parts):
    shutil.copyfile(parts[0], parts[1])  # a part copied over another


def _damage_schema(parts):
    pq.write_table(pa.table({"case": [1, 2], "x": [0.5, 0.25]}), parts[1])


def _damage_bytes(parts):
    parts[1].write_bytes(np.random.default_rng(0).bytes(4000))


def _damage_truncate(parts):
    data = parts[1].read_bytes()
    parts[1].write_bytes(data[:len(data) // 2])


def _damage_empty(parts):
    parts[1].write_bytes(b"")


def _damage_rows(parts):
    t = pq.read_table(parts[1])
    pq.write_table(t.slice(0, t.num_rows - 1), parts[1])  # one row lost


@pytest.mark.parametrize("damage", [_damage_copy, _damage_schema, _damage_bytes, _damage_truncate,
                                    _damage_empty, _damage_rows])
def test_a_part_that_does_not_check_out_is_run_again(finished, damage, capsys):
    spec, out, whole, parts = finished
    damage(parts)
    resumed = run_campaign(spec, out, workers=0, progress=False, products=False)
    assert resumed.tasks_run == 1  # the damaged part only
    assert_same_rows(whole.table, resumed.table)
    cases = resumed.table["case"].to_pylist()
    assert len(cases) == len(set(zip(cases, resumed.table["engine"].to_pylist())))
    assert "parts/" in capsys.readouterr().err  # the user is told which part was redone
