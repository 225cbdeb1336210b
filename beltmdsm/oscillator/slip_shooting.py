"""Shooting a pure-slip self-excited cycle: on the section where the slip speed is least.

The section is a Poincare section where the slip speed ``m v_r`` is least
(``slip_acceleration = 0``, the point of the orbit closest to stick: its slip velocity
there measures the distance to the stick onset, `beltmdsm.oscillator.onset`); the run
goes over ``T``, an unknown of the bordered system (`beltmdsm.oscillator.cycles`). The
period reported is the least: no ``T/j``, ``j <= 6``, returns to the state.
"""

from __future__ import annotations

import numpy as np

from ..errors import NoPeriodicResponse
from .cycle import _RETURN_TOL, NEWTON_TOL, _cycle
from .hybrid import flow

#: Divisors of a pure-slip cycle's period checked for a return.
_DIVISORS = 6
#: Halvings of a Newton step before the method counts as stalled.
_HALVINGS = 10


def _shoot_slip(system, x, T, max_iter, tol):
    """Newton's method on ``(x, T)``, the section where the slip speed is least
    (``slip_acceleration = 0``: its gradient ``J^T w`` by the derived Jacobian)."""
    k_, p = system.kernels, system.p
    x = np.asarray(x, dtype=float)
    m = x.size
    mode = _mode(system, x)
    scale = 1.0 + np.abs(x).max()
    run = flow(system, 0.0, x, T, mode=mode, variational=True, **tol)
    if run.switches:
        raise NoPeriodicResponse(
            f"{system!r}: the run from the guess switches at t = {run.switches[0][0]:.6g} s: "
            "no pure-slip cycle through it"
        )
    for _ in range(max_iter):
        r = run.y - x
        residual = float(np.abs(r).max())
        if residual <= NEWTON_TOL * scale:
            break
        w = np.asarray(k_.slip_gradient(0.0, x, p), dtype=float)
        grad = np.asarray(k_.jacobian(0.0, x, p, mode), dtype=float).T @ w
        f = np.asarray(k_.field(T, run.y, p, mode), dtype=float)
        A = np.block([[run.monodromy - np.eye(m), f[:, None]], [grad[None, :], np.zeros((1, 1))]])
        b = -np.concatenate((r, [k_.slip_acceleration(0.0, x, p, mode)]))
        step = np.linalg.solve(A, b)
        # damped: a step that reaches a switch or does not reduce the residual is halved
        for _ in range(_HALVINGS):
            trial = flow(system, 0.0, x + step[:m], T + step[m], mode=mode, variational=True, **tol)
            if not trial.switches and np.abs(trial.y - x - step[:m]).max() < residual:
                break
            step = 0.5 * step
        else:
            raise NoPeriodicResponse(
                f"{system!r}: no slip cycle found: Newton's method stalled at a residual "
                f"{residual:.2e} (no step of {_HALVINGS} halvings reduces it)"
            )
        x, T, run = x + step[:m], T + step[m], trial
    else:
        raise NoPeriodicResponse(
            f"{system!r}: no slip cycle found: Newton's method left a residual "
            f"{residual:.2e} after {max_iter} iterations"
        )
    # the scale of the orbit: the distance the flow covers in a period
    size = np.abs(np.asarray(k_.field(0.0, x, p, mode), dtype=float)).max() * T
    if size <= NEWTON_TOL * scale:  # every T returns there: no least period to test
        raise NoPeriodicResponse(
            f"{system!r}: Newton's method converged on steady sliding, not on a cycle"
        )
    for j in range(_DIVISORS, 1, -1):
        back = flow(system, 0.0, x, T / j, mode=mode, **tol)
        if np.abs(back.y - x).max() <= _RETURN_TOL * size:
            return _shoot_slip(system, x, T / j, max_iter, tol)
    return _cycle(system, x, mode, run, residual, tol)


def least_speed(c):
    """The pure-slip cycle ``c`` shot again from where its slip speed is least (the
    section ``slip_acceleration = 0`` has a second point, where it is largest, which
    Newton's method may have found; the stick onset and the continuation of a cycle,
    `beltmdsm.continuation.oscillator_cycle`, follow the least).

    Parameters
    ----------
    c : Cycle
        Pure slip.

    Returns
    -------
    Cycle

    See Also
    --------
    beltmdsm.oscillator.onset.stick_onset : follows the least slip speed to 0.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5),
    ...                        [3.0182035, 2.0991444], 6.3203187)
    >>> round(float(2.5 - least_speed(c).state[1]), 6)  # the least slip speed, Vb - x'
    0.400856
    """
    k, p = c.system.kernels, c.system.p
    samples: list = []
    flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=c.period / 2000, samples=samples)
    ys = np.concatenate([y for _, y, _ in samples])
    speed = [c.mode * k.slip_velocity(0.0, y, p) for y in ys]
    tol = dict(rtol=1e-11, atol=1e-11)
    return _shoot_slip(c.system, ys[int(np.argmin(speed))], c.period, 30, tol)


def _mode(system, x):
    v = system.kernels.slip_velocity(0.0, x, system.p)
    return 1 if v > 0.0 else -1
