"""The campaign file (TOML): what to run, checked in full before anything runs.

A campaign is the product systems × motions × (engine, setting). `load_spec(path)`
reads and validates the file and returns a frozen `CampaignSpec`; `spec.cases()`
expands it into `Case`s in a fixed order (the order, and so every case id and chunk
id, depends only on the file's content). The format is documented in
docs/campaigns.md. Every error is an `InputError` naming the key:
`systems.period = -1.0: must be a positive finite number`.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import math
from dataclasses import dataclass, replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ....analytic import shape
from ....analytic.errors import InputError, shown
from ....analytic.limits import check_acceleration, check_duration, check_isolator
from ....analytic.motion import PULSES, UNITS
from ....analytic.system import MAX_STATUE_FRICTION, PlanarBody, System
from ...core.cases import Case, build_case, build_system, pulse_for
from ...core.chunks import ANALYTIC_CHUNK, CONTACT_CHUNK
from ...core.engines import ALL_ENGINES, EngineChoice, check_carries, choose, get_engine
from ...io.schema import read_toml
from .records import SUITES, count_records
from .schema import MASS_RATIO_RANGE, check_campaign

#: Columns an agreement map may use as an axis (checked here, drawn by products.py).
AXES = ("frequency_ratio", "amplitude_ratio", "intensity", "slenderness", "alpha", "size", "height",
        "width", "period", "damping_ratio", "mass_ratio", "azimuth")

#: Largest number of rows (case × engine setting) a campaign may have: beyond it a
#: typo (a grid of 10⁴ × 10⁴) would fill the disk instead of failing.
MAX_RUNS = 2_000_000
#: Largest number of contact-engine runs (each costs ~0.1–10 s; 10⁵ is days on 2 cores).
MAX_CONTACT_RUNS = 100_000
#: Default time after the motion's end (s): model.md's tail, ample for a block past α
#: to return or fall (time scale 1/p ≈ 0.4 s).
DEFAULT_TAIL = 5.0

SCALE_BY = {"pga": "g", "pgv": "m/s"}
BASES = ("fixed", "isolated")
_TOP_KEYS = {"campaign", "systems", "motions", "engines", "duration", "products"}


def _where(key, value, allowed):
    return InputError(f"{key} = {shown(value)}: must be {allowed}")


def _number(key, value, *, positive=True, allow_zero=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _where(key, value, "a number")
    x = float(value)
    if not math.isfinite(x) or (positive and (x < 0 or (x == 0 and not allow_zero))):
        raise _where(key, value, "a positive finite number" if not allow_zero else "a non-negative finite number")
    return x


def _grid(key, value, *, allow_zero=False) -> tuple[float, ...]:
    """A number, a list of numbers, or a range {from, to, num} (linear, both ends
    included; `log = true` for geometric spacing)."""
    if isinstance(value, dict):
        unknown = set(value) - {"from", "to", "num", "log"}
        if unknown:
            raise InputError(f"{key}.{sorted(unknown)[0]}: unknown key (a range has from, to, num, log)")
        for k in ("from", "to", "num"):
            if k not in value:
                raise InputError(f"{key}.{k}: missing (a range needs from, to and num)")
        lo = _number(f"{key}.from", value["from"], allow_zero=allow_zero)
        hi = _number(f"{key}.to", value["to"], allow_zero=allow_zero)
        num = value["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise _where(f"{key}.num", num, "a positive integer")
        if num > MAX_RUNS:
            raise _where(f"{key}.num", num, f"at most {MAX_RUNS}")
        if hi < lo:
            raise _where(f"{key}.to", hi, f"at least {key}.from = {lo}")
        log = value.get("log", False)
        if not isinstance(log, bool):
            raise _where(f"{key}.log", log, "true or false")
        if log and lo <= 0:
            raise _where(f"{key}.from", lo, "positive for a log range")
        vals = np.geomspace(lo, hi, num) if log else np.linspace(lo, hi, num)
        return tuple(float(round(v, 12)) for v in vals)
    items = value if isinstance(value, list) else [value]
    if not items:
        raise _where(key, value, "a number, a non-empty list or a range {from, to, num}")
    return tuple(_number(f"{key}[{i}]" if isinstance(value, list) else key, v, allow_zero=allow_zero)
                 for i, v in enumerate(items))


def _strings(key, value, allowed) -> tuple[str, ...]:
    items = value if isinstance(value, list) else [value]
    for v in items:
        if v not in allowed:
            raise _where(key, v, f"one of {', '.join(allowed)}")
    if not items:
        raise _where(key, value, f"one or more of {', '.join(allowed)}")
    return tuple(items)


def _check_keys(key, table, allowed):
    if not isinstance(table, dict):
        raise _where(key, table, "a table")
    for k in table:
        if k not in allowed:
            raise InputError(f"{key}.{k}: unknown key (allowed: {', '.join(sorted(allowed))})")


#: "Engine, preset, overrides": the registry's one value (core.engines.EngineChoice),
#: under the name campaign files and the Python API have used.
EngineSetting = EngineChoice


@dataclass(frozen=True)
class CampaignSpec:
    name: str
    systems: dict
    motions: dict
    engines: tuple[EngineSetting, ...]
    duration: dict
    products: dict
    analytic_chunk: int = ANALYTIC_CHUNK
    contact_chunk: int = CONTACT_CHUNK
    source: str = ""  # the file's path, for messages and relative record folders

    # --- identity -------------------------------------------------------------------
    def fingerprint(self) -> str:
        """A hash of everything that defines the results (not name/products/source; a statue by
        its file's content, not the bodies read from it)."""
        body = {"systems": {k: v for k, v in self.systems.items() if not k.startswith("_")}, "motions": self.motions, "duration": self.duration,
                "engines": [(e.engine, list(e.overrides)) for e in self.engines]}
        return hashlib.sha256(json.dumps(body, sort_keys=True, default=str).encode()).hexdigest()[:16]

    # --- expansion ------------------------------------------------------------------
    def system_grid(self) -> list[dict]:
        """Every system's defining inputs, in a fixed order (geometry outer, base inner)."""
        s = self.systems
        if "statue" in s:
            geometry = [{"statue": s["statue"]["label"], "azimuth": a} for a in s["azimuth"]]
        elif "height" in s:
            geometry = [{"height": H, "width": B} for H, B in itertools.product(s["height"], s["width"])]
        else:
            geometry = []
            for lam_key, size in itertools.product(s["slenderness"], s["size"]):
                lam = lam_key
                # size is R = √(b² + h²), the half-diagonal (m): p = √(3g/4R)
                b = size / math.sqrt(1 + lam * lam)
                geometry.append({"height": round(2 * lam * b, 12), "width": round(2 * b, 12)})
        out = []
        for geo, mass in itertools.product(geometry, s["mass"]):
            if "statue" in s:  # the statue along its direction: its two edges (System.body)
                geo = {**geo, **self._statue_body(geo["azimuth"], mass)}
            for base in s["base"]:
                if base == "fixed":
                    out.append({**geo, "mass": mass, "base": "fixed", "mass_ratio": 0.0,
                                "period": math.nan, "damping_ratio": math.nan})
                elif "base_mass" in s:
                    for mb, T, xi in itertools.product(s["base_mass"], s["period"], s["damping_ratio"]):
                        out.append({**geo, "mass": mass, "base": "isolated", "mass_ratio": mass / mb,
                                    "base_mass": mb, "period": T, "damping_ratio": xi})
                else:
                    for mu, T, xi in itertools.product(s["mass_ratio"], s["period"], s["damping_ratio"]):
                        out.append({**geo, "mass": mass, "base": "isolated", "mass_ratio": mu,
                                    "period": T, "damping_ratio": xi})
        # the statue's friction, innermost (a campaign without the axis: its systems as before)
        frictions = s.get("friction", (None,))
        return [{**row, "friction": mu} if mu is not None else row for row in out for mu in frictions]

    def _statue_body(self, azimuth_deg: float, mass: float) -> dict:
        s = self.systems
        resting = s["_resting"][s["mass"].index(mass)]
        body = PlanarBody.from_resting(resting.along(math.radians(azimuth_deg)))
        return {**body.box, "body": body, "statue_sha256": s["statue"]["sha256"] or ""}

    def n_motions_per_system(self) -> int:
        m = self.motions
        if m["type"] == "pulse":
            return len(m["pulse"]) * len(m["frequency_ratio"]) * len(m["amplitude_ratio"])
        return m["n_records"] * len(m["levels"])

    def n_systems(self) -> int:
        """len(system_grid()), from the grids' lengths (nothing is built: a grid of 10¹²
        systems is refused in microseconds, not after minutes or a MemoryError)."""
        s = self.systems
        geometry = (len(s["azimuth"]) if "statue" in s else len(s["height"]) * len(s["width"]) if "height" in s
                    else len(s["slenderness"]) * len(s["size"]))
        per_geometry = ("fixed" in s["base"]) + ("isolated" in s["base"]) * (
            len(s.get("mass_ratio", s.get("base_mass", ()))) * len(s.get("period", ()))
            * len(s.get("damping_ratio", ())))
        return geometry * len(s["mass"]) * per_geometry * len(s.get("friction", (None,)))

    @property
    def n_cases(self) -> int:
        return self.n_systems() * self.n_motions_per_system()

    @property
    def n_runs(self) -> int:
        return self.n_cases * len(self.engines)

    def cases(self, records: dict | None = None) -> list[Case]:
        """Every case, systems outer, motions inner. `records`: name → GroundMotion
        for a record suite (campaign.records.load_suite)."""
        rows = []
        for sys_inputs in self.system_grid():
            for mot_inputs in self._motion_grid(records):
                rows.append({**sys_inputs, **mot_inputs})
        return [build_case(i, inputs, self.duration, records) for i, inputs in enumerate(rows)]

    def _motion_grid(self, records):
        m = self.motions
        if m["type"] == "pulse":
            for kind, fr, ar in itertools.product(m["pulse"], m["frequency_ratio"], m["amplitude_ratio"]):
                yield {"motion": kind, "cycles": m["cycles"], "frequency_ratio": fr, "amplitude_ratio": ar,
                       "scale_by": "", "intensity": math.nan}
        else:
            if records is None:
                raise InputError("motions: a record suite must be loaded to expand the cases")
            for name in sorted(records):
                for level in m["levels"]:
                    yield {"motion": name, "cycles": math.nan, "frequency_ratio": math.nan,
                           "amplitude_ratio": math.nan, "scale_by": m["scale_by"], "intensity": level}


#: how a campaign file names a statue's inputs in errors (analytic.shape.load_statue)
STATUE_KEYS = {"mesh": "systems.statue.mesh", "example": "systems.statue.example", "unit": "systems.statue.unit",
               "mass": "systems.mass", "density": "systems.statue.density", "azimuth": "systems.azimuth",
               "source": "its mesh (systems.statue.mesh = FILE) or an example (systems.statue.example = NAME)"}


def _statue(t, source: Path) -> dict:
    """A statue's mesh (docs/statues.md), read once and stood on its plinth, here: its mass
    grid (its density's one mass, or systems.mass), its directions (systems.azimuth, degrees;
    default: the one it tips first) and what identifies it (an example's name, or the file's
    path and content's digest, so that a changed file is new work)."""
    table = t["statue"]
    mesh = table.get("mesh")
    if mesh is not None and not str(mesh).strip():  # "" would be the campaign's own folder
        raise _where("systems.statue.mesh", mesh, "a mesh file's path (relative to the campaign file)")
    if mesh is not None:
        mesh = Path(mesh) if Path(mesh).is_absolute() else Path(source).parent / mesh
    density = table.get("density")
    masses = (None,) if density is not None else _grid("systems.mass", t.get("mass", 1000.0))
    # the file read once (statue_mesh), stood once per mass: a mass grid does not read it again
    # (mass or density, one of the two, and each positive: checked by the schema and _grid)
    vertices, faces, name = shape.statue_mesh(mesh=None if mesh is None else str(mesh), example=table.get("example"),
                                              unit=table.get("unit"), names=STATUE_KEYS)
    bodies = {m: shape.standing(vertices, faces, mass=m, density=density, name=name) for m in masses}
    first = next(iter(bodies.values()))
    if "azimuth" in t:
        azimuths = _grid("systems.azimuth", t["azimuth"], allow_zero=True)
        for a in azimuths:
            if not a < 360:
                raise _where("systems.azimuth", a, "degrees from 0 to under 360")
    else:
        azimuths = (round(math.degrees(shape.weakest_direction(first)[0]) % 360.0, 9),)
    # the file by its content, not its path: the same campaign run from elsewhere is the same work
    identity = {"example": table.get("example"), "unit": table.get("unit"), "density": density,
                "sha256": None if mesh is None else hashlib.sha256(mesh.read_bytes()).hexdigest()}
    label = table["example"] if mesh is None else mesh.name
    return {"statue": {**identity, "label": label}, "azimuth": azimuths,
            "mass": tuple(b.mass for b in bodies.values()), "_resting": tuple(bodies.values())}


def _systems(t, source: Path = Path("campaign.toml")) -> dict:
    allowed = {"slenderness", "alpha", "size", "height", "width", "mass", "base", "mass_ratio", "base_mass",
               "period", "damping_ratio", "friction", "statue", "azimuth"}
    _check_keys("systems", t, allowed)
    out = {}
    geometry_keys = [k for k in ("slenderness", "alpha", "height", "width") if k in t]
    if "statue" in t:
        out.update(_statue(t, source))
    elif "height" in t or "width" in t:
        if set(geometry_keys) != {"height", "width"} or "size" in t:
            raise InputError("systems: give height and width, or slenderness (or alpha) and size, not a mix")
        out["height"], out["width"] = _grid("systems.height", t["height"]), _grid("systems.width", t["width"])
    else:
        if ("slenderness" in t) == ("alpha" in t):
            raise InputError("systems: give height and width, or slenderness (or alpha) and size")
        if "alpha" in t:
            alphas = _grid("systems.alpha", t["alpha"])
            for a in alphas:
                if not 0 < a < math.pi / 2:
                    raise _where("systems.alpha", a, "between 0 and π/2 (rad)")
            out["slenderness"] = tuple(1 / math.tan(a) for a in alphas)
        else:
            out["slenderness"] = _grid("systems.slenderness", t["slenderness"])
        if "size" not in t:
            raise InputError("systems.size: missing (R = √(b² + h²), the half-diagonal, m)")
        out["size"] = _grid("systems.size", t["size"])
    if "statue" not in t:
        out["mass"] = _grid("systems.mass", t.get("mass", 1000.0))
    # the statue's friction (docs/sliding.md): None, a statue that cannot slip, is the axis's one value by default
    out["friction"] = (None,) if "friction" not in t else _grid("systems.friction", t["friction"])
    for mu in out["friction"]:
        if mu is not None and not 0 < mu <= MAX_STATUE_FRICTION:
            raise _where("systems.friction", mu, f"a friction coefficient in (0, {MAX_STATUE_FRICTION:g}]")
    out["base"] = _strings("systems.base", t.get("base", "fixed"), BASES)
    if "isolated" in out["base"]:
        if "mass_ratio" not in t and "base_mass" not in t:
            raise InputError("systems.mass_ratio: missing (needed for base = 'isolated'; or base_mass, kg)")
        for k in ("period", "damping_ratio"):
            if k not in t:
                raise InputError(f"systems.{k}: missing (needed for base = 'isolated')")
        if "base_mass" in t:
            # the base's mass as given (kg); each system's μ = mass/base_mass, within the range
            # a mass ratio may take (schema.MASS_RATIO_RANGE)
            out["base_mass"] = _grid("systems.base_mass", t["base_mass"])
            lo, hi = MASS_RATIO_RANGE
            for m, mb in itertools.product(out["mass"], out["base_mass"]):
                if not lo <= m / mb <= hi:
                    raise _where("systems.base_mass", mb, f"such that mass/base_mass is from {lo:g} to {hi:g} "
                                 f"(with mass = {m:g} kg it is {m / mb:g})")
        else:
            out["mass_ratio"] = _grid("systems.mass_ratio", t["mass_ratio"])
        out["period"] = _grid("systems.period", t["period"])
        out["damping_ratio"] = _grid("systems.damping_ratio", t["damping_ratio"], allow_zero=True)
        for z in out["damping_ratio"]:
            if z >= 1:
                raise _where("systems.damping_ratio", z, "below 1 (an underdamped isolator)")
    return out


def _motions(t, source: Path) -> dict:
    if not isinstance(t, dict) or "type" not in t:
        raise InputError("motions.type: missing (one of pulse, records)")
    kind = t["type"]
    if kind == "pulse":
        _check_keys("motions", t, {"type", "pulse", "frequency_ratio", "amplitude_ratio", "cycles"})
        for k in ("frequency_ratio", "amplitude_ratio"):
            if k not in t:
                raise InputError(f"motions.{k}: missing ({'ω_p/p' if k[0] == 'f' else 'a_p/(g·tanα)'})")
        return {"type": "pulse", "pulse": _strings("motions.pulse", t.get("pulse", "sine"), PULSES),
                "frequency_ratio": _grid("motions.frequency_ratio", t["frequency_ratio"]),
                "amplitude_ratio": _grid("motions.amplitude_ratio", t["amplitude_ratio"]),
                "cycles": _number("motions.cycles", t.get("cycles", 1.0))}
    if kind == "records":
        _check_keys("motions", t, {"type", "suite", "folder", "units", "scale_by", "levels", "limit"})
        if ("suite" in t) == ("folder" in t):
            raise InputError("motions: give suite = 'fema-p695' or folder = 'path/to/records', not both")
        out = {"type": "records"}
        if "suite" in t:
            if t["suite"] not in SUITES:
                raise _where("motions.suite", t["suite"], f"one of {', '.join(SUITES)}")
            out["suite"] = t["suite"]
        else:
            folder = Path(str(t["folder"])).expanduser()
            if not folder.is_absolute():
                folder = (source.parent / folder).resolve()
            if not folder.is_dir():
                raise _where("motions.folder", str(t["folder"]), f"a folder of records (looked in {folder})")
            out["folder"] = str(folder)
        units = t.get("units")  # None: each file states its own (AT2, JMA, a two-column header)
        if units is not None and units not in UNITS:
            raise _where("motions.units", units, f"one of {', '.join(UNITS)} (for two-column files)")
        out["units"] = units
        scale_by = t.get("scale_by", "pga")
        if scale_by not in SCALE_BY:
            raise _where("motions.scale_by", scale_by, "pga (levels in g) or pgv (levels in m/s)")
        out["scale_by"] = scale_by
        if "levels" not in t:
            raise InputError(f"motions.levels: missing (intensities in {SCALE_BY[scale_by]})")
        out["levels"] = _grid("motions.levels", t["levels"])
        limit = t.get("limit", 0)
        if isinstance(limit, bool) or not isinstance(limit, int) or limit < 0:
            raise _where("motions.limit", limit, "a non-negative integer (0: every record)")
        out["limit"] = limit
        return out
    raise _where("motions.type", kind, "one of pulse, records")


def _engines(t) -> tuple[EngineSetting, ...]:
    if not isinstance(t, list) or not t:
        raise InputError("engines: missing (one or more [[engines]] tables with name = ...)")
    out = []
    for i, e in enumerate(t):
        key = f"engines[{i}]"
        _check_keys(key, e, {"name", "settings"})
        if "name" not in e:
            raise InputError(f"{key}.name: missing (one of {', '.join(ALL_ENGINES)})")
        name = e["name"]
        if name not in ALL_ENGINES:
            raise _where(f"{key}.name", name, f"one of {', '.join(ALL_ENGINES)}")
        settings = e.get("settings", [{}])
        if isinstance(settings, dict):
            settings = [settings]
        if not isinstance(settings, list) or not settings:
            raise _where(f"{key}.settings", settings, "a list of tables, e.g. [{timestep = 1e-3}]")
        for j, s in enumerate(settings):
            if not isinstance(s, dict):
                raise _where(f"{key}.settings[{j}]", s, "a table, e.g. {timestep = 1e-3}")
            try:  # the registry's one engine choice; its Settings made once to check the values
                setting = replace(choose(name, s, strict=True), where=f"{key}.settings[{j}]")
                setting.settings()
            except (InputError, TypeError, ValueError) as err:
                raise InputError(f"{key}.settings[{j}]: {err}") from None
            if setting in out:
                raise InputError(f"{key}.settings[{j}] = {setting.label!r}: listed twice for {name}")
            out.append(setting)
    return tuple(out)


def _duration(t) -> dict:
    _check_keys("duration", t, {"tail", "end"})
    if "end" in t and "tail" in t:
        raise InputError("duration: give tail (s after the motion's end) or end (s from t = 0), not both")
    if "end" in t:
        return {"end": _number("duration.end", t["end"])}
    return {"tail": _number("duration.tail", t.get("tail", DEFAULT_TAIL), allow_zero=True)}


def _products(t) -> dict:
    _check_keys("products", t, {"agreement", "spectrum", "fragility"})
    out = {}
    if "agreement" in t:
        _check_keys("products.agreement", t["agreement"], {"x", "y"})
        out["agreement"] = dict(t["agreement"])
    for k in ("spectrum", "fragility"):
        if k in t:
            if not isinstance(t[k], bool):
                raise _where(f"products.{k}", t[k], "true or false")
            out[k] = t[k]
    return out


def parse_spec(data: dict, source: Path = Path("campaign.toml")) -> CampaignSpec:
    check_campaign(data)
    for k in data:
        if k not in _TOP_KEYS:
            raise InputError(f"{k}: unknown key (a campaign has {', '.join(sorted(_TOP_KEYS))})")
    head = data.get("campaign", {})
    _check_keys("campaign", head, {"name", "analytic_chunk", "contact_chunk"})
    for k in ("systems", "motions", "engines"):
        if k not in data:
            raise InputError(f"{k}: missing (see docs/campaigns.md)")
    _check_lengths(data)
    chunks = {}
    for k, default in (("analytic_chunk", ANALYTIC_CHUNK), ("contact_chunk", CONTACT_CHUNK)):
        v = head.get(k, default)
        if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= 100_000:
            raise _where(f"campaign.{k}", v, "an integer from 1 to 100000")
        chunks[k] = v
    spec = CampaignSpec(
        name=str(head.get("name", source.stem)), systems=_systems(data["systems"], source),
        motions=_motions(data["motions"], source), engines=_engines(data["engines"]),
        duration=_duration(data.get("duration", {})), products=_products(data.get("products", {})),
        source=str(source), **chunks)
    if spec.motions["type"] == "records":
        n = count_records(spec.motions)
        object.__setattr__(spec, "motions", {**spec.motions, "n_records": n})
    _check_size(spec)
    if spec.motions["type"] == "pulse":  # a record suite's lengths are known once it is read (run_campaign)
        check_limits(spec, longest_pulse(spec))
    if "agreement" in spec.products:
        for k in ("x", "y"):
            v = spec.products["agreement"].get(k)
            if v is not None and v not in AXES:
                raise _where(f"products.agreement.{k}", v, f"one of {', '.join(AXES)}")
    return spec


def check_limits(spec: CampaignSpec, longest_motion: float) -> None:
    """analytic/limits.py's bounds, as `run` applies them, on the campaign's longest
    case (its longest motion, `longest_motion` s, and the duration rule), its shortest
    isolator period and each engine setting's steps: an InputError naming the key the
    user wrote, before anything runs."""
    d = spec.duration
    if "end" in d:
        longest = check_duration("duration.end", d["end"])
    else:
        longest = longest_motion + d["tail"]
        check_duration("duration.tail", longest, f" (the longest motion, {longest_motion:.3g} s, + tail "
                                                  f"{d['tail']:g} s)")
    s = spec.systems
    if "isolated" in s["base"]:
        T = min(s["period"])
        # the stiffness is only quoted by the message; the bound is on duration / period
        shortest = SimpleNamespace(fixed_base=False, period=T, stiffness=math.nan)
        try:
            check_isolator(shortest, longest)
        except InputError as e:
            raise InputError(f"systems.period: {str(e).replace(' (stiffness nan N/m)', '')}") from None
    systems = [build_system(g) for g in spec.system_grid()]
    if spec.motions["type"] == "pulse":  # a pulse's peak is amplitude_ratio·g·tanα (a record's: record_factor)
        steepest = max(math.tan(system.alpha) for system in systems)
        check_acceleration("motions.amplitude_ratio", max(spec.motions["amplitude_ratio"]) * steepest,
                           f" (its largest × tanα = {steepest:.3g} of the squattest block)")
    for e in spec.engines:
        try:
            # the engine's bounds on every system of the grid, as `run` would refuse one:
            # not a chunk of error rows and exit 0
            check_carries(e, systems, longest)
        except InputError as err:
            raise InputError(f"{e.where or e.engine}: {err}") from None


def longest_pulse(spec: CampaignSpec) -> float:
    """The longest pulse of a pulse campaign (s): the lowest frequency ratio on the
    largest block (the smallest p), for each pulse kind."""
    s, m = spec.systems, spec.motions
    if "statue" in s:  # its box along every direction: the largest H, B
        boxes = [g for g in spec.system_grid()]
        H, B = max(g["height"] for g in boxes), max(g["width"] for g in boxes)
    elif "height" in s:
        H, B = max(s["height"]), max(s["width"])
    else:
        lam, R = min(s["slenderness"]), max(s["size"])
        b = R / math.sqrt(1 + lam * lam)
        H, B = 2 * lam * b, 2 * b
    big = System.fixed(height=H, width=B, mass=1.0)
    return max(pulse_for(big, kind, min(m["frequency_ratio"]), 1.0, m["cycles"]).end_time for kind in m["pulse"])


def _length(value) -> int:
    """How many values a grid entry as written holds (a range: its num), without spacing it;
    1 where it is not yet known to be well formed (its own check follows)."""
    if isinstance(value, dict):
        num = value.get("num")
        return num if isinstance(num, int) and not isinstance(num, bool) and num > 0 else 1
    return max(len(value), 1) if isinstance(value, list) else 1


def _check_lengths(data: dict) -> None:
    """The campaign's size from the lengths as written, before any range is spaced: two
    1e6-point ranges were spaced (2e6 values, 15-30 s on a loaded machine) only to be
    refused. A lower bound (a record suite's records count as one), so what it refuses
    _check_size would refuse too."""
    s, m, engines = data.get("systems"), data.get("motions"), data.get("engines")
    if not isinstance(s, dict) or not isinstance(m, dict) or not isinstance(engines, list):
        return
    geometry = (_length(s.get("height")) * _length(s.get("width")) if "height" in s
                else _length(s.get("slenderness", s.get("alpha"))) * _length(s.get("size")))
    bases = s.get("base", "fixed")
    bases = bases if isinstance(bases, list) else [bases]
    per_geometry = ("fixed" in bases) + ("isolated" in bases) * (
        _length(s.get("mass_ratio")) * _length(s.get("period")) * _length(s.get("damping_ratio")))
    motions = (_length(m.get("pulse")) * _length(m.get("frequency_ratio")) * _length(m.get("amplitude_ratio"))
               if m.get("type") == "pulse" else _length(m.get("levels")))
    settings = sum(_length(e.get("settings")) if isinstance(e, dict) else 1 for e in engines)
    n_runs = geometry * _length(s.get("mass")) * max(per_geometry, 1) * motions * max(settings, 1)
    if n_runs > MAX_RUNS:
        raise InputError(f"campaign size = {n_runs} runs or more (the lengths of its grids multiplied): must be "
                         f"at most {MAX_RUNS}")


def _check_size(spec: CampaignSpec) -> None:
    n_runs = spec.n_runs
    if n_runs > MAX_RUNS:
        raise InputError(f"campaign size = {n_runs} runs ({spec.n_cases} cases × {len(spec.engines)} "
                         f"engine settings): must be at most {MAX_RUNS}")
    n_contact = spec.n_cases * sum(not get_engine(e.engine).capabilities.batch for e in spec.engines)
    if n_contact > MAX_CONTACT_RUNS:
        raise InputError(f"campaign size = {n_contact} contact-engine runs: must be at most "
                         f"{MAX_CONTACT_RUNS} (each takes 0.1–10 s; use a coarser grid for them)")


def load_spec(path) -> CampaignSpec:
    path = Path(path)
    if not path.is_file():
        raise InputError(f"campaign file {str(path)!r}: " + ("not a regular file" if path.exists() else "no such file"))
    # bounded before it is parsed, as every file a user hands a command (issue 34)
    return parse_spec(read_toml(path, f"campaign file {str(path)!r}"), path.resolve())
