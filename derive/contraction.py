"""Two tangential motions under one normal motion: the energy of their difference.

The normal equation of Eq. (4) contains neither ``X1``, ``X1'``, ``Vb`` nor ``mu_s``
(docs/modelling.md#model-and-units, *one-way coupling*). Two runs ``a`` and ``b``
with the same normal initial state therefore share the normal motion and with it
the contact force ``F(t)``, whatever their tangential initial states. Their
tangential equations (Eq. 4, mass-normalised)

    Xi'' + c1 Xi' + k1 Xi = f_t(t) - mu_s s_i F(t),    s_i in Sgn(Xi' - Vb),  i = a, b,

with ``c1 = 2 beta1 omega1``, ``k1 = omega1^2`` and the set-valued sign ``Sgn`` (``-1``
for ``Vr < 0``, ``[-1, 1]`` for ``Vr = 0``, ``+1`` for ``Vr > 0``: the stick mode is the
middle value, ``s = a_free / (mu_s F)``), differ by ``e = Xa - Xb``:

    e'' + c1 e' + k1 e = -mu_s F (s_a - s_b).

The excitation cancels. With the energy of the difference ``E_d = e'^2/2 + k1 e^2/2``

    dE_d/dt = -c1 e'^2 - mu_s F (s_a - s_b)(v_a - v_b),     v = X1'.

What this module proves with SymPy (each a function returning the result):

1. `one_way_coupling`: the normal equation of `beltmdsm.derive.dynamics.normal_rhs` is free of
   ``X1, Y1`` for both contact laws and both tension laws, so one normal motion
   serves both runs.
2. `difference_energy`, `difference_power`: ``E_d`` is the tangential part of the
   mechanical energy of `beltmdsm.derive.dynamics.energy` evaluated at the difference, and
   its rate along the two motions (accelerations of `beltmdsm.derive.dynamics.accelerations`,
   friction directions ``s_a, s_b``) is identically ``-c1 e'^2 - (f_a - f_b) F e'``
   with ``c1 = -d a_free/d X1'`` and ``f`` the signed friction coefficient of each
   run (`beltmdsm.derive.model.friction_coefficient`: ``mu_s s`` for Coulomb's law, Eq. 3),
   ``F`` the contact force of the tension law.
3. `stick_is_set_valued`: the stick field of `beltmdsm.derive.hybrid` (``Y1' = 0``) is the slip
   field at ``Vr = 0`` with ``s = a_free / (mu(0) F)``, which lies in ``[-1, 1]``
   exactly while the stick guard ``|a_free| <= mu(0) F`` holds.
4. `friction_power_sign_cases`: ``(s_a - s_b)(v_a - v_b) >= 0`` in each of the nine
   pairs of friction states (slip back, stick, slip forward for each run; stick
   with ``s`` at either end of ``[-1, 1]`` and inside it: 25 cases), by substitution of the
   state's ``Vr`` and ``s`` and SymPy's sign decision under the symbols'
   assumptions: the monotonicity of the set-valued ``Sgn``. ``v_a - v_b = Vr_a -
   Vr_b`` because both runs see the same ``Vb``.
   `monotonicity`: the friction law beyond the sign, ``sgn(Vr) mu(|Vr|)`` with
   ``mu(0) >= 0`` and ``mu' >= 0`` (Coulomb's constant ``mu_s``); it fails for
   Stribeck's law, which falls at every ``|Vr| > 0`` where ``mu_k < mu_s``, and then
   the claim does not hold (`claim` per friction law says so).
5. `clipped_force_nonnegative`: ``max(F, 0)`` of `beltmdsm.derive.model.contact_force` with
   ``tension="clipped"`` is ``>= 0`` on each branch.
6. `sign_of_friction_power`: from 4, ``mu_s >= 0`` and ``F >= 0`` the friction term
   is ``<= 0``, so ``dE_d/dt <= -c1 e'^2 <= 0``; with ``F < 0`` it is ``>= 0``
   (the converse: energy enters the difference only through friction while the
   contact pulls), and it is ``> 0`` for runs on opposite sides of ``Vr = 0``.

Conclusion (clipped tension, F >= 0 always): ``E_d`` never increases, and it
decreases strictly while ``e' != 0`` when ``beta1 > 0``.

**The convergence step is an argument in words, not a SymPy proof.** ``E_d`` is
non-increasing and bounded below, so it converges and ``int c1 e'^2 dt`` is finite.
Along a run the states and ``F`` stay bounded, so ``e''`` is bounded, ``e'`` is
uniformly continuous and (Barbalat) ``e' -> 0``; then ``|e|`` tends to a constant
``e_inf``. If ``e_inf != 0``, the difference equation forces ``k1 e = -mu_s F (s_a -
s_b)`` on average over every later window, so the friction directions differ for
a positive share of every window while the velocities coincide: both masses sit
at ``Vr = 0``, i.e. both stick, at positions ``e_inf`` apart, for all later time.
With ``Vb > 0`` a stuck mass moves with the belt, ``X1`` grows without bound and
the spring force leaves the bounded friction cone ``mu_s F``: permanent stick is
impossible, so ``e -> 0`` (LaSalle-type). The same holds for ``Vb = 0`` when the
excitation makes the mass slip in every period. Hence all tangential motions
under one normal motion converge to one. When the normal motion is periodic with
period ``T``, the shift of a tangential motion by ``T`` is again one under the same
normal motion, so the common limit is ``T``-periodic: it has spectral lines only
at multiples of ``2 pi / T`` (a line at ``omega1`` only where ``omega1`` is one of
them, as ``omega1 = 12 = 3 Omega`` of Fig. 20c). No self-excited vibration (a free
oscillation near ``omega1``, with a free phase) and no coexistence of tangential
responses are possible, for every parameter set with ``beta1 > 0`` and ``Vb > 0``.

The runtime checks this with the simulation (beltmdsm/studies/evidence.py): two runs with one normal
motion, the energy balance of their difference split by the sign of ``F``, and the
sign of ``F`` at the reversals of the friction.

Conditions, each shown by `breaking_conditions` to be needed:

* Friction non-decreasing in ``Vr`` (Coulomb's set-valued ``mu_s Sgn``). A
  coefficient ``mu_s sgn(Vr) + m(Vr)`` gives, on one slip branch,
  ``(mu(v_a) - mu(v_b))(v_a - v_b) = (m(v_a) - m(v_b))(v_a - v_b)`` (SymPy), which is
  ``m'(xi)(v_a - v_b)^2 < 0`` for a falling ``m`` by the mean value theorem (words).
  For ``m = -kappa Vr``, ``kappa > 0`` (``|mu|`` falls with ``|Vr|`` on both branches),
  SymPy gives ``dE_d/dt = -(c1 - kappa F) e'^2`` on that branch: the difference
  grows once ``kappa F > c1``, the classical falling-friction instability.
* ``beta1 > 0``: with ``beta1 = 0`` and both runs on one slip branch,
  ``dE_d/dt = 0`` identically: the difference oscillates for ever.
* One-way coupling: if ``F`` depended on the tangential state (not the case here,
  step 1), the friction term would be ``-mu_s (F_a s_a - F_b s_b) e'``, positive
  for ``s_a = s_b = -1`` and ``(F_a - F_b) e' > 0``.
* ``F >= 0``: Eq. (1) as printed (``tension="allowed"``) is negative part of the
  time (docs/modelling.md#tension), and then the converse of step 6 applies.

The argument covers tangential motions under one normal motion. Different normal
initial states may give different normal motions (the normal equation is
nonlinear); the argument says nothing about their coexistence.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import dynamics, hybrid, laws
from .model import (
    CONTACT_LAWS,
    SPEED,
    TENSION_LAWS,
    X1,
    X2,
    Y1,
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
    "Xa",
    "Ya",
    "Xb",
    "Yb",
    "sa",
    "sb",
    "e",
    "ep",
    "STATES",
    "SignCase",
    "PowerSplit",
    "Step",
    "ContractionClaim",
    "one_way_coupling",
    "difference_energy",
    "tangential_acceleration",
    "difference_power",
    "power_split",
    "stick_is_set_valued",
    "friction_power_sign_cases",
    "clipped_force_nonnegative",
    "sign_of_friction_power",
    "breaking_conditions",
    "Monotonicity",
    "monotonicity",
    "claim",
]

#: The tangential states of the two runs and their friction directions (elements of Sgn).
Xa, Ya, Xb, Yb = sp.symbols("X1_a Y1_a X1_b Y1_b", real=True)
sa, sb = sp.symbols("s_a s_b", real=True)
#: The difference ``e = X1_a - X1_b`` and its rate ``e'``.
e, ep = sp.symbols("e e_dot", real=True)
#: The friction states of one run: the three parts of the graph of Sgn.
STATES = ("slip_back", "stick", "slip_forward")
_FRICTION, _CONTACT, _TENSION = (laws.default(o) for o in laws.OPTIONS)
#: The set-valued part of every friction law, mu(0) Sgn(Vr): the steps on the sign
#: (`friction_power_sign_cases`, `sign_of_friction_power`, `breaking_conditions`) are
#: derived for Coulomb's law, whose mu(0) = mu_s stands for any nonnegative mu(0)
#: (`monotonicity` checks mu(0) >= 0 of each law).
_SIGN_LAW = laws.default("friction")


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
        roots = sp.solve(slope, SPEED)
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


def breaking_conditions() -> dict[str, tuple[bool, str]]:
    """Each condition of the claim, dropped, with SymPy's result and one line of detail.

    ``"falling friction"``: friction ``mu_s s + m(Vr)`` on one slip branch; the friction
    factor reduces to ``(m(Vr_a) - m(Vr_b))(Vr_a - Vr_b)`` for a generic ``m``, and for
    ``m = -kappa Vr`` (``kappa > 0``: the coefficient falls with ``Vr``) the whole rate
    is ``-(c1 - kappa F) e'^2``: positive once ``kappa F > c1``.
    ``"beta1 = 0"``: on one slip branch ``dE_d/dt`` is identically 0.
    ``"two-way coupling"``: separate forces ``F_a = F_b + dF`` on one slip branch make the
    friction part ``mu_s dF e'`` for ``s = -1``, positive for ``dF e' > 0``.
    """
    out = {}
    split = power_split()
    de = Ya - Yb
    F, c1 = sp.Symbol("F", real=True), split.c1
    s = sp.Symbol("s", real=True)
    Vb = P["Vb"]
    # falling friction: mu(Vr) = mu_s s + m(Vr), one branch (s_a = s_b = s)
    m = sp.Function("m")
    mu_a = friction_coefficient(_SIGN_LAW, s) + m(Ya - Vb)
    mu_b = friction_coefficient(_SIGN_LAW, s) + m(Yb - Vb)
    factor = sp.expand((mu_a - mu_b) * de)
    generic = sp.expand(factor - (m(Ya - Vb) - m(Yb - Vb)) * de) == 0
    kappa = sp.Symbol("kappa", positive=True)
    linear = factor.replace(m, sp.Lambda(sp.Symbol("x"), -kappa * sp.Symbol("x")))
    d = sp.Symbol("d", positive=True)
    falls = sp.factor(linear.xreplace({Ya: Yb + d})).is_negative
    rate = -c1 * de**2 - linear * F
    closed = sp.expand(rate - (-(c1 - kappa * F) * de**2)) == 0
    Fbig = sp.Symbol("F_big", positive=True)
    grows = sp.factor(
        (-(c1 - kappa * F) * de**2).xreplace({F: (c1 + Fbig) / kappa, Ya: Yb + d})
    ).is_positive
    out["falling friction"] = (
        bool(generic and falls and closed and grows),
        (
            "(mu(Vr_a) - mu(Vr_b))(Vr_a - Vr_b) = (m(Vr_a) - m(Vr_b))"
            "(Vr_a - Vr_b) on one branch; with m = -kappa Vr it is "
            "-kappa e'^2 < 0 and dE_d/dt = -(c1 - kappa F) e'^2 > 0 "
            "once kappa F > c1"
        ),
    )
    # beta1 = 0
    zero = sp.expand(split.total.xreplace({P["beta1"]: 0, sa: s, sb: s})) == 0
    out["beta1 = 0"] = (
        bool(zero),
        ("dE_d/dt = 0 identically on one slip branch: the difference is an undamped oscillation"),
    )
    # two-way coupling: a force per run
    dF = sp.Symbol("dF", positive=True)
    mu_pos = sp.Symbol("mu_pos", positive=True)
    mu = friction_coefficient(_SIGN_LAW, -1)
    coupled = -(mu * (F + dF) - mu * F) * de
    coupled = sp.factor(coupled.xreplace({Ya: Yb + d, P["mu_s"]: mu_pos}))
    ok = coupled.is_positive and sp.expand(coupled - mu_pos * dF * d) == 0
    out["two-way coupling"] = (
        bool(ok),
        (
            "a force per run, F_a = F_b + dF, makes the "
            "friction part mu_s dF e' for s_a = s_b = -1: "
            "positive for dF, e' > 0"
        ),
    )
    return out


@dataclass(frozen=True)
class Step:
    """One step of the argument: how it is established and whether that succeeded."""

    name: str
    how: str  # "SymPy" or "words"
    proved: bool
    detail: str


@dataclass(frozen=True)
class ContractionClaim:
    """The contraction result for one friction law: statement, conditions, converse,
    its steps, and the law's monotonicity (where it fails, the claim does not hold)."""

    statement: str
    conditions: tuple[str, ...]
    converse: str
    steps: tuple[Step, ...]
    breaks: dict
    friction: str
    monotone: Monotonicity

    @property
    def proved_by_sympy(self) -> bool:
        """Whether every SymPy step succeeded (the words step is not counted)."""
        return all(s.proved for s in self.steps if s.how == "SymPy")


@cache
def claim(friction: str = _FRICTION) -> ContractionClaim:
    """Run every SymPy step (module docstring) for the friction law ``friction``.

    The steps on the set-valued sign hold for every law; the step "friction law
    non-decreasing" (`monotonicity`) decides whether the law keeps the claim: it
    fails for Stribeck's law, which falls with the sliding speed.
    """
    coupling = one_way_coupling()
    splits = {(c, tn): power_split(c, tn, friction) for c in CONTACT_LAWS for tn in TENSION_LAWS}
    cases = friction_power_sign_cases()
    stick = {c: stick_is_set_valued(c, friction) for c in CONTACT_LAWS}
    clipped = {c: clipped_force_nonnegative(c) for c in CONTACT_LAWS}
    signs = sign_of_friction_power()
    breaks = breaking_conditions()
    law = monotonicity(friction)
    n_pairs = len({(c.state_a, c.state_b) for c in cases})
    steps = (
        Step(
            "one-way coupling",
            "SymPy",
            all(coupling.values()),
            "the normal equation (beltmdsm.derive.dynamics.normal_rhs) is free of X1, X1' for "
            f"{len(coupling)} (contact, tension) combinations",
        ),
        Step(
            "difference energy and power",
            "SymPy",
            all(s.exact for s in splits.values()),
            "dE_d/dt = -c1 e'^2 - (f_a - f_b) F e' (expand to zero; f the signed "
            f"coefficient of friction={friction!r}), every contact and tension law",
        ),
        Step(
            "stick is Sgn at Vr = 0",
            "SymPy",
            all(stick.values()),
            "the stick field is the slip field at Vr = 0 with s = a_free/(mu(0) F), in "
            "[-1, 1] exactly while the stick guard holds",
        ),
        Step(
            "Sgn is monotone",
            "SymPy",
            all(c.proved for c in cases),
            f"(s_a - s_b)(Vr_a - Vr_b) >= 0 in all {len(cases)} cases ({n_pairs} pairs "
            "of slip back / stick / slip forward, stick with s = -1, inside, +1)",
        ),
        Step("friction law non-decreasing", "SymPy", law.holds, law.reason),
        Step(
            "clipped force >= 0",
            "SymPy",
            all(clipped.values()),
            "max(F, 0) of beltmdsm.derive.model.contact_force is >= 0 on each branch",
        ),
        Step(
            "sign of the friction power",
            "SymPy",
            signs["friction part = -mu_s F (s_a - s_b)(Vr_a - Vr_b)"]
            and signs["F >= 0 -> <= 0"]
            and signs["c1 e'^2 >= 0"],
            "F >= 0 and a non-decreasing law: friction part <= 0, so dE_d/dt <= -c1 e'^2 <= 0",
        ),
        Step(
            "converse (tension allowed)",
            "SymPy",
            signs["F < 0 -> >= 0"] and signs["F < 0, opposite sides -> > 0"],
            "F < 0: friction part >= 0, and > 0 while the runs slip in opposite directions",
        ),
        Step(
            "convergence",
            "words",
            True,
            "E_d non-increasing, strictly while e' != 0 (beta1 > 0); Barbalat gives "
            "e' -> 0; a persistent e needs both masses stuck e apart for all later "
            "time, impossible for Vb > 0 (a stuck mass moves with the belt and the "
            "spring force leaves the bounded cone) or when the excitation makes the "
            "mass slip; the limit of a T-periodic normal motion is T-periodic",
        ),
    )
    return ContractionClaim(
        statement=(
            "with tension clipped and a friction law non-decreasing in Vr, all "
            "tangential motions under one normal motion converge to one (the periodic "
            "response when the normal motion is periodic): no self-excited vibration "
            "and no coexistence of tangential responses, for every parameter set"
        ),
        conditions=(
            "a friction law sgn(Vr) mu(|Vr|) non-decreasing in Vr (Coulomb's mu_s Sgn: "
            "static = kinetic)",
            "beta1 > 0 (strict decay of E_d)",
            "one-way coupling: the normal equation is free of the tangential state",
            "F >= 0 (tension clipped)",
            "Vb > 0, or an excitation that makes the mass slip (no permanent stick)",
        ),
        converse=(
            "with tension allowed, dE_d/dt <= -c1 e'^2 while F >= 0; energy enters "
            "the difference only through friction while F < 0"
        ),
        steps=steps,
        breaks=breaks,
        friction=friction,
        monotone=law,
    )
