"""Issue 36 item 11 with either solver: a mass at rest on a still belt,
starting exactly on the friction limit, stays at rest (the events solver was fixed
first; the superposition went ``zeno`` at t = 144.84 s with 166 switches)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("solver", ["superposition", "events"])
def test_a_mass_on_its_friction_limit_stays_at_rest_with_either_solver(tmp_path, solver):
    """At rest on a still belt the spring force ``omega1^2 X1`` equals the static bound
    ``mu_s g`` exactly (the start, Eq. 9): friction holds the mass at ``X1 = 0.4 x 9.81
    / 1 = 3.924`` m, ``X1' = 0``, and the normal direction rests at its static
    compression. Two faults made it slip: a crossing of the stick limit within its
    rounding at t = 0 was taken for a switch (now held, as events.py does), and the
    normal motion's steps grew without bound at rest, which amplified its rounding to
    1e-9 m by t = 200 s (now bounded as events.py bounds them)."""
    npz = tmp_path / "rest.npz"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run(
        [sys.executable, "-m", "beltmdsm", "simulate", "--Vb", "0", "--alpha", "0",
         "--solver", solver, "--json", "--save", str(npz)],
        env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    s = json.loads(out.stdout)
    assert s["status"] == "done", s["message"]
    assert s["t_end"] == 1000.0
    assert (s["n_switches"], s["n_reversals"], s["n_sticks"], s["n_zeno"]) == (0, 0, 0, 0)
    assert s["energy_ok"], (s["energy_residual"], s["energy_bound"])
    assert (s["vr_min"], s["vr_max"]) == (0.0, 0.0)
    run = np.load(npz)
    by_hand = 0.4 * 9.81 / 1.0**2
    assert np.max(np.abs(run["X1"] - by_hand)) < 1e-12
    assert np.max(np.abs(run["Y1"])) == 0.0
    assert np.ptp(run["X2"]) < 1e-12 and np.max(np.abs(run["Y2"])) < 1e-12
