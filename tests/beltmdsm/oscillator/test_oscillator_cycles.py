"""Self-excited cycles of belt_1dof (the hand-typed reference and the generated module):
closed forms, finite differences, and the paper's model where its normal direction
decouples (alpha = 0: the normal motion sits at its equilibrium, Fn = g, and X1 is the
1-DOF oscillator)."""

import math

import numpy as np
import pytest
import reference_belt_1dof as belt
from scipy.optimize import brentq

import beltmdsm
from beltmdsm.errors import Unsupported
from beltmdsm.oscillator import System, self_excited_cycle, stick_onset
from beltmdsm.oscillator import slip_shooting as _slip
from beltmdsm.oscillator import stick_slip_shooting as _stick_slip
from beltmdsm.oscillator.hybrid import flow

#: The hand-typed reference and the generated module (the same model, the same checks).
BELTS = [pytest.param(belt, id="reference"), pytest.param("belt_1dof", id="generated")]

#: The paper's normal equilibrium at the base set (X2 = (g / omega2^2)^(2/3)).
X2_EQ = (9.81 / 0.5**2) ** (2 / 3)


def _static_kinetic_period(p):
    """The static/kinetic stick-slip period, worked out by hand.

    Slip (v_r < 0, friction +mu_k g) from the stick end x_e = (mu_s g - 2 beta1 omega1
    Vb) / omega1^2, x' = Vb: u = x - x_k, x_k = mu_k g / omega1^2, is the damped
    oscillation u = e^(-zeta w t) (u0 cos(wd t) + (Vb + zeta w u0)/wd sin(wd t)),
    u0 = x_e - x_k, until x' = Vb again (the first root t_s > 0 of u' = Vb, bracketed
    past u' = 0); then stick, x growing at Vb from x(t_s) back to x_e.
    For beta1 = 0 in closed form: the phase circle is symmetric, t_s = (2 pi - 2 phi) / w,
    phi = atan2(u0 w, Vb), and x(t_s) = x_k - u0.
    """
    w, z, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]
    xk = p["mu_k"] * g / w**2
    xe = (p["mu_s"] * g - 2 * z * w * Vb) / w**2
    u0 = xe - xk
    if z == 0:
        phi = math.atan2(u0 * w, Vb)
        return (2 * math.pi - 2 * phi) / w + 2 * u0 / Vb
    wd = w * math.sqrt(1 - z * z)
    B = (Vb + z * w * u0) / wd

    def u(t):
        return math.exp(-z * w * t) * (u0 * math.cos(wd * t) + B * math.sin(wd * t))

    def du(t):
        e = math.exp(-z * w * t)
        return -z * w * u(t) + e * (-u0 * wd * math.sin(wd * t) + B * wd * math.cos(wd * t))

    # u' falls from Vb, passes its minimum near half a period and rises back to Vb:
    # the first rise through Vb on a fine grid, then its root
    grid = np.linspace(0.5 * math.pi / wd, 2 * math.pi / wd, 2001)
    gap = np.array([du(t) - Vb for t in grid])
    i = int(np.flatnonzero((gap[:-1] < 0) & (gap[1:] >= 0))[0])
    ts = brentq(lambda t: du(t) - Vb, grid[i], grid[i + 1], xtol=1e-15)
    return ts + (xe - (xk + u(ts))) / Vb


@pytest.mark.parametrize("belt", BELTS)
@pytest.mark.parametrize("beta1", [0.0, 0.05])
def test_static_kinetic_stick_slip_period_is_the_closed_form(belt, beta1):
    s = System(belt, friction="static_kinetic", Vb=0.5, beta1=beta1)
    c = self_excited_cycle(s)
    assert c.kind == "stick_slip" and c.sticks == 1
    assert c.period == pytest.approx(_static_kinetic_period(s.params), rel=1e-10)
    # the stick end: x at the static limit, x' = Vb
    p = s.params
    x_end = (p["mu_s"] * p["g"] - 2 * p["beta1"] * p["omega1"] * p["Vb"]) / p["omega1"] ** 2
    assert c.state == pytest.approx([x_end, p["Vb"]], abs=1e-10)
    # a stick gives the multiplier 0; the trivial one is 1
    assert abs(c.multipliers[0]) < 1e-10 and abs(c.trivial_multiplier - 1) < 1e-9
    assert c.stable


@pytest.mark.parametrize("belt", BELTS)
def test_no_proper_divisor_returns(belt):
    s = System(belt, friction="static_kinetic", Vb=0.5)
    c = self_excited_cycle(s)
    # asked for two sticks a period, the shooting reports the least period (one)
    twice = _stick_slip._newton_stick(s, c.state, c.mode, 2, 30, dict(rtol=1e-11, atol=1e-11))
    assert twice.sticks == 1 and twice.period == pytest.approx(c.period, rel=1e-12)


def _fd_monodromy(system, x, T, mode, delta=1e-5):
    """Central differences of the run over T (no variational equations, no saltation)."""
    cols = []
    for e in np.eye(x.size):
        plus = flow(system, 0.0, x + delta * e, T, mode=mode).y
        minus = flow(system, 0.0, x - delta * e, T, mode=mode).y
        cols.append((plus - minus) / (2 * delta))
    return np.array(cols).T


@pytest.mark.parametrize("belt", BELTS)
def test_stribeck_stick_slip_agrees_with_the_paper_model_and_finite_differences(belt):
    s = System(belt, friction="stribeck", Vb=1.5)
    c = self_excited_cycle(s)
    paper = beltmdsm.cycle(beltmdsm.Model(friction="stribeck", alpha=0.0, Vb=1.5))
    assert c.period == pytest.approx(paper.period, rel=1e-8)
    stuck = sum(t1 - t0 for (t0, _, a), (t1, _, _) in zip(c.switches, c.switches[1:]) if a == 0)
    stuck += c.period - c.switches[-1][0] if c.switches[-1][2] == 0 else 0.0
    assert stuck == pytest.approx(paper.stick_time, rel=1e-8)
    # the tangential multipliers: the stick's 0 in both (the paper adds its normal motion's)
    assert abs(c.multipliers[0]) < 1e-8
    assert sorted(abs(paper.multipliers))[:2] == pytest.approx([0, 0], abs=1e-8)
    assert abs(c.trivial_multiplier - 1) < 1e-8
    # the monodromy against central differences of the run (Stribeck's friction is
    # continuous at the stick's end: the run over T is smooth there)
    M_fd = _fd_monodromy(s, c.state, c.period, c.mode)
    assert np.allclose(c.monodromy, M_fd, atol=1e-5)


def _slip_cycle(vb, belt="belt_1dof"):
    """The unstable pure-slip cycle, seeded at the section x = x_eq, x' = 0.8 Y with the
    first-order averaged amplitude Y^2 = 8 v_s (e^(Vb - Vb_H) - 1) (docs/modelling.md)."""
    s = System(belt, friction="stribeck", Vb=vb)
    p = s.params
    vh = p["v_s"] * math.log(p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"]))
    mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-vb / p["v_s"])
    Y = math.sqrt(8 * p["v_s"] * (math.exp(vb - vh) - 1))
    return self_excited_cycle(s, [mu * p["g"] / p["omega1"] ** 2, 0.8 * Y], 2 * math.pi)


@pytest.mark.parametrize("belt", BELTS)
def test_unstable_slip_cycle_agrees_with_the_paper_model_and_finite_differences(belt):
    c = _slip_cycle(2.5, belt)
    assert c.kind == "slip" and not c.stable
    paper = beltmdsm.cycle(
        beltmdsm.Model(friction="stribeck", alpha=0.0, Vb=2.5),
        guess=[*_on_paper_section(c), X2_EQ, 0.0],
        period=c.period,
    )
    assert c.period == pytest.approx(paper.period, rel=1e-8)
    assert c.multipliers[0].real == pytest.approx(max(abs(paper.multipliers)), rel=1e-8)
    # the section is where the slip speed is least: v_r there is the paper's largest
    v_r = c.state[1] - 2.5
    assert v_r == pytest.approx(paper.max_relative_velocity, abs=1e-8)
    # the multiplier against central differences of the return map to the section
    s = c.system
    M_fd = _fd_monodromy(s, c.state, c.period, c.mode)
    assert np.allclose(c.monodromy, M_fd, rtol=1e-6, atol=1e-6)
    f = s.kernels.field(0, c.state, s.p, c.mode)
    # the Poincare map's multiplier: the eigenvalue of the differences off the flow
    w = np.linalg.eigvals(M_fd)
    off = w[np.argmax(abs(w - 1))]
    assert off.real == pytest.approx(c.multipliers[0].real, rel=1e-6)
    assert np.allclose(M_fd @ f, f, atol=1e-6)
    # least period: the cycle asked with twice its period returns at half
    again = _slip._shoot_slip(s, c.state, 2 * c.period, 30, dict(rtol=1e-11, atol=1e-11))
    assert again.period == pytest.approx(c.period, rel=1e-10)


def _on_paper_section(c):
    """Near the point of the cycle where x' is least (the paper's section, X1'' = 0 at
    the largest |Vr|): a guess for the paper's shooting, which converges from it."""
    samples = []
    flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=1e-3, samples=samples)
    ys = np.concatenate([y for _, y, _ in samples])
    return ys[np.argmin(ys[:, 1])]


def test_stick_onset_agrees_with_the_paper_model():
    onset = stick_onset(_slip_cycle(2.5), "Vb", 0.2)
    vb = onset.system.params["Vb"]
    assert abs(onset.state[1] - vb) < 1e-11  # the cycle grazes v_r = 0
    assert vb == pytest.approx(2.900393, abs=1e-6)  # docs/modelling.md's onset
    # the paper's sliding cycles just below it: their largest v_r, extrapolated
    # linearly to 0 from 1e-5 below (curvature error ~ 1e-10), is the paper's onset
    values, tops = [], []
    for d in (1e-3, 1e-5):
        mine = self_excited_cycle(
            onset.system.replace(Vb=vb - d), onset.state - [0, 2 * d], onset.period
        )
        paper = beltmdsm.cycle(
            beltmdsm.Model(friction="stribeck", alpha=0.0, Vb=vb - d),
            guess=[*_on_paper_section(mine), X2_EQ, 0.0],
            period=mine.period,
        )
        assert paper.n_sticks == 0
        assert paper.period == pytest.approx(mine.period, rel=1e-10)
        assert paper.max_relative_velocity == pytest.approx(mine.state[1] - (vb - d), abs=1e-10)
        values.append(vb - d)
        tops.append(paper.max_relative_velocity)
    slope = (tops[1] - tops[0]) / (values[1] - values[0])
    paper_onset = values[1] - tops[1] / slope
    assert paper_onset == pytest.approx(vb, abs=1e-8)


@pytest.mark.parametrize("belt", BELTS)
def test_forced_model_and_bad_guesses_are_refused(belt):
    with pytest.raises(Unsupported, match="self-excited cycle needs the autonomous model"):
        self_excited_cycle(System(belt, alpha_t=1.0))
    s = System(belt, friction="stribeck")
    with pytest.raises(ValueError, match=r"guess: not 2 finite numbers \(x, x_dot\)"):
        self_excited_cycle(s, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="period=-1"):
        self_excited_cycle(s, [1.0, 2.0], -1)
