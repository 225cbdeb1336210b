"""Printers: SymPy expressions as numpy, scalar ``math`` and mpmath source.

Three flavours of one expression tree: `NumPy` (array code, broadcasting), `Scalar`
(plain ``math`` code for the bound kernels and numba) and `Mpmath` (arbitrary
precision). On top of SymPy's printers they

* print the roots ``b**(n/d)`` through roots computed once (`hoisted_roots`) and
  half-integer powers through ``sqrt`` (`RootPrinting`);
* print a quadrature, ``Integral(f, (x, a, b))`` of a friction law whose fast average
  has no closed form (derive/averaging.py), as one statement per flavour
  (`Quadrature`): `beltmdsm.generated._support.quad` for numpy, an inline loop over the same
  nodes for the scalar kernels (numba compiles it), ``mpmath.quad`` for mpmath. The
  integrals are lifted out of the expressions before common-subexpression
  elimination (`lift_integrals`), which would otherwise move pieces of the
  integrand, in the integration variable, out of the integral.
"""

from __future__ import annotations

import functools

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.pycode import MpmathPrinter, PythonCodePrinter

__all__ = [
    "is_root",
    "hoisted_roots",
    "NumPy",
    "Scalar",
    "Mpmath",
    "root_line",
    "lift_integrals",
    "atoms_of",
]


def is_root(e):
    """``b**(n/d)`` with ``d >= 3`` and ``b`` proved nonnegative (see `hoisted_roots`)."""
    return e.is_Pow and e.exp.is_Rational and e.exp.q >= 3 and e.base.is_nonnegative is True


def _is_half_power(e):
    """``b**(n/2)``, ``|n| >= 3`` odd, with ``b`` proved nonnegative (printed through sqrt)."""
    return (
        e.is_Pow
        and e.exp.is_Rational
        and e.exp.q == 2
        and abs(e.exp.p) >= 3
        and e.base.is_nonnegative is True
    )


def hoisted_roots(flat, args=()):
    """The roots ``b**(1/d)``, ``d >= 3``, that a function computes once, up front.

    Why: numpy's ``power`` costs several times its ``cbrt`` plus a multiply, and
    ``g**(1/3)``, ``omega2**(4/3)``, ``omega2**(10/3)`` then share one root each; in a
    numba kernel a scalar ``cbrt`` or ``pow`` costs about 20 ns, so the kernels take
    the roots as inputs computed by numpy's vectorised functions (a bound kernel
    computes them once, when it is bound). Only bases SymPy proves nonnegative and
    free of the positional arguments qualify (for a negative base ``cbrt`` is not
    SymPy's principal root). Square roots stay in place: they are cheap everywhere.
    The expressions are not rewritten (a rebuilt tree would be re-evaluated by
    SymPy, which can turn ``Abs`` of a complex expression into another form);
    the printers print each such power through the roots (`RootPrinting`).

    Returns
    -------
    list of (name, base, d), in a canonical order.
    """
    return list(_roots(tuple(flat), tuple(args)))


@functools.cache
def atoms_of(expr, kind) -> frozenset:
    """``expr.atoms(kind)``, once per expression: one expression is an output of many
    variants and functions, and each walk of its tree costs as much as printing it."""
    return frozenset(expr.atoms(kind))


@functools.cache
def _roots(flat: tuple, args: tuple) -> tuple:
    """`hoisted_roots`, found once for every printing of ``flat``."""
    found = sorted(
        {
            (e.base, int(e.exp.q))
            for x in flat
            for e in atoms_of(x, sp.Pow)
            if is_root(e) and not (e.base.free_symbols & set(args))
        },
        key=lambda bd: (sp.default_sort_key(bd[0]), bd[1]),
    )
    return tuple((f"_root{k}", base, d) for k, (base, d) in enumerate(found))


@functools.cache
def _ordered_terms(expr, order) -> tuple:
    return tuple(expr.as_ordered_terms(order=order))


#: ``(printer class, its settings and hoisted roots, expression) -> text`` (`OrderedTerms`).
_PRINTED: dict = {}


class OrderedTerms:
    """The terms of a sum in SymPy's printing order, computed once per sum and order;
    and each expression's text, printed once per printer.

    Ordering a sum's terms (``Expr.as_ordered_terms``) is most of a printer's time, and
    one sum is printed many times: by the numpy, scalar and mpmath printers of a
    variant, and in every variant of a function that shares it. The order is a
    function of the sum alone, so the printed text is unchanged.

    Whole expressions recur as well (a 0 in every Jacobian, the growth rate's root
    selection in every variant, the lines variants share: seven printings in eight
    were repeats): ``doprint``'s text is a function of the printer's class, settings
    and hoisted roots and of the expression, and is kept. Not for an expression with a
    ``Float`` (equal Floats of different precisions print differently). SymPy's
    ``doprint`` also rewrites ``re(...)`` nodes by a ``replace`` that walks and
    rebuilds the whole tree: done only where there is one.
    """

    def doprint(self, expr, assign_to=None):
        if assign_to is not None or not isinstance(expr, sp.Basic) or expr.has(sp.Float):
            return super().doprint(expr, assign_to)
        key = (self._memo_key(), expr)
        text = _PRINTED.get(key)
        if text is None:
            text = _PRINTED[key] = super().doprint(expr)
        return text

    def _memo_key(self):
        if "_memo" not in self.__dict__:
            roots = frozenset(getattr(self, "roots", {}).items())
            self._memo = (type(self), repr(sorted(self._settings.items())), roots)
        return self._memo

    def _handle_UnevaluatedExpr(self, expr):
        # without an ``re`` node SymPy's replace returns the expression unchanged
        if isinstance(expr, sp.Basic) and not expr.has(sp.re):
            return expr
        return super()._handle_UnevaluatedExpr(expr)

    def _as_ordered_terms(self, expr, order=None):
        order = order or self.order
        if order in ("old", "none"):
            return super()._as_ordered_terms(expr, order=order)
        return list(_ordered_terms(expr, order))


class RootPrinting(OrderedTerms):
    """Print ``b**(n/d)`` as ``b**(n//d) * _rootk**(n % d)`` (reciprocal for ``n < 0``)."""

    def __init__(self, roots=()):
        super().__init__()
        self.roots = {(base, d): name for name, base, d in roots}

    def _print_Pow(self, expr, rational=False):
        if _is_half_power(expr):
            # b**(n/2) as b**(n//2) * sqrt(b): a square root and a product cost a
            # fraction of a power (in a kernel's inner loop, X2**(3/2) of Eq. 1)
            n = abs(int(expr.exp.p))
            base = self.parenthesize(expr.base, PRECEDENCE["Pow"], strict=False)
            root = self._print(sp.sqrt(expr.base, evaluate=False))
            whole = n // 2
            product = (
                root if not whole else f"({base if whole == 1 else f'{base}**{whole}'}*{root})"
            )
            return product if expr.exp > 0 else f"(1/{product})"
        name = self.roots.get((expr.base, int(expr.exp.q))) if is_root(expr) else None
        if name is None:
            return super()._print_Pow(expr, rational=rational)
        n, d = abs(int(expr.exp.p)), int(expr.exp.q)
        whole, part = divmod(n, d)
        base = self.parenthesize(expr.base, PRECEDENCE["Pow"], strict=False)
        factors = ([base if whole == 1 else f"{base}**{whole}"] if whole else []) + [
            name if part == 1 else f"{name}**{part}"
        ]
        product = "*".join(factors) if len(factors) == 1 else f"({'*'.join(factors)})"
        return product if expr.exp > 0 else f"(1/{product})"


def _limits(integral):
    ((x, lo, hi),) = integral.limits
    return x, lo, hi


class NumPy(RootPrinting, NumPyPrinter):
    def _print_Heaviside(self, expr):
        # The derivative of max(X2, 0): 0 out of contact, 1 in contact.
        return f"numpy.heaviside({self._print(expr.args[0])}, 0.0)"

    # SymPy prints And/Or as numpy.logical_and.reduce((a, b)), which stacks its
    # arguments and fails when they have different shapes: nest the binary ufuncs,
    # which broadcast.
    def _print_And(self, expr):
        return self._nested("numpy.logical_and", expr)

    def _print_Or(self, expr):
        return self._nested("numpy.logical_or", expr)

    def _nested(self, ufunc, expr):
        return functools.reduce(
            lambda a, b: f"{ufunc}({a}, {b})", (self._print(a) for a in expr.args)
        )

    def quadrature(self, name, integral):
        """``name = _support.quad(integrand, lo, hi, *its inputs)`` (broadcast over them)."""
        x, lo, hi = _limits(integral)
        inputs = sorted(s.name for s in integral.function.free_symbols - {x})
        body = NumPy().doprint(integral.function)  # no hoisted roots inside the lambda
        params = ", ".join([x.name] + inputs)
        tail = "".join(f", {n}" for n in inputs)
        return [
            f"{name} = _support.quad(lambda {params}: {body}, "
            f"{self.doprint(lo)}, {self.doprint(hi)}{tail})"
        ]


class Mpmath(OrderedTerms, MpmathPrinter):
    def _print_Heaviside(self, expr):
        return f"(1 if ({self._print(expr.args[0])}) > 0 else 0)"

    def quadrature(self, name, integral):
        """``name = mpmath.quad(integrand, [lo, hi])`` at the working precision."""
        x, lo, hi = _limits(integral)
        body = self.doprint(integral.function)
        return [
            f"{name} = mpmath.quad(lambda {x.name}: {body}, "
            f"[{self.doprint(lo)}, {self.doprint(hi)}])"
        ]


class Scalar(RootPrinting, PythonCodePrinter):
    """Scalar ``math`` code for the kernels (Piecewise as conditional expressions)."""

    def _print_Heaviside(self, expr):
        return f"(1.0 if ({self._print(expr.args[0])}) > 0 else 0.0)"

    def quadrature(self, name, integral):
        """The rule of `_support.quad` as an inline loop: numba compiles it with the kernel."""
        x, lo, hi = _limits(integral)
        body = Scalar().doprint(integral.function)
        return [
            f"{name}_m = {self.doprint((lo + hi) / 2)}",
            f"{name}_h = {self.doprint((hi - lo) / 2)}",
            f"{name} = 0.0",
            f"for {name}_k in range(_support.QUAD_NODES.shape[0]):\n"
            f"    {x.name} = {name}_m + {name}_h*_support.QUAD_NODES[{name}_k]\n"
            f"    {name} += _support.QUAD_WEIGHTS[{name}_k]*({body})",
            f"{name} = {name}*{name}_h",
        ]


def root_line(name, base, d, printer):
    arg = printer.doprint(base)
    value = f"numpy.cbrt({arg})" if d == 3 else f"numpy.power({arg}, 1/{d})"
    return f"{name} = {value}"


def lift_integrals(flat, printer):
    """``(lines, flat)``: each ``Integral`` in ``flat`` computed by a statement of its own.

    The integrals are replaced by the names of those statements, ``_quad0, _quad1,
    ...`` in a canonical order.
    """
    found, lifted = _integrals(tuple(flat))
    if not found:
        return [], flat
    lines = [line for name, i in found for line in printer.quadrature(name, i)]
    return lines, list(lifted)


@functools.cache
def _integrals(flat: tuple) -> tuple:
    """``((name, integral), ...)`` of `lift_integrals` and the outputs with the names in
    place, found once for the numpy, scalar and mpmath printings of ``flat``."""
    found = sorted({i for e in flat for i in atoms_of(e, sp.Integral)}, key=sp.default_sort_key)
    if not found:
        return (), flat
    names = {i: sp.Symbol(f"_quad{k}", real=True) for k, i in enumerate(found)}
    return tuple((names[i].name, i) for i in found), tuple(e.xreplace(names) for e in flat)
