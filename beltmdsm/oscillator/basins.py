"""Basins of attraction of any model on a plane of two of its states.

Each start of a ``points x points`` grid (the other states at steady sliding's, or at
rest where the model is forced) runs until it provably lands (Attractors.jl's
recurrence, with the exact events of `beltmdsm.oscillator.hybrid.flow`):

* unforced, on **steady sliding** where it is within ``1e-4`` (relative) of the
  equilibrium, in its slip mode, and the equilibrium is stable (its derived Hurwitz
  determinants): there the slip velocity is ``-Vb`` to ``1e-4``, the run stays in the
  smooth slip mode and the linearisation's error is of order ``1e-8``;
* unforced, on a **stick-slip cycle** where the state at the end of a stick recurs:
  a stick-slip cycle passes through one stick-end state per stick, so the recurrence
  is exact up to ``tol`` and gives the number of sticks per period;
* forced, on a **periodic response** of ``k`` excitation periods where the
  stroboscopic state (every period, at phase 0) recurs after ``k``;
* else, after ``t_end``, on a **slip cycle** (unforced, no stick in the last window)
  named by the range of its first state, or ``unresolved``.

An attractor is identified by its kind and a representative state (the least, in
lexicographic order, of the recurring states), and the labels are numbered by sorting
the attractors found, not by which start found one first: the map does not depend on
the executor's order.
"""

from __future__ import annotations

import math
from concurrent.futures import Executor
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .equilibria import steady_sliding
from .hybrid import flow
from .system import STICK, System

__all__ = [
    "Basins", "BasinAttractor", "basins", "land", "merge", "run_starts", "Stability",
    "basin_stability",
]  # fmt: skip

#: Within this of stable steady sliding (relative), a start has landed on it.
_NEAR = 1e-4
#: A slip cycle's range of its first state agrees over two windows to this (relative).
_SAME = 1e-3


@dataclass(frozen=True)
class BasinAttractor:
    """An attractor a start lands on.

    Attributes
    ----------
    kind : str
        ``"steady_sliding"``, ``"stick_slip"``, ``"periodic"`` (forced), ``"slip_cycle"``
        or ``"unresolved"``.
    periods : int
        Sticks per period (stick-slip), excitation periods (forced), else 1 (0 where
        unresolved).
    state : tuple of float
        Its representative state (a stick-slip cycle's stick-end state, a forced
        response's state at phase 0; a slip cycle's range of its first state).
    seed : tuple of float
        A state on it, where a shooting can start (not part of its identity).
    """

    kind: str
    periods: int
    state: tuple[float, ...]
    seed: tuple[float, ...] = field(default=(), compare=False, repr=False)


@dataclass(repr=False)
class Basins:
    """Which attractor each start of a plane lands on.

    Attributes
    ----------
    system : System
    x, y : str
        The states of the plane's axes (the model's names).
    xs, ys : ndarray
        The grid's values.
    labels : ndarray (len(ys), len(xs)) of int
        Index into ``attractors`` (-1: unresolved).
    attractors : list of BasinAttractor
        Sorted by kind and state.

    See Also
    --------
    basins : makes it.
    """

    system: System
    x: str
    y: str
    xs: NDArray[np.float64]
    ys: NDArray[np.float64]
    labels: NDArray[np.int64]
    attractors: list[BasinAttractor]

    def shares(self) -> list[float]:
        """The share of the starts that land on each attractor."""
        return [float(np.mean(self.labels == i)) for i in range(len(self.attractors))]

    def __repr__(self) -> str:
        parts = ", ".join(
            f"{a.kind}({a.periods}) {s:.0%}" for a, s in zip(self.attractors, self.shares())
        )
        n = self.labels.size
        return f"Basins({self.system!r}; {n} starts on ({self.x}, {self.y}): {parts})"

    def as_dict(self) -> dict:
        return {
            **self.system.as_dict(),
            "x": self.x,
            "y": self.y,
            "xs": self.xs.tolist(),
            "ys": self.ys.tolist(),
            "labels": self.labels.tolist(),
            "attractors": [
                {"kind": a.kind, "periods": a.periods, "state": list(a.state), "share": s}
                for a, s in zip(self.attractors, self.shares())
            ],
        }


def _close(a, b, tol) -> bool:
    return bool(np.max(np.abs(a - b)) <= tol * (1.0 + np.max(np.abs(b))))


def _least(states) -> tuple[float, ...]:
    return min(tuple(float(v) for v in s) for s in states)


def land(
    system: System, y0: ArrayLike, *, t_end: float = 500.0, tol: float = 1e-6, max_periods: int = 8
) -> BasinAttractor:
    """The attractor the run from ``y0`` lands on (module docstring)."""
    y0 = np.asarray(y0, dtype=float)
    T = system.excitation_period()
    if T is not None:
        return _land_forced(system, y0, T, t_end, tol, max_periods)
    eq = steady_sliding(system)
    t, y, mode = 0.0, y0, None
    ends: list[tuple[float, NDArray[np.float64]]] = []
    chunk = 10.0
    stick_end = lambda switch, n: switch[1] == STICK  # noqa: E731
    while t < t_end:
        end = flow(system, t, y, min(t + chunk, t_end), mode=mode, stop=stick_end)
        t, y, mode = end.t, end.y, end.mode
        if end.status == "zeno":
            break
        if end.status == "stopped":
            for j in range(len(ends) - 1, max(-1, len(ends) - 1 - max_periods), -1):
                if _close(y, ends[j][1], tol):
                    cycle = [s for _, s in ends[j:]]
                    least = _least(cycle)
                    return BasinAttractor("stick_slip", len(cycle), least, least)
            ends.append((t, y.copy()))
        elif eq.stable and mode == eq.mode and _close(y, eq.state, _NEAR):
            state = tuple(float(v) for v in eq.state)
            return BasinAttractor("steady_sliding", 1, state, state)
    if not ends or ends[-1][0] < t - 5 * chunk:
        # no stick for a while: a slip cycle where the range of the first state is the
        # same over two windows (1e-3), named by it; else still on its way: unresolved
        spans = []
        for _ in range(2):
            samples: list = []
            end = flow(system, t, y, t + 5 * chunk, mode=mode, dt=0.01, samples=samples)
            first = np.concatenate([ys[:, 0] for _, ys, _ in samples])
            spans.append((float(first.min()), float(first.max())))
            t, y, mode = end.t, end.y, end.mode
        (lo0, hi0), (lo, hi) = spans
        width = hi - lo
        steady = max(abs(lo - lo0), abs(hi - hi0)) <= _SAME * max(width, tol)
        if steady and width > 10 * tol * (1.0 + abs(hi)) and not end.switches:
            return BasinAttractor(
                "slip_cycle", 1, (round(lo, 3), round(hi, 3)), tuple(map(float, y))
            )
    return BasinAttractor("unresolved", 0, ())


def _land_forced(system, y, T, t_end, tol, max_periods):
    strobe = [y.copy()]
    mode = None
    for k in range(1, int(math.ceil(t_end / T)) + 1):
        end = flow(system, (k - 1) * T, y, k * T, mode=mode)
        y, mode = end.y, end.mode
        if end.status == "zeno":
            break
        for p in range(1, min(max_periods, len(strobe)) + 1):
            if _close(y, strobe[-p], tol):
                least = _least(strobe[-p:])
                return BasinAttractor("periodic", p, least, least)
        strobe.append(y.copy())
    return BasinAttractor("unresolved", 0, ())


def _start(name, friction, params, y0, t_end, tol, max_periods):
    return land(System(name, friction, **params), y0, t_end=t_end, tol=tol, max_periods=max_periods)


def basins(
    system: System,
    x: str,
    x_range: tuple[float, float],
    y: str,
    y_range: tuple[float, float],
    *,
    points: int = 11,
    t_end: float = 500.0,
    tol: float = 1e-6,
    max_periods: int = 8,
    executor: Executor | None = None,
) -> Basins:
    """Which attractor each start of a plane of two states lands on (module docstring).

    Parameters
    ----------
    system : System
    x, y : str
        Two of the model's states (``system.states``), the plane's axes.
    x_range, y_range : (float, float)
        The axes' ends, ``lo < hi``.
    points : int
        Starts per axis, >= 2.
    t_end : float
        The longest run of a start [s].
    tol : float
        The recurrence and the distance to steady sliding, relative to ``1 + |state|``.
    max_periods : int
        The longest recurrence looked for (sticks or excitation periods).
    executor : concurrent.futures.Executor, optional
        Where the starts run (None: here).

    Returns
    -------
    Basins

    Raises
    ------
    ValueError
        A state the model does not have (its states listed), a range not ``lo < hi``,
        fewer than 2 points.

    See Also
    --------
    land : one start.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> s = System("belt_1dof", friction="stribeck", Vb=2.5)
    >>> b = basins(s, "x", (2.0, 3.0), "x_dot", (-3.0, 0.0), points=2, t_end=300.0)
    >>> [a.kind for a in b.attractors]
    ['steady_sliding', 'stick_slip']
    """
    _check_plane(system, x, x_range, y, y_range)
    if not (isinstance(points, int) and points >= 2):
        raise ValueError(f"points={points!r}: not a whole number >= 2")
    base = _base(system)
    xs, ys = np.linspace(*x_range, points), np.linspace(*y_range, points)
    ix, iy = system.states.index(x), system.states.index(y)
    starts = []
    for vy in ys:
        for vx in xs:
            s = base.copy()
            s[ix], s[iy] = vx, vy
            starts.append(s)
    found = run_starts(system, starts, t_end, tol, max_periods, executor)
    merged, labels = merge(found, tol)
    return Basins(system, x, y, xs, ys, labels.reshape(points, points), merged)


def _check_plane(system, x, x_range, y, y_range) -> None:
    for axis, name in (("x", x), ("y", y)):
        if name not in system.states:
            raise ValueError(
                f"{axis}={name!r}: not a state of model {system.name!r} "
                f"({', '.join(system.states)})"
            )
    for axis, (lo, hi) in (("x_range", x_range), ("y_range", y_range)):
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ValueError(f"{axis}=({lo!r}, {hi!r}): not lo < hi")


def _base(system) -> NDArray[np.float64]:
    """The start's other states: steady sliding's (unforced), else rest."""
    if system.excitation_period() is None:
        return steady_sliding(system).state.copy()
    return np.zeros(len(system.states))


def run_starts(
    system: System,
    starts: list[NDArray[np.float64]],
    t_end: float,
    tol: float,
    max_periods: int,
    executor: Executor | None,
) -> list[BasinAttractor]:
    """`land` of every start, here or on ``executor`` (each worker rebuilds the
    `System` from plain values: a `System` holds a module)."""
    args = (system.name, system.friction, dict(system.params))
    jobs = [(*args, s, t_end, tol, max_periods) for s in starts]
    if executor is None:
        return [_start(*job) for job in jobs]
    return list(executor.map(_start, *zip(*jobs)))


def merge(
    found: list[BasinAttractor], tol: float
) -> tuple[list[BasinAttractor], NDArray[np.int64]]:
    """The distinct attractors of ``found``, sorted by kind and state, and each start's
    index into them (-1: unresolved). Two representatives within ``100 tol`` of each
    other are one attractor (found from two starts)."""
    known = sorted({a for a in found if a.kind != "unresolved"}, key=lambda a: (a.kind, a.state))
    merged: list[BasinAttractor] = []
    index = {}
    for a in known:
        same = next(
            (j for j, b in enumerate(merged) if b.kind == a.kind and b.periods == a.periods
             and len(a.state) == len(b.state)
             and _close(np.array(a.state), np.array(b.state), 100 * tol)),
            None,
        )  # fmt: skip
        if same is None:
            merged.append(a)
            same = len(merged) - 1
        index[a] = same
    return merged, np.array([index.get(a, -1) for a in found], dtype=np.int64)


@dataclass(repr=False)
class Stability:
    """Basin stability by sampling: each attractor's share of random starts.

    Attributes
    ----------
    system : System
    x, y : str
        The states of the box's axes.
    box : ((float, float), (float, float))
    samples : int
    attractors : list of BasinAttractor
    fractions, errors : ndarray (len(attractors),)
        Each share and its standard error ``sqrt(p (1 - p) / N)`` (bSTAB, pyBasin).
    unresolved : float
        The share of starts that landed on nothing within ``t_end``.

    See Also
    --------
    basin_stability : makes it.
    """

    system: System
    x: str
    y: str
    box: tuple
    samples: int
    attractors: list[BasinAttractor]
    fractions: NDArray[np.float64]
    errors: NDArray[np.float64]
    unresolved: float

    def __repr__(self) -> str:
        parts = ", ".join(
            f"{a.kind}({a.periods}) {p:.3f} +- {e:.3f}"
            for a, p, e in zip(self.attractors, self.fractions, self.errors)
        )
        return f"Stability({self.system!r}; {self.samples} starts: {parts})"

    def as_dict(self) -> dict:
        return {
            **self.system.as_dict(),
            "x": self.x,
            "y": self.y,
            "box": [list(self.box[0]), list(self.box[1])],
            "samples": self.samples,
            "attractors": [
                {
                    "kind": a.kind,
                    "periods": a.periods,
                    "state": list(a.state),
                    "fraction": float(p),
                    "error": float(e),
                }
                for a, p, e in zip(self.attractors, self.fractions, self.errors)
            ],  # fmt: skip
            "unresolved": self.unresolved,
        }


def basin_stability(
    system: System,
    x: str,
    x_range: tuple[float, float],
    y: str,
    y_range: tuple[float, float],
    *,
    samples: int = 100,
    seed: int = 0,
    t_end: float = 500.0,
    tol: float = 1e-6,
    max_periods: int = 8,
    executor: Executor | None = None,
) -> Stability:
    """Each attractor's share of ``samples`` uniform random starts in a box of two
    states (the others as `basins` sets them), with its standard error.

    Parameters
    ----------
    system, x, x_range, y, y_range, t_end, tol, max_periods, executor
        As `basins`.
    samples : int
        Starts, >= 1.
    seed : int
        Of the random starts (numpy's default generator): the same starts for the same
        seed, whatever the system.

    Returns
    -------
    Stability

    See Also
    --------
    basins : the same on a grid.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> s = System("belt_1dof", friction="stribeck", Vb=1.5)
    >>> r = basin_stability(s, "x", (0.0, 4.0), "x_dot", (-3.0, 1.0), samples=3)
    >>> [(a.kind, float(p)) for a, p in zip(r.attractors, r.fractions)]
    [('stick_slip', 1.0)]
    """
    _check_plane(system, x, x_range, y, y_range)
    if not (isinstance(samples, int) and samples >= 1):
        raise ValueError(f"samples={samples!r}: not a whole number >= 1")
    draws = np.random.default_rng(seed).random((samples, 2))
    base = _base(system)
    ix, iy = system.states.index(x), system.states.index(y)
    starts = []
    for u, v in draws:
        s = base.copy()
        s[ix] = x_range[0] + u * (x_range[1] - x_range[0])
        s[iy] = y_range[0] + v * (y_range[1] - y_range[0])
        starts.append(s)
    found = run_starts(system, starts, t_end, tol, max_periods, executor)
    merged, labels = merge(found, tol)
    p = np.array([np.mean(labels == i) for i in range(len(merged))])
    errors = np.sqrt(p * (1.0 - p) / samples)
    return Stability(
        system, x, y, (tuple(x_range), tuple(y_range)), samples, merged, p, errors,
        float(np.mean(labels < 0)),
    )  # fmt: skip
