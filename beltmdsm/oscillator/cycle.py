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
#: A slip phase shorter than this share of steady sliding's shortest time scale is none.
_LEAST_PHASE = 1e-6


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
    phase of at least ``1e-6`` of steady sliding's shortest time scale (``1 / max
    |eigenvalue|``). The bordered shooting system is also solved by ``T -> 0`` at a
    point where a stick ends and begins again at once: no cycle.

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
    why = _not_a_return(cycle.system, cycle.mode, cycle.period, cycle.switches)
    if why:
        raise NoPeriodicResponse(f"{cycle.system!r}: no self-excited cycle: the {why}")
    return cycle


def _not_a_return(system, mode, period, switches):
    """Why a run of ``period`` from ``mode`` with ``switches`` is no cycle ("" if it is)."""
    shortest = 1.0 / float(np.abs(steady_sliding(system).eigenvalues).max())
    times = [0.0] + [t for t, _, _ in switches] + [period]
    modes = [mode] + [after for _, _, after in switches]
    slip = max((b - a for a, b, md in zip(times, times[1:], modes) if md != STICK), default=0.0)
    if modes[-1] != mode:
        return f"run of period {period:.3g} s ends in mode {modes[-1]}, not in its mode {mode}"
    if slip < _LEAST_PHASE * shortest:
        return (
            f"run of period {period:.3g} s slips for {slip:.3g} s at most, below "
            f"{_LEAST_PHASE:g} of steady sliding's shortest time scale {shortest:.3g} s: "
            "a stick that ends and begins at once, no cycle"
        )
    return ""


def _cycle(system, x, mode, run, residual):
    M = run.monodromy
    f = np.asarray(system.kernels.field(0.0, x, system.p, mode), dtype=float)
    w, V = np.linalg.eig(M)
    V = V / np.linalg.norm(V, axis=0)
    align = np.abs(V.conj().T @ (f / np.linalg.norm(f)))
    i = int(np.argmax(align))
    rest = np.delete(w, i)
    rest = rest[np.argsort(-np.abs(rest), kind="stable")]
    sticks = sum(1 for _, _, after in run.switches if after == STICK)
    return genuine(
        Cycle(system, x, mode, float(run.t), rest, complex(w[i]), M, run.switches, sticks, residual)
    )
