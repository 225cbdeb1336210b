"""The special points between two accepted points of a branch, located along the arclength.

A sign change of the tangent's parameter component is a fold; a change in the number of
multipliers outside the unit circle a Neimark-Sacker, period-doubling or branch point,
classified by the critical multiplier (`beltmdsm.continuation.edges.multiplier_kind`).
Each is located by regula falsi (Illinois) to `LOCATE_TOL` in the parameter.

One source for both kinds of branch: the forced responses'
(`beltmdsm.continuation.branch_walk`, on `beltmdsm.continuation.forced`'s corrector)
and the self-excited cycles' (`beltmdsm.cycles.continuation`). A continuation hands in
``cont.trial(start, tangent, s)``, the corrected point at arclength ``s`` from ``start``
along ``tangent`` (raising `NoPeriodicResponse` where its corrector fails); a point has
``value``, ``tangent`` (the parameter component of its unit tangent), ``stable`` and
``multipliers`` (without a cycle's trivial one).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import NoPeriodicResponse
from .branch_result import LOCATE_TOL, SpecialPoint
from .edges import multiplier_kind

__all__ = ["count_outside", "critical", "regula_falsi", "special_between"]


def count_outside(point: Any) -> int:
    """The number of ``point``'s multipliers outside the unit circle.

    Parameters
    ----------
    point
        Any object with ``multipliers`` (an array).

    Returns
    -------
    int

    See Also
    --------
    beltmdsm.continuation.special.critical : the multiplier of a rank.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> count_outside(SimpleNamespace(multipliers=np.array([1.5, -0.2, 0.3 + 1.1j])))
    2
    """
    return int(np.sum(np.abs(point.multipliers) > 1.0))


def critical(point: Any, rank: int) -> complex:
    """The multiplier of rank ``rank`` (0: the largest modulus; a stable sort, so that a
    cycle's multipliers, already in that order, keep it).

    Parameters
    ----------
    point
        Any object with ``multipliers`` (an array).
    rank : int
        0 for the largest modulus; past the last, the last.

    Returns
    -------
    complex

    See Also
    --------
    beltmdsm.continuation.special.count_outside : how many lie outside the unit circle.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> point = SimpleNamespace(multipliers=np.array([0.5, -1.5, 0.9j]))
    >>> complex(critical(point, 0)), complex(critical(point, 1)), complex(critical(point, 7))
    ((-1.5+0j), 0.9j, (0.5+0j))
    """
    mu = point.multipliers[np.argsort(-np.abs(point.multipliers), kind="stable")]
    return mu[min(rank, mu.size - 1)]


def regula_falsi(
    cont: Any,
    start: Any,
    tangent: np.ndarray,
    ds: float,
    psi: Callable[[Any], float],
    fa: float,
    fb: float,
    *,
    s_tol: float,
    fold_scale: float | None = None,
) -> tuple[Any, float]:
    """The arclength ``s`` in ``[0, ds]`` from ``start`` along ``tangent`` where ``psi`` is zero.

    ``psi(point)`` is evaluated at the corrected point of each trial (``cont.trial``; a
    trial whose corrector fails is retried at the bracket's middle); ``fa``, ``fb`` its
    values at the two ends. The bracket shrinks by the Illinois variant of regula falsi
    until its two ends are `LOCATE_TOL` apart in the parameter, or ``s_tol`` apart in
    the (scaled) arclength.

    Parameters
    ----------
    cont
        The continuation: ``cont.trial(start, tangent, s)`` (module docstring).
    start : point
        Where ``s = 0``.
    tangent : ndarray
        The direction (handed to ``cont.trial``).
    ds : float
        The bracket's far end.
    psi : callable
        ``psi(point)``: the function whose zero is located.
    fa, fb : float
        ``psi`` at ``s = 0`` and ``s = ds``, of opposite signs.
    s_tol : float
        The smallest bracket in the arclength.
    fold_scale : float, optional
        Where ``psi`` is the parameter component of the unit tangent (a fold): the
        parameter's scale ``sp`` (``dp/ds = sp psi``). The parameter is then extremal
        inside the bracket, above (or below) both its ends, and the difference of the
        ends' parameters says nothing of the error: the accuracy is the located point's
        distance below the turn, ``sp psi^2 / (2 kappa)`` (``p`` a parabola in ``s``,
        ``psi`` linear, ``kappa = |psi_a - psi_b| / (b - a)`` by the bracket's secant).

    Returns
    -------
    point, accuracy
        The located point and the accuracy in the parameter (inf where the zero's side
        was never reached). For a fold, the accuracy is that distance and the caller
        adds it to the point's value (`special_between`).

    Raises
    ------
    NoPeriodicResponse
        Where a trial's corrector fails at the middle too.

    See Also
    --------
    beltmdsm.continuation.special.special_between : the special points it locates.

    Examples
    --------
    A toy continuation: the curve ``p = 1 - (s - 1)^2`` in the arclength ``s`` from
    ``s = 0``, its tangent turning at ``s = 1`` (a fold), one multiplier
    ``-(0.4 + s / 2)`` through -1 at ``s = 1.2`` (period doubling):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> class Toy:
    ...     def at(self, s):
    ...         mu = np.array([-(0.4 + 0.5 * s)])
    ...         return SimpleNamespace(value=1 - (s - 1) ** 2, tangent=-2 * (s - 1),
    ...                                multipliers=mu, stable=bool(abs(mu[0]) < 1))
    ...     def trial(self, start, tangent, s):
    ...         return self.at(s)
    >>> toy = Toy()
    >>> point, accuracy = regula_falsi(toy, toy.at(0.0), None, 1.5, lambda q: q.tangent,
    ...                                2.0, -1.0, s_tol=1e-12)
    >>> round(point.value, 9), bool(accuracy <= 1e-6)
    (1.0, True)
    """
    a, b = 0.0, ds
    pa_value, pb_value = start.value, None
    located, side = start, 0
    psi_a, psi_b = fa, fb  # the true values at the ends (Illinois halves fa, fb)
    accuracy = math.inf
    for _ in range(60):
        s = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        s = min(max(s, a + 1e-3 * (b - a)), b - 1e-3 * (b - a))
        try:
            pt = cont.trial(start, tangent, s)
        except NoPeriodicResponse:
            s = 0.5 * (a + b)
            pt = cont.trial(start, tangent, s)
        fs = psi(pt)
        if fs * fa > 0:
            a, fa, pa_value, psi_a = s, fs, pt.value, fs
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb, pb_value, psi_b = s, fs, pt.value, fs
            if side == 1:
                fa *= 0.5
            side = 1
        located = pt
        if fold_scale is not None:
            accuracy = fold_scale * fs * fs * (b - a) / (2.0 * abs(psi_a - psi_b))
        elif pb_value is not None:
            accuracy = abs(pb_value - pa_value)
        if accuracy <= LOCATE_TOL or b - a <= s_tol:
            break
    return located, accuracy


def special_between(
    cont: Any,
    prev: Any,
    new: Any,
    tangent: np.ndarray,
    ds: float,
    period: Callable[[Any], float],
    *,
    s_tol: float,
) -> list[SpecialPoint]:
    """The special points between two accepted points of one switch structure.

    Parameters
    ----------
    cont
        The continuation (``cont.trial``, module docstring).
    prev, new : point
        The two points; ``new`` at arclength ``ds`` from ``prev`` along ``tangent``.
    tangent : ndarray
    ds : float
    period : callable
        ``period(point)``: the orbit's period at a located point [s], for the frequency
        of a Neimark-Sacker pair.
    s_tol : float
        `regula_falsi`'s smallest bracket in the arclength.

    Returns
    -------
    list of SpecialPoint
        A fold and a multiplier's crossing, nearest ``prev`` first (a real multiplier
        through +1 at a fold is the fold's, not a second point).

    Raises
    ------
    NoPeriodicResponse
        Where a trial's corrector fails (`regula_falsi`): the caller shortens its step.

    See Also
    --------
    beltmdsm.continuation.branch.branch : the forced responses' branches.
    beltmdsm.cycles.branch.cycle_branch : the self-excited cycles' branches.

    Examples
    --------
    A toy continuation: the curve ``p = 1 - (s - 1)^2`` in the arclength ``s`` from
    ``s = 0``, its tangent turning at ``s = 1`` (a fold), one multiplier
    ``-(0.4 + s / 2)`` through -1 at ``s = 1.2`` (period doubling):

    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> class Toy:
    ...     sp = 1.0  # the parameter's scale: ``value`` unscaled
    ...     def at(self, s):
    ...         mu = np.array([-(0.4 + 0.5 * s)])
    ...         return SimpleNamespace(value=1 - (s - 1) ** 2, tangent=-2 * (s - 1),
    ...                                multipliers=mu, stable=bool(abs(mu[0]) < 1))
    ...     def trial(self, start, tangent, s):
    ...         return self.at(s)
    >>> toy = Toy()
    >>> found = special_between(toy, toy.at(0.0), toy.at(1.5), None, 1.5, lambda q: 1.0,
    ...                         s_tol=1e-12)
    >>> [(s.kind, round(s.value, 6)) for s in found]
    [('period_doubling', 0.96), ('fold', 1.0)]
    """
    out = []
    if prev.tangent * new.tangent < 0:
        # the located point lies below the turn by ``acc`` (`regula_falsi`'s fold_scale):
        # the turn is its value plus that, known to better than ``acc``
        pt, acc = regula_falsi(
            cont, prev, tangent, ds, lambda q: q.tangent, prev.tangent, new.tangent,
            s_tol=s_tol, fold_scale=cont.sp,
        )  # fmt: skip
        turn = math.copysign(acc, prev.tangent) if math.isfinite(acc) else 0.0
        out.append(
            SpecialPoint(
                "fold",
                pt.value + turn,
                acc,
                None,
                pt.multipliers,
                prev.stable,
                new.stable,
                "the branch turns back",
            )
        )
    na, nb = count_outside(prev), count_outside(new)
    if na != nb:
        rank = min(na, nb)

        def psi(q, rank=rank):
            return math.log(abs(critical(q, rank)))

        pt, acc = regula_falsi(cont, prev, tangent, ds, psi, psi(prev), psi(new), s_tol=s_tol)
        kind, frequency = multiplier_kind(critical(pt, rank), period(pt))
        if kind == "fold" and out:
            # the multiplier through +1 of the fold located above by the turn
            return out
        if kind == "fold":
            kind = "branch_point"
        detail = (
            f"a complex pair crosses the unit circle at {frequency:.6g} rad/s"
            if kind == "neimark_sacker"
            else "a real multiplier crosses -1"
            if kind == "period_doubling"
            else "a real multiplier crosses +1"
        )
        out.append(
            SpecialPoint(
                kind, pt.value, acc, frequency, pt.multipliers, prev.stable, new.stable, detail
            )
        )
    return sorted(out, key=lambda s: abs(s.value - prev.value))
