"""Branches of self-excited cycles, born at the Hopf point of steady sliding.

Without excitation a cycle is a zero of ``phi_T(x; p) - x`` closed by a phase condition
``h(x) = 0`` (`beltmdsm.periodic.cycle_flow`: the section through the smallest
``X1'``); its period ``T`` is an unknown. `cycle_branch` follows the curve of zeros in
``(x, T, p)`` by pseudo-arclength continuation, as `beltmdsm.continuation.branch` does
for forced responses (the same steps, special points and parts), in coordinates
scaled by the state's, the period's and the range's size:

* **Birth.** At the Hopf point ``p_H`` (`beltmdsm.cycles.hopf.hopf_point`) the cycle
  has zero amplitude. `hopf_cycle` solves the cycle of a small amplitude ``A`` of
  ``X1'`` (the arclength equation replaced by ``x_k - x_eq,k(p) = -A``) from the
  first-order cycle ``x_eq + (A / |v_k|) Re(v e^{i theta})``, ``T = 2 pi / omega_H``,
  with ``p`` free: Newton's method finds the side on which the cycle exists, and the
  branch starts there (label ``hopf``). **Criticality** follows from that side:
  ``supercritical`` where the cycles exist where steady sliding is unstable,
  ``subcritical`` where it is stable (hysteresis: both coexist with the cycle).
* **Stick onset** (``stick_onset``): the largest ``Vr = X1' - Vb`` of the cycle reaches
  0 (grazing-sliding, in Filippov's terms). Cycles of one side solved at safe
  distances are extrapolated to it (``max_relative_velocity`` on the sliding side,
  the stick time squared on the other) to `LOCATE_TOL` / 10, and the branch goes on
  on the other side, also where it turns back there (a nonsmooth fold: Stribeck's
  law), `beltmdsm.cycles.continuation`.
* **Folds** (a sign change of the tangent's ``p``-component) and the multipliers
  (without the trivial one) through the unit circle: ``period_doubling`` (-1),
  ``neimark_sacker`` (a complex pair), ``branch_point`` (+1 without a turn), located by
  regula falsi along the arclength to `LOCATE_TOL` (between points of the same switch
  structure; at a stick onset the multipliers jump, the point says whether the
  stability changes).
* **Ends**: the range's bounds (``range``), or ``failed`` with the reason (no corrector
  converges even at the smallest step; the period grows past `PERIOD_LIMIT` times the
  Hopf period, as towards a homoclinic orbit; a segment of multiple shooting
  amplifies by more than `beltmdsm.cycles.continuation.MULTIPLIER_LIMIT`). Where the
  largest multiplier passes that limit the walk goes on by multiple shooting
  (`beltmdsm.cycles.multiple`), and back to single shooting below a tenth of it. A branch
  that shrinks back to a second Hopf point is not recognised as such: it ends
  ``failed`` where the corrector no longer converges near zero amplitude.

Without a Hopf point in the range, the branch goes both ways through the cycle found
at the model's value of the parameter (`beltmdsm.periodic.cycle.cycle`).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..continuation.branch_result import Branch, SpecialPoint
from ..continuation.driver import join
from ..continuation.settings import ContinuationSettings, as_settings
from ..errors import NoPeriodicResponse
from ..excitation import is_autonomous
from ..model import MODEL_PARAMETERS, Backend, Model
from ..periodic.cycle import Cycle, cycle
from ..periodic.cycle_flow import CycleFlow
from .continuation import PERIOD_LIMIT, Continuation, CyclePoint
from .hopf import HopfPoint, NoHopfPoint, hopf_point
from .multiple import walk

__all__ = [
    "CyclePoint",
    "CycleBranch",
    "cycle_branch",
    "cycle_branch_from",
    "hopf_cycle",
    "HOPF_AMPLITUDE",
    "PERIOD_LIMIT",
]

#: The first cycle of a branch from a Hopf point: amplitude of ``X1'`` over the
#: state's scale (`_scale`).
HOPF_AMPLITUDE = 2e-3


def _scale(state) -> float:
    """The scale of the state: ``1 + max |x|``."""
    return 1.0 + float(np.max(np.abs(state)))


class _KindOfBranch(type):
    """``isinstance(b, CycleBranch)``: a `Branch` of kind ``"cycle"``."""

    def __instancecheck__(cls, obj) -> bool:
        return isinstance(obj, Branch) and obj.kind == "cycle"

    def __call__(cls, *args, **kwargs) -> Branch:
        return Branch(*args, **kwargs, kind="cycle")


class CycleBranch(metaclass=_KindOfBranch):
    """Moved (issue 38): a branch of self-excited cycles is a
    `beltmdsm.continuation.branch_result.Branch` of ``kind = "cycle"``.

    ``CycleBranch(...)`` builds that `Branch` (the arguments in the order they had:
    ``param, periods, model, points, special, hopf, criticality, wall_s``), and
    ``isinstance(b, CycleBranch)`` asks ``b.kind == "cycle"``.

    See Also
    --------
    beltmdsm.continuation.branch_result.Branch : The one branch type.
    beltmdsm.cycles.branch.cycle_branch : Computes it.

    Examples
    --------
    Stribeck friction: the cycles born at ``Vb = 1.9957`` exist above it, where steady
    sliding is stable (subcritical), and they are unstable there:

    >>> from beltmdsm.model import Model
    >>> branch = cycle_branch(Model(friction="stribeck", alpha=0.0), lo=1.9, hi=2.1)
    >>> branch  # doctest: +ELLIPSIS
    CycleBranch(Vb: hopf 1.99572, subcritical -> range 2.1, ... points, 0 special points inside)
    >>> round(branch.hopf.value, 4), any(point.stable for point in branch.points)
    (1.9957, False)
    >>> type(branch).__name__, branch.kind, isinstance(branch, CycleBranch)
    ('Branch', 'cycle', True)
    """


def hopf_cycle(hopf: HopfPoint, amplitude: float, *, backend: Backend | None = None) -> CyclePoint:
    """The cycle of amplitude ``amplitude`` of ``X1'`` (coordinate ``k``) near a Hopf point.

    Newton's method on the cycle's equations and ``x_k - x_eq,k(p) = -amplitude``, the
    parameter free, from the first-order cycle (module docstring).

    Parameters
    ----------
    hopf : HopfPoint
        The Hopf point.
    amplitude : float
        How far ``x_k`` on the section lies below steady sliding's.
    backend : {"python", "numba", None}
        The kernels; None: numba if installed.

    Returns
    -------
    CyclePoint
        The cycle, at the parameter value Newton's method finds.

    Raises
    ------
    NoPeriodicResponse
        Where Newton's method does not converge.

    See Also
    --------
    beltmdsm.cycles.hopf.hopf_point : The Hopf point.

    Examples
    --------
    A small cycle near the Stribeck Hopf point has the crossing's period
    ``2 pi / omega_H = 2 pi``, and lies above ``Vb = 1.9957`` (subcritical):

    >>> from beltmdsm.cycles.hopf import hopf_point
    >>> from beltmdsm.model import Model
    >>> hopf = hopf_point(Model(friction="stribeck", alpha=0.0), "Vb", 0.5, 5.0)
    >>> small = hopf_cycle(hopf, 0.01)
    >>> round(small.period, 4), round(small.amplitude, 6), small.value > hopf.value
    (6.2832, 0.01, True)
    """
    cont, z = _hopf_start(hopf, float(amplitude), backend)
    x, T, p, img, J, _ = cont.correct(z, _amplitude_row(cont, hopf, amplitude))
    t = cont.tangent(J, sign=-1.0 if cont.tangent(J)[cont.flow.k] > 0 else 1.0)
    return cont.point(x, T, p, img, t[-1], J)


def _coordinate(hopf: HopfPoint) -> int:
    """The coordinate of the section: ``X1'`` unless the pair barely moves it (``X2'``)."""
    v = np.abs(hopf.eigenvector)
    return 1 if v[1] >= 0.1 * v.max() else 3


def _hopf_start(hopf, amplitude, backend, lo=None, hi=None):
    k = _coordinate(hopf)
    flow = CycleFlow(hopf.model, hopf.param, k, backend)
    v = hopf.eigenvector
    theta = math.pi - float(np.angle(v[k]))  # x_k smallest: on the section
    x0 = hopf.equilibrium + (amplitude / abs(v[k])) * np.real(v * np.exp(1j * theta))
    lo = hopf.value - 1.0 if lo is None else lo
    hi = hopf.value + 1.0 if hi is None else hi
    cont = Continuation(flow, lo, hi, _scale(hopf.equilibrium), hopf.period, x0, hopf.value)
    return cont, np.concatenate([x0 / cont.sx, [hopf.period / cont.sT, hopf.value / cont.sp]])


def _equilibrium_k(hopf, p):
    from beltmdsm.generated import unforced

    model = hopf.model.replace(**{hopf.param: p})
    return float(unforced.equilibrium(**model.arguments(unforced.equilibrium))[_coordinate(hopf)])


def _amplitude_row(cont, hopf, amplitude):
    k = cont.flow.k

    def extra(z):
        x, _, p = cont.unpack(z)
        h = 1e-6 * max(1.0, abs(p))
        deq = (_equilibrium_k(hopf, p + h) - _equilibrium_k(hopf, p - h)) / (2 * h)
        row = np.zeros(6)
        row[k] = 1.0
        row[5] = -deq * cont.sp / cont.sx
        return (x[k] - _equilibrium_k(hopf, p) + amplitude) / cont.sx, row

    return extra


# ---------------------------------------------------------------- the branch


def cycle_branch(
    model: Model,
    *,
    param: str = "Vb",
    lo: float,
    hi: float,
    backend: Backend | None = None,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch of self-excited cycles in ``param`` over ``[lo, hi]`` (module docstring).

    Parameters
    ----------
    model : Model
        Without excitation; its value of ``param`` is used only where the range holds
        no Hopf point (the branch then goes both ways through the cycle there).
    param : str
        A model parameter.
    lo, hi : float
        The range.
    backend : {"python", "numba", None}
        The kernels; None: numba if installed.
    settings : ContinuationSettings, optional
        The driver's steps and tolerances; default
        `beltmdsm.continuation.settings.CYCLE_SETTINGS`.

    Returns
    -------
    Branch
        Of ``kind = "cycle"``: from the Hopf point, or both ways through the model's
        cycle.

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range, or a model with excitation.
    NoPeriodicResponse
        Where no cycle is found: none near the Hopf point, or, without a Hopf point in
        the range, none at the model's value (the message gives both reasons).

    See Also
    --------
    beltmdsm.cycles.branch.cycle_branch_from : From a given cycle.
    beltmdsm.cycles.hopf.hopf_point : Where the branch is born.

    Examples
    --------
    Near the Stribeck Hopf point the period stays near ``2 pi`` while the amplitude
    of ``X1'`` grows to 0.92 at ``Vb = 2.1``; a forced model is refused:

    >>> from beltmdsm.model import Model
    >>> branch = cycle_branch(Model(friction="stribeck", alpha=0.0), lo=1.9, hi=2.1)
    >>> end = branch.points[-1]
    >>> end.value, round(end.period, 3), round(end.amplitude, 2)
    (2.1, 6.292, 0.92)
    >>> cycle_branch(Model(), lo=1.0, hi=2.0)
    Traceback (most recent call last):
    ...
    ValueError: a branch of self-excited cycles needs a model without excitation
    """
    clock = time.perf_counter()
    settings = as_settings(settings, Continuation.default_settings)
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    if not is_autonomous(model):
        raise ValueError("a branch of self-excited cycles needs a model without excitation")
    try:
        hopf = hopf_point(model, param, lo, hi)
    except NoHopfPoint as err:
        return _from_cycle(model, param, float(lo), float(hi), backend, str(err), settings)
    amplitude = HOPF_AMPLITUDE * _scale(hopf.equilibrium)
    cont, z = _hopf_start(hopf, amplitude, backend, float(lo), float(hi))
    try:
        x, T, p, img, J, _ = cont.correct(z, _amplitude_row(cont, hopf, amplitude))
    except NoPeriodicResponse as err:
        raise NoPeriodicResponse(
            f"no cycle of amplitude {amplitude:.3g} near the Hopf point {param} = "
            f"{hopf.value:.6g}: {err}"
        ) from None
    k = cont.flow.k
    t = cont.tangent(J)
    tangent = t if t[k] < 0 else -t  # the amplitude (-x_k on the section) grows
    first = cont.point(x, T, p, img, tangent[-1], J)
    unstable = 1.0 if hopf.transversality > 0 else -1.0
    criticality = "supercritical" if (p - hopf.value) * unstable > 0 else "subcritical"
    born = SpecialPoint(
        "hopf",
        hopf.value,
        hopf.accuracy,
        hopf.frequency,
        first.multipliers,
        None,
        first.stable,
        f"steady sliding's {hopf.pair} pair crosses the imaginary axis at "
        f"{hopf.frequency:.6g} rad/s; {criticality}: the cycles exist where sliding is "
        + ("unstable" if criticality == "supercritical" else "stable"),
    )
    points, special = walk(cont, first, tangent, hopf.period, settings)
    return Branch(
        param,
        1,
        hopf.model,
        points,
        [born] + special,
        hopf,
        criticality,
        time.perf_counter() - clock,
        kind="cycle",
    )


def cycle_branch_from(
    start: Cycle,
    param: str,
    lo: float,
    hi: float,
    *,
    backend: Backend | None = None,
    settings: ContinuationSettings | None = None,
) -> Branch:
    """The branch of cycles through ``start`` in ``param`` over ``[lo, hi]``, both ways.

    Parameters
    ----------
    start : Cycle
        A cycle (`beltmdsm.periodic.cycle.cycle`).
    param : str
        A model parameter.
    lo, hi : float
        The range, holding the start's value.
    backend : {"python", "numba", None}
        The kernels; None: numba if installed.
    settings : ContinuationSettings, optional
        The driver's steps and tolerances; default
        `beltmdsm.continuation.settings.CYCLE_SETTINGS`.

    Returns
    -------
    Branch
        Of ``kind = "cycle"``, without a Hopf point; its points run from ``lo`` to ``hi``.

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range or a start outside it.

    See Also
    --------
    beltmdsm.cycles.branch.cycle_branch : From a Hopf point.

    Examples
    --------
    Both ways from the stick-slip cycle at ``Vb = 1.5`` (period 6.654 s): a faster belt
    shortens it.

    >>> from beltmdsm.periodic.cycle import cycle
    >>> from beltmdsm.model import Model
    >>> model = Model(friction="stribeck", alpha=0.0, Vb=1.5)
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> start = cycle(model, guess=x, period=6.654341995080)
    >>> branch = cycle_branch_from(start, "Vb", 1.48, 1.52)
    >>> [(p.value, round(p.period, 4)) for p in (branch.points[0], branch.points[-1])]
    [(1.48, 6.6672), (1.52, 6.6419)]
    >>> cycle_branch_from(start, "Vb", 1.6, 1.7)
    Traceback (most recent call last):
    ...
    ValueError: the start's Vb = 1.5 must lie in [1.6, 1.7]
    """
    clock = time.perf_counter()
    settings = as_settings(settings, Continuation.default_settings)
    model = start.model
    v0 = float(model[param])
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo <= v0 <= hi and lo < hi):
        raise ValueError(f"the start's {param} = {v0:g} must lie in [{lo:g}, {hi:g}]")
    flow = CycleFlow(model, param, 1, backend)
    cont = Continuation(flow, lo, hi, _scale(start.state), start.period, start.state, v0)
    z = cont.z_of(start.state, start.period, v0)
    row = np.zeros(6)
    row[5] = 1.0
    x, T, p, img, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    walks = []
    for sign in (1.0, -1.0):
        t = cont.tangent(J, sign=1.0)
        t = t if t[-1] * sign >= 0 else -t
        first = cont.point(x, T, p, img, t[-1], J)
        walks.append(walk(cont, first, t, start.period, settings))
    points, special = join(*walks)
    wall = time.perf_counter() - clock
    return Branch(param, 1, model, points, special, None, None, wall, kind="cycle")


def _from_cycle(model, param, lo, hi, backend, no_hopf, settings):
    """The branch both ways through the cycle at the model's value of ``param``."""
    v0 = float(model[param])
    if not lo <= v0 <= hi:
        raise NoPeriodicResponse(
            f"{no_hopf}; and the model's {param} = {v0:g} is outside the range"
        )
    try:
        found = cycle(model, backend=backend)
    except NoPeriodicResponse as err:
        raise NoPeriodicResponse(f"{no_hopf}; and no cycle at {param} = {v0:g}: {err}") from None
    return cycle_branch_from(found, param, lo, hi, backend=backend, settings=settings)
