"""beltmdsm.generated.stability against Eqs. (22), (25), (28), (A7), (A8) typed by hand and mpmath.

Includes the hard cases: next to the stability boundary, double roots, Vb -> Vhat, and
parameters from 1e-6 to 1e6.
"""

import functools

import mpmath
import numpy as np
import pytest
from conftest import random_params, rel_err

from beltmdsm.generated import _support, friction, stability, unforced
from beltmdsm.generated.mp import friction as mp_friction
from beltmdsm.generated.mp import stability as mp_stability
from beltmdsm.generated.parameters import BASE

CONVENTIONS = ("paper", "consistent")
CONTACTS = ("hertz_damp", "kelvin_voigt")
BASE_ARRAY = {k: v for k, v in BASE.items() if k != "Vb"}


# Closed forms typed by hand from the paper -------------------------------------------


def slope_eq25(p):
    Vb, Vh, mu = p["Vb"], p["Vhat"], p["mu_s"]
    return 2 * mu / (np.pi * Vh * np.sqrt(1 - (Vb / Vh) ** 2)) if Vb < Vh else 0.0


def mu0_eq25(p):
    """mu_bar(Z1'^0 - Vb) with Eq. (23) and Z1'^0 = 0 (Coulomb's -mu_s beyond Vhat)."""
    if p["Vb"] >= p["Vhat"]:
        return -p["mu_s"]
    return p["mu_s"] * (1 - 2 / np.pi * np.arccos(-p["Vb"] / p["Vhat"]))


def eq22(p, convention="paper"):
    """Eq. (22) as printed; ``consistent`` flips the sign of every friction entry."""
    b1, w1, b2, w2, g = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "g"))
    s = 1 if convention == "paper" else -1
    m0, m1 = mu0_eq25(p), slope_eq25(p)
    k = 1.5 * w2**2 * (g / w2**2) ** (1 / 3)
    return np.array(
        [
            [0, 1, 0, 0],
            [-(w1**2), -2 * b1 * w1 + s * m1 * g, s * m0 * k, s * 2 * m0 * b2 * g / w2],
            [0, 0, 0, 1],
            [0, 0, -k, -2 * b2 * g / w2],
        ]
    )


def a8(p):
    """Eq. (A8) as printed (paper convention)."""
    b1, w1, b2, w2, g = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "g"))
    m1 = slope_eq25(p)
    k = 1.5 * w2**2 * (g / w2**2) ** (1 / 3)
    return (
        2 * b1 * w1 - m1 * g + 2 * b2 * g / w2,
        w1**2 + (-2 * b1 * w1 + m1 * g) * (-2 * b2 * g / w2) + k,
        2 * b2 * g * w1**2 / w2 + (-2 * b1 * w1 + m1 * g) * (-k),
        w1**2 * k,
    )


def eq28(a1, a2, a3, a4):
    """Eq. (28) exactly as printed (its H4 has a1 a4^2, see test_printed_h4_differs)."""
    return (
        a1,
        a1 * a2 - a3,
        a1 * a2 * a3 - a3**2 - a4 * a1**2,
        a1 * a2 * a3 * a4 - a1 * a4**2 - a4 * a3**2,
    )


def forced_params(rng, **over):
    p = random_params(rng)
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0.05, 1.4)
    return {**p, **over}


# Closed forms ------------------------------------------------------------------------


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_jacobian_is_eq22(rng, convention):
    for _ in range(30):
        p = forced_params(rng)
        np.testing.assert_allclose(
            stability.jacobian(convention=convention, **p),
            eq22(p, convention),
            rtol=1e-12,
            atol=1e-14,
        )


def test_coefficients_are_a8_and_the_charpoly_of_eq22(rng):
    for _ in range(30):
        p = forced_params(rng)
        got = stability.coefficients(**p)
        np.testing.assert_allclose(got, a8(p), rtol=1e-10)
        np.testing.assert_allclose(got, np.poly(eq22(p))[1:], rtol=1e-10)


def test_coefficients_depend_on_the_slope_not_on_mu_bar0(base):
    """Sect. 4.3: two sets with the same slope mu_bar' but different mu_bar^0.

    With Vhat = 8: mu_s = 0.4 at Vb = 4 and mu_s = 0.3 at Vb = sqrt(37) have the same
    slope 2 mu_s / (pi sqrt(64 - Vb^2)).
    """
    p = {**base, "Vhat": 8.0, "Vb": 4.0, "mu_s": 0.4}
    q = {**base, "Vhat": 8.0, "Vb": np.sqrt(37.0), "mu_s": 0.3}
    assert friction.mu_bar_slope(q["Vb"], 8.0, 0.3) == pytest.approx(
        friction.mu_bar_slope(4.0, 8.0, 0.4), rel=1e-14
    )
    assert abs(friction.mu_bar0(q["Vb"], 8.0, 0.3) - friction.mu_bar0(4.0, 8.0, 0.4)) > 0.02
    np.testing.assert_allclose(stability.coefficients(**q), stability.coefficients(**p), rtol=1e-13)
    assert not np.allclose(stability.jacobian(**q)[1, 2:], stability.jacobian(**p)[1, 2:])


def test_hurwitz_is_eq28_and_h4_is_a4_h3(rng):
    for _ in range(30):
        p = forced_params(rng)
        a = stability.coefficients(**p)
        H = stability.hurwitz(**p)
        printed = eq28(*a)
        scale = [
            abs(a[0]),
            abs(a[0] * a[1]) + abs(a[2]),
            abs(a[0] * a[1] * a[2]) + a[2] ** 2 + abs(a[3]) * a[0] ** 2,
        ]
        for k in range(3):
            assert abs(H[k] - printed[k]) <= 1e-12 * scale[k]
        assert H[3] == pytest.approx(a[3] * H[2], rel=1e-12)


def test_printed_h4_differs_from_the_hurwitz_determinant(base):
    """Eq. (28) prints -a1 a4^2 where the determinant of the Hurwitz matrix has -a1^2 a4^2."""
    p = {**base, "Vb": 12.0}
    a1, a2, a3, a4 = stability.coefficients(**p)
    hurwitz_matrix = np.array([[a1, a3, 0, 0], [1, a2, a4, 0], [0, a1, a3, 0], [0, 1, a2, a4]])
    det = np.linalg.det(hurwitz_matrix)
    assert stability.hurwitz(**p)[3] == pytest.approx(det, rel=1e-10)
    assert abs(eq28(a1, a2, a3, a4)[3] - det) > 1e-3 * abs(det)


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_equilibrium_is_a7(rng, convention):
    for _ in range(10):
        p = forced_params(rng)
        s = 1 if convention == "paper" else -1
        Z1, S1, Z2, S2 = stability.equilibrium(convention=convention, **p)
        assert Z1 == pytest.approx(s * mu0_eq25(p) * p["g"] / p["omega1"] ** 2, rel=1e-12)
        assert Z2 == pytest.approx((p["g"] / p["omega2"] ** 2) ** (2 / 3), rel=1e-13)
        assert S1 == 0 and S2 == 0


def test_consistent_equilibrium_is_on_the_physical_side(base):
    """The friction of a belt moving forward pulls the mass forward.

    docs/modelling.md#friction-sign
    """
    Vb = np.linspace(0.1, 8.4, 20)
    Z1_paper = stability.equilibrium(**{**base, "Vb": Vb})[0]
    Z1_consistent = stability.equilibrium(**{**base, "Vb": Vb}, convention="consistent")[0]
    assert np.all(Z1_consistent > 0) and np.all(Z1_paper < 0)


# Eigenvalues, growth rate, verdict against mpmath -----------------------------------


def mp_eigenvalues(p, convention):
    J = mpmath.matrix(mp_stability.jacobian(convention=convention, **p))
    ev = mpmath.eig(J, left=False, right=False)
    return sorted(ev, key=lambda z: (float(z.real), float(z.imag)))


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_eigenvalues_and_growth_rate_against_mpmath(rng, mp50, convention, backend):
    for _ in range(15):
        p = forced_params(rng)
        lam = stability.eigenvalues(convention=convention, **p)
        exact = mp_eigenvalues(p, convention)
        assert rel_err(sorted(lam, key=lambda z: (z.real, z.imag)), exact) < 1e-11
        top = max(z.real for z in exact)
        assert abs(
            stability.growth_rate(convention=convention, backend=backend, **p) - float(top)
        ) <= 1e-12 * max(abs(z) for z in exact)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", CONTACTS)
def test_is_stable_against_mpmath_hurwitz_signs(rng, mp50, convention, contact, backend):
    """The verdict p > 0 and r > 0 against the signs of all four Hurwitz determinants."""
    seen = set()
    for _ in range(40):
        p = forced_params(rng)
        if rng.uniform() < 0.2:
            p["beta2"] = 0.0  # r = 0: marginal normal mode, not stable
        H = mp_stability.hurwitz(convention=convention, contact=contact, **p)
        verdict = bool(
            stability.is_stable(convention=convention, contact=contact, backend=backend, **p)
        )
        assert verdict == all(h > 0 for h in H)
        seen.add(verdict)
    assert seen == {True, False}


def test_consistent_convention_is_never_unstable(rng):
    for _ in range(200):
        p = forced_params(rng)
        assert stability.is_stable(convention="consistent", **p)


def test_paper_base_set_is_unstable_below_vhat_only(base, backend):
    """Fig. 5a: positive growth rate below the bifurcation near Vb = 8 (tangential Vhat)."""
    Vhat = friction.vhat(**base)
    Vb = np.linspace(0.25, 16, 64)
    stable = stability.is_stable(**{**base, "Vb": Vb}, backend=backend)
    np.testing.assert_array_equal(stable, Vb > Vhat)
    sigma = stability.growth_rate(**{**base, "Vb": Vb}, backend=backend)
    np.testing.assert_array_equal(sigma > 0, ~stable)


# Critical belt speed -----------------------------------------------------------------


def test_critical_belt_speed_is_the_root_of_p(rng, mp50):
    n = 0
    for _ in range(60):
        p = forced_params(rng)
        lower, upper = stability.unstable_interval(**p)
        assert upper == p["Vhat"]
        Vc = float(stability.critical_belt_speed(**p))
        assert lower == Vc
        m = p["mu_s"] * p["g"] / (np.pi * p["beta1"] * p["omega1"])
        if m >= p["Vhat"]:
            assert Vc == 0.0
            continue
        n += 1
        # p(Vc) = 0: the tangential damping 2 beta1 omega1 - g mu_bar'(Vc) vanishes (mpmath).
        slope = (
            2
            * mpmath.mpf(p["mu_s"])
            / (mpmath.pi * mpmath.sqrt((mpmath.mpf(p["Vhat"]) - Vc) * (mpmath.mpf(p["Vhat"]) + Vc)))
        )
        damping = 2 * mpmath.mpf(p["beta1"]) * p["omega1"] - mpmath.mpf(p["g"]) * slope
        assert abs(damping) < 1e-12 * 2 * p["beta1"] * p["omega1"]
        assert stability.is_stable(**{**p, "Vb": Vc * (1 - 1e-9)})
        assert not stability.is_stable(**{**p, "Vb": Vc * (1 + 1e-9)})
    assert n > 5


def test_critical_belt_speed_documented_values(base):
    assert stability.critical_belt_speed(**base) == 0.0  # m > Vhat: all unstable
    assert stability.critical_belt_speed(**{**base, "beta1": 0.0}) == 0.0
    assert np.isnan(stability.critical_belt_speed(**base, convention="consistent"))
    assert np.all(np.isnan(stability.unstable_interval(**base, convention="consistent")))


@pytest.mark.parametrize("vhat_model", ["tangential", "coupled"])
def test_without_friction_the_paper_interval_is_empty(vhat_model):
    """Issue 17: with mu_s = 0 the interval (Vb_c, Vhat] had Vb_c = Vhat and was returned as
    (Vhat, Vhat), read as the point Vhat, where is_stable is True: it is empty, (NaN, NaN)."""
    p = {**BASE, "mu_s": 0.0}
    lower, upper = stability.unstable_interval(vhat_model=vhat_model, **p)
    assert np.isnan(lower) and np.isnan(upper)
    vhat = float(friction.vhat(model=vhat_model, **p))
    assert float(stability.critical_belt_speed(vhat_model=vhat_model, **p)) == vhat
    for Vb in (0.5 * vhat, vhat, 1.5 * vhat):
        assert stability.is_stable(vhat_model=vhat_model, **{**p, "Vb": Vb})
    assert all(mpmath.isnan(x) for x in mp_stability.unstable_interval(vhat_model=vhat_model, **p))
    # any friction at rest keeps the interval, closed at Vhat
    lower, upper = stability.unstable_interval(vhat_model=vhat_model, **{**p, "mu_s": 0.01})
    assert 0 < lower < upper == float(friction.vhat(model=vhat_model, **{**p, "mu_s": 0.01}))
    assert not stability.is_stable(vhat_model=vhat_model, **{**p, "mu_s": 0.01, "Vb": upper})


def test_higher_beta1_narrows_the_unstable_range(base):
    """Fig. 6a and the conclusions: a higher beta1 shrinks the unstable range of Vb."""
    beta1 = np.array([0.05, 0.1, 0.2, 0.3, 0.4, 0.6])
    lower, upper = stability.unstable_interval(**{**base, "beta1": beta1})
    width = np.clip(upper - lower, 0, None)
    assert np.all(np.diff(width) <= 0) and width[-1] < width[0]


# Hard cases --------------------------------------------------------------------------

STIFF = {"omega1": 100.0, "beta1": 1e-3, "beta2": 5.0, "omega2": 1.0, "Vhat": 20.0}


def test_verdict_next_to_the_boundary_where_expanded_h3_loses_its_sign(base, mp50, backend):
    """Relative distance 1e-6 ... 1e-14 from the boundary: the factored verdict is right
    everywhere; the expanded H3 = a1 a2 a3 - a3^2 - a4 a1^2 of Eq. (28) gets the sign wrong."""
    p = {**base, **STIFF}
    Vc = float(stability.critical_belt_speed(**p))
    expanded_wrong = 0
    for d in (1e-6, 1e-8, 1e-10, 1e-12, 1e-13, 1e-14):
        for side in (-1, 1):
            q = {**p, "Vb": Vc * (1 + side * d)}
            exact = mp_stability.hurwitz(**q)[2]  # 50 digits, same input
            assert bool(stability.is_stable(**q, backend=backend)) == (exact > 0)
            assert np.sign(stability.growth_rate(**q, backend=backend)) == -mpmath.sign(exact)
            assert np.sign(stability.hurwitz(**q)[2]) == mpmath.sign(exact)
            a1, a2, a3, a4 = stability.coefficients(**q)
            expanded_wrong += np.sign(a1 * a2 * a3 - a3**2 - a4 * a1**2) != mpmath.sign(exact)
    assert expanded_wrong >= 1


def test_verdict_next_to_the_boundary_on_random_sets(rng, mp50, backend):
    checked = 0
    for _ in range(80):
        p = forced_params(rng)
        Vc = float(stability.critical_belt_speed(**p))
        if not 0 < Vc < p["Vhat"]:
            continue
        for d in (1e-10, 1e-12, 1e-14):
            for side in (-1, 1):
                q = {**p, "Vb": Vc * (1 + side * d)}
                exact = mp_stability.hurwitz(**q)
                assert bool(stability.is_stable(**q, backend=backend)) == all(h > 0 for h in exact)
                checked += 1
    assert checked >= 30


@pytest.mark.parametrize("beta1", [1 - 1e-10, 1.0, 1 + 1e-10, 1 + 1e-7])
def test_double_root_eigenvalues_to_1e12(base, mp50, beta1, backend):
    """A critically damped tangential mode (slope zero for Vb > Vhat, and the unforced J0)."""
    p = {**base, "beta1": beta1, "Vb": 12.0, "omega2": 4.0, "beta2": 1.0}
    exact = mp_eigenvalues(p, "paper")
    got = sorted(stability.eigenvalues(**p), key=lambda z: (z.real, z.imag))
    assert rel_err(got, exact) < 1e-12
    top = max(z.real for z in exact)
    assert abs(top + beta1 * p["omega1"]) < 1e-3 * p["omega1"]  # the tangential mode leads
    assert rel_err([stability.growth_rate(**p, backend=backend)], [top]) < 1e-12
    got0 = sorted(unforced.eigenvalues(**p), key=lambda z: (z.real, z.imag))
    assert rel_err(got0, exact) < 1e-12


def test_vb_to_vhat_from_below_at_and_beyond(base, mp50, backend):
    Vhat = 8.0
    p = {**base, "Vhat": Vhat}
    for k in range(1, 16):
        q = {**p, "Vb": Vhat * (1 - 10.0**-k)}
        sigma = stability.growth_rate(**q, backend=backend)
        exact = max(z.real for z in mp_eigenvalues(q, "paper"))
        assert np.isfinite(sigma) and sigma == pytest.approx(float(exact), rel=1e-11)
        assert not stability.is_stable(**q, backend=backend)
    at = {**p, "Vb": Vhat}
    assert stability.growth_rate(**at, backend=backend) == np.inf
    assert not stability.is_stable(**at, backend=backend)
    # Infinite damping: the slow tangential root -q/p is -0.0, the limit from below.
    assert stability.growth_rate(**at, convention="consistent", backend=backend) == 0.0
    assert not np.any(np.isnan(stability.hurwitz(**at)))
    assert stability.is_stable(**at, convention="consistent", backend=backend)
    assert not np.any(np.isnan(stability.eigenvalues(**at, convention="consistent")))
    # no friction: nothing to destabilise, at Vb = Vhat as anywhere (J_f^0 is J^0)
    frictionless = {**at, "mu_s": 0.0}
    assert stability.is_stable(**frictionless, backend=backend)
    assert stability.growth_rate(**frictionless, backend=backend) == max(
        unforced.eigenvalues(**frictionless).real
    )
    beyond = {**p, "Vb": np.nextafter(Vhat, 20)}
    np.testing.assert_array_equal(stability.eigenvalues(**beyond), unforced.eigenvalues(**beyond))
    assert stability.is_stable(**beyond, backend=backend)


def test_extreme_parameter_scales(mp50, backend):
    """Parameters log-uniform in [1e-6, 1e6]: finite results matching mpmath."""
    rng = np.random.default_rng(7)
    names = ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g")
    for _ in range(100):
        p = {k: float(10 ** rng.uniform(-6, 6)) for k in names}
        p["Vhat"] = float(10 ** rng.uniform(-6, 6))
        p["Vb"] = p["Vhat"] * float(rng.choice([0.3, 0.999, 1.5]))
        for conv in CONVENTIONS:
            lam = stability.eigenvalues(convention=conv, **p)
            assert np.all(np.isfinite(lam))
            assert rel_err(lam, mp_stability.eigenvalues(convention=conv, **p)) < 1e-9
            H = mp_stability.hurwitz(convention=conv, **p)
            assert bool(stability.is_stable(convention=conv, backend=backend, **p)) == all(
                h > 0 for h in H
            )
            sigma = stability.growth_rate(convention=conv, backend=backend, **p)
            exact = mp_stability.eigenvalues(convention=conv, **p)
            assert abs(sigma - float(max(z.real for z in exact))) <= 1e-12 * float(
                max(abs(z) for z in exact)
            )
        assert np.isfinite(friction.vhat(**p)) and friction.vhat(**p) > 0
        assert friction.vhat(**p) == pytest.approx(
            float(
                mpmath.mpf(p["alpha"])
                * mpmath.mpf(p["Omega"]) ** 3
                / abs(
                    mpmath.mpf(p["omega1"]) ** 2
                    - mpmath.mpf(p["Omega"]) ** 2
                    + 2j * mpmath.mpf(p["beta1"]) * p["omega1"] * p["Omega"]
                )
            ),
            rel=1e-12,
        )


# API ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name",
    [
        "coefficients",
        "hurwitz",
        "eigenvalues",
        "growth_rate",
        "is_stable",
        "critical_belt_speed",
        "unstable_interval",
        "equilibrium",
        "jacobian",
    ],
)
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_numpy_matches_mpmath_variant(rng, mp50, name, convention):
    for _ in range(5):
        p = forced_params(rng)
        fast = getattr(stability, name)(convention=convention, **p)
        ref = getattr(mp_stability, name)(convention=convention, **p)
        if name == "is_stable":
            assert bool(fast) == ref
            continue
        ref = ref.tolist() if isinstance(ref, mpmath.matrix) else ref
        fast = np.asarray(fast, dtype=complex)
        finite = np.isfinite(fast)
        assert rel_err(fast[finite], np.asarray(ref, dtype=object)[finite]) < 1e-10


def test_vhat_model_and_explicit_vhat(base):
    tangential = friction.vhat(**base)
    coupled = friction.vhat(model="coupled", **base)
    assert stability.growth_rate(**base) == stability.growth_rate(**base, Vhat=tangential)
    assert stability.growth_rate(**base, vhat_model="coupled") == stability.growth_rate(
        **base, Vhat=coupled
    )
    with pytest.raises(ValueError, match="not both"):
        stability.is_stable(**base, Vhat=3.0, vhat_model="tangential")
    with pytest.raises(ValueError, match="model"):
        stability.is_stable(**base, vhat_model="linear")


def test_grids_broadcast_for_a_stability_map(base, backend):
    """Fig. 6a in a few lines: a (beta1, Vb) map."""
    Vb = np.linspace(0.1, 12, 50)[None, :]
    beta1 = np.linspace(0.01, 0.6, 30)[:, None]
    stable = stability.is_stable(**{**base, "Vb": Vb, "beta1": beta1}, backend=backend)
    assert stable.shape == (30, 50) and stable.dtype == bool
    assert stable.any() and not stable.all()
    alpha = np.array([0.5, 1.0, 2.0])[:, None, None]  # used by Vhat only: broadcasts
    sigma = stability.growth_rate(
        **{**base, "Vb": Vb, "beta1": beta1, "alpha": alpha}, backend=backend
    )
    assert sigma.shape == (3, 30, 50) and sigma.dtype == float
    assert np.isscalar(stability.growth_rate(**base, backend=backend))


@pytest.mark.parametrize(
    "bad,name",
    [
        ({"Vb": -1.0}, "'Vb'"),
        ({"Vhat": 0.0}, "'Vhat'"),
        ({"beta2": -0.1}, "'beta2'"),
        ({"Vb": np.nan}, "'Vb'"),
    ],
)
def test_bad_input_raises_naming_the_parameter(base, bad, name, backend):
    with pytest.raises(ValueError, match=name):
        stability.is_stable(**{**base, **bad}, backend=backend)
    with pytest.raises(ValueError, match=name):
        stability.growth_rate(**{**base, **bad}, backend=backend)


# Backends ----------------------------------------------------------------------------
#
# Each backend of `growth_rate` is compared with the mpmath twin under a rounding-error
# bound derived below, not with the other backend under "a few ulps": the two share
# every operation except the power omega2**3 of the Hertz-Damp normal mode (numpy's
# power ufunc, numba's own lowering), and how far those differ depends on the CPU
# (numpy's SIMD dispatch, LLVM's target): 2.2 ulps of the spectrum with AVX-512,
# 4.4 without (issue 11).

EPS = np.finfo(float).eps
#: Relative distances from a double root: 0 and +-1e-2 ... +-1e-15.
OFFSETS = np.concatenate([[0.0], 10.0 ** -np.arange(2, 16), -(10.0 ** -np.arange(2, 16))])


def around_base(rng, n):
    """``n`` parameter sets (no Vb, Vhat): base values times log-uniform factors in [1/3, 3]."""
    return {k: BASE_ARRAY[k] * np.exp(rng.uniform(-np.log(3), np.log(3), n)) for k in BASE_ARRAY}


def hertz_stiffness(p):
    """q of the Hertz-Damp normal mode: 1.5 omega2^2 (g / omega2^2)^(1/3), Eq. (22)."""
    return 1.5 * np.cbrt(p["g"]) * p["omega2"] ** (4 / 3)


def backend_points(convention, contact, n_random=2000, n_base=8):
    """Parameter sets by family: random ones and three families of near-double roots.

    Each near-double-root family takes ``n_base`` random sets and moves one
    parameter to ``OFFSETS`` relative distances from the double root, with the other
    mode placed so that the double root leads (it is sigma):

    ``tangential_unforced``: beta1 = 1 with Vb > Vhat (no friction slope);
    ``tangential_forced``: g mu_bar'(Vb) = 2 omega1 |1 -+ beta1| (paper: double root at
    +omega1, unstable; consistent: at -omega1), Vb solved for;
    ``normal``: beta2 at the critical damping of the normal mode, with a fast
    tangential mode (omega1 = 30, beta1 = 0.7, Vb > Vhat).
    """
    rng = np.random.default_rng(11)
    families = {}
    p = around_base(rng, n_random)
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0, 1.4, n_random)
    families["random"] = p

    def repeated():
        return {k: np.repeat(v, len(OFFSETS)) for k, v in around_base(rng, n_base).items()}

    offset = np.tile(OFFSETS, n_base)
    beyond_vhat = np.repeat(rng.uniform(1.01, 1.4, n_base), len(OFFSETS))

    def fast_normal_mode(p):
        # omega2 = 10 (times the random factor) and underdamped at real part -0.9 sqrt(q):
        # far left of the tangential double root at -+omega1 (omega1 <= 3)
        p["omega2"] = p["omega2"] * (10 / BASE["omega2"])
        p["beta2"] = 0.9 * (
            p["omega2"] * np.sqrt(hertz_stiffness(p)) / p["g"]
            if contact == "hertz_damp"
            else np.ones_like(p["g"])
        )

    p = repeated()
    fast_normal_mode(p)
    p["beta1"] = 1 + offset
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * beyond_vhat
    families["tangential_unforced"] = p

    p = repeated()
    fast_normal_mode(p)
    c = 1 + p["beta1"] if convention == "paper" else 1 - p["beta1"]
    m = p["mu_s"] * p["g"] / (np.pi * p["omega1"] * c)  # sqrt(Vhat^2 - Vb^2) there
    p["Vhat"] = m * np.repeat(rng.uniform(2, 4, n_base), len(OFFSETS))
    p["Vb"] = np.sqrt(p["Vhat"] ** 2 - m**2) * (1 + offset)
    families["tangential_forced"] = p

    p = repeated()
    p["omega1"] = np.full_like(p["g"], 30.0)
    p["beta1"] = np.full_like(p["g"], 0.7)
    critical = (
        p["omega2"] * np.sqrt(hertz_stiffness(p)) / p["g"] if contact == "hertz_damp" else 1.0
    )
    p["beta2"] = critical * (1 + offset)
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * beyond_vhat
    families["normal"] = p
    return families


def growth_rate_bound(p, lam, contact):
    """Bound on ``|sigma - sigma_exact|`` of the float64 `stability.growth_rate`.

    Parameters
    ----------
    p : dict of float
        One parameter set (exact doubles), with ``Vb < Vhat`` or ``Vb > Vhat``.
    lam : list of 4 mpmath.mpc
        `beltmdsm.generated.mp.stability.eigenvalues` at >= 30 digits: the tangential pair,
        then the normal pair.
    contact : {"hertz_damp", "kelvin_voigt"}

    Returns
    -------
    bound : float
    leader : int
        0 if the tangential mode has the larger growth rate, else 1.

    Notes
    -----
    Error model. The inputs are exact doubles. +, -, *, /, sqrt are correctly rounded
    (relative error <= u = eps/2) in numpy's SIMD loops and in numba alike; so is the
    double pi. The transcendental functions, numpy's ``cbrt(g)``, ``cbrt(omega2)``
    (computed once for both backends) and the power ``omega2**3`` (numpy's power ufunc,
    or numba's lowering), are taken at <= 4 ulp, i.e. relative <= 4 eps: numpy's
    AVX-512 loops call Intel's SVML, whose low-accuracy variants are specified to 4 ulp
    (numpy's own accuracy tests hold its float64 cbrt to 2 ulp); the fallback, glibc,
    lists cbrt at up to 4 ulp on x86-64 in its ulps tables and pow below 1 ulp; numba
    computes small integer powers by multiplication. Counted to first order,
    rounded up (which covers the O(eps^2) terms), the kernels of
    ``generated/stability.py`` compute h, q and d = h^2 - q of each quadratic
    l^2 + 2 h l + q with absolute errors e_h, e_q, e_d:

    Tangential mode: x0 = g |mu_bar'(Vb)| (0 beyond Vhat) carries 8 roundings
    (pi, two sqrt of a rounded sum at 1.5 u each, four products and quotients): 4 eps
    x0. With a = beta1 omega1, h = a -+ x0/2: e_h = eps (2.25 x0 + a); q = omega1^2:
    e_q = u q. d = F1 F2 / 4 is factored, F = x0 -+ 2 omega1 (beta1 -+ 1):
    e_F <= 4.5 eps M_F with M_F = x0 + 2 omega1 |beta1 -+ 1|, so e_d = 2.5 eps M_F1 M_F2.
    Beyond Vhat (x0 = 0) M_F = |F|: d is accurate relative to itself and the bound does
    not widen at the unforced double root beta1 = 1; at the forced one F cancels and it
    does.

    Hertz-Damp normal mode: h = beta2 g / omega2: e_h = eps h (2 roundings);
    q = 1.5 cbrt(g) omega2 cbrt(omega2): e_q = 9.5 eps q (2 cube roots, 3 products);
    d = (2 beta2^2 g^2 - 3 cbrt(g) omega2^3 cbrt(omega2)) / (2 omega2^2) = h^2 - q is
    not factored: 13.5 eps q (3 transcendental, 3 products) + 1.5 eps h^2 + 3 u |d|,
    so e_d = 15 eps (h^2 + q).

    Kelvin-Voigt normal mode: h = beta2 omega2, q = omega2^2: e_h = u h, e_q = u q;
    d = omega2^2 (beta2 - 1)(beta2 + 1): e_d = 2.5 eps |d| (5 roundings).

    From (h, q, d) to the mode's growth rate g (`statespace.Quadratic.largest_real_part`, the
    same branches in the numba kernels): -h if d < 0, q / -(h + s) if h > 0, else
    s - h, with s = sqrt|d|. The square root is where the conditioning is:
    |s_computed - s| <= min(e_d / sqrt|d|, sqrt(e_d)) + u s, both exact inequalities;
    the second holds at a double root, and also when rounding flips the sign of d (then
    |d| <= e_d and the other branch is off by at most sqrt(e_d)). In the quotient
    branch the relative error is e_q/q + (e_h + e_s)/(h + s) + 2u and |g| <= h + s
    (g is the smaller root), so in every branch

        |g_computed - g| <= e_h + min(e_d / sqrt|d|, sqrt(e_d)) + u sqrt(|d| + e_d)
                            + |g| (e_q / q + eps).

    sigma = max(g_tangential, g_normal) moves by at most the larger of the two.
    """
    bounds, rates = [], []
    for mode, (la, lb) in enumerate((lam[:2], lam[2:])):
        h_exact = -(la + lb).real / 2
        h, q = float(h_exact), float((la * lb).real)
        d = float((((la - lb) / 2) ** 2).real)
        g = float(max(la.real, lb.real))
        if mode == 0:
            a = p["beta1"] * p["omega1"]
            x0 = 2 * abs(float(h_exact - mpmath.mpf(p["beta1"]) * p["omega1"]))
            e_h = EPS * (2.25 * x0 + a)
            e_d = (
                2.5
                * EPS
                * (x0 + 2 * p["omega1"] * abs(p["beta1"] - 1))
                * (x0 + 2 * p["omega1"] * (p["beta1"] + 1))
            )
            rel_q = EPS / 2
        elif contact == "hertz_damp":
            e_h, e_d, rel_q = EPS * abs(h), 15 * EPS * (h * h + q), 9.5 * EPS
        else:
            e_h, e_d, rel_q = EPS / 2 * abs(h), 2.5 * EPS * abs(d), EPS / 2
        e_s = min(e_d / np.sqrt(abs(d)), np.sqrt(e_d)) if d != 0 else np.sqrt(e_d)
        bounds.append(e_h + e_s + EPS / 2 * np.sqrt(abs(d) + e_d) + abs(g) * (rel_q + EPS))
        rates.append(g)
    return max(bounds), int(rates[1] > rates[0])


@functools.cache
def mp_reference(convention, contact):
    """Per family of `backend_points`: exact sigma (mpmath, 30 digits), bound, scale, leader."""
    opts = dict(convention=convention, contact=contact)
    out = {}
    with mpmath.workdps(30):
        for family, p in backend_points(convention, contact).items():
            ref = {"p": p, "exact": [], "bound": [], "scale": [], "leader": []}
            for i in range(len(p["g"])):
                point = {k: float(v[i]) for k, v in p.items()}
                lam = mp_stability.eigenvalues(**opts, **point)
                exact = mp_stability.growth_rate(**opts, **point)
                scale = max(abs(z) for z in lam)
                # the twin's growth rate is its top eigenvalue, and its eigenvalues come
                # as the tangential pair (product omega1^2), then the normal pair
                assert abs(exact - max(z.real for z in lam)) <= 1e-20 * scale
                assert (
                    abs(lam[0] * lam[1] - mpmath.mpf(point["omega1"]) ** 2)
                    <= 1e-20 * point["omega1"] ** 2
                )
                bound, leader = growth_rate_bound(point, lam, contact)
                for key, value in zip(
                    ("exact", "bound", "scale", "leader"), (exact, bound, float(scale), leader)
                ):
                    ref[key].append(value)
            out[family] = {k: v if k in ("p", "exact") else np.array(v) for k, v in ref.items()}
    return out


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", CONTACTS)
def test_growth_rate_within_its_rounding_bound_of_mpmath(convention, contact, backend):
    """Each backend against the mpmath twin, pointwise under `growth_rate_bound`.

    2000 random sets and 3 x 232 next to double roots, where the bound widens.
    """
    for family, ref in mp_reference(convention, contact).items():
        sigma = stability.growth_rate(
            convention=convention, contact=contact, backend=backend, **ref["p"]
        )
        error = np.array([float(abs(mpmath.mpf(s) - e)) for s, e in zip(sigma, ref["exact"])])
        worst = np.argmax(error / ref["bound"])
        assert np.all(error <= ref["bound"]), (
            f"{family}: |error| {error[worst]:.3g} > bound {ref['bound'][worst]:.3g} at "
            f"{ {k: float(v[worst]) for k, v in ref['p'].items()} }"
        )


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", CONTACTS)
def test_growth_rate_bound_is_tight_and_widens_at_rounded_double_roots(convention, contact):
    """`growth_rate_bound` is not vacuous, and its test points reach the double roots.

    Relative to the spectrum S = max |lambda|: about 1e-15 at random sets (the
    few above 1e-13 sit near a double root by chance); up to sqrt(eps) times the
    mode's own scale (1e-9 to 1e-7 of S) next to a double root whose discriminant
    carries a rounding error of order eps times its terms (the forced tangential one,
    the unfactored Hertz-Damp normal one), and no widening
    where the discriminant is factored exactly (beta1 = 1 beyond Vhat, beta2 = 1 with
    Kelvin-Voigt contact), which thus checks that the kernels keep that accuracy.
    """
    ref = mp_reference(convention, contact)
    rel = {family: r["bound"] / r["scale"] for family, r in ref.items()}
    assert np.median(rel["random"]) < 1e-14 and np.quantile(rel["random"], 0.9) < 1e-13
    assert rel["tangential_forced"].max() > 1e-9
    assert rel["tangential_unforced"].max() < 1e-13
    if contact == "hertz_damp":
        assert rel["normal"].max() > 1e-9
    else:
        assert rel["normal"].max() < 1e-13
    # the double root leads in its family: the comparison is of its rounding error
    assert np.all(ref["tangential_unforced"]["leader"] == 0)
    assert np.all(ref["tangential_forced"]["leader"] == 0)
    assert np.all(ref["normal"]["leader"] == 1)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", CONTACTS)
def test_numba_verdicts_and_the_limit_at_vhat_equal_numpy_bit_for_bit(convention, contact):
    """Verdicts are equal, and so is sigma at Vb = Vhat (outside `growth_rate_bound`).

    The verdict is the sign of p and r: +, -, *, /, sqrt and the double pi only, each
    correctly rounded in numpy's SIMD loops and in numba's code (compiled without
    fastmath: no FMA contraction, no reordering), so no CPU can make the backends
    disagree. At Vb = Vhat the slope is +inf: sigma is +inf (paper) or -0.0
    (consistent) from both.
    """
    pytest.importorskip("numba")
    rng = np.random.default_rng(3)
    n = 20000
    p = around_base(rng, n)
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0, 1.4, n)
    p["Vb"][:50] = p["Vhat"][:50]
    opts = dict(convention=convention, contact=contact)
    stable = {b: stability.is_stable(**opts, backend=b, **p) for b in ("numpy", "numba")}
    np.testing.assert_array_equal(stable["numba"], stable["numpy"])
    assert stable["numpy"].any() and (convention == "consistent" or not stable["numpy"].all())
    for family in backend_points(convention, contact).values():
        np.testing.assert_array_equal(
            stability.is_stable(**opts, backend="numba", **family),
            stability.is_stable(**opts, backend="numpy", **family),
        )
    at = {k: v[:50] for k, v in p.items()}
    sigma = {b: stability.growth_rate(**opts, backend=b, **at) for b in ("numpy", "numba")}
    np.testing.assert_array_equal(sigma["numba"].view(np.uint64), sigma["numpy"].view(np.uint64))
    limit = np.inf if convention == "paper" else -0.0
    np.testing.assert_array_equal(
        sigma["numpy"].view(np.uint64), np.full(50, limit).view(np.uint64)
    )


def test_backend_choice(base, monkeypatch):
    with pytest.raises(ValueError, match="backend"):
        stability.growth_rate(**base, backend="cuda")
    monkeypatch.setattr(_support, "_numba", False)  # as if numba were missing
    with pytest.raises(ImportError, match="numba"):
        stability.is_stable(**base, backend="numba")
    assert stability.is_stable(**base) == stability.is_stable(**base, backend="numpy")
    assert (
        _support.compiled(stability._is_stable__coulomb__hertz_damp__paper__scalar, "boolean", None)
        is None
    )


def test_unknown_convention_raises(base):
    with pytest.raises(ValueError, match="convention"):
        stability.growth_rate(**base, convention="printed")


def test_results_never_alias_the_callers_arrays(base):
    Vhat = np.array([5.0, 8.0])
    _, upper = stability.unstable_interval(**{**base, "Vhat": Vhat})
    upper[:] = 0.0
    np.testing.assert_array_equal(Vhat, [5.0, 8.0])


# Stribeck's law: the same closed forms in its effective friction (a quadrature) -------


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_stribeck_growth_rate_against_mpmath_and_both_backends(mp50, convention, backend):
    """The forced eigenvalues with Stribeck's effective friction (quadrature: numpy,
    the scalar kernels' inline loop, mpmath.quad) agree: numpy and numba to the
    quadrature's 1e-13 of the slope's scale (times g), mpmath to its own precision."""
    Vb = np.array([0.5, 3.0, 7.5, 9.0, 12.0])
    p = {**BASE_ARRAY, "Vb": Vb}
    law = dict(friction="stribeck", convention=convention)
    got = stability.growth_rate(**p, **law, backend=backend)
    vhat = friction.vhat(friction="stribeck", **p)
    for k, v in enumerate(Vb):
        q = {**BASE_ARRAY, "Vb": v, "Vhat": float(vhat[k])}
        ref = mp_stability.growth_rate(**{n: mpmath.mpf(x) for n, x in q.items()}, **law)
        assert abs(got[k] - float(ref)) <= 1e-13 * BASE["g"] + 1e-15 * abs(float(ref)), v


def test_stribeck_consistent_analysis_tends_to_the_unforced_one_and_the_excitation_stabilises(
    base,
):
    """Consistent convention, Stribeck's law: with a vanishing excitation (V_hat ~ 4e-3 <<
    Vb, no reversal) the slow damping tends to the unforced 2 beta1 omega1 + g mu'(Vb)
    (to O(V_hat^2 / v_s^2) ~ 1e-5); at the base excitation the averaging over the fast
    motion makes the same belt speed stable (Vb = 1 < unforced Vb_c = 2.0)."""
    p = {**base, "Vb": 1.0}
    assert unforced.critical_belt_speed(friction="stribeck", **p) > 1.0
    weak = {**p, "alpha": 1e-3}
    J = stability.jacobian(friction="stribeck", convention="consistent", **weak)
    J0 = unforced.jacobian_at_equilibrium(friction="stribeck", **weak)
    assert J[1, 1] == pytest.approx(J0[1, 1], rel=1e-4)
    assert not stability.is_stable(friction="stribeck", convention="consistent", **weak)
    assert stability.is_stable(friction="stribeck", convention="consistent", **p)


# Stribeck's law in the paper's pointwise analysis, by an independent computation -----


def stribeck_mu_bar_by_hand(Vr, Vh, p):
    """Eq. (23)'s average of sgn(v) mu(|v|), v = Vr + Vh sin t, over a period: mpmath.quad
    of Stribeck's law typed here, split where v changes sign."""
    mu_s, mu_k, v_s = (mpmath.mpf(p[k]) for k in ("mu_s", "mu_k", "v_s"))

    def f(t):
        v = Vr + Vh * mpmath.sin(t)
        return mpmath.sign(v) * (mu_k + (mu_s - mu_k) * mpmath.exp(-abs(v) / v_s))

    cuts = [-mpmath.pi / 2, mpmath.pi / 2, 3 * mpmath.pi / 2]
    if abs(Vr) < Vh:
        t1 = mpmath.asin(-Vr / Vh)
        cuts += [t1, mpmath.pi - t1]
    return mpmath.quad(f, sorted(cuts)) / (2 * mpmath.pi)


def stribeck_vhat_by_hand(Vb, p):
    """The tangential reading: alpha Omega^3 / |omega1^2 - Omega^2 + i (2 beta1 omega1 +
    g mu'(Vb)) Omega| with Stribeck's slope mu'(Vb) = -(mu_s - mu_k) exp(-Vb/v_s) / v_s."""
    q = {k: mpmath.mpf(v) for k, v in p.items()}
    slope = -(q["mu_s"] - q["mu_k"]) * mpmath.exp(-Vb / q["v_s"]) / q["v_s"]
    W = q["Omega"]
    damping = 2 * q["beta1"] * q["omega1"] + q["g"] * slope
    return q["alpha"] * W**3 / abs(q["omega1"] ** 2 - W**2 + 1j * damping * W)


def hurwitz_by_hand(J):
    """H1..H4 of the characteristic quartic of J (Faddeev-LeVerrier), as minors of the
    Hurwitz matrix."""
    n = J.rows
    M, a = mpmath.zeros(n, n), []
    for k in range(1, n + 1):
        M = J * M + (a[-1] if a else 1) * mpmath.eye(n) if k > 1 else mpmath.eye(n)
        c = -sum((J * M)[i, i] for i in range(n)) / k
        a.append(c)
    a1, a2, a3, a4 = a
    H = mpmath.matrix([[a1, a3, 0, 0], [1, a2, a4, 0], [0, a1, a3, 0], [0, 1, a2, a4]])
    return [mpmath.det(H[:k, :k]) if k > 1 else a1 for k in range(1, 5)]


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("Vb", [1.0, 5.0, 8.53])
def test_stribeck_pointwise_analysis_against_an_independent_computation(mp50, Vb, convention):
    """At a Stribeck point (mu_k = 0.25, v_s = 1): V_hat (tangential reading) typed by
    hand, mu_bar^0 by mpmath.quad of the law, its slope by a central difference
    (h = 1e-18 at 50 digits), the slow Jacobian of Eq. (22) built from them and its
    eigenvalues and Hurwitz determinants (Faddeev-LeVerrier) computed here: the mpmath
    twins agree to 30 digits, the numpy functions to their quadrature's 1e-12, and
    is_stable is the sign of all four H_k. Vb = 8.53 lies above V_hat(Vb) (no reversal:
    the consistent convention's band just above the crossing)."""
    p = {k: v for k, v in BASE.items() if k != "Vb"}
    Vb_mp = mpmath.mpf(Vb)
    Vh = stribeck_vhat_by_hand(Vb_mp, p)
    law = dict(friction="stribeck", convention=convention)
    mp_p = {k: mpmath.mpf(v) for k, v in p.items()}
    vh_twin = mp_friction.vhat(friction="stribeck", **mp_p, Vb=Vb_mp)
    assert abs(vh_twin - Vh) <= mpmath.mpf(10) ** -30 * Vh
    h = mpmath.mpf(10) ** -18
    m0 = stribeck_mu_bar_by_hand(-Vb_mp, Vh, p)
    m1 = (
        stribeck_mu_bar_by_hand(-Vb_mp + h, Vh, p) - stribeck_mu_bar_by_hand(-Vb_mp - h, Vh, p)
    ) / (2 * h)
    b1, w1, b2, w2, g = (mp_p[k] for k in ("beta1", "omega1", "beta2", "omega2", "g"))
    s = 1 if convention == "paper" else -1
    k = mpmath.mpf(3) / 2 * w2**2 * mpmath.cbrt(g / w2**2)
    J = mpmath.matrix(
        [
            [0, 1, 0, 0],
            [-(w1**2), -2 * b1 * w1 + s * m1 * g, s * m0 * k, s * 2 * m0 * b2 * g / w2],
            [0, 0, 0, 1],
            [0, 0, -k, -2 * b2 * g / w2],
        ]
    )
    sigma = max(mpmath.re(x) for x in mpmath.eig(J)[0])
    H = hurwitz_by_hand(J)
    at = {**mp_p, "Vb": Vb_mp, "Vhat": Vh}
    tol = mpmath.mpf(10) ** -30
    assert abs(mp_stability.growth_rate(**at, **law) - sigma) <= tol
    for got, ref in zip(mp_stability.hurwitz(**at, **law), H):
        assert abs(got - ref) <= tol * max(1, abs(ref))
    J_twin = mp_stability.jacobian(**at, **law)
    assert mpmath.mnorm(J_twin - J, 1) <= tol
    # the numpy functions (V_hat from vhat_model, as paper_intervals uses them)
    q = {**p, "Vb": Vb}
    got = stability.growth_rate(**q, **law, vhat_model="tangential", backend="numpy")
    assert abs(got - float(sigma)) <= 1e-12
    stable = stability.is_stable(**q, **law, vhat_model="tangential", backend="numpy")
    assert bool(stable) == all(x > 0 for x in H) == (sigma < 0)


@pytest.mark.parametrize("vhat_model", ["tangential", "coupled"])
@pytest.mark.parametrize("convention", CONVENTIONS)
def test_stribeck_with_mu_k_equal_to_mu_s_has_coulombs_growth_rate(convention, vhat_model):
    """mu_k = mu_s: the law's part beyond mu(0) is exactly 0, its quadratures too, and the
    growth rate, verdict and Hurwitz determinants are Coulomb's to rounding, on both
    sides of V_hat and at Vb = 0."""
    Vb = np.linspace(0.0, 12.0, 241)
    p = {**BASE_ARRAY, "Vb": Vb}
    opts = dict(convention=convention, vhat_model=vhat_model, backend="numpy")
    same = dict(friction="stribeck", mu_k=BASE["mu_s"])
    ref = stability.growth_rate(**p, **opts)
    got = stability.growth_rate(**{**p, **same}, **opts)
    np.testing.assert_allclose(got, ref, rtol=1e-13, atol=1e-15)
    np.testing.assert_array_equal(
        stability.is_stable(**{**p, **same}, **opts), stability.is_stable(**p, **opts)
    )
    opts.pop("backend")  # hurwitz has one backend
    for a, b in zip(stability.hurwitz(**{**p, **same}, **opts), stability.hurwitz(**p, **opts)):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("fn", [stability.hurwitz, mp_stability.hurwitz, stability.coefficients])
def test_an_unknown_keyword_with_vhat_model_names_the_function_called(fn):
    # it reached vhat() first, whose message named vhat() and not the caller
    with pytest.raises(TypeError, match=rf"^{fn.__name__}\(\) got unexpected .*'backend'"):
        fn(vhat_model="tangential", backend="numpy", **{**BASE, "Vb": 4.0})


@pytest.mark.parametrize("fn", [stability.is_stable, mp_stability.growth_rate, stability.hurwitz])
def test_a_bad_value_with_vhat_from_the_model_names_the_function_called(fn):
    # issue 17: stability.is_stable(Vb=nan) raised an error that named vhat()
    with pytest.raises(ValueError, match=rf"^{fn.__name__}\(\): parameter 'Vb' .*NaN"):
        fn(**{**BASE, "Vb": float("nan")})
