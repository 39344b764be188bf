"""The one error type for bad input, so the CLI can turn it into exit code 2."""
import importlib
import os
import reprlib


class InputError(ValueError):
    """Bad input from a user: names the field, the value and what is allowed."""


#: how a value is shown in an error's one line: a list or table of any length as its first
#: items and "...", a long string as its ends (a grid of a million numbers was a 7.9 MB line)
_SHOWN = reprlib.Repr()
_SHOWN.maxlist = _SHOWN.maxtuple = _SHOWN.maxdict = _SHOWN.maxset = 6
_SHOWN.maxstring = _SHOWN.maxother = 400  # a file's path whole
_SHOWN.maxlevel = 3


def shown(value) -> str:
    """`value` as an error's one line shows it: its repr, bounded (reprlib)."""
    return _SHOWN.repr(value)


def require(condition: bool, field: str, value, allowed: str) -> None:
    """Raise InputError("field = value: must be allowed") unless condition holds."""
    if not condition:
        raise InputError(f"{field} = {value!r}: must be {allowed}")


def real_number(field: str, value, allowed: str = "a number") -> float:
    """`value` as a float where it is a real number: an int, a float, NumPy's scalars and 0-d
    arrays, a Fraction, a Decimal, a number's text ('1e-8', as a file or an option gives it).
    A bool is refused (True is not the number 1 a user meant), as are None, a sequence and
    other text: one line naming `field` and `allowed`, never a TypeError from deeper down."""
    if (isinstance(value, bool) or value is None or getattr(value, "dtype", None) == bool
            or getattr(value, "ndim", 0) != 0):  # an array of one value: float() would take it, warning
        raise InputError(f"{field} = {value!r}: must be {allowed}")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"{field} = {value!r}: must be {allowed}") from None


def python_number(field: str, value, allowed: str = "a number") -> float:
    """A number given from Python as its float (real_number: NumPy's scalars, a Fraction); text
    refused too, which the command line's and files' readers take as a number's spelling but a
    keyword given '2' or b'2' meant otherwise (a period of 2 s)."""
    if isinstance(value, (str, bytes)):
        raise InputError(f"{field} = {value!r}: must be {allowed}")
    return real_number(field, value, allowed)


def require_positive_finite(field: str, value) -> float:
    x = real_number(field, value, "a positive finite number")
    require(x > 0 and x < float("inf"), field, value, "a positive finite number")
    return x


def require_nonnegative_finite(field: str, value) -> float:
    x = real_number(field, value, "a non-negative finite number")
    require(x >= 0 and x < float("inf"), field, value, "a non-negative finite number")
    return x


def import_extra(module: str, extra: str, needed_for: str):
    """`module`, imported; where it is not installed, an InputError (exit 2, one line)
    naming the optional extra that brings it: the light install (`pip install -e .`)
    leaves out what only one command needs, and that command says so instead of a
    traceback."""
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as e:
        if e.name is None or module.split(".")[0] != e.name.split(".")[0]:
            raise  # a module the package itself imports is missing: not a missing extra
        raise InputError(f"{needed_for} needs the package {e.name!r}, not installed: "
                         f"pip install 'isorock[{extra}]' (or, in a checkout, pip install -e '.[{extra}]')") from None


def path_value(key: str, value, *, optional: bool = True):
    """A path given from Python: a str or an os.PathLike (a number would name a folder '123',
    None a campaign file 'None'); None where `optional`."""
    if value is None and optional:
        return None
    if isinstance(value, (str, os.PathLike)) and str(value).strip():
        return value
    raise InputError(f"{key} = {value!r}: must be a path (a str or a pathlib.Path)")
