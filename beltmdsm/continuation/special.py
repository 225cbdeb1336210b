"""The special points between two accepted points of a branch, located along the arclength.

A sign change of the tangent's parameter component is a fold; a change in the number of
multipliers outside the unit circle a Neimark-Sacker, period-doubling or branch point,
classified by the critical multiplier (`beltmdsm.continuation.edges.multiplier_kind`).
Each is located by regula falsi (Illinois) to `LOCATE_TOL` in the parameter.
"""

from __future__ import annotations

import math

import numpy as np

from ..periodic.periodmap import NoPeriodicResponse
from .branch_parts import LOCATE_TOL, SpecialPoint
from .edges import multiplier_kind


def _count_outside(point):
    return int(np.sum(np.abs(point.multipliers) > 1.0))


def _critical(point, rank):
    """The multiplier of rank ``rank`` (0: the largest modulus)."""
    mu = point.multipliers[np.argsort(-np.abs(point.multipliers))]
    return mu[min(rank, mu.size - 1)]


def _regula_falsi(cont, start, tangent, ds, psi, fa, fb):
    """The arclength ``s`` in ``[0, ds]`` from ``start`` along ``tangent`` where ``psi`` is zero.

    ``psi(point)`` is evaluated at the corrected point of each trial; ``fa``, ``fb``
    its values at the two ends. Returns the located `BranchPoint` and the accuracy in
    the parameter.
    """
    a, b = 0.0, ds
    pa_value = start.value
    z0 = cont.z(start.state, start.value)
    located, pb_value = start, None
    side = 0
    for _ in range(60):
        s = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        s = min(max(s, a + 1e-3 * (b - a)), b - 1e-3 * (b - a))
        try:
            x, value, image, J, _ = cont.correct(z0 + s * tangent, tangent, start.column)
        except NoPeriodicResponse:
            s = 0.5 * (a + b)
            x, value, image, J, _ = cont.correct(z0 + s * tangent, tangent, start.column)
        t = cont.tangent(J, tangent)
        pt = cont.point(x, value, float(t[-1]), image)
        fs = psi(pt)
        if fs * fa > 0:
            a, fa, pa_value = s, fs, value
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb, pb_value = s, fs, value
            if side == 1:
                fa *= 0.5
            side = 1
        located = pt
        if pb_value is not None and abs(pb_value - pa_value) <= LOCATE_TOL:
            break
        if b - a <= 1e-12:
            break
    accuracy = abs(pb_value - pa_value) if pb_value is not None else math.inf
    return located, accuracy


def _special_between(cont, prev, new, tangent, ds, kT):
    """The special points between two accepted points (same switch structure)."""
    out = []
    if prev.tangent * new.tangent < 0:
        pt, acc = _regula_falsi(
            cont, prev, tangent, ds, lambda q: q.tangent, prev.tangent, new.tangent
        )
        out.append(
            SpecialPoint(
                "fold",
                pt.value,
                acc,
                None,
                pt.multipliers,
                prev.stable,
                new.stable,
                "the branch turns back",
            )
        )
    na, nb = _count_outside(prev), _count_outside(new)
    if na != nb:
        rank = min(na, nb)

        def psi(q, rank=rank):
            return math.log(abs(_critical(q, rank)))

        pt, acc = _regula_falsi(cont, prev, tangent, ds, psi, psi(prev), psi(new))
        kind, frequency = multiplier_kind(_critical(pt, rank), kT)
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
