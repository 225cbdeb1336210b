"""Self-excited cycles: the periodic orbits of Eq. (4) where the excitation is absent.

Without excitation (``alpha_t Omega_t = alpha_n Omega_n = 0``, `beltmdsm.excitation.is_autonomous`)
Eq. (4) is autonomous: a friction that falls with the sliding speed makes steady
sliding unstable below a belt speed (the Hopf point of the unforced Jacobian,
`beltmdsm.generated.unforced.eigenvalues`), and the motion settles on a self-excited cycle,
pure slip close to the Hopf point, stick-slip further from it. Its period is not
given by any excitation: it is an unknown of the shooting problem, as in AUTO, COCO's
``po`` toolbox or BifurcationKit.

**Shooting with a phase condition.** The unknowns are the state ``x`` (all four,
``(X1, X1', X2, X2')``) and the period ``T``; the equations are ``phi_T(x) - x = 0``
(the event-driven run of `beltmdsm.integrate.events` over ``T``) and a phase condition
``g(x) = 0`` that pins ``x`` to a Poincare section. Newton's method solves the
bordered system

    [[M - I, f(phi_T(x))], [grad g(x), 0]] [dx, dT] = -[phi_T(x) - x, g(x)]

with ``M = d phi_T / dx`` the monodromy of the run by its variational equations and a
saltation matrix at every switch (`beltmdsm.periodic.variational`), ``f`` the generated
field of the mode where the run ends (`beltmdsm.generated.hybrid.vector_field`) and ``grad g``
from the mode's generated Jacobian (`beltmdsm.generated.hybrid.mode_jacobian`).

**The section.** ``g(x) = X1''(x)``, the acceleration in the slip mode of ``x``, at the
extremum of ``X1'`` where the mass slides fastest against the belt: the minimum of
``X1'`` for ``Vb > 0`` (``X1''' > 0`` there), the maximum for ``Vb < 0``. It lies inside
a slip phase on every cycle, pure-slip ones around the Hopf point as stick-slip ones
(the velocity there is as far from the belt's as the orbit goes), never in a stick
phase, where ``X1'' = 0`` holds on a whole interval and the flow collapses the
velocity; it does not need a switch (a pure-slip cycle has none); and it is crossed
transversally wherever the cycle has an amplitude (``X1'''`` is about ``omega1^2``
times it). The seed (`seed_cycle`) chooses the extremum of largest ``|Vr|`` of a
settled run; Newton's method then keeps ``x`` near it (the condition is local).
``X1'' = 0`` holds elsewhere on the orbit too, on a whole stick phase and, under a
friction continuous at ``Vr = 0`` (Stribeck's), where a stick ends: a Newton step that
would leave the section's side (its slip mode, with ``X1'`` at a minimum there for
``Vb > 0``) is shortened.

**Multipliers.** The monodromy ``M`` of the cycle always has the multiplier 1 along the
flow (``M f(x) = f(x)``): the *trivial* multiplier, reported apart (its distance from
1 measures the accuracy of the orbit and its monodromy, about 1e-10 here); it is the
eigenvalue whose eigenvector is closest to ``f(x)``. The others, the multipliers of
the Poincare map, decide stability: ``stable`` where all are inside the unit circle.
A **stick phase gives a multiplier 0**: the saltation matrix into stick zeroes the
velocity perturbation and the end of the stick is fixed by the friction limit, so
every perturbation of the tangential state comes out of the stick as a shift along
the orbit (``stick_collapses``). The normal motion ``(X2, X2')`` is autonomous and sits
at its equilibrium on the cycle; its two multipliers are ``exp(lambda T)`` of the
normal eigenvalues of steady sliding (strongly damped: near 0), and it does not
disturb Newton's method (``M - I`` is regular in those directions).

See docs/modelling.md#self-excited-cycles.

**Grazing.** A crossing of ``Vr = 0`` reached with a vanishing rate
(`beltmdsm.periodic.margins.GRAZING_RATIO`) is reported as for forced responses:
``grazing`` set, no multiplier (NaN), ``stable`` None.

Part of the paper model's engine (issue 39): it runs the paper's model only, on its
states (``beltmdsm.generated.models.paper.STATES``); another registered model runs on
the generic runtime (beltmdsm/oscillator/).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from beltmdsm.generated import hybrid

from .. import arguments
from .._calling import public
from .._tables import DataFrame
from ..arguments import count, number
from ..errors import NoPeriodicResponse
from ..integrate.events import StepTooSmall, integrate_events
from ..integrate.switching import Mode, Switching
from ..model import Backend, Model, as_model
from ..settings import SolverSettings
from ..starts.cycle_seed import (
    SEED_AMPLITUDE,
    SEED_PERIODS,
    SETTLE_TOL,
    require_autonomous,
    section_direction,
    seed_cycle,
    unstable_pair,
)
from . import variational
from .base import RTOL
from .cycle_returns import first_return, rest_step
from .general_map import EventPeriod
from .margins import GRAZING_RATIO, crossing_ratio, orbit_range
from .newton import NEWTON_TOL

__all__ = [
    "Cycle",
    "cycle",
    "seed_cycle",
    "require_autonomous",
    "section_direction",
    "unstable_pair",
    "SEED_AMPLITUDE",
    "SEED_PERIODS",
    "SETTLE_TOL",
]

#: Dense samples per period of a shooting run (as `beltmdsm.periodic.general_map.GeneralMap`).
_DENSE_SAMPLES = 50
#: Halvings of a Newton step before the method counts as stalled, and the iterations
#: over which the residual must halve (as `beltmdsm.periodic.newton.fixed_point`).
_LINE_SEARCH = 8
_STAGNATION = 2
#: The most times a period is shortened to the least one
#: (`beltmdsm.periodic.cycle_returns.first_return`).
_DIVISIONS = 4


@dataclass(repr=False, eq=False)
class Cycle:
    """A self-excited cycle of the autonomous Eq. (4) and its multipliers (module docstring).

    Attributes
    ----------
    model : Model
    state : ndarray (4,)
        ``(X1, X1', X2, X2')`` on the section (the extremum of ``X1'`` of largest ``|Vr|``).
    period : float
        The period found [s].
    monodromy : ndarray (4, 4)
        ``d phi_T / d x`` at ``state``.
    multipliers : ndarray of complex
        The three multipliers of the Poincare map (all but the trivial one), by
        decreasing modulus; NaN where the cycle grazes. A stick phase makes one of them
        0 (``stick_collapses``).
    trivial_multiplier : complex
        The multiplier along the flow, 1 in exact arithmetic: ``|it - 1|`` measures the
        accuracy.
    residual : float
        ``max |phi_T(x) - x|``.
    iterations : int
        Newton iterations.
    n_sticks, n_reversals : int
        Stick phases and reversals of the friction per period.
    x1_range, velocity_range : tuple of float
        ``(min, max)`` of ``X1`` and ``X1'`` over the orbit.
    max_relative_velocity : float
        ``max Vr = max X1' - Vb`` over the orbit: negative on a cycle that slips back
        throughout, 0 where it sticks (stick onset is where it reaches 0 from below).
    stable : bool or None
        ``max |multipliers| < 1``; None where the cycle grazes.
    grazing : dict or None
        ``{"t", "surface", "ratio"}`` of a crossing of ``Vr = 0`` with a vanishing rate.
    stick_time : float
        Time spent sticking per period [s].
    phase_residual : float
        ``|g(x)|``, the phase condition's residual [m/s^2].
    switches : list of (t, before, after, surface)
        The switches over one period from ``state``.
    segments : list of (t0, t1, mode)

    Two cycles are equal only when they are the same object (arrays have no one truth
    value); compare ``period`` and ``state`` to a tolerance instead.

    See Also
    --------
    beltmdsm.periodic.cycle.cycle : finds one.
    beltmdsm.periodic.floquet.Floquet : the same multipliers as `floquet` reports them.

    Examples
    --------
    The stick-slip cycle of Stribeck friction at Vb = 1.5 m/s: one stick a period, the
    trivial multiplier 1 to rounding, and a stick phase that collapses two multipliers
    to 0:

    >>> from beltmdsm import Model, cycle
    >>> c = cycle(Model(friction="stribeck", alpha=0.0, Vb=1.5))
    >>> c.n_sticks, round(c.stick_time, 2), abs(c.trivial_multiplier - 1) < 1e-9
    (1, 1.52, True)
    >>> [float(round(abs(mu), 3)) for mu in c.multipliers]
    [0.224, 0.0, 0.0]
    """

    model: Model
    state: NDArray[np.float64]
    period: float
    monodromy: NDArray[np.float64]
    multipliers: NDArray[np.complex128]
    trivial_multiplier: complex
    residual: float
    iterations: int
    n_sticks: int
    n_reversals: int
    x1_range: tuple[float, float]
    velocity_range: tuple[float, float]
    max_relative_velocity: float
    stable: bool | None
    grazing: dict | None = None
    stick_time: float = 0.0
    phase_residual: float = 0.0
    switches: list = field(default_factory=list)
    segments: list = field(default_factory=list)

    @property
    def stick_collapses(self) -> bool:
        """Whether a stick phase collapses the velocity perturbation (a multiplier 0)."""
        return self.n_sticks > 0

    @property
    def max_abs_multiplier(self) -> float:
        """The largest ``|mu|`` without the trivial multiplier."""
        return float(np.max(np.abs(self.multipliers)))

    def __repr__(self) -> str:
        p = self.model["Vb"]
        return (
            f"Cycle(Vb={p:g}, period={self.period:.6g}, max|mu|={self.max_abs_multiplier:.4g}, "
            f"stable={self.stable}, sticks={self.n_sticks}, reversals={self.n_reversals}, "
            f"|mu_1 - 1|={abs(self.trivial_multiplier - 1):.1e}, residual={self.residual:.1e})"
        )

    def to_pandas(self) -> DataFrame:
        """A `pandas.DataFrame` (needs pandas) of the three multipliers of the Poincare
        map (the trivial one left out), as `beltmdsm.periodic.floquet.Floquet.to_pandas`:
        ``multiplier``, ``abs``, ``angle`` [rad], ``rate = log|mu| / period`` [1/s].

        Examples
        --------
        A stick phase collapses two of them to 0 (to rounding):

        >>> from beltmdsm import Model, cycle
        >>> table = cycle(Model(alpha=0.0, friction="stribeck", Vb=1.5)).to_pandas()
        >>> table["abs"].round(3).tolist(), round(float(table["rate"].iloc[0]), 4)
        ([0.224, 0.0, 0.0], -0.2251)
        """
        from .._tables import multiplier_frame

        return multiplier_frame(self.multipliers, self.period)

    def as_dict(self) -> dict:
        """For JSON: the keys of ``floquet --json`` for a cycle (``autonomous: true``)."""
        stick = (
            "a stick phase collapses the velocity perturbation: one multiplier is 0"
            if self.stick_collapses
            else None
        )
        mu = self.max_abs_multiplier
        return {
            "autonomous": True,
            # the attractor's classification (beltmdsm.attractors.classification): its largest
            # Lyapunov exponent is 0 along the flow where the cycle attracts
            "kind": "periodic",
            "lyapunov": max(0.0, math.log(mu) / self.period) if mu > 0 else 0.0,
            "period": self.period,
            "state0": [float(v) for v in self.state],
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "max_abs_multiplier": self.max_abs_multiplier,
            "trivial_multiplier": [
                float(self.trivial_multiplier.real),
                float(self.trivial_multiplier.imag),
            ],
            "stable": self.stable,
            "grazing": self.grazing,
            "n_sticks": self.n_sticks,
            "n_reversals": self.n_reversals,
            "stick_time": self.stick_time,
            "stick_collapses": stick,
            "x1_range": list(self.x1_range),
            "velocity_range": list(self.velocity_range),
            "max_relative_velocity": self.max_relative_velocity,
            "residual": self.residual,
            "phase_residual": self.phase_residual,
            "newton_iterations": self.iterations,
        }


class _Shooting:
    """The flow of the autonomous model over a time ``T`` and the section, for Newton."""

    def __init__(self, model: Model, backend: Backend | None) -> None:
        self.model, self.backend = model, backend
        self.sw = Switching(model)
        self.jacobian = hybrid.bind_mode_jacobian(
            backend="python", **model.arguments(hybrid.bind_mode_jacobian)
        )
        self.direction = section_direction(model)
        # the run's steps and the variational equation's pieces keep h |lambda| <= 1 for
        # the motion that rests while the mass sticks (`beltmdsm.periodic.cycle_returns.rest_step`):
        # over a long stick the steps would grow to seconds; in slip the state moves,
        # and the step control bounds them
        self.max_step = self.max_piece = rest_step(model)

    def flow(self, x: NDArray[np.float64], T: float):
        """``(phi_T(x), M, period, f(phi_T(x)))``: the run of ``T`` from ``x`` and its monodromy."""
        if not (math.isfinite(T) and T > 0):
            raise NoPeriodicResponse(f"no self-excited cycle found: the period went to {T:.3g}")
        settings = SolverSettings(
            t_end=T,
            rtol=RTOL,
            atol=RTOL,
            dt=T / _DENSE_SAMPLES,
            t_discard=0.0,
            backend=self.backend,
        )
        try:
            run = integrate_events(self.model, settings, y0=x, max_step=self.max_step)
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"no self-excited cycle found: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"no self-excited cycle found: {run.message}")
        m = variational.monodromy(run, self.backend, self.max_piece)
        period = EventPeriod.of(run, m.switches)
        end = period.final
        f_end = np.array(self.sw.field(T, *end, float(period.modes[-1])), dtype=float)
        return end, m.matrix, period, f_end

    def mode(self, x: NDArray[np.float64]) -> Mode:
        return self.sw.initial_mode(0.0, x)

    def section(self, x: NDArray[np.float64]) -> tuple[float, NDArray[np.float64], bool]:
        """``(g(x), grad g(x), on_side)``: ``X1''`` in the mode of ``x``, its gradient, and
        whether ``x`` lies on the section's side (`_on_side`)."""
        mode = self.mode(x)
        f = np.array(self.sw.field(0.0, *x, float(mode)), dtype=float)
        # the generated Jacobian evaluates every mode's branch: Stribeck's exp(|Vr| / v_s)
        # of the other slip direction overflows far from the belt's speed, unused
        with np.errstate(over="ignore"):
            jac = np.array(self.jacobian(0.0, *x, float(mode)), dtype=float)
        grad = jac.reshape(4, 4)[1]
        return float(f[1]), grad, self._on_side(mode, f, grad)

    def _on_side(self, mode: Mode, f: NDArray[np.float64], grad: NDArray[np.float64]) -> bool:
        """In the slip mode of the section, with ``X1'`` at a minimum (``Vb > 0``; a maximum
        for ``Vb < 0``).

        ``X1'' = 0`` holds elsewhere too: on a whole stick phase and, for a friction
        continuous at ``Vr = 0`` (Stribeck's), where a stick ends, at the other extreme of
        ``X1'`` (the belt's speed). The rate ``X1''' = grad g . f`` must have the sign of
        an extremum on the section's side; Newton's steps that leave it are shortened.
        """
        return int(mode) == self.direction and -self.direction * float(grad @ f) > 0

    def scale(self, x: NDArray[np.float64]) -> float:
        """The rounding scale of an acceleration at ``x`` (that of the friction cone)."""
        return float(self.sw.scales(0.0, *x)[1])


@public(models=True)
def cycle(
    model: Model | Mapping[str, Any],
    guess: ArrayLike | None = None,
    period: float | None = None,
    *,
    max_iter: int = 30,
    backend: Backend | None = None,
) -> Cycle:
    """The self-excited cycle of the autonomous model by shooting with a phase condition.

    Parameters
    ----------
    model : Model or dict
        Without excitation (`beltmdsm.excitation.is_autonomous`).
    guess : array_like (4,), optional
        A full state near the section (the extremum of ``X1'`` of largest ``|Vr|``);
        None: `seed_cycle` (a run from perturbed steady sliding).
    period : float, optional
        The period's guess; needed with ``guess``.
    max_iter : int
    backend : {"python", "numba", None}

    Returns
    -------
    Cycle
        At its least period: where the orbit passes its state on the section earlier
        (``period`` a multiple of it), it is shot again with the shorter one
        (`beltmdsm.periodic.cycle_returns.first_return`).

    Raises
    ------
    ValueError
        For a forced model, a guess that is not 4 finite numbers, or a guess without a
        positive period.
    NoPeriodicResponse
        Where no cycle is found: the seed's reason (steady sliding stable, the run does
        not settle), Newton's method stalling, or converging to steady sliding.

    See Also
    --------
    beltmdsm.continuation.branch.branch : the cycles continued in a parameter, from the Hopf point.
    beltmdsm.periodic.floquet.floquet : the same cycle where the model has no excitation.

    Examples
    --------
    >>> from beltmdsm import Model, cycle
    >>> c = cycle(Model(friction="stribeck", alpha=0.0, Vb=1.5))
    >>> round(c.period, 3), c.n_sticks, c.stable
    (6.654, 1, True)
    """
    model = as_model(model)
    max_iter = count("max_iter", max_iter, 1)
    if model.model != "paper":  # another registered model: the generic runtime
        from ..oscillator import api

        return api.cycle(model, guess, period, max_iter)
    if period is not None:
        period = number("period", period, above=0)
        if guess is None:
            raise ValueError("period is the period of the guess: give guess= too, or neither")
    if guess is not None:
        guess = arguments.state("guess", guess, (4,), "X1, X1', X2, X2'")
        if period is None:
            raise ValueError("period must be a finite number > 0 with a guess; got None")
    require_autonomous(model)
    if guess is None:
        guess, period = seed_cycle(model, backend=backend)
    x = np.array(guess, dtype=float).ravel()
    shoot = _Shooting(model, backend)
    x, T, (end, M, run, f_end), residual, iterations = _newton(shoot, x, float(period), max_iter)
    # the least period: where the orbit passes its state earlier, T is a multiple of it
    for _ in range(_DIVISIONS):
        shorter = first_return(shoot.sw, run, x, shoot.direction, T)
        if shorter is None:
            break
        try:
            x, T, (end, M, run, f_end), residual, more = _newton(shoot, x, shorter, max_iter)
        except NoPeriodicResponse:
            break  # passes close by, without closing (near a period doubling)
        iterations += more
    return _cycle_of(shoot, x, T, M, run, residual, iterations)


def _residuals(shoot, x, T):
    g, grad, on_side = shoot.section(x)
    if not on_side:
        raise NoPeriodicResponse(
            "no self-excited cycle found: the state is off the section (not in the slip "
            "mode of the largest |Vr|, or X1' not at its extremum on that side)"
        )
    flow = shoot.flow(x, T)
    r = flow[0] - x
    return flow, r, g, grad


def _newton(shoot, x, T, max_iter):
    """Newton's method on the bordered system (module docstring), damped steps."""
    flow, r, g, grad = _residuals(shoot, x, T)
    history, polished = [], False
    for iteration in range(1, max_iter + 1):
        residual = float(np.max(np.abs(r)))
        scale = 1.0 + float(np.max(np.abs(x)))
        converged = residual <= NEWTON_TOL * scale and abs(g) <= NEWTON_TOL * shoot.scale(x)
        # once within the tolerance, one more step polishes the orbit to the rounding:
        # the trivial multiplier's distance from 1 is the phase condition's residual at
        # the end times the sensitivity of the return time, large after a long stick
        if converged and polished:
            return x, T, flow, residual, iteration
        polished = converged
        merit = max(residual, abs(g))
        history.append(merit)
        if len(history) > _STAGNATION and history[-1] > 0.5 * history[-1 - _STAGNATION]:
            raise NoPeriodicResponse(
                f"no self-excited cycle found: Newton's method stagnates at a residual "
                f"{residual:.2e} (not halved in {_STAGNATION} iterations)"
            )
        end, M, _, f_end = flow
        A = np.zeros((5, 5))
        A[:4, :4] = M - np.eye(4)
        A[:4, 4] = f_end
        A[4, :4] = grad
        rhs = -np.concatenate([r, [g]])
        try:
            step = np.linalg.solve(A, rhs)
        except np.linalg.LinAlgError:
            step = np.linalg.lstsq(A, rhs, rcond=None)[0]
        lam = 1.0
        for _ in range(_LINE_SEARCH):
            x_new, T_new = x + lam * step[:4], T + lam * step[4]
            try:
                trial = _residuals(shoot, x_new, T_new)
            except NoPeriodicResponse:
                lam *= 0.5
                continue
            if max(float(np.max(np.abs(trial[1]))), abs(trial[2])) < merit:
                break
            lam *= 0.5
        else:
            if converged:  # at the rounding already
                return x, T, flow, residual, iteration
            raise NoPeriodicResponse(
                f"no self-excited cycle found: Newton's method stalled at a residual "
                f"{residual:.2e} (no step of {_LINE_SEARCH} halvings reduces it)"
            )
        x, T = x_new, T_new
        flow, r, g, grad = trial
    raise NoPeriodicResponse(
        f"no self-excited cycle found: Newton's method left a residual "
        f"{float(np.max(np.abs(r))):.2e} after {max_iter} iterations"
    )


def _trivial_index(M, f):
    """The eigenvalues of ``M`` and the index of the one whose eigenvector is closest in
    direction to ``f``."""
    mu, V = np.linalg.eig(M)
    unit = f / np.linalg.norm(f)
    cosines = np.abs(np.conj(V).T @ unit) / np.linalg.norm(V, axis=0)
    return mu.astype(complex), int(np.argmax(cosines))


def _multipliers(model, M, f):
    """``(trivial, others)``: the multiplier along the flow ``f`` and the others.

    Where the normal equation is free of the tangential state (the laws' fact
    ``one_way_coupling``, ``beltmdsm.generated.capabilities``) the monodromy is block upper
    triangular, and its eigenvalues are those of the diagonal blocks: computed so, the
    stick's 0 and the trivial 1 of the tangential block keep the rounding of that
    block, not that of the coupling block (which grows like 1e4 at small ``Vb``, where
    a perturbation of the normal force moves the end of a long stick) through a double
    0 with the fast normal multiplier.
    """
    if model.fact("one_way_coupling")[0] and not np.any(M[2:, :2]):
        mu, k = _trivial_index(M[:2, :2], f[:2])
        normal = np.linalg.eigvals(M[2:, 2:]).astype(complex)
        return mu[k], np.concatenate([np.delete(mu, k), normal])
    mu, k = _trivial_index(M, f)
    return mu[k], np.delete(mu, k)


def _cycle_of(shoot, x, T, M, run, residual, iterations):
    """The `Cycle` through ``x`` of period ``T`` from its converged run and monodromy."""
    model = shoot.model
    vr = orbit_range([run], 1)
    if vr[1] - vr[0] <= NEWTON_TOL * (1.0 + abs(model["Vb"])):
        raise NoPeriodicResponse(
            "no self-excited cycle found: Newton's method converges to steady sliding "
            f"(X1' varies by {vr[1] - vr[0]:.1e} m/s over the orbit)"
        )
    f = np.array(shoot.sw.field(0.0, *x, float(shoot.mode(x))), dtype=float)
    trivial, others = _multipliers(model, M, f)
    others = others[np.argsort(-np.abs(others), kind="stable")]
    switches = [(t, b, a, s) for t, b, a, s, _ in run.switches]
    grazing = None
    for t, before, _, surface, state in run.switches:
        if surface == "relative_velocity":
            ratio = crossing_ratio(shoot.sw, t, state, before, surface)
            if ratio < GRAZING_RATIO:
                grazing = {"t": float(t), "surface": surface, "ratio": float(ratio)}
                break
    if grazing is not None:
        others = np.full(others.size, complex(math.nan, math.nan))
        stable = None
    else:
        stable = bool(np.max(np.abs(others)) < 1.0)
    n_rev = sum(
        1
        for _, b, a, s in switches
        if s == "relative_velocity" and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD}
    )
    n_stick = sum(1 for _, _, a, _ in switches if a == Mode.STICK)
    segments = list(zip(run.starts, run.ends, run.modes))
    stick_time = float(sum(t1 - t0 for t0, t1, m in segments if m == Mode.STICK))
    return Cycle(
        model,
        x,
        float(T),
        M,
        others,
        complex(trivial),
        residual,
        iterations,
        n_stick,
        n_rev,
        orbit_range([run], 0),
        vr,
        float(vr[1] - model["Vb"]),
        stable,
        grazing,
        stick_time,
        abs(shoot.section(x)[0]),
        switches,
        segments,
    )
