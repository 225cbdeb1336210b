"""beltmdsm.prediction: the consistent MDSM and the paper's intervals."""

import json

import mpmath
import numpy as np
import pytest

from beltmdsm.cli import main
from beltmdsm.generated import correlation, friction, stability
from beltmdsm.generated.parameters import BASE
from beltmdsm.model import Model
from beltmdsm.prediction import mdsm, paper, paper_numeric, prediction, scan
from beltmdsm.prediction.prediction import Prediction
from beltmdsm.settings import MAX_VB_POINTS


def test_linear_fast_motion_is_the_coupled_vhat():
    p = Model(Vb=12.0)
    fast = mdsm.fast_motion(p)
    assert not fast.reverses
    assert fast.V == pytest.approx(friction.vhat(model="coupled", **p.params), rel=1e-12)


def test_harmonic_balance_residual_and_reversal():
    p = Model(Vb=4.0)
    fast = mdsm.fast_motion(p)
    assert fast.reverses and fast.V > 4.0 and fast.residual < 1e-9


def test_consistent_mdsm_reduces_to_the_consistent_convention_without_normal_fluctuation():
    """With N1 = 0 (no normal excitation) the slope is mu_bar' and the damping positive."""
    p = Model(Vb=2.0, alpha_n=0.0)
    fast = mdsm.fast_motion(p)
    assert fast.N1 == 0.0
    slope = friction.mu_bar_slope(2.0, fast.V, p["mu_s"])
    expected = 2 * p["beta1"] * p["omega1"] + p["g"] * slope
    assert mdsm.consistent_mdsm_damping(p, fast=fast) == pytest.approx(expected, rel=1e-12)
    assert not scan.unstable_intervals(alpha_n=0.0)[0]


def test_prediction_edges_are_roots_or_the_reversal_onset():
    intervals, table = scan.unstable_intervals()
    assert len(intervals) == 1
    lower, upper = intervals[0]
    p = Model()
    assert abs(mdsm.consistent_mdsm_damping(p.replace(Vb=lower))) < 1e-8
    assert upper == pytest.approx(correlation.fast_tangential_velocity(**p.params)[0], rel=1e-12)
    inside = table["Vb"][(table["Vb"] > lower) & (table["Vb"] < upper)]
    assert np.all(table["damping"][np.isin(table["Vb"], inside)] < 0)


def test_paper_intervals_match_generated_stability():
    out = paper.paper_intervals(beta1=0.4)
    lo, up = stability.unstable_interval(**{**BASE, "beta1": 0.4})
    assert out["tangential"] == [(float(lo), float(up))]
    # each sign convention of Eq. (A4) is its own closed form, and the default is "paper"
    for convention in ("paper", "consistent"):
        got = paper.paper_intervals(beta1=0.4, convention=convention)
        for reading in ("tangential", "coupled"):
            lo, up = stability.unstable_interval(
                convention=convention, vhat_model=reading, **{**BASE, "beta1": 0.4}
            )
            assert got[reading] == ([] if np.isnan(lo) else [(float(lo), float(up))])
    assert paper.paper_intervals(beta1=0.4, convention="paper") == out
    assert paper.paper_intervals(convention="consistent") != paper.paper_intervals()


def test_two_frequencies_are_refused():
    with pytest.raises(ValueError, match="one excitation frequency"):
        scan.unstable_intervals(Omega_t=6.0)


def test_predict_cli_json(capsys):
    assert main(["predict", "--beta1", "0.4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) == {
        "model",  # every command's JSON names its model (issue 39)
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


# ------------------------------------------- issue 19: the model's laws, never Coulomb's


def _mu(model, s):
    """The friction coefficient at sliding speed ``s``, typed here from the laws' formulas."""
    if model.friction == "coulomb":
        return mpmath.mpf(model["mu_s"])
    assert model.friction == "stribeck"
    return model["mu_k"] + (model["mu_s"] - model["mu_k"]) * mpmath.exp(-s / model["v_s"])


def _average(model, u, V, N1, theta, weight=lambda t: 1):
    """``integral over a period of mu(|v|) sgn(v) (g + N1 sin(t + theta)) weight(t)``,
    ``v = u + V sin t``, by mpmath with the reversals as breakpoints."""

    def f(t):
        v = u + V * mpmath.sin(t)
        return (
            mpmath.sign(v)
            * _mu(model, abs(v))
            * (model["g"] + N1 * mpmath.sin(t + theta))
            * weight(t)
        )

    points = {mpmath.mpf(0), 2 * mpmath.pi}
    if abs(u) < V:
        a = mpmath.asin(-u / V)
        points |= {a % (2 * mpmath.pi), (mpmath.pi - a) % (2 * mpmath.pi)}
    return mpmath.quad(f, sorted(points))


def _reference(model, fast):
    """The harmonic balance's residual at ``fast`` and the slow damping, from Eq. (A1) and
    the averaged friction typed here and integrated by mpmath (30 digits), independent
    of the generated quadratures: ``q(iW) V / (iW) - F_t e^(-i phi) + (s1 + i c1)``
    relative to ``|F_t|``, and ``2 beta1 omega1 + d/du <mu(|v|) sgn(v) N>`` at ``u = -Vb``
    (mpmath's numerical derivative of the average)."""
    with mpmath.workdps(30):
        V, phi, N1, psi = (mpmath.mpf(x) for x in (fast.V, fast.phi, fast.N1, fast.psi))
        u, theta = -mpmath.mpf(model["Vb"]), psi - phi
        s1 = _average(model, u, V, N1, theta, mpmath.sin) / mpmath.pi
        c1 = _average(model, u, V, N1, theta, mpmath.cos) / mpmath.pi
        W, w1, b1 = mpmath.mpf(model["Omega_t"]), model["omega1"], model["beta1"]
        q = w1**2 - W**2 + 2j * b1 * w1 * W
        Ft = model["alpha_t"] * W**2 * mpmath.expj(model["phase_t"])
        residual = abs(q * V / (1j * W) - Ft * mpmath.expj(-phi) + (s1 + 1j * c1)) / abs(Ft)
        slope = mpmath.diff(lambda x: _average(model, x, V, N1, theta) / (2 * mpmath.pi), u)
        return float(residual), float(2 * b1 * w1 + slope)


STRIBECK = {"friction": "stribeck", "mu_k": 0.25, "v_s": 1.0}


@pytest.mark.parametrize(
    "laws",
    [
        {},
        STRIBECK,
        {**STRIBECK, "contact": "kelvin_voigt"},
        {**STRIBECK, "contact": "hunt_crossley", "n_h": 1.3},
    ],
    ids=["coulomb", "stribeck", "stribeck-kelvin_voigt", "stribeck-hunt_crossley"],
)
@pytest.mark.parametrize("Vb", [1.0, 4.0, 6.5, 7.05, 7.2, 9.0])
def test_fast_motion_and_damping_against_mpmath(laws, Vb):
    """The consistent MDSM with the model's laws (generated harmonic balance and slow
    damping; for Stribeck's law quadratures of the same expression) against Eq. (A1)
    and the averaged friction integrated by mpmath: reversing and not, below and above
    the onset of reversal (7.083 for Stribeck at the base set)."""
    model = Model(Vb=Vb, **laws)
    fast = mdsm.fast_motion(model)
    fn = correlation.fast_normal_force
    assert (fast.N1, fast.psi) == tuple(float(x) for x in fn(**model.arguments(fn)))
    assert fast.reverses == (fast.V > Vb)
    residual, damping = _reference(model, fast)
    assert residual < 1e-12
    got = mdsm.consistent_mdsm_damping(model, fast)
    assert got == pytest.approx(damping, rel=1e-12, abs=1e-13)


def test_stribeck_band_against_its_own_edges():
    """Stribeck's law (mu_k = 0.25, v_s = 1) at the base set: the band [5.878, 7.083]
    (Coulomb's is [4.682, 6.375]). Its lower edge is a root of the damping, its upper
    edge the onset of reversal, where the fast motion without reversal has V = Vb."""
    found, table = scan.unstable_intervals(Model(**STRIBECK), points=60)
    assert len(found) == 1
    lower, upper = found[0]
    assert lower == pytest.approx(5.878018659582, abs=1e-9)
    assert upper == pytest.approx(7.082839963373, abs=1e-9)
    at = Model(Vb=lower, **STRIBECK)
    assert abs(mdsm.consistent_mdsm_damping(at)) < 1e-8
    onset = Model(Vb=upper, **STRIBECK)
    fast = mdsm.fast_motion(onset)
    assert not fast.reverses and fast.V == pytest.approx(upper, rel=1e-12)
    assert _reference(onset, fast)[0] < 1e-12
    # just below the onset the friction reverses and the damping is negative
    below = mdsm.fast_motion(onset.replace(Vb=upper * (1 - 1e-3)))
    assert below.reverses
    assert mdsm.consistent_mdsm_damping(onset.replace(Vb=upper * (1 - 1e-3)), below) < -1
    assert np.all(table["damping"][(table["Vb"] > upper)] > 0)
    # not Coulomb's band
    assert scan.unstable_intervals(points=60)[0][0] == pytest.approx((4.6816, 6.3754), abs=1e-4)


@pytest.mark.parametrize(
    "laws",
    [
        {},
        {"contact": "kelvin_voigt"},
        {"contact": "hunt_crossley", "n_h": 1.2},
        {"beta1": 0.4},
        {"Omega": 10.0},
        {"alpha": 0.0},
    ],
)
def test_stribeck_with_mu_k_equal_to_mu_s_is_coulomb(laws):
    """mu_k = mu_s: Stribeck's law is Coulomb's. The consistent MDSM takes the general
    path (harmonic balance without reversal, onset solved for) and reproduces the
    closed-form path to rounding."""
    coulomb = prediction.predict(laws, points=40)
    stribeck = prediction.predict(Model(friction="stribeck", mu_k=0.4, **laws), points=40)
    assert len(coulomb.consistent_mdsm) == len(stribeck.consistent_mdsm)
    for a, b in zip(coulomb.consistent_mdsm, stribeck.consistent_mdsm):
        assert a == pytest.approx(b, rel=1e-13, abs=1e-13)
    _, c_table = scan.unstable_intervals(points=40, **laws)
    _, s_table = scan.unstable_intervals(points=40, friction="stribeck", mu_k=0.4, **laws)
    np.testing.assert_allclose(s_table["Vb"], c_table["Vb"], rtol=1e-13)
    np.testing.assert_allclose(s_table["damping"], c_table["damping"], rtol=1e-11, atol=1e-12)
    assert list(s_table["reverses"]) == list(c_table["reverses"])


def test_stribeck_without_excitation_is_the_unforced_boundary():
    """No fast motion: the consistent MDSM is the unforced linearisation, unstable below
    the unforced critical belt speed (v_s ln(g (mu_s - mu_k) / (2 beta1 omega1 v_s)),
    1.996 m/s, by hand), not Coulomb's "no belt speed is unstable"."""
    out = prediction.predict(Model(alpha=0.0, **STRIBECK))
    ((lower, upper),) = out.consistent_mdsm
    p = Model(**STRIBECK)
    by_hand = p["v_s"] * np.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    assert upper == pytest.approx(by_hand, rel=1e-10)
    assert "unforced equilibrium" in out.reasons["consistent_mdsm"]
    assert "may extend below" in out.reasons["consistent_mdsm"]
    coulomb = prediction.predict(Model(alpha=0.0))
    assert (
        coulomb.consistent_mdsm == []
        and coulomb.reasons["consistent_mdsm"] == prediction.NO_EXCITATION
    )


def test_the_paper_analysis_of_stribeck_is_numeric_and_says_so():
    """Stribeck's law has no closed-form fast average (closed_form_average): the paper's
    analysis is solved numerically from the pointwise growth rate, never with Coulomb's
    closed form, and the reason says so with its grid and tolerance."""
    from beltmdsm.generated.capabilities import CAPABILITIES

    holds, _ = CAPABILITIES[("stribeck", "hertz_damp", "allowed")]["closed_form_average"]
    assert not holds
    for contact in ("hertz_damp", "kelvin_voigt", "hunt_crossley"):
        out = prediction.predict(Model(contact=contact, **STRIBECK), points=10)
        for key, reading in (
            ("paper_tangential_vhat", "tangential"),
            ("paper_coupled_vhat", "coupled"),
        ):
            assert getattr(out, key)
            reason = out.reasons[key]
            assert reason.startswith("numeric (friction='stribeck' has no closed-form fast")
            assert f"({reading} reading)" in reason and "brentq to 1e-12" in reason
            assert "\n" not in reason
        assert out.friction == "stribeck" and out.contact == contact
    # the numbers of the base set (docs/modelling.md, README): the tangential reading
    # has a lower edge where Coulomb's has 0, the coupled one ends at V_hat(Vb) = Vb
    found = paper.paper_intervals(**STRIBECK)
    ((lo, hi),) = found["tangential"]
    assert lo == pytest.approx(3.8049, abs=1e-4) and hi == pytest.approx(8.5213, abs=1e-4)
    ((lo, hi),) = found["coupled"]
    assert lo == 0.0 and hi == pytest.approx(7.1177, abs=1e-4)
    p = Model(**STRIBECK, Vb=hi)
    assert friction.vhat(model="coupled", **p.arguments(friction.vhat)) == pytest.approx(
        hi, abs=1e-11
    )


def test_predict_prints_stribecks_numeric_paper_intervals(capsys):
    assert main(["predict", "--friction", "stribeck", "--mu_k", "0.25", "--v_s", "1",
                 "--no-progress"]) == 0  # fmt: skip
    lines = capsys.readouterr().out.splitlines()
    for key, interval in (
        ("paper_tangential_vhat", "[3.805, 8.521]"),
        ("paper_coupled_vhat", "[0.000, 7.118]"),
    ):
        (line,) = [x for x in lines if x.strip().startswith(f"{key}:")]
        assert f"unstable Vb in {interval}; numeric (" in line


CLOSED_CASES = {
    "base": {},  # the closed form's lower edge is 0 (m >= V_hat)
    "low_mu": {"mu_s": 0.1},  # a positive lower edge
    "damped": {"beta1": 0.4},
}


@pytest.mark.parametrize("convention", ["paper", "consistent"])
@pytest.mark.parametrize("case", list(CLOSED_CASES))
def test_stribeck_with_mu_k_equal_to_mu_s_has_coulombs_paper_intervals(case, convention):
    """mu_k = mu_s: the numeric path (a quadrature of a law part that is exactly 0, a
    V_hat that does not vary) gives the closed form's intervals to brentq's 1e-12 m/s;
    Coulomb's own numeric path too."""
    p = CLOSED_CASES[case]
    coulomb = Model(**p)
    stribeck = Model(**p, friction="stribeck", mu_k=coulomb["mu_s"], v_s=1.0)
    closed = paper.paper_intervals(coulomb, convention=convention)
    numeric = paper.paper_intervals(stribeck, convention=convention)
    for reading in ("tangential", "coupled"):
        own = paper_numeric.paper_numeric(coulomb, reading=reading, convention=convention)[0]
        for got in (numeric[reading], own):
            assert len(got) == len(closed[reading]), (reading, got, closed[reading])
            for (a, b), (c, d) in zip(got, closed[reading]):
                assert abs(a - c) <= 2e-12 and abs(b - d) <= 2e-12, (reading, got)
    assert "numeric" in paper.paper_reasons(stribeck, convention=convention)["coupled"]
    assert paper.paper_reasons(coulomb, convention=convention) == {}


@pytest.mark.parametrize("contact", ["kelvin_voigt", "hunt_crossley"])
def test_the_contact_law_reaches_every_generated_function(contact):
    """The paper's intervals take the contact law's coupled V_hat, the consistent MDSM
    its fast normal force; hunt_crossley at n_h = 3/2 is hertz_damp."""
    model = Model(contact=contact)
    vhat = float(friction.vhat(model="coupled", contact=contact, **model.params))
    assert paper.paper_intervals(model)["coupled"][0][1] == vhat
    N1 = float(correlation.fast_normal_force(contact=contact, **model.params)[0])
    assert mdsm.fast_motion(model.replace(Vb=2.0)).N1 == N1
    if contact == "hunt_crossley":
        a = prediction.predict(model, points=20)
        b = prediction.predict(points=20)
        for key in Prediction.ANALYSES:
            np.testing.assert_allclose(getattr(a, key), getattr(b, key), rtol=1e-12)
    else:
        # Kelvin-Voigt's linear contact: no unstable speed in the consistent MDSM here,
        # and a V_hat of its own (not Hertz-Damp's 6.375)
        assert prediction.predict(model, points=20).consistent_mdsm == []
        assert vhat == pytest.approx(8.5714, abs=1e-4)


def test_without_friction_the_paper_intervals_are_empty():
    """Issue 17: ``predict --mu_s 0`` printed "unstable Vb in [8.521, 8.521]" while
    is_stable(mu_s=0, Vb=8.521) is True: the interval (Vb_c, Vhat] with Vb_c = Vhat."""
    out = prediction.predict(Model(mu_s=0.0), points=10)
    assert out.paper_tangential_vhat == [] and out.paper_coupled_vhat == []
    assert paper.paper_intervals(mu_s=0.0, convention="consistent") == {
        "tangential": [],
        "coupled": [],
    }
    for reading in ("tangential", "coupled"):
        vhat = float(friction.vhat(model=reading, **{**BASE, "mu_s": 0.0}))
        assert stability.is_stable(vhat_model=reading, **{**BASE, "mu_s": 0.0, "Vb": vhat})


def test_a_balance_without_tangential_excitation_is_refused_by_name():
    out = prediction.predict(Model(alpha_t=0.0), points=10)
    assert out.consistent_mdsm is None
    assert out.reasons["consistent_mdsm"].startswith("alpha_t = 0: the residual of the harmonic")


# ---------------------------------------------------------------- issue 17, item 3


def _close(a, b, tol=1e-8):
    return len(a) == len(b) and all(
        abs(x - y) <= tol and abs(u - v) <= tol for (x, u), (y, v) in zip(a, b)
    )


def test_a_coarse_grid_keeps_both_edges():
    """``--vb-points 2`` found no unstable speed: the band was between two points."""
    ref, _ = scan.unstable_intervals(points=400)
    for points in (2, 3, 10):
        found, _ = scan.unstable_intervals(points=points)
        assert _close(found, ref), (points, found)
    V_lin = float(correlation.fast_tangential_velocity(**Model().params)[0])
    assert ref[0][1] == V_lin


def test_the_harmonic_balance_converges_next_to_the_linear_amplitude():
    """``--vb-points 30000`` failed at Vb = 6.3753, 1.5e-5 below the linear amplitude."""
    p = Model()
    V_lin = float(correlation.fast_tangential_velocity(**p.params)[0])
    for eps in (1.5e-5, 1e-8, 1e-12):
        q = p.replace(Vb=V_lin * (1 - eps))
        fast = mdsm.fast_motion(q)
        # the reversing solution keeps a reversal of 2.1e-3 m/s up to V_lin, where the
        # damping tends to -18.4 (it is continuous in s = sqrt(V - Vb))
        assert fast.reverses and 2e-3 < fast.V - q["Vb"] < 2.3e-3 and fast.residual < 1e-14
        assert -18.5 < mdsm.consistent_mdsm_damping(q, fast) < -17.5
    # a grid with points where the report failed finds the same band
    ref, _ = scan.unstable_intervals(points=400)
    grid = [1.0, 4.0, 6.375275534917551, V_lin * (1 - 1e-9), V_lin * (1 + 1e-9), 6.4]
    found, table = scan.unstable_intervals(vb=grid)
    assert _close(found, ref)
    # the table is on the grid asked for, the point 1e-9 below V_lin included
    assert list(table["Vb"]) == sorted(grid)
    assert table["reverses"][3] and -18.5 < table["damping"][3] < -18.4


def test_at_resonance_the_onset_point_is_solved_too():
    # Omega = omega1: the reversal vanishes as (V_lin - Vb)^2 and the damping tends to
    # +infinity: no unstable speed, on any grid
    for points in (2, 400):
        found, _ = scan.unstable_intervals(Omega=1.0, points=points)
        assert found == []
    # within 1e-8 of V_lin the reversal is below the rounding of V: such a point of
    # the grid is NaN in the table and does not cost the answer
    p = Model(Omega=1.0)
    V_lin = float(correlation.fast_tangential_velocity(**p.params)[0])
    found, table = scan.unstable_intervals(p, vb=[1.0, V_lin * (1 - 1e-10), 7.0])
    assert found == [] and np.isnan(table["damping"][1]) and not table["reverses"][1]


def test_a_band_at_the_end_of_the_grid_says_it_may_extend_beyond():
    out = prediction.predict(Model(Omega=10.0), points=2)
    assert "reaches the lowest belt speed of the grid" in out.reasons["consistent_mdsm"]
    out = prediction.predict(vb=[1.0, 5.0])
    assert "reaches the highest belt speed of the grid, 5 m/s" in out.reasons["consistent_mdsm"]
    assert "consistent_mdsm" not in prediction.predict(points=400).reasons


def test_the_grid_has_a_cap():
    from beltmdsm.errors import Refused

    with pytest.raises(Refused, match="MAX_VB_POINTS") as err:
        prediction.predict(points=MAX_VB_POINTS + 1)
    assert err.value.names == ("points",)
    with pytest.raises(Refused, match="MAX_VB_POINTS"):
        scan.unstable_intervals(vb=np.linspace(1, 2, MAX_VB_POINTS + 1))


def test_the_repr_of_a_prediction_says_what_it_holds():
    # issue 30 item 3: a short repr, in the words of the command line
    from beltmdsm._display import intervals

    result = prediction.predict(Model(Omega_n=7.0), points=20)
    lines = repr(result).splitlines()
    assert lines[0] == "Prediction(coulomb friction, hertz_damp, tension allowed)"
    assert (
        lines[1]
        == f"  paper_tangential_vhat: unstable Vb in {intervals(result.paper_tangential_vhat)}"
    )
    assert lines[3] == f"  consistent_mdsm: no prediction ({result.reasons['consistent_mdsm']})"
    assert len(lines) == 4
