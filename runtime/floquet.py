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
  (`runtime.superposition.Superposition`). The first guess is the orbit that slides
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

import functools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from generated import dynamics, hybrid, oscillator

from .model import TENSIONS, resolve_parameters
from .parameters import excitation_period
from .normal import NORMAL_NAMES, normal_motion
from .superposition import Superposition
from .switching import SURFACE_INDEX, Mode, Switching

__all__ = ["excitation_period", "NormalOrbit", "normal_orbit", "PeriodicResponse",
           "periodic_response", "Floquet", "floquet", "floquet_band", "GRAZING_RATIO",
           "NEWTON_TOL"]

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
_LINE_SEARCH = 12
#: Periods the normal motion is followed before Newton's method polishes its orbit.
_NORMAL_PERIODS = 200


@dataclass
class NormalOrbit:
    """The periodic normal motion: ``(X2, X2')`` at phase 0, its monodromy, its switches."""
    state0: np.ndarray
    period: float
    monodromy: np.ndarray
    multipliers: np.ndarray
    switches: list = field(default_factory=list)
    iterations: int = 0


def _normal_flow(p, contact, tension, x0, T):
    """The normal state after ``T``, the monodromy of the normal block and the switches.

    The normal equation with its variational equation (`generated.dynamics`:
    ``normal_rhs``, ``normal_jacobian``), integrated mode by mode; at each switch the
    variational solution jumps by the normal block of the saltation matrix.
    """
    rhs = dynamics.bind_normal_rhs(contact=contact, tension=tension, backend="python", **p)
    jac = dynamics.bind_normal_jacobian(contact=contact, tension=tension, backend="python", **p)
    sw = Switching(p, contact, tension, "python")

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
        sol = solve_ivp(fun, (t, T), y, method="DOP853", rtol=_RTOL, atol=_RTOL,
                        events=[h for h, _, _ in watched] or None)
        if sol.status < 0:
            raise RuntimeError(f"normal orbit: {sol.message}")
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
        S = np.array(hybrid.bind_saltation(
            before=mode.name.lower(), after=new.name.lower(), surface=surface,
            contact=contact, backend="python", **p)(t, *state)).reshape(4, 4)[2:, 2:]
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


@functools.lru_cache(maxsize=16)
def _normal_orbit_cached(key, contact, tension):
    p = dict(key, mu_s=0.0, Vb=0.0)
    T = excitation_period(p)
    from .model import initial_state
    # The normal motion is overdamped: follow it from the equilibrium until it repeats
    # itself to 1e-4 (a few periods; more where it loses contact), then Newton.
    x = initial_state(p, contact)[2:]
    for _ in range(_NORMAL_PERIODS):
        xT, M, switches = _normal_flow(p, contact, tension, x, T)
        close = np.max(np.abs(xT - x)) <= 1e-4 * (1 + np.max(np.abs(x)))
        x = xT
        if close:
            break
    for iteration in range(1, 31):
        xT, M, switches = _normal_flow(p, contact, tension, x, T)
        r = xT - x
        if np.max(np.abs(r)) <= NEWTON_TOL * (1 + np.max(np.abs(x))):
            break
        x = x + np.linalg.lstsq(np.eye(2) - M, r, rcond=None)[0]
    else:
        raise RuntimeError("the normal motion has no periodic orbit: followed from the "
                           f"equilibrium for {_NORMAL_PERIODS} periods and then by Newton's "
                           "method it does not repeat itself (it loses contact irregularly)")
    xT, M, switches = _normal_flow(p, contact, tension, x, T)
    return NormalOrbit(x, T, M, np.linalg.eigvals(M), switches, iteration)


def normal_orbit(p, contact="hertz_damp", tension="allowed"):
    """The periodic orbit of the normal motion (cached per normal parameter set)."""
    key = tuple((k, float(p[k])) for k in NORMAL_NAMES + ("alpha", "Omega"))
    return _normal_orbit_cached(key, contact, tension)


@dataclass
class PeriodicResponse:
    """The periodic response of period ``period`` and its monodromy.

    Attributes
    ----------
    state0 : ndarray (4,)
        ``(X1, X1', X2, X2')`` at phase 0 (``t = 0``, a multiple of the period).
    switches : list of (t, before, after, surface)
        The switches over one period, with the modes (`runtime.switching.Mode`).
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
    params: dict
    contact: str
    tension: str
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
    def monodromy(self):
        M = np.zeros((4, 4))
        M[:2, :2] = self.monodromy_tangential
        M[2:, 2:] = self.monodromy_normal
        M[:2, 2:] = _coupling_block(self)
        return M


class _PeriodMap:
    """The tangential period map on the periodic normal motion, and its Jacobian."""

    def __init__(self, p, contact, tension, backend=None):
        self.p, self.contact, self.tension = p, contact, tension
        self.orbit = normal_orbit(p, contact, tension)
        self.T = self.orbit.period
        normal = normal_motion(p, contact, tension, self.T, _RTOL, _RTOL,
                               self.orbit.state0, backend)
        self.engine = Superposition(p, contact, tension, normal, backend)
        self.stm = oscillator.bind_state_transition(backend=backend, **p)
        self.sw = self.engine.sw
        self._saltation = {}
        self.backend = backend

    def saltation(self, before, after, surface):
        key = (before, after, surface)
        if key not in self._saltation:
            self._saltation[key] = hybrid.bind_saltation(
                before=before.name.lower(), after=after.name.lower(), surface=surface,
                contact=self.contact, backend=self.backend, **self.p)
        return self._saltation[key]

    def __call__(self, x):
        """``(P(x), M_t, run, grazing)`` for the tangential state ``x`` at phase 0."""
        run = self.engine.run(0.0, float(x[0]), float(x[1]), self.T)
        if run["status"] != "done":
            raise RuntimeError(f"period map: {run['message']}")
        M = np.eye(2)
        grazing = None
        for (t0, t1, mode), switch in zip(zip(run["starts"], run["ends"], run["modes"]),
                                          run["switches"] + [None]):
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
        return run["final"][:2], M, run, grazing

    def _rate_ratio(self, t, state, before, surface):
        """``|dh/dt|`` at the switch over its scale (None where S = I regardless)."""
        if surface != "relative_velocity":
            return None
        rate = self.sw.rates(t, *state, float(before))[SURFACE_INDEX[surface]]
        scale = self.sw.scales(t, *state)[SURFACE_INDEX["stick_forward"]]
        return abs(rate) / scale if scale > 0 else 0.0


def _coupling_block(resp):
    """``d x_t(T) / d x_n(0)`` by central differences of the period map (4 normal runs)."""
    p, contact, tension = resp.params, resp.contact, resp.tension
    x_t, x_n = resp.state0[:2], resp.state0[2:]
    out = np.zeros((2, 2))
    for j in range(2):
        h = 1e-6 * max(1.0, abs(x_n[j]))
        ends = []
        for sign in (1, -1):
            xn = x_n.copy()
            xn[j] += sign * h
            normal = normal_motion(p, contact, tension, resp.period, _RTOL, _RTOL, xn)
            engine = Superposition(p, contact, tension, normal)
            run = engine.run(0.0, float(x_t[0]), float(x_t[1]), resp.period)
            ends.append(run["final"][:2])
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


def periodic_response(params=None, *, contact="hertz_damp", tension="allowed", guess=None,
                      max_iter=30, backend=None, **overrides):
    """The periodic response of Eq. (4) by shooting (module docstring).

    Parameters
    ----------
    params : dict, optional
        Model parameters (default: the base set); ``**overrides`` too.
    contact, tension : str
    guess : array_like (2,) or PeriodicResponse, optional
        Tangential state ``(X1, X1')`` at phase 0 to start Newton's method from (a
        continuation's predictor); default the backward-sliding orbit.
    max_iter : int
    backend : {"python", "numba", None}

    Returns
    -------
    PeriodicResponse

    Raises
    ------
    ValueError
        For bad parameters, a tension law that does not exist, or an excitation without
        a period (zero or incommensurate frequencies).
    RuntimeError
        If Newton's method does not converge.
    """
    if tension not in TENSIONS:
        raise ValueError(f"tension must be one of {', '.join(map(repr, TENSIONS))}; "
                         f"got {tension!r}")
    p = resolve_parameters(params, contact=contact, **overrides)
    excitation_period(p)
    pmap = _PeriodMap(p, contact, tension, backend)
    if isinstance(guess, PeriodicResponse):
        guess = guess.state0[:2]
    x = _sliding_guess(pmap) if guess is None else np.array(guess, dtype=float)
    scale = 1.0 + np.max(np.abs(x))
    xT, M, run, grazing = pmap(x)
    r = xT - x
    for iteration in range(1, max_iter + 1):
        if np.max(np.abs(r)) <= NEWTON_TOL * scale:
            break
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
            raise RuntimeError(f"no periodic response found: Newton's method stalled at a "
                               f"residual {np.max(np.abs(r)):.2e} (no step of {_LINE_SEARCH} "
                               "halvings reduces it)")
        x, xT, M, run, grazing, r = x_new, xT_new, M_new, run_new, grazing_new, r_new
        scale = 1.0 + np.max(np.abs(x))
    else:
        raise RuntimeError(f"no periodic response found: Newton's method left a residual "
                           f"{np.max(np.abs(r)):.2e} after {max_iter} iterations")
    switches = [(t, b, a, s) for t, b, a, s, _ in run["switches"]]
    segments = list(zip(run["starts"], run["ends"], run["modes"]))
    return PeriodicResponse(p, contact, tension, pmap.T,
                            np.concatenate([x, pmap.orbit.state0]), switches, segments, M,
                            pmap.orbit.monodromy, grazing, float(np.max(np.abs(r))),
                            iteration, pmap)


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

    def as_dict(self):
        """The JSON-able summary (the keys of ``python -m derive floquet --json``)."""
        return {"multipliers": [[float(z.real), float(z.imag)] for z in self.multipliers],
                "max_abs_multiplier": self.max_abs_multiplier,
                "growth_rate": self.growth_rate, "frequency": self.frequency,
                "stable": self.stable, "n_reversals": self.n_reversals,
                "n_sticks": self.n_sticks, "grazing": self.grazing, "period": self.period,
                "state0": [float(v) for v in self.response.state0],
                "newton_iterations": self.response.iterations,
                "residual": self.response.residual}


def floquet(params=None, *, contact="hertz_damp", tension="allowed", guess=None,
            backend=None, **overrides):
    """Floquet multipliers of the periodic response (module docstring).

    Returns
    -------
    Floquet
    """
    resp = periodic_response(params, contact=contact, tension=tension, guess=guess,
                             backend=backend, **overrides)
    return _multipliers(resp)


def _multipliers(resp):
    n_rev = sum(1 for _, b, a, s in resp.switches if s == "relative_velocity"
                and {b, a} == {Mode.SLIP_BACK, Mode.SLIP_FORWARD})
    n_stick = sum(1 for _, _, a, _ in resp.switches if a == Mode.STICK)
    if resp.grazing is not None:
        nan = float("nan")
        return Floquet(np.full(4, complex(nan, nan)), nan, nan, nan, None, n_rev, n_stick,
                       resp.grazing, resp.period, resp)
    mt = np.linalg.eigvals(resp.monodromy_tangential)
    mn = np.linalg.eigvals(resp.monodromy_normal)
    mu = np.concatenate([mt, mn])
    k = int(np.argmax(np.abs(mu)))
    biggest = float(abs(mu[k]))
    growth = math.log(biggest) / resp.period if biggest > 0 else -math.inf
    return Floquet(mu, biggest, growth, abs(float(np.angle(mu[k]))) / resp.period,
                   bool(biggest < 1.0), n_rev, n_stick, None, resp.period, resp)


def floquet_band(param, lo, hi, params=None, *, contact="hertz_damp", tension="allowed",
                 points=17, tol=1e-3, backend=None, **overrides):
    """Ranges of ``param`` in ``[lo, hi]`` where the periodic response is unstable.

    A grid of ``points`` values is walked from ``hi`` down to ``lo``, each periodic
    response continued from the previous one (the backward-sliding orbit where that
    fails). Between neighbours with the same switch structure (numbers of reversals
    and sticks per period) a change of the verdict is bisected on ``|mu| = 1``
    (``"multiplier"`` edge). Where the structure changes, the grazing point (a
    reversal appears with a vanishing acceleration) is bisected on whether the
    simpler orbit, continued, keeps its structure (``"grazing"`` point); the verdict
    may jump there, and a ``|mu| = 1`` crossing on the far side is bisected too.
    Every edge is located to ``tol``.

    Returns
    -------
    dict
        ``unstable``: list of ``[lo, hi]`` where no stable periodic response exists
        (unstable, or none at all: the ``no_periodic_response`` ranges are included);
        ``edges``: list of dicts (``value``,
        ``kind``, ``bracket``, ``unstable_above``); ``grazing_points``: the located
        grazing points; ``grid``: the walked values with ``max_abs_multiplier``,
        ``stable``, ``growth_rate``, ``n_reversals``, ``n_sticks``, ``grazing``;
        ``no_periodic_response``: ranges where no periodic response exists next to a
        grazing point (the far side's orbit ends at a fold before it; they are part
        of ``unstable``: there is no stable periodic response to be on);
        ``failed``: grid values where no periodic response was found, with the reason.

    Raises
    ------
    ValueError
        For an unknown parameter, a bad range, ``points < 2`` or ``tol <= 0``.
    """
    from generated.parameters import KNOWN
    if param not in KNOWN or param == "Vhat":
        raise ValueError(f"param must be a model parameter; got {param!r}")
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"the range must be finite with lo < hi; got [{lo}, {hi}]")
    if int(points) < 2 or not tol > 0:
        raise ValueError(f"points must be >= 2 and tol > 0; got {points}, {tol}")
    base = {**(params or {}), **overrides}
    failed = []

    def evaluate(v, guess, record=True):
        for start in ((guess, None) if guess is not None else (None,)):
            try:
                return floquet({**base, param: float(v)}, contact=contact, tension=tension,
                               guess=start, backend=backend)
            except RuntimeError as err:
                reason = str(err)
        if record:
            failed.append({"value": float(v), "reason": reason})
        return None

    rows, guess = [], None
    for v in np.linspace(hi, lo, int(points)):
        f = evaluate(v, guess)
        if f is not None:
            guess = f.response
            rows.append((float(v), f))
    rows.sort(key=lambda r: r[0])
    edges, grazing_points, gaps = [], [], []
    for (a, fa), (b, fb) in zip(rows[:-1], rows[1:]):
        if _structure(fa) == _structure(fb):
            if _verdict(fa) != _verdict(fb):
                edges.append(_bisect_verdict(evaluate, a, fa, b, fb, tol))
            continue
        simple_low = sum(_structure(fa)) <= sum(_structure(fb))
        g, (a2, fa2), (b2, fb2) = _bisect_structure(evaluate, a, fa, b, fb, tol, simple_low)
        grazing_points.append(g)
        if _verdict(fa2) != _verdict(fb2):
            edges.append({"value": g, "kind": "grazing", "bracket": [a2, b2],
                          "unstable_above": _verdict(fb2) == "unstable"})
        # the far side's orbit, continued towards the grazing point, may end before it
        # (a fold of its own): between the two no periodic response exists
        far = (b, fb) if simple_low else (a, fa)
        end = _bisect_existence(evaluate, far, g, tol)
        if end is not None:
            gaps.append(sorted([end[0], g]))
            far_end = end
        else:
            far_end = (b2, fb2) if simple_low else (a2, fa2)
        # a |mu| = 1 crossing between the grazing point and the far grid point
        ends = sorted([far_end, far], key=lambda r: r[0])
        if _verdict(ends[0][1]) != _verdict(ends[1][1]) and ends[1][0] - ends[0][0] > tol \
                and _structure(ends[0][1]) == _structure(ends[1][1]):
            edges.append(_bisect_verdict(evaluate, *ends[0], *ends[1], tol))
    edges.sort(key=lambda e: e["value"])
    unstable = []
    start = rows[0][0] if rows and _verdict(rows[0][1]) == "unstable" else None
    for e in edges:
        if e["unstable_above"] and start is None:
            start = e["value"]
        elif not e["unstable_above"] and start is not None:
            unstable.append([start, e["value"]])
            start = None
    if start is not None:
        unstable.append([start, rows[-1][0]])
    unstable = _union(unstable + gaps)
    grid = [{"value": v, "max_abs_multiplier": f.max_abs_multiplier, "stable": f.stable,
             "growth_rate": f.growth_rate, "n_reversals": f.n_reversals,
             "n_sticks": f.n_sticks, "grazing": f.grazing is not None} for v, f in rows]
    return {"param": param, "unstable": unstable, "edges": edges,
            "grazing_points": grazing_points, "no_periodic_response": gaps, "grid": grid,
            "failed": failed, "tension": tension, "contact": contact}


def _union(ranges):
    """The union of closed ranges, as sorted disjoint ``[lo, hi]``."""
    out = []
    for lo, hi in sorted(ranges):
        if out and lo <= out[-1][1]:
            out[-1][1] = max(out[-1][1], hi)
        else:
            out.append([lo, hi])
    return out


def _structure(f):
    return (f.n_reversals, f.n_sticks)


def _verdict(f):
    """'stable', 'unstable' or 'grazing' (no multiplier at a grazing orbit)."""
    if f.stable is None:
        return "grazing"
    return "stable" if f.stable else "unstable"


def _bisect_verdict(evaluate, a, fa, b, fb, tol):
    """The ``|mu| = 1`` edge between ``a`` and ``b`` (same structure), to ``tol``."""
    while b - a > tol:
        m = 0.5 * (a + b)
        fm = evaluate(m, fa.response, record=False) or evaluate(m, fb.response)
        if fm is None:
            break
        if _verdict(fm) == _verdict(fa):
            a, fa = m, fm
        else:
            b, fb = m, fm
    return {"value": 0.5 * (a + b), "kind": "multiplier", "bracket": [a, b],
            "unstable_above": _verdict(fb) == "unstable"}


def _bisect_existence(evaluate, start, target, tol):
    """Where the orbit of ``start = (value, Floquet)``, continued towards ``target``, ends.

    None if it reaches within ``tol`` of ``target`` with its structure; else the last
    value where it exists, and its evaluation (to ``tol``).
    """
    a, fa = start
    structure = _structure(fa)
    b = target
    while abs(b - a) > tol:
        m = 0.5 * (a + b)
        fm = evaluate(m, fa.response, record=False)
        if fm is not None and fm.grazing is None and _structure(fm) == structure:
            a, fa = m, fm
        else:
            b = m
    near = target - tol if target > start[0] else target + tol
    if abs(a - near) <= tol:
        return None
    return a, fa


def _bisect_structure(evaluate, a, fa, b, fb, tol, simple_low):
    """The grazing point between ``a`` and ``b``: where the simpler orbit stops existing.

    The simpler side's orbit is continued towards the other side; a midpoint where it
    converges to the same switch structure, without grazing, is on the simpler side.
    Returns the point and the last evaluations on either side.
    """
    simple = fa if simple_low else fb
    while b - a > tol:
        m = 0.5 * (a + b)
        guess = (fa if simple_low else fb).response
        fm = evaluate(m, guess, record=False)
        keeps = fm is not None and fm.grazing is None and \
            _structure(fm) == _structure(simple)
        if keeps == simple_low:
            a, fa = (m, fm) if fm is not None else (m, fa)
        else:
            b, fb = (m, fm) if fm is not None else (m, fb)
    return 0.5 * (a + b), (a, fa), (b, fb)
