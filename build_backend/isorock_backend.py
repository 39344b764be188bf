"""isorock's build backend: setuptools' own, and, for an editable install (the README's
`pip install -e .`), the compiled analytic kernels built into the checkout before pip ends
(analytic/kernel_build.py; issue 34: a first run, design or sweep that waits for no build).

Why here: pip runs no code of a package after installing it, and an editable install's
kernels live in the checkout (analytic/__pycache__), where this backend runs. It builds with
the numba, NumPy and SciPy of pip's build environment (pyproject.toml's build-system
requirements, the project's own bounds): the compiled modules are stamped with those
versions, so where pip resolved others for the install they are simply not loaded, and a
first run builds its kernel as it would have. A failed or stopped build never fails the
install. ISOROCK_BUILD_KERNELS=0 (or no, false, off) skips it. A wheel (`pip install .`) carries no kernels: its
first run builds them (or `python -m isorock.analytic.kernel_build`).
"""
import os
import sys

from setuptools import build_meta as _setuptools
from setuptools.build_meta import *  # noqa: F401,F403 - every PEP 517/660 hook, as setuptools has them

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: ISOROCK_BUILD_KERNELS values that skip the build (any other builds)
SKIP = ("0", "no", "false", "off")

#: run first in each build process: the checkout's analytic/ importable as isorock.analytic, as
#: the install maps it (the kernels' caches are named after their modules), without the rest of
#: the project, whose dependencies pip's build environment lacks
PREAMBLE = f"""
import importlib.util, os, sys, types
root = {ROOT!r}
top = types.ModuleType("isorock")
top.__path__ = []
sys.modules["isorock"] = top
spec = importlib.util.spec_from_file_location("isorock.analytic", os.path.join(root, "analytic", "__init__.py"),
                                              submodule_search_locations=[os.path.join(root, "analytic")])
module = importlib.util.module_from_spec(spec)
sys.modules["isorock.analytic"] = module
spec.loader.exec_module(module)
"""


def build_kernels() -> bool:
    """analytic.kernel_build.build in pip's build environment; False where it was skipped or failed."""
    if os.environ.get("ISOROCK_BUILD_KERNELS", "1").strip().lower() in SKIP:
        return False
    # the checkout's package in place of any other of that name, for this call only
    ours = [name for name in sys.modules if name == "isorock" or name.startswith("isorock.")]
    saved = {name: sys.modules.pop(name) for name in ours}
    try:
        exec(compile(PREAMBLE, "<isorock build preamble>", "exec"), {})
        from isorock.analytic import kernel_build
        return kernel_build.build(preamble=PREAMBLE, python=sys.executable)
    except Exception as e:  # noqa: BLE001 - the install goes on; a first run builds the kernels
        print(f"isorock: the compiled kernels were not built at install ({type(e).__name__}: {e}); "
              "a first run builds them", file=sys.stderr)
        return False
    finally:
        for name in [name for name in sys.modules if name == "isorock" or name.startswith("isorock.")]:
            del sys.modules[name]
        sys.modules.update(saved)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    wheel = _setuptools.build_editable(wheel_directory, config_settings, metadata_directory)
    build_kernels()
    return wheel
