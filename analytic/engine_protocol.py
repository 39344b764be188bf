"""The engine protocol: what every engine package hands the registry
(`isorock.validate.core.engines`), so that commands, figures and reports loop over engines
without knowing their names.

An engine package exposes one `ENGINE = EngineSpec(...)`. Its `simulate` takes
(system, motion, *, settings, duration, theta0 (rad), progress) and returns either the
shared `Trajectory` (an engine whose impacts are exact events, the analytic model) or a
`RawHistory` (a contact engine), which the registry measures the same way for every
engine. A third engine is one new package plus one registry line.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable, Protocol

if TYPE_CHECKING:  # the registry loads this module for every command: keep it light
    from .motion import GroundMotion
    from .system import System
    from .trajectory import RawHistory, Trajectory


class Simulate(Protocol):
    def __call__(self, system: System, motion: GroundMotion | None = None, *, settings: Any = None,
                 duration: float | None = None, theta0: float = 0.0,
                 progress: Callable[[float, float], None] | None = None) -> Trajectory | RawHistory: ...


@dataclass(frozen=True)
class Capabilities:
    """What an engine supports. isolated_base: the spring–dashpot base (every engine
    here); past_alpha: it simulates beyond |θ| = α (model.md, "Past α"); batch: it runs
    many cases in one call (`simulate_batch`); exact_impacts: its impacts are located as
    events of the rigid model, not measured from a contact history; campaigns: it is fast
    enough for grids of thousands of runs (bench and stress run it unless told otherwise)."""

    isolated_base: bool = True
    past_alpha: bool = True
    batch: bool = False
    exact_impacts: bool = False
    campaigns: bool = True


@dataclass(frozen=True)
class Tuning:
    """The contact parameters of an engine a calibration may move: `names` of the
    coordinates, their `bounds` (in the coordinates' own, possibly logarithmic, scale),
    `start(settings)` the coordinates of given settings, `apply(settings, x)` the settings
    at coordinates x (everything else kept)."""

    names: tuple[str, ...]
    bounds: tuple[tuple[float, float], ...]
    start: Callable[[Any], list]
    apply: Callable[[Any, Any], Any]


@dataclass(frozen=True)
class EngineSpec:
    """One engine. `settings_type` is its frozen Settings dataclass (validated on
    construction); `settings_for(**overrides)` builds one where some settings follow
    others (default: the dataclass with the overrides); `scene_text(system, settings)`
    is the model file a user can open, `scene_format` its format and suffix (None: no
    file); `label` is the name figures and reports show; `presets` maps a name a user
    can ask for as ENGINE:PRESET to a zero-argument callable returning Settings;
    `ladder(quick)` lists (label, Settings) from cheapest to most accurate, for
    work-precision benchmarks; `tuning` is what `isorock calibrate` may move;
    `simulate_many(runs, *, settings, threads)` (optional) runs many (system, motion,
    duration, theta0) at once, each result what `simulate` returns for it alone or the
    exception it raised (without it, the registry runs them one by one);
    `replay_scene(system)` (optional) is (model, pose(u, θ) → joint positions): a scene of
    the engine's viewer in which any engine's history can be replayed (`isorock view`)."""

    name: str
    label: str
    settings_type: type
    simulate: Simulate
    capabilities: Capabilities = Capabilities()
    settings_for: Callable[..., Any] | None = None
    scene_text: Callable[..., str] | None = None
    scene_format: tuple[str, str] | None = None  # (format name, file suffix)
    presets: dict = field(default_factory=dict)
    ladder: Callable[[bool], list] | None = None
    tuning: Tuning | None = None
    simulate_many: Callable[..., list] | None = None
    replay_scene: Callable[..., tuple] | None = None

    def settings(self, **overrides):
        if self.settings_for is not None:
            return self.settings_for(**overrides)
        return replace(self.settings_type(), **overrides)


__all__ = ["EngineSpec", "Capabilities", "Simulate", "Tuning"]
