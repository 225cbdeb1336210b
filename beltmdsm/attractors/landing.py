"""Landing a start on a known attractor of the period map: stopped as soon as it is claimed.

Moved whole from beltmdsm/studies/basins.py (its module docstring says how a start is
claimed and how the claim radii are measured); `beltmdsm.studies.basins` runs these per
start on its executors and caches them.
"""

from __future__ import annotations

import functools

import numpy as np

from ..periodic.periodmap import NoPeriodicResponse, period_map

#: Consecutive periods a start must stay on an attractor that is not a periodic
#: response (a curve or a cloud of points) to be claimed by it.
CONFIRM = 20
#: The claim radius (relative to ``1 + |x|``) of an attractor before the pilot has
#: measured one, and the least (`_land`, `_radii`). The basins here are O(1) wide (the
#: T-periodic response's at Vb = 3.88 about 2 m by 3 m/s, 30 times this at |x| = 6).
IDENTIFY_TOL = 1e-2
#: The largest claim radius of a periodic attractor (relative, as `IDENTIFY_TOL`).
LARGEST = 0.2


@functools.lru_cache(maxsize=4)
def _map(model, general=False):
    """The one-period map; the general engine where the plane has a normal axis (the
    closed-form map keeps the normal motion on its periodic orbit)."""
    return period_map(model, engine="general" if general else None)


def _distances(x, known):
    """The relative distance (to ``1 + |x|``) of ``x`` from each known attractor's points."""
    scale = 1.0 + float(np.max(np.abs(x)))
    return [float(np.min(np.max(np.abs(points - x), axis=1))) / scale for _, points, *_ in known]


def _land(model, general, start, known, max_periods):
    """Iterate the period map from ``start`` until a known attractor claims it.

    ``known`` holds ``(label, points, radius, k)``. A periodic attractor of ``k`` phases
    (``k > 0``) claims a start that comes within its radius and is closer still one
    cycle (``k`` periods) later: the contraction its neighbourhood shows, which a
    trajectory passing by on its way elsewhere does not. Any other attractor claims
    after `CONFIRM` consecutive periods within its radius.

    Returns ``{"label", "periods", "final", "failed", "approach"}``: the label (None if
    unclaimed after ``max_periods``), the periods iterated, the shooting state reached,
    and the closest approach to each known attractor on the way (`_radii` reads it).
    """
    pmap = _map(model, general)
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
        d = _distances(x, known)
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


def _radii(known, rows):
    """The claim radius of each periodic attractor: half the closest approach to its
    points of any pilot trajectory that ended elsewhere or nowhere (the basin's edge is
    at least that far), within [`IDENTIFY_TOL`, `LARGEST`]; the others keep theirs."""
    out = []
    for i, (label, points, radius, k) in enumerate(known):
        if k > 0:
            foreign = [r["approach"][i] for r in rows if r["label"] != label]
            radius = min(max(0.5 * min(foreign, default=np.inf), IDENTIFY_TOL), LARGEST)
        out.append((label, points, radius, k))
    return out


def _points(pmap, attractor):
    """An attractor's stroboscopic points in the map's shooting state."""
    if attractor.kind == "periodic":
        x = pmap.guess(attractor.state)
        out = [x]
        for _ in range(attractor.periods - 1):
            x = pmap.step(x)
            out.append(x)
        return np.array(out)
    return pmap.shooting(attractor.points)


def _tolerance(attractor, points):
    """Periodic: `IDENTIFY_TOL`; a curve or a cloud: twice its largest gap between
    neighbours as well (its points are samples, not the whole set)."""
    if attractor.kind == "periodic" or len(points) < 2:
        return IDENTIFY_TOL
    from scipy.spatial import cKDTree

    d, _ = cKDTree(points).query(points, k=2)
    scale = 1.0 + float(np.max(np.abs(points)))
    return max(IDENTIFY_TOL, 2.0 * float(np.max(d[:, 1])) / scale)


def _same(a, pa, b, pb):
    """Whether two classified attractors are one (kind, period and points agree)."""
    if a.kind != b.kind or a.periods != b.periods:
        return False
    scale = 1.0 + float(np.max(np.abs(pa)))
    tol = max(_tolerance(a, pa), _tolerance(b, pb)) * scale
    near = [float(np.min(np.max(np.abs(pa - x), axis=1))) for x in pb]
    return max(near) <= max(tol, 1e-6 * scale)
