"""The period map of Eq. (4) as an object: the state at phase 0 to the state ``k`` periods later.

The analyses of periodic responses (shooting on the ``k``-fold map in
`beltmdsm.periodic.response`, branches, edges, bands and two-parameter maps:
`beltmdsm.continuation.branch`, `beltmdsm.continuation.edges`, `beltmdsm.continuation.band`,
`beltmdsm.continuation.floquet_map`) see a period map only through `PeriodMap`, the
contract this module states: a callable from the shooting state ``x`` at phase 0 to a
`MapImage` (the state ``k`` excitation periods later, its Jacobian, the switches on the
way and the `beltmdsm.periodic.margins.Margin` of every feature of the orbit that a
parameter change could remove), plus the multipliers of the directions that are not part
of the shooting state. An engine gives one excitation period (`PeriodMap.one_period`) and
how its shooting state and the full state relate; the ``k``-fold map, the grazing test
and the margins are read here from the runs of the ``k`` periods, whatever the engine.

Two engines implement it (`beltmdsm.periodic.engines.ENGINES`), and
`beltmdsm.periodic.engines.period_map` chooses by the structural facts of the model's
laws that SymPy decided (``beltmdsm.generated.capabilities``), never by assumption:

* `beltmdsm.periodic.closed_form.ClosedFormMap` (``"closed_form"``), the fast special
  case, where the slip-mode friction does not depend on the tangential state and the
  normal equation is free of it (Coulomb friction with every contact and tension law):
  the tangential map on the cached periodic normal motion (`beltmdsm.periodic.normal_orbit`);
  it refuses a model without them (`beltmdsm.errors.Unsupported`).
* `beltmdsm.periodic.general_map.GeneralMap` (``"general"``), every law: the event-driven
  run in the full state ``(X1, X1', X2, X2')`` and its monodromy by the variational
  equations (`beltmdsm.periodic.variational`). Where both apply they agree to 1e-9 in
  the multipliers (tests/beltmdsm/periodic/test_general.py).

Newton's method on the map's fixed points is `beltmdsm.periodic.newton`; the maps of one
parameter's values, with their derivative in it, `beltmdsm.periodic.family`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import abc
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..integrate.switching import Switching
from ..model import Model
from .margins import (
    GRAZING_RATIO,
    MARGIN_KINDS,
    Margin,
    crossing_ratio,
    orbit_margins,
    orbit_range,
)

__all__ = [
    "RTOL",
    "Engine",
    "MapImage",
    "PeriodMap",
    "signature",
]

#: Integration tolerance of the periodic orbits.
RTOL = 1e-12

Engine = Literal["closed_form", "general"]


def signature(switches: Sequence[tuple]) -> tuple:
    """The switch structure of an orbit: the ``(before, after, surface)`` of its switches.

    Parameters
    ----------
    switches : sequence of (t, before, after, surface)
        As `MapImage.switches` and `beltmdsm.periodic.response.PeriodicResponse.switches`
        hold them (the modes as `beltmdsm.integrate.switching.Mode`).

    Returns
    -------
    tuple of (int, int, str)
        The modes as integers (-1 slip back, 1 slip forward, 0 stick, ...).

    Raises
    ------
    ValueError
        Where an entry is not four values.

    See Also
    --------
    beltmdsm.periodic.family.MapFamily.derivative : keeps a signature on both sides.

    Examples
    --------
    >>> from beltmdsm.integrate.switching import Mode
    >>> signature([(0.3, Mode.SLIP_BACK, Mode.SLIP_FORWARD, "relative_velocity")])
    ((-1, 1, 'relative_velocity'),)
    """
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
        multiplier with 8 correct digits (`beltmdsm.periodic.margins.GRAZING_RATIO`).

    See Also
    --------
    PeriodMap : what makes it (``pmap(x)``).
    beltmdsm.periodic.margins.Margin : what `MapImage.margins` holds.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0))
    >>> image = pmap(pmap.sliding_guess())
    >>> image.jacobian.shape, image.signature
    ((2, 2), ((-1, 1, 'relative_velocity'), (1, -1, 'relative_velocity')))
    >>> sorted({m.kind for m in image.margins})
    ['crossing', 'decision']
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
    ``k`` of them per application, ``engine`` the name of the implementation
    (`beltmdsm.periodic.engines.ENGINES`), ``sw`` the model's switching rules. An
    implementation gives the map over one excitation period (`one_period`), the
    multipliers of the directions it does not shoot in, how a full state and its
    shooting state relate, and the first guess of the shooting. The ``k``-fold map
    (`__call__`) and what an orbit is near (its margins, the module docstring, and its
    velocity range) are read here from the runs of the ``k`` periods, whatever the
    engine: each run has ``starts``, ``ends`` and ``modes`` of its segments,
    ``switches`` ``(t, before, after, surface, state)``, ``final`` (the state where it
    ends) and ``segments(t, index) -> (4, n)``.

    Attributes
    ----------
    model : Model
    period : float
        One excitation period [s].
    periods : int
        ``k``: the periods of one application.
    sw : beltmdsm.integrate.switching.Switching
        The model's switching rules.
    engine : str
        ``"closed_form"`` or ``"general"``.

    See Also
    --------
    beltmdsm.periodic.closed_form.ClosedFormMap : the closed-form engine.
    beltmdsm.periodic.general_map.GeneralMap : the general engine.
    beltmdsm.periodic.engines.period_map : the engine the model's laws allow.
    beltmdsm.periodic.newton.fixed_point : Newton's method on a map.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> pmap = period_map(Model(Vb=5.0), periods=2)
    >>> pmap.engine, pmap.periods, pmap.dimension
    ('closed_form', 2, 2)
    >>> len(pmap(pmap.sliding_guess()).phases)  # the state at phase 0 of each period
    2
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

    def margins(self, runs: list, kinds: Sequence[str] = MARGIN_KINDS) -> list[Margin]:
        """The margins of the given kinds of the orbit made of ``runs``
        (`beltmdsm.periodic.margins.orbit_margins`)."""
        return orbit_margins(self, runs, kinds)

    def velocity_range(self, runs: list) -> tuple[float, float]:
        """The smallest and largest ``X1'`` over the runs (`orbit_range`)."""
        return orbit_range(runs, 1)


def _periods(periods):
    if int(periods) != periods or int(periods) < 1:
        raise ValueError(f"periods must be an integer >= 1; got {periods!r}")
    return int(periods)
