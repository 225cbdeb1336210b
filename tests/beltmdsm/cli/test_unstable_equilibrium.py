"""Issue 29 item 5: no silent answer at an unstable steady state, end to end.

Stribeck's law without excitation: steady sliding is unstable below
``Vb_c = v_s ln(F (mu_s - mu_k) / (2 beta1 omega1 v_s))`` (typed here by hand, ``F``
the static normal force per unit mass, ``g`` in Eq. 4), where the tangential damping
``2 beta1 omega1 + F mu'(Vb)`` is negative.
"""

import json
import math
import re

import numpy as np
import pytest
from inprocess import cli as _run

from beltmdsm.excitation import initial_state
from beltmdsm.model import Model
from beltmdsm.simulation import START_PERTURBATION, equilibrium_start, simulate

LAW = ["--friction", "stribeck", "--alpha", "0"]


def _by_hand(Vb, beta1=0.1, omega1=1.0, mu_s=0.4, mu_k=0.25, v_s=1.0, g=9.81):
    """The free tangential rate and the critical speed of Stribeck's law, by hand."""
    slope = -(mu_s - mu_k) / v_s * math.exp(-Vb / v_s)  # mu'(Vb)
    damping = 2 * beta1 * omega1 + g * slope  # F = g: the static normal force per mass
    critical = v_s * math.log(g * (mu_s - mu_k) / (2 * beta1 * omega1 * v_s))
    return -damping / 2, critical  # underdamped: the real part of the tangential pair


def _static_normal_force(model):
    """F: the normal force per unit mass at the unforced equilibrium, read from a short
    run that starts there (the contact force the model computes, not typed here)."""
    sim = simulate(model, y0=initial_state(model), t_end=1.0, dt=0.01)
    return float(sim.normal_force[0])


def test_simulate_on_unstable_sliding_is_moved_off_it_and_says_it_has_not_left():
    Vb = 1.9
    sigma, critical = _by_hand(Vb)
    assert 0 < sigma < 0.02 and Vb < critical  # slowly unstable
    r = _run("simulate", *LAW, "--Vb", str(Vb), "--t-end", "300", "--json", "--no-progress")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["start_perturbation"] == START_PERTURBATION
    assert out["resolved"] is False and out["omega1_peak_present"] is None
    assert out["regime"] == "continuous_sliding"
    reason = out["unresolved_reason"]
    assert "steady sliding is unstable" in reason and f"sigma = {sigma:.3g} 1/s" in reason
    # the disturbance grows at the hand-typed rate: the band's amplitude in the second
    # half of the window over the first is exp(sigma h), h the half window
    halves = re.search(r"holds (\S+) m/s in the first half .* and (\S+) m/s in the second", reason)
    first, second = map(float, halves.groups())
    h = (300.0 - 90.0) / 2
    assert second / first == pytest.approx(math.exp(sigma * h), rel=0.01)
    text = _run("simulate", *LAW, "--Vb", str(Vb), "--t-end", "300", "--no-progress").stdout
    assert "start: steady sliding is unstable here; the run starts on it moved by 1e-06" in text
    assert "omega1 peak unresolved (steady sliding is unstable" in text


def test_the_start_moves_along_the_unstable_plane_only_where_sliding_is_unstable():
    from beltmdsm.generated import unforced

    for Vb, unstable in ((1.0, True), (1.9, True), (2.5, False)):
        model = Model(friction="stribeck", alpha=0.0, Vb=Vb)
        sigma, _ = _by_hand(Vb)
        assert (sigma > 0) is unstable
        y0, size = equilibrium_start(model)
        if not unstable:
            assert y0 is None and size == 0.0
            continue
        d = y0 - initial_state(model)
        assert np.max(np.abs(d)) == pytest.approx(START_PERTURBATION, rel=1e-12)
        # the tangential plane: the normal block does not move, and the unforced
        # Jacobian keeps the move in the plane (the unstable pair's invariant plane)
        assert np.all(d[2:] == 0)
        J = np.asarray(unforced.jacobian_at_equilibrium(**model.arguments(
            unforced.jacobian_at_equilibrium)), dtype=float)  # fmt: skip
        assert np.allclose((J @ d)[2:], 0.0, atol=1e-20)
        # and the tangential block's eigenvalues are the hand-typed rate
        lam = np.linalg.eigvals(J[:2, :2])
        assert np.max(lam.real) == pytest.approx(sigma, rel=1e-12)


def test_a_start_given_exactly_on_unstable_sliding_is_named_not_called_absent():
    model = Model(friction="stribeck", alpha=0.0, Vb=1.9)
    s = simulate(model, y0=initial_state(model), t_end=200.0).summary
    assert s.start_perturbation == 0.0
    assert s.resolved is False and s.omega1_peak_present is None
    assert "steady sliding is unstable" in s.unresolved_reason
    assert "where only rounding moves it" in s.unresolved_reason


def test_sweep_over_unstable_sliding_says_unresolved_not_absent():
    argv = ["sweep", "--param", "Vb", "--values", "1.9", "2.5", *LAW, "--t-end", "300"]
    r = _run(*argv, "--no-cache", "--jobs", "1", "--no-progress", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["unresolved"] == [1.9]  # stable at 2.5 (hand-typed Vb_c = 1.9957)
    rows = {row["Vb"]: row for row in out["rows"]}
    assert rows[2.5]["resolved"] is True and rows[2.5]["omega1_peak_present"] is False


# ------------------------------------------------------------- predict --alpha 0


def test_predict_without_excitation_finds_the_critical_speed_of_the_closed_form():
    _, critical = _by_hand(1.0)
    r = _run("predict", *LAW, "--no-progress", "--json")
    assert r.returncode == 0, r.stderr
    ((lo, hi),) = json.loads(r.stdout)["consistent_mdsm"]
    assert lo < 0.01 and hi == pytest.approx(critical, abs=1e-9)


def test_predict_finds_the_unforced_edges_numerically_where_the_closed_form_is_refused(
    monkeypatch,
):
    from beltmdsm.generated import unforced
    from beltmdsm.prediction import prediction, sliding

    model = Model(friction="stribeck", alpha=0.0)
    F = _static_normal_force(model)
    assert F == pytest.approx(model["g"], rel=1e-12)  # Eq. (4): the contact carries g
    _, critical = _by_hand(1.0, g=F)
    # the generated closed form agrees with the hand-typed one
    fn = unforced.critical_belt_speed
    assert float(fn(**model.arguments(fn))) == pytest.approx(critical, rel=1e-13)

    def refused(**kw):
        raise ValueError("friction='stribeck': no closed form (refused in this test)")

    monkeypatch.setattr(unforced, "critical_belt_speed", refused)
    (edge,) = sliding.unforced_edges(model)
    assert edge == pytest.approx(critical, rel=1e-11)
    # the largest real part of the unforced eigenvalues changes sign there
    below, above = sliding.unforced_rate(model, [edge * (1 - 1e-6), edge * (1 + 1e-6)])
    assert below > 0 > above
    result = prediction.predict(model)
    ((lo, hi),) = result.consistent_mdsm
    assert hi == pytest.approx(critical, abs=1e-9)
    assert "no closed form (friction='stribeck'" in result.reasons["consistent_mdsm"]
    assert "roots of the largest real part" in result.reasons["consistent_mdsm"]
