"""The axes of a basin map: the state components on them and their ranges, checked.

`AXES` names the components of the state at phase 0 that a plane of starts spans;
`axis_range` checks the ends given (finite, ordered, each within floating point for the
model), `_range` spans the attractors found where none are given.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import state_names
from ..arguments import number
from ..errors import Refused
from ..model import Model
from ..settings import fastest_rate

__all__ = ["AXES", "axis_range"]


#: The axes of the plane: the paper model's states at phase 0 (`beltmdsm.state_names`;
#: another model's basins, `beltmdsm.oscillator.basins`, span its own).
AXES = state_names.names()
#: The default plane: the first coordinate and its rate; a plane on any other state
#: needs the map that follows the normal dynamics too.
TANGENTIAL = state_names.plane()


def axis_range(model: Model, axis: str, state: str, lo: Any, hi: Any) -> tuple | None:
    """``(lo, hi)`` of axis ``axis`` ("x" or "y", the state ``state``), checked: both
    finite numbers, ``lo < hi``, or neither (None); and each end within floating point
    for the model: ``(r s)^2`` finite, ``r`` its fastest rate
    (`beltmdsm.settings.fastest_rate`), since the runs square the state (the energy,
    the spring forces). A start at ``X1 = 1e300`` was iterated for 36 s and reported
    "4 unidentified" with no reason (issue 36).

    Parameters
    ----------
    model : Model
        The model of the map.
    axis : {"x", "y"}
        The axis, for the message (``x_lo``, ``x_hi``).
    state : str
        The state component on that axis, for the message.
    lo, hi : float or None
        The ends given.

    Returns
    -------
    tuple of float or None
        ``(lo, hi)``, or None where neither is given.

    Raises
    ------
    ValueError
        Naming ``{axis}_lo``/``{axis}_hi``; a `beltmdsm.errors.Refused` where an end is
        beyond floating point.

    See Also
    --------
    beltmdsm.basin.basins.basins : Takes the ranges.

    Examples
    --------
    >>> axis_range(Model(), "x", "X1", 1e300, 1e301)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    beltmdsm.errors.Refused: x_lo/x_hi: a start at X1 = 1e+300 is beyond floating point...
    """
    if lo is None and hi is None:
        return None
    if lo is None or hi is None:
        raise ValueError(f"{axis}_lo and {axis}_hi go together: give both or neither")
    lo = number(f"{axis}_lo", lo)
    hi = number(f"{axis}_hi", hi, above=lo)
    rate = fastest_rate(model)
    for end in (lo, hi):
        with np.errstate(over="ignore"):
            energy = (np.float64(end) * rate) ** 2
        if not np.isfinite(energy):
            raise Refused(
                f"{axis}_lo/{axis}_hi: a start at {state} = {end:g} is beyond floating "
                f"point: the runs square it (the energy balance, the forces; rate "
                f"{rate:.3g} 1/s) and would be integrated as inf or NaN; choose "
                f"|{state}| < {np.sqrt(np.finfo(float).max) / rate:.3g}",
                f"{axis}_lo",
                f"{axis}_hi",
            )
    return lo, hi


def _checked(name, given):
    if given is None:
        return None
    try:
        lo, hi = (float(v) for v in given)
    except (TypeError, ValueError):
        lo, hi = np.nan, np.nan
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"{name} must be two finite numbers, low < high; got {given!r}")
    return lo, hi


def _range(name, given, found, index):
    if given is not None:
        return given
    values = np.concatenate([np.atleast_1d(a.points[:, index]) for a in found])
    values = np.append(values, [a.state[index] for a in found])
    c, w = 0.5 * (values.min() + values.max()), max(float(np.ptp(values)), 1.0)
    return c - 1.5 * w, c + 1.5 * w
