"""The summary of a run: regime, spectral peaks, energy balance, counts (Sects. 2-3).

`summarize` reads the steady window of a run (`beltmdsm.integrate.trajectory.Run`):
regime, spectral peaks (Fig. 2b), energy balance (Sect. 3), counts, and whether the
window resolves the omega1 band and is free of the transient (``resolved``); a run
that cannot tell says so instead of reporting a peak as absent.

What a run can tell is bounded by its tolerances, and the summary says so: a peak is
compared with the largest amplitude that the integration error and rounding can put
into the windowed spectrum (`beltmdsm.run.tolerances.noise_floor`), never with noise
alone (a run without a forced peak says so), and an energy balance that does not close
within the bound of its tolerances (`beltmdsm.run.tolerances.energy_bound`) marks the
run (``energy_ok``, ``warnings``). Whether the window tells the omega1 peak at all is
`beltmdsm.run.resolution`'s; its criteria (`PEAK_PRESENT_RATIO`, `TRANSIENT_DECAYED`,
`free_decay_rate`) and the tolerances' bounds are also importable from here, where the
summary's readers look for them.
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
from ..state_names import rate_row
from . import spectra
from .resolution import (
    PEAK_PRESENT_RATIO,
    STATIONARY_RATIO,
    TRANSIENT_DECAYED,
    _on_unstable_sliding,
    _resolution,
    _threshold,
    free_decay_rate,
)
from .tolerances import (
    ENERGY_RESIDUAL_FACTOR,
    ENERGY_RESIDUAL_FLOOR,
    ENERGY_RESIDUAL_MAX,
    NOISE_GLOBAL_FACTOR,
    energy_bound,
    noise_floor,
)

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


def classify_regime(trajectory: Trajectory, t0: float, t1: float) -> str:
    """Regime in the window [t0, t1] from the time spent in each mode.

    contact_loss (any flight) > stick_slip (any stick) > sliding_with_reversals
    (both slip directions) > continuous_sliding. Separation under the clipped tension
    law (``X2 > 0``, no force) is part of the contact cycle and does not enter; its
    share is in the summary's ``time_fraction``.

    Parameters
    ----------
    trajectory : beltmdsm.integrate.trajectory.Trajectory
        The run's trajectory.
    t0, t1 : float
        The window [s].

    Returns
    -------
    str
        One of `REGIMES`.

    See Also
    --------
    summarize : the summary that holds it.

    Examples
    --------
    >>> from beltmdsm import simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> classify_regime(sim.trajectory, 10.0, 40.0)
    'sliding_with_reversals'
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

    Parameters
    ----------
    p : mapping
        The model's parameters (``omega1``, ``Omega_t``, ``Omega_n``).

    Returns
    -------
    (float, float) or None

    See Also
    --------
    beltmdsm.run.spectra.peak_amplitudes : what reads the peak in it.

    Examples
    --------
    >>> from beltmdsm import Model
    >>> omega1_band(Model().params)  # omega1 = 1 rad/s, the excitation at 4 rad/s
    (0.75, 1.25)
    >>> omega1_band(Model(Omega_t=1.0, Omega_n=1.0).params) is None
    True
    """
    w1 = p["omega1"]
    half = 0.25 * w1
    for line in (p["Omega_t"], p["Omega_n"]):
        if line > 0:
            half = min(half, 0.5 * abs(w1 - line))
    return (w1 - half, w1 + half) if half > 0 else None


@dataclass(frozen=True)
class EnergyBalance:
    """The energy balance of Sect. 3 over a run (`Trajectory.energy_balance`).

    Parameters
    ----------
    energy_change : float
        The change of the energy E (kinetic, spring, Hertz and gravity) over the run.
    work_input, work_viscous, work_friction : float
        The work of the excitation, and the work dissipated by damping and friction.
    imbalance : float
        ``energy_change - work_input + work_viscous + work_friction``.
    residual : float
        ``|imbalance| / work_total``.
    work_total : float
        The sum of the absolute works, the residual's scale.
    energy_level : float
        ``max |E|`` at the two ends (the scale of the rounding of ``energy_change``).

    See Also
    --------
    beltmdsm.run.tolerances.energy_bound : the residual a run may leave.

    Examples
    --------
    >>> from beltmdsm import simulate
    >>> e = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0).summary.energy
    >>> e.residual < 1e-8, e.work_input > e.work_friction > 0
    (True, True)
    """

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

    ``start_perturbation`` is how far the run's start was moved off steady sliding
    along its unstable direction (without excitation, where steady sliding is
    unstable: `beltmdsm.excitation.equilibrium_start`; 0.0 elsewhere). Such a run that
    still slides steadily at its end is unresolved, the instability named.

    Parameters
    ----------
    status, message, solver : str
        The run's end (``"done"``, ``"contact_lost"``, ...), its words, the integrator
        that ran it.
    tension, regime : str
        The tension law; the regime of the steady window (one of `REGIMES`).
    t_end, t_discard : float
        The run's end and the start of the steady window [s].
    omega1_band : (float, float) or None
        Where the omega1 peak is read [rad/s] (`omega1_band`).
    peak_omega1, omega1_peak_at, peak_Omega, peak_Omega_n : float
        Amplitudes of X1' [m/s] in the omega1 band and at the excitation lines, and
        where the omega1 peak is [rad/s]; NaN where not read.
    noise_floor : float
        See above (`beltmdsm.run.tolerances.noise_floor`) [m/s].
    forced_peak, resolved : bool
        See above.
    omega1_peak_present : bool or None
        Whether the omega1 peak reaches `PEAK_PRESENT_RATIO` of the forced peak and
        the noise floor; None where unresolved.
    unresolved_reason : str
        Why the window cannot tell ("" where resolved).
    energy_residual, energy_bound : float
        The energy balance's residual (relative to the total work) and its bound.
    energy_ok : bool
        Whether the residual is within its bound.
    warnings : tuple of str
        One sentence per problem.
    energy : EnergyBalance
        The terms of the energy balance of Sect. 3.
    n_switches, n_reversals, n_sticks, n_contact_losses, n_separations, n_zeno : int
        Counts of the run's switches, by kind.
    time_fraction : dict of float
        The share of the steady window spent in each mode.
    min_normal_force, tension_fraction, mean_friction : float
        The least contact force [m/s^2 per unit mass], the share of the window where
        it pulls, the mean friction force.
    final_state : tuple of float
        (X1, Y1, X2, Y2) at ``t_end``.
    vr_min, vr_max : float
        The range of the relative velocity ``Vr = X1' - Vb`` in the window [m/s].
    wall_s : float
        The wall-clock time of the run [s].
    start_perturbation : float
        See above.

    See Also
    --------
    beltmdsm.run.summary.summarize : what computes it from a run.
    beltmdsm.simulate : a run and its summary.
    beltmdsm.batch.row.Row : the columns of a sweep's table, taken from it.

    Examples
    --------
    >>> from beltmdsm import simulate
    >>> s = simulate(Model(Vb=4.0), t_end=300.0).summary
    >>> s.regime, s.resolved, s.omega1_peak_present, s.energy_ok
    ('sliding_with_reversals', True, True, True)
    >>> round(s.peak_omega1, 1), round(s.omega1_peak_at, 2)
    (4.9, 1.0)
    >>> short = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0).summary
    >>> short.resolved, short.omega1_peak_present
    (False, None)
    >>> print(short.unresolved_reason)  # doctest: +ELLIPSIS
    the tangential transient has not decayed in the steady window ...; lengthen --t-end
    >>> short.as_dict()["regime"]
    'sliding_with_reversals'
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
    start_perturbation: float = 0.0

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
    model: Model,
    settings: SolverSettings,
    run: Run,
    samples: Samples,
    wall_s: float = 0.0,
    start_perturbation: float = 0.0,
) -> Summary:
    """Regime, spectral peaks, energy balance and counts of a run.

    Parameters
    ----------
    model : Model
        The model that was run.
    settings : SolverSettings
        Its settings (the steady window, the tolerances, the sampling step).
    run : beltmdsm.integrate.trajectory.Run
        The integrated run.
    samples : beltmdsm.integrate.trajectory.Samples
        The run sampled every ``settings.dt``.
    wall_s : float
        The run's wall-clock time [s], stated in the summary.
    start_perturbation : float
        How far the run's start was moved off an unstable steady sliding
        (`beltmdsm.excitation.equilibrium_start`), stated in the summary.

    Returns
    -------
    Summary

    See Also
    --------
    beltmdsm.simulate : a run with its summary.

    Examples
    --------
    >>> from beltmdsm import simulate
    >>> sim = simulate(Model(Vb=4.0), t_end=40.0, t_discard=10.0)
    >>> s = summarize(sim.model, sim.settings, sim.run, sim.samples)
    >>> s.regime, s.n_reversals == sim.summary.n_reversals
    ('sliding_with_reversals', True)
    """
    p = model.params
    t0, t1 = settings.window_start, run.trajectory.t_end
    win = samples.t >= t0
    if win.sum() < 16:
        # stopped (contact lost, Zeno) before the steady window: the counts and the
        # regime cover the whole run, there is no spectrum
        t0, win = 0.0, np.ones_like(win)
    v = samples.y[rate_row(model), win]  # the first coordinate's rate (X1')
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
    regime = (
        "contact_loss" if run.status == "contact_lost" else classify_regime(run.trajectory, t0, t1)
    )
    resolved, why = _resolution(model, settings, v, out, regime)
    present = bool(out["peak_omega1"] > _threshold(out)) if resolved else None
    if resolved:
        why = _on_unstable_sliding(model, regime, present, t1, start_perturbation)
        if why:
            resolved, present = False, None
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
            "(beltmdsm/run/tolerances.py, energy_bound); the run's numbers are not "
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
        regime=regime,
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
        start_perturbation=float(start_perturbation),
        **out,
    )
