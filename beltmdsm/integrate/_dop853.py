"""A compiled Dormand-Prince 8(5,3) integrator of one smooth mode, stopping at switches.

The method and its step-size control are SciPy's ``DOP853`` (Hairer, Norsett and
Wanner, *Solving ODEs I*, Sect. II.10; the coefficients are Hairer's, as SciPy's,
``beltmdsm.generated.tableau`` from derive/dop853.py), with the 7th-order dense output
computed for every step, because a trajectory is sampled, integrated
(energy balance) and searched for switches between the steps.

`advance` integrates the field of one mode from ``t0`` until ``t_end`` or until one
of the watched switching functions crosses zero in its stated direction. The
functions are generated kernels (`beltmdsm.generated.hybrid`: ``vector_field``, ``surfaces``,
``surface_rates``) called with their bound parameters, so this module holds no
physics: only the Runge-Kutta scheme and the search for the first crossing.

A crossing is searched between the steps, never stepped over: after each accepted
step the watched functions are evaluated at its end; a sign change, or a minimum
inside the step (rates of opposite signs at its ends), is bracketed by sampling the
dense output and refined by bisection-secant (Illinois) on the dense output. A
function that starts at zero (the surface the run has just switched on) counts
only once it has been strictly inside the mode.

The same source runs as plain Python or compiled by numba, with its kernels, in the
entry points of `beltmdsm.integrate._compiled`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import functools
import math
import types

import numpy as np

from beltmdsm.generated import tableau as _coef
from beltmdsm.generated._support import import_numba

from . import _background
from ._roots import GOLDEN, GOLDEN_STEPS, converged, golden, illinois, secant

__all__ = [
    "advance",
    "evaluate",
    "N_DENSE",
    "TABLEAU_A",
    "TABLEAU_B",
    "TABLEAU_C",
    "STATUS_END",
    "STATUS_EVENT",
    "STATUS_STEP_TOO_SMALL",
    "STATUS_NOT_FINITE",
    "STATUS_TOO_MANY_STEPS",
    "MAX_STEPS",
]


def _table(a):
    """A coefficient array as nested tuples: constants numba can cache with the code
    (a global array would be a dynamic global, which its disk cache refuses)."""
    a = np.asarray(a, dtype=float)
    return tuple(map(float, a)) if a.ndim == 1 else tuple(_table(row) for row in a)


_N_STAGES = _coef.N_STAGES
_A = _table(np.asarray(_coef.A)[:_N_STAGES, :_N_STAGES])
_B = _table(_coef.B)
_C = _table(_coef.C[:_N_STAGES])
_E3 = _table(_coef.E3)
_E5 = _table(_coef.E5)
_D = _table(_coef.D)
_A_EXTRA = _table(_coef.A[_N_STAGES + 1 :])
_C_EXTRA = _table(_coef.C[_N_STAGES + 1 :])
_N_EXTENDED = _coef.N_STAGES_EXTENDED
#: Rows of the dense-output coefficients of a step.
N_DENSE = _coef.INTERPOLATOR_POWER
#: The method's tableau as arrays (its 12 stages, order 8), for a linear equation
#: carried along a run's steps (`beltmdsm.periodic.variational`).
TABLEAU_A = np.array(_A)
TABLEAU_B = np.array(_B)
TABLEAU_C = np.array(_C)

_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
_EXPONENT = -1.0 / 8.0
#: Dense-output samples per step when a crossing is bracketed inside it.
_SAMPLES = 16
#: `_dip` narrows a minimum to this share of the step: the value there is then the
#: minimum's to ``(1e-8 h)^2`` times the surface's curvature, far below any tolerance.
_DIP_RESOLUTION = 1e-8

STATUS_END, STATUS_EVENT, STATUS_STEP_TOO_SMALL = 0, 1, 2
#: The state or the step size is NaN or infinite (an overflow): no step can be accepted,
#: and a NaN step size compares false with every bound, so it is tested for by name.
STATUS_NOT_FINITE = 3
#: More than `MAX_STEPS` (or the call's ``max_steps``) steps in one call.
STATUS_TOO_MANY_STEPS = 4
#: The most steps of one call: 2^24 steps hold (2 + 4 + 4 N_DENSE) x 8 bytes each, about
#: 4.6 GB, past `beltmdsm.settings.MAX_RUN_BYTES`: a run that needs more cannot be kept.
MAX_STEPS = 2**24

# The kernels are globals of the functions below, not arguments: `beltmdsm.integrate._compiled`
# binds them (copies of the functions with these globals set, or a module numba
# compiles with them), so that a compiled integrator's signature holds numbers only.
_field_kernel = _surface_kernel = _rate_kernel = None


def _rhs(fa, t, y, mode, out):
    r = _field_kernel(t, y[0], y[1], y[2], y[3], mode, *fa)
    for i in range(4):
        out[i] = r[i]


def _dense(F, y_old, x, out):
    """DOP853's dense output at ``x = (t - t_old) / h`` (SciPy's Dop853DenseOutput)."""
    for i in range(4):
        out[i] = 0.0
    for k in range(N_DENSE):
        row = N_DENSE - 1 - k
        for i in range(4):
            out[i] += F[row, i]
            if k % 2 == 0:
                out[i] *= x
            else:
                out[i] *= 1.0 - x
    for i in range(4):
        out[i] += y_old[i]


def _initial_step(fa, t, y, f, mode, t_end, rtol, atol, max_step, y1, f1):
    """SciPy's ``select_initial_step`` (Hairer, Norsett and Wanner, Sect. II.4)."""
    d0 = 0.0
    d1 = 0.0
    for i in range(4):
        sc = atol + abs(y[i]) * rtol
        d0 += (y[i] / sc) ** 2
        d1 += (f[i] / sc) ** 2
    d0, d1 = math.sqrt(d0 / 4), math.sqrt(d1 / 4)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_end - t)
    for i in range(4):
        y1[i] = y[i] + h0 * f[i]
    _rhs(fa, t + h0, y1, mode, f1)
    d2 = 0.0
    for i in range(4):
        sc = atol + abs(y[i]) * rtol
        d2 += ((f1[i] - f[i]) / sc) ** 2
    d2 = math.sqrt(d2 / 4) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, max_step, t_end - t)


def _inside(sa, watch, dirs, t, y, values):
    """``-direction * h`` of each watched surface: positive inside the mode."""
    h = _surface_kernel(t, y[0], y[1], y[2], y[3], *sa)
    for j in range(watch.shape[0]):
        values[j] = -dirs[j] * h[watch[j]]


def _rates(ra, watch, dirs, t, y, mode, values):
    r = _rate_kernel(t, y[0], y[1], y[2], y[3], mode, *ra)
    for j in range(watch.shape[0]):
        values[j] = -dirs[j] * r[watch[j]]


def _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, t, tmp):
    _dense(F, y_old, (t - t_old) / h, tmp)
    hv = _surface_kernel(t, tmp[0], tmp[1], tmp[2], tmp[3], *sa)
    return -dirs[j] * hv[watch[j]]


def _refine(sa, watch, dirs, j, F, y_old, t_old, h, a, fa, b, fb, tmp):
    """Root of surface ``j`` in ``[a, b]`` (``fa > 0 >= fb``) by the Illinois method."""
    side = 0
    for _ in range(200):
        if converged(a, b):
            break
        c = secant(a, fa, b, fb)
        fc = _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, c, tmp)
        a, fa, b, fb, side = illinois(a, fa, b, fb, c, fc, side)
    return b


def _dip(sa, watch, dirs, j, F, y_old, t_old, h, lo, hi, tmp):
    """The lowest value of surface ``j`` on ``[lo, hi]``, which holds one minimum:
    ``(t, f)`` by golden-section steps to ``_DIP_RESOLUTION`` of the step, or the
    first value found <= 0 (a crossing)."""
    a, b = lo, hi
    c, d = a + GOLDEN * (b - a), b - GOLDEN * (b - a)
    fc = _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, c, tmp)
    fd = _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, d, tmp)
    # bounded: once the bracket is a few ulps of t wide (a short step late in a long
    # run: 1e-8 h below one ulp), rounding stops shrinking it and the search ends there
    for _ in range(GOLDEN_STEPS):
        if not (fc > 0.0 and fd > 0.0) or b - a <= _DIP_RESOLUTION * h or converged(a, b):
            break
        a, b, kept, f_kept, t = golden(a, b, c, fc, d, fd)
        ft = _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, t, tmp)
        if t < kept:
            c, fc, d, fd = t, ft, kept, f_kept
        else:
            c, fc, d, fd = kept, f_kept, t, ft
    return (c, fc) if fc <= fd else (d, fd)


def _first_crossing(sa, watch, dirs, F, y_old, t_old, h, u_old, u_new, r_old, r_new, armed, tmp):
    """Earliest crossing inside the step ``[t_old, t_old + h]``: ``(j, t)`` or ``(-1, 0)``.

    A surface crosses where its inside value falls to <= 0 after being > 0. Within
    the step the dense output is sampled where the end values change sign, where
    the rates show a minimum inside, or where the surface is not yet armed (it
    started on zero). A minimum that no sample shows below zero is searched for
    (`_dip`): a surface crossed by less than the samples resolve is crossed too.
    """
    best_j, best_t = -1, 0.0
    t_new = t_old + h
    for j in range(watch.shape[0]):
        dip = r_old[j] < 0.0 and r_new[j] > 0.0
        if u_new[j] > 0.0 and not dip:
            continue
        # a: the last time known inside (an unarmed surface starts on zero: not inside)
        a, fa = t_old, u_old[j] if armed[j] else 0.0
        if not armed[j]:
            # the mode's field points inside at the start: the first time inside may be
            # far closer to it than a sample (a short excursion), so look there first
            delta = h / _SAMPLES
            for _ in range(60):
                delta *= 0.5
                fk = _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, t_old + delta, tmp)
                if fk > 0.0:
                    a, fa = t_old + delta, fk
                    break
        found = False
        # the lowest sample of a dip and the sample before it (> 0, inside)
        low_k, low_f, before, f_before = 0, fa, a, fa
        for k in range(1, _SAMPLES + 1):
            tk = t_old + h * k / _SAMPLES if k < _SAMPLES else t_new
            if tk <= a:
                continue
            fk = (
                u_new[j]
                if k == _SAMPLES
                else _surface_at(sa, watch, dirs, j, F, y_old, t_old, h, tk, tmp)
            )
            if fa > 0.0 and fk <= 0.0:
                tc = _refine(sa, watch, dirs, j, F, y_old, t_old, h, a, fa, tk, fk, tmp)
                found = True
                break
            if fk > 0.0:
                if fk < low_f:
                    low_k, low_f, before, f_before = k, fk, a, fa
                a, fa = tk, fk
        if not found and dip and armed[j] and f_before > 0.0:
            after = t_old + h * min(low_k + 1, _SAMPLES) / _SAMPLES
            tm, fm = _dip(sa, watch, dirs, j, F, y_old, t_old, h, before, after, tmp)
            if fm <= 0.0:
                tc = _refine(sa, watch, dirs, j, F, y_old, t_old, h, before, f_before, tm, fm, tmp)
                found = True
        if not found and not armed[j] and u_new[j] <= 0.0 and fa <= 0.0:
            # never inside: the field leaves through the surface it started on
            tc, found = t_old, True
        if found and (best_j < 0 or tc < best_t):
            best_j, best_t = j, tc
    return best_j, best_t


def advance(
    fa, sa, ra, mode, watch, dirs, t0, y0, t_end, h0, rtol, atol, max_step, max_steps=MAX_STEPS
):
    """Integrate one mode from ``t0`` until ``t_end`` or the first watched crossing.

    Parameters
    ----------
    fa, sa, ra : tuple
        The bound arguments of the kernels: the vector field
        ``_field_kernel(t, X1, Y1, X2, Y2, mode, *fa)`` (a 4-tuple), the switching
        functions ``_surface_kernel(t, X1, Y1, X2, Y2, *sa)`` (one value per surface)
        and their rates along a mode ``_rate_kernel(t, X1, Y1, X2, Y2, mode, *ra)``.
    mode : float
        The mode code passed to ``fk`` and ``rk``.
    watch, dirs : int64 array, float64 array
        The surfaces that end the mode and the direction of the crossing that ends
        it (+1: the function rises through zero, -1: falls).
    t0, y0, t_end : float, float64 array (4,), float
    h0 : float
        First step size (``<= 0``: chosen from the tolerances).
    rtol, atol, max_step : float
    max_steps : int, optional
        The most steps (at most `MAX_STEPS`): past them the call ends with
        `STATUS_TOO_MANY_STEPS`, its memory bounded.

    Returns
    -------
    status : int
        `STATUS_END`, `STATUS_EVENT` or `STATUS_STEP_TOO_SMALL`.
    n : int
        Number of steps.
    t_steps, h_steps : float64 arrays (n,)
        Start and length of each step (the last one may end early, at the event).
    y_steps : float64 array (n, 4)
        State at each step's start.
    F_steps : float64 array (n, N_DENSE, 4)
        Dense-output coefficients of each step.
    t_stop : float
    y_stop : float64 array (4,)
    hit : int
        Index into ``watch`` of the surface crossed (-1 if none).
    h_next : float
        Step size to try next.
    """
    n_watch = watch.shape[0]
    cap = 256
    t_steps = np.empty(cap)
    h_steps = np.empty(cap)
    y_steps = np.empty((cap, 4))
    F_steps = np.empty((cap, N_DENSE, 4))
    K = np.empty((_N_EXTENDED, 4))
    y = y0.copy()
    y_new = np.empty(4)
    tmp = np.empty(4)
    f = np.empty(4)
    u_old = np.empty(n_watch)
    u_new = np.empty(n_watch)
    r_old = np.empty(n_watch)
    r_new = np.empty(n_watch)
    armed = np.empty(n_watch, dtype=np.bool_)
    t = t0
    _rhs(fa, t, y, mode, f)
    _inside(sa, watch, dirs, t, y, u_old)
    _rates(ra, watch, dirs, t, y, mode, r_old)
    for j in range(n_watch):
        armed[j] = u_old[j] > 0.0
    h_abs = h0
    if h_abs <= 0.0:
        h_abs = _initial_step(fa, t, y, f, mode, t_end, rtol, atol, max_step, tmp, y_new)
    n = 0
    status = STATUS_END
    hit = -1
    while t < t_end:
        if n >= max_steps or n >= MAX_STEPS:
            status = STATUS_TOO_MANY_STEPS
            break
        if not (math.isfinite(y[0]) and math.isfinite(y[1])):
            status = STATUS_NOT_FINITE
            break
        if not (math.isfinite(y[2]) and math.isfinite(y[3])):
            status = STATUS_NOT_FINITE
            break
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)
        if h_abs > max_step:
            h_abs = max_step
        if h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if not (math.isfinite(h_abs) and math.isfinite(t)):
                status = STATUS_NOT_FINITE
                break
            if h_abs < min_step:
                status = STATUS_STEP_TOO_SMALL
                break
            t_new = min(t + h_abs, t_end)
            h = t_new - t
            for i in range(4):
                K[0, i] = f[i]
            for s in range(1, _N_STAGES):
                for i in range(4):
                    acc = 0.0
                    for r in range(s):
                        acc += _A[s][r] * K[r, i]
                    tmp[i] = y[i] + h * acc
                _rhs(fa, t + _C[s] * h, tmp, mode, K[s])
            for i in range(4):
                acc = 0.0
                for r in range(_N_STAGES):
                    acc += _B[r] * K[r, i]
                y_new[i] = y[i] + h * acc
            _rhs(fa, t_new, y_new, mode, K[_N_STAGES])
            err5 = 0.0
            err3 = 0.0
            for i in range(4):
                sc = atol + max(abs(y[i]), abs(y_new[i])) * rtol
                e5 = 0.0
                e3 = 0.0
                for r in range(_N_STAGES + 1):
                    e5 += _E5[r] * K[r, i]
                    e3 += _E3[r] * K[r, i]
                err5 += (e5 / sc) ** 2
                err3 += (e3 / sc) ** 2
            if err5 == 0.0 and err3 == 0.0:
                norm = 0.0
            else:
                norm = h * err5 / math.sqrt((err5 + 0.01 * err3) * 4)
            if norm < 1.0:
                factor = _MAX_FACTOR if norm == 0.0 else min(_MAX_FACTOR, _SAFETY * norm**_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(_MIN_FACTOR, _SAFETY * norm**_EXPONENT)
            rejected = True
        if status != STATUS_END:
            break
        # the dense output of the accepted step [t, t_new]
        for s in range(_N_STAGES + 1, _N_EXTENDED):
            row = s - _N_STAGES - 1
            for i in range(4):
                acc = 0.0
                for r in range(s):
                    acc += _A_EXTRA[row][r] * K[r, i]
                tmp[i] = y[i] + h * acc
            _rhs(fa, t + _C_EXTRA[row] * h, tmp, mode, K[s])
        if n == cap:
            cap *= 2
            t_steps = np.concatenate((t_steps, np.empty(cap - n)))
            h_steps = np.concatenate((h_steps, np.empty(cap - n)))
            y_steps = np.concatenate((y_steps, np.empty((cap - n, 4))))
            F_steps = np.concatenate((F_steps, np.empty((cap - n, N_DENSE, 4))))
        Fs = F_steps[n]
        for i in range(4):
            dy = y_new[i] - y[i]
            Fs[0, i] = dy
            Fs[1, i] = h * K[0, i] - dy
            Fs[2, i] = 2.0 * dy - h * (K[_N_STAGES, i] + K[0, i])
            for row in range(N_DENSE - 3):
                acc = 0.0
                for r in range(_N_EXTENDED):
                    acc += _D[row][r] * K[r, i]
                Fs[3 + row, i] = h * acc
        t_steps[n] = t
        h_steps[n] = h
        for i in range(4):
            y_steps[n, i] = y[i]
        n += 1
        _inside(sa, watch, dirs, t_new, y_new, u_new)
        _rates(ra, watch, dirs, t_new, y_new, mode, r_new)
        j, tc = _first_crossing(
            sa, watch, dirs, Fs, y, t, h, u_old, u_new, r_old, r_new, armed, tmp
        )
        if j >= 0:
            hit = j
            if tc <= t:
                n -= 1  # the run leaves at the start of the step: drop it
            _dense(Fs, y, (tc - t) / h, y_new)
            t = tc
            for i in range(4):
                y[i] = y_new[i]
            status = STATUS_EVENT
            break
        t = t_new
        for i in range(4):
            y[i] = y_new[i]
            f[i] = K[_N_STAGES, i]
        for j in range(n_watch):
            u_old[j] = u_new[j]
            r_old[j] = r_new[j]
            if u_new[j] > 0.0:
                armed[j] = True
    return (status, n, t_steps[:n], h_steps[:n], y_steps[:n], F_steps[:n], t, y, hit, h_abs)


def evaluate(t_steps, h_steps, y_steps, F_steps, t):
    """The dense output of a run of steps at the times ``t`` (sorted or not): (4, m).

    Compiled by numba where it is installed (no kernels in it: cached on disk as it
    is), else numpy on all times at once.
    """
    t = np.asarray(t, dtype=float).ravel()
    fast = _evaluate_compiled()
    if fast is not None:
        out = np.empty((4, t.size))
        fast(t_steps, h_steps, y_steps, F_steps, t, out)
        return out
    k = np.clip(np.searchsorted(t_steps, t, side="right") - 1, 0, len(t_steps) - 1)
    x = (t - t_steps[k]) / h_steps[k]
    F = F_steps[k]
    y = np.zeros((t.size, 4))
    for j in range(N_DENSE):
        y += F[:, N_DENSE - 1 - j, :]
        y *= (x if j % 2 == 0 else 1.0 - x)[:, None]
    y += y_steps[k]
    # C order, as the compiled loop's: an array passed on to a compiled integrator has
    # the layout its cached signature holds
    return np.ascontiguousarray(y.T)


def _evaluate_loop(t_steps, h_steps, y_steps, F_steps, t, out):
    """`evaluate` point by point (the compiled form)."""
    n = t_steps.shape[0]
    tmp = np.empty(4)
    for m in range(t.shape[0]):
        k = np.searchsorted(t_steps, t[m], side="right") - 1
        k = min(max(k, 0), n - 1)
        _dense(F_steps[k], y_steps[k], (t[m] - t_steps[k]) / h_steps[k], tmp)
        for i in range(4):
            out[i, m] = tmp[i]


def _evaluate_numba():
    """`_evaluate_loop` compiled by numba (no kernels in it: cached on disk as it is)."""
    numba = import_numba(True)
    dense = numba.njit(cache=True)(_dense)
    loop = types.FunctionType(
        _evaluate_loop.__code__, {**globals(), "_dense": dense}, "_evaluate_loop"
    )
    return numba.njit(cache=True)(loop)


_COMPILED_EVALUATE = []


def _evaluate_compiled():
    """The compiled loop of `evaluate` where it is ready; None where numba is not
    installed, or while it compiles in the background (`_background.Lazy`)."""
    if not _COMPILED_EVALUATE:
        lazy = None
        if _background.numba_installed():
            stem = "beltmdsm_evaluate_" + _background.digest(
                _background.numba_version(), __file__, _coef.__file__
            )
            lazy = _background.Lazy((_evaluate_numba, ()), stem, None)
        _COMPILED_EVALUATE.append(lazy)
    lazy = _COMPILED_EVALUATE[0]
    return None if lazy is None else lazy.fn or lazy.compiled(_evaluate_types())


@functools.cache
def _evaluate_types():
    """Arguments of the types of `_evaluate_loop`'s (`_background` compiles for their
    types; a function, not a constant, which `beltmdsm.integrate._compiled` would copy)."""
    return (
        np.zeros(1),
        np.ones(1),
        np.zeros((1, 4)),
        np.zeros((1, N_DENSE, 4)),
        np.zeros(1),
        np.empty((4, 1)),
    )
