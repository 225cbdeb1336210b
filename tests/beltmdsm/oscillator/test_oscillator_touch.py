"""A touch of v_r = 0 shorter than the integrator's samples starts a stick (issue: the
event-driven integrator stepped over a grazing touch of its slip-velocity guard).

The reference is closed form: the undamped belt_1dof with static/kinetic friction and
no excitation slips (v_r < 0) as x = mu_k g / w^2 + A cos(w t + th), so that with
``A w = Vb (1 + delta)`` the speed x' first reaches Vb for ``2 sqrt(2 delta) / w`` only
(2.8e-4 s at delta = 1e-8, against steps of about 0.1 s and samples every 1/16 of
one): a touch, at the root of ``-A w sin(w t + th) = Vb`` (brentq). There the holding
force w^2 x = mu_k g (1 + O(sqrt delta)) is inside the cone mu_s g: the mass sticks, and
rides the belt (x' = Vb) until w^2 x reaches mu_s g.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from beltmdsm.oscillator import System
from beltmdsm.oscillator.hybrid import flow

W, VB, G, MU_S, MU_K, TH = 1.0, 1.0, 9.81, 0.4, 0.3, 0.3
TOL = 1e-10


def _backends():
    try:
        import numba  # noqa: F401
    except ImportError:
        return ["python"]
    return ["python", "numba"]


@pytest.mark.parametrize("backend", _backends())
@pytest.mark.parametrize("delta", [1e-4, 1e-6, 1e-8])
def test_a_touch_between_samples_starts_the_stick(delta, backend):
    s = System("belt_1dof", friction="static_kinetic", beta1=0.0, omega1=W, Vb=VB,
               mu_s=MU_S, mu_k=MU_K)  # fmt: skip
    A = VB * (1.0 + delta) / W
    y0 = [MU_K * G / W**2 + A * math.cos(TH), -A * W * math.sin(TH)]
    top = (1.5 * math.pi - TH) / W  # the maximum of x'
    v_r = lambda t: -A * W * math.sin(W * t + TH) - VB  # noqa: E731
    touch = brentq(v_r, top - 0.5 * math.pi / W, top, xtol=1e-15)
    x_touch = MU_K * G / W**2 + A * math.cos(W * touch + TH)
    release = touch + (MU_S * G / W**2 - x_touch) / VB
    end = flow(s, 0.0, y0, 6.0, mode=-1, rtol=TOL, atol=TOL, backend=backend)
    assert [(a, b) for _, a, b in end.switches] == [(-1, 0), (0, -1)]
    # the error model: the dense output's error in v_r, ~10 tol (1 + |y|), over the
    # rate at which v_r crosses 0 there, w Vb sqrt((1 + delta)^2 - 1)
    e_v = 10.0 * TOL * (1.0 + np.abs(y0).max())
    slope = W * VB * math.sqrt((1.0 + delta) ** 2 - 1.0)
    assert end.switches[0][0] == pytest.approx(touch, abs=e_v / slope)
    # the stick's end does not depend on where on the touch it began (x' = Vb both ways)
    assert end.switches[1][0] == pytest.approx(release, abs=e_v / VB)


def test_the_forced_branch_goes_through_the_stick_onset():
    """Just past the onset the stick is a touch of v_r = 0 shorter than the samples (the
    period map of the old integrator alternated between it and none, and the branch
    skipped 1e-3 of its range there): the branch now converges right past it."""
    import beltmdsm
    from beltmdsm import Model

    m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.7, Omega_t=0.95)
    b = beltmdsm.branch(m, param="Omega_t", lo=0.95, hi=0.97)
    # the closed form (tests/beltmdsm/oscillator/test_oscillator_forced_branch.py): the
    # harmonic response's slip-velocity amplitude reaches Vb
    onset = brentq(lambda W: 0.7 * W**3 / abs(1 - W * W + 0.2j * W) - 3.0, 0.95, 0.97, xtol=1e-14)
    (sl,) = [s for s in b.special if s.kind == "stick_onset"]
    assert sl.value == pytest.approx(onset, abs=1e-7)
    past = [q for q in b.points if q.value > onset]
    assert past and all(q.n_sticks == 1 for q in past) and b.points[-1].value == 0.97
    first = min(past, key=lambda q: q.value)
    assert first.value - onset < 5e-6
    # a response: one period returns to the state, through a stick
    back = flow(first.system, 0.0, first.state, first.period, rtol=1e-11, atol=1e-11)
    assert back.y == pytest.approx(first.state, abs=1e-8)
    assert [(a, c) for _, a, c in back.switches].count((-1, 0)) == 1
