"""Least-squares polynomial fit of the contact law's power ``X2^n`` on ``[0, X2max]`` (Eqs. 16-17).

The MDSM replaces the power of the penetration in the contact force (``X2^(3/2)`` of
Eq. 1) by a polynomial (Eq. 16). The exponent ``n`` is the contact law's
(`exponent`, derived from its elastic force): 3/2 for Hertz-Damp, 1 for Kelvin-Voigt
(the fit is exact), the symbol ``n_h`` for Hunt-Crossley.

The continuous L2 fit is exact after scaling ``s = X2/X2max``: the normal equations
have the Hilbert matrix ``1/(j+k+1)`` and the right-hand side ``1/(k+n+1)``, so every
coefficient is a rational function of ``n`` times a power of ``X2max``, solved with
the exact inverse of the Hilbert matrix. Degree 3 at ``n = 3/2`` reproduces Eq. (17).
The RMS error follows from the normal equations,
``int (s^n - p)^2 = 1/(2n+1) - sum_k d_k/(k+n+1)``, a closed form in ``n``. The
largest error is exact for a rational exponent (its interior extrema are algebraic
numbers that SymPy isolates); for a symbolic exponent it is the larger of the two
end values, which are closed forms in ``n`` (`FitError.endpoints`).
"""

from __future__ import annotations

import functools
import operator
from dataclasses import dataclass
from functools import cache

import sympy as sp
from sympy.core.exprtools import _keep_coeff

from . import laws
from .model import X2, normal_force

__all__ = [
    "X2max",
    "s",
    "FitError",
    "exponent",
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
#: Eq. (1)'s exponent, the default of the scaled fit.
HERTZ = sp.Rational(3, 2)
_CONTACT = laws.default("contact")


@cache
def exponent(contact: str = _CONTACT) -> sp.Expr:
    """The power ``n`` of the penetration in the contact law's elastic force ``k X2^n``.

    Derived as ``X2 F'(X2) / F(X2)`` of the force at rest (``X2' = 0``).

    Raises
    ------
    ValueError
        If that ratio depends on ``X2``: the elastic force is not a power of the
        penetration, and the polynomial fit of the MDSM has nothing to replace.
    """
    F = normal_force(contact, X2, 0)
    n = sp.simplify(X2 * sp.diff(F, X2) / F)
    if X2 in n.free_symbols:
        raise ValueError(f"{contact}: the elastic force {F} is not a power of X2")
    return n


@cache
def _hilbert_inverse(size: int) -> sp.Matrix:
    return sp.Matrix(size, size, lambda j, k: sp.Rational(1, j + k + 1)).inv()


def _moments(degree: int, n) -> list:
    """``int_0^1 s^n s^k ds = 1/(k + n + 1)``, ``k = 0..degree``."""
    return [1 / (k + n + 1) for k in range(degree + 1)]


def _cofactors(degree: int, n) -> tuple[sp.Poly, list]:
    """``D = prod_k (n + k + 1)`` and ``D / (n + k + 1)`` as polynomials in ``n``: the
    moments of a symbolic exponent over a common denominator, so that every closed
    form below is a polynomial in ``n`` (factored at once) over a product of linear
    factors. Polynomial arithmetic (``Poly``) keeps this fast for degree 8."""
    factors = [sp.Poly(n + k + 1, n, domain="QQ") for k in range(degree + 1)]
    one = sp.Poly(1, n, domain="QQ")
    D = functools.reduce(operator.mul, factors, one)
    return D, [
        functools.reduce(operator.mul, factors[:k] + factors[k + 1 :], one)
        for k in range(degree + 1)
    ]


def _over(numerator: sp.Poly, denominator: sp.Poly) -> sp.Expr:
    """``numerator / denominator`` with both factored."""
    return _factored(numerator) / _factored(denominator)


def _factored(p: sp.Poly) -> sp.Expr:
    """``sp.factor(p.as_expr())``, from the polynomial's own factorisation.

    The same expression (``factor``'s content times the product of the factors' powers),
    without ``factor``'s pass back through expressions (``together``, ``gcd_terms``:
    half its time here). Where the generator is not a symbol (an exponent such as
    ``2 m``), ``factor`` would factor in the symbols: it is called.
    """
    if not p.gen.is_Symbol:
        return sp.factor(p.as_expr())
    coeff, factors = p.factor_list()
    return _keep_coeff(sp.sympify(coeff), sp.Mul(*(f.as_expr() ** k for f, k in factors)))


@cache
def scaled_coefficients(degree: int, n=HERTZ) -> tuple[sp.Expr, ...]:
    """Exact ``d_k`` of the best ``sum d_k s^k`` to ``s^n`` on ``[0, 1]`` in L2.

    For a rational ``n`` the normal equations are solved in rational arithmetic; for a
    symbolic one ``d = H^-1 m`` with the exact inverse of the Hilbert matrix ``H`` and
    the moments over their common denominator (`_cofactors`).
    """
    if n.is_Rational:
        m = sp.Matrix(_moments(degree, n))
        gram = sp.Matrix(degree + 1, degree + 1, lambda j, k: sp.Rational(1, j + k + 1))
        return tuple(gram.LUsolve(m))
    D, Q = _cofactors(degree, n)
    H = _hilbert_inverse(degree + 1)
    size = range(degree + 1)
    return tuple(_over(sum((Q[k] * H[j, k] for k in size), 0 * D), D) for j in size)


def coefficients_eq_17(degree: int = 3, contact: str = _CONTACT) -> tuple[sp.Expr, ...]:
    """``(c0, ..., c_degree)`` with ``X2^n ~ sum c_k X2^k``, Eq. (17) for degree 3."""
    n = exponent(contact)
    return tuple(d * X2max ** (n - k) for k, d in enumerate(scaled_coefficients(degree, n)))


def polynomial_eq_16(X2, degree: int = 3, contact: str = _CONTACT) -> sp.Expr:
    """The fitted polynomial in ``X2``, Eq. (16)."""
    return sum(c * X2**k for k, c in enumerate(coefficients_eq_17(degree, contact)))


@dataclass(frozen=True)
class FitError:
    """Error of the fit on ``[0, 1]`` in the scaled variable, exact.

    The error in ``X2`` is ``X2max^n`` times these (at ``X2 = X2max * argmax``).
    ``max_abs`` and ``argmax`` may be algebraic numbers (``CRootOf``) when the
    largest error sits at an interior extremum. ``endpoints`` are the errors at
    ``s = 0`` and ``s = 1``; for a symbolic exponent ``max_abs`` is the larger of
    them (interior extrema of ``s^n - p(s)`` have no closed form in ``n``).
    """

    max_abs: sp.Expr
    argmax: sp.Expr
    rms: sp.Expr
    endpoints: tuple = ()


@cache
def scaled_error(degree: int = 3, n=HERTZ) -> FitError:
    """Largest absolute error, its location and the RMS error on ``[0, 1]``, exactly.

    For ``n = p/q`` interior extrema solve ``n u^(p - q) = p'(u^q)`` with ``u = s^(1/q)``:
    a polynomial in ``u`` whose real roots in ``(0, 1)`` SymPy isolates exactly.
    """
    d = scaled_coefficients(degree, n)
    poly = sum(c * s**k for k, c in enumerate(d))
    err = s**n - poly
    # int (s^n - p)^2 = int s^2n - 2 m.d + d.H.d = 1/(2n+1) - m.d, since H d = m
    if n.is_Rational:
        ends = (-d[0], 1 - sum(d))
        rms = sp.sqrt(1 / (2 * n + 1) - sum(m * c for m, c in zip(_moments(degree, n), d)))
    else:
        # over the common denominators D and (2n+1) D^2: polynomials in n, factored
        D, Q = _cofactors(degree, n)
        H = _hilbert_inverse(degree + 1)
        size = range(degree + 1)
        rows = [sum((Q[k] * H[j, k] for k in size), 0 * D) for j in size]
        ends = (_over(-rows[0], D), _over(D - sum(rows, 0 * D), D))
        cross = sum((Q[j] * Q[k] * H[j, k] for j in size for k in size), 0 * D)
        square = D * D - sp.Poly(2 * n + 1, n, domain="QQ") * cross
        rms = sp.sqrt(_over(square, sp.Poly(2 * n + 1, n) * D * D))
    if not n.is_Rational:
        larger = sp.Abs(ends[0]) >= sp.Abs(ends[1])
        return FitError(
            sp.Max(sp.Abs(ends[0]), sp.Abs(ends[1])),
            sp.Piecewise((0, larger), (1, True)),
            rms,
            ends,
        )
    u = sp.Symbol("u", nonnegative=True)
    p, q = n.p, n.q
    # n s^(n-1) = p'(s) with s = u^q, multiplied through by u^(q-p) where n < 1
    # (p'(u^q) written from the coefficients: sp.diff of the sum took longer than the rest)
    derivative = sum(k * c * u ** (q * (k - 1)) for k, c in enumerate(d) if k)
    slope = n * u ** max(p - q, 0) - derivative * u ** max(q - p, 0)
    stationary = sp.Poly(sp.expand(slope), u)
    roots = [sp.Integer(0), sp.Integer(1)]
    if not stationary.is_zero:
        roots += [r for r in stationary.real_roots() if 0 < r < 1]
    candidates = roots[:2] + [r**q for r in roots[2:]]
    values = [err.subs(s, c) for c in candidates]
    k = _largest(err, roots, q, values)
    return FitError(sp.Abs(values[k]), candidates[k], rms, ends)


def _largest(err, roots, q, values) -> int:
    """The index of the largest ``|err|`` at the candidates ``roots[i]**q`` (``values``).

    Only the largest becomes a closed form (SymPy's Abs of an expression in algebraic
    numbers tries to decide its sign, seconds at degree 8). The comparison is numerical:
    each root evaluated once at 60 digits (evaluating the values at 50 digits refined
    every root again for every power of it). Where the two largest agree to 30 digits,
    the values themselves are compared at 50 digits, as before; the first largest wins.
    """
    at = [abs(err.subs(s, sp.Float(r.evalf(60), 60) ** q)) for r in roots]
    order = sorted(range(len(at)), key=lambda i: (-at[i], i))
    if len(order) == 1 or at[order[0]] - at[order[1]] > sp.Float("1e-30") * at[order[0]]:
        return order[0]
    return max(range(len(values)), key=lambda i: abs(sp.N(values[i], 50)))


def fit_error(degree: int = 3, contact: str = _CONTACT) -> FitError:
    """`scaled_error` in ``X2``: largest error, where it sits, and RMS, in ``X2max``."""
    n = exponent(contact)
    e = scaled_error(degree, n)
    scale = X2max**n
    return FitError(
        e.max_abs * scale, e.argmax * X2max, e.rms * scale, tuple(x * scale for x in e.endpoints)
    )
