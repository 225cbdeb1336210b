"""The checks of the public functions' arguments that are not model parameters.

The command line checks every flag when it parses it (`beltmdsm.cli.flags`); the
Python functions check their arguments once, at the boundary, with these: a bad value
is one `ValueError` naming the argument, before anything is computed (issue 28: a
bool taken for a count, ``max_iter=-1`` reported "after -1 iterations", a complex
state a `TypeError` from deep inside, a dict of settings an `AttributeError`). One
check per kind of argument, used by every public function, so that a value gets the
same answer everywhere (issue 36): `count` (an integer, numpy's too; not a bool, 3.0 or
a Fraction), `number` (a finite real, Fraction and numpy scalars too; not a bool or a
string), `flag`, `reals`, `state`, `settings_of`, `executor_of`, `cache_dir_of` and
`items_of`. Model parameters are `beltmdsm.model.Model`'s; an unknown keyword is
`beltmdsm._calling`'s.
"""

from __future__ import annotations

import numbers
import os
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .model import is_real
from .settings import SolverSettings

__all__ = [
    "count",
    "number",
    "flag",
    "state",
    "reals",
    "settings_of",
    "executor_of",
    "cache_dir_of",
    "items_of",
]

#: What ``executor=`` takes, the same in every function that takes one.
EXECUTORS = (
    "None (a process pool over this machine's cores), 'serial' (in this process) "
    "or a concurrent.futures.Executor (Client.get_executor() of dask)"
)


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


def number(
    name: str,
    value: Any,
    *,
    above: float | None = None,
    at_least: float | None = None,
    below: float | None = None,
    below_name: str | None = None,
) -> float:
    """``value`` as a float: a finite real number (an int, a float, a numpy scalar, a
    `fractions.Fraction`; not a bool or a string) in the bounds given.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : object
        What the caller passed.
    above, at_least : float, optional
        A strict and a non-strict lower bound.
    below : float, optional
        A strict upper bound, named ``below_name`` in the message where given.
    below_name : str, optional
        What ``below`` is (another argument), for the message.

    Returns
    -------
    float
        ``value``.

    Raises
    ------
    ValueError
        Naming ``name``, for anything else.

    See Also
    --------
    beltmdsm.arguments.count : The check of a count.

    Examples
    --------
    >>> from fractions import Fraction
    >>> number("period", Fraction(13, 2), above=0)
    6.5
    >>> for bad in ("6", -1, float("nan"), True):
    ...     try:
    ...         number("period", bad, above=0)
    ...     except ValueError as error:
    ...         print(error)
    period must be a finite number > 0; got '6'
    period must be a finite number > 0; got -1
    period must be a finite number > 0; got nan
    period must be a finite number > 0; got True
    >>> number("t_transient", 500, at_least=0, below=100, below_name="t_end")
    Traceback (most recent call last):
    ...
    ValueError: t_transient must be a finite number >= 0 and < t_end (100); got 500
    """
    bounds = []
    if above is not None:
        bounds.append(f"> {above:g}")
    if at_least is not None:
        bounds.append(f">= {at_least:g}")
    if below is not None:
        bounds.append(f"< {below_name} ({below:g})" if below_name else f"< {below:g}")
    what = f"{name} must be a finite number" + (f" {' and '.join(bounds)}" if bounds else "")
    if not is_real(value):
        raise ValueError(f"{what}; got {value!r}")
    x = float(value)
    if (
        not np.isfinite(x)
        or (above is not None and not x > above)
        or (at_least is not None and not x >= at_least)
        or (below is not None and not x < below)
    ):
        raise ValueError(f"{what}; got {value!r}")
    return x


def executor_of(value: Any) -> Any:
    """``value`` where it names where the work runs: None (a process pool over this
    machine's cores, which the function starts and stops), ``"serial"`` (in this
    process) or an object with ``submit`` (a `concurrent.futures.Executor`).

    Parameters
    ----------
    value : object
        What the caller passed as ``executor``.

    Returns
    -------
    concurrent.futures.Executor or str or None
        ``value``.

    Raises
    ------
    ValueError
        In one line naming the choices, for anything else.

    See Also
    --------
    beltmdsm.batch.pool.process_pool : The pool that None stands for.

    Examples
    --------
    >>> executor_of("serial")
    'serial'
    >>> executor_of("proces")
    Traceback (most recent call last):
    ...
    ValueError: executor must be None (a process pool ...), 'serial' (in this process) or ...
    """
    if value is None or value == "serial" or callable(getattr(value, "submit", None)):
        return value
    raise ValueError(f"executor must be {EXECUTORS}; got {value!r}")


def cache_dir_of(value: Any) -> Any:
    """``value`` where it names a cache: ``"default"`` (the user's cache folder,
    ``$BELTMDSM_CACHE`` or the platform's), a folder (a str or a path) or None (no cache).

    Parameters
    ----------
    value : object
        What the caller passed as ``cache_dir``.

    Returns
    -------
    str or os.PathLike or None
        ``value``.

    Raises
    ------
    ValueError
        For anything else, naming its type.

    See Also
    --------
    beltmdsm.batch.cache.default_cache_dir : Where ``"default"`` is.

    Examples
    --------
    >>> cache_dir_of(123)
    Traceback (most recent call last):
    ...
    ValueError: cache_dir must be 'default', a folder (str or os.PathLike) or None; got int 123
    """
    if value is None or isinstance(value, (str, os.PathLike)):
        return value
    raise ValueError(
        "cache_dir must be 'default', a folder (str or os.PathLike) or None; "
        f"got {type(value).__name__} {value!r}"
    )


def items_of(name: str, value: Any, kind: type, what: str) -> list[Any]:
    """``value`` as a list of ``kind`` (``what`` names it for the message), or an empty
    list for None.

    Parameters
    ----------
    name : str
        The argument's name, for the message.
    value : iterable or None
        What the caller passed.
    kind : type
        The type of each item.
    what : str
        How the message names ``kind``.

    Returns
    -------
    list
        The items.

    Raises
    ------
    ValueError
        Naming ``name``, where ``value`` is not an iterable of ``kind``.

    See Also
    --------
    beltmdsm.arguments.reals : Real numbers in any shape.

    Examples
    --------
    >>> items_of("attractors", [1], str, "beltmdsm.Attractor")
    Traceback (most recent call last):
    ...
    ValueError: attractors must be a list of beltmdsm.Attractor or None; got [1]
    """
    if value is None:
        return []
    try:
        items = list(value)
    except TypeError:
        items = None
    if (
        items is None
        or isinstance(value, (str, bytes))
        or not all(isinstance(v, kind) for v in items)
    ):
        raise ValueError(f"{name} must be a list of {what} or None; got {value!r}")
    return items
