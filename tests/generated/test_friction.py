"""beltmdsm.generated.friction against Eqs. (23)-(25) typed by hand, their definition and
mpmath."""

import mpmath
import numpy as np
import pytest
from conftest import random_params

from beltmdsm.generated import friction, unforced
from beltmdsm.generated.mp import friction as mp_friction


def eq23(Vr, Vhat, mu_s):
    """Eq. (23) as printed."""
    Vr = np.asarray(Vr, float)
    inside = mu_s * (1 - 2 / np.pi * np.arccos(np.clip(Vr / Vhat, -1, 1)))
    return np.where(np.abs(Vr) <= Vhat, inside, mu_s * np.sign(Vr))


def eq25(Vb, Vhat, mu_s):
    """Eq. (25) as printed (valid for Vb < Vhat)."""
    return 2 * mu_s / (np.pi * Vhat * np.sqrt(1 - (Vb / Vhat) ** 2))


def test_mu_bar_is_eq23():
    Vr = np.linspace(-12, 12, 241)
    np.testing.assert_allclose(
        friction.mu_bar(Vr, 8.5, 0.4), eq23(Vr, 8.5, 0.4), rtol=1e-13, atol=1e-15
    )


@pytest.mark.parametrize("Vr", [-9.0, -7.99, -4.0, -0.3, 0.0, 2.5, 7.9, 11.0])
def test_mu_bar_is_the_average_of_coulomb_friction_over_a_harmonic_cycle(mp50, Vr):
    """Eq. (23)'s meaning: <mu_s sgn(Vr + Vhat sin theta)> over theta."""
    Vhat, mu_s = mpmath.mpf(8), mpmath.mpf("0.4")
    Vr = mpmath.mpf(Vr)
    if abs(Vr) < Vhat:
        cut = mpmath.asin(-Vr / Vhat)  # where the sign changes
        points = [-mpmath.pi / 2, cut, mpmath.pi - cut, 3 * mpmath.pi / 2]
    else:
        points = [-mpmath.pi / 2, 3 * mpmath.pi / 2]
    avg = mpmath.quad(lambda th: mu_s * mpmath.sign(Vr + Vhat * mpmath.sin(th)), points) / (
        2 * mpmath.pi
    )
    assert abs(mp_friction.mu_bar(Vr, Vhat, mu_s) - avg) < mpmath.mpf(10) ** -40
    # numpy's arccos at <= 4 ulp (<= 8 eps near pi; Vr / 8 is exact), then / pi (and the
    # double pi), 1 + and mu_s *: |error| <= 8.1 eps mu_s = 7.2e-16 on any CPU
    assert friction.mu_bar(float(Vr), 8.0, 0.4) == pytest.approx(float(avg), abs=1e-15)


def test_mu_bar_at_the_ends_of_the_arc_cosine_is_coulomb_exactly(mp50):
    """At |Vr| = Vhat the sine only touches the sign change: the average is -+mu_s."""
    assert mp_friction.mu_bar(-8, 8, "0.4") == -mpmath.mpf("0.4")
    assert mp_friction.mu_bar(8, 8, "0.4") == mpmath.mpf("0.4")
    assert friction.mu_bar(-8.0, 8.0, 0.4) == -0.4


def test_mu_bar0_is_mu_bar_at_minus_vb():
    Vb = np.linspace(0, 10, 21)
    np.testing.assert_array_equal(friction.mu_bar0(Vb, 8.5, 0.4), friction.mu_bar(-Vb, 8.5, 0.4))


def test_slope_is_eq25_and_the_derivative_of_eq23(mp50):
    Vb = np.linspace(0, 8, 17)
    np.testing.assert_allclose(friction.mu_bar_slope(Vb, 8.5, 0.4), eq25(Vb, 8.5, 0.4), rtol=1e-14)
    for v in (0.5, 4.0, 8.4):
        d = mpmath.diff(lambda x: mp_friction.mu_bar(x, 8.5, "0.4"), -mpmath.mpf(v))
        assert abs(mp_friction.mu_bar_slope(v, 8.5, "0.4") - d) < mpmath.mpf(10) ** -30


def test_slope_as_vb_approaches_vhat_from_below(mp50):
    """Relative error <= 1e-13 up to 1e-15 below Vhat; the printed Eq. (25) loses digits."""
    Vhat = 8.5
    for k in range(2, 16):
        Vb = Vhat * (1 - 10.0**-k)
        exact = mp_friction.mu_bar_slope(Vb, Vhat, "0.4")  # exact input, 50 digits
        got = friction.mu_bar_slope(Vb, Vhat, 0.4)
        assert np.isfinite(got)
        assert abs(got - float(exact)) / float(exact) < 1e-13
    printed = eq25(Vhat * (1 - 1e-15), Vhat, 0.4)
    exact = float(mp_friction.mu_bar_slope(Vhat * (1 - 1e-15), Vhat, "0.4"))
    assert abs(printed - exact) / exact > 1e-3


def test_slope_at_and_beyond_vhat_is_documented_and_not_nan():
    assert friction.mu_bar_slope(8.5, 8.5, 0.4) == np.inf
    assert friction.mu_bar_slope(np.nextafter(8.5, 9), 8.5, 0.4) == 0.0
    assert friction.mu_bar_slope(20.0, 8.5, 0.4) == 0.0
    assert np.isfinite(friction.mu_bar_slope(np.nextafter(8.5, 0), 8.5, 0.4))
    # without friction mu_bar is identically 0: so is its slope, at Vb = Vhat too
    np.testing.assert_array_equal(friction.mu_bar_slope([3.0, 8.5, 20.0], 8.5, 0.0), 0.0)


def test_vhat_tangential_is_the_oscillator_velocity_amplitude(rng):
    for _ in range(20):
        p = random_params(rng)
        b1, w1, a, W = p["beta1"], p["omega1"], p["alpha"], p["Omega"]
        hand = a * W**3 / abs(w1**2 - W**2 + 2j * b1 * w1 * W)
        assert friction.vhat(**p) == pytest.approx(hand, rel=1e-13)


def coupled_by_linear_algebra(p, contact="hertz_damp"):
    """Velocity amplitude of X1 for x' = J0 x + b e^(i W t), solved with numpy."""
    J0 = unforced.jacobian_at_equilibrium(contact=contact, **p)

    def velocity(b, W):
        x = np.linalg.solve(1j * W * np.eye(4) - J0, b)
        return 1j * W * x[0]

    Wt = p.get("Omega_t", p["Omega"])
    Wn = p.get("Omega_n", p["Omega"])
    Ft = p["alpha"] * Wt**2 * np.exp(1j * p.get("phase_t", 0.0))
    Fn = -p["alpha"] * Wn**2 * np.exp(1j * p.get("phase_n", 0.0))
    vt = velocity(np.array([0, Ft, 0, 0]), Wt)
    vn = velocity(np.array([0, 0, 0, Fn]), Wn)
    return abs(vt + vn) if Wt == Wn else abs(vt) + abs(vn)


@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
@pytest.mark.parametrize("extra", [{}, {"phase_t": np.pi / 2}, {"Omega_t": 6.0}])
def test_vhat_coupled_against_linear_algebra(rng, contact, extra):
    for _ in range(10):
        p = {**random_params(rng), **extra}
        assert friction.vhat(model="coupled", contact=contact, **p) == pytest.approx(
            coupled_by_linear_algebra(p, contact), rel=1e-11
        )


def test_vhat_readings_differ_at_the_base_set(base):
    """docs/modelling.md#vhat: the tangential reading is close to the paper's 'about 8'."""
    tangential = friction.vhat(**base)
    assert 8.0 < tangential < 9.0
    assert abs(friction.vhat(model="coupled", **base) - tangential) > 1.0


@pytest.mark.parametrize(
    "fn,args",
    [
        ("mu_bar", (-3.0, 8.5, 0.4)),
        ("mu_bar", (12.0, 8.5, 0.4)),
        ("mu_bar0", (3.0, 8.5, 0.4)),
        ("mu_bar_slope", (3.0, 8.5, 0.4)),
        ("mu_bar_slope", (9.0, 8.5, 0.4)),
    ],
)
def test_numpy_matches_mpmath_variant(mp50, fn, args):
    fast = getattr(friction, fn)(*args)
    ref = getattr(mp_friction, fn)(*args)
    assert fast == pytest.approx(float(ref), rel=1e-14, abs=1e-300)


@pytest.mark.parametrize("model", ["tangential", "coupled"])
def test_vhat_matches_mpmath_variant(mp50, rng, model):
    for _ in range(10):
        p = random_params(rng)
        assert friction.vhat(model=model, **p) == pytest.approx(
            float(mp_friction.vhat(model=model, **p)), rel=1e-12
        )


@pytest.mark.parametrize(
    "args,name",
    [
        ((1.0, -8.5, 0.4), "'Vhat'"),
        ((1.0, 8.5, -0.4), "'mu_s'"),
        ((-1.0, 8.5, 0.4), "'Vb'"),
        ((np.nan, 8.5, 0.4), "'Vb'"),
    ],
)
def test_bad_input_raises_naming_the_parameter(args, name):
    with pytest.raises(ValueError, match=name):
        friction.mu_bar_slope(*args)


def test_unknown_vhat_model_raises(base):
    with pytest.raises(ValueError, match="model"):
        friction.vhat(model="linear", **base)


# Stribeck's law: the effective friction is Eq. (23) with mu_s plus a quadrature ----------


def stribeck_signed(v, mu_s, mu_k, v_s, m=mpmath):
    """sgn(v) (mu_k + (mu_s - mu_k) exp(-|v|/v_s)), typed by hand."""
    return m.sign(v) * (mu_k + (mu_s - mu_k) * m.exp(-abs(v) / v_s))


def mp_average(f, Vr, Vhat):
    """<f(Vr + Vhat sin theta)> over a period by mpmath, split where the sign changes and
    at the extremes of the sine (where an exp(-|v|/v_s) peaks)."""
    points = [-mpmath.pi / 2, mpmath.pi / 2, 3 * mpmath.pi / 2]
    if abs(Vr) < Vhat:
        cut = mpmath.asin(-Vr / Vhat)
        points = sorted(points + [cut, mpmath.pi - cut])
    return mpmath.quad(lambda th: f(Vr + Vhat * mpmath.sin(th)), points) / (2 * mpmath.pi)


#: Quadrature error of beltmdsm.generated._support.quad (28 graded panels of 10 Gauss-Legendre
#: nodes) for these integrands, measured against mpmath over Vhat/v_s in [0.1, 1e3]:
#: below 1e-13 of the integral's scale mu_s - mu_k; rounding adds a few ulps of mu_s.
QUAD_TOL = 1e-13


@pytest.mark.parametrize("kappa", [0.5, 5.0, 50.0, 500.0])
@pytest.mark.parametrize("Vr", [-9.0, -7.99, -4.0, -0.3, 0.0, 2.5, 11.0])
def test_stribeck_mu_bar_is_the_average_of_the_law_over_a_harmonic_cycle(mp50, Vr, kappa):
    """friction.mu_bar(friction="stribeck") (numpy: the quadrature of beltmdsm.generated._support;
    mpmath: mpmath.quad) against the cycle average by mpmath of the law typed here."""
    Vhat, mu_s, mu_k = mpmath.mpf(8), mpmath.mpf("0.4"), mpmath.mpf("0.25")
    v_s = Vhat / kappa
    avg = mp_average(lambda v: stribeck_signed(v, mu_s, mu_k, v_s), mpmath.mpf(Vr), Vhat)
    law = dict(friction="stribeck", mu_k=mu_k, v_s=v_s)
    assert abs(mp_friction.mu_bar(Vr, Vhat, mu_s, **law) - avg) < mpmath.mpf(10) ** -30
    got = friction.mu_bar(Vr, 8.0, 0.4, friction="stribeck", mu_k=0.25, v_s=float(v_s))
    assert abs(got - float(avg)) <= QUAD_TOL * 0.15 + 16 * np.finfo(float).eps * 0.4


@pytest.mark.parametrize("kappa", [0.5, 5.0, 50.0])
@pytest.mark.parametrize("Vb", [0.3, 4.0, 7.9, 11.0])
def test_stribeck_slope_is_the_derivative_of_the_average(mp50, Vb, kappa):
    """mu_bar_slope at Vr = -Vb: the sign's Eq. (25) times mu_s plus the quadrature of the
    law's slope, against mpmath's derivative of the mpmath cycle average."""
    Vhat, mu_s, mu_k = mpmath.mpf(8), mpmath.mpf("0.4"), mpmath.mpf("0.25")
    v_s = Vhat / kappa

    def average(x):
        return mp_average(lambda v: stribeck_signed(v, mu_s, mu_k, v_s), x, Vhat)

    with mpmath.workdps(40):
        d = mpmath.diff(average, -mpmath.mpf(Vb))
    law = dict(friction="stribeck", mu_k=mu_k, v_s=v_s)
    assert abs(mp_friction.mu_bar_slope(Vb, Vhat, mu_s, **law) - d) < mpmath.mpf(10) ** -25
    got = friction.mu_bar_slope(Vb, 8.0, 0.4, friction="stribeck", mu_k=0.25, v_s=float(v_s))
    # the sign's part: Eq. (25)'s rounding (a few ulps of it, <= 1e-15 relative)
    assert abs(got - float(d)) <= QUAD_TOL * 0.15 * float(kappa / Vhat) + 1e-15 * abs(float(d))


def test_stribeck_slope_below_vhat_is_coulombs_minus_the_fall(base):
    """Without reversal (Vb > Vhat) the sign has no slope; the law's slope remains and is
    negative (falling friction): the effective friction is no longer flat above Vhat."""
    s = friction.mu_bar_slope(12.0, 8.0, 0.4, friction="stribeck", mu_k=0.25, v_s=1.0)
    assert s < 0
    assert friction.mu_bar_slope(12.0, 8.0, 0.4) == 0.0
