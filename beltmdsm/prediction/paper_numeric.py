"""The paper's analysis without its closed form: the sign of its growth rate over ``Vb``.

Where Eqs. (25), (28) have no closed form (the law's fast average is a quadrature, or
``V_hat`` depends on ``Vb``: Stribeck's law), `paper_numeric` finds the same analysis'
unstable set: the sign of the pointwise `beltmdsm.generated.stability.growth_rate` (its
effective friction a quadrature of the law's expression) on a grid of ``Vb``, each
edge refined by ``brentq``, with ``V_hat`` of the chosen reading evaluated at each
``Vb`` (the fast amplitude frozen in the slow linearisation: the slope is
``d mu_bar / d Vr`` at fixed ``V_hat``).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Literal

import numpy as np
from scipy import optimize

from beltmdsm.generated import friction, stability

from .. import intervals
from ..model import Model, as_model
from .scan import _EXTEND
from .sliding import _unforced_edge

__all__ = ["paper_numeric", "PAPER_POINTS", "PAPER_XTOL", "NO_VHAT"]


NO_VHAT = "V_hat = 0 (no fast tangential motion): Eqs. (23)-(25) need V_hat > 0"


#: Points of the grid of `paper_numeric` (from ``Vb = 0``); the growth rate under a
#: quadrature costs about 20 us a point, vectorised.
PAPER_POINTS = 2000


#: The tolerance of `paper_numeric`'s edges (brentq's ``xtol``) [m/s].
PAPER_XTOL = 1e-12


#: How far (relative) either side of a crossing ``V_hat(Vb) = Vb`` `paper_numeric` puts
#: grid points: the slope of Eq. (25) jumps there, and a change of stability between
#: them is an edge at the crossing itself.
_CROSSING_STEP = 1e-9


def _grid_top(model: Model, kw_vhat: dict) -> float:
    """The default top of `paper_numeric`'s grid: 1.05 times ``V_hat(0)`` plus the
    unforced critical belt speed (as the consistent MDSM's grid: above ``V_hat`` the
    fast motion still sweeps the falling part of a law like Stribeck's)."""
    v0 = float(friction.vhat(**{**kw_vhat, "Vb": 0.0}))
    return 1.05 * (v0 + _unforced_edge(model))


def paper_numeric(
    model: Model | Mapping[str, Any] | None = None,
    *,
    reading: Literal["tangential", "coupled"] = "tangential",
    convention: Literal["paper", "consistent"] = "paper",
    points: int = PAPER_POINTS,
    **kw: Any,
) -> tuple[list[tuple[float, float]], dict[str, Any]]:
    """The unstable belt speeds of the paper's analysis without its closed form.

    The set where `beltmdsm.generated.stability.growth_rate` (Eq. 26 with Eqs. 23-25; the
    effective friction and its slope a quadrature of the law's expression where the
    law has no closed-form fast average) is positive, with ``V_hat`` of ``reading``
    (`beltmdsm.generated.friction.vhat`) evaluated at each ``Vb``: the reading implemented is
    the fast amplitude of the equilibrium at that belt speed, held fixed in the slow
    linearisation (the slope is ``d mu_bar / d Vr`` at fixed ``V_hat``, not the total
    derivative in ``Vb``). For Coulomb's law it is the closed form's set, to the
    tolerance (`tests/beltmdsm/prediction/test_predict.py`).

    On ``points`` belt speeds from 0 up to `_grid_top` (doubled up to 3 times while
    a band reaches it) plus the points either side of each crossing ``V_hat(Vb) = Vb``
    (found by brentq), each change of sign of the growth rate between neighbours is
    an edge: the crossing itself where the two sit either side of one (the slope of
    Eq. 25 jumps there), else a root of the growth rate refined by brentq to
    `PAPER_XTOL`. A band narrower than the grid step can be missed.

    Parameters
    ----------
    model : Model, mapping or None
        The parameter set (or the keywords ``**kw`` it is built from).
    reading : {"tangential", "coupled"}
        The reading of ``V_hat`` (`beltmdsm.generated.friction.vhat`).
    convention : {"paper", "consistent"}
        The sign of the effective friction in Eq. (A4), as for
        `beltmdsm.prediction.paper.paper_intervals`.
    points : int
        The grid's size before the points at the crossings are added.

    Returns
    -------
    intervals : list of (lower, upper)
        The unstable belt speeds [m/s].
    info : dict
        ``top`` (the grid's end), ``points``, ``step``, ``crossings`` (the belt speeds
        where ``V_hat(Vb) = Vb``), ``reaches_top`` (a band ends at the grid's end).

    Raises
    ------
    ValueError
        Where ``V_hat`` is not positive on the grid (no fast motion: Eqs. 23-25
        need ``V_hat > 0``; the message is `NO_VHAT`).

    See Also
    --------
    beltmdsm.prediction.paper.paper_intervals : the closed forms, where they exist.

    Examples
    --------
    Stribeck's law has no closed-form fast average; the tangential reading is
    unstable from 3.805 m/s up to the crossing ``V_hat(Vb) = Vb``:

    >>> found, info = paper_numeric(friction="stribeck", mu_k=0.25, v_s=1.0, points=200)
    >>> [(round(lo, 3), round(hi, 3)) for lo, hi in found]
    [(3.805, 8.521)]
    >>> [round(c, 3) for c in info["crossings"]], info["reaches_top"]
    ([8.521], False)
    """
    model = as_model(model, **kw)
    grow, fv = stability.growth_rate, friction.vhat
    kw_grow = {**model.arguments(grow), "convention": convention, "vhat_model": reading}
    kw_vhat = {**model.arguments(fv), "model": reading}

    def sigma(vb):
        return grow(**{**kw_grow, "Vb": vb})

    def gap(vb):
        return vb - fv(**{**kw_vhat, "Vb": vb})

    top = _grid_top(model, kw_vhat)
    if not top > 0:
        raise ValueError(NO_VHAT)
    for extend in range(_EXTEND + 1):
        base = np.linspace(0.0, top, points)
        g = gap(base)
        if not np.all(g < base):
            raise ValueError(NO_VHAT)
        crossings = [
            optimize.brentq(gap, base[i], base[i + 1], xtol=PAPER_XTOL)
            for i in intervals.sign_changes(g)
        ]
        sides = [c * (1 + d * _CROSSING_STEP) for c in crossings for d in (-1, 1)]
        grid = np.union1d(base, [v for v in sides if 0 < v < top])
        s = sigma(grid)
        cuts = []
        for i in intervals.sign_changes(-s):
            lo, hi = grid[i], grid[i + 1]
            at = [c for c in crossings if lo <= c <= hi]
            if at:
                cuts.append(at[0])
            else:
                cuts.append(optimize.brentq(sigma, lo, hi, xtol=PAPER_XTOL))
        found = intervals.from_crossings(grid, s > 0, cuts)
        reaches = bool(found and found[-1][1] == grid[-1])
        if not reaches or extend == _EXTEND:
            break
        top *= 2
    info = {
        "top": float(top),
        "points": int(grid.size),
        "step": float(top / (points - 1)),
        "crossings": [float(c) for c in crossings],
        "reaches_top": reaches,
    }
    return found, info
