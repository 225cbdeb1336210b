"""Steady sliding without excitation: where it changes stability, numerically.

The consistent MDSM's default grid (`beltmdsm.prediction.scan`) and the paper's
numeric path (`beltmdsm.prediction.paper_numeric`) reach above the onset of friction
reversal by the unforced critical belt speed, `beltmdsm.generated.unforced.critical_belt_speed`
where the law has it in closed form; where the closed form is refused, its edges are
the roots of the largest real part of `beltmdsm.generated.unforced.eigenvalues`
(`unforced_edges`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import optimize

from beltmdsm.generated import unforced

from .. import intervals
from ..model import Model, as_model

__all__ = ["UNFORCED_SCAN", "UNFORCED_NUMERIC", "unforced_rate", "unforced_edges"]


#: Where the unforced growth rate's roots are looked for when the law's closed form is
#: refused (`unforced_edges`): 1e-8 to 1e8 m/s, 100 speeds a decade (a ratio of 2.3 %
#: between neighbours: a band narrower than that can be missed).
UNFORCED_SCAN = (1e-8, 1e8, 100)


def unforced_rate(model: Model | Mapping[str, Any] | None, vb: ArrayLike) -> NDArray:
    """The largest real part of `beltmdsm.generated.unforced.eigenvalues` at each belt speed:
    steady sliding is unstable where it is positive.

    Parameters
    ----------
    model : Model or dict or None
        The parameters and the laws (None: the base set).
    vb : array_like
        Belt speeds [m/s].

    Returns
    -------
    ndarray
        The rate [1/s] at each belt speed, of the shape of ``vb``.

    See Also
    --------
    unforced_edges : its roots.

    Examples
    --------
    Under Stribeck's law steady sliding grows at 0.5 m/s and decays at 5 m/s:

    >>> rate = unforced_rate({"friction": "stribeck", "mu_k": 0.25, "v_s": 1.0}, [0.5, 5.0])
    >>> [round(float(r), 4) for r in rate]
    [0.3463, -0.095]
    """
    model = as_model(model)
    fn = unforced.eigenvalues
    args = {**model.arguments(fn), "Vb": np.asarray(vb, dtype=float)}
    return np.max(np.real(fn(**args)), axis=-1)


def unforced_edges(model: Model | Mapping[str, Any] | None = None, **kw: Any) -> list[float]:
    """The belt speeds where steady sliding changes stability, numerically.

    The roots of `unforced_rate` over `UNFORCED_SCAN` (a geometric grid), each sign
    change refined by ``brentq`` to 1e-12 relative: the path where the law's closed
    form (`beltmdsm.generated.unforced.critical_belt_speed`) is refused. A band narrower than
    the scan's ratio (2.3 %) can be missed.

    Parameters
    ----------
    model : Model or dict, optional
        The parameters and the laws (default: the base set); ``**kw`` too.

    Returns
    -------
    list of float
        The belt speeds [m/s], ascending; empty where steady sliding keeps its
        stability over the scan.

    See Also
    --------
    unforced_rate : the rate whose roots they are.

    Examples
    --------
    >>> [round(v, 6) for v in unforced_edges(friction="stribeck", mu_k=0.25, v_s=1.0)]
    [1.99572]
    >>> unforced_edges()  # Coulomb's law: steady sliding is stable at every belt speed
    []
    """
    model = as_model(model, **kw)
    lo, hi, per_decade = UNFORCED_SCAN
    vb = np.geomspace(lo, hi, int(round(per_decade * math.log10(hi / lo))) + 1)
    rate = unforced_rate(model, vb)
    edges = []
    for i in intervals.sign_changes(rate):
        edges.append(
            optimize.brentq(
                lambda v: float(unforced_rate(model, [v])[0]),
                vb[i],
                vb[i + 1],
                xtol=1e-300,
                rtol=1e-12,
            )
        )
    return edges


def _unforced_edge(model: Model) -> float:
    """The unforced critical belt speed (`beltmdsm.generated.unforced.critical_belt_speed`) where it
    is finite and positive; where the law's closed form is refused, the largest of
    `unforced_edges`; else 0."""
    fn = unforced.critical_belt_speed
    try:
        edge = float(fn(**model.arguments(fn)))
    except ValueError:  # a law without a closed-form boundary refuses (Unsupported)
        edges = unforced_edges(model)
        return max(edges) if edges else 0.0
    return edge if math.isfinite(edge) and edge > 0 else 0.0


def _unforced_note(model: Model) -> str:
    """Where the unforced critical speed's closed form is refused: how it was found."""
    fn = unforced.critical_belt_speed
    try:
        fn(**model.arguments(fn))
    except ValueError as err:
        edges = unforced_edges(model)
        found = ", ".join(f"{v:.6g}" for v in edges) or "none"
        return UNFORCED_NUMERIC.format(why=err, edges=found)
    return ""


#: How the unforced critical belt speed was found where the law's closed form is
#: refused (formatted with the refusal and the edges found).
UNFORCED_NUMERIC = (
    "the unforced critical belt speed has no closed form ({why}); steady sliding "
    "changes stability at Vb = {edges} m/s, the roots of the largest real part of "
    "beltmdsm.generated.unforced.eigenvalues over 1e-8..1e8 m/s (100 speeds a decade, brentq "
    "to 1e-12 relative; a band narrower than 2.3 % can be missed)"
)
