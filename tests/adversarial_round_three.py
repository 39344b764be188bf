"""Hostile inputs, round three (issue 34): the newest surfaces — `isorock design`, config and
campaign files as a parser sees them (sizes, nesting, key parts, digits), experiments' data,
the notebook API, accelerations and periods at the edge of a float, worker counts, and
output paths. Shared, as rounds one and two, by tests/test_adversarial.py (in-process) and
scripts/adversarial_table.py (as real processes, the closing table of docs/robustness.md).

A case expects exit 2 with one error line, or exit 0 with a result its `check` proves right
against an independent answer (the file as written, the closed form of a normalisation, a
fresh computation). A notebook-API case (`code`) runs Python instead of a command: its
InputError is its "exit 2", its one line the error's text."""
from __future__ import annotations

import gzip
import json
import math
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VSR = ROOT.parent / "shared" / "data" / "vsr"

STATUE = ["--height", "1", "--width", "0.35", "--mass", "100", "--base-mass", "100"]
DESIGN = ["design", "--records", "recs", "--pga", "0.5", "--periods", "2", "--damping-ratios", "0.1", *STATUE,
          "--tail", "1", "--quiet", "--out", "out"]
OUT = ("out/",)
PAPER = ["--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]
RUN = ["run", *PAPER, "--fixed-base", "--duration", "0.5", "--quiet"]


def _record_text(a, dt=0.01, units="g") -> str:
    return (f"# units: {units}\n" if units else "") + "".join(f"{i * dt:.4f} {x:.9g}\n" for i, x in enumerate(a))


def _shaking(k: int, n: int = 300):
    return [math.sin(2 * math.pi * (1 + k) * i / 100) * math.exp(-0.3 * i / 100) for i in range(n)]


def _records(**extra):
    """Setup: recs/ with two short records in g (and `extra` files by name)."""
    def setup(d: Path):
        (d / "recs").mkdir()
        for k in range(2):
            (d / "recs" / f"r{k}.txt").write_text(_record_text(_shaking(k)))
        for name, text in extra.items():
            p = d / name
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(text) if isinstance(text, bytes) else p.write_text(text)
    return setup


def _design_json(key, want):
    def check(d: Path, out: str) -> bool:
        got = json.loads((d / "out" / "design.json").read_text())
        for k in key.split("."):
            got = got[k]
        return got == want
    return check


def _design_weights(want):
    """design.json's level weights are `want` to rounding (the normalisation's closed form)."""
    def check(d: Path, out: str) -> bool:
        got = json.loads((d / "out" / "design.json").read_text())["hazard"]["level_weights"]
        return len(got) == len(want) and all(abs(g - w) <= 1e-12 for g, w in zip(got, want))
    return check


def _file(name: str, text):
    def setup(d: Path):
        p = d / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_bytes(text) if isinstance(text, bytes) else p.write_text(text)
    return setup


def _both(*setups):
    def setup(d: Path):
        for s in setups:
            s(d)
    return setup


# --- hostile TOML, as any of the three readers sees it ------------------------------------------

#: name → the file's text: each too big, too deep or too long for a parser to be handed
HOSTILE_TOML = {
    "a 5,000-digit integer": "[system]\nheight = " + "9" * 5000 + "\n",
    "a 5,000-digit integer in an array": "x = [1, " + "7" * 5000 + "]\n",
    "100,000 nested arrays": "x = " + "[" * 100_000 + "]" * 100_000 + "\n",
    "50,000 nested inline tables": "x = " + "{a = " * 50_000 + "1" + "}" * 50_000 + "\n",
    "a dotted key of 50,000 parts": ".".join(["a"] * 50_000) + " = 1\n",
    "a table header of 50,000 parts": "[" + ".".join(["t"] * 50_000) + "]\nx = 1\n",
    "a quoted dotted key of 20,000 parts": ".".join(['"q"'] * 20_000) + " = 1\n",
    "a 2 MiB file": "# padding\n" * 210_000 + "x = 1\n",
    "2,000 nested arrays": "x = " + "[" * 2000 + "]" * 2000 + "\n",
}


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
SWEEP = ["sweep", "c.toml", "--out", "out", "--workers", "0", "--no-products"]


# --- experiments' data: a small copy of the shared folder's layout -----------------------------

EXP_HEAD = ("test,Experimental Results for response-Specimen 1,Experimental Results for response-Specimen 2,"
            "Specimen 1-Numerical KN=10 KS=1,Specimen 2-Numerical KN=15 KS=1,ground_motion,pgv_over_pga_s,"
            "scaled_pga_g")
EXP_TESTS = (11, 13, 15, 17)


def _test_text(n: int = 4000, amp: float = 0.2, header: str = "Time [s]\tAcceleration [g]", columns: int = 2,
               spike=None) -> str:
    lines = [header]
    for i in range(n):
        a = amp * math.sin(2 * math.pi * 1.5 * i / 800) * min(1.0, i / 800)
        if spike is not None and i == n // 2:
            a = spike
        lines.append(f"{i / 800:.6g}\t{a:.7g}" + "\t0" * (columns - 2))
    return "\n".join(lines) + "\n"


def _exp_rows(tests=EXP_TESTS) -> str:
    out = [EXP_HEAD]
    for k, t in enumerate(tests):
        out.append(f"{t},{k % 2},{(k // 2) % 2},{k % 2},0,'RSN{t}_X.xlsx',0.05,{0.1 + 0.1 * k:.2f}")
    return "\n".join(out) + "\n"


def _experiments_data(results=None, tests=None, models=True, gz=True):
    """Setup: data/ with results.csv, one test file per row (each `tests[t]` text, else a
    4,000-sample shaking in g) and, where the shared folder is here, its `models` linked."""
    def setup(d: Path):
        folder = d / "data" / "Shake_Table_Response"
        folder.mkdir(parents=True)
        text = _exp_rows() if results is None else results
        (d / "data" / "results.csv").write_bytes(text if isinstance(text, bytes) else text.encode())
        for t in EXP_TESTS:
            body = (tests or {}).get(t, _test_text())
            if body is None:
                continue
            raw = body if isinstance(body, bytes) else body.encode()
            if gz:
                (folder / f"Test{t:03d}.txt.gz").write_bytes(gzip.compress(raw))
            else:
                (folder / f"Test{t:03d}.txt").write_bytes(raw)
        if models and (VSR / "models").is_dir():
            (d / "data" / "models").symlink_to(VSR / "models")
    return setup


def _clone_layout(d: Path):
    """A clone of the original repository as it is: data/Shake_Table_Response/TestNNN.txt with
    eight unit-less 'Plot' columns, the outcomes in spreadsheets, no results.csv."""
    folder = d / "clone" / "data" / "Shake_Table_Response"
    folder.mkdir(parents=True)
    head = "\t".join(f"Time [s] - Plot {k}\tAmplitude - Plot {k}" for k in range(4)) + "\t"
    for t in EXP_TESTS:
        (folder / f"Test{t:03d}.txt").write_text(_test_text(header=head, columns=8))
    (d / "clone" / "data" / "Results_Granite.xlsx").write_bytes(b"PK\x03\x04 not read")
    (folder / "Earthquake_Records_Info.xlsx").write_bytes(b"PK\x03\x04 not read")


EXP = ["experiments", "--data", "data", "--out", "exp"]


def _experiments_ran(tests):
    """exit 0 and study.json lists exactly `tests` (the rows as written)."""
    def check(d: Path, out: str) -> bool:
        return json.loads((d / "exp" / "study.json").read_text())["tests"] == list(tests)
    return check


# --- the notebook API ----------------------------------------------------------------------

API_RUN = ("import isorock, numpy as np\n"
           "tr = isorock.run(engine='analytic', height={h}, width=0.7, mass=3800, base_mass=3800, fixed_base=True, "
           "theta0_over_alpha=0.5, duration=1.0)\n"
           "print(tr.theta_max_over_alpha)\n")


def _free_rocking(d: Path, out: str) -> bool:
    """Free rocking from 0.5α on a fixed base peaks at 0.5α (θ̇0 = 0: the first half-cycle's peak)."""
    return abs(float(out.strip()) - 0.5) < 1e-9


def round_three(Case) -> list:
    c = []

    def add(cls, name, argv=(), expect="exit2", **kw):
        c.append(Case(cls, name, list(argv), expect, **kw))

    # --- design: empty values, axes, overflow, weights (items 3, 4, 5, 15) -------------------------
    def design(name, *extra, expect="exit2", setup=None, **kw):
        """DESIGN with `extra`; another isolator family runs on its own axes (given, or its
        defaults), not the linear family's --periods and --damping-ratios."""
        base = list(DESIGN)
        if "--isolator" in extra and extra[extra.index("--isolator") + 1] != "linear":
            for option in ("--periods", "--damping-ratios"):
                i = base.index(option)
                del base[i:i + 2]
        add("design", name, [*base, *extra], expect, setup=setup or _records(), **kw)
    for option in ("--periods", "--damping-ratios", "--pga", "--level-weights", "--config", "--records"):
        design(f"{option} ''", option, "")
    for option, isolator in (("--radii", "friction-pendulum"), ("--friction-coefficients", "friction-pendulum"),
                             ("--slopes", "ball-in-cone"), ("--rolling-resistances", "ball-in-bowl")):
        design(f"{option} '' ({isolator})", "--isolator", isolator, option, "")
    design("--check ''", "--check", "")
    design("--periods '  ' (blank)", "--periods", "  ")
    for option, value in (("--periods", "1:4:inf"), ("--pga", "0.1:1:inf"), ("--damping-ratios", "0.05:0.3:-inf"),
                          ("--periods", "1:4:1e400"), ("--periods", "1:4:nan"), ("--periods", "1:4:0"),
                          ("--periods", "1:4:2.5"), ("--periods", "4:1:3"), ("--periods", "1,1"),
                          ("--periods", "2,1"), ("--periods", "nan"), ("--periods", "-1"), ("--periods", "1:2:3:4"),
                          ("--periods", "a:b:3"), ("--periods", "1:4:201"), ("--periods", "1e-300"),
                          ("--periods", "1e-300:1:3"), ("--periods", "1e308"), ("--periods", "inf"),
                          ("--damping-ratios", "1"), ("--pga", "1e300"), ("--pga", "0.5:1e300:2"),
                          ("--pga", "150"), ("--pga", "0"), ("--level-weights", "1,2,3"),
                          ("--level-weights", "-1"), ("--level-weights", "0"), ("--level-weights", "inf"),
                          ("--level-weights", "nan"), ("--level-weights", "1e400"), ("--level-weights", "a"),
                          ("--target", "1.5"), ("--target", "nan"), ("--max-stroke", "0"), ("--max-stroke", "inf"),
                          ("--check-runs", "0"), ("--check-runs", "201"), ("--tail", "-1"), ("--tail", "nan"),
                          ("--tail", "1e9"), ("--limit", "-1")):
        design(f"{option} {value}", option, value)
    design("--level-weights 1e308,1e308 (overflowed to 0, 0)", "--pga", "0.5,1.5", "--level-weights", "1e308,1e308",
           expect="ok", outputs=OUT, check=_design_weights([0.5, 0.5]))
    design("--level-weights 1e308,1e307,1e306", "--pga", "0.3,0.5,0.7", "--level-weights", "1e308,1e307,1e306",
           expect="ok", outputs=OUT, check=_design_weights([100 / 111, 10 / 111, 1 / 111]))
    design("--level-weights 5e-324,5e-324 (subnormal)", "--pga", "0.5,1.5", "--level-weights", "5e-324,5e-324",
           expect="ok", outputs=OUT, check=_design_weights([0.5, 0.5]))
    for option, value, isolator in (("--radii", "1e-12", "friction-pendulum"), ("--radii", "1e-12", "ball-in-bowl"),
                                    ("--friction-coefficients", "5", "friction-pendulum"),
                                    ("--slopes", "2", "ball-in-cone"), ("--radii", "1e308", "friction-pendulum")):
        design(f"{option} {value} ({isolator})", "--isolator", isolator, option, value)
    design("--radii with the linear family", "--radii", "1")
    add("design", "--height without --width", ["design", "--records", "recs", "--height", "1", "--out", "out"],
        setup=_records())
    add("design", "--width and --slenderness", [*DESIGN, "--slenderness", "2"], setup=_records())
    add("design", "--slenderness 0", ["design", "--records", "recs", "--height", "1", "--slenderness", "0",
                                      "--out", "out"], setup=_records())
    add("design", "--mass-ratio 0", ["design", "--records", "recs", "--height", "1", "--width", "0.35",
                                     "--mass-ratio", "0", "--out", "out"], setup=_records())
    design("--records a file", "--records", "recs/r0.txt")
    design("--records an empty folder", "--records", "empty", setup=_both(_records(), lambda d: (d / "empty").mkdir()))
    design("--records with an all-zero record", setup=_records(**{"recs/z.txt": _record_text([0.0] * 50)}))
    design("--records with a record of random bytes", setup=_records(**{"recs/x.txt": bytes(range(256)) * 4}))
    design("--records with a record without units",
           setup=_records(**{"recs/u.txt": _record_text(_shaking(3), units=None)}))
    design("--records with a 1e300 g sample (scaled to the level)", expect="ok", outputs=OUT,
           setup=_records(**{"recs/h.txt": _record_text([0.0, 1e300, 0.0, 0.0])}),
           check=_design_json("hazard.records", ["h.txt", "r0.txt", "r1.txt"]))
    design("--config no such file", "--config", "nofile.toml")
    design("--config a folder", "--config", "recs")
    design("--config [system] height = true", "--config", "s.toml", setup=_both(_records(), _file(
        "s.toml", "[system]\nheight = true\n")))
    add("design", "--config pga = 0.7 (the file's pga is the level)",
        [x for x in DESIGN if x not in ("--pga", "0.5")] + ["--config", "s.toml"], "ok", outputs=OUT,
        setup=_both(_records(), _file("s.toml", "pga = 0.7\n")), check=_design_json("hazard.pga_levels", [0.7]))
    design("--config pga = 0.7 and --pga 0.5 (the option wins)", "--config", "s.toml", expect="ok", outputs=OUT,
           setup=_both(_records(), _file("s.toml", "pga = 0.7\n")), check=_design_json("hazard.pga_levels", [0.5]))
    design("--config pgv = 0.3 (design scales by PGA)", "--config", "s.toml",
           setup=_both(_records(), _file("s.toml", "pgv = 0.3\n")))
    for label, value in (("'' ", ""), ("a file", "recs/r0.txt"), ("under a file", "recs/r0.txt/x"),
                         ("the working folder", ".")):
        add("design", f"--out {label.strip()}", [*DESIGN[:-2], "--out", value], setup=_records())

    # --- design --check: asked of the engine before any work; more than one engine (items 1, 2) ---
    for label, extra in (
            ("--check analytic", ["--check", "analytic"]), ("--check warp", ["--check", "warp"]),
            ("--check mujoco,mujoco", ["--check", "mujoco,mujoco"]),
            ("--check mujoco --check warp", ["--check", "mujoco", "--check", "warp"]),
            ("--check mujoco, ball-in-cone", ["--isolator", "ball-in-cone", "--check", "mujoco"]),
            ("--check bullet, ball-in-cone", ["--isolator", "ball-in-cone", "--check", "bullet"]),
            ("--check drake, ball-in-cone", ["--isolator", "ball-in-cone", "--check", "drake"]),
            ("--check mujoco, a 1e-30 kg statue", ["--mass", "1e-30", "--base-mass", "1e-30", "--check", "mujoco"]),
            ("--check bullet, mass ratio 5000", ["--base-mass", "0.02", "--check", "bullet"]),
            ("--check bullet, period 0.001 s", ["--periods", "0.001", "--check", "bullet"]),
            ("--check mujoco,bullet, a 1e-30 kg statue", ["--mass", "1e-30", "--base-mass", "1e-30", "--check",
                                                         "mujoco,bullet"])):
        design(label, *extra)

    def checked(engines):
        """design.json: each engine's block in `checks` (the first also as `check`, as before),
        its runs counted once each: agreed, differed or failed."""
        def check(d: Path, out: str) -> bool:
            doc = json.loads((d / "out" / "design.json").read_text())
            checks = doc["checks"]
            return ([x["engine"] for x in checks] == engines and doc["check"] == checks[0]
                    and all(x["n"] == len(x["runs"]) == x["outcomes_agree"] + x["outcomes_differ"] + x["failed"]
                            for x in checks))
        return check
    design("--check mujoco --check bullet --check-runs 2", "--check", "mujoco", "--check", "bullet",
           "--check-runs", "2", expect="ok", outputs=OUT, check=checked(["mujoco", "bullet"]))

    # --- runs at the edge of a float (items 5, 9, 15) ----------------------------------------
    for label, extra in (("--period 1e-300", ["--period", "1e-300", "--damping", "0.1"]),
                         ("--period 1e-12", ["--period", "1e-12", "--damping", "0.1"]),
                         ("--period 1e308", ["--period", "1e308", "--damping", "0.1"])):
        add("float-edges", f"run {label}", ["run", *PAPER, *extra, "--duration", "0.5", "--quiet"])
    add("float-edges", "validate --config period = 1e-300", ["validate", "--config", "v.toml", "--quick", "--quiet",
                                                       "--out", "rep"],
        setup=_file("v.toml", "[system]\nheight = 2.0\nwidth = 0.7\nmass = 3800\nbase_mass = 3800\n"
                              "period = 1e-300\ndamping_ratio = 0.2\n"))
    for label, text in (("one 1e300 g sample", [0.0, 1e300, 0.0, 0.0]), ("one 1e40 g sample", [0.0, 1e40, 0.0, 0.0]),
                        ("one 1e25 g sample", [0.0, 1e25, 0.0, 0.0]), ("one -1e300 g sample", [0.0, -1e300, 0, 0])):
        for base in (["--fixed-base"], ["--period", "1.5", "--damping", "0.2"]):
            add("float-edges", f"run, a record of {label}, {'fixed' if len(base) == 1 else 'isolated'}",
                ["run", *PAPER, *base, "--motion", "huge.txt", "--budget", "20", "--quiet"],
                setup=_file("huge.txt", _record_text(text)), in_process=False)
    add("float-edges", "run --pga 1e300 (a pulse)", [*RUN, "--motion", "sine:amp=0.5,freq=1", "--pga", "1e300"])
    add("float-edges", "run, sine:amp=1e300", [*RUN, "--motion", "sine:amp=1e300,freq=1"])
    add("float-edges", "run --scale 1e300", [*RUN, "--motion", "sine:amp=0.5,freq=1", "--scale", "1e300"])
    add("float-edges", "run --pga 0.5, an all-zero record (named, not 'none')",
        [*RUN, "--motion", "zero.txt", "--pga", "0.5"], setup=_file("zero.txt", _record_text([0.0] * 20)),
        says="zero.txt")
    add("float-edges", "run --pgv 0.5, an all-zero record", [*RUN, "--motion", "zero.txt", "--pgv", "0.5"],
        setup=_file("zero.txt", _record_text([0.0] * 20)), says="zero.txt")
    add("float-edges", "run --motion ''", [*RUN, "--motion", ""])
    add("float-edges", "run --friction-coefficient … --radius 1e-12", ["run", *PAPER, "--isolator", "friction-pendulum",
                                                              "--radius", "1e-12", "--friction-coefficient", "0.1",
                                                              "--duration", "0.5", "--quiet"])
    add("float-edges", "run without the block (the paper's, as validate and design)",
        ["run", "--fixed-base", "--theta0", "0.5", "--duration", "1", "--json", "-"], "ok",
        check=lambda d, out: abs(json.loads(out)["theta_max_over_alpha"] - 0.5) < 1e-9
        and abs(json.loads(out)["slenderness"] - 2.0 / 0.7) < 1e-12)

    # --- hostile TOML through each reader (item 6) ---------------------------------------------
    readers = {"validate --config": (["validate", "--config", "h.toml", "--quick", "--quiet", "--out", "rep"], "h.toml"),
               "design --config": ([*DESIGN, "--config", "h.toml"], "h.toml"),
               "sweep": (["sweep", "h.toml", "--out", "out", "--workers", "0", "--no-products"], "h.toml")}
    for reader, (argv, name) in readers.items():
        for label, text in HOSTILE_TOML.items():
            add("toml", f"{reader}: {label}", argv, setup=_both(_records(), _file(name, text)))
    add("toml", "sweep: a campaign with a NUL byte", SWEEP, setup=_file("c.toml", CAMPAIGN + "\x00\n"))
    add("toml", "sweep: a 5,000-digit hex integer", SWEEP,
        setup=_file("c.toml", CAMPAIGN.replace("analytic_chunk = 4", "analytic_chunk = 0x" + "f" * 5000)))
    add("toml", "sweep: amplitude_ratio = 1e300", SWEEP,
        setup=_file("c.toml", CAMPAIGN.replace("amplitude_ratio = [0.9, 3.0]", "amplitude_ratio = [0.9, 1e300]")))
    add("toml", "sweep: amplitude_ratio = 1e99999 (inf)", SWEEP,
        setup=_file("c.toml", CAMPAIGN.replace("amplitude_ratio = [0.9, 3.0]", "amplitude_ratio = 1e99999")))
    add("toml", "sweep: period = 1e-300", SWEEP, setup=_file("c.toml", CAMPAIGN.replace("period = 1.5",
                                                                                        "period = 1e-300")))
    add("toml", "sweep: records scaled to 1e300 g", SWEEP, setup=_both(_records(), _file(
        "c.toml", "[systems]\nalpha = 0.25\nsize = 1.0\nbase = \"fixed\"\n\n[motions]\ntype = \"records\"\n"
                  "folder = \"recs\"\nscale_by = \"pga\"\nlevels = [0.5, 1e300]\n\n[[engines]]\nname = \"analytic\"\n")))
    add("toml", "sweep: the plain campaign (the loader's bounds pass it)", SWEEP, "ok",
        setup=_file("c.toml", CAMPAIGN), outputs=OUT,
        check=lambda d, out: __import__("pyarrow.parquet").parquet.read_table(d / "out" / "results.parquet").num_rows == 8)
    add("toml", "validate --config: a deep but lawful file (4 levels)", ["validate", "--config", "v.toml", "--quick",
                                                                        "--quiet", "--engines", "analytic", "--out",
                                                                        "rep", "--motion", "sine:amp=0.1,freq=1"],
        "ok", setup=_file("v.toml", "[system]\nheight = 2.0\nwidth = 0.7\nmass = 3800\nfixed_base = true\n"
                                    "[settings.analytic]\nrtol = 1e-10\n"),
        outputs=("rep/",), check=lambda d, out: (d / "rep" / "metrics.json").is_file())

    # --- sweep's options (items 4, 10) ----------------------------------------------------------
    for label, extra in (("--workers 1000000000", ["--workers", "1000000000"]), ("--workers 65", ["--workers", "65"]),
                         ("--out ''", ["--out", ""]), ("--scheduler ''", ["--scheduler", ""])):
        argv = ["sweep", "c.toml", "--no-products", *extra]
        if extra[0] != "--out":
            argv += ["--out", "out"]
        add("workers", f"sweep {label}", argv, setup=_file("c.toml", CAMPAIGN))
    add("workers", "'' as the campaign file", ["sweep", "", "--workers", "0"])
    for command in (["validate", "--quick", "--engines", "analytic", "mujoco", "--out", "rep"],
                    ["calibrate", "--engine", "mujoco", "--quiet"],
                    ["atlas", "--quick", "--engines", "analytic", "--out", "at"]):
        add("workers", f"{command[0]} --workers 1000000000", [*command, "--workers", "1000000000"])

    # --- experiments' data (items 7, 8) ----------------------------------------------------------
    def exp(name, *extra, expect="exit2", setup=None, needs=(), **kw):
        add("experiments-data", name, [*EXP, *extra], expect, setup=setup or _experiments_data(), needs=needs, **kw)
    exp("a test of 15 rows", setup=_experiments_data(tests={13: _test_text(n=15)}))
    exp("a test of 16 rows (the shortest the zero-phase filter pads)", expect="ok", outputs=("exp/",), needs=("vsr",),
        setup=_experiments_data(tests={13: _test_text(n=16)}), check=_experiments_ran(EXP_TESTS))
    exp("--lowpass-hz 1e-6", "--lowpass-hz", "1e-6")
    for value in ("0", "-1", "nan", "inf", "1e9", "0.01"):
        exp(f"--lowpass-hz {value}", "--lowpass-hz", value)
    exp("a stray Latin-1 byte in results.csv", setup=_experiments_data(
        results=_exp_rows().encode().replace(b"RSN11_X", b"RSN11_\xe9X")))
    exp("one common test", setup=_experiments_data(results=_exp_rows(tests=(11,))))
    exp("a UTF-8 byte-order mark on results.csv (read)", expect="ok", outputs=("exp/",), needs=("vsr",),
        setup=_experiments_data(results=b"\xef\xbb\xbf" + _exp_rows().encode()), check=_experiments_ran(EXP_TESTS))
    exp("uncompressed 8-column tests with units (read)", expect="ok", outputs=("exp/",), needs=("vsr",),
        setup=_experiments_data(tests={t: _test_text(columns=8, header="Time [s]\tAcceleration [g]\tA2 [g]\tx\tx\tx\t"
                                                                       "x\tx") for t in EXP_TESTS}, gz=False),
        check=_experiments_ran(EXP_TESTS))
    exp("results.csv empty", setup=_experiments_data(results=""))
    exp("results.csv, the header only", setup=_experiments_data(results=EXP_HEAD + "\n"))
    exp("results.csv without scaled_pga_g", setup=_experiments_data(
        results=_exp_rows().replace(",scaled_pga_g", ",scaled")))
    exp("results.csv, a test number 'x'", setup=_experiments_data(results=_exp_rows().replace("\n13,", "\nx,")))
    exp("results.csv, a test twice", setup=_experiments_data(results=_exp_rows() + _exp_rows().splitlines()[1] + "\n"))
    exp("results.csv, an outcome of 2", setup=_experiments_data(results=_exp_rows().replace("\n13,1,", "\n13,2,")))
    exp("results.csv, pgv_over_pga_s = 0", setup=_experiments_data(results=_exp_rows().replace(",0.05,", ",0,", 1)))
    exp("results.csv, scaled_pga_g = nan", setup=_experiments_data(results=_exp_rows().replace(",0.10\n", ",nan\n")))
    exp("results.csv, a short row", setup=_experiments_data(results=_exp_rows() + "19,1,0\n"))
    exp("results.csv of random bytes", setup=_experiments_data(results=bytes(range(256)) * 8))
    def truncate(d: Path):
        p = d / "data" / "Shake_Table_Response" / "Test013.txt.gz"
        p.write_bytes(p.read_bytes()[:100])
    exp("a test file truncated (gzip)", setup=_both(_experiments_data(), truncate))
    exp("a test file without units", setup=_experiments_data(tests={13: _test_text(header="Time\tAcceleration")}))
    exp("a test file of random bytes", setup=_experiments_data(tests={13: bytes(range(256)) * 16}))
    exp("a test file with a NaN sample", setup=_experiments_data(tests={13: _test_text(spike=float("nan"))}))
    exp("a test file off its time grid", setup=_experiments_data(
        tests={13: _test_text().replace("\n0.0025\t", "\n0.003\t", 1)}))
    exp("a test file with a 1e300 g sample", setup=_experiments_data(tests={13: _test_text(spike=1e300)}))
    exp("a test file with a 1e25 g sample", setup=_experiments_data(tests={13: _test_text(spike=1e25)}))
    add("experiments-data", "--data a clone of the original repository", ["experiments", "--data", "clone",
                                                                           "--out", "exp"], setup=_clone_layout)
    add("experiments-data", "--data ''", ["experiments", "--data", "", "--out", "exp"])
    add("experiments-data", "--data a file", ["experiments", "--data", "f.csv", "--out", "exp"],
        setup=_file("f.csv", "x\n"))
    exp("--steps ''", "--steps", "")
    exp("--tests ''", "--tests", "")
    exp("--tests 11,11", "--tests", "11,11")
    exp("--tests 11,99", "--tests", "11,99")
    exp("--engines ''", "--engines", "")
    exp("--mujoco-friction nan", "--mujoco-friction", "nan")
    exp("--bullet-restitution 2", "--bullet-restitution", "2")
    exp("--out ''", "--out", "")

    # --- devices and output paths of the newest commands --------------------------------------------
    add("out-paths", "validate --config /dev/zero (read no further than the bound)",
        ["validate", "--config", "/dev/zero", "--quick", "--out", "rep"])
    add("out-paths", "design --config /dev/urandom", [*DESIGN, "--config", "/dev/urandom"], setup=_records())
    add("out-paths", "sweep /dev/zero", ["sweep", "/dev/zero", "--workers", "0", "--out", "out"])
    add("out-paths", "design --out a dangling link", [*DESIGN[:-2], "--out", "gone"],
        setup=_both(_records(), lambda d: (d / "gone").symlink_to(d / "missing" / "x")))
    add("out-paths", "design --out a folder of notes", [*DESIGN[:-2], "--out", "notes"],
        setup=_both(_records(), _file("notes/mine.txt", "keep\n")))
    add("out-paths", "design --out an earlier design's folder (replaced whole)", DESIGN, "ok", outputs=OUT,
        setup=_both(_records(), lambda d: __import__("subprocess").run(
            [__import__("sys").executable, "-m", "isorock.validate.cli.main", *DESIGN], cwd=d, check=True,
            capture_output=True, timeout=120)), check=_design_json("hazard.pga_levels", [0.5]), in_process=False)
    for label, value in (("a file", "f.txt"), ("under a file", "f.txt/x"), ("the data folder itself", "data")):
        add("out-paths", f"experiments --out {label}", ["experiments", "--data", "data", "--out", value],
            setup=_both(_experiments_data(), _file("f.txt", "mine\n")))

    # --- the notebook API (item 14) ----------------------------------------------------------------
    def api(name, code, expect="exit2", **kw):
        add("notebook-api", name, (), expect, code=code, **kw)
    for label, value in (("np.float64(2.0)", "np.float64(2.0)"), ("np.float32(2.0)", "np.float32(2.0)"),
                         ("np.int64(2)", "np.int64(2)"), ("a 0-d array", "np.array(2.0)"),
                         ("Fraction(2)", "__import__('fractions').Fraction(2)"),
                         ("Decimal('2.0')", "__import__('decimal').Decimal('2.0')")):
        api(f"run(height={label})", API_RUN.format(h=value), "ok", check=_free_rocking)
    for label, code in (
            ("sweep(123)", "import isorock\nisorock.sweep(123)\n"),
            ("sweep(None)", "import isorock\nisorock.sweep(None)\n"),
            ("sweep(['c.toml'])", "import isorock\nisorock.sweep(['c.toml'])\n"),
            ("sweep(b'c.toml')", "import isorock\nisorock.sweep(b'c.toml')\n"),
            ("sweep('')", "import isorock\nisorock.sweep('')\n"),
            ("sweep(workers=10**9)", "import isorock\nisorock.sweep('c.toml', workers=10**9)\n"),
            ("sweep(workers=True)", "import isorock\nisorock.sweep('c.toml', workers=True)\n"),
            ("sweep(workers=2.0)", "import isorock\nisorock.sweep('c.toml', workers=2.0)\n"),
            ("sweep(out=123)", "import isorock\nisorock.sweep('c.toml', out=123)\n"),
            ("sweep(out='')", "import isorock\nisorock.sweep('c.toml', out='')\n"),
            ("sweep(products='yes')", "import isorock\nisorock.sweep('c.toml', products='yes')\n"),
            ("sweep(scheduler=5)", "import isorock\nisorock.sweep('c.toml', scheduler=5)\n"),
            ("report(out=123)", "import isorock\nisorock.report(out=123, quick=True, engines=['analytic'])\n"),
            ("report(config=5)", "import isorock\nisorock.report(config=5, quick=True)\n"),
            ("run(height=True)", API_RUN.format(h="True")),
            ("run(height='abc')", API_RUN.format(h="'abc'")),
            ("run(height=float('nan'))", API_RUN.format(h="float('nan')")),
            ("run(height=np.nan)", API_RUN.format(h="np.nan")),
            ("run(height=[1, 2])", API_RUN.format(h="[1, 2]")),
            ("run(height=1e-300j)", API_RUN.format(h="1e-300j")),
            ("run(bogus=1)", "import isorock\nisorock.run(bogus=1)\n"),
            ("run(json='x.json')", "import isorock\nisorock.run(json='x.json')\n"),
            ("run(fixed_base='yes')", "import isorock\nisorock.run(fixed_base='yes')\n"),
            ("run(motion='')", "import isorock\nisorock.run(fixed_base=True, motion='')\n"),
            ("run(period=np.float64(1e-300))", "import isorock, numpy as np\nisorock.run(period=np.float64(1e-300), "
                                               "damping_ratio=0.1)\n")):
        api(label, code, setup=_file("c.toml", CAMPAIGN))
    return c
