"""The generated ``hoffmann`` (Hoffmann, Fischer and Gaul 2002, as derive/models/entries.py
reads it) through the runtime: the flutter threshold, the self-excited stick-slip cycle
beyond it and its multipliers, each against a reference typed here.

As read there: a mass m at x (along the belt) and y (into the belt), springs k1 (x),
k2 (y) and k3 at 45 degrees, K = [[k1 + k3/2, k3/2], [k3/2, k2 + k3/2]], dampers c1, c2;
the normal force N = F_pre + k_c y (bilateral), friction mu N against v_r = x' - Vb:

    m x'' + c1 x' + K11 x + K12 y = -mu N sgn(v_r),
    m y'' + c2 y' + K21 x + (K22 + k_c) y = 0.

The tests' hand-typed 2-DOF module (reference_two_dof.py) is the same model per unit mass
with y pointing away from the belt (y -> -y): the kernels are compared through that map.
"""

import math

import numpy as np
import pytest
import reference_two_dof as two
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from beltmdsm.generated.models import hoffmann as gen
from beltmdsm.oscillator import System, hopf_points, self_excited_cycle, simulate, steady_sliding
from beltmdsm.oscillator import stick_slip_shooting as _stick_slip
from beltmdsm.oscillator.hybrid import flow

#: reference_two_dof's base set, in the generated module's names (m = 1).
BASE = dict(k1=1.25, k2=0.25, k3=0.5, k_c=1.0, F_pre=1.0, c1=0.05, c2=0.05, Vb=1.0)
#: y -> -y: the reference's state of the generated module's.
FLIP = np.diag([1.0, -1.0, 1.0, -1.0])


def _typed(p):
    """Stiffness, the steady-sliding stiffness (mode -1: +mu N on x) and Jacobian."""
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    K_eff = K + np.array([[0.0, -p["mu_s"] * p["k_c"]], [0.0, p["k_c"]]])
    C = np.diag([p["c1"], p["c2"]])
    J = np.block([[np.zeros((2, 2)), np.eye(2)], [-K_eff / p["m"], -C / p["m"]]])
    return K, K_eff, J


def test_generated_kernels_agree_with_the_hand_typed_two_dof():
    kg, kr = gen.kernels("coulomb"), two.kernels("coulomb")
    rng = np.random.default_rng(39)
    worst = 0.0
    for _ in range(40):
        q = {
            n: gen.DEFAULTS[n] * math.exp(rng.uniform(-0.5, 0.5)) for n in gen.PARAMETERS["coulomb"]
        }
        q["m"] = 1.0
        r = {**two.DEFAULTS, **q, "alpha_t": 0.0}
        pg = np.array([q[n] for n in gen.PARAMETERS["coulomb"]])
        pr = np.array([r[n] for n in two.PARAMETERS["coulomb"]])
        t = rng.uniform(0.0, 10.0)
        y = rng.normal(size=4) + [0, 0, q["Vb"], 0]
        # the error model: rounding of the largest term of the equations of motion
        scale = max(np.abs(_typed(q)[1]).max() * np.abs(y[:2]).max(), q["F_pre"], 1.0)

        def agree(a, b, scale=scale):
            nonlocal worst
            err = np.max(np.abs(np.asarray(a, float) - np.asarray(b, float))) / scale
            assert np.isfinite(err)
            worst = max(worst, err)

        for mode in (-1, 0, 1):
            agree(kg.field(t, y, pg, mode), FLIP @ kr.field(t, FLIP @ y, pr, mode))
            agree(kg.jacobian(t, y, pg, mode), FLIP @ kr.jacobian(t, FLIP @ y, pr, mode) @ FLIP)
            for name in ("slip_acceleration", "friction_force"):
                agree(getattr(kg, name)(t, y, pg, mode), getattr(kr, name)(t, FLIP @ y, pr, mode))
        for name in ("normal_force", "holding_force", "stick_limit", "slip_velocity"):
            agree(getattr(kg, name)(t, y, pg), getattr(kr, name)(t, FLIP @ y, pr))
        agree(kg.slip_gradient(t, y, pg), kr.slip_gradient(t, FLIP @ y, pr) @ FLIP, 1.0)
        agree(kg.equilibrium(pg), FLIP @ kr.equilibrium(pr))
        agree(kg.characteristic(pg), kr.characteristic(pr), scale**4)
        agree(kg.hurwitz(pg), kr.hurwitz(pr), scale**10)
        # slip's end (the surface v_r = 0 is the state's own; S relative to its condition)
        for before, after in ((-1, 0), (1, 0), (-1, 1), (1, -1)):
            S = FLIP @ kr.saltation(t, FLIP @ y, pr, before, after) @ FLIP
            rate = abs(kr.slip_acceleration(t, FLIP @ y, pr, before))
            agree(kg.saltation(t, y, pg, before, after), S, np.abs(S).max() * scale / rate)
    assert kg.gap is None and not gen.UNILATERAL and gen.EXCITATION == ()
    assert worst < 2e-14, worst


def test_flutter_threshold_in_the_friction_coefficient():
    s = System("hoffmann", **BASE)
    p = {**s.params}
    K, _, _ = _typed(p)
    # undamped, in closed form: K_eff's eigenvalues coalesce where
    # (K11 - K22 - k_c)^2 + 4 K21 (K12 - mu k_c) = 0
    mu_0 = ((K[0, 0] - K[1, 1] - p["k_c"]) ** 2 + 4 * K[1, 0] * K[0, 1]) / (4 * K[1, 0] * p["k_c"])
    assert mu_0 == pytest.approx(0.25, rel=1e-15)  # ((k1 - k2 - k_c)^2 + k3^2) / (2 k3 k_c)
    undamped = s.replace(c1=0.0, c2=0.0)

    def numpy_growth(mu):
        return np.linalg.eigvals(_typed({**p, "c1": 0.0, "c2": 0.0, "mu_s": mu})[2]).real.max()

    assert numpy_growth(mu_0 - 1e-6) < 1e-12 < 1e-5 < numpy_growth(mu_0 + 1e-6)
    # the runtime's eigenvalues of steady sliding: the threshold where its growth rate
    # leaves 0 (~ sqrt(mu - mu_0) beyond; rounding moves it by < 1e-12 off coalescence)
    lo, hi = 0.1, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (
            (mid, hi)
            if steady_sliding(undamped.replace(mu_s=mid)).growth_rate < 1e-9
            else (lo, mid)
        )
    assert hi == pytest.approx(mu_0, abs=1e-9)
    # damped: the runtime's Hopf point from the derived Hurwitz determinants against
    # numpy's eigenvalues of the Jacobian typed here
    found = hopf_points(s, "mu_s", 0.01, 1.0)
    assert found.size == 1 and found[0] > mu_0  # equal damping raises the threshold

    def growth(mu):
        return np.linalg.eigvals(_typed({**p, "mu_s": mu})[2]).real.max()

    assert found[0] == pytest.approx(brentq(growth, 0.01, 1.0, xtol=1e-15), abs=1e-10)
    for mu in (0.2, 0.4):
        eq = steady_sliding(s.replace(mu_s=mu))
        typed = np.linalg.eigvals(_typed({**p, "mu_s": mu})[2])
        assert np.allclose(
            sorted(eq.eigenvalues, key=lambda z: (z.real, z.imag)),
            sorted(typed, key=lambda z: (z.real, z.imag)),
            atol=1e-12,
        )
        assert eq.stable == (mu < found[0]) and eq.mode == -1 and eq.state.shape == (4,)
        assert all(eq.hurwitz > 0) == eq.stable


def _reference(p, y0, t_end):
    """The hybrid run by solve_ivp, stick by hand: slip back (v_r < 0) until x' = Vb,
    stick (x' = Vb, the normal motion on) while |H| <= mu_s N; switch times and end."""
    K, _, _ = _typed(p)
    m, Vb, mu, kc, F = p["m"], p["Vb"], p["mu_s"], p["k_c"], p["F_pre"]

    def normal(z):
        return (-p["c2"] * z[3] - K[1, 0] * z[0] - (K[1, 1] + kc) * z[1]) / m

    def slip(t, z):
        ax = (-p["c1"] * z[2] - K[0, 0] * z[0] - K[0, 1] * z[1] + mu * (F + kc * z[1])) / m
        return [z[2], z[3], ax, normal(z)]

    def stick(t, z):
        return [Vb, z[3], 0.0, normal(z)]

    def hold(z):
        return abs(p["c1"] * Vb + K[0, 0] * z[0] + K[0, 1] * z[1]) - mu * (F + kc * z[1])

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
    s = System("hoffmann", m=2.0, **{k: 2 * v if k not in ("Vb",) else v for k, v in BASE.items()})
    run = simulate(s, 60.0, [1.0, 0.0, 0.0, 0.0])
    z, events = _reference(s.params, [1.0, 0.0, 0.0, 0.0], 60.0)
    assert {(a, b) for _, a, b in run.switches} == {(-1, 0), (0, -1)}
    assert len(run.switches) == len(events) >= 10
    assert np.allclose([t for t, _, _ in run.switches], events, atol=1e-7)
    assert np.allclose(run.y[:, -1], z, atol=1e-7)
    assert run.states == ("x", "y", "x_dot", "y_dot")


def test_self_excited_cycle_beyond_flutter():
    s = System("hoffmann", mu_s=0.4, **BASE)
    c = self_excited_cycle(s)
    assert c.kind == "stick_slip" and c.multipliers.shape == (3,) and c.sticks == 1
    # the solve_ivp reference returns to the cycle's state after its period, with the
    # same switch times
    z, events = _reference(s.params, c.state, c.period + 1e-9)
    assert z == pytest.approx(c.state, abs=1e-7)
    assert events[:2] == pytest.approx([t for t, _, _ in c.switches], abs=1e-7)
    # the same cycle per unit mass: m = 2 with every force doubled
    heavy = System(
        "hoffmann", m=2.0, mu_s=0.4, **{k: 2 * v if k != "Vb" else v for k, v in BASE.items()}
    )
    twin = self_excited_cycle(heavy)
    assert twin.period == pytest.approx(c.period, rel=1e-10)
    assert twin.state == pytest.approx(c.state, abs=1e-9)
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

    # and of the return map to the next end of a stick (the section: the trivial
    # multiplier becomes 0 there, the others stay), conjugated by the flow over 0.5 s:
    # the perturbed starts lie inside the slip phase, not on the stick end, where half
    # of them would start in the friction cone and stick at once (a touch of v_r = 0)
    def later(y, mode):
        return flow(s, 0.0, y, 0.5, mode=mode)

    half = later(c.state, c.mode)
    P = []
    for e in np.eye(4):
        ends = [
            later(
                _stick_slip._end_states(s, half.y + sign * 1e-5 * e, half.mode, 1, {})[0], c.mode
            ).y
            for sign in (1, -1)
        ]
        P.append((ends[0] - ends[1]) / 2e-5)
    w = np.linalg.eigvals(np.array(P).T)
    assert sorted(abs(w))[-2:] == pytest.approx(sorted(abs(c.multipliers))[-2:], abs=1e-5)
    # least period: asked for two sticks a period, the shooting reports one
    twice = _stick_slip._newton_stick(s, c.state, c.mode, 2, 30, dict(rtol=1e-11, atol=1e-11))
    assert twice.sticks == 1 and twice.period == pytest.approx(c.period, rel=1e-12)
