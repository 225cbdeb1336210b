"""Shared fixtures: parameter sets drawn at random around the paper's base set."""

import shutil
import tempfile
from pathlib import Path

import mpmath
import numpy as np
import pytest

from beltmdsm.generated.parameters import BASE

#: Module fixtures whose work runs in processes of their own, started when the tests are
#: collected (`pytest_collection_finish`): fixture -> its test module's functions that
#: start it (into a folder; None: nothing to start) and that stop what was started.
EARLY = {
    "derivations": ("start_derivations", "stop_derivations"),  # tests/derive/test_codegen.py
    "site": ("start_site", "stop_site"),  # tests/test_docs_site.py
}
#: What `pytest_collection_finish` started: (module, fixture, stop, folder).
_STARTED = pytest.StashKey[list]()

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
    """Start the fixtures in `EARLY` as soon as the tests are collected, when a selected
    test reads one: they are work in processes of their own (minutes of SymPy, of
    Sphinx), which then runs on a second core beside the rest of the suite instead of
    after it. Each test module keeps what it started in its ``STARTED``, by fixture."""
    if session.config.option.collectonly:
        return
    started = session.config.stash.setdefault(_STARTED, [])
    seen = set()
    for item in session.items:
        for name in set(getattr(item, "fixturenames", ())) & EARLY.keys():
            module = item.module
            start, stop = (getattr(module, f, None) for f in EARLY[name])
            if start is None or (module, name) in seen:
                continue
            seen.add((module, name))
            folder = Path(tempfile.mkdtemp(prefix=f"beltmdsm-{name}-"))
            work = start(folder)
            if work is not None:
                module.STARTED[name] = work
            started.append((module, name, stop, folder))


def pytest_sessionfinish(session):
    for module, name, stop, folder in session.config.stash.get(_STARTED, []):
        work = module.STARTED.pop(name, None)
        if work is not None:  # not read: the session stopped before the tests that read it
            stop(work)
        shutil.rmtree(folder, ignore_errors=True)
