"""Friction correlated with the fast normal force: the spec of generated/correlation.py."""

from __future__ import annotations

import sympy as sp

from .. import correlation as cr
from ..codegen import FunctionSpec, ModuleSpec
from ._shared import (
    CONTACT,
    FRICTION,
    LAWS_FC,
    _per,
)

__all__ = ["build"]


def build() -> ModuleSpec:
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
        "beltmdsm.generated.capabilities) the law's part beyond mu(0) is a quadrature of the "
        "same expression (beltmdsm.generated._support.quad)."
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
            examples=(
                "With a constant normal force (N0 = 1, N1 = 0) it is Eq. (23) over mu_s:\n"
                "(2/pi) asin(1/2) = 1/3:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> round(float(correlation.averaged_friction(0.5, 1.0, 1.0, 0.0, 0.0)), 4)\n"
                "0.3333"
            ),
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
            examples=(
                "With N0 = 1, N1 = 0 at u = 0.6, V = 1: 2 / (pi sqrt(1 - 0.6^2)) = 2.5/pi:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> import math\n"
                ">>> s = correlation.averaged_friction_slope(0.6, 1.0, 1.0, 0.0, 0.0)\n"
                ">>> round(float(s), 4), round(2.5 / math.pi, 4)\n"
                "(0.7958, 0.7958)"
            ),
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
            examples=(
                "sgn(sin t) (u = 0, N0 = 1, N1 = 0) is a square wave: s1 = 4/pi, c1 = 0:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> import math\n"
                ">>> s1, c1 = correlation.first_harmonic(0.0, 1.0, 1.0, 0.0, 0.0)\n"
                ">>> round(float(s1), 4), round(float(c1), 4), round(4 / math.pi, 4)\n"
                "(1.2732, 0.0, 1.2732)"
            ),
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
            examples=(
                "Kelvin-Voigt: the penetration alpha Omega^2 / |omega2^2 - Omega^2 + 2i beta2\n"
                "omega2 Omega| times the contact's |omega2^2 + 2i beta2 omega2 Omega|:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                '>>> N1, psi = correlation.fast_normal_force(**BASE, contact="kelvin_voigt")\n'
                ">>> w2, b2, W = 0.5, 0.15, 4.0\n"
                ">>> contact = abs(w2**2 + 2j * b2 * w2 * W)\n"
                ">>> X2 = 2.0 * W**2 / abs(w2**2 - W**2 + 2j * b2 * w2 * W)\n"
                ">>> round(float(N1), 4), round(X2 * contact, 4)\n"
                "(1.3197, 1.3197)"
            ),
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
            examples=(
                "V is the coupled V_hat of `beltmdsm.generated.friction.vhat`:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> from beltmdsm.generated import friction\n"
                ">>> V, phi = correlation.fast_tangential_velocity(**BASE)\n"
                '>>> round(float(V), 4), round(float(friction.vhat(**BASE, model="coupled")), 4)\n'
                "(6.3754, 6.3754)"
            ),
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
            examples=(
                "Coulomb's law: mu_s times `averaged_friction`:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.5, 1.0, 9.81, 1.0, 0.3)\n"
                ">>> F = correlation.friction_average(*x, **BASE)\n"
                ">>> F0 = correlation.averaged_friction(*x)\n"
                ">>> round(float(F), 4), round(0.4 * float(F0), 4)\n"
                "(1.5187, 1.5187)"
            ),
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
            examples=(
                "Coulomb's law: mu_s times `averaged_friction_slope`:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.5, 1.0, 9.81, 1.0, 0.3)\n"
                ">>> s = correlation.friction_average_slope(*x, **BASE)\n"
                ">>> s0 = correlation.averaged_friction_slope(*x)\n"
                ">>> round(float(s), 4), round(0.4 * float(s0), 4)\n"
                "(2.7441, 2.7441)"
            ),
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
            examples=(
                "Coulomb's law: mu_s times `first_harmonic`:\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> x = (0.5, 1.0, 9.81, 1.0, 0.3)\n"
                ">>> [round(float(h), 4) for h in correlation.friction_harmonic(*x, **BASE)]\n"
                "[4.3489, 0.072]\n"
                ">>> [round(0.4 * float(h), 4) for h in correlation.first_harmonic(*x)]\n"
                "[4.3489, 0.072]"
            ),
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
            examples=(
                "Without a normal fluctuation (N1 = 0): 2 beta1 omega1 + g times the slope of\n"
                "Eq. (25) at Vb = 4, V = 5 (Coulomb):\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> from beltmdsm.generated import friction\n"
                ">>> p = correlation.slow_damping(5.0, 0.0, 0.0, **BASE)\n"
                ">>> slope = friction.mu_bar_slope(4.0, 5.0, 0.4)\n"
                ">>> round(float(p), 4), round(0.2 + 9.81 * float(slope), 4)\n"
                "(1.0327, 1.0327)"
            ),
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
            examples=(
                "(omega1^2 - Omega_t^2, 2 beta1 omega1 Omega_t) = (1 - 16, 0.8):\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                ">>> [round(float(q), 4) for q in correlation.transfer_function(**BASE)]\n"
                "[-15.0, 0.8]"
            ),
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
            examples=(
                "The linear responses solve it where friction never reverses (Vb = 10 > V):\n"
                "\n"
                ">>> from beltmdsm.generated import correlation\n"
                ">>> from beltmdsm.generated.parameters import BASE\n"
                '>>> P = {**BASE, "Vb": 10.0}\n'
                ">>> V, phi = correlation.fast_tangential_velocity(**P)\n"
                ">>> N1, psi = correlation.fast_normal_force(**P)\n"
                ">>> res = correlation.harmonic_balance(V, phi, N1, psi, **P)\n"
                ">>> [round(float(r), 10) + 0.0 for r in res]\n"
                "[0.0, 0.0]"
            ),
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
