"""Exact two-parameter stability maps: where the periodic response is unstable, boundaries traced.

The paper's Figs. 6-9 map the verdict of its linear analysis over two parameters. The
exact counterpart is the region of ``(x, y)`` where the periodic response of period
``T`` (`beltmdsm.periodic.floquet`) is unstable or absent, bounded by curves of its edges, each
of one bifurcation kind (`beltmdsm.continuation.edges.KINDS`). `floquet_map` traces these curves by
continuation in ``y``, row by row, not on a grid of pixels:

* The first row is a band in ``x`` (`beltmdsm.continuation.band.floquet_band`): its edges start
  the curves, each with the responses next to it.
* A **multiplier** curve (Neimark-Sacker, period doubling) is continued by the secant
  in ``x`` of ``log max |mu|``, its response continued from the row before (the edge
  and the response extrapolated from the last rows, cubically; along the row by the
  tangent of the secant's last wide step), to `EDGE_TOL` of the range: the secant's
  last step bounds the error of its next iterate, which is taken without a period map
  of its own. Where the secant's slope, predicted linearly from the last two rows
  that measured it, is known to better than half its value, the row takes one
  response: the step with that slope from the predicted edge is within `EDGE_TOL`,
  and its error is below the step.
* An **end** (tangency, grazing) is continued by `beltmdsm.continuation.edges.locate_end` from
  four responses on the side where they exist, next to the predicted end: ``x`` is a
  smooth function of the closing margin, whose cubic through them gives the end. That
  function changes smoothly from row to row: between rows that measure it, a row
  takes one response and the cubic of the rows before, extrapolated (its accuracy
  theirs plus the difference of the cubic and the quadratic extrapolation; four
  responses again every `_REMEASURE` rows, or where that difference passes `_DRIFT`
  of the tolerance). A fold is continued by a short branch
  (`beltmdsm.continuation.branch.continue_branch`) across the predicted fold. Where ``x`` is
  ``Vb`` and the response slides back throughout, its grazing point is exact: its
  largest velocity in contact (`beltmdsm.periodic.closed_form.largest_sliding_velocity`,
  as the band finds it).
* A curve that cannot be continued on a row ends there; a band on that row, on every
  row where no curve is followed, and on every ``check_every``-th row, finds the
  edges afresh, and an edge that no curve follows starts a new one.

Each row's unstable set is where no stable periodic response is found: on a row with a
band, the band's (`beltmdsm.continuation.band_result.Band.unstable`; a curve of a second periodic
response that coexists with a stable one then bounds nothing); on the rows between,
it follows from the curves' edges and from which of their sides is unstable, which
assumes one periodic response at each ``x``. The paper's linear analysis
(`beltmdsm.generated.stability.is_stable`, the options of the paper) is evaluated on the same
rows for comparison, on a grid of ``x`` fine enough to show it (`LINEAR_POINTS`).
``floquet-map --png`` draws the result (`beltmdsm.cli.figure`).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from .._calling import mapped, rename
from ..arguments import count, flag, number
from ..errors import NoPeriodicResponse, Refused
from ..excitation import excitation_period
from ..model import MODEL_PARAMETERS, Backend, Model, as_model
from ..periodic.family import MapFamily
from ..settings import MAX_MAP_ROWS
from .band import floquet_band
from .edges import NoEdge
from .linear_verdict import LINEAR_POINTS, _linear
from .map_result import Curve, FloquetMap
from .map_tracker import EDGE_TOL, _extrapolate, _trackers_from_band
from .settings import FORCED_SETTINGS, ContinuationSettings, as_settings

__all__ = ["floquet_map"]

#: A band's edge within this share of the ``x`` range of where a lost curve of its kind
#: was heading goes on that curve.
_RESUME = 0.1
#: Two curves of one kind closer than this many times `EDGE_TOL` on a row have become
#: one (edges that merge, e.g. grazings that become one tangency): one goes on.
_SAME = 10


def _row_unstable(edges, lo, hi):
    """The unstable set of a row from its edges: ``(x, unstable_below, unstable_above)``."""
    edges = sorted(edges)
    if not edges:
        return []
    out, start = [], lo if edges[0][1] else None
    for x, _, above in edges:
        if start is not None and not above:
            out.append([start, x])
            start = None
        elif start is None and above:
            start = x
    if start is not None:
        out.append([start, hi])
    return out


@mapped(
    renamed={
        "x_from": rename("x_lo"),
        "x_to": rename("x_hi"),
        "y_from": rename("y_lo"),
        "y_to": rename("y_hi"),
        "rows": rename("points"),
    },
    models=True,
)
def floquet_map(
    model: Model | Mapping[str, Any] | None,
    x: str,
    x_lo: float,
    x_hi: float,
    y: str,
    y_lo: float,
    y_hi: float,
    *,
    points: int = 100,
    check_every: int = 50,
    backend: Backend | None = None,
    progress: bool = False,
    settings: ContinuationSettings | None = None,
) -> FloquetMap:
    """The region of ``(x, y)`` where the periodic response is unstable, its boundary traced.

    Parameters
    ----------
    model : Model or dict or None
        The other parameters and the options (None: the base set).
    x, y : str
        Two different model parameters.
    x_lo, x_hi, y_lo, y_hi : float
        Their ranges (``x_from=`` ... before: deprecated).
    points : int
        Values of ``y`` (>= 2), evenly spaced: the rows of the map (``rows=`` before:
        deprecated).
    check_every : int
        A band finds the edges afresh on every such row (>= 1), besides where a curve
        cannot be continued and where no curve is followed.
    backend : {"python", "numba", None}
    progress : bool
        Show the rows on stderr (tqdm) once they take more than 2 s.
    settings : ContinuationSettings, optional
        The driver's steps and tolerances, for the bands of the rows and the branches
        across a fold (`beltmdsm.continuation.settings`).

    Returns
    -------
    FloquetMap
        The boundary curves, and per row the unstable set and the linear verdict.

    Raises
    ------
    ValueError
        For unknown or equal parameters, bad ranges, ``points < 2`` or
        ``check_every < 1``, or a model without excitation.
    beltmdsm.errors.Refused
        For more than `beltmdsm.settings.MAX_MAP_ROWS` points.

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : the edges of one row.
    beltmdsm.continuation.branch.branch : one response continued in one parameter.

    Examples
    --------
    The Neimark-Sacker curve in ``(Vb, beta1)`` over three rows:

    >>> from beltmdsm import floquet_map
    >>> m = floquet_map(None, "Vb", 5.3, 5.7, "beta1", 0.29, 0.31, points=3)
    >>> [(c.kind, len(c.x)) for c in m.curves]
    [('neimark_sacker', 3)]
    >>> [round(x, 3) for x in m.curves[0].x]
    [5.426, 5.45, 5.471]
    >>> [[round(a, 2), round(b, 2)] for (a, b), in m.unstable]
    [[5.43, 5.7], [5.45, 5.7], [5.47, 5.7]]
    """
    clock = time.perf_counter()
    if (other := as_model(model)).model != "paper":  # another model: its forced response
        from ..oscillator.api import _paper_keywords
        from .oscillator_band import oscillator_map

        _paper_keywords("floquet_map", other, backend=backend, settings=settings)
        return oscillator_map(other, x, x_lo, x_hi, y, y_lo, y_hi, points=points)
    for name in (x, y):
        if name not in MODEL_PARAMETERS:
            raise ValueError(f"a map's axes must be model parameters; got {name!r}")
    if x == y:
        raise ValueError(f"the two axes must differ; got {x!r} twice")
    x_lo, y_lo = number("x_lo", x_lo), number("y_lo", y_lo)
    x_hi, y_hi = number("x_hi", x_hi, above=x_lo), number("y_hi", y_hi, above=y_lo)
    points, check_every = count("points", points, 2), count("check_every", check_every, 1)
    progress = flag("progress", progress)
    if points > MAX_MAP_ROWS:
        raise Refused(
            f"points = {points} is more than MAX_MAP_ROWS = {MAX_MAP_ROWS} "
            "(beltmdsm/settings.py; a row is a continuation step of every curve, every "
            f"{check_every}th a band): use points <= {MAX_MAP_ROWS}",
            "points",
        )
    as_settings(settings, FORCED_SETTINGS)  # checked where it enters
    base = as_model(model).replace(**{x: x_lo, y: y_lo})
    excitation_period(base)
    span = x_hi - x_lo
    ys = np.linspace(y_lo, y_hi, points)
    xs = np.linspace(x_lo, x_hi, LINEAR_POINTS)
    curves, trackers, unstable, models, band_rows = [], [], [], [], []
    from tqdm import tqdm

    bar = tqdm(
        total=ys.size,
        desc=f"floquet-map {y}",
        unit=" rows",
        delay=2,
        leave=False,
        disable=not progress,
        file=sys.stderr,
    )
    for i, value in enumerate(ys):
        bar.update()
        row = base.replace(**{y: float(value)})
        family = MapFamily(row, x, 1, backend)
        live, lost = [], []
        for tracker in trackers:
            try:
                kind, at, accuracy, frequency = tracker.step(family, value, span)
            except (NoPeriodicResponse, NoEdge) as err:
                tracker.curve.ended = f"not continued to {y} = {value:g}: {err}"
                lost.append(tracker)
                continue
            c = tracker.curve
            if not x_lo <= at <= x_hi:
                c.ended = f"leaves the range of {x} at {y} = {value:g}"
                continue
            if kind != c.kind:  # a new kind: a new curve from the same point
                # a tangency ends the response, violently unstable next to it (the
                # saltation diverges): unstable on both sides; a change between
                # multiplier kinds keeps the stable side
                both = kind == "tangency"
                new = Curve(
                    kind,
                    unstable_below=both or c.unstable_below,
                    unstable_above=both or c.unstable_above,
                )
                c.ended = f"becomes {kind} at {y} = {value:g}"
                curves.append(new)
                tracker.curve, c = new, new
            c.y.append(float(value))
            c.x.append(float(at))
            tracker.record(value, at)
            c.accuracy.append(float(accuracy))
            c.frequency.append(frequency)
            twin = next(
                (
                    t
                    for t in live
                    if t.curve.kind == kind and abs(t.xs[-1] - at) <= _SAME * EDGE_TOL * span
                ),
                None,
            )
            if twin is not None:  # two edges that have become one: one curve goes on
                c.ended = f"joins another {kind} curve at {y} = {value:g}"
                continue
            live.append(tracker)
        band = None
        if i == 0 or not live or len(live) < len(trackers) or i % int(check_every) == 0:
            # the band's tol is at most its grid's step (17 points)
            tol = min(1e-3, (x_hi - x_lo) / 16)
            band = floquet_band(row, x, x_lo, x_hi, tol=tol, backend=backend, settings=settings)
            band_rows.append(float(value))
            followed = [t.curve.x[-1] for t in live if t.curve.y[-1] == float(value)]
            for e in band.edges:
                if any(abs(e.value - f) <= 1e-3 * span for f in followed):
                    continue
                new = _trackers_from_band(band, [e], family, value, span, settings)
                for t in new:
                    # an edge the row before's curve of its kind lost: the same curve
                    before = [
                        old
                        for old in lost
                        if old.curve.kind == t.curve.kind
                        and abs(_extrapolate(old.curve.y, old.curve.x, value) - t.curve.x[-1])
                        <= _RESUME * span
                    ]
                    if before:
                        c = before[0].curve
                        lost.remove(before[0])
                        for name in ("y", "x", "accuracy", "frequency"):
                            getattr(c, name).append(getattr(t.curve, name)[-1])
                        c.ended, t.curve = "", c
                    else:
                        curves.append(t.curve)
                live += new
        trackers = live
        edges = [
            (t.curve.x[-1], t.curve.unstable_below, t.curve.unstable_above)
            for t in trackers
            if t.curve.y and t.curve.y[-1] == float(value)
        ]
        if band is None:
            unstable.append(_row_unstable(edges, x_lo, x_hi))
        else:  # where no stable response is found, also beside an unstable one
            unstable.append([[float(a), float(b)] for a, b in band.unstable])
        models.append(row)
    bar.close()
    return FloquetMap(
        x,
        y,
        [float(x_lo), float(x_hi)],
        [float(y_lo), float(y_hi)],
        ys,
        base,
        curves,
        unstable,
        _linear(models, x, xs),
        band_rows,
        time.perf_counter() - clock,
    )
