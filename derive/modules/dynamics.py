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
            examples=(
                "At t = 0 (no excitation) the unforced equilibrium is a rest point:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> dstate = dynamics.rhs(0.0, *unforced.equilibrium(**BASE), **BASE)\n"
                ">>> dstate.shape, bool(abs(dstate).max() < 1e-12)\n"
                "((4,), True)"
            ),
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
            examples=(
                "With sgn = 0 the second entry is the acceleration without friction:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> d = dynamics.rhs_branch(0.0, 1.0, 0.0, 11.5, 0.0, 0.0, **BASE)\n"
                ">>> a_free = dynamics.free_acceleration(0.0, 1.0, 0.0, **BASE)\n"
                ">>> round(float(d[1]), 4), round(float(a_free), 4)\n"
                "(-1.0, -1.0)"
            ),
            bind_examples=(
                "The kernel at one point gives `rhs_branch` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.0, 1.0, 0.5, 11.5, 0.0, -1.0)\n"
                '>>> kernel = dynamics.bind_rhs_branch(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[0.5, 2.7998, 0.0, 0.0604]\n"
                ">>> ref = dynamics.rhs_branch(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "On the branch sgn = -1 at the unforced equilibrium it is J^0 (Eq. 11):\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import numpy as np\n"
                ">>> eq = unforced.equilibrium(**BASE)\n"
                ">>> J = dynamics.jacobian_branch(0.0, *eq, -1.0, **BASE)\n"
                ">>> bool(np.allclose(J, unforced.jacobian_at_equilibrium(**BASE)))\n"
                "True"
            ),
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
            examples=(
                "At the equilibrium penetration it carries gravity, g; out of contact it is 0:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X2 = float(unforced.equilibrium(**BASE)[2])\n"
                ">>> dynamics.normal_force([X2, -1.0], 0.0, **BASE).round(4).tolist()\n"
                "[9.81, 0.0]"
            ),
            bind_examples=(
                "The kernel at one point gives `normal_force` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (11.5, 0.1)\n"
                '>>> kernel = dynamics.bind_normal_force(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[10.3346]\n"
                ">>> ref = dynamics.normal_force(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Sliding backwards (sgn = -1) at the equilibrium penetration: mu_s g:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X2 = float(unforced.equilibrium(**BASE)[2])\n"
                ">>> round(float(dynamics.friction_force(0.0, X2, 0.0, -1.0, **BASE)), 4)\n"
                "3.924"
            ),
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
            examples=(
                "Kelvin-Voigt at rest at X2 = g / omega2^2 (t = 0: no excitation):\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X2 = 9.81 / 0.5**2\n"
                '>>> dn = dynamics.normal_rhs(0.0, X2, 0.0, **BASE, contact="kelvin_voigt")\n'
                ">>> [round(abs(float(v)), 10) for v in dn]\n"
                "[0.0, 0.0]"
            ),
            bind_examples=(
                "The kernel at one point gives `normal_rhs` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 11.5, 0.1)\n"
                '>>> kernel = dynamics.bind_normal_rhs(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[0.1, -30.3498]\n"
                ">>> ref = dynamics.normal_rhs(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Kelvin-Voigt is linear: [[0, 1], [-omega2^2, -2 beta2 omega2]]:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                '>>> J = dynamics.normal_jacobian(0.0, 1.0, 0.0, **BASE, contact="kelvin_voigt")\n'
                ">>> J.round(4).tolist()\n"
                "[[0.0, 1.0], [-0.25, -0.15]]"
            ),
            bind_examples=(
                "The kernel at one point gives `normal_jacobian` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 11.5, 0.1)\n"
                '>>> kernel = dynamics.bind_normal_jacobian(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[0.0, 1.0, -1.348, -5.8498]\n"
                ">>> ref = dynamics.normal_jacobian(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "-omega1^2 X1 - 2 beta1 omega1 X1' at t = 0 (no excitation):\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> round(float(dynamics.free_acceleration(0.0, 1.0, 0.5, **BASE)), 4)\n"
                "-1.1"
            ),
            bind_examples=(
                "The kernel at one point gives `free_acceleration` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5)\n"
                '>>> kernel = dynamics.bind_free_acceleration(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[28.7253]\n"
                ">>> ref = dynamics.free_acceleration(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "At Omega t = pi/2 both reach their amplitude alpha Omega^2 = 2 * 4^2:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import math\n"
                ">>> f_t, f_n = dynamics.excitation(math.pi / 8, **BASE)\n"
                ">>> round(float(f_t), 4), round(float(f_n), 4)\n"
                "(32.0, -32.0)"
            ),
            bind_examples=(
                "The kernel at one point gives `excitation` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3,)\n"
                '>>> kernel = dynamics.bind_excitation(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[29.8253, -29.8253]\n"
                ">>> ref = dynamics.excitation(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Spring energy omega1^2 X1^2 / 2 and kinetic energy X1'^2 / 2:\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> float(dynamics.energy(1.0, 0.0, 0.0, 0.0, **BASE))\n"
                "0.5\n"
                ">>> float(dynamics.energy(0.0, 2.0, 0.0, 0.0, **BASE))\n"
                "2.0"
            ),
            bind_examples=(
                "The kernel at one point gives `energy` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (1.0, 0.5, 11.5, 0.1)\n"
                '>>> kernel = dynamics.bind_energy(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[-67.3368]\n"
                ">>> ref = dynamics.energy(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
            examples=(
                "Sliding at X1' = 1 against the belt (sgn = -1), at t = 0: no input,\n"
                "viscous 2 beta1 omega1 X1'^2 = 0.2, and friction -mu_s g X1' (it feeds energy):\n"
                "\n"
                ">>> from beltmdsm.generated import dynamics, unforced\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> X2 = float(unforced.equilibrium(**BASE)[2])\n"
                ">>> P = dynamics.power_balance(0.0, 0.0, 1.0, X2, 0.0, -1.0, **BASE)\n"
                ">>> [round(float(p), 4) for p in P]\n"
                "[0.0, 0.2, -3.924]"
            ),
            bind_examples=(
                "The kernel at one point gives `power_balance` there:\n"
                "\n"
                ">>> import numpy as np\n"
                ">>> from beltmdsm.generated import dynamics\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.3, 1.0, 0.5, 11.5, 0.1, -1.0)\n"
                '>>> kernel = dynamics.bind_power_balance(**BASE, backend="python")\n'
                ">>> np.round(np.ravel(kernel(*x)), 4).tolist()\n"
                "[11.9301, 0.1085, -2.0669]\n"
                ">>> ref = dynamics.power_balance(*x, **BASE)\n"
                ">>> bool(np.allclose(kernel(*x), np.ravel(ref)))\n"
                "True"
            ),
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
