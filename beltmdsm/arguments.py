"""The checks of the public functions' arguments that are not model parameters.

The command line checks every flag when it parses it (`beltmdsm.cli.flags`); the
Python functions check their arguments once, at the boundary, with these: a bad value
is one `ValueError` naming the argument, before anything is computed (issue 28: a
bool taken for a count, ``max_iter=-1`` reported "after -1 iterations", a complex
state a `TypeError` from deep inside, a dict of settings an `AttributeError`). Model
parameters are `beltmdsm.model.Model`'s.
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .model import is_real
from .settings import SolverSettings

__all__ = ["count", "flag", "state", "reals", "settings_of"]


def count(name: str, value: Any, minimum: int, maximum: int | None = None) -> int:
    """``value`` as an int: an integer (not a bool) in ``[minimum, maximum]``.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    minimum : int
        The least value allowed.
    maximum : int, optional
        The largest value allowed; no bound where None.

    Returns
    -------
    int
        ``value``.

    Raises
    ------
    ValueError
        Naming ``name``, for a bool, a non-integer or a value out of range.

    See Also
    --------
    beltmdsm.arguments.flag : The check of a bool.

    Examples
    --------
    ``True`` is an int to Python, but no count (issue 28):

    >>> count("points", 5, 2)
    5
    >>> for bad in (True, 1, 2.0):
    ...     try:
    ...         count("points", bad, 2, 10)
    ...     except ValueError as error:
    ...         print(error)
    points must be an integer >= 2; got True
    points must be an integer in 2..10; got 1
    points must be an integer >= 2; got 2.0
    """
    if not isinstance(value, numbers.Integral) or isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer >= {minimum}; got {value!r}")
    value = int(value)
    if value < minimum or (maximum is not None and value > maximum):
        bound = f">= {minimum}" if maximum is None else f"in {minimum}..{maximum}"
        raise ValueError(f"{name} must be an integer {bound}; got {value}")
    return value


def flag(name: str, value: Any) -> bool:
    """``value`` as a bool: True or False (a number or a string is refused).

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.

    Returns
    -------
    bool
        ``value``.

    Raises
    ------
    ValueError
        Naming ``name``, for anything but True, False or a numpy bool.

    See Also
    --------
    beltmdsm.arguments.count : The check of a count.

    Examples
    --------
    >>> flag("verbose", True)
    True
    >>> flag("verbose", "no")
    Traceback (most recent call last):
    ...
    ValueError: verbose must be True or False; got 'no'
    """
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False; got {value!r}")
    return bool(value)


def reals(name: str, values: Any) -> NDArray[np.float64]:
    """``values`` as a float array: real numbers only (no bool, complex or string).

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    values : array_like
        What the caller passed.

    Returns
    -------
    numpy.ndarray
        ``values`` as floats, in their shape.

    Raises
    ------
    ValueError
        Naming ``name``, where any item is not a real number.

    See Also
    --------
    beltmdsm.arguments.state : A state vector of a given size.

    Examples
    --------
    >>> reals("Vb", [1, 2.5])
    array([1. , 2.5])
    >>> reals("Vb", [1, 2j])
    Traceback (most recent call last):
    ...
    ValueError: Vb must be real numbers; got [1, 2j]
    """
    if isinstance(values, np.ndarray):
        good = values.dtype.kind in "iuf"
    else:
        items = np.asarray(values, dtype=object).ravel()
        good = all(is_real(v) for v in items)
    if not good:
        raise ValueError(f"{name} must be real numbers; got {values!r}")
    return np.asarray(values, dtype=float)


def state(name: str, value: Any, sizes: Sequence[int], what: str) -> NDArray[np.float64]:
    """``value`` as a 1-D float array of one of ``sizes`` finite real numbers
    (``what`` says what they are, for the message).

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : array_like
        What the caller passed.
    sizes : sequence of int
        The sizes allowed.
    what : str
        What the numbers are, for the message.

    Returns
    -------
    numpy.ndarray
        ``value`` as a 1-D float array.

    Raises
    ------
    ValueError
        Naming ``name``, for a wrong size, a non-real or a non-finite number.

    See Also
    --------
    beltmdsm.arguments.reals : The check of real numbers in any shape.

    Examples
    --------
    >>> state("y0", [0, 0, 1, 0], (4,), "X1, X1', X2, X2'")
    array([0., 0., 1., 0.])
    >>> state("y0", [0, 0, float("nan"), 0], (4,), "X1, X1', X2, X2'")
    Traceback (most recent call last):
    ...
    ValueError: y0 must be 4 finite real numbers (X1, X1', X2, X2'); got [0, 0, nan, 0]
    """
    try:
        y = reals(name, value)
    except ValueError:
        y = None
    if y is None or y.ndim != 1 or y.size not in sizes or not np.all(np.isfinite(y)):
        n = " or ".join(map(str, sizes))
        raise ValueError(f"{name} must be {n} finite real numbers ({what}); got {value!r}")
    return y


def settings_of(settings: Any) -> SolverSettings:
    """``settings`` itself, or the defaults for None; anything else is refused (a
    dict: build ``SolverSettings(**it)``).

    Parameters
    ----------
    settings : SolverSettings or None
        What the caller passed.

    Returns
    -------
    SolverSettings
        ``settings``, or the defaults.

    Raises
    ------
    ValueError
        For anything else, naming its type.

    See Also
    --------
    beltmdsm.settings.SolverSettings : How a run is computed.

    Examples
    --------
    >>> settings_of(None).t_end
    1000.0
    >>> settings_of({"t_end": 5})
    Traceback (most recent call last):
    ...
    ValueError: settings must be a beltmdsm.SolverSettings ... or None; got dict
    """
    if settings is None:
        return SolverSettings()
    if not isinstance(settings, SolverSettings):
        raise ValueError(
            "settings must be a beltmdsm.SolverSettings (SolverSettings(t_end=...)) or "
            f"None; got {type(settings).__name__}"
        )
    return settings
