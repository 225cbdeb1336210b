"""Shared fixtures: parameter sets drawn at random around the paper's base set."""

import mpmath
import numpy as np
import pytest

from beltmdsm.generated.parameters import BASE

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


@pytest.fixture(scope="session")
def small_results():
    """One of each public result of beltmdsm, computed once per session on small ranges
    (seconds): what tests/beltmdsm/test_results.py and test_plotting.py read."""
    import beltmdsm

    m = beltmdsm.Model(Vb=4.0)
    return {
        "simulation": beltmdsm.simulate(m, t_end=50.0),
        "floquet": beltmdsm.floquet(m),
        "band": beltmdsm.floquet_band(m, "Vb", 3.0, 7.0, points=9),
        "branch": beltmdsm.branch(m, param="Vb", lo=3.0, hi=5.0),
        "coexistence": beltmdsm.coexistence(m, "Vb", 3.5, 4.5, step=0.5),
        "map": beltmdsm.floquet_map(m, "Vb", 0.5, 12.0, "beta1", 0.05, 0.35, rows=3),
        "sweep": beltmdsm.sweep(
            m, "Vb", [3.0, 4.0], t_end=50.0, executor="serial", cache_dir=None, progress=False
        ),
    }
