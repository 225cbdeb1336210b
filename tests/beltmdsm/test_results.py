"""What a result is as a value (issue 30, item 3): a short ``repr``, standard-library
pickling (to a worker process and back), ``to_pandas()`` of the tables, and one
argument order (the model first) across the analyses.

References: the results' own attributes and ``as_dict()`` (what the ``repr`` and the
tables show must be what the result holds), and the same computation in this process
(for the results that come back from a worker process).
"""

import concurrent.futures as cf
import math
import pickle

import numpy as np
import pytest

import beltmdsm
from beltmdsm import Model
from beltmdsm._display import MAX_LINES

MODEL = Model(Vb=4.0)  # that of the small results (tests/conftest.py)


@pytest.fixture
def results(small_results):
    """One of each result, on small ranges (tests/conftest.py)."""
    return small_results


@pytest.mark.parametrize(
    "name", ["simulation", "floquet", "band", "branch", "coexistence", "map", "sweep"]
)
def test_a_repr_is_one_screen(results, name):
    text = repr(results[name])
    lines = text.splitlines()
    # a heading, at most MAX_LINES items (and "... and n more"), a nested summary's
    assert len(lines) <= MAX_LINES + 7 and max(map(len, lines)) < 400, text
    assert len(text) < 3000


def test_the_reprs_say_what_the_results_hold(results):
    branch, band, coex = results["branch"], results["band"], results["coexistence"]
    ns = [s for s in branch.special if s.kind == "neimark_sacker"]
    assert ns and f"NS at Vb = {ns[0].value:.6g}" in repr(branch)
    for e in band.edges:
        assert f"at Vb = {e.value:.6g}" in repr(band)
    for c in coex.ranges:
        assert f"coexist in [{c.range[0]:.6g}, {c.range[1]:.6g}]" in repr(coex)
    f = results["floquet"]
    assert f"max |mu| = {f.max_abs_multiplier:.6g}" in repr(f) and f.verdict in repr(f)


@pytest.mark.parametrize("name", ["simulation", "floquet", "band", "branch", "coexistence", "map"])
def test_results_pickle_and_report_the_same(results, name):
    r = results[name]
    back = pickle.loads(pickle.dumps(r))
    assert repr(back) == repr(r)
    if hasattr(r, "as_dict"):
        assert _same(back.as_dict(), r.as_dict())


def _same(a, b):
    """Equal, NaN equal to NaN (the JSON of a result carries NaN where it grazes)."""
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return a == b


def test_floquet_runs_in_a_process_pool():
    models = [MODEL.replace(Vb=v) for v in (3.0, 5.0)]
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        remote = list(pool.map(beltmdsm.floquet, models))
    for m, r in zip(models, remote):
        assert _same(r.as_dict(), beltmdsm.floquet(m).as_dict())
    # the response keeps what it reports: its monodromy and the state it shoots in
    local = beltmdsm.floquet(models[0]).response.monodromy_tangential
    np.testing.assert_array_equal(remote[0].response.monodromy_tangential, local)


def test_the_model_is_given_once():
    # the model last (deprecated, issue 37) is tests/beltmdsm/test_calling.py's
    with pytest.raises(TypeError, match="multiple values for argument 'model'"):
        beltmdsm.floquet_band(MODEL, "Vb", 3.0, 7.0, model=MODEL)
    with pytest.raises(TypeError, match="model twice"):
        beltmdsm.floquet_band("Vb", 3.0, 7.0, MODEL, model=MODEL)


def test_sweep_takes_the_settings_as_keywords(results):
    s = results["sweep"]
    assert s.settings.t_end == 50.0
    explicit = beltmdsm.sweep(
        MODEL, "Vb", [3.0, 4.0], settings=beltmdsm.SolverSettings(t_end=50.0),
        executor="serial", cache_dir=None, progress=False,
    )  # fmt: skip
    for name in set(s.table.dtype.names) - {"wall_s"}:  # the run's time differs
        np.testing.assert_array_equal(explicit.table[name], s.table[name])


def test_the_tables_are_the_results_arrays(results):
    pd = pytest.importorskip("pandas")
    sweep, branch, band, fmap = results["sweep"], results["branch"], results["band"], results["map"]
    df = sweep.to_pandas()
    assert list(df.columns) == list(sweep.table.dtype.names)
    for name in sweep.table.dtype.names:
        np.testing.assert_array_equal(df[name].to_numpy(), sweep.table[name])
    points = branch.to_pandas()
    np.testing.assert_array_equal(points["Vb"], [p.value for p in branch.points])
    np.testing.assert_array_equal(points["X1'"], [p.state[1] for p in branch.points])
    np.testing.assert_array_equal(points["stable"], [p.stable for p in branch.points])
    special = branch.to_pandas("special")
    assert list(special["label"]) == [{"neimark_sacker": "NS"}.get(s.kind, s.kind)
                                      for s in branch.special]  # fmt: skip
    edges = band.to_pandas()
    np.testing.assert_array_equal(edges["value"], [e.value for e in band.edges])
    assert list(edges["kind"]) == [e.kind for e in band.edges]
    grid = band.to_pandas("grid")
    np.testing.assert_array_equal(
        grid["max_abs_multiplier"], [g.max_abs_multiplier for g in band.grid]
    )
    curves = fmap.to_pandas()
    for i, c in enumerate(fmap.curves):
        mine = curves[curves["curve"] == i]
        np.testing.assert_array_equal(mine["Vb"], c.x)
        np.testing.assert_array_equal(mine["beta1"], c.y)
    assert isinstance(df, pd.DataFrame)


def test_to_pandas_names_pandas_where_it_is_missing(results, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas then raises
    with pytest.raises(ImportError, match="needs pandas"):
        results["sweep"].to_pandas()
