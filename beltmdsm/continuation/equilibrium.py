"""Steady sliding as a continuation problem: the equilibrium branch and its Hopf points.

A problem added by implementing `beltmdsm.continuation.problem.Problem` alone (issue
38): the unknowns are the equilibrium state ``x``, the residual ``F = (x - x_eq(p)) /
sx`` (steady sliding is derived in closed form: `beltmdsm.generated.unforced`
for the paper's model, `beltmdsm.oscillator.equilibria.steady_sliding` for any derived
model), its Jacobian ``[I, -dx_eq/dp]`` (central differences in ``p``). A point's
multipliers are ``exp(lambda)`` of the eigenvalues ``lambda`` of the Jacobian there, so
that the driver's special-point hook (a multiplier pair through the unit circle) sees a
complex pair of eigenvalues cross the imaginary axis: `EquilibriumProblem` names it a
**Hopf** point, its frequency the pair's imaginary part, located by the driver's regula
falsi to `beltmdsm.continuation.branch_result.LOCATE_TOL` in the parameter.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..model import MODEL_PARAMETERS, Model
from .branch_result import Branch, SpecialPoint
from .driver import join, walk
from .problem import Problem, Residual, Step, range_end
from .settings import ContinuationSettings, as_settings

__all__ = ["EquilibriumPoint", "EquilibriumProblem", "equilibrium_branch"]


@dataclass
class EquilibriumPoint:
    """Steady sliding at one parameter value.

    Attributes
    ----------
    value : float
    state : ndarray (n,)
    eigenvalues : ndarray (n,) complex
        Of the Jacobian there, largest real part first.
    multipliers : ndarray (n,) complex
        ``exp(eigenvalues)``: what the driver's special points watch.
    stable : bool
    tangent : float
        The parameter component of the unit tangent.

    See Also
    --------
    beltmdsm.continuation.equilibrium.equilibrium_branch : a branch of them.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> b = equilibrium_branch(Model(friction="stribeck", alpha=0.0, Vb=1.5), lo=1.4, hi=1.6)
    >>> p = b.points[0]
    >>> p.value, p.stable, p.state.shape, round(p.observables(p.value)["growth_rate"], 4)
    (1.4, False, (4,), 0.0814)
    """

    value: float
    state: NDArray[np.float64]
    eigenvalues: NDArray[np.complex128] = field(repr=False)
    multipliers: NDArray[np.complex128] = field(repr=False)
    stable: bool
    tangent: float
    column: NDArray[np.float64] | None = field(default=None, repr=False)
    recorded: dict[str, float] = field(default_factory=dict, repr=False)

    @property
    def max_abs_multiplier(self) -> float:
        return float(np.max(np.abs(self.multipliers)))

    def observables(self, vb: float) -> dict[str, float]:
        """The largest real part of the eigenvalues (``growth_rate``, 1/s)."""
        return {"growth_rate": float(self.eigenvalues.real.max())}


class EquilibriumProblem(Problem):
    """Steady sliding in one parameter over ``[lo, hi]`` (module docstring).

    Parameters
    ----------
    at : callable
        ``at(p) -> (state, eigenvalues)``: steady sliding at ``p`` and its eigenvalues.
    lo, hi : float
        The range.
    sx : float
        The state's scale.

    See Also
    --------
    beltmdsm.continuation.equilibrium.equilibrium_branch : builds and walks it.
    beltmdsm.continuation.problem.Problem : the contract.

    Examples
    --------
    >>> import numpy as np
    >>> line = EquilibriumProblem(lambda p: (np.array([p]), np.array([p - 1.0])), 0.0, 2.0, 1.0)
    >>> points, special = walk(line, *line.start(0.5, 1.0))
    >>> [(s.kind, round(s.value, 6)) for s in special]
    [('branch_point', 1.0), ('range', 2.0)]
    """

    kind = "equilibrium"

    def __init__(self, at: Callable[[float], tuple], lo: float, hi: float, sx: float):
        self.at, self.lo, self.hi, self.sx = at, float(lo), float(hi), float(sx)
        self.sp = max((self.hi - self.lo) / 10.0, 1e-12)

    def start(self, p: float, direction: float):
        """The first point at ``p`` and its tangent (``direction``: of ``p``)."""
        x, _ = self.at(p)
        step = self.solution((np.asarray(x, float), float(p)), 0)
        t = self.tangent(step.J, direction=direction)
        first = self.point(step, float(t[-1]))
        first.column = step.J[:, -1].copy()
        return first, t

    def z(self, point):
        return np.append(point.state / self.sx, point.value / self.sp)

    def residual(self, z, extra, iteration):
        x, p = z[:-1] * self.sx, float(z[-1] * self.sp)
        F = (x - np.asarray(self.at(p)[0], float)) / self.sx
        size = float(np.max(np.abs(F)))
        converged = size <= 1e-13 and abs(extra) <= 1e-13
        return Residual(F, size, converged, (x, p))

    def jacobian(self, data, column=None):
        x, p = data
        n = x.size
        J = np.empty((n, n + 1))
        J[:, :n] = np.eye(n)
        if column is None:
            h = 1e-6 * max(1.0, abs(p))
            dx = (np.asarray(self.at(p + h)[0]) - np.asarray(self.at(p - h)[0])) / (2 * h)
            column = -dx * self.sp / self.sx
        J[:, n] = column
        return J

    def solution(self, data, iteration):
        x, p = data
        z = np.append(x / self.sx, p / self.sp)
        return Step(z, p, self.jacobian(data), iteration, data)

    def point(self, step, tangent_p):
        x, p = step.data
        lam = np.asarray(self.at(p)[1], dtype=complex)
        lam = lam[np.argsort(-lam.real, kind="stable")]
        stable = bool(lam.real.max() < 0)
        return EquilibriumPoint(p, np.array(x, float), lam, np.exp(lam), stable, tangent_p)

    def special_between(self, prev, new, tangent, ds, settings):
        """The driver's crossings, a complex pair's named a Hopf point."""
        out = []
        for s in super().special_between(prev, new, tangent, ds, settings):
            if s.kind == "neimark_sacker":
                at = self.point(self.solution(self._at(s.value), 0), 0.0)
                pair = at.eigenvalues[np.argmin(np.abs(at.eigenvalues.real))]
                omega = abs(float(pair.imag))
                s = SpecialPoint(
                    "hopf", s.value, s.accuracy, omega, at.multipliers, s.stable_before,
                    s.stable_after,
                    f"a complex pair of eigenvalues crosses the imaginary axis at {omega:.6g} "
                    "rad/s",
                )  # fmt: skip
            out.append(s)
        return out

    def at_bound(self, end, bound):
        """Steady sliding at the bound itself (it is explicit: nothing to solve)."""
        last = self.point(self.solution(self._at(bound), 0), end.tangent)
        return last, range_end(last, bound)

    def _at(self, p):
        return np.asarray(self.at(p)[0], float), float(p)


def _steady_sliding(model: Any, param: str) -> Callable[[float], tuple]:
    """``at(p)`` for the paper's `Model` (generated closed forms) or a derived `System`."""
    if isinstance(model, Model):
        from beltmdsm.generated import unforced

        def at(p):
            m = model.replace(**{param: p})
            x = np.asarray(unforced.equilibrium(**m.arguments(unforced.equilibrium)), float)
            lam = np.asarray(unforced.eigenvalues(**m.arguments(unforced.eigenvalues)))
            return x.reshape(-1), lam.reshape(-1)

        return at
    from ..oscillator.equilibria import steady_sliding

    def at_system(p):
        eq = steady_sliding(model.replace(**{param: p}))
        return eq.state, eq.eigenvalues

    return at_system


def equilibrium_branch(
    model: Any,
    *,
    param: str = "Vb",
    lo: float,
    hi: float,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch of steady sliding in ``param`` over ``[lo, hi]``, its Hopf points located.

    Parameters
    ----------
    model : Model or beltmdsm.oscillator.system.System
        The paper's model (steady sliding from `beltmdsm.generated.unforced`) or any
        derived model (`beltmdsm.oscillator.equilibria.steady_sliding`); its value of
        ``param`` is the start, both ways.
    param : str
        The parameter continued.
    lo, hi : float
        The range, holding the model's value.
    settings : ContinuationSettings, optional
        The driver's; default `beltmdsm.continuation.settings.FORCED_SETTINGS`.

    Returns
    -------
    Branch
        Of ``kind = "equilibrium"``: `EquilibriumPoint` points, ``hopf`` special points
        where a complex pair of eigenvalues crosses the imaginary axis.

    Raises
    ------
    ValueError
        For an unknown parameter or a range that does not hold the model's value.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_point : the paper's Hopf point by a scan and Brent's method.
    beltmdsm.oscillator.equilibria.hopf_points : a derived model's, from its Hurwitz
        determinants.

    Examples
    --------
    Stribeck friction: steady sliding turns stable at ``Vb = 1.9957`` as the belt speeds up
    (`beltmdsm.cycles.hopf.hopf_point` finds the same point):

    >>> from beltmdsm import Model
    >>> b = equilibrium_branch(Model(friction="stribeck", alpha=0.0, Vb=1.5), lo=1.0, hi=3.0)
    >>> [(s.kind, round(s.value, 4)) for s in b.special]
    [('range', 1.0), ('hopf', 1.9957), ('range', 3.0)]
    >>> b.kind, b.stable_ranges()  # doctest: +ELLIPSIS
    ('equilibrium', [[1.9957..., 3.0]])
    """
    if isinstance(model, Model) and param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    settings = as_settings(settings, EquilibriumProblem.default_settings)
    p0 = float(model[param]) if isinstance(model, Model) else float(model.params[param])
    if not (np.isfinite(lo) and np.isfinite(hi) and lo <= p0 <= hi and lo < hi):
        raise ValueError(f"the model's {param} = {p0:g} must lie in [{lo:g}, {hi:g}]")
    at = _steady_sliding(model, param)
    x0 = np.asarray(at(p0)[0], float)
    problem = EquilibriumProblem(at, lo, hi, 1.0 + float(np.max(np.abs(x0))))
    problem.settings = settings
    walks = []
    for direction, bound in ((1.0, hi), (-1.0, lo)):
        first, tangent = problem.start(p0, direction)
        done = p0 == bound  # a start on a bound ends there that way
        walks.append(([first], [range_end(first, p0)]) if done else walk(problem, first, tangent))
    points, special = join(*walks)
    return Branch(param, 1, model, points, special, kind="equilibrium")
