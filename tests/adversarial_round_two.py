"""Hostile inputs, round two (issue 24): campaign files, campaign faults, validate
--config files, calibration, the kernel cache and leftovers. Run as real processes by
scripts/adversarial_table.py (`in_process=False`: the suite's own tests of these fixes
are tests/test_campaign_schema.py, test_config_file.py, test_campaign_trust.py and
their neighbours; 300 more in-process cases would double the suite's time).

A case expects exit 2 with one error line, or exit 0 with a result its `check` proves
right against an independent computation (a fresh run of the same campaign into an
empty folder, a closed form)."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

CAMPAIGN = """[campaign]
name = "adv"
analytic_chunk = 4

[systems]
alpha = 0.25
size = 1.0
mass = 1000.0
base = ["fixed", "isolated"]
mass_ratio = 1.0
period = 1.5
damping_ratio = 0.2

[motions]
type = "pulse"
pulse = "sine"
frequency_ratio = [2.0, 4.0]
amplitude_ratio = [0.9, 3.0]

[duration]
tail = 1.0

[[engines]]
name = "analytic"
"""
N_CASES = 8  # 2 bases × 2 × 2
SWEEP = ["sweep", "c.toml", "--out", "out", "--workers", "0", "--no-products"]
OUT = ("out/",)

HOSTILE = {"true": "true", "string": '"1.5"', "negative": "-1.5", "zero": "0", "inf": "inf", "nan": "nan",
           "400 digits": "9" * 400, "empty list": "[]", "duplicates": "[1.5, 1.5]", "half range": "{from = 1}",
           "list of booleans": "[true]", "table": "{a = 1}", "negative in list": "[1.5, -1.5]",
           "date": "1979-05-27"}


def _spec(text: str | bytes, name: str = "c.toml"):
    def setup(d: Path):
        p = d / name
        if isinstance(text, bytes):
            p.write_bytes(text)
        else:
            p.write_text(text)
    return setup


def _set(key: str, value: str, section: str) -> str:
    """CAMPAIGN with `key = value` in [section] (replacing the line there, or added)."""
    lines = CAMPAIGN.split("\n")
    start = lines.index(f"[{section}]") if f"[{section}]" in lines else lines.index(f"[[{section}]]")
    for i in range(start + 1, len(lines)):
        if lines[i].startswith("["):
            break
        if lines[i].split(" = ")[0] == key:
            lines[i] = f"{key} = {value}"
            return "\n".join(lines)
    lines.insert(start + 1, f"{key} = {value}")
    return "\n".join(lines)


def _rows(n: int):
    def check(d: Path, out: str) -> bool:
        import pyarrow.parquet as pq
        return pq.read_table(d / "out" / "results.parquet").num_rows == n
    return check


def _same_as_fresh(spec_name: str = "c.toml"):
    """The folder's results.parquet equals a fresh run of the same campaign file into an
    empty folder (every column but the wall time)."""
    def check(d: Path, out: str) -> bool:
        import tempfile

        import pyarrow.parquet as pq

        from isorock.validate.tools.campaign import run_campaign
        from isorock.validate.core.summary import NONDETERMINISTIC_COLUMNS
        got = pq.read_table(d / "out" / "results.parquet").drop_columns(list(NONDETERMINISTIC_COLUMNS))
        with tempfile.TemporaryDirectory() as t:
            fresh = run_campaign(d / spec_name, Path(t) / "fresh", workers=0, progress=False, products=False)
        want = fresh.table.drop_columns(list(NONDETERMINISTIC_COLUMNS))
        return got.num_rows == want.num_rows and all(
            all(x == y or (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
                for x, y in zip(got[c].to_pylist(), want[c].to_pylist())) for c in want.column_names)
    return check


def _sweep_first(spec_text: str, then, files: dict | None = None):
    """Setup: write the campaign (and record files), run it once as a process, then `then(d)`."""
    def setup(d: Path):
        for name, text in (files or {}).items():
            (d / name).parent.mkdir(parents=True, exist_ok=True)
            (d / name).write_text(text)
        (d / "c.toml").write_text(spec_text)
        subprocess.run([sys.executable, "-m", "isorock.validate.cli.main", *SWEEP], cwd=d, check=True,
                       capture_output=True, timeout=120)
        then(d)
    return setup


def _parts(d: Path):
    return sorted((d / "out" / "parts").glob("*.parquet"))


def _record(a, dt=0.01, units="g"):
    return f"# units: {units}\n" + "".join(f"{i * dt:.4f} {x:.9g}\n" for i, x in enumerate(a))


def _pushes():
    n = 300
    return [math.sin(2 * math.pi * i / 50) if i < 50 else 0.05 * math.sin(2 * math.pi * 3 * i / 100)
            for i in range(n)]


RECORDS = """[systems]
alpha = 0.25
size = 1.0
base = "fixed"

[motions]
type = "records"
{motions}

[duration]
tail = 1.0

[[engines]]
name = "analytic"
"""


def round_two(Case) -> list:
    c = []
    add = lambda *a, **k: c.append(Case(*a, in_process=False, **k))  # noqa: E731

    # --- campaign files: every value means what it says, or one line naming its key ---------
    keys = [("alpha", "systems"), ("size", "systems"), ("mass", "systems"), ("mass_ratio", "systems"),
            ("period", "systems"), ("damping_ratio", "systems"), ("frequency_ratio", "motions"),
            ("amplitude_ratio", "motions"), ("cycles", "motions")]
    for key, section in keys:
        for label, value in HOSTILE.items():
            if key == "damping_ratio" and label == "zero":
                add("campaign-files", f"{section}.{key} = 0 (no damping)", SWEEP, "ok",
                    setup=_spec(_set(key, value, section)), outputs=OUT, check=_rows(N_CASES))
                continue
            if key == "cycles" and label in ("duplicates", "negative in list", "empty list", "half range",
                                             "list of booleans"):
                label += " (cycles takes one number)"
            add("campaign-files", f"{section}.{key} = {label}", SWEEP, setup=_spec(_set(key, value, section)))
    for key in ("tail", "end"):
        for label, value in (("true", "true"), ("string", '"1"'), ("negative", "-1"), ("inf", "inf"),
                             ("nan", "nan"), ("1e9", "1e9"), ("400 digits", "9" * 400), ("list", "[1]"),
                             ("an hour", "3600.5")):
            text = _set(key, value, "duration")
            if key == "end":
                text = text.replace("tail = 1.0\n", "")
            add("campaign-files", f"duration.{key} = {label}", SWEEP, setup=_spec(text))
    add("campaign-files", "duration: tail and end", SWEEP, setup=_spec(_set("end", "3", "duration")))
    for key in ("analytic_chunk", "contact_chunk"):
        for label, value in (("0", "0"), ("7.5", "7.5"), ("true", "true"), ("string", '"7"'), ("1e6", "1000000"),
                             ("negative", "-1"), ("400 digits", "9" * 400)):
            add("campaign-files", f"campaign.{key} = {label}", SWEEP, setup=_spec(_set(key, value, "campaign")))
    add("campaign-files", "campaign.name = 5", SWEEP, setup=_spec(_set("name", "5", "campaign")))
    add("campaign-files", "campaign: unknown key", SWEEP, setup=_spec(_set("nmae", '"x"', "campaign")))
    for label, value in (("square", '"square"'), ("twice", '["sine", "sine"]'), ("5", "5"), ("empty list", "[]"),
                         ("true", "true"), ("empty string", '[""]')):
        add("campaign-files", f"motions.pulse = {label}", SWEEP, setup=_spec(_set("pulse", value, "motions")))
    for label, value in (("pulses", '"pulses"'), ("5", "5"), ("list", '["pulse"]'), ("empty", '""')):
        add("campaign-files", f"motions.type = {label}", SWEEP, setup=_spec(_set("type", value, "motions")))
    for label, value in (("floating", '"floating"'), ("twice", '["fixed", "fixed"]'), ("empty list", "[]"),
                         ("5", "5"), ("true", "true")):
        add("campaign-files", f"systems.base = {label}", SWEEP, setup=_spec(_set("base", value, "systems")))
    add("campaign-files", "isolator without a base (ran a fixed base)", SWEEP,
        setup=_spec(CAMPAIGN.replace('base = ["fixed", "isolated"]\n', "")))
    add("campaign-files", "base = fixed alone", SWEEP, "ok", setup=_spec(_set("base", '"fixed"', "systems")),
        outputs=OUT, check=_rows(4))
    add("campaign-files", "UTF-8 byte-order mark", SWEEP, "ok", setup=_spec(b"\xef\xbb\xbf" + CAMPAIGN.encode()),
        outputs=OUT, check=_rows(N_CASES))
    add("campaign-files", "the plain file", SWEEP, "ok", setup=_spec(CAMPAIGN), outputs=OUT, check=_same_as_fresh())
    engines = {
        "name = drake9": 'name = "drake9"', "name = 5": "name = 5", "name = ''": 'name = ""',
        "rtol = '1e-8' (a string)": 'name = "analytic"\nsettings = [{rtol = "1e-8"}]',
        "rtol = true": 'name = "analytic"\nsettings = [{rtol = true}]',
        "rtoll (unknown setting)": 'name = "analytic"\nsettings = [{rtoll = 1e-8}]',
        "settings = 5": 'name = "analytic"\nsettings = 5',
        "settings = []": 'name = "analytic"\nsettings = []',
        "settings = [5]": 'name = "analytic"\nsettings = [5]',
        "max_step = 1e-12 (MAX_STEPS)": 'name = "analytic"\nsettings = [{max_step = 1e-12}]',
        "mujoco timestep = '2e-3'": 'name = "mujoco"\nsettings = [{timestep = "2e-3"}]',
        "mujoco timestep = 1e-12": 'name = "mujoco"\nsettings = [{timestep = 1e-12}]',
        "mujoco timestep = 0": 'name = "mujoco"\nsettings = [{timestep = 0}]',
        "bullet substeps = 1.5": 'name = "bullet"\nsettings = [{substeps = 1.5}]',
        "the same setting twice": 'name = "analytic"\nsettings = [{rtol = 1e-8}, {rtol = 1e-8}]',
        "mujoco solref = 'a'": 'name = "mujoco"\nsettings = [{solref = "a"}]',
    }
    for label, body in engines.items():
        add("campaign-files", f"engines: {label}", SWEEP, setup=_spec(CAMPAIGN.replace('name = "analytic"', body)))
    for label, text in (("spectrum = 'yes'", "[products]\nspectrum = \"yes\"\n"),
                        ("fragility = 5", "[products]\nfragility = 5\n"),
                        ("agreement = 5", "[products]\nagreement = 5\n"),
                        ("agreement.x = bogus", "[products.agreement]\nx = \"bogus\"\n"),
                        ("unknown product", "[products]\nmovie = true\n")):
        add("campaign-files", f"products.{label}", SWEEP, setup=_spec(CAMPAIGN + "\n" + text))
    tops = {
        "unknown table": CAMPAIGN + "\n[extra]\na = 1\n",
        "systems = 5": "systems = 5\n" + CAMPAIGN.replace("[systems]", "[x_systems]"),
        "no [systems]": CAMPAIGN.replace("[systems]", "[x]"),
        "no [motions]": CAMPAIGN.replace("[motions]", "[y]"),
        "no [[engines]]": CAMPAIGN.replace('[[engines]]\nname = "analytic"\n', ""),
        "not TOML": CAMPAIGN + "\ntail = = 1\n",
        "empty file": "",
        "a byte-order mark alone": "\ufeff",
    }
    for label, text in tops.items():
        add("campaign-files", label, SWEEP, setup=_spec(text))
    add("campaign-files", "invalid UTF-8", SWEEP, setup=_spec(CAMPAIGN.encode() + b"# \xff\xfe\n"))
    add("campaign-files", "no such file", ["sweep", "missing.toml", "--out", "out"])
    add("campaign-files", "the file is a folder", ["sweep", "d", "--out", "out"],
        setup=lambda d: (d / "d").mkdir())
    grids = {
        "two 1e6-point ranges": _set("size", "{from = 0.5, to = 2, num = 1000000}", "systems").replace(
            "mass = 1000.0", "mass = {from = 10, to = 2000, num = 1000000}"),
        "three 1000-point ranges": _set("size", "{from = 0.5, to = 2, num = 1000}", "systems").replace(
            "period = 1.5", "period = {from = 1, to = 3, num = 1000}").replace(
            "mass_ratio = 1.0", "mass_ratio = {from = 0.5, to = 3, num = 1000}"),
        "range num = 0": _set("size", "{from = 0.5, to = 2, num = 0}", "systems"),
        "range num = 1.5": _set("size", "{from = 0.5, to = 2, num = 1.5}", "systems"),
        "log range from 0": _set("damping_ratio", "{from = 0, to = 0.5, num = 3, log = true}", "systems"),
        "range to < from": _set("size", "{from = 2, to = 0.5, num = 3}", "systems"),
        "period = 1e-9 (isolator periods)": _set("period", "1e-9", "systems"),
        "mass_ratio = 1e-300": _set("mass_ratio", "1e-300", "systems"),
        "damping_ratio = 1e6": _set("damping_ratio", "1e6", "systems"),
        "alpha = 2 (past π/2)": _set("alpha", "2.0", "systems"),
    }
    for label, text in grids.items():
        add("campaign-files", label, SWEEP, setup=_spec(text))

    # --- campaign faults: records, output folders, schedulers, parts ---------------------------
    loud = _record(_pushes())
    quiet = _record([0.0] * 100)
    rec = {
        "a record of PGA 0": ('folder = "suite"\nlevels = [0.3]', {"suite/q.txt": quiet}),
        "a record of PGV 0, scaled by PGV": ('folder = "suite"\nscale_by = "pgv"\nlevels = [0.3]',
                                             {"suite/q.txt": quiet}),
        "'1_000' in a record": ('folder = "suite"\nlevels = [0.3]',
                                {"suite/a.txt": loud.replace("\n0.0000 0\n", "\n0.0000 1_000\n")}),
        "two contradicting '# units' lines": ('folder = "suite"\nlevels = [0.3]',
                                              {"suite/a.txt": "# units: gal\n" + loud}),
        "units = ['g']": ('folder = "suite"\nunits = ["g"]\nlevels = [0.3]', {"suite/a.txt": loud}),
        "scale_by = ['pga']": ('folder = "suite"\nscale_by = ["pga"]\nlevels = [0.3]', {"suite/a.txt": loud}),
        "folder = ''": ('folder = ""\nlevels = [0.3]', {"suite/a.txt": loud}),
        "folder missing": ('folder = "nowhere"\nlevels = [0.3]', {}),
        "folder is a file": ('folder = "f.txt"\nlevels = [0.3]', {"f.txt": loud}),
        "folder empty": ('folder = "suite"\nlevels = [0.3]', {"suite/.keep": ""}),
        "a record of random bytes": ('folder = "suite"\nlevels = [0.3]', {"suite/r.txt": "\x01\x02garbage\x7f"}),
        "a record without units": ('folder = "suite"\nlevels = [0.3]',
                                   {"suite/a.txt": loud.replace("# units: g\n", "")}),
        "levels = []": ('folder = "suite"\nlevels = []', {"suite/a.txt": loud}),
        "levels twice": ('folder = "suite"\nlevels = [0.3, 0.3]', {"suite/a.txt": loud}),
        "limit = -1": ('folder = "suite"\nlevels = [0.3]\nlimit = -1', {"suite/a.txt": loud}),
        "limit = 1.5": ('folder = "suite"\nlevels = [0.3]\nlimit = 1.5', {"suite/a.txt": loud}),
        "suite = 'nga'": ('suite = "nga"\nlevels = [0.3]', {}),
        "suite and folder": ('suite = "fema-p695"\nfolder = "suite"\nlevels = [0.3]', {"suite/a.txt": loud}),
        "a pulse key in records": ('folder = "suite"\nlevels = [0.3]\nfrequency_ratio = 2', {"suite/a.txt": loud}),
        "scale_by = 'pgd'": ('folder = "suite"\nscale_by = "pgd"\nlevels = [0.3]', {"suite/a.txt": loud}),
    }
    for label, (motions, files) in rec.items():
        def setup(d, motions=motions, files=files):
            for name, text in files.items():
                (d / name).parent.mkdir(parents=True, exist_ok=True)
                (d / name).write_text(text)
            (d / "c.toml").write_text(RECORDS.format(motions=motions))
        add("campaign-faults", label, SWEEP, setup=setup)

    def project(d: Path):
        (d / "c.toml").write_text(CAMPAIGN)
        (d / "mine").mkdir()
        (d / "mine" / "notes.txt").write_text("keep me\n")
        (d / "file.txt").write_text("mine\n")
    outs = {"--out an existing file": ["--out", "file.txt"], "--out a folder of mine": ["--out", "mine"],
            "--out under a file": ["--out", "file.txt/out"], "--workers -1": ["--workers", "-1"],
            "--workers abc": ["--workers", "abc"], "--scheduler 'not a url'": ["--scheduler", "not a url"],
            "--scheduler tcp://": ["--scheduler", "tcp://"],
            "--scheduler a closed port": ["--scheduler", "tcp://127.0.0.1:1"],
            "--scheduler http://[::1": ["--scheduler", "http://[::1"]}
    for label, extra in outs.items():
        argv = ["sweep", "c.toml", "--out", "out", "--no-products", *extra]
        if extra[0] == "--out":
            argv = ["sweep", "c.toml", *extra, "--workers", "0"]
        add("campaign-faults", label, argv, setup=project)

    reversed_record = _record(_pushes()[::-1])
    rec_spec = RECORDS.format(motions='folder = "suite"\nlevels = [0.3, 0.6]')
    add("campaign-faults", "resumed after a record was replaced (same PGA, same length)", SWEEP, "ok",
        setup=_sweep_first(rec_spec, lambda d: (d / "suite" / "a.txt").write_text(reversed_record),
                           {"suite/a.txt": loud}),
        outputs=("out/", "suite/a.txt"), check=_same_as_fresh())

    def damage(how):
        def then(d: Path):
            parts = _parts(d)
            if how == "copied over another":
                (parts[1]).write_bytes(parts[0].read_bytes())
            elif how == "random bytes":
                parts[1].write_bytes(os.urandom(3000))
            elif how == "truncated":
                parts[1].write_bytes(parts[1].read_bytes()[:200])
            elif how == "empty":
                parts[1].write_bytes(b"")
            elif how == "another schema":
                import pyarrow as pa
                import pyarrow.parquet as pq
                pq.write_table(pa.table({"case": [0, 1], "x": [1.0, 2.0]}), parts[1])
            elif how == "a row lost":
                import pyarrow.parquet as pq
                t = pq.read_table(parts[1])
                pq.write_table(t.slice(0, t.num_rows - 1), parts[1])
            elif how == "results.parquet damaged":
                (d / "out" / "results.parquet").write_bytes(b"garbage")
        return then
    for how in ("copied over another", "random bytes", "truncated", "empty", "another schema", "a row lost",
                "results.parquet damaged"):
        add("campaign-faults", f"a part {how}, rerun" if "results" not in how else f"{how}, rerun", SWEEP, "ok",
            setup=_sweep_first(CAMPAIGN, damage(how)), outputs=OUT, check=_same_as_fresh())
    add("campaign-faults", "a finished campaign rerun", SWEEP, "ok", setup=_sweep_first(CAMPAIGN, lambda d: None),
        outputs=OUT, check=_same_as_fresh())

    # --- validate --config files ---------------------------------------------------------------
    VAL = ["validate", "--config", "v.toml", "--quick", "--quiet", "--out", "rep"]
    paper = {"height": "2.0", "width": "0.7", "mass": "3800", "base_mass": "3800", "period": "1.5",
             "damping_ratio": "0.2"}

    def config(system=None, top="", raw=None):
        if raw is not None:
            return _spec(raw, "v.toml")
        body = top + "[system]\n" + "".join(f"{k} = {v}\n" for k, v in (system or paper).items())
        return _spec(body, "v.toml")
    values = {"true": "true", "string": '"1"', "negative": "-1", "zero": "0", "inf": "inf", "400 digits": "9" * 400,
              "list": "[1]", "table": "{a = 1}"}
    for key in ("height", "width", "mass", "base_mass", "period", "damping_ratio", "stiffness", "dashpot"):
        for label, value in values.items():
            if key in ("damping_ratio", "dashpot") and label == "zero":
                continue  # no damping is allowed
            system = dict(paper)
            if key in ("stiffness", "dashpot"):
                system.pop("period")
                system.pop("damping_ratio")
                system.update(stiffness="1e5", dashpot="1e3")
            system[key] = value
            add("config-files", f"system.{key} = {label}", VAL, setup=config(system))
    add("config-files", "system.damping_ratio = 1e6 (hung)", VAL, setup=config({**paper, "damping_ratio": "1e6"}))
    add("config-files", "system.damping_ratio = 1", VAL, setup=config({**paper, "damping_ratio": "1"}))
    for label, value in (('"no"', '"no"'), ("1", "1"), ('"true"', '"true"'), ("[]", "[]")):
        add("config-files", f"system.fixed_base = {label}", VAL,
            setup=config({"height": "2.0", "width": "0.7", "mass": "3800", "fixed_base": value}))
    add("config-files", "system: unknown key", VAL, setup=config({**paper, "widht": "0.3"}))
    tops = {
        'engines = "analytic"': 'engines = "analytic"\n', "engines = []": "engines = []\n",
        "engines = [5]": "engines = [5]\n", 'engines = [""]': 'engines = [""]\n', "engines = 5": "engines = 5\n",
        'engines = ["warp"]': 'engines = ["warp"]\n', 'engines = ["mujoco"] (no analytic)': 'engines = ["mujoco"]\n',
        'engines = ["mujoco:finest"]': 'engines = ["analytic", "mujoco:finest"]\n',
        'motions = "sine:amp=0.5,freq=1"': 'motions = "sine:amp=0.5,freq=1"\n', "motions = []": "motions = []\n",
        "motions = [5]": "motions = [5]\n", "motions = 5": "motions = 5\n",
        'motions = ["nofile.AT2"]': 'motions = ["nofile.AT2"]\n',
        'motions = ["sine:amp=0.5"]': 'motions = ["sine:amp=0.5"]\n',
        'quick = "no"': 'quick = "no"\n', "quick = 1": "quick = 1\n", 'quick = "true"': 'quick = "true"\n',
        'duration = "10"': 'duration = "10"\n', "duration = true": "duration = true\n",
        "duration = -1": "duration = -1\n", "duration = 0": "duration = 0\n", "duration = inf": "duration = inf\n",
        "duration = 1e9": "duration = 1e9\n", "duration = 400 digits": "duration = " + "9" * 400 + "\n",
        'units = "furlongs"': 'units = "furlongs"\n', 'units = ["g"]': 'units = ["g"]\n',
        'format = "xls"': 'format = "xls"\n', "unknown key": "colour = 1\n",
        "settings = 5": "settings = 5\n",
    }
    for label, top in tops.items():
        add("config-files", label, VAL, setup=config(top=top))
    tables = {
        "[settings] analytic = 5": "[settings]\nanalytic = 5\n",
        "[settings.warp]": "[settings.warp]\ntimestep = 1e-3\n",
        "[settings.analytic] rtoll": "[settings.analytic]\nrtoll = 1e-8\n",
        "[settings.analytic] rtol = true": "[settings.analytic]\nrtol = true\n",
        "[settings.analytic] rtol = 0": "[settings.analytic]\nrtol = 0\n",
        "[settings.mujoco] timestep = -1": "[settings.mujoco]\ntimestep = -1\n",
        "[settings.mujoco] timestep = 1e-9": "[settings.mujoco]\ntimestep = 1e-9\n",
        "[settings.bullet] substeps = 0": "[settings.bullet]\nsubsteps = 0\n",
        "[settings.mujoco:finest]": "[settings.\"mujoco:finest\"]\ntimestep = 1e-3\n",
        "[settings.\"*\"] bogus": "[settings.\"*\"]\nbogus = 1\n",
    }
    for label, text in tables.items():
        body = "[system]\n" + "".join(f"{k} = {v}\n" for k, v in paper.items()) + text
        add("config-files", label, VAL, setup=config(raw=body))
    add("config-files", "system = 5", VAL, setup=config(raw="system = 5\n"))
    add("config-files", "invalid UTF-8", VAL, setup=config(raw=b"[system]\nheight = 2.0 # \xff\xfe\n"))
    add("config-files", "not TOML", VAL, setup=config(raw="[system\n"))
    add("config-files", "no such file", ["validate", "--config", "none.toml", "--out", "rep"])
    add("config-files", "the config is a folder", ["validate", "--config", "d", "--out", "rep"],
        setup=lambda d: (d / "d").mkdir())
    add("config-files", "height without width or mass", VAL, setup=config({"height": "2.0"}))

    # --- calibration ----------------------------------------------------------------------------
    CAL = ["calibrate", "--engine", "mujoco", "--quiet"]

    def mine(d: Path):
        (d / "mine.toml").write_text("my preset\n")
        (d / "src").mkdir()
    cal = {
        "--out an existing file": ["--out", "mine.toml"], "--out a folder": ["--out", "src"],
        "--out ''": ["--out", ""], "--out newdir/": ["--out", "newdir/"], "--out under a file": ["--out", "mine.toml/x"],
        "--json a folder": ["--json", "src"], "--json and --out the same": ["--out", "p.toml", "--json", "p.toml"],
        "--max-evals 3": ["--max-evals", "3"], "--max-evals 1e9": ["--max-evals", "1000000000"],
        "--max-evals abc": ["--max-evals", "abc"], "--tilts 1": ["--tilts", "1"], "--tilts 102": ["--tilts", "102"],
        "--workers 0": ["--workers", "0"], "--timestep -1": ["--timestep", "-1"], "--solref 1": ["--solref", "1"],
        "--timestep nan": ["--timestep", "nan"], "--friction -1": ["--friction", "-1"],
        "--height -2": ["--height", "-2", "--width", "0.7", "--mass", "1", "--fixed-base"],
    }
    for label, extra in cal.items():
        add("calibration", label, [*CAL, *extra], setup=mine)
    for label, engine in (("--engine analytic (nothing to calibrate)", "analytic"), ("--engine warp", "warp"),
                          ("--engine ''", "")):
        add("calibration", label, ["calibrate", "--engine", engine, "--quiet"])

    # --- the kernel cache and leftovers ----------------------------------------------------------
    FREE = ["run", "--engine", "analytic", "--height", "2.0", "--width", "0.7", "--mass", "3800", "--base-mass",
            "3800", "--fixed-base", "--theta0", "0.5", "--duration", "1", "--json", "-"]

    def free_rocks(d: Path, out: str) -> bool:
        return abs(json.loads(out)["theta_max_over_alpha"] - 0.5) < 1e-9

    def afile(d: Path):
        (d / "afile").write_text("not a folder\n")
    for label, env in (("XDG_CACHE_HOME is a file", {"XDG_CACHE_HOME": "afile"}),
                       ("ISOROCK_CACHE_DIR is a file", {"ISOROCK_CACHE_DIR": "afile"}),
                       ("ISOROCK_CACHE_DIR under a file", {"ISOROCK_CACHE_DIR": "afile/sub"}),
                       ("ISOROCK_CACHE_DIR empty", {"ISOROCK_CACHE_DIR": ""}),
                       ("HOME is a file", {"HOME": "afile", "XDG_CACHE_HOME": ""}),
                       ("ISOROCK_KERNEL=bogus", {"ISOROCK_KERNEL": "bogus"})):
        add("cache", label, FREE, "ok", setup=afile, env=env, check=free_rocks)
    add("cache", "scene --out newdir/", ["scene", "--engine", "mujoco", "--out", "newdir/"])
    add("cache", "view --speed 1e-6", ["view", "--height", "2", "--width", "0.7", "--mass", "3800",
                                       "--base-mass", "3800", "--fixed-base", "--motion", "sine:amp=0.2,freq=1",
                                       "--out", "v.gif", "--speed", "1e-6"])
    add("cache", "view --fps 1e6", ["view", "--height", "2", "--width", "0.7", "--mass", "3800",
                                    "--base-mass", "3800", "--fixed-base", "--out", "v.gif", "--fps", "1e6"])
    add("cache", "stress writes only its --out", ["stress", "--quick", "--drawn", "2", "--engines", "analytic",
                                                  "--out", "st"], "ok", outputs=("st/",))
    add("cache", "bullet on a base 1e6 times lighter", ["run", "--engine", "bullet", "--height", "2", "--width",
                                                        "0.7", "--mass", "3800", "--base-mass", "3.8e-3",
                                                        "--period", "2", "--damping-ratio", "0.1",
                                                        "--motion", "sine:amp=0.5,freq=1,cycles=1"])
    return c
