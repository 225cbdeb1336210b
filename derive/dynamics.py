"""The full equations of motion for simulation: Eq. (4) with loss of contact and energy.

Eq. (1) gives the normal force in contact (``X2 > 0``) and zero in flight. Each
quantity is derived on both branches and joined entrywise, so the Jacobian of the
simulated system is the derivative of each branch, not of a kink. The friction
direction is either ``sgn(X1' - Vb)`` (Eq. 3) or a given value ``sgn`` (the
simulator's branch; ``sgn = 0`` gives the force that sticking must supply). The
friction, contact and tension laws come from the registry (`beltmdsm.derive.laws`,
`beltmdsm.derive.model`): the coefficient ``mu(|Vr|)`` of the friction law, the contact law's
force, and Eq. (1) as printed or a contact that cannot pull.

The mechanical energy and the power balance let a simulation check itself (the
paper verifies its simulations with an energy balance, Sect. 3):
``dE/dt = P_input - P_viscous - P_friction``.

The one-way coupling of Eq. (4) is kept visible: `normal_rhs` and `normal_jacobian`
are the normal equation alone (it does not contain the tangential state), and
`free_acceleration` is the tangential acceleration without friction.
"""

from __future__ import annotations

import sympy as sp

from . import laws
from .model import (
    X1,
    X2,
    Y1,
    Y2,
    P,
    contact_force,
    contact_potential,
    excitation,
    friction_coefficient,
    normal_force,
)

__all__ = [
    "X2r",
    "sgn",
    "in_contact",
    "accelerations",
    "rhs",
    "jacobian",
    "free_acceleration",
    "normal_rhs",
    "normal_jacobian",
    "friction_force",
    "energy",
    "power_balance",
]

#: Penetration as a real number: negative in flight.
X2r = sp.Symbol("X2", real=True)
#: Friction direction chosen by the simulator.
sgn = sp.Symbol("sgn", real=True)
STATE_R = (X1, Y1, X2r, Y2)
DEFAULT = {option: laws.default(option) for option in laws.OPTIONS}


def in_contact(expr_contact, expr_flight):
    """Join a contact-branch expression (in positive ``X2``) and a flight branch.

    ``X2`` enters the contact branch as ``max(X2, 0)``: numpy evaluates both
    branches of a select, and ``X2**(3/2)`` of a negative number would warn.
    """
    contact = sp.sympify(expr_contact).subs(X2, sp.Max(X2r, 0))
    return sp.Piecewise((contact, X2r > 0), (sp.sympify(expr_flight), True))


def free_acceleration() -> sp.Expr:
    """Tangential acceleration without friction: ``f_t - 2 beta1 omega1 X1' - omega1^2 X1``.

    Its size against ``mu_s F_n`` decides whether sticking holds (Eq. 4 with the
    friction set-valued at ``Vr = 0``).
    """
    b1, w1 = P["beta1"], P["omega1"]
    return -2 * b1 * w1 * Y1 - w1**2 * X1 + excitation()[0]


def accelerations(
    contact: str = DEFAULT["contact"],
    direction=None,
    flight: bool = False,
    tension: str = DEFAULT["tension"],
    friction: str = DEFAULT["friction"],
):
    """``(X1'', X2'')`` of Eq. (4) in contact (positive ``X2``) or in flight."""
    Fn = 0 if flight else contact_force(contact, tension)
    f_n = excitation()[1]
    mu = friction_coefficient(friction, direction)
    return sp.Matrix([free_acceleration() - mu * Fn, -Fn + P["g"] + f_n])


def rhs(
    contact: str = DEFAULT["contact"],
    direction=None,
    tension: str = DEFAULT["tension"],
    friction: str = DEFAULT["friction"],
) -> sp.Matrix:
    """Right-hand side ``(X1', Y1', X2', Y2')`` of Eq. (4) with loss of contact."""
    c = accelerations(contact, direction, tension=tension, friction=friction)
    f = accelerations(contact, direction, flight=True, friction=friction)
    return sp.Matrix([Y1, in_contact(c[0], f[0]), Y2, in_contact(c[1], f[1])])


def jacobian(
    contact: str = DEFAULT["contact"],
    direction=sgn,
    tension: str = DEFAULT["tension"],
    friction: str = DEFAULT["friction"],
) -> sp.Matrix:
    """State Jacobian of `rhs` on a fixed friction branch, branch by branch."""

    def branch(flight):
        a = accelerations(contact, direction, flight, tension, friction)
        return sp.Matrix([Y1, a[0], Y2, a[1]]).jacobian((X1, Y1, X2, Y2))

    c, f = branch(False), branch(True)
    return sp.Matrix(4, 4, lambda i, j: in_contact(c[i, j], f[i, j]))


def normal_rhs(contact: str = DEFAULT["contact"], tension: str = DEFAULT["tension"]) -> sp.Matrix:
    """``(X2', Y2')`` of Eq. (4): the normal equation, free of the tangential state."""
    return rhs(contact, 0, tension)[2:, 0]


def normal_jacobian(
    contact: str = DEFAULT["contact"], tension: str = DEFAULT["tension"]
) -> sp.Matrix:
    """Jacobian of `normal_rhs` with respect to ``(X2, Y2)`` (its variational equation)."""
    return jacobian(contact, 0, tension)[2:, 2:]


def friction_force(
    contact: str = DEFAULT["contact"],
    tension: str = DEFAULT["tension"],
    friction: str = DEFAULT["friction"],
) -> sp.Expr:
    """``-mu(|Vr|) sgn F``, zero out of contact: the friction term of Eq. (4) on branch ``sgn``."""
    return in_contact(-friction_coefficient(friction, sgn) * contact_force(contact, tension), 0)


def energy(contact: str = DEFAULT["contact"]) -> sp.Expr:
    """Mechanical energy per unit mass: kinetic, spring, contact and gravity.

    ``X2`` points into the belt, so gravity's potential is ``-g X2``. The tension
    law does not change it: the clip removes part of the force, and
    `power_balance` books that part with the contact damping.
    """
    w1, g = P["omega1"], P["g"]
    return (
        Y1**2 / 2
        + Y2**2 / 2
        + w1**2 * X1**2 / 2
        + in_contact(contact_potential(contact), 0)
        - g * X2r
    )


def power_balance(
    contact: str = DEFAULT["contact"],
    direction=sgn,
    tension: str = DEFAULT["tension"],
    friction: str = DEFAULT["friction"],
):
    """``(P_input, P_viscous, P_friction)`` per unit mass.

    ``P_input`` is the work rate of the excitation, ``P_viscous`` that of the
    tangential dashpot and of the contact force beyond its elastic part (the
    contact damping; with ``tension="clipped"`` also the elastic force the clip
    removes, which is then ``>= 0``), ``P_friction = mu sgn F_n X1'`` the rate at which
    friction takes energy from the mass (it includes the belt's work). The split is
    checked against ``dE/dt`` along `rhs` by the tests.
    """
    b1, w1 = P["beta1"], P["omega1"]
    f_t, f_n = excitation()
    elastic = normal_force(contact, X2, 0)
    Fc = contact_force(contact, tension)
    p_input = f_t * Y1 + f_n * Y2
    p_viscous = 2 * b1 * w1 * Y1**2 + in_contact((Fc - elastic) * Y2, 0)
    p_friction = friction_coefficient(friction, direction) * in_contact(Fc, 0) * Y1
    return p_input, p_viscous, p_friction
