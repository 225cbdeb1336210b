"""The periodic response of Eq. (4): its state at phase 0, its switches and its monodromy.

`PeriodicResponse` is what shooting finds (`beltmdsm.periodic.shooting.periodic_response`)
and what the Floquet multipliers are read from (`beltmdsm.periodic.floquet.Floquet`):
built from a fixed point of a ``k``-fold period map by `response_from` (either engine,
`beltmdsm.periodic.engines.ENGINES`), or from a self-excited cycle of a model without
excitation by `response_of_cycle` (`beltmdsm.periodic.cycle.Cycle`).

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..integrate.normal import normal_motion
from ..integrate.superposition import Superposition
from ..model import Model
from .base import RTOL, PeriodMap
from .engines import ENGINES, period_map
from .general_map import GeneralMap
from .newton import FixedPoint

__all__ = [
    "PeriodicResponse",
    "response_of_cycle",
    "response_from",
]


@dataclass(kw_only=True)
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
        The period map that found it (`beltmdsm.periodic.engines.ENGINES`, chosen by
        the facts of the model's laws, `beltmdsm.periodic.engines.engine_of`).
    autonomous : bool
        A self-excited cycle of the model without excitation (`response_of_cycle`):
        ``period`` was found, ``state0`` lies on its section, ``cycle`` is the
        `beltmdsm.periodic.cycle.Cycle`.

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : finds it.
    beltmdsm.periodic.floquet.Floquet : its multipliers and what they say.

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model, periodic_response
    >>> r = periodic_response(Model(Vb=5.0))
    >>> r.engine, r.periods, round(r.period, 4), len(r.switches), r.residual < 1e-10
    ('closed_form', 1, 1.5708, 2, True)
    >>> np.round(r.state0, 3)  # X1, X1', X2, X2' at phase 0
    array([ 4.566, -6.146, 12.521,  2.264])

    The normal equation is free of the tangential state: the monodromy is block
    triangular, its multipliers those of the diagonal blocks.

    >>> bool(np.all(r.monodromy[2:, :2] == 0))
    True
    >>> r.shooting_state.shape  # the closed-form map shoots in (X1, X1')
    (2,)
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
        period map at ``state0`` (computed once), its extremes refined to 1e-12 s
        (`beltmdsm.periodic.margins.orbit_range`).

        Returns
        -------
        x1_range, velocity_range : (float, float)
            ``X1`` [m] and ``X1'`` [m/s].

        Raises
        ------
        beltmdsm.errors.NoPeriodicResponse
            Where the period map fails at ``state0`` (not for a response it found).

        See Also
        --------
        beltmdsm.periodic.observables.observables : the observables of a branch point.

        Examples
        --------
        >>> from beltmdsm import periodic_response
        >>> x1, v1 = periodic_response(Model(Vb=5.0)).ranges()
        >>> [round(v, 3) for v in x1 + v1]
        [3.373, 6.623, -6.412, 6.985]
        """
        if self._ranges is None:
            if self.autonomous:
                self._ranges = (self.cycle.x1_range, self.cycle.velocity_range)
            else:
                # the model of a response found: checked where it entered
                pmap = period_map(self.model, self.periods, engine=self.engine, check=False)
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
    """The `PeriodicResponse` of a self-excited cycle (`beltmdsm.periodic.cycle.Cycle`).

    Its ``state0`` is the cycle's state on the section, ``period`` the one found, the
    monodromy the whole one of the general path (``engine="general"``).

    Parameters
    ----------
    c : beltmdsm.periodic.cycle.Cycle

    Returns
    -------
    PeriodicResponse
        With ``autonomous`` set and ``cycle`` the cycle.

    Raises
    ------
    AttributeError
        Where ``c`` is not a cycle (it lacks what a `beltmdsm.periodic.cycle.Cycle` has).

    See Also
    --------
    beltmdsm.periodic.cycle.cycle : the cycle by shooting with a phase condition.
    beltmdsm.periodic.shooting.periodic_response : calls it for a model without excitation.

    Examples
    --------
    >>> from beltmdsm import Model, cycle
    >>> r = response_of_cycle(cycle(Model(friction="stribeck", alpha=0.0, Vb=1.5)))
    >>> r.autonomous, r.engine, round(r.period, 3), r.monodromy.shape
    (True, 'general', 6.654, (4, 4))
    """
    M = np.array(c.monodromy, dtype=float)
    return PeriodicResponse(
        model=c.model,
        period=c.period,
        state0=np.array(c.state, dtype=float),
        switches=list(c.switches),
        segments=list(c.segments),
        monodromy_tangential=M[:2, :2],
        monodromy_normal=M[2:, 2:],
        grazing=c.grazing,
        residual=c.residual,
        iterations=c.iterations,
        _engine=None,
        periods=1,
        engine="general",
        _monodromy=M,
        autonomous=True,
        cycle=c,
        _ranges=(c.x1_range, c.velocity_range),
    )


def response_from(pmap: PeriodMap, point: FixedPoint) -> PeriodicResponse:
    """The `PeriodicResponse` of a fixed point of a ``k``-fold map (either engine).

    Parameters
    ----------
    pmap : beltmdsm.periodic.base.PeriodMap
        The map of ``k = pmap.periods`` periods.
    point : beltmdsm.periodic.newton.FixedPoint
        Its fixed point (`beltmdsm.periodic.newton.fixed_point`).

    Returns
    -------
    PeriodicResponse
        Of ``periods = k``; on the closed-form path its normal block the normal orbit's
        monodromy to the power ``k``.

    Raises
    ------
    AttributeError
        Where ``pmap`` is not a period map of `beltmdsm.periodic.engines.ENGINES`.

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : the shooting that calls it.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> from beltmdsm.periodic.engines import period_map
    >>> from beltmdsm.periodic.newton import fixed_point
    >>> pmap = period_map(Model(Vb=5.0))
    >>> r = response_from(pmap, fixed_point(pmap, pmap.sliding_guess()))
    >>> r.engine, r.periods, round(r.period, 4)
    ('closed_form', 1, 1.5708)
    """
    k, image = pmap.periods, point.image
    if isinstance(pmap, GeneralMap):
        M = image.jacobian
        blocks, full, engine = (M[:2, :2], M[2:, 2:]), M, pmap
    else:
        blocks = (image.jacobian, np.linalg.matrix_power(pmap.one.orbit.monodromy, k))
        full, engine = None, pmap.one
    return PeriodicResponse(
        model=pmap.model,
        period=k * pmap.period,
        state0=pmap.full_state(point.state),
        switches=list(image.switches),
        segments=list(image.segments),
        monodromy_tangential=blocks[0],
        monodromy_normal=blocks[1],
        grazing=image.grazing,
        residual=point.residual,
        iterations=point.iterations,
        _engine=engine,
        periods=k,
        engine=pmap.engine,
        _monodromy=full,
    )
