"""The self-excited cycle as a continuation problem (`beltmdsm.continuation.problem`).

The curve of zeros of ``(phi_T(x; p) - x, h(x))`` (`beltmdsm.periodic.cycle_flow`) in
``z = (x / sx, T / sT, p / sp)``: the period is unknown and the section ``h`` is the
phase condition. `CycleProblem` states the residual and the 5 x 6 Jacobian ``[M - I, f,
dphi/dp; grad h, 0, dh/dp]``, the point (`CyclePoint`, its multipliers without the
trivial one) and its hooks: a step whose stick count changes is refused, and the stick
onset crossed (`beltmdsm.cycles.stick.cross_stick`); a cycle whose largest multiplier
passes `MULTIPLIER_LIMIT` ends single shooting (the walk goes on by multiple shooting,
`beltmdsm.cycles.multiple`), and one whose period passes `PERIOD_LIMIT` times the
first ends the branch. The one driver (`beltmdsm.continuation.driver`) does the rest, as for the
forced responses; its defaults here are
`beltmdsm.continuation.settings.CYCLE_SETTINGS`.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..continuation.driver import walk as drive
from ..continuation.problem import Problem, Residual, Step, failed, null_vector, range_end
from ..continuation.settings import CYCLE_SETTINGS, ContinuationSettings
from ..errors import NoPeriodicResponse
from ..model import Model
from ..periodic.cycle_flow import CycleFlow, FlowImage, orbit_observables, split_multipliers
from ..periodic.newton import NEWTON_TOL
from .stick import cross_stick, stick_ahead, sticks

__all__ = ["CyclePoint", "CycleProblem", "Continuation", "walk"]

#: The parameter's scale is at most this many times the start's value (or 1).
P_SCALE = 2.0
#: Single shooting ends where a cycle's largest multiplier exceeds this (and
#: `beltmdsm.cycles.multiple` takes the branch on, in segments): its corrector converges
#: only within about ``1 / |mu|`` of the cycle (Stribeck's law at ``v_s = 0.12``: ``|mu|
#: = 6e3``, steps of 1e-6 in ``v_s``, 2000 points without reaching the stick onset); the
#: branches of the shipped laws in ``Vb`` stay below 20.
MULTIPLIER_LIMIT = 1e3
#: A branch ends where the period exceeds this many times the first one (the Hopf period).
PERIOD_LIMIT = 50.0
#: The section's residual (relative to its gradient times the state's scale).
_SECTION_TOL = 1e-11


@dataclass
class CyclePoint:
    """One cycle on a branch.

    Attributes
    ----------
    value : float
    state : ndarray (4,)
        ``(X1, X1', X2, X2')`` on the section (the smallest ``X1'``).
    period : float
    multipliers : ndarray
        Without the trivial one, ``|mu|`` descending.
    trivial_multiplier : complex
        The one nearest 1 (its distance from 1 shows the accuracy).
    max_abs_multiplier : float
    stable : bool
    n_sticks, n_reversals : int
    amplitude : float
        Half the range of ``X1'``.
    x1_range, velocity_range : tuple of float
    max_relative_velocity : float
        Largest ``Vr = X1' - Vb`` (0 where the mass sticks).
    stick_time : float
        Time stuck per period [s].
    tangent : float
        The parameter component of the unit tangent, along the continuation.
    recorded : dict of str to float
        What the ``record`` callable of `beltmdsm.continuation.branch.branch` returned
        here (empty without one).
    segments : ndarray (m, 4) or None
        The states at ``t = i T / m`` where the cycle was solved by multiple shooting
        (`beltmdsm.cycles.multiple`); None for single shooting.
    model : Model or None
        The model at the point (the branch's parameter at ``value``), from which
        `beltmdsm.branches.continue_branch` continues it.

    See Also
    --------
    beltmdsm.cycles.continuation.Continuation.point : Builds it.
    beltmdsm.cycles.branch.CycleBranch : A branch of them.

    Examples
    --------
    The stick-slip cycle of Stribeck friction at ``Vb = 1.5`` (period 6.654 s, one
    stick phase of 1.52 s), corrected at ``p = 1.5`` fixed:

    >>> from beltmdsm.model import Model
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> T = 6.654341995080
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> cont = Continuation(flow, 1.45, 1.55, 1.0 + 11.55, T, x, 1.5)
    >>> z, row = cont.z_of(x, T, 1.5), np.eye(6)[5]
    >>> x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    >>> tangent = cont.tangent(J, sign=1.0)
    >>> tangent = tangent if tangent[-1] > 0 else -tangent
    >>> first = cont.point(x, T, p, image, tangent[-1], J)
    >>> round(first.period, 4), first.stable, first.n_sticks, round(first.stick_time, 3)
    (6.6543, True, 1, 1.52)
    >>> round(first.max_abs_multiplier, 4), round(abs(first.trivial_multiplier - 1), 9)
    (0.2236, 0.0)
    >>> round(first.observables(1.5)["max_abs_Vr"], 4)  # 1.5 + 2.0338
    3.5338
    """

    value: float
    state: NDArray[np.float64] = field(repr=False)
    period: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    trivial_multiplier: complex = field(repr=False)
    max_abs_multiplier: float
    stable: bool
    n_sticks: int
    n_reversals: int
    amplitude: float
    x1_range: tuple[float, float] = field(repr=False)
    velocity_range: tuple[float, float] = field(repr=False)
    max_relative_velocity: float
    tangent: float = field(repr=False)
    stick_time: float = field(repr=False, default=0.0)
    image: FlowImage = field(repr=False, default=None)
    column: NDArray[np.float64] | None = field(repr=False, default=None)
    recorded: dict[str, float] = field(repr=False, default_factory=dict)
    segments: NDArray[np.float64] | None = field(repr=False, default=None)
    model: Model | None = field(repr=False, default=None)

    def observables(self, vb: float) -> dict[str, float]:
        """The ranges of ``X1'`` and ``X1``, the largest ``|Vr| = |X1' - vb|`` (at an
        end of the range of ``X1'``, which the orbit passes continuously) and the
        period [s]: the columns of `beltmdsm.continuation.branch_result.Branch.observables`
        for a cycle (the forced responses' names; no mean friction)."""
        (v_lo, v_hi), (x_lo, x_hi) = self.velocity_range, self.x1_range
        return {
            "X1'_amplitude": float(self.amplitude),
            "X1'_min": float(v_lo),
            "X1'_max": float(v_hi),
            "X1_amplitude": 0.5 * float(x_hi - x_lo),
            "X1_min": float(x_lo),
            "X1_max": float(x_hi),
            "max_abs_Vr": max(abs(v_lo - vb), abs(v_hi - vb)),
            "period": float(self.period),
        }

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``state0``, ``period``, ``amplitude``, ``x1_range``,
        ``velocity_range``, ``max_relative_velocity``, ``multipliers`` (pairs),
        ``trivial_multiplier``, ``max_abs_multiplier``, ``stable``, ``n_sticks``,
        ``n_reversals``."""
        return {
            "value": self.value,
            "state0": [float(v) for v in self.state],
            "period": self.period,
            "amplitude": self.amplitude,
            "x1_range": list(self.x1_range),
            "velocity_range": list(self.velocity_range),
            "max_relative_velocity": self.max_relative_velocity,
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "trivial_multiplier": [self.trivial_multiplier.real, self.trivial_multiplier.imag],
            "max_abs_multiplier": self.max_abs_multiplier,
            "stable": self.stable,
            "n_sticks": self.n_sticks,
            "n_reversals": self.n_reversals,
            "stick_time": self.stick_time,
        }


class CycleProblem(Problem):
    """A self-excited cycle continued in ``z = (x/sx, T/sT, p/sp)`` (module docstring).

    Parameters
    ----------
    flow : CycleFlow
        The flow in the parameter.
    lo, hi : float
        The parameter's range (``sp`` is a tenth of it).
    sx, sT : float
        The scales of the state and the period.
    x : array_like, shape (4,)
        A state, where the section's gradient sets the scale of ``h``.
    p : float
        The parameter there.

    See Also
    --------
    beltmdsm.continuation.problem.Problem : The contract it fills in.
    beltmdsm.cycles.continuation.walk : The walk along a branch.
    beltmdsm.cycles.branch.cycle_branch : The public entry.

    Examples
    --------
    From the stick-slip cycle at ``Vb = 1.5``, corrected with ``p`` fixed, a step of
    0.05 along the tangent lands on the cycle at ``Vb = 1.5005``, slightly shorter:

    >>> from beltmdsm.model import Model
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> T = 6.654341995080
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> cont = Continuation(flow, 1.45, 1.55, 1.0 + 11.55, T, x, 1.5)
    >>> z, row = cont.z_of(x, T, 1.5), np.eye(6)[5]
    >>> x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    >>> tangent = cont.tangent(J, sign=1.0)
    >>> tangent = tangent if tangent[-1] > 0 else -tangent
    >>> first = cont.point(x, T, p, image, tangent[-1], J)
    >>> step = cont.trial(first, tangent, 0.05)
    >>> round(step.value, 4), round(step.period, 4), step.n_sticks
    (1.5005, 6.654, 1)
    """

    kind = "cycle"
    default_settings = CYCLE_SETTINGS
    diverge_after = 2

    def __init__(self, flow: CycleFlow, lo: float, hi: float, sx: float, sT: float, x, p):
        self.flow, self.lo, self.hi = flow, lo, hi
        self.period0 = sT  # the reference period of `PERIOD_LIMIT`
        # the parameter's scale: a tenth of the range, but at most `P_SCALE` times the
        # start's size: a range out to 1e300 would otherwise make every step jump by
        # 1e298 (issue 36, item 9); the branch then ends where it ends, as in a range
        # that holds it
        span = min((hi - lo) / 10.0, P_SCALE * max(1.0, abs(float(p))))
        self.sx, self.sT, self.sp = sx, sT, max(span, 1e-12)
        self.hs = float(np.linalg.norm(flow.section_gradient(x, p))) * sx or 1.0

    def z(self, point) -> NDArray[np.float64]:
        return np.concatenate(
            [point.state / self.sx, [point.period / self.sT, point.value / self.sp]]
        )

    def z_of(self, x, T, p) -> NDArray[np.float64]:
        return np.concatenate([np.asarray(x, float) / self.sx, [T / self.sT, p / self.sp]])

    def unpack(self, z):
        return z[:4] * self.sx, float(z[4] * self.sT), float(z[5] * self.sp)

    def residual(self, z, extra, iteration) -> Residual:
        x, T, p = self.unpack(z)
        img = self.flow.image(x, T, p)
        G = (img.state - x) / self.sx
        H = self.flow.section(x, p) / self.hs
        size = max(float(np.max(np.abs(G))), abs(H), abs(extra))
        converged = (
            size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x))))
            and abs(H) <= _SECTION_TOL
            and iteration > 1
        )
        return Residual(np.append(G, H), size, converged, (x, T, p, img))

    def jacobian(self, *args, column=None) -> NDArray[np.float64]:  # type: ignore[override]
        """``d(G, H)/dz`` (5 x 6) at ``(x, T, p, image)`` (or ``data``, that tuple, as the
        driver calls it); ``column``: the scaled ``p`` column, if known."""
        if len(args) <= 2:  # (data[, column])
            (x, T, p, img), column = args[0], args[1] if len(args) == 2 else column
        else:  # (x, T, p, img[, column])
            x, T, p, img = args[:4]
            column = args[4] if len(args) == 5 else column
        J = np.zeros((5, 6))
        J[:4, :4] = img.monodromy - np.eye(4)
        J[:4, 4] = img.field * self.sT / self.sx
        J[4, :4] = self.flow.section_gradient(x, p) * self.sx / self.hs
        if column is None:
            c = self.flow.p_column(x, T, p)
            column = np.append(c[:4] * self.sp / self.sx, c[4] * self.sp / self.hs)
        J[:, 5] = column
        return J

    def solution(self, data, iteration) -> Step:
        x, T, p, _ = data
        return Step(self.z_of(x, T, p), p, self.jacobian(data), iteration, data)

    def correct(self, z_pred, extra, column=None, fresh=False):
        """Newton's method on ``G = 0``, ``H = 0`` and ``extra(z) = (value, row)``
        (`beltmdsm.continuation.driver.newton`).

        ``column``: the ``p`` column of a point nearby, kept through the iterations
        (computed at the first where not given) unless ``fresh`` (across a kink of the
        map it changes).

        Returns ``(x, T, p, image, J, iterations)``, ``J`` (5 x 6) with the ``p``
        column at the result; raises NoPeriodicResponse.
        """
        step = self.solve(z_pred, extra, column, fresh)
        x, T, p, img = step.data
        return x, T, p, img, step.J, step.iterations

    @staticmethod
    def tangent(J, previous=None, sign=1.0, direction=None):
        """The unit null vector of ``J``: along ``previous``, else signed by ``sign``
        (``direction``: by the sign of its parameter component, as the driver asks)."""
        if direction is not None:
            return Problem.tangent(J, previous, direction)
        t = null_vector(J)
        if previous is not None:
            return t if float(t @ previous) >= 0 else -t
        return t if sign >= 0 else -t

    def point(self, *args, **kw) -> CyclePoint:  # type: ignore[override]
        """``point(x, T, p, image, tangent_p, J=None)``, or ``point(step, tangent_p)``
        (the driver's form)."""
        if isinstance(args[0], Step):
            step, tangent_p = args
            return self.point_at(*step.data, tangent_p, step.J)
        return self.point_at(*args, **kw)

    def point_at(self, x, T, p, img, tangent_p, J=None) -> CyclePoint:
        """The cycle with state ``x`` on the section, period ``T``, at ``p``."""
        trivial, rest = split_multipliers(img.monodromy, self.flow.field(p, x))
        biggest = float(np.abs(rest[0])) if rest.size else 0.0
        model, _ = self.flow.at(p)
        obs = orbit_observables(img.run, model["Vb"])
        return CyclePoint(
            float(p),
            np.array(x, float),
            float(T),
            rest,
            trivial,
            biggest,
            bool(biggest < 1.0),
            obs.n_sticks,
            obs.n_reversals,
            obs.amplitude,
            obs.x1_range,
            obs.velocity_range,
            obs.max_relative_velocity,
            float(tangent_p),
            obs.stick_time,
            img,
            None if J is None else J[:, 5].copy(),
            model=model,
        )

    # -- the hooks: the stick onset, the limits of single shooting

    def period(self, point):
        """The period of a located cycle, for the frequency of a Neimark-Sacker pair."""
        return point.period

    def check_step(self, prev, step, jumped):
        if jumped:
            return "the corrector jumps to another branch"
        if (prev.n_sticks == 0) != (sticks(step.data[3]) == 0):
            return "a stick phase " + ("disappears" if prev.n_sticks else "appears")
        return None

    def same_structure(self, prev, new):
        return (prev.n_sticks, prev.n_reversals) == (new.n_sticks, new.n_reversals)

    def range_specials(self, prev, end, tangent, ds, bound, settings):
        if end.n_sticks != prev.n_sticks:
            return []
        lo, hi = min(prev.value, bound), max(prev.value, bound)
        found = self.special_between(prev, end, tangent, ds, settings)
        return [s for s in found if lo <= s.value <= hi]

    def at_bound(self, end, bound):
        return _at_value(self, end, bound), range_end(end, bound)

    def rescue(self, points, prev, tangent, ds):
        """Across the stick onset ahead (`beltmdsm.cycles.stick`), where one is."""
        ahead = stick_ahead(self, points, ds)
        crossed = None if ahead is None else cross_stick(self, prev, tangent, ahead)
        if crossed is None:
            return None
        sp, near, first, tangent = crossed
        return sp, [near, first], tangent

    def give_up(self, stretch, failure, stage):
        detail = f"no step converges: {failure}" if stage == "step" else failure
        return super().give_up(stretch, detail, stage)

    def stop(self, new):
        if new.max_abs_multiplier > MULTIPLIER_LIMIT:
            return failed(
                new,
                f"the cycle's largest multiplier reaches {new.max_abs_multiplier:.3g}: "
                "shooting over one period amplifies the run's rounding by it, and the "
                "corrector's steps shrink towards nothing (a cycle this unstable needs "
                "multiple shooting)",
            )
        return self.period_stop(new)

    def period_stop(self, new):
        """The end where the period passes `PERIOD_LIMIT` times the first (or None)."""
        if new.period > PERIOD_LIMIT * self.period0:
            return failed(
                new,
                f"the period ({new.period:.4g} s) grows past {PERIOD_LIMIT:g} times the Hopf "
                "period: towards a homoclinic orbit or a standstill",
            )
        return None


#: The name before issue 38.
Continuation = CycleProblem


def _at_value(cont, point, value):
    """The cycle at ``p = value`` exactly, from a point located near it (itself where
    Newton's method does not converge)."""
    z = cont.z(point)
    z[-1] = value / cont.sp
    row = np.zeros(z.size)
    row[-1] = 1.0
    try:
        x, T, p, img, J, _ = cont.correct(z, lambda q: (float(q[-1] - z[-1]), row))
    except NoPeriodicResponse:
        return point
    t = cont.tangent(J)
    return cont.point(x, T, p, img, t[-1] if t[-1] * point.tangent >= 0 else -t[-1], J)


def walk(cont, first, tangent, period0, settings: ContinuationSettings | None = None):
    """Continue from ``first`` along ``tangent`` to the range's end or a failure.

    Parameters
    ----------
    cont : Continuation
        The continuation.
    first : CyclePoint
        The first cycle.
    tangent : numpy.ndarray, shape (6,)
        The unit tangent there, in the direction to go.
    period0 : float
        The reference period of `PERIOD_LIMIT`.
    settings : ContinuationSettings, optional
        The driver's; default `beltmdsm.continuation.settings.CYCLE_SETTINGS`.

    Returns
    -------
    points : list of CyclePoint
        From ``first`` on.
    special : list of SpecialPoint
        The special points passed, and how the walk ended (``"range"`` or ``"failed"``).

    See Also
    --------
    beltmdsm.continuation.driver.walk : The driver it hands the problem to.
    beltmdsm.cycles.stick.cross_stick : Crosses the stick onset on the way.
    beltmdsm.cycles.branch.cycle_branch : Walks both ways from a Hopf point or a cycle.

    Examples
    --------
    Up from the stick-slip cycle at ``Vb = 1.5`` to the end of the range, 1.55: the
    cycle stays stable, with one stick phase, its period shortening to 6.624 s:

    >>> from beltmdsm.model import Model
    >>> x = np.array([2.902211983923, -2.033757676987, 11.547447572261, 0.0])
    >>> T = 6.654341995080
    >>> flow = CycleFlow(Model(friction="stribeck", alpha=0.0), "Vb")
    >>> cont = Continuation(flow, 1.45, 1.55, 1.0 + 11.55, T, x, 1.5)
    >>> z, row = cont.z_of(x, T, 1.5), np.eye(6)[5]
    >>> x, T, p, image, J, _ = cont.correct(z, lambda q: (float(q[5] - z[5]), row))
    >>> tangent = cont.tangent(J, sign=1.0)
    >>> tangent = tangent if tangent[-1] > 0 else -tangent
    >>> first = cont.point(x, T, p, image, tangent[-1], J)
    >>> points, special = walk(cont, first, tangent, T)
    >>> [(s.kind, s.value) for s in special]
    [('range', 1.55)]
    >>> end = points[-1]
    >>> end.value, round(end.period, 3), end.stable, end.n_sticks
    (1.55, 6.624, True, 1)
    """
    cont.period0 = period0
    return drive(cont, first, tangent, settings)


#: Names this module had before issue 38, and where they went.
_MOVED = {"STEP_FIRST": "step_first", "STEP_MIN": "step_min", "STEP_MAX": "step_max"}


def __getattr__(name: str):
    if name in _MOVED:
        warnings.warn(
            f"beltmdsm.cycles.continuation.{name} is now "
            f"beltmdsm.continuation.settings.CYCLE_SETTINGS.{_MOVED[name]} (issue 38)",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(CYCLE_SETTINGS, _MOVED[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
