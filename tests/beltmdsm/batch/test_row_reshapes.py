"""A sweep row goes from its run to the table and to JSON in two reshapes (issue 38, item 5).

Before: ``Summary`` -> `Row` -> dict (``Row.as_dict``) -> numpy record -> list of dicts
(``records``) -> ``Sweep.as_dict`` -> ``jsonable``. Now: ``Summary`` -> `Row`, then `Row`
-> record (`Row.record`, the table) or `Row` -> JSON row (`Row.json_row`). The
references here are the old path, written out: the JSON and the CSV it gave, byte for
byte, for the same rows (a run, a failed point with NaN columns, the modulation
columns computed or NaN).
"""

import json
import subprocess
import sys

import numpy as np
import pytest

from beltmdsm import Model, SolverSettings, sweep
from beltmdsm.batch import table as table_module
from beltmdsm.batch.row import Row, columns, failed_row
from beltmdsm.batch.sweep import Sweep
from beltmdsm.cli.text.common import jsonable

SHORT = SolverSettings(t_end=40.0, t_discard=10.0)


def _old_table(param, values, rows, modulation):
    """The table as the old `to_table` built it: through each row's dict."""
    cols = ((param, "f8"),) + columns(modulation)
    out = np.zeros(len(rows), dtype=list(cols))
    for i, (value, row) in enumerate(zip(values, rows)):
        data = row.as_dict()
        out[i] = (value, *(data.get(name, np.nan) for name, _ in cols[1:]))
    return out


def _old_json(result):
    """``sweep --json`` as the old path wrote it: the table's records, then jsonable."""
    out = result.as_dict()
    out["rows"] = table_module.records(result.table)
    return json.dumps(jsonable(out))


@pytest.fixture(scope="module", params=[False, True], ids=["plain", "modulation"])
def mixed(request):
    """A sweep of two runs, with a failed point (NaN columns) put in its middle."""
    modulation = request.param
    result = sweep(
        None, "Vb", [1.0, 4.0], settings=SHORT, executor="serial", cache_dir=None, progress=False,
        modulation=modulation,
    )  # fmt: skip
    failed = failed_row(Model(Vb=2.0), SHORT, modulation, RuntimeError("stopped, at t = 3 s"))
    rows = [result.rows[0], failed, result.rows[1]]
    values = [1.0, 2.0, 4.0]
    table = table_module.to_table("Vb", values, rows, modulation)
    return Sweep("Vb", result.model, SHORT, table, rows=rows), values, modulation


def test_the_json_is_byte_for_byte_the_old_paths(mixed):
    result, _, _ = mixed
    new = json.dumps(jsonable(result.as_dict()))
    assert new == _old_json(result)
    # the failed point's NaN columns are null in the JSON, and the rows need no jsonable
    rows = result.as_dict()["rows"]
    assert rows[1]["status"] == "failed" and rows[1]["peak_omega1"] is None
    assert jsonable(rows) == rows


def test_the_table_and_its_csv_are_byte_for_byte_the_old_paths(mixed, tmp_path):
    result, values, modulation = mixed
    old = _old_table("Vb", values, result.rows, modulation)
    assert old.dtype == result.table.dtype
    table_module.table_to_csv(old, tmp_path / "old.csv")
    table_module.table_to_csv(result.table, tmp_path / "new.csv")
    assert (tmp_path / "new.csv").read_bytes() == (tmp_path / "old.csv").read_bytes()


def test_the_table_and_the_json_are_one_step_from_the_rows(mixed, monkeypatch):
    """The table does not go through the cache's dict, nor the JSON through the table."""
    result, values, modulation = mixed
    expected = json.dumps(jsonable(result.as_dict()))

    def refused(*args, **kwargs):
        raise AssertionError("an extra reshape")

    monkeypatch.setattr(Row, "as_dict", refused)
    monkeypatch.setattr(table_module, "records", refused)
    table = table_module.to_table("Vb", values, result.rows, modulation)
    assert table.tobytes() == result.table.tobytes()
    assert json.dumps(jsonable(result.as_dict())) == expected


def test_a_sweep_without_its_rows_says_so():
    result = sweep(
        None, "Vb", [4.0], settings=SHORT, executor="serial", cache_dir=None, progress=False
    )
    bare = Sweep("Vb", result.model, SHORT, result.table)
    with pytest.raises(ValueError, match="rows for 1 records"):
        bare.as_dict()


def test_the_cache_file_is_read_back_as_the_row(tmp_path):
    """The cache's format is unchanged (``Row.as_dict``, NaN as NaN): a row read back
    is the row, and the second sweep's JSON is the first's."""
    kw = dict(settings=SHORT, executor="serial", cache_dir=tmp_path, progress=False)
    first = sweep(None, "Vb", [4.0], modulation=True, **kw)
    again = sweep(None, "Vb", [4.0], modulation=True, **kw)
    assert again.n_cached == 1 and again.rows == first.rows
    (path,) = tmp_path.glob("*.json")
    assert json.loads(path.read_text())["row"] == first.rows[0].as_dict()
    same = {k: v for k, v in again.as_dict().items() if k != "n_cached"}
    assert same == {k: v for k, v in first.as_dict().items() if k != "n_cached"}


def test_the_command_lines_json_and_csv_hold_the_same_rows(tmp_path):
    """``sweep --json`` (rows from the `Row`) and ``sweep --out`` (the table's CSV)."""
    args = [sys.executable, "-m", "beltmdsm", "sweep", "--param", "Vb", "--values", "3", "4",
            "--t-end", "40", "--t-discard", "10", "--jobs", "1", "--no-cache",
            "--no-progress"]  # fmt: skip
    done = subprocess.run([*args, "--json"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    rows = json.loads(done.stdout)["rows"]
    done = subprocess.run(
        [*args, "--out", str(tmp_path / "s.csv")], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    back = jsonable(table_module.records(table_module.table_from_csv(tmp_path / "s.csv")))

    def computed(row):  # two runs: their wall times differ; an empty CSV field reads as False
        return {k: v for k, v in row.items() if k not in ("wall_s", "error")}

    assert [computed(r) for r in back] == [computed(r) for r in rows] and len(rows) == 2
    assert list(back[0]) == list(rows[0])
