"""State-space form, equilibrium, Jacobian and characteristic polynomial (Sect. 4.1).

Implements Eqs. (5)-(12) of the paper for every friction and contact law of the
registry (`beltmdsm.derive.laws`): the first-order form on the sliding branch ``X1' < Vb``,
``X2 > 0`` (Eqs. 5-8), the equilibrium solved by SymPy (Eq. 9), the Jacobian
(Eq. 10) and its value at equilibrium (Eq. 11), the characteristic polynomial
(Eq. 12) and its exact factorisation into the tangential and normal quadratics.

With a friction coefficient that depends on the sliding speed the equilibrium
depends on the belt speed (``X1^0 = mu(Vb) g / omega1^2``) and the tangential
damping of the linearisation is ``2 beta1 omega1 + g mu'(Vb)``: Stribeck's falling
law makes steady sliding unstable below a belt speed that `critical_belt_speed`
solves for in closed form.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import budget, laws
from .model import SPEED, STATE, Y1, Y2, P, coefficient, equations_of_motion, lam

__all__ = [
    "SLIDING",
    "DEFAULT",
    "state_space_eqs_5_8",
    "equilibrium_eq_9",
    "jacobian_eq_10",
    "jacobian_at_equilibrium_eq_11",
    "charpoly_eq_12",
    "Quadratic",
    "block_quadratics",
    "free_of",
    "critical_belt_speed",
    "never_positive",
    "tangential_damping",
    "quadratics_at_equilibrium",
    "MU_VB",
    "DMU_VB",
]

#: Friction direction on the branch of Eqs. (5)-(8): the mass is slower than the belt.
SLIDING = -1
#: The default friction and contact laws (the paper's).
DEFAULT = {"friction": laws.default("friction"), "contact": laws.default("contact")}


def state_space_eqs_5_8(
    contact: str = DEFAULT["contact"],
    forced: bool = False,
    direction=SLIDING,
    friction: str = DEFAULT["friction"],
) -> sp.Matrix:
    """Right-hand side ``(X1', Y1', X2', Y2')`` of Eqs. (5)-(8)."""
    acc = equations_of_motion(contact, direction=direction, forced=forced, friction=friction)
    return sp.Matrix([Y1, acc[0], Y2, acc[1]])


#: The friction law's value ``mu(Vb)`` and slope ``mu'(Vb)`` at the sliding speed of the
#: equilibrium, as symbols while SymPy simplifies (see `_law_at_equilibrium`).
MU_VB, DMU_VB = sp.symbols("mu_Vb dmu_Vb", real=True)


def _law_at_equilibrium(friction: str) -> tuple[tuple, tuple]:
    """``(early, late)`` substitutions of `MU_VB`, `DMU_VB` by the law's value and slope.

    What does not depend on the belt speed (Coulomb's ``mu_s`` and its zero slope) is
    substituted before the simplification, which then sees the law; what does
    (Stribeck's ``exp(-Vb/v_s)``) after it, so that ``simplify`` cannot rewrite it into
    a form such as ``exp(Vb/v_s)``, which overflows. Both are tuples (hashable keys
    of the cached derivations).
    """
    m = coefficient(friction, SPEED)
    at = {MU_VB: m.subs(SPEED, P["Vb"]), DMU_VB: sp.diff(m, SPEED).subs(SPEED, P["Vb"])}
    early = tuple((k, v) for k, v in at.items() if P["Vb"] not in v.free_symbols)
    late = tuple((k, v) for k, v in at.items() if P["Vb"] in v.free_symbols)
    return early, late


def _sliding_equations(contact: str, early: tuple) -> sp.Matrix:
    """Eqs. (5)-(8), unforced, with the friction law to first order in the speed at ``Vb``.

    On the branch the sliding speed is ``Vb - X1'``, and ``mu(Vb - X1') = mu(Vb) -
    mu'(Vb) X1' + O(X1'^2)``: exact for the equilibrium (``X1' = 0``) and for the
    Jacobian there, which is all that `equilibrium_eq_9` and
    `jacobian_at_equilibrium_eq_11` take from it.
    """
    early = dict(early)

    def linear(speed):
        return (MU_VB + DMU_VB * (speed - P["Vb"])).subs(early)

    return state_space_eqs_5_8(contact, friction=linear)


@cache
def _equilibrium(contact: str, early: tuple) -> dict[sp.Symbol, sp.Expr]:
    solutions = sp.solve(list(_sliding_equations(contact, early)), list(STATE), dict=True)
    if len(solutions) != 1:
        raise RuntimeError(f"expected one equilibrium in contact, got {solutions}")
    return {s: sp.simplify(v) for s, v in solutions[0].items()}


def equilibrium_eq_9(
    contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> dict[sp.Symbol, sp.Expr]:
    """Equilibrium of the unforced state equations, Eq. (9), solved by SymPy.

    ``X1^0 = mu(Vb) g / omega1^2``: for Coulomb's law ``mu_s g / omega1^2`` as printed.

    Raises
    ------
    RuntimeError
        If SymPy does not find exactly one equilibrium with ``X2 > 0``.
    """
    early, late = _law_at_equilibrium(friction)
    return {s: v.subs(dict(late)) for s, v in _equilibrium(contact, early).items()}


def jacobian_eq_10(
    contact: str = DEFAULT["contact"], forced: bool = False, friction: str = DEFAULT["friction"]
) -> sp.Matrix:
    """Jacobian of Eqs. (5)-(8) with respect to ``(X1, Y1, X2, Y2)``, Eq. (10)."""
    return state_space_eqs_5_8(contact, forced, friction=friction).jacobian(STATE)


@cache
def _jacobian_at_equilibrium(contact: str, early: tuple) -> sp.Matrix:
    J = _sliding_equations(contact, early).jacobian(STATE)
    return J.subs(_equilibrium(contact, early)).applyfunc(sp.simplify)


def jacobian_at_equilibrium_eq_11(
    contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> sp.Matrix:
    """Eq. (10) evaluated at Eq. (9): the matrix ``J^0`` of Eq. (11)."""
    early, late = _law_at_equilibrium(friction)
    return _jacobian_at_equilibrium(contact, early).subs(dict(late))


@cache
def _quadratics(contact: str, early: tuple) -> tuple[Quadratic, Quadratic]:
    return block_quadratics(_jacobian_at_equilibrium(contact, early))


def quadratics_at_equilibrium(
    contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> tuple[Quadratic, Quadratic]:
    """`block_quadratics` of ``J^0``: (tangential, normal), factored before the law's
    belt-speed dependence is substituted (see `_law_at_equilibrium`)."""
    early, late = _law_at_equilibrium(friction)
    return tuple(
        Quadratic(*(x.subs(dict(late)) for x in (q.p, q.q, q.disc)))
        for q in _quadratics(contact, early)
    )


def charpoly_eq_12(J: sp.Matrix) -> sp.Poly:
    """Monic characteristic polynomial ``det(lambda I - J)``, Eq. (12).

    Computed as a Berkowitz determinant without a ``simplify`` pass. (SymPy 1.14's
    ``Matrix.charpoly`` fails on this matrix: it tries to order the block factors
    by comparing symbolic coefficients.)
    """
    n = J.shape[0]
    return sp.Poly(sp.expand((lam * sp.eye(n) - J).det(method="berkowitz")), lam)


@dataclass(frozen=True)
class Quadratic:
    """A monic quadratic factor ``lambda^2 + p lambda + q`` of a characteristic polynomial.

    ``disc`` is the quarter discriminant ``(p/2)^2 - q`` in factored form: near a
    double root it is a difference of nearly equal numbers, and the factored form
    (for the tangential mode ``omega1^2 (beta1 - 1)(beta1 + 1)``) avoids that
    cancellation.
    """

    p: sp.Expr
    q: sp.Expr
    disc: sp.Expr

    @classmethod
    def from_block(cls, block: sp.Matrix) -> Quadratic:
        """The characteristic polynomial of a 2x2 block."""
        return _from_block(sp.ImmutableMatrix(block))

    def expr(self) -> sp.Expr:
        return lam**2 + self.p * lam + self.q

    def growth(self) -> sp.Expr:
        """The largest real part of the two roots (see `largest_real_part`)."""
        return self.largest_real_part(self.p / 2, self.q, self.disc)

    @staticmethod
    def largest_real_part(h, q, disc) -> sp.Expr:
        """Largest real part of the roots of ``lambda^2 + 2 h lambda + q``, ``disc = h^2 - q``.

        A complex pair has real part ``-h``. Of two real roots the larger is
        ``sqrt(disc) - h``; for ``h > 0`` it is the one nearer zero, computed as
        ``q / (-(h + sqrt(disc)))`` so that a slowly decaying mode beside a fast one
        keeps its digits. The one definition of the root selection: the code
        generator prints it, in symbols standing for ``h, q, disc``, for numpy, for
        the scalar kernels and for mpmath.
        """
        root = sp.sqrt(disc)
        return sp.Piecewise((-h, disc < 0), (q / (-(h + root)), h > 0), (root - h, True))


@cache
def _from_block(block: sp.ImmutableMatrix) -> Quadratic:
    """`Quadratic.from_block`, once per block (the normal block is every friction law's)."""
    p = sp.simplify(-block.trace())
    q = sp.simplify(block.det())
    disc = sp.factor(sp.expand(p**2 / 4 - q))
    return Quadratic(p, q, sp.Mul(*(_grouped(f) for f in sp.Mul.make_args(disc))))


def _grouped(factor: sp.Expr) -> sp.Expr:
    """A sum with its terms collected on the symbol that leaves the fewest terms.

    ``-2 beta1 omega1 + 2 omega1 + g mu'`` becomes ``-2 omega1 (beta1 - 1) + g mu'``:
    the difference of inputs (``beta1 - 1``) is then exact in floating point, which is
    what keeps a double root (a critically damped mode) accurate.
    """
    if not factor.is_Add:
        return factor
    options = [
        sp.collect(factor, x, sp.factor) for x in sorted(factor.free_symbols, key=lambda x: x.name)
    ]
    return min([factor] + options, key=lambda e: len(sp.Add.make_args(e)))


def block_quadratics(J: sp.Matrix) -> tuple[Quadratic, Quadratic]:
    """Exact factorisation of ``det(lambda I - J)`` for a block-triangular 4x4 ``J``.

    The friction couples the tangential block to the normal one but not back
    (Eq. 4 is one-way coupled), so the lower-left 2x2 block is zero and the
    characteristic polynomial is the product of those of the diagonal blocks.

    Returns
    -------
    (tangential, normal) : tuple of Quadratic

    Raises
    ------
    ValueError
        If the lower-left block is not identically zero, or the product of the
        factors is not the characteristic polynomial.
    """
    if not J[2:, :2].is_zero_matrix:
        raise ValueError(
            f"Jacobian is not block triangular: lower-left block {J[2:, :2]} is not zero"
        )
    factors = Quadratic.from_block(J[:2, :2]), Quadratic.from_block(J[2:, 2:])
    difference = sp.expand(factors[0].expr() * factors[1].expr() - charpoly_eq_12(J).as_expr())
    # expanded, the difference is 0 for a polynomial law; simplify only what remains
    if difference != 0 and sp.simplify(difference) != 0:
        raise ValueError("factorisation does not reproduce the characteristic polynomial")
    return factors


def free_of(expr, symbol: sp.Symbol) -> bool:
    """Whether ``symbol`` is absent from ``expr`` (the claim below Eq. 12 for ``mu_s``)."""
    return symbol not in sp.sympify(expr).free_symbols


def _largest_irreducible_degree(expr: sp.Expr, x: sp.Symbol) -> int:
    """The largest degree in ``x`` of an irreducible factor of ``expr = 0`` cleared of its
    denominators and radicals (SymPy's `unrad`); 0 where it is not algebraic in ``x``.

    A cheap test of what `sympy.solve` would find: above 2 its roots are Cardano's or
    Ferrari's formulas in the parameters, or none (degree 5 and up), and more than one
    of them may be positive, so no closed form is claimed from them. The rational-root
    law's ``p(Vb) = 0`` is a cubic in ``Vb**2``: solving it ran to the budget of
    `beltmdsm.derive.budget`; this test decides it in a tenth of a second.
    """
    from sympy.polys.polyerrors import BasePolynomialError
    from sympy.solvers.solvers import unrad

    numerator = sp.numer(sp.together(expr))
    try:
        cleared = unrad(numerator, x)
        if cleared is not None and cleared[1]:  # a change of variable: not a polynomial in x
            return 0
        poly = sp.Poly(numerator if cleared is None else cleared[0], x)
    except (BasePolynomialError, NotImplementedError, ValueError):
        return 0
    return max((f.degree() for f, _ in poly.factor_list()[1]), default=0)


def never_positive(root: sp.Expr) -> bool:
    """Whether ``root`` is provably ``<= 0`` wherever it is real (no belt speed then).

    Each fractional power of a base of unknown sign is real only where the base is
    nonnegative: there it is taken as a power of a nonnegative symbol, so that
    ``-sqrt(c_1 g - 2 beta1 omega1) / sqrt(3 c_3 g)`` is recognised as nonpositive. A
    nonnegative parameter is taken positive (at 0, where ``-1/delta_l`` has no value, the
    law degenerates to another one).
    """
    root = root.subs(
        {x: sp.Dummy(x.name, positive=True) for x in root.free_symbols if x.is_positive is not True}
    )

    def real_branch(e):
        return sp.Pow(sp.Dummy("base", nonnegative=True), e.exp)

    def fractional(e):
        return (
            e.is_Pow
            and e.exp.is_Rational
            and not e.exp.is_integer
            and e.base.is_nonnegative is not True
        )

    return root.replace(fractional, real_branch).is_nonpositive is True


@cache
def critical_belt_speed(
    contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> sp.Expr | None | budget.NoClosedForm:
    """The belt speed below which steady sliding is unstable, solved by SymPy; NaN if none.

    The tangential damping of ``J^0`` is ``p(Vb) = 2 beta1 omega1 + g mu'(Vb)`` (the
    slope of the friction law at the sliding speed ``Vb``); the normal block does not
    depend on ``Vb``. Where ``p = 0`` has one root in ``Vb`` that may be positive (a
    falling law such as Stribeck's; of the cubic law ``mu_s - c_1 s + c_3 s^3`` the
    roots are ``+-sqrt((c_1 g - 2 beta1 omega1) / (3 c_3 g))``, and the negative one is
    no belt speed), steady sliding is unstable for ``0 <= Vb < Vb_c`` where ``Vb_c >
    0``, and NaN stands for "no unstable belt speed" where the root is not positive.
    Without a root (Coulomb: ``p = 2 beta1 omega1`` whatever ``Vb``) the value is NaN.
    `sympy.solve` runs under the budget of `beltmdsm.derive.budget`.

    Returns
    -------
    sympy.Expr, None or budget.NoClosedForm
        None where more than one root may be positive (the unstable set is then not
        one interval from 0), or where ``p(0) > 0`` (steady sliding is stable at low
        belt speeds: a root bounds the unstable speeds from below); `NoClosedForm` where
        `sympy.solve` ran past its budget. No closed form is claimed then.
    """
    p = tangential_damping(contact, friction)
    Vb = P["Vb"]
    if Vb not in p.free_symbols:
        return sp.nan
    if _largest_irreducible_degree(p, Vb) > 2:
        return None  # several roots, none proved the only positive one: not solved
    try:
        roots = budget.within(f"{friction}: p(Vb) = 0", sp.solve, p, Vb)
    except budget.Undecided as over:
        return budget.NoClosedForm(f"SymPy's roots of the tangential damping p(Vb): {over.reason}")
    roots = [r for r in roots if not never_positive(r)]
    if len(roots) != 1 or p.subs(Vb, 0).is_positive:
        return None
    return sp.Piecewise((roots[0], roots[0] > 0), (sp.nan, True))


def tangential_damping(
    contact: str = DEFAULT["contact"], friction: str = DEFAULT["friction"]
) -> sp.Expr:
    """``p`` of the tangential quadratic ``lambda^2 + p lambda + q`` of ``J^0`` (Eq. 12)."""
    return quadratics_at_equilibrium(contact, friction)[0].p
