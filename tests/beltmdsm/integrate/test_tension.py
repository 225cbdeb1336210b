"""The tension law of the contact (docs/modelling.md#tension): Eq. (1) as printed, or
``max(F, 0)``, a contact that cannot pull.

References: Eqs. (1)-(4) typed by hand (tests/hand_eq4.py); the energy balance
dE/dt = P_input - P_viscous - P_friction with dE/dt by the chain rule and the gradient
of `energy` by finite differences; Jacobians against finite differences.

Error model of the comparisons with hand formulas: each generated value is a short sum
of products with at most one elementary function, so it is within ~16 ulps of the sum
of the absolute values of its terms (the *scale* that hand_eq4 computes), including the
rounding of the excitation's argument.
"""

import hand_eq4 as H
import mpmath
import numpy as np
import pytest
from conftest import random_params

from beltmdsm.generated import dynamics
from beltmdsm.generated.mp import dynamics as mp_dynamics

EPS = H.EPS
ULPS = 16


def tension_params(rng):
    p = random_params(rng)
    p.update(
        alpha_n=p["alpha"] * rng.uniform(0.3, 2),
        Omega_n=p["Omega"] * rng.uniform(0.5, 2),
        phase_t=rng.uniform(-3, 3),
        phase_n=rng.uniform(-3, 3),
    )
    return p


def state(rng, p, contact, pulling=None, X2=None):
    """A random state; ``pulling=True``: in contact with Eq. (1) tensile (F < 0:
    Hertz-Damp Y2 < -omega2 / (2 beta2), Kelvin-Voigt Y2 < -omega2 X2 / (2 beta2));
    ``False``: in contact with F > 0."""
    t = rng.uniform(-5, 5)
    X2 = rng.uniform(0.3, 3.0) if X2 is None else X2
    edge = -p["omega2"] * (1.0 if contact == "hertz_damp" else X2) / (2 * p["beta2"])
    if pulling is None:
        Y2 = rng.normal() * 3
    elif pulling:
        Y2 = edge - rng.uniform(0.05, 3)
    else:
        Y2 = edge + rng.uniform(0.05, 3)
    return t, np.array([rng.normal() * 2, rng.normal() * 3, X2, Y2])


def within(got, ref, scale, ulps=ULPS):
    got = np.asarray(got, dtype=float).ravel()
    ref = np.asarray([float(r) for r in np.ravel(np.asarray(ref, dtype=object))])
    scale = np.asarray(scale, dtype=float).ravel()
    return np.all(np.abs(got - ref) <= ulps * EPS * scale), np.abs(got - ref), scale


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_normal_force_clipped_is_max_of_eq1_and_zero_out_of_contact(rng, contact):
    pulls = 0
    for i in range(60):
        p = tension_params(rng)
        t, x = state(rng, p, contact, pulling=i % 2 == 0 or None, X2=rng.uniform(-1, 3))
        X2, Y2 = x[2], x[3]
        F = H.force(X2, Y2, p, contact)
        scale = H.force_scale(X2, Y2, p, contact)
        allowed = dynamics.normal_force(X2, Y2, contact=contact, **p)
        clipped = dynamics.normal_force(X2, Y2, contact=contact, tension="clipped", **p)
        assert abs(allowed - F) <= ULPS * EPS * scale
        if X2 <= 0:
            assert allowed == 0 and clipped == 0
        elif F < -ULPS * EPS * scale:
            assert clipped == 0
            pulls += 1
        else:
            assert abs(clipped - max(F, 0.0)) <= ULPS * EPS * scale
        assert clipped >= 0
    assert pulls >= 10


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_normal_force_broadcasts_and_its_mpmath_twin_agrees(rng, mp50, contact):
    p = tension_params(rng)
    X2 = np.linspace(-1, 3, 9)[:, None]
    Y2 = np.linspace(-4, 1, 11)[None, :] * p["omega2"] / (2 * p["beta2"])  # F < 0 and > 0
    for tension in H.TENSIONS:
        grid = dynamics.normal_force(X2, Y2, contact=contact, tension=tension, **p)
        assert grid.shape == (9, 11)
        assert (grid < 0).any() == (tension == "allowed")
        for i, j in [(0, 0), (8, 0), (8, 10), (5, 3), (6, 1)]:
            ref = H.force(
                mpmath.mpf(X2[i, 0]),
                mpmath.mpf(Y2[0, j]),
                {k: mpmath.mpf(v) for k, v in p.items()},
                contact,
                tension,
            )
            twin = mp_dynamics.normal_force(
                X2[i, 0], Y2[0, j], contact=contact, tension=tension, **p
            )
            scale = H.force_scale(X2[i, 0], Y2[0, j], p, contact)
            assert abs(grid[i, j] - float(ref)) <= ULPS * EPS * scale
            assert abs(grid[i, j] - float(twin)) <= ULPS * EPS * scale


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_clipped_law_has_no_friction_and_no_normal_force_where_eq1_would_pull(rng, contact):
    """Where Eq. (1) is tensile the clipped field is the free one: (Y1, a_free, Y2,
    g + f_n) for every friction direction; where it pushes, the two laws agree."""
    for _ in range(30):
        p = tension_params(rng)
        t, x = state(rng, p, contact, pulling=True)
        free = H.rhs(t, x, 0, p, contact, "clipped")
        scale = H.rhs_scale(t, x, p, contact)
        assert H.force(x[2], x[3], p, contact, "clipped") == 0
        ok, err, _ = within(
            dynamics.rhs(t, *x, contact=contact, tension="clipped", **p), free, scale
        )
        assert ok, err
        for sgn in (-1, 0, 1):
            ok, err, _ = within(
                dynamics.rhs_branch(t, *x, sgn, contact=contact, tension="clipped", **p),
                free,
                scale,
            )
            assert ok, err
        # the allowed law does pull there: its normal acceleration exceeds g + f_n
        allowed = dynamics.rhs(t, *x, contact=contact, **p)
        assert allowed[3] > free[3]
        t, x = state(rng, p, contact, pulling=False)
        for sgn in (-1, 1):
            clipped = dynamics.rhs_branch(t, *x, sgn, contact=contact, tension="clipped", **p)
            np.testing.assert_array_equal(
                clipped, dynamics.rhs_branch(t, *x, sgn, contact=contact, **p)
            )
            ok, err, _ = within(
                clipped, H.rhs(t, x, sgn, p, contact), H.rhs_scale(t, x, p, contact)
            )
            assert ok, err


@pytest.mark.parametrize("contact", H.CONTACTS)
def test_energy_is_the_hand_energy_and_the_same_for_both_laws(rng, contact):
    for _ in range(30):
        p = tension_params(rng)
        t, x = state(rng, p, contact, X2=rng.uniform(-2, 3))
        allowed = dynamics.energy(*x, contact=contact, **p)
        assert dynamics.energy(*x, contact=contact, tension="clipped", **p) == allowed
        assert abs(allowed - H.energy(x, p, contact)) <= ULPS * EPS * H.energy_scale(x, p, contact)


def energy_gradient(x, p, contact, tension):
    """Gradient of the generated energy by the 5-point central difference, step
    h_k = 1e-3 max(1, |x_k|). Error: truncation h^4 |E^(5)| / 30 (E is quadratic
    except the contact potential, whose 5th derivative is ~w2^2 X2^(-5/2) <~ 10 w2^2 for
    X2 >= 0.3: <= 1e-11) plus rounding (3/2) (8 eps E_scale) / h_k. Returns (grad, err)."""
    grad, err = np.empty(4), np.empty(4)
    scale = H.energy_scale(x, p, contact)
    for k in range(4):
        h = 1e-3 * max(1.0, abs(x[k]))
        E = {}
        for j in (-2, -1, 1, 2):
            y = x.copy()
            y[k] += j * h
            E[j] = dynamics.energy(*y, contact=contact, tension=tension, **p)
        grad[k] = (8 * (E[1] - E[-1]) - (E[2] - E[-2])) / (12 * h)
        err[k] = 1.5 * 8 * EPS * scale / h + 1e-11 * (1 + p["omega2"] ** 2)
    return grad, err


@pytest.mark.parametrize("tension", H.TENSIONS)
@pytest.mark.parametrize("contact", H.CONTACTS)
def test_power_balance_closes_the_energy_balance_along_rhs(rng, contact, tension):
    """dE/dt = grad E . rhs = P_input - P_viscous - P_friction, with sgn = sgn(Y1 - Vb)
    as in rhs; the power terms are the hand ones; P_viscous >= 0 everywhere, and where
    the clip acts it is the dashpot plus the elastic force the clip removes, -F_el Y2."""
    clipped_states = 0
    for i in range(40):
        p = tension_params(rng)
        pulling = [True, False, None, None][i % 4]
        t, x = state(rng, p, contact, pulling=pulling)
        if i % 8 == 7:
            x[2] = -rng.uniform(0.3, 2)  # flight
        sgn = float(np.sign(x[1] - p["Vb"]))
        f = dynamics.rhs(t, *x, contact=contact, tension=tension, **p)
        grad, grad_err = energy_gradient(x, p, contact, tension)
        P = dynamics.power_balance(t, *x, sgn, contact=contact, tension=tension, **p)
        scales = H.power_scale(t, x, p, contact)
        ok, err, _ = within(P, H.power_balance(t, x, sgn, p, contact, tension), scales)
        assert ok, err
        balance = P[0] - P[1] - P[2]
        # dE/dt: |f_k| times the gradient's error, plus the power terms' rounding
        tol = np.abs(f) @ grad_err + ULPS * EPS * sum(scales)
        assert abs(grad @ f - balance) <= tol, (grad @ f, balance, tol)
        assert P[1] >= -ULPS * EPS * scales[1]
        if tension == "clipped" and x[2] > 0 and H.force(x[2], x[3], p, contact) < 0:
            clipped_states += 1
            elastic = H.force(x[2], 0.0, p, contact)
            dashpot = 2 * p["beta1"] * p["omega1"] * x[1] ** 2
            assert abs(P[1] - (dashpot - elastic * x[3])) <= ULPS * EPS * scales[1]
            assert P[1] >= dashpot and P[2] == 0
    assert clipped_states >= 5 or tension == "allowed"


def fd_jacobian(fun, x, steps):
    cols = []
    for k, h in enumerate(steps):
        e = np.zeros(len(x))
        e[k] = h
        cols.append((np.asarray(fun(x + e)) - np.asarray(fun(x - e))) / (2 * h))
    return np.stack(cols, axis=-1)


@pytest.mark.parametrize("tension", H.TENSIONS)
@pytest.mark.parametrize("contact", H.CONTACTS)
def test_jacobians_match_finite_differences_away_from_the_kink(rng, contact, tension):
    """jacobian_branch against central differences of rhs_branch, normal_jacobian
    against those of normal_rhs, at states in contact with |F| far from 0 (so the step
    does not cross the kink of max(F, 0)) and in flight; and the hand Jacobian.

    Error of the differences with step h_k = 1e-6 max(1, |x_k|): rounding
    eps scale_i / h_k (scale_i: the terms' scale of entry i) plus truncation
    h_k^2 |f'''| / 6 (f''' ~ scale X2^(-3/2) <~ 6 scale at X2 >= 0.3: <= 1e-11 scale);
    tolerance 4 eps scale_i / h_k + 1e-10 scale_i.
    """
    for i in range(24):
        p = tension_params(rng)
        t, x = state(rng, p, contact, pulling=[True, False, None][i % 3])
        if i % 6 == 5:
            x[2] = -rng.uniform(0.3, 2)
        F, Fs = H.force(x[2], x[3], p, contact), H.force_scale(x[2], x[3], p, contact)
        if 0 < x[2] and abs(F) < 1e-2 * Fs:
            continue  # next to the kink F = 0
        steps = 1e-6 * np.maximum(1.0, np.abs(x))
        scale = np.array(H.rhs_scale(t, x, p, contact))
        tol = 4 * EPS * scale[:, None] / steps[None, :] + 1e-10 * scale[:, None]
        for sgn in (-1, 0, 1):
            J = dynamics.jacobian_branch(t, *x, sgn, contact=contact, tension=tension, **p)
            fd = fd_jacobian(
                lambda y: dynamics.rhs_branch(t, *y, sgn, contact=contact, tension=tension, **p),
                x,
                steps,
            )
            assert np.all(np.abs(J - fd) <= tol), (J, fd)
            hand = np.array(H.jacobian(t, x, sgn, p, contact, tension))
            assert np.all(
                np.abs(J - hand) <= ULPS * EPS * np.array(H.jacobian_scale(t, x, p, contact))
            )
        N = dynamics.normal_jacobian(t, x[2], x[3], contact=contact, tension=tension, **p)
        fd = fd_jacobian(
            lambda y: dynamics.normal_rhs(t, *y, contact=contact, tension=tension, **p),
            x[2:],
            steps[2:],
        )
        assert np.all(np.abs(N - fd) <= tol[2:, 2:]), (N, fd)
        np.testing.assert_array_equal(N, J[2:, 2:])
        if tension == "clipped" and x[2] > 0 and F < 0:
            # the clipped force is 0 on a neighbourhood: the free field's Jacobian
            assert np.all(N == [[0, 1], [0, 0]])


@pytest.mark.parametrize("tension", H.TENSIONS)
@pytest.mark.parametrize("contact", H.CONTACTS)
def test_normal_rhs_is_the_normal_equation_alone(rng, contact, tension):
    for i in range(20):
        p = tension_params(rng)
        t, x = state(rng, p, contact, pulling=[True, False][i % 2])
        if i % 5 == 4:
            x[2] = -rng.uniform(0.3, 2)
        got = dynamics.normal_rhs(t, x[2], x[3], contact=contact, tension=tension, **p)
        ref = H.rhs(t, x, 0, p, contact, tension)[2:]
        ok, err, _ = within(got, ref, H.rhs_scale(t, x, p, contact)[2:])
        assert ok, err
        # Eq. (4)'s normal rows, which do not contain the tangential state (same
        # expression, summed in another order: a few ulps of its scale)
        ok, err, _ = within(
            got,
            dynamics.rhs_branch(t, *x, -1, contact=contact, tension=tension, **p)[2:],
            H.rhs_scale(t, x, p, contact)[2:],
            ulps=4,
        )
        assert ok, err
