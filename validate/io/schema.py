"""What the schemas of the files users write share (`validate --config`, `design --config`,
a campaign file): the file read and bounded before a parser sees it (`read_toml`), and a
TOML number read strictly, so that `true` is never 1.0 and "10" never 10. One home, for
the config schema of `isorock validate` and `isorock.report` (io/config_file.py) and the campaign's
(campaign/schema.py) alike."""
from __future__ import annotations

import math
import re
import tomllib
from typing import Annotated, Literal

from pydantic import BeforeValidator, StrictBool, ValidationError

from ...analytic.errors import InputError, shown
from . import keys

# --- the file, bounded before it is parsed ---------------------------------------------------
# tomllib is recursive and trusts its input: 100,000 nested arrays are a RecursionError, a
# 5,000-digit integer a ValueError past Python's int-to-string limit, and a dotted key of
# 50,000 parts took it 366 s (its walk is quadratic in the parts). A config or campaign file
# is a page of keys: these bounds are far above any and far below any harm.

#: largest file (bytes): a campaign with every grid written out is a few kB
MAX_TOML_BYTES = 1 << 20
#: deepest nesting of arrays and tables (a campaign engine's settings: 3)
MAX_TOML_DEPTH = 32
#: most parts of one dotted key or table header (`[settings."mujoco:fast"]`: 2)
MAX_KEY_PARTS = 64
#: longest number or bare key, in characters (a float's exponent ends at 308; the schemas
#: refuse an integer past a float's range, and could not even print one past 4,300 digits)
MAX_TOML_WORD = 1000

# what the scan sees of a TOML file: strings and comments whole (the brackets, dots and digits
# inside them are text), then the brackets, dots, separators and words between them
_TOML_TOKENS = re.compile(r'''
      (?P<string> """(?:[^\\]|\\.)*?""" | \'\'\'.*?\'\'\' | "(?:[^"\\\n]|\\.)*" | '[^'\n]*' )
    | (?P<comment> \#[^\n]* )
    | (?P<open> [\[{] )
    | (?P<close> [\]}] )
    | (?P<dot> \. )
    | (?P<end> [=,\n] )
    | (?P<word> [A-Za-z0-9_-]+ )
''', re.VERBOSE | re.DOTALL)


def _check_toml_shape(text: str, where: str) -> None:
    """One line naming the first bound `text` passes: nesting, a key's parts, a word's length."""
    depth = parts = 0
    for m in _TOML_TOKENS.finditer(text):
        kind = m.lastgroup
        if kind == "open":
            depth, parts = depth + 1, 0
            if depth > MAX_TOML_DEPTH:
                raise InputError(f"{where}: line {_line(text, m)}: arrays and tables nested more than "
                                 f"{MAX_TOML_DEPTH} deep; must be at most {MAX_TOML_DEPTH} (MAX_TOML_DEPTH)")
        elif kind == "close":
            depth, parts = max(depth - 1, 0), 0
        elif kind == "dot":
            parts += 1  # a float's point counts too: a number has two parts at most
            if parts >= MAX_KEY_PARTS:
                raise InputError(f"{where}: line {_line(text, m)}: a dotted key of more than {MAX_KEY_PARTS} "
                                 f"parts; must be at most {MAX_KEY_PARTS} (MAX_KEY_PARTS)")
        elif kind == "end":
            parts = 0
        elif kind == "word" and len(m.group()) > MAX_TOML_WORD:
            raise InputError(f"{where}: line {_line(text, m)}: a number of {len(m.group())} digits (or a bare key "
                             f"of as many characters); must be at most {MAX_TOML_WORD} (MAX_TOML_WORD)")


def _line(text: str, m) -> int:
    return text.count("\n", 0, m.start()) + 1


def parse_toml(data: bytes, where: str) -> dict:
    """A TOML file's bytes as a table: UTF-8 (a byte-order mark allowed), within the bounds
    above, valid TOML; otherwise one InputError line starting with `where` (e.g. "config =
    'statue.toml'")."""
    if len(data) > MAX_TOML_BYTES:
        raise InputError(f"{where}: larger than {MAX_TOML_BYTES >> 20} MiB; must be at most {MAX_TOML_BYTES} "
                         "bytes (MAX_TOML_BYTES)")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise InputError(f"{where}: not UTF-8 text (byte {e.start}: {data[e.start:e.start + 1]!r})") from None
    _check_toml_shape(text, where)
    try:
        return tomllib.loads(text)
    except ValueError as e:  # TOMLDecodeError, or any value the parser cannot take
        raise InputError(f"{where}: not valid TOML ({e})") from None


def read_toml(path, where: str) -> dict:
    """The TOML file at `path`, read no further than MAX_TOML_BYTES (a device or a huge file
    is not read whole), through `parse_toml`."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_TOML_BYTES + 1)
    except OSError as e:
        raise InputError(f"{where}: cannot be read ({e.strerror or e})") from None
    return parse_toml(data, where)


# --- numbers ---------------------------------------------------------------------------------


def number(v, *, positive: bool = True):
    """A TOML number (integer or float) as a finite float; booleans, strings and
    integers too large for a float are refused, each with its reason."""
    if isinstance(v, bool):
        raise ValueError("must be a number (a boolean is not a number)")
    if isinstance(v, str):
        raise ValueError("must be a number, not a string (write 10, not \"10\")")
    if not isinstance(v, (int, float)):
        raise ValueError("must be a number")
    try:
        x = float(v)
    except OverflowError:
        raise ValueError("must be a finite number (this integer is beyond a float's range)") from None
    if not math.isfinite(x):
        raise ValueError("must be a finite number")
    if positive and x <= 0:
        raise ValueError("must be a positive number")
    if not positive and x < 0:
        raise ValueError("must be zero or a positive number")
    return x


Positive = Annotated[float, BeforeValidator(number)]
NonNegative = Annotated[float, BeforeValidator(lambda v: number(v, positive=False))]


def field_type(key: keys.Key):
    """The type a file's key of this declaration is read as (io/keys.py), absent allowed."""
    if key.kind == keys.CHOICE:
        return Literal[key.choices] | None
    return {keys.POSITIVE: Positive, keys.NON_NEGATIVE: NonNegative, keys.BOOL: StrictBool}[key.kind] | None


# --- a validation error as one line --------------------------------------------------------


def _where(loc) -> str:
    return ".".join(str(p) for p in loc)


def describe(e: ValidationError, prefix: str = "config key") -> InputError:
    """The first error of a pydantic ValidationError as the project's one line: the key after
    `prefix` ("config key system.height = true: …"; with prefix "" the key alone, as the notebook
    API names its keywords: "height = 'abc': …")."""
    err = e.errors(include_url=False)[0]
    key, value, kind = _where(err["loc"]), err.get("input"), err["type"]
    msg = err["msg"].removeprefix("Value error, ")
    named = f"{prefix} {key}" if prefix else key
    if kind == "extra_forbidden":
        return InputError(f"{named}: not known")
    if kind == "missing":
        return InputError(f"{named}: missing")
    if kind in ("dict_type", "model_type"):
        return InputError(f"{named} = {shown(value)}: must be a table")
    if kind == "literal_error":
        return InputError(f"{named} = {shown(value)}: {msg.replace('Input should be', 'must be')}")
    if kind == "bool_type":
        return InputError(f"{named} = {shown(value)}: must be true or false")
    if key.startswith("settings") and msg.startswith("[settings."):
        return InputError(f"config {msg}")
    return InputError(f"{named} = {shown(value)}: {msg}")

__all__ = ["describe", "number", "Positive", "NonNegative", "field_type", "parse_toml", "read_toml", "MAX_TOML_BYTES",
           "MAX_TOML_DEPTH", "MAX_KEY_PARTS", "MAX_TOML_WORD"]
