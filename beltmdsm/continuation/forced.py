"""The forced response as a continuation problem: a fixed point of the ``k``-fold period map.

`BranchPoint` is one response on a branch of `beltmdsm.continuation.branch`;
`ForcedProblem` (`beltmdsm.continuation.problem.Problem`) states the unknowns ``z = (x /
sx, p / sp)``, the residual ``G = (P_p(x) - x) / sx`` and its Jacobian ``[dP/dx - I,
dP/dp]``, and the hooks of its switch structure: a step onto another structure is cut
below `GRAZING_STEP` and passes a **grazing**; where no step converges the branch ends
at a **tangency** or a **grazing** located by `beltmdsm.continuation.edges.locate_end`
(also where a crawl of small steps approaches one), or as ``failed``. The driver
(`beltmdsm.continuation.driver.walk`) does the rest. Moved here from
beltmdsm/continuation/forced.py and branch_walk.py (issue 38).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..integrate.switching import Mode
from ..model import Model
from ..periodic.base import MapImage
from ..periodic.family import MapFamily
from ..periodic.newton import NEWTON_TOL, FixedPoint, fixed_point
from .branch_result import LOCATE_TOL, SpecialPoint
from .edges import NoEdge, locate_end
from .problem import Problem, Residual, Step, range_end

__all__ = ["BranchPoint", "ForcedProblem", "GRAZING_STEP", "CRAWL_MARGIN"]

#: A change of switch structure is accepted as grazing only from steps below this.
GRAZING_STEP = 1e-4
#: A crawl of small steps (`beltmdsm.continuation.settings.ContinuationSettings`) ends
#: the branch where the margin closing there is below this.
CRAWL_MARGIN = 1e-3


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
    model : Model or None
        The model at the point (the branch's parameter at ``value``), from which
        `beltmdsm.branches.continue_branch` continues it.
    periods : int
        ``k``: the response of ``k`` excitation periods.

    See Also
    --------
    beltmdsm.continuation.branch_result.Branch : its ``points``.
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
    model: Model | None = field(default=None, repr=False)
    periods: int = field(default=1, repr=False)

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


class ForcedProblem(Problem):
    """A forced response of ``k`` periods continued in a parameter (module docstring).

    Parameters
    ----------
    family : MapFamily
        The ``k``-fold period map in the parameter.
    lo, hi : float
        The range (``sp`` is a tenth of it).
    sx : float
        The state's scale.
    kT : float
        The orbit's period at the start: the special points' frequencies are against it.

    See Also
    --------
    beltmdsm.continuation.problem.Problem : the contract.
    beltmdsm.continuation.branch.continue_branch : builds and walks it both ways.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> b = branch(Model(beta1=0.3, Vb=5.3), lo=5.3, hi=5.6)
    >>> b.kind, [s.kind for s in b.special]
    ('forced', ['range', 'neimark_sacker', 'range'])
    """

    kind = "forced"

    def __init__(self, family: MapFamily, lo: float, hi: float, sx: float, kT: float = 1.0):
        self.family, self.lo, self.hi, self.kT = family, lo, hi, kT
        self.sx, self.sp = sx, max((hi - lo) / 10.0, 1e-12)

    # -- the unknowns, the equations and the points

    def z(self, point) -> np.ndarray:
        return self.z_of(point.state, point.value)

    def z_of(self, x, value):
        return np.concatenate([np.asarray(x, float) / self.sx, [value / self.sp]])

    def residual(self, z, extra, iteration) -> Residual:
        n = z.size - 1
        x, value = z[:n] * self.sx, z[n] * self.sp
        image = self.family(value)(x)
        G = (image.state - x) / self.sx
        size = float(np.max(np.abs(G)))
        converged = size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x))))
        return Residual(G, size, converged, (x, float(value), image))

    def jacobian(self, data, column=None):
        """``[dG/dz_x, dG/dz_p]`` of ``G / sx`` (n x n+1)."""
        x, value, image = data
        n = x.size
        J = np.empty((n, n + 1))
        J[:, :n] = image.jacobian - np.eye(n)
        if column is None:
            J[:, n] = self.family.derivative(x, value, image.signature) * self.sp / self.sx
        else:
            J[:, n] = column
        return J

    def solution(self, data, iteration) -> Step:
        x, value, _ = data
        return Step(self.z_of(x, value), value, self.jacobian(data), iteration, data)

    def point(self, step, tangent_p) -> BranchPoint:
        x, value, image = step.data
        return self.point_at(x, value, tangent_p, image)

    def point_at(self, x, value, tangent_p, image=None) -> BranchPoint:
        """The point of the response with shooting state ``x`` at ``value``."""
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
        family = self.family
        return BranchPoint(
            float(value), np.array(x, float), mu, biggest, stable, n_rev, n_stick, tangent_p,
            image, model=family(value).model, periods=family.periods,
        )  # fmt: skip

    def start(self, x, value, direction, image):
        """The first point of a walk and its unit tangent (``direction``: of the parameter)."""
        first = self.point_at(x, value, direction, image)
        J = self.jacobian((first.state, first.value, first.image))
        tangent = self.tangent(J, direction=direction)
        first.tangent, first.column = float(tangent[-1]), J[:, -1].copy()
        return first, tangent

    # -- the hooks: the switch structure, its grazings and tangencies

    def period(self, point):
        """``k T`` of the start: the special points' frequencies are against it."""
        return self.kT

    def check_structure(self, prev, step, ds, jumped):
        if step.data[2].signature == prev.image.signature:
            return None
        if ds > GRAZING_STEP:
            return "the switch structure changes"
        return "the corrector jumps to another structure" if jumped else None

    def same_structure(self, prev, new):
        return new.image.signature == prev.image.signature

    def range_specials(self, prev, end, tangent, ds, bound, settings):
        if end.image.signature != prev.image.signature:
            return []
        return self.special_between(prev, end, tangent, ds * 0.999, settings)

    def at_bound(self, end, bound):
        try:  # the response at the bound itself
            at = fixed_point(self.family(bound), end.state)
            end = self.point_at(at.state, bound, end.tangent, at.image)
        except NoPeriodicResponse:
            pass
        return end, range_end(end, bound)

    def crossing(self, prev, new, stretch):
        """A small step onto another structure: the response goes on through a grazing."""
        try:
            end = locate_end(self.family, [(p.value, _fixed(p)) for p in stretch])
            value_g, acc_g = end.value, end.accuracy
        except NoEdge:
            value_g, acc_g = 0.5 * (prev.value + new.value), abs(new.value - prev.value)
        return SpecialPoint(
            "grazing", value_g, acc_g, None, new.multipliers, prev.stable, new.stable,
            "the switch structure changes; the response goes on",
        )  # fmt: skip

    def give_up(self, stretch, failure, stage):
        """The end where the corrector fails: a tangency, a grazing, or failed."""
        last = stretch[-1]
        if len(stretch) >= 2:
            try:
                end = locate_end(self.family, [(p.value, _fixed(p)) for p in stretch])
            except NoEdge as err:
                failure = f"{failure}; {err}"
            else:
                at = SpecialPoint(
                    end.kind, end.value, end.accuracy, None, last.multipliers, last.stable,
                    None, _closing(end.margin),
                )  # fmt: skip
                return at, [self.point_at(p.state, v, last.tangent, p.image) for v, p in end.solved]
        return super().give_up(stretch, failure, stage)

    def near_end(self, stretch):
        """The end that a crawl of small steps approaches, where a margin is about to vanish.

        Close to a tangency or a grazing the corrector converges only from ever smaller
        steps; where the closing margin is below `CRAWL_MARGIN` and
        `beltmdsm.continuation.edges.locate_end` places its zero to `LOCATE_TOL`, the
        branch ends there. None otherwise.
        """
        try:
            end = locate_end(self.family, [(p.value, _fixed(p)) for p in stretch], tol=LOCATE_TOL)
        except NoEdge:
            return None
        if end.margin.value > CRAWL_MARGIN or end.accuracy > LOCATE_TOL:
            return None
        last = stretch[-1]
        return SpecialPoint(
            end.kind, end.value, end.accuracy, None, last.multipliers, last.stable, None,
            _closing(end.margin),
        )  # fmt: skip


def _closing(m) -> str:
    return f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at t = {m.t:.4g} s vanishes"


def _fixed(point):
    return FixedPoint(point.state, point.image, 0.0, 0)


#: The name before issue 38.
_Continuation = ForcedProblem
