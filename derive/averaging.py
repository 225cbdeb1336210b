"""A friction law averaged over a harmonic fast motion: what is closed form, what is a quadrature.

The MDSM replaces the friction of Eq. (4) by its average over a fast period (Eq. 23;
`beltmdsm.derive.mdsm`). For a relative velocity ``v = u + V sin(phi)`` (slow part ``u``, fast
amplitude ``V``) the friction coefficient with its direction is
``f(v) = sgn(v) mu(|v|)``. Split the law at rest, ``mu(s) = mu(0) + r(s)`` with
``r(0) = 0``:

    < f(v) w > = mu(0) < sgn(v) w > + < sgn(v) r(|v|) w >

for a weight ``w(phi)`` (1 for the effective friction of Eq. 23; the fast normal force,
and its products with ``sin``, ``cos`` for the consistent MDSM, `beltmdsm.derive.correlation`).
Here ``mu(0)`` is the slip law's value at rest (`beltmdsm.derive.model.rest_coefficient`): the
fast motion is taken to pass ``Vr = 0`` without sticking, so a static bound above it
(``static_kinetic``'s ``mu_s``) enters no average. The first term is the set-valued
sign's average, the framework's closed form (Eq. 23: an arc-cosine; `beltmdsm.derive.friction`,
`beltmdsm.derive.correlation`). The second is the law's own:

* zero for Coulomb's law (``r = 0``);
* a closed form where ``r(u + V sin phi)`` has an elementary antiderivative: SymPy's
  Risch algorithm decides (`closed_form`), on the Weierstrass substitution
  ``x = tan(phi/2)`` that makes the integrand rational in ``x`` and its exponentials
  (the Risch implementation has no trigonometric extensions);
* otherwise a quadrature, ``Integral`` objects that the code generator prints as a
  Gauss-Legendre rule (`beltmdsm.generated._support.quad`) and as ``mpmath.quad``. Stribeck's
  ``exp(-|v|/v_s)`` is such a case: ``exp(-k sin)`` has no elementary antiderivative
  (SymPy proves it), and its average over a period is a Bessel function only where
  the sign does not change.

The integrals run over the pieces of the period where ``v`` keeps its sign
(``|u| < V``: ``[-a, pi + a]`` and ``[pi + a, 2 pi - a]``, ``a = asin(u/V)``), or,
without a reversal, over the halves between the extremes of ``sin``. Inside a piece
the integrand is smooth; ``r(0) = 0`` makes ``sgn(v) r(|v|)`` continuous at a reversal,
so the slope in ``u`` is the integral of the slope (`remainder_slope`: the boundary
terms vanish, which SymPy checks).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from sympy.integrals.risch import NonElementaryIntegral, risch_integrate

from . import budget, memo
from .lawcheck import value_at_rest
from .model import SPEED, coefficient, rest_coefficient

__all__ = [
    "u",
    "V",
    "PHASE",
    "remainder",
    "closed_form",
    "remainder_average",
    "remainder_slope",
    "fallbacks",
]

#: Slow relative velocity, fast amplitude and the fast phase (the integration variable).
_ONE = sp.Integer(1)
u = sp.Symbol("u", real=True)
V = sp.Symbol("V", positive=True)
PHASE = sp.Symbol("fast_phase", real=True)


@cache
def remainder(friction: str) -> sp.Expr:
    """``r(s) = mu(s) - mu(0)``: the friction law beyond its value at rest, in `SPEED`."""
    return coefficient(friction, SPEED) - rest_coefficient(friction)


def _risch(friction: str):
    """``(elementary, reason)`` of Risch's algorithm on ``r(u + V sin phi) dphi``."""
    r = remainder(friction)
    x = sp.Symbol("x", real=True)
    integrand = r.subs(SPEED, u + V * 2 * x / (1 + x**2)) * 2 / (1 + x**2)
    try:
        result = risch_integrate(integrand, x)
    except NotImplementedError:  # SymPy's own words name its internals: not shown
        return False, (
            f"{friction}: SymPy's Risch algorithm does not decide whether mu(|Vr + V sin|) - "
            "mu(0) has an elementary antiderivative over the fast phase (its implementation "
            "lacks the case); its average is a quadrature"
        )
    if isinstance(result, NonElementaryIntegral):
        return False, (
            f"{friction}: mu(|Vr + V sin|) - mu(0) = {sp.sstr(r.subs(SPEED, sp.Symbol('s')))} "
            "(s = |Vr + V sin|) has no elementary antiderivative over the fast phase "
            "(SymPy's Risch algorithm proves it); its average is a quadrature"
        )
    return True, f"{friction}: mu(|Vr + V sin|) has an elementary antiderivative (Risch)"


@cache
def closed_form(friction: str) -> tuple[bool, str]:
    """Whether ``<sgn(v) r(|v|)>`` over a fast period has an elementary closed form, and why.

    ``r = 0`` (Coulomb): yes. Otherwise SymPy's Risch algorithm on
    ``r(u + V sin phi) dphi`` with ``x = tan(phi/2)``: an elementary antiderivative
    gives a closed form; a proof that there is none (``NonElementaryIntegral``), or
    a case the implementation cannot decide, gives a quadrature. Risch's algorithm and
    then the definite integrals of the average and its slope run under the budget of
    `beltmdsm.derive.budget`; past it the average is a quadrature too, and the reason says so.
    """
    r = remainder(friction)
    if memo.simplify(r) == 0:
        return True, f"{friction}: mu(|Vr|) = mu(0) is constant, its average is Eq. (23)'s"
    try:
        if r.is_polynomial(SPEED):  # a polynomial in sin: elementary, no search needed
            elementary, why = (
                True,
                (
                    f"{friction}: mu(|Vr + V sin|) - mu(0) is a polynomial in the speed, whose "
                    "antiderivative over the fast phase is elementary"
                ),
            )
        else:
            elementary, why = budget.within(f"{friction}: Risch", _risch, friction, inputs=r)
    except budget.Undecided as over:
        return False, (
            f"{friction}: {over.reason} (SymPy's Risch algorithm on mu(|Vr + V sin|) - "
            "mu(0)); its average is a quadrature"
        )
    if not elementary:
        return False, why
    try:
        _EXACT.update(budget.within(f"{friction}: averages", _exact_averages, friction, inputs=r))
    except budget.Undecided as over:
        return False, (
            f"{friction}: mu(|Vr + V sin|) has an elementary antiderivative (Risch), but its "
            f"integrals over the pieces of the fast period: {over.reason}; its average "
            "is a quadrature"
        )
    return True, why


#: ``sgn(u)`` while the integrand is differentiated in ``u`` (it is constant on a side).
_SIDE = sp.Symbol("side", real=True)


def _pieces(inside: bool):
    """``[(lo, hi, sign of v), ...]`` covering a fast period (`_SIDE` stands for ``sgn(u)``)."""
    if inside:
        a = sp.asin(u / V)
        return [(-a, sp.pi + a, 1), (sp.pi + a, 2 * sp.pi - a, -1)]
    half = sp.pi / 2
    return [(-half, half, _SIDE), (half, 3 * half, _SIDE)]


def _trig_polynomial(integrand) -> sp.Expr | None:
    """``integrand`` expanded, where it is a polynomial in ``sin``, ``cos`` of `PHASE` (a
    polynomial law's: ``c_v v``, ``mu_3 v^3`` times the weights), else None."""
    expanded = sp.expand(sp.expand_trig(integrand))
    S, C = sp.Dummy("S"), sp.Dummy("C")
    plain = expanded.xreplace({sp.sin(PHASE): S, sp.cos(PHASE): C})
    if PHASE in plain.free_symbols or not plain.is_polynomial(S, C):
        return None
    return expanded


def _sided(expr):
    """`_SIDE` as ``sgn(u)`` (its even powers 1)."""
    return expr.subs(_SIDE**2, 1).subs(_SIDE, sp.sign(u))


def _integrate(integrand, lo, hi, exact: bool):
    polynomial = _trig_polynomial(integrand) if exact else None
    if polynomial is not None:
        # A polynomial in sin and cos has an antiderivative of the same kind (plus a
        # multiple of the phase), continuous everywhere: the limits go in directly. SymPy's
        # definite integral reaches the same value through its general machinery, 10-20 s
        # for a cubic law's weighted averages (the budget's limit, issue 41); with sgn(u)
        # in the integrand even the antiderivative ran for minutes, so `_SIDE` stays a
        # symbol until the limits are in.
        antiderivative = sp.integrate(polynomial, PHASE)
        return _sided(antiderivative.subs(PHASE, hi) - antiderivative.subs(PHASE, lo))
    integrand = _sided(integrand)
    if exact:
        return sp.integrate(integrand, (PHASE, lo, hi))
    return sp.Integral(integrand, (PHASE, lo, hi))


#: The exact averages computed under the budget: ``{(friction, weight, scale, slope): (inside,
#: outside)}`` (`closed_form` fills those of weight 1, `_average` the others).
_EXACT: dict = {}
#: friction -> the averages of other weights that fell back to quadratures (`fallbacks`).
_FALLBACKS: dict[str, list[str]] = {}


def fallbacks(friction: str) -> tuple[str, ...]:
    """The weighted averages of ``friction`` (the consistent MDSM's, `beltmdsm.derive.correlation`)
    that ran past their budget and are quadratures, each as one phrase; `capabilities`
    appends them to the reason of ``closed_form_average`` (derived after the MDSM)."""
    return tuple(_FALLBACKS.get(friction, ()))


def _exact_averages(friction: str) -> dict:
    """The effective friction's exact average and slope (weight 1), for `closed_form`."""
    key = (_ONE, 1 / (2 * sp.pi))
    return {
        (friction, *key, slope): _pieces_sum(friction, *key, slope, True) for slope in (False, True)
    }


def _average(friction: str, weight, scale, slope: bool):
    """`_pieces_sum`, exact where `closed_form` holds and the budget suffices, else quadratures.

    A weight other than 1 (the consistent MDSM's) is integrated under its own budget; past
    it that average is a quadrature, as a law without a closed form has.
    """
    if not closed_form(friction)[0]:
        return _pieces_sum(friction, weight, scale, slope, False)
    key = (friction, weight, scale, slope)
    if key not in _EXACT:
        try:
            _EXACT[key] = budget.within(
                f"{friction}: average",
                _pieces_sum, friction, weight, scale, slope, True,
                inputs=(remainder(friction), weight, scale, slope),
            )  # fmt: skip
        except budget.Undecided as over:
            note = (
                f"a weighted average of the consistent MDSM (derive/correlation.py): "
                f"{over.reason}, a quadrature"
            )
            if note not in _FALLBACKS.setdefault(friction, []):
                _FALLBACKS[friction].append(note)
            _EXACT[key] = _pieces_sum(friction, weight, scale, slope, False)
    return _EXACT[key]


def _signed(friction: str, direction, weight) -> sp.Expr:
    """``sgn(v) r(|v|) w`` on a piece where ``sgn(v) = direction``."""
    v = u + V * sp.sin(PHASE)
    return direction * remainder(friction).subs(SPEED, direction * v) * weight


@cache
def remainder_average(friction: str, weight=_ONE, scale=1 / (2 * sp.pi)):
    """``scale * integral over a fast period of sgn(v) r(|v|) weight``, per side of ``|u| = V``.

    Returns
    -------
    (inside, outside) : tuple of sympy.Expr
        For ``|u| <= V`` (the friction reverses within the period) and ``|u| >= V``;
        ``(0, 0)`` for Coulomb's law. ``weight`` is a function of `PHASE`.
    """
    if memo.simplify(remainder(friction)) == 0:
        return sp.Integer(0), sp.Integer(0)
    return _average(friction, weight, scale, False)


@cache
def remainder_slope(friction: str, weight=_ONE, scale=1 / (2 * sp.pi)):
    """``d/du`` of `remainder_average`: the integrals of the slope of the integrand.

    The limits of the pieces move with ``u``, but the integrand vanishes there
    (``r(0) = 0`` at a reversal; the extremes of ``sin`` do not move): the boundary
    terms of Leibniz's rule are zero, which SymPy checks.

    Raises
    ------
    AssertionError
        If a boundary term does not vanish (a law with ``r(0) != 0``).
    """
    if memo.simplify(remainder(friction)) == 0:
        return sp.Integer(0), sp.Integer(0)
    r = remainder(friction)
    for inside in (True, False):
        for lo, hi, sign in _pieces(inside):
            for end in (lo, hi):
                if sp.diff(end, u) == 0:
                    continue
                # at a reversal the speed is 0: r there is its limit (tanh(s/v)/(s/v) - 1
                # is 0/0 at s = 0 as written)
                speed = sp.simplify(sign * (u + V * sp.sin(end)))
                at_end = value_at_rest(r, SPEED) if speed == 0 else r.subs(SPEED, speed)
                if sp.simplify(at_end * weight.subs(PHASE, end)) != 0:
                    raise AssertionError(f"{friction}: the integrand does not vanish at {end}")
    return _average(friction, weight, scale, True)


def _pieces_sum(friction: str, weight, scale, slope: bool, exact: bool):
    """``(inside, outside)``: the integrals over the pieces of a fast period (of the slope of
    the integrand where ``slope``), exact or as ``Integral`` objects."""
    out = []
    for inside in (True, False):
        total = 0
        for lo, hi, sign in _pieces(inside):
            f = _signed(friction, sign, weight)
            total += _integrate(sp.diff(f, u) if slope else f, lo, hi, exact)
        out.append(scale * total)
    return tuple(out)
