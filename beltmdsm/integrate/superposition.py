"""Fast simulation of Eq. (4) by the one-way coupling and superposition.

The normal equation of Eq. (4) does not depend on the tangential state, on Vb or on
mu_s, so the normal motion and ``z``, the tangential oscillator's response to its
contact force, are integrated once (`beltmdsm.integrate.normal.NormalMotion`, cached across a
sweep). The tangential equation is linear in each mode, so between switches

    (X1, X1')(t) = Phi(t - t0) (x(t0) - f(t0)) + f(t),    f = zf - mu_s sgn z,

with ``Phi`` the closed-form state-transition matrix and ``zf`` the closed-form
response to the tangential excitation: the generated superposition
`beltmdsm.generated.oscillator.tangential_state` (derived in derive/oscillator.py), with
``sgn = 0`` in flight and separation (no friction), while sticking ``X1' = Vb``. Every
tangential switch is located on these closed forms (`beltmdsm.integrate._switch_scan.scan`),
every normal switch comes from the normal motion, and the mode after a switch is
chosen by the same rules as in the event-driven integrator (`beltmdsm.integrate.switching`).

Where its closed forms do not exist, it raises `NotApplicable` with the reason, and
`beltmdsm.simulation.simulate` hands the run to `beltmdsm.integrate.events`: where the
model's laws lack a fact it needs (`FACTS`, decided by SymPy in
``beltmdsm.generated.capabilities``: the slip-mode friction free of the tangential state, as
Coulomb's is and Stribeck's is not, and the normal equation free of it), and at
undamped resonance of the tangential oscillator (``beta1 = 0``, ``Omega_t = omega1``,
where the excitation response grows without bound).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import oscillator

from ..errors import NotApplicable  # its home; importable here as before
from ..excitation import initial_state
from ..model import Backend, Model, Unsupported, require
from ..settings import SolverSettings
from . import _compiled
from .normal import GRID_STEP, NormalMotion, clear_cache, normal_motion
from .switching import SURFACE_INDEX, Mode, Switching
from .trajectory import Run, Segment, Trajectory
from .zeno import Zeno

__all__ = [
    "FACTS",
    "check_applicable",
    "Superposition",
    "TangentialRun",
    "NotApplicable",
    "integrate_superposed",
    "clear_cache",
    "GRID_STEP",
    "KNOT_STEP",
]


#: The facts of the laws (``beltmdsm.generated.capabilities``) that the superposition needs: the
#: tangential equation linear in each slip mode, the normal motion integrated alone.
FACTS = ("slip_friction_state_independent", "one_way_coupling")


def check_applicable(model: Model) -> None:
    """Raise `NotApplicable` where a fact of `FACTS` fails for the model's laws (the
    law and the property, `beltmdsm.model.require`).

    Parameters
    ----------
    model : Model
        The model to run.

    Raises
    ------
    NotApplicable
        Naming the law and the property it lacks.

    See Also
    --------
    beltmdsm.model.require : The check of one fact.
    beltmdsm.integrate.superposition.FACTS : The facts checked.

    Examples
    --------
    Coulomb's slip friction is a constant times the contact force; Stribeck's depends
    on the slip speed, so the tangential equation is not linear in a slip mode:

    >>> check_applicable(Model(friction="coulomb"))
    >>> try:
    ...     check_applicable(Model(friction="stribeck"))
    ... except NotApplicable as refusal:
    ...     print(refusal)
    superposition: friction='stribeck': the slip-mode friction mu(|Vr|) F depends on X1' ...
    """
    for fact in FACTS:
        try:
            require(model, fact, "superposition")
        except Unsupported as reason:
            raise NotApplicable(str(reason)) from None


#: Grid points of the normal motion per quadrature piece of a segment, at most.
KNOT_STEP = 10
_TANGENTIAL = ("relative_velocity", "stick_forward", "stick_back")


class _Segments:
    """The closed form of every segment, evaluated for many times at once."""

    def __init__(self, normal, state, exc, Vb):
        self.normal, self.state, self.exc, self.Vb = normal, state, exc, Vb
        self.t0, self.stick, self.sgn, self.start = [], [], [], []

    def add(self, t0, stick, sgn, start):
        """A segment from ``t0``: ``start`` is `Superposition.start` there."""
        self.t0.append(t0)
        self.stick.append(stick)
        self.sgn.append(sgn)
        self.start.append(start)

    def freeze(self):
        self.t0, self.stick, self.sgn = (
            np.array(a, dtype=dt)
            for a, dt in ((self.t0, float), (self.stick, bool), (self.sgn, float))
        )
        self.start = np.array(self.start, dtype=float).reshape(-1, 6)

    def __call__(self, t, index):
        t = np.asarray(t, dtype=float)
        z, v, X2, Y2 = self.normal.evaluate(t)
        zf, vf = self.exc.array(t)
        t0, start = self.t0[index], self.start[index]
        X1, Y1 = self.state.array(t - t0, *start.T, zf, vf, z, v, self.sgn[index])
        stick = self.stick[index]
        X1 = np.where(stick, start[:, 0] + self.Vb * (t - t0), X1)
        Y1 = np.where(stick, self.Vb, Y1)
        return np.array([X1, Y1, X2, Y2])


@dataclass
class TangentialRun:
    """The tangential motion on a normal motion between two times (`Superposition.run`).

    Attributes
    ----------
    segments : _Segments
        The closed form of every segment, evaluated for many times at once.
    modes, starts, ends : lists
        The mode and the time span of each segment.
    events : list of (t, kind, new_mode)
    switches : list of (t, before, after, surface, state)
        Every switch with the surface's name and the state on it.
    status, message : str
    n_zeno : int
    final : ndarray (4,)
        The state where the run stopped.

    See Also
    --------
    beltmdsm.integrate.superposition.Superposition.run : Returns it.

    Examples
    --------
    Coulomb friction at ``Vb = 1.5`` from rest: slip back and slip forward alternate,
    each segment starting where the last ends.

    >>> from beltmdsm.integrate.normal import normal_motion
    >>> from beltmdsm.excitation import initial_state
    >>> model = Model(Vb=1.5)
    >>> y0 = initial_state(model)
    >>> normal = normal_motion(model, 4.0, 1e-10, 1e-10, y0[2:], backend="python")
    >>> tangential = Superposition(model, normal, "python").run(0.0, y0[0], y0[1], 4.0)
    >>> [mode.name for mode in tangential.modes[:3]], tangential.starts[1:] == tangential.ends[:-1]
    (['SLIP_BACK', 'SLIP_FORWARD', 'SLIP_BACK'], True)
    >>> round(tangential.starts[1], 6), [round(float(v), 4) for v in tangential.final]
    (0.166042, [2.2746, 3.5045, 9.7574, -1.5597])
    """

    segments: _Segments = field(repr=False)
    modes: list
    starts: list
    ends: list
    events: list = field(repr=False)
    switches: list = field(repr=False)
    status: str
    message: str
    n_zeno: int
    final: NDArray[np.float64]


class Superposition:
    """The tangential switching on one normal motion: closed forms between switches.

    Parameters
    ----------
    model : Model
        The model; its laws must have the facts of `FACTS`.
    normal : beltmdsm.integrate.normal.NormalMotion
        The normal motion the tangential one is built on.
    backend : {"python", "numba", None}
        The kernels; None: numba if installed.

    Raises
    ------
    NotApplicable
        Where the model's laws lack a fact of `FACTS`, and at undamped resonance,
        where the excitation response has no closed form.

    See Also
    --------
    beltmdsm.integrate.superposition.integrate_superposed : A whole run on it.
    beltmdsm.integrate.superposition.TangentialRun : What `run` returns.

    Examples
    --------
    Undamped (``beta1 = 0``) and excited at its natural frequency
    (``Omega_t = omega1``), the tangential response grows like ``t sin t``: it has no
    closed form of the kind used here.

    >>> try:
    ...     Superposition(Model(beta1=0.0, Omega_t=1.0), None)
    ... except NotApplicable as refusal:
    ...     print(refusal)
    no closed-form excitation response at undamped resonance (beta1 = 0, Omega_t = omega1)
    """

    def __init__(
        self,
        model: Model,
        normal: NormalMotion,
        backend: Backend | None = None,
    ) -> None:
        check_applicable(model)
        self.model, self.normal = model, normal
        stm, exc = oscillator.bind_state_transition, oscillator.bind_excitation_response
        state = oscillator.bind_tangential_state
        self.stm = stm(backend=_compiled.scalar_backend(backend), **model.arguments(stm))
        self.exc = exc(backend=_compiled.scalar_backend(backend), **model.arguments(exc))
        #: the superposition: ``state(tau, *start, zf, vf, z, v, sgn)`` is ``(X1, X1')``
        #: at ``t0 + tau`` of a mode entered at ``t0`` (`start`)
        self.state = state(backend=_compiled.scalar_backend(backend), **model.arguments(state))
        # the scalar kernel answers inf or NaN where the closed form does not exist, as
        # the array implementation does, at a fraction of its cost
        with np.errstate(divide="ignore", invalid="ignore"):
            finite = np.all(np.isfinite(self.exc(1.0)))
        if not finite:
            raise NotApplicable(
                "no closed-form excitation response at undamped resonance "
                "(beta1 = 0, Omega_t = omega1)"
            )
        self.sw = sw = Switching(model)
        self.backend = backend
        self.scan = _compiled.scan(model, backend)
        self.watch = {}
        for mode in (Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK):
            rows = [
                (i, SURFACE_INDEX[s], float(d))
                for i, (s, d, _) in enumerate(sw.guards[mode][2])
                if s in _TANGENTIAL
            ]
            self.watch[mode] = (
                np.array([r[1] for r in rows], dtype=np.int64),
                np.array([r[2] for r in rows]),
                [r[0] for r in rows],
            )
        self._none = (np.zeros(0, dtype=np.int64), np.zeros(0), [])
        self._args = (
            normal.grid,
            normal.on_grid,
            normal.t_steps,
            normal.h_steps,
            normal.y_steps,
            normal.F_steps,
            self.state.args,
            self.exc.args,
            sw.surfaces.args,
            sw.rates.args,
        )

    def __getstate__(self) -> dict[str, Any]:
        # the scan is a function compiled (or being compiled) for the model's laws, which
        # does not pickle: made again where the object arrives (results travel to other
        # processes with their period map)
        return {k: v for k, v in self.__dict__.items() if k != "scan"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self.scan = _compiled.scan(self.model, self.backend)

    def start(self, t0: float, X1: float, Y1: float) -> tuple[float, ...]:
        """``(X1, X1', zf, zf', z, z')`` at ``t0``: the state at a switch and the two
        responses there, the start of `self.state <Superposition>` (the superposition,
        `beltmdsm.generated.oscillator.tangential_state`)."""
        z, v = self.normal.at(t0)[:2]
        zf, vf = self.exc(t0)
        return (float(X1), float(Y1), float(zf), float(vf), float(z), float(v))

    def run(
        self,
        t0: float,
        X1: float,
        Y1: float,
        t_end: float,
        on_contact_loss: Literal["continue", "stop"] = "continue",
        progress: Callable[[float], object] | None = None,
    ) -> TangentialRun:
        """The tangential motion from ``(X1, Y1)`` at ``t0`` to ``t_end``.

        ``progress``, if given, is called with the time reached after every segment.
        """
        sw, normal = self.sw, self.normal
        Vb = self.model.params["Vb"]
        segs = _Segments(normal, self.state, self.exc, Vb)
        modes, starts, ends, events, switches = [], [], [], [], []
        zeno = Zeno(sw)
        t = float(t0)
        mode = _mode_in(sw, normal, normal.segment_at(t), t, X1, Y1)
        status, message = "done", "reached t_end"
        held = -np.inf  # the time friction last held the mass at a crossed stick limit
        while t < t_end:
            k = normal.segment_at(t)
            tc = min(float(normal.switch_t[k + 1]), t_end)
            stick = mode == Mode.STICK
            sgn = friction_direction(mode)
            start = self.start(t, X1, Y1)
            w, dirs, rows = self.watch.get(mode, self._none)
            hit, t_hit = self.scan(float(mode), stick, sgn, w, dirs, t, tc, start, Vb, *self._args)
            t_stop = float(t_hit) if hit >= 0 else tc
            segs.add(t, stick, sgn, start)
            modes.append(mode)
            starts.append(t)
            ends.append(t_stop)
            state = segs_state(segs, t_stop, len(modes) - 1)
            if t_stop >= t_end:
                break
            if hit >= 0:
                guard = rows[hit]
                inside = sw.holds(mode, guard, t_stop, state) if t_stop > held else None
                if inside is not None:
                    # a stick limit crossed within its rounding, the margin not shrinking:
                    # the mass stays stuck, no switch (as in events.py, once per time)
                    held, t, X1, Y1 = t_stop, t_stop, float(inside[0]), float(inside[1])
                    continue
                surface = sw.guards[mode][2][guard][0]
                kind = sw.kind(mode, guard)
                state = sw.project(mode, guard, state)
                target = sw.target(mode, guard, t_stop, state)
                new = zeno.after(t_stop, kind, surface, state, target)
                if isinstance(new, str):
                    events.append((t_stop, kind, target))
                    status, message = "zeno", new
                    break
            else:
                surface = normal.switch_surface[k]
                kind = normal.switch_kind[k]
                new = _mode_in(sw, normal, k + 1, t_stop, state[0], state[1])
            events.append((t_stop, kind, new))
            switches.append((t_stop, mode, new, surface, state))
            if kind == "lift_off" and on_contact_loss == "stop":
                status = "contact_lost"
                message = (
                    f"contact lost (X2 = 0, Eq. 1) at t = {t_stop:.6g} s; stopped as "
                    "requested (on_contact_loss='stop')"
                )
                break
            t, X1, Y1, mode = t_stop, float(state[0]), float(state[1]), new
            if progress is not None:
                progress(t)
        segs.freeze()
        return TangentialRun(
            segs, modes, starts, ends, events, switches, status, message, zeno.entered, state
        )


def integrate_superposed(
    model: Model,
    settings: SolverSettings,
    *,
    y0: ArrayLike | None = None,
    progress: Callable[[float], object] | None = None,
) -> Run:
    """A run of Eq. (4) by superposition.

    ``progress``, if given, is called with the time reached after every segment of
    the tangential motion (the normal motion is integrated first, in one call).

    Parameters
    ----------
    model : Model
        The model to run; its laws must have the facts of `FACTS`.
    settings : SolverSettings
        ``t_end``, ``rtol``, ``atol``, ``on_contact_loss``, ``backend``.
    y0 : array_like, optional
        The state at ``t = 0``; default the unforced equilibrium at rest.
    progress : callable, optional
        Called with the time reached.

    Returns
    -------
    Run
        With ``solver="superposition"``.

    Raises
    ------
    NotApplicable
        Where the closed forms do not exist (the reason); the event-driven
        integrator applies there.

    See Also
    --------
    beltmdsm.integrate.events.integrate_events : The general integrator.

    Examples
    --------
    The closed forms and the event-driven integrator agree on the same run, to the
    tolerances (1e-10), switch for switch:

    >>> from beltmdsm.integrate.events import integrate_events
    >>> settings = SolverSettings(t_end=4.0, backend="python")
    >>> closed = integrate_superposed(Model(Vb=1.5), settings)
    >>> stepped = integrate_events(Model(Vb=1.5), settings)
    >>> end = np.array([4.0])
    >>> gap = np.abs(closed.trajectory.state(end) - stepped.trajectory.state(end)).max()
    >>> closed.solver, len(closed.events) == len(stepped.events), bool(gap < 1e-7)
    ('superposition', True, True)
    """
    check_applicable(model)
    y = initial_state(model) if y0 is None else np.array(y0, dtype=float)
    normal = normal_motion(
        model, settings.t_end, settings.rtol, settings.atol, y[2:], settings.backend
    )
    engine = Superposition(model, normal, settings.backend)
    out = engine.run(
        0.0, float(y[0]), float(y[1]), float(settings.t_end), settings.on_contact_loss, progress
    )
    # quadrature pieces (energy balance, cycle averages): a knot every KNOT_STEP grid
    # points, and the normal motion's own steps within 0.2 s of its switches, where
    # they shrink because it is not smooth there (X2^(3/2) about a touchdown)
    near = np.zeros(normal.t_steps.size, dtype=bool)
    for ts in normal.switch_t[1:-1]:
        near |= np.abs(normal.t_steps - ts) <= 4 * KNOT_STEP * GRID_STEP
    knots = np.union1d(normal.grid[::KNOT_STEP], normal.t_steps[near])
    lo = np.searchsorted(knots, out.starts, side="right")
    hi = np.searchsorted(knots, out.ends, side="left")
    segments = [
        Segment(a, b, m, None, knots[i:j])
        for a, b, m, i, j in zip(out.starts, out.ends, out.modes, lo, hi)
    ]
    trajectory = Trajectory(segments, model, out.segments)
    trajectory.n_zeno = out.n_zeno
    return Run(trajectory, out.events, out.status, out.message, "superposition")


def friction_direction(mode: Mode) -> float:
    """The friction direction ``sgn`` of a mode in the superposition: ``sgn(Vr)`` of a
    slip mode (its code), 0 in flight or separation (no friction) and in stick (unused)."""
    return float(int(mode)) if mode in (Mode.SLIP_BACK, Mode.SLIP_FORWARD) else 0.0


def segs_state(segs, t, index):
    """The state at ``t`` in segment ``index`` (before `_Segments.freeze`)."""
    z, v, X2, Y2 = segs.normal.at(t)
    start, t0 = segs.start[index], segs.t0[index]
    if segs.stick[index]:
        return np.array([start[0] + segs.Vb * (t - t0), segs.Vb, X2, Y2])
    zf, vf = segs.exc(t)
    X1, Y1 = segs.state(t - t0, *start, zf, vf, z, v, segs.sgn[index])
    return np.array([X1, Y1, X2, Y2])


def _mode_in(sw, normal, k, t, X1, Y1):
    """The mode at ``t`` where the normal motion is in its segment ``k``."""
    normal_mode = normal.switch_mode[k]
    if normal_mode != Mode.SLIP_BACK:
        return normal_mode
    _, _, X2, Y2 = normal.at(t)
    return sw.by_relative_velocity(t, np.array([X1, Y1, X2, Y2]))
