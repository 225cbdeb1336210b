"""Simulation of Eq. (4) and the summary of a run (Sects. 2-3).

A run integrates Eq. (4) as a hybrid system: smooth modes (slip in either direction,
stick, flight and, under the clipped tension law, separation) joined at located
switches, with Filippov's rules where the friction is set-valued
(`runtime.switching`). Two integrators produce the same `Trajectory`:

* ``solver="events"`` (`runtime.events`, the default): the compiled DOP853
  integrator on the generated field of each mode, the general one and, compiled,
  the faster;
* ``solver="superposition"`` (`runtime.superposition`): the normal motion is
  integrated once and the tangential motion is a closed-form superposition between
  switches (Eq. 4 is one-way coupled); it falls back to ``events`` with a stated
  reason where it does not apply.

The tension law (``tension=``, docs/modelling.md#tension) is Eq. (1) as printed
(``"allowed"``: the force turns tensile when the mass moves up fast, at the base set
in every excitation cycle, and friction then acts with the negative normal force)
or a contact that cannot pull (``"clipped"``: where Eq. (1) would pull, the surfaces
separate and neither normal force nor friction acts).

`summarize` reads the steady window of a run: regime, spectral peaks (Fig. 2b),
energy balance (Sect. 3), counts, and whether the window resolves the omega1 band
and is free of the transient (``resolved``); a run that cannot tell says so instead
of reporting a peak as absent.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import spectra
from .events import integrate_events
from .model import MODE_NAMES, TENSIONS, Mode, resolve_parameters
from .parameters import Backend, Contact, Tension
from .trajectory import Trajectory

__all__ = [
    "SolverSettings",
    "Simulation",
    "simulate",
    "integrate_events",
    "classify_regime",
    "omega1_band",
    "summarize",
    "REGIMES",
    "DEFAULT_T_END",
    "PEAK_PRESENT_RATIO",
    "PERTURBATION",
    "STARTS",
    "TRANSIENT_DECAYED",
    "STATIONARY_RATIO",
]

REGIMES = ("continuous_sliding", "sliding_with_reversals", "stick_slip", "contact_loss")
DEFAULT_T_END = 1000.0
# The omega1 peak counts as present when it reaches this fraction of the excitation
# peak: fixed before looking at any sweep (the paper gives no number).
PEAK_PRESENT_RATIO = 0.01


@dataclass(frozen=True)
class SolverSettings:
    """How a run is computed; part of the cache key of a sweep.

    ``solver``: "events" (the default; `runtime.events`, the compiled DOP853
    integrator on each mode: the general one, and the faster) or "superposition"
    (`runtime.superposition`: the normal equation once, the tangential one by
    superposition; it falls back to "events" where it does not apply). ``method``: the
    Runge-Kutta method ("DOP853", the only one).
    ``dt``: sampling step of the returned time series [s]. ``t_discard``: start of
    the steady window [s]; ``None`` means 30 % of ``t_end``. ``backend``: "numba"
    (compiled), "python" or None (numba if installed).
    """

    solver: Literal["events", "superposition"] = "events"
    method: Literal["DOP853"] = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-10
    t_end: float = DEFAULT_T_END
    t_discard: float | None = None
    dt: float = 0.02
    on_contact_loss: Literal["continue", "stop"] = "continue"
    backend: Backend | None = None

    def __post_init__(self):
        # The limits live in runtime.parameters, beside the checks of the model.
        from .parameters import MAX_SAMPLES, METHODS, is_real

        if self.solver not in ("events", "superposition"):
            raise ValueError(f"solver must be 'events' or 'superposition'; got {self.solver!r}")
        if self.method not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}; got {self.method!r}")
        if self.on_contact_loss not in ("continue", "stop"):
            raise ValueError(
                f"on_contact_loss must be 'continue' or 'stop'; got {self.on_contact_loss!r}"
            )
        if self.backend not in (None, "numba", "python"):
            raise ValueError(f"backend must be 'numba', 'python' or None; got {self.backend!r}")
        for name in ("rtol", "atol", "t_end", "dt"):
            value = getattr(self, name)
            if not (is_real(value) and np.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a finite number > 0; got {value!r}")
        if self.t_discard is not None and not (
            is_real(self.t_discard) and np.isfinite(self.t_discard)
        ):
            raise ValueError(f"t_discard must be None or a finite number; got {self.t_discard!r}")
        if self.t_end / self.dt > MAX_SAMPLES:
            raise ValueError(
                f"t_end / dt = {self.t_end / self.dt:.3g} samples is more than "
                f"MAX_SAMPLES = {MAX_SAMPLES:.0e} (runtime/parameters.py); "
                "shorten t_end or sample with a larger dt"
            )
        if not 0 <= self.window_start < self.t_end - 20 * self.dt:
            raise ValueError(
                f"t_discard={self.t_discard!r} must be >= 0 and leave a steady "
                f"window before t_end={self.t_end!r}"
            )

    @property
    def window_start(self) -> float:
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
    tension: str = "allowed"

    @property
    def window(self) -> NDArray[np.bool_]:
        """Boolean mask of the samples in the steady window."""
        return self.t >= self.settings.window_start


def classify_regime(trajectory: Trajectory, t0: float, t1: float) -> str:
    """Regime in the window [t0, t1] from the time spent in each mode.

    contact_loss (any flight) > stick_slip (any stick) > sliding_with_reversals
    (both slip directions) > continuous_sliding. Separation under the clipped tension
    law (``X2 > 0``, no force) is part of the contact cycle and does not enter; its
    share is in the summary's ``time_fraction``.
    """
    spent = trajectory.time_in_modes(t0, t1)
    if spent[Mode.FLIGHT] > 0:
        return "contact_loss"
    if spent[Mode.STICK] > 0:
        return "stick_slip"
    if spent[Mode.SLIP_BACK] > 0 and spent[Mode.SLIP_FORWARD] > 0:
        return "sliding_with_reversals"
    return "continuous_sliding"


def omega1_band(p: Mapping[str, float]) -> tuple[float, float] | None:
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


#: The free tangential transient has decayed in the steady window when its envelope
#: exp(-beta1 omega1 t) is below this at the window's start (a priori), or when the
#: omega1 band holds the same amplitude, within `STATIONARY_RATIO`, in both halves of
#: the window (measured).
TRANSIENT_DECAYED = 1e-3
STATIONARY_RATIO = 0.5


def _resolution(sim, v, out):
    """Whether the steady window can tell the omega1 peak (``resolved``) and why not.

    Two things can make it unable to: a window too short for the omega1 band to hold
    two frequency bins, and a window in which the transient of the tangential
    oscillator (frequency near omega1, envelope ``exp(-beta1 omega1 t)``) has not
    decayed, which would read as an omega1 peak whatever the dynamics.
    """
    p, s = sim.params, sim.settings
    if out["omega1_band"] is None:
        return False, "an excitation line sits at omega1: no band to read the peak in"
    if not np.isfinite(out["peak_omega1"]):
        return False, (
            f"the steady window ({s.window_start:g}-{out['t_end']:g} s) is too "
            "short to resolve the omega1 band; lengthen --t-end"
        )
    envelope = np.exp(-p["beta1"] * p["omega1"] * out["t_discard"])
    if envelope <= TRANSIENT_DECAYED:
        return True, ""
    half = v.size // 2
    band = [out["omega1_band"]]
    first, second = (
        spectra.peak_amplitudes(part, s.dt, band)[0][1] for part in (v[:half], v[half:])
    )
    floor = PEAK_PRESENT_RATIO * out["peak_Omega"]
    if max(first, second) <= floor or min(first, second) >= STATIONARY_RATIO * max(first, second):
        return True, ""
    return False, (
        f"the tangential transient has not decayed in the steady window (its "
        f"envelope exp(-beta1 omega1 t) is {envelope:.2g} at t = "
        f"{out['t_discard']:g} s; the omega1 band holds {first:.3g} in the first "
        f"half of the window and {second:.3g} in the second); lengthen --t-end"
    )


def summarize(sim: Simulation) -> dict[str, Any]:
    """Regime, spectral peaks, energy balance and counts of a run (``sim.summary``).

    ``omega1_peak_present`` is None (not False) where ``resolved`` is False: the
    window cannot tell (`_resolution`), and a warning says why.
    """
    p, s = sim.params, sim.settings
    t0, t1 = s.window_start, sim.trajectory.t_end
    win = sim.window
    if win.sum() < 16:
        # stopped (contact lost, Zeno) before the steady window: the counts and the
        # regime cover the whole run, there is no spectrum
        t0, win = 0.0, np.ones_like(win)
    v = sim.y[1, win]
    out = {
        "status": sim.status,
        "message": sim.message,
        "solver": sim.solver_used,
        "tension": sim.tension,
        "regime": (
            "contact_loss"
            if sim.status == "contact_lost"
            else classify_regime(sim.trajectory, t0, t1)
        ),
        "t_end": float(t1),
        "t_discard": float(t0),
    }
    resolution = 2 * np.pi / (max(v.size, 1) * s.dt)
    bands, keys = [], []
    band = omega1_band(p)
    out["omega1_band"] = band
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
    if v.size >= 16:
        for key, (at, amp) in zip(keys, spectra.peak_amplitudes(v, s.dt, bands) if bands else []):
            if key == "omega1":
                out["omega1_peak_at"], out["peak_omega1"] = at, amp
            else:
                out[key] = amp
    out["resolved"], why = _resolution(sim, v, out)
    if out["resolved"]:
        out["omega1_peak_present"] = bool(
            out["peak_omega1"] > PEAK_PRESENT_RATIO * out["peak_Omega"]
        )
    else:
        out["omega1_peak_present"] = None
        out["unresolved_reason"] = why
        warnings.warn(f"omega1 peak not resolved: {why}", RuntimeWarning, stacklevel=3)
    balance = sim.trajectory.energy_balance()
    out["energy_residual"] = balance["residual"]
    out["energy"] = balance
    kinds = [k for _, k, _ in sim.events]
    out["n_switches"] = len(sim.events)
    out["n_reversals"] = sum(
        1 for _, k, m in sim.events if k == "vr_zero" and m in (Mode.SLIP_BACK, Mode.SLIP_FORWARD)
    )
    out["n_sticks"] = sum(1 for _, _, m in sim.events if m == Mode.STICK)
    out["n_contact_losses"] = kinds.count("lift_off")
    out["n_separations"] = kinds.count("separation")
    out["n_zeno"] = sim.trajectory.n_zeno
    spent = sim.trajectory.time_in_modes(t0, t1)
    duration = t1 - t0
    out["time_fraction"] = {
        MODE_NAMES[m]: (spent[m] / duration if duration > 0 else 0.0) for m in spent
    }
    out["min_normal_force"] = float(sim.normal_force.min())
    out["tension_fraction"] = float(np.mean(sim.normal_force[win] < 0))
    out["mean_friction"] = float(np.mean(sim.friction[win]))
    out["final_state"] = [float(x) for x in sim.trajectory.state(np.array([t1]))[:, 0]]
    out["vr_max"] = float(np.max(v - p["Vb"]))
    out["vr_min"] = float(np.min(v - p["Vb"]))
    out["wall_s"] = sim.wall_s
    return out


#: ``start="periodic"``: the run starts on the periodic response with X1 moved by this [m].
PERTURBATION = 1e-2
STARTS = ("rest", "periodic")
#: `STARTS` as an annotation.
Start = Literal["rest", "periodic"]


def simulate(
    params: Mapping[str, float | None] | None = None,
    *,
    contact: Contact = "hertz_damp",
    tension: Tension = "allowed",
    settings: SolverSettings | None = None,
    y0: ArrayLike | None = None,
    start: Start = "rest",
    perturbation: float = PERTURBATION,
    **overrides: float | str | None,
) -> Simulation:
    """Simulate Eq. (4) and summarise the run.

    Parameters
    ----------
    params : dict, optional
        model parameters; missing ones come from the base set ``generated.parameters.BASE``
    contact : {"hertz_damp", "kelvin_voigt"}
    tension : {"allowed", "clipped"}
        Eq. (1) as printed, or a contact that cannot pull (docs/modelling.md#tension)
    settings : SolverSettings, optional
    y0 : array_like, optional
        initial state (X1, Y1, X2, Y2) at t = 0; default the unforced equilibrium, Eq. (9)
    start : {"rest", "periodic"}
        where the run starts when ``y0`` is not given: the unforced equilibrium at rest,
        or the periodic response (`runtime.floquet.periodic_response`) with ``X1`` moved
        by ``perturbation`` [m], so that an unstable response shows its instability
    perturbation : float
    **overrides
        parameters (``Vb=4``) or solver settings (``t_end=500``, ``solver="events"``)

    Returns
    -------
    Simulation, with ``summary`` filled in (see `summarize`).

    Raises
    ------
    ValueError
        Naming the parameter, setting or option, for a bad value.
    RuntimeError
        For ``start="periodic"`` where no periodic response is found.
    """
    clock = time.perf_counter()
    if start not in STARTS:
        raise ValueError(f"start must be one of {', '.join(map(repr, STARTS))}; got {start!r}")
    if not (isinstance(perturbation, (int, float)) and np.isfinite(perturbation)):
        raise ValueError(f"perturbation must be a finite number; got {perturbation!r}")
    if tension not in TENSIONS:
        raise ValueError(
            f"tension must be one of {', '.join(map(repr, TENSIONS))}; got {tension!r}"
        )
    names = set(SolverSettings.__dataclass_fields__)
    setting_overrides = {k: overrides.pop(k) for k in list(overrides) if k in names}
    settings = settings or SolverSettings()
    if setting_overrides:
        settings = SolverSettings(**{**settings.__dict__, **setting_overrides})
    p = resolve_parameters(params, contact=contact, **overrides)
    if y0 is not None:
        if start != "rest":
            raise ValueError("give y0 or start='periodic', not both")
        y0 = np.asarray(y0, dtype=float)
        if y0.shape != (4,) or not np.all(np.isfinite(y0)):
            raise ValueError(f"y0 must be 4 finite numbers (X1, Y1, X2, Y2); got {y0!r}")
    elif start == "periodic":
        from .floquet import periodic_response

        y0 = periodic_response(p, contact=contact, tension=tension).state0 + np.array(
            [perturbation, 0.0, 0.0, 0.0]
        )
    trajectory = events = None
    solver_used, fallback = "events", ""
    if settings.solver == "superposition":
        from .superposition import integrate_superposed

        result = integrate_superposed(p, contact, tension, settings, y0=y0)
        if isinstance(result, str):
            fallback = result
        else:
            trajectory, events, status, message = result
            solver_used = "superposition"
    if trajectory is None:
        trajectory, events, status, message = integrate_events(
            p,
            contact,
            tension=tension,
            t_end=settings.t_end,
            y0=y0,
            method=settings.method,
            rtol=settings.rtol,
            atol=settings.atol,
            on_contact_loss=settings.on_contact_loss,
            backend=settings.backend,
        )
        if fallback:
            message = f"{message} (events solver: {fallback})"
    n = int(np.floor(trajectory.t_end / settings.dt + 1e-9)) + 1
    t = settings.dt * np.arange(n)
    y = trajectory.state(t)
    Fn, friction = trajectory.forces(t, y)
    sim = Simulation(
        p,
        contact,
        settings,
        trajectory,
        t,
        y,
        Fn,
        friction,
        events,
        status,
        message,
        solver_used,
        tension=tension,
    )
    sim.wall_s = time.perf_counter() - clock
    sim.summary = summarize(sim)
    sim.summary["start"] = start
    if start == "periodic":
        sim.summary["perturbation"] = float(perturbation)
    sim.wall_s = sim.summary["wall_s"] = time.perf_counter() - clock
    return sim
