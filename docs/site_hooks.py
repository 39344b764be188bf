"""mkdocs hooks for the documentation site (mkdocs.yml): the README becomes the home page,
and the API reference's pages are generated, one per public module, from the docstrings.

Nothing here is typed by hand twice: the home page is the README itself (its links into
docs/ made relative to the site), and a reference page is one mkdocstrings directive."""
import atexit
import re
import shutil
import tempfile
import tomllib
from pathlib import Path

from mkdocs.plugins import event_priority
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parent.parent

#: the modules the reference covers: the notebook API, the model, the registry and measuring
#: core, the campaigns (README, "From Python")
REFERENCE = ("isorock", "isorock.analytic", "isorock.analytic.system", "isorock.analytic.motion", "isorock.analytic.shape",
             "isorock.analytic.trajectory", "isorock.analytic.coefficients", "isorock.validate.core", "isorock.validate.core.engines",
             "isorock.validate.core.measure", "isorock.validate.core.plan", "isorock.validate.core.tolerances",
             "isorock.validate.io.options", "isorock.validate.cli.api",
             "isorock.validate.tools.campaign")

# a link to a file of the repository that is not a page (an example, a script, a folder): the
# site has no copy of it, so it is shown as the path it has in a checkout
_REPOSITORY_LINK = re.compile(r"\[([^\]]*)\]\(((?:\.\./)*)([^)#\s:]+\.(?:py|toml)|[^)#\s:.]+/)\)")


def _import_tree():
    """A folder where the import names stand as folders: isorock/ holding api/'s files, and
    isorock/analytic, isorock/validate, … linked to the folders pyproject's package-dir maps
    them from. Griffe reads the sources statically from there (it cannot follow the mapping),
    so the reference is the code's own text, not what importing it leaves behind."""
    mapping = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-dir"]
    tree = Path(tempfile.mkdtemp(prefix="isorock-griffe-"))
    atexit.register(shutil.rmtree, tree, ignore_errors=True)
    top = tree / "isorock"
    top.mkdir()
    for source in (ROOT / mapping["isorock"]).glob("*.py"):
        (top / source.name).symlink_to(source)
    for name, folder in mapping.items():
        if name.count(".") == 1:  # isorock.X: its subpackages come with its folder
            (top / name.split(".")[1]).symlink_to(ROOT / folder, target_is_directory=True)
    return tree


@event_priority(100)  # before mkdocstrings reads its handlers' options
def on_config(config):
    python = config.plugins["mkdocstrings"].config["handlers"]["python"]
    python["paths"] = [str(_import_tree())]
    # the navigation: every guide in docs/ (a new one joins by being written), then the reference
    guides = sorted(p.name for p in (ROOT / "docs").glob("*.md"))
    config["nav"] = [{"Home": "index.md"}, {"Guides": guides},
                     {"API reference": [f"reference/{module}.md" for module in REFERENCE]}]
    return config


def _home_page():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return text.replace("](docs/", "](")


def _reference_page(module):
    return f"# `{module}`\n\n::: {module}\n"


def on_files(files, config):
    files.append(File.generated(config, "index.md", content=_home_page()))
    for module in REFERENCE:
        files.append(File.generated(config, f"reference/{module}.md", content=_reference_page(module)))
    return files


def on_page_markdown(markdown, page, config, files):
    def in_checkout(link):
        path = link.group(3) if link.group(2) else f"docs/{link.group(3)}"
        return f"{link.group(1)} (`{path}`)"
    return _REPOSITORY_LINK.sub(in_checkout, markdown)
