"""The branch of a derived model's forced response (``beltmdsm.branch`` of another model),
and of its self-excited cycles (``beltmdsm.continue_branch`` of its cycle).

`oscillator_branch` shoots the response at the model's value of the parameter
(`beltmdsm.oscillator.forced.forced_response`) and walks
`beltmdsm.continuation.oscillator_forced.OscillatorForcedProblem` both ways on the one
driver (`beltmdsm.continuation.driver`). The result is a `Branch` of ``kind =
"forced"``: `OscillatorBranch`, whose JSON, table, ``repr`` and plot name the model and
its states (``x``, ``x_dot``), never the paper's X1, X2. `continue_oscillator_cycle`
walks `beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem` both ways from a
pure-slip cycle: an `OscillatorBranch` of ``kind = "cycle"``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..branch_lines import draw_branch, new_axes
from ..errors import Unsupported
from ..model import Model
from ..oscillator.api import system_of
from ..oscillator.cycle import Cycle
from ..oscillator.forced import Response, forced_response
from ..oscillator.hybrid import flow
from ..oscillator.slip_shooting import least_speed
from ..oscillator.system import System
from .branch_result import Branch, record_points
from .driver import join, walk
from .oscillator_cycle import DETECTS as CYCLE_DETECTS
from .oscillator_cycle import OscillatorCyclePoint, OscillatorCycleProblem
from .oscillator_forced import OscillatorForcedProblem, OscillatorPoint
from .problem import range_end
from .settings import FORCED_SETTINGS, ContinuationSettings, as_settings

__all__ = [
    "OscillatorBranch", "oscillator_branch", "continue_oscillator_branch",
    "continue_oscillator_cycle", "forced_system",
]  # fmt: skip


class OscillatorBranch(Branch):
    """A `Branch` of a derived model's forced responses: its points are
    `beltmdsm.continuation.oscillator_forced.OscillatorPoint`; its output names the model
    and its states (module docstring).

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0),
    ...            param="Omega_t", lo=1.9, hi=2.1)
    >>> isinstance(b, Branch), b.kind, [s.kind for s in b.special]
    (True, 'forced', ['range', 'range'])
    >>> d = b.as_dict()
    >>> d["model"], d["states"], "X1" in str(d)
    ('belt_1dof', ['x', 'x_dot'], False)
    """

    @property
    def system(self) -> System:
        return system_of(self.model)

    def __repr__(self) -> str:
        from .._display import block, intervals, label

        lo, hi = self.value_range() if self.points else (math.nan, math.nan)
        what = "T" if self.periods == 1 else f"{self.periods}T"
        what = "self-excited cycles" if self.kind == "cycle" else f"{what}-periodic response"
        lines = [
            f"{label(s.kind)} at {self.param} = {s.value:.6g} (+- {s.accuracy:.0e})"
            + (f", {s.frequency:.4g} rad/s" if s.frequency is not None else "")
            + (f": {s.detail}" if s.detail else "")
            for s in self.special
        ]
        return block(
            f"Branch({self.param!r}, {what}, {self.model!r}; "
            f"{self.model.friction} friction; {len(self.points)} points, {self.param} from "
            f"{lo:.6g} to {hi:.6g}): stable in {intervals(self.stable_ranges())}",
            lines,
        )

    def as_dict(self) -> dict:
        """For JSON: the model's part (``model``, ``friction``, ``params`` less ``param``,
        ``states``), then ``param``, ``periods``, ``kind``, ``range``, ``parts``,
        ``stable_ranges``, ``special_points``, ``points`` and ``detects`` (the special
        points this problem looks for)."""
        return {
            **self.system.as_dict(without=self.param),
            "param": self.param,
            "periods": self.periods,
            "kind": self.kind,
            "detects": list(CYCLE_DETECTS if self.kind == "cycle" else DETECTS),
            "range": self.value_range(),
            "parts": [p.as_dict() for p in self.parts()],
            "stable_ranges": self.stable_ranges(),
            "special_points": [s.as_dict() for s in self.special],
            "points": [p.as_dict() for p in self.points],
        }

    def _state_names(self) -> list[str]:
        """The points' state columns: the model's states."""
        return list(self.system.states)

    def plot(self, ax: Any = None, observable: str | None = None, labels: bool = True) -> Any:
        """The bifurcation diagram: ``observable`` (a column of `observables`; default the
        amplitude of the first rate, ``x_dot_amplitude``) against ``param``, stable solid,
        unstable dashed, the special points marked; on matplotlib axes ``ax`` (new ones if
        None), which it returns."""

        states = self.system.states
        observable = observable or f"{states[len(states) // 2]}_amplitude"
        table = self.observables()
        if observable not in table or observable == self.param:
            raise ValueError(
                f"observable must be one of {', '.join(list(table)[1:])}; got {observable!r}"
            )
        ax = new_axes(ax)
        x, y = table[self.param], table[observable]
        draw_branch(ax, x, y, [p.stable for p in self.points], self.special, labels=labels)
        ax.set_xlabel(self.param)
        ax.set_ylabel(observable.replace("_", " "))
        ax.set_title(f"{self.response} of model {self.model.model}: {self.model!r}", fontsize=8)
        ax.legend(loc="best", fontsize="small")
        return ax


#: The special points that `OscillatorForcedProblem` detects (module docstring of
#: beltmdsm/continuation/oscillator_forced.py); it detects no tangency and no flight onset.
DETECTS = (
    "fold", "period_doubling", "neimark_sacker", "branch_point", "stick_onset", "grazing",
)  # fmt: skip


def forced_system(model: Model, analysis: str, params: tuple[str, ...] = ()) -> System:
    """The `System` of another model for a forced analysis: refused in one line where
    the model has no excitation (its line in `beltmdsm.model.LACKS`), a ValueError for
    a parameter it lacks."""
    system = system_of(model)
    if system.excitation_period() is None:
        raise Unsupported(model.refusal(analysis))
    for name in params:
        if name not in system.params:
            raise ValueError(
                f"param must be a parameter of model {model.model!r} "
                f"({', '.join(system.params)}); got {name!r}"
            )
    return system


def _check_forced(system: System, param: str, lo: float, hi: float) -> None:
    """The excitation must keep one period over the whole range."""
    for end in (lo, hi):
        if system.replace(**{param: end}).excitation_period() is None:
            raise ValueError(
                f"the range of {param} reaches {end:g}, where model {system.name!r} has no "
                "excitation (every amplitude 0): a forced response needs one throughout"
            )


def oscillator_branch(
    model: Model,
    *,
    periods: int = 1,
    param: str,
    lo: float,
    hi: float,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> OscillatorBranch:
    """The branch of a derived model's forced response in ``param`` over ``[lo, hi]``.

    Parameters
    ----------
    model : Model
        Another registered model than the paper's (``Model(model="belt_1dof", ...)``),
        with excitation; its value of ``param`` is the start, both ways.
    periods : int
        ``k``: the response of ``k`` excitation periods.
    param : str
        One of the model's parameters.
    lo, hi : float
        The range, holding the model's value.
    record : callable, optional
        As for `beltmdsm.branches.branch`.
    settings : ContinuationSettings, optional
        Default `beltmdsm.continuation.settings.FORCED_SETTINGS`.

    Returns
    -------
    OscillatorBranch

    Raises
    ------
    beltmdsm.errors.Unsupported
        A model without excitation.
    ValueError
        An unknown parameter, a range that does not hold the model's value or reaches
        a value without excitation.
    NoPeriodicResponse
        Where shooting finds no response at the start.

    See Also
    --------
    beltmdsm.branches.branch : the public entry, which routes another model here.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> b = oscillator_branch(m, param="Omega_t", lo=1.9, hi=2.1)
    >>> b.stable_ranges()
    [[1.9, 2.1]]
    """
    system = forced_system(model, "branch", (param,))
    if not isinstance(periods, int) or isinstance(periods, bool) or periods < 1:
        raise ValueError(f"periods must be a whole number >= 1; got {periods!r}")
    lo, hi = _checked_range(system, param, lo, hi, "the model's")
    start = forced_response(system, periods=periods)
    return _both_ways(model, system, start.state, periods, param, lo, hi, record, settings)


def continue_oscillator_branch(
    start: Response | OscillatorPoint,
    param: str,
    lo: float,
    hi: float,
    *,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> OscillatorBranch:
    """The branch of a derived model's forced response through ``start``, both ways.

    Parameters
    ----------
    start : Response or OscillatorPoint
        A forced response (`beltmdsm.oscillator.forced.forced_response`, what
        ``beltmdsm.periodic_response`` returns for another model) or a point of an
        `OscillatorBranch` (``b.points[-1]`` continues ``b`` from its end; at a special
        point, ``b.point_near(s.value)``); its state is the start, its ``k`` periods kept.
    param : str
        One of the model's parameters (not necessarily the one ``start``'s branch took).
    lo, hi : float
        The range, holding the start's value of ``param``.
    record, settings
        As for `oscillator_branch`.

    Returns
    -------
    OscillatorBranch

    Raises
    ------
    ValueError
        An unknown parameter, a range that does not hold the start's value or reaches
        a value without excitation.

    See Also
    --------
    beltmdsm.branches.continue_branch : the public entry, which routes another model here.

    Examples
    --------
    Continue a branch from its upper end; the two pieces meet at ``Omega_t = 2.0``:

    >>> from beltmdsm import Model, branch
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=1.9)
    >>> first = branch(m, param="Omega_t", lo=1.9, hi=2.0)
    >>> more = continue_oscillator_branch(first.points[-1], "Omega_t", 2.0, 2.1)
    >>> more.value_range(), more.model["Omega_t"]
    ([2.0, 2.1], 2.0)
    """
    system = start.system
    if param not in system.params:
        raise ValueError(
            f"param must be a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {param!r}"
        )
    periods = getattr(start, "periods", None)
    if periods is None:  # a branch point: its period is k excitation periods
        periods = int(round(start.period / system.excitation_period()))
    lo, hi = _checked_range(system, param, lo, hi, "the start's")
    model = Model(model=system.name, friction=system.friction, **system._given)
    return _both_ways(model, system, start.state, periods, param, lo, hi, record, settings)


def _checked_range(system: System, param: str, lo: float, hi: float, whose: str):
    """``(lo, hi)`` as floats: finite, ordered, holding the system's value of
    ``param``, with excitation throughout (`_check_forced`)."""
    lo, hi = float(lo), float(hi)
    p0 = system.params[param]
    if not (np.isfinite(lo) and np.isfinite(hi) and lo <= p0 <= hi and lo < hi):
        raise ValueError(f"{whose} {param} = {p0:g} must lie in [{lo:g}, {hi:g}]")
    _check_forced(system, param, lo, hi)
    return lo, hi


def _both_ways(model, system, state, periods, param, lo, hi, record, settings):
    """Walk `OscillatorForcedProblem` from the fixed point ``state`` at the system's
    value of ``param`` up to ``hi`` and down to ``lo`` on the one driver, joined."""
    settings = as_settings(settings, FORCED_SETTINGS)
    p0 = system.params[param]
    problem = OscillatorForcedProblem(
        system, param, periods, lo, hi, 1.0 + float(np.max(np.abs(state)))
    )
    problem.settings = settings
    walks = []
    for direction, bound in ((1.0, hi), (-1.0, lo)):
        first, tangent = problem.start(state, p0, direction)
        done = p0 == bound  # a start on a bound ends there that way
        walks.append(([first], [range_end(first, p0)]) if done else walk(problem, first, tangent))
    points, special = join(*walks)
    found = OscillatorBranch(param, periods, model, points, special, kind="forced")
    return record_points(found, record)


def continue_oscillator_cycle(
    start: Cycle | OscillatorCyclePoint,
    param: str,
    lo: float,
    hi: float,
    *,
    record: Callable[[Any], float | Mapping[str, float]] | None = None,
    settings: ContinuationSettings | None = None,
) -> OscillatorBranch:
    """The branch of a derived model's self-excited cycle through ``start``, both ways
    (`beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`).

    Each way ends at the range's bound or where no step converges; a pure-slip branch
    at its stick onset (the grazing cycle its last point) or its Hopf point (the cycle
    shrinks onto steady sliding), a stick-slip one where its switches change
    (``grazing``). Folds, period doublings and Neimark-Sacker points are located on
    the way.

    Parameters
    ----------
    start : Cycle or OscillatorCyclePoint
        A cycle, pure slip or with stick phases (what ``beltmdsm.cycle`` returns for
        another model, `beltmdsm.oscillator.cycles.self_excited_cycle`), or a point of
        such a branch.
    param : str
        One of the model's parameters.
    lo, hi : float
        The range, holding the start's value of ``param``.
    record, settings
        As for `oscillator_branch` (default
        `beltmdsm.continuation.settings.CYCLE_SETTINGS`).

    Returns
    -------
    OscillatorBranch
        ``kind = "cycle"``.

    Raises
    ------
    ValueError
        An unknown parameter, a range that does not hold the start's value.
    NoPeriodicResponse
        Where the start does not correct at its value.

    See Also
    --------
    beltmdsm.branches.continue_branch : the public entry, which routes such a start here.

    Examples
    --------
    The unstable slip cycles of the Stribeck belt, down to their Hopf point and up to
    their stick onset:

    >>> from beltmdsm import Model, cycle
    >>> c = cycle(Model(model="belt_1dof", friction="stribeck", Vb=2.5),
    ...           guess=[3.0182035, 2.0991444], period=6.3203187)
    >>> b = continue_oscillator_cycle(c, "Vb", 1.5, 3.5)
    >>> [(s.kind, round(s.value, 5)) for s in b.special]
    [('hopf', 1.99572), ('stick_onset', 2.90039)]
    >>> b.kind, b.stable_ranges()
    ('cycle', [])

    The stable stick-slip cycle of the same belt, one stick a period throughout:

    >>> b = continue_oscillator_cycle(cycle(Model(model="belt_1dof", friction="stribeck",
    ...                                           Vb=1.5)), "Vb", 1.4, 1.6)
    >>> [s.kind for s in b.special], {p.n_sticks for p in b.points}, b.stable_ranges()
    (['range', 'range'], {1}, [[1.4, 1.6]])
    """
    system = start.system
    if param not in system.params:
        raise ValueError(
            f"param must be a parameter of model {system.name!r} "
            f"({', '.join(system.params)}); got {param!r}"
        )
    hybrid = bool(start.switches)
    if isinstance(start, Cycle):
        start = _on_section(start)
    lo, hi = float(lo), float(hi)
    p0 = system.params[param]
    if not (np.isfinite(lo) and np.isfinite(hi) and lo <= p0 <= hi and lo < hi):
        raise ValueError(f"the start's {param} = {p0:g} must lie in [{lo:g}, {hi:g}]")
    sx = 1.0 + float(np.max(np.abs(start.state)))
    problem = OscillatorCycleProblem(
        system, param, start.mode, lo, hi, sx, start.period, hybrid=hybrid
    )
    problem.settings = as_settings(settings, problem.default_settings)
    walks = []
    for direction, bound in ((1.0, hi), (-1.0, lo)):
        first, tangent = problem.start(start.state, start.period, p0, direction)
        if p0 == bound:  # a start on a bound ends there that way
            walks.append(([first], [range_end(first, p0)]))
        else:
            walks.append(problem.finish(*walk(problem, first, tangent)))
    points, special = join(*walks)
    model = Model(model=system.name, friction=system.friction, **system._given)
    return record_points(OscillatorBranch(param, 1, model, points, special, kind="cycle"), record)


def _on_section(c: Cycle):
    """``c`` on its problem's section: a pure-slip cycle shot again from where its slip
    speed is least (`beltmdsm.oscillator.slip_shooting.least_speed`); one with a stick
    phase at the sample of its run (T / 2000 apart) where the slip speed is largest,
    its slip mode there (`OscillatorCycleProblem.start` corrects it)."""
    if not c.switches:
        return least_speed(c)
    samples: list = []
    flow(c.system, 0.0, c.state, c.period, mode=c.mode, dt=c.period / 2000, samples=samples,
         rtol=1e-11, atol=1e-11)  # fmt: skip
    k, p = c.system.kernels, c.system.p
    best = max(
        ((md * float(k.slip_velocity(0.0, y, p)), md, y) for _, ys, md in samples
         if md in (1, -1) for y in ys),
        key=lambda item: item[0],
    )  # fmt: skip
    return SimpleNamespace(state=best[2], mode=best[1], period=c.period, switches=c.switches)
