"""generated.dynamics against Eq. (4) typed by hand and against the mpmath variant."""
import mpmath
import numpy as np
import pytest

from generated import dynamics, unforced
from generated.mp import dynamics as mp_dynamics
from conftest import random_params, rel_err


def eq4_rhs(t, X1, Y1, X2, Y2, p, contact="hertz_damp"):
    """Eq. (4) typed by hand, with Eq. (1)'s zero force out of contact."""
    b1, w1, b2, w2, a, W, mu, g, Vb = (p[k] for k in
                                       ("beta1", "omega1", "beta2", "omega2", "alpha",
                                        "Omega", "mu_s", "g", "Vb"))
    if X2 <= 0:
        Fn = 0.0
    elif contact == "hertz_damp":
        Fn = 2 * b2 * w2 * X2**1.5 * Y2 + w2**2 * X2**1.5
    else:
        Fn = 2 * b2 * w2 * Y2 + w2**2 * X2
    force = a * W**2 * np.sin(W * t)
    Y1d = -2 * b1 * w1 * Y1 - w1**2 * X1 - mu * np.sign(Y1 - Vb) * Fn + force
    Y2d = -Fn + g - force
    return np.array([Y1, Y1d, Y2, Y2d])


@pytest.mark.parametrize("contact", ["hertz_damp", "kelvin_voigt"])
def test_rhs_is_eq4(rng, contact):
    for _ in range(50):
        p = random_params(rng)
        t, X1, Y1, X2, Y2 = rng.normal(size=5) * [10, 1, 5, 1, 1]
        np.testing.assert_allclose(dynamics.rhs(t, X1, Y1, X2, Y2, contact=contact, **p),
                                   eq4_rhs(t, X1, Y1, X2, Y2, p, contact), rtol=1e-12,
                                   atol=1e-12)


def test_rhs_branch_agrees_with_sign_and_sgn_zero_removes_friction(rng):
    p = random_params(rng)
    t, X1, Y1, X2, Y2 = 0.3, 0.1, p["Vb"] - 1.0, 2.0, 0.2
    np.testing.assert_array_equal(dynamics.rhs_branch(t, X1, Y1, X2, Y2, -1, **p),
                                  dynamics.rhs(t, X1, Y1, X2, Y2, **p))
    free = dynamics.rhs_branch(t, X1, Y1, X2, Y2, 0, **p)[1]
    with_friction = dynamics.rhs_branch(t, X1, Y1, X2, Y2, 1, **p)[1]
    Fn = dynamics.normal_force(X2, Y2, **p)
    np.testing.assert_allclose(free - with_friction, p["mu_s"] * Fn, rtol=1e-13)


def test_rhs_at_equilibrium_without_excitation_is_zero(base):
    base["alpha"] = 0.0
    state = unforced.equilibrium(**base)
    np.testing.assert_allclose(dynamics.rhs(1.0, *state, **base), 0, atol=1e-14)


def test_jacobian_branch_matches_finite_differences(rng):
    for contact in ("hertz_damp", "kelvin_voigt"):
        p = random_params(rng)
        x = np.array([0.2, 1.0, 1.5, -0.3])
        J = dynamics.jacobian_branch(0.7, *x, -1, contact=contact, **p)
        h = 1e-6
        for j in range(4):
            e = np.zeros(4)
            e[j] = h
            fd = (dynamics.rhs_branch(0.7, *(x + e), -1, contact=contact, **p)
                  - dynamics.rhs_branch(0.7, *(x - e), -1, contact=contact, **p)) / (2 * h)
            np.testing.assert_allclose(J[:, j], fd, rtol=1e-7, atol=1e-7)


def test_flight_has_no_normal_force_and_free_fall(base):
    assert dynamics.normal_force(-0.1, -3.0, **base) == 0
    d = dynamics.rhs(0.0, 0.0, 0.0, -0.1, 0.0, **base)
    assert d[3] == base["g"]


def test_general_excitation_phase_and_frequencies(base):
    f_t, f_n = dynamics.excitation(0.25, phase_t=np.pi / 2, Omega_n=6.0, alpha_n=1.0, **base)
    a, W = base["alpha"], base["Omega"]
    np.testing.assert_allclose(f_t, a * W**2 * np.cos(W * 0.25), rtol=1e-14)
    np.testing.assert_allclose(f_n, -1.0 * 36 * np.sin(6 * 0.25), rtol=1e-14)


@pytest.mark.parametrize("name,args", [
    ("rhs", (0.4, 0.1, 2.0, 1.3, -0.2)), ("rhs_branch", (0.4, 0.1, 2.0, 1.3, -0.2, -1)),
    ("jacobian_branch", (0.4, 0.1, 2.0, 1.3, -0.2, 1)), ("normal_force", (1.3, -0.2)),
    ("excitation", (0.4,)), ("energy", (0.1, 2.0, 1.3, -0.2)),
    ("power_balance", (0.4, 0.1, 2.0, 1.3, -0.2, -1)), ("rhs", (0.4, 0.1, 2.0, -0.5, -0.2)),
])
def test_numpy_matches_mpmath_variant(rng, mp50, name, args):
    for contact in ("hertz_damp", "kelvin_voigt"):
        kw = {} if name == "excitation" else {"contact": contact}
        p = random_params(rng)
        fast = getattr(dynamics, name)(*args, **kw, **p)
        ref = getattr(mp_dynamics, name)(*args, **kw, **p)
        ref = ref.tolist() if isinstance(ref, mpmath.matrix) else ref
        assert rel_err(fast, ref) < 1e-12


def test_state_nan_raises(base):
    with pytest.raises(ValueError, match="'Y2'"):
        dynamics.rhs(0.0, 0.0, 0.0, 1.0, float("nan"), **base)
