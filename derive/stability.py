"""Stability of the forced system: Eqs. (20)-(22), (26)-(28), (A3)-(A8).

The slow equations (Eqs. 20-21, state-space form A3-A6) carry the effective friction
``mu_bar(Z1' - Vb)`` of Eq. (23). Their sign is a choice
(docs/modelling.md#friction-sign):

* ``convention="paper"``: Eq. (A4) as printed, ``+ mu_bar (...) Z2^(3/2)`` with
  ``mu_bar`` taken literally from Eq. (23) (negative for ``Vr < 0``). Linearised, this
  gives Eq. (22) as printed (entry ``-2 beta1 omega1 + mu_bar' g``) and Eq. (A7)
  (``Z1^0 = mu_bar^0 g / omega1^2``, which is negative);
* ``convention="consistent"``: the sign of Eq. (4), ``- mu_bar(Z1' - Vb) F_n``: the
  entry becomes ``-2 beta1 omega1 - mu_bar' g`` and ``Z1^0 > 0``.

The friction law enters only through ``mu_bar^0`` and ``mu_bar'`` (`with_friction`,
`beltmdsm.derive.friction`): the slow equations, their Jacobian, quartic and Hurwitz
determinants are derived once per contact law in the symbols ``mu0, mu1``.
Derivations are cached (pure functions of the option strings; SymPy objects are
immutable). The forced Jacobian is block triangular, so its quartic is the product of a
tangential quadratic ``lambda^2 + p lambda + q`` and a normal one
``lambda^2 + r lambda + s``. In those four quantities the Hurwitz determinants of
Eq. (28) factor exactly:

    H1 = p + r
    H2 = p (q + r (p + r)) + r s
    H3 = p r ((q - s)^2 + (p + r)(p s + q r))
    H4 = q s H3

so with ``q, r, s > 0`` the steady sliding is stable exactly when ``p > 0``, and the
stability boundary is ``p = 0``: the critical belt speed in closed form.

`stability_conditions` turns this into the verdict the generated ``is_stable``
evaluates: ``q`` and ``s`` are proved positive on the parameter domain, and then all
four ``H_k > 0`` holds exactly when ``p > 0`` and ``r > 0``. The proof is by roots:
the quartic's roots are those of the two quadratics, and a real quadratic
``lambda^2 + p lambda + q`` with ``q > 0`` has its roots in the left half-plane
exactly when ``p > 0`` (their product ``q`` is positive and their sum is ``-p``).
Two sign tests replace four determinants, and no root or power is needed for them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import budget, laws, memo
from .friction import mu_bar0_eq_25, mu_bar_slope_eq_25
from .model import P, normal_force
from .statespace import Quadratic, block_quadratics, charpoly_eq_12

__all__ = [
    "CONVENTIONS",
    "Z1",
    "S1",
    "Z2",
    "S2",
    "SLOW",
    "mu_bar",
    "mu0",
    "mu1",
    "slow_state_space_A3_A6",
    "slow_equilibrium_A7",
    "forced_jacobian_eq_22",
    "Factored",
    "factored",
    "coefficients_A8",
    "hurwitz_eq_28",
    "hurwitz_determinants",
    "hurwitz_factored",
    "stability_conditions",
    "critical_belt_speed",
    "with_friction",
]

CONVENTIONS = ("paper", "consistent")
Z1, S1, S2 = sp.symbols("Z1 S1 S2", real=True)
Z2 = sp.Symbol("Z2", positive=True)
SLOW = (Z1, S1, Z2, S2)
#: The effective friction as an unknown function of the relative velocity.
mu_bar = sp.Function("mu_bar")
#: Its value and slope at the slow equilibrium (Eqs. 24-25).
mu0, mu1 = sp.symbols("mu_bar0 mu_bar_slope", real=True)

_SIGN = {"paper": 1, "consistent": -1}
_CONTACT = laws.default("contact")
_FRICTION = laws.default("friction")


def slow_state_space_A3_A6(convention: str = "paper", contact: str = _CONTACT) -> sp.Matrix:
    """Right-hand side ``(Z1', S1', Z2', S2')`` of Eqs. (A3)-(A6)."""
    if convention not in _SIGN:
        raise ValueError(f"convention must be one of {CONVENTIONS}, got {convention!r}")
    b1, w1, g = P["beta1"], P["omega1"], P["g"]
    Fn = normal_force(contact, Z2, S2)
    friction = _SIGN[convention] * mu_bar(S1 - P["Vb"]) * Fn
    return sp.Matrix([S1, -2 * b1 * w1 * S1 - w1**2 * Z1 + friction, S2, -Fn + g])


def _linearise(expr):
    """Replace ``mu_bar`` and its derivative at the equilibrium by ``mu0`` and ``mu1``."""
    at = mu_bar(-P["Vb"])
    expr = expr.subs(S1, 0).doit()
    expr = expr.replace(
        lambda e: isinstance(e, sp.Subs) or isinstance(e, sp.Derivative), lambda e: mu1
    )
    return expr.subs(at, mu0)


def slow_equilibrium_A7(convention: str = "paper", contact: str = _CONTACT) -> dict:
    """Equilibrium of Eqs. (A3)-(A6), solved by SymPy, in terms of ``mu0``, Eq. (A7)."""
    return dict(_slow_equilibrium(convention, contact))


@cache
def _slow_equilibrium(convention: str, contact: str) -> dict:
    """`slow_equilibrium_A7`, solved once per convention and contact law (every friction
    law's equilibrium is this one with its ``mu0``)."""
    rhs = slow_state_space_A3_A6(convention, contact).subs(S1, 0).subs(mu_bar(-P["Vb"]), mu0)
    sol = sp.solve(list(rhs), [Z1, Z2, S2], dict=True)
    if len(sol) != 1:
        raise RuntimeError(f"expected one slow equilibrium, got {sol}")
    return {Z1: sol[0][Z1], S1: sp.Integer(0), Z2: sol[0][Z2], S2: sol[0][S2]}


@cache
def forced_jacobian_eq_22(convention: str = "paper", contact: str = _CONTACT) -> sp.Matrix:
    """Jacobian of Eqs. (A3)-(A6) at Eq. (A7), ``J_f^0`` of Eq. (22), in ``mu0, mu1``."""
    J = slow_state_space_A3_A6(convention, contact).jacobian(SLOW)
    eq = slow_equilibrium_A7(convention, contact)
    return J.applyfunc(lambda e: memo.simplify(_linearise(e).subs(eq)))


@dataclass(frozen=True)
class Factored:
    """The quartic of ``J_f^0`` as tangential (``p, q``) times normal (``r, s``) quadratics."""

    tangential: Quadratic
    normal: Quadratic

    @property
    def pqrs(self):
        return self.tangential.p, self.tangential.q, self.normal.p, self.normal.q


@cache
def factored(convention: str = "paper", contact: str = _CONTACT) -> Factored:
    """Exact factorisation of Eq. (26) found from the block structure of Eq. (22)."""
    return Factored(*block_quadratics(forced_jacobian_eq_22(convention, contact)))


@cache
def coefficients_A8(convention: str = "paper", contact: str = _CONTACT) -> tuple[sp.Expr, ...]:
    """``a1..a4`` of the monic quartic, Eqs. (26)-(27) and (A8)."""
    J = forced_jacobian_eq_22(convention, contact)
    return tuple(sp.expand(a) for a in charpoly_eq_12(J).all_coeffs()[1:])


def hurwitz_eq_28(a1, a2, a3, a4) -> list[sp.Expr]:
    """The Hurwitz determinants exactly as printed in Eq. (28).

    The printed ``H4`` has ``- a1 a4^2`` where the determinant has ``- a1^2 a4^2``
    (see `hurwitz_determinants`); kept here as printed for the paper check.
    """
    return [
        a1,
        a1 * a2 - a3,
        a1 * a2 * a3 - a3**2 - a4 * a1**2,
        a1 * a2 * a3 * a4 - a1 * a4**2 - a4 * a3**2,
    ]


def hurwitz_determinants(a1, a2, a3, a4) -> list[sp.Expr]:
    """Leading principal minors of the Hurwitz matrix of the monic quartic, Eq. (28)."""
    H = sp.Matrix([[a1, a3, 0, 0], [1, a2, a4, 0], [0, a1, a3, 0], [0, 1, a2, a4]])
    return [sp.expand(H[:k, :k].det()) for k in range(1, 5)]


def hurwitz_factored(p, q, r, s) -> list[sp.Expr]:
    """Eq. (28) in the factored form of the module docstring (proved by the tests)."""
    H3 = p * r * ((q - s) ** 2 + (p + r) * (p * s + q * r))
    return [p + r, p * (q + r * (p + r)) + r * s, H3, q * s * H3]


@cache
def stability_conditions(convention: str = "paper", contact: str = _CONTACT) -> tuple:
    """``(p, r)``: ``is_stable`` is ``p > 0 and r > 0``, equivalent to Eq. (28)'s ``H_k > 0``.

    Raises
    ------
    AssertionError
        If SymPy cannot prove ``q > 0`` and ``s > 0`` from the parameter domains
        (after a change of the model): the reduction would then not hold and the
        full Hurwitz test must be used.
    """
    p, q, r, s = factored(convention, contact).pqrs
    for name, value in (("q", q), ("s", s)):
        if value.is_positive is not True:
            raise AssertionError(
                f"{name} = {value} is not provably positive: "
                "the Hurwitz test does not reduce to p > 0, r > 0"
            )
    return p, r


@cache
def critical_belt_speed(
    convention: str = "paper", contact: str = _CONTACT, friction: str = _FRICTION
) -> sp.Expr | None:
    """Lower edge of the unstable belt speeds: the root of ``p(Vb) = 0`` below ``V_hat``.

    SymPy solves ``p = 0`` with the slope of Eq. (25); a root ``sqrt(R)`` with
    ``V_hat^2 - R = m^2`` free of ``V_hat`` is returned in the factored form
    ``sqrt((V_hat - m)(V_hat + m))`` (for Coulomb's law ``m = mu_s g / (pi beta1
    omega1)``), proved equal to SymPy's. Where ``m >= V_hat`` the whole range
    ``0 <= Vb < V_hat`` is unstable and the value is 0. In the consistent
    convention with Coulomb's law ``p > 0`` for every ``Vb``: there is no boundary
    and the value is NaN.

    Returns
    -------
    sympy.Expr, None or budget.NoClosedForm
        None where the slope of the law's effective friction is a quadrature
        (`beltmdsm.derive.averaging.closed_form`), or where SymPy's roots of ``p(Vb) = 0`` are
        not one root of the form above; `NoClosedForm` where ``p`` depends on ``Vb``
        otherwise than through ``V_hat^2 - Vb^2`` (no root of that form: `sympy.solve`
        is not called) or `sympy.solve` ran past its budget (`beltmdsm.derive.budget`): then no
        closed-form boundary is claimed.
    """
    slope = mu_bar_slope_eq_25(friction).args[0][0]
    if slope.has(sp.Integral):
        return None
    return _root_below_vhat(factored(convention, contact).tangential.p.subs(mu1, slope))


@cache
def _root_below_vhat(p_of_vb: sp.Expr) -> sp.Expr | None | budget.NoClosedForm:
    """`critical_belt_speed` of the tangential damping ``p(Vb)`` (the same for every
    contact law: the normal block does not enter it), found under the budget of
    `beltmdsm.derive.budget` (`NoClosedForm` past it)."""
    try:
        return budget.within("p(Vb) = 0 below Vhat", _solve_below_vhat, p_of_vb)
    except budget.Undecided as over:
        return budget.NoClosedForm(f"SymPy's roots of p(Vb) = 0: {over.reason}")


def _solve_below_vhat(p_of_vb: sp.Expr) -> sp.Expr | None | budget.NoClosedForm:
    Vb, Vh = P["Vb"], P["Vhat"]
    # The closed form claimed is a root sqrt(Vhat^2 - m^2) with m free of Vhat: where p
    # depends on Vb and Vhat through Vhat^2 - Vb^2 alone (its derivative along the
    # hyperbolas Vhat^2 - Vb^2 = const vanishes), and then SymPy finds it in a second.
    # Elsewhere solve() would search for roots of other forms (a cubic law: for hours),
    # none of which would be claimed: it is not called.
    if sp.simplify(Vh * sp.diff(p_of_vb, Vb) + Vb * sp.diff(p_of_vb, Vh)) != 0:
        return budget.NoClosedForm(
            "p(Vb) depends on Vb otherwise than through Vhat^2 - Vb^2, so no root "
            "sqrt(Vhat^2 - m^2) is claimed (SymPy's solve is not called)"
        )
    # solve() squares the square root away, so each candidate is substituted back
    # on the branch where it is real (Vhat = m + d, d > 0).
    d = sp.Symbol("d", positive=True)
    # (check=False: solve's own check of each root against the assumptions took 90% of
    # this step's 3-10 s, and the substitution below is the check that decides)
    candidates = [r for r in sp.solve(p_of_vb, Vb, check=False) if not r.could_extract_minus_sign()]
    if not candidates:
        return sp.nan
    m = sp.sqrt(sp.factor(sp.expand(Vh**2 - candidates[0] ** 2)))
    if Vh in m.free_symbols or len(candidates) != 1:
        return None  # a root of another form: no closed-form boundary is claimed
    closed = sp.sqrt((Vh - m) * (Vh + m))
    if sp.simplify(sp.expand(p_of_vb.subs(Vb, closed).subs(Vh, m + d))) != 0:
        return sp.nan
    return sp.Piecewise((closed, m < Vh), (0, True))


def with_friction(expr, friction: str = _FRICTION) -> sp.Expr:
    """``expr`` with ``mu0``, ``mu1`` replaced by Eq. (25) of the friction law (``Vhat``
    stays a parameter)."""
    return sp.sympify(expr).subs({mu0: mu_bar0_eq_25(friction), mu1: mu_bar_slope_eq_25(friction)})
