"""Pseudo-arclength continuation on the ``k``-fold period map: a branch's point and corrector.

`BranchPoint` is one response on a branch of `beltmdsm.continuation.branch`;
`_Continuation` evaluates points, the Jacobian ``[dP/dx - I, dP/dp]``, its unit null
vector (the tangent) and the corrector (Newton's method on ``G = 0`` and the hyperplane
normal to the tangent) in coordinates scaled by the state's and the range's size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..integrate.switching import Mode
from ..periodic.base import MapImage
from ..periodic.family import MapFamily
from ..periodic.newton import NEWTON_TOL

__all__ = ["BranchPoint"]

#: Corrector iterations.
_CORRECTOR_ITER = 12


@dataclass
class BranchPoint:
    """One response on a branch.

    Attributes
    ----------
    value : float
        The parameter value.
    state : ndarray (n,)
        The shooting state at phase 0.
    multipliers : ndarray
        Those of the shooting state's monodromy, then the fixed ones (the normal
        block's).
    max_abs_multiplier : float
    stable : bool or None
        None where the orbit grazes (`beltmdsm.periodic.margins.GRAZING_RATIO`).
    n_reversals, n_sticks : int
        Per orbit (``k`` periods).
    tangent : float
        The parameter component of the unit tangent (scaled coordinates), in the
        direction of continuation.
    image : MapImage
        The period map's image of ``state``: the runs of the orbit, its Jacobian.
    recorded : dict of str to float
        What the ``record`` callable of `beltmdsm.continuation.branch.branch` returned
        here (empty without one).

    See Also
    --------
    beltmdsm.continuation.branch_parts.Branch : its ``points``.
    beltmdsm.cycles.continuation.CyclePoint : a point of a branch of cycles.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> p = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6).points[0]
    >>> p.value, p.stable, p.n_reversals, p.n_sticks, p.state.shape
    (5.3, True, 2, 0, (2,))
    >>> sorted(p.observables(5.3))[:3]
    ["X1'_amplitude", "X1'_max", "X1'_min"]
    """

    value: float
    state: NDArray[np.float64]
    multipliers: NDArray[np.complex128]
    max_abs_multiplier: float
    stable: bool | None
    n_reversals: int
    n_sticks: int
    tangent: float
    image: MapImage = field(repr=False)
    column: NDArray[np.float64] | None = field(default=None, repr=False)
    recorded: dict[str, float] = field(default_factory=dict, repr=False)

    def observables(self, vb: float) -> dict[str, float]:
        """The `beltmdsm.periodic.observables.OBSERVABLES` of the orbit at belt speed
        ``vb`` [m/s], read from the runs of ``image`` (nothing is solved again)."""
        from ..periodic.observables import observables

        return observables(self.image, vb)

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``state0``, ``multipliers`` (pairs of real and imaginary
        parts), ``max_abs_multiplier``, ``stable``, ``n_reversals``, ``n_sticks``."""
        return {
            "value": self.value,
            "state0": [float(v) for v in self.state],
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "max_abs_multiplier": self.max_abs_multiplier,
            "stable": self.stable,
            "n_reversals": self.n_reversals,
            "n_sticks": self.n_sticks,
        }


class _Continuation:
    """Pseudo-arclength continuation of one branch in scaled coordinates ``z = (x/sx, p/sp)``."""

    def __init__(self, family: MapFamily, lo: float, hi: float, sx: float):
        self.family, self.lo, self.hi = family, lo, hi
        self.sx, self.sp = sx, max((hi - lo) / 10.0, 1e-12)

    # -- evaluation

    def point(self, x, value, tangent_p, image=None) -> BranchPoint:
        image = image if image is not None else self.family(value)(x)
        fixed = self.family(value).fixed_multipliers()
        mu_x = np.linalg.eigvals(image.jacobian)
        mu = np.concatenate([mu_x, fixed])
        biggest = float(np.max(np.abs(mu)))
        n_rev = sum(
            1
            for _, b, a, s in image.switches
            if s == "relative_velocity" and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD}
        )
        n_stick = sum(1 for _, _, a, _ in image.switches if a == Mode.STICK)
        stable = None if image.grazing is not None else bool(biggest < 1.0)
        return BranchPoint(
            float(value), np.array(x, float), mu, biggest, stable, n_rev, n_stick, tangent_p, image
        )

    def jacobian(self, x, value, image):
        """``[dG/dz_x, dG/dz_p]`` of ``G / sx`` (n x n+1)."""
        n = x.size
        J = np.empty((n, n + 1))
        J[:, :n] = image.jacobian - np.eye(n)
        J[:, n] = self.family.derivative(x, value, image.signature) * self.sp / self.sx
        return J

    def tangent(self, J, previous=None, direction=1.0):
        """The unit null vector of ``J``, along ``previous`` (or with the sign of ``direction``)."""
        t = np.linalg.svd(J)[2][-1]
        if previous is not None:
            return t if float(t @ previous) >= 0 else -t
        return t if t[-1] * direction >= 0 else -t

    def correct(self, z_pred, tangent, column=None):
        """Newton's method on ``G = 0`` and ``tangent . (z - z_pred) = 0``.

        ``column``: the parameter column of the Jacobian at a nearby point (kept through
        the iterations; computed at the first iterate where not given; the state block
        is exact at every iterate). Returns ``(x, value, image, J, iterations)`` with
        ``J`` exact at the result; raises NoPeriodicResponse.
        """
        z = z_pred.copy()
        n = z.size - 1
        J = None
        if column is not None:
            J = np.empty((n, n + 1))
            J[:, n] = column
        last = math.inf
        for iteration in range(1, _CORRECTOR_ITER + 1):
            x, value = z[:n] * self.sx, z[n] * self.sp
            image = self.family(value)(x)
            G = (image.state - x) / self.sx
            size = float(np.max(np.abs(G)))
            if size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x)))):
                return x, float(value), image, self.jacobian(x, value, image), iteration
            if size >= last:
                raise NoPeriodicResponse(f"the corrector diverges (residual {size:.2e})")
            last = size
            if J is None:
                J = self.jacobian(x, value, image)
            else:
                J[:, :n] = image.jacobian - np.eye(n)
            A = np.vstack([J, tangent])
            b = -np.concatenate([G, [float(tangent @ (z - z_pred))]])
            try:
                z = z + np.linalg.solve(A, b)
            except np.linalg.LinAlgError:
                raise NoPeriodicResponse("the corrector's matrix is singular") from None
        raise NoPeriodicResponse(f"the corrector leaves a residual {last:.2e}")

    def trial(self, start, tangent, s) -> BranchPoint:
        """The corrected point at arclength ``s`` from ``start`` along ``tangent``
        (`beltmdsm.continuation.special`); raises NoPeriodicResponse."""
        z0 = self.z(start.state, start.value)
        x, value, image, J, _ = self.correct(z0 + s * tangent, tangent, start.column)
        t = self.tangent(J, tangent)
        return self.point(x, value, float(t[-1]), image)

    def z(self, x, value):
        return np.concatenate([np.asarray(x, float) / self.sx, [value / self.sp]])
