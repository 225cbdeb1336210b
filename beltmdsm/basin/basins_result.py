"""The result of `beltmdsm.basin.basins.basins`: which attractor each start of a plane of
initial states reaches (`Basins`), and each attractor found with its share
(`BasinAttractor`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._tables import DataFrame
from ..attractors.classification import (
    Attractor,
)
from ..model import Model
from .axes import AXES

__all__ = ["BasinAttractor", "Basins"]


@dataclass
class BasinAttractor:
    """An attractor of a basin map: its classification, label and share of the starts.

    Attributes
    ----------
    label : int
        its value in `Basins.labels`
    attractor : beltmdsm.attractors.classification.Attractor
        what it is (periodic, quasi-periodic, chaotic) and the evidence
    fraction : float
        the share of the grid's starts that reach it
    points : ndarray (n, 4)
        its stroboscopic points (one per excitation period of a periodic one); of a
        self-excited cycle, points along its orbit
    period : float or None
        A self-excited cycle's period [s] (None for a forced model's attractors, whose
        ``periods`` counts excitation periods)

    See Also
    --------
    beltmdsm.basin.basins.basins : computes the map and its attractors.

    Examples
    --------
    At 3.88 m/s eight of nine starts (88.9%) land on the response locked at four
    excitation periods, drawn by its four stroboscopic points:

    >>> from beltmdsm import Model, basins
    >>> b = basins(Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5,
    ...            cache_dir=None)
    >>> a = b.attractors[1]
    >>> a
    BasinAttractor(1: periodic 4T, 88.9% of the starts)
    >>> a.points.shape, a.as_dict()["periods"], round(a.as_dict()["fraction"], 3)
    ((4, 4), 4, 0.889)
    """

    label: int
    attractor: Attractor = field(repr=False)
    fraction: float
    points: NDArray[np.float64] = field(repr=False)
    period: float | None = field(repr=False, default=None)

    def __repr__(self) -> str:
        a = self.attractor
        if self.period is not None:  # a self-excited cycle: its period in seconds
            what = f"{a.kind} {self.period:.4g} s"
        else:
            what = a.kind + (f" {a.periods}T" if a.periods else "")
        return f"BasinAttractor({self.label}: {what}, {100 * self.fraction:.1f}% of the starts)"

    def as_dict(self) -> dict:
        a = self.attractor.as_dict()
        return {
            "label": self.label,
            "kind": a["kind"],
            "periods": a["periods"],
            "period": self.period,
            "rotation_number": a["rotation_number"],
            "lyapunov": a["lyapunov"],
            "lyapunov_error": a["lyapunov_error"],
            "fraction": self.fraction,
            "evidence": a["evidence"],
            "state": a["state"],
        }


@dataclass
class Basins:
    """A basin map: a label per start of a grid of the plane ``(x, y)``.

    Attributes
    ----------
    model : Model
    x, y : str
        The axes (`AXES`).
    xs, ys : ndarray
        The grid's values on each axis.
    labels : ndarray (len(ys), len(xs)) of int
        The attractor each start reaches (`BasinAttractor.label`), -1 where none was
        identified within the rounds.
    attractors : list of BasinAttractor
    periods : ndarray (len(ys), len(xs))
        The periods each start was iterated before it was identified (0 without
        excitation: no period map is iterated).
    boundaries : list of ndarray (m, 4)
        Without excitation: the unstable cycles that bound the basins, one period each.

    See Also
    --------
    beltmdsm.basin.basins.basins : computes it.

    Examples
    --------
    >>> from beltmdsm import Model, basins
    >>> b = basins(Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5,
    ...            cache_dir=None)
    >>> b  # doctest: +NORMALIZE_WHITESPACE
    Basins(9 starts on (X1, Y1): [BasinAttractor(0: periodic 1T, 11.1% of the starts),
        BasinAttractor(1: periodic 4T, 88.9% of the starts)])
    >>> b.labels.tolist()
    [[1, 1, 1], [1, 0, 1], [1, 1, 1]]
    >>> sorted(b.as_dict()), b.as_dict()["grid"]["x"]
    (['attractors', 'grid', 'unidentified'], 'X1')
    """

    model: Model = field(repr=False)
    x: str
    y: str
    xs: NDArray[np.float64] = field(repr=False)
    ys: NDArray[np.float64] = field(repr=False)
    labels: NDArray[np.int_] = field(repr=False)
    attractors: list[BasinAttractor]
    periods: NDArray[np.int_] = field(repr=False)
    boundaries: list = field(repr=False, default_factory=list)

    def __repr__(self) -> str:
        shares = ", ".join(repr(a) for a in self.attractors)
        left = int(np.sum(self.labels < 0))
        return (
            f"Basins({self.labels.size} starts on ({self.x}, {self.y}): [{shares}]"
            + (f", {left} unidentified" if left else "")
            + ")"
        )

    def as_dict(self) -> dict:
        """JSON-ready: ``attractors`` and ``grid`` (the axes and a label per start)."""
        return {
            "attractors": [a.as_dict() for a in self.attractors],
            "grid": {
                "x": self.x,
                "y": self.y,
                "xs": [float(v) for v in self.xs],
                "ys": [float(v) for v in self.ys],
                "labels": self.labels.tolist(),
            },
            "unidentified": int(np.sum(self.labels < 0)),
        }

    def to_pandas(self, table: str = "starts") -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the ``"starts"`` (one row per start of
        the grid: its two coordinates, named by the axes, the ``label`` of the attractor
        it reaches, -1 where none, and the ``periods`` it was iterated) or of the
        ``"attractors"`` (``label``, ``kind``, ``periods``, ``rotation_number``,
        ``lyapunov``, ``lyapunov_error``, ``fraction``).

        Raises
        ------
        ValueError
            For another ``table``.

        Examples
        --------
        >>> from beltmdsm import Model, basins
        >>> b = basins(Model(Vb=3.88), points=3, x_lo=3.0, x_hi=7.0, y_lo=-8.5, y_hi=-4.5,
        ...            cache_dir=None)
        >>> starts = b.to_pandas()
        >>> list(starts), len(starts), starts["label"].tolist()[:3]
        (['X1', 'Y1', 'label', 'periods'], 9, [1, 1, 1])
        >>> b.to_pandas("attractors")[["kind", "periods"]].values.tolist()
        [['periodic', 1], ['periodic', 4]]
        """
        from .._tables import frame

        if table == "starts":
            xx, yy = np.meshgrid(self.xs, self.ys)
            rows = {self.x: xx.ravel(), self.y: yy.ravel(), "label": self.labels.ravel(),
                    "periods": self.periods.ravel()}  # fmt: skip
            return frame(rows, list(rows))
        if table == "attractors":
            columns = ["label", "kind", "periods", "rotation_number", "lyapunov",
                       "lyapunov_error", "fraction"]  # fmt: skip
            return frame([a.as_dict() for a in self.attractors], columns)
        raise ValueError(f"table must be 'starts' or 'attractors'; got {table!r}")

    def plot(self, ax: Any = None) -> Any:
        """The basin map: one colour per attractor, a legend with its kind and share, on
        matplotlib axes ``ax`` (new ones if None), which it returns
        (`beltmdsm.plotting.basins`)."""
        from ..plotting import basins as draw

        ax = draw(self, ax)
        ix, iy = AXES.index(self.x), AXES.index(self.y)
        for k, orbit in enumerate(self.boundaries):
            ax.plot(orbit[:, ix], orbit[:, iy], "k--", lw=1.2,
                    label="unstable cycle (basin boundary)" if k == 0 else None)  # fmt: skip
        if self.boundaries:
            ax.legend(loc="best", fontsize="small")
        return ax
