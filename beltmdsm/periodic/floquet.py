"""Exact stability of the forced periodic response: Floquet multipliers with saltation matrices.

The MDSM and the paper's analysis (Sects. 4.2-4.3) linearise about a slow equilibrium
that stands for the response of period ``T = 2 pi / Omega``; the exact counterpart is
the Floquet stability of that periodic response (docs/modelling.md#what-unstable-means).
This module computes it, on the period map of `beltmdsm.periodic.periodmap`, by one of
two engines that the facts of the model's laws choose (``beltmdsm.generated.capabilities``,
`beltmdsm.periodic.periodmap.engine_of`), never by assumption:

* ``closed_form`` (`beltmdsm.periodic.periodmap.TangentialMap`), where the slip-mode
  friction is free of the tangential state and the normal equation too (Coulomb
  friction): the tangential map on the cached normal orbit, closed-form state
  transitions and saltation matrices, the normal block's multipliers apart;
* ``general`` (`beltmdsm.periodic.periodmap.GeneralMap`), every law (Stribeck
  friction): the full state shot with the event-driven integrator, the monodromy by
  the variational equations with the generated Jacobians of the modes and the
  saltation matrices (`beltmdsm.periodic.variational`; Leine and Nijmeijer 2004).

The results say which (``engine``); where both apply they agree to 1e-9.

* **Without excitation** (`beltmdsm.model.is_autonomous`) there is no period to take
  the phase from: `periodic_response` and `floquet` compute the self-excited cycle
  instead (`beltmdsm.cycles.cycle`: the period found by shooting with a phase
  condition), with ``autonomous`` set, its multipliers without the trivial one (along
  the flow, reported as ``trivial_multiplier``) and a multiplier 0 for a stick phase.

* **Periodic response.** `periodic_response` finds the state at phase 0 that the
  period map returns to, by Newton's method with the map's Jacobian (damped steps,
  `beltmdsm.periodic.periodmap.fixed_point`). The first guess is the orbit that
  slides backwards throughout, which is exact where the friction never reverses; a
  continuation passes the previous orbit instead.
* **Phase-locked responses** (``periods = k > 1``): the response of ``k T``, a fixed
  point of the ``k``-fold map, whose multipliers are those of the ``k``-fold map
  (the eigenvalues of the product of the ``k`` one-period Jacobians, and on the
  closed-form path the normal block's to the power ``k``). Without a guess it is
  seeded from the attractor of the period map iterated from rest
  (`beltmdsm.periodic.locked.map_stroboscope`), where that attractor locks at ``k``
  periods (docs/modelling.md#bifurcations).
* **Grazing.** A switch reached with a vanishing rate
  (`beltmdsm.periodic.periodmap.GRAZING_RATIO`) is reported as grazing, and no
  multiplier is returned for it.

`floquet` reports the multipliers, the largest modulus, the growth rate per unit time
``log|mu| / (k T)``, the frequency of the critical pair ``|arg mu| / (k T)`` (to
compare with omega1; it is defined modulo ``2 pi / (k T)``) and the verdict. The
ranges of a parameter where the response is unstable are `beltmdsm.continuation.band`'s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from ..arguments import count, state
from ..errors import Refused
from ..integrate.normal import normal_motion
from ..integrate.superposition import Superposition, friction_direction
from ..integrate.switching import Mode
from ..model import Backend, Model, as_model, excitation_period, initial_state, is_autonomous
from .locked import LOCK_LIMIT, NotLocked, map_stroboscope, minimal_periods
from .periodmap import (
    ENGINES,
    GRAZING_RATIO,
    NEWTON_TOL,
    RTOL,
    Engine,
    FixedPoint,
    GeneralMap,
    NoPeriodicResponse,
    NormalOrbit,
    OnePeriodMap,
    PeriodMap,
    fixed_point,
    normal_orbit,
    period_map,
)

__all__ = [
    "excitation_period",
    "NoPeriodicResponse",
    "NormalOrbit",
    "normal_orbit",
    "PeriodicResponse",
    "periodic_response",
    "response_of_cycle",
    "response_from",
    "Floquet",
    "floquet",
    "periodic_start",
    "largest_sliding_velocity",
    "PERTURBATION",
    "GRAZING_RATIO",
    "NEWTON_TOL",
    "FORWARD_PERIODS",
    "SEED_PERIODS",
    "MAX_SEED_PERIODS",
    "ShorterPeriod",
]

#: Periods of forward iteration of the tangential period map where Newton's method
#: fails (a stable response next to a grazing point).
FORWARD_PERIODS = 200
#: Forward iteration gives up when its step has not shrunk below this fraction over
#: this many periods: converging to a response with |mu| <= 0.995 it shrinks by 0.88
#: or more, while next to no stable response (another attractor, a drift) it does not.
_FORWARD_WINDOW = 25
_FORWARD_PROGRESS = 0.9
#: The seed of a response of ``k > 1`` periods: the period map iterated from rest for
#: this many periods to settle, then as many again sampled (the last 40% of a run of
#: 1000 s at the base set; the lock is found there at every point of
#: tests/beltmdsm/periodic/test_locked.py, as the run from rest of Eq. (4) finds it).
SEED_PERIODS = (400, 256)
#: The longest response looked for without a guess: a lock at ``k`` periods is seen in
#: more than ``2 k`` samples (`beltmdsm.periodic.locked.stroboscope`), of which the
#: seed has ``SEED_PERIODS[1]``.
MAX_SEED_PERIODS = (SEED_PERIODS[1] - 1) // 2


@dataclass
class PeriodicResponse:
    """The periodic response of period ``period`` and its monodromy.

    Attributes
    ----------
    model : Model
    period : float
        ``k T`` [s].
    state0 : ndarray (4,)
        ``(X1, X1', X2, X2')`` at phase 0 (``t = 0``, a multiple of the period).
    switches : list of (t, before, after, surface)
        The switches over one period, with the modes (`beltmdsm.integrate.switching.Mode`).
    segments : list of (t0, t1, mode)
    monodromy_tangential, monodromy_normal : ndarray (2, 2)
        The diagonal blocks of the monodromy matrix.
    monodromy : ndarray (4, 4)
        The whole monodromy matrix. On the closed-form path its coupling block
        ``[:2, 2:]`` by central finite differences of the period map (relative
        accuracy about 1e-6), the diagonal blocks as above; on the general path the
        variational equations' (`beltmdsm.periodic.variational`).
    grazing : dict or None
        ``{"t", "surface", "ratio"}`` of a switch reached with a vanishing rate.
    residual : float
        ``|P(x) - x|`` at the returned state.
    iterations : int
    periods : int
        ``k``: the response repeats after ``k`` excitation periods; the monodromy is
        that of the ``k``-fold map.
    engine : {"closed_form", "general"}
        The period map that found it (`beltmdsm.periodic.periodmap.ENGINES`, chosen by
        the facts of the model's laws, `beltmdsm.periodic.periodmap.engine_of`).
    autonomous : bool
        A self-excited cycle of the model without excitation (`response_of_cycle`):
        ``period`` was found, ``state0`` lies on its section, ``cycle`` is the
        `beltmdsm.cycles.cycle.Cycle`.
    """

    model: Model
    period: float
    state0: np.ndarray
    switches: list
    segments: list
    monodromy_tangential: np.ndarray
    monodromy_normal: np.ndarray
    grazing: dict | None
    residual: float
    iterations: int
    _engine: object = field(default=None, repr=False)
    periods: int = 1
    engine: str = "closed_form"
    _monodromy: np.ndarray | None = field(default=None, repr=False)
    autonomous: bool = False
    cycle: Any = field(default=None, repr=False)
    _ranges: tuple | None = field(default=None, repr=False)

    @property
    def monodromy(self) -> np.ndarray:
        """The 4 x 4 monodromy matrix (see the class docstring)."""
        if self._monodromy is None:
            M = np.zeros((4, 4))
            M[:2, :2] = self.monodromy_tangential
            M[2:, 2:] = self.monodromy_normal
            M[:2, 2:] = _coupling_block(self)
            self._monodromy = M
        return self._monodromy.copy()

    def ranges(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """``(x1_range, velocity_range)``: ``(min, max)`` of ``X1`` and ``X1'`` over the orbit.

        A cycle carries them; a forced response's are read from one application of its
        period map at ``state0`` (computed once).
        """
        if self._ranges is None:
            if self.autonomous:
                self._ranges = (self.cycle.x1_range, self.cycle.velocity_range)
            else:
                pmap = period_map(self.model, self.periods, engine=self.engine)
                image = pmap(self.shooting_state)
                self._ranges = (image.x1_range(), image.velocity_range())
        return self._ranges

    @property
    def shooting_state(self) -> np.ndarray:
        """The state at phase 0 that the engine's period map shoots in: ``(X1, X1')``
        on the closed-form path, all four on the general one."""
        return ENGINES[self.engine].shooting(self.state0)

    def __repr__(self) -> str:
        state = ", ".join(f"{v:.6g}" for v in self.state0)
        grazing = "" if self.grazing is None else f", GRAZING at t = {self.grazing['t']:.6g} s"
        return (
            f"PeriodicResponse({self.model!r}, period={self.period:.6g} s, "
            f"periods={self.periods}, state0=[{state}], {len(self.switches)} switches, "
            f"{self.engine} path, residual {self.residual:.1e} after {self.iterations} "
            f"Newton iterations{grazing})"
        )


def _coupling_block(resp):
    """``d x_t(T) / d x_n(0)`` by central differences of the period map (4 normal runs)."""
    x_t, x_n = resp.state0[:2], resp.state0[2:]
    out = np.zeros((2, 2))
    for j in range(2):
        h = 1e-6 * max(1.0, abs(x_n[j]))
        ends = []
        for sign in (1, -1):
            xn = x_n.copy()
            xn[j] += sign * h
            normal = normal_motion(resp.model, resp.period, RTOL, RTOL, xn)
            engine = Superposition(resp.model, normal)
            run = engine.run(0.0, float(x_t[0]), float(x_t[1]), resp.period)
            ends.append(run.final[:2])
        out[:, j] = (ends[0] - ends[1]) / (2 * h)
    return out


def response_of_cycle(c: Any) -> PeriodicResponse:
    """The `PeriodicResponse` of a self-excited cycle (`beltmdsm.cycles.cycle.Cycle`).

    Its ``state0`` is the cycle's state on the section, ``period`` the one found, the
    monodromy the whole one of the general path (``engine="general"``).
    """
    M = np.array(c.monodromy, dtype=float)
    return PeriodicResponse(
        c.model,
        c.period,
        np.array(c.state, dtype=float),
        list(c.switches),
        list(c.segments),
        M[:2, :2],
        M[2:, 2:],
        c.grazing,
        c.residual,
        c.iterations,
        None,
        1,
        "general",
        M,
        True,
        c,
        (c.x1_range, c.velocity_range),
    )


def _cycle_response(model, guess, max_iter, backend, periods, engine):
    """`periodic_response` without excitation: the self-excited cycle."""
    from ..cycles.cycle import Cycle, cycle

    if periods != 1:
        raise ValueError(
            f"periods must be 1 without excitation (a self-excited cycle has no "
            f"excitation period to count); got {periods!r}"
        )
    if engine not in (None, "general"):
        raise ValueError(
            f"engine={engine!r}: a self-excited cycle is computed on the general path only"
        )
    if isinstance(guess, PeriodicResponse):
        guess = guess.cycle if guess.autonomous else None
    if isinstance(guess, Cycle):
        return response_of_cycle(
            cycle(model, guess.state, guess.period, max_iter=max_iter, backend=backend)
        )
    if guess is not None:
        raise ValueError(
            "a guess of a self-excited cycle needs its period: pass a PeriodicResponse "
            "or a beltmdsm.cycles.cycle.Cycle, or call beltmdsm.cycles.cycle.cycle"
        )
    return response_of_cycle(cycle(model, max_iter=max(max_iter, 30), backend=backend))


def response_from(pmap: PeriodMap, point: FixedPoint) -> PeriodicResponse:
    """The `PeriodicResponse` of a fixed point of a ``k``-fold map (either engine)."""
    k, image = pmap.periods, point.image
    if isinstance(pmap, GeneralMap):
        M = image.jacobian
        blocks, full, engine = (M[:2, :2], M[2:, 2:]), M, pmap
    else:
        blocks = (image.jacobian, np.linalg.matrix_power(pmap.one.orbit.monodromy, k))
        full, engine = None, pmap.one
    return PeriodicResponse(
        pmap.model,
        k * pmap.period,
        pmap.full_state(point.state),
        list(image.switches),
        list(image.segments),
        *blocks,
        image.grazing,
        point.residual,
        point.iterations,
        engine,
        k,
        pmap.engine,
        full,
    )


def periodic_response(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    max_iter: int = 20,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    periods: int = 1,
    engine: Engine | None = None,
    **kw: Any,
) -> PeriodicResponse:
    """The periodic response of Eq. (4) by shooting (module docstring).

    Newton's method from ``guess`` (or the backward-sliding orbit); where it fails,
    the period map is iterated forward from the sliding orbit for up to ``forward``
    periods (it converges to a stable periodic response, where Newton's method may
    not, next to a grazing point) and Newton's method polishes the result. The period
    map is the closed-form one where the model's laws allow it, else the general one
    (`beltmdsm.periodic.periodmap.period_map`); the result's ``engine`` says which.

    Parameters
    ----------
    model : Model or dict, optional
        The model (default: the base set); ``**kw``: parameters and options.
    guess : array_like (2,) or (4,), or PeriodicResponse, optional
        The state at phase 0 to start Newton's method from (a continuation's
        predictor, a neighbour on a branch): ``(X1, X1', X2, X2')`` or the tangential
        ``(X1, X1')`` (on the general path completed by the sliding orbit's normal
        state); default the backward-sliding orbit (``periods = 1``) or the attractor
        of the period map iterated from rest (``periods > 1``).
    max_iter : int
    forward : int
        Periods of forward iteration after Newton's method fails (0: none;
        ``periods = 1`` only).
    backend : {"python", "numba", None}
    periods : int
        ``k >= 1``: the response of ``k`` excitation periods (phase-locked for ``k >
        1``), by shooting on the ``k``-fold map.
    engine : {"closed_form", "general", None}
        The period map (`beltmdsm.periodic.periodmap.period_map`); None: the one the
        model's laws allow.

    Without excitation (`beltmdsm.model.is_autonomous`) the response is the self-excited
    cycle (`beltmdsm.cycles.cycle.cycle`, ``autonomous`` set): seeded from a run off
    unstable steady sliding, or from ``guess`` (a `PeriodicResponse` of a cycle or a
    `beltmdsm.cycles.cycle.Cycle`: a neighbour); ``forward`` does not apply.

    Returns
    -------
    PeriodicResponse
        With ``periods = k`` and ``period = k T``.

    Raises
    ------
    ValueError
        Naming the argument: bad parameters, a tension law that does not exist, an
        excitation without a period (zero or incommensurate frequencies), ``periods``
        or ``max_iter`` not an integer >= 1 (a bool is not one), ``forward`` not an
        integer >= 0, a guess that is not 2 or 4 finite real numbers, or an unknown
        engine; `beltmdsm.errors.Refused` for ``periods > MAX_SEED_PERIODS`` without
        a guess (the seed cannot tell such a lock).
    beltmdsm.model.Unsupported
        For ``engine="closed_form"`` where the model's laws lack a fact it needs.
    NoPeriodicResponse
        (a RuntimeError) If no periodic response is found; for ``periods > 1``
        without a guess, where the attractor of the period map does not lock at
        ``k`` periods (the message says what it does instead): `ShorterPeriod` where
        it locks at a divisor ``d`` of ``k`` (its orbit is ``k T``-periodic too, a
        response of ``d`` periods; ``floquet --periods 8 --Vb 5`` reports the 4T one).
    """
    model = as_model(model, **kw)
    periods = count("periods", periods, 1)
    max_iter = count("max_iter", max_iter, 1)
    forward = count("forward", forward, 0)
    if is_autonomous(model):
        return _cycle_response(model, guess, max_iter, backend, periods, engine)
    if isinstance(guess, PeriodicResponse):
        guess = guess.state0
    if guess is not None:
        guess = state("guess", guess, (2, 4), "the state at phase 0")
    elif periods > MAX_SEED_PERIODS:
        raise Refused(
            f"periods must be <= {MAX_SEED_PERIODS} without a guess: the seed samples "
            f"{SEED_PERIODS[1]} periods of the period map, and a lock at k periods needs "
            f"more than 2 k (SEED_PERIODS, beltmdsm/periodic/floquet.py); got {periods}",
            "periods",
        )
    excitation_period(model)
    pmap = period_map(model, periods, backend, engine)
    if guess is not None:
        guess = pmap.guess(guess)
    if pmap.periods > 1 and guess is not None:
        return response_from(pmap, fixed_point(pmap, guess, max_iter))
    if pmap.periods > 1:
        seed, locks = _locked_seed(pmap)
        if locks != pmap.periods:
            raise ShorterPeriod(pmap.periods, locks, "the period map iterated from rest locks at")
        point = fixed_point(pmap, seed, max_iter)
        shortest = minimal_periods(point.image, pmap.periods)
        if shortest != pmap.periods:
            raise ShorterPeriod(
                pmap.periods,
                shortest,
                "from the attractor of the period map iterated from rest, Newton's method "
                "finds a response of",
            )
        return response_from(pmap, point)
    start = pmap.sliding_guess() if guess is None else guess
    try:
        point = fixed_point(pmap, start, max_iter)
    except NoPeriodicResponse as newton_failed:
        if not forward:
            raise
        x, steps = pmap.sliding_guess(), []
        for k in range(int(forward)):
            xT = pmap.step(x)
            steps.append(float(np.max(np.abs(xT - x))))
            if steps[-1] <= 1e-7 * (1 + np.max(np.abs(x))):
                break
            if k >= _FORWARD_WINDOW and steps[-1] > _FORWARD_PROGRESS * steps[-1 - _FORWARD_WINDOW]:
                raise NoPeriodicResponse(
                    f"{newton_failed}; nor does the period map, iterated from the sliding "
                    f"orbit: its step does not shrink over {_FORWARD_WINDOW} periods "
                    f"({steps[-1 - _FORWARD_WINDOW]:.2e} to {steps[-1]:.2e})"
                ) from None
            x = xT
        else:
            raise NoPeriodicResponse(
                f"{newton_failed}; nor does the period map, iterated "
                f"{forward} periods from the sliding orbit, settle"
            ) from None
        point = fixed_point(pmap, x, max_iter)
    return response_from(pmap, point)


def _locked_seed(pmap):
    """The last sample of the attractor of the period map from rest, and the number of
    periods it locks at: ``k`` or a divisor of it (a ``k/d``-periodic orbit is
    ``k``-periodic too)."""
    k = pmap.periods
    strobe = map_stroboscope(
        pmap,
        pmap.shooting(initial_state(pmap.model)),
        *SEED_PERIODS,
        "the period map iterated from rest",
        max(k, LOCK_LIMIT),
    )
    locks = strobe.candidate
    if locks is None or k % locks:
        what = f"locks at {_periods(locks)}" if locks else NotLocked.of(strobe).text()
        raise NoPeriodicResponse(
            f"no response of {_periods(k)} found: the period map iterated from rest {what}"
        )
    return strobe.samples[-1], locks


class ShorterPeriod(NoPeriodicResponse):
    """No response of minimal period ``asked`` periods: the attractor is a response of
    ``periods``, a divisor of it (its orbit repeats after ``asked`` periods too, but is
    not a new response). ``periodic_response(..., periods=periods)`` computes it
    (``floquet --periods K`` reports it so)."""

    def __init__(self, asked: int, periods: int, how: str) -> None:
        super().__init__(
            f"no response of minimal period {_periods(asked)} found: {how} "
            f"{_periods(periods)}, whose orbit repeats after {asked} too "
            f"(periods={periods} computes it)"
        )
        self.asked, self.periods = asked, periods


def _periods(k: int) -> str:
    return "1 period" if k == 1 else f"{k} periods"


@dataclass
class Floquet:
    """Floquet multipliers of the periodic response and what they say.

    ``multipliers`` are those of the ``k``-fold map (``k = response.periods``): on the
    closed-form path the tangential pair, then the normal pair; on the general path
    the four eigenvalues of the whole monodromy, by decreasing modulus (no pair is
    singled out where nothing says the blocks decouple). NaN where the response
    grazes (``grazing`` is then set and ``stable`` is None). ``n_reversals`` and
    ``n_sticks`` count over the ``k`` periods. ``engine`` is the path taken
    (`PeriodicResponse`). For a self-excited cycle (``autonomous``) the multipliers are
    the three of its Poincare map, without the trivial one along the flow
    (``trivial_multiplier``, 1 to the accuracy of the orbit); a stick phase makes one 0.
    """

    multipliers: np.ndarray
    max_abs_multiplier: float
    growth_rate: float
    frequency: float
    stable: bool | None
    n_reversals: int
    n_sticks: int
    grazing: dict | None
    period: float
    response: PeriodicResponse = field(repr=False)
    autonomous: bool = False
    trivial_multiplier: complex | None = None

    @classmethod
    def of(cls, resp: PeriodicResponse) -> Floquet:
        """The multipliers of a periodic response and what they say."""
        if resp.autonomous:
            return cls._of_cycle(resp)
        n_rev = sum(
            1
            for _, b, a, s in resp.switches
            if s == "relative_velocity" and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD}
        )
        n_stick = sum(1 for _, _, a, _ in resp.switches if a == Mode.STICK)
        if resp.grazing is not None:
            nan = float("nan")
            return cls(
                np.full(4, complex(nan, nan)),
                nan,
                nan,
                nan,
                None,
                n_rev,
                n_stick,
                resp.grazing,
                resp.period,
                resp,
            )
        if resp.engine == "closed_form":
            mt = np.linalg.eigvals(resp.monodromy_tangential)
            mn = np.linalg.eigvals(resp.monodromy_normal)
            mu = np.concatenate([mt, mn])
        else:
            mu = np.linalg.eigvals(resp.monodromy).astype(complex)
            mu = mu[np.argsort(-np.abs(mu), kind="stable")]
        k = int(np.argmax(np.abs(mu)))
        biggest = float(abs(mu[k]))
        growth = math.log(biggest) / resp.period if biggest > 0 else -math.inf
        return cls(
            mu,
            biggest,
            growth,
            abs(float(np.angle(mu[k]))) / resp.period,
            bool(biggest < 1.0),
            n_rev,
            n_stick,
            None,
            resp.period,
            resp,
        )

    @classmethod
    def _of_cycle(cls, resp: PeriodicResponse) -> Floquet:
        """`Floquet` of a self-excited cycle: its multipliers as the cycle reports them."""
        c = resp.cycle
        mu = np.asarray(c.multipliers, dtype=complex)
        biggest = float(np.max(np.abs(mu)))
        if resp.grazing is not None or not math.isfinite(biggest):
            growth = frequency = math.nan
        else:
            k = int(np.argmax(np.abs(mu)))
            growth = math.log(biggest) / c.period if biggest > 0 else -math.inf
            frequency = abs(float(np.angle(mu[k]))) / c.period
        return cls(
            mu,
            biggest,
            growth,
            frequency,
            c.stable,
            c.n_reversals,
            c.n_sticks,
            c.grazing,
            c.period,
            resp,
            True,
            complex(c.trivial_multiplier),
        )

    @property
    def engine(self) -> str:
        """The path that computed the response: ``"closed_form"`` or ``"general"``."""
        return self.response.engine

    @property
    def verdict(self) -> Literal["stable", "unstable", "grazing"]:
        """``"stable"``, ``"unstable"`` or ``"grazing"`` (no multiplier at a grazing orbit)."""
        if self.stable is None:
            return "grazing"
        return "stable" if self.stable else "unstable"

    def __repr__(self) -> str:
        from .._display import block, laws

        resp = self.response
        head = (
            f"Floquet({resp.model!r}; {laws(resp.model)}: {self.verdict}, "
            f"period {self.period:.6g} s ({resp.periods} T), {self.engine} path)"
        )
        if self.stable is None:
            return block(head, [f"grazing: {self.grazing}"])
        mus = ", ".join(f"{z.real:.6g}{z.imag:+.6g}j" for z in self.multipliers)
        return block(
            head,
            [
                f"max |mu| = {self.max_abs_multiplier:.6g}, growth rate "
                f"{self.growth_rate:.6g} 1/s, critical pair at {self.frequency:.6g} rad/s",
                f"multipliers: {mus}",
                f"{self.n_reversals} reversals and {self.n_sticks} sticks per orbit",
            ],
        )

    def as_dict(self) -> dict:
        """The JSON-able summary (the keys of ``python -m beltmdsm floquet --json``).

        ``autonomous`` says whether it is a self-excited cycle; a cycle adds the keys of
        `beltmdsm.cycles.cycle.Cycle.as_dict` (``trivial_multiplier``, ``x1_range``,
        ``velocity_range``, ``stick_time``, ``stick_collapses``, ...).
        """
        if self.autonomous:
            return {
                **self.response.cycle.as_dict(),
                "growth_rate": self.growth_rate,
                "frequency": self.frequency,
                "periods": 1,
                "engine": self.engine,
            }
        return {
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "max_abs_multiplier": self.max_abs_multiplier,
            "growth_rate": self.growth_rate,
            "frequency": self.frequency,
            "stable": self.stable,
            "n_reversals": self.n_reversals,
            "n_sticks": self.n_sticks,
            "grazing": self.grazing,
            "period": self.period,
            "periods": self.response.periods,
            "state0": [float(v) for v in self.response.state0],
            "newton_iterations": self.response.iterations,
            "residual": self.response.residual,
            "engine": self.engine,
            "autonomous": False,
        }


def floquet(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    periods: int = 1,
    engine: Engine | None = None,
    **kw: Any,
) -> Floquet:
    """Floquet multipliers of the periodic response (module docstring).

    Takes the arguments of `periodic_response`; ``periods = k > 1``: of the response
    of ``k`` periods, the multipliers of the ``k``-fold map; ``engine``: the period
    map (None: the one the model's laws allow).

    Returns
    -------
    Floquet
    """
    model = as_model(model, **kw)
    return Floquet.of(
        periodic_response(
            model, guess=guess, forward=forward, backend=backend, periods=periods, engine=engine
        )
    )


#: ``periodic_start``: the run starts on the periodic response with X1 moved by this [m].
PERTURBATION = 1e-2


def periodic_start(
    model: Model, perturbation: float = PERTURBATION, backend: Backend | None = None
) -> np.ndarray:
    """A start state on the periodic response with ``X1`` moved by ``perturbation`` [m].

    An unstable response shows its instability from there, a stable one stays put
    (``simulate --start periodic``).

    Raises
    ------
    ValueError
        For a perturbation that is not a finite number.
    NoPeriodicResponse
        Where no periodic response is found.
    """
    if not (isinstance(perturbation, (int, float)) and math.isfinite(perturbation)):
        raise ValueError(f"perturbation must be a finite number; got {perturbation!r}")
    state = periodic_response(model, backend=backend).state0
    return state + np.array([perturbation, 0.0, 0.0, 0.0])


def largest_sliding_velocity(pmap: OnePeriodMap) -> float:
    """The largest ``X1'`` over one period of the backward-sliding orbit, in contact.

    ``pmap`` is a one-period map of the closed-form path (``TangentialMap.one``). Out of
    contact (flight, separation) there is no friction to reverse, so only the times in
    contact count. Where the slip-mode friction does not depend on the tangential state
    (the closed-form path's condition) it does not depend on ``Vb``: the sliding
    response grazes at the belt speed equal to it (`beltmdsm.continuation.band`).
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
