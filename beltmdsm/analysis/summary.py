"""The summary of a run: regime, spectral peaks, energy balance, counts (Sects. 2-3).

`summarize` reads the steady window of a run (`beltmdsm.integrate.trajectory.Run`):
regime, spectral peaks (Fig. 2b), energy balance (Sect. 3), counts, and whether the
window resolves the omega1 band and is free of the transient (``resolved``); a run
that cannot tell says so instead of reporting a peak as absent.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..integrate.switching import MODE_NAMES, Mode
from ..integrate.trajectory import Run, Samples, Trajectory
from ..model import Model
from ..settings import SolverSettings
from . import spectra

__all__ = [
    "Summary",
    "EnergyBalance",
    "REGIMES",
    "PEAK_PRESENT_RATIO",
    "TRANSIENT_DECAYED",
    "STATIONARY_RATIO",
    "classify_regime",
    "omega1_band",
    "summarize",
]

REGIMES = ("continuous_sliding", "sliding_with_reversals", "stick_slip", "contact_loss")
# The omega1 peak counts as present when it reaches this fraction of the excitation
# peak: fixed before looking at any sweep (the paper gives no number).
PEAK_PRESENT_RATIO = 0.01


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


def _resolution(model, settings, v, out):
    """Whether the steady window can tell the omega1 peak (``resolved``) and why not.

    Two things can make it unable to: a window too short for the omega1 band to hold
    two frequency bins, and a window in which the transient of the tangential
    oscillator (frequency near omega1, envelope ``exp(-beta1 omega1 t)``) has not
    decayed, which would read as an omega1 peak whatever the dynamics.
    """
    p = model.params
    if out["omega1_band"] is None:
        return False, "an excitation line sits at omega1: no band to read the peak in"
    if not np.isfinite(out["peak_omega1"]):
        return False, (
            f"the steady window ({settings.window_start:g}-{out['t_end']:g} s) is too "
            "short to resolve the omega1 band; lengthen --t-end"
        )
    envelope = np.exp(-p["beta1"] * p["omega1"] * out["t_discard"])
    if envelope <= TRANSIENT_DECAYED:
        return True, ""
    half = v.size // 2
    band = [out["omega1_band"]]
    first, second = (
        spectra.peak_amplitudes(part, settings.dt, band)[0][1] for part in (v[:half], v[half:])
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


@dataclass(frozen=True)
class EnergyBalance:
    """The energy balance of Sect. 3 over a run (`Trajectory.energy_balance`)."""

    energy_change: float
    work_input: float
    work_viscous: float
    work_friction: float
    imbalance: float
    residual: float


@dataclass(frozen=True)
class Summary:
    """What a run says: regime, spectral peaks, energy balance, counts (``--json`` keys).

    ``omega1_peak_present`` is None (not False) where ``resolved`` is False: the
    window cannot tell, and ``unresolved_reason`` says why ("" where resolved).
    ``peak_Omega_n`` is NaN where the normal excitation has the tangential frequency.
    """

    status: str
    message: str
    solver: str
    tension: str
    regime: str
    t_end: float
    t_discard: float
    omega1_band: tuple[float, float] | None
    peak_omega1: float
    omega1_peak_at: float
    peak_Omega: float
    peak_Omega_n: float
    resolved: bool
    omega1_peak_present: bool | None
    unresolved_reason: str
    energy_residual: float
    energy: EnergyBalance
    n_switches: int
    n_reversals: int
    n_sticks: int
    n_contact_losses: int
    n_separations: int
    n_zeno: int
    time_fraction: dict[str, float]
    min_normal_force: float
    tension_fraction: float
    mean_friction: float
    final_state: tuple[float, ...]
    vr_min: float
    vr_max: float
    wall_s: float

    def as_dict(self) -> dict[str, Any]:
        """The summary as plain JSON-able values, by field name."""
        return asdict(self)


def summarize(
    model: Model, settings: SolverSettings, run: Run, samples: Samples, wall_s: float = 0.0
) -> Summary:
    """Regime, spectral peaks, energy balance and counts of a run."""
    p = model.params
    t0, t1 = settings.window_start, run.trajectory.t_end
    win = samples.t >= t0
    if win.sum() < 16:
        # stopped (contact lost, Zeno) before the steady window: the counts and the
        # regime cover the whole run, there is no spectrum
        t0, win = 0.0, np.ones_like(win)
    v = samples.y[1, win]
    out = {
        "t_end": float(t1),
        "t_discard": float(t0),
    }
    resolution = 2 * np.pi / (max(v.size, 1) * settings.dt)
    bands, keys = [], []
    band = omega1_band(p)
    out["omega1_band"] = band
    if band is not None and band[1] - band[0] >= 2 * resolution:
        bands.append(band)
        keys.append("omega1")
    lines = [("peak_Omega", p["Omega_t"]), ("peak_Omega_n", p["Omega_n"])]
    for key, line in lines:
        out[key] = float("nan")
        if line > 2 * resolution and not (key == "peak_Omega_n" and line == p["Omega_t"]):
            bands.append((line - resolution, line + resolution))
            keys.append(key)
    out["omega1_peak_at"], out["peak_omega1"] = float("nan"), float("nan")
    if v.size >= 16:
        found = spectra.peak_amplitudes(v, settings.dt, bands) if bands else []
        for key, (at, amp) in zip(keys, found):
            if key == "omega1":
                out["omega1_peak_at"], out["peak_omega1"] = at, amp
            else:
                out[key] = amp
    resolved, why = _resolution(model, settings, v, out)
    present = (
        bool(out["peak_omega1"] > PEAK_PRESENT_RATIO * out["peak_Omega"]) if resolved else None
    )
    balance = run.trajectory.energy_balance()
    events = run.events
    kinds = [k for _, k, _ in events]
    spent = run.trajectory.time_in_modes(t0, t1)
    duration = t1 - t0
    return Summary(
        status=run.status,
        message=run.message,
        solver=run.solver,
        tension=model.tension,
        regime=(
            "contact_loss"
            if run.status == "contact_lost"
            else classify_regime(run.trajectory, t0, t1)
        ),
        resolved=resolved,
        omega1_peak_present=present,
        unresolved_reason=why,
        energy_residual=balance["residual"],
        energy=EnergyBalance(**balance),
        n_switches=len(events),
        n_reversals=sum(
            1 for _, k, m in events if k == "vr_zero" and m in (Mode.SLIP_BACK, Mode.SLIP_FORWARD)
        ),
        n_sticks=sum(1 for _, _, m in events if m == Mode.STICK),
        n_contact_losses=kinds.count("lift_off"),
        n_separations=kinds.count("separation"),
        n_zeno=run.trajectory.n_zeno,
        time_fraction={
            MODE_NAMES[m]: (spent[m] / duration if duration > 0 else 0.0) for m in spent
        },
        min_normal_force=float(samples.normal_force.min()),
        tension_fraction=float(np.mean(samples.normal_force[win] < 0)),
        mean_friction=float(np.mean(samples.friction[win])),
        final_state=tuple(float(x) for x in run.trajectory.state(np.array([t1]))[:, 0]),
        vr_max=float(np.max(v - p["Vb"])),
        vr_min=float(np.min(v - p["Vb"])),
        wall_s=float(wall_s),
        **out,
    )
