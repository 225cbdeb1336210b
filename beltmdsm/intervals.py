"""Intervals of belt speed (or of any swept parameter): runs, edges, set algebra, text.

Sweeps, predictions and the validation all turn values on a grid into sets of
intervals and compare such sets. An interval is a pair ``(lo, hi)`` of floats with
``lo <= hi``, closed; a set is a list of intervals. The functions here are pure
and small; `beltmdsm.batch.sweep`, `beltmdsm.prediction`,
`beltmdsm.paper_reports.validation` and the notebooks' ``_nbutil`` call them.

Runtime layer: numpy only.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "true_runs",
    "label_runs",
    "runs",
    "sign_changes",
    "from_crossings",
    "union",
    "intersection",
    "difference",
    "symmetric_difference",
    "clip",
    "hull",
    "length",
    "jaccard",
    "format_intervals",
]

#: Any label of `label_runs`: what it is given comes back.
_Label = TypeVar("_Label")


def true_runs(flags: ArrayLike) -> list[tuple[int, int]]:
    """Maximal runs of consecutive true entries, in sequence order.

    Parameters
    ----------
    flags : array_like of bool

    Returns
    -------
    list of (int, int)
        ``(first, last)`` indices of each run, both inclusive.

    See Also
    --------
    beltmdsm.intervals.label_runs : runs of equal labels of any kind
    beltmdsm.intervals.runs : the same runs as ranges of a grid

    Examples
    --------
    Two runs: indices 1 to 2 and the last one alone.

    >>> true_runs([False, True, True, False, True])
    [(1, 2), (4, 4)]
    """
    # a run starts where the flags (padded with False) rise and ends before they fall:
    # vectorised, as a map's linear analysis asks for thousands of flags a row
    padded = np.concatenate(([False], np.asarray(flags, dtype=bool).ravel(), [False]))
    changes = np.flatnonzero(padded[1:] != padded[:-1])
    return [(int(i), int(j) - 1) for i, j in zip(changes[::2], changes[1::2])]


def label_runs(labels: Iterable[_Label]) -> list[tuple[_Label, int, int]]:
    """Maximal runs of consecutive equal labels, in sequence order.

    Parameters
    ----------
    labels : sequence
        any labels that compare with ``==`` (regime names, flags)

    Returns
    -------
    list of (label, int, int)
        the label and the ``(first, last)`` indices of its run, both inclusive.

    See Also
    --------
    beltmdsm.intervals.true_runs : runs of true flags only

    Examples
    --------
    Three runs of regime names along a sweep:

    >>> label_runs(["slip", "slip", "stick-slip", "slip"])
    [('slip', 0, 1), ('stick-slip', 2, 2), ('slip', 3, 3)]
    """
    out = []
    for i, label in enumerate(labels):
        if out and out[-1][0] == label:
            out[-1] = (label, out[-1][1], i)
        else:
            out.append((label, i, i))
    return out


def runs(x: ArrayLike, flags: ArrayLike) -> list[tuple[float, float]]:
    """Ranges of ``x`` over which ``flags`` holds at consecutive grid points.

    Parameters
    ----------
    x : array_like of float
        the grid (sorted here first, so any order will do)
    flags : array_like of bool
        one flag per grid point

    Returns
    -------
    list of (float, float)
        ``(first x, last x)`` of each maximal run of true flags, ascending; a run of
        one point is ``(x, x)``.

    Examples
    --------
    >>> runs([1, 2, 3, 4, 5], [False, True, True, False, True])
    [(2.0, 3.0), (5.0, 5.0)]
    """
    x = np.asarray(x, dtype=float)
    flags = np.asarray(flags, dtype=bool)
    if x.shape != flags.shape or x.ndim != 1:
        raise ValueError(
            f"x and flags must be 1-D of one length; got shapes {x.shape} and {flags.shape}"
        )
    order = np.argsort(x)
    x, flags = x[order], flags[order]
    return [(float(x[i]), float(x[j])) for i, j in true_runs(flags)]


def sign_changes(values: ArrayLike) -> NDArray[np.intp]:
    """Indices ``i`` where ``values < 0`` differs between ``values[i]`` and ``values[i+1]``.

    Each is a bracket ``[x[i], x[i+1]]`` of a crossing on the grid ``x`` of the values
    (to be refined by a root finder, see `from_crossings`).

    Parameters
    ----------
    values : array_like of float
        the values on a grid; zero counts as non-negative

    Returns
    -------
    ndarray of int

    See Also
    --------
    beltmdsm.intervals.from_crossings : the set bounded by the refined crossings

    Examples
    --------
    The sign changes between entries 1 and 2 and between 3 and 4:

    >>> sign_changes([1.0, 0.5, -0.2, -1.0, 2.0]).tolist()
    [1, 3]
    """
    negative = np.asarray(values) < 0
    return np.flatnonzero(negative[:-1] != negative[1:])


def from_crossings(
    x: ArrayLike, inside: ArrayLike, crossings: Iterable[float]
) -> list[tuple[float, float]]:
    """The set over the grid ``x`` bounded by its refined crossing points.

    Parameters
    ----------
    x : array_like of float
        the grid, ascending
    inside : array_like of bool
        membership at each grid point
    crossings : sequence of float
        one point per change of membership along the grid (as bracketed by
        `sign_changes`), ascending

    Returns
    -------
    list of (float, float)
        A set that holds at an end of the grid is bounded there by that end.

    Raises
    ------
    ValueError
        if the crossings do not pair up with the changes of membership.

    See Also
    --------
    beltmdsm.intervals.sign_changes : brackets of the crossings on the grid

    Examples
    --------
    Inside at the start of the grid and again from a crossing at 3.5 to its end:

    >>> from_crossings([0, 1, 2, 3, 4], [True, True, False, False, True], [1.5, 3.5])
    [(0.0, 1.5), (3.5, 4.0)]
    """
    x = np.asarray(x, dtype=float)
    inside = np.asarray(inside, dtype=bool)
    bounds = ([x[0]] if inside[0] else []) + list(crossings) + ([x[-1]] if inside[-1] else [])
    if len(bounds) % 2:
        raise ValueError("crossings must have one point per change of membership")
    return [(float(a), float(b)) for a, b in zip(bounds[::2], bounds[1::2])]


def union(a: Iterable[tuple[float, float]]) -> list[tuple[float, float]]:
    """The set as sorted, disjoint intervals: overlapping or touching ones merged.

    Parameters
    ----------
    a : iterable of (float, float)
        intervals in any order, each with ``lo <= hi``

    Returns
    -------
    list of (float, float)

    Raises
    ------
    ValueError
        if an interval has ``lo > hi``.

    See Also
    --------
    beltmdsm.intervals.intersection, beltmdsm.intervals.difference

    Examples
    --------
    ``[0, 1]`` and ``[1, 2]`` touch, so they merge:

    >>> union([(3, 4), (1, 2), (0, 1)])
    [(0.0, 2.0), (3.0, 4.0)]
    """
    out = []
    for lo, hi in sorted((float(lo), float(hi)) for lo, hi in a):
        if lo > hi:
            raise ValueError(f"interval ({lo}, {hi}) has lo > hi")
        if out and lo <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], hi))
        else:
            out.append((lo, hi))
    return out


def intersection(
    a: Iterable[tuple[float, float]], b: Sequence[tuple[float, float]]
) -> list[tuple[float, float]]:
    """``A and B``: sorted, disjoint intervals (a single shared point is kept).

    Parameters
    ----------
    a, b : sequence of (float, float)
        two sets of intervals

    Returns
    -------
    list of (float, float)

    See Also
    --------
    beltmdsm.intervals.union, beltmdsm.intervals.clip

    Examples
    --------
    The overlap ``[1, 2]`` and the shared point 3:

    >>> intersection([(0, 2), (3, 4)], [(1, 3)])
    [(1.0, 2.0), (3.0, 3.0)]
    """
    out = []
    for l1, h1 in union(a):
        for l2, h2 in union(b):
            lo, hi = max(l1, l2), min(h1, h2)
            if lo <= hi:
                out.append((lo, hi))
    return out


def difference(
    a: Iterable[tuple[float, float]], b: Iterable[tuple[float, float]]
) -> list[tuple[float, float]]:
    """``A minus B`` up to the end points: sorted, disjoint intervals of positive length.

    The pieces of A left between the intervals of B; end points shared with B are
    kept (the sets are compared by their length), and pieces of zero length dropped.

    Parameters
    ----------
    a, b : iterable of (float, float)
        two sets of intervals

    Returns
    -------
    list of (float, float)

    See Also
    --------
    beltmdsm.intervals.symmetric_difference

    Examples
    --------
    Cutting ``[1, 2]`` out of ``[0, 4]`` leaves two pieces, with the cut's ends kept:

    >>> difference([(0, 4)], [(1, 2)])
    [(0.0, 1.0), (2.0, 4.0)]
    """
    out = []
    cuts = union(b)
    for lo, hi in union(a):
        for l2, h2 in cuts:
            if h2 <= lo or l2 >= hi:
                continue
            if l2 > lo:
                out.append((lo, l2))
            lo = max(lo, h2)
            if lo >= hi:
                break
        if lo < hi:
            out.append((lo, hi))
    return out


def symmetric_difference(
    a: Sequence[tuple[float, float]], b: Sequence[tuple[float, float]]
) -> list[tuple[float, float]]:
    """``A xor B`` (up to the end points, as in `difference`).

    Parameters
    ----------
    a, b : sequence of (float, float)
        two sets of intervals

    Returns
    -------
    list of (float, float)

    See Also
    --------
    beltmdsm.intervals.difference, beltmdsm.intervals.jaccard

    Examples
    --------
    ``[0, 2]`` and ``[1, 3]`` differ on ``[0, 1]`` and ``[2, 3]``:

    >>> symmetric_difference([(0, 2)], [(1, 3)])
    [(0.0, 1.0), (2.0, 3.0)]
    """
    return union(difference(a, b) + difference(b, a))


def clip(a: Iterable[tuple[float, float]], lo: float, hi: float) -> list[tuple[float, float]]:
    """``A`` within ``[lo, hi]``.

    Parameters
    ----------
    a : iterable of (float, float)
        a set of intervals
    lo, hi : float
        the window

    Returns
    -------
    list of (float, float)

    See Also
    --------
    beltmdsm.intervals.intersection

    Examples
    --------
    >>> clip([(0, 2), (3, 5)], 1, 4)
    [(1.0, 2.0), (3.0, 4.0)]
    """
    return intersection(a, [(lo, hi)])


def hull(a: Sequence[tuple[float, float]]) -> tuple[float, float]:
    """``(lowest lo, highest hi)`` of a non-empty set.

    Parameters
    ----------
    a : sequence of (float, float)
        a non-empty set of intervals

    Returns
    -------
    (float, float)

    Raises
    ------
    ValueError
        if the set is empty.

    See Also
    --------
    beltmdsm.intervals.union

    Examples
    --------
    >>> hull([(2.0, 3.0), (0.5, 1.0)])
    (0.5, 3.0)
    """
    if not a:
        raise ValueError("the hull of an empty set is undefined")
    return min(lo for lo, _ in a), max(hi for _, hi in a)


def length(a: Iterable[tuple[float, float]]) -> float:
    """Total length of the set (overlaps counted once).

    Parameters
    ----------
    a : iterable of (float, float)
        a set of intervals

    Returns
    -------
    float

    See Also
    --------
    beltmdsm.intervals.jaccard

    Examples
    --------
    ``[0, 2]`` and ``[1, 3]`` overlap on ``[1, 2]``, which counts once: 3, not 4.

    >>> length([(0, 2), (1, 3)])
    3.0
    """
    return sum(hi - lo for lo, hi in union(a))


def jaccard(a: Sequence[tuple[float, float]], b: Sequence[tuple[float, float]]) -> float:
    """Jaccard overlap ``|A and B| / |A or B|`` of two sets (1 = identical).

    Two sets of zero length give 1. Points (zero-length intervals) count through
    the grid resolution only, so callers pass ranges widened by half a grid step.

    Parameters
    ----------
    a, b : sequence of (float, float)
        two sets of intervals

    Returns
    -------
    float
        in ``[0, 1]``

    See Also
    --------
    beltmdsm.intervals.symmetric_difference

    Examples
    --------
    ``[0, 2]`` and ``[1, 3]`` share 1 of their 3 units of length:

    >>> round(jaccard([(0, 2)], [(1, 3)]), 4)
    0.3333
    """
    inter = length(intersection(a, b))
    total = length(a) + length(b) - inter
    return 1.0 if total == 0 else inter / total


def format_intervals(
    a: Iterable[tuple[float, float]], spec: str = ".2f", empty: str = "none"
) -> str:
    """``[lo, hi], ...`` with each number formatted by ``spec``; ``empty`` for no interval.

    Examples
    --------
    >>> format_intervals([(0.0, 8.5214)], ".3f")
    '[0.000, 8.521]'
    """
    return ", ".join(f"[{lo:{spec}}, {hi:{spec}}]" for lo, hi in a) or empty
