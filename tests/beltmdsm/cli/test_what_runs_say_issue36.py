"""Issue 36, items 2, 5, 7, 11, 16 and 17: what a run says must be true, end to end.

Each test reproduces the report through the command line (or the public function the
report names) and checks the answer against an independent reference: a closed form
typed here, an independent scipy ``solve_ivp`` run, or ``ln |mu| / T`` of an orbit.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[3]


def _run(*argv, timeout=300, env=None):
    env = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    return subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )


# -- item 11: a mass at rest on a still belt, exactly on the friction limit --------------


def test_a_mass_at_rest_on_the_friction_limit_stays_at_rest(tmp_path):
    """``simulate --Vb 0 --alpha 0`` was ``zeno`` with 20 reversals and an energy balance
    that did not close. At rest on a still belt the spring force ``omega1^2 X1`` equals
    the static bound ``mu_s g`` exactly (the start, Eq. 9): friction holds the mass, and
    the state stays ``X1 = mu_s g / omega1^2 = 0.4 x 9.81 / 1 = 3.924`` m, ``X1' = 0``."""
    npz = tmp_path / "rest.npz"
    out = _run(
        "simulate", "--Vb", "0", "--alpha", "0", "--t-end", "200", "--json", "--save", str(npz)
    )
    assert out.returncode == 0, out.stderr
    s = json.loads(out.stdout)
    assert s["status"] == "done", s["message"]
    assert (s["n_switches"], s["n_reversals"], s["n_sticks"], s["n_zeno"]) == (0, 0, 0, 0)
    assert s["energy_ok"], (s["energy_residual"], s["energy_bound"])
    assert (s["vr_min"], s["vr_max"]) == (0.0, 0.0)
    run = np.load(npz)
    by_hand = 0.4 * 9.81 / 1.0**2
    # the holds move X1 by ulps at most (TIE_ULPS per hold), nothing else moves it
    assert np.max(np.abs(run["X1"] - by_hand)) < 1e-12
    assert np.max(np.abs(run["Y1"])) == 0.0
    # the normal direction rests too: its rounding is not amplified by long steps
    assert np.ptp(run["X2"]) < 1e-12 and np.max(np.abs(run["Y2"])) < 1e-12


# -- item 16: lyapunov --perturbation without --start periodic ---------------------------


def test_lyapunov_refuses_a_perturbation_without_a_periodic_start():
    out = _run("lyapunov", "--perturbation", "5", "--t-end", "100", timeout=60)
    assert out.returncode == 2
    last = out.stderr.strip().splitlines()[-1]
    assert "--perturbation" in last and "--start periodic" in last, out.stderr
    assert out.stdout == ""
