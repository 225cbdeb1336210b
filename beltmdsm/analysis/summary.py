"""The summary of a run: regime, spectral peaks, energy balance, counts (Sects. 2-3).

`summarize` reads the steady window of a run (`beltmdsm.integrate.trajectory.Run`):
regime, spectral peaks (Fig. 2b), energy balance (Sect. 3), counts, and whether the
window resolves the omega1 band and is free of the transient (``resolved``); a run
that cannot tell says so instead of reporting a peak as absent.

What a run can tell is bounded by its tolerances, and the summary says so: a peak is
compared with the largest amplitude that the integration error and rounding can put
into the windowed spectrum (`noise_floor`), never with noise alone (a run without a
forced peak says so), and an energy balance that does not close within the bound of
its tolerances (`energy_bound`) marks the run (``energy_ok``, ``warnings``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

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
    "NOISE_GLOBAL_FACTOR",
    "ENERGY_RESIDUAL_FACTOR",
    "ENERGY_RESIDUAL_FLOOR",
    "ENERGY_RESIDUAL_MAX",
    "classify_regime",
    "free_decay_rate",
    "omega1_band",
    "noise_floor",
    "energy_bound",
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


#: How far the error of the sampled velocity in the steady window exceeds the local
#: error bound of one step (`noise_floor`): measured against runs at rtol = atol =
#: 1e-12, the largest error of X1' in the window was at most 6.1 times
#: ``2 (atol + rtol max|y|)`` (base set at Vb = 1, 4, 10; Omega = 10 at Vb = 7;
#: omega1 = 12 at Vb = 0.5; rtol = atol from 1e-4 to 1e-10), rounded up to 8.
NOISE_GLOBAL_FACTOR = 8.0


def noise_floor(rtol: float, atol: float, y: NDArray[np.float64], v: NDArray[np.float64]) -> float:
    """The largest amplitude that integration error and rounding can put into the spectrum.

    An error ``e`` of the samples with ``|e| <= E`` changes the windowed amplitude
    ``2 |sum w (x - mean x) exp(i omega t)| / sum w`` by at most ``4 E`` at every
    frequency. DOP853 keeps the local error of each of the four state components
    below ``2 (atol + rtol |y|)`` (its error norm is the RMS over the components);
    over the run the error of X1' grows to at most `NOISE_GLOBAL_FACTOR` times that
    (measured). Rounding in the transform's sum of ``N`` terms adds at most
    ``2 N eps max|v|``.

    Parameters
    ----------
    rtol, atol : float
        The run's tolerances.
    y : ndarray (4, n)
        The state in the steady window.
    v : ndarray (n,)
        The sampled X1' in the steady window.

    Returns
    -------
    float
        ``4 NOISE_GLOBAL_FACTOR 2 (atol + rtol max|y|) + 2 N eps max|v|`` [m/s]
    """
    if v.size == 0:
        return float("nan")
    local = 2 * (atol + rtol * float(np.max(np.abs(y))))
    rounding = 2 * v.size * np.finfo(float).eps * float(np.max(np.abs(v)))
    return float(4 * NOISE_GLOBAL_FACTOR * local + rounding)


#: The energy residual per unit tolerance that a run may leave (`energy_bound`):
#: measured at most 5.2 x max(rtol, atol) over the 16 cases of
#: `beltmdsm.studies.validation.CASES` at Vb = 0.5, 4, 10 m/s, both solvers, both
#: tension laws, rtol = atol from 1e-3 to 1e-10 (960 runs of 300 s), but for the
#: one below the floor; rounded up to 64.
ENERGY_RESIDUAL_FACTOR = 64.0
#: The residual that a run at any tolerance may leave: where the contact is lost
#: under the clipped law (omega2 = 1.5) the residual shrinks only slowly with the
#: tolerance (4.2e-9 at rtol = atol = 1e-10 in the measurement above).
ENERGY_RESIDUAL_FLOOR = 1e-8
#: The largest residual of a trusted run, whatever its tolerances: the energy balance
#: of Sect. 3 closes to within 1e-4 of the total work. Looser runs of the base set
#: (rtol 1e-3 to 0.1) had residuals from 5e-6 to 1 and moved the omega1 peak by up
#: to 48 % and the minimum normal force from -16.4 to -7.7e4 m/s^2.
ENERGY_RESIDUAL_MAX = 1e-4


def energy_bound(
    rtol: float, atol: float, energy_level: float = 0.0, work_total: float = 1.0
) -> float:
    """The largest energy residual a run with these tolerances may leave.

    The integration error of a state is about ``tol = max(rtol, atol)`` relative, so
    it moves the work integrals by about ``tol`` of the total work and the change of
    the energy by about ``tol`` of the energy level; relative to the total work, the
    imbalance is then of the order of ``tol (1 + energy_level / work_total)``. The
    bound is ``ENERGY_RESIDUAL_FACTOR`` times that, at least
    `ENERGY_RESIDUAL_FLOOR` and at most `ENERGY_RESIDUAL_MAX`. (Where nothing moves
    but the integration error, without excitation, the total work is of the order
    of the error and the ratio carries no information: the bound is then the cap.)
    A larger residual means the run did not keep its tolerances, or they are too
    loose to trust: `summarize` then sets ``energy_ok`` False and says so in
    ``warnings``.

    Parameters
    ----------
    rtol, atol : float
        The run's tolerances.
    energy_level : float
        ``max |E|`` at the ends of the run (`EnergyBalance.energy_level`).
    work_total : float
        The total absolute work (`EnergyBalance.work_total`), the residual's scale.
    """
    tol = max(rtol, atol)
    ratio = energy_level / work_total if work_total > 0 else math.inf
    scaled = ENERGY_RESIDUAL_FACTOR * tol * (1.0 + ratio)
    return float(max(ENERGY_RESIDUAL_FLOOR, min(scaled, ENERGY_RESIDUAL_MAX)))


#: The free tangential transient has decayed in the steady window when its envelope
#: exp(sigma t) (`free_decay_rate`; Coulomb: sigma = -beta1 omega1) is below this at
#: the window's start (a priori), or when the omega1 band holds the same amplitude,
#: within `STATIONARY_RATIO`, in both halves of the window (measured). A peak that
#: would be present is also checked against the slowest decay towards the periodic
#: response, ``|mu|^(t / T)`` with the largest Floquet multiplier ``mu``
#: (`beltmdsm.analysis.floquet`): next to a Floquet edge it is far slower than the
#: free transient.
TRANSIENT_DECAYED = 1e-3
STATIONARY_RATIO = 0.5


def _threshold(out):
    """The amplitude above which the omega1 peak is present (NaN: no band to read)."""
    if out["forced_peak"]:
        return max(PEAK_PRESENT_RATIO * out["forced_amplitude"], out["noise_floor"])
    return out["noise_floor"]


def _floquet_decay(model, settings, t0):
    """``(envelope, text)`` of the slowest decay towards the periodic response at ``t0``.

    ``envelope`` is ``|mu|^(t0 / T)`` where the periodic response is stable, 0.0 where
    it is unstable (the run does not decay towards it: a peak there grows), and None
    where its multipliers cannot be computed (``text`` says why).
    """
    from .floquet import NoPeriodicResponse, floquet

    try:
        f = floquet(model, backend=settings.backend)
    except (NoPeriodicResponse, ValueError) as err:
        return None, f"its Floquet multipliers are not known ({err})"
    if f.stable is None:
        return None, "its Floquet multipliers are not known (the periodic response grazes)"
    if not f.stable:
        return 0.0, ""
    envelope = f.max_abs_multiplier ** (t0 / f.period)
    return envelope, (
        f"the periodic response attracts at the Floquet rate |mu| = "
        f"{f.max_abs_multiplier:.6g} per period {f.period:.4g} s, an envelope of "
        f"{envelope:.2g} at t = {t0:g} s"
    )


def free_decay_rate(model: Model) -> float:
    """``sigma``: the slowest rate of the free tangential transient about steady sliding.

    The largest real part of the tangential pair of `generated.unforced.eigenvalues`
    for the model's laws: ``-beta1 omega1`` for Coulomb friction (``beta1 < 1``);
    ``-beta1 omega1 + g dmu/d|Vr| / 2`` at ``|Vr| = Vb`` for a friction that falls with
    speed, which is >= 0 where steady sliding is unstable (the transient grows).
    """
    from generated import unforced

    lam = unforced.eigenvalues(**model.arguments(unforced.eigenvalues))
    return float(np.max(np.real(lam[:2])))


#: How `_transient_rate` names the Floquet rate of the periodic response.
FLOQUET_RATE = "the Floquet rate |mu|^(t/T)"


def _transient_rate(model, settings, forced):
    """``(sigma, what)``: the rate at which a disturbance decays in the run, and its name.

    `free_decay_rate` where it is the rate: without excitation (steady sliding), and
    under a law whose slip friction does not depend on the tangential state (Coulomb:
    between switches the tangential equation is linear with that rate). Under excitation
    and a friction that depends on the sliding speed (Stribeck), the disturbance decays
    towards the periodic response at its Floquet rate ``ln max|mu| / T`` instead, which
    steady sliding's rate need not resemble; where that response is not stable or not
    known, the free rate is all there is.
    """
    sigma = free_decay_rate(model)
    if not forced or model.fact("slip_friction_state_independent")[0]:
        return sigma, "exp(sigma t)"
    from .floquet import NoPeriodicResponse, floquet

    try:
        f = floquet(model, backend=settings.backend)
    except (NoPeriodicResponse, ValueError):
        return sigma, "exp(sigma t)"
    if not f.stable:
        return sigma, "exp(sigma t)"
    return math.log(f.max_abs_multiplier) / f.period, FLOQUET_RATE


def _resolution(model, settings, v, out):
    """Whether the steady window can tell the omega1 peak (``resolved``) and why not.

    Three things can make it unable to: a window too short for the omega1 band to hold
    two frequency bins; a window in which the transient of the tangential oscillator
    (frequency near omega1, envelope ``exp(sigma t)``, `free_decay_rate`, or under
    excitation and a speed-dependent friction the Floquet rate, `_transient_rate`) has
    not decayed, which would read as an omega1 peak whatever the dynamics; and, for a peak
    that would be present, a slow decay towards a stable periodic response (Floquet
    multiplier close to 1, next to an edge of the Floquet band), which the free
    transient does not see. Both decays are checked in the window itself where they
    are not small a priori: a peak that holds its amplitude in both halves is
    stationary (a self-excited oscillation), one that does not is a transient; unless
    the free transient decays so slowly (next to a Stribeck boundary, ``sigma -> 0-``)
    that it too would hold its amplitude within `STATIONARY_RATIO` over half the
    window: then the window cannot tell the two.
    """
    if out["omega1_band"] is None:
        return False, "an excitation line sits at omega1: no band to read the peak in"
    if not np.isfinite(out["peak_omega1"]):
        return False, (
            f"the steady window ({settings.window_start:g}-{out['t_end']:g} s) is too "
            "short to resolve the omega1 band; lengthen --t-end"
        )
    t0 = out["t_discard"]
    threshold = _threshold(out)
    sigma, what = _transient_rate(model, settings, out["forced_peak"])
    envelope = math.exp(min(sigma * t0, 0.0)) if sigma < 0 else 1.0
    why = (
        f"the tangential transient has not decayed in the steady window (its "
        f"envelope, {what} with sigma = {sigma:.3g} 1/s, is {envelope:.2g} at t = {t0:g} s)"
        if sigma < 0
        else f"steady sliding is unstable (free tangential rate sigma = {sigma:.3g} 1/s >= 0)"
    )
    if envelope <= TRANSIENT_DECAYED:
        if not out["peak_omega1"] > threshold or what == FLOQUET_RATE:
            # (the envelope was the Floquet rate already: no need to ask again)
            return True, ""
        # a present peak: is it a slow decay towards a stable periodic response?
        envelope, text = _floquet_decay(model, settings, t0)
        if envelope is not None and envelope <= TRANSIENT_DECAYED:
            return True, ""
        why = (
            f"the peak may be a decay towards the periodic response ({text})"
            if envelope is not None
            else f"the peak may be a slow decay towards the periodic response, and {text}"
        )
    half = v.size // 2
    band = [out["omega1_band"]]
    first, second = (
        spectra.peak_amplitudes(part, settings.dt, band)[0][1] for part in (v[:half], v[half:])
    )
    if max(first, second) <= threshold:
        return True, ""
    slow = sigma < 0 and math.exp(sigma * (out["t_end"] - t0) / 2) >= STATIONARY_RATIO
    if min(first, second) >= STATIONARY_RATIO * max(first, second) and not slow:
        return True, ""
    if slow:
        why = (
            f"{why}, and so slow (sigma = {sigma:.3g} 1/s) that a decay would hold its "
            f"amplitude within {STATIONARY_RATIO:g} over half the window too"
        )
    return False, (
        f"{why}; the omega1 band holds {first:.3g} m/s in the first half of the window "
        f"and {second:.3g} m/s in the second; lengthen --t-end"
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
    work_total: float
    energy_level: float


@dataclass(frozen=True)
class Summary:
    """What a run says: regime, spectral peaks, energy balance, counts (``--json`` keys).

    ``omega1_peak_present`` is None (not False) where ``resolved`` is False: the
    window cannot tell, and ``unresolved_reason`` says why ("" where resolved).
    ``peak_Omega_n`` is NaN where the normal excitation has the tangential frequency.

    ``noise_floor`` is the largest amplitude the run's tolerances and rounding can put
    into the spectrum (`noise_floor`); ``forced_peak`` is False where no peak at an
    excitation frequency rises above it (no excitation, or tolerances too loose to
    tell): the omega1 peak is then judged against the floor alone, never against
    another peak of noise. ``energy_ok`` is False where ``energy_residual`` exceeds
    ``energy_bound`` (`energy_bound`); ``warnings`` says so in words, one sentence
    per problem (empty where there is none).
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
    noise_floor: float
    forced_peak: bool
    resolved: bool
    omega1_peak_present: bool | None
    unresolved_reason: str
    energy_residual: float
    energy_bound: float
    energy_ok: bool
    warnings: tuple[str, ...]
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

    def __repr__(self) -> str:
        from .._display import block, number

        if not self.resolved:
            peak = f"unresolved ({self.unresolved_reason})"
        else:
            peak = (
                f"{'present' if self.omega1_peak_present else 'absent'} "
                f"(amplitude {number(self.peak_omega1, '.3g')} at "
                f"{number(self.omega1_peak_at, '.4g')} rad/s)"
            )
        return block(
            f"Summary({self.status!r}, regime {self.regime!r}, {self.solver}, "
            f"t_end={self.t_end:g} s)",
            [
                f"omega1 peak: {peak}",
                f"{self.n_switches} switches: {self.n_reversals} reversals, {self.n_sticks} "
                f"sticks, {self.n_contact_losses} contact losses, {self.n_zeno} Zeno",
                f"Vr in [{self.vr_min:.4g}, {self.vr_max:.4g}] m/s, mean friction "
                f"{number(self.mean_friction, '.4g')} m/s^2 (per unit mass)",
                f"energy residual {self.energy_residual:.1e} "
                f"({'within' if self.energy_ok else 'ABOVE'} its bound {self.energy_bound:.1e})",
                *self.warnings,
            ],
        )


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
    out["noise_floor"] = noise_floor(settings.rtol, settings.atol, samples.y[:, win], v)
    forced = [a for a in (out["peak_Omega"], out["peak_Omega_n"]) if np.isfinite(a)]
    out["forced_amplitude"] = max(forced) if forced else float("nan")
    out["forced_peak"] = bool(forced and out["forced_amplitude"] > out["noise_floor"])
    resolved, why = _resolution(model, settings, v, out)
    present = bool(out["peak_omega1"] > _threshold(out)) if resolved else None
    del out["forced_amplitude"]
    balance = run.trajectory.energy_balance()
    bound = energy_bound(
        settings.rtol, settings.atol, balance["energy_level"], balance["work_total"]
    )
    energy_ok = bool(balance["residual"] <= bound)
    warnings = []
    if not energy_ok:
        warnings.append(
            f"the energy balance does not close: residual {balance['residual']:.3g} is above "
            f"the bound {bound:.3g} of rtol = {settings.rtol:g}, atol = {settings.atol:g} "
            "(beltmdsm/analysis/summary.py, energy_bound); the run's numbers are not "
            "trusted: tighten the tolerances"
        )
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
        energy_bound=bound,
        energy_ok=energy_ok,
        warnings=tuple(warnings),
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
