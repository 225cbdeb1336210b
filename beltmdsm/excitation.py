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

__all__ = [
    "initial_state",
    "excited_directions",
    "is_autonomous",
    "excitation_period",
    "START_PERTURBATION",
    "equilibrium_start",
]

#: How far a run without excitation is moved off steady sliding where that is unstable
#: (the max-norm of the move along the unstable eigenvector of
#: `beltmdsm.generated.unforced.jacobian_at_equilibrium`, in the state's units, m and m/s).
#: Started exactly on it, a run stays there up to rounding (a cubic law at Vb = 0.48
#: for 20 000 s, called "continuous_sliding, omega1 peak absent", issue 29): 1e-6 is ten
#: orders above the rounding of a state of order 1-10, and a millionth of the cycle
#: it grows into. The summary states it (``start_perturbation``).
START_PERTURBATION = 1e-6


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
    beltmdsm.excitation.equilibrium_start : The start of a run near steady sliding.

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
    period is found, not given (`beltmdsm.periodic.cycle`).

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


def equilibrium_start(model: Model) -> tuple[NDArray[np.float64] | None, float]:
    """``(y0, size)``: where a run from the unforced equilibrium starts, and how far off.

    Without excitation, at ``Vb > 0`` and where steady sliding is unstable (an
    eigenvalue of `beltmdsm.generated.unforced.jacobian_at_equilibrium` with a positive real
    part), the equilibrium moved by `START_PERTURBATION` along the real part of that
    eigenvalue's eigenvector (its X1' component made positive); else ``(None, 0.0)``:
    the equilibrium itself (`beltmdsm.excitation.initial_state`).

    Parameters
    ----------
    model : Model
        The model to run.

    Returns
    -------
    y0 : numpy.ndarray or None
        The start ``[X1, X1', X2, X2']``, or None for the equilibrium itself.
    size : float
        How far ``y0`` is from the equilibrium (its largest component), 0.0 for None.

    See Also
    --------
    beltmdsm.excitation.initial_state : The unforced equilibrium.
    beltmdsm.excitation.START_PERTURBATION : The size of the step off it.

    Examples
    --------
    Under Stribeck friction at ``Vb = 1.5`` steady sliding is unstable (eigenvalues
    ``0.0642 +- 0.9979 i``), so a run starts 1e-6 off it; under Coulomb friction it is
    stable, and a run starts on it:

    >>> from beltmdsm import Model
    >>> m = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    >>> y0, size = equilibrium_start(m)
    >>> size, [round(float(v), 4) for v in (y0 - initial_state(m)) / size]
    (1e-06, [1.0, 0.0642, 0.0, 0.0])
    >>> equilibrium_start(Model(friction="coulomb", alpha=0.0, Vb=1.5))
    (None, 0.0)
    """
    from beltmdsm.generated import unforced

    p = model.params
    excited = any(p[f"alpha_{d}"] != 0 and p[f"Omega_{d}"] != 0 for d in ("t", "n"))
    if excited or not p["Vb"] > 0:
        return None, 0.0
    fn = unforced.jacobian_at_equilibrium
    lam, vec = np.linalg.eig(np.asarray(fn(**model.arguments(fn)), dtype=float))
    k = int(np.argmax(lam.real))
    if not lam[k].real > 0:
        return None, 0.0
    v = vec[:, k].real if np.max(np.abs(vec[:, k].real)) > 0 else vec[:, k].imag
    v = v / np.max(np.abs(v))
    if v[1] < 0 or (v[1] == 0 and v[0] < 0):
        v = -v
    return initial_state(model) + START_PERTURBATION * v, START_PERTURBATION
