"""Sweeps: executors, the disk cache, the table."""

import concurrent.futures as cf
import json

import numpy as np
import pytest

from runtime import sweep as sweep_module
from runtime.simulate import PEAK_PRESENT_RATIO, SolverSettings
from runtime.sweep import cache_key, omega1_peak_ranges, sweep, table_from_csv, table_to_csv

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
    with distributed.Client(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as client:
        table = sweep(
            "Vb",
            VALUES,
            settings=SHORT,
            executor=client.get_executor(),
            cache_dir=None,
            progress=False,
        )
    _same(table, serial)


def test_cache_returns_stored_rows_without_recomputing(tmp_path, serial, monkeypatch):
    first = sweep(
        "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    )
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(VALUES)
    stored = json.loads(files[0].read_text())
    assert {"params", "contact", "settings", "row"} <= set(stored)

    def fail(*args, **kwargs):
        raise AssertionError("recomputed a cached point")

    monkeypatch.setattr(sweep_module, "run_point", fail)
    again = sweep(
        "Vb", VALUES, settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    )
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


# ------------------------------------------------------- the cache under corruption and load


def _cache_file(tmp_path, vb=4.0):
    from runtime.model import resolve_parameters

    p = resolve_parameters(Vb=vb)
    return tmp_path / f"{cache_key(p, 'hertz_damp', SHORT)}.json"


def _stored_is_valid(path):
    from runtime.model import resolve_parameters

    data = json.loads(path.read_text())
    p = resolve_parameters(Vb=data["params"]["Vb"])
    row, problem = sweep_module.read_cached(path, p, "hertz_damp", SHORT)
    return row is not None and problem is None


CORRUPTIONS = {
    "not valid JSON": lambda text: text[: len(text) // 2],
    "missing checksum": lambda text: json.dumps(
        {k: v for k, v in json.loads(text).items() if k != "checksum"}
    ),
    "does not match its checksum": lambda text: text.replace('"n_switches": ', '"n_switches": 1'),
    "another point's parameters": lambda text: text.replace('"Vb": 4.0', '"Vb": 4.5'),
    "not its name's": lambda text: json.dumps({**json.loads(text), "key": "0" * 64}),
    "lacks": lambda text: json.dumps(_drop_column(json.loads(text), "peak_omega1")),
}


def _drop_column(data, name):
    del data["row"][name]
    data["checksum"] = sweep_module._checksum(data["row"])
    return data


@pytest.mark.parametrize("what", list(CORRUPTIONS))
def test_a_corrupted_cache_file_is_reported_recomputed_and_rewritten(tmp_path, serial, what):
    sweep("Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False)
    path = _cache_file(tmp_path)
    good = path.read_text()
    path.write_text(CORRUPTIONS[what](good))
    with pytest.warns(sweep_module.CacheWarning, match=f"{path.name}.*{what}"):
        table = sweep(
            "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
        )
    _same(table, serial[1:2])  # the recomputed row, not the corrupted one
    assert json.loads(path.read_text())["row"]["n_switches"] == int(serial["n_switches"][1])
    assert _stored_is_valid(path)


def test_a_valid_cache_file_passes_its_checks(tmp_path):
    sweep("Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False)
    assert _stored_is_valid(_cache_file(tmp_path))
    assert sweep_module.read_cached(tmp_path / "absent.json", {}, "hertz_damp", SHORT) == (
        None,
        None,
    )


def _sweep_into(cache_dir, values):
    return sweep(
        "Vb", values, settings=SHORT, executor="serial", cache_dir=cache_dir, progress=False
    )


def test_concurrent_writers_into_one_cache_leave_valid_files(tmp_path, serial):
    """Two processes and two threads write the same points at once: every file is whole."""
    import threading

    values = VALUES * 2
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        tables = list(pool.map(_sweep_into, [tmp_path] * 2, [values] * 2))
    threads = [threading.Thread(target=_sweep_into, args=(tmp_path, values)) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(VALUES)
    assert all(_stored_is_valid(f) for f in files)
    assert not list(tmp_path.glob(".*.tmp"))  # every temporary file was renamed
    for table in tables:
        _same(table[: len(VALUES)], serial)


def test_temporary_names_are_unique_per_write(tmp_path, monkeypatch):
    """A UUID, not a process id: workers on two hosts can share a pid."""
    seen = []
    real = sweep_module.os.replace

    def spy(src, dst):
        seen.append(str(src))
        real(src, dst)

    monkeypatch.setattr(sweep_module.os, "replace", spy)
    for _ in range(2):
        sweep_module._write_atomically(tmp_path / "x.json", "{}")
    assert len(set(seen)) == 2 and all(".x.json." in s for s in seen)


def test_cache_key_changes_with_the_code_and_the_version(tmp_path, monkeypatch):
    from runtime.model import resolve_parameters

    p = resolve_parameters(Vb=4.0)
    source = tmp_path / "integrator.py"
    source.write_text("x = 1\n")
    monkeypatch.setattr(sweep_module, "_ROOT", tmp_path)
    monkeypatch.setattr(sweep_module, "code_files", lambda: [source])
    sweep_module.code_hash.cache_clear()
    try:
        before = cache_key(p, "hertz_damp", SHORT)
        assert cache_key(p, "hertz_damp", SHORT) == before
        source.write_text("x = 2\n")
        sweep_module.code_hash.cache_clear()
        after = cache_key(p, "hertz_damp", SHORT)
        assert after != before
        monkeypatch.setattr(sweep_module, "package_version", lambda: "99.0")
        assert cache_key(p, "hertz_damp", SHORT) != after
    finally:
        monkeypatch.undo()
        sweep_module.code_hash.cache_clear()


def test_the_code_hash_covers_generated_and_runtime_sources():
    names = {f.relative_to(sweep_module._ROOT).as_posix() for f in sweep_module.code_files()}
    assert {
        "generated/stability.py",
        "generated/mp/stability.py",
        "generated/_support.py",
        "runtime/simulate.py",
        "runtime/superposition.py",
    } <= names
    assert len(sweep_module.code_hash()) == 64


def test_package_version_falls_back_to_pyproject(monkeypatch):
    from importlib import metadata

    tomllib = pytest.importorskip("tomllib")

    def missing(name):
        raise metadata.PackageNotFoundError(name)

    monkeypatch.setattr(metadata, "version", missing)
    sweep_module.package_version.cache_clear()
    try:
        with open(sweep_module._ROOT / "pyproject.toml", "rb") as fh:
            expected = tomllib.load(fh)["project"]["version"]
        assert sweep_module.package_version() == expected
    finally:
        monkeypatch.undo()
        sweep_module.package_version.cache_clear()


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


def test_sweep_refuses_what_it_cannot_run_before_running():
    with pytest.raises(ValueError, match="cannot sweep 'Vhat'"):
        sweep("Vhat", [1.0], executor="serial", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="MAX_POINTS"):
        sweep(
            "Vb",
            np.zeros(sweep_module.MAX_POINTS + 1),
            executor="serial",
            cache_dir=None,
            progress=False,
        )
    with pytest.raises(ValueError, match="executor must be"):
        sweep("Vb", [1.0], executor="threads", cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="'Vb' must be finite"):
        sweep("Vb", [1.0, float("inf")], executor="serial", cache_dir=None, progress=False)


# ------------------------------------------------------- tension law and resolution


def test_a_clipped_run_is_never_served_for_an_allowed_one(tmp_path, serial, monkeypatch):
    from runtime.model import resolve_parameters

    p = resolve_parameters(Vb=4.0)
    assert cache_key(p, "hertz_damp", SHORT) == cache_key(p, "hertz_damp", SHORT, tension="allowed")
    assert cache_key(p, "hertz_damp", SHORT) != cache_key(p, "hertz_damp", SHORT, tension="clipped")
    allowed = sweep(
        "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False
    )
    calls = []
    real = sweep_module.run_point

    def counting(*args, **kwargs):
        calls.append(kwargs["tension"])
        return real(*args, **kwargs)

    monkeypatch.setattr(sweep_module, "run_point", counting)
    clipped = sweep(
        "Vb",
        [4.0],
        settings=SHORT,
        tension="clipped",
        executor="serial",
        cache_dir=tmp_path,
        progress=False,
    )
    assert calls == ["clipped"]
    assert allowed["tension"][0] == "allowed" and clipped["tension"][0] == "clipped"
    # the laws differ at Vb = 4 (Eq. 1 pulls there 39 % of the time), so a mix-up shows
    assert clipped["n_switches"][0] != allowed["n_switches"][0]
    with pytest.raises(ValueError, match="tension must be one of 'allowed', 'clipped'"):
        sweep("Vb", [4.0], tension="pulling", executor="serial", cache_dir=None, progress=False)


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
    assert sweep_module.unresolved_values(t) == [2.0, 6.0]
    # a dict of columns (the notebooks' scans), with and without the resolved column
    scan = {name: t[name] for name in t.dtype.names}
    assert omega1_peak_ranges(scan) == [(1.0, 1.0), (4.0, 5.0)]
    del scan["resolved"]
    assert omega1_peak_ranges(scan) == [(1.0, 2.0), (4.0, 5.0)]


# ------------------------------------------------------- continuation (issue 13 item 3)


def test_excitation_period_is_the_common_period_of_the_active_excitations():
    from runtime.model import resolve_parameters

    period = sweep_module.excitation_period
    assert period(resolve_parameters()) == pytest.approx(2 * np.pi / 4, rel=1e-15)
    # Fig. 14b: 6 and 4 rad/s share 2 rad/s, T = pi
    assert period(resolve_parameters(alpha_t=2, Omega_t=6, alpha_n=2, Omega_n=4)) == pytest.approx(
        np.pi, rel=1e-15
    )
    # a direction without force does not enter
    assert period(resolve_parameters(alpha_n=0, Omega_t=6, Omega_n=np.sqrt(2))) == pytest.approx(
        2 * np.pi / 6, rel=1e-15
    )
    with pytest.raises(ValueError, match="no excitation"):
        period(resolve_parameters(Omega=0))
    with pytest.raises(ValueError, match="incommensurate"):
        period(resolve_parameters(Omega_t=4, Omega_n=4 * np.sqrt(2)))


HYSTERESIS = dict(
    params={"Omega": 6.0}, settings=SolverSettings(t_end=300.0), executor="serial", progress=False
)
HYSTERESIS_VB = [12.0, 14.0, 16.0]


@pytest.fixture(scope="module")
def hysteresis():
    return {
        d: sweep("Vb", HYSTERESIS_VB, cache_dir=None, continuation=d, **HYSTERESIS)
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
    from runtime.simulate import simulate

    seen = []
    real = sweep_module.simulate

    def recording(params, **kwargs):
        seen.append((params["Vb"], kwargs["y0"]))
        return real(params, **kwargs)

    monkeypatch.setattr(sweep_module, "simulate", recording)
    sweep("Vb", HYSTERESIS_VB, cache_dir=None, continuation="down", **HYSTERESIS)
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
    assert row["peak_omega1"] == again["peak_omega1"]
    assert row["n_switches"] == again["n_switches"]


def test_a_continued_sweep_is_cached_by_direction_and_start_state(
    tmp_path, hysteresis, monkeypatch
):
    from runtime.model import resolve_parameters

    up = sweep("Vb", HYSTERESIS_VB, cache_dir=tmp_path, continuation="up", **HYSTERESIS)
    assert len(list(tmp_path.glob("*.json"))) == 3
    p = resolve_parameters(Vb=12.0, Omega=6.0)
    s = HYSTERESIS["settings"]
    keys = {
        cache_key(p, "hertz_damp", s),
        cache_key(p, "hertz_damp", s, continuation="up"),
        cache_key(p, "hertz_damp", s, continuation="down"),
        cache_key(p, "hertz_damp", s, continuation="up", y0=[1.0, 0.0, 1.0, 0.0]),
    }
    assert len(keys) == 4

    def fail(*args, **kwargs):
        raise AssertionError("recomputed a cached point")

    monkeypatch.setattr(sweep_module, "run_point", fail)
    again = sweep("Vb", HYSTERESIS_VB, cache_dir=tmp_path, continuation="up", **HYSTERESIS)
    _same(again, up)
    _same(up, hysteresis["up"])
    # the other direction starts elsewhere: nothing of it is in the cache
    with pytest.raises(AssertionError, match="recomputed"):
        sweep("Vb", HYSTERESIS_VB, cache_dir=tmp_path, continuation="down", **HYSTERESIS)


def test_continuation_refuses_what_it_cannot_do():
    kw = dict(cache_dir=None, progress=False)
    with pytest.raises(ValueError, match="continuation must be None, 'up' or 'down'"):
        sweep("Vb", [1.0], executor="serial", continuation="sideways", **kw)
    with (
        cf.ThreadPoolExecutor(1) as pool,
        pytest.raises(ValueError, match="one after another.*executor must be None"),
    ):
        sweep("Vb", [1.0], executor=pool, continuation="up", **kw)
    with pytest.raises(ValueError, match="continuation at Vb = 1: no excitation"):
        sweep("Vb", [1.0], {"Omega": 0.0}, executor="serial", continuation="up", **kw)
    with pytest.raises(ValueError, match="period 1.5708 s is longer than t_end = 1 s"):
        sweep(
            "Vb",
            [1.0],
            settings=SolverSettings(t_end=1.0, dt=0.01),
            executor="serial",
            continuation="up",
            **kw,
        )


def test_a_sweep_started_on_the_periodic_response(tmp_path):
    from runtime.floquet import floquet

    settings = SolverSettings(t_end=300.0)
    kw = dict(settings=settings, executor="serial", progress=False)
    # 3: stable, 5: unstable (Floquet); 6.3: no periodic response (runtime/floquet.py)
    table = sweep("Vb", [3.0, 5.0, 6.3], start="periodic", cache_dir=tmp_path, **kw)
    assert floquet(Vb=3.0).stable is True and floquet(Vb=5.0).stable is False
    assert list(table["omega1_peak_present"]) == [False, True, False]
    assert list(table["resolved"]) == [True, True, False]
    assert table["regime"][2] == sweep_module.NO_PERIODIC_RESPONSE
    assert table["status"][2] == "no_periodic" and np.isnan(table["peak_omega1"][2])
    # the start is part of the point: the cache never serves a run from rest for it
    rest = sweep("Vb", [3.0, 5.0, 6.3], cache_dir=tmp_path, **kw)
    assert list(rest["regime"]).count(sweep_module.NO_PERIODIC_RESPONSE) == 0
    again = sweep("Vb", [3.0, 5.0, 6.3], start="periodic", cache_dir=tmp_path, **kw)
    np.testing.assert_array_equal(again["peak_Omega"], table["peak_Omega"])
    p = {"Vb": 3.0}
    assert cache_key(p, "hertz_damp", settings) != cache_key(
        p, "hertz_damp", settings, start="periodic"
    )


def test_a_periodic_start_is_refused_where_it_means_nothing():
    kw = dict(cache_dir=None, progress=False, executor="serial")
    with pytest.raises(ValueError, match="start must be one of 'rest', 'periodic'"):
        sweep("Vb", [1.0], start="equilibrium", **kw)
    with pytest.raises(ValueError, match="continued sweep.*start must be 'rest'"):
        sweep("Vb", [1.0], start="periodic", continuation="up", **kw)
