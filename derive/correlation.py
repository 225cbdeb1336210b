"""A consistent first-order average: friction with the fast normal force (beyond the paper).

The paper's slow equations keep ``mu_bar N(Z)`` and drop the correlation of the fast
friction direction with the fast normal force (docs/modelling.md#averaging;
`beltmdsm.derive.mdsm` labels it). For a harmonic fast motion, relative sliding velocity
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

These are the set-valued sign's averages. A friction law enters as its value at rest
``mu(0)`` times them plus the average of the law beyond it (`beltmdsm.derive.averaging`:
nothing for Coulomb's law, a quadrature for Stribeck's): `friction_average`,
`friction_average_slope` and `friction_harmonic`. From them the pieces of the
consistent MDSM: `slow_damping`, the damping of the slow tangential motion at the
equilibrium, and `harmonic_balance`, the residual of the harmonic balance of the fast
tangential motion (Eq. A1).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from . import averaging, laws
from .dynamics import free_acceleration
from .friction import coupled_velocity, frequency_response, normal_response
from .model import Y1, P, excitation, normal_force, rest_coefficient, t
from .oscillator import system_matrix
from .stability import S2, Z2, slow_state_space_A3_A6
from .statespace import Quadratic

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
    "friction_average",
    "friction_average_slope",
    "friction_harmonic",
    "mean_normal_force",
    "slow_damping",
    "phi",
    "psi",
    "transfer_function",
    "harmonic_balance",
]

u, V = averaging.u, averaging.V
N0, N1 = sp.symbols("N0 N1", real=True)
theta = sp.Symbol("theta", real=True)
#: Phases of the fast velocity and of the fast normal force (harmonic balance).
phi, psi = sp.symbols("phi psi", real=True)
_t = averaging.PHASE
_FRICTION, _CONTACT = laws.default("friction"), laws.default("contact")
_a = sp.Symbol("a", real=True)  # asin(u/V): sgn(u + V sin t) > 0 on (-a, pi + a)


def _signed_average(f, weight=1, scale=1 / (2 * sp.pi)):
    """``scale * integral over a period of sgn(u + V sin t) f(t) weight(t)`` in ``a``.

    The integrand is a trigonometric polynomial: expanded into powers of ``sin t`` and
    ``cos t`` it has an antiderivative that SymPy finds at once, evaluated at the ends of
    both pieces (two definite integrals of the product took three times as long).
    """
    g = sp.expand(sp.expand_trig(f * weight))
    F = sp.integrate(g, _t)
    plus = F.subs(_t, sp.pi + _a) - F.subs(_t, -_a)
    minus = F.subs(_t, 2 * sp.pi - _a) - F.subs(_t, sp.pi + _a)
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


def fast_normal_force(contact: str = _CONTACT) -> tuple[sp.Expr, sp.Expr]:
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
    # linear in sin and cos of the phase: simplified with them as symbols, the same
    # rational function, without trigsimp's search (two thirds of the time)
    trig = {
        sp.sin(P["phase_n"]): sp.Dummy("s", real=True),
        sp.cos(P["phase_n"]): sp.Dummy("c", real=True),
    }
    back = {v: k for k, v in trig.items()}
    return tuple(sp.simplify(part.xreplace(trig)).xreplace(back) for part in (re, im))


def fast_tangential_velocity(
    contact: str = _CONTACT, friction: str = _FRICTION
) -> tuple[sp.Expr, sp.Expr]:
    """Complex amplitude ``(Re, Im)`` of the fast relative velocity while friction keeps
    its direction (``Vr < 0`` throughout the fast cycle), one excitation frequency.

    The linear response of Eq. (11) to both excitations (the ``"coupled"`` reading of
    ``V_hat`` with its phase): ``X1' = Im((Re + i Im) e^(i Omega t))``. The friction
    law enters through its value and slope at ``Vb``.
    """
    W = P["Omega_t"]
    Ft = P["alpha_t"] * W**2 * sp.exp(sp.I * P["phase_t"])
    Fn = -P["alpha_n"] * W**2 * sp.exp(sp.I * P["phase_n"])
    re, im = sp.expand_complex(coupled_velocity(Ft, Fn, W, contact, friction)).as_real_imag()
    return re, im


def _with_law(friction: str, sign_part: sp.Expr, weight, scale, slope: bool) -> sp.Expr:
    """``mu(0)`` times a Piecewise of the sign's average plus the law's part beyond ``mu(0)``."""
    build = averaging.remainder_slope if slope else averaging.remainder_average
    inside, outside = build(friction, weight, scale)
    mu0 = rest_coefficient(friction)
    (sign_in, cond), (sign_out, _) = sign_part.args
    return sp.Piecewise((mu0 * sign_in + inside, cond), (mu0 * sign_out + outside, True))


@cache
def friction_average(friction: str = _FRICTION) -> sp.Expr:
    """``<mu(|v|) sgn(v) (N0 + N1 sin(. + theta))>``, ``v = u + V sin``: the mean friction
    force per unit mass of the law. Coulomb's: ``mu_s`` times `averaged_friction`."""
    return _with_law(friction, averaged_friction(), _normal(), 1 / (2 * sp.pi), False)


@cache
def friction_average_slope(friction: str = _FRICTION) -> sp.Expr:
    """``d/du`` of `friction_average`: the sign's slope (`averaged_friction_slope`) times
    ``mu(0)`` plus the slope of the law beyond it (`beltmdsm.derive.averaging.remainder_slope`)."""
    return _with_law(friction, averaged_friction_slope(), _normal(), 1 / (2 * sp.pi), True)


@cache
def friction_harmonic(friction: str = _FRICTION) -> tuple[sp.Expr, sp.Expr]:
    """``(s1, c1)``: the first harmonic of ``mu(|v|) sgn(v) (N0 + N1 sin(t + theta))``,
    ``v = u + V sin t``, as `first_harmonic` is of the sign alone."""
    s1, c1 = first_harmonic()
    return (
        _with_law(friction, s1, _normal() * sp.sin(_t), 1 / sp.pi, False),
        _with_law(friction, c1, _normal() * sp.cos(_t), 1 / sp.pi, False),
    )


@cache
def mean_normal_force() -> sp.Expr:
    """``<N>`` at the slow equilibrium: the slow normal equation (Eq. A6) at rest gives ``g``."""
    F = sp.Symbol("F", real=True)
    rest = slow_state_space_A3_A6()[3].subs(normal_force(_CONTACT, Z2, S2), F)
    (mean,) = sp.solve(rest, F)
    return mean


@cache
def slow_damping(friction: str = _FRICTION) -> sp.Expr:
    """Damping of the slow tangential motion at the equilibrium ``u = -Vb`` (consistent MDSM).

    The slow tangential equation has the free damping ``-d a_free/d X1'`` and the
    averaged friction ``<mu(|v|) sgn(v) N>`` in the sign of Eq. (4): linearised at
    frozen fast amplitude ``V`` and phase ``theta``, its damping is
    ``2 beta1 omega1 + d/du <mu sgn N>`` at ``u = -Vb``, ``N0 = <N>`` (unstable where
    negative; for Coulomb's law ``2 beta1 omega1 + mu_s dF/du`` of
    `averaged_friction_slope`).
    """
    free = -sp.diff(free_acceleration(), Y1)
    return free + friction_average_slope(friction).subs({u: -P["Vb"], N0: mean_normal_force()})


def _phasor(force, W) -> sp.Expr:
    """``c`` with ``force(t) = Im(c e^(i W t))`` for a harmonic ``force`` of frequency ``W``."""
    expanded = sp.expand(sp.expand_trig(force))
    return expanded.coeff(sp.sin(W * t)) + sp.I * expanded.coeff(sp.cos(W * t))


def transfer_function() -> tuple[sp.Expr, sp.Expr]:
    """``(Re, Im)`` of ``q(i Omega_t)`` of the tangential oscillator without friction.

    ``q(lambda) = lambda^2 + 2 beta1 omega1 lambda + omega1^2`` is the characteristic
    polynomial of `beltmdsm.derive.oscillator.system_matrix`: a displacement ``x e^(iWt)``
    needs the force ``q(iW) x``. The fast tangential motion's harmonic balance
    (`harmonic_balance`) divides the excitation's phasor by it.
    """
    return frequency_response(Quadratic.from_block(system_matrix()), P["Omega_t"])


@cache
def harmonic_balance(friction: str = _FRICTION) -> tuple[sp.Expr, sp.Expr]:
    """Residual ``(Re, Im)`` of the harmonic balance of the fast tangential motion (Eq. A1).

    For ``X1' - Z1' = V sin(W t + phi)`` and the normal force ``<N> + N1 sin(W t +
    psi)`` at one excitation frequency ``W = Omega_t``: with the tangential
    oscillator's ``q(iW)`` (`beltmdsm.derive.oscillator.system_matrix`), the excitation's
    phasor ``F_t`` and the first harmonic ``s1 + i c1`` of the friction force
    (`friction_harmonic` at ``u = -Vb``, ``theta = psi - phi``),

        q(iW) V / (iW) - F_t e^(-i phi) + (s1 + i c1) = 0,

    divided by ``|F_t|`` (0 where the balance holds).
    """
    s1, c1 = (
        h.subs({u: -P["Vb"], N0: mean_normal_force(), theta: psi - phi})
        for h in friction_harmonic(friction)
    )
    re, im, size = _balance_without_friction()
    return (re + s1) / size, (im + c1) / size


@cache
def _balance_without_friction() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """``(Re, Im)`` of `harmonic_balance`'s terms other than the friction's, and ``|F_t|``:
    the same for every friction law, derived once."""
    W = P["Omega_t"]
    a, b = transfer_function()
    Ft = _phasor(excitation()[0], W)
    # the friction's harmonic (s1, c1) is real already: split the rest only
    linear = (a + sp.I * b) * V / (sp.I * W) - Ft * sp.exp(-sp.I * phi)
    re, im = sp.expand_complex(linear).as_real_imag()
    size = sp.simplify(sp.sqrt(sp.expand_complex(Ft * sp.conjugate(Ft))))
    return re, im, size
