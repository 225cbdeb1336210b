"""Results by keyword (issue 38 item 5): PeriodicResponse (14 positional fields before),
Band (11) and Floquet (10) are keyword-only dataclasses; a positional call is refused."""

import dataclasses

import pytest

from beltmdsm import Model, periodic_response
from beltmdsm.continuation.band_result import Band
from beltmdsm.periodic.floquet import Floquet
from beltmdsm.periodic.response import PeriodicResponse


@pytest.mark.parametrize("cls", [PeriodicResponse, Band, Floquet])
def test_every_field_is_keyword_only(cls):
    fields = dataclasses.fields(cls)
    assert len(fields) >= 10 and all(f.kw_only for f in fields)
    required = [f for f in fields if f.default is dataclasses.MISSING]
    required = [f for f in required if f.default_factory is dataclasses.MISSING]
    with pytest.raises(TypeError, match="positional"):
        cls(*([None] * len(required)))


def test_a_response_rebuilt_by_keyword_is_the_same():
    r = periodic_response(Model(Vb=5.0))
    again = PeriodicResponse(**{f.name: getattr(r, f.name) for f in dataclasses.fields(r)})
    assert again.period == r.period and (again.state0 == r.state0).all()
    f = Floquet.of(again)
    assert f.max_abs_multiplier == Floquet.of(r).max_abs_multiplier
