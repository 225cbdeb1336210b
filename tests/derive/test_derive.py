"""Symbolic facts of the derivation, proved by SymPy (not sampled)."""

import pytest
import sympy as sp

from beltmdsm.derive import dynamics as dyn
from beltmdsm.derive import oscillator as osc
from beltmdsm.derive import stability as st
from beltmdsm.derive import statespace as ss
from beltmdsm.derive.model import (
    CONTACT_LAWS,
    FRICTION_LAWS,
    STATE,
    X2,
    P,
    equal_excitation,
    equations_of_motion,
    t,
)


@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_equilibrium_satisfies_state_equations_exactly(contact):
    eq = ss.equilibrium_eq_9(contact)
    residual = ss.state_space_eqs_5_8(contact).subs(eq)
    assert residual.applyfunc(sp.simplify) == sp.zeros(4, 1)
    assert eq[X2].is_positive


def test_equilibrium_is_eq9_as_printed():
    eq = ss.equilibrium_eq_9("hertz_damp")
    g, w1, w2, mu = P["g"], P["omega1"], P["omega2"], P["mu_s"]
    assert sp.simplify(eq[STATE[0]] - mu * g / w1**2) == 0
    assert sp.simplify(eq[X2] - (g / w2**2) ** sp.Rational(2, 3)) == 0


@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_mu_s_absent_from_characteristic_polynomial(contact):
    J0 = ss.jacobian_at_equilibrium_eq_11(contact)
    assert P["mu_s"] in J0.free_symbols  # present in J^0 (Eq. 11) ...
    assert ss.free_of(ss.charpoly_eq_12(J0).as_expr(), P["mu_s"])  # ... not in Eq. (12)


@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_block_factorisation_is_exact(contact):
    J0 = ss.jacobian_at_equilibrium_eq_11(contact)
    tangential, normal = ss.block_quadratics(J0)
    product = sp.expand(tangential.expr() * normal.expr())
    assert sp.simplify(product - ss.charpoly_eq_12(J0).as_expr()) == 0
    assert sp.simplify(tangential.disc - (tangential.p**2 / 4 - tangential.q)) == 0
    assert tangential.disc == P["omega1"] ** 2 * (P["beta1"] - 1) * (P["beta1"] + 1)


def test_block_quadratics_rejects_a_coupled_matrix():
    J = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"j{i}{j}"))
    with pytest.raises(ValueError, match="block triangular"):
        ss.block_quadratics(J)


def test_general_excitation_defaults_give_eq4():
    general = equations_of_motion().subs(equal_excitation())
    assert (general - equations_of_motion(general=False)).applyfunc(sp.simplify) == sp.zeros(2, 1)


@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_power_balance_is_the_time_derivative_of_energy(contact):
    """dE/dt along Eq. (4) equals P_input - P_viscous - P_friction, in contact and in flight."""
    E = dyn.energy(contact)
    f = dyn.rhs(contact, dyn.sgn)
    dEdt = sum(sp.diff(E, s) * fi for s, fi in zip(dyn.STATE_R, f)) + sp.diff(E, t)
    p_in, p_visc, p_fric = dyn.power_balance(contact)
    for branch in (dyn.X2r > 0, dyn.X2r < 0):
        x = sp.Symbol("x", positive=True)
        value = x if branch == (dyn.X2r > 0) else -x
        residual = (dEdt - (p_in - p_visc - p_fric)).subs(dyn.X2r, value)
        assert sp.simplify(residual) == 0


def test_hurwitz_factored_is_the_hurwitz_determinants():
    p, q, r, s, lam = sp.symbols("p q r s lambda")
    quartic = sp.Poly(sp.expand((lam**2 + p * lam + q) * (lam**2 + r * lam + s)), lam)
    minors = st.hurwitz_determinants(*quartic.all_coeffs()[1:])
    for factored, minor in zip(st.hurwitz_factored(p, q, r, s), minors):
        assert sp.expand(factored - minor) == 0


def test_reduced_verdict_is_the_hurwitz_test():
    """With q, s > 0: every H_k > 0 exactly when p > 0 and r > 0.

    If p, r > 0 each factored H_k is a sum of products of positive terms (SymPy proves
    it); the converse (a root argument, see beltmdsm.derive.stability) is checked in exact
    arithmetic on a grid of signs
    and magnitudes."""
    pos = sp.symbols("p q r s", positive=True)
    assert all(h.is_positive for h in st.hurwitz_factored(*pos))
    values = [sp.Rational(v) for v in ("-3", "-1", "-1/7", "0", "1/5", "1", "4")]
    positive = [sp.Rational(v) for v in ("1/9", "1", "3", "25")]
    for p in values:
        for r in values:
            for q in positive:
                for s in positive:
                    H = st.hurwitz_factored(p, q, r, s)
                    assert all(h > 0 for h in H) == (p > 0 and r > 0)


@pytest.mark.parametrize("convention", st.CONVENTIONS)
@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_stability_conditions_are_p_and_r_with_q_and_s_positive(convention, contact):
    p, q, r, s = st.factored(convention, contact).pqrs
    assert q.is_positive and s.is_positive
    assert st.stability_conditions(convention, contact) == (p, r)
    assert (
        p
        == 2 * P["beta1"] * P["omega1"]
        + (1 if convention == "consistent" else -1) * P["g"] * st.mu1
    )


# The registry of laws (derive/laws.py) -------------------------------------------------


def test_registry_refuses_a_clash_and_a_wrong_kind():
    from beltmdsm.derive import laws
    from beltmdsm.derive.parameters import Parameter

    coulomb = laws.get("friction", "coulomb")
    with pytest.raises(ValueError, match="registered already"):
        laws.register("friction", coulomb)
    with pytest.raises(ValueError, match="must be a ContactLaw"):
        laws.register("contact", coulomb)
    clash = laws.FrictionLaw(
        "other", "s", "d", "e", (Parameter("mu_s", "1", 1.0, "positive", "taken"),), lambda P, s: 1
    )
    with pytest.raises(ValueError, match="taken already"):
        laws.register("friction", clash)
    with pytest.raises(ValueError, match="friction must be one of"):
        laws.get("friction", "dahl")


def test_registry_shares_a_parameter_name_only_where_it_means_the_same():
    """A law may list a parameter of another law with the same row (one row in the
    table, every owner in `laws.owners`); a row that differs is refused by name."""
    from dataclasses import replace

    from beltmdsm.derive import laws

    (mu_k,) = [p for p in laws.get("friction", "static_kinetic").parameters if p.name == "mu_k"]
    assert laws.owners("mu_k") == (("friction", "stribeck"), ("friction", "static_kinetic"))
    assert [p.name for p in laws.parameter_table()].count("mu_k") == 1
    same = replace(mu_k, law=None)

    def law(name, parameter):
        return laws.FrictionLaw(name, "s", "d", "e", (parameter,), lambda P, s: P["mu_k"])

    try:
        laws.register("friction", law("sharing", same))
        assert laws.owners("mu_k")[-1] == ("friction", "sharing")
        assert [p.name for p in laws.parameter_table()].count("mu_k") == 1
    finally:
        laws.LAWS["friction"].pop("sharing", None)
    for field, value in (("unit", "m/s"), ("base", 0.3), ("description", "another")):
        with pytest.raises(ValueError, match=rf"mu_k: 'stribeck' gives it another {field}"):
            laws.register("friction", law("differing", replace(same, **{field: value})))
    assert "differing" not in laws.choices("friction")


def test_static_coefficient_is_mu_s_for_every_shipped_law():
    from beltmdsm.derive.model import static_coefficient

    assert all(static_coefficient(f) == P["mu_s"] for f in FRICTION_LAWS)
    # the slip law at rest: mu_s but for static_kinetic, whose slip is at mu_k
    from beltmdsm.derive.model import rest_coefficient

    assert rest_coefficient("static_kinetic") == P["mu_k"]
    assert all(rest_coefficient(f) == P["mu_s"] for f in ("coulomb", "stribeck"))


@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_exponent_of_the_contact_law(contact):
    from beltmdsm.derive.fit import exponent

    assert (
        exponent(contact)
        == {
            "hertz_damp": sp.Rational(3, 2),
            "kelvin_voigt": 1,
            "hunt_crossley": P["n_h"],
        }[contact]
    )


def test_the_fast_average_is_closed_form_exactly_for_a_constant_or_polynomial_law():
    """Risch decides: Coulomb's (nothing beyond mu_s) and a polynomial remainder are
    elementary; Stribeck's exp(-|v|/v_s) is not (a quadrature)."""
    from beltmdsm.derive import averaging

    assert averaging.closed_form("coulomb")[0]
    holds, why = averaging.closed_form("stribeck")
    assert not holds and "no elementary antiderivative" in why
    inside, outside = averaging.remainder_average("stribeck")
    assert inside.has(sp.Integral) and outside.has(sp.Integral)


@pytest.mark.parametrize("friction", FRICTION_LAWS)
@pytest.mark.parametrize("contact", CONTACT_LAWS)
def test_power_balance_is_the_time_derivative_of_energy_for_every_law(friction, contact):
    E = dyn.energy(contact)
    f = dyn.rhs(contact, dyn.sgn, friction=friction)
    dEdt = sum(sp.diff(E, s) * fi for s, fi in zip(dyn.STATE_R, f)) + sp.diff(E, t)
    p_in, p_visc, p_fric = dyn.power_balance(contact, friction=friction)
    x = sp.Symbol("x", positive=True)
    for value in (x, -x):
        assert sp.simplify((dEdt - (p_in - p_visc - p_fric)).subs(dyn.X2r, value)) == 0


def test_the_superposition_solves_the_tangential_equation():
    """Phi' = A Phi, Phi(0) = I for each damping regime, and Phi (x0 - f0) + f solves
    the tangential equation of a mode from x0 (derive/oscillator.py); no superposition
    for a friction law that depends on the sliding speed."""
    osc.verify_state_transition()
    for friction in FRICTION_LAWS:
        if osc.tangential_state(friction) is None:
            with pytest.raises(AssertionError, match="no superposition"):
                osc.verify_tangential_state(friction)
        else:
            osc.verify_tangential_state(friction)
    assert osc.tangential_state("coulomb") is not None
    assert osc.tangential_state("stribeck") is None
