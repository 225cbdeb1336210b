"""Exact stability of the forced periodic response: Floquet multipliers with saltation matrices.

The MDSM and the paper's analysis (Sects. 4.2-4.3) linearise about a slow equilibrium
that stands for the response of period ``T = 2 pi / Omega``; the exact counterpart is
the Floquet stability of that periodic response (docs/modelling.md#what-unstable-means).
This module computes it.

* **Structure.** The normal equation of Eq. (4) does not contain the tangential
  state, so the monodromy matrix (the Jacobian of the period map) is block
  triangular, ``[[M_t, M_tn], [0, M_n]]``, and the multipliers are those of the
  tangential block ``M_t`` and of the normal block ``M_n``. The normal block belongs
  to the periodic orbit of the (overdamped) normal motion, which does not depend on
  ``Vb``, ``mu_s`` or the tangential parameters: `normal_orbit` computes it once per
  normal parameter set (cached), by shooting on the normal period map with the
  variational equation (`generated.dynamics.normal_jacobian`) and the normal blocks
  of the saltation matrices.
* **Tangential block.** Between switches the tangential variational flow is the
  closed-form state-transition matrix of the tangential oscillator
  (`generated.oscillator.state_transition`; the identity while sticking, where
  ``X1' = Vb`` holds whatever the perturbation); across a switch it jumps by the
  tangential block of the saltation matrix (`generated.hybrid.saltation`). So
  ``M_t = Phi(T - t_n) S_n ... Phi(t_2 - t_1) S_1 Phi(t_1)``. A stick phase makes
  ``M_t`` singular (the saltation into stick zeroes the velocity perturbation).
* **Periodic response.** `periodic_response` finds the tangential state at phase 0
  that the period map returns to, by Newton's method with ``M_t`` as the Jacobian
  (damped steps), on the closed-form superposition over one period
  (`beltmdsm.integrate.superposition.Superposition`). The first guess is the orbit that slides
  backwards throughout, which is exact where the friction never reverses; a
  continuation passes the previous orbit instead.
* **Grazing.** Where a reversal is reached with a vanishing acceleration (a velocity
  that just touches the belt's), the saltation entry ``a_after / a_before`` diverges
  (the square-root singularity of grazing bifurcations). A switch whose rate is
  below `GRAZING_RATIO` of its scale is reported as grazing, and no multiplier is
  returned for it.

`floquet` reports the multipliers, the largest modulus, the growth rate per unit time
``log|mu| / T``, the frequency of the critical pair ``|arg mu| / T`` (to compare with
omega1; it is defined modulo ``2 pi / T``) and the verdict; `floquet_band` the ranges
of one parameter where the periodic response is unstable, with edges located to a
tolerance by bisection (on ``|mu| = 1`` or on a change of the switch structure at a
grazing point).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import optimize
from scipy.integrate import solve_ivp

from generated import dynamics, hybrid, oscillator

from ..errors import Refused
from ..integrate.normal import normal_key, normal_motion
from ..integrate.superposition import Superposition
from ..integrate.switching import SURFACE_INDEX, Mode, Switching
from ..model import (
    MODEL_PARAMETERS,
    Backend,
    Model,
    as_model,
    check_domain,
    excitation_period,
    initial_state,
)

__all__ = [
    "excitation_period",
    "NoPeriodicResponse",
    "NormalOrbit",
    "normal_orbit",
    "PeriodicResponse",
    "periodic_response",
    "Floquet",
    "floquet",
    "floquet_band",
    "periodic_start",
    "PERTURBATION",
    "GRAZING_RATIO",
    "NEWTON_TOL",
    "MAX_BAND_POINTS",
    "MIN_TOL_ULPS",
]

#: A switch whose rate is below this fraction of its scale is grazing: the saltation
#: entry a_after / a_before then carries a relative rounding error of about
#: ulps / ratio, so below it a multiplier would keep fewer than 8 correct digits.
GRAZING_RATIO = 1e-8
#: Newton's method stops when the period map moves the state by less than this
#: (relative to the state's scale).
NEWTON_TOL = 1e-11
#: Integration tolerance of the periodic orbits.
_RTOL = 1e-12
#: Halvings of a Newton step before the method counts as stalled.
_LINE_SEARCH = 8
#: Iterations over which Newton's residual must halve (converging, it squares; where
#: the orbit has stopped existing, the damped steps creep towards a switch-structure
#: change and the residual shrinks by a few per cent per iteration). 2 finds the same
#: periodic responses as 4 at all 262 points of the quick validation grids and every
#: band of its 16 cases, with a third fewer period maps in a band.
_STAGNATION = 2
#: Periods the normal motion is followed before Newton's method polishes its orbit.
_NORMAL_PERIODS = 200
#: Periods of forward iteration of the tangential period map where Newton's method
#: fails (a stable response next to a grazing point).
FORWARD_PERIODS = 200
#: Forward iteration gives up when its step has not shrunk below this fraction over
#: this many periods: converging to a response with |mu| <= 0.995 it shrinks by 0.88
#: or more, while next to no stable response (another attractor, a drift) it does not.
_FORWARD_WINDOW = 25
_FORWARD_PROGRESS = 0.9


class NoPeriodicResponse(RuntimeError):
    """No periodic response is found (Newton's method and forward iteration fail)."""


@dataclass
class NormalOrbit:
    """The periodic normal motion: ``(X2, X2')`` at phase 0, its monodromy, its switches."""

    state0: np.ndarray
    period: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    switches: list = field(default_factory=list)
    iterations: int = 0


def _normal_flow(model, x0, T):
    """The normal state after ``T``, the monodromy of the normal block and the switches.

    The normal equation with its variational equation (`generated.dynamics`:
    ``normal_rhs``, ``normal_jacobian``), integrated mode by mode; at each switch the
    variational solution jumps by the normal block of the saltation matrix.
    """
    p, kw = model.params, dict(contact=model.contact, tension=model.tension, backend="python")
    rhs = dynamics.bind_normal_rhs(**kw, **p)
    jac = dynamics.bind_normal_jacobian(**kw, **p)
    sw = Switching(model, "python")

    def fun(t, y):
        J = np.array(jac(t, y[0], y[1])).reshape(2, 2)
        return np.concatenate([rhs(t, y[0], y[1]), (J @ y[2:].reshape(2, 2)).ravel()])

    def events_of(mode):
        out = []
        for surface, direction, target in sw.guards[mode][2]:
            if surface not in ("penetration", "contact_force"):
                continue
            index = SURFACE_INDEX[surface]

            def h(t, y, index=index):
                return sw.surfaces(t, 0.0, 0.0, y[0], y[1])[index]

            h.terminal, h.direction = True, float(direction)
            out.append((h, surface, target))
        return out

    mode = _normal_mode(sw, 0.0, x0)
    t, y = 0.0, np.concatenate([x0, np.eye(2).ravel()])
    switches = []
    while t < T:
        watched = events_of(mode)
        sol = solve_ivp(
            fun,
            (t, T),
            y,
            method="DOP853",
            rtol=_RTOL,
            atol=_RTOL,
            events=[h for h, _, _ in watched] or None,
        )
        if sol.status < 0:
            raise NoPeriodicResponse(f"normal orbit: {sol.message}")
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status == 0:
            break
        k = next(i for i, te in enumerate(sol.t_events) if te.size)
        _, surface, target = watched[k]
        if surface == "penetration":
            y[0] = 0.0
        state = np.array([0.0, 0.0, y[0], y[1]])
        if target == hybrid.DECIDE_CONTACT:
            new = _normal_mode(sw, t, y[:2], entering=True)
        else:
            new = Mode[target.upper()]
        S = np.array(
            hybrid.bind_saltation(
                before=mode.name.lower(),
                after=new.name.lower(),
                surface=surface,
                contact=model.contact,
                backend="python",
                **p,
            )(t, *state)
        ).reshape(4, 4)[2:, 2:]
        y[2:] = (S @ y[2:].reshape(2, 2)).ravel()
        switches.append((t, mode, new, surface))
        mode = new
    return y[:2], y[2:].reshape(2, 2), switches


def _normal_mode(sw, t, x, entering=False):
    """Contact (coded SLIP_BACK), flight or separation, for a normal state ``x``.

    ``entering``: the state is on the contact surface, coming into contact.
    """
    X2, Y2 = x
    if not entering and (X2 < 0 or (X2 == 0 and Y2 <= 0)):
        return Mode.FLIGHT
    if sw.tension == "clipped" and sw.pulls(t, np.array([0.0, 0.0, X2, Y2])):
        return Mode.SEPARATED
    return Mode.SLIP_BACK


#: The normal orbits of the last parameter sets, by `beltmdsm.integrate.normal.normal_key`.
_NORMAL_ORBITS: dict = {}
_NORMAL_ORBITS_KEPT = 16


def _normal_orbit(model):
    T = excitation_period(model)
    # The normal motion is overdamped: follow it from the equilibrium until it repeats
    # itself to 1e-4 (a few periods; more where it loses contact), then Newton.
    x = initial_state(model)[2:]
    for _ in range(_NORMAL_PERIODS):
        xT, M, switches = _normal_flow(model, x, T)
        close = np.max(np.abs(xT - x)) <= 1e-4 * (1 + np.max(np.abs(x)))
        x = xT
        if close:
            break
    for iteration in range(1, 31):  # noqa: B007 (the count is reported after the loop)
        xT, M, switches = _normal_flow(model, x, T)
        r = xT - x
        if np.max(np.abs(r)) <= NEWTON_TOL * (1 + np.max(np.abs(x))):
            break
        x = x + np.linalg.lstsq(np.eye(2) - M, r, rcond=None)[0]
    else:
        raise NoPeriodicResponse(
            "the normal motion has no periodic orbit: followed from the "
            f"equilibrium for {_NORMAL_PERIODS} periods and then by Newton's "
            "method it does not repeat itself (it loses contact irregularly)"
        )
    xT, M, switches = _normal_flow(model, x, T)
    return NormalOrbit(x, T, M, np.linalg.eigvals(M), switches, iteration)


def normal_orbit(model: Model) -> NormalOrbit:
    """The periodic orbit of the normal motion (cached per normal parameter set)."""
    key = (normal_key(model), excitation_period(model))
    if key not in _NORMAL_ORBITS:
        if len(_NORMAL_ORBITS) >= _NORMAL_ORBITS_KEPT:
            del _NORMAL_ORBITS[next(iter(_NORMAL_ORBITS))]
        _NORMAL_ORBITS[key] = _normal_orbit(model)
    return _NORMAL_ORBITS[key]


@dataclass
class PeriodicResponse:
    """The periodic response of period ``period`` and its monodromy.

    Attributes
    ----------
    state0 : ndarray (4,)
        ``(X1, X1', X2, X2')`` at phase 0 (``t = 0``, a multiple of the period).
    switches : list of (t, before, after, surface)
        The switches over one period, with the modes (`beltmdsm.integrate.switching.Mode`).
    segments : list of (t0, t1, mode)
    monodromy_tangential, monodromy_normal : ndarray (2, 2)
        The diagonal blocks of the monodromy matrix.
    monodromy : ndarray (4, 4)
        The whole monodromy matrix; its coupling block ``[:2, 2:]`` by central finite
        differences of the period map (relative accuracy about 1e-6), the diagonal
        blocks as above.
    grazing : dict or None
        ``{"t", "surface", "ratio"}`` of a switch reached with a vanishing rate.
    residual : float
        ``|P(x) - x|`` at the returned state.
    iterations : int
    """

    model: Model
    period: float
    state0: np.ndarray
    switches: list
    segments: list
    monodromy_tangential: np.ndarray
    monodromy_normal: np.ndarray
    grazing: dict | None
    residual: float
    iterations: int
    _engine: object = field(default=None, repr=False)

    @property
    def monodromy(self) -> np.ndarray:
        """The 4 x 4 monodromy matrix (see the class docstring)."""
        M = np.zeros((4, 4))
        M[:2, :2] = self.monodromy_tangential
        M[2:, 2:] = self.monodromy_normal
        M[:2, 2:] = _coupling_block(self)
        return M


class _PeriodMap:
    """The tangential period map on the periodic normal motion, and its Jacobian."""

    def __init__(self, model, backend=None):
        self.model, self.p = model, model.params
        self.orbit = normal_orbit(model)
        self.T = self.orbit.period
        normal = normal_motion(model, self.T, _RTOL, _RTOL, self.orbit.state0, backend)
        self.engine = Superposition(model, normal, backend)
        self.stm = oscillator.bind_state_transition(backend=backend, **self.p)
        self.sw = self.engine.sw
        self._saltation = {}
        self.backend = backend

    def saltation(self, before, after, surface):
        key = (before, after, surface)
        if key not in self._saltation:
            self._saltation[key] = hybrid.bind_saltation(
                before=before.name.lower(),
                after=after.name.lower(),
                surface=surface,
                contact=self.model.contact,
                backend=self.backend,
                **self.p,
            )
        return self._saltation[key]

    def __call__(self, x):
        """``(P(x), M_t, run, grazing)`` for the tangential state ``x`` at phase 0."""
        run = self.engine.run(0.0, float(x[0]), float(x[1]), self.T)
        if run.status != "done":
            raise NoPeriodicResponse(f"period map: {run.message}")
        M = np.eye(2)
        grazing = None
        for (t0, t1, mode), switch in zip(
            zip(run.starts, run.ends, run.modes), run.switches + [None]
        ):
            if mode != Mode.STICK:
                M = np.array(self.stm(t1 - t0)).reshape(2, 2) @ M
            if switch is None:
                continue
            t, before, after, surface, state = switch
            S = np.array(self.saltation(before, after, surface)(t, *state)).reshape(4, 4)
            M = S[:2, :2] @ M
            ratio = self._rate_ratio(t, state, before, surface)
            if ratio is not None and ratio < GRAZING_RATIO and grazing is None:
                grazing = {"t": float(t), "surface": surface, "ratio": float(ratio)}
        return run.final[:2], M, run, grazing

    def _rate_ratio(self, t, state, before, surface):
        """``|dh/dt|`` at the switch over its scale (None where S = I regardless)."""
        if surface != "relative_velocity":
            return None
        rate = self.sw.rates(t, *state, float(before))[SURFACE_INDEX[surface]]
        scale = self.sw.scales(t, *state)[SURFACE_INDEX["stick_forward"]]
        return abs(rate) / scale if scale > 0 else 0.0


def _coupling_block(resp):
    """``d x_t(T) / d x_n(0)`` by central differences of the period map (4 normal runs)."""
    x_t, x_n = resp.state0[:2], resp.state0[2:]
    out = np.zeros((2, 2))
    for j in range(2):
        h = 1e-6 * max(1.0, abs(x_n[j]))
        ends = []
        for sign in (1, -1):
            xn = x_n.copy()
            xn[j] += sign * h
            normal = normal_motion(resp.model, resp.period, _RTOL, _RTOL, xn)
            engine = Superposition(resp.model, normal)
            run = engine.run(0.0, float(x_t[0]), float(x_t[1]), resp.period)
            ends.append(run.final[:2])
        out[:, j] = (ends[0] - ends[1]) / (2 * h)
    return out


def _sliding_guess(pmap):
    """The orbit that slides backwards throughout: exact where the friction never reverses.

    Sliding back in contact and free of friction in flight or separation, the
    tangential motion is linear: ``x(T) = Phi(T) x0 + zf(T) + mu_s z(T)``.
    """
    normal = pmap.engine.normal
    z = normal.evaluate(np.array([pmap.T]))[:2, 0]
    zf = np.array(pmap.engine.exc(pmap.T))
    Phi = np.array(pmap.stm(pmap.T)).reshape(2, 2)
    return np.linalg.solve(np.eye(2) - Phi, zf + pmap.p["mu_s"] * z)


def periodic_response(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    max_iter: int = 20,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    **kw: Any,
) -> PeriodicResponse:
    """The periodic response of Eq. (4) by shooting (module docstring).

    Newton's method from ``guess`` (or the backward-sliding orbit); where it fails,
    the period map is iterated forward from the sliding orbit for up to ``forward``
    periods (it converges to a stable periodic response, where Newton's method may
    not, next to a grazing point) and Newton's method polishes the result.

    Parameters
    ----------
    model : Model or dict, optional
        The model (default: the base set); ``**kw``: parameters and options.
    guess : array_like (2,) or PeriodicResponse, optional
        Tangential state ``(X1, X1')`` at phase 0 to start Newton's method from (a
        continuation's predictor); default the backward-sliding orbit.
    max_iter : int
    forward : int
        Periods of forward iteration after Newton's method fails (0: none).
    backend : {"python", "numba", None}

    Returns
    -------
    PeriodicResponse

    Raises
    ------
    ValueError
        For bad parameters, a tension law that does not exist, or an excitation without
        a period (zero or incommensurate frequencies).
    NoPeriodicResponse
        (a RuntimeError) If no periodic response is found.
    """
    model = as_model(model, **kw)
    excitation_period(model)
    pmap = _PeriodMap(model, backend)
    if isinstance(guess, PeriodicResponse):
        guess = guess.state0[:2]
    sliding = _sliding_guess(pmap)
    start = sliding if guess is None else np.array(guess, dtype=float)
    try:
        found = _newton(pmap, start, max_iter)
    except NoPeriodicResponse as newton_failed:
        if not forward:
            raise
        x, steps = sliding, []
        for k in range(int(forward)):
            xT = pmap(x)[0]
            steps.append(float(np.max(np.abs(xT - x))))
            if steps[-1] <= 1e-7 * (1 + np.max(np.abs(x))):
                break
            if k >= _FORWARD_WINDOW and steps[-1] > _FORWARD_PROGRESS * steps[-1 - _FORWARD_WINDOW]:
                raise NoPeriodicResponse(
                    f"{newton_failed}; nor does the period map, iterated from the sliding "
                    f"orbit: its step does not shrink over {_FORWARD_WINDOW} periods "
                    f"({steps[-1 - _FORWARD_WINDOW]:.2e} to {steps[-1]:.2e})"
                ) from None
            x = xT
        else:
            raise NoPeriodicResponse(
                f"{newton_failed}; nor does the period map, iterated "
                f"{forward} periods from the sliding orbit, settle"
            ) from None
        found = _newton(pmap, x, max_iter)
    x, M, run, grazing, residual, iteration = found
    switches = [(t, b, a, s) for t, b, a, s, _ in run.switches]
    segments = list(zip(run.starts, run.ends, run.modes))
    return PeriodicResponse(
        model,
        pmap.T,
        np.concatenate([x, pmap.orbit.state0]),
        switches,
        segments,
        M,
        pmap.orbit.monodromy,
        grazing,
        residual,
        iteration,
        pmap,
    )


def _newton(pmap, x, max_iter):
    """Newton's method with damped steps on ``P(x) - x``, ``M_t - I`` its Jacobian."""
    scale = 1.0 + np.max(np.abs(x))
    xT, M, run, grazing = pmap(x)
    r = xT - x
    history = []
    for iteration in range(1, max_iter + 1):
        residual = float(np.max(np.abs(r)))
        if residual <= NEWTON_TOL * scale:
            return x, M, run, grazing, residual, iteration
        history.append(residual)
        if len(history) > _STAGNATION and history[-1] > 0.5 * history[-1 - _STAGNATION]:
            raise NoPeriodicResponse(
                f"no periodic response found: Newton's method stagnates at a "
                f"residual {residual:.2e} (not halved in {_STAGNATION} "
                "iterations)"
            )
        A = M - np.eye(2)
        try:
            step = -np.linalg.solve(A, r)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(A, r, rcond=None)[0]
        lam = 1.0
        for _ in range(_LINE_SEARCH):
            x_new = x + lam * step
            xT_new, M_new, run_new, grazing_new = pmap(x_new)
            r_new = xT_new - x_new
            if np.max(np.abs(r_new)) < np.max(np.abs(r)):
                break
            lam *= 0.5
        else:
            raise NoPeriodicResponse(
                f"no periodic response found: Newton's method stalled at a "
                f"residual {np.max(np.abs(r)):.2e} (no step of {_LINE_SEARCH} "
                "halvings reduces it)"
            )
        x, xT, M, run, grazing, r = x_new, xT_new, M_new, run_new, grazing_new, r_new
        scale = 1.0 + np.max(np.abs(x))
    raise NoPeriodicResponse(
        f"no periodic response found: Newton's method left a residual "
        f"{np.max(np.abs(r)):.2e} after {max_iter} iterations"
    )


@dataclass
class Floquet:
    """Floquet multipliers of the periodic response and what they say.

    ``multipliers`` are the tangential pair, then the normal pair; NaN where the
    response grazes (``grazing`` is then set and ``stable`` is None).
    """

    multipliers: np.ndarray
    max_abs_multiplier: float
    growth_rate: float
    frequency: float
    stable: bool | None
    n_reversals: int
    n_sticks: int
    grazing: dict | None
    period: float
    response: PeriodicResponse = field(repr=False)

    def as_dict(self) -> dict:
        """The JSON-able summary (the keys of ``python -m derive floquet --json``)."""
        return {
            "multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
            "max_abs_multiplier": self.max_abs_multiplier,
            "growth_rate": self.growth_rate,
            "frequency": self.frequency,
            "stable": self.stable,
            "n_reversals": self.n_reversals,
            "n_sticks": self.n_sticks,
            "grazing": self.grazing,
            "period": self.period,
            "state0": [float(v) for v in self.response.state0],
            "newton_iterations": self.response.iterations,
            "residual": self.response.residual,
        }


def floquet(
    model: Model | Mapping[str, Any] | None = None,
    *,
    guess: Sequence[float] | PeriodicResponse | None = None,
    forward: int = FORWARD_PERIODS,
    backend: Backend | None = None,
    **kw: Any,
) -> Floquet:
    """Floquet multipliers of the periodic response (module docstring).

    Takes the arguments of `periodic_response`.

    Returns
    -------
    Floquet
    """
    model = as_model(model, **kw)
    return _multipliers(periodic_response(model, guess=guess, forward=forward, backend=backend))


#: ``periodic_start``: the run starts on the periodic response with X1 moved by this [m].
PERTURBATION = 1e-2


def periodic_start(
    model: Model, perturbation: float = PERTURBATION, backend: Backend | None = None
) -> np.ndarray:
    """A start state on the periodic response with ``X1`` moved by ``perturbation`` [m].

    An unstable response shows its instability from there, a stable one stays put
    (``simulate --start periodic``).

    Raises
    ------
    ValueError
        For a perturbation that is not a finite number.
    NoPeriodicResponse
        Where no periodic response is found.
    """
    if not (isinstance(perturbation, (int, float)) and math.isfinite(perturbation)):
        raise ValueError(f"perturbation must be a finite number; got {perturbation!r}")
    state = periodic_response(model, backend=backend).state0
    return state + np.array([perturbation, 0.0, 0.0, 0.0])


def _multipliers(resp):
    n_rev = sum(
        1
        for _, b, a, s in resp.switches
        if s == "relative_velocity" and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD}
    )
    n_stick = sum(1 for _, _, a, _ in resp.switches if a == Mode.STICK)
    if resp.grazing is not None:
        nan = float("nan")
        return Floquet(
            np.full(4, complex(nan, nan)),
            nan,
            nan,
            nan,
            None,
            n_rev,
            n_stick,
            resp.grazing,
            resp.period,
            resp,
        )
    mt = np.linalg.eigvals(resp.monodromy_tangential)
    mn = np.linalg.eigvals(resp.monodromy_normal)
    mu = np.concatenate([mt, mn])
    k = int(np.argmax(np.abs(mu)))
    biggest = float(abs(mu[k]))
    growth = math.log(biggest) / resp.period if biggest > 0 else -math.inf
    return Floquet(
        mu,
        biggest,
        growth,
        abs(float(np.angle(mu[k]))) / resp.period,
        bool(biggest < 1.0),
        n_rev,
        n_stick,
        None,
        resp.period,
        resp,
    )


def floquet_band(
    param: str,
    lo: float,
    hi: float,
    model: Model | Mapping[str, Any] | None = None,
    *,
    points: int = 17,
    tol: float = 1e-3,
    backend: Backend | None = None,
    progress: bool = False,
    **kw: Any,
) -> dict:
    """Ranges of ``param`` in ``[lo, hi]`` where the periodic response is unstable.

    A grid of ``points`` values is walked from ``hi`` down to ``lo``, each periodic
    response continued from the previous one. Between neighbours whose state differs
    (found or not, the switch structure: reversals and sticks per period, the
    verdict) the interval is bisected, each midpoint continued from a neighbour,
    until it is below ``tol``: every change is located to ``tol``, and several
    changes between two grid points are all found. A change is an edge of kind
    ``"multiplier"`` (``|mu| = 1`` within one structure), ``"grazing"`` (the
    structure changes: a reversal appears or disappears with a vanishing
    acceleration; the verdict may jump there) or ``"existence"`` (no periodic
    response is found on one side). For ``param = "Vb"`` the grazing point of the
    backward-sliding response is computed exactly: it is that response's largest
    velocity in contact, which does not depend on ``Vb``.

    Changes closer together than ``tol`` cannot be told apart at that tolerance: they
    are one edge, whose sides are the outer sides of the first and the last, and the
    values evaluated between them do not enter the ranges. So the edges' sides agree
    with the ranges at every ``tol``, and a finer ``tol`` only resolves more.

    Parameters
    ----------
    points : int
        the grid walked before the bisection, 2 to `MAX_BAND_POINTS`
    tol : float
        the edges' tolerance, at least `MIN_TOL_ULPS` ulps of the larger end of the
        range (the bisection cannot split a bracket finer than its rounding)
    progress : bool
        show the evaluations on stderr (tqdm) once they take more than 2 s

    Returns
    -------
    dict
        ``unstable``: list of ``[lo, hi]`` where no stable periodic response is found
        (unstable, or none found: the ``no_periodic_response`` ranges are included);
        ``edges``: list of dicts (``value``, ``kind``, ``bracket``,
        ``unstable_below``, ``unstable_above``: whether no stable response is found
        just below and just above); ``grazing_points``; ``no_periodic_response``: ranges
        where no periodic response is found (from the continued neighbours by
        Newton's method, or, next to a stable one, by iterating the period map);
        ``grid``: every evaluated value with ``max_abs_multiplier``, ``stable``,
        ``growth_rate``, ``n_reversals``, ``n_sticks``, ``grazing``; ``failed``: the
        grid values where no periodic response was found, with the reason; ``tol``.

    Raises
    ------
    ValueError
        For an unknown parameter, a range that is not finite, empty or outside the
        parameter's domain, ``points < 2`` or ``tol <= 0``; `beltmdsm.errors.Refused`
        for ``points`` above `MAX_BAND_POINTS` or ``tol`` below the rounding of the
        range (`MIN_TOL_ULPS`).
    """
    if param not in MODEL_PARAMETERS:
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    for end in (lo, hi):
        problem = check_domain(param, end)
        if problem:
            raise ValueError(f"the range [{lo:g}, {hi:g}] leaves the domain: {param} {problem}")
    model = as_model(model, **kw)
    if int(points) < 2 or not tol > 0:
        raise ValueError(f"points must be >= 2 and tol > 0; got {points}, {tol}")
    _check_band_request(lo, hi, int(points), tol)
    from tqdm import tqdm

    bar = tqdm(
        desc=f"floquet-band {param}", unit=" values", disable=not progress, delay=2, leave=False
    )
    failed, seen = [], {}

    def evaluate(v, neighbours, record=False):
        """The Floquet analysis at ``v``, continued from the nearest neighbour found."""
        near = [f for f in neighbours if f is not None]
        guess = near[0].response if near else None
        # forward iteration finds only a stable response: tried next to a stable one
        forward = FORWARD_PERIODS if not near or near[0].stable is not False else 0
        try:
            f = floquet(
                model.replace(**{param: float(v)}), guess=guess, forward=forward, backend=backend
            )
        except NoPeriodicResponse as err:
            if record:
                failed.append({"value": float(v), "reason": str(err)})
            f = None
        seen[float(v)] = f
        bar.update()
        return f

    grid, last = [], None
    for v in np.linspace(hi, lo, int(points)):
        f = evaluate(v, [last], record=True)
        last = f if f is not None else last
        grid.append((float(v), f))
    grid.sort(key=lambda r: r[0])
    edges, grazing_points = [], []

    def refine(a, fa, b, fb):
        # iterative (a stack of brackets, the left one first), not recursive: a fine
        # tol on a wide range needs many levels
        stack = [(a, fa, b, fb)]
        while stack:
            a, fa, b, fb = stack.pop()
            if _state(fa) == _state(fb):
                continue
            if b - a <= tol:
                edges.append(_edge(a, fa, b, fb))
                continue
            g = _sliding_grazing(param, fa, fb)
            if g is not None and a + tol / 4 < g < b - tol / 4:
                below = evaluate(g - tol / 4, [fa, fb])
                above = evaluate(g + tol / 4, [fb, fa])
                grazing_points.append(g)
                edges.append(_edge(g - tol / 4, below, g + tol / 4, above, kind="grazing"))
                stack += [(g + tol / 4, above, b, fb), (a, fa, g - tol / 4, below)]
                continue
            m = _multiplier_step(a, fa, b, fb, tol) if _same_structure(fa, fb) else None
            m = 0.5 * (a + b) if m is None else m
            fm = evaluate(m, [fa, fb] if abs(m - a) <= abs(b - m) else [fb, fa])
            stack += [(m, fm, b, fb), (a, fa, m, fm)]

    try:
        for (a, fa), (b, fb) in zip(grid[:-1], grid[1:]):
            refine(a, fa, b, fb)
    finally:
        bar.close()
    edges = [e for e in sorted(edges, key=lambda e: e["value"]) if e is not None]
    edges, hidden = _merge_close(edges, tol)
    grazing_points += [
        e["value"] for e in edges if e["kind"] == "grazing" and e["value"] not in grazing_points
    ]
    points_seen = sorted((v, f) for v, f in seen.items() if not any(a < v < b for a, b in hidden))
    unstable = _runs(points_seen, edges, lambda f: f is None or f.stable is not True, lo, hi)
    gaps = _runs(points_seen, edges, lambda f: f is None, lo, hi)
    table = [
        {
            "value": v,
            "max_abs_multiplier": f.max_abs_multiplier,
            "stable": f.stable,
            "growth_rate": f.growth_rate,
            "n_reversals": f.n_reversals,
            "n_sticks": f.n_sticks,
            "grazing": f.grazing is not None,
        }
        for v, f in points_seen
        if f is not None
    ]
    return {
        "param": param,
        "unstable": unstable,
        "edges": edges,
        "grazing_points": sorted(grazing_points),
        "no_periodic_response": gaps,
        "grid": table,
        "failed": failed,
        "tension": model.tension,
        "contact": model.contact,
        "tol": float(tol),
    }


#: Most grid points of `floquet_band`: a point takes about 2 ms (6 ms where no
#: periodic response is found; measured at the base set over Vb in [1, 9]), so 10^4
#: points take 20 s to a minute.
MAX_BAND_POINTS = 10**4
#: `floquet_band`'s ``tol`` must span this many ulps of the larger end of the range:
#: below, the midpoint of a bracket rounds to one of its ends and the bisection stops
#: shrinking it.
MIN_TOL_ULPS = 64


def _check_band_request(lo, hi, points, tol):
    """Refuse a grid above `MAX_BAND_POINTS` or a ``tol`` below the range's rounding."""
    if points > MAX_BAND_POINTS:
        raise Refused(
            f"points = {points} is more than MAX_BAND_POINTS = {MAX_BAND_POINTS:.0e} "
            "(beltmdsm/analysis/floquet.py): about 2 ms a point, and every edge is "
            "bisected to tol anyway",
            "points",
        )
    finest = MIN_TOL_ULPS * float(np.spacing(max(abs(lo), abs(hi))))
    if tol < finest:
        raise Refused(
            f"tol = {tol:g} is below what the rounding of the range [{lo:g}, {hi:g}] can "
            f"resolve: at least {MIN_TOL_ULPS} ulps of {max(abs(lo), abs(hi)):g}, "
            f"{finest:.2g} (MIN_TOL_ULPS in beltmdsm/analysis/floquet.py)",
            "tol",
        )


def _merge_close(edges, tol):
    """Edges closer than ``tol`` to the first of their group, merged into one.

    At that tolerance they cannot be told apart. The merged edge takes the outer
    sides (below from the first, above from the last), the union of the brackets,
    the kind "grazing" if one is (its value then that exact grazing point), else
    "existence" if one is, else "multiplier" (its value the middle of the union).

    Returns
    -------
    edges : list of dict
    hidden : list of (lo, hi)
        The merged brackets: the values evaluated strictly inside do not enter the
        ranges (their change is below the resolution).
    """
    groups = []
    for e in edges:
        if groups and e["value"] - groups[-1][0]["value"] <= tol:
            groups[-1].append(e)
        else:
            groups.append([e])
    out, hidden = [], []
    for group in groups:
        if len(group) == 1:
            out.append(group[0])
            continue
        kinds = [e["kind"] for e in group]
        kind = next(k for k in ("grazing", "existence", "multiplier") if k in kinds)
        bracket = [group[0]["bracket"][0], group[-1]["bracket"][1]]
        value = (
            next(e["value"] for e in group if e["kind"] == "grazing")
            if kind == "grazing"
            else 0.5 * (bracket[0] + bracket[1])
        )
        out.append(
            {
                "value": value,
                "kind": kind,
                "bracket": bracket,
                "unstable_below": group[0]["unstable_below"],
                "unstable_above": group[-1]["unstable_above"],
            }
        )
        hidden.append(tuple(bracket))
    return out, hidden


def _same_structure(fa, fb):
    return (
        fa is not None
        and fb is not None
        and fa.stable is not None
        and fb.stable is not None
        and (fa.n_reversals, fa.n_sticks) == (fb.n_reversals, fb.n_sticks)
    )


def _multiplier_step(a, fa, b, fb, tol):
    """The next value for ``|mu| = 1`` within one structure: the secant of ``log|mu|``.

    ``log|mu|`` is smooth there (it is ``T`` times the growth rate), so the secant
    converges in a few steps; kept inside the bracket, a tolerance away from its ends
    so that the bracket shrinks.
    """
    ga, gb = math.log(fa.max_abs_multiplier), math.log(fb.max_abs_multiplier)
    if ga == gb:
        return None
    m = a - ga * (b - a) / (gb - ga)
    return min(max(m, a + tol / 3), b - tol / 3)


def _state(f):
    """What a value's evaluation says: not found, or (structure, verdict)."""
    return None if f is None else (f.n_reversals, f.n_sticks, _verdict(f))


def _verdict(f):
    """'stable', 'unstable' or 'grazing' (no multiplier at a grazing orbit)."""
    if f.stable is None:
        return "grazing"
    return "stable" if f.stable else "unstable"


def _edge(a, fa, b, fb, kind=None):
    """The change between two values closer than the tolerance, classified."""
    if kind is None:
        if fa is None or fb is None:
            kind = "existence"
        elif (fa.n_reversals, fa.n_sticks) != (fb.n_reversals, fb.n_sticks):
            kind = "grazing"
        else:
            kind = "multiplier"
    return {
        "value": 0.5 * (a + b),
        "kind": kind,
        "bracket": [a, b],
        "unstable_below": fa is None or fa.stable is not True,
        "unstable_above": fb is None or fb.stable is not True,
    }


def _runs(points, edges, flag, lo, hi):
    """Maximal ranges of the evaluated values where ``flag`` holds, cut at the edges."""
    out, start, previous = [], None, None
    cuts = sorted(e["value"] for e in edges)
    for v, f in points:
        if flag(f) and start is None:
            inside = [c for c in cuts if previous is not None and previous < c < v]
            start = inside[-1] if inside else (lo if previous is None else v)
        elif not flag(f) and start is not None:
            inside = [c for c in cuts if previous < c < v]
            out.append([start, inside[0] if inside else previous])
            start = None
        previous = v
    if start is not None:
        out.append([start, hi])
    return out


def _sliding_grazing(param, fa, fb):
    """The grazing point of the backward-sliding response between ``a`` and ``b``, or None.

    Where the side above slides backwards throughout (no switch in contact) and the
    side below does not, the sliding response stops at the belt speed equal to its
    largest velocity in contact; it does not depend on ``Vb``. Only for ``param =
    "Vb"``; other parameters are bisected.
    """
    if (
        param != "Vb"
        or fb is None
        or (fb.n_reversals, fb.n_sticks) != (0, 0)
        or (fa is not None and (fa.n_reversals, fa.n_sticks) == (0, 0))
    ):
        return None
    pmap = fb.response._engine
    return _largest_sliding_velocity(pmap)


def _largest_sliding_velocity(pmap):
    """The largest ``X1'`` over one period of the backward-sliding orbit, in contact.

    Out of contact (flight, separation) there is no friction to reverse, so only the
    times in contact count.
    """
    x0 = _sliding_guess(pmap)
    normal = pmap.engine.normal
    grid = normal.grid[normal.grid <= pmap.T]
    segment = np.clip(
        np.searchsorted(normal.switch_t, grid, side="right") - 1, 0, len(normal.switch_mode) - 1
    )
    contact = np.array([normal.switch_mode[k] == Mode.SLIP_BACK for k in segment])
    P = pmap.stm.array(grid)
    mu = pmap.p["mu_s"]
    v = (
        P[:, 1, 0] * x0[0]
        + P[:, 1, 1] * x0[1]
        + normal.on_grid[5, : grid.size]
        + mu * normal.on_grid[1, : grid.size]
    )
    v = np.where(contact, v, -np.inf)
    k = int(np.argmax(v))

    def minus_velocity(t):
        P = np.array(pmap.stm(t)).reshape(2, 2)
        z = normal.at(t)
        return -(P[1] @ x0 + pmap.engine.exc(t)[1] + mu * z[1])

    # refine within the contact segment that holds the largest grid value
    lo = max(grid[max(k - 1, 0)], normal.switch_t[segment[k]])
    hi = min(grid[min(k + 1, grid.size - 1)], normal.switch_t[segment[k] + 1])
    best = optimize.minimize_scalar(
        minus_velocity, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12}
    )
    return float(max(-best.fun, v[k]))
