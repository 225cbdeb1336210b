"""Self-excited cycles without excitation (beltmdsm/periodic/cycle.py), against references.

References, independent of the package's shooting: the Hopf speed of steady sliding by
hand, a stick-slip cycle computed here with scipy's ``solve_ivp`` and events on the
tangential equation typed by hand (the normal motion sits at its equilibrium, where the
Hertz force is ``g``), and the Poincare map differentiated by finite differences.

Error model of the comparisons with ``solve_ivp``: both integrations run at tolerance
1e-12 over one slip phase of about 5 s; the slip phase contracts or grows by at most
``exp(0.35 * 5) ~ 6`` (the largest real part of the linearised slip field, 0.35 1/s at
Vb = 0.5), so each side carries about 6e-11 of the state's scale (measured: 2e-13 to
2e-12); the stick time is a closed form of the state where the slip ends. 1e-9 relative
leaves an order for other CPUs and is orders below anything a wrong section,
saltation or stick rule would change.
"""

import json
import math
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from beltmdsm.cli import main
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.excitation import is_autonomous
from beltmdsm.generated import unforced
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import Model
from beltmdsm.periodic.cycle import Cycle, cycle, seed_cycle, unstable_pair
from beltmdsm.periodic.floquet import floquet
from beltmdsm.periodic.shooting import periodic_response
from beltmdsm.settings import SolverSettings
from beltmdsm.starts.forced import periodic_start

P = dict(beta1=0.1, omega1=1.0, mu_s=0.4, mu_k=0.25, v_s=1.0, g=9.81)


def stribeck(model=None, **kw):
    return Model(friction="stribeck", alpha=0, **kw)


def hopf_speed():
    """Where 2 beta1 omega1 + g mu'(Vb) = 0, mu(s) = mu_k + (mu_s - mu_k) exp(-s / v_s)."""
    p = P
    return p["v_s"] * math.log(p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["v_s"]))


def tangential_damping(vb):
    p = P
    slope = -(p["mu_s"] - p["mu_k"]) / p["v_s"] * math.exp(-vb / p["v_s"])
    return 2 * p["beta1"] * p["omega1"] + p["g"] * slope


def test_the_hopf_speed_by_hand_is_where_the_unforced_eigenvalues_cross():
    vc = hopf_speed()
    model = stribeck(Vb=1.0)
    generated = float(unforced.critical_belt_speed(**model.arguments(unforced.critical_belt_speed)))
    assert vc == pytest.approx(generated, rel=1e-14)
    for vb in (0.5, 1.5, vc - 1e-6, vc + 1e-6, 2.5):
        lam = np.asarray(unforced.eigenvalues(**stribeck(Vb=vb).arguments(unforced.eigenvalues)))
        # the tangential pair: lambda^2 + c lambda + omega1^2 = 0 (normal block apart)
        c = tangential_damping(vb)
        pair = np.roots([1.0, c, P["omega1"] ** 2])
        got = np.sort_complex(np.asarray(lam[:2], dtype=complex))
        np.testing.assert_allclose(got, np.sort_complex(pair), atol=1e-12)
        assert (got.real.max() > 0) == (vb < vc) == (c < 0)
        assert is_autonomous(stribeck(Vb=vb))


def reference_stick_slip(vb):
    """The stick-slip cycle of the tangential equation by solve_ivp: (period, stick time,
    min X1', min X1, max X1), starting where a stick ends."""
    p, F = P, P["g"]
    w, z = p["omega1"], p["beta1"]

    def accel(x, v):  # slipping back (Vr = v - Vb < 0): friction along the belt
        mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-(vb - v) / p["v_s"])
        return F * mu - w**2 * x - 2 * z * w * v

    x_unstick = (p["mu_s"] * F - 2 * z * w * vb) / w**2  # the cone's edge, Eq. (3)

    def stick(t, y):  # Vr = 0 reached from below, after leaving it
        return y[1] - vb

    stick.terminal, stick.direction = True, 1

    def turn(t, y):
        return y[1]

    def minimum(t, y):
        return accel(*y)

    minimum.direction = 1
    # where a stick ends X1'' = 0 (mu(0) = mu_s) and Vr = 0: the events' directions
    # ignore the start (Vr and X1'' leave zero downwards)
    sol = solve_ivp(
        lambda t, y: [y[1], accel(*y)],
        (0.0, 100.0),
        [x_unstick, vb],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        events=(stick, turn, minimum),
        dense_output=True,
    )
    t_slip = float(sol.t_events[0][0])
    x_stick = float(sol.y_events[0][0][0])
    stick_time = (x_unstick - x_stick) / vb
    v_min = float(sol.y_events[2][0][1])
    x_turns = [float(y[0]) for y in sol.y_events[1]]
    return t_slip + stick_time, stick_time, v_min, min(x_turns), max(x_turns)


@pytest.fixture(scope="module")
def stick_slip():
    return cycle(stribeck(Vb=0.5))


def test_a_stick_slip_cycle_agrees_with_an_independent_simulation(stick_slip):
    c = stick_slip
    period, stick_time, v_min, x_min, x_max = reference_stick_slip(0.5)
    assert c.period == pytest.approx(period, rel=1e-9)
    assert c.stick_time == pytest.approx(stick_time, rel=1e-9)
    assert c.velocity_range[0] == pytest.approx(v_min, rel=1e-9)
    assert c.velocity_range[1] == 0.5 and c.max_relative_velocity == 0.0
    assert c.x1_range == pytest.approx((x_min, x_max), rel=1e-9)
    # the state lies on the section: the minimum of X1'
    assert c.state[1] == pytest.approx(v_min, rel=1e-10)
    assert (c.n_sticks, c.n_reversals) == (1, 0) and c.stable and c.stick_collapses
    assert abs(c.trivial_multiplier - 1) < 1e-8


@pytest.mark.parametrize("vb", [0.5, 0.03])
def test_a_stick_phase_gives_a_zero_multiplier_and_the_normal_ones_are_closed_form(vb, stick_slip):
    # Vb = 0.03: a stick of 20 s, over which the run's steps grew to 7 s and one
    # Runge-Kutta step of the variational equation made the fast normal multiplier
    # (1e-47) 1.4e7 before the pieces were bounded (variational.split_pieces)
    c = stick_slip if vb == 0.5 else cycle(stribeck(Vb=vb))
    # the normal motion ignores the tangential: the monodromy is block triangular, and
    # the stick collapses its tangential block, whose eigenvalues are 1 (trivial) and 0
    assert np.all(c.monodromy[2:, :2] == 0)
    tangential = np.sort(np.abs(np.linalg.eigvals(c.monodromy[:2, :2])))
    assert tangential[0] < 1e-12 and abs(tangential[1] - 1) < 1e-8
    # the normal multipliers are exp(lambda T) of steady sliding's normal eigenvalues
    lam = np.asarray(unforced.eigenvalues(**c.model.arguments(unforced.eigenvalues)))[2:]
    normal = np.sort(np.exp(np.real(lam) * c.period))[::-1]
    mu = c.multipliers
    assert np.abs(mu) == pytest.approx(sorted(np.abs(mu), reverse=True))
    assert mu[0] == pytest.approx(normal[0], rel=1e-9)
    # the stick's 0, and the fast normal multiplier, below the rounding (1e-20 or less)
    assert normal[1] < 1e-20
    assert np.all(np.abs(mu[1:]) < 1e-12)
    assert c.stable and c.max_abs_multiplier == pytest.approx(normal[0], rel=1e-9)
    assert "multiplier is 0" in c.as_dict()["stick_collapses"]


def _return_map(model, x, T):
    """The first return to the section near T (X1'' = 0 with X1''' > 0), by a run and
    a root of the acceleration typed by hand (Stribeck, Hertz-Damp)."""
    p, m = P, model.params

    def accel(y):
        fn = (m["omega2"] ** 2 + 2 * m["beta2"] * m["omega2"] * y[3]) * max(y[2], 0.0) ** 1.5
        mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-(m["Vb"] - y[1]) / p["v_s"])
        return fn * mu - p["omega1"] ** 2 * y[0] - 2 * p["beta1"] * p["omega1"] * y[1]

    settings = SolverSettings(t_end=1.3 * T, rtol=1e-12, atol=1e-12, dt=T / 50, t_discard=0.0)
    tr = integrate_events(model, settings, y0=x).trajectory

    def a(t):
        return accel(tr.state(np.array([t]))[:, 0])

    t = brentq(a, 0.8 * T, 1.2 * T, xtol=1e-15, rtol=1e-15)
    return tr.state(np.array([t]))[:, 0]


def _fd_multipliers(c, h=1e-6):
    """Eigenvalues of the Poincare map's Jacobian by central differences in full
    coordinates: the nontrivial multipliers and a 0 (the flow direction is projected)."""
    D = np.zeros((4, 4))
    for j in range(4):
        e = np.zeros(4)
        e[j] = h * max(1.0, abs(c.state[j]))
        up = _return_map(c.model, c.state + e, c.period)
        down = _return_map(c.model, c.state - e, c.period)
        D[:, j] = (up - down) / (2 * e[j])
    return np.linalg.eigvals(D)


def test_the_multipliers_of_a_stick_slip_cycle_agree_with_finite_differences(stick_slip):
    fd = np.sort(np.abs(_fd_multipliers(stick_slip)))[::-1]
    # central differences: truncation ~h^2, rounding ~1e-12 / h = 1e-6
    np.testing.assert_allclose(fd[:3], np.abs(stick_slip.multipliers), atol=1e-5)


def _pure_slip(dv=0.05):
    """The unstable pure-slip cycle born at the (subcritical) Hopf point, from the
    first-order averaged amplitude of X1': (Y)^2 = 8 (exp(dv) - 1) at Vb = Vc + dv."""
    model = stribeck(Vb=hopf_speed() + dv)
    lam, v = unstable_pair(model)
    eq = np.array([float(s) for s in unforced.equilibrium(**model.arguments(unforced.equilibrium))])
    amplitude = math.sqrt(8 * (math.exp(dv) - 1))
    return cycle(model, eq + amplitude * np.real(-v / v[1]), 2 * math.pi / abs(lam.imag))


def test_a_pure_slip_cycle_its_multipliers_against_finite_differences():
    c = _pure_slip()
    assert (c.n_sticks, c.n_reversals) == (0, 0) and not c.stick_collapses
    assert c.max_relative_velocity < 0  # it never reaches the belt's speed
    assert abs(c.trivial_multiplier - 1) < 1e-8
    assert not c.stable and c.multipliers[0].real > 1  # subcritical: unstable
    fd = _fd_multipliers(c)
    fd = fd[np.argsort(-np.abs(fd))]
    np.testing.assert_allclose(fd[:2], c.multipliers[:2], atol=1e-5)
    # the averaged amplitude is first order in dv: 2 % at dv = 0.05
    assert 0.5 * (c.velocity_range[1] - c.velocity_range[0]) == pytest.approx(
        math.sqrt(8 * (math.exp(0.05) - 1)), rel=0.02
    )


def test_the_seed_is_the_run_settled_on_the_section():
    model = stribeck(Vb=1.5)
    x, T = seed_cycle(model)
    c = cycle(model, x, T)
    assert np.max(np.abs(x - c.state)) < 1e-4 * np.max(np.abs(c.state))
    assert T == pytest.approx(c.period, rel=1e-4)
    assert isinstance(c, Cycle) and "Cycle(Vb=1.5" in repr(c) and "\n" not in repr(c)
    back = pickle.loads(pickle.dumps(c))
    assert back.period == c.period and back.model == c.model and back.switches == c.switches


def test_where_steady_sliding_is_stable_no_cycle_and_one_line_why():
    # beyond the stick-slip branch's end (a run from the end of a stick decays too)
    for model in (stribeck(Vb=3.5), Model(alpha=0, Vb=1.5)):
        with pytest.raises(NoPeriodicResponse, match="steady sliding is stable") as err:
            cycle(model)
        assert "\n" not in str(err.value) and "nor from the end of a stick" in str(err.value)
    with pytest.raises(NoPeriodicResponse, match="decays to steady sliding"):
        seed_cycle(stribeck(Vb=2.5), perturbation=[0.0, 1e-3, 0.0, 0.0])
    with pytest.raises(NoPeriodicResponse, match="Vb = 0"):
        cycle(stribeck(Vb=0.0))
    with pytest.raises(ValueError, match="forced"):
        cycle(Model(friction="stribeck", Vb=1.5))


def test_a_cycle_coexisting_with_stable_sliding_is_found_from_the_end_of_a_stick():
    c = cycle(stribeck(Vb=1.99))
    c = cycle(stribeck(Vb=2.2), c.state, c.period)  # above the Hopf speed, by a neighbour
    assert c.stable and c.n_sticks == 1
    seeded = cycle(stribeck(Vb=2.2))  # steady sliding is stable: the seed starts at a stick's end
    assert seeded.period == pytest.approx(c.period, rel=1e-10)
    np.testing.assert_allclose(seeded.state, c.state, rtol=0, atol=1e-9)


def test_floquet_and_periodic_response_compute_the_cycle_without_excitation(stick_slip):
    model = stribeck(Vb=0.5)
    f = floquet(model)
    assert f.autonomous and f.period == pytest.approx(stick_slip.period, rel=1e-12)
    assert f.trivial_multiplier == stick_slip.trivial_multiplier
    assert f.response.autonomous and f.response.periods == 1
    again = periodic_response(model, guess=f.response)
    assert again.period == pytest.approx(f.period, rel=1e-12)
    with pytest.raises(ValueError, match="periods must be 1"):
        floquet(model, periods=2)
    # a run started on the cycle comes back to its state after one period
    y0 = periodic_start(model, 0.0)
    settings = SolverSettings(t_end=f.period, rtol=1e-12, atol=1e-12, dt=0.1, t_discard=0.0)
    tr = integrate_events(model, settings, y0=y0).trajectory
    np.testing.assert_allclose(tr.state(np.array([f.period]))[:, 0], y0, atol=1e-9)


def test_floquet_cli_for_a_cycle_has_the_documented_keys(capsys):
    argv = ["floquet", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.5", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["autonomous"] is True
    for key in (
        "period",
        "multipliers",
        "max_abs_multiplier",
        "trivial_multiplier",
        "stable",
        "n_sticks",
        "n_reversals",
        "x1_range",
        "velocity_range",
    ):
        assert key in out
    assert len(out["multipliers"]) == 3 and out["n_sticks"] == 1
    assert abs(complex(*out["trivial_multiplier"]) - 1) < 1e-8
    assert out["max_abs_multiplier"] == max(abs(complex(*z)) for z in out["multipliers"])
    assert main(argv[:-1]) == 0
    assert "one multiplier is 0" in capsys.readouterr().out


def test_floquet_cli_without_a_cycle_says_why_in_one_line(capsys):
    assert main(["floquet", "--alpha", "0", "--friction", "stribeck", "--Vb", "3.5"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "steady sliding is stable at Vb=3.5" in err


def test_forced_floquet_json_gains_the_ranges_of_its_orbit(capsys):
    assert main(["floquet", "--Vb", "4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["autonomous"] is False
    # the orbit sampled every 1e-4 s from its phase-0 state: a sampled extreme misses
    # the true one by at most max|X1'''| dt^2 / 8 < 1e-6
    model = Model(Vb=4)
    settings = SolverSettings(t_end=out["period"], rtol=1e-12, atol=1e-12, dt=1e-4, t_discard=0.0)
    tr = integrate_events(model, settings, y0=out["state0"]).trajectory
    y = tr.state(np.arange(0.0, out["period"], 1e-4))
    assert out["x1_range"] == pytest.approx([y[0].min(), y[0].max()], abs=1e-6)
    assert out["velocity_range"] == pytest.approx([y[1].min(), y[1].max()], abs=1e-6)
    assert out["x1_range"][0] <= y[0].min() and out["velocity_range"][1] >= y[1].max()


def test_responses_find_the_cycle_that_coexists_with_stable_sliding():
    from beltmdsm.multistability.responses import responses

    found = responses(stribeck(Vb=2.2), ladder=1.0)
    (r,) = found.responses
    assert r.floquet.autonomous and r.floquet.stable and r.floquet.n_sticks == 1
    # steady sliding is stable at 2.2: the seed's run starts where a stick ends
    assert r.sources == [
        "the run from the end of a stick",
        "cycles continued up from Vb = 1.2",
    ]
    # the same cycle as continued here by hand from the seed at 1.99
    c = cycle(stribeck(Vb=1.99))
    c = cycle(stribeck(Vb=2.2), c.state, c.period)
    assert r.floquet.period == pytest.approx(c.period, rel=1e-9)
    assert r.as_dict()["x1_range"] == pytest.approx(list(c.x1_range), rel=1e-9)
    reasons = {f.source: f.reason for f in found.failed}
    assert "steady sliding is stable at Vb=3.2" in reasons["cycles continued down from Vb = 3.2"]
    # where sliding is unstable, the seed and both ladders find one cycle, listed once
    (r,) = responses(stribeck(Vb=1.5), ladder=0.5).responses
    assert len(r.sources) == 3 and r.run_distance < 1e-4


def test_simulate_starts_on_the_cycle(capsys):
    argv = ["simulate", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.5"]
    argv += ["--start", "periodic", "--perturbation", "0", "--t-end", "100", "--json"]
    assert main(argv + ["--no-progress"]) == 0
    out = json.loads(capsys.readouterr().out)
    c = cycle(stribeck(Vb=1.5))
    assert out["regime"] == "stick_slip" and out["n_reversals"] == 0
    # sampled every 0.02 s: the sampled minimum misses by <= |X1'''| dt^2 / 8 < 1e-4
    assert out["vr_min"] == pytest.approx(c.velocity_range[0] - 1.5, abs=1e-4)
    assert out["n_sticks"] == pytest.approx(100 / c.period, abs=1)
