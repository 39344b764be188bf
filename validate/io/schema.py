"""What the schemas of the files users write share (`validate --config`, a campaign file):
a TOML number read strictly, so that `true` is never 1.0 and "10" never 10. One home,
for the command line's config schema (cli/config_file.py) and the campaign's
(campaign/schema.py) alike."""
from __future__ import annotations

import math
from typing import Annotated

from pydantic import BeforeValidator


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


__all__ = ["number", "Positive", "NonNegative"]
