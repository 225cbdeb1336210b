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


# ---------------------------------------------------------------- check_request


def test_the_default_sampling_passes_every_case_of_the_paper():
    from beltmdsm.model import Model
    from beltmdsm.paper_reports.validation import CASES

    cases = [Model(**c.overrides) for c in CASES]
    assert max(max(m["Omega_t"], m["omega1"]) for m in cases) == 12.0  # omega1 = 12, Omega 10
    for model in cases:
        settings.check_request(model, SolverSettings())


def test_a_sampling_step_below_the_nyquist_bound_is_refused_by_name():
    from beltmdsm.errors import Refused
    from beltmdsm.model import Model

    model = Model(Vb=1.0)  # Omega = 4 is the fastest line
    bound = math.pi / (settings.NYQUIST_MULTIPLE * 4.0)
    settings.check_request(model, SolverSettings(dt=bound))  # at the bound: accepted
    with pytest.raises(Refused, match="dt = 0.7 s samples up to pi/dt") as err:
        settings.check_request(model, SolverSettings(dt=0.7))
    assert err.value.names == ("dt",)
    with pytest.raises(Refused, match="8 x omega1"):
        settings.check_request(Model(omega1=12.0), SolverSettings(dt=1.1 * math.pi / 96))


def test_the_memory_estimate_bounds_what_a_run_holds():
    """`run_bytes` is above the arrays a run keeps: its steps' dense output and samples."""
    from beltmdsm.model import Model
    from beltmdsm.simulation import simulate

    for kw in ({"Vb": 4.0}, {"Vb": 1.0, "Omega": 10.0}, {"Vb": 4.0, "omega1": 12.0}):
        s = SolverSettings(t_end=500.0)
        sim = simulate(Model(**kw), settings=s)
        ev = sim.trajectory.evaluator
        kept = sum(a.nbytes for a in (ev.t_steps, ev.h_steps, ev.y_steps, ev.F_steps))
        kept += sum(a.nbytes for a in (sim.t, sim.y, sim.normal_force, sim.friction))
        # the arrays are a part of the peak memory (the measurement behind the
        # constants found 41-59 kB per period in all, against 64 KiB estimated)
        assert kept < settings.run_bytes(sim.model, s) / 4


def test_a_run_larger_than_the_memory_bound_is_refused_by_name():
    from beltmdsm.errors import Refused
    from beltmdsm.model import Model

    model = Model()
    with pytest.raises(Refused, match="MAX_RUN_BYTES") as err:
        settings.check_request(model, SolverSettings(t_end=1e7, dt=1.0))
    assert err.value.names == ("t_end",)
    # a tighter tolerance takes more steps: the same t_end can be too much
    t_end = 0.9 * settings.MAX_RUN_BYTES / settings.run_bytes(model, SolverSettings(t_end=1.0))
    settings.check_request(model, SolverSettings(t_end=t_end))
    with pytest.raises(Refused, match="t_end"):
        settings.check_request(model, SolverSettings(t_end=t_end, rtol=1e-14, atol=1e-14))
