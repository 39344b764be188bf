"""Not a module: Python never imports this file. The checkout's top-level folders are the
subpackages of `isorock` as pyproject.toml installs them (analytic/ is isorock.analytic,
validate/ isorock.validate, …; api/ is isorock itself), and they import one another by
relative imports (`from ..analytic.system import System`). This file marks the folder that
holds them as their package, so that a reader's tool which resolves imports by path alone
finds the folder each relative import names (docs/floors.md)."""
