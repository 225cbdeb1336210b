"""Self-excited stick-slip cycles at their least period (issue 36, items 1 and 4).

Reference, independent of the package: an event-driven run written here with scipy's
``solve_ivp`` and Filippov's exact stick. On a cycle the normal motion rests at its
equilibrium (the normal equation is free of the tangential state and strongly
damped), where the contact force equals ``g``; the tangential motion is then

    slip back (Vr = X1' - Vb < 0):  X1'' = -2 beta1 omega1 X1' - omega1^2 X1 + mu(|Vr|) g
    stick (X1' = Vb):               held while |omega1^2 X1 + 2 beta1 omega1 Vb| <= mu_s g

with ``mu = mu_k`` (static and kinetic) or ``mu_k + (mu_s - mu_k) exp(-|Vr| / v_s)``
(Stribeck). The stick ends where the spring and damper's force reaches ``mu_s g``, at
``X1* = (mu_s g - 2 beta1 omega1 Vb) / omega1^2`` with ``X1' = Vb``: one state. From there
the reference slips until ``Vr`` returns to 0 (an event, located by ``solve_ivp``), checks
that friction holds the mass there, and rides the belt back to ``X1*`` in closed form:
the least period is the slip time plus ``(X1* - X1_in) / Vb``, with one stick.

Error model: ``solve_ivp`` (DOP853, ``rtol = atol = 1e-12``) locates the stick's start
to about 1e-11 s relative over slip arcs of up to 3 s, and the stick's length follows
exactly; the package's shooting converges to 1e-11 relative. Periods and ranges agree
to 1e-8 relative (1e-6 where ``X1'`` sweeps hundreds of m/s, ``mu_s >= 40``, where the
slip's state is 300 times the state scale of the default set).
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from beltmdsm.model import Model
from beltmdsm.periodic.cycle import cycle

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
G, BETA1, OMEGA1, MU_K, V_S = 9.81, 0.1, 1.0, 0.25, 1.0


def _cli_json(*argv, timeout=300):
    out = subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv, "--json"],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=ENV,
        cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def reference_cycle(law, Vb, mu_s=0.4):
    """``(period, n_sticks, (min X1, max X1), min X1')`` of the stick-slip cycle."""

    def mu(vr):
        if law == "static_kinetic":
            return MU_K
        return MU_K + (mu_s - MU_K) * math.exp(-abs(vr) / V_S)

    def slip(t, y):
        return [y[1], -2 * BETA1 * OMEGA1 * y[1] - OMEGA1**2 * y[0] + mu(y[1] - Vb) * G]

    def caught_up(t, y):
        return y[1] - Vb

    caught_up.terminal, caught_up.direction = True, 1.0
    x_star = (mu_s * G - 2 * BETA1 * OMEGA1 * Vb) / OMEGA1**2
    # Stribeck's mu(0) = mu_s: the mass leaves the stick with X1'' = 0, so Vr starts at 0
    # with a vanishing slope; the first instant is stepped over by a hair (1e-9 s of
    # X1' = Vb costs 1e-9 Vb of X1, far below the tolerance)
    sol = solve_ivp(
        slip,
        (0.0, 1e4),
        [x_star, Vb],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        events=caught_up,
        dense_output=True,
        first_step=1e-6,
    )
    assert sol.status == 1, "the reference never catches up with the belt"
    t_in = float(sol.t_events[0][-1])
    x_in = float(sol.y_events[0][-1][0])
    # friction holds the mass there (else it would reverse instead of sticking)
    assert abs(OMEGA1**2 * x_in + 2 * BETA1 * OMEGA1 * Vb) <= mu_s * G
    t = np.linspace(0.0, t_in, 200001)
    y = sol.sol(t)
    stick = (x_star - x_in) / Vb
    return t_in + stick, 1, (float(y[0].min()), float(y[0].max())), float(y[1].min())


def _check(found, period, n_sticks, x1_range, v_min, rel=1e-8):
    assert found["period"] == pytest.approx(period, rel=rel)
    assert found["n_sticks"] == n_sticks
    assert found["x1_range"][0] == pytest.approx(x1_range[0], rel=rel)
    assert found["x1_range"][1] == pytest.approx(x1_range[1], rel=rel)
    assert found["velocity_range"][0] == pytest.approx(v_min, rel=rel)


@pytest.mark.parametrize("Vb", [0.31, 0.45])
def test_static_kinetic_cycle_is_reported_at_its_least_period(Vb):
    # issue 36 item 1: 0.31 was reported at twice the period with 2 sticks, 0.45 refused
    # ("Newton stalled")
    found = _cli_json("floquet", "--alpha", "0", "--friction", "static_kinetic", "--Vb", str(Vb))
    _check(found, *reference_cycle("static_kinetic", Vb))
    # the stick's multiplier 0 (rounding), the trivial one 1
    assert min(math.hypot(*mu) for mu in found["multipliers"]) < 1e-12
    assert abs(complex(*found["trivial_multiplier"]) - 1) < 1e-8


@pytest.mark.parametrize("Vb", [0.26, 0.36])
def test_static_kinetic_cycle_in_process(Vb):
    # 0.36 was reported at twice the period, 0.26 refused
    c = cycle(Model(alpha=0.0, friction="static_kinetic", Vb=Vb))
    found = {
        "period": c.period,
        "n_sticks": c.n_sticks,
        "x1_range": c.x1_range,
        "velocity_range": c.velocity_range,
    }
    _check(found, *reference_cycle("static_kinetic", Vb))


def test_the_reference_period_of_the_issue():
    # the number the report gives for Vb = 0.31 (its own event-driven run)
    assert reference_cycle("static_kinetic", 0.31)[0] == pytest.approx(11.460529, abs=1e-6)


def test_a_cycle_shot_at_a_multiple_of_its_period_comes_back_at_the_least_one():
    model = Model(alpha=0.0, friction="static_kinetic", Vb=0.31)
    period, *_ = reference_cycle("static_kinetic", 0.31)
    one = cycle(model)
    for k in (2, 3):
        found = cycle(model, guess=one.state, period=k * one.period)
        assert found.period == pytest.approx(period, rel=1e-8)
        assert found.n_sticks == 1


def test_responses_report_the_least_period():
    # issue 36 item 1: `responses` said 22.9211 s and 2 sticks
    argv = ["--alpha", "0", "--friction", "static_kinetic", "--Vb", "0.31"]
    (r,) = _cli_json("responses", *argv)["responses"]
    _check(r, *reference_cycle("static_kinetic", 0.31))
    # steady sliding is stable there: the seed's run starts where a stick ends
    assert r["sources"][0] == "the run from the end of a stick"


def test_coexistence_finds_no_period_doubling_on_stick_slip_cycles():
    # issue 36 item 1: a period_doubling at 0.301738 and branch points on a cycle whose
    # stick gives a multiplier 0 (and cannot period-double)
    argv = ["--alpha", "0", "--friction", "static_kinetic", "--param", "Vb"]
    found = _cli_json("coexistence", *argv, "--from", "0.2", "--to", "3")
    kinds = [s["kind"] for s in found["special_points"]]
    assert "period_doubling" not in kinds and "branch_point" not in kinds
    (stable,) = found["cycle_stable"]
    assert stable["range"][0] == 0.2
    # the cycles end where the reference no longer catches up with the belt (its
    # events see sign changes at step ends only, so it may stop short of a grazing)
    assert reference_cycle("static_kinetic", 1.0008)[1] == 1
    assert 1.0008 <= stable["range"][1] <= 1.001
    # every cycle on the way: one stick, a multiplier 0
    for s in found["special_points"]:
        assert min(math.hypot(*mu) for mu in s["multipliers"]) < 1e-12


@pytest.mark.parametrize("mu_s", [5.0, 100.0])
def test_a_long_stick_is_a_stick_slip_cycle_not_steady_sliding(mu_s):
    # issue 36 item 4: mu_s 100 was read as steady sliding, 5 refused ("Newton stalled")
    argv = ["--alpha", "0", "--friction", "stribeck", "--Vb", "1.5", "--mu_s", str(mu_s)]
    found = _cli_json("floquet", *argv)
    assert found["autonomous"] is True and found["stable"] is True
    _check(found, *reference_cycle("stribeck", 1.5, mu_s), rel=1e-8 if mu_s < 40 else 1e-6)
    assert found["stick_time"] / found["period"] > 0.9


@pytest.mark.parametrize("mu_s", [20.0, 40.0])
def test_a_long_stick_in_process(mu_s):
    c = cycle(Model(alpha=0.0, friction="stribeck", Vb=1.5, mu_s=mu_s))
    found = {
        "period": c.period,
        "n_sticks": c.n_sticks,
        "x1_range": c.x1_range,
        "velocity_range": c.velocity_range,
    }
    _check(found, *reference_cycle("stribeck", 1.5, mu_s), rel=1e-8 if mu_s < 40 else 1e-6)
    assert c.stable


def test_a_branch_out_to_1e300_is_the_branch_that_ends_inside():
    # issue 36 item 9: brentq's RuntimeError traceback (cycles/hopf.py)
    argv = ["--alpha", "0", "--friction", "stribeck", "--param", "Vb", "--from", "0.5"]
    wide = _cli_json("branch", *argv, "--to", "1e300")
    near = _cli_json("branch", *argv, "--to", "5")
    kinds = [(s["kind"], round(s["value"], 5)) for s in wide["special_points"]]
    assert kinds == [(s["kind"], round(s["value"], 5)) for s in near["special_points"]]
    assert ("stick_onset", 2.90039) in kinds and ("range", 0.5) in kinds


# issue 36 item 8, the branch in v_s (was: it ends where the largest multiplier passes
# 1e3): it now reaches its stick onset by multiple shooting,
# tests/beltmdsm/cycles/test_multiple_shooting.py
