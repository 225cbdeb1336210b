"""Shared fixtures: parameter sets drawn at random around the paper's base set."""

import shutil
import tempfile
from pathlib import Path

import mpmath
import numpy as np
import pytest

from beltmdsm.generated.parameters import BASE

#: tests/derive/test_codegen.py's derivations started at collection: (module, folder).
_DERIVATIONS = pytest.StashKey[tuple]()

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


def pytest_collection_finish(session):
    """Start tests/derive/test_codegen.py's two derivations (two minutes of SymPy in
    processes of their own) as soon as the tests are collected, when one of the tests
    that read them is selected: they then run on a second core beside the rest of the
    suite instead of after it (`start_derivations`)."""
    if session.config.option.collectonly:
        return
    for item in session.items:
        if "derivations" in getattr(item, "fixturenames", ()):
            module = item.module
            folder = Path(tempfile.mkdtemp(prefix="beltmdsm-derivations-"))
            module.STARTED["runs"] = module.start_derivations(folder)
            session.config.stash[_DERIVATIONS] = (module, folder)
            return


def pytest_sessionfinish(session):
    module, folder = session.config.stash.get(_DERIVATIONS, (None, None))
    if module is not None:
        runs = module.STARTED.pop("runs", None)
        if runs:  # not read: the session stopped before the tests that read them
            module.stop_derivations(runs)
        shutil.rmtree(folder, ignore_errors=True)
