"""`beltmdsm.oscillator.cycle.genuine`'s threshold of a slip phase (issue 39): a phase
counts where it lasts longer than the rounding of its integration, ``100 (rtol + atol /
scale) tau`` (its docstring's error model), not a typed share of the time scale.

Both directions, on ``belt_1dof`` under static/kinetic friction (``tau = 1 / omega1``):

* a real short phase is kept: a run that starts slipping back at ``v_r = -eps`` sticks
  after ``eps / a`` (``a`` its slip acceleration, typed here), 1e-8 of ``tau`` at the
  tolerances 1e-12; the state moves by ``1e-8`` over it, 1e4 times its tolerance. The old
  threshold (1e-6 of ``tau``) dropped it;
* a rounding artefact is dropped: at the tolerances 1e-6, a slip phase over which the
  state moves by its tolerance ``atol + rtol |x|`` (the time that takes at the speed
  ``|f(x)|`` at the cycle's state) is indistinguishable from none. The old threshold
  kept it, as would any threshold that does not grow with the tolerances.
"""

import dataclasses

import numpy as np
import pytest

from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.oscillator import System, self_excited_cycle
from beltmdsm.oscillator.cycle import genuine
from beltmdsm.oscillator.hybrid import flow
from beltmdsm.oscillator.stick_slip_shooting import _nth_end

SYSTEM = System("belt_1dof", friction="static_kinetic", Vb=0.5)


@pytest.fixture(scope="module")
def cycle():
    c = self_excited_cycle(SYSTEM)
    assert c.kind == "stick_slip" and c.sticks == 1
    return c


def _slip_acceleration(p, x):
    """x'' while slipping back (v_r < 0): the kinetic friction mu_k g pushes forward."""
    return -2 * p["beta1"] * p["omega1"] * p["Vb"] - p["omega1"] ** 2 * x + p["mu_k"] * p["g"]


def test_a_real_short_slip_phase_is_kept(cycle):
    p = SYSTEM.params
    tau = 1.0 / p["omega1"]
    x = 1.0  # inside the friction cone: the slip accelerates forward, towards stick
    a = _slip_acceleration(p, x)
    assert a > 0
    eps = 1e-8 * tau * a
    tol = dict(rtol=1e-12, atol=1e-12)
    run = flow(SYSTEM, 0.0, [x, p["Vb"] - eps], np.inf, mode=-1, stop=_nth_end(1), **tol)
    (t_stick, before, after), (t_end, _, back) = run.switches
    # the phase is physical: its length is eps / a (a constant to first order)
    assert (before, after, back) == (-1, 0, -1)
    assert t_stick == pytest.approx(eps / a, rel=1e-6)
    # a cycle of this run (slip, stick, slip again at its end), shot at these tolerances
    c = dataclasses.replace(
        cycle, state=np.array([x, p["Vb"] - eps]), mode=-1, period=t_end,
        switches=run.switches, **tol,
    )  # fmt: skip
    assert genuine(c) is c
    assert t_stick < 1e-6 * tau  # below the old typed threshold, which refused it


def test_a_rounding_artefact_is_dropped(cycle):
    tol = dict(rtol=1e-6, atol=1e-6)
    x = cycle.state
    speed = float(np.abs(SYSTEM.kernels.field(0.0, x, SYSTEM.p, cycle.mode)).max())
    # the time over which the state moves by its tolerance: no phase at that resolution
    rounding = (tol["atol"] + tol["rtol"] * float(np.abs(x).max())) / speed
    tau = 1.0 / SYSTEM.params["omega1"]
    assert rounding > 1e-6 * tau  # above the old typed threshold, which kept it
    # the stick ends at the state and begins again after that time, then lasts a period
    switches = [(rounding, cycle.mode, 0), (cycle.period, 0, cycle.mode)]
    c = dataclasses.replace(cycle, switches=switches, **tol)
    with pytest.raises(NoPeriodicResponse, match="the rounding of its integration"):
        genuine(c)
    # the same phase at tight tolerances is a real one (1e5 times their rounding)
    assert genuine(dataclasses.replace(c, rtol=1e-11, atol=1e-11)) is not None
