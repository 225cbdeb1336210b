"""Friction against relative velocity (Fig. 3b) and cycle averages (Figs. 10-12)."""

import numpy as np
import pytest

from beltmdsm.model import Model
from beltmdsm.run.modulation import cycle_averages, friction_loop, modulation_scatter
from beltmdsm.simulation import simulate


@pytest.fixture(scope="module")
def sliding():
    return simulate(Model(Vb=12.0), t_end=120.0, t_discard=40.0)


@pytest.fixture(scope="module")
def reversing():
    return simulate(Model(Vb=4.0), t_end=150.0, t_discard=60.0)


def test_continuous_sliding_has_mu_eff_equal_to_mu_s(sliding):
    # friction = mu_s Fn at every instant, so every cycle average of it is mu_s <Fn>
    out = modulation_scatter(sliding)
    assert out["mu_eff_Omega_mean"] == pytest.approx(sliding.params["mu_s"], rel=1e-12)
    assert out["mu_eff_omega1_mean"] == pytest.approx(sliding.params["mu_s"], rel=1e-12)
    assert out["mu_eff_Omega_range"] < 1e-12


def test_cycle_mean_of_the_normal_force_balances_gravity(reversing):
    """Over a period of the normal excitation, <Fn> = g - (Y2(t0+T) - Y2(t0)) / T."""
    p = reversing.params
    T = 2 * np.pi / p["Omega_n"]
    out = cycle_averages(reversing, T)
    y0 = reversing.trajectory.state(out["t0"])
    y1 = reversing.trajectory.state(out["t0"] + T)
    np.testing.assert_allclose(out["normal_force"], p["g"] - (y1[3] - y0[3]) / T, rtol=1e-9)


def test_cycle_mean_of_the_friction_balances_the_tangential_motion(reversing):
    """Eq. (4), tangential row, integrated over a cycle of the excitation."""
    p = reversing.params
    T = 2 * np.pi / p["Omega_t"]
    out = cycle_averages(reversing, T)
    tr = reversing.trajectory
    t0 = out["t0"]
    y0, y1 = tr.state(t0), tr.state(t0 + T)

    def x1(t, y, mode):
        return y[0:1]

    mean_x1 = np.array([tr.integrate(x1, [a, a + T])[0, 0] / T for a in t0[:5]])
    c1, k1 = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2
    # <Y1'> = <f_t> - c1 <Y1> - k1 <X1> + <friction>, <f_t> = 0 over a full period
    expected = (y1[1, :5] - y0[1, :5]) / T + c1 * (y1[0, :5] - y0[0, :5]) / T + k1 * mean_x1
    np.testing.assert_allclose(out["friction"][:5], expected, rtol=1e-8, atol=1e-9)


def test_averaging_over_2pi_over_omega1_scatters_less_than_over_2pi_over_Omega(reversing):
    """Figs. 10b and 11b: with the omega1 oscillation the Omega-cycles differ."""
    assert reversing.summary.omega1_peak_present
    out = modulation_scatter(reversing)
    assert out["mu_eff_omega1_std"] < 0.01 * out["mu_eff_Omega_std"]


def test_friction_loop_over_one_period(reversing):
    p = reversing.params
    t, vr, friction = friction_loop(reversing)
    assert t[-1] - t[0] == pytest.approx(2 * np.pi / p["omega1"])
    y = reversing.trajectory.state(t)
    Fn = reversing.trajectory.forces(t, y)[0]
    # Eqs. (2)-(3) with the friction on the mass: -mu_s sgn(Vr) Fn
    slipping = vr != 0
    np.testing.assert_allclose(
        friction[slipping], -p["mu_s"] * np.sign(vr[slipping]) * Fn[slipping]
    )
    assert vr.max() > 0 > vr.min()


def test_bad_periods_are_named(reversing):
    with pytest.raises(ValueError, match="period"):
        cycle_averages(reversing, 0.0)
    with pytest.raises(ValueError, match="period"):
        friction_loop(reversing, period=1e4)
