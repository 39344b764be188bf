"""A design as a Python value (`isorock.design`): the keyword arguments checked, the design run
(design.py), and its answer (`Answer`), whose rows and files are the report's (design_report.py).
Above both, so that neither imports the other's caller."""
from __future__ import annotations

import numbers
from dataclasses import dataclass

from ....analytic.errors import InputError, import_extra, path_value, python_number
from ....analytic.limits import check_workers
from ....analytic.motion import GroundMotion
from ....analytic.system import LINEAR, PAPER_BLOCK
from ...io.output import Outputs
from .design import (DEFAULT_GRIDS, DEFAULT_LEVELS, DEFAULT_TAIL, FAMILIES, Design, Hazard, Statue, check_axis,
                     check_decision, check_engines_carry, check_family_runs, check_points, check_size, check_with,
                     contact_engines, even_grid, numbers_of, run_design, verdict)
from .design_report import isolator_rows, write_design
from .records import load_suite, suite_spec


@dataclass
class Answer:
    """A design's answer as a value: the runs (`design`), the verdict (`verdict`, as
    design.json's `answer`), one row per base (`rows`, as design.csv's)."""

    design: Design
    target: float
    max_stroke: float | None
    verdict: dict

    @property
    def headline(self) -> str:
        return self.verdict["headline"]

    def rows(self) -> list[dict]:
        return isolator_rows(self.design, self.target, self.max_stroke)

    def to_dataframe(self):
        """The rows as a pandas DataFrame (the notebook extra), the values at the highest level as columns."""
        pd = import_extra("pandas", "notebook", "Answer.to_dataframe")
        top = self.design.hazard.levels[-1]
        return pd.DataFrame([{**{k: v for k, v in r.items() if not isinstance(v, list)},
                              "p_hazard_low": r["p_hazard_interval"][0], "p_hazard_high": r["p_hazard_interval"][1],
                              f"p_at_{top:g}g": r["p_levels"][-1], f"stroke_median_at_{top:g}g_m": r["stroke_median"][-1],
                              f"stroke_84_at_{top:g}g_m": r["stroke_84"][-1]} for r in self.rows()])

    def write(self, out) -> None:
        """design.md, design.png, design.json, design.csv and runs.parquet into `out` (a new or
        empty folder, or an earlier isorock output), all or none (validate.io.output)."""

        out = path_value("out", out, optional=False)
        with Outputs() as outputs:
            folder = outputs.folder("out", out)
            folder.write(lambda tmp: write_design(self.design, self.target, self.max_stroke, tmp))
            outputs.commit()


def design(*, height: float | None = None, width: float | None = None, mass: float | None = None,
           base_mass: float | None = None, friction: float | None = None, plinth_margin: float | None = None,
           isolator: str = LINEAR, x=None, y=None, records="fema-p695", units: str | None = None,
           pga=None, level_weights=(), target: float = 0.05, max_stroke: float | None = None, check=(),
           check_runs: int = 12, tail: float = DEFAULT_TAIL, threads: int | None = None,
           out=None) -> Answer:
    """`isorock design` from Python: which isolator keeps my statue standing at my site?

    The statue: height, width, mass, base_mass (m, kg; none of them: the paper's block),
    friction (μ_s on its plinth) and plinth_margin (m). The family: `isolator` (linear,
    friction-pendulum, ball-in-cone, ball-in-bowl) with its two axes `x` and `y` (sequences;
    the linear one's periods (s) and damping ratios, and so on: DEFAULT_GRIDS when left out).
    The hazard: `records` (a dict name → GroundMotion, a folder of record files with their
    `units` where they do not state them, or 'fema-p695'), scaled to the PGA levels `pga` (g;
    default 0.1–1 in 10), weighted by `level_weights`. The decision: `target`, `max_stroke`,
    and `check`, contact engines that rerun `check_runs` of the runs. `out`: a folder to
    write the files `isorock design --out` writes. Every value is checked by the rules the
    command's options follow (an InputError naming the keyword)."""
    out = path_value("out", out)  # a number would name a folder '123'
    # every number as its float, once, here: Python values are not the command line's floats
    # (np.float32(0.05) was refused as a target, True taken as 1, 'x' a TypeError further down)
    target, tail = python_number("target", target), python_number("tail", tail)
    max_stroke, friction, plinth_margin = (None if v is None else python_number(k, v) for k, v in (
        ("max_stroke", max_stroke), ("friction", friction), ("plinth_margin", plinth_margin)))
    check_runs = _whole_of("check_runs", check_runs)
    if threads is not None:
        threads = check_workers("threads", _whole_of("threads", threads))
    check_decision(target, max_stroke, tail, check_runs)
    if isinstance(check, str):
        check = [check]
    elif not isinstance(check, (list, tuple)):
        raise InputError(f"check = {check!r}: must be an engine's name or a list of them")
    engines = contact_engines(check)  # before any record is read
    if not isinstance(isolator, str) or isolator not in FAMILIES:
        raise InputError(f"isolator = {isolator!r}: must be one of {', '.join(FAMILIES)}")
    given = {k: python_number(k, v) for k, v in dict(height=height, width=width, mass=mass, base_mass=base_mass).items()
             if v is not None}
    if given and len(given) < 4:
        missing = [k for k in ("height", "width", "mass", "base_mass") if k not in given]
        raise InputError(f"{missing[0]}: give the statue's height, width, mass and base_mass, or none of them for the "
                         "paper's block")
    statue = Statue(**{k: float(v) for k, v in (given or PAPER_BLOCK).items()}, friction=friction,
                    plinth_margin=plinth_margin)
    (x_name, x_grid), (y_name, y_grid) = DEFAULT_GRIDS[isolator]
    family = FAMILIES[isolator](check_axis("x", x if x is not None else even_grid(*x_grid)),
                                check_axis("y", y if y is not None else even_grid(*y_grid),
                                           below_one=isolator == LINEAR))
    check_family_runs(family)
    levels = check_axis("pga", pga if pga is not None else even_grid(*DEFAULT_LEVELS))
    hazard = Hazard(_records(records, units), levels, numbers_of("level_weights", level_weights),
                    records if isinstance(records, str) else "")
    check_size(family, hazard, tail)
    check_engines_carry(statue, family, hazard, engines, tail, named=str)
    d = run_design(statue, family, hazard, tail=tail, threads=threads)
    if engines:
        picks = check_points(d, target, max_stroke, check_runs)
        d.checks = [check_with(d, engine, picks) for engine in engines]
        d.check = d.checks[0]
    answer = Answer(d, target, max_stroke, verdict(d, target, max_stroke))
    if out is not None:
        answer.write(out)
    return answer


def _whole_of(name: str, value) -> int:
    """A keyword's whole number as an int (NumPy's integers too); a bool, a float or text is one
    line naming it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(f"{name} = {value!r}: must be a whole number")
    return int(value)


def _records(records, units) -> dict:
    """The hazard's records: a dict name → GroundMotion as given, or a suite or folder read."""
    if isinstance(records, dict):
        for name, r in records.items():
            if not (isinstance(name, str) and name.strip()):  # a name the table's string column holds
                raise InputError(f"records: the key {name!r} must be the record's name (a non-empty str)")
            if not isinstance(r, GroundMotion):
                raise InputError(f"records[{name!r}] = {type(r).__name__}: must be a GroundMotion")
            if r.pulse is not None or r.vertical is not None:
                raise InputError(f"records[{name!r}] = {r.name or 'a motion'}: must be a sampled horizontal record "
                                 "(GroundMotion.from_array, or a record file), not a pulse or a motion with a "
                                 "vertical component")
        return dict(records)
    return load_suite(suite_spec(records, units=units,
                                 allowed="a dict of GroundMotions, 'fema-p695' or a folder of record files")[0])
