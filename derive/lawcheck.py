"""What a law may not contain: the cheap structural check `beltmdsm.derive.laws.register` runs.

The derivation takes a law as an expression in its arguments and the parameter table.
A law that the framework cannot take is refused when it is registered, in one line
naming the law and the construct (`UnsupportedLaw`, a ``ValueError``), instead of a
SymPy traceback minutes into ``python -m derive``:

* an internal state (LuGre's bristle deflection ``z``), as an undefined function such as
  ``Function("z")(t)``, a symbol or a name of ``P`` that is neither an argument of the
  law nor a parameter of the table: laws with internal state are not supported yet
  (the model's state is ``(X1, X1', X2, X2')``), and a parameter the law forgot to
  declare is one of its ``Parameter`` rows;
* a friction law whose value at rest ``mu(0)``, its limit as ``s -> 0+``
  (`value_at_rest`), is not finite (Dieterich-Ruina's steady state ``mu_0 + (a - b)
  ln(s/V0)``): the stick cone at ``Vr = 0`` needs it;
* a static bound (``static``) that is not an expression of the parameters alone, or
  names a parameter that neither the table nor the law declares;
* the sign of the sliding speed (``sign(s)``, ``Heaviside(s)``, ``DiracDelta(s)``):
  ``s = |Vr| >= 0``, and the framework applies the direction itself
  (``-mu(|Vr|) sgn(Vr) F``), with the stick cone at ``Vr = 0``; SymPy differentiates
  ``sign`` into ``DiracDelta``, which no printer has;
* a function that one of the printers of the generated code (numpy, ``math`` for the
  scalar kernels, mpmath) lacks, in the law or in its derivative.

The check is structural: a law it accepts may still have no closed form for some
derived quantity, which the budgets of `beltmdsm.derive.budget` turn into a quadrature or a
numeric root.
"""

from __future__ import annotations

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.pycode import MpmathPrinter, PythonCodePrinter

__all__ = ["UnsupportedLaw", "check", "value_at_rest"]

#: Assumptions of the parameter symbols (as `beltmdsm.derive.model.P` makes them).
_ASSUMPTIONS = {
    "positive": {"positive": True},
    "nonnegative": {"nonnegative": True},
    "real": {"real": True},
}
#: Constructs of the sliding speed's sign, which the framework applies.
_SIGNS = (sp.sign, sp.Heaviside, sp.DiracDelta)
_HINT = "s = |Vr| >= 0 and the framework applies the direction: write mu(s) for s >= 0"
#: What a name that is no parameter may be, and what to do about either.
_STATE = (
    "laws with internal state (LuGre's bristle deflection) are not supported yet, the "
    "model's state is X1, X1', X2, X2'; a parameter of the law is declared in its "
    "Parameter rows"
)


class UnsupportedLaw(ValueError):
    """A law the framework cannot take: one line naming the law and the construct."""


def value_at_rest(mu: sp.Expr, s: sp.Symbol) -> sp.Expr:
    """``mu(0)``: the limit of ``mu(s)`` as ``s -> 0+`` (a removable singularity such as
    ``tanh(s/v)/(s/v)``'s has its value there, which substituting ``s = 0`` would miss)."""
    at = mu.subs(s, 0)
    if at.is_finite and not at.has(sp.nan, sp.zoo):
        return at
    return sp.limit(mu, s, 0, "+")


def _arguments(option: str, law):
    """The law's arguments as symbols, and its expression(s) built from them."""
    if option == "friction":
        s = sp.Symbol("speed", nonnegative=True)
        return (s,), law.coefficient, ("P", s)
    if option == "contact":
        X2, Y2 = sp.Symbol("X2", positive=True), sp.Symbol("Y2", real=True)
        return (X2, Y2), law.force, ("P", X2, Y2)
    F = sp.Symbol("F", real=True)
    return (F,), law.acting, (F,)


def _expression(name: str, what: str, build, call, P) -> sp.Expr:
    """``build(*call)`` with ``P`` for ``"P"``, refused where it names no parameter."""
    lead = f"{name}: " + (f"its {what}: " if what else "")
    try:
        expr = sp.sympify(build(*[P if a == "P" else a for a in call]))
    except KeyError as err:
        raise UnsupportedLaw(
            f"{lead}P[{err.args[0]!r}] is neither a parameter of the table nor one "
            f"of the law's own ({_STATE})"
        ) from None
    if not isinstance(expr, sp.Expr):
        raise UnsupportedLaw(f"{lead}{expr!r} is not an expression")
    undefined = sorted(map(str, expr.atoms(AppliedUndef)))
    if undefined:
        raise UnsupportedLaw(f"{lead}undefined function {undefined[0]} ({_STATE})")
    return expr


def _foreign(name: str, what: str, expr: sp.Expr, allowed) -> None:
    foreign = sorted(map(str, expr.free_symbols - set(allowed)))
    if foreign:
        lead = f"{name}: " + (f"its {what}: " if what else "")
        raise UnsupportedLaw(
            f"{lead}symbol {foreign[0]} is neither an argument of the law nor a "
            f"parameter ({_STATE})"
        )


def _printable(name: str, forms) -> None:
    for form in forms:
        for printer in (NumPyPrinter, PythonCodePrinter, MpmathPrinter):
            try:
                printer({"strict": True}).doprint(form)
            except Exception as err:  # noqa: BLE001 (the printers' refusals vary)
                what = str(err).splitlines()[0] if str(err) else type(err).__name__
                raise UnsupportedLaw(
                    f"{name}: {what} (the generated code prints it for numpy, math and mpmath)"
                ) from None


def check(option: str, law, table) -> None:
    """Refuse ``law`` (of ``option``) if its expression has a construct the framework lacks.

    Parameters
    ----------
    option : {"friction", "contact", "tension"}
    law : beltmdsm.derive.laws.Law
    table : tuple of Parameter
        The parameter table the law may use (the model's, the registered laws' and its own).

    Raises
    ------
    UnsupportedLaw
        Naming the law and the construct.
    """
    name = f"{option} law {law.name!r}"
    P = {p.name: sp.Symbol(p.name, **_ASSUMPTIONS[p.domain]) for p in table}
    args, build, call = _arguments(option, law)
    if build is None:
        raise UnsupportedLaw(f"{name}: no expression (the {option} law's function is missing)")
    expr = _expression(name, "", build, call, P)
    _foreign(name, "", expr, (*P.values(), *args))
    forms = [expr, *(sp.diff(expr, a) for a in args)]
    if option == "friction":
        (s,) = args
        signs = [e for e in expr.atoms(*_SIGNS) if s in e.free_symbols]
        if signs:
            shown = sorted(str(e.subs(s, sp.Symbol("s"))) for e in signs)
            raise UnsupportedLaw(f"{name}: {shown[0]} ({_HINT})")
        rest = value_at_rest(expr, s)
        if rest.is_finite is not True or rest.has(sp.Limit, sp.nan, sp.zoo):
            raise UnsupportedLaw(
                f"{name}: its value at rest, the limit of mu(s) as s -> 0+, is "
                f"{sp.sstr(rest)}, not finite: the stick cone at Vr = 0 needs a finite mu(0)"
            )
        if law.static is not None:
            static = _expression(name, "static bound", law.static, ("P",), P)
            _foreign(name, "static bound", static, P.values())
            if static.is_finite is False or static.has(sp.oo, -sp.oo, sp.zoo, sp.nan):
                raise UnsupportedLaw(f"{name}: its static bound {sp.sstr(static)} is not finite")
            forms.append(static)
    _printable(name, forms)
