"""What happens at the edge of a periodic response: bifurcation kinds, classified and located.

A periodic response (of period ``k T``, `beltmdsm.periodic.base`) changes at a parameter
value in one of these ways (docs/modelling.md#bifurcations says what a run near each
looks like):

* ``neimark_sacker``: a complex pair of multipliers crosses the unit circle; the
  frequency of the pair, ``|arg mu| / (k T)``, is that of the oscillation that grows
  (defined modulo ``2 pi / (k T)``).
* ``period_doubling``: a real multiplier crosses -1.
* ``fold``: a real multiplier reaches +1 where the branch turns back: two responses
  (one stable, one not, or two unstable) meet and end. `beltmdsm.continuation.branch` continues
  through it.
* ``grazing``: a segment of the orbit touches a switching surface that it did not
  cross, or Filippov's choice at a switch reaches a tie (a stick phase appears or
  disappears): the switch structure changes (`beltmdsm.periodic.margins.Margin` of kind
  ``approach`` or ``decision`` reaches zero). The response may go on with the new
  structure, or end.
* ``tangency``: a crossing of the orbit becomes tangential (a ``crossing`` margin
  reaches zero): the saltation matrix diverges like one over the crossing rate, and
  so does the largest multiplier; the response ends there. It is grazing seen from
  the side where the orbit crosses.

The paper's linear analysis (Sect. 4.3, Eqs. 26-28) sees an edge only where a pair of
eigenvalues of the slow equations crosses the imaginary axis, the counterpart of
``neimark_sacker``. `beltmdsm.continuation.band.floquet_band` used the kinds ``multiplier`` (now
``neimark_sacker``, ``period_doubling`` or ``fold``), ``existence`` (now ``tangency``,
``grazing`` or ``fold``) and ``grazing``; its edges keep the old one as ``old_kind``
for one release (`OLD_KINDS`).

`locate_end` finds where a response ends at a tangency or a grazing: the margin that
closes is a smooth function of the parameter up to the end, so the secant of its
values at responses on the side where they exist, each continued from the last two,
converges to its zero without ever solving for a response at the degenerate point.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..errors import (
    NoEdge,  # its home; importable here as before
    NoPeriodicResponse,
)
from ..periodic.base import PeriodMap
from ..periodic.family import MapFamily
from ..periodic.margins import MARGIN_KINDS, Margin
from ..periodic.newton import FixedPoint, fixed_point

__all__ = [
    "KINDS",
    "OLD_KINDS",
    "NoEdge",
    "End",
    "multiplier_kind",
    "log_max_multiplier",
    "margin_kind",
    "closing_margins",
    "counterpart",
    "locate_end",
]

#: The bifurcation kinds (module docstring).
KINDS = ("neimark_sacker", "period_doubling", "fold", "grazing", "tangency")
#: The kind that `beltmdsm.continuation.band.floquet_band` gave an edge before, by the new kind.
OLD_KINDS = {
    "neimark_sacker": "multiplier",
    "period_doubling": "multiplier",
    "fold": "existence",
    "grazing": "grazing",
    "tangency": "existence",
}
#: A multiplier whose imaginary part is below this share of its modulus is real.
REAL_SHARE = 1e-6
#: Trials of `locate_end` before it gives up.
_END_TRIALS = 40


def multiplier_kind(mu: complex, period: float) -> tuple[str, float | None]:
    """The kind of a multiplier on the unit circle, and the frequency of a complex pair.

    Parameters
    ----------
    mu : complex
        The critical multiplier.
    period : float
        ``k T`` [s].

    Returns
    -------
    (kind, frequency)
        ``("neimark_sacker", |arg mu| / period)``, ``("period_doubling", None)`` or
        ``("fold", None)``.

    Raises
    ------
    TypeError
        Where ``mu`` is not a number.

    See Also
    --------
    beltmdsm.continuation.edges.log_max_multiplier : the critical multiplier of a response.

    Examples
    --------
    >>> import cmath
    >>> kind, frequency = multiplier_kind(cmath.exp(0.5j), 2.0)
    >>> kind, round(frequency, 6)
    ('neimark_sacker', 0.25)
    >>> multiplier_kind(-1.0, 2.0), multiplier_kind(1.0 + 1e-9j, 2.0)
    (('period_doubling', None), ('fold', None))
    """
    mu = complex(mu)
    if abs(mu.imag) > REAL_SHARE * abs(mu):
        return "neimark_sacker", abs(math.atan2(mu.imag, mu.real)) / period
    return ("period_doubling", None) if mu.real < 0 else ("fold", None)


def margin_kind(margin: Margin) -> str:
    """``tangency`` for a crossing margin, ``grazing`` for the others.

    Parameters
    ----------
    margin : Margin
        `beltmdsm.periodic.margins.Margin`.

    Returns
    -------
    {"tangency", "grazing"}

    See Also
    --------
    beltmdsm.continuation.edges.locate_end : where a margin closes.

    Examples
    --------
    >>> from beltmdsm.integrate.switching import Mode
    >>> from beltmdsm.periodic.margins import Margin
    >>> margin_kind(Margin("crossing", "relative_velocity", Mode.SLIP_BACK, 0.7, 0.02))
    'tangency'
    >>> margin_kind(Margin("approach", "relative_velocity", Mode.SLIP_BACK, 0.7, 0.02))
    'grazing'
    """
    return "tangency" if margin.kind == "crossing" else "grazing"


def counterpart(margin, margins, window):
    """The margin of another orbit on the same branch that is ``margin`` (same feature).

    Parameters
    ----------
    margin : Margin
    margins : list of Margin
        The other orbit's.
    window : float
        How far in time [s] the feature may have moved.

    Returns
    -------
    Margin or None
        Of the same kind, surface and mode, nearest in time within ``window``.

    See Also
    --------
    beltmdsm.continuation.edges.closing_margins : the margins that fall between two orbits.

    Examples
    --------
    >>> from beltmdsm.integrate.switching import Mode
    >>> from beltmdsm.periodic.margins import Margin
    >>> m = Margin("crossing", "relative_velocity", Mode.SLIP_BACK, 0.70, 0.02)
    >>> others = [Margin("crossing", "relative_velocity", Mode.SLIP_BACK, 0.72, 0.01),
    ...           Margin("crossing", "relative_velocity", Mode.SLIP_FORWARD, 0.70, 0.1)]
    >>> counterpart(m, others, 0.1).t, counterpart(m, others, 0.01)
    (0.72, None)
    """
    same = [
        m
        for m in margins
        if (m.kind, m.surface, m.mode) == (margin.kind, margin.surface, margin.mode)
        and abs(m.t - margin.t) <= window
    ]
    return min(same, key=lambda m: abs(m.t - margin.t)) if same else None


def closing_margins(
    a: Sequence[Margin], b: Sequence[Margin], va: float, vb: float, window: float
) -> list[tuple[float, Margin]]:
    """The margins of orbit ``b`` that fall from orbit ``a``, with the secant's zero.

    Parameters
    ----------
    a, b : list of Margin
        The margins of two orbits of one branch, at parameter values ``va`` and ``vb``.
    window : float
        How far in time [s] a feature may move between the two.

    Returns
    -------
    list of (value, Margin)
        Where the secant through the two values of each falling margin is zero, beyond
        ``vb`` as seen from ``va``; nearest first.

    Raises
    ------
    AttributeError
        Where an item of ``a`` or ``b`` is no `beltmdsm.periodic.margins.Margin`.

    See Also
    --------
    beltmdsm.continuation.edges.locate_end : the zero located exactly.

    Examples
    --------
    The crossing margin of the response at ``Vb`` 6.0 and 6.1 falls towards a
    tangency near 6.16 (`locate_end` places it exactly):

    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.family import MapFamily
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> family = MapFamily(Model(), "Vb")
    >>> a = fixed_point(family(6.0), periodic_response(Model(Vb=6.0)).shooting_state)
    >>> b = fixed_point(family(6.1), a.state)
    >>> crossing = ("crossing",)
    >>> found = closing_margins(a.image.margins_of(crossing), b.image.margins_of(crossing),
    ...                         6.0, 6.1, 1.0)
    >>> zero, margin = found[0]
    >>> round(zero, 2), margin.surface
    (6.18, 'relative_velocity')
    """
    out = []
    for mb in b:
        ma = counterpart(mb, a, window)
        if ma is None or not ma.value > mb.value:
            continue
        zero = vb + mb.value * (vb - va) / (ma.value - mb.value)
        out.append((zero, mb))
    return sorted(out, key=lambda z: abs(z[0] - vb))


@dataclass
class End:
    """Where a response ends at a tangency or a grazing.

    Attributes
    ----------
    kind : {"tangency", "grazing"}
    value : float
        The parameter value: the zero of the closing margin's secant.
    accuracy : float
        The distance from ``value`` to the nearest response solved (an upper bound of
        the error; the secant's own error is of second order in it).
    margin : Margin
        The closing margin at that response.
    point : FixedPoint
        That response.
    point_value : float
        Its parameter value.
    solved : list of (float, FixedPoint)
        Every response solved on the way, in order.
    chain : list of (float, float)
        The parameter values and closing margins that ``value`` was fitted to (the
        polynomial of `_zero`), towards the end.

    See Also
    --------
    beltmdsm.continuation.edges.locate_end : returns it.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.family import MapFamily
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> family = MapFamily(Model(), "Vb")
    >>> a = fixed_point(family(6.0), periodic_response(Model(Vb=6.0)).shooting_state)
    >>> b = fixed_point(family(6.1), a.state)
    >>> end = locate_end(family, [(6.0, a), (6.1, b)])
    >>> end.kind, round(end.value, 5), bool(end.accuracy < 1e-6), end.margin.surface
    ('tangency', 6.16435, True, 'relative_velocity')
    """

    kind: str
    value: float
    accuracy: float
    margin: Margin
    point: FixedPoint
    point_value: float
    solved: list = field(default_factory=list, repr=False)
    chain: list = field(default_factory=list, repr=False)


def _same_structure(a: FixedPoint, b: FixedPoint) -> bool:
    return a.image.signature == b.image.signature


def _zero(values, margins):
    """The parameter value where a margin vanishes: inverse interpolation.

    The parameter is a smooth function of the closing margin up to the end (also where
    the branch meets the end almost at right angles to the parameter axis); the
    polynomials through the last points, of degree 1 up to 3 (as many as the points
    allow), evaluated at zero. Lowest degree first.
    """
    out = []
    for degree in range(1, min(3, len(values) - 1) + 1):
        v = np.asarray(values[-(degree + 1) :], dtype=float)
        m = np.asarray(margins[-(degree + 1) :], dtype=float)
        out.append(float(np.polyval(np.polyfit(m, v, degree), 0.0)))
    return out


def locate_end(
    family: MapFamily,
    points: Sequence[tuple[float, FixedPoint]],
    tol: float = 1e-7,
    required: float = 1e-4,
    kinds: Sequence[str] = MARGIN_KINDS,
) -> End:
    """Where the response through ``points`` ends, by the margin that closes.

    The margin that closes is a smooth function of the parameter up to the end. Each
    trial continues the response (quadratic predictor through the last three) to a
    value short of the margin's predicted zero; a trial that finds no response, or
    one whose structure has changed, halves the reach (close to a tangency Newton's
    method converges only from ever better guesses). The zero is that of the
    polynomial through the last margins (degree 3 where four are known), and its
    accuracy the distance to the zero of one degree less.

    Parameters
    ----------
    family : MapFamily
    points : list of (value, FixedPoint)
        At least two responses of one branch, in order towards the end.
    tol : float
        Stop when the accuracy is below it.
    required : float
        Raise NoEdge when the trials end with an accuracy above it.
    kinds : tuple of str
        The kinds of margin that may close (`beltmdsm.periodic.margins.MARGIN_KINDS`); where
        the kind is known, a narrower choice saves the search of the ``approach``
        margins.

    Returns
    -------
    End

    Raises
    ------
    ValueError
        For fewer than two ``points``.
    NoEdge
        If no margin of the response falls towards the end (it does not end at a
        tangency or a grazing: a fold, or a failure of Newton's method), or its zero
        is not found to ``required``.

    See Also
    --------
    beltmdsm.continuation.edges.closing_margins : the first secant.
    beltmdsm.continuation.branch.branch : ends a branch where its corrector fails.

    Examples
    --------
    The response of the base set ends at a tangency at ``Vb`` = 6.16435 (its crossing
    of the relative velocity's zero in backward slip becomes tangential):

    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.family import MapFamily
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> family = MapFamily(Model(), "Vb")
    >>> a = fixed_point(family(6.0), periodic_response(Model(Vb=6.0)).shooting_state)
    >>> b = fixed_point(family(6.1), a.state)
    >>> end = locate_end(family, [(6.0, a), (6.1, b)])
    >>> end.kind, round(end.value, 5), end.margin.mode.name
    ('tangency', 6.16435, 'SLIP_BACK')
    """
    points = list(points)
    if len(points) < 2:
        raise ValueError("locate_end needs two responses")
    window = 0.25 * family.periods * family(points[-1][0]).period
    solved, reach = [], 0.9
    best = None
    for _ in range(_END_TRIALS):
        (va, pa), (vb, pb) = points[-2], points[-1]
        closing = closing_margins(
            pa.image.margins_of(kinds), pb.image.margins_of(kinds), va, vb, window
        )
        if not closing:
            raise NoEdge(
                f"no margin of the response falls from {family.param} = {va:.6g} to {vb:.6g}"
            )
        first_zero, margin = closing[0]
        # the margin's chain back along the points, each at least 1.5 times as far
        # from the last as the one before and the first half the gap to the end
        # (points crowded at the end would make the fit noise)
        chain, gap = [(vb, margin)], max(0.5 * abs(first_zero - vb), 1e-300)
        for v, p in reversed(points[:-1]):
            if len(chain) == 4:
                break
            if abs(v - vb) < gap:
                continue
            m = counterpart(chain[-1][1], p.image.margins_of(kinds), window)
            if m is None or not m.value > chain[-1][1].value:
                break
            chain.append((v, m))
            gap = 1.5 * abs(v - vb)
        chain.reverse()
        if len(chain) < 2:
            chain = [(va, counterpart(margin, pa.image.margins_of(kinds), window)), (vb, margin)]
        chain = [(v, m.value) for v, m in chain]
        zeros = _zero([v for v, _ in chain], [m for _, m in chain])
        zero = zeros[-1]
        accuracy = abs(zero - zeros[-2]) if len(zeros) > 1 else abs(zero - vb)
        accuracy = max(accuracy, 1e-3 * abs(zero - vb))
        best = End(margin_kind(margin), zero, accuracy, margin, pb, vb, solved, chain)
        if accuracy <= tol or reach < 1e-3:
            break
        v = vb + reach * (zero - vb)
        known = np.array([q for q, _ in points[-3:]])
        states = np.array([p.state for _, p in points[-3:]])
        coefficients = np.polyfit(known - vb, states, min(2, known.size - 1))
        guess = np.array([np.polyval(coefficients[:, i], v - vb) for i in range(states.shape[1])])
        try:
            pv = fixed_point(family(v), guess)
        except NoPeriodicResponse:
            pv = None
        if pv is None or not _same_structure(pv, pb):
            reach *= 0.5
            continue
        solved.append((v, pv))
        points.append((v, pv))
        reach = min(0.9, 2 * reach)
    if best is None or best.accuracy > required:
        raise NoEdge(
            f"the zero of the closing margin near {family.param} = {vb:.8g} is not "
            f"found to {required:g}" + ("" if best is None else f" (accuracy {best.accuracy:.1e})")
        )
    return best


def log_max_multiplier(pmap: PeriodMap, point: FixedPoint) -> tuple[float, complex]:
    """``log max |mu|`` of a response and its critical multiplier.

    Parameters
    ----------
    pmap : PeriodMap
        The period map at the response's parameter values (its fixed multipliers).
    point : FixedPoint
        The response (`beltmdsm.periodic.newton.fixed_point`).

    Returns
    -------
    (float, complex)
        ``log max |mu|`` over the monodromy's and the fixed multipliers, and that
        multiplier.

    Raises
    ------
    ValueError
        Where the largest multiplier is 0 (``log`` of zero).

    See Also
    --------
    beltmdsm.continuation.edges.multiplier_kind : the critical multiplier's kind.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.family import MapFamily
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> family = MapFamily(Model(), "Vb")
    >>> a = fixed_point(family(6.0), periodic_response(Model(Vb=6.0)).shooting_state)
    >>> b = fixed_point(family(6.1), a.state)
    >>> g, mu = log_max_multiplier(family(6.0), a)
    >>> round(g, 4), multiplier_kind(mu, family(6.0).period)[0]
    (0.6214, 'neimark_sacker')
    """
    mu = np.concatenate([np.linalg.eigvals(point.image.jacobian), pmap.fixed_multipliers()])
    k = int(np.argmax(np.abs(mu)))
    return math.log(float(abs(mu[k]))), mu[k]
