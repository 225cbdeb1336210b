"""Issue 36/39: `beltmdsm.cycle` on Hoffmann's model at mu_s = 1 returned the trivial
solution of the periodic boundary-value problem (period 5e-12 s at a point where a stick
ends and begins again at once) as a "stick-slip cycle".

The true long-time behaviour there, by a solve_ivp reference typed here (stick exact,
slip both ways): the run from rest settles on a stick-slip cycle of 21 sticks a period
(period 126.19 s), slipping back and forward. The shooting finds it now; the trivial
return is refused by `beltmdsm.oscillator.cycles.genuine`.

As test_oscillator_hoffmann.py reads the model (x along the belt, y into it, N = F_pre +
k_c y bilateral, Coulomb mu_s against v_r = x' - Vb):

    m x'' + c1 x' + K11 x + K12 y = -mu N sgn(v_r),
    m y'' + c2 y' + K21 x + (K22 + k_c) y = 0,

K = [[k1 + k3/2, k3/2], [k3/2, k2 + k3/2]]; stick (x' = Vb) holds while |H| <= mu N,
H = c1 Vb + K11 x + K12 y; it ends into the slip the net force points to.
"""

import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import beltmdsm
from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.oscillator import cycle as _cycle
from beltmdsm.oscillator import steady_sliding
from beltmdsm.oscillator import stick_slip_shooting as _stick_slip
from beltmdsm.oscillator.api import system_of
from beltmdsm.oscillator.hybrid import flow

MODEL = beltmdsm.Model(model="hoffmann", mu_s=1.0)
#: The trivial return the shooting converged on before (state where a stick ends, mode
#: -1): a stick begins 4e-16 s later and ends 5.4e-12 s later.
TRIVIAL = np.array([-0.42778707, -0.37221293, 4.0, -30.70859665])


def _reference(p, y0, mode, t_end, stick_ends=None):
    """solve_ivp run from ``y0`` in ``mode`` (-1 slip back, 1 forward, 0 stick) to
    ``t_end`` or to the ``stick_ends``-th end of a stick; returns (t, y, mode, ends),
    ``ends`` the (t, y, mode after) of each end of a stick."""
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    m, Vb, mu, kc, F = p["m"], p["Vb"], p["mu_s"], p["k_c"], p["F_pre"]

    def normal(z):
        return (-p["c2"] * z[3] - K[1, 0] * z[0] - (K[1, 1] + kc) * z[1]) / m

    def hold(z):
        return p["c1"] * Vb + K[0, 0] * z[0] + K[0, 1] * z[1]

    def field(md):
        if md == 0:
            return lambda t, z: [Vb, z[3], 0.0, normal(z)]

        def slip(t, z):
            ax = (-hold(z) - p["c1"] * (z[2] - Vb) - md * mu * (F + kc * z[1])) / m
            return [z[2], z[3], ax, normal(z)]

        return slip

    def event(md):
        if md == 0:
            ev = lambda t, z: abs(hold(z)) - mu * (F + kc * z[1])  # noqa: E731
            ev.direction = 1
        else:
            ev = lambda t, z: z[2] - Vb  # noqa: E731
            ev.direction = -md
        ev.terminal = True
        return ev

    t, z, ends = 0.0, np.array(y0, float), []
    while t < t_end:
        sol = solve_ivp(
            field(mode), (t, t_end), z, method="DOP853", rtol=1e-12, atol=1e-12,
            events=event(mode), max_step=0.05,
        )  # fmt: skip
        t, z = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1:
            break
        z[2] = Vb
        if mode == 0:
            mode = -1 if hold(z) > 0 else 1
            ends.append((t, z.copy(), mode))
            if stick_ends is not None and len(ends) == stick_ends:
                break
        else:
            mode = 0 if abs(hold(z)) <= mu * (F + kc * z[1]) else -mode
        # off the surface by one step of rounding: solve_ivp skips an event at its start
        if mode:
            z[2] = Vb + mode * 1e-13
    return t, z, mode, ends


@pytest.fixture(scope="module")
def cycle():
    return beltmdsm.cycle(MODEL)


def test_the_call_returns_the_cycle_a_run_from_rest_settles_on(cycle):
    p = system_of(MODEL).params
    assert cycle.period > 100.0 and cycle.kind == "stick_slip" and cycle.sticks == 21
    # the reference from rest: bounded, and after some 12 periods its stick ends pass
    # through the cycle's state (the run's long-time behaviour is this cycle)
    _, z, _, ends = _reference(p, np.zeros(4), 0, 1700.0)
    assert np.abs(z).max() < 50.0 and len(ends) > 200
    late = [(t, y) for t, y, md in ends if t > 1500.0 and md == cycle.mode]
    gap = min(np.abs(y - cycle.state).max() for _, y in late)
    assert gap < 1e-6, gap
    # it slips both ways on the cycle
    assert {(a, b) for _, a, b in cycle.switches} >= {(-1, 0), (0, -1), (0, 1), (1, -1)}


def test_cycle_against_the_solve_ivp_reference(cycle):
    p = system_of(MODEL).params
    t, z, mode, ends = _reference(p, cycle.state, cycle.mode, np.inf, cycle.sticks)
    assert t == pytest.approx(cycle.period, abs=1e-8)
    assert np.abs(z - cycle.state).max() < 1e-8 and mode == cycle.mode
    # the switch times of one period
    stick_ends = [s for s, before, _ in cycle.switches if before == 0]
    assert np.allclose([e[0] for e in ends], stick_ends, atol=1e-8)
    # the multipliers against central differences of the reference's return map to the
    # 21st end of a stick, on the section x' = Vb (the stick gives 0 there)
    eps, cols = 1e-5, []
    for i in (0, 1, 3):
        e = np.zeros(4)
        e[i] = eps
        plus, minus = (
            _reference(p, cycle.state + s * e, cycle.mode, np.inf, cycle.sticks)[1] for s in (1, -1)
        )
        cols.append(((plus - minus) / (2 * eps))[[0, 1, 3]])
    w = sorted(np.abs(np.linalg.eigvals(np.array(cols).T)), reverse=True)
    assert w == pytest.approx(np.abs(cycle.multipliers), abs=1e-5)
    assert abs(cycle.trivial_multiplier - 1) < 1e-8


def test_the_trivial_return_is_refused():
    s = system_of(MODEL)
    # Newton's method from the old answer: its run returns at once, in another mode
    with pytest.raises(NoPeriodicResponse, match="hoffmann.*mu_s=1.0.*not in its mode -1"):
        _stick_slip._newton_stick(s, TRIVIAL, -1, 1, 30, dict(rtol=1e-11, atol=1e-11))
    # and the check itself on a cycle of that run
    run = flow(s, 0.0, TRIVIAL, np.inf, mode=-1, variational=True, stop=_stick_slip._nth_end(1))
    assert run.t < 1e-10
    with pytest.raises(NoPeriodicResponse, match="no self-excited cycle"):
        _cycle._cycle(s, TRIVIAL, -1, run, 0.0, dict(rtol=1e-11, atol=1e-11))


def test_a_run_that_sticks_no_more_is_refused_in_bounded_time():
    """Hoffmann's model at mu_s = 0.6 (steady sliding stable): the run from the stick
    state sticks three times and decays onto steady sliding; the search for its next
    stick end ran without end before (a run to t = inf), now it refuses in one line."""
    code = (
        "import beltmdsm\n"
        "try:\n"
        "    beltmdsm.cycle(beltmdsm.Model(model='hoffmann', mu_s=0.6))\n"
        "except beltmdsm.errors.NoPeriodicResponse as err:\n"
        "    print('REFUSED', err)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    ).stdout
    line = next(s for s in out.splitlines() if s.startswith("REFUSED"))
    assert "hoffmann" in line and "mu_s=0.6" in line and "sticks no more within 200 s" in line
    assert steady_sliding(system_of(beltmdsm.Model(model="hoffmann", mu_s=0.6))).stable
