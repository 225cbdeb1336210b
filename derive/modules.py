"""What ``generated/`` contains: each module as a list of function specs.

This is the pipeline's last pure step: it calls the derivations and packages their
expressions as `codegen.Function` specs. Nothing here writes files.
"""
from __future__ import annotations

from . import dynamics as dyn
from . import statespace as ss
from .codegen import Function, Module
from .model import CONTACT_LAWS, STATE, X1, Y1, Y2, t, normal_force

__all__ = ["unforced", "dynamics", "all_modules"]

CONTACT_OPTION = (("contact", '{"hertz_damp", "kelvin_voigt"}', "hertz_damp",
                   "contact law: Hertz-Damp, Eq. (1), or linear Kelvin-Voigt (Fig. 16)"),)
STATE_DOCS = {"X1": "tangential displacement [m]",
              "Y1": "tangential velocity X1' [m/s]",
              "X2": "normal penetration into the belt [m]",
              "Y2": "normal velocity X2' [m/s]",
              "t": "time [s]",
              "sgn": "friction direction: -1 (mass slower than the belt), +1, "
                     "or 0 (no friction: the force sticking must supply)"}
IN_CONTACT = {"X2": ("positive", "Eqs. (5)-(8) hold in contact only, X2 > 0")}


def _per_contact(build):
    return {(c,): build(c) for c in CONTACT_LAWS}


def unforced() -> Module:
    """Sect. 4.1: equilibrium, Jacobian and characteristic polynomial (Eqs. 9-12)."""
    eq = _per_contact(ss.equilibrium_eq_9)
    J0 = _per_contact(ss.jacobian_at_equilibrium_eq_11)
    functions = (
        Function("equilibrium", "Equilibrium (X1, Y1, X2, Y2) of the unforced system.",
                 "Eq. (9), solved by SymPy from Eqs. (5)-(8)", "tuple",
                 "X1, Y1, X2, Y2 : ndarray\n    Broadcast to the shape of the inputs.",
                 {k: [v[s] for s in STATE] for k, v in eq.items()}, CONTACT_OPTION),
        Function("jacobian", "Jacobian of the state equations on the sliding branch.",
                 "Eq. (10)", "matrix",
                 "J : ndarray, shape (..., 4, 4)\n    d(X1', Y1', X2', Y2')/d(X1, Y1, X2, Y2).",
                 _per_contact(ss.jacobian_eq_10), CONTACT_OPTION, STATE, STATE_DOCS,
                 IN_CONTACT),
        Function("jacobian_at_equilibrium", "The Jacobian at the equilibrium, J^0.",
                 "Eq. (11)", "matrix", "J0 : ndarray, shape (..., 4, 4)", J0,
                 CONTACT_OPTION),
        Function("charpoly", "Coefficients of the monic characteristic quartic of J^0.",
                 "Eq. (12)", "tuple",
                 "a1, a2, a3, a4 : ndarray\n"
                 "    det(lambda I - J0) = lambda^4 + a1 lambda^3 + a2 lambda^2 + a3 lambda + a4.",
                 {k: ss.charpoly_eq_12(v).all_coeffs()[1:] for k, v in J0.items()},
                 CONTACT_OPTION,
                 notes="mu_s does not appear (the claim below Eq. 12)."),
        Function("eigenvalues", "Eigenvalues of J^0 in closed form.",
                 "Eq. (12), via its exact factorisation", "roots",
                 "lam : complex ndarray, shape (..., 4)\n"
                 "    Tangential pair, then normal pair; for a complex pair the root with\n"
                 "    positive imaginary part first.",
                 {k: ss.block_quadratics(v) for k, v in J0.items()}, CONTACT_OPTION,
                 notes="J^0 is block triangular, so the quartic is the product of a "
                       "tangential and a normal quadratic; their roots are computed "
                       "without cancellation from factored discriminants, which keeps "
                       "full accuracy at a double root (beta1 = 1)."),
    )
    return Module("unforced", """The unforced system at its equilibrium (Sect. 4.1, Eqs. 9-12).

Both contact laws (``contact="hertz_damp"``, Eq. 1, the default; ``"kelvin_voigt"``,
Fig. 16). Every function takes the parameters as keywords.
""", functions)


def dynamics() -> Module:
    """Eq. (4) for simulation: right-hand side, Jacobian, normal force, energy."""
    sd = {"sgn": dyn.sgn}
    state_t = (t,) + dyn.STATE_R
    fns = (
        Function("rhs", "Right-hand side (X1', Y1', X2', Y2') of Eq. (4).",
                 "Eqs. (1)-(4)", "vector", "dstate : ndarray, shape (..., 4)",
                 _per_contact(lambda c: list(dyn.rhs(c))), CONTACT_OPTION, state_t,
                 STATE_DOCS,
                 notes="Friction direction sgn(X1' - Vb) as in Eq. (3); zero normal "
                       "force when X2 <= 0 (loss of contact, Eq. 1)."),
        Function("rhs_branch", "Right-hand side of Eq. (4) with a given friction direction.",
                 "Eqs. (1)-(4)", "vector", "dstate : ndarray, shape (..., 4)",
                 _per_contact(lambda c: list(dyn.rhs(c, dyn.sgn))), CONTACT_OPTION,
                 state_t + (dyn.sgn,), STATE_DOCS,
                 notes="For a simulator that tracks the sliding direction itself: "
                       "with sgn = 0 the second entry is the tangential acceleration "
                       "without friction, whose magnitude against mu_s F_n decides "
                       "whether sticking holds."),
        Function("jacobian_branch", "State Jacobian of `rhs_branch`.",
                 "Eqs. (1)-(4)", "matrix", "J : ndarray, shape (..., 4, 4)",
                 _per_contact(dyn.jacobian), CONTACT_OPTION, state_t + (dyn.sgn,),
                 STATE_DOCS),
        Function("normal_force", "Normal force per unit mass, zero out of contact.",
                 "Eq. (1)", "value", "Fn : ndarray",
                 _per_contact(lambda c: dyn.in_contact(normal_force(c), 0)),
                 CONTACT_OPTION, (dyn.X2r, Y2), STATE_DOCS),
        Function("excitation", "Excitation forces per unit mass (tangential, normal).",
                 "Eq. (4), right-hand side", "tuple", "f_t, f_n : ndarray",
                 {(): list(dyn.excitation())}, (), (t,), STATE_DOCS,
                 notes="alpha_t Omega_t^2 sin(Omega_t t + phase_t) and "
                       "-alpha_n Omega_n^2 sin(Omega_n t + phase_n); by default "
                       "both directions use alpha, Omega and zero phase, as in Eq. (4)."),
        Function("energy", "Mechanical energy per unit mass.",
                 "Eq. (4) (energy balance of Sect. 3)", "value", "E : ndarray",
                 _per_contact(dyn.energy), CONTACT_OPTION, (X1, Y1, dyn.X2r, Y2),
                 STATE_DOCS,
                 notes="Kinetic + tangential spring + contact potential - g X2."),
        Function("power_balance", "Power terms with dE/dt = P_input - P_viscous - P_friction.",
                 "Eq. (4) (energy balance of Sect. 3)", "tuple",
                 "P_input, P_viscous, P_friction : ndarray",
                 _per_contact(lambda c: list(dyn.power_balance(c))), CONTACT_OPTION,
                 state_t + (dyn.sgn,), STATE_DOCS),
    )
    return Module("dynamics", """The full equations of motion, Eq. (4), for simulation.

Loss of contact follows Eq. (1): zero normal force for ``X2 <= 0``. ``rhs`` uses the
sign function of Eq. (3); ``rhs_branch`` and ``jacobian_branch`` take the friction
direction as an argument for an event-driven simulator. ``energy`` and
``power_balance`` give the energy check of Sect. 3.
""", fns)


def all_modules() -> tuple[Module, ...]:
    return unforced(), dynamics()

