"""Issue 38: the rigid model's misses test by test and the sliding re-run (experiments/misses.py,
docs/scripts/experiments_misses.py). The oracles are closed forms and hand counts; the shake-table
data (GPL-3.0, ../shared/data/vsr) are read only by the tests that say so, skipped without them."""
import gzip
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isorock.analytic.system import System
from isorock.validate.tools.experiments import misses, study

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
    over, theta, slid = misses.run_sliding(block, {1: a}, {1: dt}, mu)[1]
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
    over, theta, slid = misses.run_sliding(block, {1: a}, {1: 1e-3}, 0.5)[1]
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


def test_the_batched_sliding_runs_are_the_engine_runs_one_by_one():
    """run_sliding's batches (analytic.fast.simulate_batch's summaries, on threads) against the
    analytic engine's own run of each record with its history: the same verdict, θmax/α and
    slide (the largest |slide| of the history, within its sampling)."""
    from isorock.analytic.motion import GroundMotion
    from isorock.validate.core.engines import get_engine
    block = System.fixed(height=1.0, width=0.5, mass=100.0)  # tanα 0.5 > μ 0.3: it slides before it tips
    rng = np.random.default_rng(38)
    dt = 0.005
    accel = {t: np.convolve(rng.normal(0.0, 0.8 * G, 1200), np.ones(8) / 8, mode="same") for t in (1, 2, 3)}
    rows = misses.run_sliding(block, accel, {t: dt for t in accel}, 0.3)
    slid_somewhere = False
    for t, a in accel.items():
        motion = GroundMotion.from_array(a, dt=dt, units="m/s2", name=f"Test{t:03d}")
        tr = get_engine("analytic").simulate(block.with_friction(0.3), motion, duration=motion.end_time + study.PAD)
        over, theta, slid = rows[t]
        assert over == bool(tr.overturned) and theta == pytest.approx(tr.theta_max_over_alpha, rel=1e-9, abs=1e-12)
        history = float(np.max(np.abs(tr.slide)))
        assert history <= slid * (1 + 1e-9) + 1e-12 and slid == pytest.approx(history, rel=1e-3, abs=1e-9)
        slid_somewhere |= slid > 1e-3
    assert slid_somewhere  # the block slid in at least one record: the slide was exercised


@needs_data
def test_the_command_writes_the_study_whole(tmp_path, capsys):
    from isorock.validate.cli.main import main
    out = tmp_path / "m"
    assert main(["experiments", "--misses", "0.5", "--tests", "11,62,383", "--data", str(VSR), "--out", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == ["misses.csv", "misses.md"]
    assert len((out / "misses.csv").read_text().splitlines()) == 1 + 6
    assert "mu 0.5: fixed" in capsys.readouterr().out


@pytest.mark.parametrize("argv, words", [
    (["--misses", "0"], "friction"),
    (["--misses", "abc"], "misses"),
    (["--misses", "0.5", "--fit", "x"], "misses"),
    (["--misses", "0.5", "--overturning-scale"], "misses"),
])
def test_a_bad_misses_option_is_one_line(tmp_path, capsys, argv, words):
    from isorock.validate.cli.main import main
    out = tmp_path / "m"
    assert main(["experiments", *argv, "--data", str(ROOT), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and not out.exists(), err
