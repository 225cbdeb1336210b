"""One boundary curve of a Floquet map continued from row to row (`_Tracker`).

`beltmdsm.continuation.floquet_map.floquet_map` starts a tracker at each edge of a band
row (`_trackers_from_band`) and steps it to the next row: a multiplier curve by the
secant of ``log max |mu|``, an end by the cubic of ``x`` against the closing margin
(`beltmdsm.continuation.edges.locate_end`), a fold by a short branch, the sliding
response's grazing exactly (the module docstring of
`beltmdsm.continuation.floquet_map` says how and why).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import NoPeriodicResponse
from ..periodic.closed_form import largest_sliding_velocity
from ..periodic.engines import engine_of
from ..periodic.margins import MARGIN_KINDS, Margin
from ..periodic.newton import fixed_point
from ..periodic.response import response_from
from .band_result import Band
from .branch import continue_branch
from .edges import (
    NoEdge,
    counterpart,
    locate_end,
    log_max_multiplier,
    margin_kind,
    multiplier_kind,
)
from .map_result import Curve
from .settings import ContinuationSettings

#: Curves are located to this share of the ``x`` range on every row.
EDGE_TOL = 1e-6
#: Iterations of the secant on one row.
_SECANT_ITER = 12
#: The responses next to an end are taken this share of the ``x`` range from it, at
#: least, and at these shares of that distance (four: the end is the zero of the cubic
#: through their margins, its accuracy the distance to the quadratic's).
_END_OFFSET = 2e-3
_END_SHARES = (1.0, 0.5, 0.25, 0.125)
#: Times the distance to the end is tripled where fewer than two responses are found.
_END_WIDENINGS = 4
#: A row takes one response per curve where the shape of the end (``x`` against the
#: closing margin) or the slope of the multiplier's secant was measured on one of
#: this many rows before, and measures it afresh otherwise.
_REMEASURE = 8
#: ... and where the shape's extrapolation to the row (the difference between its
#: cubic and its quadratic extrapolation) is below this share of the tolerance.
_DRIFT = 0.1
#: Steps of the natural continuation that carries a band's response to a curve's start
#: (the band's nearest response lies about its tolerance from the edge; where a step
#: fails, the rest are halved).
_WALK_STEPS = 2


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
    # multiplier curves: d(response)/dx along the row, from the last secant step
    tangent: np.ndarray | None = None
    # multiplier curves: (row index, y, slope) where the secant measured its slope
    slopes: list = field(default_factory=list)
    # ends: per row, the x of each response kept in ``states`` (None where none)
    positions: list = field(default_factory=list)
    # ends: (row index, y, coefficients of x against the closing margin, accuracy) where
    # four responses measured that shape, and the closing margin on the last row
    shapes: list = field(default_factory=list)
    margin: Margin | None = None
    # the driver's settings for the branches across a fold (`floquet_map`'s settings=)
    settings: ContinuationSettings | None = None

    def record(self, y, x):
        """The edge located at ``x`` on row ``y`` (the responses already kept by `step`)."""
        self.ys.append(float(y))
        self.xs.append(float(x))

    def step(self, family, y, span):
        if self.role == "sliding":
            # the grazing point of the backward-sliding response in Vb is its largest
            # velocity in contact, which does not depend on Vb: any map of the row's
            one = family.any_map(self.xs[-1]).one
            return "grazing", largest_sliding_velocity(one), 1e-12, None
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
        predicted = self._predicted_slope(y)
        if predicted is not None and abs(g0 / predicted) <= tol:
            # one response on this row: the secant's step with the predicted slope,
            # whose error is the step times the slope's relative error (below one)
            x1 = x0 - g0 / predicted
            kind, frequency = multiplier_kind(mu0, family.periods * family(x0).period)
            self.states.append((along(p0, x0, x1),))
            return kind, x1, abs(x1 - x0), frequency
        slope = predicted or (self.slopes[-1][2] if self.slopes else None) or None
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
        self.slopes.append((len(self.ys), float(y), slope))
        kind, frequency = multiplier_kind(mu0, family.periods * family(x0).period)
        self.states.append((along(p0, x0, x1),))
        return kind, x1, accuracy, frequency

    def _predicted_slope(self, y):
        """The secant's slope on row ``y``, linear in ``y`` from the last two measured.

        None where the last was measured `_REMEASURE` rows before or more, or where the
        prediction differs from it by more than half its value: that difference bounds
        the prediction's error (pessimistically, by one order), and below one half
        the error of a step with it is below the step.
        """
        if len(self.slopes) < 2 or len(self.ys) - self.slopes[-1][0] >= _REMEASURE:
            return None
        (_, ya, sa), (_, yb, sb) = self.slopes[-2:]
        s = sb + (sb - sa) * (y - yb) / (yb - ya)
        return s if abs(s - sb) <= 0.5 * abs(s) else None

    def _end(self, family, y, span):
        x_end = _extrapolate(self.ys, self.xs, y)
        last = self.xs[-1] - self.xs[-2] if len(self.xs) > 1 else 0.0
        offset = max(3 * abs(last), _END_OFFSET * span)
        found, nearest = self._end_from_shape(family, y, span, x_end, offset)
        if found is not None:
            return found
        for _ in range(_END_WIDENINGS):
            points, states, positions = self._next_to_end(family, y, x_end, offset, nearest)
            if len(points) >= 2:
                break
            # the end moved more than predicted: responses farther from it
            offset, nearest = 3 * offset, None
        else:
            raise NoEdge("no two responses next to the predicted end")
        end = locate_end(family, points, tol=EDGE_TOL * span, kinds=self.kinds)
        self.states.append(tuple(states))
        self.positions.append(tuple(positions))
        if len(end.chain) == 4:
            values, margins = zip(*end.chain)
            shape = np.polyfit(margins, values, 3)
            self.shapes.append((len(self.ys), float(y), shape, end.accuracy))
        self.margin = end.margin
        return end.kind, end.value, end.accuracy, None

    def _end_from_shape(self, family, y, span, x_end, offset):
        """The end from one response next to it and the shape measured on rows before.

        Along a row ``x`` is a smooth function of the closing margin up to the end
        (`beltmdsm.continuation.edges.locate_end`), and that function changes smoothly from
        row to row: its cubic on the last four rows where four responses measured it,
        extrapolated to this row, carries the one response at the nearest share to
        the margin's zero. The accuracy is the largest of those rows' plus the
        difference between the cubic and the quadratic extrapolation (the drift).

        Returns ``(edge, None)``, or ``(None, (x, response))`` with the response solved
        (or None) where four responses measure the shape afresh: where four rows have
        not measured it, the last `_REMEASURE` rows before or more, where the drift is
        above `_DRIFT` of the tolerance or the accuracy above the tolerance.
        """
        shapes, last = self.shapes[-4:], len(_END_SHARES) - 1
        rows = self._solved(last)
        if len(shapes) < 4 or len(self.ys) - shapes[-1][0] >= _REMEASURE or not rows:
            return None, None
        x = x_end - self.side * offset * _END_SHARES[last]
        try:  # (outside the parameter's domain, family(x) raises it too)
            pmap = family(x)
            point = fixed_point(pmap, self._extrapolated(last, rows, y, x, x_end))
        except NoPeriodicResponse:
            return None, None
        window = 0.25 * family.periods * pmap.period
        margin = counterpart(self.margin, point.image.margins_of(self.kinds), window)
        if margin is None or not margin.value > 0:
            return None, (x, point)
        ys, shapes_at = [s[1] for s in shapes], [s[2] for s in shapes]

        def reach(shape):  # x at the margin less x at its zero
            return float(np.polyval(np.append(shape[:-1], 0.0), margin.value))

        cubic = reach(_extrapolate(ys, shapes_at, y))
        quadratic = reach(_extrapolate(ys[1:], shapes_at[1:], y))
        value = x - cubic
        drift = abs(cubic - quadratic)
        accuracy = max(s[3] for s in shapes) + drift
        if (
            accuracy > EDGE_TOL * span
            or drift > _DRIFT * EDGE_TOL * span
            or self.side * (value - x) <= 0
        ):
            return None, (x, point)
        self.states.append((None,) * last + (point.state,))
        self.positions.append((None,) * last + (x,))
        self.margin = margin
        return (margin_kind(margin), value, accuracy, None), None

    def _next_to_end(self, family, y, x_end, offset, nearest=None):
        """The responses at `_END_SHARES` of ``offset`` from the predicted end, and their states.

        ``nearest``: ``(x, response)`` at the last share, already solved (or None).
        """
        n = len(_END_SHARES)
        history = [self._solved(i) for i in range(n)]
        # the share with the freshest history first (after rows of one response,
        # `_end_from_shape`, the nearest), the others in order
        order = sorted(range(n), key=lambda i: -history[i][-1] if history[i] else 1)
        solved = {} if nearest is None else {n - 1: nearest}
        for i in (i for i in order if i not in solved):
            x = x_end - self.side * offset * _END_SHARES[i]
            rows = history[i]
            # the same share on the rows before, extrapolated in y, is the better guess:
            # next to a tangency the response is not linear along the row (it varies
            # like the square root of the distance to the end), and Newton's method
            # needed 11 iterations from the row's secant, 3 from this; corrected by the
            # error that extrapolation from the same rows makes at the nearest share
            # solved on this row (where few rows are known, 4 iterations instead of 10;
            # after rows of one response, 3 instead of 5)
            if rows:
                guess = self._extrapolated(i, rows, y, x, x_end)
                donors = [j for j in solved if all(self.states[k][j] is not None for k in rows)]
                if donors:
                    j = min(donors, key=lambda j: abs(j - i))
                    xj, pj = solved[j]
                    guess = guess + pj.state - self._extrapolated(j, rows, y, xj, x_end)
            else:  # along the row from the nearest shares solved
                near = sorted(solved, key=lambda j: abs(j - i))[:2]
                if not near:
                    continue
                guess = solved[near[0]][1].state
                if len(near) == 2:
                    (xa, pa), (xb, pb) = solved[near[1]], solved[near[0]]
                    guess = pb.state + (pb.state - pa.state) * (x - xb) / (xb - xa)
            try:  # the nearest may lie beyond the end, or too close for Newton's method
                solved[i] = (x, fixed_point(family(x), guess))
            except NoPeriodicResponse:
                continue
        return (
            [solved[i] for i in range(n) if i in solved],
            [solved[i][1].state if i in solved else None for i in range(n)],
            [solved[i][0] if i in solved else None for i in range(n)],
        )

    def _solved(self, i):
        """The last (up to four) rows where the response at share ``i`` was solved."""
        return [k for k, st in enumerate(self.states) if st[i] is not None][-4:]

    def _extrapolated(self, i, rows, y, x, x_end):
        """The response at share ``i`` at ``x`` on row ``y``, from ``rows`` before.

        Each row's response is first moved along its row to the distance from that
        row's end that ``x`` has from ``x_end`` (the predicted end), by the slope along
        the row between two shares on the last row where both were solved: an end
        located less smoothly than the rows around it (by 1e-7, within its accuracy)
        moves the responses next to a tangency by 1e-7 from where a smooth curve
        would put them, and Newton's method then takes three period maps, not two.
        """
        slope, j = None, i - 1 if i > 0 else i + 1
        for k in reversed(range(len(self.states))):
            st, at = self.states[k], self.positions[k]
            if st[i] is not None and st[j] is not None:
                slope = (st[i] - st[j]) / (at[i] - at[j])
                break
        distance = x_end - x
        values = [
            self.states[k][i]
            + (0.0 if slope is None else slope * (self.xs[k] - distance - self.positions[k][i]))
            for k in rows
        ]
        return _extrapolate([self.ys[k] for k in rows], values, y)

    def _fold(self, family, y, span):
        x_fold = _extrapolate(self.ys, self.xs, y)
        last = abs(self.xs[-1] - self.xs[-2]) if len(self.xs) > 1 else 0.0
        offset = max(10 * last, 10 * _END_OFFSET * span)
        x = x_fold - self.side * offset
        guess = _extrapolate(self.ys, [s[0] for s in self.states], y)
        point = fixed_point(family(x), guess)
        lo, hi = sorted((x, x_fold + self.side * offset))
        start = response_from(family(x), point)
        branch = continue_branch(start, family.param, lo, hi, settings=self.settings)
        folds = [s for s in branch.special if s.kind == "fold"]
        if not folds:
            raise NoEdge("no fold within the window")
        fold = min(folds, key=lambda s: abs(s.value - x_fold))
        self.states.append((point.state,))
        return "fold", fold.value, fold.accuracy, None


# ---------------------------------------------------------------- seeding from a band


def _trackers_from_band(band: Band, edges, family, y, span, settings=None):
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
        tracker = _Tracker(curve, role, side, _margin_kinds(kind), settings=settings)
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
                tracker.positions.append(
                    tuple(x if st is not None else None for x, st in zip(xs, states))
                )
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
