"""generated.correlation: closed forms against mpmath quadrature."""

import mpmath
import numpy as np
import pytest

from generated import correlation, friction, unforced
from generated.mp import correlation as mp_correlation

CASES = [
    (-4.0, 8.0, 9.81, 27.0, 3.9),
    (-7.5, 8.0, 9.81, 5.0, 0.3),
    (2.0, 3.0, 1.0, 0.5, -2.0),
    (-9.0, 8.0, 9.81, 27.0, 3.9),
    (0.0, 1.0, 2.0, 3.0, 1.0),
]


def quad_average(u, V, N0, N1, th, weight=lambda t: 1, harmonic=False):
    """Direct quadrature of sgn(u + V sin t)(N0 + N1 sin(t + th)) weight(t) over a period,
    divided by 2 pi (an average) or by pi (a Fourier coefficient, ``harmonic=True``)."""
    scale = 1 / mpmath.pi if harmonic else 1 / (2 * mpmath.pi)  # at the current precision
    u, V, N0, N1, th = map(mpmath.mpf, (u, V, N0, N1, th))
    points = [-mpmath.pi / 2, 3 * mpmath.pi / 2]
    if abs(u) < V:
        a = mpmath.asin(u / V)
        points = [-a, mpmath.pi + a, 2 * mpmath.pi - a]

    def f(t):
        return mpmath.sign(u + V * mpmath.sin(t)) * (N0 + N1 * mpmath.sin(t + th)) * weight(t)

    return scale * mpmath.quad(f, points)


@pytest.mark.parametrize("case", CASES)
def test_averaged_friction_against_quadrature(mp50, case):
    exact = quad_average(*case)
    assert abs(mp_correlation.averaged_friction(*case) - exact) < mpmath.mpf(10) ** -35
    assert correlation.averaged_friction(*case) == pytest.approx(float(exact), rel=1e-13, abs=1e-14)


@pytest.mark.parametrize("case", CASES[:3])
def test_slope_against_mpmath_derivative(mp50, case):
    u, rest = case[0], case[1:]
    d = mpmath.diff(lambda x: mp_correlation.averaged_friction(x, *rest), mpmath.mpf(u))
    assert correlation.averaged_friction_slope(*case) == pytest.approx(float(d), rel=1e-12)


@pytest.mark.parametrize("case", CASES)
def test_first_harmonic_against_quadrature(mp50, case):
    s1 = quad_average(*case, weight=mpmath.sin, harmonic=True)
    c1 = quad_average(*case, weight=mpmath.cos, harmonic=True)
    got = correlation.first_harmonic(*case)
    assert got[0] == pytest.approx(float(s1), rel=1e-12, abs=1e-13)
    assert got[1] == pytest.approx(float(c1), rel=1e-12, abs=1e-13)


def test_without_correlation_it_is_eq23(base):
    Vr = np.linspace(-10, 10, 41)
    np.testing.assert_allclose(
        0.4 * correlation.averaged_friction(Vr, 8.0, 1.0, 0.0, 0.7),
        friction.mu_bar(Vr, 8.0, 0.4),
        rtol=1e-13,
        atol=1e-15,
    )


@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
def test_fast_normal_force_is_the_linear_normal_response(rng, contact):
    from conftest import random_params

    for _ in range(10):
        p = random_params(rng)
        J = unforced.jacobian_at_equilibrium(contact=contact, **p)[2:, 2:]
        W = p["Omega"]
        x = np.linalg.solve(1j * W * np.eye(2) - J, [0, -p["alpha"] * W**2])
        force = -(J[1, 0] * x[0] + J[1, 1] * x[1])  # stiffness and damping terms
        N1, psi = correlation.fast_normal_force(contact=contact, **p)
        assert N1 == pytest.approx(abs(force), rel=1e-12)
        assert np.exp(1j * psi) == pytest.approx(force / abs(force), rel=1e-12)


@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
def test_fast_tangential_velocity_amplitude_and_phase(rng, contact):
    """X1' = V sin(Omega t + phi) from (i W I - J0) x = b with both excitations."""
    from conftest import random_params

    for _ in range(10):
        p = {**random_params(rng), "phase_t": rng.uniform(-3, 3), "phase_n": rng.uniform(-3, 3)}
        J0 = unforced.jacobian_at_equilibrium(contact=contact, **p)
        W, a = p["Omega"], p["alpha"]
        b = np.array(
            [0, a * W**2 * np.exp(1j * p["phase_t"]), 0, -a * W**2 * np.exp(1j * p["phase_n"])]
        )
        v = 1j * W * np.linalg.solve(1j * W * np.eye(4) - J0, b)[0]
        V, phi = correlation.fast_tangential_velocity(contact=contact, **p)
        assert V * np.exp(1j * phi) == pytest.approx(v, rel=1e-11)
