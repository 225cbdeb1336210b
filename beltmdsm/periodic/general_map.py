"""The general period map: the full state of Eq. (4) by its variational equations, every law.

`GeneralMap` (engine ``"general"``) shoots in the full state ``(X1, X1', X2, X2')``
with the Jacobian of the whole period map: one period is a run of the event-driven
integrator (`beltmdsm.integrate.events`), its Jacobian the monodromy of that run
(`beltmdsm.periodic.variational`: the generated Jacobian of each mode's field and the
saltation matrix at every switch; Leine and Nijmeijer 2004). Its multipliers are all four
eigenvalues of it; the grazing test and the margins are read from its runs as from
`beltmdsm.periodic.closed_form.ClosedFormMap`'s (the same switches, the same rules,
`beltmdsm.periodic.base.PeriodMap`), a period of a run being an `EventPeriod`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import NoPeriodicResponse
from ..excitation import excitation_period, initial_state
from ..integrate import _compiled, _dop853
from ..integrate.events import StepTooSmall, integrate_events
from ..integrate.switching import Mode, Switching
from ..integrate.trajectory import Run
from ..model import Backend, Model
from ..settings import SolverSettings
from . import variational
from .base import RTOL, PeriodMap, _periods
from .newton import NEWTON_TOL

__all__ = [
    "EventPeriod",
    "GeneralMap",
]

#: Iterations on the backward-sliding field (`GeneralMap.sliding_guess`): where that
#: orbit exists they converge in 5 to 8 from the equilibrium.
_SLIDING_ITER = 30
#: The most steps of one period of `GeneralMap.sliding_guess`'s iterations: about 5 MB
#: with their variational propagators tens of MB. Stribeck friction with v_s = 1e-3
#: takes 1 700 a period, v_s = 1e-5 150 000 (the continued slip-back field crosses
#: Vr = 0, where it changes on the scale v_s: steps ~ T / v_s), which cost 1.3 GB and
#: half a minute for a guess; past the bound the guess is the last iterate.
_SLIDING_STEPS = 20_000
#: Samples per excitation period of `GeneralMap`'s runs (the integrator's samples are
#: not read; its dense output is).
_DENSE_SAMPLES = 50


@dataclass
class EventPeriod:
    """One excitation period of an event-driven run, as `PeriodMap` reads a period.

    Attributes
    ----------
    segments : callable
        ``(t, index) -> (4, n)``: the run's dense output.
    modes, starts, ends : list
        The mode and the time span of each segment.
    switches : list of (t, before, after, surface, state)
    final : ndarray (4,)
        The state at the end of the period.

    See Also
    --------
    GeneralMap : whose runs these are.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> pmap = GeneralMap(Model(Vb=5.0))
    >>> _, _, period, _ = pmap.one_period(pmap.sliding_guess())
    >>> [mode.name for mode in period.modes], period.final.shape
    (['SLIP_BACK', 'SLIP_FORWARD', 'SLIP_BACK'], (4,))
    """

    segments: Any = field(repr=False)
    modes: list
    starts: list
    ends: list
    switches: list = field(repr=False)
    final: NDArray[np.float64]

    @classmethod
    def of(cls, run: Run, switches: list) -> EventPeriod:
        """The period of a run of `beltmdsm.integrate.events.integrate_events`."""
        tr = run.trajectory
        return cls(
            tr.state,
            [Mode(int(s.mode)) for s in tr.segments],
            [float(s.t0) for s in tr.segments],
            [float(s.t1) for s in tr.segments],
            switches,
            tr.state(np.array([tr.t_end]))[:, 0],
        )


class GeneralMap(PeriodMap):
    """``k`` periods of the period map of Eq. (4) in the full state, by its variational equations.

    The general path: the shooting state is ``(X1, X1', X2, X2')`` at phase 0; one
    period is a run of the event-driven integrator (`beltmdsm.integrate.events`) at the
    tolerance `RTOL`, its Jacobian the monodromy of that run by the variational
    equations (`beltmdsm.periodic.variational`: the generated Jacobian of each mode's
    field, the saltation matrix at every switch; Leine and Nijmeijer 2004). Nothing
    of the laws' structure is assumed: every direction is shot in, so there are no
    fixed multipliers, and the normal motion is integrated with the tangential one.

    Parameters
    ----------
    model : Model
    periods : int
        ``k >= 1``.
    backend : {"python", "numba", None}

    Raises
    ------
    ValueError
        For ``periods < 1``, or an excitation without a period.

    See Also
    --------
    beltmdsm.periodic.closed_form.ClosedFormMap : the closed-form engine, where it applies.
    beltmdsm.periodic.engines.period_map : the engine the laws allow.

    Examples
    --------
    Where both engines apply they agree (tests/beltmdsm/periodic/test_general.py):

    >>> import numpy as np
    >>> from beltmdsm import Model, floquet
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> pmap = GeneralMap(Model(Vb=5.0))
    >>> point = fixed_point(pmap, pmap.sliding_guess())
    >>> mu = np.linalg.eigvals(point.image.jacobian)
    >>> closed_form = floquet(Model(Vb=5.0)).max_abs_multiplier
    >>> bool(abs(np.max(np.abs(mu)) - closed_form) < 1e-8)
    True
    """

    engine = "general"

    def __init__(self, model: Model, periods: int = 1, backend: Backend | None = None) -> None:
        self.periods = _periods(periods)
        self.model, self.backend = model, backend
        self.period = excitation_period(model)
        self.sw = Switching(model)
        self._settings = SolverSettings(
            t_end=self.period,
            rtol=RTOL,
            atol=RTOL,
            dt=self.period / _DENSE_SAMPLES,
            t_discard=0.0,
            backend=backend,
        )
        self._sliding = None

    def one_period(
        self, x: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], EventPeriod, dict | None]:
        """``(P(x), dP/dx, period, grazing)`` from the full state ``x`` at phase 0."""
        try:
            run = integrate_events(self.model, self._settings, y0=np.array(x, dtype=float))
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"period map: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"period map: {run.message}")
        m = variational.monodromy(run, self.backend)
        period = EventPeriod.of(run, m.switches)
        return period.final, m.matrix, period, self._grazing(m.switches)

    def step(self, x: ArrayLike) -> NDArray[np.float64]:
        """The full state one excitation period after ``x``: the run alone, without its
        monodromy (most of `one_period`'s cost), for forward iterations."""
        try:
            run = integrate_events(self.model, self._settings, y0=np.array(x, dtype=float))
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"period map: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"period map: {run.message}")
        tr = run.trajectory
        return tr.state(np.array([tr.t_end]))[:, 0]

    def fixed_multipliers(self) -> NDArray[np.complex128]:
        """None: every direction is shot in."""
        return np.zeros(0, dtype=complex)

    def full_state(self, x: ArrayLike) -> NDArray[np.float64]:
        """``x`` itself."""
        return np.array(x, dtype=float)

    @staticmethod
    def shooting(state: ArrayLike) -> NDArray[np.float64]:
        """Full states as they are."""
        return np.asarray(state, dtype=float)

    def sliding_guess(self) -> NDArray[np.float64]:
        """The periodic orbit of the backward-sliding field alone, by Newton's method.

        The field of the mode ``slip_back`` (`beltmdsm.generated.hybrid.vector_field`; without
        its contact force where ``X2 < 0``, as in flight) is integrated over one period
        with no switch watched (the compiled DOP853 of `beltmdsm.integrate._dop853`),
        its Jacobian by the step propagators of `beltmdsm.periodic.variational`, from
        the unforced equilibrium (Eq. 9). The Jacobian is kept while the residual at
        least halves (a chord method: the field is linear in the tangential state under
        Coulomb friction and nearly so under Stribeck's, so one Jacobian serves most
        iterations). It is the counterpart of the closed-form sliding orbit of
        `beltmdsm.periodic.closed_form.ClosedFormMap` and the same where the mass slides
        back in contact throughout; where the iterations do not settle in
        `_SLIDING_ITER`, the last iterate is the guess (kept).
        """
        if self._sliding is not None:
            return self._sliding.copy()
        sw = self.sw
        advance = _compiled.advance("vector_field", self.model, self.backend)
        watch, dirs = np.zeros(0, dtype=np.int64), np.zeros(0)
        mode = float(Mode.SLIP_BACK)
        x, M, last = initial_state(self.model), None, np.inf
        for _ in range(_SLIDING_ITER):
            code, n, ts, hs, ys, Fs, t_stop, y, _, _ = advance(
                sw.field.args,
                sw.surfaces.args,
                sw.rates.args,
                mode,
                watch,
                dirs,
                0.0,
                x,
                self.period,
                0.0,
                RTOL,
                RTOL,
                np.inf,
                _SLIDING_STEPS,
            )
            if code != _dop853.STATUS_END:
                # too stiff to be worth a guess (a slip law that changes on a small
                # velocity scale where this continued field crosses Vr = 0), or no
                # end at all: the last iterate is the guess
                break
            r = np.asarray(y) - x
            size = float(np.max(np.abs(r)))
            if size <= NEWTON_TOL * (1.0 + np.max(np.abs(x))):
                break
            if M is None or size > 0.5 * last:
                ts, hs, ys, Fs = ts[:n], hs[:n], ys[:n], Fs[:n]
                ends = np.minimum(ts + hs, np.append(ts[1:], t_stop))
                M = np.eye(4)
                for R in variational.propagators(
                    self.model, ts, hs, ys, Fs, ends, np.full(n, mode)
                ):
                    M = R @ M
            last = size
            try:
                x_new = x + np.linalg.solve(np.eye(4) - M, r)
            except np.linalg.LinAlgError:
                break
            if not np.all(np.isfinite(x_new)):
                break
            x = x_new
        self._sliding = x
        return x.copy()
