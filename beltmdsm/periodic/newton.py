"""Newton's method on the fixed points of a period map: the shooting of a periodic response.

`fixed_point` solves ``P(x) = x`` with damped steps, ``dP/dx - I`` its Jacobian, for
any `beltmdsm.periodic.base.PeriodMap`: the shooting of a response of period ``k T``
from a guess (the sliding orbit, an attractor of the map, a neighbour on a branch). It
raises `beltmdsm.errors.NoPeriodicResponse` where the residual stops halving. The
tolerances here are the shooting's: `NEWTON_TOL` (converged) and `ISOLATION_TOL` (a
fixed point that is not isolated).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse
from .base import MapImage, PeriodMap

__all__ = [
    "NEWTON_TOL",
    "ISOLATION_TOL",
    "FixedPoint",
    "fixed_point",
]

#: Newton's method stops when the period map moves the state by less than this
#: (relative to the state's scale).
NEWTON_TOL = 1e-11
#: ``I - M`` whose smallest singular value is below this (relative to ``M``) is singular:
#: a multiplier is 1 to within the closed forms' rounding amplified far past it, and the
#: fixed point, if any, is not isolated (its solve would return ~ 1 / this times the
#: forcing, or rounding noise).
ISOLATION_TOL = 1e-9
#: Halvings of a Newton step before the method counts as stalled.
_LINE_SEARCH = 8
#: Iterations over which Newton's residual must halve (converging, it squares; where
#: the orbit has stopped existing, the damped steps creep towards a switch-structure
#: change and the residual shrinks by a few per cent per iteration). 2 finds the same
#: periodic responses as 4 at all 262 points of the quick validation grids and every
#: band of its 16 cases, with a third fewer period maps in a band.
_STAGNATION = 2


@dataclass
class FixedPoint:
    """A fixed point of a period map: the state at phase 0 of a response of ``k`` periods.

    Attributes
    ----------
    state : ndarray (n,)
    image : MapImage
        The map at ``state`` (its Jacobian is the monodromy of the shooting state).
    residual : float
        ``max |P(x) - x|``.
    iterations : int

    See Also
    --------
    fixed_point : finds it.
    beltmdsm.periodic.response.response_from : the response of a fixed point.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> point = fixed_point(pmap, pmap.sliding_guess())
    >>> point.residual < 1e-10, point.image.jacobian.shape
    (True, (2, 2))
    """

    state: NDArray[np.float64]
    image: MapImage
    residual: float
    iterations: int


def fixed_point(pmap: PeriodMap, guess: ArrayLike, max_iter: int = 30) -> FixedPoint:
    """Newton's method on ``P(x) - x`` with damped steps, ``dP/dx - I`` its Jacobian.

    Parameters
    ----------
    pmap : PeriodMap
    guess : array_like (n,)
    max_iter : int

    Returns
    -------
    FixedPoint

    Raises
    ------
    NoPeriodicResponse
        If the residual stops halving (over a few iterations), no damped step reduces
        it, or ``max_iter`` iterations leave it above `NEWTON_TOL` (relative to the
        state's scale).

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : the shooting with its guesses.
    beltmdsm.periodic.engines.period_map : the map.

    Examples
    --------
    >>> from beltmdsm import Model, NoPeriodicResponse
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> point = fixed_point(pmap, pmap.sliding_guess())
    >>> [round(float(v), 3) for v in point.state]  # (X1, X1') at phase 0
    [4.566, -6.146]

    Where the backward-sliding orbit is no guess for it, Newton's method says so:

    >>> far = period_map(Model(Vb=6.3))
    >>> try:
    ...     fixed_point(far, far.sliding_guess())
    ... except NoPeriodicResponse as failure:
    ...     print(failure)  # doctest: +ELLIPSIS
    no periodic response found: Newton's method ...
    """
    what = "" if pmap.periods == 1 else f" of {pmap.periods} periods"
    x = np.array(guess, dtype=float)
    image = pmap(x)
    r = image.state - x
    history = []
    for iteration in range(1, max_iter + 1):
        residual = float(np.max(np.abs(r)))
        if residual <= NEWTON_TOL * (1.0 + np.max(np.abs(x))):
            return FixedPoint(x, image, residual, iteration)
        history.append(residual)
        if len(history) > _STAGNATION and history[-1] > 0.5 * history[-1 - _STAGNATION]:
            raise NoPeriodicResponse(
                f"no periodic response{what} found: Newton's method stagnates at a "
                f"residual {residual:.2e} (not halved in {_STAGNATION} iterations)"
            )
        A = image.jacobian - np.eye(x.size)
        try:
            step = -np.linalg.solve(A, r)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(A, r, rcond=None)[0]
        lam = 1.0
        for _ in range(_LINE_SEARCH):
            x_new = x + lam * step
            image_new = pmap(x_new)
            r_new = image_new.state - x_new
            if np.max(np.abs(r_new)) < residual:
                break
            lam *= 0.5
        else:
            raise NoPeriodicResponse(
                f"no periodic response{what} found: Newton's method stalled at a "
                f"residual {residual:.2e} (no step of {_LINE_SEARCH} halvings reduces it)"
            )
        x, image, r = x_new, image_new, r_new
    raise NoPeriodicResponse(
        f"no periodic response{what} found: Newton's method left a residual "
        f"{float(np.max(np.abs(r))):.2e} after {max_iter} iterations"
    )
