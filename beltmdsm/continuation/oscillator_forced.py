"""The forced response of any derived model as a continuation problem (issue 39).

`OscillatorForcedProblem` (`beltmdsm.continuation.problem.Problem`) continues a fixed
point of the ``k``-fold period map of a `beltmdsm.oscillator.System` with excitation in
one of its parameters: the unknowns ``z = (x / sx, p / sp)``, the residual
``G = (P_p(x) - x) / sx`` where ``P_p`` is the hybrid run over ``k`` excitation periods
(`beltmdsm.oscillator.hybrid.flow`, the period ``2 pi k / Omega`` at ``p``), its
Jacobian ``[M - I, dP/dp]``: ``M`` the monodromy with the saltation matrix at every
switch (as `beltmdsm.oscillator.forced.forced_response` shoots), ``dP/dp`` by central
differences (the generic runtime has no parametric sensitivities). A point carries the
response's Floquet multipliers (the eigenvalues of ``M``) and its observables
(`beltmdsm.oscillator.orbit.orbit_observables`).

The special points it detects: **fold**, **period doubling**, **Neimark-Sacker** and
**branch point** by the driver (`beltmdsm.continuation.special`); a change of switch
structure (switches per orbit: slip reversals, stick phases) as **stick_onset** where a
stick phase appears on an orbit that had none, else **grazing**, located by the secant
on the margin that closes there: the slip velocity's where the orbit slips throughout
(`beltmdsm.oscillator.orbit.slip_margin`), the holding force's against the stick limit
at the reversals where its switches are all slip reversals; by bisection on the
structure otherwise. It does not detect a
tangency or a flight onset (no such margin here): where the corrector fails the
branch ends as ``failed``, its reason said.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace

import numpy as np
from numpy.typing import NDArray

from ..errors import NoPeriodicResponse
from ..oscillator.forced import forced_response
from ..oscillator.hybrid import flow
from ..oscillator.orbit import orbit_observables, slip_margin
from ..oscillator.system import STICK, System
from ..periodic.newton import NEWTON_TOL, fixed_point
from .branch_result import LOCATE_TOL, SpecialPoint
from .problem import Problem, Residual, Step, range_end

__all__ = ["OscillatorPoint", "OscillatorForcedProblem", "GRAZING_STEP", "TOL"]

#: A change of switch structure is accepted as grazing only from steps below this.
GRAZING_STEP = 1e-4
#: The integrator's tolerances (rtol = atol) of the period map.
TOL = 1e-11


def _signature(switches) -> tuple:
    """The switch structure of an orbit: its switches ``(before, after)``, sorted (the
    phase at which the orbit is cut does not change it)."""
    return tuple(sorted((int(b), int(a)) for _, b, a in switches))


@dataclass
class OscillatorPoint:
    """One forced response of a derived model on a branch.

    Attributes
    ----------
    value : float
        The parameter's value.
    state : ndarray (2n,)
        The state at phase 0, in the model's ``states`` order.
    multipliers : ndarray (2n,) complex
        The Floquet multipliers, by decreasing modulus.
    max_abs_multiplier : float
    stable : bool
    n_reversals, n_sticks : int
        Slip reversals and stick phases per orbit.
    tangent : float
        The parameter component of the unit tangent.
    period : float
        ``k T`` at ``value`` [s].
    switches : list of (t, before, after)
    system : System
        The model at ``value``.

    See Also
    --------
    beltmdsm.continuation.oscillator_forced.OscillatorForcedProblem : makes them.

    Examples
    --------
    >>> from beltmdsm import Model, branch
    >>> m = Model(model="belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> p = branch(m, param="Omega_t", lo=1.9, hi=2.1).points[0]
    >>> p.value, p.stable, p.n_sticks, p.state.shape
    (1.9, True, 0, (2,))
    >>> sorted(p.observables())[:3]
    ['max_abs_v_r', 'v_r_max', 'v_r_min']
    """

    value: float
    state: NDArray[np.float64]
    multipliers: NDArray[np.complex128]
    max_abs_multiplier: float
    stable: bool
    n_reversals: int
    n_sticks: int
    tangent: float
    period: float
    switches: list = field(repr=False)
    system: System = field(repr=False)
    column: NDArray[np.float64] | None = field(default=None, repr=False)
    recorded: dict[str, float] = field(default_factory=dict, repr=False)
    _observed: dict[str, float] | None = field(default=None, repr=False)

    @property
    def signature(self) -> tuple:
        return _signature(self.switches)

    def observables(self, vb: float | None = None) -> dict[str, float]:
        """The orbit's extremes (`beltmdsm.oscillator.orbit.orbit_observables`), computed
        once; ``vb`` is not read (the slip velocity is the model's own)."""
        if self._observed is None:
            self._observed = orbit_observables(self.system, self.state, self.period)
        return self._observed

    def as_dict(self) -> dict:
        """For JSON: ``value``, ``state0`` (in ``states`` order), ``state`` (by name),
        ``period``, ``multipliers`` (pairs), ``max_abs_multiplier``, ``stable``,
        ``n_reversals``, ``n_sticks``, ``observables``."""
        return {
            "value": self.value,
            "state0": [float(v) for v in self.state],
            "state": {n: float(v) for n, v in zip(self.system.states, self.state)},
            "period": self.period,
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "max_abs_multiplier": self.max_abs_multiplier,
            "stable": self.stable,
            "n_reversals": self.n_reversals,
            "n_sticks": self.n_sticks,
            "observables": self.observables(),
        }


class _PeriodMap:
    """``x -> P_p(x)`` with its Jacobian, as `fixed_point` takes it."""

    def __init__(self, problem, value):
        self.problem, self.value, self.periods = problem, value, problem.periods

    def __call__(self, x):
        r = self.problem.run(x, self.value)
        return SimpleNamespace(state=r.y, jacobian=r.monodromy, run=r)


class SystemAt:
    """The model at a value of the continued parameter, the last few kept: what the
    problems of another model (`OscillatorForcedProblem`,
    `beltmdsm.continuation.oscillator_cycle.OscillatorCycleProblem`) share; each sets
    ``system``, ``param`` and ``_at = {}``."""

    system: System
    param: str
    _at: dict[float, System]

    def at(self, value: float) -> System:
        """The model at ``value`` (the last few kept)."""
        value = float(value)
        if value not in self._at:
            if len(self._at) > 8:
                self._at.clear()
            self._at[value] = self.system.replace(**{self.param: value})
        return self._at[value]


class OscillatorForcedProblem(SystemAt, Problem):
    """A derived model's forced response of ``k`` periods in one parameter (module docstring).

    Parameters
    ----------
    system : System
        With excitation over the whole range.
    param : str
        One of ``system.params``.
    periods : int
    lo, hi : float
    sx : float
        The state's scale.

    See Also
    --------
    beltmdsm.continuation.problem.Problem : the contract.
    beltmdsm.continuation.oscillator_branch.oscillator_branch : builds and walks it.

    Examples
    --------
    >>> from beltmdsm.oscillator import System, forced_response
    >>> from beltmdsm.continuation.driver import walk
    >>> s = System("belt_1dof", Vb=3.0, mu_s=0.1, alpha_t=0.5, Omega_t=2.0)
    >>> problem = OscillatorForcedProblem(s, "Omega_t", 1, 2.0, 2.1, 1.0)
    >>> first, tangent = problem.start(forced_response(s).state, 2.0, 1.0)
    >>> points, special = walk(problem, first, tangent)
    >>> [(sp.kind, sp.value) for sp in special]
    [('range', 2.1)]
    """

    kind = "forced"

    def __init__(self, system: System, param: str, periods: int, lo: float, hi: float, sx: float):
        self.system, self.param, self.periods = system, param, int(periods)
        self.lo, self.hi, self.sx = float(lo), float(hi), float(sx)
        self.sp = max((self.hi - self.lo) / 10.0, 1e-12)
        self._at: dict[float, System] = {}

    # -- the period map

    def kT(self, value: float) -> float:
        return self.periods * self.at(value).excitation_period()

    def run(self, x, value, variational: bool = True):
        """The hybrid run over ``k T`` from ``x`` at ``value``."""
        return flow(
            self.at(value), 0.0, x, self.kT(value), variational=variational, rtol=TOL, atol=TOL
        )

    def pmap(self, value: float):
        """The period map at ``value`` as `beltmdsm.periodic.newton.fixed_point` takes it."""

        return _PeriodMap(self, value)

    # -- the unknowns, the equations and the points

    def z(self, point) -> NDArray[np.float64]:
        return self.z_of(point.state, point.value)

    def z_of(self, x, value) -> NDArray[np.float64]:
        return np.concatenate([np.asarray(x, float) / self.sx, [value / self.sp]])

    def residual(self, z, extra, iteration) -> Residual:
        n = z.size - 1
        x, value = z[:n] * self.sx, float(z[n] * self.sp)
        run = self.run(x, value)
        G = (run.y - x) / self.sx
        size = float(np.max(np.abs(G)))
        converged = size * self.sx <= NEWTON_TOL * (1.0 + float(np.max(np.abs(x))))
        return Residual(G, size, converged, (x, value, run))

    def jacobian(self, data, column=None) -> NDArray[np.float64]:
        x, value, run = data
        n = x.size
        J = np.empty((n, n + 1))
        J[:, :n] = run.monodromy - np.eye(n)
        if column is None:
            h = 1e-6 * max(1.0, abs(value))
            up = self.run(x, value + h, variational=False).y
            down = self.run(x, value - h, variational=False).y
            column = (up - down) / (2.0 * h) * self.sp / self.sx
        J[:, n] = column
        return J

    def solution(self, data, iteration) -> Step:
        x, value, _ = data
        return Step(self.z_of(x, value), value, self.jacobian(data), iteration, data)

    def point(self, step, tangent_p) -> OscillatorPoint:
        x, value, run = step.data
        return self.point_at(x, value, tangent_p, run)

    def point_at(self, x, value, tangent_p, run=None) -> OscillatorPoint:
        """The point of the response with state ``x`` at phase 0 at ``value``."""
        run = run if run is not None else self.run(x, value)
        mu = np.linalg.eigvals(run.monodromy)
        mu = mu[np.argsort(-np.abs(mu), kind="stable")]
        biggest = float(np.max(np.abs(mu)))
        reversals = sum(1 for _, b, a in run.switches if {b, a} == {1, -1})
        sticks = sum(1 for _, _, a in run.switches if a == STICK)
        return OscillatorPoint(
            float(value), np.array(x, float), mu, biggest, bool(biggest < 1.0), reversals,
            sticks, float(tangent_p), self.kT(value), list(run.switches), self.at(value),
        )  # fmt: skip

    def start(self, x, value, direction):
        """The first point of a walk at ``value`` (``x`` a fixed point there) and its
        unit tangent (``direction``: of the parameter)."""
        run = self.run(x, value)
        first = self.point_at(x, value, direction, run)
        J = self.jacobian((first.state, first.value, run))
        tangent = self.tangent(J, direction=direction)
        first.tangent, first.column = float(tangent[-1]), J[:, -1].copy()
        return first, tangent

    # -- the hooks

    def period(self, point) -> float:
        return point.period

    def check_structure(self, prev, step, ds, jumped):
        if _signature(step.data[2].switches) == prev.signature:
            return None
        if ds > GRAZING_STEP:
            return "the switch structure changes"
        return "the corrector jumps to another structure" if jumped else None

    def same_structure(self, prev, new) -> bool:
        return new.signature == prev.signature

    def range_specials(self, prev, end, tangent, ds, bound, settings):
        if end.signature != prev.signature:
            return [self.crossing(prev, end, [prev])]
        return self.special_between(prev, end, tangent, ds * 0.999, settings)

    def at_bound(self, end, bound):
        try:  # the response at the bound itself
            at = fixed_point(self.pmap(bound), end.state)
            end = self.point_at(at.state, bound, end.tangent, at.image.run)
        except NoPeriodicResponse:
            pass
        return end, range_end(end, bound)

    def crossing(self, prev, new, stretch) -> SpecialPoint:
        """The switch structure changes between ``prev`` and ``new`` (module docstring)."""
        value, accuracy = self._locate(prev, new)
        kind = "stick_onset" if prev.n_sticks == 0 and new.n_sticks > 0 else "grazing"
        what = {
            "stick_onset": "a stick phase appears: "
            + (
                "the holding force at a slip reversal reaches the stick limit"
                if prev.switches
                else "the slip velocity grazes 0 where stick holds"
            ),
            "grazing": "the switch structure changes "
            f"({len(prev.switches)} to {len(new.switches)} switches an orbit)",
        }[kind]
        return SpecialPoint(
            kind, value, accuracy, None, new.multipliers, prev.stable, new.stable,
            f"{what}; the response goes on",
        )  # fmt: skip

    def rescue(self, points, prev, tangent, ds):
        """A pure-slip branch whose corrector fails where its slip margin is about to
        vanish: the stick onset located (`_locate`), and the walk resumed just past it
        from the response shot there (the period map has a kink at the onset, which
        Newton's method does not cross)."""
        if prev.signature or len(points) < 2 or points[-2].signature:
            return None
        a, b = points[-2], prev
        ma, mb = (slip_margin(q.observables()) for q in (a, b))
        if ma == mb:
            return None
        guess = b.value - mb * (b.value - a.value) / (mb - ma)
        direction = 1.0 if b.value >= a.value else -1.0
        ahead = (guess - b.value) * direction
        if ahead < 0 or ahead > 4 * abs(ds) * self.sp or not self.lo < guess < self.hi:
            return None
        value, accuracy = self._locate(b, SimpleNamespace(value=guess + direction * ahead))
        # just past the onset, by the locating tolerance: the integrator finds the touch
        # of v_r = 0 that starts the short stick there (`beltmdsm.oscillator.guards.touch`)
        jump = value + direction * min(
            LOCATE_TOL * max(self.hi - self.lo, 1.0) + accuracy,
            0.5 * abs((self.hi if direction > 0 else self.lo) - value),
        )
        found = self._solve(jump, b.state)
        if found is None:
            try:
                settle = 20 * self.kT(jump)
                found = (forced_response(self.at(jump), b.state, periods=self.periods,
                                         settle=settle).state, None)  # fmt: skip
            except NoPeriodicResponse:
                return None
        new, t_new = self.start(found[0], jump, direction)
        kind = "stick_onset" if new.n_sticks > 0 else "grazing"
        special = SpecialPoint(
            kind, value, accuracy, None, b.multipliers, b.stable, new.stable,
            "the slip velocity grazes 0"
            + ("; a stick phase appears" if kind == "stick_onset" else "")
            + "; the response goes on",
        )  # fmt: skip
        return special, [new], t_new

    def _solve(self, value, guess):
        """The response at ``value`` from ``guess``: (state, run), or None."""
        try:
            at = fixed_point(self.pmap(value), guess)
        except NoPeriodicResponse:
            return None
        return at.state, at.image.run

    def _margin(self, signature):
        """The margin that vanishes where an orbit of ``signature`` changes structure,
        ``margin(value, x)``: the slip margin of a pure-slip orbit
        (`beltmdsm.oscillator.orbit.slip_margin`), ``|H| - mu(0) N`` (the holding force
        against the stick limit, least over the reversals) of an orbit whose switches
        are all slip reversals; None for another structure (located by bisection)."""
        if not signature:
            return lambda v, x: slip_margin(orbit_observables(self.at(v), x, self.kT(v)))
        if all({b, a} == {1, -1} for b, a in signature):
            return self._reversal_margin
        return None

    def _reversal_margin(self, value, x) -> float:
        system, k = self.at(value), self.system.kernels
        least = np.inf
        for n in range(1, len(self.run(x, value, variational=False).switches) + 1):
            r = flow(system, 0.0, x, self.kT(value), stop=lambda sw, c, n=n: c == n,
                     rtol=TOL, atol=TOL)  # fmt: skip
            hold = abs(float(k.holding_force(r.t, r.y, system.p)))
            least = min(least, hold - float(k.stick_limit(r.t, r.y, system.p)))
        return float(least)

    def _locate(self, prev, new) -> tuple[float, float]:
        """Where the structure of ``prev`` ends between ``prev`` and ``new``: the secant
        on the structure's margin (`_margin`), kept inside the bracket (bisection where
        a secant step leaves it, or where the structure has no margin here); to
        `LOCATE_TOL` of the range (the secant's last step where it converges)."""
        inside, outside = prev.value, new.value
        x_in = prev.state
        sig = prev.signature
        margin = self._margin(sig)
        history = [(inside, margin(inside, x_in))] if margin else []
        tol = LOCATE_TOL * max(self.hi - self.lo, 1.0)
        for _ in range(60):
            width = abs(outside - inside)
            if width <= tol:
                break
            v = 0.5 * (inside + outside)
            if len(history) >= 2:
                (v0, m0), (v1, m1) = history[-2:]
                if m1 != m0:
                    guess = v1 - m1 * (v1 - v0) / (m1 - m0)
                    if min(inside, outside) < guess < max(inside, outside):
                        v = guess
            found = self._solve(v, x_in)
            if found is None or _signature(found[1].switches) != sig:
                outside = v
                continue
            x_in, inside = found[0], v
            if margin:
                history.append((v, margin(v, found[0])))
                if abs(history[-1][0] - history[-2][0]) <= tol:
                    break
        if len(history) >= 2 and history[-1][1] != history[-2][1]:
            # the secant's zero of the smooth margin (the structure itself flips within
            # the integrator's accuracy of it); bounded by the last step
            (v0, m0), (v1, m1) = history[-2:]
            zero = v1 - m1 * (v1 - v0) / (m1 - m0)
            return zero, max(abs(zero - v1), 1e-15)
        return 0.5 * (inside + outside), 0.5 * abs(outside - inside)
