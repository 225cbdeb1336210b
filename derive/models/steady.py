"""Steady sliding of a registered model: equilibrium, Jacobian, characteristic polynomial,
Hurwitz determinants.

Steady sliding is the rest state of the unforced system with the belt moving: ``q' = 0``,
``v_r = -Vb < 0`` (mode -1), every excitation amplitude 0, and ``M q'' = 0``.

* **Equilibrium.** SymPy solves ``M q'' = 0`` for ``q`` only where the outcome is bounded
  by the structure of the equations, never by a clock: the equations are linear in the
  unknowns (one linear solve), or one equation has a single unknown ``u`` and is a
  polynomial of degree at most 4 in ``u^(1/k)`` (the paper's ``X2^(3/2)``: a cubic in
  ``X2^(1/2)``) with exactly one admissible root; the others are solved in turn. A
  unilateral contact's penetration is positive there (in contact). Where this does not
  finish, the generated module takes the named numeric path `NUMERIC` instead: Newton's
  method on the same equations with their derived Jacobian.
* **Jacobian** ``J0 = d f / d y`` of mode -1 at the equilibrium, and the **characteristic
  polynomial** ``det(lambda I - J0) = lambda^m + a_1 lambda^(m-1) + ... + a_m`` in layers:
  the coefficients as polynomials in the non-constant entries of ``J0`` (Berkowitz's
  algorithm on a matrix of placeholders), the entries as expressions of the parameters
  and the equilibrium.
* **Hurwitz determinants** ``H_1 .. H_m`` in the coefficients ``a_1 .. a_m`` (the leading
  minors of the Hurwitz matrix, ``H_m = a_m H_(m-1)``), any order: a handful of
  operations where, written in the parameters, they explode.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from .hybrid import jacobian
from .system import System

__all__ = ["NUMERIC", "Steady", "steady", "hurwitz", "coefficient_symbols", "MAX_DEGREE"]

#: The named numeric path of an equilibrium without a closed form.
NUMERIC = (
    "numeric: Newton's method on M q'' = 0 (q' = 0, mode -1, unforced) with its derived "
    "Jacobian, from q = 0 (a unilateral penetration from 1), at most 60 steps"
)
#: The largest polynomial degree the equilibrium's closed form solves (in a root of u).
MAX_DEGREE = 4


@dataclass(frozen=True)
class Steady:
    """Steady sliding of one model and law.

    ``solution``: coordinate symbol -> closed form, or None (then ``path`` is
    `NUMERIC`); ``residual`` and ``residual_jacobian``: ``M q''`` at rest and its
    derivative in ``q`` (the numeric path's); ``entries``: placeholder -> entry of
    ``J0`` in the parameters and the coordinates (at the equilibrium);
    ``coefficients``: ``a_0 = 1, a_1 .. a_m`` in the placeholders.
    """

    solution: dict | None
    path: str
    residual: tuple
    residual_jacobian: sp.Matrix
    entries: dict
    coefficients: tuple


def _at_rest(s: System) -> dict:
    return {**{v: 0 for v in s.v}, **s.unforced}


def _residual(s: System) -> sp.Matrix:
    rates = [s.fields[-1][s.state.index(v)] for v in s.v]
    return (s.M * sp.Matrix(rates)).subs(_at_rest(s)).applyfunc(sp.expand)


def _linear(eqs, unknowns):
    try:
        A, b = sp.linear_eq_to_matrix(eqs, unknowns)
    except (sp.PolynomialError, ValueError):
        return None
    if A.shape[0] != A.shape[1] or A.free_symbols & set(unknowns) or A.det() == 0:
        return None
    return dict(zip(unknowns, A.LUsolve(b).applyfunc(sp.cancel)))


def _one_unknown(e, u):
    """The single admissible root of ``e(u) = 0``, polynomial in ``u^(1/k)`` of degree
    at most `MAX_DEGREE`; None otherwise."""
    k = sp.ilcm(1, *[p.exp.q for p in e.atoms(sp.Pow) if p.base == u and p.exp.is_Rational])
    z = sp.Dummy("z", positive=True) if u.is_positive else sp.Dummy("z", real=True)
    ez = sp.expand(sp.powdenest(e.subs(u, z**k), force=False))
    try:
        poly = sp.Poly(ez, z)
    except sp.PolynomialError:
        return None
    if poly.degree() > MAX_DEGREE or poly.free_symbols_in_domain & {z} or poly.degree() < 1:
        return None
    roots = [r for r in sp.solve(ez, z) if r.is_real is not False]
    if len(roots) != 1:
        return None
    return sp.factor_terms(roots[0] ** k)


def _solve(eqs: list, unknowns: list) -> dict | None:
    """The closed form by the bounded steps of the module docstring, or None."""
    solution = {}
    while unknowns:
        linear = _linear(eqs, unknowns)
        if linear is not None:
            solution.update(linear)
            break
        for e in eqs:
            free = e.free_symbols & set(unknowns)
            if len(free) == 1:
                (u,) = free
                root = _one_unknown(e, u)
                if root is not None:
                    break
        else:
            return None
        solution[u] = root
        unknowns = [x for x in unknowns if x != u]
        eqs = [sp.expand(x.subs(u, root)) for x in eqs if x is not e]
        solution = {k: v.subs(u, root) for k, v in solution.items()} | {u: root}
    return solution


@cache
def steady(s: System) -> Steady:
    """Steady sliding of ``s`` (module docstring)."""
    residual = _residual(s)
    jac = residual.jacobian(sp.Matrix(s.q))
    # in contact at the equilibrium: a unilateral penetration is positive
    contact = {}
    if s.gap is not None:
        (k,) = [x for x in s.q if x == -s.gap]
        contact = {k: sp.Symbol(k.name, positive=True)}
    eqs = [e.subs({sp.Max(0, k): p for k, p in contact.items()}).subs(contact) for e in residual]
    unknowns = [contact.get(x, x) for x in s.q]
    solved = _solve([e for e in eqs if e != 0], unknowns)
    if solved is not None and len(solved) == len(s.q):
        back = {p: k for k, p in contact.items()}
        solution = {back.get(x, x): solved[x] for x in unknowns}
        path = "closed form"
    else:
        solution, path = None, NUMERIC
    J0 = jacobian(s, -1).subs(_at_rest(s))
    entries, placeholders = {}, sp.zeros(*J0.shape)
    for i in range(J0.rows):
        for j in range(J0.cols):
            e = J0[i, j]
            if e.is_Number:
                placeholders[i, j] = e
            else:
                sym = sp.Symbol(f"_j{i}_{j}", real=True)
                entries[sym] = e
                placeholders[i, j] = sym
    lam = sp.Dummy("lambda")
    poly = placeholders.charpoly(lam, simplify=lambda e: e)
    coefficients = tuple(sp.expand(c) for c in poly.all_coeffs())
    return Steady(solution, path, tuple(residual), jac, entries, coefficients)


def coefficient_symbols(m: int) -> tuple:
    """``a_1 .. a_m``, the coefficients of a monic polynomial of degree ``m``."""
    return sp.symbols(f"a1:{m + 1}", real=True)


@cache
def hurwitz(m: int) -> tuple:
    """The Hurwitz determinants ``H_1 .. H_m`` of ``lambda^m + a_1 lambda^(m-1) + ... + a_m``,
    polynomials in `coefficient_symbols`."""
    a = (sp.Integer(1), *coefficient_symbols(m))

    def entry(i, j):  # 1-based: h_ij = a_(2j - i)
        k = 2 * j - i
        return a[k] if 0 <= k <= m else 0

    H = sp.Matrix(m, m, lambda i, j: entry(i + 1, j + 1))
    out = [sp.expand(H[:k, :k].det(method="berkowitz")) for k in range(1, m)]
    return (*out, sp.expand(a[m] * out[-1]) if out else a[m])
