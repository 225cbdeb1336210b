"""Basins of attraction without excitation: steady sliding and the self-excited cycles.

`beltmdsm.basin.basins.basins` hands an autonomous model here. There is no
excitation period to take a phase from, so the starts are states: a grid of a plane of
two states, the others at steady sliding's (Eq. 9). Each start lands on an attractor
of `beltmdsm.attractors.self_excited.Landscape`: steady sliding where it is stable, a
stable cycle (stick-slip or pure slip) of the branch through the Hopf point or of the
seed from the stick end. A start is decided by the region of the plane the cycles
assign to one attractor (no run at all), or as soon as it sticks (every stick ends
at one state, so a start that sticks lands where that state lands: exact), else by a
run that stops at the first of those (`Landscape.land`). The map marks the
attractors and the unstable cycles that bound the basins (``Basins.boundaries``).
"""

from __future__ import annotations

import numpy as np

from ..attractors.classification import Attractor
from ..attractors.self_excited import InvariantSet, Landscape
from ..model import Model
from .basin_stability import AXES, CHUNK, _run_chunks, landscape_of

__all__ = ["self_excited_basins", "as_attractor", "MARKS"]

#: Points of a cycle drawn on the map.
MARKS = 48


def as_attractor(s: InvariantSet) -> Attractor:
    """An `InvariantSet` as the `Attractor` a basin map lists: steady sliding
    (``equilibrium``, its eigenvalues' real parts as exponents) or a cycle
    (``periodic``, ``ln |mu| / T`` of its multipliers).

    Examples
    --------
    >>> s = InvariantSet("equilibrium", True, np.zeros(4), None, 0, np.zeros((1, 4)), -0.1)
    >>> as_attractor(s).kind, as_attractor(s).lyapunov
    ('equilibrium', -0.1)
    """
    if s.kind == "equilibrium":
        return Attractor(
            "equilibrium", None, None, None, s.leading, 0.0, np.array([s.leading]),
            "steady sliding (Eq. 9): the unforced Jacobian's eigenvalues have negative "
            "real parts", s.state, s.state[None, :],
        )  # fmt: skip
    lyap = float(np.log(max(s.leading, 1e-300)) / s.period)
    slip = "stick-slip" if s.n_sticks else "pure-slip"
    step = max(len(s.orbit) // MARKS, 1)
    return Attractor(
        "periodic", 1, None, None, lyap, 0.0, np.array([0.0, lyap]),
        f"a stable {slip} self-excited cycle of period {s.period:.6g} s (shooting with a "
        "phase condition, beltmdsm/cycles/cycle.py)", s.state, s.orbit[::step],
    )  # fmt: skip


def self_excited_basins(
    model: Model,
    *,
    x: str,
    x_range: tuple[float, float] | None,
    y: str,
    y_range: tuple[float, float] | None,
    points: int,
    executor=None,
    cache_dir=None,
    branch=None,
    landscape: Landscape | None = None,
):
    """The basin map of an autonomous model on a ``points x points`` grid (module
    docstring); the arguments are `beltmdsm.basin.basins.basins`'s, checked there.

    Returns
    -------
    dict
        ``xs``, ``ys``, ``labels`` (points x points), ``attractors`` (a list of
        ``(Attractor, fraction, points, period)``), ``boundaries`` (the unstable
        cycles' orbits), from which `beltmdsm.basin.basins.basins` builds its
        `beltmdsm.basin.basins.Basins`.

    See Also
    --------
    beltmdsm.basin.basins.basins
    beltmdsm.attractors.self_excited.landscape
    """
    ls = landscape if landscape is not None else landscape_of(model, branch)
    ix, iy = AXES.index(x), AXES.index(y)
    xs = np.linspace(*_span(x_range, ls, ix), points)
    ys = np.linspace(*_span(y_range, ls, iy), points)
    starts = np.tile(ls.equilibrium.state, (points * points, 1))
    gx, gy = np.meshgrid(xs, ys)
    starts[:, ix], starts[:, iy] = gx.ravel(), gy.ravel()
    chunks = [starts[i : i + CHUNK] for i in range(0, len(starts), CHUNK)]
    rows, interrupted = _run_chunks(ls, chunks, 500.0, executor, cache_dir, False)
    if interrupted:
        raise KeyboardInterrupt("basins: stopped (a grid is kept only through its cache)")
    labels = np.array([v for r in rows for v in r["labels"]], dtype=int)
    attractors = []
    for i, a in enumerate(ls.attractors):
        named = as_attractor(a)
        attractors.append((named, float(np.sum(labels == i)) / labels.size, named.points, a.period))
    return {
        "xs": xs,
        "ys": ys,
        "labels": labels.reshape(points, points),
        "attractors": attractors,
        "boundaries": [c.orbit for c in ls.cycles if not c.stable],
    }


def _span(given, ls, index):
    if given is not None:
        return given
    values = np.concatenate(
        [ls.equilibrium.orbit[:, index], *(c.orbit[:, index] for c in ls.cycles)]
    )
    c, w = 0.5 * (values.min() + values.max()), max(float(np.ptp(values)), 1.0)
    return c - 0.75 * w, c + 0.75 * w
