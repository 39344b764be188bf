"""Hostile inputs, round four (issue 34's goal: 300 new cases of our own on the newest
surfaces, round three's 238 and these): the typed Python API (`isorock.simulate`,
`isorock.design`), the first run on the SciPy reference while a kernel is not built, `isorock
atlas --frictions`, the engine entry-point registry (docs/plugins.md), the sliding statue and
vertical shaking through `isorock run`, and design's statue and decision options. Shared, as
rounds one to three, by tests/test_adversarial.py (in-process) and
scripts/adversarial_table.py (as real processes, the closing table of docs/robustness.md).

A case expects exit 2 with one error line naming what it says, or exit 0 with a result its
`check` proves right against an independent answer: a closed form (free rocking's first
peak, the impact law's β), the other integrator of the same model (the compiled kernel
against the SciPy reference), a run that must not differ (a zero vertical record, the same
record in other units), the file as written. A code case runs Python instead of a command:
its InputError is its "exit 2"; one that drives the command line sets EXIT to main's code.
Code that monkeypatches a module (the kernel's readiness, the plugin registry) puts it back
in a `finally`, so an in-process case leaves nothing behind."""
from __future__ import annotations

import json
import math
from pathlib import Path

PAPER = ["--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800"]
STATUE = ["--height", "1", "--width", "0.35", "--mass", "100", "--base-mass", "100"]
FIXED = ["run", *PAPER, "--fixed-base", "--quiet"]
SINE = ["--motion", "sine:amp=0.6,freq=1.3,cycles=1", "--duration", "3"]
SLIDE = [*FIXED, *SINE, "--statue-friction", "0.3"]
DESIGN = ["design", "--records", "recs", "--pga", "0.5", "--periods", "2", "--damping-ratios", "0.1", *STATUE,
          "--tail", "1", "--quiet", "--out", "out"]
OUT = ("out/",)
ALPHA_PAPER = math.atan(0.7 / 2.0)


def _record_text(a, dt=0.01, units="g") -> str:
    return (f"# units: {units}\n" if units else "") + "".join(f"{i * dt:.4f} {x:.12g}\n" for i, x in enumerate(a))


def _shaking(k: int, n: int = 300, amp: float = 1.0):
    return [amp * math.sin(2 * math.pi * (1 + k) * i / 100) * math.exp(-0.3 * i / 100) for i in range(n)]


def _files(**named):
    """Setup: each name (with '__' for '.', '_S_' for '/') written with its text or bytes."""
    def setup(d: Path):
        for name, text in named.items():
            p = d / name.replace("_S_", "/").replace("__", ".")
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(text) if isinstance(text, bytes) else p.write_text(text)
    return setup


def _records(d: Path):
    (d / "recs").mkdir()
    for k in range(2):
        (d / "recs" / f"r{k}.txt").write_text(_record_text(_shaking(k)))


#: `capture(argv)`: (main's exit code, what it printed on stdout) — a byte stream under the
#: text, as a real stdout has (`--json -` writes through sys.stdout.buffer)
CAPTURE = """import io, contextlib
def capture(argv):
    from isorock.validate.cli.main import main
    raw = io.BytesIO()
    text = io.TextIOWrapper(raw, encoding='utf-8', write_through=True)
    with contextlib.redirect_stdout(text):
        code = main(argv)
    text.flush()
    return code, raw.getvalue().decode('utf-8')
"""
def _capture_in(d: Path, argv) -> tuple[int, str]:
    """`isorock ARGV` run in folder d as a process of its own, its stderr dropped (a check's own
    reference run: a process, since the table runs checks in threads, and a working folder and
    sys.stdout are the whole process's)."""
    import subprocess
    import sys
    p = subprocess.run([sys.executable, "-m", "isorock.validate.cli.main", *argv], cwd=d, capture_output=True,
                       text=True, timeout=120)
    return p.returncode, p.stdout


# --- the typed API: isorock.simulate, isorock.design -----------------------------------------

SIM = ("import isorock, numpy as np, math\n"
       "S = isorock.System.fixed(height=2, width=0.7, mass=3800)\n"
       "M = isorock.load_motion('sine:amp=0.5,freq=1,cycles=1')\n")
#: free rocking from 0.5α for 1 s on the paper's fixed block: the first half-cycle's peak is 0.5α
FREE = SIM + "tr = isorock.simulate(S, None, theta0=0.5 * S.alpha, duration=1.0{extra})\nprint(tr.theta_max_over_alpha)\n"


def _half_alpha(d: Path, out: str) -> bool:
    return abs(float(out.strip().splitlines()[-1]) - 0.5) < 1e-9


DESIGN_API = ("import isorock, math\n"
              "from isorock.analytic.motion import GroundMotion\n"
              "rec = {f'r{k}': GroundMotion.from_array([math.sin(2 * math.pi * (1 + k) * i / 100) * "
              "math.exp(-0.3 * i / 100) for i in range(300)], dt=0.01, units='g', name=f'r{k}') for k in range(2)}\n"
              "K = dict(height=1, width=0.35, mass=100, base_mass=100, x=[2.0], y=[0.1], records=rec, pga=[0.5], "
              "tail=1)\n")


def _design_api(**kw) -> str:
    args = ", ".join(f"{k}={v}" for k, v in kw.items())
    return DESIGN_API + f"a = isorock.design(**{{**K, **dict({args})}})\nprint(a.target, a.max_stroke)\n"


def _printed(*want):
    """The last line printed is `want` (the values design kept, as floats)."""
    def check(d: Path, out: str) -> bool:
        got = out.strip().splitlines()[-1].split()
        return [None if g == "None" else float(g) for g in got] == list(want)
    return check


# --- the first run: the reference while the kernel is not built ------------------------------

#: code driving `isorock run` with every kernel reported not built (a new install), then with
#: ISOROCK_FIRST_RUN=kernel: prints {"first": run's JSON, "kernel": the kernel's JSON}
FIRST = CAPTURE + """import json, os
from isorock.analytic import kernel_cache
argv = {argv!r}
def one(kernel_mode):
    code, out = capture([*argv, '--json', '-'])
    return code, (json.loads(out) if code == 0 else None)
ready, mode = kernel_cache.is_ready, os.environ.get('ISOROCK_FIRST_RUN')
try:
    kernel_cache.is_ready = lambda dispatcher: False
    {env}
    EXIT, first = one(False)
finally:
    kernel_cache.is_ready = ready
    if mode is None:
        os.environ.pop('ISOROCK_FIRST_RUN', None)
    else:
        os.environ['ISOROCK_FIRST_RUN'] = mode
if EXIT == 0:
    os.environ['ISOROCK_FIRST_RUN'] = 'kernel'
    try:
        EXIT, kernel = one(True)
    finally:
        if mode is None:
            os.environ.pop('ISOROCK_FIRST_RUN', None)
        else:
            os.environ['ISOROCK_FIRST_RUN'] = mode
    print(json.dumps({{'first': first, 'kernel': kernel}}))
"""


def _first(argv, env_value=None) -> str:
    # None: unset, as in a new install (the test suite itself asks for the kernel)
    env = ("os.environ.pop('ISOROCK_FIRST_RUN', None)" if env_value is None
           else f"os.environ['ISOROCK_FIRST_RUN'] = {env_value!r}")
    return FIRST.format(argv=list(argv), env=env)


def _first_agrees(engine="analytic-reference", rel=1e-6, kernel="analytic"):
    """The first run took `engine` and agrees with the run with the kernel built (`kernel`:
    the compiled engine, unless another was asked for): the same status and impacts, θmax/α
    and the stroke to `rel` (two integrators of one model)."""
    def check(d: Path, out: str) -> bool:
        doc = json.loads(out.strip().splitlines()[-1])
        f, k = doc["first"], doc["kernel"]
        close = all(abs(f[key] - k[key]) <= rel * max(1.0, abs(k[key])) for key in ("theta_max_over_alpha", "u_max")
                    if f.get(key) is not None and k.get(key) is not None)
        return (f["engine"] == engine and k["engine"] == kernel and f["status"] == k["status"]
                and f["impacts"] == k["impacts"] and close)
    return check


# --- plugins: the registry's loader monkeypatched ---------------------------------------------

#: a plugin module `fakeplug` in sys.modules holding SPEC (whatever the case builds), registered
#: as `name` in the registry the way its module-level loader registers an entry point
PLUGIN = """import sys, types, json, io, contextlib, dataclasses
import numpy as np
from isorock.analytic.engine_protocol import EngineSpec, Capabilities
from isorock.analytic.trajectory import RawHistory
from isorock.validate.core import engines
from isorock.validate.cli.main import main

@dataclasses.dataclass(frozen=True)
class Settings:
    step: float = 1e-3

def history(system, n=50, **arrays):
    t = np.linspace(0.0, 1.0, n)
    base = dict(t=t, u=np.zeros(n), u_dot=np.zeros(n), theta=np.zeros(n), theta_dot=np.zeros(n))
    base.update(arrays)
    return RawHistory('fake', system, **base)

def spec(simulate, name='fake', **kw):
    return EngineSpec(name=name, label='fake (plugin)', settings_type=Settings, simulate=simulate, **kw)

def registered(name, obj, run):
    module = types.ModuleType('fakeplug')
    module.SPEC = obj
    saved = dict(engines.ENGINE_MODULES), dict(engines.PLUGINS)
    sys.modules['fakeplug'] = module
    engines.ENGINE_MODULES[name] = engines.PLUGINS[name] = 'fakeplug:SPEC'
    try:
        return run()
    finally:
        engines.ENGINE_MODULES.clear(); engines.ENGINE_MODULES.update(saved[0])
        engines.PLUGINS.clear(); engines.PLUGINS.update(saved[1])
        sys.modules.pop('fakeplug', None)

RUN = ['run', '--height', '2', '--width', '0.7', '--mass', '3800', '--fixed-base', '--motion',
       'sine:amp=0.5,freq=1,cycles=1', '--duration', '1', '--quiet']
"""

#: the loader itself fed entry points (importlib.metadata.entry_points monkeypatched), its result
#: applied as the module applies it at import, then `isorock run --engine ASKED`
LOADER = CAPTURE + """import importlib.metadata as md, json
from isorock.validate.core import engines
eps = [md.EntryPoint(n, v, engines.PLUGIN_GROUP) for n, v in {eps!r}]
real = md.entry_points
saved = dict(engines.ENGINE_MODULES), dict(engines.PLUGINS), dict(engines.PLUGINS_REFUSED)
md.entry_points = lambda group=None, **kw: [e for e in eps if group in (None, e.group)]
try:
    found, refused = engines._plugins()
    engines.PLUGINS.update(found); engines.PLUGINS_REFUSED.update(refused); engines.ENGINE_MODULES.update(found)
    EXIT, out = capture(['run', '--engine', {asked!r}, '--height', '2', '--width', '0.7', '--mass', '3800',
                         '--fixed-base', '--theta0-over-alpha', '0.5', '--duration', '1', '--quiet', '--json', '-'])
    print(json.dumps({{'found': sorted(found), 'refused': sorted(refused),
                      'run': json.loads(out) if EXIT == 0 else None}}))
finally:
    md.entry_points = real
    for target, old in zip((engines.ENGINE_MODULES, engines.PLUGINS, engines.PLUGINS_REFUSED), saved):
        target.clear(); target.update(old)
"""


def _loader(eps, asked) -> str:
    return LOADER.format(eps=list(eps), asked=asked)


def _plugin_run(body: str, simulate: str = "", *, settings: str = "", argv: str = "RUN") -> str:
    """PLUGIN, the simulate function `simulate` (Python source of `def sim(...)`), `body`
    building `obj` (the module's SPEC), then `isorock run --engine fake`."""
    return (PLUGIN + simulate + "\n" + body + "\n"
            + f"EXIT = registered('fake', obj, lambda: main([*{argv}, '--engine', 'fake'{settings}]))\n")


def round_four(Case) -> list:
    c = []

    def add(cls, name, argv=(), expect="exit2", **kw):
        c.append(Case(cls, name, list(argv), expect, **kw))

    # --- api: isorock.simulate -------------------------------------------------------------------
    def api(name, code, expect="exit2", **kw):
        add("api", name, (), expect, code=code, **kw)
    for label, extra in (("settings={1: 2} (a key not a name)", "settings={1: 2}"),
                         ("settings={None: 1}", "settings={None: 1}"),
                         ("settings={'rtol': 'abc'}", "settings={'rtol': 'abc'}"),
                         ("settings={'rtol': nan}", "settings={'rtol': float('nan')}"),
                         ("settings={'rtol': True}", "settings={'rtol': True}"),
                         ("settings={'bogus': 1}", "settings={'bogus': 1}"),
                         ("settings=[('rtol', 1e-8)]", "settings=[('rtol', 1e-8)]"),
                         ("theta0='x'", "theta0='x'"), ("theta0=None", "theta0=None"),
                         ("theta0=[0.1]", "theta0=[0.1]"), ("theta0=True", "theta0=True"),
                         ("duration=True", "duration=True"), ("duration='abc'", "duration='abc'"),
                         ("duration=-1", "duration=-1"), ("duration=1e300", "duration=1e300"),
                         ("budget_s=-1", "budget_s=-1"), ("budget_s=nan", "budget_s=float('nan')"),
                         ("budget_s='x'", "budget_s='x'"), ("budget_s=0", "budget_s=0"),
                         ("budget_s=True", "budget_s=True"),
                         ("overturn_rule='bogus'", "overturn_rule='bogus'"),
                         ("engine='warp'", "engine='warp'"), ("engine=''", "engine=''"),
                         ("engine=None", "engine=None"), ("engine=b'analytic'", "engine=b'analytic'"),
                         ("engine='analytic:nope'", "engine='analytic:nope'"),
                         ("engine='analytic,mujoco'", "engine='analytic,mujoco'"),
                         ("engine='analytic:nope' with a Settings", "engine='analytic:nope', "
                          "settings=__import__('isorock.analytic.settings', fromlist=['x']).AnalyticSettings()"),
                         ("engine='analytic:conservative' with a Settings (which one?)",
                          "engine='analytic:conservative', "
                          "settings=__import__('isorock.analytic.settings', fromlist=['x']).AnalyticSettings()"),
                         ("engine='mujoco', settings={'timestep': True}", "engine='mujoco', settings={'timestep': True}"),
                         ("engine='mujoco', settings={'timestep': 0}", "engine='mujoco', settings={'timestep': 0}"),
                         ("engine='bullet', settings={'substeps': 2.5}", "engine='bullet', settings={'substeps': 2.5}")):
        args = extra if "duration=" in extra else extra + ", duration=1.0"
        api(f"simulate({label})", SIM + f"isorock.simulate(S, M, {args})\n")
    api("simulate('paper', M)", SIM + "isorock.simulate('paper', M)\n")
    api("simulate(S, np.zeros(10))", SIM + "isorock.simulate(S, np.zeros(10))\n")
    for label, extra in (("", ""), ("duration=np.float32(1)", ", engine='analytic'"),
                         ("engine=np.str_('analytic')", ", engine=np.str_('analytic')"),
                         ("engine='analytic-fast'", ", engine='analytic-fast'"),
                         ("engine='analytic:conservative'", ", engine='analytic:conservative'"),
                         ("settings={'rtol': np.float64(1e-11)}", ", settings={'rtol': np.float64(1e-11)}"),
                         ("settings={'rtol': None} (the default)", ", settings={'rtol': None}"),
                         ("theta0=np.float64", "")):
        code = FREE.format(extra=extra)
        if label == "duration=np.float32(1)":
            code = code.replace("duration=1.0", "duration=np.float32(1.0)")
        if label == "theta0=np.float64":
            code = code.replace("theta0=0.5 * S.alpha", "theta0=np.float64(0.5 * S.alpha)")
        api(f"simulate, free rocking from 0.5α{', ' + label if label else ''}", code, "ok", check=_half_alpha)

    # --- api: isorock.design ----------------------------------------------------------------------
    for label, kw in (("height='abc'", dict(height="'abc'")), ("height=[1, 2]", dict(height="[1, 2]")),
                      ("height=True", dict(height="True")), ("friction=True", dict(friction="True")),
                      ("plinth_margin='x'", dict(friction="0.5", plinth_margin="'x'")),
                      ("isolator=['linear']", dict(isolator="['linear']")), ("x=[True]", dict(x="[True]")),
                      ("x='2'", dict(x="'2'")), ("level_weights='ab'", dict(level_weights="'ab'")),
                      ("level_weights=5 for two levels", dict(level_weights="5", pga="[0.3, 0.5]")), ("level_weights=[None]", dict(level_weights="[None]")),
                      ("target=True", dict(target="True")), ("max_stroke=True", dict(max_stroke="True")),
                      ("check_runs=True", dict(check_runs="True")), ("tail=True", dict(tail="True")),
                      ("check=5", dict(check="5")), ("threads=10**9", dict(threads="10**9")),
                      ("threads=True", dict(threads="True")), ("records={1: a record}", dict(records="{1: rec['r0']}")),
                      ("records={'p': a pulse}", dict(records="{'p': isorock.load_motion('sine:amp=0.3,freq=2')}")),
                      ("out=123", dict(out="123")), ("out=b'x'", dict(out="b'x'"))):
        api(f"design({label})", _design_api(**kw), says="records" if "records" in kw else "")
    for label, kw, want in (("target=np.float32(0.25)", dict(target="__import__('numpy').float32(0.25)"), (0.25, None)),
                            ("max_stroke=np.float32(0.5)", dict(max_stroke="__import__('numpy').float32(0.5)"),
                             (0.05, 0.5)),
                            ("check_runs=np.int64(3), tail=np.float32(1)",
                             dict(check_runs="__import__('numpy').int64(3)", tail="__import__('numpy').float32(1)"),
                             (0.05, None)),
                            ("target=Fraction(1, 4)", dict(target="__import__('fractions').Fraction(1, 4)"), (0.25, None))):
        api(f"design({label})", _design_api(**kw), "ok", check=_printed(*want))

    # --- first-run: the reference while the kernel is not built ------------------------------------
    def first(name, argv, expect="ok", env_value=None, **kw):
        add("first-run", name, (), expect, code=_first(argv, env_value), **kw)
    free = ["run", *PAPER, "--fixed-base", "--theta0-over-alpha", "0.5", "--duration", "2", "--quiet"]
    first("run, free rocking on a fixed base (the reference, as the kernel)", free, check=_first_agrees())
    for value in ("Kernel", "", "yes", "kernel ", "reference"):
        first(f"ISOROCK_FIRST_RUN={value!r} (not 'kernel': the reference)", free, env_value=value,
              check=_first_agrees())
    iso = ["run", *STATUE, "--motion", "ricker:amp=0.5,freq=2.0", "--duration", "3", "--quiet"]
    for kind, extra in (("linear", ["--period", "1.5", "--damping", "0.2"]),
                        ("bilinear", ["--isolator", "bilinear", "--period", "1.5", "--damping", "0.05",
                                      "--post-yield-ratio", "0.1", "--yield-displacement", "0.01"]),
                        ("friction-pendulum", ["--isolator", "friction-pendulum", "--radius", "1.0",
                                               "--friction-coefficient", "0.05"]),
                        ("ball-in-cone", ["--isolator", "ball-in-cone", "--slope", "0.05",
                                          "--rolling-resistance", "0.01"]),
                        ("ball-in-bowl", ["--isolator", "ball-in-bowl", "--radius", "1.0",
                                          "--rolling-resistance", "0.01"]),
                        ("double-friction-pendulum", ["--isolator", "double-friction-pendulum", "--radius", "1.0",
                                                      "--friction-coefficient", "0.05", "--radius-2", "2.0",
                                                      "--friction-coefficient-2", "0.08"])):
        first(f"run, {kind} isolator", [*iso, *extra], check=_first_agrees())
    first("run, the sliding statue", [*SLIDE], check=_first_agrees())
    first("run, the sliding statue, μ_k < μ_s", [*SLIDE, "--kinetic-friction", "0.2"], check=_first_agrees())
    first("run, vertical shaking", [*FIXED, *SINE, "--vertical", "sine:amp=0.3,freq=3"], check=_first_agrees())
    first("run, 201 s (past FIRST_RUN_REFERENCE_S: the kernel)", [*free[:-2], "201", "--quiet"],
          check=_first_agrees(engine="analytic"))
    first("run --engine analytic-reference (asked: kept)", [*free, "--engine", "analytic-reference"],
          check=_first_agrees(engine="analytic-reference", kernel="analytic-reference"))
    first("run --engine analytic (named: swapped as the default)", [*free, "--engine", "analytic"],
          check=_first_agrees())
    first("run --duration nan (refused before any kernel is asked)", [*free[:-2], "nan", "--quiet"], "exit2")
    first("run --duration 0", [*free[:-2], "0", "--quiet"], "exit2")
    first("run --duration 1e9", [*free[:-2], "1e9", "--quiet"], "exit2")
    for label, args in (("duration=None", "None"), ("duration='abc'", "'abc'"), ("duration=-1", "-1.0"),
                        ("duration=nan", "float('nan')"), ("duration=inf", "float('inf')")):
        add("first-run", f"first_run_reference({label}): no reference asked", (), "ok",
            code="import os\nfrom isorock.analytic import engines, kernel_cache\n"
                 "from isorock.analytic.system import paper_system\n"
                 "ready, mode = kernel_cache.is_ready, os.environ.pop('ISOROCK_FIRST_RUN', None)\n"
                 "kernel_cache.is_ready = lambda d: False\n"
                 f"try:\n    print(engines.first_run_reference(paper_system(), None, {args}))\n"
                 "finally:\n    kernel_cache.is_ready = ready\n"
                 "    if mode is not None:\n        os.environ['ISOROCK_FIRST_RUN'] = mode\n",
            check=lambda d, out: out.strip() == "None")

    # --- atlas --frictions ---------------------------------------------------------------------------
    atlas = ["atlas", "--engines", "mujoco:default", "--slenderness", "2.5", "--mass-ratios", "0", "--heights", "0.5",
             "--out", "at", "--quiet", "--workers", "1"]
    for value in (",", "0", "-0.3", "nan", "inf", "-inf", "1e300", "1e-300", "11", "0.3,0.3", "none,none",
                  "none,NONE", "0.3,none,0.3", "0.3;0.5", "0x1", "0.3,", " ", ",".join(f"{0.1 + 0.1 * k:.1f}"
                                                                                        for k in range(21)),
                  ",".join(["0.5"] * 1000), "1" * 400, "nan,none"):
        add("atlas", f"--frictions {value[:40]!r}{'…' if len(value) > 40 else ''}", [*atlas, "--frictions", value])
    add("atlas", "--frictions with 241 cells", ["atlas", "--engines", "mujoco:default", "--slenderness",
                                                 ",".join(str(2 + k) for k in range(20)), "--heights",
                                                 ",".join(f"{0.1 * (k + 1):.1f}" for k in range(3)),
                                                 "--mass-ratios", "0,1", "--frictions", "0.3,0.5,none",
                                                 "--out", "at", "--quiet"])

    def atlas_ok(frictions):
        """atlas.json's grid lists the frictions sorted (none last) and each row's β is the closed
        form 1 - 1.5 sin²α of its cell's λ (the impact law)."""
        def check(d: Path, out: str) -> bool:
            doc = json.loads((d / "at" / "atlas.json").read_text())
            beta = 1 - 1.5 * math.sin(math.atan(1 / 2.5)) ** 2
            return (doc["grid"]["frictions"] == frictions and len(doc["rows"]) == len(frictions)
                    and all(abs(r["beta_closed"] - beta) < 1e-12 for r in doc["rows"])
                    and sorted(r["friction"] for r in doc["rows"] if r["friction"] is not None)
                    == [f for f in frictions if f is not None])
        return check
    add("atlas", "--frictions 'none, 0.3' (spaces, unsorted)", [*atlas, "--frictions", "none, 0.3"], "ok",
        outputs=("at/",), check=atlas_ok([0.3, None]))
    add("atlas", "--frictions 10 (the top of the range)", [*atlas, "--frictions", "10"], "ok", outputs=("at/",),
        check=atlas_ok([10.0]))

    # --- plugins: the registry's loader and what a plugin hands over --------------------------------
    def plugin(name, code, expect="exit2", **kw):
        add("plugins", name, (), expect, code=code, **kw)
    plugin("an entry point naming a built-in engine ('analytic'): the built-in runs",
           _loader([("analytic", "fakeplug:SPEC")], "analytic"), "ok",
           check=lambda d, out: (json.loads(out)["refused"] == ["analytic"]
                                 and abs(json.loads(out)["run"]["theta_max_over_alpha"] - 0.5) < 1e-9))
    plugin("a name declared twice, then asked for (said why)",
           _loader([("twice", "a:SPEC"), ("twice", "b:SPEC")], "twice"), says="declared twice")
    plugin("a name with a space, asked for (said why)", _loader([("my engine", "a:SPEC")], "my engine"),
           says="no ':', ',' or space")
    plugin("an empty name", _loader([("", "a:SPEC")], "analytic"), "ok",
           check=lambda d, out: json.loads(out)["refused"] == [""])
    plugin("a plugin whose module is not installed", _loader([("ghost", "no_such_module_xyz:SPEC")], "ghost"),
           says="ghost")
    plugin("a plugin whose attribute is missing", _loader([("ghost", "json:NO_SUCH_SPEC")], "ghost"), says="ghost")
    plugin("a plugin whose module raises on import", PLUGIN + "sys.modules.pop('fakeplug', None)\n"
           "import importlib.abc\n"
           "class Boom(importlib.abc.MetaPathFinder):\n"
           "    def find_spec(self, name, path, target=None):\n"
           "        if name == 'boomplug':\n"
           "            raise RuntimeError('boom at import')\n"
           "sys.meta_path.insert(0, Boom())\n"
           "engines.ENGINE_MODULES['boom'] = engines.PLUGINS['boom'] = 'boomplug:SPEC'\n"
           "try:\n    EXIT = main([*RUN, '--engine', 'boom'])\n"
           "finally:\n    del engines.ENGINE_MODULES['boom'], engines.PLUGINS['boom']; sys.meta_path.pop(0)\n",
           says="boom")
    plugin("SPEC is a dict, not an EngineSpec", _plugin_run("obj = {'name': 'fake'}"), says="EngineSpec")
    plugin("SPEC is None", _plugin_run("obj = None"), says="EngineSpec")
    plugin("SPEC is an EngineSpec named otherwise", _plugin_run("obj = spec(lambda *a, **k: None, name='other')"),
           says="EngineSpec")
    plugin("simulate raises RuntimeError", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n    raise RuntimeError('solver blew up')\n"),
        says="solver blew up")
    plugin("simulate raises ZeroDivisionError", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n    return 1 / 0\n"), says="fake")
    plugin("simulate returns None", _plugin_run("obj = spec(sim)", "def sim(system, motion=None, **kw):\n"
                                                "    return None\n"), says="fake")
    plugin("simulate returns a dict", _plugin_run("obj = spec(sim)", "def sim(system, motion=None, **kw):\n"
                                                  "    return {'theta': [0.0]}\n"), says="fake")
    plugin("simulate returns a history with NaN", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n"
        "    return history(system, theta=np.full(50, np.nan))\n"), says="fake")
    plugin("simulate returns a history of unequal arrays", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n"
        "    return history(system, theta=np.zeros(7))\n"), says="fake")
    plugin("simulate returns a history running backwards in time", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n"
        "    return history(system, t=np.linspace(1.0, 0.0, 50))\n"), says="fake")
    plugin("simulate returns an empty history", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n    return history(system, n=0)\n"), says="fake")
    plugin("simulate raises an InputError (its own one line)", _plugin_run(
        "obj = spec(sim)", "from isorock.analytic.errors import InputError\n"
        "def sim(system, motion=None, **kw):\n    raise InputError('step = 1: too coarse for me')\n"),
        says="too coarse for me")
    plugin("a plugin without the isolator asked for", _plugin_run(
        "obj = spec(lambda *a, **k: None)", argv="[*RUN[:7], '--base-mass', '3800', '--isolator', "
        "'friction-pendulum', '--radius', '1', '--friction-coefficient', '0.05', *RUN[8:]]"), says="fake")
    plugin("a plugin that cannot carry the sliding statue", _plugin_run(
        "obj = spec(lambda *a, **k: None, capabilities=Capabilities(statue_friction=False))",
        argv="[*RUN, '--statue-friction', '0.3']"), says="fake")
    plugin("a plugin that cannot carry vertical shaking", _plugin_run(
        "obj = spec(lambda *a, **k: None, capabilities=Capabilities(vertical=False))",
        argv="[*RUN, '--vertical', 'sine:amp=0.2,freq=2']"), says="vertical")
    plugin("a plugin's settings_type is not a dataclass", _plugin_run(
        "obj = EngineSpec(name='fake', label='fake', settings_type=int, simulate=lambda *a, **k: None)"),
        says="fake")
    plugin("a plugin asked for a preset it does not have", _plugin_run(
        "obj = spec(lambda *a, **k: None)").replace("'--engine', 'fake'", "'--engine', 'fake:fine'"), says="fine")
    plugin("a plugin's history of rest (ok: it stays at 0)", _plugin_run(
        "obj = spec(sim)", "def sim(system, motion=None, **kw):\n    return history(system)\n",
        argv="[*RUN, '--json', '-']"), "ok",
        check=lambda d, out: json.loads(out)["theta_max_over_alpha"] == 0.0 and json.loads(out)["impacts"] == 0)

    # --- sliding: --statue-friction, --kinetic-friction, --vertical ------------------------------------
    def slide(name, argv, expect="exit2", **kw):
        add("sliding", name, argv, expect, **kw)
    for value in ("0", "-0.3", "nan", "inf", "-inf", "1e300", "11", "0x1", "true"):
        slide(f"--statue-friction {value}", [*FIXED, *SINE, "--statue-friction", value])
    for value in ("0.5", "nan", "-0.1", "0", "inf", "0.30000001"):
        slide(f"--kinetic-friction {value} (μ_s 0.3)", [*SLIDE, "--kinetic-friction", value])
    slide("--kinetic-friction without --statue-friction", [*FIXED, *SINE, "--kinetic-friction", "0.2"])
    slide("--vertical-units without --vertical", [*FIXED, *SINE, "--vertical-units", "g"])
    slide("--vertical none", [*FIXED, *SINE, "--vertical", "none"])
    slide("--vertical a folder", [*FIXED, *SINE, "--vertical", "recs"], setup=_records)
    slide("--vertical /dev/zero", [*FIXED, *SINE, "--vertical", "/dev/zero"])
    slide("--vertical a file of random bytes", [*FIXED, *SINE, "--vertical", "v.txt"],
          setup=_files(v__txt=bytes(range(256)) * 4))
    slide("--vertical a record with a NaN", [*FIXED, *SINE, "--vertical", "v.txt"],
          setup=_files(v__txt=_record_text([0.0, 0.1, float("nan"), 0.0])))
    slide("--vertical a record of 1e300 g", [*FIXED, *SINE, "--vertical", "v.txt", "--budget", "20"],
          setup=_files(v__txt=_record_text([0.0, 1e300, 0.0, 0.0])), in_process=False)
    slide("--vertical a record of 1e40 g, isolated", ["run", *PAPER, "--period", "1.5", "--damping", "0.2", *SINE,
                                                      "--vertical", "v.txt", "--budget", "20", "--quiet"],
          setup=_files(v__txt=_record_text([0.0, 1e40, 0.0, 0.0])), in_process=False)
    slide("--vertical sine:amp=1e300", [*FIXED, *SINE, "--vertical", "sine:amp=1e300,freq=2"])
    slide("--vertical a record without units (and none given)", [*FIXED, *SINE, "--vertical", "v.txt"],
          setup=_files(v__txt=_record_text(_shaking(1), units=None)))
    slide("--vertical, --pga on a zero horizontal", [*FIXED, "--motion", "none", "--vertical", "sine:amp=0.3,freq=2",
                                                     "--pga", "0.5", "--duration", "2"])
    slide("--statue-friction 0.3 --engine mujoco --kinetic-friction 0.2 (one coefficient)",
          [*SLIDE, "--engine", "mujoco", "--kinetic-friction", "0.2"])

    def same_as(argv_ref, keys=("theta_max_over_alpha", "impacts", "status", "slide_max"), rel=1e-9):
        """The run's JSON agrees with `argv_ref`'s (run here, the same way) on `keys`."""
        def check(d: Path, out: str) -> bool:
            code, text = _capture_in(d, [*argv_ref, "--json", "-"])
            got, ref = json.loads(out), json.loads(text)
            for k in keys:
                a, b = got.get(k), ref.get(k)
                if isinstance(a, float) and isinstance(b, float):
                    if not abs(a - b) <= rel * max(1.0, abs(b)):
                        return False
                elif a != b:
                    return False
            return True
        return check
    quake = _record_text(_shaking(0, 400, 0.5))
    base = [*FIXED, "--motion", "h.txt", "--duration", "5", "--statue-friction", "0.3"]
    slide("--vertical an all-zero record (the run without it)", [*base, "--vertical", "z.txt", "--json", "-"], "ok",
          setup=_files(h__txt=quake, z__txt=_record_text([0.0] * 400)), check=same_as(base))
    slide("--vertical a zero record shorter than the horizontal", [*base, "--vertical", "z.txt", "--json", "-"], "ok",
          setup=_files(h__txt=quake, z__txt=_record_text([0.0] * 20)), check=same_as(base))
    vert_g = _record_text([0.15 * math.sin(2 * math.pi * 3 * i / 100) for i in range(400)])
    vert_gal = _record_text([0.15 * 980.665 * math.sin(2 * math.pi * 3 * i / 100) for i in range(400)], units="gal")
    slide("--vertical in gal beside a horizontal in g (the same run as in g)",
          [*base, "--vertical", "vgal.txt", "--json", "-"], "ok",
          setup=_files(h__txt=quake, vg__txt=vert_g, vgal__txt=vert_gal), check=same_as([*base, "--vertical", "vg.txt"],
                                                                                          rel=1e-4))
    vert_fine = "# units: g\n" + "".join(f"{i * 0.005:.4f} 0.2\n" for i in range(800))
    vert_coarse = "# units: g\n" + "".join(f"{i * 0.01:.4f} 0.2\n" for i in range(400))
    slide("--vertical a constant record at another dt (the same run)", [*base, "--vertical", "vf.txt", "--json", "-"],
          "ok", setup=_files(h__txt=quake, vf__txt=vert_fine, vc__txt=vert_coarse),
          check=same_as([*base, "--vertical", "vc.txt"], rel=1e-6))
    slide("--vertical longer than the horizontal (the run lasts to its end + 5 s)",
          [*FIXED, "--motion", "h.txt", "--statue-friction", "0.3", "--vertical", "z.txt", "--json", "-"], "ok",
          setup=_files(h__txt=quake, z__txt=_record_text([0.0] * 900)),
          check=lambda d, out: abs(json.loads(out)["duration"] - (8.99 + 5.0)) < 1e-9)
    slide("--statue-friction 0.3 --kinetic-friction 0.3 (equal: the same run as without it)",
          [*SLIDE, "--kinetic-friction", "0.3", "--json", "-"], "ok", check=same_as(SLIDE))
    slide("--statue-friction 10 (no slip: the block as without friction)",
          [*FIXED, *SINE, "--statue-friction", "10", "--json", "-"], "ok",
          check=same_as([*FIXED, *SINE], keys=("impacts", "status")))
    slide("--vertical alone on a symmetric block: it never rocks", [*FIXED, "--motion", "none", "--vertical",
                                                                     "sine:amp=0.3,freq=2", "--duration", "2",
                                                                     "--json", "-"], "ok",
          check=lambda d, out: json.loads(out)["theta_max_over_alpha"] == 0.0)
    add("sliding", "--vertical below -g: the run says free flight (status failed, exit 1)", (), "ok",
        setup=_files(v__txt=_record_text([-1.5] * 300)),
        code=CAPTURE + "import json\nEXIT_RUN, out = capture(" + repr([*FIXED, *SINE, "--vertical", "v.txt", "--json", "-"])
        + ")\nd = json.loads(out)\nprint(json.dumps([EXIT_RUN, d['status'], d['message']]))\n",
        check=lambda d, out: (json.loads(out)[0] == 1 and json.loads(out)[1] in ("failed", "outside-model")
                             and "free flight" in json.loads(out)[2]))
    slide("--statue-friction 1e-300: the ground slides under it, it never tips",
          [*FIXED, *SINE, "--statue-friction", "1e-300", "--json", "-"], "ok",
          check=lambda d, out: json.loads(out)["theta_max_over_alpha"] == 0.0 and json.loads(out)["slide_max"] > 0.1)

    # --- design-statue: --friction, --plinth-margin, --target, --max-stroke, --check-runs --------------
    def dstat(name, *extra, expect="exit2", **kw):
        add("design-statue", name, [*DESIGN, *extra], expect, setup=kw.pop("setup", _records), **kw)
    for option, value in (("--friction", "0"), ("--friction", "-0.3"), ("--friction", "nan"), ("--friction", "inf"),
                          ("--friction", "1e300"), ("--friction", "none"), ("--plinth-margin", "0.1"),
                          ("--target", "-0.01"), ("--target", "1.0000001"), ("--target", "inf"),
                          ("--target", "-inf"), ("--max-stroke", "-1"), ("--max-stroke", "nan"),
                          ("--max-stroke", "-inf"), ("--check-runs", "1.5"), ("--check-runs", "-1"),
                          ("--check-runs", "1e9"), ("--check-runs", "nan"), ("--check-runs", "10000000000000000000000")):
        dstat(f"{option} {value}", option, value)
    for v in ("0", "-1", "nan", "inf"):
        dstat(f"--friction 0.5 --plinth-margin {v}", "--friction", "0.5", "--plinth-margin", v)
    dstat("--plinth-margin before --friction's value is checked", "--plinth-margin", "nan", "--friction", "nan")
    dstat("--friction 0.5 --check bullet (one coefficient: carried?)", "--friction", "0.5", "--check", "bullet",
          "--check-runs", "1", expect="ok", outputs=OUT,
          # one run on each base it compares (the named isolator, the fixed base), as --check-runs says
          check=lambda d, out: json.loads((d / "out" / "design.json").read_text())["checks"][0]["n"] == 2)

    from adversarial_round_three import _design_json as design_doc  # design.json's value at a dotted key

    def no_slip_as_without(d: Path, out: str) -> bool:
        """--friction 10: no record slides the statue, so every P(overturn) is the no-slip design's
        (the same records, levels and grid, run again here without the friction)."""
        assert _capture_in(d, [*DESIGN[:-1], "ref"])[0] == 0
        got = json.loads((d / "out" / "design.json").read_text())
        ref = json.loads((d / "ref" / "design.json").read_text())
        import shutil
        shutil.rmtree(d / "ref")
        return [r["p_levels"] for r in got["isolators"]] == [r["p_levels"] for r in ref["isolators"]]
    dstat("--friction 10 (no slip: the no-slip design's P)", "--friction", "10", expect="ok", outputs=OUT,
          check=no_slip_as_without)
    dstat("--target 0 (nothing but P = 0 meets it)", "--target", "0", expect="ok", outputs=OUT,
          check=design_doc("rule.target", 0.0))
    dstat("--target 1 (everything meets it)", "--target", "1", expect="ok", outputs=OUT,
          check=design_doc("rule.target", 1.0))
    dstat("--max-stroke 1e-300 (no isolator within it)", "--max-stroke", "1e-300", expect="ok", outputs=OUT,
          check=lambda d, out: not json.loads((d / "out" / "design.json").read_text())["answer"]["recommended"])
    dstat("--friction 0.5 --plinth-margin 1e300 (never walks off; design.json says the statue)", "--friction", "0.5",
          "--plinth-margin", "1e300", expect="ok", outputs=OUT, check=lambda d, out: (
              json.loads((d / "out" / "design.json").read_text())["statue"] == {
                  "height": 1.0, "width": 0.35, "mass": 100.0, "base_mass": 100.0, "friction": 0.5,
                  "plinth_margin": 1e300}))
    return c
