"""The model: symbols, contact laws, friction, excitation and the equations of motion.

Implements Eqs. (1)-(4) of the paper. The equations of motion are assembled from
parts so that each part is a choice:

* the contact law: Hertz-Damp, Eq. (1) (``"hertz_damp"``), or the linear
  Kelvin-Voigt law of Fig. 16 (``"kelvin_voigt"``);
* the tension law: Eq. (1) as printed, whose force turns negative (tensile) when
  the damping term outweighs the stiffness term (``"allowed"``), or a contact that
  cannot pull, ``max(F, 0)`` (``"clipped"``; docs/modelling.md#tension);
* the friction direction: ``sgn(Vr)`` as in Eq. (3), or a fixed branch
  (``-1`` while the mass is slower than the belt, the branch of Eqs. 5-8);
* the excitation: amplitude, frequency and phase per direction (Figs. 14-15),
  whose defaults reduce to Eq. (4).

Everything here is a pure function returning SymPy objects.
"""

from __future__ import annotations

import sympy as sp

from .parameters import PARAMETERS

__all__ = [
    "CONTACT_LAWS",
    "TENSION_LAWS",
    "P",
    "t",
    "X1",
    "Y1",
    "X2",
    "Y2",
    "STATE",
    "lam",
    "normal_force",
    "contact_force",
    "contact_potential",
    "friction_coefficient",
    "excitation",
    "equal_excitation",
    "equations_of_motion",
]

CONTACT_LAWS = ("hertz_damp", "kelvin_voigt")
TENSION_LAWS = ("allowed", "clipped")

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
lam = sp.Symbol("lambda")


def normal_force(contact: str = "hertz_damp", X2=X2, Y2=Y2) -> sp.Expr:
    """Mass-normalised normal force in contact, Eq. (1) divided by ``M``.

    ``hertz_damp``: ``(omega2^2 + 2 beta2 omega2 X2') X2^(3/2)``;
    ``kelvin_voigt``: ``omega2^2 X2 + 2 beta2 omega2 X2'`` (Fig. 16).
    Both vanish for ``X2 <= 0``; the caller handles loss of contact.
    """
    b2, w2 = P["beta2"], P["omega2"]
    if contact == "hertz_damp":
        return (w2**2 + 2 * b2 * w2 * Y2) * X2 ** sp.Rational(3, 2)
    if contact == "kelvin_voigt":
        return w2**2 * X2 + 2 * b2 * w2 * Y2
    raise ValueError(f"contact must be one of {CONTACT_LAWS}, got {contact!r}")


def contact_force(contact: str = "hertz_damp", tension: str = "allowed", X2=X2, Y2=Y2) -> sp.Expr:
    """The normal force in contact under a tension law.

    ``allowed``: Eq. (1) as printed (`normal_force`), negative when the damping term
    outweighs the stiffness term. ``clipped``: ``max(F, 0)``, a contact that cannot
    pull; where Eq. (1) would be tensile the surfaces separate and no force acts.
    The clipped force is continuous where Eq. (1) crosses zero, so the clip is a kink
    of the vector field, not a jump.
    """
    F = normal_force(contact, X2, Y2)
    if tension == "allowed":
        return F
    if tension == "clipped":
        return sp.Piecewise((F, F > 0), (0, True))
    raise ValueError(f"tension must be one of {TENSION_LAWS}, got {tension!r}")


def contact_potential(contact: str = "hertz_damp", X2=X2) -> sp.Expr:
    """Potential of the elastic part of the normal force, per unit mass.

    Derived by integration so that it stays consistent with `normal_force`.
    """
    s = sp.Dummy("s", positive=True)
    elastic = normal_force(contact, s, 0)
    return sp.integrate(elastic, (s, 0, X2))


def friction_coefficient(direction=None) -> sp.Expr:
    """Friction coefficient ``mu_s sgn(Vr)``, Eq. (3), ``Vr = X1' - Vb``.

    ``direction`` replaces ``sgn(Vr)`` by a fixed branch (``-1``: the mass is slower
    than the belt, as in Eqs. 5-8); ``None`` keeps the sign function.
    """
    sgn = sp.sign(Y1 - P["Vb"]) if direction is None else sp.sympify(direction)
    return P["mu_s"] * sgn


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
    contact: str = "hertz_damp", direction=None, forced: bool = True, general: bool = True
) -> sp.Matrix:
    """Accelerations ``(X1'', X2'')`` of Eq. (4), solved for (the mass matrix is I).

    Parameters
    ----------
    contact : {"hertz_damp", "kelvin_voigt"}
    direction : None, -1 or +1
        Friction direction; see `friction_coefficient`.
    forced : bool
        ``False`` drops the excitation (the unforced system of Sect. 4.1).
    general : bool
        Per-direction excitation (``True``) or the single one of Eq. (4).
    """
    b1, w1, g = P["beta1"], P["omega1"], P["g"]
    Fn = normal_force(contact)
    f_t, f_n = excitation(general) if forced else (0, 0)
    X1dd = -2 * b1 * w1 * Y1 - w1**2 * X1 - friction_coefficient(direction) * Fn + f_t
    X2dd = -Fn + g + f_n
    return sp.Matrix([X1dd, X2dd])
