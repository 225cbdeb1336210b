"""beltmdsm.generated.correlation: closed forms against mpmath quadrature."""

import mpmath
import numpy as np
import pytest

from beltmdsm.generated import correlation, friction, unforced
from beltmdsm.generated.mp import correlation as mp_correlation
from beltmdsm.generated.parameters import BASE

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


# Friction laws: the law's averages, and the consistent MDSM's pieces generated ---------


def stribeck_signed(v, p):
    """sgn(v) (mu_k + (mu_s - mu_k) exp(-|v|/v_s)), typed by hand."""
    return mpmath.sign(v) * (p["mu_k"] + (p["mu_s"] - p["mu_k"]) * mpmath.exp(-abs(v) / p["v_s"]))


def quad_law(u, V, N0, N1, th, p, weight=lambda t: 1, harmonic=False):
    """Quadrature of f(u + V sin t)(N0 + N1 sin(t + th)) weight(t) for Stribeck's f, split
    where the sign changes and at the extremes of the sine."""
    u, V, N0, N1, th = map(mpmath.mpf, (u, V, N0, N1, th))
    points = [-mpmath.pi / 2, mpmath.pi / 2, 3 * mpmath.pi / 2]
    if abs(u) < V:
        a = mpmath.asin(-u / V)
        points = sorted(points + [a, mpmath.pi - a])

    def f(t):
        return (
            stribeck_signed(u + V * mpmath.sin(t), p) * (N0 + N1 * mpmath.sin(t + th)) * weight(t)
        )

    return mpmath.quad(f, points) / (mpmath.pi if harmonic else 2 * mpmath.pi)


LAW = {"mu_s": mpmath.mpf("0.4"), "mu_k": mpmath.mpf("0.25"), "v_s": mpmath.mpf("0.8")}
#: beltmdsm.generated._support.quad's error for these integrands (test_friction.QUAD_TOL) times the
#: integral's scale (mu_s - mu_k)(|N0| + |N1|), plus a few ulps of the closed part.
QUAD_TOL = 1e-13


@pytest.mark.parametrize("case", CASES)
def test_stribeck_friction_average_slope_and_harmonic_against_quadrature(mp50, case):
    law = {k: float(v) for k, v in LAW.items()}
    scale = float(LAW["mu_s"] - LAW["mu_k"]) * (abs(case[2]) + abs(case[3]))
    eps = np.finfo(float).eps
    opts = dict(friction="stribeck", **law)
    mp_opts = dict(friction="stribeck", **LAW)
    avg = quad_law(*case, LAW)
    assert abs(mp_correlation.friction_average(*case, **mp_opts) - avg) < mpmath.mpf(10) ** -30
    got = correlation.friction_average(*case, **opts)
    assert abs(got - float(avg)) <= QUAD_TOL * scale + 16 * eps * abs(float(avg))
    for k, w in enumerate((mpmath.sin, mpmath.cos)):
        ref = quad_law(*case, LAW, weight=w, harmonic=True)
        assert abs(mp_correlation.friction_harmonic(*case, **mp_opts)[k] - ref) < 1e-30
        got = correlation.friction_harmonic(*case, **opts)[k]
        assert abs(got - float(ref)) <= QUAD_TOL * scale + 16 * eps * max(1, abs(float(ref)))
    if abs(case[0]) != case[1]:
        d = mpmath.diff(lambda x: quad_law(x, *case[1:], LAW), case[0])
        assert abs(mp_correlation.friction_average_slope(*case, **mp_opts) - d) < 1e-20


def test_coulomb_law_averages_are_mu_s_times_the_signs():
    for case in CASES:
        for law_fn, sign_fn in (
            (correlation.friction_average, correlation.averaged_friction),
            (correlation.friction_average_slope, correlation.averaged_friction_slope),
        ):
            assert law_fn(*case, **BASE) == pytest.approx(BASE["mu_s"] * sign_fn(*case), rel=1e-15)


def test_stribeck_slow_damping_has_the_laws_slope(base):
    """Without fast motion the slow damping is 2 beta1 omega1 + g mu'(Vb) (the unforced
    damping of Stribeck's law): the law enters, not only its value at rest."""
    p = {**base, "Vb": 2.0}
    V = 1e-9  # no reversal: the sign's slope vanishes, the law's remains
    got = correlation.slow_damping(V, 0.0, 0.0, friction="stribeck", **p)
    slope = -(p["mu_s"] - p["mu_k"]) / p["v_s"] * np.exp(-p["Vb"] / p["v_s"])
    assert got == pytest.approx(2 * p["beta1"] * p["omega1"] + p["g"] * slope, rel=1e-12)
