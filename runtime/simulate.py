"""Event-driven simulation of Eq. (4) with SciPy's solve_ivp (Sects. 2-3).

The sign function of Eq. (3) makes Eq. (4) piecewise smooth. Instead of stepping
over its discontinuities, the integrator runs one smooth mode at a time and stops
at located events:

* slip- / slip+ (friction direction sgn(Vr) = -1 / +1): the event Vr = X1' - Vb = 0
  ends the mode. At Vr = 0 the friction-free acceleration ``a_free`` (the generated
  ``rhs_branch(sgn=0)[1]``) decides: if ``|a_free| <= mu_s Fn`` the mass sticks,
  otherwise it slips on with sgn = sign(a_free) (a velocity reversal).
* stick: X1' = Vb, X1'' = 0 while the friction limit holds; the event
  ``mu_s Fn - |a_free| = 0`` ends it and the mass slips with sgn = sign(a_free).
  No chattering: the stick is a mode of its own.
* flight: the event X2 = 0 (downwards) is loss of contact (Eq. 1: Fn = 0 for
  X2 <= 0). By default the run continues in flight (no normal force, no friction)
  until X2 = 0 upwards; ``on_contact_loss="stop"`` ends the run at the first
  loss of contact instead, with ``status = "contact_lost"`` and a message.
  In flight there is no friction, so the sign of Vr does not enter the dynamics and
  its changes are not events; at touch-down the friction direction is sign(Vr)
  (or the stick test if Vr = 0).

The normal force of Eq. (1), 2 beta2* omega2* X2^{3/2} X2' + omega2*^2 X2^{3/2}, is
used as printed: it becomes negative (tensile) when the mass moves up fast enough,
which happens at the base set in every excitation cycle. It is not clipped; the
run reports its minimum and the fraction of time it is negative.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from .model import (FLIGHT, MODE_NAMES, SLIP_BACK, SLIP_FORWARD, STICK, Lean,
                    initial_state, resolve_parameters)
from .trajectory import Segment, Trajectory
from . import spectra

__all__ = ["SolverSettings", "Simulation", "simulate", "integrate_events", "classify_regime",
           "omega1_band", "REGIMES", "DEFAULT_T_END", "PEAK_PRESENT_RATIO"]

REGIMES = ("continuous_sliding", "sliding_with_reversals", "stick_slip", "contact_loss")
DEFAULT_T_END = 1000.0
# The omega1 peak counts as present when it reaches this fraction of the excitation
# peak: fixed before looking at any sweep (the paper gives no number).
PEAK_PRESENT_RATIO = 0.01


@dataclass(frozen=True)
class SolverSettings:
    """How a run is computed; part of the cache key of a sweep.

    ``solver``: "events" (solve_ivp on Eq. 4, this module) or "superposition"
    (`runtime.superposition`: the normal equation once, the tangential one by
    superposition; it falls back to "events" where it does not apply).
    ``dt``: sampling step of the returned time series [s]. ``t_discard``: start of
    the steady window [s]; ``None`` means 30 % of ``t_end``.
    """
    solver: str = "superposition"
    method: str = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-10
    t_end: float = DEFAULT_T_END
    t_discard: float | None = None
    dt: float = 0.02
    on_contact_loss: str = "continue"

    def __post_init__(self):
        # The limits live in runtime.parameters, beside the checks of the model.
        from .parameters import MAX_SAMPLES, SOLVE_IVP_METHODS, is_real
        if self.solver not in ("events", "superposition"):
            raise ValueError(f"solver must be 'events' or 'superposition'; got {self.solver!r}")
        if self.on_contact_loss not in ("continue", "stop"):
            raise ValueError("on_contact_loss must be 'continue' or 'stop'; "
                             f"got {self.on_contact_loss!r}")
        if self.method not in SOLVE_IVP_METHODS:
            raise ValueError(f"method must be one of {', '.join(SOLVE_IVP_METHODS)}; "
                             f"got {self.method!r}")
        for name in ("rtol", "atol", "t_end", "dt"):
            value = getattr(self, name)
            if not (is_real(value) and np.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0; got {value!r}")
        if self.t_discard is not None and not (is_real(self.t_discard)
                                               and np.isfinite(self.t_discard)):
            raise ValueError(f"t_discard must be None or a finite number; got {self.t_discard!r}")
        if self.t_end / self.dt > MAX_SAMPLES:
            raise ValueError(f"t_end / dt = {self.t_end / self.dt:.3g} samples is more than "
                             f"MAX_SAMPLES = {MAX_SAMPLES:.0e} (runtime/parameters.py); "
                             "shorten t_end or sample with a larger dt")
        if not 0 <= self.window_start < self.t_end - 20 * self.dt:
            raise ValueError(f"t_discard={self.t_discard!r} must be >= 0 and leave a steady "
                             f"window before t_end={self.t_end!r}")

    @property
    def window_start(self):
        return 0.3 * self.t_end if self.t_discard is None else float(self.t_discard)


@dataclass
class Simulation:
    """A run: the trajectory, samples on a uniform grid and the summary."""
    params: dict
    contact: str
    settings: SolverSettings
    trajectory: Trajectory = field(repr=False)
    t: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    normal_force: np.ndarray = field(repr=False)
    friction: np.ndarray = field(repr=False)
    events: list = field(repr=False)
    status: str
    message: str
    solver_used: str
    wall_s: float = 0.0
    summary: dict = field(default_factory=dict)

    @property
    def window(self):
        """Boolean mask of the samples in the steady window."""
        return self.t >= self.settings.window_start


def _decide_at_zero_slip(lean, t, y):
    """Mode at Vr = 0 in contact: stick if the friction limit holds, else sign(a_free)."""
    a = lean.free_acceleration(t, y)
    if abs(a) <= lean.mu * lean.normal_force(y[2], y[3]):
        return STICK
    return SLIP_FORWARD if a > 0 else SLIP_BACK


def _mode_from_state(lean, t, y):
    if y[2] < 0 or (y[2] == 0 and y[3] <= 0):
        return FLIGHT
    vr = y[1] - lean.Vb
    if vr == 0:
        return _decide_at_zero_slip(lean, t, y)
    return SLIP_FORWARD if vr > 0 else SLIP_BACK


def _events_for(lean, mode):
    """(events, kinds) ending ``mode``; every one is terminal and directional."""
    Vb, mu, Fn, a_free = lean.Vb, lean.mu, lean.normal_force, lean.free_acceleration

    def relative_velocity(t, y):
        return y[1] - Vb

    def lift_off(t, y):
        return y[2]

    def unstick(t, y):
        return mu * Fn(y[2], y[3]) - abs(a_free(t, y))

    for f in (relative_velocity, lift_off, unstick):
        f.terminal = True
    lift_off.direction = -1.0 if mode != FLIGHT else 1.0
    unstick.direction = -1.0
    if mode in (SLIP_BACK, SLIP_FORWARD):
        relative_velocity.direction = -float(mode)
        return [relative_velocity, lift_off], ["vr_zero", "lift_off"]
    if mode == STICK:
        return [unstick, lift_off], ["unstick", "lift_off"]
    return [lift_off], ["touch_down"]


def integrate_events(p, contact="hertz_damp", *, t_end=DEFAULT_T_END, y0=None, method="DOP853",
                     rtol=1e-10, atol=1e-10, on_contact_loss="continue", max_events=200_000):
    """Integrate Eq. (4) mode by mode with located events (see the module docstring).

    Returns
    -------
    trajectory : Trajectory
    events : list of (t, kind, new_mode)
    status : "done", "contact_lost" (stopped, ``on_contact_loss="stop"``) or
        "too_many_events"
    message : str
    """
    lean = Lean(p, contact)
    y = initial_state(p, contact) if y0 is None else np.array(y0, dtype=float)
    t = 0.0
    mode = _mode_from_state(lean, t, y)
    segments, events = [], []
    status, message = "done", "reached t_end"
    while t < t_end:
        if len(events) >= max_events:
            status = "too_many_events"
            message = (f"stopped at t = {t:.6g} s after {max_events} events "
                       "(raise max_events, or the switching accumulates)")
            break
        f = lean.stick_rhs if mode == STICK else lean.branch(0.0 if mode == FLIGHT else mode)
        evs, kinds = _events_for(lean, mode)
        sol = solve_ivp(f, (t, t_end), y, method=method, rtol=rtol, atol=atol, events=evs,
                        dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {sol.t[-1]:.6g} s: {sol.message}")
        t_stop = sol.t[-1]
        segments.append(Segment(t, t_stop, mode, sol.sol, sol.t))
        if sol.status == 0:
            break
        hit = min((te[0], k) for k, te in enumerate(sol.t_events) if te.size)[1]
        y = sol.y_events[hit][0].copy()
        t, kind = t_stop, kinds[hit]
        if kind == "lift_off":
            y[2] = 0.0
            new = FLIGHT
            if on_contact_loss == "stop":
                status = "contact_lost"
                message = (f"contact lost (X2 = 0, Eq. 1) at t = {t:.6g} s; stopped as "
                           "requested (on_contact_loss='stop')")
                events.append((t, kind, new))
                break
        elif kind == "touch_down":
            y[2] = 0.0
            new = _mode_from_state(lean, t, np.array([y[0], y[1], 1.0, y[3]]))
        elif kind == "unstick":
            # |a_free| = mu_s Fn here: the limit is just exceeded, slip along a_free
            y[1] = lean.Vb
            new = SLIP_FORWARD if lean.free_acceleration(t, y) > 0 else SLIP_BACK
        else:
            y[1] = lean.Vb
            new = _decide_at_zero_slip(lean, t, y)
        events.append((t, kind, new))
        mode = new
    return Trajectory(segments, p, contact), events, status, message


def classify_regime(trajectory, t0, t1):
    """Regime in the window [t0, t1] from the time spent in each mode.

    contact_loss (any flight) > stick_slip (any stick) > sliding_with_reversals
    (both slip directions) > continuous_sliding.
    """
    spent = trajectory.time_in_modes(t0, t1)
    if spent[FLIGHT] > 0:
        return "contact_loss"
    if spent[STICK] > 0:
        return "stick_slip"
    if spent[SLIP_BACK] > 0 and spent[SLIP_FORWARD] > 0:
        return "sliding_with_reversals"
    return "continuous_sliding"


def omega1_band(p):
    """Band ``(low, high)`` [rad/s] around omega1 in which the omega1 peak is read.

    Half-width 0.25 omega1, narrowed to keep clear of the excitation lines
    ``Omega_t`` and ``Omega_n``; ``None`` when an excitation line sits at omega1.
    """
    w1 = p["omega1"]
    half = 0.25 * w1
    for line in (p["Omega_t"], p["Omega_n"]):
        if line > 0:
            half = min(half, 0.5 * abs(w1 - line))
    return (w1 - half, w1 + half) if half > 0 else None


def summarize(sim):
    """Regime, spectral peaks, energy balance and counts of a run (``sim.summary``)."""
    p, s = sim.params, sim.settings
    t0, t1 = s.window_start, sim.trajectory.t_end
    win = sim.window
    if win.sum() < 16:
        # stopped (contact lost) before the steady window: the counts and the
        # regime cover the whole run, there is no spectrum
        t0, win = 0.0, np.ones_like(win)
    v = sim.y[1, win]
    out = {"status": sim.status, "message": sim.message, "solver": sim.solver_used,
           "regime": ("contact_loss" if sim.status == "contact_lost"
                      else classify_regime(sim.trajectory, t0, t1)),
           "t_end": float(t1), "t_discard": float(t0)}
    resolution = 2 * np.pi / (v.size * s.dt)
    bands, keys = [], []
    band = omega1_band(p)
    if band is not None and band[1] - band[0] >= 2 * resolution:
        bands.append(band)
        keys.append("omega1")
    lines = [("peak_Omega", p["Omega_t"])]
    if p["Omega_n"] != p["Omega_t"]:
        lines.append(("peak_Omega_n", p["Omega_n"]))
    for key, line in lines:
        out[key] = float("nan")
        if line > 2 * resolution:
            bands.append((line - resolution, line + resolution))
            keys.append(key)
    out["omega1_peak_at"], out["peak_omega1"] = float("nan"), float("nan")
    for key, (at, amp) in zip(keys, spectra.peak_amplitudes(v, s.dt, bands) if bands else []):
        if key == "omega1":
            out["omega1_peak_at"], out["peak_omega1"] = at, amp
        else:
            out[key] = amp
    out["omega1_peak_present"] = bool(out["peak_omega1"] > PEAK_PRESENT_RATIO * out["peak_Omega"])
    balance = sim.trajectory.energy_balance()
    out["energy_residual"] = balance["residual"]
    out["energy"] = balance
    kinds = [k for _, k, _ in sim.events]
    out["n_switches"] = len(sim.events)
    out["n_reversals"] = sum(1 for _, k, m in sim.events
                             if k == "vr_zero" and m in (SLIP_BACK, SLIP_FORWARD))
    out["n_sticks"] = sum(1 for _, _, m in sim.events if m == STICK)
    out["n_contact_losses"] = kinds.count("lift_off")
    spent = sim.trajectory.time_in_modes(t0, t1)
    out["time_fraction"] = {MODE_NAMES[m]: spent[m] / (t1 - t0) for m in spent}
    out["min_normal_force"] = float(sim.normal_force.min())
    out["tension_fraction"] = float(np.mean(sim.normal_force[win] < 0))
    out["mean_friction"] = float(np.mean(sim.friction[win]))
    out["final_state"] = [float(x) for x in sim.trajectory.state(np.array([t1]))[:, 0]]
    out["vr_max"] = float(np.max(v - p["Vb"]))
    out["vr_min"] = float(np.min(v - p["Vb"]))
    out["wall_s"] = sim.wall_s
    return out


def simulate(params=None, *, contact="hertz_damp", settings=None, y0=None, **overrides):
    """Simulate Eq. (4) and summarise the run.

    Parameters
    ----------
    params : dict, optional
        model parameters; missing ones come from the base set ``generated.parameters.BASE``
    contact : {"hertz_damp", "kelvin_voigt"}
    settings : SolverSettings, optional
    y0 : array_like, optional
        initial state (X1, Y1, X2, Y2); default the unforced equilibrium, Eq. (9)
    **overrides
        parameters (``Vb=4``) or solver settings (``t_end=500``, ``solver="events"``)

    Returns
    -------
    Simulation, with ``summary`` filled in (see `summarize`).
    """
    start = time.perf_counter()
    names = set(SolverSettings.__dataclass_fields__)
    setting_overrides = {k: overrides.pop(k) for k in list(overrides) if k in names}
    settings = settings or SolverSettings()
    if setting_overrides:
        settings = SolverSettings(**{**settings.__dict__, **setting_overrides})
    p = resolve_parameters(params, contact=contact, **overrides)
    trajectory = events = None
    solver_used = "events"
    if settings.solver == "superposition" and y0 is None:
        from .superposition import integrate_superposed
        result = integrate_superposed(p, contact, settings)
        if result is not None:
            trajectory, events = result
            status, message, solver_used = "done", "reached t_end", "superposition"
    if trajectory is None:
        trajectory, events, status, message = integrate_events(
            p, contact, t_end=settings.t_end, y0=y0, method=settings.method, rtol=settings.rtol,
            atol=settings.atol, on_contact_loss=settings.on_contact_loss)
    n = int(np.floor(trajectory.t_end / settings.dt + 1e-9)) + 1
    t = settings.dt * np.arange(n)
    y = trajectory.state(t)
    Fn, friction = trajectory.forces(t, y)
    sim = Simulation(p, contact, settings, trajectory, t, y, Fn, friction, events, status,
                     message, solver_used)
    sim.wall_s = time.perf_counter() - start
    sim.summary = summarize(sim)
    sim.wall_s = sim.summary["wall_s"] = time.perf_counter() - start
    return sim
