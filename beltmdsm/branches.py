"""The branch of any model: the continuation problem picked by the model (issue 38).

As SciPy's ``solve_ivp`` picks its solver above every solver, `branch` and
`continue_branch` sit above every problem they pick (tests/test_layers.py): a model
with excitation continues its forced response (`beltmdsm.continuation.branch`, the
``k``-fold period map), a model without excitation its self-excited cycles
(`beltmdsm.cycles.branch`, from the Hopf point of steady sliding). Both drive the one
continuation driver (`beltmdsm.continuation.driver`) and return one `Branch` type, its
``kind`` saying which. ``beltmdsm.branch`` is this `branch`; before issue 38 it lived in
beltmdsm/continuation/branch.py, which now continues forced responses only and names
this module for a self-excited cycle.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from ._calling import public
from .continuation import branch as forced
from .continuation.branch_result import Branch, record_points
from .continuation.forced import BranchPoint
from .continuation.oscillator_branch import (
    continue_oscillator_branch,
    continue_oscillator_cycle,
    oscillator_branch,
)
from .continuation.oscillator_cycle_point import OscillatorCyclePoint
from .continuation.oscillator_forced import OscillatorPoint
from .continuation.settings import ContinuationSettings
from .cycles.branch import cycle_branch, cycle_branch_from
from .cycles.continuation import CyclePoint
from .errors import Unsupported
from .excitation import is_autonomous
from .model import Backend, Model, as_model
from .oscillator.api import _paper_keywords
from .oscillator.cycles import Cycle as OscillatorCycle
from .oscillator.forced import Response
from .periodic.cycle import cycle as shoot_cycle
from .periodic.response import PeriodicResponse

__all__ = ["branch", "continue_branch"]


@public(models=True)
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
    """The branch of a model's periodic response in ``param`` over ``[lo, hi]``.

    With excitation: the response of ``periods`` periods at the point, continued
    (`beltmdsm.continuation.branch.branch`). Without excitation
    (`beltmdsm.excitation.is_autonomous`): the branch of self-excited cycles born at
    the Hopf point of steady sliding in ``[lo, hi]`` (`beltmdsm.cycles.branch.cycle_branch`,
    a `Branch` of ``kind = "cycle"``).

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
        ``record(point)`` at each point, stored there (`beltmdsm.continuation.branch.branch`).
    settings : ContinuationSettings, optional
        The driver's steps and tolerances; default the problem's.

    Returns
    -------
    Branch
        Its points in arclength order from the lower end, its special points.

    Raises
    ------
    ValueError
        For bad parameters or range; ``periods != 1`` without excitation.
    NoPeriodicResponse
        Where no response (no cycle) is found at the start.
    beltmdsm.errors.Refused
        Naming ``record`` (`beltmdsm.continuation.branch_result.record_points`).

    See Also
    --------
    beltmdsm.continuation.branch.branch : forced responses.
    beltmdsm.cycles.branch.cycle_branch : self-excited cycles.
    beltmdsm.continuation.equilibrium.equilibrium_branch : steady sliding.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6, record=lambda p: p.state[0])
    >>> b.kind, [(s.kind, round(s.value, 3)) for s in b.special]
    ('forced', [('range', 5.3), ('neimark_sacker', 5.45), ('range', 5.6)])
    >>> b.stable_ranges()  # doctest: +ELLIPSIS
    [[5.3, 5.449...]]
    >>> table = b.observables()
    >>> bool(all(table["record"] == [p.state[0] for p in b.points]))
    True
    >>> c = branch(Model(friction="stribeck", alpha=0.0), lo=1.9, hi=2.1)
    >>> c.kind, c.special[0].kind, round(c.special[0].value, 4)
    ('cycle', 'hopf', 1.9957)
    """
    forced._check_record(record)
    model = as_model(model)
    if model.model != "paper":  # another registered model: its forced response
        _paper_keywords("branch", model, backend=backend)
        return oscillator_branch(
            model, periods=periods, param=param, lo=lo, hi=hi, record=record, settings=settings
        )
    if not is_autonomous(model):
        return forced.branch(
            model, periods=periods, param=param, lo=lo, hi=hi, backend=backend,
            record=record, settings=settings,
        )  # fmt: skip
    if periods != 1:
        raise ValueError(
            f"periods must be 1 without excitation (a self-excited cycle has no "
            f"excitation period to count); got {periods!r}"
        )
    found = cycle_branch(model, param=param, lo=lo, hi=hi, backend=backend, settings=settings)
    return record_points(found, record)


def continue_branch(
    start: PeriodicResponse
    | BranchPoint
    | CyclePoint
    | Response
    | OscillatorPoint
    | OscillatorCycle
    | OscillatorCyclePoint,
    param: str,
    lo: float,
    hi: float,
    *,
    backend: Backend | None = None,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch through a response (forced, or a self-excited cycle's), both ways.

    Parameters
    ----------
    start : a response, a self-excited cycle or a point of a branch
        The paper's: from `beltmdsm.periodic.shooting.periodic_response`, or a point of
        its branch (`beltmdsm.continuation.forced.BranchPoint`, or of a branch of cycles
        `beltmdsm.cycles.continuation.CyclePoint`: ``b.points[-1]`` continues ``b``
        from its end, ``b.point_near(s.value)`` from a special point). Another
        model's forced response: what ``beltmdsm.periodic_response`` returns for it
        (`beltmdsm.oscillator.forced.Response`), or a point of its branch
        (`beltmdsm.continuation.oscillator_forced.OscillatorPoint`: ``b.points[-1]``
        continues ``b`` from its end, ``b.point_near(s.value)`` from a special point).
        Another model's self-excited cycle: what ``beltmdsm.cycle`` returns for it
        (`beltmdsm.oscillator.cycle.Cycle`), or a point of its branch
        (`beltmdsm.continuation.oscillator_cycle_point.OscillatorCyclePoint`).
    param : str
        A model parameter.
    lo, hi : float
        The range; the start's value must lie in it.
    backend : {"python", "numba", None}
        The paper's integrators only.
    record : callable, optional
        As for `branch`.
    settings : ContinuationSettings, optional
        The driver's steps and tolerances; default the problem's.

    Returns
    -------
    Branch
        ``kind = "forced"`` (`beltmdsm.continuation.branch.continue_branch`; another
        model's: `beltmdsm.continuation.oscillator_branch.continue_oscillator_branch`)
        or ``"cycle"`` (`beltmdsm.cycles.branch.cycle_branch_from`; another model's:
        `beltmdsm.continuation.oscillator_branch.continue_oscillator_cycle`).

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range or a start outside it.
    beltmdsm.errors.Unsupported
        ``backend`` with another model.

    See Also
    --------
    beltmdsm.branches.branch : from a model.

    Examples
    --------
    >>> from beltmdsm import Model, periodic_response
    >>> start = periodic_response(Model(friction="stribeck", alpha=0.0, Vb=1.5))
    >>> b = continue_branch(start, "Vb", 1.48, 1.52)
    >>> b.kind, [s.kind for s in b.special]
    ('cycle', ['range', 'range'])

    Another model's branch continued from its end:

    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=1.9)
    >>> first = branch(m, param="Omega_t", lo=1.9, hi=2.0)
    >>> more = continue_branch(first.points[-1], "Omega_t", 2.0, 2.1)
    >>> more.kind, more.model.model, more.value_range()
    ('forced', 'belt_1dof', [2.0, 2.1])
    """
    if isinstance(start, (Response, OscillatorPoint, OscillatorCycle, OscillatorCyclePoint)):
        if backend is not None:
            raise Unsupported(
                f"continue_branch: backend={backend!r} applies to the paper's model, not "
                f"to model {start.system.name!r} (the generic runtime, beltmdsm/oscillator/)"
            )
        forced._check_record(record)
        if isinstance(start, (OscillatorCycle, OscillatorCyclePoint)):
            return continue_oscillator_cycle(start, param, lo, hi, record=record, settings=settings)
        return continue_oscillator_branch(start, param, lo, hi, record=record, settings=settings)
    if not isinstance(start, CyclePoint) and not getattr(start, "autonomous", False):
        return forced.continue_branch(
            start, param, lo, hi, backend=backend, record=record, settings=settings
        )
    forced._check_record(record)
    forced._check_range(param, lo, hi)
    if isinstance(start, CyclePoint):  # a point of a branch of cycles: its cycle, shot again
        cycle = shoot_cycle(start.model, guess=start.state, period=start.period, backend=backend)
    else:
        cycle = start.cycle
    found = cycle_branch_from(cycle, param, lo, hi, backend=backend, settings=settings)
    return record_points(found, record)
