"""Static above kinetic friction (``friction="static_kinetic"``, derive/laws.py): stick held
up to ``mu_s F``, slip at ``mu_k F``, through simulation, saltation matrices and Floquet.

References, each independent of what it checks:

* the undamped belt oscillator (``beta1 = 0``, no excitation, constant normal force
  ``F = g``, ``omega1 = w``): its stick-slip cycle in closed form, derived here. With
  ``x_s = mu_s F / w^2`` and ``x_k = mu_k F / w^2``, stick ends where the spring force
  reaches the static bound, ``X1 = x_s``; the slip is a harmonic arc about ``x_k``
  starting at ``d = x_s - x_k`` with velocity ``Vb``, and it ends where ``X1' = Vb``
  again, by energy at ``X1 - x_k = -d``, after the phase angle ``pi + 2 atan(Vb / (w d))``;
  the mass then sticks (``|w^2 (x_k - d)| <= mu_s F``) and rides the belt at ``Vb`` back
  to ``x_s``, for ``2 d / Vb``;
* the saltation matrix of leaving stick, typed by hand from ``S = I + (f+ - f-) n^T /
  (n . f-)`` on that oscillator, and the finite-difference Jacobian of the simulated flow
  across the switch;
* Den Hartog's forced oscillator (``Vb = 0``, tangential force ``F0 sin(Omega t)``, constant
  normal force) with ``r_k = mu_k g / F0 = 0.3``, ``r_s = mu_s g / F0 = 0.4`` at
  ``Omega = 3 omega1``, whose periodic orbit moves without stops and reverses twice per
  period: the multipliers of both Floquet engines against central finite differences of
  the period map simulated by the event-driven integrator; the same forcing at
  ``Omega = omega1 / 2`` on a slow belt, whose orbit sticks twice a period and leaves
  stick with the jump of the acceleration, likewise;
* Coulomb's law with ``mu_s = mu_k`` for what the MDSM predicts (it averages the slip law).

Error model. The event-driven runs at ``rtol = atol = 1e-12`` locate a switch and carry
the state to about 1e-11 (measured: 3e-11 on the first stick, 1e-12 per period later);
the closed-form cycle is compared to 1e-8. A central difference with step ``h`` has a
truncation error of order ``h^2`` times the map's third derivative (order 1 here) and
a rounding error of order ``1e-11 / h``: with ``h = 1e-5`` both are below 1e-6, the
tolerance of the Jacobians and multipliers; the law's error that these checks exclude
(the static bound used at a reversal, issue 29) moved the determinant by 40 %.
"""

import json
import math

import numpy as np
import pytest

import beltmdsm
from beltmdsm.cli import main
from beltmdsm.excitation import initial_state
from beltmdsm.generated import hybrid, unforced
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet

G = 9.81
TIGHT = dict(rtol=1e-12, atol=1e-12, solver="events", t_discard=0.0)


def _belt_oscillator(mu_s=0.4, mu_k=0.25, w=1.0, Vb=1.0):
    return Model(
        friction="static_kinetic", mu_s=mu_s, mu_k=mu_k, beta1=0.0, omega1=w, Vb=Vb, alpha=0.0, g=G
    )


def _state_at(sim, t):
    return sim.run.trajectory.state(np.array([t]))[:, 0]


@pytest.mark.parametrize("solver", ["events", "superposition"])
def test_the_undamped_belt_oscillators_stick_slip_cycle_is_the_closed_form(solver):
    mu_s, mu_k, w, Vb = 0.4, 0.25, 1.0, 1.0
    m = _belt_oscillator(mu_s, mu_k, w, Vb)
    x_s, x_k = mu_s * G / w**2, mu_k * G / w**2
    d = x_s - x_k
    stick = 2 * d / Vb
    slip = (math.pi + 2 * math.atan(Vb / (w * d))) / w
    # start where a stick begins: X1 = x_k - d, riding the belt; the normal state at
    # its equilibrium, where F = g
    y0 = initial_state(m)
    y0[:2] = (x_k - d, Vb)
    run = {**TIGHT, "solver": solver}
    sim = beltmdsm.simulate(m, y0=y0, t_end=3.2 * (stick + slip), dt=0.05, **run)
    assert sim.solver_used == solver
    unstick = [t for t, kind, _ in sim.events if kind == "unstick"]
    sticks = [t for t, kind, mode in sim.events if kind == "vr_zero" and mode == 0]
    assert len(unstick) == 3 and len(sticks) == 3
    assert len(sim.events) == 6  # nothing but sticks and unsticks
    assert unstick[0] == pytest.approx(stick, abs=1e-8)
    for k in range(3):
        assert sticks[k] - unstick[k] == pytest.approx(slip, abs=1e-8)
        if k:
            assert unstick[k] - sticks[k - 1] == pytest.approx(stick, abs=1e-8)
            assert unstick[k] - unstick[k - 1] == pytest.approx(stick + slip, abs=1e-8)
    # the static bound ends the stick, the kinetic coefficient centres the slip
    assert _state_at(sim, unstick[1])[0] == pytest.approx(x_s, abs=1e-8)
    assert _state_at(sim, sticks[1])[0] == pytest.approx(x_k - d, abs=1e-8)
    assert sim.summary.regime == "stick_slip"


def test_the_self_excited_cycle_by_shooting_is_the_closed_form():
    # issue 29: the autonomous cycle of beltmdsm.periodic.cycle (period unknown, phase
    # condition) on the same oscillator, against the same closed form; its stick phase
    # gives a multiplier 0, and it coexists with steady sliding (constant mu_k: stable
    # for beta1 > 0, neutral here), which the static bound alone makes possible
    mu_s, mu_k, w, Vb = 0.4, 0.25, 1.0, 1.0
    x_s, x_k = mu_s * G / w**2, mu_k * G / w**2
    d = x_s - x_k
    period = 2 * d / Vb + (math.pi + 2 * math.atan(Vb / (w * d))) / w
    c = beltmdsm.cycle(_belt_oscillator(mu_s, mu_k, w, Vb))
    assert c.period == pytest.approx(period, abs=1e-8)
    assert c.n_sticks == 1 and c.n_reversals == 0 and c.stable
    assert c.stick_time == pytest.approx(2 * d / Vb, abs=1e-8)
    # the slip's harmonic arc about x_k, of amplitude A (it starts at d with velocity
    # Vb), spans X1 beyond the stick's [x_k - d, x_s] on both sides
    A = math.hypot(d, Vb / w)
    assert c.x1_range == pytest.approx((x_k - A, x_k + A), abs=1e-8)
    assert c.velocity_range == pytest.approx((-A * w, Vb), abs=1e-8)
    assert min(abs(c.multipliers)) < 1e-12 and abs(c.trivial_multiplier - 1) < 1e-8


def test_the_saltation_of_leaving_stick_is_the_flows_jacobian_across_the_switch():
    """Stick ends on ``stick_back`` (``h = mu_s F + a_free``, ``a_free = -w^2 X1``) into
    ``slip_back``: ``f+ - f- = (0, -(mu_s - mu_k) F)``, ``n = (-w^2, 0)``, ``n . f- =
    -w^2 Vb``, so ``S = I + [[0, 0], [-(mu_s - mu_k) F / Vb, 0]]`` (the identity for
    Coulomb's law, where the acceleration does not jump)."""
    mu_s, mu_k, w, Vb = 0.4, 0.25, 1.0, 1.0
    m = _belt_oscillator(mu_s, mu_k, w, Vb)
    x_s = mu_s * G / w**2
    y0 = initial_state(m)
    S = np.array(
        hybrid.bind_saltation(
            before="stick", after="slip_back", surface="stick_back", backend="python",
            **m.arguments(hybrid.bind_saltation),
        )(0.0, x_s, Vb, y0[2], 0.0)
    ).reshape(4, 4)  # fmt: skip
    by_hand = np.eye(2) + np.array([[0.0, 0.0], [-(mu_s - mu_k) * G / Vb, 0.0]])
    assert np.allclose(S[:2, :2], by_hand, rtol=0, atol=1e-13)
    # the flow from 0.1 s before the unstick to 0.1 s after it; X1 is the direction of
    # the stick mode's state (X1' = Vb holds there): its Jacobian column is
    # Phi_slip(0.1) S (1, 0) with the harmonic state transition of the slip
    before = after = 0.1
    h = 1e-5

    def flow(x1):
        y = y0.copy()
        y[:2] = (x1, Vb)
        sim = beltmdsm.simulate(m, y0=y, t_end=before + after, dt=0.005, **TIGHT)
        assert [kind for _, kind, _ in sim.events] == ["unstick"]
        return _state_at(sim, before + after)[:2]

    start = x_s - Vb * before
    column = (flow(start + h) - flow(start - h)) / (2 * h)
    c, s = math.cos(w * after), math.sin(w * after)
    phi_slip = np.array([[c, s / w], [-w * s, c]])
    assert np.allclose(column, phi_slip @ by_hand[:, 0], rtol=0, atol=1e-6)
    coulomb = phi_slip @ np.array([1.0, 0.0])
    assert abs(column[1] - coulomb[1]) > 1.0  # the jump's share: (mu_s - mu_k) F / Vb


def _den_hartog(W=3.0, r_k=0.3, r_s=0.4):
    F0 = G  # mu = r F0 / g
    return Model(
        friction="static_kinetic", mu_s=r_s * F0 / G, mu_k=r_k * F0 / G, beta1=0.0,
        omega1=1.0, Vb=0.0, alpha_t=F0 / W**2, Omega_t=W, alpha_n=0.0, Omega_n=W, g=G,
    )  # fmt: skip


def _period_map_jacobian(m, x0, T, h=1e-5):
    J = np.zeros((4, 4))
    for j in range(4):
        step = np.zeros(4)
        step[j] = h
        ends = [
            _state_at(beltmdsm.simulate(m, y0=x0 + s, t_end=T, dt=T / 32, **TIGHT), T)
            for s in (step, -step)
        ]
        J[:, j] = (ends[0] - ends[1]) / (2 * h)
    return J


def test_den_hartogs_orbit_multipliers_on_both_engines_are_the_period_maps():
    m = _den_hartog()
    closed, general = floquet(m, engine="closed_form"), floquet(m, engine="general")
    assert closed.engine == "closed_form" and general.engine == "general"
    assert closed.n_reversals == general.n_reversals == 2
    assert closed.n_sticks == general.n_sticks == 0
    r = general.response
    J = _period_map_jacobian(m, r.state0, r.period)
    fd_t = np.linalg.eigvals(J[:2, :2])
    fd_all = np.linalg.eigvals(J)
    # the tangential pair: det is the product of the reversals' a+/a- (beta1 = 0), with
    # mu_k on both sides of each reversal
    det_fd = np.linalg.det(J[:2, :2])
    assert np.linalg.det(closed.response.monodromy_tangential) == pytest.approx(det_fd, abs=1e-6)
    assert np.linalg.det(r.monodromy[:2, :2]) == pytest.approx(det_fd, abs=1e-6)
    assert np.sort_complex(closed.multipliers[:2]) == pytest.approx(np.sort_complex(fd_t), abs=1e-6)
    assert np.sort_complex(general.multipliers) == pytest.approx(np.sort_complex(fd_all), abs=1e-6)
    assert np.allclose(r.monodromy, J, rtol=0, atol=1e-5 * np.abs(J).max())
    assert general.stable and closed.stable


def test_a_forced_stick_slip_orbits_multipliers_are_the_period_maps():
    """Den Hartog's forcing at Omega = omega1 / 2 on a belt (Vb = 0.2, beta1 = 0.1): two
    stick phases per period, each left with the acceleration's jump (mu_s - mu_k) F, whose
    saltation (S21 = -(mu_s - mu_k) F / Vb, about -4.9 here) the one nonzero tangential
    multiplier carries; a stick makes the other zero."""
    W = 0.5
    m = _den_hartog(W).replace(Vb=0.2, beta1=0.1)
    closed, general = floquet(m, engine="closed_form"), floquet(m, engine="general")
    assert closed.n_sticks == general.n_sticks == 2 and general.n_reversals == 0
    r = general.response
    kinds = {(int(b), int(a), s) for _, b, a, s in r.switches}
    assert (0, -1, "stick_back") in kinds and (0, 1, "stick_forward") in kinds
    J = _period_map_jacobian(m, r.state0, r.period)
    assert np.allclose(r.monodromy, J, rtol=0, atol=1e-6)
    assert np.allclose(closed.response.monodromy_tangential, J[:2, :2], rtol=0, atol=1e-6)
    (fd,) = [z for z in np.linalg.eigvals(J[:2, :2]) if abs(z) > 1e-6]
    for f in (closed, general):
        big = [z for z in f.multipliers if abs(z) > 0.1]
        assert big[0] == pytest.approx(fd, abs=1e-6), f.engine
    assert min(abs(z) for z in closed.multipliers[:2]) < 1e-12  # the stick's zero


def test_command_line_simulate_and_floquet_under_static_kinetic(capsys):
    W = 3.0
    args = [
        "--friction", "static_kinetic", "--mu_k", "0.3", "--mu_s", "0.4", "--beta1", "0",
        "--Vb", "0", "--alpha_t", str(G / W**2), "--Omega_t", str(W), "--alpha_n", "0",
        "--Omega_n", str(W),
    ]  # fmt: skip
    assert main(["floquet", *args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["friction"] == "static_kinetic" and out["params"]["mu_k"] == 0.3
    assert out["engine"] == "closed_form" and out["stable"] is True
    assert (out["n_reversals"], out["n_sticks"]) == (2, 0)
    ref = floquet(_den_hartog(W))
    assert out["max_abs_multiplier"] == pytest.approx(ref.max_abs_multiplier, rel=1e-12)
    T, t_end = 2 * math.pi / W, 100.0
    assert main(["simulate", *args, "--t-end", str(t_end), "--json"]) == 0
    run = json.loads(capsys.readouterr().out)
    assert run["friction"] == "static_kinetic" and run["regime"] == "sliding_with_reversals"
    # from rest at X1 = mu_k g / omega1^2 the run settles on the stable orbit: its two
    # reversals per period, and no stick after the first
    assert abs(run["n_reversals"] - 2 * t_end / T) <= 3 and run["n_sticks"] <= 1


def test_mu_k_belongs_to_both_laws_that_list_it_and_to_no_other():
    assert Model(friction="static_kinetic", mu_k=0.2)["mu_k"] == 0.2
    assert Model(friction="stribeck", mu_k=0.2)["mu_k"] == 0.2
    assert "mu_k" not in Model().params  # Coulomb's model has no kinetic coefficient
    with pytest.raises(ValueError, match="'stribeck' or 'static_kinetic', not chosen"):
        Model(mu_k=0.2)
    # a law's parameter goes with the law, and stays where the next law lists it too
    m = Model(friction="stribeck", mu_k=0.2, v_s=2.0).replace(friction="static_kinetic")
    assert m["mu_k"] == 0.2 and "v_s" not in m.params


def test_predict_averages_the_kinetic_coefficient_and_says_what_it_leaves_out():
    """The MDSM averages the slip law over a fast motion that passes Vr = 0: static above
    kinetic predicts what Coulomb's law with mu_s = mu_k does, and each analysis notes
    the static bound it cannot see."""
    from beltmdsm.prediction.prediction import predict

    got = predict(Model(friction="static_kinetic", mu_s=0.4, mu_k=0.25), points=60)
    coulomb = predict(Model(friction="coulomb", mu_s=0.25), points=60)
    for key in got.ANALYSES:
        assert getattr(got, key) == getattr(coulomb, key), key
        assert "static bound mu_s bounds stick only" in got.reasons[key]
        assert "friction='static_kinetic'" in got.reasons[key] and "\n" not in got.reasons[key]
    assert got.paper_tangential_vhat  # not empty: a check that compares something


def test_a_static_bound_below_the_kinetic_coefficient_is_refused_by_name(capsys):
    """mu_k > mu_s would let slip hold more than stick: at Vr = 0 with mu_s F < |a_free|
    <= mu_k F neither mode is consistent. Refused once, where the model is built."""
    assert Model(friction="static_kinetic", mu_s=0.3, mu_k=0.3)["mu_k"] == 0.3  # Coulomb's
    with pytest.raises(ValueError, match=r"static_kinetic.*mu_k exceeds its static bound mu_s"):
        Model(friction="static_kinetic", mu_s=0.3, mu_k=0.31)
    assert Model(friction="stribeck", mu_s=0.3, mu_k=0.5)["mu_k"] == 0.5  # rising: its own
    args = ["simulate", "--friction", "static_kinetic", "--mu_k", "0.5", "--t-end", "10"]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "choose mu_k <= mu_s" in err[0]


def test_a_stick_slip_cycle_coexists_with_stable_sliding_without_a_hopf_point():
    # a constant kinetic coefficient leaves steady sliding stable (no Hopf point), yet the
    # static bound keeps a stick-slip cycle beside it: coexistence finds it by seeding
    # where a stick ends, and says hysteresis where both are stable
    m = Model(friction="static_kinetic", mu_k=0.25, beta1=0.05, alpha=0.0, Vb=1.0)
    c = beltmdsm.coexistence(m, "Vb", 0.5, 2.0)
    assert not c.hopf and c.branch is not None
    ((lo, hi),) = [r.range for r in c.ranges]
    assert lo == 0.5 and 1.0 < hi < 2.0
    # at Vb = 1, independently: the cycle by shooting is stable and so is steady sliding
    assert beltmdsm.cycle(m).stable
    lam = np.asarray(unforced.eigenvalues(**m.arguments(unforced.eigenvalues)), dtype=complex)
    assert np.max(lam.real) < 0
