"""Every periodic response at one point: the ``T``-periodic one and the phase-locked ones.

A run of Eq. (4) from rest (the runs of Fig. 2b and Figs. 17-21), a run from the
perturbed periodic response or a sweep continued in a parameter ends on one attractor;
where it locks to the excitation at ``k`` periods (`beltmdsm.periodic.locked`), the
attractor is a fixed point of the ``k``-fold period map, which shooting computes
exactly (`beltmdsm.periodic.newton.fixed_point`), with the multipliers of the
``k``-fold map (`beltmdsm.periodic.floquet.Floquet`). The runs, ladders and shootings
that seed the search are `beltmdsm.starts`.

* `responses`: every periodic response found at one point (``python -m derive
  responses``): the periodic one of period ``T`` and every locked one up to a limit,
  each with its multipliers, the amplitude of ``X1'`` and where it was found; the
  attractors that do not lock, with the evidence (`beltmdsm.periodic.locked.NotLocked`).
  Without excitation (`beltmdsm.excitation.is_autonomous`): the self-excited cycles
  (`beltmdsm.periodic.cycle`), from the run off perturbed steady sliding (where that is
  stable, from the end of a stick) and from cycles continued up and down in ``Vb``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._calling import public
from ..arguments import count
from ..attractors.classification import classify
from ..errors import NoPeriodicResponse
from ..excitation import excitation_period, is_autonomous
from ..model import Backend, Model, as_model, is_real
from ..periodic.engines import period_map
from ..periodic.floquet import Floquet, floquet
from ..periodic.locked import LOCK_LIMIT, NotLocked, minimal_periods, same_phases
from ..periodic.response import response_from
from ..settings import check_finite
from ..starts.forced import (
    LADDER_SPAN,
    LADDER_STEP,
    RUN_T_END,
    check_limit,
    ladder_stroboscope,
    run_stroboscope,
    shoot,
)
from ..state_names import rate_column

__all__ = [
    "Response",
    "SeedFailure",
    "ResponseSet",
    "responses",
    "cycle_responses",
]


@dataclass
class Response:
    """One periodic response at a parameter point.

    Attributes
    ----------
    periods : int
        ``k``: the response repeats after ``k`` excitation periods (1: the periodic
        response of `beltmdsm.periodic.floquet`).
    floquet : Floquet
        Multipliers of the ``k``-fold map and what they say.
    velocity_range : tuple of float
        The smallest and largest ``X1'`` over the orbit [m/s].
    sources : list of str
        The attractors and shootings that found it.
    run_distance : float or None
        For a response found from an attractor: the largest distance between its
        last ``k`` stroboscopic samples and the orbit's phase-0 states (a check of the
        shooting against the simulation), relative to their scale.
    phases : list of ndarray
        The tangential state at phase 0 of each of the ``k`` periods (of a cycle: its
        state on the section).
    x1_range : tuple of float or None
        The smallest and largest ``X1`` over the orbit [m].

    See Also
    --------
    beltmdsm.multistability.responses.responses : what finds them.
    beltmdsm.periodic.floquet.Floquet : the multipliers.

    Examples
    --------
    At ``Vb = 5`` m/s the run from rest locks on a stable response of four excitation
    periods; its four phase-0 states are the fixed point of the 4-fold map:

    >>> from beltmdsm import responses
    >>> locked = responses(Model(Vb=5.0), ladder=0.0, t_end=300.0).responses[1]
    >>> locked.periods, locked.floquet.stable, len(locked.phases)
    (4, True, 4)
    >>> round(locked.floquet.max_abs_multiplier, 3), round(locked.amplitude, 1)
    (0.587, 12.1)
    >>> bool(locked.lyapunov < 0 and locked.run_distance < 1e-6)
    True
    >>> locked.same_orbit(4, locked.phases[2]), locked.same_orbit(1, locked.phases[0])
    (True, False)
    """

    periods: int
    floquet: Floquet
    velocity_range: tuple[float, float]
    sources: list[str]
    run_distance: float | None
    phases: list[NDArray[np.float64]] = field(repr=False)
    x1_range: tuple[float, float] | None = None

    @property
    def amplitude(self) -> float:
        """Half the peak-to-peak of ``X1'`` [m/s]."""
        return 0.5 * (self.velocity_range[1] - self.velocity_range[0])

    def __repr__(self) -> str:
        return (
            f"Response({self.periods}T: {self.floquet.verdict}, max |mu| = "
            f"{self.floquet.max_abs_multiplier:.5g}, amplitude of {rate_column()} "
            f"{self.amplitude:.4g} m/s, "
            f"found by {', '.join(self.sources)})"
        )

    def same_orbit(self, periods: int, x: ArrayLike) -> bool:
        """Whether the orbit of ``periods`` periods through ``x`` is this one."""
        return periods == self.periods and same_phases(self.phases, x)

    @property
    def lyapunov(self) -> float:
        """The largest Lyapunov exponent of the orbit [1/s]: its Floquet growth rate
        ``ln max |mu| / (k T)``; of a cycle the larger of that and 0 (along the flow)."""
        rate = self.floquet.growth_rate
        return max(0.0, rate) if self.floquet.autonomous else rate

    def as_dict(self) -> dict:
        """The keys of ``floquet --json``, and ``kind`` ("periodic"), ``lyapunov``,
        ``amplitude``, ``velocity_range``, ``sources``, ``run_distance``."""
        return {
            **self.floquet.as_dict(),
            "kind": "periodic",
            "lyapunov": self.lyapunov,
            "periods": self.periods,
            "amplitude": self.amplitude,
            "velocity_range": list(self.velocity_range),
            "x1_range": None if self.x1_range is None else list(self.x1_range),
            "sources": list(self.sources),
            "run_distance": self.run_distance,
        }


@dataclass(frozen=True)
class SeedFailure:
    """A seed whose shooting failed: where it came from, and why.

    Attributes
    ----------
    source : str
        the seed (``run from rest``, ``ladder up``)
    reason : str
        the failure's message

    See Also
    --------
    beltmdsm.multistability.responses.ResponseSet : lists them in ``failed``.

    Examples
    --------
    >>> SeedFailure("ladder up", "the ladder from Vb = 3 stops on the way").as_dict()
    {'source': 'ladder up', 'reason': 'the ladder from Vb = 3 stops on the way'}
    """

    source: str
    reason: str

    def as_dict(self) -> dict:
        """For JSON: ``source``, ``reason``."""
        return {"source": self.source, "reason": self.reason}


@dataclass
class ResponseSet:
    """The periodic responses found at one parameter point (`responses`).

    Its ``repr`` is one screen (a line per response, attractor not locked and failed
    seed); ``as_dict()`` is the JSON of ``responses --json``.

    Parameters
    ----------
    model : Model
        The point: parameters and options.
    limit : int
        The largest ``k`` looked for.
    responses : list of Response
        By ``k``, then by amplitude.
    unlocked : list of NotLocked
        The attractors that do not lock within the limit.
    failed : list of SeedFailure
        The seeds whose shooting failed, and why.

    See Also
    --------
    beltmdsm.multistability.responses.responses : what builds it.
    beltmdsm.multistability.responses.Response : one response: its multipliers, amplitude, sources.

    Examples
    --------
    Built by `responses`; here by hand, with one failed seed and nothing found:

    >>> from beltmdsm import Model
    >>> from beltmdsm.multistability.responses import ResponseSet, SeedFailure
    >>> found = ResponseSet(Model(Vb=5), 12, [], [], [SeedFailure("a ladder", "it stopped")])
    >>> found  # doctest: +NORMALIZE_WHITESPACE
    ResponseSet(Model(Vb=5.0); coulomb friction, hertz_damp, tension allowed; locks up to
    12 periods): 0 responses
      no response from a ladder: it stopped
    >>> found.as_dict()["failed"]
    [{'source': 'a ladder', 'reason': 'it stopped'}]
    """

    model: Model
    limit: int
    responses: list[Response]
    unlocked: list[NotLocked]
    failed: list[SeedFailure]

    def __repr__(self) -> str:
        from .._display import block, laws

        lines = [
            f"{r.periods}T: {r.floquet.verdict}, max |mu| = {r.floquet.max_abs_multiplier:.5g}, "
            f"amplitude of {rate_column(self.model)} {r.amplitude:.4g} m/s, found by "
            f"{', '.join(r.sources)}"
            for r in self.responses
        ]
        lines += [f"not locked: {u.text()}" for u in self.unlocked]
        lines += [f"no response from {f.source}: {f.reason}" for f in self.failed]
        return block(
            f"ResponseSet({self.model!r}; {laws(self.model)}; locks up to {self.limit} "
            f"periods): {len(self.responses)} responses",
            lines,
        )

    def as_dict(self) -> dict:
        """The JSON of ``responses --json``: ``params``, ``contact``, ``tension``,
        ``limit``, ``responses``, ``unlocked``, ``failed``."""
        return {
            **self.model.as_dict(),
            "limit": self.limit,
            "responses": [r.as_dict() for r in self.responses],
            "unlocked": [u.as_dict() for u in self.unlocked],
            "failed": [f.as_dict() for f in self.failed],
        }


def _run_distance(strobe, phases):
    """How far the last samples of a run are from an orbit's phase-0 states (best alignment)."""
    k = len(phases)
    last = strobe.samples[-k:]
    scale = 1.0 + float(np.max(np.abs(last)))
    return (
        min(
            max(float(np.max(np.abs(last[i] - phases[(i + shift) % k]))) for i in range(k))
            for shift in range(k)
        )
        / scale
    )


@public(models=True)
def responses(
    model: Model | Mapping[str, Any] | None = None,
    *,
    limit: int = LOCK_LIMIT,
    ladder: float = LADDER_SPAN,
    t_end: float = RUN_T_END,
    backend: Backend | None = None,
) -> ResponseSet:
    """Every periodic response found at one point: the ``T``-periodic one and the locked ones.

    The periodic response of period ``T`` by `beltmdsm.periodic.floquet.floquet`; then
    the attractors of the run from rest, of the run from the perturbed periodic
    response (where there is one), and of ladders in ``Vb`` continued up and down over
    ``ladder`` m/s (0: none) on the period map. Each attractor that locks at ``k <=
    limit`` periods is polished by Newton's method on the ``k``-fold map; the others
    are listed with the evidence (`beltmdsm.periodic.locked.NotLocked`). Without
    excitation, the self-excited cycles (`cycle_responses`; ``limit`` and ``t_end`` do
    not apply).

    Another registered model (``Model(model="belt_1dof")``) runs on the generic runtime,
    as ``responses --model NAME`` does: the stable attractors that runs from a grid of
    starts land on, each shot exactly (`beltmdsm.oscillator.responses.responses`, an
    ``Attractors``); it has no ladders (``ladder`` other than 0 or its default, or a
    ``backend``, is refused).

    Parameters
    ----------
    model : Model or dict, optional
        The model (default: the base set); ``**kw``: parameters and options.
    limit : int
        The largest ``k`` looked for (>= 1).
    ladder : float
        Span of the continued ladders [m/s], >= 0 (0: no ladder; the default
        `beltmdsm.starts.forced.LADDER_SPAN`).
    t_end : float
        Duration of the runs [s] (default `beltmdsm.starts.forced.RUN_T_END`).
    backend : {"python", "numba", None}
        The kernels: compiled by numba, plain Python, or numba where installed.
    **kw
        Model parameters and options (``Vb=5``, ``tension="clipped"``).

    Returns
    -------
    ResponseSet
        The responses by ``k``, then by amplitude, each with its Floquet multipliers
        and the seeds that found it; the attractors that do not lock; the seeds whose
        shooting failed.

    Raises
    ------
    ValueError
        For bad parameters, ``limit < 1``, ``ladder < 0`` or ``t_end <= 0``.
    beltmdsm.errors.Refused
        For a ``limit`` that the samples cannot decide
        (`beltmdsm.starts.forced.check_limit`).

    See Also
    --------
    beltmdsm.periodic.floquet.floquet : the ``T``-periodic response alone, or one of ``k`` periods.
    beltmdsm.multistability.coexistence.coexistence : the responses over a range, where
        they coexist.
    beltmdsm.attractors.classification.classify : what one run settles on, named.

    Examples
    --------
    At the base set and ``Vb = 5`` m/s the ``T``-periodic response is unstable and the
    run from rest locks at four excitation periods, on a stable response:

    >>> from beltmdsm import responses
    >>> found = responses(Model(Vb=5.0), ladder=0.0)
    >>> [(r.periods, r.floquet.stable) for r in found.responses]
    [(1, False), (4, True)]
    >>> found.responses[1].sources
    ['run from rest', 'run from the perturbed periodic response']
    """
    limit = count("limit", limit, 1)
    if not (is_real(ladder) and ladder >= 0 and is_real(t_end) and t_end > 0):
        raise ValueError(f"ladder must be >= 0 and t_end > 0; got {ladder!r}, {t_end!r}")
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        no_ladder = None if ladder in (0.0, LADDER_SPAN) else ladder
        return api.responses(model, limit, t_end, ladder=no_ladder, backend=backend)
    if is_autonomous(model):
        return cycle_responses(model, limit=limit, ladder=ladder, backend=backend)
    excitation_period(model)
    check_limit(limit, [model], t_end, ladder=ladder > 0)
    check_finite(model)  # once: the maps below are of this model
    found, unlocked, failed = [], [], []
    try:
        f = floquet(model, backend=backend)
        image = period_map(model, 1, backend, check=False)(f.response.shooting_state)
        found.append(
            Response(
                1,
                f,
                image.velocity_range(),
                ["shooting from the sliding orbit"],
                None,
                [f.response.shooting_state],
                image.x1_range(),
            )
        )
    except NoPeriodicResponse as err:
        failed.append(SeedFailure("shooting from the sliding orbit", str(err)))
    strobes = []
    for start in ("rest", "periodic"):
        if start == "periodic" and not found:
            continue
        strobes.append(
            run_stroboscope(model, start=start, t_end=t_end, limit=limit, backend=backend)
        )
    if ladder > 0:
        for direction in ("up", "down"):
            try:
                strobes.append(
                    ladder_stroboscope(model, direction, span=ladder, limit=limit, backend=backend)
                )
            except NoPeriodicResponse as err:
                failed.append(SeedFailure(f"ladder {direction}", str(err)))
    for strobe in strobes:
        point = None
        k = strobe.candidate
        if k is None:
            k, point, evidence = _classified(model, strobe, backend)
            if point is None:
                unlocked.append(evidence)
                continue
            strobe = replace(strobe, source=f"{strobe.source} (classified)")
        known = next((r for r in found if r.same_orbit(k, strobe.samples[-1])), None)
        if known is None and point is not None:
            pmap = period_map(model, k, backend, check=False)
            known = Response(
                k,
                Floquet.of(response_from(pmap, point)),
                point.image.velocity_range(),
                [],
                None,
                point.image.phases,
                point.image.x1_range(),
            )
            found.append(known)
        if known is None:
            try:
                pmap, point = shoot(model, k, strobe.samples[-1], backend)
            except NoPeriodicResponse as err:
                failed.append(SeedFailure(strobe.source, str(err)))
                unlocked.append(NotLocked.of(strobe))
                continue
            k = minimal_periods(point.image, k)
            if k != pmap.periods:
                pmap, point = shoot(model, k, point.state, backend)
            known = next((r for r in found if r.same_orbit(k, point.state)), None)
            if known is None:
                known = Response(
                    k,
                    Floquet.of(response_from(pmap, point)),
                    point.image.velocity_range(),
                    [],
                    None,
                    point.image.phases,
                    point.image.x1_range(),
                )
                found.append(known)
        known.sources.append(strobe.source)
        distance = _run_distance(strobe, known.phases)
        if known.run_distance is None or distance < known.run_distance:
            known.run_distance = distance
    found.sort(key=lambda r: (r.periods, r.amplitude))
    return ResponseSet(model, limit, found, unlocked, failed)


def _classified(model, strobe, backend):
    """A stroboscope that does not lock within the limit, classified from its last sample
    (`beltmdsm.attractors.classification.classify`: returns after any number of periods and the
    Lyapunov spectrum): ``(k, FixedPoint, None)`` of a long lock it finds, else
    ``(None, None, NotLocked)`` with the classification as the evidence."""
    evidence = NotLocked.of(strobe)
    pmap = period_map(model, 1, backend, check=False)
    start = pmap.full_state(pmap.guess(strobe.samples[-1]))
    a = classify(model, y0=start, backend=backend)
    if a.kind == "periodic":
        try:
            _, point = shoot(model, a.periods, a.state, backend)
            return a.periods, point, None
        except NoPeriodicResponse:
            pass  # classify's Newton converged from the same state: not expected
    return None, None, replace(evidence, classification=a.as_dict())


def _cycle_response(c, source, distance=None):
    """The `Response` of a self-excited cycle (`beltmdsm.periodic.cycle.Cycle`)."""
    from ..periodic.response import response_of_cycle

    return Response(
        1,
        Floquet.of(response_of_cycle(c)),
        c.velocity_range,
        [source],
        distance,
        [c.state],
        c.x1_range,
    )


def _continued_cycle(model, first, last, backend):
    """The cycle seeded at ``Vb = first`` and continued to ``Vb = last`` by Newton's method
    from each step's cycle: steps of `LADDER_STEP`, halved where Newton's method fails
    (down to 1/64 of it) and doubled again after each success."""
    from ..periodic.cycle import cycle

    c = cycle(model.replace(Vb=float(first)), backend=backend)
    v, step = float(first), LADDER_STEP * np.sign(last - first)
    while v != last:
        target = last if abs(last - v) <= abs(step) else v + step
        try:
            c = cycle(model.replace(Vb=target), c.state, c.period, backend=backend)
        except NoPeriodicResponse as err:
            if abs(step) < LADDER_STEP / 64:
                raise NoPeriodicResponse(f"at Vb = {target:g} from Vb = {v:g}: {err}") from None
            step *= 0.5
            continue
        v, step = target, np.sign(step) * min(2 * abs(step), LADDER_STEP)
    return c


def cycle_responses(
    model: Model,
    *,
    limit: int = LOCK_LIMIT,
    ladder: float = LADDER_SPAN,
    backend: Backend | None = None,
) -> ResponseSet:
    """The self-excited cycles of the model without excitation (`beltmdsm.periodic.cycle`).

    The cycle from the run off perturbed steady sliding (`beltmdsm.periodic.cycle.seed_cycle`:
    ``run_distance`` is how far the run's settled return lies from the cycle), and the
    cycles continued in ``Vb`` from ``ladder`` m/s below and above (seeded there, then
    Newton's method from each step's cycle, `_continued_cycle`): where steady sliding
    is stable at ``Vb`` and a stick-slip cycle coexists with it (a subcritical Hopf
    point), the ladder from below finds the cycle. Cycles found from several seeds are
    listed once, with every source; a seed that fails is listed in ``failed``.

    Parameters
    ----------
    model : Model
        Without excitation.
    limit : int
        Reported in the result only (a cycle's period is found, not a multiple of ``T``).
    ladder : float
        The distance in ``Vb`` of the ladders' seeds [m/s]; 0: none.
    backend : {"python", "numba", None}

    Returns
    -------
    ResponseSet
        Each cycle as a `Response` of one period (its own).

    See Also
    --------
    beltmdsm.periodic.cycle.cycle : one cycle by Newton's method.
    beltmdsm.multistability.responses.responses : what calls it without excitation.

    Examples
    --------
    Stribeck friction without excitation at 1 m/s: steady sliding is unstable and its
    run settles on a stable stick-slip cycle:

    >>> from beltmdsm import Model
    >>> found = cycle_responses(Model(alpha=0, friction="stribeck", Vb=1.0), ladder=0.0)
    >>> [(r.floquet.stable, r.sources) for r in found.responses]
    [(True, ['the run off perturbed steady sliding'])]
    >>> round(found.responses[0].amplitude, 2), found.failed
    (1.34, [])
    """
    from ..periodic.cycle import cycle, seed_cycle, unstable_pair

    found, failed = [], []

    def add(c, source, distance=None):
        known = next((r for r in found if r.same_orbit(1, c.state)), None)
        if known is None:
            found.append(_cycle_response(c, source, distance))
        else:
            known.sources.append(source)

    # where steady sliding is stable the seed's run starts where a stick ends
    # (`beltmdsm.starts.cycle_seed.seed_cycle`)
    source = (
        "the run off perturbed steady sliding"
        if unstable_pair(model)[0].real > 0
        else "the run from the end of a stick"
    )
    try:
        x, T = seed_cycle(model, backend=backend)
        c = cycle(model, x, T, backend=backend)
        add(c, source, float(np.max(np.abs(x - c.state))) / (1.0 + float(np.max(np.abs(x)))))
    except NoPeriodicResponse as err:
        failed.append(SeedFailure(source, str(err)))
    vb = float(model["Vb"])
    for direction, first in (("up", vb - ladder), ("down", vb + ladder)):
        if ladder <= 0 or first <= 0:
            continue
        source = f"cycles continued {direction} from Vb = {first:g}"
        try:
            add(_continued_cycle(model, first, vb, backend), source)
        except NoPeriodicResponse as err:
            failed.append(SeedFailure(source, str(err)))
    found.sort(key=lambda r: r.amplitude)
    return ResponseSet(model, int(limit), found, [], failed)
