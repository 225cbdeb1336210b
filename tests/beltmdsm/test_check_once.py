"""A value is checked once, where it enters (the project's standard): the checks of a model's start
(`beltmdsm.settings.check_finite`) and its parameters are not made again inside, and bad
input is still refused where it enters."""

from __future__ import annotations

import numpy as np
import pytest

from beltmdsm import Model, periodic_response, settings
from beltmdsm.errors import Refused
from beltmdsm.generated import _checks, unforced
from beltmdsm.multistability.responses import responses
from beltmdsm.periodic.engines import period_map
from beltmdsm.settings import check_finite, fastest_rate


@pytest.mark.parametrize(
    "enter",
    [
        lambda m: periodic_response(m),
        lambda m: period_map(m),
        lambda m: responses(m),
        lambda m: check_finite(m),
    ],
    ids=["periodic_response", "period_map", "responses", "check_finite"],
)
def test_a_start_beyond_floating_point_is_refused_where_it_enters_every_time(enter):
    # X1 = mu_s g / omega1^2 (Eq. 9) = inf: refused naming omega1, the second time too
    # (the verdict is kept per model, not forgotten)
    model = Model(omega1=1e-200, Vb=3.0)
    for _ in range(2):
        with pytest.raises(Refused, match=r"X1 = inf.*omega1 = 1e-200") as caught:
            enter(model)
        assert caught.value.names == ("omega1",)


def test_the_start_of_a_model_is_computed_once(monkeypatch):
    calls = []
    real = unforced.equilibrium
    monkeypatch.setattr(unforced, "equilibrium", lambda **kw: calls.append(1) or real(**kw))
    model = Model(Vb=5.0, beta1=0.123456789)  # a model no other test checked
    for _ in range(3):
        check_finite(model)
    assert len(calls) == 1
    # nor by the maps of that model (each computes its own start, not the check's)
    misses = settings._overflows.cache_info().misses
    for _ in range(3):
        period_map(model)
    assert settings._overflows.cache_info().misses == misses


@pytest.mark.parametrize(
    "kw",
    [{}, {"friction": "stribeck", "Vb": 0.3}, {"contact": "kelvin_voigt"}, {"Omega_t": 50.0}],
)
def test_fastest_rate_does_not_check_the_models_parameters_again(kw, monkeypatch):
    model = Model(beta1=0.2345678901, **kw)  # not in fastest_rate's cache yet
    # the reference: the eigenvalues of the unforced model (default friction law) from the
    # parameters passed raw, checked by the generated function
    lam = np.abs(unforced.eigenvalues(contact=model.contact, **model.params))
    p = model.params
    expected = float(max(p["Omega_t"], p["Omega_n"], p["omega1"], float(np.max(lam))))
    checked = []
    real = _checks.param
    monkeypatch.setattr(_checks, "param", lambda *a: checked.append(a[1]) or real(*a))
    assert fastest_rate(model) == expected  # bit for bit
    assert checked == []


def test_a_continuation_in_vb_shares_one_eigenvalue_solve(monkeypatch):
    # the unforced eigenvalues under the default friction law do not take Vb or mu_s
    # (the generated variant declares its parameters): one solve serves every Vb
    calls = []
    real = unforced.eigenvalues
    monkeypatch.setattr(unforced, "eigenvalues", lambda **kw: calls.append(1) or real(**kw))
    base = Model(beta1=0.3456789012)
    rates = {fastest_rate(base.replace(Vb=v, mu_s=0.3)) for v in (0.5, 1.0, 7.0)}
    assert len(calls) == 1 and len(rates) == 1
    # a parameter it takes is a new solve, and the same number as from scratch
    moved = base.replace(omega2=1.7)
    p = moved.params
    lam = np.abs(real(contact=moved.contact, **p))
    assert fastest_rate(moved) == max(p["Omega_t"], p["Omega_n"], p["omega1"], float(lam.max()))
    assert len(calls) == 2
