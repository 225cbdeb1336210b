"""What ``generated/`` contains: each module as a list of function specs.

This is the pipeline's last pure step: it calls the derivations and packages their
expressions as `codegen.FunctionSpec` specs. Nothing here writes files. The options
``friction=``, ``contact=`` and ``tension=`` of every function are the choices of the
registry (`derive.laws`), one variant per choice, and a function takes an option
only where its law enters.
"""

from __future__ import annotations

import itertools
import time

import sympy as sp

from . import budget, laws, mdsm
from . import capabilities as cap
from . import contraction as ctr
from . import correlation as cr
from . import dynamics as dyn
from . import fit as ft
from . import friction as fr
from . import hybrid as hy
from . import oscillator as osc
from . import stability as st
from . import statespace as ss
from .codegen import FunctionSpec, ModuleSpec, Refusal
from .model import STATE, X1, Y1, Y2, P, contact_force, t

__all__ = [
    "law_options",
    "unforced",
    "dynamics",
    "fit",
    "friction",
    "stability",
    "correlation",
    "hybrid",
    "oscillator",
    "capabilities",
    "tableau",
    "contraction",
    "BUILDERS",
    "all_modules",
]

_WHAT = {
    "friction": "friction law (derive/laws.py)",
    "contact": "contact law (derive/laws.py)",
    "tension": "tension law (derive/laws.py; docs/modelling.md#tension)",
}


def law_options(*options: str) -> tuple:
    """The ``(name, choices, default, description)`` rows of the law options, from the registry."""
    rows = []
    for option in options:
        choices = laws.choices(option)
        doc = "; ".join(f"{c}: {laws.get(option, c).summary}" for c in choices)
        rows.append(
            (
                option,
                "{" + ", ".join(f'"{c}"' for c in choices) + "}",
                laws.default(option),
                f"{_WHAT[option]}: {doc}.",
            )
        )
    return tuple(rows)


def _or_refuse(expr, reason: str):
    """``expr``, or a `Refusal` with ``reason`` where the derivation claims no closed form
    (with the budget's reason where a step ran past its budget, `derive.budget`)."""
    if isinstance(expr, budget.NoClosedForm):
        return Refusal(f"{reason.split(':')[0]}: {expr.reason}; no closed-form boundary is claimed")
    return Refusal(reason) if expr is None else expr


def _per(build, *options: str) -> dict:
    """``{(choice, ...): build(choice, ...)}`` over every combination of the options' choices."""
    keys = itertools.product(*(laws.choices(o) for o in options))
    return {key: build(*key) for key in keys}


FRICTION = law_options("friction")
CONTACT = law_options("contact")
LAWS_FC = law_options("friction", "contact")
CONTACT_TENSION = law_options("contact", "tension")
LAWS_FCT = law_options("friction", "contact", "tension")
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


def unforced() -> ModuleSpec:
    """Sect. 4.1: equilibrium, Jacobian and characteristic polynomial (Eqs. 9-12)."""
    eq = _per(lambda f, c: ss.equilibrium_eq_9(c, f), "friction", "contact")
    J0 = _per(lambda f, c: ss.jacobian_at_equilibrium_eq_11(c, f), "friction", "contact")
    functions = (
        FunctionSpec(
            "equilibrium",
            "Equilibrium (X1, Y1, X2, Y2) of the unforced system.",
            "Eq. (9), solved by SymPy from Eqs. (5)-(8)",
            "tuple",
            "X1, Y1, X2, Y2 : ndarray\n    Broadcast to the shape of the inputs.",
            {k: [v[s] for s in STATE] for k, v in eq.items()},
            LAWS_FC,
            notes="X1 = mu(Vb) g / omega1^2: the friction coefficient at the sliding "
            "speed Vb (mu_s for Coulomb's law, as printed).",
        ),
        FunctionSpec(
            "jacobian",
            "Jacobian of the state equations on the sliding branch.",
            "Eq. (10)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)\n    d(X1', Y1', X2', Y2')/d(X1, Y1, X2, Y2).",
            _per(lambda f, c: ss.jacobian_eq_10(c, friction=f), "friction", "contact"),
            LAWS_FC,
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
            LAWS_FC,
            notes="The tangential damping entry is -(2 beta1 omega1 + g mu'(Vb)) with "
            "the slope of the friction law at the sliding speed (0 for Coulomb).",
        ),
        FunctionSpec(
            "charpoly",
            "Coefficients of the monic characteristic quartic of J^0.",
            "Eq. (12)",
            "tuple",
            "a1, a2, a3, a4 : ndarray\n"
            "    det(lambda I - J0) = lambda^4 + a1 lambda^3 + a2 lambda^2 + a3 lambda + a4.",
            {k: ss.charpoly_eq_12(v).all_coeffs()[1:] for k, v in J0.items()},
            LAWS_FC,
            notes="mu_s does not appear for Coulomb's law (the claim below Eq. 12); a "
            "friction law that depends on the speed enters through its slope mu'(Vb).",
        ),
        FunctionSpec(
            "eigenvalues",
            "Eigenvalues of J^0 in closed form.",
            "Eq. (12), via its exact factorisation",
            "roots",
            "lam : complex ndarray, shape (..., 4)\n"
            "    Tangential pair, then normal pair; for a complex pair the root with\n"
            "    positive imaginary part first.",
            _per(lambda f, c: ss.quadratics_at_equilibrium(c, f), "friction", "contact"),
            LAWS_FC,
            notes="J^0 is block triangular, so the quartic is the product of a "
            "tangential and a normal quadratic; their roots are computed "
            "without cancellation from factored discriminants, which keeps "
            "full accuracy at a double root (beta1 = 1).",
        ),
        FunctionSpec(
            "critical_belt_speed",
            "Belt speed below which steady sliding is unstable, closed form.",
            "Eqs. (11)-(12): root of the tangential damping p(Vb)",
            "value",
            "Vb_c : ndarray\n    Steady sliding is unstable for 0 <= Vb < Vb_c, where the "
            "tangential\n    damping 2 beta1 omega1 + g mu'(Vb) is negative; NaN where no belt "
            "speed is\n    (Coulomb's law: always).",
            _per(
                lambda f, c: _or_refuse(
                    ss.critical_belt_speed(c, f),
                    f"friction={f!r}: the tangential damping of J^0 may vanish at more than "
                    "one belt speed, or is positive at rest; no closed-form boundary is claimed",
                ),
                "friction",
                "contact",
            ),
            LAWS_FC,
            notes="Stribeck's law: Vb_c = v_s log(g (mu_s - mu_k) / (2 beta1 omega1 v_s)), "
            "solved by SymPy from p(Vb) = 0.",
        ),
    )
    return ModuleSpec(
        "unforced",
        """The unforced system at its equilibrium (Sect. 4.1, Eqs. 9-12).

Every friction and contact law of the registry (``friction=``, ``contact=``; the
choices are ``generated.parameters.OPTIONS``, the defaults the paper's Eqs. 1 and 3).
Every function takes the parameters as keywords.
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
            "parameter (the one-way coupling of Eq. 4; generated.capabilities).",
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
    for f, c in itertools.product(laws.choices("friction"), laws.choices("contact")):
        for before, after, surface in hy.transitions():
            salt[(f, c, before, after, surface)] = hy.saltation(before, after, surface, c, f)
    names = sorted({k for k in hy.MODE_CODES})
    salt_opts = LAWS_FC + (
        ("before", "str", "slip_back", "mode before the switch"),
        ("after", "str", "slip_forward", "mode after the switch"),
        ("surface", "str", "relative_velocity", "the surface crossed (SURFACES)"),
    )
    fns = (
        FunctionSpec(
            "vector_field",
            "Vector field (X1', Y1', X2', Y2') of one mode of Eq. (4).",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)",
            _per(lambda f, c: list(hy.vector_field(c, f)), "friction", "contact"),
            LAWS_FC,
            state_t + (hy.mode,),
            mode_doc,
            notes="Each field is smooth on the whole state space: the contact modes "
            "use the unclipped force of the contact law (with max(X2, 0)) and the "
            "friction law's coefficient at sgn Vr, stick holds X1' = Vb, flight and "
            "separated are free of contact.",
            bind=True,
        ),
        FunctionSpec(
            "mode_jacobian",
            "Jacobian d(X1', Y1', X2', Y2')/d(X1, Y1, X2, Y2) of one mode's field.",
            "Eqs. (1)-(4)",
            "matrix",
            "J : ndarray, shape (..., 4, 4)",
            _per(lambda f, c: hy.mode_jacobian(c, f), "friction", "contact"),
            LAWS_FC,
            state_t + (hy.mode,),
            mode_doc,
            notes="The variational equation Phi' = J Phi of a run within one mode; across "
            "a switch the variation jumps by `saltation`. For a general Floquet "
            "analysis along an event-driven run (every friction law).",
            bind=True,
        ),
        FunctionSpec(
            "response_field",
            "Normal motion and the tangential response to its contact force.",
            "Eqs. (1)-(4)",
            "vector",
            "dstate : ndarray, shape (..., 4)\n    Derivative of (z, z', X2, X2').",
            _per(lambda c: list(hy.response_field(c)[0]), "contact"),
            CONTACT,
            (t,) + hy.response_field(laws.default("contact"))[1] + hy.STATE[2:] + (hy.mode,),
            {
                **mode_doc,
                "z": "tangential response to the contact force [m]",
                "v": "its velocity [m/s]",
            },
            notes="z'' + 2 beta1 omega1 z' + omega1^2 z = F(mode) from rest, beside "
            "the normal equation: the normal motion does not depend on the "
            "tangential one, so the superposition integrator integrates this "
            "once. Friction laws whose slip-mode friction depends on the tangential "
            "state cannot use it (generated.capabilities).",
            bind=True,
        ),
        FunctionSpec(
            "surfaces",
            "Switching functions h(t, x) of the hybrid system.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per(lambda f, c: [hy.surfaces(c, f)[n] for n in hy.SURFACES], "friction", "contact"),
            LAWS_FC,
            state_t,
            STATE_DOCS,
            notes="relative_velocity Y1 - Vb; stick_forward, stick_back "
            "mu(0) F -+ a_free (the stick cone of the friction law); penetration X2; "
            "contact_force: the sign of F (F over its factors positive in contact).",
            bind=True,
        ),
        FunctionSpec(
            "surface_scales",
            "Rounding scale of each switching function.",
            "Eqs. (1)-(4)",
            "tuple",
            surfaces_doc,
            _per(
                lambda f, c: [hy.surface_scales(c, f)[n] for n in hy.SURFACES],
                "friction",
                "contact",
            ),
            LAWS_FC,
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
            _per(
                lambda f, c: [hy.surface_rates(c, f)[n] for n in hy.SURFACES],
                "friction",
                "contact",
            ),
            LAWS_FC,
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

Modes with smooth vector fields (`vector_field`, by mode code) and their Jacobians
(`mode_jacobian`), the switching surfaces between them (`surfaces`, with rounding
scales and rates along a mode), the guards of each tension law (`GUARDS`: which
surface ends which mode, crossed in which direction, and what follows) and the
saltation matrices of the switches (`saltation`), which the Floquet analysis of the
periodic response needs. Fields, surfaces and saltation matrices take the friction
and contact laws of the registry (``friction=``, ``contact=``).
""",
        fns,
        constants,
    )


#: The arguments of `generated.oscillator.tangential_state` after ``tau``.
SUPERPOSITION_DOCS = {
    "X1_0": "tangential displacement at the switch t0 [m]",
    "Y1_0": "tangential velocity X1' at the switch t0 [m/s]",
    "zf_0": "excitation response at t0 (`excitation_response`) [m]",
    "vf_0": "its rate at t0 [m/s]",
    "z_0": "response to the contact force at t0 (per unit friction coefficient) [m]",
    "v_0": "its rate at t0 [m/s]",
    "zf": "excitation response at t0 + tau [m]",
    "vf": "its rate at t0 + tau [m/s]",
    "z": "response to the contact force at t0 + tau [m]",
    "v": "its rate at t0 + tau [m/s]",
    "sgn": "friction direction of the mode: -1 (mass slower than the belt), +1, "
    "or 0 (flight or separation: no friction)",
}


def oscillator() -> ModuleSpec:
    """The tangential oscillator in closed form: state-transition matrix, forced response,
    their superposition."""
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
        FunctionSpec(
            "tangential_state",
            "(X1, X1') at t0 + tau of a mode entered at t0: the superposition.",
            "Eq. (4), first row",
            "tuple",
            "X1, Y1 : ndarray\n    The tangential state at t0 + tau.",
            {
                (f,): _or_refuse(
                    None if osc.tangential_state(f) is None else list(osc.tangential_state(f)),
                    cap.slip_friction_state_independent(f, laws.default("contact"))[1]
                    + ": the tangential motion of a slip mode is no superposition",
                )
                for f in laws.choices("friction")
            },
            FRICTION,
            (osc.tau, *osc.SUPERPOSITION_ARGS),
            {**docs, **SUPERPOSITION_DOCS},
            notes="Phi(tau) (x0 - f(t0)) + f(t) with f = zf - mu sgn z: the free motion "
            "from the state at the switch and the forced responses, zf to the "
            "excitation (`excitation_response`) and z to the contact force (integrated "
            "with the normal motion, generated.hybrid.response_field), both from rest "
            "at t = 0 (derive/oscillator.py). Exact for a friction law whose slip-mode "
            "friction mu sgn F does not depend on the tangential state.",
            bind=True,
        ),
    )
    return ModuleSpec(
        "oscillator",
        """The tangential oscillator of Eq. (4) in closed form.

Between two switches the tangential motion is linear: the state-transition matrix
carries the state at the switch, the excitation response and the response to the
contact force (integrated by the runtime) add to it (derive/oscillator.py);
`tangential_state` is that superposition.
""",
        fns,
    )


def fit() -> ModuleSpec:
    """Eqs. (16)-(17): the least-squares polynomial of the contact law's X2^n, exact errors."""
    options = CONTACT + (("degree", "int, 1 to 8", 3, "polynomial degree; 3 gives Eq. (17)"),)
    arg = (ft.X2max,)
    docs = {"X2max": "upper end of the fitted range [0, X2max] [m]"}

    def per_degree(build):
        return {(c, n): build(n, c) for c in laws.choices("contact") for n in ft.DEGREES}

    endpoints = (
        "For a symbolic exponent (hunt_crossley) the larger of the errors at X2 = 0 and at "
        "X2max, closed forms in n_h: an interior extremum of X2^n_h - fit has no closed "
        "form (the tests check against a dense scan that none is larger)."
    )
    functions = (
        FunctionSpec(
            "coefficients",
            "Coefficients (c0, ..., c_degree) of the L2 fit of X2^n.",
            "Eqs. (16)-(17)",
            "tuple",
            "c : tuple of ndarray\n    X2^n ~ sum_k c_k X2^k on [0, X2max], n the contact "
            "law's exponent\n    (3/2: Eq. 17).",
            per_degree(lambda n, c: list(ft.coefficients_eq_17(n, c))),
            options,
            arg,
            docs,
            notes="Rational functions of the exponent times powers of X2max, from the "
            "continuous normal equations (Hilbert matrix) solved by SymPy; exact "
            "rationals for Eq. (1).",
        ),
        FunctionSpec(
            "max_error",
            "Largest absolute error of the fit on [0, X2max], exact.",
            "Eq. (17) (the paper: 'about 1e-2')",
            "value",
            "err : ndarray\n    max |X2^n - fit| (for Eq. 1, degree 3: 8/1155 X2max^(3/2)).",
            per_degree(lambda n, c: ft.fit_error(n, c).max_abs),
            options,
            arg,
            docs,
            notes=endpoints,
        ),
        FunctionSpec(
            "max_error_location",
            "Where the largest error of the fit sits.",
            "Eq. (17)",
            "value",
            "X2 : ndarray",
            per_degree(lambda n, c: ft.fit_error(n, c).argmax),
            options,
            arg,
            docs,
            notes=endpoints,
        ),
        FunctionSpec(
            "rms_error",
            "Root-mean-square error of the fit on [0, X2max], exact.",
            "Eq. (17)",
            "value",
            "rms : ndarray",
            per_degree(lambda n, c: ft.fit_error(n, c).rms),
            options,
            arg,
            docs,
            notes="From the normal equations: the mean square error is "
            "X2max^(2n) (1/(2n+1) - sum_k d_k/(k+n+1)), a closed form in n.",
        ),
        FunctionSpec(
            "mdsm_fit_range",
            "The fitted range for the MDSM: X2^0 plus the fast normal amplitude.",
            "Eqs. (9), (14), (16)",
            "value",
            "X2max : ndarray",
            _per(mdsm.x2max, "contact"),
            CONTACT,
            notes="The fast normal motion is the linear response of the normal block "
            "of Eq. (11) to the normal excitation; X2^0 and the block are those of "
            "the contact law whose power `coefficients` fits.",
        ),
    )
    return ModuleSpec(
        "fit",
        """Least-squares polynomial fit of the contact law's power X2^n on [0, X2max] (Eqs. 16-17).

Degrees 1 to 8, exact in X2max and in the exponent (``contact=``: 3/2 for Eq. 1, the
symbol ``n_h`` of Hunt-Crossley's law; the linear law's fit is exact). ``X2max`` comes
from the scene (for the MDSM: the slow penetration plus the amplitude of the fast
normal motion, `mdsm_fit_range` of the same contact law), not a constant.
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
        "mu_s": "static friction coefficient (Coulomb's of Eq. 3)",
    }
    quadrature = (
        "For a friction law whose fast average has no closed form (Stribeck's; "
        "generated.capabilities) the law's part beyond mu(0) is a quadrature of the "
        "same expression (generated._support.quad)."
    )
    vhat_opts = (
        (
            "model",
            '{"tangential", "coupled"}',
            "tangential",
            "reading of V_hat (docs/modelling.md#vhat): the tangential oscillator alone, "
            "or the 2-DOF system linearised at equilibrium",
        ),
    )
    functions = (
        FunctionSpec(
            "mu_bar",
            "Effective friction coefficient, with the sign of Vr.",
            "Eq. (23)",
            "value",
            "mu_bar : ndarray",
            _per(lambda f: fr.mu_bar_eq_23(fr.Vr, f), "friction"),
            FRICTION,
            (fr.Vr, Vh, mu),
            docs,
            notes="mu(0) (1 - 2/pi acos(Vr/Vhat)) inside |Vr| <= Vhat, mu(0) sgn(Vr) outside "
            "(Eq. 23), plus the average of mu(|Vr + Vhat sin|) - mu(0). " + quadrature,
        ),
        FunctionSpec(
            "mu_bar0",
            "Effective friction at the slow equilibrium, mu_bar(-Vb).",
            "Eq. (25), mu_bar^0",
            "value",
            "mu_bar0 : ndarray\n    Negative: the mass is slower than the belt.",
            _per(fr.mu_bar0_eq_25, "friction"),
            FRICTION,
            (Vb, Vh, mu),
            docs,
            notes=quadrature,
        ),
        FunctionSpec(
            "mu_bar_slope",
            "Slope of the effective friction at the equilibrium.",
            "Eqs. (24)-(25)",
            "value",
            "slope : ndarray\n    Coulomb: 2 mu_s / (pi sqrt((Vhat - Vb)(Vhat + Vb))) for "
            "Vb < Vhat;\n    +inf at Vb = Vhat exactly; 0 for Vb > Vhat. Other laws add the "
            "slope of\n    their part beyond mu(0) on both sides.",
            _per(fr.mu_bar_slope_eq_25, "friction"),
            FRICTION,
            (Vb, Vh, mu),
            docs,
            notes="The same in both sign conventions: they differ in how the slope "
            "enters the slow equations (generated.stability). " + quadrature,
        ),
        FunctionSpec(
            "vhat",
            "Velocity amplitude V_hat of the linear response.",
            "Eq. (23) (docs/modelling.md#vhat)",
            "value",
            "Vhat : ndarray",
            {
                (f, c, m): fr.vhat(m, c, f)
                for f in laws.choices("friction")
                for c in laws.choices("contact")
                for m in fr.VHAT_MODELS
            },
            LAWS_FC + vhat_opts,
            notes="tangential: alpha_t Omega_t^3 / |omega1^2 - Omega_t^2 + 2i (beta1 "
            "omega1 + g mu'(Vb)/2) Omega_t| (Coulomb: mu' = 0). coupled: the normal "
            "response drives the tangential one through mu(Vb) times the normal force "
            "fluctuation; with Omega_t != Omega_n the two amplitudes add.",
        ),
    )
    return ModuleSpec(
        "friction",
        """Effective friction of the MDSM (Eqs. 23-25) and V_hat.

``mu_bar(Vr, Vhat, mu_s)`` is Eq. (23) as printed (the sign of ``Vr``);
``mu_bar_slope(Vb, Vhat, mu_s)`` its slope at the equilibrium ``Vr = -Vb``
(Eq. 25), exact up to ``Vb -> Vhat`` (``+inf`` at equality, 0 beyond);
``vhat(model=...)`` the two readings of ``V_hat``. ``friction=`` takes any friction
law of the registry: Eq. (23) with its static coefficient, plus the average of the
rest of the law (a quadrature for Stribeck's, derive/averaging.py).
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
    )
    keys = list(
        itertools.product(laws.choices("friction"), laws.choices("contact"), st.CONVENTIONS)
    )

    def each(build):
        return {(f, c, cv): build(f, c, cv) for f, c, cv in keys}

    def pqrs(f, c, cv):
        return [st.with_friction(e, f) for e in st.factored(cv, c).pqrs]

    def quads(f, c, cv):
        fq = st.factored(cv, c)
        return [
            ss.Quadratic(*(st.with_friction(e, f) for e in (q.p, q.q, q.disc)))
            for q in (fq.tangential, fq.normal)
        ]

    def _below(expr, bound):
        """``expr < bound`` as a condition (a Piecewise ``expr`` taken branch by branch:
        the printers' conditions are plain relations, not Piecewise values)."""
        if not isinstance(expr, sp.Piecewise):
            return sp.StrictLessThan(expr, bound)
        terms, others = [], sp.true
        for value, cond in expr.args:
            terms.append(sp.And(others, cond, _below(value, bound)))
            others = sp.And(others, sp.Not(cond))
        return sp.Or(*terms)

    def boundary(f, c, cv, upper=False):
        lower = st.critical_belt_speed(cv, c, f)
        if isinstance(lower, budget.NoClosedForm):
            return Refusal(
                f"friction={f!r} has no closed-form critical belt speed: {lower.reason}; the "
                "pointwise functions (growth_rate, is_stable, hurwitz) take it, and "
                "beltmdsm.prediction.paper.paper_intervals finds the unstable belt speeds "
                "numerically from growth_rate"
            )
        if lower is None:
            closed, why = cap.closed_form_average(f)
            return Refusal(
                f"friction={f!r} has no closed-form critical belt speed: "
                + (
                    "SymPy's roots of p(Vb) = 0 are not one root sqrt(Vhat^2 - m^2)"
                    if closed
                    else f"the slope of its effective friction is a quadrature "
                    f"(closed_form_average: {why})"
                )
                + "; the pointwise functions (growth_rate, is_stable, hurwitz) take it, and "
                "beltmdsm.prediction.paper.paper_intervals finds the unstable belt speeds "
                "numerically from growth_rate"
            )
        if not upper:
            return lower
        if cv != "paper":
            return [lower, sp.nan]
        # (Vb_c, Vhat] is empty where Vb_c = Vhat (no friction at rest, mu_s = 0: the
        # slope of Eq. 25 is 0, also at Vhat): NaN, as the consistent convention's
        nonempty = _below(lower, P["Vhat"])
        return [
            sp.Piecewise((lower, nonempty), (sp.nan, True)),
            sp.Piecewise((P["Vhat"], nonempty), (sp.nan, True)),
        ]

    hurwitz = each(lambda f, c, cv: st.hurwitz_factored(*pqrs(f, c, cv)))
    common = dict(options=LAWS_FC + opts, vhat=True)
    functions = (
        FunctionSpec(
            "equilibrium",
            "Slow equilibrium (Z1, S1, Z2, S2) of the forced system.",
            "Eq. (A7)",
            "tuple",
            "Z1, S1, Z2, S2 : ndarray",
            each(
                lambda f, c, cv: [
                    st.with_friction(v, f) for v in st.slow_equilibrium_A7(cv, c).values()
                ]
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
            each(
                lambda f, c, cv: st.forced_jacobian_eq_22(cv, c).applyfunc(
                    lambda e: st.with_friction(e, f)
                )
            ),
            **common,
        ),
        FunctionSpec(
            "coefficients",
            "Coefficients a1..a4 of the monic characteristic quartic.",
            "Eqs. (26)-(27), (A8)",
            "tuple",
            "a1, a2, a3, a4 : ndarray",
            each(lambda f, c, cv: [st.with_friction(a, f) for a in st.coefficients_A8(cv, c)]),
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
            each(lambda f, c, cv: [st.with_friction(e, f) for e in st.stability_conditions(cv, c)]),
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
            "for all\n    0 <= Vb <= Vhat); consistent: NaN (no belt speed is unstable).\n"
            "    Only where the effective friction's slope has a closed form.",
            each(boundary),
            **common,
        ),
        FunctionSpec(
            "unstable_interval",
            "Belt speeds (lower, upper) where the analysis predicts instability.",
            "Eqs. (25), (28)",
            "tuple",
            "lower, upper : ndarray\n    paper: (critical_belt_speed, Vhat), an interval"
            " closed at Vhat\n    (infinite slope), or (NaN, NaN) where it is empty "
            "(critical_belt_speed = Vhat:\n    mu_s = 0); consistent: (NaN, NaN), empty.",
            each(lambda f, c, cv: boundary(f, c, cv, upper=True)),
            **common,
        ),
    )
    return ModuleSpec(
        "stability",
        """Stability of the forced system (Sects. 4.2-4.3, Eqs. 22, 26-28, A7-A8).

Every function takes ``Vb`` and either ``Vhat=`` or ``vhat_model=`` (default
``"tangential"``; ``V_hat`` is then that of the same laws), the sign ``convention=``
(``"paper"``, default, or ``"consistent"``), ``friction=`` and ``contact=``. The forced
Jacobian is block triangular: the quartic factors into a tangential and a normal
quadratic, so eigenvalues, Hurwitz determinants and the critical belt speed are
closed forms in the effective friction's value and slope (a quadrature for a
friction law without a closed-form fast average; the critical belt speed and the
unstable interval then refuse, and ``beltmdsm.prediction.paper.paper_intervals``
finds the unstable belt speeds numerically from the pointwise ``growth_rate``, with
``V_hat`` of the chosen reading at each ``Vb``). A stability map needs only ``is_stable`` (a sign),
not eigenvalues.
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
    quadrature = (
        "For a friction law whose fast average has no closed form (Stribeck's; "
        "generated.capabilities) the law's part beyond mu(0) is a quadrature of the "
        "same expression (generated._support.quad)."
    )

    def amplitude_phase(re_im):
        re, im = re_im
        return [sp.sqrt(re**2 + im**2), sp.atan2(im, re)]

    balance_docs = {
        "V": "amplitude of the fast relative velocity [m/s]",
        "phi": "its phase: X1' - Z1' = V sin(Omega_t t + phi) [rad]",
        "N1": "amplitude of the fast normal force per unit mass [m/s^2]",
        "psi": "its phase: N = g + N1 sin(Omega_t t + psi) [rad]",
        "theta": "phase of the fast normal force ahead of the fast velocity, psi - phi [rad]",
    }
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
            _per(lambda c: amplitude_phase(cr.fast_normal_force(c)), "contact"),
            CONTACT,
        ),
        FunctionSpec(
            "fast_tangential_velocity",
            "Amplitude and phase of the fast relative velocity without friction reversal.",
            "Eqs. (11), (A1) linearised",
            "tuple",
            "V, phi : ndarray\n    X1'(t) - Z1' = V sin(Omega_t t + phi) while Vr < 0 "
            "throughout\n    (V is the coupled V_hat). One frequency: Omega_n is taken "
            "equal to Omega_t.",
            _per(
                lambda f, c: amplitude_phase(cr.fast_tangential_velocity(c, f)),
                "friction",
                "contact",
            ),
            LAWS_FC,
            notes="The friction law enters through its value and slope at Vb.",
        ),
        FunctionSpec(
            "friction_average",
            "Average of mu(|v|) sgn(v) (N0 + N1 sin(. + theta)), v = u + V sin, over a period.",
            "Eq. (23) generalised (docs/modelling.md#averaging)",
            "value",
            "F : ndarray\n    The mean friction force per unit mass of the friction law (Coulomb: "
            "mu_s\n    times `averaged_friction`).",
            _per(cr.friction_average, "friction"),
            FRICTION,
            args,
            docs,
            notes=quadrature,
        ),
        FunctionSpec(
            "friction_average_slope",
            "Slope in u of `friction_average`.",
            "Eq. (25) generalised",
            "value",
            "dF/du : ndarray",
            _per(cr.friction_average_slope, "friction"),
            FRICTION,
            args,
            docs,
            notes=quadrature,
        ),
        FunctionSpec(
            "friction_harmonic",
            "First harmonic (s1, c1) of mu(|v|) sgn(v) (N0 + N1 sin(t + theta)), v = u + V sin t.",
            "harmonic balance of Eq. (A1)",
            "tuple",
            "s1, c1 : ndarray\n    The friction force ~ s1 sin t + c1 cos t + (mean, higher "
            "harmonics).",
            _per(lambda f: list(cr.friction_harmonic(f)), "friction"),
            FRICTION,
            args,
            docs,
            notes=quadrature,
        ),
        FunctionSpec(
            "slow_damping",
            "Damping of the slow tangential motion at the equilibrium (consistent MDSM).",
            "Eqs. (20), (23)-(25) generalised",
            "value",
            "p : ndarray\n    2 beta1 omega1 + d/du <mu(|v|) sgn(v) N> at u = -Vb, N0 = g; "
            "the slow\n    sliding is unstable where p < 0.",
            _per(cr.slow_damping, "friction"),
            FRICTION,
            (cr.V, cr.N1, cr.theta),
            {**docs, **balance_docs},
            notes="The linearisation of the averaged friction at frozen fast amplitude and "
            "phase (beltmdsm.prediction.mdsm's consistent MDSM). " + quadrature,
        ),
        FunctionSpec(
            "transfer_function",
            "q(i Omega_t) of the tangential oscillator without friction.",
            "Eq. (4), first row, harmonic",
            "tuple",
            "re, im : ndarray\n    omega1^2 - Omega_t^2 and 2 beta1 omega1 Omega_t: a displacement "
            "x e^(i W t)\n    needs the force q(i W) x.",
            {(): list(cr.transfer_function())},
            notes="The transfer function of the harmonic balance (`harmonic_balance`).",
        ),
        FunctionSpec(
            "harmonic_balance",
            "Residual of the harmonic balance of the fast tangential motion.",
            "Eq. (A1), first harmonic",
            "tuple",
            "re, im : ndarray\n    Of q(i W) V/(i W) - F_t e^(-i phi) + (s1 + i c1), divided by "
            "|F_t|,\n    W = Omega_t; zero at a solution (V, phi).",
            _per(lambda f: list(cr.harmonic_balance(f)), "friction"),
            FRICTION,
            (cr.V, cr.phi, cr.N1, cr.psi),
            balance_docs,
            notes="s1 + i c1 is the first harmonic of the friction force (`friction_harmonic` "
            "at u = -Vb, N0 = g, theta = psi - phi): with the fast normal force "
            "(`fast_normal_force`) its roots give the fast motion of the consistent MDSM. "
            + quadrature,
        ),
    )
    return ModuleSpec(
        "correlation",
        """Beyond the paper: friction correlated with the fast normal force.

The paper's slow equations drop the correlation between the fast friction direction
and the fast normal force (docs/modelling.md#averaging). These closed forms keep it, for a
harmonic fast motion: the averaged friction and its slope (the consistent
counterpart of Eqs. 23-25), the first harmonic for the harmonic balance of the
fast tangential motion, and the fast normal force. ``averaged_friction``,
``averaged_friction_slope`` and ``first_harmonic`` are the set-valued sign's
averages; ``friction_average``, ``friction_average_slope`` and ``friction_harmonic``
those of a friction law (``friction=``), and ``slow_damping`` and
``harmonic_balance`` the pieces of the consistent MDSM built from them.
``beltmdsm.prediction`` builds the stability prediction from them.
""",
        functions,
    )


def capabilities() -> ModuleSpec:
    """The structural facts of each combination of laws, as data (derive/capabilities.py)."""
    table = cap.capabilities()
    return ModuleSpec(
        "capabilities",
        """What each combination of laws allows: facts SymPy decided (derive/capabilities.py).

``CAPABILITIES[(friction, contact, tension)][fact] = (holds, reason)``: ``holds`` a
bool, ``reason`` one line naming the law and the property. ``FACTS`` are the fact
names, ``FACT_DOCS`` say what each means and which analysis relies on it. An
analysis checks the facts it needs and either takes a general path or refuses with
the reason, never computing with the physics of another law.
""",
        (),
        (
            ("FACTS", tuple(cap.FACTS), "The facts, in the order of every entry."),
            ("FACT_DOCS", dict(cap.FACTS), "What each fact means and which analysis needs it."),
            ("CAPABILITIES", table, "(friction, contact, tension) -> fact -> (holds, reason)."),
        ),
        mp=False,
    )


def contraction() -> ModuleSpec:
    """The energy of the difference of two tangential motions (derive/contraction.py)."""
    docs = {
        "e": "difference of the tangential displacements X1 of two runs [m]",
        "e_dot": "difference of their velocities X1' [m/s]",
    }
    functions = (
        FunctionSpec(
            "difference_energy",
            "Energy E_d(e, e') of the difference of two tangential motions.",
            "Eq. (4) (derive/contraction.py)",
            "value",
            "E_d : ndarray\n    The tangential part of the mechanical energy at (e, e').",
            {(): ctr.difference_energy()},
            (),
            (ctr.e, ctr.ep),
            docs,
            notes="Two runs under one normal motion: dE_d/dt = -c1 e'^2 - (f_a - f_b) F e' "
            "(`difference_damping`), the evidence of the contraction claim.",
        ),
        FunctionSpec(
            "difference_damping",
            "The dashpot's coefficient c1 in dE_d/dt = -c1 e'^2 + the friction's part.",
            "Eq. (4) (derive/contraction.py)",
            "value",
            "c1 : ndarray\n    -d a_free / d X1'.",
            {(): ctr.power_split().c1},
        ),
    )
    return ModuleSpec(
        "contraction",
        """The energy of the difference of two tangential motions under one normal motion.

derive/contraction.py proves with SymPy that it never rises while the contact cannot
pull; these functions let a simulation show it (beltmdsm/studies/evidence.py).
""",
        functions,
    )


def tableau() -> ModuleSpec:
    """The Dormand-Prince 8(5,3) tableau of the runtime's integrator, as data.

    Copied from ``scipy.integrate`` when generated/ is written, so that the runtime's
    integrator (beltmdsm/integrate/_dop853.py) starts without importing
    ``scipy.integrate``, which costs half a second of every run's start.
    """
    from scipy.integrate._ivp import dop853_coefficients as c

    def data(a):
        return tuple(data(row) for row in a) if a.ndim > 1 else tuple(float(x) for x in a)

    constants = (
        ("N_STAGES", int(c.N_STAGES), "Stages of a step (the 8th-order solution)."),
        (
            "N_STAGES_EXTENDED",
            int(c.N_STAGES_EXTENDED),
            "Stages with those of the dense output.",
        ),
        ("INTERPOLATOR_POWER", int(c.INTERPOLATOR_POWER), "Rows of a step's dense output."),
        ("A", data(c.A), "The Runge-Kutta matrix, extended stages included."),
        ("B", data(c.B), "The weights of the 8th-order solution."),
        ("C", data(c.C), "The nodes, extended stages included."),
        ("E3", data(c.E3), "The 3rd-order error estimate's weights."),
        ("E5", data(c.E5), "The 5th-order error estimate's weights."),
        ("D", data(c.D), "The dense output's coefficients."),
    )
    return ModuleSpec(
        "tableau",
        """The Dormand-Prince 8(5,3) tableau (Hairer, Norsett and Wanner) of ``scipy.integrate``.

Copied when generated/ is written, so that the runtime's integrator
(beltmdsm/integrate/_dop853.py) starts without importing ``scipy.integrate``.
""",
        (),
        constants,
        mp=False,
    )


#: The builders of the generated modules, in the order `all_modules` derives them.
BUILDERS = (
    unforced,
    dynamics,
    fit,
    friction,
    stability,
    correlation,
    hybrid,
    oscillator,
    capabilities,
    tableau,
    contraction,
)


def all_modules(progress=None) -> tuple[ModuleSpec, ...]:
    """Every generated module's spec; ``progress(spec, seconds)`` is called after each."""
    specs = []
    for build in BUILDERS:
        start = time.perf_counter()
        specs.append(build())
        if progress is not None:
            progress(specs[-1], time.perf_counter() - start)
    return tuple(specs)
