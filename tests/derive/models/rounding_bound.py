"""A first-order bound on the rounding error of a SymPy expression evaluated in doubles.

The error model of tests/generated/test_hybrid.py (each entry within a few ulps of the
sum of the absolute values of its terms, a quotient adding its denominator's relative
error), made mechanical for expressions no one types by hand: `evaluate` walks the
expression at the working precision of mpmath (50 digits in the tests) and returns its
value and ``E``, such that a double evaluation of the same expression, in any order of
its sums and products and with any common subexpressions shared, is within ``EPS * E``
of the exact value (to first order in ``EPS``). Each rounding of a result ``r`` costs
``|r|`` (``EPS`` is one ulp of 1, twice the unit roundoff, so a correctly rounded
operation uses half of it); an elementary function (``sin``, ``cos``, ``exp``, ``pow``,
``sqrt``) costs ``ULPS_FUNCTION`` of them (libm and numpy's SIMD loops are documented at
up to 4 ulps: /work/shared/LESSONS.md, "Floating point across machines"); errors of the
arguments propagate through the derivatives of each operation:

* a sum of ``n`` terms: the terms' errors plus ``(n - 1) * sum |terms|`` (every partial
  sum of any order is bounded by that sum: the *scale* of the hand-typed error model);
* a product of ``n`` factors: ``sum_i E_i prod_(j != i) |a_j|`` plus ``(n - 1) |r|``;
* ``b**k``: ``|k| |b|^(k - 1) E_b``, plus one rounding (``1/b``) or a function's; a
  rational exponent that is not a dyadic fraction is itself rounded: ``|r ln b| |k|``
  more;
* ``f(x)``: ``|f'(x)| E_x`` plus a function's rounding; ``Max``, ``Abs``, ``Piecewise``:
  the error of the branch taken; ``Heaviside``, ``sign``: none (the points stay off
  their jumps).

Inputs are exact unless ``env`` gives them an error (a layered kernel: the
characteristic coefficients read the rounded equilibrium and Jacobian entries).
"""

from __future__ import annotations

import mpmath
import sympy as sp

EPS = 2.0**-52
#: ulps of one elementary function's rounding (see the module docstring).
ULPS_FUNCTION = 4

__all__ = ["EPS", "ULPS_FUNCTION", "evaluate"]


def _dyadic(r: sp.Rational) -> bool:
    q = int(r.q)
    return q & (q - 1) == 0


def evaluate(expr, env: dict, memo: dict | None = None):
    """``(value, E)`` of ``expr`` at ``env`` (symbol -> (value, E)), module docstring."""
    memo = {} if memo is None else memo
    return _walk(sp.sympify(expr), env, memo)


def _walk(e, env, memo):
    if e in memo:
        return memo[e]
    memo[e] = out = _node(e, env, memo)
    return out


def _node(e, env, memo):
    mpf, zero = mpmath.mpf, mpmath.mpf(0)
    if e.is_Symbol:
        v, err = env[e]
        return mpf(v), mpf(err)
    if e.is_Integer:
        return mpf(int(e)), zero
    if e.is_Rational:
        v = mpf(int(e.p)) / int(e.q)
        return v, zero if _dyadic(e) else abs(v)
    if e.is_Float:
        return mpf(e), zero  # printed by repr: the double it is
    if e is sp.pi:
        return +mpmath.pi, abs(mpmath.pi)
    args = [_walk(a, env, memo) for a in e.args]
    if e.is_Add:
        v = mpmath.fsum(a for a, _ in args)
        return v, mpmath.fsum(err for _, err in args) + (len(args) - 1) * mpmath.fsum(
            abs(a) for a, _ in args
        )
    if e.is_Mul:
        v = mpmath.fprod(a for a, _ in args)
        err = zero
        for i, (_, ei) in enumerate(args):
            if ei:
                err += ei * mpmath.fprod(abs(a) for j, (a, _) in enumerate(args) if j != i)
        return v, err + (len(args) - 1) * abs(v)
    if e.is_Pow:
        (b, eb), k = args[0], e.exp
        if not k.is_Rational:
            raise NotImplementedError(f"a symbolic exponent: {e}")
        kv = mpf(int(k.p)) / int(k.q)
        v = b**kv if b or kv > 0 else mpmath.inf
        err = abs(kv) * abs(b) ** (kv - 1) * eb if eb else zero
        if k == -1:
            err += abs(v)
        elif k.is_Integer and k > 0:
            err += ULPS_FUNCTION * abs(v)
        else:  # a negative power: a function and a quotient; a root: a function and a product
            err += (ULPS_FUNCTION + 1) * abs(v)
        if not _dyadic(k) and b:
            err += abs(v * mpmath.log(abs(b)) * kv)
        return v, err
    (x, ex), *_ = args
    if isinstance(e, sp.sin):
        v, slope = mpmath.sin(x), abs(mpmath.cos(x))
    elif isinstance(e, sp.cos):
        v, slope = mpmath.cos(x), abs(mpmath.sin(x))
    elif isinstance(e, sp.exp):
        v = mpmath.exp(x)
        slope = abs(v)
    else:
        return _piecewise(e, args)
    return v, slope * ex + ULPS_FUNCTION * abs(v)


def _piecewise(e, args):
    zero = mpmath.mpf(0)
    if isinstance(e, sp.Max):
        return max(args, key=lambda a: a[0])
    if isinstance(e, sp.Min):
        return min(args, key=lambda a: a[0])
    if isinstance(e, sp.Abs):
        return abs(args[0][0]), args[0][1]
    if isinstance(e, sp.Heaviside):  # the printers' convention: 1 above 0, else 0
        return (mpmath.mpf(1) if args[0][0] > 0 else zero), zero
    if isinstance(e, sp.sign):
        return mpmath.sign(args[0][0]), zero
    raise NotImplementedError(f"no rounding rule for {type(e).__name__}")
