"""The walk of a forced response's branch: steps, special points, grazings and its ends.

`_walk` continues from a response one way (`beltmdsm.continuation.arclength`'s
corrector), watches each step for special points (`beltmdsm.continuation.special`) and
changes of switch structure (a grazing), and ends the branch at the range's bound, at a
tangency or grazing located by `beltmdsm.continuation.edges.locate_end`, or as failed
(module docstring of `beltmdsm.continuation.branch`).
"""

from __future__ import annotations

import numpy as np

from ..errors import NoPeriodicResponse
from ..periodic.newton import FixedPoint, fixed_point
from .branch_parts import LOCATE_TOL, SpecialPoint
from .edges import NoEdge, locate_end
from .special import regula_falsi, special_between

#: Arclength steps (in the scaled coordinates): first, smallest, largest.
STEP_FIRST = 0.02
STEP_MIN = 1e-7
STEP_MAX = 0.25
#: A change of switch structure is accepted as grazing only from steps below this.
GRAZING_STEP = 1e-4
#: Corrector iterations under which the step grows.
_EASY = 4
#: A special point's regula falsi stops at brackets below this (scaled arclength).
_S_TOL = 1e-12
#: A crawl: this many steps in a row below `CRAWL_STEP` make the continuation try to
#: locate the end it approaches (`_near_end`), accepted where the closing margin is
#: below `CRAWL_MARGIN`.
CRAWL_STEP = 1e-4
CRAWL_LIMIT = 8
CRAWL_MARGIN = 1e-3
#: Points handed to `beltmdsm.continuation.edges.locate_end` at an end.
_END_POINTS = 400
#: Accepted points per branch at most.
MAX_POINTS = 2000


def _end(cont, points, reason):
    """The end of a branch where the corrector fails: a tangency, a grazing, or failed."""
    last = points[-1]
    if len(points) >= 2:
        try:
            end = locate_end(cont.family, [(p.value, _fixed(p)) for p in points])
            m = end.margin
            detail = (
                f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at "
                f"t = {m.t:.4g} s vanishes"
            )
            return SpecialPoint(
                end.kind, end.value, end.accuracy, None, last.multipliers, last.stable, None, detail
            ), [cont.point(p.state, v, last.tangent, p.image) for v, p in end.solved]
        except NoEdge as err:
            reason = f"{reason}; {err}"
    return SpecialPoint(
        "failed", last.value, 0.0, None, last.multipliers, last.stable, None, reason
    ), []


def _fixed(point):
    return FixedPoint(point.state, point.image, 0.0, 0)


def _walk(cont, first, direction, kT):
    """Continue from ``first`` with the parameter growing (``direction = 1``) or falling."""
    points, special = [first], []
    J = cont.jacobian(first.state, first.value, first.image)
    tangent = cont.tangent(J, direction=direction)
    first.tangent, first.column = float(tangent[-1]), J[:, -1].copy()
    ds = STEP_FIRST
    crawl = 0

    def period(_point):
        """``k T`` (of the start: the special points' frequencies are against it)."""
        return kT

    def stretch(last=None):
        """The points since the last special point (at most `_END_POINTS`), up to ``last``.

        An end or a grazing is located from the margins of one stretch of one switch
        structure: across a fold the same margin belongs to another half of the branch.
        """
        stop = len(points) if last is None else points.index(last) + 1
        start = max(stop - _END_POINTS, min(since[-1], stop - 2), 0)
        return points[start:stop]

    since = [0]
    while True:
        prev = points[-1]
        if len(points) >= MAX_POINTS:
            special.append(
                SpecialPoint(
                    "failed",
                    prev.value,
                    0.0,
                    None,
                    prev.multipliers,
                    prev.stable,
                    None,
                    f"stopped after {MAX_POINTS} points",
                )
            )
            return points, special
        z0 = cont.z(prev.state, prev.value)
        try:
            x, value, image, J_new, iterations = cont.correct(
                z0 + ds * tangent, tangent, prev.column
            )
            failure = None
        except NoPeriodicResponse as err:
            failure = str(err)
        if failure is None and not (cont.lo <= value <= cont.hi):
            bound = cont.hi if value > cont.hi else cont.lo
            try:
                end_point, acc = regula_falsi(
                    cont,
                    prev,
                    tangent,
                    ds,
                    lambda q, b=bound: q.value - b,
                    prev.value - bound,
                    value - bound,
                    s_tol=_S_TOL,
                )
                if end_point.image.signature == prev.image.signature:
                    found = special_between(
                        cont, prev, end_point, tangent, ds * 0.999, period, s_tol=_S_TOL
                    )
                else:
                    found = []
            except NoPeriodicResponse as err:
                # a corrector inside the step failed: a shorter step gets closer first
                failure = f"locating the end of the range: {err}"
        if failure is None and not (cont.lo <= value <= cont.hi):
            special += found
            try:  # the response at the bound itself
                at = fixed_point(cont.family(bound), end_point.state)
                end_point = cont.point(at.state, bound, end_point.tangent, at.image)
            except NoPeriodicResponse:
                pass
            points.append(end_point)
            special.append(
                SpecialPoint(
                    "range",
                    bound,
                    0.0,
                    None,
                    end_point.multipliers,
                    end_point.stable,
                    None,
                    "the end of the requested range",
                )
            )
            return points, special
        if failure is None and image.signature != prev.image.signature:
            if ds > GRAZING_STEP:
                failure = "the switch structure changes"
            elif np.max(np.abs(cont.z(x, value) - z0 - ds * tangent)) > 10 * ds:
                failure = "the corrector jumps to another structure"
        if failure is not None:
            ds *= 0.5
            if ds < STEP_MIN:
                end, extra = _end(cont, stretch(), failure)
                points += extra
                special.append(end)
                return points, special
            continue
        t_new = cont.tangent(J_new, tangent)
        new = cont.point(x, value, float(t_new[-1]), image)
        new.column = J_new[:, -1].copy()
        found = []
        if image.signature == prev.image.signature:
            try:
                found = special_between(cont, prev, new, tangent, ds, period, s_tol=_S_TOL)
            except NoPeriodicResponse:
                # a corrector inside the step failed while locating a special point: a
                # shorter step brackets it more closely
                ds *= 0.5
                if ds < STEP_MIN:
                    end, extra = _end(cont, stretch(), "a special point cannot be located")
                    points += extra
                    special.append(end)
                    return points, special
                continue
        if image.signature != prev.image.signature:
            # a small step onto another structure: the response goes on through a grazing
            try:
                end = locate_end(cont.family, [(p.value, _fixed(p)) for p in stretch(prev)])
                value_g, acc_g = end.value, end.accuracy
            except NoEdge:
                value_g, acc_g = 0.5 * (prev.value + new.value), abs(new.value - prev.value)
            special.append(
                SpecialPoint(
                    "grazing",
                    value_g,
                    acc_g,
                    None,
                    new.multipliers,
                    prev.stable,
                    new.stable,
                    "the switch structure changes; the response goes on",
                )
            )
            since.append(len(points))
        else:
            special += found
            if found:
                since.append(len(points))
        points.append(new)
        tangent = t_new
        if iterations <= _EASY:
            ds = min(ds * 1.5, STEP_MAX)
        crawl = crawl + 1 if ds < CRAWL_STEP else 0
        if crawl >= CRAWL_LIMIT:
            crawl = -3 * CRAWL_LIMIT  # the next try after as many steps again
            end = _near_end(cont, stretch())
            if end is not None:
                special.append(end)
                return points, special


def _near_end(cont, points):
    """The end that a crawl of small steps approaches, where a margin is about to vanish.

    Close to a tangency or a grazing the corrector converges only from ever smaller
    steps; where the closing margin is below `CRAWL_MARGIN` and
    `beltmdsm.continuation.edges.locate_end` places its zero to `LOCATE_TOL`, the branch
    ends there. None otherwise.
    """
    try:
        end = locate_end(cont.family, [(p.value, _fixed(p)) for p in points], tol=LOCATE_TOL)
    except NoEdge:
        return None
    if end.margin.value > CRAWL_MARGIN or end.accuracy > LOCATE_TOL:
        return None
    last = points[-1]
    m = end.margin
    return SpecialPoint(
        end.kind,
        end.value,
        end.accuracy,
        None,
        last.multipliers,
        last.stable,
        None,
        f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at t = {m.t:.4g} s vanishes",
    )
