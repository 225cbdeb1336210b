"""Another model's self-excited pure-slip cycle as a continuation problem (issue 39).

`OscillatorCycleProblem` (`beltmdsm.continuation.problem.Problem`) continues a cycle of
an unforced `beltmdsm.oscillator.System` that slips throughout, as
`beltmdsm.cycles.continuation.CycleProblem` does the paper's: the unknowns ``z = (x /
sx, T / sT, p / sp)``, a state on the cycle, its period and the parameter last; the
residual ``G = (phi_T(x) - x) / sx`` and the phase condition ``H = h(x) / hs``,
``h = slip_acceleration`` (the section where the slip speed ``m v_r`` is least, as
`beltmdsm.oscillator.slip_shooting` shoots); the Jacobian ``[M - I, f(phi_T), dphi/dp;
grad h, 0, dh/dp]``, ``M`` the monodromy by the variational equations, ``grad h = J^T
w`` by the derived Jacobian and slip gradient, the parameter column by central
differences (the generic runtime has no parametric sensitivities), fresh at every
iterate of the corrector (`OscillatorCycleProblem.solve`).

**The run.** A pure-slip cycle stays in its slip mode ``m``: the run is the slip mode's
derived field, integrated by the hybrid flow's own DOP853 stepper
(`beltmdsm.oscillator._stepper`, the steps `beltmdsm.oscillator.hybrid.flow` takes while
no surface is crossed: the same numbers), with no switching surface armed. The field
is smooth across ``v_r = 0``, so past the onset of stick the run goes on along the
smooth continuation of the cycle (a *virtual* cycle, which the hybrid system does not
have: there it sticks); the least slip speed ``margin = m v_r(x)`` then changes sign
smoothly, and the driver locates its zero as it locates a fold (`regula_falsi` on the
arclength), polished by the corrector with ``margin = 0`` in place of the arclength's
equation. No saltation matrix enters: a pure-slip cycle switches nowhere.

**Special points.** ``fold``, ``period_doubling``, ``neimark_sacker`` and
``branch_point`` by the driver (`beltmdsm.continuation.special`) on the multipliers
without the trivial one; ``stick_onset`` (the cycle first touches ``v_r = 0``), which
ends the branch at the grazing cycle (its points are real cycles of the hybrid system
only up to there); ``failed`` where the largest multiplier passes `MULTIPLIER_LIMIT`
(single shooting amplifies rounding by it) or the cycle shrinks onto steady sliding
(the Hopf point: the phase condition degenerates there), or no step converges.

A cycle with a stick phase is no cycle of this problem (its phase condition is the end
of a stick, `beltmdsm.oscillator.stick_slip_shooting`); it is refused where it enters
(`beltmdsm.continuation.oscillator_branch.continue_oscillator_cycle`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..oscillator import _stepper
from ..oscillator.cycle import NEWTON_TOL, Cycle
from ..oscillator.equilibria import hopf_points
from ..oscillator.orbit import orbit_observables
from ..oscillator.system import System
from .branch_result import SpecialPoint
from .corrector import newton
from .problem import Problem, Residual, Step, failed, range_end
from .settings import CYCLE_SETTINGS
from .special import regula_falsi

__all__ = ["OscillatorCyclePoint", "OscillatorCycleProblem", "slip_run", "TOL", "DETECTS"]

#: The integrator's tolerances (rtol = atol), as `beltmdsm.oscillator.slip_shooting`'s.
TOL = 1e-11
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
#: The special points this problem detects (module docstring).
DETECTS = ("fold", "period_doubling", "neimark_sacker", "branch_point", "stick_onset")


def slip_run(system: System, x, T: float, mode: int, variational: bool = True):
    """The run of slip mode ``mode``'s field from ``x`` over ``T`` (module docstring):
    ``(y, M)``, ``M`` the monodromy where ``variational`` (else None)."""
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
    while t < T:
        try:
            st, h = _stepper.step(fun, t, z, f, h, T, TOL, TOL, math.inf)
        except ArithmeticError as err:
            raise NoPeriodicResponse(f"{system!r}: the slip run fails: {err}") from None
        t, z, f = st.t + st.h, st.y_new, st.f_new
    return z[:m].copy(), (z[m:].reshape(m, m).copy() if variational else None)


def split(M, f) -> tuple[complex, NDArray[np.complex128]]:
    """``(trivial, others)``: the multiplier whose eigenvector lies closest to the field
    ``f`` (as `beltmdsm.oscillator.cycle` picks it) and the others by decreasing modulus."""
    w, V = np.linalg.eig(M)
    V = V / np.linalg.norm(V, axis=0)
    i = int(np.argmax(np.abs(V.conj().T @ (f / np.linalg.norm(f)))))
    rest = np.delete(w, i)
    return complex(w[i]), rest[np.argsort(-np.abs(rest), kind="stable")]


@dataclass
class OscillatorCyclePoint:
    """One pure-slip cycle of another model on a branch.

    Attributes
    ----------
    value : float
    state : ndarray (2n,)
        On the section where the slip speed is least.
    period : float
    multipliers : ndarray (2n-1,) complex
        Without the trivial one, by decreasing modulus.
    trivial_multiplier : complex
    max_abs_multiplier : float
    stable : bool
    margin : float
        The least slip speed ``m v_r`` (at ``state``): 0 at the stick onset.
    curvature : float
        ``d^2 (m v_r) / dt^2`` at ``state``: > 0 at the least slip speed; 0 at the Hopf
        point, where the cycle shrinks onto steady sliding.
    tangent : float
        The parameter component of the unit tangent.
    mode : int
        The slip mode (+1 or -1).
    monodromy : ndarray (2n, 2n)
    system : System
        The model at ``value``.

    See Also
    --------
    beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem : makes them.

    Examples
    --------
    >>> from beltmdsm import Model, cycle
    >>> from beltmdsm.branches import continue_branch
    >>> c = cycle(Model(model="belt_1dof", friction="stribeck", Vb=2.5),
    ...           guess=[3.0182035, 2.0991444], period=6.3203187)
    >>> p = continue_branch(c, "Vb", 2.45, 2.55).point_near(2.5)
    >>> p.value, round(p.period, 6), p.stable, p.n_sticks
    (2.5, 6.320319, False, 0)
    >>> round(p.observables()["period"], 6), round(p.margin, 6)
    (6.320319, 0.400856)
    """

    value: float
    state: NDArray[np.float64]
    period: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    trivial_multiplier: complex = field(repr=False)
    max_abs_multiplier: float
    stable: bool
    margin: float
    curvature: float = field(repr=False)
    tangent: float = field(repr=False)
    mode: int = field(repr=False)
    monodromy: NDArray[np.float64] = field(repr=False)
    system: System = field(repr=False)
    column: NDArray[np.float64] | None = field(default=None, repr=False)
    recorded: dict[str, float] = field(default_factory=dict, repr=False)
    _observed: dict[str, float] | None = field(default=None, repr=False)

    #: A pure-slip cycle: no switch, no stick, no reversal.
    n_sticks, n_reversals, switches, signature = 0, 0, (), ()

    def observables(self, vb: float | None = None) -> dict[str, float]:
        """The orbit's extremes (`beltmdsm.oscillator.orbit.orbit_observables`: the
        states' and the slip velocity's ranges, ``max_abs_v_r`` the largest slip speed),
        then ``period`` and ``max_abs_multiplier``; computed once (``vb`` unread)."""
        if self._observed is None:
            found = orbit_observables(self.system, self.state, self.period)
            found["period"] = self.period
            found["max_abs_multiplier"] = self.max_abs_multiplier
            self._observed = found
        return self._observed

    def cycle(self) -> Cycle:
        """The `beltmdsm.oscillator.cycle.Cycle` this point is (no switch)."""
        y, M = self.state, self.monodromy
        return Cycle(self.system, y, self.mode, self.period, self.multipliers,
                     self.trivial_multiplier, M, [], 0, 0.0, TOL, TOL)  # fmt: skip

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``state0``, ``state`` (by name), ``period``,
        ``multipliers`` (pairs), ``trivial_multiplier``, ``max_abs_multiplier``,
        ``stable``, ``margin``, ``n_sticks``, ``n_reversals``, ``observables``."""
        return {
            "value": self.value,
            "state0": [float(v) for v in self.state],
            "state": {n: float(v) for n, v in zip(self.system.states, self.state)},
            "period": self.period,
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "trivial_multiplier": [self.trivial_multiplier.real, self.trivial_multiplier.imag],
            "max_abs_multiplier": self.max_abs_multiplier,
            "stable": self.stable,
            "margin": self.margin,
            "n_sticks": 0,
            "n_reversals": 0,
            "observables": self.observables(),
        }


class OscillatorCycleProblem(Problem):
    """A derived model's pure-slip cycle in one parameter (module docstring).

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

    def __init__(self, system: System, param: str, mode: int, lo, hi, sx, sT):
        self.system, self.param, self.mode = system, param, int(mode)
        self.lo, self.hi, self.sx, self.sT = float(lo), float(hi), float(sx), float(sT)
        self.sp = max((self.hi - self.lo) / 10.0, 1e-12)
        self.hs = 1.0
        self.end: tuple[Any, SpecialPoint] | None = None
        self._at: dict[float, System] = {}

    # -- the model at a value, the phase condition, the margin

    def at(self, value: float) -> System:
        """The model at ``value`` (the last few kept)."""
        value = float(value)
        if value not in self._at:
            if len(self._at) > 8:
                self._at.clear()
            self._at[value] = self.system.replace(**{self.param: value})
        return self._at[value]

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
        y, M = slip_run(self.at(value), x, T, self.mode)
        G = (y - x) / self.sx
        H = self.section(x, value) / self.hs
        size = max(float(np.max(np.abs(G))), abs(H), abs(extra))
        converged = (
            size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x))))
            and abs(H) <= _SECTION_TOL
            and iteration > 1
        )
        return Residual(np.append(G, H), size, converged, (x, T, value, y, M))

    def jacobian(self, data, column=None) -> NDArray[np.float64]:
        x, T, value, y, M = data
        n = x.size
        s = self.at(value)
        J = np.zeros((n + 1, n + 2))
        J[:n, :n] = M - np.eye(n)
        f_end = np.asarray(s.kernels.field(T, y, s.p, self.mode), dtype=float)
        J[:n, n] = f_end * self.sT / self.sx
        J[n, :n] = self.section_gradient(x, value) * self.sx / self.hs
        if column is None:
            h = _P_STEP * max(1.0, abs(value))
            up = slip_run(self.at(value + h), x, T, self.mode, False)[0]
            down = slip_run(self.at(value - h), x, T, self.mode, False)[0]
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

    def point_at(self, x, T, value, y, M, tangent_p) -> OscillatorCyclePoint:
        s = self.at(value)
        f = np.asarray(s.kernels.field(0.0, x, s.p, self.mode), dtype=float)
        trivial, rest = split(M, f)
        biggest = float(np.abs(rest[0])) if rest.size else 0.0
        return OscillatorCyclePoint(
            float(value), np.array(x, float), float(T), rest, trivial, biggest,
            bool(biggest < 1.0), self.margin(x, value),
            self.mode * float(self.section_gradient(x, value) @ f), float(tangent_p),
            self.mode, M, s,
        )  # fmt: skip

    def start(self, x, T, value, direction):
        """The first point at ``value`` (``x``, ``T`` a cycle there, ``x`` on the section)
        corrected with the parameter pinned, and its unit tangent along ``direction``."""
        x = np.asarray(x, dtype=float)
        self.hs = float(np.linalg.norm(self.section_gradient(x, value))) * self.sx or 1.0
        z0 = self.z_of(x, T, value)
        row = np.zeros(z0.size)
        row[-1] = 1.0
        step = self.solve(z0, lambda z: (float(z[-1] - z0[-1]), row))
        tangent = self.tangent(step.J, direction=direction)
        first = self.point(step, float(tangent[-1]))
        first.column = step.J[:, -1].copy()
        return first, tangent

    # -- the hooks

    def period(self, point) -> float:
        return point.period

    def check_step(self, prev, step, jumped):
        return "the corrector jumps to another branch" if jumped else None

    def special_between(self, prev, new, tangent, ds, settings) -> list[SpecialPoint]:
        """The folds and multiplier crossings; where ``new`` lies past the Hopf point or
        the stick onset, those before it, the end kept in ``end`` (for `stop` and
        `at_bound`)."""
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
        return end, range_end(end, bound)

    def give_up(self, stretch, failure, stage):
        detail = f"no step converges: {failure}" if stage == "step" else failure
        return super().give_up(stretch, detail, stage)

    def finish(self, points, special):
        """A walk's points and special points, its last point (past the end) replaced by
        the grazing cycle where the walk ended at the stick onset, dropped where it ended
        at the Hopf point."""
        if self.end is not None and special and special[-1] is self.end[1]:
            last = self.end[0]
            points = [*points[:-1], last] if points[-2] is not last else points[:-1]
        self.end = None
        return points, special
