"""What ``generated/`` contains: each module as a list of function specs.

This is the pipeline's last pure step: it calls the derivations and packages their
expressions as `codegen.FunctionSpec` specs. Nothing here writes files.
"""

from __future__ import annotations

import sympy as sp

from . import correlation as cr
from . import dynamics as dyn
from . import fit as ft
from . import friction as fr
from . import hybrid as hy
from . import mdsm
from . import oscillator as osc
from . import stability as st
from . import statespace as ss
from .codegen import FunctionSpec, ModuleSpec
from .model import CONTACT_LAWS, STATE, TENSION_LAWS, X1, Y1, Y2, P, contact_force, t

__all__ = [
    "unforced",
    "dynamics",
    "fit",
    "friction",
    "stability",
    "correlation",
    "hybrid",
    "oscillator",
    "all_modules",
]

CONTACT_OPTION = (
    (
        "contact",
        '{"hertz_damp", "kelvin_voigt"}',
        "hertz_damp",
        "contact law: Hertz-Damp, Eq. (1), or linear Kelvin-Voigt (Fig. 16)",
    ),
)
TENSION_OPTION = (
    (
        "tension",
        '{"allowed", "clipped"}',
        "allowed",
        "Eq. (1) as printed, tensile when its damping term outweighs its "
        "stiffness term, or max(F, 0), a contact that cannot pull "
        "(docs/modelling.md#tension)",
    ),
)
CONTACT_TENSION = CONTACT_OPTION + TENSION_OPTION
STATE_DOCS = {
    "X1": "tangential displacement [m]",
    "Y1": "tangential velocity X1' [m/s]",
    "X2": "normal penetration into the belt [m]",
    "Y2": "normal velocity X2' [m/s]",
    "t": "time [s]",
    "sgn": "friction direction: -1 (mass slower than the belt), +1, "
    "or 0 (no friction: the force sticking must supply)",
}
IN_CONTACT = {"X2": ("positive", "Eqs. (5)-(8) hold in contact only, X2 > 0")}


def _per_contact(build):
    return {(c,): build(c) for c in CONTACT_LAWS}


def _per_contact_tension(build):
    return {(c, tl): build(c, tl) for c in CONTACT_LAWS for tl in TENSION_LAWS}


def unforced() -> ModuleSpec:
    """Sect. 4.1: equilibrium, Jacobian and characteristic polynomial (Eqs. 9-12)."""
    eq = _per_contact(ss.equilibrium_eq_9)
    J0 = _per_contact(ss.jacobian_at_equilibrium_eq_11)
    functions = (
        FunctionSpec(
            "equilibrium",
            "Equilibrium (X1, Y1, X2, Y2) of the unforced system.",
            "Eq. (9), solved by SymPy from Eqs. (5)-(8)",
            "tuple",
            "X1, Y1, X2, Y2 : ndarray\n    Broadcast to the shape of the inputs.",
            {k: [v[s] for s in STATE] for k, v in eq.items()},
            CONTACT_OPTION,
        ),
        FunctionSpec(
            "jacobian",
            "Jacobian of the state equations on the sliding branch.",
            "Eq. (10)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)\n    d(X1', Y1', X2', Y2')/d(X1, Y1, X2, Y2).",
            _per_contact(ss.jacobian_eq_10),
            CONTACT_OPTION,
            STATE,
            STATE_DOCS,
            IN_CONTACT,
        ),
        FunctionSpec(
            "jacobian_at_equilibrium",
            "The Jacobian at the equilibrium, J^0.",
            "Eq. (11)",
            "matrix",
            "J0 : ndarray, shape (..., 4, 4)",
            J0,
            CONTACT_OPTION,
        ),
        FunctionSpec(
            "charpoly",
            "Coefficients of the monic characteristic quartic of J^0.",
            "Eq. (12)",
            "tuple",
            "a1, a2, a3, a4 : ndarray\n"
            "    det(lambda I - J0) = lambda^4 + a1 lambda^3 + a2 lambda^2 + a3 lambda + a4.",
            {k: ss.charpoly_eq_12(v).all_coeffs()[1:] for k, v in J0.items()},
            CONTACT_OPTION,
            notes="mu_s does not appear (the claim below Eq. 12).",
        ),
        FunctionSpec(
            "eigenvalues",
            "Eigenvalues of J^0 in closed form.",
            "Eq. (12), via its exact factorisation",
            "roots",
            "lam : complex ndarray, shape (..., 4)\n"
            "    Tangential pair, then normal pair; for a complex pair the root with\n"
            "    positive imaginary part first.",
            {k: ss.block_quadratics(v) for k, v in J0.items()},
            CONTACT_OPTION,
            notes="J^0 is block triangular, so the quartic is the product of a "
            "tangential and a normal quadratic; their roots are computed "
            "without cancellation from factored discriminants, which keeps "
            "full accuracy at a double root (beta1 = 1).",
        ),
    )
    return ModuleSpec(
        "unforced",
        """The unforced system at its equilibrium (Sect. 4.1, Eqs. 9-12).

Both contact laws (``contact="hertz_damp"``, Eq. 1, the default; ``"kelvin_voigt"``,
Fig. 16). Every function takes the parameters as keywords.
""",
        functions,
    )


def dynamics() -> ModuleSpec:
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
            _per_contact_tension(lambda c, tl: list(dyn.rhs(c, tension=tl))),
            CONTACT_TENSION,
            state_t,
            STATE_DOCS,
            notes="Friction direction sgn(X1' - Vb) as in Eq. (3); zero normal "
            "force when X2 <= 0 (loss of contact, Eq. 1).",
        ),
        FunctionSpec(
            "rhs_branch",
            "Right-hand side of Eq. (4) with a given friction direction.",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per_contact_tension(lambda c, tl: list(dyn.rhs(c, dyn.sgn, tl))),
            CONTACT_TENSION,
            state_t + (dyn.sgn,),
            STATE_DOCS,
            notes="For a simulator that tracks the sliding direction itself: "
            "with sgn = 0 the second entry is the tangential acceleration "
            "without friction, whose magnitude against mu_s F_n decides "
            "whether sticking holds.",
            bind=True,
        ),
        FunctionSpec(
            "jacobian_branch",
            "State Jacobian of `rhs_branch`.",
            "Eqs. (1)-(4)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)",
            _per_contact_tension(lambda c, tl: dyn.jacobian(c, dyn.sgn, tl)),
            CONTACT_TENSION,
            state_t + (dyn.sgn,),
            STATE_DOCS,
        ),
        FunctionSpec(
            "normal_force",
            "Normal force per unit mass, zero out of contact.",
            "Eq. (1)",
            "value",
            "Fn : ndarray",
            _per_contact_tension(lambda c, tl: dyn.in_contact(contact_force(c, tl), 0)),
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
            _per_contact_tension(
                lambda c, tl: dyn.in_contact(
                    -dyn.friction_coefficient(dyn.sgn) * contact_force(c, tl), 0
                )
            ),
            CONTACT_TENSION,
            (dyn.X2r, Y2, dyn.sgn),
            STATE_DOCS,
            notes="-mu_s sgn F_n, zero out of contact: the friction term of Eq. (4) on a "
            "slip branch (positive along the belt). While sticking the force that holds "
            "the mass is -a_free (`free_acceleration`).",
        ),
        FunctionSpec(
            "normal_rhs",
            "Right-hand side (X2', Y2') of the normal equation alone.",
            "Eq. (4), second row",
            "vector",
            "dnormal : ndarray, shape (..., 2)",
            _per_contact_tension(lambda c, tl: list(dyn.normal_rhs(c, tl))),
            CONTACT_TENSION,
            normal,
            STATE_DOCS,
            notes="The normal equation contains neither X1, X1', Vb nor mu_s "
            "(the one-way coupling of Eq. 4).",
            bind=True,
        ),
        FunctionSpec(
            "normal_jacobian",
            "Jacobian of `normal_rhs` with respect to (X2, Y2).",
            "Eq. (4), second row",
            "matrix",
            "J : ndarray, shape (..., 2, 2)",
            _per_contact_tension(lambda c, tl: dyn.normal_jacobian(c, tl)),
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
            "|a_free| <= mu_s F_n.",
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
            _per_contact_tension(lambda c, tl: dyn.energy(c)),
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
            _per_contact_tension(lambda c, tl: list(dyn.power_balance(c, tension=tl))),
            CONTACT_TENSION,
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
printed or a contact that cannot pull (docs/modelling.md#tension). ``bind_<name>``
returns a function's scalar kernel with the parameters checked once, for the
runtime's inner loops.
""",
        fns,
    )


def hybrid() -> ModuleSpec:
    """Eq. (4) as a hybrid system: mode fields, switching surfaces, saltation matrices."""
    state_t = (t,) + hy.STATE
    mode_doc = {
        **STATE_DOCS,
        "mode": "mode code (MODE_CODES): -1 slip_back, 0 stick, "
        "+1 slip_forward, 2 flight, 3 separated",
    }
    surfaces_doc = (
        "h : tuple of ndarray\n    One value per switching surface, in the order of SURFACES."
    )
    salt = {}
    for before, after, surface in hy.transitions():
        for c in CONTACT_LAWS:
            salt[(before, after, surface, c)] = hy.saltation(before, after, surface, c)
    names = sorted({k for k in hy.MODE_CODES})
    salt_opts = (
        ("before", "str", "slip_back", "mode before the switch"),
        ("after", "str", "slip_forward", "mode after the switch"),
        ("surface", "str", "relative_velocity", "the surface crossed (SURFACES)"),
    ) + CONTACT_OPTION
    fns = (
        FunctionSpec(
            "vector_field",
            "Vector field (X1', Y1', X2', Y2') of one mode of Eq. (4).",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per_contact(lambda c: list(hy.vector_field(c))),
            CONTACT_OPTION,
            state_t + (hy.mode,),
            mode_doc,
            notes="Each field is smooth on the whole state space: the contact modes "
            "use the unclipped force of Eq. (1) (with max(X2, 0)), stick holds "
            "X1' = Vb, flight and separated are free of contact.",
            bind=True,
        ),
        FunctionSpec(
            "response_field",
            "Normal motion and the tangential response to its contact force.",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)\n    Derivative of (z, z', X2, X2').",
            _per_contact(lambda c: list(hy.response_field(c)[0])),
            CONTACT_OPTION,
            (t,) + hy.response_field("hertz_damp")[1] + hy.STATE[2:] + (hy.mode,),
            {
                **mode_doc,
                "z": "tangential response to the contact force [m]",
                "v": "its velocity [m/s]",
            },
            notes="z'' + 2 beta1 omega1 z' + omega1^2 z = F(mode) from rest, beside "
            "the normal equation: the normal motion does not depend on the "
            "tangential one, so the superposition integrator integrates this "
            "once.",
            bind=True,
        ),
        FunctionSpec(
            "surfaces",
            "Switching functions h(t, x) of the hybrid system.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per_contact(lambda c: [hy.surfaces(c)[n] for n in hy.SURFACES]),
            CONTACT_OPTION,
            state_t,
            STATE_DOCS,
            notes="relative_velocity Y1 - Vb; stick_forward, stick_back "
            "mu_s F -+ a_free; penetration X2; contact_force: the sign of F "
            "(F over its factors positive in contact).",
            bind=True,
        ),
        FunctionSpec(
            "surface_scales",
            "Rounding scale of each switching function.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per_contact(lambda c: [hy.surface_scales(c)[n] for n in hy.SURFACES]),
            CONTACT_OPTION,
            state_t,
            STATE_DOCS,
            notes="The sum of the absolute values of the terms of h: a computed h "
            "is within a few ulps of it, so a sign decision at a tie uses a "
            "tolerance proportional to it.",
            bind=True,
        ),
        FunctionSpec(
            "surface_rates",
            "Rates dh/dt of the switching functions along a mode.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per_contact(lambda c: [hy.surface_rates(c)[n] for n in hy.SURFACES]),
            CONTACT_OPTION,
            state_t + (hy.mode,),
            mode_doc,
            notes="dh/dt = partial h / partial t + grad h . f(mode): which side of a "
            "surface the field of a mode points to (Filippov's rule), and the "
            "denominator of the saltation matrix.",
            bind=True,
        ),
        FunctionSpec(
            "saltation",
            "Saltation matrix of a switch: the jump of the variational solution.",
            "Eqs. (1)-(4)",
            "matrix",
            "S : ndarray, shape (..., 4, 4)",
            salt,
            salt_opts,
            state_t,
            STATE_DOCS,
            notes="S = I + (f+ - f-) n^T / (dh/dt)-, n = grad h, evaluated at the "
            "state on the surface. It diverges as (dh/dt)- -> 0 (grazing). "
            "Valid (before, after, surface) triples: TRANSITIONS.",
            bind=True,
        ),
    )
    guards = {tl: {m: tuple(g) for m, g in sorted(gs.items())} for tl, gs in hy.GUARDS.items()}
    constants = (
        (
            "MODE_CODES",
            dict(sorted(hy.MODE_CODES.items(), key=lambda kv: kv[1])),
            "Integer code of each mode; the slip codes are sgn(Vr) of Eq. (3).",
        ),
        ("FIELDS", {m: hy.FIELDS[m] for m in names}, "The vector field of each mode."),
        ("SURFACES", hy.SURFACES, "The switching surfaces, in the order of `surfaces`."),
        ("DECIDE_SLIP", hy.DECIDE_SLIP, "Guard target: Filippov's rule at Vr = 0."),
        ("DECIDE_CONTACT", hy.DECIDE_CONTACT, "Guard target: entering contact."),
        (
            "GUARDS",
            guards,
            "Per tension law: mode -> ((surface, crossing direction, target), ...).",
        ),
        ("TRANSITIONS", hy.transitions(), "Every (before, after, surface) of `saltation`."),
    )
    return ModuleSpec(
        "hybrid",
        """Eq. (4) as a hybrid system (derive/hybrid.py).

Modes with smooth vector fields (`vector_field`, by mode code), the switching surfaces
between them (`surfaces`, with rounding scales and rates along a mode), the guards of
each tension law (`GUARDS`: which surface ends which mode, crossed in which direction,
and what follows) and the saltation matrices of the switches (`saltation`), which the
Floquet analysis of the periodic response needs.
""",
        fns,
        constants,
    )


def oscillator() -> ModuleSpec:
    """The tangential oscillator in closed form: state-transition matrix, forced response."""
    docs = {"tau": "time since the switch [s], >= 0", **STATE_DOCS}
    fns = (
        FunctionSpec(
            "state_transition",
            "State-transition matrix expm(A tau) of the tangential oscillator.",
            "Eq. (4), first row",
            "matrix",
            "Phi : ndarray, shape (..., 2, 2)\n    (X1, X1')(t0 + tau) = Phi (X1, "
            "X1')(t0) without forcing.",
            {(): osc.state_transition()},
            (),
            (osc.tau,),
            docs,
            notes="Under-, over- and critically damped closed forms; exact at "
            "beta1 = 1, no overflow for long tau (derive/oscillator.py).",
            bind=True,
        ),
        FunctionSpec(
            "excitation_response",
            "Response (X1, X1') to the tangential excitation from rest at t = 0.",
            "Eq. (4), first row",
            "tuple",
            "X1, Y1 : ndarray",
            {(): list(osc.excitation_response())},
            (),
            (t,),
            docs,
            notes="The periodic response minus the free motion that cancels its "
            "initial value. Not finite at undamped resonance (beta1 = 0, "
            "Omega_t = omega1).",
            bind=True,
        ),
    )
    return ModuleSpec(
        "oscillator",
        """The tangential oscillator of Eq. (4) in closed form.

Between two switches the tangential motion is linear: the state-transition matrix
carries the state at the switch, the excitation response and the response to the
contact force (integrated by the runtime) add to it (derive/oscillator.py).
""",
        fns,
    )


def fit() -> ModuleSpec:
    """Eqs. (16)-(17): the least-squares polynomial of X2^(3/2) and its exact errors."""
    degree = (("degree", "int, 1 to 8", 3, "polynomial degree; 3 gives Eq. (17)"),)
    arg = (ft.X2max,)
    docs = {"X2max": "upper end of the fitted range [0, X2max] [m]"}

    def per_degree(build):
        return {(n,): build(n) for n in ft.DEGREES}

    functions = (
        FunctionSpec(
            "coefficients",
            "Coefficients (c0, ..., c_degree) of the L2 fit of X2^(3/2).",
            "Eqs. (16)-(17)",
            "tuple",
            "c : tuple of ndarray\n    X2^(3/2) ~ sum_k c_k X2^k on [0, X2max].",
            per_degree(lambda n: list(ft.coefficients_eq_17(n))),
            degree,
            arg,
            docs,
            notes="Exact rationals times powers of X2max, from the continuous "
            "normal equations (Hilbert matrix) solved by SymPy.",
        ),
        FunctionSpec(
            "max_error",
            "Largest absolute error of the fit on [0, X2max], exact.",
            "Eq. (17) (the paper: 'about 1e-2')",
            "value",
            "err : ndarray\n    max |X2^(3/2) - fit| (for degree 3: 8/1155 X2max^(3/2)).",
            per_degree(lambda n: ft.fit_error(n).max_abs),
            degree,
            arg,
            docs,
        ),
        FunctionSpec(
            "max_error_location",
            "Where the largest error of the fit sits.",
            "Eq. (17)",
            "value",
            "X2 : ndarray",
            per_degree(lambda n: ft.fit_error(n).argmax),
            degree,
            arg,
            docs,
        ),
        FunctionSpec(
            "rms_error",
            "Root-mean-square error of the fit on [0, X2max], exact.",
            "Eq. (17)",
            "value",
            "rms : ndarray",
            per_degree(lambda n: ft.fit_error(n).rms),
            degree,
            arg,
            docs,
        ),
        FunctionSpec(
            "mdsm_fit_range",
            "The fitted range for the MDSM: X2^0 plus the fast normal amplitude.",
            "Eqs. (9), (14), (16)",
            "value",
            "X2max : ndarray",
            _per_contact(mdsm.x2max),
            CONTACT_OPTION,
            notes="The fast normal motion is the linear response of the normal block "
            "of Eq. (11) to the normal excitation.",
        ),
    )
    return ModuleSpec(
        "fit",
        """Least-squares polynomial fit of X2^(3/2) on [0, X2max] (Eqs. 16-17).

Degrees 1 to 8, exact in X2max. ``X2max`` comes from the scene (for the MDSM: the
slow penetration plus the amplitude of the fast normal motion), not a constant.
""",
        functions,
    )


def friction() -> ModuleSpec:
    """Eqs. (23)-(25) and the two readings of V_hat."""
    mu, Vh, Vb = P["mu_s"], P["Vhat"], P["Vb"]
    docs = {
        "Vr": "relative velocity X1' - Vb [m/s]",
        "Vb": "belt speed [m/s]; the equilibrium has Vr = -Vb",
        "Vhat": "velocity amplitude of Eq. (23) [m/s]",
        "mu_s": "Coulomb friction coefficient",
    }
    vhat_opts = (
        (
            "model",
            '{"tangential", "coupled"}',
            "tangential",
            "reading of V_hat (docs/modelling.md#vhat): the tangential oscillator alone, "
            "or the 2-DOF system linearised at equilibrium",
        ),
    ) + CONTACT_OPTION
    functions = (
        FunctionSpec(
            "mu_bar",
            "Effective friction coefficient, with the sign of Vr.",
            "Eq. (23)",
            "value",
            "mu_bar : ndarray",
            {(): fr.mu_bar_eq_23()},
            (),
            (fr.Vr, Vh, mu),
            docs,
        ),
        FunctionSpec(
            "mu_bar0",
            "Effective friction at the slow equilibrium, mu_bar(-Vb).",
            "Eq. (25), mu_bar^0",
            "value",
            "mu_bar0 : ndarray\n    Negative: the mass is slower than the belt.",
            {(): fr.mu_bar0_eq_25()},
            (),
            (Vb, Vh, mu),
            docs,
        ),
        FunctionSpec(
            "mu_bar_slope",
            "Slope of the effective friction at the equilibrium.",
            "Eqs. (24)-(25)",
            "value",
            "slope : ndarray\n    2 mu_s / (pi sqrt((Vhat - Vb)(Vhat + Vb))) for Vb < Vhat;\n"
            "    +inf at Vb = Vhat exactly; 0 for Vb > Vhat.",
            {(): fr.mu_bar_slope_eq_25()},
            (),
            (Vb, Vh, mu),
            docs,
            notes="The same in both sign conventions: they differ in how the slope "
            "enters the slow equations (generated.stability).",
        ),
        FunctionSpec(
            "vhat",
            "Velocity amplitude V_hat of the linear response.",
            "Eq. (23) (docs/modelling.md#vhat)",
            "value",
            "Vhat : ndarray",
            {(m, c): fr.vhat(m, c) for m in fr.VHAT_MODELS for c in CONTACT_LAWS},
            vhat_opts,
            notes="tangential: alpha_t Omega_t^3 / |omega1^2 - Omega_t^2 + 2i beta1 "
            "omega1 Omega_t|. coupled: the normal response drives the "
            "tangential one through mu_s times the normal force fluctuation; "
            "with Omega_t != Omega_n the two amplitudes add.",
        ),
    )
    return ModuleSpec(
        "friction",
        """Effective friction of the MDSM (Eqs. 23-25) and V_hat.

``mu_bar(Vr, Vhat, mu_s)`` is Eq. (23) as printed (the sign of ``Vr``);
``mu_bar_slope(Vb, Vhat, mu_s)`` its slope at the equilibrium ``Vr = -Vb``
(Eq. 25), exact up to ``Vb -> Vhat`` (``+inf`` at equality, 0 beyond);
``vhat(model=...)`` the two readings of ``V_hat``.
""",
        functions,
    )


def stability() -> ModuleSpec:
    """Sects. 4.2-4.3: forced Jacobian, quartic, Hurwitz, eigenvalues, boundary."""
    opts = (
        (
            "convention",
            '{"paper", "consistent"}',
            "paper",
            "sign of the effective friction in Eq. (A4): as printed, or as Eq. (4) "
            "implies (docs/modelling.md#friction-sign)",
        ),
    ) + CONTACT_OPTION
    keys = [(cv, c) for cv in st.CONVENTIONS for c in CONTACT_LAWS]

    def each(build):
        return {k: build(*k) for k in keys}

    def pqrs(cv, c):
        return [st.with_friction(e) for e in st.factored(cv, c).pqrs]

    def quads(cv, c):
        f = st.factored(cv, c)
        return [
            ss.Quadratic(*(st.with_friction(e) for e in (q.p, q.q, q.disc)))
            for q in (f.tangential, f.normal)
        ]

    hurwitz = each(lambda cv, c: st.hurwitz_factored(*pqrs(cv, c)))
    common = dict(options=opts, vhat=True)
    functions = (
        FunctionSpec(
            "equilibrium",
            "Slow equilibrium (Z1, S1, Z2, S2) of the forced system.",
            "Eq. (A7)",
            "tuple",
            "Z1, S1, Z2, S2 : ndarray",
            each(
                lambda cv, c: [st.with_friction(v) for v in st.slow_equilibrium_A7(cv, c).values()]
            ),
            **common,
            notes="paper: Z1 = mu_bar^0 g / omega1^2 with mu_bar^0 < 0 (Eq. A7 as "
            "printed); consistent: Z1 = -mu_bar^0 g / omega1^2 > 0.",
        ),
        FunctionSpec(
            "jacobian",
            "Forced Jacobian J_f^0 at the slow equilibrium.",
            "Eq. (22)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)",
            each(lambda cv, c: st.forced_jacobian_eq_22(cv, c).applyfunc(st.with_friction)),
            **common,
        ),
        FunctionSpec(
            "coefficients",
            "Coefficients a1..a4 of the monic characteristic quartic.",
            "Eqs. (26)-(27), (A8)",
            "tuple",
            "a1, a2, a3, a4 : ndarray",
            each(lambda cv, c: [st.with_friction(a) for a in st.coefficients_A8(cv, c)]),
            **common,
            notes="Only the slope mu_bar' enters, not mu_bar^0 (Sect. 4.3).",
        ),
        FunctionSpec(
            "hurwitz",
            "Hurwitz determinants H1..H4 in cancellation-free factored form.",
            "Eq. (28)",
            "tuple",
            "H1, H2, H3, H4 : ndarray\n    With the quartic = (l^2 + p l + q)(l^2 + r l + s):"
            "\n    H1 = p + r, H2 = p (q + r (p + r)) + r s,"
            "\n    H3 = p r ((q - s)^2 + (p + r)(p s + q r)), H4 = q s H3.",
            hurwitz,
            **common,
            notes="Equal to the determinants of the Hurwitz matrix (H4 = a4 H3; the "
            "printed Eq. 28 has a1 a4^2 where the determinant has a1^2 a4^2). "
            "The factored form keeps the sign of H3 next to the boundary p = 0, "
            "where a1 a2 a3 - a3^2 - a4 a1^2 cancels.",
        ),
        FunctionSpec(
            "eigenvalues",
            "Eigenvalues of J_f^0 in closed form.",
            "Eq. (26), via its exact factorisation",
            "roots",
            "lam : complex ndarray, shape (..., 4)\n    Tangential pair, then normal pair.",
            each(quads),
            **common,
        ),
        FunctionSpec(
            "growth_rate",
            "Largest real part of the eigenvalues of J_f^0.",
            "Eq. (26)",
            "growth",
            "sigma : ndarray\n    At Vb = Vhat exactly (infinite slope, mu_s > 0): +inf "
            "in the paper convention;\n    -0.0 in the consistent one (the slow tangential "
            "root -q/p, as p -> +inf).",
            each(quads),
            **common,
            accelerate=True,
        ),
        FunctionSpec(
            "is_stable",
            "Routh-Hurwitz verdict: all of H1..H4 positive.",
            "Eq. (28)",
            "stable",
            "stable : bool ndarray",
            each(lambda cv, c: [st.with_friction(e) for e in st.stability_conditions(cv, c)]),
            **common,
            notes="With the quartic = (l^2 + p l + q)(l^2 + r l + s) and q, s > 0 "
            "(proved by SymPy on the parameter domains), all of H1..H4 > 0 "
            "holds exactly when p > 0 and r > 0 "
            "(derive.stability.stability_conditions): two sign tests, no "
            "determinant, root or power.",
            accelerate=True,
        ),
        FunctionSpec(
            "critical_belt_speed",
            "Lower edge of the unstable belt speeds, closed form.",
            "Eqs. (25), (28): root of p(Vb) = 0",
            "value",
            "Vb_c : ndarray\n    paper: sqrt((Vhat - m)(Vhat + m)), m = mu_s g / (pi beta1 "
            "omega1),\n    unstable for Vb_c < Vb <= Vhat; 0 where m >= Vhat (unstable "
            "for all\n    0 <= Vb <= Vhat); consistent: NaN (no belt speed is unstable).",
            each(lambda cv, c: st.critical_belt_speed(cv, c)),
            **common,
        ),
        FunctionSpec(
            "unstable_interval",
            "Belt speeds (lower, upper) where the analysis predicts instability.",
            "Eqs. (25), (28)",
            "tuple",
            "lower, upper : ndarray\n    paper: (critical_belt_speed, Vhat), an interval"
            " closed at Vhat\n    (infinite slope); consistent: (NaN, NaN), empty.",
            each(
                lambda cv, c: [
                    st.critical_belt_speed(cv, c),
                    P["Vhat"] if cv == "paper" else sp.nan,
                ]
            ),
            **common,
        ),
    )
    return ModuleSpec(
        "stability",
        """Stability of the forced system (Sects. 4.2-4.3, Eqs. 22, 26-28, A7-A8).

Every function takes ``Vb`` and either ``Vhat=`` or ``vhat_model=`` (default
``"tangential"``), the sign ``convention=`` (``"paper"``, default, or
``"consistent"``) and ``contact=``. The forced Jacobian is block triangular: the
quartic factors into a tangential and a normal quadratic, so eigenvalues, Hurwitz
determinants and the critical belt speed are closed forms. A stability map
needs only ``is_stable`` (a sign), not eigenvalues.
""",
        functions,
    )


def correlation() -> ModuleSpec:
    """Beyond the paper: the average of friction times the fast normal force."""
    args = (cr.u, cr.V, cr.N0, cr.N1, cr.theta)
    docs = {
        "u": "slow relative velocity Z1' - Vb [m/s] (-Vb at the equilibrium)",
        "V": "amplitude of the fast relative velocity [m/s]",
        "N0": "mean normal force per unit mass [m/s^2] (g at the equilibrium)",
        "N1": "amplitude of the fast normal force per unit mass [m/s^2]",
        "theta": "phase of the fast normal force ahead of the fast velocity [rad]",
    }
    re, im, vre, vim = {}, {}, {}, {}
    for contact in CONTACT_LAWS:
        re[contact], im[contact] = cr.fast_normal_force(contact)
        vre[contact], vim[contact] = cr.fast_tangential_velocity(contact)
    functions = (
        FunctionSpec(
            "averaged_friction",
            "Average of sgn(u + V sin) (N0 + N1 sin(. + theta)) over a fast period.",
            "Eq. (23) generalised (docs/modelling.md#averaging)",
            "value",
            "F : ndarray\n    (2/pi)(N0 asin(u/V) + N1 cos(theta) sqrt(1 - u^2/V^2)) for "
            "|u| < V,\n    N0 sgn(u) otherwise. Times mu_s: the mean friction force.",
            {(): cr.averaged_friction()},
            (),
            args,
            docs,
            notes="With N1 = 0 and N0 = 1 this is Eq. (23) divided by mu_s.",
        ),
        FunctionSpec(
            "averaged_friction_slope",
            "Slope in u of `averaged_friction`.",
            "Eq. (25) generalised",
            "value",
            "dF/du : ndarray\n    2 (N0 V - N1 u cos(theta)) / (pi V sqrt((V - u)(V + u)))"
            " for |u| < V, 0 otherwise.",
            {(): cr.averaged_friction_slope()},
            (),
            args,
            docs,
        ),
        FunctionSpec(
            "first_harmonic",
            "First harmonic (s1, c1) of sgn(u + V sin t)(N0 + N1 sin(t + theta)).",
            "harmonic balance of Eq. (A1)",
            "tuple",
            "s1, c1 : ndarray\n    The product ~ s1 sin t + c1 cos t + (mean, higher harmonics).",
            {(): list(cr.first_harmonic())},
            (),
            args,
            docs,
        ),
        FunctionSpec(
            "fast_normal_force",
            "Amplitude and phase of the fast normal force.",
            "Eqs. (11), (A2) linearised",
            "tuple",
            "N1, psi : ndarray\n    N(t) = g + N1 sin(Omega_n t + psi) per unit mass, "
            "from the\n    linear response of the normal block of Eq. (11).",
            {
                (c,): [sp.sqrt(re[c] ** 2 + im[c] ** 2), sp.atan2(im[c], re[c])]
                for c in CONTACT_LAWS
            },
            CONTACT_OPTION,
        ),
        FunctionSpec(
            "fast_tangential_velocity",
            "Amplitude and phase of the fast relative velocity without friction reversal.",
            "Eqs. (11), (A1) linearised",
            "tuple",
            "V, phi : ndarray\n    X1'(t) - Z1' = V sin(Omega_t t + phi) while Vr < 0 "
            "throughout\n    (V is the coupled V_hat). One frequency: Omega_n is taken "
            "equal to Omega_t.",
            {
                (c,): [sp.sqrt(vre[c] ** 2 + vim[c] ** 2), sp.atan2(vim[c], vre[c])]
                for c in CONTACT_LAWS
            },
            CONTACT_OPTION,
        ),
    )
    return ModuleSpec(
        "correlation",
        """Beyond the paper: friction correlated with the fast normal force.

The paper's slow equations drop the correlation between the fast friction direction
and the fast normal force (docs/modelling.md#averaging). These closed forms keep it, for a
harmonic fast motion: the averaged friction and its slope (the consistent
counterpart of Eqs. 23-25), the first harmonic for the harmonic balance of the
fast tangential motion, and the fast normal force. ``runtime.predict`` builds the
stability prediction from them.
""",
        functions,
    )


def all_modules() -> tuple[ModuleSpec, ...]:
    return (
        unforced(),
        dynamics(),
        fit(),
        friction(),
        stability(),
        correlation(),
        hybrid(),
        oscillator(),
    )
