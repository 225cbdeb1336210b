"""Lyapunov exponents through the switches (beltmdsm/attractors/lyapunov.py), against
references it does not use: the Floquet multipliers of periodic responses (T-periodic,
with reversals, with a stick phase, and a 4T lock), the unforced eigenvalues of steady
sliding, the separation of two trajectories, and the mean divergence of the field plus
the saltation matrices' ``ln |det S|``; the command line end to end."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from beltmdsm.attractors.lyapunov import BLOCKS, chunk_length, lyapunov
from beltmdsm.generated import hybrid, unforced
from beltmdsm.integrate.events import integrate_events
from beltmdsm.model import Model
from beltmdsm.periodic import variational
from beltmdsm.periodic.floquet import floquet
from beltmdsm.settings import SolverSettings

ROOT = Path(__file__).resolve().parents[3]

#: Stable periodic responses of the base set: sliding only, with reversals, with a stick
#: phase (multiplier 0: exponent -inf), and the stable 4T lock of Vb = 5 (issue 20).
ORBITS = {
    "sliding": (dict(Vb=9.0), 1),
    "reversals": (dict(Vb=2.0), 1),
    "stick": (dict(Vb=0.1, alpha=0.05), 1),
    "locked_4T": (dict(Vb=5.0), 4),
}


def _floquet_exponents(f):
    # a stick phase zeroes a multiplier exactly; the product of the saltation and
    # propagator matrices leaves rounding there (2.8e-17 at the stick orbit below)
    mu = np.sort(np.abs(f.multipliers))[::-1]
    if f.n_sticks:
        mu = np.where(mu < 1e-12 * mu.max(), 0.0, mu)
    with np.errstate(divide="ignore"):
        return np.log(mu) / f.response.period, mu > 1e-10 * mu.max()


@pytest.mark.parametrize("name", ORBITS)
def test_on_a_stable_periodic_response_the_exponents_are_ln_mu_over_the_period(name):
    params, k = ORBITS[name]
    f = floquet(Model(**params), periods=k)
    assert f.stable
    spec = lyapunov(f.response.model, y0=f.response.state0, t_end=300.0, t_transient=0.0)
    ref, finite = _floquet_exponents(f)
    # a stick phase, and only it, removes a direction (Floquet multiplier 0)
    assert spec.collapsed == int(np.isneginf(ref).sum()) == (1 if name == "stick" else 0)
    assert np.all(np.isneginf(spec.exponents[np.isneginf(ref)]))
    # a multiplier below 1e-10 of the largest (the contact's exp(-5.66 kT) = 3.5e-16 of
    # the 4T lock) is lost in the rounding of the monodromy: no reference there, but
    # Benettin's chunks resolve it (the contact's rate of the T-periodic orbits)
    if name == "locked_4T":
        assert spec.exponents[3] == pytest.approx(_floquet_exponents(floquet(Model(Vb=9.0)))[0][3])
    # within the error the method states for itself, which is small (a few 1e-3 at most)
    err = spec.error[finite]
    assert np.all(err < 3e-3)
    assert np.all(np.abs(spec.exponents[finite] - ref[finite]) <= err + 1e-6), (
        spec.exponents,
        ref,
    )
    # a complex pair's exponents converge slowly one by one, their sum fast
    assert spec.exponents[finite].sum() == pytest.approx(ref[finite].sum(), abs=1e-3)


def test_on_steady_sliding_the_exponents_are_the_real_parts_of_the_unforced_eigenvalues():
    model = Model(alpha=0.0, Vb=1.0)
    spec = lyapunov(model, t_end=300.0)
    lam = np.asarray(unforced.eigenvalues(**model.arguments(unforced.eigenvalues)), dtype=complex)
    ref = np.sort(lam.real)[::-1]
    assert spec.collapsed == 0 and spec.switches == 0
    assert np.all(np.abs(spec.exponents - ref) <= spec.error + 1e-8), (spec.exponents, ref)


def test_the_largest_exponent_agrees_with_the_separation_of_two_trajectories():
    # two runs from the stable orbit with a stick phase every period, one moved by 1e-4
    # in every component: their distance at each excitation period decays like
    # exp(lambda_1 t) (real exponents here), so the least-squares slope of log d from 10
    # to 40 periods (d from 3e-6 to 1e-10: above the runs' rounding, below where the
    # nonlinearity shows) is lambda_1; it passes a stick and a slip every period
    model = Model(Vb=0.1, alpha=0.05)
    f = floquet(model)
    T = f.response.period
    n = 40
    settings = SolverSettings(t_end=n * T, rtol=1e-12, atol=1e-12, dt=T / 50, t_discard=0.0)
    t = T * np.arange(10, n + 1)
    a = integrate_events(model, settings, y0=f.response.state0).trajectory.state(t)
    b = integrate_events(model, settings, y0=f.response.state0 + 1e-4).trajectory.state(t)
    slope = np.polyfit(t, np.log(np.linalg.norm(a - b, axis=0)), 1)[0]
    spec = lyapunov(model, y0=f.response.state0, t_end=200.0, t_transient=0.0)
    assert spec.collapsed == 1
    assert slope == pytest.approx(spec.largest, rel=1e-3)


def test_the_sum_of_the_exponents_is_the_mean_divergence_plus_the_switches():
    # Liouville through the switches: d ln vol / dt = tr J between switches, and a jump
    # of ln |det S| at each; over one period of the stable orbit with reversals
    model = Model(Vb=2.0)
    f = floquet(model)
    T = f.response.period
    settings = SolverSettings(t_end=T, rtol=1e-12, atol=1e-12, dt=T / 50, t_discard=0.0)
    run = integrate_events(model, settings, y0=f.response.state0)
    tr = run.trajectory
    total = 0.0
    for seg in tr.segments:
        s = np.linspace(seg.t0, seg.t1, 2001)
        y = tr.state(s)
        J = np.asarray(
            hybrid.mode_jacobian(
                s, *y, np.full(s.size, float(seg.mode)), **model.arguments(hybrid.mode_jacobian)
            ),
            dtype=float,
        )
        trace = np.einsum("nii->n", J)  # (n, 4, 4)
        h = (seg.t1 - seg.t0) / 2000
        total += h / 3 * (trace[0] + trace[-1] + 4 * trace[1:-1:2].sum() + 2 * trace[2:-1:2].sum())
    m = variational.monodromy(run)
    jumps = 0
    for t, before, after, surface, state in m.switches:
        if after != before:
            S = np.array(variational.saltation(model, before, after, surface)(t, *state))
            total += np.log(abs(np.linalg.det(S.reshape(4, 4))))
            jumps += 1
    assert jumps >= 2
    spec = lyapunov(model, y0=f.response.state0, t_end=300.0, t_transient=0.0)
    assert spec.exponents.sum() == pytest.approx(total / T, abs=spec.error.sum() + 1e-6)
    # and both equal ln |det M| / T of the Floquet multipliers
    assert total / T == pytest.approx(np.log(np.prod(np.abs(f.multipliers))) / T, abs=1e-6)


def test_a_window_too_short_for_the_error_is_refused_naming_t_end():
    with pytest.raises(ValueError, match="raise t_end"):
        lyapunov(Model(Vb=9.0), t_end=20.0)
    base, cuts = chunk_length(Model(Vb=9.0))
    assert base == pytest.approx(np.pi / 2) and cuts >= 1
    with pytest.raises(ValueError, match="t_end"):
        lyapunov(Model(Vb=9.0), t_end=float("nan"))
    with pytest.raises(ValueError, match="y0"):
        lyapunov(Model(Vb=9.0), y0=[0.0, 0.0, np.nan, 0.0], t_end=100.0)
    assert BLOCKS >= 4


def _cli(*argv):
    env = {**__import__("os").environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "beltmdsm", "lyapunov", *argv],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=300,
    )


def test_the_command_prints_the_spectrum_as_json_and_refuses_in_one_line():
    r = _cli("--Vb", "0.1", "--alpha", "0.05", "--t-end", "200", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    ex = out["exponents"]
    assert len(ex) == 4 and ex[3] is None and out["collapsed"] == 1  # -inf: a stick phase
    assert ex[0] >= ex[1] >= ex[2] and ex[0] < 0 and len(out["error"]) == 4
    r = _cli("--Vb", "9", "--t-end", "20")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    # the flag typed, not the Python argument (issue 36, item 15)
    assert len(r.stderr.strip().splitlines()) == 1 and "--t-end" in r.stderr
