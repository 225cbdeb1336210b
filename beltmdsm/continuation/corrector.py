"""The one corrector: Newton's method on a problem's equations and the driver's own.

`newton` serves every `beltmdsm.continuation.problem.Problem` (through
``Problem.solve``): it asks the problem for its residual, its Jacobian (the parameter
column kept from a nearby point unless ``fresh``) and its solution, and adds one
equation (the arclength's hyperplane, or a pinned parameter).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import NoPeriodicResponse

__all__ = ["newton"]


def newton(problem: Any, z_pred, extra, column=None, fresh=False) -> Any:
    """Newton's method on a problem's equations and ``extra(z) = (value, row)``.

    Parameters
    ----------
    problem : Problem
        Its ``residual``, ``jacobian`` and ``solution``.
    z_pred : ndarray (n + 1,)
        Where it starts (scaled unknowns).
    extra : callable
        The driver's own equation: ``(residual, gradient row)`` at ``z``.
    column : ndarray (n,), optional
        The Jacobian's parameter column at a point nearby, kept through the iterations
        (computed at the first where None) unless ``fresh``.
    fresh : bool
        Recompute the parameter column at every iterate (across a kink).
    Returns
    -------
    Step
        The solution, its Jacobian fresh.

    Raises
    ------
    NoPeriodicResponse
        Where the residual does not shrink, the matrix is singular, or the iterations
        run out.

    See Also
    --------
    beltmdsm.continuation.driver.walk : calls it at every step (``Problem.solve``).

    Examples
    --------
    The unit circle ``u^2 + p^2 = 1`` (`beltmdsm.continuation.circle`) pinned at
    ``p = 0.6``:

    >>> from beltmdsm.continuation.circle import Circle
    >>> pin = lambda z: (z[1] - 0.6, np.array([0.0, 1.0]))
    >>> step = newton(Circle(-1.0, 1.0), np.array([1.0, 0.6]), pin)
    >>> round(float(step.z[0]), 12), step.value
    (0.8, 0.6)
    """
    settings = problem.settings
    z, last = np.array(z_pred, dtype=float), math.inf
    for iteration in range(1, settings.corrector_iter + 1):
        e, row = extra(z)
        r = problem.residual(z, e, iteration)
        if r.converged:
            return problem.solution(r.data, iteration)
        if r.size >= last and iteration > problem.diverge_after:
            raise NoPeriodicResponse(f"the corrector diverges (residual {r.size:.2e})")
        last = r.size
        J = problem.jacobian(r.data, None if fresh else column)
        column = J[:, -1].copy()
        try:
            z = z + np.linalg.solve(np.vstack([J, row]), -np.append(r.F, e))
        except np.linalg.LinAlgError:
            raise NoPeriodicResponse("the corrector's matrix is singular") from None
    raise NoPeriodicResponse(f"the corrector leaves a residual {last:.2e}")
