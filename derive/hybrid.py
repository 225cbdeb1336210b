"""Eq. (4) as a hybrid system: modes, switching surfaces, guards and saltation matrices.

The sign function of Eq. (3) and the loss of contact of Eq. (1) make Eq. (4)
piecewise smooth. An event-driven integrator, the superposition integrator and the
Floquet analysis all work on the same description, derived here:

* **modes**, each with a smooth vector field on the whole state space (so that a
  root finder may look past a switch): ``slip_back`` and ``slip_forward`` (in
  contact, friction ``-mu(sgn Vr) sgn F`` with ``sgn = -1, +1``, the friction law's
  coefficient at the speed ``sgn Vr`` (``|Vr|`` on the branch, continued smoothly
  past it) and the unclipped force ``F`` of the contact law); ``stick``
  (Filippov's sliding mode on ``Vr = 0``: ``X1' = Vb``, ``Y1' = 0``, the friction
  holds the mass); ``flight`` (``X2 <= 0``, no contact force, Eq. 1) and
  ``separated`` (under a tension law that cannot pull only: ``X2 > 0`` where the
  contact law would pull; docs/modelling.md#tension), both with the free field;
* **switching surfaces** ``h(t, x) = 0``: ``relative_velocity`` ``Y1 - Vb``;
  ``stick_forward`` and ``stick_back`` ``mu_st F -+ a_free`` (the stick cone: the
  friction law's static bound ``mu_st``, `beltmdsm.derive.model.static_coefficient`, ``mu_s`` for
  every shipped law, while the slip modes take the law's coefficient, ``mu_k`` below it
  for ``static_kinetic``: leaving stick then has ``S != I``; ``a_free`` the tangential
  acceleration without friction); ``penetration`` ``X2``;
  ``contact_force``, a function with the sign of ``F`` in contact (``F`` divided by
  its factors that are positive there: for Hertz-Damp ``omega2 + 2 beta2 X2'``,
  which, unlike ``F``, crosses zero transversally where ``X2 = 0`` does not);
* **guards**: per tension law (a law that can pull, and one that cannot: decided by
  `pulls` from the law itself), which surfaces end which mode, crossed in which
  direction, and what follows (a mode, or a rule: `DECIDE_SLIP` is Filippov's rule
  at ``Vr = 0``, `DECIDE_CONTACT` the choice on entering contact);
* **saltation matrices** ``S = I + (f+ - f-) n^T / (dh/dt)-``, ``n = grad h`` and
  ``(dh/dt)- = dh/dt + n^T f-`` (Aizerman-Gantmakher; Leine and Nijmeijer 2004), the
  jump of the variational solution across a switch: without them Floquet
  multipliers are wrong. Where the two fields agree on the surface (the clipped
  force, the friction limit of a law whose static bound is its slip coefficient at
  rest, lift-off of the Hertz-Damp contact) ``S = I``;
* **mode Jacobians** ``d f / d x`` of each mode's field (`mode_jacobian`), for the
  variational equations along an event-driven run (a Floquet analysis that does not
  rely on the tangential motion between switches being linear).

Modes are coded by integers (`MODE_CODES`) so that a compiled integrator can pass
the mode to one kernel: the slip codes are the friction direction ``sgn(Vr)`` of
Eq. (3).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from . import laws
from .dynamics import X2r, free_acceleration
from .model import (
    TENSION_LAWS,
    X1,
    X2,
    Y1,
    Y2,
    P,
    excitation,
    friction_coefficient,
    normal_force,
    static_coefficient,
    t,
)

__all__ = [
    "MODE_CODES",
    "FIELDS",
    "SURFACES",
    "DECIDE_SLIP",
    "DECIDE_CONTACT",
    "GUARDS",
    "STATE",
    "pulls",
    "mode",
    "contact_force_in_contact",
    "vector_field",
    "field_of_mode",
    "response_field",
    "surfaces",
    "rounding_scale",
    "surface_scales",
    "surface_rates",
    "transitions",
    "saltation",
    "mode_jacobian",
]

#: Integer code of each mode; the slip codes are the friction direction of Eq. (3).
MODE_CODES = {"slip_back": -1, "stick": 0, "slip_forward": 1, "flight": 2, "separated": 3}
#: The vector field of each mode (flight and separated are both free of contact).
FIELDS = {
    "slip_back": "slip_back",
    "stick": "stick",
    "slip_forward": "slip_forward",
    "flight": "free",
    "separated": "free",
}
SURFACES = ("relative_velocity", "stick_forward", "stick_back", "penetration", "contact_force")
#: Guard target: decide by Filippov's rule at Vr = 0 (stick, reversal or leaving).
DECIDE_SLIP = "decide_slip"
#: Guard target: entering contact (the sign of Vr, or DECIDE_SLIP at Vr = 0; with the
#: clipped law, separated while the contact force would pull).
DECIDE_CONTACT = "decide_contact"

_CONTACT_GUARDS = {
    "slip_back": (("relative_velocity", 1, DECIDE_SLIP), ("penetration", -1, "flight")),
    "slip_forward": (("relative_velocity", -1, DECIDE_SLIP), ("penetration", -1, "flight")),
    "stick": (
        ("stick_forward", -1, "slip_forward"),
        ("stick_back", -1, "slip_back"),
        ("penetration", -1, "flight"),
    ),
    "flight": (("penetration", 1, DECIDE_CONTACT),),
}
#: A contact that cannot pull: every contact mode also ends where the force would,
#: into ``separated``, which ends on recontact or in flight.
_SEPARATING_GUARDS = {
    **{
        m: g + (("contact_force", -1, "separated"),)
        for m, g in _CONTACT_GUARDS.items()
        if m != "flight"
    },
    "flight": _CONTACT_GUARDS["flight"],
    "separated": (("contact_force", 1, DECIDE_CONTACT), ("penetration", -1, "flight")),
}


def pulls(tension: str) -> bool:
    """Whether the tension law lets the contact pull: its force for a negative ``F`` is not 0.

    Decided by SymPy on the law's expression (`beltmdsm.derive.laws.TensionLaw.acting`).
    """
    F = sp.Symbol("F", negative=True)
    return sp.simplify(laws.get("tension", tension).acting(F)) != 0


#: Per tension law: mode -> ((surface, direction of the crossing, target), ...). A
#: mode ends where one of its surfaces is crossed in the stated direction (+1: h
#: rises through 0, -1: falls through 0).
GUARDS = {
    tension: _CONTACT_GUARDS if pulls(tension) else _SEPARATING_GUARDS for tension in TENSION_LAWS
}

#: The mode code, an argument of the generated kernels.
mode = sp.Symbol("mode", real=True)
#: The state with a real (signed) penetration.
STATE = (X1, Y1, X2r, Y2)


def contact_force_in_contact(contact: str) -> sp.Expr:
    """The unclipped contact force of Eq. (1), extended smoothly past ``X2 = 0``."""
    return normal_force(contact).subs(X2, sp.Max(X2r, 0))


def _contact_sign(contact: str) -> sp.Expr:
    """``F`` of Eq. (1) divided by its factors that SymPy proves positive in contact."""
    F = sp.factor(normal_force(contact))
    kept = [f for f in sp.Mul.make_args(F) if f.is_positive is not True]
    return sp.Mul(*kept)


@cache
def field_of_mode(name: str, contact: str, friction: str = laws.default("friction")) -> sp.Matrix:
    """Vector field ``(X1', Y1', X2', Y2')`` of one mode (by name; see `FIELDS`)."""
    F = contact_force_in_contact(contact)
    f_n = excitation()[1]
    a_free = free_acceleration()
    normal = P["g"] + f_n - F
    field = FIELDS[name]
    if field == "free":
        return sp.Matrix([Y1, a_free, Y2, P["g"] + f_n])
    if field == "stick":
        return sp.Matrix([P["Vb"], 0, Y2, normal])
    mu = friction_coefficient(friction, MODE_CODES[field])
    return sp.Matrix([Y1, a_free - mu * F, Y2, normal])


def response_field(contact: str) -> sp.Matrix:
    """The normal motion with the tangential oscillator's response to its force.

    State ``(z, z', X2, X2')``: ``z`` is the response of the tangential oscillator,
    from rest, to the contact force of the mode (``F`` of Eq. (1) in contact, 0 in
    flight or separation). The normal equation does not contain the tangential
    state, so this system is integrated once per normal motion; between switches a
    slip mode's tangential motion is then the free motion plus the excitation
    response minus ``mu_s sgn`` times ``z`` (derive/oscillator.py), for a friction law
    whose slip-mode friction is ``mu_s sgn F`` (the capability
    ``slip_friction_state_independent``, derive/capabilities.py). The positions
    of ``X2, X2'`` are those of the full state, so `surfaces` applies unchanged.
    """
    b1, w1 = P["beta1"], P["omega1"]
    z, v = sp.symbols("z v", real=True)
    F = contact_force_in_contact(contact)
    f_n = excitation()[1]
    contact_modes = sp.Or(
        *(sp.Eq(mode, MODE_CODES[m]) for m in ("slip_back", "stick", "slip_forward"))
    )
    Fm = sp.Piecewise((F, contact_modes), (0, True))
    return sp.Matrix([v, Fm - 2 * b1 * w1 * v - w1**2 * z, Y2, P["g"] + f_n - Fm]), (z, v)


def _by_mode(build):
    """``(piece, condition)`` for each mode code with a field of its own, and the free
    field (the codes of flight and separated)."""
    pieces = [
        (build(name), sp.Eq(mode, code))
        for name, code in MODE_CODES.items()
        if FIELDS[name] == name
    ]
    free = build("flight")
    return pieces, free


def _per_mode(build, rows, cols):
    """A matrix whose entries are Piecewise over the mode codes of `_by_mode`."""
    pieces, free = _by_mode(build)
    return sp.Matrix(
        rows,
        cols,
        lambda i, j: sp.Piecewise(*[(f[i, j], cond) for f, cond in pieces], (free[i, j], True)),
    )


def vector_field(contact: str, friction: str = laws.default("friction")) -> sp.Matrix:
    """The field of the mode with code ``mode`` (`MODE_CODES`), entry by entry."""
    return _per_mode(lambda name: field_of_mode(name, contact, friction), 4, 1)


def mode_jacobian(contact: str, friction: str = laws.default("friction")) -> sp.Matrix:
    """``d f / d (X1, X1', X2, X2')`` of the field of the mode with code ``mode``.

    The variational equation of a run within one mode, ``Phi' = (df/dx) Phi``;
    across a switch the variation jumps by `saltation`. Each mode's field is smooth
    on the whole state space except the contact modes' ``max(X2, 0)``, whose
    derivative is taken in contact (the run leaves the mode at ``X2 = 0``).
    """

    def jacobian(name):
        field = field_of_mode(name, contact, friction)
        return sp.Matrix(4, 4, lambda i, j: _d(field[i], STATE[j]))

    return _per_mode(jacobian, 4, 4)


@cache
def surfaces(contact: str, friction: str = laws.default("friction")) -> dict[str, sp.Expr]:
    """The switching functions ``h(t, x)`` of `SURFACES`, by name.

    The stick surfaces bound the holding force by the friction law's static bound
    (`beltmdsm.derive.model.static_coefficient`: its ``static`` where it gives one, else
    ``mu(0)``).
    """
    F = contact_force_in_contact(contact)
    a_free = free_acceleration()
    mu = static_coefficient(friction)
    return {
        "relative_velocity": Y1 - P["Vb"],
        "stick_forward": mu * F - a_free,
        "stick_back": mu * F + a_free,
        "penetration": X2r,
        "contact_force": _contact_sign(contact).subs(X2, sp.Max(X2r, 0)),
    }


@cache
def _d(expr, x) -> sp.Expr:
    """``d expr / d x`` with powers of one base merged: SymPy differentiates ``X2**n`` of a
    symbolic exponent to ``n X2**n / X2``, which is 0/0 where ``max(X2, 0)`` is 0 (in
    flight); ``n X2**(n - 1)`` is finite there (rational exponents merge by
    themselves, so the paper's laws are unchanged). Cached: a surface's gradient enters
    its rate in every mode and every saltation matrix across it."""
    return sp.powsimp(sp.diff(expr, x), combine="exp")


def _term_scale(expr) -> sp.Expr:
    return sp.Add(*[sp.Abs(term) for term in sp.Add.make_args(sp.expand(expr))])


def rounding_scale(h) -> sp.Expr:
    """A scale of the rounding error of a computed ``h``.

    The sum of the absolute values of its terms, plus, for every sine or cosine in
    it, ``|dh/du|`` times the scale of its argument ``u``: ``Omega t + phase`` is
    rounded before the sine, by about an ulp of ``Omega t``, which late in a run is
    far more than an ulp of the sine.
    """
    scale = _term_scale(h)
    for trig in sorted(h.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
        u = trig.args[0]
        w = sp.Dummy("w")
        slope = sp.diff(h.xreplace({trig: trig.func(w)}), w).subs(w, u)
        scale += sp.Abs(slope) * _term_scale(u)
    return scale


def surface_scales(contact: str, friction: str = laws.default("friction")) -> dict[str, sp.Expr]:
    """A rounding-error scale of each switching function (`rounding_scale`).

    A computed ``h`` is within a few ulps of this scale of the exact one, so a
    decision on the sign of ``h`` (stick against slip at a tie) is taken with a
    tolerance proportional to it.
    """
    return {name: rounding_scale(h) for name, h in surfaces(contact, friction).items()}


def _rate(h, field):
    return _d(h, t) + sum(_d(h, x) * f for x, f in zip(STATE, field))


def surface_rates(contact: str, friction: str = laws.default("friction")) -> dict[str, sp.Expr]:
    """``dh/dt`` of each switching function along the field of mode ``mode``."""
    pieces, free = _by_mode(lambda name: field_of_mode(name, contact, friction))
    out = {}
    for name, h in surfaces(contact, friction).items():
        out[name] = sp.Piecewise(
            *[(_rate(h, f), cond) for f, cond in pieces], (_rate(h, free), True)
        )
    return out


def transitions() -> tuple[tuple[str, str, str], ...]:
    """Every ``(before, after, surface)`` a run can take, over both tension laws.

    A guard's rule expands to the modes it can choose: `DECIDE_SLIP` to the other
    slip direction (a reversal) and ``stick``; `DECIDE_CONTACT` to either slip
    direction and ``stick`` (and ``separated`` under a law that cannot pull).
    """
    found = set()
    for tension in TENSION_LAWS:
        for before, guards in GUARDS[tension].items():
            for surface, _, target in guards:
                if target == DECIDE_SLIP:
                    after = ["stick", "slip_forward" if before == "slip_back" else "slip_back"]
                elif target == DECIDE_CONTACT:
                    after = ["slip_back", "slip_forward", "stick"]
                    if not pulls(tension) and before != "separated":
                        after.append("separated")
                else:
                    after = [target]
                found.update((before, a, surface) for a in after)
    return tuple(sorted(found))


def saltation(
    before: str, after: str, surface: str, contact: str, friction: str = laws.default("friction")
) -> sp.Matrix:
    """Saltation matrix of a switch from ``before`` to ``after`` across ``surface``.

    ``S = I + (f+ - f-) n^T / (dh/dt)-`` with ``n`` the state gradient of ``h`` and
    ``(dh/dt)- = dh/dt + n^T f-`` the rate at which the run reaches the surface.
    ``S`` maps a perturbation just before the switch to one just after it, for the
    perturbed run that switches at a shifted time.
    """
    h = surfaces(contact, friction)[surface]
    f_minus = field_of_mode(before, contact, friction)
    f_plus = field_of_mode(after, contact, friction)
    n = sp.Matrix([[_d(h, x) for x in STATE]])
    rate = _d(h, t) + (n * f_minus)[0]
    return sp.eye(4) + (f_plus - f_minus) * n / rate
