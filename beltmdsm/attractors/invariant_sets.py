"""The invariant sets of the model without excitation and where a state lies among them.

`InvariantSet`: steady sliding or a self-excited cycle, with its stability. `Landscape`
(the result of `beltmdsm.attractors.self_excited.landscape`): the equilibrium and the
cycles around it, and which attractor a start reaches (by the nested closed orbits in
the plane of X1 and X1', or by where a stick ends). The plane geometry they use
(`_polygon_area`, `_inside`, `_segment_distance`, `_polar`) is here too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from ..errors import StepTooSmall
from ..integrate.events import integrate_events
from ..integrate.switching import Mode
from ..model import Model
from ..settings import SolverSettings

__all__ = ["InvariantSet", "Landscape"]

#: Starts this close to a cycle's sampled curve (relative to ``1 + |x|``) are run,
#: not decided by region: the chord error of the orbit's samples
#: (`beltmdsm.attractors.self_excited.ORBIT_SAMPLES`) is below 1e-6 on these orbits,
#: the cycle's own error (Newton's residual) below 1e-9.
BAND = 1e-5
#: Longest run of a start [s] (the peers' horizon, pyBasin's t = 500).
T_MAX = 500.0
#: The normal state is at its equilibrium within this (relative) for the plane's rules:
#: above the runs' own drift of it (their tolerance, `RTOL`).
NORMAL_TOL = 1e-6
#: Tolerances of the runs (the period maps' are 1e-10; a decision needs less).
RTOL, ATOL = 1e-8, 1e-10
#: States checked per chunk of a run (one chunk: the period of the equilibrium's pair).
_CHECKS = 32


@dataclass
class InvariantSet:
    """An equilibrium or a cycle of the autonomous model.

    Attributes
    ----------
    kind : {"equilibrium", "cycle"}
    stable : bool
    state : ndarray (4,)
        The equilibrium, or the cycle's state on its section.
    period : float or None
        The cycle's period [s].
    n_sticks : int
        Stick phases per period (0: pure slip).
    orbit : ndarray (m, 4)
        One period sampled (the equilibrium: its state).
    leading : float
        The largest real part of the eigenvalues (equilibrium) or the largest
        ``|multiplier|`` but the trivial one (cycle).

    See Also
    --------
    landscape : computes them.

    Examples
    --------
    >>> s = InvariantSet("equilibrium", True, np.zeros(4), None, 0, np.zeros((1, 4)), -0.1)
    >>> s
    InvariantSet(stable equilibrium)
    """

    kind: str
    stable: bool
    state: NDArray[np.float64] = field(repr=False)
    period: float | None
    n_sticks: int
    orbit: NDArray[np.float64] = field(repr=False)
    leading: float = field(repr=False)

    def __repr__(self) -> str:
        what = "stable" if self.stable else "unstable"
        if self.kind == "equilibrium":
            return f"InvariantSet({what} equilibrium)"
        slip = "stick-slip" if self.n_sticks else "pure-slip"
        return f"InvariantSet({what} {slip} cycle, period {self.period:.6g} s)"

    @property
    def name(self) -> str:
        """``steady sliding``, ``stick-slip cycle`` or ``pure-slip cycle``."""
        if self.kind == "equilibrium":
            return "steady sliding"
        return "stick-slip cycle" if self.n_sticks else "pure-slip cycle"


def _polygon_area(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _inside(xy, curve):
    """Whether each point of ``xy`` lies inside the closed polygon ``curve``."""
    from matplotlib.path import Path

    return Path(curve, closed=False).contains_points(xy)


def _segment_distance(xy, curve, tree):
    """The distance of each point from the closed polyline ``curve``: to the two
    segments at its nearest vertex (exact wherever the spacing is below the distance
    to every other part of the curve)."""
    _, i = tree.query(xy)
    n = len(curve)
    out = np.full(len(xy), np.inf)
    for a, b in ((i - 1) % n, i), (i, (i + 1) % n):
        p, q = curve[a], curve[b]
        d = q - p
        t = np.clip(np.sum((xy - p) * d, axis=1) / np.maximum(np.sum(d * d, axis=1), 1e-300), 0, 1)
        out = np.minimum(out, np.linalg.norm(xy - p - t[:, None] * d, axis=1))
    return out


def _polar(curve, centre):
    """``(theta, r, sine)`` of a closed curve seen from ``centre`` where every ray from
    it meets the curve once (its angle turns one way), sorted by angle; ``sine`` the
    least sine of the angle between the curve and a ray (a radial distance ``d`` is a
    distance of at least ``d * sine``). None for a curve that is not star-shaped."""
    d = curve - centre
    theta = np.arctan2(d[:, 1], d[:, 0])
    turn = np.diff(np.unwrap(np.append(theta, theta[0])))
    if not (np.all(turn > 0) or np.all(turn < 0)):
        return None
    r = np.hypot(d[:, 0], d[:, 1])
    chord = np.roll(curve, -1, axis=0) - curve
    cross = np.abs(d[:, 0] * chord[:, 1] - d[:, 1] * chord[:, 0])
    sine = float(np.min(cross / np.maximum(r * np.hypot(chord[:, 0], chord[:, 1]), 1e-300)))
    order = np.argsort(theta)
    return theta[order], r[order], sine


@dataclass
class Landscape:
    """The invariant sets of an autonomous model at one parameter value and the rules
    that decide a start (module docstring).

    Attributes
    ----------
    model : Model
    equilibrium : InvariantSet
    cycles : list of InvariantSet
        By enclosed area, smallest first.
    attractors : list of InvariantSet
        The stable ones, in the order of the labels: steady sliding first, then the
        cycles from the inside out.
    nested : bool
        The cycles are nested around the equilibrium (the region rule holds).
    stick_end : ndarray (4,) or None
        Where every stick phase ends (`beltmdsm.starts.cycle_seed.stick_end`).
    stick_label : int or None
        The label of the attractor the stick end lands on (None: undecided, or no
        stick end).

    See Also
    --------
    landscape : computes it.
    beltmdsm.basin.basin_stability.basin_stability : samples starts with it.
    """

    model: Model = field(repr=False)
    equilibrium: InvariantSet
    cycles: list[InvariantSet]
    attractors: list[InvariantSet] = field(repr=False)
    nested: bool = field(repr=False)
    stick_end: NDArray[np.float64] | None = field(repr=False)
    stick_label: int | None = field(repr=False, default=None)
    focus: tuple | None = field(repr=False, default=None)
    _trees: list = field(repr=False, default_factory=list)
    _polars: list = field(repr=False, default_factory=list)
    _rules: list = field(repr=False, default_factory=list)

    def __post_init__(self):
        self._derive()

    def _derive(self):
        self._trees = [cKDTree(c.orbit[:, :2]) for c in self.cycles]
        centre = self.equilibrium.state[:2]
        self._polars = [_polar(c.orbit[:, :2], centre) for c in self.cycles]
        self._rules = self._region_rules()

    def __getstate__(self):
        # sent to every task of an executor: the tables derived from the orbits are
        # rebuilt there (milliseconds) rather than shipped (half the bytes)
        return {k: v for k, v in self.__dict__.items() if k not in ("_trees", "_polars")}

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._derive()

    def _near_inside(self, xy, i, band):
        """Within ``band`` of cycle ``i``, and inside it: by its polar table where it is
        star-shaped about the equilibrium (a start costs a bisection), else by the
        polygon and the distance to its segments."""
        polar = self._polars[i]
        if polar is None:
            curve = self.cycles[i].orbit[:, :2]
            near = _segment_distance(xy, curve, self._trees[i]) <= band
            return near, _inside(xy, curve)
        theta, r, sine = polar
        d = xy - self.equilibrium.state[:2]
        rc = np.interp(np.arctan2(d[:, 1], d[:, 0]), theta, r, period=2 * np.pi)
        gap = np.hypot(d[:, 0], d[:, 1]) - rc
        return np.abs(gap) * sine <= band, gap < 0

    def _label(self, s: InvariantSet) -> int:
        return next(i for i, a in enumerate(self.attractors) if a is s)

    def _region_rules(self):
        """The label of each ring from the inside out (None: not decided by region)."""
        if not self.nested or not self.cycles:
            return []
        rules = []
        bounds = [self.equilibrium, *self.cycles, None]
        for inner, outer in zip(bounds[:-1], bounds[1:]):
            stable = [s for s in (inner, outer) if s is not None and s.stable]
            rules.append(self._label(stable[0]) if len(stable) == 1 else None)
        return rules

    def decide(self, states: ArrayLike) -> NDArray[np.int_]:
        """The label each state is decided to land on by region alone, -1 where the
        region rule does not decide it (near a cycle, off the plane, or a ring without
        exactly one attracting boundary).

        Parameters
        ----------
        states : array_like (n, 4)

        Returns
        -------
        ndarray (n,) of int
        """
        y = np.atleast_2d(np.asarray(states, dtype=float))
        out = np.full(len(y), -1)
        eq = self.equilibrium.state
        planar = np.all(np.abs(y[:, 2:] - eq[2:]) <= NORMAL_TOL * (1.0 + np.abs(eq[2:])), axis=1)
        if not self._rules:
            return self._in_focus(y, planar, out)
        xy = y[:, :2]
        scale = 1.0 + np.max(np.abs(xy), axis=1)
        near = np.zeros(len(y), dtype=bool)
        ring = np.zeros(len(y), dtype=int)  # the cycles that do not contain it: 0 innermost
        for i in range(len(self.cycles)):
            close, inside = self._near_inside(xy, i, BAND * scale)
            near |= close
            ring += ~inside
        rules = np.array([-1 if r is None else r for r in self._rules])
        ok = planar & ~near
        out[ok] = rules[ring[ok]]
        return self._in_focus(y, planar, out)

    def _in_focus(self, y, planar, out):
        if self.focus is None:
            return out
        P, c = self.focus
        d = y[:, :2] - self.equilibrium.state[:2]
        inside = planar & (out < 0) & (np.einsum("ni,ij,nj->n", d, P, d) < c)
        out[inside] = self._label(self.equilibrium)
        return out

    def land(self, start: ArrayLike, t_max: float = T_MAX) -> dict[str, Any]:
        """Decide ``start``: by region at once, else by a run that stops as soon as a
        state on its way sticks or is decided by region (module docstring).

        Parameters
        ----------
        start : array_like (4,)
        t_max : float
            The longest run [s].

        Returns
        -------
        dict
            ``{"label", "how", "t"}``: the label (-1: undecided), ``"region"``,
            ``"stick"`` or ``"none"``, and the time run [s]. JSON-ready.
        """
        y = np.asarray(start, dtype=float)
        label = int(self.decide(y[None, :])[0])
        if label >= 0:
            return {"label": label, "how": "region", "t": 0.0}
        return self._run(y, t_max, self.stick_label)

    def _run(self, y, t_max, stick_label):
        chunk = _chunk_length(self)
        t = 0.0
        eq = self.equilibrium.state
        while t < t_max:
            span = min(chunk, t_max - t)
            settings = SolverSettings(
                t_end=t + span, rtol=RTOL, atol=ATOL, dt=span / 100, t_discard=0.0
            )
            try:
                run = integrate_events(self.model, settings, y0=y, t0=t)
            except StepTooSmall:
                return {"label": -1, "how": "none", "t": t}
            sticks = [
                e[0]
                for e in run.events
                if Mode(int(e[2])) == Mode.STICK
                and np.all(
                    np.abs(run.trajectory.state(np.array([e[0]]))[2:, 0] - eq[2:])
                    <= NORMAL_TOL * (1.0 + np.abs(eq[2:]))
                )
            ]
            end = run.trajectory.t_end
            if sticks and stick_label is not None:
                return {"label": int(stick_label), "how": "stick", "t": float(sticks[0])}
            ts = np.linspace(t, end, _CHECKS + 1)[1:]
            if sticks:
                ts = ts[ts < sticks[0]]
            labels = self.decide(run.trajectory.state(ts).T)
            hit = np.flatnonzero(labels >= 0)
            if hit.size:
                return {"label": int(labels[hit[0]]), "how": "region", "t": float(ts[hit[0]])}
            if run.status != "done":
                return {"label": -1, "how": "none", "t": float(end)}
            y, t = run.trajectory.state(np.array([end]))[:, 0], float(end)
        return {"label": -1, "how": "none", "t": t}


def _chunk_length(ls):
    period = [c.period for c in ls.cycles if c.period]
    return float(min(period)) if period else 2 * math.pi
