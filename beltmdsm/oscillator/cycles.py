"""Self-excited cycles of any unforced model by shooting, with their Floquet multipliers.

The period is an unknown. Newton's method solves the bordered system

    [[M - I, f(x_T)], [c^T, 0]] [dx, dT] = -[x_T - x, c(x)]

``M`` the monodromy of the run by its variational equations with the saltation matrix
at every switch (`beltmdsm.oscillator.hybrid.flow`), ``f`` the derived field at the end,
``c`` the phase condition:

* **stick-slip**: a cycle with a stick is fixed by the state where a stick ends (a
  single point of the orbit): the run from there goes to the ``k``-th end of a stick
  (``x_T``), and ``c`` is that surface, ``|holding_force| - stick_limit`` (its gradient
  by central differences of the two kernels: it steers Newton's steps only);
* **pure slip**: a Poincare section where the slip speed ``m v_r`` is least
  (``slip_acceleration = 0``, the point of the orbit closest to stick: its slip
  velocity there measures the distance to the stick onset, `stick_onset`); the run
  goes over ``T``.

The period reported is the least: no proper divisor of the ``k`` sticks (or ``T/j``,
``j <= 6``, of a pure-slip cycle) returns to the state. ``k`` is the least number of
stick ends after which the settled run's stick ends repeat (up to 32); a run whose
stick ends repeat after none is refused, never shot with a guessed ``k``. Every cycle
reported is a genuine return (`genuine`): it comes back in the mode it left, and a slip
phase of it lasts longer than a rounding artefact of its integration at ``rtol`` and
``atol`` (the bordered system is also solved by the trivial return ``T -> 0`` at a
point where a stick ends and begins again at once). The multipliers are the
eigenvalues of ``M``; the trivial one (its eigenvector closest to the field, ``M f =
f``) is reported apart, its distance from 1 measuring the accuracy; a stick gives a
multiplier 0. A seed (`beltmdsm.oscillator.cycle_seed`) is a run settled over
``settle`` seconds from ``guess``, else from steady sliding moved along its least stable
direction (where it grows) and then from the stick state over steady sliding (where a
stick-slip cycle coexists with stable sliding, as under Stribeck's law above its Hopf
point).

The pieces, one module each: the result and its check (`beltmdsm.oscillator.cycle`),
the seed (`beltmdsm.oscillator.cycle_seed`), the two shootings
(`beltmdsm.oscillator.stick_slip_shooting`, `beltmdsm.oscillator.slip_shooting`) and the
onset of stick (`beltmdsm.oscillator.onset`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..errors import Unsupported
from .cycle import NEWTON_TOL, Cycle, genuine
from .cycle_seed import Seed, _stick_ends, cycle_seed
from .hybrid import flow
from .onset import stick_onset
from .slip_shooting import _shoot_slip
from .stick_slip_shooting import _newton_stick
from .system import STICK, System

__all__ = ["Cycle", "self_excited_cycle", "stick_onset", "genuine", "NEWTON_TOL"]


def self_excited_cycle(
    system: System,
    guess: ArrayLike | None = None,
    period: float | None = None,
    *,
    settle: float = 200.0,
    max_iter: int = 30,
    rtol: float = 1e-11,
    atol: float = 1e-11,
) -> Cycle:
    """The self-excited cycle of an unforced model, by shooting.

    Parameters
    ----------
    system : System
        Without excitation (every amplitude 0).
    guess : array_like (2n,), optional
        A state near the cycle; steady sliding moved along its least stable direction
        by default. A run of ``settle`` seconds from it seeds the shooting.
    period : float, optional
        With ``guess``: ``guess`` is then taken as the seed itself (a pure-slip cycle
        near its unstable branch, where a run would leave it; where the run from it
        over ``period`` sticks, the stick-slip cycle is shot from its next stick ends,
        as from `cycle_seed`'s state and period).
    settle : float
        The seed run's length [s].
    max_iter : int
    rtol, atol : float
        The integrator's tolerances.

    Returns
    -------
    Cycle

    Raises
    ------
    ValueError
        ``guess`` not ``2n`` finite numbers, ``period`` not positive.
    Unsupported
        A forced model (`beltmdsm.oscillator.forced_response` computes its response).
    NoPeriodicResponse
        Newton's method does not converge, or the seed run settles on no cycle.

    See Also
    --------
    beltmdsm.oscillator.steady_sliding : the equilibrium whose instability feeds it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=1.5))
    >>> c.kind, round(c.period, 6), c.sticks
    ('stick_slip', 6.654342, 1)
    >>> bool(abs(c.multipliers[0]) < 1e-8), abs(c.trivial_multiplier - 1) < 1e-8
    (True, True)
    """
    if system.excitation_period() is not None:
        raise Unsupported(
            f"model {system.name!r}: the excitation is on (an amplitude is not 0): a "
            "self-excited cycle needs the autonomous model; forced_response computes "
            "the forced response"
        )
    tol = dict(rtol=rtol, atol=atol)
    m = len(system.states)
    if guess is not None:
        guess = np.asarray(guess, dtype=float)
        if guess.shape != (m,) or not np.all(np.isfinite(guess)):
            raise ValueError(f"guess: not {m} finite numbers ({', '.join(system.states)})")
    if period is not None and not (np.isfinite(period) and period > 0):
        raise ValueError(f"period={period!r}: not a positive number")
    if guess is not None and period is not None:
        # a run over the period, up to where it first sticks (a stop, not its end: a
        # stick that ends exactly at the end of a run is a case the stepper does not
        # finish, as where the guess is a stick end and the period its estimate)
        run = flow(system, 0.0, guess, float(period), stop=_sticks, **tol)
        if run.status != "stopped":
            return _shoot_slip(system, guess, float(period), max_iter, tol)
        # a stick-slip seed: shot from its stick ends (`cycle_seed`), from the guess on
        return _shoot(system, _stick_ends(system, guess, None, settle, tol), max_iter, tol)
    return _shoot(system, cycle_seed(system, guess, settle=settle, **tol), max_iter, tol)


def _sticks(switch, n) -> bool:
    """A stop at the first switch into stick."""
    return switch[2] == STICK


def _shoot(system: System, seed: Seed, max_iter: int, tol: dict) -> Cycle:
    """The cycle shot from ``seed``: from its stick end over its ``sticks``, or on the
    section of least slip speed over its period."""
    if seed.sticks:
        return _newton_stick(system, seed.state, seed.mode, seed.sticks, max_iter, tol)
    return _shoot_slip(system, seed.state, seed.period, max_iter, tol)
