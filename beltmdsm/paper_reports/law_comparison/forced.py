"""Where the ``T``-periodic forced response is unstable, per friction law (`forced_stability`).

The Floquet band of `beltmdsm.continuation.band.floquet_band` over ``Vb``, its labelled
edges and the growth rate ``log max|mu| / T`` at every evaluated value.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...continuation.band import floquet_band
from ...continuation.band_result import Band
from ...model import Model
from ...periodic.engines import engine_of
from .laws import VB_RANGE, Law

__all__ = ["ForcedStability", "forced_stability"]


@dataclass(frozen=True)
class ForcedStability:
    """Where the ``T``-periodic forced response is unstable, by Floquet (part (b)).

    Attributes
    ----------
    law : Law
    tension : str
    band : Band
        `beltmdsm.continuation.band.floquet_band` over ``Vb``.
    engine : str
        The Floquet path the law takes (``"closed_form"`` or ``"general"``).
    vb, growth_rate : ndarray
        Every value the band evaluated, ascending, and the growth rate
        ``log max|mu| / T`` there [1/s] (NaN where the response grazes).
    n_reversals : ndarray of int
        Reversals per period of the response at each value.
    wall_s : float
        The band's wall time [s].

    See Also
    --------
    beltmdsm.paper_reports.law_comparison.forced.forced_stability : what builds it.

    Examples
    --------
    At ``beta1 = 0.3`` under Coulomb's law the response loses stability at a
    Neimark-Sacker point near 5.45 m/s; the growth rate changes sign there:

    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> f = forced_stability(LAWS["coulomb"], "allowed", {"beta1": 0.3},
    ...                      lo=5.2, hi=5.8, points=4)
    >>> f.engine, [(round(v, 3), kind) for v, kind in f.edges]
    ('closed_form', [(5.45, 'neimark_sacker')])
    >>> bool(f.growth_at(5.2) < 0 < f.growth_at(5.8)), f.growth_at(5.3)
    (True, nan)
    """

    law: Law
    tension: str
    band: Band = field(repr=False)
    engine: str
    vb: NDArray[np.float64] = field(repr=False)
    growth_rate: NDArray[np.float64] = field(repr=False)
    n_reversals: NDArray[np.int64] = field(repr=False)
    wall_s: float

    @property
    def unstable(self) -> list[tuple[float, float]]:
        """The band's unstable ranges (unstable, or no periodic response found)."""
        return [(float(lo), float(hi)) for lo, hi in self.band.unstable]

    @property
    def edges(self) -> list[tuple[float, str]]:
        """``(value, kind)`` of each edge of the band."""
        return [(e.value, e.kind) for e in self.band.edges]

    def growth_at(self, vb: float) -> float:
        """The growth rate at an evaluated value (within 1e-9); NaN if none was evaluated."""
        i = int(np.argmin(np.abs(self.vb - vb)))
        return float(self.growth_rate[i]) if abs(self.vb[i] - vb) < 1e-9 else math.nan

    def as_dict(self) -> dict:
        """For JSON: the band's ranges and edges, the engine and the wall time."""
        return {
            "law": self.law.name,
            "tension": self.tension,
            "engine": self.engine,
            "unstable": [list(r) for r in self.unstable],
            "edges": [{"value": v, "kind": k} for v, k in self.edges],
            "no_periodic_response": [list(r) for r in self.band.no_periodic_response],
            "failed": [f.value for f in self.band.failed],
            "wall_s": self.wall_s,
        }


def forced_stability(
    law: Law,
    tension: str,
    model: Model | Mapping[str, Any] | None = None,
    *,
    lo: float = VB_RANGE[0],
    hi: float = VB_RANGE[1],
    points: int = 49,
    tol: float = 1e-3,
) -> ForcedStability:
    """The Floquet band of the forced response over ``Vb`` (part (b)).

    Parameters
    ----------
    law : Law
    tension : {"allowed", "clipped"}
    model : Model or dict, optional
        The other parameters (default: the base set, with its excitation).
    lo, hi : float
        The range of ``Vb`` [m/s].
    points, tol
        Of `beltmdsm.continuation.band.floquet_band`: grid values, and the edges' tolerance.

    Returns
    -------
    ForcedStability

    Raises
    ------
    ValueError
        for an unknown tension law or a bad parameter (from the model).

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : the band.
    beltmdsm.paper_reports.law_comparison.steady.steady_sliding : the unforced side (a).

    Examples
    --------
    Stribeck's law A at the base set: the forced response is unstable from a
    Neimark-Sacker point near 5.705 m/s to the top of the range:

    >>> from beltmdsm.paper_reports.law_comparison import LAWS
    >>> f = forced_stability(LAWS["stribeck_A"], "allowed", lo=5.5, hi=6.0, points=3)
    >>> [(round(lo, 3), hi) for lo, hi in f.unstable], [k for _, k in f.edges]
    ([(5.705, 6.0)], ['neimark_sacker'])
    """
    m = law.model(model, tension=tension)
    start = time.perf_counter()
    band = floquet_band(m, "Vb", lo, hi, points=points, tol=tol)
    wall = time.perf_counter() - start
    rows = sorted(band.grid, key=lambda r: r.value)
    return ForcedStability(
        law=law,
        tension=tension,
        band=band,
        engine=engine_of(m),
        vb=np.array([r.value for r in rows]),
        growth_rate=np.array([r.growth_rate for r in rows]),
        n_reversals=np.array([r.n_reversals for r in rows], dtype=np.int64),
        wall_s=wall,
    )
