"""The model: symbols, the laws of the registry, excitation and the equations of motion.

Implements Eqs. (1)-(4) of the paper. The equations of motion are assembled from
parts so that each part is a choice:

* the contact law (`beltmdsm.derive.laws`): Hertz-Damp, Eq. (1) (``"hertz_damp"``), the
  linear Kelvin-Voigt law of Fig. 16 (``"kelvin_voigt"``), Hunt-Crossley with a
  symbolic exponent (``"hunt_crossley"``), or any registered law;
* the tension law (`beltmdsm.derive.laws`): Eq. (1) as printed, whose force turns negative
  (tensile) when the damping term outweighs the stiffness term (``"allowed"``), or a
  contact that cannot pull, ``max(F, 0)`` (``"clipped"``; docs/modelling.md#tension);
* the friction law (`beltmdsm.derive.laws`): the coefficient ``mu(|Vr|)``, Coulomb's constant
  ``mu_s`` of Eq. (3) (``"coulomb"``) or Stribeck's falling one (``"stribeck"``),
  with the direction applied here: ``sgn(Vr)`` as in Eq. (3), or a fixed branch
  (``-1`` while the mass is slower than the belt, the branch of Eqs. 5-8);
* the excitation: amplitude, frequency and phase per direction (Figs. 14-15),
  whose defaults reduce to Eq. (4).

Everything here is a pure function returning SymPy objects.
"""

from __future__ import annotations

import sympy as sp

from . import laws
from .lawcheck import value_at_rest
from .parameters import base_values

__all__ = [
    "FRICTION_LAWS",
    "CONTACT_LAWS",
    "TENSION_LAWS",
    "PARAMETERS",
    "BASE",
    "P",
    "t",
    "X1",
    "Y1",
    "X2",
    "Y2",
    "STATE",
    "SPEED",
    "lam",
    "coefficient",
    "static_coefficient",
    "rest_coefficient",
    "normal_force",
    "contact_force",
    "contact_potential",
    "friction_coefficient",
    "excitation",
    "equal_excitation",
    "equations_of_motion",
]

#: The choices of each option, from the registry (the default first).
FRICTION_LAWS = laws.choices("friction")
CONTACT_LAWS = laws.choices("contact")
TENSION_LAWS = laws.choices("tension")
#: The full parameter table: the model's own parameters and those of every law.
PARAMETERS = laws.parameter_table()
#: The base set: the paper's Fig. 2 with Vb = 4 (Fig. 3), and each law's base values.
BASE = base_values(PARAMETERS)

_ASSUMPTIONS = {
    "positive": {"positive": True},
    "nonnegative": {"nonnegative": True},
    "real": {"real": True},
}

#: Parameter symbols by name, with the assumptions of the parameter table.
P: dict[str, sp.Symbol] = {p.name: sp.Symbol(p.name, **_ASSUMPTIONS[p.domain]) for p in PARAMETERS}

t = sp.Symbol("t", real=True)
X1, Y1, Y2 = sp.symbols("X1 Y1 Y2", real=True)
#: Penetration. Positive: Eqs. (5)-(8) hold in contact only (the non-jumping case).
X2 = sp.Symbol("X2", positive=True)
STATE = (X1, Y1, X2, Y2)
#: The sliding speed |Vr|, the argument of a friction law's coefficient.
SPEED = sp.Symbol("speed", nonnegative=True)
lam = sp.Symbol("lambda")

_DEFAULT = {option: laws.default(option) for option in laws.OPTIONS}


def coefficient(friction=_DEFAULT["friction"], speed=SPEED) -> sp.Expr:
    """The friction law's coefficient ``mu(speed)`` at the sliding speed ``speed = |Vr|``.

    ``friction`` is the name of a law of `beltmdsm.derive.laws`, or a function of the speed
    (a derivation's stand-in for a law, e.g. its expansion at an operating point).
    """
    if callable(friction):
        return sp.sympify(friction(speed))
    return sp.sympify(laws.get("friction", friction).coefficient(P, speed))


def static_coefficient(friction: str = _DEFAULT["friction"]) -> sp.Expr:
    """The static bound: the bound of the holding force while sticking (the stick cone).

    At ``Vr = 0`` the set-valued sign of Eq. (3) lets friction take any value in
    ``[-mu_st F, mu_st F]``: ``mu_st`` is the law's ``static`` where it gives one
    (`beltmdsm.derive.laws.FrictionLaw`; ``mu_s`` of ``static_kinetic``), else `rest_coefficient`
    (``mu_s`` of ``coulomb`` and ``stribeck``).
    """
    law = laws.get("friction", friction)
    if law.static is not None:
        return sp.sympify(law.static(P))
    return rest_coefficient(friction)


def rest_coefficient(friction: str = _DEFAULT["friction"]) -> sp.Expr:
    """``mu(0)``: the slip law's coefficient at rest, its limit as ``|Vr| -> 0+``.

    What a slip mode's friction is at ``Vr = 0`` and what the averages of the slip
    friction over a fast motion multiply the sign's average by (`beltmdsm.derive.averaging`);
    it differs from `static_coefficient` where the law has a static bound of its own.
    """
    return sp.simplify(value_at_rest(coefficient(friction, SPEED), SPEED))


def normal_force(contact: str = _DEFAULT["contact"], X2=X2, Y2=Y2) -> sp.Expr:
    """Mass-normalised normal force in contact, Eq. (1) divided by ``M``: the contact law's.

    ``hertz_damp``: ``(omega2^2 + 2 beta2 omega2 X2') X2^(3/2)``;
    ``kelvin_voigt``: ``omega2^2 X2 + 2 beta2 omega2 X2'`` (Fig. 16);
    ``hunt_crossley``: ``(omega2^2 + 2 beta2 omega2 X2') X2^n_h``.
    All vanish for ``X2 <= 0``; the caller handles loss of contact.
    """
    return sp.sympify(laws.get("contact", contact).force(P, X2, Y2))


def contact_force(
    contact: str = _DEFAULT["contact"], tension: str = _DEFAULT["tension"], X2=X2, Y2=Y2
) -> sp.Expr:
    """The normal force in contact under a tension law (`beltmdsm.derive.laws`).

    ``allowed``: Eq. (1) as printed (`normal_force`), negative when the damping term
    outweighs the stiffness term. ``clipped``: ``max(F, 0)``, a contact that cannot
    pull; where Eq. (1) would be tensile the surfaces separate and no force acts.
    """
    return laws.get("tension", tension).acting(normal_force(contact, X2, Y2))


def contact_potential(contact: str = _DEFAULT["contact"], X2=X2) -> sp.Expr:
    """Potential of the elastic part of the normal force, per unit mass.

    Derived by integration so that it stays consistent with `normal_force`.
    """
    s = sp.Dummy("s", positive=True)
    elastic = normal_force(contact, s, 0)
    return sp.integrate(elastic, (s, 0, X2))


def friction_coefficient(friction: str = _DEFAULT["friction"], direction=None) -> sp.Expr:
    """The signed friction coefficient ``mu(|Vr|) sgn(Vr)``, Eq. (3), ``Vr = X1' - Vb``.

    ``direction`` replaces ``sgn(Vr)`` by a fixed branch (``-1``: the mass is slower
    than the belt, as in Eqs. 5-8; a symbol: the simulator's branch); on a branch
    the speed is ``direction * Vr``, which is ``|Vr|`` there and differentiable.
    ``None`` keeps the sign function (and ``|Vr|``).
    """
    Vr = Y1 - P["Vb"]
    if direction is None:
        return coefficient(friction, sp.Abs(Vr)) * sp.sign(Vr)
    direction = sp.sympify(direction)
    return coefficient(friction, direction * Vr) * direction


def excitation(general: bool = True) -> tuple[sp.Expr, sp.Expr]:
    """Forces per unit mass ``(f_t, f_n)`` on the right-hand side of Eq. (4).

    With ``general=True`` each direction has its own amplitude, frequency and phase
    (Figs. 14-15); `equal_excitation` maps them back to Eq. (4).
    """
    if not general:
        a, W = P["alpha"], P["Omega"]
        return a * W**2 * sp.sin(W * t), -a * W**2 * sp.sin(W * t)
    at, Wt, pt = P["alpha_t"], P["Omega_t"], P["phase_t"]
    an, Wn, pn = P["alpha_n"], P["Omega_n"], P["phase_n"]
    return (at * Wt**2 * sp.sin(Wt * t + pt), -an * Wn**2 * sp.sin(Wn * t + pn))


def equal_excitation() -> dict[sp.Symbol, sp.Expr]:
    """The substitution under which the general excitation is that of Eq. (4)."""
    return {
        P["alpha_t"]: P["alpha"],
        P["Omega_t"]: P["Omega"],
        P["phase_t"]: 0,
        P["alpha_n"]: P["alpha"],
        P["Omega_n"]: P["Omega"],
        P["phase_n"]: 0,
    }


def equations_of_motion(
    contact: str = _DEFAULT["contact"],
    direction=None,
    forced: bool = True,
    general: bool = True,
    friction: str = _DEFAULT["friction"],
) -> sp.Matrix:
    """Accelerations ``(X1'', X2'')`` of Eq. (4), solved for (the mass matrix is I).

    Parameters
    ----------
    contact : str
        A contact law of `beltmdsm.derive.laws`.
    direction : None, -1 or +1
        Friction direction; see `friction_coefficient`.
    forced : bool
        ``False`` drops the excitation (the unforced system of Sect. 4.1).
    general : bool
        Per-direction excitation (``True``) or the single one of Eq. (4).
    friction : str
        A friction law of `beltmdsm.derive.laws`.
    """
    b1, w1, g = P["beta1"], P["omega1"], P["g"]
    Fn = normal_force(contact)
    f_t, f_n = excitation(general) if forced else (0, 0)
    X1dd = -2 * b1 * w1 * Y1 - w1**2 * X1 - friction_coefficient(friction, direction) * Fn + f_t
    X2dd = -Fn + g + f_n
    return sp.Matrix([X1dd, X2dd])
