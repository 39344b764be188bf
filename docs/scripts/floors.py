"""The import graph between the project's folders and floors, and the lines on each floor,
computed from the code (issue 23's closing note).

    python docs/scripts/floors.py [ROOT] [--before OLD_ROOT]

ROOT (default: this checkout) and OLD_ROOT are checkouts of the project, e.g. an older
commit checked out with `git worktree add /tmp/floors-before REV`. Every import is counted:
module level and inside functions, `import a.b` and `from a import b`, absolute and
relative, and a module named in a string (importlib, the registry's ENGINE_MODULES); one
edge is one import statement (or string) naming a module of another folder. The folders
are the packages of the checkout's own pyproject.toml ([tool.setuptools.package-dir]).

The floors are the architecture test's table (tests/test_architecture.py: FLOORS, the one
home). An older checkout had no floors inside validate/: each of its files is placed on the
floor of the module it became (WENT_TO below, else the module of the same name today), so
the same rule (no import goes up a floor) can be counted before and after.
"""
from __future__ import annotations

import argparse
import ast
import re
import sys
from collections import Counter
from pathlib import Path

HERE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(HERE / "tests"))
from test_architecture import FLOORS  # noqa: E402  (the floors' one home)

#: where a module of the flat validate/ (and campaign/, analytic/) went, where its name changed
WENT_TO = {
    "validate/cli.py": "validate.cli", "validate/run_cli.py": "validate.cli",
    "validate/report_cli.py": "validate.cli", "campaign/cli.py": "validate.cli",
    "validate/progress.py": "validate.io", "campaign/build.py": "validate.core",
    "campaign/execute.py": "validate.core", "campaign/fragility.py": "validate.core",
    "validate/runner.py": "validate.core", "validate/tolerances.py": "validate.core",
    "analytic/agreement.py": "tests (test code, moved out)",
}
#: the tools' folders that stood at the top before issue 35 moved them under validate/tools/
MOVED = {"campaign": "validate.tools.campaign", "experiments": "validate.tools.experiments"}
FLOOR_NAMES = {0: "model", 1: "engines", 2: "core", 3: "io", 4: "tools", 5: "cli", 6: "api"}


def packages(root: Path) -> dict[str, Path]:
    """Import name (without 'isorock.') → folder, from the checkout's pyproject.toml."""
    text = (root / "pyproject.toml").read_text()
    section = text.split("[tool.setuptools.package-dir]", 1)[1].split("\n[", 1)[0]
    return {name.removeprefix("isorock."): root / folder
            for name, folder in re.findall(r'^"([^"]+)"\s*=\s*"([^"]+)"', section, re.M)}


def package_of(module: str, names) -> str | None:
    module = module.removeprefix("isorock.")
    return next((n for n in sorted(names, key=len, reverse=True) if module == n or module.startswith(n + ".")),
                None)


def files(root: Path) -> dict[Path, str]:
    """Each .py file → the package (folder) it belongs to: the longest folder holding it."""
    pkgs = packages(root)
    out = {}
    for name, folder in sorted(pkgs.items(), key=lambda kv: len(str(kv[1]))):
        for path in folder.rglob("*.py"):
            out[path] = name  # a subpackage, listed later (longer folder), wins
    return out


#: a module named in a string, imported by name (importlib, the registry's ENGINE_MODULES)
BY_NAME = re.compile(r"isorock\.[A-Za-z_][\w.]*(?::\w+)?")
#: the registry, the one module that names the engine packages (then and now)
REGISTRY = ("validate/engines.py", "validate/core/engines.py")


def statements(path: Path, package: str, folder: Path):
    """(in_function, imported modules) of each import statement of the file, at any depth,
    relative imports made absolute (`from x import y` names x.y: y may be a module), and of
    each module named in a string (an import by name), as tests/test_architecture.py reads them."""
    here = ["isorock", *package.split("."), *path.relative_to(folder).with_suffix("").parts[:-1]]
    tree = ast.parse(path.read_text(), str(path))
    inside = {id(n) for f in ast.walk(tree) if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))
              for n in ast.walk(f) if n is not f}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield id(node) in inside, [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                module = ".".join(here[:len(here) - node.level + 1] + ([node.module] if node.module else []))
            yield id(node) in inside, [f"{module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and BY_NAME.fullmatch(node.value):
            yield id(node) in inside, [node.value.partition(":")[0]]


def graph(root: Path):
    """(edges, lines, where): edges[(from folder, to folder)] = [statements, of them inside
    functions]; lines[folder] = lines of code; where[folder] = the floor package of each file
    (today's packages map to themselves)."""
    pkgs = packages(root)
    edges: dict = {}
    lines: Counter = Counter()
    floor_lines: Counter = Counter()
    floor_edges: Counter = Counter()
    around: Counter = Counter()  # engine packages named above floor 1 outside the registry
    for path, package in files(root).items():
        n = len(path.read_text().splitlines())
        lines[package] += n
        rel = path.relative_to(root).as_posix()
        own_floor = floor_package(rel, package)
        floor_lines[own_floor] += n
        for in_function, modules in statements(path, package, pkgs[package]):
            targets = {package_of(m, pkgs) for m in modules} - {None}
            for target in targets:
                if target != package:
                    e = edges.setdefault((package, target), [0, 0])
                    e[0] += 1
                    e[1] += in_function
            for target_floor in {floor_package_of_module(m, pkgs, root) for m in modules} - {None}:
                if target_floor != own_floor:
                    floor_edges[(own_floor, target_floor)] += 1
                    if floor(target_floor) == 1 and (floor(own_floor) or 0) >= 2 and rel not in REGISTRY:
                        around[(own_floor, target_floor)] += 1
    return edges, lines, floor_lines, floor_edges, around


def floor_package(rel: str, package: str) -> str:
    """The floor package (a FLOORS key) a file stands on, today or by where it went."""
    if package in FLOORS:
        return package
    if rel in WENT_TO:
        return WENT_TO[rel]
    if package in MOVED:  # a tool's own folder, once at the top (issue 35 moved it under validate/tools/)
        return MOVED[package]
    top, stem = rel.split("/", 1)[0], Path(rel).stem
    # the module of the same name today, in the same top folder (validate/engines.py became
    # validate/core/engines.py, not analytic/engines.py)
    for name, (_, folder) in FLOORS.items():
        if folder.split("/", 1)[0] == top and (HERE / folder / f"{stem}.py").is_file():
            return name
    return package  # e.g. validate/__init__.py: the folder itself


def floor_package_of_module(module: str, pkgs, root: Path) -> str | None:
    package = package_of(module, pkgs)
    if package is None:
        return None
    if package in FLOORS:
        return package
    # an older flat package: the module's file decides (validate.engines → validate/engines.py)
    rest = module.removeprefix("isorock.").removeprefix(package).lstrip(".").split(".")
    folder = pkgs[package]
    for k in range(len(rest), 0, -1):
        candidate = folder.joinpath(*rest[:k]).with_suffix(".py")
        if candidate.is_file():
            return floor_package(candidate.relative_to(root).as_posix(), package)
    return package


def floor(name: str) -> int | None:
    return FLOORS[name][0] if name in FLOORS else None


def report(root: Path, title: str) -> dict:
    edges, lines, floor_lines, floor_edges, around = graph(root)
    print(f"\n## {title}: {root}\n")
    print("Imports between folders (import statements; of them inside functions):\n")
    print("| from → to | statements | in functions |")
    print("|---|---:|---:|")
    for (a, b), (n, inner) in sorted(edges.items()):
        print(f"| {a} → {b} | {n} | {inner} |")
    both = sorted({tuple(sorted(k)) for k in edges if (k[1], k[0]) in edges})
    print(f"\nFolders importing each other: {', '.join(f'{a} ⇄ {b} ({edges[(a, b)][0]}/{edges[(b, a)][0]})' for a, b in both) or 'none'}")
    print(f"Import statements between folders: {sum(n for n, _ in edges.values())} "
          f"({sum(i for _, i in edges.values())} inside functions)")
    up = {k: n for k, n in floor_edges.items() if None not in (floor(k[0]), floor(k[1])) and floor(k[1]) > floor(k[0])}
    down = sum(n for k, n in floor_edges.items() if None not in (floor(k[0]), floor(k[1])) and floor(k[1]) < floor(k[0]))
    level = sum(n for k, n in floor_edges.items() if None not in (floor(k[0]), floor(k[1])) and floor(k[1]) == floor(k[0]))
    print(f"\nBy today's floors (each file on the floor of the module it is or became): "
          f"{down} statements down, {level} across one floor, {sum(up.values())} up")
    for (a, b), n in sorted(up.items()):
        print(f"  up: {a} (floor {floor(a)}) → {b} (floor {floor(b)}): {n}")
    matrix = Counter()
    for (a, b), n in floor_edges.items():
        if None not in (floor(a), floor(b)) and floor(a) != floor(b):
            matrix[(floor(a), floor(b))] += n
    print("\nImport statements from floor (row) to floor (column); above the diagonal goes up:\n")
    print("| from \\ to | " + " | ".join(f"{f} {FLOOR_NAMES[f]}" for f in FLOOR_NAMES) + " |")
    print("|---|" + "---:|" * len(FLOOR_NAMES))
    for f in FLOOR_NAMES:
        print(f"| {f} {FLOOR_NAMES[f]} | " + " | ".join(str(matrix[(f, g)]) if f != g else "·" for g in FLOOR_NAMES)
              + " |")
    print(f"Engine packages imported above floor 1 outside the registry (around it): {sum(around.values())}"
          + "".join(f"\n  {a} → {b}: {n}" for (a, b), n in sorted(around.items())))
    into_campaign = {k: n for k, n in floor_edges.items() if k[1] == "validate.tools.campaign" and k[0] not in ("validate.cli", "validate.tools.campaign")}
    print(f"campaign imported from elsewhere than the command line: {sum(into_campaign.values())}"
          + "".join(f"\n  {a} → {b}: {n}" for (a, b), n in sorted(into_campaign.items())))
    print("\nLines of Python per folder and per floor:\n")
    print("| folder | lines |")
    print("|---|---:|")
    for name, n in sorted(lines.items()):
        print(f"| {name} | {n} |")
    by_floor = Counter()
    for name, n in floor_lines.items():
        by_floor[floor(name)] += n
    print("\n| floor | lines |")
    print("|---|---:|")
    for f, n in sorted(by_floor.items(), key=lambda kv: (kv[0] is None, kv[0] or 0)):
        print(f"| {'-' if f is None else f'{f} {FLOOR_NAMES[f]}'} | {n} |")
    return {"edges": edges, "up": up, "lines": lines, "by_floor": by_floor}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("root", nargs="?", default=str(HERE))
    p.add_argument("--before", help="an older checkout to count the same way")
    a = p.parse_args(argv)
    if a.before:
        report(Path(a.before).resolve(), "before")
    report(Path(a.root).resolve(), "now")


if __name__ == "__main__":
    main()
