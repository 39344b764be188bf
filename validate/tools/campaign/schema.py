"""The campaign file's schema (pydantic), checked before spec.py expands it.

Strict types and no silent reinterpretation: a number is a TOML number (not a boolean,
not a string, not an integer beyond a float's range), a list holds no duplicates (they
ran cases twice), an isolator's keys need `base = "isolated"` (without it they were
dropped and a fixed base ran), `folder = ""` is not the campaign's own folder, a
setting's value has the type of the engine's setting (`rtol = "1e-8"` is refused), and
an unknown key anywhere is an error. Each error is one InputError naming the key the
user wrote, the value and what is allowed:

    systems.period[1] = -1.5: must be a positive number

`check_campaign(data)` raises or returns None; spec.parse_spec then builds the spec
from the same data (its own checks of ranges and sizes stay there).
"""
from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import (BaseModel, BeforeValidator, ConfigDict, Field, StrictBool, StrictInt, StrictStr, ValidationError,
                      model_validator)

from ....analytic.errors import InputError, shown
from ...core.engines import ALL_ENGINES, check_settings_table
from ...io import keys
from ...io.schema import NonNegative, Positive, number as _number

#: the block-to-base mass ratio μ = m/m_b a campaign may ask for: μ = 1e-300 made a
#: base of 1e303 kg whose derived stiffness overflowed (the error named `stiffness =
#: inf`, a key nobody wrote); a millionth to a million spans every isolated statue
MASS_RATIO_RANGE = (1e-6, 1e6)


def _grid(*, zero: bool = False):
    """A number, a non-empty list of distinct numbers, or a range {from, to, num[, log]}."""
    def check(v):
        if isinstance(v, dict):
            unknown = set(v) - {"from", "to", "num", "log"}
            if unknown:
                raise ValueError(f"a range has from, to, num and log (not {sorted(unknown)[0]})")
            for k in ("from", "to"):
                if k in v:
                    try:
                        _number(v[k], positive=not zero)
                    except ValueError as e:
                        raise ValueError(f"{k}: {e}") from None
            if "num" in v and (isinstance(v["num"], bool) or not isinstance(v["num"], int)):
                raise ValueError(f"num = {shown(v['num'])}: must be a whole number")
            if "log" in v and not isinstance(v["log"], bool):
                raise ValueError(f"log = {shown(v['log'])}: must be true or false")
            return v
        if isinstance(v, list):
            if not v:
                raise ValueError("must be a number, a non-empty list or a range {from, to, num}")
            xs = []
            for i, x in enumerate(v):
                try:
                    xs.append(_number(x, positive=not zero))
                except ValueError as e:
                    raise ValueError(f"item {i} ({shown(x)}) {e}") from None
            if len(set(xs)) != len(xs):
                dup = next(x for x in xs if xs.count(x) > 1)
                raise ValueError(f"lists {dup:g} twice (each value once: a repeat runs its cases twice)")
            return v
        _number(v, positive=not zero)
        return v
    return BeforeValidator(check)


def _words(allowed):
    """A word of `allowed`, or a non-empty list of distinct ones."""
    def check(v):
        items = v if isinstance(v, list) else [v]
        if not items:
            raise ValueError(f"must be one or more of {', '.join(allowed)}")
        for x in items:
            if not isinstance(x, str) or x not in allowed:
                raise ValueError(f"must be one of {', '.join(allowed)} (or a list of them), not {shown(x)}")
        if len(set(items)) != len(items):
            raise ValueError("lists a value twice (each once: a repeat runs its cases twice)")
        return v
    return BeforeValidator(check)


Grid = Annotated[Any, _grid()]
GridZero = Annotated[Any, _grid(zero=True)]


def _axis(name: str):
    """The check of a grid axis that is a System key (io/keys.py): each of its values as the
    key's kind, as a --config file's [system] table checks its one value (0 only where the key
    may be 0)."""
    return _grid(zero={keys.POSITIVE: False, keys.NON_NEGATIVE: True}[keys.SYSTEM[name].kind])


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, populate_by_name=True)


class Head(_Strict):
    name: StrictStr | None = None
    analytic_chunk: StrictInt | None = Field(None, ge=1, le=100_000)
    contact_chunk: StrictInt | None = Field(None, ge=1, le=100_000)


ISOLATOR_KEYS = ("mass_ratio", "base_mass", "period", "damping_ratio")


class Statue(_Strict):
    """A statue's own mesh instead of the block H × B (docs/statues.md): its file (relative to
    the campaign file) in its length unit, or an example made by code; its density instead of
    systems.mass."""
    mesh: StrictStr | None = None
    example: StrictStr | None = None
    unit: StrictStr | None = None
    density: Positive | None = None


class Systems(_Strict):
    #: a statue's own mesh (docs/statues.md), and the directions it is shaken along (degrees)
    statue: Statue | None = None
    azimuth: GridZero = None
    slenderness: Grid = None
    alpha: Grid = None
    size: Grid = None
    # the axes that are System keys (io/keys.py) are checked as the declaration says; the others
    # (slenderness, alpha, size, mass_ratio, base) are the campaign's own ways to span a grid
    height: Annotated[Any, _axis("height")] = None
    width: Annotated[Any, _axis("width")] = None
    mass: Annotated[Any, _axis("mass")] = None
    base: Annotated[Any, _words(("fixed", "isolated"))] = None
    mass_ratio: Grid = None
    #: the base's mass, kg: instead of mass_ratio, for one who knows the plinth (μ = mass/base_mass)
    base_mass: Annotated[Any, _axis("base_mass")] = None
    period: Annotated[Any, _axis("period")] = None
    damping_ratio: Annotated[Any, _axis("damping_ratio")] = None
    #: the statue's friction on its base, μ_s (docs/sliding.md): an axis of its own; absent: no slip
    friction: Annotated[Any, _axis("statue_friction")] = None

    @model_validator(mode="after")
    def _a_statue_is_its_own_shape(self):
        if self.statue is None:
            if self.azimuth is not None:
                raise ValueError("azimuth: the direction a statue's mesh is shaken along; give systems.statue")
            return self
        for k in ("height", "width", "slenderness", "alpha", "size"):
            if getattr(self, k) is not None:
                raise ValueError(f"{k}: the statue's mesh gives its shape; leave {k} out")
        if self.friction is not None:
            raise ValueError("friction: the sliding model takes the block H × B, not a statue's mesh yet")
        if self.statue.density is not None and self.mass is not None:
            raise ValueError("mass: the statue's statue.density gives its mass; give one of the two")
        return self

    @model_validator(mode="after")
    def _isolator_needs_its_base(self):
        given = [k for k in ISOLATOR_KEYS if getattr(self, k) is not None]
        if given and self.base is None:  # the default base is fixed: the isolator would be dropped unsaid
            raise ValueError(f"base: missing, and {given[0]} describes an isolator: give base = \"isolated\" "
                             "(or [\"fixed\", \"isolated\"], or \"fixed\" to run without it)")
        if self.mass_ratio is not None and self.base_mass is not None:
            raise ValueError("mass_ratio and base_mass: give one of them, not both (base_mass in kg, or "
                             "mass_ratio = mass/base_mass)")
        if self.mass_ratio is not None:
            values = (self.mass_ratio if isinstance(self.mass_ratio, list)
                      else [self.mass_ratio.get("from"), self.mass_ratio.get("to")] if isinstance(self.mass_ratio, dict)
                      else [self.mass_ratio])
            lo, hi = MASS_RATIO_RANGE
            for x in values:
                if x is not None and not lo <= float(x) <= hi:
                    raise ValueError(f"mass_ratio = {shown(x)}: must be from {lo:g} to {hi:g} (m/m_b, "
                                     "MASS_RATIO_RANGE)")
        return self


class Motions(_Strict):
    type: Literal["pulse", "records"]
    pulse: Annotated[Any, _words(("sine", "cosine", "ricker"))] = None
    frequency_ratio: Grid = None
    amplitude_ratio: Grid = None
    cycles: Positive | None = None
    suite: Literal["fema-p695"] | None = None
    folder: StrictStr | None = Field(None, min_length=1)
    units: Literal[keys.UNITS] | None = None
    scale_by: Literal["pga", "pgv"] | None = None
    levels: Grid = None
    limit: StrictInt | None = Field(None, ge=0)

    @model_validator(mode="after")
    def _keys_of_its_type(self):
        mine = ({"pulse", "frequency_ratio", "amplitude_ratio", "cycles"} if self.type == "pulse"
                else {"suite", "folder", "units", "scale_by", "levels", "limit"})
        for k in self.model_fields_set - {"type"} - mine:
            raise ValueError(f"{k} is not a key of type = {self.type!r} motions (allowed: {', '.join(sorted(mine))})")
        if self.type == "records" and self.folder is not None and not self.folder.strip():
            raise ValueError("folder must name a folder")
        return self


def _settings_table(engine: str, table: dict) -> None:
    """Each value has the type of the engine's setting (core.engines.check_settings_table, the
    one schema the config file and the command line's --set share); an unknown engine or
    setting is named later by spec.py, with the engines and settings there are."""
    if engine.partition(":")[0] in ALL_ENGINES:
        check_settings_table(engine, table, unknown_keys=False)


class Engine(_Strict):
    name: StrictStr
    settings: dict[str, Any] | list[dict[str, Any]] | None = None

    @model_validator(mode="after")
    def _typed_settings(self):
        tables = self.settings if isinstance(self.settings, list) else [self.settings or {}]
        if isinstance(self.settings, list) and not self.settings:
            raise ValueError("settings = []: must be a table or a non-empty list of tables")
        for table in tables:
            _settings_table(self.name, table)
        return self


class Duration(_Strict):
    tail: NonNegative | None = None
    end: Positive | None = None


class Agreement(_Strict):
    x: StrictStr | None = None
    y: StrictStr | None = None


class Products(_Strict):
    agreement: Agreement | None = None
    spectrum: StrictBool | None = None
    fragility: StrictBool | None = None


class CampaignFile(_Strict):
    campaign: Head | None = None
    systems: Systems
    motions: Motions
    engines: list[Engine] = Field(min_length=1)
    duration: Duration | None = None
    products: Products | None = None


def _key(loc) -> str:
    out = ""
    for p in loc:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out


def _value_at(data, loc):
    for p in loc:
        try:
            data = data[p]
        except (KeyError, IndexError, TypeError):
            return None
    return data


def check_campaign(data: dict) -> None:
    """Raise InputError (one line: key, value, what is allowed) if the parsed TOML is not
    a campaign file."""
    try:
        CampaignFile.model_validate(data)
    except ValidationError as e:
        err = e.errors(include_url=False)[0]
        # a union's members each report; the loc then ends in the member's type name
        loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and ("[" in p or p in ("list", "dict"))))
        key, kind = _key(loc), err["type"]
        msg = err["msg"].removeprefix("Value error, ")
        value = _value_at(data, loc)
        if kind == "extra_forbidden":
            raise InputError(f"{key}: unknown key") from None
        if kind == "missing":
            raise InputError(f"{key}: missing (see docs/campaigns.md)") from None
        if kind in ("model_type", "dict_type", "model_attributes_type"):
            raise InputError(f"{key} = {shown(value)}: must be a table") from None
        if kind in ("list_type",):
            raise InputError(f"{key} = {shown(value)}: must be a list of tables ([[{key}]])") from None
        if kind == "too_short":
            raise InputError(f"{key}: must have one or more entries") from None
        msg = msg.replace("Input should be", "must be")
        if value is None or (isinstance(value, dict) and kind == "value_error"):
            raise InputError(f"{key}: {msg}") from None
        raise InputError(f"{key} = {shown(value)}: {msg}") from None
