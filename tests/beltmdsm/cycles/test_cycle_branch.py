"""Branches of self-excited cycles from the Hopf point of steady sliding (issue 29, item 4).

References typed here, not read from the package:

* Stribeck's law ``mu(s) = mu_k + (mu_s - mu_k) exp(-s / v_s)``, ``s = |Vr|``. Without
  excitation the normal motion rests at its equilibrium, where the Hertz force is the
  weight: ``F = omega2^2 X2^(3/2) = g`` per unit mass (Eq. 4). Sliding back
  (``Vr = X1' - Vb < 0``), the friction pushes the mass along the belt:
  ``X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = g mu(Vb - X1')``.
* Linearised: the damping of steady sliding is ``2 beta1 omega1 + g mu'(Vb)``, zero at
  ``Vb_H = v_s ln(g (mu_s - mu_k) / (2 beta1 omega1 v_s))``; there the pair is
  ``+-i omega1`` and ``d Re(lambda)/dVb = -g mu''(Vb_H) / 2 = -beta1 omega1 / v_s``.
* Averaged (first order, the Rayleigh equation ``x'' + a x' + c3 x'^3 + omega^2 x = 0``,
  ``a = 2 beta1 omega1 + g mu'(Vb)``, ``c3 = g mu'''(Vb) / 6``; the quadratic term does
  not enter at this order): the velocity amplitude obeys ``V^2 = -4 a / (3 c3)``, so
  near ``Vb_H``, ``V^2 = -4 g mu''(Vb_H) (Vb - Vb_H) / (3 g mu'''(Vb_H) / 6)
  = 8 v_s (Vb - Vb_H)``. ``c3 < 0``: the cycles exist for ``Vb > Vb_H``, where steady
  sliding is stable: subcritical.
* The onset of stick: the ``Vb`` where the sliding cycle of the slip-back equation
  above (solve_ivp, shooting written here) reaches ``max X1' = Vb``.
"""

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

import beltmdsm
from beltmdsm.branches import branch  # moved from beltmdsm.continuation.branch (issue 38)
from beltmdsm.cli import main
from beltmdsm.cycles.branch import (
    CycleBranch,
    cycle_branch,
    cycle_branch_from,
    hopf_cycle,
)
from beltmdsm.cycles.cycle import cycle
from beltmdsm.cycles.hopf import NoHopfPoint, hopf_point
from beltmdsm.model import Model

BASE = Model(friction="stribeck", alpha=0)


def vb_hopf(p):
    return p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )


@pytest.fixture(scope="module")
def cycles():
    return branch(BASE, param="Vb", lo=1.8, hi=3.0)


@pytest.mark.parametrize(
    "changes", [{}, {"beta1": 0.05, "v_s": 0.5, "mu_k": 0.2, "omega1": 1.7, "g": 5.0}]
)
def test_hopf_point_is_the_closed_form(changes):
    model = BASE.replace(**changes)
    p = model.params
    h = hopf_point(model, "Vb", 0.01, 6.0)
    assert h.value == pytest.approx(vb_hopf(p), abs=1e-9)
    assert h.frequency == pytest.approx(p["omega1"], rel=1e-9)
    assert h.period == pytest.approx(2 * math.pi / p["omega1"], rel=1e-9)
    assert h.transversality == pytest.approx(-p["beta1"] * p["omega1"] / p["v_s"], rel=1e-6)
    assert h.unstable_side == "below" and h.pair == "tangential"
    # the eigenvector of +i omega1 is (1, i omega1, 0, 0) up to a factor
    v = h.eigenvector / h.eigenvector[0]
    assert np.allclose(v, [1, 1j * p["omega1"], 0, 0], atol=1e-9)


def test_hopf_point_in_another_parameter_and_none_for_coulomb():
    # beta1_H: the damping 2 beta1 omega1 = g (mu_s - mu_k) exp(-Vb/v_s) / v_s
    p = BASE.params
    expected = (
        p["g"]
        * (p["mu_s"] - p["mu_k"])
        * math.exp(-p["Vb"] / p["v_s"])
        / (2 * p["omega1"] * p["v_s"])
    )
    assert hopf_point(BASE, "beta1", 0.001, 1.0).value == pytest.approx(expected, abs=1e-10)
    with pytest.raises(NoHopfPoint, match="no Hopf point of steady sliding for Vb"):
        hopf_point(Model(alpha=0), "Vb", 0.5, 3.0)


def test_small_cycles_grow_like_the_averaged_amplitude_and_tend_to_the_hopf_period():
    h = hopf_point(BASE, "Vb", 0.5, 3.0)
    amplitudes = np.array([0.01, 0.02, 0.04])
    found = [hopf_cycle(h, a) for a in amplitudes]
    dp = np.array([c.value - h.value for c in found])
    assert np.all(dp > 0)  # subcritical: the cycles lie where steady sliding is stable
    # V^2 = 8 v_s (Vb - Vb_H) to first order; the next order is O(V^2 / Vb^2) < 1e-3
    ratio = np.array([c.amplitude for c in found]) ** 2 / dp
    assert ratio == pytest.approx(8 * BASE["v_s"], rel=1e-3)
    # T = 2 pi / omega_H + c A^2 + O(A^4): the intercept of the fit on A^2
    periods = np.array([c.period for c in found])
    slope, intercept = np.polyfit(amplitudes**2, periods, 1)
    assert intercept == pytest.approx(2 * math.pi / h.frequency, abs=1e-7)
    assert all(not c.stable for c in found)  # unstable, as a subcritical Hopf cycle is


def test_branch_labels_criticality_and_parts(cycles):
    assert isinstance(cycles, CycleBranch) and cycles.criticality == "subcritical"
    kinds = [s.kind for s in cycles.special]
    assert kinds == ["hopf", "stick_onset", "range"]
    assert cycles.special[0].value == pytest.approx(vb_hopf(BASE.params), abs=1e-9)
    parts = cycles.parts()
    assert [(p.stable, p.start, p.end) for p in parts] == [
        (False, "hopf", "stick_onset"),
        (True, "stick_onset", "range"),
    ]
    onset = cycles.special[1]
    sliding = [q for q in cycles.points if q.n_sticks == 0]
    sticking = [q for q in cycles.points if q.n_sticks > 0]
    assert all(q.max_relative_velocity < 0 and q.value <= onset.value for q in sliding)
    assert all(q.max_relative_velocity == pytest.approx(0, abs=1e-9) for q in sticking)
    assert "turns back" in onset.detail  # both lie below the onset: a nonsmooth fold
    assert "CycleBranch(Vb: hopf" in repr(cycles) and len(repr(cycles)) < 200


def _slip_field(model):
    p = model.params

    def mu(s):
        return p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-s / p["v_s"])

    def f(t, y):
        x, v = y
        a = -2 * p["beta1"] * p["omega1"] * v - p["omega1"] ** 2 * x + p["g"] * mu(p["Vb"] - v)
        return [v, a]

    return f, mu


def _sliding_max_vr(model, v0, T0):
    """The sliding cycle of the slip-back equation by shooting from the section x'' = 0,
    and its largest Vr (the velocity maximum, an event of solve_ivp)."""
    f, mu = _slip_field(model)
    p = model.params

    def start(v):
        return [(p["g"] * mu(p["Vb"] - v) - 2 * p["beta1"] * p["omega1"] * v) / p["omega1"] ** 2, v]

    def residual(u):
        y0 = start(u[0])
        sol = solve_ivp(f, (0, u[1]), y0, method="DOP853", rtol=1e-12, atol=1e-12)
        return sol.y[:, -1] - y0

    v, T = fsolve(residual, [v0, T0], xtol=1e-13)
    top = lambda t, y: f(t, y)[1]  # noqa: E731
    top.direction = -1
    sol = solve_ivp(f, (0, T), start(v), method="DOP853", rtol=1e-12, atol=1e-12, events=top)
    return max(y[1] for y in sol.y_events[0]) - p["Vb"]


def test_stick_onset_is_where_the_independent_sliding_cycle_reaches_the_belt(cycles):
    onset = cycles.special[1]
    assert onset.accuracy <= 1e-6
    near = max((q for q in cycles.points if q.n_sticks == 0), key=lambda q: q.value)
    values, tops = [], []
    for vb in (near.value, onset.value):  # a secant from the package's guesses
        values.append(vb)
        tops.append(_sliding_max_vr(BASE.replace(Vb=vb), near.state[1], near.period))
    for _ in range(6):
        if abs(tops[-1]) < 1e-11:
            break
        vb = values[-1] - tops[-1] * (values[-1] - values[-2]) / (tops[-1] - tops[-2])
        values.append(vb)
        tops.append(_sliding_max_vr(BASE.replace(Vb=vb), near.state[1], near.period))
    assert onset.value == pytest.approx(values[-1], abs=1e-6)
    # at the located value the sliding cycle's largest Vr is 0 within the tolerance
    slope = (tops[-1] - tops[-2]) / (values[-1] - values[-2])
    located = _sliding_max_vr(BASE.replace(Vb=onset.value), near.state[1], near.period)
    assert abs(located) <= abs(slope) * 1e-6


def _hybrid_run(model, y0, T):
    """Slip back, stick at Vr = 0 while the friction holds (mu_s g), slip on: the end
    state after ``T`` and the time stuck."""
    f, _ = _slip_field(model)
    p = model.params
    hit = lambda t, y: y[1] - p["Vb"]  # noqa: E731
    hit.terminal, hit.direction = True, 1
    t, y, stuck = 0.0, np.array(y0, float), 0.0
    while t < T:
        sol = solve_ivp(f, (t, T), y, method="DOP853", rtol=1e-12, atol=1e-12, events=hit)
        t, y = sol.t[-1], sol.y[:, -1]
        if sol.status != 1:
            break
        # stuck: x = x_s + Vb (t - t_s) until omega1^2 x + 2 beta1 omega1 Vb = mu_s g
        x_end = (p["mu_s"] * p["g"] - 2 * p["beta1"] * p["omega1"] * p["Vb"]) / p["omega1"] ** 2
        dt = min(max((x_end - y[0]) / p["Vb"], 0.0), T - t)
        stuck += dt
        t, y = t + dt, np.array([y[0] + p["Vb"] * dt, p["Vb"] - 1e-13])
    return y, stuck


def test_independent_runs_on_either_side_of_the_onset(cycles):
    i = next(k for k, q in enumerate(cycles.points) if q.n_sticks)
    before, after = cycles.points[i - 1], cycles.points[i]
    for q, sticks in ((before, False), (after, True)):
        model = BASE.replace(Vb=q.value)
        end, stuck = _hybrid_run(model, q.state[:2], q.period)
        assert np.max(np.abs(end - q.state[:2])) < 1e-7  # the orbit closes after T
        assert bool(stuck > 1e-6) == sticks


def test_branch_stability_agrees_with_cycles_recomputed(cycles):
    picks = [cycles.points[len(cycles.points) // 4]]
    picks += [q for q in cycles.points if q.n_sticks][1::20][:2]
    for q in picks:
        c = cycle(BASE.replace(Vb=q.value), q.state, q.period)
        assert c.period == pytest.approx(q.period, rel=1e-9)
        assert c.stable == q.stable and c.n_sticks == q.n_sticks
        assert np.allclose(np.abs(c.multipliers), np.abs(q.multipliers), atol=1e-6)
        assert c.max_relative_velocity == pytest.approx(q.max_relative_velocity, abs=1e-8)
        assert c.velocity_range == pytest.approx(q.velocity_range, abs=1e-8)


def test_refusals():
    with pytest.raises(ValueError, match="periods must be 1"):
        branch(BASE, periods=2, param="Vb", lo=1.0, hi=3.0)
    with pytest.raises(ValueError, match="without excitation"):
        cycle_branch(Model(friction="stribeck"), param="Vb", lo=1.0, hi=3.0)


def test_branch_cli_json_and_text(capsys):
    args = ["branch", "--alpha", "0", "--friction", "stribeck", "--param", "Vb"]
    args += ["--from", "1.8", "--to", "3"]
    assert main(args + ["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["autonomous"] is True and out["criticality"] == "subcritical"
    assert out["hopf"]["value"] == pytest.approx(vb_hopf(BASE.params), abs=1e-9)
    assert [s["kind"] for s in out["special_points"]] == ["hopf", "stick_onset", "range"]
    assert {"period", "amplitude", "stable", "max_relative_velocity"} <= set(out["points"][0])
    assert main(args[:-4] + ["--from", "1.9", "--to", "2.1"]) == 0  # the sliding part only
    text = capsys.readouterr().out
    assert "Hopf point of steady sliding at Vb = 1.99572" in text and "subcritical" in text


def test_coexistence_cli_gives_the_hysteresis(capsys):
    args = ["coexistence", "--alpha", "0", "--friction", "stribeck", "--param", "Vb"]
    assert main(args + ["--from", "1.8", "--to", "3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (both,) = out["coexistence"]
    assert both["range"][0] == pytest.approx(vb_hopf(BASE.params), abs=1e-9)
    assert (both["lower"], both["upper"]) == ("hopf", "stick_onset")
    assert main(["coexistence", "--alpha", "0", "--param", "Vb", "--from", "1", "--to", "3"]) == 0
    assert "coexistence: none: no Hopf point" in capsys.readouterr().out


def test_the_onset_from_the_stick_side_is_the_same(cycles):
    # from a stick-slip cycle towards the onset: the stick time vanishes there, the
    # branch turns back onto the sliding cycles (unstable)
    q = min((q for q in cycles.points if q.n_sticks), key=lambda q: abs(q.value - 2.85))
    start = cycle(BASE.replace(Vb=q.value), q.state, q.period)
    from_stick = cycle_branch_from(start, "Vb", 2.8, 3.0)
    kinds = [s.kind for s in from_stick.special]
    assert kinds == ["range", "stick_onset", "range"]
    onset = from_stick.special[1]
    assert onset.value == pytest.approx(cycles.special[1].value, abs=1e-6)
    assert (onset.stable_before, onset.stable_after) == (True, False)
    assert "disappears" in onset.detail and "turns back" in onset.detail


def test_continue_branch_of_a_cycle_goes_both_ways():
    from beltmdsm.branches import continue_branch  # moved from continuation.branch (issue 38)
    from beltmdsm.periodic.shooting import periodic_response

    start = periodic_response(BASE.replace(Vb=1.0))
    found = continue_branch(start, "Vb", 0.9, 1.1)
    assert isinstance(found, CycleBranch) and found.hopf is None
    assert [s.kind for s in found.special] == ["range", "range"]
    assert found.value_range() == pytest.approx([0.9, 1.1], abs=1e-9)
    assert all(q.stable and q.n_sticks == 1 for q in found.points)


def test_cycles_seeded_without_a_hopf_point_and_sliding_nowhere_stable_say_why():
    # Stribeck with a small kinetic coefficient: steady sliding is unstable over the
    # whole range and no Hopf point lies in it, so the cycles come from a seed where a
    # stick ends; the reason names that (it indexed the empty list of Hopf points)
    m = beltmdsm.Model(Vb=2, alpha=0, friction="stribeck", mu_k=0.1, v_s=3.0)
    c = beltmdsm.coexistence(m, "Vb", 1.0, 3.0)
    assert c.hopf == [] and c.sliding == [] and c.ranges == []
    assert c.branch is not None and c.branch.points
    assert "no Hopf point is in the range" in c.reason
    text = repr(c)
    assert text.startswith("CycleCoexistence(Vb in [1, 3]") and "Hopf points: none" in text
    assert len(text.splitlines()) <= 10
