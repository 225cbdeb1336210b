"""Rendering: function specs to the source text of the generated modules.

A generated module is described by a `ModuleSpec` of `FunctionSpec` entries (built
in `beltmdsm.derive.modules`); `render` turns the specs into source text, deterministically
(common-subexpression elimination over all outputs of a function together,
canonical ordering, parameters in table order), `render_all` gives every file of
``generated/`` (`beltmdsm.derive.codegen.files` writes them).

The layers of a generated function (PyDy's generator / printer / wrapper):

* one unchecked implementation per distinct option variant
  (``_name__opt1__opt2``; variants with equal expressions share one): the printed
  expressions, positional arguments only;
* the public function: it picks the variant (``_support.choose``, which raises
  ``_support.Unsupported`` for a `Refusal`), checks every argument once
  (``_support.arguments``, ``_support.param``: ``ValueError`` naming the parameter
  for NaN, inf or a value outside its domain, ``TypeError`` for an unknown keyword
  or a missing parameter of the chosen law), and calls the implementation; the
  numpy variant broadcasts over arrays, the mpmath variant (same name in
  ``beltmdsm.generated.mp``) computes at ``mpmath.mp.dps``;
* for a spec with ``bind=True``, ``bind_<name>(options, **params)``: it checks the
  parameters once, as SciPy's ``check_arguments`` does, and returns a
  ``_support.Bound`` scalar kernel (plain ``math`` code; compiled by
  ``numba.njit`` when numba is installed) with the parameters bound, for the inner
  loops of the runtime;
* for a spec with ``accelerate=True`` (one output per point: ``growth_rate``,
  ``is_stable``), the numpy kernel runs on blocks of points
  (``_support.blockwise``) or its scalar twin as a numba ufunc (``backend=``).
"""

from __future__ import annotations

import functools
import math
import pprint
import re
import textwrap
from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from .. import laws
from ..model import PARAMETERS, rest_coefficient, static_coefficient
from ..parameters import DOMAINS as DOMAIN_RULES
from ..statespace import Quadratic
from ..units import contact_units
from .files import HEADER
from .printers import Mpmath, NumPy, Scalar, hoisted_roots, lift_integrals, root_line
from .specs import FunctionSpec, ModuleSpec, Refusal

__all__ = ["render", "render_all"]

TEMPLATES = Path(__file__).resolve().parent / "templates"

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
    names = {s.name for e in exprs for s in e.free_symbols} - {a.name for a in args}
    unknown = names - set(_ORDER)
    if unknown:
        raise ValueError(
            f"{where}: expressions use symbols that are neither arguments "
            f"({', '.join(a.name for a in args) or 'none'}) nor parameters: {sorted(unknown)}"
        )
    return sorted(names, key=_ORDER.__getitem__)


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
    if not any(e.has(sp.Piecewise) for e in flat):
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
        Key -> `Refusal`.
    """
    shared, refused = {}, {}
    for key, outputs in fn.variants.items():
        if isinstance(outputs, Refusal):
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


def _branches(flat):
    """``[(condition, outputs), ...]`` where every Piecewise of ``flat`` has one condition list.

    Then a scalar implementation evaluates only the branch it takes: common
    subexpressions of the other branches (a square root of a negative number, a
    division by zero at critical damping) are never computed, where Python and
    mpmath would raise. None where the Piecewise terms differ in their conditions
    (those implementations guard their branches themselves, e.g. ``max(X2, 0)``).
    """
    pieces = {p for e in flat for p in e.atoms(sp.Piecewise)}
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
        out.append((cond, branch))
    return out


def _branched_body(flat, printer, finish):
    """Source lines: CSE per branch of `_branches` (or over all), then ``finish(out)``."""
    branches = _branches(flat)
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

    Keys in the order of ``fn.variants``; a refused key maps to ``_support.Refused``.
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
        entries[key] = f"_support.Refused({refusal.reason!r})"
    rows = [f"    {key!r}: {entries[key]}," for key in fn.variants]
    return f"_{fn.name.upper()} = {{\n" + "\n".join(rows) + "\n}"


# --------------------------------------------------------------------------- docstrings


def _unit(p):
    """``[unit]``, or the unit under each contact law for a parameter whose unit it sets."""
    if not p.derived_unit:
        return f"[{p.unit}]"
    per_law = "; ".join(f"{c}: {contact_units(c)[p.name]}" for c in laws.choices("contact"))
    return f"[{per_law}]"


def _param_docs(params, kind):
    doc = []
    for n in params:
        p = _TABLE[n]
        default = ""
        if p.default_from:
            default = f", default: ``{p.default_from}``"
        elif n.startswith("phase"):
            default = f", default {p.base!r}"
        owner = ""
        if p.law:
            owner = " Only for " + " or ".join(f"{o}={c!r}" for o, c in laws.owners(n)) + "."
        text = f"{p.description} {_unit(p)}, {p.domain}{default}.{owner}"
        doc += [f"{n} : {kind}"] + ["    " + line for line in textwrap.wrap(text, 80)]
    return doc


def _option_docs(fn):
    doc = []
    for name, choices, default, what in fn.options:
        doc += [f"{name} : {choices}, default {default!r}"]
        doc += ["    " + line for line in textwrap.wrap(what, 80)]
    return doc


def _expressions(fn):
    """Every expression of every variant that is not refused."""
    return [
        e
        for outs in fn.variants.values()
        if not isinstance(outs, Refusal)
        for e in _flat(fn.returns, outs)[0]
    ]


def _docstring(fn, mp):
    exprs = _expressions(fn)
    params = _doc_params(exprs, fn.args)
    kind = "mpmath number" if mp else "array_like"
    doc = [fn.summary, "", f"Implements {fn.equations} of the paper."]
    if fn.notes:
        doc += [""] + textwrap.wrap(fn.notes, 84)
    if mp:
        doc += ["", "mpmath variant: scalar arguments, computed at ``mpmath.mp.dps`` digits."]
    doc += ["", "Parameters", "----------"]
    for a in fn.args:
        doc += [f"{a.name} : {kind}", f"    {fn.arg_docs.get(a.name, 'state variable')}"]
    doc += _param_docs(params, kind)
    doc += _option_docs(fn)
    if fn.vhat:
        doc += [
            'vhat_model : {"tangential", "coupled"}, optional',
            "    How ``Vhat`` is computed (``beltmdsm.generated.friction.vhat``) when it is not",
            '    passed; default "tangential". Passing both is an error.',
        ]
    if fn.accelerate and not mp:
        doc += [
            'backend : {"numpy", "numba"}, optional',
            "    numpy array operations, or a numba ufunc compiled from the same",
            "    expressions (one pass over the points; compiled on first use and",
            "    cached on disk). Default: numba if it is installed (the ``fast``",
            "    extra), else numpy. Both give the same results to rounding.",
        ]
    doc += [
        "**params",
        "    Any other model parameter (accepted and ignored); an unknown",
        "    name raises TypeError.",
        "",
        "Returns",
        "-------",
    ]
    doc += fn.returns_doc.strip("\n").split("\n")
    doc += _raises(fn.accelerate and not mp, _refusals(fn))
    if fn.examples and not mp:
        doc += ["", "Examples", "--------"] + fn.examples.strip("\n").split("\n")
    return _quote(doc)


def _refusals(fn):
    """The option values for which ``fn`` refuses, with their reasons."""
    return [(key, v.reason) for key, v in fn.variants.items() if isinstance(v, Refusal)]


def _raises(numba, refusals=()):
    doc = [
        "",
        "Raises",
        "------",
        "ValueError",
        "    If an input is NaN, infinite or outside its domain (the message names",
        "    it), or an option value is unknown.",
        "TypeError",
        "    If a keyword is not a model parameter, or a parameter is missing (also",
        "    a parameter of the chosen law).",
    ]
    if refusals:
        reasons = sorted({reason for _, reason in refusals})
        doc += [
            "_support.Unsupported",
            "    A ValueError, for a choice of laws without the property this needs:",
        ]
        doc += ["    " + line for r in reasons for line in textwrap.wrap("- " + r, 80)]
    if numba:
        doc += ["ImportError", '    For backend="numba" when numba is not installed.']
    return doc


def _quote(doc):
    body = "\n".join(("    " + line).rstrip() for line in doc)
    return f'    """{body.lstrip()}\n    """'


def _bind_docstring(fn):
    params = _doc_params(_expressions(fn), fn.args)
    args = ", ".join(a.name for a in fn.args)
    result = {
        "value": "a float",
        "tuple": "a tuple of floats",
        "vector": "a tuple of floats",
        "matrix": "the entries as a flat tuple, row by row",
    }[fn.returns]
    doc = [
        f"`{fn.name}` as a scalar kernel with the parameters checked once and bound.",
        "",
        f"``bind_{fn.name}(**params)({args})`` equals ``{fn.name}({args}, **params)``",
        f"for scalar inputs and returns {result}. For the inner loops of an",
        "integrator: the arguments are checked here, not on every call.",
        "",
        "Parameters",
        "----------",
    ]
    doc += _param_docs(params, "float")
    doc += _option_docs(fn)
    doc += [
        'backend : {"python", "numba"}, optional',
        "    The kernel as plain Python, or compiled by ``numba.njit`` (on first call;",
        "    cached on disk). Default: numba if it is installed, else python.",
        "**params",
        "    Any other model parameter (accepted and ignored).",
        "",
        "Returns",
        "-------",
        "_support.Bound",
        f"    Call it as ``kernel({args})``; ``.kernel`` and ``.args`` are the raw kernel",
        "    and the bound values, for a caller that compiles its own loop.",
    ]
    doc += _raises(True, _refusals(fn))
    return _quote(doc)


# --------------------------------------------------------------------------- functions


def _option_signature(fn, mp, extra=()):
    opts = [f"{n}={d!r}" for n, _, d, _ in fn.options]
    if fn.vhat:
        opts.append("vhat_model=None")
    opts += list(extra)
    pos = [a.name for a in fn.args]
    return ", ".join(pos + (["*"] + opts if opts else []) + ["**params"])


def _choose_call(fn, table_name, label):
    choose = "".join(f", {n}={n}" for n, *_ in fn.options)
    return f'_variant = _support.choose("{label}", {table_name}{choose})'


def _public(fn, mp):
    """The checked public function: choose the variant, check once, call it."""
    backend = ("backend=None",) if fn.accelerate and not mp else ()
    lines = [f"def {fn.name}({_option_signature(fn, mp, backend)}):", _docstring(fn, mp)]
    body = []
    if fn.vhat:
        # V_hat comes from the same laws as the rest of the function
        same = "".join(f", {n}={n}" for n, *_ in fn.options if n in laws.OPTIONS)
        body.append(
            f'params = _support.resolve_vhat("{fn.name}", params, vhat_model, _friction.vhat{same})'
        )
    body.append(_choose_call(fn, f"_{fn.name.upper()}", fn.name))
    check = "_support.mp_param" if mp else "_support.param"
    if mp:
        body.append(f'_values = _support.mp_arguments("{fn.name}", _variant.names, params)')
    else:
        body.append(f'_values, _extra = _support.arguments("{fn.name}", _variant.names, params)')
    for a in fn.args:
        domain, why = fn.arg_domains.get(a.name, (_domain_of(a), None))
        why_s = f", {why!r}" if why else ""
        body.append(f'{a.name} = {check}("{fn.name}", "{a.name}", {a.name}, "{domain}"{why_s})')
    args = "".join(f"{a.name}, " for a in fn.args)
    if mp:
        body.append(f"return _variant.impl({args}*_values)")
    elif fn.accelerate:
        body += [
            f"_shape = _support.shape_of({args}*_values, *_extra)",
            f"return _support.full(_shape, _support.evaluate(_variant, "
            f'"{_KERNEL_RESULT[fn.returns]}", backend, {args}*_values))',
        ]
    else:
        body += [
            f"_shape = _support.shape_of({args}*_values, *_extra)",
            f"return _variant.impl(_shape, {args}*_values)",
        ]
    return "\n".join(lines + _indent(body))


def _binder(fn):
    opts = "".join(f"{n}={d!r}, " for n, _, d, _ in fn.options)
    lines = [f"def bind_{fn.name}(*, {opts}backend=None, **params):", _bind_docstring(fn)]
    body = [
        _choose_call(fn, f"_{fn.name.upper()}", f"bind_{fn.name}"),
        f'return _support.bind("{fn.name}", _variant, params, backend)',
    ]
    return "\n".join(lines + _indent(body))


def _function(fn, mp):
    """Source chunks of one public function, its table and its implementations."""
    if fn.bind and fn.returns not in ("value", "tuple", "vector", "matrix"):
        raise ValueError(f"{fn.name}: bind needs returns in value/tuple/vector/matrix")
    if fn.accelerate and fn.returns not in _KERNEL_RESULT:
        raise ValueError(f"{fn.name}: no kernel for returns={fn.returns!r}")
    variants, refused = _variants(fn)
    chunks = [_public(fn, mp)]
    if fn.bind and not mp:
        chunks.append(_binder(fn))
    for v in variants:
        chunks.append(_mp_impl(v) if mp else _numpy_impl(v))
        if not mp and v.has_scalar:
            chunks.append(_scalar_impl(v))
            if v.prep:
                chunks.append(_prep_impl(v))
    chunks.append(_table(fn, variants, refused, mp))
    return chunks


def render(module: ModuleSpec, mp: bool = False) -> str:
    """Source text of one generated module (numpy, or mpmath with ``mp=True``)."""
    chunks = [c for fn in module.functions for c in _function(fn, mp)]
    code = "\n\n\n".join(chunks)
    imports = [
        name
        for name in ("functools", "math", "mpmath", "numpy")
        if re.search(rf"(?<![\w.]){name}\.", code)
    ]
    public = [fn.name for fn in module.functions]
    if not mp:
        public += [f"bind_{fn.name}" for fn in module.functions if fn.bind]
    public += [name for name, _, _ in module.constants]
    names = ", ".join(repr(n) for n in public)
    variant = (
        "mpmath variant (same names, arbitrary precision) of "
        f"``beltmdsm.generated.{module.name}``.\n\n"
        if mp
        else ""
    )
    doc = f'"""{variant}{module.doc.strip()}\n"""'
    # a module of data alone (the integrator's tableau) imports nothing
    support = None
    if module.functions:
        support = "from .. import _support" if mp else "from . import _support"
    if any(fn.vhat for fn in module.functions):
        support += "\nfrom . import friction as _friction"
    constants = "\n\n".join(
        f"#: {comment}\n{name} = {_literal(value)}" for name, value, comment in module.constants
    )
    parts = [
        HEADER + doc,
        "\n".join(f"import {i}" for i in imports) if imports else None,
        support,
        f"__all__ = [{names}]",
        constants or None,
    ]
    return "\n\n".join(p for p in parts if p) + "\n\n\n" + code + "\n"


def _literal(value) -> str:
    """``repr`` of plain data, laid out one item per line where it is long (deterministic)."""
    return pprint.pformat(value, width=96, sort_dicts=False)


def _parameters_module() -> str:
    """``generated/parameters.py``: the parameter table and the model options, as data."""
    default_units = contact_units(laws.default("contact"))
    rows = "\n".join(
        f"    dict(name={p.name!r}, unit={default_units.get(p.name, p.unit)!r}, "
        f"base={p.base!r}, domain={p.domain!r},\n"
        f"         description={p.description!r}, default_from={p.default_from!r},\n"
        f"         law={p.law!r}),"
        for p in PARAMETERS
    )
    options = "\n".join(
        f"{option.upper()}_LAWS = {laws.choices(option)!r}" for option in laws.OPTIONS
    )
    by_option = ", ".join(f"{o!r}: {o.upper()}_LAWS" for o in laws.OPTIONS)
    docs = {o: {c: laws.get(o, c).summary for c in laws.choices(o)} for o in laws.OPTIONS}
    owners = {
        (o, c): tuple(p.name for p in laws.get(o, c).parameters)
        for o in laws.OPTIONS
        for c in laws.choices(o)
    }
    units = {("contact", c): contact_units(c) for c in laws.choices("contact")}
    with_static = [c for c in laws.choices("friction") if laws.get("friction", c).static]
    static = {
        c: (sp.sstr(static_coefficient(c)), sp.sstr(rest_coefficient(c))) for c in with_static
    }
    shortfalls = []
    for c in with_static:
        excess = rest_coefficient(c) - static_coefficient(c)
        names = ", ".join(sorted(str(x) for x in excess.free_symbols))
        shortfalls.append(f"    {c!r}: lambda {names}, **_: {sp.pycode(excess)},")
    shortfall = "\n".join(shortfalls)
    rules = ", ".join(
        f"{name!r}: ({'-math.inf' if bound == -math.inf else repr(bound)}, {strict!r}, {text!r})"
        for name, (bound, strict, text) in DOMAIN_RULES.items()
    )
    return (
        HEADER
        + '"""The parameter table and the model options (derive/parameters.py, derive/laws.py).\n\n'
        "``PARAMETERS``: one dict per parameter (``law``: the ``(option, choice)`` of the\n"
        "first law that lists it, or None; ``LAW_PARAMETERS`` has every law that shares\n"
        "it); ``BASE``: the paper's base set (Fig. 2, with ``Vb = 4`` of\n"
        "Fig. 3) and every law's base values, so that ``**BASE`` serves every law;\n"
        "``KNOWN``: every accepted keyword; ``DEFAULT_FROM``: the parameter a\n"
        "per-direction one defaults to; ``DEFAULTS``: the values of the optional\n"
        "parameters (the phases).\n\n"
        "The options of the model's laws: ``OPTIONS`` (option -> its choices, the default\n"
        "first; the same tuples as ``FRICTION_LAWS``, ``CONTACT_LAWS``, ``TENSION_LAWS``,\n"
        "ready for ``typing.Literal[...]``), ``OPTION_DEFAULTS``, ``OPTION_DOCS`` (option ->\n"
        "choice -> one line), ``LAW_PARAMETERS`` ((option, choice) -> the law's own\n"
        "parameters) and ``LAW_UNITS`` ((option, choice) -> the units the law gives to\n"
        "parameters; ``PARAMETERS`` has those of the default contact law).\n"
        "``STATIC_BOUNDS``: friction law -> ``(static bound, slip coefficient at rest)``\n"
        "of the laws that bound stick by a static coefficient of their own\n"
        "(derive/laws.py, ``FrictionLaw.static``); ``static_shortfall`` how far the slip\n"
        "coefficient at rest exceeds that bound for given parameters.\n"
        "\n"
        "``DOMAIN_RULES``: each domain as (lower bound, bound excluded, the text of a\n"
        "failure); ``within(domain, x)`` applies it (NaN is never within).\n"
        '"""\n\n'
        "import math\n\n"
        f"PARAMETERS = (\n{rows}\n)\n\n"
        "BASE = {p['name']: p['base'] for p in PARAMETERS\n"
        "        if p['base'] is not None and p['default_from'] is None\n"
        "        and not p['name'].startswith('phase')}\n"
        "KNOWN = frozenset(p['name'] for p in PARAMETERS)\n"
        "DOMAINS = {p['name']: p['domain'] for p in PARAMETERS}\n"
        "DEFAULT_FROM = {p['name']: p['default_from'] for p in PARAMETERS\n"
        "                if p['default_from'] is not None}\n"
        "DEFAULTS = {p['name']: p['base'] for p in PARAMETERS if p['name'].startswith('phase')}\n"
        "\n"
        f"{options}\n"
        f"OPTIONS = {{{by_option}}}\n"
        f"OPTION_DEFAULTS = {_literal({o: laws.default(o) for o in laws.OPTIONS})}\n"
        f"OPTION_DOCS = {_literal(docs)}\n"
        f"LAW_PARAMETERS = {_literal(owners)}\n"
        f"LAW_UNITS = {_literal(units)}\n"
        f"STATIC_BOUNDS = {_literal(static)}\n"
        f"_SHORTFALL = {{\n{shortfall}\n}}\n"
        "\n"
        f"DOMAIN_RULES = {{{rules}}}\n"
        "\n\n"
        "def within(domain, x):\n"
        '    """Whether ``x`` (a number, or the least of an array) lies in ``domain``."""\n'
        "    bound, excluded, _ = DOMAIN_RULES[domain]\n"
        "    return x > bound if excluded else x >= bound\n"
        "\n\n"
        "def static_shortfall(friction, **params):\n"
        '    """The friction law\'s slip coefficient at rest minus its static bound\n'
        "    (``STATIC_BOUNDS``) at ``params``: positive where the stick cone would hold less\n"
        '    than slip does; 0 for a law without a static bound of its own."""\n'
        "    return _SHORTFALL[friction](**params) if friction in _SHORTFALL else 0.0\n"
    )


#: The package's refusal of any name but its own (beltmdsm/_layout.py).
_GUARD = """
if __name__ != "beltmdsm.generated":
    raise ImportError(
        f"generated/ is the package beltmdsm.generated: import it by that name, not as "
        f"{__name__!r} (a second name would load a second copy of every module)"
    )
"""


def render_all(modules) -> dict[str, str]:
    """Every file of ``generated/``: relative path -> text."""
    listing = "\n".join(f"* ``{m.name}``: {m.doc.strip().splitlines()[0]}" for m in modules)
    files = {
        "__init__.py": (
            HEADER + '"""Code-generated numeric modules (numpy; mpmath variants in '
            "``beltmdsm.generated.mp``).\n\n" + listing + "\n\nImporting them never "
            "imports SymPy. A source checkout keeps generated/ beside beltmdsm/ and an\n"
            "installed package inside it; either way it is imported as\n"
            "``beltmdsm.generated`` (beltmdsm/_layout.py). By another name it refuses: a\n"
            'second name would load a second copy of every module.\n"""\n' + _GUARD
        ),
        "mp/__init__.py": HEADER + '"""mpmath variants of the generated modules."""\n',
        "parameters.py": _parameters_module(),
        "_support.py": HEADER + (TEMPLATES / "_support.py").read_text(),
    }
    for m in modules:
        files[f"{m.name}.py"] = render(m)
        if m.mp:
            files[f"mp/{m.name}.py"] = render(m, mp=True)
    return dict(sorted(files.items()))
