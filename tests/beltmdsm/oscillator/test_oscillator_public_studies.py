"""``beltmdsm.responses``, ``coexistence``, ``classify`` and ``periodic_start`` of another
registered model (issue 39 item 4): the public functions run it on the generic runtime,
through the same function the ``--model`` commands run, each number against a
reference typed here (closed forms, an event-driven solve_ivp run with exact stick)."""

import json
import math

import numpy as np
import pytest
from inprocess import cli
from scipy.integrate import solve_ivp

import beltmdsm
from beltmdsm import Model
from beltmdsm.attractors import classification as paper_classification
from beltmdsm.oscillator import classification

STRIBECK = dict(model="belt_1dof", friction="stribeck")


def _stribeck(p, v):
    return p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-abs(v) / p["v_s"])


def _hopf(p):
    """The Stribeck belt's Hopf point in closed form (issue 39 item 5)."""
    return p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )


def _stick_slip_period(p):
    """The stick-slip cycle of x'' + 2 b w x' + w^2 x = mu(|v_r|) g (v_r = x' - Vb < 0)
    from its stick end, typed: the stick ends where the holding force w^2 x + 2 b w Vb
    reaches mu_s g; slip (solve_ivp) until v_r = 0 again; stick back at x' = Vb."""
    w, b, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]
    x_end = (p["mu_s"] * g - 2 * b * w * Vb) / w**2

    def slip(t, y):
        return [y[1], -2 * b * w * y[1] - w * w * y[0] + _stribeck(p, y[1] - Vb) * g]

    def back(t, y):
        return y[1] - Vb if t > 1e-6 else -1.0

    back.terminal, back.direction = True, 1
    sol = solve_ivp(slip, (0, 100), [x_end, Vb - 1e-13], events=back, rtol=1e-12, atol=1e-13)
    t_slip, x_stick = sol.t_events[0][0], sol.y_events[0][0][0]
    return t_slip + (x_end - x_stick) / Vb, x_end


def _json(*argv):
    done = cli(*argv, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


# --- responses and coexistence: the Python API and the command, one path -------------------


def test_responses_of_another_model_is_the_command_and_meets_the_references():
    m = Model(**STRIBECK, Vb=2.5)
    found = beltmdsm.responses(m)
    assert [f.attractor.kind for f in found.found] == ["steady_sliding", "stick_slip"]
    p = m.params
    eq, cycle = found.found[0].orbit, found.found[1].orbit
    assert eq.state[0] == pytest.approx(_stribeck(p, p["Vb"]) * p["g"], rel=1e-12)
    period, x_end = _stick_slip_period(p)
    assert cycle.sticks == 1 and cycle.period == pytest.approx(period, rel=1e-8)
    assert cycle.state == pytest.approx([x_end, p["Vb"]], abs=1e-8)
    out = _json("responses", "--model", "belt_1dof", "--friction", "stribeck", "--Vb", "2.5")
    assert out["model"] == "belt_1dof"
    # the default --t-end (1000) and --limit are the function's defaults: the same result
    assert out["attractors"] == json.loads(json.dumps(found.as_dict()["attractors"]))


def test_coexistence_of_another_model_starts_at_the_closed_form_hopf_point():
    m = Model(**STRIBECK)
    hopf = _hopf(m.params)  # 1.9957: steady sliding stable above it
    found = beltmdsm.coexistence(m, "Vb", 1.5, 2.5, points=5)  # 1.5, 1.75, ... 2.5
    # below the Hopf point no run lands on steady sliding (it is unstable); above it,
    # where the unstable slip cycle bounding its basin has grown, both are found (at
    # 2.0, 0.004 past the subcritical Hopf point, that basin is below the grid's reach)
    for point in found.points:
        kinds = [f.attractor.kind for f in point.found if f.orbit.stable]
        below = point.system.params["Vb"] < hopf
        assert kinds == ["stick_slip"] if below else kinds[-1] == "stick_slip"
    assert found.ranges == [(2.25, 2.5)] and 1.75 < hopf < 2.25
    out = _json(
        "coexistence", "--model", "belt_1dof", "--friction", "stribeck", "--param", "Vb",
        "--from", "1.5", "--to", "2.5", "--step", "0.25",
    )  # fmt: skip
    assert out["ranges"] == [[2.25, 2.5]]
    assert out["points"] == json.loads(json.dumps(found.as_dict()["points"]))


def test_coexistence_of_another_model_checks_its_own_parameters():
    m = Model(model="hoffmann")
    with pytest.raises(ValueError, match="param must be a model parameter of model 'hoffmann'"):
        beltmdsm.coexistence(m, "alpha", 1.0, 2.0)
    with pytest.raises(ValueError, match="lo < hi"):
        beltmdsm.coexistence(m, "mu_s", 2.0, 1.0)
    with pytest.raises(beltmdsm.Unsupported, match="settings=.*applies to the paper's model"):
        beltmdsm.coexistence(m, "mu_s", 1.0, 2.0, settings=beltmdsm.ContinuationSettings())


def test_a_paper_only_keyword_is_refused_not_ignored():
    m = Model(**STRIBECK, Vb=2.5)
    with pytest.raises(beltmdsm.Unsupported, match="ladder=1.0 applies to the paper's"):
        beltmdsm.responses(m, ladder=1.0)
    with pytest.raises(beltmdsm.Unsupported, match="backend='python' applies to the paper's"):
        beltmdsm.classify(m, backend="python")


# --- classify ------------------------------------------------------------------------


def test_classify_thresholds_are_the_papers():
    for name in ("SIGNIFICANCE", "ZERO_FLOOR", "ZERO_TOL"):
        assert getattr(classification, name) == getattr(paper_classification, name)


def test_classify_names_the_stick_slip_cycle_with_the_reference_period():
    m = Model(**STRIBECK, Vb=1.5)
    a = beltmdsm.classify(m, t_end=200.0)
    assert (a.kind, a.cycle, a.periods) == ("periodic", "stick_slip", 1)
    period, x_end = _stick_slip_period(m.params)
    assert a.orbit.period == pytest.approx(period, rel=1e-8)
    assert a.state == pytest.approx([x_end, 1.5], abs=1e-8)
    # the exponent along the flow is zero within its error; stick removes the other
    assert abs(a.lyapunov) <= 3 * a.lyapunov_error + 5e-4
    assert a.exponents[-1] == -np.inf


def test_a_run_on_unstable_steady_sliding_is_unstable_not_chaotic():
    """Issue 36 item 2 for another model: the run that starts exactly on unstable
    steady sliding stays there; its positive exponent is the equilibrium's growth rate,
    -c / 2 with the effective damping c = 2 b w - g mu'(Vb) typed here."""
    m = Model(**STRIBECK, Vb=1.5)
    p = m.params
    x_eq = _stribeck(p, p["Vb"]) * p["g"] / p["omega1"] ** 2
    a = beltmdsm.classify(m, y0=[x_eq, 0.0], t_end=100.0)
    slope = (p["mu_s"] - p["mu_k"]) / p["v_s"] * math.exp(-p["Vb"] / p["v_s"])
    c = 2 * p["beta1"] * p["omega1"] - p["g"] * slope
    assert a.kind == "unstable" and "steady sliding" in a.evidence
    assert a.orbit.growth_rate == pytest.approx(-c / 2, rel=1e-12)
    assert a.lyapunov > 0 and a.lyapunov == pytest.approx(-c / 2, abs=0.01)
    assert a.state == pytest.approx([x_eq, 0.0], rel=1e-12)


def test_a_run_near_stable_steady_sliding_is_an_equilibrium():
    m = Model(**STRIBECK, Vb=2.5)
    p = m.params
    x_eq = _stribeck(p, p["Vb"]) * p["g"] / p["omega1"] ** 2
    a = beltmdsm.classify(m, y0=[x_eq + 1e-3, 0.0], t_end=200.0)
    assert a.kind == "equilibrium" and a.lyapunov < 0
    assert a.state == pytest.approx([x_eq, 0.0], abs=1e-12)


def _forced_slip(p):
    """Under Coulomb friction in pure slip (v_r < 0 throughout) the forced belt is
    linear, x'' + 2 b w x' + w^2 x = mu_s g + alpha_t W^2 sin(W t) (the model's
    tangential force): x = mu_s g / w^2 + Im(A e^{i W t}),
    A = alpha_t W^2 / (w^2 - W^2 + 2 i b w W); its state at t = 0 and its speed."""
    w, b, W = p["omega1"], p["beta1"], p["Omega_t"]
    A = p["alpha_t"] * W * W / (w * w - W * W + 2j * b * w * W)
    return np.array([p["mu_s"] * p["g"] / w**2 + A.imag, W * A.real]), abs(A) * W


def test_classify_and_periodic_start_of_a_forced_slip_response_meet_the_closed_form():
    m = Model(model="belt_1dof", Vb=5.0, alpha_t=1.0, Omega_t=1.5)
    state, speed = _forced_slip(m.params)
    assert speed < 5.0  # never reaches the belt's speed: pure slip
    a = beltmdsm.classify(m, t_end=300.0)
    assert (a.kind, a.cycle, a.periods) == ("periodic", "forced", 1)
    assert a.state == pytest.approx(state, abs=1e-9)
    # the multipliers of the linear slip response: exp(-b w T) twice, in closed form
    T = 2 * math.pi / 1.5
    assert np.abs(a.orbit.multipliers) == pytest.approx([math.exp(-0.1 * T)] * 2, rel=1e-8)
    start = beltmdsm.periodic_start(m, perturbation=0.25)
    assert start == pytest.approx(state + [0.25, 0.0], abs=1e-9)


def test_periodic_start_of_an_unforced_model_is_on_its_cycle():
    m = Model(**STRIBECK, Vb=1.5)
    period, x_end = _stick_slip_period(m.params)
    assert beltmdsm.periodic_start(m, 0.0) == pytest.approx([x_end, 1.5], abs=1e-8)


def test_simulate_classify_of_another_model_runs_beltmdsm_classify():
    """``simulate --model NAME --classify`` names what the run settles on by
    `beltmdsm.classify` (from the run's start, over 2000 s, as the paper's)."""
    out = _json("simulate", "--model", "belt_1dof", "--friction", "stribeck", "--Vb", "1.5",
                "--t-end", "50", "--classify")  # fmt: skip
    a = out["attractor"]
    assert (a["kind"], a["cycle"], a["periods"]) == ("periodic", "stick_slip", 1)
    period, x_end = _stick_slip_period(Model(**STRIBECK, Vb=1.5).params)
    assert a["state"] == pytest.approx([x_end, 1.5], abs=1e-8)
    assert f"period {period:.7g} s" in a["evidence"]
    assert a["exponents"][-1] is None  # -inf: the direction the stick removes


def test_a_run_on_an_unstable_forced_response_is_unstable_not_chaotic():
    """Issue 36 item 2, forced: weakly forced (alpha_t = 1e-3) unstable steady sliding
    has a T-periodic pure-slip response next to it whose multipliers are those of the
    unforced linearisation, exp(lambda T), lambda = -c / 2 + i sqrt(w^2 - c^2 / 4), to
    the forcing's order; a run started on it stays on it (the excitation period does not
    divide t_end: classify cuts the run to whole periods)."""
    from beltmdsm.oscillator import System, forced_response

    forcing = dict(alpha_t=1e-3, Omega_t=4.0)
    s = System("belt_1dof", friction="stribeck", Vb=1.5, **forcing)
    p = s.params
    x_eq = _stribeck(p, p["Vb"]) * p["g"] / p["omega1"] ** 2
    on = forced_response(s, [x_eq, 0.0], settle=0.0)
    a = beltmdsm.classify(Model(**STRIBECK, Vb=1.5, **forcing), y0=on.state, t_end=60.0)
    assert (a.kind, a.cycle, a.periods) == ("unstable", "forced", 1)
    assert "not chaos" in a.evidence
    slope = (p["mu_s"] - p["mu_k"]) / p["v_s"] * math.exp(-p["Vb"] / p["v_s"])
    c = 2 * p["beta1"] * p["omega1"] - p["g"] * slope
    lam = complex(-c / 2, math.sqrt(p["omega1"] ** 2 - c * c / 4))
    T = 2 * math.pi / p["Omega_t"]
    typed = abs(np.exp(lam * T))
    assert np.abs(a.orbit.multipliers) == pytest.approx([typed, typed], rel=1e-4)
    assert a.lyapunov == pytest.approx(-c / 2, abs=0.01)


def test_a_stick_that_ends_and_begins_at_once_is_no_cycle():
    """The shooting behind responses and classify never reports a cycle whose period is
    far below every time scale of steady sliding (Hoffmann's model at mu_s = 1: Newton's
    method from the default seed converges on a stick end that sticks again at once,
    period 5e-12 s)."""
    from beltmdsm.errors import NoPeriodicResponse
    from beltmdsm.oscillator import System, self_excited_cycle, steady_sliding
    from beltmdsm.oscillator.basins import BasinAttractor
    from beltmdsm.oscillator.responses import shoot_attractor

    s = System("hoffmann", mu_s=1.0)
    seed = tuple(self_excited_cycle(s).state)
    shortest = 1.0 / np.abs(steady_sliding(s).eigenvalues).max()
    try:
        c = shoot_attractor(s, BasinAttractor("stick_slip", 1, seed, seed))
    except NoPeriodicResponse as err:
        assert "a stick that ends and begins at once, no cycle" in str(err)
    else:
        assert c.period > 1e-6 * shortest
