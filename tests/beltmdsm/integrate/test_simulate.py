"""The event-driven simulation of Eq. (4): accuracy, regimes, energy balance, stick, flight."""

import numpy as np
import pytest

from beltmdsm.generated import dynamics
from beltmdsm.integrate.switching import Mode
from beltmdsm.model import Model
from beltmdsm.run.summary import REGIMES
from beltmdsm.settings import SolverSettings
from beltmdsm.simulation import simulate

FLIGHT, SLIP_BACK, SLIP_FORWARD, STICK = Mode.FLIGHT, Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK

T_SHORT = 150.0


@pytest.fixture(scope="module")
def reversing_tight():
    """Vb = 4 at the base set (reversals every cycle) at a far tighter tolerance."""
    return simulate(Model(Vb=4.0), solver="events", rtol=1e-12, atol=1e-12, t_end=T_SHORT)


def _state_error(a, b):
    return np.abs(a.y - b.y).max()


def test_event_located_run_converges_to_a_far_tighter_run(reversing_tight):
    ref = reversing_tight
    assert ref.summary.n_reversals > 10
    errs = []
    for tol in (1e-8, 1e-10):
        run = simulate(Model(Vb=4.0), solver="events", rtol=tol, atol=tol, t_end=T_SHORT)
        # the same switches, located at the same times
        assert [k for _, k, _ in run.events] == [k for _, k, _ in ref.events]
        times = np.array([e[0] for e in run.events]) - np.array([e[0] for e in ref.events])
        assert np.abs(times).max() < 1e3 * tol
        errs.append(_state_error(run, ref))
    # error falls with the tolerance: no O(1) error from a switch stepped over
    assert errs[1] < errs[0] / 10
    assert errs[1] < 1e3 * 1e-10


def test_superposition_agrees_with_the_event_located_reference(reversing_tight):
    fast = simulate(Model(Vb=4.0), solver="superposition", t_end=T_SHORT)
    assert fast.solver_used == "superposition"
    assert [k for _, k, _ in fast.events] == [k for _, k, _ in reversing_tight.events]
    # spline grid 0.005 s: (omega h)^4 / 384 of the signal, about 1e-8
    assert _state_error(fast, reversing_tight) < 1e-6
    assert fast.summary.peak_omega1 == pytest.approx(reversing_tight.summary.peak_omega1, rel=1e-6)


@pytest.mark.parametrize("solver", ["events", "superposition"])
def test_frictionless_run_matches_the_forced_linear_oscillator(solver):
    """mu_s = 0: X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = alpha Omega^2 sin(Omega t)."""
    sim = simulate(Model(mu_s=0.0), solver=solver, t_end=400.0)
    p = sim.params
    amp = (
        p["alpha"]
        * p["Omega"] ** 3
        / abs(p["omega1"] ** 2 - p["Omega"] ** 2 + 2j * p["beta1"] * p["omega1"] * p["Omega"])
    )
    assert sim.summary.peak_Omega == pytest.approx(amp, rel=1e-6)
    assert sim.summary.peak_omega1 < 1e-6 * amp


@pytest.mark.parametrize("solver", ["events", "superposition"])
@pytest.mark.parametrize(
    "case, regime",
    [
        (dict(Vb=12.0), "continuous_sliding"),
        (dict(Vb=4.0), "sliding_with_reversals"),
        # small excitation at a low belt speed: the excitation cannot break the friction
        # limit on its own, the mass rides with the belt and slips back
        (dict(Vb=0.1, alpha=0.05), "stick_slip"),
    ],
)
def test_regimes_and_energy_balance(solver, case, regime):
    sim = simulate(case, solver=solver, t_end=T_SHORT)
    s = sim.summary
    assert s.regime == regime
    # against the independent generated power terms: quadrature and integration error only
    assert s.energy_residual < 1e-8
    e = s.energy
    assert abs(e.imbalance) < 1e-8 * (abs(e.work_input) + abs(e.work_viscous))
    win = sim.window
    vr = sim.y[1, win] - sim.params["Vb"]
    if regime == "continuous_sliding":
        assert s.n_switches == 0 and vr.max() < 0
    if regime == "sliding_with_reversals":
        assert vr.max() > 0 > vr.min() and s.n_sticks == 0
    if regime == "stick_slip":
        assert s.n_sticks > 0 and s.time_fraction["stick"] > 0


def test_sticking_holds_the_mass_within_the_friction_limit():
    sim = simulate(Model(Vb=0.1, alpha=0.05), solver="events", t_end=T_SHORT)
    tr, p = sim.trajectory, sim.params
    sticks = [s for s in tr.segments if s.mode == STICK]
    assert sticks
    for seg in sticks:
        t = np.linspace(seg.t0, seg.t1, 50)
        y = tr.state(t)
        assert np.all(y[1] == p["Vb"])  # no chatter: Vr is exactly 0
        Fn, friction = tr.forces(t, y)
        a_free = dynamics.rhs_branch(t, *y, 0.0, **p)[..., 1]
        assert np.all(np.abs(a_free) <= p["mu_s"] * Fn * (1 + 1e-9) + 1e-12)
        np.testing.assert_allclose(friction, -a_free)
    # each stick ends where the limit is reached, and the mass slips along a_free
    for t, kind, mode in sim.events:
        if kind == "unstick":
            y = tr.state(np.array([t]))
            Fn = dynamics.normal_force(y[2], y[3], **p)[0]
            a = dynamics.rhs_branch(t, *y[:, 0], 0.0, **p)[1]
            assert abs(a) == pytest.approx(p["mu_s"] * Fn, rel=1e-8)
            assert mode == (SLIP_FORWARD if a > 0 else SLIP_BACK)


@pytest.mark.parametrize("solver", ["events", "superposition"])
@pytest.mark.parametrize("contact, extra", [("hertz_damp", {}), ("kelvin_voigt", {"beta2": 0.3})])
def test_contact_loss_is_detected_and_the_run_continues_in_flight(contact, extra, solver):
    # a stiff contact (omega2 = 5): the normal excitation alpha Omega^2 = 32 m/s^2 > g
    # lifts the mass
    sim = simulate(
        Model(omega2=5.0, contact=contact, **extra), t_end=60.0, t_discard=20.0, solver=solver
    )
    s = sim.summary
    assert sim.solver_used == solver  # flight is a mode of both integrators
    assert s.regime == "contact_loss" and s.n_contact_losses > 0
    assert sim.status == "done" and sim.trajectory.t_end == 60.0
    flights = [seg for seg in sim.trajectory.segments if seg.mode == FLIGHT]
    for seg in flights:
        t = np.linspace(seg.t0, seg.t1, 20)[1:-1]
        y = sim.trajectory.state(t)
        assert np.all(y[2] < 0)
        Fn, friction = sim.trajectory.forces(t, y)
        assert np.all(Fn == 0) and np.all(friction == 0)
    assert s.energy_residual < 1e-8


def test_contact_loss_can_stop_the_run_with_a_message():
    sim = simulate(Model(omega2=5.0), on_contact_loss="stop", t_end=60.0)
    assert sim.status == "contact_lost"
    assert "contact lost" in sim.message and "t =" in sim.message
    assert sim.trajectory.t_end < 60.0
    assert sim.summary.regime == "contact_loss"
    assert sim.trajectory.state(np.array([sim.trajectory.t_end]))[2, 0] == pytest.approx(
        0, abs=1e-12
    )


def test_negative_normal_force_is_reported_not_clipped():
    sim = simulate(Model(Vb=12.0), t_end=100.0)
    p = sim.params
    Fn = dynamics.normal_force(sim.y[2], sim.y[3], **p)
    assert sim.summary.min_normal_force == Fn.min()
    assert (Fn < 0).any() == (sim.summary.tension_fraction > 0)
    # friction follows Eq. (2) with the signed normal force
    np.testing.assert_allclose(sim.friction, p["mu_s"] * Fn)


def test_summary_keys_and_regime_names():
    s = simulate(Model(Vb=8.0), t_end=100.0).summary
    for key in ("regime", "peak_omega1", "peak_Omega", "energy_residual", "n_switches", "wall_s"):
        assert key in s.as_dict()
    assert s.regime in REGIMES


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"rtol": 0}, "rtol"),
        ({"solver": "rk4"}, "solver"),
        ({"t_end": 10.0, "t_discard": 20.0}, "t_discard"),
        ({"on_contact_loss": "ignore"}, "on_contact_loss"),
        ({"model": {"Vb": -2.0}}, "Vb"),
    ],
)
def test_bad_settings_raise_valueerror_naming_them(kwargs, name):
    with pytest.raises(ValueError, match=name):
        simulate(**kwargs)


def test_settings_object_is_used():
    s = SolverSettings(solver="events", t_end=50.0, dt=0.05)
    sim = simulate(settings=s)
    assert sim.solver_used == "events" and sim.t[-1] == 50.0 and sim.t[1] == 0.05


@pytest.mark.slow
def test_omega1_peak_at_vb4_and_not_at_vb12_as_in_fig2b():
    """The paper's Fig. 2b statement, on full 1000 s runs."""
    on = simulate(Model(Vb=4.0)).summary
    off = simulate(Model(Vb=12.0)).summary
    assert on.omega1_peak_present and not off.omega1_peak_present
    assert max(on.energy_residual, off.energy_residual) < 1e-8


@pytest.mark.parametrize(
    "excitation",
    [
        dict(Omega_t=6.0, Omega_n=4.0),  # Fig. 14b
        dict(phase_t=np.pi / 2),
    ],
)  # Fig. 15
def test_general_excitation_agrees_between_integrators(excitation):
    ref = simulate(
        Model(Vb=3.0, **excitation), solver="events", rtol=1e-12, atol=1e-12, t_end=100.0
    )
    fast = simulate(Model(Vb=3.0, **excitation), solver="superposition", t_end=100.0)
    assert fast.solver_used == "superposition"
    assert _state_error(fast, ref) < 1e-6
    assert ref.summary.energy_residual < 1e-8 and fast.summary.energy_residual < 1e-8
    if excitation.get("Omega_n", 4.0) != excitation.get("Omega_t", 4.0):
        assert fast.summary.peak_Omega_n == pytest.approx(ref.summary.peak_Omega_n, rel=1e-6)
