"""The documentation site (issue 35): the guides in docs/ and the API reference, built
together by mkdocs as README's command builds it. Built here, so that CI builds it on every
submission, with --strict: a link to a missing page or heading fails it. The oracles are the
sources themselves: README's text, each guide's title, a docstring's own words."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from isorock.analytic.system import System

ROOT = Path(__file__).resolve().parent.parent


def _build(config, out):
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config), "-d", str(out)],
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    pytest.importorskip("mkdocstrings")
    out = tmp_path_factory.mktemp("site")
    done = _build(ROOT / "mkdocs.yml", out)
    assert done.returncode == 0, done.stderr[-3000:]
    return out


def test_the_home_page_is_the_readme(site):
    home = (site / "index.html").read_text()
    readme = (ROOT / "README.md").read_text()
    first_command = next(line for line in readme.splitlines() if line.startswith("python3 -m venv"))
    assert "isorock validate" in first_command and "isorock validate" in home
    # README's links into docs/ lead to the guides' pages
    assert 'href="install/"' in home and 'href="docs/install.md"' not in home


def test_every_guide_has_its_page(site):
    for guide in sorted((ROOT / "docs").glob("*.md")):
        page = site / guide.stem / "index.html"
        assert page.exists(), guide.name
        title = next(line for line in guide.read_text().splitlines() if line.startswith("# "))[2:]
        first_word = title.split()[0].strip("`*")
        assert first_word in page.read_text(), (guide.name, first_word)


def test_the_reference_carries_the_docstrings(site):
    page = (site / "reference" / "isorock.analytic.system" / "index.html").read_text()
    first_line = System.rocking_rate.__doc__.split(".")[0].split(":")[0].strip()
    assert "rocking_rate" in page and first_line.split()[0] in page
    api = (site / "reference" / "isorock.validate.cli.api" / "index.html").read_text()
    assert "to_dataframe" in api


def test_a_broken_link_fails_the_build(tmp_path):
    """The site's strictness is live: the same configuration over a copy of the guides with
    one link to a heading that is not there is refused."""
    pytest.importorskip("mkdocstrings")
    for name in ("mkdocs.yml", "README.md", "pyproject.toml"):
        shutil.copy(ROOT / name, tmp_path / name)
    shutil.copytree(ROOT / "docs", tmp_path / "docs", ignore=shutil.ignore_patterns("images", "__pycache__"))
    shutil.copytree(ROOT / "docs" / "images", tmp_path / "docs" / "images", dirs_exist_ok=True)
    for folder in ("api", "analytic", "mujoco_models", "bullet_models", "drake_models", "dart_models", "validate",
                   "campaign", "experiments"):
        (tmp_path / folder).symlink_to(ROOT / folder, target_is_directory=True)
    guide = tmp_path / "docs" / "plugins.md"
    guide.write_text(guide.read_text() + "\nSee [the install](install.md#no-such-heading).\n")
    done = _build(tmp_path / "mkdocs.yml", tmp_path / "site")
    assert done.returncode != 0 and "no-such-heading" in done.stderr
