"""beltmdsm.analysis.predict: the consistent MDSM and the paper's intervals."""

import json

import numpy as np
import pytest

from beltmdsm.analysis import predict
from beltmdsm.cli import main
from beltmdsm.model import Model
from beltmdsm.settings import MAX_VB_POINTS
from generated import correlation, friction, stability
from generated.parameters import BASE


def test_linear_fast_motion_is_the_coupled_vhat():
    p = Model(Vb=12.0)
    fast = predict.fast_motion(p)
    assert not fast.reverses
    assert fast.V == pytest.approx(friction.vhat(model="coupled", **p.params), rel=1e-12)


def test_harmonic_balance_residual_and_reversal():
    p = Model(Vb=4.0)
    fast = predict.fast_motion(p)
    assert fast.reverses and fast.V > 4.0 and fast.residual < 1e-9


def test_consistent_mdsm_reduces_to_the_consistent_convention_without_normal_fluctuation():
    """With N1 = 0 (no normal excitation) the slope is mu_bar' and the damping positive."""
    p = Model(Vb=2.0, alpha_n=0.0)
    fast = predict.fast_motion(p)
    assert fast.N1 == 0.0
    slope = friction.mu_bar_slope(2.0, fast.V, p["mu_s"])
    expected = 2 * p["beta1"] * p["omega1"] + p["g"] * slope
    assert predict.consistent_mdsm_damping(p, fast=fast) == pytest.approx(expected, rel=1e-12)
    assert not predict.unstable_intervals(alpha_n=0.0)[0]


def test_prediction_edges_are_roots_or_the_reversal_onset():
    intervals, table = predict.unstable_intervals()
    assert len(intervals) == 1
    lower, upper = intervals[0]
    p = Model()
    assert abs(predict.consistent_mdsm_damping(p.replace(Vb=lower))) < 1e-8
    assert upper == pytest.approx(correlation.fast_tangential_velocity(**p.params)[0], rel=1e-12)
    inside = table["Vb"][(table["Vb"] > lower) & (table["Vb"] < upper)]
    assert np.all(table["damping"][np.isin(table["Vb"], inside)] < 0)


def test_paper_intervals_match_generated_stability():
    out = predict.paper_intervals(beta1=0.4)
    lo, up = stability.unstable_interval(**{**BASE, "beta1": 0.4})
    assert out["tangential"] == [(float(lo), float(up))]
    # each sign convention of Eq. (A4) is its own closed form, and the default is "paper"
    for convention in ("paper", "consistent"):
        got = predict.paper_intervals(beta1=0.4, convention=convention)
        for reading in ("tangential", "coupled"):
            lo, up = stability.unstable_interval(
                convention=convention, vhat_model=reading, **{**BASE, "beta1": 0.4}
            )
            assert got[reading] == ([] if np.isnan(lo) else [(float(lo), float(up))])
    assert predict.paper_intervals(beta1=0.4, convention="paper") == out
    assert predict.paper_intervals(convention="consistent") != predict.paper_intervals()


def test_two_frequencies_are_refused():
    with pytest.raises(ValueError, match="one excitation frequency"):
        predict.unstable_intervals(Omega_t=6.0)


def test_predict_cli_json(capsys):
    assert main(["predict", "--beta1", "0.4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == {
        "paper_tangential_vhat",
        "paper_coupled_vhat",
        "consistent_mdsm",
        "reasons",
        "tension",
        "contact",
        "friction",
    }
    assert out["tension"] == "allowed"
    assert out["consistent_mdsm"][0][0] > out["paper_coupled_vhat"][0][0]


@pytest.mark.parametrize("Vb", [1.0, 4.0, 7.0, 12.0])
def test_generated_slow_damping_and_harmonic_balance_are_the_runtimes(Vb):
    """The consistent MDSM's pieces that beltmdsm.analysis.predict types by hand (its damping
    2 beta1 omega1 + mu_s dF/du and the residual of its harmonic balance), generated from
    the derivation: equal to rounding (one rearranged product and sum)."""
    p = Model(Vb=Vb)
    fast = predict.fast_motion(p)
    damping = correlation.slow_damping(fast.V, fast.N1, fast.theta, **p.params)
    assert damping == pytest.approx(predict.consistent_mdsm_damping(p, fast=fast), rel=1e-14)
    W = p["Omega_t"]
    D = p["omega1"] ** 2 - W**2 + 2j * p["beta1"] * p["omega1"] * W
    assert complex(*correlation.transfer_function(**p.params)) == pytest.approx(D, rel=1e-15)
    Ft = p["alpha_t"] * W**2 * np.exp(1j * p["phase_t"])
    ref = predict._balance((fast.V, fast.phi), p.params, W, fast.N1, fast.psi, D, Ft)
    got = correlation.harmonic_balance(fast.V, fast.phi, fast.N1, fast.psi, **p.params)
    # the residual is 0 at the solution: compare against the size of its terms, |D| V / W
    np.testing.assert_allclose(
        got, ref, rtol=0, atol=64 * np.finfo(float).eps * abs(D) * fast.V / W
    )


# ---------------------------------------------------------------- issue 17, item 3


def _close(a, b, tol=1e-8):
    return len(a) == len(b) and all(
        abs(x - y) <= tol and abs(u - v) <= tol for (x, u), (y, v) in zip(a, b)
    )


def test_a_coarse_grid_keeps_both_edges():
    """``--vb-points 2`` found no unstable speed: the band was between two points."""
    ref, _ = predict.unstable_intervals(points=400)
    for points in (2, 3, 10):
        found, _ = predict.unstable_intervals(points=points)
        assert _close(found, ref), (points, found)
    V_lin = float(correlation.fast_tangential_velocity(**Model().params)[0])
    assert ref[0][1] == V_lin


def test_the_harmonic_balance_converges_next_to_the_linear_amplitude():
    """``--vb-points 30000`` failed at Vb = 6.3753, 1.5e-5 below the linear amplitude."""
    p = Model()
    V_lin = float(correlation.fast_tangential_velocity(**p.params)[0])
    for eps in (1.5e-5, 1e-8, 1e-12):
        q = p.replace(Vb=V_lin * (1 - eps))
        fast = predict.fast_motion(q)
        # the reversing solution keeps a reversal of 2.1e-3 m/s up to V_lin, where the
        # damping tends to -18.4 (it is continuous in s = sqrt(V - Vb))
        assert fast.reverses and 2e-3 < fast.V - q["Vb"] < 2.3e-3 and fast.residual < 1e-14
        assert -18.5 < predict.consistent_mdsm_damping(q, fast) < -17.5
    # a grid with points where the report failed finds the same band
    ref, _ = predict.unstable_intervals(points=400)
    grid = [1.0, 4.0, 6.375275534917551, V_lin * (1 - 1e-9), V_lin * (1 + 1e-9), 6.4]
    found, table = predict.unstable_intervals(vb=grid)
    assert _close(found, ref)
    # the table is on the grid asked for, the point 1e-9 below V_lin included
    assert list(table["Vb"]) == sorted(grid)
    assert table["reverses"][3] and -18.5 < table["damping"][3] < -18.4


def test_at_resonance_the_onset_point_is_solved_too():
    # Omega = omega1: the reversal vanishes as (V_lin - Vb)^2 and the damping tends to
    # +infinity: no unstable speed, on any grid
    for points in (2, 400):
        found, _ = predict.unstable_intervals(Omega=1.0, points=points)
        assert found == []
    # within 1e-8 of V_lin the reversal is below the rounding of V: such a point of
    # the grid is NaN in the table and does not cost the answer
    p = Model(Omega=1.0)
    V_lin = float(correlation.fast_tangential_velocity(**p.params)[0])
    found, table = predict.unstable_intervals(p, vb=[1.0, V_lin * (1 - 1e-10), 7.0])
    assert found == [] and np.isnan(table["damping"][1]) and not table["reverses"][1]


def test_a_band_at_the_end_of_the_grid_says_it_may_extend_beyond():
    out = predict.predict(Omega=10.0, points=2)
    assert "reaches the lowest belt speed of the grid" in out.reasons["consistent_mdsm"]
    out = predict.predict(vb=[1.0, 5.0])
    assert "reaches the highest belt speed of the grid, 5 m/s" in out.reasons["consistent_mdsm"]
    assert "consistent_mdsm" not in predict.predict(points=400).reasons


def test_the_grid_has_a_cap():
    from beltmdsm.errors import Refused

    with pytest.raises(Refused, match="MAX_VB_POINTS") as err:
        predict.predict(points=MAX_VB_POINTS + 1)
    assert err.value.names == ("points",)
    with pytest.raises(Refused, match="MAX_VB_POINTS"):
        predict.unstable_intervals(vb=np.linspace(1, 2, MAX_VB_POINTS + 1))
