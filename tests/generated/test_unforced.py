"""beltmdsm.generated.unforced against Eqs. (9)-(12) typed by hand and against mpmath at 50
digits."""

import mpmath
import numpy as np
import pytest
from conftest import random_params, rel_err

from beltmdsm.generated import unforced
from beltmdsm.generated.mp import unforced as mp_unforced

CONTACTS = ("hertz_damp", "kelvin_voigt")


# Closed forms typed by hand from the paper -------------------------------------------


def eq9(p, contact="hertz_damp"):
    """Eq. (9); for Kelvin-Voigt contact the spring is linear: X2 = g/omega2^2."""
    X2 = (
        (p["g"] / p["omega2"] ** 2) ** (2 / 3)
        if contact == "hertz_damp"
        else p["g"] / p["omega2"] ** 2
    )
    return p["mu_s"] * p["g"] / p["omega1"] ** 2, 0.0, X2, 0.0


def eq10(X1, Y1, X2, Y2, p):
    """Eq. (10) as printed."""
    b1, w1, b2, w2, mu = p["beta1"], p["omega1"], p["beta2"], p["omega2"], p["mu_s"]
    return np.array(
        [
            [0, 1, 0, 0],
            [
                -(w1**2),
                -2 * b1 * w1,
                mu * (3 * b2 * w2 * X2**0.5 * Y2 + 1.5 * w2**2 * X2**0.5),
                2 * mu * b2 * w2 * X2**1.5,
            ],
            [0, 0, 0, 1],
            [0, 0, -3 * b2 * w2 * X2**0.5 * Y2 - 1.5 * w2**2 * X2**0.5, -2 * b2 * w2 * X2**1.5],
        ]
    )


def eq11(p):
    """Eq. (11) as printed."""
    b1, w1, b2, w2, mu, g = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "mu_s", "g"))
    k = 1.5 * w2**2 * (g / w2**2) ** (1 / 3)
    return np.array(
        [
            [0, 1, 0, 0],
            [-(w1**2), -2 * b1 * w1, mu * k, 2 * mu * b2 * g / w2],
            [0, 0, 0, 1],
            [0, 0, -k, -2 * b2 * g / w2],
        ]
    )


def kv_j0(p):
    """J^0 for the linear contact of Fig. 16 (the normal block of a linear oscillator)."""
    b1, w1, b2, w2, mu = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "mu_s"))
    return np.array(
        [
            [0, 1, 0, 0],
            [-(w1**2), -2 * b1 * w1, mu * w2**2, 2 * mu * b2 * w2],
            [0, 0, 0, 1],
            [0, 0, -(w2**2), -2 * b2 * w2],
        ]
    )


# Against the hand-typed closed forms -----------------------------------------------


@pytest.mark.parametrize("contact", CONTACTS)
def test_equilibrium_is_eq9(rng, contact):
    for _ in range(20):
        p = random_params(rng)
        np.testing.assert_allclose(
            unforced.equilibrium(contact=contact, **p), eq9(p, contact), rtol=1e-14, atol=0
        )


def test_jacobian_is_eq10(rng):
    for _ in range(20):
        p = random_params(rng)
        state = rng.normal(size=4)
        state[2] = abs(state[2]) + 0.01
        np.testing.assert_allclose(
            unforced.jacobian(*state, **p), eq10(*state, p), rtol=1e-13, atol=1e-300
        )


def test_jacobian_at_equilibrium_is_eq11_and_eq10_at_eq9(rng):
    for _ in range(20):
        p = random_params(rng)
        J0 = unforced.jacobian_at_equilibrium(**p)
        np.testing.assert_allclose(J0, eq11(p), rtol=1e-13)
        np.testing.assert_allclose(J0, unforced.jacobian(*eq9(p), **p), rtol=1e-13)


@pytest.mark.parametrize("contact", CONTACTS)
def test_charpoly_is_det_of_eq11(rng, contact):
    for _ in range(20):
        p = random_params(rng)
        J0 = eq11(p) if contact == "hertz_damp" else kv_j0(p)
        np.testing.assert_allclose(
            unforced.charpoly(contact=contact, **p), np.poly(J0)[1:], rtol=1e-12
        )


def test_charpoly_does_not_depend_on_mu_s(base):
    mu = np.array([0.0, 0.1, 0.4, 5.0])
    a = np.array(unforced.charpoly(**{**base, "mu_s": mu}))
    assert a.shape == (4, 4)
    np.testing.assert_array_equal(a, a[:, :1].repeat(4, axis=1))


@pytest.mark.parametrize("contact", CONTACTS)
def test_eigenvalues_against_mpmath_eig(rng, mp50, contact):
    for _ in range(10):
        p = random_params(rng)
        J0 = mpmath.matrix(
            (eq11 if contact == "hertz_damp" else kv_j0)(
                {k: mpmath.mpf(v) for k, v in p.items()}
            ).tolist()
        )
        exact = sorted(
            mpmath.eig(J0, left=False, right=False), key=lambda z: (float(z.real), float(z.imag))
        )
        got = sorted(unforced.eigenvalues(contact=contact, **p), key=lambda z: (z.real, z.imag))
        assert rel_err(got, exact) < 1e-12


def test_eigenvalues_paper_fig4_regime(base):
    """Fig. 4: beta1 >= 1 overdamps the tangential mode; all real parts negative."""
    beta1 = np.array([0.1, 0.5, 0.99, 1.0, 1.5, 3.0])
    lam = unforced.eigenvalues(**{**base, "beta1": beta1})
    assert lam.shape == (6, 4)
    assert np.all(lam.real < 0)
    tangential_real = np.all(lam[:, :2].imag == 0, axis=1)
    np.testing.assert_array_equal(tangential_real, beta1 >= 1)
    # The normal mode is overdamped for beta2* = 0.15 (Sect. 4.2).
    assert np.all(lam[:, 2:].imag == 0)


# Against the mpmath variants at 50 digits -----------------------------------------

MP_CASES = [
    ("equilibrium", ()),
    ("jacobian_at_equilibrium", ()),
    ("charpoly", ()),
    ("eigenvalues", ()),
    ("jacobian", ("state",)),
]


@pytest.mark.parametrize("contact", CONTACTS)
@pytest.mark.parametrize("name,args", MP_CASES)
def test_numpy_matches_mpmath_variant(rng, mp50, contact, name, args):
    for _ in range(10):
        p = random_params(rng)
        state = ()
        if args:
            state = tuple(rng.normal(size=4))
            state = (state[0], state[1], abs(state[2]) + 0.01, state[3])
        fast = getattr(unforced, name)(*state, contact=contact, **p)
        ref = getattr(mp_unforced, name)(*state, contact=contact, **p)
        ref = ref.tolist() if isinstance(ref, mpmath.matrix) else ref
        assert rel_err(fast, ref) < 1e-13, name


def test_broadcasting_over_parameter_grids(base):
    b1 = np.linspace(0.05, 2, 5)[:, None]
    w2 = np.linspace(0.3, 2, 3)[None, :]
    p = {**base, "beta1": b1, "omega2": w2}
    assert unforced.eigenvalues(**p).shape == (5, 3, 4)
    assert unforced.jacobian_at_equilibrium(**p).shape == (5, 3, 4, 4)
    assert all(a.shape == (5, 3) for a in unforced.charpoly(**p))
    assert all(a.shape == (5, 3) for a in unforced.equilibrium(**p))
    J = unforced.jacobian_at_equilibrium(**p)
    np.testing.assert_allclose(
        J[2, 1], eq11({**base, "beta1": b1[2, 0], "omega2": w2[0, 1]}), rtol=1e-14
    )


# Bad input -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name,value,fn",
    [
        ("omega1", -1.0, "charpoly"),
        ("omega2", 0.0, "equilibrium"),
        ("beta1", -0.1, "charpoly"),
        ("beta2", -1e-9, "eigenvalues"),
        ("mu_s", -0.4, "equilibrium"),
        ("g", -9.81, "charpoly"),
        ("mu_s", float("nan"), "jacobian_at_equilibrium"),
    ],
)
def test_non_physical_parameter_raises_naming_it(base, name, value, fn):
    with pytest.raises(ValueError, match=repr(name)):
        getattr(unforced, fn)(**{**base, name: value})


def test_one_bad_element_in_an_array_raises(base):
    with pytest.raises(ValueError, match="'beta1'"):
        unforced.eigenvalues(**{**base, "beta1": np.array([0.1, -0.2, 0.3])})


@pytest.mark.parametrize("X2", [0.0, -1e-3])
def test_jacobian_out_of_contact_raises(base, X2):
    with pytest.raises(ValueError, match="'X2'"):
        unforced.jacobian(0.0, 0.0, X2, 0.0, **base)


def test_unknown_keyword_is_a_type_error_and_known_ones_are_accepted(base):
    with pytest.raises(TypeError, match="'omega_1'"):
        unforced.charpoly(omega_1=1.0, **base)
    # Vb, alpha, Omega are not used by charpoly but are known: accepted.
    assert len(unforced.charpoly(**base, Vhat=3.0, phase_t=0.5)) == 4


def test_missing_parameter_is_a_type_error(base):
    del base["g"]
    with pytest.raises(TypeError, match="'g'"):
        unforced.equilibrium(**base)


def test_unknown_contact_law_raises(base):
    with pytest.raises(ValueError, match="contact"):
        unforced.charpoly(contact="hertz", **base)


# Stribeck friction: the equilibrium depends on Vb, the slope damps the tangential mode ----


def stribeck(speed, p):
    """mu(|Vr|) = mu_k + (mu_s - mu_k) exp(-|Vr|/v_s) and its slope in |Vr|, by hand."""
    fall = (p["mu_s"] - p["mu_k"]) * np.exp(-speed / p["v_s"])
    return p["mu_k"] + fall, -fall / p["v_s"]


def stribeck_boundary(p):
    """Hand closed form: the tangential damping 2 beta1 omega1 + g mu'(Vb) of J^0 vanishes
    where g (mu_s - mu_k) exp(-Vb/v_s) / v_s = 2 beta1 omega1, i.e. at
    Vb_c = v_s log(g (mu_s - mu_k) / (2 beta1 omega1 v_s)); below it sliding is unstable."""
    return p["v_s"] * np.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )


@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt", "hunt_crossley"])
def test_stribeck_equilibrium_and_jacobian_at_it(rng, contact):
    """X1^0 = mu(Vb) g / omega1^2; J^0[1, 1] = -(2 beta1 omega1 + g mu'(Vb)); the friction
    column is mu(Vb) times the normal block's stiffness and damping."""
    for _ in range(10):
        p = random_params(rng)
        mu, slope = stribeck(p["Vb"], p)
        X1, Y1, X2, Y2 = unforced.equilibrium(friction="stribeck", contact=contact, **p)
        assert X1 == pytest.approx(mu * p["g"] / p["omega1"] ** 2, rel=1e-14)
        J = unforced.jacobian_at_equilibrium(friction="stribeck", contact=contact, **p)
        J_c = unforced.jacobian_at_equilibrium(friction="coulomb", contact=contact, **p)
        damping = 2 * p["beta1"] * p["omega1"] + p["g"] * slope
        assert J[1, 1] == pytest.approx(-damping, rel=1e-13, abs=1e-15 * p["g"] * abs(slope))
        np.testing.assert_allclose(J[1, 2:], mu / p["mu_s"] * J_c[1, 2:], rtol=1e-13)
        np.testing.assert_array_equal(J[2:], J_c[2:])  # the normal block: no friction


def test_unforced_stribeck_boundary_is_the_hand_closed_form(rng):
    """unforced.critical_belt_speed against the hand formula, and the growth rate of the
    tangential pair changes sign there (Re = -p/2 for a complex pair)."""
    for _ in range(20):
        p = random_params(rng)
        p["mu_k"] = p["mu_s"] * rng.uniform(0.05, 0.9)
        Vc = stribeck_boundary(p)
        got = unforced.critical_belt_speed(friction="stribeck", **p)
        if Vc <= 0:
            assert np.isnan(got)
            continue
        assert got == pytest.approx(Vc, rel=1e-13)
        for side, Vb in ((1, Vc * (1 - 1e-6)), (-1, Vc * (1 + 1e-6))):
            lam = unforced.eigenvalues(friction="stribeck", **{**p, "Vb": Vb})
            assert np.sign(lam[:2].real.max()) == side


def test_coulomb_has_no_unforced_boundary(base):
    assert np.isnan(unforced.critical_belt_speed(**base))
    assert np.isnan(unforced.critical_belt_speed(friction="stribeck", **{**base, "mu_k": 0.4}))
