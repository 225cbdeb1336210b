"""beltmdsm.model: the Model is checked once, frozen, hashable; the initial state (Eq. 9)."""

import math
import subprocess
import sys

import numpy as np
import pytest

from beltmdsm.excitation import excitation_period, initial_state
from beltmdsm.generated import dynamics
from beltmdsm.generated.parameters import BASE
from beltmdsm.model import LAW_OF, OPTIONS, Model, as_model


def test_the_base_model_is_the_base_set_with_the_excitation_of_eq4():
    m = Model()
    assert {k: m[k] for k in m.params if k in BASE} == {
        k: v for k, v in BASE.items() if k not in LAW_OF or LAW_OF[k] in m.options.items()
    }
    assert (m["alpha_t"], m["alpha_n"], m["Omega_t"], m["Omega_n"]) == (2.0, 2.0, 4.0, 4.0)
    assert m["phase_t"] == m["phase_n"] == 0.0
    assert (m.contact, m.tension) == ("hertz_damp", "allowed")
    assert dict(m.options) == {name: choices[0] for name, choices in OPTIONS.items()}


def test_per_direction_excitation_follows_alpha_and_omega_unless_given():
    m = Model(alpha=1.5, Omega=6.0, Omega_n=4.0)
    assert (m["alpha_t"], m["alpha_n"], m["Omega_t"], m["Omega_n"]) == (1.5, 1.5, 6.0, 4.0)
    r = m.replace(alpha=3.0, Omega=5.0)
    assert (r["alpha_t"], r["alpha_n"], r["Omega_t"], r["Omega_n"]) == (3.0, 3.0, 5.0, 4.0)


def test_a_model_is_frozen_hashable_and_equal_by_value():
    a, b = Model(Vb=5), Model(Vb=5.0, tension="allowed")
    assert a == b and hash(a) == hash(b) and a.digest() == b.digest()
    assert a != a.replace(tension="clipped") and a.digest() != Model(Vb=6).digest()
    with pytest.raises(AttributeError, match="immutable"):
        a.Vb = 3
    with pytest.raises(TypeError):
        a.params["Vb"] = 3
    assert len({a, b, Model(Vb=6)}) == 2


def test_as_model_passes_a_model_through_and_builds_one_from_keywords():
    m = Model(Vb=3)
    assert as_model(m) is m
    assert as_model(m, Vb=4) == Model(Vb=4)
    assert as_model({"Vb": 3, "tension": "clipped"}) == Model(Vb=3, tension="clipped")
    assert as_model(None, Vb=3) == m
    assert Model.from_mapping({"Vb": 2}, Vb=3) == m


@pytest.mark.parametrize(
    "kwargs, text",
    [
        ({"mu_s": True}, "'mu_s' must be a number"),
        ({"Vb": np.array([1.0, 2.0])}, "'Vb' must be a number"),
        ({"Omega": -math.inf}, "'Omega' must be finite"),
        ({"Omega_t": -1.0}, "'Omega_t' must be >= 0"),
        ({"phase_n": math.nan}, "'phase_n' must be finite"),
        ({"Vb": -1.0}, "'Vb' must be >= 0"),
        ({"omega1": 0.0}, "'omega1' must be > 0"),
        ({"g": "x"}, "'g' must be a number"),
        ({"Vbelt": 1.0}, "unknown parameter 'Vbelt'"),
        ({"Vhat": 3.0}, "Vhat is an input of the effective friction"),
        ({"contact": "coulomb"}, "contact must be one of 'hertz_damp'"),
        ({"tension": "pulling"}, "tension must be one of 'allowed', 'clipped'"),
    ],
)
def test_bad_input_is_refused_naming_it(kwargs, text):
    with pytest.raises(ValueError, match=text):
        Model(**kwargs)


def test_from_mapping_wants_a_mapping():
    with pytest.raises(ValueError, match="params must be a dict"):
        Model.from_mapping([("Vb", 1.0)])


def test_numpy_scalars_are_numbers():
    m = Model(Vb=np.float32(2.5), omega1=np.int64(2))
    assert m["Vb"] == 2.5 and m["omega1"] == 2.0 and type(m["omega1"]) is float


def test_rhs_with_sign_equals_branch_in_each_direction():
    m = Model(Vb=4.0)
    y = initial_state(m)
    for vr, sgn in ((-1.0, -1.0), (1.0, 1.0)):
        state = y + np.array([0, m["Vb"] + vr, 0, 0])
        np.testing.assert_array_equal(
            dynamics.rhs(0.7, *state, **m.params),
            dynamics.rhs_branch(0.7, *state, sgn, **m.params),
        )


def test_initial_state_is_the_unforced_equilibrium_eq9():
    m = Model()
    X1, Y1, X2, Y2 = initial_state(m)
    # X1: * and / only, 3 correctly rounded steps a side: <= 3 eps = 6.7e-16 on any CPU.
    # X2: three cube roots at <= 4 ulp and 3 roundings (13.5 eps) against libm's pow
    # (< 1 ulp) of a 2-rounding quotient to the rounded power 2/3 (~2.6 eps): <= 3.6e-15
    assert X1 == pytest.approx(m["mu_s"] * m["g"] / m["omega1"] ** 2, rel=1e-15)
    assert X2 == pytest.approx((m["g"] / m["omega2"] ** 2) ** (2 / 3), rel=1e-14)
    assert Y1 == Y2 == 0
    # at rest, sliding backwards, without excitation: no acceleration
    q = m.replace(alpha=0.0).params
    np.testing.assert_allclose(dynamics.rhs(0.0, X1, Y1, X2, Y2, **q), 0.0, atol=1e-13)


def test_excitation_period_is_two_pi_over_the_gcd():
    assert excitation_period(Model()) == pytest.approx(2 * np.pi / 4, rel=1e-15)
    m = Model(alpha_t=2, Omega_t=6, alpha_n=2, Omega_n=4)  # ratio 3/2: period 2 pi / 2
    assert excitation_period(m) == pytest.approx(np.pi, rel=1e-15)
    # one direction without force does not enter
    m = Model(alpha_n=0, Omega_t=6, Omega_n=np.sqrt(2))
    assert excitation_period(m) == pytest.approx(2 * np.pi / 6, rel=1e-15)
    with pytest.raises(ValueError, match="no excitation"):
        excitation_period(Model(Omega=0))
    with pytest.raises(ValueError, match="incommensurate"):
        excitation_period(Model(Omega_t=4, Omega_n=4 * np.sqrt(2)))


def test_importing_the_runtime_does_not_import_sympy():
    code = (
        "import sys, beltmdsm, beltmdsm.simulation, beltmdsm.integrate.superposition, "
        "beltmdsm.run.spectra, beltmdsm.run.modulation, beltmdsm.periodic.floquet, "
        "beltmdsm.prediction.prediction, beltmdsm.batch.sweep, beltmdsm.paper_reports.validation, "
        "beltmdsm.cli; "
        "sys.exit(1 if any(m == 'sympy' or m.startswith('sympy.') for m in sys.modules) else 0)"
    )
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


def test_the_public_api_is_importable_by_name():
    import beltmdsm

    for name in beltmdsm.__all__:
        assert getattr(beltmdsm, name) is not None
    assert beltmdsm.Model is Model
    with pytest.raises(AttributeError, match="no attribute 'resolve_parameters'"):
        beltmdsm.resolve_parameters  # noqa: B018


def test_a_model_survives_pickling_with_its_given_values():
    import pickle

    m = Model(Vb=3, alpha_t=1.0, tension="clipped")
    back = pickle.loads(pickle.dumps(m))
    assert back == m and back.replace(alpha=3.0)["alpha_t"] == 1.0


def test_equal_models_stay_equal_under_replace():
    # issue 28: Model(alpha=3, alpha_t=3) == Model(alpha=3), yet replace(alpha=1)
    # moved alpha_t in the second only
    pinned, follows = Model(alpha=3, alpha_t=3), Model(alpha=3)
    assert pinned.params == follows.params
    assert pinned.replace(alpha=1)["alpha_t"] == 3.0 and follows.replace(alpha=1)["alpha_t"] == 1.0
    assert pinned != follows and pinned.digest() != follows.digest()
    assert repr(pinned) == "Model(alpha=3.0, alpha_t=3.0)" and repr(follows) == "Model(alpha=3.0)"
    # where replace() treats them alike they are equal, hash and digest alike
    for a, b in [(Model(alpha=3), Model(alpha=3.0)), (pinned, Model(alpha_t=3, alpha=3))]:
        assert a == b and hash(a) == hash(b) and a.digest() == b.digest()
        assert a.replace(alpha=1) == b.replace(alpha=1)


def test_minus_zero_is_zero():
    a, b = Model(phase_t=-0.0, Vb=-0.0), Model(phase_t=0.0, Vb=0.0)
    assert a == b and hash(a) == hash(b) and a.digest() == b.digest()
    assert math.copysign(1.0, a["phase_t"]) == 1.0


# A Model is checked once (issue 30, item 5) ---------------------------------------------


@pytest.fixture
def checks(monkeypatch):
    """The parameter names that the model's domain check sees, in order."""
    import beltmdsm.model as model_module

    seen, real = [], model_module.check_domain

    def counting(name, value):
        seen.append(name)
        return real(name, value)

    monkeypatch.setattr(model_module, "check_domain", counting)
    return seen


def test_replace_checks_only_the_changed_parameters(checks):
    m = Model(Vb=5)
    assert sorted(checks) == sorted(m.params)  # built: every parameter once
    checks.clear()
    assert m.replace(Vb=6)["Vb"] == 6.0 and checks == ["Vb"]
    checks.clear()
    # what follows a changed parameter changes with it, and is checked with it
    assert m.replace(alpha=3)["alpha_n"] == 3.0
    assert sorted(checks) == ["alpha", "alpha_n", "alpha_t"]
    checks.clear()
    Model(alpha_t=2.5).replace(alpha=3)
    assert sorted(checks[-2:]) == ["alpha", "alpha_n"]  # alpha_t was given: it stays
    checks.clear()
    m.replace(friction="stribeck")  # an option: the model is built whole
    assert len(checks) == len(Model(friction="stribeck").params)


def test_replace_checks_a_constraint_only_where_it_is_involved(monkeypatch):
    import beltmdsm.model as model_module

    calls = []
    real = model_module._table.static_shortfall
    monkeypatch.setattr(
        model_module._table,
        "static_shortfall",
        lambda *a, **k: calls.append(a) or real(*a, **k),
    )
    m = Model(friction="static_kinetic", mu_s=0.6, mu_k=0.4)
    calls.clear()
    m.replace(Vb=2.0)  # mu_k <= mu_s does not involve Vb
    assert calls == []
    m.replace(mu_k=0.5)
    assert len(calls) == 1
    with pytest.raises(ValueError, match="static bound mu_s"):
        m.replace(mu_k=0.7)


@pytest.mark.parametrize(
    "kw, text",
    [
        ({"Vb": -1.0}, "parameter 'Vb' must be >= 0; got -1.0"),
        ({"omega1": 0}, "parameter 'omega1' must be > 0"),
        ({"Vb": math.nan}, "parameter 'Vb' must be finite"),
        ({"beta1": True}, "parameter 'beta1' must be a number"),
        ({"alpha": -2.0}, "parameter 'alpha"),
        ({"Vhat": 1.0}, "Vhat is an input"),
        ({"mu_k": 0.3}, "parameter 'mu_k' belongs to the friction law"),
    ],
)
def test_a_bad_replace_value_is_refused_naming_it(kw, text):
    m = Model(Vb=5)
    with pytest.raises(ValueError, match=text.replace("(", r"\(")):
        m.replace(**kw)
    assert m == Model(Vb=5)  # unchanged


@pytest.mark.parametrize(
    "start, kw",
    [
        ({}, {"Vb": 6.0}),
        ({}, {"alpha": 3, "Omega": 4}),
        ({"alpha_t": 2.5}, {"alpha": 3}),
        ({"alpha": 3}, {"alpha_t": 3}),
        ({"tension": "clipped"}, {"phase_n": 0.5, "Vb": -0.0}),
        ({"friction": "static_kinetic", "mu_s": 0.6, "mu_k": 0.4}, {"mu_k": 0.6}),
        ({"friction": "stribeck", "mu_k": 0.2}, {"v_s": 0.3}),
    ],
)
def test_a_replaced_model_is_the_model_built_whole(start, kw):
    # the checked part is not all: parameters, what was given, options, identity
    fast = Model(**start).replace(**kw)
    whole = Model(**{**start, **kw})
    assert fast == whole and fast.digest() == whole.digest() and hash(fast) == hash(whole)
    assert list(fast.params.items()) == list(whole.params.items()) and repr(fast) == repr(whole)
    assert fast.replace(alpha=1.5) == whole.replace(alpha=1.5)


@pytest.fixture
def generated_checks(monkeypatch):
    """The parameters a generated function checks (``beltmdsm.generated._checks``: ``param``,
    ``within``)."""
    from beltmdsm.generated import _checks

    seen = []
    param, within = _checks.param, _checks.within

    def counting_param(function, name, value, *a, **k):
        seen.append(("param", name))
        return param(function, name, value, *a, **k)

    def counting_within(domain, x):
        seen.append(("within", domain))
        return within(domain, x)

    monkeypatch.setattr(_checks, "param", counting_param)
    monkeypatch.setattr(_checks, "within", counting_within)
    return seen


def test_generated_functions_do_not_check_a_checked_model_again(generated_checks):
    from beltmdsm.generated import hybrid, unforced

    m = Model(Vb=5, friction="stribeck")
    bind = hybrid.bind_vector_field
    checked = bind(backend="python", **m.arguments(bind))
    assert generated_checks == []
    eq = unforced.equilibrium(**m.arguments(unforced.equilibrium))
    assert generated_checks == []
    # the same values, checked, give the same results
    unchecked = bind(backend="python", friction="stribeck", **m.params)
    assert len(generated_checks) >= len(unchecked.params)
    assert checked.args == unchecked.args
    assert eq == unforced.equilibrium(friction="stribeck", **m.params)


def test_a_value_put_in_the_place_of_a_checked_one_is_checked(generated_checks):
    from beltmdsm.generated import unforced

    m = Model(Vb=5)
    grid = np.array([1.0, 2.0, 3.0])
    eq = unforced.equilibrium(**{**m.arguments(unforced.equilibrium), "Vb": grid})
    assert [c for c in generated_checks if c[0] == "param"] == [("param", "Vb")]
    assert np.shape(eq[0]) == (3,)
    with pytest.raises(ValueError, match="parameter 'Vb' must be"):
        unforced.equilibrium(**{**m.arguments(unforced.equilibrium), "Vb": -1.0})
    with pytest.raises(ValueError, match="parameter 'omega1' must be"):
        bind = dynamics.bind_normal_force
        bind(backend="python", **{**m.arguments(bind), "omega1": 0.0})
