"""The sign of the friction's power on the difference of two motions.

Steps 4-6 of the contraction argument (derive/contraction.py, its docstring has the
whole argument): `friction_power_sign_cases` (``(s_a - s_b)(Vr_a - Vr_b) >= 0``: the
set-valued sign is monotone), `monotonicity` (whether a friction law beyond the sign
is non-decreasing in ``Vr``), `clipped_force_nonnegative` (``max(F, 0) >= 0``) and
`sign_of_friction_power` (the friction part of `beltmdsm.derive.contraction_energy.power_split`
never adds energy while the contact pushes).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import budget, laws
from .contraction_energy import Ya, Yb, ep, power_split, sa, sb
from .model import (
    SPEED,
    X2,
    Y2,
    P,
    coefficient,
    contact_force,
    friction_coefficient,
    normal_force,
    rest_coefficient,
    static_coefficient,
)

__all__ = [
    "STATES",
    "SignCase",
    "Monotonicity",
    "monotonicity",
    "friction_power_sign_cases",
    "clipped_force_nonnegative",
    "sign_of_friction_power",
]

#: The friction states of one run: the three parts of the graph of Sgn.
STATES = ("slip_back", "stick", "slip_forward")
_FRICTION, _CONTACT, _TENSION = (laws.default(o) for o in laws.OPTIONS)
#: The set-valued part of every friction law, mu(0) Sgn(Vr): the steps on the sign
#: (`friction_power_sign_cases`, `sign_of_friction_power`,
#: `beltmdsm.derive.contraction.breaking_conditions`) are derived for Coulomb's law, whose
#: mu(0) = mu_s stands for any nonnegative mu(0) (`monotonicity` checks mu(0) >= 0
#: of each law).
_SIGN_LAW = laws.default("friction")


@dataclass(frozen=True)
class Monotonicity:
    """Whether ``f(Vr) = sgn(Vr) mu(|Vr|)`` is non-decreasing, and where it is not.

    ``slope`` is ``d mu / d|Vr|``; ``holds`` is True when SymPy proves ``mu_st >= 0``
    (the static bound), ``mu(0) - mu_st >= 0`` (no falling jump from the stick cone to
    slip) and ``slope >= 0`` for every speed and every parameter value of the domain;
    otherwise ``falls`` says for which ``|Vr|`` (and under which condition on the
    parameters) the slope is negative, and ``reason`` is one line for the reports.
    """

    friction: str
    slope: sp.Expr
    holds: bool
    falls: str
    reason: str


def _inequality(expr: sp.Expr) -> str:
    """``expr < 0`` with the negative terms moved to the right: ``mu_k < mu_s``."""
    terms = sp.Add.make_args(sp.expand(expr))
    left = sp.Add(*(x for x in terms if not x.could_extract_minus_sign()))
    right = -sp.Add(*(x for x in terms if x.could_extract_minus_sign()))
    return f"{sp.sstr(left)} < {sp.sstr(right)}"


@cache
def monotonicity(friction: str = _FRICTION) -> Monotonicity:
    """Decide with SymPy whether the friction law is non-decreasing in ``Vr``.

    The set-valued sign is monotone (`friction_power_sign_cases`); ``sgn(Vr) mu(|Vr|)``
    is then non-decreasing exactly when its graph at ``Vr = 0``, ``[-mu_st, mu_st]``
    with the static bound ``mu_st >= 0``, lies below its value ``mu(0)`` just beyond
    (``mu(0) >= mu_st``: a static bound above the slip law's value at rest, as
    ``static_kinetic``'s ``mu_s > mu_k``, is a falling jump), and ``mu' >= 0`` at every
    speed. The slope is factored; factors SymPy proves positive or negative are
    dropped (with their sign), and what remains decides: a factor free of the speed
    gives a condition on the parameters under which the law falls at every
    ``|Vr| > 0`` (Stribeck's: ``mu_k < mu_s``); one that depends on the speed gives the
    speeds between the roots SymPy finds.
    """
    m0, rest = static_coefficient(friction), rest_coefficient(friction)
    slope = sp.diff(coefficient(friction, SPEED), SPEED)
    shown = slope.subs(SPEED, sp.Symbol("|Vr|", nonnegative=True))
    if m0.is_nonnegative is not True:
        why = f"friction={friction!r}: the static bound {sp.sstr(m0)} is not provably >= 0"
        return Monotonicity(friction, slope, False, "Vr = 0", why)
    jump = sp.simplify(rest - m0)
    if jump != 0 and jump.is_nonnegative is not True:
        falls = f"Vr = 0, where {_inequality(jump)}"
        why = (
            f"friction={friction!r}: the static bound {sp.sstr(m0)} exceeds the slip "
            f"coefficient at rest {sp.sstr(rest)} where {_inequality(jump)}: a falling "
            "jump at Vr = 0, so sgn(Vr) mu(|Vr|) is not monotone in Vr (steady sliding "
            "and a stick-slip cycle may coexist)"
        )
        return Monotonicity(friction, slope, False, falls, why)
    if slope == 0 or slope.is_nonnegative:
        why = (
            f"friction={friction!r}: mu(0) >= 0 and dmu/d|Vr| = {sp.sstr(shown)} >= 0: "
            "non-decreasing in Vr"
        )
        return Monotonicity(friction, slope, True, "", why)
    sign, rest = 1, []
    for factor in sp.Mul.make_args(sp.factor(slope)):
        if factor.is_positive:
            continue
        if factor.is_negative:
            sign = -sign
            continue
        rest.append(factor)
    remaining = sign * sp.Mul(*rest)
    if SPEED not in remaining.free_symbols:
        falls = f"every |Vr| > 0 (0 < |Vr| < oo) where {_inequality(remaining)}"
    else:
        # a root provably <= 0 is no sliding speed inside (0, oo) (the cubic law's
        # -sqrt(mu_1/(3 mu_3))): only the others bound where the law falls
        try:
            found = budget.within(f"{friction}: dmu/d|Vr| = 0", sp.solve, slope, SPEED)
        except budget.Undecided as why:
            falls = f"|Vr| where {sp.sstr(shown)} < 0 (its roots: {why.reason})"
        else:
            roots = [r for r in found if r.is_nonpositive is not True]
            falls = f"|Vr| where {sp.sstr(shown)} < 0 (roots at {sp.sstr(roots)})"
    why = (
        f"friction={friction!r}: dmu/d|Vr| = {sp.sstr(shown)} < 0 for {falls}: the "
        "coefficient falls with the sliding speed there, so sgn(Vr) mu(|Vr|) is not "
        "monotone in Vr"
    )
    return Monotonicity(friction, slope, False, falls, why)


@dataclass(frozen=True)
class SignCase:
    """One pair of friction states and the sign SymPy proves for ``(s_a - s_b)(Vr_a - Vr_b)``.

    ``product`` is the factor after substituting each state's ``Vr`` and ``s``;
    ``sign`` is ``"= 0"``, ``"> 0"`` or ``">= 0"`` (the weakest that SymPy decides),
    ``proved`` whether SymPy decided it is non-negative.
    """

    state_a: str
    state_b: str
    s_a: sp.Expr
    s_b: sp.Expr
    product: sp.Expr
    sign: str
    proved: bool


def _state(name: str, tag: str):
    """``[(Vr, s), ...]`` covering one friction state (stick: both ends and the inside)."""
    u = sp.Symbol(f"u_{tag}", positive=True)  # |Vr| while slipping
    if name == "slip_back":
        return [(-u, sp.Integer(-1))]
    if name == "slip_forward":
        return [(u, sp.Integer(1))]
    p, q = sp.symbols(f"p_{tag} q_{tag}", positive=True)
    return [
        (sp.Integer(0), sp.Integer(-1)),
        (sp.Integer(0), (p - q) / (p + q)),
        (sp.Integer(0), sp.Integer(1)),
    ]  # s in [-1, 1]


def _decide(expr):
    f = sp.factor(expr)
    if f == 0:
        return "= 0", True
    if f.is_positive:
        return "> 0", True
    if f.is_nonnegative:
        return ">= 0", True
    return "undecided", False


@cache
def friction_power_sign_cases() -> tuple[SignCase, ...]:
    """``(s_a - s_b)(Vr_a - Vr_b) >= 0`` for every pair of friction states (Sgn is monotone).

    Slip back: ``Vr = -u``, ``s = -1``; slip forward: ``Vr = u``, ``s = 1`` (``u > 0``);
    stick: ``Vr = 0`` with ``s = -1``, ``s = (p - q)/(p + q)`` (``p, q > 0``: the open
    interval) and ``s = 1``. One `SignCase` per pair of states and per stick value.
    """
    out = []
    for A in STATES:
        for B in STATES:
            for ra, s_a in _state(A, "a"):
                for rb, s_b in _state(B, "b"):
                    prod = (s_a - s_b) * (ra - rb)
                    sign, ok = _decide(prod)
                    out.append(SignCase(A, B, s_a, s_b, sp.factor(prod), sign, ok))
    return tuple(out)


def clipped_force_nonnegative(contact: str = _CONTACT, tension: str = "clipped") -> bool:
    """Whether ``contact_force(tension="clipped")`` is ``>= 0`` on each of its branches.

    The clipped force is ``Piecewise((F, F > 0), (0, True))``; with ``F`` replaced by a
    positive symbol it is that symbol, with a non-positive one it is 0.
    """
    Fc = contact_force(contact, tension)
    F = normal_force(contact)
    pos, nonpos = sp.Symbol("F_pos", positive=True), sp.Symbol("F_np", nonnegative=True)
    y = sp.Dummy("F", real=True)
    branches = Fc.xreplace({F: y})
    if branches.has(X2, Y2):
        return False
    return bool(branches.subs(y, pos).is_nonnegative and branches.subs(y, -nonpos) == 0)


def sign_of_friction_power() -> dict[str, bool]:
    """The sign of ``-mu_s F M`` with ``M = (s_a - s_b)(Vr_a - Vr_b) >= 0`` (step 4).

    Keys: ``"friction part = -mu_s F (s_a - s_b)(Vr_a - Vr_b)"`` (the factor of
    `power_split` is ``-mu_s`` times the product of step 4), ``"F >= 0 -> <= 0"`` (the
    friction part of `power_split` never adds energy while the contact pushes),
    ``"F < 0 -> >= 0"`` (it never removes energy while the contact pulls),
    ``"F < 0, opposite sides -> > 0"`` (it adds energy when the runs slip in opposite
    directions, ``mu_s > 0``), ``"c1 e'^2 >= 0"`` and ``"beta1 > 0 -> c1 > 0"`` (the
    dashpot dissipates, strictly with damping).
    """
    M = sp.Symbol("M", nonnegative=True)
    Fp, Fm = sp.Symbol("F_p", nonnegative=True), sp.Symbol("F_m", negative=True)
    mu = friction_coefficient(_SIGN_LAW, 1)
    split = power_split()
    ua, ub = sp.symbols("u_a u_b", positive=True)
    mu_pos = sp.Symbol("mu_pos", positive=True)
    opposite = (split.friction_factor * Fm).xreplace(
        {sa: 1, sb: -1, Ya: P["Vb"] + ua, Yb: P["Vb"] - ub, P["mu_s"]: mu_pos}
    )
    b1 = sp.Symbol("beta1_pos", positive=True)
    Vr_diff = (Ya - P["Vb"]) - (Yb - P["Vb"])
    return {
        "friction part = -mu_s F (s_a - s_b)(Vr_a - Vr_b)": sp.expand(
            split.friction_factor + mu * (sa - sb) * Vr_diff
        )
        == 0,
        "F >= 0 -> <= 0": bool((-mu * Fp * M).is_nonpositive),
        "F < 0 -> >= 0": bool((-mu * Fm * M).is_nonnegative),
        "F < 0, opposite sides -> > 0": bool(sp.factor(opposite).is_positive),
        "c1 e'^2 >= 0": bool((split.c1 * ep**2).is_nonnegative),
        "beta1 > 0 -> c1 > 0": bool(split.c1.xreplace({P["beta1"]: b1}).is_positive),
    }
