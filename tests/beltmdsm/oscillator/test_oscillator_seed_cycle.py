"""``beltmdsm.seed_cycle`` of another model (issue 39): the generic runtime's seed
(`beltmdsm.oscillator.cycle_seed`) in the paper's result type ``(state, period)``, and
``beltmdsm.cycle`` shot from it, against the cycle that an independent ``solve_ivp`` run
settles on (the equations typed here, stick exact by events).

The references, per unit mass, with ``v_r = x' - Vb`` (friction opposes it; on these
cycles the mass only slips back, ``v_r < 0``, or sticks):

* ``belt_1dof``: ``x'' + 2 beta1 omega1 x' + omega1^2 x = mu(|v_r|) g`` while slipping,
  Stribeck's ``mu = mu_k + (mu_s - mu_k) exp(-|v_r| / v_s)``; stuck, ``x' = Vb`` and the
  belt holds ``H = 2 beta1 omega1 Vb + omega1^2 x`` while ``|H| <= mu_s g``;
* ``hoffmann``: ``m x'' + c1 x' + K11 x + K12 y = mu_s N``, ``m y'' + c2 y' + K21 x + (K22 +
  k_c) y = 0``, ``N = F_pre + k_c y``, ``K = [[k1 + k3/2, k3/2], [k3/2, k2 + k3/2]]``; stuck,
  ``x' = Vb`` and ``H = c1 Vb + K11 x + K12 y`` while ``|H| <= mu_s N``.

The error model. The reference runs at ``rtol = atol = 1e-12`` and its events are
located to that; it has settled where its last two periods agree to ``SETTLED`` (its
distance from the cycle then shrinks by the cycle's leading multiplier per period: 0 for
the belt's, a stick resets it, 0.88 for Hoffmann's, hence its longer run). The shot cycle
returns to its state to ``NEWTON_TOL`` of the state's scale (``1 + max|x|``): its period
is then off by at most that over the speed ``|f(x)|`` at its state, its integration
(``1e-11``) adding less. The amplitude is read by `beltmdsm.oscillator.orbit` from 2048
samples (a parabola's vertex: below 2e-9 of the amplitude on a smooth extremum, its
docstring); the reference's by the events ``x' = 0``. Each bound below is 10 times the
sum.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import beltmdsm
from beltmdsm import Model
from beltmdsm.errors import NoPeriodicResponse, Unsupported
from beltmdsm.oscillator.api import system_of
from beltmdsm.oscillator.cycle import NEWTON_TOL
from beltmdsm.oscillator.orbit import orbit_observables
from beltmdsm.settings import SETTLE_TOL

#: The reference has settled where its last two periods agree to this (relative).
SETTLED = 1e-10
#: Hoffmann's model beyond its flutter threshold (tests/beltmdsm/oscillator/
#: test_oscillator_hoffmann.py's set): a stick-slip cycle with one stick.
HOFFMANN = dict(
    k1=1.25, k2=0.25, k3=0.5, k_c=1.0, F_pre=1.0, c1=0.05, c2=0.05, Vb=1.0, mu_s=0.4
)  # fmt: skip


def _belt(p):
    """(slip field, stuck field, |H| - limit, index of x') of belt_1dof, Stribeck."""
    b, w, g, vb = 2 * p["beta1"] * p["omega1"], p["omega1"] ** 2, p["g"], p["Vb"]

    def mu(v):
        return p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-abs(v) / p["v_s"])

    def slip(t, z):
        return [z[1], -b * z[1] - w * z[0] + mu(z[1] - vb) * g]

    def stuck(t, z):
        return [vb, 0.0]

    def hold(t, z):
        return abs(b * vb + w * z[0]) - p["mu_s"] * g

    return slip, stuck, hold, 1


def _hoffmann(p):
    """(slip field, stuck field, |H| - limit, index of x') of hoffmann, Coulomb."""
    K = np.array([[p["k1"] + p["k3"] / 2, p["k3"] / 2], [p["k3"] / 2, p["k2"] + p["k3"] / 2]])
    m, vb, mu, kc, F = p["m"], p["Vb"], p["mu_s"], p["k_c"], p["F_pre"]

    def normal(z):
        return (-p["c2"] * z[3] - K[1, 0] * z[0] - (K[1, 1] + kc) * z[1]) / m

    def slip(t, z):
        ax = (-p["c1"] * z[2] - K[0, 0] * z[0] - K[0, 1] * z[1] + mu * (F + kc * z[1])) / m
        return [z[2], z[3], ax, normal(z)]

    def stuck(t, z):
        return [vb, z[3], 0.0, normal(z)]

    def hold(t, z):
        return abs(p["c1"] * vb + K[0, 0] * z[0] + K[0, 1] * z[1]) - mu * (F + kc * z[1])

    return slip, stuck, hold, 2


def _reference(equations, p, t_end):
    """The run from rest by solve_ivp, stick exact: the times of its stick ends and the
    extremes of x (its events x' = 0 while slipping) after the last but one stick end."""
    slip, stuck, hold, iv = equations(p)
    vb = p["Vb"]
    to_stick = lambda t, z: z[iv] - vb  # noqa: E731
    to_stick.terminal, to_stick.direction = True, 1
    to_slip = lambda t, z: hold(t, z)  # noqa: E731
    to_slip.terminal, to_slip.direction = True, 1
    turn = lambda t, z: z[iv]  # noqa: E731
    t, z, stuck_now, ends, extremes = 0.0, np.zeros(2 * iv), False, [], []
    while t < t_end:
        if stuck_now:
            sol = solve_ivp(stuck, (t, t_end), z, "DOP853", rtol=1e-12, atol=1e-12, events=to_slip)
        else:
            sol = solve_ivp(
                slip, (t, t_end), z, "DOP853", rtol=1e-12, atol=1e-12, events=[to_stick, turn]
            )
            extremes += [(te, ze[0]) for te, ze in zip(sol.t_events[1], sol.y_events[1])]
        t, z = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1:
            break
        if stuck_now:
            ends.append(t)
            z[iv], stuck_now = vb - 1e-13, False  # below the event: a start on it is skipped
        else:
            assert hold(t, z) <= 0, "a reversal: not in this reference"
            z[iv], stuck_now = vb, True
    last = [x for te, x in extremes if te > ends[-2]]
    return np.array(ends), max(last) - min(last)


CASES = [
    pytest.param(Model(model="belt_1dof", friction="stribeck", Vb=1.5), _belt, 60.0, id="belt"),
    # Stribeck's law above its Hopf point (1.9957): steady sliding is stable, the
    # stick-slip cycle coexists; the seed starts from the stick state over sliding
    pytest.param(
        Model(model="belt_1dof", friction="stribeck", Vb=2.5), _belt, 60.0, id="belt-bistable"
    ),
    pytest.param(Model(model="hoffmann", **HOFFMANN), _hoffmann, 1000.0, id="hoffmann"),
]


@pytest.mark.parametrize("model, equations, t_end", CASES)
def test_the_seed_shoots_to_the_cycle_a_solve_ivp_run_settles_on(model, equations, t_end):
    state, period = beltmdsm.seed_cycle(model)
    system = system_of(model)
    assert isinstance(state, np.ndarray) and state.shape == (len(system.states),)
    assert isinstance(period, float) and period > 0
    ends, amplitude = _reference(equations, system.params, t_end)
    spans = np.diff(ends)
    T_ref = spans[-1]
    assert abs(spans[-1] - spans[-2]) <= SETTLED * T_ref, "the reference has not settled"
    for c in (
        beltmdsm.cycle(model, guess=state),
        beltmdsm.cycle(model, guess=state, period=period),
    ):
        assert c.kind == "stick_slip" and c.sticks == 1 and c.stable
        f = system.kernels.field(0.0, c.state, system.p, c.mode)
        speed = float(np.abs(f).max())
        scale = 1.0 + float(np.abs(c.state).max())
        bound_T = 10 * (NEWTON_TOL * scale / speed + SETTLED * T_ref + 1e-12 * T_ref)
        assert abs(c.period - T_ref) <= bound_T
        # read short of the period's end, inside the stick before the state's stick end
        # (no extreme of x there: x' = Vb): a run whose end falls on a stick end does
        # not finish (beltmdsm.oscillator.hybrid.flow; reported in issue 39's notes)
        assert max(t for t, _, after in c.switches if after == 0) < (1 - 1e-3) * c.period
        obs = orbit_observables(system, c.state, (1 - 1e-3) * c.period)
        bound_a = 10 * (2e-9 * amplitude + NEWTON_TOL * scale + 1e-12 * scale)
        assert abs(obs["x_max"] - obs["x_min"] - amplitude) <= bound_a
    # the seed's own period: the time over its sticks in the settled run; the shooting
    # moves it by what the run had left to settle (Hoffmann's: 0.88 a period)
    assert period == pytest.approx(T_ref, rel=1e-5)


def test_the_belt_seed_is_the_stick_end_in_closed_form():
    # the stick ends where the spring and the damper moving with the belt pull with the
    # static limit: omega1^2 x + 2 beta1 omega1 Vb = mu_s g, x' = Vb
    m = Model(model="belt_1dof", friction="stribeck", Vb=1.5)
    state, period = beltmdsm.seed_cycle(m)
    x = (m["mu_s"] * m["g"] - 2 * m["beta1"] * m["omega1"] * m["Vb"]) / m["omega1"] ** 2
    # the end located by the event search to the integrator's tolerance (1e-11)
    assert state == pytest.approx([x, m["Vb"]], abs=1e-9)


def test_seed_cycle_of_another_model_refuses_in_one_line():
    m = Model(model="belt_1dof", friction="stribeck", Vb=1.5)
    with pytest.raises(ValueError, match=r"^perturbation must be 2 finite numbers \(x, x_dot\)"):
        beltmdsm.seed_cycle(m, perturbation=[0.1, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^t_end must be a finite number > 0"):
        beltmdsm.seed_cycle(m, t_end=-1.0)
    with pytest.raises(Unsupported, match="backend='python' applies to the paper's model"):
        beltmdsm.seed_cycle(m, backend="python")
    with pytest.raises(Unsupported, match="the excitation is on"):
        beltmdsm.seed_cycle(m.replace(alpha_t=0.1))
    assert m.capabilities["seed_cycle"] == (True, "")


def test_a_perturbation_is_the_start():
    # Stribeck's belt at Vb = 2.5: steady sliding stable beside the stick-slip cycle. A
    # small offset decays back (no cycle from there); a push forward past the belt's
    # speed (x' = 4 > Vb) slips forward, sticks and lands on the stick-slip cycle, at the
    # default seed's stick end
    m = Model(model="belt_1dof", friction="stribeck", Vb=2.5)
    with pytest.raises(NoPeriodicResponse, match="the runs from the guess settle on no cycle"):
        beltmdsm.seed_cycle(m, perturbation=[1e-3, 0.0])
    state, _ = beltmdsm.seed_cycle(m, perturbation=[0.0, 4.0])
    default, _ = beltmdsm.seed_cycle(m)
    assert state == pytest.approx(default, abs=1e-9)


def test_a_slowly_decaying_run_is_no_pure_slip_seed():
    """Just on the stable side of belt_1dof's Stribeck Hopf point (closed form, issue
    39: Vb = v_s ln(g (mu_s - mu_k) / (2 beta1 omega1 v_s)) = 1.9957), a start off steady
    sliding decays at its growth rate: its least slip speeds move by some 1e-3 a period,
    far above SETTLE_TOL, so they never repeat. The paper's seed refuses such a run (it
    never settles); another model's returned a "pure-slip seed" of it (its least slip
    speed's point and the time between its last two)."""
    m = Model(model="belt_1dof", friction="stribeck", Vb=2.0)
    hopf = m["v_s"] * math.log(
        m["g"] * (m["mu_s"] - m["mu_k"]) / (2 * m["beta1"] * m["omega1"] * m["v_s"])
    )
    assert hopf < m["Vb"] < hopf + 0.01
    eigenvalues = np.linalg.eigvals([[0.0, 1.0], [-m["omega1"] ** 2, -2 * m["beta1"] * m["omega1"]
                                      + m["g"] * (m["mu_s"] - m["mu_k"]) / m["v_s"]
                                      * math.exp(-m["Vb"] / m["v_s"])]])  # fmt: skip
    growth = eigenvalues.real.max()
    # the least speed moves by 1 - exp(2 pi growth / omega) a period, ~2.7e-3
    assert -1e-3 < growth < 0 and 1 - math.exp(2 * math.pi * growth) > 1e3 * SETTLE_TOL
    with pytest.raises(NoPeriodicResponse) as refusal:
        beltmdsm.seed_cycle(m, perturbation=[0.0, 0.05])
    message = str(refusal.value)
    assert "\n" not in message
    assert message.startswith("model 'belt_1dof': no pure-slip cycle")
    assert "decays slowly towards steady sliding" in message
