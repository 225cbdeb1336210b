"""Exact two-parameter stability maps: where the periodic response is unstable, boundaries traced.

The paper's Figs. 6-9 map the verdict of its linear analysis over two parameters. The
exact counterpart is the region of ``(x, y)`` where the periodic response of period
``T`` (`beltmdsm.analysis.floquet`) is unstable or absent, bounded by curves of its edges, each
of one bifurcation kind (`beltmdsm.analysis.edges.KINDS`). `floquet_map` traces these curves by
continuation in ``y``, row by row, not on a grid of pixels:

* The first row is a band in ``x`` (`beltmdsm.analysis.band.floquet_band`): its edges start
  the curves, each with the responses next to it.
* A **multiplier** curve (Neimark-Sacker, period doubling) is continued by the secant
  in ``x`` of ``log max |mu|``, its response continued from the row before (the edge
  and the response extrapolated from the last rows, cubically; along the row by the
  tangent of the secant's last wide step), to `EDGE_TOL` of the range: the secant's
  last step bounds the error of its next iterate, which is taken without a period map
  of its own.
* An **end** (tangency, grazing) is continued by `beltmdsm.analysis.edges.locate_end` from
  responses on the side where they exist, next to the predicted end; a fold by a short
  branch (`beltmdsm.analysis.branch.continue_branch`) across the predicted fold. Where ``x`` is
  ``Vb`` and the response slides back throughout, its grazing point is exact: its
  largest velocity in contact (`beltmdsm.analysis.floquet.largest_sliding_velocity`,
  as the band finds it).
* A curve that cannot be continued on a row ends there; a band on that row, on every
  row where no curve is followed, and on every ``check_every``-th row, finds the
  edges afresh, and an edge that no curve follows starts a new one.

Each row's unstable set is where no stable periodic response is found: on a row with a
band, the band's (`beltmdsm.analysis.band.Band.unstable`; a curve of a second periodic
response that coexists with a stable one then bounds nothing); on the rows between,
it follows from the curves' edges and from which of their sides is unstable, which
assumes one periodic response at each ``x``. The paper's linear analysis
(`generated.stability.is_stable`, the options of the paper) is evaluated on the same
rows for comparison, on a grid of ``x`` fine enough to show it (`LINEAR_POINTS`).
``floquet-map --png`` draws the result (`beltmdsm.cli.figure`).
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from generated import stability

from ..intervals import runs as true_intervals
from ..model import MODEL_PARAMETERS, Backend, Model, as_model, excitation_period
from .band import Band, floquet_band
from .branch import continue_branch
from .edges import NoEdge, locate_end, log_max_multiplier, multiplier_kind
from .floquet import NoPeriodicResponse, largest_sliding_velocity, response_from
from .periodmap import MARGIN_KINDS, MapFamily, engine_of, fixed_point

__all__ = [
    "EDGE_TOL",
    "LINEAR_POINTS",
    "Curve",
    "FloquetMap",
    "floquet_map",
]

#: Curves are located to this share of the ``x`` range on every row.
EDGE_TOL = 1e-6
#: Points of ``x`` on which the linear analysis is evaluated per row.
LINEAR_POINTS = 2001
#: Iterations of the secant on one row.
_SECANT_ITER = 12
#: The responses next to an end are taken this share of the ``x`` range from it, at
#: least, and at these shares of that distance (four: the end is the zero of the cubic
#: through their margins, its accuracy the distance to the quadratic's).
_END_OFFSET = 2e-3
_END_SHARES = (1.0, 0.5, 0.25, 0.125)
#: Times the distance to the end is tripled where fewer than two responses are found.
_END_WIDENINGS = 4
#: A band's edge within this share of the ``x`` range of where a lost curve of its kind
#: was heading goes on that curve.
_RESUME = 0.1
#: Steps of the natural continuation that carries a band's response to a curve's start.
_WALK_STEPS = 8
#: Two curves of one kind closer than this many times `EDGE_TOL` on a row have become
#: one (edges that merge, e.g. grazings that become one tangency): one goes on.
_SAME = 10


@dataclass
class Curve:
    """A boundary curve of one kind: ``x`` against ``y``.

    Attributes
    ----------
    kind : str
    y, x : list of float
    accuracy : list of float
        Per point, a bound of the error of ``x``.
    frequency : list of float or None
        Of the critical pair at a Neimark-Sacker curve [rad/s].
    unstable_below, unstable_above : bool
        Whether no stable response lies just below and just above the edge in ``x``.
    ended : str
        Why the curve stops where it does ("" at the last row).
    """

    kind: str
    y: list = field(default_factory=list)
    x: list = field(default_factory=list)
    accuracy: list = field(default_factory=list)
    frequency: list = field(default_factory=list)
    unstable_below: bool = True
    unstable_above: bool = True
    ended: str = ""

    def as_dict(self) -> dict:
        """For JSON: the attributes."""
        return {
            "kind": self.kind,
            "y": self.y,
            "x": self.x,
            "accuracy": self.accuracy,
            "frequency": self.frequency,
            "unstable_below": self.unstable_below,
            "unstable_above": self.unstable_above,
            "ended": self.ended,
        }


@dataclass
class FloquetMap:
    """The result of `floquet_map`.

    Attributes
    ----------
    x, y : str
        The parameters of the axes.
    x_range, y_range : list of float
    rows : ndarray
        The ``y`` of each row.
    model : Model
        The other parameters and the options (``x`` and ``y`` at the first row's start).
    curves : list of Curve
    unstable : list of list
        Per row, the ``[lo, hi]`` of ``x`` where no stable periodic response is found
        (unstable or absent; on a row in ``band_rows`` the band's, module docstring).
    linear : list of list
        Per row, where the paper's linear analysis says unstable (``x`` resolved to
        the range over `LINEAR_POINTS` - 1).
    band_rows : list of float
        The rows on which a band found the edges afresh.
    wall_s : float
    """

    x: str
    y: str
    x_range: list
    y_range: list
    rows: np.ndarray
    model: Model
    curves: list
    unstable: list
    linear: list
    band_rows: list
    wall_s: float

    def as_dict(self) -> dict:
        """For JSON: ``x``, ``y``, ``x_range``, ``y_range``, ``rows``, ``contact``,
        ``tension``, ``friction``, ``engine``, ``curves``, ``unstable``, ``linear``,
        ``band_rows``, ``wall_s``."""
        return {
            "x": self.x,
            "y": self.y,
            "x_range": self.x_range,
            "y_range": self.y_range,
            "rows": [float(v) for v in self.rows],
            "contact": self.model.contact,
            "tension": self.model.tension,
            "friction": self.model.friction,
            "engine": engine_of(self.model),
            "curves": [c.as_dict() for c in self.curves],
            "unstable": self.unstable,
            "linear": self.linear,
            "band_rows": self.band_rows,
            "wall_s": self.wall_s,
        }


# ---------------------------------------------------------------- tracking one edge


def _extrapolate(ys, values, y):
    """The polynomial through the last (up to four) points, at ``y``: Lagrange's form.

    Cubic: the responses kept next to an end, extrapolated so from the rows before,
    are within about 1e-8 of the next row's, and Newton's method takes two period maps
    from there (three from the quadratic's 1e-6).
    """
    ys, values = [float(v) for v in ys[-4:]], [np.asarray(v, dtype=float) for v in values[-4:]]
    out = 0.0
    for i, (yi, vi) in enumerate(zip(ys, values)):
        weight = 1.0
        for j, yj in enumerate(ys):
            if j != i:
                weight *= (y - yj) / (yi - yj)
        out = out + weight * vi
    return float(out) if np.ndim(out) == 0 else out


def _walk(family, x0, state, x1):
    """The response at ``x1``, continued from ``state`` at ``x0`` in natural steps."""
    steps, x, s = _WALK_STEPS, float(x0), np.asarray(state, dtype=float)
    while True:
        target = x + (x1 - x) / steps
        try:
            s = fixed_point(family(target), s).state
            x = target
            if x == x1 or steps == 1:
                return fixed_point(family(x1), s)
            steps -= 1
        except NoPeriodicResponse:
            steps *= 2
            if steps > 512:
                raise


@dataclass
class _Tracker:
    """Continues one edge in ``y`` (module docstring)."""

    curve: Curve
    role: str  # "multiplier", "end", "fold" or "sliding"
    side: float  # ends: +1 where the responses lie below the edge in x, -1 above
    kinds: tuple
    # per row where the edge was located (across changes of kind, unlike the curve's
    # points): the row's y, the edge's x and the responses kept next to it
    ys: list = field(default_factory=list)
    xs: list = field(default_factory=list)
    states: list = field(default_factory=list)
    slope: float | None = None
    # multiplier curves: d(response)/dx along the row, from the last secant step
    tangent: np.ndarray | None = None

    def record(self, y, x):
        """The edge located at ``x`` on row ``y`` (the responses already kept by `step`)."""
        self.ys.append(float(y))
        self.xs.append(float(x))

    def step(self, family, y, span):
        if self.role == "sliding":
            # the grazing point of the backward-sliding response in Vb is its largest
            # velocity in contact, which does not depend on Vb
            return "grazing", largest_sliding_velocity(family(self.xs[-1]).one), 1e-12, None
        if self.role == "multiplier":
            return self._multiplier(family, y, span)
        if self.role == "fold":
            return self._fold(family, y, span)
        return self._end(family, y, span)

    def _multiplier(self, family, y, span):
        c, tol = self.curve, EDGE_TOL * span
        x0 = _extrapolate(self.ys, self.xs, y)
        guess = _extrapolate(self.ys, [s[0] for s in self.states], y)

        def g(x, guess):
            point = fixed_point(family(x), guess)
            value, mu = log_max_multiplier(family(x), point)
            return value, mu, point

        def along(point, x_from, x):
            """The response at ``x`` predicted from ``point`` at ``x_from`` by the
            tangent of the last secant step wide enough to measure it (Newton's method
            then takes two period maps, not three)."""
            if self.tangent is None:
                return point.state
            return point.state + self.tangent * (x - x_from)

        g0, mu0, p0 = g(x0, guess)
        slope = self.slope if self.slope else None
        x1 = x0 - g0 / slope if slope else x0 + 1e-3 * span
        for _ in range(_SECANT_ITER):
            g1, mu1, p1 = g(x1, along(p0, x0, x1))
            if g1 == g0:  # a flat secant: x1 itself, to the step that reached it
                accuracy, x0, mu0, p0 = abs(x1 - x0), x1, mu1, p1
                break
            slope = (g1 - g0) / (x1 - x0)
            if abs(x1 - x0) > tol:  # above the Newton tolerance's noise (1e-11 / tol)
                self.tangent = (p1.state - p0.state) / (x1 - x0)
            x0, g0, mu0, p0 = x1, g1, mu1, p1
            x1 = x1 - g1 / slope
            # the secant's last step bounds the error of its next iterate (which is
            # of second order in it): x1 is taken without a period map of its own,
            # its multiplier that at x0, within tol
            if abs(x1 - x0) <= tol:
                accuracy = abs(x1 - x0)
                break
        else:
            raise NoEdge(f"the secant of log max|mu| does not converge at {c.kind}")
        self.slope = slope
        kind, frequency = multiplier_kind(mu0, family.periods * family(x0).period)
        self.states.append((along(p0, x0, x1),))
        return kind, x1, accuracy, frequency

    def _end(self, family, y, span):
        x_end = _extrapolate(self.ys, self.xs, y)
        last = self.xs[-1] - self.xs[-2] if len(self.xs) > 1 else 0.0
        offset = max(3 * abs(last), _END_OFFSET * span)
        for _ in range(_END_WIDENINGS):
            points, states = self._next_to_end(family, y, x_end, offset)
            if len(points) >= 2:
                break
            # the end moved more than predicted: responses farther from it
            offset *= 3
        else:
            raise NoEdge("no two responses next to the predicted end")
        end = locate_end(family, points, tol=EDGE_TOL * span, kinds=self.kinds)
        self.states.append(tuple(states))
        return end.kind, end.value, end.accuracy, None

    def _next_to_end(self, family, y, x_end, offset):
        """The responses at `_END_SHARES` of ``offset`` from the predicted end, and their states."""
        points, states, shift = [], [], None
        for i, share in enumerate(_END_SHARES):
            x = x_end - self.side * offset * share
            known = zip(self.ys, self.states)
            rows = [(yy, st[i]) for yy, st in known if st[i] is not None]
            # the same share on the rows before, extrapolated in y, is the better guess:
            # next to a tangency the response is not linear along the row (it varies
            # like the square root of the distance to the end), and Newton's method
            # needed 11 iterations from the row's secant, 3 from this; corrected by the
            # error of that prediction at the share solved before on this row (where few
            # rows are known, 4 iterations instead of 10)
            predicted = None
            if rows:
                predicted = _extrapolate([r[0] for r in rows], [r[1] for r in rows], y)
                guess = predicted if shift is None else predicted + shift
            elif len(points) >= 2:  # along the row from the two before
                (xa, pa), (xb, pb) = points[-2:]
                guess = pb.state + (pb.state - pa.state) * (x - xb) / (xb - xa)
            elif points:
                guess = points[-1][1].state
            else:
                states.append(None)
                continue
            try:  # the nearest may lie beyond the end, or too close for Newton's method
                point = fixed_point(family(x), guess)
            except NoPeriodicResponse:
                states.append(None)
                continue
            points.append((x, point))
            states.append(point.state)
            if predicted is not None:
                shift = point.state - predicted
        return points, states

    def _fold(self, family, y, span):
        x_fold = _extrapolate(self.ys, self.xs, y)
        last = abs(self.xs[-1] - self.xs[-2]) if len(self.xs) > 1 else 0.0
        offset = max(10 * last, 10 * _END_OFFSET * span)
        x = x_fold - self.side * offset
        guess = _extrapolate(self.ys, [s[0] for s in self.states], y)
        point = fixed_point(family(x), guess)
        lo, hi = sorted((x, x_fold + self.side * offset))
        branch = continue_branch(response_from(family(x), point), family.param, lo, hi)
        folds = [s for s in branch.special if s.kind == "fold"]
        if not folds:
            raise NoEdge("no fold within the window")
        fold = min(folds, key=lambda s: abs(s.value - x_fold))
        self.states.append((point.state,))
        return "fold", fold.value, fold.accuracy, None


# ---------------------------------------------------------------- seeding from a band


def _trackers_from_band(band: Band, edges, family, y, span):
    """A tracker for each of ``edges`` of a band row (with the responses it needs)."""
    gaps = band.no_periodic_response
    out = []
    for e in edges:
        v, kind = e.value, e.kind
        curve = Curve(kind, unstable_below=e.unstable_below, unstable_above=e.unstable_above)
        if kind in ("neimark_sacker", "period_doubling"):
            role, side = "multiplier", 0.0
        else:
            role = "fold" if kind == "fold" else "end"
            # the responses lie below the edge where a gap begins at it, above where one ends
            below = any(abs(g[0] - v) <= 1e-9 * span for g in gaps)
            above = any(abs(g[1] - v) <= 1e-9 * span for g in gaps)
            side = 1.0 if below or not above else -1.0
        near = sorted(
            (r for r in band.grid if role == "multiplier" or side * (v - r.value) > 0),
            key=lambda r: abs(r.value - v),
        )
        if not near:
            continue
        start = near[0]
        sliding = (start.n_reversals, start.n_sticks) == (0, 0)
        # the grazing point is the largest velocity only where the friction is free of
        # the tangential state (the closed-form path)
        closed = engine_of(family.model) == "closed_form"
        if kind == "grazing" and family.param == "Vb" and sliding and closed:
            role = "sliding"
        tracker = _Tracker(curve, role, side, _margin_kinds(kind))
        try:
            if role == "sliding":
                pass
            elif role == "multiplier":
                point = _walk(family, start.value, family(start.value).guess(start.state0), v)
                tracker.states.append((point.state,))
            else:
                offset = _END_OFFSET * span
                xs = [v - side * offset * share for share in _END_SHARES]
                guess = family(start.value).guess(start.state0)
                states = [_walk(family, start.value, guess, xs[0]).state]
                for j in range(1, len(xs)):
                    # along the row from the two before; the nearest may be too close
                    # to a tangency for Newton's method (as in _Tracker._next_to_end)
                    known = [(xk, sk) for xk, sk in zip(xs, states) if sk is not None]
                    xb, guess = known[-1]
                    if len(known) > 1:
                        xa, sa = known[-2]
                        guess = guess + (guess - sa) * (xs[j] - xb) / (xb - xa)
                    try:
                        states.append(fixed_point(family(xs[j]), guess).state)
                    except NoPeriodicResponse:
                        states.append(None)
                if sum(s is not None for s in states) < 2:
                    continue
                tracker.states.append(tuple(states))
        except NoPeriodicResponse:
            continue
        curve.y.append(float(y))
        curve.x.append(float(v))
        tracker.record(y, v)
        curve.accuracy.append(float(e.accuracy))
        curve.frequency.append(e.frequency)
        if role == "multiplier":  # the band's tolerance, refined by the secant
            try:
                _, at, accuracy, frequency = tracker.step(family, y, span)
                tracker.states.pop(0)
                curve.x[-1], curve.accuracy[-1], curve.frequency[-1] = (
                    float(at),
                    accuracy,
                    frequency,
                )
                tracker.xs[-1] = float(at)
            except (NoPeriodicResponse, NoEdge):
                pass
        out.append(tracker)
    return out


def _margin_kinds(kind):
    return ("crossing",) if kind == "tangency" else MARGIN_KINDS


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


def _linear(row, x, xs):
    """Where the paper's linear analysis says unstable on a row (`generated.stability`)."""
    stable = stability.is_stable(**{**row.arguments(stability.is_stable), x: xs})
    return [[float(a), float(b)] for a, b in true_intervals(xs, ~np.asarray(stable, bool))]


def floquet_map(
    x: str,
    x_from: float,
    x_to: float,
    y: str,
    y_from: float,
    y_to: float,
    model: Model | Mapping[str, Any] | None = None,
    *,
    rows: int = 100,
    check_every: int = 50,
    backend: Backend | None = None,
    **kw: Any,
) -> FloquetMap:
    """The region of ``(x, y)`` where the periodic response is unstable, its boundary traced.

    Parameters
    ----------
    x, y : str
        Two different model parameters.
    x_from, x_to, y_from, y_to : float
        Their ranges.
    model : Model or dict, optional
        The other parameters and the options (default: the base set); ``**kw`` too.
    rows : int
        Values of ``y`` (>= 2), evenly spaced.
    check_every : int
        A band finds the edges afresh on every such row (>= 1), besides where a curve
        cannot be continued and where no curve is followed.
    backend : {"python", "numba", None}

    Returns
    -------
    FloquetMap

    Raises
    ------
    ValueError
        For unknown or equal parameters, bad ranges, ``rows < 2`` or ``check_every < 1``.
    """
    clock = time.perf_counter()
    for name in (x, y):
        if name not in MODEL_PARAMETERS:
            raise ValueError(f"a map's axes must be model parameters; got {name!r}")
    if x == y:
        raise ValueError(f"the two axes must differ; got {x!r} twice")
    for a, b in ((x_from, x_to), (y_from, y_to)):
        if not (np.isfinite(a) and np.isfinite(b) and a < b):
            raise ValueError(f"each range must be finite with from < to; got [{a}, {b}]")
    if int(rows) < 2 or int(check_every) < 1:
        raise ValueError(f"rows must be >= 2 and check_every >= 1; got {rows}, {check_every}")
    base = as_model(model, **kw).replace(**{x: x_from, y: y_from})
    excitation_period(base)
    span = x_to - x_from
    ys = np.linspace(y_from, y_to, int(rows))
    xs = np.linspace(x_from, x_to, LINEAR_POINTS)
    curves, trackers, unstable, linear, band_rows = [], [], [], [], []
    for i, value in enumerate(ys):
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
            if not x_from <= at <= x_to:
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
            band = floquet_band(x, x_from, x_to, row, backend=backend)
            band_rows.append(float(value))
            followed = [t.curve.x[-1] for t in live if t.curve.y[-1] == float(value)]
            for e in band.edges:
                if any(abs(e.value - f) <= 1e-3 * span for f in followed):
                    continue
                new = _trackers_from_band(band, [e], family, value, span)
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
            unstable.append(_row_unstable(edges, x_from, x_to))
        else:  # where no stable response is found, also beside an unstable one
            unstable.append([[float(a), float(b)] for a, b in band.unstable])
        linear.append(_linear(row, x, xs))
    return FloquetMap(
        x,
        y,
        [float(x_from), float(x_to)],
        [float(y_from), float(y_to)],
        ys,
        base,
        curves,
        unstable,
        linear,
        band_rows,
        time.perf_counter() - clock,
    )
