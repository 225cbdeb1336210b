"""The closed-form period map: the tangential map of Eq. (4) on its periodic normal motion.

`ClosedFormMap` (engine ``"closed_form"``; ``ClosedFormMap`` before issue 38, an
alias) is the fast special case of
`beltmdsm.periodic.base.PeriodMap`, where the slip-mode friction does not depend on
the tangential state and the normal equation is free of it (`CLOSED_FORM_FACTS`:
Coulomb friction with every contact and tension law); it refuses a model without them
(`beltmdsm.errors.Unsupported`). On Eq. (4) with those facts:

* **Structure.** The normal equation of Eq. (4) does not contain the tangential
  state, so the monodromy matrix (the Jacobian of the period map) is block
  triangular, ``[[M_t, M_tn], [0, M_n]]``, and the multipliers are those of the
  tangential block ``M_t`` and of the normal block ``M_n``. The normal block belongs
  to the periodic orbit of the normal motion (`beltmdsm.periodic.normal_orbit.normal_orbit`,
  cached per normal parameter set).
* **Tangential block.** Between switches the tangential variational flow is the
  closed-form state-transition matrix of the tangential oscillator
  (`beltmdsm.generated.oscillator.state_transition`; the identity while sticking, where
  ``X1' = Vb`` holds whatever the perturbation); across a switch it jumps by the
  tangential block of the saltation matrix (`beltmdsm.generated.hybrid.saltation`). So over
  one period ``M_t = Phi(T - t_n) S_n ... Phi(t_2 - t_1) S_1 Phi(t_1)``, on the
  closed-form superposition of the tangential motion
  (`beltmdsm.integrate.superposition.Superposition`). A stick phase makes ``M_t``
  singular (the saltation into stick zeroes the velocity perturbation). The
  ``k``-fold map applies the one-period map ``k`` times; its Jacobian is the product.
* **Grazing.** A reversal reached with a vanishing acceleration is reported as grazing
  (`beltmdsm.periodic.margins.GRAZING_RATIO`).

`largest_sliding_velocity` is the largest velocity of the backward-sliding orbit in
contact, where that orbit grazes the belt's speed.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import hybrid

from ..errors import NoPeriodicResponse
from ..integrate import _compiled
from ..integrate.normal import normal_motion
from ..integrate.superposition import FACTS as SUPERPOSITION_FACTS
from ..integrate.superposition import Superposition, TangentialRun, friction_direction
from ..integrate.switching import Mode
from ..model import Backend, Model, require
from .base import RTOL, PeriodMap, _periods
from .margins import GRAZING_RATIO, crossing_ratio
from .newton import ISOLATION_TOL
from .normal_orbit import normal_orbit

__all__ = [
    "CLOSED_FORM_FACTS",
    "ClosedFormMap",
    "OnePeriodMap",
    "ClosedFormMap",
    "largest_sliding_velocity",
]

#: The facts of the laws (``beltmdsm.generated.capabilities``) that the closed-form path needs,
#: those of the superposition it runs on: the slip-mode friction free of the
#: tangential state (the tangential motion is linear between switches) and the normal
#: equation free of it (the cached normal orbit, the block-triangular monodromy).
CLOSED_FORM_FACTS = SUPERPOSITION_FACTS


class OnePeriodMap:
    """One excitation period of `ClosedFormMap` (its step, not another engine): the
    tangential period map over one period on the periodic normal motion.

    ``map(x)`` is ``(P(x), M_t, run, grazing)``: the image of the tangential state
    ``x`` at phase 0, the Jacobian of the map there (module docstring), the
    `beltmdsm.integrate.superposition.TangentialRun` and the grazing switch or None.

    Parameters
    ----------
    model : Model
    backend : {"python", "numba", None}

    Raises
    ------
    beltmdsm.errors.Unsupported
        Where a fact of `CLOSED_FORM_FACTS` does not hold for the model's laws (the
        law and the property).
    beltmdsm.errors.NoPeriodicResponse
        Where the normal motion has no periodic orbit.

    See Also
    --------
    ClosedFormMap : its ``k``-fold map, the closed-form `beltmdsm.periodic.base.PeriodMap`.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> one = OnePeriodMap(Model(Vb=5.0))
    >>> state, M_t, run, grazing = one(one.sliding_orbit())
    >>> state.shape, M_t.shape, len(run.switches), grazing
    ((2,), (2, 2), 2, None)
    """

    def __init__(self, model: Model, backend: Backend | None = None) -> None:
        for fact in CLOSED_FORM_FACTS:
            require(model, fact, "the closed-form period map")
        self.model, self.p = model, model.params
        self.orbit = normal_orbit(model)
        self.T = self.orbit.period
        normal = normal_motion(model, self.T, RTOL, RTOL, self.orbit.state0, backend)
        self.engine = Superposition(model, normal, backend)
        self.stm, self.sw = self.engine.stm, self.engine.sw
        self._saltation = {}
        self.backend = backend

    def __getstate__(self) -> dict[str, Any]:
        # ``p`` is the model's read-only view of its parameters, which does not pickle;
        # it is rebuilt from the model (results holding a map travel to other processes)
        return {k: v for k, v in self.__dict__.items() if k != "p"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self.p = self.model.params

    def sliding_orbit(self) -> NDArray[np.float64]:
        """``(X1, X1')`` at phase 0 of the orbit that slides backwards throughout.

        Sliding back in contact and free of friction in flight or separation (where the
        response ``z`` to the contact force has no forcing), the tangential motion is
        one superposition with ``sgn = -1`` (`beltmdsm.generated.oscillator.tangential_state`),
        affine in the start: ``x(T) = Phi(T) x0 + c`` with ``c`` the motion from
        ``x0 = 0``, whose fixed point solves ``(I - Phi(T)) x0 = c``.
        """
        engine = self.engine
        start = engine.start(0.0, 0.0, 0.0)
        z, v = engine.normal.evaluate(np.array([self.T]))[:2, 0]
        sgn = friction_direction(Mode.SLIP_BACK)
        c = np.array(engine.state(self.T, *start, *engine.exc(self.T), z, v, sgn))
        Phi = np.array(self.stm(self.T)).reshape(2, 2)
        smallest = float(np.linalg.svd(np.eye(2) - Phi, compute_uv=False)[-1])
        if smallest <= ISOLATION_TOL * max(1.0, float(np.max(np.abs(Phi)))):
            raise NoPeriodicResponse(
                "no periodic response found: the response is not isolated: a multiplier "
                f"is 1 (I - M singular: the smallest singular value of I - Phi(T) of the "
                f"backward-sliding motion is {smallest:.1e}), so its periodic responses form "
                "a family (an undamped free oscillation whose period divides the "
                f"excitation's, T = {self.T:.6g} s) and shooting has no isolated one to "
                "converge to; with damping (beta1 > 0) or a detuned omega1 it is isolated"
            )
        return np.linalg.solve(np.eye(2) - Phi, c)

    def saltation(self, before: Mode, after: Mode, surface: str) -> Any:
        """The bound saltation matrix of one switch (`beltmdsm.generated.hybrid.saltation`),
        kept."""
        key = (before, after, surface)
        if key not in self._saltation:
            self._saltation[key] = hybrid.bind_saltation(
                before=before.name.lower(),
                after=after.name.lower(),
                surface=surface,
                backend=_compiled.scalar_backend(self.backend),
                **self.model.arguments(hybrid.bind_saltation),
            )
        return self._saltation[key]

    def __call__(
        self, x: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], TangentialRun, dict | None]:
        """``(P(x), M_t, run, grazing)`` for the tangential state ``x`` at phase 0."""
        run = self.engine.run(0.0, float(x[0]), float(x[1]), self.T)
        if run.status != "done":
            raise NoPeriodicResponse(f"period map: {run.message}")
        M = np.eye(2)
        grazing = None
        for (t0, t1, mode), switch in zip(
            zip(run.starts, run.ends, run.modes), run.switches + [None]
        ):
            if mode != Mode.STICK:
                M = np.array(self.stm(t1 - t0)).reshape(2, 2) @ M
            if switch is None:
                continue
            t, before, after, surface, state = switch
            if after != before:  # a touch that keeps the mode has one field: S = I
                S = np.array(self.saltation(before, after, surface)(t, *state)).reshape(4, 4)
                M = S[:2, :2] @ M
            if surface == "relative_velocity" and grazing is None:
                ratio = crossing_ratio(self.sw, t, state, before, surface)
                if ratio < GRAZING_RATIO:
                    grazing = {"t": float(t), "surface": surface, "ratio": float(ratio)}
        return run.final[:2], M, run, grazing


class ClosedFormMap(PeriodMap):
    """``k`` periods of the tangential period map of Eq. (4) on its periodic normal motion.

    The closed-form path (module docstring): the shooting state is ``(X1, X1')`` at
    phase 0, the normal motion the cached periodic orbit (`normal_orbit`). It needs the
    facts `CLOSED_FORM_FACTS` of the model's laws (``beltmdsm.generated.capabilities``) and
    refuses a model without them.

    Parameters
    ----------
    model : Model
    periods : int
        ``k >= 1``.
    backend : {"python", "numba", None}

    Raises
    ------
    beltmdsm.model.Unsupported
        Where a fact of `CLOSED_FORM_FACTS` does not hold (the law and the property).
    ValueError
        For ``periods < 1``, or an excitation without a period.
    NoPeriodicResponse
        Where the normal motion has no periodic orbit.

    See Also
    --------
    beltmdsm.periodic.general_map.GeneralMap : the general engine, every law.
    beltmdsm.periodic.engines.period_map : the engine the laws allow.

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model, Unsupported
    >>> pmap = ClosedFormMap(Model(Vb=5.0))
    >>> np.round(np.abs(pmap.fixed_multipliers()), 3)  # the normal block's
    array([0.701, 0.   ])
    >>> try:
    ...     ClosedFormMap(Model(friction="stribeck"))
    ... except Unsupported as refusal:
    ...     print(refusal)  # doctest: +ELLIPSIS
    the closed-form period map: friction='stribeck': the slip-mode friction ... depends on X1' ...
    """

    engine = "closed_form"

    def __init__(self, model: Model, periods: int = 1, backend: Backend | None = None) -> None:
        self.periods = _periods(periods)
        self.model = model
        self.one = OnePeriodMap(model, backend)
        self.period = self.one.T
        self.sw = self.one.sw

    def one_period(
        self, x: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], TangentialRun, dict | None]:
        """``(P(x), M_t, run, grazing)`` of `OnePeriodMap`."""
        return self.one(x)

    def step(self, x: ArrayLike) -> NDArray[np.float64]:
        """The tangential state one excitation period after ``x``: the run alone, without
        the Jacobian and the grazing test of `one_period` (a third of its cost), for the
        forward iterations that read the state only (basins, attractors of the map)."""
        run = self.one.engine.run(0.0, float(x[0]), float(x[1]), self.period)
        if run.status != "done":
            raise NoPeriodicResponse(f"period map: {run.message}")
        return np.array(run.final[:2], dtype=float)

    def fixed_multipliers(self) -> NDArray[np.complex128]:
        """The normal block's multipliers to the power ``k``."""
        return np.asarray(self.one.orbit.multipliers, dtype=complex) ** self.periods

    def full_state(self, x: ArrayLike) -> NDArray[np.float64]:
        """``x`` with the periodic normal motion's state at phase 0."""
        return np.concatenate([np.asarray(x, dtype=float), self.one.orbit.state0])

    @staticmethod
    def shooting(state: ArrayLike) -> NDArray[np.float64]:
        """``(X1, X1')`` of full states."""
        return np.asarray(state, dtype=float)[..., :2]

    def sliding_guess(self) -> NDArray[np.float64]:
        """`OnePeriodMap.sliding_orbit`."""
        return self.one.sliding_orbit()


def largest_sliding_velocity(pmap: OnePeriodMap) -> float:
    """The largest ``X1'`` over one period of the backward-sliding orbit, in contact.

    ``pmap`` is a one-period map of the closed-form path (``ClosedFormMap.one``). Out of
    contact (flight, separation) there is no friction to reverse, so only the times in
    contact count. Where the slip-mode friction does not depend on the tangential state
    (the closed-form path's condition) it does not depend on ``Vb``: the sliding
    response grazes at the belt speed equal to it (`beltmdsm.continuation.band`).

    Parameters
    ----------
    pmap : OnePeriodMap

    Returns
    -------
    float
        ``max X1'`` in contact [m/s], refined to 1e-12 s by a bounded search.

    Raises
    ------
    beltmdsm.errors.NoPeriodicResponse
        Where the sliding orbit is not isolated (`OnePeriodMap.sliding_orbit`).

    See Also
    --------
    beltmdsm.continuation.band.floquet_band : the grazing edge it predicts.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> round(largest_sliding_velocity(OnePeriodMap(Model(Vb=5.0))), 3)
    6.415
    """
    x0 = pmap.sliding_orbit()
    engine = pmap.engine
    normal = engine.normal
    grid = normal.grid[normal.grid <= pmap.T]
    segment = np.clip(
        np.searchsorted(normal.switch_t, grid, side="right") - 1, 0, len(normal.switch_mode) - 1
    )
    contact = np.array([mode == Mode.SLIP_BACK for mode in normal.switch_mode])[segment]
    # the orbit is one superposition from phase 0 (`OnePeriodMap.sliding_orbit`)
    start, sgn = engine.start(0.0, x0[0], x0[1]), friction_direction(Mode.SLIP_BACK)
    z, v, _, _, zf, vf = normal.on_grid[:, : grid.size]
    v = engine.state.array(grid, *start, zf, vf, z, v, sgn)[1]
    v = np.where(contact, v, -np.inf)
    k = int(np.argmax(v))

    def minus_velocity(t):
        z, v = normal.at(t)[:2]
        return -engine.state(t, *start, *engine.exc(t), z, v, sgn)[1]

    from scipy import optimize

    # refine within the contact segment that holds the largest grid value
    lo = max(grid[max(k - 1, 0)], normal.switch_t[segment[k]])
    hi = min(grid[min(k + 1, grid.size - 1)], normal.switch_t[segment[k] + 1])
    best = optimize.minimize_scalar(
        minus_velocity, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12}
    )
    return float(max(-best.fun, v[k]))


#: The closed-form engine's names before issue 38: one name now, ``"closed_form"``
#: (`ClosedFormMap`); ``OnePeriodMap`` stays the name of its one-period step.
TangentialMap = ClosedFormMap
