"""A sweep's table: its rows stacked, as records, as CSV, and what it says.

`to_table` stacks the `beltmdsm.batch.row.Row.record` of each point into a numpy
structured array (the swept parameter first, then the row's columns); `records` gives
its rows back as plain dicts (`beltmdsm.batch.sweep.Sweep.to_pandas`; ``sweep --json``
writes the rows themselves, `beltmdsm.batch.row.Row.json_row`),
`table_to_csv` and `table_from_csv` the CSV of ``sweep --out``. `omega1_peak_ranges`
and `unresolved_values` read where the omega1 peak is present and where a run could
not tell; they take the notebooks' dicts of columns too.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import intervals
from .row import Row, columns

__all__ = [
    "to_table",
    "records",
    "table_to_csv",
    "table_from_csv",
    "resolved_mask",
    "omega1_peak_ranges",
    "unresolved_values",
]


def to_table(
    param: str, values: ArrayLike, rows: Sequence[Row], modulation: bool = False
) -> NDArray[np.void]:
    """The sweep's table: one record per row, ``param`` (its ``values``) first, then
    `columns` (a modulation column NaN for a row without it).

    Parameters
    ----------
    param : str
        The swept parameter.
    values : array_like
        Its value at each row.
    rows : sequence of Row
    modulation : bool
        Whether the table holds the modulation columns.

    Returns
    -------
    numpy structured array

    See Also
    --------
    records : the table's rows as dicts.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> from beltmdsm.batch.row import failed_row
    >>> short = SolverSettings(t_end=40.0, t_discard=10.0)
    >>> failed = failed_row(Model(), short, False, RuntimeError("no"))
    >>> table = to_table("Vb", [4.0], [failed])
    >>> table.dtype.names[:3], table["status"].tolist()
    (('Vb', 'regime', 'peak_omega1'), ['failed'])
    """
    cols = ((param, "f8"),) + columns(modulation)
    out = np.zeros(len(rows), dtype=list(cols))
    for i, (value, row) in enumerate(zip(values, rows)):
        out[i] = (value, *row.record(modulation))
    return out


def records(table: NDArray[np.void]) -> list[dict[str, Any]]:
    """The table's rows as plain dicts by column (the rows of `Sweep.to_pandas`).

    Parameters
    ----------
    table : numpy structured array
        A sweep's table (`to_table`).

    Returns
    -------
    list of dict
        Plain Python values by column, in the table's order.

    See Also
    --------
    to_table : the table.

    Examples
    --------
    >>> from beltmdsm import Model, SolverSettings
    >>> from beltmdsm.batch.row import failed_row
    >>> short = SolverSettings(t_end=40.0, t_discard=10.0)
    >>> table = to_table("Vb", [4.0], [failed_row(Model(), short, False, RuntimeError("no"))])
    >>> (row,) = records(table)
    >>> row["Vb"], row["status"], row["error"]
    (4.0, 'failed', 'RuntimeError: no')
    """
    return [dict(zip(table.dtype.names, r.tolist())) for r in table]


def table_to_csv(table: NDArray[np.void], path: os.PathLike | str) -> None:
    """Write a sweep table as CSV with a header line.

    Parameters
    ----------
    table : numpy structured array
        A sweep's table.
    path : path
        The file written.

    See Also
    --------
    table_from_csv : reads it back.

    Examples
    --------
    >>> import os, tempfile
    >>> from beltmdsm import Model, SolverSettings
    >>> from beltmdsm.batch.row import failed_row
    >>> short = SolverSettings(t_end=40.0, t_discard=10.0)
    >>> failed = failed_row(Model(), short, False, RuntimeError("no"))
    >>> table = to_table("Vb", [4.0, 5.0], [failed, failed])
    >>> path = os.path.join(tempfile.mkdtemp(), "sweep.csv")
    >>> table_to_csv(table, path)
    >>> open(path).readline().split(",")[:3]
    ['Vb', 'regime', 'peak_omega1']
    >>> back = table_from_csv(path)
    >>> back.dtype.names == table.dtype.names, back["Vb"].tolist(), back["status"].tolist()
    (True, [4.0, 5.0], ['failed', 'failed'])
    """
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(table.dtype.names)
        for row in table:
            w.writerow([repr(float(x)) if isinstance(x, np.floating) else x for x in row.tolist()])


def table_from_csv(path: os.PathLike | str) -> NDArray[np.void]:
    """Read a table written by `table_to_csv` back into a structured array.

    Parameters
    ----------
    path : path
        A file `table_to_csv` wrote.

    Returns
    -------
    numpy structured array
        The columns by name, their types read from the text.

    See Also
    --------
    table_to_csv : writes it (its Examples read one back).
    """
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")


def resolved_mask(
    table: NDArray[np.void] | dict[str, Any], param: str | None = None
) -> NDArray[np.bool_]:
    """The ``resolved`` column of a sweep table; all True for a table without one.

    Parameters
    ----------
    table : structured array or dict of arrays
        A sweep's table (`Sweep.table`) or a dict of columns (the notebooks' scans).
    param : str, optional
        A column whose length counts the points of a dict without ``resolved``.

    Returns
    -------
    ndarray of bool

    See Also
    --------
    unresolved_values : the values where it is False.

    Examples
    --------
    >>> import numpy as np
    >>> table = np.zeros(4, dtype=[("Vb", "f8"), ("omega1_peak_present", "?"), ("resolved", "?")])
    >>> table["Vb"] = [1.0, 2.0, 3.0, 4.0]
    >>> table["omega1_peak_present"] = [False, True, True, False]
    >>> table["resolved"] = [True, True, True, False]
    >>> resolved_mask(table).tolist()
    [True, True, True, False]
    >>> resolved_mask({"Vb": [1.0, 2.0]}, "Vb").tolist()
    [True, True]
    """
    names = (
        table.keys()
        if isinstance(table, dict)
        else getattr(getattr(table, "dtype", None), "names", None) or ()
    )
    if "resolved" in names:
        return np.asarray(table["resolved"], dtype=bool)
    n = len(table[param]) if isinstance(table, dict) else len(table)
    return np.ones(n, dtype=bool)


def omega1_peak_ranges(
    table: NDArray[np.void] | dict[str, Any], param: str = "Vb"
) -> list[tuple[float, float]]:
    """Contiguous ranges of ``param`` where the omega1 peak is present: [(lo, hi), ...].

    `beltmdsm.intervals.runs` of ``omega1_peak_present`` at resolved points. An
    unresolved point (``resolved`` False: the run could not tell) is treated like
    an excluded point of the validation: it is not a point with the peak, so it
    ends a range, and it is not a point without it either; `unresolved_values`
    lists them, so that a reader never takes the gap for "no peak".

    Parameters
    ----------
    table : structured array or dict of arrays
        A sweep's table, ascending in ``param``.
    param : str
        The swept parameter.

    Returns
    -------
    list of (float, float)

    See Also
    --------
    beltmdsm.batch.sweep.Sweep.omega1_peak_ranges : the same, of a sweep.

    Examples
    --------
    >>> import numpy as np
    >>> table = np.zeros(4, dtype=[("Vb", "f8"), ("omega1_peak_present", "?"), ("resolved", "?")])
    >>> table["Vb"] = [1.0, 2.0, 3.0, 4.0]
    >>> table["omega1_peak_present"] = [False, True, True, False]
    >>> table["resolved"] = [True, True, True, False]
    >>> omega1_peak_ranges(table)
    [(2.0, 3.0)]
    """
    present = np.asarray(table["omega1_peak_present"], dtype=bool) & resolved_mask(table, param)
    return intervals.runs(table[param], present)


def unresolved_values(table: NDArray[np.void] | dict[str, Any], param: str = "Vb") -> list[float]:
    """Values of ``param`` whose run could not tell the omega1 peak (ascending).

    Parameters
    ----------
    table : structured array or dict of arrays
        A sweep's table.
    param : str
        The swept parameter.

    Returns
    -------
    list of float

    See Also
    --------
    resolved_mask : the column it reads.

    Examples
    --------
    >>> import numpy as np
    >>> table = np.zeros(4, dtype=[("Vb", "f8"), ("omega1_peak_present", "?"), ("resolved", "?")])
    >>> table["Vb"] = [1.0, 2.0, 3.0, 4.0]
    >>> table["omega1_peak_present"] = [False, True, True, False]
    >>> table["resolved"] = [True, True, True, False]
    >>> unresolved_values(table)
    [4.0]
    """
    return sorted(float(v) for v in np.asarray(table[param])[~resolved_mask(table, param)])
