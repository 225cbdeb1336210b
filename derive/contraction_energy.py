"""The energy of the difference of two tangential motions under one normal motion.

Steps 1-3 of the contraction argument (derive/contraction.py, its docstring has the
whole argument): `one_way_coupling` (one normal motion serves both runs),
`difference_energy` and `difference_power` (``E_d`` and its rate along the two
motions), `power_split` (``dE_d/dt = -c1 e'^2 - (f_a - f_b) F e'``, proved by
expansion) and `stick_is_set_valued` (the stick mode is ``Sgn`` at ``Vr = 0``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import dynamics, hybrid, laws
from .model import (
    CONTACT_LAWS,
    TENSION_LAWS,
    X1,
    Y1,
    Y2,
    P,
    contact_force,
    friction_coefficient,
    rest_coefficient,
    static_coefficient,
)

__all__ = [
    "Xa",
    "Ya",
    "Xb",
    "Yb",
    "sa",
    "sb",
    "e",
    "ep",
    "PowerSplit",
    "one_way_coupling",
    "difference_energy",
    "tangential_acceleration",
    "difference_power",
    "power_split",
    "stick_is_set_valued",
]

#: The tangential states of the two runs and their friction directions (elements of Sgn).
Xa, Ya, Xb, Yb = sp.symbols("X1_a Y1_a X1_b Y1_b", real=True)
sa, sb = sp.symbols("s_a s_b", real=True)
#: The difference ``e = X1_a - X1_b`` and its rate ``e'``.
e, ep = sp.symbols("e e_dot", real=True)
_FRICTION, _CONTACT, _TENSION = (laws.default(o) for o in laws.OPTIONS)


def _run(expr, X, Y):
    return sp.sympify(expr).xreplace({X1: X, Y1: Y})


def one_way_coupling() -> dict[tuple[str, str], bool]:
    """Whether the normal equation is free of the tangential state, per (contact, tension).

    `beltmdsm.derive.dynamics.normal_rhs` is ``(X2', Y2')`` of Eq. (4) with loss of contact; a
    True means SymPy finds neither ``X1`` nor ``Y1`` among its free symbols.
    """
    return {
        (c, tn): dynamics.normal_rhs(c, tn).free_symbols.isdisjoint({X1, Y1})
        for c in CONTACT_LAWS
        for tn in TENSION_LAWS
    }


@cache
def difference_energy() -> sp.Expr:
    """``E_d(e, e')``: the tangential part of the mechanical energy at the difference.

    The mechanical energy of `beltmdsm.derive.dynamics.energy` (per unit mass, Eq. 4) splits
    into a tangential part in ``(X1, Y1)`` and a normal part; the tangential part,
    evaluated at ``(e, e')``, is ``e'^2/2 + omega1^2 e^2/2``.

    Raises
    ------
    RuntimeError
        If the energy does not split (the tangential part depends on the normal state).
    """
    E = dynamics.energy()
    tangential = sp.expand(E - E.xreplace({X1: 0, Y1: 0}))
    if not tangential.free_symbols.isdisjoint({dynamics.X2r, Y2}):
        raise RuntimeError(f"the energy does not split: {tangential}")
    return tangential.xreplace({X1: e, Y1: ep})


def tangential_acceleration(
    contact: str = _CONTACT,
    tension: str = _TENSION,
    X=X1,
    Y=Y1,
    s=sa,
    friction: str = _FRICTION,
) -> sp.Expr:
    """``X1''`` of Eq. (4) in contact for the tangential state ``(X, Y)`` and direction ``s``.

    `beltmdsm.derive.dynamics.accelerations` with ``direction=s``; ``s`` is any element of
    ``Sgn(Y - Vb)`` (in stick ``s = a_free / (mu(0) F)``, `stick_is_set_valued`).
    """
    acc = dynamics.accelerations(contact, direction=s, tension=tension, friction=friction)
    return _run(acc[0], X, Y)


@cache
def difference_power(
    contact: str = _CONTACT, tension: str = _TENSION, friction: str = _FRICTION
) -> sp.Expr:
    """``dE_d/dt`` along two motions under one normal motion, by the chain rule.

    ``dE_d/dt = dE_d/de e' + dE_d/de' e''`` with ``e' = Y1_a - Y1_b`` and ``e''`` the
    difference of `tangential_acceleration` of run ``a`` (direction ``s_a``) and run
    ``b`` (``s_b``) at the same ``t, X2, X2'``. An expression in ``X1_a, Y1_a, X1_b,
    Y1_b, s_a, s_b``, the normal state and the parameters.
    """
    Ed = difference_energy()
    de = Ya - Yb
    dde = tangential_acceleration(contact, tension, Xa, Ya, sa, friction) - tangential_acceleration(
        contact, tension, Xb, Yb, sb, friction
    )
    rate = sp.diff(Ed, e) * de + sp.diff(Ed, ep) * dde
    return rate.xreplace({e: Xa - Xb, ep: de})


@dataclass(frozen=True)
class PowerSplit:
    """``dE_d/dt = viscous + friction``, and whether SymPy proved the identity.

    ``c1`` is ``-d a_free / d X1'`` of `beltmdsm.derive.dynamics.free_acceleration`; ``force`` the
    contact force of the tension law (`beltmdsm.derive.model.contact_force`);
    ``friction = friction_factor * force``.
    """

    total: sp.Expr
    c1: sp.Expr
    force: sp.Expr
    viscous: sp.Expr
    friction_factor: sp.Expr
    friction: sp.Expr
    exact: bool


@cache
def power_split(
    contact: str = _CONTACT, tension: str = _TENSION, friction: str = _FRICTION
) -> PowerSplit:
    """Split `difference_power` into the dashpot's and the friction's part.

    ``viscous = -c1 e'^2``, ``friction = -(f_a - f_b) F e'`` with ``f`` the signed
    coefficient of the friction law on each run (``mu_s s`` for Eq. 3);
    ``exact`` is True when ``total - viscous - friction`` expands to zero.
    """
    total = difference_power(contact, tension, friction)
    c1 = -sp.diff(dynamics.free_acceleration(), Y1)
    F = contact_force(contact, tension)
    de = Ya - Yb
    viscous = -c1 * de**2
    f_a = _run(friction_coefficient(friction, sa), Xa, Ya)
    f_b = _run(friction_coefficient(friction, sb), Xb, Yb)
    factor = -(f_a - f_b) * de
    friction = factor * F
    exact = sp.expand(total - viscous - friction) == 0
    return PowerSplit(total, c1, F, viscous, factor, friction, bool(exact))


def stick_is_set_valued(contact: str = _CONTACT, friction: str = _FRICTION) -> bool:
    """Whether the stick mode is the slip field at ``Vr = 0`` with ``s = a_free / (mu_st F)``.

    `beltmdsm.derive.hybrid.field_of_mode`: the ``Y1'`` entry of the ``slip_forward`` field at
    ``X1' = Vb`` with its friction ``mu(0) F`` replaced by ``s mu_st F`` (``mu_st`` the
    static bound, `beltmdsm.derive.model.static_coefficient`; ``mu(0)`` the slip law's value at
    rest) equals the stick field's ``0`` at that ``s``. The stick guard
    ``mu_st F -+ a_free >= 0`` (`beltmdsm.derive.hybrid.surfaces`) is ``-1 <= s <= 1``.
    """
    at_rest = {Y1: P["Vb"]}
    slip = hybrid.field_of_mode("slip_forward", contact, friction)[1].subs(at_rest)
    stick = hybrid.field_of_mode("stick", contact, friction)[1]
    F = hybrid.contact_force_in_contact(contact)
    a_free = dynamics.free_acceleration().subs(at_rest)
    mu, rest = static_coefficient(friction), rest_coefficient(friction)
    # the slip friction mu(0+) F of direction +1 replaced by the set's value s mu_st F
    with_s = slip + rest * F - mu * sa * F
    return bool(sp.simplify(with_s.xreplace({sa: a_free / (mu * F)}) - stick) == 0)
