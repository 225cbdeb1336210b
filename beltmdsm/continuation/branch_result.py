"""The results of a branch: its special points, its stable and unstable parts, the branch.

Shared by the branches of forced responses (`beltmdsm.continuation.branch`) and of
self-excited cycles (`beltmdsm.cycles.branch`).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from .._tables import STATE_COLUMNS, DataFrame
from ..errors import Refused
from ..model import Model
from ..periodic.engines import engine_of
from ..periodic.observables import OBSERVABLES

__all__ = ["LOCATE_TOL", "SpecialPoint", "BranchPart", "Branch", "Hopf", "record_points"]

#: Special points are located to this in the parameter.
LOCATE_TOL = 1e-6


@dataclass
class SpecialPoint:
    """A bifurcation or an end of a branch.

    Attributes
    ----------
    kind : str
        One of `beltmdsm.continuation.edges.KINDS`, ``branch_point`` (a real multiplier through +1
        without a turn), ``range`` (the end of the requested range) or ``failed`` (the
        continuation stops for another reason, in ``detail``).
    value : float
    accuracy : float
        A bound of the error of ``value``.
    frequency : float or None
        Of the critical pair at a Neimark-Sacker point [rad/s].
    multipliers : ndarray
        At the located point (at an end: at the last response solved).
    stable_before, stable_after : bool or None
        Whether the branch is stable just before and after, along the continuation.
    detail : str

    See Also
    --------
    beltmdsm.continuation.branch_result.Branch : its ``special`` holds them, in arclength order.
    beltmdsm.continuation.special.special_between : locates folds and crossings.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6)
    >>> ns = b.special[1]
    >>> ns.kind, round(ns.value, 3), round(ns.frequency, 3), ns.stable_before, ns.stable_after
    ('neimark_sacker', 5.45, 1.052, True, False)
    >>> bool(ns.accuracy <= 1e-6)
    True
    """

    kind: str
    value: float
    accuracy: float
    frequency: float | None
    multipliers: NDArray[np.complex128]
    stable_before: bool | None
    stable_after: bool | None
    detail: str = ""

    def as_dict(self) -> dict:
        """For JSON: the attributes (``multipliers`` as pairs of real and imaginary parts)."""
        return {
            "kind": self.kind,
            "value": self.value,
            "accuracy": self.accuracy,
            "frequency": self.frequency,
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "stable_before": self.stable_before,
            "stable_after": self.stable_after,
            "detail": self.detail,
        }


@dataclass(frozen=True)
class BranchPart:
    """A stretch of a branch between two special points, stable or not.

    Attributes
    ----------
    range : tuple of float
        ``(lo, hi)``: the parameter values it covers.
    stable : bool or None
        None where the orbit grazes.
    start, end : str
        The kinds of the special points that bound it, in arclength order
        (``from`` and ``to`` in `as_dict`).
    lower, upper : str
        The kinds of those at its lower and upper value.

    See Also
    --------
    beltmdsm.continuation.branch_result.Branch.parts : the parts of a branch.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6)
    >>> [(p.start, p.end, p.stable) for p in b.parts()]
    [('range', 'neimark_sacker', True), ('neimark_sacker', 'range', False)]
    """

    range: tuple[float, float]
    stable: bool | None
    start: str
    end: str
    lower: str
    upper: str

    def as_dict(self) -> dict:
        """For JSON: ``range``, ``stable``, ``from``, ``to``, ``lower``, ``upper``."""
        return {
            "range": list(self.range),
            "stable": self.stable,
            "from": self.start,
            "to": self.end,
            "lower": self.lower,
            "upper": self.upper,
        }


class Hopf(Protocol):
    """What a type checker knows of a branch's Hopf point (`beltmdsm.cycles.hopf.HopfPoint`,
    a layer above this one)."""

    @property
    def param(self) -> str: ...
    @property
    def value(self) -> float: ...
    @property
    def accuracy(self) -> float: ...
    @property
    def frequency(self) -> float: ...
    @property
    def transversality(self) -> float: ...


@dataclass
class Branch:
    """A branch of one continuation problem in one parameter: forced responses of
    ``periods`` excitation periods, self-excited cycles, or steady sliding (``kind``).

    Attributes
    ----------
    param : str
    periods : int
    model : Model
        The other parameters and the options (``param`` at the start's value).
    points : list of BranchPoint (`beltmdsm.continuation.forced`) or CyclePoint
        In arclength order, from the start's lower end.
    special : list of SpecialPoint
        In arclength order; the first and the last are the ends.
    hopf : Hopf or None
        Where a branch of self-excited cycles is born; None for forced responses.
    criticality : str or None
        A branch of cycles from a Hopf point: ``"supercritical"`` or ``"subcritical"``
        (which side of it the cycles exist on).
    wall_s : float
        The time the continuation took [s] (a branch of cycles; 0 otherwise).
    kind : str
        The problem continued (`beltmdsm.continuation.problem.Problem.kind`):
        ``"forced"``, ``"cycle"`` (self-excited cycles: what ``CycleBranch`` was
        before issue 38) or ``"equilibrium"``.

    See Also
    --------
    beltmdsm.continuation.branch.branch : computes it.
    beltmdsm.continuation.band_result.Band : the unstable ranges of a grid.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6)
    >>> b  # doctest: +ELLIPSIS
    Branch('Vb', T-periodic response, Model(beta1=0.3, Vb=5.3); ...): stable in [5.3, 5.4499...]
      range at Vb = 5.3 (+- 0e+00): the end of the requested range
      NS at Vb = 5.4499... (+- ...), 1.052 rad/s: a complex pair crosses the unit circle at ...
      range at Vb = 5.6 (+- 0e+00): the end of the requested range
    >>> b.value_range()
    [5.3, 5.6]
    >>> b.to_pandas("special")["label"].tolist()
    ['range', 'NS', 'range']
    >>> table = b.observables()
    >>> bool(table["X1'_amplitude"][0] > 0 and len(table["Vb"]) == len(b.points))
    True
    """

    param: str
    periods: int
    model: Model
    points: list[Any]
    special: list[SpecialPoint]
    #: Where a branch of self-excited cycles is born (`beltmdsm.cycles.hopf.HopfPoint`);
    #: None for a branch of forced responses.
    hopf: Hopf | None = None
    criticality: str | None = None
    wall_s: float = 0.0
    kind: str = "forced"

    @property
    def response(self) -> str:
        """What the branch continues, in words (figure titles): ``"the 4T response"``."""
        if self.kind != "forced":
            return "self-excited cycles" if self.kind == "cycle" else "steady sliding"
        return "the T response" if self.periods == 1 else f"the {self.periods}T response"

    @property
    def ends(self) -> tuple[SpecialPoint, SpecialPoint]:
        """The first and the last special point: where the branch ends both ways."""
        return self.special[0], self.special[-1]

    def parts(self) -> list[BranchPart]:
        """The stable and unstable parts, in arclength order."""
        out = []
        bounds = self.special
        for a, b in zip(bounds[:-1], bounds[1:]):
            stable = a.stable_after if a.stable_after is not None else b.stable_before
            low, high = (a, b) if a.value <= b.value else (b, a)
            out.append(
                BranchPart((low.value, high.value), stable, a.kind, b.kind, low.kind, high.kind)
            )
        return out

    def stable_ranges(self) -> list[list[float]]:
        """The parameter ranges where the branch is stable (merged where they touch)."""
        ranges = sorted(list(p.range) for p in self.parts() if p.stable)
        merged = []
        for lo, hi in ranges:
            if merged and lo <= merged[-1][1]:
                merged[-1][1] = max(merged[-1][1], hi)
            else:
                merged.append([lo, hi])
        return merged

    def value_range(self) -> list[float]:
        """The smallest and largest parameter value the branch reaches."""
        values = [p.value for p in self.points] + [s.value for s in self.special]
        return [min(values), max(values)]

    def point_near(self, value: float) -> Any | None:
        """The point of the branch nearest to ``value`` (None on an empty branch)."""
        if not self.points:
            return None
        return min(self.points, key=lambda p: abs(p.value - value))

    def observables(
        self, record: Callable[[Any], float | Mapping[str, float]] | None = None
    ) -> dict[str, NDArray[np.float64]]:
        """What each point's orbit measures, in arclength order: ``param``'s value, then
        the `beltmdsm.periodic.observables.OBSERVABLES` (ranges of X1' and X1, the
        largest |Vr|, the mean friction and ``mu_eff = <Ff>/<Fn>``), read from the
        runs the point keeps (nothing is solved again; a branch of cycles gives the
        ranges, the largest |Vr| and the ``period``), then what the ``record`` of
        `beltmdsm.continuation.branch.branch` stored at each point.

        ``record(point)`` adds columns of its own afterwards, as the ``record`` of
        `beltmdsm.continuation.branch.branch` does (`record_points`).

        Raises
        ------
        beltmdsm.errors.Refused
            Where ``record`` raises or returns anything but a real number or a mapping
            of names to real numbers (`record_points`).
        """
        vb = [p.value if self.param == "Vb" else self.model["Vb"] for p in self.points]
        rows = [p.observables(v) for p, v in zip(self.points, vb)]
        out = {self.param: np.array([p.value for p in self.points], dtype=float)}
        columns = rows[0] if rows else dict.fromkeys(OBSERVABLES)
        out.update({k: np.array([r[k] for r in rows], dtype=float) for k in columns})
        for key in self.points[0].recorded if self.points else ():
            out[key] = np.array([p.recorded[key] for p in self.points], dtype=float)
        if record is not None and self.points:
            rows = _recorded_rows(record, self.points, self.param)
            out.update({k: np.array([r[k] for r in rows], dtype=float) for k in rows[0]})
        return out

    def plot(self, ax: Any = None, observable: str | None = None, labels: bool = True) -> Any:
        """The bifurcation diagram: ``observable`` (one of `observables`' columns; default
        the amplitude of the model's first rate, ``X1'_amplitude``) against ``param``,
        stable solid, unstable dashed, grazing dotted, the special points marked (NS, PD,
        LP, GR, BP, HB); on matplotlib axes ``ax`` (new ones if None), which it returns
        (`beltmdsm.plotting.branch`)."""
        from ..plotting import branch as draw

        return draw(self, ax, observable, labels)

    def _state_names(self) -> list[str]:
        """The columns of the points' states: the paper's (another model's branch names
        its own, `beltmdsm.continuation.oscillator_branch.OscillatorBranch`)."""
        return list(STATE_COLUMNS[: len(self.points[0].state) if self.points else None])

    def to_pandas(self, table: str = "points") -> DataFrame:
        """A `pandas.DataFrame` (needs pandas, imported here) of the ``"points"`` (one row
        per `BranchPoint`: ``param``'s value, the shooting state at phase 0,
        ``max_abs_multiplier``, ``stable``, ``n_reversals``, ``n_sticks``, then the
        `observables`) or of the ``"special"`` points (their attributes, ``label`` the
        short name of the kind).

        Raises
        ------
        ValueError
            For another ``table``.
        """
        from .._display import label
        from .._tables import frame

        if table == "points":
            names = self._state_names()
            rows = [
                {
                    self.param: p.value,
                    **dict(zip(names, map(float, p.state))),
                    "max_abs_multiplier": p.max_abs_multiplier,
                    "stable": p.stable,
                    "n_reversals": p.n_reversals,
                    "n_sticks": p.n_sticks,
                }
                for p in self.points
            ]
            tail = ["max_abs_multiplier", "stable", "n_reversals", "n_sticks"]
            table_ = frame(rows, [self.param, *names, *tail])
            for key, column in list(self.observables().items())[1:]:
                table_[key] = column
            return table_
        if table == "special":
            rows = [{**s.as_dict(), "label": label(s.kind)} for s in self.special]
            columns = ["kind", "label", "value", "accuracy", "frequency", "multipliers",
                       "stable_before", "stable_after", "detail"]  # fmt: skip
            return frame(rows, columns)
        raise ValueError(f"table must be 'points' or 'special'; got {table!r}")

    def __repr__(self) -> str:
        from .._display import block, intervals, label, laws

        if self.kind == "cycle":
            a, b = self.ends
            crit = f", {self.criticality}" if self.criticality else ""
            return (
                f"CycleBranch({self.param}: {a.kind} {a.value:.6g}{crit} -> {b.kind} "
                f"{b.value:.6g}, {len(self.points)} points, "
                f"{len(self.special) - 2} special points inside)"
            )

        lo, hi = self.value_range() if self.points else (math.nan, math.nan)
        what = "T" if self.periods == 1 else f"{self.periods}T"
        lines = [
            f"{label(s.kind)} at {self.param} = {s.value:.6g} (+- {s.accuracy:.0e})"
            + (f", {s.frequency:.4g} rad/s" if s.frequency is not None else "")
            + (f": {s.detail}" if s.detail else "")
            for s in self.special
        ]
        return block(
            f"Branch({self.param!r}, {what}-periodic response, {self.model!r}; "
            f"{laws(self.model)}; {len(self.points)} points, {self.param} from {lo:.6g} "
            f"to {hi:.6g}): stable in {intervals(self.stable_ranges())}",
            lines,
        )

    def as_dict(self) -> dict:
        """For JSON: ``param``, ``periods``, ``contact``, ``tension``, ``friction``,
        ``engine``, ``range``, ``parts``, ``stable_ranges``, ``special_points``,
        ``points``; a branch of cycles adds ``autonomous: true``, ``hopf``,
        ``criticality``, ``wall_s``."""
        out = {
            "param": self.param,
            "periods": self.periods,
            "contact": self.model.contact,
            "tension": self.model.tension,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
            "range": self.value_range(),
            "parts": [p.as_dict() for p in self.parts()],
            "stable_ranges": self.stable_ranges(),
            "special_points": [s.as_dict() for s in self.special],
            "points": [p.as_dict() for p in self.points],
        }
        if self.kind == "cycle":
            out["autonomous"] = True
            out["hopf"] = None if self.hopf is None else self.hopf.as_dict()
            out["criticality"] = self.criticality
            out["wall_s"] = self.wall_s
        return out


#: Columns of `Branch.to_pandas` that a recorded name may not take: the paper model's
#: state columns, the point's verdicts and the observables.
_RESERVED = frozenset(
    [*STATE_COLUMNS, "max_abs_multiplier", "stable", "n_reversals", "n_sticks"]
    + [*OBSERVABLES, "period"]
)


def _recorded_rows(record: Callable[[Any], Any], points: list[Any], param: str) -> list:
    """``record(point)`` at each of ``points``, checked: a list of dicts of one set of names."""
    if not callable(record):
        raise Refused(f"record must be a callable of a branch point; got {record!r}", "record")
    rows = []
    for p in points:
        where = f"{param} = {p.value:.6g}"
        try:
            got = record(p)
        except Exception as err:  # the user's code: refused, its error chained
            raise Refused(
                f"record raised {type(err).__name__} at {where}: {err}", "record"
            ) from err
        row = dict(got) if isinstance(got, Mapping) else {"record": got}
        bad = [
            k
            for k, v in row.items()
            if not isinstance(k, str) or isinstance(v, bool) or not isinstance(v, numbers.Real)
        ]
        if bad or not row:
            raise Refused(
                "record must return a real number or a mapping of names (str) to real "
                f"numbers; at {where} it returned {got!r}",
                "record",
            )
        taken = sorted(_RESERVED.intersection(row) | ({param} & row.keys()))
        if taken:
            raise Refused(
                f"record's names {taken} are the branch's own columns; choose others",
                "record",
            )
        if rows and row.keys() != rows[0].keys():
            raise Refused(
                f"record must return the same names at every point; at {where} "
                f"{sorted(row)}, at the first {sorted(rows[0])}",
                "record",
            )
        rows.append({k: float(v) for k, v in row.items()})
    return rows


def record_points(branch: Branch, record: Callable[[Any], Any] | None) -> Branch:
    """Store ``record(point)`` on each point of ``branch`` (``point.recorded``); returns it.

    As BifurcationKit's ``record_from_solution``: ``record`` takes a point of the branch
    (a `beltmdsm.continuation.forced.BranchPoint`: ``value``, ``state``, ``image``
    with the orbit's runs, ``multipliers``; a cycle's
    `beltmdsm.cycles.continuation.CyclePoint`: also ``period``) and returns a real number
    (the column ``"record"``) or a mapping of names to real numbers, the same names at
    every point. They are columns of `Branch.observables` and `Branch.to_pandas`.

    Parameters
    ----------
    branch : Branch
    record : callable or None
        None: nothing is recorded.

    Returns
    -------
    Branch
        ``branch`` itself, its points' ``recorded`` filled.

    Raises
    ------
    beltmdsm.errors.Refused
        Naming ``record``: not callable; it raises; it returns anything else, no name,
        a name of the branch's own columns or other names at another point.

    See Also
    --------
    beltmdsm.continuation.branch.branch : takes ``record`` and calls this.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6)
    >>> from beltmdsm.continuation.branch_result import record_points
    >>> _ = record_points(b, lambda p: {"twice": 2 * p.value})
    >>> b.points[0].recorded
    {'twice': 10.6}
    >>> record_points(b, lambda p: "a word")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    beltmdsm.errors.Refused: record must return a real number or a mapping ...
    """
    if record is None:
        return branch
    for p, row in zip(branch.points, _recorded_rows(record, branch.points, branch.param)):
        p.recorded = row
    return branch
