"""Event-driven integration of Eq. (4): one smooth mode at a time, every switch located.

The general integrator of the package, and the fallback of `runtime.superposition`.
It runs the compiled Dormand-Prince 8(5,3) integrator (`runtime._dop853`) on the
generated field of the current mode (`generated.hybrid.vector_field`) until one of
the mode's guard surfaces is crossed (`generated.hybrid.GUARDS`), then lets
`runtime.switching` choose the next mode, and goes on. Nothing is stepped over: the
run is a sequence of smooth segments joined at located switches.

Accumulating switches (Zeno) are detected, never counted to a cap: when
`ZENO_SWITCHES` switches fall within `ZENO_WINDOW` (relative to the time), the run
is chattering on one surface. On ``Vr = 0`` with friction that holds the mass
(``|a_free| <= mu_s F``), the limit of that chattering is Filippov's sliding motion,
which is the stick mode: the run enters it (and counts it in ``n_zeno``). Anywhere
else the run stops with status ``"zeno"`` and a message naming the surface and the
time.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _compiled, _dop853
from .parameters import Backend, Contact, Tension
from .switching import Mode, Switching
from .trajectory import Segment, Trajectory

__all__ = ["integrate_events", "ZENO_SWITCHES", "ZENO_WINDOW", "StepSegment"]

ZENO_SWITCHES = 8
ZENO_WINDOW = 1e-9


class StepSegment:
    """The dense output of a run of DOP853 steps: ``evaluate(t[, index]) -> (4, n)``.

    Built over the steps of all segments of a run (they follow each other in time,
    each switch starting a new step), it evaluates the whole trajectory at once.
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
    p: Mapping[str, float],
    contact: Contact = "hertz_damp",
    *,
    tension: Tension = "allowed",
    t_end: float = 1000.0,
    y0: ArrayLike | None = None,
    t0: float = 0.0,
    rtol: float = 1e-10,
    atol: float = 1e-10,
    on_contact_loss: Literal["continue", "stop"] = "continue",
    backend: Backend | None = None,
    method: Literal["DOP853"] = "DOP853",
) -> tuple[Trajectory, list[tuple[float, str, Mode]], str, str]:
    """Integrate Eq. (4) mode by mode with located switches (module docstring).

    Parameters
    ----------
    p : dict
        Complete parameters (`runtime.model.resolve_parameters`).
    contact, tension : str
    t_end : float
    y0 : array_like, optional
        Initial state at ``t0``; default the unforced equilibrium (Eq. 9) at rest.
    t0 : float
    rtol, atol : float
    on_contact_loss : {"continue", "stop"}
    backend : {"python", "numba", None}
        The integrator and kernels compiled by numba, or plain Python; None: numba
        if installed.
    method : {"DOP853"}
        The only method (kept as a setting so that a run records it).

    Returns
    -------
    trajectory : Trajectory
    events : list of (t, kind, new_mode)
    status : "done", "contact_lost" or "zeno"
    message : str
    """
    if method != "DOP853":
        raise ValueError(f"method must be 'DOP853' for the events solver; got {method!r}")
    from .model import initial_state

    sw = Switching(p, contact, tension, backend)
    advance = _compiled.advance("vector_field", contact, backend)
    y = initial_state(p, contact) if y0 is None else np.array(y0, dtype=float)
    t = float(t0)
    mode = sw.initial_mode(t, y)
    segments, events, steps = [], [], []
    recent = deque(maxlen=ZENO_SWITCHES)
    status, message = "done", "reached t_end"
    h_next = 0.0
    max_step = np.inf
    field, surf, rates = sw.field, sw.surfaces, sw.rates
    n_zeno = 0
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
            rtol,
            atol,
            max_step,
        )
        if code == _dop853.STATUS_STEP_TOO_SMALL:
            raise RuntimeError(
                f"step size too small at t = {t_stop:.6g} s in mode "
                f"{mode.name} (the field is not smooth there)"
            )
        if n:
            steps.append((ts, hs, ys, Fs))
            segments.append(Segment(t, float(t_stop), mode, StepSegment(ts, hs, ys, Fs), ts.copy()))
        t, y = float(t_stop), np.array(y_stop)
        if code == _dop853.STATUS_END:
            break
        h_next = 0.0  # the field jumps at a switch: choose the next step afresh
        kind = sw.kind(mode, hit)
        y = sw.project(mode, hit, y)
        new = sw.target(mode, hit, t, y)
        recent.append(t)
        if len(recent) == ZENO_SWITCHES and t - recent[0] <= ZENO_WINDOW * max(1.0, abs(t)):
            if kind == "vr_zero" and _cone_holds(sw, t, y):
                new = Mode.STICK
                n_zeno += 1
                recent.clear()
            else:
                events.append((t, kind, new))
                status = "zeno"
                message = (
                    f"switches accumulate on the {sw.guards[mode][2][hit][0]} surface "
                    f"at t = {t:.9g} s ({ZENO_SWITCHES} within "
                    f"{t - recent[0]:.2g} s); stopped"
                )
                break
        events.append((t, kind, new))
        if kind == "lift_off" and on_contact_loss == "stop":
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
    trajectory = Trajectory(segments, p, contact, tension, evaluator)
    trajectory.n_zeno = n_zeno
    return trajectory, events, status, message


def _cone_holds(sw, t, y):
    """Whether friction holds the mass at this state: ``mu_s F > 0`` beyond rounding and
    ``|a_free| <= mu_s F`` within it (both stick limits non-negative).

    Chattering on ``Vr = 0`` converges to Filippov's sliding motion only there; a run
    that chatters outside the cone is not chattering in exact arithmetic, and stops.
    """
    h, tol = sw._ties(t, y)
    return h[1] + h[2] > tol[1] + tol[2] and h[1] >= -tol[1] and h[2] >= -tol[2]
