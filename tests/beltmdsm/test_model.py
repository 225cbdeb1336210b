"""beltmdsm.model: the Model is checked once, frozen, hashable; the initial state (Eq. 9)."""

import math
import subprocess
import sys

import numpy as np
import pytest

from beltmdsm.model import LAW_OF, OPTIONS, Model, as_model, excitation_period, initial_state
from generated import dynamics
from generated.parameters import BASE


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
        "beltmdsm.prediction.prediction, beltmdsm.studies.sweep, beltmdsm.studies.validation, "
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
