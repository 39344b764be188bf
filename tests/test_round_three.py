"""Issue 34's hostile-input defects (and issue 39's overlapping ones), each by its own test,
written before its fix; the breadth of hostile cases is tests/adversarial_round_three.py
(run by tests/test_adversarial.py)."""
from __future__ import annotations

import pytest

from isorock.analytic.errors import InputError
from isorock.validate.cli.main import main


def _one_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err


# --- item 4: an empty value is never replaced by a default -----------------------------------

@pytest.mark.parametrize("argv, option", [
    (["design", "--periods", ""], "--periods"),
    (["design", "--isolator", "ball-in-cone", "--slopes", " "], "--slopes"),
    (["design", "--config", ""], "--config"),
    (["design", "--records", ""], "--records"),
    (["validate", "--config", ""], "--config"),
    (["run", "--fixed-base", "--motion", ""], "--motion"),
    (["sweep", "c.toml", "--out", ""], "--out"),
    (["sweep", "c.toml", "--scheduler", ""], "--scheduler"),
    (["sweep", ""], "spec"),
    (["experiments", "--steps", ""], "--steps"),
])
def test_an_empty_value_is_refused_by_its_option(argv, option, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = _one_line(capsys)
    assert option in err and "empty" in err
    assert list(tmp_path.iterdir()) == []  # nothing ran, nothing written


# --- item 6: a TOML file is bounded before any parser sees it, in one place ----------------

#: (text, what the refusal names): each once handed to tomllib as it was (a ValueError past
#: Python's 4,300-digit limit, a RecursionError, minutes of a quadratic walk)
HOSTILE_TOML = [
    ("height = " + "9" * 5000 + "\n", "digits"),
    ("x = " + "[" * 100_000 + "]" * 100_000 + "\n", "nested"),
    ("x = " + "{a = " * 50_000 + "1" + "}" * 50_000 + "\n", "nested"),
    (".".join(["a"] * 50_000) + " = 1\n", "parts"),
    ("[" + ".".join(["t"] * 50_000) + "]\n", "parts"),
    ("# pad\n" * 200_000, "MiB"),
]


def _readers():
    from isorock.validate.tools.campaign.spec import load_spec
    from isorock.validate.io.config_file import read_config
    return {"config": read_config, "campaign": load_spec}


@pytest.mark.parametrize("reader", ["config", "campaign"])
@pytest.mark.parametrize("text, named", HOSTILE_TOML, ids=["digits", "arrays", "inline tables", "dotted key",
                                                          "table header", "size"])
def test_every_toml_reader_bounds_the_file_before_parsing_it(tmp_path, reader, text, named):
    path = tmp_path / "f.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=named) as e:
        _readers()[reader](path)
    assert "f.toml" in str(e.value) and "\n" not in str(e.value)


def test_the_bounds_pass_what_a_lawful_file_holds():
    """Strings (with brackets, dots, digits and '#' in them), floats, dates, dotted keys and
    tables of every kind, as the scan sees them: the parser's own answer comes back."""
    from isorock.validate.io.schema import parse_toml
    text = ('a.b."c.d" = "x.y.z [[[{{{ 999 # not a comment"\n'
            "f = [1.5, 2.5e-3, 1979-05-27T07:32:00.999, 0x" + "f" * 900 + "]\n"
            "[t.u]\nv = {w.x = 1, y = [[1], [2]]}\n"
            "[[arr.of.tables]]\nlit = '''a . b\n[ ] ]'''\nml = \"\"\"q\\\"\"\" . [\"\"\"\n")
    import tomllib
    assert parse_toml(text.encode(), "where") == tomllib.loads(text)
    deep = "x = " + "[" * 32 + "]" * 32 + "\n"
    assert parse_toml(deep.encode(), "where") == tomllib.loads(deep)
    with pytest.raises(InputError, match="nested"):
        parse_toml(("x = " + "[" * 33 + "]" * 33 + "\n").encode(), "where")


# --- items 3 and 5: a design's axes and weights at the edge of a float ----------------------

@pytest.mark.parametrize("option, text", [("periods", "1:4:inf"), ("pga", "0.1:1:inf"),
                                          ("damping-ratios", "0.05:0.3:-inf"), ("periods", "1:4:1e400"),
                                          ("periods", "1:4:nan"), ("periods", "1:2:3:4")])
def test_an_axis_range_whose_count_is_not_a_whole_number_is_one_line(option, text):
    from isorock.validate.cli.design import parse_grid
    with pytest.raises(InputError, match=f"--{option}"):
        parse_grid(option, text)


@pytest.mark.parametrize("weights, want", [((1e308, 1e308), (0.5, 0.5)), ((5e-324, 5e-324), (0.5, 0.5)),
                                           ((1e308, 1e307, 1e306), (100 / 111, 10 / 111, 1 / 111))])
def test_level_weights_are_normalised_without_overflow(weights, want):
    """Closed form: w_i / Σw. 1e308 + 1e308 overflowed to inf and the weights to 0, 0: an
    isolator that fell at every level read 'P 0.0% over the hazard'."""
    from isorock.analytic.motion import GroundMotion
    from isorock.validate.tools.campaign.design import Hazard
    record = GroundMotion.from_array([0.0, 0.3, -0.2, 0.0], dt=0.01, units="g", name="r")
    hazard = Hazard({"r": record}, tuple(0.1 * (k + 1) for k in range(len(weights))), weights)
    assert hazard.weights == pytest.approx(want, rel=1e-15)


@pytest.mark.parametrize("argv", [
    ["run", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--period", "1e-300",
     "--damping-ratio", "0.1"],
    ["run", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--period", "1e308",
     "--damping-ratio", "0.1"],
    ["design", "--records", "recs", "--periods", "1e-300", "--damping-ratios", "0.1", "--pga", "0.5"],
    ["validate", "--config", "v.toml", "--quick"],
])
def test_a_period_no_isolator_has_is_one_line_naming_it(argv, tmp_path, monkeypatch, capsys):
    """A period of 1e-300 s overflowed the stiffness M·(2π/T)² (OverflowError); 1e308 s
    made it 0 and the line named a stiffness nobody gave."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "recs").mkdir()
    (tmp_path / "recs" / "r.txt").write_text("# units: g\n0 0\n0.01 0.3\n0.02 -0.2\n0.03 0\n")
    (tmp_path / "v.toml").write_text("[system]\nheight = 2.0\nwidth = 0.7\nmass = 3800\nbase_mass = 3800\n"
                                     "period = 1e-300\ndamping_ratio = 0.2\n")
    assert main(argv) == 2
    assert "period" in _one_line(capsys)


# --- item 9: an acceleration no earthquake has is refused before any run ----------------------

def _spike(g: float):
    from isorock.analytic.motion import GroundMotion
    return GroundMotion.from_array([0.0, g, 0.0, 0.0], dt=0.01, units="g", name="spike")


@pytest.mark.parametrize("g", [1e300, -1e300, 1e40, 1e25, 101.0])
@pytest.mark.parametrize("engine", ["analytic", "analytic-reference"])
def test_a_record_past_the_acceleration_bound_is_refused_before_any_run(g, engine):
    """The compiled kernel spun for ever on one sample of 1e40 or 1e300 g on an isolated base
    (and the budget, a Python callback, could not stop it); 1e25 g ran 200,000 events."""
    from isorock.analytic.limits import MAX_PGA_G
    from isorock.analytic.system import System
    from isorock.validate.core.engines import get_engine
    system = System.isolated(height=2, width=0.7, mass=3800, base_mass=3800, period=1.5, damping_ratio=0.2)
    with pytest.raises(InputError, match="MAX_PGA_G"):
        get_engine(engine).simulate(system, _spike(g))
    assert abs(g) > MAX_PGA_G


def test_the_kernel_ends_cleanly_up_to_the_bound_and_far_past_it():
    """Below the bound every isolator the kernel carries, on blocks from a millimetre to 100 m,
    ends a one-sample spike, its negative and a sustained sine as completed or overturned
    (measured: the longest of them 0.2 s at 1e10 g; the kernel spun from about 1e25 g)."""
    import numpy as np

    from isorock.analytic.fast import simulate_fast
    from isorock.analytic.limits import MAX_PGA_G
    from isorock.analytic.motion import GroundMotion
    from isorock.analytic.system import BallInBowl, BallInCone, BilinearIsolator, FrictionPendulum, System
    for g in (MAX_PGA_G, 1e4 * MAX_PGA_G):
        motions = [_spike(g), _spike(-g), GroundMotion.from_array(g * np.sin(4 * np.pi * np.arange(200) * 0.01),
                                                                  dt=0.01, units="g", name="sine")]
        for H, B, m in ((2, 0.7, 3800), (1e-3, 3e-4, 1e-3), (100, 30, 1e7)):
            block = dict(height=H, width=B, mass=m, base_mass=m)
            systems = [System.fixed(height=H, width=B, mass=m),
                       System.isolated(**block, period=1.5, damping_ratio=0.2),
                       System.isolated(**block, period=0.01, damping_ratio=0.0),
                       System.with_isolator(**block, isolator=FrictionPendulum(1.0, 0.1)),
                       System.with_isolator(**block, isolator=BallInCone(0.1, 0.02)),
                       System.with_isolator(**block, isolator=BallInBowl(1.0, 0.01)),
                       System.with_isolator(**block, isolator=BilinearIsolator(
                           stiffness=20 * m, damping=m, post_yield_ratio=0.1, yield_displacement=0.01))]
            for system in systems:
                for motion in motions:
                    tr = simulate_fast(system, motion, duration=motion.end_time + 2) if abs(g) <= MAX_PGA_G else \
                        _unchecked(system, motion)
                    assert str(tr.status) in ("completed", "overturned"), (H, system.isolator_kind, g, tr.message)


def _unchecked(system, motion):
    """simulate_fast past the bound (the margin): the refusal is the front door's, not the kernel's."""
    from unittest import mock

    from isorock.analytic import limits
    from isorock.analytic.fast import simulate_fast
    with mock.patch.object(limits, "check_acceleration", lambda *a, **k: None):
        return simulate_fast(system, motion, duration=motion.end_time + 2)


def test_design_and_campaign_levels_past_the_bound_are_refused():
    from isorock.analytic.motion import GroundMotion
    from isorock.validate.tools.campaign.design import Hazard
    record = GroundMotion.from_array([0.0, 0.3, -0.2, 0.0], dt=0.01, units="g", name="r")
    with pytest.raises(InputError, match="MAX_PGA_G"):
        Hazard({"r": record}, (0.5, 1e300))


@pytest.mark.parametrize("motions", [
    'type = "pulse"\npulse = "sine"\nfrequency_ratio = 2.0\namplitude_ratio = [0.9, 1e300]\n',
    'type = "pulse"\npulse = "sine"\nfrequency_ratio = 2.0\namplitude_ratio = 500.0\n',
    'type = "records"\nfolder = "recs"\nscale_by = "pga"\nlevels = [0.5, 1e300]\n',
    'type = "records"\nfolder = "recs"\nscale_by = "pgv"\nlevels = [0.5, 1e6]\n',
])
def test_a_campaign_past_the_acceleration_bound_runs_nothing(tmp_path, motions):
    from isorock.validate.tools.campaign.run import run_campaign
    (tmp_path / "recs").mkdir()
    (tmp_path / "recs" / "r.txt").write_text("# units: g\n0 0\n0.01 0.3\n0.02 -0.2\n0.03 0\n")
    spec = tmp_path / "c.toml"
    spec.write_text(f'[systems]\nalpha = 0.25\nsize = 1.0\nbase = "fixed"\n\n[motions]\n{motions}\n'
                    '[[engines]]\nname = "analytic"\n')
    with pytest.raises(InputError, match="MAX_PGA_G"):
        run_campaign(spec, tmp_path / "out", workers=0, progress=False, products=False)
    assert not (tmp_path / "out").exists()


# --- items 1, 2 (and issue 39): design --check asks each engine before any work ----------------

def _records_folder(d):
    import math
    (d / "recs").mkdir()
    for k in range(2):
        rows = "".join(f"{i * 0.01:.2f} {math.sin(2 * math.pi * (1 + k) * i / 100) * math.exp(-0.003 * i):.6f}\n"
                       for i in range(300))
        (d / "recs" / f"r{k}.txt").write_text("# units: g\n" + rows)
    return d / "recs"


DESIGN_SMALL = ["design", "--records", "recs", "--pga", "0.5", "--periods", "2", "--damping-ratios", "0.1",
                "--height", "1", "--width", "0.35", "--mass", "100", "--base-mass", "100", "--tail", "1", "--quiet",
                "--out", "out"]


@pytest.mark.parametrize("extra, named", [
    (["--isolator", "ball-in-cone", "--slopes", "0.1", "--rolling-resistances", "0.01", "--check", "mujoco"],
     "ball-in-cone"),
    (["--isolator", "ball-in-cone", "--slopes", "0.1", "--rolling-resistances", "0.01", "--check", "drake"],
     "ball-in-cone"),
    (["--mass", "1e-30", "--base-mass", "1e-30", "--check", "mujoco"], "mass"),
    (["--base-mass", "0.02", "--check", "bullet"], "mass_ratio"),
    (["--periods", "0.001", "--check", "bullet"], "period"),
    (["--check", "mujoco", "--check", "warp"], "warp"),
    (["--check", "mujoco,mujoco"], "once"),
])
def test_a_check_engine_that_cannot_carry_the_design_is_refused_before_any_run(extra, named, tmp_path,
                                                                               monkeypatch, capsys):
    """It was asked after the whole design (30,100 runs, 607 s, then exit 2), or never: a
    1e-30 kg statue's MuJoCo runs failed, and were counted as agreeing."""
    import isorock.validate.cli.design as command
    import isorock.validate.tools.campaign.design as design
    monkeypatch.chdir(tmp_path)
    _records_folder(tmp_path)

    def no_work(*a, **k):
        raise AssertionError("the design ran before its check engine was asked")
    # the command imports run_design by name: imported first, then patched in both, so that the
    # patch is undone in both (imported under the patch, the command kept no_work for the tests after)
    monkeypatch.setattr(design, "run_design", no_work)
    monkeypatch.setattr(command, "run_design", no_work)
    argv = [x for x in DESIGN_SMALL]
    for opt in ("--periods", "--damping-ratios") if "--isolator" in extra else ():
        i = argv.index(opt)
        del argv[i:i + 2]
    if "--base-mass" in extra or "--mass" in extra:
        for opt in ("--mass", "--base-mass"):
            if opt in extra:
                i = argv.index(opt)
                del argv[i:i + 2]
    assert main([*argv, *extra]) == 2
    assert named in _one_line(capsys)
    assert not (tmp_path / "out").exists()


def test_a_failed_contact_run_is_counted_apart_never_as_agreement(monkeypatch):
    """Oracle: every picked run fails (the engine's table says so); agreement is then 0 of 0,
    and the runs are said to have failed."""
    import numpy as np
    import pyarrow as pa

    from isorock.analytic.motion import GroundMotion
    from isorock.validate.tools.campaign import design
    records = {f"r{k}": GroundMotion.from_array(0.5 * np.sin(np.arange(200) * 0.1 * (k + 1)), dt=0.01, units="g",
                                                name=f"r{k}") for k in range(2)}
    d = design.run_design(design.Statue(1.0, 0.35, 100.0, 100.0), design.LinearFamily((2.0,), (0.1,)),
                          design.Hazard(records, (0.5,)), tail=1.0, threads=1)
    picks = design.check_points(d, 0.05, None, 4)

    def all_failed(cases, engines, **k):
        return pa.table({"case": [c.case for c in cases], "overturned": [False] * len(cases),
                         "u_max": [None] * len(cases), "status": ["failed"] * len(cases),
                         "theta_max_over_alpha": [None] * len(cases)})
    monkeypatch.setattr(design, "run_cases", all_failed)  # the executor as design calls it
    c = design.check_with(d, "mujoco", picks)
    assert (c["outcomes_agree"], c["outcomes_differ"], c["failed"], c["n"]) == (0, 0, len(picks), len(picks))
    assert f"{len(picks)} failed" in c["text"] and "in 0 of 0" in c["text"]


def test_several_check_engines_each_check_the_design(tmp_path, monkeypatch, capsys):
    pytest.importorskip("mujoco")
    pytest.importorskip("pybullet")
    import json
    monkeypatch.chdir(tmp_path)
    _records_folder(tmp_path)
    assert main([*DESIGN_SMALL, "--check", "mujoco,bullet", "--check-runs", "1"]) == 0
    doc = json.loads((tmp_path / "out" / "design.json").read_text())
    assert [c["engine"] for c in doc["checks"]] == ["mujoco", "bullet"] and doc["check"] == doc["checks"][0]
    out = capsys.readouterr().out
    assert "mujoco on" in out and "bullet on" in out


# --- item 15: the minor ones ------------------------------------------------------------------

@pytest.mark.parametrize("option", ["--pga", "--pgv"])
def test_an_all_zero_record_scaled_to_a_peak_is_named(option, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "zero.txt").write_text("# units: g\n" + "".join(f"{i * 0.01:.2f} 0\n" for i in range(20)))
    assert main(["run", "--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base",
                 "--motion", "zero.txt", option, "0.5"]) == 2
    err = _one_line(capsys)
    assert "zero.txt" in err and "'none'" not in err


@pytest.mark.parametrize("config, argv, levels", [("pga = 0.7\n", [], [0.7]),
                                                   ("pga = 0.7\n", ["--pga", "0.5"], [0.5]),
                                                   ("[system]\nheight = 1.0\nwidth = 0.35\n", [], None)])
def test_design_config_gives_its_pga_unless_the_option_does(config, argv, levels, tmp_path, monkeypatch):
    import json

    from isorock.validate.cli.design import DEFAULT_PGA, parse_grid
    monkeypatch.chdir(tmp_path)
    _records_folder(tmp_path)
    (tmp_path / "s.toml").write_text(config)
    assert main(["design", "--records", "recs", "--periods", "2", "--damping-ratios", "0.1", "--tail", "1",
                 "--quiet", "--config", "s.toml", "--out", "out", *argv]) == 0
    got = json.loads((tmp_path / "out" / "design.json").read_text())["hazard"]["pga_levels"]
    assert got == (levels or list(parse_grid("pga", DEFAULT_PGA)))


def test_design_config_pgv_is_refused_not_ignored(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    _records_folder(tmp_path)
    (tmp_path / "s.toml").write_text("pgv = 0.3\n")
    assert main(["design", "--records", "recs", "--config", "s.toml", "--out", "out"]) == 2
    assert "pgv" in _one_line(capsys) and not (tmp_path / "out").exists()


# --- items 7 and 8: experiments' data ------------------------------------------------------------

HEAD = ("test,Experimental Results for response-Specimen 1,Experimental Results for response-Specimen 2,"
        "ground_motion,pgv_over_pga_s,scaled_pga_g")


def _test_file(path, n=4000, spike=None, header="Time [s]\tAcceleration [g]"):
    import math
    rows = [f"{i / 800:.6g}\t{(spike if spike is not None and i == n // 2 else 0.2 * math.sin(i / 80)):.7g}"
            for i in range(n)]
    path.write_text(header + "\n" + "\n".join(rows) + "\n")


def _data(tmp_path, results: bytes | None = None, tests=(11, 13, 15)):
    folder = tmp_path / "data"
    (folder / "Shake_Table_Response").mkdir(parents=True)
    body = HEAD + "\n" + "".join(f"{t},{k % 2},0,'RSN{t}_X.xlsx',0.05,0.3\n" for k, t in enumerate(tests))
    (folder / "results.csv").write_bytes(body.encode() if results is None else results)
    for t in tests:
        _test_file(folder / "Shake_Table_Response" / f"Test{t:03d}.txt")
    return folder


def test_results_csv_with_a_byte_order_mark_is_read(tmp_path):
    from isorock.validate.tools.experiments import data
    plain = data.read_results(_data(tmp_path / "a") / "results.csv")
    bom = data.read_results(_data(tmp_path / "b", ("\ufeff" + HEAD + "\n11,0,0,'RSN11_X.xlsx',0.05,0.3\n13,1,0,"
                                                  "'RSN13_X.xlsx',0.05,0.3\n15,0,0,'RSN15_X.xlsx',0.05,0.3\n").encode())
                            / "results.csv")
    assert bom == plain


@pytest.mark.parametrize("raw, named", [(HEAD.encode() + b"\n11,0,0,'RSN\xe9',0.05,0.3\n", "not UTF-8"),
                                        (bytes(range(256)) * 4, "not UTF-8")])
def test_results_csv_that_is_not_text_is_one_line(tmp_path, raw, named):
    from isorock.validate.tools.experiments import data
    folder = _data(tmp_path, raw)
    with pytest.raises(InputError, match=named):
        data.read_results(folder / "results.csv")


def test_data_with_one_common_test_is_refused(tmp_path):
    from isorock.validate.tools.experiments import data
    folder = _data(tmp_path, tests=(11,))
    with pytest.raises(InputError, match="at least 2"):
        data.load(folder)


@pytest.mark.parametrize("n", [3, 15])
def test_a_test_shorter_than_the_filter_pads_is_named(tmp_path, n):
    from isorock.validate.tools.experiments import data, study
    folder = _data(tmp_path)
    _test_file(folder / "Shake_Table_Response" / "Test013.txt", n=n)
    m = data.read_test(folder / "Shake_Table_Response" / "Test013.txt", 13)
    with pytest.raises(InputError, match="Test013"):
        study._motion(m, study.processing.DEFAULT_STEPS, study.processing.LOWPASS_HZ)


def test_the_shortest_test_the_filter_pads_is_processed():
    import numpy as np

    from isorock.validate.tools.experiments import processing
    a = np.sin(np.arange(processing.MIN_SAMPLES) / 3.0)
    assert np.isfinite(processing.process(a, 1 / 800, ("offset", "drift", "lowpass"))).all()


@pytest.mark.parametrize("hz", [1e-6, 0.01, 0.0])
def test_a_lowpass_corner_below_the_shaking_is_refused_up_front(hz, tmp_path, monkeypatch, capsys):
    from isorock.validate.tools.experiments import study

    def no_work(*a, **k):
        raise AssertionError("the study ran")
    monkeypatch.setattr(study, "build", no_work)
    assert main(["experiments", "--data", str(_data(tmp_path)), "--lowpass-hz", str(hz),
                 "--out", str(tmp_path / "out")]) == 2
    assert "lowpass" in _one_line(capsys)


def test_a_test_with_an_acceleration_no_table_makes_is_named(tmp_path):
    from isorock.validate.tools.experiments import data
    folder = _data(tmp_path)
    _test_file(folder / "Shake_Table_Response" / "Test013.txt", spike=1e300)
    with pytest.raises(InputError, match="Test013.*MAX_PGA_G"):
        data.read_test(folder / "Shake_Table_Response" / "Test013.txt", 13)


def test_a_clone_of_the_original_repository_is_refused_saying_why(tmp_path):
    """The original's test files say 'Time [s] - Plot 0 / Amplitude - Plot 0' (no units) and
    its outcomes are spreadsheets: the docs promised it was read (it never was)."""
    from isorock.validate.tools.experiments import data
    folder = tmp_path / "clone" / "data" / "Shake_Table_Response"
    folder.mkdir(parents=True)
    head = "\t".join(f"Time [s] - Plot {k}\tAmplitude - Plot {k}" for k in range(4))
    _test_file(folder / "Test011.txt", header=head)
    (tmp_path / "clone" / "data" / "Results_Granite.xlsx").write_bytes(b"PK")
    with pytest.raises(InputError, match="clone of the original repository") as e:
        data.load(tmp_path / "clone")
    assert "README" in str(e.value)


# --- item 10: worker processes are bounded, in one place ---------------------------------------

@pytest.mark.parametrize("argv", [["sweep", "c.toml", "--out", "out", "--workers", "1000000000"],
                                  ["sweep", "c.toml", "--out", "out", "--workers", "65"],
                                  ["validate", "--quick", "--out", "rep", "--workers", "1000000000"],
                                  ["atlas", "--quick", "--out", "at", "--workers", "1000000000"],
                                  ["calibrate", "--engine", "mujoco", "--workers", "1000000000"],
                                  ["stress", "--quick", "--out", "st", "--workers", "1000000000"]])
def test_a_worker_count_past_the_bound_is_one_line_naming_it(argv, tmp_path, monkeypatch, capsys):
    """sweep --workers 1000000000 started processes until it had taken 2.2 GB in 45 s."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "c.toml").write_text('[systems]\nalpha = 0.25\nsize = 1.0\n\n[motions]\ntype = "pulse"\n'
                                     'pulse = "sine"\nfrequency_ratio = 2.0\namplitude_ratio = 2.0\n\n'
                                     '[[engines]]\nname = "analytic"\n')
    assert main(argv) == 2
    assert "MAX_WORKERS" in _one_line(capsys)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.toml"]


# --- item 14: the notebook API ---------------------------------------------------------------------

@pytest.mark.parametrize("height", ["np.float64(2.0)", "np.float32(2.0)", "np.int64(2)", "Fraction(2)"])
def test_the_api_takes_numbers_of_any_real_type(height):
    """NumPy 2's repr (np.float64(2.0)) reached the parser: 'not a number'."""
    from fractions import Fraction  # noqa: F401 — named by the parameter

    import numpy as np  # noqa: F401 — named by the parameter

    import isorock
    tr = isorock.run(engine="analytic", height=eval(height), width=0.7, mass=3800, base_mass=3800, fixed_base=True,
                     theta0_over_alpha=0.5, duration=1.0)
    assert abs(tr.theta_max_over_alpha - 0.5) < 1e-9  # free rocking from 0.5α peaks at 0.5α


@pytest.mark.parametrize("call", ["sweep(123)", "sweep(None)", "sweep(['c.toml'])", "sweep(b'c.toml')",
                                  "sweep('c.toml', out=123)", "sweep('c.toml', products='yes')",
                                  "sweep('c.toml', scheduler=5)", "sweep('c.toml', workers=10**9)",
                                  "sweep('c.toml', progress=1)", "report(out=123, quick=True)"])
def test_the_api_refuses_a_wrong_type_with_one_line(call, tmp_path, monkeypatch):
    import isorock
    monkeypatch.chdir(tmp_path)
    (tmp_path / "c.toml").write_text("x = 1\n")
    with pytest.raises(InputError) as e:
        eval(f"isorock.{call}")
    assert "\n" not in str(e.value)
    assert list(p.name for p in tmp_path.iterdir()) == ["c.toml"]


# --- item 11, deterministically: the two mechanisms the Dask sweep's noise came through ----------

def test_a_signal_raised_inside_a_finalizer_is_not_printed_and_still_ends_the_command(capsys):
    """Dask's scheduler installs a garbage-collector callback; a signal landing in it raised
    there, where Python prints 'Exception ignored' with a traceback and swallows it."""
    import gc
    import os
    import signal

    from isorock.validate.io.output import Terminated, signal_received, signals_end_cleanly

    class Landing:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGTERM)  # the signal arrives while a finalizer runs

    with pytest.raises(Terminated):
        with signals_end_cleanly():
            Landing()  # collected at once: its finalizer runs, the handler raises inside it
            gc.collect()
            import time
            for _ in range(500):  # the signal sent again ends the command here (a guard, not a measurement;
                time.sleep(0.01)  # short sleeps: a handler pending as one starts runs after it)
            pytest.fail("the signal was swallowed")
    assert signal_received() == signal.SIGTERM
    assert "Exception ignored" not in capsys.readouterr().err


def test_workers_ended_at_once_leave_no_warning_after_the_line(tmp_path):
    """A process that started the resource tracker through quiet_resource_tracker and exits
    at once (os._exit, as a stopped command does) with a semaphore still registered: the
    tracker unlinks it and says nothing (it printed 'There appear to be 1 leaked semaphore
    objects' on the command's stderr)."""
    import subprocess
    import sys
    code = ("import os, sys, multiprocessing as mp\n"
            "from isorock.validate.core.executor import quiet_resource_tracker\n"
            "quiet_resource_tracker()\n"
            "lock = mp.get_context('spawn').Lock()\n"
            "print('the line', file=sys.stderr, flush=True)\n"
            "os._exit(143)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 143 and r.stderr == "the line\n", r.stderr


# --- item 13: the cost is said before minutes of work --------------------------------------------

def test_experiments_with_the_hull_engines_says_its_cost_before_running_them(tmp_path, monkeypatch, capsys):
    from isorock.validate.tools.experiments import study
    models = study.default_data() / "models"
    if not models.is_dir():
        pytest.skip(f"shared shake-table data (its models) not found at {models}")
    folder = _data(tmp_path)
    for t in (11, 13, 15):  # 40 s each, as the real tests last
        _test_file(folder / "Shake_Table_Response" / f"Test{t:03d}.txt", n=32_000)
    (folder / "models").symlink_to(models)

    def stop(*a, **k):
        raise InputError("stopped before the first hull run")
    monkeypatch.setattr(study, "run_body", stop)
    pytest.importorskip("pydrake")  # three short tests are minutes of Drake's hull: said before (bound 2 min)
    assert main(["experiments", "--data", str(folder), "--engines", "analytic,mujoco,bullet,drake",
                 "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith("experiments: ") and "at most" in err[0] and "stopped" in err[1], err


def test_calibrate_says_its_cost_before_running(monkeypatch, capsys):
    from isorock.validate.tools import calibrate as tool

    def stop(*a, **k):
        raise InputError("stopped before the first run")
    monkeypatch.setattr(tool, "calibrate", stop)
    assert main(["calibrate", "--engine", "bullet", "--max-evals", "2000"]) == 2  # a search of hours
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith("calibrate: ") and "at most" in err[0] and "stopped" in err[1], err


# --- issue 39's small items ------------------------------------------------------------------------

def test_bench_prints_its_table_on_standard_output_and_its_progress_on_standard_error(tmp_path, capsys,
                                                                                       monkeypatch):
    from isorock.analytic import paper_system
    from isorock.validate.core.scenarios import Scenario
    from isorock.validate.tools import bench
    sc = Scenario("free-rocking", paper_system(fixed_base=True), "none", 2.0, 0.5)
    monkeypatch.setattr(bench, "bench_scenarios", lambda quick: [sc])
    assert main(["bench", "--quick", "--engines", "analytic", "--out", str(tmp_path / "b")]) == 0
    out, err = capsys.readouterr()
    assert (tmp_path / "b" / "bench.md").read_text().strip() in out  # the tables as written
    assert len([ln for ln in out.splitlines() if ln.startswith("| analytic | rtol=") and "free-rocking" in ln]) == 3
    assert not [ln for ln in err.splitlines() if ln.startswith("| ")]  # stderr: progress only


def test_the_run_plot_names_the_time_it_shows_not_the_record_s_length(tmp_path):
    """A 150 s record run for 40 s: the title said '150 s'."""
    import numpy as np

    from isorock.analytic.motion import GroundMotion
    from isorock.analytic.system import System
    from isorock.validate.core.engines import get_engine
    from isorock.validate.io.run_plot import runs_figure
    record = GroundMotion.from_array(0.05 * np.sin(np.arange(15_001) * 0.01), dt=0.01, units="g", name="long")
    system = System.fixed(height=2, width=0.7, mass=3800)
    tr = get_engine("analytic").simulate(system, record, duration=40.0)
    title = runs_figure({"analytic": tr}, record)._suptitle.get_text()
    assert "150 s" in title and "first 40 s shown" in title


def test_run_defaults_to_the_paper_s_block_as_validate_and_design_do(capsys):
    """It required the block's four options where validate and design take the paper's."""
    import json

    from isorock.analytic.system import PAPER_BLOCK
    assert main(["run", "--fixed-base", "--theta0", "0.5", "--duration", "1", "--json", "-"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["system"]["height"] == PAPER_BLOCK["height"] and got["system"]["width"] == PAPER_BLOCK["width"]
    assert got["system"]["mass"] == PAPER_BLOCK["mass"]


def test_run_without_an_isolator_option_is_still_told_to_choose_one(capsys):
    assert main(["run", "--duration", "1"]) == 2
    assert "--period" in _one_line(capsys)


def test_calibrate_keeping_the_current_settings_is_a_result_not_an_error(monkeypatch, capsys):
    """'keep them' exited 1; its help and docs now say what each exit code means."""
    from isorock.validate.tools import calibrate as tool
    monkeypatch.setattr(tool, "calibrate", lambda *a, **k: {"verdict": "keep"})
    monkeypatch.setattr("isorock.validate.cli.calibrate.preset_worthy", lambda r: False)
    monkeypatch.setattr("isorock.validate.cli.calibrate.report_lines", lambda *a: ["verdict: keep them"])
    assert main(["calibrate", "--engine", "mujoco", "--quiet"]) == 0
    from isorock.validate.cli.main import build_parser
    import argparse
    top = build_parser("calibrate")
    sub = next(x for x in top._actions if isinstance(x, argparse._SubParsersAction)).choices["calibrate"]
    assert "exit" in (sub.epilog or "") and "0" in sub.epilog and "2" in sub.epilog


def test_the_report_cites_the_tolerances_where_they_are():
    from pathlib import Path

    import isorock.validate.core.tolerances as tolerances
    from isorock.validate.tools import report_render
    root = Path(tolerances.__file__).resolve().parents[2]
    cited = Path(report_render.__file__).read_text()
    assert "validate/core/tolerances.py" in cited and "validate/tolerances.py" not in cited
    assert (root / "validate" / "core" / "tolerances.py").is_file()


# --- found by this round's own table ---------------------------------------------------------------

def test_a_range_to_a_huge_value_is_spaced_without_overflow():
    """NumPy's round multiplies by 1e12 first: 0.5:1e300:2 became (0.5, inf), refused as 'inf'
    with a RuntimeWarning above the line."""
    from isorock.validate.cli.design import parse_grid
    assert parse_grid("pga", "0.5:1e300:2") == (0.5, 1e300)


def test_a_family_is_checked_cell_by_cell_when_it_is_made():
    """A friction pendulum of radius 1e308 m (a period of 2e154 s) ran, and its chart's axis
    was a matplotlib traceback; a friction coefficient of 5 is named, not prefixed by a radius."""
    from isorock.validate.tools.campaign.design import FrictionPendulumFamily
    with pytest.raises(InputError, match="radius = 1e\\+308: period"):
        FrictionPendulumFamily((1.0, 1e308), (0.1,))
    with pytest.raises(InputError, match="^friction_coefficient = 5.0"):
        FrictionPendulumFamily((1.0,), (5.0,))
