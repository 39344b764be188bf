"""The rest phase of a block on a linear isolator under a record, for every scale of the
record in one pass (what `isorock design` uses to skip the runs in which the block never
lifts).

While the block rests on its base, the base is a linear oscillator driven by ẍg, so its
state under the record scaled by f is f times its state under the record itself, and
the block lifts once f·|a₁(t)| reaches g·tanα, a₁ being the base's absolute acceleration
under the unscaled record. One pass over the record, with the compiled kernel's own
closed form of each translation interval (analytic.physics.translation_*, the very
functions the kernel runs, located uplift and extremes of u included), gives for every
scale f_k at once: the first time the block would lift (never, for most scales of a
design grid) and the peak |u₁| over the whole run. A run at a scale that never lifts
is then known without running it: the block stays down (θmax = 0, no impact, not
overturned, the run completes) and its stroke is f_k·max|u₁|, equal to what the kernel
reports for that run to rounding (tests/test_design.py checks both against the kernel
run by run). A scale that lifts is run by the kernel as any other run.

Thresholds are compared as |a₁| against g·tanα / f_k rather than f_k·|a₁| against g·tanα:
the two differ by rounding alone, so only a grazing touch of the threshold within ~1e-15
of it could be called differently; the kernel itself treats such touches as events
of measure zero.
"""
from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import physics
from .errors import InputError
from .kernel_cache import c_writable, cached_jit, call_kernel
from .limits import available_cores
from .settings import AnalyticSettings

# the kernel's compiled physics (analytic.fast), the same functions its closed-form
# translation pieces call
from .fast import _P, _breaks, _mp_tuple, _sp_tuple  # noqa: E402
from .system import LINEAR

_record_piece = _P["record_piece"]
_xgp = _P["piece_acceleration"]
_base_acc = _P["base_acceleration"]
_tr_start = _P["translation_start"]
_tr_state = _P["translation_state"]
_tr_uplift = _P["translation_uplift"]
_tr_vzeros = _P["translation_velocity_zeros"]
_tr_ubound = _P["translation_u_bound"]
_fv_change = _P["free_vibration_change"]
_K, _INV_M, _THR = physics.K, physics.INV_M, physics.THR
_PIECE, _PA0, _PA1, _INV_DT, _DT, _SAMPLED, _KIND = (physics.PIECE, physics.PA0, physics.PA1, physics.INV_DT,
                                                    physics.DT, physics.SAMPLED, physics.KIND)


@cached_jit(nogil=True)
def _rest_pass(sp, mp_in, acc, breaks, T, thresholds, uplift):
    """One pass over [0, T] of the base in pure translation from rest under the unscaled
    record. thresholds: the uplift thresholds g·tanα/f_k (m/s²), increasing; uplift[k]
    is set to the first time |a₁| reaches thresholds[k] (inf: never). Returns max|u₁|
    over [0, T], or over [0, t_last] once every threshold has been reached (then nothing
    more is needed)."""
    # tuples, not arrays, in the calls below: numba reference-counts an array at every
    # call it is passed to (analytic.fast._sp_tuple), which cost this loop most of its time
    sp = _sp_tuple(sp)
    mp = mp_in.copy()
    mp[_PIECE] = 0.0
    mp[_INV_DT] = 1.0 / mp[_DT] if mp[_DT] > 0.0 else 0.0
    cf_cap = 0.1 / math.sqrt(sp[_K] * sp[_INV_M])
    ext = np.empty(4)
    n_thr = thresholds.size
    for k in range(n_thr):
        uplift[k] = math.inf
    # the free vibration's change over a piece, as a matrix: free_vibration_change is linear in
    # z, so its columns at z = (1, 0) and (0, 1) are it, for one piece length; a record's pieces
    # are its dt to an ulp, so one expm1, sin and cos serve thousands of pieces (they were most
    # of this loop's time), each piece's state then differing from the kernel's by rounding alone
    h_coef, d00, d01, d10, d11 = -1.0, 0.0, 0.0, 0.0, 0.0
    j = 0  # thresholds[j]: the lowest not reached yet
    u, v = 0.0, 0.0
    u_max = 0.0
    t = 0.0
    ibreak = 1
    nb = breaks.size
    while t < T and j < n_thr:
        while ibreak < nb and breaks[ibreak] <= t + 1e-12:
            ibreak += 1
        t1 = breaks[ibreak] if ibreak < nb else T
        _record_piece(mp, acc, t, t1)
        mpt = _mp_tuple(mp)
        t_end = min(t1, t + cf_cap)
        a0 = _xgp(t, mpt) if mp[_PIECE] == 1.0 else 0.0
        a1 = (mp[_PA1] - mp[_PA0]) * mp[_INV_DT] if mp[_PIECE] == 1.0 else 0.0
        zu0, zv0, p0, p1 = _tr_start(sp, u, v, a0, a1)
        h = t_end - t
        if abs(h - h_coef) > 1e-12 * h:
            d00, d10 = _fv_change(sp, 1.0, 0.0, h)
            d01, d11 = _fv_change(sp, 0.0, 1.0, h)
            h_coef = h
        u1 = u + (d00 * zu0 + d01 * zv0) + p1 * h  # translation_state's u and u̇
        v1 = v + (d10 * zu0 + d11 * zv0)
        a_end = _base_acc(sp, u1, v1, 0.0)
        while j < n_thr:
            tau, side = _tr_uplift(sp, zu0, zv0, a0, a1, h, thresholds[j], a_end)
            if side == 0 or tau >= h:
                break
            uplift[j] = t + tau
            j += 1
        # the extremes of u inside the interval, only where they could exceed the peak so far
        # (the kernel's own test: the chord's ends plus the largest bow)
        n_ext = 0
        if max(abs(u), abs(u1)) + _tr_ubound(sp, zu0, zv0, h) > u_max:
            n_ext = _tr_vzeros(sp, zu0, zv0, p1, h, ext)
        u_max = max(u_max, abs(u), abs(u1))
        for q in range(n_ext):
            uq = _tr_state(sp, zu0, zv0, p1, u, v, a0, a1, ext[q])[0]
            u_max = max(u_max, abs(uq))
        u, v = u1, v1
        t = t_end
    return u_max


def rest_phases(systems, records, factors, durations, settings: AnalyticSettings | None = None,
                workers: int | None = None, on_system=None):
    """For each linear isolator of `systems` (on an isolated base) under each of `records`
    scaled by each of its `factors` (records × levels, > 0), from rest, for durations[r]
    s: (uplift, u1_max). uplift[s, r, k]: the first time the block would lift, inf where
    it never does; u1_max[s, r]: max|u₁| under the unscaled record over the whole run
    (the stroke of a run that never lifts is factor·u1_max; nan where every factor lifts,
    the pass having stopped at the last uplift). Threads over the GIL-free pass
    (`workers`: default, the cores this process may use); on_system(): called here, in the
    calling thread, as each system's passes are done (a progress bar's update)."""
    for system in systems:
        if system.fixed_base or system.isolator_kind != LINEAR:
            raise InputError("rest_phases: needs linear isolators on an isolated base (their rest phase is linear "
                             "in the record's scale)")
    for record in records:
        if record.pulse is not None:
            raise InputError("rest_phases: needs records (sampled motions), not pulses")
    f = np.asarray(factors, dtype=float).reshape(len(records), -1)
    if not np.all(f > 0) or not np.all(np.isfinite(f)):
        raise InputError("rest_phases: factors must be positive and finite")
    settings = settings or AnalyticSettings()
    sps = [physics.system_params(s, settings.rest_velocity) for s in systems]
    prepared = []
    for record, fr, T in zip(records, f, durations):
        mp, acc = physics.motion_params(record)
        order = np.argsort(-fr, kind="stable")  # largest factor first: the lowest threshold
        # every array writable and C-contiguous, the one signature call_kernel compiles and
        # kernel_cache.is_ready looks for (a record's samples are read-only)
        prepared.append((mp, c_writable(np.asarray(acc, dtype=np.float64)), _breaks(record, float(T)), float(T),
                         order))
    uplift = np.empty((len(systems), len(records), f.shape[1]))
    u1_max = np.empty((len(systems), len(records)))

    def one(i):
        sp = sps[i]
        for r, (mp, acc, breaks, T, order) in enumerate(prepared):
            up = np.empty(order.size)
            # the forward edge's threshold per factor; translation_uplift scales the backward
            # edge's alike (physics.other_threshold), so a statue lifts on either edge
            u1_max[i, r] = call_kernel(_rest_pass, sp, mp, acc, breaks, T, np.ascontiguousarray(sp[_THR] / f[r][order]),
                                       up)
            uplift[i, r, order] = up
            if np.isfinite(up).all():
                u1_max[i, r] = math.nan  # the pass stopped at the last uplift
    workers = workers or available_cores()
    if workers == 1 or len(systems) == 1:
        for i in range(len(systems)):
            one(i)
            if on_system is not None:
                on_system()
    else:
        pool = ThreadPoolExecutor(max_workers=workers)
        try:
            for fut in [pool.submit(one, i) for i in range(len(systems))]:
                fut.result()
                if on_system is not None:
                    on_system()
        finally:
            pool.shutdown(wait=False, cancel_futures=True)  # a signal: the passes not started are dropped
    return uplift, u1_max


def rest_phase(system, record, factors, duration: float, settings: AnalyticSettings | None = None):
    """rest_phases for one system and one record: (uplift per factor, u1_max)."""
    uplift, u1_max = rest_phases([system], [record], [list(np.atleast_1d(factors))], [duration], settings, workers=1)
    return uplift[0, 0], float(u1_max[0, 0])
