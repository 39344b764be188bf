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

import math
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Callable, Mapping, Protocol

from . import limits  # its checks read through the module: a test stubs limits.check_acceleration
from .errors import InputError, real_number, require, require_positive_finite
from .system import System

#: model.md's counting rule: an impact counts when its half-cycle's peak |θ| exceeds this
#: fraction of α. Here, in the light module every engine and the registry load, so that it
#: has one home.
DEFAULT_IMPACT_THRESHOLD = 0.01


def contact_scale(system: "System", time: float, share: float) -> float:
    """The factor by which a contact engine multiplies a default `time` of its contact (s: a
    contact time constant, a physics step) so that time·p_eff = `share`: every block then
    meets the same contact in units of its own rocking time 1/p_eff (System.rocking_rate),
    as the similarity law of the rigid model asks (tests/test_similarity.py)."""
    return share / (time * system.rocking_rate)


if TYPE_CHECKING:  # the registry loads this module for every command: keep it light
    from .motion import GroundMotion
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
    enough for grids of thousands of runs (bench and stress run it unless told otherwise);
    isolators: the isolator kinds it carries (System.isolator_kind; every engine the
    linear one, both analytic paths every kind, MuJoCo and PyBullet all but the cone, Drake the
    pendulums: docs/isolators.md). Any other is
    refused with one line, never run as linear. kinetic_friction: it carries a statue whose
    kinetic friction is below its static one (System.kinetic_friction < friction); an engine
    with one friction coefficient refuses such a System with one line (check_friction),
    never runs it at either coefficient."""

    isolated_base: bool = True
    past_alpha: bool = True
    batch: bool = False
    exact_impacts: bool = False
    campaigns: bool = True
    isolators: tuple[str, ...] = ("linear",)
    kinetic_friction: bool = True
    #: it carries a statue that may slip on its base (System.friction: docs/sliding.md), and a
    #: vertical ground motion (GroundMotion.vertical): every engine here does; an engine a
    #: package registers may not, and is then refused such a run in one line, never runs it
    #: as a statue that cannot slip or on level ground
    statue_friction: bool = True
    vertical: bool = True
    #: it carries a statue of two different tipping edges (System.body: issue 36, the planar
    #: model of a real shape): the analytic engines; a contact engine that builds the box H × B
    #: is refused such a System in one line (check_body), never runs the box in its place
    two_edges: bool = False
    #: it carries a second horizontal ground-motion component (GroundMotion.transverse: a record
    #: pair, issue 36): MuJoCo's, PyBullet's, Drake's and DART's scenes, whose body may leave the plane
    #: (Drake puts its block on a free body for a pair); a planar model, or a contact engine on planar
    #: joints, is refused such a motion in one line (check_transverse),
    #: never runs the first component alone in its place
    transverse: bool = False
    #: the isolator kinds it carries under two horizontal components: the linear one (the same
    #: k and c along x and y) unless its scene builds another's friction in the plane (MuJoCo's,
    #: PyBullet's and Drake's: the pendulums', isolator_parts.PLANE_ISOLATORS); any other is refused in one line
    transverse_isolators: tuple[str, ...] = ("linear",)


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
class Preset:
    """A named family of an engine's settings (ENGINE:PRESET) and why it is there, in one
    line: `reason` is what `isorock presets` shows beside the settings, so it is data, not
    a comment. Called, it returns the Settings (`make()`), as a plain factory would."""

    reason: str
    make: Callable[[], Any]

    def __call__(self):
        return self.make()


@dataclass(frozen=True)
class Facet:
    """A tool's optional part of an engine, declared by the tool that uses it (`declare_facet`):
    its `name` (the key of EngineSpec.facets), who uses it and what the value is. An engine without
    it is simply not offered what that tool does with it (bench's ladder, calibrate's tuning, …)."""

    name: str
    used_by: str
    what: str

    def of(self, spec: "EngineSpec"):
        """spec's value of this facet, or None."""
        return spec.facets.get(self.name)


#: every facet declared by the tools imported so far: name → Facet (tests/test_engine_facets.py
#: imports every tool and holds each engine's facets to it)
FACETS: dict[str, Facet] = {}


def declare_facet(name: str, used_by: str, what: str) -> Facet:
    """The Facet `name`, declared once (a tool module's import); declared again with another
    meaning is a programming error."""
    facet = FACETS.setdefault(name, Facet(name, used_by, what))
    if facet != Facet(name, used_by, what):
        raise ValueError(f"facet {name!r} declared twice: by {facet.used_by} and by {used_by}")
    return facet


@dataclass(frozen=True, init=False)
class EngineSpec:
    """One engine: the narrow protocol every command relies on, and the optional parts single
    tools use, apart.

    The protocol: `name`; `label`, the name figures and reports show; `settings_type`, its frozen
    Settings dataclass (validated on construction); `simulate` (Simulate); `capabilities`, what it
    carries (anything else is refused in one line before any work); `presets`, a name a user can
    ask for as ENGINE:PRESET → a `Preset` (its one-line reason, and a zero-argument callable
    returning Settings); `settings_for(system=…, **overrides)`, the settings that follow the
    system (default: the dataclass with the overrides); `check_system(system, settings)`, which
    raises an InputError naming the field for a System it cannot carry with those (derived)
    settings, beyond the checks every engine shares (MuJoCo: a body below mjMINVAL; PyBullet: a
    base too light, an isolator too stiff for its control step), asked before any work;
    `tolerances` (an engine a package registers), its limits, each with its reason.

    `facets`: name → value, the parts a tool uses, each declared by that tool (`declare_facet`,
    FACETS; docs/plugins.md lists them): the registry's batch path (`simulate_many`), the scene
    file (`scene_text`, `scene_format`), bench's work-precision ladder (`ladder`) and step cost
    (`step_cost`), calibrate's `tuning`, view's `replay_scene`, experiments' `simulate_body`. They
    may also be given as keywords: `EngineSpec(..., ladder=f)` is `facets={"ladder": f}`."""

    name: str
    label: str
    settings_type: type
    simulate: Simulate
    capabilities: Capabilities = Capabilities()
    presets: dict = field(default_factory=dict)
    settings_for: Callable[..., Any] | None = None
    check_system: Callable[..., None] | None = None
    #: an engine a package registers (docs/plugins.md) brings its own limits: metric → an object
    #: with `limit`, `reason` and `kind` ("max", "min", "equal"; validate.core.tolerances.Tolerance),
    #: judged like the table's rows; the built-in engines' are in the table itself
    tolerances: dict = field(default_factory=dict)
    facets: Mapping[str, Any] = field(default_factory=dict)

    def __init__(self, name: str, label: str, settings_type: type, simulate: Simulate,
                 capabilities: Capabilities = Capabilities(), presets: dict | None = None,
                 settings_for: Callable[..., Any] | None = None, check_system: Callable[..., None] | None = None,
                 tolerances: dict | None = None, facets: Mapping[str, Any] | None = None, **more_facets):
        values = dict(name=name, label=label, settings_type=settings_type, simulate=simulate,
                      capabilities=capabilities, presets=dict(presets or {}), settings_for=settings_for,
                      check_system=check_system, tolerances=dict(tolerances or {}),
                      # a facet given as None is one the engine does not have
                      facets=MappingProxyType({k: v for k, v in {**dict(facets or {}), **more_facets}.items()
                                               if v is not None}))
        for key, value in values.items():
            object.__setattr__(self, key, value)

    def settings(self, **overrides):
        if self.settings_for is not None:
            return self.settings_for(**overrides)
        return replace(self.settings_type(), **overrides)


#: A rigid body of the simulate_body facet (experiments/study.py) whose tilt from its resting orientation passes
#: this (rad) has overturned: well past any rocking edge's α of the measured rocks (≤ 0.41
#: rad), where no granite rock comes back. One rule for every engine's hull scene.
BODY_OVERTURN_TILT = 1.0


#: seconds simulated after the motion ends, and without any motion (free rocking)
TAIL_AFTER_MOTION = 5.0
FREE_DURATION = 10.0


def run_inputs(system: "System", motion: "GroundMotion | None", duration: float | None, theta0: float,
               impact_threshold: float, *, theta_dot0: float = 0.0, u0: float = 0.0,
               u_dot0: float = 0.0, settings=None, isolators: tuple[str, ...] = ("linear",),
               kinetic_friction: bool = True, two_edges: bool = False,
               transverse: bool = False, transverse_isolators: tuple[str, ...] = ("linear",)
               ) -> tuple[GroundMotion, float]:
    """What every engine's `simulate` takes, checked in one place so that all engines
    accept and refuse the same inputs with the same messages: (motion, duration) after the
    shared checks: `none` motion is zero ground
    acceleration; the default duration is the motion's end + 5 s, or 10 s without motion;
    θ0 (rad) must be a finite tilt below α; the counting threshold in [0, 1). The work
    bounds of analytic.limits: the motion's peak acceleration, the duration, the isolator periods it spans and, when the
    engine's `settings` are given, the steps they imply. `isolators`: the isolator kinds the
    calling engine carries (Capabilities.isolators): a System on another is refused, so
    that no engine runs a friction pendulum or a bilinear bearing as a linear spring;
    `kinetic_friction` (Capabilities.kinetic_friction) False: a statue whose kinetic friction
    is below its static one is refused too (check_friction); `two_edges`
    (Capabilities.two_edges) False: a statue of two different edges is refused (check_body);
    `transverse` (Capabilities.transverse) False: a motion of two horizontal components is
    refused (check_transverse), and so is one on an isolator not in `transverse_isolators`
    (Capabilities.transverse_isolators)."""
    from .motion import GroundMotion  # lazy: motion loads NumPy, and every command loads this module
    require(isinstance(system, System), "system", system, "a System")
    # the initial state and the counting threshold as numbers first: a str, None or a list
    # given from Python met math.isfinite below as a TypeError
    theta0, theta_dot0, u0, u_dot0 = (real_number(name, v, "a finite number") for name, v in (
        ("theta0", theta0), ("theta_dot0", theta_dot0), ("u0", u0), ("u_dot0", u_dot0)))
    impact_threshold = real_number("impact_threshold", impact_threshold, "a number in [0, 1)")
    check_isolator_kind(system, isolators)
    check_friction(system, kinetic_friction)
    check_body(system, two_edges)
    motion = motion or GroundMotion.zero()
    limits.check_acceleration("motion", motion.pga_g, f" ({motion.name or 'its peak'})")
    if motion.vertical is not None:  # the vertical component is bounded as the horizontal is
        limits.check_acceleration("vertical", motion.vertical.pga_g, f" ({motion.vertical.name or 'its peak'})")
    check_transverse(system, motion, transverse, isolators=transverse_isolators)
    given = duration is not None
    if not given:
        duration = FREE_DURATION if motion.is_zero else motion.last_time + TAIL_AFTER_MOTION
    duration = require_positive_finite("duration", duration)
    limits.check_duration("duration", duration, "" if given else f" (the motion's end + {TAIL_AFTER_MOTION:g} s)")
    limits.check_isolator(system, duration)
    limits.check_settings(settings, duration)
    side_alpha = system.edge_alpha(1 if theta0 >= 0 else -1) if math.isfinite(theta0) else system.alpha
    require(math.isfinite(theta0) and abs(theta0) < side_alpha, "theta0", theta0,
            f"a finite tilt smaller than α = {side_alpha:.6g} rad in magnitude (of the edge it tilts onto)")
    for name, v in (("theta_dot0", theta_dot0), ("u0", u0), ("u_dot0", u_dot0)):
        require(math.isfinite(v), name, v, "a finite number")
    if system.fixed_base:
        require(u0 == 0 and u_dot0 == 0, "u0/u_dot0", (u0, u_dot0), "zero on a fixed base")
    require(0 <= impact_threshold < 1, "impact_threshold", impact_threshold, "in [0, 1)")
    # a stepping engine samples the ground motion once per (control) step: a pulse that
    # ends within two of them is lost, or reduced to one sample, without a word
    step = getattr(settings, "control_step", None) or getattr(settings, "timestep", None)
    if step and motion.pulse is not None and not motion.is_zero and motion.end_time < 2 * step:
        raise InputError(f"motion = {motion.name or 'pulse'}: lasts {motion.end_time:.3g} s, less than two of this "
                         f"engine's steps ({step:g} s): it would be lost; a longer pulse or a shorter --timestep")
    return motion, duration


def check_isolator_kind(system: "System", isolators: tuple[str, ...], engine: str = "this engine") -> None:
    """One line refusing a System whose isolator `engine` does not carry (Capabilities.isolators)."""
    kind = system.isolator_kind
    if kind not in isolators:
        raise InputError(f"isolator = {kind}: {engine} carries the {', '.join(isolators)} isolator only, not a "
                         f"{kind} one (engine 'analytic-reference' carries it; docs/isolators.md)")


def check_transverse(system: "System", motion: "GroundMotion", transverse: bool, engine: str = "this engine",
                     isolators: tuple[str, ...] = ("linear",)) -> None:
    """One line refusing a second horizontal component (GroundMotion.transverse) for an engine
    that does not carry it, and for an isolator whose two directions its scene does not build
    (`isolators`, Capabilities.transverse_isolators): the linear one is isotropic with the same
    k and c along x and y; a pendulum's dry friction in the plane only where the scene makes it
    isotropic (MuJoCo's and PyBullet's); a bearing's coupled 2-D yielding is not built (issue 36)."""
    if motion.transverse is None:
        return
    if not transverse:
        raise InputError(f"transverse = {motion.transverse.name or 'a second component'}: {engine} runs one "
                         "horizontal component only (engines 'mujoco', 'bullet', 'drake' and 'dart' carry two)")
    if not system.fixed_base and system.isolator_kind not in isolators:
        others = (" (engines 'mujoco', 'bullet' and 'drake' carry the friction pendulum and the ball in a bowl too)"
                  if isolators == ("linear",) else "")
        raise InputError(f"isolator = {system.isolator_kind}: with two horizontal components must be "
                         f"{' or '.join(isolators)} or a fixed base{others}")
    limits.check_acceleration("transverse", motion.transverse.pga_g, f" ({motion.transverse.name or 'its peak'})")


def check_body(system: "System", two_edges: bool, engine: str = "this engine") -> None:
    """One line refusing a statue of two different tipping edges (System.body) for an engine
    that builds the box H × B (Capabilities.two_edges False)."""
    if system.body is not None and not two_edges:
        raise InputError(f"body: {engine} builds the symmetric box H × B; a statue of two different edges "
                         f"(b₊ {system.body.lever_forward:.4g} m, b₋ {system.body.lever_backward:.4g} m) runs on the "
                         "analytic engines (Capabilities.two_edges; docs/statues.md)")


def check_friction(system: "System", kinetic_friction: bool, engine: str = "this engine", *,
                   statue_friction: bool = True) -> None:
    """One line refusing a statue whose kinetic friction is below its static one, for an engine
    with one friction coefficient (Capabilities.kinetic_friction False: MuJoCo's and PyBullet's
    contacts; Drake's discrete plant): run at μ_s it would slide too far, at μ_k start too early.
    And a statue that may slip at all, for an engine that carries none (statue_friction False)."""
    if not statue_friction and system.friction is not None:
        raise InputError(f"friction = {system.friction!r}: {engine} carries a statue that cannot slip on its base only "
                         "(Capabilities.statue_friction)")
    if kinetic_friction or system.friction is None or system.kinetic_friction == system.friction:
        return
    raise InputError(f"kinetic_friction = {system.kinetic_friction!r}: {engine} has one friction coefficient, "
                     f"it cannot carry a kinetic one below friction = {system.friction!r} (the analytic engines and "
                     "Drake's continuous plant carry both; or give kinetic_friction equal to friction)")


def contact_friction(system: "System", own: float) -> float:
    """The friction coefficient of a contact engine's block–base contact: the statue's
    (System.friction, its static one) when it has one, else the engine's own setting, which
    keeps a statue that cannot slip from slipping (docs/sliding_engines.md)."""
    return own if system.friction is None else system.friction


__all__ = ["check_friction", "check_isolator_kind", "contact_friction", "DEFAULT_IMPACT_THRESHOLD", "EngineSpec", "Capabilities", "Simulate", "Tuning", "run_inputs", "TAIL_AFTER_MOTION", "FREE_DURATION"]
