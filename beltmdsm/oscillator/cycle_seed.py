"""The seed of a self-excited cycle of an unforced model: a settled run, read where the
shooting starts (`Seed`).

A run of ``settle`` seconds from a start (the guess, else steady sliding moved along its
least stable direction where it grows, then the stick state over steady sliding, from
which a stick-slip cycle coexisting with stable sliding is reached) is read:

* where it sticks (three stick ends or more): from its last state, stick end after
  stick end, until the ends repeat; ``k`` the least number of stick ends after which
  one repeats (up to `_MAX_STICKS`), the seed the state of that earlier end and the
  period the time over the ``k`` sticks. A run whose stick ends repeat after no such
  ``k`` is refused, never shot with a guessed ``k``;
* where it slips throughout and ends away from steady sliding: a run on, in chunks of
  100 s, until its least slip speed ``m v_r`` (the pure-slip shooting's section,
  `beltmdsm.oscillator.slip_shooting`) repeats to `SETTLE_TOL` of its distance from
  steady sliding's, as the paper's seed's returns do; the seed its last point there,
  the period the time since the one it repeats. A run that does not settle so (one
  still decaying slowly towards steady sliding) is refused, as the paper's is.

`beltmdsm.oscillator.self_excited_cycle` shoots from the seed; ``beltmdsm.seed_cycle``
of another model than the paper's returns its state and period.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicHermiteSpline

from ..errors import NoPeriodicResponse
from ..settings import SETTLE_TOL
from .equilibria import steady_sliding
from .guards import to_stick
from .hybrid import flow
from .stick_slip_shooting import _nth_end
from .system import STICK, System

__all__ = ["Seed", "cycle_seed"]

#: The most stick ends per period looked for, and the most stick ends a settled run
#: goes on for until they repeat (Hoffmann's model at mu_s = 1: 21 sticks a period,
#: its ends repeating to 1e-5 after some 7 periods).
_MAX_STICKS = 32
_MAX_ENDS = 8 * _MAX_STICKS
#: Chunks of 100 s a slipping run goes on for until its least slip speeds repeat.
_SLIP_CHUNKS = 4


@dataclass(frozen=True, repr=False)
class Seed:
    """Where a self-excited cycle is shot from.

    Attributes
    ----------
    state : ndarray (2n,)
        Where a stick ends (``sticks > 0``), else the point of least slip speed.
    mode : int
        The mode at ``state`` (slip, ``1`` or ``-1``).
    period : float
        The estimate of the period [s]: the time over ``sticks`` stick ends, or between
        two least slip speeds.
    sticks : int
        Stick ends per period; 0 for a pure-slip cycle.

    See Also
    --------
    cycle_seed : makes it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> cycle_seed(System("belt_1dof", friction="static_kinetic", Vb=0.5))
    Seed(period 8.61101 s, 1 sticks, mode -1)
    """

    state: NDArray[np.float64]
    mode: int
    period: float
    sticks: int

    def __repr__(self) -> str:
        kind = f"{self.sticks} sticks" if self.sticks else "pure slip"
        return f"Seed(period {self.period:.6g} s, {kind}, mode {self.mode})"


def cycle_seed(
    system: System,
    guess: ArrayLike | None = None,
    *,
    settle: float = 200.0,
    rtol: float = 1e-11,
    atol: float = 1e-11,
) -> Seed:
    """The seed of the self-excited cycle of an unforced ``system`` (module docstring).

    Parameters
    ----------
    system : System
        Without excitation (checked by the caller).
    guess : ndarray (2n,), optional
        The start of the run (checked by the caller); by default steady sliding moved
        along its least stable direction, then the stick state over steady sliding.
    settle : float
        The run's length [s].
    rtol, atol : float
        The integrator's tolerances.

    Returns
    -------
    Seed

    Raises
    ------
    NoPeriodicResponse
        Naming why: the runs decay onto steady sliding (or switch without sticking), a
        sticking run sticks no more, or its stick ends do not repeat.

    See Also
    --------
    beltmdsm.oscillator.self_excited_cycle : shoots the cycle from it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> s = cycle_seed(System("belt_1dof", friction="stribeck", Vb=1.5))
    >>> s.sticks, round(s.period, 4)
    (1, 6.6543)
    """
    tol = dict(rtol=rtol, atol=atol)
    for start in [guess] if guess is not None else _starts(system):
        run = flow(system, 0.0, start, settle, **tol)
        if sum(1 for s in run.switches if s[1] == STICK) >= 3:
            return _stick_ends(system, run.y, run.mode, settle, tol)
        if not run.switches and _moving(system, run):
            return _least_slip(system, run.y, tol)
    raise NoPeriodicResponse(
        f"{system!r}: no self-excited cycle found: the runs from "
        f"{'the guess' if guess is not None else 'steady sliding and from stick'} "
        f"settle on no cycle within {settle:g} s"
    )


def _starts(system):
    """Steady sliding moved along its least stable direction, where it grows; and the
    stick state over steady sliding (its position, the slip velocity 0), from which a
    stick-slip cycle coexisting with stable sliding is reached."""
    eq = steady_sliding(system)
    out = []
    if eq.growth_rate > 1e-9 * np.abs(eq.eigenvalues).max():
        J = np.asarray(system.kernels.jacobian(0.0, eq.state, system.p, eq.mode))
        w, V = np.linalg.eig(J)
        v = np.real(V[:, np.argmax(w.real)])
        out.append(eq.state + 1e-3 * (1.0 + np.abs(eq.state).max()) * v / np.abs(v).max())
    out.append(to_stick(system, 0.0, eq.state))
    return out


def _moving(system, seed):
    """Whether a run ends away from steady sliding (not decayed onto it)."""
    eq = steady_sliding(system)
    return np.abs(seed.y - eq.state).max() > 1e-6 * (1.0 + np.abs(eq.state).max())


def _stick_ends(system, y, mode, settle, tol) -> Seed:
    """From ``(y, mode)``, stick end after stick end: ``k`` stick ends per period, the
    least ``k <= _MAX_STICKS`` after which the ends repeat (an end ``n`` equal to the end
    ``n - k``, the first such ``n``; the seed is the end ``n - k``). A run that sticks no
    more within ``settle`` seconds is refused (it would run on without end)."""
    ends: list = []  # (state, mode, time from the end before)
    for n in range(_MAX_ENDS):
        r = flow(system, 0.0, y, settle, mode=mode, stop=_nth_end(1), **tol)
        if r.status != "stopped":
            raise NoPeriodicResponse(
                f"{system!r}: no stick-slip cycle found: the settled run sticks no more "
                f"within {settle:g} s after {n} stick ends (no cycle with a stick there)"
            )
        y, mode = r.y, r.mode
        k = next(
            (
                j
                for j in range(1, min(n, _MAX_STICKS) + 1)
                if ends[n - j][1] == mode and np.allclose(ends[n - j][0], y, rtol=1e-5, atol=1e-7)
            ),
            None,
        )
        if k is not None:
            period = sum(t for _, _, t in ends[n - k + 1 :]) + float(r.t)
            return Seed(ends[n - k][0], ends[n - k][1], period, k)
        ends.append((y, mode, float(r.t)))
    raise NoPeriodicResponse(
        f"{system!r}: no stick-slip cycle found: the stick ends of the settled run repeat "
        f"after no k <= {_MAX_STICKS} sticks within {len(ends)} sticks (it settles on no "
        "cycle of so few sticks)"
    )


def _least_slip(system, x, tol) -> Seed:
    """A pure-slip seed: the last point of a run where the slip speed ``m v_r`` is
    least, where the least speed repeats an earlier one to `SETTLE_TOL` of its distance
    from steady sliding's (the paper's rule, `beltmdsm.starts.cycle_seed`, on the
    section's one free value); the period the time since that one. A run whose least
    speeds do not repeat within `_SLIP_CHUNKS` chunks of 100 s (one still decaying
    slowly towards steady sliding, beside a Hopf point on its stable side) is refused."""
    k_, p = system.kernels, system.p
    steady = steady_sliding(system)
    rest = steady.mode * k_.slip_velocity(0.0, steady.state, p)  # steady sliding's speed
    t0, first = 0.0, None
    for _ in range(_SLIP_CHUNKS):
        samples: list = []
        end = flow(system, t0, x, t0 + 100.0, dt=0.01, samples=samples, **tol)
        if end.switches:
            raise NoPeriodicResponse(f"{system!r}: the seed run switches without sticking")
        mode = end.mode
        ts = np.concatenate([t for t, _, _ in samples])
        ys = np.concatenate([y for _, y, _ in samples])
        speed = np.array([mode * k_.slip_velocity(t, y, p) for t, y in zip(ts, ys)])
        low = np.flatnonzero((speed[1:-1] < speed[:-2]) & (speed[1:-1] <= speed[2:])) + 1
        if len(low) < 3:
            raise NoPeriodicResponse(f"{system!r}: the seed run settles on no cycle")
        depth = [rest - _least(system, mode, ts[i - 1 : i + 2], ys[i - 1 : i + 2]) for i in low]
        first = depth[0] if first is None else first
        for j in range(len(low) - 2, max(-1, len(low) - 10), -1):
            if abs(depth[-1] - depth[j]) <= SETTLE_TOL * abs(depth[-1]):
                return Seed(ys[low[-1]], mode, float(ts[low[-1]] - ts[low[j]]), 0)
        t0, x = end.t, end.y
    trend = (
        f": its least slip speed's distance from steady sliding's shrinks from {first:.3g} "
        f"to {depth[-1]:.3g} m/s, it decays slowly towards steady sliding"
        if abs(depth[-1]) < abs(first)
        else ""
    )
    raise NoPeriodicResponse(
        f"model {system.name!r}: no pure-slip cycle: the run slips throughout, and its "
        f"least slip speeds do not repeat to {SETTLE_TOL:g} within {t0:g} s{trend}"
    )


def _least(system, mode, t, y) -> float:
    """The least slip speed ``m v_r`` about the middle of three samples: the minimum of
    the cubic Hermite interpolant of ``m v_r`` and its rate ``m slip_acceleration``
    (its error ~ dt^4 / 384 times the speed's fourth derivative, far below
    `SETTLE_TOL` at dt = 0.01 s)."""
    k_, p = system.kernels, system.p
    v = [mode * k_.slip_velocity(ti, yi, p) for ti, yi in zip(t, y)]
    a = [mode * k_.slip_acceleration(ti, yi, p, mode) for ti, yi in zip(t, y)]
    spline = CubicHermiteSpline(t, v, a)
    roots = spline.derivative().roots(extrapolate=False)
    return float(min([v[1], *spline(roots)]))
