"""generated/models/<name>.py: a registered model's numeric module, and its mpmath twin
generated/mp/models/<name>.py (the same expressions, `beltmdsm.derive.models.flavours`).

One module per model, plain ``math`` and numpy (no SymPy), deterministic text: every
kernel is printed by the scalar printer of `beltmdsm.derive.codegen.printers` after
common-subexpression elimination over all its outputs together (canonical order), one
implementation per friction law and a `Kernels` tuple of them (``kernels(friction)``).
Every kernel takes ``(t, state, params)`` (and a mode): ``state`` in the order of
``STATES``, ``params`` in the order of ``PARAMETERS[friction]``. ``__init__.py`` lists
the models (``MODELS``, the default first) and loads one (``load``).
"""

from __future__ import annotations

import functools
import pprint
import textwrap

import sympy as sp

from .. import laws
from ..codegen.files import HEADER
from . import hybrid as hy
from .flavours import MPMATH, NUMPY
from .linearity import linear_slip
from .registry import MODELS
from .steady import NUMERIC, coefficient_symbols, hurwitz, steady
from .system import MODES, defaults, law_parameters, model_parameters, system

__all__ = ["render_model", "render_entry", "render_init", "files", "KERNELS", "PAPER_PIECES"]

#: The kernels of every model, in the order of the `Kernels` tuple.
KERNELS = (
    "field",
    "jacobian",
    "slip_velocity",
    "slip_gradient",
    "slip_acceleration",
    "normal_force",
    "friction_force",
    "holding_force",
    "stick_limit",
    "gap",
    "surfaces",
    "surface_rates",
    "saltation",
    "equilibrium",
    "characteristic",
    "hurwitz",
)
#: The paper's own pieces, derived in derive/ for the paper's model only.
PAPER_PIECES = {
    "cubic_fit": "the cubic fit of the contact force (Eqs. 16-17, derive/fit.py)",
    "mdsm": "the MDSM split into fast and slow motions (Eqs. 13-21, derive/mdsm.py)",
    "correlation": "the consistent MDSM's correlation averages (derive/correlation.py)",
    "paper_check": "the check of the paper's claims (derive/paper_check/)",
}

_FAILED = f"equilibrium did not converge: {NUMERIC}"
_IMPORTS = "import math  # noqa: F401 (the kernels')\nfrom typing import NamedTuple\n\nimport numpy"
_MP_IMPORTS = "from typing import NamedTuple\n\nimport mpmath"


def _unpack(exprs, s, fl=NUMPY) -> list[str]:
    """Lines binding the states and parameters the expressions use, by index."""
    free = set().union(*[sp.sympify(e).free_symbols for e in exprs]) if exprs else set()
    lines = ["t = mpmath.mpf(t)"] if fl.uses_time(exprs) else []
    lines += [f"{x.name} = {fl.read(f'state[{i}]')}" for i, x in enumerate(s.state) if x in free]
    lines += [f"{x.name} = {fl.read(f'params[{i}]')}" for i, x in enumerate(s.params) if x in free]
    return lines


def _cse(exprs, prefix):
    """Common subexpressions of the outputs together (canonical order): one pass, shared
    by both flavours' printing."""
    return _cse_cached(tuple(sp.sympify(e) for e in exprs), prefix)


@functools.cache
def _cse_cached(exprs, prefix):
    return sp.cse(list(exprs), symbols=sp.numbered_symbols(prefix), order="canonical")


def _body(exprs, shape, prefix="_x", fl=NUMPY) -> list[str]:
    """CSE of the outputs together, then ``return`` of a number, a vector or a matrix."""
    repl, red = _cse(exprs, prefix)
    lines = [f"{x} = {fl.printer.doprint(e)}" for x, e in repl]
    out = [fl.number(e) for e in red]
    if shape is None:
        lines.append(f"return {out[0]}")
    elif isinstance(shape, int):
        lines.append(fl.vector(out))
    else:
        r, c = shape
        lines.append(fl.matrix([out[i * c : (i + 1) * c] for i in range(r)]))
    return lines


def _indent(lines, n=1):
    pad = "    " * n
    return [(pad + line.replace("\n", "\n" + pad)).rstrip() for line in lines]


def _function(name, signature, doc, cases, shape, s, fail, fl=NUMPY):
    """A function whose body picks one case by a condition (``None``: the only case)."""
    lines = [f"def {name}({signature}):", f'    """{doc}"""']
    for condition, exprs in cases:
        flat = list(exprs) if shape is not None else [exprs]
        body = _unpack(flat, s, fl) + _body(flat, shape, fl=fl)
        if condition is None:
            lines += _indent(body)
        else:
            lines += [f"    if {condition}:"] + _indent(body, 2)
    if fail:
        lines.append(f"    raise ValueError({fail!r})")
    return "\n".join(lines)


def _modes_of(s):
    return sorted(s.fields, key=lambda m: (m != 1, m != -1, m != 0, m))


def _kernels(s, law, fl=NUMPY) -> tuple[list[str], dict[str, str]]:
    """The functions of one friction law, and the kernel name -> function name."""
    tag = f"__{law}"
    n2 = len(s.state)
    modes = _modes_of(s)
    bad_mode = f"mode must be one of {tuple(modes)}"
    sig, sig_m = "t, state, params", "t, state, params, mode"
    surf = hy.surfaces(s)
    grad = [hy.d(s.slip, x) for x in s.state]
    out, names = [], {}

    def add(kernel, args):
        out.append(_function(*args, fl=fl))
        names[kernel] = f"_{kernel}{tag}"

    def per_mode(build):
        return [(f"mode == {m}", build(m)) for m in modes]

    add(
        "field",
        (
            f"_field{tag}",
            sig_m,
            "The vector field of ``mode``.",
            per_mode(lambda m: s.fields[m]),
            n2,
            s,
            bad_mode,
        ),
    )
    add(
        "jacobian",
        (
            f"_jacobian{tag}",
            sig_m,
            "d field / d state of ``mode``.",
            per_mode(lambda m: hy.jacobian(s, m)),
            (n2, n2),
            s,
            bad_mode,
        ),
    )
    add(
        "slip_velocity",
        (f"_slip_velocity{tag}", sig, "v_r = w . q' - Vb.", [(None, s.slip)], None, s, None),
    )
    add(
        "slip_gradient",
        (f"_slip_gradient{tag}", sig, "d v_r / d state.", [(None, grad)], n2, s, None),
    )
    add(
        "slip_acceleration",
        (
            f"_slip_acceleration{tag}",
            sig_m,
            "d v_r / dt along the field of ``mode``.",
            per_mode(lambda m: hy.rate(s, s.slip, m)),
            None,
            s,
            bad_mode,
        ),
    )
    add(
        "normal_force",
        (f"_normal_force{tag}", sig, "The normal force N.", [(None, s.normal)], None, s, None),
    )
    add(
        "friction_force",
        (
            f"_friction_force{tag}",
            sig_m,
            "Friction along the friction direction: the law times N slipping, the holding "
            "force sticking, 0 in flight.",
            per_mode(lambda m: s.friction[m]),
            None,
            s,
            bad_mode,
        ),
    )
    add(
        "holding_force",
        (
            f"_holding_force{tag}",
            sig,
            "The derived Lagrange multiplier that keeps d v_r / dt = 0 (stick).",
            [(None, s.holding)],
            None,
            s,
            None,
        ),
    )
    add(
        "stick_limit",
        (f"_stick_limit{tag}", sig, "The static limit mu_st N.", [(None, s.limit)], None, s, None),
    )
    if s.gap is not None:
        add(
            "gap",
            (f"_gap{tag}", sig, "-q_k: positive in flight.", [(None, s.gap)], None, s, None),
        )
    add(
        "surfaces",
        (
            f"_surfaces{tag}",
            sig,
            "The switching functions (SURFACES).",
            [(None, list(surf.values()))],
            len(surf),
            s,
            None,
        ),
    )
    add(
        "surface_rates",
        (
            f"_surface_rates{tag}",
            sig_m,
            "dh/dt of the switching functions (SURFACES) along the field of ``mode``.",
            per_mode(lambda m: [hy.rate(s, h, m) for h in surf.values()]),
            len(surf),
            s,
            bad_mode,
        ),
    )
    pairs = hy.switches(s)
    add(
        "saltation",
        (
            f"_saltation{tag}",
            "t, state, params, mode_before, mode_after",
            "I + (f+ - f-) n^T / (n^T f-) of the switch across its surface (SWITCHES).",
            [
                (f"mode_before == {b} and mode_after == {a}", hy.saltation(s, b, a))
                for (b, a) in pairs
            ],
            (n2, n2),
            s,
            f"no switch between these modes; the switches are {tuple(pairs)}",
        ),
    )
    out.extend(_steady(s, tag, fl))
    for k in ("equilibrium", "characteristic", "hurwitz"):
        names[k] = f"_{k}{tag}"
    return out, names


def _q_line(s, rows=None):
    """Bind the coordinates from ``state`` (the equilibrium's) by their names."""
    return [f"{x.name} = state[{s.state.index(x)}]" for x in s.q]


def _steady(s, tag, fl=NUMPY) -> list[str]:
    st = steady(s)
    n2 = len(s.state)
    out = []
    if st.solution is not None:
        values = [st.solution.get(x, sp.Integer(0)) for x in s.state]
        lines = [
            f"def _equilibrium{tag}(params):",
            '    """Steady sliding (q\' = 0, mode -1, unforced): the closed form."""',
        ]
        lines += _indent(_unpack(values, s, fl) + _body(values, n2, fl=fl))
        out.append("\n".join(lines))
    else:
        res = list(st.residual)
        jac = st.residual_jacobian
        q_of = {x: f"q[{i}]" for i, x in enumerate(s.q)}
        # one assignment: a coordinate named ``q`` must not shadow ``q`` before all are read
        names = ", ".join(x.name for x in s.q)
        bind = [f"{names}, = ({', '.join(fl.read(q_of[x]) for x in s.q)},)"]
        for name, exprs, shape in (
            ("_residual", res, len(res)),
            ("_residual_jacobian", jac, jac.shape),
        ):
            flat = list(exprs)
            lines = [f"def {name}{tag}(q, params):", '    """M q\'\' at rest (numeric path)."""']
            lines += _indent(
                bind
                + [ln for ln in _unpack(flat, s, fl) if "state[" not in ln]
                + _body(flat, shape, fl=fl)
            )
            out.append("\n".join(lines))
        start = [1.0 if s.gap is not None and x == -s.gap else 0.0 for x in s.q]
        idx = [s.state.index(x) for x in s.q]
        out.append(
            _mp_newton(s, tag, start, idx)
            if fl.mp
            else "\n".join(
                [
                    f"def _equilibrium{tag}(params):",
                    f'    """Steady sliding by the {NUMERIC}."""',
                    f"    q = numpy.array({tuple(start)!r}, dtype=numpy.float64)",
                    "    for _ in range(60):",
                    f"        jac = _residual_jacobian{tag}(q, params)",
                    f"        step = numpy.linalg.solve(jac, _residual{tag}(q, params))",
                    "        q = q - step",
                    "        scale = 1.0 + numpy.max(numpy.abs(q))",
                    "        if numpy.max(numpy.abs(step)) <= 1e-14 * scale:",
                    "            break",
                    "    else:",
                    f"        raise ArithmeticError({_FAILED!r})",
                    f"    state = numpy.zeros({n2})",
                    f"    state[numpy.array({idx!r})] = q",
                    "    return state",
                ]
            )
        )
    # characteristic: equilibrium -> entries of J0 -> coefficients
    entries = list(st.entries.items())
    lines = [
        f"def _characteristic{tag}(params):",
        '    """1, a_1 .. a_m of det(lambda I - J0) at steady sliding."""',
        f"    state = _equilibrium{tag}(params)",
    ]
    values = [e for _, e in entries]
    body = _unpack(values, s, fl)
    repl, red = _cse(values, "_x")
    body += [f"{x} = {fl.printer.doprint(e)}" for x, e in repl]
    body += [f"{sym.name} = {fl.number(e)}" for (sym, _), e in zip(entries, red)]
    body += _body(st.coefficients, len(st.coefficients), prefix="_c", fl=fl)
    lines += _indent(body)
    out.append("\n".join(lines))
    out.append(
        "\n".join(
            [
                f"def _hurwitz{tag}(params):",
                '    """Hurwitz determinants H_1 .. H_m of the characteristic coefficients."""',
                f"    return _hurwitz_{n2}(_characteristic{tag}(params))",
            ]
        )
    )
    return out


def _mp_newton(s, tag, start, idx) -> str:
    """The mpmath twin's numeric path: ``mpmath.findroot`` (Newton with the derived
    Jacobian) at the working precision, from the numpy path's start; ArithmeticError
    naming the path where it does not converge."""
    n = len(s.q)
    names = ", ".join(f"q{i}" for i in range(n))
    lines = [
        f"def _equilibrium{tag}(params):",
        f'    """Steady sliding by the {NUMERIC} (mpmath.findroot at mpmath.mp.dps)."""',
        f"    def residual({names}):",
        f"        return _residual{tag}(({names},), params)",
        "",
        f"    def jacobian({names}):",
        f"        return _residual_jacobian{tag}(({names},), params)",
        "",
        "    try:",
        f"        q = mpmath.findroot(residual, {list(start)!r}, J=jacobian, maxsteps=60)",
        "    except ValueError:",
        f"        raise ArithmeticError({_FAILED!r}) from None",
        "    q = q if isinstance(q, mpmath.matrix) else mpmath.matrix([q])",
        f"    state = [mpmath.mpf(0)] * {len(s.state)}",
    ]
    lines += [f"    state[{j}] = q[{i}]" for i, j in enumerate(idx)]
    lines.append("    return state")
    return "\n".join(lines)


def _hurwitz_function(m, fl=NUMPY) -> str:
    a = coefficient_symbols(m)
    lines = [
        f"def _hurwitz_{m}(a):",
        f'    """H_1 .. H_{m} of lambda^{m} + a[1] lambda^{m - 1} + ... + a[{m}]."""',
    ]
    read = [f"{x.name} = {fl.read(f'a[{i + 1}]')}" for i, x in enumerate(a)]
    lines += _indent(read + _body(hurwitz(m), m, fl=fl))
    return "\n".join(lines)


def _literal(value) -> str:
    return pprint.pformat(value, width=88, sort_dicts=False)


def render_model(name: str, mp: bool = False) -> str:
    """The source text of generated/models/<name>.py (``mp``: generated/mp/models/<name>.py)."""
    return render_entry(MODELS[name], mp)


def render_entry(entry, mp: bool = False) -> str:
    """The source text of the module of ``entry``, registered or not (a check's); with
    ``mp``, of its mpmath twin."""
    fl = MPMATH if mp else NUMPY
    name = entry.name
    friction_laws = entry.friction_laws or laws.choices("friction")
    systems = {law: system(entry, law) for law in friction_laws}
    s0 = systems[friction_laws[0]]
    own = model_parameters(entry)
    params = {law: tuple(r.name for r in own + law_parameters(entry, law)) for law in friction_laws}
    rows = own + tuple(
        {r.name: r for law in friction_laws for r in law_parameters(entry, law)}.values()
    )
    excitation = tuple((x.target, x.amplitude, x.frequency, x.phase) for x in entry.excitation)
    absent = (
        {}
        if name == "paper"
        else {k: f"{v} is the paper's model's only" for k, v in PAPER_PIECES.items()}
    )
    unilateral = entry.contact.unilateral
    constants = (
        ("NAME", name, "The model's name in the registry."),
        ("SUMMARY", entry.summary, "One line."),
        ("COORDINATES", entry.coordinates, "The generalized coordinates q."),
        ("STATES", entry.state_names, "The state vector's names, in order."),
        (
            "STATE_UNITS",
            entry.state_units,
            "The unit of each state, in the order of STATES (a rate's: its coordinate's per s).",
        ),
        ("UNILATERAL", unilateral, "Whether flight (mode 2) exists."),
        ("FRICTION_LAWS", tuple(friction_laws), "The friction laws generated, the default first."),
        ("PARAMETERS", params, "Friction law -> names of params, in order."),
        ("DEFAULTS", defaults(rows), "A default value for every parameter."),
        ("UNITS", {r.name: r.unit for r in rows}, "The unit of every parameter."),
        ("DESCRIPTIONS", {r.name: r.description for r in rows}, "One line per parameter."),
        (
            "DOMAINS",
            {r.name: r.domain for r in rows},
            "The domain of every parameter (beltmdsm.generated.parameters.DOMAINS' names).",
        ),
        (
            "DEFAULT_FROM",
            {r.name: r.default_from for r in rows if r.default_from},
            "A parameter whose default is another's value, when that one is given.",
        ),
        ("EXCITATION", excitation, "(target, amplitude, frequency, phase) per term."),
        ("MODES", {k: v for k, v in MODES.items() if unilateral or v != 2}, "Mode codes."),
        ("SURFACES", tuple(hy.surfaces(s0)), "The switching functions of `surfaces`, in order."),
        ("SWITCHES", {k: v for k, v in hy.switches(s0).items()}, "(before, after) -> surface."),
        (
            "GUARDS",
            hy.guards(s0),
            "mode -> ((surface, crossing direction, target), ...): +1 rising, -1 falling.",
        ),
        ("DECIDE_SLIP", hy.DECIDE_SLIP, "Guard target: Filippov's rule at v_r = 0."),
        ("DECIDE_CONTACT", hy.DECIDE_CONTACT, "Guard target: entering contact."),
        (
            "EQUILIBRIUM",
            {law: steady(systems[law]).path for law in friction_laws},
            "How the equilibrium is computed, per friction law.",
        ),
        ("ABSENT", absent, "The paper's own pieces this model lacks, and why."),
        (
            "LINEAR_SLIP",
            {law: linear_slip(systems[law]) for law in friction_laws},
            "Friction law -> whether both slip modes' unforced fields are affine in the state.",
        ),
    )
    functions, tables = [], []
    for law in friction_laws:
        funcs, names = _kernels(systems[law], law, fl)
        functions += funcs
        fields = ", ".join(f"{k}={names.get(k, 'None')}" for k in KERNELS)
        tables.append(f"    {law!r}: Kernels({fields}),")
    twin = (
        f"mpmath variant (same names, arbitrary precision) of "
        f"``beltmdsm.generated.models.{name}``:\nevery kernel computes at ``mpmath.mp.dps`` "
        "digits (inputs converted to ``mpf``; vectors as\nlists, matrices as "
        "``mpmath.matrix``); the numeric equilibrium path by ``mpmath.findroot``.\n\n"
        if mp
        else ""
    )
    doc = (
        f'"""{twin}{entry.summary} (the model ``{name}``, derive/models/entries.py).\n\n'
        f"{_wrap(entry.doc)}\n\n"
        "Generated from its registry entry by derive/models/: "
        "``kernels(friction)`` gives\nthe model's functions under one friction law, "
        "each taking ``(t, state, params)`` (and a\nmode: 1 slip with v_r > 0, -1 slip "
        "with v_r < 0, 0 stick, 2 flight), ``state`` in the\norder of STATES, ``params`` "
        'in the order of PARAMETERS[friction].\n"""'
    )
    parts = [
        HEADER + doc,
        _MP_IMPORTS if mp else _IMPORTS,
        '__all__ = ["kernels", "Kernels"'
        + "".join(f", {c[0]!r}" for c in constants).replace("'", '"')
        + "]",
        "\n\n".join(
            f"#: {comment}\n{cname} = {_literal(value)}" for cname, value, comment in constants
        ),
        "class Kernels(NamedTuple):\n"
        '    """The functions of one friction law; ``gap`` is None '
        'where\n    the contact is bilateral."""\n\n'
        + "\n".join(f"    {k}: object" for k in KERNELS),
        _hurwitz_function(len(s0.state), fl),
        *functions,
        "#: Friction law -> its kernels.\n_KERNELS = {\n" + "\n".join(tables) + "\n}",
        "def kernels(friction):\n"
        '    """The `Kernels` of ``friction`` (a name of FRICTION_LAWS)."""\n'
        "    try:\n        return _KERNELS[friction]\n    except KeyError:\n"
        "        raise ValueError(\n"
        '            f"friction must be one of {FRICTION_LAWS}; got {friction!r}"\n'
        "        ) from None",
    ]
    return "\n\n\n".join(parts) + "\n"


def _wrap(text, width=88):
    return textwrap.fill(text, width)


def render_init(mp: bool = False) -> str:
    """generated/models/__init__.py (``mp``: generated/mp/models/__init__.py): ``MODELS``
    and ``load``."""
    what = "mpmath twins" if mp else "numeric modules"
    return (
        HEADER + f'"""The registered models\' {what} (derive/models/).\n\n'
        "``MODELS`` lists the models, the default (``paper``) first; ``load(name)`` imports "
        'one.\n"""\n\n'
        "import importlib\n\n"
        '__all__ = ["MODELS", "load"]\n\n'
        f"#: The registered models, the default first.\nMODELS = {tuple(MODELS)!r}\n\n\n"
        "def load(name):\n"
        '    """The module of the model ``name`` (one of MODELS)."""\n'
        "    if name not in MODELS:\n"
        '        raise ValueError(f"model must be one of {MODELS}; got {name!r}")\n'
        '    return importlib.import_module(f"{__name__}.{name}")\n'
    )


def files() -> dict[str, str]:
    """Every file of generated/models/ and generated/mp/models/, by path relative to
    generated/."""
    out = {"models/__init__.py": render_init(), "mp/models/__init__.py": render_init(mp=True)}
    for name in MODELS:
        out[f"models/{name}.py"] = render_model(name)
        out[f"mp/models/{name}.py"] = render_model(name, mp=True)
    return out
