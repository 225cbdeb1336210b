"""The scan of the superposition integrator: the first switch of a closed-form tangential motion.

Between switches the tangential motion of a slip mode, in flight or in separation
is the generated superposition `beltmdsm.generated.oscillator.tangential_state` of the state at
the switch ``t0``, the excitation response and the response to the contact force
(`beltmdsm.integrate.normal`) with the mode's friction direction (0 out of contact),
while sticking ``X1 = X1(t0) + Vb (t - t0)``. `scan` walks a uniform grid from ``t0`` to ``tc`` (the
end of the normal motion's current segment), evaluates the watched switching
functions there (`beltmdsm.generated.hybrid.surfaces`, at the full state) with their rates
along the mode (`beltmdsm.generated.hybrid.surface_rates`), and where a sign changes or the
rates show a minimum inside a cell, samples the cell and refines the crossing on the
exact motion (the normal motion's dense output, the closed forms), as
`beltmdsm.integrate._dop853` does between its steps. No formula of the model is here.

Plain Python, or compiled by numba with its kernels (`beltmdsm.integrate._compiled`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import numpy as np

from ._dop853 import _dense
from ._roots import GOLDEN, GOLDEN_STEPS, converged, golden, illinois, secant

__all__ = ["scan", "tangential_state"]

_SAMPLES = 16
#: `_dip` narrows a minimum to this share of the cell (`beltmdsm.integrate._dop853`).
_DIP_RESOLUTION = 1e-8

# The kernels are globals, bound by `beltmdsm.integrate._compiled` (see its _dop853).
_state_kernel = _exc_kernel = _surface_kernel = _rate_kernel = None


def tangential_state(stick, sgn, t, t0, start, Vb, z, v, zf, vf, state_a):
    """``(X1, X1')`` at ``t`` of the mode started at ``t0`` (module docstring).

    ``start``: ``(X1, X1', zf, zf', z, z')`` at ``t0``; ``z, v, zf, vf`` the responses
    at ``t``; ``sgn`` the friction direction (0 out of contact).
    """
    if stick:
        return start[0] + Vb * (t - t0), Vb
    return _state_kernel(
        t - t0,
        start[0],
        start[1],
        start[2],
        start[3],
        start[4],
        start[5],
        zf,
        vf,
        z,
        v,
        sgn,
        *state_a,
    )


def _normal_at(ts, hs, ys, Fs, t, out):
    k = np.searchsorted(ts, t, side="right") - 1
    if k < 0:
        k = 0
    _dense(Fs[k], ys[k], (t - ts[k]) / hs[k], out)


def _inside_at(t, j, ctx):
    """``-direction * h`` of watched surface ``j`` at ``t``: positive inside the mode.

    ``ctx`` holds the mode's motion: ``(watch, dirs, stick, sgn, t0, start, Vb, ts, hs,
    ys, Fs, state_a, exc_a, surf_a, tmp)`` (`scan`).
    """
    watch, dirs, stick, sgn, t0, start, Vb, ts, hs, ys, Fs, state_a, exc_a, surf_a, tmp = ctx
    _normal_at(ts, hs, ys, Fs, t, tmp)
    zf, vf = _exc_kernel(t, *exc_a)
    X1, Y1 = tangential_state(stick, sgn, t, t0, start, Vb, tmp[0], tmp[1], zf, vf, state_a)
    h = _surface_kernel(t, X1, Y1, tmp[2], tmp[3], *surf_a)
    return -dirs[j] * h[watch[j]]


def _refine(a, fa, b, fb, j, ctx):
    """Root of surface ``j`` in ``[a, b]`` (``fa > 0 >= fb``) by the Illinois method."""
    side = 0
    for _ in range(200):
        if converged(a, b):
            break
        c = secant(a, fa, b, fb)
        fc = _inside_at(c, j, ctx)
        a, fa, b, fb, side = illinois(a, fa, b, fb, c, fc, side)
    return b


def _dip(lo, hi, j, ctx):
    """The lowest value of surface ``j`` on ``[lo, hi]``, which holds one minimum:
    ``(t, f)`` by golden-section steps to ``_DIP_RESOLUTION`` of the interval, or the
    first value found <= 0 (a crossing)."""
    a, b = lo, hi
    c, d = a + GOLDEN * (b - a), b - GOLDEN * (b - a)
    fc = _inside_at(c, j, ctx)
    fd = _inside_at(d, j, ctx)
    # bounded, and ends at ulp resolution of t (`beltmdsm.integrate._dop853._dip`)
    for _ in range(GOLDEN_STEPS):
        if not (fc > 0.0 and fd > 0.0) or b - a <= _DIP_RESOLUTION * (hi - lo) or converged(a, b):
            break
        a, b, kept, f_kept, t = golden(a, b, c, fc, d, fd)
        ft = _inside_at(t, j, ctx)
        if t < kept:
            c, fc, d, fd = t, ft, kept, f_kept
        else:
            c, fc, d, fd = kept, f_kept, t, ft
    return (c, fc) if fc <= fd else (d, fd)


def scan(
    mode,
    stick,
    sgn,
    watch,
    dirs,
    t0,
    tc,
    start,
    Vb,
    grid,
    on_grid,
    ts,
    hs,
    ys,
    Fs,
    state_a,
    exc_a,
    surf_a,
    rate_a,
):
    """The first crossing of a watched surface in ``(t0, tc]``.

    Parameters
    ----------
    mode : float
        Mode code (for the rates along the mode).
    stick : bool
        Whether the mode holds ``X1' = Vb``.
    sgn : float
        The friction direction of a slip mode (-1, +1), 0 in flight or separation.
    watch, dirs : arrays
        Watched surfaces and the directions of the crossings that end the mode.
    t0, tc : float
    start : tuple of 6 floats
        ``(X1, X1', zf, zf', z, z')`` at ``t0``: the state and the two responses.
    grid, on_grid : arrays
        `beltmdsm.integrate.normal.NormalMotion` grid and its ``z, z', X2, X2', zf, zf'``.
    ts, hs, ys, Fs : arrays
        The normal motion's DOP853 steps.
    state_a, exc_a, surf_a, rate_a : tuple
        The bound arguments of the kernels ``_state_kernel`` (the superposition),
        ``_exc_kernel`` (excitation response), ``_surface_kernel``, ``_rate_kernel``.

    Returns
    -------
    hit : int
        Index into ``watch`` (-1: none before ``tc``).
    t_hit : float
    """
    n_watch = watch.shape[0]
    tmp = np.empty(4)
    u_old = np.empty(n_watch)
    u_new = np.empty(n_watch)
    r_old = np.empty(n_watch)
    r_new = np.empty(n_watch)
    armed = np.empty(n_watch, dtype=np.bool_)
    ctx = (watch, dirs, stick, sgn, t0, start, Vb, ts, hs, ys, Fs, state_a, exc_a, surf_a, tmp)
    _normal_at(ts, hs, ys, Fs, t0, tmp)
    zf, vf = _exc_kernel(t0, *exc_a)
    X1, Y1 = tangential_state(stick, sgn, t0, t0, start, Vb, tmp[0], tmp[1], zf, vf, state_a)
    h = _surface_kernel(t0, X1, Y1, tmp[2], tmp[3], *surf_a)
    r = _rate_kernel(t0, X1, Y1, tmp[2], tmp[3], mode, *rate_a)
    for j in range(n_watch):
        u_old[j] = -dirs[j] * h[watch[j]]
        r_old[j] = -dirs[j] * r[watch[j]]
        armed[j] = u_old[j] > 0.0
    if n_watch == 0:
        return -1, tc
    k = np.searchsorted(grid, t0, side="right")
    t_prev = t0
    while k < grid.shape[0] and t_prev < tc:
        t_new = grid[k]
        if t_new > tc:
            t_new = tc
            _normal_at(ts, hs, ys, Fs, t_new, tmp)
            zf, vf = _exc_kernel(t_new, *exc_a)
            z, v, X2, Y2 = tmp[0], tmp[1], tmp[2], tmp[3]
        else:
            z, v, X2, Y2 = on_grid[0, k], on_grid[1, k], on_grid[2, k], on_grid[3, k]
            zf, vf = on_grid[4, k], on_grid[5, k]
        X1, Y1 = tangential_state(stick, sgn, t_new, t0, start, Vb, z, v, zf, vf, state_a)
        h = _surface_kernel(t_new, X1, Y1, X2, Y2, *surf_a)
        r = _rate_kernel(t_new, X1, Y1, X2, Y2, mode, *rate_a)
        best_j, best_t = -1, 0.0
        for j in range(n_watch):
            u_new[j] = -dirs[j] * h[watch[j]]
            r_new[j] = -dirs[j] * r[watch[j]]
            dip = r_old[j] < 0.0 and r_new[j] > 0.0
            if u_new[j] > 0.0 and not dip:
                continue
            a, fa = t_prev, u_old[j] if armed[j] else 0.0
            if not armed[j]:
                # the mode's field points inside at the start: the first time inside may
                # be far closer to it than a sample (a short excursion), so look there
                delta = (t_new - t_prev) / _SAMPLES
                for _ in range(60):
                    delta *= 0.5
                    fk = _inside_at(t_prev + delta, j, ctx)
                    if fk > 0.0:
                        a, fa = t_prev + delta, fk
                        break
            found = False
            tcross = t_prev
            # the lowest sample of a dip and the sample before it (> 0, inside)
            low_s, low_f, before, f_before = 0, fa, a, fa
            for s in range(1, _SAMPLES + 1):
                tk = t_prev + (t_new - t_prev) * s / _SAMPLES if s < _SAMPLES else t_new
                if tk <= a:
                    continue
                fk = u_new[j] if s == _SAMPLES else _inside_at(tk, j, ctx)
                if fa > 0.0 and fk <= 0.0:
                    tcross = _refine(a, fa, tk, fk, j, ctx)
                    found = True
                    break
                if fk > 0.0:
                    if fk < low_f:
                        low_s, low_f, before, f_before = s, fk, a, fa
                    a, fa = tk, fk
            if not found and dip and armed[j] and f_before > 0.0:
                after = t_prev + (t_new - t_prev) * min(low_s + 1, _SAMPLES) / _SAMPLES
                tm, fm = _dip(before, after, j, ctx)
                if fm <= 0.0:
                    tcross = _refine(before, f_before, tm, fm, j, ctx)
                    found = True
            if not found and not armed[j] and u_new[j] <= 0.0 and fa <= 0.0:
                tcross, found = t_prev, True
            if found and (best_j < 0 or tcross < best_t):
                best_j, best_t = j, tcross
        if best_j >= 0:
            return best_j, best_t
        for j in range(n_watch):
            u_old[j] = u_new[j]
            r_old[j] = r_new[j]
            if u_new[j] > 0.0:
                armed[j] = True
        t_prev = t_new
        k += 1
    return -1, tc
