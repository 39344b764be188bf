"""The engine registry: every command, report and test loops over these names.

Each entry names a package exposing `ENGINE` (or "module:ATTRIBUTE" for a module declaring
more than one), an `isorock.analytic.engine_protocol.
EngineSpec` (simulate, its frozen Settings, presets, what it can export and supports).
`Engine.simulate` always returns the shared Trajectory: a contact engine's raw history
is measured here (`isorock.validate.core.measure`), the same way for every engine, so no
engine measures anything itself. Packages are imported lazily, so `isorock beta` never
loads a physics engine.
"""
from __future__ import annotations

import dataclasses
import importlib
import math
from dataclasses import MISSING, asdict, dataclass, field, fields, is_dataclass, replace

from ...analytic.engine_protocol import (DEFAULT_IMPACT_THRESHOLD, EngineSpec, check_body, check_friction,
                                              check_isolator_kind, declare_facet)
from ...analytic.errors import InputError
from ...analytic.limits import BudgetExceeded, RunBudget, check_budget, check_settings
from ...analytic.motion import GroundMotion
from ...analytic.overturning import PAST_ALPHA
from ...analytic.trajectory import RawHistory, Trajectory
from . import measure
# the registry's names (validate/core/registry.py, light): importable from here as before
from .registry import (ALIASES, ALL_ENGINES, CONTACT_ENGINES, DISTINCT_ENGINES, ENGINE_MODULES, ENGINE_NAMES,  # noqa: F401
                       PLUGIN_GROUP, PLUGINS, PLUGINS_REFUSED, REFERENCE, _plugins, canonical)


#: the facets the registry itself uses (engine_protocol.Facet)
BATCH = declare_facet("simulate_many", "the registry (Engine.simulate_many: campaigns, ensembles, bench's batch)",
                      "(runs, *, settings, threads, budget_s) → per (system, motion, duration, theta0) of runs, "
                      "what simulate returns for it alone or the exception it raised, each within budget_s s "
                      "of wall time")
SCENE_TEXT = declare_facet("scene_text", "isorock scene, validate's scene files",
                           "(system, settings) → the text of the model file a user can open")
SCENE_FORMAT = declare_facet("scene_format", "isorock scene", "(format name, file suffix) of scene_text's file")


@dataclass(frozen=True)
class Engine:
    """A registered engine: its spec, and `simulate` that returns a measured Trajectory."""

    name: str
    spec: EngineSpec

    @property
    def label(self) -> str:
        return self.spec.label

    @property
    def capabilities(self):
        return self.spec.capabilities

    @property
    def Settings(self):
        return self.spec.settings_type

    def settings(self, **overrides):
        """The engine's default settings with `overrides` applied (settings that follow
        others, e.g. MuJoCo's contact parameters after its timestep, follow them); an
        override the engine does not have is an InputError naming it."""
        refuse_unknown_settings(self.name, self.Settings, overrides)
        return self.spec.settings(**overrides)

    def preset(self, name: str):
        """The Settings of a named preset (ENGINE:PRESET on the command line)."""
        presets = self.spec.presets
        if name not in presets:
            raise InputError(f"preset = {name!r}: not a preset of engine {self.name!r} "
                             f"(its presets: {', '.join(presets) or 'none'})")
        return presets[name]()

    @property
    def has_scene(self) -> bool:
        return SCENE_TEXT.of(self.spec) is not None

    @property
    def scene_format(self) -> tuple[str, str] | None:
        return SCENE_FORMAT.of(self.spec)

    @property
    def has_batch(self) -> bool:
        """Whether simulate_many runs its cases together (the engine's simulate_many facet) rather
        than one by one."""
        return BATCH.of(self.spec) is not None and not self.capabilities.exact_impacts

    def scene_text(self, system, settings=None) -> str:
        self.check_isolator(system)
        return SCENE_TEXT.of(self.spec)(system, settings)

    def check_isolator(self, system) -> None:
        """One line refusing, before any work, a System this engine does not carry: on an
        isolator it does not build (docs/isolators.md), or a statue whose kinetic friction is
        below its static one, where the engine has one friction coefficient (MuJoCo, PyBullet:
        Capabilities.kinetic_friction)."""
        check_isolator_kind(system, self.capabilities.isolators, f"engine {self.name!r}")
        check_body(system, getattr(self.capabilities, "two_edges", False), f"engine {self.name!r}")
        check_friction(system, self.capabilities.kinetic_friction, f"engine {self.name!r}",
                       statue_friction=self.capabilities.statue_friction)

    def check_run(self, system, motion=None) -> None:
        """One line refusing, before any work, a run this engine does not carry: its System
        (check_isolator), or a vertical ground motion where it carries horizontal motion only
        (Capabilities.vertical: an engine a package registers may not)."""
        self.check_isolator(system)
        if motion is not None and motion.vertical is not None and not self.capabilities.vertical:
            raise InputError(f"vertical: engine {self.name!r} carries horizontal ground motion only "
                             "(Capabilities.vertical)")

    def check_system(self, system, settings=None) -> None:
        """Every bound this engine puts on `system` before any work: the isolator it carries
        and the engine's own (EngineSpec.check_system), with `settings` as the run will use
        them (default: the engine's defaults derived for the system)."""
        self.check_isolator(system)
        if self.spec.check_system is not None:
            self.spec.check_system(system, settings if settings is not None else settings_used(self.settings(), system))

    def simulate(self, system, motion=None, *, settings=None, duration=None, theta0=0.0,
                 impact_threshold=DEFAULT_IMPACT_THRESHOLD, contact_window=None, overturn_rule=None,
                 progress=None, effective_beta: bool = True, budget_s: float | None = None,
                 checked: bool = False) -> Trajectory:
        """Run the engine and measure its history: θ0 in rad; impact_threshold as a
        fraction of α (model.md's counting rule); contact_window (s) is how a contact
        engine's history is measured (validate.measure); overturn_rule ("past-alpha" or
        "alpha", model.md) judges every engine the same way: the analytic engines take it
        as their `overturn` setting, a contact engine's history is judged by it (default:
        the analytic setting's, else "past-alpha"). effective_beta=False: a contact engine's
        impacts are located and counted but their velocities not mapped (NaN), for runs
        read only as summaries (campaign rows, ensembles): the summary is the same.
        checked=True: the inputs come from a Plan (core.plan.make_plan), which checked that this
        engine carries them; they are not checked again here."""

        if not checked:
            self.check_run(system, motion)
        if settings is None:
            settings = self.settings()
        if budget_s is not None:  # a wall-clock budget (analytic/limits.py): the run stops past it
            progress = RunBudget(budget_s, progress)
        if overturn_rule is not None and hasattr(settings, "overturn"):
            settings = replace(settings, overturn=overturn_rule)
        kwargs = dict(settings=settings, duration=duration, theta0=theta0, progress=progress)
        if self.capabilities.exact_impacts:
            kwargs["impact_threshold"] = impact_threshold
        if self.name in PLUGINS:  # a package's engine: what it raises or hands over is checked here
            try:
                out = self.spec.simulate(system, motion, **kwargs)
            except (InputError, BudgetExceeded):
                raise
            except Exception as e:  # noqa: BLE001 — the package's failure, said as its own
                raise PluginError(f"engine {self.name!r} (its package's {PLUGINS[self.name]}) failed: "
                                  f"{type(e).__name__}: {e}") from None
            check_plugin_run(self.name, out, exact_impacts=self.capabilities.exact_impacts)
        else:
            out = self.spec.simulate(system, motion, **kwargs)
        if isinstance(out, RawHistory):
            out = measure.measure(out, motion or GroundMotion.zero(), impact_threshold=impact_threshold,
                                  window=contact_window,
                                  overturn_rule=overturn_rule or PAST_ALPHA, effective_beta=effective_beta)
        return out

    def simulate_many(self, runs, *, settings=None, overturn_rule=None, effective_beta: bool = True,
                      threads: int = 1, budget_s: float | None = None) -> list:
        """`simulate` of each (system, motion, duration, theta0) in `runs`: per run its
        Trajectory, or the exception it raised. An engine with a batch path
        (its simulate_many facet, BATCH: MuJoCo's, `threads` runs at a time) runs them
        together, each exactly as alone; any other runs them one by one."""
        runs = list(runs)
        if budget_s is not None:
            check_budget(budget_s)
        for system, *_ in runs:
            self.check_isolator(system)
        if not self.has_batch:
            out = []
            for system, motion, duration, theta0 in runs:
                try:
                    out.append(self.simulate(system, motion, settings=settings, duration=duration, theta0=theta0,
                                             overturn_rule=overturn_rule, effective_beta=effective_beta,
                                             budget_s=budget_s))
                except Exception as e:  # noqa: BLE001 — one bad case is that case's result
                    out.append(e)
            return out
        raws = BATCH.of(self.spec)(runs, settings=settings if settings is not None else self.settings(),
                                   threads=threads, budget_s=budget_s)
        return [raw if isinstance(raw, Exception) else
                measure.measure(raw, motion or GroundMotion.zero(), overturn_rule=overturn_rule or PAST_ALPHA,
                                effective_beta=effective_beta)
                for raw, (_, motion, _, _) in zip(raws, runs)]


def unknown_settings(name: str, settings_type, overrides) -> list[str]:
    """The names among `overrides` (a dict of setting → value) that engine `name`'s
    Settings does not have, sorted; a key that is not a name at all (a number, None: a dict
    built in Python) is one line here, not a TypeError where the names are joined."""
    for key in overrides:
        if not isinstance(key, str):
            raise InputError(f"settings: the key {key!r} is not a setting's name (a str) of engine {name!r}")
    known = {f.name for f in fields(settings_type)}
    return sorted(k for k in overrides if k not in known)


def refuse_unknown_settings(name: str, settings_type, overrides) -> None:
    """One line naming every override engine `name`'s Settings does not have, and its settings."""
    unknown = unknown_settings(name, settings_type, overrides)
    if unknown:
        raise InputError(f"{', '.join(unknown)}: not a setting of engine {name!r} "
                         f"(its settings: {', '.join(sorted(f.name for f in fields(settings_type)))})")


def setting_value_problem(settings_type, key: str, value) -> str | None:
    """What is wrong with `value` for setting `key` of `settings_type`, judged by the type of
    the key's default (a number for a number or for None, a word for a word, true or false for
    a boolean, a list of numbers for a tuple), or None. The one schema of an engine setting's
    value: a --config [settings.ENGINE] table, a campaign's [[engines]] settings and the command
    line's --set all ask it (an engine's own Settings checks ranges when it is made)."""
    f = next((f for f in fields(settings_type) if f.name == key), None)
    if f is None:
        return None
    default = f.default if f.default is not MISSING else None
    if isinstance(default, bool):
        ok = isinstance(value, bool)
    elif isinstance(default, str):
        ok = isinstance(value, str)
    elif isinstance(default, tuple):
        ok = isinstance(value, (list, tuple)) and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                                      for x in value)
    else:  # a number (or None: a number when given)
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        try:
            if ok and not math.isfinite(float(value)):
                return f"{key} = {value!r}: must be a finite number"
        except OverflowError:  # an integer beyond a float's range
            return f"{key} = {value!r}: must be a finite number (beyond a float's range)"
    if ok:
        return None
    what = ("true or false" if isinstance(default, bool) else "a word" if isinstance(default, str)
            else "a list of numbers" if isinstance(default, tuple) else "a number")
    return f"{key} = {value!r}: must be {what}"


def check_settings_table(table: str, values: dict, *, unknown_keys: bool = True) -> None:
    """A table of engine settings (`table`: an engine, ENGINE:PRESET, or "*" for every engine
    that has the key) checked whole: the engine and its preset exist, each key is a setting of
    it (unknown_keys; a campaign names unknown ones later, with the engine's settings), each
    value has its setting's type (setting_value_problem). Raises ValueError, one line; an engine
    not installed here is checked where it runs."""
    def settings_of(name):
        try:
            return get_engine(name).Settings
        except ImportError:
            return None
    base, _, preset = table.partition(":")
    if table == "*":
        types = [t for t in map(settings_of, ALL_ENGINES) if t is not None]
    elif base not in ALL_ENGINES:
        raise ValueError(f"{table}: not an engine (allowed: *, {', '.join(ALL_ENGINES)}, or ENGINE:PRESET)")
    else:
        types = [settings_of(base)]
        if types[0] is None:
            return
        if preset:
            try:
                get_engine(base).preset(preset)
            except InputError as e:
                raise ValueError(str(e)) from None
    for key, value in values.items():
        having = [t for t in types if any(f.name == key for f in fields(t))]
        if not having:
            if unknown_keys:
                known = sorted({f.name for t in types for f in fields(t)})
                raise ValueError(f"{key}: not a setting of {'any engine' if table == '*' else table} "
                                 f"(allowed: {', '.join(known)})")
            continue
        problem = setting_value_problem(having[0], key, value)
        if problem:
            raise ValueError(problem)


def table_overrides(tables: dict, label: str) -> dict:
    """The overrides engine `label` ("ENGINE" or "ENGINE:PRESET") takes from tables of settings
    keyed "*", ENGINE and ENGINE:PRESET: each later one over the one before."""
    base = label.partition(":")[0]
    return {**tables.get("*", {}), **tables.get(base, {}), **tables.get(label, {})}


class EngineUnavailable(InputError, ImportError):
    """An engine a package registers that cannot be loaded here (its module missing, or raising
    on import): one line when it is asked for by name (an InputError), skipped with the reason
    where every engine is looped over (an ImportError, as Drake is where it is not installed)."""


class PluginError(InputError):
    """What an engine a package registers handed over, or raised, is not a run: one line naming
    the engine and its package (docs/plugins.md), never a traceback from deeper down or a
    result measured from garbage."""


def get_engine(name: str) -> Engine:
    if isinstance(name, str) and name not in ENGINE_MODULES and name in PLUGINS_REFUSED:
        # declared by a package and not registered (a built-in's name keeps the built-in): say why
        raise InputError(f"engine = {name!r}: {PLUGINS_REFUSED[name]}")
    if not isinstance(name, str) or name not in ENGINE_MODULES:
        raise InputError(f"engine = {name!r}: must be one of {', '.join(ALL_ENGINES)}")
    module, _, attribute = ENGINE_MODULES[name].partition(":")
    if name not in PLUGINS:
        try:
            spec = getattr(importlib.import_module(module), attribute or "ENGINE")
        except ImportError as e:
            if isinstance(e, ModuleNotFoundError) and (e.name or "isorock").split(".")[0] == "isorock":
                raise  # a module of isorock's own: a bug, with its traceback
            # an optional extra not installed (pydrake, mujoco_warp): skipped where every engine is
            # looped over (an ImportError), one line where it is named (an InputError)
            raise EngineUnavailable(f"engine = {name!r}: cannot be loaded here ({e})") from None
        return Engine(name, spec)
    try:  # a package's code: whatever its import raises is the package's, said in one line
        spec = getattr(importlib.import_module(module), attribute or "ENGINE")
    except Exception as e:  # noqa: BLE001
        raise EngineUnavailable(f"engine = {name!r}: its package's {PLUGINS[name]} cannot be loaded here "
                                f"({type(e).__name__}: {e})") from None
    if not (isinstance(spec, EngineSpec) and spec.name == name):
        raise InputError(f"engine = {name!r}: its package's {PLUGINS[name]} must be an EngineSpec named {name!r} "
                         f"(isorock.analytic.engine_protocol; docs/plugins.md), not {type(spec).__name__}"
                         + (f" named {spec.name!r}" if isinstance(spec, EngineSpec) else ""))
    if not (isinstance(spec.settings_type, type) and dataclasses.is_dataclass(spec.settings_type)):
        raise InputError(f"engine = {name!r}: its package's {PLUGINS[name]} has settings_type = "
                         f"{spec.settings_type!r}; must be a frozen dataclass (docs/plugins.md)")
    return Engine(name, spec)


def check_plugin_run(name: str, out, *, exact_impacts: bool):
    """What a plugin's simulate returned, checked before it is measured: a RawHistory (or a
    Trajectory, where it declares exact impacts) of at least two rows, its arrays 1-D of one
    length, finite, in increasing time. A PluginError naming the engine otherwise (None, a
    dict, NaN or time running backwards were measured, or a traceback)."""
    import numpy as np  # lazy: NumPy; every command loads the registry

    where = f"engine {name!r} (its package's {PLUGINS.get(name, name)})"
    kinds = (RawHistory, Trajectory) if exact_impacts else (RawHistory,)
    if not isinstance(out, kinds):
        raise PluginError(f"{where} returned {type(out).__name__}; must return a RawHistory (docs/plugins.md)")
    if isinstance(out, Trajectory):
        return
    arrays = {}
    for field_name in ("t", "u", "u_dot", "theta", "theta_dot"):
        try:
            arrays[field_name] = np.asarray(getattr(out, field_name), dtype=float)
        except (TypeError, ValueError):
            raise PluginError(f"{where} returned a history whose {field_name} is not numbers") from None
    shapes = {k: a.shape for k, a in arrays.items()}
    if len(set(shapes.values())) != 1 or arrays["t"].ndim != 1:
        raise PluginError(f"{where} returned a history of arrays {shapes}: must be 1-D, of one length")
    if arrays["t"].size < 2:
        raise PluginError(f"{where} returned a history of {arrays['t'].size} rows: must have at least 2")
    for k, a in arrays.items():
        if not np.all(np.isfinite(a)):
            raise PluginError(f"{where} returned a history whose {k} is not finite at t = "
                              f"{arrays['t'][np.argmin(np.isfinite(a))]:.6g} s (end it there, with a status)")
    if not np.all(np.diff(arrays["t"]) > 0):
        raise PluginError(f"{where} returned a history whose time t does not increase")



@dataclass(frozen=True)
class EngineChoice:
    """One engine as a user chooses it: its name, a named preset or none ("" is the
    engine's defaults), and setting overrides on top, as sorted (name, value) pairs so the
    value is hashable, small and sent to other processes as it is. The one value every
    command, campaign and table uses for "engine, preset, overrides" (`choose` makes one);
    `settings()` is the one way from it to the engine's Settings; `label` names it in a
    table ("default", "preset=fine", "timestep=0.001")."""

    engine: str
    overrides: tuple[tuple[str, object], ...] = ()
    preset: str = ""
    #: the key the user wrote it under (a campaign file's engines[i]), for messages alone
    where: str = field(default="", compare=False, hash=False)

    @property
    def name(self) -> str:
        """ENGINE or ENGINE:PRESET, as on the command line."""
        return f"{self.engine}:{self.preset}" if self.preset else self.engine

    @property
    def label(self) -> str:
        parts = [f"preset={self.preset}"] if self.preset else []
        parts += [f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in self.overrides]
        return ",".join(parts) or "default"

    @property
    def settings_kwargs(self) -> dict:
        return {k: (tuple(v) if isinstance(v, list) else v) for k, v in self.overrides}

    def settings(self):
        """The engine's Settings: its defaults, or its preset's, with the overrides (an
        override the engine does not have is an InputError naming it)."""
        engine = get_engine(self.engine)
        if not self.preset:
            return engine.settings(**self.settings_kwargs)
        preset = engine.preset(self.preset)
        try:
            return replace(preset, **self.settings_kwargs)
        except InputError as e:
            given = ", ".join(f"{k} = {v!r}" for k, v in self.settings_kwargs.items())
            try:  # the user's value alone, on the engine's defaults: is it theirs that is out of range?
                engine.settings(**self.settings_kwargs)
            except InputError as own:
                raise InputError(f"{own} (given on preset {self.engine}:{self.preset})") from None
            # a setting the user did not give (the preset's solref, made for its own step)
            # must not be blamed alone: say which of theirs made it unfit
            raise InputError(f"{given} on preset {self.engine}:{self.preset}: the preset's other settings do not fit "
                             f"it ({e}); give them too, or leave out the preset") from None


def choose(label: str, overrides: dict | None = None, *, strict: bool = False) -> EngineChoice:
    """The EngineChoice of "ENGINE" or "ENGINE:PRESET" with `overrides` (a TOML table, the
    command line's engine options). strict: every override must be a setting of the
    engine; otherwise those it does not have are left out (a friction given for every
    engine of a report means nothing to the analytic model). An unknown engine or preset
    is an InputError here, before any work."""
    name, _, preset = str(label).partition(":")
    engine = get_engine(name)
    if preset:
        engine.preset(preset)
    known = {f.name for f in fields(engine.Settings)}
    given = {k: (tuple(v) if isinstance(v, list) else v) for k, v in (overrides or {}).items() if v is not None}
    if strict:
        refuse_unknown_settings(name, engine.Settings, given)
    else:
        unknown_settings(name, engine.Settings, given)  # a key that is not a name: one line, strict or not
    mine = {k: v for k, v in given.items() if k in known}
    return EngineChoice(name, tuple(sorted(mine.items())), preset)


def resolve(label: str, overrides: dict | None = None):
    """(Engine, Settings) of "ENGINE" or "ENGINE:PRESET" with those `overrides` the engine
    has: `choose(label, overrides).settings()` with the engine beside it."""
    choice = choose(label, overrides)
    return get_engine(choice.engine), choice.settings()


def runs_here(label: str) -> bool:
    """Are the engine's runs kept in this process, even when a cluster is at hand? The
    analytic engines' are (their impacts are exact events; a run takes milliseconds to a
    second, and the compiled kernel is loaded here already); a contact engine's go to the
    cluster's workers. The one predicate the executor's callers ask. An engine that
    cannot be imported here stays here too, where its failure is reported."""
    try:
        return get_engine(str(label).partition(":")[0]).capabilities.exact_impacts
    except ImportError:
        return True

def presets_of(name: str) -> dict:
    """Every preset of engine `name`: preset → {"reason": its one line, "settings": every
    setting's value, "differs": the names of those that differ from the engine's default}.
    An engine whose package cannot be imported here (an optional extra not installed) is an
    InputError saying what to install."""
    try:
        engine = get_engine(name)
    except EngineUnavailable:
        raise  # says it already, in one line
    except ImportError as e:
        raise InputError(f"engine = {name!r}: cannot be loaded here ({e})") from None
    default = asdict(engine.settings())
    out = {}
    for preset, make in engine.spec.presets.items():
        values = asdict(make())
        out[preset] = {"reason": getattr(make, "reason", ""), "settings": values,
                       "differs": [k for k, v in values.items() if default.get(k) != v]}
    return out


def campaign_engines() -> tuple[str, ...]:
    """The registered engines fast enough for grids of thousands of runs that can be
    imported here: what bench and stress run unless told otherwise."""
    out = []
    for name in DISTINCT_ENGINES:
        try:
            if get_engine(name).capabilities.campaigns:
                out.append(name)
        except ImportError:
            continue
    return tuple(out)


def settings_used(settings, system, duration: float | None = None):
    """The settings a run of `system` (and of `duration` s) steps with: an engine whose
    settings follow the system (`for_system`: MuJoCo's, PyBullet's and Drake's step and
    contact) derives them; any other uses them as given. Work bounds, estimates and reports
    read these, not the settings as given."""
    return settings.for_system(system, duration) if hasattr(settings, "for_system") else settings


def check_carries(choice: EngineChoice, systems, duration: float) -> None:
    """Every bound the engine of `choice` puts on each of `systems` for runs of `duration`
    s, before any work (one line naming the field otherwise): the isolator it carries, its
    own (EngineSpec.check_system: MuJoCo's representable masses, PyBullet's mass ratio and
    control step against the isolator), and the steps its settings take on the
    fastest-rocking system (analytic/limits.py). What `run` asks of its one system, asked by a
    campaign of its grid and by `design --check` of every system it may pick."""
    systems = list(systems)
    engine = get_engine(choice.engine)
    settings = choice.settings()
    # an engine whose step follows the block (MuJoCo's, PyBullet's) takes the most steps on
    # the fastest-rocking one: its steps are the bound
    fastest = max(systems, key=lambda system: system.rocking_rate)
    check_settings(settings_used(settings, fastest, duration), duration)
    for system in systems:
        engine.check_isolator(system)
        if engine.spec.check_system is not None:
            engine.check_system(system, settings_used(settings, system, duration))


def describe_settings(settings, system=None, duration: float | None = None) -> dict:
    """Every setting a run used, as plain values, with those derived from them (properties,
    e.g. PyBullet's control step); for an engine whose settings follow the system
    (`for_system`: MuJoCo's and PyBullet's step and contact), the numbers derived for
    `system` (and a run of `duration` s: MuJoCo's step divides it), which is what the run
    used."""
    if system is not None:
        settings = settings_used(settings, system, duration)
    out = asdict(settings) if is_dataclass(settings) else {}
    for name in dir(type(settings)):
        if isinstance(getattr(type(settings), name, None), property):
            out[name] = getattr(settings, name)
    return out


def engine_label(name: str) -> str:
    """The name figures and reports show; an engine that is not registered or cannot be
    imported here shows its name."""
    if name not in ENGINE_MODULES:
        return name
    try:
        return get_engine(name).label
    except ImportError:
        return name
