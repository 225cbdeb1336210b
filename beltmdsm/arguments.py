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
    """``value`` as an int: an integer (not a bool) in ``[minimum, maximum]``."""
    if not isinstance(value, numbers.Integral) or isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer >= {minimum}; got {value!r}")
    value = int(value)
    if value < minimum or (maximum is not None and value > maximum):
        bound = f">= {minimum}" if maximum is None else f"in {minimum}..{maximum}"
        raise ValueError(f"{name} must be an integer {bound}; got {value}")
    return value


def flag(name: str, value: Any) -> bool:
    """``value`` as a bool: True or False (a number or a string is refused)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False; got {value!r}")
    return bool(value)


def reals(name: str, values: Any) -> NDArray[np.float64]:
    """``values`` as a float array: real numbers only (no bool, complex or string)."""
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
    (``what`` says what they are, for the message)."""
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
    dict: build ``SolverSettings(**it)``)."""
    if settings is None:
        return SolverSettings()
    if not isinstance(settings, SolverSettings):
        raise ValueError(
            "settings must be a beltmdsm.SolverSettings (SolverSettings(t_end=...)) or "
            f"None; got {type(settings).__name__}"
        )
    return settings
