"""A fold of self-excited cycles on the one continuation driver (issue 39), located by
`beltmdsm.oscillator.hopf_branch` on `OscillatorCycleProblem` and checked against a
reference computed here.

No shipped model has a smooth fold of cycles before its stick onset, so the test model is
derived here into a temporary folder, never registered nor shipped (as
tests/derive/models/test_model_units.py derives the how-to's example): the belt_1dof
entry with a quintic damper, per unit mass

    x'' + 2 beta1 omega1 x' + omega1^2 x + c5 x'^5 = mu(v_r) g,  v_r = x' - Vb < 0,

under Stribeck's law ``mu(v) = mu_k + (mu_s - mu_k) exp(-|v| / v_s)``. The damper leaves
steady sliding (x' = 0) and its Hopf point alone: subcritical, the unstable slip cycles
grow from it with Vb. The damper takes ``<c5 x'^6>`` of energy per period, growing
faster than the friction's pumping at moderate amplitude (averaging: ``g (mu_s - mu_k)
e^(-Vb/v_s) I1(A/v_s) = beta1 omega1 A + 5/16 c5 A^5``), so the unstable cycles turn
back at a fold into stable larger ones, which fall in Vb to their stick onset. With c5 =
0.01 the fold lies at Vb ~ 2.118 with x' <= 1.45 on the cycle, its least slip speed
0.67, clear of the onset (~ 2.048).

The reference: the equation above typed by hand, solve_ivp (DOP853, rtol 1e-12) from the
section ``x'' = 0`` falling (where x' is largest, the driver's section on a slip cycle)
to its next crossing, the return map ``P(v; Vb)`` of the section's x'. A cycle through
``v`` exists at the Vb solving ``P(v; Vb) = v`` (brentq); along the branch so
parametrized by ``v`` the fold is the largest Vb (Brent's method on ``v``).
"""

import importlib.util
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from beltmdsm.derive.models import get
from beltmdsm.derive.models.registry import check
from beltmdsm.derive.models.render import render_entry
from beltmdsm.derive.parameters import Parameter
from beltmdsm.generated.models import MODELS
from beltmdsm.oscillator import System, hopf_points
from beltmdsm.oscillator.hopf_branch import hopf_branch

C5 = 0.01


@pytest.fixture(scope="module")
def damped():
    """The belt_1dof entry with the quintic damper, derived (Stribeck's law only) and
    imported from a temporary folder (module docstring)."""
    base = get("belt_1dof")
    entry = replace(
        base,
        name="belt_quintic",
        summary="belt_1dof with a quintic damper (a test model: a fold of cycles)",
        parameters=base.parameters
        + (Parameter("c5", "s^3/m^4", C5, "nonnegative", "quintic damper per unit mass"),),
        forces=lambda P, q, v, t: {"x": -P["c5"] * v["x"] ** 5},
        friction_laws=("stribeck",),
    )
    check(entry)
    return entry


@pytest.fixture(scope="module")
def module(damped, tmp_path_factory):
    path = tmp_path_factory.mktemp("derived") / f"{damped.name}.py"
    path.write_text(render_entry(damped), encoding="utf-8")
    spec = importlib.util.spec_from_file_location(damped.name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.NAME not in MODELS
    return mod


def _return_map(p, Vb):
    """``v -> P(v; Vb)``: the typed equation from the section state with ``x' = v`` to
    the next crossing of ``x'' = 0`` falling."""
    w, z, g, c5 = p["omega1"], p["beta1"], p["g"], p["c5"]

    def acc(x, v):
        mu = p["mu_k"] + (p["mu_s"] - p["mu_k"]) * math.exp(-abs(v - Vb) / p["v_s"])
        return -2 * z * w * v - w * w * x - c5 * v**5 + mu * g

    def rhs(t, u):
        return [u[1], acc(u[0], u[1])]

    def event(t, u):
        return acc(u[0], u[1])

    event.terminal, event.direction = True, -1

    def image(v):
        x = acc(0.0, v) / w**2  # x'' = 0 at (x, v): the equation is linear in x
        # past the start (where the event function is 0) before arming the event
        first = solve_ivp(rhs, (0, 0.5), [x, v], method="DOP853", rtol=1e-12, atol=1e-13)
        sol = solve_ivp(rhs, (0.5, 100.0), first.y[:, -1], method="DOP853", rtol=1e-12,
                        atol=1e-13, events=event)  # fmt: skip
        assert sol.status == 1
        return sol.y_events[0][0][1]

    return image


def _branch_value(p, v, lo=2.05, hi=2.2):
    """The Vb of the cycle through the section with ``x' = v`` (near the fold, where
    ``P(v; Vb) - v`` falls through 0 once in ``[lo, hi]``)."""
    return brentq(lambda Vb: _return_map(p, Vb)(v) - v, lo, hi, xtol=1e-14, rtol=1e-15)


@pytest.fixture(scope="module")
def reference(module):
    """The fold's Vb: the largest Vb along the branch parametrized by the section's x'."""
    p = System(module, friction="stribeck").params
    best = minimize_scalar(lambda v: -_branch_value(p, v), bracket=(1.2, 1.45, 1.7), tol=1e-8)
    return float(-best.fun)


# span 0.5 throws corrector iterates across the fold where the quintic damper overflows a
# trial step: the stepper rejects it, silently (oscillator/_stepper.py)
@pytest.mark.filterwarnings("error::RuntimeWarning")
@pytest.mark.parametrize("span", [0.1, 0.5])
def test_a_fold_of_self_excited_cycles_against_the_reference(module, reference, span):
    """``span`` 0.5: steps long enough to throw a corrector's iterate across the fold
    into a stiff field (the damper at large x'), where the stepper once rejected its
    least step forever (beltmdsm/oscillator/_stepper.py)."""
    s = System(module, friction="stribeck")
    p = s.params
    (h,) = hopf_points(s, "Vb", 0.5, 5.0)
    # the damper leaves steady sliding (x' = 0) and so the belt's Hopf point alone
    typed = p["v_s"] * math.log(
        p["g"] * (p["mu_s"] - p["mu_k"]) / (2 * p["beta1"] * p["omega1"] * p["v_s"])
    )
    assert h == pytest.approx(typed, abs=1e-10)
    b = hopf_branch(s, "Vb", float(h), span)
    assert b.criticality == "subcritical" and not b.failure
    assert [sp.kind for sp in b.special] == ["fold", "stick_onset"]
    fold, onset = b.special
    # the branch passes through it: unstable cycles up to it, stable ones after, the
    # nontrivial multiplier through +1 there
    values = np.array([c.system.params["Vb"] for c in b.cycles])
    i = int(np.argmax(values))
    assert fold.stable_before is False and fold.stable_after is True
    assert all(not c.stable and abs(c.multipliers[0]) > 1 for c in b.cycles[:i])
    assert all(c.stable and abs(c.multipliers[0]) < 1 for c in b.cycles[i + 1 :])
    assert all(np.diff(values[: i + 1]) > 0) and all(np.diff(values[i:]) < 0)
    assert onset.value < fold.value and fold.value - onset.value > 0.05
    # a smooth fold well before the stick onset: the least slip speed Vb - x' there
    top = b.cycles[i]
    assert top.system.params["Vb"] - top.state[1] > 0.5
    # the fold's multiplier nearer +1 than any cycle's of the walk
    assert abs(fold.multipliers[0] - 1) < min(abs(c.multipliers[0] - 1) for c in b.cycles)
    print(f"fold {fold.value!r} +- {fold.accuracy:.3g}; reference {reference!r}; "
          f"error {fold.value - reference:.3g}")  # fmt: skip
    # the error model: the driver's reported accuracy (the located cycle's distance below
    # the turn, `beltmdsm.continuation.special.regula_falsi`) plus the reference's: each
    # Vb by brentq to 1e-14 on a return map good to ~1e-12 (rtol 1e-12, a slope dP/dVb
    # of order 1), Brent's v to 1e-8 costing ~0.2 (1e-8)^2 at the top
    assert fold.value == pytest.approx(reference, abs=fold.accuracy + 1e-11)
    # the accuracy is not the bracket's spread of Vb (both ends sit below the turn)
    assert fold.accuracy > 0 and abs(fold.value - reference) < 1e-7


def test_a_slip_run_is_bounded_in_steps(module, monkeypatch):
    """A slip run refuses past `MAX_STEPS` steps (a stiff iterate far off the cycle) in
    one line, which the corrector takes as a failed step; an ordinary one takes ~40."""
    from beltmdsm.continuation import oscillator_cycle
    from beltmdsm.errors import NoPeriodicResponse

    s = System(module, friction="stribeck", Vb=2.1)
    x = np.array([1.0, 1.0])
    y, _ = oscillator_cycle.slip_run(s, x, 6.3, -1)
    assert np.all(np.isfinite(y))
    monkeypatch.setattr(oscillator_cycle, "MAX_STEPS", 5)
    with pytest.raises(NoPeriodicResponse, match="the slip run takes more than 5 steps"):
        oscillator_cycle.slip_run(s, x, 6.3, -1)
