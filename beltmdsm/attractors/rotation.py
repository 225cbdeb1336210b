"""The returns and rotation number of stroboscopic samples: whether a run's samples close
on themselves after ``k`` periods (`_returns`), or turn about a centre at a constant mean
angle per period, a quasi-periodic torus (`rotation_number`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["rotation_number"]

#: A return after ``k`` periods closer than this (relative to the state's scale) is a
#: candidate period; Newton's method on the ``k``-fold map decides.
RETURN_TOL = 1e-6
#: Candidate periods tried by Newton's method before the exponents decide.
_CANDIDATES = 3
#: A window whose first sample lies within this distance (relative to the state's
#: scale, as `RETURN_TOL`) of unstable steady sliding begins in its linear
#: neighbourhood: at Stribeck's Vb = 1.5 (sigma = 0.064 1/s) a start 1e-6 off it is
#: 3e-3 off after 150 s and on the stick-slip cycle only after about 215 s.
NEAR = 1e-2
#: Samples at the start of the window searched for a return onto a periodic response
#: (`unstable_set`): periods up to four.
_HEAD = 14


def _angles(samples):
    """The angle of each sample about the samples' centre in ``(X1, X1')``, scaled."""
    y = samples[:, :2]
    w = (y - y.mean(axis=0)) / np.where(y.std(axis=0) > 0, y.std(axis=0), 1.0)
    return np.arctan2(w[:, 1], w[:, 0])


def rotation_number(samples: ArrayLike) -> tuple[float, float]:
    """The rotation number of stroboscopic samples [turns per period] and its accuracy.

    The weighted Birkhoff average of the angle turned per period about the samples'
    centre (module docstring), and its difference from the same average over the first
    half of the samples.

    Parameters
    ----------
    samples : array_like, shape (n, 2) or (n, 4)
        The states once per period, ``n >= 64``; the angle is taken in the plane of
        the first two components.

    Returns
    -------
    rotation : float
        The turns per period, in ``(-1/2, 1/2]``.
    error : float
        The difference of the two averages, an estimate of its error.

    Raises
    ------
    ValueError
        For fewer than 64 samples (below that the two averages are not yet in their
        fast convergence, and their difference understates the error:
        benchmarks/bench_lyapunov.py).

    See Also
    --------
    beltmdsm.attractors.classification.classify : Names a torus by this number.

    Examples
    --------
    Samples that turn by ``rho = (sqrt(5) - 1) / 4`` (irrational) each period about
    their centre: the weighted average finds ``rho`` to 1e-9 from 200 samples.

    >>> rho = (np.sqrt(5) - 1) / 4
    >>> k = np.arange(200)
    >>> ring = np.c_[1 + np.cos(2 * np.pi * rho * k), np.sin(2 * np.pi * rho * k)]
    >>> turns, error = rotation_number(ring)
    >>> round(turns, 9), round(float(rho), 9), error < 1e-9
    (0.309016994, 0.309016994, True)
    """
    y = np.asarray(samples, dtype=float)
    if y.ndim != 2 or y.shape[0] < 64:
        raise ValueError(f"samples must be (n, 2+) with n >= 64; got {y.shape}")
    turn = np.angle(np.exp(1j * np.diff(_angles(y)))) / (2 * np.pi)

    def average(x):
        t = (np.arange(x.size) + 0.5) / x.size
        w = np.exp(-1.0 / (t * (1.0 - t)))
        return float(np.sum(w * x) / np.sum(w))

    full, half = average(turn), average(turn[: turn.size // 2])
    return full, abs(full - half)


def _returns(samples, tol):
    """The ``k`` (increasing, up to a third of the samples) after which the last two
    samples repeat to ``tol``: the candidate periods."""
    y = samples
    scale = 1.0 + float(np.max(np.abs(y)))
    n = y.shape[0]
    return [
        k
        for k in range(1, n // 3 + 1)
        if float(np.max(np.abs(y[n - 2 :] - y[n - 2 - k : n - k]))) <= tol * scale
    ]
