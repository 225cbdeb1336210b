"""Landing a start on a known attractor of the period map: stopped as soon as it is claimed.

`land` iterates the one-period map (`one_period_map`) from a start only until a known
attractor claims it, as Attractors.jl's recurrence approach does, instead of running it
to the end and classifying it by its spectrum; `beltmdsm.basin.basins` runs it per
start of a grid on its executors and caches it.

* A periodic attractor of ``k`` points claims a start that comes within its claim
  radius of one of them and is closer still one cycle (``k`` periods) later: the
  contraction its neighbourhood shows, which a trajectory passing by on its way
  elsewhere does not.
* The claim radius is measured on the map, not assumed (`claim_radii`): a pilot of the
  starts is claimed within `IDENTIFY_TOL` only, and each periodic attractor's radius is
  then half the closest approach to its points of any pilot trajectory that went
  elsewhere or nowhere, or of another known attractor's points (at most `LARGEST`):
  the edge of its basin is at least that far.
  At the base set, Vb = 3.88, the 4T lock's radius is 0.2 and the T-periodic
  response's 0.064 (a trajectory bound for the 4T lock passes 0.13 from it), and a
  start is claimed after 27 periods on average instead of 63, with the same labels
  (benchmarks/bench_basins.py). A quadratic Lyapunov function of the orbit's
  monodromy (the linearised neighbourhood, ``M^T S M - S = -I``) was tried first: the
  closed-form map is linear only within 0.003 of the 4T orbit (a stick-slip decision
  near its third point), far inside `IDENTIFY_TOL`, so it claimed nothing earlier.
* Any other attractor (a closed curve, a cloud of points) claims a start after
  `CONFIRM` consecutive periods within its tolerance (`tolerance`).

Distances are in the map's shooting state, the largest component's, relative to
``1 + |x|``. ``known`` is a list of ``(label, points, radius, k)``: the label, the
attractor's points (`attractor_points`), its claim radius and ``k`` (its period in
excitation periods; 0 where it is not periodic).
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from ..errors import NoPeriodicResponse
from ..model import Model
from ..periodic.base import PeriodMap
from ..periodic.engines import period_map
from .classification import Attractor

__all__ = [
    "land",
    "claim_radii",
    "attractor_points",
    "tolerance",
    "same_attractor",
    "one_period_map",
    "distances",
    "CONFIRM",
    "IDENTIFY_TOL",
    "LARGEST",
]

#: Consecutive periods a start must stay on an attractor that is not a periodic
#: response (a curve or a cloud of points) to be claimed by it.
CONFIRM = 20
#: The claim radius (relative to ``1 + |x|``) of an attractor before the pilot has
#: measured one, and the least (`land`, `claim_radii`). The basins here are O(1) wide (the
#: T-periodic response's at Vb = 3.88 about 2 m by 3 m/s, 30 times this at |x| = 6).
IDENTIFY_TOL = 1e-2
#: The largest claim radius of a periodic attractor (relative, as `IDENTIFY_TOL`).
LARGEST = 0.2


@functools.lru_cache(maxsize=4)
def one_period_map(model: Model, general: bool = False) -> PeriodMap:
    """The one-period map of ``model``, kept per process (a worker builds it once).

    Parameters
    ----------
    model : Model
    general : bool
        The general engine (the full state is shot in: a plane with a normal axis; the
        closed-form map keeps the normal motion on its periodic orbit).

    Returns
    -------
    PeriodMap

    Raises
    ------
    ValueError
        Without a periodic excitation.

    See Also
    --------
    beltmdsm.periodic.engines.period_map

    Examples
    --------
    >>> from beltmdsm import Model
    >>> one_period_map(Model(Vb=3.88)).engine
    'closed_form'
    """
    return period_map(model, engine="general" if general else None)


def distances(x: ArrayLike, known: list) -> list[float]:
    """The relative distance of the shooting state ``x`` from each known attractor's
    points (module docstring).

    Parameters
    ----------
    x : array_like (n,)
    known : list of (label, points, radius, k)

    Returns
    -------
    list of float

    Raises
    ------
    ValueError
        Where ``x`` and the points differ in size.

    See Also
    --------
    land

    Examples
    --------
    >>> import numpy as np
    >>> distances([1.0, 1.0], [(0, np.array([[1.0, 0.0]]), 0.01, 1)])
    [0.5]
    """
    scale = 1.0 + float(np.max(np.abs(x)))
    return [float(np.min(np.max(np.abs(points - x), axis=1))) / scale for _, points, *_ in known]


def land(
    model: Model, general: bool, start: ArrayLike, known: list, max_periods: int
) -> dict[str, Any]:
    """Iterate the period map from ``start`` until a known attractor claims it (module
    docstring).

    Parameters
    ----------
    model : Model
    general : bool
        The map's engine (`one_period_map`).
    start : array_like (4,) or the map's shooting state
    known : list of (label, points, radius, k)
    max_periods : int
        Periods iterated at most.

    Returns
    -------
    dict
        ``{"label", "periods", "final", "failed", "approach"}``: the label (None if
        unclaimed after ``max_periods`` or where the map failed), the periods iterated,
        the shooting state reached (a list; None where the map failed), the failure's
        message, and the closest approach to each known attractor on the way (a list,
        in the order of ``known``: `claim_radii` reads it). JSON-ready: it is cached.

    Raises
    ------
    ValueError
        For a start of the wrong size. A map that fails on the way (a run that cannot
        go on) is no exception: ``failed`` says why.

    See Also
    --------
    claim_radii : the radii measured from pilot landings.
    beltmdsm.basin.basins.basins : a grid of starts.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.classification import periodic_attractor
    >>> m = Model(Vb=3.88)
    >>> lock = periodic_attractor(m, t_end=300.0)  # the 4T lock
    >>> known = [(0, attractor_points(one_period_map(m), lock), IDENTIFY_TOL, 4)]
    >>> row = land(m, False, [2.0, -9.0, 0.0, 0.0], known, 500)
    >>> row["label"], row["periods"]
    (0, 46)
    """
    pmap = one_period_map(model, general)
    x = pmap.guess(np.asarray(start, dtype=float))
    approach = [np.inf] * len(known)
    candidate, run = None, [0] * len(known)  # (index, period, distance); runs of k = 0

    def row(label, n, final, failed=None):
        return {
            "label": label,
            "periods": n,
            "final": final,
            "failed": failed,
            "approach": [float(a) for a in approach],
        }

    for n in range(1, max_periods + 1):
        try:
            x = pmap.step(x)
        except NoPeriodicResponse as err:
            return row(None, n, None, str(err))
        d = distances(x, known)
        approach = [min(a, b) for a, b in zip(approach, d)]
        if candidate is not None:
            i, n0, d0 = candidate
            if n == n0 + known[i][3]:
                if d[i] < d0:
                    return row(known[i][0], n, x.tolist())
                candidate = None
        for i, (label, _, radius, k) in enumerate(known):
            inside = d[i] <= radius
            run[i] = run[i] + 1 if inside else 0
            if k == 0 and run[i] >= CONFIRM:
                return row(label, n, x.tolist())
            if k > 0 and inside and candidate is None:
                candidate = (i, n, d[i])
    return row(None, max_periods, x.tolist())


def claim_radii(known: list, rows: list[dict]) -> list:
    """``known`` with each periodic attractor's claim radius measured from pilot landings.

    Half the closest approach to its points of any pilot trajectory that ended
    elsewhere or nowhere, or of another known attractor's points (states bound
    elsewhere too): the basin's edge is at least that far. Within [`IDENTIFY_TOL`,
    `LARGEST`]; the other attractors keep theirs.

    Parameters
    ----------
    known : list of (label, points, radius, k)
    rows : list of dict
        `land`'s results of the pilot starts with this ``known``.

    Returns
    -------
    list of (label, points, radius, k)

    Raises
    ------
    IndexError
        For rows landed with another ``known``.

    See Also
    --------
    land

    Examples
    --------
    >>> import numpy as np
    >>> known = [(0, np.zeros((1, 2)), IDENTIFY_TOL, 1), (1, np.ones((1, 2)), 0.05, 0)]
    >>> rows = [{"label": 0, "approach": [0.0, 0.5]}, {"label": None, "approach": [0.3, 0.4]}]
    >>> [round(r, 6) for _, _, r, _ in claim_radii(known, rows)]
    [0.15, 0.05]
    """
    out = []
    for i, (label, points, radius, k) in enumerate(known):
        if k > 0:
            foreign = [r["approach"][i] for r in rows if r["label"] != label]
            foreign += [
                min(distances(x, [known[i]])[0] for x in other)
                for j, (_, other, _, _) in enumerate(known)
                if j != i
            ]
            radius = min(max(0.5 * min(foreign, default=np.inf), IDENTIFY_TOL), LARGEST)
        out.append((label, points, radius, k))
    return out


def attractor_points(pmap: PeriodMap, attractor: Attractor) -> NDArray[np.float64]:
    """An attractor's stroboscopic points in the map's shooting state.

    Parameters
    ----------
    pmap : PeriodMap
        The one-period map.
    attractor : Attractor

    Returns
    -------
    ndarray (k, n)
        Periodic: its ``k`` points in order, by the map from its state; else its samples.

    Raises
    ------
    NoPeriodicResponse
        Where the map fails from the periodic attractor's state.

    See Also
    --------
    land

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.classification import periodic_attractor
    >>> m = Model(Vb=3.88)
    >>> attractor_points(one_period_map(m), periodic_attractor(m, t_end=300.0)).shape
    (4, 2)
    """
    if attractor.kind == "periodic":
        x = pmap.guess(attractor.state)
        out = [x]
        for _ in range(attractor.periods - 1):
            x = pmap.step(x)
            out.append(x)
        return np.array(out)
    return pmap.shooting(attractor.points)


def tolerance(attractor: Attractor, points: NDArray[np.float64]) -> float:
    """The claim radius of an attractor before any is measured.

    Periodic: `IDENTIFY_TOL`; a curve or a cloud: twice its largest gap between
    neighbours as well (its points are samples, not the whole set).

    Parameters
    ----------
    attractor : Attractor
    points : ndarray (m, n)
        Its points (`attractor_points`).

    Returns
    -------
    float
        Relative to ``1 + |x|``.

    Raises
    ------
    ValueError
        For points that are not 2-D.

    See Also
    --------
    claim_radii

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.classification import periodic_attractor
    >>> a = periodic_attractor(Model(Vb=3.88), t_end=300.0)
    >>> tolerance(a, a.points[:, :2])
    0.01
    """
    if attractor.kind == "periodic" or len(points) < 2:
        return IDENTIFY_TOL
    d, _ = cKDTree(points).query(points, k=2)
    scale = 1.0 + float(np.max(np.abs(points)))
    return max(IDENTIFY_TOL, 2.0 * float(np.max(d[:, 1])) / scale)


def same_attractor(
    a: Attractor, pa: NDArray[np.float64], b: Attractor, pb: NDArray[np.float64]
) -> bool:
    """Whether two classified attractors are one: kind and period agree and every point
    of ``b`` is within the larger of their tolerances of a point of ``a``.

    Parameters
    ----------
    a, b : Attractor
    pa, pb : ndarray
        Their points (`attractor_points`).

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        For points of different sizes.

    See Also
    --------
    tolerance

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.attractors.classification import periodic_attractor
    >>> a = periodic_attractor(Model(Vb=3.88), t_end=300.0)
    >>> same_attractor(a, a.points, a, a.points[::-1])
    True
    """
    if a.kind != b.kind or a.periods != b.periods:
        return False
    scale = 1.0 + float(np.max(np.abs(pa)))
    tol = max(tolerance(a, pa), tolerance(b, pb)) * scale
    near = [float(np.min(np.max(np.abs(pa - x), axis=1))) for x in pb]
    return max(near) <= max(tol, 1e-6 * scale)
