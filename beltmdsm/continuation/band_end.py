"""Where a response found on one side of a band's interval ends within it.

`beltmdsm.continuation.band.floquet_band` continues the response across the interval
(`_band_existence`): natural continuation with step control (`_natural`) to where a
margin closes, located by `beltmdsm.continuation.edges.locate_end`, else the
pseudo-arclength branch (`beltmdsm.continuation.branch.continue_branch`), whose special
points become the band's edges.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import NoPeriodicResponse
from ..periodic.family import MapFamily
from ..periodic.floquet import Floquet, floquet
from ..periodic.margins import MARGIN_KINDS
from ..periodic.newton import FixedPoint, fixed_point
from ..periodic.response import response_from
from .band_result import Edge
from .branch import continue_branch
from .branch_result import SpecialPoint
from .edges import (
    KINDS,
    OLD_KINDS,
    End,
    NoEdge,
    closing_margins,
    locate_end,
    log_max_multiplier,
    multiplier_kind,
)

#: An end (tangency, grazing) inside an interval is located to the band's ``tol`` or to
#: this, whichever is smaller (the margin's secant converges fast: 1e-4 asked takes
#: less than half the period maps of 1e-7, 35 against 81 at the base set, and gives
#: about 1e-6).
_END_TOL = 1e-4
#: Natural continuation towards an end stops at steps below this share of its way.
_NATURAL_SMALLEST = 1e-3


@dataclass
class _BandEnd:
    """Where the response found on one side of a band's interval ends within it.

    ``edges``: the band's edges that the continuation across the interval finds (its
    bifurcations and its end); ``reached``: the `Floquet` of the response at the far
    value, where the continuation reaches it (Newton's method had missed it there);
    ``solved``: ``(value, Floquet)`` of the responses solved on the way; ``stalled``:
    why the continuation stopped inside without locating an end ("" where it did not).
    """

    edges: list
    reached: Floquet | None
    solved: list = field(default_factory=list)
    stalled: str = ""


def _end_detail(end: End) -> str:
    m = end.margin
    return f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at t = {m.t:.4g} s vanishes"


def _special_edge(kind, value, accuracy, frequency, detail, unstable_below, unstable_above):
    """An edge at a located special point or end (its accuracy as located)."""
    if kind == "branch_point":  # a real multiplier through +1 without a turn
        kind = "fold"
    kind = kind if kind in KINDS else "unclassified"
    return Edge(
        value,
        kind,
        OLD_KINDS.get(kind, "existence"),
        (value - accuracy, value + accuracy),
        accuracy,
        frequency,
        unstable_below,
        unstable_above,
        detail,
    )


def _natural(family, value, state, far):
    """Natural continuation from ``value`` towards ``far``, quadratic predictor, step control.

    Returns the responses solved (``(value, FixedPoint)``, in order), whether ``far``
    was reached, and whether the response kept its switch structure on the way (if
    not, the caller continues by arclength). A step that finds no response is halved;
    the continuation stops where the step falls below `_NATURAL_SMALLEST` of the
    distance, or at once where a margin of the last two responses closes before the
    step's end (`_closes_before`): `locate_end` takes over from there, its steps aimed
    at the margin's zero (halving blindly towards a tangency costs a failed Newton's
    method of 10-20 period maps a time).
    """
    first = fixed_point(family(value), state)
    points = [(value, first)]
    h = (far - value) / 8
    smallest = _NATURAL_SMALLEST * abs(far - value)
    while abs(h) >= smallest:
        x = points[-1][0] + h
        if (far - x) * h <= 0:
            x = far
        known = np.array([v for v, _ in points[-3:]])
        states = np.array([p.state for _, p in points[-3:]])
        if known.size > 1:
            c = np.polyfit(known - known[-1], states, known.size - 1)
            guess = np.array([np.polyval(c[:, i], x - known[-1]) for i in range(states.shape[1])])
        else:
            guess = states[-1]
        try:
            p = fixed_point(family(x), guess)
        except NoPeriodicResponse:
            if _closes_before(family, points, x):
                return points, False, True
            h = 0.5 * (x - points[-1][0])  # of the step tried (it may end at far)
            continue
        if p.image.signature != points[-1][1].image.signature:
            return points, False, False
        points.append((x, p))
        if x == far:
            return points, True, True
        if _closes_before(family, points, far):
            return points, False, True
        h *= 1.5
    return points, False, True


def _closes_before(family, points, x):
    """Whether a margin of the last two of ``points`` has its secant's zero before ``x``.

    Close to a tangency the crossing margin falls like the square root of the distance
    to the end, so the secant's zero lies beyond the end: a zero before ``x`` is taken
    for an end before ``x`` (`beltmdsm.continuation.edges.closing_margins`); `locate_end`
    finds it, or `_band_existence` falls back on the branch.
    """
    if len(points) < 2:
        return False
    (va, pa), (vb, pb) = points[-2:]
    window = 0.25 * family.periods * family(vb).period
    closing = closing_margins(
        pa.image.margins_of(MARGIN_KINDS), pb.image.margins_of(MARGIN_KINDS), va, vb, window
    )
    return any(0.0 < (zero - vb) * (x - vb) < (x - vb) ** 2 for zero, _ in closing)


def _multiplier_edge(family, a, b, tol):
    """The edge where ``max |mu| = 1`` between two responses of one structure (secant)."""
    (va, pa), (vb, pb) = a, b
    ga, gb = log_max_multiplier(family(va), pa)[0], log_max_multiplier(family(vb), pb)[0]
    stable_below = (ga < 0) if va < vb else (gb < 0)
    # the secant, kept inside the bracket of the sign change [lo, hi]: where it has no
    # slope (ga == gb: a multiplier flat in the parameter, as on |mu| = 1 undamped) or
    # leaves the bracket, the bracket is bisected
    (lo, glo), hi = (va, ga), vb
    for _ in range(40):
        v = vb - gb * (vb - va) / (gb - ga) if gb != ga else math.nan
        if not min(lo, hi) < v < max(lo, hi):
            v = 0.5 * (lo + hi)
        p = fixed_point(family(v), pb.state)
        g, mu = log_max_multiplier(family(v), p)
        (va, pa, ga), (vb, pb, gb) = (vb, pb, gb), (v, p, g)
        if (g < 0) == (glo < 0):
            lo, glo = v, g
        else:
            hi = v
        if abs(vb - va) <= tol or abs(hi - lo) <= tol:
            break
    kind, frequency = multiplier_kind(mu, family.periods * family(vb).period)
    return Edge(
        vb,
        kind,
        OLD_KINDS[kind],
        (vb - abs(vb - va), vb + abs(vb - va)),
        abs(vb - va),
        frequency,
        not stable_below,
        stable_below,
    )


def _towards(points, value, far):
    """The branch's points from the one at ``value`` towards ``far``, up to where it turns.

    Past a fold the branch comes back over values where the first part holds responses
    too; the band records the first part only.
    """
    if not points:
        return []
    i = min(range(len(points)), key=lambda j: abs(points[j].value - value))
    toward = 1.0 if far > value else -1.0
    step = 1 if i + 1 < len(points) and (points[i + 1].value - value) * toward > 0 else -1
    out = []
    while 0 <= i + step < len(points) and (points[i + step].value - points[i].value) * toward > 0:
        i += step
        out.append(points[i])
    return out


def _verdict(pmap, point):
    """Whether a fixed point of a map is stable: every multiplier inside the unit circle."""
    mu = np.concatenate([np.linalg.eigvals(point.image.jacobian), pmap.fixed_multipliers()])
    return bool(np.max(np.abs(mu)) < 1.0)


def _band_existence(param, a, fa, b, fb, backend, tol, settings=None):
    """Continue the response found at ``a`` or ``b`` across ``[a, b]``: a `_BandEnd`.

    Exactly one of ``fa``, ``fb`` (`beltmdsm.periodic.floquet.Floquet`) is None. The
    response through the other either reaches the far value (Newton's method had
    missed it there) or ends inside at a tangency, a grazing or a fold, located to
    ``min(tol, _END_TOL)``; the bifurcations on the way are edges too.
    """
    found, value, far = (fa, a, b) if fa is not None else (fb, b, a)
    r = found.response
    family = MapFamily(r.model, param, r.periods, backend)

    def floquet_at(v, point):
        return Floquet.of(response_from(family(v), point))

    # the common case first: the response goes on unchanged to where a margin closes
    points, reached, plain = _natural(family, value, r.shooting_state, far)
    solved = [(v, floquet_at(v, p)) for v, p in points[1:]]
    if plain and not reached and len(points) >= 2:
        try:
            end = locate_end(family, points, tol=min(tol, _END_TOL))
        except NoEdge:
            end = None
        if end is not None and not min(value, far) < end.value < max(value, far):
            # a margin's extrapolated zero beyond the interval is no end inside it:
            # the branch decides (Newton's method may have missed the response at far)
            end = None
        if end is not None:
            # the responses of locate_end's trials belong to the branch too: a
            # multiplier crossing may lie among them, and they are the band's responses
            # nearest the end (where a map starts its curve)
            points = points + end.solved
            solved += [(v, floquet_at(v, p)) for v, p in end.solved]
            stable = _verdict(family(end.point_value), end.point)
            side = {("unstable_below" if far > value else "unstable_above"): not stable}
            edge = _special_edge(
                end.kind, end.value, end.accuracy, None, _end_detail(end), True, True
            )
            # a multiplier crossing on the way (the verdict changes between two responses)
            crossings = [
                _multiplier_edge(family, p, q, 1e-9 * abs(far - value))
                for p, q in zip(points[:-1], points[1:])
                if _verdict(family(p[0]), p[1]) != _verdict(family(q[0]), q[1])
            ]
            return _BandEnd(crossings + [dataclasses.replace(edge, **side)], None, solved)
    if plain and reached:
        guess = points[-1][1].state
        at = r.model.replace(**{param: far})
        reached_f = floquet(at, guess=guess, forward=0, backend=backend, periods=r.periods)
        return _BandEnd([], reached_f, solved)
    branch = continue_branch(r, param, min(a, b), max(a, b), backend=backend, settings=settings)
    solved = [
        (q.value, floquet_at(q.value, FixedPoint(q.state, q.image, 0.0, 0)))
        for q in _towards(branch.points, value, far)
    ]
    toward = 1.0 if far > value else -1.0
    out = [
        _from_special(s, s.stable_before is not True, s.stable_after is not True)
        for s in branch.special
        if s.kind in ("neimark_sacker", "period_doubling", "branch_point")
    ]
    # the farthest the branch gets towards the far value is where the response ends
    extreme = max(branch.special, key=lambda s: toward * s.value)
    if extreme.kind == "range" and extreme.value == far:
        near = branch.point_near(far)
        reached_f = floquet(
            branch.model.replace(**{param: far}),
            guess=near.state,
            forward=0,
            backend=backend,
            periods=branch.periods,
        )
        return _BandEnd(out, reached_f, solved)
    if extreme.kind not in KINDS:
        # the continuation stopped (a corrector diverged) short of an end it could
        # locate: no edge, the band bisects what is left (its grid cannot tell)
        return _BandEnd(out, None, solved, stalled=extreme.detail or extreme.kind)
    # no stable response on the side where they exist: neither half at a fold is stable
    exists_unstable = True not in (extreme.stable_before, extreme.stable_after)
    if toward > 0:
        edge = _from_special(extreme, exists_unstable, True)
    else:
        edge = _from_special(extreme, True, exists_unstable)
    return _BandEnd(out + [edge], None, solved)


def _from_special(s: SpecialPoint, unstable_below: bool, unstable_above: bool) -> Edge:
    return _special_edge(
        s.kind, s.value, s.accuracy, s.frequency, s.detail, unstable_below, unstable_above
    )
