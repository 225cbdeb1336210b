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
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..integrate.switching import Mode
from ..model import MODEL_PARAMETERS, Backend, Model, as_model, is_autonomous
from ..periodic.base import MapImage
from ..periodic.family import MapFamily
from ..periodic.newton import NEWTON_TOL, FixedPoint, fixed_point
from ..periodic.response import PeriodicResponse
from ..periodic.shooting import periodic_response
from .branch_parts import LOCATE_TOL, Branch, BranchPart, SpecialPoint
from .edges import NoEdge, locate_end, multiplier_kind

__all__ = [
    "BranchPoint",
    "SpecialPoint",
    "BranchPart",
    "Branch",
    "continue_branch",
    "branch",
    "LOCATE_TOL",
    "GRAZING_STEP",
]

#: Arclength steps (in the scaled coordinates): first, smallest, largest.
STEP_FIRST = 0.02
STEP_MIN = 1e-7
STEP_MAX = 0.25
#: A change of switch structure is accepted as grazing only from steps below this.
GRAZING_STEP = 1e-4
#: Corrector iterations, and the iterations under which the step grows.
_CORRECTOR_ITER = 12
_EASY = 4
#: A crawl: this many steps in a row below `CRAWL_STEP` make the continuation try to
#: locate the end it approaches (`_near_end`), accepted where the closing margin is
#: below `CRAWL_MARGIN`.
CRAWL_STEP = 1e-4
CRAWL_LIMIT = 8
CRAWL_MARGIN = 1e-3
#: Points handed to `beltmdsm.continuation.edges.locate_end` at an end.
_END_POINTS = 400
#: Accepted points per branch at most.
MAX_POINTS = 2000


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


# ---------------------------------------------------------------- the continuation


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

    def z(self, x, value):
        return np.concatenate([np.asarray(x, float) / self.sx, [value / self.sp]])


def _count_outside(point):
    return int(np.sum(np.abs(point.multipliers) > 1.0))


def _critical(point, rank):
    """The multiplier of rank ``rank`` (0: the largest modulus)."""
    mu = point.multipliers[np.argsort(-np.abs(point.multipliers))]
    return mu[min(rank, mu.size - 1)]


def _regula_falsi(cont, start, tangent, ds, psi, fa, fb):
    """The arclength ``s`` in ``[0, ds]`` from ``start`` along ``tangent`` where ``psi`` is zero.

    ``psi(point)`` is evaluated at the corrected point of each trial; ``fa``, ``fb``
    its values at the two ends. Returns the located `BranchPoint` and the accuracy in
    the parameter.
    """
    a, b = 0.0, ds
    pa_value = start.value
    z0 = cont.z(start.state, start.value)
    located, pb_value = start, None
    side = 0
    for _ in range(60):
        s = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        s = min(max(s, a + 1e-3 * (b - a)), b - 1e-3 * (b - a))
        try:
            x, value, image, J, _ = cont.correct(z0 + s * tangent, tangent, start.column)
        except NoPeriodicResponse:
            s = 0.5 * (a + b)
            x, value, image, J, _ = cont.correct(z0 + s * tangent, tangent, start.column)
        t = cont.tangent(J, tangent)
        pt = cont.point(x, value, float(t[-1]), image)
        fs = psi(pt)
        if fs * fa > 0:
            a, fa, pa_value = s, fs, value
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb, pb_value = s, fs, value
            if side == 1:
                fa *= 0.5
            side = 1
        located = pt
        if pb_value is not None and abs(pb_value - pa_value) <= LOCATE_TOL:
            break
        if b - a <= 1e-12:
            break
    accuracy = abs(pb_value - pa_value) if pb_value is not None else math.inf
    return located, accuracy


def _special_between(cont, prev, new, tangent, ds, kT):
    """The special points between two accepted points (same switch structure)."""
    out = []
    if prev.tangent * new.tangent < 0:
        pt, acc = _regula_falsi(
            cont, prev, tangent, ds, lambda q: q.tangent, prev.tangent, new.tangent
        )
        out.append(
            SpecialPoint(
                "fold",
                pt.value,
                acc,
                None,
                pt.multipliers,
                prev.stable,
                new.stable,
                "the branch turns back",
            )
        )
    na, nb = _count_outside(prev), _count_outside(new)
    if na != nb:
        rank = min(na, nb)

        def psi(q, rank=rank):
            return math.log(abs(_critical(q, rank)))

        pt, acc = _regula_falsi(cont, prev, tangent, ds, psi, psi(prev), psi(new))
        kind, frequency = multiplier_kind(_critical(pt, rank), kT)
        if kind == "fold" and out:
            # the multiplier through +1 of the fold located above by the turn
            return out
        if kind == "fold":
            kind = "branch_point"
        detail = (
            f"a complex pair crosses the unit circle at {frequency:.6g} rad/s"
            if kind == "neimark_sacker"
            else "a real multiplier crosses -1"
            if kind == "period_doubling"
            else "a real multiplier crosses +1"
        )
        out.append(
            SpecialPoint(
                kind, pt.value, acc, frequency, pt.multipliers, prev.stable, new.stable, detail
            )
        )
    return sorted(out, key=lambda s: abs(s.value - prev.value))


def _end(cont, points, reason):
    """The end of a branch where the corrector fails: a tangency, a grazing, or failed."""
    last = points[-1]
    if len(points) >= 2:
        try:
            end = locate_end(cont.family, [(p.value, _fixed(p)) for p in points])
            m = end.margin
            detail = (
                f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at "
                f"t = {m.t:.4g} s vanishes"
            )
            return SpecialPoint(
                end.kind, end.value, end.accuracy, None, last.multipliers, last.stable, None, detail
            ), [cont.point(p.state, v, last.tangent, p.image) for v, p in end.solved]
        except NoEdge as err:
            reason = f"{reason}; {err}"
    return SpecialPoint(
        "failed", last.value, 0.0, None, last.multipliers, last.stable, None, reason
    ), []


def _fixed(point):
    return FixedPoint(point.state, point.image, 0.0, 0)


def _walk(cont, first, direction, kT):
    """Continue from ``first`` with the parameter growing (``direction = 1``) or falling."""
    points, special = [first], []
    J = cont.jacobian(first.state, first.value, first.image)
    tangent = cont.tangent(J, direction=direction)
    first.tangent, first.column = float(tangent[-1]), J[:, -1].copy()
    ds = STEP_FIRST
    crawl = 0

    def stretch(last=None):
        """The points since the last special point (at most `_END_POINTS`), up to ``last``.

        An end or a grazing is located from the margins of one stretch of one switch
        structure: across a fold the same margin belongs to another half of the branch.
        """
        stop = len(points) if last is None else points.index(last) + 1
        start = max(stop - _END_POINTS, min(since[-1], stop - 2), 0)
        return points[start:stop]

    since = [0]
    while True:
        prev = points[-1]
        if len(points) >= MAX_POINTS:
            special.append(
                SpecialPoint(
                    "failed",
                    prev.value,
                    0.0,
                    None,
                    prev.multipliers,
                    prev.stable,
                    None,
                    f"stopped after {MAX_POINTS} points",
                )
            )
            return points, special
        z0 = cont.z(prev.state, prev.value)
        try:
            x, value, image, J_new, iterations = cont.correct(
                z0 + ds * tangent, tangent, prev.column
            )
            failure = None
        except NoPeriodicResponse as err:
            failure = str(err)
        if failure is None and not (cont.lo <= value <= cont.hi):
            bound = cont.hi if value > cont.hi else cont.lo
            try:
                end_point, acc = _regula_falsi(
                    cont,
                    prev,
                    tangent,
                    ds,
                    lambda q, b=bound: q.value - b,
                    prev.value - bound,
                    value - bound,
                )
                if end_point.image.signature == prev.image.signature:
                    found = _special_between(cont, prev, end_point, tangent, ds * 0.999, kT)
                else:
                    found = []
            except NoPeriodicResponse as err:
                # a corrector inside the step failed: a shorter step gets closer first
                failure = f"locating the end of the range: {err}"
        if failure is None and not (cont.lo <= value <= cont.hi):
            special += found
            try:  # the response at the bound itself
                at = fixed_point(cont.family(bound), end_point.state)
                end_point = cont.point(at.state, bound, end_point.tangent, at.image)
            except NoPeriodicResponse:
                pass
            points.append(end_point)
            special.append(
                SpecialPoint(
                    "range",
                    bound,
                    0.0,
                    None,
                    end_point.multipliers,
                    end_point.stable,
                    None,
                    "the end of the requested range",
                )
            )
            return points, special
        if failure is None and image.signature != prev.image.signature:
            if ds > GRAZING_STEP:
                failure = "the switch structure changes"
            elif np.max(np.abs(cont.z(x, value) - z0 - ds * tangent)) > 10 * ds:
                failure = "the corrector jumps to another structure"
        if failure is not None:
            ds *= 0.5
            if ds < STEP_MIN:
                end, extra = _end(cont, stretch(), failure)
                points += extra
                special.append(end)
                return points, special
            continue
        t_new = cont.tangent(J_new, tangent)
        new = cont.point(x, value, float(t_new[-1]), image)
        new.column = J_new[:, -1].copy()
        found = []
        if image.signature == prev.image.signature:
            try:
                found = _special_between(cont, prev, new, tangent, ds, kT)
            except NoPeriodicResponse:
                # a corrector inside the step failed while locating a special point: a
                # shorter step brackets it more closely
                ds *= 0.5
                if ds < STEP_MIN:
                    end, extra = _end(cont, stretch(), "a special point cannot be located")
                    points += extra
                    special.append(end)
                    return points, special
                continue
        if image.signature != prev.image.signature:
            # a small step onto another structure: the response goes on through a grazing
            try:
                end = locate_end(cont.family, [(p.value, _fixed(p)) for p in stretch(prev)])
                value_g, acc_g = end.value, end.accuracy
            except NoEdge:
                value_g, acc_g = 0.5 * (prev.value + new.value), abs(new.value - prev.value)
            special.append(
                SpecialPoint(
                    "grazing",
                    value_g,
                    acc_g,
                    None,
                    new.multipliers,
                    prev.stable,
                    new.stable,
                    "the switch structure changes; the response goes on",
                )
            )
            since.append(len(points))
        else:
            special += found
            if found:
                since.append(len(points))
        points.append(new)
        tangent = t_new
        if iterations <= _EASY:
            ds = min(ds * 1.5, STEP_MAX)
        crawl = crawl + 1 if ds < CRAWL_STEP else 0
        if crawl >= CRAWL_LIMIT:
            crawl = -3 * CRAWL_LIMIT  # the next try after as many steps again
            end = _near_end(cont, stretch())
            if end is not None:
                special.append(end)
                return points, special


def _near_end(cont, points):
    """The end that a crawl of small steps approaches, where a margin is about to vanish.

    Close to a tangency or a grazing the corrector converges only from ever smaller
    steps; where the closing margin is below `CRAWL_MARGIN` and
    `beltmdsm.continuation.edges.locate_end` places its zero to `LOCATE_TOL`, the branch
    ends there. None otherwise.
    """
    try:
        end = locate_end(cont.family, [(p.value, _fixed(p)) for p in points], tol=LOCATE_TOL)
    except NoEdge:
        return None
    if end.margin.value > CRAWL_MARGIN or end.accuracy > LOCATE_TOL:
        return None
    last = points[-1]
    m = end.margin
    return SpecialPoint(
        end.kind,
        end.value,
        end.accuracy,
        None,
        last.multipliers,
        last.stable,
        None,
        f"the {m.kind} margin of {m.surface} ({m.mode.name.lower()}) at t = {m.t:.4g} s vanishes",
    )


def continue_branch(
    start: PeriodicResponse,
    param: str,
    lo: float,
    hi: float,
    *,
    backend: Backend | None = None,
) -> Branch:
    """The branch through a response in ``param`` over ``[lo, hi]``, both ways from the start.

    Parameters
    ----------
    start : PeriodicResponse
        A response (`beltmdsm.periodic.shooting.periodic_response`, ``periods=k`` for a
        locked one).
    param : str
        A model parameter.
    lo, hi : float
        The range; the start's value must lie in it.
    backend : {"python", "numba", None}

    Returns
    -------
    Branch

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range or a start outside it.
    """
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    model = start.model
    if getattr(start, "autonomous", False):
        from ..cycles.branch import cycle_branch_from

        return cycle_branch_from(start.cycle, param, lo, hi, backend=backend)
    v0 = float(model[param])
    if not lo <= v0 <= hi:
        raise ValueError(f"the start's {param} = {v0:g} is outside [{lo:g}, {hi:g}]")
    family = MapFamily(model, param, start.periods, backend)
    x0 = np.asarray(start.shooting_state, dtype=float)
    cont = _Continuation(family, float(lo), float(hi), 1.0 + float(np.max(np.abs(x0))))
    image = family(v0)(x0)
    kT = start.periods * family(v0).period
    walks = []
    for direction in (1.0, -1.0):
        first = cont.point(x0, v0, direction, image)
        bound = hi if direction > 0 else lo
        if v0 == bound:  # a start on a bound ends there that way
            end = SpecialPoint(
                "range",
                v0,
                0.0,
                None,
                first.multipliers,
                first.stable,
                None,
                "the end of the requested range",
            )
            walks.append(([first], [end]))
        else:
            walks.append(_walk(cont, first, direction, kT))
    (up, up_special), (down, down_special) = walks
    points = list(reversed(down[1:])) + up
    special = list(reversed(down_special)) + up_special
    # along the arclength from the lower end: 'before' and 'after' of the reversed half swap
    for s in reversed(down_special):
        s.stable_before, s.stable_after = s.stable_after, s.stable_before
    return Branch(param, start.periods, model, points, special)


def branch(
    model: Model | Mapping[str, Any] | None = None,
    *,
    periods: int = 1,
    param: str = "Vb",
    lo: float,
    hi: float,
    backend: Backend | None = None,
    **kw: Any,
) -> Branch:
    """The branch of the response of ``periods`` periods at a point (`continue_branch`).

    The response is found as `beltmdsm.periodic.shooting.periodic_response` finds it
    (``periods > 1``: seeded from the attractor of the period map). Without excitation
    (`beltmdsm.model.is_autonomous`) it is the branch of self-excited cycles born at
    the Hopf point of steady sliding in ``[lo, hi]``
    (`beltmdsm.cycles.branch.cycle_branch`: a `CycleBranch`).

    Parameters
    ----------
    model : Model or dict, optional
        The model at the start (default: the base set); ``**kw``: parameters and options.
    periods : int
    param : str
    lo, hi : float
    backend : {"python", "numba", None}

    Returns
    -------
    Branch

    Raises
    ------
    ValueError
        For bad parameters or range.
    NoPeriodicResponse
        Where no response of ``periods`` periods is found at the point.
    """
    model = as_model(model, **kw)
    if is_autonomous(model):
        from ..cycles.branch import cycle_branch

        if periods != 1:
            raise ValueError(
                f"periods must be 1 without excitation (a self-excited cycle has no "
                f"excitation period to count); got {periods!r}"
            )
        return cycle_branch(model, param=param, lo=lo, hi=hi, backend=backend)
    start = periodic_response(model, periods=periods, backend=backend)
    return continue_branch(start, param, lo, hi, backend=backend)
