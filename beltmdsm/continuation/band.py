"""The ranges of one parameter where the periodic response is unstable, every edge labelled.

`floquet_band` walks a grid of the parameter with the Floquet analysis of
`beltmdsm.periodic.floquet`, each periodic response continued from its neighbour, and
locates every change between neighbours: a multiplier crossing the unit circle by the
secant of ``log|mu|``, a change of switch structure by bisection, and an end of the
response (found on one side only) by continuing it across the interval
(`beltmdsm.continuation.branch`) to where its closing margin vanishes
(`beltmdsm.continuation.edges.locate_end`). Each edge carries its bifurcation
(`beltmdsm.continuation.edges.KINDS`, docs/modelling.md#bifurcations) and, for one
release, the kind of before (``old_kind``). In ``Vb`` the band is the exact
counterpart of the unstable belt speeds of the paper's linear analysis (Sects. 4.2-4.3,
Fig. 5) and of the ranges Figs. 17-21 validate.

The result is a `Band`; its `Band.as_dict` is the JSON of ``floquet-band --json``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from .._calling import ranged
from .._tables import DataFrame
from ..errors import NoPeriodicResponse, Refused
from ..model import MODEL_PARAMETERS, Backend, Model, as_model, check_domain, excitation_period
from ..periodic.engines import engine_of
from ..periodic.family import MapFamily
from ..periodic.floquet import Floquet, floquet
from ..periodic.margins import MARGIN_KINDS
from ..periodic.newton import FixedPoint, fixed_point
from ..periodic.response import response_from
from ..periodic.shooting import FORWARD_PERIODS
from ..periodic.tangential import largest_sliding_velocity
from ..settings import MAX_BAND_POINTS, MIN_TOL_ULPS
from .branch import SpecialPoint, continue_branch
from .edges import (
    KINDS,
    OLD_KINDS,
    End,
    NoEdge,
    closing_margins,
    locate_end,
    log_max_multiplier,
    multiplier_kind,
)

__all__ = ["Edge", "BandPoint", "BandFailure", "Band", "floquet_band"]

#: An end (tangency, grazing) inside an interval is located to the band's ``tol`` or to
#: this, whichever is smaller (the margin's secant converges fast: 1e-4 asked takes
#: less than half the period maps of 1e-7, 35 against 81 at the base set, and gives
#: about 1e-6).
_END_TOL = 1e-4
#: Natural continuation towards an end stops at steps below this share of its way.
_NATURAL_SMALLEST = 1e-3


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

    ``grazing``: whether the response grazes (no multiplier); ``state0`` its state at
    phase 0 (``X1, X1', X2, X2'``).
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
    """A grid value where no periodic response is found, and why."""

    value: float
    reason: str

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``reason``."""
        return dataclasses.asdict(self)


@dataclass
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
        per `Edge`, its attributes) or of the ``"grid"`` (one row per `BandPoint`)."""
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
            "tension": self.model.tension,
            "contact": self.model.contact,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
        }


@ranged
def floquet_band(
    param: str,
    lo: float,
    hi: float,
    model: Model | Mapping[str, Any] | None = None,
    *,
    points: int = 17,
    tol: float = 1e-3,
    backend: Backend | None = None,
    periods: int = 1,
    progress: bool = False,
    **kw: Any,
) -> Band:
    """Ranges of ``param`` in ``[lo, hi]`` where the periodic response is unstable.

    A grid of ``points`` values is walked from ``hi`` down to ``lo``, each periodic
    response continued from the previous one. Between neighbours whose state differs
    (found or not, the switch structure: reversals and sticks per period, the
    verdict) the interval is refined, each new value continued from a neighbour,
    until it is below ``tol``: every change is located to ``tol``, and several
    changes between two grid points are all found. Where a response is found on one
    side only, it is continued across the interval instead (natural continuation,
    else the pseudo-arclength continuation of `beltmdsm.continuation.branch`): it either
    reaches the other side (where Newton's method had missed it) or ends at a
    tangency, a grazing or a fold, located exactly (to about 1e-6; `Edge.accuracy`).
    For ``param = "Vb"`` the grazing point of the backward-sliding response is
    computed exactly: it is that response's largest velocity in contact, which does
    not depend on ``Vb`` (`beltmdsm.periodic.tangential.largest_sliding_velocity`).

    Changes closer together than ``tol`` cannot be told apart at that tolerance: they
    are one edge, whose sides are the outer sides of the first and the last, and the
    values evaluated between them do not enter the ranges. So the edges' sides agree
    with the ranges at every ``tol``, and a finer ``tol`` only resolves more.

    Parameters
    ----------
    param : str
        A model parameter.
    lo, hi : float
        The range, inside the parameter's domain.
    model : Model or dict, optional
        The other parameters and the options (default: the base set); ``**kw`` too.
    points : int
        Grid values walked before the refinement, 2 to
        `beltmdsm.settings.MAX_BAND_POINTS`.
    tol : float
        The edges' tolerance, at least `beltmdsm.settings.MIN_TOL_ULPS` ulps of the
        larger end of the range (a bracket cannot be split finer than its rounding)
        and at most the grid's step ``(hi - lo) / (points - 1)`` (a larger one only
        merges what the grid resolves). A range without a stable response narrower
        than ``tol`` merges away: `Band.merged_away` says where.
    backend : {"python", "numba", None}
    periods : int
        ``k > 1``: the band of the response of ``k`` periods (a value without a
        neighbour is seeded from the attractor of the period map,
        `beltmdsm.periodic.shooting.periodic_response`).
    progress : bool
        Show the evaluations on stderr (tqdm) once they take more than 2 s.

    Returns
    -------
    Band

    Raises
    ------
    ValueError
        For an unknown parameter, a range that is not finite, empty or outside the
        parameter's domain, ``points < 2`` or ``tol <= 0``.
    beltmdsm.errors.Refused
        For ``points`` above `beltmdsm.settings.MAX_BAND_POINTS`, ``tol`` above the
        grid's step or below the rounding of the range
        (`beltmdsm.settings.MIN_TOL_ULPS`).
    """
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    for end in (lo, hi):
        problem = check_domain(param, end)
        if problem:
            raise ValueError(f"the range [{lo:g}, {hi:g}] leaves the domain: {param} {problem}")
    model = as_model(model, **kw)
    excitation_period(model)  # a band of the forced response (not of self-excited cycles)
    if int(points) < 2 or not tol > 0:
        raise ValueError(f"points must be >= 2 and tol > 0; got {points}, {tol}")
    _check_band_request(lo, hi, int(points), tol)
    from tqdm import tqdm

    bar = tqdm(
        desc=f"floquet-band {param}", unit=" values", disable=not progress, delay=2, leave=False
    )
    failed, seen = [], {}

    def evaluate(v, neighbours, record=False):
        """The Floquet analysis at ``v``, continued from the nearest neighbour found."""
        near = [f for f in neighbours if f is not None]
        guess = near[0].response if near else None
        # forward iteration finds only a stable response: tried next to a stable one
        forward = FORWARD_PERIODS if not near or near[0].stable is not False else 0
        try:
            f = floquet(
                model.replace(**{param: float(v)}),
                guess=guess,
                forward=forward,
                backend=backend,
                periods=periods,
            )
        except NoPeriodicResponse as err:
            if record:
                failed.append(BandFailure(float(v), str(err)))
            f = None
        seen[float(v)] = f
        bar.update()
        return f

    grid, last = [], None
    for v in np.linspace(hi, lo, int(points)):
        f = evaluate(v, [last], record=True)
        last = f if f is not None else last
        grid.append((float(v), f))
    grid.sort(key=lambda r: r[0])
    edges, grazing_points = [], []

    def refine(a, fa, b, fb):
        """Locate the changes between ``a`` and ``b``; ``b``'s evaluation (a miss repaired)."""
        if _state(fa) == _state(fb):
            return fb
        g = _sliding_grazing(param, fa, fb)
        if g is not None and a + tol / 4 < g < b - tol / 4:
            below = evaluate(g - tol / 4, [fa, fb])
            above = evaluate(g + tol / 4, [fb, fa])
            grazing_points.append(g)
            below = refine(a, fa, g - tol / 4, below)
            # the grazing point of the sliding response is exact (its largest velocity)
            edges.append(
                _edge(g - tol / 4, below, g + tol / 4, above, kind="grazing", accuracy=1e-12)
            )
            return refine(g + tol / 4, above, b, fb)
        if (fa is None) != (fb is None):
            end = _band_existence(param, a, fa, b, fb, backend, tol)
            edges.extend(end.edges)
            for v, f in end.solved:
                seen.setdefault(v, f)
            if end.stalled:
                return bisect_stall(a, fa, b, fb, end)
            if end.reached is None:
                return fb
            seen[b if fb is None else a] = end.reached
            if fb is None:
                return refine(a, fa, b, end.reached)
            return refine(a, end.reached, b, fb)
        if b - a <= tol:
            edges.append(_edge(a, fa, b, fb))
            return fb
        m = _multiplier_step(a, fa, b, fb, tol) if _same_structure(fa, fb) else None
        m = 0.5 * (a + b) if m is None else m
        fm = evaluate(m, [fa, fb] if abs(m - a) <= abs(b - m) else [fb, fa])
        fm = refine(a, fa, m, fm)
        return refine(m, fm, b, fb)

    def bisect_stall(a, fa, b, fb, end):
        """The continuation across ``[a, b]`` stopped without locating an end: bisect.

        It is split at the farthest response the continuation solved (its stop), else
        at the middle, each part refined again; where the part with the response's end
        is below ``tol`` and the end is still not classified, the edge says so
        (``unclassified``, its bracket that part). The grid never takes the stop for
        the response's end (it called one at 0.5768 with accuracy 0 where the response
        goes on to 0.2395, `floquet-band --param Vb --from 0 --to 40 --omega1 12`).
        """
        if b - a <= tol:
            edges.append(_unclassified_edge(a, fa, b, fb, end.stalled))
            return fb
        found = b if fa is None else a
        inside = [v for v, f in end.solved if f is not None and a < v < b and v != found]
        m = (min(inside) if fa is None else max(inside)) if inside else 0.5 * (a + b)
        fm = seen.get(m) if inside else None
        if fm is None:
            fm = evaluate(m, [fa, fb] if abs(m - a) <= abs(b - m) else [fb, fa])
        fm = refine(a, fa, m, fm)
        return refine(m, fm, b, fb)

    try:
        for i in range(len(grid) - 1):
            (a, fa), (b, fb) = grid[i], grid[i + 1]
            grid[i + 1] = (b, refine(a, fa, b, fb))
    finally:
        bar.close()
    edges, hidden = _merge_close(sorted(edges, key=lambda e: e.value), tol)

    grazing_points += [
        e.value for e in edges if e.kind == "grazing" and e.value not in grazing_points
    ]
    points_seen = sorted((v, f) for v, f in seen.items() if not any(a < v < b for a, b in hidden))
    # a response that grazes (no multipliers) is neither: it ends no range and starts
    # none (its grazing is an edge); only where none is found or it is unstable
    decided = [(v, f) for v, f in points_seen if f is None or f.stable is not None]
    unstable = _runs(decided, edges, lambda f: f is None or f.stable is False, lo, hi)
    gaps = _runs(points_seen, edges, lambda f: f is None, lo, hi)

    # what the merging removes: a value inside a merged bracket without a stable
    # response (without any) that no unstable range (no range without one) holds
    def held(v, ranges):
        return any(r[0] <= v <= r[1] for r in ranges)

    merged_away = [
        [a, b]
        for a, b in hidden
        if any(
            a < v < b
            and (
                (f is None and not held(v, gaps))
                or ((f is None or f.stable is False) and not held(v, unstable))
            )
            for v, f in seen.items()
        )
    ]
    table = [
        BandPoint(
            v,
            f.max_abs_multiplier,
            f.stable,
            f.growth_rate,
            f.n_reversals,
            f.n_sticks,
            f.grazing is not None,
            tuple(float(x) for x in f.response.state0),
        )
        for v, f in points_seen
        if f is not None
    ]
    return Band(
        param,
        model,
        int(periods),
        unstable,
        edges,
        sorted(grazing_points),
        gaps,
        table,
        failed,
        float(tol),
        merged_away,
    )


def _check_band_request(lo, hi, points, tol):
    """Refuse a grid above `MAX_BAND_POINTS`, or a ``tol`` above the grid's step or below
    the range's rounding."""
    if points > MAX_BAND_POINTS:
        raise Refused(
            f"points = {points} is more than MAX_BAND_POINTS = {MAX_BAND_POINTS:.0e} "
            "(beltmdsm/settings.py): about 2 ms a point, and every edge is refined to tol "
            "anyway",
            "points",
        )
    step = (hi - lo) / (points - 1)
    if tol > step:
        raise Refused(
            f"tol = {tol:g} is above the grid's step (hi - lo) / (points - 1) = {step:.4g} "
            f"of [{lo:g}, {hi:g}] with {points} points: every change between grid points "
            "is located to tol and edges closer than tol are one, so a tol above the step "
            "only merges what the grid resolves (a whole band can vanish); choose tol <= "
            f"{step:.4g}, or more points",
            "tol",
        )
    finest = MIN_TOL_ULPS * float(np.spacing(max(abs(lo), abs(hi))))
    if tol < finest:
        raise Refused(
            f"tol = {tol:g} is below what the rounding of the range [{lo:g}, {hi:g}] can "
            f"resolve: at least {MIN_TOL_ULPS} ulps of {max(abs(lo), abs(hi)):g}, "
            f"{finest:.2g} (MIN_TOL_ULPS in beltmdsm/settings.py)",
            "tol",
        )


#: Which edge of a group closer than the tolerance names the group: an exact grazing
#: point, then an end of the response, then a multiplier crossing.
_MERGE_ORDER = (
    "grazing",
    "tangency",
    "fold",
    "existence",
    "unclassified",
    "period_doubling",
    "neimark_sacker",
)


def _merge_close(edges, tol):
    """Edges closer than ``tol`` to the first of their group, merged into one.

    At that tolerance they cannot be told apart. The merged edge takes the outer
    sides (below from the first, above from the last), the union of the brackets and
    the value, kind and frequency of the first of the group in `_MERGE_ORDER`; its
    accuracy covers the union.

    Returns
    -------
    edges : list of Edge
    hidden : list of (lo, hi)
        The merged brackets: the values evaluated strictly inside do not enter the
        ranges (their changes are below the resolution).
    """
    groups = []
    for e in edges:
        if groups and e.value - groups[-1][0].value <= tol:
            groups[-1].append(e)
        else:
            groups.append([e])
    out, hidden = [], []
    for group in groups:
        if len(group) == 1:
            out.append(group[0])
            continue
        lead = min(group, key=lambda e: _MERGE_ORDER.index(e.kind))
        bracket = (min(e.bracket[0] for e in group), max(e.bracket[1] for e in group))
        others = ", ".join(f"{e.kind} at {e.value:.9g}" for e in group if e is not lead)
        out.append(
            dataclasses.replace(
                lead,
                bracket=bracket,
                accuracy=max(lead.value - bracket[0], bracket[1] - lead.value),
                unstable_below=group[0].unstable_below,
                unstable_above=group[-1].unstable_above,
                detail="; ".join(
                    filter(None, [lead.detail, f"with {others}, closer than tol = {tol:g}"])
                ),
            )
        )
        hidden.append(bracket)
    return out, hidden


def _same_structure(fa, fb):
    return (
        fa is not None
        and fb is not None
        and fa.stable is not None
        and fb.stable is not None
        and (fa.n_reversals, fa.n_sticks) == (fb.n_reversals, fb.n_sticks)
    )


def _multiplier_step(a, fa, b, fb, tol):
    """The next value for ``|mu| = 1`` within one structure: the secant of ``log|mu|``.

    ``log|mu|`` is smooth there (it is ``k T`` times the growth rate), so the secant
    converges in a few steps; kept inside the bracket, a tolerance away from its ends
    so that the bracket shrinks.
    """
    ga, gb = math.log(fa.max_abs_multiplier), math.log(fb.max_abs_multiplier)
    if ga == gb:
        return None
    m = a - ga * (b - a) / (gb - ga)
    return min(max(m, a + tol / 3), b - tol / 3)


def _state(f):
    """What a value's evaluation says: not found, or (structure, verdict)."""
    return None if f is None else (f.n_reversals, f.n_sticks, f.verdict)


def _band_kind(old_kind, fa, fb):
    """The bifurcation of an edge between two responses, from the band's classification.

    A ``multiplier`` edge takes the kind of the critical multiplier of the unstable
    side (the largest in modulus); a change of structure is a grazing.
    """
    if old_kind != "multiplier":
        return "grazing", None
    unstable = fa if fa.stable is False else fb
    mu = unstable.multipliers[int(np.argmax(np.abs(unstable.multipliers)))]
    return multiplier_kind(mu, unstable.period)


def _edge(a, fa, b, fb, kind=None, accuracy=None):
    """The change between two responses closer than the tolerance, classified.

    ``kind``: the old kind, ``multiplier`` or ``grazing`` (found from the structures
    where not given); the new one by `_band_kind`. ``accuracy``: where the value is
    known better than the bracket says.
    """
    if kind is None:
        # a response that grazes has no multipliers (`Floquet.stable` None): the change
        # next to it is the grazing, never a multiplier's crossing
        same = (fa.n_reversals, fa.n_sticks) == (fb.n_reversals, fb.n_sticks)
        kind = "multiplier" if same and None not in (fa.stable, fb.stable) else "grazing"
    new_kind, frequency = _band_kind(kind, fa, fb)
    return Edge(
        0.5 * (a + b),
        new_kind,
        kind,
        (a, b),
        0.5 * (b - a) if accuracy is None else accuracy,
        frequency,
        fa is None or fa.stable is False,
        fb is None or fb.stable is False,
    )


def _unclassified_edge(a, fa, b, fb, why):
    """The end of a response between ``a`` and ``b`` (closer than the tolerance, found on
    one side only) that no continuation could classify: kind ``unclassified``."""
    return Edge(
        0.5 * (a + b),
        "unclassified",
        "existence",
        (a, b),
        0.5 * (b - a),
        None,
        fa is None or fa.stable is False,
        fb is None or fb.stable is False,
        f"the response ends between {a:.9g} and {b:.9g}; its continuation stops there "
        f"without classifying the end ({why})",
    )


def _runs(points, edges, flag, lo, hi):
    """Maximal ranges of the evaluated values where ``flag`` holds, cut at the edges."""
    out, start, previous = [], None, None
    cuts = sorted(e.value for e in edges)
    for v, f in points:
        if flag(f) and start is None:
            inside = [c for c in cuts if previous is not None and previous < c < v]
            start = inside[-1] if inside else (lo if previous is None else v)
        elif not flag(f) and start is not None:
            inside = [c for c in cuts if previous < c < v]
            out.append([start, inside[0] if inside else previous])
            start = None
        previous = v
    if start is not None:
        out.append([start, hi])
    return out


def _sliding_grazing(param, fa, fb):
    """The grazing point of the backward-sliding response between ``a`` and ``b``, or None.

    Where the side above slides backwards throughout (no switch in contact) and the
    side below does not, the sliding response stops at the belt speed equal to its
    largest velocity in contact; on the closed-form path it does not depend on ``Vb``.
    Only for ``param = "Vb"`` on that path; other parameters, and the general path
    (where the friction depends on the velocity), are bisected.
    """
    if (
        param != "Vb"
        or fb is None
        or fb.engine != "closed_form"
        or (fb.n_reversals, fb.n_sticks) != (0, 0)
        or (fa is not None and (fa.n_reversals, fa.n_sticks) == (0, 0))
    ):
        return None
    return largest_sliding_velocity(fb.response._engine)


# ---------------------------------------------------------------- an end inside an interval


@dataclass
class _BandEnd:
    """Where the response found on one side of a band's interval ends within it.

    ``edges``: the band's edges that the continuation across the interval finds (its
    bifurcations and its end); ``reached``: the `Floquet` of the response at the far
    value, where the continuation reaches it (Newton's method had missed it there);
    ``solved``: ``(value, Floquet)`` of the responses solved on the way; ``stalled``:
    why the continuation stopped inside without locating an end ("" where it did not).
    """

    edges: list
    reached: Floquet | None
    solved: list = field(default_factory=list)
    stalled: str = ""


def _end_detail(end: End) -> str:
    m = end.margin
    return f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at t = {m.t:.4g} s vanishes"


def _special_edge(kind, value, accuracy, frequency, detail, unstable_below, unstable_above):
    """An edge at a located special point or end (its accuracy as located)."""
    if kind == "branch_point":  # a real multiplier through +1 without a turn
        kind = "fold"
    kind = kind if kind in KINDS else "unclassified"
    return Edge(
        value,
        kind,
        OLD_KINDS.get(kind, "existence"),
        (value - accuracy, value + accuracy),
        accuracy,
        frequency,
        unstable_below,
        unstable_above,
        detail,
    )


def _natural(family, value, state, far):
    """Natural continuation from ``value`` towards ``far``, quadratic predictor, step control.

    Returns the responses solved (``(value, FixedPoint)``, in order), whether ``far``
    was reached, and whether the response kept its switch structure on the way (if
    not, the caller continues by arclength). A step that finds no response is halved;
    the continuation stops where the step falls below `_NATURAL_SMALLEST` of the
    distance, or at once where a margin of the last two responses closes before the
    step's end (`_closes_before`): `locate_end` takes over from there, its steps aimed
    at the margin's zero (halving blindly towards a tangency costs a failed Newton's
    method of 10-20 period maps a time).
    """
    first = fixed_point(family(value), state)
    points = [(value, first)]
    h = (far - value) / 8
    smallest = _NATURAL_SMALLEST * abs(far - value)
    while abs(h) >= smallest:
        x = points[-1][0] + h
        if (far - x) * h <= 0:
            x = far
        known = np.array([v for v, _ in points[-3:]])
        states = np.array([p.state for _, p in points[-3:]])
        if known.size > 1:
            c = np.polyfit(known - known[-1], states, known.size - 1)
            guess = np.array([np.polyval(c[:, i], x - known[-1]) for i in range(states.shape[1])])
        else:
            guess = states[-1]
        try:
            p = fixed_point(family(x), guess)
        except NoPeriodicResponse:
            if _closes_before(family, points, x):
                return points, False, True
            h = 0.5 * (x - points[-1][0])  # of the step tried (it may end at far)
            continue
        if p.image.signature != points[-1][1].image.signature:
            return points, False, False
        points.append((x, p))
        if x == far:
            return points, True, True
        if _closes_before(family, points, far):
            return points, False, True
        h *= 1.5
    return points, False, True


def _closes_before(family, points, x):
    """Whether a margin of the last two of ``points`` has its secant's zero before ``x``.

    Close to a tangency the crossing margin falls like the square root of the distance
    to the end, so the secant's zero lies beyond the end: a zero before ``x`` is taken
    for an end before ``x`` (`beltmdsm.continuation.edges.closing_margins`); `locate_end`
    finds it, or `_band_existence` falls back on the branch.
    """
    if len(points) < 2:
        return False
    (va, pa), (vb, pb) = points[-2:]
    window = 0.25 * family.periods * family(vb).period
    closing = closing_margins(
        pa.image.margins_of(MARGIN_KINDS), pb.image.margins_of(MARGIN_KINDS), va, vb, window
    )
    return any(0.0 < (zero - vb) * (x - vb) < (x - vb) ** 2 for zero, _ in closing)


def _multiplier_edge(family, a, b, tol):
    """The edge where ``max |mu| = 1`` between two responses of one structure (secant)."""
    (va, pa), (vb, pb) = a, b
    ga, gb = log_max_multiplier(family(va), pa)[0], log_max_multiplier(family(vb), pb)[0]
    stable_below = (ga < 0) if va < vb else (gb < 0)
    # the secant, kept inside the bracket of the sign change [lo, hi]: where it has no
    # slope (ga == gb: a multiplier flat in the parameter, as on |mu| = 1 undamped) or
    # leaves the bracket, the bracket is bisected
    (lo, glo), hi = (va, ga), vb
    for _ in range(40):
        v = vb - gb * (vb - va) / (gb - ga) if gb != ga else math.nan
        if not min(lo, hi) < v < max(lo, hi):
            v = 0.5 * (lo + hi)
        p = fixed_point(family(v), pb.state)
        g, mu = log_max_multiplier(family(v), p)
        (va, pa, ga), (vb, pb, gb) = (vb, pb, gb), (v, p, g)
        if (g < 0) == (glo < 0):
            lo, glo = v, g
        else:
            hi = v
        if abs(vb - va) <= tol or abs(hi - lo) <= tol:
            break
    kind, frequency = multiplier_kind(mu, family.periods * family(vb).period)
    return Edge(
        vb,
        kind,
        OLD_KINDS[kind],
        (vb - abs(vb - va), vb + abs(vb - va)),
        abs(vb - va),
        frequency,
        not stable_below,
        stable_below,
    )


def _towards(points, value, far):
    """The branch's points from the one at ``value`` towards ``far``, up to where it turns.

    Past a fold the branch comes back over values where the first part holds responses
    too; the band records the first part only.
    """
    if not points:
        return []
    i = min(range(len(points)), key=lambda j: abs(points[j].value - value))
    toward = 1.0 if far > value else -1.0
    step = 1 if i + 1 < len(points) and (points[i + 1].value - value) * toward > 0 else -1
    out = []
    while 0 <= i + step < len(points) and (points[i + step].value - points[i].value) * toward > 0:
        i += step
        out.append(points[i])
    return out


def _verdict(pmap, point):
    """Whether a fixed point of a map is stable: every multiplier inside the unit circle."""
    mu = np.concatenate([np.linalg.eigvals(point.image.jacobian), pmap.fixed_multipliers()])
    return bool(np.max(np.abs(mu)) < 1.0)


def _band_existence(param, a, fa, b, fb, backend, tol):
    """Continue the response found at ``a`` or ``b`` across ``[a, b]``: a `_BandEnd`.

    Exactly one of ``fa``, ``fb`` (`beltmdsm.periodic.floquet.Floquet`) is None. The
    response through the other either reaches the far value (Newton's method had
    missed it there) or ends inside at a tangency, a grazing or a fold, located to
    ``min(tol, _END_TOL)``; the bifurcations on the way are edges too.
    """
    found, value, far = (fa, a, b) if fa is not None else (fb, b, a)
    r = found.response
    family = MapFamily(r.model, param, r.periods, backend)

    def floquet_at(v, point):
        return Floquet.of(response_from(family(v), point))

    # the common case first: the response goes on unchanged to where a margin closes
    points, reached, plain = _natural(family, value, r.shooting_state, far)
    solved = [(v, floquet_at(v, p)) for v, p in points[1:]]
    if plain and not reached and len(points) >= 2:
        try:
            end = locate_end(family, points, tol=min(tol, _END_TOL))
        except NoEdge:
            end = None
        if end is not None and not min(value, far) < end.value < max(value, far):
            # a margin's extrapolated zero beyond the interval is no end inside it:
            # the branch decides (Newton's method may have missed the response at far)
            end = None
        if end is not None:
            # the responses of locate_end's trials belong to the branch too: a
            # multiplier crossing may lie among them, and they are the band's responses
            # nearest the end (where a map starts its curve)
            points = points + end.solved
            solved += [(v, floquet_at(v, p)) for v, p in end.solved]
            stable = _verdict(family(end.point_value), end.point)
            side = {("unstable_below" if far > value else "unstable_above"): not stable}
            edge = _special_edge(
                end.kind, end.value, end.accuracy, None, _end_detail(end), True, True
            )
            # a multiplier crossing on the way (the verdict changes between two responses)
            crossings = [
                _multiplier_edge(family, p, q, 1e-9 * abs(far - value))
                for p, q in zip(points[:-1], points[1:])
                if _verdict(family(p[0]), p[1]) != _verdict(family(q[0]), q[1])
            ]
            return _BandEnd(crossings + [dataclasses.replace(edge, **side)], None, solved)
    if plain and reached:
        guess = points[-1][1].state
        at = r.model.replace(**{param: far})
        reached_f = floquet(at, guess=guess, forward=0, backend=backend, periods=r.periods)
        return _BandEnd([], reached_f, solved)
    branch = continue_branch(r, param, min(a, b), max(a, b), backend=backend)
    solved = [
        (q.value, floquet_at(q.value, FixedPoint(q.state, q.image, 0.0, 0)))
        for q in _towards(branch.points, value, far)
    ]
    toward = 1.0 if far > value else -1.0
    out = [
        _from_special(s, s.stable_before is not True, s.stable_after is not True)
        for s in branch.special
        if s.kind in ("neimark_sacker", "period_doubling", "branch_point")
    ]
    # the farthest the branch gets towards the far value is where the response ends
    extreme = max(branch.special, key=lambda s: toward * s.value)
    if extreme.kind == "range" and extreme.value == far:
        near = branch.point_near(far)
        reached_f = floquet(
            branch.model.replace(**{param: far}),
            guess=near.state,
            forward=0,
            backend=backend,
            periods=branch.periods,
        )
        return _BandEnd(out, reached_f, solved)
    if extreme.kind not in KINDS:
        # the continuation stopped (a corrector diverged) short of an end it could
        # locate: no edge, the band bisects what is left (its grid cannot tell)
        return _BandEnd(out, None, solved, stalled=extreme.detail or extreme.kind)
    # no stable response on the side where they exist: neither half at a fold is stable
    exists_unstable = True not in (extreme.stable_before, extreme.stable_after)
    if toward > 0:
        edge = _from_special(extreme, exists_unstable, True)
    else:
        edge = _from_special(extreme, True, exists_unstable)
    return _BandEnd(out + [edge], None, solved)


def _from_special(s: SpecialPoint, unstable_below: bool, unstable_above: bool) -> Edge:
    return _special_edge(
        s.kind, s.value, s.accuracy, s.frequency, s.detail, unstable_below, unstable_above
    )
