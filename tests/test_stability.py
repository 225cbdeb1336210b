"""generated.stability against Eqs. (22), (25), (28), (A7), (A8) typed by hand and mpmath.

Includes the hard cases: next to the stability boundary, double roots, Vb -> Vhat, and
parameters from 1e-6 to 1e6.
"""
import mpmath
import numpy as np
import pytest

from generated import _support, friction, stability, unforced
from generated.parameters import BASE
from generated.mp import stability as mp_stability
from conftest import random_params, rel_err

CONVENTIONS = ("paper", "consistent")
BASE_ARRAY = {k: v for k, v in BASE.items() if k != "Vb"}


# Closed forms typed by hand from the paper -------------------------------------------

def slope_eq25(p):
    Vb, Vh, mu = p["Vb"], p["Vhat"], p["mu_s"]
    return 2 * mu / (np.pi * Vh * np.sqrt(1 - (Vb / Vh)**2)) if Vb < Vh else 0.0


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
    k = 1.5 * w2**2 * (g / w2**2)**(1 / 3)
    return np.array([[0, 1, 0, 0],
                     [-w1**2, -2 * b1 * w1 + s * m1 * g, s * m0 * k, s * 2 * m0 * b2 * g / w2],
                     [0, 0, 0, 1],
                     [0, 0, -k, -2 * b2 * g / w2]])


def a8(p):
    """Eq. (A8) as printed (paper convention)."""
    b1, w1, b2, w2, g = (p[k] for k in ("beta1", "omega1", "beta2", "omega2", "g"))
    m1 = slope_eq25(p)
    k = 1.5 * w2**2 * (g / w2**2)**(1 / 3)
    return (2 * b1 * w1 - m1 * g + 2 * b2 * g / w2,
            w1**2 + (-2 * b1 * w1 + m1 * g) * (-2 * b2 * g / w2) + k,
            2 * b2 * g * w1**2 / w2 + (-2 * b1 * w1 + m1 * g) * (-k),
            w1**2 * k)


def eq28(a1, a2, a3, a4):
    """Eq. (28) exactly as printed (its H4 has a1 a4^2, see test_printed_h4_differs)."""
    return (a1, a1 * a2 - a3, a1 * a2 * a3 - a3**2 - a4 * a1**2,
            a1 * a2 * a3 * a4 - a1 * a4**2 - a4 * a3**2)


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
        np.testing.assert_allclose(stability.jacobian(convention=convention, **p),
                                   eq22(p, convention), rtol=1e-12, atol=1e-14)


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
        friction.mu_bar_slope(4.0, 8.0, 0.4), rel=1e-14)
    assert abs(friction.mu_bar0(q["Vb"], 8.0, 0.3) - friction.mu_bar0(4.0, 8.0, 0.4)) > 0.02
    np.testing.assert_allclose(stability.coefficients(**q), stability.coefficients(**p),
                               rtol=1e-13)
    assert not np.allclose(stability.jacobian(**q)[1, 2:], stability.jacobian(**p)[1, 2:])


def test_hurwitz_is_eq28_and_h4_is_a4_h3(rng):
    for _ in range(30):
        p = forced_params(rng)
        a = stability.coefficients(**p)
        H = stability.hurwitz(**p)
        printed = eq28(*a)
        scale = [abs(a[0]), abs(a[0] * a[1]) + abs(a[2]),
                 abs(a[0] * a[1] * a[2]) + a[2]**2 + abs(a[3]) * a[0]**2]
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
        assert Z1 == pytest.approx(s * mu0_eq25(p) * p["g"] / p["omega1"]**2, rel=1e-12)
        assert Z2 == pytest.approx((p["g"] / p["omega2"]**2)**(2 / 3), rel=1e-13)
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
        assert abs(stability.growth_rate(convention=convention, backend=backend, **p)
                   - float(top)) <= 1e-12 * max(abs(z) for z in exact)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
def test_is_stable_against_mpmath_hurwitz_signs(rng, mp50, convention, contact, backend):
    """The verdict p > 0 and r > 0 against the signs of all four Hurwitz determinants."""
    seen = set()
    for _ in range(40):
        p = forced_params(rng)
        if rng.uniform() < 0.2:
            p["beta2"] = 0.0                      # r = 0: marginal normal mode, not stable
        H = mp_stability.hurwitz(convention=convention, contact=contact, **p)
        verdict = bool(stability.is_stable(convention=convention, contact=contact,
                                           backend=backend, **p))
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
        slope = 2 * mpmath.mpf(p["mu_s"]) / (mpmath.pi * mpmath.sqrt(
            (mpmath.mpf(p["Vhat"]) - Vc) * (mpmath.mpf(p["Vhat"]) + Vc)))
        damping = 2 * mpmath.mpf(p["beta1"]) * p["omega1"] - mpmath.mpf(p["g"]) * slope
        assert abs(damping) < 1e-12 * 2 * p["beta1"] * p["omega1"]
        assert stability.is_stable(**{**p, "Vb": Vc * (1 - 1e-9)})
        assert not stability.is_stable(**{**p, "Vb": Vc * (1 + 1e-9)})
    assert n > 5


def test_critical_belt_speed_documented_values(base):
    assert stability.critical_belt_speed(**base) == 0.0           # m > Vhat: all unstable
    assert stability.critical_belt_speed(**{**base, "beta1": 0.0}) == 0.0
    assert np.isnan(stability.critical_belt_speed(**base, convention="consistent"))
    assert np.all(np.isnan(stability.unstable_interval(**base, convention="consistent")))


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
            exact = mp_stability.hurwitz(**q)[2]                    # 50 digits, same input
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
    assert abs(top + beta1 * p["omega1"]) < 1e-3 * p["omega1"]   # the tangential mode leads
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
    assert stability.growth_rate(**frictionless, backend=backend) \
        == max(unforced.eigenvalues(**frictionless).real)
    beyond = {**p, "Vb": np.nextafter(Vhat, 20)}
    np.testing.assert_array_equal(stability.eigenvalues(**beyond), unforced.eigenvalues(**beyond))
    assert stability.is_stable(**beyond, backend=backend)


def test_extreme_parameter_scales(mp50, backend):
    """Parameters log-uniform in [1e-6, 1e6]: finite results matching mpmath."""
    rng = np.random.default_rng(7)
    names = ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g")
    for _ in range(100):
        p = {k: float(10**rng.uniform(-6, 6)) for k in names}
        p["Vhat"] = float(10**rng.uniform(-6, 6))
        p["Vb"] = p["Vhat"] * float(rng.choice([0.3, 0.999, 1.5]))
        for conv in CONVENTIONS:
            lam = stability.eigenvalues(convention=conv, **p)
            assert np.all(np.isfinite(lam))
            assert rel_err(lam, mp_stability.eigenvalues(convention=conv, **p)) < 1e-9
            H = mp_stability.hurwitz(convention=conv, **p)
            assert bool(stability.is_stable(convention=conv, backend=backend, **p)) \
                == all(h > 0 for h in H)
            sigma = stability.growth_rate(convention=conv, backend=backend, **p)
            exact = mp_stability.eigenvalues(convention=conv, **p)
            assert abs(sigma - float(max(z.real for z in exact))) \
                <= 1e-12 * float(max(abs(z) for z in exact))
        assert np.isfinite(friction.vhat(**p)) and friction.vhat(**p) > 0
        assert friction.vhat(**p) == pytest.approx(float(
            mpmath.mpf(p["alpha"]) * mpmath.mpf(p["Omega"])**3 / abs(
                mpmath.mpf(p["omega1"])**2 - mpmath.mpf(p["Omega"])**2
                + 2j * mpmath.mpf(p["beta1"]) * p["omega1"] * p["Omega"])), rel=1e-12)


# API ---------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["coefficients", "hurwitz", "eigenvalues", "growth_rate",
                                  "is_stable", "critical_belt_speed", "unstable_interval",
                                  "equilibrium", "jacobian"])
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
    assert stability.growth_rate(**base, vhat_model="coupled") == \
        stability.growth_rate(**base, Vhat=coupled)
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
    alpha = np.array([0.5, 1.0, 2.0])[:, None, None]          # used by Vhat only: broadcasts
    sigma = stability.growth_rate(**{**base, "Vb": Vb, "beta1": beta1, "alpha": alpha},
                                  backend=backend)
    assert sigma.shape == (3, 30, 50) and sigma.dtype == float
    assert np.isscalar(stability.growth_rate(**base, backend=backend))


@pytest.mark.parametrize("bad,name", [({"Vb": -1.0}, "'Vb'"), ({"Vhat": 0.0}, "'Vhat'"),
                                      ({"beta2": -0.1}, "'beta2'"), ({"Vb": np.nan}, "'Vb'")])
def test_bad_input_raises_naming_the_parameter(base, bad, name, backend):
    with pytest.raises(ValueError, match=name):
        stability.is_stable(**{**base, **bad}, backend=backend)
    with pytest.raises(ValueError, match=name):
        stability.growth_rate(**{**base, **bad}, backend=backend)


# Backends ----------------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
def test_numba_kernels_match_the_numpy_path(convention, contact):
    """Same expressions, one pass per point: equal verdicts, growth rates to rounding."""
    pytest.importorskip("numba")
    rng = np.random.default_rng(3)
    n = 20000
    p = {k: BASE_ARRAY[k] * np.exp(rng.uniform(-np.log(3), np.log(3), n)) for k in BASE_ARRAY}
    p["Vhat"] = friction.vhat(**p)
    p["Vb"] = p["Vhat"] * rng.uniform(0, 1.4, n)
    p["Vb"][:50] = p["Vhat"][:50]                               # Vb = Vhat exactly
    opts = dict(convention=convention, contact=contact)
    stable = {b: stability.is_stable(**opts, backend=b, **p) for b in ("numpy", "numba")}
    np.testing.assert_array_equal(stable["numba"], stable["numpy"])
    assert stable["numpy"].any() and (convention == "consistent" or not stable["numpy"].all())
    sigma = {b: stability.growth_rate(**opts, backend=b, **p) for b in ("numpy", "numba")}
    scale = np.abs(stability.eigenvalues(**opts, **p)).max(axis=-1)
    finite = np.isfinite(sigma["numpy"])
    np.testing.assert_array_equal(sigma["numba"][~finite], sigma["numpy"][~finite])
    diff = np.abs(sigma["numba"][finite] - sigma["numpy"][finite]) / scale[finite]
    assert diff.max() <= 4 * np.finfo(float).eps              # a few ulps of the spectrum


def test_backend_choice(base, monkeypatch):
    with pytest.raises(ValueError, match="backend"):
        stability.growth_rate(**base, backend="cuda")
    monkeypatch.setattr(_support, "_numba", False)              # as if numba were missing
    with pytest.raises(ImportError, match="numba"):
        stability.is_stable(**base, backend="numba")
    assert stability.is_stable(**base) == stability.is_stable(**base, backend="numpy")
    assert _support.compiled(stability._is_stable__paper__hertz_damp__scalar, "boolean",
                             None) is None


def test_unknown_convention_raises(base):
    with pytest.raises(ValueError, match="convention"):
        stability.growth_rate(**base, convention="printed")


def test_results_never_alias_the_callers_arrays(base):
    Vhat = np.array([5.0, 8.0])
    _, upper = stability.unstable_interval(**{**base, "Vhat": Vhat})
    upper[:] = 0.0
    np.testing.assert_array_equal(Vhat, [5.0, 8.0])
