"""Phase-locked responses (shooting on the k-fold map, lock detection) against independent
references.

References: the event-driven integrator (`beltmdsm.integrate.events`, not the
superposition the period map is built on) for the k-fold map and its finite
differences; the simulated runs of `beltmdsm.simulation.simulate` (started on the
computed orbit); stroboscopic samples of known sequences for the lock detection.
"""

import math

import numpy as np
import pytest

from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import Model
from beltmdsm.periodic import locked as L
from beltmdsm.periodic.closed_form import TangentialMap
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.newton import fixed_point
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.settings import SolverSettings
from beltmdsm.simulation import simulate

# Newton stops at 1e-11 of the state's scale; the event-driven run at rtol = atol =
# 1e-13 over k periods adds ~k 1e-12 per unit of state: the orbit closes to ~1e-10.
PERIODIC = 1e-9


def _events_flow(model, y0, t_end):
    settings = SolverSettings(t_end=t_end, rtol=1e-13, atol=1e-13, dt=t_end / 100)
    run = integrate_events(model, settings, y0=y0)
    assert run.status == "done"
    return run.trajectory.state(np.array([t_end]))[:, 0]


@pytest.mark.parametrize(
    ("case", "k"), [(dict(Vb=5.0), 4), (dict(Vb=6.3), 4), (dict(Vb=12.0, Omega=6.0), 6)]
)
def test_the_locked_orbit_closes_under_the_other_integrator_and_its_multipliers_are_its_flows(
    case, k
):
    resp = periodic_response(case, periods=k)
    assert resp.periods == k
    assert resp.period == pytest.approx(k * 2 * math.pi / resp.model["Omega"])
    m, kT, x0 = resp.model, resp.period, resp.state0
    np.testing.assert_allclose(
        _events_flow(m, x0, kT), x0, rtol=0, atol=PERIODIC * (1 + np.abs(x0).max())
    )
    J = np.zeros((2, 2))
    for j in range(2):
        h = 1e-6 * max(1.0, abs(x0[j]))
        e = np.zeros(4)
        e[j] = h
        J[:, j] = (_events_flow(m, x0 + e, kT)[:2] - _events_flow(m, x0 - e, kT)[:2]) / (2 * h)
    # central differences (h = 1e-6): truncation ~1e-12 times the curvature, rounding of
    # the 1e-13 runs over k periods ~1e-13 k / h = 1e-6; the product of k one-period
    # Jacobians with the saltation matrices of every reversal must agree to that
    np.testing.assert_allclose(resp.monodromy_tangential, J, rtol=0, atol=2e-5)
    mu_fd = np.sort(np.abs(np.linalg.eigvals(J)))
    mu = np.sort(np.abs(np.linalg.eigvals(resp.monodromy_tangential)))
    np.testing.assert_allclose(mu, mu_fd, rtol=0, atol=2e-5)


def test_floquet_of_k_periods_keeps_the_keys_and_raises_the_normal_block_to_the_power_k():
    one, four = floquet(Model(Vb=5.0)), floquet(Model(Vb=5.0), periods=4)
    assert set(one.as_dict()) == set(four.as_dict())
    assert one.as_dict()["periods"] == 1 and four.as_dict()["periods"] == 4
    np.testing.assert_allclose(
        np.sort(np.abs(four.multipliers[2:])),
        np.sort(np.abs(one.multipliers[2:])) ** 4,
        rtol=1e-9,
        atol=1e-15,
    )
    # the 4T orbit is stable where the T-periodic one is not (issue 20)
    assert four.stable and not one.stable
    assert four.n_reversals == 4 and four.period == pytest.approx(4 * one.period)


def test_a_run_started_on_the_stable_locked_orbit_stays_on_it():
    resp = periodic_response(Model(Vb=5.0), periods=4)
    T = resp.period / 4
    sim = simulate(resp.model, y0=resp.state0, t_end=200 * T, t_discard=10 * T)
    phases = [resp.state0[:2]] + [
        sim.trajectory.state(np.array([j * T]))[:2, 0] for j in range(1, 4)
    ]
    samples = sim.trajectory.state(T * np.arange(0, 200))[:2].T
    # every sample is the phase it should be, to the two integrators' difference
    scale = 1 + np.abs(resp.state0).max()
    for n, y in enumerate(samples):
        np.testing.assert_allclose(y, phases[n % 4], rtol=0, atol=1e-7 * scale)


def test_lock_detection_on_known_sequences():
    rng = np.random.default_rng(1)
    phases = rng.normal(size=(3, 2))
    period3 = np.array([phases[n % 3] for n in range(200)]) + 1e-9 * rng.normal(size=(200, 2))
    assert L.stroboscope(period3, "three").candidate == 3
    # an irrational rotation on an ellipse: not locked, on a closed curve, its number
    rho = (math.sqrt(5) - 1) / 2 - 0.5
    angle = 2 * math.pi * rho * np.arange(300)
    circle = np.column_stack([2 * np.cos(angle), 0.5 * np.sin(angle)])
    s = L.stroboscope(circle, "torus")
    assert s.candidate is None
    evidence = L.NotLocked.of(s)
    assert evidence.closed_curve and abs(evidence.dimension - 1) < 0.2
    assert evidence.rotation_number == pytest.approx(rho, abs=1e-3)
    cloud = L.NotLocked.of(L.stroboscope(rng.normal(size=(300, 2)), "cloud"))
    assert not cloud.closed_curve
    with pytest.raises(ValueError):
        L.stroboscope(np.zeros((5, 2)), "short")


def test_a_response_of_the_wrong_period_is_refused_with_what_the_attractor_does():
    with pytest.raises(NoPeriodicResponse, match="locks at 4 periods"):
        periodic_response(Model(Vb=5.0), periods=3)
    # just below the band the attractor rotates on a closed curve (docs/modelling.md)
    with pytest.raises(NoPeriodicResponse, match="not locked .* closed curve"):
        periodic_response(Model(Vb=3.5), periods=4)
    for bad in (0, 2.5):
        with pytest.raises(ValueError, match="periods"):
            periodic_response(Model(Vb=5.0), periods=bad)


def test_fixed_point_of_the_one_period_map_is_floquets_periodic_response():
    f = floquet(Model(Vb=4.0))
    pmap = TangentialMap(f.response.model)
    point = fixed_point(pmap, f.response.state0[:2] + 1e-3)
    np.testing.assert_allclose(point.state, f.response.state0[:2], rtol=0, atol=1e-10)
    np.testing.assert_allclose(point.image.jacobian, f.response.monodromy_tangential, atol=1e-9)
    np.testing.assert_allclose(
        pmap.fixed_multipliers(), f.response._engine.orbit.multipliers, rtol=1e-12
    )
