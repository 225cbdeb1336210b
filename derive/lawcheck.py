"""What a law may not contain: the cheap structural check `beltmdsm.derive.laws.register` runs.

The derivation takes a law as an expression in its arguments and the parameter table.
A law that the framework cannot take is refused when it is registered, in one line
naming the law and the construct (`UnsupportedLaw`, a ``ValueError``), instead of a
SymPy traceback minutes into ``python -m derive``:

* an undefined function, such as ``Function("z")(t)``: an internal state (LuGre's
  bristle deflection) needs an equation of its own, and the model's state is
  ``(X1, X1', X2, X2')``;
* a symbol that is neither an argument of the law nor a parameter of the table
  (``t``, or a parameter the law forgot to declare);
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

__all__ = ["UnsupportedLaw", "check"]

#: Assumptions of the parameter symbols (as `beltmdsm.derive.model.P` makes them).
_ASSUMPTIONS = {
    "positive": {"positive": True},
    "nonnegative": {"nonnegative": True},
    "real": {"real": True},
}
#: Constructs of the sliding speed's sign, which the framework applies.
_SIGNS = (sp.sign, sp.Heaviside, sp.DiracDelta)
_HINT = "s = |Vr| >= 0 and the framework applies the direction: write mu(s) for s >= 0"


class UnsupportedLaw(ValueError):
    """A law the framework cannot take: one line naming the law and the construct."""


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
    try:
        expr = sp.sympify(build(*[P if a == "P" else a for a in call]))
    except KeyError as err:
        raise UnsupportedLaw(
            f"{name}: P[{err.args[0]!r}] is neither a parameter of the table nor one of "
            "the law's own (declare it as a Parameter of the law)"
        ) from None
    if not isinstance(expr, sp.Expr):
        raise UnsupportedLaw(f"{name}: its value {expr!r} is not an expression")
    undefined = sorted(map(str, expr.atoms(AppliedUndef)))
    if undefined:
        raise UnsupportedLaw(
            f"{name}: undefined function {undefined[0]} (an internal state, as LuGre's, needs "
            "an equation of its own; the model's state is X1, X1', X2, X2')"
        )
    foreign = sorted(map(str, expr.free_symbols - set(P.values()) - set(args)))
    if foreign:
        raise UnsupportedLaw(
            f"{name}: symbol {foreign[0]} is neither an argument of the law nor a parameter "
            "(declare it as a Parameter of the law)"
        )
    if option == "friction":
        (s,) = args
        signs = [e for e in expr.atoms(*_SIGNS) if s in e.free_symbols]
        if signs:
            shown = sorted(str(e.subs(s, sp.Symbol("s"))) for e in signs)
            raise UnsupportedLaw(f"{name}: {shown[0]} ({_HINT})")
    for form in (expr, *(sp.diff(expr, a) for a in args)):
        for printer in (NumPyPrinter, PythonCodePrinter, MpmathPrinter):
            try:
                printer({"strict": True}).doprint(form)
            except Exception as err:  # noqa: BLE001 (the printers' refusals vary)
                what = str(err).splitlines()[0] if str(err) else type(err).__name__
                raise UnsupportedLaw(
                    f"{name}: {what} (the generated code prints it for numpy, math and mpmath)"
                ) from None
