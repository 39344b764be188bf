"""The floors, guarded: every import in every package (module level, inside functions,
relative or absolute, `import a.b` or `from a import b`) goes down the building or stays
on its floor, never up. The floors (README, Layout):

    0  analytic/                          the model and the vocabulary every engine speaks
    1  mujoco_models/ bullet_models/ drake_models/   the engines (they import the model only)
    2  validate/core/                     registry, cases, measure, compare, tolerances, executor
    3  validate/io/                       outputs, provenance, progress, figures
    4  validate/tools/ campaign/ experiments/   the tools: report, bench, stress, atlas, …
    5  validate/cli/                      the command line: the only floor that imports a tool

Two rules more than the order: the tools reach an engine through the registry only
(no tool imports an engine package), and the tools do not import one another across
packages (validate/tools, campaign and experiments each stand on the floors below)."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: package (import name under isorock.) → (floor, folder)
FLOORS = {
    "analytic": (0, "analytic"),
    "mujoco_models": (1, "mujoco_models"),
    "bullet_models": (1, "bullet_models"),
    "drake_models": (1, "drake_models"),
    "validate.core": (2, "validate/core"),
    "validate.io": (3, "validate/io"),
    "validate.tools": (4, "validate/tools"),
    "campaign": (4, "campaign"),
    "experiments": (4, "experiments"),
    "validate.cli": (5, "validate/cli"),
}
ENGINES = ("mujoco_models", "bullet_models", "drake_models")


def package_of(module: str) -> str | None:
    """The floor package an absolute import name belongs to (None: not isorock's)."""
    if module.startswith("isorock."):
        module = module[len("isorock."):]
    for name in sorted(FLOORS, key=len, reverse=True):
        if module == name or module.startswith(name + "."):
            return name
    return None


def imports(path: Path, package: str) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in the file, at any depth."""
    parts = ("isorock." + package).split(".")
    rel = path.relative_to(ROOT / FLOORS[package][1]).with_suffix("").parts
    here = parts + list(rel[:-1])  # the file's own package, for relative imports
    out = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = here[:len(here) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            # `from isorock.validate import cli` names its floor only in the imported name
            out += [(node.lineno, f"{module}.{a.name}") for a in node.names]
    return out


def all_imports():
    for package, (_, folder) in FLOORS.items():
        for path in sorted((ROOT / folder).rglob("*.py")):
            for line, module in imports(path, package):
                yield package, path.relative_to(ROOT), line, module


def test_every_floor_has_its_folder():
    missing = [folder for _, folder in FLOORS.values() if not (ROOT / folder).is_dir() and folder != "experiments"]
    assert not missing


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
        if target in ENGINES and floor[package] >= 2:
            bad.append(f"{path}:{line} imports the engine package {module} (use the registry)")
        if floor[package] == 4 and floor[target] == 4 and target != package:
            bad.append(f"{path}:{line}: the tool {package} imports the tool {module}")
    assert not bad, "\n".join(bad)


def test_engines_import_only_the_model():
    bad = [f"{path}:{line} imports {module}" for package, path, line, module in all_imports()
           if package in ENGINES and package_of(module) not in (None, "analytic", package)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("module,expected", [
    ("isorock.validate.core.engines", "validate.core"), ("isorock.validate.cli", "validate.cli"),
    ("isorock.analytic.fast", "analytic"), ("numpy", None), ("isorock.validate.tools.atlas", "validate.tools")])
def test_package_of_reads_import_names(module, expected):
    """The checker itself: an import name maps to its floor (else the rules check nothing)."""
    assert package_of(module) == expected


def test_the_checker_sees_imports_inside_functions_and_relative_ones(tmp_path):
    """A violation hidden in a function body, or written relatively, is still found."""
    folder = ROOT / "validate" / "core"
    probe = folder / "_probe_architecture_tmp.py"
    probe.write_text("def f():\n    from isorock.validate.cli import main\n    from ..tools import atlas\n")
    try:
        found = [m for _, m in imports(probe, "validate.core")]
    finally:
        probe.unlink()
    assert [package_of(m) for m in found] == ["validate.cli", "validate.tools"]


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
