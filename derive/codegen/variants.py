"""The implementations of a generated function: one per distinct option variant.

A `FunctionSpec`'s variants with equal expressions share one implementation
(`_variants`); each is printed, after common-subexpression elimination over all its
outputs together, as an unchecked numpy function (`_numpy_impl`), its scalar
``math`` twin for numba and the bound kernels (`_scalar_impl`, with the hoisted
roots of its parameters, `_prep_impl`), or an mpmath function (`_mp_impl`); `_table`
writes the ``{key: _support.Variant(...)}`` table the public function dispatches on
(`beltmdsm.derive.codegen.render`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy as sp

from ..model import PARAMETERS
from ..statespace import Quadratic
from .printers import Mpmath, NumPy, Scalar, atoms_of, hoisted_roots, lift_integrals, root_line
from .specs import FunctionSpec, NoVariant

_TABLE = {p.name: p for p in PARAMETERS}
_ORDER = {p.name: i for i, p in enumerate(PARAMETERS)}


# --------------------------------------------------------------------------- helpers


def _flat(returns, outputs):
    """Outputs as a flat list of expressions, plus the shape to rebuild."""
    if returns == "value":
        return [sp.sympify(outputs)], None
    if returns in ("tuple", "vector"):
        return [sp.sympify(e) for e in outputs], len(outputs)
    if returns == "matrix":
        M = sp.Matrix(outputs)
        return list(M), M.shape
    if returns in ("roots", "growth"):
        flat = []
        for quad in outputs:
            assert isinstance(quad, Quadratic)
            flat += [quad.p / 2, quad.q, quad.disc]
        return flat, len(outputs)
    if returns == "stable":
        return [sp.sympify(e) for e in outputs], len(outputs)
    raise ValueError(f"unknown returns kind {returns!r}")


def _combine(returns, out, flavor):
    """One output per point from the printed outputs: a value, the largest growth
    rate of the factors, or the Routh-Hurwitz verdict (every output positive).

    ``flavor`` is ``"numpy"``, ``"scalar"`` or ``"mp"``; a NaN wins the maximum in
    each, as in ``numpy.maximum``.
    """
    if returns == "value":
        return out[0]
    if returns == "stable":
        return (" & " if flavor == "numpy" else " and ").join(f"({o} > 0)" for o in out)
    if flavor == "numpy":
        return functools.reduce(lambda a, b: f"numpy.maximum({a}, {b})", out)
    if flavor == "mp":
        return f"max({', '.join(out)})"
    # scalar: `out` are names (see `_growth_lines`), each printed more than once
    return functools.reduce(lambda a, b: f"({a} if ({a} >= {b} or {a} != {a}) else {b})", out)


def _growth_lines(out, printer):
    """Name ``h, q, disc`` of each quadratic factor and select its growth rate.

    The selection is `Quadratic.largest_real_part` printed in symbols named after
    the lines, so every printer prints the one definition.
    Returns the lines and the names of the per-factor growth rates.
    """
    lines, names = [], []
    for k in range(len(out) // 3):
        h, q, d = (sp.Symbol(f"_{c}{k}", real=True) for c in "hqd")
        lines.append(f"{h}, {q}, {d} = {', '.join(out[3 * k : 3 * k + 3])}")
        lines.append(f"_g{k} = {printer.doprint(Quadratic.largest_real_part(h, q, d))}")
        names.append(f"_g{k}")
    return lines, names


def _impl_params(exprs, args, where):
    """Parameters an implementation takes, in table order.

    Raises
    ------
    ValueError
        Naming ``where`` (the function and variant), for a symbol that is neither a
        positional argument nor a parameter.
    """
    names = _free_names(tuple(exprs)) - {a.name for a in args}
    unknown = names - set(_ORDER)
    if unknown:
        raise ValueError(
            f"{where}: expressions use symbols that are neither arguments "
            f"({', '.join(a.name for a in args) or 'none'}) nor parameters: {sorted(unknown)}"
        )
    return sorted(names, key=_ORDER.__getitem__)


@functools.cache
def _free_names(exprs: tuple) -> frozenset:
    """The names of the free symbols of ``exprs``, found once per variant."""
    return frozenset().union(*map(_names_of, exprs))


@functools.cache
def _names_of(expr) -> frozenset:
    """The names of the free symbols of one expression, found once (SymPy's
    ``free_symbols`` walks the whole tree each time; an expression is an output of
    many variants, and of a function's docstring)."""
    return frozenset(s.name for s in expr.free_symbols)


def _doc_params(exprs, args):
    """Parameters a user may pass: those used, and those their defaults come from."""
    names = set(_impl_params(exprs, args, "docstring"))
    names |= {_TABLE[n].default_from for n in names if _TABLE[n].default_from}
    return sorted(names, key=_ORDER.__getitem__)


def _domain_of(symbol):
    """A positional argument's domain: the parameter table's, else its assumptions."""
    if symbol.name in _TABLE:
        return _TABLE[symbol.name].domain
    if symbol.is_positive:
        return "positive"
    return "nonnegative" if symbol.is_nonnegative else "real"


def _errstate(flat, body):
    """``body`` under ``numpy.errstate`` where the expressions have a Piecewise."""
    if not any(atoms_of(e, sp.Piecewise) for e in flat):
        return body
    # numpy evaluates every branch of a select (and a compiled kernel may evaluate
    # both sides of a branch): silence the unused ones.
    return ['with numpy.errstate(divide="ignore", invalid="ignore"):'] + [
        "    " + b.replace("\n", "\n    ") for b in body
    ]


def _indent(lines):
    return [("    " + line.replace("\n", "\n    ")).rstrip() for line in lines]


@functools.cache
def _eliminate(flat: tuple) -> tuple:
    """``sp.cse`` of ``flat``, once: the numpy, scalar and mpmath printings of a
    variant share it (it does not depend on the printer)."""
    return sp.cse(list(flat), symbols=sp.numbered_symbols("_x"), order="canonical")


def _cse(flat, printer):
    """Common subexpressions of ``flat`` as lines, and the reduced outputs.

    Quadratures come first, one statement each (`lift_integrals`).
    """
    lines, flat = lift_integrals(flat, printer)
    repl, reduced = _eliminate(tuple(flat))
    return lines + [f"{sym} = {printer.doprint(e)}" for sym, e in repl], reduced


# --------------------------------------------------------------------------- variants


@dataclass
class _Variant:
    """One implementation of a function: the option keys that share it, its names."""

    fn: FunctionSpec
    keys: list
    outputs: object

    @property
    def key(self):
        return self.keys[0]

    @property
    def impl(self):
        if not self.fn.options:
            return f"_{self.fn.name}__impl"
        return f"_{self.fn.name}__{'__'.join(map(str, self.key))}"

    @functools.cached_property
    def flat(self):
        return _flat(self.fn.returns, self.outputs)[0]

    @functools.cached_property
    def shape(self):
        return _flat(self.fn.returns, self.outputs)[1]

    @functools.cached_property
    def params(self):
        return _impl_params(self.flat, self.fn.args, f"{self.fn.name}{self.key}")

    @functools.cached_property
    def roots(self):
        return hoisted_roots(self.flat, self.fn.args)

    @property
    def has_scalar(self):
        return self.fn.accelerate or self.fn.bind

    @property
    def prep(self):
        return f"{self.impl}__roots" if self.roots and self.has_scalar else None


def _variants(fn):
    """The implementations of ``fn``: variants with equal outputs share one, refusals none.

    Returns
    -------
    variants : list of _Variant
    refused : dict
        Key -> `NoVariant`.
    """
    shared, refused = {}, {}
    for key, outputs in fn.variants.items():
        if isinstance(outputs, NoVariant):
            refused[key] = outputs
            continue
        flat, shape = _flat(fn.returns, outputs)
        same = shared.get((tuple(flat), shape))
        if same is None:
            shared[(tuple(flat), shape)] = _Variant(fn, [key], outputs)
        else:
            same.keys.append(key)
    return list(shared.values()), refused


def _numpy_impl(v):
    """The unchecked numpy implementation of one variant.

    An accelerated function's implementation is its array kernel (roots as inputs,
    one output per point, shaped by the caller); the others take the broadcast
    shape first and compute their roots themselves.
    """
    fn, args = v.fn, [a.name for a in v.fn.args]
    roots = v.roots
    printer = NumPy(roots)
    if fn.accelerate:
        sig = args + v.params + [r for r, _, _ in roots]
        extra = ", ".join(f"{r} = {base}**(1/{d})" for r, base, d in roots) or "none"
        doc = [
            f'"""numpy kernel of `{fn.name}` (``_support.blockwise``).',
            "",
            f"Extra arguments: {extra}.",
            '"""',
        ]
        lines, reduced = _cse(v.flat, printer)
        out = [
            f"numpy.copy({e.name})" if e.is_Symbol and e.name in sig else printer.doprint(e)
            for e in reduced
        ]
        if fn.returns == "growth":
            more, out = _growth_lines(out, printer)
            lines += more
        body = lines + [f"return {_combine(fn.returns, out, 'numpy')}"]
        return "\n".join(
            [f"def {v.impl}({', '.join(sig)}):"] + _indent(doc) + _indent(_errstate(v.flat, body))
        )
    body = [root_line(r, base, d, printer) for r, base, d in roots]
    lines, reduced = _cse(v.flat, printer)
    body += lines
    inputs = set(args) | set(v.params)
    # An output that is an input unchanged is copied: the caller's array must not
    # come back as (an alias of) a result.
    out = [
        f"numpy.copy({e.name})" if e.is_Symbol and e.name in inputs else printer.doprint(e)
        for e in reduced
    ]
    body += _assemble(fn.returns, out, v.shape, mp=False)
    sig = ["_shape"] + args + v.params
    return "\n".join([f"def {v.impl}({', '.join(sig)}):"] + _indent(_errstate(v.flat, body)))


@functools.cache
def _branches(flat: tuple):
    """``((condition, outputs), ...)`` where every Piecewise of ``flat`` has one condition list.

    Then a scalar implementation evaluates only the branch it takes: common
    subexpressions of the other branches (a square root of a negative number, a
    division by zero at critical damping) are never computed, where Python and
    mpmath would raise. None where the Piecewise terms differ in their conditions
    (those implementations guard their branches themselves, e.g. ``max(X2, 0)``).
    Cached: the scalar and mpmath printings of a variant split it alike.
    """
    pieces = {p for e in flat for p in atoms_of(e, sp.Piecewise)}
    conditions = {tuple(c for _, c in p.args) for p in pieces}
    if len(conditions) != 1:
        return None
    (conds,) = conditions
    out = []
    for i, cond in enumerate(conds):
        branch = list(flat)
        while any(e.has(sp.Piecewise) for e in branch):
            branch = [
                e.replace(lambda x: isinstance(x, sp.Piecewise), lambda x, i=i: x.args[i].expr)
                for e in branch
            ]
        out.append((cond, tuple(branch)))
    return tuple(out)


def _branched_body(flat, printer, finish):
    """Source lines: CSE per branch of `_branches` (or over all), then ``finish(out)``."""
    branches = _branches(tuple(flat))
    if branches is None:
        lines, reduced = _cse(flat, printer)
        return lines + finish([printer.doprint(e) for e in reduced])
    body = []
    for k, (cond, outputs) in enumerate(branches):
        lines, reduced = _cse(outputs, printer)
        inner = _indent(lines + finish([printer.doprint(e) for e in reduced]))
        if cond is sp.true:
            body += (["else:"] if k else []) + (inner if k else [line[4:] for line in inner])
        else:
            body += [f"{'if' if k == 0 else 'elif'} {printer.doprint(cond)}:"] + inner
    return body


def _mp_impl(v):
    fn, args = v.fn, [a.name for a in v.fn.args]
    printer = Mpmath()
    body = _branched_body(v.flat, printer, lambda out: _assemble(fn.returns, out, v.shape, mp=True))
    return "\n".join([f"def {v.impl}({', '.join(args + v.params)}):"] + _indent(body))


def _scalar_impl(v):
    """The scalar ``math`` twin of a variant: for numba (ufunc or njit) and bound kernels."""
    fn, args = v.fn, [a.name for a in v.fn.args]
    roots = v.roots
    printer = Scalar(roots)
    sig = args + v.params + [r for r, _, _ in roots]

    def finish(out):
        if fn.returns == "growth":
            more, names = _growth_lines(out, printer)
            return more + [f"return {_combine(fn.returns, names, 'scalar')}"]
        if fn.returns in _KERNEL_RESULT:
            return [f"return {_combine(fn.returns, out, 'scalar')}"]
        return [f"return {out[0] if fn.returns == 'value' else '(' + ', '.join(out) + ',)'}"]

    body = _branched_body(v.flat, printer, finish)
    extra = ", ".join(f"{r} = {base}**(1/{d})" for r, base, d in roots) or "none"
    doc = [
        f'"""Scalar kernel of `{fn.name}` (``_support.compiled``, ``_support.Bound``).',
        "",
        f"Extra arguments: {extra}.",
        '"""',
    ]
    return "\n".join([f"def {v.impl}__scalar({', '.join(sig)}):"] + _indent(doc) + _indent(body))


def _prep_impl(v):
    """``impl__roots(params) -> roots``: the hoisted roots of a variant's parameters."""
    printer = NumPy()
    lines = [f"    {root_line(r, base, d, printer)}" for r, base, d in v.roots]
    names = ", ".join(r for r, _, _ in v.roots)
    return "\n".join([f"def {v.prep}({', '.join(v.params)}):"] + lines + [f"    return ({names},)"])


def _assemble(returns, out, shape, mp):
    if returns in _KERNEL_RESULT:
        lines = []
        if returns == "growth":
            lines, out = _growth_lines(out, Mpmath() if mp else NumPy())
        if mp:
            one = _combine(returns, out, "mp")
            return lines + [f"return bool({one})" if returns == "stable" else f"return {one}"]
        return lines + [f"return _support.full(_shape, {_combine(returns, out, 'numpy')})"]
    if returns == "tuple":
        items = ", ".join(out)
        return [f"return ({items},)" if mp else f"return _support.tuple_of(_shape, {items})"]
    if returns == "vector":
        items = ", ".join(out)
        return [f"return [{items}]" if mp else f"return _support.vector(_shape, [{items}])"]
    if returns == "matrix":
        n, m = shape
        rows = ["[" + ", ".join(out[i * m : (i + 1) * m]) + "]" for i in range(n)]
        joined = (",\n" + " " * 8).join(rows)
        if mp:
            return [f"return mpmath.matrix([\n        {joined},\n    ])"]
        return [f"return _support.matrix(_shape, [\n        {joined},\n    ])"]
    if returns == "roots":
        fn = "_support.mp_quadratic_roots" if mp else "_support.quadratic_roots"
        calls = [f"{fn}({out[3 * k]}, {out[3 * k + 1]}, {out[3 * k + 2]})" for k in range(shape)]
        lines = [f"_r{k} = {c}" for k, c in enumerate(calls)]
        items = ", ".join(f"*_r{k}" for k in range(shape))
        if mp:
            return lines + [f"return [{items}]"]
        return lines + [f"return _support.vector(_shape, [{items}])"]
    raise ValueError(returns)


_KERNEL_RESULT = {"value": "float64", "growth": "float64", "stable": "boolean"}


def _table(fn, variants, refused, mp):
    """``_NAME = {key: _support.Variant(...)}``: what the public function dispatches on.

    Keys in the order of ``fn.variants``; a refused key maps to ``_support.NoVariant``.
    """
    entries = {}
    for v in variants:
        names = "(" + "".join(f"{n!r}, " for n in v.params) + ")"
        parts = [v.impl, names]
        if not mp and v.has_scalar:
            parts += [f"{v.impl}__scalar", v.prep or "None"]
        for key in v.keys:
            entries[key] = f"_support.Variant({', '.join(parts)})"
    for key, refusal in refused.items():
        entries[key] = f"_support.NoVariant({refusal.reason!r})"
    rows = [f"    {key!r}: {entries[key]}," for key in fn.variants]
    return f"_{fn.name.upper()} = {{\n" + "\n".join(rows) + "\n}"
