"""The studies of any model (issue 39): Lyapunov spectra, sweeps, basins, responses and
basin stability of belt_1dof and hoffmann, each against a reference typed here:
ln|mu|/T of multipliers from finite differences of the period map, the undamped
static/kinetic stick-slip cycle in closed form, single runs, and a scipy solve_ivp
integration of the 1-DOF belt oscillator with exact stick written below."""

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from beltmdsm.oscillator import System, forced_response, self_excited_cycle, simulate
from beltmdsm.oscillator.basins import basin_stability, basins
from beltmdsm.oscillator.hybrid import flow
from beltmdsm.oscillator.lyapunov import lyapunov
from beltmdsm.oscillator.responses import coexistence, responses
from beltmdsm.oscillator.sweep import sweep


def _fd_period_map(system, x, T, mode=None, h=1e-6):
    """Central differences of the period map (runs without the variational equations)."""
    m = x.size
    M = np.empty((m, m))
    for j in range(m):
        e = np.zeros(m)
        e[j] = h
        up = flow(system, 0.0, x + e, T, mode=mode, rtol=1e-12, atol=1e-12).y
        down = flow(system, 0.0, x - e, T, mode=mode, rtol=1e-12, atol=1e-12).y
        M[:, j] = (up - down) / (2 * h)
    return M


# --- Lyapunov exponents against ln|mu| / T ---------------------------------------------


def test_lyapunov_of_a_forced_slip_response_is_ln_mu_over_T():
    s = System("belt_1dof", friction="stribeck", Vb=4.0, alpha_t=0.3, Omega_t=1.3)
    r = forced_response(s)
    assert r.sticks == 0 and not r.switches  # smooth: pure slip
    M = _fd_period_map(s, r.state, r.period)
    mu, V = np.linalg.eig(M)
    ref = np.sort(np.log(np.abs(mu)) / r.period)[::-1]
    N = 100
    spec = lyapunov(s, r.state, t_end=N * r.period, t_transient=0.0, tau=r.period)
    # the sum is ln|det M| / T per period (Liouville): to the differences' error
    assert spec.exponents.sum() == pytest.approx(ref.sum(), rel=1e-6)
    # each: QR's diagonal of M^N lies within cond(V) of |mu|^N, so within
    # ln cond(V) / (N T) of ln|mu| / T
    bound = math.log(np.linalg.cond(V)) / (N * r.period) + 1e-6
    assert np.all(np.abs(spec.exponents - ref) <= bound)
    assert spec.collapsed == 0


def test_lyapunov_of_a_forced_stick_slip_response_goes_through_the_saltations():
    s = System("belt_1dof", friction="static_kinetic", Vb=1.0, alpha_t=0.5, Omega_t=1.2)
    r = forced_response(s)
    assert r.sticks >= 1
    M = _fd_period_map(s, r.state, r.period)
    mu = np.linalg.eigvals(M)
    assert np.min(np.abs(mu)) < 1e-6  # stick removes a direction: a multiplier 0
    N = 60
    spec = lyapunov(s, r.state, t_end=N * r.period, t_transient=0.0, tau=r.period)
    assert spec.collapsed == 1 and spec.exponents[1] == -np.inf
    # rank one, M = u v^T: the first period stretches the frame's first vector e_1 by
    # |M e_1|, every later one (along u) by |v . u| = |mu_1| exactly
    lead = ((N - 1) * math.log(np.max(np.abs(mu))) + math.log(np.linalg.norm(M[:, 0]))) / (
        N * r.period
    )
    assert spec.exponents[0] == pytest.approx(lead, rel=1e-6)
    # and so tends to ln|mu_1| / T
    assert abs(spec.exponents[0] - math.log(np.max(np.abs(mu))) / r.period) < 0.01


def test_lyapunov_of_an_autonomous_stick_slip_cycle_is_zero_and_minus_inf():
    s = System("belt_1dof", friction="static_kinetic", Vb=1.0)
    c = self_excited_cycle(s)
    # a point 1 s into the slip (the period map is smooth there; at the stick end the
    # image lands on the switch and differences of the two sides disagree)
    start = flow(s, 0.0, c.state, 1.0, mode=c.mode, rtol=1e-12, atol=1e-12)
    assert start.mode == -1
    N = 10
    spec = lyapunov(s, start.y, t_end=N * c.period, t_transient=0.0, tau=c.period)
    # multipliers 1 (along the flow) and 0 (stick): rank one again, so the first
    # period stretches e_1 by |M e_1| and every later one by |mu| = 1
    M = _fd_period_map(s, start.y, c.period)
    assert np.sort(np.abs(np.linalg.eigvals(M))) == pytest.approx([0.0, 1.0], abs=1e-6)
    lead = math.log(np.linalg.norm(M[:, 0])) / (N * c.period)
    assert spec.exponents[0] == pytest.approx(lead, rel=1e-6)
    assert spec.exponents[1] == -np.inf and spec.collapsed == 1


# --- sweeps against the closed form and single runs ----------------------------------------


def _undamped_stick_slip(p):
    """beta1 = 0, static/kinetic: every stick ends at x_s = mu_s g / w^2 with x' = Vb;
    the slip is a circle of radius R = sqrt((x_s - x_k)^2 + (Vb / w)^2) in (x, x'/w)
    about x_k = mu_k g / w^2, left where x' comes back to Vb at x_k - (x_s - x_k),
    before x' reaches R w: x in [x_k - R, x_k + R], x' in [-R w, Vb]."""
    w, g, Vb = p["omega1"], p["g"], p["Vb"]
    xs, xk = p["mu_s"] * g / w**2, p["mu_k"] * g / w**2
    R = math.hypot(xs - xk, Vb / w)
    return {"x_min": xk - R, "x_max": xk + R, "x_dot_min": -R * w, "x_dot_max": Vb}


def test_sweep_rows_meet_the_undamped_stick_slip_cycle_and_single_runs():
    s = System("belt_1dof", friction="static_kinetic", beta1=0.0)
    dt = 0.01
    with ThreadPoolExecutor(2) as pool:
        result = sweep(s, "Vb", [1.0, 0.5, 1.0], t_end=60.0, t_discard=20.0, dt=dt, executor=pool)
    assert [r["Vb"] for r in result.rows] == [0.5, 1.0]  # ascending, once
    for row in result.rows:
        p = s.replace(Vb=row["Vb"]).params
        ref = _undamped_stick_slip(p)
        assert row["regime"] == "stick_slip" and row["sticks"] >= 3
        # the samples miss an extremum by at most R (1 - cos(w dt / 2)) <= R (w dt)^2 / 8
        # (R w for x'); x' = Vb while sticking is sampled exactly
        w = p["omega1"]
        R = ref["x_max"] - p["mu_k"] * p["g"] / w**2
        for key, value in ref.items():
            slack = R * (w * dt) ** 2 / 8 * (w if "dot" in key else 1.0) + 1e-9
            assert abs(row[key] - value) <= slack, (key, row[key], value)
        # the row is what a single run says
        run = simulate(s.replace(Vb=row["Vb"]), 60.0, dt=dt)
        keep = run.t >= 20.0
        assert row["x_max"] == run["x"][keep].max() and row["x_dot_min"] == run["x_dot"][keep].min()
    assert result.as_dict()["model"] == "belt_1dof" and "x_dot_max" in result.columns


def test_sweep_of_hoffmann_names_its_four_states(tmp_path):
    s = System("hoffmann")
    result = sweep(s, "mu_s", [0.3], t_end=40.0)
    assert [c for c in result.columns if c.endswith("_min")] == [
        "x_min", "y_min", "x_dot_min", "y_dot_min"
    ]  # fmt: skip
    result.to_csv(tmp_path / "t.csv")
    head, row = (tmp_path / "t.csv").read_text().splitlines()[:2]
    assert head.startswith("model,mu_s,") and row.startswith("hoffmann,0.3,")
    with pytest.raises(ValueError, match="not a parameter of model 'hoffmann'"):
        sweep(s, "alpha", [1.0])


# --- basins against solve_ivp with exact stick -------------------------------------------


def _reference_land(p, y0, t_end=300.0):
    """The 1-DOF belt oscillator under Stribeck friction, by solve_ivp with exact
    stick, typed from x'' + 2 beta w x' + w^2 x = -mu(|v_r|) g sgn(v_r), v_r = x' - Vb,
    mu(v) = mu_k + (mu_s - mu_k) exp(-v / v_s): slip until v_r = 0, then stick (x' =
    Vb) while the holding force |w^2 x + 2 beta w Vb| <= mu_s g. Returns
    "stick_slip" where it sticks (each stick of the autonomous 1-DOF model ends at the
    same state, so the first puts it on the cycle), "steady_sliding" where it ends
    within 1e-3 of x_eq = mu(Vb) g / w^2 at rest."""
    w, b, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]
    mus, muk, vs = p["mu_s"], p["mu_k"], p["v_s"]

    def mu(v):
        return muk + (mus - muk) * math.exp(-abs(v) / vs)

    def slip(t, y, sign):
        # the friction of the slip direction the phase started in, held to its end (a
        # field switched on the sign of v_r inside the solver would chatter there)
        return [y[1], -2 * b * w * y[1] - w * w * y[0] - mu(y[1] - Vb) * g * sign]

    def hold(x):
        return w * w * x + 2 * b * w * Vb

    t, y = 0.0, np.array(y0, float)
    while t < t_end:
        sign = math.copysign(1.0, y[1] - Vb)

        def v_zero(t, y, sign=sign):
            return (y[1] - Vb) * sign if t > t0 + 1e-12 else 1.0

        t0 = t
        v_zero.terminal = True
        sol = solve_ivp(slip, (t, t_end), y, events=v_zero, args=(sign,), rtol=1e-10, atol=1e-11)
        t, y = sol.t[-1], sol.y[:, -1]
        if sol.status != 1:
            break
        y[1] = Vb - sign * 1e-12  # the slip reverses, unless it sticks:
        if abs(hold(y[0])) <= mus * g:
            # stick: x grows at Vb until |hold| = mu_s g, at x_end; every stick ends
            # there, at (x_end, Vb), so a run that sticks once is on the one stick-slip
            # cycle through that state
            return "stick_slip"
    x_eq = mu(Vb) * g / w**2
    if abs(y[0] - x_eq) < 1e-3 and abs(y[1]) < 1e-3:
        return "steady_sliding"
    return "unresolved"


def test_basins_of_the_stribeck_belt_meet_solve_ivp_runs_with_exact_stick():
    s = System("belt_1dof", friction="stribeck", Vb=2.5)
    b = basins(s, "x", (1.5, 3.5), "x_dot", (-3.0, 0.5), points=3, t_end=600.0)
    kinds = [a.kind for a in b.attractors]
    assert kinds == ["steady_sliding", "stick_slip"]
    for iy, vy in enumerate(b.ys):
        for ix, vx in enumerate(b.xs):
            ref = _reference_land(s.params, [vx, vy])
            assert kinds[b.labels[iy, ix]] == ref, (vx, vy)
    # the stick-slip cycle's stick end in closed form: (mu_s g - 2 beta w Vb) / w^2, Vb
    p = s.params
    x_end = (p["mu_s"] * p["g"] - 2 * p["beta1"] * p["omega1"] * p["Vb"]) / p["omega1"] ** 2
    assert b.attractors[1].state == pytest.approx((x_end, 2.5), abs=1e-6)


def test_basins_do_not_depend_on_the_executor():
    s = System("belt_1dof", friction="stribeck", Vb=2.5)
    args = (s, "x", (1.5, 3.5), "x_dot", (-3.0, 0.5))
    serial = basins(*args, points=2, t_end=600.0)
    with ThreadPoolExecutor(2) as pool:
        pooled = basins(*args, points=2, t_end=600.0, executor=pool)
    assert np.array_equal(serial.labels, pooled.labels)
    assert serial.attractors == pooled.attractors


def test_basin_stability_shares_are_the_reference_landings_of_the_same_starts():
    s = System("belt_1dof", friction="stribeck", Vb=2.5)
    box = ((1.5, 3.5), (-3.0, 0.5))
    r = basin_stability(s, "x", box[0], "x_dot", box[1], samples=6, seed=3, t_end=600.0)
    draws = np.random.default_rng(3).random((6, 2))
    refs = [_reference_land(s.params, [box[0][0] + u * 2.0, box[1][0] + v * 3.5]) for u, v in draws]
    for a, p, e in zip(r.attractors, r.fractions, r.errors):
        share = refs.count(a.kind) / 6
        assert p == pytest.approx(share) and e == pytest.approx(math.sqrt(share * (1 - share) / 6))
    assert r.unresolved == 0.0


# --- responses and coexistence ---------------------------------------------------------------


def test_responses_of_the_bistable_stribeck_belt():
    s = System("belt_1dof", friction="stribeck", Vb=2.5)
    found = responses(s, points=2)
    kinds = [f.attractor.kind for f in found.found]
    assert kinds == ["steady_sliding", "stick_slip"]
    p = s.params
    mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-p["Vb"] / p["v_s"])
    eq, cycle = found.found[0].orbit, found.found[1].orbit
    assert eq.state[0] == pytest.approx(mu * p["g"] / p["omega1"] ** 2, rel=1e-12)
    assert eq.stable and cycle.stable and cycle.sticks == 1
    # the cycle's period: one stick-end-to-stick-end of the solve_ivp reference
    assert cycle.period == pytest.approx(_reference_period(p, tuple(cycle.state)), rel=1e-8)


def _reference_period(p, stick_end):
    """From the stick end, slip until v_r = 0 (solve_ivp), then stick back to it."""
    w, b, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]
    mus, muk, vs = p["mu_s"], p["mu_k"], p["v_s"]

    def slip(t, y):
        vr = y[1] - Vb
        mu = muk + (mus - muk) * math.exp(-abs(vr) / vs)
        return [y[1], -2 * b * w * y[1] - w * w * y[0] + mu * g]  # v_r < 0

    def back(t, y):
        return y[1] - Vb if t > 1e-6 else -1.0

    back.terminal, back.direction = True, 1
    y0 = [stick_end[0], Vb - 1e-13]
    sol = solve_ivp(slip, (0, 100), y0, events=back, rtol=1e-12, atol=1e-13)
    t_slip, x_stick = sol.t_events[0][0], sol.y_events[0][0][0]
    return t_slip + (stick_end[0] - x_stick) / Vb


def test_coexistence_names_the_range_of_the_two_attractors():
    s = System("belt_1dof", friction="stribeck")
    # Hopf point in closed form: v_s ln(g (mu_s - mu_k) / (2 beta w v_s)) = 1.9957:
    # below it only the stick-slip cycle; above it steady sliding too
    result = coexistence(s, "Vb", [1.5, 2.5], points=2)
    assert result.ranges == [(2.5, 2.5)]
    assert result.as_dict()["points"][0]["attractors"][0]["kind"] == "stick_slip"
