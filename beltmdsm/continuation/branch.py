"""Branches of periodic responses: pseudo-arclength continuation on the ``k``-fold period map.

A response of Eq. (4) of ``k`` excitation periods is a zero of ``G(x, p) = P_p(x) - x``,
with ``P_p`` the ``k``-fold period map at the parameter value ``p``
(`beltmdsm.periodic.family.MapFamily`). `continue_branch` follows the curve of zeros in
``(x, p)`` by pseudo-arclength continuation, so it passes folds: a secant predictor
along the unit tangent (the null vector of ``[dP/dx - I, dP/dp]``, in coordinates
scaled by the state's and the range's size), a corrector by Newton's method on ``G = 0``
and the hyperplane normal to the tangent (``dP/dx`` is the monodromy of the shooting
state, ``dP/dp`` by central differences), and a step that grows after easy steps and
halves after failed ones.

Between two accepted points it watches

* the tangent's ``p``-component: a sign change is a **fold**;
* the number of multipliers outside the unit circle: a change is a **Neimark-Sacker**
  (complex pair), **period-doubling** (through -1) or **fold** bifurcation (through +1
  without a turn: a branch point, ``branch_point``), classified by the critical
  multiplier (`beltmdsm.continuation.edges.multiplier_kind`);
* the switch structure: where the corrector lands on another structure, the step is
  cut until it is below `GRAZING_STEP`; a response that goes on with the new structure
  passes a **grazing** point (located where the closing margin of the old side
  vanishes, `beltmdsm.continuation.edges.locate_end`).

Each special point is located by regula falsi along the arclength to `LOCATE_TOL` in
the parameter (1e-4 asked for; a tangency or grazing to the accuracy `locate_end`
reports). A branch ends at the range's bounds, or where no corrector converges even
with the smallest step: at a **tangency** or a **grazing** (the margin that closes,
located by `beltmdsm.continuation.edges.locate_end`), or, where no margin closes, as ``failed``
with the reason.

The problem (its point, residual, Jacobian and the hooks of its switch structure) is
`beltmdsm.continuation.forced.ForcedProblem`; the walk, its step control, special
points and range ends the one driver's (`beltmdsm.continuation.driver`, shared with the
self-excited cycles and steady sliding), its settings a
`beltmdsm.continuation.settings.ContinuationSettings`; the result (`Branch`)
`beltmdsm.continuation.branch_result`'s.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from .._calling import public
from ..errors import Refused
from ..excitation import is_autonomous
from ..model import MODEL_PARAMETERS, Backend, Model, as_model
from ..periodic.family import MapFamily
from ..periodic.response import PeriodicResponse
from ..periodic.shooting import periodic_response
from .branch_result import Branch, _recorded_rows, record_points
from .driver import join
from .driver import walk as _walk  # the name tests patch
from .forced import BranchPoint, ForcedProblem
from .problem import range_end
from .settings import ContinuationSettings, as_settings

__all__ = ["continue_branch", "branch"]


def continue_branch(
    start: PeriodicResponse | BranchPoint,
    param: str,
    lo: float,
    hi: float,
    *,
    backend: Backend | None = None,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch through a response in ``param`` over ``[lo, hi]``, both ways from the start.

    Parameters
    ----------
    start : PeriodicResponse or BranchPoint
        A forced response (`beltmdsm.periodic.shooting.periodic_response`,
        ``periods=k`` for a locked one), or a point of a forced `Branch`
        (`beltmdsm.continuation.forced.BranchPoint`: ``b.points[-1]`` continues ``b``
        from its end, ``b.point_near(s.value)`` from a special point; its model and
        ``k`` kept). A self-excited cycle's continues as a branch of cycles one layer
        up: `beltmdsm.branches.continue_branch` picks the problem.
    param : str
        A model parameter.
    lo, hi : float
        The range; the start's value must lie in it.
    backend : {"python", "numba", None}
    record : callable, optional
        ``record(point)`` at each point of the branch, stored there (`branch`).
    settings : ContinuationSettings, optional
        The driver's steps and tolerances (`beltmdsm.continuation.settings`); default
        the problem's (`FORCED_SETTINGS`, a cycle's `CYCLE_SETTINGS`).

    Returns
    -------
    Branch
        Its points in arclength order from the lower end, its special points.

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range or a start outside it; for a self-excited
        cycle, naming `beltmdsm.branches.continue_branch` (moved there, issue 38).
    TypeError
        For ``settings`` that is not a ContinuationSettings.
    beltmdsm.errors.Refused
        Naming ``record`` where it is not callable, raises, or returns anything but a
        real number or a mapping of names to real numbers
        (`beltmdsm.continuation.branch_result.record_points`).

    See Also
    --------
    beltmdsm.continuation.branch.branch : the same from a model, the response found first.
    beltmdsm.continuation.band.floquet_band : the unstable ranges on a grid, edges located.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> from beltmdsm.continuation.branch import continue_branch
    >>> start = periodic_response(Model(beta1=0.3, Vb=5.3))
    >>> b = continue_branch(start, "Vb", 5.3, 5.6)
    >>> [(s.kind, round(s.value, 3)) for s in b.special]
    [('range', 5.3), ('neimark_sacker', 5.45), ('range', 5.6)]
    """
    _check_record(record)
    as_settings(settings, ForcedProblem.default_settings)  # checked before anything runs
    _check_range(param, lo, hi)
    model = start.model
    if getattr(start, "autonomous", False):
        raise ValueError(
            _CYCLES.format(what="the start is a self-excited cycle", f="continue_branch")
        )
    v0 = float(model[param])
    if not lo <= v0 <= hi:
        raise ValueError(f"the start's {param} = {v0:g} is outside [{lo:g}, {hi:g}]")
    family = MapFamily(model, param, start.periods, backend)
    point = isinstance(start, BranchPoint)
    x0 = np.asarray(start.state if point else start.shooting_state, dtype=float)
    kT = start.periods * family(v0).period
    problem = ForcedProblem(family, float(lo), float(hi), 1.0 + float(np.max(np.abs(x0))), kT)
    problem.settings = as_settings(settings, problem.default_settings)
    image = family(v0)(x0)
    if record is not None:  # one that fails is refused before the continuation runs
        _recorded_rows(record, [problem.point_at(x0, v0, 1.0, image)], param)
    walks = []
    for direction in (1.0, -1.0):
        first, tangent = problem.start(x0, v0, direction, image)
        bound = hi if direction > 0 else lo
        if v0 == bound:  # a start on a bound ends there that way
            first = problem.point_at(x0, v0, direction, image)
            walks.append(([first], [range_end(first, v0)]))
        else:
            walks.append(_walk(problem, first, tangent))
    points, special = join(*walks)
    return record_points(
        Branch(param, start.periods, model, points, special, kind="forced"), record
    )


@public()
def branch(
    model: Model | Mapping[str, Any] | None = None,
    *,
    periods: int = 1,
    param: str = "Vb",
    lo: float,
    hi: float,
    backend: Backend | None = None,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch of the response of ``periods`` periods at a point (`continue_branch`).

    The response is found as `beltmdsm.periodic.shooting.periodic_response` finds it
    (``periods > 1``: seeded from the attractor of the period map). Without excitation
    (`beltmdsm.excitation.is_autonomous`) the branch is of self-excited cycles, one
    layer up: `beltmdsm.branches.branch` (``beltmdsm.branch``) picks the problem for
    any model; this one refuses such a model, naming it (issue 38).

    Parameters
    ----------
    model : Model or dict, optional
        The model at the start (default: the base set); ``**kw``: parameters and options.
    periods : int
        ``k``: the response of ``k`` excitation periods (1 without excitation).
    param : str
        The model parameter continued.
    lo, hi : float
        Its range.
    backend : {"python", "numba", None}
    record : callable, optional
        As BifurcationKit's ``record_from_solution``: ``record(point)`` is called at
        each point of the branch once it is continued, with the point (a
        `beltmdsm.continuation.forced.BranchPoint`: ``value``, ``state`` the
        shooting state at phase 0 (``X1, X1'`` first), ``multipliers``, ``image``
        the period map's image with the orbit's runs; on a branch of cycles a
        `beltmdsm.cycles.continuation.CyclePoint`, with ``period`` too), and returns a
        real number (a column ``"record"``) or a mapping of names to real numbers,
        the same names at every point. Stored as the point's ``recorded``, they are
        columns of `Branch.observables` and `Branch.to_pandas`. It is tried at the
        start first: one that fails there is refused before the continuation runs.
    settings : ContinuationSettings, optional
        The driver's steps and tolerances (`beltmdsm.continuation.settings`); default
        the problem's.

    Returns
    -------
    Branch
        Its points in arclength order from the lower end, its special points (folds,
        Neimark-Sacker, period doubling, grazing, tangency, the range's ends).

    Raises
    ------
    ValueError
        For bad parameters or range.
    TypeError
        For ``settings`` that is not a ContinuationSettings.
    NoPeriodicResponse
        Where no response of ``periods`` periods is found at the point.
    beltmdsm.errors.Refused
        Naming ``record`` where it is not callable, raises, or returns anything but a
        real number or a mapping of names to real numbers, one of the branch's own
        column names, or other names at another point.

    See Also
    --------
    beltmdsm.continuation.branch.continue_branch : the same from a response already found.
    beltmdsm.branches.branch : the same for any model (self-excited cycles too).
    beltmdsm.continuation.band.floquet_band : the unstable ranges on a grid, edges located.
    beltmdsm.continuation.floquet_map.floquet_map : the edges traced over two parameters.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6, record=lambda p: p.state[0])
    >>> [(s.kind, round(s.value, 3)) for s in b.special]
    [('range', 5.3), ('neimark_sacker', 5.45), ('range', 5.6)]
    >>> b.stable_ranges()  # doctest: +ELLIPSIS
    [[5.3, 5.449...]]
    >>> table = b.observables()
    >>> bool(all(table["record"] == [p.state[0] for p in b.points]))
    True
    """
    _check_record(record)
    as_settings(settings, ForcedProblem.default_settings)  # checked before anything runs
    model = as_model(model)
    if is_autonomous(model):
        raise ValueError(_CYCLES.format(what="the model has no excitation", f="branch"))
    start = periodic_response(model, periods=periods, backend=backend)
    return continue_branch(start, param, lo, hi, backend=backend, record=record, settings=settings)


#: The refusal of a self-excited cycle: its branch is continued one layer up.
_CYCLES = (
    "{what}: its branch is of self-excited cycles, continued by beltmdsm.branches.{f} "
    "(moved there from beltmdsm.continuation.branch, issue 38)"
)


def _check_range(param: str, lo: float, hi: float) -> None:
    """Refuse an unknown parameter or a range that is not finite with ``lo < hi``."""
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")


def _check_record(record: Any) -> None:
    """Refuse a ``record`` that is not callable before anything is computed."""
    if record is not None and not callable(record):
        raise Refused(f"record must be a callable of a branch point; got {record!r}", "record")
