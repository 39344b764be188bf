"""The `isorock atlas` command: options, the engines asked for, the atlas written as one folder."""
from __future__ import annotations

import math

from ...analytic.errors import InputError
from ...analytic.limits import check_workers
from ..io.inputs import engine_labels
from ..core.engines import get_engine
from ..io.output import check_folder
from ..io.progress import Progress
from ..tools import atlas as tool
from ..tools.atlas import (AXES, FULL, QUICK, QUICK_HEIGHTS, QUICK_MASS_RATIOS, QUICK_SLENDERNESS,
                           RUN_BUDGET, build, default_engines, user_grid, verdict_lines, write)

DEFAULT_OUT = "isorock-atlas"


def add_parser(sub) -> None:
    p = sub.add_parser("atlas", help="the contact-model atlas: β and t₁ error of every preset over λ × μ × size, "
                                     "with its cost",
                       description=tool.__doc__.split("\n\n")[0])
    p.add_argument("--engines", nargs="+", metavar="ENGINE[:PRESET]",
                   help="engines or presets, space- or comma-separated; ENGINE alone is every preset of it "
                        "(default: every preset of mujoco and bullet; drake is slow, name it, e.g. drake:tamsi)")
    p.add_argument("--quick", action="store_true",
                   help=f"a small grid ({len(QUICK.cells())} cells: λ {', '.join(map(str, QUICK_SLENDERNESS))}, "
                        f"μ {', '.join(map(str, QUICK_MASS_RATIOS))}, H {', '.join(map(str, QUICK_HEIGHTS))} m) "
                        f"instead of the full {len(FULL.cells())}")
    for option, (name, (lo, hi), meaning, _) in AXES.items():
        default = ", ".join("none" if x is None else f"{x:g}" for x in getattr(FULL, option))
        p.add_argument("--" + option.replace("_", "-"), metavar="X,Y,…",
                       help=f"your grid's {option.replace('_', ' ')}, {meaning}, comma-separated, {lo:g} to {hi:g}"
                            + (" or 0" if option == "mass_ratios" else "")
                            + f" (default: {default}, or the quick grid's with --quick)")
    p.add_argument("--out", default=DEFAULT_OUT, metavar="DIR",
                   help="folder for atlas.md, atlas.csv, atlas.json and the figures: new, empty or an earlier "
                        "isorock output (default: %(default)s)")
    p.add_argument("--workers", type=int, metavar="N",
                   help="worker processes for the runs (default: 2, or the cores there are)")
    p.add_argument("--run-budget", type=float, default=RUN_BUDGET, metavar="S",
                   help="CPU seconds one run may take before it stops and counts as 'too slow' (CPU, not "
                        "wall: other jobs on the machine do not count against it; default: %(default)g)")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=cmd_atlas)


def expand(items) -> list[str]:
    """--engines → labels: ENGINE:PRESET as given, ENGINE alone as every preset of it;
    an unknown engine or preset is an InputError before any work (run_cli.engine_labels)."""
    out = []
    for label in engine_labels(items):
        name, _, preset = label.partition(":")
        if preset:
            out.append(label)
            continue
        try:
            out += [f"{name}:{p}" for p in get_engine(name).spec.presets]
        except ImportError:
            out.append(label)  # reported as not run
    return list(dict.fromkeys(out))


def cmd_atlas(a) -> int:
    engines = expand(a.engines) if a.engines else default_engines()
    if a.workers is not None:
        check_workers("workers", a.workers)
    if not (a.run_budget > 0 and math.isfinite(a.run_budget)):
        raise InputError(f"run-budget = {a.run_budget!r}: must be a positive number of seconds")
    grid = user_grid(QUICK if a.quick else FULL, slenderness=a.slenderness, mass_ratios=a.mass_ratios,
                     heights=a.heights, frictions=a.frictions)
    check_folder(a.out)  # a folder we may not write is refused before the runs, not after
    bars = []

    def progress(total):
        bars.append(Progress(total, "atlas", enabled=False if a.quiet else None))
        return bars[-1]
    atlas = build(engines, grid, workers=a.workers, budget=a.run_budget, progress=progress)
    for bar in bars:
        bar.close()
    write(atlas, a.out, quick=a.quick)
    print(f"atlas: {len(atlas['rows'])} runs ({len(atlas['presets'])} presets × {len(grid.cells())} cells) in "
          f"{atlas['wall_s']:.0f} s; wrote {a.out}/atlas.md, atlas.csv, atlas.json and the figures")
    print("\n".join(verdict_lines(atlas)))
    return 0
