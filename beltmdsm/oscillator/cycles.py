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
phase of it lasts at least ``1e-6`` of steady sliding's shortest time scale (the
bordered system is also solved by the trivial return ``T -> 0`` at a point where a stick
ends and begins again at once). The multipliers are the
eigenvalues of ``M``; the trivial one (its eigenvector closest to the field, ``M f =
f``) is reported apart, its distance from 1 measuring the accuracy; a stick gives a
multiplier 0. A seed is a run settled over ``settle`` seconds from ``guess``, else
from steady sliding moved along its least stable direction (where it grows) and then
from the stick state over steady sliding (where a stick-slip cycle coexists with
stable sliding, as under Stribeck's law above its Hopf point).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse, Unsupported
from .equilibria import steady_sliding
from .hybrid import Switch, _to_stick, flow
from .system import STICK, System

__all__ = ["Cycle", "self_excited_cycle", "stick_onset", "genuine", "NEWTON_TOL"]

#: Newton's method stops when the run returns to its start to this (relative to the
#: state's scale).
NEWTON_TOL = 1e-10
#: A proper divisor of the period "returns" where the state comes back to this.
_RETURN_TOL = 1e-6
#: Divisors of a pure-slip cycle's period checked for a return.
_DIVISORS = 6
#: Halvings of a Newton step before the method counts as stalled.
_HALVINGS = 10
#: The most stick ends per period looked for, and the most stick ends a settled run
#: goes on for until they repeat (Hoffmann's model at mu_s = 1: 21 sticks a period,
#: its ends repeating to 1e-5 after some 7 periods).
_MAX_STICKS = 32
_MAX_ENDS = 8 * _MAX_STICKS
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
    >>> from beltmdsm.oscillator import System
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
        near its unstable branch, where a run would leave it).
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
        return _shoot_slip(system, guess, float(period), max_iter, tol)
    for start in [guess] if guess is not None else _starts(system):
        seed = flow(system, 0.0, start, settle, **tol)
        if sum(1 for s in seed.switches if s[1] == STICK) >= 3:
            return _shoot_stick_slip(system, seed, settle, max_iter, tol)
        if not seed.switches and _moving(system, seed):
            return _seed_slip(system, seed.y, max_iter, tol)
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
    out.append(_to_stick(system, 0.0, eq.state))
    return out


def _moving(system, seed):
    """Whether a run ends away from steady sliding (not decayed onto it)."""
    eq = steady_sliding(system)
    return np.abs(seed.y - eq.state).max() > 1e-6 * (1.0 + np.abs(eq.state).max())


def _shoot_stick_slip(system, seed, settle, max_iter, tol):
    """From a stick end of a settled run: ``k`` stick ends per period, the least ``k
    <= _MAX_STICKS`` after which the run's stick ends repeat (an end ``n`` equal to the
    end ``n - k``, the first such ``n``; from the end ``n - k``). A run that sticks no
    more within ``settle`` seconds is refused (it would run on without end)."""
    ends: list = []
    y, mode = seed.y, seed.mode
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
            return _newton_stick(system, *ends[n - k], k, max_iter, tol)
        ends.append((y, mode))
    raise NoPeriodicResponse(
        f"{system!r}: no stick-slip cycle found: the stick ends of the settled run repeat "
        f"after no k <= {_MAX_STICKS} sticks within {len(ends)} sticks (it settles on no "
        "cycle of so few sticks)"
    )


def _nth_end(k):
    count = [0]

    def stop(switch, n):
        if switch[1] == STICK:
            count[0] += 1
        return count[0] == k

    return stop


def _end_states(system, x, mode, k, tol):
    """The states at the next ``k`` ends of a stick from ``x``."""
    out = []
    y, md = x, mode
    for _ in range(k):
        r = flow(system, 0.0, y, np.inf, mode=md, stop=_nth_end(1), **tol)
        if r.status != "stopped":
            break
        y, md = r.y, r.mode
        out.append(y)
    return out


def _newton_stick(system, x, mode, k, max_iter, tol):
    k_ = system.kernels
    p = system.p
    m = x.size

    def surface(y):
        return abs(k_.holding_force(0.0, y, p)) - k_.stick_limit(0.0, y, p)

    scale = 1.0 + np.abs(x).max()
    for _ in range(max_iter):
        run = flow(system, 0.0, x, np.inf, mode=mode, variational=True, stop=_nth_end(k), **tol)
        if run.status != "stopped":
            raise NoPeriodicResponse(f"{system!r}: the run from a stick end does not stick again")
        # a step onto a stick end that sticks at once returns trivially (T -> 0)
        why = _not_a_return(system, mode, run.t, run.switches)
        if why:
            raise NoPeriodicResponse(f"{system!r}: no stick-slip cycle found: Newton's {why}")
        r = run.y - x
        residual = float(np.abs(r).max())
        if residual <= NEWTON_TOL * scale:
            break
        eps = 1e-7 * scale
        grad = np.array(
            [(surface(x + eps * e) - surface(x - eps * e)) / (2 * eps) for e in np.eye(m)]
        )
        f = np.asarray(k_.field(run.t, run.y, p, run.mode), dtype=float)
        A = np.block([[run.monodromy - np.eye(m), f[:, None]], [grad[None, :], np.zeros((1, 1))]])
        step = np.linalg.lstsq(A, -np.concatenate((r, [surface(x)])), rcond=None)[0]
        x = x + step[:m]
    else:
        raise NoPeriodicResponse(
            f"{system!r}: no stick-slip cycle found: Newton's method left a residual "
            f"{residual:.2e} after {max_iter} iterations"
        )
    for j in (j for j in range(1, k) if k % j == 0):
        back = _end_states(system, x, mode, j, tol)
        if len(back) == j and np.abs(back[-1] - x).max() <= _RETURN_TOL * scale:
            return _newton_stick(system, x, mode, j, max_iter, tol)
    return _cycle(system, x, mode, run, residual)


def _seed_slip(system, x, max_iter, tol):
    """A pure-slip seed: the last point of a run where the slip speed ``m v_r`` is
    least, the period from its last two minima."""
    k_, p = system.kernels, system.p
    samples: list = []
    end = flow(system, 0.0, x, 100.0, dt=0.01, samples=samples, **tol)
    if end.switches:
        raise NoPeriodicResponse(f"{system!r}: the seed run switches without sticking")
    mode = end.mode
    ts = np.concatenate([t for t, _, _ in samples])
    ys = np.concatenate([y for _, y, _ in samples])
    speed = np.array([mode * k_.slip_velocity(t, y, p) for t, y in zip(ts, ys)])
    low = np.flatnonzero((speed[1:-1] < speed[:-2]) & (speed[1:-1] <= speed[2:])) + 1
    if len(low) < 3:
        raise NoPeriodicResponse(f"{system!r}: the seed run settles on no cycle")
    return _shoot_slip(system, ys[low[-1]], ts[low[-1]] - ts[low[-2]], max_iter, tol)


def _shoot_slip(system, x, T, max_iter, tol):
    """Newton's method on ``(x, T)``, the section where the slip speed is least
    (``slip_acceleration = 0``: its gradient ``J^T w`` by the derived Jacobian)."""
    k_, p = system.kernels, system.p
    x = np.asarray(x, dtype=float)
    m = x.size
    mode = _mode(system, x)
    scale = 1.0 + np.abs(x).max()
    run = flow(system, 0.0, x, T, mode=mode, variational=True, **tol)
    if run.switches:
        raise NoPeriodicResponse(
            f"{system!r}: the run from the guess switches at t = {run.switches[0][0]:.6g} s: "
            "no pure-slip cycle through it"
        )
    for _ in range(max_iter):
        r = run.y - x
        residual = float(np.abs(r).max())
        if residual <= NEWTON_TOL * scale:
            break
        w = np.asarray(k_.slip_gradient(0.0, x, p), dtype=float)
        grad = np.asarray(k_.jacobian(0.0, x, p, mode), dtype=float).T @ w
        f = np.asarray(k_.field(T, run.y, p, mode), dtype=float)
        A = np.block([[run.monodromy - np.eye(m), f[:, None]], [grad[None, :], np.zeros((1, 1))]])
        b = -np.concatenate((r, [k_.slip_acceleration(0.0, x, p, mode)]))
        step = np.linalg.solve(A, b)
        # damped: a step that reaches a switch or does not reduce the residual is halved
        for _ in range(_HALVINGS):
            trial = flow(system, 0.0, x + step[:m], T + step[m], mode=mode, variational=True, **tol)
            if not trial.switches and np.abs(trial.y - x - step[:m]).max() < residual:
                break
            step = 0.5 * step
        else:
            raise NoPeriodicResponse(
                f"{system!r}: no slip cycle found: Newton's method stalled at a residual "
                f"{residual:.2e} (no step of {_HALVINGS} halvings reduces it)"
            )
        x, T, run = x + step[:m], T + step[m], trial
    else:
        raise NoPeriodicResponse(
            f"{system!r}: no slip cycle found: Newton's method left a residual "
            f"{residual:.2e} after {max_iter} iterations"
        )
    # the scale of the orbit: the distance the flow covers in a period
    size = np.abs(np.asarray(k_.field(0.0, x, p, mode), dtype=float)).max() * T
    if size <= NEWTON_TOL * scale:  # every T returns there: no least period to test
        raise NoPeriodicResponse(
            f"{system!r}: Newton's method converged on steady sliding, not on a cycle"
        )
    for j in range(_DIVISORS, 1, -1):
        back = flow(system, 0.0, x, T / j, mode=mode, **tol)
        if np.abs(back.y - x).max() <= _RETURN_TOL * size:
            return _shoot_slip(system, x, T / j, max_iter, tol)
    return _cycle(system, x, mode, run, residual)


def _mode(system, x):
    v = system.kernels.slip_velocity(0.0, x, system.p)
    return 1 if v > 0.0 else -1


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
    >>> from beltmdsm.oscillator import System
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


#: The bracket of the stick onset, relative, where the last pure-slip cycle is taken.
_BRACKET = 1e-10


def stick_onset(
    cycle: Cycle, parameter: str, step: float, *, tol: float = 1e-12, max_iter: int = 40
) -> Cycle:
    """The pure-slip cycle where its least slip speed reaches 0: the onset of stick.

    From ``cycle`` (pure slip) the parameter moves by ``step`` towards the onset, then
    by the secant of the least slip speed ``m v_r`` (the slip velocity on the cycle's
    section), each cycle shot from the one before; a value where no pure-slip cycle is
    found (past the onset) is halved back.

    Parameters
    ----------
    cycle : Cycle
        A pure-slip cycle.
    parameter : str
    step : float
        The first step in the parameter, towards the onset.
    tol : float
        The least slip speed at the onset, relative to ``1 + |state|``.
    max_iter : int

    Returns
    -------
    Cycle
        The grazing cycle; ``cycle.system.params[parameter]`` is the onset.

    Raises
    ------
    ValueError
        A cycle with a stick, or an unknown parameter.
    NoPeriodicResponse
        No onset within ``max_iter`` steps.

    See Also
    --------
    self_excited_cycle : the cycle to start from.

    Examples
    --------
    >>> from beltmdsm.oscillator import System
    >>> slip = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5),
    ...                           [3.0182035, 2.0991444], 6.3203187)
    >>> onset = stick_onset(slip, "Vb", 0.2)
    >>> round(onset.system.params["Vb"], 6)
    2.900393
    """
    if cycle.sticks or cycle.switches:
        raise ValueError("cycle: has switches; the stick onset starts from a pure-slip cycle")
    if parameter not in cycle.system.params:
        raise ValueError(f"parameter={parameter!r}: not a parameter of {cycle.system!r}")

    def speed(c):
        k = c.system.kernels
        return c.mode * k.slip_velocity(0.0, c.state, c.system.p)

    good = [(cycle.system.params[parameter], speed(cycle), cycle)]
    value = good[-1][0] + step
    for _ in range(max_iter):
        last = good[-1][2]
        try:
            c = _shoot_slip(
                last.system.replace(**{parameter: value}),
                last.state,
                last.period,
                30,
                dict(rtol=1e-11, atol=1e-11),
            )
        except NoPeriodicResponse:
            # past the onset (the run grazes or sticks): bisect back; a bracket that has
            # shrunk to 1e-10 leaves the last pure-slip cycle as the grazing one (its
            # least slip speed is then below the integration's resolution of a switch)
            if abs(value - good[-1][0]) <= _BRACKET * (1.0 + abs(value)):
                return good[-1][2]
            value = 0.5 * (value + good[-1][0])
            continue
        good.append((value, speed(c), c))
        if abs(good[-1][1]) <= tol * (1.0 + np.abs(c.state).max()):
            return c
        (v0, s0, _), (v1, s1, _) = good[-2], good[-1]
        if abs(v1 - v0) <= _BRACKET * (1.0 + abs(v1)):
            return c  # the secant moves below the parameter's resolution: at the onset
        value = v1 - s1 * (v1 - v0) / (s1 - s0)
    raise NoPeriodicResponse(
        f"{cycle.system!r}: no stick onset in {parameter} found in {max_iter} steps"
    )
