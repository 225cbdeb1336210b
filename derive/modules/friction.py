"""Effective friction (Eqs. 23-25) and V_hat: the spec of generated/friction.py."""

from __future__ import annotations

from .. import friction as fr
from .. import laws
from ..codegen import FunctionSpec, ModuleSpec
from ..model import P
from ._shared import (
    FRICTION,
    LAWS_FC,
    _per,
)

__all__ = ["build"]

#: The imports of the Examples of `friction`'s functions.
_IMPORTS = ">>> from beltmdsm.generated import friction\n"


def build() -> ModuleSpec:
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
        "beltmdsm.generated.capabilities) the law's part beyond mu(0) is a quadrature of the "
        "same expression (beltmdsm.generated._support.quad)."
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
            examples="Coulomb's law (Vhat = 1, mu_s = 0.4): -mu_s and mu_s outside |Vr| <= Vhat,\n"
            "0 at Vr = 0, and mu_s (1 - 2/pi acos(1/2)) = mu_s / 3 at Vr = 1/2:\n\n"
            + _IMPORTS
            + ">>> friction.mu_bar([-2.0, 0.0, 0.5, 2.0], 1.0, 0.4).round(4).tolist()\n"
            + "[-0.4, 0.0, 0.1333, 0.4]",
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
            examples="It is mu_bar at Vr = -Vb:\n\n"
            + _IMPORTS
            + ">>> round(float(friction.mu_bar0(0.5, 1.0, 0.4)), 4)\n"
            + "-0.1333\n"
            + ">>> round(float(friction.mu_bar(-0.5, 1.0, 0.4)), 4)\n"
            + "-0.1333",
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
            "enters the slow equations (beltmdsm.generated.stability). " + quadrature,
            examples="Coulomb's law (Vhat = 1, mu_s = 0.4): 2 mu_s / (pi sqrt(1 - 0.6^2)) = 1/pi\n"
            "at Vb = 0.6, +inf at Vb = Vhat, 0 beyond:\n\n"
            + _IMPORTS
            + ">>> friction.mu_bar_slope([0.6, 1.0, 2.0], 1.0, 0.4).round(4).tolist()\n"
            + "[0.3183, inf, 0.0]",
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
            examples="The tangential reading at the base set (Coulomb) is\n"
            "alpha Omega^3 / |omega1^2 - Omega^2 + 2i beta1 omega1 Omega|:\n\n"
            + _IMPORTS
            + ">>> from beltmdsm.generated.parameters import BASE\n"
            + ">>> round(float(friction.vhat(**BASE)), 4)\n"
            + "8.5212\n"
            + ">>> round(2.0 * 4.0**3 / abs(1.0 - 4.0**2 + 2j * 0.1 * 4.0), 4)\n"
            + "8.5212",
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
