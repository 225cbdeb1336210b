"""Where the runs and the searches of the forced model start (`beltmdsm.starts`).

* `periodic_start`: a state on the periodic response with ``X1`` moved a little. A run
  from there shows the instability of an unstable periodic response (``simulate --start
  periodic``, `beltmdsm.simulation.simulate`), where a run from rest may settle
  elsewhere; a stable response stays put.

A run of Eq. (4) from rest (the runs of Fig. 2b and Figs. 17-21), a run from the
perturbed periodic response or a sweep continued in a parameter ends on one attractor;
its stroboscopic samples (`beltmdsm.periodic.locked.Stroboscope`) say whether it locks
to the excitation at ``k`` periods, and shooting from the last sample gives the fixed
point of the ``k``-fold period map (`beltmdsm.periodic.newton.fixed_point`).

* `run_stroboscope`: the stroboscopic samples of a run of `beltmdsm.simulation.simulate`
  from rest or from the perturbed periodic response (`periodic_start`); `run_samples`,
  `check_limit`: how many there are, and the refusal of a lock limit they cannot decide.
* `ladder`, `ladder_stroboscope`: a sweep continued on the period map: the shooting
  state carried from rung to rung (the tangential one on the periodic normal motion,
  on the closed-form path), as ``sweep --continue`` carries a run's state, and the
  samples of each rung.
* `shoot`: Newton's method on the ``k``-fold map from a sample.

`beltmdsm.multistability.responses` and `beltmdsm.multistability.coexistence` seed their
searches here. It was ``beltmdsm.starts`` (one module), ``beltmdsm.studies.seeds`` and
``beltmdsm.periodic.start`` before; those paths still import (issue 38).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from .._calling import public
from ..errors import NoPeriodicResponse, Refused
from ..excitation import excitation_period, initial_state
from ..model import Backend, Model, as_model
from ..periodic.base import PeriodMap
from ..periodic.engines import ENGINES, engine_of, period_map
from ..periodic.locked import LOCK_LIMIT, Stroboscope, map_stroboscope, stroboscope
from ..periodic.newton import FixedPoint, fixed_point
from ..periodic.shooting import periodic_response
from ..settings import SolverSettings
from ..simulation import simulate

__all__ = [
    "PERTURBATION",
    "periodic_start",
    "RUN_T_END",
    "WINDOW",
    "LADDER_SPAN",
    "LADDER_STEP",
    "LADDER_PERIODS",
    "run_samples",
    "check_limit",
    "run_stroboscope",
    "ladder",
    "ladder_stroboscope",
    "shoot",
]

#: ``periodic_start``: the run starts on the periodic response with X1 moved by this [m].
PERTURBATION = 1e-2


@public(models=True)
def periodic_start(
    model: Model, perturbation: float = PERTURBATION, backend: Backend | None = None
) -> np.ndarray:
    """A start state on the periodic response with ``X1`` moved by ``perturbation`` [m].

    An unstable response shows its instability from there, a stable one stays put
    (``simulate --start periodic``).

    Parameters
    ----------
    model : Model
    perturbation : float
        Added to ``X1`` [m] (default `PERTURBATION`).
    backend : {"python", "numba", None}

    Returns
    -------
    ndarray (4,)
        ``(X1, X1', X2, X2')`` at ``t = 0``: the response's state at phase 0 with
        ``X1`` moved.
        Another registered model: its ``2n`` states (`beltmdsm.oscillator.api.periodic_start`:
        the forced response at phase 0, or without excitation the self-excited cycle's
        shooting state, the first state moved).

    Raises
    ------
    ValueError
        For a perturbation that is not a finite number.
    beltmdsm.errors.NoPeriodicResponse
        Where no periodic response is found.

    See Also
    --------
    beltmdsm.periodic.shooting.periodic_response : the response it starts on.
    beltmdsm.simulation.simulate : ``y0=periodic_start(model)``, or ``start="periodic"``.

    Examples
    --------
    >>> import numpy as np
    >>> from beltmdsm import Model, periodic_response, periodic_start
    >>> m = Model(Vb=5.0)
    >>> y0 = periodic_start(m, perturbation=0.5)
    >>> np.round(y0 - periodic_response(m).state0, 12)
    array([0.5, 0. , 0. , 0. ])
    """
    if not (isinstance(perturbation, (int, float)) and math.isfinite(perturbation)):
        raise ValueError(f"perturbation must be a finite number; got {perturbation!r}")
    model = as_model(model)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.periodic_start(model, float(perturbation), backend=backend)
    state = periodic_response(model, backend=backend).state0
    return state + np.array([perturbation, 0.0, 0.0, 0.0])


#: Duration of the runs that seed the search [s] (the runs of `beltmdsm.simulation`
#: default to it too), and the share of it whose samples are examined.
RUN_T_END = 1000.0
WINDOW = 0.4
#: A ladder of belt speeds (a continued sweep on the period map): its span below and
#: above the point [m/s], its step, and the periods spent at each rung to settle (as
#: many more are sampled).
LADDER_SPAN = 2.0
LADDER_STEP = 0.25
LADDER_PERIODS = 150


def run_samples(model: Model, t_end: float) -> int:
    """The number of stroboscopic samples of `run_stroboscope` for a run of ``t_end``
    seconds: the excitation periods of its last `WINDOW`, both ends counted.

    Parameters
    ----------
    model : Model
        With excitation (its period ``T``).
    t_end : float
        The run's duration [s].

    Returns
    -------
    int

    See Also
    --------
    beltmdsm.starts.forced.check_limit : the refusal of a limit they cannot decide.

    Examples
    --------
    With ``T = pi / 2`` s, a 1000 s run has 636 whole periods; the last 40% of them,
    from period 382 to 636, are 255 samples:

    >>> from beltmdsm import Model
    >>> run_samples(Model(), 1000.0), run_samples(Model(), 200.0)
    (255, 51)
    """
    n_end = int(math.floor(t_end / excitation_period(model) + 1e-9))
    return n_end - max(int(math.ceil((1.0 - WINDOW) * n_end)), 0) + 1


def check_limit(
    limit: int,
    models: Sequence[Model],
    t_end: float,
    ladder: bool,
    t_end_is_given: bool = True,
) -> None:
    """Refuse a ``limit`` that the samples cannot decide: a lock at ``k`` periods needs
    more than ``2 k`` samples (`beltmdsm.periodic.locked.stroboscope`), the runs' of
    ``t_end`` s (`run_samples`, for each model) and, with ``ladder``, the ladders'
    (`LADDER_PERIODS` a rung). ``t_end_is_given``: the caller's argument (named in
    the message), not a constant of the study.

    Parameters
    ----------
    limit : int
        The largest ``k`` looked for.
    models : sequence of Model
        The points of the runs.
    t_end : float
        The runs' duration [s].
    ladder : bool
        Whether ladders are run too.
    t_end_is_given : bool
        Whether the message may ask for a longer ``t_end``.

    Raises
    ------
    beltmdsm.errors.Refused
        Naming ``limit`` (and ``t_end`` where a longer run would do) and the bound.

    See Also
    --------
    beltmdsm.starts.forced.run_samples

    Examples
    --------
    A 50 s run has 13 samples, too few to decide a lock at 12 periods:

    >>> from beltmdsm import Model
    >>> check_limit(6, [Model()], 50.0, ladder=False)  # 13 > 2 * 6: passes
    >>> check_limit(12, [Model()], 50.0, ladder=False)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    beltmdsm.errors.Refused: a run of 50 s has 13 stroboscopic samples ... or limit <= 6
    """
    if ladder and 2 * limit >= LADDER_PERIODS:
        raise Refused(
            f"limit must be <= {(LADDER_PERIODS - 1) // 2}, since the ladders sample "
            f"{LADDER_PERIODS} periods a rung and a lock of k periods needs more than 2 k "
            f"samples (LADDER_PERIODS, beltmdsm/starts/forced.py); got {limit}"
            + (" (or give ladder 0 and a long enough t_end)" if t_end_is_given else ""),
            "limit",
        )
    for model in models:
        n = run_samples(model, t_end)
        if n > 2 * limit:
            continue
        T = excitation_period(model)
        need = math.ceil((2 * limit + 1) / WINDOW) * T
        bound = f"limit <= {max((n - 1) // 2, 0)}"
        raise Refused(
            f"a run of {t_end:g} s has {n} stroboscopic samples (the last {WINDOW:.0%} of "
            f"its periods of T = {T:.6g} s) and a lock at limit = {limit} periods needs "
            f"more than {2 * limit}: "
            + (f"give t_end >= {need:.6g} s or {bound}" if t_end_is_given else f"give {bound}"),
            *(("limit", "t_end") if t_end_is_given else ("limit",)),
        )


def run_stroboscope(
    model: Model,
    *,
    start: Literal["rest", "periodic"] = "rest",
    t_end: float = RUN_T_END,
    limit: int = LOCK_LIMIT,
    backend: Backend | None = None,
    settings: SolverSettings | None = None,
) -> Stroboscope:
    """The stroboscope of a run of `beltmdsm.simulation.simulate` from rest or the periodic start.

    The samples are the last `WINDOW` of the run's whole excitation periods. The run's
    settings are ``settings`` where given (its ``t_end`` and ``backend`` then replace
    the arguments), else ``SolverSettings(t_end=t_end, backend=backend)``.

    Parameters
    ----------
    model : Model
        With excitation.
    start : {"rest", "periodic"}
        From rest, or from the perturbed periodic response.
    t_end : float
        The run's duration [s].
    limit : int
        The largest lock looked for.
    backend : {"python", "numba", None}
    settings : SolverSettings, optional
        The run's settings.

    Returns
    -------
    beltmdsm.periodic.locked.Stroboscope
        The samples (shooting states) and the lock they show, if any.

    Raises
    ------
    NoPeriodicResponse
        For ``start="periodic"`` where there is no periodic response to start on, or a
        run that stops before ``t_end``.

    See Also
    --------
    beltmdsm.starts.forced.shoot : the fixed point from the last sample.

    Examples
    --------
    A 300 s run from rest at 5 m/s locks at four excitation periods (77 samples of the
    two tangential coordinates):

    >>> from beltmdsm import Model
    >>> s = run_stroboscope(Model(Vb=5.0), t_end=300.0)
    >>> s.source, s.candidate, s.samples.shape
    ('run from rest', 4, (77, 2))
    """
    T = excitation_period(model)
    if settings is None:
        settings = SolverSettings(t_end=t_end, backend=backend)
    y0 = periodic_start(model, backend=settings.backend) if start == "periodic" else None
    sim = simulate(model, settings=settings, y0=y0)
    if sim.status != "done":
        raise NoPeriodicResponse(f"the run ({start}) stopped: {sim.message}")
    n_end = int(math.floor(sim.trajectory.t_end / T + 1e-9))
    n_start = max(int(math.ceil((1.0 - WINDOW) * n_end)), 0)
    states = sim.trajectory.state(T * np.arange(n_start, n_end + 1)).T
    y = ENGINES[engine_of(model)].shooting(states)
    name = "run from rest" if start == "rest" else "run from the perturbed periodic response"
    return stroboscope(y, name, limit)


def ladder(
    model: Model,
    param: str,
    values: Sequence[float],
    *,
    limit: int = LOCK_LIMIT,
    backend: Backend | None = None,
) -> list[Stroboscope]:
    """A continued sweep on the period map: the stroboscope of every rung.

    The shooting state (`beltmdsm.periodic.base.PeriodMap.shooting`: the tangential
    state on the periodic normal motion, on the closed-form path) starts at rest at
    ``values[0]`` and is carried from rung to rung, as ``sweep --continue`` carries a
    run's state; at each rung `LADDER_PERIODS` periods settle it and as many more are
    the samples. A rung where the period map fails ends the ladder.

    Parameters
    ----------
    model : Model
        The other parameters and the options.
    param : str
        The parameter stepped.
    values : sequence of float
        The rungs, in the order climbed.
    limit : int
        The largest lock looked for.
    backend : {"python", "numba", None}

    Returns
    -------
    list of beltmdsm.periodic.locked.Stroboscope
        One per rung reached.

    See Also
    --------
    beltmdsm.starts.forced.ladder_stroboscope : the last rung of a ladder in ``Vb``.

    Examples
    --------
    Up from 4.5 to 5 m/s every rung is on the response of four periods:

    >>> from beltmdsm import Model
    >>> rungs = ladder(Model(), "Vb", [4.5, 4.75, 5.0])
    >>> [s.candidate for s in rungs], rungs[0].source
    ([4, 4, 4], 'continued up from Vb = 4.5')
    """
    values = [float(v) for v in values]
    first = model.replace(**{param: values[0]})
    x = ENGINES[engine_of(first)].shooting(initial_state(first))
    direction = "up" if values[-1] >= values[0] else "down"
    source = f"continued {direction} from {param} = {values[0]:g}"
    out = []
    for v in values:
        pmap = period_map(model.replace(**{param: v}), 1, backend)
        try:
            strobe = map_stroboscope(pmap, x, LADDER_PERIODS, LADDER_PERIODS, source, limit)
        except NoPeriodicResponse:
            break
        x = strobe.samples[-1]
        out.append(strobe)
    return out


def ladder_stroboscope(
    model: Model,
    direction: Literal["up", "down"],
    *,
    span: float = LADDER_SPAN,
    limit: int = LOCK_LIMIT,
    backend: Backend | None = None,
) -> Stroboscope:
    """The last rung of a `ladder` in ``Vb`` that ends at ``model``, from ``span`` below or above.

    Parameters
    ----------
    model : Model
        The point reached.
    direction : {"up", "down"}
        From below or from above.
    span : float
        How far below or above it starts [m/s] (not below 0).
    limit : int
        The largest lock looked for.
    backend : {"python", "numba", None}

    Returns
    -------
    beltmdsm.periodic.locked.Stroboscope

    Raises
    ------
    ValueError
        For a direction other than "up" or "down".
    NoPeriodicResponse
        Where the ladder does not reach ``model`` (the period map fails on the way).

    See Also
    --------
    beltmdsm.starts.forced.ladder

    Examples
    --------
    >>> from beltmdsm import Model
    >>> s = ladder_stroboscope(Model(Vb=5.0), "up", span=0.5)
    >>> s.candidate, s.source
    (4, 'continued up from Vb = 4.5')
    >>> ladder_stroboscope(Model(Vb=5.0), "sideways")
    Traceback (most recent call last):
    ValueError: direction must be 'up' or 'down'; got 'sideways'
    """
    if direction not in ("up", "down"):
        raise ValueError(f"direction must be 'up' or 'down'; got {direction!r}")
    vb = float(model["Vb"])
    first = max(vb - span, 0.0) if direction == "up" else vb + span
    rungs = np.linspace(first, vb, max(int(round(abs(vb - first) / LADDER_STEP)), 1) + 1)
    strobes = ladder(model, "Vb", rungs, limit=limit, backend=backend)
    if len(strobes) < rungs.size:
        raise NoPeriodicResponse(f"the ladder from Vb = {first:g} stops on the way")
    return strobes[-1]


def shoot(
    model: Model, periods: int, guess: ArrayLike, backend: Backend | None = None
) -> tuple[PeriodMap, FixedPoint]:
    """The ``periods``-fold map of ``model`` and its fixed point from ``guess`` (Newton).

    Parameters
    ----------
    model : Model
    periods : int
        ``k`` of the ``k``-fold map.
    guess : array_like
        A shooting state (a stroboscopic sample).
    backend : {"python", "numba", None}

    Returns
    -------
    (PeriodMap, FixedPoint)

    Raises
    ------
    NoPeriodicResponse
        Where Newton's method fails.

    See Also
    --------
    beltmdsm.periodic.newton.fixed_point : Newton's method.

    Examples
    --------
    The fixed point of the 4-fold map from a run's last sample is where the map
    returns, to Newton's tolerance:

    >>> import numpy as np
    >>> from beltmdsm import Model
    >>> model = Model(Vb=5.0)
    >>> pmap, point = shoot(model, 4, run_stroboscope(model, t_end=300.0).samples[-1])
    >>> pmap.periods, point.state.shape
    (4, (2,))
    >>> bool(np.max(np.abs(point.image.phases[0] - point.state)) < 1e-8)
    True
    """
    pmap = period_map(model, periods, backend)
    return pmap, fixed_point(pmap, pmap.guess(guess))
