"""Shared fixtures: parameter sets drawn at random around the paper's base set."""

import mpmath
import numpy as np
import pytest

from generated.parameters import BASE

#: Parameters of the paper's Eq. (4) (the per-direction excitation defaults to these).
MODEL = ("beta1", "omega1", "beta2", "omega2", "alpha", "Omega", "mu_s", "g", "Vb")


def random_params(rng, spread=3.0):
    """One parameter set: the registry's base set (``BASE``: every law's parameters too),
    each parameter of Eq. (4) times a log-uniform factor in [1/spread, spread]."""
    varied = {
        k: BASE[k] * float(np.exp(rng.uniform(-np.log(spread), np.log(spread)))) for k in MODEL
    }
    return {**BASE, **varied}


@pytest.fixture
def rng():
    return np.random.default_rng(20261121)


@pytest.fixture
def base():
    return dict(BASE)


@pytest.fixture
def mp50():
    with mpmath.workdps(50):
        yield


def rel_err(approx, exact):
    """Largest relative error of ``approx`` against mpmath ``exact`` (nested sequences)."""
    a = np.asarray(approx, dtype=complex).ravel()
    e = [mpmath.mpc(x) for x in np.asarray(exact, dtype=object).ravel()]
    worst = 0.0
    for x, y in zip(a, e):
        scale = max(abs(y), mpmath.mpf(1e-300))
        worst = max(worst, float(abs(mpmath.mpc(x) - y) / scale))
    return worst


@pytest.fixture(params=["numpy", "numba"])
def backend(request):
    """Both paths of the accelerated functions (``backend=``); numba's where installed."""
    if request.param == "numba":
        pytest.importorskip("numba")
    return request.param
