"""Effective friction (Eqs. 23-25) and the velocity amplitude ``V_hat`` in two readings.

Eq. (23) gives the average of ``mu_s sgn(Vr + V_hat sin)`` over a fast period: an
arc-cosine for ``|Vr| <= V_hat``, Coulomb's value outside. Its slope at the
equilibrium ``Vr = -Vb`` (Eq. 25) is derived here by differentiation and then
written in the factored form ``2 mu_s / (pi sqrt((V_hat - Vb)(V_hat + Vb)))``,
which SymPy proves equal and which keeps full accuracy as ``Vb -> V_hat``.

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

import sympy as sp

from .model import P
from .statespace import Quadratic, block_quadratics, jacobian_at_equilibrium_eq_11

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


def mu_bar_eq_23(Vr=Vr) -> sp.Expr:
    """Effective friction coefficient, Eq. (23), with the sign of ``Vr``."""
    mu, Vh = P["mu_s"], P["Vhat"]
    return sp.Piecewise(
        (mu * (1 - 2 / sp.pi * sp.acos(Vr / Vh)), sp.Abs(Vr) <= Vh), (mu * sp.sign(Vr), True)
    )


def mu_bar0_eq_25() -> sp.Expr:
    """``mu_bar^0 = mu_bar(Z1'^0 - Vb)`` at the slow equilibrium ``Z1'^0 = 0``, Eq. (25)."""
    return mu_bar_eq_23(-P["Vb"])


def mu_bar_slope_derived() -> sp.Expr:
    """``d mu_bar / d Vr`` at ``Vr = -Vb`` for ``Vb < V_hat``, by differentiation of Eq. (23)."""
    inner = P["mu_s"] * (1 - 2 / sp.pi * sp.acos(Vr / P["Vhat"]))
    return sp.diff(inner, Vr).subs(Vr, -P["Vb"])


def mu_bar_slope_eq_25() -> sp.Expr:
    """Slope ``mu_bar'`` of Eq. (25), piecewise in ``Vb``, in cancellation-free form.

    ``Vb < V_hat``: ``2 mu_s / (pi sqrt((V_hat - Vb)(V_hat + Vb)))`` (proved equal to the
    derivative of Eq. 23); ``Vb = V_hat``: ``+oo`` (the arc-cosine's vertical tangent,
    a documented non-NaN value) if ``mu_s > 0``; ``Vb > V_hat``: 0 (Coulomb's constant
    value). Without friction (``mu_s = 0``) ``mu_bar`` vanishes and so does its slope,
    also at ``Vb = V_hat`` (not ``0 * oo``).
    """
    mu, Vh, Vb = P["mu_s"], P["Vhat"], P["Vb"]
    factored = 2 * mu / (sp.pi * sp.sqrt((Vh - Vb) * (Vh + Vb)))
    below = sp.Symbol("below", positive=True)  # Vh - Vb > 0 on this branch
    check = (mu_bar_slope_derived() - factored).subs(Vh, Vb + below)
    if sp.simplify(check) != 0:
        raise AssertionError("factored slope differs from the derivative of Eq. (23)")
    return sp.Piecewise((factored, Vb < Vh), (sp.oo, sp.Eq(Vb, Vh) & (mu > 0)), (0, True))


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


def normal_block(contact: str = "hertz_damp") -> Quadratic:
    """The normal quadratic ``lambda^2 + r lambda + s`` of Eq. (11), a companion block."""
    J0 = jacobian_at_equilibrium_eq_11(contact)
    _companion(J0[2:, 2:])
    return block_quadratics(J0)[1]


def normal_response(force_n, W, contact: str = "hertz_damp") -> tuple[sp.Expr, sp.Expr]:
    """Complex amplitudes ``(x2, F)`` of the normal block of Eq. (11) under ``force_n e^(i W t)``.

    ``x2`` is the displacement and ``F = (s + i r W) x2`` the fluctuation of the normal
    force per unit mass, with the block's stiffness ``s`` and damping ``r``. The normal
    motion does not depend on the tangential one (Eq. 4 is one-way coupled).
    """
    normal = normal_block(contact)
    a, b = frequency_response(normal, W)
    x2 = force_n / (a + sp.I * b)
    return x2, (normal.q + sp.I * normal.p * W) * x2


def coupled_velocity(force_t, force_n, W, contact: str = "hertz_damp") -> sp.Expr:
    """Complex amplitude of X1' for forces ``force_t``, ``force_n`` e^(i W t) (sliding, Vr < 0).

    The normal block of Eq. (11) responds to ``force_n``; its force fluctuation drives
    the tangential block through the friction column of Eq. (11) (``mu_s`` times the
    normal stiffness and damping), added to ``force_t``.
    """
    J0 = jacobian_at_equilibrium_eq_11(contact)
    _companion(J0[:2, :2])
    tangential = block_quadratics(J0)[0]
    x_n = normal_response(force_n, W, contact)[0]
    drive = force_t + J0[1, 2] * x_n + J0[1, 3] * sp.I * W * x_n
    a_t, b_t = frequency_response(tangential, W)
    return sp.I * W * drive / (a_t + sp.I * b_t)


def vhat(model: str = "tangential", contact: str = "hertz_damp") -> sp.Expr:
    """Velocity amplitude ``V_hat`` of the linear response (docs/modelling.md#vhat).

    Parameters
    ----------
    model : {"tangential", "coupled"}
    contact : {"hertz_damp", "kelvin_voigt"}
        Only for ``"coupled"``: the contact law linearised at equilibrium.

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
        J0 = jacobian_at_equilibrium_eq_11(contact)
        _companion(J0[:2, :2])
        a, b = frequency_response(block_quadratics(J0)[0], Wt)
        return at * Wt**3 / sp.sqrt(a**2 + b**2)
    if model != "coupled":
        raise ValueError(f"model must be one of {VHAT_MODELS}, got {model!r}")
    Ft = at * Wt**2 * sp.exp(sp.I * pt)
    Fn = -an * Wn**2 * sp.exp(sp.I * pn)
    same = coupled_velocity(Ft, Fn.subs(Wn, Wt), Wt, contact)
    apart = sp.Abs(coupled_velocity(Ft, 0, Wt, contact), evaluate=False) + sp.Abs(
        coupled_velocity(0, Fn, Wn, contact), evaluate=False
    )
    return sp.Piecewise((sp.Abs(same, evaluate=False), sp.Eq(Wt, Wn)), (apart, True))
