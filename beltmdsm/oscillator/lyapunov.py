"""The Lyapunov spectrum of a run of any model, through its switches.

Benettin's method: the run is cut into chunks of length ``tau``; over each the
variational run (`beltmdsm.oscillator.hybrid.flow` with ``variational=True``: the
derived mode Jacobians, and the derived saltation matrix at every switch) carries an
orthonormal frame ``Q``, re-orthonormalised by QR (``Phi Q = Q' R``); the exponents are
the time averages of ``ln |R_ii|``. A stick phase removes a direction (the saltation
matrix into stick has rank ``2n - 1``): its ``R_ii`` is 0 and its exponent ``-inf``,
counted in ``collapsed``. On a periodic orbit the exponents are ``ln |mu_i| / T`` of
its Floquet multipliers (the check in tests/beltmdsm/oscillator/test_oscillator_studies.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .hybrid import flow
from .system import System

__all__ = ["Spectrum", "lyapunov"]

#: ``|R_ii|`` below this times ``max |R|`` is a direction a stick removed (exactly 0
#: up to rounding: the saltation matrix into stick has a zero row).
_COLLAPSED = 1e-13


@dataclass(repr=False)
class Spectrum:
    """The Lyapunov exponents of a run of a model.

    Attributes
    ----------
    system : System
    exponents : ndarray (2n,)
        Largest first [1/s]; ``-inf`` for a direction a stick phase removed.
    t_transient, t_average : float
        The time run before averaging, and the time averaged over [s].
    tau : float
        The chunk between re-orthonormalisations [s].
    collapsed : int
        Directions removed by stick (exponent ``-inf``).
    switches : int
        Switches of mode while averaging.
    status : str
        ``"done"``, or ``"zeno"`` where a run stopped on accumulating switches.
    error : ndarray (2n,)
        Half the difference of the exponents over the two halves of the window (0 for
        a direction stick removed): how far the average has settled [1/s].
    state : ndarray (2n,)
        The run's last state, and ``mode`` its mode.

    See Also
    --------
    lyapunov : makes it.
    """

    system: System
    exponents: NDArray[np.float64]
    t_transient: float
    t_average: float
    tau: float
    collapsed: int
    switches: int
    status: str = "done"
    error: NDArray[np.float64] | None = None
    state: NDArray[np.float64] | None = None
    mode: int | None = None

    @property
    def largest(self) -> float:
        return float(self.exponents[0])

    def __repr__(self) -> str:
        values = ", ".join(f"{v:.6g}" for v in self.exponents)
        return (
            f"Spectrum({self.system!r}; [{values}] 1/s over {self.t_average:g} s "
            f"after {self.t_transient:g} s; {self.collapsed} removed by stick; {self.status})"
        )

    def as_dict(self) -> dict:
        """Plain JSON values (``-inf`` as None)."""
        return {
            "exponents": [float(v) if math.isfinite(v) else None for v in self.exponents],
            "t_transient": self.t_transient,
            "t_average": self.t_average,
            "tau": self.tau,
            "collapsed": self.collapsed,
            "switches": self.switches,
            "status": self.status,
        }


def lyapunov(
    system: System,
    y0: ArrayLike | None = None,
    *,
    t_end: float = 1000.0,
    t_transient: float | None = None,
    tau: float | None = None,
    rtol: float = 1e-10,
    atol: float = 1e-10,
) -> Spectrum:
    """The Lyapunov spectrum of the run from ``y0`` (module docstring).

    Parameters
    ----------
    system : System
    y0 : array_like (2n,), optional
        The start (rest by default, as `beltmdsm.oscillator.simulate`).
    t_end : float
        The run's length [s], > 0.
    t_transient : float, optional
        Run before averaging [s], in ``[0, t_end)``; 30 % of ``t_end`` by default.
    tau : float, optional
        The chunk between re-orthonormalisations [s]: the excitation period where
        there is one, else 1 s.
    rtol, atol : float
        The integrator's tolerances.

    Returns
    -------
    Spectrum

    Raises
    ------
    ValueError
        A length not positive, ``t_transient`` outside ``[0, t_end)``, ``y0`` not
        ``2n`` finite numbers.

    See Also
    --------
    beltmdsm.oscillator.forced_response : multipliers whose ``ln |mu| / T`` it meets.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> s = System("belt_1dof", friction="static_kinetic", Vb=1.0)
    >>> spec = lyapunov(s, t_end=60.0)
    >>> spec.collapsed, bool(abs(spec.exponents[0]) < 0.05)  # a stick-slip cycle
    (1, True)
    """
    for name, value in (("t_end", t_end), ("rtol", rtol), ("atol", atol)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name}={value!r}: not a positive number")
    t_transient = 0.3 * t_end if t_transient is None else t_transient
    if not (isinstance(t_transient, (int, float)) and 0 <= t_transient < t_end):
        raise ValueError(f"t_transient={t_transient!r}: not in [0, t_end = {t_end:g})")
    if tau is None:
        tau = system.excitation_period() or 1.0
    if not (math.isfinite(tau) and tau > 0):
        raise ValueError(f"tau={tau!r}: not a positive number")
    m = len(system.states)
    y = np.zeros(m) if y0 is None else np.asarray(y0, dtype=float)
    if y.shape != (m,) or not np.all(np.isfinite(y)):
        raise ValueError(f"y0: not {m} finite numbers ({', '.join(system.states)})")
    tol = dict(rtol=rtol, atol=atol)
    t, mode = 0.0, None
    if t_transient > 0:
        end = flow(system, 0.0, y, float(t_transient), **tol)
        t, y, mode = end.t, end.y, end.mode
    Q = np.eye(m)
    logs = np.zeros(m)
    collapsed = np.zeros(m, dtype=bool)
    switches, status = 0, "done"
    n = max(1, round((t_end - t) / tau))
    half, t_half = None, t
    for k in range(n):
        t1 = t_transient + (k + 1) * (t_end - t_transient) / n
        end = flow(system, t, y, t1, mode=mode, variational=True, **tol)
        switches += len(end.switches)
        Q, R = np.linalg.qr(end.monodromy @ Q)
        d = np.abs(np.diag(R))
        gone = d <= _COLLAPSED * max(1.0, float(np.abs(R).max()))
        collapsed |= gone
        logs += np.log(np.where(gone, 1.0, d))
        t, y, mode = end.t, end.y, end.mode
        if k + 1 == n // 2:
            half, t_half = logs.copy(), t
        if end.status != "done":
            status = end.status
            break
    span = t - t_transient
    exponents = np.where(collapsed, -np.inf, logs / max(span, 1e-300))
    order = np.argsort(-exponents, kind="stable")
    error = np.zeros(m)
    if half is not None and t > t_half > t_transient:  # the two halves' exponents
        first = half / (t_half - t_transient)
        second = (logs - half) / (t - t_half)
        error = np.where(collapsed, 0.0, 0.5 * np.abs(second - first))
    return Spectrum(
        system, exponents[order], float(t_transient), float(span), float(tau),
        int(collapsed.sum()), switches, status, error[order], y.copy(), mode,
    )  # fmt: skip
