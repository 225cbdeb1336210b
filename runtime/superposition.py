"""Fast simulation of Eq. (4) by the one-way coupling and superposition.

The normal equation of Eq. (4) does not depend on the tangential state, on Vb or on
mu_s, so the normal motion and ``z``, the tangential oscillator's response to its
contact force, are integrated once (`runtime.normal.NormalMotion`, cached across a
sweep). The tangential equation is linear in each mode, so between switches

    (X1, X1')(t) = Phi(t - t0) d + zf(t) - mu_s sgn z(t)

with ``Phi`` the closed-form state-transition matrix and ``zf`` the closed-form
response to the tangential excitation (`generated.oscillator`, derived in
derive/oscillator.py), ``d`` fixed by the state at the switch ``t0``; in flight and
separation the ``z`` term drops (no friction), while sticking ``X1' = Vb``. Every
tangential switch is located on these closed forms (`runtime._superpose.scan`),
every normal switch comes from the normal motion, and the mode after a switch is
chosen by the same rules as in the event-driven integrator (`runtime.switching`).

The superposition hands over to `runtime.events` (with the reason in the run's
message) where its closed forms do not exist: at undamped resonance of the
tangential oscillator (``beta1 = 0``, ``Omega_t = omega1``), where the excitation
response grows without bound.
"""
from __future__ import annotations

from collections import deque

import numpy as np

from generated import oscillator

from . import _superpose
from .events import ZENO_SWITCHES, ZENO_WINDOW, _cone_holds
from .model import initial_state
from .normal import GRID_STEP, clear_cache, normal_motion
from .switching import SURFACE_INDEX, Mode, Switching
from .trajectory import Segment, Trajectory

__all__ = ["integrate_superposed", "clear_cache", "GRID_STEP", "KNOT_STEP"]

#: Grid points of the normal motion per quadrature piece of a segment, at most.
KNOT_STEP = 10
_TANGENTIAL = ("relative_velocity", "stick_forward", "stick_back")


class _Segments:
    """The closed form of every segment, evaluated for many times at once."""

    def __init__(self, normal, stm, exc, Vb):
        self.normal, self.stm, self.exc, self.Vb = normal, stm, exc, Vb
        self.t0, self.stick, self.ms, self.d, self.X1s = [], [], [], [], []

    def add(self, t0, stick, ms, d, X1s):
        self.t0.append(t0)
        self.stick.append(stick)
        self.ms.append(ms)
        self.d.append(d)
        self.X1s.append(X1s)

    def freeze(self):
        self.t0, self.stick, self.ms = (np.array(a, dtype=dt) for a, dt in
                                        ((self.t0, float), (self.stick, bool), (self.ms, float)))
        self.d, self.X1s = np.array(self.d, dtype=float).reshape(-1, 2), np.array(self.X1s)

    def __call__(self, t, index):
        t = np.asarray(t, dtype=float)
        z, v, X2, Y2 = self.normal.evaluate(t)
        zf, vf = self.exc.array(t)
        t0 = self.t0[index]
        P = self.stm.array(t - t0)
        d, ms = self.d[index], self.ms[index]
        X1 = P[:, 0, 0] * d[:, 0] + P[:, 0, 1] * d[:, 1] + zf - ms * z
        Y1 = P[:, 1, 0] * d[:, 0] + P[:, 1, 1] * d[:, 1] + vf - ms * v
        stick = self.stick[index]
        X1 = np.where(stick, self.X1s[index] + self.Vb * (t - t0), X1)
        Y1 = np.where(stick, self.Vb, Y1)
        return np.array([X1, Y1, X2, Y2])


class _SuperposedTrajectory(Trajectory):
    def state(self, t, index=None):
        t = np.asarray(t, dtype=float)
        index = self._index(t) if index is None else index
        return self.closed_form(t, index)


def integrate_superposed(p, contact, tension, settings, y0=None, grid_step=GRID_STEP):
    """Trajectory of Eq. (4) by superposition, or the reason it does not apply.

    Returns
    -------
    (trajectory, events, status, message), or a str saying why the event-driven
    integrator must be used instead.
    """
    backend = settings.backend
    stm = oscillator.bind_state_transition(backend=backend, **p)
    exc = oscillator.bind_excitation_response(backend=backend, **p)
    with np.errstate(divide="ignore", invalid="ignore"):
        finite = np.all(np.isfinite(exc.array(np.array([1.0]))))
    if not finite:
        return ("no closed-form excitation response at undamped resonance "
                "(beta1 = 0, Omega_t = omega1)")
    y = initial_state(p, contact) if y0 is None else np.array(y0, dtype=float)
    normal = normal_motion(p, contact, tension, settings.t_end, settings.rtol, settings.atol,
                           y[2:], backend)
    sw = Switching(p, contact, tension, backend)
    scan = _superpose.compiled() if backend != "python" else None
    scan = scan or _superpose.scan
    watch = {}
    for mode in (Mode.SLIP_BACK, Mode.SLIP_FORWARD, Mode.STICK):
        rows = [(i, SURFACE_INDEX[s], float(d)) for i, (s, d, _)
                in enumerate(sw.guards[mode][2]) if s in _TANGENTIAL]
        watch[mode] = (np.array([r[1] for r in rows], dtype=np.int64),
                       np.array([r[2] for r in rows]), [r[0] for r in rows])
    none = (np.zeros(0, dtype=np.int64), np.zeros(0), [])
    Vb, mu, t_end = p["Vb"], p["mu_s"], float(settings.t_end)
    segs = _Segments(normal, stm, exc, Vb)
    segments, events = [], []
    recent = deque(maxlen=ZENO_SWITCHES)
    # quadrature pieces (energy balance, cycle averages): the normal motion's own steps,
    # which shrink where it is not smooth (X2^(3/2) after a touchdown), with at least
    # one knot every KNOT_STEP grid points
    knots = np.union1d(normal.grid[::KNOT_STEP], normal.t_steps)
    t, X1, Y1 = 0.0, float(y[0]), float(y[1])
    k = normal.segment_at(t)
    mode = _mode_in(sw, normal, k, t, X1, Y1)
    n_zeno = 0
    status, message = "done", "reached t_end"
    args = (normal.grid, normal.on_grid, normal.t_steps, normal.h_steps, normal.y_steps,
            normal.F_steps, stm.kernel, stm.args, exc.kernel, exc.args,
            sw.surfaces.kernel, sw.surfaces.args, sw.rates.kernel, sw.rates.args)
    while t < t_end:
        k = normal.segment_at(t)
        tc = float(normal.switch_t[k + 1])
        stick = mode == Mode.STICK
        ms = mu * int(mode) if mode in (Mode.SLIP_BACK, Mode.SLIP_FORWARD) else 0.0
        z, v = normal.evaluate(np.array([t]))[:2, 0]
        zf, vf = exc(t)
        d = (X1 - zf + ms * z, Y1 - vf + ms * v)
        w, dirs, rows = watch.get(mode, none)
        hit, t_hit = scan(float(mode), stick, ms, w, dirs, t, tc, d[0], d[1], X1, Vb, *args)
        t_stop = float(t_hit) if hit >= 0 else tc
        segs.add(t, stick, ms, d, X1)
        inside = knots[(knots > t) & (knots < t_stop)]
        segments.append(Segment(t, t_stop, mode, None, inside))
        state = segs_state(segs, t_stop, len(segments) - 1)
        if t_stop >= t_end:
            break
        if hit >= 0:
            guard = rows[hit]
            kind = sw.kind(mode, guard)
            state = sw.project(mode, guard, state)
            new = sw.target(mode, guard, t_stop, state)
            recent.append(t_stop)
            if len(recent) == ZENO_SWITCHES and \
                    t_stop - recent[0] <= ZENO_WINDOW * max(1.0, abs(t_stop)):
                if kind == "vr_zero" and _cone_holds(sw, t_stop, state):
                    new, n_zeno = Mode.STICK, n_zeno + 1
                    recent.clear()
                else:
                    events.append((t_stop, kind, new))
                    status = "zeno"
                    message = f"switches accumulate at t = {t_stop:.9g} s; stopped"
                    t = t_stop
                    break
        else:
            kind = normal.switch_kind[k]
            new = _mode_in(sw, normal, k + 1, t_stop, state[0], state[1])
        events.append((t_stop, kind, new))
        if kind == "lift_off" and settings.on_contact_loss == "stop":
            status = "contact_lost"
            message = (f"contact lost (X2 = 0, Eq. 1) at t = {t_stop:.6g} s; stopped as "
                       "requested (on_contact_loss='stop')")
            break
        t, X1, Y1, mode = t_stop, float(state[0]), float(state[1]), new
    segs.freeze()
    trajectory = _SuperposedTrajectory(segments, p, contact, tension)
    trajectory.closed_form = segs
    trajectory.n_zeno = n_zeno
    return trajectory, events, status, message


def segs_state(segs, t, index):
    """The state at ``t`` in segment ``index`` (before `_Segments.freeze`)."""
    z, v, X2, Y2 = segs.normal.evaluate(np.array([t]))[:, 0]
    if segs.stick[index]:
        return np.array([segs.X1s[index] + segs.Vb * (t - segs.t0[index]), segs.Vb, X2, Y2])
    P = segs.stm(t - segs.t0[index])
    zf, vf = segs.exc(t)
    d, ms = segs.d[index], segs.ms[index]
    return np.array([P[0] * d[0] + P[1] * d[1] + zf - ms * z,
                     P[2] * d[0] + P[3] * d[1] + vf - ms * v, X2, Y2])


def _mode_in(sw, normal, k, t, X1, Y1):
    """The mode at ``t`` where the normal motion is in its segment ``k``."""
    normal_mode = normal.switch_mode[k]
    if normal_mode != Mode.SLIP_BACK:
        return normal_mode
    _, _, X2, Y2 = normal.evaluate(np.array([t]))[:, 0]
    return sw.by_relative_velocity(t, np.array([X1, Y1, X2, Y2]))
