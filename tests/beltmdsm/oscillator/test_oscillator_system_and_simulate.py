"""The generic runtime's system object and hybrid run on belt_1dof (the hand-typed module,
and the generated one where marked)."""

import numpy as np
import pytest
import reference_belt_1dof as belt
from scipy.integrate import solve_ivp

from beltmdsm.errors import Unsupported
from beltmdsm.oscillator import System, load_model, simulate

#: The hand-typed reference and the generated module (the same model, the same checks).
BELTS = [pytest.param(belt, id="reference"), pytest.param("belt_1dof", id="generated")]


def test_parameters_are_checked_where_they_enter():
    s = System(belt, friction="static_kinetic", Vb=2.0)
    assert s.params["Vb"] == 2.0 and s.params["mu_k"] == belt.DEFAULTS["mu_k"]
    assert list(s.params) == list(belt.PARAMETERS["static_kinetic"])
    assert repr(s) == "System('belt_1dof', friction='static_kinetic', Vb=2.0)"
    with pytest.raises(ValueError, match="did you mean 'omega1'"):
        System(belt, omega_1=2.0)
    with pytest.raises(ValueError, match="v_s: not a parameter of belt_1dof with friction="):
        System(belt, friction="coulomb", v_s=1.0)
    with pytest.raises(ValueError, match="friction='viscous': not a law"):
        System(belt, friction="viscous")
    with pytest.raises(ValueError, match="Vb=nan: not a finite number"):
        System(belt, Vb=float("nan"))
    with pytest.raises(ValueError, match="got 'belt_1dfo'; did you mean 'belt_1dof'"):
        load_model("belt_1dfo")
    with pytest.raises(Unsupported, match="frequencies"):
        System(belt, alpha_t=1.0, alpha_n=0.1, Omega_n=2.0).excitation_period()


def _reference_run(p, y0, t_end):
    """The static/kinetic belt oscillator by solve_ivp, stick handled by hand: slip
    (v_r < 0) until x' = Vb, then x = x_s + Vb t until the spring and damping reach
    mu_s g, then slip again."""
    w, b, g, Vb = p["omega1"], p["beta1"], p["g"], p["Vb"]
    x_end = (p["mu_s"] * g - 2 * b * w * Vb) / w**2

    def f(t, y):
        return [y[1], -2 * b * w * y[1] - w**2 * y[0] + p["mu_k"] * g]

    hit = lambda t, y: y[1] - Vb  # noqa: E731
    hit.terminal, hit.direction = True, 1
    t, y, events = 0.0, np.array(y0, float), []
    while t < t_end:
        # max_step: x' rises above Vb for only 0.07 s at t = 5.2 (by 7e-4), which
        # solve_ivp would step over
        sol = solve_ivp(
            f, (t, t_end), y, method="DOP853", rtol=1e-12, atol=1e-12, events=hit, max_step=0.01
        )
        t, y = sol.t[-1], sol.y[:, -1]
        if sol.status != 1:
            break
        events.append(t)
        stuck = (x_end - y[0]) / Vb
        if t + stuck >= t_end:
            return np.array([y[0] + Vb * (t_end - t), Vb]), events
        t += stuck
        y = np.array([x_end, Vb - 1e-13])  # below the event: solve_ivp skips a start on it
        events.append(t)
    return y, events


@pytest.mark.parametrize("belt", BELTS)
def test_stick_slip_run_agrees_with_a_solve_ivp_reference(belt):
    s = System(belt, friction="static_kinetic", Vb=1.0)
    run = simulate(s, 30.0, dt=0.01)
    y_ref, events = _reference_run(s.params, [0.0, 0.0], 30.0)
    times = [t for t, _, _ in run.switches]
    assert [(a, b) for _, a, b in run.switches[:2]] == [(-1, 0), (0, -1)]
    assert len(times) == len(events) >= 6
    assert np.allclose(times, events, atol=1e-8)
    assert np.allclose(run.y[:, -1], y_ref, atol=1e-8)
    assert run.states == ("x", "x_dot") and run["x_dot"].shape == run.t.shape
    assert set(np.unique(run.modes)) == {-1, 0}
    assert "3001 samples of x, x_dot" in repr(run)


def test_slip_reversal_without_stick():
    # the belt at rest, a strong harmonic force: the slip reverses (no stick)
    s = System(belt, Vb=0.0, beta1=0.0, mu_s=0.03, alpha_t=1.0, Omega_t=0.8)
    run = simulate(s, 30.0, [2.0, 0.0])
    kinds = {(a, b) for _, a, b in run.switches}
    assert kinds == {(1, -1), (-1, 1)}
    # between reversals, x' keeps its sign
    for (t0, _, after), (t1, _, _) in zip(run.switches, run.switches[1:]):
        inside = (run.t > t0 + 1e-6) & (run.t < t1 - 1e-6)
        assert np.all(np.sign(run["x_dot"][inside]) == after)


def test_bad_run_arguments_are_named():
    s = System(belt)
    with pytest.raises(ValueError, match="t_end=-1"):
        simulate(s, -1)
    with pytest.raises(ValueError, match="y0: not 2 finite numbers"):
        simulate(s, 1.0, [0.0, 0.0, 0.0])


def _chattering_module():
    """A toy model to the contract: both slips accelerate towards v_r = 0 and the
    friction never holds (a negative stick limit): reversals accumulate."""
    import types

    module = types.ModuleType("chattering")
    module.NAME, module.COORDINATES, module.STATES = "chattering", ("x",), ("x", "x_dot")
    module.UNILATERAL, module.FRICTION_LAWS = False, ("coulomb",)
    module.PARAMETERS, module.DEFAULTS, module.EXCITATION = {"coulomb": ("Vb",)}, {"Vb": 1.0}, ()
    module.SURFACES = ("slip_velocity", "stick_forward", "stick_back")

    def kernels(friction):
        return types.SimpleNamespace(
            field=lambda t, y, p, mode: np.array([y[1], -float(mode)]),
            slip_velocity=lambda t, y, p: y[1] - p[0],
            slip_gradient=lambda t, y, p: np.array([0.0, 1.0]),
            slip_acceleration=lambda t, y, p, mode: -float(mode),
            holding_force=lambda t, y, p: 0.0,
            stick_limit=lambda t, y, p: -1.0,
            normal_force=lambda t, y, p: 1.0,
            surfaces=lambda t, y, p: np.array([y[1] - p[0], -1.0, -1.0]),
            surface_rates=lambda t, y, p, mode: np.array([-float(mode), 0.0, 0.0]),
        )

    module.kernels = kernels
    return module


def test_accumulating_switches_outside_the_friction_cone_stop_the_run():
    run = simulate(System(_chattering_module()), 10.0, [0.0, 0.5], backend="python")
    assert run.status == "zeno"
    assert "switches within" in run.message and "outside the friction cone" in run.message
    assert run.switches[-1][0] == pytest.approx(0.5, abs=1e-9)  # where v_r first reaches 0
    assert run.t[-1] < 10.0


@pytest.mark.parametrize("belt", BELTS)
def test_numba_and_python_backends_agree(belt):
    pytest.importorskip("numba")
    s = System(belt, friction="stribeck", Vb=1.5)
    fast = simulate(s, 100.0, backend="numba")
    slow = simulate(s, 100.0, backend="python")
    assert [(a, b) for _, a, b in fast.switches] == [(a, b) for _, a, b in slow.switches]
    # the same method and steps; sums in another order: rounding, grown over 100 s
    times = [t for t, _, _ in fast.switches], [t for t, _, _ in slow.switches]
    assert np.allclose(*times, atol=1e-9)
    assert np.allclose(fast.y, slow.y, atol=1e-9)
