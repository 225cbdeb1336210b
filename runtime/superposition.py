"""Fast simulation of Eq. (4) by the one-way coupling and superposition.

The normal equation of Eq. (4) does not depend on X1, on Vb or on mu_s, so X2(t) and
the normal force Fn(t) (Eq. 1) are integrated once. The tangential equation,

    X1'' + 2 beta1 omega1 X1' + omega1^2 X1 = f_t(t) - mu_s sgn(Vr) Fn(t),

is linear with a fixed friction direction, so between switches its solution is

    x(t) = Phi(t - t0) d + z_f(t) - mu_s sgn z_n(t),     x = (X1, X1'),

with Phi the closed-form fundamental matrix, z_f and z_n the responses of the
oscillator to f_t and to Fn from rest (integrated once, with the normal equation),
and d fixed by the state at the switch t0. Every switch (Vr = 0, stick, unstick) is
located as a root of these closed forms, first bracketed on a fine grid (with a
check for a double crossing between grid points) and then solved by brentq: no
step is ever taken across a switch, and no right-hand side is called per step.

The shared functions are kept as cubic Hermite splines on a grid of step
``GRID_STEP`` (values and derivatives from the ODE), accurate to about
(omega h)^4 / 384 of the signal; the energy balance of each run checks the result
with the generated power terms. Loss of contact is not handled here: if X2 reaches 0
the caller falls back to the event-driven solve_ivp integrator.
"""
from __future__ import annotations

import functools
import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

from generated import dynamics

from .model import SLIP_BACK, SLIP_FORWARD, STICK, Lean, initial_state
from .trajectory import Segment, Trajectory

__all__ = ["integrate_superposed", "fundamental_matrix", "clear_cache", "GRID_STEP"]

GRID_STEP = 0.005       # spline grid [s]
KNOT_STEP = 10          # grid points per quadrature piece (0.05 s)
_CHUNK = 128            # grid points scanned first for the next switch (then x4)
_SHARED_NAMES = ("beta1", "omega1", "beta2", "omega2", "g", "alpha", "Omega", "alpha_t", "Omega_t", "phase_t",
                 "alpha_n", "Omega_n", "phase_n")


def fundamental_matrix(tau, c1, k1):
    """Phi(tau) = expm(A tau) for A = [[0, 1], [-k1, -c1]], shape (2, 2, n).

    Written as exp(a tau) [C I + S (A - a I)] with a = -c1/2, which is continuous
    through critical damping and never forms cosh of a large argument.
    """
    tau = np.asarray(tau, dtype=float)
    a = -0.5 * c1
    q = a * a - k1
    if q < 0:
        b = np.sqrt(-q)
        e = np.exp(a * tau)
        C, S = e * np.cos(b * tau), e * np.sin(b * tau) / b
    elif q > 0:
        b = np.sqrt(q)
        ep, em = np.exp((a + b) * tau), np.exp((a - b) * tau)
        C, S = 0.5 * (ep + em), 0.5 * (ep - em) / b
    else:
        e = np.exp(a * tau)
        C, S = e, e * tau
    # A - a I = [[-a, 1], [-k1, -c1 - a]]
    return np.array([[C - a * S, S], [-k1 * S, C + (-c1 - a) * S]])


class _Shared:
    """The normal motion and the responses z_f, z_n on a grid, with splines."""

    def __init__(self, p, contact, t_end, method, rtol, atol, h):
        lean = Lean(p, contact)
        c1, k1 = lean.c1, lean.k1
        fn, at = lean.normal_force, p["alpha_t"] * p["Omega_t"] ** 2
        wt, pt = p["Omega_t"], p["phase_t"]
        normal = lean.normal_rhs
        sin = np.sin

        def f(t, s):
            X2, Y2, zf, vf, zn, vn = s
            Fn = fn(X2, Y2)
            return np.array([*normal(t, s[:2]), vf, at * sin(wt * t + pt) - c1 * vf - k1 * zf,
                             vn, Fn - c1 * vn - k1 * zn])

        def lift_off(t, s):
            return s[0]
        lift_off.terminal, lift_off.direction = True, -1.0
        y0 = initial_state(p, contact)
        sol = solve_ivp(f, (0.0, t_end), [y0[2], y0[3], 0, 0, 0, 0], method=method,
                        rtol=rtol, atol=atol, events=lift_off, dense_output=True)
        self.lost_contact = sol.status == 1
        if self.lost_contact:
            return
        n = int(np.ceil(t_end / h - 1e-9))
        self.t = np.linspace(0.0, t_end, n + 1)
        self.h = self.t[1] - self.t[0]
        S = sol.sol(self.t)
        X2, Y2 = S[0], S[1]
        Fn = dynamics.normal_force(X2, Y2, contact=contact, **p)
        ft, fnorm = dynamics.excitation(self.t, **p)
        dS = np.array([Y2, p["g"] + fnorm - Fn, S[3], ft - c1 * S[3] - k1 * S[2],
                       S[5], Fn - c1 * S[5] - k1 * S[4]])
        self.S, self.Fn, self.ft = S, Fn, ft
        self.knots = self.t[::KNOT_STEP]
        self.spline = CubicHermiteSpline(self.t, S, dS, axis=1)


@functools.lru_cache(maxsize=4)
def _shared_cached(key, contact, t_end, method, rtol, atol, h):
    # mu_s and Vb do not enter the normal motion or z_f, z_n: any value will do
    return _Shared(dict(key, mu_s=0.0, Vb=0.0), contact, t_end, method, rtol, atol, h)


def clear_cache():
    """Forget the shared normal motions kept for the last parameter sets.

    A sweep over ``Vb`` reuses one normal motion; a benchmark that times a single
    run from a cold start clears it first.
    """
    _shared_cached.cache_clear()


def _shared(p, contact, settings, h):
    key = tuple((k, p[k]) for k in _SHARED_NAMES)
    return _shared_cached(key, contact, float(settings.t_end), settings.method,
                          float(settings.rtol), float(settings.atol), float(h))


class _Member:
    """Switch-by-switch construction of one run on the shared functions."""

    def __init__(self, p, contact, sh):
        self.p, self.contact, self.sh = p, contact, sh
        lean = Lean(p, contact)
        self.c1, self.k1, self.mu, self.Vb = lean.c1, lean.k1, lean.mu, lean.Vb
        self._normal_force = lean.normal_force
        self.at, self.wt, self.pt = p["alpha_t"] * p["Omega_t"] ** 2, p["Omega_t"], p["phase_t"]

    # closed forms ------------------------------------------------------------
    def slip_state(self, t, t0, d, s, S=None):
        S = self.sh.spline(t) if S is None else S
        hom = np.einsum("ijn,j->in", fundamental_matrix(np.atleast_1d(t - t0), self.c1, self.k1), d)
        ms = self.mu * s
        return hom[0] + S[2] - ms * S[4], hom[1] + S[3] - ms * S[5]

    def free_acceleration(self, t, X1, Y1):
        return self.at * np.sin(self.wt * t + self.pt) - self.c1 * Y1 - self.k1 * X1

    def deviation(self, t, X1, Y1, s):
        S = self.sh.spline(t)
        return np.array([X1 - S[2] + self.mu * s * S[4], Y1 - S[3] + self.mu * s * S[5]])

    # scanning ----------------------------------------------------------------
    def next_slip_event(self, j, t0, d, s, X1a, Y1a):
        """First t > t0 where Vr = 0 in slip direction s, or None."""
        sh, Vb, n = self.sh, self.Vb, self.sh.t.size
        ms = self.mu * s
        # the segment start heads the first chunk, so a crossing before the first
        # grid point is seen too
        ta = np.array([t0])
        ga = s * (np.array([Y1a]) - Vb)
        dga = s * (self.free_acceleration(t0, X1a, Y1a) - ms * np.array([self._fn_at(t0)]))
        chunk = _CHUNK
        while j < n:
            k = min(n, j + chunk)
            tg = sh.t[j:k]
            X1, Y1 = self.slip_state(tg, t0, d, s, sh.S[:, j:k])
            g = np.concatenate([ga, s * (Y1 - Vb)])
            dg = np.concatenate([dga, s * (self.free_acceleration(tg, X1, Y1) - ms * sh.Fn[j:k])])
            tt = np.concatenate([ta, tg])
            start = 0
            while (hit := self._first_crossing(tt[start:], g[start:], dg[start:])) is not None:
                root = self._root_in_cell(*hit, t0, d, s)
                if root is not None:
                    return root
                # a dip of the grid cubic that the closed form does not share: go on
                start = int(np.searchsorted(tt, hit[0], side="right"))
            ta, ga, dga = tt[-1:], g[-1:], dg[-1:]
            j, chunk = k, min(4 * chunk, 16 * _CHUNK)
        return None

    def _root_in_cell(self, a, b, t0, d, s):
        """Root of Vr on [a, b] (inside one spline cell) from scalar closed forms, or None."""
        sh = self.sh
        i = min(int(np.searchsorted(sh.t, a, side="right")) - 1, sh.t.size - 2)
        cf, cn = sh.spline.c[:, i, 3], sh.spline.c[:, i, 5]
        ti, ms, Vb = sh.t[i], self.mu * s, self.Vb
        ha, k1, c1 = -0.5 * self.c1, self.k1, self.c1
        q = ha * ha - k1
        b_ = math.sqrt(abs(q))
        d0, d1 = float(d[0]), float(d[1])

        def fun(t):
            tau, x = t - t0, t - ti
            if q < 0:
                e = math.exp(ha * tau)
                C, S = e * math.cos(b_ * tau), e * math.sin(b_ * tau) / b_
            elif q > 0:
                ep, em = math.exp((ha + b_) * tau), math.exp((ha - b_) * tau)
                C, S = 0.5 * (ep + em), 0.5 * (ep - em) / b_
            else:
                C = math.exp(ha * tau)
                S = C * tau
            hom = -k1 * S * d0 + (C + (-c1 - ha) * S) * d1
            zf = ((cf[0] * x + cf[1]) * x + cf[2]) * x + cf[3]
            zn = ((cn[0] * x + cn[1]) * x + cn[2]) * x + cn[3]
            return hom + zf - ms * zn - Vb
        fa, fb = fun(a), fun(b)
        if fa == 0:
            return a
        if fa * fb > 0:
            return None
        return brentq(fun, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps)

    @staticmethod
    def _first_crossing(t, g, dg):
        """Bracket of the first zero of g (> 0 at t[0]) from grid values and slopes.

        Checks sign changes and, between two positive values, the minimum of the
        cubic Hermite interpolant (a double crossing inside one grid interval).
        """
        h = np.diff(t)
        neg = np.flatnonzero(g[1:] <= 0)
        first = neg[0] if neg.size else None
        cand = np.flatnonzero((dg[:-1] < 0) & (dg[1:] > 0))
        if first is not None:
            cand = cand[cand < first]
        if cand.size:
            # sample the cubic on each candidate interval
            u = np.linspace(0, 1, 17)[1:-1]
            g0, g1 = g[cand][:, None], g[cand + 1][:, None]
            m0, m1 = (dg[cand] * h[cand])[:, None], (dg[cand + 1] * h[cand])[:, None]
            h00, h10 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u
            h01, h11 = -2 * u**3 + 3 * u**2, u**3 - u**2
            cubic = g0 * h00 + m0 * h10 + g1 * h01 + m1 * h11
            dips = np.flatnonzero((cubic <= 0).any(axis=1))
            if dips.size:
                i = cand[dips[0]]
                ui = u[np.argmax(cubic[dips[0]] <= 0)]
                return t[i], t[i] + ui * h[i]
        if first is None:
            return None
        return t[first], t[first + 1]

    def _fn_at(self, t):
        X2, Y2 = self.sh.spline(t)[:2]
        return self._normal_force(float(X2), float(Y2))

    def next_unstick(self, j, ts, X1s):
        """First t > ts where |a_free| exceeds mu_s Fn while sticking, or None."""
        sh, Vb, n = self.sh, self.Vb, self.sh.t.size
        while j < n:
            k = min(n, j + _CHUNK)
            tg = sh.t[j:k]
            margin = self.mu * sh.Fn[j:k] - np.abs(self.free_acceleration(tg, X1s + Vb * (tg - ts), Vb))
            bad = np.flatnonzero(margin < 0)
            if bad.size:
                b = tg[bad[0]]
                a = ts if bad[0] == 0 and j == self._j0 else (tg[bad[0] - 1] if bad[0] else sh.t[j - 1])

                def fun(t):
                    X1 = X1s + Vb * (t - ts)
                    return self.mu * self._fn_at(t) - abs(self.free_acceleration(t, X1, Vb))
                if fun(a) <= 0:
                    return a
                return brentq(fun, a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps)
            j = k
        return None

    def decide(self, t, X1):
        a = self.free_acceleration(t, X1, self.Vb)
        if abs(a) <= self.mu * self._fn_at(t):
            return STICK
        return SLIP_FORWARD if a > 0 else SLIP_BACK

    # segments ------------------------------------------------------------------
    def run(self, max_events=200_000):
        sh, t_end = self.sh, self.sh.t[-1]
        y0 = initial_state(self.p, self.contact)
        t, X1, Y1 = 0.0, y0[0], y0[1]
        vr = Y1 - self.Vb
        mode = self.decide(t, X1) if vr == 0 else (SLIP_FORWARD if vr > 0 else SLIP_BACK)
        segments, events = [], []
        while t < t_end and len(events) < max_events:
            self._j0 = int(np.searchsorted(sh.t, t, side="right"))
            if mode == STICK:
                t1 = self.next_unstick(self._j0, t, X1)
                seg_end = t_end if t1 is None else t1
                segments.append(self._segment(t, seg_end, mode, self._stick_eval(t, X1)))
                if t1 is None:
                    break
                X1 = X1 + self.Vb * (t1 - t)
                t, Y1 = t1, self.Vb
                a = self.free_acceleration(t, X1, Y1)
                mode = SLIP_FORWARD if a > 0 else SLIP_BACK
                events.append((t, "unstick", mode))
                continue
            s = mode
            d = self.deviation(t, X1, Y1, s)
            t1 = self.next_slip_event(self._j0, t, d, s, X1, Y1)
            seg_end = t_end if t1 is None else t1
            segments.append(self._segment(t, seg_end, mode, self._slip_eval(t, d, s)))
            if t1 is None:
                break
            X1n, _ = self.slip_state(np.array([t1]), t, d, s)
            t, X1, Y1 = t1, float(X1n[0]), self.Vb
            mode = self.decide(t, X1)
            events.append((t, "vr_zero", mode))
        if len(events) >= max_events:
            return None
        return Trajectory(segments, self.p, self.contact), events

    def _segment(self, t0, t1, mode, evaluate):
        knots = self.sh.knots
        lo, hi = np.searchsorted(knots, [t0, t1], side="right")
        return Segment(t0, t1, mode, evaluate, knots[lo:hi][knots[lo:hi] < t1])

    def _slip_eval(self, t0, d, s):
        def evaluate(t):
            S = self.sh.spline(t)
            X1, Y1 = self.slip_state(t, t0, d, s, S)
            return np.array([X1, Y1, S[0], S[1]])
        return evaluate

    def _stick_eval(self, ts, X1s):
        def evaluate(t):
            S = self.sh.spline(t)
            return np.array([X1s + self.Vb * (t - ts), np.full(t.shape, self.Vb), S[0], S[1]])
        return evaluate


def integrate_superposed(p, contact, settings, grid_step=GRID_STEP):
    """Trajectory and events of Eq. (4) by superposition, or None where it does not apply.

    None when the normal motion loses contact (X2 reaches 0) or the switching does
    not end; the caller then uses the event-driven solve_ivp integrator.
    """
    sh = _shared(p, contact, settings, grid_step)
    if sh.lost_contact:
        return None
    return _Member(p, contact, sh).run()
