"""A parameter's value where it enters: a real number, finite, in its domain.

The checks that every model's parameters pass once, when the model is built
(`beltmdsm.model.Model` for the paper's, `beltmdsm.other_model` for another registered
model's): `is_real` (no flag, string or array where a number belongs), `real_number` (a
finite float, the two zeros one value) and `check_domain` (the one domain table,
``beltmdsm.generated.parameters.DOMAINS``). `beltmdsm.model` re-exports the public two.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from beltmdsm.generated.parameters import DOMAIN_RULES, DOMAINS, within

__all__ = ["is_real", "check_domain", "real_number"]


def is_real(value: object) -> bool:
    """True for a real number (int, float, numpy scalar), False for a bool or anything else.

    Parameters
    ----------
    value : object
        What a caller passed where a number belongs.

    Returns
    -------
    bool
        Whether ``value`` is a real number; ``True`` (a flag) is not one.

    See Also
    --------
    check_domain : Whether a number lies in a parameter's domain.

    Examples
    --------
    A flag is no number, although ``float(True)`` is 1.0:

    >>> is_real(2), is_real(1.5), is_real(True), is_real("2")
    (True, True, False, False)
    """
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def check_domain(name: str, value: float) -> str | None:
    """What is wrong with ``value`` for parameter ``name`` ("must be > 0"), or None.

    Parameters
    ----------
    name : str
        A parameter of Eq. (4) or of a law (``beltmdsm.model.MODEL_PARAMETERS``).
    value : float
        The value to check.

    Returns
    -------
    str or None
        The rule ``value`` breaks, worded to follow the parameter's name, or None where
        it lies in the domain.

    Raises
    ------
    KeyError
        For a name that is no parameter.

    See Also
    --------
    beltmdsm.model.Model : Checks every parameter this way when it is built.

    Examples
    --------
    The belt speed ``Vb`` may be zero but not negative:

    >>> check_domain("Vb", -1.0), check_domain("Vb", 0.0)
    ('must be >= 0', None)
    """
    domain = DOMAINS[name]
    return None if within(domain, value) else f"must be {DOMAIN_RULES[domain][2]}"


def real_number(name: str, value: object) -> float:
    """``value`` as a finite float (``-0.0`` as ``0.0``), else ValueError naming ``name``.

    Parameters
    ----------
    name : str
        The parameter, named in the message.
    value : object

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For a value that is no real number (a bool, a string, an array), NaN or infinite.

    See Also
    --------
    is_real : the test of a real number.

    Examples
    --------
    >>> real_number("Vb", 2), real_number("Vb", -0.0)
    (2.0, 0.0)
    >>> real_number("Vb", True)
    Traceback (most recent call last):
    ...
    ValueError: parameter 'Vb' must be a number; got True
    """
    # float(True) is 1.0: a flag passed where a number belongs is a mistake
    if not is_real(value):
        raise ValueError(f"parameter {name!r} must be a number; got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"parameter {name!r} must be finite; got {value!r}")
    # -0.0 + 0.0 is 0.0: the two zeros are one value, with one digest
    return value + 0.0
