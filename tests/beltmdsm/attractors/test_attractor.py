"""Attractors named (beltmdsm/attractors/classification.py): the runs VALIDATION.md called "not
locked" are long-period locks, found by their return and confirmed by Newton's method and
Floquet; the weighted Birkhoff rotation number against closed forms; a run too short to
tell says so instead of naming a kind."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from beltmdsm.attractors.classification import KINDS, classify, rotation_number
from beltmdsm.model import Model
from beltmdsm.periodic.floquet import floquet


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
