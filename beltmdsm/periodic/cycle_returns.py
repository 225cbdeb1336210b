"""Where a self-excited cycle returns: its section, its stick end and its least period.

A cycle's state is read where ``X1'`` has its extremum of largest ``|Vr|`` (the section
of `beltmdsm.periodic.cycle`); `section_returns` finds those extrema on a run. A period
found from such returns, or given, may be a multiple of the least one: a run that
passes the section ``k`` times per period closes after every ``k``-th pass as well as
after each, and shooting converges on either. Two facts give the least period:

* **A stick-slip cycle passes one state where its sticks end** (`stick_slip_start`):
  while the mass sticks ``X1' = Vb`` whatever came before, the normal motion sits at
  its equilibrium on the cycle (it is free of the tangential state: the laws' fact
  ``one_way_coupling``) and the stick ends where the spring's force leaves the friction
  cone, ``beltmdsm.starts.cycle_seed.stick_end``. The run from there to the next end of a
  stick is one least period, found without Newton's method: the cycle is superstable
  (its multiplier 0), and a run that sticks once is on it.
* **No proper divisor of the period returns** (`first_return`): where the orbit passes
  the section again at an earlier time, within `RETURN_TOL` of its state, the cycle is
  shot again with that shorter period.

`rest_step` bounds a run's steps where the state rests (a long stick): see there.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from beltmdsm.generated import unforced

from ..errors import NoPeriodicResponse, StepTooSmall
from ..integrate.events import integrate_events
from ..integrate.switching import Mode, Switching
from ..model import Backend, Model
from ..settings import SolverSettings

__all__ = ["rest_step", "section_returns", "stick_slip_start", "first_return", "RETURN_TOL"]

#: A pass of the section within this of the state's scale (``1 + max |x|``) counts as a
#: return of the orbit: far above the shooting's tolerance (1e-11), far below the
#: distance between the passes of a cycle of a multiple period (the square root of the
#: distance from its period-doubling point).
RETURN_TOL = 1e-6
#: Samples per turn ``2 pi / omega1`` when a run is searched for the section's extrema.
_SAMPLES = 64
#: A run that does not stick within this many turns, with ``X1'`` varying by less than
#: `_DECAYED` of ``|Vb|`` over one of them, has decayed to steady sliding (as
#: `beltmdsm.starts.cycle_seed`).
_CHUNK_TURNS = 10
_DECAYED = 1e-6


def rest_step(model: Model) -> float:
    """The longest step of a run on a cycle: ``1 / rate``, the fastest rate of the motion
    that rests while the mass sticks (the normal block of ``J^0``, and ``omega1``).

    The step control sees the state only. While the mass sticks the normal motion sits
    at its equilibrium and the tangential one moves with the belt, so the steps grow to
    seconds, and ``h |lambda| > 6`` lies outside the stability region of DOP853: the
    rounding of the normal state then grows by orders of magnitude over a long stick
    (1e-16 to 4e-8 over 9 s at ``Vb = 0.26`` under ``static_kinetic``), the friction limit
    moves with it and the end of the stick with it, and Newton's method on a cycle
    stalls at that noise. Steps of ``h |lambda| <= 1`` keep it at the rounding.

    Parameters
    ----------
    model : Model
        Without excitation.

    Returns
    -------
    float
        The bound [s].

    See Also
    --------
    beltmdsm.integrate.events.integrate_events : Takes it as ``max_step``.

    Examples
    --------
    The base contact's fast normal eigenvalue is -5.661 1/s:

    >>> round(rest_step(Model(friction="stribeck", alpha=0.0, Vb=1.5)), 4)
    0.1767
    """
    J = np.array(
        unforced.jacobian_at_equilibrium(**model.arguments(unforced.jacobian_at_equilibrium)),
        dtype=float,
    ).reshape(4, 4)
    rate = max(float(np.max(np.abs(np.linalg.eigvals(J[2:, 2:])))), float(model["omega1"]))
    return 1.0 / rate


def run_from(model: Model, y, t0: float, t1: float, backend: Backend | None, rtol: float):
    """The event-driven run from ``y`` at ``t0`` to ``t1``, its steps bounded by `rest_step`
    (raises NoPeriodicResponse where it stops)."""
    settings = SolverSettings(
        t_end=t1, rtol=rtol, atol=rtol, dt=(t1 - t0) / 50, t_discard=t0, backend=backend
    )
    try:
        run = integrate_events(
            model, settings, y0=np.array(y, dtype=float), t0=t0, max_step=rest_step(model)
        )
    except StepTooSmall as err:
        raise NoPeriodicResponse(f"no self-excited cycle found: {err}") from None
    if run.status != "done":
        raise NoPeriodicResponse(f"no self-excited cycle found: {run.message}")
    return run


def section_returns(sw: Switching, state, spans, d: int, step: float) -> list:
    """``(t, state, depth)`` of the interior extrema of ``X1'`` in the slip mode ``d``.

    Parameters
    ----------
    sw : Switching
        The model's switching rules (its field).
    state : callable
        ``t -> (4, n)``: a run's dense output.
    spans : iterable of (t0, t1, mode)
        The run's segments.
    d : int
        The slip mode of the section (`beltmdsm.starts.cycle_seed.section_direction`).
    step : float
        The spacing of the samples searched for extrema [s].

    Returns
    -------
    list of (float, numpy.ndarray, float)
        Each extremum's time (where ``X1''`` vanishes, by bisection), state and depth
        ``d X1'``: the largest is the section's point.

    See Also
    --------
    beltmdsm.periodic.cycle_returns.first_return : Reads them for the least period.

    Examples
    --------
    One period of the stick-slip cycle at ``Vb = 1.5`` from where its stick ends: the slip
    phase has one extremum of ``X1'``, at -2.0338 m/s:

    >>> from beltmdsm.starts.cycle_seed import stick_end
    >>> from beltmdsm.model import Model
    >>> model = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    >>> tr = run_from(model, stick_end(model), 0.0, 6.654341995080, "python", 1e-12).trajectory
    >>> spans = [(s.t0, s.t1, s.mode) for s in tr.segments]
    >>> found = section_returns(Switching(model), tr.state, spans, -1, 0.1)
    >>> [round(float(depth), 4) for _, _, depth in found]
    [2.0338]
    """
    out = []
    for t0, t1, mode in spans:
        if int(mode) != d or t1 - t0 < 2 * step:
            continue
        t = np.linspace(t0, t1, int((t1 - t0) / step) + 2)
        w = d * state(t)[1]
        for k in np.flatnonzero((w[1:-1] > w[:-2]) & (w[1:-1] >= w[2:])) + 1:
            s = _extremum(sw, state, d, t[k - 1], t[k + 1])
            y = state(np.array([s]))[:, 0]
            out.append((s, y, d * y[1]))
    return out


def _extremum(sw, state, d, a, b):
    """Where ``X1''`` vanishes in ``[a, b]`` (slip mode ``d``), by bisection on the field."""

    def accel(s):
        return float(sw.field(s, *state(np.array([s]))[:, 0], float(d))[1])

    fa = accel(a)
    while b - a > 1e-13 * max(1.0, abs(b)):
        m = 0.5 * (a + b)
        fm = accel(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def _turn(model: Model) -> float:
    return 2 * math.pi / float(model["omega1"])


def stick_slip_start(
    model: Model, end: NDArray[np.float64], d: int, t_end: float, backend: Backend | None
) -> tuple[NDArray[np.float64], float] | None:
    """The stick-slip cycle through the stick end ``end``: ``(state on the section, least
    period)``; None where the run from there does not stick again within ``t_end``.

    Parameters
    ----------
    model : Model
        Without excitation.
    end : numpy.ndarray, shape (4,)
        The state where a stick ends (`beltmdsm.starts.cycle_seed.stick_end`).
    d : int
        The slip mode of the section.
    t_end : float
        The longest run [s].
    backend : {"python", "numba", None}
        The kernels.

    Returns
    -------
    tuple or None
        The deepest extremum of ``X1'`` over one period (the section's point) and the
        time from ``end`` to the next end of a stick.

    See Also
    --------
    beltmdsm.starts.cycle_seed.seed_cycle : Calls it where its run sticks.

    Examples
    --------
    Under static and kinetic friction at ``Vb = 0.31`` the cycle sticks once a period
    of 11.4605 s (a period twice as long closes too):

    >>> from beltmdsm.starts.cycle_seed import stick_end
    >>> from beltmdsm.model import Model
    >>> model = Model(friction="static_kinetic", alpha=0.0, Vb=0.31)
    >>> state, period = stick_slip_start(model, stick_end(model), -1, 1e3, "python")
    >>> round(period, 4), round(float(state[1]), 5)
    (11.4605, -1.24409)
    """
    if not model.fact("one_way_coupling")[0]:
        return None  # the normal motion need not rest on the cycle: no single stick end
    vb = abs(float(model["Vb"]))
    t, y, chunk = 0.0, np.array(end, dtype=float), _CHUNK_TURNS * _turn(model)
    period = entered = None
    while t < t_end:
        t1 = min(t + chunk, t_end)
        chunk *= 2
        run = run_from(model, y, t, t1, backend, 1e-12)
        tr = run.trajectory
        for s, kind, new in run.events:
            if kind == "unstick" and entered is not None:
                period = float(s)
                break
            if Mode(int(new)) == Mode.STICK:
                entered = float(s)
        if period is not None:
            break
        v = tr.state(np.linspace(t, t1, 64 * _CHUNK_TURNS))[1]
        if tr.time_in_modes(t, t1)[Mode.STICK] == 0 and np.ptp(v) <= _DECAYED * vb:
            return None
        t, y = t1, tr.state(np.array([t1]))[:, 0]
    if period is None:
        return None
    back = tr.state(np.array([period]))[:, 0]
    if np.max(np.abs(back - end)) > RETURN_TOL * (1.0 + np.max(np.abs(end))):
        return None  # it stuck again, but not at this end (another edge): no single state
    # the slip phase from the start to the stick, read on a run that ends in the stick
    tr = run_from(model, end, 0.0, 0.5 * (entered + period), backend, 1e-12).trajectory
    spans = [(s.t0, s.t1, s.mode) for s in tr.segments]
    found = section_returns(Switching(model), tr.state, spans, d, _turn(model) / _SAMPLES)
    if not found:
        return None
    _, state, _ = max(found, key=lambda r: r[2])
    return state, period


def first_return(sw: Switching, period, x, d: int, T: float) -> float | None:
    """The first time in ``(0, T)`` at which the orbit through ``x`` passes the section
    within `RETURN_TOL` of ``x`` (a proper divisor of ``T`` returns), else None.

    Parameters
    ----------
    sw : Switching
        The model's switching rules.
    period : beltmdsm.periodic.general_map.EventPeriod
        The run of ``T`` from ``x``.
    x : numpy.ndarray, shape (4,)
        The cycle's state on the section.
    d : int
        The slip mode of the section.
    T : float
        The period found.

    Returns
    -------
    float or None
        The shorter period.

    See Also
    --------
    beltmdsm.periodic.cycle.cycle : Shoots again with it.

    Examples
    --------
    The static and kinetic cycle at ``Vb = 0.31`` run over twice its period passes its
    state again at 11.4605 s:

    >>> from beltmdsm.starts.cycle_seed import stick_end
    >>> from beltmdsm.model import Model
    >>> from beltmdsm.periodic.general_map import EventPeriod
    >>> model = Model(friction="static_kinetic", alpha=0.0, Vb=0.31)
    >>> x, T = stick_slip_start(model, stick_end(model), -1, 1e3, "python")
    >>> run = run_from(model, x, 0.0, 2 * T, "python", 1e-12)
    >>> shorter = first_return(Switching(model), EventPeriod.of(run, []), x, -1, 2 * T)
    >>> round(shorter, 4)
    11.4605
    """
    spans = zip(period.starts, period.ends, period.modes)
    step = min(T, _turn(sw.model)) / _SAMPLES
    tol = RETURN_TOL * (1.0 + float(np.max(np.abs(x))))
    for t, y, _ in section_returns(sw, period.segments, spans, d, step):
        if step < t < T - step and float(np.max(np.abs(y - x))) <= tol:
            return float(t)
    return None
