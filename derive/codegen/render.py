"""Rendering: function specs to the source text of the generated modules.

A generated module is described by a `ModuleSpec` of `FunctionSpec` entries (built
in `beltmdsm.derive.modules`); `render` turns the specs into source text, deterministically
(common-subexpression elimination over all outputs of a function together,
canonical ordering, parameters in table order), `render_all` gives every file of
``generated/`` (`beltmdsm.derive.codegen.files` writes them). The implementations are
`beltmdsm.derive.codegen.variants`', the docstrings `beltmdsm.derive.codegen.docstrings`'.

The layers of a generated function (PyDy's generator / printer / wrapper):

* one unchecked implementation per distinct option variant
  (``_name__opt1__opt2``; variants with equal expressions share one): the printed
  expressions, positional arguments only;
* the public function: it picks the variant (``_support.choose``, which raises
  ``_support.Unsupported`` for a `NoVariant`), checks every argument once
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

import math
import pprint
import re
from pathlib import Path

import sympy as sp

from .. import laws
from ..model import PARAMETERS, rest_coefficient, static_coefficient
from ..parameters import DOMAINS as DOMAIN_RULES
from ..units import contact_units
from .docstrings import _bind_docstring, _docstring
from .files import HEADER
from .specs import ModuleSpec
from .variants import (
    _KERNEL_RESULT,
    _domain_of,
    _indent,
    _mp_impl,
    _numpy_impl,
    _prep_impl,
    _scalar_impl,
    _table,
    _variants,
)

__all__ = ["render", "render_all"]

TEMPLATES = Path(__file__).resolve().parent / "templates"


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
    shortfalls, involved = [], {}
    for c in with_static:
        excess = rest_coefficient(c) - static_coefficient(c)
        involved[c] = tuple(sorted(str(x) for x in excess.free_symbols))
        names = ", ".join(involved[c])
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
        "coefficient at rest exceeds that bound for given parameters, and\n"
        "``STATIC_PARAMETERS`` the parameters it depends on (a change of another one\n"
        "cannot change it).\n"
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
        f"STATIC_PARAMETERS = {_literal(involved)}\n"
        f"_SHORTFALL = {{\n{shortfall}\n}}\n"
        "\n"
        f"DOMAIN_RULES = {{{rules}}}\n"
        "\n\n"
        "def within(domain, x):\n"
        '    """Whether ``x`` (a number, or the least of an array) lies in ``domain``.\n'
        "\n"
        "    Examples\n"
        "    --------\n"
        "    mu_s may be 0 (nonnegative), omega1 may not (positive):\n"
        "\n"
        "    >>> from beltmdsm.generated.parameters import DOMAINS, within\n"
        '    >>> DOMAINS["mu_s"], DOMAINS["omega1"]\n'
        "    ('nonnegative', 'positive')\n"
        '    >>> within("nonnegative", 0.0), within("positive", 0.0)\n'
        "    (True, False)\n"
        '    """\n'
        "    bound, excluded, _ = DOMAIN_RULES[domain]\n"
        "    return x > bound if excluded else x >= bound\n"
        "\n\n"
        "def static_shortfall(friction, **params):\n"
        '    """The friction law\'s slip coefficient at rest minus its static bound\n'
        "    (``STATIC_BOUNDS``) at ``params``: positive where the stick cone would hold less\n"
        "    than slip does; 0 for a law without a static bound of its own.\n"
        "\n"
        "    Examples\n"
        "    --------\n"
        "    Static above kinetic with mu_k = 0.5 > mu_s = 0.4 slips harder than stick\n"
        "    holds, by mu_k - mu_s; Coulomb's law has no bound of its own:\n"
        "\n"
        "    >>> from beltmdsm.generated.parameters import BASE, static_shortfall\n"
        '    >>> round(float(static_shortfall("static_kinetic", **{**BASE, "mu_k": 0.5})), 4)\n'
        "    0.1\n"
        '    >>> float(static_shortfall("coulomb", **BASE))\n'
        "    0.0\n"
        '    """\n'
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
        # the runtime support, copied: `_support` and the modules it reaches
        **{path.name: HEADER + path.read_text() for path in sorted(TEMPLATES.glob("*.py"))},
    }
    for m in modules:
        files[f"{m.name}.py"] = render(m)
        if m.mp:
            files[f"mp/{m.name}.py"] = render(m, mp=True)
    return dict(sorted(files.items()))
