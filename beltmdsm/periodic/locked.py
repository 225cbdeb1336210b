"""Phase locking: whether stroboscopic samples repeat after ``k`` excitation periods.

A self-excited oscillation of a forced system often locks to the excitation: the
stroboscopic samples ``y(nT)`` of a run of Eq. (4) (``T`` the excitation period) then
repeat with a period ``k T``; the omega1 peak of the spectra of Fig. 2b is then a line
of the ``k T``-periodic response. At the base set the run from rest locks at ``4 T`` for ``Vb`` in
[3.87, 7.67] (``omega1 = 1 = Omega / 4``), and at ``Omega = 6`` at ``6 T``. A locked
response is a fixed point of the ``k``-fold period map
(`beltmdsm.periodic.closed_form.ClosedFormMap`), which shooting computes exactly
(``periodic_response(..., periods=k)``, `beltmdsm.periodic.shooting`).

* `Stroboscope` (`stroboscope`): the samples of one attractor, with the distance of
  each return ``|y(n T + k T) - y(n T)|`` for ``k`` up to a limit (`LOCK_LIMIT`). The
  smallest ``k`` whose return is below `LOCK_TOL` is the candidate period; Newton's
  method on the ``k``-fold map from the last sample decides.
* `map_stroboscope`: the samples of the attractor of the period map itself, iterated
  from a state (the tangential motion on the periodic normal motion, in closed form):
  the seed of ``periodic_response(..., periods=k)``. The runs of Eq. (4) from rest and
  the ladders continued in a parameter are studies (`beltmdsm.starts`).
* `NotLocked`: where no ``k`` within the limit locks, the evidence: the closest return,
  the rotation number of the samples about their centre and whether they lie on a
  closed curve (an invariant torus of the stroboscopic map: quasi-periodic motion, or
  a lock of a longer period).
* `minimal_periods`: the smallest period, in excitation periods, of an orbit of the
  ``k``-fold map.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .base import MapImage, PeriodMap

__all__ = [
    "LOCK_LIMIT",
    "LOCK_TOL",
    "SAME_ORBIT",
    "Stroboscope",
    "stroboscope",
    "map_stroboscope",
    "NotLocked",
    "minimal_periods",
    "same_phases",
]

#: The largest period, in excitation periods, that a lock is looked for at.
LOCK_LIMIT = 12
#: A return ``|y(nT + kT) - y(nT)|`` over the samples' scale below this makes ``k`` the
#: candidate period. A run that settles on a response with ``|mu| <= 0.99`` per ``k``
#: periods is within it after about 700 periods from a distance of 1; Newton's method
#: then converges from the last sample in a few steps, and decides.
LOCK_TOL = 1e-3
#: Two phase-0 states of one orbit agree to this (relative to their scale).
SAME_ORBIT = 1e-6
#: The samples lie on a closed curve when their correlation dimension (the slope of
#: the share of pairs closer than ``r`` against ``r``, between `DIMENSION_RADII` of
#: their diameter) is within `CURVE_DIMENSION`, and, ordered by their angle about the
#: centre, no step exceeds `CURVE_STEP` of the closed path's length.
DIMENSION_RADII = (0.05, 0.15)
CURVE_DIMENSION = (0.8, 1.3)
CURVE_STEP = 0.15


@dataclass
class Stroboscope:
    """Stroboscopic samples ``y(nT)`` of one attractor.

    Attributes
    ----------
    source : str
        How the attractor was reached ("run from rest", ...).
    samples : ndarray (n, 2) or (n, 4)
        The shooting states at phase 0 (`beltmdsm.periodic.base.PeriodMap.shooting`:
        ``(X1, X1')`` on the closed-form path, the full state on the general one), in
        time order.
    returns : ndarray (limit,)
        ``max_n |y(nT + kT) - y(nT)|`` over the samples' scale, for ``k = 1..limit``.

    See Also
    --------
    stroboscope : builds it from samples.
    map_stroboscope : the samples of the period map's attractor.
    NotLocked : the evidence where no ``k`` locks.

    Examples
    --------
    >>> import numpy as np
    >>> s = stroboscope(np.tile([[0.0, 1.0], [1.0, 0.0], [-1.0, -1.0]], (20, 1)), "a 3-cycle")
    >>> s.candidate, s.samples.shape
    (3, (60, 2))
    """

    source: str
    samples: NDArray[np.float64]
    returns: NDArray[np.float64]

    @property
    def candidate(self) -> int | None:
        """The smallest ``k`` whose return is below `LOCK_TOL`, or None."""
        below = np.flatnonzero(self.returns < LOCK_TOL)
        return int(below[0]) + 1 if below.size else None


def stroboscope(samples: ArrayLike, source: str, limit: int = LOCK_LIMIT) -> Stroboscope:
    """`Stroboscope` of samples of the shooting state at phase 0 (rows in time order).

    Parameters
    ----------
    samples : array_like (n, 2) or (n, 4)
        ``y(nT)``, one excitation period apart.
    source : str
        How the attractor was reached (for the reports).
    limit : int
        The largest ``k`` whose return is measured.

    Returns
    -------
    Stroboscope

    Raises
    ------
    ValueError
        Unless ``samples`` is ``(n, 2)`` or ``(n, 4)`` with ``n > 2 limit``.

    See Also
    --------
    map_stroboscope : the samples of the period map's attractor.
    beltmdsm.multistability.responses.responses : the samples of runs of Eq. (4).

    Examples
    --------
    >>> import numpy as np
    >>> y = np.tile([[0.0, 1.0], [1.0, 0.0], [-1.0, -1.0]], (20, 1))
    >>> s = stroboscope(y, "a 3-cycle")
    >>> s.candidate, np.round(s.returns[:4], 3)
    (3, array([1., 1., 0., 1.]))
    >>> stroboscope(y[:10], "too few")
    Traceback (most recent call last):
    ...
    ValueError: samples must be (n, 2) or (n, 4) with n > 2 * limit; got (10, 2)
    """
    y = np.asarray(samples, dtype=float)
    if y.ndim != 2 or y.shape[1] not in (2, 4) or y.shape[0] < 2 * limit + 1:
        raise ValueError(f"samples must be (n, 2) or (n, 4) with n > 2 * limit; got {y.shape}")
    scale = 1.0 + float(np.max(np.abs(y)))
    returns = np.array([float(np.max(np.abs(y[k:] - y[:-k]))) / scale for k in range(1, limit + 1)])
    return Stroboscope(source, y, returns)


def map_stroboscope(
    pmap: PeriodMap,
    x: ArrayLike,
    settle: int,
    samples: int,
    source: str,
    limit: int = LOCK_LIMIT,
) -> Stroboscope:
    """The attractor of the period map iterated from ``x``: ``settle`` periods, then samples.

    The one-period map of ``pmap`` (`beltmdsm.periodic.base.PeriodMap.step`) is
    iterated, whatever its ``k``: the samples are one excitation period apart.

    Parameters
    ----------
    pmap : beltmdsm.periodic.base.PeriodMap
    x : array_like
        The shooting state to start from (`beltmdsm.periodic.base.PeriodMap.shooting`).
    settle : int
        Periods iterated before sampling.
    samples : int
        Periods sampled; more than ``2 limit``.
    source : str
        How the attractor was reached (for the reports).
    limit : int
        The largest ``k`` whose return is measured.

    Returns
    -------
    Stroboscope

    Raises
    ------
    beltmdsm.errors.NoPeriodicResponse
        Where the map fails on the way.
    ValueError
        For ``samples <= 2 limit`` (`stroboscope`).

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : seeds ``periods > 1`` so.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.excitation import initial_state
    >>> from beltmdsm.periodic.engines import period_map
    >>> m = Model(Vb=5.0)
    >>> pmap = period_map(m)
    >>> s = map_stroboscope(pmap, pmap.shooting(initial_state(m)), 100, 48, "from rest")
    >>> s.candidate  # locked at 4 T: omega1 = Omega / 4
    4
    """
    x = np.array(x, dtype=float)
    for _ in range(int(settle)):
        x = pmap.step(x)
    out = np.empty((int(samples), x.size))
    for n in range(int(samples)):
        x = out[n] = pmap.step(x)
    return stroboscope(out, source, limit)


@dataclass
class NotLocked:
    """An attractor that does not lock within the limit, and the evidence.

    Attributes
    ----------
    source : str
    limit : int
    closest_periods, closest_return : int, float
        The ``k <= limit`` whose return is smallest, and that return.
    rotation_number : float
        Mean angle turned per period about the samples' centre, in turns.
    closed_curve : bool
        Whether the samples lie on a closed curve about their centre (module constants).
    dimension : float
        Their correlation dimension: about 1 on a curve, 2 filling an area.
    largest_step : float
        The largest step between the samples ordered by angle, over the length of the
        closed path through them in that order.
    centre : tuple of float
        ``(X1, X1')`` of the centre.
    state : tuple of float
        The last sample (a shooting state at phase 0): where a closer look, the
        classification of `beltmdsm.attractors.classification`, starts.
    classification : dict or None
        That classification (`beltmdsm.attractors.classification.Attractor.as_dict`: ``kind``,
        ``lyapunov``, ``evidence``, ...) where one was made.

    See Also
    --------
    Stroboscope : the samples it reads (`NotLocked.of`).
    beltmdsm.attractors.classification.classify : what the attractor is.

    Examples
    --------
    Samples that turn by 0.1234 of a circle per period: a torus, not a lock.

    >>> import numpy as np
    >>> angle = 2 * np.pi * 0.1234 * np.arange(300)
    >>> s = stroboscope(np.c_[np.cos(angle), np.sin(angle)], "a torus")
    >>> s.candidate is None
    True
    >>> evidence = NotLocked.of(s)
    >>> evidence.closed_curve, round(evidence.rotation_number, 4)
    (True, 0.1234)
    >>> print(evidence.text())  # doctest: +ELLIPSIS
    not locked (quasi-periodic or longer period) within 12 periods (a torus): the ...
    """

    source: str
    limit: int
    closest_periods: int
    closest_return: float
    rotation_number: float
    closed_curve: bool
    dimension: float
    largest_step: float
    centre: tuple[float, float]
    state: tuple[float, ...] = ()
    classification: dict | None = None

    @classmethod
    def of(cls, strobe: Stroboscope) -> NotLocked:
        """The evidence of a stroboscope that does not lock, in the samples' projection
        on ``(X1, X1')`` (all the closed-form path samples)."""
        from scipy.spatial.distance import pdist

        y = strobe.samples[:, :2]
        centre = y.mean(axis=0)
        spread = y.std(axis=0)
        spread[spread == 0] = 1.0
        w = (y - centre) / spread
        angle = np.arctan2(w[:, 1], w[:, 0])
        turn = np.angle(np.exp(1j * np.diff(angle)))
        path = w[np.argsort(angle)]
        steps = np.hypot(*(np.roll(path, -1, axis=0) - path).T)
        step = float(np.max(steps) / np.sum(steps)) if np.sum(steps) > 0 else 1.0
        pairs = pdist(w)
        radii = np.array(DIMENSION_RADII) * max(float(np.max(pairs)), 1e-300)
        shares = np.array([max(np.mean(pairs < r), 1e-300) for r in radii])
        dimension = float(np.diff(np.log(shares))[0] / np.diff(np.log(radii))[0])
        k = int(np.argmin(strobe.returns))
        lo, hi = CURVE_DIMENSION
        return cls(
            strobe.source,
            strobe.returns.size,
            k + 1,
            float(strobe.returns[k]),
            float(np.mean(turn) / (2 * np.pi)),
            bool(lo <= dimension <= hi and step <= CURVE_STEP),
            dimension,
            step,
            (float(centre[0]), float(centre[1])),
            tuple(float(v) for v in strobe.samples[-1]),
        )

    def text(self) -> str:
        """One line: the verdict and its evidence."""
        where = (
            "lie on a closed curve about"
            if self.closed_curve
            else "do not lie on one closed curve about"
        )
        curve = (
            f"the stroboscopic points {where} (X1, X1') = ({self.centre[0]:.4g}, "
            f"{self.centre[1]:.4g}) (correlation dimension {self.dimension:.2f}, largest "
            f"step {100 * self.largest_step:.0f}% of the path)"
        )
        return (
            f"not locked (quasi-periodic or longer period) within {self.limit} periods "
            f"({self.source}): {curve}; rotation number {self.rotation_number:.4f} per "
            f"period; closest return after {self.closest_periods} periods, "
            f"{self.closest_return:.1e}"
        )

    def as_dict(self) -> dict:
        """The evidence for JSON: the attributes, ``locked`` (False) and ``text``; ``kind``,
        ``lyapunov`` and ``evidence`` of the classification where one was made
        (``kind`` "unclassified" otherwise)."""
        c = self.classification or {}
        return {
            "kind": c.get("kind", "unclassified"),
            "lyapunov": c.get("lyapunov"),
            "evidence": c.get(
                "evidence",
                "not classified here: beltmdsm.attractors.classification.classify names it from "
                "its last sample (state), by its Lyapunov spectrum and its returns",
            ),
            "source": self.source,
            "locked": False,
            "limit": self.limit,
            "text": self.text(),
            "closest_periods": self.closest_periods,
            "closest_return": self.closest_return,
            "rotation_number": self.rotation_number,
            "closed_curve": self.closed_curve,
            "dimension": self.dimension,
            "largest_step": self.largest_step,
            "centre": list(self.centre),
        }


def same_phases(phases: list[NDArray[np.float64]], x: ArrayLike) -> bool:
    """Whether ``x`` is one of an orbit's phase-0 states (to `SAME_ORBIT`, relative).

    Parameters
    ----------
    phases : list of ndarray
        The orbit's shooting states at phase 0 (`beltmdsm.periodic.base.MapImage.phases`).
    x : array_like
        A shooting state.

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        Where ``x`` and the phases differ in size (numpy's broadcast).

    See Also
    --------
    minimal_periods : the period of the orbit itself.

    Examples
    --------
    >>> import numpy as np
    >>> phases = [np.array([1.0, 0.0]), np.array([0.0, 1.0])]
    >>> same_phases(phases, [1e-9, 1.0]), same_phases(phases, [0.0, 1.1])
    (True, False)
    """
    x = np.asarray(x, dtype=float)
    scale = 1.0 + float(np.max(np.abs(x)))
    return any(np.max(np.abs(x - y)) <= SAME_ORBIT * scale for y in phases)


def minimal_periods(image: MapImage, k: int) -> int:
    """The smallest divisor ``j`` of ``k`` after which the orbit's phase-0 states repeat.

    Parameters
    ----------
    image : beltmdsm.periodic.base.MapImage
        The ``k``-fold map at a point of the orbit.
    k : int
        The map's periods.

    Returns
    -------
    int
        ``j``: the orbit is a response of ``j`` periods (``k`` where it is of minimal
        period ``k``).

    Raises
    ------
    IndexError
        Where ``image`` has fewer than ``k`` phases.

    See Also
    --------
    beltmdsm.errors.ShorterPeriod : raised where shooting for ``k`` finds ``j < k``.

    Examples
    --------
    The response of 4 periods seen by the 8-fold map:

    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.periodic.engines import period_map
    >>> r = periodic_response(Model(Vb=5.0), periods=4)
    >>> minimal_periods(period_map(r.model, 8)(r.shooting_state), 8)
    4
    """
    phases = image.phases
    scale = 1.0 + max(float(np.max(np.abs(x))) for x in phases)
    for j in range(1, k):
        if k % j == 0 and all(
            np.max(np.abs(phases[i] - phases[(i + j) % k])) <= SAME_ORBIT * scale for i in range(k)
        ):
            return j
    return k
