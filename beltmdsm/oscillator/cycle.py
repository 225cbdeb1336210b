"""A self-excited cycle of an unforced model: the result (`Cycle`), read off a converged
shooting run (its Floquet multipliers, the trivial one apart), and the check that it is a
genuine return (`genuine`).

Both shootings (`beltmdsm.oscillator.stick_slip_shooting`,
`beltmdsm.oscillator.slip_shooting`) end here: every cycle they report has passed
`genuine`, since their bordered systems are also solved by the trivial return ``T -> 0``
at a point where a stick ends and begins again at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from .equilibria import steady_sliding
from .hybrid import Switch
from .system import STICK, System

__all__ = ["Cycle", "genuine", "NEWTON_TOL"]

#: Newton's method stops when the run returns to its start to this (relative to the
#: state's scale).
NEWTON_TOL = 1e-10
#: A proper divisor of the period "returns" where the state comes back to this.
_RETURN_TOL = 1e-6
#: A slip phase is a rounding artefact where the state moves over it by no more than
#: this many times the integration's tolerance (`genuine`'s error model).
_ROUNDING = 100.0


@dataclass(repr=False)
class Cycle:
    """A self-excited cycle of an unforced model.

    Attributes
    ----------
    system : System
    state : ndarray (2n,)
        A point of the cycle: where a stick ends (stick-slip) or on the section.
    mode : int
        The mode at ``state``.
    period : float
        The least period [s].
    multipliers : ndarray (2n-1,) complex
        The Floquet multipliers but the trivial one, by decreasing modulus.
    trivial_multiplier : complex
        The multiplier along the flow (1 up to the accuracy).
    monodromy : ndarray (2n, 2n)
    switches : list of (t, before, after)
        The switches of one period, ``t`` from ``state``.
    sticks : int
        Stick phases per period.
    residual : float
        ``max |x_T - x|`` at the solution.
    rtol, atol : float
        The integrator's tolerances it was shot at (`genuine`'s error model).

    See Also
    --------
    self_excited_cycle : makes it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> c = self_excited_cycle(System("belt_1dof", friction="static_kinetic", Vb=0.5))
    >>> c  # doctest: +ELLIPSIS +NORMALIZE_WHITESPACE
    Cycle(System('belt_1dof', friction='static_kinetic', Vb=0.5); stick_slip,
    period ... s, 1 sticks; |multipliers| ...; stable)
    >>> c.kind, c.stable
    ('stick_slip', True)
    """

    system: System
    state: NDArray[np.float64]
    mode: int
    period: float
    multipliers: NDArray[np.complex128]
    trivial_multiplier: complex
    monodromy: NDArray[np.float64]
    switches: list[Switch]
    sticks: int
    residual: float
    rtol: float = 1e-11
    atol: float = 1e-11

    @property
    def stable(self) -> bool:
        """All multipliers but the trivial one inside the unit circle."""
        return bool(np.all(np.abs(self.multipliers) < 1.0))

    @property
    def kind(self) -> str:
        return "stick_slip" if self.sticks else "slip"

    def __repr__(self) -> str:
        mults = ", ".join(f"{abs(m):.4g}" for m in self.multipliers)
        return (
            f"Cycle({self.system!r}; {self.kind}, period {self.period:.10g} s, "
            f"{self.sticks} sticks; |multipliers| {mults}; "
            f"{'stable' if self.stable else 'unstable'})"
        )


def genuine(cycle: Cycle) -> Cycle:
    """``cycle`` where it is a genuine return, else NoPeriodicResponse (the one check).

    A genuine cycle leaves its state and comes back: in the mode it left, with a slip
    phase longer than a rounding artefact of its integration. The bordered shooting
    system is also solved by ``T -> 0`` at a point where a stick ends and begins again
    at once: no cycle.

    The error model of that artefact: the integrator holds the state to ``atol + rtol
    |y|`` a step (the dense output that locates a switch to about the same), so a slip
    phase over which the state moves by no more than that is indistinguishable from
    none. The state moves at a speed of order ``scale / tau`` (``scale = 1 + max |x|``
    of the cycle's state, ``tau = 1 / max |eigenvalue|`` steady sliding's shortest time
    scale), so such a phase lasts up to ``(rtol + atol / scale) tau``. A phase counts
    where it lasts longer than ``100 (rtol + atol / scale) tau``: a factor 10 for the
    dense output's error over the step's at each of the phase's two switches, and 5
    for a speed below ``scale / tau``. At the default tolerances (``1e-11``) and
    ``scale`` of order 1 that is ``2e-9 tau``.

    Parameters
    ----------
    cycle : Cycle

    Returns
    -------
    Cycle
        ``cycle`` itself.

    Raises
    ------
    NoPeriodicResponse
        Naming the model, its parameters and the check that fails.

    See Also
    --------
    self_excited_cycle : applies it to every cycle it returns.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=1.5))
    >>> genuine(c) is c
    True
    """
    tol = dict(rtol=cycle.rtol, atol=cycle.atol)
    why = _not_a_return(cycle.system, cycle.state, cycle.mode, cycle.period, cycle.switches, tol)
    if why:
        raise NoPeriodicResponse(f"{cycle.system!r}: no self-excited cycle: the {why}")
    return cycle


def _least_phase(system, state, rtol, atol) -> float:
    """The shortest slip phase that is no rounding artefact (`genuine`'s error model)."""
    tau = 1.0 / float(np.abs(steady_sliding(system).eigenvalues).max())
    scale = 1.0 + float(np.abs(state).max())
    return _ROUNDING * (rtol + atol / scale) * tau


def _not_a_return(system, state, mode, period, switches, tol):
    """Why a run of ``period`` from ``(state, mode)`` with ``switches``, integrated at
    ``tol`` (``rtol``, ``atol``), is no cycle ("" if it is)."""
    times = [0.0] + [t for t, _, _ in switches] + [period]
    modes = [mode] + [after for _, _, after in switches]
    slip = max((b - a for a, b, md in zip(times, times[1:], modes) if md != STICK), default=0.0)
    if modes[-1] != mode:
        return f"run of period {period:.3g} s ends in mode {modes[-1]}, not in its mode {mode}"
    least = _least_phase(system, state, tol["rtol"], tol["atol"])
    if slip <= least:
        return (
            f"run of period {period:.3g} s slips for {slip:.3g} s at most, not above "
            f"{least:.3g} s, the rounding of its integration (rtol={tol['rtol']:g}, "
            f"atol={tol['atol']:g}): a stick that ends and begins at once, no cycle"
        )
    return ""


def _cycle(system, x, mode, run, residual, tol):
    M = run.monodromy
    f = np.asarray(system.kernels.field(0.0, x, system.p, mode), dtype=float)
    w, V = np.linalg.eig(M)
    V = V / np.linalg.norm(V, axis=0)
    align = np.abs(V.conj().T @ (f / np.linalg.norm(f)))
    i = int(np.argmax(align))
    rest = np.delete(w, i)
    rest = rest[np.argsort(-np.abs(rest), kind="stable")]
    sticks = sum(1 for _, _, after in run.switches if after == STICK)
    T = float(run.t)
    return genuine(
        Cycle(system, x, mode, T, rest, complex(w[i]), M, run.switches, sticks, residual, **tol)
    )
