"""``to_pandas()`` of the results that are tables: pandas imported when called.

pandas is no dependency of beltmdsm (``pip install beltmdsm[pandas]``); without it,
`frame` raises an `ImportError` naming it, and nothing else of the package needs it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from .state_names import columns

if TYPE_CHECKING:
    from pandas import DataFrame
else:  # pandas is optional: the annotations name its DataFrame for type checkers only
    DataFrame = Any

__all__ = ["DataFrame", "STATE_COLUMNS", "frame", "multiplier_frame"]

#: The columns of the paper model's state in a table (`beltmdsm.state_names.columns`:
#: its rates are named by their coordinates); another model's are its own.
STATE_COLUMNS = columns()


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


def multiplier_frame(multipliers: Sequence[complex], period: float) -> DataFrame:
    """One row per Floquet multiplier: ``multiplier`` (complex), ``abs``, ``angle``
    [rad] and ``rate = log|mu| / period`` [1/s] (``-inf`` for a multiplier 0, as a
    stick phase gives), in the result's order.

    Examples
    --------
    >>> multiplier_frame([0.5j, 0.0], 2.0)[["abs", "rate"]].round(4).values.tolist()
    [[0.5, -0.3466], [0.0, -inf]]
    """
    import numpy as np

    mu = np.asarray(multipliers, dtype=complex)
    with np.errstate(divide="ignore"):
        rate = np.log(np.abs(mu)) / period
    rows = {"multiplier": mu, "abs": np.abs(mu), "angle": np.angle(mu), "rate": rate}
    return frame(rows, list(rows))
