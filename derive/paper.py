"""The paper's numbered equations, typed by hand exactly as printed.

Each equation is a text constant ``EQ_<number>`` (``EQ_A4`` for the appendix) in
SymPy syntax, next to the function that parses it. Nothing here is derived: the
texts are copied from the paper, including what looks wrong, so that
`beltmdsm.derive.paper_check` can compare them with the derivation and report every
difference instead of silently fixing it.

The texts use the paper's notation in ASCII:

* parameters as in the parameter table (``beta2``, ``omega2`` are the starred
  Hertz-Damp ``beta2*``, ``omega2*``; ``Omega`` is ``Omega_e``);
* a dot is ``dot``: ``X1dot`` is ``X1'``, ``Z1ddot`` is ``Z1''``;
* ``mu_bar_0`` and ``mu_bar_p`` are ``mu_bar^0`` and the slope ``mu_bar'`` (Eqs. 22-25);
* in the fast equations (A1-A2) a prime is ``D(., theta)`` and a dot ``D(., tau)``;
* ``sgn``, ``arccos``, ``det`` as printed.

`parse` is strict: a name that is not in the notation above (a typo such as
``omgea1``) raises ``NameError`` instead of becoming a new symbol, and a syntax
error raises. Number literals are exact (``3/2`` is a rational).
"""

from __future__ import annotations

import sympy as sp
from sympy.parsing.sympy_parser import auto_number, parse_expr

from . import mdsm
from .fit import X2max
from .friction import Vr
from .model import X1, X2, Y1, Y2, P, lam, t
from .stability import S1, S2, Z1, Z2, mu0, mu1, mu_bar

__all__ = [
    "parse",
    "a_symbols",
    "X1ddot",
    "X2ddot",
    "NOTATION",
    "TRANSCRIPTIONS",
    "eq_4",
    "eq_5",
    "eq_6",
    "eq_7",
    "eq_8",
    "eq_9",
    "eq_10",
    "eq_11",
    "eq_12",
    "eq_13",
    "eq_14",
    "eq_15",
    "eq_16",
    "eq_17",
    "eq_18",
    "eq_19",
    "eq_20",
    "eq_21",
    "eq_22",
    "eq_23",
    "eq_24",
    "eq_25_mu0",
    "eq_25_slope",
    "eq_26",
    "eq_27",
    "eq_28",
    "eq_A1",
    "eq_A2",
    "eq_A3",
    "eq_A4",
    "eq_A5",
    "eq_A6",
    "eq_A7",
    "eq_A8",
]

X1ddot, X2ddot = sp.symbols("X1ddot X2ddot", real=True)
#: The coefficients of the quartic (27) as free symbols (Eq. 28 is generic in them).
a_symbols = sp.symbols("a1:5", real=True)

_PARAMETERS = {
    name: P[name]
    for name in ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g", "Vb", "Vhat")
}
_FUNCTIONS = {
    "sgn": sp.sign,
    "arccos": sp.acos,
    "sqrt": sp.sqrt,
    "sin": sp.sin,
    "Abs": sp.Abs,
    "pi": sp.pi,
    "Piecewise": sp.Piecewise,
    "Matrix": sp.Matrix,
    "eye": sp.eye,
    "Integral": sp.Integral,
    "Derivative": sp.Derivative,
    "Subs": sp.Subs,
    "D": sp.Derivative,
    "det": lambda M: M.det(method="berkowitz"),
}

#: Names a transcription may use, per notation: the total motion and slow state
#: space (Sect. 4.1, A.2), and the MDSM split (Eqs. 13-21, A1-A2) whose slow
#: variables are functions of the slow time ``tau``.
NOTATION: dict[str, dict[str, object]] = {
    "state": {
        **_PARAMETERS,
        **_FUNCTIONS,
        "t": t,
        "lam": lam,
        "Vr": Vr,
        "X1": X1,
        "X2": X2,
        "Y1": Y1,
        "Y2": Y2,
        "X1dot": Y1,
        "X2dot": Y2,
        "X1ddot": X1ddot,
        "X2ddot": X2ddot,
        "Z1": Z1,
        "Z2": Z2,
        "S1": S1,
        "S2": S2,
        "Z1dot": S1,
        "Z2dot": S2,
        "mu_bar": mu_bar,
        "mu_bar_0": mu0,
        "mu_bar_p": mu1,
        "X2max": X2max,
        **dict(zip(("a1", "a2", "a3", "a4"), a_symbols)),
    },
    "mdsm": {
        **_PARAMETERS,
        **_FUNCTIONS,
        "tau": mdsm.tau,
        "theta": mdsm.theta,
        "Z1": mdsm.Z1,
        "Z2": mdsm.Z2,
        "Phi1": mdsm.Phi1,
        "Phi2": mdsm.Phi2,
        "Z1dot": sp.diff(mdsm.Z1, mdsm.tau),
        "Z2dot": sp.diff(mdsm.Z2, mdsm.tau),
        "Z1ddot": sp.diff(mdsm.Z1, mdsm.tau, 2),
        "Z2ddot": sp.diff(mdsm.Z2, mdsm.tau, 2),
        "mu": mdsm.mu,
        "mu_bar": mdsm.mu_bar,
        **{f"c{k}": ck for k, ck in enumerate(mdsm.c)},
    },
}

_GLOBALS = {"Integer": sp.Integer, "Float": sp.Float, "Rational": sp.Rational, "__builtins__": {}}


def parse(text: str, notation: str = "state", **bound):
    """Parse a transcription; unknown names and syntax errors raise.

    Parameters
    ----------
    text : str
        SymPy syntax in the notation of the module docstring.
    notation : {"state", "mdsm"}
        Which names are known (see `NOTATION`).
    **bound
        Further names bound to earlier transcriptions (``J0`` for Eq. 12 is Eq. 11).

    Raises
    ------
    SyntaxError, NameError, TypeError, sympy.parsing.sympy_parser.TokenError
        On any typo: nothing is skipped or guessed.
    """
    names = {**NOTATION[notation], **bound}
    # Parenthesised so that a multi-line text continues across its line breaks.
    return parse_expr(
        f"({text})", local_dict=names, global_dict=dict(_GLOBALS), transformations=(auto_number,)
    )


# Sect. 2 -------------------------------------------------------------------------

#: Eq. (4) in matrix form, written as left side minus right side (a residual).
EQ_4 = """
Matrix([[1, 0], [0, 1]]) * Matrix([X1ddot, X2ddot])
+ Matrix([[2*beta1*omega1, 0], [0, 2*beta2*omega2*X2**(3/2)]]) * Matrix([X1dot, X2dot])
+ Matrix([[omega1**2, 0], [0, omega2**2]]) * Matrix([X1, X2**(3/2)])
+ Matrix([mu_s*sgn(X1dot - Vb)*(2*beta2*omega2*X2**(3/2)*X2dot + omega2**2*X2**(3/2)), -g])
- Matrix([alpha*Omega**2*sin(Omega*t), -alpha*Omega**2*sin(Omega*t)])
"""


def eq_4() -> sp.Matrix:
    """Eq. (4) as the residual ``M X'' + C X' + K (X1, X2^(3/2)) + f - F``."""
    return parse(EQ_4)


# Sect. 4.1 -----------------------------------------------------------------------
# Eqs. (5)-(8): each is the right-hand side of the state equation it defines
# (Eq. 5 "Y1 = X1'" is the equation X1' = Y1).

EQ_5 = "Y1"
EQ_6 = (
    "-2*beta1*omega1*Y1 - omega1**2*X1 + mu_s*(2*beta2*omega2*X2**(3/2)*Y2 + omega2**2*X2**(3/2))"
)
EQ_7 = "Y2"
EQ_8 = "-2*beta2*omega2*X2**(3/2)*Y2 - omega2**2*X2**(3/2) + g"

#: Eq. (9): (X1^0, Y1^0, X2^0, Y2^0).
EQ_9 = "Matrix([mu_s*g/omega1**2, 0, (g/omega2**2)**(2/3), 0])"

EQ_10 = """Matrix([
 [0, 1, 0, 0],
 [-omega1**2, -2*beta1*omega1,
  mu_s*(3*beta2*omega2*X2**(1/2)*Y2 + 3/2*omega2**2*X2**(1/2)),
  2*mu_s*beta2*omega2*X2**(3/2)],
 [0, 0, 0, 1],
 [0, 0, -3*beta2*omega2*X2**(1/2)*Y2 - 3/2*omega2**2*X2**(1/2),
  -2*beta2*omega2*X2**(3/2)]])"""

EQ_11 = """Matrix([
 [0, 1, 0, 0],
 [-omega1**2, -2*beta1*omega1, 3/2*mu_s*omega2**2*(g/omega2**2)**(1/3),
  2*mu_s*beta2*g/omega2],
 [0, 0, 0, 1],
 [0, 0, -3/2*omega2**2*(g/omega2**2)**(1/3), -2*beta2*g/omega2]])"""

#: Eq. (12): the left side of |lambda I - J^0| = 0, with J^0 of Eq. (11).
EQ_12 = "det(lam*eye(4) - J0)"


def eq_5():
    """Eq. (5): ``X1' = Y1``."""
    return parse(EQ_5)


def eq_6():
    """Eq. (6): ``Y1'`` on the branch ``X1' < Vb`` (sign of friction resolved)."""
    return parse(EQ_6)


def eq_7():
    """Eq. (7): ``X2' = Y2``."""
    return parse(EQ_7)


def eq_8():
    """Eq. (8): ``Y2'``."""
    return parse(EQ_8)


def eq_9() -> sp.Matrix:
    """Eq. (9): the unforced equilibrium ``(X1^0, Y1^0, X2^0, Y2^0)``."""
    return parse(EQ_9)


def eq_10() -> sp.Matrix:
    """Eq. (10): the Jacobian of Eqs. (5)-(8) (right-hand matrix)."""
    return parse(EQ_10)


def eq_11() -> sp.Matrix:
    """Eq. (11): ``J^0``, the Jacobian at the equilibrium."""
    return parse(EQ_11)


def eq_12():
    """Eq. (12): ``|lambda I - J^0|`` with the printed ``J^0`` of Eq. (11)."""
    return parse(EQ_12, J0=eq_11())


# Sect. 4.2: the MDSM split ---------------------------------------------------------

EQ_13 = "Z1 + Omega**(-1)*Phi1"
EQ_14 = "Z2 + Omega**(-1)*Phi2"
#: Eq. (15): the average operator, applied to a fast function ``f(theta)``
#: (``theta = Omega tau``); the constraint is that it vanishes for ``f = Phi``.
EQ_15 = "1/(2*pi)*Integral(f, (theta, 0, 2*pi))"


def eq_13():
    """Eq. (13): ``X1 = Z1 + Omega^-1 Phi1(tau, Omega tau)``."""
    return parse(EQ_13, "mdsm")


def eq_14():
    """Eq. (14): ``X2 = Z2 + Omega^-1 Phi2(tau, Omega tau)``."""
    return parse(EQ_14, "mdsm")


def eq_15(f):
    """Eq. (15): ``<f> = (1/2 pi) int_0^2pi f d(Omega tau)`` for an expression ``f``."""
    return parse(EQ_15, "mdsm", f=f).doit()


# Eqs. (16)-(17): the cubic fit -----------------------------------------------------

EQ_16 = "c3*X2**3 + c2*X2**2 + c1*X2 + c0"
#: Eq. (17) in the printed order (c3, c2, c1, c0).
EQ_17 = """Matrix([-8/(33*X2max**(3/2)), 72/(77*X2max**(1/2)),
                   24*X2max**(1/2)/77, -8*X2max**(3/2)/1155])"""


def eq_17() -> sp.Matrix:
    """Eq. (17): ``(c3, c2, c1, c0)`` as printed."""
    return parse(EQ_17)


def eq_16():
    """Eq. (16): the cubic in ``X2`` with the printed coefficients of Eq. (17)."""
    c3, c2, c1, c0 = eq_17()
    return parse(EQ_16, c3=c3, c2=c2, c1=c1, c0=c0)


# Eqs. (18)-(21): slow motion, residuals "= 0" ---------------------------------------

EQ_18 = (
    "Z1ddot + 2*beta1*omega1*Z1dot + omega1**2*Z1"
    " + mu_bar*(2*beta2*omega2*Z2dot + omega2**2)*(c3*Z2**3 + c2*Z2**2 + c1*Z2 + c0)"
)
EQ_19 = "Z2ddot + (2*beta2*omega2*Z2dot + omega2**2)*(c3*Z2**3 + c2*Z2**2 + c1*Z2 + c0) - g"
EQ_20 = (
    "Z1ddot + 2*beta1*omega1*Z1dot + omega1**2*Z1"
    " + mu_bar*(2*beta2*omega2*Z2dot + omega2**2)*Z2**(3/2)"
)
EQ_21 = "Z2ddot + (2*beta2*omega2*Z2dot + omega2**2)*Z2**(3/2) - g"


def eq_18():
    """Eq. (18), tangential slow motion with the cubic."""
    return parse(EQ_18, "mdsm")


def eq_19():
    """Eq. (19), normal slow motion with the cubic."""
    return parse(EQ_19, "mdsm")


def eq_20():
    """Eq. (20), Eq. (18) with ``Z2^(3/2)``."""
    return parse(EQ_20, "mdsm")


def eq_21():
    """Eq. (21), Eq. (19) with ``Z2^(3/2)``."""
    return parse(EQ_21, "mdsm")


# Eqs. (22)-(28): forced stability ---------------------------------------------------

EQ_22 = """Matrix([
 [0, 1, 0, 0],
 [-omega1**2, -2*beta1*omega1 + mu_bar_p*g, 3/2*mu_bar_0*omega2**2*(g/omega2**2)**(1/3),
  2*mu_bar_0*beta2*g/omega2],
 [0, 0, 0, 1],
 [0, 0, -3/2*omega2**2*(g/omega2**2)**(1/3), -2*beta2*g/omega2]])"""

EQ_23 = """Piecewise(
 (mu_s*(1 - 2/pi*arccos((Z1dot - Vb)/Vhat)), Abs(Z1dot - Vb) <= Vhat),
 (mu_s*sgn(Z1dot - Vb), Abs(Z1dot - Vb) >= Vhat))"""

#: Eq. (24) without the remainder O(Z1'^2); ``mu_bar`` is Eq. (23), ``mu_bar_0`` Eq. (25).
EQ_24 = "mu_bar_0 + Subs(Derivative(mu_bar, Z1dot), Z1dot, 0)*Z1dot"

#: Eq. (25), first part: mu_bar^0 = mu_bar(Z1'^0), with Z1'^0 = S1^0 = 0 (Eq. A7).
EQ_25_MU0 = "Subs(mu_bar, Z1dot, 0)"
#: The same with the argument read as Eq. (23)'s left side mu_bar(V_r): V_r = Z1'^0 = 0.
EQ_25_MU0_VR = "Subs(mu_bar, Vr, 0)"
#: Eq. (25), second part, "for Vhat > Vb".
EQ_25_SLOPE = "2*mu_s/(pi*Vhat*sqrt(1 - (Vb/Vhat)**2))"

EQ_26 = "det(lam*eye(4) - J_f0)"
EQ_27 = "lam**4 + a1*lam**3 + a2*lam**2 + a3*lam + a4"
EQ_28 = """Matrix([
 a1,
 a1*a2 - a3,
 a1*a2*a3 - a3**2 - a4*a1**2,
 a1*a2*a3*a4 - a1*a4**2 - a4*a3**2])"""


def eq_22() -> sp.Matrix:
    """Eq. (22): ``J_f^0`` in ``mu_bar^0`` and ``mu_bar'``."""
    return parse(EQ_22)


def eq_23():
    """Eq. (23): the effective friction in ``Z1'`` (as printed, sign of ``Z1' - Vb``)."""
    return parse(EQ_23)


def eq_25_mu0(argument: str = "Z1dot"):
    """Eq. (25): ``mu_bar^0 = mu_bar(Z1'^0)`` with Eq. (23).

    Parameters
    ----------
    argument : {"Z1dot", "Vr"}
        What ``mu_bar(.)`` takes: ``Z1'`` (Eq. 23's pieces are written in
        ``Z1' - Vb``) or ``V_r`` (Eq. 23's left side is ``mu_bar(V_r)``).
    """
    if argument == "Z1dot":
        return parse(EQ_25_MU0, mu_bar=eq_23()).doit()
    in_vr = eq_23().subs(S1, Vr + P["Vb"])
    return parse(EQ_25_MU0_VR, mu_bar=in_vr).doit()


def eq_25_slope():
    """Eq. (25): ``mu_bar'`` for ``Vhat > Vb``."""
    return parse(EQ_25_SLOPE)


def eq_24():
    """Eq. (24) to first order, with the printed Eqs. (23) and (25)."""
    return parse(EQ_24, mu_bar=eq_23(), mu_bar_0=eq_25_mu0()).doit()


def eq_26():
    """Eq. (26): ``|lambda I - J_f^0|`` with the printed ``J_f^0`` of Eq. (22)."""
    return parse(EQ_26, J_f0=eq_22())


def eq_28() -> sp.Matrix:
    """Eq. (28): ``H1..H4`` as printed, in the symbols ``a1..a4``."""
    return parse(EQ_28)


# Appendix A.2 ----------------------------------------------------------------------

_CUBIC = (
    "(c3*(Z2 + Omega**(-1)*Phi2)**3 + c2*(Z2 + Omega**(-1)*Phi2)**2"
    " + c1*(Z2 + Omega**(-1)*Phi2) + c0)"
)
_SLOW_CUBIC = "(c3*Z2**3 + c2*Z2**2 + c1*Z2 + c0)"

#: Eq. (A1), left side minus right side.
EQ_A1 = (
    "Omega*D(Phi1, theta, theta) + 2*D(Phi1, tau, theta) + Omega**(-1)*D(Phi1, tau, tau)"
    " + 2*beta1*omega1*(D(Phi1, theta) + Omega**(-1)*D(Phi1, tau))"
    " + omega1**2*Omega**(-1)*Phi1"
    " + mu(Z1dot - Vb + D(Phi1, theta) + Omega**(-1)*D(Phi1, tau))"
    " * (2*beta2*omega2*(Z2dot + D(Phi2, theta) + Omega**(-1)*D(Phi2, tau)) + omega2**2)"
    f" * {_CUBIC}"
    f" - mu_bar*(2*beta2*omega2*Z2dot + omega2**2)*{_SLOW_CUBIC}"
    " - alpha*Omega**2*sin(Omega*tau)"
)

#: Eq. (A2), left side minus right side.
EQ_A2 = (
    "Omega*D(Phi2, theta, theta) + 2*D(Phi2, tau, theta) + Omega**(-1)*D(Phi2, tau, tau)"
    " + (2*beta2*omega2*(Z2dot + D(Phi2, theta) + Omega**(-1)*D(Phi2, tau)) + omega2**2)"
    f" * {_CUBIC}"
    f" - (2*beta2*omega2*Z2dot + omega2**2)*{_SLOW_CUBIC}"
    " + alpha*Omega**2*sin(Omega*tau)"
)


def _fast_time(expr):
    """``sin(Omega_e tau)`` is the fast phase: the second argument ``theta`` of ``Phi``."""
    return expr.subs(sp.sin(P["Omega"] * mdsm.tau), sp.sin(mdsm.theta))


def eq_A1():
    """Eq. (A1): the tangential fast equation as a residual (``mu`` the Coulomb law)."""
    return _fast_time(parse(EQ_A1, "mdsm"))


def eq_A2():
    """Eq. (A2): the normal fast equation as a residual."""
    return _fast_time(parse(EQ_A2, "mdsm"))


# Eqs. (A3)-(A6): right-hand sides of the slow state equations; mu_bar printed
# without argument is that of Eq. (23), mu_bar(Z1' - Vb).
EQ_A3 = "S1"
EQ_A4 = (
    "-2*beta1*omega1*S1 - omega1**2*Z1"
    " + mu_bar(Z1dot - Vb)*(2*beta2*omega2*S2 + omega2**2)*Z2**(3/2)"
)
EQ_A5 = "S2"
EQ_A6 = "-(2*beta2*omega2*S2 + omega2**2)*Z2**(3/2) + g"
#: Eq. (A7): (Z1^0, S1^0, Z2^0, S2^0).
EQ_A7 = "Matrix([mu_bar_0*g/omega1**2, 0, (g/omega2**2)**(2/3), 0])"
#: Eq. (A8): (a1, a2, a3, a4).
EQ_A8 = """Matrix([
 2*beta1*omega1 - mu_bar_p*g + 2*beta2*g/omega2,
 omega1**2 + (-2*beta1*omega1 + mu_bar_p*g)*(-2*beta2*g/omega2)
  + 3/2*omega2**2*(g/omega2**2)**(1/3),
 2*beta2*g*omega1**2/omega2 + (-2*beta1*omega1 + mu_bar_p*g)
  *(-3/2*omega2**2*(g/omega2**2)**(1/3)),
 3/2*omega1**2*omega2**2*(g/omega2**2)**(1/3)])"""


def eq_A3():
    """Eq. (A3): ``Z1' = S1``."""
    return parse(EQ_A3)


def eq_A4():
    """Eq. (A4): ``S1'`` with ``+ mu_bar (...) Z2^(3/2)`` as printed."""
    return parse(EQ_A4)


def eq_A5():
    """Eq. (A5): ``Z2' = S2``."""
    return parse(EQ_A5)


def eq_A6():
    """Eq. (A6): ``S2'``."""
    return parse(EQ_A6)


def eq_A7() -> sp.Matrix:
    """Eq. (A7): the slow equilibrium ``(Z1^0, S1^0, Z2^0, S2^0)``."""
    return parse(EQ_A7)


def eq_A8() -> sp.Matrix:
    """Eq. (A8): ``a1..a4`` in ``mu_bar'``."""
    return parse(EQ_A8)


def eq_27():
    """Eq. (27): the quartic with the printed ``a1..a4`` of Eq. (A8)."""
    return parse(EQ_27, **dict(zip(("a1", "a2", "a3", "a4"), eq_A8())))


#: Every transcription text by the name of its constant (for tests and the report).
TRANSCRIPTIONS = {
    name: value
    for name, value in sorted(globals().items())
    if name.startswith("EQ_") and isinstance(value, str)
}
