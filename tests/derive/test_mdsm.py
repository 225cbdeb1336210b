"""The MDSM split (Eqs. 13-21, A1-A2): averaging rules, bookkeeping, sizes."""

import mpmath
import pytest
import sympy as sp

from beltmdsm.derive import mdsm
from beltmdsm.derive.fit import X2max, coefficients_eq_17
from beltmdsm.derive.model import P
from beltmdsm.generated.parameters import BASE

b1, w1, b2, w2, g = (P[k] for k in ("beta1", "omega1", "beta2", "omega2", "g"))
Z1, Z2, tau = mdsm.Z1, mdsm.Z2, mdsm.tau


def test_slow_equations_are_eqs_18_19_as_printed():
    cubic = sum(ck * Z2**k for k, ck in enumerate(mdsm.c))
    Z1d, Z2d = sp.diff(Z1, tau), sp.diff(Z2, tau)
    eq18 = (
        sp.diff(Z1, tau, 2)
        + 2 * b1 * w1 * Z1d
        + w1**2 * Z1
        + mdsm.mu_bar * (2 * b2 * w2 * Z2d + w2**2) * cubic
    )
    eq19 = sp.diff(Z2, tau, 2) + (2 * b2 * w2 * Z2d + w2**2) * cubic - g
    got = mdsm.slow_equations_18_19()
    assert sp.expand(got[0] - eq18) == 0 and sp.expand(got[1] - eq19) == 0


def test_slow_equations_20_21_put_the_power_back():
    eqs = mdsm.slow_equations_20_21()
    assert eqs.has(Z2 ** sp.Rational(3, 2)) and not eqs.has(mdsm.c[3])


@pytest.mark.parametrize(
    "term,expected",
    [
        (mdsm.Phi2, 0),
        (sp.diff(mdsm.Phi1, mdsm.theta), 0),
        (sp.sin(mdsm.theta), 0),
        (sp.diff(mdsm.Phi2, tau), 0),
        (mdsm.Phi2**2 * sp.diff(mdsm.Phi2, mdsm.theta), 0),
        (3 * Z2 * mdsm.Phi2**2, 3 * Z2 * mdsm.avg(mdsm.Phi2**2)),
    ],
)
def test_averaging_rules(term, expected):
    assert mdsm._average(term) == expected


def test_every_dropped_term_is_an_average_and_every_kept_one_is_slow():
    terms = mdsm.averaged_terms()
    assert any(not t.kept for t in terms) and any(t.kept for t in terms)
    for t in terms:
        fast = t.expr.has(mdsm.avg) or t.expr.has(mdsm.cov)
        assert t.kept != fast, t
    labels = {t.label for t in terms if not t.kept}
    assert any("correlation" in lab for lab in labels)
    assert any("powers of Phi2" in lab for lab in labels)


def test_fast_equations_average_to_the_dropped_terms():
    """A1-A2 subtract only what the paper keeps: their average is what it drops."""
    fast = mdsm.fast_equations_A1_A2()
    dropped = sum(t.expr for t in mdsm.averaged_terms() if t.equation == "normal" and not t.kept)
    assert sp.expand(mdsm._average(fast[1]) - dropped) == 0


def test_harmonic_averages_against_mpmath_quadrature(mp50):
    """The dropped normal terms at equilibrium equal <N(Z2 + x sin)> - N(Z2) by quadrature."""
    X = mpmath.mpf(12)
    c = [mpmath.mpf(sp.N(ck.subs(X2max, 12), 60)) for ck in coefficients_eq_17(3)]
    z2, x, om2 = mpmath.mpf(10), mpmath.mpf("1.5"), mpmath.mpf("0.5")

    def cubic(v):
        return sum(ck * v**k for k, ck in enumerate(c))

    quad = om2**2 * (
        mpmath.quad(lambda th: cubic(z2 + x * mpmath.sin(th)), [0, 2 * mpmath.pi]) / (2 * mpmath.pi)
        - cubic(z2)
    )
    W = 4
    A = sp.Symbol("A", positive=True)
    total = sum(
        mdsm.harmonic_averages(t.expr, 0, A)
        for t in mdsm.averaged_terms()
        if t.equation == "normal" and not t.kept
    )
    total = (
        total.subs(sp.diff(Z2, tau), 0)
        .subs(Z2, 10)
        .subs(dict(zip(mdsm.c, [sp.Float(str(ck), 50) for ck in c])))
        .subs({A: W * sp.Rational(3, 2), P["Omega"]: W, P["omega2"]: sp.Rational(1, 2)})
    )
    assert abs(mpmath.mpf(sp.N(total, 50)) - quad) < mpmath.mpf(10) ** -40
    assert X > z2 + x


def test_dropped_cubic_averages_are_small_at_the_base_set():
    """Measured: the dropped normal averages are below 1 % of g (docs/modelling.md#averaging)."""
    rows = mdsm.dropped_at_equilibrium(BASE)
    assert rows and all(eq == "normal" for eq, *_ in rows)
    assert abs(sum(rel for *_, rel in rows)) < 1e-2


@pytest.mark.parametrize("contact", ["kelvin_voigt", "hunt_crossley"])
def test_the_split_of_every_contact_law(contact):
    """Eqs. (18)-(21) of the other contact laws: Hunt-Crossley's X2^n_h replaced by the
    cubic and put back (slow_equations_20_21 checks that the two agree), the linear law
    with nothing to replace; the dropped terms are averages, the kept ones slow."""
    eqs = mdsm.slow_equations_20_21(contact)
    if contact == "hunt_crossley":
        assert eqs.has(Z2 ** P["n_h"]) and not mdsm.slow_equations_18_19(contact).has(
            Z2 ** P["n_h"]
        )
    else:
        assert not mdsm.slow_equations_18_19(contact).has(mdsm.c[0])
    for t in mdsm.averaged_terms(contact):
        assert t.kept != (t.expr.has(mdsm.avg) or t.expr.has(mdsm.cov)), t


def test_hunt_crossley_dropped_averages_at_three_halves_are_hertz_damps():
    """At n_h = 3/2 the sizes of the dropped averages equal Hertz-Damp's (same fit,
    same equilibrium, same fast amplitude: exact in SymPy up to float evaluation)."""
    hertz = mdsm.dropped_at_equilibrium(BASE)
    hunt = mdsm.dropped_at_equilibrium({**BASE, "n_h": 1.5}, "hunt_crossley")
    assert [(e, lab) for e, lab, _, _ in hunt] == [(e, lab) for e, lab, _, _ in hertz]
    for (_, _, a, _), (_, _, b, _) in zip(hunt, hertz):
        assert a == pytest.approx(b, rel=1e-12)
