"""State-space form, equilibrium, Jacobian and characteristic polynomial (Sect. 4.1).

Implements Eqs. (5)-(12) of the paper for either contact law: the first-order
form on the sliding branch ``X1' < Vb``, ``X2 > 0`` (Eqs. 5-8), the equilibrium
solved by SymPy (Eq. 9), the Jacobian (Eq. 10) and its value at equilibrium
(Eq. 11), the characteristic polynomial (Eq. 12) and its exact factorisation into
the tangential and normal quadratics.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from .model import STATE, Y1, Y2, equations_of_motion, lam

__all__ = [
    "SLIDING",
    "state_space_eqs_5_8",
    "equilibrium_eq_9",
    "jacobian_eq_10",
    "jacobian_at_equilibrium_eq_11",
    "charpoly_eq_12",
    "Quadratic",
    "block_quadratics",
    "free_of",
]

#: Friction direction on the branch of Eqs. (5)-(8): the mass is slower than the belt.
SLIDING = -1


def state_space_eqs_5_8(
    contact: str = "hertz_damp", forced: bool = False, direction=SLIDING
) -> sp.Matrix:
    """Right-hand side ``(X1', Y1', X2', Y2')`` of Eqs. (5)-(8)."""
    acc = equations_of_motion(contact, direction=direction, forced=forced)
    return sp.Matrix([Y1, acc[0], Y2, acc[1]])


def equilibrium_eq_9(contact: str = "hertz_damp") -> dict[sp.Symbol, sp.Expr]:
    """Equilibrium of the unforced state equations, Eq. (9), solved by SymPy.

    Raises
    ------
    RuntimeError
        If SymPy does not find exactly one equilibrium with ``X2 > 0``.
    """
    solutions = sp.solve(list(state_space_eqs_5_8(contact)), list(STATE), dict=True)
    if len(solutions) != 1:
        raise RuntimeError(f"expected one equilibrium in contact, got {solutions}")
    return {s: sp.simplify(v) for s, v in solutions[0].items()}


def jacobian_eq_10(contact: str = "hertz_damp", forced: bool = False) -> sp.Matrix:
    """Jacobian of Eqs. (5)-(8) with respect to ``(X1, Y1, X2, Y2)``, Eq. (10)."""
    return state_space_eqs_5_8(contact, forced).jacobian(STATE)


@cache
def jacobian_at_equilibrium_eq_11(contact: str = "hertz_damp") -> sp.Matrix:
    """Eq. (10) evaluated at Eq. (9): the matrix ``J^0`` of Eq. (11)."""
    return jacobian_eq_10(contact).subs(equilibrium_eq_9(contact)).applyfunc(sp.simplify)


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
        p = sp.simplify(-block.trace())
        q = sp.simplify(block.det())
        disc = sp.factor(sp.expand(p**2 / 4 - q))
        return cls(p, q, sp.Mul(*(_grouped(f) for f in sp.Mul.make_args(disc))))

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
    product = sp.expand(factors[0].expr() * factors[1].expr())
    if sp.simplify(product - charpoly_eq_12(J).as_expr()) != 0:
        raise ValueError("factorisation does not reproduce the characteristic polynomial")
    return factors


def free_of(expr, symbol: sp.Symbol) -> bool:
    """Whether ``symbol`` is absent from ``expr`` (the claim below Eq. 12 for ``mu_s``)."""
    return symbol not in sp.sympify(expr).free_symbols
