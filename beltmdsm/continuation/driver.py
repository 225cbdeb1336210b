"""The one continuation driver: corrector, walk, step control, special points, range ends.

It drives any `beltmdsm.continuation.problem.Problem` (the forced responses, the
self-excited cycles, steady sliding): a secant predictor along the unit tangent, a
corrector by Newton's method on the problem's equations and the hyperplane normal to
the tangent (`newton`), a step that grows by 1.5 after easy corrections and halves after
failed ones (`beltmdsm.continuation.settings.ContinuationSettings`), the special points
between accepted points (the problem's ``special_between``, by default folds and
multiplier crossings, `beltmdsm.continuation.special`), and the clamping of the branch
to its range: a step that leaves it is cut back by regula falsi onto the bound.
The problem's hooks say what else ends or refuses a step (a grazing, a stick onset, a
tangency, a multiplier or period limit).
"""

from __future__ import annotations

import numpy as np

from ..errors import NoPeriodicResponse
from .corrector import newton  # noqa: F401  (one corrector for every problem)
from .problem import Problem, failed
from .settings import ContinuationSettings
from .special import regula_falsi

__all__ = ["newton", "walk", "join"]  # newton: beltmdsm.continuation.corrector

#: Points handed to a problem's end hooks at most (the last stretch of one structure).
_END_POINTS = 400


def join(up, down):
    """One branch from the walks up and down from one start, in arclength order.

    Parameters
    ----------
    up, down : (points, special)
        The walks with the parameter growing and falling; both start at the same point.

    Returns
    -------
    points, special : list
        From the lower end; the special points of ``down`` have ``stable_before`` and
        ``stable_after`` swapped (along the arclength from the lower end).

    See Also
    --------
    beltmdsm.continuation.driver.walk : each walk.

    Examples
    --------
    >>> join(([0, 1, 2], ["a"]), ([0, -1], []))
    ([-1, 0, 1, 2], ['a'])
    """
    (up_points, up_special), (down_points, down_special) = up, down
    for s in down_special:
        s.stable_before, s.stable_after = s.stable_after, s.stable_before
    points = list(reversed(down_points[1:])) + list(up_points)
    return points, list(reversed(down_special)) + list(up_special)


def walk(problem: Problem, first, tangent, settings: ContinuationSettings | None = None):
    """Continue a problem from ``first`` along ``tangent`` to an end of the branch.

    Parameters
    ----------
    problem : Problem
        What is continued (`beltmdsm.continuation.problem`).
    first
        A point of the problem, its ``column`` set.
    tangent : ndarray (n + 1,)
        The unit tangent at ``first`` in the direction to go.
    settings : ContinuationSettings, optional
        Set on the problem (``problem.settings``); default the problem's.

    Returns
    -------
    points : list
        From ``first`` on.
    special : list of SpecialPoint
        The special points passed, then how the walk ended: ``range`` at a bound,
        the problem's end (a tangency, a grazing, a limit) or ``failed``.

    See Also
    --------
    beltmdsm.continuation.driver.join : two walks into one branch.
    beltmdsm.continuation.branch.continue_branch : the forced responses' walks.
    beltmdsm.cycles.branch.cycle_branch : the self-excited cycles'.

    Examples
    --------
    The unit circle ``u^2 + p^2 = 1`` (`beltmdsm.continuation.circle`) from ``(1, 0)``
    up to the range's end at ``p = 0.8``, the branch turning nowhere:

    >>> from beltmdsm.continuation.circle import Circle
    >>> circle = Circle(-1.0, 0.8)
    >>> points, special = walk(circle, *circle.start(0.0, direction=1.0))
    >>> [(s.kind, s.value) for s in special], round(float(points[-1].u), 6)
    ([('range', 0.8)], 0.6)
    """
    if settings is not None:
        problem.settings = settings
    s = problem.settings
    points, special, since = [first], [], [0]
    ds, crawl = s.step_first, 0

    def stretch(last=None):
        """The points since the last special point (at most `_END_POINTS`), up to
        ``last``: an end or a grazing is located on one switch structure's stretch."""
        stop = len(points) if last is None else points.index(last) + 1
        start = max(stop - _END_POINTS, min(since[-1], stop - 2), 0)
        return points[start:stop]

    def fail(failure, stage, rescue=True):
        """Halve the step, or end the walk: True where it ends."""
        nonlocal ds, tangent
        if rescue:
            crossed = problem.rescue(points, points[-1], tangent, ds)
            if crossed is not None:
                sp, new_points, tangent = crossed
                special.append(sp)
                points.extend(new_points)
                ds = s.step_first
                return False
        ds *= 0.5
        if ds < s.step_min:
            end, extra = problem.give_up(stretch(), failure, stage)
            points.extend(extra)
            special.append(end)
            return True
        return False

    while True:
        prev = points[-1]
        if len(points) >= s.max_points:
            stopped = f"stopped after {s.max_points} points"
            special.append(failed(prev, stopped))
            return points, special
        z_pred = problem.z(prev) + ds * tangent
        try:
            step = problem.solve(z_pred, problem.arclength(z_pred, tangent), prev.column)
            jumped = bool(np.max(np.abs(step.z - z_pred)) > 10 * ds)
            failure = problem.check_step(prev, step, jumped)
        except NoPeriodicResponse as err:
            step, failure = None, str(err)
        if failure is not None:
            if fail(failure, "step"):
                return points, special
            continue
        if not problem.lo <= step.value <= problem.hi:
            bound = problem.hi if step.value > problem.hi else problem.lo
            try:  # the branch's end on the bound, and what lies before it
                end, _ = regula_falsi(
                    problem,
                    prev,
                    tangent,
                    ds,
                    lambda q, b=bound: q.value - b,
                    prev.value - bound,
                    step.value - bound,
                    s_tol=s.s_tol,
                )
                found = problem.range_specials(prev, end, tangent, ds, bound, s)
            except NoPeriodicResponse as err:
                if fail(f"locating the end of the range: {err}", "range", rescue=False):
                    return points, special
                continue
            special += found
            last, at_end = problem.at_bound(end, bound)
            points.append(last)
            special.append(at_end)
            return points, special
        failure = problem.check_structure(prev, step, ds, jumped)
        if failure is not None:
            if fail(failure, "step", rescue=False):
                return points, special
            continue
        new, t_new = problem.accept(step, tangent)
        found = []
        if problem.same_structure(prev, new):
            try:
                found = problem.special_between(prev, new, tangent, ds, s)
            except NoPeriodicResponse:
                # a corrector failed locating a special point: a shorter step brackets it
                if fail("a special point cannot be located", "special", rescue=False):
                    return points, special
                continue
            special += found
        else:
            crossing = problem.crossing(prev, new, stretch(prev))
            if crossing is not None:
                special.append(crossing)
                found = [crossing]
        if found:
            since.append(len(points))
        points.append(new)
        tangent = t_new
        end = problem.stop(new)
        if end is not None:
            special.append(end)
            return points, special
        if step.iterations <= s.easy:
            ds = min(ds * 1.5, s.step_max)
        crawl = crawl + 1 if ds < s.crawl_step else 0
        if crawl >= s.crawl_limit:
            crawl = -3 * s.crawl_limit  # the next try after as many steps again
            end = problem.near_end(stretch())
            if end is not None:
                special.append(end)
                return points, special
