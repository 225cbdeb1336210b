"""A consistent first-order average: friction with the fast normal force (beyond the paper).

The paper's slow equations keep ``mu_bar N(Z)`` and drop the correlation of the fast
friction direction with the fast normal force (docs/modelling.md#averaging;
`derive.mdsm` labels it). For a harmonic fast motion, relative sliding velocity
``u + V sin(tau)`` and normal force ``N0 + N1 sin(tau + theta)``, the average of
Coulomb friction over a fast period is a closed form, derived here by integrating over
the arcs where the sign of the sliding velocity is constant (``a = asin(u/V)``):

    <sgn(u + V sin) (N0 + N1 sin(. + theta))>
        = (2/pi) (N0 asin(u/V) + N1 cos(theta) sqrt(1 - u^2/V^2))

for ``|u| < V`` and ``N0 sgn(u)`` outside. Its slope in ``u`` carries the correlation:

    d/du = 2 (N0 V - N1 u cos(theta)) / (pi V sqrt((V - u)(V + u))),

which at the equilibrium ``u = -Vb`` is negative when the normal force is high while the
mass slides backwards fastest (``cos(theta) < 0``) and ``N1 Vb |cos(theta)| > N0 V``:
a negative damping that the paper's ``mu_bar'`` (``N1 = 0``) can never give in the sign
of Eq. (4).

The first harmonic of the same product (``sin`` and ``cos`` coefficients) closes the
harmonic balance of the fast tangential motion when the friction reverses within a
fast cycle (``Vb < V``); with ``|u| >= V`` it is the friction times the fast normal force.
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from .friction import coupled_velocity, normal_response
from .model import P

__all__ = [
    "u",
    "V",
    "N0",
    "N1",
    "theta",
    "averaged_friction",
    "averaged_friction_slope",
    "first_harmonic",
    "fast_normal_force",
    "fast_tangential_velocity",
]

u = sp.Symbol("u", real=True)
V = sp.Symbol("V", positive=True)
N0, N1 = sp.symbols("N0 N1", real=True)
theta = sp.Symbol("theta", real=True)
_t = sp.Symbol("t", real=True)
_a = sp.Symbol("a", real=True)  # asin(u/V): sgn(u + V sin t) > 0 on (-a, pi + a)


def _signed_average(f, weight=1, scale=1 / (2 * sp.pi)):
    """``scale * integral over a period of sgn(u + V sin t) f(t) weight(t)`` in ``a``."""
    g = f * weight
    plus = sp.integrate(g, (_t, -_a, sp.pi + _a))
    minus = sp.integrate(g, (_t, sp.pi + _a, 2 * sp.pi - _a))
    return sp.simplify(sp.expand_trig(scale * (plus - minus)))


def _normal():
    return N0 + N1 * sp.sin(_t + theta)


@cache
def averaged_friction() -> sp.Expr:
    """``<sgn(u + V sin) (N0 + N1 sin(. + theta))>``, piecewise in ``|u| < V``."""
    inside = _signed_average(_normal()).subs(_a, sp.asin(u / V))
    return sp.Piecewise((sp.simplify(inside), sp.Abs(u) < V), (N0 * sp.sign(u), True))


@cache
def averaged_friction_slope() -> sp.Expr:
    """``d/du`` of `averaged_friction` (0 for ``|u| > V``), in cancellation-free form.

    The derivative SymPy computes is proved equal to
    ``2 (N0 V - N1 u cos(theta)) / (pi V sqrt((V - u)(V + u)))``.
    """
    inside = averaged_friction().args[0][0]
    factored = 2 * (N0 * V - N1 * u * sp.cos(theta)) / (sp.pi * V * sp.sqrt((V - u) * (V + u)))
    if sp.simplify(sp.diff(inside, u) - factored) != 0:
        raise AssertionError("slope of the averaged friction differs from its factored form")
    return sp.Piecewise((factored, sp.Abs(u) < V), (0, True))


@cache
def first_harmonic() -> tuple[sp.Expr, sp.Expr]:
    """``(s1, c1)``: ``sgn(u + V sin t)(N0 + N1 sin(t + theta)) ~ s1 sin t + c1 cos t + ...``.

    Piecewise: the closed forms hold for ``|u| < V``; outside, the sign is constant and
    the first harmonic is ``sgn(u) N1 (cos(theta) sin t + sin(theta) cos t)``. The two
    branches join continuously at ``|u| = V``.
    """
    s1 = _signed_average(_normal(), sp.sin(_t), 1 / sp.pi).subs(_a, sp.asin(u / V))
    c1 = _signed_average(_normal(), sp.cos(_t), 1 / sp.pi).subs(_a, sp.asin(u / V))
    inside = sp.Abs(u) < V
    return (
        sp.Piecewise((sp.simplify(s1), inside), (sp.sign(u) * N1 * sp.cos(theta), True)),
        sp.Piecewise((sp.simplify(c1), inside), (sp.sign(u) * N1 * sp.sin(theta), True)),
    )


def fast_normal_force(contact: str = "hertz_damp") -> tuple[sp.Expr, sp.Expr]:
    """Complex amplitude ``(Re, Im)`` of the fast normal force per unit mass.

    The normal block of Eq. (11), forced by ``-alpha_n Omega_n^2 sin(Omega_n t + phase_n)``,
    responds linearly (the normal motion does not depend on the tangential one); the
    force fluctuation is ``(s + i r Omega_n) x2`` with the block's stiffness ``s`` and
    damping ``r``. ``N(t) = g + Im((Re + i Im) e^(i Omega_n t))``.
    """
    W = P["Omega_n"]
    force = -P["alpha_n"] * W**2 * sp.exp(sp.I * P["phase_n"])
    amplitude = normal_response(force, W, contact)[1]
    re, im = sp.expand_complex(amplitude).as_real_imag()
    return sp.simplify(re), sp.simplify(im)


def fast_tangential_velocity(contact: str = "hertz_damp") -> tuple[sp.Expr, sp.Expr]:
    """Complex amplitude ``(Re, Im)`` of the fast relative velocity while friction keeps
    its direction (``Vr < 0`` throughout the fast cycle), one excitation frequency.

    The linear response of Eq. (11) to both excitations (the ``"coupled"`` reading of
    ``V_hat`` with its phase): ``X1' = Im((Re + i Im) e^(i Omega t))``.
    """
    W = P["Omega_t"]
    Ft = P["alpha_t"] * W**2 * sp.exp(sp.I * P["phase_t"])
    Fn = -P["alpha_n"] * W**2 * sp.exp(sp.I * P["phase_n"])
    re, im = sp.expand_complex(coupled_velocity(Ft, Fn, W, contact)).as_real_imag()
    return re, im
