"""Sweeps: executors, the table, continuation, the periodic start (beltmdsm.batch.sweep)."""

import concurrent.futures as cf
import json

import numpy as np
import pytest

from beltmdsm.batch import row as row_module
from beltmdsm.batch import sweep as sweep_module
from beltmdsm.batch import table as table_module
from beltmdsm.batch.cache import cache_key, identity
from beltmdsm.batch.sweep import sweep
from beltmdsm.batch.table import omega1_peak_ranges, table_from_csv, table_to_csv
from beltmdsm.model import Model
from beltmdsm.run.summary import PEAK_PRESENT_RATIO
from beltmdsm.settings import SolverSettings

SHORT = SolverSettings(t_end=40.0, t_discard=10.0)
VALUES = [2.0, 4.0, 12.0]
NUMERIC = (
    "peak_omega1",
    "peak_Omega",
    "energy_residual",
    "n_switches",
    "mean_friction",
    "min_normal_force",
)


def _same(a, b):
    assert list(a["regime"]) == list(b["regime"])
    for name in NUMERIC:
        np.testing.assert_array_equal(a[name], b[name])


def _key(model, settings=SHORT, **kw):
    return cache_key(identity(model, settings, **kw))


@pytest.fixture(scope="module")
def serial():
    return sweep(
        None, "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=None, progress=False
    ).table


def test_sweep_on_a_process_pool_equals_the_serial_sweep(serial):
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        pooled = sweep(
            None, "Vb", VALUES, settings=SHORT, executor=pool, cache_dir=None, progress=False
        ).table
    np.testing.assert_array_equal(pooled["Vb"], VALUES)
    _same(pooled, serial)


def test_sweep_on_a_dask_local_cluster_equals_the_serial_sweep(serial):
    distributed = pytest.importorskip("distributed")
    with distributed.Client(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as client:
        table = sweep(
            None,
            "Vb",
            VALUES,
            settings=SHORT,
            executor=client.get_executor(),
            cache_dir=None,
            progress=False,
        ).table
    _same(table, serial)


def test_cache_returns_stored_rows_without_recomputing(tmp_path, serial, monkeypatch):
    first = sweep(
        None, "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    )
    assert first.n_cached == 0
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(VALUES)
    stored = json.loads(files[0].read_text())
    assert {"params", "contact", "tension", "settings", "row"} <= set(stored)

    def fail(*args, **kwargs):
        raise AssertionError("recomputed a cached point")

    monkeypatch.setattr(sweep_module, "run_point", fail)
    again = sweep(
        None, "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    )
    assert again.n_cached == len(VALUES)
    _same(again.table, first.table)
    _same(first.table, serial)


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
        sweep(None, "Vbx", [1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="Vb"):
        sweep(None, "Vb", [-1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="values"):
        sweep(None, "Vb", [], executor="serial", cache_dir=None, progress=False)
    # the swept parameter is not a fixed one as well (the CLI's --param Vb --Vb 3)
    with pytest.raises(ValueError, match="Vb is swept"):
        sweep({"Vb": 3.0}, "Vb", [1.0], executor="serial", cache_dir=None, progress=False)


def test_values_are_sorted_and_duplicates_computed_once(serial):
    result = sweep(
        None,
        "Vb",
        [12.0, 2.0, 12.0, 4.0],
        settings=SHORT,
        executor="serial",
        cache_dir=None,
        progress=False,
    )
    np.testing.assert_array_equal(result.table["Vb"], VALUES)
    assert result.dropped == [12.0]
    _same(result.table, serial)


def test_the_json_of_a_sweep_holds_what_the_text_says(serial):
    result = sweep(
        None, "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=None, progress=False
    )
    out = result.as_dict()
    assert out["param"] == "Vb" and "Vb" not in out["params"]
    assert out["contact"] == "hertz_damp" and out["tension"] == "allowed"
    assert [r["Vb"] for r in out["rows"]] == VALUES and out["n_points"] == 3
    assert out["omega1_peak_ranges"] == [list(r) for r in result.omega1_peak_ranges()]
    assert out["unresolved"] == result.unresolved_values()
    assert out["n_cached"] == 0 and out["cache_problems"] == []
    assert out["settings"]["t_end"] == 40.0
    json.dumps(out)  # plain data


def test_linear_values_are_the_cli_grid_and_refuse_absurd_ranges():
    np.testing.assert_array_equal(
        sweep_module.linear_values(0.5, 16.0, 0.5), 0.5 + 0.5 * np.arange(32)
    )
    with pytest.raises(ValueError, match="MAX_POINTS"):
        sweep_module.linear_values(0.0, 1.0, 1e-15)
    with pytest.raises(ValueError, match="step must be > 0"):
        sweep_module.linear_values(0.0, 1.0, 0.0)
    with pytest.raises(ValueError, match="stop must be >= start"):
        sweep_module.linear_values(2.0, 1.0, 0.5)
    with pytest.raises(ValueError, match="start must be a finite number"):
        sweep_module.linear_values(float("nan"), 1.0, 0.5)


def test_sweep_refuses_what_it_cannot_run_before_running(tmp_path):
    with pytest.raises(ValueError, match="cannot sweep 'Vhat'"):
        sweep(None, "Vhat", [1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="MAX_POINTS"):
        sweep(
            None,
            "Vb",
            np.zeros(sweep_module.MAX_POINTS + 1),
            executor="serial",
            cache_dir=None,
            progress=False,
        )
    with pytest.raises(ValueError, match="executor must be"):
        sweep(None, "Vb", [1.0], executor="threads", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="'Vb' must be finite"):
        sweep(None, "Vb", [1.0, float("inf")], executor="serial", cache_dir=None, progress=False)
    # a cache folder that cannot be written is refused before any point is computed
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(ValueError, match=f"cache folder {blocker / 'x'} cannot be written"):
        sweep(None, "Vb", [1.0], executor="serial", cache_dir=blocker / "x", progress=False)


# ------------------------------------------------------- tension law and resolution


def test_a_clipped_run_is_never_served_for_an_allowed_one(tmp_path, serial, monkeypatch):
    m = Model(Vb=4.0)
    assert _key(m) == _key(Model(Vb=4.0, tension="allowed"))
    assert _key(m) != _key(m.replace(tension="clipped"))
    allowed = sweep(
        None, "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    ).table
    calls = []
    real = sweep_module.run_point

    def counting(model, *args, **kwargs):
        calls.append(model.tension)
        return real(model, *args, **kwargs)

    monkeypatch.setattr(sweep_module, "run_point", counting)
    clipped = sweep(
        Model(tension="clipped"),
        "Vb",
        [4.0],
        settings=SHORT,
        executor="serial",
        cache_dir=tmp_path,
        progress=False,
    ).table
    assert calls == ["clipped"]
    assert allowed["tension"][0] == "allowed" and clipped["tension"][0] == "clipped"
    # the laws differ at Vb = 4 (Eq. 1 pulls there 39 % of the time), so a mix-up shows
    assert clipped["n_switches"][0] != allowed["n_switches"][0]
    with pytest.raises(ValueError, match="tension must be one of 'allowed', 'clipped'"):
        sweep(
            Model(tension="pulling"), "Vb", [4.0], executor="serial", cache_dir=None, progress=False
        )


def test_unresolved_points_are_false_and_flagged_and_break_the_peak_ranges(serial):
    # t_end = 40 s: the steady window 10-40 s holds fewer than two bins of the omega1
    # band at Vb = 2 and 4, so those runs cannot tell; at 12 the transient test decides
    assert serial["resolved"].dtype == bool and serial["tension"].dtype.kind == "U"
    unresolved = ~serial["resolved"]
    assert unresolved.any()
    assert not serial["omega1_peak_present"][unresolved].any()
    t = np.zeros(6, dtype=[("Vb", "f8"), ("omega1_peak_present", "?"), ("resolved", "?")])
    t["Vb"] = [1, 2, 3, 4, 5, 6]
    t["omega1_peak_present"] = [True, True, False, True, True, False]
    t["resolved"] = [True, False, True, True, True, False]
    assert omega1_peak_ranges(t) == [(1.0, 1.0), (4.0, 5.0)]
    assert table_module.unresolved_values(t) == [2.0, 6.0]
    # a dict of columns (the notebooks' scans), with and without the resolved column
    scan = {name: t[name] for name in t.dtype.names}
    assert omega1_peak_ranges(scan) == [(1.0, 1.0), (4.0, 5.0)]
    del scan["resolved"]
    assert omega1_peak_ranges(scan) == [(1.0, 2.0), (4.0, 5.0)]


# ------------------------------------------------------- continuation (issue 13 item 3)


HYSTERESIS_MODEL = {"Omega": 6.0}
HYSTERESIS = dict(settings=SolverSettings(t_end=300.0), executor="serial", progress=False)
HYSTERESIS_VB = [12.0, 14.0, 16.0]


@pytest.fixture(scope="module")
def hysteresis():
    return {
        d: sweep(
            HYSTERESIS_MODEL, "Vb", HYSTERESIS_VB, cache_dir=None, continuation=d, **HYSTERESIS
        ).table
        for d in (None, "up", "down")
    }


def test_continued_sweeps_up_and_down_follow_different_attractors(hysteresis):
    """Fig. 19a's Omega = 6: the omega1 oscillation (amplitude ~19 m/s) and the periodic
    sliding response coexist at Vb = 12-16 m/s; a sweep keeps the one it is on.

    t_end = 300 s: the transient's envelope exp(-beta1 omega1 t) is e^-9 < 1e-3 at the
    window start, so every run is resolved a priori. The peaks read either ~19 m/s or
    below 1e-4 m/s against the threshold 0.01 x the Omega peak (~0.2 m/s), so no
    tolerance of the integration can move a point across it.
    """
    for table in hysteresis.values():
        assert table["resolved"].all() and (table["status"] == "done").all()
        np.testing.assert_array_equal(table["Vb"], HYSTERESIS_VB)  # ascending either way
        ratio = table["peak_omega1"] / table["peak_Omega"]
        assert np.all((ratio > 10 * PEAK_PRESENT_RATIO) | (ratio < 1e-2 * PEAK_PRESENT_RATIO))
    present = {d: set(t["Vb"][t["omega1_peak_present"]]) for d, t in hysteresis.items()}
    # from rest: the oscillation at 12 and 14, sliding at 16
    assert present[None] == {12.0, 14.0}
    # up from the oscillation at 12: it persists at 16; down from sliding at 16: it
    # persists at 12 and 14 (hysteresis)
    assert present["up"] == {12.0, 14.0, 16.0}
    assert present["down"] == set()
    assert (hysteresis["up"]["peak_omega1"] > 15).all()


def test_a_continued_point_starts_at_its_predecessors_state_at_phase_zero(hysteresis, monkeypatch):
    from beltmdsm.simulation import simulate

    seen = []
    real = row_module.simulate

    def recording(model, **kwargs):
        seen.append((model["Vb"], kwargs["y0"]))
        return real(model, **kwargs)

    monkeypatch.setattr(row_module, "simulate", recording)
    sweep(HYSTERESIS_MODEL, "Vb", HYSTERESIS_VB, cache_dir=None, continuation="down", **HYSTERESIS)
    assert [vb for vb, _ in seen] == [16.0, 14.0, 12.0]  # descending
    assert seen[0][1] is None  # the first from rest
    first = real(dict(Vb=16.0, Omega=6.0), settings=HYSTERESIS["settings"])
    T = np.pi / 3
    t_k = np.floor(300.0 / T) * T
    assert 300.0 - T < t_k <= 300.0
    np.testing.assert_array_equal(seen[1][1], first.trajectory.state(np.array([t_k]))[:, 0])
    # and the continued point is that run: the same row as a run from that state
    again = simulate(
        dict(Vb=14.0, Omega=6.0), settings=HYSTERESIS["settings"], y0=seen[1][1]
    ).summary
    row = hysteresis["down"][1]
    assert row["peak_omega1"] == again.peak_omega1
    assert row["n_switches"] == again.n_switches


def test_a_continued_sweep_is_cached_by_direction_and_start_state(
    tmp_path, hysteresis, monkeypatch
):
    up = sweep(
        HYSTERESIS_MODEL, "Vb", HYSTERESIS_VB, cache_dir=tmp_path, continuation="up", **HYSTERESIS
    ).table
    assert len(list(tmp_path.glob("*.json"))) == 3
    m = Model(Vb=12.0, Omega=6.0)
    s = HYSTERESIS["settings"]
    keys = {
        _key(m, s),
        _key(m, s, continuation="up"),
        _key(m, s, continuation="down"),
        _key(m, s, continuation="up", y0=[1.0, 0.0, 1.0, 0.0]),
    }
    assert len(keys) == 4

    def fail(*args, **kwargs):
        raise AssertionError("recomputed a cached point")

    monkeypatch.setattr(sweep_module, "run_point", fail)
    again = sweep(
        HYSTERESIS_MODEL, "Vb", HYSTERESIS_VB, cache_dir=tmp_path, continuation="up", **HYSTERESIS
    )
    _same(again.table, up)
    _same(up, hysteresis["up"])
    # the other direction starts elsewhere: nothing of it is in the cache
    with pytest.raises(AssertionError, match="recomputed"):
        sweep(
            HYSTERESIS_MODEL,
            "Vb",
            HYSTERESIS_VB,
            cache_dir=tmp_path,
            continuation="down",
            **HYSTERESIS,
        )


def test_continuation_refuses_what_it_cannot_do():
    kw = dict(cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="continuation must be None, 'up' or 'down'"):
        sweep(None, "Vb", [1.0], executor="serial", continuation="sideways", **kw)
    with (
        cf.ThreadPoolExecutor(1) as pool,
        pytest.raises(ValueError, match="one after another.*executor must be None"),
    ):
        sweep(None, "Vb", [1.0], executor=pool, continuation="up", **kw)
    with pytest.raises(ValueError, match="continuation at Vb = 1: no excitation"):
        sweep({"Omega": 0.0}, "Vb", [1.0], executor="serial", continuation="up", **kw)
    with pytest.raises(ValueError, match="period 1.5708 s is longer than t_end = 1 s"):
        sweep(
            None,
            "Vb",
            [1.0],
            settings=SolverSettings(t_end=1.0, dt=0.01),
            executor="serial",
            continuation="up",
            **kw,
        )


def test_a_sweep_started_on_the_periodic_response(tmp_path):
    from beltmdsm.periodic.floquet import floquet

    settings = SolverSettings(t_end=300.0)
    kw = dict(settings=settings, executor="serial", progress=False)
    # 3: stable, 5: unstable (Floquet); 6.3: no periodic response (periodic/shooting.py)
    table = sweep(None, "Vb", [3.0, 5.0, 6.3], start="periodic", cache_dir=tmp_path, **kw).table
    assert floquet(Model(Vb=3.0)).stable is True and floquet(Model(Vb=5.0)).stable is False
    assert list(table["omega1_peak_present"]) == [False, True, False]
    assert list(table["resolved"]) == [True, True, False]
    assert table["regime"][2] == row_module.NO_PERIODIC_RESPONSE
    assert table["status"][2] == "no_periodic" and np.isnan(table["peak_omega1"][2])
    # the start is part of the point: the cache never serves a run from rest for it
    rest = sweep(None, "Vb", [3.0, 5.0, 6.3], cache_dir=tmp_path, **kw).table
    assert list(rest["regime"]).count(row_module.NO_PERIODIC_RESPONSE) == 0
    again = sweep(None, "Vb", [3.0, 5.0, 6.3], start="periodic", cache_dir=tmp_path, **kw)
    assert again.n_cached == 3
    np.testing.assert_array_equal(again.table["peak_Omega"], table["peak_Omega"])
    m = Model(Vb=3.0)
    assert _key(m, settings) != _key(m, settings, start="periodic")


def test_a_periodic_start_is_refused_where_it_means_nothing():
    kw = dict(cache_dir=None, progress=False, executor="serial")
    with pytest.raises(ValueError, match="start must be one of 'rest', 'periodic'"):
        sweep(None, "Vb", [1.0], start="equilibrium", **kw)
    with pytest.raises(ValueError, match="continued sweep.*start must be 'rest'"):
        sweep(None, "Vb", [1.0], start="periodic", continuation="up", **kw)


def test_a_row_has_one_shape_from_the_run_to_the_table(tmp_path):
    # issue 30 item 5: the run's Row is what the cache stores, what the table holds,
    # what --json prints and what to_pandas gives, with the same keys and values
    from beltmdsm.batch.row import COLUMNS, MODULATION_COLUMNS, Row, run_point
    from beltmdsm.simulation import simulate

    m = Model(Vb=4.0)
    row = run_point(m, SHORT, modulation=True)
    assert isinstance(row, Row) and set(row.modulation) == {n for n, _ in MODULATION_COLUMNS}
    stored = row.as_dict()
    assert list(stored) == [n for n, _ in COLUMNS + MODULATION_COLUMNS]
    # plain JSON values: a round trip through the cache's JSON changes nothing
    assert Row.from_dict(json.loads(json.dumps(stored))) == row
    # the summary's numbers, as a run of its own gives them (wall_s aside)
    summary = simulate(m, settings=SHORT).summary
    for name, _ in COLUMNS:
        if name not in ("wall_s", "error", "omega1_peak_present"):
            assert stored[name] == getattr(summary, name), name
    # an unresolved peak (None) is stored as False beside resolved False: a bool column
    assert stored["omega1_peak_present"] is bool(summary.omega1_peak_present)
    assert stored["error"] == ""
    result = sweep(
        None, "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False,
        modulation=True,
    )  # fmt: skip
    (cached,) = tmp_path.glob("*.json")
    on_disk = json.loads(cached.read_text())["row"]
    (json_row,) = result.as_dict()["rows"]
    (record,) = table_module.records(result.table)
    assert json_row == record == {"Vb": 4.0, **on_disk}
    assert on_disk.keys() == stored.keys()
    again = sweep(
        None, "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False,
        modulation=True,
    )  # fmt: skip
    assert again.n_cached == 1 and table_module.records(again.table) == [json_row]
    pandas = pytest.importorskip("pandas")
    frame = again.to_pandas()
    assert isinstance(frame, pandas.DataFrame) and list(frame.columns) == list(json_row)
    assert frame.iloc[0].to_dict() == json_row


def test_a_modulation_row_without_a_period_is_served_from_the_cache(tmp_path):
    # Omega_t = 0: no cycles of 2 pi / Omega_t, whose columns are NaN; the row once
    # lacked them, and its cache file was recomputed (and warned about) on every rerun
    kw = dict(settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False)
    first = sweep(Model(Omega_t=0.0, Omega_n=0.0), "Vb", [2.0], modulation=True, **kw)
    assert np.isnan(first.table["mu_eff_Omega_mean"][0])
    assert first.table["mu_eff_omega1_mean"][0] == pytest.approx(Model()["mu_s"], rel=1e-12)
    again = sweep(Model(Omega_t=0.0, Omega_n=0.0), "Vb", [2.0], modulation=True, **kw)
    assert again.n_cached == 1 and again.problems == []
