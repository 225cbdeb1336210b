"""Floquet analysis of the periodic response against independent references.

References: the event-driven integrator (`beltmdsm.events`, another integrator than
the superposition the period map uses) for periodicity and for finite differences of
the flow; the damped oscillator's own multipliers typed by hand where the friction
never reverses; scipy's solve_ivp on the normal equation for the normal orbit.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from beltmdsm.generated import dynamics
from beltmdsm.integrate.events import integrate_events
from beltmdsm.integrate.normal import NormalMotion
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.normal_orbit import normal_orbit
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.settings import SolverSettings
from beltmdsm.simulation import simulate
from beltmdsm.starts.forced import periodic_start

# Newton stops at 1e-11 of the state's scale; the event-driven run at rtol = atol =
# 1e-12 over one period adds a few 1e-12: the orbit closes to ~1e-10 there.
PERIODIC = 1e-9


def test_normal_orbit_is_periodic_and_its_monodromy_is_the_flow_jacobian():
    m = Model()
    orbit = normal_orbit(m)
    T = orbit.period
    rhs = dynamics.bind_normal_rhs(backend="python", **m.params)

    def flow(x):
        sol = solve_ivp(lambda t, y: rhs(t, *y), (0, T), x, method="DOP853", rtol=1e-13, atol=1e-13)
        return sol.y[:, -1]

    x0 = orbit.state0
    np.testing.assert_allclose(flow(x0), x0, rtol=0, atol=1e-10)
    J = np.zeros((2, 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = 1e-5
        J[:, j] = (flow(x0 + e) - flow(x0 - e)) / 2e-5
    # central differences: O(h^2) of the flow's curvature plus 1e-13/h rounding
    np.testing.assert_allclose(orbit.monodromy, J, rtol=0, atol=1e-7)
    # the overdamped normal motion: both multipliers well inside the unit circle
    assert np.all(np.abs(orbit.multipliers) < 0.9)
    # kept per normal parameter set: the tangential parameters, mu_s and Vb are not in
    # the normal equation (a map over beta1 computes one normal orbit)
    assert normal_orbit(Model(beta1=0.3, omega1=2.0, mu_s=0.2, Vb=7.0)) is orbit
    assert normal_orbit(Model(omega2=0.6)) is not orbit


@pytest.mark.parametrize(
    "laws",
    [dict(alpha_n=20.0), dict(alpha_n=5.0, tension="clipped")],
    ids=["lift-off and touchdown", "separation, lift-off and touchdown"],
)
def test_normal_orbit_that_loses_contact_has_the_monodromy_of_its_flow(laws):
    """Across a touchdown or a lift-off the Hertz force's Jacobian goes like sqrt(X2):
    one Runge-Kutta step of the variational equation there was off by 2.3e-6 (of 13.9)
    at alpha_n = 20; the steps next to those switches are now carried in graded pieces
    (beltmdsm.periodic.variational.graded_pieces). Reference: central differences of
    the package's normal motion, integrated at 1e-13 with its switches located."""
    m = Model(**laws)
    orbit = normal_orbit(m)
    assert {s for _, _, _, s in orbit.switches} >= {"penetration"}
    T = orbit.period

    def flow(x):
        return NormalMotion(m, T, 1e-13, 1e-13, x).at(T)[2:]

    x0, h = orbit.state0, 1e-5
    J = np.column_stack([(flow(x0 + e) - flow(x0 - e)) / (2 * h) for e in h * np.eye(2)])
    # the differences agree with each other to 3e-9 at h = 1e-4 and 1e-5 (truncation
    # and the flow's rounding over h): 2e-8 of the matrix's scale
    np.testing.assert_allclose(orbit.monodromy, J, rtol=0, atol=2e-8 * np.max(np.abs(J)))


@pytest.mark.parametrize(
    "case",
    [
        dict(Vb=4.0),
        dict(Vb=6.0),
        dict(Vb=2.0),
        dict(Vb=5.0, Omega=10.0),
        dict(Vb=4.0, tension="clipped"),
        dict(Vb=3.0, contact="kelvin_voigt", omega2=0.5, beta2=3.0),
    ],
)
def test_periodic_response_closes_under_the_other_integrator_and_its_monodromy_is_the_flow_jacobian(
    case,
):
    resp = periodic_response(case)
    T, x0 = resp.period, resp.state0
    settings = SolverSettings(t_end=T, rtol=1e-13, atol=1e-13, dt=T / 100)

    def flow(y0):
        run = integrate_events(resp.model, settings, y0=y0)
        assert run.status == "done"
        return run.trajectory.state(np.array([T]))[:, 0]

    np.testing.assert_allclose(flow(x0), x0, rtol=0, atol=PERIODIC * (1 + np.abs(x0).max()))
    J = np.zeros((4, 4))
    for j in range(4):
        h = 1e-6 * max(1.0, abs(x0[j]))
        e = np.zeros(4)
        e[j] = h
        J[:, j] = (flow(x0 + e) - flow(x0 - e)) / (2 * h)
    # the tangential block by the closed forms and saltation matrices, against central
    # differences of the other integrator's flow (h = 1e-6: truncation ~1e-12 times the
    # second derivative, rounding 1e-13/h = 1e-7): dropping a saltation matrix changes
    # entries by O(1)
    np.testing.assert_allclose(resp.monodromy_tangential, J[:2, :2], rtol=0, atol=1e-6)
    np.testing.assert_allclose(resp.monodromy_normal, J[2:, 2:], rtol=0, atol=1e-6)
    # one-way coupling: zero up to the differences' rounding, 1e-13 / h = 1e-7
    np.testing.assert_allclose(J[2:, :2], 0, atol=1e-7)
    np.testing.assert_allclose(resp.monodromy[:2, 2:], J[:2, 2:], rtol=1e-4, atol=1e-5)


def test_without_reversals_the_multipliers_are_the_damped_oscillators():
    """Sliding throughout, the tangential motion is the linear oscillator: its
    multipliers over one period are exp(lambda T), lambda = -beta1 omega1 +- i omega1
    sqrt(1 - beta1^2)."""
    for case in (
        dict(Vb=12.0),
        dict(Vb=12.0, beta1=0.3, omega1=1.7),
        dict(Vb=4.0, tension="clipped"),
    ):
        f = floquet(case)
        p = f.response.model.params
        assert f.n_reversals == 0 and f.n_sticks == 0
        lam = complex(-p["beta1"] * p["omega1"], p["omega1"] * math.sqrt(1 - p["beta1"] ** 2))
        expected = sorted(
            [np.exp(lam * f.period), np.exp(lam.conjugate() * f.period)], key=lambda z: z.imag
        )
        got = sorted(f.multipliers[:2], key=lambda z: z.imag)
        np.testing.assert_allclose(got, expected, rtol=1e-12)
        normal = np.log(np.abs(f.multipliers[2:]).max()) / f.period
        assert f.growth_rate == pytest.approx(max(-p["beta1"] * p["omega1"], normal), rel=1e-9)


def test_the_paper_point_and_the_issue_examples():
    unstable = floquet(Model(Vb=6.0))
    assert not unstable.stable and unstable.max_abs_multiplier > 1
    assert unstable.n_reversals == 2
    # the critical pair oscillates near omega1 (= 1 rad/s at the base set)
    assert 0.8 < unstable.frequency < 1.2
    # Omega = 6, Vb = 12: the periodic sliding response is stable (issue 13)
    stable = floquet(Model(Vb=12.0, Omega=6.0))
    assert stable.stable and stable.n_reversals == 0
    # the verdict text of the band and the validation
    assert (unstable.verdict, stable.verdict) == ("unstable", "stable")
    assert dataclasses.replace(stable, stable=None).verdict == "grazing"


def test_a_stick_phase_makes_the_tangential_monodromy_singular():
    f = floquet(Model(Vb=0.1, alpha=0.05))
    assert f.n_sticks >= 1
    assert abs(np.linalg.det(f.response.monodromy_tangential)) < 1e-12
    assert min(abs(f.multipliers[:2])) < 1e-12


def test_clipped_contact_is_stable_wherever_the_response_exists():
    """With a contact that cannot pull the difference of two tangential motions loses
    energy (derive/contraction.py): every multiplier of the tangential block is inside
    the unit circle."""
    for case in (dict(), dict(Omega=6.0), dict(Omega=10.0), dict(beta1=0.05)):
        for Vb in (1.0, 4.0, 8.0):
            f = floquet(Model(Vb=Vb, tension="clipped", **case))
            assert f.stable and np.all(np.abs(f.multipliers[:2]) < 1)


def test_a_run_started_on_the_perturbed_periodic_response_follows_the_verdict():
    """Unstable (Vb = 6): the perturbation grows into the omega1 oscillation; stable
    (Omega = 6, Vb = 12): it decays although a run from rest finds the oscillation."""
    unstable = Model(Vb=6.0)
    grows = simulate(unstable, y0=periodic_start(unstable), t_end=300.0).summary
    assert grows.omega1_peak_present
    stable = Model(Vb=12.0, Omega=6.0)
    decays = simulate(stable, y0=periodic_start(stable), t_end=300.0).summary
    assert decays.omega1_peak_present is False

    with pytest.raises(TypeError, match="periodic_start"):
        simulate(Model(Vb=6.0), start="periodic")


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="tension"):
        floquet(Model(tension="loose"))
    with pytest.raises(ValueError, match="incommensurate"):
        floquet(Model(Omega_t=4.0 * math.sqrt(2), Omega_n=4.0))
    with pytest.raises(ValueError, match="perturbation"):
        periodic_start(Model(), float("nan"))
    with pytest.raises(ValueError, match="'mu_s'"):
        floquet(Model(mu_s=-1.0))
