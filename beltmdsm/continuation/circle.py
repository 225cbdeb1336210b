"""The smallest continuation problem: the unit circle ``u^2 + p^2 = 1``.

It shows what `beltmdsm.continuation.problem.Problem` asks of a problem and no more:
its unknown ``u``, its residual ``F = u^2 + p^2 - 1`` and Jacobian, its points; the
driver (`beltmdsm.continuation.driver.walk`) continues it through its folds at
``p = +-1``. Its "multiplier" is ``exp(dF/du) = exp(2 u)``: the branch is stable where
``u < 0``, as the flow ``u' = -F`` makes it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .problem import Problem, Residual, Step

__all__ = ["Circle", "CirclePoint"]


@dataclass
class CirclePoint:
    """A point of the circle: ``u`` at the parameter ``value``.

    See Also
    --------
    beltmdsm.continuation.circle.Circle : the problem.

    Examples
    --------
    >>> first, _ = Circle(-1.0, 1.0).start(0.6)
    >>> round(first.u, 12), first.value, first.stable
    (0.8, 0.6, False)
    """

    value: float
    u: float
    tangent: float
    multipliers: np.ndarray = field(repr=False)
    stable: bool = True
    column: np.ndarray | None = field(default=None, repr=False)


class Circle(Problem):
    """The unit circle ``u^2 + p^2 = 1`` over ``p`` in ``[lo, hi]`` (module docstring).

    Parameters
    ----------
    lo, hi : float
        The range of ``p``.

    See Also
    --------
    beltmdsm.continuation.problem.Problem : the contract it fills in.
    beltmdsm.continuation.equilibrium.EquilibriumProblem : a physical one.

    Examples
    --------
    From ``(u, p) = (1, 0)`` both ways: the driver passes the folds at ``p = 1`` and
    ``p = -1`` and ends at the range's bounds on the other half:

    >>> from beltmdsm.continuation.driver import join, walk
    >>> circle = Circle(-0.5, 1.5)
    >>> up = walk(circle, *circle.start(0.0, direction=1.0))
    >>> [(s.kind, round(s.value, 9)) for s in up[1]]
    [('fold', 1.0), ('range', -0.5)]
    """

    kind = "circle"

    def __init__(self, lo: float, hi: float):
        self.lo, self.hi, self.sp = float(lo), float(hi), 1.0

    def start(self, p: float, direction: float = -1.0):
        """The point on the upper half at ``p`` and its tangent (``direction``: of ``p``)."""
        u = float(np.sqrt(1.0 - p * p))
        step = self.solution(np.array([u, p]), 0)
        t = self.tangent(step.J, direction=direction)
        first = self.point(step, float(t[-1]))
        first.column = step.J[:, -1].copy()
        return first, t

    def z(self, point):
        return np.array([point.u, point.value])

    def residual(self, z, extra, iteration):
        F = np.array([z[0] ** 2 + z[1] ** 2 - 1.0])
        size = float(np.max(np.abs(F)))
        return Residual(F, size, size <= 1e-14 and abs(extra) <= 1e-14, z.copy())

    def jacobian(self, data, column=None):
        return np.array([[2.0 * data[0], 2.0 * data[1] if column is None else column[0]]])

    def solution(self, data, iteration):
        return Step(data.copy(), float(data[1]), self.jacobian(data), iteration, data)

    def point(self, step: Step, tangent_p: float) -> CirclePoint:
        mu = np.array([np.exp(2.0 * step.z[0])])
        return CirclePoint(step.value, float(step.z[0]), tangent_p, mu, bool(step.z[0] < 0))
