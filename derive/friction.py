"""Effective friction (Eqs. 23-25) and the velocity amplitude ``V_hat`` in two readings.

Eq. (23) gives the average of ``mu_s sgn(Vr + V_hat sin)`` over a fast period: an
arc-cosine for ``|Vr| <= V_hat``, Coulomb's value outside. Its slope at the
equilibrium ``Vr = -Vb`` (Eq. 25) is derived here by differentiation and then
written in the factored form ``2 mu_s / (pi sqrt((V_hat - Vb)(V_hat + Vb)))``,
which SymPy proves equal and which keeps full accuracy as ``Vb -> V_hat``.

Every friction law of the registry gets its effective friction: the sign's average
times the law's value at rest ``mu(0)`` (Eq. 23 with ``mu(0)`` for ``mu_s``) plus the
average of the rest of the law (`beltmdsm.derive.averaging`), which is zero for Coulomb's law
and a quadrature for Stribeck's. ``mu(0)`` is the slip law's
(`beltmdsm.derive.model.rest_coefficient`: the kinetic ``mu_k`` of ``static_kinetic``):
the fast motion passes ``Vr = 0`` without sticking, so a static bound does not enter.

``V_hat`` is "the amplitude of the velocity response obtained for linear contact
properties" (below Eq. 23); the paper gives no formula (docs/modelling.md#vhat).
Both readings are derived from phasor solutions, never typed in:

* ``"tangential"``: the tangential oscillator alone under its excitation;
* ``"coupled"``: the two-degree-of-freedom system linearised at the unforced
  equilibrium on the sliding branch ``Vr < 0`` (Eq. 11), so the fluctuation of
  the normal force feeds the tangential motion through friction. With different
  tangential and normal frequencies the two responses are superposed and
  ``V_hat`` is the sum of their amplitudes (the largest velocity they reach).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from . import averaging, laws
from .model import P, rest_coefficient
from .statespace import Quadratic, jacobian_at_equilibrium_eq_11, quadratics_at_equilibrium

__all__ = [
    "Vr",
    "VHAT_MODELS",
    "mu_bar_eq_23",
    "mu_bar0_eq_25",
    "mu_bar_slope_eq_25",
    "mu_bar_slope_derived",
    "frequency_response",
    "normal_block",
    "normal_response",
    "coupled_velocity",
    "vhat",
]

Vr = sp.Symbol("Vr", real=True)
VHAT_MODELS = ("tangential", "coupled")


DEFAULT = {"friction": laws.default("friction"), "contact": laws.default("contact")}


def _beyond_rest(friction: str, slope: bool, Vr, Vh):
    """The law's part beyond ``mu(0)``, averaged (or its slope), at ``u = Vr``, ``V = Vh``."""
    parts = (averaging.remainder_slope if slope else averaging.remainder_average)(friction)
    return tuple(x.subs({averaging.u: Vr, averaging.V: Vh}) for x in parts)


@cache
def mu_bar_eq_23(Vr=Vr, friction: str = DEFAULT["friction"]) -> sp.Expr:
    """Effective friction coefficient, Eq. (23), with the sign of ``Vr``.

    ``mu(0) (1 - 2/pi acos(Vr/V_hat))`` for ``|Vr| <= V_hat`` and ``mu(0) sgn(Vr)``
    outside (Eq. 23 with the law's static coefficient), plus the average of the law
    beyond it (`beltmdsm.derive.averaging`; zero for Coulomb's law).
    """
    mu, Vh = rest_coefficient(friction), P["Vhat"]
    inside, outside = _beyond_rest(friction, False, Vr, Vh)
    return sp.Piecewise(
        (mu * (1 - 2 / sp.pi * sp.acos(Vr / Vh)) + inside, sp.Abs(Vr) <= Vh),
        (mu * sp.sign(Vr) + outside, True),
    )


def mu_bar0_eq_25(friction: str = DEFAULT["friction"]) -> sp.Expr:
    """``mu_bar^0 = mu_bar(Z1'^0 - Vb)`` at the slow equilibrium ``Z1'^0 = 0``, Eq. (25)."""
    return mu_bar_eq_23(-P["Vb"], friction)


def mu_bar_slope_derived(friction: str = DEFAULT["friction"]) -> sp.Expr:
    """``d mu_bar / d Vr`` of the sign's part at ``Vr = -Vb`` for ``Vb < V_hat``, by
    differentiation of Eq. (23)."""
    inner = rest_coefficient(friction) * (1 - 2 / sp.pi * sp.acos(Vr / P["Vhat"]))
    return sp.diff(inner, Vr).subs(Vr, -P["Vb"])


@cache
def mu_bar_slope_eq_25(friction: str = DEFAULT["friction"]) -> sp.Expr:
    """Slope ``mu_bar'`` of Eq. (25), piecewise in ``Vb``, in cancellation-free form.

    ``Vb < V_hat``: ``2 mu(0) / (pi sqrt((V_hat - Vb)(V_hat + Vb)))`` (proved equal to the
    derivative of Eq. 23); ``Vb = V_hat``: ``+oo`` (the arc-cosine's vertical tangent,
    a documented non-NaN value) if ``mu(0) > 0``; ``Vb > V_hat``: 0 for Coulomb's
    constant value. Without friction at rest (``mu(0) = 0``) the sign's part vanishes
    and so does its slope, also at ``Vb = V_hat`` (not ``0 * oo``). The slope of the
    law's part beyond ``mu(0)`` (`beltmdsm.derive.averaging.remainder_slope`) adds on both
    sides.
    """
    mu, Vh, Vb = rest_coefficient(friction), P["Vhat"], P["Vb"]
    factored = 2 * mu / (sp.pi * sp.sqrt((Vh - Vb) * (Vh + Vb)))
    below = sp.Symbol("below", positive=True)  # Vh - Vb > 0 on this branch
    check = (mu_bar_slope_derived(friction) - factored).subs(Vh, Vb + below)
    if sp.simplify(check) != 0:
        raise AssertionError("factored slope differs from the derivative of Eq. (23)")
    inside, outside = _beyond_rest(friction, True, -Vb, Vh)
    return sp.Piecewise(
        (factored + inside, Vb < Vh), (sp.oo, sp.Eq(Vb, Vh) & (mu > 0)), (outside, True)
    )


@cache
def frequency_response(quad: Quadratic, W) -> tuple[sp.Expr, sp.Expr]:
    """Real and imaginary part of ``q(iW)`` for a quadratic ``lambda^2 + p lambda + q``.

    A companion block ``[[0, 1], [-q, -p]]`` forced in its second row with
    ``F e^(i W t)`` responds with displacement ``F / q(iW)``. The real part is
    factored so that it stays accurate at resonance.
    """
    return sp.factor(quad.q - W**2), quad.p * W


def _companion(block: sp.Matrix) -> None:
    if list(block[0, :]) != [0, 1]:
        raise ValueError(f"not a companion block: {block}")


def normal_block(contact: str = DEFAULT["contact"]) -> Quadratic:
    """The normal quadratic ``lambda^2 + r lambda + s`` of Eq. (11), a companion block.

    The friction law does not enter it (Eq. 4 is one-way coupled).
    """
    _companion(jacobian_at_equilibrium_eq_11(contact)[2:, 2:])
    return quadratics_at_equilibrium(contact)[1]


def normal_response(force_n, W, contact: str = DEFAULT["contact"]) -> tuple[sp.Expr, sp.Expr]:
    """Complex amplitudes ``(x2, F)`` of the normal block of Eq. (11) under ``force_n e^(i W t)``.

    ``x2`` is the displacement and ``F = (s + i r W) x2`` the fluctuation of the normal
    force per unit mass, with the block's stiffness ``s`` and damping ``r``. The normal
    motion does not depend on the tangential one (Eq. 4 is one-way coupled).
    """
    normal = normal_block(contact)
    a, b = frequency_response(normal, W)
    x2 = force_n / (a + sp.I * b)
    return x2, (normal.q + sp.I * normal.p * W) * x2


def coupled_velocity(
    force_t, force_n, W, contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> sp.Expr:
    """Complex amplitude of X1' for forces ``force_t``, ``force_n`` e^(i W t) (sliding, Vr < 0).

    The normal block of Eq. (11) responds to ``force_n``; its force fluctuation drives
    the tangential block through the friction column of Eq. (11) (``mu(Vb)`` times the
    normal stiffness and damping), added to ``force_t``. The tangential block's
    damping has the slope of the friction law (``2 beta1 omega1 + g mu'(Vb)``).
    """
    J0 = jacobian_at_equilibrium_eq_11(contact, friction)
    _companion(J0[:2, :2])
    tangential = quadratics_at_equilibrium(contact, friction)[0]
    x_n = normal_response(force_n, W, contact)[0]
    drive = force_t + J0[1, 2] * x_n + J0[1, 3] * sp.I * W * x_n
    a_t, b_t = frequency_response(tangential, W)
    return sp.I * W * drive / (a_t + sp.I * b_t)


def vhat(
    model: str = "tangential",
    contact: str = DEFAULT["contact"],
    friction: str = DEFAULT["friction"],
) -> sp.Expr:
    """Velocity amplitude ``V_hat`` of the linear response (docs/modelling.md#vhat).

    Parameters
    ----------
    model : {"tangential", "coupled"}
    contact : str
        Only for ``"coupled"``: the contact law linearised at equilibrium.
    friction : str
        The friction law linearised at equilibrium: its slope at ``Vb`` damps the
        tangential block (both readings), its value couples the normal force
        fluctuation (``"coupled"``). Coulomb's law enters neither reading's
        tangential damping.

    Returns
    -------
    sympy.Expr
        ``"tangential"``: real closed form ``alpha_t Omega_t^3 / |q_t(i Omega_t)|``;
        ``"coupled"``: the modulus of a complex expression (printed as complex
        arithmetic, which stays compact).
    """
    at, Wt, pt = P["alpha_t"], P["Omega_t"], P["phase_t"]
    an, Wn, pn = P["alpha_n"], P["Omega_n"], P["phase_n"]
    if model == "tangential":
        _companion(jacobian_at_equilibrium_eq_11(contact, friction)[:2, :2])
        a, b = frequency_response(quadratics_at_equilibrium(contact, friction)[0], Wt)
        return at * Wt**3 / sp.sqrt(a**2 + b**2)
    if model != "coupled":
        raise ValueError(f"model must be one of {VHAT_MODELS}, got {model!r}")
    Ft = at * Wt**2 * sp.exp(sp.I * pt)
    Fn = -an * Wn**2 * sp.exp(sp.I * pn)
    same = coupled_velocity(Ft, Fn.subs(Wn, Wt), Wt, contact, friction)
    apart = sp.Abs(coupled_velocity(Ft, 0, Wt, contact, friction), evaluate=False) + sp.Abs(
        coupled_velocity(0, Fn, Wn, contact, friction), evaluate=False
    )
    return sp.Piecewise((sp.Abs(same, evaluate=False), sp.Eq(Wt, Wn)), (apart, True))
