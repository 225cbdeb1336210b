"""beltmdsm.generated.dynamics against Eq. (4) typed by hand and against the mpmath variant."""

import hand_eq4 as H
import mpmath
import numpy as np
import pytest
from conftest import random_params, rel_err

from beltmdsm.generated import dynamics, unforced
from beltmdsm.generated.mp import dynamics as mp_dynamics


def eq4_rhs(t, X1, Y1, X2, Y2, p, contact="hertz_damp"):
    """Eq. (4) typed by hand, with Eq. (1)'s zero force out of contact."""
    b1, w1, b2, w2, a, W, mu, g, Vb = (
        p[k] for k in ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g", "Vb")
    )
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
        np.testing.assert_allclose(
            dynamics.rhs(t, X1, Y1, X2, Y2, contact=contact, **p),
            eq4_rhs(t, X1, Y1, X2, Y2, p, contact),
            rtol=1e-12,
            atol=1e-12,
        )


def test_rhs_branch_agrees_with_sign_and_sgn_zero_removes_friction(rng):
    p = random_params(rng)
    t, X1, Y1, X2, Y2 = 0.3, 0.1, p["Vb"] - 1.0, 2.0, 0.2
    np.testing.assert_array_equal(
        dynamics.rhs_branch(t, X1, Y1, X2, Y2, -1, **p), dynamics.rhs(t, X1, Y1, X2, Y2, **p)
    )
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
            fd = (
                dynamics.rhs_branch(0.7, *(x + e), -1, contact=contact, **p)
                - dynamics.rhs_branch(0.7, *(x - e), -1, contact=contact, **p)
            ) / (2 * h)
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


@pytest.mark.parametrize(
    "name,args",
    [
        ("rhs", (0.4, 0.1, 2.0, 1.3, -0.2)),
        ("rhs_branch", (0.4, 0.1, 2.0, 1.3, -0.2, -1)),
        ("jacobian_branch", (0.4, 0.1, 2.0, 1.3, -0.2, 1)),
        ("normal_force", (1.3, -0.2)),
        ("excitation", (0.4,)),
        ("energy", (0.1, 2.0, 1.3, -0.2)),
        ("power_balance", (0.4, 0.1, 2.0, 1.3, -0.2, -1)),
        ("rhs", (0.4, 0.1, 2.0, -0.5, -0.2)),
    ],
)
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


# The functions added with the tension law and the hybrid system ------------------------

EPS = np.finfo(float).eps


def test_free_acceleration_is_the_tangential_acceleration_without_friction(rng):
    """f_t - 2 beta1 omega1 X1' - omega1^2 X1 (hand), within 16 ulps of its terms'
    scale; it is rhs_branch's Y1' with sgn = 0 in contact and in flight."""
    for _ in range(30):
        p = random_params(rng)
        p.update(alpha_t=p["alpha"] * 0.7, Omega_t=p["Omega"] * 1.3, phase_t=0.4)
        t, X1, Y1 = rng.uniform(-5, 5), rng.normal() * 2, rng.normal() * 3
        got = dynamics.free_acceleration(t, X1, Y1, **p)
        with mpmath.workdps(30):
            ref = H.a_free(
                mpmath.mpf(t),
                mpmath.mpf(X1),
                mpmath.mpf(Y1),
                {k: mpmath.mpf(v) for k, v in p.items()},
                m=mpmath,
            )
        assert abs(got - float(ref)) <= 16 * EPS * H.a_free_scale(t, X1, Y1, p)
        for X2, tension in [(1.5, "allowed"), (1.5, "clipped"), (-0.5, "allowed")]:
            branch = dynamics.rhs_branch(t, X1, Y1, X2, 0.3, 0, tension=tension, **p)[1]
            assert abs(branch - got) <= 16 * EPS * H.a_free_scale(t, X1, Y1, p)


def tension_state(rng, p, contact, i):
    """Cycle through: in contact pushing, in contact pulling (F < 0), in flight."""
    t, X1, Y1 = rng.uniform(-5, 5), rng.normal() * 2, rng.normal() * 3
    X2 = rng.uniform(0.3, 3) if i % 3 != 2 else -rng.uniform(0.3, 2)
    edge = -p["omega2"] * (1.0 if contact == "hertz_damp" else max(X2, 0)) / (2 * p["beta2"])
    Y2 = edge - rng.uniform(0.1, 2) if i % 3 == 1 else edge + rng.uniform(0.1, 2)
    return t, np.array([X1, Y1, X2, Y2])


def hand_scale(name, t, x, sgn, p, contact):
    if name in ("rhs", "rhs_branch"):
        return H.rhs_scale(t, x, p, contact)
    if name == "jacobian_branch":
        return np.array(H.jacobian_scale(t, x, p, contact))
    if name == "normal_force":
        return H.force_scale(x[2], x[3], p, contact) if x[2] > 0 else 0.0
    if name == "friction_force":
        return p["mu_s"] * H.force_scale(x[2], x[3], p, contact) if x[2] > 0 else 0.0
    if name == "normal_rhs":
        return H.rhs_scale(t, x, p, contact)[2:]
    if name == "normal_jacobian":
        return np.array(H.jacobian_scale(t, x, p, contact))[2:, 2:]
    if name == "energy":
        return H.energy_scale(x, p, contact)
    if name == "power_balance":
        return H.power_scale(t, x, p, contact)
    raise KeyError(name)


def call_args(name, t, x, sgn):
    return {
        "rhs": (t, *x),
        "rhs_branch": (t, *x, sgn),
        "jacobian_branch": (t, *x, sgn),
        "normal_force": tuple(x[2:]),
        "friction_force": (*x[1:], sgn),
        "normal_rhs": (t, *x[2:]),
        "normal_jacobian": (t, *x[2:]),
        "energy": tuple(x),
        "power_balance": (t, *x, sgn),
    }[name]


@pytest.mark.parametrize("tension", ["allowed", "clipped"])
@pytest.mark.parametrize(
    "name",
    [
        "rhs",
        "rhs_branch",
        "jacobian_branch",
        "normal_force",
        "friction_force",
        "normal_rhs",
        "normal_jacobian",
        "energy",
        "power_balance",
    ],
)
def test_numpy_matches_mpmath_variant_under_both_tension_laws(rng, mp50, name, tension):
    """The mpmath twin at 50 digits as the reference, at states where Eq. (1) pushes,
    pulls and in flight; numpy within 16 ulps of each entry's terms' scale (hand_eq4)."""
    for contact in ("hertz_damp", "kelvin_voigt"):
        for i in range(6):
            p = random_params(rng)
            t, x = tension_state(rng, p, contact, i)
            sgn = float(rng.choice([-1, 0, 1]))
            args = call_args(name, t, x, sgn)
            fast = getattr(dynamics, name)(*args, contact=contact, tension=tension, **p)
            ref = getattr(mp_dynamics, name)(*args, contact=contact, tension=tension, **p)
            ref = ref.tolist() if isinstance(ref, mpmath.matrix) else ref
            ref = np.array([float(v) for v in np.ravel(np.array(ref, dtype=object))])
            scale = np.ravel(np.asarray(hand_scale(name, t, x, sgn, H.full(p), contact), float))
            err = np.abs(np.ravel(np.asarray(fast, dtype=float)) - ref)
            assert np.all(err <= 16 * EPS * scale), (contact, i, fast, ref)


@pytest.mark.parametrize(
    "name,args", [("free_acceleration", (0.4, 0.1, 2.0)), ("excitation", (0.4,))]
)
def test_numpy_matches_mpmath_variant_of_the_excitation_terms(rng, mp50, name, args):
    for _ in range(10):
        p = random_params(rng)
        p.update(
            phase_t=rng.uniform(-3, 3),
            phase_n=rng.uniform(-3, 3),
            Omega_n=p["Omega"] * rng.uniform(0.5, 2),
        )
        fast = np.ravel(getattr(dynamics, name)(*args, **p))
        ref = np.array([float(v) for v in np.ravel(getattr(mp_dynamics, name)(*args, **p))])
        scale = (
            H.a_free_scale(args[0], args[1], args[2], p)
            if name == "free_acceleration"
            else np.array(H.excitation_scale(args[0], p))
        )
        assert np.all(np.abs(fast - ref) <= 16 * EPS * scale)


def test_tension_option_is_checked_by_name(base):
    for fn, args in [
        (dynamics.rhs, (0.0, 0.0, 0.0, 1.0, 0.0)),
        (dynamics.normal_force, (1.0, 0.0)),
        (dynamics.normal_rhs, (0.0, 1.0, 0.0)),
        (mp_dynamics.normal_jacobian, (0.0, 1.0, 0.0)),
    ]:
        with pytest.raises(ValueError, match="tension"):
            fn(*args, tension="elastic", **base)
    with pytest.raises(ValueError, match="tension"):
        dynamics.bind_normal_rhs(tension="none", **base)


@pytest.mark.parametrize("tension", ["allowed", "clipped"])
def test_friction_force_is_coulomb_with_the_normal_force_of_eq1(rng, tension):
    """Eqs. (2)-(3): -mu_s sgn F_n with F_n typed by hand (hand_eq4), zero in flight."""
    for contact in ("hertz_damp", "kelvin_voigt"):
        for i in range(6):
            p = random_params(rng)
            _, x = tension_state(rng, p, contact, i)
            for sgn in (-1.0, 0.0, 1.0):
                got = dynamics.friction_force(
                    x[1], x[2], x[3], sgn, contact=contact, tension=tension, **p
                )
                Fn = H.force(x[2], x[3], H.full(p), contact, tension) if x[2] > 0 else 0.0
                scale = p["mu_s"] * H.force_scale(x[2], x[3], H.full(p), contact) if x[2] > 0 else 0
                assert abs(got - (-p["mu_s"] * sgn * Fn)) <= 16 * EPS * scale, (contact, i, sgn)
