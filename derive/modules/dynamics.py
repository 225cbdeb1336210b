"""Eq. (4) for simulation: the spec of generated/dynamics.py."""

from __future__ import annotations

from .. import dynamics as dyn
from ..codegen import FunctionSpec, ModuleSpec
from ..model import X1, Y1, Y2, contact_force, t
from ._shared import (
    CONTACT_TENSION,
    LAWS_FCT,
    STATE_DOCS,
    _per,
)

__all__ = ["build"]


def build() -> ModuleSpec:
    """Eq. (4) for simulation: right-hand side, Jacobian, normal force, energy."""
    state_t = (t,) + dyn.STATE_R
    normal = (t, dyn.X2r, Y2)
    fns = (
        FunctionSpec(
            "rhs",
            "Right-hand side (X1', Y1', X2', Y2') of Eq. (4).",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per(
                lambda f, c, tl: list(dyn.rhs(c, tension=tl, friction=f)),
                "friction",
                "contact",
                "tension",
            ),
            LAWS_FCT,
            state_t,
            STATE_DOCS,
            notes="Friction -mu(|Vr|) sgn(Vr) F with the sign of Eq. (3); zero normal "
            "force when X2 <= 0 (loss of contact, Eq. 1).",
        ),
        FunctionSpec(
            "rhs_branch",
            "Right-hand side of Eq. (4) with a given friction direction.",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per(
                lambda f, c, tl: list(dyn.rhs(c, dyn.sgn, tl, f)), "friction", "contact", "tension"
            ),
            LAWS_FCT,
            state_t + (dyn.sgn,),
            STATE_DOCS,
            notes="For a simulator that tracks the sliding direction itself: "
            "with sgn = 0 the second entry is the tangential acceleration "
            "without friction, whose magnitude against mu(0) F_n decides "
            "whether sticking holds. On branch sgn the friction coefficient is "
            "mu(sgn Vr), |Vr| on the branch.",
            bind=True,
        ),
        FunctionSpec(
            "jacobian_branch",
            "State Jacobian of `rhs_branch`.",
            "Eqs. (1)-(4)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)",
            _per(
                lambda f, c, tl: dyn.jacobian(c, dyn.sgn, tl, f), "friction", "contact", "tension"
            ),
            LAWS_FCT,
            state_t + (dyn.sgn,),
            STATE_DOCS,
        ),
        FunctionSpec(
            "normal_force",
            "Normal force per unit mass, zero out of contact.",
            "Eq. (1)",
            "value",
            "Fn : ndarray",
            _per(lambda c, tl: dyn.in_contact(contact_force(c, tl), 0), "contact", "tension"),
            CONTACT_TENSION,
            (dyn.X2r, Y2),
            STATE_DOCS,
            bind=True,
        ),
        FunctionSpec(
            "friction_force",
            "Friction force of the belt on the mass per unit mass while sliding.",
            "Eqs. (2)-(3)",
            "value",
            "Ff : ndarray",
            _per(lambda f, c, tl: dyn.friction_force(c, tl, f), "friction", "contact", "tension"),
            LAWS_FCT,
            (Y1, dyn.X2r, Y2, dyn.sgn),
            STATE_DOCS,
            notes="-mu(sgn Vr) sgn F_n, zero out of contact: the friction term of Eq. (4) "
            "on a slip branch (positive along the belt). While sticking the force that "
            "holds the mass is -a_free (`free_acceleration`). Coulomb's law does not use "
            "X1'; every law takes it, so that one call serves all.",
        ),
        FunctionSpec(
            "normal_rhs",
            "Right-hand side (X2', Y2') of the normal equation alone.",
            "Eq. (4), second row",
            "vector",
            "dnormal : ndarray, shape (..., 2)",
            _per(lambda c, tl: list(dyn.normal_rhs(c, tl)), "contact", "tension"),
            CONTACT_TENSION,
            normal,
            STATE_DOCS,
            notes="The normal equation contains neither X1, X1', Vb nor a friction "
            "parameter (the one-way coupling of Eq. 4; beltmdsm.generated.capabilities).",
            bind=True,
        ),
        FunctionSpec(
            "normal_jacobian",
            "Jacobian of `normal_rhs` with respect to (X2, Y2).",
            "Eq. (4), second row",
            "matrix",
            "J : ndarray, shape (..., 2, 2)",
            _per(lambda c, tl: dyn.normal_jacobian(c, tl), "contact", "tension"),
            CONTACT_TENSION,
            normal,
            STATE_DOCS,
            notes="The variational equation of the normal motion, for the "
            "normal block of the monodromy matrix.",
            bind=True,
        ),
        FunctionSpec(
            "free_acceleration",
            "Tangential acceleration without friction.",
            "Eq. (4), first row",
            "value",
            "a_free : ndarray",
            {(): dyn.free_acceleration()},
            (),
            (t, X1, Y1),
            STATE_DOCS,
            notes="f_t - 2 beta1 omega1 X1' - omega1^2 X1; sticking holds while "
            "|a_free| <= mu_st F_n, mu_st the law's static bound (mu_s for every "
            "shipped friction law; static_kinetic slips at mu_k below it).",
            bind=True,
        ),
        FunctionSpec(
            "excitation",
            "Excitation forces per unit mass (tangential, normal).",
            "Eq. (4), right-hand side",
            "tuple",
            "f_t, f_n : ndarray",
            {(): list(dyn.excitation())},
            (),
            (t,),
            STATE_DOCS,
            notes="alpha_t Omega_t^2 sin(Omega_t t + phase_t) and "
            "-alpha_n Omega_n^2 sin(Omega_n t + phase_n); by default "
            "both directions use alpha, Omega and zero phase, as in Eq. (4).",
            bind=True,
        ),
        FunctionSpec(
            "energy",
            "Mechanical energy per unit mass.",
            "Eq. (4) (energy balance of Sect. 3)",
            "value",
            "E : ndarray",
            _per(lambda c, tl: dyn.energy(c), "contact", "tension"),
            CONTACT_TENSION,
            (X1, Y1, dyn.X2r, Y2),
            STATE_DOCS,
            notes="Kinetic + tangential spring + contact potential - g X2. The same "
            "for both tension laws (the clip is booked in power_balance).",
            bind=True,
        ),
        FunctionSpec(
            "power_balance",
            "Power terms with dE/dt = P_input - P_viscous - P_friction.",
            "Eq. (4) (energy balance of Sect. 3)",
            "tuple",
            "P_input, P_viscous, P_friction : ndarray",
            _per(
                lambda f, c, tl: list(dyn.power_balance(c, tension=tl, friction=f)),
                "friction",
                "contact",
                "tension",
            ),
            LAWS_FCT,
            state_t + (dyn.sgn,),
            STATE_DOCS,
            bind=True,
        ),
    )
    return ModuleSpec(
        "dynamics",
        """The full equations of motion, Eq. (4), for simulation.

Loss of contact follows Eq. (1): zero normal force for ``X2 <= 0``. ``rhs`` uses the
sign function of Eq. (3); ``rhs_branch`` and ``jacobian_branch`` take the friction
direction as an argument for an event-driven simulator. ``energy`` and
``power_balance`` give the energy check of Sect. 3. ``tension=`` chooses Eq. (1) as
printed or a contact that cannot pull (docs/modelling.md#tension), ``friction=`` the
friction law, ``contact=`` the contact law (derive/laws.py). ``bind_<name>``
returns a function's scalar kernel with the parameters checked once, for the
runtime's inner loops.
""",
        fns,
    )
