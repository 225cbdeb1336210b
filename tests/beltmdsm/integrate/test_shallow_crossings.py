"""A switching function crossed by less than the samples resolve is still crossed.

Reference: the backward-sliding orbit of the base set does not depend on ``Vb`` (the
friction is ``mu_s Fn`` whatever the slip), so its largest velocity in contact ``g``
(`beltmdsm.periodic.closed_form.largest_sliding_velocity`, found by a bounded scalar
minimisation on the closed form) is the belt speed at which it grazes. Started on
that orbit at ``Vb = g - delta``, a run must reverse its slip within one excitation
period, however small ``delta``: the relative velocity dips below zero for a time of
about ``2 sqrt(delta / |X1'''|)``, 6e-4 s at ``delta = 1e-7`` and 6e-6 s at 1e-11,
far less than a step or a sample (1/16 of a step). At ``Vb = g + delta`` it must not.
Before the dip search (``_dip`` of both integrators), both stepped over it: Newton's
method found the sliding response 2.9e-7 m/s below its grazing point, and
``floquet-band --tol 1e-7`` reported a stable window there.
"""

import numpy as np
import pytest

from beltmdsm.errors import NoPeriodicResponse
from beltmdsm.integrate.events import integrate_events
from beltmdsm.integrate.superposition import integrate_superposed
from beltmdsm.model import Model
from beltmdsm.periodic.closed_form import largest_sliding_velocity
from beltmdsm.periodic.floquet import floquet
from beltmdsm.settings import SolverSettings

INTEGRATORS = {"events": integrate_events, "superposition": integrate_superposed}


@pytest.fixture(scope="module")
def sliding():
    found = floquet(Model(Vb=8.0))
    assert (found.n_reversals, found.n_sticks) == (0, 0)
    return found.response, largest_sliding_velocity(found.response._engine)


def _reversals(integrate, model, state0):
    T = 2 * np.pi / model["Omega"]
    settings = SolverSettings(t_end=T, dt=T / 64, rtol=1e-12, atol=1e-12)
    run = integrate(model, settings, y0=state0)
    assert run.status == "done", run.message
    return [t for t, kind, _ in run.events if kind == "vr_zero"]


@pytest.mark.parametrize("solver", INTEGRATORS)
@pytest.mark.parametrize("delta", [1e-7, 1e-9, 1e-11])
def test_a_hair_below_the_grazing_point_the_slip_reverses(sliding, solver, delta):
    response, g = sliding
    model = response.model.replace(Vb=g - delta)
    assert _reversals(INTEGRATORS[solver], model, response.state0)


@pytest.mark.parametrize("solver", INTEGRATORS)
def test_a_hair_above_it_the_orbit_slides_on(sliding, solver):
    response, g = sliding
    # the orbit's rounding: its velocity is known to about 1e-12 relative (rtol)
    model = response.model.replace(Vb=g + 1e-9)
    assert _reversals(INTEGRATORS[solver], model, response.state0) == []


def test_no_sliding_response_below_its_grazing_point(sliding):
    _, g = sliding
    for delta in (1e-7, 3e-7):
        try:
            found = floquet(Model(Vb=g - delta))
        except NoPeriodicResponse:
            continue
        # Newton's method may land on another response, never on the sliding one
        assert (found.n_reversals, found.n_sticks) != (0, 0)
