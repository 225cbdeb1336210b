"""What a run's tolerances can tell: the noise floor of its spectrum, the bound of its
energy residual.

A peak of the spectrum is compared with the largest amplitude that the integration
error and rounding can put into the windowed spectrum (`noise_floor`), never with
noise alone, and an energy balance that does not close within the bound of its
tolerances (`energy_bound`) marks the run (`beltmdsm.run.summary.Summary`'s
``energy_ok`` and ``warnings``).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "NOISE_GLOBAL_FACTOR",
    "ENERGY_RESIDUAL_FACTOR",
    "ENERGY_RESIDUAL_FLOOR",
    "ENERGY_RESIDUAL_MAX",
    "noise_floor",
    "energy_bound",
]


#: How far the error of the sampled velocity in the steady window exceeds the local
#: error bound of one step (`noise_floor`): measured against runs at rtol = atol =
#: 1e-12, the largest error of X1' in the window was at most 6.1 times
#: ``2 (atol + rtol max|y|)`` (base set at Vb = 1, 4, 10; Omega = 10 at Vb = 7;
#: omega1 = 12 at Vb = 0.5; rtol = atol from 1e-4 to 1e-10), rounded up to 8.
NOISE_GLOBAL_FACTOR = 8.0


def noise_floor(rtol: float, atol: float, y: NDArray[np.float64], v: NDArray[np.float64]) -> float:
    """The largest amplitude that integration error and rounding can put into the spectrum.

    An error ``e`` of the samples with ``|e| <= E`` changes the windowed amplitude
    ``2 |sum w (x - mean x) exp(i omega t)| / sum w`` by at most ``4 E`` at every
    frequency. DOP853 keeps the local error of each of the four state components
    below ``2 (atol + rtol |y|)`` (its error norm is the RMS over the components);
    over the run the error of X1' grows to at most `NOISE_GLOBAL_FACTOR` times that
    (measured). Rounding in the transform's sum of ``N`` terms adds at most
    ``2 N eps max|v|``.

    Parameters
    ----------
    rtol, atol : float
        The run's tolerances.
    y : ndarray (4, n)
        The state in the steady window.
    v : ndarray (n,)
        The sampled X1' in the steady window.

    Returns
    -------
    float
        ``4 NOISE_GLOBAL_FACTOR 2 (atol + rtol max|y|) + 2 N eps max|v|`` [m/s]; NaN
        for no samples.

    See Also
    --------
    energy_bound : the other bound a run's tolerances set.

    Examples
    --------
    A state of size 1 at rtol = atol = 1e-10: ``4 x 8 x 2 (1e-10 + 1e-10)``, and the
    rounding of 1000 samples:

    >>> import numpy as np
    >>> v = np.sin(np.linspace(0.0, 20.0, 1000))
    >>> y = np.vstack([v, v, v, v])
    >>> f"{noise_floor(1e-10, 1e-10, y, v):.4g}"
    '1.28e-08'
    """
    if v.size == 0:
        return float("nan")
    local = 2 * (atol + rtol * float(np.max(np.abs(y))))
    rounding = 2 * v.size * np.finfo(float).eps * float(np.max(np.abs(v)))
    return float(4 * NOISE_GLOBAL_FACTOR * local + rounding)


#: The energy residual per unit tolerance that a run may leave (`energy_bound`):
#: measured at most 5.2 x max(rtol, atol) over the 16 cases of
#: `beltmdsm.paper_reports.validation.CASES` at Vb = 0.5, 4, 10 m/s, both solvers, both
#: tension laws, rtol = atol from 1e-3 to 1e-10 (960 runs of 300 s), but for the
#: one below the floor; rounded up to 64.
ENERGY_RESIDUAL_FACTOR = 64.0


#: The residual that a run at any tolerance may leave: where the contact is lost
#: under the clipped law (omega2 = 1.5) the residual shrinks only slowly with the
#: tolerance (4.2e-9 at rtol = atol = 1e-10 in the measurement above).
ENERGY_RESIDUAL_FLOOR = 1e-8


#: The largest residual of a trusted run, whatever its tolerances: the energy balance
#: of Sect. 3 closes to within 1e-4 of the total work. Looser runs of the base set
#: (rtol 1e-3 to 0.1) had residuals from 5e-6 to 1 and moved the omega1 peak by up
#: to 48 % and the minimum normal force from -16.4 to -7.7e4 m/s^2.
ENERGY_RESIDUAL_MAX = 1e-4


def energy_bound(
    rtol: float, atol: float, energy_level: float = 0.0, work_total: float = 1.0
) -> float:
    """The largest energy residual a run with these tolerances may leave.

    The integration error of a state is about ``tol = max(rtol, atol)`` relative, so
    it moves the work integrals by about ``tol`` of the total work and the change of
    the energy by about ``tol`` of the energy level; relative to the total work, the
    imbalance is then of the order of ``tol (1 + energy_level / work_total)``. The
    bound is ``ENERGY_RESIDUAL_FACTOR`` times that, at least
    `ENERGY_RESIDUAL_FLOOR` and at most `ENERGY_RESIDUAL_MAX`, but where nothing
    moves but the integration error (a mass at rest without excitation: the total
    work at or below ``ENERGY_RESIDUAL_FACTOR tol`` of the energy level), where it is
    not capped: the imbalance is then held to the error of the energy itself,
    ``|imbalance| <= ENERGY_RESIDUAL_FACTOR tol (energy_level + work_total)``, and a
    work of the order of that error divides nothing into a residual that means anything.
    A larger residual means the run did not keep its tolerances, or they are too
    loose to trust: `summarize` then sets ``energy_ok`` False and says so in
    ``warnings``.

    Parameters
    ----------
    rtol, atol : float
        The run's tolerances.
    energy_level : float
        ``max |E|`` at the ends of the run (`EnergyBalance.energy_level`).
    work_total : float
        The total absolute work (`EnergyBalance.work_total`), the residual's scale.

    Returns
    -------
    float
        The bound, relative to the total work.

    See Also
    --------
    noise_floor : the other bound a run's tolerances set.

    Examples
    --------
    >>> energy_bound(1e-10, 1e-10)  # the floor
    1e-08
    >>> round(energy_bound(1e-6, 1e-10), 12)  # 64 tol
    6.4e-05
    >>> energy_bound(1e-2, 1e-10)  # a tolerance too loose to trust: the cap
    0.0001
    >>> at_rest = energy_bound(1e-10, 1e-10, energy_level=100.0, work_total=1e-11)
    >>> round(at_rest * 1e-11, 12)  # the imbalance allowed: 64 tol of the energy level
    6.4e-07
    """
    tol = max(rtol, atol)
    ratio = energy_level / work_total if work_total > 0 else math.inf
    scaled = ENERGY_RESIDUAL_FACTOR * tol * (1.0 + ratio)
    if ratio * ENERGY_RESIDUAL_FACTOR * tol >= 1.0:
        # nothing moves but the integration error: the imbalance against the error of
        # the energy itself, uncapped
        return float(max(ENERGY_RESIDUAL_FLOOR, scaled))
    return float(max(ENERGY_RESIDUAL_FLOOR, min(scaled, ENERGY_RESIDUAL_MAX)))
