"""A piecewise-smooth trajectory of Eq. (4): smooth segments between located events.

Both integrators (`beltmdsm.integrate.events` with the compiled DOP853,
`beltmdsm.integrate.superposition` with the one-way coupling) produce a `Run`: a
`Trajectory`, its events and how it ended. Everything computed from a run (samples,
friction force, energy balance of Sect. 3, cycle averages of Sect. 5) integrates or
evaluates segment by segment, never across a switch, and uses the generated
functions of ``beltmdsm.generated.dynamics`` for the physics so that they stay the reference.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import dynamics

from ..model import Model
from .switching import Mode

__all__ = ["Segment", "Trajectory", "Run", "Samples", "STATUSES"]

#: How a run ends: at ``t_end``, at the first loss of contact (on request), or where
#: switches accumulate off the friction cone (Zeno).
STATUSES = ("done", "contact_lost", "zeno")

# 5-point Gauss-Legendre on each smooth piece: exact for degree 9, well beyond the
# order of the dense outputs it integrates, so the quadrature adds no visible error.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(5)


@dataclass
class Segment:
    """One smooth piece [t0, t1] in one mode.

    ``evaluate(t) -> (4, n)`` gives the state inside; ``knots`` are the solver's own
    step points (the pieces on which ``evaluate`` is one polynomial or closed form).

    Parameters
    ----------
    t0, t1 : float
        Its start and end [s].
    mode : int
        Its mode (`beltmdsm.integrate.switching.Mode`).
    evaluate : callable
        ``evaluate(t) -> (4, n)``, the state at times inside.
    knots : numpy.ndarray
        The solver's step points.

    See Also
    --------
    beltmdsm.integrate.trajectory.Trajectory : The segments of a run.

    Examples
    --------
    Coulomb friction at ``Vb = 1.5`` from rest: the mass first slips backward, and the
    first segment ends where ``Vr = 0``:

    >>> from beltmdsm.integrate.events import integrate_events
    >>> from beltmdsm.settings import SolverSettings
    >>> run = integrate_events(Model(Vb=1.5), SolverSettings(t_end=2.0, backend="python"))
    >>> first = run.trajectory.segments[0]
    >>> Mode(first.mode).name, round(first.t1, 6)
    ('SLIP_BACK', 0.166042)
    >>> round(float(first.evaluate([first.t1])[1, 0]), 9)  # X1' = Vb there
    1.5
    """

    t0: float
    t1: float
    mode: int
    evaluate: object
    knots: np.ndarray = field(repr=False)


class Trajectory:
    """Segments in time order covering [segments[0].t0, segments[-1].t1].

    ``evaluator(t, index) -> (4, n)``, if given, evaluates the state at times ``t`` in
    the segments ``index`` all at once (an integrator's dense output of the whole run);
    otherwise each segment's ``evaluate`` is called on its own times.

    Parameters
    ----------
    segments : sequence of Segment
        The smooth pieces, in time order, each starting where the last ends.
    model : Model
        The model they solve.
    evaluator : callable, optional
        ``evaluator(t, index) -> (4, n)`` for the whole run.

    Raises
    ------
    ValueError
        Without segments.

    See Also
    --------
    beltmdsm.integrate.trajectory.Run : A trajectory and how it ended.

    Examples
    --------
    The energy balance of Sect. 3 closes to the integration error: over 20 s of
    stick-slip the works are about 1800 J while the imbalance is about 1e-8 J.

    >>> from beltmdsm.integrate.events import integrate_events
    >>> from beltmdsm.settings import SolverSettings
    >>> run = integrate_events(Model(Vb=1.5), SolverSettings(t_end=20.0, backend="python"))
    >>> balance = run.trajectory.energy_balance()
    >>> round(balance["work_input"]), balance["residual"] < 1e-9
    (1807, True)
    >>> modes = run.trajectory.time_in_modes(0.0, 20.0)
    >>> round(sum(modes.values()), 9), round(modes[Mode.SLIP_FORWARD], 3)
    (20.0, 7.94)
    """

    def __init__(
        self,
        segments: Sequence[Segment],
        model: Model,
        evaluator: Callable[[NDArray[np.float64], NDArray[np.intp]], NDArray[np.float64]]
        | None = None,
    ) -> None:
        if not segments:
            raise ValueError("a trajectory needs at least one segment")
        self.segments, self.model = segments, model
        self.evaluator = evaluator
        self.n_zeno = 0
        self.starts = np.array([s.t0 for s in segments])
        self.modes_by_segment = np.array([s.mode for s in segments])

    @property
    def t_end(self) -> float:
        return self.segments[-1].t1

    def _index(self, t):
        return np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.segments) - 1)

    def state(self, t: ArrayLike, index: NDArray[np.intp] | None = None) -> NDArray[np.float64]:
        """State (X1, Y1, X2, Y2) at the times ``t``, shape (4, n)."""
        t = np.asarray(t, dtype=float)
        index = self._index(t) if index is None else index
        if self.evaluator is not None:
            return self.evaluator(t, index)
        out = np.empty((4, t.size))
        order = np.argsort(index, kind="stable")
        bounds = np.flatnonzero(np.diff(index[order])) + 1
        for chunk in np.split(order, bounds):
            if chunk.size:
                out[:, chunk] = self.segments[index[chunk[0]]].evaluate(t[chunk])
        return out

    def mode(self, t: ArrayLike) -> NDArray[np.int_]:
        return self.modes_by_segment[self._index(np.asarray(t, dtype=float))]

    def forces(
        self, t: ArrayLike, y: NDArray[np.float64] | None = None, mode: ArrayLike | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Normal force Fn (Eq. 1, under the run's tension law) and friction force on the
        mass, per unit mass.

        The friction force is the tangential force of the belt on the mass,
        ``-mu_s sgn(Vr) Fn`` while sliding (Eqs. 2-3), the force that holds the mass
        (``-a_free``) while sticking and zero in flight and separation; positive =
        along the belt.
        """
        t = np.asarray(t, dtype=float)
        y = self.state(t) if y is None else y
        mode = self.mode(t) if mode is None else mode
        kw = self.model.arguments
        Fn = dynamics.normal_force(y[2], y[3], **kw(dynamics.normal_force))
        a_free = dynamics.free_acceleration(t, y[0], y[1], **kw(dynamics.free_acceleration))
        slip = (mode == Mode.SLIP_BACK) | (mode == Mode.SLIP_FORWARD)
        sliding = dynamics.friction_force(
            y[1], y[2], y[3], np.where(slip, mode, 0), **kw(dynamics.friction_force)
        )
        friction = np.where(slip, sliding, np.where(mode == Mode.STICK, -a_free, 0.0))
        return Fn, friction

    def pieces(
        self, edges: ArrayLike | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.intp]]:
        """Smooth pieces (a, b, segment index) split at knots and at ``edges``.

        The segments follow each other in time, so the cuts of all of them are one
        sorted set: the knots, the segment boundaries and the edges inside the run.
        """
        t0, t1 = self.segments[0].t0, self.t_end
        cuts = [s.knots for s in self.segments] + [self.starts, [t1]]
        if edges is not None:
            e = np.asarray(edges, dtype=float)
            cuts.append(e[(e > t0) & (e < t1)])
        pts = np.unique(np.concatenate(cuts))
        pts = pts[(pts >= t0) & (pts <= t1)]
        a, b = pts[:-1], pts[1:]
        i = self._index(0.5 * (a + b))
        keep = b > a
        return a[keep], b[keep], i[keep]

    def integrate(
        self,
        integrand: Callable[
            [NDArray[np.float64], NDArray[np.float64], NDArray[np.int_]], ArrayLike
        ],
        edges: ArrayLike,
    ) -> NDArray[np.float64]:
        """Integrals of ``integrand(t, y, mode) -> (k, n)`` over [edges[j], edges[j+1]].

        Gauss-Legendre on every smooth piece, so no switch is integrated across.
        Returns shape (k, len(edges) - 1).
        """
        edges = np.asarray(edges, dtype=float)
        a, b, seg = self.pieces(edges)
        inside = (a >= edges[0]) & (b <= edges[-1])  # the pieces are cut at the edges
        a, b, seg = a[inside], b[inside], seg[inside]
        mid, half = (a + b) / 2, (b - a) / 2
        t = (mid[:, None] + half[:, None] * _GL_X[None, :]).ravel()
        w = (half[:, None] * _GL_W[None, :]).ravel()
        index = np.repeat(seg, _GL_X.size)
        y = self.state(t, index)
        values = np.atleast_2d(integrand(t, y, self.modes_by_segment[index]))
        # the nodes are in time order: those of bin j lie between the edges' places
        cuts = np.searchsorted(t, edges)
        sums = [values[:, i:j] @ w[i:j] for i, j in zip(cuts[:-1], cuts[1:])]
        return np.stack(sums, axis=1)

    def energy_balance(self, t0: float | None = None, t1: float | None = None) -> dict[str, float]:
        """Energy balance of Sect. 3 over [t0, t1] from the generated power terms.

        dE/dt = P_input - P_viscous - P_friction (``beltmdsm.generated.dynamics.power_balance``);
        while sticking the friction power is ``Vb a_free`` (the holding force times
        the velocity Vb). Returns a dict with the change of E (``energy_change``:
        kinetic, spring, Hertz and gravity), the three works (``work_input``,
        ``work_viscous``, ``work_friction``), ``imbalance`` =
        Delta E - W_in + W_visc + W_fric, ``work_total`` = int |P_in| + int |P_visc| +
        int |P_fric|, ``residual`` = |imbalance| / work_total and ``energy_level`` =
        max |E| at the two ends (the scale of the rounding and of the integration
        error of Delta E).
        """
        kw = self.model.arguments
        t0 = self.segments[0].t0 if t0 is None else t0
        t1 = self.t_end if t1 is None else t1

        def powers(t, y, mode):
            slip = (mode == Mode.SLIP_BACK) | (mode == Mode.SLIP_FORWARD)
            sgn = np.where(slip, mode, 0).astype(float)
            P_in, P_visc, P_fric = dynamics.power_balance(t, *y, sgn, **kw(dynamics.power_balance))
            a_free = dynamics.free_acceleration(t, y[0], y[1], **kw(dynamics.free_acceleration))
            P_fric = P_fric + np.where(mode == Mode.STICK, y[1] * a_free, 0.0)
            return np.stack([P_in, P_visc, P_fric, np.abs(P_in), np.abs(P_visc), np.abs(P_fric)])

        W = self.integrate(powers, [t0, t1])[:, 0]
        ends = self.state(np.array([t0, t1]))
        E0, E1 = dynamics.energy(*ends, **kw(dynamics.energy))
        dE = float(E1 - E0)
        balance = dE - (W[0] - W[1] - W[2])
        scale = W[3] + W[4] + W[5]
        return {
            "energy_change": dE,
            "work_input": float(W[0]),
            "work_viscous": float(W[1]),
            "work_friction": float(W[2]),
            "imbalance": float(balance),
            "residual": float(abs(balance) / scale) if scale > 0 else 0.0,
            "work_total": float(scale),
            "energy_level": float(max(abs(E0), abs(E1))),
        }

    def time_in_modes(self, t0: float, t1: float) -> dict[Mode, float]:
        """Time spent in each mode within [t0, t1] (dict mode -> seconds)."""
        out = {m: 0.0 for m in Mode}
        for s in self.segments:
            out[s.mode] += max(0.0, min(s.t1, t1) - max(s.t0, t0))
        return out


@dataclass(frozen=True)
class Samples:
    """A run on a uniform time grid: state, normal force and friction force (Eqs. 1-3).

    Attributes
    ----------
    t : numpy.ndarray, shape (n,)
        The times ``0, dt, 2 dt, ...`` [s].
    y : numpy.ndarray, shape (4, n)
        The states ``X1, X1', X2, X2'``.
    normal_force, friction : numpy.ndarray, shape (n,)
        The forces of Eqs. (1)-(3).

    See Also
    --------
    beltmdsm.integrate.trajectory.Run.sample : Builds it.

    Examples
    --------
    >>> from beltmdsm.integrate.events import integrate_events
    >>> from beltmdsm.settings import SolverSettings
    >>> run = integrate_events(Model(Vb=1.5), SolverSettings(t_end=2.0, backend="python"))
    >>> samples = run.sample(0.5)
    >>> samples.t.tolist(), samples.y.shape
    ([0.0, 0.5, 1.0, 1.5, 2.0], (4, 5))
    """

    t: NDArray[np.float64] = field(repr=False)
    y: NDArray[np.float64] = field(repr=False)
    normal_force: NDArray[np.float64] = field(repr=False)
    friction: NDArray[np.float64] = field(repr=False)


@dataclass
class Run:
    """What an integrator returns: the trajectory, its switches and how it ended.

    Attributes
    ----------
    trajectory : Trajectory
    events : list of (t, kind, new_mode)
        Every switch: its time, its kind (`beltmdsm.integrate.switching.EVENT_KINDS`)
        and the mode that follows.
    status : str
        One of `STATUSES`.
    message : str
        What ended the run, in words.
    solver : str
        The integrator that produced it ("events" or "superposition").

    See Also
    --------
    beltmdsm.integrate.events.integrate_events : One integrator that returns it.
    beltmdsm.integrate.superposition.integrate_superposed : The other.

    Examples
    --------
    Coulomb friction at ``Vb = 1.5`` from rest: the mass switches between slip back and
    slip forward, and every switch is on ``Vr = 0``:

    >>> from beltmdsm.integrate.events import integrate_events
    >>> from beltmdsm.settings import SolverSettings
    >>> run = integrate_events(Model(Vb=1.5), SolverSettings(t_end=20.0, backend="python"))
    >>> run
    Run(status='done', message='reached t_end', solver='events')
    >>> len(run.events), {kind for _, kind, _ in run.events}
    (26, {'vr_zero'})
    """

    trajectory: Trajectory = field(repr=False)
    events: list = field(repr=False)
    status: str
    message: str
    solver: str

    def sample(self, dt: float) -> Samples:
        """The run at ``0, dt, 2 dt, ...`` up to its end."""
        tr = self.trajectory
        n = int(np.floor(tr.t_end / dt + 1e-9)) + 1
        t = dt * np.arange(n)
        y = tr.state(t)
        Fn, friction = tr.forces(t, y)
        return Samples(t, y, Fn, friction)
