"""Shared fixtures: parameter sets drawn at random around the paper's base set."""

import os
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
        "coexistence": beltmdsm.coexistence(m, "Vb", 3.5, 4.5, points=3),
        "map": beltmdsm.floquet_map(m, "Vb", 0.5, 12.0, "beta1", 0.05, 0.35, points=3),
        "sweep": beltmdsm.sweep(
            m, "Vb", [3.0, 4.0], t_end=50.0, executor="serial", cache_dir=None, progress=False
        ),
    }


def pytest_collection_finish(session):
    """Start the fixtures in `EARLY` as soon as the tests are collected, when a selected
    test reads one: they are work in processes of their own (minutes of SymPy, of
    Sphinx), which then runs on a second core beside the rest of the suite instead of
    after it. Each test module keeps what it started in its ``STARTED``, by fixture."""
    if session.config.option.collectonly or hasattr(session.config, "workerinput"):
        # under pytest-xdist every worker collects every test: each would start them.
        # There the fixtures start their work when their first test runs, which
        # `pytest_collection_modifyitems` puts first, beside the other workers' tests
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


#: The tests (node id prefixes) that pytest-xdist hands out first, longest first, each
#: with its measured wall time on 2 idle cores: a worker that takes a long test near the
#: end of the run would leave the other core idle until it finishes. The fixtures of
#: `EARLY` head the list: their tests wait for processes of their own (minutes of SymPy,
#: of Sphinx), which then run beside the other worker's tests.
FIRST = (
    # the first test of each group that reads an `EARLY` fixture: the group goes with it
    "tests/derive/test_codegen.py::test_generated_is_up_to_date",  # two SymPy processes
    "tests/test_docs_site.py::test_the_site_builds_and_its_internal_links_resolve",  # Sphinx
    "notebooks/fig17_21_validation.ipynb",  # 119 s
    "notebooks/fig06_09_stability_maps.ipynb",  # 66 s
    "notebooks/stribeck_research.ipynb",  # 42 s
    "tests/beltmdsm/attractors/test_attractor.py",  # the locks and the torus: 36 + 30 + 18 + 12 s
)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_auto_num_workers(config):
    """``-n auto`` (pyproject.toml's addopts): a worker per core, 8 at most, where the
    run names a folder (the whole suite, ``tests``, a subpackage's tests); none where it
    names files or tests only, so that ``python -m pytest tests/test_layers.py`` starts at once
    (each worker imports and collects for seconds). ``PYTEST_XDIST_AUTO_NUM_WORKERS`` or
    ``-n N`` decide instead; ``-n 0`` runs in this process."""
    given = os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS")
    if given:
        return int(given)
    here = config.invocation_params.dir
    if not any((here / arg.split("::")[0]).is_dir() for arg in config.args):
        return 0
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    # one core: the `EARLY` processes give the overlap; more than 8 workers: each holds
    # its own imports (hundreds of MB) and the tests' process pools already span the cores
    return min(cores or 1, 8) if (cores or 1) > 1 else 0


def _groups(item):
    """The xdist groups of ``item``: a fixture of this suite's that outlives one test
    (module, class or package scope: its module; session scope: its name) is computed
    once per worker, so the tests that share it run on one worker (``--dist
    loadgroup``); a test that shares none runs wherever a worker is free."""
    info = getattr(item, "_fixtureinfo", None)  # a notebook has none
    names = set()
    for defs in info.name2fixturedefs.values() if info else ():
        fixture = defs[-1]
        if fixture.scope != "function" and fixture.baseid:  # "": pytest's or a plugin's
            names.add(fixture.argname if fixture.scope == "session" else item.nodeid.split("::")[0])
    return names


@pytest.hookimpl(tryfirst=True)  # before xdist's, which reads the groups
def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist: the groups of each test (`_groups`) and the longest tests
    first (`FIRST`), in every worker alike (xdist checks that they collect the same)."""
    if not hasattr(config, "workerinput"):
        return
    for item in items:
        for name in sorted(_groups(item)):
            item.add_marker(pytest.mark.xdist_group(name))
    rank = {prefix: i for i, prefix in enumerate(FIRST)}

    def first(item):
        return next((i for p, i in rank.items() if item.nodeid.startswith(p)), len(FIRST))

    items.sort(key=first)  # stable: the rest keep their order
