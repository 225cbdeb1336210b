"""One of each public result, computed once per session on small ranges (seconds):
what tests/beltmdsm/test_results.py and test_plotting.py read."""

import pytest

import beltmdsm
from beltmdsm import Model

#: The model of the small results (the base set at Vb = 4 m/s).
SMALL_MODEL = Model(Vb=4.0)


@pytest.fixture(scope="session")
def small_results():
    m = SMALL_MODEL
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
