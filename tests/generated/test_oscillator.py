"""beltmdsm.generated.oscillator: the tangential oscillator of Eq. (4) in closed form.

References: the matrix exponential expm(A tau) of A = [[0, 1], [-omega1^2,
-2 beta1 omega1]] by mpmath at 40 digits (and scipy where it is accurate), and the
response from rest to f_t = alpha_t Omega_t^2 sin(Omega_t t + phase_t) by scipy's
DOP853 at rtol 1e-12 and by mpmath's Taylor integrator (odefun) at 30 digits.

Error model of the closed form: exp, cos and sin are evaluated at arguments lambda tau
that are rounded to eps |lambda| tau, with |lambda| <= omega1 for beta1 <= 1 (|lambda| =
omega1 for the complex pair) and the slow exponent ~omega1 / (2 beta1) for beta1 > 1;
so a few ulps times (1 + omega1 tau) of the matrix norm. Over-damped, the slow exponent
is -omega1 / (beta1 + sqrt(beta1^2 - 1)), free of cancellation for any beta1.
"""

import hand_eq4 as H
import mpmath
import numpy as np
import pytest
import scipy.linalg
from scipy.integrate import solve_ivp

from beltmdsm.generated import hybrid, oscillator
from beltmdsm.generated.mp import oscillator as mp_oscillator
from beltmdsm.generated.parameters import BASE

EPS = np.finfo(float).eps
TAUS = (0.0, 1e-3, 0.5, 3.0, 30.0, 300.0, 1000.0)
BETAS = (0.0, 0.1, 0.5, 1 - 1e-4, 1 - 1e-9, 1.0, 1 + 1e-9, 1 + 1e-4, 2.0, 5.0)


def params(**values):
    """The registry's base set (every law's parameters too) with ``values``."""
    return {**BASE, **values}


def system_matrix(beta1, omega1):
    return [[0, 1], [-(omega1**2), -2 * beta1 * omega1]]


def expm_mp(beta1, omega1, tau):
    """expm(A tau) by mpmath at 40 digits (its Taylor series with scaling and squaring;
    exact-input: beta1, omega1, tau are the floats given)."""
    with mpmath.workdps(40):
        A = mpmath.matrix(system_matrix(mpmath.mpf(beta1), mpmath.mpf(omega1)))
        return mpmath.expm(A * mpmath.mpf(tau))


def check_against(Phi, ref, tol_rel):
    """max |Phi - ref| <= tol_rel |ref|_inf, or both below the float range."""
    with mpmath.workdps(40):
        norm = mpmath.mnorm(ref, "inf")
        if norm < mpmath.mpf("1e-290"):  # e^(-beta1 omega1 tau) underflows
            assert np.all(np.isfinite(Phi)) and np.abs(Phi).max() < 1e-280
            return 0.0
        err = mpmath.mnorm(mpmath.matrix(Phi.tolist()) - ref, "inf")
        return float(err / norm) / tol_rel


@pytest.mark.parametrize("omega1", [1.0, 3.7])
@pytest.mark.parametrize("beta1", BETAS)
def test_state_transition_is_the_matrix_exponential(beta1, omega1):
    """Against mpmath's expm at 40 digits: relative to the matrix norm, 8 ulps times
    (1 + omega1 tau); no NaN or overflow up to tau = 1000 (the result may underflow)."""
    for tau in TAUS:
        Phi = oscillator.state_transition(tau, **params(beta1=beta1, omega1=omega1))
        assert Phi.shape == (2, 2) and np.all(np.isfinite(Phi))
        ratio = check_against(Phi, expm_mp(beta1, omega1, tau), 8 * EPS * (1 + omega1 * tau))
        assert ratio <= 1, (tau, ratio)
    np.testing.assert_array_equal(
        oscillator.state_transition(0.0, **params(beta1=beta1, omega1=omega1)), np.eye(2)
    )


@pytest.mark.parametrize("beta1", [0.0, 0.3, 2.0, 5.0])
def test_state_transition_agrees_with_scipy_expm(beta1):
    """scipy.linalg.expm (scaling and squaring with Pade) is accurate to a few ulps of
    |A tau| |Phi| away from a double eigenvalue: tolerance 64 eps (1 + |A| tau)."""
    omega1 = 1.7
    A = np.array(system_matrix(beta1, omega1))
    for tau in (0.01, 0.5, 2.0, 10.0):
        Phi = oscillator.state_transition(tau, **params(beta1=beta1, omega1=omega1))
        ref = scipy.linalg.expm(A * tau)
        tol = 64 * EPS * (1 + np.abs(A).sum(axis=1).max() * tau) * np.abs(ref).max()
        assert np.abs(Phi - ref).max() <= tol


def test_state_transition_broadcasts_and_composes(rng):
    """Phi(tau1 + tau2) = Phi(tau1) Phi(tau2) (a semigroup), entrywise over a grid of
    damping ratios across critical damping; error: 8 ulps (1 + omega1 tau) each."""
    beta1 = np.array([0.0, 0.2, 1 - 1e-7, 1.0, 1 + 1e-7, 1.5, 4.0])[:, None]
    omega1 = 1.3
    t1, t2 = 0.7, 2.1
    P1 = oscillator.state_transition(t1, **params(beta1=beta1, omega1=omega1))
    P2 = oscillator.state_transition(t2, **params(beta1=beta1, omega1=omega1))
    P12 = oscillator.state_transition(np.array([t1 + t2]), **params(beta1=beta1, omega1=omega1))
    assert P1.shape == (7, 1, 2, 2)
    np.testing.assert_allclose(P12, P1 @ P2, rtol=0, atol=3 * 8 * EPS * (1 + omega1 * (t1 + t2)))


def test_state_transition_long_times_stay_finite():
    for beta1, omega1, tau in [
        (5.0, 1.0, 1000.0),
        (1.0, 50.0, 1e4),
        (0.0, 3.0, 1e6),
        (1 + 1e-12, 2.0, 1e5),
        (1e3, 10.0, 1e6),
        (0.999, 10.0, 1e5),
    ]:
        Phi = oscillator.state_transition(tau, **params(beta1=beta1, omega1=omega1))
        assert np.all(np.isfinite(Phi)), (beta1, omega1, tau)
    # undamped: a rotation, |det| = 1 at any tau
    Phi = oscillator.state_transition(1e6, **params(beta1=0.0, omega1=3.0))
    assert abs(np.linalg.det(Phi) - 1) < 1e-9


@pytest.mark.parametrize("beta1", [341.0, 1000.0])
def test_state_transition_strongly_overdamped_keeps_its_accuracy(beta1):
    """The same model, 8 ulps (1 + omega1 tau), for beta1 >> 1 (it is generous there:
    the problem's own condition is |lambda_slow| tau = omega1 tau / (2 beta1)). The
    closed form misses it by a factor ~13 (beta1 = 341) to ~25 (beta1 = 1000)."""
    worst = max(
        check_against(
            oscillator.state_transition(tau, **params(beta1=beta1, omega1=1.0)),
            expm_mp(beta1, 1.0, tau),
            8 * EPS * (1 + tau),
        )
        for tau in (30.0, 300.0, 1000.0)
    )
    assert worst <= 1


@pytest.mark.parametrize("function", ["state_transition", "excitation_response"])
def test_mpmath_twin_at_critical_damping(function):
    """beta1 = 1 exactly takes the critical branch (the under- and over-damped forms
    divide by sqrt(1 - beta1) = 0 there and must not be evaluated); numpy within a few
    ulps of the terms (all O(1) here: 24 ulps)."""
    with mpmath.workdps(30):
        got = getattr(mp_oscillator, function)(
            0.8, **params(beta1=1.0, omega1=1.3, alpha=1.0, Omega=2.0)
        )
    fast = getattr(oscillator, function)(0.8, **params(beta1=1.0, omega1=1.3, alpha=1.0, Omega=2.0))
    got = got.tolist() if isinstance(got, mpmath.matrix) else got
    assert np.allclose(
        np.asarray(fast, dtype=float).ravel(),
        [float(v) for v in np.ravel(np.array(got, dtype=object))],
        rtol=8 * EPS * 3,
        atol=0,
    )


@pytest.mark.parametrize("beta1", [0.0, 0.1, 0.7, 1.5, 4.0])
def test_state_transition_mpmath_twin_agrees(beta1, mp50):
    for tau in (0.3, 7.0, 80.0):
        fast = oscillator.state_transition(tau, **params(beta1=beta1, omega1=1.9))
        twin = mp_oscillator.state_transition(tau, **params(beta1=beta1, omega1=1.9))
        assert check_against(fast, twin, 8 * EPS * (1 + 1.9 * tau)) <= 1


# The response to the tangential excitation --------------------------------------------


def forced(p):
    b1, w1, a, W, ph = (p[k] for k in ("beta1", "omega1", "alpha_t", "Omega_t", "phase_t"))
    return lambda t, y: [y[1], a * W**2 * np.sin(W * t + ph) - 2 * b1 * w1 * y[1] - w1**2 * y[0]]


response_scale = H.response_scale


RESPONSE_CASES = [
    params(beta1=b, omega1=w, alpha_t=a, Omega_t=W, phase_t=ph)
    for b, w, a, W, ph in [
        (0.0, 1.3, 2.0, 0.5, 0.7),
        (0.0, 1.0, 2.0, 4.0, 0.0),
        (0.1, 1.0, 2.0, 4.0, 0.0),
        (0.1, 1.3, 0.5, 1.3, 1.1),
        (0.05, 2.0, 1.0, 2.0, -0.4),
        (1.0, 1.3, 2.0, 0.5, 0.3),
        (1.0, 2.0, 1.0, 2.0, 0.0),
        (3.0, 1.3, 2.0, 4.0, 2.0),
        (1 + 1e-6, 0.8, 1.0, 3.0, 0.5),
        (0.4, 10.0, 0.2, 9.0, 0.0),
    ]
]


@pytest.mark.parametrize(
    "p", RESPONSE_CASES, ids=lambda p: "b{beta1}-w{omega1}-W{Omega_t}".format(**p)
)
def test_excitation_response_is_the_motion_from_rest(p):
    """Against DOP853 at rtol = 1e-12, atol = 1e-14 x amplitude: its global error is the
    per-step tolerance accumulated over <~ 10^3 steps of a stable or neutral flow,
    <~ 1e-9 of the amplitude; plus the closed form's own error (response_scale)."""
    ts = np.linspace(0.0, 30.0, 121)
    X, V = oscillator.excitation_response(ts, **p)
    amp = response_scale(p, 0.0)
    assert np.all(np.abs([X[0], V[0]]) <= 8 * EPS * amp)  # from rest
    sol = solve_ivp(
        forced(p),
        (0, ts[-1]),
        [0.0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14 * amp.max(),
        t_eval=ts,
    )
    assert sol.success and sol.t.size == ts.size
    size = np.abs(sol.y).max(axis=1)
    tol = 1e-9 * size + 8 * EPS * response_scale(p, ts)
    assert np.all(np.abs(X - sol.y[0]) <= tol[0]) and np.all(np.abs(V - sol.y[1]) <= tol[1])


@pytest.mark.parametrize("p", [RESPONSE_CASES[2], RESPONSE_CASES[7]], ids=["under", "over"])
def test_excitation_response_against_a_30_digit_integration(p):
    """mpmath.odefun (Taylor series at 30 digits) as the reference: the closed form is
    within 8 ulps of its terms' scale (response_scale)."""
    with mpmath.workdps(30):
        b1, w1, a, W, ph = (
            mpmath.mpf(p[k]) for k in ("beta1", "omega1", "alpha_t", "Omega_t", "phase_t")
        )
        sol = mpmath.odefun(
            lambda t, y: [
                y[1],
                a * W**2 * mpmath.sin(W * t + ph) - 2 * b1 * w1 * y[1] - w1**2 * y[0],
            ],
            0,
            [0, 0],
        )
        for t in (0.5, 2.0, 6.0):
            ref = [float(v) for v in sol(t)]
            got = oscillator.excitation_response(t, **p)
            tol = 8 * EPS * response_scale(p, t)
            assert np.all(np.abs(np.array(got) - ref) <= tol), (t, got, ref)


def test_excitation_response_mpmath_twin_agrees(rng, mp50):
    for _ in range(20):
        p = params(
            beta1=float(rng.choice([0.0, rng.uniform(0, 1), rng.uniform(1, 5)])),
            omega1=rng.uniform(0.3, 3),
            alpha_t=rng.uniform(0.1, 3),
            Omega_t=rng.uniform(0, 6),
            phase_t=rng.uniform(-3, 3),
        )
        t = rng.uniform(0, 40)
        fast = oscillator.excitation_response(t, **p)
        twin = mp_oscillator.excitation_response(t, **p)
        tol = 8 * EPS * response_scale(p, t)
        assert np.all(np.abs(np.array(fast) - [float(v) for v in twin]) <= tol), p


def test_excitation_response_is_nan_only_at_undamped_resonance():
    """At beta1 = 0, Omega_t = omega1 the steady state does not exist (its amplitude
    divides by |omega1^2 - Omega_t^2 + 2i beta1 omega1 Omega_t| = 0): both entries are
    NaN at every t, t = 0 included. Next to it (damped, or detuned) they are finite."""
    t = np.array([0.0, 0.5, 10.0])
    X, V = oscillator.excitation_response(
        t, **params(beta1=0.0, omega1=1.3, alpha_t=1.0, Omega_t=1.3)
    )
    assert np.all(np.isnan(X)) and np.all(np.isnan(V))
    for beta1, Omega_t in [
        (1e-9, 1.3),
        (0.0, 1.3 * (1 + 1e-9)),
        (0.0, 1.3 * (1 - 1e-6)),
        (0.5, 1.3),
    ]:
        X, V = oscillator.excitation_response(
            t, **params(beta1=beta1, omega1=1.3, alpha_t=1.0, Omega_t=Omega_t)
        )
        assert np.all(np.isfinite(X)) and np.all(np.isfinite(V)), (beta1, Omega_t)
    b, W = np.meshgrid(np.linspace(0, 2, 41), np.linspace(0, 3, 61))
    X, V = oscillator.excitation_response(
        7.0, **params(beta1=b, omega1=1.5, alpha_t=1.0, Omega_t=W)
    )
    bad = ~np.isfinite(X) | ~np.isfinite(V)
    assert np.array_equal(bad, (b == 0) & (W == 1.5))


def test_excitation_response_next_to_resonance_loses_only_what_its_terms_cancel():
    """beta1 = 0, Omega_t = omega1 (1 + 1e-6): the response grows like t sin(omega1 t)
    while x_p and Phi x_p(0) are ~1e6 times larger and cancel. The error stays within
    8 ulps of those terms (response_scale), i.e. ~1e-9 of the response here."""
    p = params(beta1=0.0, omega1=1.3, alpha_t=1.0, Omega_t=1.3 * (1 + 1e-6), phase_t=0.3)
    ts = np.linspace(0, 20, 41)
    X, V = oscillator.excitation_response(ts, **p)
    sol = solve_ivp(
        forced(p), (0, ts[-1]), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=ts
    )
    size = np.abs(sol.y).max(axis=1)
    tol = 1e-9 * size + 8 * EPS * response_scale(p, ts)
    assert np.all(np.abs(X - sol.y[0]) <= tol[0]) and np.all(np.abs(V - sol.y[1]) <= tol[1])
    assert np.all(tol <= 1e-6 * size)  # still 6 digits


@pytest.mark.parametrize(
    "mode,contact",
    [("slip_back", "hertz_damp"), ("slip_forward", "kelvin_voigt"), ("flight", "hertz_damp")],
)
def test_slip_motion_is_free_plus_forced_plus_contact_response(mode, contact):
    """Between switches the tangential motion of a slip mode s is the superposition
    Phi(t) x1(0) + excitation_response(t) - mu_s s z(t), z the response to the contact
    force integrated beside the normal equation (hybrid.response_field); in flight
    without the last term. Reference: the mode's vector_field integrated directly.
    Both integrations by DOP853 at rtol = 1e-12, atol = 1e-12: each within ~1e-10 of the
    states' size over these 3 s; tolerance 1e-9 of it."""
    from beltmdsm.generated.parameters import BASE

    p = dict(BASE, alpha=0.5, phase_t=0.3)
    code = hybrid.MODE_CODES[mode]
    x0 = [0.4, -1.2 if code != 1 else p["Vb"] + 2.0, 11.0 if code != 2 else -0.5, 0.2]
    T = 3.0
    full = solve_ivp(
        lambda t, x: hybrid.vector_field(t, *x, code, contact=contact, **p),
        (0, T),
        x0,
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        dense_output=True,
    )
    resp = solve_ivp(
        lambda t, y: hybrid.response_field(t, *y, code, contact=contact, **p),
        (0, T),
        [0.0, 0.0, x0[2], x0[3]],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        dense_output=True,
    )
    assert full.success and resp.success
    s = code if code in (-1, 1) else 0
    for t in (0.5, 1.7, 3.0):
        x, y = full.sol(t), resp.sol(t)
        Phi = oscillator.state_transition(t, **p)
        parts = (
            Phi @ x0[:2] + np.array(oscillator.excitation_response(t, **p)) - p["mu_s"] * s * y[:2]
        )
        size = max(1.0, np.abs(x).max(), np.abs(y).max())
        assert np.abs(x[:2] - parts).max() <= 1e-9 * size, (t, x[:2], parts)
        # the generated superposition, from a switch at t0 = 0.5 where the responses
        # are not at rest
        t0 = 0.5
        start = (*full.sol(t0)[:2], *oscillator.excitation_response(t0, **p), *resp.sol(t0)[:2])
        zf, vf = oscillator.excitation_response(t, **p)
        got = oscillator.tangential_state(t - t0, *start, zf, vf, *y[:2], s, **p)
        assert np.abs(x[:2] - np.array(got)).max() <= 1e-9 * size, (t, x[:2], got)
        assert np.abs(x[2:] - y[2:]).max() <= 1e-9 * size  # the same normal motion
        assert np.abs(y[:2]).max() > 1e-3 or s == 0 or contact == "kelvin_voigt"


@pytest.mark.parametrize("beta1", [0.3, 1.0, 2.5])
def test_tangential_state_is_its_parts_and_its_mpmath_twin(beta1):
    """Phi (x0 - f0) + f with f = zf - mu_s sgn z, typed here from `state_transition`;
    and the mpmath twin at 30 digits (the critical branch at beta1 = 1). A few ulps of
    the terms: (1 + omega1 tau) |Phi| times the free part, plus the forced part."""
    p = params(beta1=beta1, omega1=1.3)
    tau, x0, f0, z0, f, z = 2.1, (0.4, -1.2), (0.3, -0.7), (1.1, 0.2), (-0.2, 0.9), (0.8, -0.5)
    for sgn in (-1.0, 0.0, 1.0):
        args = (tau, *x0, *f0, *z0, *f, *z, sgn)
        got = np.array(oscillator.tangential_state(*args, **p))
        m = p["mu_s"] * sgn
        free = np.subtract(x0, np.subtract(f0, np.multiply(m, z0)))
        Phi = oscillator.state_transition(tau, **p)
        ref = Phi @ free + np.subtract(f, np.multiply(m, z))
        scale = (1 + 1.3 * tau) * np.abs(Phi).max() * np.abs(free).sum() + 2
        assert np.abs(got - ref).max() <= 16 * EPS * scale
        with mpmath.workdps(30):
            twin = [float(v) for v in mp_oscillator.tangential_state(*args, **p)]
        assert np.abs(got - twin).max() <= 16 * EPS * scale


def test_tangential_state_refuses_a_friction_law_that_depends_on_the_speed():
    from beltmdsm.generated._support import Unsupported

    with pytest.raises(Unsupported, match="no superposition"):
        oscillator.tangential_state(1.0, *[0.0] * 10, -1.0, friction="stribeck", **BASE)
    with pytest.raises(Unsupported, match="stribeck"):
        oscillator.bind_tangential_state(friction="stribeck", **BASE)
