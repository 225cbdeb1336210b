"""The guards of any model's hybrid system: the mode of a state, the surfaces whose fall
to 0 ends a mode and their rates, the next mode after a switch, and where a step of
`beltmdsm.oscillator.hybrid.flow` crosses or touches a surface.

The surfaces and the choice of the next mode are the contract's (docs/howto/own_model.md),
read through the model's kernels only; `beltmdsm.oscillator.hybrid` states the rules.
A crossing between two of the step's nodes (`beltmdsm.oscillator._dips.NODES`) is
refined by the Illinois method (`beltmdsm.integrate._roots`); a touch that no node shows
(the start of a short stick, a brief excursion of the holding force past the static
limit, a brief take-off) is found by an error model (`touch`): the guard's polynomial on
the step and the error its values show clear what cannot reach 0, and where it may, the
guard's minimum is bracketed by a sign change of its rate along the mode's field
(`rates`). The numba twins of `crossing` and `touch` are in
`beltmdsm.oscillator._compiled`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..integrate._roots import converged, illinois, secant
from . import _dips, _stepper
from .system import FLIGHT, STICK, System

__all__ = [
    "initial_mode", "leave_stick", "surfaces", "rates", "surface_index", "quadratures",
    "next_mode", "slip_sign", "to_stick", "crossing", "touch", "refine",
]  # fmt: skip

#: A surface or its rate as a function of ``(t, y)``; one along a step, of ``t`` only.
Guard = Callable[[float, NDArray], float]
Along = Callable[[float], float]


def initial_mode(system: System, t: float, y: ArrayLike) -> int:
    """The mode of a state: flight where the gap is open (``UNILATERAL``), slip in the
    sign of the slip velocity, stick at 0 slip velocity inside the friction cone."""
    k, p = system.kernels, system.p
    y = np.asarray(y, dtype=float)
    if system.unilateral and k.gap(t, y, p) > 0.0:
        return FLIGHT
    v = k.slip_velocity(t, y, p)
    if v != 0.0:
        return 1 if v > 0.0 else -1
    return leave_stick(system, t, y, default_stick=True)


def leave_stick(system: System, t: float, y: NDArray, default_stick: bool = False) -> int:
    """Stick where the friction cone holds (``default_stick``), else the slip sign."""
    k, p = system.kernels, system.p
    H = k.holding_force(t, y, p)
    if default_stick and abs(H) <= k.stick_limit(t, y, p):
        return STICK
    for m in (-1, 1) if H > 0.0 else (1, -1):
        if m * k.slip_acceleration(t, y, p, m) > 0.0:
            return m
    return -1 if H > 0.0 else 1


def surfaces(system: System, mode: int) -> tuple[Callable, ...]:
    """The functions ``u(t, y)``, positive inside the mode, whose fall to 0 ends it."""
    k, p = system.kernels, system.p
    if mode == FLIGHT:
        return (lambda t, y: k.gap(t, y, p),)
    if mode == STICK:
        first = lambda t, y: k.stick_limit(t, y, p) - abs(k.holding_force(t, y, p))  # noqa: E731
    else:
        first = lambda t, y: mode * k.slip_velocity(t, y, p)  # noqa: E731
    if system.unilateral:
        return (first, lambda t, y: -k.gap(t, y, p))
    return (first,)


def rates(system: System, mode: int) -> tuple[Callable, ...]:
    """The time derivatives of `surfaces` along the mode's field: ``m
    slip_acceleration`` in slip ``m``; in stick, that of ``stick_limit -
    |holding_force|``, the derived rate of ``stick_back`` where the holding force is >=
    0, else of ``stick_forward``; the gap's (``surface_rates``): the rates by which
    `touch` finds grazing touches between samples."""
    k, p = system.kernels, system.p
    index = surface_index(system)
    if mode == FLIGHT:
        g = index["gap"]
        return (lambda t, y: k.surface_rates(t, y, p, mode)[g],)
    if mode == STICK:
        fw, bk = index["stick_forward"], index["stick_back"]

        def first(t, y):
            r = k.surface_rates(t, y, p, mode)
            return r[bk] if k.holding_force(t, y, p) >= 0.0 else r[fw]

    else:
        first = lambda t, y: mode * k.slip_acceleration(t, y, p, mode)  # noqa: E731
    if system.unilateral:
        g = index["gap"]
        return (first, lambda t, y: -k.surface_rates(t, y, p, mode)[g])
    return (first,)


def surface_index(system: System) -> dict[str, int]:
    """Name -> position in the module's ``SURFACES`` (of ``surfaces``, ``surface_rates``)."""
    return {name: i for i, name in enumerate(system.module.SURFACES)}


def quadratures(system: System, mode: int) -> list[int]:
    """The positions in ``SURFACES`` of the surfaces integrated beside the state in
    ``mode`` (stick: the two sides of the cone, module docstring), else none."""
    if mode != STICK:
        return []
    index = surface_index(system)
    return [index["stick_forward"], index["stick_back"]]


def next_mode(system: System, mode: int, surface: int, t: float, y: NDArray) -> int:
    k, p = system.kernels, system.p
    if surface == 1 or (mode == FLIGHT and surface == 0):
        if mode != FLIGHT:
            return FLIGHT
        return initial_mode(system, t, y) if k.gap(t, y, p) <= 0.0 else slip_sign(system, t, y)
    if mode == STICK:
        return leave_stick(system, t, y)
    return STICK if abs(k.holding_force(t, y, p)) <= k.stick_limit(t, y, p) else -mode


def slip_sign(system: System, t: float, y: NDArray) -> int:
    v = system.kernels.slip_velocity(t, y, system.p)
    return 1 if v >= 0.0 else -1


def to_stick(system: System, t: float, y: NDArray) -> NDArray:
    """The state projected onto ``v_r = 0`` along the slip velocity's gradient."""
    k, p = system.kernels, system.p
    w = np.asarray(k.slip_gradient(t, y, p), dtype=float)
    return y - w * (k.slip_velocity(t, y, p) / (w @ w))


def crossing(
    u: Guard, du: Guard, step: _stepper.Step, m: int, u_old: float, armed: bool
) -> tuple[float | None, bool]:
    """The first time in the step where ``u`` falls to <= 0 after being > 0, or None;
    with whether ``u`` has been > 0 (armed) by the step's end. ``u`` is taken at the
    `_dips.NODES` of the step: a fall between two of them is refined by the Illinois
    method, and before it (or anywhere, where none shows) `touch` looks for a fall
    that no node shows. ``du``: the rate of ``u`` along the mode's field (`rates`)."""
    t0, h = step.t, step.h
    t1 = t0 + h
    ts = t0 + h * _dips.NODES
    ts[-1] = t1
    ys = step.many(ts[1:-1])[:, :m]
    values = np.empty(ts.size)
    values[0], values[-1] = u_old, u(t1, step.y_new[:m])
    for i in range(1, ts.size - 1):
        values[i] = u(ts[i], ys[i - 1])
    first = 0
    if not armed:
        inside = np.flatnonzero(values > 0.0)
        if not inside.size:
            return t0, False  # never inside: the field leaves through its own start surface
        first = int(inside[0])
    falls = np.flatnonzero(values[first + 1 :] <= 0.0)
    last = first + int(falls[0]) if falls.size else ts.size - 1
    at = lambda t: u(t, step.at(t)[:m])  # noqa: E731
    if last > first:
        rate = lambda t: du(t, step.at(t)[:m])  # noqa: E731
        tc = touch(at, rate, values, first, last, t0, h, ts)
        if tc is not None:
            return tc, True
    if falls.size:
        return refine(at, ts[last], values[last], ts[last + 1], values[last + 1]), True
    return None, True


def touch(
    at: Along,
    rate: Along,
    values: NDArray,
    first: int,
    last: int,
    t0: float,
    h: float,
    ts: NDArray,
) -> float | None:
    """The first fall of ``u`` to 0 between the nodes ``first`` and ``last`` (``u`` > 0
    at both) that no node shows, or None: the guard's polynomial on the step
    (`beltmdsm.oscillator._dips`) clears what its Bernstein hull holds above its error;
    on a piece of ``1 / 2**DEPTH`` of the interval that it does not clear, the guard's
    own values decide (a fall at the piece's end: refined by the Illinois method), or a
    rise of its ``rate`` through 0 inside it (the minimum, found by the Illinois method
    on the rate, ``u`` tested there)."""
    c = _dips.TO_BERNSTEIN @ values
    e = _dips.error(values)
    xa, xb = _dips.NODES[first], _dips.NODES[last]
    scratch = np.empty_like(c)
    if xa > 0.0:
        _dips.split(c, xa, scratch, c)
    if xb < 1.0:
        _dips.split(c, (xb - xa) / (1.0 - xa), c, scratch)
    stack = [(xa, xb, c, 0)]
    t_pos, u_pos = ts[first], values[first]  # the last time known inside
    while stack:
        lo, hi, c, depth = stack.pop()
        if _dips.lowest(c) > e:
            continue
        if depth < _dips.DEPTH:
            left, right = np.empty_like(c), np.empty_like(c)
            _dips.split(c, 0.5, left, right)
            mid = 0.5 * (lo + hi)
            stack += [(mid, hi, right, depth + 1), (lo, mid, left, depth + 1)]
            continue
        ta = t0 + h * lo if lo > xa else ts[first]
        tb = t0 + h * hi if hi < xb else ts[last]
        ua = u_pos if ta == t_pos else at(ta)
        if ua <= 0.0:
            return refine(at, t_pos, u_pos, ta, ua)
        ub = at(tb)
        if ub <= 0.0:
            return refine(at, ta, ua, tb, ub)
        ra, rb = rate(ta), rate(tb)
        if ra < 0.0 <= rb:
            tm = refine(lambda t: -rate(t), ta, -ra, tb, -rb)
            um = at(tm)
            if um <= 0.0:
                return refine(at, ta, ua, tm, um)
        t_pos, u_pos = tb, ub
    return None


def refine(at: Along, a: float, fa: float, b: float, fb: float) -> float:
    side = 0
    for _ in range(200):
        if converged(a, b):
            break
        c = secant(a, fa, b, fb)
        a, fa, b, fb, side = illinois(a, fa, b, fb, c, at(c), side)
    return b
