"""The one result type every engine returns, and model.md's impact-counting rule.

Arrays are in SI units: t (s), u (m, base relative to ground), u_dot (m/s),
theta (rad, > 0 rocking about O), theta_dot (rad/s), mode (0 translation,
+1 rocking about O, -1 about O').
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from .engine_protocol import DEFAULT_IMPACT_THRESHOLD  # one home (the counting rule); re-exported
from .errors import import_extra
from .limits import energy_balance_failure
from .overturning import PAST_ALPHA, THETA_MAX_DEFINITION, theta_max_over_alpha
from .status import Status
from .system import System


@dataclass(frozen=True)
class Impact:
    """One impact at θ = 0. Velocities are those at θ = 0 just before (`_pre`) and
    just after (`_post`). For contact engines they are the states outside the contact
    transient mapped to θ = 0 with the rigid equations. `amplitude` is the largest |θ|
    (rad) of the half-cycle that ends in the impact; `counted` applies model.md's rule."""

    t: float
    theta_dot_pre: float
    theta_dot_post: float
    u_dot_pre: float
    u_dot_post: float
    continued: bool
    amplitude: float
    counted: bool

    @property
    def beta(self) -> float:
        """Effective θ̇⁺/θ̇⁻ of this impact (nan for a zero pre-impact velocity)."""
        return self.theta_dot_post / self.theta_dot_pre if self.theta_dot_pre else math.nan

    def as_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True, eq=False)
class EnergyLog:
    """Energy bookkeeping (J), sampled like the trajectory. With E = kinetic + potential
    (velocities relative to the ground, gravity and the isolator's springs in `potential`):
    E(t) − E(0) = ground_work − dashpot_loss − impact_loss − isolator_loss, and `residual`
    is what is left of that balance. `isolator_loss`: the hysteretic or friction work of a
    non-linear isolator (None for the linear one); `slip_loss`: the friction work of a statue
    that slips on its base (None where it cannot slip)."""

    kinetic: np.ndarray
    potential: np.ndarray
    ground_work: np.ndarray
    dashpot_loss: np.ndarray
    impact_loss: np.ndarray  # cumulative
    per_impact: tuple[float, ...] = ()  # energy lost in each impact, in the order of Trajectory.impacts
    isolator_loss: np.ndarray | None = None  # cumulative slip work of a non-linear isolator
    slip_loss: np.ndarray | None = None  # cumulative friction work of a statue slipping on its base

    @property
    def total(self) -> np.ndarray:
        return self.kinetic + self.potential

    @property
    def residual(self) -> np.ndarray:
        r = self.total - self.total[0] - self.ground_work + self.dashpot_loss + self.impact_loss
        if self.slip_loss is not None:
            r = r + self.slip_loss
        return r if self.isolator_loss is None else r + self.isolator_loss

    @property
    def input_energy(self) -> float:
        """A scale for the residual: the largest energy that entered or was held (0 for a run
        with no rows: one that failed at its start, e.g. in free flight at once)."""
        if not self.total.size:
            return 0.0
        return float(max(np.max(np.abs(self.ground_work)), np.max(np.abs(self.total)),
                         np.max(self.impact_loss) if self.impact_loss.size else 0.0,
                         np.max(self.isolator_loss) if self.isolator_loss is not None and self.isolator_loss.size
                         else 0.0,
                         np.max(self.slip_loss) if self.slip_loss is not None and self.slip_loss.size else 0.0))

    @property
    def relative_residual(self) -> float:
        scale = self.input_energy
        return float(np.max(np.abs(self.residual)) / scale) if scale > 0 else 0.0

    def failure(self, t: np.ndarray) -> str | None:
        """limits.energy_balance_failure of this balance, sampled at the times t: its message
        where the relative residual exceeds ENERGY_BALANCE_LIMIT, else None."""
        return energy_balance_failure(t, self.residual.tolist(), self.input_energy)


@dataclass(frozen=True, eq=False)
class RawHistory:
    """What a contact engine hands over: its sampled states (arrays as in Trajectory),
    how the run ended, and its own diagnostics (`extras`, scalars, one vocabulary: see
    `isorock.analytic.kinematics.contact_extras`). Impacts, effective β, uplifts and
    overturning are measured from it outside the engine, the same way for every engine
    (`isorock.validate.core.measure.measure`). `stop_reason` says why the history ends
    early, if it does ('non-finite', 'lying', 'falling'; see kinematics.first_stop).
    `slide`, `slide_dot`: the block's slide x on its base (m) and ẋ (m/s), as the Trajectory's,
    where the run needs the model of a contact that may slip (kinematics.slide_history),
    else None."""

    engine: str
    system: System
    t: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    status: Status = Status.COMPLETED
    message: str = ""
    runtime_s: float = 0.0
    extras: dict = field(default_factory=dict)
    stop_reason: str | None = None
    slide: np.ndarray | None = None
    slide_dot: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class Trajectory:
    engine: str
    system: System
    t: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    mode: np.ndarray
    impacts: tuple[Impact, ...] = ()
    uplift_times: tuple[float, ...] = ()
    overturned: bool = False
    overturn_time: float | None = None
    impact_threshold: float = DEFAULT_IMPACT_THRESHOLD
    runtime_s: float = 0.0
    status: Status = Status.COMPLETED
    message: str = ""
    energy: EnergyLog | None = None
    extras: dict = field(default_factory=dict)  # engine-specific histories (lift-off, drift…)
    #: where the statue may slip on its base (System.friction): its slide x (m), the position
    #: on the base of the middle of its bottom face (docs/sliding.md), and ẋ (m/s); None where
    #: the model assumes no slip
    slide: np.ndarray | None = None
    slide_dot: np.ndarray | None = None

    # --- summary metrics ----------------------------------------------------------
    @property
    def alpha(self) -> float:
        return self.system.alpha

    @property
    def theta_max_over_alpha(self) -> float:
        """overturning.THETA_MAX_DEFINITION under the run's rule."""
        if not self.theta.size:
            return 0.0
        theta_max = float(np.max(np.abs(self.theta)))
        if self.system.asymmetric:  # each way against its own edge's α, as the weaker edge's share
            theta_max = self.alpha * self.edge_tilt_max
        return float(theta_max_over_alpha(theta_max, self.alpha, self.overturned,
                                          self.extras.get("overturn_rule", PAST_ALPHA)))

    @property
    def edge_tilt_max(self) -> float:
        """The largest tilt each way against the α of the edge it tilts onto, max(θ⁺/α₊, θ⁻/α₋):
        a statue of two edges' θmax/α (before an overturned run's end is taken as π/2)."""
        if not self.theta.size:
            return 0.0
        sy = self.system
        return max(max(float(np.max(self.theta)), 0.0) / sy.edge_alpha(1),
                   max(-float(np.min(self.theta)), 0.0) / sy.edge_alpha(-1))

    def _theta_max_definition(self) -> str:
        return THETA_MAX_DEFINITION.get(self.extras.get("overturn_rule", PAST_ALPHA), "")

    @property
    def counted_impacts(self) -> tuple[Impact, ...]:
        return tuple(i for i in self.impacts if i.counted)

    @property
    def impact_count(self) -> int:
        return len(self.counted_impacts)

    @property
    def uplifts(self) -> int:
        return len(self.uplift_times)

    @property
    def u_max(self) -> float:
        return float(np.max(np.abs(self.u))) if self.u.size else 0.0

    @property
    def rocking_duration(self) -> float:
        """Time (s) spent rocking (mode ≠ 0), from the sampled modes."""
        if self.t.size < 2:
            return 0.0
        rocking = self.mode[:-1] != 0
        return float(np.sum(np.diff(self.t)[rocking]))

    def summary(self) -> dict:
        """The machine-readable metrics (field names are a contract: keep them)."""
        out = {
            "engine": self.engine,
            "status": str(self.status),
            "message": self.message,
            "alpha": self.alpha,
            # a statue of two edges: α and λ above are its weaker edge's; both edges here
            **({"body": self.system.body.describe()} if self.system.asymmetric else {}),
            "slenderness": self.system.slenderness,
            "mass_ratio": self.system.mu,
            "fixed_base": self.system.fixed_base,
            "theta_max_over_alpha": self.theta_max_over_alpha,
            "theta_max_over_alpha_definition": self._theta_max_definition(),
            "impacts": self.impact_count,
            "impacts_total": len(self.impacts),
            "impact_threshold": self.impact_threshold,
            "uplifts": self.uplifts,
            "uplift_times": list(self.uplift_times),
            "overturned": self.overturned,
            "overturn_time": self.overturn_time,
            "u_max": self.u_max,
            "rocking_duration": self.rocking_duration,
            "duration": float(self.t[-1]) if self.t.size else 0.0,
            "runtime_s": self.runtime_s,
            "impact_log": [i.as_dict() for i in self.counted_impacts],
        }
        # a run that failed at its start (free flight at once) has no rows: no energy to account for
        if self.energy is not None and self.energy.total.size:
            out["energy_balance_residual"] = self.energy.relative_residual
            out["energy_lost_in_impacts"] = float(sum(self.energy.per_impact))
            out["energy_lost_in_dashpot"] = float(self.energy.dashpot_loss[-1])
            out["ground_work"] = float(self.energy.ground_work[-1])
            if self.energy.isolator_loss is not None:
                out["energy_lost_in_isolator"] = float(self.energy.isolator_loss[-1])
        if self.energy is not None and self.energy.slip_loss is not None and self.energy.slip_loss.size:
            out["energy_lost_in_slip"] = float(self.energy.slip_loss[-1])
        if self.slide is not None:
            out.update(self.slide_summary())
        for key, value in self.extras.items():
            if np.isscalar(value):
                out[key] = value
        return out

    def slide_summary(self) -> dict:
        """The slide's metrics (m, s): how far the statue walked on its base at most and at the
        end, and when it first slid (slide_onset: the first time |x| passes SLIDING_FRACTION·b,
        None: never, read off the samples: a contact engine's ẋ is never exactly 0, its contact
        creeps; the analytic engines, which locate slips as events, also say when the first began:
        extras' slip_onset)."""
        x = self.slide
        return {"slide_max": float(np.max(np.abs(x))) if x.size else 0.0,
                "slide_final": float(x[-1]) if x.size else 0.0,
                "slide_onset": first_passage(self.t, x, SLIDING_FRACTION * self.system.b)}

    # --- resampling -----------------------------------------------------------------
    def resample(self, dt: float) -> "Trajectory":
        """The histories at t = 0, dt, 2dt, …: θ and u by cubic Hermite interpolation
        (θ̇ and u̇ are their derivatives, so the error is O(Δt⁴) instead of linear
        interpolation's O(Δt²)), θ̇ and u̇ linearly. At an impact the stored points
        repeat the time, and the later (post-impact) one starts the next interval."""
        if not (dt > 0 and math.isfinite(dt)):
            raise ValueError(f"dt = {dt!r}: must be a positive finite number")
        if self.t.size == 0:
            return self
        tn = np.arange(int(math.floor(self.t[-1] / dt + 1e-9)) + 1) * dt
        # mode is piecewise constant: take the mode of the last stored point at or before tn
        idx = np.clip(np.searchsorted(self.t, tn, side="right") - 1, 0, self.t.size - 1)
        return Trajectory(
            engine=self.engine, system=self.system, t=tn,
            u=hermite(self.t, self.u, self.u_dot, tn), u_dot=np.interp(tn, self.t, self.u_dot),
            theta=hermite(self.t, self.theta, self.theta_dot, tn),
            theta_dot=np.interp(tn, self.t, self.theta_dot),
            mode=self.mode[idx], impacts=self.impacts, uplift_times=self.uplift_times,
            overturned=self.overturned, overturn_time=self.overturn_time,
            impact_threshold=self.impact_threshold, runtime_s=self.runtime_s,
            status=self.status, message=self.message, energy=None, extras={
                k: v for k, v in self.extras.items() if np.isscalar(v)},
        )

    def _one_row_per_time(self) -> np.ndarray:
        """The rows the tables keep: an impact is stored twice at its time (the states just
        before and just after it); the post-impact row, the one the history continues
        from, is kept, so that t increases strictly."""
        keep = np.ones(self.t.size, dtype=bool)
        keep[:-1] = self.t[1:] != self.t[:-1]  # drop a row whose time the next row repeats
        return keep

    def to_dataframe(self):
        """The history as a pandas DataFrame, one row per time (the rows of to_csv): t (s),
        u (m), u_dot (m/s), theta (rad), theta_dot (rad/s), theta_over_alpha and mode (0
        translation, ±1 rocking); `.attrs` holds the engine and the summary() metrics.
        Needs pandas (`pip install 'isorock[notebook]'`)."""
        pd = import_extra("pandas", "notebook", "Trajectory.to_dataframe")
        keep = self._one_row_per_time()
        frame = pd.DataFrame({"t": self.t[keep], "u": self.u[keep], "u_dot": self.u_dot[keep],
                              "theta": self.theta[keep], "theta_dot": self.theta_dot[keep],
                              "theta_over_alpha": self.theta[keep] / self.alpha, "mode": self.mode[keep]})
        frame.attrs.update(engine=self.engine, summary=self.summary())
        return frame

    def to_csv(self, path) -> None:
        """The history as CSV, one row per time (_one_row_per_time)."""
        keep = self._one_row_per_time()
        rows = np.column_stack([self.t, self.u, self.u_dot, self.theta, self.theta_dot])[keep]
        np.savetxt(path, rows,
                   delimiter=",", header="t,u,u_dot,theta,theta_dot", comments="", fmt="%.10g")


def cumulative_impact_loss(t: np.ndarray, impact_times, losses) -> np.ndarray:
    """Energy lost in impacts up to each stored time (J). An integrator stores each
    piece between events from its start, so an impact's time appears twice: the first
    point (closing the piece before) precedes the impact, the repeated one follows it."""
    t = np.asarray(t, dtype=float)
    if len(losses) == 0:
        return np.zeros_like(t)
    at = np.asarray(impact_times, dtype=float)
    padded = np.concatenate([[0.0], np.cumsum(losses)])
    after = np.zeros(t.size, dtype=bool)
    after[1:] = t[1:] == t[:-1]
    return np.where(after, padded[np.searchsorted(at, t, side="right")],
                    padded[np.searchsorted(at, t, side="left")])


#: A statue has slid once its slide x passes this fraction of its half width b: far above a
#: contact's compliance and creep (the contact engines' pivot moves up to 4e-4·b while it
#: rocks without slipping), well below a slide that matters. Contact engines' runs of a
#: statue without friction are flagged as slid past it (validate.core.measure).
SLIDING_FRACTION = 0.01


def first_passage(t, x, level: float) -> float | None:
    """The first time (s) |x| exceeds `level`, interpolated linearly between the samples
    around it (None: never)."""
    t, a = np.asarray(t, dtype=float), np.abs(np.asarray(x, dtype=float))
    over = np.flatnonzero(a > level)
    if not over.size:
        return None
    i = int(over[0])
    if i == 0 or a[i] == a[i - 1]:
        return float(t[i])
    return float(t[i - 1] + (t[i] - t[i - 1]) * (level - a[i - 1]) / (a[i] - a[i - 1]))


def half_cycles(theta: np.ndarray) -> list[tuple[int, float]]:
    """Sign changes of a sampled θ: (index of the first sample after the change,
    largest |θ| of the half-cycle ending in it). Zero samples carry no sign, so a
    block that lands and later rocks the other way changes sign once."""
    theta = np.asarray(theta, dtype=float)
    nz = np.flatnonzero(theta)
    if nz.size < 2:
        return []
    signs = np.sign(theta[nz])
    changes = nz[1:][signs[1:] != signs[:-1]]
    if changes.size == 0:
        return []
    # each half-cycle runs from the previous change (inclusive) to this one (exclusive)
    peaks = np.maximum.reduceat(np.abs(theta), np.concatenate([[0], changes]))[:-1]
    return [(int(i), float(p)) for i, p in zip(changes, peaks)]


def counted_sign_changes(theta: np.ndarray, alpha: float, threshold: float = DEFAULT_IMPACT_THRESHOLD):
    """model.md's rule on a sampled history: indices of sign changes whose
    half-cycle peak exceeds threshold·α."""
    return [(i, peak) for i, peak in half_cycles(theta) if peak > threshold * alpha]


def hermite(t: np.ndarray, y: np.ndarray, dy: np.ndarray, tn: np.ndarray) -> np.ndarray:
    """Cubic Hermite interpolation of y (with derivative dy) at times tn; repeated times
    (the two sides of an impact) are handled by starting each interval at the last of them."""
    t, y, dy, tn = (np.asarray(a, dtype=float) for a in (t, y, dy, tn))
    if t.size < 2:
        return np.full(tn.shape, y[0] if y.size else 0.0)
    i = np.clip(np.searchsorted(t, tn, side="right") - 1, 0, t.size - 2)
    # an interval of zero length (an impact at the last point) cannot be used
    h = t[i + 1] - t[i]
    zero = h <= 0
    i = np.where(zero, np.maximum(i - 1, 0), i)
    h = t[i + 1] - t[i]
    safe = np.where(h > 0, h, 1.0)
    x = np.clip((tn - t[i]) / safe, 0.0, 1.0)
    h00, h10 = 2 * x**3 - 3 * x**2 + 1, x**3 - 2 * x**2 + x
    h01, h11 = -2 * x**3 + 3 * x**2, x**3 - x**2
    out = h00 * y[i] + h10 * safe * dy[i] + h01 * y[i + 1] + h11 * safe * dy[i + 1]
    return np.where(h > 0, out, y[i])
