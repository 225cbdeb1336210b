"""A self-excited cycle of another model on a branch: `OscillatorCyclePoint`, what
`beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem` makes of a solution (issue
39), and `split`, its multipliers with the trivial one apart.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..oscillator.cycle import Cycle
from ..oscillator.orbit import orbit_observables
from ..oscillator.system import STICK, System

__all__ = ["OscillatorCyclePoint", "split"]

#: The integrator's tolerances (rtol = atol) the cycles are run at.
TOL = 1e-11


def split(M, f) -> tuple[complex, NDArray[np.complex128]]:
    """``(trivial, others)``: the multiplier whose eigenvector lies closest to the field
    ``f`` (as `beltmdsm.oscillator.cycle` picks it) and the others by decreasing modulus.

    Parameters
    ----------
    M : ndarray (m, m)
        A cycle's monodromy.
    f : ndarray (m,)
        The field at the cycle's state.

    Returns
    -------
    trivial : complex
    others : ndarray

    See Also
    --------
    beltmdsm.periodic.cycle_flow.split_multipliers : the paper's engine's.

    Examples
    --------
    >>> split(np.array([[1.0, 0.5], [0.0, 0.3]]), np.array([1.0, 0.0]))
    ((1+0j), array([0.3]))
    """
    w, V = np.linalg.eig(M)
    V = V / np.linalg.norm(V, axis=0)
    i = int(np.argmax(np.abs(V.conj().T @ (f / np.linalg.norm(f)))))
    rest = np.delete(w, i)
    return complex(w[i]), rest[np.argsort(-np.abs(rest), kind="stable")]


@dataclass
class OscillatorCyclePoint:
    """One self-excited cycle of another model on a branch.

    Attributes
    ----------
    value : float
    state : ndarray (2n,)
        On the section where the slip speed is least (a pure-slip cycle) or largest (one
        with a stick phase).
    period : float
    multipliers : ndarray (2n-1,) complex
        Without the trivial one, by decreasing modulus.
    trivial_multiplier : complex
    max_abs_multiplier : float
    stable : bool
    margin : float
        The slip speed ``m v_r`` at ``state``: the least of a pure-slip cycle, 0 at its
        stick onset.
    curvature : float
        ``d^2 (m v_r) / dt^2`` at ``state``: > 0 at the least slip speed; 0 at the Hopf
        point, where the cycle shrinks onto steady sliding.
    tangent : float
        The parameter component of the unit tangent.
    mode : int
        The slip mode (+1 or -1).
    monodromy : ndarray (2n, 2n)
    system : System
        The model at ``value``.
    switches : list of (t, before, after)
        The switches of one period from ``state`` (none on a pure-slip cycle).
    n_sticks, n_reversals : int
        Stick phases and slip reversals a period.

    See Also
    --------
    beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem : makes them.

    Examples
    --------
    >>> from beltmdsm import Model, cycle
    >>> from beltmdsm.branches import continue_branch
    >>> c = cycle(Model(model="belt_1dof", friction="stribeck", Vb=2.5),
    ...           guess=[3.0182035, 2.0991444], period=6.3203187)
    >>> p = continue_branch(c, "Vb", 2.45, 2.55).point_near(2.5)
    >>> p.value, round(p.period, 6), p.stable, p.n_sticks
    (2.5, 6.320319, False, 0)
    >>> round(p.observables()["period"], 6), round(p.margin, 6)
    (6.320319, 0.400856)
    """

    value: float
    state: NDArray[np.float64]
    period: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    trivial_multiplier: complex = field(repr=False)
    max_abs_multiplier: float
    stable: bool
    margin: float
    curvature: float = field(repr=False)
    tangent: float = field(repr=False)
    mode: int = field(repr=False)
    monodromy: NDArray[np.float64] = field(repr=False)
    system: System = field(repr=False)
    column: NDArray[np.float64] | None = field(default=None, repr=False)
    recorded: dict[str, float] = field(default_factory=dict, repr=False)
    _observed: dict[str, float] | None = field(default=None, repr=False)
    switches: list = field(default_factory=list, repr=False)

    @property
    def n_sticks(self) -> int:
        return sum(1 for _, _, after in self.switches if after == STICK)

    @property
    def n_reversals(self) -> int:
        return sum(1 for _, b, a in self.switches if {b, a} == {1, -1})

    @property
    def stick_time(self) -> float:
        """Time stuck a period [s] (the run starts in slip, so every stick ends in it)."""
        times = [t for t, _, _ in self.switches]
        return float(sum(t1 - t0 for (t0, _, a), t1 in zip(self.switches, times[1:]) if a == STICK))

    @property
    def signature(self) -> tuple:
        """The switch structure: the switches ``(before, after)``, sorted."""
        return tuple(sorted((int(b), int(a)) for _, b, a in self.switches))

    def observables(self, vb: float | None = None) -> dict[str, float]:
        """The orbit's extremes (`beltmdsm.oscillator.orbit.orbit_observables`: the
        states' and the slip velocity's ranges, ``max_abs_v_r`` the largest slip speed),
        then ``period`` and ``max_abs_multiplier``; computed once (``vb`` unread)."""
        if self._observed is None:
            found = orbit_observables(self.system, self.state, self.period)
            found["period"] = self.period
            found["max_abs_multiplier"] = self.max_abs_multiplier
            self._observed = found
        return self._observed

    def cycle(self) -> Cycle:
        """The `beltmdsm.oscillator.cycle.Cycle` this point is."""
        y, M = self.state, self.monodromy
        return Cycle(self.system, y, self.mode, self.period, self.multipliers,
                     self.trivial_multiplier, M, list(self.switches), self.n_sticks, 0.0,
                     TOL, TOL)  # fmt: skip

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``state0``, ``state`` (by name), ``period``,
        ``multipliers`` (pairs), ``trivial_multiplier``, ``max_abs_multiplier``,
        ``stable``, ``margin``, ``n_sticks``, ``n_reversals``, ``observables``."""
        return {
            "value": self.value,
            "state0": [float(v) for v in self.state],
            "state": {n: float(v) for n, v in zip(self.system.states, self.state)},
            "period": self.period,
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "trivial_multiplier": [self.trivial_multiplier.real, self.trivial_multiplier.imag],
            "max_abs_multiplier": self.max_abs_multiplier,
            "stable": self.stable,
            "margin": self.margin,
            "n_sticks": self.n_sticks,
            "n_reversals": self.n_reversals,
            "observables": self.observables(),
        }
