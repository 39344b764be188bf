"""`isorock atlas`: the contact-model atlas. For each engine and preset, the
effective β error and the first-impact time error of free rocking over a grid of
slenderness λ = H/B × mass ratio μ = m/m_b (0: a fixed base) × size H, with the cost in
simulated seconds per wall second: which contact formulation reproduces the impact law,
where, and at which cost.

Every cell is one free-rocking run from θ0 = FREE_THETA0_OVER_ALPHA·α, measured as every
contact run is (validate.measure). Its β is judged on the impacts the report judges free
rocking by (report_run.beta_impacts: the first ≤ 3 that peaked above 0.1α), chosen in the
rigid model's history and matched by their order among the engine's counted impacts (so
an impact whose peak sits at 0.1α is judged in every engine or in none). The oracles are the
closed forms of model.md: β(λ, μ) (analytic.coefficients) on every cell, the exact t₁
integral (compare.exact_first_impact_time) on a fixed base; on an isolated base t₁ has no
closed form and the analytic model (its impact an event located to rtol 1e-10) is the
reference. A run that fails, slides, overturns, misses impacts the rigid model has, or
runs past its CPU budget (the executor's Pool stops it) is reported as such in its row and
in the verdict, never as a small error.

Data flow: System (one per cell) → engine → raw history → measure → effective β and t₁
against the oracles (in the worker that ran it) → rows → summaries per preset → verdict,
tables and figures.
"""
from __future__ import annotations

import csv
import io
import math
import statistics
import time
from dataclasses import dataclass

import numpy as np

from ...analytic.coefficients import beta
from ...analytic.errors import InputError
from ...analytic.motion import GroundMotion
from ...analytic.system import PAPER_BLOCK, PAPER_DAMPING_RATIO, PAPER_PERIOD, System, paper_system
from ..core.cases import block_system
from ..core.chunks import worker_pool
from ..core.compare import exact_first_impact_time
from ..core.engines import REFERENCE, campaign_engines, get_engine, resolve
from ..core.executor import default_workers
from ..core.measure import beta_errors
from ..core.runner import Task
from ..core.scenarios import FREE_THETA0_OVER_ALPHA
from ..core.summary import row_of_trajectory
from ..core.tolerances import has_tolerance, limit, tolerance
from ..core.verdict import rate_verdict
from ..io.output import to_json, write_folder_atomic
from ..io.progress import bar_of
from ..io.provenance import provenance
from .atlas_figures import error_map, pareto
from .report_run import beta_impacts

#: Mass ratios are μ = m/m_b (model.md's); 0 is a fixed base. The grid is issue 12's
#: (λ 1.5–10, μ 0 and 0.25–4, H 0.2–5 m) with issue 19's sizes from 0.1 to 10 m.
FULL_SLENDERNESS = (1.5, 2.5, 4.0, 6.0, 10.0)
FULL_MASS_RATIOS = (0.0, 0.25, 1.0, 4.0)
FULL_HEIGHTS = (0.1, 0.2, 1.0, 5.0, 10.0)
#: --quick: 8 cells inside the full grid's range, fixed and isolated, two sizes (the tests'
#: grid: under a minute for every MuJoCo and PyBullet preset on 2 cores).
QUICK_SLENDERNESS = (2.5, 6.0)
QUICK_MASS_RATIOS = (0.0, 1.0)
QUICK_HEIGHTS = (0.5, 2.0)
#: kg/m³: the paper's block's (3800 kg, 2.0 × 0.7 × 0.7 m), so that an engine's absolute
#: contact parameters (Drake's stiffness in N/m, MuJoCo's impedance width in m) meet the
#: mass and size a statue of that shape would have.
DENSITY = PAPER_BLOCK["mass"] / (PAPER_BLOCK["height"] * PAPER_BLOCK["width"] * PAPER_BLOCK["width"])
#: How many of a run's counted impacts it sends back (β error and time of each).
KEPT_IMPACTS = 12
#: A contact run lasts this factor × the time of the reference's last judged impact, plus
#: DURATION_PAD s: room for a contact engine's impacts to come a little late and for the
#: measuring window after the last one.
DURATION_FACTOR, DURATION_PAD = 1.2, 0.1
#: The rigid model rocks down to its last impact above KEPT_AMPLITUDE·α well within this
#: many 1/p (λ 10 on a fixed base, the slowest decay of the grid: about 80 impacts, 90/p).
REFERENCE_SPAN = 400.0
#: ×α: the rigid model's impacts that peak above this must all be counted by a contact run.
KEPT_AMPLITUDE = limit("atlas_kept_impact_amplitude")
#: The first impact within this of its reference for a preset to qualify.
T1_LEVEL = limit("atlas_t1_level")
#: T·p of every isolated cell: the paper's isolator (T 1.5 s) on the paper's block (p 2.64/s).
#: Held in units of the block's own 1/p, so that the cells of one λ and μ at different sizes
#: are one dimensionless case (Dimitrakopoulos & DeJong 2012): an engine that treats every
#: size alike gives them the same errors (the similarity columns).
PERIOD_TIMES_P = PAPER_PERIOD * paper_system().p
#: Worst β error levels of the verdict (issue 12: 0.5% and 0.1%).
LEVELS = (limit("atlas_level_coarse"), limit("atlas_level_fine"))
#: Default CPU-time budget of one run (s): past it the run stops and is reported "too
#: slow" (Drake's continuous plant takes minutes for a second of a 0.2 m block, docs/atlas.md).
#: CPU time, not wall time: on a shared machine the wall clock would judge the other jobs.
RUN_BUDGET = 300.0
#: The row status of a run whose β is judged.
OK = "ok"


@dataclass(frozen=True)
class Grid:
    slenderness: tuple[float, ...]
    mass_ratios: tuple[float, ...]
    heights: tuple[float, ...]
    #: the statue's friction μ_s (docs/sliding.md); None: it cannot slip (the grid as before)
    frictions: tuple[float | None, ...] = (None,)

    def cells(self) -> list["Cell"]:
        return [Cell(lam, mu, h, f) for f in self.frictions for mu in self.mass_ratios for h in self.heights
                for lam in self.slenderness]

    def describe(self) -> dict:
        out = {"slenderness": list(self.slenderness), "mass_ratios": list(self.mass_ratios),
               "heights_m": list(self.heights)}
        if self.frictions != (None,):
            out["frictions"] = list(self.frictions)
        return out


FULL = Grid(FULL_SLENDERNESS, FULL_MASS_RATIOS, FULL_HEIGHTS)
QUICK = Grid(QUICK_SLENDERNESS, QUICK_MASS_RATIOS, QUICK_HEIGHTS)

#: A user's grid (--slenderness, --mass-ratios, --heights): each axis's allowed range, with
#: why. λ from 1 (a square block; a squatter one slides rather than rocks, docs/atlas.md) to
#: 100; μ 0 (a fixed base) or a base from a hundredth to a hundred times the block's mass
#: (the paper's isolated statues sit at 0.25–4); H from 1 cm to 100 m (a statue to a tower).
AXES = {"slenderness": ("slenderness", (1.0, 100.0), "λ = H/B", "3,8"),
        "mass_ratios": ("mass ratio", (0.01, 100.0), "μ = m/m_b, 0 for a fixed base", "0,0.5"),
        "heights": ("height", (0.01, 100.0), "H, m", "0.3,3"),
        # the statue's friction μ_s (docs/sliding.md), "none" for no slip: from a polished plinth
        # to a coefficient no landing's impulse exceeds (System.friction's range)
        "frictions": ("friction", (0.01, 10.0), "the statue's μ_s, or none for no slip", "0.1,0.3,none")}
#: Values per axis and cells in all: four times the full grid's 60 cells, each run by every
#: preset asked for (minutes per preset on 2 cores for the full grid, docs/atlas.md).
MAX_AXIS_VALUES, MAX_CELLS = 20, 240


def axis_values(option: str, text: str) -> tuple[float, ...]:
    """One axis of a user's grid from "0.3,3": distinct numbers in the axis's range (AXES),
    at most MAX_AXIS_VALUES, sorted; anything else is an InputError naming the option,
    the value and what is allowed."""
    name, (lo, hi), meaning, example = AXES[option]
    flag = "--" + option.replace("_", "-")
    allowed = (f"comma-separated numbers from {lo:g} to {hi:g}" + (" or 0" if option == "mass_ratios" else "")
               + f" ({meaning}), e.g. {flag} {example}")
    items = [x.strip() for x in str(text).split(",")]
    values = []
    for item in items:
        if option == "frictions" and item.lower() == "none":
            values.append(None)
            continue
        try:
            x = float(item)
        except ValueError:
            raise InputError(f"{flag} = {text!r}: {item!r} is not a number; must be {allowed}") from None
        if not (lo <= x <= hi or (option == "mass_ratios" and x == 0.0)):
            raise InputError(f"{flag} = {text!r}: {name} {item} is out of range; must be {allowed}")
        values.append(x)
    if len(set(values)) != len(values):
        dup = next(x for x in values if values.count(x) > 1)
        raise InputError(f"{flag} = {text!r}: lists {'none' if dup is None else f'{dup:g}'} twice; each value once "
                         "(a repeat runs its cells twice)")
    if len(values) > MAX_AXIS_VALUES:
        raise InputError(f"{flag} = {text!r}: {len(values)} values; must be at most {MAX_AXIS_VALUES}")
    return tuple(sorted(values, key=lambda x: math.inf if x is None else x))


def user_grid(base: Grid, *, slenderness: str | None = None, mass_ratios: str | None = None,
              heights: str | None = None, frictions: str | None = None) -> Grid:
    """`base` with each axis the user gave replaced by theirs (axis_values), at most
    MAX_CELLS cells in all."""
    given = {"slenderness": slenderness, "mass_ratios": mass_ratios, "heights": heights, "frictions": frictions}
    axes = {k: (axis_values(k, v) if v is not None else getattr(base, k)) for k, v in given.items()}
    grid = Grid(**axes)
    n = len(grid.cells())
    if n > MAX_CELLS:
        raise InputError(f"--slenderness × --mass-ratios × --heights × --frictions = {len(grid.slenderness)} × "
                         f"{len(grid.mass_ratios)} × {len(grid.heights)} × {len(grid.frictions)} = {n} cells: "
                         f"must be at most {MAX_CELLS}")
    return grid


@dataclass(frozen=True)
class Cell:
    """One system of the grid: λ = H/B, μ = m/m_b (0: fixed base), H in m; a square
    footprint B × B of DENSITY, on the paper's isolator when μ > 0."""

    slenderness: float
    mass_ratio: float
    height: float
    friction: float | None = None  # the statue's μ_s (None: it cannot slip)

    def system(self):
        width = self.height / self.slenderness
        mass = DENSITY * self.height * width * width
        p = System.fixed(height=self.height, width=width, mass=mass).p
        return block_system(height=self.height, slenderness=self.slenderness, mass=mass,
                            mass_ratio=self.mass_ratio, period=PERIOD_TIMES_P / p, friction=self.friction)

    @property
    def key(self) -> tuple:
        return (self.slenderness, self.mass_ratio, self.height) + (() if self.friction is None else (self.friction,))


def peak_betas(traj) -> list[float]:
    """Effective β of each counted impact read from the rocking peaks on either side of it:
    the half-cycle's energy before and after it, on a fixed base
    cos(α − θp) − cos α ∝ θ̇² at θ = 0, so β = √[(cos(α − θp⁺) − cos α)/(cos(α − θp⁻) − cos α)].
    Where the statue may slip (a friction cell) the rigid map of a contact engine's states
    to θ = 0 no longer holds (its pivot may slide after the impact); the peaks are read alike
    from every engine's history and the exact model's, and compared with each other."""
    a = traj.alpha
    amps = [i.amplitude for i in traj.counted_impacts]

    def energy(p):
        return np.cos(a - p) - np.cos(a)
    return [float(np.sqrt(energy(amps[k + 1]) / energy(amps[k]))) for k in range(len(amps) - 1)]


# --- the reference of each cell -------------------------------------------------------

def reference(cell: Cell) -> dict:
    """What the cell's runs are judged against: the closed-form β, t₁ (closed form on a
    fixed base, the analytic model on an isolated one), which of the counted impacts β is
    judged on (their order in the rigid model's history), and how long a contact run must
    last to show them."""
    system = cell.system()
    theta0 = FREE_THETA0_OVER_ALPHA * system.alpha
    rigid = get_engine(REFERENCE).simulate(system, None, duration=REFERENCE_SPAN / system.p, theta0=theta0)
    judged = beta_impacts(rigid)
    if not judged:  # every λ ≥ 1.5 rocks on: a grid cell without impacts is a broken reference
        raise RuntimeError(f"the analytic model gives no impact to judge β by for {cell}")
    impacts = rigid.counted_impacts
    order = [k for k, i in enumerate(impacts) if any(i is j for j in judged)]
    kept = [k for k, i in enumerate(impacts) if i.amplitude > KEPT_AMPLITUDE * system.alpha]
    last = max(order[-1], kept[-1] if kept else 0)
    # a contact run must have counted as many impacts by then: half a half-cycle past the
    # rigid model's last kept impact, room for its impacts to come a little early or late
    kept_by = impacts[last].t + 0.5 * (impacts[last].t - (impacts[last - 1].t if last else 0.0))
    # without slip, the closed forms; where the statue may slip, the exact model's own history
    # (its impacts may slip, and its pivot slide: docs/sliding.md)
    fixed = system.fixed_base and cell.friction is None
    slips = cell.friction is not None
    return {"system": system, "theta0": theta0, "beta_closed": beta(system.slenderness, system.mu),
            "beta_reference": peak_betas(rigid) if slips else None,
            "beta_from": "the rocking peaks, against the exact model's" if slips else "the closed form",
            "judged_impacts": order, "impacts_expected": len(order),
            # every impact up to the rigid model's last one above KEPT_AMPLITUDE·α must be counted
            "impacts_kept": last + 1, "impacts_kept_by": kept_by,
            "t1_reference": exact_first_impact_time(system, theta0) if fixed else impacts[0].t,
            "t1_reference_from": "closed form" if fixed else "analytic model",
            "duration": DURATION_FACTOR * impacts[last].t + DURATION_PAD}


# --- one run, in whichever process runs it ---------------------------------------------

def run_cell(task) -> dict:
    """One engine on one cell, measured where it ran (a worker of the executor's Pool, which
    stops it at its CPU budget). Every way a run can end is a result: its status says how
    (the rows judge it, `judge`)."""
    # loaded before the clock: a worker's first run would otherwise pay for the imports
    out = {"status": "error", "message": "", "sim_s": 0.0, "loop_s": math.nan}
    try:
        engine, settings = resolve(task.engine, task.overrides)  # imports the engine's package
    except Exception as e:
        return dict(out, message=f"{type(e).__name__}: {e}", wall_s=0.0, cpu_s=0.0)
    start, cpu = time.perf_counter(), time.process_time()
    try:
        traj = engine.simulate(task.system, task.motion, settings=settings, duration=task.duration,
                               theta0=task.theta0)
    except InputError as e:  # the engine refuses this system (e.g. an isolator too stiff for it)
        out.update(status="refused", message=str(e))
    except Exception as e:  # an engine that raises on one cell: that cell's result
        out.update(status="error", message=f"{type(e).__name__}: {e}")
    else:
        counted = traj.counted_impacts
        out.update(row_of_trajectory(traj))  # the one summary row every table shares, then the atlas's own
        slips = task.system.friction is not None
        out.update(status=str(traj.status), message=traj.message or "",
                   sim_s=float(traj.t[-1]) if len(traj.t) else 0.0, loop_s=float(traj.runtime_s),
                   impacts_counted=len(counted),
                   beta_errors_counted=None if slips else beta_errors(traj, KEPT_IMPACTS),
                   peak_betas=peak_betas(traj)[:KEPT_IMPACTS] if slips else None,
                   first_impact_time=counted[0].t if counted else None,
                   impact_times=[i.t for i in counted],
                   lift_off_after_impact=traj.extras.get("lift_off_max_after_impact"),
                   pivot_slip=traj.extras.get("pivot_slip_max"))
    out.update(wall_s=time.perf_counter() - start, cpu_s=time.process_time() - cpu)
    return out


def _stopped(outcome, budget: float) -> dict:
    """The measured dict of a run the Pool did not see finish: past its CPU budget ("too
    slow"), or its worker died ("error")."""
    out = {"sim_s": 0.0, "loop_s": math.nan, "wall_s": outcome.seconds}
    if outcome.status == "timeout":
        return dict(out, status="too slow", cpu_s=budget,
                    message=f"stopped after {budget:g} CPU s ({outcome.seconds:.0f} s of wall time)")
    reason = f"its worker died (exit code {outcome.value})" if outcome.status == "crashed" else str(outcome.value)
    return dict(out, status="error", cpu_s=math.nan, message=reason)


def judge(measured: dict, ref: dict) -> tuple[str, str]:
    """(status, note) of a run: OK only when it completed with every impact the rigid model
    has and a finite β error; otherwise the word that says what happened."""
    status = measured["status"]
    if status != "completed":
        return status, measured.get("message", "")
    errors = judged_errors(measured, ref)
    if errors is None:
        return "missing impacts", (f"{measured['impacts_counted']} counted impacts; β is judged on impacts "
                                   f"{', '.join(str(k + 1) for k in ref['judged_impacts'])} of the rigid model's "
                                   "(the contact took the energy, or the block stopped rocking)")
    if not all(map(math.isfinite, errors)):
        return "unmeasured", "an impact's states could not be mapped to θ = 0 with the rigid equations"
    return OK, ""


def judged_errors(measured: dict, ref: dict) -> list[float] | None:
    """β errors of the run's counted impacts in the places the reference judges; None when
    the run has fewer counted impacts than that. A friction cell's are its peak β against the
    exact model's (peak_betas)."""
    if ref.get("beta_reference") is not None:
        mine, theirs = measured.get("peak_betas") or [], ref["beta_reference"]
        if len(mine) <= max(ref["judged_impacts"]) or len(theirs) <= max(ref["judged_impacts"]):
            return None
        return [mine[k] / theirs[k] - 1 for k in ref["judged_impacts"]]
    errors = measured.get("beta_errors_counted") or []
    if len(errors) <= max(ref["judged_impacts"]):
        return None
    return [errors[k] for k in ref["judged_impacts"]]


def row(label: str, cell: Cell, ref: dict, measured: dict) -> dict:
    """One CSV row: the cell, the run's status and its errors against the oracles, the cost."""
    status, note = judge(measured, ref)
    name, _, preset = label.partition(":")
    system = ref["system"]
    t1 = measured.get("first_impact_time")
    judged = status == OK
    errors = judged_errors(measured, ref) if judged else None
    return {
        "engine": label, "engine_name": name, "preset": preset or "default",
        "slenderness": cell.slenderness, "mass_ratio": cell.mass_ratio, "height": cell.height,
        "friction": cell.friction,
        "width": system.width, "mass": system.mass, "base": "fixed" if system.fixed_base else "isolated",
        "status": status, "note": note,
        "beta_closed": ref["beta_closed"], "beta_from": ref["beta_from"],
        # signed, the impact of largest |error|; only for a judged run (others are no error at all)
        "beta_error": max(errors, key=abs) if errors else None,
        "impacts_counted": measured.get("impacts_counted"), "impacts_judged": ref["impacts_expected"],
        "impacts_kept": ref["impacts_kept"],
        # impacts of the rigid model above KEPT_AMPLITUDE·α the run did not count
        "impacts_lost": max(0, ref["impacts_kept"] - sum(t <= ref["impacts_kept_by"] for t in
                                                         measured.get("impact_times", []))) if judged else None,
        "first_impact_time": t1, "t1_reference": ref["t1_reference"], "t1_reference_from": ref["t1_reference_from"],
        "t1_error": t1 / ref["t1_reference"] - 1 if judged and t1 is not None else None,
        "sim_s": measured["sim_s"], "loop_s": measured["loop_s"], "wall_s": measured["wall_s"],
        "cpu_s": measured["cpu_s"],
        "lift_off_after_impact": measured.get("lift_off_after_impact"), "pivot_slip": measured.get("pivot_slip"),
        "beta_errors": errors,
    }


COLUMNS = ("engine", "engine_name", "preset", "slenderness", "mass_ratio", "height", "friction", "width", "mass",
           "base", "status", "note", "beta_closed", "beta_from", "beta_error", "impacts_counted", "impacts_judged", "impacts_kept",
           "impacts_lost", "first_impact_time",
           "t1_reference", "t1_reference_from", "t1_error", "sim_s", "loop_s", "wall_s", "cpu_s",
           "lift_off_after_impact", "pivot_slip")


# --- running the atlas ------------------------------------------------------------------

def default_engines() -> list[str]:
    """Every preset of every contact engine fast enough for grids (MuJoCo, PyBullet);
    slower ones (Drake) only by name."""
    out = []
    for name in campaign_engines():
        engine = get_engine(name)
        if not engine.capabilities.exact_impacts:
            out += [f"{name}:{preset}" for preset in engine.spec.presets]
    return out


def distinct(labels: list[str]) -> tuple[list[str], dict, dict]:
    """(labels to run, alias → the label whose settings it shares, label → why not run): a
    preset with the same settings as an earlier one of its engine (mujoco:newton is the
    default) is run once; an engine that cannot be imported here is not run, with the reason."""
    run, aliases, skipped, seen = [], {}, {}, {}
    for label in labels:
        try:
            engine, settings = resolve(label)
        except ImportError as e:
            skipped[label] = f"{type(e).__name__}: {e}"
            continue
        key = (engine.name, settings)
        if key in seen:
            aliases[label] = seen[key]
        else:
            seen[key] = label
            run.append(label)
    return run, aliases, skipped


def build(engines: list[str], grid: Grid, *, workers: int | None = None, budget: float = RUN_BUDGET,
          progress=None, overrides: dict | None = None) -> dict:
    """Run every engine label on every cell; the atlas as a dict (rows, summaries, verdict).
    `overrides`: settings applied to every run that has them (a test's way to break one);
    `progress`: a factory total → bar (io.progress.bar_of), updated as each run ends."""
    labels, aliases, skipped = distinct(engines)
    cells = grid.cells()
    start = time.perf_counter()
    refs = {c.key: reference(c) for c in cells}
    # cell by cell, every preset in turn: the load of a shared machine drifts over a run, and
    # this way it weighs on every preset alike rather than on the ones that ran late
    tasks = [Task(key=(label, c.key), engine=label, system=refs[c.key]["system"], motion=None,
                  duration=refs[c.key]["duration"], theta0=refs[c.key]["theta0"], overrides=dict(overrides or {}))
             for c in cells for label in labels]
    bar = bar_of(progress, len(tasks))
    with worker_pool(default_workers() if workers is None else workers) as executor:
        outcomes = executor.map(run_cell, [(t,) for t in tasks], budget=budget, clock="cpu", progress=bar,
                                note=lambda args: args[0].key[0])
    results = {t.key: (o.value if o.done else _stopped(o, budget),) for t, o in zip(tasks, outcomes)}
    rows = [row(label, c, refs[c.key], results[(label, c.key)][0]) for label in labels for c in cells]
    summaries = [summarize(label, [r for r in rows if r["engine"] == label]) for label in labels]
    tilts = slide_tilts(labels, grid, overrides) if any(f is not None for f in grid.frictions) else []
    return {"grid": grid, "rows": rows, "presets": summaries, "verdict": verdict(summaries),
            "aliases": aliases, "skipped": skipped, "budget_s": budget, "wall_s": time.perf_counter() - start,
            "slide_tilt": tilts}


# --- where a statue that slides tilts in an engine, and cannot in the exact model --------------

#: The slip speed of the sustained push, in units of √(g·R): a fast slide, as a statue walking on
#: its plinth in a strong record (docs/sliding_engines.md: the tilt grows with it)
TILT_SLIP = 1.0


def sustained_push(system):
    """(motion, duration) that slides a block with μ_s < tanα without rocking it in the exact
    model (friction's resultant stays inside its base): the ground pushed at μ_s·g + 0.5·g until
    the slip reaches TILT_SLIP·√(g·R), then still while the slip stops."""

    g = system.gravity
    length = TILT_SLIP * math.sqrt(g * system.R) / (0.5 * g)
    dt = length / 100
    push = GroundMotion.from_array(np.r_[np.zeros(10), np.full(101, (system.friction + 0.5) * g), 0.0], dt=dt,
                                   name="sustained push")
    stop = TILT_SLIP * math.sqrt(system.R / g) / system.friction
    return push, 10 * dt + length + 2 * stop


def slide_tilts(labels, grid: Grid, overrides: dict | None = None) -> list[dict]:
    """Per engine label and fixed-base friction cell with μ_s < tanα (the exact model's block
    slides there and never tips: θmax/α = 0): how far the engine's block tilts while it slides
    (sustained_push), against slide_theta_max_diff's limit. The atlas's answer to where an
    engine cannot follow a sliding statue, and why (issue 33: MuJoCo's soft contact lets the
    leading corners sink, the more the nearer μ_s is to tanα)."""
    out = []
    cells = [c for c in grid.cells() if c.mass_ratio == 0 and c.friction is not None
             and c.friction < 1.0 / c.slenderness]
    # each label's engine, settings and limit once, not once per cell
    chosen = {label: resolve(label, dict(overrides or {})) for label in labels}
    limits = {label: tolerance(label, "slide_theta_max_diff").limit
              if has_tolerance(label, "slide_theta_max_diff") else math.nan for label in labels}
    for c in cells:
        system = c.system()
        motion, duration = sustained_push(system)
        exact = get_engine(REFERENCE).simulate(system, motion, duration=duration)
        for label in labels:
            engine, settings = chosen[label]
            try:
                tr = engine.simulate(system, motion, settings=settings, duration=duration)
            except InputError as e:
                out.append({"engine": label, "cell": c.key, "status": "refused", "note": str(e)})
                continue
            lim = limits[label]
            diff = abs(tr.theta_max_over_alpha - exact.theta_max_over_alpha)
            out.append({"engine": label, "slenderness": c.slenderness, "height": c.height, "friction": c.friction,
                        "friction_over_tan_alpha": c.friction * c.slenderness, "status": str(tr.status),
                        "slide": float(abs(tr.slide).max()) / system.b if tr.slide is not None else None,
                        "slide_exact": float(abs(exact.slide).max()) / system.b,
                        "theta_max_over_alpha": tr.theta_max_over_alpha,
                        "theta_max_over_alpha_exact": exact.theta_max_over_alpha, "limit": lim,
                        "within": bool(diff <= lim) and str(tr.status) == str(exact.status)})
    return out


def tilt_lines(atlas: dict) -> list[str]:
    """The sliding section of atlas.md: per engine, where its sliding block tilts past the limit."""
    rows = [r for r in atlas.get("slide_tilt", []) if r.get("status") != "refused"]
    if not rows:
        return []
    lines = ["## A statue that slides: where an engine tilts it", "",
             f"Each fixed-base cell with a friction μ_s below tanα, pushed at μ_s·g + 0.5·g until its slip reaches "
             f"{TILT_SLIP:g}·√(gR), then left to stop: the exact model's block slides and never tips (friction's "
             "resultant stays inside its base, θmax/α = 0). An engine whose block tilts there by more than "
             "slide_theta_max_diff parts from the model: its soft contact lets the leading corners sink while it "
             "slides, the more the nearer μ_s is to tanα (docs/sliding_engines.md).", "",
             "| engine | λ | H (m) | μ_s | μ_s/tanα | slide/b (exact) | θmax/α (exact 0) | within |",
             "|---|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        slide = "–" if r["slide"] is None else f"{r['slide']:.3g} ({r['slide_exact']:.3g})"
        lines.append(f"| {r['engine']} | {r['slenderness']:g} | {r['height']:g} | {r['friction']:g} | "
                     f"{r['friction_over_tan_alpha']:.2g} | {slide} | {r['theta_max_over_alpha']:.3g} "
                     f"({r['status']}) | {'yes' if r['within'] else 'NO'} |")
    lines.append("")
    for engine in dict.fromkeys(r["engine"] for r in rows):
        bad = [r for r in rows if r["engine"] == engine and not r["within"]]
        mine = [r for r in rows if r["engine"] == engine]
        if bad:
            worst = max(bad, key=lambda r: r["theta_max_over_alpha"])
            lines.append(f"- **{engine}** tilts a sliding statue past the limit in {len(bad)} of {len(mine)} cells, "
                         f"from μ_s/tanα {min(r['friction_over_tan_alpha'] for r in bad):.2g} (worst θmax/α "
                         f"{worst['theta_max_over_alpha']:.3g}"
                         + (", it overturned" if worst["status"] == "overturned" else "")
                         + f" at λ {worst['slenderness']:g}, μ_s/tanα {worst['friction_over_tan_alpha']:.2g}): judge "
                         "statues that slide there by another engine.")
        else:
            lines.append(f"- **{engine}** follows the sliding statue without tilting it in all {len(mine)} cells.")
    return lines + [""]


def summarize(label: str, rows: list[dict]) -> dict:
    """One preset over the grid: how many cells were judged, what happened to the others,
    the worst and median |β error| and |t₁ error| of the judged ones, and the cost:
    simulated s per wall s of the engine's own stepping (Trajectory.runtime_s) summed over
    the grid, of the whole call (scene, stepping, measuring), and per CPU s of the whole
    call (the process's CPU time: what a loaded machine changes least)."""
    judged = [r for r in rows if r["status"] == OK]
    failures = {}
    for r in rows:
        if r["status"] != OK:
            failures[r["status"]] = failures.get(r["status"], 0) + 1
    worst = max(judged, key=lambda r: abs(r["beta_error"]), default=None)
    t1 = [abs(r["t1_error"]) for r in judged if r["t1_error"] is not None]
    sim = sum(r["sim_s"] for r in rows)
    loop = sum(r["loop_s"] for r in rows if math.isfinite(r["loop_s"]))
    wall = sum(r["wall_s"] for r in rows)
    cpu = sum(r["cpu_s"] for r in rows)
    hops = [r["lift_off_after_impact"] for r in judged if r["lift_off_after_impact"] is not None]
    lost = [r["impacts_lost"] for r in judged if r["impacts_lost"]]
    return {
        "engine": label, "engine_name": label.partition(":")[0], "preset": label.partition(":")[2] or "default",
        "cells": len(rows), "judged": len(judged), "failures": failures,
        "complete": not failures and bool(rows),
        "worst_beta_error": abs(worst["beta_error"]) if worst else None,
        "worst_cell": _cell_text(worst) if worst else None,
        "median_beta_error": statistics.median(abs(r["beta_error"]) for r in judged) if judged else None,
        # by size: the step and the contact's own length scales weigh most on the smallest block
        "worst_beta_error_by_height": {h: max((abs(r["beta_error"]) for r in judged if r["height"] == h), default=None)
                                       for h in dict.fromkeys(r["height"] for r in rows)},
        "worst_t1_error": max(t1) if t1 else None,
        "worst_t1_error_by_height": {h: max((abs(r["t1_error"]) for r in judged if r["height"] == h
                                             and r["t1_error"] is not None), default=None)
                                     for h in dict.fromkeys(r["height"] for r in rows)},
        "cells_losing_impacts": len(lost), "impacts_lost": sum(lost),
        **similarity(judged),
        "sim_per_wall": sim / loop if loop > 0 else None,
        "sim_per_wall_whole": sim / wall if wall > 0 else None,
        "sim_per_cpu_whole": sim / cpu if cpu > 0 else None,
        # m; the lowest corner's height after an impact: above 0 the block hopped (not the
        # perfectly inelastic impact of model.md), which is where the largest β errors come from
        "largest_hop": max(hops) if hops else None,
        "sim_s": sim, "loop_s": loop, "wall_s": wall, "cpu_s": cpu,
        "counts": {f"{level:g}": cell_count(rows, level).as_dict() for level in LEVELS},
    }


def similarity(judged: list[dict]) -> dict:
    """How far a preset is from treating every size alike: the cells of one λ and μ are one
    dimensionless case at every H (PERIOD_TIMES_P), so the rigid model gives them the same
    history in units of 1/p; the spread over H of the signed β error and of the t₁ error
    (largest over λ, μ) is what the engine adds by size. 0 for an engine whose settings scale
    exactly with the block; None with fewer than two sizes judged."""
    cases = {}
    for r in judged:
        cases.setdefault((r["slenderness"], r["mass_ratio"], r.get("friction")), []).append(r)
    spread_beta = [max(r["beta_error"] for r in rs) - min(r["beta_error"] for r in rs)
                   for rs in cases.values() if len(rs) > 1]
    t1 = [[r["t1_error"] for r in rs if r["t1_error"] is not None] for rs in cases.values()]
    spread_t1 = [max(v) - min(v) for v in t1 if len(v) > 1]
    return {"similarity_beta_spread": max(spread_beta, default=None),
            "similarity_t1_spread": max(spread_t1, default=None)}


def cell_count(rows: list[dict], level: float):
    """The preset's cells beyond `level` (β error above it, or not judged: failed, slid,
    overturned, missed an impact, too slow) of all its cells, judged as every agreement
    count is (core.verdict.rate_verdict, as stress's): the exact interval of the rate at
    which systems of the grid's range part from the closed form by more than the level.
    The atlas's verdict stays the worst case over the grid (`qualifies`); the count says
    how far one bad cell generalises."""
    beyond = sum(r["status"] != OK or abs(r["beta_error"]) > level for r in rows)
    return rate_verdict(beyond, len(rows), limit=limit("verdict_disagreement_rate"),
                        confidence=limit("verdict_confidence"), min_cases=int(limit("verdict_min_cases")),
                        quantity=f"share of cells beyond {100 * level:g}%")


def qualifies(summary: dict, level: float) -> bool:
    """Every cell judged (nothing failed, slid, overturned, missed impacts or ran out of
    time), no impact above KEPT_AMPLITUDE·α lost, t₁ within T1_LEVEL and the worst β error
    over the grid within `level`."""
    return (summary["complete"] and summary["worst_beta_error"] is not None and summary["worst_beta_error"] <= level
            and not summary["impacts_lost"]
            and summary["worst_t1_error"] is not None and summary["worst_t1_error"] <= T1_LEVEL)


def _similar(s: dict) -> str:
    return f"{_pct(s['similarity_beta_spread'])} / {_pct(s['similarity_t1_spread'])}"


def verdict(summaries: list[dict]) -> list[dict]:
    """Per engine: the cheapest preset (most simulated s per wall s) whose worst β error
    over the grid is within each of LEVELS, or None."""
    out = []
    for name in dict.fromkeys(s["engine_name"] for s in summaries):
        mine = [s for s in summaries if s["engine_name"] == name]
        entry = {"engine": name, "presets": len(mine), "levels": {}}
        for level in LEVELS:
            ok = [s for s in mine if qualifies(s, level)]
            best = max(ok, key=lambda s: s["sim_per_wall"] or 0.0, default=None)
            entry["levels"][f"{level:g}"] = None if best is None else {
                "engine": best["engine"], "preset": best["preset"], "sim_per_wall": best["sim_per_wall"],
                "worst_beta_error": best["worst_beta_error"]}
        entry["incomplete"] = {s["engine"]: s["failures"] for s in mine if not s["complete"]}
        out.append(entry)
    return out


def _cell_text(r: dict) -> str:
    friction = "" if r.get("friction") is None else f", μ_s {r['friction']:g}"
    return f"λ {r['slenderness']:g}, μ {r['mass_ratio']:g}, H {r['height']:g} m{friction}"


# --- writing it -------------------------------------------------------------------------

def _pct(x, digits=3) -> str:
    return "—" if x is None or not math.isfinite(x) else f"{100 * x:.{digits}g}%"


def _speed(x) -> str:
    return "—" if x is None else f"{x:.3g}"


#: m; a corner that rises less than this after an impact rides on the contact's own
#: compliance (MuJoCo's rest penetration moves by ~1e-5 mm), it does not hop.
HOP_FLOOR = 1e-5


def _hop(x) -> str:
    return "—" if x is None else "none" if x <= HOP_FLOOR else f"{1000 * x:.2g} mm"


def _count_cell(c: dict) -> str:
    lo, hi = c["interval"]
    need = f" ({c['n_needed']} cells would decide)" if c["n_needed"] else ""
    return f"{c['note']}: [{_pct(lo)}, {_pct(hi)}] {c['word']}{need}"


def _failures_text(failures: dict) -> str:
    return ", ".join(f"{status} in {n}" for status, n in sorted(failures.items()))


def verdict_lines(atlas: dict) -> list[str]:
    """The Pareto table: per engine the cheapest preset within each level, with its speed."""
    head = "| engine | " + " | ".join(f"cheapest at ≤ {100 * lv:g}% worst β error | sim s / wall s"
                                       for lv in LEVELS) + " |"
    lines = [head, "|---|" + "---|---|" * len(LEVELS)]
    for v in atlas["verdict"]:
        cells = []
        for lv in LEVELS:
            best = v["levels"][f"{lv:g}"]
            cells += ([f"{best['engine']} ({_pct(best['worst_beta_error'])})", _speed(best["sim_per_wall"])]
                      if best else ["none", "—"])
        lines.append(f"| {v['engine']} | " + " | ".join(cells) + " |")
    return lines


def markdown(atlas: dict, *, quick: bool) -> str:
    grid = atlas["grid"]
    lines = ["# isorock atlas: contact models against the closed forms", "",
             "## Verdict", "",
             f"Per engine, the cheapest preset whose worst effective-β error over the whole grid "
             f"({len(grid.cells())} cells{', --quick' if quick else ''}) is within 0.5% and 0.1%, and its "
             "speed (simulated s per wall s of the engine's stepping, summed over the grid). A preset with "
             "any cell that failed, slid, overturned, missed an impact or ran out of time, that lost an "
             f"impact the rigid model has above {KEPT_AMPLITUDE:g}α, or whose t₁ errs by more than "
             f"{100 * T1_LEVEL:g}% does not qualify.", ""]
    lines += verdict_lines(atlas)
    lines += [""] + tilt_lines(atlas) if atlas.get("slide_tilt") else []
    notes = []
    for v in atlas["verdict"]:
        for label, failures in v["incomplete"].items():
            notes.append(f"- {label}: {_failures_text(failures)} of {len(grid.cells())} cells (see atlas.csv)")
    if notes:
        lines += ["", "Presets not judged on every cell:", ""] + notes
    lines += ["", "## Every preset", "",
              "β error: max |β_eff/β − 1| over the impacts of each cell that peak above 0.1α in the rigid "
              "model (the first 3 at most; matched by order among the engine's counted impacts), against the "
              "closed form β(λ, μ); t₁ error: |t₁/t₁,ref − 1|, t₁,ref the exact integral on a "
              "fixed base and the analytic model on an isolated one. Worst and median over the judged cells. "
              "Speed: simulated s per wall s of the engine's stepping, and of the whole call (scene built, "
              "history measured); per CPU s of the whole call (the process's CPU time, what other jobs on "
              "the machine change least). Impacts lost: judged cells that counted fewer impacts than the rigid "
              f"model has up to its last one above {KEPT_AMPLITUDE:g}α (and how many in all). Similarity: the "
              "cells of one λ and μ are one dimensionless case at every size (the isolator's T·p held), so "
              "the rigid model gives them one history in units of 1/p; the spread over sizes of the signed β "
              "error / of the t₁ error (largest over λ, μ) is what the engine adds by size.", "",
              "| preset | judged cells | worst β error (cell) | median β error | worst t₁ error | impacts lost "
              "| similarity: β / t₁ spread over sizes | sim s / wall s "
              "| whole call | per CPU s, whole call | largest hop after an impact | not judged |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    by_height = ["", "Worst β error / worst t₁ error by the block's height (judged cells):", "",
                 "| preset | " + " | ".join(f"H {h:g} m" for h in grid.heights) + " |",
                 "|---|" + "---|" * len(grid.heights)]
    for s in atlas["presets"]:
        where = f" ({s['worst_cell']})" if s["worst_cell"] else ""
        lines.append(f"| {s['engine']} | {s['judged']}/{s['cells']} | {_pct(s['worst_beta_error'])}{where} | "
                     f"{_pct(s['median_beta_error'])} | {_pct(s['worst_t1_error'])} | "
                     f"{s['impacts_lost']} in {s['cells_losing_impacts']} cells | {_similar(s)} | "
                     f"{_speed(s['sim_per_wall'])} | "
                     f"{_speed(s['sim_per_wall_whole'])} | {_speed(s['sim_per_cpu_whole'])} | "
                     f"{_hop(s['largest_hop'])} | "
                     f"{_failures_text(s['failures']) or '—'} |")
        by_height.append(f"| {s['engine']} | " + " | ".join(
            f"{_pct(s['worst_beta_error_by_height'].get(h))} / {_pct(s['worst_t1_error_by_height'].get(h))}"
            for h in grid.heights) + " |")
    lines += by_height
    lines += ["", f"Cells beyond each level, judged as every agreement count is (core.verdict.rate_verdict, as "
                  f"`isorock stress`): the exact {limit('verdict_confidence'):.0%} interval of the share of the "
                  f"grid's systems that part from the closed form by more than the level (or are not judged), "
                  f"against ≤ {100 * limit('verdict_disagreement_rate'):g}%. The verdict above stays the worst "
                  "case; this says how far one bad cell generalises.", "",
              "| preset | " + " | ".join(f"beyond {100 * lv:g}%" for lv in LEVELS) + " |",
              "|---|" + "---|" * len(LEVELS)]
    for s in atlas["presets"]:
        lines.append(f"| {s['engine']} | " + " | ".join(_count_cell(s["counts"][f"{lv:g}"]) for lv in LEVELS) + " |")
    for alias, label in atlas["aliases"].items():
        lines.append(f"\n{alias}: the same settings as {label}, not run again.")
    for label, why in atlas["skipped"].items():
        lines.append(f"\n{label}: not run ({why}).")
    lines += ["", "## The grid", "",
              f"- slenderness λ = H/B: {', '.join(f'{x:g}' for x in grid.slenderness)}",
              f"- mass ratio μ = m/m_b: {', '.join(f'{x:g}' for x in grid.mass_ratios)} (0: a fixed base; "
              f"isolated: T·p {PERIOD_TIMES_P:.3f}, the paper's T {PAPER_PERIOD:g} s on its block, held in units "
              f"of each block's 1/p; ξ {PAPER_DAMPING_RATIO:g})",
              f"- height H: {', '.join(f'{x:g}' for x in grid.heights)} m; square footprint B × B, density "
              f"{DENSITY:.0f} kg/m³ (the paper's block)",
              *([f"- the statue's friction μ_s: {', '.join('none' if x is None else f'{x:g}' for x in grid.frictions)}"
                 " (docs/sliding.md). A cell with friction is judged on β read from the rocking peaks either side "
                 "of each impact, in the engine's history and the exact model's alike (`peak_betas`: a pivot that "
                 "slides after an impact breaks the rigid map), and on t₁ against the exact model"]
                if grid.frictions != (None,) else []),
              "- free rocking from θ0 = 0.5α; each run lasts 1.2 × the time of the rigid model's last impact "
              f"above {KEPT_AMPLITUDE:g}α (or its last judged one, if later) + 0.1 s",
              f"- a run past {atlas['budget_s']:g} CPU s stops and is reported 'too slow'",
              "", "## Figures", "",
              "- `pareto.png`: cost (wall s per simulated s) against worst β error, per engine; presets not "
              "judged on every cell drawn above the plot",
              "- `map_ENGINE_PRESET.png`: signed β error (top) and t₁ error (bottom) per cell, λ across and H up, "
              "one panel per mass ratio; grey cells were not judged (their status written in)", ""]
    lines += [f"Atlas run in {atlas['wall_s']:.0f} s of wall time. Speeds were measured on the machine that ran it "
              "with whatever else ran there: compare presets of one run, not runs."]
    return "\n".join(lines) + "\n"


def file_stem(label: str) -> str:
    name, _, preset = label.partition(":")
    return f"map_{name}_{preset or 'default'}"


def write(atlas: dict, out: str, *, quick: bool) -> None:
    """The whole folder, or nothing (validate.io.output)."""

    def fill(tmp):
        (tmp / "atlas.md").write_text(markdown(atlas, quick=quick), encoding="utf-8")
        data = {k: v for k, v in atlas.items() if k != "grid"}
        data.update(grid=atlas["grid"].describe(), quick=quick, levels=list(LEVELS), density=DENSITY,
                    isolator={"period_times_p": PERIOD_TIMES_P, "damping_ratio": PAPER_DAMPING_RATIO},
                    rows=[{k: v for k, v in r.items()} for r in atlas["rows"]], provenance=provenance())
        (tmp / "atlas.json").write_text(to_json(data) + "\n", encoding="utf-8")
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=COLUMNS, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        w.writerows(atlas["rows"])
        (tmp / "atlas.csv").write_text(buf.getvalue(), encoding="utf-8")
        for s in atlas["presets"]:
            error_map([r for r in atlas["rows"] if r["engine"] == s["engine"]], atlas["grid"], s,
                      tmp / f"{file_stem(s['engine'])}.png")
        pareto(atlas["presets"], tmp / "pareto.png", LEVELS)
    write_folder_atomic(out, fill)


__all__ = ["Grid", "Cell", "FULL", "QUICK", "LEVELS", "build", "summarize", "verdict", "qualifies", "judge", "reference", "run_cell", "write", "default_engines"]
