"""A guard along one accepted step as a polynomial, with the error the values show.

Where a guard of a mode may fall to 0 inside an accepted step, without a sample below
0 (a short excursion between them), `beltmdsm.oscillator.guards.touch` and its
compiled twin look for it on this polynomial, not on a few samples of its rate.

The error model. The step's dense output (DOP853's interpolant) is a polynomial of
degree 7 in ``x = (t - t0) / h``, and the step-size control holds what the run
integrates to its tolerances over the step: the slip velocity and the gap are affine
in the state, and in stick the two sides of the cone are integrated beside it
(`beltmdsm.oscillator.hybrid`). So a guard along the step is a smooth function of
``x`` that its interpolant ``Q`` at the ``NODES`` (the 9 Chebyshev-Lobatto points of
``[0, 1]``, ends and middle included) represents within ``e`` (`error`): twice the
magnitude of ``Q``'s last Chebyshev coefficient (the tail of a Chebyshev series that
decays at least as 1/2 per degree, exactly 0 but for rounding where the guard is a
polynomial of degree <= 7 in ``x``), plus the rounding of the values and of the
conversion to Bernstein form. A dip shallower than the step-size control resolves (a
guard that the step does not resolve) is below the run's tolerances.

In Bernstein form, ``Q`` on an interval lies within the hull of its coefficients there
(`split`: de Casteljau's subdivision): where every coefficient exceeds ``e``, the
guard is > 0 on the interval. What is not cleared so is split down to ``1 /
2**DEPTH`` of the interval searched, and there the guard's own values and rates
decide. Plain functions of numbers, compiled by numba for
`beltmdsm.oscillator._compiled` as `beltmdsm.integrate._roots` is.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["NODES", "TO_BERNSTEIN", "DEPTH", "bernstein", "error", "split", "lowest"]

#: The degree of the guard's polynomial on a step (the dense output's 7, and one more
#: whose coefficient measures the rest).
DEGREE = 8
#: The Chebyshev-Lobatto points of [0, 1], ascending: 0, ..., 1/2, ..., 1.
NODES = 0.5 * (1.0 - np.cos(np.arange(DEGREE + 1) * math.pi / DEGREE))
#: Values at the NODES -> Bernstein coefficients of their interpolant.
TO_BERNSTEIN = np.linalg.inv(
    np.array(
        [
            [math.comb(DEGREE, i) * x**i * (1.0 - x) ** (DEGREE - i) for i in range(DEGREE + 1)]
            for x in NODES
        ]
    )
)
#: The rounding of a value and of its Bernstein coefficients, relative to the largest
#: value: a few ulps times the conversion's norm (184).
ROUNDING = 4.0 * np.finfo(float).eps * (1.0 + float(np.abs(TO_BERNSTEIN).sum(axis=1).max()))
#: Halvings of the searched interval down to where the guard's own values decide.
DEPTH = 6


def bernstein(values, out) -> None:
    """The Bernstein coefficients of the interpolant of ``values`` at the `NODES`."""
    for i in range(DEGREE + 1):
        acc = 0.0
        for j in range(DEGREE + 1):
            acc += TO_BERNSTEIN[i, j] * values[j]
        out[i] = acc


def error(values) -> float:
    """``e``: a bound on ``|guard - Q|`` over the step (module docstring). The last
    Chebyshev coefficient of the interpolant at the Lobatto points is the alternating
    sum of the values, the ends halved, over the degree."""
    last = 0.0
    top = 0.0
    for j in range(DEGREE + 1):
        w = 0.5 if j == 0 or j == DEGREE else 1.0
        last += w * values[j] if j % 2 == 0 else -w * values[j]
        top = max(top, abs(values[j]))
    return 2.0 * abs(last) / DEGREE + ROUNDING * top


def split(c, x, left, right) -> None:
    """De Casteljau's subdivision at ``x`` in (0, 1): the Bernstein coefficients of the
    polynomial on ``[0, x]`` into ``left``, on ``[x, 1]`` into ``right`` (``c`` may be
    either of them)."""
    n = c.shape[0]
    for i in range(n):
        right[i] = c[i]
    for r in range(n):
        left[r] = right[0]
        for i in range(n - 1 - r):
            right[i] = (1.0 - x) * right[i] + x * right[i + 1]


def lowest(c) -> float:
    """The least coefficient: ``Q`` is no lower on its interval."""
    low = c[0]
    for i in range(1, c.shape[0]):
        low = min(low, c[i])
    return low
