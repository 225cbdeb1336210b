"""Hoffmann's model under Coulomb friction (issue 39 item 4, left-over of item 5): no Hopf
point in the belt speed, said in one line; the flutter threshold in the friction
coefficient against its closed form; the stick-slip cycles born there against a solve_ivp
reference with exact stick written here.

The model as derive/models/entries.py reads it (per unit mass, m = 1 here): springs k1
(x), k2 (y), k3 at 45 degrees, K = [[k1 + k3/2, k3/2], [k3/2, k2 + k3/2]], dampers c1 =
c2 = c, normal force N = F_pre + k_c y, friction mu N against v_r = x' - Vb:

    x'' + c x' + K11 x + K12 y = -mu N sgn(v_r),    y'' + c y' + K21 x + (K22 + k_c) y = 0.

Under Coulomb friction (mu constant) the slip field is linear: steady sliding's
Jacobian holds no Vb, and K_eff = [[K11, K12 - mu k_c], [K21, K22 + k_c]] has the
eigenvalues a +- i b (b^2 = D - T^2 / 4, T and D its trace and determinant). With equal
damping c the pair of ``s^2 + c s + kappa = 0`` crosses the axis where b^2 = a c^2, linear
in mu through D:

    mu_c = (T^2 / 4 + T c^2 / 2 - K11 (K22 + k_c) + K21 K12) / (K21 k_c),

at c = 0 the mode-coupling (flutter) threshold ((K11 - K22 - k_c)^2 / 4 + K12 K21) / (K21 k_c).
"""

import json
import math
import re

import numpy as np
import pytest
from inprocess import cli
from scipy.integrate import solve_ivp

from beltmdsm.oscillator import System, hopf_points, steady_sliding
from beltmdsm.oscillator.equilibria import no_hopf_reason
from beltmdsm.oscillator.hopf_branch import hopf_branch
from beltmdsm.oscillator.hybrid import flow

BASE = dict(k1=1.25, k2=0.25, k3=0.5, k_c=1.0, F_pre=1.0, c1=0.05, c2=0.05, Vb=1.0)
FLAGS = [x for k, v in BASE.items() for x in (f"--{k}", str(v))]


def _K(p):
    return np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])


def _threshold(p, c):
    """mu_c of the module docstring, equal damping c, m = 1."""
    K, kc = _K(p), p["k_c"]
    T = K[0, 0] + K[1, 1] + kc
    return (T * T / 4 + T * c * c / 2 - K[0, 0] * (K[1, 1] + kc) + K[1, 0] * K[0, 1]) / (
        K[1, 0] * kc
    )


def _jacobian(p, mu):
    K, kc, c = _K(p), p["k_c"], p["c1"]
    K_eff = K + np.array([[0.0, -mu * kc], [0.0, kc]])
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-K_eff, -c * np.eye(2)]])


def _json(*argv):
    done = cli(*argv, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_no_hopf_point_in_the_belt_speed_is_said_in_one_line():
    s = System("hoffmann", **{**BASE, "mu_s": 0.4})
    typed = np.linalg.eigvals(_jacobian(s.params, 0.4))  # holds no Vb
    for Vb in (0.5, 2.0):
        eq = steady_sliding(s.replace(Vb=Vb))
        assert np.sort_complex(eq.eigenvalues) == pytest.approx(np.sort_complex(typed), abs=1e-12)
    assert hopf_points(s, "Vb", 0.5, 2.0).size == 0
    why = no_hopf_reason(s, "Vb", 0.5, 2.0)
    assert why.startswith(
        "steady sliding's characteristic polynomial does not depend on Vb (friction 'coulomb')"
    )
    assert "unstable at every Vb" in why and "\n" not in why
    assert why.endswith("(its threshold in the friction coefficient mu_s)")
    # F_pre only moves the equilibrium, as Vb does
    assert "F_pre" not in why.split("depends on")[1] and "mu_s" in why.split("depends on")[1]
    out = _json("branch", "--model", "hoffmann", "--param", "Vb", "--from", "0.5", "--to", "2",
                *FLAGS, "--mu_s", "0.4")  # fmt: skip
    assert out["hopf_points"] == [] and out["no_hopf_point"] == why
    done = cli("branch", "--model", "hoffmann", "--param", "Vb", "--from", "0.5", "--to", "2",
               *FLAGS, "--mu_s", "0.4")  # fmt: skip
    assert f"Hopf points none: {why}" in done.stdout


def test_a_stable_range_without_hopf_point_is_named():
    s = System("hoffmann", **BASE)
    why = no_hopf_reason(s, "mu_s", 0.01, 0.2)
    assert why.startswith("steady sliding is stable over mu_s in [0.01, 0.2]")


def test_flutter_threshold_is_the_closed_form():
    p = System("hoffmann", **BASE).params
    assert _threshold(p, 0.0) == pytest.approx(0.25, rel=1e-15)  # undamped flutter
    for c in (0.05, 0.01):
        s = System("hoffmann", **{**BASE, "c1": c, "c2": c})
        (found,) = hopf_points(s, "mu_s", 0.1, 0.6)
        assert found == pytest.approx(_threshold(p, c), abs=1e-12)
        for d, sign in ((-1e-6, -1), (1e-6, 1)):
            growth = np.linalg.eigvals(_jacobian({**p, "c1": c}, found + d)).real.max()
            assert np.sign(growth) == sign
    out = _json("branch", "--model", "hoffmann", "--param", "mu_s", "--from", "0.1",
                "--to", "0.6", *FLAGS)  # fmt: skip
    assert out["hopf_points"] == pytest.approx([_threshold(p, 0.05)], abs=1e-12)
    (born,) = out["cycle_branches"]
    assert born["degenerate"] and "linear centre" in born["note"]
    assert born["criticality"] == "degenerate" and born["side"] == 1
    values = [c["mu_s"] for c in born["cycles"]]
    assert len(values) == 10 and values[-1] == pytest.approx(0.6)
    assert all(c["stable"] for c in born["cycles"])


# --- the stick-slip cycles of the branch against solve_ivp with exact stick --------------------


def _reference(p, mu, z0, until):
    """Slip back (v_r < 0) until x' = Vb, stick (x' = Vb) while the holding force
    |c Vb + K11 x + K12 y| stays below mu N; ``until(mode_before, z)`` ends the run at a
    switch. Returns the end state, the switch times and the run's range of x (its
    extremes where x' = 0 in slip, or at a switch)."""
    K, kc, F, c, Vb = _K(p), p["k_c"], p["F_pre"], p["c1"], p["Vb"]

    def normal(z):
        return -c * z[3] - K[1, 0] * z[0] - (K[1, 1] + kc) * z[1]

    def slip(t, z):  # v_r < 0: the friction mu N pushes x along the belt
        ax = -c * z[2] - K[0, 0] * z[0] - K[0, 1] * z[1] + mu * (F + kc * z[1])
        return [z[2], z[3], ax, normal(z)]

    def stick(t, z):
        return [Vb, z[3], 0.0, normal(z)]

    def excess(z):
        return abs(c * Vb + K[0, 0] * z[0] + K[0, 1] * z[1]) - mu * (F + kc * z[1])

    to_stick = lambda t, z: z[2] - Vb  # noqa: E731
    to_stick.terminal, to_stick.direction = True, 1
    to_slip = lambda t, z: excess(z)  # noqa: E731
    to_slip.terminal, to_slip.direction = True, 1
    turn = lambda t, z: z[2]  # noqa: E731  (x' = 0: x at its extremes)
    t, z, mode, events, xs = 0.0, np.array(z0, float), -1, [], [z0[0]]
    while True:
        fun, ev = (slip, [to_stick, turn]) if mode == -1 else (stick, [to_slip])
        sol = solve_ivp(fun, (t, t + 100.0), z, method="DOP853", rtol=1e-12, atol=1e-13,
                        events=ev)  # fmt: skip
        assert sol.status == 1, "no switch within 100 s"
        if mode == -1:
            xs += [y[0] for y in sol.y_events[1]]
        t, z = sol.t[-1], sol.y[:, -1].copy()
        xs.append(z[0])
        events.append(t)
        if mode == -1:
            assert excess(z) <= 0, "a reversal: not in this reference"
            z[2], before, mode = Vb, -1, 0
        else:
            z[2], before, mode = Vb - 1e-13, 0, -1
        if until(before, z):
            return z, events, (min(xs), max(xs))


def _x_range(c):
    """The runtime cycle's range of x: its run sampled every T / 4000, each interior
    extreme refined by the parabola through its three samples (error ~ dt^3)."""
    samples = []
    flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=c.period / 4000, samples=samples)
    x = np.concatenate([y[:, 0] for _, y, _ in samples])
    out = []
    for i in (int(np.argmin(x)), int(np.argmax(x))):
        if 0 < i < x.size - 1:
            a, b, d = x[i - 1], x[i], x[i + 1]
            out.append(b - (d - a) ** 2 / (8 * (d - 2 * b + a)))
        else:
            out.append(x[i])
    return tuple(out)


def test_the_branch_cycles_meet_a_solve_ivp_reference():
    s = System("hoffmann", **BASE)
    (h,) = hopf_points(s, "mu_s", 0.1, 0.6)
    branch = hopf_branch(s, "mu_s", h, 0.5, (0.1, 0.6))
    assert branch.degenerate and len(branch.cycles) == 10 and not branch.failure
    p = s.params
    for c in (branch.cycles[0], branch.cycles[5]):
        mu = c.system.params["mu_s"]
        assert c.kind == "stick_slip" and c.sticks == 1 and c.stable
        # one stick per period: from the stick end, slip, stick, to the stick end
        z, events, x_range = _reference(p, mu, c.state, lambda before, z: before == 0)
        assert events[-1] == pytest.approx(c.period, rel=1e-9)
        assert z == pytest.approx(c.state, abs=1e-8)
        assert _x_range(c) == pytest.approx(x_range, abs=1e-8)

        # the multipliers: the return map to the next stick end, by central differences
        # of the reference (x' is Vb at a stick end: the stick collapses it, and a start
        # moved below Vb in x' slips back as the cycle does)
        def back(z0):
            return _reference(p, mu, z0, lambda before, z: before == 0)[0]

        cols = []
        for j in (0, 1, 3):
            e = np.zeros(4)
            e[j] = 1e-5
            cols.append((back(c.state + e) - back(c.state - e)) / 2e-5)
        e = np.array([0.0, 0.0, 1e-5, 0.0])
        cols.insert(2, (back(c.state - e) - back(c.state - 2 * e)) / 1e-5)
        w = np.linalg.eigvals(np.array(cols).T)
        assert sorted(abs(w))[-2:] == pytest.approx(sorted(abs(c.multipliers))[-2:], abs=1e-5)


def test_the_branch_starts_from_the_grazing_orbit_of_the_linear_centre():
    """At the threshold the slip field's critical pair is +-i w with w^2 = a = T / 2 (b =
    0 at c = 0 and b^2 = a c^2 with damping: the pair's real part -c / 2 + c / 2 = 0); the
    centre's orbit that grazes v_r = 0 swings x' between -Vb and Vb. The stick-slip
    cycles born there tend to it: their period to 2 pi / w, their least x' to -Vb (off by
    an amount linear in the distance to the threshold)."""
    s = System("hoffmann", **BASE)
    p = s.params
    K = _K(p)
    w = math.sqrt((K[0, 0] + K[1, 1] + p["k_c"]) / 2)
    h = _threshold(p, 0.05)
    branch = hopf_branch(s, "mu_s", hopf_points(s, "mu_s", 0.1, 0.6)[0], 0.01, (0.1, h + 0.01))
    near, far = branch.cycles[0], branch.cycles[3]  # 0.001 and 0.004 past the threshold
    assert near.system.params["mu_s"] - h == pytest.approx(0.001, abs=1e-12)
    gaps = []
    for c in (near, far):
        samples = []
        flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=c.period / 4000, samples=samples)
        least = np.concatenate([y[:, 2] for _, y, _ in samples]).min()
        gaps.append((c.period - 2 * math.pi / w, least + p["Vb"]))
    assert 0 < gaps[0][0] < 1e-3 and -1e-2 < gaps[0][1] < 0
    assert gaps[1][0] > 3 * gaps[0][0]
    assert gaps[1][1] / gaps[0][1] == pytest.approx(4.0, rel=0.05)


def test_the_undamped_flutter_point_is_named_and_is_the_closed_form():
    """Without damping steady sliding is marginal below the threshold (no Hurwitz sign
    change: no Hopf point); the line names where the pair leaves the axis."""
    p = System("hoffmann", **BASE).params
    out = _json("branch", "--model", "hoffmann", "--param", "mu_s", "--from", "0.1",
                "--to", "0.6", *FLAGS, "--c1", "0", "--c2", "0")  # fmt: skip
    assert out["hopf_points"] == [] and out["cycle_branches"] == []
    why = out["no_hopf_point"]
    assert why.startswith("steady sliding is marginally stable") and "flutter" in why
    found = float(re.search(r"to mu_s = ([0-9.e+-]+), where two", why).group(1))
    assert found == pytest.approx(_threshold(p, 0.0), abs=1e-8)
    # numpy's eigenvalues of the typed Jacobian leave the axis there
    for d, grows in ((-1e-6, False), (1e-6, True)):
        growth = np.linalg.eigvals(_jacobian({**p, "c1": 0.0}, found + d)).real.max()
        assert (growth > 1e-6) == grows
