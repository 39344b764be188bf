"""The analytic engine ("analytic"): the hybrid model compiled with numba. The physics is
analytic/physics.py, which the SciPy reference path (analytic/hybrid.py, engine
"analytic-reference") calls too; here it is compiled into the kernel. Same integrator
and event logic as the reference, two to three orders of magnitude faster.

Why it matches the reference to ~1e-13 rad on Kobe rather than only to its tolerance
(1e-10 relative): the kernel is a port of what `analytic.hybrid.simulate` asks SciPy to
do, namely `solve_ivp(method="DOP853", dense_output=True, events=...)` restarted at every
event and every kink of the ground motion. That includes SciPy's initial-step heuristic
(after every event), its step-size controller, its 7th-order dense output, its rule for
which events fired in a step (sign change between step ends, `find_active_events`) and
Brent's method on the dense output (xtol = rtol = 4·eps). Where a piece only continues
the last one across a kink of a record (no event between them) the kernel carries on
with the step the controller proposed and the last stage of the last step, where the
reference starts afresh with the heuristic: two evaluations and often a step fewer per
sample of a rocking phase, a difference in θ of ~1e-13 (the reference's own error at
rtol 1e-10 on Kobe). Taking nearly the same steps, the kernel misses the grazing
crossings the reference misses, so the two take the same branch at every event that the
integrator's tolerance resolves.

Speed comes from doing that work without Python: no per-step allocation, the dense
output (3 extra stages) built only where a stored point or an event needs it, events
evaluated on only the components they read, θ and θ̇ skipped in translation (their
rates are zero), a record read as one sample interval per piece (pieces restart
at every sample), and no reference counting in the loop (`_borrowed`). These change
results only at rounding level.

One place where the kernel does not port the reference: an isolated base in pure
translation under a record is a linear oscillator driven by a piecewise-linear ẍg, and
the kernel solves it in closed form over each sample interval (physics.translation_*:
state, the ground's work and the dashpot's loss exact to rounding), with uplift and the
extremes of u located on the closed form itself. That is most of a record's run on an
isolated base, ~20 times cheaper than DOP853 steps, and it agrees with the reference to
~1e-13 (the reference's own error at rtol 1e-10). It also finds an excursion of |a|
past g·tanα that lies between two integrator steps, which a sign test at step ends
(the reference) can miss. Pulses, fixed bases and rocking are integrated as before.

Beyond the reference: extremes of u (u̇ = 0) are located as events too, so u_max is
exact and those times are stored (the reference reads u_max off its stored points;
the two agree to ~1e-5 relative). Where the reference leaves SciPy to IEEE arithmetic
(Brent's step and the error norm dividing by an underflowed zero, once a free vibration
has decayed into denormals), the kernel says what C would have done instead of raising
ZeroDivisionError.

Every isolator of the System (linear, bilinear bearing, friction pendulum) runs here: the
non-linear ones in a second kernel compiled from the same source (`_integrate_iso`, see "one
source, two kernels" below; docs/isolators.md), a port of hybrid._IsolatorIntegrator that
agrees with it to ~1e-11 (docs/scripts/kernel_isolator_agreement.py).

Public entry points:
- `simulate_fast(system, motion, ...) -> Trajectory`, engine "analytic" (formerly
  "analytic-fast", a name that still works);
- `simulate_batch(systems, motions, ...) -> list[dict]`, summaries over many cases
  on all cores (Python threads over the GIL-free kernel), any mix of isolators;
- `compare_on_grid(a, b)`, the largest |Δθ| of two histories on their shared output grid.
(`isorock bench` times the kernel against the reference: validate/tools/bench.py.)

The kernel is compiled on first use (said on stderr, with how long it took) and cached on
disk (analytic/kernel_cache.py: stamped with physics.py too, a writable folder found for
a read-only install, a damaged cache rebuilt), so a new process loads it instead of
compiling again. It is compiled ahead of time (numba.pycc) into an extension module: a
new process's first run then takes its own run time plus milliseconds, not the ~1 s
numba's JIT needs to start; the JIT kernel is the fallback where no C compiler is found.
"""
from __future__ import annotations

import math
import threading
import time
import types
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np
from numba import types as nt

try:
    from numba import njit
    from numba.core import types as _nbtypes
    from numba.core.extending import intrinsic
except ImportError as e:  # pragma: no cover - numba is a declared dependency
    raise ImportError(
        "analytic.fast needs the 'numba' package (the JIT compiler of its kernel); "
        "install it with `pip install numba` (it is listed in pyproject.toml's dependencies)"
    ) from e


from . import physics
from .errors import InputError, require, require_positive_finite
from .kernel_cache import ahead_of_time, cached_jit, call_kernel
from .dop853 import _A, _B, _C, _D, _E3, _E5
from .limits import available_cores, energy_balance_failure
from .overturning import describe, theta_max_over_alpha
from . import slide_fast
from .settings import AnalyticSettings
from .motion import GroundMotion
from .engine_protocol import check_isolator_kind, run_inputs
from .slide_physics import needs_contact_model
from .status import Status
from .system import ISOLATOR_KINDS, System
from .trajectory import DEFAULT_IMPACT_THRESHOLD, EnergyLog, Impact, Trajectory, cumulative_impact_loss

ENGINE = "analytic"


def _nonzero_rows(a):
    """Per row, the columns of its non-zero entries (padded), and how many: the stage
    sums skip DOP853's many zero coefficients."""
    a = np.atleast_2d(a)
    nnz = (a != 0).sum(axis=1)
    idx = np.zeros((a.shape[0], max(int(nnz.max()), 1)), dtype=np.int64)
    for r in range(a.shape[0]):
        cols = np.nonzero(a[r])[0]
        idx[r, :cols.size] = cols
    return idx, nnz.astype(np.int64)


_A_IDX, _A_NNZ = _nonzero_rows(_A)
_B_IDX, _B_NNZ = _nonzero_rows(_B)
_E_IDX, _E_NNZ = _nonzero_rows((_E3 != 0) | (_E5 != 0))
_D_IDX, _D_NNZ = _nonzero_rows((_D != 0).any(axis=0))
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0  # scipy.integrate._ivp.rk
_EPS = float(np.finfo(float).eps)

# packed system and motion parameters: analytic.physics's layout
from .physics import (ALPHA_NEG as _ALPHA_NEG, GRAZE_MARGIN as _GRAZE, ALPHA as _ALPHA, FIXED as _FIXED, INV_DT as _INV_DT, KIND as _KIND,  # noqa: E402
                      M_BLOCK as _M_BLOCK, M_TOTAL as _M_TOTAL, PA0 as _PA0, PA1 as _PA1, PI as _PI,
                      PIECE as _PIECE, DT as _DT, END as _END, SAMPLED as _SAMPLED, THR as _THR, SIDE_ANGLE as _SIDE,
                      C_DAMP as _C_DAMP, K as _K, INV_M as _INV_M, G as _G)

# statuses
_COMPLETED, _OVERTURNED, _EVENT_LIMIT, _FAILED = 0, 1, 2, 3
_NO_ROOM = 4  # internal: the run filled its outputs; _call_integrate runs it again with more
_BATCH_ROOM = 256  # impacts and uplifts a batch run has room for at first
STATUS_NAMES = (Status.COMPLETED, Status.OVERTURNED, Status.EVENT_LIMIT, Status.FAILED)
# event slots: translation (0 lift about O, 1 lift about O', 3 u̇ = 0); rocking (0 impact,
# 1 |θ| rising through α, 2 θ̇ = 0, 3 u̇ = 0, 4 |θ| reaching π/2). Slot 3 only on an
# isolated base: it locates the extremes of u so that u_max is exact (the reference
# reads it off its stored points). Slot 1 ends the run under the rule "alpha" (and on a
# fixed base after the motion), slot 4 under "past-alpha"; otherwise slot 1 is noted only.
_N_EV = 5
_DIRECTION = np.array([[1, 1, 0, 0, 0], [-1, 1, 0, 0, 1]], dtype=np.int64)

# --- one source, two kernels --------------------------------------------------------
# The kernel is compiled twice from the functions below (_isolator_kernel): for the
# linear isolator with _ISO False, where numba prunes every `if _ISO:` block before typing,
# so that what it compiles is the linear kernel as it was (same arithmetic, bit for bit); and
# for the non-linear isolators (docs/isolators.md) with _ISO True: the state carries the
# slider's loss S as a 7th component (_NY, as the reference's state does, so that the step
# sizes and error norms are the reference's), event slots 5 and 6 watch the slider (a slip
# stops: slot 5, direction −1; a stuck slider slips, or an elastic bearing yields, either
# way: slots 5 and 6, direction +1), and the slider's phase and position go from piece to
# piece. `iso`, the tuple the functions take, is that state within a piece (_IS_*). The
# linear kernel passes _NO_ISO, a float it never reads: a tuple of floats, passed by value to
# every call that is not inlined, cost it ~1% with stored histories.
_ISO = False
_NY = 6
_ISO_N_EV = 7
_N_REC = 128  # rows of the isolator kernel's record of its energy residual's growth
_DIP = 7  # a pseudo event slot of the isolator kernel: a slipping slider's phase·ü (_event_dense)
_ISO_DIRECTION = np.array([[1, 1, 0, 0, 0, 1, 1], [-1, 1, 0, 0, 1, 1, 1]], dtype=np.int64)
# iso tuple: physics.isolator_params's ip, I_KIND … I_FCONE (so that physics's isolator
# functions take it as their ip; _IS_UY is its I_UY, the element's u_y), then the rigid slider's
# stick limit (physics.stick_limit), the phase (0 stuck, ±1 or ±2 slipping: physics), the
# slider's position u_p, whether a slip started from u̇ = 0 at the piece's start, and σ·ü there
_IS_UY, _IS_FLIM, _IS_PH, _IS_UP, _IS_REST, _IS_START = physics.I_UY, 7, 8, 9, 10, 11
assert physics.N_IP == _IS_FLIM  # the tuple's layout above
_NO_ISO = 0.0
# ip, the array the isolator kernel takes: physics's ip
_IP_UY, _N_IPK = physics.I_UY, physics.N_IP
_ISO_FRICTION = float(physics.ISO_FRICTION)
_ISO_BILINEAR = float(physics.ISO_BILINEAR)
_ISO_CONE = float(physics.ISO_CONE)
_ISO_DOUBLE = float(physics.ISO_DOUBLE)


# --- reference counting off the hot path ----------------------------------------------

@intrinsic
def _borrowed(typingctx, a):
    """A view of the array `a` that numba does not reference-count (its meminfo is null,
    so every NRT_incref/decref on it is a null test instead of an atomic add). Numba
    increfs and decrefs an array at almost every assignment and inlined call; in the
    kernel's step loop those atomic operations took about half of the time, and two
    threads sharing one parameter array fought over its count's cache line. The caller
    keeps `a` itself alive for as long as the view is used."""
    if not isinstance(a, _nbtypes.Array):
        return None

    def codegen(context, builder, sig, args):
        from numba.np.arrayobj import make_array, populate_array  # lazy: compile time only
        src = make_array(a)(context, builder, value=args[0])
        dst = make_array(a)(context, builder)
        populate_array(dst, data=src.data, shape=src.shape, strides=src.strides,
                       itemsize=src.itemsize, meminfo=None)
        return dst._getvalue()
    return a(a), codegen


# --- the physics: analytic.physics, compiled --------------------------------------------

def _compile_physics():
    """analytic.physics's functions, compiled: each is rebuilt over a copy of the physics
    module's globals in which the functions it calls are the compiled ones (numba can
    only call compiled functions), then wrapped with njit. Nothing is compiled here;
    numba compiles them into the kernel (inlined where small) when the kernel compiles."""
    table = dict(vars(physics))
    inline = ("ground_acceleration", "piece_acceleration", "pulse_acceleration", "translation_acceleration",
              "rocking_accelerations", "rocking_accelerations_with", "base_acceleration", "oscillator_constants",
              "free_vibration_change", "rocking_pivot_force_ratio", "_times_a", "base_pinned",
              "isolator_element_force", "isolator_translation_acceleration", "isolator_rocking_accelerations",
              "pinned_rocking_accelerations", "isolator_base_acceleration", "stick_demand", "stick_limit",
              "slip_power", "slip_force", "rigid_demand", "element_hold", "slip_phase", "slider_position",
              "hidden_crossing", "vertex_function", "edge", "landing_side", "other_threshold")
    for name in ("edge", "landing_side", "other_threshold", "ground_acceleration",
                 "piece_acceleration", "record_piece", "pulse_acceleration",
                 "translation_acceleration",
                 "rocking_accelerations", "rocking_accelerations_with", "base_acceleration", "uplift_direction",
                 "relift", "lifts_clearly", "impact_function_order", "lift_order", "impact_continues", "impact_map", "kinetic_energy",
                 "impact_energy_loss", "pivot_force_ratio", "rocking_pivot_force_ratio", "overturn_code", "_bisect_ricker",
                 "_pulse_crossings", "first_uplift", "oscillator_constants", "free_vibration_change",
                 "free_vibration", "translation_start", "translation_state", "_energy_norm", "_times_a",
                 "_second_rate_norm",
                 "_oscillator_line", "_newton_bracket", "_oscillator_zeros", "translation_uplift",
                 "translation_velocity_zeros", "translation_u_bound", "base_pinned", "isolator_element_force",
                 "isolator_translation_acceleration", "isolator_rocking_accelerations",
                 "pinned_rocking_accelerations", "isolator_base_acceleration", "stick_demand", "stick_limit",
                 "slip_power", "slip_force", "rigid_demand", "element_hold", "slip_phase", "slider_position",
                 "vertex_rest_speed", "kinetic_energy", "hidden_crossing", "vertex_function",
                 "potential_energy", "element_energy", "balance_energy"):
        f = getattr(physics, name)
        rebuilt = types.FunctionType(f.__code__, table, f.__name__, f.__defaults__, f.__closure__)
        table[name] = njit(inline="always")(rebuilt) if name in inline else njit(rebuilt)
    return table


_P = _compile_physics()
_edge = _P["edge"]
_other_thr = _P["other_threshold"]
_xg = _P["ground_acceleration"]
_xgp = _P["piece_acceleration"]
_record_piece = _P["record_piece"]
_translation_acc = _P["translation_acceleration"]
_rocking_acc = _P["rocking_accelerations"]
_base_acc = _P["base_acceleration"]
_uplift_dir = _P["uplift_direction"]
_relift = _P["relift"]
_impact_order = _P["impact_function_order"]
_impact_continues = _P["impact_continues"]
_impact_map = _P["impact_map"]
_impact_loss = _P["impact_energy_loss"]
_friction = _P["pivot_force_ratio"]
_friction_rocking = _P["rocking_pivot_force_ratio"]
_overturn_code = _P["overturn_code"]
_first_uplift = _P["first_uplift"]
_tr_start = _P["translation_start"]
_tr_state = _P["translation_state"]
_tr_uplift = _P["translation_uplift"]
_tr_vzeros = _P["translation_velocity_zeros"]
_tr_ubound = _P["translation_u_bound"]
_iso_tr_acc = _P["isolator_translation_acceleration"]
_iso_rocking_acc = _P["isolator_rocking_accelerations"]
_iso_base_acc = _P["isolator_base_acceleration"]
_stick_demand = _P["stick_demand"]
_rigid_demand = _P["rigid_demand"]
_slip_phase = _P["slip_phase"]
_slider_position = _P["slider_position"]
_vertex_rest_speed = _P["vertex_rest_speed"]
_kinetic = _P["kinetic_energy"]
_stick_limit = _P["stick_limit"]
_slip_power = _P["slip_power"]
_lift_order = _P["lift_order"]
_lifts_clearly = _P["lifts_clearly"]
_balance_energy = _P["balance_energy"]
_hidden_crossing = _P["hidden_crossing"]
_vertex_function = _P["vertex_function"]


assert physics.N_SP == 26 and physics.N_MP == 14  # the tuples below


@njit(inline="always")
def _sp_tuple(a):
    """The packed system parameters as a tuple: numba reference-counts an array at every
    inlined call it is passed to (function calls that also bar the optimizer), a tuple of
    floats never."""
    return (a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11], a[12], a[13],
            a[14], a[15], a[16], a[17], a[18], a[19], a[20], a[21], a[22], a[23], a[24], a[25])


@njit(inline="always")
def _tilt_share(sp, theta):
    """|θ| against its own edge's α, as a tilt of the weaker edge: θmax/α of a statue of two
    edges is the larger of θ⁺/α₊ and θ⁻/α₋ (Trajectory.theta_max_over_alpha); |θ| itself for the
    rectangle (α/α is 1 to the bit)."""
    alpha = _edge(sp, 1.0 if theta >= 0.0 else -1.0, _ALPHA, _ALPHA_NEG)
    return abs(theta) * (min(sp[_ALPHA], sp[_ALPHA_NEG]) / alpha)


@njit(inline="always")
def _mp_tuple(a):
    """The packed motion parameters of the current piece as a tuple (see _sp_tuple)."""
    return (a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11], a[12], a[13])


@njit(inline="always")
def _rhs(mode, t, y0, y1, y2, y3, sp, mp, iso):
    """Right-hand side of (u, u̇, θ, θ̇, ground work, dashpot loss) in `mode`, and of the
    slider's loss S on a non-linear isolator (hybrid._IsolatorIntegrator's); mp: the
    piece's motion parameters (physics.piece_acceleration)."""
    xg = _xgp(t, mp)
    c = sp[_C_DAMP]
    if _ISO:
        ph, up = iso[_IS_PH], iso[_IS_UP]
        slip = _slip_power(iso, ph, y1)
        if mode == 0:
            return (y1, _iso_tr_acc(sp, iso, ph, y0, y1, up, xg), 0.0, 0.0, -xg * sp[_M_TOTAL] * y1,
                    c * y1 * y1, slip)
        udd, thdd, L1 = _iso_rocking_acc(sp, iso, ph, float(mode), y2, y3, y0, y1, up, xg)
        return (y1, udd, y3, thdd, -xg * (sp[_M_TOTAL] * y1 + sp[_M_BLOCK] * L1 * y3), c * y1 * y1, slip)
    if mode == 0:
        if sp[_FIXED] != 0.0:
            return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        return y1, _translation_acc(sp, y0, y1, xg), 0.0, 0.0, -xg * sp[_M_TOTAL] * y1, c * y1 * y1
    udd, thdd, L1 = _rocking_acc(sp, float(mode), y2, y3, y0, y1, xg)
    Mw = 0.0 if sp[_FIXED] != 0.0 else sp[_M_TOTAL]
    return y1, udd, y3, thdd, -xg * (Mw * y1 + sp[_M_BLOCK] * L1 * y3), c * y1 * y1


@njit
def _eval_rhs(mode, t, y, out, sp, mp, iso):
    r = _rhs(mode, t, y[0], y[1], y[2], y[3], sp, mp, iso)
    out[0] = r[0]
    out[1] = r[1]
    out[2] = r[2]
    out[3] = r[3]
    out[4] = r[4]
    out[5] = r[5]
    if _ISO:
        out[6] = r[6]


# --- events -------------------------------------------------------------------------

@njit
def _impact_fun(s, theta, t, t0, kpow, limit):
    """hybrid._Integrator.impact_function: s·θ, divided by (t − t0)^k on a piece that
    starts at θ = 0 so that the root at t0 itself is not found."""
    if kpow == 0:
        return s * theta
    dt = t - t0
    if dt > 0:
        return s * theta / dt ** kpow
    return limit


@njit(inline="always")
def _slider_event(e, mode, t, u, ud, th, thd, xg, t0, sp, iso):
    """Slot 5 or 6 on a non-linear isolator (hybrid._IsolatorIntegrator.slider_events): a
    slipping slider's σ·u̇ (÷ (t − t0) for a slip that started from rest: STICK_BAND), and in
    slot 6 a returning cone's ball reaching its vertex (σ·u) or a double pendulum's second
    surface starting to slide (σ·(u − u_p) − u_y); a pinned rigid slider's ±demand − F_s, an
    elastic bearing's ±(u − u_p) − u_y."""
    ph = iso[_IS_PH]
    if ph != 0.0:
        if e == 6:
            sigma = 1.0 if ph > 0.0 else -1.0
            if iso[0] == _ISO_CONE:
                return _vertex_function(sigma, u, t <= t0)
            return sigma * (u - iso[_IS_UP]) - iso[_IS_UY]
        if iso[_IS_REST] != 0.0:
            return ph * ud / (t - t0) if t > t0 else iso[_IS_START]
        return ph * ud
    if iso[0] >= _ISO_FRICTION:
        demand = _rigid_demand(sp, iso, mode, th, thd, u, iso[_IS_UP], xg)
        return (demand - iso[_IS_FLIM]) if e == 5 else (-demand - iso[_IS_FLIM])
    return (u - iso[_IS_UP] - iso[_IS_UY]) if e == 5 else (iso[_IS_UP] - u - iso[_IS_UY])


@njit(inline="always")
def _event(e, mode, t, ud, th, thd, a, t0, kpow, limit, thr, u, xg, sp, iso):
    """Event slot e's function (see _DIRECTION) in `mode`; a: the base's absolute
    acceleration (translation), thr: the forward edge's uplift threshold (the backward edge's
    follows it, physics.other_threshold). Scalars only (see _sp_tuple); u, xg, sp and iso are
    read by the slider's slots only."""
    if _ISO:
        if e >= 5:
            return _slider_event(e, mode, t, u, ud, th, thd, xg, t0, sp, iso)
    if mode == 0:
        if e == 3:
            return ud
        return (-a - thr) if e == 0 else (a - _other_thr(sp, thr))
    s = float(mode)
    if e == 0:
        return _impact_fun(s, th, t, t0, kpow, limit)
    if e == 1:
        return s * th - _edge(sp, s, _ALPHA, _ALPHA_NEG)
    if e == 2:
        return thd
    if e == 4:
        return s * th - _SIDE
    return ud


@njit(inline="always")
def _dense1(F, y_old, x, i):
    """One component of SciPy's Dop853DenseOutput at x = (t − t_old)/h."""
    y = 0.0
    y = (y + F[6, i]) * x
    y = (y + F[5, i]) * (1.0 - x)
    y = (y + F[4, i]) * x
    y = (y + F[3, i]) * (1.0 - x)
    y = (y + F[2, i]) * x
    y = (y + F[1, i]) * (1.0 - x)
    y = (y + F[0, i]) * x
    return y + y_old[i]


@njit(inline="always")
def _dense_all(F, y_old, t_old, h, t, out, full):
    x = (t - t_old) / h
    for i in range(_NY):
        if full or i < 2 or i > 3:
            out[i] = _dense1(F, y_old, x, i)
        else:
            out[i] = y_old[i]  # zero rates in translation


@njit
def _event_dense(e, mode, t, F, y_old, t_old, h, sp, mp, t0, kpow, limit, thr, iso):
    x = (t - t_old) / h
    if _ISO:
        if e == _DIP:  # phase·ü of a slipping slider (a dip of its stop's function: _dip_root)
            u, ud = _dense1(F, y_old, x, 0), _dense1(F, y_old, x, 1)
            ph = iso[_IS_PH]
            if mode == 0:
                return ph * _iso_tr_acc(sp, iso, ph, u, ud, iso[_IS_UP], _xgp(t, mp))
            return ph * _iso_rocking_acc(sp, iso, ph, float(mode), _dense1(F, y_old, x, 2), _dense1(F, y_old, x, 3),
                                         u, ud, iso[_IS_UP], _xgp(t, mp))[0]
        if e >= 5:
            return _slider_event(e, mode, t, _dense1(F, y_old, x, 0), _dense1(F, y_old, x, 1),
                                 _dense1(F, y_old, x, 2), _dense1(F, y_old, x, 3), _xgp(t, mp), t0, sp, iso)
        if mode == 0 and e < 3:
            a = _iso_base_acc(sp, iso, iso[_IS_PH], _dense1(F, y_old, x, 0), _dense1(F, y_old, x, 1),
                              iso[_IS_UP], _xgp(t, mp))
            return (-a - thr) if e == 0 else (a - _other_thr(sp, thr))
    if mode == 0:
        if e == 3:
            return _dense1(F, y_old, x, 1)
        if sp[_FIXED] != 0.0:
            a = _xgp(t, mp)
        else:
            a = _base_acc(sp, _dense1(F, y_old, x, 0), _dense1(F, y_old, x, 1), 0.0)
        return (-a - thr) if e == 0 else (a - _other_thr(sp, thr))
    if e == 0:
        return _impact_fun(float(mode), _dense1(F, y_old, x, 2), t, t0, kpow, limit)
    if e == 1:
        return float(mode) * _dense1(F, y_old, x, 2) - _edge(sp, float(mode), _ALPHA, _ALPHA_NEG)
    if e == 2:
        return _dense1(F, y_old, x, 3)
    if e == 4:
        return float(mode) * _dense1(F, y_old, x, 2) - _SIDE
    return _dense1(F, y_old, x, 1)


@njit
def _brentq(e, mode, xa, xb, fpre, F, y_old, t_old, h, sp, mp, t0, kpow, limit, thr, iso):
    """scipy.optimize.brentq (Zeros/brentq.c) with xtol = rtol = 4·eps, on the dense
    output, as solve_ivp's solve_event_equation calls it; fpre is f(xa)."""
    xtol = 4.0 * _EPS
    rtol = 4.0 * _EPS
    xpre, xcur = xa, xb
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    fcur = _event_dense(e, mode, xcur, F, y_old, t_old, h, sp, mp, t0, kpow, limit, thr, iso)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if (fpre < 0.0) == (fcur < 0.0):
        return xcur  # rounding moved the sign change onto the step end
    for _ in range(100):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre = xcur
            xcur = xblk
            xblk = xpre
            fpre = fcur
            fcur = fblk
            fblk = fpre
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            # C's brentq divides by zero silently (inf, then bisection); event values in
            # denormals (a free vibration ~250 s old) make these denominators underflow
            if xpre == xblk:
                den = fcur - fpre
                stry = -fcur * (xcur - xpre) / den if den != 0.0 else math.inf
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                den = dblk * dpre * (fblk - fpre)
                stry = -fcur * (fblk * dblk - fpre * dpre) / den if den != 0.0 else math.inf
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = _event_dense(e, mode, xcur, F, y_old, t_old, h, sp, mp, t0, kpow, limit, thr, iso)
    return xcur


# --- DOP853 (scipy.integrate._ivp.rk.DOP853) ----------------------------------------

@njit
def _rms(x0, x1, x2, x3, x4, x5):
    return math.sqrt(x0 * x0 + x1 * x1 + x2 * x2 + x3 * x3 + x4 * x4 + x5 * x5) / math.sqrt(6.0)


@njit
def _rms7(x0, x1, x2, x3, x4, x5, x6):
    return math.sqrt(x0 * x0 + x1 * x1 + x2 * x2 + x3 * x3 + x4 * x4 + x5 * x5 + x6 * x6) / math.sqrt(7.0)


@njit
def _initial_step(mode, t0, y0, f0, t_bound, max_step, rtol, atol, tmp, f1, sp, mp, iso):
    """scipy.integrate._ivp.common.select_initial_step for order 7."""
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    if _ISO:  # the same with the slider's loss S, the 7th component
        s0, s1, s2 = atol + abs(y0[0]) * rtol, atol + abs(y0[1]) * rtol, atol + abs(y0[2]) * rtol
        s3, s4, s5 = atol + abs(y0[3]) * rtol, atol + abs(y0[4]) * rtol, atol + abs(y0[5]) * rtol
        s6 = atol + abs(y0[6]) * rtol
        d0 = _rms7(y0[0] / s0, y0[1] / s1, y0[2] / s2, y0[3] / s3, y0[4] / s4, y0[5] / s5, y0[6] / s6)
        d1 = _rms7(f0[0] / s0, f0[1] / s1, f0[2] / s2, f0[3] / s3, f0[4] / s4, f0[5] / s5, f0[6] / s6)
        if d0 < 1e-5 or d1 < 1e-5:
            h0 = 1e-6
        else:
            h0 = 0.01 * d0 / d1
        h0 = min(h0, interval)
        for i in range(_NY):
            tmp[i] = y0[i] + h0 * f0[i]
        _eval_rhs(mode, t0 + h0, tmp, f1, sp, mp, iso)
        d2 = _rms7((f1[0] - f0[0]) / s0, (f1[1] - f0[1]) / s1, (f1[2] - f0[2]) / s2,
                   (f1[3] - f0[3]) / s3, (f1[4] - f0[4]) / s4, (f1[5] - f0[5]) / s5, (f1[6] - f0[6]) / s6) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = math.sqrt(math.sqrt(math.sqrt(0.01 / max(d1, d2))))
        return min(100.0 * h0, h1, interval, max_step)
    s0, s1, s2 = atol + abs(y0[0]) * rtol, atol + abs(y0[1]) * rtol, atol + abs(y0[2]) * rtol
    s3, s4, s5 = atol + abs(y0[3]) * rtol, atol + abs(y0[4]) * rtol, atol + abs(y0[5]) * rtol
    d0 = _rms(y0[0] / s0, y0[1] / s1, y0[2] / s2, y0[3] / s3, y0[4] / s4, y0[5] / s5)
    d1 = _rms(f0[0] / s0, f0[1] / s1, f0[2] / s2, f0[3] / s3, f0[4] / s4, f0[5] / s5)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(6):
        tmp[i] = y0[i] + h0 * f0[i]
    _eval_rhs(mode, t0 + h0, tmp, f1, sp, mp, iso)
    d2 = _rms((f1[0] - f0[0]) / s0, (f1[1] - f0[1]) / s1, (f1[2] - f0[2]) / s2,
              (f1[3] - f0[3]) / s3, (f1[4] - f0[4]) / s4, (f1[5] - f0[5]) / s5) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = math.sqrt(math.sqrt(math.sqrt(0.01 / max(d1, d2))))  # (·)^(1/8), without pow
    return min(100.0 * h0, h1, interval, max_step)


@njit(inline="always")
def _stage(K, s, y, h, tmp, full):
    """tmp = y + h·Σ_j A[s, j] K[j] over the non-zero A[s, j] (rk.rk_step's np.dot).
    In translation (full False) θ and θ̇ have zero rates and are carried as they are."""
    a0 = a1 = a2 = a3 = a4 = a5 = a6 = 0.0
    if full:
        for q in range(_A_NNZ[s]):
            j = _A_IDX[s, q]
            a = _A[s, j]
            a0 += K[j, 0] * a
            a1 += K[j, 1] * a
            a2 += K[j, 2] * a
            a3 += K[j, 3] * a
            a4 += K[j, 4] * a
            a5 += K[j, 5] * a
            if _ISO:
                a6 += K[j, 6] * a
        tmp[2] = y[2] + a2 * h
        tmp[3] = y[3] + a3 * h
    else:
        for q in range(_A_NNZ[s]):
            j = _A_IDX[s, q]
            a = _A[s, j]
            a0 += K[j, 0] * a
            a1 += K[j, 1] * a
            a4 += K[j, 4] * a
            a5 += K[j, 5] * a
            if _ISO:
                a6 += K[j, 6] * a
        tmp[2] = y[2]
        tmp[3] = y[3]
    if _ISO:
        tmp[6] = y[6] + a6 * h
    tmp[0] = y[0] + a0 * h
    tmp[1] = y[1] + a1 * h
    tmp[4] = y[4] + a4 * h
    tmp[5] = y[5] + a5 * h


@njit(inline="always")
def _set_row(K, s, r):
    K[s, 0] = r[0]
    K[s, 1] = r[1]
    K[s, 2] = r[2]
    K[s, 3] = r[3]
    K[s, 4] = r[4]
    K[s, 5] = r[5]
    if _ISO:
        K[s, 6] = r[6]


@njit(inline="always")
def _rk_step(mode, t, y, h, K, tmp, y_new, sp, mp, iso):
    """One DOP853 step from (t, y) with K[0] = f(t, y) already set; fills K[1..12] and
    y_new (rk.rk_step). The stage sums are _stage's, written out (see _sp_tuple)."""
    full = mode != 0
    y0, y1, y2, y3 = y[0], y[1], y[2], y[3]
    for s in range(1, 12):
        a0 = a1 = a2 = a3 = 0.0
        for q in range(_A_NNZ[s]):
            j = _A_IDX[s, q]
            a = _A[s, j]
            a0 += K[j, 0] * a
            a1 += K[j, 1] * a
            if full:
                a2 += K[j, 2] * a
                a3 += K[j, 3] * a
        r = _rhs(mode, t + _C[s] * h, y0 + a0 * h, y1 + a1 * h, (y2 + a2 * h) if full else y2,
                 (y3 + a3 * h) if full else y3, sp, mp, iso)
        _set_row(K, s, r)
    for i in range(_NY):
        if mode == 0 and (i == 2 or i == 3):
            y_new[i] = y[i]
            continue
        acc_ = 0.0
        for q in range(_B_NNZ[0]):
            j = _B_IDX[0, q]
            acc_ += K[j, i] * _B[j]
        y_new[i] = y[i] + h * acc_
    _set_row(K, 12, _rhs(mode, t + h, y_new[0], y_new[1], y_new[2], y_new[3], sp, mp, iso))


@njit(inline="always")
def _error_norm(K, h, y, y_new, rtol, atol, full):
    e5sq = 0.0
    e3sq = 0.0
    for i in range(_NY):
        if not full and (i == 2 or i == 3):
            continue  # zero rates: no error
        sc = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        e5 = 0.0
        e3 = 0.0
        for q in range(_E_NNZ[0]):
            j = _E_IDX[0, q]
            e5 += K[j, i] * _E5[j]
            e3 += K[j, i] * _E3[j]
        e5 /= sc
        e3 /= sc
        e5sq += e5 * e5
        e3sq += e3 * e3
    den = (e5sq + 0.01 * e3sq) * (7.0 if _ISO else 6.0)
    if den == 0.0:  # both zero, or underflowed to zero from denormals: no error to speak of
        return 0.0
    return abs(h) * e5sq / math.sqrt(den)


@njit
def _dense_coeffs(mode, t_old, h, y_old, y_new, K, F, tmp, sp, mp, iso):
    """Extra stages 13-15 and the 7 interpolant rows (DOP853._dense_output_impl)."""
    for s in range(13, 16):
        _stage(K, s, y_old, h, tmp, mode != 0)
        _set_row(K, s, _rhs(mode, t_old + _C[s] * h, tmp[0], tmp[1], tmp[2], tmp[3], sp, mp, iso))
    for i in range(_NY):
        if mode == 0 and (i == 2 or i == 3):
            for r_ in range(7):
                F[r_, i] = 0.0
            continue
        dy = y_new[i] - y_old[i]
        F[0, i] = dy
        F[1, i] = h * K[0, i] - dy
        F[2, i] = 2.0 * dy - h * (K[12, i] + K[0, i])
        for r_ in range(4):
            acc_ = 0.0
            for q in range(_D_NNZ[0]):
                j = _D_IDX[0, q]
                acc_ += _D[r_, j] * K[j, i]
            F[3 + r_, i] = h * acc_


@njit
def _spacing(t):
    """np.nextafter(t, inf) − t for t ≥ 0, without the libm call."""
    if t == 0.0:
        return 5e-324
    e = math.frexp(t)[1]
    return max(math.ldexp(1.0, e - 53), 5e-324)  # subnormal t: the smallest step


# --- outputs of a fixed size ----------------------------------------------------------
# The kernel never reallocates (an array variable reassigned inside its loop would be
# reference-counted at every turn of it): a run that fills its room returns _NO_ROOM
# and its caller runs it again with more (_call_integrate).

# _store and the isolator's bookkeeping below (_next_point … _pivot_ratio) are compiled as
# functions of their own, not inlined into the kernel as the step's arithmetic is: inlined at
# their 40-odd call sites they doubled the isolator kernel's build (157 s and 2.7 GB against
# 80 s and 1.7 GB, a fresh build on the shared 2 cores) for no speed (farm-bench A/B of the
# kernels on a pulse and Kobe, both bases and a pendulum: CPU median 0.995, n = 11); not
# inlining the events too (_event, _slider_event) saved memory (1.1 GB) but cost 4.5%.
@njit
def _store(out_t, out_y, out_m, n, t, y, mode, out_ph, out_up, iso):
    """Store one point at index n; False (nothing stored) when the arrays are full. On a
    non-linear isolator also its phase and slider (which moves with a yielding bearing)."""
    if n >= out_t.size:
        return False
    out_t[n] = t
    for i in range(_NY):
        out_y[i, n] = y[i]
    out_m[n] = mode
    if _ISO:
        ph = iso[_IS_PH]
        out_ph[n] = ph
        out_up[n] = _slider_position(iso, ph, y[0], iso[_IS_UP])
    return True


@njit
def _next_point(kg, odt, grid, t_stop, roots, n_roots, kr, offset):
    """The next time to store or measure, merging two ordered sequences: grid points kg·odt
    below t_stop (when `grid`) and roots[kr] + offset (kr < n_roots); a tie takes the root.
    Returns (found, t, kg, kr) with the index taken advanced."""
    tg = kg * odt
    take_grid = grid and tg < t_stop
    take_root = kr < n_roots
    if not take_grid and not take_root:
        return False, 0.0, kg, kr
    if take_root and (not take_grid or roots[kr] + offset <= tg):
        return True, roots[kr] + offset, kg, kr + 1
    return True, tg, kg + 1, kr


# --- the isolator's slider (hybrid._IsolatorIntegrator), compiled ------------------------

@njit
def _iso_state(ipk, phase, u_p, rest, start):
    """The iso tuple of a piece (_IS_*) from the run's isolator constants ipk (physics's ip,
    u_y, stick limit: the tuple's first _IS_PH entries)."""
    return (ipk[0], ipk[1], ipk[2], ipk[3], ipk[4], ipk[5], ipk[6], ipk[7], phase, u_p, rest, start)


@njit
def _stick_or_slip(sp, iso, mode, theta, theta_dot, u, xg):
    """A rigid slider's phase at rest (u̇ = 0): 0 if its demand is within the stick limit, else
    a slip its way (hybrid._IsolatorIntegrator.stick_or_slip; iso's phase and u_p: now)."""
    u_p = _slider_position(iso, iso[_IS_PH], u, iso[_IS_UP])
    demand = _rigid_demand(sp, iso, mode, theta, theta_dot, u, u_p, xg)
    if abs(demand) <= iso[_IS_FLIM]:
        return 0.0
    return _slip_phase(iso, 1.0 if demand > 0 else -1.0, u, u_p)


@njit
def _phase_after_velocity(sp, iso, phase, mode, theta, theta_dot, u, u_dot, xg):
    """The phase a new base velocity (after an impact) leaves the slider in."""
    if iso[0] >= _ISO_FRICTION:
        if u_dot == 0.0:
            return _stick_or_slip(sp, iso, mode, theta, theta_dot, u, xg)
        sigma = 1.0 if u_dot > 0 else -1.0
        if phase * sigma > 0.0:
            return phase  # on its way still (a cone's side, a double pendulum's regime)
        return _slip_phase(iso, sigma, u, _slider_position(iso, phase, u, iso[_IS_UP]))
    if phase != 0.0 and phase * u_dot <= 0:
        return 0.0  # the bearing unloads elastically
    return phase


@njit
def _iso_relift(sp, iso, phase, u, u_dot, u_p, xg):
    """physics.relift on the isolator (hybrid._IsolatorIntegrator.relift)."""
    side = _uplift_dir(sp, _iso_base_acc(sp, iso, phase, u, u_dot, u_p, xg))
    if side == 0:
        return 0
    thdd = _iso_rocking_acc(sp, iso, phase, float(side), 0.0, 0.0, u, u_dot, u_p, xg)[1]
    return side if _lifts_clearly(sp, side, thdd) else 0


@njit
def _set_phase(ipk, phase, u_p, u, u_dot, new):
    """hybrid._IsolatorIntegrator.set_phase: (phase, u_p, u̇) once the slider takes phase
    `new`: a yielding bearing's slider stops where it is, a sticking pendulum's base rests."""
    if new == phase:
        return phase, u_p, u_dot
    u_p = _slider_position(ipk, phase, u, u_p)  # a yielded element's slider stops where it is
    if new == 0.0 and ipk[0] >= _ISO_FRICTION:
        u_dot = 0.0
    return new, u_p, u_dot


@njit
def _log_phase(iev, n, t, phase, u):
    """Row n of the isolator's events (t, phase after, u); -1 when they are full (_NO_ROOM)."""
    if n == iev.shape[0]:
        return -1
    iev[n, 0] = t
    iev[n, 1] = phase
    iev[n, 2] = u
    return n + 1


@njit
def _base_acc_of(sp, u, u_dot, xg, iso):
    """The base's absolute acceleration in translation (the uplift events read it)."""
    if _ISO:
        return _iso_base_acc(sp, iso, iso[_IS_PH], u, u_dot, iso[_IS_UP], xg)
    return _base_acc(sp, u, u_dot, xg)


@njit
def _pivot_ratio(sp, mode, theta, theta_dot, u, u_dot, xg, iso):
    """physics.pivot_force_ratio, with the isolator's accelerations on a non-linear one."""
    if _ISO:
        ph, up = iso[_IS_PH], iso[_IS_UP]
        if mode == 0:
            return abs(_iso_base_acc(sp, iso, ph, u, u_dot, up, xg)) / sp[_G]
        udd, thdd, _l1 = _iso_rocking_acc(sp, iso, ph, float(mode), theta, theta_dot, u, u_dot, up, xg)
        return _friction_rocking(sp, float(mode), theta, theta_dot, udd, thdd, xg)
    return _friction(sp, mode, theta, theta_dot, u, u_dot, xg)


# --- the driver ---------------------------------------------------------------------

def _integrate_signature():
    """_integrate's argument types, for its ahead-of-time build (kernel_cache.ahead_of_time;
    numba infers what it returns): every array C-contiguous float64, which call_kernel
    makes them (a copy of one that is not, or is read-only)."""
    f8, i8, b1, vec = nt.float64, nt.int64, nt.boolean, nt.float64[::1]
    return (vec, vec, vec, vec, f8, vec, f8, f8, f8, i8, f8, b1, i8, f8, b1, f8, vec)


@ahead_of_time(_integrate_signature())
@cached_jit(nogil=True)
def _integrate(sp, mp, acc, breaks, T, y_init, rtol, atol, max_step, max_events, odt,
               history, cap, impact_frac, rule_alpha, motion_end, ip):
    """hybrid._Integrator.run. Returns (status, t_last, overturn_time, n_out, out_t,
    out_y, out_mode, n_imp, impacts, n_upl, uplifts, theta_max, u_max, verdict,
    friction_demand); the isolator kernel (_integrate_iso: hybrid._IsolatorIntegrator.run)
    also (out_phase, out_slider, n_iso_events, iso_events), its y_init and out_y with the
    slider's loss S as a 7th row, iso_events rows (t, phase after, u), and the energy balance
    read at every step end: (the largest energy involved (J), n_rec, rec) with rec's first
    n_rec rows (t, |residual| (J)) where |residual| first passed twice its last row, and last
    its largest (limits.energy_balance_failure reads them).

    ip: the isolator's constants (physics.isolator_params's ip; read by _integrate_iso only).

    history: store points (every odt, at every step end and event) in out_*;
    otherwise only the summary is kept. impacts rows: t, θ̇⁻, θ̇⁺, u̇⁻, u̇⁺, continued,
    amplitude, counted, kinetic energy lost (J). rule_alpha: the overturning rule
    "alpha" (else "past-alpha"); verdict: physics.overturn_code's, 0 if it survived.
    overturn_time: when |θ| last rose through α (nan if never)."""
    # the arguments are kept alive by the caller, the scratch arrays by `own` (used at
    # the end): every array of the loop below is a borrowed view (see _borrowed)
    sp = _sp_tuple(sp)
    acc = _borrowed(acc)
    breaks = _borrowed(breaks)
    fixed = sp[_FIXED] != 0.0
    own = np.zeros(mp.size + _NY + 16 * _NY + 7 * _NY + 4 * _NY + 3 * _N_EV + 4)
    own_flags = np.zeros(3 * _N_EV, dtype=np.bool_)
    own_ev = np.zeros(_N_EV, dtype=np.int64)
    work = _borrowed(own)
    flags = _borrowed(own_flags)
    root_ev = _borrowed(own_ev)
    o = 0
    mp_in = mp
    mp = work[o:o + mp_in.size]  # its piece slots change as the run goes
    o += mp_in.size
    mp[:] = mp_in
    mp[_PIECE] = 0.0
    mp[_INV_DT] = 1.0 / mp[_DT] if mp[_DT] > 0.0 else 0.0
    y = work[o:o + _NY]
    o += _NY
    y[:] = y_init
    t = 0.0
    cap = max(cap, 64)
    own_t = np.empty(cap if history else 1)
    own_y = np.empty((_NY, cap if history else 1))  # rows u, u̇, θ, θ̇, W, D (, S)
    own_m = np.empty(cap if history else 1, dtype=np.int8)
    own_imp = np.empty((cap, 9))
    own_upl = np.empty(cap)
    out_t = _borrowed(own_t)
    out_y = _borrowed(own_y)
    out_m = _borrowed(own_m)
    imp = _borrowed(own_imp)
    upl = _borrowed(own_upl)
    if _ISO:
        own_ph = np.zeros(cap if history else 1, dtype=np.int8)
        own_up = np.zeros(cap if history else 1)
        own_iev = np.empty((cap, 3))
        out_ph = _borrowed(own_ph)
        out_up = _borrowed(own_up)
        iev = _borrowed(own_iev)
    else:
        out_ph = out_m  # never written (_store's isolator part is pruned)
        out_up = out_t
    room = True  # False: an output is full, the run stops (_NO_ROOM)
    n_out = 0
    n_imp = 0
    n_upl = 0
    K = work[o:o + 16 * _NY].reshape((16, _NY))
    o += 16 * _NY
    F = work[o:o + 7 * _NY].reshape((7, _NY))
    o += 7 * _NY
    tmp = work[o:o + _NY]
    y_new = work[o + _NY:o + 2 * _NY]
    f1 = work[o + 2 * _NY:o + 3 * _NY]
    yq = work[o + 3 * _NY:o + 4 * _NY]
    o += 4 * _NY
    g_old = work[o:o + _N_EV]
    g_new = work[o + _N_EV:o + 2 * _N_EV]
    roots = work[o + 2 * _N_EV:o + 3 * _N_EV]
    o += 3 * _N_EV
    ext = work[o:o + 4]  # extremes of u inside a closed-form translation piece
    # closed-form translation pieces span at most 0.1 rad of the isolator's phase (records
    # are cut at every sample anyway; this bounds the tail after the record)
    cf_ok = not _ISO and not fixed and sp[_K] > 0.0
    cf_cap = 0.1 / math.sqrt(sp[_K] * sp[_INV_M]) if cf_ok else math.inf
    active = flags[0:_N_EV]
    use = flags[_N_EV:2 * _N_EV]
    terminal = flags[2 * _N_EV:3 * _N_EV]

    # the slider's phase and position (hybrid._IsolatorIntegrator.initial_state): a bearing
    # displaced to u0 was pushed there from its virgin state; a pendulum moving slips its
    # way, at rest it sticks unless its demand exceeds F_s
    phase = 0.0
    u_p = 0.0
    n_iev = 0
    if not _ISO:
        iso = _NO_ISO
    else:
        ipk = (ip[0], ip[1], ip[2], ip[3], ip[4], ip[5], ip[6], _stick_limit(sp, ip))
        if ipk[_IS_UY] > 0.0:  # a bearing's or double pendulum's element pushed to u0 from its virgin state
            u_p = y[0] - min(max(y[0], -ipk[_IS_UY]), ipk[_IS_UY])
        iso = _iso_state(ipk, 0.0, u_p, 0.0, 0.0)
        if ipk[0] >= _ISO_FRICTION:
            if y[1] != 0.0:
                phase = _slip_phase(iso, 1.0 if y[1] > 0.0 else -1.0, y[0], u_p)
            else:
                m0 = 0 if y[2] == 0.0 else (1 if y[2] > 0.0 else -1)
                phase = _stick_or_slip(sp, iso, m0, y[2], y[3], y[0], _xg(0.0, mp, acc))
        iso = _iso_state(ipk, phase, u_p, 0.0, 0.0)
    # the energy balance (EnergyLog), read at every step end: E(0), the impacts' loss so far, the
    # largest energy involved, and where |residual| first doubled (its growth, in _N_REC rows at
    # most: from rounding's 1e-20 J a wrong branch's joules are 70 doublings) and its largest
    e0 = 0.0
    imp_loss = 0.0
    e_held = 0.0
    n_rec = 0
    if _ISO:
        e0 = _balance_energy(sp, ipk, 1.0 if y[2] >= 0.0 else -1.0, y[0], y[1], y[2], y[3],
                             _slider_position(ipk, phase, y[0], u_p))
        e_held = abs(e0)
        own_rec = np.zeros((_N_REC, 2))
        rec = _borrowed(own_rec)
    else:
        own_rec = own_imp  # never written (the isolator's part is pruned)
        rec = imp
    if y[2] != 0.0:
        mode = 1 if y[2] > 0.0 else -1
    elif y[3] != 0.0:
        mode = 1 if y[3] > 0.0 else -1
    else:
        mode = _uplift_dir(sp, _base_acc_of(sp, y[0], y[1], _xg(0.0, mp, acc), iso))
        if mode != 0:
            upl[0] = 0.0
            n_upl = 1
            if _ISO:
                if ipk[0] >= _ISO_FRICTION and y[1] == 0.0:
                    # a rigid slider at rest takes its phase from the rocking block's demand
                    # (hybrid._IsolatorIntegrator.uplift_mode)
                    phase = _stick_or_slip(sp, iso, mode, y[2], y[3], y[0], _xg(0.0, mp, acc))
                    iso = _iso_state(ipk, phase, u_p, 0.0, 0.0)

    status = _COMPLETED
    verdict = 0
    t_alpha = np.nan
    n_events = 0
    ibreak = 1
    nb = breaks.size
    peak = 0.0
    th_max = 0.0
    u_max = 0.0
    demand = 0.0
    graze = False  # a grazing uplift stayed down: re-lift only clearly above g·tanα
    # a piece that only continues the last one across a kink of the ground motion (no
    # event between them) starts with the step the controller proposed and the last
    # stage of the last step (f there, the motion being continuous), not with SciPy's
    # initial-step heuristic: it saves two evaluations and, as often as not, a step
    carry = False
    h_next = 0.0
    while t < T:
        while ibreak < nb and breaks[ibreak] <= t + 1e-12:
            ibreak += 1
        t1 = breaks[ibreak] if ibreak < nb else T
        s = float(mode)
        tp0 = t
        if mp[_KIND] == _SAMPLED:
            _record_piece(mp, acc, t, t1)
        mpt = _mp_tuple(mp)  # the hot path reads the piece from this tuple
        closed = mode == 0 and (fixed or (cf_ok and mp[_PIECE] != 0.0))
        t_next, side = t, 0
        if mode == 0 and fixed:
            # the state cannot change: the first uplift is found from the motion itself
            mp[_PIECE] = 0.0
            t_up, side = _first_uplift(sp, mp, acc, t, t1, _GRAZE if graze else 0.0)
            kg = math.ceil(t / odt - 1e-9)
            tq = t
            while True:  # stored points: the piece's start, grid points, its end
                if history and (n_out == 0 or tq > out_t[n_out - 1]):
                    room = _store(out_t, out_y, out_m, n_out, tq, y, 0, out_ph, out_up, iso)
                    if not room:
                        break
                    n_out += 1
                demand = max(demand, _friction(sp, 0, 0.0, 0.0, y[0], y[1], _xg(tq, mp, acc)))
                if tq >= t_up:
                    break
                while kg * odt <= tq:
                    kg += 1
                tq = min(kg * odt, t_up)
            if not room:
                break
            t_next = t_up
        elif closed:
            # an isolated base in pure translation under a record: the linear oscillator in
            # closed form over the sample interval (physics.translation_*), uplift located on it
            t_end = min(t1, t + cf_cap)
            # after the record's end ẍg is zero (its value at the end instant is no ramp)
            a0 = _xgp(t, mpt) if mp[_PIECE] == 1.0 else 0.0
            a1 = (mp[_PA1] - mp[_PA0]) * mp[_INV_DT] if mp[_PIECE] == 1.0 else 0.0
            zu0, zv0, p0, p1 = _tr_start(sp, y[0], y[1], a0, a1)
            thr = sp[_THR] * (1.0 + (_GRAZE if graze else 0.0))
            u0, v0 = y[0], y[1]
            u1, v1, dW, dD = _tr_state(sp, zu0, zv0, p1, u0, v0, a0, a1, t_end - t)
            tau_up, side = _tr_uplift(sp, zu0, zv0, a0, a1, t_end - t, thr, _base_acc(sp, u1, v1, 0.0))
            t_stop = t_end
            if side != 0 and t + tau_up < t_end:
                t_stop = t + tau_up
                u1, v1, dW, dD = _tr_state(sp, zu0, zv0, p1, u0, v0, a0, a1, tau_up)
            h_stop = t_stop - t
            if history:
                room = _store(out_t, out_y, out_m, n_out, t, y, 0, out_ph, out_up, iso)
                if not room:
                    break
                n_out += 1
            u_max = max(u_max, abs(u0))
            demand = max(demand, _friction(sp, 0, 0.0, 0.0, u0, v0, a0))
            n_ext = 0
            if history or max(abs(u0), abs(u1)) + _tr_ubound(sp, zu0, zv0, h_stop) > u_max:
                n_ext = _tr_vzeros(sp, zu0, zv0, p1, h_stop, ext)
            kg = math.ceil(t / odt - 1e-9)
            kr = 0
            last_t = t
            while True:  # grid points (history) and extremes of u inside, in order
                found, tq, kg, kr = _next_point(kg, odt, history, t_stop, ext, n_ext, kr, t)
                if not found:
                    break
                if tq <= last_t or tq >= t_stop:
                    continue
                uq, vq, dWq, dDq = _tr_state(sp, zu0, zv0, p1, u0, v0, a0, a1, tq - t)
                yq[0], yq[1], yq[2], yq[3], yq[4], yq[5] = uq, vq, 0.0, 0.0, y[4] + dWq, y[5] + dDq
                if history:
                    room = _store(out_t, out_y, out_m, n_out, tq, yq, 0, out_ph, out_up, iso)
                    if not room:
                        break
                    n_out += 1
                last_t = tq
                u_max = max(u_max, abs(uq))
                demand = max(demand, _friction(sp, 0, 0.0, 0.0, uq, vq, _xgp(tq, mpt)))
            if not room:
                break
            y[0], y[1], y[4], y[5] = u1, v1, y[4] + dW, y[5] + dD
            if history and t_stop > last_t:
                room = _store(out_t, out_y, out_m, n_out, t_stop, y, 0, out_ph, out_up, iso)
                if not room:
                    break
                n_out += 1
            u_max = max(u_max, abs(u1))
            demand = max(demand, _friction(sp, 0, 0.0, 0.0, u1, v1, _xgp(t_stop, mpt)))
            t_next = t_stop
        if closed:
            # a translation piece done without the integrator (above) ends at t_next, and
            # the block lifts there about `side` unless side is 0
            t = t_next
            if side != 0:
                n_events += 1
                if n_events > max_events:
                    status = _EVENT_LIMIT
                    break
                mode = side
                if n_upl == upl.size:
                    room = False
                    break
                upl[n_upl] = t
                n_upl += 1
                peak = 0.0
                graze = False
            continue
        if (mode != 0 and not rule_alpha and fixed and t >= motion_end
                and s * y[2] > _edge(sp, s, _ALPHA, _ALPHA_NEG)
                and s * y[3] > 0.0):
            verdict = 3  # past α and falling after the motion: nothing can pull it back
            break
        thr = sp[_THR] * (1.0 + (_GRAZE if graze else 0.0))
        kpow = 0
        limit = 0.0
        if _ISO:
            iso = _iso_state(ipk, phase, u_p, 0.0, 0.0)
        if mode != 0 and y[2] == 0.0:
            if _ISO:  # hybrid._IsolatorIntegrator.function_order
                if y[3] != 0.0:
                    kpow, limit = 1, s * y[3]
                else:
                    kpow, limit = _lift_order(sp, s, _iso_rocking_acc(sp, iso, phase, s, 0.0, 0.0, y[0], y[1], u_p,
                                                                      _xgp(t, mpt))[1])
            else:
                kpow, limit = _impact_order(sp, s, y[0], y[1], y[3], _xgp(t, mpt))
        mi = 0 if mode == 0 else 1
        for e in range(_N_EV):
            use[e] = not ((e == 3 and fixed) or (mode == 0 and (e == 2 or e == 4))
                          or (e == 4 and rule_alpha))
            terminal[e] = e == 0 or e == 4 or (e == 1 and (mode == 0 or rule_alpha
                                                            or (fixed and tp0 >= motion_end)))
            if _ISO:
                terminal[e] = terminal[e] or e >= 5
                if e == 6:  # a stuck slider has two events (it slips either way), a slipping one
                    # one (it stops), and a returning cone's ball or a double pendulum in regime I two
                    use[e] = (phase == 0.0 or (ipk[0] == _ISO_CONE and abs(phase) == 2.0)
                              or (ipk[0] == _ISO_DOUBLE and abs(phase) == 1.0 and ipk[_IS_UY] > 0.0))
                if e == 3 and phase == 0.0 and ipk[0] >= _ISO_FRICTION:
                    use[e] = False  # a pinned base: u̇ ≡ 0, no extremes of u to locate
        # piece start: f, first step, events
        if carry:
            h_abs = h_next  # K[0] holds f at t already
        else:
            _eval_rhs(mode, t, y, tmp, sp, mpt, iso)
            for i in range(_NY):
                K[0, i] = tmp[i]
            h_abs = _initial_step(mode, t, y, tmp, t1, max_step, rtol, atol, yq, f1, sp, mpt, iso)
        carry = False
        h_full = 0.0
        if _ISO and phase != 0.0 and y[1] == 0.0:
            # a slip from u̇ = 0 (from rest, or reversing) is watched as σ·u̇/(t − t0), which
            # starts at σ·ü(t0) (hybrid: slider_events)
            iso = _iso_state(ipk, phase, u_p, 1.0, phase * K[0, 1])
        xg_now = _xgp(t, mpt) if _ISO else 0.0
        a_now = _base_acc_of(sp, y[0], y[1], _xgp(t, mpt), iso) if mode == 0 else 0.0
        for e in range(_N_EV):
            if use[e]:
                g_old[e] = _event(e, mode, t, y[1], y[2], y[3], a_now, tp0, kpow, limit, thr,
                                  y[0], xg_now, sp, iso)
        piece_out = n_out
        if history:
            room = _store(out_t, out_y, out_m, n_out, t, y, mode, out_ph, out_up, iso)
            if not room:
                break
            n_out += 1
        if mode != 0:
            peak = max(peak, abs(y[2]))
            th_max = max(th_max, _tilt_share(sp, y[2]))
        u_max = max(u_max, abs(y[0]))
        demand = max(demand, _pivot_ratio(sp, mode, y[2], y[3], y[0], y[1], _xgp(t, mpt), iso))
        kg = math.ceil(t / odt - 1e-9)
        last_t = t
        term = -1
        failed = False
        while True:
            # one accepted step (RungeKutta._step_impl)
            min_step = 10.0 * _spacing(t)
            if h_abs > max_step:
                h_abs = max_step
            elif h_abs < min_step:
                h_abs = min_step
            rejected = False
            while True:
                if h_abs < min_step:
                    failed = True
                    break
                t_new = t + h_abs
                clipped = t_new - t1 > 0.0
                if clipped:
                    t_new = t1
                h = t_new - t
                h_abs = abs(h)
                _rk_step(mode, t, y, h, K, tmp, y_new, sp, mpt, iso)
                err = _error_norm(K, h, y, y_new, rtol, atol, mode != 0)
                if err < 1.0:
                    if err == 0.0:
                        factor = _MAX_FACTOR
                    else:
                        factor = min(_MAX_FACTOR, _SAFETY / math.sqrt(math.sqrt(math.sqrt(err))))
                    if rejected:
                        factor = min(1.0, factor)
                    h_abs *= factor
                    if not clipped:
                        h_full = h_abs
                    break
                h_abs *= max(_MIN_FACTOR, _SAFETY / math.sqrt(math.sqrt(math.sqrt(err))))
                rejected = True
            if failed:
                break
            t_old = t
            finished = t_new - t1 >= 0.0
            # events that fired in this step (ivp.find_active_events); the dense output
            # is built once, if a root or a stored grid point needs it
            need_dense = history and kg * odt < t_new
            a_new = _base_acc_of(sp, y_new[0], y_new[1], _xgp(t_new, mpt), iso) if mode == 0 else 0.0
            xg_new = _xgp(t_new, mpt) if _ISO else 0.0
            for e in range(_N_EV):
                active[e] = False
                if not use[e]:
                    continue
                g_new[e] = _event(e, mode, t_new, y_new[1], y_new[2], y_new[3], a_new,
                                  tp0, kpow, limit, thr, y_new[0], xg_new, sp, iso)
                d = _DIRECTION[mi, e]
                if _ISO:
                    if e == 5 and phase != 0.0:
                        d = -1  # a slip stops: σ·u̇ falling through 0
                go, gn = g_old[e], g_new[e]
                up = go <= 0.0 and gn >= 0.0
                down = go >= 0.0 and gn <= 0.0
                if (up and d > 0) or (down and d < 0) or ((up or down) and d == 0):
                    active[e] = True
                    need_dense = need_dense or go != 0.0
            dip = t_new
            if _ISO:
                # a slip whose phase·u̇ dips through 0 and back within the step stops at its first
                # zero, though its sign at the step's ends is the same (hybrid: hidden_stop): where
                # phase·ü rises through 0 inside the step, at phase·u̇'s least
                if (phase != 0.0 and use[5] and not active[5] and g_old[5] > 0.0 and g_new[5] > 0.0
                        and phase * K[0, 1] < 0.0 and phase * K[12, 1] > 0.0):
                    _dense_coeffs(mode, t_old, h, y, y_new, K, F, tmp, sp, mpt, iso)
                    need_dense = False
                    fa = _event_dense(_DIP, mode, t_old, F, y, t_old, h, sp, mpt, tp0, kpow, limit, thr, iso)
                    fb = _event_dense(_DIP, mode, t_new, F, y, t_old, h, sp, mpt, tp0, kpow, limit, thr, iso)
                    if fa < 0.0 < fb:
                        t_m = _brentq(_DIP, mode, t_old, t_new, fa, F, y, t_old, h, sp, mpt, tp0, kpow, limit, thr,
                                      iso)
                        if phase * _dense1(F, y, (t_m - t_old) / h, 1) < 0.0:
                            active[5] = True
                            dip = t_m
            if need_dense:
                _dense_coeffs(mode, t_old, h, y, y_new, K, F, tmp, sp, mpt, iso)
            # their roots, in time order (ivp.handle_events, np.argsort)
            n_root = 0
            for e in range(_N_EV):
                if not active[e]:
                    continue
                go = g_old[e]
                if go == 0.0:
                    r = t_old  # brentq returns the bracket end where f is zero
                else:  # a dipping slip's stop lies before its least (dip)
                    r = _brentq(e, mode, t_old, dip if e == 5 else t_new, go, F, y, t_old, h, sp, mpt,
                                tp0, kpow, limit, thr, iso)
                k = n_root
                while k > 0 and roots[k - 1] > r:
                    roots[k] = roots[k - 1]
                    root_ev[k] = root_ev[k - 1]
                    k -= 1
                roots[k] = r
                root_ev[k] = e
                n_root += 1
            cut = n_root
            for k in range(n_root):
                if terminal[root_ev[k]]:
                    cut = k  # roots before it are kept; it ends the piece
                    term = root_ev[k]
                    break
            if _ISO:
                # a terminal event that the cut hid ends the piece instead, checked again from
                # the earlier cut (hybrid._IsolatorIntegrator.first_terminal)
                while term >= 0 and roots[cut] > t_old:
                    hid = -1
                    r_hid = roots[cut]
                    for e in range(_N_EV):
                        if not use[e] or not terminal[e] or e == term:
                            continue
                        d = _DIRECTION[mi, e]
                        if e == 5 and phase != 0.0:
                            d = -1  # a slip stops: σ·u̇ falling through 0
                        g_cut = _event_dense(e, mode, roots[cut], F, y, t_old, h, sp, mpt, tp0, kpow, limit, thr, iso)
                        if _hidden_crossing(d, g_old[e], g_cut):
                            r = _brentq(e, mode, t_old, roots[cut], g_old[e], F, y, t_old, h, sp, mpt,
                                        tp0, kpow, limit, thr, iso)
                            if r < r_hid:
                                hid = e
                                r_hid = r
                    if hid < 0:
                        break
                    while cut > 0 and roots[cut - 1] >= r_hid:
                        cut -= 1  # the roots after the new cut did not happen
                    roots[cut] = r_hid
                    root_ev[cut] = hid
                    term = hid
            for k in range(cut):
                if root_ev[k] == 1:
                    t_alpha = roots[k]  # |θ| rose through α, and the run goes on
            t_stop = roots[cut] if term >= 0 else t_new
            # stored points inside the step: grid points and non-terminal roots, in order
            if history:
                kr = 0
                while True:
                    found, tq, kg, kr = _next_point(kg, odt, True, t_stop, roots, cut, kr, 0.0)
                    if not found:
                        break
                    if tq <= last_t or tq >= t_stop:
                        continue
                    _dense_all(F, y, t_old, h, tq, yq, mode != 0)
                    room = _store(out_t, out_y, out_m, n_out, tq, yq, mode, out_ph, out_up, iso)
                    if not room:
                        break
                    n_out += 1
                    last_t = tq
                    if mode != 0:
                        peak = max(peak, abs(yq[2]))
                        th_max = max(th_max, _tilt_share(sp, yq[2]))
                    u_max = max(u_max, abs(yq[0]))
                    demand = max(demand, _pivot_ratio(sp, mode, yq[2], yq[3], yq[0], yq[1], _xgp(tq, mpt), iso))
            else:
                for k in range(cut):
                    if roots[k] <= t_old:
                        continue  # the step start, already counted
                    _dense_all(F, y, t_old, h, roots[k], yq, mode != 0)
                    if mode != 0:
                        peak = max(peak, abs(yq[2]))
                        th_max = max(th_max, _tilt_share(sp, yq[2]))
                    u_max = max(u_max, abs(yq[0]))
                    demand = max(demand, _pivot_ratio(sp, mode, yq[2], yq[3], yq[0], yq[1],
                                                      _xgp(roots[k], mpt), iso))
            if not room:
                break
            # the step end, or the event that ends the piece
            if term >= 0 and t_stop == t_old:
                for i in range(_NY):
                    yq[i] = y[i]
            elif term >= 0:
                _dense_all(F, y, t_old, h, t_stop, yq, mode != 0)
            else:
                for i in range(_NY):
                    yq[i] = y_new[i]
            if history and t_stop > last_t:
                room = _store(out_t, out_y, out_m, n_out, t_stop, yq, mode, out_ph, out_up, iso)
                if not room:
                    break
                n_out += 1
                last_t = t_stop
            if mode != 0:
                peak = max(peak, abs(yq[2]))
                th_max = max(th_max, _tilt_share(sp, yq[2]))
            u_max = max(u_max, abs(yq[0]))
            if mode != 0 and term < 0:  # the step's end: its last stage has ü and θ̈ there
                demand = max(demand, _friction_rocking(sp, s, yq[2], yq[3], K[12, 1], K[12, 3],
                                                       _xgp(t_stop, mpt)))
            else:
                demand = max(demand, _pivot_ratio(sp, mode, yq[2], yq[3], yq[0], yq[1], _xgp(t_stop, mpt), iso))
            t = t_stop
            for i in range(_NY):
                y[i] = yq[i]
                K[0, i] = K[12, i]  # f at the new step start (unused after a terminal event)
            if _ISO:
                e_now = _balance_energy(sp, ipk, s if mode != 0 else 1.0, y[0], y[1], y[2], y[3],
                                        _slider_position(ipk, phase, y[0], u_p))
                res = abs(e_now - e0 - y[4] + y[5] + imp_loss + y[6])
                e_held = max(e_held, abs(y[4]), abs(e_now), imp_loss, y[6])
                if n_rec == 0 or res > 2.0 * rec[n_rec - 1, 1]:
                    if n_rec < _N_REC - 1:  # the last row is the largest's
                        rec[n_rec, 0] = t
                        rec[n_rec, 1] = res
                        n_rec += 1
                if res > rec[_N_REC - 1, 1]:
                    rec[_N_REC - 1, 0] = t
                    rec[_N_REC - 1, 1] = res
            for e in range(_N_EV):
                g_old[e] = g_new[e]
            if term >= 0 or finished:
                break
        if not room:
            break
        if failed:
            status = _FAILED
            n_out = piece_out  # the reference drops a failed piece
            t = tp0
            break
        if term < 0:
            carry = True
            h_next = max(h_abs, h_full)  # a step cut short at the piece's end proposes less
            continue
        n_events += 1
        if n_events > max_events:
            status = _EVENT_LIMIT
            break
        if _ISO:
            if term >= 5:  # the slider sticks or slips (hybrid._IsolatorIntegrator.isolator_event)
                if term == 5 and phase != 0.0:  # a slip's u̇ crossed 0: located to rounding, made exact
                    y[1] = 0.0
                    new = 0.0
                    if ipk[0] >= _ISO_FRICTION:
                        new = _stick_or_slip(sp, iso, mode, y[2], y[3], y[0], _xgp(t, mpt))
                    if new * phase > 0.0:
                        new = 0.0  # slipping on the same way is rounding: the slider holds
                elif phase == 0.0 and ipk[0] >= _ISO_FRICTION:  # a pinned slider slips
                    new = _slip_phase(iso, 1.0 if term == 5 else -1.0, y[0], u_p)
                elif phase != 0.0 and ipk[0] == _ISO_CONE:  # the returning ball reaches the vertex
                    y[0] = 0.0
                    new = 1.0 if phase > 0.0 else -1.0
                    if abs(y[1]) < _vertex_rest_speed(sp, ipk):  # its Zeno tail: it rests there
                        sv = 1.0 if mode >= 0 else -1.0
                        y[6] += _kinetic(sp, sv, y[1], y[2], y[3]) - _kinetic(sp, sv, 0.0, y[2], y[3])
                        y[1] = 0.0
                        phase = 0.0
                        n_iev = _log_phase(iev, n_iev, t, phase, y[0])
                        if n_iev < 0:
                            room = False
                            break
                        new = _stick_or_slip(sp, _iso_state(ipk, phase, u_p, 0.0, 0.0), mode, y[2], y[3], y[0],
                                             _xgp(t, mpt))
                elif phase != 0.0:  # a double pendulum's second surface starts to slide
                    new = 2.0 if phase > 0.0 else -2.0
                else:  # the bearing yields
                    new = 1.0 if term == 5 else -1.0
                nph, u_p, y[1] = _set_phase(ipk, phase, u_p, y[0], y[1], new)
                if nph != phase:
                    phase = nph
                    n_iev = _log_phase(iev, n_iev, t, phase, y[0])
                    if n_iev < 0:
                        room = False
                        break
                if mode == 0:  # the base's acceleration may have jumped (the pendulum sticking)
                    side = _iso_relift(sp, iso, phase, y[0], y[1], u_p, _xgp(t, mpt))
                    if side != 0:
                        mode = side
                        if n_upl == upl.size:
                            room = False
                            break
                        upl[n_upl] = t
                        n_upl += 1
                        peak = 0.0
                        graze = False
                continue
        if mode != 0 and term == 1:
            t_alpha = t
            verdict = 1 if rule_alpha else 3
            break
        if mode != 0 and term == 4:
            verdict = 2
            break
        if mode != 0:  # impact at θ = 0 (hybrid._Integrator.impact)
            y[2] = 0.0
            thd_pre, ud_pre = y[3], y[1]
            continued = _impact_continues(sp, thd_pre)
            thd_post, ud_post = _impact_map(sp, thd_pre, ud_pre, continued)
            if n_imp == imp.shape[0]:
                room = False
                break
            imp[n_imp, 0] = t
            imp[n_imp, 1] = thd_pre
            imp[n_imp, 2] = thd_post
            imp[n_imp, 3] = ud_pre
            imp[n_imp, 4] = ud_post
            imp[n_imp, 5] = 1.0 if continued else 0.0
            imp[n_imp, 6] = peak
            imp[n_imp, 7] = 1.0 if peak > impact_frac * _edge(sp, float(mode), _ALPHA, _ALPHA_NEG) else 0.0
            imp[n_imp, 8] = _impact_loss(sp, ud_pre, thd_pre, ud_post, thd_post)
            imp_loss += imp[n_imp, 8]
            n_imp += 1
            peak = 0.0
            y[3] = thd_post
            y[1] = ud_post
            if continued:
                mode = -mode
            else:
                y[3] = 0.0
            if _ISO:  # the slider takes the new u̇ (hybrid._IsolatorIntegrator.after_impact)
                new = _phase_after_velocity(sp, iso, phase, mode if continued else 0, y[2], y[3], y[0], y[1],
                                            _xgp(t, mpt))
                nph, u_p, y[1] = _set_phase(ipk, phase, u_p, y[0], y[1], new)
                if nph != phase:
                    phase = nph
                    n_iev = _log_phase(iev, n_iev, t, phase, y[0])
                    if n_iev < 0:
                        room = False
                        break
            if not continued:
                if _ISO:
                    mode = _iso_relift(sp, iso, phase, y[0], y[1], u_p, _xgp(t, mpt))
                else:
                    mode = _relift(sp, y[0], y[1], _xgp(t, mpt))
                if mode != 0:
                    if n_upl == upl.size:
                        room = False
                        break
                    upl[n_upl] = t
                    n_upl += 1
                    graze = False
                else:
                    graze = True
        else:  # uplift
            mode = 1 if term == 0 else -1
            if n_upl == upl.size:
                room = False
                break
            upl[n_upl] = t
            n_upl += 1
            peak = 0.0
            graze = False
    if not room:
        status = _NO_ROOM
    if status == _COMPLETED and verdict == 0:
        end_side = 1.0 if y[2] >= 0.0 else -1.0
        verdict = _overturn_code(rule_alpha, y[2], _edge(sp, end_side, _ALPHA, _ALPHA_NEG), False)
    if verdict != 0:
        status = _OVERTURNED
    own[0] = own_flags.size + own_ev.size  # the owners of the borrowed views live until here
    if _ISO:
        return (status, t, t_alpha, n_out, own_t, own_y, own_m, n_imp, own_imp, n_upl, own_upl, th_max,
                u_max, verdict, demand, own_ph, own_up, n_iev, own_iev, e_held, n_rec, own_rec)
    return (status, t, t_alpha, n_out, own_t, own_y, own_m, n_imp, own_imp, n_upl, own_upl, th_max,
            u_max, verdict, demand)


# the functions compiled into the kernel that the isolator kernel rebuilds (see "one
# source, two kernels"): every one that reads _ISO, _NY, _N_EV or _DIRECTION, or calls one that does
_KERNEL_FUNCTIONS = ("_rhs", "_eval_rhs", "_slider_event", "_event", "_dense_all", "_event_dense", "_brentq",
                     "_initial_step", "_stage", "_set_row", "_rk_step", "_error_norm", "_dense_coeffs", "_store",
                     "_base_acc_of", "_pivot_ratio", "_stick_or_slip", "_phase_after_velocity", "_iso_relift")


def _isolator_kernel():
    """_integrate compiled with _ISO True (the non-linear isolators): its functions rebuilt
    over a copy of this module's globals (as _compile_physics does for analytic.physics),
    named _integrate_iso so that its caches (JIT and ahead of time) are its own."""
    table = dict(globals())
    table.update(_ISO=True, _NY=7, _N_EV=_ISO_N_EV, _DIRECTION=_ISO_DIRECTION)
    for name in _KERNEL_FUNCTIONS:
        dispatcher = table[name]
        f = dispatcher.py_func
        rebuilt = types.FunctionType(f.__code__, table, f.__name__, f.__defaults__, f.__closure__)
        inline = dispatcher.targetoptions.get("inline", "never")
        table[name] = njit(inline=inline)(rebuilt)
    f = _integrate.py_func
    rebuilt = types.FunctionType(f.__code__, table, "_integrate_iso", f.__defaults__, f.__closure__)
    rebuilt.__qualname__ = "_integrate_iso"
    rebuilt.__doc__ = f.__doc__
    return ahead_of_time(_integrate_signature())(cached_jit(nogil=True)(rebuilt))


_integrate_iso = _isolator_kernel()


# --- Python side: packing, the public wrapper, batches --------------------------------

def _call_integrate(*args, kernel=None):
    """call_kernel(kernel, *args) (default _integrate), run again with four times the room
    (args[12], `cap`) while a run reports that it filled its outputs (_NO_ROOM)."""
    kernel = _integrate if kernel is None else kernel
    while True:
        r = call_kernel(kernel, *args)
        if r[0] != _NO_ROOM:
            return r
        args = args[:12] + (4 * args[12],) + args[13:]


_LINEAR_IP = np.zeros(_N_IPK)


def _balance_failure(r):
    """limits.energy_balance_failure of an isolator kernel's run r (its energy balance, read at
    its step ends, as simulate_batch's rows read it too), or None."""
    held, n_rec, rec = r[19:22]
    rows = np.concatenate([rec[:n_rec], rec[-1:]])
    return energy_balance_failure(rows[:, 0], rows[:, 1], held)


def _kernel_for(system: System, settings: AnalyticSettings):
    """(kernel, sp, ip, state size) for a System: the linear kernel and physics.system_params
    for the linear isolator and the fixed base, as before; the isolator kernel with
    physics.isolator_params (K the parallel spring) and the element's constants otherwise."""
    if system.fixed_base or system.isolator is None:
        return _integrate, _system_params(system, settings), _LINEAR_IP, 6
    sp, ip = physics.isolator_params(system, settings.rest_velocity)
    return _integrate_iso, sp, ip, 7


_FAILED_MESSAGE = "Required step size is less than spacing between numbers."
_N_OUT = 10  # summary row: status, θmax, counted impacts, all impacts, uplifts,
#              last time past α, u_max, end time, overturning verdict, friction demand


def _system_params(system: System, settings: AnalyticSettings) -> np.ndarray:
    return physics.system_params(system, settings.rest_velocity)


def _motion_params(motion: GroundMotion):
    return physics.motion_params(motion)


def _breaks(motion: GroundMotion, duration: float) -> np.ndarray:
    """hybrid._Integrator's restart times: motion.breakpoints(duration) + [duration]."""
    return np.append(motion.breakpoints(duration), duration).astype(np.float64)


def _check_settings(settings: AnalyticSettings | None) -> AnalyticSettings:
    settings = settings or AnalyticSettings()
    require(isinstance(settings, AnalyticSettings), "settings", settings, "an AnalyticSettings")
    require(settings.method == "DOP853", "settings.method", settings.method,
            "'DOP853' (the only method the compiled kernel implements)")
    return settings


def _check_isolator(system) -> None:
    """The kernel carries the isolators of ISOLATOR_KINDS (the linear one in _integrate; the
    bilinear bearing, the single and double concave pendulums and the rolling balls in
    _integrate_iso); any other is refused, never run as linear."""
    if isinstance(system, System):
        check_isolator_kind(system, ISOLATOR_KINDS, "the compiled kernel (engine 'analytic')")


def _check_run(system, motion, duration, theta0, theta_dot0, u0, u_dot0, impact_threshold):
    """The input checks every engine shares (analytic.protocol)."""
    _check_isolator(system)
    return run_inputs(system, motion, duration, theta0, impact_threshold,
                      theta_dot0=theta_dot0, u0=u0, u_dot0=u_dot0, isolators=ISOLATOR_KINDS, two_edges=True)


def simulate_fast(system: System, motion: GroundMotion | None = None, *,
                  settings: AnalyticSettings | None = None, duration: float | None = None,
                  theta0: float = 0.0, theta_dot0: float = 0.0, u0: float = 0.0, u_dot0: float = 0.0,
                  impact_threshold: float = DEFAULT_IMPACT_THRESHOLD,
                  output_dt: float | None = None) -> Trajectory:
    """`analytic.hybrid.simulate`, compiled: same arguments, same Trajectory (engine
    "analytic-fast"), same impacts, uplifts and status, θ within ~1e-10 rad of it.

    theta0: initial tilt in rad (sign picks the corner). output_dt (s): stored points
    are at most this far apart (default settings.output_dt); every step end and event
    (θ̇ = 0, u̇ = 0, impacts, uplifts) is stored too, and each piece between restarts
    is stored from its start, so an event time appears twice, before and after.
    Only settings.method = "DOP853" is implemented.
    """
    start = time.perf_counter()  # runtime_s: everything this call takes, the kernel's loading included
    settings = _check_settings(settings)
    motion, duration = _check_run(system, motion, duration, theta0, theta_dot0, u0, u_dot0,
                                  impact_threshold)
    odt = settings.output_dt if output_dt is None else require_positive_finite("output_dt", output_dt)
    if needs_contact_model(system, motion):  # the statue may slip, or the ground heaves: docs/sliding.md
        return slide_fast.simulate(system, motion, replace(settings, output_dt=odt), duration, theta0, theta_dot0,
                                   u0, u_dot0, impact_threshold, ENGINE)
    kernel, sp, ip, n_y = _kernel_for(system, settings)
    mp, acc = _motion_params(motion)
    y0 = np.array([u0, u_dot0, theta0, theta_dot0, 0.0, 0.0, 0.0][:n_y])  # W, D (, S) from 0
    cap = int(2.5 * duration / odt) + 256  # grid points, step ends and events
    # plain float/int/bool, so that one compiled signature serves every call
    args = (sp, mp, acc, _breaks(motion, duration), float(duration), y0, float(settings.rtol),
            float(settings.atol), float(settings.max_step), int(settings.max_events), float(odt), True, cap,
            float(impact_threshold), settings.overturn == physics.AT_ALPHA, float(motion.end_time), ip)
    try:
        r = _call_integrate(*args, kernel=kernel)
    except ArithmeticError as e:  # a failed run is a status, not a traceback
        return _failed_trajectory(system, settings, impact_threshold, start, f"{type(e).__name__}: {e}")
    return _trajectory(system, settings, sp, mp, acc, r, impact_threshold, start, ip)


def _failed_trajectory(system, settings, impact_threshold, start, why) -> Trajectory:
    z = np.zeros(1)
    return Trajectory(
        engine=ENGINE, system=system, t=z, u=z, u_dot=z, theta=z, theta_dot=z, mode=np.zeros(1, np.int8),
        impact_threshold=impact_threshold, runtime_s=time.perf_counter() - start, status=Status.FAILED,
        message=f"the compiled kernel failed: {why}", extras={"overturn_rule": settings.overturn})


def _trajectory(system, settings, sp, mp, acc, r, impact_threshold, start, ip) -> Trajectory:
    status_code, t_last, t_alpha, n_out, out_t, out_y, out_m, n_imp, imp, n_upl, upl = r[:11]
    verdict, demand = int(r[13]), float(r[14])
    status = STATUS_NAMES[status_code]
    t_alpha = None if math.isnan(t_alpha) else float(t_alpha)
    t = out_t[:n_out]
    y = out_y[:, :n_out]
    mode = out_m[:n_out]
    if status == "completed":
        message = "reached the end time"
    elif status == "overturned":
        end_alpha = system.edge_alpha(1 if y[2, -1] >= 0 else -1)
        message = describe(verdict, t_last, t_alpha, float(y[2, -1]) / end_alpha)
    elif status == "event-limit":
        message = f"stopped after {settings.max_events} events at t = {t_last:.6g} s (max_events)"
    else:
        message = f"integration failed at t = {t_last:.6g} s: {_FAILED_MESSAGE}"
    imp = imp[:n_imp]
    impacts = tuple(
        Impact(t=row[0], theta_dot_pre=row[1], theta_dot_post=row[2], u_dot_pre=row[3],
               u_dot_post=row[4], continued=bool(row[5]), amplitude=row[6], counted=bool(row[7]))
        for row in imp.tolist())
    s = np.where(mode == 0, 1.0, mode)
    kin = physics.kinetic_energy(sp, s, y[1], y[2], y[3])
    pot = physics.potential_energy(sp, s, y[0], y[2])
    cum = cumulative_impact_loss(t, imp[:, 0], imp[:, 8])
    extras = {"overturn_rule": settings.overturn, "friction_demand": demand}
    if len(r) > 15:  # a non-linear isolator (hybrid._IsolatorIntegrator.trajectory)
        out_ph, out_up, n_iev, iev = r[15:19]
        u_p = out_up[:n_out]
        log = EnergyLog(kinetic=kin, potential=pot + physics.element_energy(ip, y[0], u_p), ground_work=y[4],
                        dashpot_loss=y[5], impact_loss=cum, per_impact=tuple(imp[:, 8].tolist()),
                        isolator_loss=y[6])
        extras.update(isolator=system.isolator_kind, isolator_phase=out_ph[:n_out].copy(), isolator_slider=u_p,
                      isolator_events=tuple((float(a), int(b), float(c)) for a, b, c in iev[:n_iev].tolist()))
        failure = _balance_failure(r) if status.ended_normally else None
        if failure:
            status, message = Status.FAILED, failure
    else:
        log = EnergyLog(kinetic=kin, potential=pot, ground_work=y[4], dashpot_loss=y[5], impact_loss=cum,
                        per_impact=tuple(imp[:, 8].tolist()))
    return Trajectory(
        engine=ENGINE, system=system, t=t, u=y[0], u_dot=y[1], theta=y[2], theta_dot=y[3],
        mode=mode, impacts=impacts, uplift_times=tuple(upl[:n_upl].tolist()),
        overturned=status == "overturned", overturn_time=t_alpha if status == "overturned" else None,
        impact_threshold=impact_threshold, runtime_s=time.perf_counter() - start, status=status,
        message=message, energy=log, extras=extras)


# --- many runs ---------------------------------------------------------------------

def _as_list(x, kind, name):
    if isinstance(x, kind):
        return [x]
    items = list(x)
    require(len(items) > 0, name, x, f"a {kind.__name__} or a non-empty sequence of them")
    for i, item in enumerate(items):
        require(isinstance(item, kind), f"{name}[{i}]", item, f"a {kind.__name__}")
    return items


def _cases(systems, motions, product):
    nsys, nmot = len(systems), len(motions)
    if product:
        i, j = np.meshgrid(np.arange(nsys), np.arange(nmot), indexing="ij")
        return i.ravel(), j.ravel()
    if nsys == nmot:
        return np.arange(nsys), np.arange(nmot)
    if nsys == 1:
        return np.zeros(nmot, dtype=np.int64), np.arange(nmot)
    if nmot == 1:
        return np.arange(nsys), np.zeros(nsys, dtype=np.int64)
    raise InputError(f"systems ({nsys}) and motions ({nmot}): must be as many, or one of them "
                     "a single item, or product=True for every combination")


def _per_case(value, n, name):
    a = np.asarray(value, dtype=float)
    if a.ndim == 0:
        a = np.full(n, float(a))
    require(a.shape == (n,), name, f"shape {a.shape}", f"a number or one per case ({n})")
    require(bool(np.all(np.isfinite(a))), name, value, "finite")
    return a


def simulate_batch(systems, motions=None, *, duration, theta0=0.0,
                   impact_threshold: float = DEFAULT_IMPACT_THRESHOLD,
                   settings: AnalyticSettings | None = None, product: bool = False,
                   workers: int | None = None) -> list[dict]:
    """Summaries of many runs of the hybrid model, on all cores.

    systems, motions: a System / GroundMotion or sequences of them. Paired one to one
    (a single item is used for every case), or every combination with product=True
    (systems outer, motions inner). duration (s) and theta0 (rad): a number or one per
    case (with one system and one motion, their length sets the number of cases). workers: how many
    threads (default: the cores this process may use); 1 runs serially in this thread. The
    threads run the GIL-free kernel (as fast here as numba's parallel loop, which needed a
    second compilation, or a process pool: both were dropped, unused; a table's processes
    are the executor's, validate/core/executor.py).

    Returns one dict per case: system, motion (indices), status, theta_max_over_alpha,
    impacts (counted by model.md's rule), impacts_all, uplifts, overturned,
    overturn_time (s or None), u_max (m, exact: extremes of u are located as events),
    duration (time reached, s). They equal the same fields of
    `simulate_fast(...)` (θmax and u_max to ~1e-12: without stored histories the
    kernel reads them at step ends and located extremes only).
    """
    settings = _check_settings(settings)
    systems = _as_list(systems, System, "systems")
    for system in systems:
        _check_isolator(system)
    motions = _as_list(motions if motions is not None else GroundMotion.zero(), GroundMotion, "motions")
    case_sys, case_mot = _cases(systems, motions, product)
    n = case_sys.size
    per_case = max(np.size(duration), np.size(theta0))
    if n == 1 and per_case > 1:  # one system and one motion, many durations or tilts
        case_sys, case_mot = np.repeat(case_sys, per_case), np.repeat(case_mot, per_case)
        n = per_case
    T = _per_case(duration, n, "duration")
    require(bool(np.all(T > 0)), "duration", duration, "positive")
    th0 = _per_case(theta0, n, "theta0")
    # θ0 below the α of the edge it tilts onto (a statue's two edges differ)
    edge_alphas = np.array([[s.edge_alpha(1), s.edge_alpha(-1)] for s in systems])
    limit = np.where(th0 >= 0, edge_alphas[case_sys, 0], edge_alphas[case_sys, 1])
    bad = np.abs(th0) >= limit
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"theta0 = {th0[k]!r} (case {k}): must be smaller than α = "
                         f"{limit[k]:.6g} rad in magnitude")
    require(0 <= impact_threshold < 1, "impact_threshold", impact_threshold, "in [0, 1)")
    if workers is not None:
        require(isinstance(workers, int) and workers >= 1, "workers", workers, "a positive integer")
    contact = np.array([needs_contact_model(systems[i], motions[j]) for i, j in zip(case_sys, case_mot)], bool)
    if not contact.any():
        return _batch_threads(systems, motions, case_sys, case_mot, T, th0, impact_threshold, settings, workers)
    # a statue that may slip, or a heaving ground: the sliding model's kernel (docs/sliding.md)
    rows = [None] * n
    rest = np.flatnonzero(~contact)
    if rest.size:
        for c, row in zip(rest, _batch_threads(systems, motions, case_sys[rest], case_mot[rest], T[rest], th0[rest],
                                               impact_threshold, settings, workers)):
            rows[c] = row
    for c, row in _contact_rows(systems, motions, case_sys, case_mot, T, th0, np.flatnonzero(contact),
                                impact_threshold, settings, workers):
        rows[c] = row
    return rows


def _contact_rows(systems, motions, case_sys, case_mot, T, th0, cases, impact_threshold, settings, workers):
    """(case, row) of the cases that need the sliding model, on threads over its GIL-free kernel."""
    def one(c):
        i, j = int(case_sys[c]), int(case_mot[c])
        try:
            row = slide_fast.summary(systems[i], motions[j], settings, float(T[c]), float(th0[c]), impact_threshold)
        except Exception as e:  # noqa: BLE001 - one case's failure is its row's status, never the batch's
            row = {"status": Status.FAILED, "theta_max_over_alpha": math.nan, "impacts": 0, "impacts_all": 0,
                   "uplifts": 0, "overturned": False, "overturn_time": None, "u_max": math.nan,
                   "duration": math.nan, "overturn_rule": settings.overturn, "friction_demand": math.nan,
                   "message": f"the compiled kernel failed: {type(e).__name__}: {e}"}
        return c, {"system": i, "motion": j, **row}
    if cases.size == 1 or workers == 1:
        return [one(c) for c in cases]
    pool = ThreadPoolExecutor(max_workers=workers or available_cores())
    try:
        return list(pool.map(one, cases))
    finally:
        pool.shutdown(wait=False, cancel_futures=True)  # as _batch_pool: a signal drops what is left


def _batch_threads(systems, motions, case_sys, case_mot, T, th0, impact_threshold, settings, workers):
    n = case_sys.size
    # (kernel, sp, ip, state size) per system, packed once per System: a chunk of a table
    # passes one System per case, the same one hundreds of times
    packed_systems = {}
    kernels = [packed_systems.get(id(s)) or packed_systems.setdefault(id(s), _kernel_for(s, settings))
               for s in systems]
    sps = np.stack([k[1] for k in kernels])
    ips = np.stack([k[2] for k in kernels])
    packed = [_motion_params(m) for m in motions]
    mps = np.stack([p[0] for p in packed])
    # a record's samples after its longest run's end are never read: leave them out
    t_max = np.zeros(len(motions))
    np.maximum.at(t_max, case_mot, T)
    accs = [p[1] if m.pulse is not None or p[1].size < 2 else p[1][:int(t_max[j] / m.dt) + 3]
            for j, (m, p) in enumerate(zip(motions, packed))]
    acc_off = np.concatenate([[0], np.cumsum([a.size for a in accs])]).astype(np.int64)
    acc_all = np.concatenate(accs)
    # restart times depend on the duration and on the motion only through its sample
    # times and end: one list per distinct (times, end, duration), shared by scaled records
    keys, brk_list, case_brk = {}, [], np.empty(n, dtype=np.int64)
    for c in range(n):
        m = motions[int(case_mot[c])]
        key = ((m.n, m.dt) if m.pulse is None else None, m.end_time, float(T[c]))
        if key not in keys:
            keys[key] = len(brk_list)
            brk_list.append(_breaks(m, key[2]))
        case_brk[c] = keys[key]
    brk_off = np.concatenate([[0], np.cumsum([b.size for b in brk_list])]).astype(np.int64)
    brk_all = np.concatenate(brk_list)
    y_init = np.zeros((n, 7))  # the isolator kernel's state has the slider's loss S too
    y_init[:, 2] = th0
    out = np.zeros((n, _N_OUT))
    motion_end = np.array([m.end_time for m in motions], dtype=np.float64)
    args = (sps, mps, acc_all, acc_off, brk_all, brk_off, case_sys.astype(np.int64),
            case_mot.astype(np.int64), case_brk, T, y_init, float(settings.rtol), float(settings.atol),
            float(settings.max_step), int(settings.max_events), float(impact_threshold),
            settings.overturn == physics.AT_ALPHA, motion_end, out, [k[0] for k in kernels], ips,
            [k[3] for k in kernels])
    failures = {}  # case: why it failed (the kernel raised, or its energy balance did)
    if n == 1 or (workers == 1 and threading.current_thread() is not threading.main_thread()):
        _run_cases(args, 0, n, failures)
    else:  # the main thread waits, and so hears signals
        _batch_pool(args, workers or available_cores(), failures)
    alphas = np.array([s.alpha for s in systems])
    rows = []
    for c in range(n):
        r = out[c]
        status = STATUS_NAMES[int(r[0])]
        if status == Status.FAILED and math.isnan(r[1]):  # the kernel raised: nothing measured
            rows.append({
                "system": int(case_sys[c]), "motion": int(case_mot[c]), "status": status,
                "theta_max_over_alpha": math.nan, "impacts": 0, "impacts_all": 0, "uplifts": 0,
                "overturned": False, "overturn_time": None, "u_max": math.nan, "duration": math.nan,
                "overturn_rule": settings.overturn, "friction_demand": math.nan,
                "message": failures.get(c, "the compiled kernel failed"),
            })
            continue
        # a run on a non-linear isolator whose energy balance failed is no answer (limits.py)
        failure = failures.get(c)
        if failure:
            status = Status.FAILED
        rows.append({
            "system": int(case_sys[c]), "motion": int(case_mot[c]), "status": status,
            "theta_max_over_alpha": float(theta_max_over_alpha(r[1], alphas[case_sys[c]], status == "overturned",
                                                               settings.overturn)), "impacts": int(r[2]),
            "impacts_all": int(r[3]), "uplifts": int(r[4]), "overturned": status == "overturned",
            "overturn_time": float(r[5]) if status == "overturned" and math.isfinite(r[5]) else None,
            "u_max": float(r[6]), "duration": float(r[7]), "overturn_rule": settings.overturn,
            "friction_demand": float(r[9]),
        })
        if failure:
            rows[-1]["message"] = failure
    return rows


def _run_cases(args, lo, hi, failures):
    """Cases lo..hi-1, one kernel call each from Python: the call costs ~10 µs against
    milliseconds of integration, and the kernel (nogil) lets other threads run."""
    (sps, mps, acc_all, acc_off, brk_all, brk_off, case_sys, case_mot, case_brk, T, y_init,
     rtol, atol, max_step, max_events, impact_frac, rule_alpha, motion_end, out, kernels, ips, sizes) = args
    for n in range(lo, hi):
        i, j, kb = case_sys[n], case_mot[n], case_brk[n]
        try:
            r = _call_integrate(sps[i], mps[j], acc_all[acc_off[j]:acc_off[j + 1]],
                                brk_all[brk_off[kb]:brk_off[kb + 1]], float(T[n]), y_init[n, :sizes[i]], rtol,
                                atol, max_step, max_events, 1.0, False, _BATCH_ROOM, impact_frac, rule_alpha,
                                float(motion_end[j]), ips[i], kernel=kernels[i])
        except Exception as e:  # noqa: BLE001 - one case's failure is its row's status, never the batch's
            out[n, 0] = _FAILED
            out[n, 1:] = math.nan
            failures[n] = f"the compiled kernel failed: {type(e).__name__}: {e}"
            continue
        n_imp = r[7]
        out[n] = (r[0], r[11], r[8][:n_imp, 7].sum(), n_imp, r[9], r[2], r[12], r[1], r[13], r[14])
        if len(r) > 15 and STATUS_NAMES[r[0]].ended_normally:  # a non-linear isolator's energy balance
            failures[n] = _balance_failure(r)


def _batch_pool(args, workers, failures):
    """Python threads over the GIL-free kernel, cases handed out in small chunks (runs
    differ in cost by orders of magnitude: Zeno tails, overturning)."""
    n = args[6].size
    bounds = np.linspace(0, n, min(n, workers * 16) + 1).astype(int)
    pool = ThreadPoolExecutor(max_workers=workers)
    try:
        for f in [pool.submit(_run_cases, args, bounds[k], bounds[k + 1], failures) for k in range(bounds.size - 1)]:
            f.result()  # the waiting thread hears signals; the kernel's threads do not
    finally:
        # on a signal (or an error) the cases not started are dropped and the running ones
        # not waited for: `with` waited for the whole batch, hours for a long chunk, and a
        # sweep told to stop went on (issue 24, item 10)
        pool.shutdown(wait=False, cancel_futures=True)


# --- measuring ---------------------------------------------------------------------

def _grid_values(t, x, dt):
    """x at the stored points that lie on the output grid k·dt, first occurrence of each."""
    k = np.round(t / dt)
    on = np.abs(t - k * dt) <= 1e-12 * max(1.0, float(np.max(np.abs(t))))
    kk, first = np.unique(k[on], return_index=True)
    return kk.astype(np.int64), x[on][first]


def compare_on_grid(a: Trajectory, b: Trajectory, dt: float = 0.005) -> float:
    """Largest |θa − θb| (rad) over the output-grid times k·dt both histories store."""
    ka, xa = _grid_values(a.t, a.theta, dt)
    kb, xb = _grid_values(b.t, b.theta, dt)
    common, ia, ib = np.intersect1d(ka, kb, return_indices=True)
    if common.size == 0:
        return math.nan
    return float(np.max(np.abs(xa[ia] - xb[ib])))
