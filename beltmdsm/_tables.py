"""``to_pandas()`` of the results that are tables: pandas imported when called.

pandas is no dependency of beltmdsm (``pip install beltmdsm[pandas]``); without it,
`frame` raises an `ImportError` naming it, and nothing else of the package needs it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pandas import DataFrame
else:  # pandas is optional: the annotations name its DataFrame for type checkers only
    DataFrame = Any

__all__ = ["DataFrame", "frame"]


def frame(
    rows: Sequence[Mapping[str, Any]] | Any, columns: Sequence[str] | None = None
) -> DataFrame:
    """A `pandas.DataFrame` of ``rows`` (dicts, or a numpy structured array).

    Raises
    ------
    ImportError
        Naming pandas, where it is not installed.
    """
    try:
        import pandas
    except ImportError as err:
        raise ImportError(
            "to_pandas() needs pandas, which beltmdsm does not install: "
            "pip install pandas (or beltmdsm[pandas])"
        ) from err
    return pandas.DataFrame(rows, columns=list(columns) if columns is not None else None)
