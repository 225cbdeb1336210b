"""Another model's forced branch on the one driver (issue 39): `beltmdsm.branches.continue_branch`
from a branch's end, and the folds and period doublings its branch reports.

The references are typed here: the 1-DOF belt oscillator under Stribeck friction in
backward slip (v_r = x' - Vb < 0 throughout), per unit mass

    x'' + 2 beta1 omega1 x' + omega1^2 x = alpha_t Omega_t^2 sin(Omega_t t + phase_t)
                                            + mu(Vb - x') N(t),
    mu(u) = mu_k + (mu_s - mu_k) exp(-u / v_s),  N(t) = g - alpha_n Omega_n^2 sin(Omega_n t),

with its variational equations, run by scipy's solve_ivp (DOP853); the bifurcation is
solved by scipy.optimize.fsolve on the extended system ``P(x) - x = 0``,
``det(M - sigma I) = 0`` (sigma = +1 a fold, -1 a period doubling) in the state and the
parameter. That system is regular at a fold and at a period doubling, so its solution
moves by the integration error times a condition number of order one: the reference's
(rtol = atol = 1e-12) moves the period doublings by 1.4e-13 against 1e-13 and by 1.3e-12
against 1e-11; the package integrates at `TOL` = 1e-11, so some 1e-11. `REF_ERR`
bounds both with a factor 10 to spare. The package locates a special point to its
reported ``accuracy`` on its own period map; the errors add.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

import beltmdsm
from beltmdsm import Model
from beltmdsm.branches import continue_branch
from beltmdsm.continuation.oscillator_forced import TOL, OscillatorForcedProblem
from beltmdsm.errors import Unsupported
from beltmdsm.oscillator import steady_sliding
from beltmdsm.oscillator.api import system_of
from beltmdsm.periodic.newton import NEWTON_TOL, fixed_point

#: The integration errors of both in a located parameter value (module docstring).
REF_ERR = 1e-10
#: Period doubling: normal-load modulation near twice the natural frequency, beside the
#: Hopf point of steady sliding (Vb = ln(g (mu_s - mu_k) / (2 beta1 omega1 v_s)) = 1.9957):
#: the modulated negative slope of the friction is a parametric damping.
PD_MODEL = dict(model="belt_1dof", friction="stribeck", Vb=2.1, alpha_n=0.4, Omega_n=1.8)
#: Fold: tangential excitation at resonance (Omega_t = omega1) above the Hopf point, in
#: the excitation's amplitude: the subcritical Hopf point's unstable cycle bends the
#: branch back.
FOLD_MODEL = dict(model="belt_1dof", friction="stribeck", Vb=2.2, alpha_t=0.01, Omega_t=1.0)


def _reference(params, param, sigma, guess, value, tol=1e-12):
    """The bifurcation point of the typed model (module docstring): ``(value, state,
    max x' over the orbit)``."""
    p = dict(params)

    def run(x, v):
        q = {**p, param: v}
        w, b, W_t, W_n = q["omega1"], q["beta1"], q["Omega_t"], q["Omega_n"]
        dmu = q["mu_s"] - q["mu_k"]
        T = 2 * math.pi / (W_t if q["alpha_t"] else W_n)

        def field(t, y):
            N = q["g"] - q["alpha_n"] * W_n**2 * math.sin(W_n * t + q["phase_n"])
            slope = N * dmu / q["v_s"] * math.exp(-(q["Vb"] - y[1]) / q["v_s"])
            mu = q["mu_k"] + dmu * math.exp(-(q["Vb"] - y[1]) / q["v_s"])
            force = q["alpha_t"] * W_t**2 * math.sin(W_t * t + q["phase_t"])
            A = np.array([[0.0, 1.0], [-w * w, -2 * b * w + slope]])
            dy = [y[1], -2 * b * w * y[1] - w * w * y[0] + force + mu * N]
            return np.concatenate([dy, (A @ y[2:].reshape(2, 2)).ravel()])

        y0 = np.concatenate([x, np.eye(2).ravel()])
        return solve_ivp(field, (0, T), y0, method="DOP853", rtol=tol, atol=tol,
                         dense_output=True)  # fmt: skip

    def equations(z):
        r = run(z[:2], z[2])
        M = r.y[2:, -1].reshape(2, 2)
        return [*(r.y[:2, -1] - z[:2]), np.linalg.det(M - sigma * np.eye(2))]

    z = fsolve(equations, [*guess, value], xtol=1e-13)
    assert np.max(np.abs(equations(z))) < 1e-10
    r = run(z[:2], z[2])
    fastest = float(np.max(r.sol(np.linspace(0, r.t[-1], 2001))[1]))
    return float(z[2]), z[:2], fastest


@pytest.fixture(scope="module")
def pd_branch():
    return beltmdsm.branch(Model(**PD_MODEL), param="Omega_n", lo=1.8, hi=2.2)


def test_the_branch_reports_two_period_doublings_where_a_multiplier_is_minus_one(pd_branch):
    b = pd_branch
    assert [s.kind for s in b.special] == [
        "range", "period_doubling", "period_doubling", "range",
    ]  # fmt: skip
    params = b.system.params
    for s, stable in zip(b.special[1:3], (True, False)):
        assert s.stable_before is stable and s.stable_after is not stable
        near = b.point_near(s.value)
        value, state, fastest = _reference(params, "Omega_n", -1.0, near.state, s.value)
        assert fastest < params["Vb"]  # the reference's orbit slips backwards throughout
        assert abs(s.value - value) <= s.accuracy + REF_ERR, (s.value, value)
        # the critical multiplier at the located point is -1 to the locating accuracy
        # (its rate in Omega_n is about 1: 2e-8 here)
        assert np.min(np.abs(s.multipliers + 1.0)) < 1e-5
    # between them the response is unstable, a real multiplier below -1
    inside = b.point_near(2.0)
    assert not inside.stable and np.min(inside.multipliers.real) < -1.0
    assert np.all(np.abs(inside.multipliers.imag) == 0.0)


def test_the_branch_reports_a_fold_where_a_multiplier_is_plus_one():
    m = Model(**FOLD_MODEL)
    # from steady sliding: a run from rest sticks and lands on the stick-slip cycle
    guess = steady_sliding(system_of(m)).state
    start = beltmdsm.periodic_response(m, guess=guess)
    b = continue_branch(start, "alpha_t", 0.01, 1.0)
    assert [s.kind for s in b.special] == ["range", "fold", "range"]
    fold = b.special[1]
    assert fold.stable_before is True and fold.stable_after is False
    # the branch turns back: both ends at the lower bound, the fold its largest value
    assert b.special[0].value == b.special[-1].value == 0.01
    assert b.value_range()[1] == pytest.approx(fold.value, abs=fold.accuracy + 1e-12)
    near = b.point_near(fold.value)
    value, state, fastest = _reference(b.system.params, "alpha_t", 1.0, near.state, fold.value)
    assert fastest < b.system.params["Vb"]
    assert abs(fold.value - value) <= fold.accuracy + REF_ERR, (fold.value, value)
    # at a fold the multiplier moves linearly along the arclength while the parameter
    # moves quadratically: the accuracy's square root (6e-4), with room
    assert np.min(np.abs(fold.multipliers - 1.0)) < 3 * math.sqrt(fold.accuracy)
    # continued again from its point nearest the fold: both ways round the same fold
    again = continue_branch(near, "alpha_t", 0.01, 1.0)
    assert [s.kind for s in again.special] == ["range", "fold", "range"]
    assert abs(again.special[1].value - value) <= again.special[1].accuracy + REF_ERR


def test_continuing_a_branch_from_its_end_gives_the_one_branch(pd_branch):
    whole = pd_branch
    first = beltmdsm.branch(Model(**PD_MODEL), param="Omega_n", lo=1.8, hi=2.0)
    more = continue_branch(first.points[-1], "Omega_n", 2.0, 2.2)
    assert more.kind == "forced" and more.model.model == "belt_1dof"
    assert more.model["Omega_n"] == 2.0 and more.value_range() == [2.0, 2.2]
    # the special points of the pieces, less the joint's range ends, are the whole's
    joined = first.special[:-1] + more.special[1:]
    assert [s.kind for s in joined] == [s.kind for s in whole.special]
    for a, b in zip(joined, whole.special):
        assert abs(a.value - b.value) <= a.accuracy + b.accuracy + 1e-12
    # every point of the pieces lies on the whole branch: the response solved at its
    # value from the whole's nearest point is its state, to the corrector's tolerance
    # over the smallest singular value of M - I (its residual NEWTON_TOL, the
    # integrator's TOL, each at both solutions)
    system = whole.system
    problem = OscillatorForcedProblem(system, "Omega_n", 1, 1.8, 2.2, 1.0)
    for q in first.points + more.points:
        at = fixed_point(problem.pmap(q.value), whole.point_near(q.value).state)
        scale = 1.0 + float(np.max(np.abs(q.state)))
        sigma = np.linalg.svd(at.image.jacobian - np.eye(2), compute_uv=False)[-1]
        tol = 2 * (NEWTON_TOL + TOL) * scale / sigma
        assert np.max(np.abs(at.state - q.state)) <= tol, (q.value, at.state - q.state, tol)
    assert whole.points[-1].state == pytest.approx(more.points[-1].state, abs=1e-9)


def test_continue_branch_of_another_model_refuses_what_it_cannot_run():
    m = Model(**PD_MODEL)
    first = beltmdsm.branch(m, param="Omega_n", lo=1.8, hi=1.85)
    with pytest.raises(Unsupported, match="backend='python' applies to the paper's model"):
        continue_branch(first.points[-1], "Omega_n", 1.85, 1.9, backend="python")
    with pytest.raises(ValueError, match=r"start's Omega_n = 1.85 must lie in \[1.9, 2\]"):
        continue_branch(first.points[-1], "Omega_n", 1.9, 2.0)
    with pytest.raises(ValueError, match="param must be a parameter of model 'belt_1dof'"):
        continue_branch(first.points[-1], "omega", 1.8, 2.0)
    # a self-excited cycle is no longer refused (its problem: beltmdsm/continuation/
    # oscillator_cycle.py; tests/beltmdsm/continuation/test_oscillator_cycle_continuation.py)
    cycle = beltmdsm.periodic_response(Model(model="belt_1dof", friction="stribeck", Vb=1.5))
    with pytest.raises(Unsupported, match="backend='python' applies to the paper's model"):
        continue_branch(cycle, "Vb", 1.4, 1.6, backend="python")


@pytest.mark.parametrize(
    "model, why",
    [
        (dict(model="belt_1dof", friction="stribeck", Vb=1.5), "set an excitation amplitude"),
        (dict(model="hoffmann"), "the model has no excitation terms"),
    ],
)
def test_branch_of_an_unforced_model_is_refused_in_one_line(model, why):
    """The self-excited kind of another model: no Branch to continue (`branch --model`
    follows its cycles from the Hopf points instead)."""
    with pytest.raises(Unsupported) as err:
        beltmdsm.branch(Model(**model), param="Vb", lo=1.0, hi=2.0)
    (line,) = str(err.value).splitlines()
    assert f"model {model['model']!r}" in line and why in line
