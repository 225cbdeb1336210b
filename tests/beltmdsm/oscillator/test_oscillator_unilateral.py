"""The runtime on a unilateral contact: the paper's model with the Kelvin-Voigt contact
typed by hand (reference_paper_kv.py), against the paper's own simulation through
take-off, landing, stick and slip reversals."""

import numpy as np
import pytest
import reference_paper_kv as kv

import beltmdsm
from beltmdsm.oscillator import System, forced_response, simulate


@pytest.mark.parametrize("backend", ["python", "numba"])
def test_flight_stick_and_reversals_agree_with_the_paper_model(backend):
    if backend == "numba":
        pytest.importorskip("numba")
    paper = beltmdsm.simulate(beltmdsm.Model(contact="kelvin_voigt", omega2=3.0), t_end=30.0)
    order = [0, 2, 1, 3]  # the paper's (X1, Y1, X2, Y2) as (X1, X2, X1', X2')
    run = simulate(System(kv), 30.0, paper.y[order, 0], backend=backend)
    assert run.status == "done"
    # the same switches, to the same modes (the paper's Mode codes are the contract's)
    assert [int(e[2]) for e in paper.events] == [after for _, _, after in run.switches]
    assert {2, 0, 1, -1} <= {after for _, _, after in run.switches}  # flight, stick, both slips
    # 36 switches in 30 s: the times to 1e-6, the states to 1e-5 (both at 1e-10)
    assert np.allclose([e[0] for e in paper.events], [t for t, _, _ in run.switches], atol=1e-6)
    assert np.allclose(run.y, paper.y[order], atol=1e-5)
    assert set(np.unique(run.modes)) == {-1, 0, 1, 2}


def test_forced_response_and_multipliers_agree_with_the_paper_model():
    # the paper's Floquet analysis (its closed-form engine: the normal motion's periodic
    # orbit and the tangential map on it) against shooting on the full hand-typed model
    model = beltmdsm.Model(contact="kelvin_voigt", Vb=5.0)
    paper = beltmdsm.floquet(model)
    mine = forced_response(System(kv, omega2=0.5, Vb=5.0), settle=200.0)
    assert mine.period == pytest.approx(paper.period, rel=1e-14)
    assert np.allclose(mine.state, paper.response.state0[[0, 2, 1, 3]], atol=1e-8)
    by_value = lambda z: (round(z.real, 6), round(z.imag, 6))  # noqa: E731
    assert np.allclose(
        sorted(mine.multipliers, key=by_value), sorted(paper.multipliers, key=by_value), atol=1e-8
    )
    assert len(mine.switches) == paper.n_reversals == 2 and mine.sticks == paper.n_sticks == 0
