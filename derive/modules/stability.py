"""Stability of the forced system (Sects. 4.2-4.3): the spec of generated/stability.py."""

from __future__ import annotations

import itertools

import sympy as sp

from .. import budget, laws
from .. import capabilities as cap
from .. import stability as st
from .. import statespace as ss
from ..codegen import FunctionSpec, ModuleSpec, NoVariant
from ..model import P
from ._shared import (
    LAWS_FC,
)

__all__ = ["build"]


#: The imports of the Examples of `stability`'s functions.
_STABILITY_IMPORTS = (
    ">>> from beltmdsm.generated import stability\n"
    ">>> from beltmdsm.generated.parameters import BASE\n"
)


def build() -> ModuleSpec:
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
        the printers' conditions are plain relations, not Piecewise values). NaN (no
        boundary) is below nothing."""
        if expr is sp.nan:
            return sp.false
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
            return NoVariant(
                f"friction={f!r} has no closed-form critical belt speed: {lower.reason}; the "
                "pointwise functions (growth_rate, is_stable, hurwitz) take it, and "
                "beltmdsm.prediction.paper.paper_intervals finds the unstable belt speeds "
                "numerically from growth_rate"
            )
        if lower is None:
            closed, why = cap.closed_form_average(f)
            return NoVariant(
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
            examples=(
                "Z1 = mu_bar^0 g / omega1^2 as printed (negative), the opposite sign in the\n"
                "consistent convention; mu_bar^0 at the base set's V_hat:\n"
                "\n"
                ">>> from beltmdsm.generated import stability\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> from beltmdsm.generated import friction\n"
                ">>> mu0 = friction.mu_bar0(4.0, friction.vhat(**BASE), 0.4)\n"
                ">>> Z1 = stability.equilibrium(**BASE)[0]\n"
                '>>> Z1c = stability.equilibrium(**BASE, convention="consistent")[0]\n'
                ">>> round(float(Z1), 4), round(float(Z1c), 4), round(float(mu0) * 9.81, 4)\n"
                "(-1.2206, 1.2206, -1.2206)"
            ),
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
            examples=(
                "Block triangular; its tangential damping entry is -2 beta1 omega1 + g mu_bar'\n"
                "(the paper's sign), positive at Vb = 4: negative damping:\n"
                "\n"
                ">>> from beltmdsm.generated import stability\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> from beltmdsm.generated import friction\n"
                ">>> J = stability.jacobian(**BASE)\n"
                ">>> slope = friction.mu_bar_slope(4.0, friction.vhat(**BASE), 0.4)\n"
                ">>> round(float(J[1, 1]), 4), round(-0.2 + 9.81 * float(slope), 4)\n"
                "(0.132, 0.132)\n"
                ">>> J[2:, :2].tolist()\n"
                "[[0.0, 0.0], [0.0, 0.0]]"
            ),
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
            examples=(
                "Those of det(lambda I - J) (numpy.poly):\n"
                "\n"
                ">>> from beltmdsm.generated import stability\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> import numpy as np\n"
                ">>> [round(float(a), 4) for a in stability.coefficients(**BASE)]\n"
                "[5.754, 1.4973, 5.7178, 1.2743]\n"
                ">>> np.poly(stability.jacobian(**BASE))[1:].round(4).tolist()\n"
                "[5.754, 1.4973, 5.7178, 1.2743]"
            ),
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
            examples=(
                "H1 = a1; H3 < 0 at Vb = 4, so the slow equilibrium is unstable:\n"
                "\n"
                ">>> from beltmdsm.generated import stability\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> [round(float(h), 4) for h in stability.hurwitz(**BASE)]\n"
                "[5.754, 2.8975, -25.6231, -32.6517]\n"
                '>>> bool(stability.is_stable(**BASE, backend="numpy"))\n'
                "False"
            ),
        ),
        FunctionSpec(
            "eigenvalues",
            "Eigenvalues of J_f^0 in closed form.",
            "Eq. (26), via its exact factorisation",
            "roots",
            "lam : complex ndarray, shape (..., 4)\n    Tangential pair, then normal pair.",
            each(quads),
            **common,
            examples=(
                "The largest real part is `growth_rate`; the tangential pair comes first:\n"
                "\n"
                ">>> from beltmdsm.generated import stability\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> lam = stability.eigenvalues(**BASE)\n"
                '>>> sigma = stability.growth_rate(**BASE, backend="numpy")\n'
                ">>> round(float(lam.real.max()), 4), round(float(sigma), 4)\n"
                "(0.066, 0.066)\n"
                ">>> [complex(round(z.real, 4), round(z.imag, 4)) for z in lam[:2]]\n"
                "[(0.066+0.9978j), (0.066-0.9978j)]"
            ),
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
            examples=_STABILITY_IMPORTS
            + '>>> sigma = stability.growth_rate(**{**BASE, "Vb": [5.0, 12.0]}, backend="numpy")\n'
            + ">>> [round(float(s), 4) for s in sigma]  # unstable at 5 m/s, stable at 12\n"
            + "[0.081, -0.1]",
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
            "(beltmdsm.derive.stability.stability_conditions): two sign tests, no "
            "determinant, root or power.",
            accelerate=True,
            examples=_STABILITY_IMPORTS
            + '>>> stability.is_stable(**{**BASE, "Vb": [5.0, 12.0]}, backend="numpy").tolist()\n'
            + "[False, True]",
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
            examples=_STABILITY_IMPORTS
            + '>>> round(float(stability.critical_belt_speed(**{**BASE, "mu_s": 0.1})), 4)\n'
            + "7.9285",
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
            examples=_STABILITY_IMPORTS
            + '>>> lower, upper = stability.unstable_interval(**{**BASE, "mu_s": 0.1})\n'
            + ">>> round(float(lower), 4), round(float(upper), 4)\n"
            + "(7.9285, 8.5212)",
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
