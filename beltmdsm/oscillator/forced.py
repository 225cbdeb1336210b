"""Forced periodic responses of any model by shooting, with their Floquet multipliers.

The period is the excitation's, ``T = 2 pi / Omega`` (``k T`` for a response of ``k``
periods). The shooting is `beltmdsm.periodic.newton.fixed_point` (damped Newton on
``P(x) - x``) on the map ``P`` of the hybrid run over ``k T``
(`beltmdsm.oscillator.hybrid.flow`), whose Jacobian is the monodromy with the saltation
matrix at every switch; its eigenvalues are the Floquet multipliers. The guess is the
state after a run of ``settle`` seconds from rest (or from ``guess``), at a whole number
of periods.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import Unsupported
from ..periodic.newton import fixed_point
from .hybrid import Switch, flow
from .system import STICK, System

__all__ = ["Response", "forced_response"]


@dataclass(repr=False)
class Response:
    """A periodic response of a forced model.

    Attributes
    ----------
    system : System
    state : ndarray (2n,)
        The state at phase 0 (``t = 0`` of the excitation).
    period : float
        ``k`` excitation periods [s].
    periods : int
        ``k``.
    multipliers : ndarray (2n,) complex
        By decreasing modulus.
    monodromy : ndarray (2n, 2n)
    switches : list of (t, before, after)
        The switches of one period of the response.
    residual : float
        ``max |P(x) - x|``.

    See Also
    --------
    forced_response : makes it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> r = forced_response(System("belt_1dof", Vb=0.0, mu_s=0.02, alpha_t=1.0, Omega_t=2.0))
    >>> r.periods, r.sticks, r.stable
    (1, 0, True)
    """

    system: System
    state: NDArray[np.float64]
    period: float
    periods: int
    multipliers: NDArray[np.complex128]
    monodromy: NDArray[np.float64]
    switches: list[Switch]
    residual: float

    @property
    def stable(self) -> bool:
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def sticks(self) -> int:
        return sum(1 for _, _, after in self.switches if after == STICK)

    def __repr__(self) -> str:
        mults = ", ".join(f"{abs(m):.4g}" for m in self.multipliers)
        return (
            f"Response({self.system!r}; period {self.period:.10g} s, {len(self.switches)} "
            f"switches, {self.sticks} sticks; |multipliers| {mults}; "
            f"{'stable' if self.stable else 'unstable'})"
        )


@dataclass
class _Image:
    state: NDArray[np.float64]
    jacobian: NDArray[np.float64]
    switches: list


class _PeriodMap:
    """The ``k``-period map of the hybrid run, as `fixed_point` takes it."""

    def __init__(self, system, T, periods, tol):
        self.system, self.T, self.periods, self.tol = system, T, periods, tol

    def __call__(self, x):
        run = flow(self.system, 0.0, x, self.periods * self.T, variational=True, **self.tol)
        return _Image(run.y, run.monodromy, run.switches)


def forced_response(
    system: System,
    guess: ArrayLike | None = None,
    *,
    periods: int = 1,
    settle: float = 100.0,
    max_iter: int = 30,
    rtol: float = 1e-11,
    atol: float = 1e-11,
) -> Response:
    """The periodic response of ``periods`` excitation periods, by shooting.

    Parameters
    ----------
    system : System
        With excitation (an amplitude not 0, one frequency).
    guess : array_like (2n,), optional
        The state at phase 0 from which the seed run starts; rest by default.
    periods : int
        ``k`` >= 1: a response of ``k`` excitation periods.
    settle : float
        The seed run's length [s] (rounded up to whole periods; 0: ``guess`` itself).
    max_iter : int
    rtol, atol : float
        The integrator's tolerances.

    Returns
    -------
    Response

    Raises
    ------
    Unsupported
        An unforced model, or excitation terms of different frequencies.
    NoPeriodicResponse
        Newton's method does not converge.

    See Also
    --------
    beltmdsm.oscillator.self_excited_cycle : the cycle of the unforced model.

    Examples
    --------
    Den Hartog's non-stop motion under Coulomb friction (the belt at rest):

    >>> from beltmdsm.oscillator import System
    >>> s = System("belt_1dof", Vb=0.0, beta1=0.0, mu_s=0.03, alpha_t=1.5625,
    ...            Omega_t=0.8, phase_t=np.pi / 2)
    >>> r = forced_response(s)
    >>> round(float(np.abs(r.state).max()), 6), len(r.switches), r.sticks
    (2.472633, 2, 0)
    """
    T = system.excitation_period()
    if T is None:
        raise Unsupported(
            f"model {system.name!r}: every excitation amplitude is 0; "
            "self_excited_cycle computes its cycles"
        )
    if not (isinstance(periods, int) and periods >= 1):
        raise ValueError(f"periods={periods!r}: not a whole number >= 1")
    tol = dict(rtol=rtol, atol=atol)
    m = len(system.states)
    x = np.zeros(m) if guess is None else np.asarray(guess, dtype=float)
    if x.shape != (m,) or not np.all(np.isfinite(x)):
        raise ValueError(f"guess: not {m} finite numbers ({', '.join(system.states)})")
    n_settle = int(np.ceil(settle / T))
    if n_settle:
        x = flow(system, 0.0, x, n_settle * T, **tol).y
    pmap = _PeriodMap(system, T, periods, tol)
    point = fixed_point(pmap, x, max_iter=max_iter)
    M = point.image.jacobian
    w = np.linalg.eigvals(M)
    w = w[np.argsort(-np.abs(w), kind="stable")]
    return Response(
        system, point.state, periods * T, periods, w, M, point.image.switches, point.residual
    )
