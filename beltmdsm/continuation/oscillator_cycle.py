"""Another model's self-excited cycle as a continuation problem (issue 39).

`OscillatorCycleProblem` (`beltmdsm.continuation.problem.Problem`) continues a cycle of
an unforced `beltmdsm.oscillator.System`, as `beltmdsm.cycles.continuation.CycleProblem`
does the paper's: the unknowns ``z = (x / sx, T / sT, p / sp)``, a state on the cycle,
its period and the parameter last; the residual ``G = (phi_T(x) - x) / sx`` and the
phase condition ``H = h(x) / hs``, ``h = slip_acceleration`` (a section where the slip
speed ``m v_r`` is extremal: its least on a pure-slip cycle, as
`beltmdsm.oscillator.slip_shooting` shoots; its largest on a cycle with a stick phase,
in the middle of a slip phase, away from every switch); the Jacobian ``[M - I,
f(phi_T), dphi/dp; grad h, 0, dh/dp]``, ``M`` the monodromy by the variational
equations, ``grad h = J^T w`` by the derived Jacobian and slip gradient, the parameter
column by central differences (the generic runtime has no parametric sensitivities),
fresh at every iterate of the corrector (`OscillatorCycleProblem.solve`).

**The run.** A cycle with a stick phase (``hybrid``) is run by the hybrid flow
(`beltmdsm.oscillator.hybrid.flow`), its monodromy with the saltation matrix at every
switch, as `beltmdsm.continuation.oscillator_forced` runs a forced response; a change
of its switch structure ends the branch (``grazing``, not followed across). A pure-slip
cycle stays in its slip mode ``m``: the run is the slip mode's derived field,
integrated by the hybrid flow's own DOP853 stepper (`beltmdsm.oscillator._stepper`, the
steps `beltmdsm.oscillator.hybrid.flow` takes while no surface is crossed: the same
numbers), with no switching surface armed. The field is smooth across ``v_r = 0``, so
past the onset of stick the run goes on along the smooth continuation of the cycle (a
*virtual* cycle, which the hybrid system does not have: there it sticks); the least
slip speed ``margin = m v_r(x)`` then changes sign smoothly, and the driver locates its
zero as it locates a fold (`regula_falsi` on the arclength), polished by the corrector
with ``margin = 0`` in place of the arclength's equation.

**Special points.** ``fold``, ``period_doubling``, ``neimark_sacker`` and
``branch_point`` by the driver (`beltmdsm.continuation.special`) on the multipliers
without the trivial one; on a pure-slip branch ``stick_onset`` (the cycle first touches
``v_r = 0``), which ends it at the grazing cycle (its points are real cycles of the
hybrid system only up to there), and ``hopf`` where the cycle shrinks onto steady
sliding (the section's curvature passes 0; the phase condition degenerates there);
``grazing`` where a stick-slip cycle's switches change; ``failed`` where the largest
multiplier passes `MULTIPLIER_LIMIT` (single shooting amplifies rounding by it) or no
step converges.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..oscillator import _stepper
from ..oscillator.cycle import NEWTON_TOL
from ..oscillator.equilibria import hopf_points
from ..oscillator.hybrid import flow
from ..oscillator.system import System
from .branch_result import SpecialPoint
from .corrector import newton
from .oscillator_cycle_point import TOL, OscillatorCyclePoint, split
from .oscillator_forced import SystemAt
from .problem import Problem, Residual, Step, failed, range_end
from .settings import CYCLE_SETTINGS
from .special import regula_falsi

__all__ = ["OscillatorCyclePoint", "OscillatorCycleProblem", "slip_run", "TOL", "DETECTS"]

#: Single shooting ends where the largest multiplier passes this (as the paper's
#: `beltmdsm.cycles.continuation.MULTIPLIER_LIMIT`).
MULTIPLIER_LIMIT = 1e3
#: The branch ends where the orbit's size (``max |f| T``) falls below this, relative to
#: ``1 + max |x|``: the cycle has shrunk onto steady sliding (its Hopf point).
COLLAPSE = 1e-4
#: The phase condition's residual (relative to its gradient times the state's scale).
_SECTION_TOL = 1e-11
#: Relative step of the central differences in the parameter.
_P_STEP = 1e-6
#: A slip run takes at most this many steps (the shipped cycles take about 40): a corrector's
#: iterate thrown far off the branch (a step across a fold) can make the field stiff
#: (a damper growing as x'^5), where the explicit stepper would crawl for minutes.
MAX_STEPS = 20_000
#: Why a step is refused where the cycle's switches change.
_RESTRUCTURED = "the switch structure changes"
#: The special points this problem detects (module docstring).
DETECTS = (
    "fold", "period_doubling", "neimark_sacker", "branch_point", "stick_onset", "hopf",
    "grazing",
)  # fmt: skip


def slip_run(system: System, x, T: float, mode: int, variational: bool = True):
    """The run of slip mode ``mode``'s field from ``x`` over ``T`` (module docstring):
    ``(y, M)``, ``M`` the monodromy where ``variational`` (else None).

    Parameters
    ----------
    system : System
    x : array_like (2n,)
    T : float
    mode : int
        +1 or -1.
    variational : bool

    Returns
    -------
    y : ndarray (2n,)
    M : ndarray (2n, 2n) or None

    See Also
    --------
    beltmdsm.oscillator.hybrid.flow : the same steps while no surface is crossed.

    Examples
    --------
    The unstable slip cycle of the Stribeck belt returns, its monodromy the shooting's:

    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5),
    ...                        [3.0182035, 2.0991444], 6.3203187)
    >>> y, M = slip_run(c.system, c.state, c.period, c.mode)
    >>> bool(np.abs(y - c.state).max() < 1e-9), bool(np.allclose(M, c.monodromy, atol=1e-8))
    (True, True)
    """
    k, p = system.kernels, system.p
    x = np.asarray(x, dtype=float)
    m = x.size
    if variational:

        def fun(s, z):
            J = np.asarray(k.jacobian(s, z[:m], p, mode), dtype=float)
            f = np.asarray(k.field(s, z[:m], p, mode), dtype=float)
            return np.concatenate((f, (J @ z[m:].reshape(m, m)).ravel()))

        z = np.concatenate((x, np.eye(m).ravel()))
    else:

        def fun(s, z):
            return np.asarray(k.field(s, z, p, mode), dtype=float)

        z = x.copy()
    t, f = 0.0, fun(0.0, z)
    h = _stepper.initial_step(fun, t, z, f, T, TOL, TOL, T)
    steps = 0
    while t < T:
        if steps == MAX_STEPS:
            raise NoPeriodicResponse(
                f"{system!r}: the slip run takes more than {MAX_STEPS} steps by t = "
                f"{t:.6g} s of {T:.6g} s (a stiff field: the iterate lies far off the cycle)"
            )
        try:
            st, h = _stepper.step(fun, t, z, f, h, T, TOL, TOL, math.inf)
        except ArithmeticError as err:
            raise NoPeriodicResponse(f"{system!r}: the slip run fails: {err}") from None
        t, z, f, steps = st.t + st.h, st.y_new, st.f_new, steps + 1
    return z[:m].copy(), (z[m:].reshape(m, m).copy() if variational else None)


class OscillatorCycleProblem(SystemAt, Problem):
    """A derived model's self-excited cycle in one parameter (module docstring).

    Parameters
    ----------
    system : System
        Unforced.
    param : str
    mode : int
        The slip mode of the cycles (+1 or -1).
    lo, hi : float
    sx, sT : float
        The scales of the state and of the period.
    hybrid : bool
        The cycles stick (run by the hybrid flow, on the section of largest slip speed).

    See Also
    --------
    beltmdsm.continuation.problem.Problem : the contract.
    beltmdsm.continuation.oscillator_branch.continue_oscillator_cycle : walks it.

    Examples
    --------
    From the unstable slip cycle of the Stribeck belt at ``Vb = 2.5`` up to its stick
    onset (docs/modelling.md's 2.900393):

    >>> from beltmdsm.oscillator import System, self_excited_cycle
    >>> from beltmdsm.continuation.driver import walk
    >>> c = self_excited_cycle(System("belt_1dof", friction="stribeck", Vb=2.5),
    ...                        [3.0182035, 2.0991444], 6.3203187)
    >>> problem = OscillatorCycleProblem(c.system, "Vb", c.mode, 2.5, 3.5, 4.0, c.period)
    >>> first, tangent = problem.start(c.state, c.period, 2.5, 1.0)
    >>> points, special = problem.finish(*walk(problem, first, tangent))
    >>> [(s.kind, round(s.value, 6)) for s in special]
    [('stick_onset', 2.900393)]
    >>> abs(points[-1].margin) < 1e-10
    True
    """

    kind = "cycle"
    default_settings = CYCLE_SETTINGS
    diverge_after = 2

    def __init__(self, system: System, param: str, mode: int, lo, hi, sx, sT, hybrid=False):
        self.system, self.param, self.mode = system, param, int(mode)
        self.hybrid = bool(hybrid)
        self.lo, self.hi, self.sx, self.sT = float(lo), float(hi), float(sx), float(sT)
        self.sp = max((self.hi - self.lo) / 10.0, 1e-12)
        self.hs = 1.0
        self.end: tuple[Any, SpecialPoint] | None = None
        self._at: dict[float, System] = {}

    # -- the phase condition, the margin (the model at a value: `SystemAt.at`)

    def section(self, x, value) -> float:
        s = self.at(value)
        return float(s.kernels.slip_acceleration(0.0, x, s.p, self.mode))

    def section_gradient(self, x, value) -> NDArray[np.float64]:
        """``J^T w``: the slip velocity is a linear form ``w . y - Vb``."""
        s, k = self.at(value), self.system.kernels
        w = np.asarray(k.slip_gradient(0.0, x, s.p), dtype=float)
        return np.asarray(k.jacobian(0.0, x, s.p, self.mode), dtype=float).T @ w

    def margin(self, x, value) -> float:
        """The least slip speed ``m v_r`` at the section state ``x``."""
        s = self.at(value)
        return self.mode * float(s.kernels.slip_velocity(0.0, x, s.p))

    def run(self, x, T, value, variational: bool = True):
        """``(y, M, switches)`` of the run over ``T`` from ``x`` at ``value``: the slip
        mode's (module docstring), or the hybrid flow's where the cycle sticks."""
        if not self.hybrid:
            return (*slip_run(self.at(value), x, T, self.mode, variational), [])
        r = flow(self.at(value), 0.0, x, T, mode=self.mode, variational=variational,
                 rtol=TOL, atol=TOL)  # fmt: skip
        if r.status != "done":
            raise NoPeriodicResponse(f"the run from the cycle's state stops: {r.message}")
        return r.y, r.monodromy, list(r.switches)

    # -- the unknowns, the equations and the points

    def z(self, point) -> NDArray[np.float64]:
        return self.z_of(point.state, point.period, point.value)

    def z_of(self, x, T, value) -> NDArray[np.float64]:
        x = np.asarray(x, dtype=float) / self.sx
        return np.concatenate([x, [T / self.sT, value / self.sp]])

    def unpack(self, z):
        n = z.size - 2
        return z[:n] * self.sx, float(z[n] * self.sT), float(z[n + 1] * self.sp)

    def residual(self, z, extra, iteration) -> Residual:
        x, T, value = self.unpack(z)
        if not T > 0.0:
            raise NoPeriodicResponse(f"the corrector's period {T:.3g} s is not positive")
        y, M, switches = self.run(x, T, value)
        G = (y - x) / self.sx
        H = self.section(x, value) / self.hs
        size = max(float(np.max(np.abs(G))), abs(H), abs(extra))
        converged = (
            size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x))))
            and abs(H) <= _SECTION_TOL
            and iteration > 1
        )
        return Residual(np.append(G, H), size, converged, (x, T, value, y, M, switches))

    def jacobian(self, data, column=None) -> NDArray[np.float64]:
        x, T, value, y, M, _ = data
        n = x.size
        s = self.at(value)
        J = np.zeros((n + 1, n + 2))
        J[:n, :n] = M - np.eye(n)
        f_end = np.asarray(s.kernels.field(T, y, s.p, self.mode), dtype=float)
        J[:n, n] = f_end * self.sT / self.sx
        J[n, :n] = self.section_gradient(x, value) * self.sx / self.hs
        if column is None:
            h = _P_STEP * max(1.0, abs(value))
            up = self.run(x, T, value + h, False)[0]
            down = self.run(x, T, value - h, False)[0]
            dh = self.section(x, value + h) - self.section(x, value - h)
            column = np.append((up - down) / self.sx, dh / self.hs) * self.sp / (2.0 * h)
        J[:, n + 1] = column
        return J

    def solve(self, z_pred, extra, column=None, fresh=False) -> Step:
        """The driver's corrector with the parameter column fresh at every iterate (two
        plain runs): with a neighbour's column Newton's method converges only linearly
        here (by a factor of the step's order: 6 to 7 iterations a step on the Stribeck
        belt), never counts as easy, and the step never grows; fresh, 3 to 4 iterations
        and a quarter of the steps (benchmarks/bench_oscillator_cycle_branch.py)."""
        return newton(self, z_pred, extra, None, True)

    def solution(self, data, iteration) -> Step:
        x, T, value = data[:3]
        return Step(self.z_of(x, T, value), value, self.jacobian(data), iteration, data)

    def point(self, step, tangent_p) -> OscillatorCyclePoint:
        return self.point_at(*step.data, tangent_p)

    def point_at(self, x, T, value, y, M, switches, tangent_p) -> OscillatorCyclePoint:
        s = self.at(value)
        f = np.asarray(s.kernels.field(0.0, x, s.p, self.mode), dtype=float)
        trivial, rest = split(M, f)
        biggest = float(np.abs(rest[0])) if rest.size else 0.0
        return OscillatorCyclePoint(
            float(value), np.array(x, float), float(T), rest, trivial, biggest,
            bool(biggest < 1.0), self.margin(x, value),
            self.mode * float(self.section_gradient(x, value) @ f), float(tangent_p),
            self.mode, M, s, switches=switches,
        )  # fmt: skip

    def start(self, x, T, value, direction):
        """The first point at ``value`` (``x``, ``T`` a cycle there, ``x`` on the section)
        corrected with the parameter pinned, and its unit tangent along ``direction``."""
        x = np.asarray(x, dtype=float)
        self.hs = float(np.linalg.norm(self.section_gradient(x, value))) * self.sx or 1.0
        step = self._pin(x, T, value)
        tangent = self.tangent(step.J, direction=direction)
        first = self.point(step, float(tangent[-1]))
        first.column = step.J[:, -1].copy()
        return first, tangent

    def _pin(self, x, T, value) -> Step:
        z0 = self.z_of(x, T, value)
        row = np.zeros(z0.size)
        row[-1] = 1.0
        return self.solve(z0, lambda z: (float(z[-1] - z0[-1]), row))

    def pinned(self, x, T, value, direction) -> OscillatorCyclePoint:
        """The cycle at ``value`` exactly, corrected from ``(x, T)``; its tangent's
        parameter component signed by ``direction``."""
        step = self._pin(np.asarray(x, dtype=float), T, value)
        tangent = self.tangent(step.J, direction=direction)
        point = self.point(step, float(tangent[-1]))
        point.column = step.J[:, -1].copy()
        return point

    # -- the hooks

    def period(self, point) -> float:
        return point.period

    def check_step(self, prev, step, jumped):
        return "the corrector jumps to another branch" if jumped else None

    def check_structure(self, prev, step, ds, jumped):
        switches = step.data[5]
        if tuple(sorted((int(b), int(a)) for _, b, a in switches)) != prev.signature:
            return _RESTRUCTURED
        return None

    def same_structure(self, prev, new) -> bool:
        return new.signature == prev.signature

    def special_between(self, prev, new, tangent, ds, settings) -> list[SpecialPoint]:
        """The folds and multiplier crossings; where ``new`` lies past the Hopf point or
        the stick onset, those before it, the end kept in ``end`` (for `stop` and
        `at_bound`)."""
        if self.hybrid:
            return super().special_between(prev, new, tangent, ds, settings)
        if new.curvature <= 0.0 < prev.curvature:
            self.end = (prev, self._hopf(prev, new))
            return []
        if new.margin > 0.0 or new.margin > prev.margin:
            return super().special_between(prev, new, tangent, ds, settings)
        if prev.margin <= 0.0:  # from the grazing cycle itself, away from the slip side
            self.end = (prev, self._onset_special(prev, prev, 0.0))
            return []
        on = self._locate_onset(prev, tangent, ds, new, settings)
        s_on = float(tangent @ (self.z(on) - self.z(prev)))
        found = super().special_between(prev, on, tangent, s_on, settings) if s_on > 0 else []
        sp = self._onset_special(prev, on, self._onset_accuracy)
        self.end = (on, sp)
        return found

    @staticmethod
    def _onset_special(prev, on, accuracy) -> SpecialPoint:
        return SpecialPoint(
            "stick_onset", on.value, accuracy, None, on.multipliers, prev.stable, None,
            "the cycle grazes v_r = 0: past it the mass sticks (the branch of pure-slip "
            "cycles ends)",
        )  # fmt: skip

    def _hopf(self, prev, new) -> SpecialPoint:
        """Through the Hopf point: the amplitude (the curvature of the slip speed at the
        section) passes 0 between ``prev`` and ``new`` and the section's point turns from
        the least slip speed to the largest. The parameter is quadratic in the amplitude
        there (it turns, as at a fold): its vertex through the two points estimates the
        Hopf point, which steady sliding's derived Hurwitz determinant then gives to
        rounding (`beltmdsm.oscillator.hopf_points`, within a step of the estimate);
        where it has none there, the estimate stands, its accuracy the step."""
        a, b = prev.curvature, new.curvature
        c = (prev.value - new.value) / (a * a - b * b)
        guess = prev.value - c * a * a
        width = max(abs(new.value - prev.value), abs(prev.value - guess), 1e-12)
        found = hopf_points(self.system, self.param, guess - width, guess + width, 16)
        if found.size:
            value, accuracy = (
                float(found[np.argmin(np.abs(found - guess))]),
                1e-12 * max(1.0, abs(guess)),
            )
            how = "at steady sliding's Hopf point"
        else:
            value, accuracy = guess, width
            how = "near a Hopf point (none of steady sliding's within the step)"
        return SpecialPoint(
            "hopf", value, accuracy, None, prev.multipliers, prev.stable, None,
            f"the cycle shrinks onto steady sliding {how}: the branch ends",
        )  # fmt: skip

    def _locate_onset(self, prev, tangent, ds, new, settings):
        """The grazing cycle: regula falsi on the margin along the arclength, then the
        corrector with ``margin = 0`` in place of the arclength's equation."""
        near, accuracy = regula_falsi(
            self, prev, tangent, ds, lambda q: q.margin, prev.margin, new.margin,
            s_tol=settings.s_tol,
        )  # fmt: skip
        s = self.system
        w = np.asarray(s.kernels.slip_gradient(0.0, near.state, s.p), dtype=float)
        h = _P_STEP * max(1.0, abs(near.value))
        dv = self.margin(near.state, near.value + h) - self.margin(near.state, near.value - h)
        row = np.concatenate([self.mode * w * self.sx, [0.0], [dv / (2 * h) * self.sp]])

        def pin(z):
            x, _, value = self.unpack(z)
            return self.margin(x, value), row

        try:
            step = self.solve(self.z(near), pin, near.column)
        except NoPeriodicResponse:
            self._onset_accuracy = accuracy
            return near
        t = self.tangent(step.J, tangent)
        on = self.point(step, float(t[-1]))
        on.column = step.J[:, -1].copy()
        # the margin left by the corrector (its tolerance) over its slope along the branch
        slope = abs(prev.margin - on.margin) / max(abs(prev.value - on.value), 1e-300)
        left = max(abs(on.margin), NEWTON_TOL * (1.0 + float(np.abs(on.state).max())))
        self._onset_accuracy = left / slope if slope > 0 else accuracy
        return on

    def stop(self, new) -> SpecialPoint | None:
        if self.end is not None:
            return self.end[1]
        if new.max_abs_multiplier > MULTIPLIER_LIMIT:
            return failed(
                new,
                f"the cycle's largest multiplier reaches {new.max_abs_multiplier:.3g}: "
                "single shooting amplifies the run's rounding by it",
            )
        f = np.asarray(new.system.kernels.field(0.0, new.state, new.system.p, self.mode))
        if np.abs(f).max() * new.period <= COLLAPSE * (1.0 + np.abs(new.state).max()):
            return failed(new, "the cycle shrinks onto steady sliding (its Hopf point)")
        return None

    def range_specials(self, prev, end, tangent, ds, bound, settings):
        return self.special_between(prev, end, tangent, ds, settings)

    def at_bound(self, end, bound):
        if self.end is not None:  # the walk's end lies before the bound
            return self.end
        try:  # the cycle at the bound itself, the parameter pinned
            end = self.pinned(end.state, end.period, bound, end.tangent)
        except NoPeriodicResponse:
            pass
        return end, range_end(end, bound)

    def give_up(self, stretch, failure, stage):
        if failure == _RESTRUCTURED:
            return self._grazing(stretch), []
        detail = f"no step converges: {failure}" if stage == "step" else failure
        return super().give_up(stretch, detail, stage)

    def _grazing(self, stretch) -> SpecialPoint:
        """Where a stick-slip branch's switches change: at its last cycle, or, where its
        stick phases shrink towards it, where their time extrapolates linearly to 0 from
        the last two cycles (a stick born at a grazing lasts in proportion to the
        distance to it); the accuracy covers the extrapolation and the last step."""
        last = stretch[-1]
        value = last.value
        step = 2.0 * self.settings.step_min * self.sp
        prior = [q for q in stretch[:-1] if q.value != last.value]
        what = f"the switch structure changes ({len(last.switches)} switches a period before)"
        if prior and 0.0 < last.stick_time < prior[-1].stick_time:
            a, b = prior[-1], last
            value = b.value - b.stick_time * (b.value - a.value) / (b.stick_time - a.stick_time)
            what = "the stick phase shrinks to nothing (the cycle grazes v_r = 0)"
        return SpecialPoint(
            "grazing", value, abs(value - last.value) + step, None, last.multipliers,
            last.stable, None, f"{what}: the branch ends (it is not followed across)",
        )  # fmt: skip

    def finish(self, points, special):
        """A walk's points and special points, its last point (past the end) replaced by
        the grazing cycle where the walk ended at the stick onset, dropped where it ended
        at the Hopf point."""
        if self.end is not None and special and special[-1] is self.end[1]:
            last = self.end[0]
            points = [*points[:-1], last] if points[-2] is not last else points[:-1]
        self.end = None
        return points, special
