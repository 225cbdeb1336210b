"""The Method of Direct Separation of Motion: Eqs. (13)-(21) and (A1)-(A2).

Eq. (4) with the polynomial contact force of Eq. (16) (the contact law's power of the
penetration replaced by the cubic of `beltmdsm.derive.fit`; nothing to replace for the linear
law of Fig. 16) is written for
``X = Z(tau) + Omega^-1 Phi(tau, theta)``, ``theta = Omega tau`` (Eqs. 13-14), so that

    X'  = Z' + Omega^-1 Phi_tau + Phi_theta,
    X'' = Z'' + Omega^-1 Phi_tautau + 2 Phi_tautheta + Omega Phi_thetatheta.

The average over the fast period (Eq. 15), with ``<Phi> = 0``, is applied term by term:

* a term without fast factors is slow and stays;
* a term linear in one fast quantity (``Phi``, any derivative of it, ``sin theta``)
  averages to zero, and so does ``Phi^k Phi_theta`` (an exact theta-derivative);
* every other product stays as an unevaluated average ``avg(...)``;
* the friction term ``mu(Vr) N`` (``mu`` the friction law with its direction, any
  law of `beltmdsm.derive.laws`; ``N`` the normal force of the total motion) becomes
  ``mu_bar <N> + cov(mu, N)``, with ``mu_bar = <mu(Vr)>`` the effective friction of
  Eq. (23) (`beltmdsm.derive.friction` derives it for each law).

Each term of the averaged equations is labelled with what the paper does with it
(docs/modelling.md#averaging): Eqs. (18)-(19) keep the slow terms and
``mu_bar N(Z)`` and drop the averages of powers of ``Phi2`` (from the cubic and from
the damping) and the correlation ``cov(mu, N)`` of the fast friction direction with
the fast normal force.
`harmonic_averages` evaluates the dropped averages for a harmonic fast motion, so
their size can be shown next to the kept terms.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

from . import laws
from .fit import X2max, coefficients_eq_17, exponent
from .friction import frequency_response, normal_block
from .model import X2, Y2, P, equal_excitation, normal_force
from .statespace import equilibrium_eq_9

__all__ = [
    "fast_normal_amplitude",
    "x2max",
    "dropped_at_equilibrium",
    "tau",
    "theta",
    "Z1",
    "Z2",
    "Phi1",
    "Phi2",
    "c",
    "mu",
    "mu_bar",
    "avg",
    "cov",
    "split_eqs_13_14",
    "polynomial_eq_16",
    "equations_of_motion_split",
    "Term",
    "averaged_terms",
    "slow_equations_18_19",
    "slow_equations_20_21",
    "fast_equations_A1_A2",
    "harmonic_averages",
]

tau, theta = sp.symbols("tau theta", real=True)
Z1, Z2 = sp.Function("Z1", real=True)(tau), sp.Function("Z2", real=True)(tau)
Phi1 = sp.Function("Phi1", real=True)(tau, theta)
Phi2 = sp.Function("Phi2", real=True)(tau, theta)
#: Coefficients of the cubic of Eq. (16).
c = sp.symbols("c0:4", real=True)
#: The friction law with its direction, mu(|Vr|) sgn(Vr) (Eq. 3 for Coulomb's law),
#: kept as an unknown function: the split and the averaging hold for every law.
mu = sp.Function("mu")
_CONTACT = laws.default("contact")
#: The effective friction <mu(Vr)> of Eq. (23).
mu_bar = sp.Symbol("mu_bar", real=True)
#: Unevaluated average over the fast period, and covariance, Eq. (15).
avg = sp.Function("avg")
cov = sp.Function("cov")


def _d(f):
    """Total derivative in tau of a function of (tau, theta = Omega tau)."""
    return sp.diff(f, tau) + P["Omega"] * sp.diff(f, theta)


def split_eqs_13_14():
    """``(X1, X2)`` and their first and second derivatives for Eqs. (13)-(14)."""
    eps = 1 / P["Omega"]
    X = [Z1 + eps * Phi1, Z2 + eps * Phi2]
    Xd = [sp.expand(_d(x)) for x in X]
    Xdd = [sp.expand(_d(x)) for x in Xd]
    return X, Xd, Xdd


def polynomial_eq_16(x):
    """``c3 x^3 + c2 x^2 + c1 x + c0`` (Eq. 16), with the coefficients as symbols."""
    return sum(ck * x**k for k, ck in enumerate(c))


def _normal(x, xd, contact=_CONTACT):
    """The contact law's normal force with its power ``X2^n`` replaced by the cubic (Eq. 16).

    A law whose force is a polynomial in ``X2`` (an integer ``n``) is left as it is.
    """
    F = normal_force(contact)
    n = exponent(contact)
    if not (n.is_integer and n.is_nonnegative):
        F = F.subs(X2**n, polynomial_eq_16(X2))
    return F.xreplace({X2: x, Y2: xd})


def equations_of_motion_split(contact: str = _CONTACT):
    """Eq. (4) with Eq. (16), in the split variables: ``(linear part, friction, normal)``.

    Returns the tangential equation as its part without friction, the friction
    ``mu(Vr) N`` separately (it is averaged by decomposition, not by expansion), and the
    normal equation, all as residuals ``= 0``.
    """
    b1, w1, a, W, g, Vb = (P[k] for k in ("beta1", "omega1", "alpha", "Omega", "g", "Vb"))
    X, Xd, Xdd = split_eqs_13_14()
    force = a * W**2 * sp.sin(theta)
    N = _normal(X[1], Xd[1], contact)
    tangential = Xdd[0] + 2 * b1 * w1 * Xd[0] + w1**2 * X[0] - force
    friction = mu(Xd[0] - Vb) * N
    normal = Xdd[1] + N - g + force
    return sp.expand(tangential), friction, sp.expand(normal)


def _is_fast(f):
    return f.has(theta)


def _average_monomial(term):
    """``<term>`` by the rules of the module docstring."""
    slow, fast = [], []
    for f in sp.Mul.make_args(term):
        (fast if _is_fast(f) else slow).append(f)
    if not fast:
        return term
    product = sp.Mul(*fast)
    powers = [f.as_base_exp() for f in sp.Mul.make_args(product)]
    if len(powers) == 1 and powers[0][1] == 1:
        return sp.Integer(0)
    derivs = [b for b, e in powers if isinstance(b, sp.Derivative)]
    plain = [(b, e) for b, e in powers if not isinstance(b, sp.Derivative)]
    if (
        len(derivs) == 1
        and derivs[0].variables == (theta,)
        and all(b == derivs[0].expr for b, _ in plain)
        and dict(powers)[derivs[0]] == 1
    ):
        return sp.Integer(0)  # Phi^k Phi_theta = d/dtheta Phi^(k+1)/(k+1)
    return sp.Mul(*slow) * avg(product)


def _average(expr):
    return sp.Add(*(_average_monomial(t) for t in sp.Add.make_args(sp.expand(expr))))


@dataclass(frozen=True)
class Term:
    """One term of an averaged slow equation and what the paper does with it."""

    equation: str
    expr: sp.Expr
    kept: bool
    label: str


def _label(term):
    if not term.has(avg) and not term.has(cov):
        return True, "slow"
    if term.has(cov):
        return False, "correlation of the fast friction direction with the fast normal force"
    fast = [a.args[0] for a in term.atoms(avg)]
    if any(f.has(sp.Derivative) for f in fast):
        return False, "average of fast normal velocity times powers of Phi2 (damping)"
    return False, "average of powers of Phi2 (from the cubic)"


@cache
def averaged_terms(contact: str = _CONTACT) -> tuple[Term, ...]:
    """Every term of the averaged equations of slow motion, labelled (kept or dropped)."""
    tangential, _, normal = equations_of_motion_split(contact)
    X, Xd, _ = split_eqs_13_14()
    N = _normal(X[1], Xd[1], contact)
    N_avg = _average(N)
    N_slow = _normal(Z2, sp.diff(Z2, tau), contact)
    out = []
    for t in sp.Add.make_args(_average(tangential)):
        out.append(Term("tangential", t, *_label(t)))
    out.append(
        Term(
            "tangential",
            mu_bar * sp.expand(N_slow),
            True,
            "effective friction times the slow normal force (mu_bar N(Z))",
        )
    )
    for t in sp.Add.make_args(sp.expand(mu_bar * (N_avg - N_slow))):
        kept, label = _label(t)
        out.append(Term("tangential", t, kept, "effective friction times " + label))
    correlation = cov(mu(Xd[0] - P["Vb"]), N)
    out.append(Term("tangential", correlation, *_label(correlation)))
    for t in sp.Add.make_args(_average(normal)):
        out.append(Term("normal", t, *_label(t)))
    return tuple(out)


def _slow(kept_only: bool, contact: str):
    terms = averaged_terms(contact)
    return sp.Matrix(
        [
            sp.Add(*(t.expr for t in terms if t.equation == eq and (t.kept or not kept_only)))
            for eq in ("tangential", "normal")
        ]
    )


def slow_equations_18_19(contact: str = _CONTACT) -> sp.Matrix:
    """The slow equations the paper keeps, Eqs. (18)-(19), as residuals ``= 0``."""
    return _slow(kept_only=True, contact=contact)


def slow_equations_20_21(contact: str = _CONTACT) -> sp.Matrix:
    """Eqs. (20)-(21): Eqs. (18)-(19) with the cubic put back as ``Z2^n``.

    Built from the contact law's normal force at the slow state and checked:
    replacing ``Z2^n`` by the cubic of Eq. (16) gives Eqs. (18)-(19) back.
    """
    b1, w1, g = P["beta1"], P["omega1"], P["g"]
    Z2d = sp.diff(Z2, tau)
    N = normal_force(contact, Z2, Z2d)
    eqs = sp.Matrix(
        [
            sp.diff(Z1, tau, 2) + 2 * b1 * w1 * sp.diff(Z1, tau) + w1**2 * Z1 + mu_bar * N,
            sp.diff(Z2, tau, 2) + N - g,
        ]
    )
    n = exponent(contact)
    back = eqs if n.is_integer else eqs.subs(Z2**n, polynomial_eq_16(Z2))
    if (back - slow_equations_18_19(contact)).applyfunc(sp.expand) != sp.zeros(2, 1):
        raise AssertionError(f"{contact}: Eqs. (20)-(21) do not reduce to Eqs. (18)-(19)")
    return eqs


def fast_equations_A1_A2(contact: str = _CONTACT) -> sp.Matrix:
    """Eqs. (A1)-(A2): Eq. (4) in split form minus the slow equations (18)-(19).

    As in the paper, only the kept slow terms are subtracted; the averages of these
    fast equations are then the dropped terms, not zero.
    """
    tangential, friction, normal = equations_of_motion_split(contact)
    slow = slow_equations_18_19(contact)
    return sp.Matrix([tangential + friction - slow[0], normal - slow[1]])


def harmonic_averages(expr, A1, A2, phase1=0, phase2=0):
    """Evaluate ``avg(...)`` for ``Phi_i = A_i sin(theta + phase_i)``, independent of tau.

    Each average becomes a closed form in the amplitudes (``A_i`` are the amplitudes of
    ``Phi``, i.e. ``Omega`` times the displacement amplitudes).
    """
    u = sp.Dummy("u", real=True)
    shapes = {
        Phi1.subs(theta, u): A1 * sp.sin(u + phase1),
        Phi2.subs(theta, u): A2 * sp.sin(u + phase2),
    }

    def evaluate(a):
        f = a.args[0].subs(theta, u)
        f = f.replace(
            lambda e: isinstance(e, sp.Derivative),
            lambda e: (
                sp.diff(e.expr.subs(theta, u).subs(shapes), u)
                if e.variables == (theta,)
                else sp.Integer(0)
            ),
        ).subs(shapes)
        return sp.integrate(sp.expand(f), (u, 0, 2 * sp.pi)) / (2 * sp.pi)

    return sp.sympify(expr).replace(lambda e: isinstance(e, avg), evaluate)


def fast_normal_amplitude(contact: str = _CONTACT) -> sp.Expr:
    """Displacement amplitude of the fast normal motion, linearised at Eq. (9).

    The normal block of Eq. (11) forced by ``-alpha_n Omega_n^2 sin``
    (`beltmdsm.derive.friction.normal_block`):
    ``alpha_n Omega_n^2 / |s - Omega_n^2 + i r Omega_n|``.
    """
    a, b = frequency_response(normal_block(contact), P["Omega_n"])
    return P["alpha_n"] * P["Omega_n"] ** 2 / sp.sqrt(a**2 + b**2)


def x2max(contact: str = _CONTACT) -> sp.Expr:
    """Upper end of the fitted range for the MDSM: ``X2^0`` plus the fast amplitude."""
    return equilibrium_eq_9(contact)[X2] + fast_normal_amplitude(contact)


def dropped_at_equilibrium(
    values: dict, contact: str = _CONTACT
) -> list[tuple[str, str, float, float]]:
    """Size of each dropped average at the slow equilibrium, for a harmonic fast motion.

    ``values`` maps parameter names to numbers (the base set, say). The cubic is the
    fit of Eq. (17) (of the contact law's power) on ``[0, x2max]``; ``Phi2`` has the
    amplitude ``Omega`` times `fast_normal_amplitude`; ``Z2 = X2^0`` (Eq. 9), ``Z2' = 0``.

    Returns
    -------
    list of (equation, label, value, relative)
        ``relative`` is the value over ``g`` (the size of the normal force it corrects).
        The correlation ``cov(mu, N)`` is not included: it needs the fast tangential
        motion as well (see docs/modelling.md#averaging).
    """
    subs = {P[k]: v for k, v in values.items() if k in P}
    subs.update({k: sp.sympify(v).subs(subs) for k, v in equal_excitation().items()})
    amp = fast_normal_amplitude(contact).subs(subs)
    top = x2max(contact).subs(subs)
    coeffs = {ck: v.subs(X2max, top).subs(subs) for ck, v in zip(c, coefficients_eq_17(3, contact))}
    z2 = equilibrium_eq_9(contact)[X2]
    A = sp.Symbol("A", positive=True)
    out = []
    for term in averaged_terms(contact):
        if term.kept or term.expr.has(cov) or term.expr.has(mu_bar):
            continue
        v = harmonic_averages(term.expr, 0, A).subs(sp.diff(Z2, tau), 0).subs(Z2, z2)
        v = float(v.subs(coeffs).subs(A, P["Omega"] * amp).subs(subs))
        if v != 0:
            out.append((term.equation, term.label, v, v / float(P["g"].subs(subs))))
    return out
