"""Simulation of Eq. (4): one run and its summary (Sects. 2-3).

A run integrates Eq. (4) as a hybrid system: smooth modes (slip in either direction,
stick, flight and, under the clipped tension law, separation) joined at located
switches, with Filippov's rules where the friction is set-valued
(`beltmdsm.integrate.switching`). Two integrators produce the same `Run`:

* ``solver="events"`` (`beltmdsm.integrate.events`, the default): the compiled DOP853
  integrator on the generated field of each mode, the general one and, compiled,
  the faster;
* ``solver="superposition"`` (`beltmdsm.integrate.superposition`): the normal motion
  is integrated once and the tangential motion is a closed-form superposition between
  switches (Eq. 4 is one-way coupled); where it does not apply, the run is handed to
  ``events`` with the reason in its message.

The tension law (``tension=``, docs/modelling.md#tension) is Eq. (1) as printed
(``"allowed"``) or a contact that cannot pull (``"clipped"``).
`beltmdsm.run.summary.summarize` reads the run's steady window.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import state_names
from ._calling import public
from ._tables import DataFrame
from .arguments import flag, settings_of, state
from .excitation import START_PERTURBATION, equilibrium_start
from .integrate import _background
from .integrate.events import integrate_events
from .integrate.superposition import NotApplicable, integrate_superposed
from .integrate.trajectory import Run, Samples, Trajectory
from .model import Model, as_model
from .run.summary import Summary, summarize
from .settings import (
    Backend,
    ContactLoss,
    Method,
    Solver,
    SolverSettings,
    check_request,
    with_fields,
)

__all__ = ["Simulation", "simulate", "START_PERTURBATION", "equilibrium_start"]


@dataclass
class Simulation:
    """A run: the model, the settings, the run, its samples on a uniform grid, the summary.

    Parameters
    ----------
    model : Model
        The model that was run.
    settings : SolverSettings
        The solver settings it was run with.
    run : beltmdsm.integrate.trajectory.Run
        The integrated run: its `Trajectory` (dense output, mode by mode), switch
        events, status and message.
    samples : beltmdsm.integrate.trajectory.Samples
        The run sampled every ``settings.dt``: ``t``, the state ``y`` (X1, Y1, X2,
        Y2), the contact force and the friction force.
    summary : Summary
        What the run says (`beltmdsm.run.summary.summarize`).
    wall_s : float
        The wall-clock time of the run [s].

    Attributes
    ----------
    t, y, normal_force, friction : ndarray
        The samples' (`samples`).
    window : ndarray of bool
        The samples in the steady window (``t >= settings.window_start``).
    params, contact, tension : mapping, str, str
        The model's.
    trajectory, events, status, message, solver_used
        The run's.

    See Also
    --------
    beltmdsm.simulate : what returns it.
    beltmdsm.plotting.simulation : its figures (`plot`).

    Examples
    --------
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> sim.status, sim.solver_used, sim.params["Vb"]
    ('done', 'events', 4.0)
    >>> sim.y.shape  # X1, Y1, X2, Y2 every dt = 0.02 s
    (4, 2001)
    >>> float(sim.t[-1]), int(sim.window.sum())  # the steady window: t >= 10 s
    (40.0, 1501)
    """

    model: Model
    settings: SolverSettings
    run: Run = field(repr=False)
    samples: Samples = field(repr=False)
    summary: Summary
    wall_s: float = 0.0

    # what a run is read by, kept by the names the studies and notebooks use
    @property
    def params(self) -> Mapping[str, float]:
        return self.model.params

    @property
    def contact(self) -> str:
        return self.model.contact

    @property
    def tension(self) -> str:
        return self.model.tension

    @property
    def trajectory(self) -> Trajectory:
        return self.run.trajectory

    @property
    def events(self) -> list:
        return self.run.events

    @property
    def status(self) -> str:
        return self.run.status

    @property
    def message(self) -> str:
        return self.run.message

    @property
    def solver_used(self) -> str:
        return self.run.solver

    @property
    def t(self) -> NDArray[np.float64]:
        return self.samples.t

    @property
    def y(self) -> NDArray[np.float64]:
        return self.samples.y

    @property
    def normal_force(self) -> NDArray[np.float64]:
        return self.samples.normal_force

    @property
    def friction(self) -> NDArray[np.float64]:
        return self.samples.friction

    @property
    def window(self) -> NDArray[np.bool_]:
        """Boolean mask of the samples in the steady window."""
        return self.samples.t >= self.settings.window_start

    def plot(self, ax: Any = None, kind: str = "time", variable: str | None = None) -> Any:
        """The run: ``variable`` (default ``X1'``) against time (``kind="time"``), or the
        friction loop, friction against Vr over the steady window (``kind="friction"``), on
        matplotlib axes ``ax`` (new ones if None), which it returns
        (`beltmdsm.plotting.simulation`; matplotlib is imported here)."""
        from .plotting import simulation as draw

        return draw(self, ax, kind, variable)

    def to_pandas(self) -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the samples: ``t``, the state
        (``X1``, ``X1'``, ``X2``, ``X2'``), ``normal_force`` and ``friction`` (per unit
        mass), one row per sample.

        Examples
        --------
        >>> from beltmdsm import Model, simulate
        >>> table = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0).to_pandas()
        >>> list(table), len(table)
        (['t', 'X1', "X1'", 'X2', "X2'", 'normal_force', 'friction'], 2001)
        """
        from ._tables import STATE_COLUMNS, frame

        rows = {"t": self.t, **dict(zip(STATE_COLUMNS, self.y)),
                "normal_force": self.normal_force, "friction": self.friction}  # fmt: skip
        return frame(rows, list(rows))

    def __repr__(self) -> str:
        from ._display import laws

        head = (
            f"Simulation({self.model!r}; {laws(self.model)}; {self.t.size} samples "
            f"to t = {self.settings.t_end:g} s in {self.wall_s:.2f} s)"
        )
        return head + "\n" + "\n".join("  " + line for line in repr(self.summary).splitlines())


#: simulate's start state is ``y0``: the keywords of `beltmdsm.cli`'s ``--start``.
_START_HINTS = dict.fromkeys(
    ("start", "perturbation"),
    "takes the start state as y0: for a start on the periodic response pass "
    "y0=beltmdsm.starts.forced.periodic_start(model, perturbation)",
)


@public(hints=_START_HINTS, models=True)
def simulate(
    model: Model | Mapping[str, Any] | None = None,
    *,
    settings: SolverSettings | None = None,
    y0: ArrayLike | None = None,
    progress: bool = False,
    t_end: float | None = None,
    t_discard: float | None = None,
    dt: float | None = None,
    rtol: float | None = None,
    atol: float | None = None,
    solver: Solver | None = None,
    method: Method | None = None,
    on_contact_loss: ContactLoss | None = None,
    backend: Backend | None = None,
) -> Simulation:
    """Simulate Eq. (4) and summarise the run.

    Parameters
    ----------
    model : Model or dict, optional
        the model (`beltmdsm.Model`), or a dict of parameters and options; missing
        parameters come from the base set ``beltmdsm.generated.parameters.BASE``
    settings : SolverSettings, optional
    y0 : array_like, optional
        initial state (X1, Y1, X2, Y2) at t = 0; default the unforced equilibrium,
        Eq. (9), or, without excitation where steady sliding is unstable, that
        equilibrium moved by `beltmdsm.excitation.START_PERTURBATION` along its unstable
        direction (`beltmdsm.excitation.equilibrium_start`; the summary's
        ``start_perturbation``). To start on the
        periodic response, pass `beltmdsm.starts.forced.periodic_start` of the model.
    progress : bool
        show the simulated time on stderr (tqdm) once the run takes more than 2 s;
        it advances at every switch (a run without switches shows its elapsed time)
    t_end, t_discard, dt, rtol, atol, solver, method, on_contact_loss, backend : optional
        the fields of `SolverSettings` (``t_end=500``, ``solver="events"``), in place
        of ``settings``' where given (None: ``settings``' own)

    Returns
    -------
    Simulation
        The run, its samples and its ``summary`` (`beltmdsm.run.summary.summarize`).

    Raises
    ------
    ValueError
        Naming the parameter, setting or option, for a bad value.
    beltmdsm.errors.Refused
        Before anything is computed, for a sampling step that would alias the
        excitation into the omega1 band or a run that would not fit in memory
        (`beltmdsm.settings.check_request`).
    beltmdsm.errors.StepTooSmall
        Where the integrator cannot go on at the tolerances given.
    TypeError
        For ``start=`` or ``perturbation=``: the start state is ``y0``.

    See Also
    --------
    beltmdsm.sweep : a run for each value of one parameter.
    beltmdsm.periodic_response : the periodic response itself, without a transient.
    beltmdsm.lyapunov, beltmdsm.classify : what a run settles on.

    Examples
    --------
    >>> from beltmdsm import Model, simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> sim.status, sim.summary.regime
    ('done', 'sliding_with_reversals')
    >>> s = sim.summary
    >>> s.n_reversals > 0, s.n_sticks, s.energy_ok
    (True, 0, True)
    >>> round(s.vr_min, 1), round(s.vr_max, 1)  # Vr = X1' - Vb in the steady window
    (-15.6, 9.5)

    A bad value is named, and so is a misspelt keyword:

    >>> simulate(Model(Vb=-1.0))
    Traceback (most recent call last):
    ...
    ValueError: parameter 'Vb' must be >= 0; got -1.0
    >>> simulate(Model(), t_edn=10)
    Traceback (most recent call last):
    ...
    TypeError: simulate() got an unexpected keyword argument 't_edn'; did you mean 't_end'?
    """
    clock = time.perf_counter()
    settings = with_fields(
        settings_of(settings),
        t_end=t_end,
        t_discard=t_discard,
        dt=dt,
        rtol=rtol,
        atol=atol,
        solver=solver,
        method=method,
        on_contact_loss=on_contact_loss,
        backend=backend,
    )
    progress = flag("progress", progress)
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from .oscillator import api

        return api.simulate(model, settings, y0)
    if y0 is not None:
        names = state_names.names(model)
        y0 = state("y0", y0, (len(names),), ", ".join(names))
    check_request(model, settings)
    return _simulate(model, settings, y0, clock, progress)


def _simulate(
    model: Model, settings: SolverSettings, y0, clock: float, progress: bool = False
) -> Simulation:
    """`simulate` on checked arguments."""
    from tqdm import tqdm

    bar = tqdm(
        total=settings.t_end,
        desc="simulate",
        unit="s",
        delay=2,
        leave=False,
        disable=not progress,
        file=sys.stderr,
        bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.0f}/{total:.0f} s of simulated "
        "time [{elapsed}<{remaining}]",
    )

    made = [_background.compile_seconds()]

    def reached(t):
        # numba's code made during the run (compiled, or loaded from its cache) is no
        # part of the run: the bar's clock leaves it out, so its time left is the run's
        now = _background.compile_seconds()
        if now != made[0] and not bar.disable:
            bar.start_t += now - made[0]
            bar.last_print_t += now - made[0]
        made[0] = now
        bar.update(t - bar.n)

    moved = 0.0
    if y0 is None:
        y0, moved = equilibrium_start(model)
    run = None
    try:
        if settings.solver == "superposition":
            try:
                run = integrate_superposed(model, settings, y0=y0, progress=reached)
            except NotApplicable as reason:
                fallback = str(reason)
        if run is None:
            run = integrate_events(model, settings, y0=y0, progress=reached)
            if settings.solver == "superposition":
                run.message = f"{run.message} (events solver: {fallback})"
    finally:
        bar.close()
    samples = run.sample(settings.dt)
    summary = summarize(model, settings, run, samples, start_perturbation=moved)
    wall = time.perf_counter() - clock
    return Simulation(model, settings, run, samples, replace(summary, wall_s=wall), wall)
