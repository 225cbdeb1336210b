"""The sweep cache: keys, checks, corruption, concurrent writers (beltmdsm.batch.cache)."""

import concurrent.futures as cf
import json
from dataclasses import replace

import numpy as np
import pytest

from beltmdsm.batch import cache as cache_module
from beltmdsm.batch import sweep as sweep_module
from beltmdsm.batch.cache import cache_key, identity, read_cached
from beltmdsm.batch.row import columns
from beltmdsm.batch.sweep import sweep
from beltmdsm.model import Model
from beltmdsm.settings import SolverSettings

SHORT = SolverSettings(t_end=40.0, t_discard=10.0)
COLUMNS = [name for name, _ in columns(False)]


def _key(model, settings=SHORT, **kw):
    return cache_key(identity(model, settings, **kw))


def _sweep(cache_dir, values=(4.0,)):
    return sweep(
        None,
        "Vb",
        list(values),
        settings=SHORT,
        executor="serial",
        cache_dir=cache_dir,
        progress=False,
    )


@pytest.fixture(scope="module")
def reference():
    return _sweep(None).table


def test_the_key_depends_on_the_model_the_settings_and_what_is_asked():
    m = Model(Vb=4.0)
    k = _key(m)
    # equal settings from Python and from the command line share a key (issue 17)
    assert k == _key(Model(Vb=4), SolverSettings(t_end=40, t_discard=10))
    assert k != _key(Model(Vb=4.5))
    assert k != _key(m.replace(contact="kelvin_voigt"))
    assert k != _key(m.replace(tension="clipped"))
    assert k != _key(m, replace(SHORT, rtol=1e-9))
    assert k != _key(m, modulation=True)
    assert k != _key(m, start="periodic")


def _cache_file(tmp_path, vb=4.0):
    return tmp_path / f"{_key(Model(Vb=vb))}.json"


def _stored_is_valid(path):
    data = json.loads(path.read_text())
    ident = identity(Model(Vb=data["params"]["Vb"]), SHORT)
    row, problem = read_cached(path, ident, COLUMNS)
    return row is not None and problem is None


CORRUPTIONS = {
    "not valid JSON": lambda text: text[: len(text) // 2].encode(),
    "not UTF-8 text": lambda text: bytes(range(128, 256)) * 4,
    "missing checksum": lambda text: json.dumps(
        {k: v for k, v in json.loads(text).items() if k != "checksum"}
    ).encode(),
    "does not match its checksum": lambda text: text.replace(
        '"n_switches": ', '"n_switches": 1'
    ).encode(),
    "another point's parameters": lambda text: text.replace('"Vb": 4.0', '"Vb": 4.5').encode(),
    "not its name's": lambda text: json.dumps({**json.loads(text), "key": "0" * 64}).encode(),
    "lacks": lambda text: json.dumps(_drop_column(json.loads(text), "peak_omega1")).encode(),
}


def _drop_column(data, name):
    del data["row"][name]
    data["checksum"] = cache_module._checksum(data["row"])
    return data


@pytest.mark.parametrize("what", list(CORRUPTIONS))
def test_a_corrupted_cache_file_is_reported_by_name_recomputed_and_rewritten(
    tmp_path, reference, what
):
    _sweep(tmp_path)
    path = _cache_file(tmp_path)
    good = path.read_text()
    path.write_bytes(CORRUPTIONS[what](good))
    with pytest.warns(cache_module.CacheWarning, match=f"{path.name}.*{what}"):
        result = _sweep(tmp_path)
    np.testing.assert_array_equal(result.table["n_switches"], reference["n_switches"])
    assert result.n_cached == 0 and [p.path for p in result.problems] == [str(path)]
    assert json.loads(path.read_text())["row"]["n_switches"] == int(reference["n_switches"][0])
    assert _stored_is_valid(path)


def test_an_unreadable_cache_file_is_recomputed(tmp_path, reference):
    _sweep(tmp_path)
    path = _cache_file(tmp_path)
    path.unlink()
    path.mkdir()  # reading it fails with an OSError (a folder), not a missing file
    row, problem = read_cached(path, identity(Model(Vb=4.0), SHORT), COLUMNS)
    assert row is None and problem.startswith("cannot be read")


def test_a_valid_cache_file_passes_its_checks(tmp_path):
    _sweep(tmp_path)
    assert _stored_is_valid(_cache_file(tmp_path))
    assert read_cached(tmp_path / "absent.json", {}, COLUMNS) == (None, None)


def _sweep_into(cache_dir, values):
    return _sweep(cache_dir, values).table


def test_concurrent_writers_into_one_cache_leave_valid_files(tmp_path):
    """Two processes and two threads write the same points at once: every file is whole."""
    import threading

    values = [2.0, 4.0, 12.0]
    with cf.ProcessPoolExecutor(max_workers=2) as pool:
        tables = list(pool.map(_sweep_into, [tmp_path] * 2, [values] * 2))
    threads = [threading.Thread(target=_sweep_into, args=(tmp_path, values)) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    files = sorted(tmp_path.glob("*.json"))
    assert len(files) == len(values)
    assert all(_stored_is_valid(f) for f in files)
    assert not list(tmp_path.glob(".*.tmp"))  # every temporary file was renamed
    np.testing.assert_array_equal(tables[0]["n_switches"], tables[1]["n_switches"])


def test_temporary_names_are_unique_per_write(tmp_path, monkeypatch):
    """A UUID, not a process id: workers on two hosts can share a pid."""
    seen = []
    real = cache_module.os.replace

    def spy(src, dst):
        seen.append(str(src))
        real(src, dst)

    monkeypatch.setattr(cache_module.os, "replace", spy)
    for _ in range(2):
        cache_module.write_cached(tmp_path / "x.json", {}, {})
    assert len(set(seen)) == 2 and all(".x.json." in s for s in seen)


def test_the_key_changes_with_the_code_and_the_version(tmp_path, monkeypatch):
    m = Model(Vb=4.0)
    source = tmp_path / "integrator.py"
    source.write_text("x = 1\n")
    monkeypatch.setattr(cache_module, "_ROOT", tmp_path)
    monkeypatch.setattr(cache_module, "code_files", lambda: [source])
    cache_module.code_hash.cache_clear()
    try:
        before = _key(m)
        assert _key(m) == before
        source.write_text("x = 2\n")
        cache_module.code_hash.cache_clear()
        after = _key(m)
        assert after != before
        monkeypatch.setattr(cache_module, "package_version", lambda: "99.0")
        assert _key(m) != after
    finally:
        monkeypatch.undo()
        cache_module.code_hash.cache_clear()


def test_the_code_hash_covers_what_a_row_imports_and_not_the_rest():
    root = cache_module._ROOT
    names = {f.relative_to(root).as_posix() for f in cache_module.code_files()}
    assert {
        "generated/_support.py",
        "generated/hybrid.py",
        "beltmdsm/simulation.py",
        "beltmdsm/integrate/superposition.py",
        "beltmdsm/integrate/_dop853.py",
        "beltmdsm/run/summary.py",
        # the summary's resolution and tolerance bounds decide a row's columns too
        "beltmdsm/run/resolution.py",
        "beltmdsm/run/tolerances.py",
        "beltmdsm/batch/row.py",
        # issue 28: they decide a row's `resolved` and its periodic start, and a hand
        # list had left them out
        "beltmdsm/periodic/base.py",
        "beltmdsm/periodic/closed_form.py",
        "beltmdsm/periodic/general_map.py",
        "beltmdsm/periodic/newton.py",
        "beltmdsm/periodic/shooting.py",
        "beltmdsm/starts/forced.py",
        "beltmdsm/periodic/variational.py",
        "beltmdsm/periodic/locked.py",
    } <= names
    # the command line, the reports and the sweep's own orchestration change no number
    for path in names:
        assert not path.startswith(("beltmdsm/cli/", "beltmdsm/paper_reports/")), path
    assert "beltmdsm/batch/sweep.py" not in names
    assert "beltmdsm/continuation/band.py" not in names
    assert len(cache_module.code_hash()) == 64


def _copy_tree(tmp_path):
    import shutil

    root = tmp_path / "tree"
    for package in ("beltmdsm", "generated"):  # a checkout: generated/ beside beltmdsm/
        shutil.copytree(
            cache_module._ROOT / package, root / package, ignore=shutil.ignore_patterns("*.pyc")
        )
    return root


def test_changing_any_imported_source_changes_the_code_hash(tmp_path, monkeypatch):
    # issue 28: the hash must follow every module a row's computation imports
    root = _copy_tree(tmp_path)
    monkeypatch.setattr(cache_module, "_ROOT", root)
    cache_module.code_hash.cache_clear()
    try:
        files = cache_module.code_files()
        assert [f.relative_to(root) for f in files] == [
            f.relative_to(cache_module._ROOT) for f in cache_module.code_files()
        ]
        before = cache_module.code_hash()
        for path in files:
            data = path.read_bytes()
            path.write_bytes(data + b"\n# changed\n")
            cache_module.code_hash.cache_clear()
            assert cache_module.code_hash() != before, path
            path.write_bytes(data)
        cache_module.code_hash.cache_clear()
        assert cache_module.code_hash() == before
        # a module a row starts to import (here by a lazy import inside a function)
        # joins the hash; the hash then follows its edits
        band = root / "beltmdsm/continuation/band.py"
        row = root / "beltmdsm/batch/row.py"
        row.write_text(row.read_text() + "\n\ndef _later():\n    from ..continuation import band\n")
        assert band in cache_module.code_files()
        cache_module.code_hash.cache_clear()
        with_band = cache_module.code_hash()
        band.write_text(band.read_text() + "\n# changed\n")
        cache_module.code_hash.cache_clear()
        assert cache_module.code_hash() != with_band
    finally:
        monkeypatch.undo()
        cache_module.code_hash.cache_clear()


def test_a_changed_period_map_serves_no_stale_row(tmp_path, monkeypatch):
    # issue 28: sweep(None, "Vb", [3, 5], start="periodic", cache_dir=D), then NEWTON_TOL =
    # 1e-300 in newton.py: the rerun served 2 cached sliding rows where the new code
    # finds no periodic response
    from beltmdsm.periodic import newton

    settings = SolverSettings(t_end=20.0)

    def run(cache_dir):
        return sweep(
            None,
            "Vb",
            [3.0, 5.0],
            start="periodic",
            settings=settings,
            executor="serial",
            cache_dir=cache_dir,
            progress=False,
        )

    first = run(tmp_path / "D")
    assert list(first.table["status"]) == ["done", "done"]
    # the edit, on disk (a copy of the tree) and in the running code
    root = _copy_tree(tmp_path)
    source = root / "beltmdsm/periodic/newton.py"
    text = source.read_text()
    assert "\nNEWTON_TOL = 1e-11\n" in text
    source.write_text(text.replace("\nNEWTON_TOL = 1e-11\n", "\nNEWTON_TOL = 1e-300\n"))
    monkeypatch.setattr(cache_module, "_ROOT", root)
    monkeypatch.setattr(newton, "NEWTON_TOL", 1e-300)
    cache_module.code_hash.cache_clear()
    try:
        fresh = run(None)
        rerun = run(tmp_path / "D")
    finally:
        monkeypatch.undo()
        cache_module.code_hash.cache_clear()
    # the new code answers otherwise (else the test would prove nothing), and the
    # rerun with the cache answers as the new code does
    assert list(fresh.table["status"]) != list(first.table["status"])
    assert rerun.n_cached == 0
    assert list(rerun.table["status"]) == list(fresh.table["status"])


def test_package_version_falls_back_to_pyproject(monkeypatch):
    from importlib import metadata

    tomllib = pytest.importorskip("tomllib")

    def missing(name):
        raise metadata.PackageNotFoundError(name)

    monkeypatch.setattr(metadata, "version", missing)
    cache_module.package_version.cache_clear()
    try:
        with open(cache_module._ROOT / "pyproject.toml", "rb") as fh:
            expected = tomllib.load(fh)["project"]["version"]
        assert cache_module.package_version() == expected
    finally:
        monkeypatch.undo()
        cache_module.package_version.cache_clear()


def test_a_folder_that_cannot_be_written_is_refused_by_name(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(ValueError, match="cannot be written"):
        cache_module.writable_folder(blocker / "sub")
    assert cache_module.writable_folder(tmp_path / "new") == tmp_path / "new"


def test_a_cache_problem_is_kept_in_the_sweep(tmp_path):
    # (sweep_module re-exports the warning class the callers filter on)
    assert sweep_module.CacheWarning is cache_module.CacheWarning
