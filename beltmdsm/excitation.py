"""What a model's excitation implies: the start of a run, its period, whether there is one.

`initial_state` is the default start of a run (the unforced equilibrium of Eq. 9),
`excited_directions` the excitation's frequencies by direction, `is_autonomous`
whether there is no excitation, and `excitation_period` the common period of the
excitation (refused, naming the frequencies, where there is none).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from numpy.typing import NDArray

from .model import Model

__all__ = ["initial_state", "excited_directions", "is_autonomous", "excitation_period"]


def initial_state(model: Model) -> NDArray[np.float64]:
    """Default initial state: the unforced equilibrium of Eq. (9), at rest.

    ``X1 = mu_s g / omega1^2``, ``X2 = (g / omega2*^2)^(2/3)`` (Hertz-Damp) or
    ``g / omega2^2`` (Kelvin-Voigt), zero velocities; the excitation is switched on at
    t = 0. For ``Vb > 0`` the mass starts sliding backwards relative to the belt.

    Parameters
    ----------
    model : Model
        The model whose equilibrium is taken.

    Returns
    -------
    numpy.ndarray
        ``[X1, X1', X2, X2']``.

    See Also
    --------
    beltmdsm.simulation.equilibrium_start : The start of a run near steady sliding.

    Examples
    --------
    With the defaults ``mu_s = 0.4``, ``g = 9.81``, ``omega1 = 1``, ``X1 = 3.924``:

    >>> [round(float(v), 4) for v in initial_state(Model())]
    [3.924, 0.0, 11.5474, 0.0]
    """
    from beltmdsm.generated import unforced

    state = unforced.equilibrium(**model.arguments(unforced.equilibrium))
    return np.array([float(v) for v in state])


def excited_directions(model: Model) -> list[float]:
    """The frequencies ``Omega_t``, ``Omega_n`` of the directions whose excitation force is
    present (``alpha != 0`` and ``Omega != 0``), tangential first: the one place that
    decides whether Eq. (4) is forced.

    Parameters
    ----------
    model : Model
        The model whose excitation is read.

    Returns
    -------
    list of float
        The frequencies of the excited directions, tangential first; empty where
        Eq. (4) is autonomous.

    See Also
    --------
    beltmdsm.excitation.is_autonomous : Whether the list is empty.
    beltmdsm.excitation.excitation_period : The common period of the excited directions.

    Examples
    --------
    >>> excited_directions(Model(alpha_t=2, Omega_t=6, alpha_n=0))
    [6.0]
    >>> excited_directions(Model(alpha=0.0))
    []
    """
    p = model.params
    return [p[f"Omega_{d}"] for d in ("t", "n") if p[f"alpha_{d}"] != 0 and p[f"Omega_{d}"] != 0]


def is_autonomous(model: Model) -> bool:
    """True where no excitation is present (``alpha_t Omega_t = alpha_n Omega_n = 0``):
    Eq. (4) is then autonomous, and its periodic orbits are self-excited cycles whose
    period is found, not given (`beltmdsm.cycles.cycle`).

    Parameters
    ----------
    model : Model
        The model whose excitation is read.

    Returns
    -------
    bool
        Whether no direction is excited.

    See Also
    --------
    beltmdsm.excitation.excited_directions : The excited directions' frequencies.

    Examples
    --------
    >>> is_autonomous(Model(alpha=0.0)), is_autonomous(Model())
    (True, False)
    """
    return not excited_directions(model)


#: (`excitation_period`): a common period of more than 1000 periods of the faster
#: excitation is longer than any run of the paper.
_MAX_DENOMINATOR = 1000


def excitation_period(model: Model) -> float:
    """The common period ``T`` [s] of the excitation of Eq. (4): ``2 pi / gcd``.

    The tangential force ``alpha_t Omega_t^2 sin(Omega_t t + phase_t)`` and the normal
    one (``_n``) repeat together after ``T = 2 pi a / Omega_t = 2 pi b / Omega_n``
    where ``Omega_t / Omega_n = a / b`` in lowest terms. A direction whose force is
    zero (``alpha = 0`` or ``Omega = 0``) is absent and does not enter.

    Parameters
    ----------
    model : Model
        A forced model.

    Returns
    -------
    float
        ``T`` [s].

    Raises
    ------
    ValueError
        Without excitation (no force in either direction: no phase to take), or for
        frequencies ``Omega_t``, ``Omega_n`` whose ratio is not a fraction with a
        denominator up to 1000 within 1e-12 (incommensurate: no common period).

    See Also
    --------
    beltmdsm.excitation.excited_directions : The frequencies that enter.

    Examples
    --------
    >>> m = Model(alpha_t=2, Omega_t=6, alpha_n=2, Omega_n=4)
    >>> round(excitation_period(m), 6)
    3.141593
    """
    active = excited_directions(model)
    if not active:
        raise ValueError(
            "no excitation (alpha_t Omega_t = alpha_n Omega_n = 0): there is no "
            "excitation period to take the phase from"
        )
    if len(active) == 1 or active[0] == active[1]:
        return 2 * math.pi / active[0]
    w_t, w_n = active
    ratio = Fraction(w_t / w_n).limit_denominator(_MAX_DENOMINATOR)
    # rounding of the given frequencies only: their ratio must be the fraction
    if abs(ratio.numerator / ratio.denominator - w_t / w_n) > 1e-12 * (w_t / w_n):
        raise ValueError(
            f"Omega_t = {w_t!r} and Omega_n = {w_n!r} are incommensurate (their "
            f"ratio is no fraction a/b with b <= {_MAX_DENOMINATOR}): the "
            "excitation has no common period"
        )
    return 2 * math.pi * ratio.numerator / w_t
