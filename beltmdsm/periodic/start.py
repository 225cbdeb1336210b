"""The periodic start: a state on the periodic response, moved a little.

A run from `periodic_start` shows the instability of an unstable periodic response
(``simulate --start periodic``, `beltmdsm.simulation.simulate`), where a run from rest
may settle elsewhere; a stable response stays put.
"""

from __future__ import annotations

import math

import numpy as np

from .._calling import public
from ..model import Backend, Model
from .shooting import periodic_response

__all__ = [
    "PERTURBATION",
    "periodic_start",
]

#: ``periodic_start``: the run starts on the periodic response with X1 moved by this [m].
PERTURBATION = 1e-2


@public()
def periodic_start(
    model: Model, perturbation: float = PERTURBATION, backend: Backend | None = None
) -> np.ndarray:
    """A start state on the periodic response with ``X1`` moved by ``perturbation`` [m].

    An unstable response shows its instability from there, a stable one stays put
    (``simulate --start periodic``).

    Parameters
    ----------
    model : Model
    perturbation : float
        Added to ``X1`` [m] (default `PERTURBATION`).
    backend : {"python", "numba", None}

    Returns
    -------
    ndarray (4,)
        ``(X1, X1', X2, X2')`` at ``t = 0``: the response's state at phase 0 with
        ``X1`` moved.

    Raises
    ------
    ValueError
        For a perturbation that is not a finite number.
    beltmdsm.errors.NoPeriodicResponse
        Where no periodic response is found.

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : the response it starts on.
    beltmdsm.simulation.simulate : ``y0=periodic_start(model)``, or ``start="periodic"``.

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model, periodic_response, periodic_start
    >>> m = Model(Vb=5.0)
    >>> y0 = periodic_start(m, perturbation=0.5)
    >>> np.round(y0 - periodic_response(m).state0, 12)
    array([0.5, 0. , 0. , 0. ])
    """
    if not (isinstance(perturbation, (int, float)) and math.isfinite(perturbation)):
        raise ValueError(f"perturbation must be a finite number; got {perturbation!r}")
    state = periodic_response(model, backend=backend).state0
    return state + np.array([perturbation, 0.0, 0.0, 0.0])
