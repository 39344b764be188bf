"""`isorock calibrate`: find a contact engine's contact parameters that reproduce the
impact law of one system, and check them on cases they were not fitted on.

Cases: free rocking of the system and of the block on its other base, from tilts spread
evenly over TILT_RANGE (fitted), and from the tilts halfway between those (held out);
every run's first IMPACTS counted impacts are compared with the closed-form β. Each
engine says what may move (its `tuning` facet, TUNING: MuJoCo the contact time constant in
steps, damping ratio and solimp dmin; PyBullet the contact ERP; Drake the point
contact's stiffness and dissipation). The search runs in the unit cube of those
coordinates: a coarse Sobol design, then Nelder–Mead from its best point. The result is
written as a preset (a TOML file whose [settings.ENGINE] table `isorock validate
--config` takes) only when it holds on the held-out runs, no worse there than the start
by the worst error nor by the 2σ bound, and gains there more than the noise (exit 1
otherwise: the start is then as good as anything found).

Why it is built this way (measured, docs/mujoco.md "Calibration"). At coarse steps an
impact's β error is mostly set by where the landing falls within a step: it changes sign
and size from one tilt to the next (MuJoCo dt 2e-3, paper block, 51 tilts: sd 0.4% at
the first impact and 2.1% at the fourth on the isolated base, against means of +0.2% and
−0.3%). The worst error of a few runs is then the largest of a few noisy numbers, which
any change of the contact parameters reshuffles; minimising it picks parameters whose
noise fell low on those runs. The former fit on 8 runs went 2.00% → 1.73% on them and
2.22% → 2.96% on 6 others, while over 102 runs both settings had the same worst error
(3.7% and 3.8%). So the objective is the 2σ bound of the signed errors of every fitted
impact (a smooth stand-in for the worst error that uses all of them, not the one
extreme), the fitted and held-out tilts interleave over one range on both bases so they
sample the same regime, and the preset must not be worse on the held-out runs by their
worst error or by that bound.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, fields

import numpy as np
from scipy.optimize import minimize
from scipy.stats import qmc

from ...analytic import limits
from ...analytic.engine_protocol import declare_facet
from ...analytic.errors import InputError
from ...analytic.system import PAPER_DAMPING_RATIO, PAPER_PERIOD
from ..core.cases import Case as _Case
from ..core.chunks import worker_pool
from ..core.engines import get_engine
from ..core.executor import Executor
from ..core.measure import beta_errors
from ..core.tolerances import has_tolerance, limit, tolerance
from ..io.progress import bar_of

#: Free-rocking tilts, fractions of α: `tilts` fitted tilts spread evenly over this range,
#: held out on the `tilts − 1` halfway between them (the same regime, never the same runs).
TILT_RANGE = (0.3, 0.8)
#: Fitted tilts per base (held-out: one fewer). 11 gives 22 fitted runs and 88 impacts:
#: the 2σ bound of the paper block's errors then moves by about ±0.1 points between
#: equally good settings (its bootstrap spread), against 0.5–1 points for the worst error.
DEFAULT_TILTS = 11
#: Impacts per run whose β counts (the first ones: later, smaller impacts measure the
#: contact's own scale more than the impact law).
IMPACTS = 4
#: The objective of settings under which some run gives fewer impacts than the rigid
#: model or an unmeasurable β (it hops, slides or breaks): worse than any real error.
PENALTY = 1.0
#: m: a run whose block hops higher than this after an impact has failed, where the engine
#: has no lift-off tolerance of its own (MuJoCo's and PyBullet's are this too).
LIFT_OFF = limit("calibrate_lift_off")
#: what an engine lets calibrate move (engine_protocol.Tuning)
TUNING = declare_facet("tuning", "isorock calibrate", "a Tuning: the contact parameters a calibration may move, "
                       "their bounds, the coordinates of given settings and the settings at given coordinates")
#: A run of other settings may take this many times the starting settings' slowest run
#: (at least MIN_TIME_LIMIT s), or it has failed: Drake's point contact at 1e11 N/m costs
#: tens of times its default's, and the search is for contact laws, not for slow ones.
TIME_FACTOR = 5.0
MIN_TIME_LIMIT = 2.0
#: s simulated past the rigid model's first uncounted impact: the last counted impact's
#: state after it is measured 0.03 s on (validate.measure.CONTACT_WINDOW).
MARGIN = 0.1
#: The coarse design: at most this many Sobol points (a power of two keeps its balance),
#: and at most half the evaluations, the other half refining the best of them.
COARSE_MAX = 16
#: Nelder–Mead's first simplex around the best coarse point, as a fraction of each range.
SIMPLEX_STEP = 0.1
#: Resamples of the runs for the spread of the change of their 2σ bound.
BOOTSTRAP = 2000
#: A preset must lower the held-out runs' 2σ bound by more than this many bootstrap
#: spreads of that change. The fitted runs cannot say it: the best of tens of evaluations
#: of a noisy objective lies below the start by chance alone (the winner's curse: on the
#: paper block at dt 2e-3 the fit gained 0.15 points there and lost 0.30 held out); the
#: held-out runs took no part in the choice, so their change is an honest estimate.
NOISE_SIGMAS = 1.0


@dataclass(frozen=True)
class Case(_Case):
    """The one case type (core.cases.Case), free rocking (motion "none"), with the counted
    impacts compared: IMPACTS, or fewer where the rigid model has fewer; its duration runs
    past the rigid model's impact after the last compared one. Made by name:
    Case.named(name, system, "none", duration, theta0_over_alpha, impacts=n)."""

    impacts: int = IMPACTS


def tilts(n: int = DEFAULT_TILTS) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(fitted, held-out) tilts as fractions of α: n evenly over TILT_RANGE, and the
    n − 1 halfway between them."""
    if not isinstance(n, (int, np.integer)) or isinstance(n, bool) or n < 2:
        raise InputError(f"tilts = {n!r}: must be a whole number of at least 2")
    lo, hi = TILT_RANGE
    fitted = np.linspace(lo, hi, n)
    held = 0.5 * (fitted[1:] + fitted[:-1])
    return tuple(round(float(x), 6) for x in fitted), tuple(round(float(x), 6) for x in held)


def other_base(system):
    """The block on its other base, and how each base is named: a fixed base for an
    isolated system; the paper's isolator (T 1.5 s, ξ 0.2) for a fixed one."""
    if system.fixed_base:
        return (system.on_isolator(PAPER_PERIOD, PAPER_DAMPING_RATIO),
                ("fixed base", f"isolated base (T {PAPER_PERIOD:g} s, ξ {PAPER_DAMPING_RATIO:g})"))
    return system.on_fixed_base(), ("isolated base", "fixed base")


def cases(system, n_tilts: int = DEFAULT_TILTS, impacts: int = IMPACTS) -> tuple[list[Case], list[Case]]:
    """(fitted, held out): the system and the block on its other base from the fitted
    and the held-out tilts. One base, or few tilts, fit the step-to-step noise of β (the
    module's docstring). Each run lasts until just past the rigid model's impact after
    its last compared one (the analytic engine says when), so no time is spent on the
    Zeno tail."""
    fitted_tilts, held_tilts = tilts(n_tilts)
    other, names = other_base(system)
    reference = _reference_engine()

    def make(fraction, name, sys_):
        times = _impact_times(reference, sys_, fraction)
        n = min(impacts, len(times))
        if n == 0:
            raise InputError(f"system: free rocking from {fraction}·α has no impact above the counting threshold; "
                             "nothing to calibrate on")
        end = times[n] if len(times) > n else times[-1] + 0.5
        return Case.named(f"θ0 = {fraction:g}α, {name}", sys_, "none", float(end + MARGIN), fraction, impacts=n)

    pairs = tuple(zip(names, (system, other)))
    return ([make(f, n, s) for n, s in pairs for f in fitted_tilts],
            [make(f, n, s) for n, s in pairs for f in held_tilts])


def _reference_engine():
    try:
        return get_engine("analytic")
    except ImportError:  # the compiled kernel needs numba: the SciPy path gives the same times
        return get_engine("analytic-reference")


def _impact_times(reference, system, fraction, horizon: float = 30.0) -> list[float]:
    tr = reference.simulate(system, None, duration=horizon, theta0=fraction * system.alpha)
    return [i.t for i in tr.counted_impacts]


# --- scoring ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Score:
    """The signed β errors of a set of runs: per run a tuple of its compared impacts'
    errors, or None when the run failed (fewer impacts, an unmeasurable β, an error)."""

    errors: tuple

    @property
    def values(self) -> np.ndarray:
        return np.array([e for run in self.errors if run is not None for e in run], dtype=float)

    @property
    def failed(self) -> int:
        return sum(run is None for run in self.errors)

    @property
    def worst(self) -> float:
        return PENALTY if self.failed else float(np.max(np.abs(self.values)))

    @property
    def mean(self) -> float:
        return float(np.mean(self.values)) if self.values.size else math.nan

    @property
    def rms(self) -> float:
        return float(np.sqrt(np.mean(self.values ** 2))) if self.values.size else math.nan

    @property
    def bound(self) -> float:
        """The 2σ bound |mean| + 2·sd: the objective; PENALTY when a run failed."""
        return PENALTY if self.failed else _bound(self.values)

    def per_run(self) -> list[float | None]:
        """The largest |error| of each run (None: the run failed)."""
        return [None if run is None else float(max(abs(e) for e in run)) for run in self.errors]

    def summary(self) -> dict:
        return {"worst": self.worst, "bound_2sigma": self.bound, "rms": self.rms, "mean": self.mean,
                "failed_runs": self.failed, "worst_per_run": self.per_run(),
                "errors": [None if r is None else list(r) for r in self.errors]}


def _bound(values: np.ndarray) -> float:
    return float(abs(values.mean()) + 2.0 * values.std())


def bootstrap_change(before: Score, after: Score, n: int = BOOTSTRAP, seed: int = 0) -> tuple[float, float]:
    """(change of the 2σ bound from `before` to `after` on the same runs, its spread):
    the standard deviation of that change over resamples of the runs (paired: a resample
    takes the same runs from both). A change smaller than its spread is noise."""
    change = after.bound - before.bound
    if len(before.errors) < 2 or before.failed or after.failed:
        return change, math.nan
    picks = np.random.default_rng(seed).integers(0, len(before.errors), size=(n, len(before.errors)))
    return change, float(np.std(_resampled_bounds(after, picks) - _resampled_bounds(before, picks)))


def _resampled_bounds(score: Score, picks: np.ndarray) -> np.ndarray:
    """The 2σ bound of each resample (a row of run indices), from per-run counts, sums
    and sums of squares (the resamples are too many for a loop)."""
    runs = [np.asarray(r, dtype=float) for r in score.errors]
    count, total, squares = (np.array([f(r) for r in runs])[picks].sum(axis=1)
                             for f in (len, np.sum, lambda r: np.sum(r * r)))
    mean = total / count
    return np.abs(mean) + 2.0 * np.sqrt(np.maximum(squares / count - mean * mean, 0.0))


# --- running the cases --------------------------------------------------------------------

def run_case(engine_name: str, settings, case: Case, time_limit: float | None = None):
    """(the signed β errors of the case's first compared impacts, wall seconds). The
    errors are None when the run does not give them (the settings are a bad point, not a
    crash), when the block hops after an impact by more than the engine's lift-off
    tolerance (the impact law is perfectly inelastic, and a hopping contact can still
    give a plausible β), or when the run takes longer than `time_limit` s."""
    start = time.perf_counter()

    def watch(t, duration):  # the engines call it between chunks of their own loops
        if time_limit is not None and time.perf_counter() - start > time_limit:
            raise _TooSlow

    try:
        tr = get_engine(engine_name).simulate(case.system, None, settings=settings, duration=case.duration,
                                              theta0=case.theta0, progress=watch)
        errs = beta_errors(tr, case.impacts)
    except InputError:
        raise
    except Exception:  # a setting that breaks the engine (or is too slow) is a bad point, not a crash
        return None, time.perf_counter() - start
    seconds = time.perf_counter() - start
    if time_limit is not None and seconds > time_limit:  # a short run ends before its first progress call
        return None, seconds
    if len(errs) < case.impacts or not all(math.isfinite(e) for e in errs):
        return None, seconds
    if tr.extras.get("lift_off_max_after_impact", 0.0) > lift_off_limit(engine_name):
        return None, seconds
    return tuple(float(e) for e in errs), seconds


class _TooSlow(Exception):
    """A run took longer than its time limit."""


def lift_off_limit(engine_name: str) -> float:
    """m: the engine's tolerance on the lift-off after an impact (validate/core/tolerances.py),
    or LIFT_OFF where it has none."""
    if has_tolerance(engine_name, "lift_off_after_impact"):
        return tolerance(engine_name, "lift_off_after_impact").limit
    return LIFT_OFF


class Runner:
    """Runs sets of cases for one engine on the one executor (core.executor.Executor).
    `workers` 0: here, one after the other (the tests; a run stuck inside one of an
    engine's chunks cannot be stopped here); n ≥ 1: in n worker processes, each run
    stopped by killing its worker at `time_limit` (s of wall time; the search sets it from
    the starting settings' runs: Drake's integrator can spend many minutes inside one
    chunk at a stiff contact). `on_run()` is called after each run (a progress bar);
    `slowest` is the longest run of the last set."""

    def __init__(self, engine_name: str, workers: int = 0, on_run=None):
        self.engine_name, self.on_run = engine_name, on_run
        # the starting settings' runs, before any is timed, have every run's budget
        self.time_limit, self.slowest = limits.RUN_BUDGET_S, 0.0
        self.executor = worker_pool(workers) if workers else Executor()

    def score(self, settings, case_list, *, until_failure: bool = False) -> Score:
        """The Score of the runs. `until_failure`: stop at the first failed run (the rest
        count as failed too): the search's objective is PENALTY from the first one on, and
        the other runs of a bad point would cost as much as a good point's."""
        tasks = [(self.engine_name, settings, c, self.time_limit) for c in case_list]

        def result(outcome):  # (errors, seconds): a run that timed out or died has failed
            return outcome.value if outcome.done else (None, outcome.seconds)
        # in worker processes the executor kills a run at time_limit; here run_case's own
        # watch stops it at the engine's next progress call
        outcomes = self.executor.map(run_case, tasks, budget=self.time_limit if self.executor.workers else None,
                                     on_result=lambda i, o: self._ran(),
                                     stop=(lambda o: result(o)[0] is None) if until_failure else None)
        results = [None if o is None else result(o) for o in outcomes]
        self.slowest = max((r[1] for r in results if r is not None), default=0.0)
        return Score(tuple(None if r is None else r[0] for r in results))

    def limit_from_slowest(self, slowest: float) -> None:
        """The search's runs may take TIME_FACTOR × the starting settings' slowest (at least
        MIN_TIME_LIMIT), never more than every run's budget (RUN_BUDGET_S)."""
        self.time_limit = min(max(TIME_FACTOR * slowest, MIN_TIME_LIMIT), limits.RUN_BUDGET_S)

    def _ran(self):
        if self.on_run:
            self.on_run()

    def close(self):
        self.executor.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


# --- the search ----------------------------------------------------------------------------

def coarse_points(max_evals: int) -> int:
    """Sobol points of the coarse design: a power of two, at most COARSE_MAX and at most
    half of what the evaluations allow after the start."""
    n = 1
    while 2 * n <= min(COARSE_MAX, (max_evals - 1) // 2):
        n *= 2
    return n


def search(objective, u0: np.ndarray, f0: float, max_evals: int, seed: int = 0) -> None:
    """Spend up to `max_evals` calls of `objective(u)` on the unit cube after the start
    u0 (whose value f0 is known): a coarse scrambled Sobol design, then bounded
    Nelder–Mead from the best point so far.
    The caller keeps every value (the best seen is the result: Nelder–Mead's last simplex
    on a noisy objective is not always its best point)."""
    seen = {tuple(np.round(np.clip(u0, 0.0, 1.0), 9)): f0}

    def f(u):
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        key = tuple(np.round(u, 9))
        if key not in seen:
            seen[key] = objective(u)
        return seen[key]

    d = u0.size
    for u in qmc.Sobol(d, scramble=True, seed=seed).random(coarse_points(max_evals + 1)):
        f(u)
    left = max_evals + 1 - len(seen)
    if left <= d:  # too few evaluations for a simplex
        return
    best = np.array(min(seen, key=seen.get))
    simplex = [best]
    for i in range(d):  # a step into the cube along each coordinate
        p = best.copy()
        p[i] = p[i] + SIMPLEX_STEP if p[i] + SIMPLEX_STEP <= 1 else p[i] - SIMPLEX_STEP
        simplex.append(p)
    budget = [left]

    def counted(u):
        key = tuple(np.round(np.clip(u, 0.0, 1.0), 9))
        if key not in seen:
            if budget[0] <= 0:
                raise _Spent
            budget[0] -= 1
        return f(u)

    try:  # maxfev counts the cached points Nelder–Mead revisits too: `counted` keeps the budget
        minimize(counted, best, method="Nelder-Mead", bounds=[(0.0, 1.0)] * d,
                 options={"maxfev": 10 * left, "xatol": 1e-3, "fatol": 1e-5, "initial_simplex": np.array(simplex)})
    except _Spent:
        pass


class _Spent(Exception):
    """The search has spent its evaluations."""


def calibrate(engine_name: str, system, *, settings=None, n_tilts: int = DEFAULT_TILTS, impacts: int = IMPACTS,
              max_evals: int = 48, workers: int = 0, progress=None) -> dict:
    """Fit the engine's tuning to `system`; returns the settings before and after, the
    fitted and held-out scores before and after with the change of their 2σ bound and
    its bootstrap spread. `workers`: processes for the runs (0: this one; Runner).
    `progress`: a factory total → bar (io.progress.bar_of), updated after each run with the
    best 2σ bound so far."""
    engine = get_engine(engine_name)
    tuning = TUNING.of(engine.spec)
    if tuning is None:
        raise InputError(f"engine = {engine_name!r}: has no contact parameters to calibrate")
    start_settings = settings or engine.settings()
    fitted, held = cases(system, n_tilts, impacts)
    lo = np.array([b[0] for b in tuning.bounds], dtype=float)
    hi = np.array([b[1] for b in tuning.bounds], dtype=float)
    x0 = np.clip(np.asarray(tuning.start(start_settings), dtype=float), lo, hi)
    total = max_evals * len(fitted) + 2 * len(held)
    best = [math.inf]
    evaluated = []  # (objective, x, settings, fitted Score)
    bar = bar_of(progress, total)

    def ran():
        bar.update(1, note=f"best 2σ bound {100 * best[0]:.3f}%" if math.isfinite(best[0]) else "")

    t0 = time.perf_counter()
    with Runner(engine_name, workers, on_run=ran) as runner:
        def objective(u):
            x = lo + u * (hi - lo)
            try:
                s = tuning.apply(start_settings, x)
            except InputError:  # outside what the engine accepts: a bad point
                evaluated.append((PENALTY, x, None, None))
                return PENALTY
            sc = runner.score(s, fitted, until_failure=True)
            value = sc.bound
            evaluated.append((value, x, s, sc))
            best[0] = min(best[0], value)
            return value

        # the start itself, exactly (its coordinates may not give back the very same settings)
        before_fit = runner.score(start_settings, fitted)
        runner.limit_from_slowest(runner.slowest)
        evaluated.append((before_fit.bound, x0, start_settings, before_fit))
        best[0] = before_fit.bound
        span = np.where(hi > lo, hi - lo, 1.0)
        search(objective, (x0 - lo) / span, before_fit.bound, max_evals - 1)
        value, best_x, best_settings, after_fit = min(evaluated, key=lambda r: r[0])
        before_held = runner.score(start_settings, held)
        improved = best_settings is not start_settings
        after_held = runner.score(best_settings, held) if improved else before_held
    return {
        "engine": engine_name,
        "coordinates": list(tuning.names),
        "start": dict(zip(tuning.names, map(float, x0))),
        "parameters": dict(zip(tuning.names, map(float, best_x))),
        "settings_before": start_settings, "settings_after": best_settings, "improved": improved,
        "fitted": _part([c.name for c in fitted], before_fit, after_fit),
        "held_out": _part([c.name for c in held], before_held, after_held),
        "tilts": tilts(n_tilts), "impacts": impacts,
        "evaluations": len(evaluated), "wall_s": time.perf_counter() - t0,
    }


def _part(labels, before: Score, after: Score) -> dict:
    change, spread = bootstrap_change(before, after)
    return {"cases": list(labels), "before": before, "after": after,
            "bound_change": change, "bound_change_spread": spread}


def beyond_noise(part: dict) -> bool:
    """Whether the runs' 2σ bound fell by more than NOISE_SIGMAS bootstrap spreads of
    its change (or runs that failed before all give their impacts after)."""
    before, after = part["before"], part["after"]
    if after.failed:
        return False
    if before.failed:
        return True
    return part["bound_change"] < -NOISE_SIGMAS * part["bound_change_spread"]


def holds(result: dict) -> bool:
    """Whether the calibrated settings hold on the held-out runs: no worse than the
    start there by the worst error nor by the 2σ bound (the worst error alone is the
    largest of a few noisy numbers, the bound alone could hide one bad impact)."""
    h = result["held_out"]
    return (result["improved"] and h["after"].failed == 0 and h["after"].worst <= h["before"].worst
            and h["after"].bound <= h["before"].bound)


def preset_worthy(result: dict) -> bool:
    """The criterion for writing a preset: the settings hold on the held-out runs and
    gain there more than the noise (a gain within it says the start is as good)."""
    return holds(result) and beyond_noise(result["held_out"])


def settings_toml(engine_name: str, settings, header_lines) -> str:
    """A TOML preset file: the header as comments, then [settings.ENGINE]."""
    lines = [f"# {line}" for line in header_lines] + ["", f"[settings.{engine_name}]"]
    for f in fields(settings):
        v = getattr(settings, f.name)
        if v is None:
            continue
        if isinstance(v, bool):
            lines.append(f"{f.name} = {'true' if v else 'false'}")
        elif isinstance(v, (int, float)):
            lines.append(f"{f.name} = {v!r}")
        elif isinstance(v, str):
            lines.append(f'{f.name} = "{v}"')
        elif isinstance(v, (tuple, list)):
            lines.append(f"{f.name} = [{', '.join(repr(float(x)) for x in v)}]")
    return "\n".join(lines) + "\n"


def report_lines(result: dict, system, command: str) -> list[str]:
    """What the command prints (and the preset file's header): the cases, the objective,
    before and after on the fitted and held-out runs, the parameters and the verdict."""
    f, h = result["fitted"], result["held_out"]
    fit_t, held_t = result["tilts"]
    d = system.describe()
    other, names = other_base(system)
    lines = [f"{command}: {d['height']:g} × {d['width']:g} m block (λ {system.slenderness:.4g}), {names[0]}; "
             f"also on its {names[1]}",
             f"cases: free rocking, the first {result['impacts']} impacts of each run against the closed-form β; "
             f"fitted: {len(fit_t)} tilts {fit_t[0]:g}–{fit_t[-1]:g}·α on both bases ({len(f['cases'])} runs); "
             f"held out: the {len(held_t)} tilt{'s' if len(held_t) > 1 else ''} halfway between them "
             f"({len(h['cases'])} runs)",
             "objective: the 2σ bound |mean| + 2·sd of the fitted impacts' signed β errors (the worst error of a "
             "few runs is mostly where each impact falls within a step, and over-fits)",
             f"searched: {', '.join(result['coordinates'])}; a coarse Sobol design, then Nelder–Mead; "
             f"{result['evaluations']} evaluations in {result['wall_s']:.0f} s",
             "",
             f"{'β error':<20}{'fitted before':>15}{'after':>10}{'held out before':>18}{'after':>10}"]
    for label, key in (("worst |error|", "worst"), ("2σ bound", "bound"), ("rms", "rms"), ("mean (signed)", "mean")):
        vals = [getattr(s, key) for s in (f["before"], f["after"], h["before"], h["after"])]
        sign = "+" if key == "mean" else ""
        lines.append(f"{label:<20}" + "".join(f"{100 * v:{sign}{w}.3f}%" for v, w in zip(vals, (14, 9, 17, 9))))
    for s, where in ((f["before"], "fitted before"), (f["after"], "fitted after"), (h["before"], "held out before"),
                     (h["after"], "held out after")):
        if s.failed:
            lines.append(f"{where}: {s.failed} run(s) gave fewer impacts, no measurable β, hopped after an "
                         f"impact or ran {TIME_FACTOR:g}× longer than the slowest run at the start (counted as "
                         f"{100 * PENALTY:g}%)")
    for part, where in ((f, "fitted"), (h, "held-out")):
        spread = part["bound_change_spread"]
        if math.isfinite(spread):
            lines.append(f"{where} 2σ bound change {100 * part['bound_change']:+.3f} points, bootstrap spread "
                         f"{100 * spread:.3f} over the {where} runs")
    lines.append("")
    if result["improved"]:
        before, after = asdict(result["settings_before"]), asdict(result["settings_after"])
        for k in after:
            if before[k] != after[k]:
                lines.append(f"{k}: {_show(before[k])} → {_show(after[k])}")
        lines.append("coordinates: " + ", ".join(f"{n} {result['start'][n]:.4g} → {result['parameters'][n]:.4g}"
                                                 for n in result["coordinates"]))
    lines.append("a preset needs, on the held-out runs: the worst error and the 2σ bound no worse than before, and "
                 f"the bound lower by more than {NOISE_SIGMAS:g} bootstrap spread of its change")
    if preset_worthy(result):
        lines.append("verdict: the calibrated settings hold on the held-out runs (worst error and 2σ bound no "
                     f"worse than before) and gain there more than {NOISE_SIGMAS:g} bootstrap spread")
    elif not result["improved"]:
        lines.append("verdict: nothing better than the starting settings on the fitted runs: keep them")
    elif holds(result):
        lines.append("verdict: the calibrated settings are no worse on the held-out runs, but their gain there is "
                     f"within {NOISE_SIGMAS:g} bootstrap spread: the starting settings are as good; keep them")
    else:
        lines.append("verdict: the calibrated settings do NOT hold on the held-out runs (worse than the starting "
                     "settings there): what the fit gained was noise; keep the starting settings")
    return lines


def _show(v):
    if isinstance(v, tuple):
        return "(" + ", ".join(f"{x:.6g}" for x in v) + ")"
    return f"{v:.6g}" if isinstance(v, float) else str(v)


def result_json(result: dict) -> dict:
    """The result as plain data (settings as tables, scores with every error)."""
    out = {k: v for k, v in result.items() if k not in ("settings_before", "settings_after", "fitted", "held_out")}
    out["settings_before"] = asdict(result["settings_before"])
    out["settings_after"] = asdict(result["settings_after"])
    for key in ("fitted", "held_out"):
        part = dict(result[key])
        part["before"], part["after"] = part["before"].summary(), part["after"].summary()
        out[key] = part
    out["holds"], out["preset"] = holds(result), preset_worthy(result)
    return out
