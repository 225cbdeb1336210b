"""Sweeps: executors, the disk cache, the table."""
import concurrent.futures as cf
import json

import numpy as np
import pytest

from runtime import sweep as sweep_module
from runtime.simulate import SolverSettings
from runtime.sweep import (cache_key, omega1_peak_ranges, sweep, table_from_csv,
                           table_to_csv)

SHORT = SolverSettings(t_end=40.0, t_discard=10.0)
VALUES = [2.0, 4.0, 12.0]
NUMERIC = ("peak_omega1", "peak_Omega", "energy_residual", "n_switches", "mean_friction",
           "min_normal_force")


def _same(a, b):
    assert list(a["regime"]) == list(b["regime"])
    for name in NUMERIC:
        np.testing.assert_array_equal(a[name], b[name])


@pytest.fixture(scope="module")
def serial():
    return sweep("Vb", VALUES, settings=SHORT, executor="serial", cache_dir=None, progress=False)


def test_sweep_on_a_process_pool_equals_the_serial_sweep(serial):
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        pooled = sweep("Vb", VALUES, settings=SHORT, executor=pool, cache_dir=None, progress=False)
    np.testing.assert_array_equal(pooled["Vb"], VALUES)
    _same(pooled, serial)


def test_sweep_on_a_dask_local_cluster_equals_the_serial_sweep(serial):
    distributed = pytest.importorskip("distributed")
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2,
                            dashboard_address=None) as client:
        table = sweep("Vb", VALUES, settings=SHORT, executor=client.get_executor(),
                      cache_dir=None, progress=False)
    _same(table, serial)


def test_cache_returns_stored_rows_without_recomputing(tmp_path, serial, monkeypatch):
    first = sweep("Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path,
                  progress=False)
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(VALUES)
    stored = json.loads(files[0].read_text())
    assert set(stored) == {"params", "contact", "settings", "row"}

    def fail(*args, **kwargs):
        raise AssertionError("recomputed a cached point")
    monkeypatch.setattr(sweep_module, "run_point", fail)
    again = sweep("Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path,
                  progress=False)
    _same(again, first)
    _same(first, serial)


def test_cache_key_depends_on_parameters_settings_and_contact():
    from runtime.model import resolve_parameters
    p = resolve_parameters(Vb=4.0)
    k = cache_key(p, "hertz_damp", SHORT)
    assert k == cache_key(dict(p), "hertz_damp", SolverSettings(t_end=40.0, t_discard=10.0))
    assert k != cache_key(resolve_parameters(Vb=4.5), "hertz_damp", SHORT)
    assert k != cache_key(p, "kelvin_voigt", SHORT)
    assert k != cache_key(p, "hertz_damp", SolverSettings(t_end=40.0, t_discard=10.0, rtol=1e-9))
    assert k != cache_key(p, "hertz_damp", SHORT, modulation=True)


def test_csv_round_trip(tmp_path, serial):
    path = tmp_path / "t.csv"
    table_to_csv(serial, path)
    back = table_from_csv(path)
    assert back.dtype.names == serial.dtype.names
    _same(back, serial)


def test_omega1_peak_ranges_groups_contiguous_values():
    t = np.zeros(6, dtype=[("Vb", "f8"), ("omega1_peak_present", "?")])
    t["Vb"] = [1, 2, 3, 4, 5, 6]
    t["omega1_peak_present"] = [False, True, True, False, True, True]
    assert omega1_peak_ranges(t) == [(2.0, 3.0), (5.0, 6.0)]


def test_bad_sweep_inputs_are_named():
    with pytest.raises(ValueError, match="Vbx"):
        sweep("Vbx", [1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="Vb"):
        sweep("Vb", [-1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="values"):
        sweep("Vb", [], executor="serial", cache_dir=None, progress=False)
