"""The validation machinery itself: comparisons, ensembles, figures, the tolerance
table and the `isorock validate` command end to end (analytic engine only, tiny runs)."""
from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from isorock.analytic import load_motion, paper_system, simulate
from isorock.analytic.errors import InputError
from isorock.analytic.trajectory import Trajectory
from isorock.validate.core import engines as engine_registry
from isorock.validate.io import figures
from isorock.validate.cli.main import main
from isorock.validate.core.compare import AGREEMENT_FRACTION, agreement, compare, exact_first_impact_time, first_tilt
from isorock.validate.core.engines import CONTACT_ENGINES, get_engine
from isorock.validate.io.naming import describe_motion
from isorock.validate.tools.ensemble import Ensemble, scale_factors
from isorock.validate.core.tolerances import TOLERANCES, check, tolerance

PULSE = "ricker:amp=0.5,freq=1"


@pytest.fixture(scope="module")
def pulse_run():
    system = paper_system(fixed_base=True)
    motion = load_motion(PULSE)
    return system, motion, simulate(system, motion, duration=3.0)


def synthetic(system, t, theta, u=None, engine="synthetic"):
    z = np.zeros_like(t)
    return Trajectory(engine=engine, system=system, t=t, u=z if u is None else u, u_dot=z, theta=theta,
                      theta_dot=z, mode=np.sign(theta).astype(np.int8))


# --- compare --------------------------------------------------------------------------

def test_compare_with_itself_agrees_over_the_whole_run(pulse_run):
    _, _, tr = pulse_run
    c = compare(tr, tr)
    assert not c.parted and c.horizon == pytest.approx(tr.t[-1], abs=1e-3)
    assert c.theta_rms_error == 0 and c.theta_max_error == 0 and c.theta_max_diff == 0
    assert c.overturn_agree and c.uplift_agree and c.first_uplift_diff == 0
    assert c.impacts == c.impacts_ref > 0
    assert max(abs(e) for e in c.beta_errors) < 1e-12
    d = c.as_dict()
    assert {"horizon", "theta_rms_error", "beta_errors", "beta_error_median", "overturn_agree"} <= set(d)


def test_horizon_is_where_theta_parts_by_a_tenth_of_alpha():
    system = paper_system(fixed_base=True)
    a = system.alpha
    t = np.linspace(0.0, 2.0, 2001)
    ref = synthetic(system, t, 0.5 * a * np.sin(2 * np.pi * t))
    drift = 0.2 * a * t  # parts when 0.2·α·t = 0.1·α, at t = 0.5 s
    other = synthetic(system, t, ref.theta + drift)
    horizon, parted, rms, worst = agreement(other, ref)
    assert parted and horizon == pytest.approx(0.5, abs=2e-3)
    assert worst <= AGREEMENT_FRACTION + 1e-9
    assert rms == pytest.approx(np.sqrt(np.mean((0.2 * t[t < horizon]) ** 2)), rel=1e-2)
    c = compare(other, ref)
    assert c.theta_max_diff == pytest.approx(other.theta_max_over_alpha - 0.5, abs=1e-9)


def test_first_tilt_interpolates_the_rest_band():
    system = paper_system(fixed_base=True)
    t = np.array([0.0, 1.0, 2.0, 3.0])
    tr = synthetic(system, t, np.array([0.0, 0.0, 2e-3, 4e-3]) * system.alpha)
    assert first_tilt(tr) == pytest.approx(1.5)
    assert first_tilt(synthetic(system, t, np.zeros(4))) is None


def test_exact_first_impact_time_needs_a_fixed_base_and_a_tilt():
    with pytest.raises(ValueError, match="fixed base"):
        exact_first_impact_time(paper_system(), 0.1)
    with pytest.raises(ValueError, match="theta0"):
        exact_first_impact_time(paper_system(fixed_base=True), 0.0)


# --- tolerances ----------------------------------------------------------------------------

def test_contact_engines_share_one_set_of_metrics():
    metrics = {e: {m for (k, m) in TOLERANCES if k == e} for e in CONTACT_ENGINES}
    first = metrics[CONTACT_ENGINES[0]]
    assert all(m == first for m in metrics.values()), metrics


def test_check_passes_fails_and_refuses_missing_values():
    limit = tolerance("mujoco", "beta_rel_error").limit
    assert check("mujoco", "beta_rel_error", "s", limit / 2).status == "pass"
    assert check("mujoco", "beta_rel_error", "s", limit * 2).status == "fail"
    assert check("mujoco", "beta_rel_error", "s", math.nan).status == "fail"
    assert check("mujoco", "beta_rel_error", "s", None).note == "could not be measured"
    assert check("mujoco", "overturn_agree", "s", False).status == "fail"
    with pytest.raises(InputError, match="not in the table"):
        tolerance("mujoco", "no_such_metric")


# --- ensembles -----------------------------------------------------------------------------

ENSEMBLE_SCALES = [0.8, 1.0, 1.4]


def test_ensembles_equal_runs_made_one_at_a_time(monkeypatch):
    """The ensembles' runs go through the campaign machinery (the analytic kernel in a
    batch, MuJoCo's batch path, a preset as its own column): every θmax/α and verdict is
    the one a single run of that engine gives. A run that raises is NaN with its message."""
    from isorock.mujoco_models import stepping
    from isorock.validate.tools.ensemble import run_ensembles
    real = stepping._run

    def flaky(model, system, motion, *args):  # MuJoCo raises above 0.6 g
        if motion.pga_g > 0.6:
            raise RuntimeError("boom")
        return real(model, system, motion, *args)
    monkeypatch.setattr(stepping, "_run", flaky)
    motion = load_motion(PULSE)
    specs = [(paper_system(fixed_base=True), motion, "fixed", 2.0, ENSEMBLE_SCALES),
             (paper_system(), motion, "isolated", 2.0, ENSEMBLE_SCALES[:2])]
    engines = ["analytic", "mujoco:fast", "analytic:conservative"]
    ensembles = run_ensembles(specs, engines, threads=2)
    assert len(ensembles) == 2
    for (system, m, label, duration, scales), ens in zip(specs, ensembles):
        assert ens.motion == label and list(ens.scales) == scales
        for name in engines:
            base, _, preset = name.partition(":")
            engine = get_engine(base)
            for k, f in enumerate(scales):
                if base == "mujoco" and m.pga_g * f > 0.6:
                    assert math.isnan(ens.theta_max[name][k]) and (f, "RuntimeError: boom") in ens.failed[name]
                    continue
                settings = engine.preset(preset) if preset else engine.settings()
                alone = engine.simulate(system, m.scaled(f), settings=settings, duration=duration)
                assert ens.theta_max[name][k] == pytest.approx(alone.theta_max_over_alpha, rel=1e-9, abs=1e-12)
                assert ens.overturned[name][k] == alone.overturned
    fixed = ensembles[0]
    assert fixed.failed["mujoco:fast"] == [(1.4, "RuntimeError: boom")] and "analytic" not in fixed.failed
    assert fixed.agreement("mujoco:fast")["cases"] == 2
    d = json.loads(json.dumps(fixed.as_dict(), default=float, allow_nan=True))
    assert d["scales"] == ENSEMBLE_SCALES and set(d["agreement"]) == {"mujoco:fast", "analytic:conservative"}


def test_ensemble_agreement_counts_overturning():
    system = paper_system()
    ens = Ensemble(system=system, motion="m", pga_g=1.0, duration=1.0, scales=np.array([1.0, 2.0, 3.0, 4.0]),
                   theta_max={"analytic": np.array([0.1, 0.5, 1.0, 1.0]), "x": np.array([0.2, 0.5, 0.9, 1.0])},
                   overturned={"analytic": np.array([0, 0, 1, 1], bool), "x": np.array([0, 0, 0, 1], bool)})
    a = ens.agreement("x")
    assert a["overturn_agreement"] == 0.75
    assert a["median_theta_max_diff"] == pytest.approx(0.05)
    assert a["max_theta_max_diff"] == pytest.approx(0.1)
    assert a["rocking_cases"] == 2 and a["median_theta_max_diff_rocking"] == pytest.approx(0.05)
    # a chaotic reference peak (not robust under ±1% of the motion) tests no engine: left out
    chaotic = Ensemble(system=system, motion="m", pga_g=1.0, duration=1.0, scales=ens.scales,
                       theta_max=ens.theta_max, overturned=ens.overturned, robust=np.array([1, 0, 1, 1], bool))
    b = chaotic.agreement("x")
    assert b["rocking_cases"] == 1 and b["median_theta_max_diff_rocking"] == pytest.approx(0.1)


def test_scale_factors():
    assert np.allclose(scale_factors(), np.linspace(0.25, 1.5, 21))
    for bad in ((0.0, 1.0, 3), (1.0, 0.5, 3), (0.5, 1.0, 2.5)):
        with pytest.raises(InputError):
            scale_factors(*bad)
    from isorock.validate.tools.ensemble import run_ensembles
    with pytest.raises(InputError, match="analytic"):
        run_ensembles([(paper_system(), load_motion(PULSE), "m", 1.0, [1.0])], ["mujoco"])


# --- figures ------------------------------------------------------------------------------

def test_figures_write_png(tmp_path, pulse_run):
    system, motion, tr = pulse_run
    iso = simulate(paper_system(), motion, duration=3.0)
    png = b"\x89PNG"
    figures.beta_slenderness([{"engine": "mujoco", "mass_ratio": 1.0, "slenderness": 2.857, "beta": 0.75,
                               "beta2_over_h": 0.3}], tmp_path / "a.png")
    figures.history(motion, {"analytic": tr, "twin": tr}, tmp_path / "b.png", title="a fixed base")
    figures.beta_per_impact([("free", [("paper", "mujoco", [0.001, -0.002])]), ("forced", [])], tmp_path / "c.png",
                            bands={"mujoco": 0.01})
    ens = Ensemble(system=system, motion="m", pga_g=0.5, duration=1.0, scales=np.array([1.0, 2.0]),
                   theta_max={"analytic": np.array([0.2, 1.0])}, overturned={"analytic": np.array([False, True])})
    figures.ensemble([ens], tmp_path / "d.png", bands={"mujoco": 0.02})
    figures.history(motion, {"analytic": iso}, tmp_path / "e.png", title="an isolated base")
    for name in "abcde":
        assert (tmp_path / f"{name}.png").read_bytes()[:4] == png


# --- the report, end to end ------------------------------------------------------------------

TINY = ["validate", "--quick", "--motion", PULSE, "--scales", "0.8,1.0,2", "--duration", "3", "--quiet"]


def test_validate_end_to_end_with_a_missing_engine(tmp_path, monkeypatch, capsys):
    # an engine whose module is missing is skipped with a note, not a crash
    monkeypatch.setitem(engine_registry.ENGINE_MODULES, "ghost", "no_such_engine_module")
    out = tmp_path / "rep"
    assert main(TINY + ["--engines", "analytic", "ghost", "--out", str(out)]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1].startswith("Result: all")
    for name in ("report.md", "report.html", "metrics.json", "fig4_beta_slenderness.png", "ensemble.png",
                 "beta_per_impact.png", "history_1.png", "history_2.png"):
        assert (out / name).is_file(), name
    m = json.loads((out / "metrics.json").read_text())
    assert {"config", "versions", "engines", "free_rocking", "scenarios", "ensembles", "checks", "passed",
            "verdict"} <= set(m)
    assert m["passed"] is True and m["engines"]["ghost"].startswith("skipped: module no_such_engine_module")
    assert {"python", "numpy", "scipy", "mujoco", "pybullet"} <= set(m["versions"])
    named = describe_motion(load_motion(PULSE))  # readable names, not spec strings
    assert [sc["name"] for sc in m["scenarios"]] == [f"{named}, isolated base", f"{named}, fixed base"]
    assert named == "Ricker wavelet 0.5 g, 1 Hz"
    assert m["provenance"]["command_line"] and "isorock_version" in m["provenance"]
    assert all(c["status"] in ("pass", "skip") for c in m["checks"]) and m["checks"]
    md = (out / "report.md").read_text()
    assert "SKIPPED" in md and "<details><summary>All" in md and md.rstrip().splitlines()[-1].startswith("Result: all")
    assert md.splitlines()[2].startswith("**Result: all")  # the verdict comes first
    assert md.count("data:image/png;base64") == 0
    # Figure 4, β per impact, one history per motion and base, the ensemble
    assert (out / "report.html").read_text().count("data:image/png;base64,") == 5


def test_validate_exit_code_1_when_a_check_fails(tmp_path, monkeypatch, capsys):
    key = ("analytic", "beta_rel_error")
    monkeypatch.setitem(TOLERANCES, key, replace(TOLERANCES[key], limit=-1.0))
    out = tmp_path / "rep"
    assert main(TINY + ["--engines", "analytic", "--out", str(out)]) == 1
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("Result: FAILED") and "analytic beta_rel_error" in last
    assert json.loads((out / "metrics.json").read_text())["passed"] is False


@pytest.mark.parametrize("bad", [
    ["--motion", "sine:amp=0.5"],             # pulse without freq
    ["--motion", "no/such/file.AT2"],
    ["--motion", "none"],
    ["--engines", "mujoco"],                  # no analytic reference
    ["--engines", "analytic", "warp"],
    ["--engines", "analytic", "mujoco", "mujoco"],  # the same engine twice: once is meant
    ["--scales", "1,0.5,3"],
    ["--scales", "abc"],
    ["--duration", "-1"],
])
def test_validate_bad_input_exits_2_and_writes_nothing(tmp_path, capsys, bad):
    out = tmp_path / "rep"
    args = ["validate", "--quick", "--quiet", "--out", str(out), "--engines", "analytic"] + bad
    assert main(args) == 2
    assert "error" in capsys.readouterr().err
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_engines_are_read_alike_by_every_command():
    """validate, bench and atlas take --engines through one parser (run_cli.engine_labels):
    items space- or comma-separated, a comma left at an item's end as in 'analytic, mujoco'."""
    from isorock.validate.io.inputs import engine_labels
    want = ["analytic", "mujoco:fast", "bullet"]
    assert engine_labels(["analytic,", "mujoco:fast", "bullet"]) == want
    assert engine_labels(["analytic,mujoco:fast,bullet"]) == want
    assert engine_labels(["analytic", " mujoco:fast ,bullet"]) == want
    with pytest.raises(InputError, match="once"):
        engine_labels(["analytic", "analytic"])


def test_validate_sets_kobe_beside_the_paper(tmp_path, kobe_at2):
    out = tmp_path / "rep"
    rc = main(["validate", "--quick", "--quiet", "--engines", "analytic", "--motion", str(kobe_at2),
               "--duration", "12", "--scales", "1,1,1", "--out", str(out)])
    assert rc == 0
    m = json.loads((out / "metrics.json").read_text())
    paper = m["paper_figure5"]
    assert paper["isolated base"]["paper_theta_max_over_alpha"] == 0.64
    assert paper["fixed base"]["paper_theta_max_over_alpha"] == 0.95
    # the fixed base overturns at 9.2 s in the reference integration (model.md): past α it
    # goes on until it lies on its side, |θ| = π/2 (model.md, "Past α")
    assert paper["fixed base"]["analytic"] == pytest.approx(0.5 * math.pi / paper_system().alpha)
    md = (out / "report.md").read_text()
    assert "Where and why our numbers differ from the paper's" in md and "unreadable" in md


def test_a_motion_that_lifts_nothing_is_not_exercised_never_passed(tmp_path, capsys):
    """0.2 g lifts the paper's block on neither base (uplift needs 0.35 g): the history and
    ensemble checks of MuJoCo are 'not exercised', counted apart, and its verdict has a caveat."""
    out = tmp_path / "rep"
    rc = main(["validate", "--quick", "--quiet", "--engines", "analytic", "mujoco", "--motion",
               "sine:amp=0.2,freq=1.3,cycles=1", "--scales", "1,1,1", "--duration", "2", "--workers", "1",
               "--out", str(out)])
    assert rc == 0
    m = json.loads((out / "metrics.json").read_text())
    assert [sc["exercised"] for sc in m["scenarios"]] == [False, False]
    idle = [c for c in m["checks"] if c["status"] == "not exercised"]
    assert idle and all(c["engine"] == "mujoco" for c in idle)
    assert "uplift needs ≈ 0.35 g" in idle[0]["note"]
    assert m["engine_verdicts"]["mujoco"]["verdict"] == "agrees with caveats"
    assert f"{len(idle)} not exercised" in m["verdict"] and m["verdict"] == capsys.readouterr().out.splitlines()[-1]
    assert all(c["status"] == "pass" for c in m["checks"] if c["scenario"].startswith("free rocking"))


def test_validate_takes_your_own_system(tmp_path, capsys):
    out = tmp_path / "rep"
    rc = main(["validate", "--quick", "--quiet", "--engines", "analytic", "--height", "1.2", "--width", "0.3",
               "--mass", "200", "--base-mass", "400", "--period", "2", "--damping-ratio", "0.1",
               "--motion", "sine:amp=0.5,freq=1.5,cycles=2", "--scales", "1,1.2,2", "--out", str(out)])
    assert rc == 0
    m = json.loads((out / "metrics.json").read_text())
    systems = [sc["system"] for sc in m["scenarios"]]
    assert [s["height"] for s in systems] == [1.2, 1.2] and [s["fixed_base"] for s in systems] == [False, True]
    assert systems[0]["period"] == pytest.approx(2.0) and systems[0]["mass_ratio"] == pytest.approx(0.5)
    assert "your block (H 1.2 m" in (out / "report.md").read_text()


def test_a_config_file_with_an_unknown_key_is_bad_input(tmp_path, capsys):
    cfg = tmp_path / "statue.toml"
    cfg.write_text("[system]\nheight = 1.2\nwidht = 0.3\n")
    assert main(["validate", "--config", str(cfg), "--out", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert "system.widht" in err and err.count("\n") == 1
    assert not (tmp_path / "rep").exists()


def test_validate_scales_its_motions_to_a_target_pga():
    """`validate --pga G` (issue 25): every motion the report runs has that peak."""
    from isorock.validate.tools.report_run import ReportConfig, load_motions
    for target in (0.25, 0.9):
        motions = load_motions(ReportConfig(motions=("sine:amp=0.6,freq=1.3,cycles=2", "ricker:amp=0.5,freq=1"),
                                            pga=target))
        assert [round(m.pga_g, 12) for m, _ in motions] == [target, target]
    with pytest.raises(InputError, match="pga/pgv"):
        ReportConfig(pga=0.3, pgv=0.2)


def test_the_verdict_line_names_what_the_ensembles_decided_and_with_what_confidence():
    """Issue 20: the report's line says, per engine, which quantity agreed, disagreed or
    stayed open, at the table's confidence, and the ensemble size the open ones need; the
    scorecard shows the interval against the limit (never a margin on a fraction)."""
    from isorock.validate.core.tolerances import judged, limit
    from isorock.validate.core.verdict import AGREES, DISAGREES, INCONCLUSIVE, Verdict
    from isorock.validate.tools.report_render import engine_verdicts, scorecard, verdict
    from isorock.validate.tools.report_run import QUICK, ReportConfig, Results

    def v(word, lo, hi, need=None):
        return Verdict("q", (lo + hi) / 2, (lo, hi), 0.1, limit("verdict_confidence"), 6, word, need)

    checks = [judged("mujoco", "ensemble_overturn_median", "ensemble a", v(AGREES, -0.05, 0.05)),
              judged("mujoco", "ensemble_overturn_median", "ensemble b", v(INCONCLUSIVE, -0.2, 0.2, 12)),
              judged("bullet", "ensemble_overturn_median", "ensemble a", v(DISAGREES, 0.3, 0.5)),
              judged("bullet", "ensemble_theta_max_diff", "ensemble a", v(INCONCLUSIVE, -0.05, 0.05, 40))]
    results = Results(config=ReportConfig(quick=True), engines={"analytic": None, "mujoco": None, "bullet": None},
                      skipped={}, free=[], scenarios=[], ensembles=[], checks=checks, versions={}, started="")
    line = verdict(results)
    assert line.startswith("Result: FAILED — 1 of 4 checks failed (bullet ensemble_overturn_median)")
    assert "ensembles judged at 95% confidence" in line
    assert "MuJoCo overturning median 1 agrees, 1 inconclusive" in line
    assert "PyBullet overturning median 1 DISAGREES, median θmax/α 1 inconclusive" in line
    assert "about 12–40 cases would decide the inconclusive; this run judged 6" in line
    words = engine_verdicts(results)
    assert words["mujoco"][0] == "agrees with caveats" and words["bullet"][0] == "disagrees"
    _, rows = scorecard(results)
    cells = {r[0]: r for r in rows}["ensemble overturning (fragility)"]
    assert "[-0.05, +0.05] within ±0.1 at 95%" in cells[2] and "inconclusive [-0.2, +0.2] against ±0.1" in cells[2]
    assert "[+0.3, +0.5] beyond ±0.1" in cells[3]
    assert all("margin" not in c for c in cells[1:])


def test_the_verdict_line_says_how_much_was_not_judged():
    """(issue 25) "agrees with caveats" with checks not exercised says how many, in the
    line itself, and "all N checks passed" never hides the checks not made."""
    from types import SimpleNamespace

    from isorock.validate.tools.report_render import NOT_EXERCISED, verdict

    def check(engine, status):
        return SimpleNamespace(engine=engine, metric="theta_max_diff", status=status, interval=None, note="",
                               scenario="s")
    checks = ([check("analytic", "pass")] * 2 + [check("mujoco", "pass")] * 18 + [check("mujoco", NOT_EXERCISED)] * 11
              + [check("mujoco", "skip")] * 2 + [check("bullet", "pass")] * 20)
    results = SimpleNamespace(checks=checks, engines=("analytic", "mujoco", "bullet"), scenarios=[], skipped={},
                              failed=[])
    line = verdict(results)
    assert line.startswith("Result: all 40 checks made passed, 13 of 53 not made (2 skipped, 11 not exercised, "
                           "0 inconclusive)")
    assert "MuJoCo agrees with caveats (11 of 31 checks not exercised, 2 skipped)" in line
    assert "PyBullet agrees." in line or "PyBullet agrees;" in line or line.endswith("PyBullet agrees.")


def test_the_verdict_says_on_which_base_the_block_never_lifted():
    """(issue 39) The museum's bust on its isolator never lifts at the site's PGA: its contact was
    not tested there, and the verdict line says where, not only how many checks."""
    from types import SimpleNamespace

    from isorock.validate.tools.report_render import NOT_EXERCISED, engine_verdicts, verdict

    def check(scenario, status):
        return SimpleNamespace(engine="mujoco", metric="theta_max_diff", status=status, interval=None, note="",
                               scenario=scenario)
    scenarios = [SimpleNamespace(name=f"{m}, {b}", system=SimpleNamespace(fixed_base=b == "fixed", subject="the block"), runs={})
                 for m in ("sine", "ricker") for b in ("isolated", "fixed")]
    checks = ([check("sine, isolated", NOT_EXERCISED)] * 4 + [check("ricker, isolated", NOT_EXERCISED)] * 4
              + [check("sine, fixed", "pass")] * 4 + [check("ricker, fixed", "pass")] * 3
              + [check("ricker, fixed", NOT_EXERCISED)])
    results = SimpleNamespace(checks=checks, engines=("mujoco",), scenarios=scenarios, skipped={}, failed=[])
    line = verdict(results)
    assert ("MuJoCo agrees with caveats (9 of 16 checks not exercised: the block never lifted on the isolated "
            "base under any motion)") in line
    assert "nothing about contact was tested there" in engine_verdicts(results)["mujoco"][1][0]
    # a base where some histories lifted is counted, not named
    checks[0] = check("sine, isolated", "pass")
    assert "the block never lifted in 1 of 4 histories" in verdict(results)


def test_an_engine_without_an_ensemble_limit_is_skipped_with_its_reason_not_a_late_exit():
    """The README's Drake example (`validate --quick --engines analytic drake`) ran 7 minutes
    and then exited 2: "tolerance ('drake', 'ensemble_theta_max_diff'): not in the table".
    An ensemble metric without a limit for the engine is a skipped check saying so, as a
    single history's metric without one is. Oracle: the table itself (has_tolerance)."""
    import numpy as np

    from isorock.analytic import paper_system
    from isorock.validate.core.tolerances import has_tolerance
    from isorock.validate.tools.ensemble import Ensemble
    from isorock.validate.tools.report_run import _ensemble_checks
    assert not has_tolerance("drake", "ensemble_theta_max_diff")  # the case this test is about
    scales = np.linspace(1.0, 2.0, 6)
    theta = np.array([0.3, 0.5, 0.7, 0.9, 5.0, 5.0])
    ens = Ensemble(system=paper_system(), motion="m", pga_g=0.3, duration=5.0, scales=scales,
                   theta_max={"analytic": theta, "drake": theta * 1.01},
                   overturned={"analytic": theta > 1, "drake": theta > 1})
    checks = _ensemble_checks(ens, "x", ["analytic", "drake"])
    by_metric = {c.metric: c for c in checks if c.engine == "drake"}
    assert by_metric["ensemble_theta_max_diff"].status == "skip"
    assert "no tolerance for drake" in by_metric["ensemble_theta_max_diff"].note
    assert by_metric["ensemble_overturn_median"].status != "skip"  # Drake has this limit: judged


def test_the_report_judges_a_statue_that_slides(tmp_path, capsys):
    """Issue 33: the default report slides the paper's block on a fixed base with μ_s 0.2 under each
    motion; PyBullet's largest and final slide are judged against the exact model's by the slide
    rows (×b), and the exact slide is the rigid-plastic block's: it never lifts (θmax/α 0)."""
    out = tmp_path / "rep"
    rc = main(["validate", "--quick", "--quiet", "--engines", "analytic", "bullet", "--motion",
               "sine:amp=0.6,freq=1.3,cycles=2", "--scales", "1,1,1", "--duration", "4", "--workers", "1",
               "--out", str(out)])
    assert rc == 0
    m = json.loads((out / "metrics.json").read_text())
    (sc,) = m["sliding"]
    assert sc["system"]["friction"] == 0.2 and sc["exercised"]
    exact = sc["runs"]["analytic"]
    assert exact["theta_max_over_alpha"] == 0.0 and exact["slide_max"] > 0.1  # 24 cm, never lifting
    slides = {c["metric"]: c for c in m["checks"] if c["scenario"] == sc["name"] and c["engine"] == "bullet"}
    assert {"slide_max", "slide_final", "slide_onset", "overturn_agree"} <= set(slides)
    assert all(c["status"] == "pass" for c in slides.values())
    assert "Where the statue slides" in (out / "report.md").read_text()


def test_an_inconclusive_check_of_too_few_cases_says_so_not_that_it_straddles():
    """(issue 39) "inconclusive" was explained as "the interval straddles its limit" beside an
    interval wholly inside it: with n = 1 the ensemble has no interval (core.verdict's
    min_cases). Oracle: the verdict rule itself, run on one case and on many."""
    from types import SimpleNamespace

    from isorock.validate.core.tolerances import judged
    from isorock.validate.core.verdict import quantile_verdict
    from isorock.validate.tools.report_render import engine_verdicts, scorecard
    rng = np.random.default_rng(1)
    one = quantile_verdict([0.501], [0.50], limit=0.02, confidence=0.95, min_cases=5)
    ref = rng.uniform(0.2, 0.8, 40)
    many = quantile_verdict(ref + 0.02 + rng.normal(0, 0.01, 40), ref, limit=0.02, confidence=0.95, min_cases=5)
    assert one.word == many.word == "inconclusive" and one.n == 1 and many.n == 40
    lo, hi = one.interval
    assert -0.02 < lo <= hi < 0.02  # wholly inside the limit, and still nothing decided
    checks = [judged("mujoco", "ensemble_theta_max_diff", "ensemble a", one),
              judged("mujoco", "ensemble_theta_max_diff", "ensemble b", many)]
    results = SimpleNamespace(checks=checks, engines=("mujoco",), scenarios=[], skipped={}, failed=[])
    reason = [r for r in engine_verdicts(results)["mujoco"][1] if "inconclusive" in r][0]
    assert "1 with too few cases for an interval (n = 1)" in reason and "1 whose interval straddles" in reason
    _, rows = scorecard(results)
    cell = {r[0]: r for r in rows}["ensemble θmax/α"][1]
    assert cell.count("too few cases") == 1 and "n = 1" in cell
