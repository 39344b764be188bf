"""Issue 38: the rigid model's misses test by test and the sliding re-run (experiments/misses.py,
docs/scripts/experiments_misses.py). The oracles are closed forms and hand counts; the shake-table
data (GPL-3.0, ../shared/data/vsr) are read only by the tests that say so, skipped without them."""
import gzip
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isorock.analytic.system import System
from isorock.experiments import misses, study

ROOT = Path(__file__).resolve().parent.parent
VSR = ROOT.parent / "shared" / "data" / "vsr"
G = 9.81
needs_data = pytest.mark.skipif(not (VSR / "results.csv").is_file(),
                                reason=f"shared shake-table data not found at {VSR}")


def test_sliding_replaces_rocking_below_tan_alpha_by_the_closed_form():
    """A block with μ < tanα under a rectangular pulse a0 > g·tanα: without friction it rocks
    (and here falls); with friction it cannot start rocking (the pivot would need more than
    tanα > μ) and slides instead. Coulomb in closed form: relative deceleration a0 − μg for the
    pulse's T, then μg until it stops: slide = (a0 − μg)·a0·T² / (2μg)."""
    block = System.fixed(height=1.0, width=0.2, mass=100.0)          # b/h = tanα = 0.2
    mu, a0, T, dt = 0.1, 0.3 * G, 0.5, 1e-3
    a = np.zeros(2001)
    a[1:int(round(T / dt)) + 1] = a0
    rigid = study.run_block(block, {1: a}, {1: dt})[1]
    assert rigid[0] is True                                            # the rigid block falls
    over, theta, slid, _ = misses.run_sliding(block, {1: a}, {1: dt}, mu)[1]
    assert over is False and theta == 0.0                              # never tips
    expected = (a0 - mu * G) * a0 * T**2 / (2 * mu * G)
    # the record's one-sample ramps (linear between samples) shift the pulse by O(dt/T)
    assert slid == pytest.approx(expected, rel=5e-3)


def test_a_block_that_cannot_slip_at_this_pulse_does_not_slide():
    """A pulse below both μ·g and g·tanα: rest, no slide
    (the contact holds |a| ≤ μg) — the sliding column must say 0, not NaN or noise."""
    block = System.fixed(height=1.0, width=0.2, mass=100.0)
    a = np.zeros(1001)
    a[1:500] = 0.05 * G
    over, theta, slid, _ = misses.run_sliding(block, {1: a}, {1: 1e-3}, 0.5)[1]
    assert over is False and theta == 0.0 and slid == 0.0


def test_counts_by_hand():
    """tally on six hand-made rows: the counts a reader would make."""
    def row(m, r, s, period):
        return {"measured": m, "rigid": r, "rigid_kind": misses.kind(m, r), "period": period,
                "slide_mu0.5": s, "slide_mu0.5_slid_m": 0.0}
    rows = [row(1, 0, 1, "long"),    # a miss sliding fixes
            row(1, 0, 0, "long"),    # a miss it does not
            row(0, 1, 0, "short"),   # a false alarm it fixes
            row(0, 0, 1, "short"),   # a right verdict it breaks
            row(1, 1, 1, "long"),    # right, kept
            row(0, 0, "", "short")]  # a run the contact model could not carry
    c = misses.tally(rows, (0.5,), [])
    assert c["long: misses"] == 2 and c["long: false alarms"] == 0
    assert c["short: misses"] == 0 and c["short: false alarms"] == 1
    assert c["mu 0.5: fixed"] == 2 and c["mu 0.5: broken"] == 1
    assert c["mu 0.5: failed runs"] == 1 and c["mu 0.5: verdict changed"] == 3


def test_bad_friction_exits_2_with_one_line():
    script = ROOT / "docs" / "scripts" / "experiments_misses.py"
    for bad in ("-0.1", "nan", "0.3,abc", "11"):
        p = subprocess.run([sys.executable, str(script), "--friction", bad, "--data", str(ROOT)],
                           capture_output=True, text=True, timeout=120)
        assert p.returncode == 2, (bad, p.stderr)
        assert len(p.stderr.strip().splitlines()) == 1 and "friction" in p.stderr


@needs_data
def test_the_data_hold_only_the_table_x_acceleration():
    """beyond_x reports what a record file holds; the oracle reads the file itself."""
    b = misses.beyond_x(VSR)
    with gzip.open(VSR / "Shake_Table_Response" / b["file"], "rt") as f:
        header = f.readline().rstrip("\n")
        ncols = len(f.readline().split())
    assert b["header"] == header == "Time [s]\tAcceleration [g]" and b["columns"] == ncols == 2


@needs_data
def test_on_three_tests_the_rows_and_counts_agree(tmp_path):
    """On three records (SP1 test 62: the forward block falls, the rock stood) the table's rows
    hold the measured outcome from results.csv and the counts follow from the rows."""
    r = misses.build(VSR, tests=[11, 62, 383], frictions=(0.5,), asymmetric=False)
    misses.write(r, tmp_path)
    text = (tmp_path / "misses.csv").read_text().splitlines()
    assert len(text) == 1 + 6
    sp1_62 = next(x for x in r["rows"] if x["specimen"] == "SP1" and x["test"] == 62)
    assert sp1_62["measured"] == 0 and sp1_62["rigid_kind"] == ("false alarm" if sp1_62["rigid"] else "ok")
    for spec, c in r["counts"].items():
        rows = [x for x in r["rows"] if x["specimen"] == spec]
        wrong = sum(x["rigid"] != x["measured"] for x in rows)
        assert c["long: misses"] + c["long: false alarms"] + c["short: misses"] + c["short: false alarms"] == wrong
        assert c["mu 0.5: fixed"] <= wrong
