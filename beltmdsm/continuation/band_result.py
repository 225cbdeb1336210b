"""The result of `beltmdsm.continuation.band.floquet_band`: the band, its edges and grid.

`Band` holds the ranges of one parameter where the periodic response is unstable, its
labelled `Edge`s, the `BandPoint` of every evaluated value and the `BandFailure` of every
grid value without a response; `Band.as_dict` is the JSON of ``floquet-band --json``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, fields
from typing import Any

from .._tables import DataFrame
from ..model import Model
from ..periodic.engines import engine_of

__all__ = ["Edge", "BandPoint", "BandFailure", "Band"]


@dataclass(frozen=True)
class Edge:
    """A change of the periodic response at one parameter value.

    Attributes
    ----------
    value : float
    kind : str
        The bifurcation (`beltmdsm.continuation.edges.KINDS`), or ``unclassified`` for an
        end of the response located to the band's ``tol`` by bisection where no
        continuation could classify it (``detail`` says why).
    old_kind : str
        The kind `floquet_band` gave before (`beltmdsm.continuation.edges.OLD_KINDS`):
        ``multiplier``, ``grazing`` or ``existence``; for one release.
    bracket : tuple of float
        Values on either side that the edge lies between.
    accuracy : float
        A bound of the error of ``value``.
    frequency : float or None
        Of the critical pair at a Neimark-Sacker edge [rad/s].
    unstable_below, unstable_above : bool
        Whether no stable response is found just below and just above (a response
        that grazes, without multipliers, counts as neither).
    detail : str
        What vanishes at an end (the margin), or "".

    See Also
    --------
    beltmdsm.continuation.band_result.Band : the band that holds the edges.
    beltmdsm.continuation.edges.KINDS : the bifurcation kinds.

    Examples
    --------
    >>> from beltmdsm import Model, floquet_band
    >>> edge = floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=4).edges[0]
    >>> edge.kind, edge.old_kind, round(edge.value, 3), round(edge.frequency, 3)
    ('neimark_sacker', 'multiplier', 5.45, 1.052)
    >>> bool(edge.bracket[0] <= edge.value <= edge.bracket[1] and edge.accuracy < 1e-3)
    True
    """

    value: float
    kind: str
    old_kind: str
    bracket: tuple[float, float]
    accuracy: float
    frequency: float | None
    unstable_below: bool
    unstable_above: bool
    detail: str = ""

    def as_dict(self) -> dict:
        """For JSON: the attributes, ``bracket`` as a list."""
        return {
            "value": self.value,
            "kind": self.kind,
            "old_kind": self.old_kind,
            "bracket": list(self.bracket),
            "accuracy": self.accuracy,
            "frequency": self.frequency,
            "unstable_below": self.unstable_below,
            "unstable_above": self.unstable_above,
            "detail": self.detail,
        }


@dataclass(frozen=True)
class BandPoint:
    """The Floquet analysis at one evaluated value of a band.

    Attributes
    ----------
    value : float
    max_abs_multiplier : float
    stable : bool or None
        None where the response grazes.
    growth_rate : float
        ``log max |mu|`` over the orbit's period [1/s].
    n_reversals, n_sticks : int
        Per orbit.
    grazing : bool
        Whether the response grazes (no multiplier).
    state0 : tuple of float
        Its state at phase 0 (``X1, X1', X2, X2'``).

    See Also
    --------
    beltmdsm.continuation.band_result.Band : its ``grid`` holds one per evaluated value.

    Examples
    --------
    >>> from beltmdsm import Model, floquet_band
    >>> first = floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=4).grid[0]
    >>> first.value, first.stable, first.n_reversals, first.n_sticks
    (5.2, True, 2, 0)
    >>> round(first.max_abs_multiplier, 3)
    0.916
    """

    value: float
    max_abs_multiplier: float
    stable: bool | None
    growth_rate: float
    n_reversals: int
    n_sticks: int
    grazing: bool
    state0: tuple[float, ...]

    def as_dict(self) -> dict:
        """For JSON: the attributes, ``state0`` as a list."""
        return {**dataclasses.asdict(self), "state0": list(self.state0)}


@dataclass(frozen=True)
class BandFailure:
    """A grid value where no periodic response is found, and why.

    Attributes
    ----------
    value : float
    reason : str
        The message of `beltmdsm.errors.NoPeriodicResponse`.

    See Also
    --------
    beltmdsm.continuation.band_result.Band : its ``failed`` holds them.

    Examples
    --------
    >>> from beltmdsm.continuation.band_result import BandFailure
    >>> BandFailure(3.0, "Newton's method diverges").as_dict()
    {'value': 3.0, 'reason': "Newton's method diverges"}
    """

    value: float
    reason: str

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``reason``."""
        return dataclasses.asdict(self)


@dataclass(kw_only=True)
class Band:
    """The ranges of one parameter where the periodic response is unstable (`floquet_band`).

    Attributes
    ----------
    param : str
    model : Model
        The other parameters and the options.
    periods : int
        ``k``: the band of the response of ``k`` excitation periods.
    unstable : list of [lo, hi]
        Where no stable periodic response is found (unstable, or none found: the
        `no_periodic_response` ranges are included). A response that grazes has no
        multipliers: it is an edge (``grazing``), not a range.
    edges : list of Edge
        In order of value.
    grazing_points : list of float
    no_periodic_response : list of [lo, hi]
        Where no periodic response is found (from the continued neighbours by Newton's
        method, or, next to a stable one, by iterating the period map, and the
        continuation across an interval).
    grid : list of BandPoint
        Every evaluated value, in order.
    failed : list of BandFailure
        The grid values where no periodic response was found, with the reason.
    tol : float
        The edges' tolerance: edges closer than it are one (`floquet_band`).
    merged_away : list of [lo, hi]
        The merged brackets of edges closer than ``tol`` inside which a value without a
        stable response (without any) was evaluated that no range of `unstable` (of
        `no_periodic_response`) holds: a range narrower than ``tol`` that the merging
        removes.

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : computes it.
    beltmdsm.continuation.branch.Branch : one response continued.

    Examples
    --------
    >>> from beltmdsm import Model, floquet_band
    >>> band = floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=4)
    >>> band  # doctest: +ELLIPSIS
    Band('Vb', T-periodic response, Model(beta1=0.3); ... values): unstable in [5.4..., 5.8]
      NS at Vb = 5.4... (+- ...e-04, 1.052 rad/s; unstable above)
    >>> band.to_pandas("grid")["stable"].iloc[[0, -1]].tolist()  # at 5.2 and 5.8
    [True, False]
    >>> sorted(band.as_dict())[:4]
    ['contact', 'edges', 'engine', 'failed']
    """

    param: str
    model: Model
    periods: int
    unstable: list[list[float]]
    edges: list[Edge]
    grazing_points: list[float]
    no_periodic_response: list[list[float]]
    grid: list[BandPoint]
    failed: list[BandFailure]
    tol: float
    merged_away: list[list[float]] = field(default_factory=list)

    def plot(self, ax: Any = None) -> Any:
        """The largest multiplier against the parameter, the unstable ranges shaded,
        the edges labelled, on matplotlib axes ``ax`` (new ones if None), which it
        returns (`beltmdsm.plotting.band`; matplotlib is imported here)."""
        from ..plotting import band as draw

        return draw(self, ax)

    def to_pandas(self, table: str = "edges") -> DataFrame:
        """A `pandas.DataFrame` (needs pandas, imported here) of the ``"edges"`` (one row
        per `Edge`, its attributes) or of the ``"grid"`` (one row per `BandPoint`).

        Raises
        ------
        ValueError
            For another ``table``.
        """
        from .._tables import frame

        if table == "edges":
            return frame([e.as_dict() for e in self.edges], [f.name for f in fields(Edge)])
        if table == "grid":
            return frame([g.as_dict() for g in self.grid], [f.name for f in fields(BandPoint)])
        raise ValueError(f"table must be 'edges' or 'grid'; got {table!r}")

    def __repr__(self) -> str:
        from .._display import block, intervals, label, laws

        what = "T" if self.periods == 1 else f"{self.periods}T"
        sides = {
            (False, True): "unstable above",
            (True, False): "unstable below",
            (False, False): "stable on both sides",
            (True, True): "unstable on both sides",
        }
        lines = [
            f"{label(e.kind)} at {self.param} = {e.value:.6g} (+- {e.accuracy:.0e}"
            + (f", {e.frequency:.4g} rad/s" if e.frequency is not None else "")
            + f"; {sides[e.unstable_below, e.unstable_above]})"
            for e in self.edges
        ]
        if self.no_periodic_response:
            lines.append(f"no periodic response in {intervals(self.no_periodic_response)}")
        lines += [f"failed at {f.value:g}: {f.reason}" for f in self.failed]
        return block(
            f"Band({self.param!r}, {what}-periodic response, {self.model!r}; "
            f"{laws(self.model)}; {len(self.grid)} values): unstable in "
            f"{intervals(self.unstable)}",
            lines,
        )

    def as_dict(self) -> dict:
        """The JSON of ``floquet-band --json``: ``param``, ``unstable``, ``edges``,
        ``grazing_points``, ``no_periodic_response``, ``grid``, ``failed``, ``tol``,
        ``merged_away``, ``tension``, ``contact``, ``friction`` and ``engine`` (the
        period map of the model's laws, `beltmdsm.periodic.engines.engine_of`)."""
        return {**self._band_dict(), **self._model_dict()}

    def _band_dict(self) -> dict:
        """The band's own part of `as_dict`, whatever the model."""
        return {
            "param": self.param,
            "unstable": [list(r) for r in self.unstable],
            "edges": [e.as_dict() for e in self.edges],
            "grazing_points": list(self.grazing_points),
            "no_periodic_response": [list(r) for r in self.no_periodic_response],
            "grid": [g.as_dict() for g in self.grid],
            "failed": [f.as_dict() for f in self.failed],
            "tol": self.tol,
            "merged_away": [list(r) for r in self.merged_away],
        }

    def _model_dict(self) -> dict:
        """The paper model's part of `as_dict`: its laws and period map."""
        return {
            "tension": self.model.tension,
            "contact": self.model.contact,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
        }
