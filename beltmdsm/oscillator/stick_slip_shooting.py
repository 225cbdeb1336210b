"""Shooting a self-excited cycle with a stick: from the state where a stick ends.

A cycle with a stick is fixed by the state where a stick ends (a single point of the
orbit): the run from there goes to the ``k``-th end of a stick (``x_T``), and the phase
condition ``c`` of the bordered system (`beltmdsm.oscillator.cycles`) is that surface,
``|holding_force| - stick_limit`` (its gradient by central differences of the two
kernels: it steers Newton's steps only). ``k`` and the first state come from the seed
(`beltmdsm.oscillator.cycle_seed`). The period reported is the least: no proper divisor
of the ``k`` sticks returns to the state.
"""

from __future__ import annotations

import numpy as np

from ..errors import NoPeriodicResponse
from .cycle import _RETURN_TOL, NEWTON_TOL, _cycle, _not_a_return
from .hybrid import flow
from .system import STICK


def _nth_end(k):
    count = [0]

    def stop(switch, n):
        if switch[1] == STICK:
            count[0] += 1
        return count[0] == k

    return stop


def _end_states(system, x, mode, k, tol):
    """The states at the next ``k`` ends of a stick from ``x``."""
    out = []
    y, md = x, mode
    for _ in range(k):
        r = flow(system, 0.0, y, np.inf, mode=md, stop=_nth_end(1), **tol)
        if r.status != "stopped":
            break
        y, md = r.y, r.mode
        out.append(y)
    return out


def _newton_stick(system, x, mode, k, max_iter, tol):
    k_ = system.kernels
    p = system.p
    m = x.size

    def surface(y):
        return abs(k_.holding_force(0.0, y, p)) - k_.stick_limit(0.0, y, p)

    scale = 1.0 + np.abs(x).max()
    for _ in range(max_iter):
        run = flow(system, 0.0, x, np.inf, mode=mode, variational=True, stop=_nth_end(k), **tol)
        if run.status != "stopped":
            raise NoPeriodicResponse(f"{system!r}: the run from a stick end does not stick again")
        # a step onto a stick end that sticks at once returns trivially (T -> 0)
        why = _not_a_return(system, x, mode, run.t, run.switches, tol)
        if why:
            raise NoPeriodicResponse(f"{system!r}: no stick-slip cycle found: Newton's {why}")
        r = run.y - x
        residual = float(np.abs(r).max())
        if residual <= NEWTON_TOL * scale:
            break
        eps = 1e-7 * scale
        grad = np.array(
            [(surface(x + eps * e) - surface(x - eps * e)) / (2 * eps) for e in np.eye(m)]
        )
        f = np.asarray(k_.field(run.t, run.y, p, run.mode), dtype=float)
        A = np.block([[run.monodromy - np.eye(m), f[:, None]], [grad[None, :], np.zeros((1, 1))]])
        step = np.linalg.lstsq(A, -np.concatenate((r, [surface(x)])), rcond=None)[0]
        x = x + step[:m]
    else:
        raise NoPeriodicResponse(
            f"{system!r}: no stick-slip cycle found: Newton's method left a residual "
            f"{residual:.2e} after {max_iter} iterations"
        )
    for j in (j for j in range(1, k) if k % j == 0):
        back = _end_states(system, x, mode, j, tol)
        if len(back) == j and np.abs(back[-1] - x).max() <= _RETURN_TOL * scale:
            return _newton_stick(system, x, mode, j, max_iter, tol)
    return _cycle(system, x, mode, run, residual, tol)
