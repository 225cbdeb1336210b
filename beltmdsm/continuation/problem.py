"""The contract of a continuation problem: what the one driver needs from it.

As BifurcationKit's problem hierarchy and SciPy's ``OdeSolver`` (``integrate/_ivp/
base.py``): a problem states its unknowns, its residual and Jacobian, how a solution
becomes a point with its observables, and hooks for its special points; the driver
(`beltmdsm.continuation.driver`) does the rest (pseudo-arclength prediction and
correction, step control, locating special points, clamping to the range) and knows
no problem by name.

A problem's unknowns, in scaled coordinates, are ``z = (u, p)``: ``n`` unknowns ``u``
(a state, a state and a period) and the parameter ``p`` last. Its equations are ``n``
residuals ``F(z) = 0``; the driver adds one equation of its own (the arclength's
hyperplane, or a pinned parameter) and solves the ``n + 1`` by Newton's method
(`beltmdsm.continuation.corrector.newton`).

The implementations:

* `beltmdsm.continuation.forced.ForcedProblem`: a forced response, a fixed point of
  the ``k``-fold period map (``F = P_p(x) - x``);
* `beltmdsm.cycles.continuation.CycleProblem`: a self-excited cycle, its period
  unknown and a phase condition (``F = (phi_T(x) - x, h(x))``);
* `beltmdsm.continuation.equilibrium.EquilibriumProblem`: steady sliding
  (``F = f(x, p)``), its Hopf points.
* `beltmdsm.continuation.oscillator_forced.OscillatorForcedProblem`: another derived
  model's forced response (``F = P_p(x) - x`` of its hybrid run), its stick onset;
* `beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`: another derived
  model's pure-slip self-excited cycle (``F = (phi_T(x) - x, h(x))``, the period
  unknown), its stick onset and Hopf end.

How to add one: docs/explanation/layout.md, "Adding a continuation problem".
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from .branch_result import SpecialPoint
from .corrector import newton
from .settings import FORCED_SETTINGS, ContinuationSettings

__all__ = ["Problem", "Residual", "Step", "failed", "null_vector", "range_end"]


@dataclass
class Residual:
    """One evaluation of a problem's equations at ``z`` (`Problem.residual`).

    Attributes
    ----------
    F : ndarray (n,)
        The residuals, scaled.
    size : float
        What the corrector watches shrink (a norm of ``F``).
    converged : bool
        Whether ``z`` solves the equations to the problem's tolerance.
    data : object
        What the problem keeps of the evaluation (a run, an image) for its Jacobian
        and its point.
    """

    F: NDArray[np.float64]
    size: float
    converged: bool
    data: Any


@dataclass
class Step:
    """A corrected solution (`Problem.solution`): the driver's view of it.

    Attributes
    ----------
    z : ndarray (n + 1,)
        The scaled unknowns, the parameter last.
    value : float
        The parameter.
    J : ndarray (n, n + 1)
        The Jacobian of the equations there, its parameter column fresh.
    iterations : int
        The corrector's.
    data : object
        The problem's evaluation (`Residual.data`).
    """

    z: NDArray[np.float64]
    value: float
    J: NDArray[np.float64]
    iterations: int
    data: Any


def null_vector(J) -> NDArray[np.float64]:
    """The unit null vector of ``J`` (n x n+1), its sign as the SVD gives it.

    Parameters
    ----------
    J : ndarray (n, n + 1)

    Returns
    -------
    ndarray (n + 1,)

    See Also
    --------
    beltmdsm.continuation.problem.Problem.tangent : signs it.

    Examples
    --------
    >>> t = null_vector(np.array([[1.0, -1.0]]))
    >>> bool(np.allclose(abs(t), [2**-0.5, 2**-0.5]))
    True
    """
    return np.linalg.svd(J)[2][-1]


def failed(point: Any, detail: str) -> SpecialPoint:
    """The end ``failed`` at ``point``, the reason in ``detail``.

    Parameters
    ----------
    point
        The last point of the branch.
    detail : str

    Returns
    -------
    SpecialPoint

    See Also
    --------
    beltmdsm.continuation.problem.Problem.give_up : its default.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> failed(SimpleNamespace(value=1.0, multipliers=np.zeros(1), stable=True), "why").kind
    'failed'
    """
    return SpecialPoint(
        "failed", point.value, 0.0, None, point.multipliers, point.stable, None, detail
    )


def range_end(point: Any, bound: float) -> SpecialPoint:
    """The special point ``range`` at ``bound``, with ``point``'s multipliers.

    Parameters
    ----------
    point
        The point of the branch at (or located next to) the bound.
    bound : float
        The end of the requested range.

    Returns
    -------
    SpecialPoint

    See Also
    --------
    beltmdsm.continuation.problem.Problem.at_bound : its caller.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> range_end(SimpleNamespace(multipliers=np.zeros(2), stable=True), 2.0).kind
    'range'
    """
    return SpecialPoint(
        "range", bound, 0.0, None, point.multipliers, point.stable, None,
        "the end of the requested range",
    )  # fmt: skip


class Problem(ABC):
    """A continuation problem (module docstring): unknowns, residual, Jacobian, points, hooks.

    Subclasses set ``lo``, ``hi`` (the range) and ``sp`` (the parameter's scale) and
    implement the five abstract methods; the hooks' defaults suit a smooth problem with
    no switch structure. A point (what `point` returns) has ``value``, ``tangent`` (the
    parameter component of the unit tangent), ``multipliers`` (the eigenvalues that
    decide stability, as multipliers: inside the unit circle is stable), ``stable`` and
    ``column`` (the Jacobian's parameter column, reused by the next correction).

    The special points and the hooks that give them:

    * fold, period doubling, Neimark-Sacker, branch point: `special_between` (the
      driver's regula falsi on the tangent's turn and on the critical multiplier);
    * Hopf: `special_between` of a problem whose multipliers are ``exp(lambda)``
      (`beltmdsm.continuation.equilibrium.EquilibriumProblem`);
    * grazing: `check_structure` and `crossing`; tangency: `give_up` and `near_end`
      (`beltmdsm.continuation.forced.ForcedProblem`);
    * stick onset: `check_step` and `rescue` (`beltmdsm.cycles.continuation.CycleProblem`);
    * range end: `range_specials` and `at_bound` (the driver clamps to the range);
    * a problem's own limits: `stop`.

    Attributes
    ----------
    kind : str
        What a branch of it holds (`beltmdsm.continuation.branch_result.Branch.kind`).
    default_settings : ContinuationSettings
        Used where the caller passes none.
    diverge_after : int
        Iterations after which a residual that does not shrink stops the corrector.

    See Also
    --------
    beltmdsm.continuation.driver.walk : drives any problem.
    beltmdsm.continuation.equilibrium.EquilibriumProblem : a short implementation.

    Examples
    --------
    The unit circle ``u^2 + p^2 = 1`` is a problem in 50 lines
    (`beltmdsm.continuation.circle`); the driver finds its fold at ``p = 1``:

    >>> from beltmdsm.continuation.circle import Circle
    >>> from beltmdsm.continuation.driver import walk
    >>> circle = Circle(-0.5, 1.5)
    >>> points, special = walk(circle, *circle.start(0.0, direction=1.0))
    >>> [(s.kind, round(s.value, 9)) for s in special]
    [('fold', 1.0), ('range', -0.5)]
    """

    kind: ClassVar[str] = "forced"
    default_settings: ClassVar[ContinuationSettings] = FORCED_SETTINGS
    diverge_after: ClassVar[int] = 0
    lo: float
    hi: float
    sp: float

    # -- the unknowns, the equations and the points (abstract)

    @abstractmethod
    def z(self, point: Any) -> NDArray[np.float64]:
        """The scaled unknowns of ``point``, the parameter last."""

    @abstractmethod
    def residual(self, z: NDArray[np.float64], extra: float, iteration: int) -> Residual:
        """The equations at ``z``; ``extra`` is the driver's own equation's residual."""

    @abstractmethod
    def jacobian(self, data: Any, column: NDArray[np.float64] | None = None) -> NDArray:
        """``dF/dz`` (n x n+1) at an evaluation; ``column``: the parameter column to
        reuse (computed where None)."""

    @abstractmethod
    def solution(self, data: Any, iteration: int) -> Step:
        """The corrected solution of an evaluation that converged (its Jacobian fresh)."""

    @abstractmethod
    def point(self, step: Step, tangent_p: float) -> Any:
        """The point of a branch at a solution, with its observables and stability."""

    # -- shared by every problem

    @property
    def settings(self) -> ContinuationSettings:
        """The driver's settings for this problem (``default_settings`` unless set)."""
        return self.__dict__.get("_settings") or self.default_settings

    @settings.setter
    def settings(self, value: ContinuationSettings) -> None:
        self.__dict__["_settings"] = value

    @staticmethod
    def tangent(J, previous=None, direction=1.0) -> NDArray[np.float64]:
        """The unit null vector of ``J``, along ``previous`` (or signed by ``direction``)."""
        t = null_vector(J)
        if previous is not None:
            return t if float(t @ previous) >= 0 else -t
        return t if t[-1] * direction >= 0 else -t

    def solve(self, z_pred, extra, column=None, fresh=False) -> Step:
        """Newton's method on ``F = 0`` and ``extra(z) = (value, row)`` from ``z_pred``
        (`beltmdsm.continuation.corrector.newton`); raises NoPeriodicResponse."""
        return newton(self, z_pred, extra, column, fresh)

    @staticmethod
    def arclength(z_pred, tangent):
        """The driver's equation: ``tangent . (z - z_pred) = 0``."""
        return lambda z: (float(tangent @ (z - z_pred)), tangent)

    def accept(self, step: Step, tangent) -> tuple[Any, NDArray[np.float64]]:
        """The point of an accepted step and the unit tangent there (along ``tangent``)."""
        t_new = self.tangent(step.J, tangent)
        new = self.point(step, float(t_new[-1]))
        new.column = step.J[:, -1].copy()
        return new, t_new

    def trial(self, start, tangent, s) -> Any:
        """The corrected point at arclength ``s`` from ``start`` along ``tangent``
        (`beltmdsm.continuation.special`); raises NoPeriodicResponse."""
        z_pred = self.z(start) + s * tangent
        step = self.solve(z_pred, self.arclength(z_pred, tangent), start.column)
        return self.accept(step, tangent)[0]

    # -- hooks for special points and ends (defaults: a smooth problem)

    def period(self, point: Any) -> float:
        """The time over which ``multipliers`` are taken, for a Neimark-Sacker pair's
        frequency [s]."""
        return 1.0

    def check_step(self, prev, step: Step, jumped: bool) -> str | None:
        """Before the range is checked: why ``step`` is refused (None: it is not)."""
        return None

    def check_structure(self, prev, step: Step, ds: float, jumped: bool) -> str | None:
        """After the range is checked: why ``step`` is refused (a switch structure)."""
        return None

    def same_structure(self, prev, new) -> bool:
        """Whether special points between ``prev`` and ``new`` are looked for."""
        return True

    def special_between(self, prev, new, tangent, ds, settings) -> list[SpecialPoint]:
        """The folds and multiplier crossings (`beltmdsm.continuation.special`): a
        problem renames them (a Hopf point) or adds its own."""
        from .special import special_between

        return special_between(self, prev, new, tangent, ds, self.period, s_tol=settings.s_tol)

    def range_specials(self, prev, end, tangent, ds, bound, settings) -> list[SpecialPoint]:
        """The special points between ``prev`` and ``end``, located at ``bound``."""
        return self.special_between(prev, end, tangent, ds, settings)

    def at_bound(self, end, bound) -> tuple[Any, SpecialPoint]:
        """The last point (``end`` polished onto ``bound``) and the special point range."""
        return end, range_end(end, bound)

    def crossing(self, prev, new, stretch) -> SpecialPoint | None:
        """A special point where ``new`` lies on another structure (a grazing)."""
        return None

    def rescue(self, points, prev, tangent, ds):
        """After a failed step: ``(special, new points, tangent)`` across a kink (stick
        onset), or None."""
        return None

    def give_up(self, stretch, failure: str, stage: str) -> tuple[SpecialPoint, list]:
        """The end where no step converges (``stage``: "step", "range" or "special"):
        the special point and points to append."""
        return failed(stretch[-1], failure), []

    def stop(self, new) -> SpecialPoint | None:
        """An end that ``new`` reaches (a limit of the problem), or None."""
        return None

    def near_end(self, stretch) -> SpecialPoint | None:
        """The end that a crawl of small steps approaches, or None."""
        return None
