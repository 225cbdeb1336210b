"""A registered model's equations of motion, derived from its entry, mode by mode.

From an `Oscillator` entry and a friction law of the registry, with ``q`` the
coordinates, ``v = q'`` their rates and ``y`` the state (the entry's order):

* the generalized forces without friction, ``Q0 = -C v - K q + Q(q, v, t) + excitation
  + Q_n`` (``Q_n = -N e_k`` for a unilateral contact on the penetration ``q_k``, with
  the contact law's force ``N`` taken at ``max(q_k, 0)`` so that it vanishes, with its
  stiffness, out of contact; zero for a bilateral one, whose normal force only presses
  the friction);
* the accelerations of each mode, ``q'' = M^-1 (Q0 + d F_f)``: slip in either
  direction ``s = sgn(v_r)`` with ``F_f = -mu(s v_r) s N`` (the law's coefficient at the
  speed ``s v_r = |v_r|`` on its side, continued smoothly past ``v_r = 0``); stick with
  ``F_f = lambda``, the holding force; flight (unilateral only) with ``N = 0``;
* the **holding force** ``lambda``: the Lagrange multiplier of the constraint
  ``v_r = 0``. It is solved by SymPy from the constraint's time derivative along the
  stick field, ``d v_r / dt = w . M^-1 (Q0 + d lambda) = 0``, not typed: for the paper's
  model it comes out as ``-a_free`` (derive/hybrid.py's stick cone), for Hoffmann's
  model it couples both coordinates through ``M^-1``;
* the static limit ``mu_st N`` (the law's static bound, else ``mu(0)``), within which
  stick holds (``|lambda| <= mu_st N``).

`System` holds these expressions; `system` derives them once per model and law.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from .. import laws
from ..lawcheck import _ASSUMPTIONS
from ..model import t
from .entry import NORMAL, Oscillator

__all__ = ["MODES", "System", "symbols", "system", "model_parameters", "defaults"]

#: Mode codes (the contract's): slip with v_r > 0, slip with v_r < 0, stick, flight.
MODES = {"slip_forward": 1, "slip_back": -1, "stick": 0, "flight": 2}
#: The holding force, before it is solved for.
_LAMBDA = sp.Symbol("lambda_h", real=True)


def _symbol(row) -> sp.Symbol:
    return sp.Symbol(row.name, **_ASSUMPTIONS[row.domain])


def symbols(entry: Oscillator) -> dict[str, sp.Symbol]:
    """Parameter symbols by name: the table's (for the laws), then the model's own."""
    P = {row.name: _symbol(row) for row in laws.parameter_table()}
    P.update({row.name: _symbol(row) for row in entry.parameters})
    return P


def _law_symbols(friction: str, P) -> set[sp.Symbol]:
    law = laws.get("friction", friction)
    s = sp.Symbol("speed", nonnegative=True)
    found = sp.sympify(law.coefficient(P, s)).free_symbols - {s}
    if law.static is not None:
        found |= sp.sympify(law.static(P)).free_symbols
    return found


def model_parameters(entry: Oscillator) -> tuple:
    """The model's parameter rows: the entry's, then those its contact law uses."""
    rows = list(entry.parameters)
    if entry.contact.unilateral:
        P = symbols(entry)
        k = sp.Symbol("k_", real=True)
        used = sp.sympify(laws.get("contact", entry.contact.law).force(P, k, k)).free_symbols
        names = {s.name for s in used} - {r.name for r in rows}
        rows += [r for r in laws.parameter_table() if r.name in names]
    return tuple(rows)


def law_parameters(entry: Oscillator, friction: str) -> tuple:
    """The parameter rows the friction law adds to the model's (table order)."""
    own = {r.name for r in model_parameters(entry)}
    names = {s.name for s in _law_symbols(friction, symbols(entry))} - own
    return tuple(r for r in laws.parameter_table() if r.name in names)


def defaults(rows) -> dict[str, float]:
    """A default for every row: its base value, else that of the row it defaults to
    (the paper's per-direction excitation), else 0 (a phase)."""
    table = {r.name: r for r in (*laws.parameter_table(), *rows)}
    out = {}
    for r in rows:
        base = r.base
        if base is None and r.default_from is not None:
            base = table[r.default_from].base
        out[r.name] = float(base if base is not None else 0.0)
    return out


@dataclass(frozen=True, eq=False)
class System:
    """The derived equations of one model under one friction law (module docstring).

    ``q``, ``v``: coordinate and rate symbols; ``state``: the state in the entry's
    order; ``params``: the parameter symbols in the order of the generated ``p``;
    ``fields``: mode code -> vector field (state order); ``holding``: the holding force;
    ``slip``: ``v_r``; ``normal``: ``N``; ``friction``: mode code -> friction force;
    ``limit``: ``mu_st N``; ``gap``: ``-q_k`` (unilateral) or None; ``unforced``: the
    substitution that switches the excitation off.
    """

    entry: Oscillator
    friction_law: str
    P: dict
    q: tuple
    v: tuple
    state: tuple
    params: tuple
    M: sp.Matrix
    fields: dict
    holding: sp.Expr
    slip: sp.Expr
    normal: sp.Expr
    friction: dict
    limit: sp.Expr
    gap: sp.Expr | None
    unforced: dict


def _vector(entry, mapping, what) -> sp.Matrix:
    mapping = mapping or {}
    stray = sorted(set(mapping) - set(entry.coordinates))
    if stray:
        raise ValueError(f"{what}: {stray} are not coordinates {entry.coordinates}")
    return sp.Matrix([sp.sympify(mapping.get(c, 0)) for c in entry.coordinates])


def _matrix(entry, build, P, fill) -> sp.Matrix:
    n = len(entry.coordinates)
    return sp.Matrix(build(P)) if build is not None else fill(n)


def _excitation(entry, P, target) -> sp.Expr:
    return sp.Add(
        *[
            x.sign * P[x.amplitude] * P[x.frequency] ** 2 * sp.sin(P[x.frequency] * t + P[x.phase])
            for x in entry.excitation
            if x.target == target
        ]
    )


@cache
def system(entry: Oscillator, friction: str) -> System:
    """Derive the model's equations under the friction law ``friction`` (cached)."""
    P = symbols(entry)
    names = dict(zip(entry.coordinates, entry.rate_names))
    q = {c: sp.Symbol(c, real=True) for c in entry.coordinates}
    v = {c: sp.Symbol(names[c], real=True) for c in entry.coordinates}
    by_name = {**{c: q[c] for c in q}, **{names[c]: v[c] for c in v}}
    state = tuple(by_name[s] for s in entry.state_names)
    qv, vv = sp.Matrix(list(q.values())), sp.Matrix(list(v.values()))
    contact = entry.contact
    law = laws.get("friction", friction)

    n = len(q)
    if entry.accelerations is not None:
        M = sp.eye(n)
        smooth = _vector(entry, entry.accelerations(P, q, v, t), "accelerations")
    else:
        M = _matrix(entry, entry.mass, P, sp.eye)
        C = _matrix(entry, entry.damping, P, sp.zeros)
        K = _matrix(entry, entry.stiffness, P, sp.zeros)
        extra = _vector(entry, entry.forces(P, q, v, t) if entry.forces else None, "forces")
        for name, X in (("mass", M), ("damping", C), ("stiffness", K)):
            if X.shape != (n, n):
                raise ValueError(f"{name}: a {n} x {n} matrix is needed; got {X.shape}")
        if M.det() == 0:
            raise ValueError("mass: the matrix is singular")
        smooth = -C * vv - K * qv + extra
    smooth += sp.Matrix([_excitation(entry, P, c) for c in entry.coordinates])

    if contact.unilateral:
        k = entry.coordinates.index(contact.normal)
        N = laws.get("contact", contact.law).force(P, sp.Max(q[contact.normal], 0), vv[k])
        push = sp.Matrix([-1 if i == k else 0 for i in range(len(q))])
        gap = -q[contact.normal]
    else:
        N = sp.sympify(contact.normal(P, q, v, t)) + _excitation(entry, P, NORMAL)
        push = sp.zeros(len(q), 1)
        gap = None
    w = _vector(entry, contact.slip(P), "contact.slip")
    d = _vector(entry, contact.direction(P), "contact.direction") if contact.direction else w
    vr = (w.T * vv)[0] - P["Vb"]
    Minv = M.inv() if not M.is_diagonal() else sp.diag(*[1 / M[i, i] for i in range(M.rows)])

    def field(acc):
        rate_of = {q[c]: v[c] for c in q}
        rate_of.update(zip(v.values(), acc))
        return sp.Matrix([rate_of[s] for s in state])

    friction_of = {}
    fields = {}
    for s in (1, -1):
        F = -sp.sympify(law.coefficient(P, s * vr)) * s * N
        friction_of[s] = F
        fields[s] = field(Minv * (smooth + push * N + d * F))
    # stick: the holding force is the multiplier that keeps v_r = 0, from d v_r / dt = 0
    acc = Minv * (smooth + push * N + d * _LAMBDA)
    rate = sp.diff(vr, t) + sum(sp.diff(vr, x) * f for x, f in zip(state, field(acc)))
    solved = sp.solve(rate, _LAMBDA)
    if len(solved) != 1:
        raise ValueError(
            "contact.direction: friction along it does not move the slip velocity "
            "(w . M^-1 d = 0), so no holding force keeps v_r = 0"
        )
    (holding,) = solved
    friction_of[0] = holding
    fields[0] = field(acc.subs(_LAMBDA, holding))
    if contact.unilateral:
        friction_of[2] = sp.Integer(0)
        fields[2] = field(Minv * smooth)
    static = law.static(P) if law.static is not None else law.coefficient(P, sp.Integer(0))
    rows = model_parameters(entry) + law_parameters(entry, friction)
    unforced = {P[x.amplitude]: 0 for x in entry.excitation}
    return System(
        entry,
        friction,
        P,
        tuple(q.values()),
        tuple(v.values()),
        state,
        tuple(P[r.name] for r in rows),
        M,
        fields,
        holding,
        vr,
        N,
        friction_of,
        sp.sympify(static) * N,
        gap,
        unforced,
    )
