"""The period map of Eq. (4) as an object: the state at phase 0 to the state ``k`` periods later.

The analyses of periodic responses (shooting on the ``k``-fold map in
`beltmdsm.periodic.floquet`, branches, edges, bands and two-parameter maps:
`beltmdsm.continuation.branch`, `beltmdsm.continuation.edges`, `beltmdsm.continuation.band`,
`beltmdsm.continuation.floquet_map`) see a period map only through `PeriodMap`: a
callable from the shooting state ``x`` at phase 0 to a `MapImage` (the state ``k``
excitation periods later, its Jacobian, the switches on the way and the `Margin` of
every feature of the orbit that a parameter change could remove), plus the
multipliers of the directions that are not part of the shooting state. Two engines
implement it (`ENGINES`), and `period_map` chooses by the structural facts of the
model's laws that SymPy decided (``generated.capabilities``), never by assumption:

* `TangentialMap` (``"closed_form"``), the fast special case, where the slip-mode
  friction does not depend on the tangential state and the normal equation is free
  of it (`CLOSED_FORM_FACTS`: Coulomb friction with every contact and tension law);
  it refuses a model without them (`beltmdsm.model.Unsupported`).
* `GeneralMap` (``"general"``), every law: the event-driven run in the full state
  ``(X1, X1', X2, X2')`` and its monodromy by the variational equations
  (`beltmdsm.periodic.variational`). Where both apply they agree to 1e-9 in the
  multipliers (tests/beltmdsm/periodic/test_general.py).

`TangentialMap` on Eq. (4) with those facts:

* **Structure.** The normal equation of Eq. (4) does not contain the tangential
  state, so the monodromy matrix (the Jacobian of the period map) is block
  triangular, ``[[M_t, M_tn], [0, M_n]]``, and the multipliers are those of the
  tangential block ``M_t`` and of the normal block ``M_n``. The normal block belongs
  to the periodic orbit of the (overdamped) normal motion, which depends only on
  what the normal equation contains (not on ``Vb``, ``mu_s`` or the tangential
  parameters): `normal_orbit` computes it once per normal parameter set (cached), by
  shooting on the normal period map with the variational equation (the normal block
  of `generated.hybrid.mode_jacobian`, through the integrator's own steps) and the
  normal blocks of the saltation matrices.
* **Tangential block.** Between switches the tangential variational flow is the
  closed-form state-transition matrix of the tangential oscillator
  (`generated.oscillator.state_transition`; the identity while sticking, where
  ``X1' = Vb`` holds whatever the perturbation); across a switch it jumps by the
  tangential block of the saltation matrix (`generated.hybrid.saltation`). So over
  one period ``M_t = Phi(T - t_n) S_n ... Phi(t_2 - t_1) S_1 Phi(t_1)``, on the
  closed-form superposition of the tangential motion
  (`beltmdsm.integrate.superposition.Superposition`). A stick phase makes ``M_t``
  singular (the saltation into stick zeroes the velocity perturbation). The
  ``k``-fold map applies the one-period map ``k`` times; its Jacobian is the product.
* **Grazing.** Where a reversal is reached with a vanishing acceleration (a velocity
  that just touches the belt's), the saltation entry ``a_after / a_before`` diverges
  (the square-root singularity of grazing bifurcations). A switch whose rate is
  below `GRAZING_RATIO` of its scale is reported as grazing.

`GeneralMap` shoots in the full state with the Jacobian of the whole period map, its
multipliers all four eigenvalues of it; the grazing test and the margins below are
read from its runs as from `TangentialMap`'s (the same switches, the same rules).

`fixed_point` is Newton's method on ``P(x) - x`` with damped steps (``dP/dx - I`` its
Jacobian): the shooting of a response of period ``k T`` from a guess (the sliding
orbit, an attractor of the map, a neighbour on a branch). `MapFamily` is the maps of
one parameter's values, with the map's derivative in that parameter.

Margins (how far an orbit is from changing its switch structure; positive away
from the change, dimensionless):

* ``crossing``: the rate of a switching function at a crossing, along the mode
  before, over the function's rounding scale (`generated.hybrid.surface_rates`,
  `surface_scales`). It vanishes where a crossing becomes tangential: a
  **tangency**, where the saltation matrix and the multipliers diverge.
* ``approach``: the closest approach of a segment to a surface it does not cross
  (an interior maximum of ``Vr`` while sliding back, a minimum while sliding
  forward, a minimum of the friction margin while sticking), over its scale. It
  vanishes at **grazing**, where the segment touches the surface and new switches
  appear.
* ``decision``: at ``Vr = 0`` (and on entering contact), how far Filippov's choice
  (`beltmdsm.integrate.switching.Switching.decide_slip`) is from the other outcome (a
  reversal from sticking, a stick from reversing). It vanishes where a stick phase
  appears or disappears, also a grazing.
"""

from __future__ import annotations

import abc
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from generated import dynamics, hybrid

from ..errors import NoPeriodicResponse  # its home; importable here as before
from ..integrate import _compiled, _dop853
from ..integrate.events import StepTooSmall, integrate_events
from ..integrate.normal import NormalMotion, normal_motion
from ..integrate.superposition import FACTS as SUPERPOSITION_FACTS
from ..integrate.superposition import Superposition, TangentialRun, friction_direction
from ..integrate.switching import SURFACE_INDEX, Mode, Switching
from ..integrate.trajectory import Run
from ..model import Backend, Model, excitation_period, initial_state, require
from ..settings import SolverSettings, check_finite
from . import variational

__all__ = [
    "NoPeriodicResponse",
    "GRAZING_RATIO",
    "NEWTON_TOL",
    "RTOL",
    "NormalOrbit",
    "normal_orbit",
    "Margin",
    "MARGIN_KINDS",
    "OnePeriodMap",
    "MapImage",
    "PeriodMap",
    "TangentialMap",
    "GeneralMap",
    "EventPeriod",
    "CLOSED_FORM_FACTS",
    "ENGINES",
    "Engine",
    "engine_of",
    "period_map",
    "crossing_ratio",
    "MapFamily",
    "FixedPoint",
    "fixed_point",
    "signature",
    "orbit_range",
]

#: A switch whose rate is below this fraction of its scale is grazing: the saltation
#: entry a_after / a_before then carries a relative rounding error of about
#: ulps / ratio, so below it a multiplier would keep fewer than 8 correct digits.
GRAZING_RATIO = 1e-8
#: Newton's method stops when the period map moves the state by less than this
#: (relative to the state's scale).
NEWTON_TOL = 1e-11
#: ``I - M`` whose smallest singular value is below this (relative to ``M``) is singular:
#: a multiplier is 1 to within the closed forms' rounding amplified far past it, and the
#: fixed point, if any, is not isolated (its solve would return ~ 1 / this times the
#: forcing, or rounding noise).
ISOLATION_TOL = 1e-9
#: Integration tolerance of the periodic orbits.
RTOL = 1e-12
#: Halvings of a Newton step before the method counts as stalled.
_LINE_SEARCH = 8
#: Iterations over which Newton's residual must halve (converging, it squares; where
#: the orbit has stopped existing, the damped steps creep towards a switch-structure
#: change and the residual shrinks by a few per cent per iteration). 2 finds the same
#: periodic responses as 4 at all 262 points of the quick validation grids and every
#: band of its 16 cases, with a third fewer period maps in a band.
_STAGNATION = 2
#: Periods the normal motion is followed before Newton's method polishes its orbit.
_NORMAL_PERIODS = 200
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

MarginKind = Literal["crossing", "approach", "decision"]
Engine = Literal["closed_form", "general"]
#: The kinds of `Margin`.
MARGIN_KINDS = ("crossing", "decision", "approach")
#: Samples per second of a segment when its closest approach is searched.
_SAMPLES_PER_S = 200
#: A sampled closest approach below this (relative) is refined to machine precision.
_REFINE_BELOW = 0.2
_VR = SURFACE_INDEX["relative_velocity"]
_SF = SURFACE_INDEX["stick_forward"]
_SB = SURFACE_INDEX["stick_back"]
_TANGENTIAL = ("relative_velocity", "stick_forward", "stick_back")


# ---------------------------------------------------------------- the normal block


@dataclass
class NormalOrbit:
    """The periodic normal motion: ``(X2, X2')`` at phase 0, its monodromy, its switches."""

    state0: np.ndarray
    period: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    switches: list = field(default_factory=list)
    iterations: int = 0


def _normal_flow(model, x0, T):
    """The normal state after ``T``, the monodromy of the normal block and the switches.

    The normal motion of `beltmdsm.integrate.normal.NormalMotion` (the compiled DOP853
    integrator, mode by mode with located switches, the motion the tangential map is
    built on), with its variational equation carried through the same steps
    (`beltmdsm.periodic.variational.propagators`) and the normal block of the saltation
    matrix applied at each switch (the steps next to a touchdown or a lift-off in
    graded pieces, `beltmdsm.periodic.variational.graded_pieces`). Under one-way
    coupling the Jacobians and the saltation matrices are block-triangular: their
    normal blocks, taken at zero tangential state, multiply on their own.
    """
    motion = NormalMotion(model, T, RTOL, RTOL, x0)
    t_steps, h_steps = motion.t_steps, motion.h_steps
    ends = np.minimum(t_steps + h_steps, np.append(t_steps[1:], T))
    contact = [t for t, s in zip(motion.switch_t[1:], motion.switch_surface) if s == "penetration"]
    index, starts, piece_ends = variational.graded_pieces(t_steps, ends, contact)
    # the tangential slots hold z (the response to the contact force): put the
    # tangential state to zero, which the normal block does not read
    y_steps, F_steps = motion.y_steps[index].copy(), motion.F_steps[index].copy()
    y_steps[:, :2] = 0.0
    F_steps[:, :, :2] = 0.0
    segment = np.searchsorted(motion.switch_t, 0.5 * (starts + piece_ends), side="right") - 1
    modes = np.array([float(motion.switch_mode[k]) for k in segment])
    R = variational.propagators(
        model, t_steps[index], h_steps[index], y_steps, F_steps, piece_ends, modes, starts
    )
    # the pieces of each segment, then the saltation of the switch that ends it
    cuts = np.searchsorted(starts, motion.switch_t[1:-1], side="left")
    M, first, switches = np.eye(2), 0, []
    for i, (t, cut) in enumerate(zip(motion.switch_t[1:-1], cuts)):
        for k in range(first, cut):
            M = R[k, 2:, 2:] @ M
        first = cut
        before, after = motion.switch_mode[i], motion.switch_mode[i + 1]
        surface = motion.switch_surface[i]
        state = np.array([0.0, 0.0, *motion.at(t)[2:]])
        S = variational.saltation(model, before, after, surface)(t, *state)
        M = np.array(S).reshape(4, 4)[2:, 2:] @ M
        switches.append((float(t), before, after, surface))
    for k in range(first, starts.size):
        M = R[k, 2:, 2:] @ M
    return motion.at(T)[2:], M, switches


#: The normal orbits of the last parameter sets, by `_normal_orbit_key`.
_NORMAL_ORBITS: dict = {}
_NORMAL_ORBITS_KEPT = 16


def _normal_orbit(model):
    T = excitation_period(model)
    # The normal motion is overdamped: follow it from the equilibrium until it repeats
    # itself to 1e-4 (a few periods; more where it loses contact), then Newton.
    x = initial_state(model)[2:]
    for _ in range(_NORMAL_PERIODS):
        xT, M, switches = _normal_flow(model, x, T)
        close = np.max(np.abs(xT - x)) <= 1e-4 * (1 + np.max(np.abs(x)))
        x = xT
        if close:
            break
    for iteration in range(1, 31):  # noqa: B007 (the count is reported after the loop)
        xT, M, switches = _normal_flow(model, x, T)
        r = xT - x
        if np.max(np.abs(r)) <= NEWTON_TOL * (1 + np.max(np.abs(x))):
            break
        x = x + np.linalg.lstsq(np.eye(2) - M, r, rcond=None)[0]
    else:
        raise NoPeriodicResponse(
            "the normal motion has no periodic orbit: followed from the "
            f"equilibrium for {_NORMAL_PERIODS} periods and then by Newton's "
            "method it does not repeat itself (it loses contact irregularly)"
        )
    xT, M, switches = _normal_flow(model, x, T)
    return NormalOrbit(x, T, M, np.linalg.eigvals(M), switches, iteration)


#: The parameter names of the normal orbit's key by contact and tension law.
_NORMAL_NAMES: dict[tuple[str, str], tuple[str, ...]] = {}


def _normal_orbit_key(model):
    """What the normal orbit depends on: the parameters of the generated normal equation
    and its Jacobian (as the generated code declares them: the names depend on the laws
    only, found once per pair), the period and the laws."""
    laws = tuple(model.options.values())
    names = _NORMAL_NAMES.get(laws)
    if names is None:
        bind_rhs, bind_jac = dynamics.bind_normal_rhs, dynamics.bind_normal_jacobian
        used = bind_rhs(backend="python", **model.arguments(bind_rhs)).params
        used |= bind_jac(backend="python", **model.arguments(bind_jac)).params
        names = _NORMAL_NAMES[laws] = tuple(sorted(used))
    p = model.params
    return (*laws, tuple((k, float(p[k])) for k in names), excitation_period(model))


def normal_orbit(model: Model) -> NormalOrbit:
    """The periodic orbit of the normal motion (cached per normal parameter set).

    The key is what the normal equation contains (the parameters of
    `generated.dynamics.normal_rhs` and ``normal_jacobian``), the excitation period
    and the laws: a band or a map over ``beta1``, ``omega1``, ``mu_s`` or ``Vb``
    computes one normal orbit.

    Raises
    ------
    beltmdsm.model.Unsupported
        Where the normal equation is not free of the tangential state (the law).
    """
    require(model, "one_way_coupling", "the normal orbit")
    key = _normal_orbit_key(model)
    if key not in _NORMAL_ORBITS:
        if len(_NORMAL_ORBITS) >= _NORMAL_ORBITS_KEPT:
            del _NORMAL_ORBITS[next(iter(_NORMAL_ORBITS))]
        _NORMAL_ORBITS[key] = _normal_orbit(model)
    return _NORMAL_ORBITS[key]


# ---------------------------------------------------------------- the tangential map


class OnePeriodMap:
    """The tangential period map over one excitation period on the periodic normal motion.

    ``map(x)`` is ``(P(x), M_t, run, grazing)``: the image of the tangential state
    ``x`` at phase 0, the Jacobian of the map there (module docstring), the
    `beltmdsm.integrate.superposition.TangentialRun` and the grazing switch or None.

    Parameters
    ----------
    model : Model
    backend : {"python", "numba", None}

    Raises
    ------
    beltmdsm.model.Unsupported
        Where a fact of `CLOSED_FORM_FACTS` does not hold for the model's laws (the
        law and the property).
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
        one superposition with ``sgn = -1`` (`generated.oscillator.tangential_state`),
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
        """The bound saltation matrix of one switch (`generated.hybrid.saltation`), kept."""
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


def crossing_ratio(sw: Switching, t: float, state: ArrayLike, before: Mode, surface: str) -> float:
    """The rate of a switching function at a crossing, along the mode before, over the
    rounding scale of the friction cone (an acceleration, as the rate of ``Vr`` and of
    the cone's functions is): the ``crossing`` margin, and the grazing test."""
    rate = sw.rates(t, *state, float(before))[SURFACE_INDEX[surface]]
    scale = sw.scales(t, *state)[_SF]
    return float(abs(rate) / scale) if scale > 0 else 0.0


@dataclass(frozen=True)
class Margin:
    """How far one feature of an orbit is from a change of its switch structure.

    Attributes
    ----------
    kind : {"crossing", "approach", "decision"}
        See the module docstring.
    surface : str
        The switching surface (`generated.hybrid.SURFACES`).
    mode : Mode
        The mode before the crossing, or of the segment.
    t : float
        Time from phase 0 [s].
    value : float
        Positive away from the change, zero at it.
    """

    kind: MarginKind
    surface: str
    mode: Mode
    t: float
    value: float


def signature(switches: Sequence[tuple]) -> tuple:
    """The switch structure of an orbit: the ``(before, after, surface)`` of its switches."""
    return tuple((int(b), int(a), s) for _, b, a, s in switches)


@dataclass
class MapImage:
    """One application of a period map at a state.

    Attributes
    ----------
    start, state : ndarray (n,)
        The shooting state at phase 0 and its image ``k`` periods later.
    jacobian : ndarray (n, n)
        ``d state / d start``.
    switches : list of (t, before, after, surface)
        Every switch on the way, ``t`` from phase 0 of the first period.
    segments : list of (t0, t1, mode)
    grazing : dict or None
        ``{"t", "surface", "ratio"}`` of a crossing whose rate is too small for a
        multiplier with 8 correct digits (`GRAZING_RATIO`).
    """

    start: NDArray[np.float64]
    state: NDArray[np.float64]
    jacobian: NDArray[np.float64]
    switches: list
    segments: list
    grazing: dict | None
    _map: PeriodMap = field(repr=False)
    _runs: list = field(repr=False)
    _margins: dict = field(default_factory=dict, repr=False)

    @property
    def signature(self) -> tuple:
        """`signature` of the switches."""
        return signature(self.switches)

    @property
    def phases(self) -> list[NDArray[np.float64]]:
        """The shooting state at phase 0 of each of the ``k`` periods."""
        return [self.start] + [self._map.shooting(r.final) for r in self._runs[:-1]]

    @property
    def margins(self) -> list[Margin]:
        """Every `Margin` of the orbit through ``start`` (computed once)."""
        return self.margins_of(MARGIN_KINDS)

    def margins_of(self, kinds: Sequence[str]) -> list[Margin]:
        """The margins of the given kinds (the ``approach`` ones cost most: a search)."""
        missing = tuple(k for k in kinds if k not in self._margins)
        if missing:
            found = self._map.margins(self._runs, missing)
            for k in missing:
                self._margins[k] = [m for m in found if m.kind == k]
        return [m for k in kinds for m in self._margins[k]]

    def velocity_range(self) -> tuple[float, float]:
        """The smallest and largest ``X1'`` over the ``k`` periods."""
        return self._map.velocity_range(self._runs)

    def x1_range(self) -> tuple[float, float]:
        """The smallest and largest ``X1`` over the ``k`` periods."""
        return orbit_range(self._runs, 0)


class PeriodMap(abc.ABC):
    """What the algorithms on periodic responses need of a period map.

    ``model`` is the model, ``period`` one excitation period, ``periods`` the number
    ``k`` of them per application, ``engine`` the name of the implementation (`ENGINES`),
    ``sw`` the model's switching rules. An implementation gives the map over one
    excitation period (`one_period`), the multipliers of the directions it does not
    shoot in, how a full state and its shooting state relate, and the first guess of
    the shooting. The ``k``-fold map (`__call__`) and what an orbit is near (its
    margins, the module docstring, and its velocity range) are read here from the
    runs of the ``k`` periods, whatever the engine: each run has ``starts``, ``ends``
    and ``modes`` of its segments, ``switches`` ``(t, before, after, surface,
    state)``, ``final`` (the state where it ends) and ``segments(t, index) -> (4, n)``.
    """

    model: Model
    period: float
    periods: int
    sw: Switching
    engine: ClassVar[str]

    @abc.abstractmethod
    def one_period(
        self, x: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], Any, dict | None]:
        """``(P(x), dP/dx, run, grazing)`` over one excitation period from the shooting
        state ``x`` at phase 0 (raises NoPeriodicResponse)."""

    @abc.abstractmethod
    def fixed_multipliers(self) -> NDArray[np.complex128]:
        """Multipliers of the directions outside the shooting state (over ``k`` periods)."""

    @abc.abstractmethod
    def full_state(self, x: ArrayLike) -> NDArray[np.float64]:
        """``(X1, X1', X2, X2')`` at phase 0 of the shooting state ``x``."""

    @staticmethod
    @abc.abstractmethod
    def shooting(state: ArrayLike) -> NDArray[np.float64]:
        """The shooting state of full states ``(..., 4)``: the last axis cut to the shot ones."""

    @abc.abstractmethod
    def sliding_guess(self) -> NDArray[np.float64]:
        """The shooting state of the orbit that slides backwards throughout: the first
        guess of the shooting, exact where the friction never reverses."""

    def guess(self, x: ArrayLike) -> NDArray[np.float64]:
        """A shooting state from a full state (4 numbers) or a shooting state.

        Raises
        ------
        ValueError
            For a guess of another size.
        """
        x = np.array(x, dtype=float).ravel()
        n = self.dimension
        if x.size == 4:
            return self.shooting(x)
        if x.size == 2 and n == 4:
            # the tangential state, the normal one from the sliding orbit
            return np.concatenate([x, self.sliding_guess()[2:]])
        if x.size != n:
            raise ValueError(f"a guess must be {n} or 4 numbers; got {x.size}")
        return x

    @property
    def dimension(self) -> int:
        """The size of the shooting state."""
        return int(self.shooting(np.zeros(4)).size)

    def step(self, x: ArrayLike) -> NDArray[np.float64]:
        """The shooting state one excitation period after ``x`` (forward iteration)."""
        return np.array(self.one_period(x)[0], dtype=float)

    def __call__(self, x: ArrayLike) -> MapImage:
        """The image of the shooting state ``x`` at phase 0 (raises NoPeriodicResponse)."""
        start = np.array(x, dtype=float)
        y, M = start, np.eye(start.size)
        switches, segments, runs, grazing = [], [], [], None
        for j in range(self.periods):
            y, Mj, run, g = self.one_period(y)
            y = np.array(y, dtype=float)
            offset = j * self.period
            M = Mj @ M
            switches += [(t + offset, b, a, s) for t, b, a, s, _ in run.switches]
            segments += [
                (t0 + offset, t1 + offset, m) for t0, t1, m in zip(run.starts, run.ends, run.modes)
            ]
            if grazing is None and g is not None:
                grazing = {**g, "t": g["t"] + offset}
            runs.append(run)
        return MapImage(start, y, M, switches, segments, grazing, self, runs)

    def _grazing(self, switches):
        """The first reversal reached with a vanishing rate (`GRAZING_RATIO`), or None."""
        for t, before, _, surface, state in switches:
            if surface != "relative_velocity":
                continue
            ratio = crossing_ratio(self.sw, t, state, before, surface)
            if ratio < GRAZING_RATIO:
                return {"t": float(t), "surface": surface, "ratio": float(ratio)}
        return None

    # ------------------------------------------------------------ what the orbit is near

    def _states(self, run, index, t):
        """``(X1, X1', X2, X2')`` at the times ``t`` of segment ``index`` of one period's run."""
        return run.segments(t, np.full(np.size(t), index))

    def _pieces(self, runs):
        """The segments of the orbit, joined where a mode goes on across a period boundary.

        Each piece is ``{"mode", "parts", "start", "end"}``: ``parts`` a list of
        ``(run, index, t0, t1, offset)`` (segment ``index`` of one period's ``run``,
        from ``t0`` to ``t1`` of that period, ``offset`` from phase 0 of the orbit),
        ``start`` and ``end`` whether the piece begins and ends at a switch. The last
        piece wraps around to the first where the orbit's mode goes on through phase 0.
        """
        pieces = []
        for j, run in enumerate(runs):
            offset = j * self.period
            n = len(run.modes)
            for i, (t0, t1, m) in enumerate(zip(run.starts, run.ends, run.modes)):
                part = (run, i, t0, t1, offset)
                if pieces and i == 0 and pieces[-1]["mode"] == m and not pieces[-1]["end"]:
                    pieces[-1]["parts"].append(part)
                    pieces[-1]["end"] = i < n - 1
                else:
                    pieces.append({"mode": m, "parts": [part], "start": i > 0, "end": i < n - 1})
        first, last = pieces[0], pieces[-1]
        if len(pieces) > 1 and last["mode"] == first["mode"] and not last["end"]:
            wrap = self.periods * self.period
            last["parts"] += [(r, i, a, b, o + wrap) for r, i, a, b, o in first["parts"]]
            last["end"] = first["end"]
            pieces = pieces[1:]
        return pieces

    def margins(self, runs: list, kinds: Sequence[str] = MARGIN_KINDS) -> list[Margin]:
        """The margins of the given kinds of the orbit made of ``runs`` (module docstring)."""
        out = []
        for j, run in enumerate(runs):
            offset = j * self.period
            for t, before, after, surface, state in run.switches:
                if surface in _TANGENTIAL and "crossing" in kinds:
                    ratio = crossing_ratio(self.sw, t, state, before, surface)
                    out.append(Margin("crossing", surface, before, t + offset, ratio))
                if "decision" in kinds and (
                    surface == "relative_velocity"
                    or (surface == "penetration" and after != Mode.FLIGHT)
                ):
                    out.append(self._decision(t, state, before, after, surface, offset))
        if "approach" not in kinds:
            return out
        for piece in self._pieces(runs):
            if piece["mode"] in (Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK):
                margin = self._approach(piece)
                if margin is not None:
                    out.append(margin)
        return out

    def _decision(self, t, state, before, after, surface, offset):
        """How far Filippov's choice at a switch onto ``Vr = 0`` is from the other outcome."""
        h = self.sw.surfaces(t, *state)
        scales = self.sw.scales(t, *state)
        sf, sb = h[_SF], h[_SB]
        if surface == "penetration" and abs(h[_VR]) > 0:
            # touchdown away from Vr = 0: the sign of Vr decides
            value = abs(h[_VR]) / scales[_VR]
        elif after == Mode.STICK:
            value = min(sf, sb) / scales[_SF]
        elif sf + sb > 0:  # a cone that could hold the mass: how far outside it
            value = -(sf if after == Mode.SLIP_FORWARD else sb) / scales[_SF]
        else:  # an empty cone: the side of a_free decides
            value = abs(0.5 * (sb - sf)) / scales[_SF]
        return Margin("decision", surface, before, t + offset, float(value))

    def _distance(self, mode, states, t):
        """Distance of a segment in ``mode`` to the surface that would end it, and that surface."""
        sw = self.sw
        h = np.asarray(sw.surfaces.array(t, *states), dtype=float)
        scale = np.asarray(sw.scales.array(t, *states), dtype=float)
        if mode == Mode.SLIP_BACK:
            return -h[_VR] / scale[_VR], np.full(t.size, _VR)
        if mode == Mode.SLIP_FORWARD:
            return h[_VR] / scale[_VR], np.full(t.size, _VR)
        sf, sb = h[_SF] / scale[_SF], h[_SB] / scale[_SB]
        return np.minimum(sf, sb), np.where(sf <= sb, _SF, _SB)

    def _approach(self, piece):
        """The smallest interior minimum of a piece's distance to the surface that would end it.

        None where the distance has no interior minimum below 1 (its saturation: a
        velocity against the belt's is as far from ``Vr = 0`` as the scale says).
        """
        from scipy import optimize

        mode, parts = piece["mode"], piece["parts"]
        times, values, where = [], [], []
        for run, index, t0, t1, offset in parts:
            n = max(8, int((t1 - t0) * _SAMPLES_PER_S))
            t = np.linspace(t0, t1, n + 1)
            d, surface = self._distance(mode, self._states(run, index, t), t)
            times.append(t + offset)
            values.append(d)
            where.append(surface)
        t, d, surface = np.concatenate(times), np.concatenate(values), np.concatenate(where)
        bounds = np.array([offset + t1 for _, _, _, t1, offset in parts])

        def at(s, rate_of=None):
            """The distance at ``s``, or the rate of the surface ``rate_of`` there."""
            k = min(int(np.searchsorted(bounds, s)), len(parts) - 1)
            run, index, _, _, offset = parts[k]
            local = s - offset
            state = self._states(run, index, np.array([local]))[:, 0]
            if rate_of is None:
                h, scale = self.sw.surfaces(local, *state), self.sw.scales(local, *state)
                if mode == Mode.STICK:
                    return min(h[_SF] / scale[_SF], h[_SB] / scale[_SB])
                return (h[_VR] if mode == Mode.SLIP_FORWARD else -h[_VR]) / scale[_VR]
            return float(self.sw.rates(local, *state, float(mode))[rate_of])

        # an end at a switch is on the surface by definition: only interior minima count
        candidate = np.ones(d.size, dtype=bool)
        candidate[0], candidate[-1] = not piece["start"], not piece["end"]
        candidate[1:] &= d[1:] <= d[:-1]
        candidate[:-1] &= d[:-1] <= d[1:]
        best = None
        for k in np.flatnonzero(candidate):
            value, tk = float(d[k]), float(t[k])
            if value < _REFINE_BELOW and 0 < k < d.size - 1:
                # the closest approach is where the surface's rate along the mode vanishes
                # (the scale varies slowly: the two minima agree to second order in the
                # distance, which vanishes at grazing)
                a, b, index = t[k - 1], t[k + 1], int(surface[k])
                ra, rb = at(a, index), at(b, index)
                if ra * rb < 0:
                    tk = optimize.brentq(at, a, b, args=(index,), xtol=1e-14, rtol=1e-15)
                    value = min(value, at(tk))
            if value < 1.0 and (best is None or value < best.value):
                name = hybrid.SURFACES[int(surface[k])]
                best = Margin("approach", name, mode, tk, value)
        return best

    def velocity_range(self, runs: list) -> tuple[float, float]:
        """The smallest and largest ``X1'`` over the runs (`orbit_range`)."""
        return orbit_range(runs, 1)


def orbit_range(runs: list, component: int = 1) -> tuple[float, float]:
    """The smallest and largest of one state component over the runs of an orbit.

    ``runs`` are periods as `PeriodMap` reads them (``starts``, ``ends`` and
    ``segments(t, index) -> (4, n)``: an `EventPeriod` or a tangential run);
    ``component`` 0 is ``X1``, 1 ``X1'``. Each segment is sampled (`_SAMPLES_PER_S`)
    and an interior extreme is refined by a bounded search to 1e-12 s.
    """
    from scipy import optimize

    def value(run, index, s):
        return float(run.segments(np.array([s]), np.full(1, index))[component][0])

    lo, hi = np.inf, -np.inf
    for run in runs:
        for index, (t0, t1) in enumerate(zip(run.starts, run.ends)):
            n = max(8, int((t1 - t0) * _SAMPLES_PER_S))
            t = np.linspace(t0, t1, n + 1)
            v = run.segments(t, np.full(t.size, index))[component]
            for sign in (1.0, -1.0):
                k = int(np.argmax(sign * v))
                extreme = float(v[k])
                if 0 < k < v.size - 1:
                    res = optimize.minimize_scalar(
                        lambda s, run=run, index=index, sign=sign: -sign * value(run, index, s),
                        bounds=(t[k - 1], t[k + 1]),
                        method="bounded",
                        options={"xatol": 1e-12},
                    )
                    extreme = sign * max(sign * extreme, -float(res.fun))
                lo, hi = (min(lo, extreme), hi) if sign < 0 else (lo, max(hi, extreme))
    return float(lo), float(hi)


class TangentialMap(PeriodMap):
    """``k`` periods of the tangential period map of Eq. (4) on its periodic normal motion.

    The closed-form path (module docstring): the shooting state is ``(X1, X1')`` at
    phase 0, the normal motion the cached periodic orbit (`normal_orbit`). It needs the
    facts `CLOSED_FORM_FACTS` of the model's laws (``generated.capabilities``) and
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

        The field of the mode ``slip_back`` (`generated.hybrid.vector_field`; without
        its contact force where ``X2 < 0``, as in flight) is integrated over one period
        with no switch watched (the compiled DOP853 of `beltmdsm.integrate._dop853`),
        its Jacobian by the step propagators of `beltmdsm.periodic.variational`, from
        the unforced equilibrium (Eq. 9). The Jacobian is kept while the residual at
        least halves (a chord method: the field is linear in the tangential state under
        Coulomb friction and nearly so under Stribeck's, so one Jacobian serves most
        iterations). It is the counterpart of the closed-form sliding orbit of
        `TangentialMap` and the same where the mass slides back in contact throughout;
        where the iterations do not settle in `_SLIDING_ITER`, the last iterate is the
        guess (kept).
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


def _periods(periods):
    if int(periods) != periods or int(periods) < 1:
        raise ValueError(f"periods must be an integer >= 1; got {periods!r}")
    return int(periods)


#: The facts of the laws (``generated.capabilities``) that the closed-form path needs,
#: those of the superposition it runs on: the slip-mode friction free of the
#: tangential state (the tangential motion is linear between switches) and the normal
#: equation free of it (the cached normal orbit, the block-triangular monodromy).
CLOSED_FORM_FACTS = SUPERPOSITION_FACTS
#: The period maps by engine name.
ENGINES: dict[str, type[PeriodMap]] = {"closed_form": TangentialMap, "general": GeneralMap}


def engine_of(model: Model) -> str:
    """The engine of the model's laws: ``"closed_form"`` where they have every fact of
    `CLOSED_FORM_FACTS`, else ``"general"``."""
    return "closed_form" if all(model.fact(f)[0] for f in CLOSED_FORM_FACTS) else "general"


def period_map(
    model: Model,
    periods: int = 1,
    backend: Backend | None = None,
    engine: Engine | None = None,
    *,
    check: bool = True,
) -> PeriodMap:
    """The ``k``-fold period map of the model.

    Parameters
    ----------
    model : Model
    periods : int
    backend : {"python", "numba", None}
    engine : {"closed_form", "general", None}
        None: the engine the model's laws allow (`engine_of`); a name asks for that
        engine (the general one applies to every law, and serves as a cross-check of
        the closed-form one).
    check : bool
        Refuse a start beyond floating point (`beltmdsm.settings.check_finite`, 0.3 ms);
        `MapFamily` checks its model once instead of at every value (an overflow there
        still ends its runs, with `beltmdsm.errors.StepTooSmall`).

    Raises
    ------
    ValueError
        For an unknown engine; `beltmdsm.errors.Refused` for parameters that put the
        start beyond floating point (`beltmdsm.settings.check_finite`).
    beltmdsm.model.Unsupported
        For ``engine="closed_form"`` where the laws lack a fact it needs.
    """
    if engine is not None and engine not in ENGINES:
        raise ValueError(f"engine must be one of {', '.join(map(repr, ENGINES))}; got {engine!r}")
    if check:
        check_finite(model)
    return ENGINES[engine or engine_of(model)](model, periods, backend)


class MapFamily:
    """The ``k``-fold period maps of one parameter's values, the others fixed.

    Parameters
    ----------
    model : Model
        The other parameters and the options.
    param : str
        The model parameter that varies.
    periods : int
    backend : {"python", "numba", None}

    ``family(value)`` is the `period_map` at ``param = value`` (the last few are
    kept); ``family.derivative(x, value)`` is ``dP/d param`` at ``x`` by central
    differences (relative step `DERIVATIVE_STEP`: a truncation error of about its
    square and a rounding error of about ``1e-12 / step`` relative, 1e-6, which slows
    Newton's method on a bordered system by nothing measurable). Both sides must keep
    the switch structure of ``x``'s image: close to a tangency the step shrinks by
    tens until they do.
    """

    DERIVATIVE_STEP = 1e-6
    _SMALLEST_STEP = 1e-11
    _KEPT = 8

    def __init__(
        self, model: Model, param: str, periods: int = 1, backend: Backend | None = None
    ) -> None:
        if param not in model.params:
            raise ValueError(f"param must be a model parameter; got {param!r}")
        check_finite(model)
        self.model, self.param = model, param
        self.periods, self.backend = int(periods), backend
        self._maps: dict = {}

    def __call__(self, value: float) -> PeriodMap:
        """The map at ``param = value`` (raises NoPeriodicResponse outside its domain)."""
        value = float(value)
        if value not in self._maps:
            if len(self._maps) >= self._KEPT:
                self._maps.pop(next(iter(self._maps)))
            try:
                model = self.model.replace(**{self.param: value})
            except ValueError as err:  # a value outside the parameter's domain
                raise NoPeriodicResponse(f"{self.param} = {value:g}: {err}") from None
            self._maps[value] = period_map(model, self.periods, self.backend, check=False)
        return self._maps[value]

    def any_map(self, value: float) -> PeriodMap:
        """The map bound last, or the map at ``value`` where none is kept: for what
        does not depend on ``param`` (it saves a binding)."""
        return next(reversed(self._maps.values())) if self._maps else self(value)

    def derivative(
        self, x: ArrayLike, value: float, structure: tuple | None = None
    ) -> NDArray[np.float64]:
        """``dP/d param`` at the shooting state ``x`` by central differences.

        ``structure``: the `signature` of the image at ``x`` (computed if not given),
        which both sides must keep.
        """
        x = np.asarray(x, dtype=float)
        if structure is None:
            structure = self(value)(x).signature
        h = self.DERIVATIVE_STEP * max(1.0, abs(float(value)))
        while True:
            up = self(value + h)(x)
            try:
                down, width = self(value - h)(x), 2 * h
            except NoPeriodicResponse:  # at the edge of the domain: one-sided
                down, width = self(value)(x), h
            if (up.signature == structure and down.signature == structure) or (
                h < self._SMALLEST_STEP * max(1.0, abs(float(value)))
            ):
                return (up.state - down.state) / width
            h *= 0.1


@dataclass
class FixedPoint:
    """A fixed point of a period map: the state at phase 0 of a response of ``k`` periods.

    Attributes
    ----------
    state : ndarray (n,)
    image : MapImage
        The map at ``state`` (its Jacobian is the monodromy of the shooting state).
    residual : float
        ``max |P(x) - x|``.
    iterations : int
    """

    state: NDArray[np.float64]
    image: MapImage
    residual: float
    iterations: int


def fixed_point(pmap: PeriodMap, guess: ArrayLike, max_iter: int = 30) -> FixedPoint:
    """Newton's method on ``P(x) - x`` with damped steps, ``dP/dx - I`` its Jacobian.

    Parameters
    ----------
    pmap : PeriodMap
    guess : array_like (n,)
    max_iter : int

    Returns
    -------
    FixedPoint

    Raises
    ------
    NoPeriodicResponse
        If the residual stops halving (over a few iterations), no damped step reduces
        it, or ``max_iter`` iterations leave it above `NEWTON_TOL` (relative to the
        state's scale).
    """
    what = "" if pmap.periods == 1 else f" of {pmap.periods} periods"
    x = np.array(guess, dtype=float)
    image = pmap(x)
    r = image.state - x
    history = []
    for iteration in range(1, max_iter + 1):
        residual = float(np.max(np.abs(r)))
        if residual <= NEWTON_TOL * (1.0 + np.max(np.abs(x))):
            return FixedPoint(x, image, residual, iteration)
        history.append(residual)
        if len(history) > _STAGNATION and history[-1] > 0.5 * history[-1 - _STAGNATION]:
            raise NoPeriodicResponse(
                f"no periodic response{what} found: Newton's method stagnates at a "
                f"residual {residual:.2e} (not halved in {_STAGNATION} iterations)"
            )
        A = image.jacobian - np.eye(x.size)
        try:
            step = -np.linalg.solve(A, r)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(A, r, rcond=None)[0]
        lam = 1.0
        for _ in range(_LINE_SEARCH):
            x_new = x + lam * step
            image_new = pmap(x_new)
            r_new = image_new.state - x_new
            if np.max(np.abs(r_new)) < residual:
                break
            lam *= 0.5
        else:
            raise NoPeriodicResponse(
                f"no periodic response{what} found: Newton's method stalled at a "
                f"residual {residual:.2e} (no step of {_LINE_SEARCH} halvings reduces it)"
            )
        x, image, r = x_new, image_new, r_new
    raise NoPeriodicResponse(
        f"no periodic response{what} found: Newton's method left a residual "
        f"{float(np.max(np.abs(r))):.2e} after {max_iter} iterations"
    )
