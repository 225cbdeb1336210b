"""runtime.parameters: resolve_parameters and initial_state (re-exported by runtime.model);
the checks of SolverSettings."""

import math

import numpy as np
import pytest

import runtime.model
from runtime import parameters
from runtime.simulate import SolverSettings


def test_runtime_model_re_exports_the_moved_names():
    for name in ("resolve_parameters", "initial_state", "CONTACTS"):
        assert getattr(runtime.model, name) is getattr(parameters, name)


@pytest.mark.parametrize(
    "kwargs, text",
    [
        ({"mu_s": True}, "'mu_s' must be a number"),
        ({"Vb": np.array([1.0, 2.0])}, "'Vb' must be a number"),
        ({"Omega": -math.inf}, "'Omega' must be finite"),
        ({"Omega_t": -1.0}, "'Omega_t' must be >= 0"),
        ({"phase_n": math.nan}, "'phase_n' must be finite"),
    ],
)
def test_resolve_parameters_names_the_bad_value(kwargs, text):
    with pytest.raises(ValueError, match=text):
        parameters.resolve_parameters(**kwargs)


def test_resolve_parameters_wants_a_mapping():
    with pytest.raises(ValueError, match="params must be a dict"):
        parameters.resolve_parameters([("Vb", 1.0)])


def test_numpy_scalars_are_numbers():
    p = parameters.resolve_parameters(Vb=np.float32(2.5), omega1=np.int64(2))
    assert p["Vb"] == 2.5 and p["omega1"] == 2.0
    assert SolverSettings(t_end=np.float64(50.0), rtol=np.float32(1e-6)).t_end == 50.0


@pytest.mark.parametrize(
    "kwargs, text",
    [
        ({"method": "Euler"}, "method must be one of DOP853"),
        ({"t_end": 0.0}, "t_end must be a finite number > 0"),
        ({"t_end": math.inf}, "t_end must be a finite number > 0"),
        ({"dt": -0.1}, "dt must be a finite number > 0"),
        ({"rtol": True}, "rtol must be a finite number > 0"),
        ({"atol": math.nan}, "atol must be a finite number > 0"),
        ({"t_discard": math.nan}, "t_discard must be None or a finite number"),
        ({"t_discard": "10"}, "t_discard must be None or a finite number"),
        ({"t_discard": 999.9}, "must be >= 0 and leave a steady window"),
        ({"t_end": 1e9}, "MAX_SAMPLES"),
        ({"solver": "rk4"}, "solver must be"),
        ({"on_contact_loss": "ignore"}, "on_contact_loss must be"),
    ],
)
def test_solver_settings_refuse_bad_values_by_name(kwargs, text):
    with pytest.raises(ValueError, match=text):
        SolverSettings(**kwargs)


def test_the_sample_limit_is_what_the_arrays_would_need():
    limit = parameters.MAX_SAMPLES
    dt = 0.02
    SolverSettings(t_end=limit * dt, dt=dt)  # at the limit: accepted
    with pytest.raises(ValueError, match="MAX_SAMPLES"):
        SolverSettings(t_end=limit * dt * 1.01, dt=dt)
