"""The unforced system at its equilibrium: the spec of generated/unforced.py (Eqs. 9-12)."""

from __future__ import annotations

from .. import statespace as ss
from ..codegen import FunctionSpec, ModuleSpec
from ..model import STATE
from ._shared import (
    IN_CONTACT,
    LAWS_FC,
    STATE_DOCS,
    _or_refuse,
    _per,
)

__all__ = ["build"]

#: The imports of the Examples of `unforced`'s functions.
_IMPORTS = (
    ">>> from beltmdsm.generated import unforced\n"
    ">>> from beltmdsm.generated.parameters import BASE\n"
)


def build() -> ModuleSpec:
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
            examples="At the base set, X1 = mu_s g / omega1^2 = 0.4 * 9.81 / 1^2 (Coulomb), and\n"
            "X2 = (g / omega2^2)^(2/3) (Hertz-Damp):\n\n"
            + _IMPORTS
            + ">>> X1, Y1, X2, Y2 = unforced.equilibrium(**BASE)\n"
            + ">>> round(float(X1), 4), round(float(X2), 4), round((9.81 / 0.5**2) ** (2 / 3), 4)\n"
            + "(3.924, 11.5474, 11.5474)",
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
            examples="Evaluated at the equilibrium, it is J^0 (Eq. 11):\n\n"
            + _IMPORTS
            + ">>> import numpy as np\n"
            + ">>> J = unforced.jacobian(*unforced.equilibrium(**BASE), **BASE)\n"
            + ">>> J.shape, bool(np.allclose(J, unforced.jacobian_at_equilibrium(**BASE)))\n"
            + "((4, 4), True)",
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
            examples="Block triangular; for Coulomb's law the tangential block is\n"
            "[[0, 1], [-omega1^2, -2 beta1 omega1]], with no friction slope:\n\n"
            + _IMPORTS
            + ">>> J0 = unforced.jacobian_at_equilibrium(**BASE)\n"
            + ">>> J0[:2, :2].round(4).tolist(), J0[2:, :2].tolist()\n"
            + "([[0.0, 1.0], [-1.0, -0.2]], [[0.0, 0.0], [0.0, 0.0]])",
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
            examples="mu_s does not change the coefficients for Coulomb's law (the claim below\n"
            "Eq. 12):\n\n"
            + _IMPORTS
            + ">>> [round(float(a), 4) for a in unforced.charpoly(**BASE)]\n"
            + "[6.086, 3.4515, 6.1409, 1.2743]\n"
            + '>>> [round(float(a), 4) for a in unforced.charpoly(**{**BASE, "mu_s": 0.1})]\n'
            + "[6.086, 3.4515, 6.1409, 1.2743]",
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
            examples="For Coulomb's law the tangential pair is\n"
            "-beta1 omega1 +- i omega1 sqrt(1 - beta1^2) = -0.1 +- 0.995i at the base set:\n\n"
            + _IMPORTS
            + ">>> lam = unforced.eigenvalues(**BASE)\n"
            + ">>> [complex(round(z.real, 4), round(z.imag, 4)) for z in lam[:2]]\n"
            + "[(-0.1+0.995j), (-0.1-0.995j)]",
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
            examples="Stribeck's law at the base set:\n"
            "v_s log(g (mu_s - mu_k) / (2 beta1 omega1 v_s)) = log(9.81 * 0.15 / 0.2);\n"
            "Coulomb's law has none (NaN):\n\n"
            + _IMPORTS
            + '>>> round(float(unforced.critical_belt_speed(**BASE, friction="stribeck")), 4)\n'
            + "1.9957\n"
            + ">>> import math; round(math.log(9.81 * 0.15 / 0.2), 4)\n"
            + "1.9957\n"
            + ">>> float(unforced.critical_belt_speed(**BASE))\n"
            + "nan",
        ),
    )
    return ModuleSpec(
        "unforced",
        """The unforced system at its equilibrium (Sect. 4.1, Eqs. 9-12).

Every friction and contact law of the registry (``friction=``, ``contact=``; the
choices are ``beltmdsm.generated.parameters.OPTIONS``, the defaults the paper's Eqs. 1 and 3).
Every function takes the parameters as keywords.
""",
        functions,
    )
