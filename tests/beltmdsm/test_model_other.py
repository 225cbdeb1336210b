"""``Model(model=NAME)``: another registered model through the public API (issue 39).

The paper's `Model` is unchanged (the default ``model="paper"``); another model's
parameters are its module's; simulate, floquet, periodic_response, cycle, lyapunov,
sweep and basins run it on the generic runtime, checked against closed forms typed
here; every other analysis refuses it in one line naming the model and what it lacks.
"""

import math
import pickle

import numpy as np
import pytest

import beltmdsm
from beltmdsm import Model, Unsupported
from beltmdsm.oscillator import System, forced_response
from beltmdsm.oscillator import simulate as run


def _undamped_period(p):
    """beta1 = 0, static/kinetic friction: the slip is a circle about x_k = mu_k g / w^2
    from the stick end x_s = mu_s g / w^2 (u0 = x_s - x_k) at x' = Vb round to x' = Vb
    at x_k - u0, an arc of 2 pi - 2 atan2(u0 w, Vb); the stick then carries x back to
    x_s at Vb."""
    w, g, Vb = p["omega1"], p["g"], p["Vb"]
    u0 = (p["mu_s"] - p["mu_k"]) * g / w**2
    return (2 * math.pi - 2 * math.atan2(u0 * w, Vb)) / w + 2 * u0 / Vb


def test_the_paper_model_is_unchanged_and_named():
    assert Model().model == "paper"
    assert Model(model="paper", Vb=3.0) == Model(Vb=3.0)
    assert Model(model="paper", Vb=3.0).digest() == Model(Vb=3.0).digest()
    assert "model" not in Model().as_dict()  # the sweep cache's identity keeps its keys
    assert all(ok for ok, _ in Model().capabilities.values())


def test_the_forced_analyses_run_another_model_only_where_it_is_excited():
    unforced, forced = Model(model="belt_1dof"), Model(model="belt_1dof", alpha_t=0.1)
    for name in ("branch", "floquet_band", "floquet_map"):
        assert forced.capabilities[name] == (True, "")
        ok, why = unforced.capabilities[name]
        assert not ok and "set an excitation amplitude" in why
        ok, why = Model(model="hoffmann").capabilities[name]
        assert not ok and "no excitation terms" in why
    assert unforced.capabilities["cycle"] == (True, "")


def test_another_model_holds_its_own_parameters_checked_once():
    m = Model(model="belt_1dof", friction="stribeck", Vb=1.5)
    assert repr(m) == "Model(model='belt_1dof', friction='stribeck', Vb=1.5)"
    assert (m.model, m.friction, m["Vb"], m["v_s"]) == ("belt_1dof", "stribeck", 1.5, 1.0)
    assert m == Model(model="belt_1dof", friction="stribeck", Vb=1.5) and hash(m) == hash(
        Model(model="belt_1dof", friction="stribeck", Vb=1.5)
    )
    assert m != Model(model="belt_1dof", friction="stribeck", Vb=1.6)
    assert pickle.loads(pickle.dumps(m)) == m
    assert m.replace(Vb=2.0)["Vb"] == 2.0 and m.replace(friction="coulomb").friction == "coulomb"
    assert m.as_dict()["model"] == "belt_1dof" and m.digest() != Model().digest()
    assert Model(model="hoffmann").states == ("x", "y", "x_dot", "y_dot")
    with pytest.raises(ValueError, match="model must be one of .*did you mean 'belt_1dof'"):
        Model(model="belt1dof")
    with pytest.raises(ValueError, match="k1: not a parameter of model 'belt_1dof'"):
        Model(model="belt_1dof", k1=1.0)
    with pytest.raises(ValueError, match="parameter 'v_s' must be > 0; got -1.0"):
        Model(model="belt_1dof", friction="stribeck", v_s=-1)
    with pytest.raises(ValueError, match="contact: an option of the paper's model"):
        Model(model="hoffmann", contact="kelvin_voigt")
    with pytest.raises(Unsupported, match="model 'hoffmann': the contact law"):
        _ = Model(model="hoffmann").contact


def test_simulate_runs_the_generic_runtime():
    m = Model(model="belt_1dof", friction="static_kinetic", Vb=1.0)
    sim = beltmdsm.simulate(m, t_end=20.0, dt=0.05)
    ref = run(System("belt_1dof", friction="static_kinetic", Vb=1.0), 20.0, dt=0.05)
    assert sim.states == ("x", "x_dot") and np.array_equal(sim.y, ref.y)
    with pytest.raises(Unsupported, match="solver='superposition' is the paper's"):
        beltmdsm.simulate(m, t_end=5.0, solver="superposition")


def test_floquet_and_cycle_meet_the_undamped_stick_slip_period():
    m = Model(model="belt_1dof", friction="static_kinetic", beta1=0.0, Vb=1.0)
    T = _undamped_period(m.params)
    for c in (beltmdsm.floquet(m), beltmdsm.cycle(m), beltmdsm.periodic_response(m)):
        assert c.period == pytest.approx(T, rel=1e-9)
        assert c.sticks == 1 and abs(c.multipliers[0]) < 1e-9
    with pytest.raises(ValueError, match="periods=2: model 'belt_1dof' is unforced"):
        beltmdsm.floquet(m, periods=2)


def test_floquet_of_a_forced_model_is_its_forced_response():
    # Den Hartog's non-stop motion (belt at rest, Coulomb friction; checked against his
    # solution in tests/beltmdsm/oscillator/test_oscillator_forced.py)
    given = dict(Vb=0.0, beta1=0.0, mu_s=0.03, alpha_t=1.5625, Omega_t=0.8, phase_t=math.pi / 2)
    r = beltmdsm.floquet(Model(model="belt_1dof", **given))
    ref = forced_response(System("belt_1dof", **given))
    assert r.period == pytest.approx(2 * math.pi / 0.8) and r.sticks == 0
    assert np.array_equal(r.state, ref.state) and np.array_equal(r.multipliers, ref.multipliers)


def test_sweep_lyapunov_and_basins_take_another_model():
    m = Model(model="belt_1dof", friction="static_kinetic", beta1=0.0)
    result = beltmdsm.sweep(m, "Vb", [1.0], t_end=40.0, t_discard=10.0, dt=0.01)
    row = result.rows[0]
    # the undamped cycle's x range: x_k +- R, R = hypot(x_s - x_k, Vb / w)
    R = math.hypot((0.4 - 0.25) * 9.81, 1.0)
    assert row["x_max"] == pytest.approx(0.25 * 9.81 + R, abs=R * 0.01**2 / 8 + 1e-9)
    spec = beltmdsm.lyapunov(m.replace(Vb=1.0), t_end=60.0)
    assert spec.collapsed == 1 and spec.exponents[-1] == -np.inf
    b = beltmdsm.basins(
        Model(model="belt_1dof", friction="stribeck", Vb=1.5), x_lo=0.0, x_hi=4.0,
        y_lo=-3.0, y_hi=1.0, points=2, t_end=300.0,
    )  # fmt: skip
    assert (b.x, b.y) == ("x", "x_dot") and [a.kind for a in b.attractors] == ["stick_slip"]


@pytest.mark.parametrize(
    "call, missing",
    [
        (lambda m: beltmdsm.predict(m), "the MDSM split"),
        (lambda m: beltmdsm.floquet_band(m, "Vb", 1.0, 2.0), "no band of unstable responses"),
        (lambda m: beltmdsm.branch(m, lo=1.0, hi=2.0), "no continuation through folds"),
        (
            lambda m: beltmdsm.floquet_map(m, "Vb", 1.0, 2.0, "alpha", 0.0, 1.0),
            "no two-parameter map",
        ),
    ],
)
def test_what_the_generic_runtime_lacks_is_refused_in_one_line(call, missing):
    for m in (Model(model="hoffmann"), {"model": "belt_1dof"}):
        with pytest.raises(Unsupported) as err:
            call(m)
        said = str(err.value)
        assert missing in said and "\n" not in said
        assert "model 'hoffmann'" in said or "model 'belt_1dof'" in said
        # the forced analyses run another model once it is excited: they say how
        paper_only = not any(word in missing for word in ("band", "folds", "two-parameter"))
        assert said.endswith("it runs the paper's model only (model='paper')") == paper_only
        if not paper_only:
            assert said.endswith(
                (
                    "set an excitation amplitude",
                    "has no excitation terms (derive/models/entries.py)",
                )
            )
