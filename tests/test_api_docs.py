"""The API reference (issue 25): HTML pages built from the docstrings by pdoc, as the
README's command builds them. Built here, so that CI builds it on every submission; the
oracle is the docstrings themselves, which the pages must carry."""
import subprocess
import sys

import pytest

from isorock.analytic.system import System

#: the modules the reference covers: the model, the registry and measuring core, the
#: notebook API and the campaigns (README, "From Python")
MODULES = ("isorock", "isorock.analytic", "isorock.analytic.system", "isorock.analytic.motion",
           "isorock.analytic.trajectory", "isorock.analytic.coefficients", "isorock.validate.core",
           "isorock.validate.cli.api", "isorock.campaign")


def test_the_api_reference_builds_from_the_docstrings(tmp_path):
    pytest.importorskip("pdoc")
    done = subprocess.run([sys.executable, "-m", "pdoc", "-o", str(tmp_path), *MODULES],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    pages = {p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.html")}
    for page in ("index.html", "isorock.html", "isorock/analytic/system.html", "isorock/validate/core/engines.html",
                 "isorock/validate/cli/api.html", "isorock/campaign.html"):
        assert page in pages, page
    system = (tmp_path / "isorock/analytic/system.html").read_text()
    # a docstring's own words reach its page (the rocking rate's, whose rule the engines follow)
    first_line = System.rocking_rate.__doc__.split(".")[0].split(":")[0].strip()
    assert "rocking_rate" in system and first_line.split()[0] in system
    api = (tmp_path / "isorock/validate/cli/api.html").read_text()
    assert "to_dataframe" in api and '<span class="name">run</span>' in api  # the entry point, documented
