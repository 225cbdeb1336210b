"""``branch(..., record=...)``: a user's values per branch point (issue 30, item 4).

References: the periodic response solved again from scratch at the branch's points
(`periodic_response`, Newton's method from its own seed), and the self-excited cycle
solved again by `cycle` (its own shooting with a section) from a perturbed guess; the
error bound of a state is the corrector's residual through ``(I - dP/dx)^-1``.
"""

import re

import numpy as np
import pytest

from beltmdsm import Model, branch
from beltmdsm.errors import Refused
from beltmdsm.periodic.cycle import cycle
from beltmdsm.periodic.newton import NEWTON_TOL
from beltmdsm.periodic.shooting import periodic_response

NS = Model(beta1=0.3, Vb=5.3)  # a Neimark-Sacker point at Vb = 5.45


def test_a_record_is_stored_at_every_point_and_equals_the_state_solved_again():
    b = branch(NS, lo=5.3, hi=5.6, record=lambda p: {"x1_0": p.state[0], "v1_0": p.state[1]})
    assert len(b.points) > 10
    table, frame = b.observables(), b.to_pandas()
    for i, p in enumerate(b.points):
        assert set(p.recorded) == {"x1_0", "v1_0"}
        assert table["x1_0"][i] == p.recorded["x1_0"] == frame["x1_0"][i]
        assert table["v1_0"][i] == p.recorded["v1_0"] == frame["v1_0"][i]
    # every fifth point solved again from scratch: X1 and X1' at phase 0 agree to the
    # corrector's residual NEWTON_TOL (1 + |x|) magnified by (I - dP/dx)^-1, both ways
    for i, p in list(enumerate(b.points))[::5]:
        again = periodic_response(b.model.replace(Vb=p.value)).shooting_state
        J = p.image.jacobian
        gain = np.linalg.norm(np.linalg.inv(np.eye(J.shape[0]) - J), 2)
        bound = 2 * NEWTON_TOL * (1 + np.max(np.abs(p.state))) * gain
        assert abs(table["x1_0"][i] - again[0]) <= bound
        assert abs(table["v1_0"][i] - again[1]) <= bound


def test_a_number_is_the_column_record_and_a_cycle_branch_records_its_period():
    base = Model(friction="stribeck", alpha=0)  # no excitation: cycles from a Hopf point
    c = branch(base, param="Vb", lo=1.8, hi=2.2, record=lambda p: p.period)
    table = c.observables()
    assert np.array_equal(table["record"], [p.period for p in c.points])
    assert np.array_equal(c.to_pandas()["record"], table["record"])
    for p in c.points[5::8]:  # the cycle solved again by its own shooting
        again = cycle(
            base.replace(Vb=p.value), guess=p.state * (1 + 1e-4), period=p.period * 1.0001
        )
        assert p.recorded["record"] == pytest.approx(again.period, rel=1e-9)
    # a cycle branch's own columns: the X1' range and max |Vr| = |X1' - Vb| at its ends
    lo, hi = np.array([p.velocity_range for p in c.points]).T
    assert np.array_equal(table["X1'_amplitude"], [p.amplitude for p in c.points])
    assert np.allclose(table["X1'_amplitude"], 0.5 * (hi - lo), rtol=1e-12)
    vb = table["Vb"]
    assert np.array_equal(table["max_abs_Vr"], np.maximum(abs(lo - vb), abs(hi - vb)))


def _raises(p):
    raise ZeroDivisionError("division by zero")


@pytest.mark.parametrize(
    "record, says",
    [
        (_raises, "record raised ZeroDivisionError at Vb = 5.3"),
        (lambda p: "big", "record must return a real number"),
        (lambda p: {"a": [1.0]}, "record must return a real number"),
        (lambda p: {"a": True}, "record must return a real number"),
        (lambda p: {}, "record must return a real number"),
        (lambda p: {"mu_eff": 1.0}, "record's names ['mu_eff'] are the branch's own columns"),
        (lambda p: {"Vb": 1.0}, "record's names ['Vb'] are the branch's own columns"),
        (
            lambda p: {("a" if p.value == 5.3 else "b"): 1.0},
            "record must return the same names at every point",
        ),
        (3.0, "record must be a callable"),
    ],
)
def test_a_record_that_raises_or_returns_a_non_number_is_refused_naming_record(record, says):
    with pytest.raises(Refused, match=f"^{re.escape(says)}") as err:
        branch(NS, lo=5.3, hi=5.32, record=record)
    assert err.value.names == ("record",)


def test_a_record_that_fails_at_the_start_is_refused_before_the_continuation(monkeypatch):
    from beltmdsm.continuation import branch as module

    def walk(*args):
        raise AssertionError("the continuation ran")

    monkeypatch.setattr(module, "_walk", walk)
    with pytest.raises(Refused, match="^record raised ZeroDivisionError at Vb = 5.3") as err:
        branch(NS, lo=5.0, hi=6.0, record=_raises)
    assert err.value.names == ("record",)
