"""Another model's self-excited cycles on the one continuation driver (issue 39):
`beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`, walked from the Hopf
point by `beltmdsm.oscillator.hopf_branch` and both ways by
`beltmdsm.branches.continue_branch`.

The references are computed here, independently of the package: the equations typed by
hand, their cycles by scipy's solve_ivp (DOP853, rtol 1e-12) with an event on the
section where the slip speed is least (the velocity along the belt at its largest:
``x'' = 0`` falling), fsolve on that return map, and its multipliers (the cycle's
Floquet multipliers but the trivial one) by central differences of the map.

The typed equations, per unit mass, slip backwards (``v_r = x' - Vb < 0``), Stribeck's
``mu(v) = mu_k + (mu_s - mu_k) exp(-|v| / v_s)``:

* belt_1dof: ``x'' + 2 beta1 omega1 x' + omega1^2 x = mu(v_r) g``;
* hoffmann (``m = 1``): ``x'' + c1 x' + K11 x + K12 y = mu(v_r) N``, ``y'' + c2 y' + K21 x
  + (K22 + k_c) y = 0``, ``N = F_pre + k_c y``, ``K = [[k1 + k3/2, k3/2], [k3/2, k2 +
  k3/2]]``.
"""

import json
import math

import numpy as np
import pytest
from inprocess import cli
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

from beltmdsm import Model, cycle
from beltmdsm.branches import continue_branch
from beltmdsm.continuation.oscillator_cycle import TOL, OscillatorCycleProblem
from beltmdsm.oscillator import System, hopf_points, self_excited_cycle, stick_onset
from beltmdsm.oscillator.cycle import NEWTON_TOL
from beltmdsm.oscillator.hopf_branch import hopf_branch

#: The unstable slip cycle of the Stribeck belt at Vb = 2.5 (docs/modelling.md), a guess.
SLIP_GUESS = ([3.0182035, 2.0991444], 6.3203187)


def _mu(p, v_r):
    return p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-abs(v_r) / p["v_s"])


def _belt(p):
    """The belt's field and the state on the section with ``x' = v``."""
    w, z, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]

    def rhs(t, u):
        return [u[1], -2 * z * w * u[1] - w * w * u[0] + _mu(p, u[1] - Vb) * g]

    def on_section(free):  # x'' = 0: x from x'
        (v,) = free
        return np.array([(-2 * z * w * v + _mu(p, v - Vb) * g) / w**2, v])

    return rhs, on_section, [1]


def _hoffmann(p):
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    kc, F, Vb, m = p["k_c"], p["F_pre"], p["Vb"], p["m"]

    def rhs(t, u):
        x, y, vx, vy = u
        N = F + kc * y
        ax = (-p["c1"] * vx - K[0, 0] * x - K[0, 1] * y + _mu(p, vx - Vb) * N) / m
        ay = (-p["c2"] * vy - K[1, 0] * x - (K[1, 1] + kc) * y) / m
        return [vx, vy, ax, ay]

    def on_section(free):  # x'' = 0: x from (y, x', y')
        y, vx, vy = free
        x = (-p["c1"] * vx - K[0, 1] * y + _mu(p, vx - Vb) * (F + kc * y)) / K[0, 0]
        return np.array([x, y, vx, vy])

    return rhs, on_section, [1, 2, 3]


def _return_map(rhs, on_section, free, accel):
    """``u -> (u', T)``: from the section state of the free coordinates ``u`` to the next
    crossing of ``x'' = 0`` falling (``accel(state)`` is ``x''``)."""

    def event(t, u):
        return accel(u)

    event.terminal, event.direction = True, -1

    def image(u):
        state = on_section(u)
        # past the start (where the event function is 0) before arming the event
        first = solve_ivp(rhs, (0, 0.5), state, method="DOP853", rtol=1e-12, atol=1e-13)
        sol = solve_ivp(rhs, (0.5, 200.0), first.y[:, -1], method="DOP853", rtol=1e-12,
                        atol=1e-13, events=event)  # fmt: skip
        assert sol.status == 1
        end = sol.y_events[0][0]
        return end[free], sol.t_events[0][0]

    return image


def _reference(system, start, typed):
    """The cycle through the section near ``start`` (a state of it): its state, period
    and multipliers (but the trivial one), all from the typed equations."""
    rhs, on_section, free = typed(system.params)
    image = _return_map(rhs, on_section, free, lambda u: rhs(0, u)[len(u) // 2])
    u = fsolve(lambda u: image(u)[0] - u, np.asarray(start, float)[free], xtol=1e-13)
    _, T = image(u)
    h = 1e-5
    D = np.array([(image(u + h * e)[0] - image(u - h * e)[0]) / (2 * h) for e in np.eye(u.size)]).T
    return on_section(u), T, np.linalg.eigvals(D)


def test_stribeck_belt_cycles_from_the_hopf_point_to_the_stick_onset():
    s = System("belt_1dof", friction="stribeck")
    p = s.params
    typed = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    (h,) = hopf_points(s, "Vb", 0.5, 5.0)
    assert h == pytest.approx(typed, abs=1e-10)
    b = hopf_branch(s, "Vb", float(h), 4.5, (0.5, 5.0))
    # subcritical: unstable slip cycles above the Hopf point, up to the stick onset, which
    # ends the walk (no fold, no period doubling, no torus before it)
    assert b.criticality == "subcritical" and b.side == 1 and not b.failure
    assert [sp.kind for sp in b.special] == ["stick_onset"]
    values = [c.system.params["Vb"] for c in b.cycles]
    assert all(np.diff(values) > 0) and all(not c.stable for c in b.cycles)
    # the onset: the cycle grazes v_r = 0 there, at the value `stick_onset` finds by its
    # own secant on the least slip speed, each cycle shot at a fixed Vb
    onset = b.onset.system.params["Vb"]
    assert b.onset is b.cycles[-1] and onset == pytest.approx(b.special[-1].value, abs=0)
    assert abs(b.onset.state[1] - onset) <= 1e-9
    other = stick_onset(self_excited_cycle(s.replace(Vb=2.5), *SLIP_GUESS), "Vb", 0.2)
    # each within its own accuracy: the special point's, and the secant's last step
    # (its least slip speed 1e-12 of the state's scale, over a slope of order 1)
    assert onset == pytest.approx(other.system.params["Vb"], abs=b.special[-1].accuracy + 1e-10)
    # a cycle half-way: the solve_ivp reference, its period, section state, amplitude and
    # multiplier (finite differences of the return map)
    mid = min(b.cycles, key=lambda c: abs(c.system.params["Vb"] - 0.5 * (h + onset)))
    state, T, (mult,) = _reference(mid.system, mid.state, _belt)
    assert mid.period == pytest.approx(T, rel=1e-9)
    assert mid.state == pytest.approx(state, abs=1e-9)
    assert mid.multipliers[0].real == pytest.approx(mult.real, rel=1e-6)
    assert abs(mid.multipliers[0].imag) == 0 and mult.real > 1.0


def test_stribeck_belt_amplitude_against_the_reference():
    c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5), *SLIP_GUESS)
    b = continue_branch(c, "Vb", 2.4, 2.6)
    q = b.point_near(2.5)
    assert q.value == 2.5
    rhs, on_section, free = _belt(q.system.params)
    state, T, _ = _reference(q.system, q.state, _belt)
    # the extremes of x' over one period of the reference: the section (largest) and the
    # least, where x'' rises through 0
    low = lambda t, u: rhs(t, u)[1]  # noqa: E731
    low.direction = 1
    sol = solve_ivp(rhs, (0, T), state, method="DOP853", rtol=1e-12, atol=1e-13, events=low)
    amplitude = 0.5 * (state[1] - sol.y_events[0][0][1])
    obs = q.observables()
    # orbit_observables refines the sampled extremes by a parabola: error below 2e-9 of
    # the amplitude (beltmdsm/oscillator/orbit.py)
    assert obs["x_dot_amplitude"] == pytest.approx(amplitude, abs=1e-8)
    assert obs["period"] == pytest.approx(T, rel=1e-9)
    assert obs["max_abs_v_r"] == pytest.approx(
        q.system.params["Vb"] - sol.y_events[0][0][1], abs=1e-8
    )
    assert obs["max_abs_multiplier"] == q.max_abs_multiplier > 1.0


def test_hoffmann_stribeck_cycles_beyond_the_hopf_point_meet_solve_ivp():
    """Hoffmann's model under Stribeck's law: steady sliding loses stability below a Vb
    (the falling friction characteristic pumps the coupled modes); the cycles born
    there are unstable slip cycles up to their stick onset. One of them against the
    reference, its three multipliers against the 3 x 3 return map's differences."""
    s = System("hoffmann", friction="stribeck")
    (h,) = hopf_points(s, "Vb", 0.2, 8.0)
    b = hopf_branch(s, "Vb", float(h), 0.1)
    assert b.criticality == "subcritical" and [sp.kind for sp in b.special] == ["stick_onset"]
    onset = b.onset.system.params["Vb"]
    assert b.onset.state[2] == pytest.approx(onset, abs=1e-9)  # x' = Vb: grazing
    mid = min(b.cycles, key=lambda c: abs(c.system.params["Vb"] - 0.5 * (h + onset)))
    state, T, mult = _reference(mid.system, mid.state, _hoffmann)
    assert mid.period == pytest.approx(T, rel=1e-9)
    assert mid.state == pytest.approx(state, abs=1e-8)
    assert np.sort(np.abs(mid.multipliers)) == pytest.approx(np.sort(np.abs(mult)), abs=1e-6)


def _corrected(problem, point, value):
    """The cycle at ``value`` exactly, corrected from ``point`` with the parameter pinned."""
    return problem.start(point.state, point.period, value, 1.0)[0]


def _tolerance(q):
    """The error model of a corrected cycle's state: the corrector's and the integrator's
    tolerances over the least singular value of the bordered matrix ``[M - I, f; grad h,
    0]`` (state and period) that Newton's method inverts."""
    s = q.system
    k = s.kernels
    f = np.asarray(k.field(0.0, q.state, s.p, q.mode))
    w = np.asarray(k.slip_gradient(0.0, q.state, s.p))
    g = np.asarray(k.jacobian(0.0, q.state, s.p, q.mode)).T @ w
    n = q.state.size
    A = np.block(
        [[q.monodromy - np.eye(n), f[:, None]], [g[None, :] / np.linalg.norm(g), np.zeros((1, 1))]]
    )
    sigma = np.linalg.svd(A, compute_uv=False)[-1]
    return 2 * (NEWTON_TOL + TOL) * (1.0 + np.abs(q.state).max()) / sigma


def _slip_cycle():
    guess, period = SLIP_GUESS
    return cycle(Model(model="belt_1dof", friction="stribeck", Vb=2.5), guess=guess, period=period)


def test_two_pieces_by_continue_branch_are_the_whole_branch():
    c = _slip_cycle()  # at Vb = 2.5: each walk starts on its lower bound and goes up
    whole = continue_branch(c, "Vb", 2.5, 3.2)
    assert whole.kind == "cycle" and [sp.kind for sp in whole.special] == ["range", "stick_onset"]
    first = continue_branch(c, "Vb", 2.5, 2.7)
    assert [sp.kind for sp in first.special] == ["range", "range"]
    more = continue_branch(first.points[-1], "Vb", 2.7, 3.2)
    assert [sp.kind for sp in more.special] == ["range", "stick_onset"]
    a, b = whole.special[-1], more.special[-1]
    assert a.value == pytest.approx(b.value, abs=a.accuracy + b.accuracy)
    assert whole.points[-1].state == pytest.approx(more.points[-1].state, abs=1e-9)
    # the second piece's cycles are the whole branch's: each corrected at its value from
    # the whole's nearest point, within the error model
    problem = OscillatorCycleProblem(c.system, "Vb", c.mode, 2.5, 3.2, 4.0, c.period)
    inner = more.points[:-1]
    for q in inner[:: max(1, len(inner) // 4)]:
        at = _corrected(problem, whole.point_near(q.value), q.value)
        assert np.abs(at.state - q.state).max() <= _tolerance(q), q.value
        assert at.period == pytest.approx(q.period, rel=1e-9)


def test_down_from_a_cycle_the_branch_ends_at_the_hopf_point():
    c = _slip_cycle()
    down = continue_branch(c, "Vb", 1.5, 2.5)
    hopf = down.special[0]
    p = c.system.params
    typed = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    assert hopf.kind == "hopf" and abs(hopf.value - typed) <= hopf.accuracy <= 1e-11
    assert "at steady sliding's Hopf point" in hopf.detail
    assert [sp.kind for sp in down.special] == ["hopf", "range"]
    # the last cycle is small: its nontrivial multiplier near the Hopf point's, 1
    assert down.points[0].max_abs_multiplier == pytest.approx(1.0, abs=1e-2)


def _static_kinetic_period(p):
    """Undamped static/kinetic stick-slip, by hand: slip from the stick end x_e = mu_s g /
    w^2 around x_k = mu_k g / w^2 on a circle of the phase plane back to x' = Vb, (2 pi
    - 2 phi) / w later (phi = atan2(u0 w, Vb), u0 = x_e - x_k), then stick from x_k - u0
    back to x_e at the belt's speed."""
    w, Vb = p["omega1"], p["Vb"]
    u0 = (p["mu_s"] - p["mu_k"]) * p["g"] / w**2
    return (2 * math.pi - 2 * math.atan2(u0 * w, Vb)) / w + 2 * u0 / Vb


def test_stick_slip_cycles_continue_on_the_hybrid_flow_to_their_closed_form():
    """A cycle with a stick phase runs on the hybrid flow (its saltation matrices), on the
    section of its largest slip speed: the static/kinetic belt's periods along Vb against
    the closed form, its multipliers the stick's 0."""
    c = cycle(Model(model="belt_1dof", friction="static_kinetic", Vb=0.5, beta1=0.0))
    assert c.kind == "stick_slip"
    b = continue_branch(c, "Vb", 0.4, 0.7, record=lambda q: q.n_sticks)
    assert [sp.kind for sp in b.special] == ["range", "range"] and b.kind == "cycle"
    assert b.value_range() == [0.4, 0.7] and len(b.points) >= 10
    for q in b.points:
        # the corrector's and the integrator's tolerances, a period of order 10 s
        assert q.period == pytest.approx(_static_kinetic_period(q.system.params), rel=1e-10)
        assert q.n_sticks == 1 and abs(q.multipliers[0]) < 1e-10 and q.stable
        assert abs(q.trivial_multiplier - 1) < 1e-8
    assert b.observables()["record"] == pytest.approx(1.0)
    d = b.as_dict()
    assert d["model"] == "belt_1dof" and d["kind"] == "cycle" and "grazing" in d["detects"]
    assert "self-excited cycles" in repr(b) and d["points"][0]["n_sticks"] == 1


def test_a_branch_point_continues_and_records():
    b = continue_branch(_slip_cycle(), "Vb", 2.45, 2.55, record=lambda q: q.margin)
    # the least slip speed, recorded, is Vb minus the section's x'
    assert b.observables()["record"] == pytest.approx([q.value - q.state[1] for q in b.points])
    again = continue_branch(b.points[-1], "Vb", 2.55, 2.6)
    assert again.points[0].state == pytest.approx(b.points[-1].state, abs=1e-12)
    assert again.special[-1].kind == "range" and again.value_range() == [2.55, 2.6]


def test_branch_command_lists_the_special_points_of_the_cycle_branch():
    done = cli("branch", "--model", "hoffmann", "--friction", "stribeck", "--param", "Vb",
               "--from", "0.5", "--to", "1.5", "--json")  # fmt: skip
    assert done.returncode == 0, done.stderr
    (born,) = json.loads(done.stdout)["cycle_branches"]
    (sp,) = born["special_points"]
    assert sp["kind"] == "stick_onset" and sp["value"] == born["stick_onset"]
    assert born["cycles"][-1]["state"]["x_dot"] == pytest.approx(sp["value"], abs=1e-9)


def test_the_stable_stick_slip_cycles_turn_into_the_unstable_slip_cycles_at_the_grazing():
    """The subcritical Stribeck belt has no smooth fold of cycles (no turn of the tangent
    on its slip branch); its family turns at the stick onset instead, a non-smooth fold:
    the stable stick-slip cycles (multiplier 0), their stick phase shrinking, end where
    the unstable slip cycles (multiplier 2.86) end, on the one grazing cycle."""
    slip = continue_branch(_slip_cycle(), "Vb", 2.5, 3.2)
    stuck = continue_branch(cycle(Model(model="belt_1dof", friction="stribeck", Vb=2.5)),
                            "Vb", 2.5, 3.2)  # fmt: skip
    onset, graze = slip.special[-1], stuck.special[-1]
    assert onset.kind == "stick_onset" and graze.kind == "grazing"
    assert "stick phase shrinks" in graze.detail
    assert abs(graze.value - onset.value) <= graze.accuracy + onset.accuracy
    assert graze.accuracy < 1e-6
    assert all(q.stable and q.n_sticks == 1 for q in stuck.points)
    assert all(not q.stable and q.n_sticks == 0 for q in slip.points)
    # the same cycle at the turn: the period, and the largest x' (the slip cycle's
    # section; the stick-slip cycle's stick at x' = Vb), to the distance between them
    a, b = slip.points[-1], stuck.points[-1]
    gap = abs(a.value - b.value)
    assert b.period == pytest.approx(a.period, abs=10 * gap + 1e-9)
    assert b.observables()["x_dot_max"] == pytest.approx(a.state[1], abs=10 * gap + 1e-8)
    assert b.stick_time < 1e-3 * b.period


#: Hoffmann's model beyond its flutter threshold under Coulomb friction
#: (tests/beltmdsm/oscillator/test_oscillator_hoffmann_branch.py: mu_c = 0.4124 here).
HOFFMANN = dict(k1=1.25, k2=0.25, k3=0.5, k_c=1.0, F_pre=1.0, c1=0.05, c2=0.05, Vb=1.0)


def _exact_stick(p, mu, z0, switches):
    """Hoffmann's model under Coulomb friction with exact stick, by solve_ivp: slip back
    (v_r < 0) until x' = Vb, stick (x' = Vb) while the holding force |c1 Vb + K11 x +
    K12 y| stays below mu N; the state and time after ``switches`` switches from ``z0``
    (in slip)."""
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    kc, F, c, Vb = p["k_c"], p["F_pre"], p["c1"], p["Vb"]

    def normal(z):
        return -p["c2"] * z[3] - K[1, 0] * z[0] - (K[1, 1] + kc) * z[1]

    def slip(t, z):
        return [z[2], z[3], -c * z[2] - K[0, 0] * z[0] - K[0, 1] * z[1] + mu * (F + kc * z[1]),
                normal(z)]  # fmt: skip

    def stick(t, z):
        return [Vb, z[3], 0.0, normal(z)]

    to_stick = lambda t, z: z[2] - Vb  # noqa: E731
    to_stick.terminal, to_stick.direction = True, 1
    to_slip = lambda t, z: abs(c * Vb + K[0, 0] * z[0] + K[0, 1] * z[1]) - mu * (F + kc * z[1])  # noqa: E731
    to_slip.terminal, to_slip.direction = True, 1
    t, z, mode = 0.0, np.array(z0, float), -1
    for _ in range(switches):
        fun, ev = (slip, to_stick) if mode == -1 else (stick, to_slip)
        sol = solve_ivp(fun, (t, t + 100.0), z, method="DOP853", rtol=1e-12, atol=1e-13,
                        events=ev)  # fmt: skip
        assert sol.status == 1, "no switch within 100 s"
        t, z = sol.t[-1], sol.y[:, -1].copy()
        z[2], mode = (Vb, 0) if mode == -1 else (Vb - 1e-13, -1)
    return z, t


def test_hoffmann_stick_slip_cycles_continue_against_exact_stick():
    """A 4-state stick-slip branch on the hybrid flow: the cycle at mu_s = 0.45 against
    solve_ivp with exact stick, its multipliers against central differences of the
    return map to the stick end."""
    c = cycle(Model(model="hoffmann", mu_s=0.45, **HOFFMANN))
    b = continue_branch(c, "mu_s", 0.44, 0.46)
    assert [sp.kind for sp in b.special] == ["range", "range"]
    assert all(q.n_sticks == 1 and q.stable for q in b.points)
    q = b.point_near(0.45)
    assert q.value == 0.45
    p = q.system.params
    end, _ = _exact_stick(p, 0.45, q.state, 2)  # from the section to the stick's end
    back, T = _exact_stick(p, 0.45, end, 2)  # one period
    assert T == pytest.approx(q.period, rel=1e-9)
    assert back == pytest.approx(end, abs=1e-8)

    def image(z0):
        return _exact_stick(p, 0.45, z0, 2)[0]

    cols = []
    for j in (0, 1, 3):
        e = np.zeros(4)
        e[j] = 1e-5
        cols.append((image(end + e) - image(end - e)) / 2e-5)
    e = np.array([0.0, 0.0, 1e-5, 0.0])  # x' below Vb only: the start slips back
    cols.insert(2, (image(end - e) - image(end - 2 * e)) / 1e-5)
    w = np.linalg.eigvals(np.array(cols).T)
    assert sorted(abs(w))[-2:] == pytest.approx(sorted(abs(q.multipliers))[-2:], abs=1e-5)
