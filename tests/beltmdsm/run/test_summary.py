"""beltmdsm.run: what a run can tell is bounded by its tolerances.

The noise floor and the energy bound are error models; these tests check each against
what runs at a far tighter tolerance show, so that a bound that stops holding fails.
"""

import numpy as np
import pytest

from beltmdsm.model import Model
from beltmdsm.run import resolution, tolerances
from beltmdsm.simulation import simulate


@pytest.mark.parametrize("tol", [1e-6, 1e-8])
def test_the_noise_floor_bounds_what_the_tolerance_changes_in_the_peaks(tol):
    # base set, Vb = 4 (reversing, the omega1 peak present) and Vb = 1 (absent)
    for Vb in (4.0, 1.0):
        ref = simulate(Model(Vb=Vb), rtol=1e-12, atol=1e-12, t_end=300.0).summary
        run = simulate(Model(Vb=Vb), rtol=tol, atol=tol, t_end=300.0).summary
        assert abs(run.peak_omega1 - ref.peak_omega1) < run.noise_floor
        assert abs(run.peak_Omega - ref.peak_Omega) < run.noise_floor


def test_without_excitation_every_peak_is_below_the_floor_at_every_tolerance():
    for tol in (1e-4, 1e-7, 1e-10, 1e-12):
        s = simulate(Model(alpha=0.0), rtol=tol, atol=tol, t_end=300.0).summary
        assert max(s.peak_omega1, s.peak_Omega) < s.noise_floor
        assert s.forced_peak is False and s.omega1_peak_present is False


def test_the_noise_floor_grows_with_the_tolerances_and_the_window():
    y = np.full((4, 1000), 10.0)
    v = np.full(1000, 2.0)
    base = tolerances.noise_floor(1e-10, 1e-10, y, v)
    assert tolerances.noise_floor(1e-8, 1e-10, y, v) > 50 * base
    assert tolerances.noise_floor(1e-10, 1e-8, y, v) > 5 * base
    assert np.isnan(tolerances.noise_floor(1e-10, 1e-10, y[:, :0], v[:0]))


def test_the_energy_bound_follows_the_tolerance_between_its_floor_and_cap():
    b = tolerances.energy_bound
    assert b(1e-10, 1e-10) == tolerances.ENERGY_RESIDUAL_FLOOR
    assert b(1e-7, 1e-10) == pytest.approx(tolerances.ENERGY_RESIDUAL_FACTOR * 1e-7)
    assert b(1e-10, 1e-7) == b(1e-7, 1e-10)
    assert b(0.1, 1e-10) == tolerances.ENERGY_RESIDUAL_MAX
    # where the work is of the order of the energy's integration error (nothing
    # moves), the imbalance is held to that error, |imbalance| <= 64 tol (E + W),
    # not to the cap: a mass at rest closes its balance (issue 36, item 11)
    f = tolerances.ENERGY_RESIDUAL_FACTOR
    at_rest = b(1e-10, 1e-10, energy_level=100.0, work_total=1e-11)
    assert at_rest * 1e-11 == pytest.approx(f * 1e-10 * (100.0 + 1e-11))
    assert b(1e-10, 1e-10, energy_level=100.0, work_total=0.0) == np.inf
    # a run that moves stays under the cap however small its work against its energy
    assert b(1e-6, 1e-6, energy_level=100.0, work_total=1.0) == tolerances.ENERGY_RESIDUAL_MAX


@pytest.mark.parametrize("solver", ["events", "superposition"])
@pytest.mark.parametrize("tension", ["allowed", "clipped"])
def test_runs_at_usual_tolerances_close_their_energy_balance(solver, tension):
    for kw in ({"Vb": 4.0}, {"Vb": 1.0, "Omega": 10.0}, {"Vb": 4.0, "omega2": 1.5}):
        for tol in (1e-6, 1e-10):
            s = simulate(
                Model(tension=tension, **kw), rtol=tol, atol=tol, t_end=300.0, solver=solver
            ).summary
            assert s.energy_ok, (kw, tol, s.energy_residual, s.energy_bound)
            assert s.warnings == ()


def test_a_stable_periodic_response_does_not_make_a_growing_peak_unresolved():
    # Vb = 5 is inside the Floquet band: the periodic response is unstable, the
    # perturbation grows into the omega1 vibration, which is present and resolved
    from beltmdsm.model import Model
    from beltmdsm.starts.forced import periodic_start

    model = Model(Vb=5.0)
    s = simulate(model, y0=periodic_start(model), t_end=400.0).summary
    assert s.resolved and s.omega1_peak_present


@pytest.mark.parametrize("beta1", [0.05, 0.5, 2.0])
def test_the_free_decay_rate_is_the_slower_root_of_the_tangential_oscillator(beta1):
    from beltmdsm.model import Model

    w1 = 1.3
    rate = resolution.free_decay_rate(Model(beta1=beta1, omega1=w1))
    # the roots of l^2 + 2 beta1 w1 l + w1^2: -beta1 w1 (+-) w1 sqrt(beta1^2 - 1)
    slower = -beta1 * w1 + (w1 * np.sqrt(beta1**2 - 1) if beta1 > 1 else 0.0)
    assert rate == pytest.approx(slower, rel=1e-13)


def test_under_excitation_a_speed_dependent_friction_decays_at_the_floquet_rate():
    import math

    from beltmdsm.model import Model
    from beltmdsm.periodic.floquet import floquet
    from beltmdsm.settings import SolverSettings

    settings = SolverSettings()
    # Stribeck (mu_k = 0.1, v_s = 3) at 4.5 m/s: steady sliding grows (its free rate is
    # > 0), the forced periodic response attracts; a disturbance of the run decays at
    # the latter's rate (docs/stribeck.md: +0.0094/s against -0.076/s)
    m = Model(friction="stribeck", mu_k=0.1, v_s=3.0, Vb=4.5)
    f = floquet(m)
    sigma, what = resolution._transient_rate(m, settings, forced=True)
    assert resolution.free_decay_rate(m) > 0 > sigma
    assert sigma == pytest.approx(math.log(f.max_abs_multiplier) / f.period, rel=1e-12)
    assert "Floquet" in what
    # without excitation, and under Coulomb friction, the free rate is the rate
    assert resolution._transient_rate(m, settings, forced=False)[0] == resolution.free_decay_rate(m)
    coulomb = Model(Vb=4.5)
    assert resolution._transient_rate(coulomb, settings, forced=True)[0] == pytest.approx(
        -coulomb["beta1"] * coulomb["omega1"], rel=1e-14
    )
