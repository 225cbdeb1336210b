"""beltmdsm.generated.fit against Eq. (17) typed by hand and against mpmath quadrature."""

import mpmath
import numpy as np
import pytest

from beltmdsm.generated import fit
from beltmdsm.generated.mp import fit as mp_fit


def eq17(X):
    """Eq. (17) as printed: (c0, c1, c2, c3)."""
    return (-8 * X**1.5 / 1155, 24 * X**0.5 / 77, 72 / (77 * X**0.5), -8 / (33 * X**1.5))


def mp_least_squares(X, degree):
    """Continuous L2 fit by mpmath: normal equations with quadrature at 50 digits."""
    n = degree + 1
    gram = mpmath.matrix(n, n)
    rhs = mpmath.matrix(n, 1)
    for j in range(n):
        rhs[j] = mpmath.quad(lambda x: x ** mpmath.mpf(1.5) * x**j, [0, X])
        for k in range(n):
            gram[j, k] = mpmath.quad(lambda x: x ** (j + k), [0, X])
    return list(mpmath.lu_solve(gram, rhs))


@pytest.mark.parametrize("X", [1e-3, 0.5, 1.0, 11.547, 2e4])
def test_degree_3_is_eq17(X):
    np.testing.assert_allclose(fit.coefficients(X), eq17(X), rtol=1e-14)


@pytest.mark.parametrize("degree", range(1, 9))
def test_coefficients_solve_the_continuous_least_squares_problem(mp50, degree):
    X = mpmath.mpf(3)
    ref = mp_least_squares(X, degree)
    got = mp_fit.coefficients(X, degree=degree)
    assert max(abs(a - b) / abs(b) for a, b in zip(got, ref)) < mpmath.mpf(10) ** -35
    fast = fit.coefficients(3.0, degree=degree)
    assert max(abs(float(a) - float(b)) / abs(float(b)) for a, b in zip(fast, ref)) < 1e-12


@pytest.mark.parametrize("degree", [1, 3, 5, 8])
def test_max_error_and_location_against_a_dense_scan(degree):
    X = 2.0
    x = np.linspace(0.0, X, 400001)
    c = fit.coefficients(X, degree=degree)
    err = np.abs(x**1.5 - sum(ck * x**k for k, ck in enumerate(c)))
    assert fit.max_error(X, degree=degree) == pytest.approx(err.max(), rel=1e-9)
    assert fit.max_error_location(X, degree=degree) == pytest.approx(x[err.argmax()], abs=1e-4)


@pytest.mark.parametrize("degree", [1, 3, 8])
def test_rms_error_against_mpmath_quadrature(mp50, degree):
    X = mpmath.mpf(5)
    c = mp_fit.coefficients(X, degree=degree)
    mean_sq = (
        mpmath.quad(
            lambda x: (x ** mpmath.mpf(1.5) - sum(ck * x**k for k, ck in enumerate(c))) ** 2, [0, X]
        )
        / X
    )
    assert abs(mp_fit.rms_error(X, degree=degree) - mpmath.sqrt(mean_sq)) < mpmath.mpf(10) ** -30


def test_degree_3_largest_error_is_at_zero_and_exact():
    """c0 < 0, the error is largest at X2 = 0: |c0| = 8/1155 X2max^(3/2).

    docs/modelling.md#cubic-fit
    """
    X = np.array([0.1, 1.0, 7.0])
    # the same numpy power of the same array and one product on both sides: equal bit for
    # bit on any CPU (the tolerance only allows another order of the product)
    np.testing.assert_allclose(fit.max_error(X), 8 / 1155 * X**1.5, rtol=1e-15)
    np.testing.assert_array_equal(fit.max_error_location(X), 0.0)
    assert fit.coefficients(1.0)[0] < 0


def test_errors_shrink_with_degree():
    errors = [fit.max_error(1.0, degree=n) for n in range(1, 9)]
    assert all(a > b for a, b in zip(errors, errors[1:]))


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan")])
def test_bad_range_raises(bad):
    with pytest.raises(ValueError, match="'X2max'"):
        fit.coefficients(bad)


@pytest.mark.parametrize("degree", [0, 9, "3", None])
def test_bad_degree_raises(degree):
    with pytest.raises(ValueError, match="degree"):
        fit.max_error(1.0, degree=degree)


def test_x2max_of_the_mdsm_scene_is_equilibrium_plus_fast_amplitude(rng):
    """X2max = X2^0 (Eq. 9) + |linear normal response| (normal block of Eq. 11)."""
    from conftest import random_params

    from beltmdsm.generated import unforced

    for contact in ("hertz_damp", "kelvin_voigt"):
        p = random_params(rng)
        J = unforced.jacobian_at_equilibrium(contact=contact, **p)[2:, 2:]
        W = p["Omega"]
        x = np.linalg.solve(1j * W * np.eye(2) - J, [0, -p["alpha"] * W**2])[0]
        expected = unforced.equilibrium(contact=contact, **p)[2] + abs(x)
        assert fit.mdsm_fit_range(contact=contact, **p) == pytest.approx(expected, rel=1e-12)


# The fit of a general exponent (Hunt-Crossley's n_h), closed forms in n_h -------------


def mp_least_squares_power(X, degree, n):
    """Continuous L2 fit of x^n by mpmath: normal equations with quadrature."""
    size = degree + 1
    gram = mpmath.matrix(size, size)
    rhs = mpmath.matrix(size, 1)
    for j in range(size):
        rhs[j] = mpmath.quad(lambda x: x**n * x**j, [0, X])
        for k in range(size):
            gram[j, k] = mpmath.quad(lambda x: x ** (j + k), [0, X])
    return list(mpmath.lu_solve(gram, rhs))


N_H = ["0.7", "1.25", "1.5", "2.3", "3.6", "5.5"]


@pytest.mark.parametrize("n", N_H)
@pytest.mark.parametrize("degree", [1, 3, 8])
def test_hunt_crossley_fit_is_the_least_squares_fit_of_the_power(mp50, n, degree):
    """Coefficients and RMS error, closed forms in n_h, against mpmath at 50 digits
    (quadrature to ~1e-45; the closed forms are exact)."""
    X, n = mpmath.mpf(3), mpmath.mpf(n)
    ref = mp_least_squares_power(X, degree, n)
    got = mp_fit.coefficients(X, degree=degree, contact="hunt_crossley", n_h=n)
    assert max(abs(a - b) for a, b in zip(got, ref)) < mpmath.mpf(10) ** -35 * max(map(abs, ref))
    mean_sq = (
        mpmath.quad(lambda x: (x**n - sum(ck * x**k for k, ck in enumerate(ref))) ** 2, [0, X]) / X
    )
    rms = mp_fit.rms_error(X, degree=degree, contact="hunt_crossley", n_h=n)
    assert abs(rms - mpmath.sqrt(mean_sq)) < mpmath.mpf(10) ** -30 * mpmath.sqrt(mean_sq)


@pytest.mark.parametrize("n", [float(x) for x in N_H])
@pytest.mark.parametrize("degree", [1, 3, 5, 8])
def test_hunt_crossley_max_error_is_the_larger_end_value_and_no_interior_one_exceeds_it(n, degree):
    """The largest error is that of an end of the range (closed forms in n_h), and a dense
    scan finds no interior value above it (to the scan's resolution, 2.5e-6 of X2max,
    where |err'| <= 1e2 X2max^(n-1) bounds the miss by 1e-3 of the largest error)."""
    X = 2.0
    kw = dict(degree=degree, contact="hunt_crossley", n_h=n)
    c = fit.coefficients(X, **kw)
    x = np.linspace(0.0, X, 800001)
    err = np.abs(x**n - sum(ck * x**k for k, ck in enumerate(c)))
    largest = fit.max_error(X, **kw)
    assert largest == pytest.approx(max(err[0], err[-1]), rel=1e-9)
    assert err.max() <= largest * (1 + 1e-9)
    assert fit.max_error_location(X, **kw) == (0.0 if err[0] >= err[-1] else X)


@pytest.mark.parametrize("degree", range(1, 9))
def test_hunt_crossley_at_three_halves_is_eq17(degree):
    """n_h = 3/2 reduces the closed forms to Eqs. (16)-(17) of Hertz-Damp (exactly at 50
    digits; the numpy forms differ by their rounding)."""
    with mpmath.workdps(50):
        X = mpmath.mpf(3)
        hc = dict(degree=degree, contact="hunt_crossley", n_h=mpmath.mpf(3) / 2)
        for name in ("coefficients", "max_error", "rms_error"):
            a, b = getattr(mp_fit, name)(X, **hc), getattr(mp_fit, name)(X, degree=degree)
            a, b = (a, b) if isinstance(a, tuple) else ((a,), (b,))
            assert all(abs(x - y) <= mpmath.mpf(10) ** -40 * (1 + abs(y)) for x, y in zip(a, b))
    if degree == 3:
        np.testing.assert_allclose(
            fit.coefficients(11.547, contact="hunt_crossley", n_h=1.5), eq17(11.547), rtol=1e-13
        )


def test_kelvin_voigt_needs_no_fit():
    assert fit.coefficients(2.0, contact="kelvin_voigt") == (0.0, 1.0, 0.0, 0.0)
    assert fit.max_error(2.0, contact="kelvin_voigt") == 0.0


def test_the_fit_and_its_range_use_the_same_exponent(base):
    """mdsm_fit_range's X2^0 is (g/omega2^2)^(1/n_h): the exponent the fit fits."""
    for n in (1.2, 1.5, 2.5):
        p = {**base, "n_h": n}
        top = fit.mdsm_fit_range(contact="hunt_crossley", **p)
        from beltmdsm.generated import unforced

        X20 = unforced.equilibrium(contact="hunt_crossley", **p)[2]
        assert X20 == pytest.approx((p["g"] / p["omega2"] ** 2) ** (1 / n), rel=1e-14)
        assert top > X20
