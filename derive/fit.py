"""Least-squares polynomial fit of ``X2^(3/2)`` on ``[0, X2max]`` (Eqs. 16-17).

The continuous L2 fit is exact in rational arithmetic after scaling ``s = X2/X2max``:
the normal equations have the Hilbert matrix ``1/(j+k+1)`` and the right-hand side
``1/(k+5/2)``. Every coefficient is a rational times a power of ``X2max``, so the
fit of any degree, its largest error, where it sits, and its RMS error are exact
closed forms in ``X2max``. Degree 3 reproduces Eq. (17).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

__all__ = [
    "X2max",
    "s",
    "FitError",
    "scaled_coefficients",
    "coefficients_eq_17",
    "polynomial_eq_16",
    "scaled_error",
    "fit_error",
    "DEGREES",
]

X2max = sp.Symbol("X2max", positive=True)
#: Scaled penetration X2/X2max in [0, 1].
s = sp.Symbol("s", nonnegative=True)
DEGREES = tuple(range(1, 9))


@cache
def scaled_coefficients(degree: int) -> tuple[sp.Rational, ...]:
    """Exact ``d_k`` of the best ``sum d_k s^k`` to ``s^(3/2)`` on ``[0, 1]`` in L2."""
    n = degree + 1
    gram = sp.Matrix(n, n, lambda j, k: sp.Rational(1, j + k + 1))
    moments = sp.Matrix(n, 1, lambda k, _: 1 / (k + sp.Rational(5, 2)))
    return tuple(gram.LUsolve(moments))


def coefficients_eq_17(degree: int = 3) -> tuple[sp.Expr, ...]:
    """``(c0, ..., c_degree)`` with ``X2^(3/2) ~ sum c_k X2^k``, Eq. (17) for degree 3."""
    return tuple(
        d * X2max ** (sp.Rational(3, 2) - k) for k, d in enumerate(scaled_coefficients(degree))
    )


def polynomial_eq_16(X2, degree: int = 3) -> sp.Expr:
    """The fitted polynomial in ``X2``, Eq. (16)."""
    return sum(c * X2**k for k, c in enumerate(coefficients_eq_17(degree)))


@dataclass(frozen=True)
class FitError:
    """Error of the fit on ``[0, 1]`` in the scaled variable, exact.

    The error in ``X2`` is ``X2max^(3/2)`` times these (at ``X2 = X2max * argmax``).
    ``max_abs`` and ``argmax`` may be algebraic numbers (``CRootOf``) when the
    largest error sits at an interior extremum.
    """

    max_abs: sp.Expr
    argmax: sp.Expr
    rms: sp.Expr


@cache
def scaled_error(degree: int = 3) -> FitError:
    """Largest absolute error, its location and the RMS error on ``[0, 1]``, exactly.

    Interior extrema solve ``(3/2) u = p'(u^2)`` with ``u = sqrt(s)``: a polynomial in
    ``u`` whose real roots in ``(0, 1)`` SymPy isolates exactly.
    """
    d = scaled_coefficients(degree)
    p = sum(c * s**k for k, c in enumerate(d))
    err = s ** sp.Rational(3, 2) - p
    u = sp.Symbol("u", nonnegative=True)
    stationary = sp.Poly(sp.Rational(3, 2) * u - sp.diff(p, s).subs(s, u**2), u)
    candidates = [sp.Integer(0), sp.Integer(1)]
    candidates += [r**2 for r in stationary.real_roots() if 0 < r < 1]
    values = [(sp.Abs(err.subs(s, c)), c) for c in candidates]
    best, where = max(values, key=lambda v: sp.N(v[0], 50))
    rms = sp.sqrt(sp.integrate(sp.expand(err**2), (s, 0, 1)))
    return FitError(best, where, sp.simplify(rms))


def fit_error(degree: int = 3) -> FitError:
    """`scaled_error` in ``X2``: largest error, where it sits, and RMS, in ``X2max``."""
    e = scaled_error(degree)
    scale = X2max ** sp.Rational(3, 2)
    return FitError(e.max_abs * scale, e.argmax * X2max, e.rms * scale)
