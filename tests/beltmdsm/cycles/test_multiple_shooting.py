"""Multiple shooting of self-excited cycles (issue 36 item 8), against references.

The branch of Stribeck cycles at ``Vb = 1.5`` continued in ``v_s`` ended at ``v_s =
0.142`` (largest multiplier 1.07e3, single shooting's limit) before its stick onset.
References, independent of the package's shooting: the cycle of the tangential
equation typed by hand (the normal motion sits at its equilibrium, where the Hertz
force is ``g``: the 4-state model's invariant plane, as tests/beltmdsm/cycles/
test_cycles.py uses it), found by scipy's ``solve_ivp`` backwards in time, where the
unstable cycle attracts: its return map to the section ``X1' = 0`` (largest ``X1``)
contracts by ``1 / |mu|``, so plain iteration converges; central differences of the
residual and of that return map.

Error model. The reference integrates at 1e-13 over one period (6.5 s) backwards,
contracting: its cycle errs by about 1e-12 of the state. The package's segments run at
``RTOL = 1e-12`` and each amplifies by at most ``|mu|^(1/m)``; its cycle satisfies the
continuity to ``NEWTON_TOL = 1e-11``, and its largest ``Vr`` is the maximum of one run
over the period from ``x_0`` (amplified by up to ``|mu| ~ 1e3``: 1e-8). Periods and
largest ``Vr`` agree to 1e-7; the stick onset, where ``d(max Vr)/d v_s = -0.38``,
to the onset's stated accuracy plus 1e-6.
"""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from beltmdsm.continuation.problem import Residual
from beltmdsm.cycles.continuation import CycleProblem
from beltmdsm.cycles.multiple import MultipleCycleProblem
from beltmdsm.model import Model
from beltmdsm.periodic.cycle_flow import CycleFlow
from beltmdsm.periodic.cycle_segments import split_run

ROOT = Path(__file__).resolve().parents[3]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
P = dict(beta1=0.1, omega1=1.0, mu_s=0.4, mu_k=0.25, g=9.81)
VB = 1.5


def accel(x, v, vs):
    """``X1''`` slipping back (``Vr < 0``), Stribeck's law, the normal force ``g``."""
    mu = P["mu_k"] + (P["mu_s"] - P["mu_k"]) * math.exp(-(VB - v) / vs)
    return P["g"] * mu - P["omega1"] ** 2 * x - 2 * P["beta1"] * P["omega1"] * v


def back_map(x0, vs):
    """From ``(x0, 0)`` on the section (largest ``X1``), one turn backwards in time:
    ``(X1 at the return, largest X1' on the way, period)``."""

    def f(t, y):
        return [-y[1], -accel(y[0], y[1], vs)]

    def section(t, y):
        return y[1]

    def top(t, y):  # X1'' = 0: the extremes of X1'
        return accel(y[0], y[1], vs)

    section.direction = 1
    sol = solve_ivp(
        f, (0, 12), [x0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13, events=(section, top)
    )
    k = next(i for i, t in enumerate(sol.t_events[0]) if t > 1.0)
    T = float(sol.t_events[0][k])
    v_max = max(float(y[1]) for t, y in zip(sol.t_events[1], sol.y_events[1]) if t < T)
    return float(sol.y_events[0][k][0]), v_max, T


def reference_cycle(vs):
    """``(X1 on the section, largest Vr, period)`` of the sliding cycle at ``v_s``."""
    x = accel(0.0, 0.0, vs) / P["omega1"] ** 2 + 0.05  # just off steady sliding
    for _ in range(200):
        new, v_max, T = back_map(x, vs)
        if abs(new - x) < 1e-13 * (1 + abs(x)):
            return new, v_max - VB, T
        x = new
    raise AssertionError("the backward return map does not converge")


def reference_multiplier(vs):
    """The forward return map's derivative: one over the backward one's, by central
    differences (the backward map contracts by ~1e-3: 1e-4 of X1 moves it by 1e-7,
    against its error of 1e-13)."""
    x, _, _ = reference_cycle(vs)
    h = 1e-4
    d = (back_map(x + h, vs)[0] - back_map(x - h, vs)[0]) / (2 * h)
    return 1.0 / d


def problem_at(vs, m):
    """A multiple-shooting problem in ``v_s`` at ``Vb = 1.5``, and its unknowns on the
    reference cycle (split from one run over the period)."""
    model = Model(friction="stribeck", alpha=0.0, Vb=VB, v_s=vs)
    flow = CycleFlow(model, "v_s")
    x1, _, T = reference_cycle(vs)
    x = np.array([x1, 0.0, model_x2(model), 0.0])
    # onto the package's section, the smallest X1' (a run of the reference cycle)
    tr = flow.run(x, T, vs).trajectory
    t = np.linspace(0.0, T, 4001)
    x = tr.state(t)[:, int(np.argmin(tr.state(t)[1]))]
    single = CycleProblem(flow, 0.1, 0.6, 12.0, T, x, vs)
    ms = MultipleCycleProblem(single, m)
    return ms, ms.z_of(split_run(flow, x, T, vs, m), T, vs)


def model_x2(model):
    """The normal equilibrium ``(g / omega2^2)^(2/3)`` (Eq. 9)."""
    return (model["g"] / model["omega2"] ** 2) ** (2.0 / 3.0)


def test_the_segments_residual_and_jacobian_against_central_differences():
    # on the reference cycle at v_s = 0.142 (|mu| ~ 1e3, where single shooting ended),
    # moved off it so that no block vanishes; 4 segments
    ms, z = problem_at(0.142, 4)
    rng = np.random.default_rng(1)
    # (a larger move lets the last segment, which amplifies by ~600, reach Vr = 0:
    # a stick phase, across which the residual has a kink)
    z = z + 1e-7 * rng.standard_normal(z.size)
    r = ms.residual(z, 0.0, 0)
    assert isinstance(r, Residual) and r.F.shape == (17,)
    J = ms.jacobian(r.data)
    assert J.shape == (17, 18)
    h = 1e-7
    fd = np.empty_like(J)
    for i in range(z.size):
        e = np.zeros(z.size)
        e[i] = h
        F = {k: ms.residual(z + k * e, 0.0, 0) for k in (-2, -1, 1, 2)}
        for r in F.values():  # no stick phase: the residual is smooth here
            assert not any(int(new) == 0 for img in r.data[3] for *_, new in img.run.events)
        fd[:, i] = (8 * (F[1].F - F[-1].F) - (F[2].F - F[-2].F)) / (12 * h)
    # the five-point difference: its truncation ~h^4 |F^(5)| is negligible even where
    # the last segments amplify by ~600 through Stribeck's steep fall (the central
    # difference's h^2 |F^(3)| was 1.5 at h = 1e-6); rounding: the runs' error 1e-12
    # amplified by <= 600, over h sx = 1.2e-6, ~1e-3 against entries up to 600
    # (2e-6 of the scale); the p column is itself a central difference (step 1e-6)
    scale = np.abs(J).max()
    np.testing.assert_allclose(J, fd, atol=1e-5 * scale)
    # the continuity blocks have the structure M_i, -I
    assert np.allclose(J[:4, 4:8], -np.eye(4) * (ms.sx / ms.sx))


def test_one_cycle_by_multiple_shooting_is_the_reference_cycle():
    vs = 0.142
    ms, z = problem_at(vs, 16)
    row = np.zeros(z.size)
    row[-1] = 1.0
    step = ms.solve(z, lambda q: (float(q[-1] - z[-1]), row), fresh=True)
    point = ms.point(step, 1.0)
    _, vr_max, T = reference_cycle(vs)
    assert point.value == vs and point.n_sticks == 0
    assert point.period == pytest.approx(T, rel=1e-9)
    assert point.max_relative_velocity == pytest.approx(vr_max, abs=1e-7)
    # the Floquet multipliers from the product of the 16 segments' monodromies
    mu = reference_multiplier(vs)
    assert mu > 1e3
    assert point.max_abs_multiplier == pytest.approx(abs(mu), rel=1e-5)
    assert abs(point.trivial_multiplier - 1) < 1e-6
    assert point.segments.shape == (16, 4) and not point.stable


def test_the_reference_onset_is_where_the_largest_vr_of_the_sliding_cycle_reaches_zero():
    onset = brentq(lambda vs: reference_cycle(vs)[1], 0.1, 0.12, xtol=1e-13)
    assert onset == pytest.approx(0.1027581325, abs=1e-9)


@pytest.mark.slow
def test_the_branch_in_v_s_reaches_the_stick_onset_of_a_reference():
    """The report's command: ``branch --alpha 0 --friction stribeck --Vb 1.5 --param v_s
    --from 0.1 --to 3`` ran 2 min 40 s to "stopped after 2000 points", then ended at
    v_s = 0.142 where the largest multiplier passed 1e3. Now multiple shooting goes on
    to the stick onset (v_s = 0.1027581, |mu| = 5e4 there) and the stick-slip cycles
    beyond it to the range's end (23 s of CPU, 1-2 min on a loaded machine)."""
    argv = ["branch", "--alpha", "0", "--friction", "stribeck", "--Vb", "1.5"]
    argv += ["--param", "v_s", "--from", "0.1", "--to", "3", "--json"]
    out = subprocess.run(
        [sys.executable, "-m", "beltmdsm", *argv],
        capture_output=True, text=True, timeout=900, cwd=ROOT, env=ENV,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    found = json.loads(out.stdout)
    kinds = [s["kind"] for s in found["special_points"]]
    assert kinds == ["hopf", "stick_onset", "range"], found["special_points"]
    onset = found["special_points"][1]
    reference = brentq(lambda vs: reference_cycle(vs)[1], 0.1, 0.12, xtol=1e-13)
    assert onset["accuracy"] <= 1e-6
    assert abs(onset["value"] - reference) <= onset["accuracy"] + 1e-7, (onset, reference)
    # the sliding cycles along the branch, those past single shooting's limit too
    # (where |mu| > 10: the reference's backward map contracts by 1/|mu| per turn; near
    # the Hopf point it barely contracts)
    sliding = [q for q in found["points"] if q["n_sticks"] == 0 and q["max_abs_multiplier"] > 10]
    assert any(q["max_abs_multiplier"] > 1e4 for q in sliding)
    for q in sliding[:: max(1, len(sliding) // 8)]:
        _, vr_max, T = reference_cycle(q["value"])
        assert q["period"] == pytest.approx(T, rel=1e-8), q["value"]
        assert q["max_relative_velocity"] == pytest.approx(vr_max, abs=1e-7), q["value"]
