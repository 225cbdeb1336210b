"""The comparison engine of the paper check: a printed equation against its derivation.

``printed - derived`` is reduced by ``expand``, then ``cancel``, then (for small
expressions only, to keep the run short) ``simplify``, under the symbols'
assumptions (positive parameters, ``X2 > 0``); where that does not reach zero the
two sides are compared numerically with mpmath at 50 digits at seeded random
parameter points (exact rational inputs). A difference is only ever reported from a
numeric counterexample, never from a failed simplification.

Where the paper admits more than one reading a row has one variant per reading, and
its status is ``matches``, ``matches under convention X`` or ``differs``. Every
variant that differs carries a hand-written reason; a difference without one is
unexplained, and a reason given for a variant that matches is stale.

The paper's model has Coulomb friction (Eq. 3). A variant whose derivation takes a
friction law (``derived_for``) is also derived for every other law of the registry
(`beltmdsm.derive.laws`): where that derivation differs, the row holds for the laws whose
derivation equals Coulomb's only, and the report says so.
"""

from __future__ import annotations

import random
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache

import mpmath
import sympy as sp

from .. import friction, laws, paper, stability
from ..fit import X2max
from ..model import BASE, STATE, X2, P, equal_excitation, lam, t

__all__ = [
    "REPORT",
    "DIGITS",
    "POINTS",
    "CONVENTIONS",
    "Variant",
    "Row",
    "Outcome",
    "RowResult",
    "compare",
    "check_row",
    "base_point",
    "d",
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


@dataclass(frozen=True)
class Variant:
    """One reading of an equation: what the paper prints and what is derived.

    Attributes
    ----------
    printed, derived : callable
        Return the two SymPy objects (expressions or matrices of equal shape).
        ``derived`` may take a friction law (`beltmdsm.derive.laws`) as its one argument: it is
        then called with the default law (Coulomb's, Eq. 3) for the comparison with
        the paper, and with every other law to find the laws the row holds for.
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
    derived: Callable[..., object]
    label: str = ""
    why: str = ""
    names: tuple[str, ...] = ()
    assume: dict = field(default_factory=dict)
    by_law: bool = False


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
    """The outcome of each variant, the row's status and explanation, and ``laws``: the
    friction laws whose derivation equals Coulomb's (all of them where the row does not
    depend on the law), with ``law_detail`` saying where another law differs."""

    row: Row
    outcomes: tuple[Outcome, ...]
    status: str
    explanation: str
    problems: tuple[str, ...]
    laws: tuple[str, ...] = ()
    law_detail: str = ""


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


def _derived(v: Variant, law: str):
    return v.derived(law) if v.by_law else v.derived()


def _same_for(v: Variant, law: str, seed: int) -> Outcome:
    """Whether the derivation under ``law`` equals the one under the default law.

    A structural match decides at once; otherwise one seeded point at 15 digits finds
    a counterexample cheaply (no simplification of a law's quadratures), and only a
    match there takes the full comparison.
    """
    default = _derived(v, laws.default("friction"))
    other = _derived(v, law)
    if other == default:
        return Outcome(True, "identical")
    a_items, labels = _components(default, v.names)
    b_items, _ = _components(other, v.names)
    rng = random.Random(seed)
    for label, a, b in zip(labels, a_items, b_items):
        a, b = sp.sympify(a).subs(v.assume), sp.sympify(b).subs(v.assume)
        if a == b:
            continue
        frozen, _ = _frozen([a, b])
        symbols = sorted(frozen[0].free_symbols | frozen[1].free_symbols, key=lambda s: s.name)
        point = [_sample(s, rng) for s in symbols]
        with mpmath.workdps(15):
            # lambdify prints an Integral as mpmath.quad; SymPy's own evalf of one
            # refines its precision for minutes
            va, vb = (complex(sp.lambdify(symbols, x, "mpmath")(*point)) for x in frozen)
        if abs(va - vb) > 1e-10 * max(1.0, abs(va), abs(vb)):
            where = f"{label}: " if label else ""
            return Outcome(
                False,
                "numeric (15 digits, one seeded point)",
                f"{where}Coulomb {_fmt(va)}, {law} {_fmt(vb)} at a seeded point",
            )
    same = compare(default, other, seed=seed, assume=v.assume, names=v.names)
    detail = same.detail.replace("printed", "Coulomb").replace("derived", law)
    return Outcome(same.equal, same.method, detail)


def check_row(row: Row) -> RowResult:
    """Compare every variant of ``row`` and derive its status, explanation and laws."""
    outcomes = tuple(
        compare(
            v.printed(),
            _derived(v, laws.default("friction")),
            seed=_seed(row.key, v.label),
            assume=v.assume,
            names=v.names,
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
    holding, details = [laws.default("friction")], []
    for law in laws.choices("friction")[1:]:
        found = [_same_for(v, law, _seed(row.key, v.label, law)) for v in row.variants if v.by_law]
        if all(f.equal for f in found):
            holding.append(law)
        else:
            details.append(f"{law}: {next(f.detail for f in found if not f.equal)}")
    return RowResult(
        row, outcomes, status, " ".join(notes), tuple(problems), tuple(holding), "; ".join(details)
    )
