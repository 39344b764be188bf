"""`isorock validate --config FILE.toml`: the file's schema, checked in full before any run.

A pydantic model (strict types: a TOML `true` is not the number 1, "no" is not a
boolean, a string is not a list of its characters, an empty list is not "the
defaults", an unknown key is not ignored). Every error is one InputError line naming
the key as the user wrote it, the value, and what is allowed:

    config key system.height = true: must be a number (a boolean is not a number)

`read_config(path)` returns the keys the file gives (a dict; absent keys absent), as
`isorock validate` and `isorock.report(config=...)` read them (and `isorock design`), below the
command line (issue 35).
"""
from __future__ import annotations

from pathlib import Path
from typing import Annotated

from pydantic import BaseModel, BeforeValidator, ConfigDict, StrictBool, ValidationError, create_model, field_validator

from ...analytic.errors import InputError
from ..core.engines import check_settings_table
from . import keys
from .schema import Positive, describe, field_type, read_toml  # noqa: F401 — describe: importable from here

#: ξ of an isolator this command runs: below 1 (underdamped), as `isorock sweep` takes
#: it; ξ = 1e6 made the report's search for the uplift scale run for ever (issue 24)
MAX_DAMPING_RATIO = 1.0


def _strings(v):
    if isinstance(v, str):
        raise ValueError("must be a list of strings, e.g. [\"a\", \"b\"] (a string alone would be read as its "
                         "characters)")
    if not isinstance(v, list):
        raise ValueError("must be a list of strings")
    if not v:
        raise ValueError("must list one or more (an empty list is not the defaults: leave the key out for them)")
    for item in v:
        if not isinstance(item, str) or not item.strip():
            raise ValueError(f"must be a list of non-empty strings ({item!r} is not one)")
    return v


Strings = Annotated[list[str], BeforeValidator(_strings)]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)


def _underdamped(cls, v):
    if v is not None and v >= MAX_DAMPING_RATIO:
        raise ValueError(f"must be below {MAX_DAMPING_RATIO:g} (an underdamped isolator)")
    return v


#: the [system] table: the system's and the isolator's keys as io/keys.py declares them (the
#: options' own), each optional, in the declaration's order (the first bad key is the one named)
SystemTable = create_model(
    "SystemTable", __base__=_Strict, __module__=__name__,
    __validators__={"_underdamped": field_validator("damping_ratio")(classmethod(_underdamped))},
    **{key.name: (field_type(key), None) for key in (*keys.SYSTEM.values(), *keys.ISOLATOR.values())})


class StatueTable(_Strict):
    """A statue's mesh instead of the block H × B (as --statue, --statue-example, --unit,
    --density, --azimuth): `mesh` relative to the config file's folder; its mass is
    [system] mass, or `density` here."""
    mesh: str | None = None
    example: str | None = None
    unit: str | None = None
    density: Positive | None = None
    azimuth: float | None = None


class ConfigFile(_Strict):
    system: SystemTable | None = None
    statue: StatueTable | None = None
    engines: Strings | None = None
    motions: Strings | None = None
    settings: dict[str, dict[str, object]] | None = None
    # a record's units and format, and the peak every motion is scaled to: --units, --format,
    # --pga (g) and --pgv (m/s), as io/keys.MOTION declares them
    units: field_type(keys.MOTION["units"]) = None
    format: field_type(keys.MOTION["format"]) = None
    quick: StrictBool | None = None
    duration: Positive | None = None
    pga: field_type(keys.MOTION["pga"]) = None
    pgv: field_type(keys.MOTION["pgv"]) = None

    @field_validator("pgv")
    @classmethod
    def _one_target(cls, v, info):
        if v is not None and info.data.get("pga") is not None:
            raise ValueError("give pga or pgv, not both (pga in g, pgv in m/s)")
        return v

    @field_validator("settings")
    @classmethod
    def _known_settings(cls, tables):
        for table, values in tables.items():
            try:
                check_settings_table(table, values)  # the one schema of engine settings
            except ValueError as e:
                msg = str(e)  # "TABLE: …" (the table itself) or "KEY …" (one of its keys)
                raise ValueError(f"[settings.{table}]{msg[len(table) + 1:]}" if msg.startswith(f"{table}:")
                                 else f"[settings.{table}] {msg}") from None
        return tables


def read_config(path) -> dict:
    """The validated keys of a --config file (only those it gives)."""
    raw = read_toml(path, f"config = {str(path)!r}")  # bounded before it is parsed (issue 34)
    try:
        model = ConfigFile.model_validate(raw)
    except ValidationError as e:
        raise describe(e) from None
    out = model.model_dump(exclude_unset=True)
    if "system" in out:
        out["system"] = {k: v for k, v in out["system"].items()}
    if out.get("statue", {}).get("mesh") is not None:  # a mesh beside the file, wherever it is run from
        out["statue"]["mesh"] = str(Path(path).parent / out["statue"]["mesh"])
    return out


def check_damping_ratio(system) -> None:
    """An isolator the report can run: ξ below MAX_DAMPING_RATIO, whichever way it was given."""
    if system is not None and not system.fixed_base and not system.damping_ratio < MAX_DAMPING_RATIO:
        raise InputError(f"damping-ratio = {system.damping_ratio:.6g}: must be below {MAX_DAMPING_RATIO:g} "
                         "(an underdamped isolator)")
