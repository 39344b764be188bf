"""The options of `isorock run` and `isorock validate` as typed values (issue 35): `RunOptions`
and `ValidateOptions`, frozen, declared once here, below the command line.

A field is the command's option by its argparse dest (`base_mass` for --base-mass), with the
option's default, so the readers that read options as attributes (the System, the motion,
the engine settings, the run's plan, the report's config) read either. Two routes build one:

    RunOptions.from_namespace(args)           # the command line: argparse's namespace
    RunOptions.from_keywords("run", kwargs)   # isorock.run(**kwargs): Python values

Both go through the same checks, which take what a notebook passes: a number is any real
number (an int, NumPy's np.float64(0.6), a Fraction, a Decimal; never a bool or a string), a pair or a
triple (solref, solimp) a sequence of numbers, a flag True or False, a list option
(validate's motion and engines, set_settings) a list or one string, a choice one of its
words, a text (a spec, a file: a path-like too) not empty. `--set`'s assignments are checked
by the one schema of engine settings (core.engines.check_settings_table). A value refused is
one InputError line naming the keyword: `height = 'abc': must be a number, not a string`.

Where the command's parser fills a number in (`Default`, io/keys.py) the value keeps it, so
`given()` tells a default from a value given, as it did on the parser's namespace.

The parser (cli/) declares the same options for --help; tests/test_api.py holds its dests and
defaults equal to these fields'.
"""
from __future__ import annotations

import numbers
import os
import tomllib
import warnings
from typing import Annotated, Any, ClassVar

from pydantic import BaseModel, ConfigDict, PlainValidator, ValidationError, create_model

from ...analytic import limits
from ...analytic.engine_protocol import DEFAULT_IMPACT_THRESHOLD
from ...analytic.errors import InputError, python_number
from ...analytic.system import LINEAR, PAPER_BLOCK
from ..core.engines import check_settings_table
from . import keys
from .keys import Default
from .schema import describe

#: validate's report folder when none is given
DEFAULT_OUT = "isorock-report"


# --- the checks of one value (ValueError: the words after "key = value: ") ---------------------


def _scalar(v):
    """A 0-d array (NumPy's) as its item."""
    if getattr(v, "ndim", None) == 0 and hasattr(v, "item"):
        return v.item()
    return v


def _real(v):
    """A number given from Python as its float, by the project's one rule of it
    (analytic.errors.python_number: NumPy's scalars, a Fraction, a Decimal; no text), its
    refusals worded for a keyword."""
    v = _scalar(v)
    if isinstance(v, bool):
        raise ValueError("must be a number (a boolean is not a number)")
    if isinstance(v, str):
        raise ValueError("must be a number, not a string")
    try:
        return python_number("", v)
    except InputError:  # a real number refused is one past a float's range (an int of 400 digits)
        raise ValueError("must be a number within a float's range" if isinstance(v, numbers.Real)
                         else "must be a number") from None


def number(v):
    """A real number as a float (finite or not: the checks that follow say what is allowed);
    a Default kept as it is."""
    if v is None or isinstance(v, Default):
        return v
    return _real(v)


def whole_number(v):
    v = _scalar(v)
    if v is None:
        return v
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise ValueError("must be a whole number")
    return int(v)


def flag(v):
    if not isinstance(v, bool):
        raise ValueError("must be True or False")
    return v


def text(v):
    """A word, a spec or a file's path (a path-like too), not empty."""
    if v is None:
        return v
    if isinstance(v, os.PathLike):
        v = os.fspath(v)
    if not isinstance(v, str):
        raise ValueError("must be a string")
    if not v.strip():
        raise ValueError("an empty value; give one, or leave it out for its default")
    return v


def texts(v):
    """A list option: a list (or tuple) of texts, or one text alone."""
    if v is None:
        return v
    items = [v] if isinstance(v, (str, os.PathLike)) else v
    if not isinstance(items, (list, tuple)):
        raise ValueError("must be a string or a list of strings")
    if not items:
        raise ValueError("must give one or more (leave it out for the defaults)")
    return tuple(text(item) for item in items)


def choice(words):
    def check(v):
        if v is None:
            return v
        if not isinstance(v, str) or v not in words:
            raise ValueError(f"must be one of {', '.join(words)}")
        return v
    return check


def numbers_of(n_min: int, n_max: int):
    """A pair or a triple (solref, solimp): a sequence of n_min to n_max numbers, as a tuple."""
    def check(v):
        if v is None:
            return v
        if isinstance(v, (str, bytes)) or not hasattr(v, "__iter__"):
            raise ValueError(f"must be a sequence of {n_min}–{n_max} numbers, e.g. (0.02, 1)")
        values = tuple(_real(x) for x in v)
        if not n_min <= len(values) <= n_max:
            raise ValueError(f"must have {n_min}–{n_max} numbers")
        return values
    return check


def setting_from_text(text: str) -> tuple[str, str, object]:
    """"[ENGINE.]KEY=VALUE" → (table, key, value), the table "*" where no engine is named, the
    value read as TOML (or else as a word); checked by the one schema of engine settings
    (core.engines.check_settings_table). ValueError, one line naming `text`."""
    target, eq, raw = text.partition("=")
    table, dot, key = target.strip().rpartition(".")
    table, key = (table if dot else "*"), key.strip()
    if not eq or not key or not raw.strip():
        raise ValueError(f"{text!r}: must be KEY=VALUE or ENGINE.KEY=VALUE (e.g. drake.accuracy=1e-5)")
    try:
        value = tomllib.loads(f"v = {raw.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw.strip()  # a word, written without TOML's quotes
    return _setting(table, key, value, text)


def _setting(table, key, value, text) -> tuple[str, str, object]:
    try:
        check_settings_table(table, {key: value})
    except ValueError as e:
        raise ValueError(f"{text!r}: {e}") from None
    return table, key, value


def settings_assigned(v):
    """--set's assignments: each "[ENGINE.]KEY=VALUE" or a (table, key, value) triple (the
    table "*": every engine that has the key), checked; one string alone is one assignment."""
    if v is None:
        return v
    items = [v] if isinstance(v, str) else v
    if not isinstance(items, (list, tuple)):
        raise ValueError("must be a list of \"[ENGINE.]KEY=VALUE\" strings")
    out = []
    for item in items:
        if isinstance(item, str):
            out.append(setting_from_text(item))
        elif isinstance(item, tuple) and len(item) == 3 and all(isinstance(x, str) for x in item[:2]):
            out.append(_setting(*item, item))
        else:
            raise ValueError(f"{item!r}: must be \"[ENGINE.]KEY=VALUE\" (e.g. drake.accuracy=1e-5)")
    return tuple(out)


def _typed(python_type, check):
    return Annotated[python_type, PlainValidator(check)]


Number = _typed(float | None, number)
Whole = _typed(int | None, whole_number)
Flag = _typed(bool, flag)
Text = _typed(str | None, text)
Texts = _typed(tuple[str, ...] | None, texts)
Assignments = _typed(tuple[tuple[str, str, Any], ...] | None, settings_assigned)


def Choice(words):  # noqa: N802 — a type
    return _typed(str | None, choice(tuple(words)))


def _key_field(key: keys.Key, default=None):
    """A declared key's field (io/keys.py), as add_key_option makes its option."""
    if key.kind == keys.BOOL:
        return Flag, False
    if key.kind == keys.CHOICE:
        return Choice(key.choices), default
    return Number, default


# --- the option groups, as cli/options.py's add_* functions make them ------------------------


def system_fields(defaults=None) -> dict:
    """add_system_options: the block's keys default to `defaults` (as Default: not given)."""
    d = {k: Default(v) for k, v in (defaults or {}).items()}
    return {key.name: _key_field(key, d.get(key.name) if key.required else None) for key in keys.SYSTEM.values()}


def isolator_fields(*, in_file: bool = False) -> dict:
    """add_isolator_options: --isolator (linear unless a --config file may give it) and its parameters."""
    return {key.name: _key_field(key, None if in_file or key.name != "isolator" else LINEAR)
            for key in keys.ISOLATOR.values()}


STATUE_FIELDS = {"statue": (Text, None), "statue_example": (Text, None), "unit": (Text, None),
                 "density": (Number, None), "azimuth": (Number, None)}

MOTION_FIELDS = {"motion": (Text, "none"), "format": _key_field(keys.MOTION["format"]),
                 "units": _key_field(keys.MOTION["units"]), "vertical": (Text, None),
                 "vertical_units": (Choice(keys.UNITS), None), "scale": (Number, 1.0),
                 "pga": _key_field(keys.MOTION["pga"]), "pgv": _key_field(keys.MOTION["pgv"])}

TRANSVERSE_FIELDS = {"motion_transverse": (Text, None), "transverse_units": (Choice(keys.UNITS), None),
                     "pair": (Text, None)}

ENGINE_FIELDS = {"timestep": (Number, None), "solref": (_typed(tuple[float, float] | None, numbers_of(2, 2)), None),
                 "solimp": (_typed(tuple[float, ...] | None, numbers_of(3, 5)), None),
                 "cone": (Choice(keys.CONES), None), "integrator": (Choice(keys.INTEGRATORS), None),
                 "friction": (Number, None), "noslip": (Whole, None), "solver_iterations": (Whole, None),
                 "substeps": (Whole, None), "rtol": (Number, None), "atol": (Number, None),
                 "max_step": (Number, None), "rest_velocity": (Number, None), "set_settings": (Assignments, None),
                 "overturn": (Choice(keys.OVERTURN_RULES), None)}


class Options(BaseModel):
    """A command's options, checked: the fields are its argparse dests."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    #: the command, as errors name it (isorock.run's keywords)
    command: ClassVar[str] = ""

    @classmethod
    def from_keywords(cls, name: str, kwargs: dict):
        """The options of keyword arguments (isorock.run(**kwargs)): an unknown keyword named with
        the keywords there are; None is the option's default; a bad value one InputError line
        naming its keyword."""
        for key in kwargs:
            if key not in cls.model_fields:
                raise InputError(f"{key}: not an option of isorock.{name} (its options: "
                                 f"{', '.join(sorted(cls.model_fields))})")
        return cls._checked({k: v for k, v in kwargs.items() if v is not None})

    @classmethod
    def from_namespace(cls, args):
        """The options of the command's parsed arguments (argparse's namespace: its fields
        that are options; the command and its function are not)."""
        return cls._checked({k: v for k, v in vars(args).items() if k in cls.model_fields})

    @classmethod
    def _checked(cls, values: dict):
        try:
            return cls.model_validate(values)
        except ValidationError as e:
            raise describe(e, prefix="") from None


def _options(name: str, doc: str, fields: dict):
    with warnings.catch_warnings():  # run's --json is a field, the deprecated BaseModel.json() is not used
        warnings.filterwarnings("ignore", message='Field name "json"', category=UserWarning)
        return create_model(name, __base__=Options, __module__=__name__, __doc__=doc, **fields)


#: `isorock run`'s options (cli/main.py's parser): one system (the paper's block unless given),
#: one motion, one or more engines, and its outputs
RunOptions = _options("RunOptions", "`isorock run`'s options, checked (isorock.run's keywords).", {
    "engine": (Text, None), **system_fields(PAPER_BLOCK), **STATUE_FIELDS, **isolator_fields(),
    **MOTION_FIELDS, **TRANSVERSE_FIELDS, "duration": (Number, None), "theta0_over_alpha": (Number, 0.0),
    "impact_threshold": (Number, DEFAULT_IMPACT_THRESHOLD), "json": (Text, None), "csv": (Text, None),
    "csv_dt": (Number, None), "plot": (Text, None), "quiet": (Flag, False), **ENGINE_FIELDS,
    "budget": (Number, limits.RUN_BUDGET_S)})

#: `isorock validate`'s options (cli/report.py's parser): the report's motions and engines, an
#: optional system (the paper's otherwise) and --config file
ValidateOptions = _options("ValidateOptions", "`isorock validate`'s options, checked (isorock.report's keywords).", {
    "config": (Text, None), "motion": (Texts, None), "format": _key_field(keys.MOTION["format"]),
    "units": _key_field(keys.MOTION["units"]), "pga": _key_field(keys.MOTION["pga"]),
    "pgv": _key_field(keys.MOTION["pgv"]), "out": (Text, DEFAULT_OUT), "engines": (Texts, None),
    "quick": (Flag, False), "duration": (Number, None), "scales": (Text, None), "workers": (Whole, None),
    "quiet": (Flag, False), **system_fields(), **isolator_fields(in_file=True), **STATUE_FIELDS, **ENGINE_FIELDS,
    **TRANSVERSE_FIELDS})

RunOptions.command = "run"
ValidateOptions.command = "validate"

__all__ = ["RunOptions", "ValidateOptions", "Options", "DEFAULT_OUT", "setting_from_text"]
