"""``python -m derive check-paper``: the paper's equations and claims against the derivation.

Every numbered equation transcribed in `derive.paper` is compared with the
expression the package derives:

1. symbolically: ``printed - derived`` is reduced by ``expand``, then ``cancel``,
   then (for small expressions only, to keep the run short) ``simplify``, under the
   symbols' assumptions (positive parameters, ``X2 > 0``);
2. where that does not reach zero, numerically with mpmath at 50 digits at seeded
   random parameter points (exact rational inputs). A difference is only ever
   reported from a numeric counterexample, never from a failed simplification.

Where the paper admits more than one reading (the sign of the effective friction,
docs/modelling.md#friction-sign; the argument of ``mu_bar`` in Eq. 25) a row has one
variant per reading, and its status is ``matches``, ``matches under convention X`` or
``differs``. Every variant that differs carries a hand-written reason; the report
marks a difference without one as unexplained, and a reason given for a variant
that matches as stale, so the reasons cannot drift from the results.

The paper's claims in words are re-derived as rows with the status ``holds``,
``holds under reading X`` or ``does not hold``. The report is deterministic
(seeded points, rows in paper order) and is written through `derive.codegen.write`.

Two claim rows, "omega1 peak (Fig. 2b)" and "contraction (clipped)", also run the
simulation of Eq. (4) (`derive.contraction`, on `beltmdsm/` and `generated/`), so
check-paper runs after ``python -m derive``. Their numbers are rounded (two or
three digits, counts, ``< 1e-4``) so that the report is the same on every code path
of the CI.
"""

from __future__ import annotations

import argparse
import random
import re
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache

import mpmath
import sympy as sp

from . import codegen, friction, mdsm, paper, stability, statespace
from .fit import X2max, coefficients_eq_17, fit_error, polynomial_eq_16
from .model import STATE, X2, P, equal_excitation, equations_of_motion, lam, t
from .parameters import BASE

__all__ = [
    "Variant",
    "Row",
    "Outcome",
    "RowResult",
    "Claim",
    "ClaimResult",
    "compare",
    "check_row",
    "rows",
    "claims",
    "run",
    "report",
    "main",
    "REPORT",
    "DIGITS",
    "POINTS",
]

REPORT = "PAPER_CHECK.md"
#: Working precision of the numeric comparison, and the agreement it requires.
DIGITS = 50
TOLERANCE = mpmath.mpf(10) ** -40
#: Seeded random points per numeric comparison.
POINTS = 16
#: Only expressions this small go through ``simplify`` (larger ones go numeric).
SIMPLIFY_OPS = 150
#: A difference this small (in ``count_ops``) is printed in the report.
SHOW_OPS = 40

CONVENTIONS = stability.CONVENTIONS
d = sp.Symbol("d", positive=True)  # Vhat - Vb on the branch Vhat > Vb


# The engine ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Variant:
    """One reading of an equation: what the paper prints and what is derived.

    Attributes
    ----------
    printed, derived : callable
        Return the two SymPy objects (expressions or matrices of equal shape).
    label : str
        The convention or reading; empty when the equation has only one.
    why : str
        Hand-written reason, required exactly when this variant differs.
    names : tuple of str
        Names of the components (``H1..H4``); default: matrix entries.
    assume : dict
        Substitution restricting both sides to where the paper states the formula
        (``Vhat -> Vb + d``, ``d > 0`` for "Vhat > Vb").
    """

    printed: Callable[[], object]
    derived: Callable[[], object]
    label: str = ""
    why: str = ""
    names: tuple[str, ...] = ()
    assume: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Row:
    """One numbered equation (or part of one: ``Eq. 25 (mu_bar^0)``)."""

    key: str
    content: str
    variants: tuple[Variant, ...]


@dataclass(frozen=True)
class Outcome:
    """Result of one comparison."""

    equal: bool
    method: str
    detail: str = ""


@dataclass(frozen=True)
class RowResult:
    row: Row
    outcomes: tuple[Outcome, ...]
    status: str
    explanation: str
    problems: tuple[str, ...]


def _components(obj, names=()):
    if isinstance(obj, sp.MatrixBase):
        items = list(obj)
        if names:
            labels = list(names)
        elif 1 in obj.shape:
            labels = [f"component {i + 1}" for i in range(len(items))]
        else:
            labels = [f"entry ({i + 1},{j + 1})" for i in range(obj.rows) for j in range(obj.cols)]
    else:
        items, labels = [sp.sympify(obj)], list(names) or [""]
    if len(labels) != len(items):
        raise ValueError(f"{len(labels)} names for {len(items)} components")
    return items, labels


def _symbolic_zero(diff) -> str | None:
    """The first reduction that takes ``diff`` to zero, or None."""
    diff = sp.expand(diff)
    if diff == 0:
        return "expand"
    if not diff.has(sp.Piecewise) and sp.cancel(sp.together(diff)) == 0:
        return "cancel"
    if sp.count_ops(diff) <= SIMPLIFY_OPS and sp.simplify(diff) == 0:
        return "simplify"
    return None


def _frozen(exprs):
    """Replace derivatives and undefined function values by real symbols.

    The comparison must hold for any function ``mu_bar``, ``Phi``..., so each
    distinct application becomes an independent random number.
    """
    atoms = set()
    for e in exprs:
        atoms |= e.atoms(sp.Derivative)
    mapping = {
        a: sp.Symbol(f"_f{i}", real=True)
        for i, a in enumerate(sorted(atoms, key=sp.default_sort_key))
    }
    exprs = [e.xreplace(mapping) for e in exprs]
    applied = set()
    for e in exprs:
        applied |= e.atoms(sp.core.function.AppliedUndef)
    more = {
        a: sp.Symbol(f"_g{i}", real=True)
        for i, a in enumerate(sorted(applied, key=sp.default_sort_key))
    }
    return [e.xreplace(more) for e in exprs], {**mapping, **more}


def _sample(sym: sp.Symbol, rng: random.Random):
    """A random exact value respecting ``sym``'s assumptions, near the paper's scales."""
    name = sym.name
    if name == "Vb":
        v = rng.uniform(0, 16)
    elif name == "Vhat":
        v = rng.uniform(1, 16)
    elif name in BASE:
        v = BASE[name] * 3 ** rng.uniform(-1, 1)
    elif sym.is_positive:
        v = rng.uniform(0.5, 20)
    elif sym.is_real:
        v = rng.uniform(-3, 3)
    else:
        return sp.Rational(round(rng.uniform(-3, 3) * 10**6), 10**6) + sp.I * sp.Rational(
            round(rng.uniform(-3, 3) * 10**6), 10**6
        )
    return sp.Rational(round(v * 10**6), 10**6)


def _value(expr, point) -> mpmath.mpc:
    v = sp.N(expr.xreplace(point), DIGITS)
    if not v.is_number or v.has(sp.nan, sp.zoo, sp.oo):
        raise ArithmeticError(f"could not evaluate {expr} at {point}: {v}")
    re, im = v.as_real_imag()
    return mpmath.mpc(
        mpmath.mpf(sp.Float(re, DIGITS)._mpf_), mpmath.mpf(sp.Float(im, DIGITS)._mpf_)
    )


def _close(a, b) -> bool:
    return abs(a - b) <= TOLERANCE * max(1, abs(a), abs(b))


def _fmt(v) -> str:
    v = complex(v)
    if abs(v.imag) <= 1e-12 * max(1.0, abs(v.real)):
        return f"{v.real:.6g}"
    return f"{v.real:.6g}{v.imag:+.6g}i"


@cache
def base_point() -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """The paper's base set (Fig. 2, ``Vb = 4``) for the numeric examples of the report.

    ``Vhat`` is the tangential reading; ``mu_bar^0, mu_bar'`` are Eq. (25) there,
    ``a1..a4`` the derived Eq. (A8) (convention paper); the state is the equilibrium
    with ``X1 = Z1 = 0``, and ``X2max`` is the equilibrium penetration.
    """
    num = {P[k]: sp.nsimplify(v) for k, v in BASE.items() if k in P}
    num.update({k: sp.sympify(v).subs(num) for k, v in equal_excitation().items()})
    vh = sp.N(friction.vhat("tangential").subs(num), DIGITS + 10)
    num[P["Vhat"]] = vh
    x20 = sp.N(((P["g"] / P["omega2"] ** 2) ** sp.Rational(2, 3)).subs(num), DIGITS + 10)
    mu0 = sp.N(friction.mu_bar0_eq_25().subs(num), DIGITS + 10)
    mu1 = sp.N(friction.mu_bar_slope_eq_25().subs(num), DIGITS + 10)
    num.update(
        {
            stability.mu0: mu0,
            stability.mu1: mu1,
            X2max: x20,
            X2: x20,
            stability.Z2: x20,
            d: vh - num[P["Vb"]],
            friction.Vr: -num[P["Vb"]],
        }
    )
    for s in (*STATE, *stability.SLOW):
        num.setdefault(s, sp.Integer(0))
    num[t] = sp.Integer(1)
    a = stability.coefficients_A8("paper")
    num.update({ak: sp.N(v.subs(num), DIGITS + 10) for ak, v in zip(paper.a_symbols, a)})
    num[lam] = sp.Integer(1)
    return tuple(num.items())


def _at_base(expr):
    """``expr`` at `base_point`, or None if it has symbols the base set does not fix."""
    point = dict(base_point())
    expr = expr.replace(
        lambda e: isinstance(e, stability.mu_bar), lambda e: friction.mu_bar_eq_23(e.args[0])
    )
    expr = expr.xreplace(point)
    if expr.free_symbols or expr.atoms(sp.core.function.AppliedUndef):
        return None
    return _value(expr, {})


def compare(printed, derived, *, seed: int, assume=None, names=()) -> Outcome:
    """Compare two SymPy objects component by component.

    Returns
    -------
    Outcome
        ``method`` says what decided: ``symbolic (expand|cancel|simplify)`` or
        ``numeric (50 digits, N seeded points)``; for a difference, ``detail`` names
        the first differing component, the difference when it is short, and a
        numeric example (the base set if it fixes every symbol, else a seeded point).

    Raises
    ------
    ValueError
        If the two objects have different shapes.
    ArithmeticError
        If a side cannot be evaluated at a sample point.
    """
    assume = assume or {}
    a_items, labels = _components(printed, names)
    b_items, _ = _components(derived, names)
    if len(a_items) != len(b_items) or (
        getattr(printed, "shape", None) != getattr(derived, "shape", None)
    ):
        raise ValueError(
            f"shapes differ: {getattr(printed, 'shape', 1)} vs {getattr(derived, 'shape', 1)}"
        )
    a_items = [sp.sympify(x).subs(assume) for x in a_items]
    b_items = [sp.sympify(x).subs(assume) for x in b_items]
    methods, pending = [], []
    for i, (a, b) in enumerate(zip(a_items, b_items)):
        how = _symbolic_zero(a - b)
        if how is None:
            pending.append(i)
        else:
            methods.append(how)
    if not pending:
        order = ("expand", "cancel", "simplify")
        return Outcome(True, f"symbolic ({max(methods, key=order.index)})")

    rng = random.Random(seed)
    frozen, _ = _frozen([a_items[i] for i in pending] + [b_items[i] for i in pending])
    fa, fb = frozen[: len(pending)], frozen[len(pending) :]
    symbols = sorted(set().union(*(e.free_symbols for e in frozen)), key=lambda s: s.name)
    bad = []
    with mpmath.workdps(DIGITS):
        for k in range(POINTS):
            point = {s: _sample(s, rng) for s in symbols}
            for j, i in enumerate(pending):
                va, vb = _value(fa[j], point), _value(fb[j], point)
                if not _close(va, vb):
                    bad.append((k, i, va, vb))
    method = f"numeric ({DIGITS} digits, {POINTS} seeded points)"
    if not bad:
        return Outcome(True, method)
    k, i, va, vb = bad[0]
    where = labels[i]
    diff = sp.factor(sp.expand(a_items[i] - b_items[i]))
    parts = [f"{where}: " if where else ""]
    if sp.count_ops(diff) <= SHOW_OPS and not diff.has(sp.Piecewise):
        parts.append(f"printed - derived = `{sp.sstr(diff)}`; ")
    with mpmath.workdps(DIGITS):
        ea, eb = _at_base(a_items[i]), _at_base(b_items[i])
    if ea is not None and eb is not None and not _close(ea, eb):
        parts.append(f"at the base set: printed {_fmt(ea)}, derived {_fmt(eb)}")
    else:
        parts.append(f"at seeded point {k + 1}: printed {_fmt(va)}, derived {_fmt(vb)}")
    return Outcome(
        False, f"{method}; differs at {len({b[0] for b in bad})} of {POINTS}", "".join(parts)
    )


def _seed(*parts: str) -> int:
    return zlib.crc32("|".join(parts).encode())


def check_row(row: Row) -> RowResult:
    """Compare every variant of ``row`` and derive its status and explanation."""
    outcomes = tuple(
        compare(
            v.printed(), v.derived(), seed=_seed(row.key, v.label), assume=v.assume, names=v.names
        )
        for v in row.variants
    )
    matching = [v.label for v, o in zip(row.variants, outcomes) if o.equal]
    if len(matching) == len(outcomes):
        status = "matches"
    elif matching:
        status = "matches under convention " + ", ".join(f"`{m}`" for m in matching)
    else:
        status = "differs"
    notes, problems = [], []
    for v, o in zip(row.variants, outcomes):
        tag = f"`{v.label}`: " if v.label else ""
        if not o.equal:
            if not v.why:
                problems.append(f"{row.key} {v.label}: unexplained difference")
            notes.append(f"{tag}{v.why or 'UNEXPLAINED difference.'} {o.detail}".strip())
        elif v.why:
            problems.append(f"{row.key} {v.label}: explanation given but it matches")
            notes.append(f"{tag}STALE explanation (this variant matches).")
    return RowResult(row, outcomes, status, " ".join(notes), tuple(problems))


# The rows, in paper order ----------------------------------------------------------------


def _matrix(values):
    return sp.Matrix(list(values))


def _eq4_printed():
    sol = sp.solve(list(paper.eq_4()), [paper.X1ddot, paper.X2ddot], dict=True)
    if len(sol) != 1:
        raise RuntimeError(f"Eq. (4) does not determine the accelerations: {sol}")
    return sp.Matrix([sol[0][paper.X1ddot], sol[0][paper.X2ddot]])


def _state(i):
    return lambda: statespace.state_space_eqs_5_8()[i]


def _slow(i, convention):
    return lambda: stability.slow_state_space_A3_A6(convention)[i]


def _forced_charpoly(convention):
    return lambda: statespace.charpoly_eq_12(stability.forced_jacobian_eq_22(convention)).as_expr()


_A1, _A2, _PH1, _PH2 = sp.symbols("A1 A2", positive=True) + sp.symbols("phi1 phi2", real=True)
#: Fast monomials whose average the MDSM uses (Eq. 15 must agree with them).
_FAST = (
    mdsm.Phi1,
    mdsm.Phi2,
    sp.diff(mdsm.Phi1, mdsm.theta),
    mdsm.Phi2**2,
    mdsm.Phi2**3,
    mdsm.Phi1 * mdsm.Phi2,
    mdsm.Phi2**2 * sp.diff(mdsm.Phi2, mdsm.theta),
    mdsm.Phi2 * sp.diff(mdsm.Phi2, mdsm.theta) ** 2,
)


def _harmonic(f):
    shapes = {
        mdsm.Phi1: _A1 * sp.sin(mdsm.theta + _PH1),
        mdsm.Phi2: _A2 * sp.sin(mdsm.theta + _PH2),
    }
    return f.subs(shapes).doit()


def _eq15_printed():
    return sp.Matrix([sp.simplify(paper.eq_15(_harmonic(f))) for f in _FAST])


def _eq15_derived():
    return sp.Matrix(
        [sp.simplify(mdsm.harmonic_averages(mdsm.avg(f), _A1, _A2, _PH1, _PH2)) for f in _FAST]
    )


_WHY_CONSISTENT = (
    "with the sign of Eq. (4), `-mu_bar(Z1'-Vb) F_n` (as Eq. 20 prints it), "
    "every friction term changes sign;"
)
_WHY_PAPER_SIGN = (
    "Eq. (A4) carries `+mu_bar F_n` with `mu_bar` of Eq. (23) negative for "
    "`V_r < 0`, i.e. friction pushing against the belt; Eq. (20) and the MDSM "
    "derivation give `-mu_bar F_n`;"
)


def rows() -> tuple[Row, ...]:
    """Every numbered equation of the paper with its derivation."""

    def conv(printed, derived_of, whys, names=()):
        return tuple(
            Variant(printed, derived_of(c), c, whys.get(c, ""), names) for c in CONVENTIONS
        )

    J11 = statespace.jacobian_at_equilibrium_eq_11
    eq9 = lambda: _matrix(statespace.equilibrium_eq_9()[s] for s in STATE)  # noqa: E731
    return (
        Row(
            "Eq. 4",
            "equations of motion, solved for the accelerations",
            (Variant(_eq4_printed, lambda: equations_of_motion(general=False)),),
        ),
        Row("Eq. 5", "state equation `X1' = Y1`", (Variant(paper.eq_5, _state(0)),)),
        Row("Eq. 6", "state equation `Y1'` (branch `X1' < Vb`)", (Variant(paper.eq_6, _state(1)),)),
        Row("Eq. 7", "state equation `X2' = Y2`", (Variant(paper.eq_7, _state(2)),)),
        Row("Eq. 8", "state equation `Y2'`", (Variant(paper.eq_8, _state(3)),)),
        Row("Eq. 9", "unforced equilibrium", (Variant(paper.eq_9, eq9),)),
        Row("Eq. 10", "Jacobian of Eqs. 5-8", (Variant(paper.eq_10, statespace.jacobian_eq_10),)),
        Row("Eq. 11", "Jacobian at equilibrium `J^0`", (Variant(paper.eq_11, J11),)),
        Row(
            "Eq. 12",
            "characteristic polynomial of the printed `J^0`",
            (Variant(paper.eq_12, lambda: statespace.charpoly_eq_12(J11()).as_expr()),),
        ),
        Row(
            "Eq. 13",
            "MDSM split of `X1`",
            (Variant(paper.eq_13, lambda: mdsm.split_eqs_13_14()[0][0]),),
        ),
        Row(
            "Eq. 14",
            "MDSM split of `X2`",
            (Variant(paper.eq_14, lambda: mdsm.split_eqs_13_14()[0][1]),),
        ),
        Row(
            "Eq. 15",
            "fast average (printed integral) against the MDSM averages, "
            "harmonic `Phi`, for "
            + ", ".join(f"`{sp.sstr(f)}`" for f in _FAST[:2])
            + " and six products",
            (Variant(_eq15_printed, _eq15_derived),),
        ),
        Row(
            "Eq. 16",
            "cubic in `X2` with the printed coefficients",
            (Variant(paper.eq_16, lambda: polynomial_eq_16(X2, 3)),),
        ),
        Row(
            "Eq. 17",
            "least-squares coefficients `c3, c2, c1, c0`",
            (
                Variant(
                    paper.eq_17,
                    lambda: _matrix(reversed(coefficients_eq_17(3))),
                    names=("c3", "c2", "c1", "c0"),
                ),
            ),
        ),
        Row(
            "Eq. 18",
            "slow tangential equation with the cubic",
            (Variant(paper.eq_18, lambda: mdsm.slow_equations_18_19()[0]),),
        ),
        Row(
            "Eq. 19",
            "slow normal equation with the cubic",
            (Variant(paper.eq_19, lambda: mdsm.slow_equations_18_19()[1]),),
        ),
        Row(
            "Eq. 20",
            "slow tangential equation with `Z2^(3/2)`",
            (Variant(paper.eq_20, lambda: mdsm.slow_equations_20_21()[0]),),
        ),
        Row(
            "Eq. 21",
            "slow normal equation with `Z2^(3/2)`",
            (Variant(paper.eq_21, lambda: mdsm.slow_equations_20_21()[1]),),
        ),
        Row(
            "Eq. 22",
            "forced Jacobian `J_f^0`",
            conv(
                paper.eq_22,
                lambda c: lambda: stability.forced_jacobian_eq_22(c),
                {"consistent": _WHY_CONSISTENT},
            ),
        ),
        Row(
            "Eq. 23",
            "effective friction (arc-cosine form)",
            (Variant(paper.eq_23, lambda: friction.mu_bar_eq_23(stability.S1 - P["Vb"])),),
        ),
        Row(
            "Eq. 24",
            "first-order expansion of the printed Eq. 23 at `Z1' = 0`",
            (
                Variant(
                    paper.eq_24,
                    lambda: stability.with_friction(stability.mu0 + stability.mu1 * stability.S1),
                ),
            ),
        ),
        Row(
            "Eq. 25 (mu_bar^0)",
            "`mu_bar^0 = mu_bar(Z1'^0)` with Eq. 23",
            (
                Variant(lambda: paper.eq_25_mu0("Z1dot"), friction.mu_bar0_eq_25, "argument Z1'"),
                Variant(
                    lambda: paper.eq_25_mu0("Vr"),
                    friction.mu_bar0_eq_25,
                    "argument V_r",
                    "read as Eq. (23)'s `mu_bar(V_r)` at `V_r = Z1'^0 = 0` the value is "
                    "`mu_bar(0) = 0`; the expansion point of Eq. (24) is `Z1' = 0`, "
                    "i.e. `V_r = -Vb`;",
                ),
            ),
        ),
        Row(
            "Eq. 25 (mu_bar')",
            "slope of the effective friction, for `Vhat > Vb`",
            (
                Variant(
                    paper.eq_25_slope, friction.mu_bar_slope_eq_25, assume={P["Vhat"]: P["Vb"] + d}
                ),
            ),
        ),
        Row(
            "Eq. 26",
            "characteristic polynomial of the printed `J_f^0`",
            conv(
                paper.eq_26,
                _forced_charpoly,
                {
                    "consistent": "inherits Eq. (22): the `mu_bar' g` term changes sign "
                    "(`mu_bar^0` drops out of the determinant);"
                },
            ),
        ),
        Row(
            "Eq. 27",
            "quartic with the printed `a1..a4` of Eq. A8",
            conv(
                paper.eq_27,
                _forced_charpoly,
                {"consistent": "inherits Eq. (22): every `mu_bar'` term changes sign;"},
            ),
        ),
        Row(
            "Eq. 28",
            "Hurwitz determinants `H1..H4` (generic `a1..a4`)",
            (
                Variant(
                    paper.eq_28,
                    lambda: _matrix(stability.hurwitz_determinants(*paper.a_symbols)),
                    why="the printed `H4` has `a1 a4^2` where the 4th leading minor of the "
                    "Hurwitz matrix (= `a4 H3`) has `a1^2 a4^2`; the printed term is "
                    "dimensionally inconsistent (`a_k` ~ 1/s^k: s^-9 among s^-10);",
                    names=("H1", "H2", "H3", "H4"),
                ),
            ),
        ),
        Row(
            "Eq. A1",
            "fast tangential equation (residual)",
            (Variant(paper.eq_A1, lambda: mdsm.fast_equations_A1_A2()[0]),),
        ),
        Row(
            "Eq. A2",
            "fast normal equation (residual)",
            (Variant(paper.eq_A2, lambda: mdsm.fast_equations_A1_A2()[1]),),
        ),
        Row(
            "Eq. A3", "slow state equation `Z1' = S1`", conv(paper.eq_A3, lambda c: _slow(0, c), {})
        ),
        Row(
            "Eq. A4",
            "slow state equation `S1'`",
            conv(paper.eq_A4, lambda c: _slow(1, c), {"consistent": _WHY_PAPER_SIGN}),
        ),
        Row(
            "Eq. A5", "slow state equation `Z2' = S2`", conv(paper.eq_A5, lambda c: _slow(2, c), {})
        ),
        Row("Eq. A6", "slow state equation `S2'`", conv(paper.eq_A6, lambda c: _slow(3, c), {})),
        Row(
            "Eq. A7",
            "slow equilibrium",
            conv(
                paper.eq_A7,
                lambda c: (
                    lambda: _matrix(stability.slow_equilibrium_A7(c)[s] for s in stability.SLOW)
                ),
                {
                    "consistent": "with the sign of Eq. (4), `Z1^0 = -mu_bar^0 g/omega1^2 > 0` "
                    "(like `X1^0` of Eq. 9); the printed `Z1^0` is negative;"
                },
            ),
        ),
        Row(
            "Eq. A8",
            "coefficients `a1..a4` of the quartic",
            conv(
                paper.eq_A8,
                lambda c: lambda: _matrix(stability.coefficients_A8(c)),
                {"consistent": "inherits Eq. (22): every `mu_bar'` term changes sign;"},
                names=("a1", "a2", "a3", "a4"),
            ),
        ),
    )


# Claims in words -------------------------------------------------------------------------


@dataclass(frozen=True)
class Claim:
    """A statement of the paper in words, with the function that checks it.

    ``check`` returns ``(holds_under, evidence)``: the readings under which the
    claim holds (``["" ]`` when it holds without a reading, ``[]`` when it does not)
    and one line of evidence computed from the derivation.
    """

    key: str
    where: str
    text: str
    readings: tuple[str, ...]
    check: Callable[[], tuple[list[str], str]]


@dataclass(frozen=True)
class ClaimResult:
    claim: Claim
    status: str
    evidence: str


def _base_numbers() -> dict:
    num = {P[k]: sp.nsimplify(v) for k, v in BASE.items() if k in P}
    num.update({k: sp.sympify(v).subs(num) for k, v in equal_excitation().items()})
    return num


def _n(expr, digits=6):
    return sp.N(expr, digits)


def _claim_mu_s():
    J0 = statespace.jacobian_at_equilibrium_eq_11()
    poly = statespace.charpoly_eq_12(J0).as_expr()
    in_J = not statespace.free_of(J0, P["mu_s"])
    absent = statespace.free_of(poly, P["mu_s"]) and statespace.free_of(paper.eq_12(), P["mu_s"])
    ok = in_J and absent
    return ([""] if ok else []), (
        f"`mu_s` {'appears' if in_J else 'does not appear'} in `J^0` (Eq. 11) and "
        f"{'is absent from' if absent else 'appears in'} `det(lambda I - J^0)` "
        "(derived and printed): the friction column only couples the tangential block "
        "to the normal one, so the determinant is the product of the two diagonal blocks."
    )


def _claim_only_slope():
    found = []
    for c in CONVENTIONS:
        a = stability.coefficients_A8(c)
        found.append(
            all(statespace.free_of(x, stability.mu0) for x in a)
            and any(not statespace.free_of(x, stability.mu1) for x in a)
        )
    printed = paper.eq_A8()
    found.append(
        printed.free_symbols.isdisjoint({stability.mu0}) and stability.mu1 in printed.free_symbols
    )
    ok = all(found)
    return ([""] if ok else []), (
        "`a1..a4` contain `mu_bar'` and not `mu_bar^0` in both conventions and in the "
        "printed Eq. A8: `mu_bar^0` sits only in the upper-right block of `J_f^0`, "
        "which a block-triangular determinant never uses."
    )


def _claim_fit():
    err = fit_error(3)
    rel = err.max_abs / X2max ** sp.Rational(3, 2)
    num = _base_numbers()
    top = mdsm.x2max().subs(num)
    absolute = err.max_abs.subs(X2max, top)
    order = lambda v: round(float(sp.log(sp.N(v, 30), 10)))  # noqa: E731
    holds = []
    if order(rel) == -2:
        holds.append("relative to X2max^(3/2)")
    if order(absolute) == -2:
        holds.append("absolute, base set")
    return holds, (
        f"largest error exactly `{sp.sstr(err.max_abs)}` at `X2 = {sp.sstr(err.argmax)}` "
        f"(RMS `{sp.sstr(err.rms)}`): {_n(rel, 3)} of `X2max^(3/2)`, which rounds to "
        f'1e{order(rel)} ("about 1e-2" read as the nearest power of ten); in absolute '
        f"terms at the base set's fitted range `X2max = {_n(top, 4)}` m "
        f"(`derive.mdsm.x2max`) it is {_n(absolute, 3)} m^(3/2)."
    )


def _claim_overdamped():
    num = _base_numbers()
    normal = statespace.block_quadratics(statespace.jacobian_at_equilibrium_eq_11())[1]
    disc = normal.disc.subs(num)
    same = all(
        stability.forced_jacobian_eq_22(c)[2:, 2:]
        == statespace.jacobian_at_equilibrium_eq_11()[2:, 2:]
        for c in CONVENTIONS
    )
    b2 = P["beta2"]
    crit = [
        r
        for r in sp.solve(normal.disc.subs({k: v for k, v in num.items() if k != b2}), b2)
        if r.is_positive
    ]
    ok = disc > 0 and normal.p.subs(num) > 0 and normal.q.subs(num) > 0 and same
    return ([""] if ok else []), (
        f"normal block of `J^0`: `lambda^2 + {_n(normal.p.subs(num), 4)} lambda + "
        f"{_n(normal.q.subs(num), 4)}`, quarter discriminant {_n(disc, 4)} > 0 (two real "
        f"negative eigenvalues); the forced `J_f^0` has the same normal block "
        f"({'both conventions' if same else 'NOT in every convention'}); critical damping "
        f"at `beta2* = {', '.join(str(_n(r, 4)) for r in crit)}`."
    )


def _unstable_ranges(convention: str, vhat_value, num) -> list[tuple[float, float]]:
    """Belt speeds in [0, 20] where a Hurwitz determinant of the derived quartic is <= 0.

    Scanned on a 0.05 m/s grid, each edge then bisected to 1e-15.
    """
    a = [
        stability.with_friction(x).subs(num).subs(P["Vhat"], vhat_value)
        for x in stability.coefficients_A8(convention)
    ]
    H = [sp.lambdify(P["Vb"], h, "mpmath") for h in stability.hurwitz_determinants(*a)]

    def unstable(v):
        return any(h(v) <= 0 for h in H)

    with mpmath.workdps(30):
        grid = [mpmath.mpf(k) / 20 for k in range(0, 401)]
        flags = [unstable(v) for v in grid]
        edges = []
        for (v0, f0), (v1, f1) in zip(zip(grid, flags), zip(grid[1:], flags[1:])):
            if f0 != f1:
                lo, hi = v0, v1
                for _ in range(50):
                    mid = (lo + hi) / 2
                    lo, hi = (mid, hi) if unstable(mid) == f0 else (lo, mid)
                edges.append(float(hi))
    bounds = ([0.0] if flags[0] else []) + edges + ([20.0] if flags[-1] else [])
    return list(zip(bounds[::2], bounds[1::2]))


def _claim_bifurcation():
    num = {k: v for k, v in _base_numbers().items() if k != P["Vb"]}
    holds, parts = [], []
    for model in friction.VHAT_MODELS:
        vh = sp.N(friction.vhat(model).subs(num), 30)
        vh = sp.re(vh) if abs(sp.im(vh)) < 1e-20 else vh
        for c in CONVENTIONS:
            ranges = _unstable_ranges(c, vh, num)
            text = ", ".join(f"[{lo:.4g}, {hi:.4g})" for lo, hi in ranges) if ranges else "none"
            parts.append(f"V_hat {model} ({_n(vh, 4)}), {c}: unstable {text}")
            if ranges and abs(ranges[-1][1] - 8) <= 0.8:
                holds.append(f"V_hat {model}, convention {c}")
    return holds, (
        "; ".join(parts) + '. "About 8" read as within 10 %: the upper end '
        "of the unstable range (stable above it) must lie in [7.2, 8.8]."
    )


def _claim_slope():
    Vb, Vh, mu = P["Vb"], P["Vhat"], P["mu_s"]
    slope = friction.mu_bar_slope_eq_25()
    below = slope.args[0][0]
    rising = sp.simplify(sp.diff(below, Vb).subs(Vh, Vb + d)).is_nonnegative
    # One-sided limit through Vb = Vhat - e, e -> 0+ (SymPy's limit at the symbolic
    # point Vhat with dir="-" returns -oo), for mu_s > 0 (mu_s = 0: no friction).
    e, m = sp.Symbol("e", positive=True), sp.Symbol("m", positive=True)
    to_inf = sp.limit(below.subs({Vb: Vh - e, mu: m}), e, 0, "+") == sp.oo
    above = slope.subs({Vh: 1, Vb: 2}) == 0
    start = below.subs(Vb, 0)
    num = _base_numbers()
    vh = sp.N(friction.vhat("tangential").subs(num), 15)
    ok = bool(rising and to_inf and above)
    return ([""] if ok else []), (
        f"for `Vb < Vhat` the slope {'rises' if rising else 'does NOT rise'} with `Vb` "
        f"(derivative >= 0), {'tends to +oo' if to_inf else 'stays finite'} as "
        f"`Vb -> Vhat-`, and is {'0' if above else 'not 0'} for `Vb > Vhat`; its smallest "
        f"value is `{sp.sstr(start)}` at `Vb = 0`, {_n(start.subs(num).subs(Vh, vh), 3)} at "
        'the base set (tangential `Vhat`): "nearly zero" only for large `Vhat`.'
    )


def _claim_unforced_limit():
    poly = statespace.charpoly_eq_12(statespace.jacobian_at_equilibrium_eq_11())
    ok = all(
        sp.expand(
            sp.Poly(
                statespace.charpoly_eq_12(stability.forced_jacobian_eq_22(c))
                .as_expr()
                .subs(stability.mu1, 0),
                lam,
            ).as_expr()
            - poly.as_expr()
        )
        == 0
        for c in CONVENTIONS
    )
    return ([""] if ok else []), (
        "with `mu_bar' = 0` the derived quartic of `J_f^0` equals `det(lambda I - J^0)` "
        f"in both conventions: {'yes' if ok else 'NO'}."
    )


def _claim_state_space():
    """Eq. (A4) against the printed Eq. (20) moved to state-space form."""
    z = mdsm
    to_state = {
        sp.diff(z.Z1, z.tau, 2): sp.Symbol("S1dot"),
        sp.diff(z.Z1, z.tau): stability.S1,
        sp.diff(z.Z2, z.tau): stability.S2,
    }
    eq20 = paper.eq_20().subs(to_state).subs({z.Z1: stability.Z1, z.Z2: stability.Z2})
    eq20 = eq20.subs(z.mu_bar, stability.mu_bar(stability.S1 - P["Vb"]))
    s1dot = sp.solve(eq20, sp.Symbol("S1dot"))[0]
    diff = sp.factor(sp.expand(paper.eq_A4() - s1dot))
    ok = diff == 0
    return ([""] if ok else []), (
        "Eq. (20) as printed, solved for `S1'`, minus Eq. (A4) as printed: "
        f"`{sp.sstr(-diff)}`"
        + (
            ""
            if ok
            else " - the friction term has opposite signs; A4 agrees "
            "with Eq. 20 only if its `mu_bar` is read as `-mu_bar`"
            " (the sign resolved for `V_r < 0`, as `+mu_s` in Eq. 6)."
        )
    )


#: The simulated claims: the base set at the Fig. 3 belt speed, 1000 s runs, and the
#: tangential offset of the second run of each pair (derive/contraction.py).
SIM_VB = 4.0
SIM_T_END = 1000.0
SIM_SHIFT = (5.0, -3.0)
#: A sampled E_d "never rises" when no step between samples exceeds this fraction of
#: E_d(0) (the runs' tolerance is 1e-10; derive/contraction.py's tests bound it finer).
RISE_TOLERANCE = 1e-9
#: E_d has "decayed" below this fraction of E_d(0) at the end of a run.
DECAYED = 1e-12


@cache
def _difference_runs():
    """Per tension law: two runs under one normal motion and their difference's balance.

    Runs the simulation (`beltmdsm.simulation`, on `generated/`): check-paper must run
    after ``python -m derive``.
    """
    from . import contraction

    out = {}
    for tension in ("allowed", "clipped"):
        run = contraction.difference_runs(SIM_SHIFT, tension=tension, t_end=SIM_T_END, Vb=SIM_VB)
        out[tension] = (run, contraction.difference_works(run))
    return out


def _shift_text() -> str:
    return "(" + ", ".join(f"{x:g}" for x in SIM_SHIFT) + ")"


def _ratio_text(sim) -> str:
    s = sim.summary
    r = s.peak_omega1 / s.peak_Omega
    return f"= {r:.2f}" if r >= 1e-2 else ("< 1e-4" if r < 1e-4 else f"= {r:.1g}")


def _claim_omega1_peak():
    from beltmdsm.analysis.summary import PEAK_PRESENT_RATIO

    from . import contraction

    runs = _difference_runs()
    holds, parts = [], []
    for tension in ("allowed", "clipped"):
        run, works = runs[tension]
        sim = run.a
        present = bool(sim.summary.omega1_peak_present)
        free_phase = run.energy[-1] > DECAYED * run.energy[0]
        rev = contraction.reversals_by_force_sign(sim, sim.settings.window_start)
        if present and free_phase:
            holds.append(f"tension {tension}")
        parts.append(
            f"tension {tension}: peak_omega1/peak_Omega {_ratio_text(sim)} "
            f"({'present' if present else 'absent'}, threshold {PEAK_PRESENT_RATIO}); a run "
            f"started {_shift_text()} away in (X1, X1') "
            + (
                "keeps its distance (E_d "
                f"{run.energy[0]:.3g} -> {run.energy[-1]:.3g}): a "
                "free phase, i.e. a self-excited oscillation"
                if free_phase
                else "converges to it (E_d < 1e-12 of its start): a forced response"
            )
            + f"; reversals in the steady window: {rev['slip_forward'][0]} to forward "
            f"sliding with F < 0 and {rev['slip_forward'][1]} with F >= 0, "
            f"{rev['slip_back'][0]} to backward sliding with F < 0 and "
            f"{rev['slip_back'][1]} with F >= 0"
        )
    return holds, (
        f"base set, Vb = {SIM_VB:g} (Fig. 3), {SIM_T_END:g} s runs, steady window after "
        "30 %. " + "; ".join(parts) + ". Mechanism: friction `-mu_s sgn(Vr) F` with "
        "`F < 0` is `mu_s |F| sgn(Vr)`, along the relative velocity; every reversal "
        "from backward to forward sliding happens while Eq. (1) pulls, so the "
        "friction flips from pushing the mass backward to pushing it forward, away from "
        "the belt speed on both sides (negative damping), while the reversals back "
        "happen under a pushing contact. With the clipped law that force is 0 and "
        "derive/contraction.py proves that no self-excited vibration is possible."
    )


def _claim_contraction():
    from . import contraction

    cl = contraction.claim()
    runs = _difference_runs()
    holds, numbers = [], []
    for tension in ("clipped", "allowed"):
        run, w = runs[tension]
        E = run.energy
        rise = float((E[1:] - E[:-1]).max())
        monotone = rise <= RISE_TOLERANCE * E[0]
        decays = E[-1] <= DECAYED * E[0]
        if decays and monotone and (tension == "allowed" or cl.proved_by_sympy):
            holds.append(f"tension {tension}")
        numbers.append(
            f"tension {tension}: E_d {E[0]:.3g} -> "
            + (f"< {DECAYED:.0e} of that" if decays else f"{E[-1]:.3g}")
            + (", never rising" if monotone else f" (largest rise between samples {rise:.2g})")
            + f"; friction work on the difference {w['work_friction_push']:+.3g} while "
            "F >= 0 and "
            + (
                f"{w['work_friction_pull']:+.3g} while F < 0"
                if w["work_friction_pull"]
                else "none while F < 0 (F never is)"
            )
            + f", dashpot {w['work_viscous']:+.3g}"
        )
    sympy_steps = "; ".join(
        f"{s.name} ({'proved' if s.proved else 'NOT proved'})" for s in cl.steps if s.how == "SymPy"
    )
    words = "; ".join(s.detail for s in cl.steps if s.how == "words")
    breaks = "; ".join(f"{k}: {d}" for k, (ok, d) in cl.breaks.items() if ok)
    return holds, (
        f"SymPy (derive/contraction.py): {sympy_steps}. So `dE_d/dt = -c1 e'^2 - mu_s F "
        "(s_a - s_b)(Vr_a - Vr_b) <= -c1 e'^2` while `F >= 0` (always, clipped); "
        f"converse: {cl.converse}. In words: {words}. Conditions: "
        + "; ".join(cl.conditions)
        + f". Without them (SymPy): {breaks}. Numerically "
        f"(base set, Vb = {SIM_VB:g}, {SIM_T_END:g} s, second run offset {_shift_text()} in "
        "(X1, X1')): " + "; ".join(numbers) + "."
    )


def claims() -> tuple[Claim, ...]:
    """The paper's claims in words, each with its check."""
    return (
        Claim(
            "omega1 peak (Fig. 2b)",
            "Sect. 3, Fig. 2b",
            "the omega1 peak of Fig. 2b is friction-induced vibration of the model",
            ("tension allowed", "tension clipped"),
            _claim_omega1_peak,
        ),
        Claim(
            "mu_s absent",
            "Sect. 4.1 below Eq. 12",
            "`mu_s` appears in `J^0` but not in the characteristic equation",
            (),
            _claim_mu_s,
        ),
        Claim(
            "only mu_bar'",
            "Sect. 4.3 (Fig. 9 text)",
            "only `mu_bar'`, not `mu_bar^0`, remains in `a1..a4`",
            (),
            _claim_only_slope,
        ),
        Claim(
            "fit error",
            "below Eq. 17",
            "the cubic fit has a maximum error of about 1e-2",
            ("relative to X2max^(3/2)", "absolute, base set"),
            _claim_fit,
        ),
        Claim(
            "overdamped normal",
            "Sect. 4.2 end",
            "with `beta2* = 0.15` the normal direction is overdamped (unforced and forced)",
            (),
            _claim_overdamped,
        ),
        Claim(
            "bifurcation ~ 8",
            "Sect. 4.2, Fig. 5; Sect. 4.3, Fig. 7",
            "base set: positive growth rate for `Vb` below about 8 m/s, stable above",
            tuple(f"V_hat {m}, convention {c}" for m in friction.VHAT_MODELS for c in CONVENTIONS),
            _claim_bifurcation,
        ),
        Claim(
            "slope (Fig. 9)",
            "Sect. 4.3, Fig. 9",
            "`mu_bar'` rises with `Vb`, goes to infinity as `Vb -> Vhat`, is zero above "
            "`Vhat`, and spans from nearly zero to infinity",
            (),
            _claim_slope,
        ),
        Claim(
            "unforced limit",
            "Sects. 4.2-4.3",
            "when `mu_bar' = 0` the forced characteristic equation is the unforced one",
            (),
            _claim_unforced_limit,
        ),
        Claim(
            "A3-A6 = Eqs. 18-21",
            "Appendix A.2",
            "Eqs. A3-A6 are the slow equations (18)-(21) in state-space form",
            (),
            _claim_state_space,
        ),
        Claim(
            "contraction (clipped)",
            "beyond the paper (docs/modelling.md#tension)",
            "two tangential motions under one normal motion converge when the contact "
            "cannot pull: no self-excited vibration, no coexistence",
            ("tension clipped", "tension allowed"),
            _claim_contraction,
        ),
    )


def check_claim(claim: Claim) -> ClaimResult:
    holds, evidence = claim.check()
    unknown = [h for h in holds if h and h not in claim.readings]
    if unknown:
        raise ValueError(f"{claim.key}: readings {unknown} not declared")
    if holds == [""]:
        status = "holds"
    elif holds and len(holds) == len(claim.readings):
        status = "holds"
    elif holds:
        status = "holds under reading " + "; ".join(f"`{h}`" for h in holds)
    else:
        status = "does not hold"
    return ClaimResult(claim, status, evidence)


# Report ----------------------------------------------------------------------------------


def run(selected: tuple[str, ...] | None = None):
    """Check the rows (all, or those whose key is in ``selected``) and every claim."""
    results = tuple(check_row(r) for r in rows() if selected is None or r.key in selected)
    claim_results = tuple(check_claim(c) for c in claims()) if selected is None else ()
    return results, claim_results


def _cell(text: str) -> str:
    return re.sub(r"\s+", " ", text.replace("|", "\\|")).strip()


def report(results, claim_results) -> str:
    """The Markdown report (deterministic: no timings, rows in paper order)."""
    counts = {"matches": 0, "matches under a convention": 0, "differs": 0}
    for r in results:
        key = "matches under a convention" if r.status.startswith("matches under") else r.status
        counts[key] += 1
    problems = [p for r in results for p in r.problems]
    lines = [
        "# The paper's equations and claims against the derivation",
        "",
        "Written by `python -m derive check-paper` (`derive/paper_check.py`); the "
        "transcriptions, typed by hand exactly as printed, are in `derive/paper.py`. "
        "Do not edit: rerun the command.",
        "",
        f"Each equation is compared symbolically (`expand`, `cancel`, `simplify` under "
        f"the symbols' assumptions); where that does not decide, with mpmath at {DIGITS} "
        f"digits at {POINTS} seeded random points (relative agreement 1e-40 required). "
        "The `decided by` column says which. A difference is always a numeric "
        "counterexample; examples use the base set of Fig. 2 with `Vb = 4` and the "
        "tangential `Vhat` (8.521) where it fixes every symbol. Conventions: `paper` = "
        "Eq. A4 as printed (`+mu_bar F_n`, `mu_bar` of Eq. 23), `consistent` = the sign "
        "of Eq. 4 (`-mu_bar(Z1' - Vb) F_n`), docs/modelling.md#friction-sign.",
        "",
        f"**Summary:** {len(results)} equation rows: {counts['matches']} match, "
        f"{counts['matches under a convention']} match under one convention only, "
        f"{counts['differs']} differ. {len(claim_results)} claims: "
        f"{sum(c.status == 'holds' for c in claim_results)} hold, "
        f"{sum(c.status.startswith('holds under') for c in claim_results)} hold under "
        f"one reading, {sum(c.status == 'does not hold' for c in claim_results)} do not hold.",
        "",
    ]
    if problems:
        lines += ["**Check the explanations:** " + "; ".join(problems), ""]
    lines += [
        "## Equations",
        "",
        "| equation | content | status | decided by | difference |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        methods = "; ".join(
            (f"`{v.label}`: " if v.label and len(r.row.variants) > 1 else "") + o.method
            for v, o in zip(r.row.variants, r.outcomes)
        )
        lines.append(
            f"| {r.row.key} | {_cell(r.row.content)} | {r.status} | "
            f"{_cell(methods)} | {_cell(r.explanation)} |"
        )
    lines += [
        "",
        "## Claims in words",
        "",
        "| claim | where | the paper says | status | evidence |",
        "|---|---|---|---|---|",
    ]
    for c in claim_results:
        lines.append(
            f"| {c.claim.key} | {c.claim.where} | {_cell(c.claim.text)} | "
            f"{c.status} | {_cell(c.evidence)} |"
        )
    lines += [
        "",
        "## Transcription choices",
        "",
        "- Eqs. 5-8 and A3-A6 are transcribed as the right-hand sides of the state "
        "equations they define (Eq. 5 `Y1 = X1'` is `X1' = Y1`).",
        "- Eq. 4 is solved for the accelerations before the comparison (the mass "
        "matrix is the identity); Eqs. 12 and 26 use the printed `J^0` and `J_f^0`, "
        "Eq. 27 the printed `a1..a4`, so they inherit any difference of those.",
        "- Eq. A4's `mu_bar` has no printed argument; it is Eq. 23's `mu_bar(Z1' - Vb)`. "
        "In Eqs. 18-21 and A1-A2 `mu_bar` is the MDSM's average of the Coulomb law "
        "(`derive.mdsm`), `mu` the Coulomb law itself.",
        "- Eq. 15 defines the average; it is checked by applying the printed integral "
        "to harmonic fast motions `Phi_i = A_i sin(theta + phi_i)` (which satisfy "
        "`<Phi> = 0`) and comparing with the averages the MDSM derivation uses.",
        "- In Eqs. A1-A2 a prime is `d/dtheta`, a dot `d/dtau`, and `sin(Omega_e tau)` is "
        "the fast phase `sin(theta)`; Eqs. 13-14 write `Omega` for `Omega_e`.",
        '- Eq. 25\'s slope is stated "for `Vhat > Vb`" and is compared there '
        "(`Vhat = Vb + d`, `d > 0`).",
        "",
    ]
    return "\n".join(lines)


def main(argv=None) -> int:
    """Run the check, write ``generated/PAPER_CHECK.md`` and print a summary.

    Returns 0 whatever the paper says; a broken check raises.
    """
    argparse.ArgumentParser(
        prog="python -m derive check-paper",
        description=f"Compare the paper's equations and claims with the derivation; "
        f"write generated/{REPORT}.",
    ).parse_args(argv)
    start = time.perf_counter()
    results, claim_results = run()
    text = report(results, claim_results)
    changed = codegen.write({REPORT: text})
    statuses = [r.status for r in results]
    print(
        f"{len(results)} equation rows: {statuses.count('matches')} match, "
        f"{sum(s.startswith('matches under') for s in statuses)} match under one "
        f"convention, {statuses.count('differs')} differ; {len(claim_results)} claims: "
        f"{sum(c.status == 'holds' for c in claim_results)} hold, "
        f"{sum(c.status.startswith('holds under') for c in claim_results)} hold under "
        f"one reading, {sum(c.status == 'does not hold' for c in claim_results)} do not."
    )
    for r in results:
        for p in r.problems:
            print(f"WARNING: {p}")
    print(
        f"generated/{REPORT} ({'updated' if changed else 'unchanged'}) "
        f"in {time.perf_counter() - start:.1f} s"
    )
    return 0
