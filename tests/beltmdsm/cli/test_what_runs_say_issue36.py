"""Issue 36, items 2, 5, 7, 11, 16 and 17: what a run says must be true, end to end.

Each test reproduces the report through the command line (in the test's process,
tests/inprocess.py; a real process where a hang is bounded in time) or the public
function the report names, and checks the answer against an independent reference: a closed form
typed here, an independent scipy ``solve_ivp`` run, or ``ln |mu| / T`` of an orbit.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from inprocess import cli as _run

ROOT = Path(__file__).resolve().parents[3]


def _process(*argv, timeout):
    """``python -m beltmdsm argv`` in a real process, bounded in time (a hang fails)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
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
    out = _process("lyapunov", "--perturbation", "5", "--t-end", "100", timeout=60)
    assert out.returncode == 2
    last = out.stderr.strip().splitlines()[-1]
    assert "--perturbation" in last and "--start periodic" in last, out.stderr
    assert out.stdout == ""


# -- item 2: an unstable equilibrium or periodic response is not chaos -------------------


def _stribeck_sigma(Vb, beta1=0.1, omega1=1.0, mu_s=0.4, mu_k=0.25, v_s=1.0, g=9.81):
    """The real part of the tangential pair of steady sliding under Stribeck's law, by
    hand: ``-(2 beta1 omega1 + g mu'(Vb)) / 2``, ``mu' = -(mu_s - mu_k) / v_s e^(-Vb/v_s)``."""
    slope = -(mu_s - mu_k) / v_s * np.exp(-Vb / v_s)
    return -(2 * beta1 * omega1 + g * slope) / 2


def test_lyapunov_on_unstable_steady_sliding_starts_off_it_and_names_it():
    """``lyapunov --alpha 0 --friction stribeck --Vb 1.9`` sat exactly on unstable steady
    sliding and printed its instability as if it were the attractor's exponent. It now
    starts as simulate does (1e-6 off, along the unstable direction) and, where 1000 s
    are too short to leave, says that the exponent is steady sliding's ``sigma``."""
    sigma = _stribeck_sigma(1.9)
    assert 0.009 < sigma < 0.011
    out = _run("lyapunov", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.9", "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["start_perturbation"] == 1e-6
    assert abs(d["largest"] - sigma) < 1e-4  # the exponent is steady sliding's sigma
    assert d["unstable_set"] and "steady sliding, which is unstable" in d["unstable_set"]
    assert f"sigma = {sigma:.4g} 1/s" in d["unstable_set"]
    text = _run("lyapunov", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.9").stdout
    assert "not chaos: the run begins its averaging window" in text


def test_classify_finds_the_stick_slip_cycle_behind_unstable_sliding():
    """``classify(Model(alpha=0, friction="stribeck", Vb=1.9))`` said chaotic. From the
    default start (off steady sliding, with the time to leave it, ``ln(1e6) / sigma``,
    as transient) it finds the stick-slip cycle: a zero exponent (along the flow) and a
    direction collapsed by the stick (a multiplier 0); started exactly on steady
    sliding it names that set, with the exponent ``sigma`` typed by hand."""
    import beltmdsm
    from beltmdsm import Model
    from beltmdsm.excitation import initial_state

    m = Model(alpha=0.0, friction="stribeck", Vb=1.9)
    a = beltmdsm.classify(m)
    assert a.kind == "periodic", a.evidence
    assert abs(a.lyapunov) <= 3 * a.lyapunov_error + 5e-4
    assert np.isneginf(a.exponents[-1])  # the stick phase: a multiplier 0
    on = beltmdsm.classify(m, y0=initial_state(m), t_end=300.0)
    assert on.kind == "unstable" and on.periods is None, on.evidence
    assert abs(on.lyapunov - _stribeck_sigma(1.9)) < 1e-4


def test_classify_on_the_unstable_periodic_response_names_it():
    """``classify(Model(Vb=5.0), y0=periodic_start(m, 0.0), t_end=300)`` said chaotic: the
    run sits on the unstable T-periodic response. Its exponent is ``ln |mu| / T`` of that
    response's largest Floquet multiplier, computed here by `floquet` apart."""
    import beltmdsm
    from beltmdsm import Model
    from beltmdsm.starts.forced import periodic_start

    m = Model(Vb=5.0)
    f = beltmdsm.floquet(m)
    rate = np.log(np.max(np.abs(f.multipliers))) / f.period
    assert rate > 0.05  # unstable, and well above the error of the run's exponent
    a = beltmdsm.classify(m, y0=periodic_start(m, 0.0), t_end=300.0)
    assert a.kind == "unstable" and a.periods == 1, a.evidence
    assert abs(a.lyapunov - rate) <= 3 * a.lyapunov_error + 1e-4, (a.lyapunov, rate)
    assert "not chaos" in a.evidence


# -- item 5: a memory bound on the run length of lyapunov, classify, basins --------------


def test_lyapunov_refuses_a_run_it_cannot_keep_in_one_line_naming_the_flag():
    out = _process("lyapunov", "--t-end", "1e300", timeout=60)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "lyapunov: error: argument --t-end: --t-end = 1e+300 s" in lines[0]
    assert "MAX_RUN_BYTES" in lines[0] and out.stdout == ""


def test_classify_and_basins_refuse_it_too():
    import beltmdsm
    from beltmdsm.errors import Refused

    with pytest.raises(Refused, match="t_end = 1e.300 s holds"):
        beltmdsm.classify(beltmdsm.Model(), t_end=1e300)
    out = _process("basins", "--Vb", "3.88", "--points", "2", "--t-end", "1e300", timeout=60)
    assert out.returncode == 2 and "--t-end" in out.stderr.splitlines()[-1], out.stderr
    assert "Traceback" not in out.stderr


# -- item 7: multipliers below the error floor ------------------------------------------


def test_floquet_reports_multipliers_below_its_error_floor_as_below_it():
    """``floquet --Omega 0.001`` reported largest |mu| 2.98e-7 and a growth rate of
    -0.00239 1/s. The response is steady backward sliding, whose largest exponent is
    the tangential pair's ``-beta1 omega1 = -0.1`` 1/s (typed by hand): the computed
    multipliers are below the computation's error floor, and are reported so, with a
    bound on the growth rate that the true rate satisfies."""
    import re

    out = _run("floquet", "--Omega", "0.001")  # a period of 6283 s: one run only
    assert out.returncode == 0, out.stderr
    head, mus, verdict = out.stdout.strip().splitlines()[:3]
    assert "0 reversals and 0 sticks" in head
    floors = re.findall(r"\|mu\| < (\S+?)(?:,|$)", mus)
    assert len(floors) == 4 and len(set(floors)) == 1  # no multiplier as a number
    floor = float(floors[0])
    assert "max |mu| below the error floor" in verdict
    bound = float(re.search(r"growth rate < (\S+) 1/s", verdict).group(1))
    T = 2 * np.pi / 0.001
    assert bound == pytest.approx(np.log(floor) / T, rel=0.02)  # printed to 2 digits
    by_hand = -0.1 * 1.0
    assert by_hand < bound < 0  # the true rate satisfies the bound
    assert 2.98e-7 < floor  # the value reported before lies below the floor


# -- item 17: a run still converging onto the T response is not "not locked" -------------


def test_coexistence_does_not_list_a_run_converging_onto_the_t_response_as_unlocked():
    """``coexistence --param Vb --from 0.5 --to 12`` listed Vb = 4 as not locked: the
    ladder continued up from below spirals into the T response, whose largest Floquet
    multiplier there is 0.995 (`floquet`, computed apart), too slowly for the lock test
    within its 150 periods. Its 1-returns fall at that multiplier's rate, ``|mu|^n``
    (the reference), and Newton's method finds the response from its last sample."""
    import beltmdsm
    from beltmdsm import Model
    from beltmdsm.starts.forced import ladder

    mu = beltmdsm.floquet(Model(Vb=4.0)).max_abs_multiplier
    assert 0.99 < mu < 1.0
    strobe = ladder(Model(), "Vb", [2.5, 3.0, 3.5, 4.0])[-1]
    y = strobe.samples
    r = np.max(np.abs(y[1:] - y[:-1]), axis=1)
    q = r.size // 4
    fall = np.median(r[-q:]) / np.median(r[:q])
    assert strobe.candidate is None  # not within the lock tolerance yet
    assert abs(np.log(fall) / (3 * q * np.log(mu)) - 1) < 0.25  # the multiplier's rate
    out = _run("coexistence", "--param", "Vb", "--from", "2.5", "--to", "4.5", "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert 4.0 not in {u["value"] for u in d["unlocked"]}
    # a long lock stays listed: Vb = 3.5 from rest, 59T (docs/explanation/attractors.md),
    # its samples on a closed curve and their returns not falling
    assert any(u["value"] == 3.5 and u["closed_curve"] for u in d["unlocked"])
