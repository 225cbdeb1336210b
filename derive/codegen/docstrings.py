"""The docstrings of a generated function and of its ``bind_<name>`` twin (numpydoc).

Parameters from the parameter table (description, unit per contact law, domain,
default, the laws that own it), options, the ``Raises`` section with the reasons of
every refused variant.
"""

from __future__ import annotations

import textwrap

from .. import laws
from ..units import contact_units
from .specs import NoVariant
from .variants import _TABLE, _doc_params, _flat


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
        if not isinstance(outs, NoVariant)
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
    return [(key, v.reason) for key, v in fn.variants.items() if isinstance(v, NoVariant)]


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
    if fn.bind_examples:
        doc += ["", "Examples", "--------"] + fn.bind_examples.strip("\n").split("\n")
    return _quote(doc)
