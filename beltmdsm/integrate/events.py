"""Event-driven integration of Eq. (4): one smooth mode at a time, every switch located.

The general integrator of the package, and the fallback of
`beltmdsm.integrate.superposition`. It runs the compiled Dormand-Prince 8(5,3)
integrator (`beltmdsm.integrate._dop853`) on the generated field of the current mode
(`beltmdsm.generated.hybrid.vector_field`) until one of the mode's guard surfaces is crossed
(`beltmdsm.generated.hybrid.GUARDS`), then lets `beltmdsm.integrate.switching` choose the next
mode, and goes on. Nothing is stepped over: the run is a sequence of smooth segments
joined at located switches. Accumulating switches are handled by
`beltmdsm.integrate.zeno`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import StepTooSmall
from ..excitation import initial_state
from ..model import Model
from ..settings import SolverSettings, fastest_rate
from . import _compiled, _dop853
from .switching import Mode, Switching
from .trajectory import Run, Segment, Trajectory
from .zeno import Zeno

__all__ = ["integrate_events", "StepSegment", "StepTooSmall", "check_status", "REST_STEP"]

#: The longest step in stick times the fastest rate of the model
#: (`beltmdsm.settings.fastest_rate`).
#: The step control sees the state only: at rest (a mass stuck without excitation) the
#: steps grew to 114 s, far outside DOP853's stability region for the contact's
#: oscillation (rate 5.66 1/s), which then amplified the rounding of the state to
#: 1e-7 m/s and the energy quadrature over those steps to a viscous work of 4e-4
#: (``simulate --Vb 0 --alpha 0 --t-end 5000``). At ``h |lambda| <= 1`` the method is
#: well inside that region; a moving run's steps at rtol = 1e-10 are far shorter.
REST_STEP = 1.0


def check_status(code: int, t: float, where: str, rtol: float, atol: float) -> None:
    """Raise the named failure of an `beltmdsm.integrate._dop853.advance` status that is
    neither its end nor an event: `StepTooSmall` (the step below the rounding of the
    time, a state that is not finite, more than `_dop853.MAX_STEPS` steps).

    ``where`` says where the run is (``"in mode slip_back"``, ``"in the normal motion"``).

    Parameters
    ----------
    code : int
        The status of ``advance`` (``_dop853.STATUS_*``).
    t : float
        The time reached [s].
    where : str
        Where the run is, for the message.
    rtol, atol : float
        The run's tolerances, for the message and the exception.

    Raises
    ------
    beltmdsm.errors.StepTooSmall
        For a status of failure, naming the time, ``where`` and the tolerances.

    See Also
    --------
    beltmdsm.errors.StepTooSmall : The failure raised.

    Examples
    --------
    The end of a step passes; a state that is no longer finite is a failure:

    >>> check_status(_dop853.STATUS_END, 3.0, "in mode slip_back", 1e-10, 1e-10)
    >>> try:
    ...     check_status(_dop853.STATUS_NOT_FINITE, 3.0, "in mode slip_back", 1e-10, 1e-10)
    ... except StepTooSmall as failure:
    ...     print(failure)
    the state is not finite (NaN or an overflow) at t = 3 s in mode slip_back: ...
    """
    if code == _dop853.STATUS_STEP_TOO_SMALL:
        raise StepTooSmall(
            f"the integrator's step fell below the rounding of the time at "
            f"t = {t:.6g} s {where} at rtol = {rtol:g}, atol = {atol:g}: tolerances this "
            "loose let the state drift across a switching surface between steps (tighten "
            "them), or tolerances this tight ask for more than the rounding allows "
            "(loosen them)",
            rtol,
            atol,
        )
    if code == _dop853.STATUS_NOT_FINITE:
        raise StepTooSmall(
            f"the state is not finite (NaN or an overflow) at t = {t:.6g} s {where}: "
            "the parameters put the motion beyond floating point",
            rtol,
            atol,
        )
    if code == _dop853.STATUS_TOO_MANY_STEPS:
        raise StepTooSmall(
            f"the integrator took more than {_dop853.MAX_STEPS} steps (MAX_STEPS, "
            f"beltmdsm/integrate/_dop853.py) by t = {t:.6g} s {where} at rtol = {rtol:g}, "
            f"atol = {atol:g}: a field this stiff needs more steps than a run can keep "
            "(shorten t_end or loosen the tolerances)",
            rtol,
            atol,
        )


class StepSegment:
    """The dense output of a run of DOP853 steps: ``evaluate(t[, index]) -> (4, n)``.

    Built over the steps of all segments of a run (they follow each other in time,
    each switch starting a new step), it evaluates the whole trajectory at once.

    Parameters
    ----------
    t_steps, h_steps : numpy.ndarray
        The start and length of each step [s].
    y_steps, F_steps : numpy.ndarray
        The state at each step's start and the coefficients of its dense output.

    See Also
    --------
    beltmdsm.integrate.trajectory.Trajectory : Holds it as its ``evaluator``.

    Examples
    --------
    A run's evaluator gives back its start, the unforced equilibrium at rest:

    >>> from beltmdsm.settings import SolverSettings
    >>> run = integrate_events(Model(Vb=1.5), SolverSettings(t_end=2.0, backend="python"))
    >>> dense = run.trajectory.evaluator
    >>> isinstance(dense, StepSegment)
    True
    >>> [round(float(v), 4) for v in dense(np.array([0.0]))[:, 0]]
    [3.924, 0.0, 11.5474, 0.0]
    """

    __slots__ = ("t_steps", "h_steps", "y_steps", "F_steps")

    def __init__(
        self,
        t_steps: NDArray[np.float64],
        h_steps: NDArray[np.float64],
        y_steps: NDArray[np.float64],
        F_steps: NDArray[np.float64],
    ) -> None:
        self.t_steps, self.h_steps = t_steps, h_steps
        self.y_steps, self.F_steps = y_steps, F_steps

    def __call__(self, t: ArrayLike, index: ArrayLike | None = None) -> NDArray[np.float64]:
        return _dop853.evaluate(self.t_steps, self.h_steps, self.y_steps, self.F_steps, t)


def integrate_events(
    model: Model,
    settings: SolverSettings,
    *,
    y0: ArrayLike | None = None,
    t0: float = 0.0,
    progress: Callable[[float], object] | None = None,
    max_step: float = np.inf,
) -> Run:
    """Integrate Eq. (4) mode by mode with located switches (module docstring).

    Parameters
    ----------
    model : Model
    settings : SolverSettings
        ``t_end``, ``rtol``, ``atol``, ``on_contact_loss``, ``backend`` (the integrator
        and kernels compiled by numba, or plain Python; None: numba if installed).
    y0 : array_like, optional
        Initial state at ``t0``; default the unforced equilibrium (Eq. 9) at rest.
    t0 : float
    progress : callable, optional
        Called with the time reached after every smooth segment (a progress bar).
    max_step : float
        The longest step [s]; in stick at most `REST_STEP` over the fastest rate. The
        step control sees the state only: where it rests (an equilibrium) the steps
        grow without bound, and a variational equation
        carried on them (`beltmdsm.periodic.variational`) leaves the method's region
        of accuracy; `beltmdsm.attractors.lyapunov` bounds them.

    Returns
    -------
    Run

    Raises
    ------
    beltmdsm.errors.StepTooSmall
        Where the step size falls below the rounding of the time (tolerances too
        loose or too tight for the field there), naming the time and the mode.

    See Also
    --------
    beltmdsm.integrate.superposition.integrate_superposed : The other integrator.
    beltmdsm.simulation.simulate : A run with its summary, from the public API.

    Examples
    --------
    A run restarted from its own state at ``t = 2`` (``y0``, ``t0``) ends where it
    ends, to the tolerances (1e-10):

    >>> from beltmdsm.settings import SolverSettings
    >>> settings = SolverSettings(t_end=4.0, backend="python")
    >>> run = integrate_events(Model(Vb=1.5), settings)
    >>> middle = run.trajectory.state(np.array([2.0]))[:, 0]
    >>> rest = integrate_events(Model(Vb=1.5), settings, y0=middle, t0=2.0)
    >>> end = np.array([4.0])
    >>> gap = np.abs(rest.trajectory.state(end) - run.trajectory.state(end)).max()
    >>> run.status, bool(gap < 1e-8)
    ('done', True)
    """
    sw = Switching(model)
    advance = _compiled.advance("vector_field", model, settings.backend)
    y = initial_state(model) if y0 is None else np.array(y0, dtype=float)
    t, t_end = float(t0), settings.t_end
    mode = sw.initial_mode(t, y)
    segments, events, steps = [], [], []
    zeno = Zeno(sw)
    status, message = "done", "reached t_end"
    h_next = 0.0
    held = -np.inf  # the time friction last held the mass at a crossed stick limit
    n_steps = 0
    max_step = float(max_step)
    rest_step = min(max_step, REST_STEP / fastest_rate(model))
    field, surf, rates = sw.field, sw.surfaces, sw.rates
    while t < t_end:
        watch, dirs, _ = sw.guards[mode]
        (code, n, ts, hs, ys, Fs, t_stop, y_stop, hit, h_next) = advance(
            field.args,
            surf.args,
            rates.args,
            float(mode),
            watch,
            dirs,
            t,
            y,
            float(t_end),
            h_next,
            settings.rtol,
            settings.atol,
            rest_step if mode == Mode.STICK else max_step,
            _dop853.MAX_STEPS - n_steps,
        )
        check_status(code, t_stop, f"in mode {mode.name.lower()}", settings.rtol, settings.atol)
        n_steps += n  # the run's steps together within MAX_STEPS (its memory)
        if n:
            steps.append((ts, hs, ys, Fs))
            segments.append(Segment(t, float(t_stop), mode, StepSegment(ts, hs, ys, Fs), ts.copy()))
        t, y = float(t_stop), np.array(y_stop)
        if progress is not None:
            progress(t)
        if code == _dop853.STATUS_END:
            break
        h_next = 0.0  # the field jumps at a switch: choose the next step afresh
        inside = sw.holds(mode, hit, t, y) if t > held else None
        if inside is not None:
            # a stick limit crossed within its rounding, the margin not shrinking: the
            # mass stays stuck, no switch (once per time: a crossing at the same time
            # again is the field leaving through the limit, and it slips)
            held, y = t, inside
            continue
        kind = sw.kind(mode, hit)
        y = sw.project(mode, hit, y)
        target = sw.target(mode, hit, t, y)
        new = zeno.after(t, kind, sw.guards[mode][2][hit][0], y, target)
        if isinstance(new, str):
            events.append((t, kind, target))
            status, message = "zeno", new
            break
        events.append((t, kind, new))
        if kind == "lift_off" and settings.on_contact_loss == "stop":
            status = "contact_lost"
            message = (
                f"contact lost (X2 = 0, Eq. 1) at t = {t:.6g} s; stopped as "
                "requested (on_contact_loss='stop')"
            )
            break
        mode = new
    if not segments:
        # the run stopped where it started: a segment of zero length keeps the state
        y_at = y.copy()
        segments.append(
            Segment(
                t,
                t,
                mode,
                lambda tt, y_at=y_at: np.repeat(y_at[:, None], np.size(tt), axis=1),
                np.array([t]),
            )
        )
        evaluator = None
    else:
        evaluator = StepSegment(*(np.concatenate(part) for part in zip(*steps)))
    trajectory = Trajectory(segments, model, evaluator)
    trajectory.n_zeno = zeno.entered
    return Run(trajectory, events, status, message, "events")
