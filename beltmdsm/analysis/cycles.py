"""Self-excited cycles: the periodic orbits of Eq. (4) where the excitation is absent.

Without excitation (``alpha_t Omega_t = alpha_n Omega_n = 0``, `beltmdsm.model.is_autonomous`)
Eq. (4) is autonomous: a friction that falls with the sliding speed makes steady
sliding unstable below a belt speed (the Hopf point of the unforced Jacobian,
`generated.unforced.eigenvalues`), and the motion settles on a self-excited cycle,
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
saltation matrix at every switch (`beltmdsm.analysis.variational`), ``f`` the generated
field of the mode where the run ends (`generated.hybrid.vector_field`) and ``grad g``
from the mode's generated Jacobian (`generated.hybrid.mode_jacobian`).

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

**Grazing.** A crossing of ``Vr = 0`` reached with a vanishing rate
(`beltmdsm.analysis.periodmap.GRAZING_RATIO`) is reported as for forced responses:
``grazing`` set, no multiplier (NaN), ``stable`` None.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from generated import hybrid, unforced

from ..integrate.events import StepTooSmall, integrate_events
from ..integrate.switching import Mode, Switching
from ..model import Backend, Model, as_model, initial_state, is_autonomous
from ..settings import SolverSettings
from . import variational
from .periodmap import (
    GRAZING_RATIO,
    NEWTON_TOL,
    RTOL,
    EventPeriod,
    NoPeriodicResponse,
    crossing_ratio,
    orbit_range,
)

__all__ = [
    "Cycle",
    "cycle",
    "seed_cycle",
    "require_autonomous",
    "section_direction",
    "SEED_AMPLITUDE",
    "SEED_PERIODS",
    "SETTLE_TOL",
]

#: Dense samples per period of a shooting run (as `beltmdsm.analysis.periodmap.GeneralMap`).
_DENSE_SAMPLES = 50
#: Halvings of a Newton step before the method counts as stalled, and the iterations
#: over which the residual must halve (as `beltmdsm.analysis.periodmap.fixed_point`).
_LINE_SEARCH = 8
_STAGNATION = 2
#: The seed's perturbation of steady sliding along its unstable direction: the
#: velocity ``X1'`` moved by this fraction of ``|Vb|``.
SEED_AMPLITUDE = 1e-2
#: The seed's run lasts at most this many periods of the unstable pair
#: (``2 pi / Im lambda``), in chunks of `_SEED_CHUNK` periods; a run of 300 s costs about
#: 15 ms compiled, so the bound is generous: from `SEED_AMPLITUDE` at a growth rate of
#: 0.01 1/s (Vb = 1.9, next to the Hopf point of the base Stribeck set) the cycle is
#: reached in about 80 periods.
SEED_PERIODS = 3000
_SEED_CHUNK = 50
#: The run has settled when the state at the section returns to within this (relative
#: to the state's scale): Newton's method converges from there.
SETTLE_TOL = 1e-6
#: The seed's run has decayed to steady sliding when ``X1'`` varies by less than this
#: fraction of ``|Vb|`` over a chunk.
_DECAYED = 1e-9
#: Samples per period of the unstable pair when the seed's run is searched for the section.
_SECTION_SAMPLES = 64
#: Extrema of the seed's run within this fraction of the orbit's velocity range of
#: the deepest one count as the section (the others are lesser extrema of the cycle).
_DEEP = 1e-3


def require_autonomous(model: Model, analysis: str = "a self-excited cycle") -> None:
    """Raise ValueError (one line) unless the model has no excitation and a moving belt."""
    if not is_autonomous(model):
        raise ValueError(
            f"{analysis}: the model is forced (alpha_t Omega_t or alpha_n Omega_n is not "
            "zero): its periodic responses have the excitation's period "
            "(beltmdsm.analysis.floquet.periodic_response)"
        )
    if model["Vb"] == 0:
        raise NoPeriodicResponse(
            f"no self-excited cycle at Vb = 0: the belt is at rest and nothing feeds one "
            f"({analysis})"
        )


def section_direction(model: Model) -> int:
    """``sgn(Vr)`` while sliding steadily, ``-sgn(Vb)``: the slip mode code of the section.

    The section is the extremum of ``X1'`` on this side: a minimum for ``Vb > 0``.
    """
    return -1 if model["Vb"] > 0 else 1


@dataclass(repr=False)
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

    def as_dict(self) -> dict:
        """For JSON: the keys of ``floquet --json`` for a cycle (``autonomous: true``)."""
        stick = (
            "a stick phase collapses the velocity perturbation: one multiplier is 0"
            if self.stick_collapses
            else None
        )
        return {
            "autonomous": True,
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
            run = integrate_events(self.model, settings, y0=x)
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"no self-excited cycle found: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"no self-excited cycle found: {run.message}")
        m = variational.monodromy(run, self.backend)
        period = EventPeriod.of(run, m.switches)
        end = period.final
        f_end = np.array(self.sw.field(T, *end, float(period.modes[-1])), dtype=float)
        return end, m.matrix, period, f_end

    def mode(self, x: NDArray[np.float64]) -> Mode:
        return self.sw.initial_mode(0.0, x)

    def section(self, x: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
        """``(g(x), grad g(x))``: ``X1''`` in the mode of ``x`` and its gradient."""
        mode = float(self.mode(x))
        g = float(self.sw.field(0.0, *x, mode)[1])
        grad = np.array(self.jacobian(0.0, *x, mode), dtype=float).reshape(4, 4)[1]
        return g, grad

    def scale(self, x: NDArray[np.float64]) -> float:
        """The rounding scale of an acceleration at ``x`` (that of the friction cone)."""
        return float(self.sw.scales(0.0, *x)[1])


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
        Without excitation (`beltmdsm.model.is_autonomous`).
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

    Raises
    ------
    ValueError
        For a forced model, a guess that is not 4 finite numbers, or a guess without a
        positive period.
    NoPeriodicResponse
        Where no cycle is found: the seed's reason (steady sliding stable, the run does
        not settle), Newton's method stalling, or converging to steady sliding.
    """
    model = as_model(model)
    require_autonomous(model)
    if guess is None:
        guess, period = seed_cycle(model, backend=backend)
    x = np.array(guess, dtype=float).ravel()
    if x.size != 4 or not np.all(np.isfinite(x)):
        raise ValueError(f"guess must be 4 finite numbers (X1, X1', X2, X2'); got {guess!r}")
    if period is None or not (math.isfinite(period) and period > 0):
        raise ValueError(f"period must be a finite number > 0 with a guess; got {period!r}")
    shoot = _Shooting(model, backend)
    x, T, (end, M, run, f_end), residual, iterations = _newton(shoot, x, float(period), max_iter)
    return _cycle_of(shoot, x, T, M, run, residual, iterations)


def _residuals(shoot, x, T):
    flow = shoot.flow(x, T)
    r = flow[0] - x
    g, grad = shoot.section(x)
    return flow, r, g, grad


def _newton(shoot, x, T, max_iter):
    """Newton's method on the bordered system (module docstring), damped steps."""
    flow, r, g, grad = _residuals(shoot, x, T)
    history = []
    for iteration in range(1, max_iter + 1):
        residual = float(np.max(np.abs(r)))
        scale = 1.0 + float(np.max(np.abs(x)))
        if residual <= NEWTON_TOL * scale and abs(g) <= NEWTON_TOL * shoot.scale(x):
            return x, T, flow, residual, iteration
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
    """The eigenvalue of ``M`` whose eigenvector is closest in direction to ``f``."""
    mu, V = np.linalg.eig(M)
    unit = f / np.linalg.norm(f)
    cosines = np.abs(np.conj(V).T @ unit) / np.linalg.norm(V, axis=0)
    return mu.astype(complex), int(np.argmax(cosines))


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
    mu, k = _trivial_index(M, f)
    others = np.delete(mu, k)
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
        complex(mu[k]),
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


# ---------------------------------------------------------------- the seed


def _unstable_pair(model):
    """The eigenvalue of steady sliding with the largest real part and its eigenvector."""
    J = np.array(
        unforced.jacobian_at_equilibrium(**model.arguments(unforced.jacobian_at_equilibrium)),
        dtype=float,
    ).reshape(4, 4)
    lam, V = np.linalg.eig(J)
    k = int(np.argmax(lam.real))
    return complex(lam[k]), V[:, k]


def seed_cycle(
    model: Model | Mapping[str, Any],
    *,
    t_end: float | None = None,
    perturbation: ArrayLike | None = None,
    backend: Backend | None = None,
) -> tuple[NDArray[np.float64], float]:
    """A state on the section and a period estimate, from a run off steady sliding.

    The run starts at the unforced equilibrium (Eq. 9) moved by ``perturbation``, or
    where none is given along the real part of the eigenvector of the most unstable
    eigenvalue of steady sliding (`generated.unforced.jacobian_at_equilibrium`), its
    velocity by `SEED_AMPLITUDE` of ``|Vb|``. It goes on in chunks until its returns to
    the section (module docstring) repeat to `SETTLE_TOL`; the period is the time
    between the last two returns that match (several turns where the cycle has
    several extrema of the same depth).

    Parameters
    ----------
    model : Model or dict
        Without excitation.
    t_end : float, optional
        The longest run [s]; default `SEED_PERIODS` periods of the unstable pair.
    perturbation : array_like (4,), optional
        The start's offset from the equilibrium (a cycle that coexists with stable
        steady sliding is reached only from far enough).
    backend : {"python", "numba", None}

    Returns
    -------
    state : ndarray (4,)
    period : float

    Raises
    ------
    ValueError
        For a forced model, a perturbation that is not 4 finite numbers, ``t_end <= 0``.
    NoPeriodicResponse
        Naming why: steady sliding is stable and no perturbation is given (a run from it
        decays to it), the run decays to steady sliding, stops, or does not settle on
        a cycle within ``t_end``.
    """
    model = as_model(model)
    require_autonomous(model, "seed_cycle")
    vb = float(model["Vb"])
    lam, vec = _unstable_pair(model)
    omega = abs(lam.imag) if abs(lam.imag) > 0 else float(model["omega1"])
    turn = 2 * math.pi / omega
    if t_end is None:
        t_end = SEED_PERIODS * turn
    if not (math.isfinite(t_end) and t_end > 0):
        raise ValueError(f"t_end must be a finite number > 0; got {t_end!r}")
    x0 = initial_state(model)
    if perturbation is None:
        if lam.real <= 0:
            raise NoPeriodicResponse(
                f"no self-excited cycle from the equilibrium: steady sliding is stable at "
                f"Vb={vb:g} (largest real part of its eigenvalues {lam.real:.3g} 1/s), a "
                "run from it decays to it; a cycle that coexists with it needs a guess or "
                "a perturbation"
            )
        v = np.real(vec)
        if abs(v[1]) < 1e-3 * np.max(np.abs(v)):
            v = np.imag(vec)
        y = x0 + SEED_AMPLITUDE * abs(vb) * v / abs(v[1])
        start = f"the equilibrium perturbed along its unstable direction (lambda = {lam:.4g})"
    else:
        offset = np.array(perturbation, dtype=float).ravel()
        if offset.size != 4 or not np.all(np.isfinite(offset)):
            raise ValueError(f"perturbation must be 4 finite numbers; got {perturbation!r}")
        y = x0 + offset
        start = "the equilibrium perturbed as given"
    sw = Switching(model)
    d = section_direction(model)
    chunk = _SEED_CHUNK * turn
    t, returns, first_amplitude = 0.0, [], None
    while t < t_end:
        t1 = min(t + chunk, t_end)
        settings = SolverSettings(
            t_end=t1, rtol=1e-10, atol=1e-10, dt=(t1 - t) / 400, t_discard=t, backend=backend
        )
        try:
            run = integrate_events(model, settings, y0=y, t0=t)
        except StepTooSmall as err:
            raise NoPeriodicResponse(f"no self-excited cycle from {start}: {err}") from None
        if run.status != "done":
            raise NoPeriodicResponse(f"no self-excited cycle from {start}: {run.message}")
        tr = run.trajectory
        amplitude = _velocity_spread(tr, turn)
        if first_amplitude is None:
            first_amplitude = amplitude
        if amplitude <= _DECAYED * abs(vb):
            raise NoPeriodicResponse(
                f"no self-excited cycle from {start}: the run decays to steady sliding at "
                f"Vb={vb:g} (X1' varies by {amplitude:.1e} m/s at t = {t1:g} s)"
            )
        returns += _section_returns(sw, tr, d, turn)
        found = _settled(returns, amplitude)
        if found is not None:
            return found
        t, y = t1, tr.state(np.array([t1]))[:, 0]
    trend = (
        "; its amplitude shrinks: it decays towards steady sliding"
        if amplitude < 0.5 * first_amplitude
        else ""
    )
    raise NoPeriodicResponse(
        f"no self-excited cycle from {start}: the run does not settle on a cycle in "
        f"{t_end:g} s (its returns to the section do not repeat to {SETTLE_TOL:g}){trend}"
    )


def _velocity_spread(tr, turn):
    """How much ``X1'`` varies over a run (sampled)."""
    t0 = tr.segments[0].t0
    t = np.linspace(t0, tr.t_end, int((tr.t_end - t0) / turn * 16) + 2)
    v = tr.state(t)[1]
    return float(np.max(v) - np.min(v))


def _section_returns(sw, tr, d, turn):
    """``(t, state, depth)`` of the interior extrema of ``X1'`` in the slip mode ``d``.

    ``depth`` is ``d X1'``: the largest is the section's point (module docstring).
    """
    out = []
    step = turn / _SECTION_SAMPLES
    for seg in tr.segments:
        if seg.mode != d or seg.t1 - seg.t0 < 2 * step:
            continue
        t = np.linspace(seg.t0, seg.t1, int((seg.t1 - seg.t0) / step) + 2)
        w = d * tr.state(t)[1]
        for k in np.flatnonzero((w[1:-1] > w[:-2]) & (w[1:-1] >= w[2:])) + 1:
            s = _extremum(sw, tr, d, t[k - 1], t[k + 1])
            state = tr.state(np.array([s]))[:, 0]
            out.append((s, state, d * state[1]))
    return out


def _extremum(sw, tr, d, a, b):
    """Where ``X1''`` vanishes in ``[a, b]`` (slip mode ``d``), by bisection on the field."""

    def accel(s):
        return float(sw.field(s, *tr.state(np.array([s]))[:, 0], float(d))[1])

    fa = accel(a)
    while b - a > 1e-13 * max(1.0, abs(b)):
        m = 0.5 * (a + b)
        fm = accel(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def _settled(returns, amplitude):
    """``(state, period)`` where the last deepest return repeats an earlier one, else None.

    The deepest returns are those within `_DEEP` of the velocity's ``amplitude`` of the
    deepest of the last 20 (a cycle's lesser extrema of ``X1'`` are not its section).
    """
    recent = returns[-20:]
    if len(recent) < 2:
        return None
    top = max(r[2] for r in recent)
    deep = [r for r in recent if r[2] >= top - _DEEP * amplitude]
    t_last, x_last, _ = deep[-1]
    scale = 1.0 + float(np.max(np.abs(x_last)))
    for t_prev, x_prev, _ in reversed(deep[-9:-1]):
        if float(np.max(np.abs(x_last - x_prev))) <= SETTLE_TOL * scale:
            return x_last, float(t_last - t_prev)
    return None
