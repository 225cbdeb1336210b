"""Attractors named (beltmdsm/attractors/classification.py): the runs VALIDATION.md called "not
locked" are long-period locks, found by their return and confirmed by Newton's method and
Floquet; a forced stick-slip cycle that does not lock is a torus (quasi-periodic), checked
by an independent run; the weighted Birkhoff rotation number against closed forms; a run
too short to tell says so instead of naming a kind; the fast periodic path agrees with
the spectrum's."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from beltmdsm.attractors.classification import (
    KINDS,
    ZERO_TOL,
    classify,
    periodic_attractor,
    rotation_number,
)
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet
from beltmdsm.settings import SolverSettings


def test_the_base_set_at_vb_3_5_is_a_59_period_lock_not_quasi_periodic():
    # VALIDATION.md: "not locked within 12 periods ... on a closed curve, rotation number
    # -0.254". The samples return after 59 periods; the 59T response exists (Newton),
    # is stable, and its Floquet rate is the run's largest exponent
    a = classify(Model(Vb=3.5), t_end=2000.0)
    assert a.kind == "periodic" and a.periods == 59
    assert a.rotation_number == pytest.approx(-15 / 59, abs=1e-15)
    f = floquet(Model(Vb=3.5), periods=59, guess=a.state)
    assert f.stable and f.response.periods == 59
    rate = np.log(np.max(np.abs(f.multipliers))) / f.response.period
    assert a.lyapunov == pytest.approx(rate, abs=a.lyapunov_error + 1e-4)
    assert a.lyapunov < -3 * a.lyapunov_error


def test_a_4T_lock_and_steady_sliding_are_named_with_their_exponents():
    a = classify(Model(Vb=5.0), t_end=1000.0)
    assert (a.kind, a.periods, a.rotation_number) == ("periodic", 4, -0.25)
    f = floquet(Model(Vb=5.0), periods=4)
    assert np.max(np.abs(a.state - f.response.state0)) < 1e-9
    e = classify(Model(alpha=0.0, Vb=1.0), t_end=500.0)
    assert e.kind == "equilibrium" and e.periods is None and e.lyapunov < 0
    assert set(KINDS) >= {a.kind, e.kind}


def test_a_run_too_short_to_show_the_lock_is_unclassified_and_says_run_longer():
    # 59 periods (93 s) need a window of three times that to be seen returning
    a = classify(Model(Vb=3.5), t_end=300.0)
    assert a.kind == "unclassified" and a.periods is None
    assert "run longer" in a.evidence


#: A stick-slip cycle of Stribeck friction (period 6.654 s without excitation, the
#: example of beltmdsm.periodic.cycle.cycle) under weak forcing at Omega = 1.53 rad/s.
TORUS = Model(friction="stribeck", Vb=1.5, alpha=0.05, Omega=1.53)


def _strobe(model, y0, n):
    """``n`` stroboscopic samples of an independent plain run from ``y0`` at phase 0."""
    T = 2 * np.pi / model.params["Omega"]
    s = SolverSettings(t_end=n * T, rtol=1e-10, atol=1e-10, dt=T, t_discard=0.0)
    return integrate_events(model, s, y0=y0).trajectory.state(T * np.arange(1, n + 1)).T


def test_a_weakly_forced_stick_slip_cycle_that_does_not_lock_is_a_torus():
    a = classify(TORUS, t_end=1500.0)
    assert a.kind == "quasi_periodic" and a.periods is None
    assert abs(a.lyapunov) <= 3 * a.lyapunov_error + ZERO_TOL < 3e-3
    assert a.exponents[1] < -0.1  # the curve attracts
    assert a.rotation_accuracy < 1e-6
    # an independent run of 1000 periods from a state on it (integrate_events alone)
    n = 1000
    y = _strobe(TORUS, a.state, n)
    # the rotation number: the plain mean of the angle turned per period about the
    # samples' centre errs like 1/n; the weighted average converges: 250 samples give
    # what 1000 give, and both the classification's value
    w = (y[:, :2] - y[:, :2].mean(0)) / y[:, :2].std(0)
    turn = np.unwrap(np.arctan2(w[:, 1], w[:, 0]))
    assert (turn[-1] - turn[0]) / (2 * np.pi * (n - 1)) == pytest.approx(
        a.rotation_number, abs=1.0 / n
    )
    early, late = rotation_number(y[:250])[0], rotation_number(y)[0]
    assert early == pytest.approx(late, abs=1e-6)
    assert late == pytest.approx(a.rotation_number, abs=1e-6)
    # no lock: the last sample returns after no k up to n / 3 periods (a lock's would to
    # rounding, 1e-10)
    scale = 1 + np.max(np.abs(y))
    returns = [np.max(np.abs(y[-1] - y[-1 - k])) / scale for k in range(1, n // 3)]
    assert min(returns) > 1e-4
    # the largest exponent zero: a neighbour's separation along the curve neither grows
    # nor shrinks over 1000 periods (6300 s); a lock contracting at 1e-3 1/s would
    # shrink it 500-fold, chaos at 1e-3 1/s grow it so
    y0 = a.state.copy()
    y0[0] += 1e-4
    d = np.max(np.abs(_strobe(TORUS, y0, n) - y), axis=1)
    assert 0.2 < d[-1] / d[0] < 5


def test_the_fast_periodic_path_agrees_with_the_spectrum():
    # returns, Newton and Floquet (no variational run) against classify's Lyapunov run
    m = Model(Vb=5.0)
    fast, slow = periodic_attractor(m, t_end=400.0), classify(m, t_end=400.0)
    assert (fast.kind, fast.periods, fast.rotation_number) == ("periodic", 4, -0.25)
    assert np.max(np.abs(fast.state - slow.state)) < 1e-9
    # the largest exponent: Floquet's rate within the average's error (the smallest
    # multipliers, near rounding, carry no such accuracy: only the largest is claimed)
    assert abs(fast.lyapunov - slow.lyapunov) <= 3 * slow.lyapunov_error
    assert fast.lyapunov_error < 1e-6 < slow.lyapunov_error
    # the torus has no return: the fast path refuses, classify names it
    with pytest.raises(NoPeriodicResponse, match="do not return"):
        periodic_attractor(TORUS, t_end=600.0)


def _ellipse(rho, n, phase=0.3):
    th = 2 * np.pi * (phase + rho * np.arange(n))
    # an invariant circle drawn as a skewed ellipse about a centre off the origin, with
    # a nonuniform speed along it (a circle map that is not a rigid rotation in angle)
    u = th + 0.3 * np.sin(th)
    return np.column_stack([4.0 + 2.0 * np.cos(u), -6.0 + 0.5 * np.sin(u) + 0.3 * np.cos(u)])


def test_the_weighted_birkhoff_rotation_number_converges_far_faster_than_the_mean():
    rho = (np.sqrt(5) - 1) / 2 - 1  # golden mean, as a turn in (-1/2, 1/2]
    samples = _ellipse(rho, 1000)
    r, acc = rotation_number(samples)
    # the conjugacy u(th) keeps the rotation number of th; the plain mean of the angle
    # increments errs like 1/n, the weighted average super-polynomially
    assert r == pytest.approx(rho, abs=1e-9)
    assert acc < 1e-7
    turn = np.angle(np.exp(1j * np.diff(np.arctan2(*(samples - samples.mean(0)).T[::-1]))))
    assert abs(np.mean(turn) / (2 * np.pi) - rho) > 10 * abs(r - rho)
    # a rational rotation: exact to rounding
    r, _ = rotation_number(_ellipse(-3 / 11, 440))
    assert r == pytest.approx(-3 / 11, abs=1e-12)
    with pytest.raises(ValueError, match="n >= 64"):
        rotation_number(samples[:63])


def _cli(*argv):
    root = Path(__file__).resolve().parents[3]
    r = subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv, "--json"],
        capture_output=True,
        text=True,
        cwd=root,
        env={**os.environ, "PYTHONPATH": str(root)},
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_every_attractor_reported_has_a_kind_and_a_largest_exponent():
    # a run's summary on request, a self-excited cycle, a branch of coexistence
    out = _cli("simulate", "--Vb", "5", "--t-end", "300", "--classify", "--no-progress")
    a = out["attractor"]
    assert (a["kind"], a["periods"], a["rotation_number"]) == ("periodic", 4, -0.25)
    f = floquet(Model(Vb=5.0), periods=4)
    rate = np.log(np.max(np.abs(f.multipliers))) / f.response.period
    assert a["lyapunov"] == pytest.approx(rate, abs=a["lyapunov_error"] + 1e-4)
    c = _cli("floquet", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.5")
    assert c["autonomous"] and c["kind"] == "periodic" and c["stable"]
    assert c["lyapunov"] == 0.0  # along the flow; the others are negative
