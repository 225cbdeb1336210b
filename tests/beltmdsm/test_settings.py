"""beltmdsm.settings: SolverSettings are checked once, by name, and normalised."""

import math
from dataclasses import asdict

import numpy as np
import pytest

from beltmdsm import settings
from beltmdsm.settings import SolverSettings


def test_numbers_are_normalised_to_floats():
    # the CLI parses floats; the Python API may pass ints or numpy scalars: both must
    # key the sweep cache alike
    assert asdict(SolverSettings(t_end=300)) == asdict(SolverSettings(t_end=300.0))
    s = SolverSettings(t_end=np.float64(50.0), rtol=np.float32(1e-6), dt=1)
    assert type(s.t_end) is float and type(s.rtol) is float and type(s.dt) is float
    assert s.t_end == 50.0


@pytest.mark.parametrize(
    "kwargs, text",
    [
        ({"method": "Euler"}, "method must be one of 'DOP853'"),
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
        ({"backend": "cuda"}, "backend must be"),
    ],
)
def test_solver_settings_refuse_bad_values_by_name(kwargs, text):
    with pytest.raises(ValueError, match=text):
        SolverSettings(**kwargs)


def test_the_sample_limit_is_what_the_arrays_would_need():
    limit = settings.MAX_SAMPLES
    dt = 0.02
    SolverSettings(t_end=limit * dt, dt=dt)  # at the limit: accepted
    with pytest.raises(ValueError, match="MAX_SAMPLES"):
        SolverSettings(t_end=limit * dt * 1.01, dt=dt)
