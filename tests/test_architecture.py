"""The floors, guarded: every import in every installed package (module level, inside
functions and classes, relative or absolute, `import a.b` or `from a import b`, and a
module named in a string for importlib) goes down the building or stays on its floor,
never up; every installed module stands on a floor. The floors (README, Layout):

    0  analytic/                          the model and the vocabulary every engine speaks
    1  mujoco_models/ bullet_models/ drake_models/ dart_models/   the engines (they import the model only)
    2  validate/core/                     registry, cases, measure, compare, tolerances, executor
    3  validate/io/                       outputs, provenance, progress, figures
    4  validate/tools/                    the tools: report, bench, stress, atlas, …, and in folders
                                          of their own campaign/ (sweep, design) and experiments/
    5  validate/cli/                      the command line: the only floor that imports a tool

Two rules more than the order: the tools reach an engine through the registry only
(no tool imports an engine package), and the tools do not import one another across
packages (validate/tools' modules, campaign/ and experiments/ each stand on the floors below),
so `campaign/` imports the lower floors only and only the command line imports it.

Every floor is a folder: the model, the engines' packages, and validate/'s four floors
(validate/tools/campaign/ and validate/tools/experiments/ are tools; issue 35)."""
from __future__ import annotations

import ast
import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: package (import name under isorock.) → (floor, folder)
FLOORS = {
    "analytic": (0, "analytic"),
    "mujoco_models": (1, "mujoco_models"),
    "bullet_models": (1, "bullet_models"),
    "drake_models": (1, "drake_models"),
    "dart_models": (1, "dart_models"),
    "validate.core": (2, "validate/core"),
    "validate.io": (3, "validate/io"),
    "validate.tools": (4, "validate/tools"),
    "validate.tools.campaign": (4, "validate/tools/campaign"),
    "validate.tools.experiments": (4, "validate/tools/experiments"),
    "validate.cli": (5, "validate/cli"),
    # the top package `isorock` (api/): the notebook API's entry points, over the command line
    "isorock": (6, "api"),
}
ENGINES = ("mujoco_models", "bullet_models", "drake_models", "dart_models")
CAMPAIGN = "validate.tools.campaign"


def package_of(module: str) -> str | None:
    """The floor package an absolute import name belongs to (None: not isorock's)."""
    if module.startswith("isorock."):
        module = module[len("isorock."):]
    for name in sorted(FLOORS, key=len, reverse=True):
        if module == name or module.startswith(name + "."):
            return name
    return None


#: a module named in a string: an import by name (importlib.import_module, __import__, the
#: registry's ENGINE_MODULES, the command line's EXTRA_COMMANDS): "isorock.pkg.mod[:ATTR]"
BY_NAME = re.compile(r"isorock\.[A-Za-z_][\w.]*(?::\w+)?")
#: the one module that may name the engine packages: the registry's names (validate/core/registry.py)
REGISTRY = Path("validate/core/registry.py")


def imports(path: Path, package: str, text: str | None = None) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in the file, at any depth (module level,
    functions, classes, `if`/`try` blocks), relative ones made absolute, and every module
    named in a string (an import by name). `text`: the file's source, if not read from it."""
    parts = ("isorock." + package).split(".")
    rel = path.relative_to(ROOT / FLOORS[package][1]).with_suffix("").parts
    here = parts + list(rel[:-1])  # the file's own package, for relative imports
    out = []
    tree = ast.parse(path.read_text() if text is None else text, str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = here[:len(here) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            # `from isorock.validate import cli` names its floor only in the imported name
            out += [(node.lineno, f"{module}.{a.name}") for a in node.names]
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and BY_NAME.fullmatch(node.value):
            out.append((node.lineno, node.value.partition(":")[0]))
    return out


def pyproject_packages() -> dict[str, str]:
    """Import name (without 'isorock.') → folder, as pyproject.toml installs them."""
    with open(ROOT / "pyproject.toml", "rb") as f:
        dirs = tomllib.load(f)["tool"]["setuptools"]["package-dir"]
    return {name.removeprefix("isorock."): folder for name, folder in dirs.items()}


def files_of(package: str) -> list[Path]:
    """The files of a floor package: its folder's, less those of a package of its own inside it
    (validate/tools/campaign/ is the package validate.tools.campaign, not validate.tools)."""
    folder = ROOT / FLOORS[package][1]
    inner = [ROOT / f for name, (_, f) in FLOORS.items() if name.startswith(package + ".")]
    return [p for p in sorted(folder.rglob("*.py")) if not any(p.is_relative_to(i) for i in inner)]


def all_imports():
    for package in FLOORS:
        for path in files_of(package):
            for line, module in imports(path, package):
                yield package, path.relative_to(ROOT), line, module


def test_every_floor_has_its_folder():
    missing = [folder for _, folder in FLOORS.values() if not (ROOT / folder).is_dir()]
    assert not missing


def test_every_installed_module_stands_on_a_floor():
    """Every package pyproject.toml installs is a floor, or the `validate` umbrella, whose
    folder holds the floors and no module of its own (a file there would be on no floor,
    and no rule would check it)."""
    installed = pyproject_packages()
    unfloored = sorted(set(installed) - set(FLOORS) - {"validate"})
    assert not unfloored, f"packages on no floor: {unfloored} (add them to FLOORS and the README's Layout)"
    assert {name: installed[name] for name in FLOORS} == {name: folder for name, (_, folder) in FLOORS.items()}
    umbrella = ROOT / installed["validate"]
    loose = [p.name for p in umbrella.glob("*.py") if p.name != "__init__.py" or p.read_text().strip()]
    assert not loose, f"validate/ holds modules on no floor: {loose}"


def test_no_floor_imports_one_above_it():
    up = [f"{path}:{line} imports {module} (floor {FLOORS[package_of(module)][0]} above "
          f"{package}'s {FLOORS[package][0]})"
          for package, path, line, module in all_imports()
          if package_of(module) is not None and FLOORS[package_of(module)][0] > FLOORS[package][0]]
    assert not up, "\n".join(up)


def test_tools_reach_engines_through_the_registry_and_stand_apart():
    floor = {name: f for name, (f, _) in FLOORS.items()}
    bad = []
    for package, path, line, module in all_imports():
        target = package_of(module)
        if target is None or floor[package] < 2:
            continue
        if target in ENGINES and path != REGISTRY:
            bad.append(f"{path}:{line} imports the engine package {module} (use the registry)")
        if floor[package] == 4 and floor[target] == 4 and target != package:
            bad.append(f"{path}:{line}: the tool {package} imports the tool {module}")
    assert not bad, "\n".join(bad)


def test_campaign_imports_lower_floors_only_and_only_the_command_line_imports_it():
    """Issue 23: `campaign/` stands on the core and io floors (and the model); the command
    line alone runs it, and the top package's Python entry points (isorock.design, issue 39),
    the floor above the command line."""
    floor = {name: f for name, (f, _) in FLOORS.items()}
    bad = [f"{path}:{line} imports {module}" for package, path, line, module in all_imports()
           if package == CAMPAIGN and package_of(module) not in (None, CAMPAIGN)
           and floor[package_of(module)] >= floor[CAMPAIGN]]
    bad += [f"{path}:{line} imports {module} (only validate/cli runs campaigns)"
            for package, path, line, module in all_imports()
            if package_of(module) == CAMPAIGN and package not in (CAMPAIGN, "validate.cli", "isorock")]
    assert not bad, "\n".join(bad)


def test_engines_import_only_the_model():
    bad = [f"{path}:{line} imports {module}" for package, path, line, module in all_imports()
           if package in ENGINES and package_of(module) not in (None, "analytic", package)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("module,expected", [
    ("isorock.validate.core.engines", "validate.core"), ("isorock.validate.cli", "validate.cli"),
    ("isorock.analytic.fast", "analytic"), ("numpy", None), ("isorock.validate.tools.atlas", "validate.tools"),
    ("isorock.validate.tools.campaign", CAMPAIGN), ("isorock.validate", None)])
def test_package_of_reads_import_names(module, expected):
    """The checker itself: an import name maps to its floor (else the rules check nothing)."""
    assert package_of(module) == expected


PROBE = """\
import isorock.validate.tools.atlas as atlas_alias
from isorock.validate.tools import campaign
from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from isorock.validate.io import output
try:
    from isorock.mujoco_models import scene
except ImportError:
    pass


class Holder:
    def method(self):
        from . import measure


def f():
    from isorock.validate.cli import main
    from ..tools import bench

    def inner():
        import importlib
        return importlib.import_module("isorock.validate.cli.sweep"), __import__("isorock.validate.tools.experiments.study")
    return inner


LAZY = {"view": "isorock.validate.tools.view:ENGINE"}
"""


def test_the_checker_sees_every_import_form():
    """Each form the rules must see (module level, `import a.b as c`, `from isorock import
    x`, TYPE_CHECKING and try blocks, methods, functions, nested functions, relative
    imports, modules named in strings) is found, as a file of validate/core would hold
    them; the file is parsed from text, nothing is written into the tree."""
    found = [m for _, m in sorted(imports(ROOT / "validate" / "core" / "probe.py", "validate.core", PROBE))]
    assert [package_of(m) for m in found if package_of(m)] == [
        "validate.tools", CAMPAIGN, "validate.io", "mujoco_models", "validate.core", "validate.cli",
        "validate.tools", "validate.cli", "validate.tools.experiments", "validate.tools"]
    assert "isorock.validate.core.measure" in found  # `from . import measure` in the probe's package
    assert "isorock.validate.tools.bench" in found  # `from ..tools import bench`


def test_the_rules_fail_on_an_upward_import(monkeypatch):
    """The rules themselves, fed one file of the core that imports the command line from
    inside a function: the upward-import rule fails and names the file and line."""
    def one_bad_file():
        yield "validate.core", Path("validate/core/probe.py"), 2, "isorock.validate.cli.main"
    monkeypatch.setitem(globals(), "all_imports", one_bad_file)
    with pytest.raises(AssertionError, match=r"validate/core/probe.py:2 imports isorock.validate.cli.main"):
        test_no_floor_imports_one_above_it()
    with pytest.raises(AssertionError, match="campaign"):
        monkeypatch.setitem(globals(), "all_imports",
                            lambda: iter([("validate.tools", Path("validate/tools/x.py"), 1, "isorock.validate.tools.campaign.run")]))
        test_campaign_imports_lower_floors_only_and_only_the_command_line_imports_it()


def test_the_top_package_is_the_api_and_nothing_below_imports_it():
    """`isorock` itself (api/, the notebook API's entry points) stands on the command
    line's floor: it imports the command line's api module only, and no floor imports
    the top package's names (isorock.run, isorock.report, isorock.sweep)."""
    top = ROOT / "api" / "__init__.py"
    mine = [m for _, m in imports_of_top(top)]
    assert mine and all(package_of(m) == "validate.cli" or not m.startswith("isorock") for m in mine), mine
    bad = [f"{path}:{line} imports {module}" for package, path, line, module in all_imports()
           if module == "isorock" or module in ("isorock.run", "isorock.report", "isorock.sweep")]
    assert not bad, "\n".join(bad)


def imports_of_top(path: Path) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and not node.level:
            out += [(node.lineno, f"{node.module}.{a.name}") for a in node.names]
    return out


def test_compare_only_compares():
    """Issue 35: core.compare compares the trajectories it is given and runs nothing; the runs that
    probe the model's robustness are core.probes'. Its imports and calls are the oracle: no engine
    registry, no call of anything named simulate."""
    path = ROOT / "validate" / "core" / "compare.py"
    assert not [m for _, m in imports(path, "validate.core") if m.startswith("isorock.validate.core.engines")]
    tree = ast.parse(path.read_text())
    calls = {n.func.attr if isinstance(n.func, ast.Attribute) else getattr(n.func, "id", "")
             for n in ast.walk(tree) if isinstance(n, ast.Call)}
    assert not {c for c in calls if "simulate" in c}


# --- issue 35: imports at the module's top; one inside a function says why it waits -------------

#: the word a reason for an import inside a function starts with (`# lazy: matplotlib, only with --plot`)
LAZY = "lazy"


def unexplained_inner_imports(text: str) -> list[tuple[int, str]]:
    """(line, statement) of each import statement inside a function (at any depth: methods,
    nested functions, `try`/`with`/`if` blocks) whose reason is not written beside it: a
    comment holding "lazy" on its own line(s) or the line above. An import right after one
    that has its reason (the next statement of the same block) shares it, so that
    `import matplotlib  # lazy: …` covers the `from matplotlib… import …` lines under it.
    Module-level imports, and the command dispatch (validate/cli/main.py imports a command's
    module by name, with importlib), are not import statements inside a function."""
    import io
    import tokenize
    lines = text.splitlines()
    comments: dict[int, str] = {}
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT:
            comments[tok.start[0]] = tok.string
    said = lambda n: LAZY in comments.get(n, "").lower()  # noqa: E731
    bad = []
    for fn in ast.walk(ast.parse(text)):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for block in ast.walk(fn):
            for field in ("body", "orelse", "finalbody", "handlers"):
                body = getattr(block, field, None)
                if not isinstance(body, list):
                    continue
                explained = False
                for stmt in body:
                    if not isinstance(stmt, (ast.Import, ast.ImportFrom)):
                        explained = False
                        continue
                    explained = explained or any(said(n) for n in range(stmt.lineno - 1, stmt.end_lineno + 1))
                    if not explained:
                        bad.append((stmt.lineno, lines[stmt.lineno - 1].strip()))
    return sorted(set(bad))


def test_every_import_inside_a_function_says_why_it_waits():
    """Issue 35: imports stand at the top of their module; one inside a function is there for
    a reason written beside it (`# lazy: …`): an import cycle, a heavy package off a light
    command's path (`isorock --help`, `isorock beta`, `import isorock.analytic`), an optional
    extra, a platform's module."""
    bad = [f"{path.relative_to(ROOT)}:{line}: {stmt}"
           for package in FLOORS for path in files_of(package)
           for line, stmt in unexplained_inner_imports(path.read_text())]
    assert not bad, "imports inside a function without a `# lazy: why` comment:\n" + "\n".join(bad)


INNER = '''\
import numpy as np  # the top: no reason needed


def drawn(path):
    import matplotlib  # lazy: matplotlib, only with --plot
    from matplotlib.figure import Figure
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return Figure, plt


def waits():
    # lazy: an import cycle, b imports this module
    from . import b
    try:
        from . import c
    except ImportError:
        pass
    return b, c


class Engine:
    def run(self):
        from .fast import simulate  # noqa: F401
        s = """lazy inside a string is no reason"""
        from .hybrid import simulate as reference
        return s, reference
'''


def test_the_inner_import_rule_fails_on_an_import_without_its_reason():
    """The rule itself, on source text: the imports that wait without a written reason are
    found (after a statement that is not an import, in a try block, in a method, after a
    string that says "lazy"), and those with a reason, or under one that has it, are not."""
    assert unexplained_inner_imports(INNER) == [
        (8, "import matplotlib.pyplot as plt"), (16, "from . import c"),
        (24, "from .fast import simulate  # noqa: F401"), (26, "from .hybrid import simulate as reference")]
    planted = INNER.replace("from . import c", "from . import c  # lazy: an optional extra")
    assert (16, "from . import c  # lazy: an optional extra") not in unexplained_inner_imports(planted)
