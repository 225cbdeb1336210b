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

The result is a `Band` (`beltmdsm.continuation.band_result`); its `Band.as_dict` is the
JSON of ``floquet-band --json``. The edges between evaluated neighbours are
`beltmdsm.continuation.band_grid`'s, an end inside an interval
`beltmdsm.continuation.band_end`'s.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .._calling import ranged
from ..arguments import count, flag, number
from ..errors import NoPeriodicResponse, Refused
from ..excitation import excitation_period
from ..model import MODEL_PARAMETERS, Backend, Model, as_model, check_domain
from ..oscillator.api import _paper_keywords
from ..periodic.floquet import floquet
from ..periodic.shooting import FORWARD_PERIODS
from ..settings import MAX_BAND_POINTS, MIN_TOL_ULPS
from .band_end import _band_existence
from .band_grid import (
    _edge,
    _merge_close,
    _multiplier_step,
    _runs,
    _same_structure,
    _sliding_grazing,
    _state,
    _unclassified_edge,
)
from .band_result import Band, BandFailure, BandPoint
from .settings import FORCED_SETTINGS, ContinuationSettings, as_settings

__all__ = ["floquet_band"]


@ranged(models=True)
def floquet_band(
    model: Model | Mapping[str, Any] | None,
    param: str,
    lo: float,
    hi: float,
    *,
    points: int = 17,
    tol: float = 1e-3,
    backend: Backend | None = None,
    periods: int = 1,
    progress: bool = False,
    settings: ContinuationSettings | None = None,
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
    not depend on ``Vb`` (`beltmdsm.periodic.closed_form.largest_sliding_velocity`).

    Changes closer together than ``tol`` cannot be told apart at that tolerance: they
    are one edge, whose sides are the outer sides of the first and the last, and the
    values evaluated between them do not enter the ranges. So the edges' sides agree
    with the ranges at every ``tol``, and a finer ``tol`` only resolves more.

    Parameters
    ----------
    model : Model or dict or None
        The other parameters and the options (None: the base set).
    param : str
        A model parameter.
    lo, hi : float
        The range, inside the parameter's domain.
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
    settings : ContinuationSettings, optional
        The driver's steps and tolerances where a response is continued across an
        interval by pseudo-arclength (`beltmdsm.continuation.settings`).

    Returns
    -------
    Band
        The unstable ranges, the labelled edges, every evaluated value.

    Raises
    ------
    ValueError
        For an unknown parameter, a range that is not finite, empty or outside the
        parameter's domain, ``points < 2`` or ``tol <= 0``; a model without
        excitation (a band is of the forced response).
    beltmdsm.errors.Refused
        For ``points`` above `beltmdsm.settings.MAX_BAND_POINTS`, ``tol`` above the
        grid's step or below the rounding of the range
        (`beltmdsm.settings.MIN_TOL_ULPS`).

    See Also
    --------
    beltmdsm.continuation.branch.branch : one response continued, its special points.
    beltmdsm.continuation.floquet_map.floquet_map : the edges traced over two parameters.
    beltmdsm.periodic.floquet.floquet : the Floquet analysis at one value.

    Examples
    --------
    The model first, then the parameter and its range (the order of before, the model
    last, is taken too). A Neimark-Sacker edge at ``Vb`` about 5.45 when ``beta1 = 0.3``:

    >>> from beltmdsm import Model, floquet_band
    >>> band = floquet_band(Model(beta1=0.3), "Vb", 5.2, 5.8, points=4)
    >>> [[round(lo, 3), round(hi, 3)] for lo, hi in band.unstable]
    [[5.45, 5.8]]
    >>> [(e.kind, round(e.value, 3), e.unstable_below, e.unstable_above) for e in band.edges]
    [('neimark_sacker', 5.45, False, True)]
    """
    model = as_model(model)
    if model.model != "paper":  # another registered model: its forced response
        from .oscillator_band import oscillator_band

        _paper_keywords("floquet_band", model, backend=backend, settings=settings)
        return oscillator_band(model, param, lo, hi, points=points, tol=tol, periods=periods)
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    lo, hi = number("lo", lo), number("hi", hi)
    if not lo < hi:
        raise ValueError(f"the range must have lo < hi; got [{lo:g}, {hi:g}]")
    for end in (lo, hi):
        problem = check_domain(param, end)
        if problem:
            raise ValueError(f"the range [{lo:g}, {hi:g}] leaves the domain: {param} {problem}")
    excitation_period(model)  # a band of the forced response (not of self-excited cycles)
    points, tol = count("points", points, 2), number("tol", tol, above=0)
    periods, progress = count("periods", periods, 1), flag("progress", progress)
    _check_band_request(lo, hi, points, tol)
    as_settings(settings, FORCED_SETTINGS)  # checked where it enters
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
            end = _band_existence(param, a, fa, b, fb, backend, tol, settings)
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
        param=param,
        model=model,
        periods=int(periods),
        unstable=unstable,
        edges=edges,
        grazing_points=sorted(grazing_points),
        no_periodic_response=gaps,
        grid=table,
        failed=failed,
        tol=float(tol),
        merged_away=merged_away,
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
