"""The result of `beltmdsm.continuation.floquet_map.floquet_map`: the map and its curves.

`FloquetMap` holds, per row, where no stable periodic response is found and where the
paper's linear analysis says unstable, and the boundary `Curve`s, each of one
bifurcation kind; `FloquetMap.as_dict` is the JSON of ``floquet-map --json``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._tables import DataFrame
from ..model import Model
from ..periodic.engines import engine_of

__all__ = ["Curve", "FloquetMap"]


@dataclass
class Curve:
    """A boundary curve of one kind: ``x`` against ``y``.

    Attributes
    ----------
    kind : str
    y, x : list of float
    accuracy : list of float
        Per point, a bound of the error of ``x``.
    frequency : list of float or None
        Of the critical pair at a Neimark-Sacker curve [rad/s].
    unstable_below, unstable_above : bool
        Whether no stable response lies just below and just above the edge in ``x``.
    ended : str
        Why the curve stops where it does ("" at the last row).

    See Also
    --------
    beltmdsm.continuation.map_result.FloquetMap : its ``curves``.

    Examples
    --------
    >>> from beltmdsm import floquet_map
    >>> m = floquet_map(None, "Vb", 5.3, 5.7, "beta1", 0.29, 0.31, points=3)
    >>> curve = m.curves[0]
    >>> curve.kind, curve.y, curve.ended
    ('neimark_sacker', [0.29, 0.3, 0.31], '')
    >>> bool(max(curve.accuracy) < 1e-6 * (5.7 - 5.3) * 10)
    True
    """

    kind: str
    y: list = field(default_factory=list)
    x: list = field(default_factory=list)
    accuracy: list = field(default_factory=list)
    frequency: list = field(default_factory=list)
    unstable_below: bool = True
    unstable_above: bool = True
    ended: str = ""

    def __repr__(self) -> str:
        from .._display import label

        if not self.x:
            return f"Curve({self.kind!r}, no points)"
        return (
            f"Curve({self.kind!r} ({label(self.kind)}), {len(self.x)} points: y "
            f"{self.y[0]:.4g}..{self.y[-1]:.4g}, x {self.x[0]:.6g}..{self.x[-1]:.6g}, to "
            f"{max(self.accuracy):.0e}" + (f"; {self.ended}" if self.ended else "") + ")"
        )

    def as_dict(self) -> dict:
        """For JSON: the attributes."""
        return {
            "kind": self.kind,
            "y": self.y,
            "x": self.x,
            "accuracy": self.accuracy,
            "frequency": self.frequency,
            "unstable_below": self.unstable_below,
            "unstable_above": self.unstable_above,
            "ended": self.ended,
        }


@dataclass
class FloquetMap:
    """The result of `floquet_map`.

    Attributes
    ----------
    x, y : str
        The parameters of the axes.
    x_range, y_range : list of float
    rows : ndarray
        The ``y`` of each row.
    model : Model
        The other parameters and the options (``x`` and ``y`` at the first row's start).
    curves : list of Curve
    unstable : list of list
        Per row, the ``[lo, hi]`` of ``x`` where no stable periodic response is found
        (unstable or absent; on a row in ``band_rows`` the band's, module docstring).
    linear : list of list
        Per row, where the paper's linear analysis says unstable (``x`` resolved to
        the range over `LINEAR_POINTS` - 1).
    band_rows : list of float
        The rows on which a band found the edges afresh.
    wall_s : float

    See Also
    --------
    beltmdsm.continuation.floquet_map.floquet_map : computes it.
    beltmdsm.continuation.band_result.Band : one row's band.

    Examples
    --------
    >>> from beltmdsm import floquet_map
    >>> m = floquet_map(None, "Vb", 5.3, 5.7, "beta1", 0.29, 0.31, points=3)
    >>> m  # doctest: +ELLIPSIS
    FloquetMap('Vb' in [5.3, 5.7], 'beta1' in [0.29, 0.31], ...; 3 rows, ... s): 1 boundary curves
      Curve('neimark_sacker' (NS), 3 points: y 0.29..0.31, x 5.42...5.47..., to ...)
    >>> m.band_rows, m.linear
    ([0.29], [[], [], []])
    >>> m.to_pandas()[["beta1", "Vb"]].round(3).values.tolist()
    [[0.29, 5.426], [0.3, 5.45], [0.31, 5.471]]
    """

    x: str
    y: str
    x_range: list
    y_range: list
    rows: np.ndarray
    model: Model
    curves: list
    unstable: list
    linear: list
    band_rows: list
    wall_s: float

    def plot(self, ax: Any = None, linear: bool = True) -> Any:
        """The map: where no stable response is found, the boundary curves by kind,
        and (``linear``) the paper's linear analysis, on matplotlib axes ``ax`` (new
        ones if None), which it returns (`beltmdsm.plotting.floquet_map`; matplotlib
        is imported here)."""
        from ..plotting import floquet_map as draw

        return draw(self, ax, linear)

    def to_pandas(self) -> DataFrame:
        """The boundary curves as a `pandas.DataFrame` (needs pandas, imported here): one
        row per point of a curve, ``curve`` (its index in `curves`), ``kind``, ``y``
        and ``x`` named by their parameters, ``accuracy``, ``frequency``."""
        from .._tables import frame

        rows = [
            {"curve": i, "kind": c.kind, self.y: y, self.x: x, "accuracy": a, "frequency": f}
            for i, c in enumerate(self.curves)
            for y, x, a, f in zip(c.y, c.x, c.accuracy, c.frequency or [None] * len(c.x))
        ]
        return frame(rows, ["curve", "kind", self.y, self.x, "accuracy", "frequency"])

    def __repr__(self) -> str:
        from .._display import block, laws

        return block(
            f"FloquetMap({self.x!r} in [{self.x_range[0]:g}, {self.x_range[1]:g}], "
            f"{self.y!r} in [{self.y_range[0]:g}, {self.y_range[1]:g}], {self.model!r}; "
            f"{laws(self.model)}; {len(self.rows)} rows, {self.wall_s:.1f} s): "
            f"{len(self.curves)} boundary curves",
            [repr(c) for c in self.curves],
        )

    def as_dict(self) -> dict:
        """For JSON: ``x``, ``y``, ``x_range``, ``y_range``, ``rows``, ``contact``,
        ``tension``, ``friction``, ``engine``, ``curves``, ``unstable``, ``linear``,
        ``band_rows``, ``wall_s``."""
        return {**self._model_dict(), **self._map_dict()}

    def _map_dict(self) -> dict:
        """The map's own part of `as_dict`, whatever the model."""
        return {
            "x": self.x,
            "y": self.y,
            "x_range": self.x_range,
            "y_range": self.y_range,
            "rows": [float(v) for v in self.rows],
            "curves": [c.as_dict() for c in self.curves],
            "unstable": self.unstable,
            "linear": self.linear,
            "band_rows": self.band_rows,
            "wall_s": self.wall_s,
        }

    def _model_dict(self) -> dict:
        """The paper model's part of `as_dict`: its laws and period map."""
        return {
            "contact": self.model.contact,
            "tension": self.model.tension,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
        }
