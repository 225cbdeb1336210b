"""The runtime on a hand-typed 2-DOF mode-coupling model with a bilateral preloaded
contact: nothing in it assumes one coordinate or a contact that can open."""

import numpy as np
import pytest
import reference_two_dof as two
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from beltmdsm.oscillator import (
    System,
    forced_response,
    hopf_points,
    self_excited_cycle,
    simulate,
    steady_sliding,
)
from beltmdsm.oscillator import stick_slip_shooting as _stick_slip
from beltmdsm.oscillator.hybrid import flow


def _typed(p):
    """Stiffness, damping and the steady-sliding Jacobian, typed from the equations."""
    K = np.array([[p["k1"] + p["k3"] / 2, -p["k3"] / 2], [-p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    K_eff = K + np.array([[0.0, p["mu_s"] * p["k_c"]], [0.0, p["k_c"]]])
    C = np.diag([p["c1"], p["c2"]])
    J = np.block([[np.zeros((2, 2)), np.eye(2)], [-K_eff, -C]])
    return K, K_eff, J


def test_flutter_threshold_in_the_friction_coefficient():
    s = System(two)
    # undamped, in closed form: K_eff's eigenvalues coalesce where
    # (K11 - K22 - k_c)^2 + 4 K21 (K12 + mu k_c) = 0, K12 = K21 = -k3/2
    p = s.params
    K, _, _ = _typed(p)
    mu_0 = ((K[0, 0] - K[1, 1] - p["k_c"]) ** 2 / (2 * p["k3"]) + p["k3"] / 2) / p["k_c"]

    def undamped_growth(mu):
        _, _, J = _typed({**p, "mu_s": mu, "c1": 0.0, "c2": 0.0})
        return np.linalg.eigvals(J).real.max()

    assert undamped_growth(mu_0 - 1e-6) < 1e-9 < undamped_growth(mu_0 + 1e-6)
    # damped: the runtime's Hopf point from the derived H_3 against numpy's eigenvalues
    found = hopf_points(s, "mu_s", 0.01, 1.0)
    assert found.size == 1 and found[0] > mu_0  # damping raises the threshold

    def growth(mu):
        return np.linalg.eigvals(_typed({**p, "mu_s": mu})[2]).real.max()

    assert found[0] == pytest.approx(brentq(growth, 0.01, 1.0, xtol=1e-15), abs=1e-10)
    eq = steady_sliding(s.replace(mu_s=0.4))
    assert np.allclose(
        sorted(eq.eigenvalues.real), sorted(np.linalg.eigvals(_typed({**p, "mu_s": 0.4})[2]).real)
    )
    assert not eq.stable and steady_sliding(s.replace(mu_s=0.2)).stable
    assert eq.state.shape == (4,)


def _reference(p, y0, t_end):
    """The hybrid run by solve_ivp, stick by hand: slip back (v_r < 0) until x' = Vb,
    stick (x' = Vb, the normal motion on) while |H| <= mu_s N; switch times and end."""
    K, _, _ = _typed(p)
    Vb, mu, kc, F = p["Vb"], p["mu_s"], p["k_c"], p["F_pre"]

    def normal(z):
        return -p["c2"] * z[3] - K[1, 0] * z[0] - K[1, 1] * z[1] - kc * z[1]

    def slip(t, z):
        ax = -p["c1"] * z[2] - K[0, 0] * z[0] - K[0, 1] * z[1] + mu * (F - kc * z[1])
        return [z[2], z[3], ax, normal(z)]

    def stick(t, z):
        return [Vb, z[3], 0.0, normal(z)]

    def hold(z):
        return abs(p["c1"] * Vb + K[0, 0] * z[0] + K[0, 1] * z[1]) - mu * (F - kc * z[1])

    to_stick = lambda t, z: z[2] - Vb  # noqa: E731
    to_stick.terminal, to_stick.direction = True, 1
    to_slip = lambda t, z: hold(z)  # noqa: E731
    to_slip.terminal, to_slip.direction = True, 1
    t, z, mode, events = 0.0, np.array(y0, float), -1, []
    while t < t_end:
        fun, ev = (slip, to_stick) if mode == -1 else (stick, to_slip)
        sol = solve_ivp(
            fun, (t, t_end), z, method="DOP853", rtol=1e-12, atol=1e-12, events=ev, max_step=0.01
        )
        t, z = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1:
            break
        events.append(t)
        if mode == -1:
            assert hold(z) <= 0, "a reversal: not in this reference"
            z[2], mode = Vb, 0
        else:
            z[2], mode = Vb - 1e-13, -1  # below the event: solve_ivp skips a start on it
    return z, events


def test_stick_slip_run_agrees_with_a_solve_ivp_reference():
    s = System(two, mu_s=0.4)
    run = simulate(s, 60.0, [1.0, 0.0, 0.0, 0.0])
    z, events = _reference(s.params, [1.0, 0.0, 0.0, 0.0], 60.0)
    assert {(a, b) for _, a, b in run.switches} == {(-1, 0), (0, -1)}
    assert len(run.switches) == len(events) >= 10
    assert np.allclose([t for t, _, _ in run.switches], events, atol=1e-7)
    assert np.allclose(run.y[:, -1], z, atol=1e-7)
    assert run.states == ("x", "y", "x_dot", "y_dot")


def test_self_excited_cycle_beyond_flutter():
    s = System(two, mu_s=0.4)
    c = self_excited_cycle(s)
    assert c.kind == "stick_slip" and c.multipliers.shape == (3,)
    # the solve_ivp reference returns to the cycle's state after its period, with the
    # same switch times
    z, events = _reference(s.params, c.state, c.period + 1e-9)
    assert z == pytest.approx(c.state, abs=1e-7)
    assert events[:2] == pytest.approx([t for t, _, _ in c.switches], abs=1e-7)
    # the stick gives a multiplier 0, the trivial one is 1
    assert abs(c.multipliers[-1]) < 1e-10 and abs(c.trivial_multiplier - 1) < 1e-9
    # the monodromy against central differences of the run (Coulomb: mu(0) = mu_s, the
    # friction is continuous where the stick ends)
    cols = []
    for e in np.eye(4):
        plus = flow(s, 0.0, c.state + 1e-5 * e, c.period, mode=c.mode).y
        minus = flow(s, 0.0, c.state - 1e-5 * e, c.period, mode=c.mode).y
        cols.append((plus - minus) / 2e-5)
    M_fd = np.array(cols).T
    assert np.allclose(c.monodromy, M_fd, atol=1e-5)
    w = np.linalg.eigvals(M_fd)
    assert sorted(abs(w)) == pytest.approx(sorted([*abs(c.multipliers), 1.0]), abs=1e-5)
    # and of the return map to the next end of a stick (the section: the trivial
    # multiplier becomes 0 there, the others stay)
    P = []
    for e in np.eye(4):
        ends = [
            _stick_slip._end_states(s, c.state + sign * 1e-5 * e, c.mode, 1, {})[0]
            for sign in (1, -1)
        ]
        P.append((ends[0] - ends[1]) / 2e-5)
    w = np.linalg.eigvals(np.array(P).T)
    assert sorted(abs(w))[-2:] == pytest.approx(sorted(abs(c.multipliers))[-2:], abs=1e-5)


def test_forced_response_below_flutter():
    s = System(two, mu_s=0.2, alpha_t=0.1, Omega_t=1.3)
    r = forced_response(s)
    assert r.switches == [] and r.stable
    # a slip-only response is the linear one about steady sliding: typed by hand,
    # (K_eff - W^2 I + i W C) X = (amplitude on x), x = Re(X e^(i W t))
    p = s.params
    _, K_eff, _ = _typed(p)
    W = p["Omega_t"]
    X = np.linalg.solve(K_eff - W**2 * np.eye(2) + 1j * W * np.diag([p["c1"], p["c2"]]), [0.1, 0])
    eq = steady_sliding(s)
    assert r.state[:2] == pytest.approx(eq.state[:2] + X.real, abs=1e-9)
    assert r.state[2:] == pytest.approx((1j * W * X).real, abs=1e-9)
    _, _, J = _typed(p)
    assert sorted(abs(r.multipliers)) == pytest.approx(
        sorted(abs(np.exp(np.linalg.eigvals(J) * r.period))), rel=1e-8
    )
